"""Realistic wrong answers to the 36 try-its, typed the way students type them (issue 29).

Written apart from kinbook.grading.mutants: each answer is what a student writes in the notebook cell — a
formula string, a number worked by hand, a numpy array — with ONE mistake, and the mistake code a teacher would
name it by. Nothing here asks kinbook for the reference: the right answers are derived here too (and
tests/book/test_student_answers.py checks that they pass), the notebook's own variables (q0, qd0, the mechanism)
are read as the notebook gives them.

Each answer carries a second computation that confirms its mistake (``confirm(wrong, right) -> bool``): for a
number, the same mistake computed another way (matrices instead of written-out terms, a relation such as
"the transpose of", "π/180 times"); for a formula string, sympy's value of the string at random coordinates
against the mistake computed with numpy matrices (:func:`planar_model`), or at least "differs from the right
answer" where the mistake is the string itself (a missing row).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from kinbook.book.tryits import get

from ..grading.tryits import newton_iterates

DEG = 180 / np.pi
c, s = np.cos, np.sin


@dataclass
class Answer:
    answer: object
    code: str                     # the name a teacher gives it
    confirm: object = None        # confirm(wrong, right) -> bool: the mistake, computed a second way
    also: tuple = ()              # another name a teacher would accept as just as true (reason in the comment)


@dataclass
class Case:
    id: str
    right: object
    wrong: list = field(default_factory=list)

    def __post_init__(self):
        """Each confirmation is computed here, with the section's values (its closures read names that later
        sections of the corpus reuse)."""
        self.unconfirmed = [a.code for a in self.wrong if not a.confirm(a.answer, self.right)]


def A(f):
    return np.array([[c(f), -s(f)], [s(f), c(f)]])


def B(f):
    return np.array([[-s(f), -c(f)], [c(f), -s(f)]])


def same(x):
    return lambda w, r: np.allclose(np.asarray(w, float), np.asarray(x, float), rtol=1e-9, atol=1e-12)


def rel(f):
    return lambda w, r: np.allclose(np.asarray(w, float), np.asarray(f(np.asarray(r, float)), float), rtol=1e-9,
                                    atol=1e-12)


# -------------------------------------------------------------------------------- planar formula strings
def pt(b, xi, eta, form="right", ang=None):
    """r_b + A(φ) s' written out, as a student types it; ``form`` is the one mistake."""
    f = f"phi{ang or b}"
    if form == "local":
        return f"x{b} + {xi}", f"y{b} + {eta}"
    if form == "At":
        return (f"x{b} + {xi}*cos({f}) + {eta}*sin({f})", f"y{b} - {xi}*sin({f}) + {eta}*cos({f})")
    if form == "sc":
        return (f"x{b} + {xi}*sin({f}) - {eta}*cos({f})", f"y{b} + {xi}*cos({f}) + {eta}*sin({f})")
    return (f"x{b} + {xi}*cos({f}) - {eta}*sin({f})", f"y{b} + {xi}*sin({f}) + {eta}*cos({f})")


def npt(q, b, xi, eta, form="right", ang=None):
    """The same point with numpy matrices — the second computation."""
    r, f, sv = np.array([q[f"x{b}"], q[f"y{b}"]]), q[f"phi{ang or b}"], np.array([xi, eta], float)
    if form == "local":
        return r + sv
    if form == "At":
        return r + A(f).T @ sv
    if form == "sc":
        return r + np.array([[s(f), -c(f)], [c(f), s(f)]]) @ sv
    return r + A(f) @ sv


_SYMS = "x1 y1 phi1 x2 y2 phi2 x3 y3 phi3 dphi1 dphi2 t".split()


def evaluate(rows, q):
    syms = {n: sp.Symbol(n) for n in _SYMS}
    out = []
    for row in np.atleast_1d(np.array(rows, dtype=object)).ravel():
        out.append(float(sp.sympify(row, locals=syms).subs({syms[k]: v for k, v in q.items()})))
    return np.array(out)


def points(seed=0, n=3):
    rng = np.random.default_rng(seed)
    return [dict(zip(_SYMS, rng.uniform(-2, 2, len(_SYMS)))) for _ in range(n)]


def planar_model(model):
    """confirm: the typed rows equal ``model(q)`` (numpy matrices) at random coordinates."""
    return lambda w, r: all(np.allclose(evaluate(w, q), np.ravel(model(q)), atol=1e-9) for q in points())


def differs():
    """confirm for a mistake that is the string itself (a missing row): the rows differ from the right ones."""
    def run(w, r):
        w, r = np.atleast_1d(np.array(w, dtype=object)).ravel(), np.atleast_1d(np.array(r, dtype=object)).ravel()
        return len(w) != len(r) or any(not np.allclose(evaluate(w, q), evaluate(r, q)) for q in points())
    return run


def rev(p1, p2):
    return [f"{p1[0]} - ({p2[0]})", f"{p1[1]} - ({p2[1]})"]


