"""Every try-it check of the chapter notebooks and every exercise part on the book's examples, re-run with
typical wrong answers (tests/grading/tryits.py): right answers pass, wrong ones fail with the mistake they
are, and the generic "wrong value" is given for at most 1 in 10."""

import pytest

from .tryits import all_tryits

TRY_ITS = all_tryits()
WRONG = [(t, answer, code) for t in TRY_ITS for answer, code in t.wrong]


@pytest.mark.parametrize("t", TRY_ITS, ids=[t.id for t in TRY_ITS])
def test_the_right_answer_passes(t):
    r = t.checker(t.right, t.target(), **t.options)
    assert r.passed, r


@pytest.mark.parametrize("t, answer, code", WRONG, ids=[f"{t.id}:{c}:{k}" for k, (t, _, c) in enumerate(WRONG)])
def test_a_typical_wrong_answer_is_named(t, answer, code):
    r = t.checker(answer, t.target(), **t.options)
    assert not r.passed, r
    assert code in r.mistakes, r


def test_at_most_one_in_ten_wrong_answers_gets_the_generic_wrong_value():
    generic = 0
    for t, answer, _ in WRONG:
        r = t.checker(answer, t.target(), **t.options)
        generic += r.mistakes == ["wrong_value"]
    assert len(WRONG) >= 80
    assert generic / len(WRONG) <= 0.1, generic
