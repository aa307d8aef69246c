"""What the book prints, typed once — only as the thing under test.

Numbers and formulas here are copied from the textbook text as printed, misprints included, so that the
errata (:mod:`kinbook.book.errata`), the notebooks and the tests compare kinbook's derivations with one copy
of the book. Nothing in kinbook uses them as a reference answer.

Chapter 13: the solutions of examples 1–4 at t = 0 (angles in degrees, as printed), example 5's Jacobian,
right-hand side and velocities, example 6's γ, accelerations and point accelerations, and Tables 13.1–13.5
written in the book's symbols (:data:`kinbook.book.notation.S`; the book's "o" is the point Q).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..grading.misprints import EX4_PHI8
from .notation import S

__all__ = ["EQ", "EX1", "EX2", "EX3", "EX4", "EX5", "EX6", "q_book", "TABLES", "TABLE_13_1_TEXT",
           "EX5_RR_ROW", "ex5_ground_point_y", "ex6_point_acceleration", "TABLE_13_5_JACOBIAN", "TABLE_13_5_GAMMA", "REVOLUTE_STEPS", "ex2_translational_general"]


def q_book(values):
    """A printed solution (angles in degrees) as kinbook's q (radians)."""
    q = np.array(values, dtype=float)
    q[2::3] = np.radians(q[2::3])
    return q


# ------------------------------------------------------------------------------ §13.5, examples 1–4 at t = 0
EX1 = {
    "q": q_book([0, 0, 0, -0.7071, 0.7071, 135, 1.5777, 1.9854, 10.81, 3.7849, 1.2783, 238.45]),
    "A": np.array([-1.4142, 1.4142]),
    "B": np.array([4.5697, 2.5566]),
}
"""Example 1 (four-bar, four bodies): the printed solution at t = 0 and the points A, B."""

EX1["q_13_6"] = sp.Matrix(sp.symbols("x1 y1 phi1 x2 y2 phi2 x3 y3 phi3", real=True))
"""§13.6's coordinate vector "for the example cited" (example 1), as printed: nine coordinates."""
EX1["Phi11_13_6"] = (sp.Symbol("y3", real=True) + 3 * sp.sin(sp.Symbol("phi3", real=True)) - sp.Symbol("y4", real=True)
                     + sp.Rational(3, 2) * sp.sin(sp.Symbol("phi4", real=True)))
"""Example 1's Φ_11 as §13.6 prints it a few lines below that vector."""

EX2 = {
    "q": q_book([0, 0, 0, 0.7071, 0.7071, 45, 4.3297, 0.7071, 346.37, 7.2452, 0, 0]),
    "A": np.array([1.4142, 1.4142]),
    "B": np.array([7.2452, 0.0]),
}
"""Example 2 (slider-crank, four bodies)."""

_x1, _y1, _phi1, _x3, _y3, _phi3, _x4, _y4, _phi4 = sp.symbols("x1 y1 phi1 x3 y3 phi3 x4 y4 phi4", real=True)
EX2["Phi6"] = (_x4 - _x1) * sp.sin(_phi1) - (_y4 - _y1) * sp.cos(_phi1)
"""Example 2's Φ_6 (the translational joint's collinearity row), in kinbook's symbols x1 … of that mechanism."""


def ex2_translational_general(P_i, Q_i, P_j, Q_j):
    """Example 2's joint 2: the general translational row as the example prints it, (x_i^P − x_i^Q)(y_j^P − y_j^Q)
    − (y_i^P − y_i^Q)(x_j^P − x_j^Q), for global points given as (x, y) pairs — Q_j, a second point of body j,
    where eq. 26 has P_i."""
    return (P_i[0] - Q_i[0]) * (P_j[1] - Q_j[1]) - (P_i[1] - Q_i[1]) * (P_j[0] - Q_j[0])

EX3 = {"q": q_book([0, 0, 0, 0.7071, 0.7071, 135, 3.7849, 1.2783, 238.45])}
"""Example 3 (four-bar with a revolute–revolute joint), printed with x_2 = +0.7071."""

EX3["Phi6_7_system"] = sp.Matrix([_x1 + 3 * sp.cos(_phi1) - _x4 - sp.Rational(3, 2) * sp.cos(_phi3),
                                  _y1 + 3 * sp.sin(_phi1) - _y4 - sp.Rational(3, 2) * sp.sin(_phi3)])
"""Example 3's Φ_6, Φ_7 as its assembled system prints them: x_4, y_4 of a body example 3 does not have (the joint
section prints x_3, y_3)."""

