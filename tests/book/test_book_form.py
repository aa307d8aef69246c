"""The book-notation printer: book_form must equal kinbook's derivation for every planar joint, print in the
book's order, and break a wide row into lines that fit a notebook column."""

import pytest
import sympy as sp

from kinbook.book import notation as N
from kinbook.book import printed, verify

S = N.S


@pytest.mark.parametrize("kind", sorted(N.PAIR_KINDS))
def test_book_form_equals_the_derivation_at_any_angle(kind):
    """Back-substituted (x_i^P → x_i + ξ cos φ_i − η sin φ_i, …), the compact form is kinbook's expression."""
    m = N.pair(kind)
    d = m.symbolic()
    for name, derived in (("Phi", d.Phi), ("Phi_q", d.Phi_q), ("gamma", d.gamma)):
        compact = N.book_form(derived, m)
        for k, (c, e) in enumerate(zip(compact, derived)):
            diff = sp.expand(sp.expand(N.from_book(c.doit(), m)) - e)
            assert sp.simplify(diff) == 0, f"{kind} {name}[{k}]: {c}"


def test_a_wrong_compact_form_is_caught():
    """The check above can fail: a slip in one difference of the compact form does not equal the derivation."""
    m = N.pair("t")
    wrong = N.book_form(m.symbolic().Phi[0], m).doit().subs(S.yQ_i, S.y_i)
    assert sp.simplify(sp.expand(N.from_book(wrong, m) - m.symbolic().Phi[0])) != 0


def test_the_book_factors_the_tables_and_gamma_as_printed():
    """Where the book is right, the compact form is the book's own (its vectors, its order of differences)."""
    for kind, table in (("rt", printed.TABLES["13.4"][1]), ("t", printed.TABLE_13_5_JACOBIAN["t"])):
        m = N.pair(kind)
        got = N.book_form(m.symbolic().Phi_q, m)
        assert N.latex(got[0, 1], book=True) == N.latex(table[0, 1], book=True)
    m = N.pair("rt")
    tex = N.latex(N.book_form(m.symbolic().gamma[0], m), book=True)
    assert tex.startswith(r"\dot{\varphi}_i \left(\dot{\varphi}_i - 2 \dot{\varphi}_j\right)")
    assert r"\left(x^{P}_{i} - x_{j}\right) \left(y^{P}_{j} - y^{Q}_{j}\right)" in tex
    m = N.pair("t")
    assert N.latex(N.book_form(m.symbolic().Phi[0], m), book=True) == (
        r"\left(x^{P}_{i} - x^{Q}_{i}\right) \left(y^{P}_{j} - y^{P}_{i}\right) - \left(x^{P}_{j} - x^{P}_{i}\right)"
        r" \left(y^{P}_{i} - y^{Q}_{i}\right)")


def test_the_printer_writes_positive_terms_first_and_keeps_factors():
    assert N.latex(S.xP_j - S.x_i, book=True) == r"x^{P}_{j} - x_{i}"
    assert N.latex(-S.x_i + S.xP_j - S.l**2, book=True) == r"x^{P}_{j} - x_{i} - l^{2}"
    rr = N.pair("rr")
    assert N.latex(N.book_form(rr.symbolic().Phi_q[0, 0], rr), book=True) == r"2 \left(x^{P}_{i} - x^{P}_{j}\right)"


def test_lines_break_a_wide_row_after_whole_terms():
    m = N.pair("rr")
    rows = N.book_form(m.symbolic().gamma, m)
    tex = N.lines(rows, [r"\gamma_1"], width=58)
    parts = tex.removeprefix(r"\begin{aligned}").removesuffix(r"\end{aligned}").split(r" \\ ")
    assert len(parts) >= 4
    assert all(N._width(p) <= 58 + 12 for p in parts)        # a line is at most one term past the budget
    one = N.lines(rows, [r"\gamma_1"], width=10**6)
    assert r"\\" not in one                                     # with room, one row is one line


def test_disagreement_lines_name_both_forms():
    m = N.pair("rt")
    c = verify.compare(printed.TABLES["13.4"][1], m.symbolic().Phi_q, m, book_form=N.book_form(m.symbolic().Phi_q, m),
                       rows=[r"\Phi_1"], columns=N.S.columns)
    (line,) = c.latex_disagreements()
    assert r"\text{printed }" in line and r"\text{kinbook }" in line and r"\left(x^{P}_{i} - x_{j}\right)" in line
