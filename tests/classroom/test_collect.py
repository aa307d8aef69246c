"""Collection accounts for every file (issue 20, item 1) and the source is pinned (item 5).

Reading names needs no grading: most tests here call kinbook.classroom.files.collect directly. The pin and the
gradebook rows are exercised with corrupt notebooks, which are graded without running anything.
"""

import os
import shutil
import sqlite3

import pytest

from kinbook.classroom import grade
from kinbook.classroom.files import collect
from kinbook.classroom.intake import SourceChanged
from kinbook.classroom.naming import NamingError, compile_pattern, read_name
from kinbook.classroom.roster import read_roster

from .conftest import SOURCE, submission

EX = "ex11-rotations-euler-parameters"


def by_path(entries, root):
    return {os.path.relpath(e.path, root): e for e in entries}


def test_browser_duplicates_canvas_names_and_resubmission_suffixes_are_attempts_not_students(tmp_path):
    c = tmp_path / "collected"
    (c / "ben.okafor").mkdir(parents=True)
    for name in (f"ben.okafor/{EX}.ipynb", f"ben.okafor/{EX} (1).ipynb", f"{EX}-dana.ipynb", f"{EX}-dana-1.ipynb",
                 f"{EX}-eve-2026-03-01T2359.ipynb", f"{EX}-eve-2026-03-02T0010.ipynb"):
        (c / name).write_text("{}")
    os.utime(c / f"ben.okafor/{EX}.ipynb", (2_000_000_000, 2_000_000_000))  # an older download, touched later
    found = by_path(collect([c], EX, max_bytes=1000), c)
    assert found[f"ben.okafor/{EX} (1).ipynb"].status is None                # the browser's second download counts
    assert found[f"ben.okafor/{EX}.ipynb"].status == "superseded"
    assert found[f"{EX}-dana-1.ipynb"].student == "dana" and found[f"{EX}-dana-1.ipynb"].status is None
    assert found[f"{EX}-dana.ipynb"].status == "superseded" and "policy: latest" in found[f"{EX}-dana.ipynb"].message
    assert found[f"{EX}-eve-2026-03-02T0010.ipynb"].status is None            # a date in the name orders eve's own
    assert found[f"{EX}-eve-2026-03-02T0010.ipynb"].submitted == ""           # files, but is never their time
    assert {e.student for e in found.values()} == {"ben.okafor", "dana", "eve"}
    best = by_path(collect([c], EX, max_bytes=1000, policy="best"), c)
    assert all(e.status is None for e in best.values())                      # best: every attempt is graded