EX4 = {
    "q": q_book([0, 0, 0, 0.7071, 0.7071, 45, 4.3297, 0.7071, 346.37]),
    "Phi8": EX4_PHI8,  # typed once, where the checkers recognise it
    "Phi8_substituted": ((_x3 + 3 * sp.cos(_phi3) - _x1 - sp.cos(_phi1)) * (_y1 - _y1 - sp.sin(_phi1))
                         - (_y3 + 3 * sp.sin(_phi3) - _y1 * sp.sin(_phi1)) * (_x1 - _x1 - sp.cos(_phi1))),
    "Phi8_system": ((_x3 + 3 * sp.cos(_phi3) - _x1 - sp.cos(_phi1)) * sp.sin(_phi1)
                    + (_y3 + 3 * sp.sin(_phi3) - _y1 * sp.sin(_phi1)) * sp.cos(_phi1)),
}
"""Example 4 (slider-crank with a revolute–translational joint): the solution and Φ_8 as printed three ways — the
general row with the points substituted (``Phi8_substituted``), simplified (``Phi8``) and in the assembled system
(``Phi8_system``) — in kinbook's symbols of that mechanism."""

# ------------------------------------------------------------------------------------ §13.7, example 5
EX5 = {
    # example 5 lists example 3's configuration (x_2 = +0.7071, erratum 13.5-ex3-x2) but its Jacobian uses
    # x_2 = −0.7071 (x^{O_A} − x_2 = 0 + 0.7071), as example 6 prints it: that is the configuration here
    "q": q_book([0, 0, 0, -0.7071, 0.7071, 135, 3.7849, 1.2783, 238.45]),
    "J": np.array([[1, 0, 0, 0, 0, 0, 0, 0, 0],
                   [0, 1, 0, 0, 0, 0, 0, 0, 0],
                   [0, 0, 1, 0, 0, 0, 0, 0, 0],
                   [1, 0, 0, -1, 0, -0.7071, 0, 0, 0],
                   [0, 1, 0, 0, -1, -0.7071, 0, 0, 0],
                   [1, 0, 0, 0, 0, 0, -1, 0, -1.2783],
                   [0, 1, 3, 0, 0, 0, 0, -1, 0.7849],
                   [0, 0, 0, -11.968, -2.2848, 10.0781, 11.968, 2.2848, -13.5053],
                   [0, 0, 0, 0, 0, 1, 0, 0, 0]]),
    "nu": np.array([0, 0, 0, 0, 0, 0, 0, 0, 100.0]),
    "qd": np.array([0, 0, 0, 70.71, 70.71, 100, 95.391, 58.5719, 74.6233]),  # "Solución"
    "qd_ex6": np.array([0, 0, 0, -70.71, -70.71, 100, -95.391, 58.5719, 74.6233]),  # as example 6 reuses it
    "vA": np.array([-141.4207, -141.4207]),
    "vB": np.array([-190.7802, 117.1410]),
    # joint 3's working: the four lever-arm values, printed under the labels x^A − x^B, y^A − y^B, x^B − x^3,
    # y^B − y^3 (erratum 13.7-ex5-joint3-working)
    "rr_arms": np.array([-0.7071, 0.7071, 0.7849, 1.2783]),
}
"""Example 5: the global Jacobian at example 3's printed configuration, ν, the velocities and v_A, v_B."""


def ex5_ground_point_y(y1, phi1, xi, eta):
    """Example 5's y^{O_A}, y^{O_B} as printed for a point (ξ, η) of the ground, body 1: y_1 + η sen φ_1 (the
    simplified transformation, η = 0, with η written where ξ belongs)."""
    return y1 + eta * np.sin(phi1)

# ------------------------------------------------------------------------------------ §13.8, example 6
EX6 = {
    "gamma": np.array([0, 0, 0, -7071, 7071, 4370.82, 7118.39, 1539.6, 0]),  # the global vector γ
    "gamma8_joint": -1539.60,  # γ_8 in the joint section
    "gamma8_system": -1539.6,  # γ_8 in the list of equations
    "qdd": np.array([0, 0, 0, 7071, -7071, 0, 2042.03, -11056, -5016.7]),
    "aA": np.array([14142.068, -14142.068]),
    "aB": np.array([4084.136, -22111.679]),
    "A": np.array([1.4142, 1.4142]),  # "(x^A, y^A)" in the list of the joints' global points
}
"""Example 6: γ (printed three ways for γ_8), the accelerations q̈ and a_A, a_B, and the point A it lists."""


def ex6_point_acceleration(r_ddot, phi, phi_dot, phi_ddot, xi, eta):
    """Example 6's acceleration of a point (ξ, η) of a body, as printed component by component:
    ẍ^P = ẍ + φ̈ (−ξ sen φ − η cos φ) φ̇² − (ξ cos φ − η sen φ), ÿ^P = ÿ + φ̈ (ξ cos φ − η sen φ) φ̇² − (ξ sen φ + η cos φ)."""
    s, c = np.sin(phi), np.cos(phi)
    return np.array([r_ddot[0] + phi_ddot * (-xi * s - eta * c) * phi_dot**2 - (xi * c - eta * s),
                     r_ddot[1] + phi_ddot * (xi * c - eta * s) * phi_dot**2 - (xi * s + eta * c)])

