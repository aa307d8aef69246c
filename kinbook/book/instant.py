"""Instant checks for the static book: everything a try-it's check needs except the student's answer, as data
a page can use without Python.

For every try-it, at build time: the reference evaluated at the checker's own sampling points (and at a few
witness points), the factor and tolerance rule, the other right answers, and the catalogued mistakes — each as
values at the same points, with its code, title and hint in English and Spanish. The page's script
(web/instant/kinbook-instant.js) reads the answer with kinbook's reader grammar (:func:`grammar`, taken from
:mod:`kinbook.core.reader` here, never retyped), evaluates it at the points and applies the same rule; what it
cannot decide (an equivalent formulation of a row, a Newton iteration) it says so and links to the live
notebook. The exercise notebooks stay graded by Python only: the page's check is formative.

Each name of :mod:`kinbook.grading` used here is called in one place below (the checker table and its
quantities, the targets' samples and references, the witness draw, the tolerances, the catalogue's texts), so a
change of grading is met at once. The page's script mirrors these rules of the Python checker, which
tests/web/test_instant.py holds together over the checker corpora (the page never passes what Python refuses):
the constant-multiple match of Φ rows (``equivalence.scale_match``), an angle row turned by whole turns
(``equivalence.turned_multiple``, the spec's ``turns``), Φ_q rows up to ±1 and ν, γ rows with factor 1 in
the book's order, the transposed Φ_q, the witness tolerances, the numeric checkers' tolerance and named variants,
and the Newton iteration; the rounding rule of constants (:mod:`kinbook.grading.rounding`: the spec's
``rounding``), the book's 2ĖĠᵀa Φ_q rows, and the equivalent Φ rows it can reduce to a reference row (√E − c, a
regular constant combination of a joint's rows, a factor proved nonzero over the whole domain by interval
arithmetic — or one seen to change sign there: a vanishing factor, as :mod:`kinbook.grading.factors` finds it).
What needs the checker's symbolic analysis (another formulation: a cross product's other rows, a factor that
touches zero without changing sign; combinations of Φ_q rows that change with q; ``phi=``/``at=``) the page
leaves to Python and says so. Every try-it
also carries its mutation run (:func:`tryit_mutants`: the mistakes :mod:`kinbook.book.tryits.mutations` makes of
it on the notebook's data), each as values at the page's points with the code Python names it by.
"""

from __future__ import annotations

import hashlib
import inspect
import json
import os
import platform
import shutil
import sys
from pathlib import Path

import mpmath
import numpy as np
import sympy as sp

from ..core.bounds import DEFAULT_LIMITS
from ..core.reader import ALIASES, CONSTANTS, FUNCTIONS
from ..errors import KinbookError
from ..grading import CHECKERS, explain, rounding, sample, witness
from ..grading.equivalence import RTOL, scale_match, zero_tol
from ..grading.expected import Expected
from ..grading.misprints import book_A_of_p
from ..grading.newton import check_iterates
from ..grading.read import read
from ..grading.target import target_for
from ..i18n import LANGUAGES, N_, Message, translate
from ..spatial.rotations import p_from_A
from .tryits import TRY_ITS, get
from .tryits import mutations as MT

__all__ = ["grammar", "spec", "tryit_spec", "page", "page_text", "cache_key", "write", "ui_texts", "tryit_mutants", "UI"]

N_WITNESS = 4
WITNESS_SEED = 35_2026
"""Witness points of the page (a fixed seed of its own, not the checker's): a row made to agree with the
reference at the checker's samples only fails there, as it fails at Python's own witness points."""

