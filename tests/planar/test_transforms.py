import numpy as np
import pytest
import sympy as sp

from kinbook import InputError
from kinbook.planar import A, B, point_acceleration, point_position, point_velocity


def test_A_is_a_rotation_and_B_its_derivative():
    phi = np.random.default_rng(0).uniform(-7, 7, 50)
    Am = A(phi)
    assert Am.shape == (50, 2, 2)
    np.testing.assert_allclose(Am @ np.swapaxes(Am, -1, -2), np.broadcast_to(np.eye(2), Am.shape), atol=1e-14)
    np.testing.assert_allclose(np.linalg.det(Am), 1.0)
    h = 1e-6
    np.testing.assert_allclose(B(phi), (A(phi + h) - A(phi - h)) / (2 * h), atol=1e-9)
    # B = A R(90°): B s' is A s' turned by a right angle
    np.testing.assert_allclose(B(phi), Am @ A(np.pi / 2), atol=1e-14)


def test_symbolic_forms_match_numeric():
    p = sp.Symbol("phi")
    assert sp.simplify(B(p) - A(p).diff(p)) == sp.zeros(2, 2)
    f = sp.lambdify(p, A(p))
    np.testing.assert_allclose(f(0.7), A(0.7))


def test_point_kinematics_are_time_derivatives_of_the_position():
    s = np.array([1.3, -0.4])
    r = lambda t: np.array([np.cos(t), t**2])
    phi = lambda t: 0.3 + 2 * t + np.sin(t)
    t, h = 0.8, 1e-4
    pos = lambda tt: point_position(r(tt), phi(tt), s)
    rd = np.array([-np.sin(t), 2 * t])
    rdd = np.array([-np.cos(t), 2.0])
    phid, phidd = 2 + np.cos(t), -np.sin(t)
    np.testing.assert_allclose(point_velocity(rd, phi(t), phid, s), (pos(t + h) - pos(t - h)) / (2 * h), atol=1e-7)
    np.testing.assert_allclose(
        point_acceleration(rdd, phi(t), phid, phidd, s), (pos(t + h) - 2 * pos(t) + pos(t - h)) / h**2, atol=1e-5
    )


def test_broadcasting_over_many_instants():
    phi = np.linspace(0, 1, 7)
    r = np.zeros((7, 2))
    out = point_position(r, phi, [1.0, 0.0])
    np.testing.assert_allclose(out, np.column_stack([np.cos(phi), np.sin(phi)]))


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_angle_is_refused(bad):
    with pytest.raises(InputError, match="finite"):
        A(bad)


def test_wrong_shape_is_refused():
    with pytest.raises(InputError, match=r"`s_local` must have shape \(\.\.\., 2\), got \(3,\)"):
        point_position([0, 0], 0.0, [1, 2, 3])
