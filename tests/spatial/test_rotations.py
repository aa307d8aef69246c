"""Direction cosines, z-x-z Euler angles and Euler parameters (§14.1–14.3), against scipy's Rotation and
against sympy differentiation — never against the book's printed formulas."""

import copy

import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

import kinbook
from kinbook.errors import InputError, SingularityWarning
from kinbook.spatial import (
    A_ddot,
    A_dot,
    A_from_axes,
    A_from_euler,
    A_from_p,
    E,
    G,
    a_bar,
    alpha_from_p,
    axis_angle_from_p,
    check_rotation,
    dAa_dp,
    euler_from_A,
    euler_rates_from_omega,
    normalization,
    normalize_p,
    omega_from_euler_rates,
    omega_from_p_dot,
    p_dot_from_omega,
    p_from_A,
    p_from_axis_angle,
    random_p,
    skew,
)

RNG_SEED = 20241121


def quat_wxyz(rot):
    x, y, z, w = np.moveaxis(rot.as_quat(), -1, 0)
    return np.stack([w, x, y, z], -1)


# --------------------------------------------------------------------------------------- direction cosines
def test_skew_is_the_cross_product():
    rng = np.random.default_rng(RNG_SEED)
    a, b = rng.normal(size=(2, 5, 3))
    np.testing.assert_allclose(np.einsum("kij,kj->ki", skew(a), b), np.cross(a, b), atol=1e-14)


def test_A_from_axes_has_the_unit_vectors_as_columns():
    R = Rotation.random(random_state=1).as_matrix()
    A = A_from_axes(R[:, 0], R[:, 1], R[:, 2])
    np.testing.assert_allclose(A, R)
    np.testing.assert_allclose(A @ [0.0, 1.0, 0.0], R[:, 1])  # s = A s'


def test_A_from_axes_rejects_a_non_orthonormal_or_left_handed_triad():
    with pytest.raises(InputError, match=r"not a rotation matrix: max \|"):
        A_from_axes([1, 0, 0], [1, 1, 0], [0, 0, 1])
    with pytest.raises(InputError, match="det .* = -1.*reflection"):
        A_from_axes([1, 0, 0], [0, 1, 0], [0, 0, -1])


@pytest.mark.parametrize("bad, message", [
    (np.eye(2), r"shape \(\.\.\., 3, 3\)"),
    (np.full((3, 3), np.nan), "finite"),
    ("abc", "numeric"),
    (2 * np.eye(3), "not a rotation"),
])
def test_check_rotation_rejects_bad_input(bad, message):
    with pytest.raises(InputError, match=message):
        check_rotation(bad)


# --------------------------------------------------------------------------------------- Euler angles
def random_angles(rng, n):
    return np.column_stack([rng.uniform(-np.pi, np.pi, n), rng.uniform(0.05, np.pi - 0.05, n),
                            rng.uniform(-np.pi, np.pi, n)])


def test_A_from_euler_equals_scipy_intrinsic_ZXZ():
    ang = random_angles(np.random.default_rng(RNG_SEED), 50)
    A = A_from_euler(ang[:, 0], ang[:, 1], ang[:, 2])
    np.testing.assert_allclose(A, Rotation.from_euler("ZXZ", ang).as_matrix(), atol=1e-14)
    np.testing.assert_allclose(A_from_euler(*np.rad2deg(ang).T, degrees=True), A, atol=1e-14)


def test_A_from_euler_is_the_transpose_of_the_book_passive_product():
    # The book composes passive (global -> local) rotations A^21 = A^phi A^theta A^psi; ours is active.
    def passive_z(a):
        c, s = np.cos(a), np.sin(a)
        return np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])

    def passive_x(a):
        c, s = np.cos(a), np.sin(a)
        return np.array([[1, 0, 0], [0, c, s], [0, -s, c]])

    psi, theta, phi = 0.3, 1.1, -2.0
    A21 = passive_z(phi) @ passive_x(theta) @ passive_z(psi)
    np.testing.assert_allclose(A_from_euler(psi, theta, phi), A21.T, atol=1e-14)


