"""Try-its of the chapter-14 notebooks (spatial kinematics); see :mod:`kinbook.book.tryits.ch13`."""

from __future__ import annotations

import numpy as np
import sympy as sp

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10: the same parser as tomli
    import tomli as tomllib

from ... import examples
from ...files import build
from ...grading import check_euler_parameters, check_gamma, check_jacobian, check_phi, check_rotation, check_value
from ...grading import expected as X
from ...grading._i18n import Msg, add_texts
from ...i18n import N_, Message
from ...spatial import A_from_p, E, Mechanism, Normal1, Revolute, Spherical, a_bar, skew
from ...spatial import rotations as R
from .registry import register, same_data

__all__ = []  # nothing to import from here: importing the module registers its try-its

_TRIPLES = [[3, 4, 5], [4, 3, 5], [5, 12, 13], [12, 5, 13], [8, 15, 17], [15, 8, 17], [7, 24, 25], [20, 21, 29],
            [3, -4, 5], [-4, 3, 5], [5, -12, 13], [-8, 15, 17]]


def _axes(triple):
    """The body of notebook 14-1 (u_ζ along global x) turned to another angle: cos, sin = a/c, b/c; rounded to
    the 6 digits the question shows."""
    a, b, c = triple
    co, si = round(a / c, 6), round(b / c, 6)
    return [[0.0, co, si], [0.0, -si, co], [1.0, 0.0, 0.0]]


_AXES = [_axes(t) for t in _TRIPLES]


def _axes_text(axes_given):
    f = lambda x: "[" + ", ".join(f"{e:.6g}" for e in x) + "]"  # noqa: E731
    u, v, w = axes_given
    return f"u_ξ = {f(u)}, u_η = {f(v)}, u_ζ = {f(w)}"


# ------------------------------------------------------------------------------------------------- 14-1
def _s14_1_1(*, axes_given):
    my_A = np.column_stack(axes_given)          # the columns are u_ξ, u_η, u_ζ (eq. 7)
    return my_A


register("14-1/try-1", "my_A", check_rotation, lambda axes_given: X.A_from_axes(*axes_given), _s14_1_1, {"name": "A"},
         data={"axes_given": _AXES[0]}, ranges={"axes_given": _AXES}, statement=_axes_text,
         explanation=N_("eq. 7: the columns of A are the body's unit vectors in global components, so that "
                        "s = A s' (a local vector's global components). The axes as rows give Aᵀ."), library=("A_from_axes",))

_S_GLOBAL = [[2, 1, -1], [1, -2, 3], [0, 2, 1], [-1, 1, 2], [3, 0, -2], [2, -1, 1]]


def _s14_1_2(*, axes_given, s_glob):
    A_try = np.column_stack(axes_given)
    my_s_local = A_try.T @ np.array(s_glob, float)          # eq. 9: s' = Aᵀ s
    return my_s_local


register("14-1/try-2", "my_s_local", check_value,
         lambda axes_given, s_glob: X.local_components(R.A_from_axes(*axes_given), s_glob), _s14_1_2,
         {"name": "s'"}, data={"axes_given": _AXES[0], "s_glob": [2, 1, -1]},
         ranges={"axes_given": _AXES, "s_glob": _S_GLOBAL},
         statement=lambda axes_given, s_glob: f"{_axes_text(axes_given)}; s = {s_glob}")


def _s14_1_3(*, axes_given, r_O, s_Q):
    A_try = np.column_stack(axes_given)
    my_rQ = np.array(r_O, float) + A_try @ np.array(s_Q, float)     # r^Q = r + A s'^Q
    return my_rQ


