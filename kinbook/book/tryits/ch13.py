"""Try-its of the chapter-13 notebooks (planar kinematics). Each worked answer is a function: its positional
parameters are the notebook variables it reads, its keyword-only parameters the try-it's data, its body is what
``kb.reveal`` shows. Names assigned in a worked answer are new in their notebook (``my_…`` or local to the
exercise), so pasting one never rebinds a name the notebook uses elsewhere.

Each try-it asks for something the notebook does not print above it — another point, another instant, another
driver — and ``kb.another`` draws other data from ``ranges``. Numeric answers are graded against
:mod:`kinbook.grading.expected` objects, so a wrong number is named (A for B, the centripetal term, degrees,
the value printed a few cells above …) without being given.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10: the same parser as tomli
    import tomli as tomllib

from ... import examples
from ...files import build
from ...grading import check_gamma, check_jacobian, check_nu, check_phi, check_value
from ...grading import expected as X
from ...grading._i18n import Msg
from ...grading.newton import Problem, check_iterates
from ...i18n import N_, Message
from ...planar import (
    A,
    B,
    Mechanism,
    Revolute,
    RevoluteRevolute,
    Translational,
    point_velocity,
)
from .registry import register

__all__ = []  # nothing to import from here: importing the module registers its try-its

DEGREES = list(range(15, 346, 15))


def _printed(what, **fields):
    """A lookalike's detail: what it is the answer to (the notebook prints it above), a marked message."""
    return Msg("x.other_data", what=Message(what, **fields))


# ------------------------------------------------------------------------------------------------- 13-1
def _s13_1_1(*, phi_deg):
    phi = np.radians(phi_deg)
    my_A = np.array([[np.cos(phi), -np.sin(phi)],
                     [np.sin(phi), np.cos(phi)]])
    return my_A


register("13-1/try-1", "my_A", check_value, lambda phi_deg: X.A(np.radians(phi_deg)), _s13_1_1,
         {"name": "A(φ)"}, data={"phi_deg": 120}, ranges={"phi_deg": [d for d in DEGREES if d % 90]},
         statement="φ = {phi_deg}°",
         explanation=N_("eq. 6 with the angle in radians: np.cos and np.sin take radians, so convert first "
                        "(np.radians). The columns of A are the body's ξ and η axes in global components."), library=("A",))

_BODY = {"x_Oi": 1.5, "y_Oi": -0.5, "phi_i_deg": 30, "xi_Q": 0.8, "eta_Q": 0.3}
_BODY_RANGES = {"x_Oi": (-2.0, 2.0), "y_Oi": (-2.0, 2.0), "phi_i_deg": DEGREES, "xi_Q": (0.3, 1.5),
                "eta_Q": (-0.8, 0.8)}
_BODY_TEXT = "q_i = [{x_Oi}, {y_Oi}, {phi_i_deg}°], (ξ_i^Q, η_i^Q) = ({xi_Q}, {eta_Q})"


def _s13_1_2(*, x_Oi, y_Oi, phi_i_deg, xi_Q, eta_Q):
    phi = np.radians(phi_i_deg)
    my_rQ = [x_Oi + xi_Q * np.cos(phi) - eta_Q * np.sin(phi),      # eq. 4: r^Q = r + A s'^Q
             y_Oi + xi_Q * np.sin(phi) + eta_Q * np.cos(phi)]
    return my_rQ


register("13-1/try-2", "my_rQ", check_value,
         lambda x_Oi, y_Oi, phi_i_deg, xi_Q, eta_Q: X.point_position([x_Oi, y_Oi], np.radians(phi_i_deg), [xi_Q, eta_Q]),
         _s13_1_2, {"name": "r_i^Q"}, data=_BODY, ranges=_BODY_RANGES, statement=_BODY_TEXT,
         explanation=N_("r^Q = r + A s'^Q (eq. 4): the local coordinates are turned by A into global "
                        "components before they are added to the origin's position."), library=("point_position",))

_MOTION = dict(_BODY, xd_i=0.2, yd_i=0.0, w_i=2.0, a_i=-1.0)
_MOTION_RANGES = dict(_BODY_RANGES, xd_i=(-1.0, 1.0), yd_i=(-1.0, 1.0), w_i=(0.5, 3.0), a_i=(-2.0, 2.0))


