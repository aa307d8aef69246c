"""Rounded constants: a decimal that is the exercise's exact constant correctly rounded to 3 or more significant
digits passes in Φ, ν and γ alike; one that is not a rounding fails and, near the constant, is named
``not_rounded`` with both values (tests/grading/corpus_rounding.py makes the decimals apart from kinbook)."""

import pytest

from kinbook import grading
from kinbook.grading.rounding import is_rounding, significant_digits

from . import corpus_rounding as C

CHECKS = {"phi": grading.check_phi, "nu": grading.check_nu, "gamma": grading.check_gamma}
CASES = C.cases()


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_rounded_constants(case):
    r = CHECKS[case.check](case.answer(), C.target(case))
    assert r.passed is case.passed, r
    assert r.mistakes == case.mistakes, r
    if "not_rounded" in case.mistakes:
        text = " ".join(r.messages)
        assert str(float(case.typed)) in text or case.typed in text, text


def test_the_corpus_has_every_class():
    ids = [c.id for c in CASES]
    for kind in ("-up", "-down", "-truncated", "-2-digits"):
        assert any(i.endswith(kind) for i in ids), kind
    assert sum(c.passed for c in CASES) >= 50 and sum(not c.passed for c in CASES) >= 100


def test_the_issue_examples():
    """The figures that failed before (rounded constants refused whatever their rounding)."""
    mech = C.mechanism("3*pi/4")
    for typed in ("2.356", "2.3562", "2.36"):
        assert grading.check_phi([f"phi1 - 3*pi/4*sin(10*t) - {typed}"], mech.constraint("d")).passed, typed
    r = grading.check_phi(["phi1 - 3*pi/4*sin(10*t) - 2.357"], mech.constraint("d"))
    assert r.mistakes == ["not_rounded"] and "2.357 is not 3*pi/4 rounded" in r.messages[0]
    assert (significant_digits(2.356), significant_digits(0.000123), significant_digits(1.05)) == (4, 3, 3)
    assert is_rounding(0.866, 3 ** 0.5 / 2) and not is_rounding(0.867, 3 ** 0.5 / 2)


_SEEDED = r"""
import kinbook
from kinbook.grading import check_phi
from kinbook.grading.rounding import exact_constants
from kinbook.grading.target import target_for
m = kinbook.examples.load("ch13_example1")
print(list(exact_constants(target_for(m))))
print(list(exact_constants(target_for(kinbook.examples.load("spatial_fourbar")), "gamma")))
print(repr(check_phi(["phi2 - 135.1 - 5730*t"], m.constraint("driver 1"))))
print(repr(check_phi(["phi2 - 2.37 - 100*t"], m.constraint("driver 1"))))
"""


def test_the_rounding_rule_does_not_depend_on_the_hash_seed():
    """The exercise's constants, and the decimals of an answer, are judged in one fixed order: a set's order (which
    follows PYTHONHASHSEED) would pick another of two constants a decimal rounds, and order the notes otherwise."""
    import os
    import subprocess
    import sys

    runs = {subprocess.run([sys.executable, "-c", _SEEDED], capture_output=True, text=True, check=True,
                           env=dict(os.environ, PYTHONHASHSEED=seed)).stdout for seed in ("0", "1", "2", "3")}
    assert len(runs) == 1, runs
    assert "not_rounded" in next(iter(runs)) and "degrees" in next(iter(runs))