register("14-1/try-3", "my_rQ", check_value,
         lambda axes_given, r_O, s_Q: X.spatial_point_position(r_O, R.p_from_A(R.A_from_axes(*axes_given)), s_Q),
         _s14_1_3, {"name": "r^Q"}, data={"axes_given": _AXES[0], "r_O": [0.5, -1.0, 2.0], "s_Q": [0.4, 0.0, 1.5]},
         ranges={"axes_given": _AXES, "r_O": [[0.5, -1.0, 2.0], [1.0, 0.5, -0.5], [-2.0, 1.0, 0.0]],
                 "s_Q": [[0.4, 0.0, 1.5], [1.0, 0.5, 0.0], [0.0, -0.8, 1.2], [0.6, 0.6, 0.6]]},
         statement=lambda axes_given, r_O, s_Q: f"{_axes_text(axes_given)}; r = {r_O}, s'^Q = {s_Q}", library=("point_position",))


# ------------------------------------------------------------------------------------------------- 14-2
_ANG = {"psi_deg": 40, "theta_deg": 25, "phi_deg": -60}
_ANG_RANGES = {"psi_deg": list(range(-150, 151, 10)), "theta_deg": list(range(10, 171, 5)),
               "phi_deg": list(range(-150, 151, 10))}
_ANG_TEXT = "ψ = {psi_deg}°, θ = {theta_deg}°, φ = {phi_deg}°"


def _s14_2_1(*, psi_deg, theta_deg, phi_deg):
    a1, a2, a3 = np.radians([psi_deg, theta_deg, phi_deg])
    turn_z1 = np.array([[np.cos(a1), -np.sin(a1), 0], [np.sin(a1), np.cos(a1), 0], [0, 0, 1]])
    turn_x = np.array([[1, 0, 0], [0, np.cos(a2), -np.sin(a2)], [0, np.sin(a2), np.cos(a2)]])
    turn_z2 = np.array([[np.cos(a3), -np.sin(a3), 0], [np.sin(a3), np.cos(a3), 0], [0, 0, 1]])
    my_A = turn_z1 @ turn_x @ turn_z2          # intrinsic turns multiply on the right
    return my_A


register("14-2/try-1", "my_A", check_rotation,
         lambda psi_deg, theta_deg, phi_deg: X.A_from_euler(*np.radians([psi_deg, theta_deg, phi_deg])), _s14_2_1,
         {"name": "A(ψ, θ, φ)"}, data=_ANG, ranges=_ANG_RANGES, statement=_ANG_TEXT, library=("A_from_euler",))


def _s14_2_2(*, theta_deg, phi_deg, psi_rate, theta_rate, phi_rate):
    a2, a3 = np.radians([theta_deg, phi_deg])          # θ and φ; ψ does not enter ω'
    my_omega_body = np.array([np.sin(a2) * np.sin(a3) * psi_rate + np.cos(a3) * theta_rate,
                              np.sin(a2) * np.cos(a3) * psi_rate - np.sin(a3) * theta_rate,
                              np.cos(a2) * psi_rate + phi_rate])
    return my_omega_body


_RATES = dict(_ANG, psi_rate=2.0, theta_rate=0.5, phi_rate=-1.0)  # θ̇ ≠ 0: its terms are tested too


register("14-2/try-2", "my_omega_body", check_value,
         lambda psi_deg, theta_deg, phi_deg, psi_rate, theta_rate, phi_rate: X.omega_from_euler_rates(
             np.radians([psi_deg, theta_deg, phi_deg]), [psi_rate, theta_rate, phi_rate], frame="body"), _s14_2_2,
         {"name": "ω' (rad/s)"}, data=_RATES,
         ranges=dict(_ANG_RANGES, psi_rate=(-3.0, 3.0), theta_rate=(-2.0, 2.0), phi_rate=(-3.0, 3.0)),
         statement=_ANG_TEXT + ", ψ̇ = {psi_rate}, θ̇ = {theta_rate}, φ̇ = {phi_rate} rad/s", library=("omega_from_euler_rates",))

