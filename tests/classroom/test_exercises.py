"""The shipped exercises (exercises/*.ipynb): each one's own solution earns full marks, through the same
data path as a submission (answers encoded in the notebook's namespace, decoded and checked by the grader)."""

import glob
import json
import os
import shutil

import pytest

from kinbook.classroom import grade, student_parameters, write_variant
from kinbook.classroom.notebook import find_parameters, load_source, student_notebook
from kinbook.classroom.release import write_notebook
from kinbook.classroom.serialize import decode, dumps
from kinbook.classroom.variant import references

from .conftest import BWRAP, ENOUGH

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
EXERCISES = sorted(glob.glob(os.path.join(ROOT, "exercises", "*.ipynb")))


def test_there_are_at_least_twelve_exercises():
    assert len(EXERCISES) >= 12


@pytest.mark.parametrize("path", EXERCISES, ids=[os.path.basename(p)[:4] for p in EXERCISES])
def test_solution_scores_full_marks(path, monkeypatch, tmp_path):
    monkeypatch.setenv("KINBOOK_SANDBOX_ROOT", str(tmp_path))  # part() stays quiet, as while grading
    monkeypatch.chdir(tmp_path)
    source = load_source(path)
    values = student_parameters(source, "alice")
    parts = references(source, values)
    assert parts and all(p.points > 0 for p in parts)
    nb = student_notebook(source, values, "alice" if values else None, keep_solutions=True)
    ns = {"__name__": "__main__"}
    import matplotlib

    matplotlib.use("Agg")
    for cell in nb.cells:
        if cell.cell_type == "code":
            exec(compile(cell.source, path, "exec"), ns)
    names = sorted({p.answer for p in parts})
    answers = {k: decode(v) for k, v in json.loads(dumps(names, ns))["answers"].items()}
    for p in parts:
        result = p.run(answers[p.answer], answers)
        assert result.passed, (p.name, result)


@pytest.mark.parametrize("path", EXERCISES, ids=[os.path.basename(p)[:4] for p in EXERCISES])
def test_release_hides_the_solutions(path):
    nb = student_notebook(load_source(path))
    text = "\n".join(c.source for c in nb.cells)
    assert "### BEGIN" not in text and "### END" not in text
    assert "raise NotImplementedError()" in text


def _exercise(prefix):
    return next(p for p in EXERCISES if os.path.basename(p).startswith(prefix))


def test_variants_are_per_student_and_reproducible(tmp_path):
    source = load_source(_exercise("ex09"))
    a1, a2, b = (student_parameters(source, s) for s in ("alice", "alice", "bob"))
    assert a1 == a2 and a1 != b
    _, _, ranges, _ = find_parameters(source.nb)
    assert 60 <= a1["omega"] <= 140 and a1["t"] in ranges["t"]
    path = write_variant(_exercise("ex09"), "alice", tmp_path)
    assert path.name == "ex09-point-kinematics-alice.ipynb"
    import nbformat

    cells = "\n".join(c.source for c in nbformat.read(str(path), 4).cells)
    assert f"P = {json.dumps(a1, sort_keys=True)}  # parameters of student 'alice'" in cells


def test_variant_solutions_are_graded_in_the_sandbox_and_a_classmates_variant_is_named(tmp_path):
    src = _exercise("ex11")
    source = load_source(src)
    subs = tmp_path / "subs"
    for student in ("alice", "bob"):
        values = student_parameters(source, student)
        write_notebook(student_notebook(source, values, student, keep_solutions=True),
                       subs / student / f"{source.exercise}.ipynb")
    (subs / "carol").mkdir()
    shutil.copy(subs / "alice" / f"{source.exercise}.ipynb", subs / "carol" / f"{source.exercise}.ipynb")
    # dave answers with kinbook.spatial's own functions, the ones ex11's hidden checks use (D4: 10/10, unreported)
    nb = student_notebook(source, student_parameters(source, "dave"), "dave")
    answers = [c for c in nb.cells if c.metadata.get("kinbook", {}).get("answer")]
    answers[0].source = "from kinbook.spatial import A_from_euler as rot\nA = rot(psi, theta, phi)"
    answers[1].source = "p = ks.p_from_A(A)"
    answers[2].source = "E, G = ks.E(p), ks.G(p)\nEGt = E @ G.T\nEtE = E.T @ E"
    write_notebook(nb, subs / "dave" / f"{source.exercise}.ipynb")
    results = {r.student: r for r in grade(src, [subs], tmp_path / "graded", timeout=ENOUGH, memory=600, jobs=2,
                                           isolation=BWRAP)}
    dave = {p.part: p for p in results["dave"].parts}
    assert results["dave"].score == 10
    assert {k: p.reference for k, p in dave.items()} == {
        "A": "kinbook.spatial.A_from_euler (cell 6)", "p": "ks.p_from_A() (cell 8)", "EGt": "ks.E() (cell 10)",
        "EtE": "ks.E() (cell 10)"}  # cells numbered as the student sees them (markdown included)
    assert all(p.reference == "" for p in results["alice"].parts)  # her own E and G, and the release's ks.
    assert results["alice"].status == results["bob"].status == "ok"
    assert results["alice"].score == results["alice"].max_score == 10
    assert results["bob"].score == 10
    # alice's notebook in carol's folder: a copying signal, said as such (not "tampered")
    assert results["carol"].status == "wrong-release"
    assert results["carol"].message == "this notebook was released for alice, not for carol"


def test_a_generic_release_graded_per_student_stops_before_grading(tmp_path):
    """Every student got `kinbook release`'s generic notebook but the run grades per-student variants: each
    would be refused, for the instructor's mistake. The run stops before grading anything and says what to do;
    one student's generic notebook among variants is that student's (`wrong-release`)."""
    import sqlite3

    from kinbook.errors import GradingError

    src = _exercise("ex11")
    source = load_source(src)
    subs = tmp_path / "subs"
    for student in ("alice", "bob", "carol"):
        write_notebook(student_notebook(source, keep_solutions=True), subs / student / f"{source.exercise}.ipynb")
    with pytest.raises(GradingError, match=r"3 of 3 students handed in .*'s generic release .* grade them with "
                                           r"--generic\. Nothing was graded\."):
        grade(src, [subs], tmp_path / "graded", timeout=ENOUGH, memory=600, isolation=BWRAP)
    db = sqlite3.connect(tmp_path / "graded" / "gradebook.sqlite")
    assert db.execute("SELECT COUNT(*) FROM submissions").fetchone() == (0,)
    db.close()
    for student in ("alice", "bob"):  # now most are variants: carol's generic notebook is carol's to fix
        values = student_parameters(source, student)
        write_notebook(student_notebook(source, values, student, keep_solutions=True),
                       subs / student / f"{source.exercise}.ipynb")
    results = {r.student: r for r in grade(src, [subs], tmp_path / "graded", timeout=ENOUGH, memory=600, jobs=2,
                                           isolation=BWRAP)}
    assert results["alice"].score == results["bob"].score == 10
    assert results["carol"].status == "wrong-release"
    assert results["carol"].message == "this is the exercise's generic release, not the notebook released for carol"
