"""Input checks and small batched algebra shared by the spatial modules (:mod:`~kinbook.spatial.rotations`,
:mod:`~kinbook.spatial.transforms`, the constraint kernels and the mechanism): arrays of the right shape,
unit Euler parameters, numpy's broadcasting errors named, and products of stacks of small matrices.
"""

from __future__ import annotations

import numpy as np

from ..core.arrays import no_overflow, real_array, shapes, symbolic_leaves  # noqa: F401 (shapes: re-exported)
from ..errors import InputError

__all__ = ["P_TOL", "symbolic", "array", "show", "unit_p", "vec3", "shapes", "parts", "stack_rows", "mm", "mv",
           "transpose"]

P_TOL = 1e-6
"""Tolerance on | |p| − 1 | accepted by functions that need unit Euler parameters."""


def symbolic(*values):
    return symbolic_leaves(*values)


def array(v, name, last=None):
    a = real_array(v, name)
    if last is not None and (a.ndim < len(last) or a.shape[a.ndim - len(last):] != tuple(last)):
        raise InputError(f"`{name}` must have shape (..., {', '.join(map(str, last))}), got {a.shape}")
    return a


def show(a):
    return np.array2string(np.asarray(a), precision=6, threshold=20)


def unit_p(p, name="p", check=True):
    p = array(p, name, (4,))
    if check:
        with np.errstate(over="ignore"):  # |p| of p = 1e300 is inf: not unit, refused below
            norm = np.linalg.norm(p, axis=-1)
        bad = np.abs(norm - 1.0) > P_TOL
        if np.any(bad):
            worst = float(np.ravel(norm)[np.argmax(np.ravel(np.abs(norm - 1.0)))])
            raise InputError(
                f"`{name}` must be unit Euler parameters (e0² + e1² + e2² + e3² = 1), got |{name}| = {worst:.9g}; "
                f"normalize it on purpose with kinbook.spatial.normalize_p"
            )
    return p


def vec3(v, name):
    return array(v, name, (3,))


def parts(p):
    return p[..., 0], p[..., 1], p[..., 2], p[..., 3]


def stack_rows(rows):
    return np.stack([np.stack(r, -1) for r in rows], -2)


def mm(X, Y):
    return np.einsum("...ij,...jk->...ik", X, Y)


def mv(M, v):
    """Batched matrix-vector product (…, m, n) @ (…, n) -> (…, m), for small n: n broadcast multiply-adds
    (numpy's stacked matmul on tiny matrices costs more per matrix than the arithmetic). Shared by
    :mod:`~kinbook.spatial.transforms` and the constraint kernels."""
    out = M[..., 0] * v[..., None, 0]
    for c in range(1, v.shape[-1]):
        out = out + M[..., c] * v[..., None, c]
    return out


def transpose(X):
    return np.swapaxes(X, -1, -2)
