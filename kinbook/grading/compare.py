"""Comparing an answer with the reference at the samples: the tolerances and the constant-multiple rule every
stage uses (:mod:`~kinbook.grading.match`, :mod:`~kinbook.grading.equivalence`, the diagnosis).

Everything here works on arrays (samples × rows × columns).
"""

from __future__ import annotations

import numpy as np

__all__ = ["RTOL", "RTOL_NUMBERS", "zero_tol", "nice", "wrapped", "scale_of", "same", "scale_match", "scale_matrix", "turned_multiple",
           "atol_of"]

RTOL = 1e-6
"""Relative tolerance of every comparison of symbolic answers and functions."""
RTOL_NUMBERS = 2e-3
"""Relative tolerance for numbers typed from a calculator (the book prints 4-6 significant digits)."""
_NICE = (1.0, -1.0, 2.0, -2.0, 0.5, -0.5, 3.0, -3.0)


def zero_tol(rtol):
    """Relative size below which a row (or a gradient's residual) is zero where a constraint holds. The samples
    are solved to rounding, so a right row is there ~1e-15 of its size: ``rtol``, and never above 1e-6 whatever
    ``rtol`` the caller chose — a length off by 1 in 10⁴ (1.4999 for 1.5) is not a zero (it was 1e3·rtol, so
    1.49 for 1.5 "held" where the mechanism is assembled and was named a masked row or a vanishing factor)."""
    return min(float(rtol), 1e-6)


def nice(c):
    """``c`` rounded to a simple factor when it is one to rounding (1, −1, 2, ½ …)."""
    for r in _NICE:
        if abs(c - r) < 1e-9 * max(1.0, abs(c)):
            return r
    return float(c)


def scale_of(a):
    """Magnitude of a row over the samples (max |value|)."""
    return float(np.max(np.abs(a))) if a.size else 0.0


def wrapped(x, period):
    """``x`` wrapped into [−period/2, period/2)."""
    return (x + period / 2) % period - period / 2


def same(a, b, rtol, period=None):
    """a ≈ b entry-wise over all samples, relative to the larger magnitude of the two."""
    d = a - b
    if period:
        d = wrapped(d, period)
    scale = max(scale_of(a), scale_of(b))
    return bool(np.all(np.abs(d) <= rtol * scale + 1e-12 * max(scale, 1.0) * rtol))


def scale_match(a, b, rtol, free=True, period=None, atol=0.0, zeros=False):
    """The constant c ≠ 0 with a ≈ c·b at every sample (arrays of shape (N,) or (N, w)), or None.

    ``free``: any constant; otherwise only c = 1. A ``period`` (a wrapped angle row) allows c = ±1 only,
    compared modulo the period. ``atol``: differences this small are zero. ``zeros``: a reference row that is
    zero at every sample is matched (c = 1) by an answer row that is zero too.
    """
    if period:
        for c in ((1.0, -1.0) if free else (1.0,)):
            if same(a, c * b, rtol, period):
                return c
        return None
    sb = scale_of(b)
    if sb <= atol:
        return 1.0 if zeros and scale_of(a) <= max(atol, 1e-12) else None
    if not free:
        d = np.max(np.abs(a - b))
        return 1.0 if d <= rtol * max(scale_of(a), sb) + atol else None
    bb = float(np.sum(b * b))
    c = float(np.sum(a * b)) / bb
    if c == 0 or not np.isfinite(c):
        return None
    if np.max(np.abs(a - c * b)) <= rtol * max(scale_of(a), abs(c) * sb) + atol:
        return nice(c)
    return None


