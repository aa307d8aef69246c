"""Chapter 13's errata (§13.5-13.8, the plane), each with its evidence computed from kinbook's examples and
derivations."""

from __future__ import annotations

import numpy as np
import sympy as sp

from ... import examples, planar
from .. import notation, verify
from ..display import agrees, small
from ..notation import S
from ..printed import (
    EQ,
    EX1,
    EX3,
    EX4,
    EX5,
    EX6,
    REVOLUTE_STEPS,
    TABLE_13_1_TEXT,
    TABLE_13_5_GAMMA,
    TABLES,
    ex2_translational_general,
    ex5_ground_point_y,
    ex6_point_acceleration,
)
from .erratum import Erratum, Evidence, below, compare

__all__ = ["ERRATA"]


def example(name):
    return examples.load(name)


# ------------------------------------------------------------------------------------------- evidence
def _math_names(coordinates):
    """kinbook's coordinate names as the book writes them, each a formula: "x4, phi4" → "$x_{4}$, $\\varphi_{4}$"."""
    return ", ".join(f"${notation.latex(sp.Symbol(c))}$" for c in coordinates)


def _ev_ex1_solution():
    m = example("ch13_example1")

    qb = EX1["q"]
    res = m.Phi(qb, 0.0)
    A = m.point_position(qb, "crank", "A")
    B = EX1["B"]
    q = m.solve_position(0.0)
    ok = np.abs(m.Phi(q, 0.0)).max()
    return Evidence(
        rf"The printed configuration leaves $\max|\Phi_k| = {np.abs(res).max():.3f}$ (row "
        rf"$\Phi_{{{np.argmax(np.abs(res)) + 1}}}$); at the printed $A$ and $B$ the coupler would be "
        rf"$|AB| = {np.linalg.norm(B - A):.3f}$ long instead of 6. kinbook's solution: "
        rf"$\varphi_3 = {np.degrees(q[8]):.2f}°$, $\varphi_4 = {np.degrees(q[11]):.2f}°$, "
        rf"$B = ({m.point_position(q, 'rocker', 'B')[0]:.4f}, {m.point_position(q, 'rocker', 'B')[1]:.4f})$, "
        rf"$\max|\Phi_k|$ {below(ok)}.",
        float(np.abs(res).max()), float(ok))


def _ev_ex3_x2():
    m = example("ch13_example3")

    qb = EX3["q"]
    res = m.Phi(qb, 0.0)
    fixed = qb.copy()
    fixed[3] = -0.7071
    return Evidence(
        rf"With the printed $x_2 = +0.7071$, $\Phi_4 = x_1 - x_2 + \cos\varphi_2 = {res[3]:.4f}$; with "
        rf"$x_2 = -0.7071$ it is {small(m.Phi(fixed, 0.0)[3], 1e-4)} (the printed four decimals).", abs(float(res[3])),
        abs(float(m.Phi(fixed, 0.0)[3])), tolerance=1e-4)


def _ex4_phi8(printed_row, what):
    """Example 4's Φ_8 as printed (``printed_row``, in the mechanism's symbols) and corrected, against kinbook's
    row 8 at 20 random configurations."""
    m = example("ch13_example4")
    x1, y1, p1, x3, y3, p3 = (m.q[m.index(c), 0] for c in ("x1", "y1", "phi1", "x3", "y3", "phi3"))
    corrected = (-(x3 + 3 * sp.cos(p3) - x1 - sp.cos(p1)) * sp.sin(p1)
                 + (y3 + 3 * sp.sin(p3) - y1 - sp.sin(p1)) * sp.cos(p1))
    f = sp.lambdify(list(m.q), [printed_row, corrected], "numpy")
    rows = [(*f(*q), m.Phi(q, 0.0)[7]) for q in np.random.default_rng(1).uniform(-2, 2, (20, 9))]
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random configurations {what} differs from kinbook's $\Phi_8$ by up to {e_p:.3f}; the "
                    rf"corrected row {agrees(e_c)}.", e_p, e_c)


def _ev_ex4_phi8():
    return _ex4_phi8(EX4["Phi8"], r"the simplified $\Phi_8$ as printed")


def _ev_ex4_phi8_substituted():
    return _ex4_phi8(EX4["Phi8_substituted"], "the row with the points substituted, as printed,")


def _ev_ex4_phi8_system():
    return _ex4_phi8(EX4["Phi8_system"], r"the system's $\Phi_8$ as printed")


def _ev_ex3_system():
    m = example("ch13_example3")
    printed_rows = EX3["Phi6_7_system"]
    own = {str(v) for v in m.q}
    foreign = sorted(str(v) for v in printed_rows.free_symbols if str(v) not in own)
    x3, y3 = (m.q[m.index(c), 0] for c in ("x3", "y3"))
    x4, y4 = sp.symbols("x4 y4", real=True)
    f = sp.lambdify(list(m.q), list(printed_rows.subs({x4: x3, y4: y3})), "numpy")
    err = max(float(np.abs(np.array(f(*q), dtype=float) - m.Phi(q, 0.0)[5:7]).max())
              for q in np.random.default_rng(3).uniform(-2, 2, (20, 9)))
    return Evidence(rf"The printed rows hold {_math_names(foreign)}: example 3 has three bodies (coordinates "
                    rf"$x_1 \dots \varphi_3$), so they cannot be evaluated. With $x_3$, $y_3$ they are kinbook's $\Phi_6$, "
                    rf"$\Phi_7$: at 20 random configurations the difference {below(err)}.", float("inf") if foreign else 0.0, err)


def _ev_ex2_translational():
    m = example("ch13_example2")
    rows = []
    for q in np.random.default_rng(2).uniform(-2, 2, (20, 12)):
        r1, A1, r4, A4 = q[0:2], planar.A(q[2]), q[9:11], planar.A(q[11])
        P_i, Q_i = r1, r1 + A1 @ (1.0, 0.0)           # the points the example chooses on body 1
        P_j, Q_j = r4, r4 + A4 @ (1.0, 0.0)           # P_j = B on body 4, Q_j any second point of body 4
        printed_row = ex2_translational_general(P_i, Q_i, P_j, Q_j)
        corrected = ex2_translational_general(P_i, Q_i, P_j, P_i)   # eq. 26: P_j − P_i
        rows.append((printed_row, corrected, m.Phi(q, 0.0)[5]))
    e_p, e_c = compare(rows)
    return Evidence(rf"With $P_i = O_1$, $Q_i = (1, 0)$ on body 1 (the example's choice) and $Q_j = (1, 0)$ on body 4, "
                    rf"the printed row is $\sin(\varphi_4 - \varphi_1)$, blind to where the slider is: at 20 random "
                    rf"configurations it differs from kinbook's $\Phi_6$ by up to {e_p:.3f}; with $P_j - P_i$ (eq. 26) it "
                    rf"{agrees(e_c)}.",
                    e_p, e_c)