def test_euler_from_A_round_trip_and_ranges():
    ang = random_angles(np.random.default_rng(RNG_SEED + 1), 50)
    psi, theta, phi = euler_from_A(Rotation.from_euler("ZXZ", ang).as_matrix())
    np.testing.assert_allclose(np.column_stack([psi, theta, phi]), ang, atol=1e-12)


@pytest.mark.parametrize("theta", [0.0, np.pi])
def test_euler_from_A_at_the_singularity_warns_and_reproduces_A(theta):
    A = A_from_euler(0.7, theta, -0.4)
    with pytest.warns(SingularityWarning, match=r"sin θ = 0.*φ = 0"):
        psi, th, phi = euler_from_A(A)
    assert phi == 0.0 and th == pytest.approx(theta)
    np.testing.assert_allclose(A_from_euler(psi, th, phi), A, atol=1e-12)


def _omega_from_A(A, A_dot):
    W = A_dot @ A.T
    return np.array([W[2, 1], W[0, 2], W[1, 0]])


def test_angular_velocity_from_euler_rates_matches_A_dot():
    ts = sp.Symbol("t")
    angles = sp.Matrix([sp.sin(ts) + 0.2, 1.0 + 0.3 * sp.cos(2 * ts), ts**2 - 1])
    Rz = lambda a: sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])  # noqa: E731
    Rx = lambda a: sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])  # noqa: E731
    A_t = Rz(angles[0]) * Rx(angles[1]) * Rz(angles[2])
    f = sp.lambdify(ts, [A_t, A_t.diff(ts), angles, angles.diff(ts)], "numpy")
    for t0 in (0.1, 0.8, 2.0):
        A, Ad, ang, rates = (np.array(v, dtype=float) for v in f(t0))
        w = _omega_from_A(A, Ad)
        np.testing.assert_allclose(omega_from_euler_rates(ang.ravel(), rates.ravel()), w, atol=1e-12)
        np.testing.assert_allclose(omega_from_euler_rates(ang.ravel(), rates.ravel(), frame="body"), A.T @ w,
                                   atol=1e-12)
        np.testing.assert_allclose(euler_rates_from_omega(ang.ravel(), w), rates.ravel(), atol=1e-12)
        np.testing.assert_allclose(euler_rates_from_omega(ang.ravel(), A.T @ w, frame="body"), rates.ravel(),
                                   atol=1e-12)


def test_euler_rates_at_the_singularity_raise_naming_theta():
    with pytest.raises(InputError, match=r"θ = 0 rad \(sin θ = 0"):
        euler_rates_from_omega([0.3, 0.0, 0.1], [0, 0, 1])
    with pytest.raises(InputError, match="frame"):
        omega_from_euler_rates([0, 1, 0], [0, 0, 1], frame="local")


# --------------------------------------------------------------------------------------- Euler parameters
def test_p_from_axis_angle_and_A_from_p_equal_scipy():
    rng = np.random.default_rng(RNG_SEED + 2)
    axis, angle = rng.normal(size=(20, 3)), rng.uniform(-2 * np.pi, 2 * np.pi, 20)
    p = p_from_axis_angle(axis, angle)
    unit = axis / np.linalg.norm(axis, axis=1, keepdims=True)
    rot = Rotation.from_rotvec(unit * angle[:, None])
    np.testing.assert_allclose(np.abs(np.einsum("ki,ki->k", p, quat_wxyz(rot))), 1.0, atol=1e-12)
    np.testing.assert_allclose(A_from_p(p), rot.as_matrix(), atol=1e-13)
    np.testing.assert_allclose(np.linalg.norm(p, axis=1), 1.0)


def test_axis_angle_round_trip():
    p = p_from_axis_angle([1.0, -2.0, 0.5], 2.5)
    axis, angle = axis_angle_from_p(p)
    np.testing.assert_allclose(axis, np.array([1.0, -2.0, 0.5]) / np.linalg.norm([1.0, -2.0, 0.5]))
    assert angle == pytest.approx(2.5)