def scale_matrix(S, R, rtol, free=True, wrap=None, atol=0.0, zeros=False, turns=None):
    """Constants C[k, j] with S[:, k] ≈ C·R[:, j] (NaN where there is none). S (N, ms, …), R (N, m, …).

    Vectorized over all pairs (the rule of :func:`scale_match`); wrapped rows are compared one by one. ``turns``
    ({reference row: period}, the rows that measure an angle): an answer row that is no multiple of such a row
    is still a multiple of it (c = 1 only, unless ``free``) turned by the same whole number of periods at every
    sample (:func:`turned_multiple`)."""
    wrap = wrap or {}
    ms, m = S.shape[1], R.shape[1]
    A = np.moveaxis(S, 1, 0).reshape(ms, -1)
    B = np.moveaxis(R, 1, 0).reshape(m, -1)
    sa, sb = np.abs(A).max(axis=1), np.abs(B).max(axis=1)
    C = np.full((ms, m), np.nan)
    with np.errstate(all="ignore"):
        if free:
            c = (A @ B.T) / np.sum(B * B, axis=1)[None, :]
        else:
            c = np.ones((ms, m))
        res = np.abs(A[:, None, :] - c[:, :, None] * B[None, :, :]).max(axis=2)
        tol = rtol * np.maximum(sa[:, None], np.abs(c) * sb[None, :]) + atol
        if not free:
            tol = rtol * np.maximum(sa[:, None], sb[None, :]) + atol
    ok = (res <= tol) & (sb[None, :] > atol) & np.isfinite(c) & (c != 0)
    C[ok] = c[ok]
    if zeros:
        both = (sb[None, :] <= atol) & (sa[:, None] <= max(atol, 1e-12))
        C[both] = 1.0
    for j, period in wrap.items():
        for k in range(ms):
            cc = scale_match(S[:, k], R[:, j], rtol, free, period, atol, zeros)
            C[k, j] = np.nan if cc is None else cc
    for j, period in (turns or {}).items():
        c, n = turned_multiple(A, B[j], rtol, period, free)
        fill = (n != 0) & np.isnan(C[:, j])
        C[fill, j] = c[fill]
    if free:
        for k, j in zip(*np.nonzero(np.isfinite(C))):
            C[k, j] = nice(C[k, j])
    return C


def turned_multiple(A, b, rtol, period, free=True):
    """Per row of ``A`` (k, N): the constant c and the whole number n ≠ 0 of periods with A ≈ c·(b + n·period) at
    every sample — c and n the same at all of them — or n = 0 where there are none. c is 1 unless ``free``.

    An angle row turned by whole turns places the bodies as the row does: φ3 − φ4 + 2π, φ4 − φ3 + 2π and
    2(φ2 − 3π/4 − 100t + 2π) vanish where a turn of a body makes φ3 − φ4 (the driver's row) vanish. A number
    of turns that changes from sample to sample is another row: atan2(sin φ2, cos φ2) − 3π/4 − 100t equals
    φ2 − 3π/4 − 100t up to turns that follow φ2, and has no zero once 100t > π/4."""
    A = np.atleast_2d(A)
    b = np.asarray(b, float).reshape(-1)
    with np.errstate(all="ignore"):
        if free:
            bc = b - b.mean()
            c = ((A - A.mean(axis=1, keepdims=True)) @ bc) / float(bc @ bc)
        else:
            c = np.ones(len(A))
        d = A - c[:, None] * b[None, :]  # c·n·period, the same at every sample
        off = d.mean(axis=1)
        n = np.round(off / (c * period))
        scale = np.maximum(np.abs(A).max(axis=1), np.abs(c) * np.abs(b).max())
        tol = rtol * scale + 1e-12 * np.maximum(scale, 1.0) * rtol
        ok = (np.all(np.abs(d - off[:, None]) <= tol[:, None], axis=1) & (np.abs(off - c * n * period) <= tol)
              & np.isfinite(c) & (c != 0) & np.isfinite(n))
    return np.where(ok, c, np.nan), np.where(ok, n, 0.0)


def atol_of(R, rtol):
    """The absolute tolerance of a quantity: rtol × its largest entry (at least rounding level)."""
    return rtol * max(scale_of(R), 1e-9)
