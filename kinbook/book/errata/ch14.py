"""Chapter 14's errata (§14.2-14.5, space), each with its evidence computed from kinbook's rotations,
constraints and derivations."""

from __future__ import annotations

import numpy as np
import sympy as sp

from ...grading.misprints import book_A_of_p, book_n1_acceleration
from ...spatial import (
    A_ddot,
    A_from_euler,
    A_from_p,
    E,
    G,
    Mechanism,
    Normal1,
    Normal2,
    Parallel1,
    Revolute,
    Universal,
    a_bar,
    euler_rates_from_omega,
    omega_from_euler_rates,
    p_from_A,
    p_from_axis_angle,
    random_p,
    skew,
)
from ..display import agrees
from .erratum import Erratum, Evidence, below, compare

__all__ = ["ERRATA"]


# ------------------------------------------------------------------------------------ chapter 14 evidence
def _unit_ps(count=20, seed=14):
    return random_p(count, rng=seed)


def _ev_elementary_rotation():
    rows = []
    for psi in np.linspace(0.1, 3.0, 12):
        c, s_ = np.cos(psi), np.sin(psi)
        printed = np.array([[c, s_, 0], [s_, c, 0], [0, 0, 1]])
        corrected = np.array([[c, s_, 0], [-s_, c, 0], [0, 0, 1]])
        reference = A_from_euler(psi, 0, 0).T  # the book's passive A^ψ
        rows.append((printed, corrected, reference))
    e_p, e_c = compare(rows)
    return Evidence(rf"The printed $\mathbf A^\psi$ has $\det = \cos 2\psi$ (0.5 at $\psi = 30°$), so it is no rotation; it "
                    rf"differs from the transpose of kinbook's $\mathbf A(\psi, 0, 0)$ by up to {e_p:.3f}; with "
                    rf"$-\sin\psi$ in row 2 it {agrees(e_c)}.", e_p, e_c)


def _ev_a21_row3():
    rng = np.random.default_rng(2)
    rows = []
    for psi, th, ph in rng.uniform(-3, 3, (20, 3)):
        ref = A_from_euler(psi, th, ph).T[2]
        printed = np.array([np.sin(psi) * np.sin(ph), -np.cos(psi) * np.sin(ph), np.cos(th)])
        corrected = np.array([np.sin(psi) * np.sin(th), -np.cos(psi) * np.sin(th), np.cos(th)])
        rows.append((printed, corrected, ref))
    e_p, e_c = compare(rows)
    return Evidence(rf"Row 3 of the product $\mathbf A^\phi\mathbf A^\theta\mathbf A^\psi$ (the transpose of kinbook's "
                    rf"A_from_euler) at 20 random angles: the printed row is off by up to {e_p:.3f}; with $\sin\theta$ "
                    rf"for $\sin\phi$ it {agrees(e_c)}.",
                    e_p, e_c)


def _ev_A_of_p():
    rows = []
    for p in _unit_ps():
        e0, e1, e2, e3 = p
        printed = book_A_of_p(p)
        corrected = 2 * printed
        corrected[0, 2] += 4 * e0 * e2
        corrected[1, 0] += 4 * e0 * e3
        corrected[2, 1] += 4 * e0 * e1
        ref = A_from_p(p)
        rows.append((printed, corrected, ref))
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random unit $\mathbf p$ the printed matrix differs from $\mathbf A(\mathbf p)$ by up to "
                    rf"{e_p:.3f} (it is symmetric, so it cannot be a rotation in general); twice it, with $+e_0$ terms "
                    rf"at $a_{{13}}$, $a_{{21}}$, $a_{{32}}$, {agrees(e_c)}.", e_p, e_c)


def _ev_G_row2():
    rows = []
    for p in _unit_ps():
        e0, e1, e2, e3 = p
        printed = G(p).copy()
        printed[1] = [-e2, e3, e0, e1]
        rows.append((printed @ p, G(p) @ p, np.zeros(3)))    # G p = 0
    e_p, e_c = compare(rows)
    return Evidence(rf"With the printed row 2, $\mathbf G\mathbf p = [0, 2e_1e_3, 0]^T$ reaches {e_p:.3f} at random unit "
                    rf"$\mathbf p$ instead of 0; kinbook's $\mathbf G$ gives $|\mathbf G\mathbf p|$ {below(e_c)}.", e_p, e_c)


def _matrices_vs(reference, samples):
    """(printed error, corrected error): ``reference(sample)`` returns (printed, corrected, kinbook's) arrays."""
    rows = []
    for sample in samples:
        printed, corrected, ref = reference(*sample)
        rows.append((printed, corrected, ref))
    return compare(rows)


def _ev_A_theta_second():
    def matrices(psi, th):
        c, s = np.cos(th), np.sin(th)
        return (np.array([[1, 0, 0], [0, np.cos(psi), -s], [0, s, c]]), np.array([[1, 0, 0], [0, c, s], [0, -s, c]]),
                A_from_euler(0.0, th, 0.0).T)  # the nutation alone, passive like the printed A^ψ and A^φ

    e_p, e_c = _matrices_vs(matrices, np.random.default_rng(21).uniform(-3, 3, (20, 2)))
    return Evidence(rf"At 20 random $(\psi, \theta)$ the printed $\mathbf A^\theta$ differs from the passive nutation "
                    rf"matrix (the transpose of kinbook's $\mathbf A(0, \theta, 0)$, as the printed $\mathbf A^\psi$ "
                    rf"and $\mathbf A^\phi$ are passive) by up to {e_p:.3f} — it is no rotation "
                    rf"($\det = c\psi\, c\theta + s\theta^2$); with $\cos\theta$ in row 2 and $+\sin\theta$ above the "
                    rf"diagonal it {agrees(e_c)}.", e_p, e_c)


