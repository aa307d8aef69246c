"""Table 14.1 filled in (kinbook.book.table14) agrees with the kernels, and the check tables catch a wrong entry."""

import numpy as np
import pytest

import kinbook
from kinbook.book import table14, verify
from kinbook.spatial import constraints as sc


@pytest.fixture(scope="module")
def bench():
    m = table14.bench()
    return m, table14.bench_states(m)


def test_every_type_of_the_bench_has_an_entry_that_agrees(bench):
    m, states = bench
    types = {type(c) for c in m.constraints}
    assert types >= {sc.Normal1, sc.Normal2, sc.Parallel1, sc.Parallel2, sc.Spherical, sc.SphericalSpherical,
                     sc.Universal, sc.Revolute, sc.Cylindrical, sc.Translational, sc.Ground, sc.Normalization}
    jac = verify.jacobian_table(m, [q for q, _, _ in states])
    gam = verify.gamma_table(m, states)
    assert jac.all_ok and gam.all_ok
    assert all(r[4] != "—" for r in jac.rows) and all(r[4] != "—" for r in gam.rows)


def test_entries_match_the_kernels_at_other_states(bench):
    """Independent of the tables: the closed forms against the mechanism's own Φ_q and γ, state by state."""
    m, _ = bench
    for q, qd, _ in table14.bench_states(m, seed=3, scales=((1.0, 1.0), (0.7, 1.4), (1.0, 1.0))):
        J, g = m.Phi_q(q), m.gamma(q, qd)
        for c in m.constraints:
            cols = verify.columns(m, c)
            assert np.allclose(table14.jacobian_rows(c, q[cols]), J[c.rows][:, cols], atol=1e-12)
            assert np.allclose(table14.gamma_rows(c, q[cols], qd[cols]), g[c.rows], atol=1e-11)


def test_a_wrong_entry_is_caught_where_it_is_used(bench, monkeypatch):
    m, states = bench
    right = table14.ENTRIES[sc.Normal1]

    def wrong(c, bi, bj):  # the (n1,1) row with the sign of s_iᵀ C_j flipped, and γ without its 2 ṡ_iᵀṡ_j
        (row, gamma), = right(c, bi, bj)
        if gamma is not None:
            gamma = gamma + 2 * (bi.vec(c.a_i)[2] @ bj.vec(c.a_j)[2])
        return [(np.c_[row[:, :7], -row[:, 7:]], gamma)]

    monkeypatch.setitem(table14.ENTRIES, sc.Normal1, wrong)
    table = verify.jacobian_table(m, [q for q, _, _ in states])
    failed = {r[0] for r in table.rows if not r[4].ok}
    assert failed == {"n1", "universal", "translational"}  # the composites that stack an (n1,1) part
    assert all(r[3].ok and r[5].ok for r in table.rows)  # finite differences and sympy still agree with kinbook
    assert "✗" in repr(table) and not table.all_ok
    gam = verify.gamma_table(m, states)
    assert {r[0] for r in gam.rows if not r[4].ok} == failed
    assert all(r[2].ok and r[3].ok for r in gam.rows)


def test_types_without_an_entry():
    m = kinbook.examples.load("spatial_fourbar")
    driver = next(c for c in m.constraints if c.kind == "driver")
    q = m.solve_position(0.0)
    assert not table14.has_entry(driver) and table14.jacobian_rows(driver, q[verify.columns(m, driver)]) is None
    table = verify.jacobian_table(m, [q])
    assert [r[4] for r in table.rows if r[0] == driver.name] == ["—"] and table.all_ok


def test_planar_mechanisms_are_checked_without_the_table():
    m = kinbook.examples.load("ch13_example3")
    q = m.solve_position(0.0)
    table = verify.jacobian_table(m, [q])
    assert table.all_ok and {r[4] for r in table.rows} == {"—"}