# ------------------------------------------------------------------------- §13.5, the joints' equations
def _A(phi):
    return sp.Matrix([[sp.cos(phi), -sp.sin(phi)], [sp.sin(phi), sp.cos(phi)]])


EQ = {
    "18": (sp.Matrix([S.x_i, S.y_i]) + _A(S.phi_i) * sp.Matrix([S.xiP_i, S.etaP_i])
           - sp.Matrix([S.x_j, S.y_j]) - _A(S.phi_j) * sp.Matrix([S.xiP_j, S.etaP_j])),
    "26": sp.Matrix([(S.xP_i - S.xQ_i) * (S.yP_j - S.yP_i) - (S.yP_i - S.yQ_i) * (S.xP_j - S.xP_i), S.phi_i - S.phi_j - S.c]),
    "32": sp.Matrix([(S.xP_i - S.xP_j) ** 2 + (S.yP_i - S.yP_j) ** 2 - S.l**2]),
    "33": sp.Matrix([(S.xP_i - S.xQ_j) * (S.yP_j - S.yQ_j) - (S.yP_i - S.yQ_j) * (S.xP_j - S.xQ_j)]),
}
"""The joints' constraint equations as printed: eq. 18 (revolute, in ξ, η), eq. 26 (translational; its point "O"
read as the guide point Q_i, erratum 13.5-eq25, and φ_i⁰ − φ_j⁰ written as the constant ``S.c``), eq. 32
(revolute–revolute) and eq. 33 (revolute–translational)."""

# ------------------------------------------------------------------------- §13.6, Tables 13.1–13.4 (Φ_q)
_s = S
_t1 = sp.Matrix([[1, 0, -(_s.yP_i - _s.y_i), -1, 0, (_s.yP_j - _s.y_j)],
                 [0, 1, (_s.xP_i - _s.x_i), 0, -1, -(_s.xP_j - _s.x_j)]])
_t2_phi = (_s.xP_j - _s.x_i) * (_s.xP_i - _s.xQ_i) + (_s.yP_j - _s.y_i) * (_s.yP_i - _s.yQ_i)
_t2 = sp.Matrix([[(_s.yP_i - _s.yQ_i), -(_s.xP_i - _s.xQ_i), -_t2_phi, -(_s.yP_i - _s.yQ_i), (_s.xP_i - _s.xQ_i),
                  _t2_phi], [0, 0, 1, 0, 0, -1]])
_dx, _dy = _s.xP_i - _s.xP_j, _s.yP_i - _s.yP_j
_t3 = sp.Matrix([[2 * _dx, 2 * _dy, -2 * _dx * _dy + 2 * _dy * _dx, -2 * _dx, -2 * _dy,
                  2 * _dx * (_s.yP_j - _s.yP_j) - 2 * _dy * (_s.xP_j - _s.xP_j)]])
_t4_phi = (_s.yP_i - _s.y_i) * (_s.yP_j - _s.yQ_j) + (_s.xP_i - _s.x_i) * (_s.xP_j - _s.xQ_j)
_t4 = sp.Matrix([[(_s.yP_j - _s.yQ_j), -(_s.xP_j - _s.xQ_j), -_t4_phi, -(_s.yP_j - _s.yQ_j), (_s.xP_j - _s.xQ_j),
                  _t4_phi]])

TABLES = {
    "13.1": ("r", _t1),
    "13.2": ("t", _t2),
    "13.3": ("rr", _t3),
    "13.4": ("rt", _t4),
}
"""Tables 13.1–13.4 as printed: table number → (pair kind, the printed Φ_q rows in :data:`S`)."""

_t2_fixed_phi_j = (_s.xP_j - _s.x_j) * (_s.xP_i - _s.xQ_i) + (_s.yP_j - _s.y_j) * (_s.yP_i - _s.yQ_i)
TABLE_13_5_JACOBIAN = {
    "r": _t1,
    "t": sp.Matrix([list(_t2.row(0))[:5] + [_t2_fixed_phi_j], [0, 0, 1, 0, 0, -1]]),
    "rr": sp.Matrix([[2 * _dx, 2 * _dy, -2 * _dx * (_s.yP_i - _s.y_i) + 2 * _dy * (_s.xP_i - _s.x_i), -2 * _dx,
                      -2 * _dy, 2 * _dx * (_s.yP_j - _s.y_j) - 2 * _dy * (_s.xP_j - _s.x_j)]]),
    "rt": _t4,
}
"""Table 13.5's Jacobian rows as printed (it corrects Tables 13.2 and 13.3, repeats Table 13.4)."""