def _ev_omega_matrix():
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
    return Evidence(rf"As printed, a $3\times4$ array multiplies the three rates $(\dot\psi, \dot\theta, \dot\phi)$: the "
                    rf"product is not defined (sympy raises ShapeError). The $3\times3$ matrix with $s\theta\, s\phi$ "
                    rf"and $s\theta\, c\phi$ in column 1 gives kinbook's $\boldsymbol\omega'$ (omega_from_euler_rates, "
                    rf"frame='body') at 20 random angles and rates: the difference {below(e_c)}.", shape_error, e_c)


def _ev_rates_inverse_first():
    rows = []
    for (psi, th, ph), w in zip(np.random.default_rng(26).uniform(0.2, 2.9, (20, 3)),
                                np.random.default_rng(27).uniform(-2, 2, (20, 3))):
        sth, cth, sph, cph = np.sin(th), np.cos(th), np.sin(ph), np.cos(ph)
        top, bottom = [sph / sth, cph / sth, 0], [-sph * cth / sth, -cph * cth / sth, 1]
        printed = np.array([top, [cph, sph, 0], bottom])
        corrected = np.array([top, [cph, -sph, 0], bottom])
        ref = euler_rates_from_omega((psi, th, ph), w, frame="body")
        rows.append((printed @ w, corrected @ w, ref))
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random angles ($\sin\theta \neq 0$) and body angular velocities $\boldsymbol\omega'$, the "
                    rf"first printed inverse gives rates off by up to {e_p:.3f} from kinbook's "
                    rf"euler_rates_from_omega(frame='body'); with $-\sin\phi$ in row 2 (as the second version prints "
                    rf"it) it {agrees(e_c)}.", e_p, e_c)


def _ev_A21_row2_first():
    def rows(psi, th, ph):
        cps, sps, cth, sth, cph, sph = np.cos(psi), np.sin(psi), np.cos(th), np.sin(th), np.cos(ph), np.sin(ph)
        return (np.array([cps * sph - sps * cth * cph, sps * sph + cps * cth * cph, sth * cph]),
                np.array([-cps * sph - sps * cth * cph, -sps * sph + cps * cth * cph, sth * cph]),
                A_from_euler(psi, th, ph).T[1])

    e_p, e_c = _matrices_vs(rows, np.random.default_rng(22).uniform(-3, 3, (20, 3)))
    return Evidence(rf"Row 2 of $\mathbf A^\phi\mathbf A^\theta\mathbf A^\psi$ at 20 random angles: the first printed "
                    rf"version is off by up to {e_p:.3f}; with $-c\psi\, s\phi$ and $-s\psi\, s\phi$ (as the second "
                    rf"version prints it) it {agrees(e_c)}.", e_p, e_c)


def _ev_turns_frames():
    def triads(psi, th, ph):
        # the book's e^{new} = A e^{old}, a triad written as the matrix of its unit vectors (rows, XYZ components);
        # kinbook's elementary turns, passive like the book's second A^ψ, A^φ: the transposes of A_from_euler
        A_psi, A_theta, A_phi = (A_from_euler(*a).T for a in ((psi, 0.0, 0.0), (0.0, th, 0.0), (0.0, 0.0, ph)))
        e_Z1 = A_psi @ np.eye(3)                        # e^{Z'}: the triad after the precession
        e_Z2 = A_theta @ e_Z1                           # the triad OX'Y''Z'' after the nutation
        return A_phi @ e_Z1, A_phi @ e_Z2, A_from_euler(psi, th, ph).T   # the body's ξ, η, ζ as rows

    samples = np.random.default_rng(24).uniform(-3, 3, (20, 3))
    e_p, e_c = _matrices_vs(triads, samples)
    zeta_on_Z = max(float(np.abs(triads(*a)[0][2] - [0.0, 0.0, 1.0]).max()) for a in samples)
    return Evidence(rf"The three turns applied to the unit vectors (a triad as the rows of its unit vectors, "
                    rf"$e^{{\rm new}} = \mathbf A\, e^{{\rm old}}$, with kinbook's elementary turns), at 20 random "
                    rf"angles: $\mathbf A^\varphi$ applied to $e^{{Z'}}$, the triad after the precession, gives a "
                    rf"triad off from the body's (the columns of kinbook's A_from_euler) by up to {e_p:.3f}, whose "
                    rf"third axis stays on $Z$ (difference {below(zeta_on_Z)}) although the nutation tilts $Z''$ by "
                    rf"$\theta$; applied to the triad after the nutation it gives the body's triad "
                    rf"(difference {below(e_c)}).", e_p, e_c)


def _ev_omega_prime():
    rng = np.random.default_rng(25)
    rows = []
    for (psi, th, ph), rates in zip(rng.uniform(-3, 3, (20, 3)), rng.uniform(-2, 2, (20, 3))):
        st, ct, sph, cph = np.sin(th), np.cos(th), np.sin(ph), np.cos(ph)
        M = np.array([[st * sph, cph, 0], [st * cph, -sph, 0], [ct, 0, 1]])   # the printed matrix, 3 columns
        omega = omega_from_euler_rates((psi, th, ph), rates, frame="global")
        omega_body = omega_from_euler_rates((psi, th, ph), rates, frame="body")
        rows.append((M @ rates - omega, M @ rates - omega_body, np.zeros(3)))   # read as ω, read as ω'
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random angles and rates, the matrix (with its three columns, 14.2-omega-matrix) times "
                    rf"$[\dot\psi, \dot\theta, \dot\phi]^T$ is off from the global components "
                    rf"$\boldsymbol\omega$ by up to {e_p:.3f}; it equals the body components "
                    rf"$\boldsymbol\omega' = \mathbf A^T\boldsymbol\omega$ (kinbook's "
                    rf"omega_from_euler_rates(frame='body'), difference {below(e_c)}).", e_p, e_c)