def _s13_1_3(*, phi_i_deg, xi_Q, eta_Q, xd_i, yd_i, w_i, a_i):
    phi, s_Q = np.radians(phi_i_deg), np.array([xi_Q, eta_Q])
    my_vaQ = np.r_[np.array([xd_i, yd_i]) + B(phi) @ s_Q * w_i,       # eq. 10
                   B(phi) @ s_Q * a_i - A(phi) @ s_Q * w_i**2]        # eq. 13 with r̈_i = 0
    return my_vaQ


def _t13_1_3(x_Oi, y_Oi, phi_i_deg, xi_Q, eta_Q, xd_i, yd_i, w_i, a_i):
    phi, s_Q = np.radians(phi_i_deg), [xi_Q, eta_Q]
    return X.stack(X.point_velocity([xd_i, yd_i], phi, w_i, s_Q), X.point_acceleration([0.0, 0.0], phi, w_i, a_i, s_Q))


register("13-1/try-3", "my_vaQ", check_value, _t13_1_3, _s13_1_3, {"name": "[v_Q, a_Q]"}, data=_MOTION,
         ranges=_MOTION_RANGES,
         statement=_BODY_TEXT + ", ṙ_i = [{xd_i}, {yd_i}] m/s, φ̇_i = {w_i} rad/s, r̈_i = 0, φ̈_i = {a_i} rad/s²",
         explanation=N_("eq. 10 differentiates A s' into B s' φ̇ (B = dA/dφ); eq. 13 differentiates once more: "
                        "a tangential part B s' φ̈ and a centripetal part −A s' φ̇², which points from Q back to "
                        "the body's origin."), library=("point_velocity", "point_acceleration"))


# ------------------------------------------------------------------------------------------------- 13-2
def _two_bodies(name, points_1, points_2, joint):
    m = Mechanism(name)
    m.add_body("b1", points=points_1)
    m.add_body("b2", points=points_2)
    m.add(joint)
    return m.constraint("1")


def _s13_2_1(*, xi_1A, eta_1A, xi_2A, eta_2A):
    my_Phi = [f"x1 + {xi_1A}*cos(phi1) - {eta_1A}*sin(phi1) - (x2 + {xi_2A}*cos(phi2) - {eta_2A}*sin(phi2))",
              f"y1 + {xi_1A}*sin(phi1) + {eta_1A}*cos(phi1) - (y2 + {xi_2A}*sin(phi2) + {eta_2A}*cos(phi2))"]
    return my_Phi


register("13-2/try-1", "my_Phi", check_phi,
         lambda xi_1A, eta_1A, xi_2A, eta_2A: _two_bodies("crank and coupler", {"A": (xi_1A, eta_1A)},
                                                          {"A": (xi_2A, eta_2A)}, Revolute("b1", "b2", point="A")),
         _s13_2_1, data={"xi_1A": 1, "eta_1A": 0, "xi_2A": -1.5, "eta_2A": 0.2},
         ranges={"xi_1A": (0.5, 2.0), "eta_1A": (-0.5, 0.5), "xi_2A": (-2.0, -0.5), "eta_2A": (-0.5, 0.5)},
         statement="(ξ_1^A, η_1^A) = ({xi_1A}, {eta_1A}), (ξ_2^A, η_2^A) = ({xi_2A}, {eta_2A})")


def _s13_2_2(*, xi_Q1, eta_Q1):
    # r_1^P = (x1, y1), r_1^Q = r_1 + A_1 s'^Q_1, r_2^P = (x2, y2); eq. 26 with O → Q
    xQ = f"(x1 + {xi_Q1}*cos(phi1) - {eta_Q1}*sin(phi1))"
    yQ = f"(y1 + {xi_Q1}*sin(phi1) + {eta_Q1}*cos(phi1))"
    my_Phi_t = [f"(x1 - {xQ})*(y2 - y1) - (y1 - {yQ})*(x2 - x1)",
                "phi1 - phi2 - (0 - 0)"]
    return my_Phi_t