# =========================================================================================== chapter 13
def ch13():
    T = []
    # 13-1/try-1: A(120°)
    f = np.radians(120)
    R = A(f)
    T.append(Case("13-1/try-1", R, [
        Answer(R.T, "transposed", rel(lambda r: r.T)),
        Answer(np.array([[np.cos(120), -np.sin(120)], [np.sin(120), np.cos(120)]]), "degrees", same(A(120.0))),
        Answer(B(f), "B_for_A", rel(lambda r: r @ np.array([[0, -1], [1, 0]]))),
        Answer(np.array([[np.sin(f), -np.cos(f)], [np.cos(f), np.sin(f)]]), "sin_cos",
               same([[np.sqrt(3) / 2, 0.5], [-0.5, np.sqrt(3) / 2]])),
        Answer(A(np.radians(np.radians(120))), "radians_twice", same(A(120 * np.pi**2 / 180**2))),
        Answer(-R, "sign_flip", rel(lambda r: -r)),
        Answer([[-0.5, -0.866], [0.866, 0.5]], "sign_flip", same([[-0.5, -0.866], [0.866, 0.5]])),  # cos 120 by hand: + on the second
    ]))
    # 13-1/try-2: r^Q = r + A s'
    r, f, sv = np.array([1.5, -0.5]), np.radians(30), np.array([0.8, 0.3])
    ok = r + A(f) @ sv
    T.append(Case("13-1/try-2", [1.5 + 0.8 * np.cos(f) - 0.3 * np.sin(f), -0.5 + 0.8 * np.sin(f) + 0.3 * np.cos(f)], [
        Answer(r + A(f).T @ sv, "A_transposed", same([1.5 + 0.8 * c(f) + 0.3 * s(f), -0.5 - 0.8 * s(f) + 0.3 * c(f)])),
        Answer(r + sv, "local_vector", same([2.3, -0.2])),
        Answer(r + A(30) @ sv, "degrees", same([1.5 + 0.8 * c(30) - 0.3 * s(30), -0.5 + 0.8 * s(30) + 0.3 * c(30)])),
        Answer(A(f) @ sv, "missing_term", rel(lambda q: q - r)),
        Answer(r + A(np.radians(f)) @ sv, "radians_twice", same(r + A(30 * np.pi**2 / 180**2) @ sv)),
        Answer([1.5 + 0.8 * s(f) - 0.3 * c(f), -0.5 + 0.8 * c(f) + 0.3 * s(f)], "sin_cos",
               same(r + np.array([[0.5, -np.sqrt(3) / 2], [np.sqrt(3) / 2, 0.5]]) @ sv)),
        Answer(r + A(f) @ [0.8, -0.3], "sign_flip", rel(lambda q: q - 2 * A(f) @ [0, 0.3])),
        Answer(r - A(f) @ sv, "sign_flip", rel(lambda q: 2 * r - q)),
    ]))
    # 13-1/try-3: [v_Q, a_Q]
    rd, w, al = np.array([0.2, 0.0]), 2.0, -1.0
    v, a = rd + B(f) @ sv * w, B(f) @ sv * al - A(f) @ sv * w**2
    right = [0.2 - (0.8 * s(f) + 0.3 * c(f)) * w, (0.8 * c(f) - 0.3 * s(f)) * w,
             -(0.8 * s(f) + 0.3 * c(f)) * al - (0.8 * c(f) - 0.3 * s(f)) * w**2,
             (0.8 * c(f) - 0.3 * s(f)) * al - (0.8 * s(f) + 0.3 * c(f)) * w**2]
    cen = A(f) @ sv * w**2
    T.append(Case("13-1/try-3", right, [
        Answer(np.r_[v, B(f) @ sv * al], "missing_term", rel(lambda q: q + np.r_[0, 0, cen])),
        Answer(np.r_[v, B(f) @ sv * al + cen], "sign_flip", rel(lambda q: q + np.r_[0, 0, 2 * cen])),
        Answer(np.r_[rd + A(f) @ sv * w, a], "A_for_B", same(np.r_[0.2 + (0.8 * c(f) - 0.3 * s(f)) * 2,
                                                                  (0.8 * s(f) + 0.3 * c(f)) * 2, a])),
        Answer(np.r_[v, B(f) @ sv * al - A(f) @ sv * w], "missing_square", rel(lambda q: q + np.r_[0, 0, cen / 2])),
        Answer(np.r_[v, B(f) @ sv * w**2 - A(f) @ sv * al], "rate_exchanged",
               same(np.r_[v, B(f) @ sv * 4 + A(f) @ sv])),
        Answer(np.r_[B(f) @ sv * w, a], "missing_term", rel(lambda q: q - np.r_[rd, 0, 0])),
        Answer(np.r_[rd + B(30) @ sv * w, B(30) @ sv * al - A(30) @ sv * w**2], "degrees",
               same(np.r_[rd + B(30.0) @ sv * 2, -B(30.0) @ sv - A(30.0) @ sv * 4])),
        Answer(v, "missing_row", lambda q, r: len(q) == 2, also=("wrong_shape",)),   # the acceleration forgotten
    ]))
    # 13-2/try-1: revolute, A = (1, 0) on 1, (-1.5, 0.2) on 2
    p1, p2 = (1, 0), (-1.5, 0.2)

    def m(form="right", f1=None, f2=None, a1=None, a2=None, q2=None):
        return lambda q: npt(q, 1, *(q2 or p1), form=f1 or form, ang=a1) - npt(q, 2, *p2, form=f2 or form, ang=a2)

    T.append(Case("13-2/try-1", rev(pt(1, *p1), pt(2, *p2)), [
        Answer(rev(pt(1, *p2), pt(2, *p1)), "swapped_points",
               planar_model(lambda q: npt(q, 1, *p2) - npt(q, 2, *p1))),
        Answer(rev(pt(1, *p1), pt(2, -1.5, -0.2)), "sign_flip",
               planar_model(lambda q: npt(q, 1, *p1) - npt(q, 2, -1.5, -0.2))),
        Answer(rev(pt(1, *p1, "At"), pt(2, *p2, "At")), "A_transposed", planar_model(m("At"))),
        Answer(rev(pt(1, *p1, "local"), pt(2, *p2, "local")), "local_vector", planar_model(m("local"))),
        Answer(rev(pt(1, *p1, "sc"), pt(2, *p2, "sc")), "sin_cos", planar_model(m("sc"))),
        Answer(rev(pt(1, *p1), pt(2, *p2, ang=1)), "other_body", planar_model(m(a2=1))),
        Answer(rev(pt(1, *p1), pt(2, *p2))[:1], "missing_row", differs()),
        Answer([f"{pt(1, *p1)[0]} + {pt(2, *p2)[0]}", f"{pt(1, *p1)[1]} + {pt(2, *p2)[1]}"], "sign_flip",
               planar_model(lambda q: npt(q, 1, *p1) + npt(q, 2, *p2))),
    ]))
    # 13-2/try-2: translational, Q = (1, 0) on body 1, P = O_1, the line to O_2
    def tr(Q, second="phi1 - phi2", cross=True):
        xQ, yQ = Q
        first = (f"(x1 - ({xQ}))*(y2 - y1) - (y1 - ({yQ}))*(x2 - x1)" if cross else
                 f"(x1 - ({xQ}))*(x2 - x1) + (y1 - ({yQ}))*(y2 - y1)")
        return [first] if second is None else [first, second]

    def ntr(Q, ang=lambda q: q["phi1"] - q["phi2"], cross=True):
        def model(q):
            d = np.array([q["x1"], q["y1"]]) - Q(q)
            e = np.array([q["x2"] - q["x1"], q["y2"] - q["y1"]])
            return [d[0] * e[1] - d[1] * e[0] if cross else d @ e, ang(q)]
        return model

    T.append(Case("13-2/try-2", tr(pt(1, 1, 0)), [
        Answer(tr(pt(1, 1, 0), cross=False), "book_misprint",
               planar_model(ntr(lambda q: npt(q, 1, 1, 0), cross=False))),
        Answer(tr(pt(1, 1, 0), "phi1 + phi2"), "sign_flip",
               planar_model(ntr(lambda q: npt(q, 1, 1, 0), ang=lambda q: q["phi1"] + q["phi2"]))),
        Answer(tr(pt(1, 1, 0), None), "missing_row", differs()),
        Answer(tr(pt(1, 1, 0, "local")), "local_vector", planar_model(ntr(lambda q: npt(q, 1, 1, 0, "local")))),
        Answer(tr(pt(1, 1, 0, "sc")), "sin_cos", planar_model(ntr(lambda q: npt(q, 1, 1, 0, "sc")))),
        Answer(tr(pt(1, 1, 0, "At")), "A_transposed", planar_model(ntr(lambda q: npt(q, 1, 1, 0, "At")))),
        # Q's A written with φ2 is no wrong answer here: the row below (φ1 − φ2) makes the two the same joint,
        # and the checker rightly accepts it as an equivalent form
    ]))
    # 13-2/try-3: revolute-revolute, B = (2, 0) on 1, C = (0, 0.5) on 2, l = 3
    def rr(pB, pC, tail="- 3**2"):
        return [f"({pB[0]} - ({pC[0]}))**2 + ({pB[1]} - ({pC[1]}))**2 {tail}"]

    def nrr(B_, C_, l2=9.0, sq=True):
        def model(q):
            d = B_(q) - C_(q)
            return [d @ d - l2 if sq else d @ d - 3.0]
        return model

    b_, c_ = (2, 0), (0, 0.5)
    T.append(Case("13-2/try-3", rr(pt(1, *b_), pt(2, *c_)), [
        Answer(rr(pt(1, *b_), pt(2, *c_), "- 3"), "missing_square",
               planar_model(nrr(lambda q: npt(q, 1, *b_), lambda q: npt(q, 2, *c_), sq=False))),
        Answer(rr(pt(1, *b_), pt(2, 0, -0.5)), "sign_flip",
               planar_model(nrr(lambda q: npt(q, 1, *b_), lambda q: npt(q, 2, 0, -0.5)))),
        Answer(rr(pt(1, *b_, "At"), pt(2, *c_, "At")), "A_transposed",
               planar_model(nrr(lambda q: npt(q, 1, *b_, "At"), lambda q: npt(q, 2, *c_, "At")))),
        Answer(rr(pt(1, *b_, "local"), pt(2, *c_, "local")), "local_vector",
               planar_model(nrr(lambda q: npt(q, 1, *b_, "local"), lambda q: npt(q, 2, *c_, "local")))),
        Answer(rr(pt(1, *b_, "sc"), pt(2, *c_, "sc")), "sin_cos",
               planar_model(nrr(lambda q: npt(q, 1, *b_, "sc"), lambda q: npt(q, 2, *c_, "sc")))),
        Answer(rr(pt(1, *c_), pt(2, *b_)), "swapped_points",
               planar_model(nrr(lambda q: npt(q, 1, *c_), lambda q: npt(q, 2, *b_)))),
        Answer(rr(pt(1, *b_), pt(2, *c_), ""), "missing_term",
               planar_model(nrr(lambda q: npt(q, 1, *b_), lambda q: npt(q, 2, *c_), l2=0.0))),
    ]))
    # 13-3/try-1: the revolute at O_A: ground point at body 1's origin, (-1.2, 0.2) on body 2
    oa = (-1.2, 0.2)

    def g(form="right", point=oa, ang=None):
        return lambda q: np.array([q["x1"], q["y1"]]) - npt(q, 2, *point, form=form, ang=ang)

    T.append(Case("13-3/try-1", [f"{pt(2, *oa)[0]} - x1", f"{pt(2, *oa)[1]} - y1"], [
        Answer(rev(("x1", "y1"), pt(2, -1.2, -0.2)), "sign_flip", planar_model(g(point=(-1.2, -0.2)))),
        Answer(["x1 - x2 + 1.2", "y1 - y2 - 0.2"], "local_vector", planar_model(g("local"))),
        Answer(rev(("x1", "y1"), pt(2, *oa, "At")), "A_transposed", planar_model(g("At"))),
        Answer(rev(("x1", "y1"), pt(2, *oa, "sc")), "sin_cos", planar_model(g("sc"))),
        Answer(rev(("x1", "y1"), pt(2, *oa, ang=1)), "other_body", planar_model(g(ang=1))),
        Answer(rev(("x1", "y1"), pt(2, *oa))[1:], "missing_row", differs()),
        Answer(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], "wrong_data",     # O_A of the example printed above
               planar_model(g(point=(-1, 0)))),
    ]))
    # 13-3/try-2: Newton iterates at t = 0.005
    m3 = get("13-3/try-2").context()["m3"]
    t = 0.005

    def newton(step=1.0, n=8, time=t, degrees=False):
        return newton_iterates(m3, time, step, n, degrees=degrees)

    ok = newton()
    T.append(Case("13-3/try-2", ok, [
        Answer(newton(step=-1.0, n=4), "newton_step", lambda w, r: not np.allclose(w[1], r[1])),
        Answer(newton(n=1), "not_converged", lambda w, r: len(w) == 2),
        Answer(newton(time=0.0), "wrong_data", lambda w, r: np.abs(m3.Phi(w[-1], 0.0)).max() < 1e-9),
        Answer(newton(degrees=True), "degrees", lambda w, r: np.allclose(np.array(w)[1:, 2::3],
                                                                            np.array(r)[1:, 2::3] * DEG)),
        Answer(m3.solve_position(t), "wrong_shape", lambda w, r: np.ndim(w) == 1),
        Answer(newton(step=0.5, n=3), "newton_step", lambda w, r: not np.allclose(w[-1], r[-1])),
    ]))
    # 13-3/try-3: r^C = r_3 + A_3 s'^C, s'^C = (2, 0.5), at q1
    q1 = get("13-3/try-3").context()["q1"]
    r3, f3, sC = q1[6:8], q1[8], np.array([2.0, 0.5])
    T.append(Case("13-3/try-3", [r3[0] + 2 * c(f3) - 0.5 * s(f3), r3[1] + 2 * s(f3) + 0.5 * c(f3)], [
        Answer(r3 + A(f3).T @ sC, "A_transposed", same([r3[0] + 2 * c(f3) + 0.5 * s(f3), r3[1] - 2 * s(f3) + 0.5 * c(f3)])),
        Answer(r3 + sC, "local_vector", same([r3[0] + 2, r3[1] + 0.5])),
        Answer(r3 + A(f3) @ [2, -0.5], "sign_flip", rel(lambda q: q - 2 * A(f3) @ [0, 0.5])),
        Answer(r3 + A(f3 * DEG) @ sC, "degrees", same(r3 + A(np.degrees(f3)) @ sC)),
        Answer(r3 + A(np.radians(f3)) @ sC, "radians_twice", same(r3 + A(f3 * np.pi / 180) @ sC)),
        Answer(r3 + A(q1[5]) @ sC, "other_body", same(r3 + A(q1[5]) @ sC)),
        Answer(q1[3:5] + A(f3) @ sC, "other_body", rel(lambda q: q - r3 + q1[3:5])),
        Answer([r3[0] + 2 * s(f3) - 0.5 * c(f3), r3[1] + 2 * c(f3) + 0.5 * s(f3)], "sin_cos",
               same(r3 + np.array([[s(f3), -c(f3)], [c(f3), s(f3)]]) @ sC)),
        Answer(A(f3) @ sC, "missing_term", rel(lambda q: q - r3)),
    ]))
    # 13-4/try-1: the gear row, ρ_1 = 3, ρ_3 = 1, carrier 2
    gear = lambda q: 3 * (q["phi1"] - q["phi2"]) + 1 * (q["phi3"] - q["phi2"])  # noqa: E731
    T.append(Case("13-4/try-1", ["3*phi1 - 4*phi2 + phi3"], [
        Answer(["3*phi1 + phi3"], "missing_term", planar_model(lambda q: [3 * q["phi1"] + q["phi3"]])),
        Answer(["1*(phi1 - phi2) + 3*(phi3 - phi2)"], "swapped_bodies",
               planar_model(lambda q: [(q["phi1"] - q["phi2"]) + 3 * (q["phi3"] - q["phi2"])])),
        Answer(["3*(phi1 - phi2) - (phi3 - phi2)"], "sign_flip",
               planar_model(lambda q: [gear(q) - 2 * (q["phi3"] - q["phi2"])])),
        Answer(["2*phi1 - 3*phi2 + phi3"], "wrong_data",   # ρ_1 = 2, ρ_3 = 1: the train printed above
               planar_model(lambda q: [2 * (q["phi1"] - q["phi2"]) + (q["phi3"] - q["phi2"])])),
        Answer(["3*phi1 - 3*phi2 + phi3"], "missing_term", planar_model(lambda q: [gear(q) + q["phi2"]])),
        Answer(["3*phi1 - 4*phi2 - phi3"], "sign_flip", planar_model(lambda q: [gear(q) - 2 * q["phi3"]])),
    ]))
    # 13-4/try-2: ω_3 = ω_arm (1 + ρ_1/ρ_3)
    wa, r1, r3_ = 1.5, 2.5, 1.0
    ok = wa + wa * r1 / r3_
    T.append(Case("13-4/try-2", ok, [
        Answer(wa * r1 / r3_, "relative_speed", rel(lambda x: x - wa)),
        Answer(wa * (1 - r1 / r3_), "sign_flip", rel(lambda x: x - 2 * wa * r1 / r3_)),
        Answer(-ok, "sign_flip", rel(lambda x: -x)),
        Answer(ok * DEG, "degrees", rel(lambda x: x * 180 / np.pi)),
        Answer(wa * (1 + r3_ / r1), "swapped_bodies", same(1.5 * 1.4)),
        Answer(5.3, "not_rounded", same(5.3)),   # 5.25 rounded to one decimal by hand
    ]))
    # 13-4/try-3: rack: Δx = ρ Δφ, in radians
    T.append(Case("13-4/try-3", 1 * np.radians(90), [
        Answer(90.0, "degrees", rel(lambda x: x * DEG)),
        Answer(-np.pi / 2, "sign_flip", rel(lambda x: -x)),
        Answer(np.radians(np.radians(90)), "radians_twice", rel(lambda x: x * np.pi / 180)),
        Answer(np.pi, "scaled", rel(lambda x: 2 * x)),
    ]))
    # 13-5/try-1: Φ_q of the ground revolute x1 − (x2 + ξ cos φ2 − η sin φ2), ξ = −1, η = 0
    J = [["1", "0", "0", "-1", "0", "-sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]]
    T.append(Case("13-5/try-1", J, [
        Answer([["1", "0", "0", "-1", "0", "0"], ["0", "1", "0", "0", "-1", "0"]], "missing_chain_rule", differs()),
        Answer([["1", "0", "0", "-1", "0", "cos(phi2)"], ["0", "1", "0", "0", "-1", "sin(phi2)"]], "A_for_B",
               differs()),
        Answer([["1", "0", "0", "-1", "0", "sin(phi2)"], ["0", "1", "0", "0", "-1", "-cos(phi2)"]], "sign_flip",
               differs()),
        Answer([list(col) for col in zip(*J)], "transposed", lambda w, r: len(w) == 6),
        Answer(J[:1], "missing_row", differs()),
        Answer([["1", "0", "-sin(phi2)", "-1", "0", "0"], ["0", "1", "cos(phi2)", "0", "-1", "0"]], "swapped_entries",
               differs()),   # the derivative put in body 1's φ column
    ]))
    # 13-5/try-2: Φ_q of the distance row, ξ_2^A = 1, ξ_3^B = −1.5
    dx, dy = "(x2 + cos(phi2) - x3 - (-1.5)*cos(phi3))", "(y2 + sin(phi2) - y3 - (-1.5)*sin(phi3))"
    j8 = [f"2*{dx}", f"2*{dy}", f"2*{dx}*(-sin(phi2)) + 2*{dy}*cos(phi2)", f"-2*{dx}", f"-2*{dy}",
          f"2*{dx}*(-1.5)*sin(phi3) - 2*{dy}*(-1.5)*cos(phi3)"]
    T.append(Case("13-5/try-2", [j8], [
        Answer([[e if k in (0, 1, 3, 4) else "0" for k, e in enumerate(j8)]], "book_misprint", differs()),
        Answer([[f"0.5*({e})" for e in j8]], "scaled", differs()),
        Answer([[e if k < 3 else f"-({e})" for k, e in enumerate(j8)]], "sign_flip", differs()),
        Answer([[f"{dx}", f"{dy}", f"{dx}*(-sin(phi2)) + {dy}*cos(phi2)", f"-{dx}", f"-{dy}",
                 f"{dx}*(-1.5)*sin(phi3) - {dy}*(-1.5)*cos(phi3)"]], "scaled", differs(),
               also=("factor_2_missing",)),    # the 2 of ∂(dᵀd)/∂q = 2dᵀ∂d/∂q forgotten
        Answer([j8[:2] + [f"2*{dx}*cos(phi2) + 2*{dy}*sin(phi2)"] + j8[3:]], "A_for_B", differs()),
        Answer([j8[:5] + [f"2*{dx}*(-1.5)*sin(phi2) - 2*{dy}*(-1.5)*cos(phi2)"]], "other_body", differs()),
    ]))
    # 13-5/try-3: the entry (8, 8) of Φ_q at t = 0.004 (corrected Table 13.3)
    mech = get("13-5/try-3").context()["mech"]
    qt = mech.solve_position(0.004)
    rA, rB = mech.point_position(qt, "crank", "A"), mech.point_position(qt, "rocker", "B")
    d, arm = rA - rB, rB - qt[6:8]
    J88 = 2 * d[0] * arm[1] - 2 * d[1] * arm[0]
    T.append(Case("13-5/try-3", J88, [
        Answer(0.0, "book_misprint", same(0.0)),
        Answer(-J88, "sign_flip", rel(lambda x: -x)),
        Answer(J88 / 2, "scaled", rel(lambda x: x / 2)),
        Answer(-2 * d @ arm, "A_for_B", same(-2 * d @ (A(qt[8]) @ (A(qt[8]).T @ arm)))),
        Answer(2 * d[0] * rB[1] - 2 * d[1] * (rB[0] - 3.0), "lever_arm",   # arm from the rocker's pivot O_B = (3, 0)
               same(2 * d @ np.array([rB[1], -(rB[0] - 3.0)]))),
        Answer(2 * d[0] * (rA[1] - qt[4]) - 2 * d[1] * (rA[0] - qt[3]), "other_body",
               same(-2 * d @ (B(qt[5]) @ (A(qt[5]).T @ (rA - qt[3:5]))))),
    ]))
    # 13-6/try-1: ν with φ_2 = 3π/4 + 100 t + ½ 500 t²
    T.append(Case("13-6/try-1", ["0"] * 8 + ["100 + 500*t"], [
        Answer(["0"] * 8 + ["-100 - 500*t"], "nu_sign", differs()),
        Answer(["0"] * 9, "nu_missing", differs()),
        Answer(["0"] * 8 + [f"{100 * DEG} + {500 * DEG}*t"], "degrees", differs()),
        Answer(["0"] * 8 + ["100"], "wrong_data", differs()),   # the book's constant-speed driver, printed above
        Answer(["0"] * 8 + ["100 + 250*t"], "factor_2_missing", differs()),   # the ½ of ½αt² kept
        Answer(["0"] * 8 + ["500*t"], "missing_term", differs()),
        Answer(["0"] * 8 + ["100*t + 250*t**2"], "missing_chain_rule", differs()),  # Φ^d not derived: nothing in the catalogue
    ]))
    # 13-6/try-2: speed of D, |O_B D| = 2
    ctx = get("13-6/try-3").context()
    q0, qd0 = ctx["q0"], ctx["qd0"]
    w3 = qd0[8]
    T.append(Case("13-6/try-2", 2 * abs(w3), [
        Answer(3 * abs(w3), "wrong_data", rel(lambda x: 1.5 * x)),
        Answer(2 * abs(w3) * DEG, "degrees", rel(lambda x: x * DEG)),
        Answer(2 * w3 if w3 < 0 else -2 * w3, "sign_flip", rel(lambda x: -x)),
        Answer(2 * abs(qd0[5]), "other_body", same(2 * 100.0),
               also=("wrong_data",)),   # named as the crank's speed printed above, whose detail says "with φ̇_2"
        Answer(2 * w3**2, "missing_square", same(2 * abs(w3) * abs(w3))),
        Answer(round(2 * abs(w3) * 2, 1), "scaled", lambda x, r: abs(x / r - 2) < 0.01),   # the diameter, by hand
    ]))
    # 13-6/try-3: v^C = ṙ_3 + B_3 s'^C φ̇_3
    sC3, f3, rd3 = np.array([0.5, 0.4]), q0[8], qd0[6:8]
    v = rd3 + B(f3) @ sC3 * w3
    T.append(Case("13-6/try-3", [rd3[0] - (0.5 * s(f3) + 0.4 * c(f3)) * w3, rd3[1] + (0.5 * c(f3) - 0.4 * s(f3)) * w3], [
        Answer(rd3 + A(f3) @ sC3 * w3, "A_for_B", rel(lambda x: rd3 + np.array([[0, 1], [-1, 0]]) @ (x - rd3))),
        Answer(rd3 - B(f3) @ sC3 * w3, "sign_flip", rel(lambda x: 2 * rd3 - x)),
        Answer(B(f3) @ sC3 * w3, "missing_term", rel(lambda x: x - rd3)),
        Answer(rd3 + B(q0[5]) @ sC3 * w3, "other_body", same(rd3 + B(q0[5]) @ sC3 * qd0[8])),
        Answer(rd3 + B(f3) @ sC3 * qd0[5], "other_body", same(rd3 + B(f3) @ sC3 * 100.0)),
        Answer(rd3 + B(np.radians(f3)) @ sC3 * w3, "radians_twice", same(rd3 + B(f3 / DEG) @ sC3 * w3)),
        Answer([rd3[0] - (0.5 * c(f3) + 0.4 * s(f3)) * w3, rd3[1] + (0.5 * s(f3) - 0.4 * c(f3)) * w3], "sin_cos",
               same(rd3 + np.array([[-c(f3), -s(f3)], [s(f3), -c(f3)]]) @ sC3 * w3)),
        Answer(rd3 + B(f3) @ [0.5, -0.4] * w3, "sign_flip", rel(lambda x: x - 2 * B(f3) @ [0, 0.4] * w3)),
    ]))
    # 13-7/try-1: γ of the ground revolute, O_A = (−1, 0.3) on body 2
    gx, gy = "(-1.0*cos(phi2) - 0.3*sin(phi2))", "(-1.0*sin(phi2) + 0.3*cos(phi2))"

    def gam(form="right", k=2, sign=-1.0, ang=None):
        return lambda q: sign * (npt(q, 2, -1.0, 0.3, form=form, ang=ang) - [q["x2"], q["y2"]]) * q["dphi2"] ** k

    T.append(Case("13-7/try-1", [f"-{gx}*dphi2**2", f"-{gy}*dphi2**2"], [
        Answer([f"{gx}*dphi2**2", f"{gy}*dphi2**2"], "gamma_sign", planar_model(gam(sign=1.0))),
        Answer([f"-{gx}*dphi2", f"-{gy}*dphi2"], "missing_square", planar_model(gam(k=1))),
        Answer([f"-{gy}*dphi2**2", f"-{gx}*dphi2**2"], "row_order", planar_model(lambda q: gam()(q)[::-1]),
               also=("swapped_entries",)),   # the two rows written in the other order
        Answer(["-(-1.0*sin(phi2) - 0.3*cos(phi2))*dphi2**2", "-(-1.0*cos(phi2) + 0.3*sin(phi2))*dphi2**2"], "sin_cos",
               planar_model(gam("sc"))),
        Answer(["-(-1.0*cos(phi2) + 0.3*sin(phi2))*dphi2**2", "-(1.0*sin(phi2) + 0.3*cos(phi2))*dphi2**2"],
               "A_transposed", planar_model(gam("At"))),
        Answer([f"-{gx}*dphi2**2"], "missing_row", differs()),
        Answer([f"-{gx}*dphi1**2", f"-{gy}*dphi1**2"], "other_body",
               planar_model(lambda q: -(npt(q, 2, -1.0, 0.3) - [q["x2"], q["y2"]]) * q["dphi1"] ** 2)),
    ]))
    # 13-7/try-2: γ_8 at t = 0.004
    mech = get("13-7/try-2").context()["mech"]
    tg = 0.004
    q = mech.solve_position(tg)
    qd = mech.solve_velocity(q, tg)
    vA, vB = mech.point_velocity(q, qd, "crank", "A"), mech.point_velocity(q, qd, "rocker", "B")
    rA, rB = mech.point_position(q, "crank", "A"), mech.point_position(q, "rocker", "B")
    cA = -A(q[5]) @ (A(q[5]).T @ (rA - q[3:5])) * qd[5] ** 2          # the centripetal parts, −A s' φ̇²
    cB = -A(q[8]) @ (A(q[8]).T @ (rB - q[6:8])) * qd[8] ** 2
    t1, t2 = -2 * (vA - vB) @ (vA - vB), -2 * (rA - rB) @ (cA - cB)
    T.append(Case("13-7/try-2", t1 + t2, [
        Answer(-(t1 + t2), "gamma_sign", rel(lambda x: -x)),
        Answer(t1 / 2 + t2, "scaled", rel(lambda x: x - t1 / 2), also=("factor_2_missing",)),
        Answer(t1, "missing_term", rel(lambda x: x - t2)),
        Answer(t1 - t2, "sign_flip", rel(lambda x: x - 2 * t2)),
        Answer(t2, "missing_term", rel(lambda x: x - t1)),
        Answer((t1 + t2) / 2, "scaled", rel(lambda x: x / 2)),
    ]))
    # 13-7/try-3: a^C = r̈_3 + B s' φ̈_3 − A s' φ̇_3²
    qdd0 = get("13-7/try-3").context()["qdd0"]
    rdd3, a3 = qdd0[6:8], qdd0[8]
    cen = A(f3) @ sC3 * w3**2
    ok = rdd3 + B(f3) @ sC3 * a3 - cen
    T.append(Case("13-7/try-3", ok, [
        Answer(ok + cen, "missing_term", rel(lambda x: x + cen)),
        Answer(ok + 2 * cen, "sign_flip", rel(lambda x: x + 2 * cen)),
        Answer(rdd3 + B(f3) @ sC3 * a3 - A(f3) @ sC3 * w3, "missing_square", rel(lambda x: x + cen - cen / w3)),
        Answer(rdd3 + B(f3) @ sC3 * w3**2 - A(f3) @ sC3 * a3, "rate_exchanged", same(
            rdd3 + B(f3) @ sC3 * qd0[8] ** 2 - A(f3) @ sC3 * qdd0[8])),
        Answer(B(f3) @ sC3 * a3 - cen, "missing_term", rel(lambda x: x - rdd3)),
        Answer(rdd3 + B(q0[5]) @ sC3 * a3 - A(q0[5]) @ sC3 * w3**2, "other_body", same(
            rdd3 + B(q0[5]) @ sC3 * qdd0[8] - A(q0[5]) @ sC3 * qd0[8] ** 2)),
        Answer(rdd3 + B(np.radians(f3)) @ sC3 * a3 - A(np.radians(f3)) @ sC3 * w3**2, "radians_twice",
               same(rdd3 + B(f3 / DEG) @ sC3 * a3 - A(f3 / DEG) @ sC3 * w3**2)),
    ]))
    return T


# =========================================================================================== chapter 14
def Rz(a):
    return np.array([[c(a), -s(a), 0], [s(a), c(a), 0], [0, 0, 1.0]])


def Rx(a):
    return np.array([[1.0, 0, 0], [0, c(a), -s(a)], [0, s(a), c(a)]])


def tilde(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]], float)


