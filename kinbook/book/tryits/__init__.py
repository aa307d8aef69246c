"""The notebooks' "Try it" exercises as data: what the student writes, how it is checked, a worked answer.

A try-it cell in a chapter notebook is blank::

    my_A = ...                      # your answer
    kb.try_it("13-1/try-1", my_A)

:func:`try_it` shows "not answered yet" while the answer is still ``...`` and otherwise runs the checker
registered here against a reference that the library computes (never one typed in the notebook).
:func:`reveal` prints the worked answer, which lives here as a small function: its body is the code shown,
and the test suite runs it through the same check (``tests/book/test_tryits.py``).

Each :class:`TryIt` keeps its checker, its target and the checker's options as data, so other tests can
re-run the check with typical wrong answers (``TRY_ITS["13-2/try-1"].check(wrong)``).
"""

from __future__ import annotations

import html
import inspect
import textwrap
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

__all__ = ["TryIt", "NotAnswered", "Variant", "TRY_ITS", "get", "try_it", "reveal", "another", "register",
           "is_blank"]

TRY_ITS: dict[str, "TryIt"] = {}
"""Every try-it, by id ("13-1/try-1"), in notebook order."""


@dataclass(frozen=True)
class TryIt:
    """One "Try it" exercise of a chapter notebook.

    Attributes
    ----------
    id : str
        ``"<notebook>/try-<k>"``, e.g. ``"13-2/try-1"``: the notebook's number and the exercise's place in it.
    answer : str
        Name of the notebook variable the student fills in (``"my_Phi"``); unique in its notebook.
    checker : callable
        A :mod:`kinbook.grading` checker, called as ``checker(answer, target, **options)``.
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
        The data as the question gives them ("t = 0.004 s"): a format string or a function of the data.
    explanation : dict or None
        ``{"en": …, "es": …}``: why the worked answer is what it is, shown by :func:`reveal` after the code.
    lookalikes : callable or None
        ``lookalikes(**data)`` → [(value, Msg)]: numbers the notebook prints nearby that a student may copy
        (named ``wrong_data``).
    """

    id: str
    answer: str
    checker: Callable
    target: Callable[..., Any]
    solution: Callable
    options: dict = field(default_factory=dict)
    context: Callable[[], dict] = field(default=dict, repr=False)
    data: dict = field(default_factory=dict)
    ranges: dict = field(default_factory=dict)
    statement: Any = None
    explanation: Any = None
    lookalikes: Any = None

    def _data(self, data):
        return dict(self.data) if data is None else dict(data)

    def check(self, answer, data=None):
        """Run the checker on ``answer`` (a :class:`kinbook.grading.CheckResult`) for ``data`` (default: the
        notebook's)."""
        data = self._data(data)
        target = self.target(**data)
        options = dict(self.options)
        if _numeric(self.checker):
            options.setdefault("reveal", False)
            target = self._with_lookalikes(target, data)
            return self.checker(answer, target, **options)
        result = self.checker(answer, target, **options)
        if result.passed or result.mistakes not in (["wrong_value"], ["malformed"]):
            return result
        copied = self._copied(answer, data, options, result._quantity)
        return result if copied is None else copied

    def _copied(self, answer, data, options, quantity):
        """A symbolic answer that is right for other data — the joint printed above, the notebook's data when a
        variant is asked: named ``wrong_data`` (None otherwise)."""
        from ...grading.report import hints
        from ...grading.result import CheckResult

        others = list(self.lookalikes(**data)) if self.lookalikes is not None else []
        if not _same(data, self.data):
            others.append((self.target(**self.data), _msg("x.other_data", what=both_texts("notebook_data"))))
        for target, detail in others:
            try:
                if self.checker(answer, target, **options).passed:
                    return CheckResult(False, 0.0, [detail] + hints(["wrong_data"], {}), ["wrong_data"], (),
                                       quantity)
            except Exception:  # noqa: BLE001 — another target may not read this answer: not a lookalike then
                continue
        return None

    def _with_lookalikes(self, target, data):
        from ...grading.expected import Expected

        if not isinstance(target, Expected):
            try:
                target = Expected(np.asarray(target, float))
            except (TypeError, ValueError):  # not a number (a Newton problem): nothing to add
                return target
        target = target.copy()
        seen = []
        if self.lookalikes is not None:
            seen += list(self.lookalikes(**data))
        if not _same(data, self.data):  # a variant: the notebook's own answer is a lookalike too
            other = self.target(**self.data)
            seen.append((np.asarray(getattr(other, "value", other), float), _msg("x.other_data",
                                                                                what=both_texts("notebook_data"))))
        for value, detail in seen:
            target.variants.insert(0, ("wrong_data", np.asarray(value, float), detail, None))
        return target

    def reference_answer(self, data=None):
        """The worked answer's value, computed from the library's context."""
        data = self._data(data)
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
        data = self._data(data)
        head = [f"{n} = {_literal(data[n])}" for n in self._data_names()]
        return "\n".join(head + textwrap.dedent("\n".join(body)).splitlines())

    def stated(self, data=None):
        """The data as the question states them (the statement filled in)."""
        data = self._data(data)
        if self.statement is None:
            return ", ".join(f"{k} = {_literal(v)}" for k, v in data.items())
        if callable(self.statement):
            return self.statement(**data)
        return self.statement.format(**{k: _literal(v) for k, v in data.items()})