def test_p_from_A_is_robust_for_every_rotation_including_half_turns():
    rng = np.random.default_rng(RNG_SEED + 3)
    rots = [Rotation.random(200, random_state=4).as_matrix()]
    axes = rng.normal(size=(50, 3))
    rots.append(A_from_p(p_from_axis_angle(axes, np.pi)))  # e0 = 0: the book's formula divides by zero
    rots.append(A_from_p(p_from_axis_angle(axes, np.pi - 1e-9)))
    rots.append(A_from_p(p_from_axis_angle([[1, 0, 0], [0, 1, 0], [0, 0, 1]], np.pi)))
    for A in rots:
        p = p_from_A(A)
        np.testing.assert_allclose(A_from_p(p), A, atol=1e-12)
        np.testing.assert_allclose(np.linalg.norm(p, axis=-1), 1.0, atol=1e-14)
        assert np.all(p[..., 0] >= 0)


def test_p_from_A_equals_scipy_quaternion_up_to_sign():
    R = Rotation.random(100, random_state=5)
    p = p_from_A(R.as_matrix())
    np.testing.assert_allclose(np.abs(np.einsum("ki,ki->k", p, quat_wxyz(R))), 1.0, atol=1e-12)


def test_non_unit_p_is_rejected_and_normalize_p_is_explicit():
    with pytest.raises(InputError, match=r"unit Euler parameters.*\|p\| = 1.41421.*normalize_p"):
        A_from_p([1, 0, 0, 1])
    A = A_from_p(normalize_p([1, 0, 0, 1]))
    np.testing.assert_allclose(A @ [1, 0, 0], [0, 1, 0], atol=1e-15)
    with pytest.raises(InputError, match="cannot be normalized"):
        normalize_p([0, 0, 0, 0])
    with pytest.raises(InputError, match=r"shape \(\.\.\., 4\)"):
        A_from_p([1, 0, 0])
    with pytest.raises(InputError, match="finite"):
        E([np.nan, 0, 0, 1])
    assert normalization([0.6, 0.0, 0.8, 0.0]) == pytest.approx(0.0)
    assert normalization([1.0, 1.0, 0.0, 0.0]) == pytest.approx(1.0)


# ----------------------------------------------------------------------- §14.3 identities with sympy
e = sp.symbols("e0:4", real=True)
P_SYM = sp.Matrix(e)
A_SYM = sp.Matrix(A_from_p(list(e)))
E_SYM, G_SYM = sp.Matrix(E(list(e))), sp.Matrix(G(list(e)))
a_sym = sp.symbols("a1:4", real=True)
PTP = (P_SYM.T * P_SYM)[0]


def zero(M):
    return sp.simplify(sp.expand(M)) == sp.zeros(*M.shape)


def test_Ep_and_Gp_vanish_for_every_p():
    assert zero(E_SYM * P_SYM) and zero(G_SYM * P_SYM)


def test_EEt_and_GGt_are_ptp_times_identity():
    assert zero(E_SYM * E_SYM.T - PTP * sp.eye(3))
    assert zero(G_SYM * G_SYM.T - PTP * sp.eye(3))


def test_A_equals_EGt_on_the_unit_sphere():
    # A = 2[(e0² − ½)I + eeᵀ + e0ẽ] and EGᵀ differ by (1 − pᵀp) I
    assert zero(E_SYM * G_SYM.T - A_SYM - (1 - PTP) * sp.eye(3))
    p = random_p(10, np.random.default_rng(RNG_SEED))
    np.testing.assert_allclose(np.einsum("kij,klj->kil", E(p), G(p)), A_from_p(p), atol=1e-14)
    np.testing.assert_allclose(np.einsum("kji,kjl->kil", A_from_p(p), A_from_p(p)), np.broadcast_to(np.eye(3), (10, 3, 3)),
                               atol=1e-14)


