"""The book's examples 1–6 solved with kinbook, checked against facts computed here independently
(link lengths, coincident joint points, drivers satisfied, |v_A| = ω·O_A A) — never against the book's printed
numbers, some of which are wrong."""

import numpy as np
import pytest

from kinbook import examples

OMEGA = 100.0


def dist(a, b):
    return float(np.hypot(*(np.asarray(a) - np.asarray(b))))


@pytest.fixture(scope="module", params=[1, 2, 3, 4])
def solved(request):
    m = examples.load(f"ch13_example{request.param}")
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    qdd = m.solve_acceleration(q, qd, 0.0)
    return request.param, m, q, qd, qdd


def test_constraint_counts_as_the_book_counts(solved):
    k, m, *_ = solved
    n, m_geo = {1: (12, 11), 2: (12, 11), 3: (9, 8), 4: (9, 8)}[k]
    assert (m.n, m.m_geometric, m.dof, m.m) == (n, m_geo, 1, n)


def test_ground_fixed_and_driver_satisfied(solved):
    _, m, q, qd, qdd = solved
    np.testing.assert_allclose(q[:3], 0, atol=1e-12)
    phi2 = q[m.index("phi2")]
    start = 3 * np.pi / 4 if m.name in ("ch13_example1", "ch13_example3") else np.pi / 4
    assert phi2 == pytest.approx(start, abs=1e-12)
    assert qd[m.index("phi2")] == pytest.approx(OMEGA)
    assert qdd[m.index("phi2")] == pytest.approx(0, abs=1e-9)


def test_link_lengths_are_kept(solved):
    _, m, q, *_ = solved
    A = m.point_position(q, "crank", "A")
    OA = m.point_position(q, "ground", "OA")
    assert dist(A, OA) == pytest.approx(2)
    if m.name == "ch13_example1":
        B = m.point_position(q, "rocker", "B")
        assert dist(A, B) == pytest.approx(6)
        assert dist(B, m.point_position(q, "ground", "OB")) == pytest.approx(3)
        np.testing.assert_allclose(m.point_position(q, "coupler", "A"), A, atol=1e-12)
        np.testing.assert_allclose(m.point_position(q, "coupler", "B"), B, atol=1e-12)
    elif m.name == "ch13_example3":
        B = m.point_position(q, "rocker", "B")
        assert dist(A, B) == pytest.approx(6)
        assert dist(B, m.point_position(q, "ground", "OB")) == pytest.approx(3)
    else:
        B = m.point_position(q, "rod", "B")
        assert dist(A, B) == pytest.approx(6)
        assert B[1] == pytest.approx(0, abs=1e-12)  # on the slide line through O_A
        if m.name == "ch13_example2":
            np.testing.assert_allclose(m.point_position(q, "slider", "B"), B, atol=1e-12)
            assert q[m.index("phi4")] == pytest.approx(0, abs=1e-12)


def test_crank_tip_speed_and_acceleration(solved):
    _, m, q, qd, qdd = solved
    vA = m.point_velocity(q, qd, "crank", "A")
    aA = m.point_acceleration(q, qd, qdd, "crank", "A")
    assert np.linalg.norm(vA) == pytest.approx(OMEGA * 2)  # |v_A| = ω · O_A A
    assert np.linalg.norm(aA) == pytest.approx(OMEGA**2 * 2)  # centripetal only: ω constant
    # v_A is perpendicular to the crank
    A = m.point_position(q, "crank", "A")
    assert np.dot(vA, A) == pytest.approx(0, abs=1e-9)


def test_velocities_and_accelerations_are_time_derivatives_of_positions(solved):
    _, m, q, qd, qdd = solved
    h = 1e-5
    qp = m.solve_position(h, q0=q)
    qm = m.solve_position(-h, q0=q)
    np.testing.assert_allclose(qd, (qp - qm) / (2 * h), rtol=1e-6, atol=1e-4)
    np.testing.assert_allclose(qdd, (qp - 2 * q + qm) / h**2, rtol=1e-3, atol=5.0)


def test_example_3_is_example_1_without_the_coupler():
    m1, m3 = examples.load("ch13_example1"), examples.load("ch13_example3")
    q1, q3 = m1.solve_position(0.0), m3.solve_position(0.0)
    np.testing.assert_allclose(q3[:6], q1[:6], atol=1e-10)
    np.testing.assert_allclose(q3[6:9], q1[9:12], atol=1e-10)  # the rocker is body 3 in example 3
    qd1, qd3 = m1.solve_velocity(q1, 0.0), m3.solve_velocity(q3, 0.0)
    np.testing.assert_allclose(qd3[6:9], qd1[9:12], atol=1e-8)


def test_example_4_is_example_2_without_the_slider():
    m2, m4 = examples.load("ch13_example2"), examples.load("ch13_example4")
    q2, q4 = m2.solve_position(0.0), m4.solve_position(0.0)
    np.testing.assert_allclose(q4, q2[:9], atol=1e-10)


def test_example_1_book_configuration_violates_the_coupler_length():
    """Why the workbook reports an erratum: the book's B = (4.5697, 2.5566) is 3 from O_B but not 6 from A."""
    m = examples.load("ch13_example1")
    q = m.solve_position(0.0)
    A = m.point_position(q, "crank", "A")
    assert dist(A, (4.5697, 2.5566)) - 6 > 0.05
    B = m.point_position(q, "rocker", "B")
    assert dist(B, A) == pytest.approx(6)
