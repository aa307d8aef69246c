"""Student answers that a whole-mechanism comparison cannot judge (issue 22): rows true only because *another*
constraint holds (masking), rows multiplied by a factor that vanishes somewhere, redundant rows.

Every answer is typed from the bodies' points the way a student types it — eq. 7 for a point, eq. 17 for a
revolute joint, eq. 26 for a translational joint (the relative-angle row φ_i − φ_j), eq. 32 for a r-r joint —
never copied from kinbook. The verdicts follow from the geometry, by hand:

* masking: the ground's rows make x1 = y1 = φ1 = 0 wherever the mechanism is assembled, so φ1 + φ6 vanishes
  there exactly where φ1 − φ6 does; −x2 + cos φ2 where x1 − x2 + cos φ2; y1 − 3 sin φ1 (Aᵀ for the ground's A)
  where y1 + 3 sin φ1. As rows of their joint alone (body 1 free) they are wrong: each one is the named slip;
* vanishing factors: cos φ2 is zero at φ2 = ±π/2, e0 at a half-turn, x1 at x1 = 0 — there the row vanishes
  while the joint is broken. 2 + cos φ3 ≥ 1, 2 + e0 ≥ 1 (|e0| ≤ 1), D + 1 ≥ 1 never vanish: right; √D − l is
  (D − l²)/(√D + l), the factor 1/(√D + l) > 0: right;
* redundancy: s̃_i s_j has three rows of which two are independent (§14.4); the parallel constraint has two
  equations, so one row of three is one too many.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import sympy as sp

from . import corpus, corpus2
from .corpus import Case

EXERCISES = Path(__file__).resolve().parents[2] / "exercises"


@lru_cache(maxsize=None)
def _exercise(stem):
    from kinbook.classroom.variant import references

    path = next(EXERCISES.glob(f"{stem}*.ipynb"))
    return next(p.target for p in references(path) if p.name == "whole_phi")


def target(name, constraint=None):
    if name == "s-ss":
        m = _ss()
        return m if constraint is None else m.constraint(constraint)
    if name.startswith("ex"):
        m = _exercise(name)
        return m if constraint is None else m.constraint(constraint)
    if name.startswith(("p-", "s-")):
        return corpus2.target(name, constraint)
    return corpus.target(name, constraint)


@lru_cache(maxsize=None)
def _ss():
    return ss_pair()


# ------------------------------------------------------------------------------------------ a student's formulas
def pt(b, s):
    """Global x, y of the local point s = (ξ, η) of body b (eq. 7)."""
    x, y, f = f"x{b}", f"y{b}", f"phi{b}"
    return (f"({x} + ({s[0]})*cos({f}) - ({s[1]})*sin({f}))", f"({y} + ({s[0]})*sin({f}) + ({s[1]})*cos({f}))")


def rev(i, si, j, sj):
    (xi, yi), (xj, yj) = pt(i, si), pt(j, sj)
    return [f"{xi} - {xj}", f"{yi} - {yj}"]


def trans(i, p, q, j, pj, phi0="0"):
    """Eq. 26: (x_i^P − x_i^Q)(y_j^P − y_i^P) − (y_i^P − y_i^Q)(x_j^P − x_i^P) and φ_i − φ_j − φ⁰."""
    (xp, yp), (xq, yq), (xj, yj) = pt(i, p), pt(i, q), pt(j, pj)
    return [f"({xp} - {xq})*({yj} - {yp}) - ({yp} - {yq})*({xj} - {xp})", f"phi{i} - phi{j} - ({phi0})"]


def rr(i, si, j, sj, l2):
    (xi, yi), (xj, yj) = pt(i, si), pt(j, sj)
    return [f"({xi} - {xj})**2 + ({yi} - {yj})**2 - ({l2})"]


GROUND = ["x1", "y1", "phi1"]

# ex04's six-bar: ground 1 (OA, OB = (3, 0), P = (0, 4), Q = (1, 4)), crank 2, coupler 3, rocker 4, rod 5, slider 6
SIX_BAR = (GROUND + rev(1, (0, 0), 2, (-1, 0)) + rev(1, (3, 0), 4, (1.5, 0)) + rev(2, (1, 0), 3, (-3, 0))
           + rev(3, (3, 0), 4, (-1.5, 0)) + rev(3, (0, 1), 5, (-1.25, 0)) + rev(5, (1.25, 0), 6, (0, 0))
           + trans(1, (0, 4), (1, 4), 6, (0, 0)) + ["phi2 - 3*pi/4 - 2*t"])

# ex03's quick return: ground 1 (O, C = (0, −3)), crank 2, rocker 3 (C, P = (0, 0), Q = (1, 0)), block 4
QUICK_RETURN = (GROUND + rev(1, (0, 0), 2, (0, 0)) + rev(1, (0, -3), 3, (0, 0)) + rev(2, (1, 0), 4, (0, 0))
                + trans(3, (0, 0), (1, 0), 4, (0, 0)) + ["phi2 - pi/3 - 2*t"])

# ex06's steering: ground 1 (O, P = (0, −0.5), Q = (1, −0.5), KL = (−4, −2), KR = (4, −2)), pinion 2, rack 3
# (P, L = (−3, 0), R = (3, 0)), knuckles 4, 5 (K, T = (0, 1)); the tie rods are √5/2 long
STEERING = (GROUND + rev(1, (0, 0), 2, (0, 0)) + trans(1, (0, -0.5), (1, -0.5), 3, (0, 0)) + ["0.3*phi2 - x3"]
            + rev(1, (-4, -2), 4, (0, 0)) + rev(1, (4, -2), 5, (0, 0)) + rr(3, (-3, 0), 4, (0, 1), "5/4")
            + rr(3, (3, 0), 5, (0, 1), "5/4") + ["phi2 - 0.5*sin(2*t)"])


def _with(rows, k, value):
    out = list(rows)
    out[k] = value
    return out


def _spatial_rows(kind):
    return corpus2._spatial_phi(kind)


def cases():
    C = []

    def add(id, check, mech, c, answer, passed, score, mistakes=(), **opts):
        C.append(Case(id, check, mech, c, answer, passed, score, list(mistakes), opts))

    # ------------------------------------------------------------------ masking: the whole Φ of ex01, ex03, ex04, ex06
    add("mask-six-bar-right", "phi", "ex04", None, SIX_BAR, True, 1.0)
    add("mask-six-bar-relative-angle-sign", "phi", "ex04", None, _with(SIX_BAR, 16, "phi1 + phi6"), False, 17 / 18,
        ["sign_flip"])
    add("mask-six-bar-x1-dropped", "phi", "ex04", None, _with(SIX_BAR, 3, "-x2 + cos(phi2)"), False,
        17 / 18, ["missing_term"])
    add("mask-six-bar-ground-A-transposed", "phi", "ex04", None,
        _with(SIX_BAR, 6, "(y1 - 3*sin(phi1)) - (y4 + 1.5*sin(phi4))"), False, 17 / 18, ["A_transposed"])
    add("mask-six-bar-slide-simplified", "phi", "ex04", None, _with(SIX_BAR, 15, "y6 - 4"), False, 17 / 18,
        ["masked_row"])
    add("mask-quick-return-right", "phi", "ex03", None, QUICK_RETURN, True, 1.0)
    add("mask-quick-return-ground-dropped", "phi", "ex03", None, _with(QUICK_RETURN, 5, "-x3"),
        False, 11 / 12, ["missing_term"])
    add("mask-quick-return-ground-A-transposed", "phi", "ex03", None,
        _with(QUICK_RETURN, 5, "x1 - 3*sin(phi1) - x3"), False, 11 / 12, ["A_transposed"])
    add("mask-steering-right", "phi", "ex06", None, STEERING, True, 1.0)
    add("mask-steering-relative-angle-sign", "phi", "ex06", None, _with(STEERING, 6, "phi1 + phi3"), False, 14 / 15,
        ["sign_flip"])
    add("mask-steering-knuckle-simplified", "phi", "ex06", None, _with(STEERING, 10, "4 - x5"), False, 14 / 15,
        ["masked_row"])
    ex1 = list(corpus.EX1_PHI_SIMPLE)
    add("mask-ex1-ground-A-transposed", "phi", "ch13_example1", None,
        _with(ex1, 6, "y1 - 3*sin(phi1) - y4 - 1.5*sin(phi4)"), False, 11 / 12, ["A_transposed"])
    add("mask-ex1-whole-simplified-with-the-ground", "phi", "ch13_example1", None,
        _with(ex1, 5, "3 - x4 - 1.5*cos(phi4)"), False, 11 / 12,
        ["masked_row"])
    ex4 = list(corpus.EX4_PHI)
    add("mask-ex4-printed-phi8", "phi", "ch13_example4", None,
        _with(ex4, 7, "(x3 + 3*cos(phi3) - x1*cos(phi1))*sin(phi1) + (y3 + 3*sin(phi3) - y1 - sin(phi1))*cos(phi1)"),
        False, 8 / 9, ["book_misprint"])
    # the same slips in the joint graded alone: plainly wrong, no masking needed
    add("mask-alone-relative-angle-sign", "phi", "ex04", "7", trans(1, (0, 4), (1, 4), 6, (0, 0))[:1]
        + ["phi1 + phi6"], False, 0.5, ["sign_flip"])

    # ------------------------------------------------------------------ factors that vanish (and that do not)
    r1 = ["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"]  # joint 1 of example 1, s'_2 = (−1, 0)
    add("factor-cos-phi2-joint", "phi", "ch13_example1", "1", [f"cos(phi2)*({r1[0]})", r1[1]], False, 0.5,
        ["vanishing_factor"])
    add("factor-x1-joint", "phi", "ch13_example1", "1", [r1[0], f"x1*({r1[1]})"], False, 0.5, ["vanishing_factor"])
    add("factor-cos-phi2-whole", "phi", "ch13_example1", None, _with(ex1, 3, f"cos(phi2)*({ex1[3]})"), False,
        11 / 12, ["vanishing_factor"])
    add("factor-never-zero-joint", "phi", "ch13_example1", "1", [f"(2 + cos(phi3))*({r1[0]})", r1[1]], True, 1.0)
    add("factor-never-zero-whole", "phi", "ch13_example1", None, _with(ex1, 4, f"(2 + cos(phi3))*({ex1[4]})"),
        True, 1.0)
    d3 = "(x2 + cos(phi2) - x3 + 1.5*cos(phi3))**2 + (y2 + sin(phi2) - y3 + 1.5*sin(phi3))**2"  # ex. 3's r-r, l = 6
    add("factor-rr-sqrt", "phi", "ch13_example3", "3", [f"sqrt({d3}) - 6"], True, 1.0)
    add("factor-rr-positive", "phi", "ch13_example3", "3", [f"({d3} - 36)*({d3} + 1)"], True, 1.0)
    add("factor-rr-times-D", "phi", "ch13_example3", "3", [f"({d3} - 36)*({d3})"], False, 0.0, ["vanishing_factor"])
    sph = _spatial_rows("sph")
    add("factor-e0-spherical", "phi", "s-sph", "c", [sph[0] * sp.Symbol("e01"), sph[1], sph[2]], False, 2 / 3,
        ["vanishing_factor"])
    add("factor-2-plus-e0-spherical", "phi", "s-sph", "c", [sph[0] * (2 + sp.Symbol("e01")), sph[1], sph[2]], True,
        1.0)
    J1 = [["1", "0", "0", "-1", "0", "-sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]]
    add("factor-jacobian-cos-phi2", "jacobian", "ch13_example1", "1", [[f"cos(phi2)*({e})" for e in J1[0]], J1[1]],
        False, 0.5, ["vanishing_factor"])
    add("factor-jacobian-never-zero", "jacobian", "ch13_example1", "1",
        [[f"(2 + sin(phi2))*({e})" for e in J1[0]], J1[1]], True, 1.0)

    # ------------------------------------------------------------------ redundant rows
    Ai, Aj = corpus2.A_of(corpus2._syms(1)[3:]), corpus2.A_of(corpus2._syms(2)[3:])
    si, sj = Ai * sp.Matrix(corpus2.AI), Aj * sp.Matrix(corpus2.AI)
    add("redundant-p1-three-cross-rows", "phi", "s-p1", "c", list(si.cross(sj)), False, 2 / 3, ["dependent_row"])
    add("redundant-revolute-six-rows", "phi", "s-rev", "c", _spatial_rows("sph") + list(si.cross(sj)), False, 5 / 6,
        ["dependent_row"])
    add("redundant-p1-two-cross-rows-right", "phi", "s-p1", "c", list(si.cross(sj))[1:], True, 1.0)
    return C


# ------------------------------------------------------------------ a long γ, written with sympy (item 5)
def ss_pair():
    """Two free bodies and a spherical-spherical joint of length 1.3 between P_i = (0.3, −0.1, 0.8) and
    P_j = (−0.5, 0.2, 0.1)."""
    from kinbook import spatial as S

    m = S.Mechanism("s-ss")
    m.add_body("i", points={"P": (0.3, -0.1, 0.8)}, q0=(0, 0, 0, 1, 0.3, -0.2, 0.1))
    m.add_body("j", points={"P": (-0.5, 0.2, 0.1)}, q0=(1, 0.5, -0.4, 0.9, -0.1, 0.4, 0.2))
    m.add(S.SphericalSpherical("i", "j", point_i="P", point_j="P", length=1.3, name="c"))
    return m


def ss_sqrt_phi_and_gamma():
    """Φ = √(dᵀd) − l with d = r_j + A_j s'_j − r_i − A_i s'_i (A(p) of §14.3 with its factor 2), and its γ by
    sympy (−(Φ_q q̇)_q q̇): some 1.3·10⁵ nodes written out as a tree, a few hundred distinct ones."""
    qi, qj = corpus2._syms(1), corpus2._syms(2)
    d = (sp.Matrix(qj[:3]) + corpus2.A_of(qj[3:]) * sp.Matrix([-0.5, 0.2, 0.1])) - \
        (sp.Matrix(qi[:3]) + corpus2.A_of(qi[3:]) * sp.Matrix([0.3, -0.1, 0.8]))
    phi = sp.sqrt((d.T * d)[0]) - sp.Rational(13, 10)
    q = qi + qj
    qd = sp.Matrix([sp.Symbol("d" + s.name) for s in q])
    J = sp.Matrix([phi]).jacobian(q)
    return phi, (-(J * qd).jacobian(q) * qd)[0]


def hostile_gamma():
    """A sympy expression of 2⁴⁰ nodes written out (80 distinct): refused by its size, at once."""
    e = sp.Symbol("dx1")
    for _ in range(40):
        e = sp.sin(e) + sp.cos(e)
    return e


def long_cases():
    C = []
    phi, gamma = ss_sqrt_phi_and_gamma()
    C.append(Case("long-ss-sqrt-phi", "phi", "s-ss", "c", [phi], True, 1.0))
    C.append(Case("long-ss-sqrt-gamma", "gamma", "s-ss", "c", [gamma], True, 1.0, [], {"phi": [phi]}))
    C.append(Case("long-ss-gamma-negated", "gamma", "s-ss", "c", [-gamma], False, 0.0, ["gamma_sign"],
                  {"phi": [phi]}))
    C.append(Case("long-hostile-gamma", "gamma", "s-ss", "c", [hostile_gamma()], False, 0.0, ["malformed"]))
    return C


# ------------------------------------------------------------------ the spatial catalogue's gaps (item 7)
def book_A(p):
    """A(p) as §14.3 prints it (typed from the text): symmetric, without the factor 2 (erratum 14.3-A-of-p)."""
    e0, e1, e2, e3 = p
    h = sp.Rational(1, 2)
    return sp.Matrix([[e0**2 + e1**2 - h, e1 * e2 - e0 * e3, e1 * e3 - e0 * e2],
                      [e1 * e2 - e0 * e3, e0**2 + e2**2 - h, e2 * e3 - e0 * e1],
                      [e1 * e3 - e0 * e2, e2 * e3 - e0 * e1, e0**2 + e3**2 - h]])


def _split_cross(gamma, qd_i, qd_j):
    """γ's cross terms (those with a velocity of each body), by sympy: γ − γ(q̇_j = 0) − γ(q̇_i = 0)."""
    alone_i = gamma.xreplace({v: 0 for v in qd_j})
    alone_j = gamma.xreplace({v: 0 for v in qd_i})
    return sp.expand(gamma - alone_i - alone_j)


