"""A hostile student (issue 22): right rows in the book's other forms, a wrong row hidden among right ones, rows
right only at the configurations the checker samples, factors that vanish there, a duplicate row in place of a
needed one — and every checker option refused by name.

The rule of form, as the book allows it (§13.2: Φ(q, t) = 0 is a set of equations):

* a Φ row may be multiplied by any nonzero *constant* (−1 included) and a joint's rows combined among
  themselves with constants, in either order mode ("book" asks row k to stand for Φ_k, with its factor);
* a Φ_q row may carry the factor −1 only (it is then the Jacobian of −Φ_k, itself right); any other constant
  is the Jacobian of c·Φ_k with a factor of the derivative missing (``scaled``);
* ν and γ rows follow their Φ row: factor 1, or the factor of the student's own Φ row given as ``phi=``.

Every verdict below follows from the answer by hand, not from kinbook: a row ``ρ + P`` where ρ is the joint's
row (typed from eq. 17) and ``P`` a product of (x − x_k) over the sampled x_k is not the joint's equation
wherever x is none of them; ``f·ρ`` with f vanishing at some configuration q* (a sampled one, or x1 = 0 which
the ground makes true everywhere it holds) is zero at q* where the joint may be broken; ``(ρ_1, 2ρ_1)`` is one
equation, not two. The sampled configurations are read from kinbook.grading.sample — the seed is public,
so this is what a student who reads the source can do.
"""

from __future__ import annotations

import numpy as np

from kinbook.grading.target import target_for

from . import corpus2, corpus3
from .corpus import EX1_PHI, EX1_PHI_SIMPLE, Case

target = corpus3.target

