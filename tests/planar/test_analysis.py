import numpy as np
import pytest

from kinbook import (
    AssemblyError,
    ConvergenceError,
    DeadPointError,
    DriverCountError,
    RedundantConstraintsError,
    examples,
)
from kinbook.planar import Simple

THETA_LIMIT = np.arccos(1 / 3)  # |A − O_B| = coupler − rocker = 3 when 13 − 12 cos θ = 9


def example1_at_limit():
    """Example 1 in its limit position, built from geometry alone: O_B lies between A and B on one line."""
    m = examples.load("ch13_example1")
    th = 2 * np.pi - THETA_LIMIT  # the limit reached when turning counter-clockwise from 135°
    A = 2 * np.array([np.cos(th), np.sin(th)])
    OB = np.array([3.0, 0.0])
    B = OB + 3 * (OB - A) / np.linalg.norm(OB - A)
    ang = lambda v: np.arctan2(v[1], v[0])
    q = np.concatenate([[0, 0, 0], A / 2, [th], (A + B) / 2, [ang(B - A)], (B + OB) / 2, [ang(OB - B)]])
    t = (th - 3 * np.pi / 4) / 100
    return m, q, t


def test_sweep_of_example_1_stops_at_the_dead_point():
    m = examples.load("ch13_example1")
    times = np.linspace(0, 2 * np.pi / 100, 400)  # one crank turn at ω = 100
    with pytest.raises(AssemblyError, match=r"cannot be assembled at t = 0\.027.*driver 'driver 1' = .*dead point") as exc:
        m.simulate(times)
    err = exc.value
    reached = err.partial.coordinate("phi2")
    assert reached[-1] < 2 * np.pi - THETA_LIMIT < err.drivers["driver 1"]
    assert len(err.partial) == np.searchsorted(times, err.t)
    # every instant solved before the failure satisfies Φ = 0
    assert np.abs(m.Phi(err.partial.q, err.partial.t)).max() < 1e-9


def test_truncated_sweep_returns_the_reachable_range():
    m = examples.load("ch13_example1")
    r = m.simulate(np.linspace(0, 2 * np.pi / 100, 400), on_failure="truncate")
    assert r.failure is not None and len(r) < 400
    A = r.position("crank", "A")
    B = r.position("rocker", "B")
    np.testing.assert_allclose(np.linalg.norm(A - B, axis=1), 6, atol=1e-9)


def test_dead_point_is_diagnosed():
    m, q, t = example1_at_limit()
    assert np.abs(m.Phi(q, t)).max() < 1e-12
    d = m.diagnose(q, t)
    assert d.kind == "dead-point"
    assert d.rank == 11 and "driver 1" in d.constraints
    with pytest.raises(DeadPointError, match=r"dead point — .*driver 'driver 1'") as exc:
        m.solve_velocity(q, t)
    assert 12 in exc.value.rows


def test_redundant_constraints_are_named():
    m = examples.load("ch13_example1")
    m.remove("driver 1")  # drop the driver ...
    m.add(Simple("ground", "x", 0))  # ... and fix x1 a second time
    with pytest.raises(RedundantConstraintsError, match=r"redundant .* rows 1, 12 .*ground.*simple") as exc:
        m.solve_position(0.0)
    assert exc.value.rows == [1, 12]


def test_driver_count_is_checked():
    m = examples.load("ch13_example3")
    m.remove("driver 1")
    with pytest.raises(DriverCountError, match=r"n = 9 coordinates and 8 geometric .* 1 degree\(s\) of freedom, but 0 driver"):
        m.solve_position(0.0)


def test_non_convergence_names_rows():
    m = examples.load("ch13_example1")
    with pytest.raises(ConvergenceError, match=r"did not converge .* after 2 iterations .* row \d+ = ") as exc:
        m.solve_position(0.0, max_iter=2)
    assert exc.value.iterations == 2 and exc.value.residual > 1e-10


def test_batched_sweep_equals_sequential_solutions():
    m = examples.load("ch13_example2")
    times = np.linspace(0, 0.05, 101)
    r = m.simulate(times, anchor_every=16)
    for k in (0, 7, 33, 100):
        qk = m.solve_position(times[k], q0=r.q[k] + 1e-3)
        np.testing.assert_allclose(r.q[k], qk, atol=1e-9)
        qd = m.solve_velocity(qk, times[k])
        np.testing.assert_allclose(r.qd[k], qd, rtol=1e-8, atol=1e-8)
        np.testing.assert_allclose(r.qdd[k], m.solve_acceleration(qk, qd, times[k]), rtol=1e-7, atol=1e-6)