def _same(a, b):
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


def _numeric(checker):
    return "reveal" in inspect.signature(checker).parameters


def _msg(key, **fields):
    from ...grading._i18n import Msg

    return Msg(key, **fields)


def both_texts(key, **fields):
    """A text of this module in every language (a dict rendered when shown)."""
    return {lang: table_text(key, lang, **fields) for lang in ("en", "es")}


def table_text(key, lang, **fields):
    table = _TEXT[key]
    return (table.get(lang) or table["en"]).format(**fields)


def register(id, answer, checker, target, solution, options=None, context=None, *, data=None, ranges=None,
             statement=None, explanation=None, lookalikes=None):
    """Add a :class:`TryIt` to :data:`TRY_ITS` (used by the chapter modules); returns it."""
    if id in TRY_ITS:
        raise ValueError(f"try-it {id!r} is registered twice")
    item = TryIt(id, answer, checker, target, solution, dict(options or {}), context or dict, dict(data or {}),
                 dict(ranges or {}), statement, explanation, lookalikes)
    TRY_ITS[id] = item
    return item


def get(id):
    """The :class:`TryIt` with this id; the error lists the ids of the same notebook."""
    from ...errors import InputError

    _load()
    try:
        return TRY_ITS[id]
    except KeyError:
        notebook = str(id).split("/")[0]
        near = [k for k in TRY_ITS if k.startswith(notebook + "/")] or list(TRY_ITS)[:6]
        raise InputError(f"no try-it {id!r}; expected one of {', '.join(near)}") from None


def _load():
    from . import ch13, ch14  # noqa: F401  (registering)


def is_blank(answer):
    """True while the answer is still the placeholder ``...`` (also inside a list or tuple)."""
    if answer is Ellipsis:
        return True
    if isinstance(answer, (list, tuple)):
        return any(is_blank(a) for a in answer)
    return False


