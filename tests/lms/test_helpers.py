"""kinbook.grading.lms without nbgrader or otter: what the helpers accept, compute and publish."""

import math

import nbformat
import pytest

import kinbook
from kinbook.grading import CheckResult, assert_passed, check_phi, nbgrader_score
from kinbook.grading.lms import nbgrader_credit

JOINT = kinbook.examples.load("ch13_example1").constraint("1")
WRONG = check_phi(["x1 - x2 - cos(phi2)", "y1 - y2 + sin(phi2)"], JOINT)
RIGHT = check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], JOINT)


@pytest.mark.parametrize("helper", [nbgrader_score, lambda r: nbgrader_credit(r, 4), assert_passed])
@pytest.mark.parametrize("value", [True, False, 1.0, 0.5, "passed", None, RIGHT.messages])
def test_only_a_check_result_is_accepted(helper, value):
    with pytest.raises(TypeError, match="expected the CheckResult a kinbook checker returns"):
        helper(value) if helper is not nbgrader_score else helper(value, 4)


@pytest.mark.parametrize("score", [-0.1, 1.5, math.nan, math.inf])
def test_a_score_outside_0_1_is_refused(score):
    with pytest.raises(ValueError, match=r"score must be a number in \[0, 1\]"):
        nbgrader_credit(CheckResult(False, score), 4)


@pytest.mark.parametrize("score", [True, "1"])
def test_a_score_that_reads_as_1_on_a_failed_check_is_refused(score):
    # CheckResult keeps its score as a float: True and "1" become 1.0, a failed check at full score
    with pytest.raises(ValueError, match="inconsistent CheckResult"):
        nbgrader_credit(CheckResult(False, score), 4)


def test_a_failed_check_at_full_score_is_inconsistent():
    with pytest.raises(ValueError, match="inconsistent CheckResult"):
        nbgrader_credit(CheckResult(False, 1.0, mistakes=["sign_flip"]), 4)


@pytest.mark.parametrize("points", [0, -4, math.nan, math.inf, True, "4", None])
def test_points_must_be_a_positive_number(points):
    with pytest.raises(ValueError, match="points must be a positive number"):
        nbgrader_credit(RIGHT, points)


@pytest.mark.parametrize(
    "score, points, credit",
    [(0.0, 4, 0.0), (0.5, 4, 2.0), (0.29, 1, 0.29), (2 / 3, 4, 2.66), (0.9999, 4, 3.99), (0.5, 1.5, 0.75)],
)
def test_credit_of_a_failed_check_is_rounded_down(score, points, credit):
    assert nbgrader_credit(CheckResult(False, score), points) == credit
    assert nbgrader_credit(CheckResult(True, 1.0), points) == float(points)


def test_assert_passed_raises_with_the_messages():
    assert_passed(RIGHT)
    with pytest.raises(AssertionError) as info:
        assert_passed(WRONG)
    assert all(m in str(info.value) for m in WRONG.messages) and "sign_flip" in str(info.value)


def test_nbgrader_score_outside_a_kernel_says_so(monkeypatch):
    import IPython

    # outside a kernel there is no shell — also when an earlier test of this process made one (`make test JOBS=1`)
    monkeypatch.setattr(IPython, "get_ipython", lambda: None)
    with pytest.raises(RuntimeError, match="runs only in a Jupyter kernel"):
        nbgrader_score(RIGHT, 4)


def test_nbgrader_score_publishes_the_credit_first(tmp_path):
    """In a real kernel: the verdict, then the credit as the cell's result, even when the cell ends otherwise."""
    from nbclient import NotebookClient

    setup = (
        "import kinbook\nfrom kinbook.grading import check_phi, nbgrader_score\n"
        'joint = kinbook.examples.load("ch13_example1").constraint("1")\n'
        'result = check_phi(["x1 - x2 - cos(phi2)", "y1 - y2 + sin(phi2)"], joint)'
    )
    cells = [setup, "nbgrader_score(result, points=4)\nresult", "%precision 0\nnbgrader_score(result, points=3)"]
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(s) for s in cells])
    NotebookClient(nb, kernel_name="python3", timeout=120, resources={"metadata": {"path": str(tmp_path)}}).execute()
    ends_otherwise, precision = nb.cells[1].outputs, nb.cells[2].outputs
    assert [o.output_type for o in ends_otherwise] == ["display_data", "execute_result", "execute_result"]
    assert ends_otherwise[0].data["text/plain"] == repr(WRONG)
    assert ends_otherwise[1].data == {"text/plain": "2.0"}
    assert precision[-1].data == {"text/plain": "1.5"}  # not "2": IPython's float precision does not apply


def test_the_readmes_lms_snippets_are_the_tested_ones():
    """The README's nbgrader/otter code is copied from docs/lms.md, whose notebooks `make test-lms` grades."""
    import os
    import re

    from .notebooks import blocks

    root = os.path.join(os.path.dirname(__file__), os.pardir, os.pardir)
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        readme = re.findall(r"^```python\n(.*?)^```$", f.read(), re.M | re.S)
    snippets = [b.rstrip("\n") for b in readme if "nbgrader_score" in b or "assert_passed" in b]
    tested = {source for section in ("nbgrader", "otter-grader") for _, source in blocks(section)}
    assert len(snippets) >= 3 and all(s in tested for s in snippets)
