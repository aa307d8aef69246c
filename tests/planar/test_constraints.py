"""Every planar constraint type: the fast kernels agree with the symbolic derivation, Φ_q with finite
differences of Φ, ν with −∂Φ/∂t and γ with the second time derivative of Φ along a smooth trajectory."""

import numpy as np
import pytest
import sympy as sp

from kinbook.planar import CONSTRAINT_TYPES

from .zoo import zoo

SEEDS = [0, 1, 2]


@pytest.fixture(scope="module", params=SEEDS)
def mech(request):
    return zoo(request.param)


@pytest.fixture(scope="module")
def lambdified(mech):
    d = mech.symbolic()
    args = (list(mech.q), list(mech.qd), mech.t)
    return {name: sp.lambdify(args, getattr(d, name), "numpy") for name in ("Phi", "Phi_q", "nu", "gamma")}


def states(mech, count=5, seed=7):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        yield rng.uniform(-2, 2, mech.n), rng.uniform(-3, 3, mech.n), float(rng.uniform(-1, 1))


def test_zoo_has_every_constraint_type(mech):
    built_in = {name for name, cls in CONSTRAINT_TYPES.items() if cls.__module__.startswith("kinbook.")}
    assert {c.type_name for c in mech.constraints} == built_in


def test_kernels_equal_symbolic_derivation(mech, lambdified):
    for q, qd, t in states(mech):
        ev = mech.evaluate(q, t, qd)
        for name in ("Phi", "Phi_q", "nu", "gamma"):
            expected = np.array(lambdified[name](q, qd, t), dtype=float).reshape(ev[name].shape)
            np.testing.assert_allclose(ev[name], expected, rtol=1e-10, atol=1e-10, err_msg=name)


def test_compiled_path_equals_hand_kernels(mech):
    """Every type's hand-written kernel is an optimization of the kernel compiled from its Φ: both agree."""
    compiled = zoo(int(mech.name[3:]))
    compiled.kernels = "compiled"
    assert all(k.kernel.__class__.__name__ in ("CompiledKernel", "StackedKernel") for k in compiled.compiled[0])
    for q, qd, t in states(mech):
        hand, comp = mech.evaluate(q, t, qd), compiled.evaluate(q, t, qd)
        for name in ("Phi", "Phi_q", "nu", "gamma"):
            np.testing.assert_allclose(comp[name], hand[name], rtol=1e-12, atol=1e-12, err_msg=name)
    qs, qds, ts = (np.array(v) for v in zip(*states(mech)))
    for jacobian in (True, False):  # batched, with and without Φ_q
        hand, comp = mech.evaluate(qs, ts, qds, jacobian=jacobian), compiled.evaluate(qs, ts, qds, jacobian=jacobian)
        np.testing.assert_allclose(comp["gamma"], hand["gamma"], rtol=1e-12, atol=1e-12)


def test_jacobian_equals_finite_differences(mech):
    h = 1e-6
    for q, _, t in states(mech):
        J = mech.Phi_q(q, t)
        fd = np.column_stack([(mech.Phi(q + h * e, t) - mech.Phi(q - h * e, t)) / (2 * h) for e in np.eye(mech.n)])
        np.testing.assert_allclose(J, fd, atol=1e-6)


def test_nu_is_minus_time_derivative(mech):
    h = 1e-6
    for q, _, t in states(mech):
        fd = (mech.Phi(q, t + h) - mech.Phi(q, t - h)) / (2 * h)
        np.testing.assert_allclose(mech.nu(q, t), -fd, atol=1e-6)


def test_gamma_equals_second_derivative_along_trajectory(mech):
    # q(t) = q0 + v t + a t²/2 + c sin(t): Φ_q q̈ − d²Φ/dt² = γ
    rng = np.random.default_rng(3)
    q0, v, a, c = (rng.uniform(-1, 1, mech.n) for _ in range(4))

    def q_of(t):
        return q0 + v * t + 0.5 * a * t * t + c * np.sin(t)

    t0, h = 0.3, 1e-4
    q = q_of(t0)
    qd = v + a * t0 + c * np.cos(t0)
    qdd = a - c * np.sin(t0)
    d2 = (mech.Phi(q_of(t0 + h), t0 + h) - 2 * mech.Phi(q, t0) + mech.Phi(q_of(t0 - h), t0 - h)) / h**2
    np.testing.assert_allclose(mech.gamma(q, qd, t0), mech.Phi_q(q, t0) @ qdd - d2, atol=2e-5)


def test_batched_evaluation_equals_one_at_a_time(mech):
    qs, qds, ts = zip(*states(mech))
    batch = mech.evaluate(np.array(qs), np.array(ts), np.array(qds))
    for k, (q, qd, t) in enumerate(zip(qs, qds, ts)):
        single = mech.evaluate(q, t, qd)
        for name in ("Phi", "Phi_q", "nu", "gamma"):
            np.testing.assert_allclose(batch[name][k], single[name], rtol=1e-13, atol=1e-13)


def test_sparse_jacobian_equals_dense(mech):
    q, _, t = next(states(mech))
    np.testing.assert_allclose(mech.Phi_q(q, t, sparse=True).toarray(), mech.Phi_q(q, t), atol=0)


def test_rows_follow_the_order_constraints_were_added(mech):
    rows = [r for c in mech.constraints for r in range(c.rows.start, c.rows.stop)]
    assert rows == list(range(mech.m))
    sym = mech.symbolic().Phi
    for c in mech.constraints:
        assert list(sym[c.rows, 0]) == list(mech.constraint_phi(c))


def test_revolute_symbolic_form_is_eq_17():
    from kinbook.planar import Mechanism, Revolute

    m = Mechanism()
    m.add_body("i", points={"P": ("xi_i", "eta_i")})
    m.add_body("j", points={"P": ("xi_j", "eta_j")})
    m.add(Revolute("i", "j", point="P"))
    x1, y1, p1, x2, y2, p2 = m.q
    xi_i, eta_i, xi_j, eta_j = sp.symbols("xi_i eta_i xi_j eta_j")
    expected = sp.Matrix([
        x1 + xi_i * sp.cos(p1) - eta_i * sp.sin(p1) - x2 - xi_j * sp.cos(p2) + eta_j * sp.sin(p2),
        y1 + xi_i * sp.sin(p1) + eta_i * sp.cos(p1) - y2 - xi_j * sp.sin(p2) - eta_j * sp.cos(p2),
    ])
    assert sp.simplify(m.symbolic().Phi - expected) == sp.zeros(2, 1)
