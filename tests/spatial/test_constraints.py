"""Every spatial constraint type: the fast kernels agree with the symbolic derivation (kinbook.core.symbolic.derive
of the constraint's own Φ), Φ_q with finite differences of Φ, ν with −∂Φ/∂t and γ with the second time
derivative of Φ along a smooth trajectory; and the Jacobian blocks of Table 14.1 (B_k, C_k) with sympy.

Deriving γ symbolically costs seconds per constraint type, so the full derivation (Φ, Φ_q, ν and γ) runs
for the primitive types whose kernel code differs (n1, n2, s, ground, the angle driver and, in every
mechanism, the normalization rows), with short half-integer geometry; the composite joints are shown to be
exactly the row-stacks of those primitives, symbolically and in their kernels; s-s and the distance driver
reuse the n2 dot-product code. Every type, with random geometry, has its Φ and Φ_q compared with sympy and
its γ with the second derivative of Φ along a trajectory.
"""

import numpy as np
import pytest
import sympy as sp

from kinbook.spatial import CONSTRAINT_TYPES, Mechanism, Normal1, Normal2, Spherical, dAa_dp, skew
from kinbook.spatial.constraints import _perpendiculars

from .zoo import FACTORIES, random_p, states, two_bodies

FULL_DERIVATION = ["ground", "normal-1", "normal-2", "spherical", "revolute-driver"]
SAME_CODE_AS = {"spherical-spherical": "normal-2", "distance-driver": "normal-2"}  # d·d − l², u·d − f(t)
COMPOSITES = {
    # type: list of (primitive factory from the composite's own parameters)
    "parallel-1": lambda c: [Normal1("a", "b", vector_i=tuple(h), vector_j=tuple(c.a_j)) for h in (c.h1, c.h2)],
    "parallel-2": lambda c: [Normal2("a", "b", vector_i=tuple(h), point_i=tuple(c.P_i), point_j=tuple(c.P_j))
                             for h in (c.h1, c.h2)],
    "universal": lambda c: [Spherical("a", "b", point_i=tuple(c.P_i), point_j=tuple(c.P_j)),
                            Normal1("a", "b", vector_i=tuple(c.a_i), vector_j=tuple(c.a_j))],
    "revolute": lambda c: [Spherical("a", "b", point_i=tuple(c.P_i), point_j=tuple(c.P_j))]
    + COMPOSITES["parallel-1"](c),
    "cylindrical": lambda c: COMPOSITES["parallel-1"](c) + COMPOSITES["parallel-2"](c),
    "translational": lambda c: COMPOSITES["cylindrical"](c)
    + [Normal1("a", "b", vector_i=tuple(c.hp_i), vector_j=tuple(c.hp_j))],
}
ALL = list(FACTORIES)


BUILT_IN = {name for name, cls in CONSTRAINT_TYPES.items() if cls.__module__.startswith("kinbook.") and cls.in_files}


def test_every_constraint_type_is_covered():
    assert set(FACTORIES) == BUILT_IN
    assert set(FULL_DERIVATION) | set(COMPOSITES) | set(SAME_CODE_AS) == BUILT_IN


@pytest.mark.parametrize("type_name, label", [("universal", "s,3 + n1,1"), ("revolute", "s,3 + p1,2"),
                                               ("cylindrical", "p1,2 + p2,2"),
                                               ("translational", "p1,2 + p2,2 + n1,1")])
def test_composites_are_declared_by_their_parts(type_name, label):
    """A composite joint is its parts, declared once (``parts``): its label (the book's notation), rows and
    kernel follow from them."""
    c = two_bodies(type_name, seed=2).constraints[-1]
    assert c.label == type(c).label == label
    assert c.n_eq == sum(p.n_eq for p in COMPOSITES[type_name](c)) == sum(v.n_eq for v in c.part_views())


def wrap(x):
    return np.mod(x + np.pi, 2 * np.pi) - np.pi


_DERIVED = {}