_A_14_2_3 = np.array([[2.0, 2.0, -1.0], [-1.0, 2.0, 2.0], [2.0, -1.0, 2.0]]) / 3  # 14-1's body turned back: Aᵀ
_A_GIVEN = [_A_14_2_3] + [np.round(R.A_from_euler(*np.radians(a)), 6) for a in
                          # ψ and φ both past ±90°, where arctan(y/x) and arctan2(y, x) part (issue 29)
                          ([150, 110, -135], [-120, 35, 160], [120, 140, -100], [-150, 80, 110], [100, 20, -170],
                           [-100, 65, 135], [135, 50, 120])]


def _s14_2_3(*, A_given):
    my_angles = [np.arctan2(A_given[0, 2], -A_given[1, 2]),      # ψ
                 np.arccos(A_given[2, 2]),                        # θ
                 np.arctan2(A_given[2, 0], A_given[2, 1])]       # φ
    return my_angles


register("14-2/try-3", "my_angles", check_value, lambda A_given: X.euler_from_A(A_given), _s14_2_3,
         {"name": "(ψ, θ, φ)"}, data={"A_given": _A_14_2_3}, ranges={"A_given": _A_GIVEN},
         statement=lambda A_given: "A_given = " + np.array2string(np.asarray(A_given), precision=6,
                                                                 separator=", ").replace("\n", ""),
         explanation=N_("the third row of A = A_z(ψ) A_x(θ) A_z(φ) is [sin θ sin φ, sin θ cos φ, cos θ] and its "
                        "third column [sin ψ sin θ, −cos ψ sin θ, cos θ]. arccos gives θ in [0, π]; the triple "
                        "(ψ + π, −θ, φ + π) gives the same A and is accepted too."), library=("euler_from_A",))


# ------------------------------------------------------------------------------------------------- 14-3
def _s14_3_1(*, axis_u, chi_deg):
    half_angle = np.radians(chi_deg) / 2
    u_unit = np.array(axis_u, float) / np.linalg.norm(axis_u)
    my_p = [np.cos(half_angle), *(u_unit * np.sin(half_angle))]
    return my_p


register("14-3/try-1", "my_p", check_euler_parameters,
         lambda axis_u, chi_deg: X.p_from_axis_angle(axis_u, np.radians(chi_deg)), _s14_3_1, {"name": "p"},
         data={"axis_u": [0, 1, 1], "chi_deg": 120},
         ranges={"axis_u": [[0, 1, 1], [1, 0, 1], [1, 1, 0], [1, 2, 2], [2, -1, 2], [1, -1, 1], [0, 3, 4]],
                 "chi_deg": list(range(30, 331, 30))},
         statement=N_("χ = {chi_deg}° about u = {axis_u}"), library=("p_from_axis_angle",))

_P_TRY = [[0.5, 0.5, 0.5, 0.5], [0.2, 0.4, 0.4, 0.8], [0.8, 0.4, 0.4, 0.2], [6 / 7, 2 / 7, 3 / 7, 0.0],
          [2 / 9, 4 / 9, 5 / 9, 6 / 9], [0.6, 0.0, 0.8, 0.0], [4 / 9, 4 / 9, 7 / 9, 0.0]]


def _s14_3_2(*, p_try):
    e0_, e_ = p_try[0], np.array(p_try[1:])
    e_tilde = np.array([[0.0, -e_[2], e_[1]],
                        [e_[2], 0.0, -e_[0]],
                        [-e_[1], e_[0], 0.0]])
    my_A_p = 2 * ((e0_**2 - 0.5) * np.eye(3) + np.outer(e_, e_) + e0_ * e_tilde)
    return my_A_p


