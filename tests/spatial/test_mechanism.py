"""The spatial Mechanism: sizes and names, normalization rows, errors that name what is wrong, mechanism
files, diagnosis of redundant constraints and point kinematics."""

import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

import kinbook
from kinbook import examples
from kinbook.errors import (
    DriverCountError,
    ExpressionError,
    InputError,
    MechanismFileError,
    ModelError,
    RedundantConstraintsError,
    UnknownBodyError,
    UnknownPointError,
)
from kinbook.planar import Revolute as PlanarRevolute
from kinbook.spatial import (
    DistanceDriver,
    Ground,
    Mechanism,
    Normalization,
    Revolute,
    RevoluteDriver,
    Spherical,
    Translational,
    p_from_axis_angle,
)


def pendulum():
    m = Mechanism("pendulum")
    m.add_body("ground", points={"O": (0, 0, 0)}, vectors={"z": (0, 0, 1), "x": (1, 0, 0)})
    m.add_body("bar", points={"O": (-1, 0, 0), "T": (1, 0, 0)}, q0=(1, 0, 0, 1, 0, 0, 0),
               vectors={"axis": (0, 0, 1), "arm": (1, 0, 0)})
    m.add(Ground("ground"))
    m.add(Revolute("ground", "bar", point="O", axis_i="z", axis_j="axis"))
    return m


def test_sizes_names_and_symbols():
    m = pendulum()
    assert (m.n, m.m, m.m_geometric, m.dof) == (14, 13, 13, 1)
    assert m.coordinate_names()[:7] == ["x1", "y1", "z1", "e01", "e11", "e21", "e31"]
    assert [str(s) for s in m.q[7:9]] == ["x2", "y2"] and str(m.qd[10]) == "de02"
    assert m.index("e32") == 13 and m.index(("bar", "x")) == 7
    kinds = [c.kind for c in m.constraints]
    assert kinds == ["normalization", "normalization", "simple", "joint"]
    assert [c.name for c in m.constraints[:2]] == ["normalization ground", "normalization bar"]
    table = repr(m.constraint_table())
    assert "revolute (s,3 + p1,2)" in table and "Φ_1" in table and "DOF = " in table
    assert "<table>" in m.constraint_table()._repr_html_()
    with pytest.raises(InputError, match="no coordinate 'phi2'"):
        m.index("phi2")


def test_normalization_rows_are_in_phi():
    m = pendulum()
    q = m.q0.copy()
    q[3:7] = [2, 0, 0, 0]  # |p|² = 4 -> the ground's normalization row reads 3
    assert m.Phi(q)[0] == pytest.approx(3.0)
    d = m.symbolic()
    e = m.q[3:7, 0]
    assert sp.simplify(d.Phi[0] - (e.T * e)[0] + 1) == 0
    with pytest.raises(ModelError, match="added with their body"):
        m.add(Normalization("bar"))


def test_q0_euler_parameters_are_normalized_and_zero_is_rejected():
    m = Mechanism("m")
    m.add_body("a", q0=(0, 0, 0, 1, 0, 0, 1))
    np.testing.assert_allclose(m.q0[3:], np.array([1, 0, 0, 1]) / np.sqrt(2))
    with pytest.raises(ModelError, match="body 'b': the Euler parameters of q0 are all zero"):
        m.add_body("b", q0=(0, 0, 0, 0, 0, 0, 0))
    with pytest.raises(ModelError, match="body 'c': q0 must have 7 values"):
        m.add_body("c", q0=(0, 0, 0))
    m.add_body("d", q0=(0, 0, 0, "cos(pi/8)", 0, 0, "sin(pi/8)"))
    np.testing.assert_allclose(m.q0[-4:], p_from_axis_angle([0, 0, 1], np.pi / 4))


def test_errors_name_the_body_point_vector_and_constraint():
    m = pendulum()
    with pytest.raises(UnknownBodyError, match="revolute joint '2' .*has no body 'nope'"):
        m.add(Revolute("ground", "nope", point="O", axis_i="z", axis_j="z"))
    with pytest.raises(UnknownPointError, match=r"spherical joint '2' \(rows 14-16 of Φ\): body 'bar' has no point 'Z'"):
        m.add(Spherical("ground", "bar", point_i="O", point_j="Z"))
    with pytest.raises(UnknownPointError, match="body 'bar' has no vector 'w'"):
        m.add(Revolute("ground", "bar", point="O", axis_i="z", axis_j="w"))
    with pytest.raises(ModelError, match="axis_j on body 'bar' is zero"):
        m.add(Revolute("ground", "bar", point="O", axis_i="z", axis_j=(0, 0, 0)))
    with pytest.raises(ModelError, match="perp_i is parallel to the axis"):
        m.add(Translational("ground", "bar", point="O", axis_i="z", axis_j="axis", perp_i=(0, 0, 2)))
    with pytest.raises(ModelError, match="connects body 'bar' to itself"):
        m.add(Spherical("bar", "bar", point="O"))
    with pytest.raises(ModelError, match="expected a spatial constraint"):
        m.add(PlanarRevolute("ground", "bar", point="O"))
    with pytest.raises(ExpressionError, match="revolute-driver on bodies 'ground', 'bar', f: unknown name 'w'"):
        RevoluteDriver("ground", "bar", axis_i="z", f="w*t")
    assert m.m == 13  # failed additions left no rows behind