E = list(EX1_PHI_SIMPLE)
R1 = ["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"]  # revolute joint 1 of example 1, s'_2 = (−1, 0) (eq. 17)
J1 = [["1", "0", "0", "-1", "0", "-sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]]
G1 = ["cos(phi2)*dphi2**2", "sin(phi2)*dphi2**2"]  # γ of joint 1: −(∂/∂q (Φ_q q̇)) q̇ by hand


def _with(rows, k, value):
    out = list(rows)
    out[k] = value
    return out


def _product(symbol, values, at):
    """c·∏ (symbol − v) over the values, as text: zero at each of them, nowhere else, and 1 at ``at`` (a student
    who means it to count gives it a size)."""
    c = 1.0 / abs(float(np.prod([at - float(v) for v in values])))
    return f"{c!r}*" + "*".join(f"({symbol} - ({float(v)!r}))" for v in values)


def _sampled(name, constraint, which, column):
    """The sampled values of one coordinate (or of t: column None) of a target — public: seeded."""
    t = target_for(target(name, constraint))
    s = t.samples(which)
    return s.T if column is None else s.Q[:, column]


def cases():
    C = []

    def add(id, check, mech, c, answer, passed, score, mistakes=(), **opts):
        C.append(Case(id, check, mech, c, answer, passed, score, list(mistakes), opts))

    ex1 = "ch13_example1"
    # ------------------------------------------------------------------ the book's other forms: right
    add("hostile-form-book-order-rows-negated", "phi", ex1, None,
        [f"-({r})" if k in (3, 6, 8) else r for k, r in enumerate(E)], True, 1.0, order="book")
    add("hostile-form-book-order-row-doubled", "phi", ex1, None, _with(E, 5, f"2*({E[5]})"), True, 1.0, order="book")
    add("hostile-form-book-matrix-form-book-order", "phi", ex1, None, list(EX1_PHI), True, 1.0, order="book")
    add("hostile-form-joint-rows-combined", "phi", ex1, "1", [f"{R1[0]} + 2*({R1[1]})", R1[1]], True, 1.0)
    add("hostile-form-jacobian-row-negated", "jacobian", ex1, "1", [[f"-({e})" for e in J1[0]], J1[1]], True, 1.0)
    add("hostile-form-jacobian-row-doubled", "jacobian", ex1, "1", [[f"2*({e})" for e in J1[0]], J1[1]], False,
        0.5, ["scaled"])
    add("hostile-form-gamma-follows-own-negated-phi", "gamma", ex1, "1", [f"-({G1[0]})", G1[1]], True, 1.0,
        phi=[f"-({R1[0]})", R1[1]])
    add("hostile-form-gamma-row-negated-alone", "gamma", ex1, "1", [f"-({G1[0]})", G1[1]], False, 0.5,
        ["gamma_sign"])

    # ------------------------------------------------------------------ a wrong row hidden among right ones
    add("hostile-hidden-length-1.49", "phi", ex1, None, _with(E, 5, "x1 + 3*cos(phi1) - x4 - 1.49*cos(phi4)"),
        False, 11 / 12, ["not_rounded"])  # 0.7 % off the length 1.5: right with 1.5 in its place
    add("hostile-hidden-length-1.4999", "phi", ex1, None,
        _with(E, 9, "x3 + 3*cos(phi3) - x4 + 1.4999*cos(phi4)"), False, 11 / 12, ["not_rounded"])
    add("hostile-hidden-one-term-sign", "phi", ex1, None, _with(E, 10, "-y3 + 3*sin(phi3) - y4 + 1.5*sin(phi4)"),
        False, 11 / 12, ["sign_flip"])
    # 1.0005 for the crank's length 1: near an integer of the exercise, not it (0.05 % off) — not_rounded
    add("hostile-hidden-joint-coefficient", "phi", ex1, "1", [R1[0], "y1 - y2 + 1.0005*sin(phi2)"], False, 0.5,
        ["not_rounded"])

    # ------------------------------------------------------------------ right only at the sampled configurations
    xg = _sampled(ex1, None, "generic", 1)  # y1 at the generic samples of the whole mechanism
    add("hostile-only-at-generic-samples-whole", "phi", ex1, None,
        _with(E, 3, f"{E[3]} + {_product('y1', xg, 0.5)}"), False, 11 / 12, ["only_at_samples"])
    xj = _sampled(ex1, "1", "generic", 4)  # y2 at the generic samples of joint 1
    add("hostile-only-at-generic-samples-joint", "phi", ex1, "1", [R1[0], f"{R1[1]} + {_product('y2', xj, 0.5)}"],
        False, 0.5, ["only_at_samples"])
    tj = _sampled(ex1, "1", "assembled", None)
    add("hostile-only-at-assembled-samples-gamma", "gamma", ex1, "1", [G1[0], f"{G1[1]} + {_product('t', tj, 0.5)}"],
        False, 0.5, ["only_at_samples"])
    qa = _sampled(ex1, "1", "assembled", 5)  # φ2 where joint 1 is sampled assembled
    add("hostile-only-at-assembled-samples-jacobian", "jacobian", ex1, "1",
        [J1[0], J1[1][:5] + [f"cos(phi2) + {_product('phi2', qa, 0.5)}"]], False, 0.5, ["only_at_samples"])

    # ------------------------------------------------------------------ factors that vanish at the samples
    add("hostile-factor-x1-ground-makes-zero", "phi", ex1, None, _with(E, 3, f"x1*({E[3]})"), False, 11 / 12,
        ["vanishing_factor"])
    add("hostile-factor-phi1-ground-makes-zero", "phi", ex1, None, _with(E, 4, f"phi1*({E[4]})"), False, 11 / 12,
        ["vanishing_factor"])
    add("hostile-factor-zero-at-a-generic-sample", "phi", ex1, "1", [f"(y2 - ({float(xj[0])!r}))*({R1[0]})", R1[1]],
        False, 0.5, ["vanishing_factor"])
    add("hostile-factor-zero-at-an-assembled-sample", "phi", ex1, "1",
        [R1[0], f"(phi2 - ({float(qa[0])!r}))*({R1[1]})"], False, 0.5, ["vanishing_factor"])

    # ------------------------------------------------------------------ a duplicate in place of a needed row
    add("hostile-duplicate-replaces-next-row", "phi", ex1, None, _with(E, 4, E[3]), False, 11 / 13,
        ["dependent_row", "missing_row"])
    add("hostile-duplicate-scaled-in-joint", "phi", ex1, "1", [R1[0], f"-2*({R1[0]})"], False, 1 / 3,
        ["dependent_row", "missing_row"])
    add("hostile-duplicate-other-joint-row", "phi", ex1, None, _with(E, 6, E[5]), False, 11 / 13,
        ["dependent_row", "missing_row"])
    add("hostile-one-row-for-two-sum-of-squares", "phi", ex1, "1", [f"({R1[0]})**2 + ({R1[1]})**2"], False, 0.0,
        ["dependent_row", "missing_row"])
    sph = corpus2._spatial_phi("sph")
    add("hostile-spherical-sum-for-third-row", "phi", "s-sph", "c", [sph[0], sph[1], sph[0] + sph[1]], False,
        2 / 4, ["dependent_row", "missing_row"])
    return C + option_cases()


# ------------------------------------------------------------------ every option, refused by name (item 8)
def option_cases():
    C = []
    right = {"phi": R1, "jacobian": J1, "nu": ["0", "0"], "gamma": G1}
    bad = [("rtol", -1e-6), ("rtol", 2.0), ("rtol", True), ("rtol", "1e-6"), ("rtol", float("nan")),
           ("rtol", float("inf")), ("symbolic", "yes"), ("symbolic", 1), ("at", [0.0] * 6), ("at", {"x": 1}),
           ("at", {"q": [0.0] * 5}), ("at", {"q": [0.0] * 12, "t": "soon"}), ("at", {"q": [np.inf] * 12}),
           ("at", {"qd": [[0.0] * 12]}), ("order", "random"), ("order", 1)]
    for check, answer in right.items():
        for k, (name, value) in enumerate(bad):
            C.append(Case(f"opt-{check}-{name}-{k}", check, "ch13_example1", "1", answer, False, 0.0, ["malformed"],
                          {name: value}))
        C.append(Case(f"opt-{check}-good", check, "ch13_example1", "1", answer, True, 1.0, [],
                      {"rtol": np.float64(1e-7), "symbolic": True, "order": "any"}))
    for k, value in enumerate((3, ["x1 +"], {"a": 1})):  # an unusable own Φ: said in a note, graded without it
        C.append(Case(f"opt-gamma-phi-unusable-{k}", "gamma", "ch13_example1", "1", G1, True, 1.0, [],
                      {"phi": value}))
    C.append(Case("opt-phi-at-numbers", "phi", "ch13_example1", "1", ["0.0", "0"], True, 1.0, [],
                  {"at": {"q": [0, 0, 0, 1, 0, 0] + [0.0] * 6, "t": 0.0}}))
    return C
