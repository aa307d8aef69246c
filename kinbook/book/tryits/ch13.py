"""Try-its of the chapter-13 notebooks (planar kinematics). Each worked answer is a function: its parameters
are the notebook variables it reads, its body is what ``kb.reveal`` shows. Names assigned in a worked answer
are new in their notebook (``my_…`` or local to the exercise), so pasting one never rebinds a name the notebook
uses elsewhere."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ... import examples
from ...grading import check_gamma, check_jacobian, check_nu, check_phi, check_value
from ...planar import (
    A,
    B,
    Mechanism,
    Revolute,
    RevoluteRevolute,
    Translational,
    point_acceleration,
    point_position,
    point_velocity,
)
from . import register


# ------------------------------------------------------------------------------------------------- 13-1
def _s13_1_1():
    phi = np.radians(120)
    my_A = np.array([[np.cos(phi), -np.sin(phi)],
                     [np.sin(phi), np.cos(phi)]])
    return my_A


register("13-1/try-1", "my_A", check_value, lambda: A(np.radians(120)), _s13_1_1,
         {"name": "A(120°)", "angles": True})


def _s13_1_2():
    x, y, phi = 1.5, -0.5, np.radians(45)
    xi, eta = 0.8, 0.3
    my_rQ = [x + xi * np.cos(phi) - eta * np.sin(phi),
             y + xi * np.sin(phi) + eta * np.cos(phi)]
    return my_rQ


register("13-1/try-2", "my_rQ", check_value,
         lambda: point_position([1.5, -0.5], np.radians(45), [0.8, 0.3]), _s13_1_2, {"name": "r_i^Q", "angles": True})


def _s13_1_3():
    phi, s_Q = np.radians(45), np.array([0.8, 0.3])
    my_vaQ = np.r_[np.array([0.2, 0.0]) + B(phi) @ s_Q * 2.0,          # eq. 10
                   B(phi) @ s_Q * (-1.0) - A(phi) @ s_Q * 2.0**2]      # eq. 13
    return my_vaQ


def _t13_1_3():
    phi, s_Q = np.radians(45), [0.8, 0.3]
    return np.r_[point_velocity([0.2, 0.0], phi, 2.0, s_Q), point_acceleration([0.0, 0.0], phi, 2.0, -1.0, s_Q)]


register("13-1/try-3", "my_vaQ", check_value, _t13_1_3, _s13_1_3, {"name": "[v_Q, a_Q]"})


# ------------------------------------------------------------------------------------------------- 13-2
def _two_bodies(name, points_1, points_2, joint):
    m = Mechanism(name)
    m.add_body("b1", points=points_1)
    m.add_body("b2", points=points_2)
    m.add(joint)
    return m.constraint("1")


def _s13_2_1():
    my_Phi = ["x1 + cos(phi1) - x2 + 1.5*cos(phi2) + 0.2*sin(phi2)",
              "y1 + sin(phi1) - y2 + 1.5*sin(phi2) - 0.2*cos(phi2)"]
    return my_Phi


register("13-2/try-1", "my_Phi", check_phi,
         lambda: _two_bodies("crank and coupler", {"A": (1, 0)}, {"A": (-1.5, 0.2)}, Revolute("b1", "b2", point="A")),
         _s13_2_1)


def _s13_2_2():
    # r_1^P = (x1, y1), r_1^Q = (x1 + cos φ1, y1 + sin φ1), r_2^P = (x2, y2); eq. 26 with O → Q
    my_Phi_t = ["(x1 - (x1 + cos(phi1)))*(y2 - y1) - (y1 - (y1 + sin(phi1)))*(x2 - x1)",
                "phi1 - phi2 - (0 - 0)"]
    return my_Phi_t


register("13-2/try-2", "my_Phi_t", check_phi,
         lambda: _two_bodies("guide and slider", {"P": (0, 0), "Q": (1, 0)}, {"P": (0, 0)},
                             Translational("b1", "b2", axis=("P", "Q"), point_j="P")), _s13_2_2)


def _s13_2_3():
    my_Phi_rr = ["(x1 + 2*cos(phi1) - x2 + 0.5*sin(phi2))**2 + (y1 + 2*sin(phi1) - y2 - 0.5*cos(phi2))**2 - 9"]
    return my_Phi_rr


register("13-2/try-3", "my_Phi_rr", check_phi,
         lambda: _two_bodies("two bodies and a link", {"B": (2, 0)}, {"C": (0, 0.5)},
                             RevoluteRevolute("b1", "b2", "B", "C", length=3)), _s13_2_3)


# ------------------------------------------------------------------------------------------------- 13-3
@lru_cache(maxsize=None)
def _example(name):
    m = examples.load(name)
    return m, m.solve_position(0.0)


def _s13_3_1():
    my_Phi_45 = ["x1 - x2 + cos(phi2)",
                 "y1 - y2 + sin(phi2)"]
    return my_Phi_45


register("13-3/try-1", "my_Phi_45", check_phi, lambda: _example("ch13_example1")[0].constraint("1"), _s13_3_1)


def _s13_3_2(m3):
    q_it = m3.q0                                   # the guess stored in the mechanism file
    for _ in range(8):                             # Φ_q Δq = −Φ, then q ← q + Δq
        q_it = q_it + np.linalg.solve(m3.Phi_q(q_it, 0.0), -m3.Phi(q_it, 0.0))
    my_q3 = q_it
    return my_q3


register("13-3/try-2", "my_q3", check_value, lambda: _example("ch13_example3")[1], _s13_3_2,
         {"name": "q(0) of example 3", "angles": True}, context=lambda: {"m3": _example("ch13_example3")[0]})


def _s13_3_3(q1):
    x4, y4, phi4 = q1[9], q1[10], q1[11]
    my_rB = np.array([x4 - 1.5 * np.cos(phi4),
                      y4 - 1.5 * np.sin(phi4)])
    return my_rB


register("13-3/try-3", "my_rB", check_value,
         lambda: _example("ch13_example1")[0].point_position(_example("ch13_example1")[1], "rocker", "B"), _s13_3_3,
         {"name": "r^B"}, context=lambda: {"q1": _example("ch13_example1")[1]})


# ------------------------------------------------------------------------------------------------- 13-4
def _s13_4_1():
    my_gear_row = ["2*((phi1 - 0) - (phi2 - 0)) + 1*((phi3 - 0) - (phi2 - 0))"]    # eq. 38, all φ⁰ = 0
    return my_gear_row


register("13-4/try-1", "my_gear_row", check_phi, lambda: _example("ch13_planetary")[0].constraints[3], _s13_4_1)


def _s13_4_2():
    my_w3 = 1 * (1 + 2 / 1)        # relative to the arm: (ω3 − ω2) = −(ρ1/ρ3)(ω1 − ω2), with ω1 = 0, ω2 = 1 rad/s
    return my_w3


def _t13_4_2():
    pl, q = _example("ch13_planetary")
    return pl.solve_velocity(q, 0.0)[pl.index("phi3")]


register("13-4/try-2", "my_w3", check_value, _t13_4_2, _s13_4_2, {"name": "φ̇_3 (rad/s)"})


def _s13_4_3():
    my_dx = 1 * np.pi / 2          # eq. 40: x_j − x_j⁰ = ρ (φ_i − φ_i⁰), the angle in radians
    return my_dx


def _t13_4_3():
    rp = examples.load("ch13_rack_pinion")
    return rp.solve_position(np.pi / 2)[rp.index("x3")] - rp.solve_position(0.0)[rp.index("x3")]


register("13-4/try-3", "my_dx", check_value, _t13_4_3, _s13_4_3, {"name": "rack displacement (m)", "angles": True})


# ------------------------------------------------------------------------------------------------- 13-5
def _s13_5_1():
    my_J1 = [["1", "0", "0", "-1", "0", "-sin(phi2)"],
             ["0", "1", "0", "0", "-1", "cos(phi2)"]]
    return my_J1


register("13-5/try-1", "my_J1", check_jacobian, lambda: _example("ch13_example3")[0].constraint("1"), _s13_5_1)


def _s13_5_2():
    dx = "(x2 + cos(phi2) - x3 + 1.5*cos(phi3))"      # x^A − x^B
    dy = "(y2 + sin(phi2) - y3 + 1.5*sin(phi3))"      # y^A − y^B
    my_J8 = [[f"2*{dx}", f"2*{dy}", f"-2*{dx}*sin(phi2) + 2*{dy}*cos(phi2)",
              f"-2*{dx}", f"-2*{dy}", f"-3*{dx}*sin(phi3) + 3*{dy}*cos(phi3)"]]
    return my_J8


register("13-5/try-2", "my_J8", check_jacobian, lambda: _example("ch13_example3")[0].constraint("3"), _s13_5_2)


def _s13_5_3(mech, q0):
    rA, rB = mech.point_position(q0, "crank", "A"), mech.point_position(q0, "rocker", "B")
    my_J88 = 2 * (rA[0] - rB[0]) * (rB[1] - q0[7]) - 2 * (rA[1] - rB[1]) * (rB[0] - q0[6])   # corrected Table 13.3
    return my_J88


def _t13_5_3():
    m, q = _example("ch13_example3")
    return m.Phi_q(q, 0.0)[7, 8]


register("13-5/try-3", "my_J88", check_value, _t13_5_3, _s13_5_3, {"name": "∂Φ_8/∂φ_3 at t = 0"},
         context=lambda: dict(zip(("mech", "q0"), _example("ch13_example3"))))


# ------------------------------------------------------------------------------------------------- 13-6
def _s13_6_1():
    my_nu = ["0", "0", "0", "0", "0", "0", "0", "0", "100"]
    return my_nu


register("13-6/try-1", "my_nu", check_nu, lambda: _example("ch13_example3")[0], _s13_6_1)


@lru_cache(maxsize=None)
def _ex3_motion():
    m, q = _example("ch13_example3")
    qd = m.solve_velocity(q, 0.0)
    return m, q, qd, m.solve_acceleration(q, qd, 0.0)


def _s13_6_2(qd0):
    my_speed_B = 3 * abs(qd0[8])         # B turns about the fixed O_B at 3 m
    return my_speed_B


register("13-6/try-2", "my_speed_B", check_value,
         lambda: np.linalg.norm(_ex3_motion()[0].point_velocity(*_ex3_motion()[1:3], "rocker", "B")), _s13_6_2,
         {"name": "|v_B| at t = 0 (m/s)"}, context=lambda: {"qd0": _ex3_motion()[2]})


def _s13_6_3(q0, qd0):
    x3d, y3d, w3, phi3 = qd0[6], qd0[7], qd0[8], q0[8]
    my_vB = [x3d - (-1.5) * np.sin(phi3) * w3,          # ẋ^P = ẋ − (ξ sin φ + η cos φ) φ̇, with η = 0
             y3d + (-1.5) * np.cos(phi3) * w3]          # ẏ^P = ẏ + (ξ cos φ − η sin φ) φ̇
    return my_vB


register("13-6/try-3", "my_vB", check_value,
         lambda: _ex3_motion()[0].point_velocity(*_ex3_motion()[1:3], "rocker", "B"), _s13_6_3,
         {"name": "v_B at t = 0 (m/s)"}, context=lambda: {"q0": _ex3_motion()[1], "qd0": _ex3_motion()[2]})


# ------------------------------------------------------------------------------------------------- 13-7
def _s13_7_1():
    my_gamma_1 = ["dphi2**2*cos(phi2)", "dphi2**2*sin(phi2)"]     # Table 13.5, revolute row, ξ_2 = −1, η_2 = 0
    return my_gamma_1


register("13-7/try-1", "my_gamma_1", check_gamma, lambda: _example("ch13_example3")[0].constraint("1"), _s13_7_1)


def _s13_7_2(mech, q0, qd0):
    rA, rB = mech.point_position(q0, "crank", "A"), mech.point_position(q0, "rocker", "B")
    vel_A, vel_B = mech.point_velocity(q0, qd0, "crank", "A"), mech.point_velocity(q0, qd0, "rocker", "B")
    cA = mech.point_acceleration(q0, qd0, np.zeros(9), "crank", "A")      # the velocity-dependent part only
    cB = mech.point_acceleration(q0, qd0, np.zeros(9), "rocker", "B")
    my_gamma_8 = -2 * (vel_A - vel_B) @ (vel_A - vel_B) - 2 * (rA - rB) @ (cA - cB)
    return my_gamma_8


register("13-7/try-2", "my_gamma_8", check_value,
         lambda: _ex3_motion()[0].gamma(*_ex3_motion()[1:3], 0.0)[7], _s13_7_2, {"name": "γ_8 at t = 0"},
         context=lambda: dict(zip(("mech", "q0", "qd0"), _ex3_motion()[:3])))


def _s13_7_3(q0, qd0, qdd0):
    x3dd, y3dd, a3, w3, phi3 = qdd0[6], qdd0[7], qdd0[8], qd0[8], q0[8]
    my_aB = [x3dd - (-1.5) * (a3 * np.sin(phi3) + w3**2 * np.cos(phi3)),       # eq. 13 with ξ = −1.5, η = 0
             y3dd + (-1.5) * (a3 * np.cos(phi3) - w3**2 * np.sin(phi3))]
    return my_aB


register("13-7/try-3", "my_aB", check_value,
         lambda: _ex3_motion()[0].point_acceleration(*_ex3_motion()[1:], "rocker", "B"), _s13_7_3,
         {"name": "a_B at t = 0 (m/s²)"}, context=lambda: dict(zip(("q0", "qd0", "qdd0"), _ex3_motion()[1:])))
