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

__all__ = ["Erratum", "Evidence", "ERRATA", "table", "get"]


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
    """

    text: str
    printed_error: float
    corrected_error: float = 0.0


@dataclass(frozen=True)
class Erratum:
    """One place where the book differs from what kinbook derives or computes."""

    id: str
    where: str
    printed: str
    correct: str
    kind: str  # "number", "formula" or "wording"
    evidence: Callable[[], Evidence] | None = field(default=None, repr=False)
    note: str = ""

    def check(self):
        """Run the evidence function (``None`` for wording errata)."""
        return None if self.evidence is None else self.evidence()


# ------------------------------------------------------------------------------------------------ helpers
def _ex(name):
    from . import examples

    return examples.load(name)


def _rad(deg):
    return np.radians(deg)


def _book_ex1_q():
    """Example 1's printed solution at t = 0."""
    return np.array([0, 0, 0, -0.7071, 0.7071, _rad(135), 1.5777, 1.9854, _rad(10.81),
                     3.7849, 1.2783, _rad(238.45)])


def _book_ex3_q():
    """Example 3's printed solution at t = 0 (with its printed x_2 = +0.7071)."""
    return np.array([0, 0, 0, 0.7071, 0.7071, _rad(135), 3.7849, 1.2783, _rad(238.45)])


def _pair(kind, seed=0):
    """A two-body mechanism with one joint of ``kind`` at random geometry and a sampler of random states.

    Returns (mech, states) where states() yields (q, qd, values) with the book's point quantities.
    """
    from .planar import Mechanism, Revolute, RevoluteRevolute, RevoluteTranslational, Translational

    rng = np.random.default_rng(seed)
    m = Mechanism(f"{kind} pair")
    pts = lambda: {k: tuple(rng.uniform(-2, 2, 2).round(3)) for k in ("P", "Q")}
    m.add_body("i", points=pts())
    m.add_body("j", points=pts())
    joint = {
        "t": lambda: Translational("i", "j", axis=("P", "Q"), point_j="P", phi0=0.4),
        "rr": lambda: RevoluteRevolute("i", "j", "P", "P", length=1.3),
        "rt": lambda: RevoluteTranslational("i", "j", point_i="P", axis=("P", "Q")),
        "r": lambda: Revolute("i", "j", point="P"),
    }[kind]()
    m.add(joint)

    def states(count=20):
        for _ in range(count):
            q, qd = rng.uniform(-2, 2, 6), rng.uniform(-2, 2, 6)
            v = {"q": q, "qd": qd}
            for b, off in (("i", 0), ("j", 3)):
                v[f"x_{b}"], v[f"y_{b}"], v[f"phi_{b}"] = q[off : off + 3]
                v[f"dx_{b}"], v[f"dy_{b}"], v[f"w_{b}"] = qd[off : off + 3]
                for p in ("P", "Q"):
                    v[f"x_{b}{p}"], v[f"y_{b}{p}"] = m.point_position(q, b, p)
            yield q, qd, v

    return m, states


def _compare(samples):
    """max |printed − reference| and max |corrected − reference| over (printed, corrected, reference) rows."""
    a = np.array(samples, dtype=float)
    return float(np.max(np.abs(a[:, 0] - a[:, 2]))), float(np.max(np.abs(a[:, 1] - a[:, 2])))


# ------------------------------------------------------------------------------------------- evidence
def _ev_ex1_solution():
    m = _ex("ch13_example1")
    qb = _book_ex1_q()
    res = m.Phi(qb, 0.0)
    A = m.point_position(qb, "crank", "A")
    B = np.array([4.5697, 2.5566])
    q = m.solve_position(0.0)
    ok = np.abs(m.Phi(q, 0.0)).max()
    return Evidence(
        f"The printed configuration leaves max |Φ_k| = {np.abs(res).max():.3f} (row Φ_{np.argmax(np.abs(res)) + 1}); "
        f"at the printed A and B the coupler would be |AB| = {np.linalg.norm(B - A):.3f} long instead of 6. "
        f"kinbook's solution: φ_3 = {np.degrees(q[8]):.2f}°, φ_4 = {np.degrees(q[11]):.2f}°, "
        f"B = ({m.point_position(q, 'rocker', 'B')[0]:.4f}, {m.point_position(q, 'rocker', 'B')[1]:.4f}), "
        f"max |Φ_k| = {ok:.1e}.",
        float(np.abs(res).max()), float(ok))


