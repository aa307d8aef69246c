"""The try-its as data: :class:`TryIt` (what the student writes, how it is checked, a worked answer, the data and
their ranges) and :data:`TRY_ITS`, filled by the chapter modules through :func:`register`. The notebooks' face
— ``kb.try_it``, ``kb.reveal``, ``kb.another`` — is :mod:`kinbook.book.tryits`."""

from __future__ import annotations

import ast
import functools
import inspect
import textwrap
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import sympy as sp

from ...grading._i18n import Msg, add_texts, render
from ...grading.catalogue import explain
from ...grading.expected import Expected
from ...grading.item import Item, checker_for
from ...grading.match import scale_match
from ...grading.quantities import PHI, quantity_of
from ...grading.read import Refused, read
from ...grading.report import CheckResult, RowResult, hints
from ...grading.target import target_for
from ...i18n import N_, Message, translate
from .code_mutants import slips

__all__ = ["TryIt", "TRY_ITS", "register", "same_data", "table_text", "text_message"]

TRY_ITS: dict[str, "TryIt"] = {}
"""Every try-it, by id ("13-1/try-1"), in notebook order."""


@dataclass(frozen=True, kw_only=True)
class TryIt(Item):
    """One "Try it" exercise of a chapter notebook: a :class:`~kinbook.grading.item.Item` (``answer``,
    ``checker``, ``target``, ``options``, ``data``, ``ranges``) with a worked answer, a statement, the lookalikes
    printed nearby and the wrong forms it names.

    Attributes
    ----------
    id : str
        ``"<notebook>/try-<k>"``, e.g. ``"13-2/try-1"``: the notebook's number and the exercise's place in it.
    answer : str
        Name of the notebook variable the student fills in (``"my_Phi"``); unique in its notebook.
    checker : kinbook.grading.item.Checker
        A checker of :data:`kinbook.grading.CHECKERS`, called as ``checker(answer, target(**data), **options)``.
    target : callable
        Called with the data (``target(**data)``); returns the checker's reference (an
        :class:`~kinbook.grading.expected.Expected`, a constraint or a mechanism), computed by the library.
    solution : callable
        The worked answer. Its positional parameters are notebook variables it reads (rebuilt by ``context``
        for tests), its keyword-only parameters the data; its body, up to the final ``return``, is the code
        :func:`reveal` shows (after one line per datum).
    options : dict
        Keyword arguments of the checker (``name=…``). Numeric checkers get ``reveal=False``: a try-it never
        shows its reference value in the feedback, only :func:`reveal` does.
    context : callable
        No arguments; returns the notebook variables the solution reads, as a dict.
    data : dict
        The notebook's data (the values its text gives); :func:`another` draws other values from ``ranges``.
    ranges : dict
        For each datum that varies, ``(low, high)`` or a list of values (as in
        :func:`kinbook.classroom.parameters`).
    statement : callable or str
        The data as the question gives them ("t = 0.004 s"): a format string or a function of the data. A
        statement with words is a marked message (``N_("χ = {chi_deg}° about u = {axis_u}")``), translated when
        stated.
    explanation : str or None
        A marked message (``N_("…")``, its Spanish in the package's catalogue): why the worked answer is what it
        is, shown by :func:`reveal` after the code.
    lookalikes : callable or None
        ``lookalikes(**data)`` → [(value, Msg)]: numbers the notebook prints nearby that a student may copy
        (named ``wrong_data``); for a symbolic try-it, [(target, Msg)]: other constraints the answer may be right
        for (the joint printed above).
    wrong_forms : callable or None
        ``wrong_forms(**data)`` → [(rows, code, detail, erratum)]: wrong formulations the equivalence rule cannot
        tell from the reference on its samples (the book's global rows 1–2 of s̃_i s_j, which lose rank where s_i
        lies in the x-y plane): an answer whose rows are these, up to order and factor, is named, never passed.
    numbers_at : float or None
        For a symbolic try-it whose answer may be typed as numbers (ν): the time they are read at. Numbers are then
        compared with the reference at that instant — right there, they are named "the values at one instant only"
        (the question asks for formulas of t); wrong there, they get the diagnosis of a wrong value, not "malformed".
    library : tuple of str
        Names of kinbook functions or methods that compute the asked quantity itself (``"gamma"`` for
        ``mech.gamma(q, qd, t)[7]``): a right answer whose cell calls one is named "kinbook's own answer", not
        plainly "correct" — the exercise is to build it.
    """

    id: str
    solution: Callable
    context: Callable[[], dict] = field(default=dict, repr=False)
    statement: Any = None
    explanation: Any = None
    lookalikes: Any = None
    wrong_forms: Any = None
    numbers_at: Any = None
    library: tuple = ()

    def check(self, answer, data=None, slips=True):
        """Run the checker on ``answer`` (a :class:`kinbook.grading.CheckResult`) for ``data`` (default: the
        notebook's). ``slips=False``: a numeric try-it without its worked answer's code slips (:meth:`slips`), the
        catalogue's names only — how the mutation table counts them apart from the mutants they are."""
        data = self.data_for(data)
        target = self.reference(data)
        options = dict(self.options)
        if self.checker.numeric:
            options.setdefault("reveal", False)
            target = self._with_lookalikes(target, data, slips)
            return self.checker(answer, target, **options)
        result = self.checker(answer, target, **options)
        if self.wrong_forms is not None:
            named = self._wrong_form(answer, target, data, result)
            if named is not None:
                return named.echo(result)
        if result.passed:
            return result
        if self.numbers_at is not None and result.mistakes == ["malformed"] and _numbers(answer):
            return described(self._numbers(answer, target, options, result.quantity_msg))
        copied = self._copied(answer, data, options, result.quantity_msg)
        return described(result if copied is None else copied.echo(result))

    def _numbers(self, answer, target, options, quantity):
        """Numbers typed for a formula of t: compared with the reference at ``numbers_at``."""
        t = float(self.numbers_at)
        q = target.solve_position(t)
        at = {"q": q, "qd": target.solve_velocity(q, t), "t": t}
        there = self.checker(answer, target, at=at, **options)
        if there.passed:
            return CheckResult(False, 0.0, [_msg("x.numbers_right_at", t=_literal(t))], ["only_at_samples"], (),
                               quantity).echo(there)
        return CheckResult(False, there.score, [_msg("x.numbers_read_at", t=_literal(t))] + list(there.notes),
                           there.mistakes, there.rows, quantity, there.columns).echo(there)

    def library_answer(self, source):
        """The ``library`` name a cell's source calls (``mech.gamma(...)``), or None."""
        if not self.library or not source:
            return None
        try:
            tree = ast.parse(source)
        except SyntaxError:
            return None
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                f = node.func
                name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", None)
                if name in self.library:
                    return name
        return None

    def _wrong_form(self, answer, target, data, result):
        """The answer's rows are one of ``wrong_forms`` (up to their order and a factor each): a failed result
        naming it, or None — a result that failed keeps its rows and score (which rows are wrong is the lesson),
        its generic name replaced. The answer is read by the checkers' own reader, evaluated on their samples."""
        quantity = result.quantity_msg

        t = target_for(target)
        qty = quantity_of(quantity, PHI)
        q_name = qty.name
        try:
            A = read(answer, t, q_name)
        except Refused:
            return None
        if A.kind != "symbolic":
            return None
        s = t.samples("generic")

        def by_row(matrix, aliases):  # (samples × columns, one per row): a row of Φ_q is compared whole

            M = sp.Matrix(matrix)
            if M.shape[1] != 1 and not qty.per_coordinate:
                return None
            V = t.tape(list(M), aliases=aliases)(s.Q, s.QD, s.T)["value"]
            return V.reshape(len(V), M.shape[0], M.shape[1]).transpose(1, 0, 2).reshape(M.shape[0], -1)

        S = by_row(A.matrix, True)
        if S is None:
            return None
        for rows, code, detail, erratum in self.wrong_forms(**data):
            W = by_row(rows, False)
            if W is None or S.shape != W.shape:
                continue
            left = list(range(W.shape[0]))
            for k in range(S.shape[0]):
                hit = next((j for j in left if scale_match(S[k], W[j], 1e-6) is not None), None)
                if hit is None:
                    break
                left.remove(hit)
            if not left:
                notes = [detail] + ([_msg("book_misprint", id=erratum)] if erratum else [])
                if result.passed:
                    return CheckResult(False, 0.0, notes + hints([code], {}), [code], (), quantity)
                # the failed result keeps its rows and score; its notes and rows lose the name it gave them
                # (the last note is its hint), but keep which entries are wrong where that name was "wrong value"

                other = [explain(m, "en")[0] for m in result.mistakes if m not in (code, "wrong_value")]
                kept = [n for n in result.notes[:-1] if not any(o in render(n, "en") for o in other)]
                rows = tuple(RowResult(r.label_msg, r.status, detail, code, r.entries, r.score)
                             if r.mistake not in (None, "wrong_value", code) else r for r in result.rows)
                return CheckResult(False, result.score, kept[:1] + notes + kept[1:] + hints([code], {}), [code],
                                   rows, quantity, result.columns)
        return None

    def _copied(self, answer, data, options, quantity):
        """A symbolic answer that is right for other data — the joint printed above, the notebook's data when a
        variant is asked: named ``wrong_data`` (None otherwise)."""
        others = list(self.lookalikes(**data)) if self.lookalikes is not None else []
        if not same_data(data, self.data):
            others.append((self.target(**self.data), _msg("x.other_data", what=text_message("notebook_data"))))
        for target, detail in others:
            try:
                if self.checker(answer, target, **options).passed:
                    return CheckResult(False, 0.0, [detail] + hints(["wrong_data"], {}), ["wrong_data"], (),
                                       quantity)
            except Exception:  # noqa: BLE001 — another target may not read this answer: not a lookalike then
                continue
        return None

    def _with_lookalikes(self, target, data, slips=True):
        if not isinstance(target, Expected):
            try:
                target = Expected(np.asarray(target, float))
            except (TypeError, ValueError):  # not a number (a Newton problem): nothing to add
                return target
        target = target.copy()
        seen = []
        if self.lookalikes is not None:
            seen += list(self.lookalikes(**data))
        if not same_data(data, self.data):  # a variant: the notebook's own answer is a lookalike too
            other = self.target(**self.data)
            seen.append((np.asarray(getattr(other, "value", other), float), _msg("x.other_data",
                                                                                what=text_message("notebook_data"))))
        for value, detail in seen:
            target.variants.insert(0, ("wrong_data", np.asarray(value, float), detail, None))
        if slips:
            target.variants += [(code, value, None, None) for code, _, value in self.slips(data)]
        return target

    def slips(self, data=None):
        """(code, operator, value) of the worked answer's slips at ``data`` (:func:`kinbook.grading.mutants.slips`):
        the wrong answers a numeric try-it names after the catalogue's own (issue 29)."""
        data = self.data_for(data)
        names, context = self._data_names(), self.context()
        key = repr([(k, np.asarray(data[k], dtype=object).tolist()) for k in sorted(data)])
        return slips(self.solution, lambda f: f(**context, **{n: data[n] for n in names}), key)

    def reference_answer(self, data=None):
        """The worked answer's value, computed from the library's context."""
        data = self.data_for(data)
        return self.solution(**self.context(), **{n: data[n] for n in self._data_names()})

    def _data_names(self):
        """The data the worked answer reads (its keyword-only parameters)."""
        return [p.name for p in inspect.signature(self.solution).parameters.values() if p.kind == p.KEYWORD_ONLY]

    def solution_code(self, data=None):
        """The worked answer as the notebook code that produces ``self.answer`` (the data first)."""
        lines = textwrap.dedent(inspect.getsource(self.solution)).splitlines()
        k = 0
        while not lines[k].rstrip().endswith(":"):  # a signature over several lines
            k += 1
        body = lines[k + 1:]  # the def line(s)
        if body and body[0].lstrip().startswith(('"""', "'''")):
            body = body[1:]
        while body and not body[-1].strip():
            body.pop()
        last = body[-1].strip()
        if last == f"return {self.answer}":
            body = body[:-1]
        elif last.startswith("return "):
            indent = body[-1][: len(body[-1]) - len(body[-1].lstrip())]
            body[-1] = f"{indent}{self.answer} = {last[len('return '):]}"
        data = self.data_for(data)
        head = [f"{n} = {_literal(data[n])}" for n in self._data_names()]
        return "\n".join(head + textwrap.dedent("\n".join(body)).splitlines())

    def stated(self, data=None):
        """The data as the question states them (the statement filled in)."""
        data = self.data_for(data)
        if self.statement is None:
            return ", ".join(f"{k} = {_literal(v)}" for k, v in data.items())
        if callable(self.statement):
            return self.statement(**data)
        return translate(self.statement).format(**{k: _literal(v) for k, v in data.items()})


