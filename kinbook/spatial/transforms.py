"""Point kinematics of a body in space with Euler parameters (textbook §14.1 and §14.3).

The spatial counterparts of :mod:`kinbook.planar.transforms`: a body point P with local coordinates s'ᴾ has

    r^P = r + A s'ᴾ
    ṙ^P = ṙ + Ȧ s'ᴾ = ṙ + ω × (A s'ᴾ)           Ȧ s'ᴾ = ∂(A s'ᴾ)/∂p ṗ = 2(E s̄'ᴾ + s'ᴾ pᵀ) ṗ
    r̈^P = r̈ + Ä s'ᴾ = r̈ + α × s + ω × (ω × s)    Ä s'ᴾ = ∂(A s'ᴾ)/∂p p̈ + 2(Ė s̄'ᴾ + s'ᴾ ṗᵀ) ṗ

Conventions (docs/conventions.md): A maps local components to global ones; p = [e0, e1, e2, e3] with unit norm
(InputError otherwise); ṗ and p̈ must be consistent with it (pᵀṗ = 0, pᵀp̈ = −ṗᵀṗ) for the results to be
the motion of a rigid body. Arrays broadcast over leading dimensions.
"""

from __future__ import annotations

from .arrays import array, mv, shapes, unit_p, vec3
from .rotations import A_from_p, dAa_dp

__all__ = ["point_position", "point_velocity", "point_acceleration"]


@shapes
def point_position(r, p, s_local):
    """Global position of a body point: r^P = r + A s'ᴾ (§14.1).

    Parameters
    ----------
    r : array_like, shape (..., 3)
        Global position of the body's origin.
    p : array_like, shape (..., 4)
        Unit Euler parameters of the body.
    s_local : array_like, shape (..., 3)
        Local coordinates (ξ, η, ζ) of the point.

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from kinbook.spatial import p_from_axis_angle
    >>> point_position([1.0, 0, 0], p_from_axis_angle([0, 0, 1], np.pi / 2), [2.0, 0, 0]).round(12)
    array([1., 2., 0.])
    """
    return vec3(r, "r") + mv(A_from_p(unit_p(p)), vec3(s_local, "s_local"))


@shapes
def point_velocity(r_dot, p, p_dot, s_local):
    """Global velocity of a body point: ṙ^P = ṙ + 2(E s̄'ᴾ + s'ᴾ pᵀ) ṗ (= ṙ + ω × A s'ᴾ), shape (..., 3)."""
    s = vec3(s_local, "s_local")
    return vec3(r_dot, "r_dot") + mv(dAa_dp(unit_p(p), s), array(p_dot, "p_dot", (4,)))


@shapes
def point_acceleration(r_ddot, p, p_dot, p_ddot, s_local):
    """Global acceleration of a body point: r̈^P = r̈ + ∂(A s')/∂p p̈ + ∂(A s')/∂p|_ṗ ṗ, shape (..., 3)."""
    s = vec3(s_local, "s_local")
    pd = array(p_dot, "p_dot", (4,))
    return (vec3(r_ddot, "r_ddot") + mv(dAa_dp(unit_p(p), s), array(p_ddot, "p_ddot", (4,)))
            + mv(dAa_dp(pd, s), pd))
