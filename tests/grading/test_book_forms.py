""""Book" means the book (issue #14 item 1): for every joint type, the book's formula typed from the text
(chapter 13 §13.5–13.8 eqs. 14–42 and Tables 13.1–13.5, chapter 14 §14.4–14.5) passes all four checkers
with order="book"; where the book prints a wrong formula, the misprint is named with its erratum id.

Nothing here is taken from kinbook's reference: Φ is typed from the book's equations with the book's point
names, Φ_q and γ are the book's tables (corrected where an erratum says so) or sympy's derivatives of the typed
Φ (for the spatial joints, whose Table 14.1 the book prints empty).
"""

import pytest
import sympy as sp

from kinbook import planar as P
from kinbook import spatial as S
from kinbook.book import errata
from kinbook.core.symbolic import derive
from kinbook.grading import check_gamma, check_jacobian, check_nu, check_phi

BOOK = {"order": "book"}


def _pair(kind, points_i, points_j, joint, q0_i=(0, 0, 0.3), q0_j=(1, 0.5, -0.4)):
    m = P.Mechanism(f"{kind} pair")
    m.add_body("i", points=points_i, q0=q0_i)
    m.add_body("j", points=points_j, q0=q0_j)
    m.add(joint)
    return m, m.constraints[-1]


def _xy(b, s):
    """The book's x^P, y^P of a local point s = (ξ, η) on planar body b (1 or 2): eq. 7."""
    x, y, f = f"x{b}", f"y{b}", f"phi{b}"
    return (f"({x} + ({s[0]})*cos({f}) - ({s[1]})*sin({f}))", f"({y} + ({s[0]})*sin({f}) + ({s[1]})*cos({f}))")


def _all_four(c, phi, jac, nu, gamma, phi_for_derived=None):
    kw = {} if phi_for_derived is None else {"phi": phi_for_derived}
    for check, answer, opts in ((check_phi, phi, BOOK), (check_jacobian, jac, kw), (check_nu, nu, kw),
                                (check_gamma, gamma, kw)):
        r = check(answer, c, **opts)
        assert r.passed, (check.__name__, r)


# ================================================================================================ chapter 13
SI, SJ = (0.4, -0.2), (-0.7, 0.3)


def test_revolute_eq_18_and_tables_13_1_and_13_5():
    m, c = _pair("r", {"P": SI}, {"P": SJ}, P.Revolute("i", "j", point="P"))
    (xi, yi), (xj, yj) = _xy(1, SI), _xy(2, SJ)
    phi = [f"{xi} - {xj}", f"{yi} - {yj}"]
    jac = [["1", "0", f"-({yi} - y1)", "-1", "0", f"({yj} - y2)"],
           ["0", "1", f"({xi} - x1)", "0", "-1", f"-({xj} - x2)"]]
    gamma = [f"({xi} - x1)*dphi1**2 - ({xj} - x2)*dphi2**2", f"({yi} - y1)*dphi1**2 - ({yj} - y2)*dphi2**2"]
    _all_four(c, phi, jac, ["0", "0"], gamma)