def _ev_ex3_x2():
    m = _ex("ch13_example3")
    qb = _book_ex3_q()
    res = m.Phi(qb, 0.0)
    fixed = qb.copy()
    fixed[3] = -0.7071
    return Evidence(
        f"With the printed x_2 = +0.7071, Φ_4 = x_1 − x_2 + cos φ_2 = {res[3]:.4f}; with x_2 = −0.7071 it is "
        f"{m.Phi(fixed, 0.0)[3]:.1e}.", abs(float(res[3])), abs(float(m.Phi(fixed, 0.0)[3])))


def _ev_ex4_phi8():
    m = _ex("ch13_example4")
    rng = np.random.default_rng(1)
    rows = []
    for _ in range(20):
        q = rng.uniform(-2, 2, 9)
        x1, y1, p1, x3, y3, p3 = q[0], q[1], q[2], q[6], q[7], q[8]
        printed = (x3 + 3 * np.cos(p3) - x1 * np.cos(p1)) * np.sin(p1) + (y3 + 3 * np.sin(p3) - y1 - np.sin(p1)) * np.cos(p1)
        corrected = -(x3 + 3 * np.cos(p3) - x1 - np.cos(p1)) * np.sin(p1) + (y3 + 3 * np.sin(p3) - y1 - np.sin(p1)) * np.cos(p1)
        rows.append((printed, corrected, m.Phi(q, 0.0)[7]))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random configurations the printed Φ_8 differs from kinbook's by up to {e_p:.3f}; the "
                    f"corrected row agrees to {e_c:.1e}.", e_p, e_c)


def _ev_table_13_2():
    m, states = _pair("t")
    rows = []
    for q, _, v in states():
        J = m.Phi_q(q)
        # the book's Φ_1 is (r_i^P − r_i^Q) × (r_j^P − r_i^P) = −(kinbook's row)
        sP = np.array([v["x_iP"] - v["x_iQ"], v["y_iP"] - v["y_iQ"]])
        printed = (v["x_jP"] - v["x_i"]) * sP[0] + (v["y_jP"] - v["y_i"]) * sP[1]
        corrected = (v["x_jP"] - v["x_j"]) * sP[0] + (v["y_jP"] - v["y_j"]) * sP[1]
        rows.append((printed, corrected, -J[0, 5]))
    e_p, e_c = _compare(rows)
    return Evidence(f"∂Φ_1/∂φ_j at 20 random configurations: the printed entry is off by up to {e_p:.3f}; with "
                    f"x_j, y_j it matches kinbook's derivative to {e_c:.1e}.", e_p, e_c)


def _ev_table_13_3():
    m, states = _pair("rr")
    rows = []
    for q, _, v in states():
        J = m.Phi_q(q)
        dx, dy = v["x_iP"] - v["x_jP"], v["y_iP"] - v["y_jP"]
        printed = -2 * dx * dy + 2 * dy * dx  # the printed ∂/∂φ_i entry: identically zero
        corrected = -2 * dx * (v["y_iP"] - v["y_i"]) + 2 * dy * (v["x_iP"] - v["x_i"])
        rows.append((printed, corrected, J[0, 2]))
    e_p, e_c = _compare(rows)
    return Evidence(f"The printed ∂Φ/∂φ_i reduces to 0; kinbook's entry reaches {e_p:.3f} at random "
                    f"configurations; the corrected entry agrees to {e_c:.1e}.", e_p, e_c)


def _ev_table_13_4():
    m, states = _pair("rt")
    rows = []
    for q, _, v in states():
        J = m.Phi_q(q)
        sx, sy = v["x_jP"] - v["x_jQ"], v["y_jP"] - v["y_jQ"]
        printed = (v["y_iP"] - v["y_i"]) * sy + (v["x_iP"] - v["x_i"]) * sx
        corrected = (v["y_iP"] - v["y_j"]) * sy + (v["x_iP"] - v["x_j"]) * sx
        rows.append((printed, corrected, J[0, 5]))
    e_p, e_c = _compare(rows)
    return Evidence(f"∂Φ/∂φ_j of the r-t joint: printed entry off by up to {e_p:.3f}; with x_j, y_j it agrees "
                    f"to {e_c:.1e}.", e_p, e_c)