register("14-3/try-2", "my_A_p", check_rotation, lambda p_try: X.A_from_p(p_try), _s14_3_2, {"name": "A(p)"},
         data={"p_try": [0.5, 0.5, 0.5, 0.5]}, ranges={"p_try": _P_TRY},
         statement=lambda p_try: "p = [" + ", ".join(f"{e:.6g}" for e in p_try) + "]",
         explanation=N_("A sends [1, 0, 0] to its first column. For p = [½, ½, ½, ½] that is [0, 1, 0], and "
                        "[0, 1, 0] goes to [0, 0, 1]: x → y → z → x, the turn of 120° about [1, 1, 1] of section 1 "
                        "(e0 = cos 60° = 0.5, e = u sin 60° with u = [1, 1, 1]/√3)."), library=("A_from_p",))


def _s14_3_3(*, p_dot):
    e0_, e_ = 0.5, np.array([0.5, 0.5, 0.5])
    e_tilde = np.array([[0.0, -e_[2], e_[1]], [e_[2], 0.0, -e_[0]], [-e_[1], e_[0], 0.0]])
    E_try = np.column_stack([-e_, e_tilde + e0_ * np.eye(3)])      # E = [−e, ẽ + e0 I]
    my_omega = 2 * E_try @ np.array(p_dot, float)
    return my_omega


register("14-3/try-3", "my_omega", check_value, lambda p_dot: X.omega_from_p_dot([0.5, 0.5, 0.5, 0.5], p_dot),
         _s14_3_3, {"name": "ω (rad/s)"}, data={"p_dot": [-0.1, 0.3, -0.1, -0.1]},
         # no zero entry and no two alike: a dropped term or a lost sign always shows (issue 29)
         ranges={"p_dot": [[-0.1, 0.3, -0.1, -0.1], [0.1, -0.1, 0.2, -0.2], [0.3, -0.2, 0.1, -0.2],
                           [-0.2, 0.3, 0.1, -0.2], [0.1, 0.2, -0.4, 0.1], [-0.3, 0.1, 0.4, -0.2],
                           [0.2, -0.3, -0.1, 0.2], [-0.1, -0.2, 0.4, -0.1]]},
         statement="ṗ = {p_dot}", library=("omega_from_p_dot",))


# ------------------------------------------------------------------------------------------------- 14-4
def _two_spatial_bodies(points_i, points_j, constraint):
    m = Mechanism("two bodies")
    m.add_body("i", points=points_i)
    m.add_body("j", points=points_j)
    m.add(constraint)
    return m.constraints[-1]


def _s14_4_1(*, s_i_P, s_j_P):
    import sympy as sp

    x1, y1, z1, e01, e11, e21, e31 = sp.symbols("x1 y1 z1 e01 e11 e21 e31", real=True)   # body i
    x2, y2, z2, e02, e12, e22, e32 = sp.symbols("x2 y2 z2 e02 e12 e22 e32", real=True)   # body j
    my_Phi_s = (sp.Matrix([x1, y1, z1]) + A_from_p([e01, e11, e21, e31]) * sp.Matrix(s_i_P)
                - sp.Matrix([x2, y2, z2]) - A_from_p([e02, e12, e22, e32]) * sp.Matrix(s_j_P))
    return my_Phi_s


def _t14_4_1(s_i_P, s_j_P):
    return _two_spatial_bodies({"P": tuple(s_i_P)}, {"P": tuple(s_j_P)}, Spherical("i", "j", point="P", name="ball"))


register("14-4/try-1", "my_Phi_s", check_phi, _t14_4_1, _s14_4_1, data={"s_i_P": [0, 0, 1], "s_j_P": [-1, 0.5, 0]},
         ranges={"s_i_P": [[0, 0, 1], [1, 0, 0], [0.5, 0.5, 0], [0, -1, 0.5], [1, 1, 1]],
                 "s_j_P": [[-1, 0.5, 0], [0, 0, -1], [0.5, -0.5, 1], [2, 0, 0], [0, 1.5, 0]]},
         statement="s'_i^P = {s_i_P}, s'_j^P = {s_j_P}")


