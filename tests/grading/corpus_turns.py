"""Whole turns (kinbook.grading.equivalence.turned_multiple, kinbook.grading.turns): every row that measures an angle
in the shipped mechanisms and exercises — a fixed body's φ1, each driver's φ_i − f(t), each slot's φ_i − φ_j — and
a length row beside it, written turned by whole turns, by half turns, and through atan2.

The rows are kinbook's own symbolic Φ of the constraint (the library, not a checker). Each expectation is made here
by a second computation with sympy and numpy alone, on placements over the whole domain (coordinates in ±5,
angles in ±20 rad, t in [0, 30]):

* **right** when the answer a places the bodies as the reference row r does: (1) a − c·r is c times a whole number
  of turns at every placement (c = ∂a/∂v ÷ ∂r/∂v for a coordinate v the row is linear in), so a vanishes only where
  r is a whole number of turns; and (2) at placements where r = 0 (solved for v), a turn of the row's angles
  (−3 … 3 each) makes a vanish;
* **whole_turn** when r measures no angle and a − c·r is one nonzero constant whole number of turns (the name);
* otherwise wrong (a half turn, atan2 + 2π that never vanishes, a driver whose atan2 has no zero for large t).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
import sympy as sp

import kinbook

TURN = 2 * np.pi
EXAMPLES = ["ch13_example1", "ch13_example2", "ch13_example3", "ch13_example4", "ch13_planetary", "ch13_rack_pinion",
            "ch13_sliding_pinion", "planetary", "quick_return", "six_bar", "steering"]
EXERCISES = Path(__file__).resolve().parents[2] / "exercises"


@dataclass
class Case:
    id: str
    mech: str
    constraint: str | None
    answer: list
    passed: bool
    names: list  # the lists of mistakes that are true of the answer (one, or two equally true)


def mechanism(name):
    if name.startswith("ex"):
        from kinbook.classroom.variant import references

        path = next(EXERCISES.glob(f"{name}*.ipynb"))
        return next(p.target for p in references(path) if p.name == "whole_phi")
    return kinbook.examples.load(name)


def _mechanisms():
    exercises = sorted({p.name[:4] for p in EXERCISES.glob("ex*.ipynb")})
    out = []
    for name in EXAMPLES + exercises:
        try:
            m = mechanism(name)
        except StopIteration:  # an exercise with no whole Φ
            continue
        if m.kind == "planar":
            out.append((name, m))
    return out


# ------------------------------------------------------------------------------------------ second computation
def _grid(names, seed=11, n=600):
    rng = np.random.default_rng(seed)
    v = {}
    for s in names:
        v[s] = rng.uniform(0, 30, n) if s == "t" else rng.uniform(-20, 20, n) if s.startswith("phi") else \
            rng.uniform(-5, 5, n)
    return v


def _f(expr, names):
    f = sp.lambdify([sp.Symbol(s) for s in names], expr, "numpy")
    return lambda v: np.broadcast_to(np.asarray(f(*[v[s] for s in names]), float), next(iter(v.values())).shape)


def verdict(answer, reference):
    """``(right, turns, whole)`` by sympy and numpy: right as the module's docstring says; ``turns`` the constant
    whole number of turns of a − c·r when it is one (else 0); ``whole`` whether (1) holds."""
    a, r = sp.sympify(answer), sp.sympify(reference)
    names = sorted({str(s) for s in (a.free_symbols | r.free_symbols)} | {"t"})
    linear = [s for s in sorted(r.free_symbols, key=str) if str(s) != "t" and sp.diff(r, s, 2) == 0 and
              sp.diff(r, s) != 0]
    v0 = linear[0]
    v = _grid(names)
    c = float(_f(sp.diff(a, v0), names)(v)[0]) / float(_f(sp.diff(r, v0), names)(v)[0])
    A, R = _f(a, names)(v), _f(r, names)(v)  # noqa: N806
    k = (A - c * R) / (c * TURN)
    whole = bool(np.all(np.abs(k - np.round(k)) < 1e-7))
    constant = whole and bool(np.all(np.round(k) == np.round(k[0])))
    turns = int(np.round(k[0])) if constant else 0
    # (2) where r = 0: solved for v0 (r is linear in it), a turn of the row's angles makes a vanish
    sol = sp.solve(r, v0)[0]
    w = dict(v)
    w[str(v0)] = _f(sol, names)(v)
    angles = sorted({str(s) for s in r.free_symbols | a.free_symbols if str(s).startswith("phi")})
    fa = _f(a, names)
    best = np.full(len(w["t"]), np.inf)
    for m in itertools.product(range(-3, 4), repeat=len(angles)):
        u = dict(w)
        for s, mm in zip(angles, m):
            u[s] = w[s] + TURN * mm
        best = np.minimum(best, np.abs(fa(u)))
    vanishes = bool(np.all(best < 1e-7 * max(1.0, float(np.abs(A).max()))))
    return whole and vanishes, turns, whole


# ------------------------------------------------------------------------------------------ the cases
ANGLE_FORMS = {
    "plus-2pi": "({r}) + 2*pi", "minus-2pi": "({r}) - 2*pi", "plus-4pi": "({r}) + 4*pi",
    "negated-plus-2pi": "-({r}) + 2*pi", "negated-minus-2pi": "-({r}) - 2*pi", "double-turned": "2*(({r}) + 2*pi)",
    "half-turn": "({r}) + pi", "plus-1": "({r}) + 1", "atan2": "atan2(sin({r}), cos({r}))",
    "atan2-plus-2pi": "atan2(sin({r}), cos({r})) + 2*pi", "double-half": "2*({r}) + 2*pi",
}
LENGTH_FORMS = {"plus-2pi": "({r}) + 2*pi", "negated-minus-4pi": "-({r}) - 4*pi", "double-minus-2pi": "2*({r}) - 2*pi",
                "plus-pi": "({r}) + pi"}


def _case(name, c, rows, k, form, text, measure):
    r = str(rows[k])
    answer = [str(x) for x in rows]
    answer[k] = text.format(r=r)
    right, turns, whole = verdict(answer[k], r)
    names = [[]] if right else [["whole_turn"]] if measure != "angle" and turns else [["wrong_value"]]
    if not right and whole and measure == "angle":
        # equal to r up to turns everywhere, though not the same placement (atan2(sin r, cos r) + 2π never
        # vanishes): whether it equals r at the checker's samples depends on where they lie — either name is true
        names.append(["only_at_samples"])
    return Case(f"{name}-{c.name}-{k + 1}-{measure}-{form}", name, c.name, answer, right, names)


def _angle_rows():
    """Each row of every constraint that has a row measuring an angle (not wrapped), in the mechanisms above:
    ``(name, m, c, rows, k, measure, first)``, ``first`` when the row (its joint type and text) is met first."""
    seen = set()
    for name, m in _mechanisms():
        for c in m.constraints:
            measures = c.measures or ()
            if "angle" not in measures or c.wrap:
                continue
            rows = list(m.constraint_phi(c))
            for k, measure in enumerate(measures):
                key = (type(c).__name__, str(rows[k]))
                yield name, m, c, rows, k, measure, key not in seen
                seen.add(key)


@lru_cache(maxsize=None)
def cases():
    """Each form of each angle row (and of a length row of the same constraint) graded with its constraint alone —
    once per distinct row — and, per mechanism, the whole Φ with one of its rows turned."""
    out, wholes = [], {}
    for name, m, c, rows, k, measure, first in _angle_rows():
        forms = ANGLE_FORMS if measure == "angle" else LENGTH_FORMS if measure.startswith("length") else {}
        if first:
            out += [_case(name, c, rows, k, form, text, measure) for form, text in forms.items()]
        form = "plus-2pi"
        if form in forms:  # the same row turned in the whole Φ
            if name not in wholes:
                wholes[name] = [str(x) for x in m.symbolic().Phi]
            one = _case(name, c, rows, k, form, forms[form], measure)
            answer = list(wholes[name])
            answer[c.rows.start + k] = one.answer[k]
            out.append(Case(f"whole-{one.id}", name, None, answer, one.passed, one.names))
    return out


def target(case):
    m = mechanism(case.mech)
    return m if case.constraint is None else m.constraint(case.constraint)


# ------------------------------------------------------------------------------------------ numbers at a configuration
NUMBER_FORMS = {"angle": ("plus-2pi", "minus-2pi", "plus-4pi", "half-turn", "plus-1"),
                "length": ("plus-2pi", "plus-pi")}
"""The forms a number can take (no factor: a number of Φ at a configuration is the row's own value)."""


@dataclass
class NumberCase:
    id: str
    mech: str
    constraint: str
    values: list
    at: dict
    passed: bool
    names: list


@lru_cache(maxsize=None)
def number_cases():
    """Each distinct angle row (and a length row beside it) given as numbers at a configuration drawn over the whole
    domain (angles in ±20 rad; t under 0.5, so that a value stays small enough for 1 and π to be more than the
    numbers' tolerance, 2·10⁻³ of it) — its value turned by whole turns, by half a turn, by 1 — with the
    expectation of :func:`verdict` (the same second computation as the expressions'); the values computed with sympy
    from kinbook's symbolic rows."""
    out = []
    rng = np.random.default_rng(29)
    for name, m, c, rows, k, measure, first in _angle_rows():
        kind = "angle" if measure == "angle" else "length" if measure.startswith("length") else None
        if kind is None or not first:
            continue
        q = [rng.uniform(-20, 20) if str(s).startswith("phi") else rng.uniform(-5, 5) for s in m.q]
        t = float(rng.uniform(0, 0.5))  # a driver's 100t stays under 50: 1 and π off stay beyond 2·10⁻³ of it
        point = dict(zip(m.q, q)) | {m.t: t}
        values = [float(row.subs(point)) for row in rows]
        for form in NUMBER_FORMS[kind]:
            text = (ANGLE_FORMS if kind == "angle" else LENGTH_FORMS)[form].format(r=str(rows[k]))
            right, turns, _ = verdict(text, str(rows[k]))
            answer = list(values)
            answer[k] = float(sp.sympify(text).subs({str(s): v for s, v in point.items()}))
            names = [[]] if right else [["whole_turn"]] if kind == "length" and turns else [["wrong_value"]]
            out.append(NumberCase(f"{name}-{c.name}-{k + 1}-{measure}-{form}", name, c.name, answer,
                                  {"q": q, "t": t}, right, names))
    return out
