"""Zeros far from the samples and answers right only on part of the domain (kinbook.grading.factors, the wide
samples and the witness).

Two classes, each expectation made here by a second computation that does not use kinbook's checker:

* **far zeros** — a row of ch13_example1's Φ multiplied by a factor f: wrong exactly when f has a real zero in the
  configuration space (every coordinate real, t ≥ 0), decided by sympy's ``solveset`` on f alone (the other
  variables of a factor in several fixed at plain values first); named ``vanishing_factor``.
* **whole domain** — a driver or a joint row written so that it agrees with the reference only for angles in
  (−π, π] or for t in [0, 1] (atan2 of the angle, a product of (t − tₖ) over the sampled instants), or right
  everywhere in another form (atan2 of a relative angle: the same placement up to 2π). Wrong when, at some
  placement of the whole domain (t up to 50, angles up to ±20 rad), numpy finds the answer row away from the
  reference row by more than a tolerance and from every placement the same up to turns of 2π; the instants of
  the product are kinbook's seeded samples (the attack needs them), read from ``target.samples``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
import sympy as sp

import kinbook

BASE = ["x1", "y1", "phi1", "x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)",
        "x1 - x4 + 3*cos(phi1) - 1.5*cos(phi4)", "y1 - y4 + 3*sin(phi1) - 1.5*sin(phi4)",
        "x2 - x3 + cos(phi2) + 3*cos(phi3)", "y2 - y3 + sin(phi2) + 3*sin(phi3)",
        "x3 - x4 + 3*cos(phi3) + 1.5*cos(phi4)", "y3 - y4 + 3*sin(phi3) + 1.5*sin(phi4)",
        "phi2 - 100*t - 3*pi/4"]
"""ch13_example1's Φ in the book's order (written out here, not taken from kinbook)."""

# (factor, the row it multiplies): rows whose bodies hold the factor's coordinates, or the driver for t
FACTORS = [
    ("x2 - 100", 3), ("x2 + 100", 4), ("phi2 - 40", 3), ("phi2 + 25", 4), ("y3**2 - 49", 7), ("t - 20", 11),
    ("t - 1000", 11), ("x3 + 50", 9), ("x2**3 - 1000", 3), ("(x2 - 7)**2", 3), ("phi2**2 - 400", 4),
    ("exp(x2) - 10000", 3), ("cos(phi2) - 1", 3), ("x2*x3 - 500", 7), ("x2 - x3 - 80", 7), ("y4 + 30", 10),
    # no real zero in the domain: right
    ("x2**2 + 1", 3), ("2 + sin(phi2)", 3), ("3 + cos(phi3)", 8), ("exp(x2)", 4), ("t + 5", 11),
    ("t**2 + 1", 11), ("phi2**2 + 4", 4), ("y3**2 + x3**2 + 1", 7),
]

_FIXED = {"x1": 0.3, "y1": -0.4, "phi1": 0.5, "x2": 1.3, "y2": 0.7, "phi2": 2.0, "x3": 1.7, "y3": -1.1, "phi3": 0.9,
          "x4": 2.3, "y4": 0.2, "phi4": -0.6, "t": 2.0}


def has_real_zero(factor):
    """sympy alone: does the factor vanish somewhere with every coordinate real and t ≥ 0? A factor in several
    variables is solved for its first (sorted) one, the others fixed at the plain values of ``_FIXED``."""
    f = sp.sympify(factor)
    names = sorted(str(s) for s in f.free_symbols)
    first = sp.Symbol(names[0])
    f = f.subs({sp.Symbol(n): _FIXED[n] for n in names[1:]})
    domain = sp.Interval(0, sp.oo) if names[0] == "t" else sp.S.Reals
    return sp.solveset(f, first, domain) != sp.S.EmptySet


@dataclass
class Case:
    id: str
    check: str
    answer: object
    passed: bool
    mistakes: list
    constraint: str | None = None
    mech: str = "ch13_example1"
    options: dict = field(default_factory=dict)


def _with(k, row):
    rows = list(BASE)
    rows[k] = row
    return rows


@lru_cache(maxsize=None)
def far_zero_cases():
    out = []
    for factor, k in FACTORS:
        zero = has_real_zero(factor)
        out.append(Case(f"far-zero-whole-{factor}", "phi", _with(k, f"({factor})*({BASE[k]})"), not zero,
                        ["vanishing_factor"] if zero else []))
    # the same factors on revolute joint 1 graded alone (rows Φ_4, Φ_5), where their body takes part
    for factor, k in FACTORS:
        if k not in (3, 4) or "3" in factor:
            continue
        zero = has_real_zero(factor)
        rows = [BASE[3], BASE[4]]
        rows[k - 3] = f"({factor})*({rows[k - 3]})"
        out.append(Case(f"far-zero-joint-{factor}", "phi", rows, not zero, ["vanishing_factor"] if zero else [],
                        constraint="1"))
    return out


# ------------------------------------------------------------------------------------------------ whole domain
def _numbers(expr):
    """A row as a numpy function of a dict of arrays (sympy's lambdify on a row this module wrote)."""
    e = sp.sympify(expr)
    names = sorted(str(s) for s in e.free_symbols)
    f = sp.lambdify([sp.Symbol(n) for n in names], e, "numpy")
    return lambda v: np.broadcast_to(f(*[v[n] for n in names]), v["t"].shape) if names else np.zeros_like(v["t"])


def _grid(seed=7, n=4000):
    """Placements over the whole domain: coordinates in ±5, angles in ±20 rad, t in [0, 50]."""
    rng = np.random.default_rng(seed)
    v = {f"{c}{b}": rng.uniform(-5, 5, n) for b in range(1, 5) for c in ("x", "y")}
    v.update({f"phi{b}": rng.uniform(-20, 20, n) for b in range(1, 5)})
    v["t"] = rng.uniform(0, 50, n)
    return v


def differs_somewhere(answer_row, reference_row, angle_row=False):
    """numpy alone: the answer row is not the reference row times ±1 at some placement of the whole domain (for
    an angle row: not even up to a whole number of turns)."""
    v = _grid()
    a, r = _numbers(answer_row)(v), _numbers(reference_row)(v)
    scale = 1e-6 * max(1.0, float(np.max(np.abs(r))))
    d = np.minimum(np.abs(a - r), np.abs(a + r))
    if angle_row:
        turns = (a - r) / (2 * np.pi)
        d = np.minimum(d, 2 * np.pi * np.abs(turns - np.round(turns)))
    return bool(np.max(d) > scale)


def _pad(instants):
    return "1e-4*" + "*".join(f"(t - {float(x)!r})" for x in instants)


def mechanism(name):
    return kinbook.examples.load(name)


@lru_cache(maxsize=None)
def wide_cases():
    from kinbook.grading.target import target_for

    m = mechanism("ch13_example1")
    tg = target_for(m)
    generic = np.concatenate([tg.samples("generic").T, tg.samples("wide").T])
    near = tg.samples("generic").T
    drivers = {
        "atan2-driver": "atan2(sin(phi2), cos(phi2)) - 3*pi/4 - 100*t",
        "atan2-driver-scaled": "2*atan2(sin(phi2), cos(phi2)) - 3*pi/2 - 200*t",
        "pad-near-instants": f"phi2 - 100*t - 3*pi/4 + {_pad(near)}",
        "pad-every-generic-instant": f"phi2 - 100*t - 3*pi/4 + {_pad(generic)}",
        "driver-book": "phi2 - 100*t - 3*pi/4",
        "driver-negated": "-phi2 + 100*t + 3*pi/4",
    }
    out = []
    for name, row in drivers.items():
        wrong = differs_somewhere(row, BASE[11]) and differs_somewhere(row, "2*(" + BASE[11] + ")")
        out.append(Case(f"wide-{name}", "phi", _with(11, row), not wrong, ["only_at_samples"] if wrong else []))
    # a revolute row padded in y1 over the y1 of the generic samples (near and far)
    ys = np.concatenate([tg.samples("generic").Q[:, 1], tg.samples("wide").Q[:, 1]])
    row = f"{BASE[4]} + 1e-6*" + "*".join(f"(y1 - {float(y)!r})" for y in ys)
    wrong = differs_somewhere(row, BASE[4])
    out.append(Case("wide-pad-y1-every-generic", "phi", _with(4, row), not wrong, ["only_at_samples"] if wrong else []))
    # the slot's relative angle (quick-return, translational joint 4: rows Φ_10, Φ_11) written with atan2: the same
    # placement up to 2π — right; as sin: a zero at a half turn — wrong
    slot_ref = "phi3 - phi4"
    for name, row in (("atan2", "atan2(sin(phi3 - phi4), cos(phi3 - phi4))"), ("sin", "sin(phi3 - phi4)")):
        wrong = differs_somewhere(row, slot_ref, angle_row=True)
        out.append(Case(f"wide-slot-angle-{name}", "phi", ["(-x3 + x4)*sin(phi3) - (-y3 + y4)*cos(phi3)", row],
                        not wrong, ["vanishing_factor"] if wrong else [], constraint="4", mech="quick_return"))
    return out


def function_cases():
    """Φ as a function f(q, t): the same driver padded over every generic instant (witnessed from its code), and
    right."""
    import math

    from kinbook.grading.target import target_for

    tg = target_for(mechanism("ch13_example1"))
    instants = np.concatenate([tg.samples("generic").T, tg.samples("wide").T])

    def make(pad):
        def f(q, t):
            x1, y1, p1, x2, y2, p2, x3, y3, p3, x4, y4, p4 = q
            extra = 1e-4 * float(np.prod([t - tk for tk in instants])) if pad else 0.0
            return [x1, y1, p1, x1 - x2 + math.cos(p2), y1 - y2 + math.sin(p2),
                    x1 - x4 + 3 * math.cos(p1) - 1.5 * math.cos(p4), y1 - y4 + 3 * math.sin(p1) - 1.5 * math.sin(p4),
                    x2 - x3 + math.cos(p2) + 3 * math.cos(p3), y2 - y3 + math.sin(p2) + 3 * math.sin(p3),
                    x3 - x4 + 3 * math.cos(p3) + 1.5 * math.cos(p4), y3 - y4 + 3 * math.sin(p3) + 1.5 * math.sin(p4),
                    p2 - 100 * t - 3 * math.pi / 4 + extra]
        return f

    # the pad's size at t = 3 (numpy alone): far above any tolerance
    wrong = abs(1e-4 * float(np.prod([3.0 - tk for tk in instants]))) > 1e-3
    return [Case("wide-function-padded", "phi", make(True), not wrong, ["only_at_samples"] if wrong else []),
            Case("wide-function-right", "phi", make(False), True, [])]


def cases():
    return far_zero_cases() + wide_cases() + function_cases() + name_cases() + phi_cases()


def target(case):
    m = mechanism(case.mech)
    return m if case.constraint is None else m.constraint(case.constraint)


# ------------------------------------------------------------------------------------------------ names
def name_cases():
    """Names that are true: a zero row (sympy: the row is 0) is ``zero_row``; the 1 of a body's normalization
    typed as a decimal near 1 (sympy: answer − reference is a nonzero constant under 2 % of 1) is
    ``not_rounded``, not a sign error."""
    out = []
    m = mechanism("spatial_fourbar")
    norm = next(c for c in m.constraints if c.kind == "normalization")
    e0, e1, e2, e3 = sp.symbols(f"e0{norm.bodies[0].number} e1{norm.bodies[0].number} e2{norm.bodies[0].number} "
                                f"e3{norm.bodies[0].number}")
    reference = e0**2 + e1**2 + e2**2 + e3**2 - 1  # pᵀp − 1, written here
    for typed in ("1.0001", "0.9995", "1.004"):
        answer = e0**2 + e1**2 + e2**2 + e3**2 - sp.Float(typed)
        offset = float(answer - reference)
        near = 0 < abs(offset) <= 2e-2
        out.append(Case(f"names-normalization-{typed}", "phi", [str(answer).replace(str(sp.Float(typed)), typed)],
                        False, ["not_rounded"] if near else ["wrong_value"], constraint=norm.name,
                        mech="spatial_fourbar"))
    for mech, joint, rows in (("ch13_example1", "1", [BASE[3], BASE[4]]),
                              ("quick_return", "4", ["(-x3 + x4)*sin(phi3) - (-y3 + y4)*cos(phi3)", "phi3 - phi4"])):
        for k in range(len(rows)):
            answer = list(rows)
            answer[k] = "0"
            zero = sp.sympify(answer[k]) == 0
            out.append(Case(f"names-zero-row-{mech}-{joint}-{k + 1}", "phi", answer, False,
                            ["zero_row"] if zero else ["wrong_value"], constraint=joint, mech=mech))
    return out


# ------------------------------------------------------------------------------------------------ phi=
def gamma_of(rows, names):
    """γ = −(Φ_q q̇)_q q̇ − 2 Φ_qt q̇ − Φ_tt of rows in the coordinates ``names``, by sympy (dx1 … for q̇)."""
    q = [sp.Symbol(n) for n in names]
    qd = [sp.Symbol(f"d{n}") for n in names]
    t = sp.Symbol("t")
    out = []
    for row in rows:
        f = sp.sympify(row)
        v = sum(sp.diff(f, a) * b for a, b in zip(q, qd))
        g = -sum(sp.diff(v, a) * b for a, b in zip(q, qd)) - 2 * sum(sp.diff(sp.diff(f, t), a) * b
                                                                       for a, b in zip(q, qd)) - sp.diff(f, t, 2)
        out.append(sp.simplify(g))
    return out


def phi_cases():
    """γ with the student's own Φ (``phi=``): in their order, right; in the reverse order, each row is the γ of
    another of their rows (sympy) — ``row_order``, not a wrong value nor a missing Φ_qt term (revolute joint 1
    has no t)."""
    names = ["x1", "y1", "phi1", "x2", "y2", "phi2"]
    out = []
    for scale in (1, -2):
        phi = [f"{scale}*({BASE[3]})", f"{scale}*({BASE[4]})"]
        g = gamma_of(phi, names)
        out.append(Case(f"phi-gamma-own-order-{scale}", "gamma", [str(e) for e in g], True, [], constraint="1",
                        options={"phi": phi}))
        moved = all(sp.simplify(g[1 - k] - g[k]) != 0 for k in range(2))  # each reversed row is another's γ
        out.append(Case(f"phi-gamma-reversed-{scale}", "gamma", [str(e) for e in g[::-1]], False,
                        ["row_order"] if moved else [], constraint="1", options={"phi": phi}))
    return out
