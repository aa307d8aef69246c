"""Every answer of the corpus gets exactly the verdict, score and mistake codes it states."""

import pytest

from kinbook import grading

from .corpus import CASES, target

CHECKS = {
    "phi": grading.check_phi,
    "jacobian": grading.check_jacobian,
    "nu": grading.check_nu,
    "gamma": grading.check_gamma,
}


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_corpus(case):
    result = CHECKS[case.check](case.answer, target(case.mech, case.constraint), **case.options)
    assert isinstance(result, grading.CheckResult)
    assert result.passed is case.passed, repr(result)
    assert result.score == pytest.approx(case.score, abs=1e-6), repr(result)
    assert result.mistakes == case.mistakes, repr(result)
    assert 0.0 <= result.score <= 1.0
    assert result.messages
