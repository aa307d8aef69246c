"""The book's misprinted formulas that a student may copy, typed once: the checkers recognise an answer built
from one of them (``book_misprint`` and the errata ids), and :mod:`kinbook.book.errata` shows each beside the
corrected formula as the evidence of its erratum. Never a reference answer: kinbook's own functions are.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..spatial.rotations import A_from_p, E, G, a_bar, dAa_dp

__all__ = ["book_A_of_p", "book_n1_acceleration", "EX4_PHI8"]


_x1, _y1, _phi1, _x3, _y3, _phi3 = sp.symbols("x1 y1 phi1 x3 y3 phi3", real=True)
EX4_PHI8 = ((_x3 + 3 * sp.cos(_phi3) - _x1 * sp.cos(_phi1)) * sp.sin(_phi1)
            + (_y3 + 3 * sp.sin(_phi3) - _y1 - sp.sin(_phi1)) * sp.cos(_phi1))
"""§13.5, example 4's Φ_8 as printed, simplified with the ground's φ_1 = 0 and wrong (erratum 13.5-ex4-phi8), in
kinbook's symbols x1 … of that mechanism (ch13_example4)."""


def book_A_of_p(p):
    """The matrix §14.3 prints for A(p) (erratum 14.3-A-of-p): symmetric, without the factor 2.

    Parameters
    ----------
    p : array_like, shape (4,)
        Euler parameters [e0, e1, e2, e3].

    Returns
    -------
    ndarray, shape (3, 3) — a sympy Matrix when ``p`` holds symbols (a Φ written with the book's A)
    """
    if any(isinstance(x, sp.Basic) and not x.is_Number for x in p):
        e0, e1, e2, e3 = p
        half = sp.Rational(1, 2)
        return sp.Matrix([
            [e0**2 + e1**2 - half, e1 * e2 - e0 * e3, e1 * e3 - e0 * e2],
            [e1 * e2 - e0 * e3, e0**2 + e2**2 - half, e2 * e3 - e0 * e1],
            [e1 * e3 - e0 * e2, e2 * e3 - e0 * e1, e0**2 + e3**2 - half],
        ])
    e0, e1, e2, e3 = np.asarray(p, dtype=float)
    return np.array([
        [e0**2 + e1**2 - 0.5, e1 * e2 - e0 * e3, e1 * e3 - e0 * e2],
        [e1 * e2 - e0 * e3, e0**2 + e2**2 - 0.5, e2 * e3 - e0 * e1],
        [e1 * e3 - e0 * e2, e2 * e3 - e0 * e1, e0**2 + e3**2 - 0.5],
    ])


def book_n1_acceleration(a_i, p_i, pd_i, a_j, p_j, pd_j):
    """§14.5's printed acceleration equation of Φ^(n1,1), as far as it can be read, for local vectors a_i, a_j
    on bodies with Euler parameters p and rates ṗ (any leading batch axes): what the checkers recognise as γ
    copied from the book (errata 14.5-gamma-n1 and 14.5-gamma-n1-table), and what the errata's evidence and
    notebook 14-5 show.

    The book writes [2 s_jᵀE_i s̄'_i, 2 s_iᵀE_j s̄'_j] [ṗ_i; ṗ_j] = 2(s_jᵀĖ_iĠ_i s'_i + s_iᵀĖ_jĠ_j s'_j + ṡ_iᵀṡ_j);
    Ġ s' is undefined and is read as Ġᵀ s'.

    Returns
    -------
    L_i, L_j : ndarray, shape (..., 4)
        The row blocks 2 s_jᵀE_i s̄'_i and 2 s_iᵀE_j s̄'_j.
    rhs : ndarray, shape (...)
        The printed right-hand side.
    extra : ndarray, shape (...)
        2(s_jᵀs'_i)ṗ_iᵀṗ_i + 2(s_iᵀs'_j)ṗ_jᵀṗ_j: what the corrected equation lacks to be γ of Table 14.1's Φ_p.
    """
    def mv(M, v):
        return np.einsum("...ij,...j->...i", M, v)

    def dot(u, v):
        return np.einsum("...i,...i->...", u, v)

    def EGt(pd):  # Ė Ġᵀ
        return E(pd, check=False) @ np.swapaxes(G(pd, check=False), -1, -2)

    a_i, a_j = np.asarray(a_i, dtype=float), np.asarray(a_j, dtype=float)
    s_i, s_j = mv(A_from_p(p_i), a_i), mv(A_from_p(p_j), a_j)
    sd_i, sd_j = mv(dAa_dp(p_i, a_i), pd_i), mv(dAa_dp(p_j, a_j), pd_j)
    L_i = 2 * np.einsum("...i,...ij->...j", s_j, E(p_i) @ a_bar(a_i))
    L_j = 2 * np.einsum("...i,...ij->...j", s_i, E(p_j) @ a_bar(a_j))
    rhs = 2 * (dot(s_j, mv(EGt(pd_i), a_i)) + dot(s_i, mv(EGt(pd_j), a_j)) + dot(sd_i, sd_j))
    extra = 2 * dot(s_j, a_i) * dot(pd_i, pd_i) + 2 * dot(s_i, a_j) * dot(pd_j, pd_j)
    return L_i, L_j, rhs, extra
