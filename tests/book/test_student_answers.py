"""Realistic wrong answers to every try-it (tests/book/student_answers.py), graded as the notebook grades them
(issue 29): generic feedback ≤ 10 %, no misleading name, no false pass. The table per try-it is printed
(``pytest -s``) and is the failure message.

An answer is *named* when the verdict names the code a teacher gives it (or the one other code its entry declares
just as true, with the reason in the corpus); *generic* when the verdict names nothing but "wrong value";
*misleading* when it names something else; a *false pass* when it passes.
"""

import pytest

from kinbook.book.tryits import get

from . import student_answers

CASES = student_answers.cases()
GENERIC = {"wrong_value"}


def verdict(case, answer):
    result = get(case.id).check(answer.answer)
    codes = set(result.mistakes)
    if result.passed:
        return "false_pass", codes
    if {answer.code, *answer.also} & codes:
        return "named", codes
    if codes <= GENERIC:
        return "generic", codes
    return "misleading", codes


def table():
    rows, lines = [], []
    for case in CASES:
        tally = {"named": 0, "generic": 0, "misleading": 0, "false_pass": 0}
        for answer in case.wrong:
            kind, codes = verdict(case, answer)
            tally[kind] += 1
            if kind != "named":
                lines.append(f"  {case.id:12} {answer.code:20} -> {kind}: {sorted(codes)}")
        rows.append((case.id, len(case.wrong), tally))
    head = f"{'try-it':12} {'answers':>7} {'named':>6} {'generic':>8} {'misleading':>10} {'false pass':>10}"
    out = [head] + [f"{id:12} {n:7} {t['named']:6} {t['generic']:8} {t['misleading']:10} {t['false_pass']:10}"
                    for id, n, t in rows]
    total = {k: sum(t[k] for _, _, t in rows) for k in rows[0][2]}
    n = sum(r[1] for r in rows)
    out.append(f"{'total':12} {n:7} {total['named']:6} {total['generic']:8} {total['misleading']:10} "
               f"{total['false_pass']:10}   generic {100 * total['generic'] / n:.1f} %")
    return n, total, "\n".join(out + lines)


def test_the_corpus_covers_every_try_it_with_six_answers_or_more():
    get("13-1/try-1")
    from kinbook.book.tryits import TRY_ITS

    assert {c.id for c in CASES} == set(TRY_ITS)
    assert sum(len(c.wrong) for c in CASES) >= 200
    assert sum(len(c.wrong) >= 6 for c in CASES) >= 27


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_the_right_answer_typed_here_passes_and_each_wrong_one_is_its_mistake(case):
    """The corpus' own derivation is right (it passes), and each wrong answer is confirmed by a second
    computation to be exactly its mistake (and to differ from the right answer)."""
    assert get(case.id).check(case.right).passed, case.id
    assert case.unconfirmed == [], case.id


def test_realistic_wrong_answers_are_named_never_passed_never_misnamed():
    n, total, text = table()
    print("\n" + text)
    assert total["false_pass"] == 0, text
    assert total["misleading"] == 0, text
    assert total["generic"] <= 0.10 * n, text


PLANAR_NOTATION = ("A(φ)", "B(φ)", "(ξ, η)", "(eq. 5)", "(ec. 5)", "eq. 10", "ec. 10", "eq. 13", "ec. 13")


@pytest.mark.parametrize("lang", ["en", "es"])
def test_a_3d_try_it_never_shows_the_planar_notation(lang):
    """The feedback to every wrong answer of chapter 14 speaks of A(p), Euler parameters and angles — never the
    plane's A(φ), (ξ, η) or chapter 13's equations (the review saw A(φ) hints in 14-1)."""
    from kinbook.grading import set_language

    set_language(lang)
    try:
        seen = []
        for case in CASES:
            if not case.id.startswith("14-"):
                continue
            for answer in case.wrong:
                lines = repr(get(case.id).check(answer.answer)).splitlines()
                text = "\n".join(line for line in lines if "as read" not in line and "tal como" not in line)
                seen += [(case.id, answer.code, p) for p in PLANAR_NOTATION if p in text]
    finally:
        set_language("en")
    assert seen == []
