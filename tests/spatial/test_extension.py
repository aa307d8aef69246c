"""A spatial joint the book does not have, written here and nowhere in kinbook: it loads from a mechanism file,
solves, sweeps, derives, draws, appears in the constraint table and is graded like the book's joints."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
import sympy as sp  # noqa: E402

import kinbook  # noqa: E402
from kinbook import spatial  # noqa: E402
from kinbook.grading import check_gamma, check_jacobian, check_phi  # noqa: E402
from kinbook.spatial import plotting  # noqa: E402


class PlaneOnPlane(spatial.Constraint):
    """Planar joint: a plane of body j slides on a plane of body i. The normal n_j of body j stays ⊥ f and g,
    where (f, g, n) is an orthonormal right-handed triad of body i, and P_j stays on the plane of body i
    through P_i: nᵀ(r_j^P − r_i^P) = 0. Three degrees of freedom remain: two slides and a turn about n."""

    type_name = "plane-on-plane"
    label = "p1,2 + n2,1"
    n_eq = 3
    title = "planar joint"
    measures = ("length",) * 3
    points = {"point_i": "i", "point_j": "j"}
    vectors = {"normal": "i", "ref": "i", "side": "i", "normal_j": "j"}

    def phi(self, Q, t=None):
        n, f, g = (self.vector(Q, key) for key in ("normal", "ref", "side"))
        nj = self.vector(Q, "normal_j")
        d = self.point(Q, "point_j") - self.point(Q, "point_i")
        return [f.dot(nj), g.dot(nj), n.dot(d)]


FILE = """
[mechanism]
kind = "spatial"
name = "puck"
[[bodies]]
name = "table"
points = { O = [0, 0, 0] }
vectors = { z = [0, 0, 1], x = [1, 0, 0], y = [0, 1, 0] }
[[bodies]]
name = "puck"
points = { O = [0, 0, 0], T = [0.5, 0, 0] }
vectors = { z = [0, 0, 1] }
q0 = [1, 0, 0, 1, 0, 0, 0]
[[constraints]]
type = "ground"
body = "table"
[[constraints]]
type = "plane-on-plane"
name = "pl"
i = "table"
j = "puck"
point_i = "O"
point_j = "O"
normal = "z"
ref = "x"
side = "y"
normal_j = "z"
[[constraints]]
type = "distance-driver"
i = "table"
j = "puck"
axis_i = "x"
point_i = "O"
point_j = "O"
f = "cos(t)"
[[constraints]]
type = "distance-driver"
i = "table"
j = "puck"
axis_i = "y"
point_i = "O"
point_j = "O"
f = "sin(t)"
[[constraints]]
type = "revolute-driver"
i = "table"
j = "puck"
axis_i = "z"
f = "2*t"
"""


@pytest.fixture(scope="module")
def mech():
    return kinbook.loads(FILE)


def tip(t):
    """Independent geometry: the puck's centre runs round the unit circle while the puck turns twice as fast
    about the table's normal; T is 0.5 from the centre, in the table's plane."""
    return np.stack([np.cos(t) + 0.5 * np.cos(2 * t), np.sin(t) + 0.5 * np.sin(2 * t), 0 * t], -1)


def test_loads_solves_and_sweeps(mech):
    assert isinstance(mech.constraint("pl"), PlaneOnPlane) and mech.dof == 3
    q = mech.solve_position(0.4)
    assert mech.point_position(q, "puck", "T") == pytest.approx(tip(0.4), abs=1e-10)
    res = mech.simulate(np.linspace(0.0, 6.0, 241))  # once round, the puck turning past ±π twice
    np.testing.assert_allclose(res.position("puck", "T"), tip(res.t), atol=1e-9)
    h = 1e-4
    np.testing.assert_allclose(res.velocity("puck", "T"), (tip(res.t + h) - tip(res.t - h)) / (2 * h), atol=1e-6)
    np.testing.assert_allclose(res.acceleration("puck", "T"),
                               (tip(res.t + h) - 2 * tip(res.t) + tip(res.t - h)) / h**2, atol=1e-5)


def test_derives_and_its_numeric_path_agrees(mech):
    c = mech.constraint("pl")
    d = mech.derivation(c)
    rng = np.random.default_rng(2)
    q, qd = mech.solve_position(0.5) + rng.normal(0, 0.05, mech.n), rng.normal(size=mech.n)
    at = {**dict(zip(mech.q, q)), **dict(zip(mech.qd, qd))}
    cols = [mech.index(str(s)) for s in d.q]
    ev = mech.evaluate(q, 0.5, qd)
    np.testing.assert_allclose(ev["Phi_q"][c.rows][:, cols], np.array(d.Phi_q.subs(at), dtype=float), atol=1e-11)
    np.testing.assert_allclose(ev["gamma"][c.rows], np.array(d.gamma.subs(at), dtype=float).ravel(), atol=1e-10)


def test_draws_and_appears_in_the_constraint_table(mech):
    drawing = plotting.draw(mech, mech.solve_position(0.4))
    assert drawing.ax.name == "3d"
    row = next(r for r in mech.constraint_table().rows if r[1] == "pl")
    assert row[2:] == ("1", "2", "plane-on-plane (p1,2 + n2,1)", "3", "Φ_9–Φ_11")


def _answer(mech, sign=1):
    """Φ of the joint as a student writes it: A_i, A_j from the Euler parameters, then the three rows;
    ``sign=-1`` slips in d = r_j − r_i."""
    q1, q2 = mech.body_symbols("table"), mech.body_symbols("puck")
    A1, A2 = spatial.A_from_p(list(q1[3:])), spatial.A_from_p(list(q2[3:]))
    e = sp.eye(3)
    n, f, g, nj = A1 * e[:, 2], A1 * e[:, 0], A1 * e[:, 1], A2 * e[:, 2]
    d = sp.Matrix(q2[:3]) - sign * sp.Matrix(q1[:3])
    return sp.Matrix([f.dot(nj), g.dot(nj), n.dot(d)])


def test_graded_by_the_checkers(mech):
    c = mech.constraint("pl")
    phi = _answer(mech)
    q = sp.Matrix(mech.derivation(c).q)
    qd = sp.Matrix([mech.qd[mech.index(str(s)), 0] for s in q])
    J = phi.jacobian(mech.q)
    gamma = -(phi.jacobian(q) * qd).jacobian(q) * qd
    assert check_phi(phi, c).passed and check_jacobian(J, c).passed and check_gamma(gamma, c).passed
    # d = r_j + r_i expands into more sign changes than the catalogue's variants of Φ try: refused, unnamed;
    # in Φ_q and γ the sign errors are named
    assert not check_phi(_answer(mech, sign=-1), c).passed
    J[2, mech.index("z2")] *= -1
    assert check_jacobian(J, c).mistakes == ["sign_flip"]
    assert "gamma_sign" in check_gamma(-gamma, c).mistakes
