"""Try-its of the chapter-14 notebooks (spatial kinematics); see :mod:`kinbook.book.tryits.ch13`."""

from __future__ import annotations

import numpy as np

from ...grading import check_euler_parameters, check_rotation, check_value
from ...spatial import (A_from_axes, A_from_euler, A_from_p, euler_from_A, omega_from_euler_rates, omega_from_p_dot,
                        p_from_A, p_from_axis_angle, point_position)
from . import register

_AXES_14_1 = ([0, 0.6, 0.8], [0, -0.8, 0.6], [1, 0, 0])


# ------------------------------------------------------------------------------------------------- 14-1
def _s14_1_1():
    my_A = np.array([[0.0, 0.0, 1.0],
                     [0.6, -0.8, 0.0],
                     [0.8, 0.6, 0.0]])          # the columns are u_ξ, u_η, u_ζ (eq. 7)
    return my_A


register("14-1/try-1", "my_A", check_rotation, lambda: A_from_axes(*_AXES_14_1), _s14_1_1, {"name": "A"})


def _s14_1_2():
    A_try = np.column_stack([[0, 0.6, 0.8], [0, -0.8, 0.6], [1, 0, 0]])
    my_s_local = A_try.T @ np.array([2.0, 1.0, -1.0])        # eq. 9: s' = Aᵀ s
    return my_s_local


register("14-1/try-2", "my_s_local", check_value, lambda: A_from_axes(*_AXES_14_1).T @ np.array([2.0, 1.0, -1.0]),
         _s14_1_2, {"name": "s'"})


def _s14_1_3():
    A_try = np.column_stack([[0, 0.6, 0.8], [0, -0.8, 0.6], [1, 0, 0]])
    my_rQ = np.array([0.5, -1.0, 2.0]) + A_try @ np.array([0.4, 0.0, 1.5])     # r^Q = r + A s'^Q
    return my_rQ


register("14-1/try-3", "my_rQ", check_value,
         lambda: point_position([0.5, -1.0, 2.0], p_from_A(A_from_axes(*_AXES_14_1)), [0.4, 0.0, 1.5]), _s14_1_3,
         {"name": "r^Q"})


# ------------------------------------------------------------------------------------------------- 14-2
_ANGLES_14_2 = np.radians([40.0, 25.0, -60.0])


def _s14_2_1():
    a1, a2, a3 = np.radians([40.0, 25.0, -60.0])
    turn_z1 = np.array([[np.cos(a1), -np.sin(a1), 0], [np.sin(a1), np.cos(a1), 0], [0, 0, 1]])
    turn_x = np.array([[1, 0, 0], [0, np.cos(a2), -np.sin(a2)], [0, np.sin(a2), np.cos(a2)]])
    turn_z2 = np.array([[np.cos(a3), -np.sin(a3), 0], [np.sin(a3), np.cos(a3), 0], [0, 0, 1]])
    my_A = turn_z1 @ turn_x @ turn_z2          # intrinsic turns multiply on the right
    return my_A


register("14-2/try-1", "my_A", check_rotation, lambda: A_from_euler(*_ANGLES_14_2), _s14_2_1,
         {"name": "A(40°, 25°, −60°)", "angles": tuple(_ANGLES_14_2)})


def _s14_2_2():
    a2, a3 = np.radians([25.0, -60.0])          # θ and φ; ψ does not enter ω'
    rates = [2.0, 0.0, -1.0]                   # ψ̇, θ̇, φ̇ in rad/s
    my_omega_body = np.array([np.sin(a2) * np.sin(a3) * rates[0] + np.cos(a3) * rates[1],
                              np.sin(a2) * np.cos(a3) * rates[0] - np.sin(a3) * rates[1],
                              np.cos(a2) * rates[0] + rates[2]])
    return my_omega_body


register("14-2/try-2", "my_omega_body", check_value,
         lambda: omega_from_euler_rates(_ANGLES_14_2, [2.0, 0.0, -1.0], frame="body"), _s14_2_2,
         {"name": "ω' (rad/s)", "angles": True})


_A_14_2_3 = np.array([[2.0, -1.0, 2.0], [2.0, 2.0, -1.0], [-1.0, 2.0, 2.0]]) / 3


def _s14_2_3(A_given):
    my_angles = [np.arctan2(A_given[0, 2], -A_given[1, 2]),      # ψ
                 np.arccos(A_given[2, 2]),                        # θ
                 np.arctan2(A_given[2, 0], A_given[2, 1])]       # φ
    return my_angles


register("14-2/try-3", "my_angles", check_value, lambda: euler_from_A(_A_14_2_3), _s14_2_3,
         {"name": "(ψ, θ, φ)", "angles": True}, context=lambda: {"A_given": _A_14_2_3})


# ------------------------------------------------------------------------------------------------- 14-3
def _s14_3_1():
    half_angle = np.radians(90) / 2
    u_unit = np.array([0.0, 1.0, 1.0]) / np.sqrt(2)
    my_p = [np.cos(half_angle), *(u_unit * np.sin(half_angle))]
    return my_p


register("14-3/try-1", "my_p", check_euler_parameters, lambda: p_from_axis_angle([0, 1, 1], 90, degrees=True),
         _s14_3_1, {"name": "p (90° about [0, 1, 1])", "axis": np.array([0, 1, 1]) / np.sqrt(2), "angle": np.pi / 2})


def _s14_3_2():
    e0_, e_ = 0.5, np.array([0.5, 0.5, 0.5])
    e_tilde = np.array([[0.0, -e_[2], e_[1]],
                        [e_[2], 0.0, -e_[0]],
                        [-e_[1], e_[0], 0.0]])
    my_A_p = 2 * ((e0_**2 - 0.5) * np.eye(3) + np.outer(e_, e_) + e0_ * e_tilde)
    return my_A_p


register("14-3/try-2", "my_A_p", check_rotation, lambda: A_from_p([0.5, 0.5, 0.5, 0.5]), _s14_3_2, {"name": "A(p)"})


def _s14_3_3():
    e0_, e_ = 0.5, np.array([0.5, 0.5, 0.5])
    e_tilde = np.array([[0.0, -e_[2], e_[1]], [e_[2], 0.0, -e_[0]], [-e_[1], e_[0], 0.0]])
    E_try = np.column_stack([-e_, e_tilde + e0_ * np.eye(3)])      # E = [−e, ẽ + e0 I]
    my_omega = 2 * E_try @ np.array([-0.1, 0.3, -0.1, -0.1])
    return my_omega


register("14-3/try-3", "my_omega", check_value,
         lambda: omega_from_p_dot([0.5, 0.5, 0.5, 0.5], [-0.1, 0.3, -0.1, -0.1]), _s14_3_3, {"name": "ω (rad/s)"})
