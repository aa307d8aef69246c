"""The stages of a check, each alone: jets (evaluate), samples, reading, the equivalence rule (match), the
target cache; and the equivalence rule end to end (issue #14 item 2, issue #13 item 4)."""

import numpy as np
import pytest
import sympy as sp

import kinbook
from kinbook import spatial as S
from kinbook.core.symbolic import derive
from kinbook.grading import check_gamma, check_jacobian, check_nu, check_phi
from kinbook.grading.jets import Tape, UnsupportedExpression
from kinbook.grading.read import Refused, read
from kinbook.grading.target import target_for
from kinbook.spatial.rotations import A_from_p, E, a_bar

from .corpus import EX1_PHI_SIMPLE, mechanism

# ================================================================================================ jets
X, Y, T = sp.symbols("x y t", real=True)
DX, DY = sp.symbols("dx dy", real=True)
FUNCS = [
    X**2 * sp.sin(Y) - sp.cos(X * Y) + T**2 * X,
    sp.atan2(Y + 2, X - 3) - sp.exp(T / 2),
    sp.sqrt(X**2 + Y**2 + 1) * sp.log(X**2 + 2) - sp.tan(Y / 3),
    sp.asin(sp.tanh(X) / 2) + sp.acos(Y / 5) + sp.atan(X * T),
    (X + 2) ** Y + sp.Abs(X - 7 + T) * Y,
]


@pytest.mark.parametrize("f", FUNCS, ids=range(len(FUNCS)))
def test_jets_give_sympy_derivatives(f):
    """Φ_q, ν = −Φ_t and γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt from the tape equal sympy's derivation."""
    rng = np.random.default_rng(7)
    Q, QD, Tt = rng.uniform(-1, 1, (12, 2)), rng.normal(size=(12, 2)), rng.uniform(0, 1, 12)
    d = derive([f], [X, Y], [DX, DY], T)
    got = Tape([f], [X, Y], [DX, DY], T).derived(Q, QD, Tt, parts=True)
    for name in ("Phi", "Phi_q", "nu", "gamma"):
        expr = getattr(d, name).replace(sp.DiracDelta, lambda *a: 0)  # |x − 7| is smooth at the samples
        ref = sp.lambdify([X, Y, DX, DY, T], expr, "numpy")
        want = np.stack([np.asarray(ref(*Q[k], *QD[k], Tt[k]), float).reshape(-1) for k in range(12)])
        assert np.allclose(got[name].reshape(12, -1), want, rtol=1e-10, atol=1e-12), name
    assert np.allclose(got["quad"] + got["qt"] + got["tt"], got["gamma"])


def test_jets_rules_make_the_derivation_mistakes():
    phi = sp.Symbol("phi", real=True)
    dphi = sp.Symbol("dphi", real=True)
    tape = Tape([X + 3 * sp.cos(phi)], [X, phi], [DX, dphi], T)
    Q, QD = np.array([[0.2, 0.7]]), np.array([[1.0, 2.0]])
    exact = tape.derived(Q, QD, np.zeros(1))
    dropped = tape.derived(Q, QD, np.zeros(1), rule="chain_dropped")
    a_for_b = tape.derived(Q, QD, np.zeros(1), rule="A_for_B")
    assert np.allclose(exact["Phi_q"][0, 0], [1, -3 * np.sin(0.7)])
    assert np.allclose(dropped["Phi_q"][0, 0], [1, 0])
    assert np.allclose(a_for_b["Phi_q"][0, 0], [1, 3 * np.cos(0.7)])


def test_jets_agree_with_the_kernels_on_every_example():
    for name in kinbook.examples.names():
        m = kinbook.examples.load(name)
        rng = np.random.default_rng(3)
        Q, QD, Tt = rng.uniform(-2, 2, (8, m.n)), rng.normal(size=(8, m.n)), rng.uniform(0, 1, 8)
        phi = sp.Matrix.vstack(*[m.constraint_phi(c) for c in m.constraints])
        got = Tape(list(phi), list(m.q), list(m.qd), m.t).derived(Q, QD, Tt)
        ev = m.evaluate(Q, Tt, QD)
        d = got["Phi"] - ev["Phi"]
        d = (d + np.pi) % (2 * np.pi) - np.pi  # wrapped angle rows
        assert np.abs(d).max() < 1e-9, name
        for q in ("Phi_q", "nu", "gamma"):
            assert np.allclose(got[q], ev[q], rtol=1e-9, atol=1e-9), (name, q)


