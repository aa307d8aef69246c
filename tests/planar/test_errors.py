"""Bad input gets a KinbookError naming the body, point, constraint, key or row concerned."""

import numpy as np
import pytest

import kinbook
from kinbook import (
    ExpressionError,
    InputError,
    MechanismFileError,
    ModelError,
    UnknownBodyError,
    UnknownPointError,
    examples,
)
from kinbook.planar import Driver, Mechanism, Revolute, RevoluteRevolute, Translational

from ..mechanisms import pendulum


@pytest.fixture
def mech():
    m = Mechanism("test")
    m.add_body("ground", points={"O": (0, 0)})
    m.add_body("bar", points={"O": (-1, 0), "A": (1, 0)})
    return m


def test_unknown_body(mech):
    with pytest.raises(UnknownBodyError, match=r"revolute joint '1'.*has no body 'rod' \(its bodies: 'ground', 'bar'\)"):
        mech.add(Revolute("ground", "rod", point="O"))
    assert mech.m == 0  # nothing half-added


def test_unknown_point(mech):
    with pytest.raises(UnknownPointError, match=r"revolute joint '1' \(rows 1-2 of Φ\): body 'ground' has no point 'A' \(its points: O\)"):
        mech.add(Revolute("ground", "bar", point="A"))


def test_joint_between_a_body_and_itself(mech):
    with pytest.raises(ModelError, match=r"revolute joint '1' .* connects body 'bar' to itself"):
        mech.add(Revolute("bar", "bar", point_i="O", point_j="A"))


def test_duplicate_body(mech):
    with pytest.raises(ModelError, match="already has a body named 'bar'"):
        mech.add_body("bar")


def test_bad_values(mech):
    with pytest.raises(ExpressionError, match=r"q0 of body 'c' \(y\): unknown name 'nan'"):
        mech.add_body("c", q0=(0, "nan", 0))
    with pytest.raises(ModelError, match="point 'P' of body 'd'.*pair"):
        mech.add_body("d", points={"P": (1, 2, 3)})
    with pytest.raises(ModelError, match="length must be a positive number"):
        mech.add(RevoluteRevolute("ground", "bar", "O", "A", length=-2))
    with pytest.raises(ModelError, match="axis points on body 'ground' coincide"):
        mech.add(Translational("ground", "bar", axis=("O", "O"), point_j="A"))
    with pytest.raises(ExpressionError, match="driver on body 'bar', f: unknown name 'w'"):
        Driver("bar", "phi", "w*t")


def test_wrong_shapes_and_non_finite(mech):
    m = examples.load("ch13_example1")
    with pytest.raises(InputError, match=r"`q` must have shape \(12,\) or \(N, 12\) .* got \(9,\)"):
        m.Phi(np.zeros(9))
    q = m.q0
    q[5] = np.nan
    with pytest.raises(InputError, match="non-finite value in phi2"):
        m.Phi_q(q)
    with pytest.raises(InputError, match="`t` must be finite"):
        m.Phi(m.q0, np.inf)
    with pytest.raises(InputError, match="`qd` must have shape"):
        m.gamma(m.q0, np.zeros(3))


def test_symbolic_parameters_are_refused_numerically():
    m = Mechanism("sym")
    m.add_body("i", points={"P": ("xi", "eta")})
    m.add_body("j", points={"P": (0, 0)})
    m.add(Revolute("i", "j", point="P"))
    assert {str(s) for s in m.symbolic().Phi.free_symbols} >= {"xi", "eta", "phi1"}
    # named where the symbols are (the body's point) and who uses it; a point no joint uses is the body's alone
    with pytest.raises(ModelError, match=r"body 'i', point 'P' has symbolic parameters \(eta, xi\) \(used by "
                                         r"revolute joint '1'"):
        m.Phi(np.zeros(6))
    m = Mechanism("sym")
    m.add_body("i", points={"P": (1, 0)})
    m.add_body("j", points={"P": (0, 0), "M": ("l", 0)})
    m.add(Revolute("i", "j", point="P"))
    with pytest.raises(ModelError, match=r"body 'j', point 'M' has symbolic parameters \(l\): substitute"):
        m.Phi(np.zeros(6))


TOML_OK = pendulum(0.5, "sin(t)")


def test_toml_round_trip():
    m = kinbook.loads(TOML_OK)
    q = m.solve_position(1.0)
    assert q[5] == pytest.approx(np.sin(1.0))
    np.testing.assert_allclose(m.point_position(q, "bar", "O"), [0, 0], atol=1e-12)


@pytest.mark.parametrize(
    "change, message",
    [
        (("point = \"O\"", "pont = \"O\""), r"constraints\[1\] \(type 'revolute'\): unknown key 'pont' \(accepted keys: i, j, point, point_i, point_j, name\)"),
        (("type = \"revolute\"", "type = \"hinge\""), r"constraints\[1\]: `type` must be one of .*got 'hinge'"),
        (("j = \"bar\"", "j = \"rod\""), r"constraints\[1\] \(type 'revolute'\): revolute joint '1' .*no body 'rod'"),
        (("q0 = [0.5, 0, 0]", "q0 = [0.5, 0]"), r"bodies\[1\] \('bar'\): body 'bar': q0 must have 3 values"),
        (("f = \"sin(t)\"", "f = \"sin(\""), r"constraints\[2\] \(type 'driver'\): driver on body 'bar', f: not a valid expression"),
        (("coordinate = \"phi\"\n", ""), r"constraints\[2\] \(type 'driver'\): missing key 'coordinate'"),
        (("[mechanism]", "[mechanism]\nkind = \"fluid\""), r"`mechanism.kind` must be one of"),
        (("name = \"ground\"\npoints", "name = \"ground\npoints"), r"pendulum.toml: not valid TOML"),
        (("points = { O = [0, 0] }", "points = 3"), r"bodies\[0\] \('ground'\): body 'ground': `points` must be a table"),
    ],
)
def test_toml_errors_name_the_key(change, message):
    old, new = change
    assert old in TOML_OK
    with pytest.raises(MechanismFileError, match=message):
        kinbook.loads(TOML_OK.replace(old, new, 1), source="pendulum.toml")


def test_missing_file_and_unknown_example(tmp_path):
    with pytest.raises(MechanismFileError, match="cannot read the mechanism file"):
        kinbook.load(tmp_path / "nope.toml")
    with pytest.raises(MechanismFileError, match="no example mechanism 'ch99' \\(available: ch13_example1"):
        examples.load("ch99")


def test_every_shipped_example_loads_and_is_square():
    for name in examples.names():
        m = examples.load(name)
        assert m.m == m.n, name


def test_remove_renumbers_rows():
    m = examples.load("ch13_example1")
    phi_before = m.symbolic().Phi
    removed = m.remove("2")
    assert removed.rows is None and m.m == 10
    assert [c.rows.start for c in m.constraints] == [0, 3, 5, 7, 9]
    assert list(m.symbolic().Phi) == list(phi_before[:5]) + list(phi_before[7:])
    with pytest.raises(ModelError, match="has no constraint '2'"):
        m.remove("2")
