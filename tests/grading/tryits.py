"""Every "Try it" check of the chapter notebooks and every exercise part built on the book's examples, as
data: the id (the notebooks' own, kinbook.book.tryits), the checker call (target + checker + options), a
right answer and the wrong answers a student typically gives. tests/grading/test_tryits.py re-runs them all.

The chapter notebooks' try-its keep these checks stable: the ids, what is checked (the target), and — for
numbers — an :mod:`kinbook.grading.expected` target where one applies (``expected.A(φ)``,
``expected.point_position(…)`` …), which names the wrong answers a plain number cannot.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
import sympy as sp

import kinbook
from kinbook import planar as P
from kinbook import spatial as S
from kinbook.grading import (
    check_euler_parameters,
    check_gamma,
    check_jacobian,
    check_nu,
    check_phi,
    check_rotation,
    check_value,
    expected,
)

from .corpus2 import xy

DEG = 180 / np.pi


@dataclass
class TryIt:
    id: str
    checker: object
    target: object  # callable: () -> the checker's reference
    right: object
    wrong: list  # (answer, the code it should get)
    options: dict = field(default_factory=dict)


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


def _two(points_1, points_2, joint):
    m = P.Mechanism("two bodies")
    m.add_body("b1", points=points_1)
    m.add_body("b2", points=points_2)
    m.add(joint)
    return m.constraints[-1]


def _rev(s1, s2, **kw):
    (x1, y1), (x2, y2) = xy(1, s1, **kw), xy(2, s2, **kw)
    return [f"{x1} - {x2}", f"{y1} - {y2}"]


# ================================================================================================ chapter 13
PHI = np.radians(120)
R13, PHI13, S13 = np.array([1.5, -0.5]), np.radians(45), np.array([0.8, 0.3])
A_ = P.A


def _ch13():
    T = []
    T.append(TryIt("13-1/try-1", check_value, lambda: expected.A(PHI), A_(PHI), [
        (A_(PHI).T, "transposed"), (A_(120.0), "degrees"), (P.B(PHI), "A_for_B")], {"name": "A(120°)"}))
    rQ = R13 + A_(PHI13) @ S13
    T.append(TryIt("13-1/try-2", check_value, lambda: expected.point_position(R13, PHI13, S13), rQ, [
        (R13 + A_(PHI13).T @ S13, "A_transposed"), (R13 + S13, "local_vector"), (R13 + A_(45.0) @ S13, "degrees"),
        (R13 - A_(PHI13) @ S13, "sign_flip")], {"name": "r_i^Q"}))
    rd, w, al = np.array([0.2, 0.0]), 2.0, -1.0
    v = rd + P.B(PHI13) @ S13 * w
    T.append(TryIt("13-1/try-3v", check_value, lambda: expected.point_velocity(rd, PHI13, w, S13), v, [
        (rd + A_(PHI13) @ S13 * w, "A_for_B"), (rd + P.B(PHI13) @ S13, "missing_term"),
        (rd - P.B(PHI13) @ S13 * w, "sign_flip"), (rd + P.B(45.0) @ S13 * w, "degrees")], {"name": "v_Q"}))
    a = P.B(PHI13) @ S13 * al - A_(PHI13) @ S13 * w**2
    T.append(TryIt("13-1/try-3a", check_value, lambda: expected.point_acceleration([0, 0], PHI13, w, al, S13), a, [
        (P.B(PHI13) @ S13 * al, "missing_term"), (P.B(PHI13) @ S13 * al + A_(PHI13) @ S13 * w**2, "sign_flip"),
        (P.B(PHI13) @ S13 * al - A_(PHI13) @ S13 * w, "missing_square")], {"name": "a_Q"}))
    crank = lambda: _two({"A": (1, 0)}, {"A": (-1.5, 0.2)}, P.Revolute("b1", "b2", point="A"))  # noqa: E731
    T.append(TryIt("13-2/try-1", check_phi, crank, _rev((1, 0), (-1.5, 0.2)), [
        (_rev((-1.5, 0.2), (1, 0)), "swapped_points"), (_rev((1, 0), (-1.5, -0.2)), "sign_flip"),
        (_rev((1, 0), (-1.5, 0.2), transposed=True), "A_transposed"), (_rev((1, 0), (-1.5, 0.2), local=True),
                                                                      "local_vector")]))
    slide = lambda: _two({"P": (0, 0), "Q": (1, 0)}, {"P": (0, 0)},  # noqa: E731
                         P.Translational("b1", "b2", axis=("P", "Q"), point_j="P"))
    (xP, yP), (xQ, yQ), (xJ, yJ) = xy(1, (0, 0)), xy(1, (1, 0)), xy(2, (0, 0))
    T.append(TryIt("13-2/try-2", check_phi, slide,
                   [f"({xP} - {xQ})*({yJ} - {yP}) - ({yP} - {yQ})*({xJ} - {xP})", "phi1 - phi2 - (0 - 0)"], [
        ([f"({xP} - {xQ})*({xJ} - {xP}) + ({yP} - {yQ})*({yJ} - {yP})", "phi1 - phi2"], "book_misprint"),
        ([f"({xP} - {xQ})*({yJ} - {yP}) - ({yP} - {yQ})*({xJ} - {xP})", "phi1 + phi2"], "sign_flip"),
        ([f"({xP} - {xQ})*({yJ} - {yP}) - ({yP} - {yQ})*({xJ} - {xP})"], "missing_row")]))
    link = lambda: _two({"B": (2, 0)}, {"C": (0, 0.5)}, P.RevoluteRevolute("b1", "b2", "B", "C", length=3))  # noqa
    (xB, yB), (xC, yC) = xy(1, (2, 0)), xy(2, (0, 0.5))
    T.append(TryIt("13-2/try-3", check_phi, link, [f"({xB} - {xC})**2 + ({yB} - {yC})**2 - 9"], [
        ([f"({xB} - {xC})**2 + ({yB} - {yC})**2 - 3"], "missing_square"),
        ([f"({xB} - {xy(2, (0, -0.5))[0]})**2 + ({yB} - {xy(2, (0, -0.5))[1]})**2 - 9"], "sign_flip"),
        ([f"({xy(1, (2, 0), transposed=True)[0]} - {xy(2, (0, 0.5), transposed=True)[0]})**2 + "
          f"({xy(1, (2, 0), transposed=True)[1]} - {xy(2, (0, 0.5), transposed=True)[1]})**2 - 9"], "A_transposed")]))
    ex1 = lambda: example("ch13_example1")[0].constraint("1")  # noqa: E731
    T.append(TryIt("13-3/try-1", check_phi, ex1, ["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], [
        (["x1 - x2 - cos(phi2)", "y1 - y2 - sin(phi2)"], "sign_flip"), (["x1 - x2 - 1", "y1 - y2"], "local_vector"),
        (["x1 - x2 + cos(phi2)", "y1 - y2 - sin(phi2)"], "A_transposed")]))
    m3, q3 = example("ch13_example3")[:2]
    q3deg = q3.copy()
    q3deg[2::3] *= DEG
    T.append(TryIt("13-3/try-2", check_value, lambda: example("ch13_example3")[1], q3, [
        (q3deg, "degrees"), (m3.q0, "wrong_value")], {"name": "q(0) of example 3"}))
    m1, q1 = example("ch13_example1")[:2]
    r4, p4 = q1[9:11], q1[11]
    T.append(TryIt("13-3/try-3", check_value, lambda: expected.point_position(r4, p4, [-1.5, 0]),
                   m1.point_position(q1, "rocker", "B"), [
        (r4 + A_(p4) @ np.array([1.5, 0]), "sign_flip"), (r4 + A_(p4 * DEG) @ np.array([-1.5, 0]), "degrees"),
        (r4 + np.array([-1.5, 0]), "local_vector")], {"name": "r^B"}))
    pl = lambda: example("ch13_planetary")[0].constraints[3]  # noqa: E731
    T.append(TryIt("13-4/try-1", check_phi, pl, None, []))  # the row is the notebook's: filled below
    T.append(TryIt("13-4/try-2", check_value, lambda: 3.0, 3.0, [
        (3.0 * DEG, "degrees"), (1.5, "scaled"), (-3.0, "sign_flip")], {"name": "φ̇_3 (rad/s)"}))
    T.append(TryIt("13-4/try-3", check_value, lambda: np.pi / 2, np.pi / 2, [
        (90.0, "degrees"), (-np.pi / 2, "sign_flip"), (np.pi, "scaled")], {"name": "rack displacement (m)"}))
    j1 = lambda: example("ch13_example3")[0].constraint("1")  # noqa: E731
    T.append(TryIt("13-5/try-1", check_jacobian, j1,
                   [["1", "0", "0", "-1", "0", "-sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]], [
        ([["1", "0", "0", "-1", "0", "0"], ["0", "1", "0", "0", "-1", "0"]], "missing_chain_rule"),
        ([["1", "0", "0", "-1", "0", "cos(phi2)"], ["0", "1", "0", "0", "-1", "sin(phi2)"]], "A_for_B"),
        ([["1", "0", "0", "-1", "0", "sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]], "sign_flip")]))
    dx, dy = "(x2 + cos(phi2) - x3 + 1.5*cos(phi3))", "(y2 + sin(phi2) - y3 + 1.5*sin(phi3))"
    j8 = [[f"2*{dx}", f"2*{dy}", f"-2*{dx}*sin(phi2) + 2*{dy}*cos(phi2)", f"-2*{dx}", f"-2*{dy}",
           f"-3*{dx}*sin(phi3) + 3*{dy}*cos(phi3)"]]
    zeros = [list(j8[0])]
    zeros[0][2] = zeros[0][5] = "0"
    T.append(TryIt("13-5/try-2", check_jacobian, lambda: example("ch13_example3")[0].constraint("3"), j8, [
        (zeros, "book_misprint"), ([[e if k < 3 else f"-({e})" for k, e in enumerate(j8[0])]], "sign_flip")]))
    m3, q3, qd3, qdd3 = example("ch13_example3")
    J88 = m3.Phi_q(q3)[7, 8]
    T.append(TryIt("13-5/try-3", check_value, lambda: J88, J88, [(-J88, "sign_flip"), (J88 / 2, "scaled")],
                   {"name": "∂Φ_8/∂φ_3 at t = 0"}))
    T.append(TryIt("13-6/try-1", check_nu, lambda: example("ch13_example3")[0], ["0"] * 8 + ["100"], [
        (["0"] * 8 + ["-100"], "nu_sign"), (["0"] * 9, "nu_missing"), (["0"] * 8 + [str(100 * DEG)], "degrees")]))
    vB = m3.point_velocity(q3, qd3, "rocker", "B")
    p3, rd3, w3 = q3[8], qd3[6:8], qd3[8]
    T.append(TryIt("13-6/try-2", check_value, lambda: float(np.linalg.norm(vB)), float(np.linalg.norm(vB)), [
        (float(np.linalg.norm(vB)) * DEG, "degrees"), (2 * float(np.linalg.norm(vB)), "scaled")],
        {"name": "|v_B| at t = 0 (m/s)"}))
    T.append(TryIt("13-6/try-3", check_value, lambda: expected.point_velocity(rd3, p3, w3, [-1.5, 0]), vB, [
        (rd3 + A_(p3) @ np.array([-1.5, 0]) * w3, "A_for_B"), (rd3 - P.B(p3) @ np.array([-1.5, 0]) * w3, "sign_flip"),
        (-vB, "sign_flip")], {"name": "v_B at t = 0 (m/s)"}))
    T.append(TryIt("13-7/try-1", check_gamma, j1, ["dphi2**2*cos(phi2)", "dphi2**2*sin(phi2)"], [
        (["-dphi2**2*cos(phi2)", "-dphi2**2*sin(phi2)"], "gamma_sign"),
        (["dphi2*cos(phi2)", "dphi2*sin(phi2)"], "missing_square"), (["0", "0"], "missing_chain_rule")]))
    g8 = m3.gamma(q3, qd3, 0.0)[7]
    T.append(TryIt("13-7/try-2", check_value, lambda: g8, g8, [(-g8, "sign_flip"), (g8 / 2, "scaled")],
                   {"name": "γ_8 at t = 0"}))
    aB = m3.point_acceleration(q3, qd3, qdd3, "rocker", "B")
    rdd3, a3 = qdd3[6:8], qdd3[8]
    sB = np.array([-1.5, 0])
    T.append(TryIt("13-7/try-3", check_value, lambda: expected.point_acceleration(rdd3, p3, w3, a3, sB), aB, [
        (rdd3 + P.B(p3) @ sB * a3, "missing_term"), (rdd3 + P.B(p3) @ sB * a3 + A_(p3) @ sB * w3**2, "sign_flip"),
        (rdd3 + P.B(p3) @ sB * a3 - A_(p3) @ sB * w3, "missing_square")], {"name": "a_B at t = 0 (m/s²)"}))
    return T


# ================================================================================================ chapter 14
AXES = ([0, 0.6, 0.8], [0, -0.8, 0.6], [1, 0, 0])
ANG = np.radians([40.0, 25.0, -60.0])
A_GIVEN = np.array([[2.0, -1.0, 2.0], [2.0, 2.0, -1.0], [-1.0, 2.0, 2.0]]) / 3
R = S.rotations


def _ch14():
    T = []
    A1 = R.A_from_axes(*AXES)
    left = A1.copy()
    left[:, 2] *= -1
    stretched = A1.copy()
    stretched[:, 1] *= 1.2
    T.append(TryIt("14-1/try-1", check_rotation, lambda: expected.A_from_axes(*AXES), A1, [
        (A1.T, "transposed"), (left, "left_handed"), (stretched, "not_orthogonal")], {"name": "A"}))
    s = np.array([2.0, 1.0, -1.0])
    T.append(TryIt("14-1/try-2", check_value, lambda: expected.local_components(A1, s), A1.T @ s, [
        (A1 @ s, "A_for_AT"), (-A1.T @ s, "sign_flip")], {"name": "s'"}))
    p1 = R.p_from_A(A1)
    r0, sQ = np.array([0.5, -1.0, 2.0]), np.array([0.4, 0.0, 1.5])
    T.append(TryIt("14-1/try-3", check_value, lambda: expected.spatial_point_position(r0, p1, sQ), r0 + A1 @ sQ, [
        (r0 + A1.T @ sQ, "A_transposed"), (r0 + sQ, "local_vector")], {"name": "r^Q"}))
    A2 = R.A_from_euler(*ANG)
    T.append(TryIt("14-2/try-1", check_rotation, lambda: expected.A_from_euler(*ANG), A2, [
        (R.A_from_euler(ANG[2], ANG[1], ANG[0]), "extrinsic_order"), (A2.T, "transposed"),
        (R.A_from_euler(*(ANG * DEG)), "degrees")], {"name": "A(40°, 25°, −60°)"}))
    rates = [2.0, 0.0, -1.0]
    wb = R.omega_from_euler_rates(ANG, rates, frame="body")
    T.append(TryIt("14-2/try-2", check_value, lambda: expected.omega_from_euler_rates(ANG, rates, frame="body"), wb, [
        (R.omega_from_euler_rates(ANG, rates, frame="global"), "wrong_frame"), (wb * DEG, "degrees")],
        {"name": "ω' (rad/s)"}))
    a = np.asarray(R.euler_from_A(A_GIVEN))
    T.append(TryIt("14-2/try-3", check_value, lambda: expected.euler_from_A(A_GIVEN), a, [
        (a * DEG, "degrees"), (a[::-1].copy(), "extrinsic_order")], {"name": "(ψ, θ, φ)"}))
    T.append(TryIt("14-2/try-3b", check_value, lambda: expected.euler_from_A(A_GIVEN),
                   np.array([a[0] + np.pi, -a[1], a[2] - np.pi]), [], {"name": "(ψ, θ, φ)"}))
    u, chi = np.array([0, 1, 1]) / np.sqrt(2), np.pi / 2
    p = R.p_from_axis_angle(u, chi)
    T.append(TryIt("14-3/try-1", check_euler_parameters, lambda: expected.p_from_axis_angle([0, 1, 1], chi), p, [
        (np.r_[np.cos(chi), u * np.sin(chi)], "full_angle"), (np.r_[np.cos(45.0), u * np.sin(45.0)], "degrees"),
        (np.r_[p[1:], p[0]], "scalar_last"), (np.r_[np.cos(chi / 2), np.array([0, 1, 1]) * np.sin(chi / 2)],
                                              "not_normalized")], {"name": "p"}))
    T.append(TryIt("14-3/try-1b", check_euler_parameters, lambda: expected.p_from_axis_angle([0, 1, 1], chi), -p, []))
    pp = np.array([0.5, 0.5, 0.5, 0.5])
    App = R.A_from_p(pp)
    from kinbook.grading.expected import _book_A_of_p

    T.append(TryIt("14-3/try-2", check_rotation, lambda: expected.A_from_p(pp), App, [
        (0.5 * App, "factor_2_missing"), (_book_A_of_p(pp), "book_misprint"), (App.T, "transposed")],
        {"name": "A(p)"}))
    pd = np.array([-0.1, 0.3, -0.1, -0.1])
    w = R.omega_from_p_dot(pp, pd)
    T.append(TryIt("14-3/try-3", check_value, lambda: expected.omega_from_p_dot(pp, pd), w, [
        (R.omega_from_p_dot(pp, pd, frame="body"), "G_for_E"), (0.5 * w, "factor_2_missing"), (-w, "sign_flip")],
        {"name": "ω (rad/s)"}))
    # 14-4, 14-5: constraints
    ball = S.Mechanism("ball joint")
    ball.add_body("i", points={"P": (0, 0, 1)})
    ball.add_body("j", points={"P": (-1, 0.5, 0)})
    ball.add(S.Spherical("i", "j", point="P", name="ball"))
    qi, qj = ball.body_symbols("i"), ball.body_symbols("j")
    Ai, Aj = R.A_from_p(list(qi[3:])), R.A_from_p(list(qj[3:]))
    si, sj = sp.Matrix([0, 0, 1]), sp.Matrix([-1, sp.Rational(1, 2), 0])
    ok = sp.Matrix(qi[:3]) + Ai * si - sp.Matrix(qj[:3]) - Aj * sj
    T.append(TryIt("14-4/try-1", check_phi, lambda: ball.constraint("ball"), ok, [
        (sp.Matrix(qi[:3]) + Ai.T * si - sp.Matrix(qj[:3]) - Aj.T * sj, "A_transposed"),
        (sp.Matrix(qi[:3]) + si - sp.Matrix(qj[:3]) - sj, "local_vector"),
        (sp.Matrix(qi[:3]) + Ai * si - sp.Matrix(qj[:3]) + Aj * sj, "sign_flip"),
        (list(ok) + [sum(x**2 for x in qi[3:]) - 1], "dependent_row")]))
    n1 = S.Mechanism("n1")
    n1.add_body("i", points={"C": (1.2, 0, 0), "B": (1.2, 0, 1.0)})
    n1.add_body("j", points={"C": (0.5, 0, 0), "B": (1.5, 0, 0)})
    n1.add(S.Normal1("i", "j", vector_i=["C", "B"], vector_j=["C", "B"], name="n1"))
    qi, qj = n1.body_symbols("i"), n1.body_symbols("j")
    pi, pj = sp.Matrix(qi[3:]), sp.Matrix(qj[3:])
    li, lj = sp.Matrix([0, 0, 1]), sp.Matrix([1, 0, 0])
    gi, gj = R.A_from_p(pi) * li, R.A_from_p(pj) * lj
    C = lambda p, a: 2 * (R.E(p) * R.a_bar(a) + a * p.T)  # noqa: E731
    right = sp.Matrix.hstack(sp.zeros(1, 3), gj.T * C(pi, li), sp.zeros(1, 3), gi.T * C(pj, lj))
    eg = sp.Matrix.hstack(sp.zeros(1, 3), gj.T * 2 * R.E(pi) * R.a_bar(li), sp.zeros(1, 3), gi.T * 2 * R.E(pj) * R.a_bar(lj))
    T.append(TryIt("14-4/try-2", check_jacobian, lambda: n1.constraint("n1"), right, [
        (eg, "eg_jacobian"), (sp.zeros(1, 14), "missing_chain_rule"), (right.T, "transposed")]))
    four = example("spatial_fourbar")[0]
    T.append(TryIt("14-5/try-1", check_gamma, lambda: four.constraint("normalization crank"),
                   "-2*(de02**2 + de12**2 + de22**2 + de32**2)", [
        ("2*(de02**2 + de12**2 + de22**2 + de32**2)", "gamma_sign"),
        ("-(de02**2 + de12**2 + de22**2 + de32**2)", "scaled"),
        ("-2*(de02 + de12 + de22 + de32)", "missing_square")]))
    p3, p4 = sp.Matrix(four.body_symbols("coupler")[3:]), sp.Matrix(four.body_symbols("rocker")[3:])
    a3, a4 = R.A_from_p(p3) * sp.Matrix([0, 1, 0]), R.A_from_p(p4) * sp.Matrix([1, 0, 0])
    I3, Z = sp.eye(3), sp.zeros(1, 3)
    Cv = lambda p, a: 2 * (R.E(p) * R.a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)  # noqa: E731
    Ev = lambda p, a: 2 * R.E(p) * R.a_bar(sp.Matrix(a))  # noqa: E731
    JB = sp.Matrix.vstack(sp.Matrix.hstack(I3, Cv(p3, [3.2, 0, 0]), -I3, -Cv(p4, [0, 1.5, 0])),
                          sp.Matrix.hstack(Z, a4.T * Cv(p3, [0, 1, 0]), Z, a3.T * Cv(p4, [1, 0, 0])))
    JE = sp.Matrix.vstack(JB[:3, :], sp.Matrix.hstack(Z, a4.T * Ev(p3, [0, 1, 0]), Z, a3.T * Ev(p4, [1, 0, 0])))
    T.append(TryIt("14-5/try-2", check_jacobian, lambda: four.constraint("B"), JB, [(JE, "eg_jacobian")]))
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
    T.append(TryIt("ex08/gamma_joint", check_gamma, lambda: ex1().constraint("3"),
                   ["cos(phi2)*dphi2**2 + 3*cos(phi3)*dphi3**2", "sin(phi2)*dphi2**2 + 3*sin(phi3)*dphi3**2"], [
        (["-cos(phi2)*dphi2**2 - 3*cos(phi3)*dphi3**2", "-sin(phi2)*dphi2**2 - 3*sin(phi3)*dphi3**2"], "gamma_sign"),
        (["cos(phi2)*dphi2 + 3*cos(phi3)*dphi3", "sin(phi2)*dphi2 + 3*sin(phi3)*dphi3"], "missing_square")]))
    return T


def all_tryits():
    out = _ch13() + _ch14() + _exercises()
    return [t for t in out if t.right is not None]