def _ev_p_from_A_recipe():
    rows = []
    for p in _unit_ps(seed=31):
        A = A_from_p(p)
        t = np.trace(A)
        squares = np.array([(t + 1) / 4, *((1 + 2 * np.diag(A) - t) / 4)])
        rows.append(float(np.abs(squares - p**2).max()))
    e_c = max(rows)
    return Evidence(rf"$e_0^2 = (p + 1)/4$ has a $p$ defined nowhere, and $t = 2(3e_0^2 + e_1^2 + e_2^2 + e_3^2) - 3$ "
                    rf"needs the parameters being sought: as printed the recipe cannot be evaluated from $\mathbf A$. "
                    rf"With $t = \operatorname{{tr}}\mathbf A$, the four squares match those of the Euler parameters "
                    rf"of 20 random rotations (the difference {below(e_c)}).", float("inf"), e_c)


def _ev_A_ddot_a():
    rows = []
    rng = np.random.default_rng(32)
    for p, a in zip(_unit_ps(seed=32), rng.uniform(-1, 1, (20, 3))):
        pd = rng.normal(size=4)
        pd -= p * (p @ pd)                           # on a motion: pᵀṗ = 0 ...
        pdd = rng.normal(size=4)
        pdd -= p * (p @ pdd + pd @ pd)               # ... and pᵀp̈ = −ṗᵀṗ
        EGt = 2 * E(pd, check=False) @ G(pd, check=False).T @ a
        ref = A_ddot(p, pd, pdd) @ a
        rows.append((EGt, EGt + 2 * E(p) @ a_bar(a) @ pdd, ref))
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random states of a motion (unit $\mathbf p$, $\mathbf p^T\dot{{\mathbf p}} = 0$, "
                    rf"$\mathbf p^T\ddot{{\mathbf p}} = -\dot{{\mathbf p}}^T\dot{{\mathbf p}}$) and vectors "
                    rf"$\mathbf a$: with $\ddot{{\mathbf a}} = \mathbf 0$ ($\mathbf a$ is constant) the printed "
                    rf"right-hand side is $2\dot{{\mathbf E}}\dot{{\mathbf G}}^T\mathbf a$, off from kinbook's "
                    rf"$\ddot{{\mathbf A}}\mathbf a$ by up to {e_p:.3f}; $2\dot{{\mathbf E}}\dot{{\mathbf G}}^T\mathbf a "
                    rf"+ 2\mathbf E\bar{{\mathbf a}}\ddot{{\mathbf p}}$ {agrees(e_c)}.", e_p, e_c)


def _ev_a_bar_explicit():
    rows = []
    for p, a in zip(_unit_ps(seed=23), np.random.default_rng(23).uniform(-1, 1, (20, 3))):
        a1, a2, a3 = a
        printed = np.array([[0, -a1, -a2, -a3], [a1, 0, -a3, a2], [a2, a3, 0, -a1], [a3, -a2, a1, 0]])
        rows.append((printed @ p, a_bar(a) @ p, G(p).T @ a))
    e_p, e_c = compare(rows)
    return Evidence(rf"$\bar{{\mathbf a}}\mathbf p$ against $\mathbf G^T\mathbf a$ at 20 random unit $\mathbf p$ and "
                    rf"vectors $\mathbf a$: the printed element-by-element $\bar{{\mathbf a}}$ is off by up to "
                    rf"{e_p:.3f}; the block form $\begin{{bmatrix}}0 & -\mathbf a^T\\ \mathbf a & -\tilde{{\mathbf a}}"
                    rf"\end{{bmatrix}}$ {agrees(e_c)}.", e_p, e_c)


