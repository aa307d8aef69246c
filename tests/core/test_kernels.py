"""The compiled kernels' Φ_q and γ, taken through the nodes of Φ (kinbook.core.kernels._chain), against the same Φ
differentiated numerically in 50-digit arithmetic (mpmath, central differences with step 1e-12: exact to far
below the 1e-12 compared): Φ_q column by column, γ as −d²Φ(q + s q̇)/ds² at s = 0 — for every planar and
spatial type and for expressions that exercise every kind of node."""

import mpmath
import numpy as np
import pytest
import sympy as sp

from kinbook.core import kernels

from ..planar.zoo import zoo
from ..spatial.zoo import FACTORIES, states, two_bodies


def _reference(kernel, values, q, qd):
    """(Φ_q, γ) of the kernel's template at the numbers ``values`` of its parameters, by differences of Φ."""
    with mpmath.workdps(50):
        phi = sp.lambdify(kernel.q + kernel.params, kernel.exprs, modules="mpmath")
        at = lambda x: mpmath.matrix(phi(*x, *(mpmath.mpf(v) for v in values)))  # noqa: E731
        q, qd, h = [mpmath.mpf(v) for v in q], [mpmath.mpf(v) for v in qd], mpmath.mpf("1e-12")
        step = lambda d, s: [a + s * b for a, b in zip(q, d)]  # noqa: E731
        cols = [(at(step(e, h)) - at(step(e, -h))) / (2 * h) for e in np.eye(len(q)).tolist()]
        J = np.array([[float(col[r]) for col in cols] for r in range(len(kernel.exprs))])
        gamma = -(at(step(qd, h)) - 2 * at(q) + at(step(qd, -h))) / h**2
        return J, np.array([float(g) for g in gamma])


def _compare(c, q, qd):
    kernel, params = kernels.compiled(c)
    nb, nc = len(c.bodies), len(c.COORDS)
    Q, Qd = (np.asarray(v, dtype=float).reshape(1, 1, nb, nc) for v in (q, qd))
    P = {"p": params["p"][None, :]}
    _, J, gamma = kernel(Q, P, Qd)
    J_ref, gamma_ref = _reference(kernel, params["p"], q, qd)
    scale = max(1.0, np.abs(gamma_ref).max())
    np.testing.assert_allclose(J[0, 0], J_ref, rtol=1e-12, atol=1e-12, err_msg=c.describe())
    np.testing.assert_allclose(gamma[0, 0], gamma_ref, rtol=1e-12, atol=1e-12 * scale, err_msg=c.describe())
    _, J_only, none = kernel(Q, P)  # the function without velocities builds Φ_q alone from the same chain
    assert none is None
    np.testing.assert_array_equal(J_only, J)


def _parts(c):
    return c.part_views() or [c]


def test_planar_types():
    mech = zoo(0)
    rng = np.random.default_rng(5)
    for c in mech.constraints:
        for part in _parts(c):
            n = len(part.bodies) * 3
            _compare(part, rng.uniform(-2, 2, n), rng.uniform(-3, 3, n))


@pytest.mark.parametrize("type_name", sorted(FACTORIES))
def test_spatial_types(type_name):
    mech = two_bodies(type_name, seed=11)
    (c,) = mech.constraints[-1:]
    start = {b.name: 7 * k for k, b in enumerate(mech.bodies)}
    for q, qd, _ in states(mech, count=2):  # unit p, then p off the unit sphere
        for part in _parts(c):
            cols = np.concatenate([np.arange(start[b], start[b] + 7) for b in part.body_names])
            _compare(part, q[cols], qd[cols])


def test_every_kind_of_node():
    """Rows that are a coordinate, a constant, a parameter, a product with a repeated factor, a power, a
    quotient, functions of sums (atan2, sqrt, sin) and a piecewise expression."""
    x, y, z = sp.symbols("_q0_0 _q0_1 _q0_2", real=True)
    k0, k1 = sp.symbols("_k0 _k1", real=True)
    exprs = [x, sp.Integer(3), k0, 2 * x * x * y * k1, (x + k0 * y) ** 3, x / (1 + y**2),
             sp.atan2(y + z, x - k1) + sp.sqrt(x**2 + y**2 + 4) * sp.sin(x * z),
             sp.Piecewise((x * y, z > 0), (y**2, True))]
    kernel = kernels.CompiledKernel(exprs, [x, y, z], [k0, k1], "test")
    values = np.array([0.7, -1.3])
    for q, qd in (([0.4, -0.9, 1.1], [1.5, 0.3, -2.0]), ([1.2, 0.5, -0.6], [-0.4, 2.2, 0.9])):
        Q, Qd = (np.array(v, dtype=float).reshape(1, 1, 1, 3) for v in (q, qd))
        _, J, gamma = kernel(Q, {"p": values[None, :]}, Qd)
        J_ref, gamma_ref = _reference(kernel, values, q, qd)
        np.testing.assert_allclose(J[0, 0], J_ref, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(gamma[0, 0], gamma_ref, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(J[0, 0, 0], [1, 0, 0])  # the rows the chain never differentiates
    np.testing.assert_array_equal(J[0, 0, 1:3], 0)
    np.testing.assert_array_equal(gamma[0, 0, :3], 0)
