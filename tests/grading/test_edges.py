"""Edges of the rounding and turning rules: degrees for radians rounded as a calculator shows them (in Φ and ν, a
driver's f(t) and a gear's φ⁰), and the constant of an angle row turned by whole turns and rounded. The decimals and
their expectations are made apart from kinbook (mpmath and decimal: tests/grading/corpus_edges.py)."""

import pytest

from kinbook import grading

from . import corpus_edges as C

CHECKS = {"phi": grading.check_phi, "nu": grading.check_nu, "gamma": grading.check_gamma}
CASES = C.cases()


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_edges_corpus(case):
    r = CHECKS[case.check](case.answer, C.target(case), **case.options)
    assert r.passed is case.passed, r
    assert r.mistakes == case.mistakes, r


def test_the_corpus_has_both_verdicts_in_each_class():
    for prefix in ("deg-", "turn-"):
        mine = [c for c in CASES if c.id.startswith(prefix)]
        assert mine and any(not c.passed for c in mine), prefix
    assert any(c.passed for c in CASES if c.id.startswith(("rad-", "turn-")))
    assert len(CASES) >= 60


def test_the_issue_example():
    """A gear's φ⁰ typed in degrees to four digits (it was named only with six)."""
    g = next(c for c in C.mechanism("ch13_planetary-phi0").constraints if c.type_name == "gear")
    r = grading.check_phi(["2*phi1 - 3*phi2 + phi3 - 28.65"], g)
    assert r.mistakes == ["degrees"] and "28.65 is 0.5 rad in degrees" in r.messages, r
    grading.set_language("es")
    try:
        text = " ".join(grading.check_phi(["2*phi1 - 3*phi2 + phi3 - 28.65"], g).messages)
    finally:
        grading.set_language("en")
    assert "28.65" in text and "grados" in text, text