def _ev_ex2_l3():
    m = example("ch13_example2")
    rod = next(b for b in m.bodies if b.name == "rod")
    length = float(np.linalg.norm(np.subtract(rod.points["B"], rod.points["A"]).astype(float)))
    return Evidence(rf"“b/6” is no length ($b$ is defined nowhere); the local coordinates printed next, $\xi_3^A = -3$ and "
                    rf"$\xi_3^B = 3$, put $A$ and $B$ 6 apart, as kinbook's example-2 rod does ($|AB| = {length:g}$).",
                    float("inf"), abs(length - 6.0))


def _ev_ex5_joint3_working():
    q = EX5["q"]
    A_, B_ = EX1["A"], EX1["B"]
    x2, y2, x3, y3 = q[3], q[4], q[6], q[7]
    as_labelled = np.array([A_[0] - B_[0], A_[1] - B_[1], 0.0, 0.0])   # x^A − x^B, y^A − y^B, x_j^p − x_j^p (= 0) …
    corrected = np.array([A_[0] - x2, A_[1] - y2, B_[0] - x3, B_[1] - y3])
    values = EX5["rr_arms"]
    e_p, e_c = float(np.abs(as_labelled - values).max()), float(np.abs(corrected - values).max())
    return Evidence(rf"At the book's own points $A = ({A_[0]}, {A_[1]})$, $B = ({B_[0]}, {B_[1]})$ and $x_2 = {x2}$, "
                    rf"$x_3 = {x3}$: the printed labels ($x^A - x^B$, $y^A - y^B$, and $x_j^p - x_j^p$, which is 0) differ "
                    rf"from the numbers written after them by up to {e_p:.4f}; the lever arms $x^A - x_2$, $y^A - y_2$, "
                    rf"$x^B - x_3$, $y^B - y_3$ give those numbers to their printed digits "
                    rf"({small(e_c, 2e-4, relation=True)}).",
                    e_p, e_c, tolerance=2e-4)


def _ev_q_13_6():
    m = example("ch13_example1")
    printed_q = {str(v) for v in EX1["q_13_6"]}
    own = [str(v) for v in m.q]
    missing = [c for c in own if c not in printed_q]
    phi11 = EX1["Phi11_13_6"]
    outside = [str(v) for v in phi11.free_symbols if str(v) not in own]   # none: the corrected q holds them all
    f = sp.lambdify(list(m.q), phi11.subs({s: m.q[m.index(str(s)), 0] for s in phi11.free_symbols}), "numpy")
    err = max(abs(float(f(*q)) - m.Phi(q, 0.0)[10]) for q in np.random.default_rng(6).uniform(-2, 2, (20, m.n)))
    needs = sorted(str(v) for v in phi11.free_symbols if str(v) not in printed_q)
    return Evidence(rf"Example 1 has four bodies, ground included: kinbook's $\mathbf q$ has {m.n} coordinates, the "
                    rf"printed one {len(printed_q)}, without {_math_names(missing)}. The $\Phi_{{11}}$ printed a few lines below holds "
                    rf"{_math_names(needs)} and is kinbook's $\Phi_{{11}}$ with all twelve (at 20 random "
                    rf"configurations the difference {below(err)}).", float(len(missing)), float(len(outside) + err))


def _ev_ex5_phi8_row():
    """Example 5's numeric Φ_8 row: the right formula (the corrected Table 13.3, as the example's own lever arms
    use it), evaluated at the configuration of example 1/3, which does not assemble."""
    m = example("ch13_example3")
    printed = np.asarray(EX5["J"], dtype=float)[7, 3:]
    q = m.solve_position(0.0)
    kinbook_row = m.Phi_q(q, 0.0)[7, 3:]

    def formula(q, rA, rB):  # the corrected Table 13.3 with i = 2 (A), j = 3 (B), written out
        d, arm_i, arm_j = rA - rB, rA - q[3:5], rB - q[6:8]
        return np.array([2 * d[0], 2 * d[1], -2 * d[0] * arm_i[1] + 2 * d[1] * arm_i[0],
                         -2 * d[0], -2 * d[1], 2 * d[0] * arm_j[1] - 2 * d[1] * arm_j[0]])

    corrected = formula(q, m.point_position(q, "crank", "A"), m.point_position(q, "rocker", "B"))
    qb = np.asarray(EX5["q"], dtype=float)
    at_book = formula(qb, m.point_position(qb, "crank", "A"), m.point_position(qb, "rocker", "B"))
    p_err, c_err = compare([(printed, corrected, kinbook_row)])
    return Evidence(
        rf"kinbook's row 8 of $\boldsymbol\Phi_{{\mathbf q}}$ at the assembled $\mathbf q(0)$ (columns $x_2 \dots \varphi_3$): "
        rf"${notation.latex(sp.Matrix([np.round(kinbook_row, 4)]))}$; the printed row differs by up to {p_err:.3f}. The "
        rf"corrected Table 13.3, written out at that $\mathbf q(0)$, agrees (difference {below(c_err, 1e-9)}); the same formula "
        rf"at the book's configuration (examples 1/3, not assembled) gives the printed numbers to "
        rf"{small(float(np.abs(at_book - printed).max()), 1e-4, 2)}: the row is right, its configuration is not.",
        p_err, c_err, tolerance=1e-9)


def _ev_ex5_ground_points():
    m = example("ch13_example3")
    rows = []
    for q in np.random.default_rng(7).uniform(-2, 2, (20, m.n)):
        for point in ("OA", "OB"):
            xi, eta = m.body("ground").points[point]
            y = m.point_position(q, "ground", point)[1]
            rows.append((ex5_ground_point_y(q[1], q[2], xi, eta), q[1] + xi * np.sin(q[2]) + eta * np.cos(q[2]), y))
    e_p, e_c = compare(rows)
    return Evidence(rf"For the ground's points $O_A = (0, 0)$ and $O_B = (3, 0)$ at 20 random ground positions, the "
                    rf"printed $y_1 + \eta_1^P \operatorname{{sen}}\varphi_1$ differs from kinbook's $y^P$ by up to "
                    rf"{e_p:.4f}; $y_1 + \xi_1^P \operatorname{{sen}}\varphi_1 + \eta_1^P\cos\varphi_1$ agrees "
                    rf"(difference {below(e_c)}). At $t = 0$ ($y_1 = \varphi_1 = 0$) both give 0, so the example's numbers "
                    rf"hide the slip.", e_p, e_c)


