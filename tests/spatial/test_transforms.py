"""Point kinematics from r, p and their rates (§14.1, §14.3) against rigid-body formulas with ω and α."""

import numpy as np
import pytest

from kinbook.errors import InputError
from kinbook.spatial import (
    A_from_p,
    E,
    alpha_from_p,
    omega_from_p_dot,
    p_dot_from_omega,
    point_acceleration,
    point_position,
    point_velocity,
)


def test_point_kinematics_equal_rigid_body_formulas():
    rng = np.random.default_rng(11)
    p = rng.normal(size=(6, 4))
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    w, wd = rng.normal(size=(2, 6, 3))
    pd = p_dot_from_omega(p, w)
    # p̈ = ½ Eᵀ α + ½ Ėᵀ ω  ⇔  α = 2E p̈ and pᵀp̈ = −ṗᵀṗ
    pdd = 0.5 * np.einsum("kji,kj->ki", E(p), wd) - p * np.sum(pd * pd, 1)[:, None]
    np.testing.assert_allclose(alpha_from_p(p, pdd), wd, atol=1e-12)
    np.testing.assert_allclose(omega_from_p_dot(p, pd), w, atol=1e-12)
    r, rd, rdd, s_local = rng.normal(size=(4, 6, 3))
    s = np.einsum("kij,kj->ki", A_from_p(p), s_local)
    np.testing.assert_allclose(point_position(r, p, s_local), r + s, atol=1e-12)
    np.testing.assert_allclose(point_velocity(rd, p, pd, s_local), rd + np.cross(w, s), atol=1e-12)
    np.testing.assert_allclose(point_acceleration(rdd, p, pd, pdd, s_local),
                               rdd + np.cross(wd, s) + np.cross(w, np.cross(w, s)), atol=1e-12)


def test_point_kinematics_reject_bad_input():
    with pytest.raises(InputError, match="unit Euler parameters"):
        point_position([0, 0, 0], [1, 1, 0, 0], [1, 0, 0])
    with pytest.raises(InputError, match=r"`s_local` must have shape \(\.\.\., 3\)"):
        point_position([0, 0, 0], [1, 0, 0, 0], [1, 0])
    with pytest.raises(InputError, match="point_velocity: arguments of incompatible shapes"):
        point_velocity(np.zeros((2, 3)), np.tile([1.0, 0, 0, 0], (3, 1)), np.zeros((3, 4)), [1, 0, 0])
