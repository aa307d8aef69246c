"""A corpus of student answers for the grading tests.

Every answer here is written the way a student would write it — by hand, from the textbook's formulas —
never copied from kinbook's reference. Each case states the verdict the checkers must reach: passed, score
and the mistake codes.

Mechanisms: the book's four planar examples (kinbook.examples) and three small ones defined here for the
joint types the examples lack (gear pair, rack and pinion, a pendulum with a non-linear driver).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy as sp

import kinbook

from ..mechanisms import pendulum

# ------------------------------------------------------------------------------------------ extra mechanisms
GEARS = """
[mechanism]
name = "gears"
[[bodies]]
name = "carrier"
points = { O1 = [0, 0], O2 = [3, 0] }
[[bodies]]
name = "gear1"
points = { O = [0, 0] }
[[bodies]]
name = "gear2"
q0 = [3, 0, 0]
points = { O = [0, 0] }
[[constraints]]
type = "ground"
body = "carrier"
[[constraints]]
type = "revolute"
i = "carrier"
j = "gear1"
point_i = "O1"
point_j = "O"
[[constraints]]
type = "revolute"
i = "carrier"
j = "gear2"
point_i = "O2"
point_j = "O"
[[constraints]]
type = "gear"
i = "gear1"
j = "gear2"
k = "carrier"
radius_i = 1
radius_j = 2
[[constraints]]
type = "driver"
body = "gear1"
coordinate = "phi"
f = "10*t"
"""

RACK = """
[mechanism]
name = "rack"
[[bodies]]
name = "ground"
points = { O = [0, 0], P = [0, -1], Q = [1, -1] }
[[bodies]]
name = "pinion"
points = { O = [0, 0] }
[[bodies]]
name = "rack"
q0 = [0, -1, 0]
points = { P = [0, 0] }
[[constraints]]
type = "ground"
body = "ground"
[[constraints]]
type = "revolute"
i = "ground"
j = "pinion"
point = "O"
[[constraints]]
type = "translational"
i = "ground"
j = "rack"
axis = ["P", "Q"]
point_j = "P"
[[constraints]]
type = "rack-pinion"
i = "pinion"
j = "rack"
radius = 0.5
[[constraints]]
type = "driver"
body = "pinion"
coordinate = "phi"
f = "10*t"
"""

PENDULUM = pendulum(1, "sin(10*t)")

_MECHS = {}


def mechanism(name):
    """The book's examples by name, and the corpus' own mechanisms ("gears", "rack", "pendulum")."""
    if name not in _MECHS:
        texts = {"gears": GEARS, "rack": RACK, "pendulum": PENDULUM}
        _MECHS[name] = kinbook.loads(texts[name]) if name in texts else kinbook.examples.load(name)
    return _MECHS[name]


def target(mech_name, constraint=None):
    m = mechanism(mech_name)
    return m if constraint is None else m.constraint(constraint)


# ------------------------------------------------------------------------- a student's formulas (book tables)
def _s(v):
    return f"({v})"


def revolute_phi(i, j, si, sj):
    """Φ^(r,2), eq. 17, written out with A(φ) as the book's matrix form."""
    return [
        f"x{i} + cos(phi{i})*{_s(si[0])} - sin(phi{i})*{_s(si[1])} - x{j} - (cos(phi{j})*{_s(sj[0])} - sin(phi{j})*{_s(sj[1])})",
        f"y{i} + sin(phi{i})*{_s(si[0])} + cos(phi{i})*{_s(si[1])} - y{j} - (sin(phi{j})*{_s(sj[0])} + cos(phi{j})*{_s(sj[1])})",
    ]


def revolute_jac(n, i, j, si, sj):
    """Rows of Φ_q of a revolute joint (book's table 13.4), as strings over n coordinates."""
    rx, ry = ["0"] * n, ["0"] * n
    ci, cj = 3 * (i - 1), 3 * (j - 1)
    rx[ci], ry[ci + 1], rx[cj], ry[cj + 1] = "1", "1", "-1", "-1"
    rx[ci + 2] = f"-{_s(si[0])}*sin(phi{i}) - {_s(si[1])}*cos(phi{i})"
    ry[ci + 2] = f"{_s(si[0])}*cos(phi{i}) - {_s(si[1])}*sin(phi{i})"
    rx[cj + 2] = f"{_s(sj[0])}*sin(phi{j}) + {_s(sj[1])}*cos(phi{j})"
    ry[cj + 2] = f"-{_s(sj[0])}*cos(phi{j}) + {_s(sj[1])}*sin(phi{j})"
    return [rx, ry]


