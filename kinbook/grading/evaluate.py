"""Evaluating the answer and the reference at the samples (third stage of a check).

The answer (a :class:`~kinbook.grading.read.Answer`) is evaluated at the target's sample instants, shaped
as the quantity asks (a column of m rows for Φ, ν and γ; m rows of the constraint's body columns or of all
n columns for Φ_q), and put beside kinbook's reference from the numeric kernels. Nothing is derived
symbolically: a student's own Φ (for error carried forward) is differentiated by the jets of its tape, or by
finite differences when it is a function.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._i18n import Msg
from .factors import starts
from .quantities import quantity_of
from .read import Refused

__all__ = ["PhiData", "DerivedData", "phi_data", "derived_data", "orient"]


@dataclass
class Block:
    """An answer Φ and the reference rows of *one* constraint at that constraint's own assembled samples (its
    rows and the bodies' normalization rows hold there, nothing else): where its rows are judged.

    Attributes
    ----------
    refs : list of int
        The constraint's rows (positions among the graded rows).
    S, gS : ndarray (N, ms), (N, ms, n)
        Every answer row and its gradient there.
    gR : ndarray (N, len(refs), n)
        Gradients of the constraint's reference rows there.
    F : ndarray (N, f, n)
        Gradients of the rows that hold anyway there (the bodies' normalization rows).
    target : Target
        The constraint graded alone (its samples, its reference).
    """

    refs: list
    S: np.ndarray
    gS: np.ndarray
    gR: np.ndarray
    F: np.ndarray
    on_manifold: bool
    target: object


@dataclass
class PhiData:
    """An answer Φ and the reference at the generic (G) and assembled (M) samples; ``blocks[i]`` are the rows of
    the target's i-th constraint and ``block(i)`` (computed when first asked) its :class:`Block`."""

    S_G: np.ndarray
    S_M: np.ndarray
    R_G: np.ndarray
    R_M: np.ndarray
    gR_M: np.ndarray
    F_M: np.ndarray
    grads: object  # callable: "assembled" | "generic" -> (N, ms, n)
    on_manifold: bool
    blocks: list = None
    block: object = None  # callable: i -> Block
    block_cols: list = None  # per constraint, a mask (n,) of its bodies' coordinates
    together: object = None  # callable: list of constraint indices -> the answer (N, ms) where only they hold
    search: object = None  # callable: (constraint index, answer rows) -> (Q, T, its reference rows) at their zeros
    book: object = None  # callable: constraint index -> the book's own rows of it at the generic samples, or None
    gR_G: np.ndarray = None  # gradients of the reference rows at the generic samples
    S_W: np.ndarray = None  # the answer at the generic samples over the whole domain (NaN where not defined)
    R_W: np.ndarray = None  # the reference there


@dataclass
class DerivedData:
    """An answer Φ_q, ν or γ and the reference at the assembled samples; ``cols`` are the coordinates of Φ_q's
    columns in the answer's order; ``transposed`` when the answer was given n × m."""

    S: np.ndarray
    R: np.ndarray
    cols: list
    transposed: bool = False


def _finite(S, target, what):
    bad = ~np.isfinite(S)
    if bad.any():
        k = int(np.argwhere(bad.reshape(bad.shape[0], bad.shape[1], -1).any(axis=(0, 2)))[0][0])
        raise Refused("not_finite", "not_finite", where=_row_where(target, k, S.shape[1]))


def _row_where(target, k, ms):
    return Msg("your_row", k=k + 1)


def column(V, target, what):
    """Values (N, r, c) of a vector quantity as (N, r): a row vector is accepted for a column."""
    if V.ndim == 3 and V.shape[2] == 1:
        return V[:, :, 0]
    if V.ndim == 3 and V.shape[1] == 1:
        return V[:, 0, :]
    raise Refused("wrong_shape", "wrong_shape", expected=f"({target.m},)", got=tuple(V.shape[1:]))


def phi_data(target, answer):
    """Evaluate an answer Φ at both sample sets."""
    G, M = target.samples("generic"), target.samples("assembled")
    S_G = column(answer.values(target, G), target, "Phi")
    _finite(S_G[:, :, None], target, "Phi")
    S_M = column(answer.values(target, M), target, "Phi")
    _finite(S_M[:, :, None], target, "Phi")
    RG, RM = target.reference("generic"), target.reference("assembled")
    cache = {}

    def grads(which):
        if which not in cache:
            s = G if which == "generic" else M
            g = answer.gradient(target, s)
            cache[which] = np.where(np.isfinite(g), g, 0.0)
        return cache[which]

    blocks = [target.block(c) for c in target.constraints]
    made = {}

    def block(i):
        if i not in made:
            made[i] = _block(target, answer, i, blocks[i], S_M, grads, RM)
        return made[i]

    ncoord = len(target.mech.COORDS)
    cols = []
    for c in target.constraints:
        mask = np.zeros(target.n, bool)
        for b in c.bodies:
            mask[ncoord * (b.number - 1): ncoord * b.number] = True
        cols.append(mask)
    def together(indices):
        from .target import group_target  # import time: grading.target loads sympy

        g = group_target(target.mech, [target.constraints[i] for i in indices])
        s = g.samples("assembled")
        return column(answer.values(target, s), target, "Phi") if s.on_manifold else None

    def search(i, ks, k=None):
        """Where the answer rows ``ks`` (those of constraint i) vanish together — from the seeded starts of
        :func:`~kinbook.grading.sample.zeros`, or (``k`` given) from the zeros of row k's factors over the whole
        domain (:mod:`~kinbook.grading.factors`) — with the reference rows of constraint i there, at the
        placement (a turn of 2π, −p) where they are least."""
        from .sample import Samples, placements, zeros  # import time: grading.sample loads sympy

        own = target.own_target(target.constraints[i])

        def F(Q, T):
            v, g, d = answer.jet(target, Q, T)
            return v[:, ks], np.where(np.isfinite(g[:, ks]), g[:, ks], 0.0), d[:, ks]

        first = None
        if k is not None:
            first = starts(target, answer, k, cols=np.flatnonzero(cols[i]))
            if not len(first[0]):
                return None
        Q, T = zeros(own, F, starts=first)
        if not len(Q):
            return None
        PQ, PT = placements(own, Q, T, np.flatnonzero(cols[i]))
        ref = own.evaluate(Samples(PQ, np.zeros_like(PQ), PT))["Phi"]
        periods = np.array([own.wrap.get(j, own.turns.get(j, 0.0)) for j in range(ref.shape[1])])
        wrapped = np.where(periods > 0, (ref + periods / 2) % np.where(periods > 0, periods, 1.0) - periods / 2, ref)
        P = len(PQ) // len(Q)
        size = np.abs(wrapped).max(axis=1).reshape(len(Q), P)
        best = np.argmin(size, axis=1)
        # another placement only where it makes the reference smaller, not by rounding (cos 40 vs cos(40 − 4π))
        best = np.where(size[np.arange(len(Q)), best] < 0.5 * size[:, 0], best, 0) + P * np.arange(len(Q))
        return PQ[best], PT[best], wrapped[best]

    def book(i):
        from .mistakes import book_form  # import time: grading.mistakes loads sympy

        return book_form(target, target.constraints[i])

    W = target.samples("wide")
    try:
        with np.errstate(all="ignore"):
            S_W = column(answer.values(target, W), target, "Phi")
    except Refused:  # a function that cannot be read there: the multiples stand as at the generic samples
        S_W = np.full((W.N, S_G.shape[1]), np.nan)
    return PhiData(S_G, S_M, RG["Phi"], RM["Phi"], RM["Phi_q"], RM["free_q"], grads, M.on_manifold, blocks, block,
                   cols, together, search, book, RG["Phi_q"], np.where(np.isfinite(S_W), S_W, np.nan),
                   target.reference("wide")["Phi"])


def _block(target, answer, i, refs, S_M, grads, RM):
    own = target.own_target(target.constraints[i])
    if own is target:  # a constraint graded alone: its samples are the target's
        return Block(refs, S_M, grads("assembled"), RM["Phi_q"][:, refs, :], RM["free_q"], target.samples(
            "assembled").on_manifold, target)
    s = own.samples("assembled")
    S = column(answer.values(target, s), target, "Phi")
    gS = answer.gradient(target, s)
    ref = own.reference("assembled")
    S = np.where(np.isfinite(S), S, np.nan)
    return Block(refs, S, np.where(np.isfinite(gS), gS, 0.0), ref["Phi_q"], ref["free_q"], s.on_manifold, own)


def orient(V, target, quantity):
    """Values (N, r, c) of Φ_q shaped (N, rows, columns): returns (V, transposed)."""
    sub, n = len(target.cols), target.n
    r, c = V.shape[1:]
    if c in (sub, n):
        return V, False
    if r in (sub, n):
        return np.swapaxes(V, 1, 2), True
    raise Refused("wrong_shape", "wrong_shape", expected=f"({target.m}, {sub})" if sub != n else f"({target.m}, {n})",
                  got=(r, c))


def best_columns(target, S, R_full, rtol):
    """Columns of a single constraint's Φ_q: its bodies in role order (i, j, k — the book's tables) or in the
    mechanism's order, whichever the answer follows better."""
    roles = list(target.cols)
    ordered = sorted(roles)
    if ordered == roles or S.shape[2] != len(roles):
        return roles if S.shape[2] == len(roles) else list(range(target.n))

    def fit(cols):
        Rc = R_full[:, :, cols]
        k = min(S.shape[1], Rc.shape[1])
        d = np.abs(S[:, :k] - Rc[:, :k])
        return int(np.sum(np.all(d <= rtol * (np.abs(Rc[:, :k]).max(axis=0) + 1e-12), axis=0)))

    return ordered if fit(ordered) > fit(roles) else roles


def derived_data(target, answer, quantity, samples, reference, rtol):
    """Evaluate an answer Φ_q, ν or γ at ``samples`` beside the reference values there."""
    V = answer.values(target, samples)
    if quantity_of(quantity).per_coordinate:
        V, transposed = orient(V, target, quantity)
        _finite(V, target, quantity)
        cols = best_columns(target, V, reference[quantity], rtol)
        return DerivedData(V, reference[quantity][:, :, cols], cols, transposed)
    S = column(V, target, quantity)
    _finite(S[:, :, None], target, quantity)
    return DerivedData(S[:, :, None], reference[quantity][:, :, None], [])
