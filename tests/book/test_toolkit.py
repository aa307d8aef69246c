"""The book toolkit: notation round trips, printed-vs-derived comparisons that can fail, cross-checks."""

import numpy as np
import pytest

import kinbook
from kinbook.book import notation as N
from kinbook.book import printed, verify


@pytest.mark.parametrize("kind", sorted(N.PAIR_KINDS))
def test_book_form_is_kinbooks_derivation_at_any_angle(kind):
    """to_book reads the derivation off at φ = 0; from_book must give back kinbook's value at every angle."""
    m = N.pair(kind)
    d = m.symbolic()
    for derived in (d.Phi, d.Phi_q, d.gamma):
        c = verify.compare(N.to_book(derived, m), derived, m, seed=7)
        assert c.all_agree and np.all(c.signs == 1)


def test_compare_finds_a_wrong_entry_and_a_negated_row():
    m = N.pair("r")
    J = printed.TABLES["13.1"][1]
    wrong = J.copy()
    wrong[1, 2] = wrong[1, 2] + N.S.x_i  # a slip in one entry
    c = verify.compare(wrong, m.symbolic().Phi_q, m)
    assert c.disagreements() == [(1, 2)]
    c = verify.compare(-J, m.symbolic().Phi_q, m)  # the same constraint with the opposite sign
    assert c.all_agree and list(c.signs) == [-1, -1]
    assert "printed rows 1, 2 = −1 × kinbook's" in c.summary()


def test_the_printed_tables_differ_exactly_where_the_errata_say():
    found = {}
    for table, (kind, P) in printed.TABLES.items():
        m = N.pair(kind)
        found[table] = verify.compare(P, m.symbolic().Phi_q, m).disagreements()
    assert found == {"13.1": [], "13.2": [(0, 5)], "13.3": [(0, 2), (0, 5)], "13.4": [(0, 5)]}


def test_cross_checks_measure_real_errors():
    m = kinbook.examples.load("ch13_example3")
    q = m.solve_position(0.0)
    qd = m.solve_velocity(q, 0.0)
    assert verify.jacobian_fd(m, q) < 1e-7
    assert verify.gamma_path(m, q, qd) < 1e-2 * np.abs(m.gamma(q, qd)).max()
    t = verify.checks(("Φ_q against finite differences", verify.jacobian_fd(m, q), 1e-6), ("a wrong one", 0.5, 1e-6))
    assert [c.ok for c in t] == [True, False] and "differs by 0.5" in repr(t)


def test_latex_uses_the_books_names():
    m = kinbook.examples.load("ch13_example1")
    tex = N.latex(m.symbolic().Phi[3] + m.qd[5])
    assert r"\varphi_{2}" in tex and r"\dot{\varphi}_{2}" in tex and "phi2" not in tex
    assert N.matrix([[-1e-17, 0.5]]) == r"\begin{array}{rr}0 & 0.5\end{array}"
    pair = N.pair("rr")
    assert r"\varphi_{i}" in N.latex(pair.symbolic().Phi, pair)


def test_figures_keep_the_title_the_notebook_gives():
    """joint_figure(title=...) and make_3d_axes(title=...) followed by plotting.draw show the caller's title (the
    figure caption of the book), not the mechanism's name; a bare draw is still titled with the mechanism."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from kinbook.spatial import joint_figure, make_3d_axes, plotting

    mech = kinbook.examples.load("spatial_fourbar")
    q0 = mech.solve_position(0.0)
    try:
        assert joint_figure(mech, q0, title="Fig. 14.12: revolute joint").get_title() == "Fig. 14.12: revolute joint"
        ax = make_3d_axes(title="global components s (eq. 1)")
        plotting.draw(mech, q0, ax=ax)
        assert ax.get_title() == "global components s (eq. 1)"
        assert plotting.draw(mech, q0).ax.get_title() == mech.title != ""
    finally:
        plt.close("all")


def test_a_verdict_cell_does_not_wrap_but_a_label_may():
    table = verify.Table(["what", "verdict"], [["a long label that may wrap", verify.Check("Φ", 3e-13, 1e-12)],
                                               ["other", verify.Check("Φ", 0.34, 1e-12)]])
    html = table._repr_html_()
    assert "<td style='text-align:left; white-space:nowrap'>✓ &lt; 1e-12</td>" in html
    assert "<td style='text-align:left; white-space:nowrap'>✗ 0.34</td>" in html
    assert "<td style='text-align:left'>a long label that may wrap</td>" in html
