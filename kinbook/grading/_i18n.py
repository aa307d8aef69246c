"""Feedback as sentences written when shown: :class:`Msg`, and the checkers' message templates.

Checkers do not write sentences: they keep :class:`Msg` objects (a template key and its fields), and a result
renders them in the current language when it is shown — translation is the last step, so a result made in
English reads in Spanish after ``set_language("es")``. The templates are English, marked for translation
(:mod:`kinbook.i18n`: ``N_``, ``Np_`` with plural forms chosen by the field ``n``, ``pN_`` with a context); the
Spanish is in the package's gettext catalogue (kinbook/locale/es/LC_MESSAGES/kinbook.po). Templates use the
book's notation (Φ, Φ_q, ν, γ, ξ, η, φ).

A module adds its own templates with :func:`add_texts` (``{"key": N_("…")}``).
"""

from __future__ import annotations

import importlib

from ..i18n import LANGUAGES, N_, Contextual, Message, Np_, Plural, get_language, pN_, set_language, translate

__all__ = ["set_language", "get_language", "tr", "Msg", "render", "both", "constraint_label", "row_name",
           "rows_name", "LANGUAGES", "add_texts"]


class Msg(Message):
    """A sentence to be written later: a template key and its fields (which may be Msg objects, marked messages
    such as a reader error's, or dicts by language, themselves rendered when the sentence is). A template with
    plural forms takes them from the field ``n``."""

    __slots__ = ("key",)

    def __init__(self, key, **fields):
        if key not in _TEXT:
            _register_all()
        if key not in _TEXT:
            raise KeyError(f"no feedback template {key!r}")
        super().__init__(_TEXT[key], **fields)
        self.key = key

    def render(self, lang=None):
        return render(self, lang)

    def __repr__(self):
        return f"Msg({self.key!r})"

    def __str__(self):
        return render(self)

    def __eq__(self, other):
        return isinstance(other, Msg) and (self.key, self.fields) == (other.key, other.fields)

    __hash__ = None


def render(x, lang=None):
    """A Msg, a marked message, a text computed per language (:func:`both`: a dict by language), a list of those,
    or a plain value, as text in ``lang`` (default: the current language)."""
    lang = lang or get_language()
    if isinstance(x, Msg):
        text = _template(x.key, lang, x.fields.get("n"))
        return text.format(**{k: _field(v, lang) for k, v in x.fields.items()})
    if isinstance(x, Message):
        return x.render(lang)
    if isinstance(x, dict) and "en" in x:
        return x.get(lang) or x["en"]
    return x if isinstance(x, str) else str(x)


def _template(key, lang, n):
    if key not in _TEXT:
        _register_all()
    return translate(_TEXT[key], lang, n)


def _field(v, lang):
    if isinstance(v, (Message, dict)):
        return render(v, lang)
    if isinstance(v, (list, tuple)) and v and all(isinstance(e, (Message, dict, str)) for e in v):
        sep = "; "
        return sep.join(render(e, lang) for e in v)
    return v


def tr(key, **fields):
    """The template ``key`` in the current language, filled with ``fields`` (rendered now)."""
    return render(Msg(key, **fields))


def both(fn):
    """{"en": fn("en"), "es": fn("es")}: a text computed once per language, chosen when shown."""
    return {lang: fn(lang) for lang in LANGUAGES}


def row_name(k):
    """Book name of the 0-based row ``k`` of Φ: "Φ_4"."""
    return f"Φ_{k + 1}"


def rows_name(rows):
    """"Φ_4–Φ_5" (or "Φ_12") for 0-based rows."""
    rows = list(rows)
    if len(rows) == 1:
        return row_name(rows[0])
    return f"{row_name(rows[0])}–{row_name(rows[-1])}"


def _title(c, lang):
    """The class's title in ``lang`` (``title = N_("revolute joint")``, every registered constraint class has one):
    through the catalogue, as written when the catalogue does not have it (an extension's own type)."""
    title = getattr(c, "title", None)
    if isinstance(title, str) and title:
        return translate(title, lang)
    return str(getattr(c, "type_name", None) or type(c).__name__)


