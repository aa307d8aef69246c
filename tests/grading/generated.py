"""Typical wrong answers generated from kinbook's reference, for every graded part of every exercise notebook
(ex01–ex12, read the way the grader reads them: :func:`kinbook.classroom.variant.references`) and every try-it
(tests/grading/tryits.py's targets).

Nothing here is typed by hand: the right answer is the library's (the target's symbolic Φ and its sympy
derivatives, the part's expected value), and each wrong answer is made from it the way a student gets it wrong —
a term's sign, a dropped term, a dropped row, rows in another order, a transposed matrix, φ̇ for φ̇², ν or γ
negated or forgotten or multiplied by 2 or by a length of the joint, the value in degrees, twice the value, an
entry negated, two entries or rows exchanged, the catalogue's structural
mistakes of the constraint (:func:`kinbook.grading.mistakes.structural`: exchanged points or bodies, Aᵀ for A,
A omitted, a local coordinate's sign, degrees, the book's misprints) carried through the derivation, and the
mistakes an :class:`~kinbook.grading.expected.Expected` carries. Each comes with the code it should get
(None: any name but the generic "wrong value" would do; the test only counts the generic ones).

tests/grading/test_tryits.py counts how many of them get only "wrong value".
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import numpy as np
import sympy as sp

from kinbook.grading import CHECKERS
from kinbook.grading import mistakes as M
from kinbook.grading.diagnose import term_variants
from kinbook.grading.expected import DEG, Expected
from kinbook.grading.target import target_for

EXERCISES = Path(__file__).resolve().parents[2] / "exercises"
PER_PART = 10
"""At most this many wrong answers per part (the first of each kind, then round-robin over the constraints)."""


@dataclass
class Part:
    id: str
    check: str
    target: object  # a mechanism or constraint (phi, jacobian, nu, gamma) or the expected value
    options: dict = field(default_factory=dict)
    angles: bool = False  # the value is (or holds) angles: its degrees are a typical mistake

    @property
    def checker(self):
        return CHECKERS[self.check]


# ================================================================================================ the parts
@lru_cache(maxsize=None)
def exercise_parts():
    from kinbook.classroom.variant import references

    out = []
    for path in sorted(EXERCISES.glob("ex*.ipynb")):
        for p in references(path):
            target = p.target if p.target is not None else p.expected
            angles = bool(p.options.get("angles")) or p.check in ("rotation", "euler_parameters")
            options = {k: v for k, v in p.options.items() if k != "phi"}
            out.append(Part(f"{path.stem[:4]}/{p.name}", p.check, target, options, angles))
    return out


def tryit_parts(tryits):
    """The try-its as parts: a chapter try-it with the notebook's target (its lookalikes included) and options
    (``reveal=False``)."""
    names = {c.function_name[len("check_"):]: k for k, c in CHECKERS.items() if k != "iterates"}
    out, seen = [], set()
    for t in tryits:
        key = getattr(t.checker, "function_name", getattr(t.checker, "__name__", ""))[len("check_"):]
        if key not in names or t.id in seen:  # the Newton iteration has its own test
            continue
        seen.add(t.id)
        angles = "degrees" in {code for _, code in t.wrong}
        item = getattr(t, "item", None)
        if item is None:
            out.append(Part(t.id, names[key], t.target(), dict(t.options), angles))
            continue
        target, options = item.target(**item.data), dict(item.options)
        if "reveal" in options or names[key] in ("value", "rotation", "euler_parameters"):
            target, options = item._with_lookalikes(target, item.data), dict(options, reveal=False)
        out.append(Part(t.id, names[key], target, options, angles))
    return out


# ================================================================================================ symbolic
def _symbolic(target_obj):
    target = target_for(target_obj)
    mech = target.mech
    rows = [sp.sympify(e) for e in target.symbolic_phi()]
    cols = [list(mech.q)[k] for k in target.cols]
    return target, mech, rows, cols


def _jacobian(rows, cols):
    return sp.Matrix(rows).jacobian(cols)


def _nu(mech, rows):
    return [-sp.diff(e, mech.t) for e in rows]


def _gamma(mech, rows):
    q, qd, t = list(mech.q), list(mech.qd), mech.t

    def D(e):
        return sum(sp.diff(e, x) * v for x, v in zip(q, qd) if x in e.free_symbols) + sp.diff(e, t)

    return [sp.expand(-D(D(e))) for e in rows]


def _unsquare(mech, e):
    """φ̇ for φ̇² (every squared velocity left unsquared)."""
    return e.subs({v**2: v for v in mech.qd})


def _flip_term(rows, kind):
    """The first row with two or more terms, with its first term's sign flipped ("sign_flip"); None when no
    row has two terms."""
    for k, e in enumerate(rows):
        for code, wrong, _term in term_variants(e):
            if code == kind:
                out = list(rows)
                out[k] = wrong
                return out
    return None


def _at_assembled(obj, exprs):
    """Values (N, entries) of expressions in q, q̇ and t at the assembled samples of a mechanism or
    constraint (a matrix flattened row by row)."""
    t = target_for(obj)
    mech = t.mech
    s = t.samples("assembled")
    f = sp.lambdify(list(mech.q) + list(mech.qd) + [mech.t], list(sp.Matrix(exprs)), "numpy")
    return np.array([np.asarray(f(*s.Q[i], *s.QD[i], s.T[i]), float) for i in range(s.N)])


def _vanishes(obj, exprs):
    """Whether Φ rows vanish wherever the mechanism or constraint ``obj`` is assembled: then they are an
    equivalent formulation (the bodies of a translational joint exchanged, a row negated, a term that the
    other constraints make zero), not a mistake."""
    return bool(np.all(np.abs(_at_assembled(obj, exprs)) <= 1e-8))


def _variants(target, c):
    """The catalogue's structural variants of c that are wrong (do not vanish where c holds): the first of
    each code."""
    seen, out = set(), []
    for v in M.structural(target_for(c), c):
        if v.code in seen or _vanishes(c, v.exprs):
            continue
        seen.add(v.code)
        out.append(v)
    return out


def _term_mistakes(c, rows):
    """A term's sign flipped and a term dropped in c's rows, when that is wrong (not an equivalent form)."""
    out = []
    for kind in ("sign_flip", "missing_term"):
        for k, e in enumerate(rows):
            made = next((w for code, w, _ in term_variants(e) if code == kind and
                         not _vanishes(c, rows[:k] + [w] + rows[k + 1:])), None)
            if made is not None:
                out.append((rows[:k] + [made] + rows[k + 1:], kind))
                break
    return out


def _per_constraint(target, make):
    """Wrong answers of a whole mechanism: each constraint's own mistakes in place of its rows, round-robin over
    the constraints (so every constraint contributes before any gives a second one)."""
    mech = target.mech
    queues = []
    for c in target.constraints:
        block = target.block(c)
        made = []
        for v in _variants(target, c):
            made.append((block, v.exprs, v.code))
        rows = [target.symbolic_phi()[j] for j in block]
        made += [(block, exprs, kind) for exprs, kind in _term_mistakes(c, rows)]
        queues.append(made)
    out = []
    while any(queues) and len(out) < PER_PART:
        for q in queues:
            if q and len(out) < PER_PART:
                block, exprs, code = q.pop(0)
                full = list(target.symbolic_phi())
                for j, e in zip(block, exprs):
                    full[j] = e
                if _vanishes(mech, full):
                    continue
                answer = make(mech, full)
                if answer is not None:
                    out.append((answer, code))
    return out


# ================================================================================================ wrong answers
def wrong_answers(part):
    """[(answer, expected code or None)] for one part."""
    if part.check in ("phi", "jacobian", "nu", "gamma"):
        return _wrong_symbolic(part)[:PER_PART]
    return _wrong_numbers(part)[:PER_PART]


def _wrong_symbolic(part):
    target, mech, rows, cols = _symbolic(part.target)
    single = target.constraint is not None
    q = part.check
    out = []

    def derive(exprs):
        if q == "phi":
            return list(exprs)
        if q == "jacobian":
            return _jacobian(exprs, cols)
        if q == "nu":
            return _nu(mech, exprs)
        return _gamma(mech, exprs)

    ref = derive(rows)
    # the catalogue's structural mistakes carried through (a single constraint), or one per constraint
    if single:
        for v in _variants(target, target.constraint):
            out.append((derive(v.exprs), v.code))
        if q == "jacobian":
            out += [(derive(e), kind) for e, kind in _term_mistakes(target.constraint, rows)]
    else:
        out += _per_constraint(target, lambda mech, full: derive(full))
    if q == "phi":
        if single:
            out[1:1] = _term_mistakes(target.constraint, rows)
        if len(rows) > 1:
            out.append((rows[:-1], "missing_row"))
            if part.options.get("order") == "book":
                out.append(([rows[1], rows[0]] + rows[2:], "row_order"))
    elif q == "jacobian":
        J = sp.Matrix(ref)
        out.insert(0, (J.T, "transposed"))
        nz = [(i, k) for i in range(J.rows) for k in range(J.cols) if J[i, k] != 0 and not J[i, k].is_number]
        if nz:
            Jf = J.copy()
            Jf[nz[0]] = -Jf[nz[0]]
            out.insert(1, (Jf, "sign_flip"))
        # ∂(A s')/∂(angle) dropped: the columns of the angles (planar φ, spatial p) zeroed
        ang = [k for k, x in enumerate(cols) if x.name.startswith(("phi", "e0", "e1", "e2", "e3"))]
        Jc = J.copy()
        for k in ang:
            for i in range(J.rows):
                if any(s in J[i, k].free_symbols for s in mech.q):
                    Jc[i, k] = 0
        if Jc != J:
            out.insert(2, (Jc, "missing_chain_rule"))
    elif q == "nu":
        if any(e != 0 for e in ref):
            out.insert(0, ([-e for e in ref], "nu_sign"))
            out.insert(1, ([sp.Integer(0)] * len(ref), "nu_missing"))
    else:
        if any(e != 0 for e in ref):
            out.insert(0, ([-e for e in ref], "gamma_sign"))
            un = [_unsquare(mech, e) for e in ref]
            if un != ref:
                out.insert(1, (un, "missing_square"))
            flipped = _flip_term(ref, "sign_flip")
            if flipped is not None:
                out.insert(2, (flipped, "sign_flip"))
            out.append(([2 * e for e in ref], "scaled"))
            if single:  # multiplied by a link length of the joint's geometry (a crank's O–A …)
                out += [([f * e for e in ref], "scaled") for f, _ in M.length_factors(target.constraint)[:1]]
    # drop answers equal to the reference (a variant that does not change this quantity)
    R = _at_assembled(part.target, ref)
    keep = []
    for answer, code in out:
        if sp.Matrix(answer).shape == sp.Matrix(ref).shape and np.allclose(_at_assembled(part.target, answer), R,
                                                                           rtol=1e-9, atol=1e-9):
            continue
        keep.append((answer, code))
    return keep


def _wrong_numbers(part):
    exp = part.target
    value = np.asarray(exp.value if isinstance(exp, Expected) else exp, float)
    out = []
    if isinstance(exp, Expected):
        out += [(np.asarray(v, float), code) for code, v, _, _ in exp.variants]
    if np.any(np.abs(value) > 1e-9) and part.check != "euler_parameters":  # −p is p's orientation
        out.append((-value, "sign_flip"))
        out.append((2 * value, "scaled"))
    if part.angles:
        out.append((value * DEG, "degrees"))
    if value.ndim == 2 and value.shape[0] == value.shape[1] and not np.allclose(value, value.T):
        out.append((value.T, "transposed"))
    if value.ndim == 2 and value.shape[0] != value.shape[1]:
        out.append((value.T, "transposed"))
    if value.size > 1:
        flat = value.ravel()
        k = int(np.argmax(np.abs(flat)))
        one = flat.copy()
        one[k] = -one[k]
        out.append((one.reshape(value.shape), "sign_flip"))
        swapped = value.copy()
        if value.shape[0] > 1 and not np.allclose(swapped[0], swapped[1]):
            swapped[[0, 1]] = swapped[[1, 0]]
            out.append((swapped, "swapped_entries"))
    keep = []
    for answer, code in out:
        if answer.shape == value.shape and np.allclose(answer, value, rtol=1e-3, atol=1e-9):
            continue
        keep.append((answer, code))
    return keep