ERRATA = [
    Erratum("14.2-termas", "§14.2, the opening paragraph",
            r"\text{“… y de las termas posibles se ha generalizado …”}",
            r"\text{“… y de las ternas posibles se ha generalizado …”}", "wording",
            note="“Ternas” (triples): of the possible triples of angles, the one of precession, nutation and spin is the "
                 "usual choice."),
    Erratum("14.2-elementary-rotations", "§14.2, the three elementary rotations (first set)",
            r"A^\psi = \begin{bmatrix}\cos\psi & \sin\psi & 0\\ \sin\psi & \cos\psi & 0\\ 0&0&1\end{bmatrix}",
            r"A^\psi = \begin{bmatrix}\cos\psi & \sin\psi & 0\\ -\sin\psi & \cos\psi & 0\\ 0&0&1\end{bmatrix}",
            "sign", _ev_elementary_rotation, r"The same slip is in $\mathbf A^\theta$ and $\mathbf A^\phi$; the "
            r"book's $\mathbf A^\psi$, $\mathbf A^\theta$, $\mathbf A^\phi$ are passive (global → local), the "
            r"transposes of kinbook's active matrices (docs/conventions.md)."),
    Erratum("14.2-A21-row3", r"§14.2, the composed matrix $\mathbf A^{21}$ (both versions), row 3",
            r"[\sin\psi\sin\phi,\ -\cos\psi\sin\phi,\ \cos\theta]",
            r"[\sin\psi\sin\theta,\ -\cos\psi\sin\theta,\ \cos\theta]", "formula", _ev_a21_row3),
    Erratum("14.2-turns-frames", "§14.2, the three turns (second version): the line of the spin",
            r"e^{Z''} = A^\varphi e^{Z'}", r"e^{Z'''} = A^\varphi e^{Z''}", "typo", _ev_turns_frames,
            r"The spin turns the triad $OX'Y''Z''$ that the nutation left, about $Z''$ (the text: $\varphi$ “define el "
            r"triedro $OX_1Y_1Z_1$ respecto al $OX'Y''Z''$”); the first version prints $e^{z'''} = \mathbf A^\phi "
            r"e^{z''}$. As printed, the chain skips $\mathbf A^\theta$ and does not compose to $\mathbf A^{21} = "
            r"\mathbf A^\phi\mathbf A^\theta\mathbf A^\psi$."),
    Erratum("14.2-A-theta-second", r"§14.2, the second (corrected) set of elementary matrices: $\mathbf A^\theta$",
            r"A^\theta = \begin{bmatrix}1&0&0\\ 0&\cos\psi&-\operatorname{sen}\theta\\ 0&\operatorname{sen}\theta&\cos\theta\end{bmatrix}",
            r"A^\theta = \begin{bmatrix}1&0&0\\ 0&\cos\theta&\operatorname{sen}\theta\\ 0&-\operatorname{sen}\theta&\cos\theta"
            r"\end{bmatrix}\ \text{(passive, like the printed } A^\psi, A^\phi\text{)}",
            "formula", _ev_A_theta_second, r"Two slips: $\cos\psi$ stands for $\cos\theta$, and the signs of "
            r"$\sin\theta$ are those of the active turn while the printed $\mathbf A^\psi$ and $\mathbf A^\phi$ "
            r"are passive; with $\cos\theta$ restored but those signs kept, the product $\mathbf A^\phi\mathbf "
            r"A^\theta\mathbf A^\psi$ would be the passive matrix of the opposite nutation $-\theta$ (notebook "
            r"14-2). The second $\mathbf A^{21}$ printed just below is the product of the passive matrices."),
    Erratum("14.2-A21-row2-first", r"§14.2, the first $\mathbf A^{21}$ (printed, before the corrected second set), row 2",
            r"[\,c\psi s\phi - s\psi c\theta c\phi,\ s\psi s\phi + c\psi c\theta c\phi,\ s\theta c\phi\,]",
            r"[\,-c\psi s\phi - s\psi c\theta c\phi,\ -s\psi s\phi + c\psi c\theta c\phi,\ s\theta c\phi\,]",
            "sign", _ev_A21_row2_first, r"The second version prints this row right. (Only a repeated copy of the "
            r"first elementary matrices is struck through in the book; this $\mathbf A^{21}$ is printed.)"),
    Erratum("14.2-omega-matrix", r"§14.2, the matrix relating $\boldsymbol\omega$ to the angle rates (both versions)",
            r"\begin{bmatrix}s\theta & s\phi & c\phi & 0\\ s\theta & c\phi & -s\phi & 0\\ c\theta & 0 & 1 & 1\end{bmatrix}"
            r"\ \text{(a } 3\times 4 \text{ array; the first version has } +s\phi \text{ in row 2 and } c\theta, 0, 0, 1 "
            r"\text{ in row 3)}",
            r"\omega' = \begin{bmatrix}s\theta s\phi & c\phi & 0\\ s\theta c\phi & -s\phi & 0\\ c\theta & 0 & 1\end{bmatrix}\begin{bmatrix}\dot\psi\\ \dot\theta\\ \dot\phi\end{bmatrix}",
            "formula", _ev_omega_matrix, r"$\sin\theta$ is split from $\sin\phi$ and $\cos\phi$ into a column of "
            r"its own; the first version also prints $+\sin\phi$ where $-\sin\phi$ belongs in row 2, and 0, 0 for "
            r"0, 1 in row 3. kinbook.spatial.omega_from_euler_rates(frame='body') is the corrected relation."),
    Erratum("14.2-omega-prime", r"§14.2, the angular velocity from the angle rates (both versions): "
            r"$\omega_1, \omega_2, \omega_3$",
            r"\begin{bmatrix}\omega_1\\ \omega_2\\ \omega_3\end{bmatrix} = \ldots\begin{bmatrix}\dot\psi\\ "
            r"\dot\theta\\ \dot\phi\end{bmatrix}",
            r"\begin{bmatrix}\omega'_1\\ \omega'_2\\ \omega'_3\end{bmatrix} = \ldots\begin{bmatrix}\dot\psi\\ "
            r"\dot\theta\\ \dot\phi\end{bmatrix}", "typo", _ev_omega_prime,
            r"The components are the body's, primed as $\mathbf s'$ is in §14.1; the inverse relations take the "
            r"same $\boldsymbol\omega'$. The global components $\boldsymbol\omega$ need another matrix "
            r"(notebook 14-2)."),
    Erratum("14.2-rates-inverse-first", r"§14.2, the first inverse relation (angle rates from $\boldsymbol\omega'$), row 2",
            r"\dot\theta = \cos\phi\,\omega_1 + \operatorname{sen}\phi\,\omega_2",
            r"\dot\theta = \cos\phi\,\omega_1 - \operatorname{sen}\phi\,\omega_2", "sign", _ev_rates_inverse_first,
            "The second version prints it right; kinbook.spatial.euler_rates_from_omega(frame='body')."),
    Erratum("14.3-A-of-p", r"§14.3, $\mathbf A$ in terms of the Euler parameters",
            r"\begin{bmatrix}e_0^2+e_1^2-\tfrac12 & e_1e_2-e_0e_3 & e_1e_3-e_0e_2\\ e_1e_2-e_0e_3 & e_0^2+e_2^2-\tfrac12 & "
            r"e_2e_3-e_0e_1\\ e_1e_3-e_0e_2 & e_2e_3-e_0e_1 & e_0^2+e_3^2-\tfrac12\end{bmatrix}",
            r"2\begin{bmatrix}e_0^2+e_1^2-\tfrac12 & e_1e_2-e_0e_3 & e_1e_3+e_0e_2\\ e_1e_2+e_0e_3 & e_0^2+e_2^2-\tfrac12 & e_2e_3-e_0e_1\\ e_1e_3-e_0e_2 & e_2e_3+e_0e_1 & e_0^2+e_3^2-\tfrac12\end{bmatrix}",
            "formula", _ev_A_of_p, r"Two kinds of slip: the factor 2 is missing, and three signs — $a_{13}$, "
            r"$a_{21}$ and $a_{32}$ need $+e_0$ terms (the printed matrix is symmetric, which a rotation is not in "
            r"general)."),
    Erratum("14.3-p-from-A", "§14.3, Definición…, the Euler parameters from the direction cosines",
            r"t = 2(3e_0^2 + e_1^2 + e_2^2 + e_3^2) - 3,\quad e_0^2 = \frac{p+1}{4}",
            r"t = \operatorname{tr}\mathbf A = a_{11} + a_{22} + a_{33},\quad e_0^2 = \frac{t+1}{4}",
            "formula", _ev_p_from_A_recipe,
            r"Two slips in the recipe: $e_0^2$ is printed with a $p$ (undefined there) for $t$, and $t$ is defined "
            r"through the parameters being sought; it is the same number as $\operatorname{tr}\mathbf A$, which is "
            r"what the recipe must compute from the known matrix. With $e_0 \neq 0$, the condition the book "
            r"states, its division by $4e_0$ is right; kinbook's p_from_A also covers $e_0 = 0$ (every half turn) "
            r"by starting from the largest of $e_0^2, \dots, e_3^2$."),
    Erratum("14.3-p-dot", "§14.3, Derivadas…, first lines",
            r"\mathbf p^T\mathbf p = e_0^2 + e_1^2 + e_2^2 + e_3^2 \ \Rightarrow\ \mathbf p^T\dot{\mathbf p} = 0",
            r"\mathbf p^T\mathbf p = 1 \ \Rightarrow\ (\text{differentiating})\ \mathbf p^T\dot{\mathbf p} = 0",
            "wording", None, "The conclusion is stated before the derivative that gives it."),
    Erratum("14.3-A-ddot-a", r"§14.3, Derivadas…, the last formula ($\ddot{\mathbf A}$ applied to a vector)",
            r"\ddot A\bar a = 2\dot E\dot G^T a + 2E\ddot a", r"\ddot A a = 2\dot E\dot G^T a + 2E\bar a\,\ddot{\mathbf p}",
            "formula", _ev_A_ddot_a, r"The vector on the left is $\mathbf a$, not $\bar{\mathbf a}$, and "
            r"$\ddot{\mathbf a}$ (the second derivative of a constant vector: zero) stands for $\bar{\mathbf "
            r"a}\ddot{\mathbf p}$; the next paragraph's “sea $\bar{\mathbf a}$ un vector arbitrario” means "
            r"$\mathbf a$."),
    Erratum("14.3-a-bar", r"§14.3, Derivadas…, $\bar{\mathbf a}$ written element by element",
            r"\bar a = \begin{bmatrix}0&-a_1&-a_2&-a_3\\ a_1&0&-a_3&a_2\\ a_2&a_3&0&-a_1\\ a_3&-a_2&a_1&0\end{bmatrix}",
            r"\bar a = \begin{bmatrix}0&-\mathbf a^T\\ \mathbf a&-\tilde{\mathbf a}\end{bmatrix} = \begin{bmatrix}0&-a_1&-a_2&-a_3\\ "
            r"a_1&0&a_3&-a_2\\ a_2&-a_3&0&a_1\\ a_3&a_2&-a_1&0\end{bmatrix}",
            "sign", _ev_a_bar_explicit, r"The block form next to it is printed right (with a stray $\bar{\mathbf "
            r"b}$ for $\tilde{\mathbf a}$); the element-by-element matrix has $+\tilde{\mathbf a}$ in the lower "
            r"right."),
    Erratum("14.3-G-row2", r"§14.3, the matrix $\mathbf G$, row 2", r"[-e_2,\ e_3,\ e_0,\ e_1]", r"[-e_2,\ -e_3,\ e_0,\ e_1]",
            "sign", _ev_G_row2),
    Erratum("14.3-euler-theorem", "§14.3, Definición…, the paragraph that introduces the Euler parameters",
            r"\text{“están basados en que el movimiento instantáneo de un sólido con un punto fijo puede definirse por "
            r"medio de una rotación instantánea alrededor de un eje”}",
            r"\text{Euler's theorem: any orientation of a body with a fixed point is reached by one finite rotation, by "
            r"an angle } \alpha \text{ about an axis } \vec u",
            "wording", None, r"The Euler parameters describe that finite rotation ($e_0 = \cos\frac{\alpha}{2}$, "
            r"$[e_1, e_2, e_3]^T = \mathbf u\sin\frac{\alpha}{2}$), as the next paragraphs say — an orientation, "
            r"not the instantaneous motion. The instantaneous rotation axis is the direction of "
            r"$\boldsymbol\omega$, which the parameters' rates give ($\boldsymbol\omega' = 2\mathbf G\dot{\mathbf "
            r"p}$)."),
    Erratum("14.3-Ep-Gp", r"§14.3, Propiedades…, the identities $\mathbf E\mathbf p = \mathbf G\mathbf p = \mathbf 0$",
            r"\frac{Ep}{Gp} = 0,\quad Ep = -e_1e_0 + e_0e_1 - e_3e_2 + e_2e_3 = 0",
            r"\mathbf E\mathbf p = \mathbf 0,\ \mathbf G\mathbf p = \mathbf 0\ (3\text{-vectors; the printed sum is row 1 of } "
            r"\mathbf E\mathbf p)", "wording", None, r"A fraction bar stands for “and”, and the check computes one "
            r"row of the three as if it were all of $\mathbf E\mathbf p$."),
]


