"""One rule for Φ_q, ν and γ whatever the answer's type, and ``phi=`` as docs/mistakes.md states it.

Answers are a driver's and a revolute joint's rows scaled by constants, typed three ways (numbers, text, a sympy
Matrix); each expectation comes from sympy apart from kinbook: the Jacobian of φ1 − f(t) is [0, 0, 1] (a factor
±1 is the Jacobian of ±Φ, right; any other constant c is the Jacobian of c·Φ, ``scaled``); with the student's own
Φ = k·Φ_ref, a row is right as k × the reference's, or as the reference's own row (docs/mistakes.md: "a row right
for the reference does too").
"""

import pytest
import sympy as sp

from kinbook import planar as P
from kinbook.grading import check_gamma, check_jacobian, check_nu

phi1, t = sp.symbols("phi1 t")
F = 2.0 * t + sp.Rational(1, 2)  # a driver φ1 = 0.5 + 2t, written exactly
PHI = phi1 - F


def _driver():
    m = P.Mechanism("one-rule")
    m.add_body("crank", q0=(0, 0, 0.5))
    m.add(P.Driver("crank", "phi", "0.5 + 2*t", name="d"))
    return m.constraint("d")


D = _driver()
JAC = [float(sp.diff(PHI, x)) for x in sp.symbols("x1 y1 phi1")]  # [0, 0, 1] by sympy
NU = float(-sp.diff(PHI, t))  # 2
FACTORS = (1.0, -1.0, 2.0, 0.5, 3.0)


def _typed(rows, how):
    if how == "numbers":
        return rows
    if how == "text":
        return [[repr(x) for x in row] for row in rows]
    return sp.Matrix(rows)


CASES = [(c, how) for c in FACTORS for how in ("numbers", "text", "sympy")]


@pytest.mark.parametrize("c, how", CASES, ids=[f"{c}-{h}" for c, h in CASES])
def test_a_jacobian_row_scaled_by_c_gets_one_verdict_whatever_its_type(c, how):
    r = check_jacobian(_typed([[c * v for v in JAC]], how), D)
    right = abs(abs(c) - 1.0) < 1e-12  # the Jacobian of ±Φ
    assert r.passed is right, r
    assert r.mistakes == ([] if right else ["scaled"]), r


@pytest.mark.parametrize("k", (1.0, -2.0, 3.0))
@pytest.mark.parametrize("c", (1.0, -2.0, 3.0, -1.0))
def test_nu_with_phi_follows_the_students_factor_or_the_reference(k, c):
    """ν of k·Φ is k·ν (sympy: −∂(kΦ)/∂t); a row c·ν is right when c = k (consistent) or c = 1 (the reference's)."""
    own = [str(k * PHI)]
    expected_nu = float(-sp.diff(k * PHI, t))
    r = check_nu([repr(c * NU)], D, phi=own)
    right = abs(c * NU - expected_nu) < 1e-9 or c == 1.0
    assert r.passed is right, r


def test_gamma_with_an_equivalent_own_row_accepts_the_reference_gamma():
    """A revolute joint's γ (sympy: −(Φ_q q̇)_q q̇ of the typed rows) with an own Φ whose first row is a sum of the
    joint's two rows (equivalent, no multiple): the reference γ rows are right."""
    m = P.Mechanism("rev")
    m.add_body("a", points={"P": (1.0, 0.0)}, q0=(0.1, 0.2, 0.3))
    m.add_body("b", points={"P": (0.0, 0.5)}, q0=(1.0, 0.5, -0.4))
    m.add(P.Revolute("a", "b", point="P", name="r"))
    q = sp.symbols("x1 y1 phi1 x2 y2 phi2")
    qd = sp.symbols("dx1 dy1 dphi1 dx2 dy2 dphi2")
    x1, y1, f1, x2, y2, f2 = q
    rows = [x1 + sp.cos(f1) - x2 + 0.5 * sp.sin(f2), y1 + sp.sin(f1) - y2 - 0.5 * sp.cos(f2)]
    gamma = []
    for row in rows:
        v = sum(sp.diff(row, a) * b for a, b in zip(q, qd))
        gamma.append(-sum(sp.diff(v, a) * b for a, b in zip(q, qd)))
    own = [str(rows[0] + rows[1]), str(rows[1])]
    r = check_gamma([str(g) for g in gamma], m.constraint("r"), phi=own)
    assert r.passed, r