register("13-2/try-2", "my_Phi_t", check_phi,
         lambda xi_Q1, eta_Q1: _two_bodies("guide and slider", {"P": (0, 0), "Q": (xi_Q1, eta_Q1)}, {"P": (0, 0)},
                                           Translational("b1", "b2", axis=("P", "Q"), point_j="P")), _s13_2_2,
         data={"xi_Q1": 1, "eta_Q1": 0}, ranges={"xi_Q1": (0.5, 2.5), "eta_Q1": (-0.8, 0.8)},
         statement="Q_1 = ({xi_Q1}, {eta_Q1})")


def _s13_2_3(*, xi_B, eta_B, xi_C, eta_C, l_BC):
    dx = f"(x1 + {xi_B}*cos(phi1) - {eta_B}*sin(phi1) - x2 - {xi_C}*cos(phi2) + {eta_C}*sin(phi2))"
    dy = f"(y1 + {xi_B}*sin(phi1) + {eta_B}*cos(phi1) - y2 - {xi_C}*sin(phi2) - {eta_C}*cos(phi2))"
    my_Phi_rr = [f"{dx}**2 + {dy}**2 - {l_BC}**2"]
    return my_Phi_rr


register("13-2/try-3", "my_Phi_rr", check_phi,
         lambda xi_B, eta_B, xi_C, eta_C, l_BC: _two_bodies("two bodies and a link", {"B": (xi_B, eta_B)},
                                                             {"C": (xi_C, eta_C)},
                                                             RevoluteRevolute("b1", "b2", "B", "C", length=l_BC)),
         _s13_2_3, data={"xi_B": 2, "eta_B": 0, "xi_C": 0, "eta_C": 0.5, "l_BC": 3},
         ranges={"xi_B": (1.0, 3.0), "eta_B": (-0.5, 0.5), "xi_C": (-1.0, 1.0), "eta_C": (-1.0, 1.0),
                 "l_BC": (2.0, 5.0)},
         statement=N_("B = ({xi_B}, {eta_B}) on body 1, C = ({xi_C}, {eta_C}) on body 2, l = {l_BC}"))


# ------------------------------------------------------------------------------------------------- 13-3
@lru_cache(maxsize=None)
def _example(name):
    m = examples.load(name)
    return m, m.solve_position(0.0)


@lru_cache(maxsize=64)
def _edited(name, body, point, value, *more):
    """The book's example ``name`` with local points of its bodies moved (a try-it's own data): ``body, point,
    value`` and as many more triples."""
    data = tomllib.loads(examples.path(name).read_text(encoding="utf-8"))
    edits = [(body, point, value)] + [tuple(more[k:k + 3]) for k in range(0, len(more), 3)]
    for b in data["bodies"]:
        for who, where, at in edits:
            if b["name"] == who:
                b["points"][where] = [float(v) for v in at]
    return build(data, source=f"{name} with " + ", ".join(f"{w}.{p} = {list(v)}" for w, p, v in edits))


@lru_cache(maxsize=64)
def _driven(name, f):
    """The book's example ``name`` with its driver's f(t) replaced."""
    data = tomllib.loads(examples.path(name).read_text(encoding="utf-8"))
    for c in data["constraints"]:
        if c["type"] == "driver":
            c["f"] = f
    return build(data, source=f"{name} driven by {f}")


def _s13_3_1(*, xi_OA, eta_OA):
    my_Phi_45 = [f"x1 - (x2 + {xi_OA}*cos(phi2) - {eta_OA}*sin(phi2))",
                 f"y1 - (y2 + {xi_OA}*sin(phi2) + {eta_OA}*cos(phi2))"]
    return my_Phi_45


def _printed_joint(name, what):
    def lookalikes(**_):
        return [(_example(name)[0].constraint("1"), _printed(what))]
    return lookalikes


register("13-3/try-1", "my_Phi_45", check_phi,
         lambda xi_OA, eta_OA: _edited("ch13_example1", "crank", "OA", (xi_OA, eta_OA)).constraint("1"), _s13_3_1,
         data={"xi_OA": -1.2, "eta_OA": 0.2}, ranges={"xi_OA": (-1.4, -0.6), "eta_OA": (-0.3, 0.3)},
         statement="(ξ_2^{{O_A}}, η_2^{{O_A}}) = ({xi_OA}, {eta_OA})",
         lookalikes=_printed_joint("ch13_example1", N_("Φ_4, Φ_5 of example 1 as printed above, with the crank's own "
                                   "O_A at (−1, 0)")))