def _numbers(answer):
    """The answer is plain numbers (a number, or a list/array of them), not formulas."""
    try:
        a = np.asarray(answer)
    except (TypeError, ValueError):
        return False
    return a.dtype.kind in "iuf" and a.size > 0


_DESCRIBED = {"d.missing_term": "d.missing_kind", "d.sign_of_term": "d.sign_of_kind",
              "d.or_sign_of_term": "d.or_sign_of_kind"}
"""A detail that writes a term out (the answer's last step) → the same detail saying what kind of term it is."""


def described(result):
    """``result`` with every term that a detail writes out described instead ("a term is missing: a term of t alone
    …" for "the term 500.0*t is missing"): a try-it's hint points at a step, never at a term to copy."""
    def swap(x):
        if isinstance(x, Msg):
            if x.key in _DESCRIBED and "kind" in x.fields:
                return Msg(_DESCRIBED[x.key], kind=x.fields["kind"])
            fields = {k: swap(v) for k, v in x.fields.items()}
            return x if all(fields[k] is x.fields[k] for k in fields) else Msg(x.key, **fields)
        if isinstance(x, list):
            out = [swap(v) for v in x]
            return x if all(a is b for a, b in zip(out, x)) else out
        if isinstance(x, tuple):
            out = tuple(swap(v) for v in x)
            return x if all(a is b for a, b in zip(out, x)) else out
        return x

    notes = [swap(m) for m in result.notes]
    rows = [RowResult(r.label_msg, r.status, swap(r.message_msg), r.mistake, r.entries, r.score) for r in result.rows]
    return CheckResult(result.passed, result.score, notes, result.mistakes, rows, result.quantity_msg,
                       result.columns).echo(result)