def sym_model(model):
    """confirm for a sympy answer: it equals ``model()`` (sympy matrices built another way) identically."""
    return lambda w, r: sp.simplify(sp.Matrix(w) - sp.Matrix(model())) == sp.zeros(*sp.Matrix(w).shape)


def sym_differs():
    def run(w, r):
        w, r = sp.Matrix(w), sp.Matrix(r)
        if w.shape != r.shape:
            return True
        syms = sorted(w.free_symbols | r.free_symbols, key=str)
        rng = np.random.default_rng(1)
        vals = dict(zip(syms, rng.uniform(-1, 1, len(syms))))
        return not np.allclose(np.array(w.subs(vals), float), np.array(r.subs(vals), float))
    return run


def ch14():
    from kinbook.spatial import rotations as R

    T = []
    # 14-1/try-1: A from the body's axes (columns)
    axes = [[0, 0.6, 0.8], [0, -0.8, 0.6], [1, 0, 0]]
    Ax = np.array(axes, float).T
    typo = Ax.copy()
    typo[1, 0] = 0.8                                              # 0.6 typed as 0.8
    T.append(Case("14-1/try-1", np.column_stack(axes), [
        Answer(np.array(axes, float), "transposed", rel(lambda r: r.T)),
        Answer(np.column_stack([axes[0], axes[1], [-1, 0, 0]]), "left_handed", lambda w, r: np.linalg.det(w) < 0),
        Answer(typo, "not_orthogonal", lambda w, r: not np.allclose(w.T @ w, np.eye(3))),
        Answer(np.column_stack([axes[2], axes[0], axes[1]]), "swapped_entries",
               lambda w, r: np.allclose(np.linalg.det(w), 1)),    # the axes in the order ζ, ξ, η: still a rotation
        Answer(np.column_stack(axes[:2]), "wrong_shape", lambda w, r: np.shape(w) == (3, 2)),
    ]))
    # 14-1/try-2: s' = Aᵀ s
    sg = np.array([2.0, 1.0, -1.0])
    T.append(Case("14-1/try-2", [np.dot(axes[0], sg), np.dot(axes[1], sg), np.dot(axes[2], sg)], [
        Answer(Ax @ sg, "A_for_AT", same(np.array(axes).T @ sg)),
        Answer(-Ax.T @ sg, "sign_flip", rel(lambda r: -r)),
        Answer(sg, "wrong_frame", same([2, 1, -1])),
        Answer(np.linalg.solve(Ax.T, sg), "A_for_AT", same(Ax @ sg)),   # "Aᵀ⁻¹" typed for Aᵀ
        Answer([0.6 + (-0.8), -1.6 + -0.6, 2.0], "sign_flip",
               same([-0.2, -2.2, 2.0])),     # by hand, one sign lost in the second component
    ]))
    # 14-1/try-3: r^Q = r + A s'^Q
    r0, sQ = np.array([0.5, -1.0, 2.0]), np.array([0.4, 0.0, 1.5])
    T.append(Case("14-1/try-3", r0 + 0.4 * np.array(axes[0]) + 1.5 * np.array(axes[2]), [
        Answer(r0 + Ax.T @ sQ, "A_transposed", same(r0 + np.array(axes) @ sQ)),
        Answer(r0 + sQ, "local_vector", same([0.9, -1.0, 3.5])),
        Answer(Ax @ (r0 + sQ), "wrong_frame", same(Ax @ [0.9, -1.0, 3.5])),
        Answer(Ax @ sQ, "missing_term", rel(lambda r: r - r0)),
        Answer(r0 - Ax @ sQ, "sign_flip", rel(lambda r: 2 * r0 - r)),
    ]))
    # 14-2/try-1: A(ψ, θ, φ) = Rz(ψ) Rx(θ) Rz(φ)
    ps, th, ph = np.radians([40.0, 25.0, -60.0])
    A2 = Rz(ps) @ Rx(th) @ Rz(ph)
    Rxneg = lambda a: Rx(a).T  # noqa: E731
    T.append(Case("14-2/try-1", A2, [
        Answer(Rz(ph) @ Rx(th) @ Rz(ps), "extrinsic_order", same(Rz(np.radians(-60)) @ Rx(th) @ Rz(np.radians(40)))),
        Answer(A2.T, "transposed", rel(lambda r: r.T)),
        Answer(Rz(40.0) @ Rx(25.0) @ Rz(-60.0), "degrees", same(Rz(40) @ Rx(25) @ Rz(-60))),
        Answer(Rz(np.radians(ps)) @ Rx(np.radians(th)) @ Rz(np.radians(ph)), "radians_twice",
               same(Rz(40 * np.pi**2 / 180**2) @ Rx(25 * np.pi**2 / 180**2) @ Rz(-60 * np.pi**2 / 180**2))),
        Answer(Rz(ps) @ Rxneg(th) @ Rz(ph), "sign_flip", same(Rz(ps) @ Rx(-th) @ Rz(ph))),
        Answer(Rz(ps) @ np.array([[1, 0, 0], [0, s(th), -c(th)], [0, c(th), s(th)]]) @ Rz(ph), "sin_cos",
               same(Rz(ps) @ Rx(np.pi / 2 - th) @ np.diag([1, 1, 1]) @ Rz(ph) if False else
                    Rz(ps) @ np.array([[1, 0, 0], [0, c(np.pi / 2 - th), -s(np.pi / 2 - th)],
                                       [0, s(np.pi / 2 - th), c(np.pi / 2 - th)]]) @ Rz(ph))),
    ]))
    # 14-2/try-2: ω' from the Euler-angle rates
    pr, tr_, fr = 2.0, 0.5, -1.0
    wb = np.array([s(th) * s(ph) * pr + c(ph) * tr_, s(th) * c(ph) * pr - s(ph) * tr_, c(th) * pr + fr])
    T.append(Case("14-2/try-2", wb, [
        Answer(A2 @ wb, "wrong_frame", lambda w, r: np.allclose(A2.T @ w, r)),
        Answer([pr, tr_, fr], "angle_rates", same([2.0, 0.5, -1.0])),
        Answer([s(25.0) * s(-60.0) * pr + c(-60.0) * tr_, s(25.0) * c(-60.0) * pr - s(-60.0) * tr_, c(25.0) * pr + fr],
               "degrees", same(np.array([s(25) * s(-60) * 2 + c(-60) * 0.5, s(25) * c(-60) * 2 - s(-60) * 0.5,
                                         c(25) * 2 - 1]))),
        Answer([s(th) * s(ph) * pr - c(ph) * tr_, s(th) * c(ph) * pr + s(ph) * tr_, c(th) * pr + fr], "sign_flip",
               rel(lambda r: r - 2 * tr_ * np.array([c(ph), -s(ph), 0]))),    # the θ̇ terms' sign
        Answer([s(th) * c(ph) * pr + s(ph) * tr_, s(th) * s(ph) * pr - c(ph) * tr_, c(th) * pr + fr], "sin_cos",
               same([s(th) * s(np.pi / 2 - ph) * pr + c(np.pi / 2 - ph) * tr_,
                     s(th) * c(np.pi / 2 - ph) * pr - s(np.pi / 2 - ph) * tr_, c(th) * pr + fr])),
        Answer([s(th) * s(ph) * pr + c(ph) * tr_, s(th) * c(ph) * pr - s(ph) * tr_, c(th) * pr], "missing_term",
               rel(lambda r: r - [0, 0, fr])),
        Answer([s(th) * s(ps) * pr + c(ps) * tr_, s(th) * c(ps) * pr - s(ps) * tr_, c(th) * pr + fr], "swapped_entries",
               same([s(th) * s(ps) * 2 + c(ps) * 0.5, s(th) * c(ps) * 2 - s(ps) * 0.5, c(th) * 2 - 1]),
               also=("other_body",)),    # ψ written where φ belongs (the wrong angle)
    ]))
    # 14-2/try-3: Euler angles of A_given
    Ag = np.array([[2.0, 2.0, -1.0], [-1.0, 2.0, 2.0], [2.0, -1.0, 2.0]]) / 3
    ang = np.array([np.arctan2(Ag[0, 2], -Ag[1, 2]), np.arccos(Ag[2, 2]), np.arctan2(Ag[2, 0], Ag[2, 1])])
    T.append(Case("14-2/try-3", ang, [
        Answer(ang * DEG, "degrees", rel(lambda r: np.degrees(r))),
        Answer(ang[::-1].copy(), "extrinsic_order", rel(lambda r: r[::-1])),
        Answer([np.arctan2(Ag[2, 0], -Ag[2, 1]), np.arccos(Ag[2, 2]), np.arctan2(Ag[0, 2], Ag[1, 2])], "transposed",
               lambda w, r: np.allclose(Rz(w[0]) @ Rx(w[1]) @ Rz(w[2]), Ag.T)),
        Answer([np.arctan(Ag[0, 2] / -Ag[1, 2]), ang[1], np.arctan(Ag[2, 0] / Ag[2, 1])], "arctan_quadrant",
               lambda w, r: np.allclose(np.tan(w), np.tan(r)) and not np.allclose(w, r)),
        Answer([ang[0], np.radians(ang[1]), ang[2]], "radians_twice", lambda w, r: np.isclose(w[1], r[1] / DEG)),
        Answer([np.arctan2(Ag[0, 2], Ag[1, 2]), ang[1], ang[2]], "sign_flip",
               lambda w, r: np.isclose(np.tan(w[0]), -np.tan(r[0]))),
    ]))
    # 14-3/try-1: p for χ = 120° about u = (0, 1, 1)
    u, chi = np.array([0.0, 1.0, 1.0]) / np.sqrt(2), np.radians(120)
    p = np.r_[c(chi / 2), u * s(chi / 2)]
    T.append(Case("14-3/try-1", p, [
        Answer(np.r_[c(chi), u * s(chi)], "full_angle", same([-0.5, 0, np.sqrt(3) / 2 / np.sqrt(2), np.sqrt(3) / 2 / np.sqrt(2)])),
        Answer(np.r_[c(60.0), u * s(60.0)], "degrees", same(np.r_[np.cos(60), u * np.sin(60)])),
        Answer(np.r_[p[1:], p[0]], "scalar_last", rel(lambda r: np.roll(r, -1))),
        Answer(np.r_[c(chi / 2), np.array([0, 1, 1]) * s(chi / 2)], "not_normalized", lambda w, r: abs(w @ w - 1) > 0.1),
        Answer(np.r_[s(chi / 2), u * c(chi / 2)], "sin_cos", same([np.sqrt(3) / 2, 0, 0.5 / np.sqrt(2), 0.5 / np.sqrt(2)])),
        Answer(np.r_[c(np.radians(chi) / 2), u * s(np.radians(chi) / 2)], "radians_twice",
               same(np.r_[c(120 * np.pi**2 / 180**2 / 2), u * s(120 * np.pi**2 / 180**2 / 2)])),
        Answer([0.5, 0, 0.61, 0.61], "not_rounded", same([0.5, 0, 0.61, 0.61]),
               also=("not_normalized",)),   # sin 60°/√2 = 0.612 rounded by hand to 2 digits: |p| ≠ 1
    ]))
    # 14-3/try-2: A(p) for p = (½, ½, ½, ½)
    e0, e = 0.5, np.array([0.5, 0.5, 0.5])
    Ap = 2 * ((e0**2 - 0.5) * np.eye(3) + np.outer(e, e) + e0 * tilde(e))
    T.append(Case("14-3/try-2", [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [
        Answer(Ap / 2, "factor_2_missing", rel(lambda r: r / 2)),
        Answer(Ap.T, "transposed", rel(lambda r: r.T)),
        Answer(2 * (e0**2 * np.eye(3) + np.outer(e, e) + e0 * tilde(e)), "missing_term", rel(lambda r: r + np.eye(3))),
        Answer(2 * ((e0**2 - 0.5) * np.eye(3) + np.outer(e, e) - e0 * tilde(e)), "transposed",
               rel(lambda r: r.T), also=("sign_flip",)),           # ẽ's sign: the same as Aᵀ
        Answer([[e0**2 + e[0]**2 - 0.5, e[0] * e[1] - e0 * e[2], e[0] * e[2] - e0 * e[1]],
                [e[0] * e[1] - e0 * e[2], e0**2 + e[1]**2 - 0.5, e[1] * e[2] - e0 * e[0]],
                [e[0] * e[2] - e0 * e[1], e[1] * e[2] - e0 * e[0], e0**2 + e[2]**2 - 0.5]], "book_misprint",
               same([[0, 0, 0], [0, 0, 0], [0, 0, 0]])),
    ]))
    # 14-3/try-3: ω = 2 E ṗ
    pd = np.array([-0.1, 0.3, -0.1, -0.1])
    Em = np.column_stack([-e, tilde(e) + e0 * np.eye(3)])
    Gm = np.column_stack([-e, -tilde(e) + e0 * np.eye(3)])
    T.append(Case("14-3/try-3", 2 * Em @ pd, [
        Answer(2 * Gm @ pd, "G_for_E", same(2 * Gm @ pd)),
        Answer(Em @ pd, "factor_2_missing", rel(lambda r: r / 2)),
        Answer(2 * np.column_stack([e, tilde(e) + e0 * np.eye(3)]) @ pd, "sign_flip", rel(lambda r: r + 4 * e * pd[0])),
        Answer(2 * (tilde(e) + e0 * np.eye(3)) @ pd[1:], "missing_term", rel(lambda r: r + 2 * e * pd[0])),
        Answer(pd[1:], "angle_rates", same([0.3, -0.1, -0.1]), also=("missing_term",)),   # ṗ's vector part as ω
    ]))
    # 14-4/try-1: spherical joint
    qi = sp.symbols("x1 y1 z1 e01 e11 e21 e31", real=True)
    qj = sp.symbols("x2 y2 z2 e02 e12 e22 e32", real=True)
    Ai, Aj = R.A_from_p(list(qi[3:])), R.A_from_p(list(qj[3:]))
    si, sj = sp.Matrix([0, 0, 1]), sp.Matrix([-1, sp.Rational(1, 2), 0])
    ri, rj = sp.Matrix(qi[:3]), sp.Matrix(qj[:3])
    ok = ri + Ai * si - rj - Aj * sj

    def A_of(p):                 # A(p) written out, the second computation
        e0_, e1_, e2_, e3_ = p
        ev = sp.Matrix([e1_, e2_, e3_])
        et = sp.Matrix([[0, -e3_, e2_], [e3_, 0, -e1_], [-e2_, e1_, 0]])
        return 2 * ((e0_**2 - sp.Rational(1, 2)) * sp.eye(3) + ev * ev.T + e0_ * et)

    Bi, Bj = A_of(qi[3:]), A_of(qj[3:])
    T.append(Case("14-4/try-1", ok, [
        Answer(ri + Ai.T * si - rj - Aj.T * sj, "A_transposed", sym_model(lambda: ri + Bi.T * si - rj - Bj.T * sj)),
        Answer(ri + si - rj - sj, "local_vector", sym_model(lambda: ri - rj + sp.Matrix([1, sp.Rational(-1, 2), 1]))),
        Answer(ri + Ai * si - rj + Aj * sj, "sign_flip", sym_model(lambda: ri + Bi * si - rj + Bj * sj)),
        Answer(ri + Ai * sj - rj - Aj * si, "swapped_points", sym_model(lambda: ri + Bi * sj - rj - Bj * si)),
        Answer(ok[:2, :], "missing_row", sym_differs()),
        Answer(ri + Aj * si - rj - Ai * sj, "other_body", sym_model(lambda: ri + Bj * si - rj - Bi * sj)),
    ]))
    # 14-4/try-2: Φ_q of the n1 row s_iᵀ s_j
    pi_, pj_ = sp.Matrix(qi[3:]), sp.Matrix(qj[3:])
    li, lj = sp.Matrix([0, 0, 1]), sp.Matrix([1, 0, 0])
    gi, gj = R.A_from_p(pi_) * li, R.A_from_p(pj_) * lj
    row = sp.Matrix([(gi.T * gj)[0]]).jacobian(list(qi) + list(qj))
    Ci = 2 * (R.E(pi_) * R.a_bar(li) + li * pi_.T)
    Cj = 2 * (R.E(pj_) * R.a_bar(lj) + lj * pj_.T)
    Z = sp.zeros(1, 3)
    T.append(Case("14-4/try-2", sp.Matrix.hstack(Z, gj.T * Ci, Z, gi.T * Cj), [
        Answer(sp.Matrix.hstack(Z, gj.T * 2 * R.E(pi_) * R.a_bar(li), Z, gi.T * 2 * R.E(pj_) * R.a_bar(lj)),
               "eg_jacobian", sym_differs()),
        Answer(sp.zeros(1, 14), "missing_chain_rule", sym_differs()),
        Answer(row.T, "transposed", lambda w, r: sp.Matrix(w).shape == (14, 1)),
        Answer(sp.Matrix.hstack(Z, gi.T * Ci, Z, gj.T * Cj), "own_arm", sym_differs()),
        Answer(sp.Matrix.hstack(Z, gj.T * Ci / 2, Z, gi.T * Cj / 2), "factor_2_missing", sym_differs(),
               also=("scaled",)),
        Answer(sp.Matrix.hstack(Z, gj.T * Ci, Z, -gi.T * Cj), "sign_flip", sym_differs()),
    ]))
    # 14-4/try-3: the hinge, P at (1.2, 0, 0) on i, the axes along ζ
    ax_i, ax_j = sp.Matrix([0, 0, sp.Rational(4, 5)]), sp.Matrix([0, 0, sp.Rational(1, 2)])
    Pl = sp.Matrix([sp.Rational(6, 5), 0, 0])
    ball = ri + Ai * Pl - rj
    cross = R.skew(list(ax_i)) * Ai.T * Aj * ax_j
    T.append(Case("14-4/try-3", ball.col_join(cross[:2, :]), [
        Answer(ball.col_join(cross), "extra_row", lambda w, r: sp.Matrix(w).shape == (6, 1)),
        Answer((ri + Pl - rj).col_join(cross[:2, :]), "local_vector", sym_differs()),
        Answer((ri + Ai.T * Pl - rj).col_join(cross[:2, :]), "A_transposed", sym_differs()),
        Answer(ball.col_join(cross[1:, :]), "zero_row",
               lambda w, r: sp.simplify(sp.Matrix(w)[4]) == 0),   # rows 2-3 of s_i × s_j in i's frame: the third ≡ 0
        Answer(ball.col_join(cross[:1, :]), "missing_row", lambda w, r: sp.Matrix(w).shape == (4, 1)),
        Answer((ri + Ai * Pl + rj).col_join(cross[:2, :]), "sign_flip", sym_differs()),
    ]))
    # 14-5/try-1: γ of the rocker's pᵀp − 1 = 0
    mech = get("14-5/try-1").context()["mech"]
    t5 = 0.15
    q5 = mech.solve_position(t5)
    qd5 = mech.solve_velocity(q5, t5)
    p4d, p2d = mech.p(qd5, "rocker"), mech.p(qd5, "crank")
    k4 = mech.index("e04")
    T.append(Case("14-5/try-1", -2 * sum(x * x for x in p4d), [
        Answer(2 * p4d @ p4d, "gamma_sign", rel(lambda r: -r)),
        Answer(-p4d @ p4d, "factor_2_missing", rel(lambda r: r / 2), also=("scaled",)),
        Answer(-2 * p2d @ p2d, "other_body", same(-2 * np.sum(qd5[mech.index("e02"):mech.index("e02") + 4] ** 2)),
               also=("wrong_data",)),   # named as a lookalike whose detail says "γ of the crank's normalization"
        Answer(0.0, "missing_term", same(0.0)),      # "the derivative of a constant is 0"
        Answer(-4 * p4d @ p4d, "factor_2_extra", rel(lambda r: 2 * r), also=("scaled",)),
        Answer(-2 * q5[k4:k4 + 4] @ q5[k4:k4 + 4], "wrong_data", same(-2.0), also=("other_body",)),  # p for ṗ: −2
    ]))
    # 14-5/try-2: Φ_q of the universal joint (s rows + n1 row)
    mech = get("14-5/try-2").context()["mech"]
    p3, p4 = sp.Matrix(mech.body_symbols("coupler")[3:]), sp.Matrix(mech.body_symbols("rocker")[3:])
    a3, a4 = R.A_from_p(p3) * sp.Matrix([0, 1, 0]), R.A_from_p(p4) * sp.Matrix([1, 0, 0])
    I3 = sp.eye(3)
    Cv = lambda p, a: 2 * (R.E(p) * R.a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)  # noqa: E731
    Ev = lambda p, a: 2 * R.E(p) * R.a_bar(sp.Matrix(a))  # noqa: E731
    JB = sp.Matrix.vstack(sp.Matrix.hstack(I3, Cv(p3, [3.2, 0, 0]), -I3, -Cv(p4, [0, 1.5, 0])),
                          sp.Matrix.hstack(Z, a4.T * Cv(p3, [0, 1, 0]), Z, a3.T * Cv(p4, [1, 0, 0])))
    T.append(Case("14-5/try-2", JB, [
        Answer(sp.Matrix.vstack(JB[:3, :], sp.Matrix.hstack(Z, a4.T * Ev(p3, [0, 1, 0]), Z, a3.T * Ev(p4, [1, 0, 0]))),
               "eg_jacobian", sym_differs()),
        Answer(JB / 2, "scaled", sym_differs(), also=("factor_2_missing",)),
        Answer(JB.T, "transposed", lambda w, r: sp.Matrix(w).shape == (14, 4)),
        Answer(sp.Matrix.vstack(sp.Matrix.hstack(I3, Cv(p3, [3.2, 0, 0]), I3, -Cv(p4, [0, 1.5, 0])), JB[3:, :]),
               "sign_flip", sym_differs()),
        Answer(sp.Matrix.vstack(JB[:3, :], sp.Matrix.hstack(Z, a3.T * Cv(p3, [0, 1, 0]), Z, a4.T * Cv(p4, [1, 0, 0]))),
               "own_arm", sym_differs()),
        Answer(JB[:3, :], "missing_row", lambda w, r: sp.Matrix(w).shape == (3, 14)),
    ]))
    # 14-5/try-3: γ of the spherical joint at A
    mech = get("14-5/try-3").context()["mech"]
    k2, k3 = mech.index("e02"), mech.index("e03")
    pd2, pd3 = sp.Matrix(mech.qd[k2:k2 + 4, 0]), sp.Matrix(mech.qd[k3:k3 + 4, 0])
    Bv = lambda p, a: 2 * (R.E(p, check=False) * R.a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)  # noqa: E731
    gA = -Bv(pd2, [1, 0, 0]) * pd2 + Bv(pd3, [0, 0, 0]) * pd3
    T.append(Case("14-5/try-3", gA, [
        Answer(-gA, "gamma_sign", sym_differs()),
        Answer(gA / 2, "scaled", sym_differs(), also=("factor_2_missing",)),
        Answer(-2 * R.E(pd2, check=False) * R.a_bar(sp.Matrix([1, 0, 0])) * pd2, "missing_term", sym_differs()),
        Answer(gA[:2, :], "missing_row", lambda w, r: sp.Matrix(w).shape == (2, 1)),
        Answer(-Bv(pd3, [1, 0, 0]) * pd3, "other_body", sym_differs(),
               also=("swapped_bodies",)),   # body j's ṗ in body i's term: the i/j roles exchanged
        Answer(-(2 * R.E(pd2, check=False) * R.a_bar(sp.Matrix([1, 0, 0])) - 2 * sp.Matrix([1, 0, 0]) * pd2.T) * pd2,
               "sign_flip", sym_differs()),     # the sign of B's a ṗᵀ term
    ]))
    return T


def cases():
    return ch13() + ch14()