def test_full_crank_turn_of_the_slider_crank():
    m = examples.load("ch13_example2")
    times = np.linspace(0, 2 * np.pi / 100, 361)
    r = m.simulate(times)
    x_B = r.position("slider", "B")[:, 0]
    # stroke of a slider-crank = 2 × crank length: extreme positions 6 ± 2 from O_A
    assert x_B.max() == pytest.approx(8, abs=1e-3) and x_B.min() == pytest.approx(4, abs=1e-3)
    # velocity of the slider is the time derivative of its position
    v = r.velocity("slider", "B")[:, 0]
    np.testing.assert_allclose(np.gradient(x_B, times)[1:-1], v[1:-1], rtol=2e-2, atol=20)


def test_sparse_solve_of_a_long_chain_matches_dense():
    from kinbook.planar import Driver, Ground, Mechanism, Revolute

    m = Mechanism("chain")
    m.add_body("ground", points={"O": (0, 0)})
    N = 60  # 183 coordinates: above the sparse threshold
    for k in range(N):
        m.add_body(f"b{k}", points={"L": (-0.5, 0), "R": (0.5, 0)}, q0=(k + 0.5, 0, 0))
    m.add(Ground("ground"))
    m.add(Revolute("ground", "b0", point_i="O", point_j="L"))
    for k in range(1, N):
        m.add(Revolute(f"b{k-1}", f"b{k}", point_i="R", point_j="L"))
    for k in range(N):
        m.add(Driver(f"b{k}", "phi", f"{0.01 * (k + 1)}*t"))
    q = m.solve_position(1.0)
    tip = m.point_position(q, f"b{N-1}", "R")
    angles = 0.01 * np.arange(1, N + 1)
    np.testing.assert_allclose(tip, [np.cos(angles).sum(), np.sin(angles).sum()], atol=1e-10)
    np.testing.assert_allclose(m.Phi_q(q, 1.0, sparse=True).toarray(), m.Phi_q(q, 1.0))


def test_sweep_starting_near_a_limit_stays_on_the_branch_of_q0():
    """The bodies' q0 describe the book's branch at t = 0 (rocker at about 241°); a sweep that starts near the
    other limit position must follow that branch, not jump to the mirror assembly."""
    m = examples.load("ch13_example3")
    t_start = (2 * np.pi - THETA_LIMIT - 0.05 - 3 * np.pi / 4) / 100  # crank 3° short of its upper limit
    r = m.simulate(np.linspace(t_start, 0.0, 50))
    phi3_at_0 = m.solve_position(0.0)[m.index("phi3")]
    assert r.coordinate("phi3")[-1] == pytest.approx(phi3_at_0, abs=1e-9)
    assert np.all(np.abs(np.diff(r.coordinate("phi3"))) < 0.2)  # continuous: no jump between branches


@pytest.mark.parametrize("name", ["ch13_example1", "ch13_example2", "spatial_fourbar"])
def test_fixed_bodies_are_set_aside_without_changing_the_system(name):
    """The solvers factor Φ_q without the ground's rows and columns; that block-triangular reduction must be the
    full matrix with those rows and columns deleted, and the ground's deleted rows must involve its columns
    only (otherwise the reduced system would not be equivalent)."""
    m = examples.load(name)
    rows, cols = m.reduction
    fixed_rows = np.setdiff1d(np.arange(m.m), rows)
    fixed_cols = np.setdiff1d(np.arange(m.n), cols)
    ground = m.bodies[0].name
    assert len(fixed_rows) == len(fixed_cols) == len(m.COORDS)
    np.testing.assert_array_equal(fixed_cols, np.arange(len(m.COORDS)) + len(m.COORDS) * (m.body(ground).number - 1))
    rng = np.random.default_rng(3)
    q = m.q0 + 0.1 * rng.standard_normal((5, m.n))
    full = m.evaluate(q, 0.01)["Phi_q"]
    red = m.evaluate(q, 0.01, reduced=True)["Phi_q"]
    np.testing.assert_array_equal(red, full[:, rows][:, :, cols])
    assert not full[:, fixed_rows][:, :, cols].any()
    # a sweep keeps the ground where it is (to rounding: the first instant is solved with the full system),
    # with zero velocity and acceleration
    r = m.simulate(np.linspace(0, 0.01, 21))
    np.testing.assert_allclose(r.q[:, fixed_cols], np.broadcast_to(m.q0[fixed_cols], (21, len(fixed_cols))),
                               atol=1e-15)
    np.testing.assert_allclose(r.qd[:, fixed_cols], 0, atol=1e-15 * np.abs(r.qd).max())
    np.testing.assert_allclose(r.qdd[:, fixed_cols], 0, atol=1e-15 * np.abs(r.qdd).max())