_TEXT = {
    "blank": {
        "en": "{title} is not answered yet: replace <code>...</code> in <code>{answer} = ...</code> with your "
              "answer and run the cell again. Stuck? <code>kb.reveal(\"{id}\")</code> shows a worked answer.",
        "es": "{title} aún no tiene respuesta: sustituya <code>...</code> en <code>{answer} = ...</code> por su "
              "respuesta y ejecute de nuevo la celda. ¿Atascado? <code>kb.reveal(\"{id}\")</code> muestra una "
              "solución.",
    },
    "title": {"en": "Try it {k} ({notebook})", "es": "Pruébelo {k} ({notebook})"},
    "worked": {"en": "A worked answer to {title}", "es": "Una solución de {title}"},
    "uses": {"en": "It uses these variables of the notebook: {names}.",
             "es": "Usa estas variables del cuaderno: {names}."},
    "variant_title": {"en": "{title}, variant {k}", "es": "{title}, variante {k}"},
    "variant_data": {"en": "the same question with this data: {data}", "es": "la misma pregunta con estos datos: "
                                                                                "{data}"},
    "variant_how": {
        "en": "Answer it in a cell of your own, then <code>kb.try_it(\"{id}\", {answer})</code> checks it and "
              "<code>kb.reveal(\"{id}\")</code> shows its worked answer; <code>kb.another(\"{id}\")</code> draws "
              "the next variant, <code>kb.another(\"{id}\", 0)</code> goes back to the notebook's data (drawn "
              "with seed {seed}).",
        "es": "Respóndala en una celda propia; luego <code>kb.try_it(\"{id}\", {answer})</code> la comprueba y "
              "<code>kb.reveal(\"{id}\")</code> muestra su solución; <code>kb.another(\"{id}\")</code> saca la "
              "variante siguiente, <code>kb.another(\"{id}\", 0)</code> vuelve a los datos del cuaderno "
              "(sorteada con la semilla {seed}).",
    },
    "variant_zero": {"en": "{title}, the notebook's data: {data}", "es": "{title}, los datos del cuaderno: {data}"},
    "no_variants": {"en": "{title} has no other data to draw: its data is the notebook's.",
                    "es": "{title} no tiene otros datos que sortear: sus datos son los del cuaderno."},
    "with_data": {"en": "for the data {data}", "es": "para los datos {data}"},
    "notebook_data": {"en": "this is the answer for the notebook's data, not for this variant's",
                      "es": "esta es la respuesta para los datos del cuaderno, no para los de esta variante"},
    "why": {"en": "Why", "es": "Por qué"},
}


def _tr(key, **fields):
    from ...grading import get_language

    return table_text(key, get_language(), **fields)


def _title(item):
    notebook, _, k = item.id.partition("/try-")
    return _tr("title", k=k, notebook=notebook)


class NotAnswered:
    """What :func:`try_it` returns while the answer is still ``...``: a notice, not an error."""

    passed = False
    score = 0.0

    def __init__(self, item):
        self.item = item

    def __bool__(self):
        return False

    def _text(self):
        return _tr("blank", title=_title(self.item), answer=self.item.answer, id=self.item.id)

    def __repr__(self):
        return html.unescape(self._text().replace("<code>", "`").replace("</code>", "`"))

    def _repr_html_(self):
        return ('<div style="border-left:4px solid #b8860b; background:#fff8e1; padding:4px 10px">'
                f"{self._text()}</div>")


def _explanation(item):
    from ...grading import get_language

    text = item.explanation
    if not text:
        return ""
    return text.get(get_language()) or text["en"]


class Revealed:
    """The worked answer of a try-it, shown as code (``kb.reveal(id)``), with why, for the data in use."""

    def __init__(self, item, data=None):
        self.item = item
        self.data = item._data(data)
        self.code = item.solution_code(self.data)
        self.uses = [p.name for p in inspect.signature(item.solution).parameters.values()
                     if p.kind != p.KEYWORD_ONLY]
        self.why = _explanation(item)

    def _head(self):
        head = _tr("worked", title=_title(self.item))
        if not _same(self.data, self.item.data):
            head += " " + _tr("with_data", data=self.item.stated(self.data))
        if self.uses:
            head += ". " + _tr("uses", names=", ".join(self.uses))
        return head

    def __repr__(self):
        out = f"# {self._head()}\n{self.code}"
        if self.why:
            out += f"\n\n{_tr('why')}: {self.why}"
        return out

    def _repr_html_(self):
        out = (f"<p><b>{html.escape(self._head())}</b></p>"
               f"<pre style='background:#f6f8fa; padding:6px 10px'>{html.escape(self.code)}</pre>")
        if self.why:
            out += f"<p><b>{html.escape(_tr('why'))}.</b> {html.escape(self.why)}</p>"
        return out