def _s13_3_2(m3, *, t_newton):
    q_it = m3.q0.copy()                         # the guess stored in the mechanism file
    my_iterates = [q_it]
    for _ in range(8):                          # Φ_q Δq = −Φ at the current iterate, then q ← q + Δq
        q_it = q_it + np.linalg.solve(m3.Phi_q(q_it, t_newton), -m3.Phi(q_it, t_newton))
        my_iterates.append(q_it)
    return my_iterates


register("13-3/try-2", "my_iterates", check_iterates,
         lambda t_newton: Problem(_example("ch13_example3")[0], t_newton, _example("ch13_example3")[0].q0),
         _s13_3_2, data={"t_newton": 0.005},
         ranges={"t_newton": [round(0.001 * k, 3) for k in range(-9, 22) if k]},
         statement="t = {t_newton} s (φ_2 = 3π/4 + 100 t)", context=lambda: {"m3": _example("ch13_example3")[0]},
         explanation=N_("each pass solves the linear system Φ_q(q_k, t) Δq = −Φ(q_k, t) at the current iterate "
                        "and steps to q_k + Δq. Near the solution the error is squared at every step (quadratic "
                        "convergence): max |Φ| goes roughly 1e-1, 1e-2, 1e-5, 1e-10. Further passes change "
                        "nothing."), library=("solve_position",))


def _s13_3_3(q1, *, xi_C, eta_C):
    x3, y3, phi3 = q1[6], q1[7], q1[8]
    my_rC = np.array([x3 + xi_C * np.cos(phi3) - eta_C * np.sin(phi3),
                      y3 + xi_C * np.sin(phi3) + eta_C * np.cos(phi3)])
    return my_rC


def _l13_3_3(xi_C, eta_C):
    m1, q1 = _example("ch13_example1")
    return [(m1.point_position(q1, b, p), _printed(N_("the position of {p}, printed above"), p=p))
            for b, p in (("crank", "A"), ("rocker", "B"), ("coupler", "B"))]


register("13-3/try-3", "my_rC", check_value,
         lambda xi_C, eta_C: X.point_position(_example("ch13_example1")[1][6:8], _example("ch13_example1")[1][8],
                                              [xi_C, eta_C]), _s13_3_3,
         {"name": "r^C"}, context=lambda: {"q1": _example("ch13_example1")[1]}, data={"xi_C": 2.0, "eta_C": 0.5},
         ranges={"xi_C": (-3.0, 3.0), "eta_C": (-1.0, 1.0)}, statement="(ξ_3^C, η_3^C) = ({xi_C}, {eta_C})",
         lookalikes=_l13_3_3, library=("point_position",))


# ------------------------------------------------------------------------------------------------- 13-4
@lru_cache(maxsize=64)
def _planetary(rho_sun, rho_planet, w_arm):
    """The workbook's planetary train (fixed sun, arm, planet) with other radii and arm speed."""
    data = tomllib.loads(examples.path("ch13_planetary").read_text(encoding="utf-8"))
    arm = (rho_sun + rho_planet) / 2
    bodies = {b["name"]: b for b in data["bodies"]}
    bodies["ground"]["points"] = {"O": [0.0, 0.0], "S": [float(rho_sun), 0.0]}
    bodies["arm"].update(q0=[arm, 0.0, 0.0], points={"O": [-arm, 0.0], "C": [arm, 0.0]})
    bodies["planet"].update(q0=[2 * arm, 0.0, 0.0], points={"C": [0.0, 0.0], "M": [float(rho_planet), 0.0]})
    for c in data["constraints"]:
        if c["type"] == "gear":
            c["radius_i"], c["radius_j"] = float(rho_sun), float(rho_planet)
        if c["type"] == "driver":
            c["f"] = f"{w_arm}*t"
    return build(data, source=f"planetary train ρ = {rho_sun}, {rho_planet}, arm {w_arm} rad/s")


def _s13_4_1(*, rho_sun, rho_planet):
    my_gear_row = [f"{rho_sun}*((phi1 - 0) - (phi2 - 0)) + {rho_planet}*((phi3 - 0) - (phi2 - 0))"]  # eq. 38
    return my_gear_row