def test_no_reduction_without_a_fully_fixed_body():
    m = examples.load("ch13_example2")
    m.remove(m.constraints[0].name)  # the ground constraint
    m.add(Simple(m.bodies[0].name, "x"))
    assert m.reduction is None


def test_hermite_guess_is_exact_for_quintics():
    """The sweep's guesses between two solved instants interpolate q, q̇, q̈ at both ends; a quintic in t is
    reproduced exactly (so the guess error is O(h⁶) for a smooth motion)."""
    from kinbook.core.sweep import _hermite5

    rng = np.random.default_rng(8)
    c = rng.normal(size=(6, 3))  # q(t) = Σ c_k t^k, three coordinates

    def q(t, d=0):
        k = np.arange(6)
        coef = np.array([np.prod(np.arange(j - d + 1, j + 1)) if j >= d else 0.0 for j in k])
        powers = np.where(k >= d, np.power.outer(t, np.maximum(k - d, 0)), 0.0)
        return (powers * coef) @ c

    t0, t1 = np.array([0.2, -1.0]), np.array([0.9, 0.5])
    t = t0 + np.array([0.3, 0.85]) * (t1 - t0)
    ends = [tuple(q(tt, d) for d in range(3)) for tt in (t0, t1)]
    np.testing.assert_allclose(_hermite5(t, t0, t1, *ends), q(t), rtol=1e-12, atol=1e-12)


# --------------------------------------------------------------------------------------------- continuation
def test_following_past_the_dead_point_stops_at_the_limit_configuration():
    from kinbook.core.sweep import follow

    m, q_limit, t_limit = example1_at_limit()
    q0 = m.solve_position(0.0)
    dt = 0.05 / 100  # 0.05 rad of crank per step
    at = follow(m, 0.02, t_from=0.0, q_from=q0, max_step=dt)  # φ₂ would be 135° + 114.6°: reachable
    assert at.reached and at.t == 0.02 and np.max(np.abs(m.Phi(at.q, at.t))) < 1e-10
    at = follow(m, 0.03, t_from=0.0, q_from=q0, max_step=dt)  # 135° + 171.9° = 306.9°: past 289.47°
    assert not at.reached and isinstance(at.failure, (ConvergenceError, DeadPointError))
    assert t_limit - dt / 1024 <= at.t <= t_limit  # the limit, to within min_step
    assert np.max(np.abs(m.Phi(at.q, at.t))) < 1e-10
    diff = at.q - q_limit
    diff[2::3] = np.mod(diff[2::3] + np.pi, 2 * np.pi) - np.pi  # angles modulo a turn
    np.testing.assert_allclose(diff, 0, atol=2e-2)  # near the limit Φ_q is singular: q is √(Δt)-sensitive
    assert m.diagnose(at.q, at.t).cond > 1e3


def test_following_many_instants_goes_outward_from_the_start():
    from kinbook.core.sweep import follow_times

    m, _, t_limit = example1_at_limit()
    times = [0.03, 0.0, -0.005, 0.01, -0.02]  # 306.9° (past), 135°, 106.4°, 192.3°, 20.4° (past 70.53°)
    found = follow_times(m, times, t0=0.0, max_step=0.0005)
    assert [f.reached for f in found] == [False, True, True, True, False]
    t_low = (THETA_LIMIT - 3 * np.pi / 4) / 100
    assert found[0].t == pytest.approx(t_limit, abs=1e-6) and found[4].t == pytest.approx(t_low, abs=1e-6)
    for f in found:
        assert np.max(np.abs(m.Phi(f.q, f.t))) < 1e-10
    # one branch: B stays on the same side of the line from A to O_B (the other branch is its mirror image)
    def side(q):
        A, B = m.point_position(q, "crank", "A"), m.point_position(q, "coupler", "B")
        (ax, ay), (bx, by) = B - A, np.array([3.0, 0.0]) - A
        return np.sign(ax * by - ay * bx)

    assert len({side(f.q) for f in found if f.reached}) == 1  # (at a limit B, O_B and A are aligned)