def test_G_transpose_a_equals_a_bar_p():
    assert zero(G_SYM.T * sp.Matrix(a_sym) - sp.Matrix(a_bar(list(a_sym))) * P_SYM)


def test_dAa_dp_equals_sympy_jacobian_for_both_forms_of_A():
    a = sp.Matrix(a_sym)
    abar = sp.Matrix(a_bar(list(a_sym)))
    assert zero((A_SYM * a).jacobian(P_SYM) - 2 * (E_SYM * abar + a * P_SYM.T))
    assert zero((E_SYM * G_SYM.T * a).jacobian(P_SYM) - 2 * E_SYM * abar)
    # the numeric function, off the unit sphere
    f = sp.lambdify([e, a_sym], [(A_SYM * a).jacobian(P_SYM), (E_SYM * G_SYM.T * a).jacobian(P_SYM)], "numpy")
    rng = np.random.default_rng(RNG_SEED)
    for _ in range(5):
        p, av = rng.normal(size=4), rng.normal(size=3)
        JA, JEG = (np.array(v, dtype=float) for v in f(p, av))
        np.testing.assert_allclose(dAa_dp(p, av), JA, atol=1e-13)
        np.testing.assert_allclose(dAa_dp(p, av, form="EG"), JEG, atol=1e-13)


@pytest.fixture(scope="module")
def unit_trajectory():
    """A unit p(t) = [cos(α/2), u sin(α/2)] with time-varying axis and angle, and its sympy derivatives."""
    ts = sp.Symbol("t", real=True)
    beta, gamma = 0.7 * ts + 0.2, 1.1 - 0.5 * ts**2  # axis u(t) on the unit sphere, by its two angles
    u = sp.Matrix([sp.cos(beta) * sp.sin(gamma), sp.sin(beta) * sp.sin(gamma), sp.cos(gamma)])
    alpha = 2 * ts + sp.sin(3 * ts)
    p = sp.Matrix([sp.cos(alpha / 2)]).col_join(u * sp.sin(alpha / 2))
    A = A_from_p(list(p))
    f = sp.lambdify(ts, [p, p.diff(ts), p.diff(ts, 2), A, A.diff(ts), A.diff(ts, 2)], "numpy")

    def at(t0):
        p0, pd, pdd, A0, Ad, Add = (np.array(v, dtype=float).squeeze() for v in f(t0))
        W, Wd = Ad @ A0.T, Add @ A0.T + Ad @ Ad.T  # ω̃ = ȦAᵀ and its time derivative
        return p0, pd, pdd, A0, Ad, Add, np.array([W[2, 1], W[0, 2], W[1, 0]]), np.array([Wd[2, 1], Wd[0, 2], Wd[1, 0]])

    return at


@pytest.mark.parametrize("t0", [0.2, 1.3])
def test_A_dot_and_A_ddot_equal_sympy_derivatives(unit_trajectory, t0):
    p, pd, pdd, A, Ad, Add, w, wd = unit_trajectory(t0)
    np.testing.assert_allclose(A_from_p(p), A, atol=1e-13)
    np.testing.assert_allclose(A_dot(p, pd), Ad, atol=1e-12)
    np.testing.assert_allclose(2 * E(pd, check=False) @ G(p).T, Ad, atol=1e-12)  # Ȧ = 2ĖGᵀ too
    np.testing.assert_allclose(A_ddot(p, pd, pdd), Add, atol=1e-12)
    a = np.array([0.3, -1.2, 2.0])
    rhs = 2 * E(pd, check=False) @ G(pd, check=False).T @ a + 2 * E(p) @ a_bar(a) @ pdd
    np.testing.assert_allclose(rhs, Add @ a, atol=1e-12)  # Ä a = 2ĖĠᵀa + 2Eā p̈


