"""verify's joint tables (notebook 14-4): values checked against geometry and finite differences, and each
table shown to fail when its input is wrong."""

import re

import numpy as np
import pytest
import sympy as sp

import kinbook
from kinbook.book import notation as N
from kinbook.book import verify
from kinbook.errors import InputError
from kinbook.spatial import A_from_euler, Cylindrical, Mechanism, Revolute, Spherical, Translational, p_from_A

A_I = A_from_euler(20, 25, 0, degrees=True)


def _pair(joint):
    """Two free bodies i, j with local points P = origin, Q on ξ, U on ζ, joined by ``joint`` along ξ."""
    m = Mechanism("pair")
    pts = {"P": (0, 0, 0), "Q": (1, 0, 0), "U": (0, 0, 1), "V": (0, 1, 0)}
    m.add_body("i", points=pts)
    m.add_body("j", points=pts)
    m.add(joint)
    slide = 0.0 if isinstance(joint, (Spherical, Revolute)) else 0.4  # j slid along the axis where allowed
    return m, np.r_[0, 0, 0, p_from_A(A_I), slide * A_I[:, 0], p_from_A(A_I)]


JOINTS = {  # joint, relative DOF it leaves (geometry: spherical 3 turns, revolute 1, cylindrical 2, slider 1)
    "s": (lambda: Spherical("i", "j", point="P", name="s"), 3),
    "r": (lambda: Revolute("i", "j", axis_i=["P", "Q"], axis_j=["P", "Q"], point="P", name="r"), 1),
    "c": (lambda: Cylindrical("i", "j", axis_i=["P", "Q"], axis_j=["P", "Q"], point="P", name="c"), 2),
    "t": (lambda: Translational("i", "j", axis_i=["P", "Q"], axis_j=["P", "Q"], point="P", perp_i=["P", "U"],
                                perp_j=["P", "V"], name="t"), 1),
}


def test_fd_jacobian_of_a_known_function():
    f = lambda x: np.array([x[0] * x[1], np.sin(x[2]), x[0] ** 3])  # noqa: E731
    x = np.array([0.3, -1.2, 0.7])
    exact = np.array([[x[1], x[0], 0], [0, 0, np.cos(x[2])], [3 * x[0] ** 2, 0, 0]])
    assert np.abs(verify.fd_jacobian(f, x) - exact).max() < 1e-9


def test_tidy_writes_float_noise_as_a_person_would():
    x = sp.Symbol("x")
    assert str(N.tidy(2.0 * x + 1.2000000000000002 * x**2 - 0.5)) == "1.2*x**2 + 2*x - 0.5"
    assert "2.0" not in N.latex(2.0 * x) and N.latex(2.0 * x) == "2 x"
    with pytest.raises(InputError, match="expected a sympy expression, got str"):
        N.tidy("2.0*x")  # text is never parsed here (kinbook.core.reader reads text)


@pytest.mark.parametrize("name", sorted(JOINTS))
def test_joint_summary_counts_what_geometry_says(name):
    make, dof = JOINTS[name]
    m, q = _pair(make())
    s = verify.joint_summary(m, q, name)
    c = m.constraint(name)
    assert s.dof == dof and c.n_eq == 6 - dof
    assert np.abs(s.value).max() < 1e-12 and f"{dof} relative DOF left" in s.text()
    html = s._repr_html_()
    assert html.startswith("<div>\\[") and "$" not in html
    heads = {"s": ["s,3"], "r": ["s,3", "p1,2"], "c": ["p1,2", "p2,2"], "t": ["p1,2", "p2,2", "n1,1"]}[name]
    assert all(f"\\Phi^{{({h})}}" in s.tex for h in heads) and "+" not in s.tex.split("=")[0]
    # the book's vector form (§14.4), its local vectors as numbers: no polynomial in the Euler parameters
    assert "e_{0" not in s.tex and "\\mathbf A" in s.tex and not re.search(r"\d\.\d{6,}", s.tex)


def test_motion_table_reads_the_rows_a_motion_breaks():
    m, q = _pair(JOINTS["r"][0]())
    axis, P = A_I[:, 0], np.zeros(3)
    t = verify.motion_table(m, q, "r", {"turn about the axis": (axis, 1.0, P, 0),
                                        "slide along the axis": (axis, 0.0, P, 0.25 * axis)})
    turn, slide = t
    assert turn.ok and turn.verdict().startswith("allowed")
    assert not slide.ok and slide.verdict().startswith("forbidden")
    # the spherical rows are r_i + A_i s'_i − r_j − A_j s'_j: sliding body j by δ makes them −δ
    assert np.allclose(slide.values[:3], np.round(-0.25 * axis, 4)) and np.allclose(slide.values[3:], 0)


def test_joint_table_agrees_and_flags_a_broken_configuration():
    joints = {n: _pair(make()) for n, (make, _) in JOINTS.items()}
    t = verify.joint_table(joints)
    assert t.all_ok and [r[3] for r in t.rows] == [str(d) for _, d in JOINTS.values()]
    m, q = joints["r"]
    bad = {"r": (m, m.moved(q, "j", A_I[:, 1], 0.3))}  # tilted: the joint is violated there
    t = verify.joint_table(bad)
    assert not t.rows[0][4].ok and not t.all_ok and "✗" in repr(t)


def test_sweep_checks_pass_on_a_solved_sweep_and_catch_a_wrong_velocity():
    m = kinbook.examples.load("spatial_fourbar")
    res = m.simulate(np.linspace(0.0, 0.25, 61))
    assert all(err < tol for _, err, tol in verify.sweep_checks(res))
    res.qd[:] *= 1.01  # every velocity 1 % too large
    failed = [what for what, err, tol in verify.sweep_checks(res) if err >= tol]
    assert failed and failed[0].startswith("all of q̇")