register("13-4/try-1", "my_gear_row", check_phi,
         lambda rho_sun, rho_planet: _planetary(rho_sun, rho_planet, 1.0).constraints[3], _s13_4_1,
         data={"rho_sun": 3, "rho_planet": 1}, ranges={"rho_sun": (1.5, 3.0), "rho_planet": (0.5, 1.5)},
         statement="ρ_1 = {rho_sun}, ρ_3 = {rho_planet}",
         lookalikes=lambda **_: [(_planetary(2, 1, 1.0).constraints[3], _printed(
             N_("the gear row of the train printed above (ρ_1 = 2, ρ_3 = 1)")))])

_TRAIN = {"w_arm": 1.5, "rho_sun": 2.5, "rho_planet": 1.0}


def _s13_4_2(*, w_arm, rho_sun, rho_planet):
    my_w3 = w_arm * (1 + rho_sun / rho_planet)   # relative to the arm: φ̇3 − φ̇2 = −(ρ1/ρ3)(φ̇1 − φ̇2), φ̇1 = 0
    return my_w3


def _t13_4_2(w_arm, rho_sun, rho_planet):
    pl = _planetary(rho_sun, rho_planet, w_arm)
    q = pl.solve_position(0.0)
    w3 = pl.solve_velocity(q, 0.0)[pl.index("phi3")]
    return X.planet_speed(w3, w_arm, 0.0, rho_sun, rho_planet)


def _l13_4_2(**_):
    pl, q = _example("ch13_planetary")
    return [(pl.solve_velocity(q, 0.0)[pl.index("phi3")],
             _printed(N_("the planet's speed printed above, for the notebook's train (arm at 1 rad/s, ρ = 2 and 1)")))]


register("13-4/try-2", "my_w3", check_value, _t13_4_2, _s13_4_2, {"name": "φ̇_3 (rad/s)"}, data=_TRAIN,
         ranges={"w_arm": (0.5, 3.0), "rho_sun": (1.5, 3.0), "rho_planet": (0.5, 1.5)},
         statement="φ̇_2 = {w_arm} rad/s, φ̇_1 = 0, ρ_1 = {rho_sun}, ρ_3 = {rho_planet}", lookalikes=_l13_4_2,
         explanation=N_("eq. 38 relates the turns relative to the arm: (φ̇_3 − φ̇_2) ρ_3 = −(φ̇_1 − φ̇_2) ρ_1. With "
                        "the sun fixed the planet turns relative to the arm at (ρ_1/ρ_3) φ̇_2, and the arm's own "
                        "turn comes on top: φ̇_3 = φ̇_2 (1 + ρ_1/ρ_3)."))


@lru_cache(maxsize=64)
def _rack(rho):
    data = tomllib.loads(examples.path("ch13_rack_pinion").read_text(encoding="utf-8"))
    bodies = {b["name"]: b for b in data["bodies"]}
    bodies["ground"]["points"].update(P=[0.0, -float(rho)], Q=[1.0, -float(rho)])
    bodies["rack"]["q0"] = [0.0, -float(rho), 0.0]
    for c in data["constraints"]:
        if c["type"] == "rack-pinion":
            c["radius"] = float(rho)
    return build(data, source=f"rack and pinion, ρ = {rho}")


def _s13_4_3(*, rho_p, turn_deg):
    my_dx = rho_p * np.radians(turn_deg)          # eq. 40: x_j − x_j⁰ = ρ (φ_i − φ_i⁰), the angle in radians
    return my_dx


def _t13_4_3(rho_p, turn_deg):
    rp, turn = _rack(rho_p), np.radians(turn_deg)          # the driver turns the pinion at 1 rad/s
    out = X.rack_displacement(rho_p, turn)
    out.value = np.asarray(rp.solve_position(turn)[rp.index("x3")] - rp.solve_position(0.0)[rp.index("x3")])
    return out


register("13-4/try-3", "my_dx", check_value, _t13_4_3, _s13_4_3, {"name": "rack displacement (m)"},
         data={"rho_p": 1, "turn_deg": 90}, ranges={"rho_p": (0.5, 2.0), "turn_deg": list(range(30, 301, 15))},
         statement=N_("ρ = {rho_p} m, a turn of {turn_deg}°"))