def test_remove_moves_the_rows_up_but_keeps_normalization():
    m = pendulum()
    m.add(Spherical("ground", "bar", point="O", name="extra"))
    assert m.remove("1").type_name == "revolute"
    assert m.constraint("extra").rows == slice(8, 11) and m.m == 11
    with pytest.raises(ModelError, match="normalization equation 'normalization bar' .*cannot be removed"):
        m.remove("normalization bar")


def test_numeric_inputs_are_checked():
    m = pendulum()
    with pytest.raises(InputError, match=r"`q` must have shape \(14,\) or \(N, 14\).*got \(13,\)"):
        m.Phi(np.zeros(13))
    q = m.q0.copy()
    q[10] = np.nan
    with pytest.raises(InputError, match="non-finite value in e02"):
        m.Phi_q(q)
    with pytest.raises(InputError, match="do not have unit norm"):
        m.point_position(np.r_[m.q0[:7], 0, 0, 0, 2, 0, 0, 0], "bar", "T")
    with pytest.raises(UnknownPointError, match="body 'bar' has no point 'X'"):
        m.point_position(m.q0, "bar", "X")
    with pytest.raises(InputError, match="point_velocity: arguments of incompatible shapes"):
        m.point_velocity(np.tile(m.q0, (3, 1)), np.zeros((2, 14)), "bar", "T")


def test_driver_count_and_redundancy_are_diagnosed():
    m = pendulum()
    with pytest.raises(DriverCountError, match="1 degree\\(s\\) of freedom, but 0 driver"):
        m.solve_position()
    # a second spherical joint at the same point repeats three of the revolute's equations
    m.add(Spherical("ground", "bar", point="O", name="again"))
    d = m.diagnose(m.q0)
    assert d.kind == "redundant" and set(d.constraints) == {"1", "again"}
    assert "repeat what the others impose" in d.message
    m.add(RevoluteDriver("ground", "bar", axis_i="z", f="t"))
    with pytest.raises(DriverCountError, match="overconstrained by 2"):
        m.solve_position()


def test_solve_velocity_acceleration_and_point_kinematics_of_a_turning_bar():
    m = pendulum()
    m.add(RevoluteDriver("ground", "bar", axis_i="z", ref_i="x", ref_j="arm", f="0.5*t**2"))
    t = 1.2
    q = m.solve_position(t)
    qd = m.solve_velocity(q, t)
    qdd = m.solve_acceleration(q, qd, t)
    th, w, a = 0.5 * t**2, t, 1.0
    tip = 2 * np.array([np.cos(th), np.sin(th), 0])
    np.testing.assert_allclose(m.point_position(q, "bar", "T"), tip, atol=1e-10)
    np.testing.assert_allclose(m.point_velocity(q, qd, "bar", "T"), w * np.array([-tip[1], tip[0], 0]), atol=1e-9)
    acc = a * np.array([-tip[1], tip[0], 0]) - w**2 * tip
    np.testing.assert_allclose(m.point_acceleration(q, qd, qdd, "bar", "T"), acc, atol=1e-9)
    np.testing.assert_allclose(m.angular_velocity(q, qd, "bar"), [0, 0, w], atol=1e-10)
    np.testing.assert_allclose(m.angular_velocity(q, qd, "bar", frame="body"), [0, 0, w], atol=1e-10)
    np.testing.assert_allclose(m.angular_acceleration(q, qdd, "bar"), [0, 0, a], atol=1e-9)
    assert np.linalg.norm(m.p(q, "bar")) == pytest.approx(1.0, abs=1e-12)


def test_angle_driver_wraps_so_a_crank_can_turn_many_times():
    m = pendulum()
    m.add(RevoluteDriver("ground", "bar", axis_i="z", f="2*pi*t"))
    res = m.simulate(np.linspace(0, 3.0, 121))  # three full turns
    assert res.failure is None
    th = 2 * np.pi * res.t
    np.testing.assert_allclose(res.position("bar", "T"), 2 * np.column_stack([np.cos(th), np.sin(th), 0 * th]),
                               atol=1e-9)  # pivot at the origin, tip 2 from it
    assert np.all(np.abs(m.Phi(res.q, res.t)) < 1e-9)


