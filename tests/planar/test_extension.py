"""A planar joint the book does not have, written here and nowhere in kinbook: it loads from a mechanism file,
solves, sweeps, derives, draws, appears in the constraint table and is graded like the book's joints."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
import sympy as sp  # noqa: E402

import kinbook  # noqa: E402
from kinbook import planar  # noqa: E402
from kinbook.grading import check_gamma, check_jacobian, check_phi  # noqa: E402
from kinbook.planar import plotting  # noqa: E402

from ..mechanisms import cam_follower  # noqa: E402


class Cam(planar.Constraint):
    """Harmonic cam and roller follower: the roller centre R (body j) stays on the pitch curve of the cam
    (body i), ρ(ψ) = base + lift·cos ψ in polar coordinates about the cam's reference point, ψ from its ξ axis."""

    type_name = "harmonic-cam"
    label = "cf"
    n_eq = 1
    title = "cam and follower"
    measures = ("length",)
    points = {"roller": "j"}
    numbers = ("base", "lift")

    def phi(self, Q, t=None):
        d = planar.A(Q[0][2]).T * (self.point(Q, "roller") - Q[0][:2, :])  # R in the cam's frame
        return [sp.sqrt(d.dot(d)) - self.base - self.lift * sp.cos(sp.atan2(d[1], d[0]))]


FILE = cam_follower("""
[[constraints]]
type = "harmonic-cam"
i = "cam"
j = "follower"
roller = "R"
base = 2
lift = 0.5
name = "cf"
""")
BASE, LIFT = 2.0, 0.5


@pytest.fixture(scope="module")
def mech():
    return kinbook.loads(FILE)


def follower_y(t):
    """Independent geometry: R = (0, y) seen from the cam turned by φ = t lies at ψ = π/2 − t, so
    y = base + lift·cos(π/2 − t) = base + lift·sin t."""
    return BASE + LIFT * np.sin(t), LIFT * np.cos(t), -LIFT * np.sin(t)


def test_loads_solves_and_sweeps(mech):
    assert isinstance(mech.constraint("cf"), Cam) and mech.dof == 1
    q = mech.solve_position(0.3)
    assert mech.point_position(q, "follower", "R") == pytest.approx([0.0, follower_y(0.3)[0]], abs=1e-10)
    res = mech.simulate(np.linspace(0.0, 2 * np.pi, 181))
    y, yd, ydd = follower_y(res.t)
    np.testing.assert_allclose(res.coordinate("y3"), y, atol=1e-9)
    np.testing.assert_allclose(res.coordinate("y3", 1), yd, atol=1e-8)
    np.testing.assert_allclose(res.coordinate("y3", 2), ydd, atol=1e-7)


def test_derives_and_its_numeric_path_agrees(mech):
    c = mech.constraint("cf")
    d = mech.derivation(c)
    rng = np.random.default_rng(1)
    q, qd = mech.solve_position(0.7) + rng.normal(0, 0.05, mech.n), rng.normal(size=mech.n)
    at = {**dict(zip(mech.q, q)), **dict(zip(mech.qd, qd))}
    cols = [mech.index(str(s)) for s in d.q]
    ev = mech.evaluate(q, 0.7, qd)
    np.testing.assert_allclose(ev["Phi_q"][c.rows][:, cols], np.array(d.Phi_q.subs(at), dtype=float), atol=1e-12)
    np.testing.assert_allclose(ev["gamma"][c.rows], np.array(d.gamma.subs(at), dtype=float).ravel(), atol=1e-12)
    h = 1e-6
    fd = [(mech.Phi(q + h * e, 0.7) - mech.Phi(q - h * e, 0.7))[c.rows] / (2 * h) for e in np.eye(mech.n)]
    np.testing.assert_allclose(ev["Phi_q"][c.rows], np.column_stack(fd), atol=1e-7)


def test_draws_and_appears_in_the_constraint_table(mech):
    q = mech.solve_position(0.3)
    ax = plotting.draw(mech, q)
    R = mech.point_position(q, "follower", "R")
    assert any(np.allclose(p.center, R) for p in ax.patches if isinstance(p, matplotlib.patches.Circle))
    row = next(r for r in mech.constraint_table().rows if r[1] == "cf")
    assert row[2:] == ("2", "3", "cf", "1", "Φ_8")


def _answer(mech, sign=1):
    """Φ of the joint as a student writes it from the figure, |d'| − ρ(ψ) with d' = A_2ᵀ (r_3 − r_2) and
    cos ψ = ξ/|d'|; ``sign=-1`` makes the classic slip in the lift term."""
    x2, y2, p2, x3, y3, _ = (*mech.body_symbols("cam"), *mech.body_symbols("follower"))
    dx, dy = x3 - x2, y3 - y2
    xi, eta = sp.cos(p2) * dx + sp.sin(p2) * dy, -sp.sin(p2) * dx + sp.cos(p2) * dy
    r = sp.sqrt(xi**2 + eta**2)
    return sp.Matrix([r - 2 - sign * sp.Rational(1, 2) * xi / r])


def test_graded_by_the_checkers(mech):
    c = mech.constraint("cf")
    phi = _answer(mech)
    q = sp.Matrix(mech.derivation(c).q)
    qd = sp.Matrix([mech.qd[mech.index(str(s)), 0] for s in q])
    J = phi.jacobian(mech.q)
    gamma = -(phi.jacobian(q) * qd).jacobian(q) * qd
    assert check_phi(phi, c).passed and check_jacobian(J, c).passed and check_gamma(gamma, c).passed
    assert check_phi(_answer(mech, sign=-1), c).mistakes == ["sign_flip"]
    J[0, mech.index("phi2")] *= -1
    assert check_jacobian(J, c).mistakes == ["sign_flip"]
    assert "gamma_sign" in check_gamma(-gamma, c).mistakes