def test_jets_refuse_what_they_cannot_evaluate():
    with pytest.raises(UnsupportedExpression):
        Tape([sp.Function("f")(X)], [X], [DX], T)
    with pytest.raises(UnsupportedExpression):
        Tape([sp.Symbol("z")], [X], [DX], T)


# ================================================================================================ samples
@pytest.mark.parametrize("name", ["ch13_example1", "ch13_example2", "ch13_example4", "spatial_fourbar"])
def test_assembled_samples_lie_on_the_manifold_with_consistent_velocities(name):
    m = kinbook.examples.load(name)
    for obj in [m] + list(m.constraints):
        t = target_for(obj)
        s = t.samples("assembled")
        assert s.on_manifold and s.N >= 8
        ev = m.evaluate(s.Q, s.T, s.QD)
        rows = t.manifold_rows
        assert np.abs(ev["Phi"][:, rows]).max() < 1e-10
        resid = np.einsum("bij,bj->bi", ev["Phi_q"][:, rows], s.QD) - ev["nu"][:, rows]
        assert np.abs(resid).max() < 1e-9
        if m.kind == "spatial":  # every body's Euler parameters of unit norm, single joints included
            P = s.Q.reshape(s.N, -1, 7)[:, :, 3:]
            assert np.allclose(np.linalg.norm(P, axis=2), 1.0)
            G = t.samples("generic").Q.reshape(-1, m.n // 7, 7)[:, :, 3:]
            assert np.allclose(np.linalg.norm(G, axis=2), 1.0)


def test_samples_are_the_same_every_time():
    a = target_for(kinbook.examples.load("ch13_example3")).samples("assembled")
    b = target_for(kinbook.examples.load("ch13_example3")).samples("assembled")
    assert np.array_equal(a.Q, b.Q) and np.array_equal(a.QD, b.QD) and np.array_equal(a.T, b.T)


# ================================================================================================ reading
def test_reading_spellings_and_refusals():
    t = target_for(mechanism("ch13_example1").constraint("3"))
    A = read(["x_2 + cos(φ2) - x3 + 3*cos(phi_3)", "y2 + sen(phi2) - y3 + 3*sin(phi3)"], t, "Phi")
    assert A.kind == "symbolic" and A.matrix.shape == (2, 1)
    assert read("dphi2 + phi2_dot", t, "gamma").matrix[0].free_symbols == {mechanism("ch13_example1").qd[5]}
    for bad, code in ((True, "malformed"), ([1 + 2j], "malformed"), (["__import__('os')"], "malformed"),
                      (["theta2"], "unknown_symbol"), ([["x1"], ["x2", "x3"]], "wrong_shape"), ({"a": 1}, "malformed")):
        with pytest.raises(Refused) as exc:
            read(bad, t, "Phi")
        assert exc.value.code == code, bad



@pytest.mark.parametrize("name", ["theta2", "x4"])
def test_a_sympy_symbol_the_mechanism_lacks_is_refused_as_unknown_not_a_crash(name):
    """Regression (issue 22): read.py used Msg without importing it, so a *sympy* symbol outside the mechanism
    (theta2, or x4 in a three-body mechanism) crashed every checker with NameError."""
    m = mechanism("ch13_example3")  # three bodies: x4 is no coordinate of it
    bad = sp.Symbol(name)
    x2, phi2 = sp.symbols("x2 phi2")
    for check, answer in ((check_phi, [x2 + sp.cos(bad), phi2]), (check_jacobian, sp.Matrix([[bad] * 9])),
                          (check_gamma, [bad] * m.m), (check_nu, [bad] * m.m)):
        r = check(answer, m)
        assert not r.passed and r.mistakes == ["unknown_symbol"], (check.__name__, r)
        assert f"unknown symbol(s) {name}" in r.messages[0], r
        try:
            kinbook.set_language("es")
            assert f"símbolo(s) desconocido(s) {name}" in r.messages[0], r
        finally:
            kinbook.set_language("en")

def test_the_target_cache_follows_the_mechanism_version():
    """Remove a constraint and add a different one under the same name: the check sees the new one
    (it used to crash on a stale target)."""
    m = kinbook.planar.Mechanism("two bodies")
    m.add_body("a", points={"P": (0, 0)})
    m.add_body("b", points={"P": (1, 0), "Q": (2, 0)})
    m.add(kinbook.planar.Revolute("a", "b", point="P", name="j"))
    assert check_phi(["x1 - x2 - cos(phi2)", "y1 - y2 - sin(phi2)"], m.constraint("j")).passed
    m.remove("j")
    m.add(kinbook.planar.Revolute("a", "b", point_i="P", point_j="Q", name="j"))
    assert check_phi(["x1 - x2 - 2*cos(phi2)", "y1 - y2 - 2*sin(phi2)"], m.constraint("j")).passed
    assert not check_phi(["x1 - x2 - cos(phi2)", "y1 - y2 - sin(phi2)"], m.constraint("j")).passed


# ================================================================================================ equivalence
EX1 = "ch13_example1"


def _with(rows, k, value):
    out = list(rows)
    out[k] = value
    return out


@pytest.mark.parametrize("row5, depends", [
    (EX1_PHI_SIMPLE[3], "row 5 depends on row 4: it repeats it"),
    (f"2*({EX1_PHI_SIMPLE[3]})", "row 5 depends on row 4: it repeats it multiplied by 2"),
    (f"({EX1_PHI_SIMPLE[3]})**2", "row 5 depends on Φ_4"),
    (f"({EX1_PHI_SIMPLE[3]})*({EX1_PHI_SIMPLE[4]})", "row 5 depends on Φ_4, Φ_5"),
])
def test_a_dependent_row_in_place_of_a_row_fails_and_is_named(row5, depends):
    """Φ_4 twice, 2·Φ_4, Φ_4², Φ_4·Φ_5 instead of Φ_5: each row alone is zero where the mechanism is
    assembled, but the set loses rank."""
    r = check_phi(_with(EX1_PHI_SIMPLE, 4, row5), mechanism(EX1))
    assert not r.passed
    assert r.mistakes == ["dependent_row", "missing_row"], r
    assert any(depends in m for m in r.messages), r
    assert [x.label for x in r.rows if x.status == "missing"] == ["Φ_5"]
    assert r.score == pytest.approx(11 / 13)


def test_equivalent_formulations_pass():
    m = mechanism(EX1)
    # a constant combination of two rows in place of one of them: the same constraints
    assert check_phi(_with(EX1_PHI_SIMPLE, 4, f"({EX1_PHI_SIMPLE[3]}) + ({EX1_PHI_SIMPLE[4]})"), m).passed
    # a row times a function that never vanishes
    assert check_phi(_with(EX1_PHI_SIMPLE, 4, f"(2 + cos(phi3))*({EX1_PHI_SIMPLE[4]})"), m).passed
    # but an extra constant combination of rows given is dependent
    r = check_phi(EX1_PHI_SIMPLE + [f"({EX1_PHI_SIMPLE[3]}) - 2*({EX1_PHI_SIMPLE[4]})"], m)
    assert r.mistakes == ["dependent_row"] and "depends on rows 4, 5" in r.messages[1]


def _p1_pair():
    m = S.Mechanism("p1 pair")
    m.add_body("i", q0=(0, 0, 0, 1, 0.2, 0.1, 0))
    m.add_body("j", q0=(1, 0, 0, 1, 0, 0.3, 0.1))
    m.add(S.Parallel1("i", "j", vector_i=(0, 0, 1), vector_j=(0, 0, 2), name="p"))
    return m


def test_all_three_cross_product_rows_of_a_parallel_constraint_are_one_row_too_many():
    """s̃_i s_j has three rows, of which the book keeps two ("only two are independent", §14.4): the third is
    named redundant (issue 22: p1 has two equations)."""
    m = _p1_pair()
    c = m.constraint("p")
    qi, qj = m.body_symbols("i"), m.body_symbols("j")
    cross = (A_from_p(list(qi[3:])) * sp.Matrix([0, 0, 1])).cross(A_from_p(list(qj[3:])) * sp.Matrix([0, 0, 2]))
    r = check_phi(cross, c)
    assert not r.passed and r.mistakes == ["dependent_row"] and r.score == pytest.approx(2 / 3), r
    assert "row 3 is redundant: parallel-1 constraint p (rows Φ_3–Φ_4) has 2 independent equations, and your " \
           "rows 1, 2 already give them" in r.messages[1], r


@pytest.mark.parametrize("which", [(0, 1), (1, 2), (0, 2)])
def test_the_books_cross_product_rows_of_a_parallel_constraint_pass(which):
    """The book writes p1 as two rows of s̃_i s_j = 0; kinbook as two h-rows. Same zero set and rank where
    assembled: accepted, in Φ and in Φ_q (the Jacobian of that formulation)."""
    m = _p1_pair()
    c = m.constraint("p")
    qi, qj = m.body_symbols("i"), m.body_symbols("j")
    si = A_from_p(list(qi[3:])) * sp.Matrix([0, 0, 1])
    sj = A_from_p(list(qj[3:])) * sp.Matrix([0, 0, 2])
    cross = sp.Matrix([si.cross(sj)[k] for k in which])
    assert check_phi(cross, c, order="book").passed
    assert check_jacobian(cross.jacobian(sp.Matrix.vstack(qi, qj)), c).passed
    assert check_nu([0] * len(which), c, phi=cross).passed
    own = derive(cross, sp.Matrix.vstack(qi, qj), sp.Matrix(sp.symbols("dq0:14")), m.t)
    gamma = own.gamma.subs({a: b for a, b in zip(own.qd, list(m.qd))})
    assert check_gamma(gamma, c, phi=cross).passed


def test_the_eg_jacobian_is_named():
    """2Eā without 2apᵀ: the derivative of E Gᵀ a, not of the A(p) the constraint uses."""
    m = S.Mechanism("n1 pair")
    m.add_body("i", q0=(0, 0, 0, 1, 0.2, 0.1, 0))
    m.add_body("j", q0=(1, 0, 0, 1, 0, 0.3, 0.1))
    m.add(S.Normal1("i", "j", vector_i=(0, 0, 1), vector_j=(1, 0, 0), name="n1"))
    qi, qj = m.body_symbols("i"), m.body_symbols("j")
    pi, pj = sp.Matrix(qi[3:]), sp.Matrix(qj[3:])
    ai, aj = sp.Matrix([0, 0, 1]), sp.Matrix([1, 0, 0])
    si, sj = A_from_p(pi) * ai, A_from_p(pj) * aj
    good = sp.Matrix.hstack(sp.zeros(1, 3), 2 * sj.T * (E(pi) * a_bar(ai) + ai * pi.T), sp.zeros(1, 3),
                            2 * si.T * (E(pj) * a_bar(aj) + aj * pj.T))
    eg = sp.Matrix.hstack(sp.zeros(1, 3), 2 * sj.T * E(pi) * a_bar(ai), sp.zeros(1, 3), 2 * si.T * E(pj) * a_bar(aj))
    assert check_jacobian(good, m.constraint("n1")).passed
    r = check_jacobian(eg, m.constraint("n1"))
    assert (r.passed, r.mistakes) == (False, ["eg_jacobian"])


def test_a_normalization_row_given_with_a_joint_is_named_not_miscounted():
    """14-4 TI1: the spherical joint's three rows and a pᵀp − 1 row: the extra row belongs to the body."""
    ball = S.Mechanism("ball joint")
    ball.add_body("i", points={"P": (0, 0, 1)})
    ball.add_body("j", points={"P": (-1, 0.5, 0)})
    ball.add(S.Spherical("i", "j", point="P", name="ball"))
    qi, qj = ball.body_symbols("i"), ball.body_symbols("j")
    rows = list(sp.Matrix(qi[:3]) + A_from_p(list(qi[3:])) * sp.Matrix([0, 0, 1]) - sp.Matrix(qj[:3])
                - A_from_p(list(qj[3:])) * sp.Matrix([-1, 0.5, 0]))
    assert check_phi(rows, ball.constraint("ball")).passed
    r = check_phi(rows + [sum(x**2 for x in qi[3:]) - 1], ball.constraint("ball"))
    assert r.mistakes == ["dependent_row"]
    assert "3 of 4 rows correct (score 0.75)" in r.messages[0]
    assert "normalization" in r.messages[1]


def test_every_joint_of_a_mechanism_graded_alone_and_whole_gives_the_same_verdict():
    m = mechanism("ch13_example2")
    d = m.symbolic()
    for c in m.constraints:
        rows = list(range(c.rows.start, c.rows.stop))
        assert check_phi([-d.Phi[k] for k in rows], c).passed, c.name
        assert check_jacobian(d.Phi_q[rows, :], c).passed, c.name
        assert check_gamma(d.gamma[rows, :], c).passed, c.name