def test_translational_joint_with_distance_driver():
    m = Mechanism("slide")
    m.add_body("ground", points={"P": (0, 0, 0)}, vectors={"d": (1, 1, 1), "h": (1, -1, 0)})
    q0 = (0.1, 0.1, 0.1, *p_from_axis_angle([1, 1, 1], 0.3))
    m.add_body("block", points={"B": (0, 0, 0)}, q0=q0, vectors={"d": (1, 1, 1)})
    m.add(Ground("ground"))
    m.add(Translational("ground", "block", point_i="P", point_j="B", axis_i="d", axis_j="d", perp_i="h"))
    m.add(DistanceDriver("ground", "block", axis_i="d", point_i="P", point_j="B", f="1 + t"))
    q = m.solve_position(0.5)
    np.testing.assert_allclose(m.point_position(q, "block", "B"), 1.5 * np.ones(3) / np.sqrt(3), atol=1e-10)
    # the block keeps its q0 orientation (default perp_j: perpendicular to h_i and the axis at q0)
    np.testing.assert_allclose(m.p(q, "block"), q0[3:], atol=1e-10)
    qd = m.solve_velocity(q, 0.5)
    np.testing.assert_allclose(qd[7:10], np.ones(3) / np.sqrt(3), atol=1e-10)


def test_mechanism_files_build_spatial_mechanisms_and_name_bad_keys():
    mech = examples.load("spatial_slider_crank")
    assert isinstance(mech, Mechanism) and mech.constraint("slide").type_name == "translational"
    text = examples.path("spatial_fourbar").read_text()
    bad_q0 = text.replace("q0 = [0, 3, 1, 0.7067, -0.7075, 0, 0]", "q0 = [0, 3, 1]")
    with pytest.raises(MechanismFileError, match=r"bodies\[3\] \('rocker'\).*q0 must have 7 values"):
        kinbook.loads(bad_q0, source="bad.toml")
    bad_type = text.replace('type = "universal"', 'type = "hooke"')
    with pytest.raises(MechanismFileError, match=r"constraints\[3\]: `type` must be one of .*universal"):
        kinbook.loads(bad_type, source="bad.toml")
    bad_key = text.replace('vector_j = "axis"', 'vector_k = "axis"')
    with pytest.raises(MechanismFileError, match="unknown key 'vector_k'"):
        kinbook.loads(bad_key, source="bad.toml")
    bad_vector = text.replace('vector_i = "cross"', 'vector_i = "nope"')
    with pytest.raises(MechanismFileError, match="body 'coupler' has no vector 'nope'"):
        kinbook.loads(bad_vector, source="bad.toml")


def test_redundant_assembly_raises_with_rows_named():
    m = Mechanism("twice")
    m.add_body("ground", points={"O": (0, 0, 0)})
    m.add_body("ball", points={"O": (0, 0, -1)}, q0=(0.1, 0, 1, 1, 0, 0, 0))
    m.add(Ground("ground"))
    m.add(Spherical("ground", "ball", point="O", name="socket"))
    m.add(Spherical("ground", "ball", point="O", name="again"))
    assert m.m == m.n == 14  # square, but rows 12-14 repeat rows 9-11
    with pytest.raises(RedundantConstraintsError, match="redundant.*spherical joint 'socket'.*'again'") as info:
        m.solve_position()
    assert set(info.value.constraints) == {"socket", "again"}


def test_derivation_is_computed_once_per_constraint_until_the_mechanism_changes():
    m = examples.load("spatial_fourbar")
    name = m.constraints[5].name
    d = m.derivation(name)
    assert m.derivation(name) is d
    m.remove(name)
    with pytest.raises(ModelError, match=name):
        m.derivation(name)


def test_moved_turns_one_body_rigidly_and_keeps_its_parameters_continuous():
    m = examples.load("spatial_fourbar")
    q0 = m.solve_position(0.0)
    axis, angle, about, shift = np.array([1.0, 2.0, -0.5]), 0.7, np.array([0.3, -0.2, 1.0]), np.array([0.1, 0, 2])
    q = m.moved(q0, "coupler", axis, angle, about=about, shift=shift)
    R = Rotation.from_rotvec(axis / np.linalg.norm(axis) * angle).as_matrix()  # scipy, independently
    for name in m.body("coupler").points:
        before, after = m.point_position(q0, "coupler", name), m.point_position(q, "coupler", name)
        np.testing.assert_allclose(after, about + R @ (before - about) + shift, atol=1e-12)
    others = [k for k in range(m.n) if not 14 <= k < 21]  # the coupler is the third body
    np.testing.assert_array_equal(q[others], q0[others])
    assert np.linalg.norm(q[17:21]) == pytest.approx(1.0) and q[17:21] @ q0[17:21] > 0.9  # no sign flip
    # the joints' rows notice the move, the normalization does not
    assert abs(m.Phi(q)).max() > 1e-3 and abs(m.Phi(q)[m.constraint("normalization coupler").rows]).max() < 1e-12
    with pytest.raises(InputError, match="about"):
        m.moved(q0, "coupler", axis, angle, about=(1, 2))
    with pytest.raises(UnknownBodyError, match="wheel"):
        m.moved(q0, "wheel")
