"""Whole turns: every row that measures an angle in the shipped mechanisms and exercises is right turned by whole
turns (the same number at every configuration) and through atan2 of the whole row, wrong by a half turn or where
atan2 leaves no zero; a length row turned is ``whole_turn``. Each expectation is made apart from kinbook's checker
(sympy and numpy over the whole domain: tests/grading/corpus_turns.py)."""

import pytest

from kinbook import grading

from . import corpus_turns as C

CASES = C.cases()


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_turns_corpus(case):
    r = grading.check_phi(case.answer, C.target(case))
    assert r.passed is case.passed, r
    assert r.mistakes in case.names, r


def test_the_corpus_covers_every_kind_of_angle_row_both_ways():
    assert len(CASES) >= 200
    for kind in ("ground", "driver", "-2-angle-"):  # a fixed body's φ, drivers, a slot's relative angle (row 2)
        mine = [c for c in CASES if kind in c.id]
        assert any(c.passed for c in mine) and any(not c.passed for c in mine), kind
    assert any(c.names == [["whole_turn"]] for c in CASES)


def test_the_issue_examples():
    """The slot's relative-angle row of the quick-return written with a 2π wrap (it was wrong_value)."""
    slot = C.mechanism("quick_return").constraint("4")
    first = "(-x3 + x4)*sin(phi3) - (-y3 + y4)*cos(phi3)"
    for row in ("phi3 - phi4 + 2*pi", "phi3 - phi4 - 2*pi", "phi4 - phi3 + 2*pi", "-(phi3 - phi4) - 2*pi",
                "atan2(sin(phi3 - phi4), cos(phi3 - phi4))"):
        assert grading.check_phi([first, row], slot).passed, row
    r = grading.check_phi([f"{first} + 2*pi", "phi3 - phi4"], slot)
    assert r.mistakes == ["whole_turn"] and "Φ_10 + 2π" in " ".join(r.messages), r


NUMBERS = C.number_cases()


@pytest.mark.parametrize("case", NUMBERS, ids=[c.id for c in NUMBERS])
def test_numbers_at_a_configuration_follow_the_same_rule(case):
    """Φ given as numbers at a configuration (``at=``): an angle row's value turned by whole turns is right, as the
    expression turned is; a length row's is ``whole_turn``; half a turn is wrong."""
    r = grading.check_phi(case.values, C.target(case), at=case.at)
    assert r.passed is case.passed, r
    assert r.mistakes in case.names, r


def test_the_numbers_cover_both_verdicts_of_every_kind_of_row():
    assert len(NUMBERS) >= 30
    for kind in ("ground", "driver", "-2-angle-"):
        mine = [c for c in NUMBERS if kind in c.id]
        assert any(c.passed for c in mine) and any(not c.passed for c in mine), kind
    assert any(c.names == [["whole_turn"]] for c in NUMBERS)