def revolute_gamma(i, j, si, sj):
    """γ of a revolute joint (book's table 13.5): (x_i^P − x_i) φ̇_i² − (x_j^P − x_j) φ̇_j², …"""
    return [
        f"({_s(si[0])}*cos(phi{i}) - {_s(si[1])}*sin(phi{i}))*dphi{i}**2 - ({_s(sj[0])}*cos(phi{j}) - {_s(sj[1])}*sin(phi{j}))*dphi{j}**2",
        f"({_s(si[0])}*sin(phi{i}) + {_s(si[1])}*cos(phi{i}))*dphi{i}**2 - ({_s(sj[0])}*sin(phi{j}) + {_s(sj[1])}*cos(phi{j}))*dphi{j}**2",
    ]


def unit_row(n, col, value="1"):
    r = ["0"] * n
    r[col] = value
    return r


# The four-bar of example 1: ground 1, crank 2, coupler 3, rocker 4.
EX1_JOINTS = [  # (i, j, s'_i, s'_j)
    (1, 2, (0, 0), (-1, 0)),
    (1, 4, (3, 0), (1.5, 0)),
    (2, 3, (1, 0), (-3, 0)),
    (3, 4, (3, 0), (-1.5, 0)),
]

EX1_PHI = ["x1", "y1", "phi1"] + [r for jt in EX1_JOINTS for r in revolute_phi(*jt)] + ["phi2 - 3*pi/4 - 100*t"]

EX1_PHI_SIMPLE = [
    "x1", "y1", "phi1",
    "x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)",
    "x1 + 3*cos(phi1) - x4 - 1.5*cos(phi4)", "y1 + 3*sin(phi1) - y4 - 1.5*sin(phi4)",
    "x2 + cos(phi2) - x3 + 3*cos(phi3)", "y2 + sin(phi2) - y3 + 3*sin(phi3)",
    "x3 + 3*cos(phi3) - x4 + 1.5*cos(phi4)", "y3 + 3*sin(phi3) - y4 + 1.5*sin(phi4)",
    "phi2 - 3*pi/4 - 100*t",
]

EX1_JAC = ([unit_row(12, 0), unit_row(12, 1), unit_row(12, 2)]
           + [r for jt in EX1_JOINTS for r in revolute_jac(12, *jt)] + [unit_row(12, 5)])

EX1_GAMMA = ["0", "0", "0"] + [r for jt in EX1_JOINTS for r in revolute_gamma(*jt)] + ["0"]

EX1_NU = ["0"] * 11 + ["100"]


# Example 2, slider-crank: ground 1, crank 2, rod 3, slider 4.
EX2_PHI = [
    "x1", "y1", "phi1",
    "x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)",
    "cos(phi1)*(y4 - y1) - sin(phi1)*(x4 - x1)", "phi1 - phi4",
    "x2 + cos(phi2) - x3 + 3*cos(phi3)", "y2 + sin(phi2) - y3 + 3*sin(phi3)",
    "x3 + 3*cos(phi3) - x4", "y3 + 3*sin(phi3) - y4",
    "phi2 - pi/4 - 100*t",
]

# Example 3, four-bar with a revolute-revolute joint: ground 1, crank 2, rocker 3.
EX3_PHI = [
    "x1", "y1", "phi1",
    "x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)",
    "x1 + 3*cos(phi1) - x3 - 1.5*cos(phi3)", "y1 + 3*sin(phi1) - y3 - 1.5*sin(phi3)",
    "(x2 + cos(phi2) - x3 + 1.5*cos(phi3))**2 + (y2 + sin(phi2) - y3 + 1.5*sin(phi3))**2 - 6**2",
    "phi2 - 3*pi/4 - 100*t",
]

# Example 4, slider-crank with a revolute-translational joint: ground 1, crank 2, rod 3.
EX4_PHI = [
    "x1", "y1", "phi1",
    "x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)",
    "x2 + cos(phi2) - x3 + 3*cos(phi3)", "y2 + sin(phi2) - y3 + 3*sin(phi3)",
    "(y3 + 3*sin(phi3) - y1)*cos(phi1) - (x3 + 3*cos(phi3) - x1)*sin(phi1)",
    "phi2 - pi/4 - 100*t",
]

