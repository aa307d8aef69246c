"""Planar transformation matrices and point kinematics (textbook §13.5, eqs. 3–13).

Every function works on numbers and on sympy expressions alike: pass a float or an ndarray of angles and get
numpy arrays (broadcasting over the leading dimensions), pass a sympy expression and get a sympy Matrix.

Conventions (see docs/conventions.md): angles in radians; ``A(φ)`` maps local components (ξ, η) to global
components (x, y): ``r^P = r + A s'^P``.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..core.arrays import no_overflow, real_array, shapes, symbolic_leaves
from ..errors import InputError

__all__ = ["A", "B", "point_position", "point_velocity", "point_acceleration"]


def _is_symbolic(*values):
    return symbolic_leaves(*values)


def _angles(phi, name="phi"):
    return real_array(phi, name, "angles in radians")


@no_overflow
def A(phi):
    """Rotation (transformation) matrix A(φ), eq. 6.

    Parameters
    ----------
    phi : float, array_like of shape (...), or sympy expression
        Angle of the body's local frame, radians.

    Returns
    -------
    ndarray, shape (..., 2, 2), or sympy.Matrix
        ``[[cos φ, −sin φ], [sin φ, cos φ]]``: maps local (ξ, η) components to global (x, y).

    Examples
    --------
    >>> A(0.0)
    array([[ 1., -0.],
           [ 0.,  1.]])
    """
    if _is_symbolic(phi):
        c, s = sp.cos(phi), sp.sin(phi)
        return sp.Matrix([[c, -s], [s, c]])
    phi = _angles(phi)
    c, s = np.cos(phi), np.sin(phi)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


@no_overflow
def B(phi):
    """Derivative matrix B(φ) = dA/dφ, eq. 11.

    Returns ``[[−sin φ, −cos φ], [cos φ, −sin φ]]`` with the same shape rules as :func:`A`.
    """
    if _is_symbolic(phi):
        c, s = sp.cos(phi), sp.sin(phi)
        return sp.Matrix([[-s, -c], [c, -s]])
    phi = _angles(phi)
    c, s = np.cos(phi), np.sin(phi)
    return np.stack([np.stack([-s, -c], -1), np.stack([c, -s], -1)], -2)


def _vec(v, name):
    if _is_symbolic(v):
        return sp.Matrix(v)
    v = real_array(v, name)
    if v.shape[-1:] != (2,):
        raise InputError(f"`{name}` must have shape (..., 2), got {v.shape}")
    return v


def _matvec(M, v):
    if isinstance(M, sp.MatrixBase):
        return M * v
    return np.einsum("...ij,...j->...i", M, v)


@shapes
def point_position(r, phi, s_local):
    """Global position of a body point, eq. 5: r^P = r + A s'^P.

    Parameters
    ----------
    r : array_like, shape (..., 2)
        Global position of the body's reference point O_i.
    phi : float or array_like, shape (...)
        Body angle, radians.
    s_local : array_like, shape (..., 2)
        Local coordinates (ξ, η) of the point.

    Examples
    --------
    >>> point_position([1.0, 0.0], np.pi / 2, [2.0, 0.0]).round(12)
    array([1., 2.])
    """
    return _vec(r, "r") + _matvec(A(phi), _vec(s_local, "s_local"))


@shapes
def point_velocity(r_dot, phi, phi_dot, s_local):
    """Global velocity of a body point, eq. 10: ṙ^P = ṙ + B s'^P φ̇."""
    sym = _is_symbolic(r_dot, phi, phi_dot, s_local)
    phi_dot = phi_dot if sym else _angles(phi_dot, "phi_dot")[..., None]
    return _vec(r_dot, "r_dot") + _matvec(B(phi), _vec(s_local, "s_local")) * phi_dot


@shapes
def point_acceleration(r_ddot, phi, phi_dot, phi_ddot, s_local):
    """Global acceleration of a body point, eq. 13: r̈^P = r̈ + B s'^P φ̈ − A s'^P φ̇²."""
    sym = _is_symbolic(r_ddot, phi, phi_dot, phi_ddot, s_local)
    if not sym:
        phi_dot = _angles(phi_dot, "phi_dot")[..., None]
        phi_ddot = _angles(phi_ddot, "phi_ddot")[..., None]
    s_local = _vec(s_local, "s_local")
    return _vec(r_ddot, "r_ddot") + _matvec(B(phi), s_local) * phi_ddot - _matvec(A(phi), s_local) * phi_dot**2