def derived(type_name):
    """Lambdified Φ, Φ_q, ν, γ of mech.symbolic() (kinbook.core.symbolic.derive), cached for the module."""
    if type_name not in _DERIVED:
        if type_name == "revolute-driver":  # atan2's second derivatives are large: axis Z, references X
            mech = Mechanism("driver")
            for b in ("a", "b"):
                mech.add_body(b, vectors={"u": (0, 0, 1), "v": (1, 0, 0)})
            mech.add(FACTORIES[type_name]())
        else:
            mech = two_bodies(type_name, simple=True)
        d = mech.symbolic()
        args = (list(mech.q), list(mech.qd), mech.t)
        _DERIVED[type_name] = mech, {
            name: sp.lambdify(args, getattr(d, name), "numpy", cse=True) for name in ("Phi", "Phi_q", "nu", "gamma")
        }
    return _DERIVED[type_name]


@pytest.mark.parametrize("type_name", FULL_DERIVATION)
def test_kernels_equal_symbolic_derivation(type_name):
    mech, f = derived(type_name)
    angular = [c.rows.start + r for c in mech.constraints for r in c.wrap]
    for q, qd, t in states(mech):  # on and off the unit sphere
        ev = mech.evaluate(q, t, qd)
        for name in ("Phi", "Phi_q", "nu", "gamma"):
            expected = np.array(f[name](q, qd, t), dtype=float).reshape(ev[name].shape)
            diff = ev[name] - expected
            if name == "Phi":
                diff[angular] = wrap(diff[angular])
            np.testing.assert_allclose(diff, 0, atol=1e-10, err_msg=f"{type_name}: {name}")


PRIMITIVES = [name for name in ALL if name not in COMPOSITES or name.startswith("parallel")]


@pytest.mark.parametrize("type_name", PRIMITIVES)
def test_kernel_phi_and_jacobian_equal_sympy(type_name):
    """Random geometry; the composite joints follow from test_composite_joints_are_the_rows_of_their_primitives."""
    mech = two_bodies(type_name, seed=1)
    c = mech.constraints[-1]
    Phi = mech.constraint_phi(c)
    f = sp.lambdify([list(mech.q), mech.t], [Phi, Phi.jacobian(mech.q)], "numpy", cse=True)
    for q, _, t in states(mech, count=2):
        Phi_s, J_s = (np.array(v, dtype=float) for v in f(q, t))
        ev = mech.evaluate(q, t)
        diff = ev["Phi"][c.rows] - Phi_s.ravel()
        if c.wrap:
            diff = wrap(diff)
        np.testing.assert_allclose(diff, 0, atol=1e-10)
        np.testing.assert_allclose(ev["Phi_q"][c.rows], J_s, atol=1e-10)


def _phi_values(mech, constraints, q):
    out = []
    for c in constraints:
        f = sp.lambdify([list(mech.q)], mech.constraint_phi(c), "numpy")
        out.append(np.array(f(q), dtype=float).ravel())
    return np.concatenate(out)


@pytest.mark.parametrize("type_name", list(COMPOSITES))
def test_composite_joints_are_the_rows_of_their_primitives(type_name):
    mech = two_bodies(type_name, seed=2)
    c = mech.constraints[-1]
    parts = COMPOSITES[type_name](c)
    for k, part in enumerate(parts):
        part.name = f"part {k}"
        mech.add(part)
    rows = np.r_[c.rows]
    part_rows = np.concatenate([np.r_[p.rows] for p in parts])
    for q, qd, t in states(mech, count=3):
        # the symbolic Φ (the source of truth) ...
        np.testing.assert_allclose(_phi_values(mech, [c], q), _phi_values(mech, parts, q), atol=1e-12)
        # ... and the kernels (Φ, Φ_q, γ)
        ev = mech.evaluate(q, t, qd)
        for name in ("Phi", "Phi_q", "gamma"):
            np.testing.assert_allclose(ev[name][rows], ev[name][part_rows], atol=1e-12, err_msg=name)


@pytest.mark.parametrize("type_name", ALL)
def test_compiled_path_equals_hand_kernels(type_name):
    """The hand-written kernels are optimizations of the kernel compiled from each type's Φ: both agree, one
    instant at a time and batched, with and without Φ_q."""
    hand, comp = two_bodies(type_name, seed=8), two_bodies(type_name, seed=8)
    comp.kernels = "compiled"
    qs, qds, ts = (np.array(v) for v in zip(*states(hand, count=3)))
    for jacobian in (True, False):
        a, b = hand.evaluate(qs, ts, qds, jacobian=jacobian), comp.evaluate(qs, ts, qds, jacobian=jacobian)
        for name in ("Phi", "Phi_q", "nu", "gamma") if jacobian else ("Phi", "gamma"):
            np.testing.assert_allclose(b[name], a[name], rtol=1e-11, atol=1e-11, err_msg=f"{type_name}: {name}")
    a, b = hand.evaluate(qs[0], ts[0]), comp.evaluate(qs[0], ts[0])
    np.testing.assert_allclose(b["Phi_q"], a["Phi_q"], rtol=1e-11, atol=1e-11)