# ------------------------------------------------------------------------------------------------- 13-5
def _s13_5_1(*, xi_OA, eta_OA):
    # Φ_4 = x1 − (x2 + ξ cos φ2 − η sin φ2), Φ_5 = y1 − (y2 + ξ sin φ2 + η cos φ2), the ground at its origin
    my_J1 = [["1", "0", "0", "-1", "0", f"{xi_OA}*sin(phi2) + {eta_OA}*cos(phi2)"],
             ["0", "1", "0", "0", "-1", f"-{xi_OA}*cos(phi2) + {eta_OA}*sin(phi2)"]]
    return my_J1


register("13-5/try-1", "my_J1", check_jacobian,
         lambda xi_OA, eta_OA: _edited("ch13_example3", "crank", "OA", (xi_OA, eta_OA)).constraint("1"), _s13_5_1,
         data={"xi_OA": -1, "eta_OA": 0}, ranges={"xi_OA": (-1.4, -0.6), "eta_OA": (-0.4, 0.4)},
         statement="(ξ_2^{{O_A}}, η_2^{{O_A}}) = ({xi_OA}, {eta_OA})")


def _s13_5_2(*, xi_A, xi_B):
    dx = f"(x2 + {xi_A}*cos(phi2) - x3 - {xi_B}*cos(phi3))"      # x^A − x^B
    dy = f"(y2 + {xi_A}*sin(phi2) - y3 - {xi_B}*sin(phi3))"      # y^A − y^B
    my_J8 = [[f"2*{dx}", f"2*{dy}", f"-2*{xi_A}*{dx}*sin(phi2) + 2*{xi_A}*{dy}*cos(phi2)",
              f"-2*{dx}", f"-2*{dy}", f"2*{xi_B}*{dx}*sin(phi3) - 2*{xi_B}*{dy}*cos(phi3)"]]
    return my_J8


register("13-5/try-2", "my_J8", check_jacobian,
         lambda xi_A, xi_B: _edited("ch13_example3", "crank", "A", (xi_A, 0), "rocker", "B", (xi_B, 0)).constraint("3"),
         _s13_5_2, data={"xi_A": 1, "xi_B": -1.5}, ranges={"xi_A": (0.8, 1.3), "xi_B": (-1.9, -1.2)},
         statement="ξ_2^A = {xi_A}, ξ_3^B = {xi_B} (η = 0)")


def _s13_5_3(mech, *, t_J):
    q_t = mech.solve_position(t_J)
    rA, rB = mech.point_position(q_t, "crank", "A"), mech.point_position(q_t, "rocker", "B")
    my_J88 = 2 * (rA[0] - rB[0]) * (rB[1] - q_t[7]) - 2 * (rA[1] - rB[1]) * (rB[0] - q_t[6])   # corrected Table 13.3
    return my_J88


def _t13_5_3(t_J):
    m = _example("ch13_example3")[0]
    q = m.solve_position(t_J)
    rA, rB = m.point_position(q, "crank", "A"), m.point_position(q, "rocker", "B")
    arm = rB - q[6:8]                                             # A_3 s'_3^B
    out = X.rr_jacobian_phi(rA - rB, np.array([-arm[1], arm[0]]))  # B_3 s'_3^B: the arm turned by 90°
    out.value = np.asarray(m.Phi_q(q, t_J)[7, 8])
    pivot = rB - m.point_position(q, "ground", "OB")              # the arm measured from O_B, not from O_3
    out.add("lever_arm", -2 * (rA - rB) @ np.array([-pivot[1], pivot[0]]))
    return out


def _l13_5_3(t_J):
    m, q = _example("ch13_example3")
    return [(m.Phi_q(q, 0.0)[7, 8], _printed(N_("the entry at t = 0, printed in Φ_q above")))]


register("13-5/try-3", "my_J88", check_value, _t13_5_3, _s13_5_3, {"name": "∂Φ_8/∂φ_3"},
         context=lambda: {"mech": _example("ch13_example3")[0]}, data={"t_J": 0.004},
         ranges={"t_J": [round(0.001 * k, 3) for k in range(-9, 22) if k]}, statement="t = {t_J} s",
         lookalikes=_l13_5_3, library=("Phi_q",))


# ------------------------------------------------------------------------------------------------- 13-6
def _s13_6_1(*, w_drive, alpha_drive):
    my_nu = ["0"] * 8 + [f"{w_drive} + {alpha_drive}*t"]     # ν = −Φ_t: only the driver's row depends on t
    return my_nu


