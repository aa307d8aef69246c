"""A spatial joint graded alone and inside its mechanism (kinbook.spatial, chapter 14)."""

import pytest
import sympy as sp

from kinbook.grading import check_gamma, check_jacobian, check_nu, check_phi

spatial = pytest.importorskip("kinbook.spatial")


@pytest.fixture(scope="module")
def pendulum():
    m = spatial.Mechanism("spherical pendulum")
    m.add_body("ground", points={"O": (0, 0, 0)})
    m.add_body("bar", points={"O": (-1, 0, 0), "T": (1, 0, 0)}, q0=(1, 0, 0, 1, 0, 0, 0))
    m.add(spatial.Ground("ground"))
    m.add(spatial.Spherical("ground", "bar", point="O"))
    return m


# the student's own symbols and the book's A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ], written out
x1, y1, z1, x2, y2, z2 = sp.symbols("x1 y1 z1 x2 y2 z2")
e0, e1, e2, e3 = sp.symbols("e02 e12 e22 e32")
A2 = sp.Matrix([
    [2 * (e0**2 + e1**2) - 1, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)],
    [2 * (e1 * e2 + e0 * e3), 2 * (e0**2 + e2**2) - 1, 2 * (e2 * e3 - e0 * e1)],
    [2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), 2 * (e0**2 + e3**2) - 1],
])
S_BAR = sp.Matrix([-1, 0, 0])
PHI = sp.Matrix([x1, y1, z1]) - sp.Matrix([x2, y2, z2]) - A2 * S_BAR
Q2 = sp.Matrix([x2, y2, z2, e0, e1, e2, e3])
QD2 = sp.Matrix(sp.symbols("dx2 dy2 dz2 de02 de12 de22 de32"))


def test_spherical_joint_phi(pendulum):
    joint = (pendulum, "1")
    assert check_phi(PHI, joint).passed
    assert check_phi(-2 * PHI[::-1, :], joint).passed
    r = check_phi(sp.Matrix([x1, y1, z1]) - sp.Matrix([x2, y2, z2]) - A2.T * S_BAR, joint)
    assert (r.passed, r.mistakes) == (False, ["A_transposed"])
    r = check_phi(sp.Matrix([x1, y1, z1]) - sp.Matrix([x2, y2, z2]) - S_BAR, joint)
    assert (r.passed, r.mistakes) == (False, ["local_vector"])


def test_spherical_joint_jacobian_nu_gamma(pendulum):
    joint = (pendulum, "1")
    J = PHI.jacobian(sp.Matrix([x1, y1, z1, *sp.symbols("e01 e11 e21 e31")]).col_join(Q2))
    assert check_jacobian(J, joint).passed
    assert check_nu([0, 0, 0], joint).passed
    Jj = PHI.jacobian(Q2)
    gamma = -(Jj * QD2).jacobian(Q2) * QD2
    assert check_gamma(gamma, joint).passed
    r = check_gamma(-gamma, joint)
    assert (r.passed, r.mistakes) == (False, ["gamma_sign"])


def test_forgotten_normalization(pendulum):
    rows = ["e01**2 + e11**2 + e21**2 + e31**2 - 1", "x1", "y1", "z1", "e11", "e21", "e31"] + list(PHI)
    rows.insert(1, "e02**2 + e12**2 + e22**2 + e32**2 - 1")
    rows[5:8] = ["e11", "e21", "e31"]
    full = check_phi(rows, pendulum)
    assert full.passed, repr(full)
    r = check_phi(rows[1:], pendulum)
    assert (r.passed, r.mistakes) == (False, ["missing_normalization"])
    assert "Euler-parameter normalization 'ground'" in r.messages[1]


def test_constraint_objects_of_a_spatial_mechanism_are_targets(pendulum):
    assert check_phi(PHI, pendulum.constraint("1")).passed


def test_every_joint_of_the_spatial_fourbar():
    import kinbook
    from kinbook.core.symbolic import derive

    if "spatial_fourbar" not in kinbook.examples.names():
        pytest.skip("spatial example not shipped yet")
    mech = kinbook.examples.load("spatial_fourbar")
    for c in mech.constraints:
        d = derive(mech.constraint_phi(c), mech.q, mech.qd, mech.t)
        assert check_phi(-d.Phi, c).passed, c.name
        assert check_jacobian(d.Phi_q, c).passed, c.name
        if c.kind != "driver":  # the revolute driver's γ (atan2) is large and slow to compile: see test below
            assert check_gamma(d.gamma, c).passed, c.name
            assert check_gamma(-d.gamma, c).mistakes in (["gamma_sign"], []), c.name
