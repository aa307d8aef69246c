"""More student answers: every joint type of both chapters × Φ, Φ_q, ν, γ — the book's forms, equivalent
forms and each catalogued mistake — typed the way a student types them, from the book's formulas.

Each answer is built by a *formula typed from the book* (eq. 7 for a point, eqs. 17-42, Tables 13.1-13.5,
§14.4's vectors) with the student's slip applied to what they type — a local coordinate with the wrong sign,
the points of i and j exchanged, sin with the wrong sign (Aᵀ), A left out, a square forgotten … — never by
asking kinbook for its reference. The verdict each case states is the one the slip deserves. Correct
answers are cross-checked in tests/grading/test_corpus.py against an independent derivation (sympy's
derivatives of the formula typed here, and finite differences along a path).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from kinbook import planar as P
from kinbook import spatial as S

from .corpus import Case

_MECHS = {}


# ================================================================================================ mechanisms
def _planar_pair(name, pi, pj, joint):
    m = P.Mechanism(name)
    m.add_body("i", points=pi, q0=(0.1, -0.2, 0.3))
    m.add_body("j", points=pj, q0=(1.0, 0.5, -0.4))
    m.add(joint)
    return m


def _build(name):
    if name == "p-rev":
        return _planar_pair(name, {"P": SI}, {"P": SJ}, P.Revolute("i", "j", point="P", name="r"))
    if name == "p-trans":
        return _planar_pair(name, {"P": TP, "Q": TQ}, {"P": TJ},
                            P.Translational("i", "j", axis=("P", "Q"), point_j="P", phi0=0.7, name="t"))
    if name == "p-rr":
        return _planar_pair(name, {"P": SI}, {"P": SJ}, P.RevoluteRevolute("i", "j", "P", "P", length=1.7, name="rr"))
    if name == "p-rt":
        return _planar_pair(name, {"P": SI}, {"P": RP, "Q": RQ},
                            P.RevoluteTranslational("i", "j", point_i="P", axis=("P", "Q"), name="rt"))
    if name == "p-gear":
        m = P.Mechanism(name)
        for b, phi0 in (("k", 0.2), ("i", 0.5), ("j", -0.3)):
            m.add_body(b, q0=(0, 0, phi0))
        m.add(P.Gear("i", "j", "k", radius_i=0.6, radius_j=1.4, name="g"))
        return m
    if name in ("p-rack", "p-rack-sliding"):
        m = P.Mechanism(name)
        m.add_body("pinion", q0=(1, 0, 0.4))
        m.add_body("rack", q0=(2, -1, 0))
        m.add(P.RackPinion("pinion", "rack", radius=0.5, sliding=name.endswith("sliding"), name="rp"))
        return m
    if name == "p-driver":
        m = P.Mechanism(name)
        m.add_body("crank", q0=(0, 0, 0.3))
        m.add(P.Driver("crank", "phi", "0.3 + 0.5*sin(4*t)", name="d"))
        return m
    if name == "p-crank":  # a crank O–A (1.8 long) pinned at A to a rod
        return _planar_pair(name, {"O": CRANK_O, "A": CRANK_A}, {"A": ROD_A}, P.Revolute("i", "j", point="A", name="r"))
    if name == "s-crank":  # a spatial crank O–A (1.6 long) with a ball joint at A
        m = S.Mechanism(name)
        m.add_body("i", points={"O": S_CRANK_O, "A": S_CRANK_A}, q0=(0, 0, 0, 1, 0.3, -0.2, 0.1))
        m.add_body("j", points={"A": S_ROD_A}, q0=(1, 0.5, -0.4, 0.9, -0.1, 0.4, 0.2))
        m.add(S.Spherical("i", "j", point="A", name="c"))
        return m
    if name.startswith("s-"):
        return _spatial(name[2:])
    raise KeyError(name)


def mechanism(name):
    if name not in _MECHS:
        _MECHS[name] = _build(name)
    return _MECHS[name]


def target(name, constraint):
    return mechanism(name).constraint(constraint)


# ================================================================================================ planar formulas
SI, SJ = (0.4, -0.2), (-0.7, 0.3)
TP, TQ, TJ = (0.2, 0.3), (1.2, 0.6), (-0.3, 0.4)
RP, RQ = (0.1, 0.2), (1.1, -0.3)
CRANK_O, CRANK_A, ROD_A = (-0.5, 0.0), (1.3, 0.0), (-0.7, 0.3)  # |O–A| = 1.8


def xy(b, s, transposed=False, local=False):
    """x^P, y^P of a local point s on body b, typed from eq. 7 (with a student's slips)."""
    x, y, f = f"x{b}", f"y{b}", f"phi{b}"
    if local:
        return f"({x} + {s[0]})", f"({y} + {s[1]})"
    sg = "+" if transposed else "-"
    so = "-" if transposed else "+"
    return (f"({x} + ({s[0]})*cos({f}) {sg} ({s[1]})*sin({f}))", f"({y} {so} ({s[0]})*sin({f}) + ({s[1]})*cos({f}))")


def rev_phi(si=SI, sj=SJ, **kw):
    (xi, yi), (xj, yj) = xy(1, si, **kw), xy(2, sj, **kw)
    return [f"{xi} - {xj}", f"{yi} - {yj}"]


def rev_jac(si=SI, sj=SJ, chain=True, a_for_b=False):
    (xi, yi), (xj, yj) = xy(1, si), xy(2, sj)
    if not chain:
        return [["1", "0", "0", "-1", "0", "0"], ["0", "1", "0", "0", "-1", "0"]]
    if a_for_b:  # ∂(A s')/∂φ taken as A s'
        return [["1", "0", f"({xi} - x1)", "-1", "0", f"-({xj} - x2)"],
                ["0", "1", f"({yi} - y1)", "0", "-1", f"-({yj} - y2)"]]
    return [["1", "0", f"-({yi} - y1)", "-1", "0", f"({yj} - y2)"],
            ["0", "1", f"({xi} - x1)", "0", "-1", f"-({xj} - x2)"]]


def rev_gamma(si=SI, sj=SJ, sq="**2", sign=1):
    (xi, yi), (xj, yj) = xy(1, si), xy(2, sj)
    rows = [f"({xi} - x1)*dphi1{sq} - ({xj} - x2)*dphi2{sq}", f"({yi} - y1)*dphi1{sq} - ({yj} - y2)*dphi2{sq}"]
    return rows if sign == 1 else [f"-({r})" for r in rows]


def trans_phi(p=TP, q=TQ, j=TJ, phi0="0.7", **kw):
    (xiP, yiP), (xiQ, yiQ), (xjP, yjP) = xy(1, p, **kw), xy(1, q, **kw), xy(2, j, **kw)
    return [f"({xiP} - {xiQ})*({yjP} - {yiP}) - ({yiP} - {yiQ})*({xjP} - {xiP})", f"phi1 - phi2 - ({phi0})"]


def trans_jac(p=TP, q=TQ, j=TJ, printed=False):
    (xiP, yiP), (xiQ, yiQ), (xjP, yjP) = xy(1, p), xy(1, q), xy(2, j)
    a, b = f"({xiP} - {xiQ})", f"({yiP} - {yiQ})"
    last = f"({xjP} - x1)*{a} + ({yjP} - y1)*{b}" if printed else f"({xjP} - x2)*{a} + ({yjP} - y2)*{b}"
    return [[b, f"-{a}", f"-({xjP} - x1)*{a} - ({yjP} - y1)*{b}", f"-{b}", a, last],
            ["0", "0", "1", "0", "0", "-1"]]


def trans_gamma(p=TP, q=TQ, printed=False):
    (xiP, yiP), (xiQ, yiQ) = xy(1, p), xy(1, q)
    a, b = f"({xiP} - {xiQ})", f"({yiP} - {yiQ})"
    sign = "" if printed else "-"
    return [f"{sign}2*({a}*(dx1 - dx2) + {b}*(dy1 - dy2))*dphi1 - ({a}*(y1 - y2) - {b}*(x1 - x2))*dphi1**2", "0"]


def rr_phi(si=SI, sj=SJ, l2="1.7**2", **kw):
    (xi, yi), (xj, yj) = xy(1, si, **kw), xy(2, sj, **kw)
    return [f"({xi} - {xj})**2 + ({yi} - {yj})**2 - {l2}"]


def rr_jac(si=SI, sj=SJ, zeros=False):
    (xi, yi), (xj, yj) = xy(1, si), xy(2, sj)
    dx, dy = f"({xi} - {xj})", f"({yi} - {yj})"
    pi = "0" if zeros else f"-2*{dx}*({yi} - y1) + 2*{dy}*({xi} - x1)"
    pj = "0" if zeros else f"2*{dx}*({yj} - y2) - 2*{dy}*({xj} - x2)"
    return [[f"2*{dx}", f"2*{dy}", pi, f"-2*{dx}", f"-2*{dy}", pj]]


def rr_gamma(si=SI, sj=SJ, dy_square="**2"):
    (xi, yi), (xj, yj) = xy(1, si), xy(2, sj)
    ai, aj = (f"({xi} - x1)", f"({yi} - y1)"), (f"({xj} - x2)", f"({yj} - y2)")
    return [f"-2*(dx1 - dx2)**2 - 2*(dy1 - dy2){dy_square}"
            f" - 2*({ai[0]}*({xj} - x1) + {ai[1]}*({yj} - y1))*dphi1**2"
            f" - 2*({aj[0]}*({xi} - x2) + {aj[1]}*({yi} - y2))*dphi2**2"
            f" + 4*({ai[0]}*{aj[0]} + {ai[1]}*{aj[1]})*dphi1*dphi2"
            f" - 4*({ai[0]}*(dy1 - dy2) - {ai[1]}*(dx1 - dx2))*dphi1"
            f" + 4*({aj[0]}*(dy1 - dy2) - {aj[1]}*(dx1 - dx2))*dphi2"]


def rt_phi(pi=SI, p=RP, q=RQ, swap=False, **kw):
    if swap:  # the revolute point taken on j and the axis on i
        (xiP, yiP), (xjP, yjP), (xjQ, yjQ) = xy(2, pi, **kw), xy(1, p, **kw), xy(1, q, **kw)
    else:
        (xiP, yiP), (xjP, yjP), (xjQ, yjQ) = xy(1, pi, **kw), xy(2, p, **kw), xy(2, q, **kw)
    return [f"({xiP} - {xjQ})*({yjP} - {yjQ}) - ({yiP} - {yjQ})*({xjP} - {xjQ})"]


def rt_jac(pi=SI, p=RP, q=RQ, printed=False):
    (xiP, yiP), (xjP, yjP), (xjQ, yjQ) = xy(1, pi), xy(2, p), xy(2, q)
    sx, sy = f"({xjP} - {xjQ})", f"({yjP} - {yjQ})"
    last = f"({yiP} - y1)*{sy} + ({xiP} - x1)*{sx}" if printed else f"({yiP} - y2)*{sy} + ({xiP} - x2)*{sx}"
    return [[sy, f"-{sx}", f"-({yiP} - y1)*{sy} - ({xiP} - x1)*{sx}", f"-{sy}", sx, last]]


def rt_gamma(pi=SI, p=RP, q=RQ):
    (xiP, yiP), (xjP, yjP), (xjQ, yjQ) = xy(1, pi), xy(2, p), xy(2, q)
    sx, sy = f"({xjP} - {xjQ})", f"({yjP} - {yjQ})"
    return [f"(({xiP} - x1)*{sy} - ({yiP} - y1)*{sx})*(dphi1 - 2*dphi2)*dphi1"
            f" + (({xiP} - x2)*{sy} - ({yiP} - y2)*{sx})*dphi2**2"
            f" - 2*({sx}*(dx1 - dx2) + {sy}*(dy1 - dy2))*dphi2"]


def _scaled(rows, k, c):
    out = list(rows)
    out[k] = f"{c}*({out[k]})"
    return out


def _with(rows, k, value):
    out = list(rows)
    out[k] = value
    return out


def _entry(rows, k, col, value):
    out = [list(r) for r in rows]
    out[k][col] = value
    return out


def _t(rows):
    return [list(r) for r in zip(*rows)]


def planar_cases():
    C = []

    def add(id, check, mech, c, answer, passed, score, mistakes=(), **opts):
        C.append(Case(id, check, mech, c, answer, passed, score, list(mistakes), opts))

    # ---------------------------------------------------------------- revolute (eqs. 17-18, Tables 13.1, 13.5)
    m, c = "p-rev", "r"
    ok = rev_phi()
    add("p-rev-phi", "phi", m, c, ok, True, 1.0)
    add("p-rev-phi-book-order", "phi", m, c, ok, True, 1.0, order="book")
    add("p-rev-phi-negated", "phi", m, c, [f"-({r})" for r in ok], True, 1.0, order="book")
    add("p-rev-phi-reordered", "phi", m, c, ok[::-1], True, 1.0)
    add("p-rev-phi-reordered-book", "phi", m, c, ok[::-1], False, 0.5, ["row_order"], order="book")
    add("p-rev-phi-scaled", "phi", m, c, _scaled(ok, 1, "-2.5"), True, 1.0)
    add("p-rev-phi-cos2sin2", "phi", m, c, _with(ok, 0, f"({ok[0]})*(cos(phi2)**2 + sin(phi2)**2)"), True, 1.0)
    add("p-rev-phi-swapped-points", "phi", m, c, rev_phi(SJ, SI), False, 0.0, ["swapped_points"])
    add("p-rev-phi-A-transposed", "phi", m, c, rev_phi(transposed=True), False, 0.0, ["A_transposed"])
    add("p-rev-phi-local", "phi", m, c, rev_phi(local=True), False, 0.0, ["local_vector"])
    add("p-rev-phi-sign-eta-j", "phi", m, c, rev_phi(sj=(SJ[0], -SJ[1])), False, 0.0, ["sign_flip"])
    add("p-rev-phi-sign-xi-i", "phi", m, c, rev_phi(si=(-SI[0], SI[1])), False, 0.0, ["sign_flip"])
    add("p-rev-phi-sign-xi-j-one-row", "phi", m, c, _with(ok, 0, rev_phi(sj=(-SJ[0], SJ[1]))[0]), False, 0.5,
        ["sign_flip"])
    add("p-rev-phi-missing-xj", "phi", m, c, _with(ok, 0, ok[0].replace("- (x2 +", "- (0 +", 1)), False, 0.5,
        ["missing_term"])
    add("p-rev-phi-missing-row", "phi", m, c, ok[:1], False, 0.5, ["missing_row"])
    add("p-rev-phi-row-twice", "phi", m, c, [ok[0], ok[0]], False, 1 / 3, ["dependent_row", "missing_row"])
    add("p-rev-phi-row-doubled", "phi", m, c, [ok[0], f"2*({ok[0]})"], False, 1 / 3,
        ["dependent_row", "missing_row"])
    add("p-rev-phi-row-squared", "phi", m, c, [ok[0], f"({ok[0]})**2"], False, 1 / 3,
        ["dependent_row", "missing_row"])
    add("p-rev-phi-product", "phi", m, c, [ok[0], f"({ok[0]})*({ok[1]})"], False, 1 / 3,
        ["dependent_row", "missing_row"])
    add("p-rev-phi-sum-for-row", "phi", m, c, [ok[0], f"({ok[0]}) + ({ok[1]})"], True, 1.0)
    add("p-rev-phi-degrees-nonsense", "phi", m, c, ["x1 - x2", "y1 - y2"], False, 0.0, ["wrong_value"])
    jac = rev_jac()
    add("p-rev-jac", "jacobian", m, c, jac, True, 1.0)
    add("p-rev-jac-negated-row", "jacobian", m, c, [[f"-({e})" for e in jac[0]], jac[1]], True, 1.0)
    add("p-rev-jac-chain", "jacobian", m, c, rev_jac(chain=False), False, 0.5, ["missing_chain_rule"])
    add("p-rev-jac-A-for-B", "jacobian", m, c, rev_jac(a_for_b=True), False, 0.5, ["A_for_B"])
    add("p-rev-jac-entry-sign", "jacobian", m, c, _entry(jac, 1, 5, f"({jac[1][5]})*(-1)"), False, 0.875,
        ["sign_flip"])
    add("p-rev-jac-transposed", "jacobian", m, c, _t(jac), False, 0.5, ["transposed"])
    add("p-rev-jac-swapped-points", "jacobian", m, c, rev_jac(SJ, SI), False, None, ["swapped_points"])
    add("p-rev-jac-swapped-points-own", "jacobian", m, c, rev_jac(SJ, SI), True, 1.0, phi=rev_phi(SJ, SI))
    add("p-rev-jac-reordered-own", "jacobian", m, c, jac[::-1], True, 1.0, phi=ok[::-1])
    add("p-rev-jac-reordered", "jacobian", m, c, jac[::-1], False, 0.5, ["row_order"])
    add("p-rev-jac-reordered-any", "jacobian", m, c, jac[::-1], True, 1.0, order="any")
    add("p-rev-jac-wrong-shape", "jacobian", m, c, [r[:3] for r in jac], False, 0.0, ["wrong_shape"])
    add("p-rev-nu", "nu", m, c, ["0", "0"], True, 1.0)
    add("p-rev-nu-numbers", "nu", m, c, [0, 0], True, 1.0)
    add("p-rev-gamma", "gamma", m, c, rev_gamma(), True, 1.0)
    add("p-rev-gamma-book-sign", "gamma", m, c, rev_gamma(sign=-1), False, 0.0, ["gamma_sign"])
    add("p-rev-gamma-unsquared", "gamma", m, c, rev_gamma(sq=""), False, 0.0, ["missing_square"])
    add("p-rev-gamma-swapped", "gamma", m, c, rev_gamma(SJ, SI), False, 0.0, ["swapped_points"])
    add("p-rev-gamma-own-negated", "gamma", m, c, rev_gamma(sign=-1), True, 1.0, phi=[f"-({r})" for r in ok])
    xi = xy(1, SI)[0]
    add("p-rev-gamma-one-term", "gamma", m, c, _with(rev_gamma(), 0, f"({xi} - x1)*dphi1**2"), False, 0.5,
        ["missing_term"])
    # ---------------------------------------------------------------- translational (eqs. 21-26, Table 13.5)
    m, c = "p-trans", "t"
    ok = trans_phi()
    add("p-trans-phi", "phi", m, c, ok, True, 1.0, order="book")
    add("p-trans-phi-kinbook-old-sign", "phi", m, c, _scaled(ok, 0, "-1"), True, 1.0, order="book")
    (xiP, yiP), (xiQ, yiQ), (xjP, yjP) = xy(1, TP), xy(1, TQ), xy(2, TJ)
    dot = f"({xiP} - {xiQ})*({xjP} - {xiP}) + ({yiP} - {yiQ})*({yjP} - {yiP})"
    add("p-trans-phi-dot-product", "phi", m, c, [dot, ok[1]], False, 0.5, ["book_misprint"])  # erratum 13.5-eq24
    add("p-trans-phi-origin", "phi", m, c, [trans_phi(q=(0, 0))[0], ok[1]], False, 0.5, ["book_misprint"])
    add("p-trans-phi-degrees", "phi", m, c, trans_phi(phi0=str(0.7 * 180 / np.pi)), False, 0.5, ["degrees"])
    add("p-trans-phi-no-phi0", "phi", m, c, trans_phi(phi0="0"), False, 0.5, ["missing_term"])
    add("p-trans-phi-A-transposed", "phi", m, c, [trans_phi(transposed=True)[0], ok[1]], False, 0.5,
        ["A_transposed"])
    add("p-trans-phi-local", "phi", m, c, [trans_phi(local=True)[0], ok[1]], False, 0.5, ["local_vector"])
    add("p-trans-phi-sign-eta-Q", "phi", m, c, [trans_phi(q=(TQ[0], -TQ[1]))[0], ok[1]], False, 0.5, ["sign_flip"])
    add("p-trans-phi-missing-angle-row", "phi", m, c, ok[:1], False, 0.5, ["missing_row"])
    jac = trans_jac()
    add("p-trans-jac", "jacobian", m, c, jac, True, 1.0)
    add("p-trans-jac-table-13-2", "jacobian", m, c, trans_jac(printed=True), False, None, ["book_misprint"])
    add("p-trans-jac-entry-sign", "jacobian", m, c, _entry(jac, 0, 0, f"-({jac[0][0]})"), False, None,
        ["sign_flip"])
    add("p-trans-jac-angle-row-sign", "jacobian", m, c, [jac[0], ["0", "0", "1", "0", "0", "1"]], False, 0.75,
        ["sign_flip"])
    add("p-trans-nu", "nu", m, c, ["0", "0"], True, 1.0)
    add("p-trans-gamma", "gamma", m, c, trans_gamma(), True, 1.0)
    add("p-trans-gamma-table-13-5", "gamma", m, c, trans_gamma(printed=True), False, 0.5, ["book_misprint"])
    add("p-trans-gamma-negated", "gamma", m, c, [f"-({trans_gamma()[0]})", "0"], False, 0.5, ["gamma_sign"])
    # ---------------------------------------------------------------- revolute-revolute (eq. 32)
    m, c = "p-rr", "rr"
    ok = rr_phi()
    add("p-rr-phi", "phi", m, c, ok, True, 1.0, order="book")
    add("p-rr-phi-sqrt", "phi", m, c, [ok[0].replace(" - 1.7**2", "").join(["sqrt(", ") - 1.7"])], True, 1.0)
    add("p-rr-phi-halved", "phi", m, c, _scaled(ok, 0, "0.5"), True, 1.0)
    add("p-rr-phi-l-not-squared", "phi", m, c, rr_phi(l2="1.7"), False, 0.0, ["missing_square"])
    add("p-rr-phi-swapped", "phi", m, c, rr_phi(SJ, SI), False, 0.0, ["swapped_points"])
    add("p-rr-phi-sign-eta-i", "phi", m, c, rr_phi(si=(SI[0], -SI[1])), False, 0.0, ["sign_flip"])
    add("p-rr-phi-A-transposed", "phi", m, c, rr_phi(transposed=True), False, 0.0, ["A_transposed"])
    add("p-rr-phi-local", "phi", m, c, rr_phi(local=True), False, 0.0, ["local_vector"])
    add("p-rr-jac", "jacobian", m, c, rr_jac(), True, 1.0)
    add("p-rr-jac-table-13-3", "jacobian", m, c, rr_jac(zeros=True), False, None, ["book_misprint"])
    add("p-rr-jac-halved", "jacobian", m, c, [[f"0.5*({e})" for e in rr_jac()[0]]], False, 0.0, ["scaled"])
    add("p-rr-nu", "nu", m, c, ["0"], True, 1.0)
    add("p-rr-gamma", "gamma", m, c, rr_gamma(), True, 1.0)
    add("p-rr-gamma-table-13-5", "gamma", m, c, rr_gamma(dy_square=""), False, 0.0, ["book_misprint"])
    add("p-rr-gamma-sign", "gamma", m, c, [f"-({rr_gamma()[0]})"], False, 0.0, ["gamma_sign"])
    # ---------------------------------------------------------------- revolute-translational (eq. 33)
    m, c = "p-rt", "rt"
    ok = rt_phi()
    add("p-rt-phi", "phi", m, c, ok, True, 1.0, order="book")
    add("p-rt-phi-negated", "phi", m, c, _scaled(ok, 0, "-1"), True, 1.0)
    add("p-rt-phi-swapped-bodies", "phi", m, c, rt_phi(swap=True), False, 0.0, ["swapped_bodies"])
    add("p-rt-phi-A-transposed", "phi", m, c, rt_phi(transposed=True), False, 0.0, ["A_transposed"])
    add("p-rt-phi-local", "phi", m, c, rt_phi(local=True), False, 0.0, ["local_vector"])
    add("p-rt-phi-sign-xi-P", "phi", m, c, rt_phi(pi=(-SI[0], SI[1])), False, 0.0, ["sign_flip"])
    add("p-rt-jac", "jacobian", m, c, rt_jac(), True, 1.0)
    add("p-rt-jac-table-13-4", "jacobian", m, c, rt_jac(printed=True), False, None, ["book_misprint"])
    add("p-rt-jac-chain", "jacobian", m, c, [[rt_jac()[0][0], rt_jac()[0][1], "0", rt_jac()[0][3], rt_jac()[0][4], "0"]],
        False, None, ["missing_chain_rule"])
    add("p-rt-nu", "nu", m, c, ["0"], True, 1.0)
    add("p-rt-gamma", "gamma", m, c, rt_gamma(), True, 1.0)
    add("p-rt-gamma-sign", "gamma", m, c, [f"-({rt_gamma()[0]})"], False, 0.0, ["gamma_sign"])
    # ---------------------------------------------------------------- gears (eqs. 36-38), rack (eqs. 40, 42)
    m, c = "p-gear", "g"
    ok = ["((phi2 - 0.5) - (phi1 - 0.2))*0.6 + ((phi3 + 0.3) - (phi1 - 0.2))*1.4"]
    add("p-gear-phi", "phi", m, c, ok, True, 1.0, order="book")
    add("p-gear-phi-expanded", "phi", m, c, ["0.6*phi2 + 1.4*phi3 - 2*phi1 + 0.52"], True, 1.0)
    add("p-gear-phi-sign", "phi", m, c, ["((phi2 - 0.5) - (phi1 - 0.2))*0.6 - ((phi3 + 0.3) - (phi1 - 0.2))*1.4"],
        False, 0.0, ["sign_flip"])
    add("p-gear-phi-radii-swapped", "phi", m, c,
        ["((phi2 - 0.5) - (phi1 - 0.2))*1.4 + ((phi3 + 0.3) - (phi1 - 0.2))*0.6"], False, 0.0, ["swapped_bodies"])
    add("p-gear-phi-fixed-carrier", "phi", m, c, ["(phi2 - 0.5)*0.6 + (phi3 + 0.3)*1.4"], False, 0.0,
        ["missing_term"])
    # eq. 37 read with φ′ = φ − φ_k: the carrier's initial angle left out (the book defines φ′ from φ′(0) = φ⁰)
    add("p-gear-phi-eq-37", "phi", m, c, ["((phi2 - phi1) - 0.5)*0.6 + ((phi3 - phi1) + 0.3)*1.4"], False, 0.0,
        ["missing_term"])
    add("p-gear-jac", "jacobian", m, c, [["0", "0", "-2", "0", "0", "0.6", "0", "0", "1.4"]], True, 1.0)
    add("p-gear-jac-no-carrier", "jacobian", m, c, [["0", "0", "0", "0", "0", "0.6", "0", "0", "1.4"]], False,
        2 / 3, ["missing_term"])
    add("p-gear-nu", "nu", m, c, ["0"], True, 1.0)
    add("p-gear-gamma", "gamma", m, c, [0], True, 1.0)
    m, c = "p-rack", "rp"
    add("p-rack-phi", "phi", m, c, ["(phi1 - 0.4)*0.5 - (x2 - 2)"], True, 1.0, order="book")
    add("p-rack-phi-sign", "phi", m, c, ["(phi1 - 0.4)*0.5 + (x2 - 2)"], False, 0.0, ["sign_flip"])
    add("p-rack-phi-degrees", "phi", m, c, [f"(phi1 - {0.4 * 180 / np.pi})*0.5 - (x2 - 2)"], False, 0.0, ["degrees"])
    add("p-rack-jac", "jacobian", m, c, [["0", "0", "0.5", "-1", "0", "0"]], True, 1.0)
    add("p-rack-jac-sign", "jacobian", m, c, [["0", "0", "0.5", "1", "0", "0"]], False, 0.5, ["sign_flip"])
    add("p-rack-nu", "nu", m, c, ["0"], True, 1.0)
    add("p-rack-gamma", "gamma", m, c, ["0"], True, 1.0)
    add("p-rack-gamma-nonsense", "gamma", m, c, ["0.5*dphi1**2"], False, 0.0, ["wrong_value"])
    m = "p-rack-sliding"
    add("p-rack-sliding-phi", "phi", m, c, ["(x1 - 1) + (phi1 - 0.4)*0.5 - (x2 - 2)"], True, 1.0)
    add("p-rack-sliding-phi-fixed-form", "phi", m, c, ["(phi1 - 0.4)*0.5 - (x2 - 2)"], False, 0.0, ["missing_term"])
    # ---------------------------------------------------------------- a driver 0.3 + 0.5 sin 4t
    m, c = "p-driver", "d"
    add("p-driver-phi", "phi", m, c, ["phi1 - 0.3 - 0.5*sin(4*t)"], True, 1.0)
    add("p-driver-phi-negated", "phi", m, c, ["0.3 + 0.5*sin(4*t) - phi1"], True, 1.0)
    add("p-driver-phi-degrees", "phi", m, c, [f"phi1 - {0.3 * 180 / np.pi} - 0.5*sin(4*t)"], False, 0.0, ["degrees"])
    add("p-driver-phi-sign-f", "phi", m, c, ["phi1 + 0.3 + 0.5*sin(4*t)"], False, 0.0, ["sign_flip"])
    add("p-driver-jac", "jacobian", m, c, [[0, 0, 1]], True, 1.0)
    add("p-driver-nu", "nu", m, c, ["2*cos(4*t)"], True, 1.0)
    add("p-driver-nu-sign", "nu", m, c, ["-2*cos(4*t)"], False, 0.0, ["nu_sign"])
    add("p-driver-nu-own-sign", "nu", m, c, ["-2*cos(4*t)"], True, 1.0, phi=["0.3 + 0.5*sin(4*t) - phi1"])
    add("p-driver-nu-zero", "nu", m, c, [0], False, 0.0, ["malformed"])  # a number: right nowhere but t = π/8 …
    add("p-driver-nu-zero-formula", "nu", m, c, ["0"], False, 0.0, ["nu_missing"])
    add("p-driver-nu-zero-text", "nu", m, c, ["0*t"], False, 0.0, ["nu_missing"])
    add("p-driver-gamma", "gamma", m, c, ["-8*sin(4*t)"], True, 1.0)
    add("p-driver-gamma-zero", "gamma", m, c, [0], False, 0.0, ["malformed"])  # the γ = [0]: refused
    add("p-driver-gamma-zero-text", "gamma", m, c, ["0*t"], False, 0.0, ["missing_tt_term"])
    add("p-driver-gamma-sign", "gamma", m, c, ["8*sin(4*t)"], False, 0.0, ["gamma_sign"])
    # ---------------------------------------------------------------- a row multiplied by a link length
    # γ (eq. 18 differentiated twice) of a revolute joint at the end A of a crank O–A: |A − O| = 1.8 from the
    # points typed above; any factor that is no length of the joint's geometry stays a "wrong value"
    m, c = "p-crank", "r"
    ok = rev_gamma(CRANK_A, ROD_A)
    length = float(np.hypot(CRANK_A[0] - CRANK_O[0], CRANK_A[1] - CRANK_O[1]))
    add("p-crank-gamma", "gamma", m, c, ok, True, 1.0)
    add("p-crank-gamma-times-crank", "gamma", m, c, [f"{length}*({r})" for r in ok], False, 0.0, ["scaled"])
    add("p-crank-gamma-row-times-crank", "gamma", m, c, _scaled(ok, 1, str(length)), False, 0.5, ["scaled"])
    add("p-crank-gamma-times-1.37", "gamma", m, c, [f"1.37*({r})" for r in ok], False, 0.0, ["wrong_value"])
    add("p-rr-gamma-times-l", "gamma", "p-rr", "rr", [f"1.7*({r})" for r in rr_gamma()], False, 0.0, ["scaled"])
    return C


# ================================================================================================ spatial
AI, AJ = (0.0, 0.6, 0.8), (1.0, 0.0, 0.0)
PI, PJ = (0.3, -0.1, 0.8), (-0.5, 0.2, 0.1)


def _spatial(kind):
    joints = {
        "sph": lambda: S.Spherical("i", "j", point_i=PI, point_j=PJ, name="c"),
        "n1": lambda: S.Normal1("i", "j", vector_i=AI, vector_j=AJ, name="c"),
        "n2": lambda: S.Normal2("i", "j", vector_i=AI, point_i=PI, point_j=PJ, name="c"),
        "p1": lambda: S.Parallel1("i", "j", vector_i=AI, vector_j=AI, name="c"),
        "uni": lambda: S.Universal("i", "j", vector_i=AI, vector_j=AJ, point_i=PI, point_j=PJ, name="c"),
        "rev": lambda: S.Revolute("i", "j", axis_i=AI, axis_j=AI, point_i=PI, point_j=PJ, name="c"),
        "cyl": lambda: S.Cylindrical("i", "j", axis_i=AI, axis_j=AI, point_i=PI, point_j=PJ, name="c"),
    }
    m = S.Mechanism(f"s-{kind}")
    m.add_body("i", q0=(0, 0, 0, 1, 0.3, -0.2, 0.1))
    m.add_body("j", q0=(1, 0.5, -0.4, 0.9, -0.1, 0.4, 0.2))
    m.add(joints[kind]())
    return m


S_CRANK_O, S_CRANK_A, S_ROD_A = (0.2, 0.0, 0.0), (1.8, 0.0, 0.0), (-0.5, 0.4, 0.3)  # |O–A| = 1.6


def A_of(p, transposed=False, factor=2):
    """A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ] typed from §14.3 (factor 2 restored; erratum 14.3-A-of-p)."""
    e0, e = p[0], sp.Matrix(p[1:])
    et = sp.Matrix([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
    A = factor * ((e0**2 - sp.Rational(1, 2)) * sp.eye(3) + e * e.T + e0 * et)
    return A.T if transposed else A


def _syms(b):
    names = f"x{b} y{b} z{b} e0{b} e1{b} e2{b} e3{b}".split()
    return [sp.Symbol(n) for n in names]  # the student's own symbols (not real=True): matched by name


def _point(b, s, **kw):
    q = _syms(b)
    if kw.get("local"):
        return sp.Matrix(q[:3]) + sp.Matrix(s)
    return sp.Matrix(q[:3]) + A_of(q[3:], kw.get("transposed", False)) * sp.Matrix(s)


def _vec(b, a, **kw):
    q = _syms(b)
    if kw.get("local"):
        return sp.Matrix(a)
    return A_of(q[3:], kw.get("transposed", False)) * sp.Matrix(a)


def _spatial_phi(kind, **kw):
    pi, pj = kw.pop("pi", PI), kw.pop("pj", PJ)
    s3 = list(_point(1, pi, **kw) - _point(2, pj, **kw))
    si, sj = _vec(1, AI, **kw), _vec(2, AJ if kind in ("n1", "uni") else AI, **kw)
    d = _point(2, pj, **kw) - _point(1, pi, **kw)
    cross = lambda a, b: list(a.cross(b))[:2]  # noqa: E731
    return {"sph": s3, "n1": [(si.T * sj)[0]], "n2": [(si.T * d)[0]], "p1": cross(si, sj),
            "uni": s3 + [(si.T * sj)[0]], "rev": s3 + cross(si, sj), "cyl": cross(si, sj) + cross(si, d)}[kind]


def _derive(rows):
    qs = _syms(1) + _syms(2)
    qd = [sp.Symbol("d" + s.name) for s in qs]
    M = sp.Matrix(rows)
    J = M.jacobian(qs)
    gamma = -(J * sp.Matrix(qd)).jacobian(qs) * sp.Matrix(qd)
    return J, gamma


def spatial_cases():
    C = []

    def add(id, check, mech, answer, passed, score, mistakes=(), **opts):
        C.append(Case(id, check, mech, "c", answer, passed, score, list(mistakes), opts))

    for kind in ("sph", "n1", "n2", "p1", "uni", "rev", "cyl"):
        m = f"s-{kind}"
        ok = _spatial_phi(kind)
        n = len(ok)
        alt = kind in ("p1", "rev", "cyl")  # the book's cross-product rows: an equivalent formulation
        add(f"s-{kind}-phi", "phi", m, ok, True, 1.0, order="book")
        add(f"s-{kind}-phi-negated", "phi", m, [-e for e in ok], True, 1.0)
        add(f"s-{kind}-phi-A-transposed", "phi", m, _spatial_phi(kind, transposed=True), False, None,
            ["A_transposed"])
        local = _spatial_phi(kind, local=True)
        # a row that local vectors make 0 (sympy: hᵢ'ᵀhⱼ' of two local axes) is named zero_row, the others local_vector
        named = list(dict.fromkeys("zero_row" if sp.sympify(e) == 0 else "local_vector" for e in local))
        add(f"s-{kind}-phi-local", "phi", m, local, False, None, named)
        if kind in ("sph", "uni", "rev"):
            add(f"s-{kind}-phi-swapped-points", "phi", m, _spatial_phi(kind, pi=PJ, pj=PI), False, None,
                ["swapped_points"])
            neg = list(ok)
            neg[:3] = _spatial_phi("sph", pj=tuple(-x for x in PJ))  # the sign of A_j s'_j
            add(f"s-{kind}-phi-sign-Aj-sj", "phi", m, neg, False, None, ["sign_flip"])
        if kind in ("sph", "uni", "rev", "cyl"):
            add(f"s-{kind}-phi-missing-row", "phi", m, ok[:-1], False, (n - 1) / n,
                ["missing_row"])
        J, gamma = _derive(ok)
        own = {"phi": ok} if alt else {}
        add(f"s-{kind}-jac", "jacobian", m, J, True, 1.0)
        add(f"s-{kind}-nu", "nu", m, [0] * n, True, 1.0)
        add(f"s-{kind}-gamma", "gamma", m, gamma, True, 1.0, **own)
        add(f"s-{kind}-gamma-sign", "gamma", m, -gamma, False, None, ["gamma_sign"], **own)
        Jt, gt = _derive(_spatial_phi(kind, transposed=True))
        add(f"s-{kind}-jac-A-transposed", "jacobian", m, Jt, False, None, ["A_transposed"])
        if not alt:
            add(f"s-{kind}-gamma-A-transposed", "gamma", m, gt, False, None, ["A_transposed"])
        frozen = J.copy()  # A treated as constant: the p-columns dropped
        for col in list(range(3, 7)) + list(range(10, 14)):
            frozen[:, col] = sp.zeros(J.rows, 1)
        add(f"s-{kind}-jac-chain", "jacobian", m, frozen, False, None, ["missing_chain_rule"])
    # the EG-form Jacobian (2Eā without 2apᵀ) of a normal-1 and of the universal joint's n1 row
    from kinbook.spatial.rotations import E, a_bar

    for kind in ("n1", "uni"):
        m = f"s-{kind}"
        ok = _spatial_phi(kind)
        J, _ = _derive(ok)
        pi, pj = sp.Matrix(_syms(1)[3:]), sp.Matrix(_syms(2)[3:])
        si, sj = _vec(1, AI), _vec(2, AJ)
        eg = J.copy()
        eg[-1, 3:7] = 2 * sj.T * E(pi) * a_bar(sp.Matrix(AI))
        eg[-1, 10:14] = 2 * si.T * E(pj) * a_bar(sp.Matrix(AJ))
        add(f"s-{kind}-jac-eg", "jacobian", m, eg, False, None, ["eg_jacobian"])
    # a ball joint at the end A of a crank O–A (|A − O| = 1.6): γ multiplied by the crank's length is "scaled",
    # by 1.37 a "wrong value"
    _, gamma = _derive(list(_point(1, S_CRANK_A) - _point(2, S_ROD_A)))
    length = float(np.linalg.norm(np.subtract(S_CRANK_A, S_CRANK_O)))
    add("s-crank-gamma", "gamma", "s-crank", gamma, True, 1.0)
    add("s-crank-gamma-times-crank", "gamma", "s-crank", length * gamma, False, 0.0, ["scaled"])
    add("s-crank-gamma-times-1.37", "gamma", "s-crank", 1.37 * gamma, False, 0.0, ["wrong_value"])
    return C


def cases():
    return planar_cases() + spatial_cases()