# ------------------------------------------------------------------------------------------- §14.4 evidence
def _ev_14_4_pair(joint, points, vectors, seed, count=20):
    """A two-body spatial mechanism with one §14.4 constraint ``joint`` (bodies "i", "j") and ``count`` seeded
    random configurations (random r, unit p; not assembled) as (q, r_i, A_i, r_j, A_j)."""
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
    s_i, B_i, B_j = np.array([0.3, -0.8, 0.5]), np.array([1.2, 0.4, -0.3]), np.array([-0.6, 0.9, 0.7])
    c = Normal2("i", "j", vector_i=tuple(s_i), point_i="B", point_j="B")
    m, states = _ev_14_4_pair(c, {"i": {"B": B_i}, "j": {"B": B_j}}, {}, 144)
    rows = []
    for q, r_i, A_i, r_j, A_j in states:
        # printed: s_iᵀ A_iᵀ (r_j + A_j s_j^B − r_i − A_i s_i^B), unprimed vectors having global components
        printed = (A_i @ s_i) @ A_i.T @ (r_j + A_j @ (A_j @ B_j) - r_i - A_i @ (A_i @ B_i))
        corrected = s_i @ A_i.T @ (r_j + A_j @ B_j - r_i - A_i @ B_i)
        rows.append((printed, corrected, m.Phi(q)[c.rows][0]))
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random configurations the printed $\Phi^{{(n2,1)}}$, read with global $\mathbf s_i$, "
                    rf"$\mathbf s_i^B$, $\mathbf s_j^B$ ($\mathbf s = \mathbf A\mathbf s'$), differs from kinbook's "
                    rf"normal-2 row by up to {e_p:.3f}; with the local $\mathbf s'_i$, $\mathbf s_i'^B$, "
                    rf"$\mathbf s_j'^B$ it {agrees(e_c)}.", e_p, e_c)


