"""Try-its of the chapter-13 notebooks (planar kinematics). Each worked answer is a function: its parameters
are the notebook variables it reads, its body is what ``kb.reveal`` shows. Names assigned in a worked answer
are new in their notebook (``my_…`` or local to the exercise), so pasting one never rebinds a name the notebook
uses elsewhere."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ... import examples
from ...grading import check_gamma, check_jacobian, check_nu, check_phi, check_value
from ...planar import A, B, Mechanism, Revolute, RevoluteRevolute, Translational, point_acceleration
from ...planar import point_position, point_velocity
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
