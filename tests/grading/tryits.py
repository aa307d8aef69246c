"""Every "Try it" check of the chapter notebooks and every exercise part built on the book's examples, as
data: the id (the notebooks' own, kinbook.book.tryits), a right answer in another form than the worked one and
the wrong answers a student typically gives, typed here from the notebook's data and the book's formulas (never
asked from kinbook's reference). tests/grading/test_tryits.py re-runs them all.

A chapter try-it is checked the way the notebook checks it: through the registry
(``kinbook.book.tryits.get(id).check``), so its target — an :mod:`kinbook.grading.expected` object that names
numeric mistakes, the lookalikes printed above it — and ``reveal=False`` are the notebook's.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
import sympy as sp

import kinbook
from kinbook import planar as P
from kinbook import spatial as S
from kinbook.book import tryits as registry
from kinbook.grading import check_gamma, check_jacobian, check_nu, check_phi

from .corpus2 import xy

DEG = 180 / np.pi


@dataclass
class TryIt:
    id: str
    checker: object
    target: object  # callable: () -> the checker's reference
    right: object
    wrong: list  # (answer, the code it should get; None: any name but the generic "wrong value")
    options: dict = field(default_factory=dict)

    def check(self, answer):
        return self.checker(answer, self.target(), **self.options)


class Notebook(TryIt):
    """A chapter try-it, checked through the registry with the notebook's data."""

    def __init__(self, id, right, wrong):
        item = registry.get(id)
        super().__init__(id, item.checker, lambda: item.target(**item.data), right, wrong, {})
        self.item = item

    def check(self, answer):
        return self.item.check(answer)


@lru_cache(maxsize=None)
def example(name):
    m = kinbook.examples.load(name)
    try:
        q = m.solve_position(0.0)
        qd = m.solve_velocity(q, 0.0)
        qdd = m.solve_acceleration(q, qd, 0.0)
    except kinbook.KinbookError:
        q = qd = qdd = None
    return m, q, qd, qdd


def newton_iterates(m, time, step=1.0, n=8, J_at_guess=False, degrees=False, start=None):
    """A student's Newton loop on mechanism ``m`` at ``time``, as typed with numpy (13-3's try-it): ``n`` steps from
    q0 (or ``start``), each ``step`` × the Newton step, the Jacobian kept at the guess when ``J_at_guess``, the
    angles shown in degrees when ``degrees``; the list of iterates."""
    q = (m.q0 if start is None else start).copy()
    out = [q]
    J0 = m.Phi_q(q, time)
    for _ in range(n):
        J = J0 if J_at_guess else m.Phi_q(q, time)
        q = q + step * np.linalg.solve(J, -m.Phi(q, time))
        out.append(q)
    if degrees:
        out = [x.copy() for x in out]
        for x in out[1:]:
            x[2::3] *= DEG
    return out


def _rev(s1, s2, **kw):
    (x1, y1), (x2, y2) = xy(1, s1, **kw), xy(2, s2, **kw)
    return [f"{x1} - {x2}", f"{y1} - {y2}"]


def _c(phi):
    return np.cos(phi)


def _s(phi):
    return np.sin(phi)


def _A(phi):
    return np.array([[_c(phi), -_s(phi)], [_s(phi), _c(phi)]])


def _B(phi):
    return np.array([[-_s(phi), -_c(phi)], [_c(phi), -_s(phi)]])


