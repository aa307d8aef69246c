"""The shipped spatial examples, solved over a sweep, keep their joints together: facts from geometry, not
from the book's printed numbers."""

import numpy as np
import pytest

from kinbook import examples

T = np.linspace(0.0, 1.0, 241)  # one crank turn (θ = 2πt)


@pytest.fixture(scope="module")
def fourbar():
    mech = examples.load("spatial_fourbar")
    return mech, mech.simulate(T)


@pytest.fixture(scope="module")
def slider_crank():
    mech = examples.load("spatial_slider_crank")
    return mech, mech.simulate(T)


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def test_examples_are_listed_and_one_dof():
    assert {"spatial_fourbar", "spatial_slider_crank"} <= set(examples.names())
    for name in ("spatial_fourbar", "spatial_slider_crank"):
        mech = examples.load(name)
        assert (mech.n, mech.m, mech.dof) == (28, 28, 1)


def check_common(mech, res):
    assert len(res) == len(T) and res.failure is None
    np.testing.assert_allclose(np.abs(mech.Phi(res.q, res.t)).max(), 0, atol=1e-9)
    for body in mech.bodies:
        np.testing.assert_allclose(np.linalg.norm(mech.p(res.q, body.name), axis=1), 1.0, atol=1e-12)
        # pᵀṗ = 0 and ground stays put
    np.testing.assert_allclose(res.q[:, :7], np.tile([0, 0, 0, 1, 0, 0, 0], (len(T), 1)), atol=1e-12)
    # crank pin on the circle of radius 1 in the XY plane at the driven angle
    theta = 2 * np.pi * res.t
    np.testing.assert_allclose(res.position("crank", "A"), np.column_stack([np.cos(theta), np.sin(theta), 0 * theta]),
                               atol=1e-9)


def test_fourbar_geometry_over_a_full_turn(fourbar):
    mech, res = fourbar
    check_common(mech, res)
    q = res.q
    # joints: coincident points
    np.testing.assert_allclose(res.position("ground", "OA"), res.position("crank", "OA"), atol=1e-9)
    np.testing.assert_allclose(res.position("crank", "A"), res.position("coupler", "A"), atol=1e-9)
    np.testing.assert_allclose(res.position("coupler", "B"), res.position("rocker", "B"), atol=1e-9)
    np.testing.assert_allclose(res.position("ground", "OB"), res.position("rocker", "OB"), atol=1e-9)
    # revolute axes parallel to the ground's Z and X
    np.testing.assert_allclose(mech.A(q, "crank")[:, :, 2], np.tile([0, 0, 1], (len(T), 1)), atol=1e-9)
    np.testing.assert_allclose(mech.A(q, "rocker")[:, :, 0], np.tile([1, 0, 0], (len(T), 1)), atol=1e-9)
    # universal joint: cross arms perpendicular
    arm_c = mech.A(q, "coupler")[:, :, 1]
    arm_r = mech.A(q, "rocker")[:, :, 0]
    np.testing.assert_allclose(np.einsum("ki,ki->k", arm_c, arm_r), 0, atol=1e-9)
    # link lengths: crank pin to rocker pin 3.2, rocker pin 1.5 from O_B, in the plane x = 0
    AB = res.position("rocker", "B") - res.position("crank", "A")
    np.testing.assert_allclose(np.linalg.norm(AB, axis=1), 3.2, atol=1e-9)
    B = res.position("rocker", "B")
    np.testing.assert_allclose(np.linalg.norm(B - [0, 3, 1], axis=1), 1.5, atol=1e-9)
    np.testing.assert_allclose(B[:, 0], 0, atol=1e-9)


