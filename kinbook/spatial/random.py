"""Seeded random orientations and states for checks and exercises: unit Euler parameters, and ṗ tangent to the
unit sphere (pᵀṗ = 0) with p̈ that keeps pᵀp = 1 along a motion (pᵀp̈ = −ṗᵀṗ)."""

from __future__ import annotations

import numpy as np

__all__ = ["random_p", "random_p_rates"]


def random_p(count=None, rng=None):
    """Random unit Euler parameters, uniform over rotations.

    Parameters
    ----------
    count : int, optional
        How many; default: one, shape (4,).
    rng : numpy.random.Generator or int, optional
        A generator or a seed (default seed 0: the same p on every run).

    Returns
    -------
    ndarray, shape (4,) or (count, 4)

    >>> p = random_p(3, rng=1); p.shape, bool(np.allclose(np.sum(p * p, axis=1), 1))
    ((3, 4), True)
    """
    rng = np.random.default_rng(0 if rng is None else rng)
    p = rng.normal(size=(1 if count is None else count, 4))
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    return p[0] if count is None else p


def random_p_rates(p, rng=None, scale=1.0):
    """Random ṗ and p̈ that fit the unit sphere at ``p``: pᵀṗ = 0 and pᵀp̈ = −ṗᵀṗ (what the normalization row
    pᵀp − 1 = 0 and its two time derivatives require).

    Returns
    -------
    p_dot, p_ddot : ndarray, same shape as ``p``
    """
    rng = np.random.default_rng(0 if rng is None else rng)
    p = np.asarray(p, dtype=float)
    pd, pdd = scale * rng.normal(size=(2, *p.shape))
    dot = lambda a, b: np.sum(a * b, axis=-1, keepdims=True)  # noqa: E731
    pd = pd - p * dot(p, pd)
    pdd = pdd - p * (dot(p, pdd) + dot(pd, pd))
    return pd, pdd