def test_translational_eq_26_and_table_13_5():
    m, c = _pair("t", {"P": (0.2, 0.3), "Q": (1.2, 0.6)}, {"P": (-0.3, 0.4)},
                 P.Translational("i", "j", axis=("P", "Q"), point_j="P", phi0=0.7))
    (xiP, yiP), (xiQ, yiQ), (xjP, yjP) = _xy(1, (0.2, 0.3)), _xy(1, (1.2, 0.6)), _xy(2, (-0.3, 0.4))
    phi = [f"({xiP} - {xiQ})*({yjP} - {yiP}) - ({yiP} - {yiQ})*({xjP} - {xiP})", "phi1 - phi2 - (0.7)"]
    a, b = f"({xiP} - {xiQ})", f"({yiP} - {yiQ})"
    jac = [[b, f"-{a}", f"-({xjP} - x1)*{a} - ({yjP} - y1)*{b}", f"-{b}", a, f"({xjP} - x2)*{a} + ({yjP} - y2)*{b}"],
           ["0", "0", "1", "0", "0", "-1"]]
    # Table 13.5's γ_1 with −2[…]φ̇_i (erratum 13.8-table-13.5-t); it already uses φ̇_j = φ̇_i
    g1 = f"-2*({a}*(dx1 - dx2) + {b}*(dy1 - dy2))*dphi1 - ({a}*(y1 - y2) - {b}*(x1 - x2))*dphi1**2"
    _all_four(c, phi, jac, ["0", "0"], [g1, "0"])
    # the printed Table 13.2 entry and the printed γ_1 are the book's misprints, named with their ids
    printed = [list(jac[0]), jac[1]]
    printed[0][5] = f"({xjP} - x1)*{a} + ({yjP} - y1)*{b}"
    r = check_jacobian(printed, c)
    assert r.mistakes == ["book_misprint"] and "13.6-table-13.2" in r.messages[1]
    r = check_gamma([g1.replace("-2*(", "2*(", 1), "0"], c)
    assert r.mistakes == ["book_misprint"] and "13.8-table-13.5-t" in r.messages[1]
    # and the book's O (the body origin) for Q in eq. 23.a
    r = check_phi([f"({xiP} - x1)*({yjP} - {yiP}) - ({yiP} - y1)*({xjP} - {xiP})", "phi1 - phi2 - (0.7)"], c)
    assert r.mistakes == ["book_misprint"] and "13.5-eq25" in r.messages[1]


def test_revolute_revolute_eq_32_and_table_13_5():
    m, c = _pair("rr", {"P": SI}, {"P": SJ}, P.RevoluteRevolute("i", "j", "P", "P", length=1.7))
    (xi, yi), (xj, yj) = _xy(1, SI), _xy(2, SJ)
    phi = [f"({xi} - {xj})**2 + ({yi} - {yj})**2 - 1.7**2"]
    dx, dy = f"({xi} - {xj})", f"({yi} - {yj})"
    jac = [[f"2*{dx}", f"2*{dy}", f"-2*{dx}*({yi} - y1) + 2*{dy}*({xi} - x1)", f"-2*{dx}", f"-2*{dy}",
            f"2*{dx}*({yj} - y2) - 2*{dy}*({xj} - x2)"]]
    ai, aj = (f"({xi} - x1)", f"({yi} - y1)"), (f"({xj} - x2)", f"({yj} - y2)")
    gamma = [f"-2*(dx1 - dx2)**2 - 2*(dy1 - dy2)**2"
             f" - 2*({ai[0]}*({xj} - x1) + {ai[1]}*({yj} - y1))*dphi1**2"
             f" - 2*({aj[0]}*({xi} - x2) + {aj[1]}*({yi} - y2))*dphi2**2"
             f" + 4*({ai[0]}*{aj[0]} + {ai[1]}*{aj[1]})*dphi1*dphi2"
             f" - 4*({ai[0]}*(dy1 - dy2) - {ai[1]}*(dx1 - dx2))*dphi1"
             f" + 4*({aj[0]}*(dy1 - dy2) - {aj[1]}*(dx1 - dx2))*dphi2"]
    _all_four(c, phi, jac, ["0"], gamma)
    zeros = [list(jac[0])]
    zeros[0][2] = zeros[0][5] = "0"  # Table 13.3's entries reduce to zero
    assert check_jacobian(zeros, c).mistakes == ["book_misprint"]
    r = check_gamma([gamma[0].replace("2*(dy1 - dy2)**2", "2*(dy1 - dy2)", 1)], c)
    assert r.mistakes == ["book_misprint"] and "13.8-table-13.5-rr" in r.messages[1]