register("13-6/try-1", "my_nu", check_nu,
         lambda w_drive, alpha_drive: _driven("ch13_example3", f"3*pi/4 + {w_drive}*t + {alpha_drive / 2}*t**2"),
         _s13_6_1, data={"w_drive": 100, "alpha_drive": 500},
         ranges={"w_drive": list(range(50, 151, 10)), "alpha_drive": list(range(-1000, 1001, 250))},
         statement="φ_2 = 3π/4 + {w_drive} t + ½·{alpha_drive} t²",
         lookalikes=lambda **_: [(_example("ch13_example3")[0], _printed(
             N_("ν of the book's driver φ_2 = 3π/4 + 100 t, printed above")))], numbers_at=0.0, library=("nu",))


@lru_cache(maxsize=None)
def _ex3_motion():
    m, q = _example("ch13_example3")
    qd = m.solve_velocity(q, 0.0)
    return m, q, qd, m.solve_acceleration(q, qd, 0.0)


def _s13_6_2(qd0, *, d_D):
    my_speed_D = d_D * abs(qd0[8])         # D turns about the fixed O_B, at d_D from it
    return my_speed_D


def _t13_6_2(d_D):
    m, q, qd, _ = _ex3_motion()
    v = point_velocity(qd[6:8], q[8], qd[8], [1.5 - d_D, 0.0])    # O_B is at ξ_3 = 1.5, B at −1.5
    vB = m.point_velocity(q, qd, "rocker", "B")
    return X.speed(float(np.linalg.norm(v)), others=[
        ("wrong_data", float(np.linalg.norm(vB)), _printed(N_("|v_B|, printed above"))),
        ("wrong_data", d_D * abs(qd[5]), _printed(N_("the speed with the crank's φ̇_2: D is on the rocker, which turns at φ̇_3")))])


register("13-6/try-2", "my_speed_D", check_value, _t13_6_2, _s13_6_2, {"name": "|v_D| (m/s)"},
         context=lambda: {"qd0": _ex3_motion()[2]}, data={"d_D": 2}, ranges={"d_D": (0.5, 2.9)},
         statement="|O_B D| = {d_D} m", library=("point_velocity",))


def _s13_6_3(q0, qd0, *, xi_C3, eta_C3):
    x3d, y3d, w3, phi3 = qd0[6], qd0[7], qd0[8], q0[8]
    my_vC = [x3d - (xi_C3 * np.sin(phi3) + eta_C3 * np.cos(phi3)) * w3,     # eq. 10 written out
             y3d + (xi_C3 * np.cos(phi3) - eta_C3 * np.sin(phi3)) * w3]
    return my_vC


def _l13_6(which):
    def lookalikes(**_):
        m, q, qd, qdd = _ex3_motion()
        if which == "v":
            return [(m.point_velocity(q, qd, "rocker", "B"), _printed(N_("v_B, printed above")))]
        return [(m.point_acceleration(q, qd, qdd, "rocker", "B"), _printed(N_("a_B, printed above")))]
    return lookalikes


register("13-6/try-3", "my_vC", check_value,
         lambda xi_C3, eta_C3: X.point_velocity(_ex3_motion()[2][6:8], _ex3_motion()[1][8], _ex3_motion()[2][8],
                                                [xi_C3, eta_C3]), _s13_6_3,
         {"name": "v_C (m/s)"}, context=lambda: {"q0": _ex3_motion()[1], "qd0": _ex3_motion()[2]},
         data={"xi_C3": 0.5, "eta_C3": 0.4}, ranges={"xi_C3": (-1.5, 1.5), "eta_C3": (-0.8, 0.8)},
         statement="(ξ_3^C, η_3^C) = ({xi_C3}, {eta_C3})", lookalikes=_l13_6("v"), library=("point_velocity",))


# ------------------------------------------------------------------------------------------------- 13-7
def _s13_7_1(*, xi_OA, eta_OA):
    # γ = A_1 s'_1 φ̇_1² − A_2 s'_2 φ̇_2² (Table 13.5, revolute), with s'_1 = 0 at the ground's origin
    my_gamma_1 = [f"({xi_OA}*cos(phi2) - {eta_OA}*sin(phi2))*(-dphi2**2)",
                  f"({xi_OA}*sin(phi2) + {eta_OA}*cos(phi2))*(-dphi2**2)"]
    return my_gamma_1


