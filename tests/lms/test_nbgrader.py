"""nbgrader 0.9.6 grades the notebook of docs/lms.md: a correct, a wrong and an unanswered submission.

Runs in the venv of `make test-lms` (requirements/lms.txt); skipped where nbgrader is not installed.
"""

import html

import nbformat
import pytest

pytest.importorskip("nbgrader", reason="nbgrader is not installed here: `make test-lms` runs these tests")

from .notebooks import STUDENTS, WRONG_ROWS, answers, expected, nbgrader_solution, nbgrader_source, run, tool_env  # noqa: E402

CONFIG = """\
c = get_config()
c.CourseDirectory.course_id = "kinbook-lms-test"
c.CourseDirectory.db_assignments = [dict(name="ps1")]
c.CourseDirectory.db_students = [dict(id=s) for s in {students!r}]
"""


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    """A course directory taken through generate_assignment, autograde and generate_feedback."""
    root = tmp_path_factory.mktemp("nbgrader")
    course, env = root / "course", tool_env(root / "home")
    (course / "source" / "ps1").mkdir(parents=True)
    (course / "nbgrader_config.py").write_text(CONFIG.format(students=STUDENTS))
    nbformat.write(nbgrader_source(), course / "source" / "ps1" / "revolute.ipynb")
    run(["nbgrader", "generate_assignment", "ps1"], course, env)
    for student, answer in answers(nbgrader_solution()).items():
        nb = nbformat.read(course / "release" / "ps1" / "revolute.ipynb", as_version=4)
        if answer is not None:
            next(c for c in nb.cells if c.metadata.get("nbgrader", {}).get("solution")).source = answer
        (course / "submitted" / student / "ps1").mkdir(parents=True)
        nbformat.write(nb, course / "submitted" / student / "ps1" / "revolute.ipynb")
    run(["nbgrader", "autograde", "ps1"], course, env)
    run(["nbgrader", "generate_feedback", "ps1"], course, env)
    return course


def scores(course):
    from nbgrader.api import Gradebook

    with Gradebook(f"sqlite:///{course / 'gradebook.db'}") as gb:
        return {
            s: {g.name: (g.auto_score, g.max_score) for g in gb.find_submission_notebook("revolute", "ps1", s).grades}
            for s in STUDENTS
        }


def test_partial_credit_4_2_0(course):
    assert scores(course) == {
        "correct": {"test": (4.0, 4.0), "hidden_test": (1.0, 1.0)},
        "wrong": {"test": (2.0, 4.0), "hidden_test": (0.5, 1.0)},  # one of two rows wrong, in both cells
        "blank": {"test": (0.0, 4.0), "hidden_test": (0.0, 1.0)},
    }


def test_release_has_neither_solution_nor_hidden_test(course):
    text = (course / "release" / "ps1" / "revolute.ipynb").read_text()
    assert nbgrader_solution() not in text
    assert 'order=\\"book\\"' not in text and "HIDDEN TESTS" not in text
    assert "raise NotImplementedError()" in text
    assert "nbgrader_score(check_phi(Phi_OA, joint), points=4)" in text  # the visible test stays


def feedback(course, student):
    return (course / "feedback" / student / "ps1" / "revolute.html").read_text()


def test_feedback_carries_the_checkers_messages(course):
    page = feedback(course, "wrong")
    for result in (expected(WRONG_ROWS), expected(WRONG_ROWS, order="book")):
        assert result.mistakes == ["sign_flip"]
        for message in result.messages:
            assert message in page or html.escape(message) in page, message
    assert "NameError" in feedback(course, "blank")


def test_validate_catches_points_that_differ_from_the_metadata(tmp_path):
    """The points are written twice (metadata, call): `nbgrader validate` on the source finds a difference."""
    names = {"same": 4, "metadata_above": 8, "metadata_below": 2}  # the call says points=4
    for name, points in names.items():
        nb = nbgrader_source()
        next(c for c in nb.cells if c.metadata.nbgrader["grade_id"] == "test").metadata.nbgrader["points"] = points
        nbformat.write(nb, tmp_path / f"{name}.ipynb")
    # one run for the three (nbgrader stops at the third: "metadata_below" must come last)
    proc = run(["nbgrader", "validate", *(f"{n}.ipynb" for n in names)], tmp_path, tool_env(tmp_path / "home"), check=False)
    report = proc.stdout
    assert report.index("Success! Your notebook passes all the tests.") < report.index("VALIDATION FAILED ON 1 CELL(S)")
    assert "partial credit cannot be greater than maximum points" in proc.stderr
    assert "fatal error while trying to validate 'metadata_below.ipynb'" in proc.stderr


MISUSES = {  # test-cell source -> nbgrader's score out of 4 (the wrong answer is worth 2)
    # why the helper exists: nbgrader gives a cell whose result is not a number full marks
    "result": 4.0,
    "result.passed": 4.0,
    # the helper publishes the credit when it runs: what the cell ends with does not matter
    "nbgrader_score(result, points=4)": 2.0,
    "nbgrader_score(result, points=4)\nresult": 2.0,
    "nbgrader_score(result, points=4)\nresult.passed": 2.0,
    "if True:\n    nbgrader_score(result, points=4)": 2.0,
    # refused loudly (an error: 0, and `nbgrader validate` on the source fails)
    "nbgrader_score(result, points=4);": 0.0,
    "nbgrader_score(result.passed, points=4)": 0.0,
    "nbgrader_score(result.score, points=4)": 0.0,
    "nbgrader_score(result, points=True)": 0.0,
    # a second call raises after the first credit, which is the one nbgrader reads
    "nbgrader_score(result, points=4)\nnbgrader_score(correct, points=4)": 2.0,
}


def test_misuses_graded_by_nbgraders_own_rule(tmp_path):
    from nbclient import NotebookClient
    from nbgrader.utils import determine_grade

    setup = nbformat.v4.new_code_cell(
        "import kinbook\nfrom kinbook.grading import check_phi, nbgrader_score\n"
        'joint = kinbook.examples.load("ch13_example1").constraint("1")\n'
        f"result = check_phi({WRONG_ROWS!r}, joint)\n"
        'correct = check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], joint)'
    )
    cells = []
    for source in MISUSES:
        cell = nbformat.v4.new_code_cell(source)
        cell.metadata["nbgrader"] = dict(grade=True, solution=False, locked=True, points=4, grade_id=f"c{len(cells)}")
        cells.append(cell)
    nb = nbformat.v4.new_notebook(cells=[setup] + cells)
    NotebookClient(nb, kernel_name="kinbook", allow_errors=True, timeout=120, resources={"metadata": {"path": str(tmp_path)}}).execute()
    got = {cell.source: determine_grade(cell)[0] for cell in cells}
    assert got == MISUSES
    twice = cells[-1].outputs
    assert [o.output_type for o in twice] == ["display_data", "execute_result", "error"]
    assert "already called in this cell" in twice[-1].evalue