def _ev_gamma_rr():
    m, states = _pair("rr")
    rows = []
    for q, qd, v in states():
        g = m.gamma(q, qd)[0]
        dx, dy = v["dx_i"] - v["dx_j"], v["dy_i"] - v["dy_j"]
        ai = (v["x_iP"] - v["x_i"], v["y_iP"] - v["y_i"])
        aj = (v["x_jP"] - v["x_j"], v["y_jP"] - v["y_j"])
        wi, wj = v["w_i"], v["w_j"]
        rest = (-2 * (ai[0] * (v["x_jP"] - v["x_i"]) + ai[1] * (v["y_jP"] - v["y_i"])) * wi**2
                - 2 * (aj[0] * (v["x_iP"] - v["x_j"]) + aj[1] * (v["y_iP"] - v["y_j"])) * wj**2
                + 4 * (ai[0] * aj[0] + ai[1] * aj[1]) * wi * wj
                - 4 * (ai[0] * dy - ai[1] * dx) * wi + 4 * (aj[0] * dy - aj[1] * dx) * wj)
        rows.append((-2 * dx**2 - 2 * dy + rest, -2 * dx**2 - 2 * dy**2 + rest, g))
    e_p, e_c = _compare(rows)
    return Evidence(f"γ of the r-r joint at 20 random states: printed entry off by up to {e_p:.2f}; with "
                    f"(ẏ_i − ẏ_j)² it agrees to {e_c:.1e}.", e_p, e_c)


def _ev_gamma_t():
    m, states = _pair("t")
    rows = []
    for q, qd, v in states():
        qd = qd.copy()
        qd[5] = qd[2]  # the joint's second velocity equation: φ̇_j = φ̇_i
        w = qd[2]
        a, b = v["x_iP"] - v["x_iQ"], v["y_iP"] - v["y_iQ"]  # the book's O read as Q
        vel = 2 * (a * (qd[0] - qd[3]) + b * (qd[1] - qd[4])) * w
        quad = (a * (v["y_i"] - v["y_j"]) - b * (v["x_i"] - v["x_j"])) * w**2
        # the book's Φ_1 is −1 × kinbook's, so its γ_1 is −1 × kinbook's
        rows.append((vel - quad, -vel - quad, -m.gamma(q, qd)[0]))
    e_p, e_c = _compare(rows)
    return Evidence(f"γ_1 of the translational joint at 20 random states with φ̇_j = φ̇_i: printed entry off by up "
                    f"to {e_p:.2f}; with −2[…]φ̇_i it agrees to {e_c:.1e}.", e_p, e_c)


def _ev_eq37():
    from .planar import Gear, Mechanism

    rng = np.random.default_rng(37)
    m = Mechanism("gear pair on a carrier")
    for b in ("i", "j", "k"):
        m.add_body(b, q0=(0, 0, float(rng.uniform(-1, 1))))
    ri, rj = 0.7, 1.9
    m.add(Gear("i", "j", "k", radius_i=ri, radius_j=rj))
    pi0, pj0, pk0 = (float(b.q0[2]) for b in m.bodies)
    rows = []
    for q in rng.uniform(-3, 3, (20, 9)):
        pi, pj, pk = q[2], q[5], q[8]
        printed = ri * ((pi - pk) - pi0) + rj * ((pj - pk) - pj0)  # eq. 37 with φ' = φ − φ_k
        corrected = ri * ((pi - pk) - (pi0 - pk0)) + rj * ((pj - pk) - (pj0 - pk0))
        rows.append((printed, corrected, m.Phi(q)[0]))
    e_p, e_c = _compare(rows)
    return Evidence(f"With the carrier's initial angle φ_k⁰ = {pk0:.3f}, eq. 37 differs from kinbook's gear row by "
                    f"(ρ_i + ρ_j) φ_k⁰ = {e_p:.3f}; measuring the initial angles relative to the carrier too (eq. 38) "
                    f"agrees to {e_c:.1e}.", e_p, e_c)


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
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(count, 4))
    return p / np.linalg.norm(p, axis=1, keepdims=True)