EX3_JAC = [unit_row(9, 0), unit_row(9, 1), unit_row(9, 2)] + revolute_jac(9, 1, 2, (0, 0), (-1, 0)) + \
    revolute_jac(9, 1, 3, (3, 0), (1.5, 0)) + [[
        "0", "0", "0",
        "2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))", "2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))",
        "2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))*(-sin(phi2)) + 2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))*cos(phi2)",
        "-2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))", "-2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))",
        "-3*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))*sin(phi3) + 3*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))*cos(phi3)",
    ]] + [unit_row(9, 5)]


def _replace(rows, k, value):
    out = list(rows)
    out[k] = value
    return out


def _numeric_phi_ex1(q, t):
    """A student's Φ as a Python function f(q, t) (0-based q: q[0] = x1 …)."""
    x1, y1, p1, x2, y2, p2, x3, y3, p3, x4, y4, p4 = q
    c, s = np.cos, np.sin
    return [x1, y1, p1, x1 - x2 + c(p2), y1 - y2 + s(p2),
            x1 + 3 * c(p1) - x4 - 1.5 * c(p4), y1 + 3 * s(p1) - y4 - 1.5 * s(p4),
            x2 + c(p2) - x3 + 3 * c(p3), y2 + s(p2) - y3 + 3 * s(p3),
            x3 + 3 * c(p3) - x4 + 1.5 * c(p4), y3 + 3 * s(p3) - y4 + 1.5 * s(p4),
            p2 - 3 * np.pi / 4 - 100 * t]


def _own_symbols_phi():
    """Φ of joint 1 with the student's own (non-real) symbols."""
    x1, y1, x2, y2, phi2 = sp.symbols("x1 y1 x2 y2 phi2")
    return sp.Matrix([x1 - x2 + sp.cos(phi2), y1 - y2 + sp.sin(phi2)])


def _cos2sin2(expr, angle):
    return f"({expr})*(cos({angle})**2 + sin({angle})**2)"


# ------------------------------------------------------------------------------------------------- cases
@dataclass
class Case:
    """One student answer and the verdict it must get."""

    id: str
    check: str  # "phi", "jacobian", "nu", "gamma"
    mech: str
    constraint: str | None
    answer: object
    passed: bool
    score: float
    mistakes: list = field(default_factory=list)
    options: dict = field(default_factory=dict)


def _phi_rows_ex1_reordered():
    rows = list(EX1_PHI_SIMPLE)
    rows = rows[::-1]
    rows[0] = f"-({rows[0]})"
    rows[3] = f"2*({rows[3]})"
    return rows


