"""otter-grader 7 grades the notebook of docs/lms.md without Docker: a correct, a wrong and an unanswered
submission, through `otter.api.grade_submission` (what `otter run` calls, without a process per submission).

Runs in the venv of `make test-lms` (requirements/lms.txt); skipped where otter-grader is not installed.
"""

import glob
import os

import nbformat
import pytest

pytest.importorskip("otter", reason="otter-grader is not installed here: `make test-lms` runs these tests")

from .notebooks import STUDENTS, WRONG_ROWS, answers, expected, otter_solution, otter_source, run, tool_env  # noqa: E402

ANSWER_TAG = "otter_answer_cell"
QUESTION = "revolute_OA"


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """`otter assign` on the source (which also runs the tests on the solution), then each student graded."""
    from otter.api import grade_submission

    root = tmp_path_factory.mktemp("otter")
    env = tool_env(root / "home")
    nbformat.write(otter_source(), root / "revolute.ipynb")
    run(["otter", "assign", "revolute.ipynb", "dist"], root, env)
    (autograder,) = glob.glob(str(root / "dist" / "autograder" / "revolute-autograder_*.zip"))
    results = {}
    with pytest.MonkeyPatch.context() as mp:  # the kernels otter starts see the same environment as `otter assign`
        for name in [k for k in os.environ if k not in env]:
            mp.delenv(name)
        for name, value in env.items():
            mp.setenv(name, value)
        for student, answer in answers(otter_solution()).items():
            nb = nbformat.read(root / "dist" / "student" / "revolute.ipynb", as_version=4)
            if answer is not None:
                next(c for c in nb.cells if ANSWER_TAG in c.metadata.get("tags", [])).source = answer
            nbformat.write(nb, root / f"{student}.ipynb")
            question = grade_submission(str(root / f"{student}.ipynb"), autograder, quiet=True).get_result(QUESTION)
            # summary(): the text otter's results.json gives the student as this question's output
            results[student] = {"score": question.score, "max_score": question.possible, "output": question.summary()}
    return root, results


def test_student_version_has_no_solution(graded):
    root, _ = graded
    text = (root / "dist" / "student" / "revolute.ipynb").read_text()
    assert otter_solution() not in text
    assert "Phi_OA = ..." in text


def test_pass_fail(graded):
    _, results = graded
    assert {s: (results[s]["score"], results[s]["max_score"]) for s in STUDENTS} == {
        "correct": (4, 4),
        "wrong": (0, 4),
        "blank": (0, 4),
    }


def test_results_carry_the_checkers_messages(graded):
    _, results = graded
    # the unanswered cell is released as `Phi_OA = ...`
    for student, answer in (("wrong", WRONG_ROWS), ("blank", Ellipsis)):
        verdict = expected(answer)
        assert not verdict.passed and verdict.messages
        output = results[student]["output"]
        for message in verdict.messages:
            assert message in output, (student, message)
    assert "All test cases passed!" in results["correct"]["output"]