def _ev_ex6_point_A():
    m = example("ch13_example3")
    A = m.point_position(EX5["q"], "crank", "A")     # the book's configuration (x_2 = −0.7071, φ_2 = 135°)
    printed_A, corrected = EX6["A"], EX6["A"] * np.array([-1.0, 1.0])
    e_p, e_c = float(np.abs(printed_A - A).max()), float(np.abs(corrected - A).max())
    return Evidence(rf"At the book's own configuration ($x_2 = -0.7071$, $\varphi_2 = 135°$, $\xi_2^A = 1$) kinbook's "
                    rf"$A$ is ({A[0]:.4f}, {A[1]:.4f}): the listed $x^A$ is off by {e_p:.4f}, −1.4142 agrees to the "
                    rf"printed digits ({small(e_c, 2e-4, relation=True)}). Example 5 and example 6's own joint-3 data "
                    rf"print −1.4142.", e_p, e_c, tolerance=2e-4)


def _ev_ex6_point_acceleration():
    rows = []
    for r in np.random.default_rng(8).uniform(-2, 2, (20, 7)):
        rdd, phi, w, al, xi, eta = r[0:2], r[2], r[3], r[4], r[5], r[6]
        s, c = np.sin(phi), np.cos(phi)
        corrected = rdd + np.array([-xi * s - eta * c, xi * c - eta * s]) * al - np.array([xi * c - eta * s,
                                                                                         xi * s + eta * c]) * w**2
        ref = planar.point_acceleration(rdd, phi, w, al, [xi, eta])
        printed_a = ex6_point_acceleration(rdd, phi, w, al, xi, eta)
        rows += [(printed_a[k], corrected[k], ref[k]) for k in range(2)]
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random states ($\ddot{{\mathbf r}}$, $\varphi$, $\dot\varphi$, $\ddot\varphi$, $\xi$, "
                    rf"$\eta$) the printed rows differ from kinbook's point_acceleration (eq. 13) by up to {e_p:.3f}; with "
                    rf"$\ddot\varphi$ on the $\mathbf B\mathbf s'$ bracket and $\dot\varphi^2$ on the $\mathbf A\mathbf s'$ "
                    rf"one they agree (difference {below(e_c)}). With $\eta = 0$ the simplified rows the example uses next "
                    rf"are right.", e_p, e_c)


def _ev_ex6_solution_dots():
    m = example("ch13_example3")
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    qdd = m.solve_acceleration(q, qd, 0.0)
    printed = EX6["qdd"][:6]                          # bodies 1 and 2, printed with one dot and whole numbers
    as_velocities = float(np.abs(printed - qd[:6]).max())
    as_accelerations = float(np.abs(printed - np.round(qdd[:6])).max())   # kinbook's rounded alike
    return Evidence(
        rf"Read as velocities, the printed $\dot x_2 = 7071$, $\dot y_2 = -7071$, $\dot\varphi_2 = 0$ are off from "
        rf"kinbook's $\dot{{\mathbf q}}_2 = ({qd[3]:.2f}, {qd[4]:.2f}, {qd[5]:.0f})$ by up to {as_velocities:.2f}; "
        rf"read as accelerations they are kinbook's $\ddot{{\mathbf q}}_2 = ({qdd[3]:.2f}, {qdd[4]:.2f}, "
        rf"{abs(qdd[5]):.0f})$ to their printed digits, as are body 1's zeros (difference {below(as_accelerations)}).",
        as_velocities, as_accelerations)


def _printed_vs_kinbook(kind, quantity, printed_matrix, corrected_matrix, entry, equal=(), up_to_sign=True):
    """(printed error, corrected error) of the entry (r, c) — or the largest over a list of entries — of a printed
    table (kinbook.book.printed), against kinbook's derivation for the two-body joint ``kind`` at 20 random states
    (with ``up_to_sign``, a printed row × −1 counts as the same row: Φ = 0 and −Φ = 0 are one constraint)."""
    m = notation.pair(kind)
    derived = getattr(m.symbolic(), quantity)
    entries = [entry] if isinstance(entry[0], int) else list(entry)
    printed_c = verify.compare(printed_matrix, derived, m, equal=equal, up_to_sign=up_to_sign)
    corrected_c = verify.compare(corrected_matrix, derived, m, equal=equal, up_to_sign=up_to_sign)
    return (max(float(printed_c.errors[r, c]) for r, c in entries),
            max(float(corrected_c.errors[r, c]) for r, c in entries))


def _with_entry(M, entry, value):
    M = M.copy()
    M[entry] = value
    return M


def _ev_table_13_1_text():
    e_p, e_c = _printed_vs_kinbook("r", "Phi_q", TABLE_13_1_TEXT, TABLES["13.1"][1], [(0, 2), (0, 5), (1, 2), (1, 5)])
    return Evidence(rf"The four printed derivatives $\partial\Phi/\partial\varphi_i$, $\partial\Phi/\partial\varphi_j$ "
                    rf"at 20 random configurations: off by up to {e_p:.3f}; with the body origins ($x_i$, $y_i$, $x_j$, "
                    rf"$y_j$), as Table 13.1 prints them, they {agrees(e_c)}.", e_p, e_c)


def _ev_eq25():
    corrected = EQ["26"]
    printed_eq = corrected.subs({S.xQ_i: S.x_i, S.yQ_i: S.y_i})   # the second guide point read as the origin O_i
    e_p, e_c = _printed_vs_kinbook("t", "Phi", printed_eq, corrected, (0, 0))
    return Evidence(rf"Eq. 26 with $O$ read as the body origin $O_i$: at 20 random configurations (guide line not "
                    rf"through $O_i$) its first row differs from kinbook's by up to {e_p:.3f}; with the guide point $Q_i$ "
                    rf"it {agrees(e_c)}.", e_p, e_c)


def _ev_gamma_sign():
    P = REVOLUTE_STEPS["(Phi_q qd)_q qd"]
    e_p, e_c = _printed_vs_kinbook("r", "gamma", P, -P, [(0, 0), (1, 0)], up_to_sign=False)
    return Evidence(rf"For the revolute joint, $\gamma = (\boldsymbol\Phi_{{\mathbf q}}\dot{{\mathbf q}})_{{\mathbf q}}"
                    rf"\dot{{\mathbf q}}$ with the section's own $(\boldsymbol\Phi_{{\mathbf q}}\dot{{\mathbf q}})_"
                    rf"{{\mathbf q}}\dot{{\mathbf q}}$ differs from kinbook's $\gamma$ by up to {e_p:.2f} at 20 random "
                    rf"states; $\gamma = -(\boldsymbol\Phi_{{\mathbf q}}\dot{{\mathbf q}})_{{\mathbf q}}"
                    rf"\dot{{\mathbf q}}$ ($\boldsymbol\Phi_t = \mathbf 0$ here) {agrees(e_c)}.", e_p, e_c)


