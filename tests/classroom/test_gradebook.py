"""The gradebook database (kinbook.classroom.gradebook): transactions, resuming, changed resubmissions, exports."""

import csv
import json
import os
import sqlite3

import pytest

from kinbook.classroom import grade
from kinbook.classroom.gradebook import COLUMNS, Gradebook
from kinbook.classroom.results import PartGrade, SubmissionResult

from .conftest import BWRAP, SOURCE, submission


def result(student, score=1.0, status="ok"):
    return SubmissionResult(student, "ex01", f"collected/{student}.ipynb", "ab" * 32, status, "",
                            [PartGrade("a", score, 2.0, status, "=cmd|' /c calc'!A0", reference="mech.symbolic() (cell 3)"),
                             PartGrade("b", 0.0, 1.0, status, "fine")], 1.5, "bubblewrap")


def test_each_result_is_one_transaction_and_survives_a_reopen(tmp_path):
    book = Gradebook(tmp_path)
    assert book.db.execute("PRAGMA journal_mode").fetchone() == ("wal",)
    book.record(result("alice"))
    book.record(result("bob", 0.5))
    book.record(result("alice", 2.0))  # graded again: replaced, not added
    # another connection (a killed run's successor) sees exactly what was committed
    other = sqlite3.connect(tmp_path / "gradebook.sqlite")
    assert other.execute("SELECT student, score FROM submissions ORDER BY student").fetchall() == [
        ("alice", 2.0), ("bob", 0.5)]
    assert other.execute("SELECT COUNT(*) FROM parts").fetchone() == (4,)
    book.close()
    again = Gradebook(tmp_path)
    assert [(r.student, r.score, r.parts[0].reference) for r in again.results()] == [
        ("alice", 2.0, "mech.symbolic() (cell 3)"), ("bob", 0.5, "mech.symbolic() (cell 3)")]


def test_exports_are_complete_and_safe_for_spreadsheets(tmp_path):
    from kinbook.classroom.feedback import write_pages

    book = Gradebook(tmp_path)
    for s in ("alice", "bob"):
        book.record(result(s))
    book.export()
    rows = list(csv.DictReader(open(tmp_path / "grades.csv", newline="")))
    assert list(rows[0]) == COLUMNS and len(rows) == 4
    assert rows[0]["message"].startswith("'=")  # never a formula
    write_pages(book, tmp_path / "feedback")
    assert sorted(str(p.relative_to(tmp_path / "feedback")) for p in (tmp_path / "feedback").rglob("*.html")) == [
        "alice/ex01.html", "alice/index.html", "bob/ex01.html", "bob/index.html"]


def test_text_that_is_not_utf8_is_stored_escaped_not_fatal(tmp_path):
    """A file name's byte that is not UTF-8 reaches a message as a lone surrogate, which SQLite refused: the
    whole run stopped at that student (those after it were never graded)."""
    odd = os.fsdecode(b"collected/bad\xff.ipynb")
    r = result("dave")
    r.submission, r.message, r.parts[1].message = odd, f"cannot read {odd}", odd
    book = Gradebook(tmp_path)
    book.record(r)
    book.export()
    (got,) = book.results()
    assert got.submission == "collected/bad\\udcff.ipynb" and got.parts[1].message == got.submission
    assert "bad\\udcff" in (tmp_path / "grades.csv").read_text(encoding="utf-8")


def test_results_of_an_older_kinbook_are_imported_once(tmp_path):
    store = tmp_path / ".kinbook" / "results" / "ex01"
    store.mkdir(parents=True)
    old = result("carol").to_dict()
    del old["isolation"]
    for p in old["parts"]:
        del p["reference"]
    (store / "carol.json").write_text(json.dumps(old))
    book = Gradebook(tmp_path)
    assert [(r.student, r.score, r.isolation) for r in book.results()] == [("carol", 1.0, "none")]


def test_a_changed_resubmission_is_a_new_attempt_and_the_old_one_is_kept(tmp_path):
    """Corrupt notebooks are graded without running anything: the bookkeeping alone is exercised here."""
    subs = tmp_path / "collected"
    subs.mkdir()
    (subs / "dave.ipynb").write_bytes(open(submission("corrupt"), "rb").read())
    out = tmp_path / "graded"
    first = grade(SOURCE, [subs], out, isolation=BWRAP)
    assert [r.status for r in first] == ["corrupt-notebook"]
    seen = []
    assert grade(SOURCE, [subs], out, isolation=BWRAP, progress=seen.append) == []  # the same file: skipped
    assert any("skipped 1 file(s) graded before" in str(s) for s in seen)
    (subs / "dave.ipynb").write_bytes(open(submission("not_a_notebook"), "rb").read())  # handed in again
    second = grade(SOURCE, [subs], out, isolation=BWRAP)
    assert [r.status for r in second] == ["corrupt-notebook"]
    book = Gradebook(out)
    history = book.attempts("tiny", "dave")
    assert len(history) == 2 and [h[-1] for h in history] == [0, 1]  # both kept, the latest counts
    assert history[0][4] != history[1][4]
    forced = grade(SOURCE, [subs], out, isolation=BWRAP, force=True)  # the same file again: regraded in place
    assert [r.status for r in forced] == ["corrupt-notebook"] and len(book.attempts("tiny", "dave")) == 2


