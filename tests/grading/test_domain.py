"""Zeros far from the samples and answers right only on part of the domain: kinbook agrees with a second
computation made apart from its checker (sympy's solveset on each factor, numpy over the whole domain:
tests/grading/corpus_domain.py)."""

import pytest

from kinbook import grading
from kinbook.grading import factors
from kinbook.grading.read import read
from kinbook.grading.target import target_for

from . import corpus_domain as C

CHECKS = {"phi": grading.check_phi}
CASES = C.cases()


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_domain_corpus(case):
    r = CHECKS[case.check](case.answer, C.target(case), **case.options)
    assert r.passed is case.passed, r
    assert r.mistakes == case.mistakes, r


def test_the_corpus_has_both_verdicts_in_each_class():
    for prefix in ("far-zero-whole", "far-zero-joint", "wide-"):
        mine = [c for c in CASES if c.id.startswith(prefix)]
        assert any(c.passed for c in mine) and any(not c.passed for c in mine), prefix


def test_the_issue_examples():
    """The far zeros and the whole-domain answers the issue found accepted."""
    mech = C.mechanism("ch13_example1")
    for factor, k in (("x2 - 100", 3), ("phi2 - 40", 3), ("y3**2 - 49", 7), ("t - 20", 11), ("x3 + 50", 9)):
        r = grading.check_phi(C._with(k, f"({factor})*({C.BASE[k]})"), mech)
        assert r.mistakes == ["vanishing_factor"], (factor, r)
    r = grading.check_phi(C._with(3, f"(x2 - 100)*({C.BASE[3]})"), mech)
    assert "x2 = 100" in r.rows[3].message, r
    r = grading.check_phi(C._with(11, f"(t - 20)*({C.BASE[11]})"), mech)
    assert "t = 20" in r.rows[11].message, r


def test_a_polynomial_factor_is_solved_not_searched():
    """(x2 − 100) gives its root exactly: the starts put x2 at 100 (and nothing else moves)."""
    mech = C.mechanism("ch13_example1")
    tg = target_for(mech)
    A = read(C._with(3, f"(x2 - 100)*({C.BASE[3]})"), tg, "Phi")
    Q, T = factors.starts(tg, A, 3)
    assert len(Q) and set(Q[:, 3]) >= {100.0}
    g = tg.samples("generic")
    moved = [q for q in Q if q[3] == 100.0]
    assert any(set((q != g.Q[i]).nonzero()[0]) == {3} for q in moved for i in range(factors.BASES))
