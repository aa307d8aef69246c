"""Zeros far from the samples and answers right only on part of the domain: kinbook agrees with a second
computation made apart from its checker (sympy's solveset on each factor, numpy over the whole domain:
tests/grading/corpus_domain.py)."""

import pytest

from kinbook import grading
from kinbook.grading import factors
from kinbook.grading.read import read
from kinbook.grading.target import target_for

from . import corpus_domain as C
from . import corpus_turns as T

CHECKS = {"phi": grading.check_phi, "gamma": grading.check_gamma}
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


# ------------------------------------------------------------------------- docs/mistakes.md, rule by rule
def _docs():
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "docs" / "mistakes.md").read_text(encoding="utf-8")
    return " ".join(text.split())


def _whole(k, row):
    return grading.check_phi(C._with(k, row), C.mechanism("ch13_example1"))


def _numbers():
    """Numbers at a configuration: an angle row turned by a whole turn, by half a turn; a length row turned."""
    cases = T.number_cases()
    return [next(c for c in cases if c.id.endswith(end)) for end in ("angle-plus-2pi", "angle-half-turn",
                                                                      "length-plus-2pi")]


# each sentence of docs/mistakes.md that states a rule of this module, and an example the rule decides
RULES = [
    ("every factor of the row is solved or searched over the whole domain",
     lambda: _whole(3, f"(x2 - 100)*({C.BASE[3]})").mistakes, ["vanishing_factor"]),
    ("its real roots, those with t ≥ 0",
     lambda: (_whole(11, f"(t - 20)*({C.BASE[11]})").mistakes, _whole(11, f"(t + 5)*({C.BASE[11]})").mistakes),
     (["vanishing_factor"], [])),
    ("a minimum of |f| that touches zero without a sign change is refined",
     lambda: _whole(3, f"(cos(phi2) - 1)*({C.BASE[3]})").mistakes, ["vanishing_factor"]),
    ("a row is a multiple of a reference row only if it is the same multiple there",
     lambda: _whole(11, "atan2(sin(phi2), cos(phi2)) - 3*pi/4 - 100*t").mistakes, ["only_at_samples"]),
    ("`atan2(sin(phi3 - phi4), cos(phi3 - phi4))` for a slot's relative angle is right",
     lambda: grading.check_phi(["(-x3 + x4)*sin(phi3) - (-y3 + y4)*cos(phi3)",
                                "atan2(sin(phi3 - phi4), cos(phi3 - phi4))"],
                               C.mechanism("quick_return").constraint("4")).passed, True),
    ("is right turned by whole turns, the same number at every sample and times any constant",
     lambda: [grading.check_phi(["(-x3 + x4)*sin(phi3) - (-y3 + y4)*cos(phi3)", row],
                                C.mechanism("quick_return").constraint("4")).passed
              for row in ("phi3 - phi4 + 2*pi", "phi4 - phi3 - 2*pi", "2*(phi3 - phi4 + 2*pi)",
                          "atan2(sin(phi3 - phi4), cos(phi3 - phi4)) + 2*pi")], [True, True, True, False]),
    ("a row that measures no angle turned by 2πk is `whole_turn`",
     lambda: _whole(3, f"{C.BASE[3]} + 2*pi").mistakes, ["whole_turn"]),
    ("Numbers given at a configuration (`at=`) follow the same rule",
     lambda: [(r.passed, r.mistakes) for r in (grading.check_phi(c.values, T.target(c), at=c.at) for c in _numbers())],
     [(True, []), (False, ["wrong_value"]), (False, ["whole_turn"])]),
    ("a decimal that is c·180/π correctly rounded to 3 or more significant digits, or within 2 % of it",
     lambda: [grading.check_phi([row], C.mechanism("steering").constraint("driver 1")).mistakes
              for row in ("phi2 - 28.65*sin(2*t)", "phi2 - 28.7*sin(2*t)", "phi2 - 29.5*sin(2*t)")],
     [["degrees"], ["degrees"], ["wrong_value"]]),
    ("`phi2 - 100*t + 3.927` and `phi3 - phi4 - 6.283` are right",
     lambda: (_whole(11, "phi2 - 100*t + 3.927").passed,
              grading.check_phi(["(-x3 + x4)*sin(phi3) - (-y3 + y4)*cos(phi3)", "phi3 - phi4 - 6.283"],
                                C.mechanism("quick_return").constraint("4")).passed), (True, True)),
    ("a row that is 0 everywhere",
     lambda: grading.check_phi(["0", C.BASE[4]], C.mechanism("ch13_example1").constraint("1")).mistakes, ["zero_row"]),
    ("A decimal near an integer of the exercise (within 2 %) is this mistake too",
     lambda: grading.check_phi([C.BASE[3], "y1 - y2 + 1.0005*sin(phi2)"],
                               C.mechanism("ch13_example1").constraint("1")).mistakes, ["not_rounded"]),
    ("a function f(q, t) is compared again too, at configurations drawn from a digest of its own code",
     lambda: [grading.check_phi(c.answer, C.target(c)).mistakes for c in C.function_cases()],
     [["only_at_samples"], []]),
]


@pytest.mark.parametrize("sentence, example, expected", RULES, ids=[r[0][:40] for r in RULES])
def test_docs_state_the_rule_the_code_applies(sentence, example, expected):
    assert sentence in _docs(), sentence
    assert example() == expected


def test_a_function_is_witnessed_from_its_code_deterministically():
    from kinbook.grading.witness import code_text

    def f(q, t, k=3):
        return [q[0] * k]

    def g(q, t, k=3):
        return [q[0] * k]

    def h(q, t, k=4):
        return [q[0] * k]

    assert code_text(f) == code_text(g) != code_text(h)
    assert "0x" not in code_text(f)


def test_a_zero_row_is_named_as_what_it_is():
    """A 0 for a spatial revolute row was named 'local instead of global vector'; for the translational joint's
    first row, the book's misprint. Each now gets zero_row and no credit for the row."""
    cases = [("spatial_fourbar", "O_A"), ("ch13_example2", "2")]
    for mech_name, joint in cases:
        m = C.mechanism(mech_name)
        c = m.constraint(joint)
        rows = [str(e) for e in m.constraint_phi(c)]
        rows[0] = "0"
        r = grading.check_phi(rows, c)
        assert r.mistakes == ["zero_row"], (mech_name, r)
        assert r.score == pytest.approx((len(rows) - 1) / len(rows)), r
        grading.set_language("es")
        try:
            assert "una fila que es cero" in r.rows[0].message
        finally:
            grading.set_language("en")


def test_a_function_that_cannot_be_read_far_away_keeps_its_match():
    """A function that raises beyond some t (t > 1.5) is not a crash in the witness nor at the wide generic samples:
    its rows' matches stand there, as a row not defined there (a joint without t: its assembled samples are near)."""
    import math

    def f(q, t):
        if t > 1.5:
            raise ValueError("t too large")
        return [q[0] - q[3] + math.cos(q[5]), q[1] - q[4] + math.sin(q[5])]

    r = grading.check_phi(f, C.mechanism("ch13_example1").constraint("1"))
    assert r.passed, r