CASES = [
    # ================================================================= Φ, example 1 (four-bar, 12 coordinates)
    Case("ex1-phi-book-matrix-form", "phi", "ch13_example1", None, EX1_PHI, True, 1.0),
    Case("ex1-phi-simplified", "phi", "ch13_example1", None, EX1_PHI_SIMPLE, True, 1.0),
    Case("ex1-phi-reordered-scaled", "phi", "ch13_example1", None, _phi_rows_ex1_reordered(), True, 1.0),
    Case("ex1-phi-cos2sin2", "phi", "ch13_example1", None,
         _replace(EX1_PHI_SIMPLE, 3, _cos2sin2("x1 - x2 + cos(phi2)", "phi3")), True, 1.0),
    Case("ex1-phi-callable", "phi", "ch13_example1", None, _numeric_phi_ex1, True, 1.0),
    Case("ex1-phi-single-string-rows-as-row-vector", "phi", "ch13_example1", None,
         sp.Matrix([EX1_PHI_SIMPLE]).T.T, True, 1.0),
    Case("ex1-phi-book-order-ok", "phi", "ch13_example1", None, EX1_PHI_SIMPLE, True, 1.0, [], {"order": "book"}),
    Case("ex1-phi-book-order-swapped", "phi", "ch13_example1", None,
         EX1_PHI_SIMPLE[:3] + EX1_PHI_SIMPLE[5:7] + EX1_PHI_SIMPLE[3:5] + EX1_PHI_SIMPLE[7:],
         False, 10 / 12, ["row_order"], {"order": "book"}),
    Case("ex1-phi-missing-driver", "phi", "ch13_example1", None, EX1_PHI_SIMPLE[:11], False, 11 / 12,
         ["missing_row"]),
    Case("ex1-phi-extra-row", "phi", "ch13_example1", None, EX1_PHI_SIMPLE + ["x1 - x2 + cos(phi2)"],
         False, 12 / 13, ["dependent_row"]),
    Case("ex1-phi-driver-degrees", "phi", "ch13_example1", None,
         _replace(EX1_PHI_SIMPLE, 11, "phi2 - 135 - 100*t"), False, 11 / 12, ["degrees"]),
    Case("ex1-phi-swapped-points-joint3", "phi", "ch13_example1", None,
         _replace(_replace(EX1_PHI_SIMPLE, 7, "x2 - 3*cos(phi2) - x3 - cos(phi3)"), 8,
                  "y2 - 3*sin(phi2) - y3 - sin(phi3)"), False, 10 / 12, ["swapped_points"]),
    Case("ex1-phi-sign-flip", "phi", "ch13_example1", None,
         _replace(EX1_PHI_SIMPLE, 9, "x3 + 3*cos(phi3) - x4 - 1.5*cos(phi4)"), False, 11 / 12, ["sign_flip"]),
    Case("ex1-phi-A-transposed-joint3", "phi", "ch13_example1", None,
         _replace(EX1_PHI_SIMPLE, 8, "y2 - sin(phi2) - y3 - 3*sin(phi3)"), False, 11 / 12, ["A_transposed"]),
    Case("ex1-phi-local-vectors-joint3", "phi", "ch13_example1", None,
         _replace(_replace(EX1_PHI_SIMPLE, 7, "x2 + 1 - x3 + 3"), 8, "y2 - y3"), False, 10 / 12,
         ["local_vector"]),
    # ================================================================= Φ, examples 2-4 (whole mechanisms)
    Case("ex2-phi", "phi", "ch13_example2", None, EX2_PHI, True, 1.0),
    Case("ex2-phi-book-order", "phi", "ch13_example2", None, EX2_PHI, True, 1.0, [], {"order": "book"}),
    Case("ex2-phi-missing-driver", "phi", "ch13_example2", None, EX2_PHI[:-1], False, 11 / 12, ["missing_row"]),
    # the slider's own axis through the ground's origin: with φ1 = φ4 (row Φ_7) the same line, so the same
    # constraint (same zero set and rank where assembled) — not a mistake here
    Case("ex2-phi-translational-axis-on-slider", "phi", "ch13_example2", None,
         _replace(EX2_PHI, 5, "cos(phi4)*(y1 - y4) - sin(phi4)*(x1 - x4)"), True, 1.0),
    Case("ex3-phi", "phi", "ch13_example3", None, EX3_PHI, True, 1.0),
    Case("ex3-phi-reversed", "phi", "ch13_example3", None, EX3_PHI[::-1], True, 1.0),
    Case("ex3-phi-rr-missing-square", "phi", "ch13_example3", None,
         _replace(EX3_PHI, 7, EX3_PHI[7].replace("6**2", "6")), False, 8 / 9, ["missing_square"]),
    Case("ex3-jac", "jacobian", "ch13_example3", None, EX3_JAC, True, 1.0),
    Case("ex4-phi", "phi", "ch13_example4", None, EX4_PHI, True, 1.0),
    Case("ex4-phi-driver-degrees", "phi", "ch13_example4", None, _replace(EX4_PHI, 8, "phi2 - 45 - 100*t"),
         False, 8 / 9, ["degrees"]),
    # ================================================================= Φ, malformed answers (never raise)
    Case("phi-unknown-symbol", "phi", "ch13_example1", "1", ["x1 - x2 + cos(theta2)", "y1 - y2"], False, 0.0,
         ["unknown_symbol"]),
    Case("phi-unparsable", "phi", "ch13_example1", "1", ["x1 - x2 +* cos(phi2)", "y1"], False, 0.0, ["malformed"]),
    Case("phi-callable-raises", "phi", "ch13_example1", "1", lambda q, t: 1 / 0, False, 0.0, ["malformed"]),
    Case("phi-callable-nan", "phi", "ch13_example1", "1", lambda q, t: [np.nan, 0.0], False, 0.0, ["not_finite"]),
    Case("phi-wrong-type", "phi", "ch13_example1", "1", {"x": 1}, False, 0.0, ["malformed"]),
    Case("phi-none", "phi", "ch13_example1", "1", None, False, 0.0, ["malformed"]),
    Case("phi-matrix-not-vector", "phi", "ch13_example1", "1", [["x1", "x2"], ["y1", "y2"]], False, 0.0,
         ["wrong_shape"]),
    Case("phi-own-symbols", "phi", "ch13_example1", "1", _own_symbols_phi(), True, 1.0),
    Case("phi-aliases", "phi", "ch13_example1", "1", ["x_1 - x_2 + cos(φ2)", "y_1 - y_2 + sin(phi_2)"], True, 1.0),
    # ================================================================= single joints of every planar type
    # revolute: joint 1 of example 1
    Case("rev-phi", "phi", "ch13_example1", "1", ["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], True, 1.0),
    Case("rev-phi-negated-swapped", "phi", "ch13_example1", "1", ["y2 - y1 - sin(phi2)", "x2 - x1 - cos(phi2)"],
         True, 1.0),
    Case("rev-phi-missing-term", "phi", "ch13_example1", "1", ["x1 - x2", "y1 - y2 + sin(phi2)"], False, 0.5,
         ["missing_term"]),
    Case("rev-phi-missing-row", "phi", "ch13_example1", "1", ["x1 - x2 + cos(phi2)"], False, 0.5, ["missing_row"]),
    # translational: joint 2 of example 2 (ground 1 carries the axis, slider 4)
    Case("trans-phi", "phi", "ch13_example2", "2",
         ["cos(phi1)*(y4 - y1) - sin(phi1)*(x4 - x1)", "phi1 - phi4"], True, 1.0),
    Case("trans-phi-book-form", "phi", "ch13_example2", "2",
         ["(x1 + cos(phi1) - x1)*(y4 - y1) - (y1 + sin(phi1) - y1)*(x4 - x1)", "phi1 - phi4 - (0 - 0)"], True, 1.0),
    Case("trans-phi-axis-on-slider", "phi", "ch13_example2", "2",
         ["cos(phi4)*(y1 - y4) - sin(phi4)*(x1 - x4)", "phi1 - phi4"], True, 1.0),
    # revolute-revolute: joint 3 of example 3 (crank 2, rocker 3, length 6)
    Case("rr-phi", "phi", "ch13_example3", "3",
         ["(x2 + cos(phi2) - x3 + 1.5*cos(phi3))**2 + (y2 + sin(phi2) - y3 + 1.5*sin(phi3))**2 - 36"], True, 1.0),
    Case("rr-phi-sqrt-form", "phi", "ch13_example3", "3",
         ["sqrt((x2 + cos(phi2) - x3 + 1.5*cos(phi3))**2 + (y2 + sin(phi2) - y3 + 1.5*sin(phi3))**2) - 6"],
         True, 1.0),
    Case("rr-phi-missing-square", "phi", "ch13_example3", "3",
         ["(x2 + cos(phi2) - x3 + 1.5*cos(phi3))**2 + (y2 + sin(phi2) - y3 + 1.5*sin(phi3))**2 - 6"],
         False, 0.0, ["missing_square"]),
    Case("rr-phi-swapped-points", "phi", "ch13_example3", "3",
         ["(x2 - 1.5*cos(phi2) - x3 - cos(phi3))**2 + (y2 - 1.5*sin(phi2) - y3 - sin(phi3))**2 - 36"],
         False, 0.0, ["swapped_points"]),
    # revolute-translational: joint 3 of example 4 (rod 3 with B, ground 1 carries the axis)
    Case("rt-phi", "phi", "ch13_example4", "3",
         ["(y3 + 3*sin(phi3) - y1)*cos(phi1) - (x3 + 3*cos(phi3) - x1)*sin(phi1)"], True, 1.0),
    Case("rt-phi-ground-fixed-simplified", "phi", "ch13_example4", "3",
         ["-((x3 + 3*cos(phi3)) - (x1 + cos(phi1)))*sin(phi1) + ((y3 + 3*sin(phi3)) - (y1 + sin(phi1)))*cos(phi1)"],
         True, 1.0),
    Case("rt-phi-swapped-bodies", "phi", "ch13_example4", "3",
         ["(y1 + 3*sin(phi1) - y3 - sin(phi3))*cos(phi3) - (x1 + 3*cos(phi1) - x3 - cos(phi3))*sin(phi3)"], False, 0.0, ["swapped_bodies"]),
    # gear pair on carrier 1: gear1 = body 2 (ρ = 1), gear2 = body 3 (ρ = 2)
    Case("gear-phi", "phi", "gears", "3", ["(phi2 - phi1) + 2*(phi3 - phi1)"], True, 1.0),
    Case("gear-phi-scaled", "phi", "gears", "3", ["-3*phi1 + phi2 + 2*phi3"], True, 1.0),
    Case("gear-phi-sign", "phi", "gears", "3", ["(phi2 - phi1) - 2*(phi3 - phi1)"], False, 0.0, ["sign_flip"]),
    Case("gear-phi-swapped-radii", "phi", "gears", "3", ["2*(phi2 - phi1) + (phi3 - phi1)"], False, 0.0,
         ["swapped_bodies"]),
    # rack and pinion: pinion 2 (ρ = 0.5), rack 3
    Case("rack-phi", "phi", "rack", "3", ["0.5*phi2 - x3"], True, 1.0),
    Case("rack-phi-sign", "phi", "rack", "3", ["0.5*phi2 + x3"], False, 0.0, ["sign_flip"]),
    # driver
    Case("driver-phi", "phi", "ch13_example1", "driver 1", ["phi2 - (3*pi/4 + 100*t)"], True, 1.0),
    Case("driver-phi-negated", "phi", "ch13_example1", "driver 1", ["3*pi/4 + 100*t - phi2"], True, 1.0),
    Case("driver-phi-degrees", "phi", "ch13_example1", "driver 1", ["phi2 - 135 - 100*t"], False, 0.0, ["degrees"]),
    Case("driver-phi-degrees-all", "phi", "ch13_example1", "driver 1", ["phi2 - 135 - 5729.5779513*t"], False, 0.0,
         ["degrees"]),
    # ================================================================= Φ_q
    Case("ex1-jac", "jacobian", "ch13_example1", None, EX1_JAC, True, 1.0),
    Case("ex1-jac-missing-driver-row", "jacobian", "ch13_example1", None, EX1_JAC[:11], False, 11 / 12,
         ["missing_row"]),
    Case("ex1-jac-entry-sign", "jacobian", "ch13_example1", None,
         _replace(EX1_JAC, 7, _replace(EX1_JAC[7], 5, "(1)*sin(phi2)")), False, (11 + 3 / 4) / 12,
         ["sign_flip"]),
    Case("ex1-jac-transposed", "jacobian", "ch13_example1", None,
         [list(r) for r in zip(*EX1_JAC)], False, 0.5, ["transposed"]),
    Case("ex1-jac-any-order", "jacobian", "ch13_example1", None, EX1_JAC[::-1], True, 1.0, [], {"order": "any"}),
    Case("rev-jac", "jacobian", "ch13_example1", "3",
         [["1", "0", "-sin(phi2)", "-1", "0", "-3*sin(phi3)"], ["0", "1", "cos(phi2)", "0", "-1", "3*cos(phi3)"]],
         True, 1.0),
    Case("rev-jac-full-width", "jacobian", "ch13_example1", "3", revolute_jac(12, 2, 3, (1, 0), (-3, 0)), True, 1.0),
    Case("rev-jac-missing-chain-rule", "jacobian", "ch13_example1", "3",
         [["1", "0", "0", "-1", "0", "0"], ["0", "1", "0", "0", "-1", "0"]], False, 0.5, ["missing_chain_rule"]),
    Case("rev-jac-A-for-B", "jacobian", "ch13_example1", "3",
         [["1", "0", "cos(phi2)", "-1", "0", "3*cos(phi3)"], ["0", "1", "sin(phi2)", "0", "-1", "3*sin(phi3)"]],
         False, 0.5, ["A_for_B"]),
    Case("rev-jac-transposed", "jacobian", "ch13_example1", "3",
         [["1", "0"], ["0", "1"], ["-sin(phi2)", "cos(phi2)"], ["-1", "0"], ["0", "-1"], ["-3*sin(phi3)", "3*cos(phi3)"]],
         False, 0.5, ["transposed"]),
    Case("rev-jac-wrong-shape", "jacobian", "ch13_example1", "3", [["1", "0", "0"], ["0", "1", "0"]], False, 0.0,
         ["wrong_shape"]),
    Case("rev-jac-callable", "jacobian", "ch13_example1", "3",
         lambda q, t: [[1, 0, -np.sin(q[5]), -1, 0, -3 * np.sin(q[8])],
                       [0, 1, np.cos(q[5]), 0, -1, 3 * np.cos(q[8])]], True, 1.0),
    Case("trans-jac", "jacobian", "ch13_example2", "2",
         [["sin(phi1)", "-cos(phi1)", "-sin(phi1)*(y4 - y1) - cos(phi1)*(x4 - x1)", "-sin(phi1)", "cos(phi1)", "0"],
          ["0", "0", "1", "0", "0", "-1"]], True, 1.0),
    Case("rr-jac", "jacobian", "ch13_example3", "3",
         [["2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))", "2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))",
           "2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))*(-sin(phi2)) + 2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))*cos(phi2)",
           "-2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))", "-2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))",
           "2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))*(-1.5*sin(phi3)) + 2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))*1.5*cos(phi3)"]],
         True, 1.0),
    Case("rt-jac-missing-chain-rule-by-entry", "jacobian", "ch13_example4", "3",
         [["-sin(phi1)", "cos(phi1)", "0", "sin(phi1)", "-cos(phi1)", "0"]], False, 4 / 6, ["missing_chain_rule"]),
    Case("rev-jac-entry-sign-flip", "jacobian", "ch13_example1", "3",
         [["1", "0", "sin(phi2)", "-1", "0", "-3*sin(phi3)"], ["0", "1", "cos(phi2)", "0", "-1", "3*cos(phi3)"]],
         False, (3 / 4 + 1) / 2, ["sign_flip"]),
    Case("gear-jac", "jacobian", "gears", "3", [["0", "0", "1", "0", "0", "2", "0", "0", "-3"]], True, 1.0),
    Case("gear-jac-mechanism-column-order", "jacobian", "gears", "3", [["0", "0", "-3", "0", "0", "1", "0", "0", "2"]],
         True, 1.0),
    Case("gear-jac-only-angles", "jacobian", "gears", "3", [["-3", "1", "2"]], False, 0.0, ["wrong_shape"]),
    Case("rack-jac", "jacobian", "rack", "3", [["0", "0", "0.5", "-1", "0", "0"]], True, 1.0),
    Case("driver-jac", "jacobian", "ch13_example1", "driver 1", [["0", "0", "1"]], True, 1.0),
    # ================================================================= ν
    Case("ex1-nu", "nu", "ch13_example1", None, EX1_NU, True, 1.0),
    Case("ex1-nu-sign", "nu", "ch13_example1", None, ["0"] * 11 + ["-100"], False, 11 / 12, ["nu_sign"]),
    Case("ex1-nu-missing", "nu", "ch13_example1", None, ["0"] * 12, False, 11 / 12, ["nu_missing"]),
    Case("ex1-nu-degrees", "nu", "ch13_example1", None, ["0"] * 11 + ["5729.5779513"], False, 11 / 12, ["degrees"]),
    Case("pendulum-nu", "nu", "pendulum", "driver 1", ["10*cos(10*t)"], True, 1.0),
    # ================================================================= γ
    Case("ex1-gamma", "gamma", "ch13_example1", None, EX1_GAMMA, True, 1.0),
    Case("ex1-gamma-book-plus-sign", "gamma", "ch13_example1", None,
         [f"-({g})" for g in EX1_GAMMA], False, 4 / 12, ["gamma_sign"]),
    Case("rev-gamma", "gamma", "ch13_example1", "3",
         ["cos(phi2)*dphi2**2 + 3*cos(phi3)*dphi3**2", "sin(phi2)*dphi2**2 + 3*sin(phi3)*dphi3**2"], True, 1.0),
    Case("rev-gamma-missing-square", "gamma", "ch13_example1", "3",
         ["cos(phi2)*dphi2 + 3*cos(phi3)*dphi3", "sin(phi2)*dphi2 + 3*sin(phi3)*dphi3"], False, 0.0,
         ["missing_square"]),
    Case("rev-gamma-missing-term", "gamma", "ch13_example1", "3",
         ["cos(phi2)*dphi2**2", "sin(phi2)*dphi2**2 + 3*sin(phi3)*dphi3**2"], False, 0.5, ["missing_term"]),
    Case("rev-gamma-sign-of-one-term", "gamma", "ch13_example1", "3",
         ["cos(phi2)*dphi2**2 - 3*cos(phi3)*dphi3**2", "sin(phi2)*dphi2**2 + 3*sin(phi3)*dphi3**2"], False, 0.5,
         ["sign_flip"]),
    Case("rev-gamma-callable", "gamma", "ch13_example1", "3",
         lambda q, qd, t: [np.cos(q[5]) * qd[5] ** 2 + 3 * np.cos(q[8]) * qd[8] ** 2,
                           np.sin(q[5]) * qd[5] ** 2 + 3 * np.sin(q[8]) * qd[8] ** 2], True, 1.0),
    Case("rr-gamma-sign", "gamma", "ch13_example3", "3",
         ["2*(dx2 - sin(phi2)*dphi2 - dx3 - 1.5*sin(phi3)*dphi3)**2 + 2*(dy2 + cos(phi2)*dphi2 - dy3 + 1.5*cos(phi3)*dphi3)**2"
          " + 2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))*(-cos(phi2)*dphi2**2 - 1.5*cos(phi3)*dphi3**2)"
          " + 2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))*(-sin(phi2)*dphi2**2 - 1.5*sin(phi3)*dphi3**2)"],
         False, 0.0, ["gamma_sign"]),
    Case("rr-gamma", "gamma", "ch13_example3", "3",
         ["-2*(dx2 - sin(phi2)*dphi2 - dx3 - 1.5*sin(phi3)*dphi3)**2 - 2*(dy2 + cos(phi2)*dphi2 - dy3 + 1.5*cos(phi3)*dphi3)**2"
          " - 2*(x2 + cos(phi2) - x3 + 1.5*cos(phi3))*(-cos(phi2)*dphi2**2 - 1.5*cos(phi3)*dphi3**2)"
          " - 2*(y2 + sin(phi2) - y3 + 1.5*sin(phi3))*(-sin(phi2)*dphi2**2 - 1.5*sin(phi3)*dphi3**2)"],
         True, 1.0),
    Case("pendulum-gamma", "gamma", "pendulum", "driver 1", ["-100*sin(10*t)"], True, 1.0),
    Case("pendulum-gamma-missing-tt", "gamma", "pendulum", "driver 1", ["0"], False, 0.0, ["missing_tt_term"]),
    Case("gear-gamma", "gamma", "gears", "3", ["0"], True, 1.0),
]

CASES += [
    # a wrong row and a missing row at once: the wrong one is paired by the coordinates it uses
    Case("ex1-phi-wrong-and-missing", "phi", "ch13_example1", None,
         _replace(EX1_PHI_SIMPLE[:11], 9, "x3 + 3*cos(phi3)*x4 + 1.5*cos(phi4)"), False, 10 / 12,
         ["wrong_value", "missing_row"]),
]

CASES += [
    Case("ex1-phi-book-order-negated-rows", "phi", "ch13_example1", None,
         [f"-({r})" if k % 2 else r for k, r in enumerate(EX1_PHI_SIMPLE)], True, 1.0, [], {"order": "book"}),
    Case("ex3-phi-rr-as-distance", "phi", "ch13_example3", None,
         _replace(EX3_PHI, 7, "sqrt((x2 + cos(phi2) - x3 + 1.5*cos(phi3))**2 + (y2 + sin(phi2) - y3 + 1.5*sin(phi3))**2) - 6"),
         True, 1.0),
    Case("ex4-phi-rt-swapped", "phi", "ch13_example4", None,
         _replace(EX4_PHI, 7, "(y1 + 3*sin(phi1) - y3 - sin(phi3))*cos(phi3) - (x1 + 3*cos(phi1) - x3 - cos(phi3))*sin(phi3)"),
         False, 8 / 9, ["swapped_bodies"]),
]


def _book_rr_gamma(square="**2"):
    """γ of the r-r joint as the book's table 13.5 prints it, for example 3's crank (P_i = A) and rocker
    (P_j = B). The book prints −2(ẏ_i − ẏ_j) without its square: ``square=""`` copies the misprint."""
    sub = {"xiPmxi": "cos(phi2)", "yiPmyi": "sin(phi2)", "xjPmxj": "(-1.5*cos(phi3))", "yjPmyj": "(-1.5*sin(phi3))",
           "xiP": "(x2 + cos(phi2))", "yiP": "(y2 + sin(phi2))", "xjP": "(x3 - 1.5*cos(phi3))",
           "yjP": "(y3 - 1.5*sin(phi3))"}
    text = ("-2*(dx2 - dx3)**2 - 2*(dy2 - dy3)SQ - 2*(xiPmxi*(xjP - x2) + yiPmyi*(yjP - y2))*dphi2**2"
            " - 2*(xjPmxj*(xiP - x3) + yjPmyj*(yiP - y3))*dphi3**2 + 4*(xiPmxi*xjPmxj + yiPmyi*yjPmyj)*dphi2*dphi3"
            " - 4*(xiPmxi*(dy2 - dy3) - yiPmyi*(dx2 - dx3))*dphi2 + 4*(xjPmxj*(dy2 - dy3) - yjPmyj*(dx2 - dx3))*dphi3")
    for key in sorted(sub, key=len, reverse=True):
        text = text.replace(key, sub[key])
    return [text.replace("SQ", square)]


CASES += [
    Case("rr-gamma-book-table", "gamma", "ch13_example3", "3", _book_rr_gamma(), True, 1.0),
    Case("rr-gamma-book-misprint", "gamma", "ch13_example3", "3", _book_rr_gamma(""), False, 0.0, ["book_misprint"]),
]