def spatial_gap_cases():
    C = []

    def add(id, check, mech, answer, passed, score, mistakes=(), **opts):
        C.append(Case(id, check, mech, "c", answer, passed, score, list(mistakes), opts))

    qi, qj = corpus2._syms(1), corpus2._syms(2)
    PI, PJ, AI, AJ = (sp.Matrix(v) for v in (corpus2.PI, corpus2.PJ, corpus2.AI, corpus2.AJ))
    A_i, A_j = corpus2.A_of(qi[3:]), corpus2.A_of(qj[3:])
    ri, rj = sp.Matrix(qi[:3]), sp.Matrix(qj[:3])
    # the book's A(p) inside a spherical joint
    s3_book = list(ri + book_A(qi[3:]) * PI - rj - book_A(qj[3:]) * PJ)
    add("gap-book-A-in-spherical", "phi", "s-sph", s3_book, False, 0.0, ["book_misprint"])
    # Aᵀ on body j only
    s3_t = list(ri + A_i * PI - rj - A_j.T * PJ)
    add("gap-A-transposed-body-j-only", "phi", "s-sph", s3_t, False, 0.0, ["A_transposed"])
    # l for l² in the s-s joint (l = 1.3)
    d = (sp.Matrix(qj[:3]) + A_j * sp.Matrix([-0.5, 0.2, 0.1])) - (sp.Matrix(qi[:3]) + A_i * sp.Matrix([0.3, -0.1, 0.8]))
    add("gap-ss-l-for-l-squared", "phi", "s-ss", [(d.T * d)[0] - 1.3], False, 0.0, ["missing_square"])
    add("gap-ss-right", "phi", "s-ss", [(d.T * d)[0] - 1.69], True, 1.0)
    # one γ cross-term sign: the n1 joint's 2ṡ_iᵀṡ_j
    si, sj = A_i * AI, A_j * AJ
    n1 = (si.T * sj)[0]
    _, g = corpus2._derive([n1])
    qdi, qdj = [sp.Symbol("d" + s.name) for s in qi], [sp.Symbol("d" + s.name) for s in qj]
    cross = _split_cross(g[0], qdi, qdj)
    assert cross != 0
    add("gap-n1-gamma-right", "gamma", "s-n1", [g[0]], True, 1.0)
    add("gap-n1-gamma-cross-term-sign", "gamma", "s-n1", [g[0] - 2 * cross], False, 0.0, ["sign_flip"])
    # n2 = s_iᵀd: its Jacobian without dᵀC_i (s_i's p_i held constant: only d differentiated)
    dn = rj + A_j * PJ - ri - A_i * PI
    frozen = [sp.Symbol(f"f{k}") for k in range(4)]
    si_frozen = corpus2.A_of(frozen) * AI
    row = sp.Matrix([(si_frozen.T * dn)[0]]).jacobian(qi + qj).xreplace(dict(zip(frozen, qi[3:])))
    add("gap-n2-jacobian-without-dC", "jacobian", "s-n2", row, False, None, ["missing_chain_rule"])
    add("gap-n2-jacobian-right", "jacobian", "s-n2", sp.Matrix([(si.T * dn)[0]]).jacobian(qi + qj), True, 1.0)
    return C


def driver_gap_cases():
    """The corpus' pendulum driver φ1 = 0.3 + 0.5 sin 4t: its amplitude typed in degrees (0.5 rad = 28.6479°)."""
    return [Case("gap-driver-amplitude-degrees", "phi", "p-driver", "d", ["phi1 - 0.3 - 28.6479*sin(4*t)"], False,
                 0.0, ["degrees"]),
            Case("gap-driver-amplitude-degrees-gamma", "gamma", "p-driver", "d",
                 [f"-{28.64788975654116 * 16}*sin(4*t)"], False, 0.0, ["degrees"])]