def test_every_entry_is_a_row_with_its_reason(tmp_path):
    c = tmp_path / "collected"
    for d in ("ana", ".carl", ".ipynb_checkpoints", "__MACOSX", "bob"):
        (c / d).mkdir(parents=True)
    (c / "ana" / f"{EX}.ipynb").write_text("{}")
    (c / ".carl" / f"{EX}.ipynb").write_text("{}")
    (c / ".ipynb_checkpoints" / f"{EX}-checkpoint.ipynb").write_text("{}")
    (c / "__MACOSX" / f"._{EX}.ipynb").write_text("{}")
    (c / "ana" / ".DS_Store").write_text("x")
    (c / "ana" / "notes.pdf").write_text("x")
    (c / "bob" / "ex01-revolute-joint-phi.ipynb").write_text("{}")           # another exercise's notebook
    shutil.copy(SOURCE, c / "tiny-solution.ipynb")
    os.link(c / "ana" / f"{EX}.ipynb", c / f"{EX}-zed.ipynb")                # tar -x of a student's archive
    os.symlink("/etc/passwd", c / f"{EX}-mal.ipynb")
    found = by_path(collect([c], EX, max_bytes=1000), c)
    assert set(found) == {f"ana/{EX}.ipynb", ".carl", ".ipynb_checkpoints", "__MACOSX", "ana/.DS_Store",
                          "ana/notes.pdf", "bob/ex01-revolute-joint-phi.ipynb", "tiny-solution.ipynb", f"{EX}-zed.ipynb",
                          f"{EX}-mal.ipynb"}
    status = {k: (e.status, e.message) for k, e in found.items()}
    assert status[".carl"][0] == "ignored" and "hidden directory" in status[".carl"][1]
    assert status[".ipynb_checkpoints"][0] == "ignored" and "checkpoints" in status[".ipynb_checkpoints"][1]
    assert status["__MACOSX"][0] == "ignored" and "macOS" in status["__MACOSX"][1]
    assert status["ana/.DS_Store"] == ("ignored", "a hidden name (editors and archives leave these): not read")
    assert status["ana/notes.pdf"][0] == "ignored" and "not a notebook" in status["ana/notes.pdf"][1]
    assert status["bob/ex01-revolute-joint-phi.ipynb"][0] == "ignored"
    assert "not named after the exercise" in status["bob/ex01-revolute-joint-phi.ipynb"][1]
    assert status[f"{EX}-mal.ipynb"][0] == "refused" and "symbolic link" in status[f"{EX}-mal.ipynb"][1]
    assert status[f"{EX}-zed.ipynb"][0] == "refused" and "hard link" in status[f"{EX}-zed.ipynb"][1]
    assert status[f"ana/{EX}.ipynb"][0] == "refused"                         # a hard link too: both names refused


PATHS = {
    "canvas": [("garciaana_12345_67890_ex11-rotations-euler-parameters.ipynb", "12345", 0, False),
               ("okaforben_late_23456_78901_ex11-rotations-euler-parameters-1.ipynb", "23456", 1, True)],
    "moodle": [("Ana García_123456_assignsubmission_file_/ex11-rotations-euler-parameters.ipynb", "123456", 0, False),
               ("Ben Okafor_234567_assignsubmission_file_ex11-rotations-euler-parameters (1).ipynb", "234567", 1,
                False)],
    "blackboard": [("HW11_ana.garcia_attempt_2026-03-01-23-59-00_ex11.ipynb", "ana.garcia", 0, False)],
}


@pytest.mark.parametrize("lms", sorted(PATHS))
def test_ready_patterns_read_the_lms_bulk_download_names(lms):
    rx = compile_pattern(lms)
    for path, raw, attempt, late in PATHS[lms]:
        name = read_name(tuple(path.split("/")), EX, "collected", rx)
        assert (name.raw, name.attempt, name.late) == (raw, attempt, late), path
    assert read_name(("README.txt",), EX, "collected", rx).raw is None


def test_a_bad_pattern_is_refused_before_anything_is_read():
    with pytest.raises(NamingError, match="no group"):
        compile_pattern(r"(\d+)_")
    with pytest.raises(NamingError, match="not a regular expression"):
        compile_pattern(r"(?P<student>")


CANVAS_ROSTER = """Student,ID,SIS User ID,SIS Login ID,Section,Exercise 11 (4242)
    Points Possible,,,,,10
"García, Ana",12345,S001,ana.garcia,Section A,
"Okafor, Ben",23456,S002,ben.okafor,Section B,
"Student, Test",99999,,,Section A,
"""