def _ev_velocity_rhs():
    m = example("ch13_example3")
    q = m.solve_position(0.0)
    h = 1e-6
    phi_t = (m.Phi(q, h) - m.Phi(q, -h)) / (2 * h)     # Φ_t: only the driver's row depends on t
    nu = m.nu(q, 0.0)
    e_p, e_c = float(np.abs(phi_t - nu).max()), float(np.abs(-phi_t - nu).max())
    return Evidence(rf"Example 3's driver $\varphi_2 - 3\pi/4 - 100t$ has $\Phi_t = {phi_t[-1]:.4g}$: the printed "
                    rf"right-hand side $[\mathbf 0; \boldsymbol\Phi_t]$ gives $\nu_9 = {phi_t[-1]:.4g}$, kinbook's "
                    rf"$\nu_9 = {nu[-1]:.4g}$ (example 5 itself uses 100); $[\mathbf 0; -\boldsymbol\Phi_t]$ "
                    rf"{agrees(e_c, 1e-6)}.", e_p, e_c, tolerance=1e-6)


def _ev_table_13_2():
    P = TABLES["13.2"][1]
    fixed = (S.xP_j - S.x_j) * (S.xP_i - S.xQ_i) + (S.yP_j - S.y_j) * (S.yP_i - S.yQ_i)
    e_p, e_c = _printed_vs_kinbook("t", "Phi_q", P, _with_entry(P, (0, 5), fixed), (0, 5))
    return Evidence(rf"$\partial\Phi_1/\partial\varphi_j$ at 20 random configurations: the printed entry is off by up "
                    rf"to {e_p:.3f}; with $x_j$, $y_j$ it {agrees(e_c)}.", e_p, e_c)


def _ev_table_13_3():
    P = TABLES["13.3"][1]
    dx, dy = S.xP_i - S.xP_j, S.yP_i - S.yP_j
    fixed = _with_entry(P, (0, 2), -2 * dx * (S.yP_i - S.y_i) + 2 * dy * (S.xP_i - S.x_i))
    fixed[0, 5] = 2 * dx * (S.yP_j - S.y_j) - 2 * dy * (S.xP_j - S.x_j)
    e_p, e_c = _printed_vs_kinbook("rr", "Phi_q", P, fixed, [(0, 2), (0, 5)])
    return Evidence(rf"Both printed entries, $\partial\Phi/\partial\varphi_i$ and $\partial\Phi/\partial\varphi_j$, "
                    rf"reduce to 0; kinbook's entries reach {e_p:.3f} at 20 random configurations; the corrected entries "
                    rf"{agrees(e_c)}.", e_p, e_c)


def _ev_table_13_4():
    P = TABLES["13.4"][1]
    fixed = (S.yP_i - S.y_j) * (S.yP_j - S.yQ_j) + (S.xP_i - S.x_j) * (S.xP_j - S.xQ_j)
    e_p, e_c = _printed_vs_kinbook("rt", "Phi_q", P, _with_entry(P, (0, 5), fixed), (0, 5))
    return Evidence(rf"$\partial\Phi/\partial\varphi_j$ of the r-t joint at 20 random configurations: printed entry off "
                    rf"by up to {e_p:.3f}; with $x_j$, $y_j$ it {agrees(e_c)}.", e_p, e_c)


def _ev_gamma_rr():
    P = TABLE_13_5_GAMMA["rr"]
    fixed = P + sp.Matrix([2 * (S.yd_i - S.yd_j) - 2 * (S.yd_i - S.yd_j) ** 2])
    e_p, e_c = _printed_vs_kinbook("rr", "gamma", P, fixed, (0, 0))
    return Evidence(rf"$\gamma$ of the r-r joint at 20 random states: printed entry off by up to {e_p:.2f}; with "
                    rf"$(\dot y_i - \dot y_j)^2$ it {agrees(e_c)}.", e_p, e_c)


def _ev_gamma_t():
    P = TABLE_13_5_GAMMA["t"]
    sx, sy = S.xP_i - S.xQ_i, S.yP_i - S.yQ_i
    velocity_term = 2 * (sx * (S.xd_i - S.xd_j) + sy * (S.yd_i - S.yd_j)) * S.w_i
    fixed = _with_entry(P, (0, 0), P[0, 0] - 2 * velocity_term)
    e_p, e_c = _printed_vs_kinbook("t", "gamma", P, fixed, (0, 0), equal=[(S.w_i, S.w_j)])
    return Evidence(rf"$\gamma_1$ of the translational joint at 20 random states with $\dot\varphi_j = \dot\varphi_i$: "
                    rf"printed entry off by up to {e_p:.2f}; with $-2[\ldots]\dot\varphi_i$ it {agrees(e_c)}.", e_p, e_c)


def _ev_revolute_steps():
    P = REVOLUTE_STEPS["Phi_q qd"]
    fixed = _with_entry(P, (1, 0), S.yd_i + (S.xP_i - S.x_i) * S.w_i - S.yd_j - (S.xP_j - S.x_j) * S.w_j)

    m = notation.pair("r")
    derived = m.symbolic().Phi_q * m.qd
    e_p = float(verify.compare(P, derived, m).errors[1, 0])
    e_c = float(verify.compare(fixed, derived, m).errors[1, 0])
    return Evidence(rf"Row 2 of $\boldsymbol\Phi_{{\mathbf q}}\dot{{\mathbf q}}$ for the revolute joint at 20 random "
                    rf"states: the printed row is off by up to {e_p:.2f}; $\dot y_i + (x_i^P - x_i)\dot\varphi_i - \dot y_j "
                    rf"- (x_j^P - x_j)\dot\varphi_j$ {agrees(e_c)}.", e_p, e_c)