UI = {
    "check": N_("Check"),
    "placeholder_rows": N_("one row per line, e.g. x1 - x2 + cos(phi2)"),
    "placeholder_value": N_("a number, or a list such as [0.5, -1.2]; pi, sqrt(2), cos(pi/3) work too"),
    "correct": N_("Correct."),
    "wrong": N_("Not right yet."),
    "refused": N_("The answer cannot be read"),
    "undecided": N_("This page cannot decide this answer"),
    "python": N_("check it with Python (the live notebook)"),
    "read_as": N_("Read as:"),
    "mistake": N_("Mistake"),
    "hint": N_("Hint"),
    "row_wrong": N_("row {k} is not one of the rows asked for"),
    "row_only": N_("row {k} agrees at the checker's points only"),
    "rows_count": N_("{got} rows given, {want} expected"),
    "shape": N_("{got} entries given, {want} expected"),
    "entries_off": N_("{n} of {total} entries are off"),
    "scaled_row": N_("row {k} is {c} times the right row: a factor of the derivative is missing"),
    "equivalent": N_("row {k} vanishes where the mechanism is assembled but is not written as the reference's row: "
                     "it may be an equivalent formulation"),
    "not_typed": N_("a Newton–Raphson iteration is checked step by step by Python"),
    "syntax": N_("not a valid expression"),
    "unknown_name": N_("unknown name '{name}'"),
    "unknown_function": N_("unknown function '{name}'"),
    "not_allowed": N_("'{what}' is not allowed"),
    "implicit": N_("a product needs its * (2*t, not 2t)"),
    "arguments": N_("{name}() takes {want} argument(s), got {got}"),
    "not_finite": N_("the answer is not finite there (a division by zero?)"),
    "too_large": N_("the answer is too large for the page"),
    "exponent": N_("an exponent is too large (at most {limit})"),
    "language": N_("Español"),
    "formative": N_("Checked in your browser; the exercises are graded by Python."),
}
"""The page's own texts (marked: their Spanish is in the package's catalogue)."""


def ui_texts():
    """:data:`UI` in every language: {key: {lang: text}} (fields in braces, filled by the page)."""
    return {k: {lang: translate(v, lang) for lang in LANGUAGES} for k, v in UI.items()}


def _both(message):
    """A message (a Message or a plain text) in every language."""
    if message is None:
        return None
    if isinstance(message, str):
        return {lang: message for lang in LANGUAGES}
    return {lang: message.render(lang) for lang in LANGUAGES}


def grammar():
    """What a student may type, from kinbook's one reader: the functions (with their numbers of arguments), the
    other spellings, the constants and the bounds."""
    limits = DEFAULT_LIMITS
    return {"functions": {name: list(counts) for name, (_, counts) in FUNCTIONS.items()},
            "aliases": dict(ALIASES),
            "constants": {name: float(value) for name, value in CONSTANTS.items()},
            "limits": {"length": limits.length, "nodes": limits.nodes, "depth": limits.depth,
                       "digits": limits.digits, "exponent": limits.exponent, "magnitude": limits.magnitude}}


def _checker_name(checker):
    """The name of a try-it's checker (a :class:`kinbook.grading.item.Checker` of the one table, or its function)."""
    name = getattr(checker, "name", None)
    if name in CHECKERS:
        return name
    for name, c in CHECKERS.items():
        if c is checker or c.function is checker:
            return name
    raise ValueError(f"no instant check for the checker {checker!r}")


def _mistake(code, values, detail=None, context=(), erratum=None):
    """A catalogued mistake as the page shows it: its code, title and hint in every language, the detail of
    this occurrence, and its values at the spec's points."""
    entry = {"code": code, "values": values, "detail": _both(detail), "erratum": erratum}
    entry["title"] = {lang: explain(code, lang, tuple(context))[0] for lang in LANGUAGES}
    entry["hint"] = {lang: explain(code, lang, tuple(context))[1] for lang in LANGUAGES}
    return entry


def _arr(a):
    return np.asarray(a, float).tolist()