def test_a_canvas_download_maps_to_the_roster_and_lists_strangers(tmp_path):
    roster_file = tmp_path / "grades.csv"
    roster_file.write_text(CANVAS_ROSTER, encoding="utf-8-sig")  # as Canvas writes it, with a byte-order mark
    roster = read_roster(roster_file)
    assert roster.source == "canvas" and [s.student for s in roster] == ["ana.garcia", "ben.okafor"]
    assert roster.by_id["ana.garcia"].lms_id == "12345" and roster.by_id["ben.okafor"].section == "Section B"
    c = tmp_path / "collected"
    c.mkdir()
    for name in ("garciaana_12345_67890_ex11-rotations-euler-parameters.ipynb",
                 "okaforben_late_23456_78901_ex11-rotations-euler-parameters.ipynb",
                 "okaforben_late_23456_78902_ex11-rotations-euler-parameters-1.ipynb",
                 "strangerx_55555_11111_ex11-rotations-euler-parameters.ipynb"):
        (c / name).write_text("{}")
    found = by_path(collect([c], EX, max_bytes=1000, pattern="canvas", roster=roster), c)
    ben = [e for e in found.values() if e.student == "ben.okafor"]
    assert sorted((e.status or "", e.attempt, e.late) for e in ben) == [("", 1, True), ("superseded", 0, True)]
    stranger = found["strangerx_55555_11111_ex11-rotations-euler-parameters.ipynb"]
    assert (stranger.student, stranger.on_roster, stranger.status) == ("55555", False, None)
    assert found["garciaana_12345_67890_ex11-rotations-euler-parameters.ipynb"].student == "ana.garcia"


def test_moodle_worksheet_and_kinbook_rosters(tmp_path):
    w = tmp_path / "worksheet.csv"
    w.write_text("Identifier,Full name,Email address,Status,Grade,Maximum Grade,Grade can be changed,"
                 "Last modified (submission),Last modified (grade),Feedback comments\n"
                 "Participant 123456,Ana García,ana.garcia@uni.example,Submitted for grading,,10.00,Yes,-,-,\n")
    (s,) = read_roster(w)
    assert (s.student, s.lms_id, s.name) == ("ana.garcia@uni.example", "123456", "Ana García")
    k = tmp_path / "roster.csv"
    k.write_text("student,name,lms_id,sis_id,section\nana,Ana García,12345,S1,A\nben-1,Ben,23456,S2,B\n")
    roster = read_roster(k)
    assert roster.source == "kinbook" and roster.find("23456", "lms").student == "ben-1"
    c = tmp_path / "c"
    c.mkdir()
    (c / f"{EX}-ben-1.ipynb").write_text("{}")  # on the roster as 'ben-1': not an attempt of 'ben'
    (e,) = collect([c], EX, max_bytes=1000, roster=roster)
    assert (e.student, e.attempt, e.on_roster) == ("ben-1", 0, True)
    bad = tmp_path / "bad.csv"
    bad.write_text("student,name\nana,A\nANA,B\n")
    with pytest.raises(Exception, match="lines 2 and 3 have the same id"):
        read_roster(bad)


def test_a_changed_source_stops_the_run_until_regrade(tmp_path):
    src = tmp_path / "tiny.ipynb"
    shutil.copy(SOURCE, src)
    subs = tmp_path / "collected"
    subs.mkdir()
    for name in ("anna", "ben"):
        shutil.copy(submission("corrupt"), subs / f"{name}.ipynb")
    out = tmp_path / "graded"
    grade(src, [subs], out, isolation=False)
    src.write_text(src.read_text().replace("points=4", "points=5"))           # the instructor edits a part's points
    with pytest.raises(SourceChanged, match="--regrade") as info:
        grade(src, [subs], out, isolation=False)
    assert "2 result(s)" in str(info.value) and "Nothing was graded" in str(info.value)
    os.remove(subs / "ben.ipynb")
    seen = []
    again = grade(src, [subs], out, isolation=False, regrade=True, progress=seen.append)
    assert [(r.student, r.max_score) for r in again] == [("anna", 7.0)]
    assert any("not regraded" in str(s) and "ben" in str(s) for s in seen)
    db = sqlite3.connect(out / "gradebook.sqlite")
    pinned = db.execute("SELECT sha256 FROM sources WHERE exercise = 'tiny'").fetchone()[0]
    assert {s: h == pinned for s, h in db.execute("SELECT student, source_sha256 FROM submissions")} == {
        "anna": True, "ben": False}
    assert "earlier version of the source" in (out / "totals.csv").read_text()
    grade(src, [subs], out, isolation=False)                                  # the new pin holds: no stop