def test_slider_crank_follows_the_closed_form(slider_crank):
    mech, res = slider_crank
    check_common(mech, res)
    theta = 2 * np.pi * res.t
    w = 2 * np.pi
    root = np.sqrt(5 - (0.5 - np.sin(theta)) ** 2)
    xB = np.cos(theta) + root
    B = res.position("slider", "B")
    np.testing.assert_allclose(B, np.column_stack([xB, 0.5 + 0 * xB, 2 + 0 * xB]), atol=1e-9)
    np.testing.assert_allclose(res.position("rod", "B"), B, atol=1e-9)
    np.testing.assert_allclose(res.position("rod", "A"), res.position("crank", "A"), atol=1e-9)
    # the slider does not rotate (translational joint), rod length 3
    np.testing.assert_allclose(mech.p(res.q, "slider"), np.tile([1, 0, 0, 0], (len(T), 1)), atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(B - res.position("crank", "A"), axis=1), 3.0, atol=1e-9)
    # velocity and acceleration of the slider: derivatives of the closed form
    u = 0.5 - np.sin(theta)
    dxB = w * (-np.sin(theta) + u * np.cos(theta) / root)
    d2xB = w**2 * (-np.cos(theta) + (-np.cos(theta) ** 2 - u * np.sin(theta)) / root
                   - (u * np.cos(theta)) ** 2 / root**3)
    np.testing.assert_allclose(res.velocity("slider", "B")[:, 0], dxB, atol=1e-8)
    np.testing.assert_allclose(res.acceleration("slider", "B")[:, 0], d2xB, atol=1e-7)
    # universal joint: cross arms perpendicular
    arms = np.einsum("ki,ki->k", mech.A(res.q, "rod")[:, :, 1], mech.A(res.q, "slider")[:, :, 1])
    np.testing.assert_allclose(arms, 0, atol=1e-9)


def test_velocities_and_accelerations_are_derivatives_of_the_sweep(fourbar):
    mech, res = fourbar
    h = T[1] - T[0]
    k = np.arange(1, len(T) - 1)
    for body in ("coupler", "rocker"):
        r = res.position(body, "B")
        np.testing.assert_allclose(res.velocity(body, "B")[k], (r[k + 1] - r[k - 1]) / (2 * h), rtol=0, atol=2e-3 * 40)
        v = res.velocity(body, "B")
        np.testing.assert_allclose(res.acceleration(body, "B")[k], (v[k + 1] - v[k - 1]) / (2 * h), atol=0.5)
    # angular velocity: crank turns at 2π rad/s about Z; ω from Ȧ Aᵀ by differences
    np.testing.assert_allclose(mech.angular_velocity(res.q, res.qd, "crank"), np.tile([0, 0, 2 * np.pi], (len(T), 1)),
                               atol=1e-9)
    np.testing.assert_allclose(mech.angular_acceleration(res.q, res.qdd, "crank"), 0, atol=1e-8)
    A = mech.A(res.q, "rocker")
    W = np.einsum("kij,klj->kil", (A[k + 1] - A[k - 1]) / (2 * h), A[k])
    w_fd = np.column_stack([W[:, 2, 1], W[:, 0, 2], W[:, 1, 0]])
    w = mech.angular_velocity(res.q, res.qd, "rocker")[k]
    np.testing.assert_allclose(w, w_fd, atol=0.05 * np.abs(w).max())
    np.testing.assert_allclose(w[:, 1:], 0, atol=1e-9)  # the rocker turns about X only
    np.testing.assert_allclose(mech.angular_velocity(res.q, res.qd, "rocker", frame="body")[k],
                               np.einsum("kji,kj->ki", A[k], w), atol=1e-12)


def test_slider_driven_past_its_reach_stops_at_the_dead_point():
    from kinbook.errors import AssemblyError
    from kinbook.spatial import DistanceDriver

    mech = examples.load("spatial_slider_crank")
    mech.remove("crank angle")
    mech.add(DistanceDriver("ground", "slider", axis_i="x", point_i="P", point_j="B", f="3.1 + t", name="stroke"))
    theta = np.linspace(0, 2 * np.pi, 200001)
    reach = np.max(np.cos(theta) + np.sqrt(5 - (0.5 - np.sin(theta)) ** 2))  # farthest slider position
    times = np.linspace(0, 0.2, 201)
    with pytest.raises(AssemblyError, match=r"cannot be assembled at t = .*driver 'stroke' = 3\.19") as info:
        mech.simulate(times)
    err = info.value
    assert 3.1 + times[len(err.partial) - 1] <= reach < 3.1 + err.t
    np.testing.assert_allclose(err.partial.position("slider", "B")[:, 0], 3.1 + err.partial.t, atol=1e-9)


def test_a_sweep_that_starts_later_stays_on_the_same_assembly_branch(fourbar):
    mech, res = fourbar
    part = mech.simulate(T[100:160])
    np.testing.assert_allclose(part.q, res.q[100:160], atol=1e-8)
    np.testing.assert_allclose(part.qd, res.qd[100:160], atol=1e-7)