TABLE_13_1_TEXT = sp.Matrix([[1, 0, -(_s.yP_i - _s.yP_j), -1, 0, (_s.yP_j - _s.yP_i)],
                             [0, 1, (_s.xP_i - _s.xP_j), 0, -1, -(_s.xP_j - _s.xP_i)]])
"""The entry-by-entry derivation printed under Table 13.1 (revolute joint)."""

EX5_RR_ROW = sp.Matrix([[2 * _dx, 2 * _dy, -2 * _dx * _dy + 2 * _dy * _dx, -2 * _dx, -2 * _dy,
                         2 * _dx * (_s.yP_j - _s.yP_i) - 2 * _dy * (_s.xP_j - _s.xP_i)]])
"""The general (r-r,1) Jacobian row example 5 repeats."""

# ------------------------------------------------------------------------------ §13.8, Table 13.5 (γ)
_vx, _vy = _s.xd_i - _s.xd_j, _s.yd_i - _s.yd_j
_ai = (_s.xP_i - _s.x_i, _s.yP_i - _s.y_i)
_aj = (_s.xP_j - _s.x_j, _s.yP_j - _s.y_j)
_rr_rest = (-2 * (_ai[0] * (_s.xP_j - _s.x_i) + _ai[1] * (_s.yP_j - _s.y_i)) * _s.w_i**2
            - 2 * (_aj[0] * (_s.xP_i - _s.x_j) + _aj[1] * (_s.yP_i - _s.y_j)) * _s.w_j**2
            + 4 * (_ai[0] * _aj[0] + _ai[1] * _aj[1]) * _s.w_i * _s.w_j
            - 4 * (_ai[0] * _vy - _ai[1] * _vx) * _s.w_i + 4 * (_aj[0] * _vy - _aj[1] * _vx) * _s.w_j)
_sx, _sy = _s.xP_i - _s.xQ_i, _s.yP_i - _s.yQ_i
TABLE_13_5_GAMMA = {
    "r": sp.Matrix([(_s.xP_i - _s.x_i) * _s.w_i**2 - (_s.xP_j - _s.x_j) * _s.w_j**2,
                    (_s.yP_i - _s.y_i) * _s.w_i**2 - (_s.yP_j - _s.y_j) * _s.w_j**2]),
    "t": sp.Matrix([2 * (_sx * _vx + _sy * _vy) * _s.w_i
                    - (_sx * (_s.y_i - _s.y_j) - _sy * (_s.x_i - _s.x_j)) * _s.w_i**2, 0]),
    "rr": sp.Matrix([-2 * _vx**2 - 2 * _vy + _rr_rest]),
    "rt": sp.Matrix([((_s.xP_i - _s.x_i) * (_s.yP_j - _s.yQ_j) - (_s.yP_i - _s.y_i) * (_s.xP_j - _s.xQ_j))
                     * (_s.w_i - 2 * _s.w_j) * _s.w_i
                     + ((_s.xP_i - _s.x_j) * (_s.yP_j - _s.yQ_j) - (_s.yP_i - _s.y_j) * (_s.xP_j - _s.xQ_j)) * _s.w_j**2
                     - 2 * ((_s.xP_j - _s.xQ_j) * _vx + (_s.yP_j - _s.yQ_j) * _vy) * _s.w_j]),
}
"""Table 13.5's γ entries as printed (the translational entry has already used φ̇_j = φ̇_i, the joint's second
velocity equation, so it is tested at states where that holds)."""

REVOLUTE_STEPS = {
    "Phi_q qd": sp.Matrix([_s.xd_i - (_s.yP_i - _s.y_i) * _s.w_i - _s.xd_j + (_s.yP_j - _s.y_j) * _s.w_j,
                           _s.xd_j - (_s.xP_i - _s.x_i) * _s.w_i - _s.yd_j + (_s.xP_j - _s.x_j) * _s.w_j]),
    "(Phi_q qd)_q qd": sp.Matrix([-(_s.xP_i - _s.x_i) * _s.w_i**2 + (_s.xP_j - _s.x_j) * _s.w_j**2,
                                  -(_s.yP_i - _s.y_i) * _s.w_i**2 + (_s.yP_j - _s.y_j) * _s.w_j**2]),
    "gamma": sp.Matrix([(_s.xP_i - _s.x_i) * _s.w_i**2 - (_s.xP_j - _s.x_j) * _s.w_j**2,
                        (_s.yP_i - _s.y_i) * _s.w_i**2 - (_s.yP_j - _s.y_j) * _s.w_j**2]),
}
"""§13.8's worked revolute joint, step by step as printed: Φ_q q̇, (Φ_q q̇)_q q̇ and the concluded γ."""