_CURRENT: dict = {}
"""The variant each try-it is checked against: id → (k, data); absent = the notebook's data."""


def _data_of(item):
    return _CURRENT.get(item.id, (0, item.data))[1]


def try_it(id, answer):
    """Check a notebook's try-it answer (against the variant drawn last by :func:`another`, if any).

    Parameters
    ----------
    id : str
        The try-it's id, e.g. ``"13-1/try-1"``.
    answer
        What the student wrote; ``...`` (the placeholder) means "not answered yet".

    Returns
    -------
    CheckResult or NotAnswered
        Both display themselves in a notebook. A wrong number is described (which entries, how they are off,
        the mistake's name), never given: only :func:`reveal` shows the answer.
    """
    item = get(id)
    if is_blank(answer):
        return NotAnswered(item)
    return item.check(answer, _data_of(item))


def reveal(id):
    """A worked answer to a try-it (for the variant in use), as code to read — and why it is so."""
    item = get(id)
    return Revealed(item, _data_of(item))


class Variant:
    """A try-it with other data (``kb.another(id)``): shows the data; ``variant.data`` holds them."""

    def __init__(self, item, k, data, seed):
        self.item, self.k, self.data, self.seed = item, k, dict(data), seed

    def __getitem__(self, key):
        return self.data[key]

    def _lines(self):
        title = _title(self.item)
        if not self.item.ranges:
            return [_tr("no_variants", title=title)]
        if self.k == 0:
            return [_tr("variant_zero", title=title, data=self.item.stated(self.data))]
        return [_tr("variant_title", title=title, k=self.k) + " — " + _tr("variant_data", data=self.item.stated(
            self.data)), _tr("variant_how", id=self.item.id, answer=self.item.answer, seed=self.seed)]

    def __repr__(self):
        return "\n".join(html.unescape(t.replace("<code>", "`").replace("</code>", "`")) for t in self._lines())

    def _repr_html_(self):
        lines = self._lines()
        body = f"<b>{html.escape(lines[0])}</b>" + "".join(f"<br>{t}" for t in lines[1:])
        return f'<div style="border-left:4px solid #1f6feb; background:#eef5ff; padding:4px 10px">{body}</div>'


MAX_DRAWS = 25


def another(id, k=None):
    """Draw a fresh variant of a try-it: the same question with other data, drawn by the seeded generator
    the exercises' per-student parameters use (:func:`kinbook.classroom.variant.draw`). :func:`try_it` and
    :func:`reveal` then use it.

    Parameters
    ----------
    id : str
        The try-it's id.
    k : int, optional
        Which variant: 1, 2, … (the same k gives the same data, on every machine); 0 is the notebook's data.
        Default: the one after the variant in use.

    Returns
    -------
    Variant
        Shows the data (and the seed it was drawn with).
    """
    from ...classroom.variant import draw, seed_from
    from ...errors import InputError, KinbookError

    item = get(id)
    if k is None:
        k = _CURRENT.get(id, (0, None))[0] + 1
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 0:
        raise InputError(f"kb.another({id!r}, k): k must be a whole number ≥ 0 (0 = the notebook's data), got {k!r}")
    k = int(k)
    if k == 0 or not item.ranges:
        _CURRENT.pop(id, None)
        return Variant(item, 0, item.data, None)
    last = None
    for attempt in range(MAX_DRAWS):
        seed = seed_from(f"try-it:{id}:{k}:{attempt}")
        data = draw(item.ranges, item.data, seed)
        if _same(data, item.data):  # the notebook's own data: not a new variant
            continue
        try:
            item.target(**data)
        except KinbookError as exc:  # the mechanism does not assemble with these data: the next draw
            last = exc
            continue
        _CURRENT[id] = (k, data)
        return Variant(item, k, data, seed)
    raise InputError(f"{id}: no data drawn for variant {k} works ({last})")