def _s14_4_2(*, vec_i, vec_j):
    import sympy as sp

    from kinbook.spatial import E, a_bar

    par_i, par_j = sp.Matrix(sp.symbols("e01 e11 e21 e31", real=True)), sp.Matrix(sp.symbols("e02 e12 e22 e32", real=True))
    loc_i, loc_j = sp.Matrix(vec_i), sp.Matrix(vec_j)
    dAa_i = 2 * (E(par_i) * a_bar(loc_i) + loc_i * par_i.T)            # ∂(A_i loc_i)/∂par_i
    dAa_j = 2 * (E(par_j) * a_bar(loc_j) + loc_j * par_j.T)
    glob_i, glob_j = A_from_p(par_i) * loc_i, A_from_p(par_j) * loc_j
    my_Phi_q_n1 = sp.Matrix.hstack(sp.zeros(1, 3), glob_j.T * dAa_i, sp.zeros(1, 3), glob_i.T * dAa_j)
    return my_Phi_q_n1


def _t14_4_2(vec_i, vec_j):
    C_i, C_j = np.array([1.2, 0, 0]), np.array([0.5, 0, 0])
    return _two_spatial_bodies({"O": (0, 0, 0), "C": tuple(C_i), "B": tuple(C_i + vec_i)},
                               {"O": (0, 0, 0), "C": tuple(C_j), "B": tuple(C_j + vec_j)},
                               Normal1("i", "j", vector_i=["C", "B"], vector_j=["C", "B"], name="n1"))


_VECTORS = [[0, 0, 1], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 2, 1], [1, 0, -1]]
register("14-4/try-2", "my_Phi_q_n1", check_jacobian, _t14_4_2, _s14_4_2, data={"vec_i": [0, 0, 1], "vec_j": [1, 0, 0]},
         ranges={"vec_i": _VECTORS, "vec_j": _VECTORS}, statement="s'_i = {vec_i}, s'_j = {vec_j}")


def _s14_4_3(*, P_hinge):
    import sympy as sp

    from kinbook.spatial import skew

    sym_i, sym_j = sp.symbols("x1 y1 z1 e01 e11 e21 e31", real=True), sp.symbols("x2 y2 z2 e02 e12 e22 e32", real=True)
    rot_1, rot_2 = A_from_p(list(sym_i[3:])), A_from_p(list(sym_j[3:]))
    axis_i, axis_j = sp.Matrix([0, 0, sp.Rational(4, 5)]), sp.Matrix([0, 0, sp.Rational(1, 2)])
    cross_in_i = skew(list(axis_i)) * rot_1.T * rot_2 * axis_j            # s_i × s_j in body i's components: row 3 ≡ 0
    ball_rows = sp.Matrix(sym_i[:3]) + rot_1 * sp.Matrix(P_hinge) - sp.Matrix(sym_j[:3])
    my_Phi_r = ball_rows.col_join(cross_in_i[:2, :])
    return my_Phi_r


def _t14_4_3(P_hinge):
    P = np.array(P_hinge, float)
    return _two_spatial_bodies({"O": (0, 0, 0), "P": tuple(P), "Q": tuple(P + [0, 0, 0.8])},
                               {"P": (0, 0, 0), "T": (1.4, 0, 0), "U": (1.4, 0, 0.5)},
                               Revolute("i", "j", point="P", axis_i=["P", "Q"], axis_j=["T", "U"], name="r"))


def _w14_4_3(P_hinge):
    """The book's way (§14.4, erratum 14.4-p1-two-rows): rows 1-2 of s̃_i s_j in global components."""
    sym_i, sym_j = sp.symbols("x1 y1 z1 e01 e11 e21 e31", real=True), sp.symbols("x2 y2 z2 e02 e12 e22 e32", real=True)
    rot_1, rot_2 = A_from_p(list(sym_i[3:])), A_from_p(list(sym_j[3:]))
    s_i, s_j = rot_1 * sp.Matrix([0, 0, sp.Rational(4, 5)]), rot_2 * sp.Matrix([0, 0, sp.Rational(1, 2)])
    ball = sp.Matrix(sym_i[:3]) + rot_1 * sp.Matrix(P_hinge) - sp.Matrix(sym_j[:3])
    return [(list(ball) + list((skew(list(s_i)) * s_j)[:2, :]), "book_misprint", _msg("x.global_rows"),
             "14.4-p1-two-rows")]