@pytest.mark.parametrize("type_name", ALL)
def test_jacobian_equals_finite_differences(type_name):
    mech = two_bodies(type_name, seed=3)
    h = 1e-6
    for q, _, t in states(mech, count=2):
        J = mech.Phi_q(q, t)
        cols = []
        for ej in np.eye(mech.n):
            d = mech.Phi(q + h * ej, t) - mech.Phi(q - h * ej, t)
            cols.append(wrap(d) / (2 * h))
        np.testing.assert_allclose(J, np.column_stack(cols), atol=2e-6)


@pytest.mark.parametrize("type_name", ALL)
def test_nu_is_minus_time_derivative(type_name):
    mech = two_bodies(type_name, seed=4)
    h = 1e-6
    for q, _, t in states(mech, count=2):
        fd = wrap(mech.Phi(q, t + h) - mech.Phi(q, t - h)) / (2 * h)
        np.testing.assert_allclose(mech.nu(q, t), -fd, atol=1e-6)


@pytest.mark.parametrize("type_name", ALL)
def test_gamma_equals_second_derivative_along_trajectory(type_name):
    # q(t) = q0 + v t + a t²/2 + c sin t (not on the unit sphere: the identity holds for any path)
    mech = two_bodies(type_name, seed=5)
    rng = np.random.default_rng(6)
    q0, v, a, c = (rng.uniform(-1, 1, mech.n) for _ in range(4))
    q0.reshape(-1, 7)[:, 3:] = random_p(mech.n // 7, rng)

    def q_of(t):
        return q0 + v * t + 0.5 * a * t * t + c * np.sin(t)

    t0, h = 0.3, 1e-4
    q, qd, qdd = q_of(t0), v + a * t0 + c * np.cos(t0), a - c * np.sin(t0)
    fp, f0, fm = mech.Phi(q_of(t0 + h), t0 + h), mech.Phi(q, t0), mech.Phi(q_of(t0 - h), t0 - h)
    d2 = (wrap(fp - f0) - wrap(f0 - fm)) / h**2
    np.testing.assert_allclose(mech.gamma(q, qd, t0), mech.Phi_q(q, t0) @ qdd - d2, atol=5e-5)


def test_batched_evaluation_equals_one_at_a_time():
    mech = two_bodies("translational", seed=7)
    qs, qds, ts = (np.array(v) for v in zip(*states(mech, count=5)))
    batch = mech.evaluate(qs, ts, qds)
    for k in range(5):
        single = mech.evaluate(qs[k], ts[k], qds[k])
        for name in ("Phi", "Phi_q", "nu", "gamma"):
            np.testing.assert_allclose(batch[name][k], single[name], atol=1e-14)
    sparse = mech.Phi_q(qs[0], ts[0], sparse=True)
    np.testing.assert_allclose(sparse.toarray(), batch["Phi_q"][0])


# --------------------------------------------------------------------------------------- Table 14.1
def _body(q, k):
    return q[7 * k : 7 * k + 3], q[7 * k + 3 : 7 * k + 7]


def _A(p):
    from kinbook.spatial import A_from_p

    return A_from_p(p, check=False)


@pytest.mark.parametrize("type_name", ["normal-1", "normal-2", "spherical", "parallel-1", "parallel-2"])
def test_table_14_1_blocks_equal_sympy_jacobian(type_name):
    """The closed forms of Table 14.1, with B_k = 2(E_k s̄'ᴾ_k + s'ᴾ_k p_kᵀ) and C_k = 2(E_k s̄'_k + s'_k p_kᵀ),
    equal sympy's Jacobian blocks of the constraint's symbolic Φ — off the unit sphere too."""
    mech = two_bodies(type_name, seed=1)
    c = mech.constraints[-1]
    Phi = mech.constraint_phi(c)
    f = sp.lambdify([list(mech.q)], Phi.jacobian(mech.q), "numpy", cse=True)
    for q, _, _ in states(mech, count=2):
        J = np.array(f(q), dtype=float)
        (ri, pi), (rj, pj) = _body(q, 0), _body(q, 1)
        Ai, Aj = _A(pi), _A(pj)
        if type_name in ("normal-1",):
            si, sj = Ai @ c.a_i, Aj @ c.a_j
            blocks = [np.zeros((1, 3)), sj @ dAa_dp(pi, c.a_i), np.zeros((1, 3)), si @ dAa_dp(pj, c.a_j)]
        elif type_name == "normal-2":
            si = Ai @ c.a_i
            d = rj + Aj @ c.P_j - ri - Ai @ c.P_i
            Bi, Bj, Ci = dAa_dp(pi, c.P_i), dAa_dp(pj, c.P_j), dAa_dp(pi, c.a_i)
            blocks = [-si, d @ Ci - si @ Bi, si, si @ Bj]
        elif type_name == "spherical":
            blocks = [np.eye(3), dAa_dp(pi, c.P_i), -np.eye(3), -dAa_dp(pj, c.P_j)]
        elif type_name == "parallel-1":
            sj = Aj @ c.a_j
            H = np.array([c.h1, c.h2])
            blocks = [np.zeros((2, 3)), np.array([sj @ dAa_dp(pi, h) for h in H]), np.zeros((2, 3)),
                      (Ai @ H.T).T @ dAa_dp(pj, c.a_j)]
        else:  # parallel-2
            d = rj + Aj @ c.P_j - ri - Ai @ c.P_i
            H = np.array([c.h1, c.h2])
            hi = (Ai @ H.T).T
            blocks = [-hi, np.array([d @ dAa_dp(pi, h) for h in H]) - hi @ dAa_dp(pi, c.P_i), hi,
                      hi @ dAa_dp(pj, c.P_j)]
        expected = np.hstack([np.atleast_2d(b) for b in blocks])
        np.testing.assert_allclose(J, expected, atol=1e-11)
        got = mech.jacobian_blocks(c.name, q)
        np.testing.assert_allclose(np.hstack([got["r_i"], got["p_i"], got["r_j"], got["p_j"]]), expected, atol=1e-11)


def test_book_cross_product_form_of_parallel_blocks_equals_sympy():
    """The book's own p1/p2 in cross-product form, Φ = s̃_i s_j and s̃_i d: Table 14.1's blocks
    Φ_pi = −s̃_j C_i, Φ_pj = s̃_i C_j (p1) and −s̃_i, −d̃ C_i − s̃_i B_i, s̃_i, s̃_i B_j (p2)."""
    q = sp.Matrix(sp.symbols("x1 y1 z1 e01 e11 e21 e31 x2 y2 z2 e02 e12 e22 e32", real=True))
    rng = np.random.default_rng(9)
    ai, aj, Pi, Pj = (rng.uniform(-2, 2, 3).round(2) for _ in range(4))
    from kinbook.spatial import A_from_p

    Ai, Aj = A_from_p(list(q[3:7])), A_from_p(list(q[10:14]))
    si, sj = Ai * sp.Matrix(ai), Aj * sp.Matrix(aj)
    d = q[7:10, 0] + Aj * sp.Matrix(Pj) - q[0:3, 0] - Ai * sp.Matrix(Pi)
    f = sp.lambdify([list(q)], [skew(list(si)) * sj, (skew(list(si)) * sj).jacobian(q), (skew(list(si)) * d).jacobian(q)],
                    "numpy", cse=True)
    for _ in range(2):
        qv = rng.uniform(-2, 2, 14)
        qv[3:7], qv[10:14] = random_p(rng=rng), random_p(rng=rng)
        _, J1, J2 = (np.array(v, dtype=float) for v in f(qv))
        ri, pi, rj, pj = qv[0:3], qv[3:7], qv[7:10], qv[10:14]
        si_, sj_ = _A(pi) @ ai, _A(pj) @ aj
        d_ = rj + _A(pj) @ Pj - ri - _A(pi) @ Pi
        Ci, Cj, Bi, Bj = dAa_dp(pi, ai), dAa_dp(pj, aj), dAa_dp(pi, Pi), dAa_dp(pj, Pj)
        np.testing.assert_allclose(J1, np.hstack([np.zeros((3, 3)), -skew(sj_) @ Ci, np.zeros((3, 3)), skew(si_) @ Cj]),
                                   atol=1e-11)
        np.testing.assert_allclose(J2, np.hstack([-skew(si_), -skew(d_) @ Ci - skew(si_) @ Bi, skew(si_), skew(si_) @ Bj]),
                                   atol=1e-11)


# --------------------------------------------------------------------------------------- parallel conditioning
@pytest.mark.parametrize("axis", [(1, 0, 0), (0, 1, 0), (0, 0, 1), (0.3, -0.8, 0.52), (1, 1, 1e-9)])
def test_parallel_rows_are_well_conditioned_in_every_orientation(axis):
    """Rotating body j by δθ changes the p1 rows by (s_j × h_k)ᵀ δθ: both singular values equal |s_j|,
    whichever direction the axis points; the book's fixed choice (first two rows of s̃_i s_j) loses rank
    when s_i lies along X."""
    from kinbook.spatial import E, Mechanism, Parallel1

    axis = np.asarray(axis, dtype=float)
    m = Mechanism("p1")
    m.add_body("a", vectors={"s": tuple(axis)})
    m.add_body("b", vectors={"s": tuple(2 * axis)})
    m.add(Parallel1("a", "b", vector_i="s", vector_j="s"))
    for p in random_p(3, np.random.default_rng(10)):
        q = np.r_[0, 0, 0, p, 1, 2, 3, p]  # same orientation: s_j ∥ s_i
        c = m.constraints[-1]
        Jpj = m.Phi_q(q)[c.rows][:, 10:14]
        sv = np.linalg.svd(Jpj @ (0.5 * E(p).T), compute_uv=False)  # ∂Φ/∂θ_j (ṗ = ½ Eᵀ ω)
        np.testing.assert_allclose(sv, 2 * np.linalg.norm(axis), rtol=1e-9)
    h1, h2 = _perpendiculars(axis)
    np.testing.assert_allclose([h1 @ axis, h2 @ axis, h1 @ h2, np.linalg.norm(h1), np.linalg.norm(h2)],
                               [0, 0, 0, 1, 1], atol=1e-12)
    book_rows = skew(np.array([1.0, 0, 0]))[:2]  # rows 1-2 of s̃_i for s_i = X: row 1 is zero
    assert np.linalg.matrix_rank(book_rows) == 1


def test_normal1_gamma_has_the_closed_form_of_section_14_5():
    """γ of (n1,1), derived by sympy for this constraint alone (Mechanism.derivation), equals
    −2[s_jᵀ(Ė_iĠ_iᵀ s'_i + s'_i ṗ_iᵀṗ_i) + s_iᵀ(Ė_jĠ_jᵀ s'_j + s'_j ṗ_jᵀṗ_j) + ṡ_iᵀṡ_j]
    (the book's printed version has ṗ for p̈, Ġ for Ġᵀ and the opposite sign, and omits the ṗᵀṗ terms that
    its own Jacobian blocks 2(Es̄' + s'pᵀ) require)."""
    from kinbook.spatial import E, G

    mech = two_bodies("normal-1", simple=True)
    c = mech.constraints[-1]
    d = mech.derivation(c)
    assert d.q.shape == (14, 1) and list(d.Phi_q.shape) == [1, 14]
    f = sp.lambdify([list(d.q), list(d.qd)], d.gamma, "numpy")
    rng = np.random.default_rng(12)
    for _ in range(3):
        p = random_p(2, rng)
        pd = rng.normal(size=(2, 4))
        pd -= p * np.sum(p * pd, 1)[:, None]  # tangent: pᵀṗ = 0
        q = np.hstack([rng.normal(size=(2, 3)), p]).ravel()
        qd = np.hstack([rng.normal(size=(2, 3)), pd]).ravel()
        A = [_A(p[k]) for k in range(2)]
        s = [A[0] @ c.a_i, A[1] @ c.a_j]
        sd = [2 * E(pd[k], check=False) @ G(p[k]).T @ a for k, a in enumerate((c.a_i, c.a_j))]
        quad = [2 * (E(pd[k], check=False) @ G(pd[k], check=False).T @ a + a * (pd[k] @ pd[k]))
                for k, a in enumerate((c.a_i, c.a_j))]
        gamma = -(s[1] @ quad[0] + s[0] @ quad[1] + 2 * sd[0] @ sd[1])
        assert float(np.ravel(f(q, qd))[0]) == pytest.approx(gamma, abs=1e-10)