def _ev_ex5_velocity():
    m = example("ch13_example3")
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    vB = m.point_velocity(q, qd, "rocker", "B")
    printed = np.array([-190.7802, 117.1410])
    # the card's "correct" line: ẋ2, ẏ2, q̇3, v_B, |v_B| as it states them, against kinbook's rounded alike
    stated = np.array([-70.71, -70.71, -96.22, 53.78, 73.49, -192.44, 107.56, 220.46])
    computed = np.round(np.r_[qd[3:5], qd[6:9], vB, np.linalg.norm(vB)], 2)
    corrected_error = float(np.abs(stated - computed).max())
    return Evidence(
        rf"kinbook: $\dot{{\mathbf q}}_3 = ({qd[6]:.2f}, {qd[7]:.2f}, {qd[8]:.2f})$, "
        rf"$\mathbf v^B = ({vB[0]:.2f}, {vB[1]:.2f})$, $|\mathbf v^B| = {np.linalg.norm(vB):.2f}$; the printed "
        rf"$\mathbf v^B = (-190.78, 117.14)$ is off by {np.linalg.norm(printed - vB):.2f} because it is computed at "
        rf"the unassembled printed configuration. The corrected line's values are kinbook's to their two decimals "
        rf"(difference {below(corrected_error, 1e-9)}).",
        float(np.linalg.norm(printed - vB)), corrected_error)


def _ev_ex6_acceleration():
    m = example("ch13_example3")
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    qdd = m.solve_acceleration(q, qd, 0.0)
    aB = m.point_acceleration(q, qd, qdd, "rocker", "B")
    printed = np.array([4084.136, -22111.679])
    g = m.gamma(q, qd, 0.0)
    # the card's "correct" line: γ_6, γ_7, γ_8 and a_B as it states them, against kinbook's rounded alike
    stated = np.array([3952.10, 7071.08, 396.38, 4582.90, -21121.33])
    corrected_error = float(np.abs(stated - np.round(np.r_[g[5:8], aB], 2)).max())
    return Evidence(
        rf"kinbook: $\gamma_6, \gamma_7, \gamma_8 = {g[5]:.2f}, {g[6]:.2f}, {g[7]:.2f}$, "
        rf"$\ddot{{\mathbf q}}_3 = ({qdd[6]:.2f}, {qdd[7]:.2f}, {qdd[8]:.2f})$, "
        rf"$\mathbf a^B = ({aB[0]:.2f}, {aB[1]:.2f})$, $|\mathbf a^B| = {np.linalg.norm(aB):.2f}$; the printed "
        rf"$\mathbf a^B$ is off by {np.linalg.norm(printed - aB):.1f}. The corrected line's values are kinbook's to "
        rf"their two decimals (difference {below(corrected_error, 1e-9)}).", float(np.linalg.norm(printed - aB)),
        corrected_error)