def _ev_elementary_rotation():
    from .spatial import A_from_euler

    rows = []
    for psi in np.linspace(0.1, 3.0, 12):
        c, s_ = np.cos(psi), np.sin(psi)
        printed = np.array([[c, s_, 0], [s_, c, 0], [0, 0, 1]])
        corrected = np.array([[c, s_, 0], [-s_, c, 0], [0, 0, 1]])
        reference = A_from_euler(psi, 0, 0).T  # the book's passive A^ψ
        rows.append((np.abs(printed - reference).max(), np.abs(corrected - reference).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"The printed A^ψ has det = cos 2ψ (0.5 at ψ = 30°), so it is no rotation; it differs from the "
                    f"transpose of kinbook's A(ψ, 0, 0) by up to {e_p:.3f}; with −sin ψ in row 2 it agrees to "
                    f"{e_c:.1e}.", e_p, e_c)


def _ev_a21_row3():
    from .spatial import A_from_euler

    rng = np.random.default_rng(2)
    rows = []
    for psi, th, ph in rng.uniform(-3, 3, (20, 3)):
        ref = A_from_euler(psi, th, ph).T[2]
        printed = np.array([np.sin(psi) * np.sin(ph), -np.cos(psi) * np.sin(ph), np.cos(th)])
        corrected = np.array([np.sin(psi) * np.sin(th), -np.cos(psi) * np.sin(th), np.cos(th)])
        rows.append((np.abs(printed - ref).max(), np.abs(corrected - ref).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"Row 3 of the product A^φ A^θ A^ψ (the transpose of kinbook's A_from_euler) at 20 random "
                    f"angles: the printed row is off by up to {e_p:.3f}; with sin θ for sin φ it agrees to {e_c:.1e}.",
                    e_p, e_c)


def _printed_A_of_p(p):
    e0, e1, e2, e3 = p
    return np.array([
        [e0**2 + e1**2 - 0.5, e1 * e2 - e0 * e3, e1 * e3 - e0 * e2],
        [e1 * e2 - e0 * e3, e0**2 + e2**2 - 0.5, e2 * e3 - e0 * e1],
        [e1 * e3 - e0 * e2, e2 * e3 - e0 * e1, e0**2 + e3**2 - 0.5],
    ])


def _ev_A_of_p():
    from .spatial import A_from_p

    rows = []
    for p in _unit_ps():
        e0, e1, e2, e3 = p
        printed = _printed_A_of_p(p)
        corrected = 2 * printed
        corrected[0, 2] += 4 * e0 * e2
        corrected[1, 0] += 4 * e0 * e3
        corrected[2, 1] += 4 * e0 * e1
        ref = A_from_p(p)
        rows.append((np.abs(printed - ref).max(), np.abs(corrected - ref).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"At 20 random unit p the printed matrix differs from A(p) by up to {e_p:.3f} (it is symmetric, "
                    f"so it cannot be a rotation in general); twice it, with + e0 terms at a13, a21, a32, agrees to "
                    f"{e_c:.1e}.", e_p, e_c)


def _ev_G_row2():
    from .spatial import G

    rows = []
    for p in _unit_ps():
        e0, e1, e2, e3 = p
        printed = G(p).copy()
        printed[1] = [-e2, e3, e0, e1]
        rows.append((np.abs(printed @ p).max(), np.abs(G(p) @ p).max(), 0.0))
    e_p, e_c = _compare(rows)
    return Evidence(f"With the printed row 2, G p = [0, 2 e1 e3, 0] reaches {e_p:.3f} at random unit p instead of "
                    f"0; kinbook's G gives |G p| ≤ {e_c:.1e}.", e_p, e_c)


def _ev_p_from_A_180():
    from .spatial import A_from_p, p_from_A, p_from_axis_angle

    A = A_from_p(p_from_axis_angle([1, 2, 2], np.pi))
    e0 = np.sqrt(max(np.trace(A) + 1, 0.0) / 4)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.array([A[2, 1] - A[1, 2], A[0, 2] - A[2, 0], A[1, 0] - A[0, 1]]) / (4 * e0)
    book_ok = bool(np.all(np.isfinite(e)))
    rebuilt = np.abs(A_from_p(p_from_A(A)) - A).max()
    return Evidence(f"For a 180° turn about (1, 2, 2)/3, e0 = {e0:.1e} and the book's recipe divides by it: "
                    f"e = {np.array2string(e, precision=3)}; kinbook's largest-component branch gives "
                    f"p = {np.array2string(p_from_A(A), precision=4)} and rebuilds A to {rebuilt:.1e}.",
                    0.0 if book_ok else np.inf, float(rebuilt))


# ----------------------------------------------------------------------------------------------- the list
ERRATA = [
    Erratum("13.5-s-notation", "§13.5, eq. 5 and the revolute joint (eqs. 14–15)", r"s_i^P",
            r"s_i^P \text{ (global components)},\ s'^P_i \text{ (local)}", "wording", None,
            "The same name s_i^P is used for the vector O_iP in global components (fig. 13.18) and for the column "
            "of local coordinates [ξ, η]ᵀ (after eq. 5); kinbook and the workbook write the local one with a prime."),
    Erratum("13.5-eq4-text", "§13.5, text after eq. 4", r"[x, y]_i \text{: coordinates of O in local axes}",
            r"[x, y]_i \text{: global coordinates of } O_i", "wording"),
    Erratum("13.5-ex1-solution", "§13.5, example 1: solution at t = 0 and the points A, B",
            r"x_3 = 1.5777,\ y_3 = 1.9854,\ \varphi_3 = 10.81°,\ x_4 = 3.7849,\ y_4 = 1.2783,\ \varphi_4 = 238.45°,\ B = (4.5697, 2.5566)",
            r"\varphi_3 = 11.58°,\ \varphi_4 = 240.80°,\ B = (4.4636, 2.6187)", "number", _ev_ex1_solution,
            "Examples 3, 5 and 6 reuse this configuration, so their numbers inherit the error."),
    Erratum("13.5-ex3-x2", "§13.5, example 3 (and example 5): solution at t = 0", r"x_2 = 0.7071",
            r"x_2 = -0.7071", "number", _ev_ex3_x2),
    Erratum("13.5-ex3-system", "§13.5, example 3: the assembled system, Φ_6 and Φ_7",
            r"\ldots - x_4 - 1.5\cos\varphi_3,\ \ldots - y_4 - 1.5\sin\varphi_3",
            r"\ldots - x_3 - 1.5\cos\varphi_3,\ \ldots - y_3 - 1.5\sin\varphi_3", "wording", None,
            "Example 3 has three bodies; there is no x_4 (the joint-2 section itself prints x_3, y_3)."),
    Erratum("13.5-ex4-phi8", "§13.5, example 4: simplified Φ_8 (and the assembled system)",
            r"(x_3 + 3\cos\varphi_3 - x_1\cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            r"-(x_3 + 3\cos\varphi_3 - x_1 - \cos\varphi_1)\sin\varphi_1 + (y_3 + 3\sin\varphi_3 - y_1 - \sin\varphi_1)\cos\varphi_1",
            "formula", _ev_ex4_phi8),
    Erratum("13.5-ex2-l3", "§13.5, example 2: local frame of body 3", r"l_3 = b/6", r"l_3 = 6", "wording"),
    Erratum("13.5-eq25", "§13.5, translational joint, eqs. 23.a, 25, 26",
            r"s_i = r_i^P - r_i^O,\ (x_i^P - x_i^O)(y_j^P - y_i^P) - (y_i^P - y_i^O)(x_j^P - x_i^P)",
            r"(x_i^Q - x_i^P)(y_j^P - y_i^P) - (y_i^Q - y_i^P)(x_j^P - x_i^P)", "wording", None,
            "The text defines s_i from P_i to Q_i; the printed O (the body origin) satisfies the constraint only "
            "when O_i lies on the line of translation. The book's sign is −1 × kinbook's row: the same constraint."),
    Erratum("13.5-eq21", "§13.5, translational joint, text after eq. 21", r"\text{eq. (19) is one of the two equations}",
            r"\text{eq. (21)}", "wording"),
    Erratum("13.5-eq24", "§13.5, translational joint, before eq. 24", r"\text{multiplying the vectors scalarly}",
            r"\text{the vector (cross) product}", "wording"),
    Erratum("13.5-eq37", "§13.5, gears: eq. 37", r"\rho_i(\varphi'_i - \varphi_i^0) + \rho_j(\varphi'_j - \varphi_j^0) = 0",
            r"\rho_i(\varphi'_i - \varphi_i'^0) + \rho_j(\varphi'_j - \varphi_j'^0) = 0,\ \varphi'^0 = \varphi^0 - \varphi_k^0",
            "formula", _ev_eq37, "Eq. 38, the constraint kinbook uses, is right; eq. 37 only holds when φ_k⁰ = 0."),
    Erratum("13.5-joint-labels", "§13.5, examples 2 and 4: labels and references",
            r"\Phi^{(i,2)},\ \Phi^{(r,1)},\ \text{apartado 4.3 / 4.5},\ \text{“as in example 3”}",
            r"\Phi^{(t,2)},\ \Phi^{(r\text{-}t,1)},\ \text{the translational / r-t subsections of §13.5},\ \text{example 2}",
            "wording"),
    Erratum("13.6-table-13.1-text", "§13.6, the derivation under Table 13.1",
            r"\partial\Phi_1/\partial\varphi_i = -(y_i^P - y_j^P),\ \ldots",
            r"-(y_i^P - y_i),\ (y_j^P - y_j),\ (x_i^P - x_i),\ -(x_j^P - x_j)", "wording", None,
            "Table 13.1 itself is right; only the worked derivatives below it use the wrong points."),
    Erratum("13.6-table-13.2", "§13.6, Table 13.2 (translational joint), ∂Φ_1/∂φ_j",
            r"(x_j^P - x_i)(x_i^P - x_i^O) + (y_j^P - y_i)(y_i^P - y_i^O)",
            r"(x_j^P - x_j)(x_i^P - x_i^Q) + (y_j^P - y_j)(y_i^P - y_i^Q)", "formula", _ev_table_13_2,
            "Table 13.5 prints this entry correctly."),
    Erratum("13.6-table-13.3", "§13.6, Table 13.3 (revolute–revolute joint), ∂/∂φ_i and ∂/∂φ_j",
            r"-2(x_i^P - x_j^P)(y_i^P - y_j^P) + 2(y_i^P - y_j^P)(x_i^P - x_j^P)\ (= 0)",
            r"-2(x_i^P - x_j^P)(y_i^P - y_i) + 2(y_i^P - y_j^P)(x_i^P - x_i)", "formula", _ev_table_13_3,
            "Example 5 repeats the zero entries; Table 13.5 prints them correctly."),
    Erratum("13.6-table-13.4", "§13.6, Tables 13.4 and 13.5 (revolute–translational joint), ∂Φ/∂φ_j",
            r"(y_i^P - y_i)(y_j^P - y_j^Q) + (x_i^P - x_i)(x_j^P - x_j^Q)",
            r"(y_i^P - y_j)(y_j^P - y_j^Q) + (x_i^P - x_j)(x_j^P - x_j^Q)", "formula", _ev_table_13_4),
    Erratum("13.8-gamma-sign", "§13.8, the revolute-joint walkthrough and example 6",
            r"\gamma = (\Phi_q\dot q)_q\dot q", r"\gamma = -(\Phi_q\dot q)_q\dot q - 2\Phi_{qt}\dot q - \Phi_{tt}",
            "wording", None, "The section first writes the minus sign, then drops it; its final γ rows use the right sign."),
    Erratum("13.8-table-13.5-rr", "§13.8, Table 13.5, γ of the revolute–revolute joint (and example 6)",
            r"-2(\dot x_i - \dot x_j)^2 - 2(\dot y_i - \dot y_j) - \ldots",
            r"-2(\dot x_i - \dot x_j)^2 - 2(\dot y_i - \dot y_j)^2 - \ldots", "formula", _ev_gamma_rr),
    Erratum("13.8-table-13.5-t", "§13.8, Table 13.5, γ_1 of the translational joint",
            r"2[(x_i^P - x_i^O)(\dot x_i - \dot x_j) + (y_i^P - y_i^O)(\dot y_i - \dot y_j)]\dot\varphi_i - [\ldots]\dot\varphi_i^2",
            r"-2[(x_i^P - x_i^Q)(\dot x_i - \dot x_j) + (y_i^P - y_i^Q)(\dot y_i - \dot y_j)]\dot\varphi_i - [\ldots]\dot\varphi_i^2",
            "formula", _ev_gamma_t, "The printed entry already uses φ̇_j = φ̇_i."),
    Erratum("13.7-velocity-rhs", "§13.7, example 5: general form of the velocity equations",
            r"\begin{bmatrix}\Phi_q\\ \Phi_q^{(d)}\end{bmatrix}\dot q = \begin{bmatrix}0\\ \Phi_t^{(d)}\end{bmatrix}",
            r"\begin{bmatrix}\Phi_q\\ \Phi_q^{(d)}\end{bmatrix}\dot q = \begin{bmatrix}0\\ -\Phi_t^{(d)}\end{bmatrix}",
            "wording", None, "The section's own derivation (before example 5) has the minus sign."),
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
            "formula", _ev_elementary_rotation, "The same slip is in A^θ and A^φ; the book's A^ψ, A^θ, A^φ are passive "
            "(global → local), the transposes of kinbook's active matrices (docs/conventions.md)."),
    Erratum("14.2-A21-row3", "§14.2, the composed matrix A²¹ (both versions), row 3",
            r"[\sin\psi\sin\phi,\ -\cos\psi\sin\phi,\ \cos\theta]",
            r"[\sin\psi\sin\theta,\ -\cos\psi\sin\theta,\ \cos\theta]", "formula", _ev_a21_row3),
    Erratum("14.2-omega-matrix", "§14.2, the matrix relating ω to the angle rates", r"3 \times 4\ \text{matrix}",
            r"\omega' = \begin{bmatrix}s\theta s\phi & c\phi & 0\\ s\theta c\phi & -s\phi & 0\\ c\theta & 0 & 1\end{bmatrix}\begin{bmatrix}\dot\psi\\ \dot\theta\\ \dot\phi\end{bmatrix}",
            "wording", None, "The first version also prints +sin φ where −sin φ belongs in row 2 of the matrix and of "
            "its inverse; kinbook.spatial.omega_from_euler_rates(frame='body') is the corrected relation."),
    Erratum("14.3-A-of-p", "§14.3, A in terms of the Euler parameters",
            r"\begin{bmatrix}e_0^2+e_1^2-\tfrac12 & e_1e_2-e_0e_3 & e_1e_3-e_0e_2\\ e_1e_2-e_0e_3 & \cdots\end{bmatrix}",
            r"2\begin{bmatrix}e_0^2+e_1^2-\tfrac12 & e_1e_2-e_0e_3 & e_1e_3+e_0e_2\\ e_1e_2+e_0e_3 & e_0^2+e_2^2-\tfrac12 & e_2e_3-e_0e_1\\ e_1e_3-e_0e_2 & e_2e_3+e_0e_1 & e_0^2+e_3^2-\tfrac12\end{bmatrix}",
            "formula", _ev_A_of_p),
    Erratum("14.3-p-from-A", "§14.3, the Euler parameters from A",
            r"e_0^2 = (p+1)/4,\ e_1 = (a_{32}-a_{23})/(4e_0),\ \ldots\ \text{(no critical cases)}",
            r"e_0^2 = (\operatorname{tr}A+1)/4;\ \text{divide by the largest of } e_0, e_1, e_2, e_3",
            "number", _ev_p_from_A_180, "Every 180° rotation has e0 = 0."),
    Erratum("14.3-G-row2", "§14.3, the matrix G, row 2", r"[-e_2,\ e_3,\ e_0,\ e_1]", r"[-e_2,\ -e_3,\ e_0,\ e_1]",
            "formula", _ev_G_row2),
    Erratum("14.3-dAa-dp", "§14.3, ∂(Aa)/∂p", r"2(E\bar a + a p^T)\ \text{(form of A not stated)}",
            r"2(E\bar a + a p^T) \text{ for } A = 2[(e_0^2-\tfrac12)I + ee^T + e_0\tilde e];\ 2E\bar a \text{ for } A = EG^T",
            "wording", None, "Both forms agree on the unit sphere, not off it; kinbook.spatial.dAa_dp(p, a, form=...) "
            "gives either."),
]


def get(erratum_id):
    """The erratum with this id."""
    for e in ERRATA:
        if e.id == erratum_id:
            return e
    raise KeyError(erratum_id)


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
                     f"<p style='margin:0'>The book prints: $${html.escape(e.printed)}$$</p>",
                     f"<p style='margin:0'>Correct: $${html.escape(e.correct)}$$</p>"]
            if ev is not None:
                parts.append(f"<p style='margin:4px 0 0 0'>Evidence: {html.escape(ev.text)}</p>")
            if e.note:
                parts.append(f"<p style='margin:4px 0 0 0'><i>{html.escape(e.note)}</i></p>")
            cards.append("<div style='text-align:left; border-left:4px solid #c62828; padding:4px 10px; "
                         "margin:10px 0; background:#fdf6f6'>" + "".join(parts) + "</div>")
        return "".join(cards)


def table(prefix=""):
    """The errata whose id starts with ``prefix`` (e.g. "13", "14.3"; all by default), evidence computed."""
    return ErrataTable([e for e in ERRATA if e.id.startswith(prefix)])