def same_data(a, b):
    """Two sets of data are the same (arrays compared by value)."""
    return a.keys() == b.keys() and all(np.array_equal(np.asarray(a[k], dtype=object), np.asarray(b[k], dtype=object))
                                        for k in a)


def _literal(v):
    """A datum as code: 0.004, 1.5, [2, 1, -1], 135."""
    if isinstance(v, np.ndarray):
        return f"np.array({_literal(v.tolist())})"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_literal(x) for x in v) + "]"
    if isinstance(v, (float, np.floating)):
        x = float(v)
        return str(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(round(x, 10))
    return repr(v)


def _msg(key, **fields):
    return Msg(key, **fields)


def text_message(key, **fields):
    """A text of this module as a marked message, written in the language of the moment when shown."""
    return Message(_TEXT[key], **fields)


def table_text(key, lang, **fields):
    """A text of this module in ``lang``, through the package's catalogue (:mod:`kinbook.i18n`)."""
    return Message(_TEXT[key], **fields).render(lang)


def register(id, answer, checker, target, solution, options=None, context=None, *, data=None, ranges=None,
             statement=None, explanation=None, lookalikes=None, wrong_forms=None, numbers_at=None, library=()):
    """Add a :class:`TryIt` to :data:`TRY_ITS` (used by the chapter modules); returns it."""
    if id in TRY_ITS:
        raise ValueError(f"try-it {id!r} is registered twice")
    checker = checker_for(checker)
    if checker.quantity is not None:  # a mechanism or a constraint: what is derived from it is cached on it
        target = ByData(target)
    if wrong_forms is not None:
        wrong_forms = ByData(wrong_forms)
    item = TryIt(answer=answer, checker=checker, target=target, options=dict(options or {}),
                 data=dict(data or {}), ranges=dict(ranges or {}), id=id, solution=solution, context=context or dict,
                 statement=statement, explanation=explanation, lookalikes=lookalikes, wrong_forms=wrong_forms,
                 numbers_at=numbers_at, library=tuple(library))
    TRY_ITS[id] = item
    return item


class ByData:
    """A function of a try-it's data that keeps its last :data:`KEPT` results by the data's values: a symbolic
    try-it's target (a mechanism or a constraint, which keeps its derivation, samples and catalogue variants —
    :meth:`~kinbook.core.mechanism.MechanismBase.cached`) and its wrong forms are built once per data, not once per
    answer checked (the mutation run checks hundreds of answers on the same data). Immutable results only: a
    mechanism invalidates its own cache when it changes; wrong forms are returned as a tuple."""

    KEPT = 8

    def __init__(self, function):
        self.function = function
        self._kept = {}
        functools.update_wrapper(self, function)

    def __call__(self, **data):
        key = repr([(k, np.asarray(data[k], dtype=object).tolist()) for k in sorted(data)])
        if key in self._kept:
            self._kept[key] = self._kept.pop(key)  # the most recent last
        else:
            if len(self._kept) >= self.KEPT:
                self._kept.pop(next(iter(self._kept)))
            found = self.function(**data)
            self._kept[key] = tuple(found) if isinstance(found, list) else found
        return self._kept[key]


_TEXT = {
    "blank": N_("{title} is not answered yet: replace <code>...</code> in <code>{answer} = ...</code> with your "
                "answer and run the cell again. Stuck? <code>kb.reveal(\"{id}\")</code> shows a worked answer."),
    "title": N_("Try it {k} ({notebook})"),
    "worked": N_("A worked answer to {title}"),
    "uses": N_("It uses these variables of the notebook: {names}."),
    "variant_title": N_("{title}, variant {k}"),
    "variant_data": N_("the same question with this data: {data}"),
    "variant_how": N_("Answer it in a cell of your own, then <code>kb.try_it(\"{id}\", {answer})</code> checks it and "
                      "<code>kb.reveal(\"{id}\")</code> shows its worked answer; <code>kb.another(\"{id}\")</code> draws "
                      "the next variant, <code>kb.another(\"{id}\", 0)</code> goes back to the notebook's data (drawn "
                      "with seed {seed})."),
    "variant_zero": N_("{title}, the notebook's data: {data}"),
    "no_variants": N_("{title} has no other data to draw: its data is the notebook's."),
    "with_data": N_("for the data {data}"),
    "notebook_data": N_("the answer for the notebook's data, not for this variant's"),
    "why": N_("Why"),
    "library": N_("this is kinbook's own answer ({name}): right, and a good check of your own — now build it by hand "
                  "(the worked answer shows how)"),
}

add_texts({
    "x.numbers_right_at": N_("these are the right values at t = {t} only: the question asks for each row as a formula "
                             "of t (a string such as \"2*t\"), which the numbers of one instant do not show"),
    "x.numbers_read_at": N_("your numbers are read as the values at t = {t} (the question asks for formulas of t); "
                            "there they are not right:"),
})