# ------------------------------------------------------------------------------------------------- numbers
def _value_spec(name, expected, options, lookalikes=()):
    """check_value, check_rotation, check_euler_parameters: the expected value, the tolerance rule (the
    checker's own defaults, read from its signature), the other right answers, the named wrong ones."""
    defaults = {k: p.default for k, p in inspect.signature(CHECKERS[name].function).parameters.items()
                if p.default is not inspect.Parameter.empty}
    exp = expected if isinstance(expected, Expected) else Expected(np.asarray(expected, float))
    e = np.asarray(exp.value, float)
    context = tuple(exp.context) or (exp.kind,)
    periodic = sorted(set(int(i) for i in exp.periodic) | set(int(i) for i in options.get("periodic", ())))
    mistakes = [_mistake(code, _arr(np.asarray(v, float).reshape(e.shape) if np.size(v) == e.size else v),
                         detail, context, erratum)
                for code, v, detail, erratum in list(lookalikes) + list(exp.variants)]
    if name == "rotation":  # the checker adds the book's A(p) misprint and ½A of any rotation matrix
        mistakes += _rotation_mistakes(e, context)
    equivalents = [{"values": _arr(v), "why": _both(why)} for v, why in exp.equivalents]
    if name == "euler_parameters":
        equivalents.append({"values": _arr(-e), "why": None})
    return {"kind": "value", "checker": name, "shape": list(e.shape), "value": _arr(e),
            "rule": {"rtol": float(options.get("rtol", defaults["rtol"])),
                     "atol": float(options.get("atol", defaults["atol"])), "periodic": periodic,
                     "sizes_only": name == "euler_parameters"},
            "equivalents": equivalents, "mistakes": mistakes}


def _rotation_mistakes(e, context):
    try:
        p = np.asarray(p_from_A(e), float)
    except (KinbookError, ValueError, np.linalg.LinAlgError):
        return []
    return [_mistake("factor_2_missing", _arr(0.5 * e), None, context, "14.3-A-of-p"),
            _mistake("book_misprint", _arr(book_A_of_p(p)), None, context, "14.3-A-of-p")]


# ------------------------------------------------------------------------------------------------- rows
def _quantity(name):
    """The quantity a checker grades (:mod:`kinbook.grading.quantities`), or None for a numeric checker."""
    return CHECKERS[name].quantity if name in CHECKERS else None


def _factor_rule(q):
    """The page's name for a quantity's factor rule: Φ rows up to any constant, Φ_q rows up to ±1, ν and γ none."""
    return "any" if not q.derived else "sign" if q.per_coordinate else "one"


def _points(s):
    return {"q": _arr(s.Q), "qd": _arr(s.QD), "t": _arr(s.T)}


def _names(t):
    """Every spelling a student may use for a coordinate, a velocity or t: name → ["q" | "qd" | "t", index]."""
    mech = t.mech
    index = {s: ("q", k) for k, s in enumerate(mech.q)} | {s: ("qd", k) for k, s in enumerate(mech.qd)}
    out = {}
    for name, symbol in t.symbols().items():
        out[name] = list(index.get(symbol, ("t", 0)))
    return out