register("14-4/try-3", "my_Phi_r", check_phi, _t14_4_3, _s14_4_3, wrong_forms=_w14_4_3, data={"P_hinge": [1.2, 0, 0]},
         ranges={"P_hinge": [[1.2, 0, 0], [0.5, 0.5, 0], [1, 0, 0.3], [0, 1.5, 0], [0.8, -0.4, 0.2]]},
         statement=N_("P at {P_hinge} on body i (s'_i, s'_j along ζ as above)"),
         explanation=N_("the checker accepts the two rows although they are not kinbook's h_1ᵀs_j, h_2ᵀs_j letter "
                        "for letter: with s'_i along ζ, kinbook's h'_1 = η and h'_2 = −ξ, so these rows are "
                        "kinbook's rows times a constant (−0.8 here): the same constraint. That is the idea of "
                        "kinbook's p1: the two rows are picked in body i's frame, where the redundant one is "
                        "known once and for all — global rows 1–2 of s̃_i s_j lose rank wherever s_i lies in "
                        "the global x-y plane."))


# ------------------------------------------------------------------------------------------------- 14-5
def _fourbar():
    return examples.load("spatial_fourbar")


def _s14_5_1(mech, *, t_n):
    q_t = mech.solve_position(t_n)
    qd_t = mech.solve_velocity(q_t, t_n)
    pdot_4 = mech.p(qd_t, "rocker")                       # ṗ of the rocker, body 4: e04 … e34 in q̇
    my_gamma_4 = -2 * pdot_4 @ pdot_4                      # γ of pᵀp − 1 = 0 is −2ṗᵀṗ
    return my_gamma_4


def _t14_5_1(t_n):
    m = _fourbar()
    q = m.solve_position(t_n)
    qd = m.solve_velocity(q, t_n)
    row = m.constraint("normalization rocker").rows.start
    value = float(m.gamma(q, qd, t_n)[row])
    out = X.Expected(np.asarray(value), kind="value", context=("value",))
    out.add("gamma_sign", -value).add("scaled", value / 2, _msg("x.term", term="−ṗᵀṗ"))
    for body in ("crank", "coupler"):
        other = float(m.gamma(q, qd, t_n)[m.constraint(f"normalization {body}").rows.start])
        out.add("wrong_data", other, _msg("x.other_data", what=Message(N_("γ of the {body}'s normalization"),
                                                                             body=body)))
    return out


def _msg(key, **fields):
    return Msg(key, **fields)


register("14-5/try-1", "my_gamma_4", check_value, _t14_5_1, _s14_5_1, {"name": "γ_4"},
         context=lambda: {"mech": _fourbar()}, data={"t_n": 0.15},
         ranges={"t_n": [round(0.05 * k, 2) for k in range(1, 20)]}, statement="t = {t_n} s", library=("gamma",))


_B_DATA = {"sB_coupler": [3.2, 0, 0], "sB_rocker": [0, 1.5, 0], "cross_coupler": [0, 1, 0], "cross_rocker": [1, 0, 0]}
_B_RANGES = {"sB_coupler": [[3.2, 0, 0], [3, 0.2, 0], [2.8, 0, -0.3], [3.1, -0.2, 0.1]],
             "sB_rocker": [[0, 1.5, 0], [0, 1.2, 0.3], [0.2, 1.4, 0], [0, 1.6, -0.2]],
             "cross_coupler": [[0, 1, 0], [0, 0, 1], [0, 0.6, 0.8], [0, 0.8, -0.6]],
             "cross_rocker": [[1, 0, 0], [0.8, 0, 0.6], [0, 0, 1], [0.6, 0.8, 0]]}