def test_revolute_translational_eq_33_and_table_13_5():
    m, c = _pair("rt", {"P": SI}, {"P": (0.1, 0.2), "Q": (1.1, -0.3)},
                 P.RevoluteTranslational("i", "j", point_i="P", axis=("P", "Q")))
    (xiP, yiP), (xjP, yjP), (xjQ, yjQ) = _xy(1, SI), _xy(2, (0.1, 0.2)), _xy(2, (1.1, -0.3))
    phi = [f"({xiP} - {xjQ})*({yjP} - {yjQ}) - ({yiP} - {yjQ})*({xjP} - {xjQ})"]
    sx, sy = f"({xjP} - {xjQ})", f"({yjP} - {yjQ})"
    jac = [[sy, f"-{sx}", f"-({yiP} - y1)*{sy} - ({xiP} - x1)*{sx}", f"-{sy}", sx,
            f"({yiP} - y2)*{sy} + ({xiP} - x2)*{sx}"]]  # ∂/∂φ_j corrected (erratum 13.6-table-13.4)
    gamma = [f"(({xiP} - x1)*{sy} - ({yiP} - y1)*{sx})*(dphi1 - 2*dphi2)*dphi1"
             f" + (({xiP} - x2)*{sy} - ({yiP} - y2)*{sx})*dphi2**2"
             f" - 2*({sx}*(dx1 - dx2) + {sy}*(dy1 - dy2))*dphi2"]
    _all_four(c, phi, jac, ["0"], gamma)
    printed = [list(jac[0])]
    printed[0][5] = f"({yiP} - y1)*{sy} + ({xiP} - x1)*{sx}"
    r = check_jacobian(printed, c)
    assert r.mistakes == ["book_misprint"] and "13.6-table-13.4" in r.messages[1]