def _ev_14_4_p1_transpose():
    s_i, s_j = np.array([0.3, -0.8, 0.5]), np.array([-0.6, 0.9, 0.7])
    ps = _unit_ps(40, seed=144)
    rows = []
    for p_i, p_j in zip(ps[:20], ps[20:]):
        A_i, A_j = A_from_p(p_i), A_from_p(p_j)
        reference = skew(A_i @ s_i) @ (A_j @ s_j)  # s̃_i s_j in global components
        printed = A_i @ skew(s_i).T @ A_i.T @ A_j @ s_j  # primes restored, the transpose kept
        corrected = A_i @ skew(s_i) @ A_i.T @ A_j @ s_j
        rows.append((printed, corrected, reference))
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random pairs of orientations $\mathbf A_i\tilde{{\mathbf s}}_i'^T\mathbf A_i^T\mathbf A_j"
                    rf"\mathbf s'_j$ differs from $\tilde{{\mathbf s}}_i\mathbf s_j$ by up to {e_p:.3f} (it equals "
                    rf"$-\tilde{{\mathbf s}}_i\mathbf s_j$, because $\tilde{{\mathbf s}}^T = -\tilde{{\mathbf s}}$); "
                    rf"$\mathbf A_i\tilde{{\mathbf s}}'_i\mathbf A_i^T\mathbf A_j\mathbf s'_j$ {agrees(e_c)}.",
                    e_p, e_c)


def _ev_14_4_p1_two_rows():
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
    e_p, e_c = compare(rows)
    return Evidence(rf"With $\mathbf s_i$ along $X$ and $\mathbf s_j$ turned 10°…170° about $Z$, rows 1-2 of "
                    rf"$\tilde{{\mathbf s}}_i\mathbf s_j$ are both 0 although $|\mathbf s_i \times \mathbf s_j|$ reaches "
                    rf"{e_p:.3f}: they miss the whole misalignment. The norm of kinbook's two rows "
                    rf"$\mathbf h_1^T\mathbf s_j$, $\mathbf h_2^T\mathbf s_j$ equals $|\mathbf s_i \times \mathbf s_j|$: "
                    rf"it {agrees(e_c)}.", e_p, e_c)


def _ev_14_4_universal_primes():
    P_i, P_j = np.array([1.5, -0.2, 0.4]), np.array([-0.7, 0.3, 1.1])
    c = Universal("i", "j", vector_i=(0, 1, 0), vector_j=(1, 0, 0), point="P")
    m, states = _ev_14_4_pair(c, {"i": {"P": P_i}, "j": {"P": P_j}}, {}, 146)
    rows = []
    for q, r_i, A_i, r_j, A_j in states:
        reference = m.Phi(q)[c.rows][:3]
        printed = r_i + A_i @ (A_i @ P_i) - A_j @ (A_j @ P_j) - r_j  # s_i^P, s_j^P global: s^P = A s'^P
        corrected = r_i + A_i @ P_i - A_j @ P_j - r_j
        rows.append((printed, corrected, reference))
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random configurations the printed $\Phi^{{(s,3)}}$ of the universal joint, read with global "
                    rf"$\mathbf s_i^P$, $\mathbf s_j^P$ as the spherical-joint section defines them, differs from "
                    rf"kinbook's first three rows by up to {e_p:.3f}; with $\mathbf s'^P_i$, $\mathbf s'^P_j$ it "
                    rf"{agrees(e_c)}.", e_p, e_c)


def _ev_14_4_revolute_tilde():
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
    return Evidence(rf"As printed, $\mathbf A_i\mathbf s'_i\mathbf A_i^T\mathbf A_j\mathbf s'_j$ multiplies a $3\times1$ "
                    rf"column by a $3\times3$ matrix: it is not defined (sympy raises ShapeError). At an assembled "
                    rf"revolute joint (kinbook's five rows: $\max|\Phi|$ {below(joint)}), the form with the tilde, "
                    rf"$\mathbf A_i\tilde{{\mathbf s}}'_i\mathbf A_i^T\mathbf A_j\mathbf s'_j$, has $\max|\cdot|$ "
                    rf"{below(corrected)}.",
                    printed, max(corrected, joint))