def _fourbar_with(sB_coupler=None, sB_rocker=None, cross_coupler=None, cross_rocker=None, sA_crank=None,
                  sA_coupler=None):
    """The spatial four-bar with other points and cross arms at its joints A and B (a try-it's variant)."""
    data = tomllib.loads(examples.path("spatial_fourbar").read_text(encoding="utf-8"))
    body = {b["name"]: b for b in data["bodies"]}
    for name, point, vector, value in (("coupler", "B", None, sB_coupler), ("rocker", "B", None, sB_rocker),
                                       ("coupler", None, "cross", cross_coupler), ("rocker", None, "axis", cross_rocker),
                                       ("crank", "A", None, sA_crank), ("coupler", "A", None, sA_coupler)):
        if value is not None:
            body[name]["points" if point else "vectors"][point or vector] = [float(x) for x in value]
    return build(data, source="spatial_fourbar, a try-it's variant")


def _s14_5_2(mech, *, sB_coupler, sB_rocker, cross_coupler, cross_rocker):
    import sympy as sp

    from kinbook.spatial import E, a_bar

    par_3, par_4 = sp.Matrix(mech.body_symbols("coupler")[3:]), sp.Matrix(mech.body_symbols("rocker")[3:])
    dAa = lambda p, a: 2 * (E(p) * a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)      # ∂(A a)/∂p: B_k or C_k
    arm_3, arm_4 = A_from_p(par_3) * sp.Matrix(cross_coupler), A_from_p(par_4) * sp.Matrix(cross_rocker)  # global
    eye3, zero13 = sp.eye(3), sp.zeros(1, 3)
    my_Phi_q_B = sp.Matrix.vstack(
        sp.Matrix.hstack(eye3, dAa(par_3, sB_coupler), -eye3, -dAa(par_4, sB_rocker)),      # (s,3):  I, B_i, −I, −B_j
        sp.Matrix.hstack(zero13, arm_4.T * dAa(par_3, cross_coupler), zero13,
                         arm_3.T * dAa(par_4, cross_rocker)))                        # (n1,1): 0, s_jᵀC_i, 0, s_iᵀC_j
    return my_Phi_q_B


def _t14_5_2(**data):
    return (_fourbar() if same_data(data, _B_DATA) else _fourbar_with(**data)).constraint("B")


def _w14_5_2(**data):
    """The n1 row with each body's own arm (s_iᵀC_i, s_jᵀC_j): named, not "missing chain-rule term"."""
    right = _s14_5_2(_fourbar(), **data)
    mech = _fourbar()
    par_3, par_4 = sp.Matrix(mech.body_symbols("coupler")[3:]), sp.Matrix(mech.body_symbols("rocker")[3:])

    dAa = lambda p, a: 2 * (E(p) * a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)  # noqa: E731
    arm_3 = A_from_p(par_3) * sp.Matrix(data["cross_coupler"])
    arm_4 = A_from_p(par_4) * sp.Matrix(data["cross_rocker"])
    z = sp.zeros(1, 3)
    own = sp.Matrix.hstack(z, arm_3.T * dAa(par_3, data["cross_coupler"]), z, arm_4.T * dAa(par_4, data["cross_rocker"]))
    return [(sp.Matrix.vstack(right[:3, :], own), "own_arm", _msg("x.own_arm"), None)]


register("14-5/try-2", "my_Phi_q_B", check_jacobian, _t14_5_2, _s14_5_2, context=lambda: {"mech": _fourbar()},
         data=_B_DATA, ranges=_B_RANGES, wrong_forms=_w14_5_2,
         statement="s'^B_3 = {sB_coupler}, s'^B_4 = {sB_rocker}, cross arms s'_3 = {cross_coupler}, s'_4 = {cross_rocker}")