# ----------------------------------------------------------------------------------------------- the list
ERRATA = [
    Erratum("13.5-eq4-text", "§13.5, text after eq. 4", r"[x, y]_i \text{: coordinates of O in local axes}",
            r"[x, y]_i \text{: global coordinates of } O_i", "wording"),
    Erratum("13.5-q-elements", r"§13.5, the sentence after $\mathbf q = [\mathbf q_1^T, \mathbf q_2^T, \dots, \mathbf q_N^T]^T$",
            r"q_1, q_2, \dots, q_n \text{ correspond to the elements } 1, 2, \dots, n",
            r"\mathbf q_1, \dots, \mathbf q_N \text{ belong to the } N \text{ bodies; } n = 3N \text{ (plane) or } 6N "
            r"\text{ (space) counts coordinates}", "wording"),
    Erratum("13.5-ex1-solution", r"§13.5, example 1: solution at $t = 0$ and the points $A$, $B$",
            r"x_3 = 1.5777,\ y_3 = 1.9854,\ \varphi_3 = 10.81°,\ x_4 = 3.7849,\ y_4 = 1.2783,\ \varphi_4 = 238.45°,\ B = (4.5697, 2.5566)",
            r"\varphi_3 = 11.58°,\ \varphi_4 = 240.80°,\ B = (4.4636, 2.6187)", "number", _ev_ex1_solution,
            "Examples 3, 5 and 6 reuse this configuration, so their numbers inherit the error."),
    Erratum("13.5-ex1-eq-ref", "§13.5, example 1, joint 2", r"\text{“puede emplearse la expresión general (1)”}",
            r"\text{the general expression, eq. 17 (in the scalar form of eq. 34)}", "wording", None,
            "There is no eq. 1 in the section: joint 1 just used eq. 17 and its scalar form, eq. 34."),
    Erratum("13.5-ex3-x2", r"§13.5, example 3 (and example 5): solution at $t = 0$", r"x_2 = 0.7071",
            r"x_2 = -0.7071", "sign", _ev_ex3_x2, r"Example 1 prints −0.7071 ($x_2 = -\cos 45°$: the crank's "
            r"middle is left of $O_A$), and so do example 5's Jacobian and example 6."),
    Erratum("13.5-ex3-system", r"§13.5, example 3: the assembled system, $\Phi_6$ and $\Phi_7$",
            r"\ldots - x_4 - 1.5\cos\varphi_3,\ \ldots - y_4 - 1.5\sin\varphi_3",
            r"\ldots - x_3 - 1.5\cos\varphi_3,\ \ldots - y_3 - 1.5\sin\varphi_3", "typo", _ev_ex3_system,
            r"Example 3 has three bodies; there is no $x_4$ (the joint-2 section itself prints $x_3$, $y_3$)."),
    Erratum("13.5-ex4-phi8-substituted", "§13.5, example 4, joint 3: the general row with the points substituted",
            r"(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)(y_1 - y_1 - \sin\varphi_1) - "
            r"(y_3 + 3\sin\varphi_3 - y_1\sin\varphi_1)(x_1 - x_1 - \cos\varphi_1)",
            r"(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)(y_1 - y_1 - \sin\varphi_1) - "
            r"(y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)(x_1 - x_1 - \cos\varphi_1)",
            "typo", _ev_ex4_phi8_substituted, r"$y_i^P - y_j^Q = y_3 + 3\sin\varphi_3 - (y_1 + \sin\varphi_1)$: "
            r"a minus sign is missing, which makes $y_1\sin\varphi_1$ a product."),
    Erratum("13.5-ex4-phi8", r"§13.5, example 4, joint 3: $\Phi_8$ simplified",
            r"(x_3 + 3\cos\varphi_3 - x_1\cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            r"-(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            "formula", _ev_ex4_phi8, r"Two slips: $x_1\cos\varphi_1$ for $x_1 + \cos\varphi_1$ … $-\cos\varphi_1$, "
            r"and the sign of the first product (the substituted row gives $-(\ldots)\sin\varphi_1$)."),
    Erratum("13.5-ex4-phi8-system", r"§13.5, example 4: $\Phi_8$ in the assembled system",
            r"(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1\sin\varphi_1)\cos\varphi_1",
            r"-(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            "inconsistency", _ev_ex4_phi8_system, r"The system repeats neither the simplified row nor its slips: here "
            r"the $x$ part is right but its sign is not, and the $y$ part has the substituted row's "
            r"$y_1\sin\varphi_1$."),
    Erratum("13.5-ex2-translational", "§13.5, example 2, joint 2: the general translational row",
            r"(x_i^P - x_i^Q)(y_j^P - y_j^Q) - (y_i^P - y_i^Q)(x_j^P - x_j^Q)",
            r"(x_i^P - x_i^Q)(y_j^P - y_i^P) - (y_i^P - y_i^Q)(x_j^P - x_i^P)\ \text{(eq. 26)}", "formula",
            _ev_ex2_translational, r"As printed it asks only that $P_jQ_j$ be parallel to the guide (the second "
            r"row already does); eq. 26 asks $P_j$ to lie on the guide line. The example defines no $Q_j$, and its "
            r"$\Phi_6$, substituted just below, is eq. 26's."),
    Erratum("13.5-ex2-l3", "§13.5, example 2: local frame of body 3", r"l_3 = b/6", r"l_3 = 6", "number",
            _ev_ex2_l3),
    Erratum("13.5-ex2-driver", "§13.5, example 2, the driver's parameters", r"\varphi_2 = \frac{\pi}{4} = 45°",
            r"\varphi_2^0 = \frac{\pi}{4} = 45°", "wording", None,
            r"The initial value $\varphi_2^0$ (as example 1 writes it), not the coordinate $\varphi_2$, which "
            r"changes with $t$."),
    Erratum("13.5-motrices", "§13.5, examples 2 and 4: headings and the sentence on driving constraints",
            r"\text{“restricciones matrices adicionales”, “ecuaciones matrices”, “una única ecuación matriz”}",
            r"\text{restricciones / ecuaciones motrices, una única ecuación motriz (driving constraints)}",
            "wording", None, "“Matriz” (matrix) for “motriz” (driving): the equations added for the degrees of "
            "freedom are the drivers, as example 1 calls them."),
    Erratum("13.5-revolute-words", "§13.5, Par elemental de Revolución, first sentence and after eqs. 14–15",
            r"\text{“la junta de revolución que une los dos puntos } i \text{ y } j\text{”; } s_j^P, s_i^P "
            r"\text{ “los vectores } O_j^P \text{ y } O_i^P\text{”}",
            r"\text{the joint connects the two bodies } i, j\text{; } s_j^P, s_i^P \text{ are the vectors } "
            r"\overrightarrow{O_jP},\ \overrightarrow{O_iP}", "wording"),
    Erratum("13.5-eq25", "§13.5, translational joint, eqs. 23.a and 24–26 (and Tables 13.2, 13.4, 13.5: “o”)",
            r"s_i = r_i^P - r_i^O,\ (x_i^P - x_i^O)(y_j^P - y_i^P) - (y_i^P - y_i^O)(x_j^P - x_i^P) = 0",
            r"s_i = r_i^P - r_i^Q,\ (x_i^P - x_i^Q)(y_j^P - y_i^P) - (y_i^P - y_i^Q)(x_j^P - x_i^P) = 0",
            "formula", _ev_eq25,
            r"The text takes the guide points $P_i$ and $Q_i$; the formulas call the second one $O$, the letter "
            r"the book reserves for a body's reference point $O_i$. Read as $O_i$ the equation holds only when "
            r"$O_i$ happens to lie on the guide line."),
    Erratum("13.5-eq21", "§13.5, translational joint, text after eq. 21", r"\text{eq. (19) is one of the two equations}",
            r"\text{eq. (21)}", "wording"),
    Erratum("13.5-three-points", "§13.5, translational joint, before eq. 22",
            r"\text{“Entre estos dos puntos se impone la condición de que permanezcan continuamente alineados”}",
            r"\text{“Entre estos tres puntos se impone la condición …”}", "wording",
            note=r"The sentence before names three points: $P_i$ and $Q_i$ on body $i$, $P_j$ on body $j$; the "
                 r"condition is that the three stay on one line ($\mathbf s_i \times \mathbf d = \mathbf 0$, eq. 22)."),
    Erratum("13.5-eq24", "§13.5, translational joint, before eq. 24", r"\text{multiplying the vectors scalarly}",
            r"\text{the vector (cross) product}", "wording"),
    Erratum("13.5-rt-collinearity", "§13.5, Par de Revolución-Traslación, last paragraph",
            r"\text{the translational joint required the collinearity of } s_i \text{ and } s_j",
            r"\text{of } s_i \text{ and } d \text{ (eq. 22)}", "wording"),
    Erratum("13.5-joint-labels", "§13.5, examples 2 and 4: labels and references",
            r"\Phi^{(i,2)},\ \Phi^{(r,1)},\ \text{apartado 4.3 / 4.5},\ \text{“as in example 3”}",
            r"\Phi^{(t,2)},\ \Phi^{(r\text{-}t,1)},\ \text{the translational / r-t subsections of §13.5},\ \text{example 2}",
            "wording"),
    Erratum("13.6-q-example1", r"§13.6, the coordinate vector $\mathbf q$ “for the example cited” (example 1)",
            r"\mathbf q = [x_1, y_1, \varphi_1, x_2, y_2, \varphi_2, x_3, y_3, \varphi_3]^T",
            r"\mathbf q = [x_1, y_1, \varphi_1, \dots, x_4, y_4, \varphi_4]^T\ (n = 12)", "formula", _ev_q_13_6,
            r"Example 1's four-bar has four bodies, the ground included ($\Phi_1$–$\Phi_3$ fix it), so $n = 12$ "
            r"and $m = 11$; the section itself then lists $\Phi_4 \dots \Phi_{11}$ with $y_4$ and $\varphi_4$. "
            r"(Nine coordinates fit three moving bars with the ground left out, which is not how example 1 is set "
            r"up.)"),
    Erratum("13.7-ex5-ground-points", r"§13.7, example 5: global coordinates of $O_A$ and $O_B$ at $t = 0$",
            r"y^{O_A} = y_1 + \eta_1^{O_A}\,\text{sen}\,\varphi_1,\quad y^{O_B} = y_1 + \eta_1^{O_B}\,\text{sen}\,\varphi_1",
            r"y^{P} = y_1 + \xi_1^{P}\sin\varphi_1\ \ (\eta_1^P = 0)", "typo", _ev_ex5_ground_points,
            r"The simplified transformation just printed, $y_i^P = y_i + \xi_i^P \operatorname{sen}\varphi_i$, has "
            r"$\xi$; the $x$ rows have $\xi$ too."),
    Erratum("13.7-ex5-reference", "§13.7, example 5, the sentence after the statement",
            r"\text{“el mismo del ejemplo 3 del capítulo 3”}",
            r"\text{the mechanism of example 3, §13.5 (this chapter)}", "wording", None,
            r"There is no chapter 3 in these chapters: example 3 (the four-bar with a revolute–revolute joint) is "
            r"in §13.5, where its constraint equations and its solution at $t = 0$ are obtained."),
    Erratum("13.6-previous-chapter", "§13.6, the paragraph before Table 13.1",
            r"\text{“Ya se comentó en el capítulo anterior que las ecuaciones de restricción …”}",
            r"\text{“Ya se comentó en el apartado anterior (§13.5) …”}", "wording",
            note=r"The constraint equations and their variables $\mathbf q_i$, $\mathbf q_j$ are the subject of §13.5, "
                 r"the section before, in the same chapter."),
    Erratum("13.6-table-13.1-text", "§13.6, the derivation under Table 13.1",
            r"\partial\Phi_1/\partial\varphi_i = -(y_i^P - y_j^P),\ \ldots",
            r"-(y_i^P - y_i),\ (y_j^P - y_j),\ (x_i^P - x_i),\ -(x_j^P - x_j)", "formula", _ev_table_13_1_text,
            "Table 13.1 itself is right; only the worked derivatives below it use the wrong points."),
    Erratum("13.6-table-13.2", r"§13.6, Table 13.2 (translational joint), $\partial\Phi_1/\partial\varphi_j$",
            r"(x_j^P - x_i)(x_i^P - x_i^O) + (y_j^P - y_i)(y_i^P - y_i^O)",
            r"(x_j^P - x_j)(x_i^P - x_i^Q) + (y_j^P - y_j)(y_i^P - y_i^Q)", "formula", _ev_table_13_2,
            "Table 13.5 prints this entry correctly."),
    Erratum("13.6-table-13.3", r"§13.6, Table 13.3 (revolute–revolute joint), $\partial/\partial\varphi_i$ and $\partial/\partial\varphi_j$",
            r"\frac{\partial}{\partial\varphi_i}: -2(x_i^P - x_j^P)(y_i^P - y_j^P) + 2(y_i^P - y_j^P)(x_i^P - x_j^P)\ (= 0),"
            r"\quad \frac{\partial}{\partial\varphi_j}: 2(x_i^P - x_j^P)(y_j^P - y_j^P) - 2(y_i^P - y_j^P)(x_j^P - x_j^P)\ (= 0)",
            r"\frac{\partial}{\partial\varphi_i}: -2(x_i^P - x_j^P)(y_i^P - y_i) + 2(y_i^P - y_j^P)(x_i^P - x_i),\quad "
            r"\frac{\partial}{\partial\varphi_j}: 2(x_i^P - x_j^P)(y_j^P - y_j) - 2(y_i^P - y_j^P)(x_j^P - x_j)",
            "formula", _ev_table_13_3,
            "Example 5 repeats the zero entries; Table 13.5 prints them correctly."),
    Erratum("13.6-table-13.4", r"§13.6, Tables 13.4 and 13.5 (revolute–translational joint), $\partial\Phi/\partial\varphi_j$",
            r"(y_i^P - y_i)(y_j^P - y_j^Q) + (x_i^P - x_i)(x_j^P - x_j^Q)",
            r"(y_i^P - y_j)(y_j^P - y_j^Q) + (x_i^P - x_j)(x_j^P - x_j^Q)", "formula", _ev_table_13_4),
    Erratum("13.7-ex5-phi8-row", r"§13.7, example 5, joint 3 (r-r): the numeric row $\Phi_8$ of the Jacobian",
            r"\Phi_8:\ [-11.968,\ -2.2848,\ 10.0781,\ 11.968,\ 2.2848,\ -13.5053]",
            r"\Phi_8:\ [-11.7557,\ -2.409,\ 10.016,\ 11.7557,\ 2.409,\ -13.6295]\ \text{at the assembled } \mathbf q(0)",
            "number", _ev_ex5_phi8_row,
            r"The row follows from the right formula, but at the configuration of example 1/3, which does not "
            r"assemble ($|AB| = 6.092$); the velocities of example 5 are solved with it (13.7-ex5-velocities)."),
    Erratum("13.7-ex5-joint3-working", "§13.7, example 5, joint 3 (r-r): the values substituted into the general row",
            r"(x_i^p - x_j^p) = (x^A - x^B) = -1.4142 + 0.7071,\ (y_i^p - y_j^p) = 1.4142 - 0.7071,\ "
            r"(x_j^p - x_j^p) = (x^B - x^3),\ (y_j^p - y_j^p) = (y^B - y^3)",
            r"(x_i^P - x_i) = x^A - x_2 = -1.4142 + 0.7071,\ (y_i^P - y_i) = y^A - y_2,\ (x_j^P - x_j) = x^B - x_3,"
            r"\ (y_j^P - y_j) = y^B - y_3", "formula", _ev_ex5_joint3_working,
            r"The first four lines are the lever arms of the corrected Table 13.3 (points relative to the body "
            r"origins), labelled as differences of joint points; the numbers that follow ($\Phi_8$'s row) were "
            r"computed with the right ones."),
    Erratum("13.8-revolute-Phiq-qd", r"§13.8, the revolute joint worked step by step: row 2 of $\boldsymbol\Phi_{\mathbf q}\dot{\mathbf q}$",
            r"\dot x_j - (x_i^P - x_i)\dot\varphi_i - \dot y_j + (x_j^P - x_j)\dot\varphi_j",
            r"\dot y_i + (x_i^P - x_i)\dot\varphi_i - \dot y_j - (x_j^P - x_j)\dot\varphi_j", "formula",
            _ev_revolute_steps, r"Row 2 of Table 13.1 times $\dot{\mathbf q}$; the next step, "
            r"$(\boldsymbol\Phi_{\mathbf q}\dot{\mathbf q})_{\mathbf q}\dot{\mathbf q}$, is printed right."),
    Erratum("13.8-gamma-sign", "§13.8, the revolute-joint walkthrough and example 6",
            r"\gamma = (\Phi_q\dot q)_q\dot q", r"\gamma = -(\Phi_q\dot q)_q\dot q - 2\Phi_{qt}\dot q - \Phi_{tt}",
            "sign", _ev_gamma_sign, r"The section first writes the minus sign, then drops it; its final $\gamma$ "
            r"rows use the right sign."),
    Erratum("13.8-table-13.5-rr", r"§13.8, Table 13.5, $\gamma$ of the revolute–revolute joint (and example 6)",
            r"-2(\dot x_i - \dot x_j)^2 - 2(\dot y_i - \dot y_j) - \ldots",
            r"-2(\dot x_i - \dot x_j)^2 - 2(\dot y_i - \dot y_j)^2 - \ldots", "formula", _ev_gamma_rr),
    Erratum("13.8-table-13.5-t", r"§13.8, Table 13.5, $\gamma_1$ of the translational joint",
            r"2[(x_i^P - x_i^O)(\dot x_i - \dot x_j) + (y_i^P - y_i^O)(\dot y_i - \dot y_j)]\dot\varphi_i - [\ldots]\dot\varphi_i^2",
            r"-2[(x_i^P - x_i^Q)(\dot x_i - \dot x_j) + (y_i^P - y_i^Q)(\dot y_i - \dot y_j)]\dot\varphi_i - [\ldots]\dot\varphi_i^2",
            "sign", _ev_gamma_t, r"The printed entry already uses $\dot\varphi_j = \dot\varphi_i$; its $O$ is the "
            r"guide point $Q_i$ (13.5-eq25)."),
    Erratum("13.7-velocity-rhs", "§13.7, example 5: general form of the velocity equations",
            r"\begin{bmatrix}\Phi_q\\ \Phi_q^{(d)}\end{bmatrix}\dot q = \begin{bmatrix}0\\ \Phi_t^{(d)}\end{bmatrix}",
            r"\begin{bmatrix}\Phi_q\\ \Phi_q^{(d)}\end{bmatrix}\dot q = \begin{bmatrix}0\\ -\Phi_t^{(d)}\end{bmatrix}",
            "sign", _ev_velocity_rhs, "The section's own derivation (before example 5) has the minus sign."),
    Erratum("13.7-ex5-velocities", r"§13.7, example 5: velocity solution and $\mathbf v^B$",
            r"\dot x_2 = \dot y_2 = 70.71,\ \dot x_3 = 95.391,\ v_B = (-190.78, 117.14),\ |v_B| = 223.87",
            r"\dot x_2 = \dot y_2 = -70.71,\ \dot q_3 = (-96.22, 53.78, 73.49),\ v_B = (-192.44, 107.56),\ |v_B| = 220.46",
            "number", _ev_ex5_velocity, r"The signs of $\dot x_2$, $\dot y_2$, $\dot x_3$ contradict the book's "
            r"own equations; the other differences come from the wrong configuration of example 1/3."),
    Erratum("13.8-ex6-point-A", r"§13.8, example 6: the global points of the joints at $t = 0$",
            r"(x^A, y^A) = (1.4142,\ 1.4142)", r"(x^A, y^A) = (-1.4142,\ 1.4142)", "sign", _ev_ex6_point_A,
            "The same example's joint-3 data, a few lines below, use (−1.4142, 1.4142)."),
    Erratum("13.8-ex6-point-acceleration", "§13.8, example 6: the acceleration of a point, component by component",
            r"\ddot x_i^P = \ddot x_i + \ddot\varphi_i(-\xi_i^P\,\text{sen}\,\varphi_i - \eta_i^P\cos\varphi_i)\,"
            r"\dot\varphi_i^2 - (\xi_i^P\cos\varphi_i - \eta_i^P\,\text{sen}\,\varphi_i),\ \ldots",
            r"\ddot x_i^P = \ddot x_i + (-\xi_i^P\sin\varphi_i - \eta_i^P\cos\varphi_i)\,\ddot\varphi_i"
            r" - (\xi_i^P\cos\varphi_i - \eta_i^P\sin\varphi_i)\,\dot\varphi_i^2,\ \ldots", "formula",
            _ev_ex6_point_acceleration,
            r"Eq. 13 written out with $\ddot\varphi_i$ and $\dot\varphi_i^2$ on the wrong brackets (the $\ddot y$ "
            r"row likewise); eq. 12 of §13.5 is right (notebook 13-1)."),
    Erratum("13.8-ex6-joint-label", r"§13.8, example 6: the heading of the joint at $O_B$ (rows 6–7)",
            r"\text{“Junta n.º 3”}", r"\text{joint 2 (the r-r joint between bodies 2 and 3, headed next, is joint 3)}",
            "wording"),
    Erratum("13.8-ex6-solution-dots", "§13.8, example 6: the solution of the acceleration equations",
            r"\dot x_1 = 0,\ \dot y_1 = 0,\ \dot\varphi_1 = 0,\ \dot x_2 = 7071,\ \dot y_2 = -7071,\ "
            r"\dot\varphi_2 = 0,\ \dot x_3 = 2042.03,\ \ldots",
            r"\ddot x_1 = 0,\ \ddot y_1 = 0,\ \ddot\varphi_1 = 0,\ \ddot x_2 = 7071,\ \ddot y_2 = -7071,\ "
            r"\ddot\varphi_2 = 0,\ \ddot x_3 = 2042.03,\ \ldots", "typo", _ev_ex6_solution_dots,
            r"The system just solved is in $\ddot{\mathbf q}$; the velocities, listed at the start of the example, "
            r"are $\dot x_2 = \dot y_2 = -70.71$, $\dot\varphi_2 = 100$. Body 3's values differ from kinbook's for "
            r"another reason (13.8-ex6-accelerations)."),
    Erratum("13.8-driver-second-derivative", "§13.8, the second derivative of the driving constraints",
            r"\frac{d^2\Phi_q^{(d)}}{dt^2} = \frac{d}{dt}(\Phi_q^{(d)}\dot q + \Phi_t^{(d)})",
            r"\frac{d^2\Phi^{(d)}}{dt^2} = \frac{d}{dt}(\Phi_q^{(d)}\dot q + \Phi_t^{(d)})", "wording", None,
            r"What is differentiated twice is the driving constraint $\Phi^{(d)}$ itself; $\Phi_{\mathbf q}^{(d)}$ "
            r"is its Jacobian. The result that follows is right."),
    Erratum("13.8-ex6-accelerations", r"§13.8, example 6: $\gamma$, the solution and $\mathbf a^B$",
            r"\gamma_6 = 4370.82,\ \gamma_7 = 7118.39,\ \gamma_8 = \pm 1539.6,\ a_B = (4084.1, -22111.7)",
            r"\gamma_6 = 3952.10,\ \gamma_7 = 7071.08,\ \gamma_8 = 396.38,\ a_B = (4582.90, -21121.33)",
            "number", _ev_ex6_acceleration, r"$\gamma_8$ is printed with both signs; the headings say “velocidad” "
            r"for accelerations."),
]
