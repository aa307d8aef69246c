"""Try-its of the chapter-14 notebooks (spatial kinematics); see :mod:`kinbook.book.tryits.ch13`."""

from __future__ import annotations

import numpy as np

from ...grading import check_euler_parameters, check_gamma, check_jacobian, check_phi, check_rotation, check_value
from ...spatial import (
    A_from_axes,
    A_from_euler,
    A_from_p,
    euler_from_A,
    omega_from_euler_rates,
    omega_from_p_dot,
    p_from_A,
    p_from_axis_angle,
    point_position,
)
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
    psi_d, theta_d, phi_d = 2.0, 0.0, -1.0     # ψ̇, θ̇, φ̇ in rad/s
    my_omega_body = np.array([np.sin(a2) * np.sin(a3) * psi_d + np.cos(a3) * theta_d,
                              np.sin(a2) * np.cos(a3) * psi_d - np.sin(a3) * theta_d,
                              np.cos(a2) * psi_d + phi_d])
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


# ------------------------------------------------------------------------------------------------- 14-4
def _two_spatial_bodies(points_i, points_j, constraint):
    from ...spatial import Mechanism

    m = Mechanism("two bodies")
    m.add_body("i", points=points_i)
    m.add_body("j", points=points_j)
    m.add(constraint)
    return m.constraints[-1]


def _s14_4_1():
    import sympy as sp

    x1, y1, z1, e01, e11, e21, e31 = sp.symbols("x1 y1 z1 e01 e11 e21 e31", real=True)   # body i
    x2, y2, z2, e02, e12, e22, e32 = sp.symbols("x2 y2 z2 e02 e12 e22 e32", real=True)   # body j
    my_Phi_s = (sp.Matrix([x1, y1, z1]) + A_from_p([e01, e11, e21, e31]) * sp.Matrix([0, 0, 1])
                - sp.Matrix([x2, y2, z2]) - A_from_p([e02, e12, e22, e32]) * sp.Matrix([-1, sp.Rational(1, 2), 0]))
    return my_Phi_s


def _t14_4_1():
    from ...spatial import Spherical

    return _two_spatial_bodies({"P": (0, 0, 1)}, {"P": (-1, 0.5, 0)}, Spherical("i", "j", point="P", name="ball"))


register("14-4/try-1", "my_Phi_s", check_phi, _t14_4_1, _s14_4_1)


def _s14_4_2():
    import sympy as sp

    from ...spatial import E, a_bar

    par_i, par_j = sp.Matrix(sp.symbols("e01 e11 e21 e31", real=True)), sp.Matrix(sp.symbols("e02 e12 e22 e32", real=True))
    loc_i, loc_j = sp.Matrix([0, 0, 1]), sp.Matrix([1, 0, 0])
    dAa_i = 2 * (E(par_i) * a_bar(loc_i) + loc_i * par_i.T)            # ∂(A_i loc_i)/∂par_i
    dAa_j = 2 * (E(par_j) * a_bar(loc_j) + loc_j * par_j.T)
    glob_i, glob_j = A_from_p(par_i) * loc_i, A_from_p(par_j) * loc_j
    my_Phi_q_n1 = sp.Matrix.hstack(sp.zeros(1, 3), glob_j.T * dAa_i, sp.zeros(1, 3), glob_i.T * dAa_j)
    return my_Phi_q_n1


def _t14_4_2():
    from ...spatial import Normal1

    return _two_spatial_bodies({"O": (0, 0, 0), "C": (1.2, 0, 0), "B": (1.2, 0, 1.0)},
                               {"O": (0, 0, 0), "C": (0.5, 0, 0), "B": (1.5, 0, 0)},
                               Normal1("i", "j", vector_i=["C", "B"], vector_j=["C", "B"], name="n1"))


register("14-4/try-2", "my_Phi_q_n1", check_jacobian, _t14_4_2, _s14_4_2)