def test_a_source_that_changes_during_grading_stops_the_run(tmp_path):
    """The grader runs the source it read at the start; a file that changes under it (an edit, or an attack from a
    submission) stops the run, keeping what was recorded."""
    import shutil

    import pytest

    from kinbook.errors import GradingError

    src = tmp_path / "tiny.ipynb"
    shutil.copy(SOURCE, src)
    subs = tmp_path / "collected"
    subs.mkdir()
    for name in ("anna", "ben", "cleo"):
        shutil.copy(submission("corrupt"), subs / f"{name}.ipynb")

    def edit(item):
        with open(src, "a") as f:
            f.write(" ")

    with pytest.raises(GradingError, match="changed during grading"):
        grade(src, [subs], tmp_path / "graded", isolation=BWRAP, progress=edit)
    db = sqlite3.connect(tmp_path / "graded" / "gradebook.sqlite")
    assert db.execute("SELECT student FROM submissions").fetchall() == [("anna",)]


def test_a_gradebook_of_an_earlier_kinbook_is_migrated(tmp_path):
    """The schema before attempts: one row per (exercise, student). Opened now, each result becomes its first attempt,
    the source its run graded with becomes the pin, and nothing is lost."""
    db = sqlite3.connect(tmp_path / "gradebook.sqlite")
    db.executescript("""
        CREATE TABLE runs (id INTEGER PRIMARY KEY, started TEXT NOT NULL, source TEXT NOT NULL,
            source_sha256 TEXT NOT NULL, exercise TEXT NOT NULL, isolation TEXT NOT NULL, kinbook TEXT NOT NULL,
            finished TEXT);
        CREATE TABLE submissions (exercise TEXT NOT NULL, student TEXT NOT NULL, submission TEXT NOT NULL,
            sha256 TEXT NOT NULL, status TEXT NOT NULL, message TEXT NOT NULL, score REAL NOT NULL,
            max_score REAL NOT NULL, seconds REAL NOT NULL, isolation TEXT NOT NULL, run INTEGER, graded TEXT NOT NULL,
            changed_sha256 TEXT, PRIMARY KEY (exercise, student));
        CREATE TABLE parts (exercise TEXT NOT NULL, student TEXT NOT NULL, position INTEGER NOT NULL, part TEXT NOT NULL,
            score REAL NOT NULL, max_score REAL NOT NULL, status TEXT NOT NULL, message TEXT NOT NULL,
            html TEXT NOT NULL, reference TEXT NOT NULL, PRIMARY KEY (exercise, student, position));
        INSERT INTO runs VALUES (1, '2026-01-01', 'ex01.ipynb', 'aaaa', 'ex01', 'bubblewrap', '0.1.0', '2026-01-01');
        INSERT INTO submissions VALUES ('ex01', 'ana', 'collected/ana.ipynb', 'cafe', 'ok', '', 2.5, 3, 1.0,
            'bubblewrap', 1, '2026-01-01', NULL);
        INSERT INTO parts VALUES ('ex01', 'ana', 0, 'a', 2.5, 3, 'ok', 'fine', '', '');
    """)
    db.commit()
    db.close()
    book = Gradebook(tmp_path)
    (r,) = book.results()
    assert (r.student, r.score, r.sha256, r.source_sha256, r.parts[0].message) == ("ana", 2.5, "cafe", "aaaa", "fine")
    assert [(a[2], a[4], a[-1]) for a in book.attempts()] == [("ana", "cafe", 1)]
    assert book.pin("ex01")[0] == "aaaa" and book.stale("ex01") == []
    book.close()
    assert len(Gradebook(tmp_path).attempts()) == 1  # migrated once


def test_a_gradebook_held_by_another_run_is_waited_for_saying_which_then_refused(tmp_path):
    from kinbook.errors import GradebookLockedError

    book = Gradebook(tmp_path)
    book.db.execute("INSERT INTO runs (started, source, source_sha256, exercise, isolation, kinbook) VALUES "
                    "('2026-03-01T10:00:00+0100', 'ex01.ipynb', 'x', 'ex01', 'none', '0')")
    book.close()
    other = sqlite3.connect(str(tmp_path / "gradebook.sqlite"), isolation_level=None)
    other.execute("BEGIN IMMEDIATE")  # another run, in the middle of recording a result
    said = []
    with pytest.raises(GradebookLockedError, match=r"in use by another kinbook run \(probably the grading of ex01 "
                                                   r"started 2026-03-01T10:00:00\+0100.*waited 2.5 s"):
        Gradebook(tmp_path, create=False, wait=2.5, notify=said.append)
    assert len(said) == 1 and "waiting up to 2.5 s" in said[0]
    other.execute("ROLLBACK")
    other.close()
    with Gradebook(tmp_path, create=False) as again:  # free again: nothing was lost
        assert again.db.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 1


def test_a_newer_or_foreign_database_is_refused_unchanged(tmp_path):
    from kinbook.errors import NewerGradebookError, NotAGradebookError

    Gradebook(tmp_path / "newer").close()
    db = sqlite3.connect(str(tmp_path / "newer" / "gradebook.sqlite"))
    db.execute("PRAGMA user_version = 99")
    db.close()
    with pytest.raises(NewerGradebookError, match="newer kinbook.*schema 99"):
        Gradebook(tmp_path / "newer", create=False)
    (tmp_path / "foreign").mkdir()
    db = sqlite3.connect(str(tmp_path / "foreign" / "gradebook.sqlite"))
    db.execute("CREATE TABLE moz_places (id INTEGER)")
    db.close()
    with pytest.raises(NotAGradebookError, match="not a kinbook gradebook.*moz_places"):
        Gradebook(tmp_path / "foreign")  # not even grade adds its tables to another application's database
    db = sqlite3.connect(str(tmp_path / "foreign" / "gradebook.sqlite"))
    assert [r[0] for r in db.execute("SELECT name FROM sqlite_master")] == ["moz_places"]
    db.close()