# §14.4, constraints between two bodies (chapters/14-4-spatial-constraints.ipynb)
ERRATA += [
    Erratum("14.4-n2-vectors", r"§14.4, Vectores perpendiculares: the sentence before $\Phi^{(n2,1)}$",
            r"\text{“Si dos vectores como el } s_i^T \text{ y el } d \text{ en la figura 14.9 …”}",
            r"\text{“Si dos vectores como el } \vec s_i \text{ y el } \vec d \text{ en la figura 14.9 …”}", "wording",
            note=r"The vectors of the figure are $\vec s_i$ and $\vec d$ (the paragraph before names the pair "
                 r"$\vec s_i$, $\vec s_j$); $\mathbf s_i^T$ is the row that enters their scalar product "
                 r"$\mathbf s_i^T\mathbf d$, not a vector."),
    Erratum("14.4-n2-primes", r"§14.4, Vectores perpendiculares: $\Phi^{(n2,1)}$ in local components",
            r"\Phi^{(n2,1)} = s_i^T A_i^T (r_j + A_j s_j^B - r_i - A_i s_i^B)",
            r"\Phi^{(n2,1)} = s_i'^T A_i^T (r_j + A_j s_j'^B - r_i - A_i s_i'^B)",
            "typo", _ev_14_4_n2_primes, r"The primes of the three local vectors are missing; the n1 formula "
            r"just above ($\mathbf s_i'^T\mathbf A_i^T\mathbf A_j\mathbf s'_j$) has them."),
    Erratum("14.4-p1-local-form", r"§14.4, Vectores paralelos: $\Phi^{(p1,2)}$ in local components",
            r"\tilde s_i s_j = A_i \tilde s_i^T A_i^T A_j s_j^B",
            r"\tilde s_i s_j = A_i \tilde s_i' A_i^T A_j s_j'", "formula", _ev_14_4_p1_transpose,
            r"The tilde is transposed ($\tilde{\mathbf s}^T = -\tilde{\mathbf s}$), the primes are missing and a "
            r"stray superscript $B$ appears. Set to zero, $-\tilde{\mathbf s}_i\mathbf s_j = \mathbf 0$ is the "
            r"same constraint, but the identity is wrong. $\Phi^{(p2,2)}$ below is printed right."),
    Erratum("14.4-p1-two-rows", r"§14.4, Vectores paralelos: which two rows of $\tilde{\mathbf s}_i\mathbf s_j = \mathbf 0$",
            r"\text{the third row is a linear combination of the first two}",
            r"s_{ix}(\tilde s_i s_j)_1 + s_{iy}(\tilde s_i s_j)_2 + s_{iz}(\tilde s_i s_j)_3 = 0:\ "
            r"\text{row 3 follows from rows 1-2 only if } s_{iz} \neq 0",
            "formula", _ev_14_4_p1_two_rows, r"Which row is redundant depends on the orientation of $\mathbf s_i$, "
            r"and it changes as the mechanism moves. kinbook writes p1 and p2 as $\mathbf h_1^T\mathbf s_j = "
            r"\mathbf h_2^T\mathbf s_j = 0$ with $\mathbf h_1, \mathbf h_2 \perp \mathbf s'_i$ fixed in body $i$ "
            r"(docs/conventions.md), two rows that stay independent in every orientation."),
    Erratum("14.4-universal-primes", r"§14.4, Junta universal: $\Phi^{(s,3)}$",
            r"r_i + A_i s_i^P - A_j s_j^P - r_j", r"r_i + A_i s_i'^P - A_j s_j'^P - r_j",
            "typo", _ev_14_4_universal_primes, "The spherical-joint section just before prints it with the primes."),
    Erratum("14.4-revolute-tilde", r"§14.4, Junta de revolución: $\Phi^{(p1,2)}$ in local components",
            r"A_i s_i' A_i^T A_j s_j' = 0", r"A_i \tilde s_i' A_i^T A_j s_j' = 0",
            "typo", _ev_14_4_revolute_tilde, "Without the tilde the product is undefined (3×1 times 3×3)."),
]

# ------------------------------------------------------------------------------------------- §14.5 evidence


def _ev_14_5_n1_states(seed, tangent):
    """A pair of free bodies with one normal-1 constraint (random local vectors a_i, a_j) and 20 random states
    (q with unit p, q̇, q̈), each with the book's quantities. ``tangent``: ṗ ⊥ p and pᵀp̈ = −ṗᵀṗ, as on a
    motion."""
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
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random states on the unit sphere ($\mathbf p^T\dot{{\mathbf p}} = 0$, $\mathbf p^T"
                    rf"\ddot{{\mathbf p}} = -\dot{{\mathbf p}}^T\dot{{\mathbf p}}$) the printed relation, "
                    rf"$2\mathbf s_j^T\mathbf E_i\bar{{\mathbf s}}'_i\dot{{\mathbf p}}_i + 2\mathbf s_i^T\mathbf E_j"
                    rf"\bar{{\mathbf s}}'_j\dot{{\mathbf p}}_j - 2(\mathbf s_j^T\dot{{\mathbf E}}_i\dot{{\mathbf G}}_i^T"
                    rf"\mathbf s'_i + \mathbf s_i^T\dot{{\mathbf E}}_j\dot{{\mathbf G}}_j^T\mathbf s'_j + "
                    rf"\dot{{\mathbf s}}_i^T\dot{{\mathbf s}}_j)$ ($\dot{{\mathbf G}}$ read as $\dot{{\mathbf G}}^T$: "
                    rf"$\dot{{\mathbf G}}\mathbf s'$ is undefined), differs from $\ddot\Phi = \boldsymbol\Phi_"
                    rf"{{\mathbf q}}\ddot{{\mathbf q}} - \gamma$ by up to {e_p:.3f}; with $\ddot{{\mathbf p}}$ for "
                    rf"$\dot{{\mathbf p}}$ and the right-hand side's sign changed it {agrees(e_c)}.",
                    e_p, e_c)


def _ev_14_5_gamma_n1_table():
    rows = [(-b["rhs"], -b["rhs"] - b["extra"], b["gamma"]) for b in _ev_14_5_n1_states(1452, tangent=False)]
    e_p, e_c = compare(rows)
    return Evidence(rf"At 20 random states the book's right-hand side, $-2(\mathbf s_j^T\dot{{\mathbf E}}_i"
                    rf"\dot{{\mathbf G}}_i^T\mathbf s'_i + \mathbf s_i^T\dot{{\mathbf E}}_j\dot{{\mathbf G}}_j^T"
                    rf"\mathbf s'_j + \dot{{\mathbf s}}_i^T\dot{{\mathbf s}}_j)$ (misprints of §14.5's n1 equation "
                    rf"corrected), differs from kinbook's $\gamma$ — the one that goes with Table 14.1's "
                    rf"$\boldsymbol\Phi_{{\mathbf p}} = 2\mathbf s_j^T(\mathbf E_i\bar{{\mathbf s}}'_i + \mathbf s'_i"
                    rf"\mathbf p_i^T)$ — by up to {e_p:.3f}; adding $-2(\mathbf s_j^T\mathbf s'_i)\dot{{\mathbf p}}_i^T"
                    rf"\dot{{\mathbf p}}_i - 2(\mathbf s_i^T\mathbf s'_j)\dot{{\mathbf p}}_j^T\dot{{\mathbf p}}_j$ it "
                    rf"{agrees(e_c)}.", e_p, e_c)