# ================================================================================================ chapter 13
def _ch13():
    T = []
    phi = np.radians(120)
    T.append(Notebook("13-1/try-1", [[-0.5, -np.sqrt(3) / 2], [np.sqrt(3) / 2, -0.5]], [
        (_A(phi).T, "transposed"), ([[_c(120), -_s(120)], [_s(120), _c(120)]], "degrees"), (_B(phi), "B_for_A")]))
    r, f, s = np.array([1.5, -0.5]), np.radians(30), np.array([0.8, 0.3])
    T.append(Notebook("13-1/try-2", [1.5 + 0.8 * 0.8660254 - 0.3 * 0.5, -0.5 + 0.8 * 0.5 + 0.3 * 0.8660254], [
        (r + _A(f).T @ s, "A_transposed"), (r + s, "local_vector"), (r + _A(30) @ s, "degrees"),
        ([1.5 + 0.8 * _c(f) + 0.3 * _s(f), -0.5 + 0.8 * _s(f) + 0.3 * _c(f)], "sign_flip"), (_A(f) @ s, "missing_term")]))
    rd, w, al = np.array([0.2, 0.0]), 2.0, -1.0
    v = [0.2 - (0.8 * _s(f) + 0.3 * _c(f)) * w, (0.8 * _c(f) - 0.3 * _s(f)) * w]
    a = _B(f) @ s * al - _A(f) @ s * w**2
    T.append(Notebook("13-1/try-3", v + list(a), [
        (np.r_[v, _B(f) @ s * al], "missing_term"), (np.r_[v, _B(f) @ s * al + _A(f) @ s * w**2], "sign_flip"),
        (np.r_[rd + _A(f) @ s * w, a], "A_for_B"), (np.r_[v, _B(f) @ s * al - _A(f) @ s * w], "missing_square")]))
    T.append(Notebook("13-2/try-1", _rev((1, 0), (-1.5, 0.2))[::-1], [
        (_rev((-1.5, 0.2), (1, 0)), "swapped_points"), (_rev((1, 0), (-1.5, -0.2)), "sign_flip"),
        (_rev((1, 0), (-1.5, 0.2), transposed=True), None), (_rev((1, 0), (-1.5, 0.2), local=True), "local_vector")]))
    (xP, yP), (xQ, yQ), (xJ, yJ) = xy(1, (0, 0)), xy(1, (1, 0)), xy(2, (0, 0))
    T.append(Notebook("13-2/try-2",
                      [f"({xP} - {xQ})*({yJ} - {yP}) - ({yP} - {yQ})*({xJ} - {xP})", "phi2 - phi1"], [
        ([f"({xP} - {xQ})*({xJ} - {xP}) + ({yP} - {yQ})*({yJ} - {yP})", "phi1 - phi2"], "book_misprint"),
        ([f"({xP} - {xQ})*({yJ} - {yP}) - ({yP} - {yQ})*({xJ} - {xP})", "phi1 + phi2"], "sign_flip"),
        ([f"({xP} - {xQ})*({yJ} - {yP}) - ({yP} - {yQ})*({xJ} - {xP})"], "missing_row")]))
    (xB, yB), (xC, yC) = xy(1, (2, 0)), xy(2, (0, 0.5))
    T.append(Notebook("13-2/try-3", [f"sqrt(({xB} - {xC})**2 + ({yB} - {yC})**2) - 3"], [
        ([f"({xB} - {xC})**2 + ({yB} - {yC})**2 - 3"], "missing_square"),
        ([f"({xB} - {xy(2, (0, -0.5))[0]})**2 + ({yB} - {xy(2, (0, -0.5))[1]})**2 - 9"], "sign_flip"),
        ([f"({xy(1, (2, 0), transposed=True)[0]} - {xy(2, (0, 0.5), transposed=True)[0]})**2 + "
          f"({xy(1, (2, 0), transposed=True)[1]} - {xy(2, (0, 0.5), transposed=True)[1]})**2 - 9"], "A_transposed")]))
    (x2, y2) = xy(2, (-1.2, 0.2))
    T.append(Notebook("13-3/try-1", [f"{x2} - x1", f"{y2} - y1"], [
        (_rev((0, 0), (-1.2, -0.2)), "sign_flip"), (["x1 - x2 + 1.2", "y1 - y2 - 0.2"], "local_vector"),
        (_rev((0, 0), (-1.2, 0.2), transposed=True), "A_transposed"),
        (["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], None)]))
    m3 = example("ch13_example3")[0]
    t = 0.005

    def loop(step=1.0, n=8, time=t, J_at_guess=False, degrees=False, start=None):
        return newton_iterates(m3, time, step, n, J_at_guess, degrees, start)

    def until_converged():
        q, out = m3.q0.copy(), [m3.q0.copy()]
        while np.abs(m3.Phi(q, t)).max() > 1e-12:
            q = q + np.linalg.solve(m3.Phi_q(q, t), -m3.Phi(q, t))
            out.append(q)
        return np.array(out)

    T.append(Notebook("13-3/try-2", until_converged(), [
        (loop(step=-1.0, n=4), "newton_step"), (loop(n=1), "not_converged"), (loop(time=0.0), "wrong_data"),
        (loop(J_at_guess=True, n=30), "newton_step"), (loop(degrees=True), "degrees"),
        (m3.solve_position(t), "wrong_shape")]))
    m1, q1 = example("ch13_example1")[:2]
    r3, p3, sC = q1[6:8], q1[8], np.array([2.0, 0.5])
    T.append(Notebook("13-3/try-3", [r3[0] + 2.0 * _c(p3) - 0.5 * _s(p3), r3[1] + 2.0 * _s(p3) + 0.5 * _c(p3)], [
        (r3 + _A(p3).T @ sC, "A_transposed"), (r3 + sC, "local_vector"), (r3 + _A(p3) @ [2.0, -0.5], "sign_flip"),
        (r3 + _A(p3 * DEG) @ sC, "degrees"), (m1.point_position(q1, "rocker", "B"), "wrong_data")]))
    T.append(Notebook("13-4/try-1", ["3*phi1 - 4*phi2 + phi3"], [   # ρ_1 = 3, ρ_3 = 1: not the train printed above
        (["3*phi1 + phi3"], "missing_term"), (["1*(phi1 - phi2) + 3*(phi3 - phi2)"], "swapped_bodies"),
        (["3*(phi1 - phi2) - 1*(phi3 - phi2)"], "sign_flip"), (["2*phi1 - 3*phi2 + phi3"], "wrong_data")]))
    T.append(Notebook("13-4/try-2", 5.25, [
        (3.75, "relative_speed"), (3.0, "wrong_data"), (-2.25, "sign_flip"), (5.25 * DEG, "degrees"),
        (-5.25, "sign_flip")]))
    T.append(Notebook("13-4/try-3", np.radians(90), [
        (90.0, "degrees"), (np.pi, "scaled"), (-np.pi / 2, "sign_flip")]))
    T.append(Notebook("13-5/try-1", [["-1", "0", "0", "1", "0", "sin(phi2)"], ["0", "-1", "0", "0", "1", "-cos(phi2)"]], [
        ([["1", "0", "0", "-1", "0", "0"], ["0", "1", "0", "0", "-1", "0"]], "missing_chain_rule"),
        ([["1", "0", "0", "-1", "0", "cos(phi2)"], ["0", "1", "0", "0", "-1", "sin(phi2)"]], "A_for_B"),
        ([["1", "0", "0", "-1", "0", "sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]], "sign_flip")]))
    dx, dy = "(x2 + cos(phi2) - x3 + 1.5*cos(phi3))", "(y2 + sin(phi2) - y3 + 1.5*sin(phi3))"
    j8 = [[f"2*{dx}", f"2*{dy}", f"-2*{dx}*sin(phi2) + 2*{dy}*cos(phi2)", f"-2*{dx}", f"-2*{dy}",
           f"-3*{dx}*sin(phi3) + 3*{dy}*cos(phi3)"]]
    zeros = [list(j8[0])]
    zeros[0][2] = zeros[0][5] = "0"
    half = [[f"0.5*({e})" for e in j8[0]]]
    j8_other = [[e.replace("(x2 + cos(phi2) - x3 + 1.5*cos(phi3))", "(cos(phi2) + x2 + 1.5*cos(phi3) - x3)")
                 for e in j8[0]]]                                 # the same row with x^A − x^B written otherwise
    T.append(Notebook("13-5/try-2", j8_other, [
        (zeros, "book_misprint"), ([[e if k < 3 else f"-({e})" for k, e in enumerate(j8[0])]], None),
        (half, "scaled")]))
    tJ = 0.004
    q = m3.solve_position(tJ)
    rA, rB = m3.point_position(q, "crank", "A"), m3.point_position(q, "rocker", "B")
    d, arm = rA - rB, rB - q[6:8]
    J88 = -2 * d @ np.array([-arm[1], arm[0]])
    T.append(Notebook("13-5/try-3", 2 * d @ np.array([arm[1], -arm[0]]), [
        (0.0, "book_misprint"), (-J88, "sign_flip"), (J88 / 2, "scaled"), (-2 * d @ arm, "A_for_B"),
        (2 * d @ np.array([rB[1] - 0.0, -(rB[0] - 3.0)]), "lever_arm"),
        (example("ch13_example3")[0].Phi_q(example("ch13_example3")[1], 0.0)[7, 8], "wrong_data")]))
    T.append(Notebook("13-6/try-1", ["0"] * 8 + ["5*(20 + 100*t)"], [
        (["0"] * 8 + ["-100 - 500*t"], "nu_sign"), (["0"] * 9, "nu_missing"),
        (["0"] * 8 + [f"{100 * DEG} + {500 * DEG}*t"], "degrees"),
        (["0"] * 8 + ["100"], "wrong_data")]))   # the book's driver, printed above: named so before "missing term"
    m3, q3, qd3, qdd3 = example("ch13_example3")
    w3 = qd3[8]
    T.append(Notebook("13-6/try-2", abs(2 * w3), [
        (abs(3 * w3), "wrong_data"), (abs(2 * w3) * DEG, "degrees"), (-abs(2 * w3), "sign_flip"),
        (2 * 100.0, "wrong_data")]))
    sC3, p3, rd3 = np.array([0.5, 0.4]), q3[8], qd3[6:8]
    vC = rd3 + _B(p3) @ sC3 * w3
    T.append(Notebook("13-6/try-3", [rd3[0] - (0.5 * _s(p3) + 0.4 * _c(p3)) * w3,
                                     rd3[1] + (0.5 * _c(p3) - 0.4 * _s(p3)) * w3], [
        (rd3 + _A(p3) @ sC3 * w3, "A_for_B"), (rd3 - _B(p3) @ sC3 * w3, "sign_flip"), (_B(p3) @ sC3 * w3, "missing_term"),
        (m3.point_velocity(q3, qd3, "rocker", "B"), "wrong_data"), (-vC, "sign_flip")]))
    gx, gy = "(-1.0*cos(phi2) - 0.3*sin(phi2))", "(-1.0*sin(phi2) + 0.3*cos(phi2))"
    T.append(Notebook("13-7/try-1", [f"-dphi2**2*{gx}", f"-{gy}*dphi2*dphi2"], [
        ([f"dphi2**2*{gx}", f"dphi2**2*{gy}"], "gamma_sign"), ([f"-dphi2*{gx}", f"-dphi2*{gy}"], "missing_square"),
        ([f"-dphi2**2*{gy}", f"-dphi2**2*{gx}"], None)]))
    tg = 0.004
    q, = [m3.solve_position(tg)]
    qd = m3.solve_velocity(q, tg)
    pts = (("crank", "A"), ("rocker", "B"))
    (pa, pb), (va, vb) = [m3.point_position(q, *x) for x in pts], [m3.point_velocity(q, qd, *x) for x in pts]
    ca, cb = [m3.point_acceleration(q, qd, np.zeros(9), *x) for x in pts]
    t1, t2 = -2 * (va - vb) @ (va - vb), -2 * (pa - pb) @ (ca - cb)
    T.append(Notebook("13-7/try-2", t1 + t2, [
        (-(t1 + t2), "gamma_sign"), (t1 / 2 + t2, "scaled"), (t1, "missing_term"), (t1 - t2, "sign_flip"),
        (m3.gamma(q3, qd3, 0.0)[7], "wrong_data")]))
    rdd3, a3 = qdd3[6:8], qdd3[8]
    T.append(Notebook("13-7/try-3", rdd3 + _B(p3) @ sC3 * a3 - _A(p3) @ sC3 * w3 * w3, [
        (rdd3 + _B(p3) @ sC3 * a3, "missing_term"), (rdd3 + _B(p3) @ sC3 * a3 + _A(p3) @ sC3 * w3**2, "sign_flip"),
        (rdd3 + _B(p3) @ sC3 * a3 - _A(p3) @ sC3 * w3, "missing_square"),
        (rdd3 + _B(p3) @ sC3 * w3**2 - _A(p3) @ sC3 * a3, "rate_exchanged"),
        (m3.point_acceleration(q3, qd3, qdd3, "rocker", "B"), "wrong_data")]))
    return T


def _two(points_1, points_2, joint):
    m = P.Mechanism("two bodies")
    m.add_body("b1", points=points_1)
    m.add_body("b2", points=points_2)
    m.add(joint)
    return m.constraints[-1]


# ================================================================================================ chapter 14
AXES = ([0, 0.6, 0.8], [0, -0.8, 0.6], [1, 0, 0])
ANG = np.radians([40.0, 25.0, -60.0])
A_GIVEN = np.array([[2.0, 2.0, -1.0], [-1.0, 2.0, 2.0], [2.0, -1.0, 2.0]]) / 3  # 14-1's body turned back (its Aᵀ)
R = S.rotations


def _rz(a):
    return np.array([[_c(a), -_s(a), 0], [_s(a), _c(a), 0], [0, 0, 1.0]])


def _rx(a):
    return np.array([[1.0, 0, 0], [0, _c(a), -_s(a)], [0, _s(a), _c(a)]])


def _ch14():
    T = []
    A1 = np.array([[0.0, 0.0, 1.0], [0.6, -0.8, 0.0], [0.8, 0.6, 0.0]])
    left, stretched = A1.copy(), A1.copy()
    left[:, 2] *= -1
    stretched[:, 1] *= 1.2
    T.append(Notebook("14-1/try-1", np.column_stack(AXES), [
        (A1.T, "transposed"), (left, "left_handed"), (stretched, "not_orthogonal")]))
    s = np.array([2.0, 1.0, -1.0])
    T.append(Notebook("14-1/try-2", [np.dot(AXES[0], s), np.dot(AXES[1], s), np.dot(AXES[2], s)], [
        (A1 @ s, "A_for_AT"), (-A1.T @ s, "sign_flip"), (s, "wrong_frame")]))
    r0, sQ = np.array([0.5, -1.0, 2.0]), np.array([0.4, 0.0, 1.5])
    T.append(Notebook("14-1/try-3", r0 + 0.4 * np.array(AXES[0]) + 1.5 * np.array(AXES[2]), [
        (r0 + A1.T @ sQ, "A_transposed"), (r0 + sQ, "local_vector"), (A1 @ (r0 + sQ), "wrong_frame")]))
    A2 = _rz(ANG[0]) @ _rx(ANG[1]) @ _rz(ANG[2])
    from scipy.spatial.transform import Rotation

    T.append(Notebook("14-2/try-1", Rotation.from_euler("ZXZ", ANG).as_matrix(), [
        (_rz(ANG[2]) @ _rx(ANG[1]) @ _rz(ANG[0]), "extrinsic_order"), (A2.T, "transposed"),
        (_rz(40.0) @ _rx(25.0) @ _rz(-60.0), "degrees")]))
    th, ph, rates = ANG[1], ANG[2], [2.0, 0.5, -1.0]
    wb = np.array([_s(th) * _s(ph) * 2.0 + _c(ph) * 0.5, _s(th) * _c(ph) * 2.0 - _s(ph) * 0.5, _c(th) * 2.0 - 1.0])
    T.append(Notebook("14-2/try-2", A2.T @ (A2 @ wb), [
        (A2 @ wb, "wrong_frame"), (rates, "angle_rates"),
        ([_s(25.0) * _s(-60.0) * 2.0 + _c(-60.0) * 0.5, _s(25.0) * _c(-60.0) * 2.0 - _s(-60.0) * 0.5,
          _c(25.0) * 2.0 - 1.0], "degrees")]))
    a = np.array([np.arctan2(A_GIVEN[0, 2], -A_GIVEN[1, 2]), np.arccos(A_GIVEN[2, 2]),
                  np.arctan2(A_GIVEN[2, 0], A_GIVEN[2, 1])])
    at = np.array([np.arctan2(A_GIVEN[2, 0], -A_GIVEN[2, 1]), np.arccos(A_GIVEN[2, 2]),
                   np.arctan2(A_GIVEN[0, 2], A_GIVEN[1, 2])])
    T.append(Notebook("14-2/try-3", [a[0] + np.pi, -a[1], a[2] - np.pi], [
        (a * DEG, "degrees"), (a[::-1].copy(), "extrinsic_order"), (at, "transposed"),
        ([np.arctan(A_GIVEN[0, 2] / -A_GIVEN[1, 2]), a[1], np.arctan(A_GIVEN[2, 0] / A_GIVEN[2, 1])], "arctan_quadrant")]))
    T.append(Notebook("14-2/try-3", Rotation.from_matrix(A_GIVEN).as_euler("ZXZ"), []))
    u, chi = np.array([0, 1, 1]) / np.sqrt(2), 2 * np.pi / 3
    p = np.r_[_c(chi / 2), u * _s(chi / 2)]
    T.append(Notebook("14-3/try-1", -p, [
        (np.r_[_c(chi), u * _s(chi)], "full_angle"), (np.r_[_c(60.0), u * _s(60.0)], "degrees"),
        (np.r_[p[1:], p[0]], "scalar_last"), (np.r_[_c(chi / 2), np.array([0, 1, 1]) * _s(chi / 2)], "not_normalized")]))
    pp = np.array([0.5, 0.5, 0.5, 0.5])
    App = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    e0, e1, e2, e3 = pp
    book = np.array([[e0**2 + e1**2 - 0.5, e1 * e2 - e0 * e3, e1 * e3 - e0 * e2],
                     [e1 * e2 - e0 * e3, e0**2 + e2**2 - 0.5, e2 * e3 - e0 * e1],
                     [e1 * e3 - e0 * e2, e2 * e3 - e0 * e1, e0**2 + e3**2 - 0.5]])
    T.append(Notebook("14-3/try-2", App, [
        (0.5 * App, "factor_2_missing"), (book, "book_misprint"), (App.T, "transposed")]))
    pd = np.array([-0.1, 0.3, -0.1, -0.1])
    E = np.array([[-0.5, 0.5, -0.5, 0.5], [-0.5, 0.5, 0.5, -0.5], [-0.5, -0.5, 0.5, 0.5]])
    G = np.array([[-0.5, 0.5, 0.5, -0.5], [-0.5, -0.5, 0.5, 0.5], [-0.5, 0.5, -0.5, 0.5]])
    Ef = E.copy()
    Ef[:, 0] *= -1
    T.append(Notebook("14-3/try-3", 2 * E @ pd, [
        (2 * G @ pd, "G_for_E"), (E @ pd, "factor_2_missing"), (2 * Ef @ pd, "sign_flip")]))
    # 14-4, 14-5: constraints
    ball = S.Mechanism("ball joint")
    ball.add_body("i", points={"P": (0, 0, 1)})
    ball.add_body("j", points={"P": (-1, 0.5, 0)})
    qi, qj = ball.body_symbols("i"), ball.body_symbols("j")
    Ai, Aj = R.A_from_p(list(qi[3:])), R.A_from_p(list(qj[3:]))
    si, sj = sp.Matrix([0, 0, 1]), sp.Matrix([-1, sp.Rational(1, 2), 0])
    ok = sp.Matrix(qj[:3]) + Aj * sj - sp.Matrix(qi[:3]) - Ai * si
    T.append(Notebook("14-4/try-1", ok, [
        (sp.Matrix(qi[:3]) + Ai.T * si - sp.Matrix(qj[:3]) - Aj.T * sj, "A_transposed"),
        (sp.Matrix(qi[:3]) + si - sp.Matrix(qj[:3]) - sj, "local_vector"),
        (sp.Matrix(qi[:3]) + Ai * si - sp.Matrix(qj[:3]) + Aj * sj, "sign_flip"),
        (list(-ok) + [sum(x**2 for x in qi[3:]) - 1], "dependent_row")]))
    n1 = S.Mechanism("n1")
    n1.add_body("i", points={"C": (1.2, 0, 0), "B": (1.2, 0, 1.0)})
    n1.add_body("j", points={"C": (0.5, 0, 0), "B": (1.5, 0, 0)})
    qi, qj = n1.body_symbols("i"), n1.body_symbols("j")
    pi, pj = sp.Matrix(qi[3:]), sp.Matrix(qj[3:])
    li, lj = sp.Matrix([0, 0, 1]), sp.Matrix([1, 0, 0])
    gi, gj = R.A_from_p(pi) * li, R.A_from_p(pj) * lj
    phi_n1 = (gi.T * gj)[0]
    right = sp.Matrix([phi_n1]).jacobian(list(qi) + list(qj))
    eg = sp.Matrix.hstack(sp.zeros(1, 3), gj.T * 2 * R.E(pi) * R.a_bar(li), sp.zeros(1, 3), gi.T * 2 * R.E(pj) * R.a_bar(lj))
    no2 = sp.Matrix.hstack(sp.zeros(1, 3), gj.T * (R.E(pi) * R.a_bar(li) + li * pi.T), sp.zeros(1, 3),
                           gi.T * (R.E(pj) * R.a_bar(lj) + lj * pj.T))
    T.append(Notebook("14-4/try-2", right, [
        (eg, "eg_jacobian"), (sp.zeros(1, 14), "missing_chain_rule"), (right.T, "transposed"), (no2, None)]))
    hinge = S.Mechanism("hinge")
    hinge.add_body("i", points={"P": (1.2, 0, 0)})
    hinge.add_body("j", points={"P": (0, 0, 0)})
    qi, qj = hinge.body_symbols("i"), hinge.body_symbols("j")
    Ai, Aj = R.A_from_p(list(qi[3:])), R.A_from_p(list(qj[3:]))
    ax_i, ax_j = sp.Matrix([0, 0, sp.Rational(4, 5)]), sp.Matrix([0, 0, sp.Rational(1, 2)])
    ball_rows = sp.Matrix(qi[:3]) + Ai * sp.Matrix([sp.Rational(6, 5), 0, 0]) - sp.Matrix(qj[:3])
    h_rows = sp.Matrix([(Ai * sp.Matrix([0, 1, 0])).dot(Aj * ax_j), (Ai * sp.Matrix([-1, 0, 0])).dot(Aj * ax_j)])
    cross_global = R.skew(list(Ai * ax_i)) * (Aj * ax_j)
    cross_local = R.skew(list(ax_i)) * Ai.T * Aj * ax_j
    T.append(Notebook("14-4/try-3", ball_rows.col_join(h_rows), [
        (ball_rows.col_join(cross_local), "extra_row"), ((sp.Matrix(qi[:3]) + sp.Matrix([sp.Rational(6, 5), 0, 0]) - sp.Matrix(qj[:3])).col_join(h_rows), "local_vector"),
        ((sp.Matrix(qi[:3]) + Ai.T * sp.Matrix([sp.Rational(6, 5), 0, 0]) - sp.Matrix(qj[:3])).col_join(h_rows),
         "A_transposed")]))
    T[-1].wrong.append((ball_rows.col_join(cross_global[:2, :]), "book_misprint"))   # the book's global rows 1-2
    four = example("spatial_fourbar")[0]
    t5 = 0.15
    q5 = four.solve_position(t5)
    qd5 = four.solve_velocity(q5, t5)
    p4d, p2d = four.p(qd5, "rocker"), four.p(qd5, "crank")
    T.append(Notebook("14-5/try-1", -2 * sum(x * x for x in p4d), [
        (2 * p4d @ p4d, "gamma_sign"), (-p4d @ p4d, "scaled"), (-2 * p2d @ p2d, "wrong_data")]))
    p3, p4 = sp.Matrix(four.body_symbols("coupler")[3:]), sp.Matrix(four.body_symbols("rocker")[3:])
    a3, a4 = R.A_from_p(p3) * sp.Matrix([0, 1, 0]), R.A_from_p(p4) * sp.Matrix([1, 0, 0])
    I3, Z = sp.eye(3), sp.zeros(1, 3)
    Cv = lambda p, a: 2 * (R.E(p) * R.a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)  # noqa: E731
    Ev = lambda p, a: 2 * R.E(p) * R.a_bar(sp.Matrix(a))  # noqa: E731
    JB = sp.Matrix.vstack(sp.Matrix.hstack(I3, Cv(p3, [3.2, 0, 0]), -I3, -Cv(p4, [0, 1.5, 0])),
                          sp.Matrix.hstack(Z, a4.T * Cv(p3, [0, 1, 0]), Z, a3.T * Cv(p4, [1, 0, 0])))
    JE = sp.Matrix.vstack(JB[:3, :], sp.Matrix.hstack(Z, a4.T * Ev(p3, [0, 1, 0]), Z, a3.T * Ev(p4, [1, 0, 0])))
    T.append(Notebook("14-5/try-2", -JB, [(JE, "eg_jacobian"), (JB / 2, "scaled"), (JB.T, "transposed")]))
    k2, k3 = four.index("e02"), four.index("e03")
    pd2, pd3 = sp.Matrix(four.qd[k2:k2 + 4, 0]), sp.Matrix(four.qd[k3:k3 + 4, 0])
    Bv = lambda p, a: 2 * (R.E(p, check=False) * R.a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)  # noqa: E731
    gA = -Bv(pd2, [1, 0, 0]) * pd2 + Bv(pd3, [0, 0, 0]) * pd3
    T.append(Notebook("14-5/try-3", -(2 * R.E(pd2, check=False) * R.a_bar(sp.Matrix([1, 0, 0])) * pd2
                                      + 2 * sp.Matrix([1, 0, 0]) * (pd2.T * pd2)), [
        (-gA, "gamma_sign"), (gA / 2, "scaled"),
        (-2 * R.E(pd2, check=False) * R.a_bar(sp.Matrix([1, 0, 0])) * pd2, "missing_term")]))  # the book's 2ĖĠᵀa
    return T


# ================================================================================================ exercises
def _exercises():
    T = []
    ex1 = lambda: example("ch13_example1")[0]  # noqa: E731
    phi_oa = ["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"]
    T.append(TryIt("ex01/revolute_OA", check_phi, lambda: ex1().constraint("1"), phi_oa, [
        (["x1 - x2 - cos(phi2)", "y1 - y2 - sin(phi2)"], "sign_flip"), (["x1 - x2 + cos(phi2)"], "missing_row")]))
    T.append(TryIt("ex01/revolute_B_order", check_phi, lambda: ex1().constraint("4"),
                   ["x3 + 3*cos(phi3) - x4 + 1.5*cos(phi4)", "y3 + 3*sin(phi3) - y4 + 1.5*sin(phi4)"], [
        (["y3 + 3*sin(phi3) - y4 + 1.5*sin(phi4)", "x3 + 3*cos(phi3) - x4 + 1.5*cos(phi4)"], "row_order"),
        (["x3 + 3*cos(phi3) - x4 - 1.5*cos(phi4)", "y3 + 3*sin(phi3) - y4 - 1.5*sin(phi4)"], "sign_flip")],
        {"order": "book"}))
    ex2 = lambda: example("ch13_example2")[0]  # noqa: E731
    T.append(TryIt("ex02/translational", check_phi, lambda: ex2().constraint("2"),
                   ["cos(phi1)*(y4 - y1) - sin(phi1)*(x4 - x1)", "phi1 - phi4"], [
        (["cos(phi1)*(x4 - x1) + sin(phi1)*(y4 - y1)", "phi1 - phi4"], "book_misprint"),
        (["cos(phi1)*(y4 - y1) - sin(phi1)*(x4 - x1)", "phi1 + phi4"], "sign_flip")]))
    T.append(TryIt("ex02/driver", check_phi, lambda: example("ch13_example1")[0].constraint("driver 1"),
                   ["phi2 - 3*pi/4 - 100*t"], [(["phi2 - 135 - 100*t"], "degrees"), (["phi2 + 3*pi/4 + 100*t"],
                                                                                        "sign_flip")]))
    ex7 = lambda: example("ch13_example2")[0]  # noqa: E731
    T.append(TryIt("ex07/revolute_rows", check_jacobian, lambda: ex7().constraint("3"),
                   [["1", "0", "-sin(phi2)", "-1", "0", "-3*sin(phi3)"], ["0", "1", "cos(phi2)", "0", "-1", "3*cos(phi3)"]],
                   [([["1", "0", "0", "-1", "0", "0"], ["0", "1", "0", "0", "-1", "0"]], "missing_chain_rule"),
                    ([["1", "0", "cos(phi2)", "-1", "0", "3*cos(phi3)"], ["0", "1", "sin(phi2)", "0", "-1", "3*sin(phi3)"]],
                     "A_for_B")]))
    T.append(TryIt("ex08/nu", check_nu, ex1, ["0"] * 11 + ["100"], [(["0"] * 11 + ["-100"], "nu_sign"),
                                                                   (["0"] * 12, "nu_missing")]))
    # numbers for a ν that is constant: an answer, diagnosed as one (not "malformed: give at=")
    T.append(TryIt("ex08/nu-as-numbers", check_nu, ex1, [0] * 11 + [100.0], [
        ([0] * 11 + [-100.0], "nu_sign"), ([0] * 12, "nu_missing"), ([0] * 11 + [100 * DEG], "degrees")]))
    T.append(TryIt("ex08/gamma_joint", check_gamma, lambda: ex1().constraint("3"),
                   ["cos(phi2)*dphi2**2 + 3*cos(phi3)*dphi3**2", "sin(phi2)*dphi2**2 + 3*sin(phi3)*dphi3**2"], [
        (["-cos(phi2)*dphi2**2 - 3*cos(phi3)*dphi3**2", "-sin(phi2)*dphi2**2 - 3*sin(phi3)*dphi3**2"], "gamma_sign"),
        (["cos(phi2)*dphi2 + 3*cos(phi3)*dphi3", "sin(phi2)*dphi2 + 3*sin(phi3)*dphi3"], "missing_square")]))
    return T


def _part(stem, name):
    """An exercise part as the grader reads it (the source's hidden checks, kinbook's references)."""
    from pathlib import Path

    from kinbook.classroom.variant import references

    path = Path(__file__).resolve().parents[2] / "exercises" / f"{stem}.ipynb"
    return next(p for p in references(path) if p.name == name)


def _exercise_numbers():
    """ex09 and ex12 (issue 22 item 6): numeric parts graded against kinbook.grading.expected objects."""
    from kinbook.grading import check_value

    T = []
    m = kinbook.loads(kinbook.examples.path("ch13_example1").read_text())
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    qdd = m.solve_acceleration(q, qd, 0.0)
    other = q.copy()
    other[11] -= 2 * np.pi                                      # φ4 − 2π: the same orientation
    guess = m.q0.copy()
    guess[6:12] = [0.7, 0.3, np.radians(-30), 2.4, -1.0, np.radians(80)]
    deg = q.copy()
    deg[2::3] *= DEG
    pq = _part("ex09-point-kinematics", "q")
    T.append(TryIt("ex09/q", check_value, lambda: pq.expected, other, [
        (m.solve_position(0.0, q0=guess), "assembly_mode"), (deg, "degrees"), (m.q0, "not_converged")],
        pq.options))
    f3, w3, a3, rd3, rdd3, sB = q[8], qd[8], qdd[8], qd[6:8], qdd[6:8], np.array([3.0, 0.0])
    pv = _part("ex09-point-kinematics", "velocity_B")
    T.append(TryIt("ex09/velocity_B", check_value, lambda: pv.expected, rd3 + _B(f3) @ sB * w3, [
        (rd3 + _A(f3) @ sB * w3, "A_for_B"), (_B(f3) @ sB * w3, "missing_term"), (rd3 - _B(f3) @ sB * w3, "sign_flip")],
        pv.options))
    pa = _part("ex09-point-kinematics", "acceleration_B")
    T.append(TryIt("ex09/acceleration_B", check_value, lambda: pa.expected,
                   rdd3 + _B(f3) @ sB * a3 - _A(f3) @ sB * w3**2, [
        (rdd3 + _B(f3) @ sB * a3, "missing_term"), (rdd3 + _B(f3) @ sB * a3 + _A(f3) @ sB * w3**2, "sign_flip"),
        (rdd3 + _B(f3) @ sB * w3**2 - _A(f3) @ sB * a3, "rate_exchanged")], pa.options))
    four = example("spatial_fourbar")[0]
    rng = np.random.default_rng(2024)                             # ex12's test configuration, typed as it is there
    q_t, qd_t = rng.uniform(-1, 1, four.n), rng.uniform(-1, 1, four.n)
    for b in range(4):
        p = q_t[7 * b + 3:7 * b + 7]
        p /= np.linalg.norm(p)
        pd = qd_t[7 * b + 3:7 * b + 7]
        pd -= p * (p @ pd)
    Ab = [np.asarray(R.A_from_p(q_t[7 * b + 3:7 * b + 7]), float) for b in range(4)]
    r = [q_t[7 * b:7 * b + 3] for b in range(4)]
    s2, s3 = np.array([1.0, 0, 0]), np.zeros(3)
    ps = _part("ex12-spatial-joints", "spherical_phi")
    T.append(TryIt("ex12/spherical_phi", check_value, lambda: ps.expected, r[1] + Ab[1] @ s2 - r[2] - Ab[2] @ s3, [
        (r[1] + Ab[1].T @ s2 - r[2], "A_transposed"), (r[1] + s2 - r[2], "local_vector"),
        (r[1] - Ab[1] @ s2 - r[2], "sign_flip")], ps.options))
    pu = _part("ex12-spatial-joints", "universal_phi")
    su3, su4, h3, h4 = np.array([3.2, 0, 0]), np.array([0, 1.5, 0]), np.array([0, 1.0, 0]), np.array([1.0, 0, 0])
    T.append(TryIt("ex12/universal_phi", check_value, lambda: pu.expected,
                   np.r_[r[2] + Ab[2] @ su3 - r[3] - Ab[3] @ su4, (Ab[2] @ h3) @ (Ab[3] @ h4)], [
        (np.r_[r[2] + su3 - r[3] - su4, h3 @ h4], "local_vector"),
        (np.r_[r[2] + Ab[2].T @ su3 - r[3] - Ab[3].T @ su4, (Ab[2].T @ h3) @ (Ab[3].T @ h4)], "A_transposed"),
        (np.r_[r[2] + Ab[2] @ su3 - r[3] + Ab[3] @ su4, (Ab[2] @ h3) @ (Ab[3] @ h4)], None)], pu.options))
    pg = _part("ex12-spatial-joints", "gamma_n1")
    g = float(four.gamma(q_t, qd_t)[four.constraint("B").rows.start + 3])
    T.append(TryIt("ex12/gamma_n1", check_value, lambda: pg.expected, g, [(-g, "gamma_sign"), (2 * g, "scaled")],
                   pg.options))
    return T


def all_tryits():
    out = _ch13() + _ch14() + _exercises() + _exercise_numbers()
    return [t for t in out if t.right is not None]