@pytest.mark.parametrize("t0", [0.2, 1.3])
def test_angular_velocity_and_acceleration_from_p(unit_trajectory, t0):
    p, pd, pdd, A, Ad, Add, w, wd = unit_trajectory(t0)
    np.testing.assert_allclose(omega_from_p_dot(p, pd), w, atol=1e-12)
    np.testing.assert_allclose(omega_from_p_dot(p, pd, frame="body"), A.T @ w, atol=1e-12)
    np.testing.assert_allclose(p_dot_from_omega(p, w), pd, atol=1e-12)
    np.testing.assert_allclose(p_dot_from_omega(p, A.T @ w, frame="body"), pd, atol=1e-12)
    np.testing.assert_allclose(alpha_from_p(p, pdd), wd, atol=1e-12)
    np.testing.assert_allclose(alpha_from_p(p, pdd, frame="body"), A.T @ wd, atol=1e-12)
    assert p @ pd == pytest.approx(0.0, abs=1e-13)
    assert p @ pdd == pytest.approx(-(pd @ pd), abs=1e-12)


def test_rates_must_be_tangent_to_the_unit_sphere():
    with pytest.raises(InputError, match=r"pᵀṗ = 0"):
        omega_from_p_dot([1, 0, 0, 0], [1, 0, 0, 0])
    with pytest.raises(InputError, match=r"pᵀp̈ \+ ṗᵀṗ = 0"):
        A_ddot([1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0])


def test_incompatible_shapes_raise_input_error():
    with pytest.raises(InputError, match="A_from_euler: arguments of incompatible shapes"):
        A_from_euler(np.zeros(2), np.zeros(3), 0.0)
    with pytest.raises(InputError, match="omega_from_euler_rates: arguments of incompatible shapes"):
        omega_from_euler_rates(np.zeros((2, 3)), np.zeros((3, 3)))
    with pytest.raises(InputError, match="dAa_dp: arguments of incompatible shapes"):
        dAa_dp(np.ones((2, 4)), np.ones((3, 3)))


def test_symbolic_A_is_built_once_and_each_caller_gets_its_own_matrix():
    """A(p) of the same symbols is built once (the checkers' mistake catalogue asks for it dozens of times): each
    call still returns a new matrix, so a caller that writes into it cannot change the next caller's A."""
    first = A_from_p(list(e))
    first[0, 0] = sp.Symbol("scribble")
    again = A_from_p(list(e))
    assert again == A_SYM and again is not first
    e0, e1, e2, e3 = e  # the matrix of §14.3 (with the factor 2 and the signs the book drops), typed out
    typed = 2 * sp.Matrix([[e0**2 + e1**2 - sp.S.Half, e1 * e2 - e0 * e3, e1 * e3 + e0 * e2],
                           [e1 * e2 + e0 * e3, e0**2 + e2**2 - sp.S.Half, e2 * e3 - e0 * e1],
                           [e1 * e3 - e0 * e2, e2 * e3 + e0 * e1, e0**2 + e3**2 - sp.S.Half]])
    assert sp.expand(again - typed) == sp.zeros(3, 3)


def test_a_constraints_global_vector_is_A_times_s_whatever_its_rotation_hook():
    """global_vector(Q, s') = A s' through the constraint's rotation hook, also when a copy overrides the hook (the
    mistake catalogue's Aᵀ): the product kept for reuse is keyed by A's entries, not by the body."""
    mech = kinbook.examples.load("spatial_fourbar")
    c = mech.constraint("B")
    Qb = mech.body_symbols(c.bodies[0].name)
    s = (0.1, -0.2, 0.3)
    A = c.rotation(Qb)
    assert sp.expand(c.global_vector(Qb, s) - A * sp.Matrix(s)) == sp.zeros(3, 1)
    flipped = copy.copy(c)
    flipped.rotation = lambda Q: A.T
    assert sp.expand(flipped.global_vector(Qb, s) - A.T * sp.Matrix(s)) == sp.zeros(3, 1)
    assert sp.expand(flipped.global_point(Qb, s) - sp.Matrix(Qb[0:3]) - A.T * sp.Matrix(s)) == sp.zeros(3, 1)