# §14.5, spatial kinematic analysis (chapters/14-5-spatial-analysis.ipynb)
ERRATA += [
    Erratum("14.5-cross-references", r"§14.5, opening paragraph, the $\boldsymbol\Phi_{\mathbf p}$ derivation and the $\gamma$ paragraph",
            r"\text{“apartado 211.5” (twice), “apartado 3.3” (once)}",
            r"\text{chapter 13 (§13.5–13.8) for the planar analysis; §14.3 for } \partial(Aa)/\partial p "
            r"\text{ and } \ddot A a", "wording", None,
            r"The book has no §211.5 or §3.3 (numbers left from another edition): the planar analysis is chapter "
            r"13, the Euler-parameter formulas are in §14.3. (A second “apartado 3.3”, before $\ddot{\mathbf "
            r"A}\mathbf a$, is in a passage the book strikes through.)"),
    Erratum("14.5-n1-rj", r"§14.5, Jacobian of $\Phi^{(n1,1)}$, the sentence before $\Phi^{(n1,1)}_{\mathbf r_j}$ and $\Phi^{(n1,1)}_{\mathbf p_j}$",
            r"\text{“respecto a } r_i \text{ y } p_j\text{”}", r"\text{with respect to } r_j \text{ and } p_j",
            "wording"),
    Erratum("14.5-A-ddot-a", r"§14.5, $\ddot{\mathbf A}\mathbf a$ recalled from §14.3 for $\gamma$ of $\Phi^{(n1,1)}$: the displayed formula",
            r"\ddot A a = 2\dot E\dot G^T a + 2E\ddot a\,\ddot p", r"\ddot A a = 2\dot E\dot G^T a + 2E\bar a\,\ddot p",
            "formula", _ev_A_ddot_a, r"$\ddot{\mathbf a}$ (the second derivative of a constant vector: zero) "
            r"stands for $\bar{\mathbf a}$; the §14.3 version also drops $\ddot{\mathbf p}$ (notebook 14-3). The "
            r"sentences that introduce the formula are struck through in the book; the formula itself is printed."),
    Erratum("14.5-gamma-n1", r"§14.5, the acceleration equation of $\Phi^{(n1,1)}$",
            r"[2s_j^TE_i\bar s'_i,\ 2s_i^TE_j\bar s'_j]\begin{bmatrix}\dot p_i\\ \dot p_j\end{bmatrix} = "
            r"2(s_j^T\dot E_i\dot G_i s'_i + s_i^T\dot E_j\dot G_j s'_j + \dot s_i^T\dot s_j)",
            r"[2s_j^TE_i\bar s'_i,\ 2s_i^TE_j\bar s'_j]\begin{bmatrix}\ddot p_i\\ \ddot p_j\end{bmatrix} = "
            r"-2(s_j^T\dot E_i\dot G_i^T s'_i + s_i^T\dot E_j\dot G_j^T s'_j + \dot s_i^T\dot s_j)",
            "formula", _ev_14_5_gamma_n1,
            r"Three slips: $\dot{\mathbf p}$ for $\ddot{\mathbf p}$, $\dot{\mathbf G}$ for $\dot{\mathbf G}^T$ "
            r"($\dot{\mathbf G}\mathbf s'$ is undefined) and the sign of the right-hand side (the book's own line "
            r"before, $\mathbf s_j^T\ddot{\mathbf A}_i\mathbf s'_i + \mathbf s_i^T\ddot{\mathbf A}_j\mathbf s'_j + "
            r"2\dot{\mathbf s}_i^T\dot{\mathbf s}_j = 0$, gives the minus)."),
    Erratum("14.5-gamma-n1-table", r"§14.5, “es necesario obtener el vector $\gamma$. Veamos como serían los pasos para su "
            r"obtención … normal tipo 1”: the $\gamma$ those steps end with",
            r"\gamma^{(n1,1)} = -2(s_j^T\dot E_i\dot G_i^T s'_i + s_i^T\dot E_j\dot G_j^T s'_j + \dot s_i^T\dot s_j)"
            r"\ \text{(misprints of 14.5-gamma-n1 corrected)}",
            r"\gamma^{(n1,1)} = -2(s_j^T\dot E_i\dot G_i^T s'_i + s_i^T\dot E_j\dot G_j^T s'_j + \dot s_i^T\dot s_j)"
            r" - 2(s_j^Ts'_i)\,\dot p_i^T\dot p_i - 2(s_i^Ts'_j)\,\dot p_j^T\dot p_j",
            "formula", _ev_14_5_gamma_n1_table,
            r"The equation's row $2\mathbf s_j^T\mathbf E_i\bar{\mathbf s}'_i$ is the derivative of $\mathbf "
            r"E\mathbf G^T\mathbf s'_i$, not Table 14.1's $\boldsymbol\Phi_{\mathbf p_i} = 2\mathbf s_j^T(\mathbf "
            r"E_i\bar{\mathbf s}'_i + \mathbf s'_i\mathbf p_i^T)$, the derivative of the $\mathbf A$ the "
            r"constraint uses. With Table 14.1's $\boldsymbol\Phi_{\mathbf q}$ the normalization rows force "
            r"$\mathbf p^T\ddot{\mathbf p} = -\dot{\mathbf p}^T\dot{\mathbf p}$, so $\boldsymbol\Phi_{\mathbf "
            r"q}\ddot{\mathbf q} = \gamma$ needs the $\dot{\mathbf p}^T\dot{\mathbf p}$ terms; without them the "
            r"accelerations are wrong whenever $\mathbf s_j^T\mathbf s'_i$ or $\mathbf s_i^T\mathbf s'_j \neq 0$."),
]
