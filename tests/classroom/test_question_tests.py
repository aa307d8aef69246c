"""Question tests written by the author (part(..., tests=[...])) and `kinbook validate --mutations` (issue 29)."""

import pytest

import kinbook
from kinbook.classroom.parts import Part, part
from kinbook.classroom.validate import question_tests
from kinbook.errors import GradingError

SIN_COS = ["x3 + 3*sin(phi3) - x4 + 1.5*cos(phi4)", "y3 + 3*cos(phi3) - y4 + 1.5*sin(phi4)"]
RIGHT = ["x4 - x3 - 3*cos(phi3) - 1.5*cos(phi4)", "y4 - y3 - 3*sin(phi3) - 1.5*sin(phi4)"]


@pytest.fixture(scope="module")
def rev_b():
    mech = kinbook.examples.load("ch13_example1")
    return mech.constraint("4")


def test_question_tests_are_run_and_report_what_fails(rev_b):
    good = Part("rev_B", 3, "Phi_B", "phi", rev_b, tests=[(SIN_COS, "sin_cos"), (RIGHT, None)])
    assert [ok for ok, _ in question_tests(good)] == [True, True]
    bad = Part("rev_B", 3, "Phi_B", "phi", rev_b, tests=[(SIN_COS, "sign_flip"), (SIN_COS, None)])
    results = question_tests(bad)
    assert [ok for ok, _ in results] == [False, False]
    assert "must be named sign_flip) is named sin_cos" in results[0][1]
    assert "(a right answer) is refused: sin_cos" in results[1][1]


def test_part_refuses_a_test_that_names_no_mistake(rev_b):
    with pytest.raises(GradingError, match="test 1 names 'sin_or_cos', which is no mistake code"):
        part("rev_B", 3, answer="Phi_B", check="phi", target=rev_b, tests=[(SIN_COS, "sin_or_cos")])
    with pytest.raises(GradingError, match=r"test 1 must be \(answer, mistake code or None\)"):
        part("rev_B", 3, answer="Phi_B", check="phi", target=rev_b, tests=[SIN_COS + ["0"]])


def test_validate_mutations_cli(capsys):
    from pathlib import Path

    from kinbook.cli import main

    source = Path(__file__).resolve().parents[2] / "exercises" / "ex01-revolute-joint-phi.ipynb"
    status = main(["validate", "--mutations", str(source), "--variants", "0", "--limit", "15"])
    out = capsys.readouterr().out
    assert status == 0, out
    assert "ex01-revolute-joint-phi:revolute_OA" in out and "valid: no mutant passes" in out
    status = main(["validate", "--mutations", "--try-its", "13-1/try-1", "--variants", "0"])
    out = capsys.readouterr().out
    assert status == 0 and "13-1/try-1" in out and "named 100.0 %" in out, out