def test_gear_eq_38_rack_eqs_40_42_and_drivers():
    m = P.Mechanism("gears")
    for name, phi0 in (("k", 0.2), ("i", 0.5), ("j", -0.3)):
        m.add_body(name, q0=(0, 0, phi0))
    m.add(P.Gear("i", "j", "k", radius_i=0.6, radius_j=1.4, name="g"))
    # body numbers: k = 1, i = 2, j = 3
    _all_four(m.constraint("g"), ["((phi2 - 0.5) - (phi1 - 0.2))*0.6 + ((phi3 + 0.3) - (phi1 - 0.2))*1.4"],
              [["0", "0", "-2.0", "0", "0", "0.6", "0", "0", "1.4"]], ["0"], ["0"])
    r = check_phi(["((phi2 - 0.5) - phi1)*0.6 + ((phi3 + 0.3) - phi1)*1.4"], m.constraint("g"))
    assert r.mistakes == ["missing_term"] and "13.5-eq37" not in str(r.messages)  # φ_k⁰ left out: no misprint
    for sliding, row in ((False, "(phi1 - 0.4)*0.5 - (x2 - 2)"), (True, "(x1 - 1) + (phi1 - 0.4)*0.5 - (x2 - 2)")):
        m = P.Mechanism("rack")
        m.add_body("pinion", q0=(1, 0, 0.4))
        m.add_body("rack", q0=(2, -1, 0))
        m.add(P.RackPinion("pinion", "rack", radius=0.5, sliding=sliding, name="rp"))
        jac = [["1" if sliding else "0", "0", "0.5", "-1", "0", "0"]]
        _all_four(m.constraint("rp"), [row], jac, ["0"], ["0"])
    m = P.Mechanism("driven")
    m.add_body("crank", q0=(0, 0, 0))
    m.add(P.Driver("crank", "phi", "3*pi/4 + 100*t", name="d"))
    _all_four(m.constraint("d"), ["phi1 - 3*pi/4 - 100*t"], [["0", "0", "1"]], ["100"], ["0"])
    m.add(P.Ground("crank", name="g"))
    _all_four(m.constraint("g"), ["x1", "y1", "phi1"], [["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]],
              ["0"] * 3, ["0"] * 3)


# ================================================================================================ chapter 14
def _A(p):
    """A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ] (§14.3, with its factor 2: erratum 14.3-A-of-p)."""
    e0, e = p[0], sp.Matrix(p[1:])
    et = sp.Matrix([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
    return 2 * ((e0**2 - sp.Rational(1, 2)) * sp.eye(3) + e * e.T + e0 * et)


def _spatial(joint, points_i=None, points_j=None):
    m = S.Mechanism("pair")
    m.add_body("i", points=points_i or {}, q0=(0, 0, 0, 1, 0.3, -0.2, 0.1))
    m.add_body("j", points=points_j or {}, q0=(1, 0.5, -0.4, 0.9, -0.1, 0.4, 0.2))
    m.add(joint)
    c = m.constraints[-1]
    qi, qj = m.body_symbols("i"), m.body_symbols("j")
    return m, c, qi, qj


def _derived_of(m, qi, qj, rows):
    """Φ_q (the constraint's 14 columns), ν and γ of the typed Φ, by sympy."""
    q = sp.Matrix.vstack(qi, qj)
    idx = [m.index(str(s)) for s in q]
    d = derive(sp.Matrix(rows), q, m.qd[idx, 0], m.t)
    return d.Phi_q, list(d.nu), list(d.gamma)


PI, PJ = (0.3, -0.1, 0.8), (-0.5, 0.2, 0.1)
AI, AJ = (0.0, 0.6, 0.8), (1.0, 0.0, 0.0)


def _vecs(qi, qj):
    Ai, Aj = _A(list(qi[3:])), _A(list(qj[3:]))
    ri, rj = sp.Matrix(qi[:3]), sp.Matrix(qj[:3])
    return Ai, Aj, ri, rj


@pytest.mark.parametrize("kind", ["n1", "n2", "p1", "p2", "spherical", "universal", "revolute", "cylindrical",
                                  "translational", "normalization"])
def test_spatial_joints_of_section_14_4(kind):
    joints = {
        "n1": lambda: S.Normal1("i", "j", vector_i=AI, vector_j=AJ),
        "n2": lambda: S.Normal2("i", "j", vector_i=AI, point_i=PI, point_j=PJ),
        "p1": lambda: S.Parallel1("i", "j", vector_i=AI, vector_j=AI),
        "p2": lambda: S.Parallel2("i", "j", vector_i=AI, point_i=PI, point_j=PJ),
        "spherical": lambda: S.Spherical("i", "j", point_i=PI, point_j=PJ),
        "universal": lambda: S.Universal("i", "j", vector_i=AI, vector_j=AJ, point_i=PI, point_j=PJ),
        "revolute": lambda: S.Revolute("i", "j", axis_i=AI, axis_j=AI, point_i=PI, point_j=PJ),
        "cylindrical": lambda: S.Cylindrical("i", "j", axis_i=AI, axis_j=AI, point_i=PI, point_j=PJ),
        "translational": lambda: S.Translational("i", "j", axis_i=AI, axis_j=AI, point_i=PI, point_j=PJ,
                                                 perp_i=AJ, perp_j=AJ),
    }
    if kind == "normalization":
        m = S.Mechanism("one body")
        m.add_body("b", q0=(0, 0, 0, 1, 0.3, -0.2, 0.1))
        c, q = m.constraints[0], m.body_symbols("b")
        rows = [sum(x**2 for x in q[3:]) - 1]
        jac = sp.Matrix(rows).jacobian(q)
        gamma = [-2 * sum(d**2 for d in m.qd[3:7])]
        _all_four(c, rows, jac, [0], gamma)
        return
    m, c, qi, qj = _spatial(joints[kind]())
    Ai, Aj, ri, rj = _vecs(qi, qj)
    si, sj = Ai * sp.Matrix(AI), Aj * sp.Matrix(AJ if kind in ("n1", "universal") else AI)
    d = rj + Aj * sp.Matrix(PJ) - ri - Ai * sp.Matrix(PI)
    s3 = list(ri + Ai * sp.Matrix(PI) - Aj * sp.Matrix(PJ) - rj)
    cross = lambda a, b: list(a.cross(b))[:2]  # noqa: E731  (the book: "only two are independent")
    rows = {
        "n1": [(si.T * sj)[0]],
        "n2": [(si.T * d)[0]],
        "p1": cross(si, sj),
        "p2": cross(si, d),
        "spherical": s3,
        "universal": s3 + [(si.T * sj)[0]],
        "revolute": s3 + cross(si, sj),
        "cylindrical": cross(si, sj) + cross(si, d),
        "translational": cross(si, sj) + cross(si, d) + [((Ai * sp.Matrix(AJ)).T * (Aj * sp.Matrix(AJ)))[0]],
    }[kind]
    jac, nu, gamma = _derived_of(m, qi, qj, rows)
    # the cross-product rows are an equivalent formulation of kinbook's h-rows: their ν and γ follow from them
    alternative = kind in ("p1", "p2", "revolute", "cylindrical", "translational")
    _all_four(c, rows, jac, nu, gamma, phi_for_derived=rows if alternative else None)


def test_the_n1_jacobian_of_section_14_5_and_its_gamma():
    """§14.5: Φ_pi = 2s_jᵀ(E_i s̄'_i + s'_i p_iᵀ) is right; the printed γ lacks −2(s_jᵀs'_i)ṗ_iᵀṗ_i … (erratum)."""
    m, c, qi, qj = _spatial(S.Normal1("i", "j", vector_i=AI, vector_j=AJ))
    Ai, Aj, _, _ = _vecs(qi, qj)

    def E(p):
        e0, e1, e2, e3 = p
        return sp.Matrix([[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]])

    def bar(a):
        a1, a2, a3 = a
        return sp.Matrix([[0, -a1, -a2, -a3], [a1, 0, a3, -a2], [a2, -a3, 0, a1], [a3, a2, -a1, 0]])

    pi, pj = sp.Matrix(qi[3:]), sp.Matrix(qj[3:])
    si, sj = Ai * sp.Matrix(AI), Aj * sp.Matrix(AJ)
    row = sp.Matrix.hstack(sp.zeros(1, 3), 2 * sj.T * (E(pi) * bar(AI) + sp.Matrix(AI) * pi.T), sp.zeros(1, 3),
                           2 * si.T * (E(pj) * bar(AJ) + sp.Matrix(AJ) * pj.T))
    assert check_jacobian(row, c).passed
    _, _, gamma = _derived_of(m, qi, qj, [(si.T * sj)[0]])
    assert check_gamma(gamma, c).passed
    # the book's γ (its three misprints corrected) lacks the ṗᵀṗ terms of its own Φ_p
    pdi, pdj = sp.Matrix(m.qd[3:7, 0]), sp.Matrix(m.qd[10:14, 0])
    book = gamma[0] + 2 * (sj.T * sp.Matrix(AI))[0] * (pdi.T * pdi)[0] + 2 * (si.T * sp.Matrix(AJ))[0] * (pdj.T * pdj)[0]
    r = check_gamma([book], c)
    assert r.mistakes == ["book_misprint"] and "14.5-gamma-n1-table" in r.messages[1]


def test_every_erratum_the_checkers_cite_exists():
    import pathlib
    import re

    import kinbook.grading as grading

    cited = set()
    for path in pathlib.Path(grading.__file__).parent.glob("*.py"):
        cited |= set(re.findall(r'"(1[34]\.\d-[A-Za-z0-9.\-]+)"', path.read_text(encoding="utf-8")))
    assert len(cited) >= 10
    for eid in cited:
        assert errata.get(eid).id == eid
