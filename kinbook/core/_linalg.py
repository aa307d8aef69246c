"""The numeric linear algebra under the analyses: one linear solve (dense or sparse), the scaling that makes
Φ_q's conditioning independent of units, and its reciprocal condition number.

Private to :mod:`kinbook.core`: :mod:`~kinbook.core.diagnose`, :mod:`~kinbook.core.solve` and
:mod:`~kinbook.core.sweep` use it.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..errors import InputError
from .arrays import real_array

__all__ = ["SPARSE_ABOVE", "length_scale", "column_scale", "scaled", "scaled_rcond", "condition_number",
           "solve_linear", "evaluate_jacobian", "scalar_time", "row_owner", "describe_rows"]

SPARSE_ABOVE = 150
"""Systems with more coordinates than this are assembled and factorized as sparse matrices."""


def row_owner(mech, row):
    for c in mech.constraints:
        if c.rows.start <= row < c.rows.stop:
            return c
    return None


def describe_rows(mech, rows, limit=8):
    """'revolute joint '3' (rows 8-9 of Φ), driver 'driver 1' (row 12 of Φ)' for 0-based ``rows``."""
    seen = []
    for r in rows:
        c = row_owner(mech, r)
        if c is not None and c not in seen:
            seen.append(c)
    text = ", ".join(c.describe() for c in seen[:limit])
    if len(seen) > limit:
        text += f" and {len(seen) - limit} more"
    return text


def scalar_time(t):
    t = real_array(t, "t", "a number (seconds)")
    if t.ndim != 0:
        raise InputError(f"`t` must be one number, got an array of shape {t.shape}")
    return float(t)


def solve_linear(J, b):
    """Solve J x = b for one square system, dense or sparse. Returns None when J is singular."""
    import scipy.linalg as sla  # imported when first needed: scipy adds about half a second to `import kinbook`
    import scipy.sparse.linalg as spla  # import time: scipy only when needed

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", sla.LinAlgWarning)
        try:
            if hasattr(J, "tocsc"):
                with np.errstate(all="ignore"):
                    x = spla.splu(J.tocsc()).solve(b)
            else:
                lu, piv = sla.lu_factor(J, check_finite=False)
                pivots = np.abs(np.diag(lu))
                if pivots.min() <= 1e-13 * max(1.0, pivots.max()):
                    return None
                x = sla.lu_solve((lu, piv), b, check_finite=False)
        except (np.linalg.LinAlgError, RuntimeError, ValueError):
            return None
    return x if np.all(np.isfinite(x)) else None


def evaluate_jacobian(mech, q, t):
    return mech.evaluate(q, t, sparse=mech.n > SPARSE_ABOVE)


def length_scale(mech):
    """The mechanism's length scale L: the largest distance of a named body point from its body's origin
    (1 when no point has a numeric nonzero distance). Kept in the mechanism's cache."""

    def build():
        L = 0.0
        for b in mech.bodies:
            for point in b.points.values():
                try:
                    L = max(L, math.hypot(*(float(v) for v in point)))  # (no overflow below 1e308)
                except (TypeError, ValueError):  # a symbolic parameter
                    continue
        return L if np.isfinite(L) and L > 0 else 1.0

    return mech.cached(("analysis", "length scale"), build)


def column_scale(mech):
    """Factors that measure each coordinate in units of the scale: L for positions, 1 for the others."""
    def build():
        L = length_scale(mech)
        return np.tile([L if c in ("x", "y", "z") else 1.0 for c in mech.COORDS], len(mech.bodies))

    return mech.cached(("analysis", "column scale"), build)


def scaled(J, cols):
    """D_r J D_c: columns times ``cols``, then each row divided by its norm (a zero row stays zero)."""
    if hasattr(J, "tocsc"):
        import scipy.sparse as sps  # import time: scipy only when needed

        Jc = J @ sps.diags(cols)
        rn = np.sqrt(np.asarray(Jc.multiply(Jc).sum(axis=1)).ravel())
        return (sps.diags(1.0 / np.where(rn > 0, rn, 1.0)) @ Jc).tocsc()
    Jc = J * cols
    rn = np.linalg.norm(Jc, axis=-1, keepdims=True)
    return Jc / np.where(rn > 0, rn, 1.0)


def scaled_rcond(mech, J, cols=None):
    """σ_min / σ_max of the scaled Φ_q (see :data:`RCOND_MIN`): exact, by SVD, for a dense Φ_q; for a sparse
    one estimated by a few steps of (inverse) power iteration from a seeded start, deterministic."""
    cols = column_scale(mech) if cols is None else cols
    Js = scaled(J, cols)
    if not hasattr(Js, "tocsc"):
        if not np.all(np.isfinite(Js)):
            return 0.0
        s = np.linalg.svd(Js, compute_uv=False)
        return float(s[-1] / s[0]) if s.size and s[0] > 0 else 0.0
    import scipy.sparse.linalg as spla  # import time: scipy only when needed

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            lu = spla.splu(Js)
    except RuntimeError:  # exactly singular
        return 0.0
    x = np.random.default_rng(0).standard_normal(Js.shape[1])
    y = x.copy()
    big = small = 1.0
    for _ in range(6):
        x /= np.linalg.norm(x)
        x = Js.T @ (Js @ x)
        big = np.linalg.norm(x)
        y /= np.linalg.norm(y)
        y = lu.solve(lu.solve(y, trans="T"))
        if not np.all(np.isfinite(y)):
            return 0.0
        small = np.linalg.norm(y)
    return float(np.sqrt(1.0 / (small * big))) if small > 0 and big > 0 else 0.0


def condition_number(J):
    """2-norm condition number of Φ_q as it is (for the Newton history), nan when too large to compute."""
    if hasattr(J, "toarray"):
        if J.shape[1] > 2000:
            return np.nan
        J = J.toarray()
    if not np.all(np.isfinite(J)):
        return np.nan
    s = np.linalg.svd(J, compute_uv=False)
    return float(s[0] / s[-1]) if s.size and s[-1] > 0 else np.inf