def _witness_points(t, which):
    """A few points of the page's own (seeded apart from the checker's): generic configurations for Φ — and the
    checker's few over the whole domain (angles beyond ±π, t up to 30: where ``atan2(sin φ, cos φ)`` is not φ) —,
    assembled ones (consistent velocities) for Φ_q, ν, γ — where a row accepted at the samples must agree as well."""
    if which == "generic":
        rng = np.random.default_rng(WITNESS_SEED)
        n = t.n
        Q = rng.uniform(-3.0, 3.0, (N_WITNESS, n))
        if t.kind == "planar":
            Q[:, 2::3] = rng.uniform(-np.pi, np.pi, (N_WITNESS, n // 3))
        else:
            p = rng.normal(size=(N_WITNESS, n // 7, 4))
            Q.reshape(N_WITNESS, n // 7, 7)[:, :, 3:] = p / np.linalg.norm(p, axis=2, keepdims=True)
        wide = sample.generic_wide(t)
        return sample.Samples(np.vstack([Q, wide.Q]), np.vstack([rng.normal(0.0, 2.0, Q.shape), wide.QD]),
                              np.concatenate([rng.uniform(0.0, 1.0, N_WITNESS), wide.T]))
    # the checker's witness draw, seeded by a fixed text of the page's (not by an answer)
    return witness.samples(t, read([f"t*{WITNESS_SEED}"], t, "nu"))


def _rows_spec(name, target, options, lookalikes=(), wrong_forms=()):
    """check_phi / check_jacobian / check_nu / check_gamma: the points, the reference there, the rule."""
    t = target_for(target)
    q = _quantity(name)
    quantity = q.name
    which = "assembled" if q.derived else "generic"
    s = t.samples(which)
    if q.derived and not s.on_manifold:
        which = "generic"
    w = _witness_points(t, which) if s.N else None
    rtol, refuse = _options(options, RTOL, t.n)
    spec = {"kind": "rows", "checker": name, "quantity": quantity, "names": _names(t), "m": t.m, "n": t.n,
            "cols": [int(c) for c in t.cols], "labels": [t.label(k) for k in range(t.m)],
            "row_blocks": [[int(k) for k in t.block(c)] for c in t.constraints],
            "points": {"samples": _points(s)},
            "reference": {"samples": _ref(t.reference(which), quantity)},
            "rule": {"rtol": rtol, "zero_tol": zero_tol(rtol),
                     "factor": _factor_rule(q),
                     "order": options.get("order") or ("book" if q.derived else "any"),
                     "wrap": {str(k): p for k, p in t.wrap.items()},
                     "turns": {str(k): p for k, p in t.turns.items()},
                     "decides": not ({"phi", "at"} & set(options)), "refuse": refuse},
            "mistakes": []}
    spec["spatial"] = t.kind == "spatial"
    spec["euler"] = [k for k in range(t.n) if t.kind == "spatial" and k % 7 >= 3]  # each in [−1, 1]
    spec["diagnoses"] = {code: _mistake(code, None) for code in DIAGNOSES}
    spec["rounding"] = _rounding(t, quantity)
    if w is not None:
        spec["points"]["witness"] = _points(w)
        spec["reference"]["witness"] = _ref(t.evaluate(w), quantity)
    if q.per_coordinate:  # rows that hold anyway (a spatial joint's normalization rows): free in a combination
        spec["reference"]["free"] = _arr(t.reference(which)["free_q"])
    if not q.derived:  # where each constraint alone holds: a row that vanishes there may be an equivalent
        spec["blocks"] = []
        for c in t.constraints:
            own = t.own_target(c).samples("assembled")
            if own.on_manifold:
                spec["blocks"].append({"rows": t.block(c), "points": _points(own)})
        spec["blocks_complete"] = len(spec["blocks"]) == len(t.constraints)
    for rows, code, detail, erratum in wrong_forms:
        S = t.tape(list(rows))(s.Q, s.QD, s.T)["value"]
        spec["mistakes"].append(_mistake(code, _arr(S), detail, (), erratum) | {"rows": True})
    for other, detail in lookalikes:
        ref = _ref(target_for(other).evaluate(s), quantity)
        spec["mistakes"].append(_mistake("wrong_data", ref, detail) | {"rows": True})
    return spec


DIAGNOSES = ("vanishing_factor", "eg_jacobian", "dependent_row", "not_rounded")
"""Mistakes the page's own rules name (a factor with a real zero, the book's 2ĖĠᵀa rows of Φ_q, rows that combine
into fewer, a constant rounded wrong): their texts, without values."""


def _rounding(t, quantity):
    """The rounding rule's numbers (:mod:`kinbook.grading.rounding`): the exercise's exact constants (value, as a
    student types it), the integers among them, and the numbers written in the rows themselves (data, exactly)."""


    constants, integers = [], []
    for value, c in rounding.exact_constants(t, quantity).items():
        if isinstance(value, tuple):
            integers.append(int(value[1]))
        elif value > 0:
            constants.append([float(value), repr(float(c)) if c.is_Float else str(c)])
    data = sorted({abs(float(x)) for row in t.symbolic_phi() for x in row.atoms(sp.Number)})
    # sorted: exact_constants comes from a set of sympy nodes, whose order changes with PYTHONHASHSEED
    return {"constants": sorted(constants), "integers": sorted(set(integers)), "data": data,
            "min_digits": rounding.MIN_DIGITS, "near": rounding.NEAR}


def _options(options, default_rtol, n=None):
    """(rtol, refused): the checker refuses (a failed, "malformed" result) an rtol outside (0, 1), an order other
    than "any" or "book", a ``symbolic`` that is not True or False and an ``at`` that is not {"q": n numbers,
    "qd": n numbers, "t": a number} (some of them) — the page refuses them too."""
    at = options.get("at")
    if at is not None:
        if not isinstance(at, dict) or set(at) - {"q", "qd", "t"}:
            return default_rtol, True
        for key, shape in (("q", (n,)), ("qd", (n,)), ("t", ())):
            try:
                v = np.asarray(at.get(key, np.zeros(shape)), dtype=float)
            except (TypeError, ValueError):
                return default_rtol, True
            if v.shape != shape or not np.all(np.isfinite(v)):
                return default_rtol, True
    rtol = options.get("rtol")
    good = rtol is None or (isinstance(rtol, (int, float, np.integer, np.floating)) and not isinstance(rtol, bool)
                            and np.isfinite(float(rtol)) and 0 < float(rtol) < 1)
    good = good and options.get("order", "any") in ("any", "book", None)
    good = good and isinstance(options.get("symbolic", False), (bool, np.bool_))
    return (float(rtol) if good and rtol is not None else default_rtol), not good


def _ref(values, quantity):
    R = np.asarray(values[quantity], float)
    return _arr(R)


# ------------------------------------------------------------------------------------------------- Newton
def _iterates_spec(problem, options):
    """check_iterates: the mechanism's Φ and Φ_q as text (the page evaluates them with the reader's grammar at the
    student's own iterates, as the checker does), the time, the guess, the solution it leads to, the tolerances."""
    defaults = {k: p.default for k, p in inspect.signature(check_iterates).parameters.items()
                if p.default is not inspect.Parameter.empty}
    mech = problem.mechanism
    t = target_for(mech)
    phi = t.symbolic_phi()
    jac = phi.jacobian(list(mech.q))
    return {"kind": "iterates", "n": int(mech.n), "names": _names(t), "t": float(problem.t),
            "phi": [str(e) for e in phi], "phi_q": [[str(e) for e in jac.row(k)] for k in range(jac.rows)],
            "guess": _arr(problem.guess), "solution": _arr(problem.solution()),
            "angles": [k for k, c in enumerate(mech.coordinate_names()) if c.startswith("phi")],
            "rule": {"tol": float(options.get("tol", defaults["tol"])),
                     "rtol": float(options.get("rtol", defaults["rtol"])), "decides": True},
            "mistakes": [_mistake(code, None) for code in ("newton_step", "not_converged", "assembly_mode",
                                                            "wrong_data")]}


# ------------------------------------------------------------------------------------------------- entry points
def spec(checker, target, options=None, *, lookalikes=(), wrong_forms=()):
    """The instant check of one answer's checker and target (a try-it's, or any corpus case's).

    Parameters
    ----------
    checker : callable
        A checker of :data:`kinbook.grading.CHECKERS` or :func:`kinbook.grading.newton.check_iterates`.
    target
        What the checker is called with: a mechanism or constraint, an expected value, a Newton problem.
    options : dict, optional
        The checker's keyword arguments.
    lookalikes : list
        Numeric: (value, detail) pairs — numbers the notebook prints nearby; symbolic: (mechanism or constraint,
        detail) — other joints the answer may be right for. Named ``wrong_data``.
    wrong_forms : list
        Symbolic: (rows, code, detail, erratum) — wrong formulations, named by their code.

    Returns
    -------
    dict
        JSON-ready: ``kind`` ("rows", "value" or "iterates"), the points, the reference there, the ``rule`` and
        the ``mistakes``.
    """
    options = dict(options or {})
    name = _checker_name(checker)
    if name == "iterates":
        return _iterates_spec(target, options)
    if _quantity(name) is not None:
        return _rows_spec(name, target, options, lookalikes, wrong_forms)
    named = [("wrong_data", np.asarray(v, float), detail, None) for v, detail in lookalikes]
    return _value_spec(name, target, options, named)


_MUTATION_RUNS = {}


def tryit_mutants(item):
    """The mutation run of a try-it on the notebook's data, as ``kinbook validate --mutations --try-its`` makes it
    (:func:`kinbook.book.tryits.mutations.mutation_tally`, its first data set): ``[(mutant, answer, result)]`` —
    the mutant, the answer a student making its mistake hands in, and the try-it's own check of it. Cached."""
    if item.id in _MUTATION_RUNS:
        return _MUTATION_RUNS[item.id]

    data = dict(item.data)
    quantity = item.checker.quantity
    found = list(MT.item_mutants(item, data))
    if quantity is None and len(found) < 3:  # a worked answer with few operators: its value's slips as well
        found += MT.value_slips(item, data)
    out = []
    for m in found:
        try:
            answer = MT.answer_of(item, m, data)
        except Exception:  # noqa: BLE001 — a code mutant that fails on these data is no answer here
            continue
        out.append((m, answer, item.check(answer, data)))
    _MUTATION_RUNS[item.id] = out
    return out


def _mutant_mistakes(item, spec):
    """The try-it's mutants Python refuses, as catalogued mistakes of the page: their values at the spec's points
    (rows) or as numbers (values), named by the code Python's check names them by (the mutant's own when Python
    names none)."""
    out = []
    for m, answer, result in tryit_mutants(item):
        if result.passed:  # a blind spot: the page must not name what Python passes
            continue
        code = next((c for c in result.mistakes or () if c), None) or m.code
        try:
            values = _mutant_values(item, spec, m, answer)
        except Exception:  # noqa: BLE001 — a mutant that cannot be evaluated at the page's points names nothing
            continue
        if values is None or not np.all(np.isfinite(np.asarray(values, float))):
            continue
        if spec["kind"] == "rows":
            values = _prefix(values, spec)
            out.append(_mistake(code, _short(values), m.operator) | {"rows": True, "points": len(values)})
        else:
            out.append(_mistake(code, _short(values), m.operator))
    return out


MUTANT_POINTS = 6
"""A mutant's rows are stored at the first few of the checker's points only (the page names a mistake by them;
a Φ_q of 14 columns at 16 points for each of 160 mutants was 1.3 MB) — unless one of its rows is, there, a
multiple of a reference row for every row: then the rest of the points are kept, so that no right answer
matches a mutant."""


def _prefix(V, spec):

    V = np.asarray(V, float)
    K = MUTANT_POINTS
    R = np.asarray(spec["reference"]["samples"], float)
    if V.ndim == 3 and R.shape[2] != V.shape[2]:
        R = R[:, :, spec["cols"]] if V.shape[2] == len(spec["cols"]) else None
    if R is None or len(V) <= K:
        return V
    same = all(any(scale_match(V[:K, i], R[:K, j], 1e-4) is not None for j in range(R.shape[1]))
               for i in range(V.shape[1]))
    return V if same else V[:K]


def _short(a):
    """Values to 9 significant digits (a mutant is named to 10⁻⁶): the page's JSON stays small."""
    return np.vectorize(lambda x: float(f"{x:.9g}"), otypes=[float])(np.asarray(a, float)).tolist()


def _mutant_values(item, spec, m, answer):
    if spec["kind"] == "value":
        v = np.asarray(answer, float)
        return v if v.size == np.size(spec["value"]) else None
    if spec["kind"] != "rows":
        return None


    target = item.target(**dict(item.data))  # held: a target keeps only a weak reference to its mechanism
    t = target_for(target)
    M = sp.Matrix(m.value)
    P = spec["points"]["samples"]
    V = np.asarray(t.tape(list(M))(np.asarray(P["q"]), np.asarray(P["qd"]), np.asarray(P["t"]))["value"], float)
    return V.reshape(len(P["t"]), *M.shape) if M.shape[1] > 1 else V.reshape(len(P["t"]), M.shape[0])


def tryit_spec(item):
    """The instant check of a :class:`~kinbook.book.tryits.TryIt` for the notebook's data, with its mutation
    run's mistakes (:func:`tryit_mutants`)."""
    data = dict(item.data)
    target = item.target(**data)
    looks = list(item.lookalikes(**data)) if item.lookalikes is not None else []
    forms = list(item.wrong_forms(**data)) if item.wrong_forms is not None else []
    out = spec(item.checker, target, item.options, lookalikes=looks, wrong_forms=forms)
    if out["kind"] != "iterates":
        out["mistakes"] += _mutant_mistakes(item, out)
    out["id"] = item.id
    out["answer"] = item.answer
    out["name"] = _both(item.options.get("name")) if isinstance(item.options.get("name"), (str, Message)) else None
    return out


def page(notebook):
    """The JSON of one book page: the grammar, the page's texts and the spec of each of its try-its."""
    get(f"{notebook}/try-1")  # registers the try-its
    items = [item for key, item in TRY_ITS.items() if key.split("/")[0] == notebook]
    return {"version": 1, "languages": list(LANGUAGES), "grammar": grammar(), "ui": ui_texts(),
            "tryits": {item.id: tryit_spec(item) for item in items}}


CPU_SETTINGS = ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES", "NPY_ENABLE_CPU_FEATURES")
"""Environment variables that choose numpy's and OpenBLAS's kernels (make test-cpu sets two): part of the cache key."""


def cache_key(package=None):
    """What a page's JSON is a function of, hashed: every file of the kinbook package (its code, the try-its' data,
    the shipped examples, the translations), the versions of Python, numpy, sympy and mpmath, the machine and the
    CPU kernels chosen (:data:`CPU_SETTINGS`)."""
    package = Path(package) if package is not None else Path(__file__).resolve().parents[1]
    h = hashlib.sha256()
    for path in sorted(p for p in package.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        h.update(path.relative_to(package).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    h.update(json.dumps([sys.version, platform.machine(), np.__version__, sp.__version__, mpmath.__version__]
                        + [os.environ.get(name) for name in CPU_SETTINGS]).encode())
    return h.hexdigest()[:32]


def page_text(notebook, cache=None):
    """The JSON text of one book page (:func:`page`). With ``cache`` (a folder: the checkout's build/cache/instant),
    it is read from ``cache/<key>/<notebook>.json`` when there (:func:`cache_key`), else computed and stored there
    and every other key's folder removed — so that the test run and the book build of one checkout make the pages'
    mutation runs once; a changed source or version is a new key, never a stale page."""
    if cache is None:
        return json.dumps(page(notebook), ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    cache = Path(cache)
    key = cache_key()
    here = cache / key / f"{notebook}.json"
    if here.is_file():
        return here.read_text(encoding="utf-8")
    text = page_text(notebook)
    here.parent.mkdir(parents=True, exist_ok=True)
    for other in cache.iterdir():
        if other.is_dir() and other.name != key:
            shutil.rmtree(other, ignore_errors=True)
    partial = here.with_name(f".{notebook}.{os.getpid()}.json")  # another process may read it meanwhile: whole
    partial.write_text(text, encoding="utf-8")
    os.replace(partial, here)
    return text


def write(folder, cache=None):
    """Write ``<notebook>.json`` (:func:`page_text`, with its ``cache``) for every notebook with try-its into
    ``folder``; returns the notebooks."""
    get("13-1/try-1")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    notebooks = sorted({key.split("/")[0] for key in TRY_ITS})
    for notebook in notebooks:
        (folder / f"{notebook}.json").write_text(page_text(notebook, cache), encoding="utf-8")
    return notebooks


if __name__ == "__main__":  # python -m kinbook.book.instant FOLDER [CACHE] (web/build.py book)
    print("instant checks:", ", ".join(write(*sys.argv[1:3])))