def _s14_4_3():
    import sympy as sp

    from ...spatial import skew

    sym_i, sym_j = sp.symbols("x1 y1 z1 e01 e11 e21 e31", real=True), sp.symbols("x2 y2 z2 e02 e12 e22 e32", real=True)
    rot_1, rot_2 = A_from_p(list(sym_i[3:])), A_from_p(list(sym_j[3:]))
    axis_i, axis_j = sp.Matrix([0, 0, sp.Rational(4, 5)]), sp.Matrix([0, 0, sp.Rational(1, 2)])
    cross_in_i = skew(list(axis_i)) * rot_1.T * rot_2 * axis_j            # s_i × s_j in body i's components: row 3 ≡ 0
    ball_rows = sp.Matrix(sym_i[:3]) + rot_1 * sp.Matrix([sp.Rational(6, 5), 0, 0]) - sp.Matrix(sym_j[:3])
    my_Phi_r = ball_rows.col_join(cross_in_i[:2, :])
    return my_Phi_r


def _t14_4_3():
    from ...spatial import Revolute

    return _two_spatial_bodies({"O": (0, 0, 0), "P": (1.2, 0, 0), "Q": (1.2, 0, 0.8)},
                               {"P": (0, 0, 0), "T": (1.4, 0, 0), "U": (1.4, 0, 0.5)},
                               Revolute("i", "j", point="P", axis_i=["P", "Q"], axis_j=["T", "U"], name="r"))


register("14-4/try-3", "my_Phi_r", check_phi, _t14_4_3, _s14_4_3)


# ------------------------------------------------------------------------------------------------- 14-5
def _fourbar():
    from ... import examples

    return examples.load("spatial_fourbar")


def _s14_5_1():
    my_gamma_norm = "-2*(de02**2 + de12**2 + de22**2 + de32**2)"      # −2 ṗᵀṗ
    return my_gamma_norm


register("14-5/try-1", "my_gamma_norm", check_gamma, lambda: _fourbar().constraint("normalization crank"), _s14_5_1)


def _s14_5_2(mech):
    import sympy as sp

    from ...spatial import E, a_bar

    par_3, par_4 = sp.Matrix(mech.body_symbols("coupler")[3:]), sp.Matrix(mech.body_symbols("rocker")[3:])
    dAa = lambda p, a: 2 * (E(p) * a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)      # ∂(A a)/∂p: B_k or C_k
    arm_3, arm_4 = A_from_p(par_3) * sp.Matrix([0, 1, 0]), A_from_p(par_4) * sp.Matrix([1, 0, 0])   # the cross arms, global
    eye3, zero13 = sp.eye(3), sp.zeros(1, 3)
    my_Phi_q_B = sp.Matrix.vstack(
        sp.Matrix.hstack(eye3, dAa(par_3, [3.2, 0, 0]), -eye3, -dAa(par_4, [0, 1.5, 0])),          # (s,3):  I, B_i, −I, −B_j
        sp.Matrix.hstack(zero13, arm_4.T * dAa(par_3, [0, 1, 0]), zero13, arm_3.T * dAa(par_4, [1, 0, 0])))  # (n1,1): 0, s_jᵀC_i, 0, s_iᵀC_j
    return my_Phi_q_B


register("14-5/try-2", "my_Phi_q_B", check_jacobian, lambda: _fourbar().constraint("B"), _s14_5_2,
         context=lambda: {"mech": _fourbar()})


def _s14_5_3(mech):
    import sympy as sp

    from ...spatial import E, a_bar

    dAa = lambda p, a: 2 * (E(p) * a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)
    k_2, k_3 = mech.index("e02"), mech.index("e03")
    pdot_2, pdot_3 = sp.Matrix(mech.qd[k_2:k_2 + 4, 0]), sp.Matrix(mech.qd[k_3:k_3 + 4, 0])
    my_gamma_A = -dAa(pdot_2, [1, 0, 0]) * pdot_2 + dAa(pdot_3, [0, 0, 0]) * pdot_3        # γ = −b_i + b_j, b_k = B_k(ṗ_k) ṗ_k
    return my_gamma_A


register("14-5/try-3", "my_gamma_A", check_gamma, lambda: _fourbar().constraint("A"), _s14_5_3,
         context=lambda: {"mech": _fourbar()})