register("13-7/try-1", "my_gamma_1", check_gamma,
         lambda xi_OA, eta_OA: _edited("ch13_example3", "crank", "OA", (xi_OA, eta_OA)).constraint("1"), _s13_7_1,
         data={"xi_OA": -1.0, "eta_OA": 0.3}, ranges={"xi_OA": (-1.4, -0.6), "eta_OA": (-0.4, 0.4)},
         statement="(ξ_2^{{O_A}}, η_2^{{O_A}}) = ({xi_OA}, {eta_OA})",
         lookalikes=_printed_joint("ch13_example3", N_("γ_4, γ_5 of the book's example printed above, with the crank's "
                                   "own O_A at (−1, 0)")))


def _s13_7_2(mech, *, t_g):
    q_t = mech.solve_position(t_g)
    qd_t = mech.solve_velocity(q_t, t_g)
    rA, rB = mech.point_position(q_t, "crank", "A"), mech.point_position(q_t, "rocker", "B")
    vel_A, vel_B = mech.point_velocity(q_t, qd_t, "crank", "A"), mech.point_velocity(q_t, qd_t, "rocker", "B")
    cA = mech.point_acceleration(q_t, qd_t, np.zeros(9), "crank", "A")      # the velocity-dependent part only
    cB = mech.point_acceleration(q_t, qd_t, np.zeros(9), "rocker", "B")
    my_gamma_8 = -2 * (vel_A - vel_B) @ (vel_A - vel_B) - 2 * (rA - rB) @ (cA - cB)
    return my_gamma_8


def _t13_7_2(t_g):
    m = _example("ch13_example3")[0]
    q = m.solve_position(t_g)
    qd = m.solve_velocity(q, t_g)
    z = np.zeros(m.n)
    pos = [m.point_position(q, b, p) for b, p in (("crank", "A"), ("rocker", "B"))]
    vel = [m.point_velocity(q, qd, b, p) for b, p in (("crank", "A"), ("rocker", "B"))]
    acc = [m.point_acceleration(q, qd, z, b, p) for b, p in (("crank", "A"), ("rocker", "B"))]
    out = X.rr_gamma(pos[0] - pos[1], vel[0] - vel[1], acc[0] - acc[1])
    out.value = np.asarray(m.gamma(q, qd, t_g)[7])
    return out


def _l13_7_2(t_g):
    m, q, qd, _ = _ex3_motion()
    return [(m.gamma(q, qd, 0.0)[7], _printed(N_("γ_8 at t = 0, printed above")))]


register("13-7/try-2", "my_gamma_8", check_value, _t13_7_2, _s13_7_2, {"name": "γ_8"},
         context=lambda: {"mech": _ex3_motion()[0]}, data={"t_g": 0.004},
         ranges={"t_g": [round(0.001 * k, 3) for k in range(-9, 22) if k]}, statement="t = {t_g} s",
         lookalikes=_l13_7_2, library=("gamma",))


def _s13_7_3(q0, qd0, qdd0, *, xi_C3, eta_C3):
    from kinbook.planar import A, B

    x3dd, y3dd, a3, w3, phi3 = qdd0[6], qdd0[7], qdd0[8], qd0[8], q0[8]
    s_C = np.array([xi_C3, eta_C3])
    my_aC = np.array([x3dd, y3dd]) + B(phi3) @ s_C * a3 - A(phi3) @ s_C * w3**2      # eq. 13
    return my_aC


register("13-7/try-3", "my_aC", check_value,
         lambda xi_C3, eta_C3: X.point_acceleration(_ex3_motion()[3][6:8], _ex3_motion()[1][8], _ex3_motion()[2][8],
                                                    _ex3_motion()[3][8], [xi_C3, eta_C3]), _s13_7_3,
         {"name": "a_C (m/s²)"}, context=lambda: dict(zip(("q0", "qd0", "qdd0"), _ex3_motion()[1:])),
         data={"xi_C3": 0.5, "eta_C3": 0.4}, ranges={"xi_C3": (-1.5, 1.5), "eta_C3": (-0.8, 0.8)},
         statement="(ξ_3^C, η_3^C) = ({xi_C3}, {eta_C3})", lookalikes=_l13_6("a"), library=("point_acceleration",))