_A_DATA = {"sA_crank": [1, 0, 0], "sA_coupler": [0, 0, 0]}
_A_RANGES = {"sA_crank": [[1, 0, 0], [0.8, 0.3, 0], [1, 0, 0.2], [0.6, -0.4, 0.3]],
             "sA_coupler": [[0, 0, 0], [0.2, 0, 0], [0, 0.1, -0.1], [-0.3, 0, 0.2]]}


def _s14_5_3(mech, *, sA_crank, sA_coupler):
    import sympy as sp

    from kinbook.spatial import E, a_bar

    dAa = lambda p, a: 2 * (E(p) * a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)
    k_2, k_3 = mech.index("e02"), mech.index("e03")
    pdot_2, pdot_3 = sp.Matrix(mech.qd[k_2:k_2 + 4, 0]), sp.Matrix(mech.qd[k_3:k_3 + 4, 0])
    my_gamma_A = -dAa(pdot_2, sA_crank) * pdot_2 + dAa(pdot_3, sA_coupler) * pdot_3   # γ = −b_i + b_j, b_k = B_k(ṗ_k) ṗ_k
    return my_gamma_A


def _t14_5_3(**data):
    return (_fourbar() if same_data(data, _A_DATA) else _fourbar_with(**data)).constraint("A")


def _w14_5_3(sA_crank, sA_coupler):
    """The book's 2ĖĠᵀa for both bodies' b (the 2a ṗᵀṗ of B(ṗ)ṗ dropped)."""
    mech = _fourbar()
    k_2, k_3 = mech.index("e02"), mech.index("e03")
    pdot_2, pdot_3 = sp.Matrix(mech.qd[k_2:k_2 + 4, 0]), sp.Matrix(mech.qd[k_3:k_3 + 4, 0])
    b_2 = 2 * E(pdot_2, check=False) * a_bar(sp.Matrix(sA_crank)) * pdot_2
    b_3 = 2 * E(pdot_3, check=False) * a_bar(sp.Matrix(sA_coupler)) * pdot_3
    return [(list(-b_2 + b_3), "missing_term", _msg("x.eg_gamma"), None)]


add_texts({
    "x.global_rows": N_("rows 1-2 of s̃_i s_j in global components, the book's choice: they lose rank wherever s_i lies in "
                        "the global x-y plane (the singular values above); take the two rows in body i's frame"),
    "x.own_arm": N_("the n1 row multiplies each body's C by its own arm (s_3ᵀC_3, s_4ᵀC_4); the derivative of s_3ᵀs_4 "
                    "with respect to p_3 is s_4ᵀC_3: the other body's arm"),
    "x.eg_gamma": N_("the book's 2ĖĠᵀa alone: it lacks 2a ṗᵀṗ, the part of B(ṗ)ṗ = 2E(ṗ)āṗ + 2a ṗᵀṗ along a"),
})


register("14-5/try-3", "my_gamma_A", check_gamma, _t14_5_3, _s14_5_3,
         context=lambda: {"mech": _fourbar()}, wrong_forms=_w14_5_3, data=_A_DATA, ranges=_A_RANGES,
         statement="s'^A_2 = {sA_crank}, s'^A_3 = {sA_coupler}",
         explanation=N_("B(ṗ)ṗ = 2E(ṗ)āṗ + 2a(ṗᵀṗ) and 2ĖĠᵀa = 2E(ṗ)āṗ (because Gᵀa = āp), so the book's form lacks "
                        "2a ṗᵀṗ — a vector along a. For the coupler a = s'^A_3 = 0 and nothing is lost; for the "
                        "crank a = s'^A_2 = (1, 0, 0), so only the x row, Φ_16, changes: the checker rejects that "
                        "row alone. (On the unit sphere the two forms differ only by this term, the same 2apᵀ "
                        "difference between ∂(Aa)/∂p and ∂(EGᵀa)/∂p seen in notebook 14-3.)"), library=("gamma",))
