"""The textbook's errata, each with evidence that kinbook computes.

Every entry says where the book is wrong, what it prints, what is correct, and — for numbers and formulas —
a function that measures the discrepancy with kinbook's own derivation or solution. The tests run every
evidence function and assert that the printed version really disagrees and the corrected one agrees, so an
erratum cannot silently become false. The errata notebook renders :func:`table`.

The book's printed numbers and formulas appear here only as the thing under test.
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import sympy as sp

from ..grading.misprints import book_A_of_p, book_n1_acceleration
from .display import agrees, small, tolerance_text
from .notation import html_math

__all__ = ["Erratum", "Evidence", "ERRATA", "KINDS", "table", "show", "get"]


@dataclass(frozen=True)
class Evidence:
    """What an evidence function measured.

    Attributes
    ----------
    text : str
        One or two sentences with the numbers.
    printed_error : float
        Size of the discrepancy of the book's version (0 would mean the book is right).
    corrected_error : float
        Size of the discrepancy of the corrected version (should be at rounding level).
    tolerance : float
        What "agrees" means for the corrected version: rounding level for a formula, the printed digits (1e-4)
        where the book's own numbers are part of the comparison.
    """

    text: str
    printed_error: float
    corrected_error: float = 0.0
    tolerance: float = 1e-9


KINDS = ("number", "formula", "sign", "wording")
"""What an erratum is: a wrong printed number; a wrong formula (a wrong term, symbol, factor, point or shape); a
sign slip alone (in a formula or a number); wrong words (a reference, a label, a claim in prose, notation)."""


@dataclass(frozen=True)
class Erratum:
    """One place where the book differs from what kinbook derives or computes.

    Only what the book prints counts: a passage it strikes through is not printed (a struck-through formula is
    never an erratum, nor is a struck-through sentence the anchor of one)."""

    id: str
    where: str
    printed: str
    correct: str
    kind: str  # one of KINDS
    evidence: Callable[[], Evidence] | None = field(default=None, repr=False)
    note: str = ""

    def check(self):
        """Run the evidence function (``None`` for wording errata)."""
        return None if self.evidence is None else self.evidence()


# ------------------------------------------------------------------------------------------------ helpers
def _below(err, tol=1e-12):
    """"< 1e-12" for a residual at round-off level, else its value."""
    return f"< {tolerance_text(tol)}" if abs(err) < tol else f"= {small(err)}"


def _ex(name):
    from .. import examples

    return examples.load(name)


def _rad(deg):
    return np.radians(deg)


def _compare(samples):
    """max |printed − reference| and max |corrected − reference| over (printed, corrected, reference) rows."""
    a = np.array(samples, dtype=float)
    return float(np.max(np.abs(a[:, 0] - a[:, 2]))), float(np.max(np.abs(a[:, 1] - a[:, 2])))


# ------------------------------------------------------------------------------------------- evidence
def _ev_ex1_solution():
    m = _ex("ch13_example1")
    from .printed import EX1

    qb = EX1["q"]
    res = m.Phi(qb, 0.0)
    A = m.point_position(qb, "crank", "A")
    B = EX1["B"]
    q = m.solve_position(0.0)
    ok = np.abs(m.Phi(q, 0.0)).max()
    return Evidence(
        f"The printed configuration leaves max |Φ_k| = {np.abs(res).max():.3f} (row Φ_{np.argmax(np.abs(res)) + 1}); "
        f"at the printed A and B the coupler would be |AB| = {np.linalg.norm(B - A):.3f} long instead of 6. "
        f"kinbook's solution: φ_3 = {np.degrees(q[8]):.2f}°, φ_4 = {np.degrees(q[11]):.2f}°, "
        f"B = ({m.point_position(q, 'rocker', 'B')[0]:.4f}, {m.point_position(q, 'rocker', 'B')[1]:.4f}), "
        f"max |Φ_k| {_below(ok)}.",
        float(np.abs(res).max()), float(ok))


def _ev_ex3_x2():
    m = _ex("ch13_example3")
    from .printed import EX3

    qb = EX3["q"]
    res = m.Phi(qb, 0.0)
    fixed = qb.copy()
    fixed[3] = -0.7071
    return Evidence(
        f"With the printed x_2 = +0.7071, Φ_4 = x_1 − x_2 + cos φ_2 = {res[3]:.4f}; with x_2 = −0.7071 it is "
        f"{small(m.Phi(fixed, 0.0)[3], 1e-4)} (the printed four decimals).", abs(float(res[3])),
        abs(float(m.Phi(fixed, 0.0)[3])), tolerance=1e-4)


def _ex4_phi8(printed_row, what):
    """Example 4's Φ_8 as printed (``printed_row``, in the mechanism's symbols) and corrected, against kinbook's
    row 8 at 20 random configurations."""
    m = _ex("ch13_example4")
    x1, y1, p1, x3, y3, p3 = (m.q[m.index(c), 0] for c in ("x1", "y1", "phi1", "x3", "y3", "phi3"))
    corrected = (-(x3 + 3 * sp.cos(p3) - x1 - sp.cos(p1)) * sp.sin(p1)
                 + (y3 + 3 * sp.sin(p3) - y1 - sp.sin(p1)) * sp.cos(p1))
    f = sp.lambdify(list(m.q), [printed_row, corrected], "numpy")
    rows = [(*f(*q), m.Phi(q, 0.0)[7]) for q in np.random.default_rng(1).uniform(-2, 2, (20, 9))]
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random configurations {what} differs from kinbook's Φ_8 by up to {e_p:.3f}; the "
                    f"corrected row {agrees(e_c)}.", e_p, e_c)


def _ev_ex4_phi8():
    from . import printed

    return _ex4_phi8(printed.EX4["Phi8"], "the simplified Φ_8 as printed")


def _ev_ex4_phi8_substituted():
    from . import printed

    return _ex4_phi8(printed.EX4["Phi8_substituted"], "the row with the points substituted, as printed,")


def _ev_ex4_phi8_system():
    from . import printed

    return _ex4_phi8(printed.EX4["Phi8_system"], "the system's Φ_8 as printed")


def _ev_ex3_system():
    from .printed import EX3

    m = _ex("ch13_example3")
    printed_rows = EX3["Phi6_7_system"]
    own = {str(v) for v in m.q}
    foreign = sorted(str(v) for v in printed_rows.free_symbols if str(v) not in own)
    x3, y3 = (m.q[m.index(c), 0] for c in ("x3", "y3"))
    x4, y4 = sp.symbols("x4 y4", real=True)
    f = sp.lambdify(list(m.q), list(printed_rows.subs({x4: x3, y4: y3})), "numpy")
    err = max(float(np.abs(np.array(f(*q), dtype=float) - m.Phi(q, 0.0)[5:7]).max())
              for q in np.random.default_rng(3).uniform(-2, 2, (20, 9)))
    return Evidence(f"The printed rows hold {', '.join(foreign)}: example 3 has three bodies (coordinates x_1 … φ_3), "
                    f"so they cannot be evaluated. With x_3, y_3 they are kinbook's Φ_6, Φ_7: at 20 random "
                    f"configurations the difference {_below(err)}.", float("inf") if foreign else 0.0, err)


def _ev_ex2_translational():
    from ..planar import A
    from .printed import ex2_translational_general

    m = _ex("ch13_example2")
    rows = []
    for q in np.random.default_rng(2).uniform(-2, 2, (20, 12)):
        r1, A1, r4, A4 = q[0:2], A(q[2]), q[9:11], A(q[11])
        P_i, Q_i = r1, r1 + A1 @ (1.0, 0.0)           # the points the example chooses on body 1
        P_j, Q_j = r4, r4 + A4 @ (1.0, 0.0)           # P_j = B on body 4, Q_j any second point of body 4
        printed_row = ex2_translational_general(P_i, Q_i, P_j, Q_j)
        corrected = ex2_translational_general(P_i, Q_i, P_j, P_i)   # eq. 26: P_j − P_i
        rows.append((printed_row, corrected, m.Phi(q, 0.0)[5]))
    e_p, e_c = _compare(rows)
    return Evidence(f"With P_i = O_1, Q_i = (1, 0) on body 1 (the example's choice) and Q_j = (1, 0) on body 4, the "
                    f"printed row is sin(φ_4 − φ_1), blind to where the slider is: at 20 random configurations it "
                    f"differs from kinbook's Φ_6 by up to {e_p:.3f}; with P_j − P_i (eq. 26) it {agrees(e_c)}.",
                    e_p, e_c)


def _ev_ex2_l3():
    m = _ex("ch13_example2")
    rod = next(b for b in m.bodies if b.name == "rod")
    length = float(np.linalg.norm(np.subtract(rod.points["B"], rod.points["A"]).astype(float)))
    return Evidence(f"“b/6” is no length (b is defined nowhere); the local coordinates printed next, ξ_3^A = −3 and "
                    f"ξ_3^B = 3, put A and B 6 apart, as kinbook's example-2 rod does (|AB| = {length:g}).",
                    float("inf"), abs(length - 6.0))


def _ev_ex5_joint3_working():
    from .printed import EX1, EX5

    q = EX5["q"]
    A_, B_ = EX1["A"], EX1["B"]
    x2, y2, x3, y3 = q[3], q[4], q[6], q[7]
    as_labelled = np.array([A_[0] - B_[0], A_[1] - B_[1], 0.0, 0.0])   # x^A − x^B, y^A − y^B, x_j^p − x_j^p (= 0) …
    corrected = np.array([A_[0] - x2, A_[1] - y2, B_[0] - x3, B_[1] - y3])
    values = EX5["rr_arms"]
    e_p, e_c = float(np.abs(as_labelled - values).max()), float(np.abs(corrected - values).max())
    return Evidence(f"At the book's own points A = ({A_[0]}, {A_[1]}), B = ({B_[0]}, {B_[1]}) and x_2 = {x2}, "
                    f"x_3 = {x3}: the printed labels (x^A − x^B, y^A − y^B, and x_j^p − x_j^p, which is 0) differ from "
                    f"the numbers written after them by up to {e_p:.4f}; the lever arms x^A − x_2, y^A − y_2, "
                    f"x^B − x_3, y^B − y_3 give those numbers to their printed digits ({small(e_c, 2e-4, relation=True)}).",
                    e_p, e_c, tolerance=2e-4)


def _printed_vs_kinbook(kind, quantity, printed_matrix, corrected_matrix, entry, equal=(), up_to_sign=True):
    """(printed error, corrected error) of the entry (r, c) — or the largest over a list of entries — of a printed
    table (kinbook.book.printed), against kinbook's derivation for the two-body joint ``kind`` at 20 random states
    (with ``up_to_sign``, a printed row × −1 counts as the same row: Φ = 0 and −Φ = 0 are one constraint)."""
    from . import notation, verify

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
    from .printed import TABLE_13_1_TEXT, TABLES

    e_p, e_c = _printed_vs_kinbook("r", "Phi_q", TABLE_13_1_TEXT, TABLES["13.1"][1], [(0, 2), (0, 5), (1, 2), (1, 5)])
    return Evidence(f"The four printed derivatives ∂Φ/∂φ_i, ∂Φ/∂φ_j at 20 random configurations: off by up to "
                    f"{e_p:.3f}; with the body origins (x_i, y_i, x_j, y_j), as Table 13.1 prints them, they "
                    f"{agrees(e_c)}.", e_p, e_c)


def _ev_eq25():
    from .notation import S
    from .printed import EQ

    corrected = EQ["26"]
    printed_eq = corrected.subs({S.xQ_i: S.x_i, S.yQ_i: S.y_i})   # the second guide point read as the origin O_i
    e_p, e_c = _printed_vs_kinbook("t", "Phi", printed_eq, corrected, (0, 0))
    return Evidence(f"Eq. 26 with O read as the body origin O_i: at 20 random configurations (guide line not through "
                    f"O_i) its first row differs from kinbook's by up to {e_p:.3f}; with the guide point Q_i it "
                    f"{agrees(e_c)}.", e_p, e_c)


def _ev_gamma_sign():
    from .printed import REVOLUTE_STEPS

    P = REVOLUTE_STEPS["(Phi_q qd)_q qd"]
    e_p, e_c = _printed_vs_kinbook("r", "gamma", P, -P, [(0, 0), (1, 0)], up_to_sign=False)
    return Evidence(f"For the revolute joint, γ = (Φ_q q̇)_q q̇ with the section's own (Φ_q q̇)_q q̇ differs from "
                    f"kinbook's γ by up to {e_p:.2f} at 20 random states; γ = −(Φ_q q̇)_q q̇ (Φ_t = 0 here) "
                    f"{agrees(e_c)}.", e_p, e_c)


def _ev_velocity_rhs():
    m = _ex("ch13_example3")
    q = m.solve_position(0.0)
    h = 1e-6
    phi_t = (m.Phi(q, h) - m.Phi(q, -h)) / (2 * h)     # Φ_t: only the driver's row depends on t
    nu = m.nu(q, 0.0)
    e_p, e_c = float(np.abs(phi_t - nu).max()), float(np.abs(-phi_t - nu).max())
    return Evidence(f"Example 3's driver φ_2 − 3π/4 − 100t has Φ_t = {phi_t[-1]:.4g}: the printed right-hand side "
                    f"[0; Φ_t] gives ν_9 = {phi_t[-1]:.4g}, kinbook's ν_9 = {nu[-1]:.4g} (example 5 itself uses "
                    f"100); [0; −Φ_t] {agrees(e_c, 1e-6)}.", e_p, e_c, tolerance=1e-6)


def _ev_table_13_2():
    from .notation import S
    from .printed import TABLES

    P = TABLES["13.2"][1]
    fixed = (S.xP_j - S.x_j) * (S.xP_i - S.xQ_i) + (S.yP_j - S.y_j) * (S.yP_i - S.yQ_i)
    e_p, e_c = _printed_vs_kinbook("t", "Phi_q", P, _with_entry(P, (0, 5), fixed), (0, 5))
    return Evidence(f"∂Φ_1/∂φ_j at 20 random configurations: the printed entry is off by up to {e_p:.3f}; with "
                    f"x_j, y_j it {agrees(e_c)}.", e_p, e_c)


def _ev_table_13_3():
    from .notation import S
    from .printed import TABLES

    P = TABLES["13.3"][1]
    dx, dy = S.xP_i - S.xP_j, S.yP_i - S.yP_j
    fixed = _with_entry(P, (0, 2), -2 * dx * (S.yP_i - S.y_i) + 2 * dy * (S.xP_i - S.x_i))
    fixed[0, 5] = 2 * dx * (S.yP_j - S.y_j) - 2 * dy * (S.xP_j - S.x_j)
    e_p, e_c = _printed_vs_kinbook("rr", "Phi_q", P, fixed, [(0, 2), (0, 5)])
    return Evidence(f"Both printed entries, ∂Φ/∂φ_i and ∂Φ/∂φ_j, reduce to 0; kinbook's entries reach {e_p:.3f} at 20 "
                    f"random configurations; the corrected entries {agrees(e_c)}.", e_p, e_c)


def _ev_table_13_4():
    from .notation import S
    from .printed import TABLES

    P = TABLES["13.4"][1]
    fixed = (S.yP_i - S.y_j) * (S.yP_j - S.yQ_j) + (S.xP_i - S.x_j) * (S.xP_j - S.xQ_j)
    e_p, e_c = _printed_vs_kinbook("rt", "Phi_q", P, _with_entry(P, (0, 5), fixed), (0, 5))
    return Evidence(f"∂Φ/∂φ_j of the r-t joint at 20 random configurations: printed entry off by up to {e_p:.3f}; "
                    f"with x_j, y_j it {agrees(e_c)}.", e_p, e_c)


def _ev_gamma_rr():
    from .notation import S
    from .printed import TABLE_13_5_GAMMA

    P = TABLE_13_5_GAMMA["rr"]
    fixed = P + sp.Matrix([2 * (S.yd_i - S.yd_j) - 2 * (S.yd_i - S.yd_j) ** 2])
    e_p, e_c = _printed_vs_kinbook("rr", "gamma", P, fixed, (0, 0))
    return Evidence(f"γ of the r-r joint at 20 random states: printed entry off by up to {e_p:.2f}; with "
                    f"(ẏ_i − ẏ_j)² it {agrees(e_c)}.", e_p, e_c)


def _ev_gamma_t():
    from .notation import S
    from .printed import TABLE_13_5_GAMMA

    P = TABLE_13_5_GAMMA["t"]
    sx, sy = S.xP_i - S.xQ_i, S.yP_i - S.yQ_i
    velocity_term = 2 * (sx * (S.xd_i - S.xd_j) + sy * (S.yd_i - S.yd_j)) * S.w_i
    fixed = _with_entry(P, (0, 0), P[0, 0] - 2 * velocity_term)
    e_p, e_c = _printed_vs_kinbook("t", "gamma", P, fixed, (0, 0), equal=[(S.w_i, S.w_j)])
    return Evidence(f"γ_1 of the translational joint at 20 random states with φ̇_j = φ̇_i: printed entry off by up "
                    f"to {e_p:.2f}; with −2[…]φ̇_i it {agrees(e_c)}.", e_p, e_c)


def _ev_revolute_steps():
    from .notation import S
    from .printed import REVOLUTE_STEPS

    P = REVOLUTE_STEPS["Phi_q qd"]
    fixed = _with_entry(P, (1, 0), S.yd_i + (S.xP_i - S.x_i) * S.w_i - S.yd_j - (S.xP_j - S.x_j) * S.w_j)
    from . import notation, verify

    m = notation.pair("r")
    derived = m.symbolic().Phi_q * m.qd
    e_p = float(verify.compare(P, derived, m).errors[1, 0])
    e_c = float(verify.compare(fixed, derived, m).errors[1, 0])
    return Evidence(f"Row 2 of Φ_q q̇ for the revolute joint at 20 random states: the printed row is off by up to "
                    f"{e_p:.2f}; ẏ_i + (x_i^P − x_i)φ̇_i − ẏ_j − (x_j^P − x_j)φ̇_j {agrees(e_c)}.", e_p, e_c)


def _ev_ex5_velocity():
    m = _ex("ch13_example3")
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    vB = m.point_velocity(q, qd, "rocker", "B")
    printed = np.array([-190.7802, 117.1410])
    return Evidence(
        f"kinbook: q̇_3 = ({qd[6]:.2f}, {qd[7]:.2f}, {qd[8]:.2f}), v_B = ({vB[0]:.2f}, {vB[1]:.2f}), "
        f"|v_B| = {np.linalg.norm(vB):.2f}; the printed v_B = (−190.78, 117.14) is off by "
        f"{np.linalg.norm(printed - vB):.2f} because it is computed at the unassembled printed configuration.",
        float(np.linalg.norm(printed - vB)), 0.0)


def _ev_ex6_acceleration():
    m = _ex("ch13_example3")
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    qdd = m.solve_acceleration(q, qd, 0.0)
    aB = m.point_acceleration(q, qd, qdd, "rocker", "B")
    printed = np.array([4084.136, -22111.679])
    g = m.gamma(q, qd, 0.0)
    return Evidence(
        f"kinbook: γ_6..γ_8 = ({g[5]:.2f}, {g[6]:.2f}, {g[7]:.2f}), q̈_3 = ({qdd[6]:.2f}, {qdd[7]:.2f}, "
        f"{qdd[8]:.2f}), a_B = ({aB[0]:.2f}, {aB[1]:.2f}), |a_B| = {np.linalg.norm(aB):.2f}; the printed a_B "
        f"is off by {np.linalg.norm(printed - aB):.1f}.", float(np.linalg.norm(printed - aB)), 0.0)


# ------------------------------------------------------------------------------------ chapter 14 evidence
def _unit_ps(count=20, seed=14):
    from ..spatial import random_p

    return random_p(count, rng=seed)


def _ev_elementary_rotation():
    from ..spatial import A_from_euler

    rows = []
    for psi in np.linspace(0.1, 3.0, 12):
        c, s_ = np.cos(psi), np.sin(psi)
        printed = np.array([[c, s_, 0], [s_, c, 0], [0, 0, 1]])
        corrected = np.array([[c, s_, 0], [-s_, c, 0], [0, 0, 1]])
        reference = A_from_euler(psi, 0, 0).T  # the book's passive A^ψ
        rows.append((np.abs(printed - reference).max(), np.abs(corrected - reference).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"The printed A^ψ has det = cos 2ψ (0.5 at ψ = 30°), so it is no rotation; it differs from the "
                    f"transpose of kinbook's A(ψ, 0, 0) by up to {e_p:.3f}; with −sin ψ in row 2 it "
                    f"{agrees(e_c)}.", e_p, e_c)


def _ev_a21_row3():
    from ..spatial import A_from_euler

    rng = np.random.default_rng(2)
    rows = []
    for psi, th, ph in rng.uniform(-3, 3, (20, 3)):
        ref = A_from_euler(psi, th, ph).T[2]
        printed = np.array([np.sin(psi) * np.sin(ph), -np.cos(psi) * np.sin(ph), np.cos(th)])
        corrected = np.array([np.sin(psi) * np.sin(th), -np.cos(psi) * np.sin(th), np.cos(th)])
        rows.append((np.abs(printed - ref).max(), np.abs(corrected - ref).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"Row 3 of the product A^φ A^θ A^ψ (the transpose of kinbook's A_from_euler) at 20 random "
                    f"angles: the printed row is off by up to {e_p:.3f}; with sin θ for sin φ it {agrees(e_c)}.",
                    e_p, e_c)


def _ev_A_of_p():
    from ..spatial import A_from_p

    rows = []
    for p in _unit_ps():
        e0, e1, e2, e3 = p
        printed = book_A_of_p(p)
        corrected = 2 * printed
        corrected[0, 2] += 4 * e0 * e2
        corrected[1, 0] += 4 * e0 * e3
        corrected[2, 1] += 4 * e0 * e1
        ref = A_from_p(p)
        rows.append((np.abs(printed - ref).max(), np.abs(corrected - ref).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random unit p the printed matrix differs from A(p) by up to {e_p:.3f} (it is symmetric, "
                    f"so it cannot be a rotation in general); twice it, with + e0 terms at a13, a21, a32, "
                    f"{agrees(e_c)}.", e_p, e_c)


def _ev_G_row2():
    from ..spatial import G

    rows = []
    for p in _unit_ps():
        e0, e1, e2, e3 = p
        printed = G(p).copy()
        printed[1] = [-e2, e3, e0, e1]
        rows.append((np.abs(printed @ p).max(), np.abs(G(p) @ p).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"With the printed row 2, G p = [0, 2 e1 e3, 0] reaches {e_p:.3f} at random unit p instead of "
                    f"0; kinbook's G gives |G p| {_below(e_c)}.", e_p, e_c)


def _matrices_vs(reference, samples):
    """(printed error, corrected error): ``reference(sample)`` returns (printed, corrected, kinbook's) arrays."""
    rows = []
    for sample in samples:
        printed, corrected, ref = reference(*sample)
        rows.append((np.abs(printed - ref).max(), np.abs(corrected - ref).max(), 0.0))
    return _compare(rows)


def _ev_A_theta_second():
    from ..spatial import A_from_euler

    def matrices(psi, th):
        c, s = np.cos(th), np.sin(th)
        return (np.array([[1, 0, 0], [0, np.cos(psi), -s], [0, s, c]]), np.array([[1, 0, 0], [0, c, s], [0, -s, c]]),
                A_from_euler(0.0, th, 0.0).T)  # the nutation alone, passive like the printed A^ψ and A^φ

    e_p, e_c = _matrices_vs(matrices, np.random.default_rng(21).uniform(-3, 3, (20, 2)))
    return Evidence(f"At 20 random (ψ, θ) the printed A^θ differs from the passive nutation matrix (the transpose of "
                    f"kinbook's A(0, θ, 0), as the printed A^ψ and A^φ are passive) by up to {e_p:.3f} — it is no "
                    f"rotation (det = cψ cθ + sθ²); with cos θ in row 2 and + sin θ above the diagonal it "
                    f"{agrees(e_c)}.", e_p, e_c)


def _ev_omega_matrix():
    from ..spatial import omega_from_euler_rates

    printed = sp.Matrix(3, 4, sp.symbols("m0:12"))
    try:  # as printed: a 3×4 array times the three rates
        printed * sp.Matrix(sp.symbols("r0:3"))
        shape_error = 0.0
    except sp.ShapeError:
        shape_error = float("inf")
    rows = []
    for (psi, th, ph), rates in zip(np.random.default_rng(24).uniform(-3, 3, (20, 3)),
                                     np.random.default_rng(25).uniform(-2, 2, (20, 3))):
        sth, cth, sph, cph = np.sin(th), np.cos(th), np.sin(ph), np.cos(ph)
        M = np.array([[sth * sph, cph, 0], [sth * cph, -sph, 0], [cth, 0, 1]])
        rows.append(float(np.abs(M @ rates - omega_from_euler_rates((psi, th, ph), rates, frame="body")).max()))
    e_c = max(rows)
    return Evidence(f"As printed, a 3×4 array multiplies the three rates (ψ̇, θ̇, φ̇): the product is not defined "
                    f"(sympy raises ShapeError). The 3×3 matrix with sθ sφ and sθ cφ in column 1 gives kinbook's ω' "
                    f"(omega_from_euler_rates, frame='body') at 20 random angles and rates: the difference "
                    f"{_below(e_c)}.", shape_error, e_c)


def _ev_rates_inverse_first():
    from ..spatial import euler_rates_from_omega

    rows = []
    for (psi, th, ph), w in zip(np.random.default_rng(26).uniform(0.2, 2.9, (20, 3)),
                                np.random.default_rng(27).uniform(-2, 2, (20, 3))):
        sth, cth, sph, cph = np.sin(th), np.cos(th), np.sin(ph), np.cos(ph)
        top, bottom = [sph / sth, cph / sth, 0], [-sph * cth / sth, -cph * cth / sth, 1]
        printed = np.array([top, [cph, sph, 0], bottom])
        corrected = np.array([top, [cph, -sph, 0], bottom])
        ref = euler_rates_from_omega((psi, th, ph), w, frame="body")
        rows.append((np.abs(printed @ w - ref).max(), np.abs(corrected @ w - ref).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random angles (sin θ ≠ 0) and body angular velocities ω', the first printed inverse gives "
                    f"rates off by up to {e_p:.3f} from kinbook's euler_rates_from_omega(frame='body'); with −sin φ in "
                    f"row 2 (as the second version prints it) it {agrees(e_c)}.", e_p, e_c)


def _ev_A21_row2_first():
    from ..spatial import A_from_euler

    def rows(psi, th, ph):
        cps, sps, cth, sth, cph, sph = np.cos(psi), np.sin(psi), np.cos(th), np.sin(th), np.cos(ph), np.sin(ph)
        return (np.array([cps * sph - sps * cth * cph, sps * sph + cps * cth * cph, sth * cph]),
                np.array([-cps * sph - sps * cth * cph, -sps * sph + cps * cth * cph, sth * cph]),
                A_from_euler(psi, th, ph).T[1])

    e_p, e_c = _matrices_vs(rows, np.random.default_rng(22).uniform(-3, 3, (20, 3)))
    return Evidence(f"Row 2 of A^φ A^θ A^ψ at 20 random angles: the first printed version is off by up to {e_p:.3f}; "
                    f"with −cψ sφ and −sψ sφ (as the second version prints it) it {agrees(e_c)}.", e_p, e_c)


def _ev_p_from_A_recipe():
    from ..spatial import A_from_p

    rows = []
    for p in _unit_ps(seed=31):
        A = A_from_p(p)
        t = np.trace(A)
        squares = np.array([(t + 1) / 4, *((1 + 2 * np.diag(A) - t) / 4)])
        rows.append(float(np.abs(squares - p**2).max()))
    e_c = max(rows)
    return Evidence(f"e_0² = (p + 1)/4 has a p defined nowhere, and t = 2(3e_0² + e_1² + e_2² + e_3²) − 3 needs the "
                    f"parameters being sought: as printed the recipe cannot be evaluated from A. With t = tr A, the four "
                    f"squares match those of the Euler parameters of 20 random rotations (the difference "
                    f"{_below(e_c)}).", float("inf"), e_c)


def _ev_A_ddot_a():
    from ..spatial import A_ddot, E, G, a_bar

    rows = []
    rng = np.random.default_rng(32)
    for p, a in zip(_unit_ps(seed=32), rng.uniform(-1, 1, (20, 3))):
        pd = rng.normal(size=4)
        pd -= p * (p @ pd)                           # on a motion: pᵀṗ = 0 ...
        pdd = rng.normal(size=4)
        pdd -= p * (p @ pdd + pd @ pd)               # ... and pᵀp̈ = −ṗᵀṗ
        EGt = 2 * E(pd, check=False) @ G(pd, check=False).T @ a
        ref = A_ddot(p, pd, pdd) @ a
        rows.append((np.abs(EGt - ref).max(), np.abs(EGt + 2 * E(p) @ a_bar(a) @ pdd - ref).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random states of a motion (unit p, pᵀṗ = 0, pᵀp̈ = −ṗᵀṗ) and vectors a: with ä = 0 (a is "
                    f"constant) the printed right-hand side is 2ĖĠᵀa, off from kinbook's Ä a by up to {e_p:.3f}; "
                    f"2ĖĠᵀa + 2Eā p̈ {agrees(e_c)}.", e_p, e_c)


def _ev_a_bar_explicit():
    from ..spatial import G, a_bar

    rows = []
    for p, a in zip(_unit_ps(seed=23), np.random.default_rng(23).uniform(-1, 1, (20, 3))):
        a1, a2, a3 = a
        printed = np.array([[0, -a1, -a2, -a3], [a1, 0, -a3, a2], [a2, a3, 0, -a1], [a3, -a2, a1, 0]])
        rows.append((np.abs(printed @ p - G(p).T @ a).max(), np.abs(a_bar(a) @ p - G(p).T @ a).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"ā p against Gᵀa at 20 random unit p and vectors a: the printed element-by-element ā is off by up "
                    f"to {e_p:.3f}; the block form [0, −aᵀ; a, −ã] {agrees(e_c)}.", e_p, e_c)


# ----------------------------------------------------------------------------------------------- the list
ERRATA = [
    Erratum("13.5-eq4-text", "§13.5, text after eq. 4", r"[x, y]_i \text{: coordinates of O in local axes}",
            r"[x, y]_i \text{: global coordinates of } O_i", "wording"),
    Erratum("13.5-q-elements", "§13.5, the sentence after q = [q_1ᵀ, q_2ᵀ, …, q_Nᵀ]ᵀ",
            r"q_1, q_2, \dots, q_n \text{ correspond to the elements } 1, 2, \dots, n",
            r"\mathbf q_1, \dots, \mathbf q_N \text{ belong to the } N \text{ bodies; } n = 3N \text{ (plane) or } 6N "
            r"\text{ (space) counts coordinates}", "wording"),
    Erratum("13.5-ex1-solution", "§13.5, example 1: solution at t = 0 and the points A, B",
            r"x_3 = 1.5777,\ y_3 = 1.9854,\ \varphi_3 = 10.81°,\ x_4 = 3.7849,\ y_4 = 1.2783,\ \varphi_4 = 238.45°,\ B = (4.5697, 2.5566)",
            r"\varphi_3 = 11.58°,\ \varphi_4 = 240.80°,\ B = (4.4636, 2.6187)", "number", _ev_ex1_solution,
            "Examples 3, 5 and 6 reuse this configuration, so their numbers inherit the error."),
    Erratum("13.5-ex1-eq-ref", "§13.5, example 1, joint 2", r"\text{“puede emplearse la expresión general (1)”}",
            r"\text{the general expression, eq. 17 (in the scalar form of eq. 34)}", "wording", None,
            "There is no eq. 1 in the section: joint 1 just used eq. 17 and its scalar form, eq. 34."),
    Erratum("13.5-ex3-x2", "§13.5, example 3 (and example 5): solution at t = 0", r"x_2 = 0.7071",
            r"x_2 = -0.7071", "sign", _ev_ex3_x2, "Example 1 prints −0.7071 (x_2 = −cos 45°: the crank's middle is "
            "left of O_A), and so do example 5's Jacobian and example 6."),
    Erratum("13.5-ex3-system", "§13.5, example 3: the assembled system, Φ_6 and Φ_7",
            r"\ldots - x_4 - 1.5\cos\varphi_3,\ \ldots - y_4 - 1.5\sin\varphi_3",
            r"\ldots - x_3 - 1.5\cos\varphi_3,\ \ldots - y_3 - 1.5\sin\varphi_3", "formula", _ev_ex3_system,
            "Example 3 has three bodies; there is no x_4 (the joint-2 section itself prints x_3, y_3)."),
    Erratum("13.5-ex4-phi8-substituted", "§13.5, example 4, joint 3: the general row with the points substituted",
            r"(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)(y_1 - y_1 - \sin\varphi_1) - "
            r"(y_3 + 3\sin\varphi_3 - y_1\sin\varphi_1)(x_1 - x_1 - \cos\varphi_1)",
            r"(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)(y_1 - y_1 - \sin\varphi_1) - "
            r"(y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)(x_1 - x_1 - \cos\varphi_1)",
            "formula", _ev_ex4_phi8_substituted, "y_i^P − y_j^Q = y_3 + 3 sin φ_3 − (y_1 + sin φ_1): a minus sign is "
            "missing, which makes y_1 sin φ_1 a product."),
    Erratum("13.5-ex4-phi8", "§13.5, example 4, joint 3: Φ_8 simplified",
            r"(x_3 + 3\cos\varphi_3 - x_1\cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            r"-(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            "formula", _ev_ex4_phi8, "Two slips: x_1 cos φ_1 for x_1 + cos φ_1 ... − cos φ_1, and the sign of the first "
            "product (the substituted row gives −(…) sin φ_1)."),
    Erratum("13.5-ex4-phi8-system", "§13.5, example 4: Φ_8 in the assembled system",
            r"(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1\sin\varphi_1)\cos\varphi_1",
            r"-(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            "formula", _ev_ex4_phi8_system, "The system repeats neither the simplified row nor its slips: here the x part "
            "is right but its sign is not, and the y part has the substituted row's y_1 sin φ_1."),
    Erratum("13.5-ex2-translational", "§13.5, example 2, joint 2: the general translational row",
            r"(x_i^P - x_i^Q)(y_j^P - y_j^Q) - (y_i^P - y_i^Q)(x_j^P - x_j^Q)",
            r"(x_i^P - x_i^Q)(y_j^P - y_i^P) - (y_i^P - y_i^Q)(x_j^P - x_i^P)\ \text{(eq. 26)}", "formula",
            _ev_ex2_translational, "As printed it asks only that P_jQ_j be parallel to the guide (the second row "
            "already does); eq. 26 asks P_j to lie on the guide line. The example defines no Q_j, and its Φ_6, "
            "substituted just below, is eq. 26's."),
    Erratum("13.5-ex2-l3", "§13.5, example 2: local frame of body 3", r"l_3 = b/6", r"l_3 = 6", "number",
            _ev_ex2_l3),
    Erratum("13.5-ex2-driver", "§13.5, example 2, the driver's parameters", r"\varphi_2 = \frac{\pi}{4} = 45°",
            r"\varphi_2^0 = \frac{\pi}{4} = 45°", "wording", None,
            "The initial value φ_2⁰ (as example 1 writes it), not the coordinate φ_2, which changes with t."),
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
            "The text takes the guide points P_i and Q_i; the formulas call the second one O, the letter the book "
            "reserves for a body's reference point O_i. Read as O_i the equation holds only when O_i happens to lie "
            "on the guide line."),
    Erratum("13.5-eq21", "§13.5, translational joint, text after eq. 21", r"\text{eq. (19) is one of the two equations}",
            r"\text{eq. (21)}", "wording"),
    Erratum("13.5-eq24", "§13.5, translational joint, before eq. 24", r"\text{multiplying the vectors scalarly}",
            r"\text{the vector (cross) product}", "wording"),
    Erratum("13.5-rt-collinearity", "§13.5, Par de Revolución-Traslación, last paragraph",
            r"\text{the translational joint required the collinearity of } s_i \text{ and } s_j",
            r"\text{of } s_i \text{ and } d \text{ (eq. 22)}", "wording"),
    Erratum("13.5-joint-labels", "§13.5, examples 2 and 4: labels and references",
            r"\Phi^{(i,2)},\ \Phi^{(r,1)},\ \text{apartado 4.3 / 4.5},\ \text{“as in example 3”}",
            r"\Phi^{(t,2)},\ \Phi^{(r\text{-}t,1)},\ \text{the translational / r-t subsections of §13.5},\ \text{example 2}",
            "wording"),
    Erratum("13.6-table-13.1-text", "§13.6, the derivation under Table 13.1",
            r"\partial\Phi_1/\partial\varphi_i = -(y_i^P - y_j^P),\ \ldots",
            r"-(y_i^P - y_i),\ (y_j^P - y_j),\ (x_i^P - x_i),\ -(x_j^P - x_j)", "formula", _ev_table_13_1_text,
            "Table 13.1 itself is right; only the worked derivatives below it use the wrong points."),
    Erratum("13.6-table-13.2", "§13.6, Table 13.2 (translational joint), ∂Φ_1/∂φ_j",
            r"(x_j^P - x_i)(x_i^P - x_i^O) + (y_j^P - y_i)(y_i^P - y_i^O)",
            r"(x_j^P - x_j)(x_i^P - x_i^Q) + (y_j^P - y_j)(y_i^P - y_i^Q)", "formula", _ev_table_13_2,
            "Table 13.5 prints this entry correctly."),
    Erratum("13.6-table-13.3", "§13.6, Table 13.3 (revolute–revolute joint), ∂/∂φ_i and ∂/∂φ_j",
            r"\frac{\partial}{\partial\varphi_i}: -2(x_i^P - x_j^P)(y_i^P - y_j^P) + 2(y_i^P - y_j^P)(x_i^P - x_j^P)\ (= 0),"
            r"\quad \frac{\partial}{\partial\varphi_j}: 2(x_i^P - x_j^P)(y_j^P - y_j^P) - 2(y_i^P - y_j^P)(x_j^P - x_j^P)\ (= 0)",
            r"\frac{\partial}{\partial\varphi_i}: -2(x_i^P - x_j^P)(y_i^P - y_i) + 2(y_i^P - y_j^P)(x_i^P - x_i),\quad "
            r"\frac{\partial}{\partial\varphi_j}: 2(x_i^P - x_j^P)(y_j^P - y_j) - 2(y_i^P - y_j^P)(x_j^P - x_j)",
            "formula", _ev_table_13_3,
            "Example 5 repeats the zero entries; Table 13.5 prints them correctly."),
    Erratum("13.6-table-13.4", "§13.6, Tables 13.4 and 13.5 (revolute–translational joint), ∂Φ/∂φ_j",
            r"(y_i^P - y_i)(y_j^P - y_j^Q) + (x_i^P - x_i)(x_j^P - x_j^Q)",
            r"(y_i^P - y_j)(y_j^P - y_j^Q) + (x_i^P - x_j)(x_j^P - x_j^Q)", "formula", _ev_table_13_4),
    Erratum("13.7-ex5-joint3-working", "§13.7, example 5, joint 3 (r-r): the values substituted into the general row",
            r"(x_i^p - x_j^p) = (x^A - x^B) = -1.4142 + 0.7071,\ (y_i^p - y_j^p) = 1.4142 - 0.7071,\ "
            r"(x_j^p - x_j^p) = (x^B - x^3),\ (y_j^p - y_j^p) = (y^B - y^3)",
            r"(x_i^P - x_i) = x^A - x_2 = -1.4142 + 0.7071,\ (y_i^P - y_i) = y^A - y_2,\ (x_j^P - x_j) = x^B - x_3,"
            r"\ (y_j^P - y_j) = y^B - y_3", "formula", _ev_ex5_joint3_working,
            "The first four lines are the lever arms of the corrected Table 13.3 (points relative to the body "
            "origins), labelled as differences of joint points; the numbers that follow (Φ_8's row) were computed "
            "with the right ones."),
    Erratum("13.8-revolute-Phiq-qd", "§13.8, the revolute joint worked step by step: row 2 of Φ_q q̇",
            r"\dot x_j - (x_i^P - x_i)\dot\varphi_i - \dot y_j + (x_j^P - x_j)\dot\varphi_j",
            r"\dot y_i + (x_i^P - x_i)\dot\varphi_i - \dot y_j - (x_j^P - x_j)\dot\varphi_j", "formula",
            _ev_revolute_steps, "Row 2 of Table 13.1 times q̇; the next step, (Φ_q q̇)_q q̇, is printed right."),
    Erratum("13.8-gamma-sign", "§13.8, the revolute-joint walkthrough and example 6",
            r"\gamma = (\Phi_q\dot q)_q\dot q", r"\gamma = -(\Phi_q\dot q)_q\dot q - 2\Phi_{qt}\dot q - \Phi_{tt}",
            "sign", _ev_gamma_sign, "The section first writes the minus sign, then drops it; its final γ rows use the "
            "right sign."),
    Erratum("13.8-table-13.5-rr", "§13.8, Table 13.5, γ of the revolute–revolute joint (and example 6)",
            r"-2(\dot x_i - \dot x_j)^2 - 2(\dot y_i - \dot y_j) - \ldots",
            r"-2(\dot x_i - \dot x_j)^2 - 2(\dot y_i - \dot y_j)^2 - \ldots", "formula", _ev_gamma_rr),
    Erratum("13.8-table-13.5-t", "§13.8, Table 13.5, γ_1 of the translational joint",
            r"2[(x_i^P - x_i^O)(\dot x_i - \dot x_j) + (y_i^P - y_i^O)(\dot y_i - \dot y_j)]\dot\varphi_i - [\ldots]\dot\varphi_i^2",
            r"-2[(x_i^P - x_i^Q)(\dot x_i - \dot x_j) + (y_i^P - y_i^Q)(\dot y_i - \dot y_j)]\dot\varphi_i - [\ldots]\dot\varphi_i^2",
            "sign", _ev_gamma_t, "The printed entry already uses φ̇_j = φ̇_i; its O is the guide point Q_i "
            "(13.5-eq25)."),
    Erratum("13.7-velocity-rhs", "§13.7, example 5: general form of the velocity equations",
            r"\begin{bmatrix}\Phi_q\\ \Phi_q^{(d)}\end{bmatrix}\dot q = \begin{bmatrix}0\\ \Phi_t^{(d)}\end{bmatrix}",
            r"\begin{bmatrix}\Phi_q\\ \Phi_q^{(d)}\end{bmatrix}\dot q = \begin{bmatrix}0\\ -\Phi_t^{(d)}\end{bmatrix}",
            "sign", _ev_velocity_rhs, "The section's own derivation (before example 5) has the minus sign."),
    Erratum("13.7-ex5-velocities", "§13.7, example 5: velocity solution and v_B",
            r"\dot x_2 = \dot y_2 = 70.71,\ \dot x_3 = 95.391,\ v_B = (-190.78, 117.14),\ |v_B| = 223.87",
            r"\dot x_2 = \dot y_2 = -70.71,\ \dot q_3 = (-96.22, 53.78, 73.49),\ v_B = (-192.44, 107.56),\ |v_B| = 220.46",
            "number", _ev_ex5_velocity, "The signs of ẋ_2, ẏ_2, ẋ_3 contradict the book's own equations; the "
            "other differences come from the wrong configuration of example 1/3."),
    Erratum("13.8-ex6-accelerations", "§13.8, example 6: γ, the solution and a_B",
            r"\gamma_6 = 4370.82,\ \gamma_7 = 7118.39,\ \gamma_8 = \pm 1539.6,\ a_B = (4084.1, -22111.7)",
            r"\gamma_6 = 3952.10,\ \gamma_7 = 7071.08,\ \gamma_8 = 396.38,\ a_B = (4582.90, -21121.33)",
            "number", _ev_ex6_acceleration, "γ_8 is printed with both signs; the headings say “velocidad” for "
            "accelerations."),
]


ERRATA += [
    Erratum("14.2-elementary-rotations", "§14.2, the three elementary rotations (first set)",
            r"A^\psi = \begin{bmatrix}\cos\psi & \sin\psi & 0\\ \sin\psi & \cos\psi & 0\\ 0&0&1\end{bmatrix}",
            r"A^\psi = \begin{bmatrix}\cos\psi & \sin\psi & 0\\ -\sin\psi & \cos\psi & 0\\ 0&0&1\end{bmatrix}",
            "sign", _ev_elementary_rotation, "The same slip is in A^θ and A^φ; the book's A^ψ, A^θ, A^φ are passive "
            "(global → local), the transposes of kinbook's active matrices (docs/conventions.md)."),
    Erratum("14.2-A21-row3", "§14.2, the composed matrix A²¹ (both versions), row 3",
            r"[\sin\psi\sin\phi,\ -\cos\psi\sin\phi,\ \cos\theta]",
            r"[\sin\psi\sin\theta,\ -\cos\psi\sin\theta,\ \cos\theta]", "formula", _ev_a21_row3),
    Erratum("14.2-A-theta-second", "§14.2, the second (corrected) set of elementary matrices: A^θ",
            r"A^\theta = \begin{bmatrix}1&0&0\\ 0&\cos\psi&-\operatorname{sen}\theta\\ 0&\operatorname{sen}\theta&\cos\theta\end{bmatrix}",
            r"A^\theta = \begin{bmatrix}1&0&0\\ 0&\cos\theta&\operatorname{sen}\theta\\ 0&-\operatorname{sen}\theta&\cos\theta"
            r"\end{bmatrix}\ \text{(passive, like the printed } A^\psi, A^\phi\text{)}",
            "formula", _ev_A_theta_second, "Two slips: cos ψ stands for cos θ, and the signs of sin θ are those of the "
            "active turn while the printed A^ψ and A^φ are passive; with cos θ restored but those signs kept, the "
            "product A^φ A^θ A^ψ would be the passive matrix of the opposite nutation −θ (notebook 14-2). The second "
            "A²¹ printed just below is the product of the passive matrices."),
    Erratum("14.2-A21-row2-first", "§14.2, the first A²¹ (printed, before the corrected second set), row 2",
            r"[\,c\psi s\phi - s\psi c\theta c\phi,\ s\psi s\phi + c\psi c\theta c\phi,\ s\theta c\phi\,]",
            r"[\,-c\psi s\phi - s\psi c\theta c\phi,\ -s\psi s\phi + c\psi c\theta c\phi,\ s\theta c\phi\,]",
            "sign", _ev_A21_row2_first, "The second version prints this row right. (Only a repeated copy of the "
            "first elementary matrices is struck through in the book; this A²¹ is printed.)"),
    Erratum("14.2-omega-matrix", "§14.2, the matrix relating ω to the angle rates (both versions)",
            r"\begin{bmatrix}s\theta & s\phi & c\phi & 0\\ s\theta & c\phi & -s\phi & 0\\ c\theta & 0 & 1 & 1\end{bmatrix}"
            r"\ \text{(a } 3\times 4 \text{ array; the first version has } +s\phi \text{ in row 2 and } c\theta, 0, 0, 1 "
            r"\text{ in row 3)}",
            r"\omega' = \begin{bmatrix}s\theta s\phi & c\phi & 0\\ s\theta c\phi & -s\phi & 0\\ c\theta & 0 & 1\end{bmatrix}\begin{bmatrix}\dot\psi\\ \dot\theta\\ \dot\phi\end{bmatrix}",
            "formula", _ev_omega_matrix, "sin θ is split from sin φ and cos φ into a column of its own; the first version "
            "also prints +sin φ where −sin φ belongs in row 2, and 0, 0 for 0, 1 in row 3. "
            "kinbook.spatial.omega_from_euler_rates(frame='body') is the corrected relation."),
    Erratum("14.2-rates-inverse-first", "§14.2, the first inverse relation (angle rates from ω'), row 2",
            r"\dot\theta = \cos\phi\,\omega_1 + \operatorname{sen}\phi\,\omega_2",
            r"\dot\theta = \cos\phi\,\omega_1 - \operatorname{sen}\phi\,\omega_2", "sign", _ev_rates_inverse_first,
            "The second version prints it right; kinbook.spatial.euler_rates_from_omega(frame='body')."),
    Erratum("14.3-A-of-p", "§14.3, A in terms of the Euler parameters",
            r"\begin{bmatrix}e_0^2+e_1^2-\tfrac12 & e_1e_2-e_0e_3 & e_1e_3-e_0e_2\\ e_1e_2-e_0e_3 & e_0^2+e_2^2-\tfrac12 & "
            r"e_2e_3-e_0e_1\\ e_1e_3-e_0e_2 & e_2e_3-e_0e_1 & e_0^2+e_3^2-\tfrac12\end{bmatrix}",
            r"2\begin{bmatrix}e_0^2+e_1^2-\tfrac12 & e_1e_2-e_0e_3 & e_1e_3+e_0e_2\\ e_1e_2+e_0e_3 & e_0^2+e_2^2-\tfrac12 & e_2e_3-e_0e_1\\ e_1e_3-e_0e_2 & e_2e_3+e_0e_1 & e_0^2+e_3^2-\tfrac12\end{bmatrix}",
            "formula", _ev_A_of_p, "Two kinds of slip: the factor 2 is missing, and three signs — a13, a21 and a32 "
            "need + e_0 terms (the printed matrix is symmetric, which a rotation is not in general)."),
    Erratum("14.3-p-from-A", "§14.3, Definición…, the Euler parameters from the direction cosines",
            r"t = 2(3e_0^2 + e_1^2 + e_2^2 + e_3^2) - 3,\quad e_0^2 = \frac{p+1}{4}",
            r"t = \operatorname{tr}\mathbf A = a_{11} + a_{22} + a_{33},\quad e_0^2 = \frac{t+1}{4}",
            "formula", _ev_p_from_A_recipe,
            "Two slips in the recipe: e_0² is printed with a p (undefined there) for t, and t is defined through the "
            "parameters being sought; it is the same number as tr A, which is what the recipe must compute from the "
            "known matrix. With e_0 ≠ 0, the condition the book states, its division by 4e_0 is right; kinbook's "
            "p_from_A also covers e_0 = 0 (every half turn) by starting from the largest of e_0², …, e_3²."),
    Erratum("14.3-p-dot", "§14.3, Derivadas…, first lines",
            r"\mathbf p^T\mathbf p = e_0^2 + e_1^2 + e_2^2 + e_3^2 \ \Rightarrow\ \mathbf p^T\dot{\mathbf p} = 0",
            r"\mathbf p^T\mathbf p = 1 \ \Rightarrow\ (\text{differentiating})\ \mathbf p^T\dot{\mathbf p} = 0",
            "wording", None, "The conclusion is stated before the derivative that gives it."),
    Erratum("14.3-A-ddot-a", "§14.3, Derivadas…, the last formula (Ä applied to a vector)",
            r"\ddot A\bar a = 2\dot E\dot G^T a + 2E\ddot a", r"\ddot A a = 2\dot E\dot G^T a + 2E\bar a\,\ddot{\mathbf p}",
            "formula", _ev_A_ddot_a, "The vector on the left is a, not ā, and ä (the second derivative of a constant vector: zero) "
            "stands for ā p̈; the next paragraph's “sea ā un vector arbitrario” means a."),
    Erratum("14.3-a-bar", "§14.3, Derivadas…, ā written element by element",
            r"\bar a = \begin{bmatrix}0&-a_1&-a_2&-a_3\\ a_1&0&-a_3&a_2\\ a_2&a_3&0&-a_1\\ a_3&-a_2&a_1&0\end{bmatrix}",
            r"\bar a = \begin{bmatrix}0&-\mathbf a^T\\ \mathbf a&-\tilde{\mathbf a}\end{bmatrix} = \begin{bmatrix}0&-a_1&-a_2&-a_3\\ "
            r"a_1&0&a_3&-a_2\\ a_2&-a_3&0&a_1\\ a_3&a_2&-a_1&0\end{bmatrix}",
            "sign", _ev_a_bar_explicit, "The block form next to it is printed right (with a stray b̄ for ã); "
            "the element-by-element matrix has +ã in the lower right."),
    Erratum("14.3-G-row2", "§14.3, the matrix G, row 2", r"[-e_2,\ e_3,\ e_0,\ e_1]", r"[-e_2,\ -e_3,\ e_0,\ e_1]",
            "sign", _ev_G_row2),
    Erratum("14.3-euler-theorem", "§14.3, Definición…, the paragraph that introduces the Euler parameters",
            r"\text{“están basados en que el movimiento instantáneo de un sólido con un punto fijo puede definirse por "
            r"medio de una rotación instantánea alrededor de un eje”}",
            r"\text{Euler's theorem: any orientation of a body with a fixed point is reached by one finite rotation, by "
            r"an angle } \alpha \text{ about an axis } \vec u",
            "wording", None, "The Euler parameters describe that finite rotation (e_0 = cos α/2, [e_1, e_2, e_3] = u sin α/2), "
            "as the next paragraphs say — an orientation, not the instantaneous motion. The instantaneous rotation "
            "axis is the direction of ω, which the parameters' rates give (ω' = 2Gṗ)."),
    Erratum("14.3-Ep-Gp", "§14.3, Propiedades…, the identities Ep = Gp = 0",
            r"\frac{Ep}{Gp} = 0,\quad Ep = -e_1e_0 + e_0e_1 - e_3e_2 + e_2e_3 = 0",
            r"\mathbf E\mathbf p = \mathbf 0,\ \mathbf G\mathbf p = \mathbf 0\ (3\text{-vectors; the printed sum is row 1 of } "
            r"\mathbf E\mathbf p)", "wording", None, "A fraction bar stands for “and”, and the check computes one row of "
            "the three as if it were all of Ep."),
]


# ------------------------------------------------------------------------------------------- §14.4 evidence
def _ev_14_4_pair(joint, points, vectors, seed, count=20):
    """A two-body spatial mechanism with one §14.4 constraint ``joint`` (bodies "i", "j") and ``count`` seeded
    random configurations (random r, unit p; not assembled) as (q, r_i, A_i, r_j, A_j)."""
    from ..spatial import A_from_p, Mechanism

    m = Mechanism("§14.4 evidence")
    for b in ("i", "j"):
        m.add_body(b, points=points.get(b), vectors=vectors.get(b))
    m.add(joint)
    rng = np.random.default_rng(seed)
    states = []
    for _ in range(count):
        q = rng.uniform(-2, 2, 14)
        for k in (3, 10):
            q[k : k + 4] /= np.linalg.norm(q[k : k + 4])
        states.append((q, q[:3], A_from_p(q[3:7]), q[7:10], A_from_p(q[10:14])))
    return m, states


def _ev_14_4_n2_primes():
    from ..spatial import Normal2

    s_i, B_i, B_j = np.array([0.3, -0.8, 0.5]), np.array([1.2, 0.4, -0.3]), np.array([-0.6, 0.9, 0.7])
    c = Normal2("i", "j", vector_i=tuple(s_i), point_i="B", point_j="B")
    m, states = _ev_14_4_pair(c, {"i": {"B": B_i}, "j": {"B": B_j}}, {}, 144)
    rows = []
    for q, r_i, A_i, r_j, A_j in states:
        # printed: s_iᵀ A_iᵀ (r_j + A_j s_j^B − r_i − A_i s_i^B), unprimed vectors having global components
        printed = (A_i @ s_i) @ A_i.T @ (r_j + A_j @ (A_j @ B_j) - r_i - A_i @ (A_i @ B_i))
        corrected = s_i @ A_i.T @ (r_j + A_j @ B_j - r_i - A_i @ B_i)
        rows.append((printed, corrected, m.Phi(q)[c.rows][0]))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random configurations the printed Φ^(n2,1), read with global s_i, s_i^B, s_j^B "
                    f"(s = A s'), differs from kinbook's normal-2 row by up to {e_p:.3f}; with the local s'_i, "
                    f"s'_i^B, s'_j^B it {agrees(e_c)}.", e_p, e_c)


def _ev_14_4_p1_transpose():
    from ..spatial import A_from_p, skew

    s_i, s_j = np.array([0.3, -0.8, 0.5]), np.array([-0.6, 0.9, 0.7])
    ps = _unit_ps(40, seed=144)
    rows = []
    for p_i, p_j in zip(ps[:20], ps[20:]):
        A_i, A_j = A_from_p(p_i), A_from_p(p_j)
        reference = skew(A_i @ s_i) @ (A_j @ s_j)  # s̃_i s_j in global components
        printed = A_i @ skew(s_i).T @ A_i.T @ A_j @ s_j  # primes restored, the transpose kept
        corrected = A_i @ skew(s_i) @ A_i.T @ A_j @ s_j
        rows.append((np.abs(printed - reference).max(), np.abs(corrected - reference).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random pairs of orientations A_i s̃'_iᵀ A_iᵀ A_j s'_j differs from s̃_i s_j by up to "
                    f"{e_p:.3f} (it equals −s̃_i s_j, because s̃ᵀ = −s̃); A_i s̃'_i A_iᵀ A_j s'_j {agrees(e_c)}.",
                    e_p, e_c)


def _ev_14_4_p1_two_rows():
    from ..spatial import Parallel1, p_from_axis_angle, skew

    c = Parallel1("i", "j", vector_i=(1, 0, 0), vector_j=(1, 0, 0))
    m, _ = _ev_14_4_pair(c, {}, {}, 0, count=0)
    rows = []
    for angle in np.radians(np.arange(10, 171, 20)):  # s_i along X, s_j turned in the XY plane: not parallel
        q = np.r_[0, 0, 0, 1, 0, 0, 0, 1, 0, 0, p_from_axis_angle([0, 0, 1], angle)]
        s_i, s_j = m.A(q, "i")[:, 0], m.A(q, "j")[:, 0]
        cross = np.linalg.norm(skew(s_i) @ s_j)
        printed = np.linalg.norm((skew(s_i) @ s_j)[:2])  # "the third row is a combination of the first two"
        corrected = np.linalg.norm(m.Phi(q)[c.rows])  # kinbook's h_1ᵀ s_j, h_2ᵀ s_j
        rows.append((printed, corrected, cross))
    e_p, e_c = _compare(rows)
    return Evidence(f"With s_i along X and s_j turned 10°…170° about Z, rows 1-2 of s̃_i s_j are both 0 although "
                    f"|s_i × s_j| reaches {e_p:.3f}: they miss the whole misalignment. The norm of kinbook's two rows "
                    f"h_1ᵀ s_j, h_2ᵀ s_j equals |s_i × s_j|: it {agrees(e_c)}.", e_p, e_c)


def _ev_14_4_universal_primes():
    from ..spatial import Universal

    P_i, P_j = np.array([1.5, -0.2, 0.4]), np.array([-0.7, 0.3, 1.1])
    c = Universal("i", "j", vector_i=(0, 1, 0), vector_j=(1, 0, 0), point="P")
    m, states = _ev_14_4_pair(c, {"i": {"P": P_i}, "j": {"P": P_j}}, {}, 146)
    rows = []
    for q, r_i, A_i, r_j, A_j in states:
        reference = m.Phi(q)[c.rows][:3]
        printed = r_i + A_i @ (A_i @ P_i) - A_j @ (A_j @ P_j) - r_j  # s_i^P, s_j^P global: s^P = A s'^P
        corrected = r_i + A_i @ P_i - A_j @ P_j - r_j
        rows.append((np.abs(printed - reference).max(), np.abs(corrected - reference).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random configurations the printed Φ^(s,3) of the universal joint, read with global "
                    f"s_i^P, s_j^P as the spherical-joint section defines them, differs from kinbook's first three "
                    f"rows by up to {e_p:.3f}; with s'^P_i, s'^P_j it {agrees(e_c)}.", e_p, e_c)


def _ev_14_4_revolute_tilde():
    import sympy as sp

    from ..spatial import A_from_p, Revolute, p_from_A, p_from_axis_angle, skew

    s_i, s_j, P_i, P_j = (0, 0, 1), (0, 0, 1), np.array([1.0, 0.0, 0.5]), np.array([0.0, 0.0, -0.4])
    c = Revolute("i", "j", point="P", axis_i=s_i, axis_j=s_j)
    m, _ = _ev_14_4_pair(c, {"i": {"P": P_i}, "j": {"P": P_j}}, {}, 0, count=0)
    # an assembled joint: body j turned 0.9 rad about body i's axis, its P on body i's P
    p_i = p_from_axis_angle([1, 2, -1], 0.7)
    A_i = A_from_p(p_i)
    A_j = A_i @ A_from_p(p_from_axis_angle(s_i, 0.9))
    r_i = np.array([0.3, -0.2, 0.5])
    r_j = r_i + A_i @ P_i - A_j @ P_j
    q = np.r_[r_i, p_i, r_j, p_from_A(A_j)]
    joint = float(np.abs(m.Phi(q)[c.rows]).max())
    try:  # as printed: A_i s'_i A_iᵀ A_j s'_j, a 3×1 column times a 3×3 matrix
        sp.Matrix(A_i) * sp.Matrix(s_i) * sp.Matrix(A_i.T) * sp.Matrix(A_j) * sp.Matrix(s_j)
        printed = 0.0
    except sp.ShapeError:
        printed = np.inf
    corrected = float(np.abs(A_i @ skew(s_i) @ A_i.T @ A_j @ np.array(s_j, float)).max())
    return Evidence(f"As printed, A_i s'_i A_iᵀ A_j s'_j multiplies a 3×1 column by a 3×3 matrix: it is not defined "
                    f"(sympy raises ShapeError). At an assembled revolute joint (kinbook's five rows: max |Φ| "
                    f"{_below(joint)}), the form with the tilde, A_i s̃'_i A_iᵀ A_j s'_j, has max |·| {_below(corrected)}.",
                    printed, max(corrected, joint))


# §14.4, constraints between two bodies (chapters/14-4-spatial-constraints.ipynb)
ERRATA += [
    Erratum("14.4-n2-primes", "§14.4, Vectores perpendiculares: Φ^(n2,1) in local components",
            r"\Phi^{(n2,1)} = s_i^T A_i^T (r_j + A_j s_j^B - r_i - A_i s_i^B)",
            r"\Phi^{(n2,1)} = s_i'^T A_i^T (r_j + A_j s_j'^B - r_i - A_i s_i'^B)",
            "formula", _ev_14_4_n2_primes, "The primes of the three local vectors are missing; the n1 formula just "
            "above (s_i'^T A_i^T A_j s_j') has them."),
    Erratum("14.4-p1-local-form", "§14.4, Vectores paralelos: Φ^(p1,2) in local components",
            r"\tilde s_i s_j = A_i \tilde s_i^T A_i^T A_j s_j^B",
            r"\tilde s_i s_j = A_i \tilde s_i' A_i^T A_j s_j'", "formula", _ev_14_4_p1_transpose,
            "The tilde is transposed (s̃ᵀ = −s̃), the primes are missing and a stray superscript B appears. Set to "
            "zero, −s̃_i s_j = 0 is the same constraint, but the identity is wrong. Φ^(p2,2) below is printed right."),
    Erratum("14.4-p1-two-rows", "§14.4, Vectores paralelos: which two rows of s̃_i s_j = 0",
            r"\text{the third row is a linear combination of the first two}",
            r"s_{ix}(\tilde s_i s_j)_1 + s_{iy}(\tilde s_i s_j)_2 + s_{iz}(\tilde s_i s_j)_3 = 0:\ "
            r"\text{row 3 follows from rows 1-2 only if } s_{iz} \neq 0",
            "formula", _ev_14_4_p1_two_rows, "Which row is redundant depends on the orientation of s_i, and it changes "
            "as the mechanism moves. kinbook writes p1 and p2 as h_1ᵀs_j = h_2ᵀs_j = 0 with h_1, h_2 ⊥ s'_i fixed in "
            "body i (docs/conventions.md), two rows that stay independent in every orientation."),
    Erratum("14.4-universal-primes", "§14.4, Junta universal: Φ^(s,3)",
            r"r_i + A_i s_i^P - A_j s_j^P - r_j", r"r_i + A_i s_i'^P - A_j s_j'^P - r_j",
            "formula", _ev_14_4_universal_primes, "The spherical-joint section just before prints it with the primes."),
    Erratum("14.4-revolute-tilde", "§14.4, Junta de revolución: Φ^(p1,2) in local components",
            r"A_i s_i' A_i^T A_j s_j' = 0", r"A_i \tilde s_i' A_i^T A_j s_j' = 0",
            "formula", _ev_14_4_revolute_tilde, "Without the tilde the product is undefined (3×1 times 3×3)."),
]

# ------------------------------------------------------------------------------------------- §14.5 evidence


def _ev_14_5_n1_states(seed, tangent):
    """A pair of free bodies with one normal-1 constraint (random local vectors a_i, a_j) and 20 random states
    (q with unit p, q̇, q̈), each with the book's quantities. ``tangent``: ṗ ⊥ p and pᵀp̈ = −ṗᵀṗ, as on a
    motion."""
    from ..spatial import Mechanism, Normal1

    rng = np.random.default_rng(seed)
    a_i, a_j = rng.uniform(-1, 1, 3).round(3), rng.uniform(-1, 1, 3).round(3)
    m = Mechanism("n1 pair")
    m.add_body("i")
    m.add_body("j")
    m.add(Normal1("i", "j", vector_i=tuple(a_i), vector_j=tuple(a_j)))
    row = m.constraint("1").rows.start
    out = []
    for _ in range(20):
        q, qd, qdd = rng.uniform(-2, 2, (3, 14))
        for k in (3, 10):
            q[k : k + 4] /= np.linalg.norm(q[k : k + 4])
            if tangent:
                p = q[k : k + 4]
                qd[k : k + 4] -= p * (p @ qd[k : k + 4])
                qdd[k : k + 4] -= p * (p @ qdd[k : k + 4] + qd[k : k + 4] @ qd[k : k + 4])
        ev = m.evaluate(q, 0.0, qd)
        b = {"phi_dd": ev["Phi_q"][row] @ qdd - ev["gamma"][row], "gamma": ev["gamma"][row]}
        (p_i, p_j), (pd_i, pd_j), (pdd_i, pdd_j) = ((v[3:7], v[10:14]) for v in (q, qd, qdd))
        L_i, L_j, rhs, extra = book_n1_acceleration(a_i, p_i, pd_i, a_j, p_j, pd_j)
        b.update(printed=L_i @ pd_i + L_j @ pd_j - rhs, corrected=L_i @ pdd_i + L_j @ pdd_j + rhs, rhs=rhs,
                 extra=extra)
        out.append(b)
    return out


def _ev_14_5_gamma_n1():
    rows = [(b["printed"], b["corrected"], b["phi_dd"]) for b in _ev_14_5_n1_states(1451, tangent=True)]
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random states on the unit sphere (pᵀṗ = 0, pᵀp̈ = −ṗᵀṗ) the printed relation, "
                    f"2s_jᵀE_i s̄'_i ṗ_i + 2s_iᵀE_j s̄'_j ṗ_j − 2(s_jᵀĖ_iĠ_iᵀs'_i + s_iᵀĖ_jĠ_jᵀs'_j + "
                    f"ṡ_iᵀṡ_j) (Ġ read as Ġᵀ: Ġ s' is undefined), differs from Φ̈ = Φ_q q̈ − γ by up to "
                    f"{e_p:.3f}; with p̈ for ṗ and the right-hand side's sign changed it {agrees(e_c)}.",
                    e_p, e_c)


def _ev_14_5_gamma_n1_table():
    rows = [(-b["rhs"], -b["rhs"] - b["extra"], b["gamma"]) for b in _ev_14_5_n1_states(1452, tangent=False)]
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random states the book's right-hand side, −2(s_jᵀĖ_iĠ_iᵀs'_i + s_iᵀĖ_jĠ_jᵀs'_j + "
                    f"ṡ_iᵀṡ_j) (misprints of §14.5's n1 equation corrected), differs from kinbook's γ — the one "
                    f"that goes with Table 14.1's Φ_p = 2s_jᵀ(E_i s̄'_i + s'_i p_iᵀ) — by up to {e_p:.3f}; "
                    f"adding −2(s_jᵀs'_i)ṗ_iᵀṗ_i − 2(s_iᵀs'_j)ṗ_jᵀṗ_j it {agrees(e_c)}.", e_p, e_c)


# §14.5, spatial kinematic analysis (chapters/14-5-spatial-analysis.ipynb)
ERRATA += [
    Erratum("14.5-cross-references", "§14.5, opening paragraph, the Φ_p derivation and the γ paragraph",
            r"\text{“apartado 211.5” (twice), “apartado 3.3” (once)}",
            r"\text{chapter 13 (§13.5–13.8) for the planar analysis; §14.3 for } \partial(Aa)/\partial p "
            r"\text{ and } \ddot A a", "wording", None,
            "The book has no §211.5 or §3.3 (numbers left from another edition): the planar analysis is chapter 13, "
            "the Euler-parameter formulas are in §14.3. (A second “apartado 3.3”, before Ä a, is in a passage the "
            "book strikes through.)"),
    Erratum("14.5-n1-rj", "§14.5, Jacobian of Φ^(n1,1), the sentence before Φ_{r_j} and Φ_{p_j}",
            r"\text{“respecto a } r_i \text{ y } p_j\text{”}", r"\text{with respect to } r_j \text{ and } p_j",
            "wording"),
    Erratum("14.5-A-ddot-a", "§14.5, Ä a recalled from §14.3 for γ of Φ^(n1,1): the displayed formula",
            r"\ddot A a = 2\dot E\dot G^T a + 2E\ddot a\,\ddot p", r"\ddot A a = 2\dot E\dot G^T a + 2E\bar a\,\ddot p",
            "formula", _ev_A_ddot_a, "ä (the second derivative of a constant vector: zero) stands for ā; the §14.3 "
            "version also drops p̈ (notebook 14-3). The sentences that introduce the formula are struck through in "
            "the book; the formula itself is printed."),
    Erratum("14.5-gamma-n1", "§14.5, the acceleration equation of Φ^(n1,1)",
            r"[2s_j^TE_i\bar s'_i,\ 2s_i^TE_j\bar s'_j]\begin{bmatrix}\dot p_i\\ \dot p_j\end{bmatrix} = "
            r"2(s_j^T\dot E_i\dot G_i s'_i + s_i^T\dot E_j\dot G_j s'_j + \dot s_i^T\dot s_j)",
            r"[2s_j^TE_i\bar s'_i,\ 2s_i^TE_j\bar s'_j]\begin{bmatrix}\ddot p_i\\ \ddot p_j\end{bmatrix} = "
            r"-2(s_j^T\dot E_i\dot G_i^T s'_i + s_i^T\dot E_j\dot G_j^T s'_j + \dot s_i^T\dot s_j)",
            "formula", _ev_14_5_gamma_n1,
            "Three slips: ṗ for p̈, Ġ for Ġᵀ (Ġ s' is undefined) and the sign of the right-hand side (the book's "
            "own line before, s_jᵀÄ_is'_i + s_iᵀÄ_js'_j + 2ṡ_iᵀṡ_j = 0, gives the minus)."),
    Erratum("14.5-gamma-n1-table", "§14.5, “es necesario obtener el vector γ. Veamos como serían los pasos para su "
            "obtención … normal tipo 1”: the γ those steps end with",
            r"\gamma^{(n1,1)} = -2(s_j^T\dot E_i\dot G_i^T s'_i + s_i^T\dot E_j\dot G_j^T s'_j + \dot s_i^T\dot s_j)"
            r"\ \text{(misprints of 14.5-gamma-n1 corrected)}",
            r"\gamma^{(n1,1)} = -2(s_j^T\dot E_i\dot G_i^T s'_i + s_i^T\dot E_j\dot G_j^T s'_j + \dot s_i^T\dot s_j)"
            r" - 2(s_j^Ts'_i)\,\dot p_i^T\dot p_i - 2(s_i^Ts'_j)\,\dot p_j^T\dot p_j",
            "formula", _ev_14_5_gamma_n1_table,
            "The equation's row 2s_jᵀE_i s̄'_i is the derivative of E Gᵀ s'_i, not Table 14.1's Φ_p_i = "
            "2s_jᵀ(E_i s̄'_i + s'_i p_iᵀ), the derivative of the A the constraint uses. With Table 14.1's Φ_q the "
            "normalization rows force pᵀp̈ = −ṗᵀṗ, so Φ_q q̈ = γ needs the ṗᵀṗ terms; without them the "
            "accelerations are wrong whenever s_jᵀs'_i or s_iᵀs'_j ≠ 0."),
]


def get(erratum_id):
    """The erratum with this id."""
    for e in ERRATA:
        if e.id == erratum_id:
            return e
    from ..errors import InputError

    raise InputError(f"no erratum {str(erratum_id)[:80]!r}: the ids are {', '.join(e.id for e in ERRATA)}")


class ErrataTable:
    """All errata with their evidence computed; renders as an HTML table in a notebook."""

    def __init__(self, errata):
        self.rows = [(e, e.check()) for e in errata]

    def __repr__(self):
        lines = []
        for e, ev in self.rows:
            lines.append(f"[{e.id}] {e.where}\n  printed: {e.printed}\n  correct: {e.correct}")
            if ev is not None:
                lines.append(f"  evidence: {ev.text}")
            if e.note:
                lines.append(f"  note: {e.note}")
        return "\n".join(lines)

    def _repr_html_(self):
        cards = []
        for e, ev in self.rows:
            parts = [f"<p style='margin:0 0 4px 0'><b>{html.escape(e.where)}</b> "
                     f"<span style='color:#777'>[{html.escape(e.id)}, {e.kind}]</span></p>",
                     f"<p style='margin:0'>The book prints: {html_math(e.printed, display=True)}</p>",
                     f"<p style='margin:0'>Correct: {html_math(e.correct, display=True)}</p>"]
            if ev is not None:
                parts.append(f"<p style='margin:4px 0 0 0'>Evidence: {html.escape(ev.text)}</p>")
            if e.note:
                parts.append(f"<p style='margin:4px 0 0 0'><i>{html.escape(e.note)}</i></p>")
            cards.append("<div style='text-align:left; border-left:4px solid #c62828; padding:4px 10px; "
                         "margin:10px 0; background:#fdf6f6'>" + "".join(parts) + "</div>")
        return "".join(cards)


def show(*ids):
    """The errata with these ids, evidence computed (what a chapter notebook displays)."""
    return ErrataTable([get(i) for i in ids])


def table(prefix=""):
    """The errata whose id starts with ``prefix`` (e.g. "13", "14.3"; all by default), evidence computed."""
    return ErrataTable([e for e in ERRATA if e.id.startswith(prefix)])