def constraint_label(c, lang=None):
    """"revolute joint 1 (rows Φ_4–Φ_5)" / "par de revolución 1 (filas Φ_4–Φ_5)"."""
    lang = lang or get_language()
    kind = _title(c, lang)
    name = str(c.name)
    if c.kind == "driver" and name.startswith("driver"):
        name = name[len("driver"):].strip()
    if getattr(c, "per_body", False) or c.kind == "normalization" or len(c.bodies) == 1 and c.kind == "simple" \
            and name in ("ground",):
        what = f"{kind} '{c.bodies[0].name}'"
    else:
        what = f"{kind} {name}"
    rows = list(range(c.rows.start, c.rows.stop))
    return render(Msg("constraint_rows", what=what, rows=rows_name(rows), n=len(rows)), lang)


_TEXT = {
    "constraint_rows": Np_("{what} (row {rows})", "{what} (rows {rows})"),
    "h.row": N_("row"),
    "h.verdict": N_("verdict"),
    "h.score": N_("score"),
    "h.mistakes": N_("mistakes"),
    "h.passed": N_("passed"),
    "h.failed": N_("failed"),
    "h.read_as": N_("your answer, as read"),
    "all_correct": Np_("{what} is correct: its only row matches kinbook's reference.",
                       "{what} is correct: all {n} rows match kinbook's reference."),
    "all_correct_equivalent": Np_("{what} is correct: your row is equivalent to the reference's {m}, constraint by "
                                  "constraint (the rows written differently say how this was checked).",
                                  "{what} is correct: your {n} rows are equivalent to the reference's {m}, constraint "
                                  "by constraint (the rows written differently say how this was checked)."),
    "all_consistent": Np_("{what} is consistent with your Φ: its only row follows from it (full credit) and differs "
                          "from the reference because your Φ does.",
                          "{what} is consistent with your Φ: all {n} rows follow from it (full credit); {k} of "
                          "them differ from the reference because your Φ does."),
    "summary": Np_("{what}: {ok} of {n} row correct (score {score:.2f}).",
                   "{what}: {ok} of {n} rows correct (score {score:.2f})."),
    "summary_entries": Np_("{what}: {ok} of {n} row fully correct, {eok} of {en} nonzero entries right (score "
                           "{score:.2f}).",
                           "{what}: {ok} of {n} rows fully correct, {eok} of {en} nonzero entries right (score "
                           "{score:.2f})."),
    "summary_half": Np_("{what}: {ok} of {n} row correct, {half} more right but out of place (half credit each; "
                        "score {score:.2f}).",
                        "{what}: {ok} of {n} rows correct, {half} more right but out of place (half credit each; "
                        "score {score:.2f})."),
    "summary_transposed": Np_("{what}: 0 of {n} row correct as given; the matrix is right once transposed (half "
                              "credit: score {score:.2f}).",
                              "{what}: 0 of {n} rows correct as given; the matrix is right once transposed (half "
                              "credit: score {score:.2f})."),
    "row_ok": pN_("a row", "correct"),
    "row_ok_scaled": N_("correct: the reference row multiplied by {c}, which defines the same constraint"),
    "row_ok_jacobian_scaled": N_("correct: the reference row multiplied by {c} (the Jacobian of {c}·{ref})"),
    "row_equivalent": N_("correct: not the reference's form, but where {owner} alone holds it vanishes with the rank "
                         "of {refs} (compared at {N} configurations), and the {S} configurations where a seeded search "
                         "found it zero all satisfy {owner}"),
    "row_equivalent_book": N_("correct: the book's form of {refs} — a row of s̃_i s_j (§14.4), equivalent to kinbook's "
                              "where {owner} holds (compared at {N} configurations)"),
    "row_equivalent_jacobian": N_("correct: not the reference's row, but at each of the {N} configurations compared a "
                                  "combination of {refs} — the Jacobian of an equivalent formulation of the "
                                  "constraint"),
    "row_moved": N_("right, but it is {ref}: the exercise asks for the book's order (half credit)"),
    "row_depends_repeat": N_("row {k} depends on row {j}: it repeats it{times}, so it adds no equation"),
    "times": N_(" multiplied by {c}"),
    "row_depends_function": N_("row {k} depends on {rows}: it vanishes together with its gradient where the "
                               "mechanism is assembled (a function of those rows: a power, a product, a sum of squares), so it "
                               "adds no independent equation"),
    "row_depends_combination": N_("row {k} depends on rows {rows}: it is a constant combination of them, so it adds "
                                  "no equation"),
    "row_depends_redundant": Np_("row {k} is redundant: {owner} has {n} independent equation, and your rows {rows} "
                                 "already give it",
                                 "row {k} is redundant: {owner} has {n} independent equations, and your rows {rows} "
                                 "already give them"),
    "row_depends_free": N_("row {k} adds nothing to this constraint: it is {what}, which holds anyway (a row of the "
                           "body, not of this joint)"),
    "row_masked": N_("{text}; it holds here only because of {others} — as a row of {owner} alone it does not"),
    "the_rest": N_("the other constraints"),
    "row_wrong": N_("wrong: it is not {ref} ({owner}), nor a multiple of any other row"),
    "row_extra": N_("extra row: it matches no row of the reference"),
    "row_missing": N_("missing: no row of your answer is {ref} ({owner})"),
    "row_missing_own": N_("missing: your Φ has a row {k} and this answer has no row for it"),
    "row_mistake": N_("wrong — {title}"),
    "row_mistake_detail": N_("wrong — {title}: {detail}"),
    "book_misprint": N_("this is the book's printed formula, which is wrong: see erratum {id}"),
    "your_row": N_("your row {k}"),
    "row_line": N_("{label} — {owner}: {text}"),
    "row_line_short": N_("{label}: {text}"),
    "row_extra_at": N_("your row {k}: extra row, it matches no row of the reference"),
    "row_with_entries": N_("{text}; wrong entries: {entries}"),
    "entries_wrong": N_("wrong entries: {entries}"),
    "consistent_correct": N_("consistent with your Φ, and correct"),
    "consistent_not_correct": N_("consistent with your Φ (full credit here); the row of Φ it comes from differs from "
                                 "the reference and was graded in the Φ part"),
    "correct_not_consistent": N_("correct, although it does not follow from your Φ"),
    "hint": N_("Hint ({title}): {hint}"),
    "symbolic_confirmed": N_("sympy confirmed the equivalence symbolically"),
    "symbolic_unconfirmed": Np_("sympy did not confirm {n} matched entry symbolically (expressions this size are "
                                "only compared numerically); the verdict rests on the numeric comparison at {N} "
                                "configurations",
                                "sympy did not confirm {n} of the matched entries symbolically (expressions this "
                                "size are only compared numerically); the verdict rests on the numeric comparison "
                                "at {N} configurations"),
    "bad_type": N_("expected {expected}; got an object of type {type}"),
    "expect_answer": N_("no answer: give a sympy Matrix, a list of expressions or strings in the mechanism's "
                        "coordinates, a function {signature}, or numbers with at="),
    "expect_Phi": N_("Φ as expressions, strings or a function f(q, t)"),
    "expect_Phi_q": N_("Φ_q as a matrix of expressions or strings, or a function f(q, t)"),
    "expect_nu": N_("ν as expressions, strings or a function f(q, t)"),
    "expect_gamma": N_("γ as expressions in q, q̇ and t, strings or a function f(q, qd, t)"),
    "bool_answer": N_("True and False are not numbers: give the value itself"),
    "complex_answer": N_("the answer has complex numbers: kinematic quantities are real"),
    "not_numbers": N_("{what}: expected real numbers, got {got}"),
    "shape_changes": N_("your function returned an array of shape {first} at one configuration and {then} at "
                        "another: it must return the same shape every time"),
    "bad_option": N_("`{name}` must be {expected}, got {got}"),
    "opt_rtol": N_("a number between 0 and 1 (a relative tolerance)"),
    "opt_bool": N_("True or False"),
    "opt_at": N_("a dict {{'q': …, 'qd': …, 't': …}} with q and qd of the mechanism's {n} coordinates"),
    "callable_result": N_("your function's result"),
    "answer": N_("the answer"),
    "too_many_numbers": N_("your function returned {n} numbers (at most {limit} are read)"),
    "too_many_axes": N_("wrong shape: a vector or a matrix was expected, got an array of shape {shape}"),
    "returns_symbols": N_("a function must return numbers, not symbolic expressions"),
    "ragged": N_("wrong shape: rows of different lengths"),
    "nested_deeper": N_("wrong shape: lists nested too deeply"),
    "empty_answer": N_("the answer is empty"),
    "empty_text": N_("{where} is empty"),
    "bad_entry": N_("{where}: expected an expression, a string or a number, got {type}"),
    "not_an_expression": N_("{where}: {type} is not an expression of a number (a relation or a set?)"),
    "reader": "{message}",  # a message of the reader (an ExpressionError's), already marked there
    "answer_row": N_("answer row {i}"),
    "answer_entry": N_("answer row {i}, entry {j}"),
    "answer_at": N_("answer{index}"),
    "unsupported": N_("the answer cannot be evaluated: {what}"),
    "unknown_symbols": N_("{where}: unknown symbol(s) {names}: write the answer in the coordinates x1, y1, phi1 … "
                          "(or φ1, phi_1), velocities dx1, dphi1 … and t"),
    "callable_failed": N_("your function raised {error} when called as {signature}"),
    "needs_expression": N_("numbers cannot be differentiated: give Φ as expressions or a function"),
    "not_finite": N_("the answer is not a finite real number (NaN, inf or complex) in {where}"),
    "wrong_shape": N_("wrong shape: expected {expected}, got {got}"),
    "transposed": N_("the matrix is transposed: expected {expected} (one row per constraint equation, one column per "
                     "coordinate), got {got}"),
    "transposed_right": N_("once transposed it would be correct"),
    "needs_configuration": N_("numbers are the values at one configuration: give the configuration, at={{'q': ..., "
                              "'qd': ..., 't': ...}} (or give the formula instead)"),
    "bad_configuration": N_("cannot use at={at}: {error}"),
    "phi_unusable": N_("your Φ could not be used for error carried forward ({reason}); graded against the reference"),
    "bad_order": N_("`order` must be 'any' or 'book', got {order!r}"),
    "not_a_target": "{message}",
    "value_ok": pN_("a value", "correct"),
    "value_ok_equivalent": N_("correct: {why}"),
    "value_wrong": N_("wrong: expected {expected}, got {got} (largest difference {err} in {where})"),
    "value_entry": N_("{got} ≠ {expected}"),
    "value_scaled": N_("your answer is the expected one multiplied by {c}"),
    "value_signs": N_("the sign of {where}"),
    "value_exchanged": N_("{a} and {b} are exchanged"),
    "value_rows_exchanged": N_("rows {a} and {b} are exchanged"),
    "value_cols_exchanged": N_("columns {a} and {b} are exchanged"),
    "p_negated": N_("correct: −p describes the same orientation as p (both are valid Euler parameters)"),
    "angles_alternative": N_("correct: the other triple of z-x-z angles that gives the same A (ψ ± π, −θ, φ ± π)"),
    "orthogonal_fail": N_("A is not orthogonal: the largest entry of AᵀA − I is {err}"),
    "det_fail": N_("det A = {det}: a rotation matrix has det A = +1"),
    "norm_fail": N_("pᵀp = {norm}: Euler parameters satisfy pᵀp = 1"),
    "entry": N_("entry {where}"),
    "the_value": N_("the value"),
    "row_order_hint": N_("every row is right for some order of Φ (or some constant factor), but not in the book's "
                         "order: pass your own Φ as phi=... so that the rows are matched to it, or use order='any'"),
    "row_order_msg": N_("the rows are right but not in the book's order"),
}


_OWNERS = ("catalogue", "expected", "numbers", "newton")
"""The modules that register templates of their own (:func:`add_texts`)."""


def _register_all():
    """Load every module that registers templates: ``kinbook.grading`` loads its modules when first used, and a
    sentence of one module may be made in another (the catalogue's ``d.…`` details in the mistakes)."""
    for name in _OWNERS:
        importlib.import_module(f"{__package__}.{name}")


def add_texts(table):
    """Register more templates: ``{key: N_("…")}`` (or ``Np_``, ``pN_``), their translations in the catalogue
    (tests/test_i18n.py fails on a marked message the Spanish catalogue lacks)."""
    for key, value in table.items():
        if key in _TEXT:
            raise KeyError(f"feedback template {key!r} defined twice")
        if not isinstance(value, (str, Plural, Contextual)):
            raise TypeError(f"feedback template {key!r} must be a marked message (N_, Np_, pN_), got {value!r}")
        _TEXT[key] = value
