"""The gradebook: an SQLite database (``graded/gradebook.sqlite``), and the files exported from it.

Every graded submission is recorded in one transaction, in WAL mode with full synchronization: a grading run
killed at any moment — SIGKILL, the OOM killer, a power cut — keeps every result recorded before, and the next run
finds them and grades only what is left. Recording one result costs the same whether the database holds 10
results or 10,000 (indexed upserts; nothing is re-read).

Tables
------
``runs``
    When, which source (path and sha256), kinbook's version, isolation.
``attempts``, ``attempt_parts``
    Every attempt ever graded or seen: file, sha256, when it was handed in (and from what: its name or the file's
    time), the source's sha256 that graded it, status, score, and one row per part (score, message, the student's
    answer, the cell it was assigned in). Attempts ``superseded`` by a later one are kept, ungraded, as history.
``submissions``, ``parts``
    For each (exercise, student), the attempt that counts under the exercise's policy (``latest``: the last one
    graded; ``best``: the highest score after the late penalty), and its parts: what ``grades.csv`` and
    ``totals.csv`` show.
``mistakes``
    (attempt, part, code, row): each catalogue mistake a checker named, so that the report's item analysis is a
    query.
``signals``
    Copying signals per attempt (a notebook released for another student …), for the instructor.
``files``
    Every entry of ``collected/`` seen by a run, with what became of it (graded, skipped, superseded, ignored,
    refused) and why.
``sources``
    The source notebook each exercise is pinned to (its sha256): a run with another source stops unless it
    regrades everything (``--regrade``).
``source_texts``
    The bytes of every source an exercise was graded with: the editions a regrade after an edit checks each
    submission against (:mod:`kinbook.classroom.editions`).
``reattached``
    Ids a newer roster mapped to one of its students (a student enrolled after the first roster): their results
    moved to the student, and the old id is dropped from the feedback folders.
``lms_points``
    What the LMS says each assignment column is worth (Canvas's ``Points Possible`` row of the roster).
``roster``, ``rules``, ``extensions``, ``overrides``
    The course: students and their LMS ids, each exercise's due date, late penalty and policy, per-student
    extensions, and the instructor's per-part overrides (kept across regrades and ``--force``).

``grades.csv`` (one row per part), ``totals.csv`` (one row per submission; its ``score`` is the one that counts,
with the instructor's overrides and the late penalty, beside the grader's) and ``collection.csv`` (one row per file
of the last run) are exports, each written atomically (:func:`kinbook.classroom.files.atomic_write`).
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import sqlite3
import time
from pathlib import Path

from .. import __version__
from ..errors import NewerGradebookError, NotAGradebookError
from .enrolment import reattach
from .files import atomic_write
from .gradebook_failures import gradebook_error, must_exist, wait_for_lock
from .notebook import source_from_bytes
from .results import UNGRADED, PartGrade, SubmissionResult
from .roster import FIELDS, Roster, Student
from .sanitize import csv_field
from .scores import Final, Rule, final

__all__ = ["Gradebook", "COLUMNS", "TOTALS", "DATABASE", "FILES", "SCHEMA_VERSION", "LOCK_WAIT", "gradebook_error"]

DATABASE = "gradebook.sqlite"
#: The gradebook's schema (SQLite's ``user_version``): a gradebook of a higher one was written by a newer kinbook.
SCHEMA_VERSION = 2
#: Seconds a command waits for another kinbook run that holds the gradebook.
LOCK_WAIT = 30.0
#: grades.csv: ``score`` is the part's score that counts (the instructor's override, when there is one);
#: ``grader_score`` the grader's, ``override`` the instructor's reason.
COLUMNS = ["student", "exercise", "part", "score", "max_score", "status", "message", "reference", "grader_score",
           "override"]
#: totals.csv: ``score`` is the score that counts — overrides and the late penalty applied, as the report, the
#: feedback and the LMS files show it (2 decimals); ``grader_score`` the grader's sum of the parts.
TOTALS = ["student", "exercise", "score", "max_score", "status", "isolation", "sha256", "note", "grader_score",
          "late_days", "penalty", "overridden"]
FILES = ["exercise", "path", "student", "outcome", "reason", "sha256", "submitted"]
_PART_COLS = "part, score, max_score, status, message, html, reference, answer, cell"
_SCHEMA = """
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY, started TEXT NOT NULL, source TEXT NOT NULL, source_sha256 TEXT NOT NULL,
    exercise TEXT NOT NULL, isolation TEXT NOT NULL, kinbook TEXT NOT NULL, finished TEXT);
CREATE TABLE IF NOT EXISTS submissions (
    exercise TEXT NOT NULL, student TEXT NOT NULL, submission TEXT NOT NULL, sha256 TEXT NOT NULL,
    status TEXT NOT NULL, message TEXT NOT NULL, score REAL NOT NULL, max_score REAL NOT NULL,
    seconds REAL NOT NULL, isolation TEXT NOT NULL, run INTEGER, graded TEXT NOT NULL, changed_sha256 TEXT,
    PRIMARY KEY (exercise, student));
CREATE TABLE IF NOT EXISTS parts (
    exercise TEXT NOT NULL, student TEXT NOT NULL, position INTEGER NOT NULL, part TEXT NOT NULL,
    score REAL NOT NULL, max_score REAL NOT NULL, status TEXT NOT NULL, message TEXT NOT NULL,
    html TEXT NOT NULL, reference TEXT NOT NULL,
    PRIMARY KEY (exercise, student, position));
CREATE TABLE IF NOT EXISTS attempts (
    id INTEGER PRIMARY KEY, exercise TEXT NOT NULL, student TEXT NOT NULL, submission TEXT NOT NULL,
    sha256 TEXT NOT NULL, submitted TEXT NOT NULL DEFAULT '', submitted_from TEXT NOT NULL DEFAULT '',
    late INTEGER NOT NULL DEFAULT 0, source_sha256 TEXT NOT NULL DEFAULT '', status TEXT NOT NULL,
    message TEXT NOT NULL, score REAL NOT NULL, max_score REAL NOT NULL, seconds REAL NOT NULL,
    isolation TEXT NOT NULL, run INTEGER, graded TEXT NOT NULL);
CREATE INDEX IF NOT EXISTS attempts_by_student ON attempts (exercise, student, sha256);
CREATE TABLE IF NOT EXISTS attempt_parts (
    attempt INTEGER NOT NULL, position INTEGER NOT NULL, part TEXT NOT NULL, score REAL NOT NULL,
    max_score REAL NOT NULL, status TEXT NOT NULL, message TEXT NOT NULL, html TEXT NOT NULL,
    reference TEXT NOT NULL, answer TEXT NOT NULL DEFAULT '', cell TEXT NOT NULL DEFAULT '',
    PRIMARY KEY (attempt, position));
CREATE TABLE IF NOT EXISTS mistakes (
    attempt INTEGER NOT NULL, exercise TEXT NOT NULL, student TEXT NOT NULL, part TEXT NOT NULL,
    code TEXT NOT NULL, row TEXT NOT NULL);
CREATE INDEX IF NOT EXISTS mistakes_by_attempt ON mistakes (attempt);
CREATE TABLE IF NOT EXISTS signals (
    attempt INTEGER NOT NULL, exercise TEXT NOT NULL, student TEXT NOT NULL, kind TEXT NOT NULL,
    detail TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS files (
    run INTEGER NOT NULL, exercise TEXT NOT NULL, path TEXT NOT NULL, student TEXT NOT NULL, outcome TEXT NOT NULL,
    reason TEXT NOT NULL, sha256 TEXT NOT NULL, submitted TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS sources (
    exercise TEXT PRIMARY KEY, sha256 TEXT NOT NULL, path TEXT NOT NULL, pinned TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS source_texts (
    sha256 TEXT PRIMARY KEY, exercise TEXT NOT NULL, path TEXT NOT NULL, data BLOB NOT NULL, first TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS lms_points (header TEXT PRIMARY KEY, points REAL NOT NULL);
CREATE TABLE IF NOT EXISTS reattached (old TEXT PRIMARY KEY, student TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS roster (
    position INTEGER NOT NULL, student TEXT PRIMARY KEY, name TEXT NOT NULL, first TEXT NOT NULL,
    last TEXT NOT NULL, lms_id TEXT NOT NULL, sis_id TEXT NOT NULL, login TEXT NOT NULL, email TEXT NOT NULL,
    section TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS rules (
    exercise TEXT PRIMARY KEY, due TEXT NOT NULL DEFAULT '', penalty REAL NOT NULL DEFAULT 0,
    cap REAL NOT NULL DEFAULT 100, policy TEXT NOT NULL DEFAULT 'latest');
CREATE TABLE IF NOT EXISTS extensions (
    exercise TEXT NOT NULL, student TEXT NOT NULL, due TEXT NOT NULL, why TEXT NOT NULL,
    PRIMARY KEY (exercise, student));
CREATE TABLE IF NOT EXISTS overrides (
    exercise TEXT NOT NULL, student TEXT NOT NULL, part TEXT NOT NULL, score REAL NOT NULL, why TEXT NOT NULL,
    set_at TEXT NOT NULL, PRIMARY KEY (exercise, student, part));
"""
#: Columns added to the tables of a gradebook made by an earlier kinbook (migrated when opened).
_ADDED = {
    "submissions": [("attempt", "INTEGER"), ("source_sha256", "TEXT NOT NULL DEFAULT ''"),
                    ("submitted", "TEXT NOT NULL DEFAULT ''"), ("submitted_from", "TEXT NOT NULL DEFAULT ''"),
                    ("late", "INTEGER NOT NULL DEFAULT 0")],
    "parts": [("answer", "TEXT NOT NULL DEFAULT ''"), ("cell", "TEXT NOT NULL DEFAULT ''")],
}


def _cell(text):
    """A CSV field a spreadsheet will not read as a formula or split into rows (messages can quote students'
    answers): :func:`kinbook.classroom.sanitize.csv_field`."""
    return csv_field(text)


def _utf8(value):
    """Text SQLite and the UTF-8 exports can store: a lone surrogate (a file name's byte that is not UTF-8, carried
    into a message) is written as an escape instead of failing the whole run."""
    return value.encode("utf-8", "backslashreplace").decode("utf-8") if isinstance(value, str) else value


def _now():
    return time.strftime("%Y-%m-%dT%H:%M:%S%z")


def _score(row):
    """A score for the exports: blank for a part or submission the grader could not grade (never a 0 the student
    did not earn)."""
    return "" if row.status in UNGRADED else f"{row.score:g}"


def _points(x):
    """A score as the report, the feedback and the LMS files show it: at most 2 decimals."""
    return f"{round(float(x), 2):g}"


def csv_text(header, rows):
    """The text of a CSV export: every field quoted and every text field sanitized and guarded against spreadsheet
    formulas (:func:`kinbook.classroom.sanitize.csv_field`)."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n", quoting=csv.QUOTE_ALL)
    w.writerow(header)
    for row in rows:
        w.writerow([_cell(v) if isinstance(v, str) else v for v in row])
    return buf.getvalue()


def write_csv(path, header, rows):
    """A CSV export (:func:`csv_text`), written atomically."""
    return atomic_write(path, csv_text(header, rows))


class Gradebook:
    """The grading output directory and its database.

    Parameters
    ----------
    outdir : path
        Holds ``gradebook.sqlite`` and the exports.
    create : bool
        Create the directory and the gradebook when they are missing (``kinbook grade``'s job). False (every other
        command): a missing directory or gradebook is a :class:`~kinbook.errors.NotAGradebookError` — a mistyped
        ``-g`` never makes an empty gradebook.
    wait : float, optional
        Default :data:`LOCK_WAIT`. Seconds to wait for another kinbook run that holds the gradebook (a message is given when waiting starts,
        through ``notify``) before :class:`~kinbook.errors.GradebookLockedError`.
    notify : callable, optional
        Called with a line when the gradebook is busy and kinbook waits (default: printed on stderr).

    Raises
    ------
    GradebookError
        Its subclasses name the file and what to do: :class:`~kinbook.errors.NotAGradebookError` (missing, another
        file, damaged), :class:`~kinbook.errors.GradebookReadOnlyError`, :class:`~kinbook.errors.GradebookLockedError`,
        :class:`~kinbook.errors.NewerGradebookError`, :class:`~kinbook.errors.GradebookFullError`. The same errors
        (never a raw ``sqlite3`` one) come out of a ``with Gradebook(...)`` block.
    """

    def __init__(self, outdir, create=True, *, wait=None, notify=None):
        self.outdir = Path(outdir)
        self.path = self.outdir / DATABASE
        self.wait = float(LOCK_WAIT if wait is None else wait)
        self.db = None
        if not create:
            must_exist(self.outdir, self.path)
        try:
            self.outdir.mkdir(parents=True, exist_ok=True)
        except FileExistsError:
            raise NotAGradebookError(f"the grading directory {str(self.outdir)!r} is a file, not a directory: give "
                                     "the directory that holds gradebook.sqlite (-g)") from None
        except OSError as exc:
            raise self._failure(exc) from None
        try:
            self._open(notify)
        except sqlite3.Error as exc:
            if self.db is not None:
                self.db.close()
            raise self._failure(exc) from None

    def _open(self, notify):
        """Connect, wait (bounded) for another run's lock, check the schema's version, create or migrate it."""
        existed = self.path.exists() and self.path.stat().st_size > 0
        self.db = sqlite3.connect(str(self.path), timeout=min(self.wait, 1.0), isolation_level=None)
        wait_for_lock(self, notify)
        self.db.execute(f"PRAGMA busy_timeout = {int(self.wait * 1000)}")
        version = self.db.execute("PRAGMA user_version").fetchone()[0]
        tables = {r[0] for r in self.db.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
        if version > SCHEMA_VERSION:
            raise NewerGradebookError(f"the gradebook {str(self.path)!r} was written by a newer kinbook (schema "
                                      f"{version}, this kinbook knows {SCHEMA_VERSION}): upgrade kinbook (pip install "
                                      "-U kinbook) to use it; it was not changed")
        if existed and tables and not {"submissions", "runs"} <= tables:
            raise NotAGradebookError(f"{str(self.path)!r} is an SQLite database but not a kinbook gradebook (its "
                                     f"tables: {', '.join(sorted(tables)[:8])}); it was not changed — move it away or "
                                     "give the grading directory kinbook grade wrote (-g)")
        self.db.execute("PRAGMA journal_mode=WAL")
        self.db.execute("PRAGMA synchronous=FULL")
        self.db.executescript(_SCHEMA)
        self._migrate()
        if version < SCHEMA_VERSION:
            self.db.execute(f"PRAGMA user_version = {SCHEMA_VERSION}")
        self._import_json_results()

    def inputs(self):
        """``(label, path)`` of the gradebook's files, which no export, report or page may be written over
        (:func:`kinbook.core.atomic.protect`)."""
        return [("the gradebook", self.path)] + [("the gradebook's journal", Path(f"{self.path}{x}"))
                                                 for x in ("-wal", "-shm")]

    def _failure(self, exc):
        """The :class:`~kinbook.errors.GradebookError` for an ``sqlite3`` or ``OSError`` met on this gradebook."""
        return gradebook_error(exc, self.path)

    @contextlib.contextmanager
    def failures(self):
        """Within the block, an error closes the gradebook, and SQLite's errors are the instructor's words
        (:func:`~kinbook.classroom.gradebook_failures.gradebook_error`); every result recorded before is kept."""
        try:
            yield self
        except BaseException as exc:
            self.close()
            if isinstance(exc, sqlite3.Error):
                raise self._failure(exc) from exc
            raise

    def close(self):
        if self.db is not None:
            self.db.close()

    def __enter__(self):
        return self

    def __exit__(self, kind, exc, tb):
        self.close()
        if isinstance(exc, sqlite3.Error):
            raise self._failure(exc) from exc

    # ----------------------------------------------------------------------------------------- recording
    def begin_run(self, source, isolation):
        """Record the start of a run; returns its id."""
        cur = self.db.execute("INSERT INTO runs (started, source, source_sha256, exercise, isolation, kinbook) "
                              "VALUES (?, ?, ?, ?, ?, ?)", (_now(), str(source.path), source.sha256, source.exercise,
                                                            isolation, __version__))
        return cur.lastrowid

    def end_run(self, run):
        self.db.execute("UPDATE runs SET finished = ? WHERE id = ?", (_now(), run))

    def graded(self, exercise, student):
        """(sha256, status) of the result that counts, or None."""
        return self.db.execute("SELECT sha256, status FROM submissions WHERE exercise = ? AND student = ?",
                               (exercise, student)).fetchone()

    def has(self, student, exercise):
        return self.graded(exercise, student) is not None

    def attempt_of(self, exercise, student, sha256):
        """(id, source_sha256, status) of the attempt with this file's sha256, or None."""
        return self.db.execute("SELECT id, source_sha256, status FROM attempts WHERE exercise = ? AND student = ? AND "
                               "sha256 = ? ORDER BY id DESC LIMIT 1", (exercise, student, sha256)).fetchone()

    def runs_graded(self, exercise, student, sha256):
        """How many runs set out to grade this very file (its sha256) of the student: a file the grader keeps
        failing on (``grader-error``) is tried again a bounded number of times across runs."""
        return self.db.execute("SELECT COUNT(DISTINCT run) FROM files WHERE exercise = ? AND student = ? AND "
                               "sha256 = ? AND outcome = 'graded'", (exercise, student, sha256)).fetchone()[0]

    def note_changed(self, exercise, student, sha256):
        """A file different from the graded one was seen for this student (not graded again without --force)."""
        self.db.execute("UPDATE submissions SET changed_sha256 = ? WHERE exercise = ? AND student = ?",
                        (sha256, exercise, student))

    def record(self, result, run=None, replace=None):
        """Store one attempt's result (in place of attempt ``replace``, a regrade, or as a new attempt), then choose
        the attempt that counts for the student under the exercise's policy; one transaction. Returns the attempt's
        id."""
        r = result
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            values = [_utf8(v) for v in (r.exercise, r.student, r.submission, r.sha256, r.submitted, r.submitted_from,
                                         int(bool(r.late)), r.source_sha256, r.status, r.message, r.score,
                                         r.max_score, r.seconds, r.isolation, run, _now())]
            cols = ("exercise, student, submission, sha256, submitted, submitted_from, late, source_sha256, status, "
                    "message, score, max_score, seconds, isolation, run, graded")
            if replace is not None:
                self.db.execute(f"UPDATE attempts SET ({cols}) = ({', '.join('?' * 16)}) WHERE id = ?",
                                values + [replace])
                attempt = replace
                for table in ("attempt_parts", "mistakes", "signals"):
                    self.db.execute(f"DELETE FROM {table} WHERE attempt = ?", (attempt,))
            else:
                attempt = self.db.execute(f"INSERT INTO attempts ({cols}) VALUES ({', '.join('?' * 16)})",
                                          values).lastrowid
            self.db.executemany(
                f"INSERT INTO attempt_parts (attempt, position, {_PART_COLS}) VALUES (?,?,?,?,?,?,?,?,?,?,?)",
                [[attempt, i] + [_utf8(v) for v in (p.part, p.score, p.max_score, p.status, p.message, p.html,
                                                    p.reference, p.answer, p.cell)] for i, p in enumerate(r.parts)])
            self.db.executemany(
                "INSERT INTO mistakes (attempt, exercise, student, part, code, row) VALUES (?,?,?,?,?,?)",
                [[attempt] + [_utf8(v) for v in (r.exercise, r.student, p.part, str(code), str(row))]
                 for p in r.parts for code, row in p.mistakes])
            self.db.executemany(
                "INSERT INTO signals (attempt, exercise, student, kind, detail) VALUES (?,?,?,?,?)",
                [[attempt] + [_utf8(str(v)) for v in (r.exercise, r.student, kind, detail)]
                 for kind, detail in r.signals])
            if r.status != "superseded":
                self.select(r.exercise, r.student)
        return attempt

    def record_file(self, run, exercise, entry, outcome, reason="", sha256=""):
        """One entry of ``collected/`` and what became of it."""
        self.db.execute("INSERT INTO files (run, exercise, path, student, outcome, reason, sha256, submitted) "
                        "VALUES (?,?,?,?,?,?,?,?)", [_utf8(v) for v in (run, exercise, entry.path, entry.student or "",
                                                                        outcome, reason or "", sha256,
                                                                        entry.submitted)])

    def select(self, exercise, student):
        """Make the attempt that counts under the policy the student's result (``submissions`` and ``parts``)."""
        rows = self.db.execute("SELECT id, run, status FROM attempts WHERE exercise = ? AND student = ? AND "
                               "status != 'superseded' ORDER BY id", (exercise, student)).fetchall()
        if not rows:
            return
        # an attempt the grader could not grade (no score) never hides one it did: the graded one counts meanwhile
        rows = [r for r in rows if r[2] not in UNGRADED] or rows
        ids = [r[0] for r in rows]
        rule = self.rule(exercise)
        chosen = ids[-1]
        if rule.policy == "latest":  # the latest run's files: several notebooks of one submission, the best counts
            last = rows[-1][1]
            ids = [i for i, run, _ in rows if run == last] if last is not None else ids[-1:]
        if len(ids) > 1:
            ext = self.extension(exercise, student)
            finals = {i: final(student, exercise, self._attempt_result(i), rule, ext).score for i in ids}
            chosen = max(ids, key=lambda i: (finals[i], i))
        a = self._attempt_result(chosen)
        self.db.execute(
            "INSERT OR REPLACE INTO submissions (exercise, student, submission, sha256, status, message, score, "
            "max_score, seconds, isolation, run, graded, changed_sha256, attempt, source_sha256, submitted, "
            "submitted_from, late) SELECT exercise, student, submission, sha256, status, message, score, max_score, "
            "seconds, isolation, run, graded, NULL, id, source_sha256, submitted, submitted_from, late FROM attempts "
            "WHERE id = ?", (chosen,))
        self.db.execute("DELETE FROM parts WHERE exercise = ? AND student = ?", (exercise, student))
        self.db.execute(f"INSERT INTO parts (exercise, student, position, {_PART_COLS}) SELECT ?, ?, position, "
                        f"{_PART_COLS} FROM attempt_parts WHERE attempt = ?", (exercise, student, chosen))
        return a

    def reselect(self, exercise):
        """Choose again every student's counting attempt (after the policy or the late rule changed)."""
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            for (student,) in self.db.execute("SELECT DISTINCT student FROM attempts WHERE exercise = ?",
                                              (exercise,)).fetchall():
                self.select(exercise, student)

    # ---------------------------------------------------------------------------------------- the source pin
    def pin(self, exercise):
        """(sha256, path, pinned) of the source the exercise's results were graded with, or None."""
        row = self.db.execute("SELECT sha256, path, pinned FROM sources WHERE exercise = ?", (exercise,)).fetchone()
        if row is None:  # a gradebook of an earlier kinbook: the source of its last run
            row = self.db.execute("SELECT source_sha256, source, started FROM runs WHERE exercise = ? AND id IN "
                                  "(SELECT run FROM submissions WHERE exercise = ?) ORDER BY id DESC LIMIT 1",
                                  (exercise, exercise)).fetchone()
        return row

    def set_pin(self, source):
        self.db.execute("INSERT OR REPLACE INTO sources (exercise, sha256, path, pinned) VALUES (?,?,?,?)",
                        (source.exercise, source.sha256, _utf8(str(source.path)), _now()))
        self.keep_source(source)

    def unpin(self, exercise, pin):
        """Put back the pin ``pin`` (:meth:`pin`'s row, or None) of a run that graded nothing."""
        if pin is None:
            self.db.execute("DELETE FROM sources WHERE exercise = ?", (exercise,))
        else:
            self.db.execute("INSERT OR REPLACE INTO sources (exercise, sha256, path, pinned) VALUES (?,?,?,?)",
                            (exercise, *pin))

    def keep_source(self, source):
        """Keep a source's bytes (once per sha256): a later edit of it is graded against this edition."""
        if source.data:
            self.db.execute("INSERT OR IGNORE INTO source_texts (sha256, exercise, path, data, first) VALUES "
                            "(?,?,?,?,?)", (source.sha256, source.exercise, _utf8(str(source.path)), source.data,
                                            _now()))

    def sources(self, exercise):
        """Every source of ``exercise`` kept (:meth:`keep_source`), most recent first: [Source]."""
        rows = self.db.execute("SELECT path, data FROM source_texts WHERE exercise = ? ORDER BY rowid DESC",
                               (exercise,)).fetchall()
        return [source_from_bytes(bytes(data), path) for path, data in rows]

    def stale(self, exercise):
        """Students whose counting result was graded with another source than the pinned one."""
        pin = self.pin(exercise)
        if pin is None:
            return []
        return [s for (s,) in self.db.execute("SELECT student FROM submissions WHERE exercise = ? AND source_sha256 "
                                              "!= ? ORDER BY student", (exercise, pin[0]))]

    # ------------------------------------------------------------------------------------------- the course
    def set_roster(self, roster):
        """Replace the stored roster (:class:`kinbook.classroom.roster.Roster`); results graded under an id it maps to
        one of its students move to that student (:func:`kinbook.classroom.enrolment.reattach`): returns [(old id,
        student)]."""
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            self.db.execute("DELETE FROM roster")
            self.db.executemany(f"INSERT INTO roster (position, {', '.join(FIELDS)}) VALUES "
                                f"(?, {', '.join('?' * len(FIELDS))})",
                                [[i] + [_utf8(getattr(s, f)) for f in FIELDS] for i, s in enumerate(roster)])
            self.db.execute("DELETE FROM lms_points")
            self.db.executemany("INSERT INTO lms_points (header, points) VALUES (?, ?)",
                                [(_utf8(c), float(p)) for c, p in getattr(roster, "points", {}).items()])

        return reattach(self, roster)

    def reattached(self):
        """``{old id: student}``: ids a newer roster mapped to one of its students (:func:`.enrolment.reattach`)."""
        return dict(self.db.execute("SELECT old, student FROM reattached"))

    def roster(self):
        """The stored roster, or None."""
        rows = self.db.execute(f"SELECT {', '.join(FIELDS)} FROM roster ORDER BY position").fetchall()
        points = dict(self.db.execute("SELECT header, points FROM lms_points"))
        return Roster([Student(*r) for r in rows], points=points) if rows else None

    def set_rule(self, exercise, *, due=None, penalty=None, cap=None, policy=None):
        """Change an exercise's due date, late penalty, cap or policy (the others are kept); the counting attempts
        are chosen again."""
        old = self.rule(exercise)
        new = Rule(old.due if due is None else due, old.penalty if penalty is None else float(penalty),
                   old.cap if cap is None else float(cap), old.policy if policy is None else policy)
        self.db.execute("INSERT OR REPLACE INTO rules (exercise, due, penalty, cap, policy) VALUES (?,?,?,?,?)",
                        (exercise, new.due, new.penalty, new.cap, new.policy))
        if new != old:
            self.reselect(exercise)
        return new

    def rule(self, exercise):
        row = self.db.execute("SELECT due, penalty, cap, policy FROM rules WHERE exercise = ?", (exercise,)).fetchone()
        return Rule(*row) if row else Rule()

    def extend(self, exercise, student, due, why=""):
        """Give ``student`` their own due date for ``exercise`` ("" removes it)."""
        if due:
            self.db.execute("INSERT OR REPLACE INTO extensions (exercise, student, due, why) VALUES (?,?,?,?)",
                            (exercise, student, due, _utf8(why)))
        else:
            self.db.execute("DELETE FROM extensions WHERE exercise = ? AND student = ?", (exercise, student))
        if self.rule(exercise).policy == "best":
            with self.db:
                self.db.execute("BEGIN IMMEDIATE")
                self.select(exercise, student)

    def extension(self, exercise, student):
        row = self.db.execute("SELECT due FROM extensions WHERE exercise = ? AND student = ?",
                              (exercise, student)).fetchone()
        return row[0] if row else ""

    def override(self, exercise, student, part, score, why):
        """Set a part's score by hand (kept across regrades and ``--force``); ``score`` None removes it."""
        if score is None:
            self.db.execute("DELETE FROM overrides WHERE exercise = ? AND student = ? AND part = ?",
                            (exercise, student, part))
        else:
            self.db.execute("INSERT OR REPLACE INTO overrides (exercise, student, part, score, why, set_at) VALUES "
                            "(?,?,?,?,?,?)", (exercise, student, part, float(score), _utf8(why), _now()))

    def overrides(self, exercise=None, student=None):
        """``{(exercise, student): {part: (score, why)}}``."""
        out = {}
        for e, s, p, score, why in self.db.execute("SELECT exercise, student, part, score, why FROM overrides"):
            if (exercise is None or e == exercise) and (student is None or s == student):
                out.setdefault((e, s), {})[p] = (score, why)
        return out

    def exercises(self):
        """Every exercise with a result, a rule or a pin, sorted."""
        return sorted({e for (e,) in self.db.execute("SELECT exercise FROM attempts UNION SELECT exercise FROM rules "
                                                     "UNION SELECT exercise FROM sources")})

    def points(self, exercise):
        """[(part, max_score)] of an exercise, from its most recent graded attempt."""
        row = self.db.execute("SELECT a.id FROM attempts a WHERE exercise = ? AND EXISTS (SELECT 1 FROM attempt_parts "
                              "p WHERE p.attempt = a.id) ORDER BY id DESC LIMIT 1", (exercise,)).fetchone()
        if row is None:
            return []
        return [tuple(r) for r in self.db.execute("SELECT part, max_score FROM attempt_parts WHERE attempt = ? "
                                                   "ORDER BY position", (row[0],))]

    def files_of(self, exercise):
        """``{student: [(path, outcome, reason, run)]}``: every entry of ``collected/`` tied to a student (notebooks,
        and files that are not: a PDF, a zip), as the latest run that saw it left it."""
        latest = {}
        for student, path, outcome, reason, run in self.db.execute(
                "SELECT student, path, outcome, reason, run FROM files WHERE exercise = ? AND student != '' ORDER BY "
                "rowid", (exercise,)):
            latest[student, path] = (outcome, reason, run)
        out = {}
        for (student, path), (outcome, reason, run) in sorted(latest.items()):
            out.setdefault(student, []).append((path, outcome, reason, run))
        return out

    # ------------------------------------------------------------------------------------------- reading
    def _attempt_result(self, attempt):
        a = self.db.execute("SELECT exercise, student, submission, sha256, status, message, seconds, isolation, "
                            "submitted, submitted_from, late, source_sha256 FROM attempts WHERE id = ?",
                            (attempt,)).fetchone()
        parts = [PartGrade(*row) for row in self.db.execute(
            f"SELECT {_PART_COLS} FROM attempt_parts WHERE attempt = ? ORDER BY position", (attempt,))]
        return SubmissionResult(a[1], a[0], a[2], a[3], a[4], a[5], parts, a[6], a[7], a[8], a[9], bool(a[10]),
                                [], a[11], attempt)

    def results(self, student=None, exercise=None):
        """Every counting result (of one student, of one exercise), ordered by student and exercise; each part's
        ``mistakes`` and the result's ``signals`` filled in."""
        where, args = [], []
        if student is not None:
            where.append("student = ?")
            args.append(student)
        if exercise is not None:
            where.append("exercise = ?")
            args.append(exercise)
        clause = ("WHERE " + " AND ".join(where)) if where else ""
        subs = self.db.execute(
            "SELECT exercise, student, submission, sha256, status, message, seconds, isolation, submitted, "
            f"submitted_from, late, source_sha256, attempt FROM submissions {clause} ORDER BY student, exercise",
            args).fetchall()
        parts = {}
        for row in self.db.execute(f"SELECT exercise, student, {_PART_COLS} FROM parts {clause} "
                                   "ORDER BY exercise, student, position", args):
            parts.setdefault((row[0], row[1]), []).append(PartGrade(*row[2:]))
        mistakes, signals = {}, {}
        for a, part, code, row in self.db.execute("SELECT attempt, part, code, row FROM mistakes WHERE attempt IN "
                                                  f"(SELECT attempt FROM submissions {clause}) ORDER BY rowid", args):
            mistakes.setdefault((a, part), []).append((code, row))
        for a, kind, detail in self.db.execute("SELECT attempt, kind, detail FROM signals WHERE attempt IN "
                                               f"(SELECT attempt FROM submissions {clause}) ORDER BY rowid", args):
            signals.setdefault(a, []).append((kind, detail))
        out = []
        for s in subs:
            ps = parts.get((s[0], s[1]), [])
            for p in ps:
                p.mistakes = mistakes.get((s[12], p.part), [])
            out.append(SubmissionResult(s[1], s[0], s[2], s[3], s[4], s[5], ps, s[6], s[7], s[8], s[9], bool(s[10]),
                                        signals.get(s[12], []), s[11], s[12]))
        return out

    def attempts(self, exercise=None, student=None):
        """Every attempt (history), as rows: (id, exercise, student, submission, sha256, submitted, status, score,
        max_score, counts)."""
        rows = self.db.execute(
            "SELECT a.id, a.exercise, a.student, a.submission, a.sha256, a.submitted, a.status, a.score, a.max_score, "
            "EXISTS (SELECT 1 FROM submissions s WHERE s.attempt = a.id) FROM attempts a ORDER BY a.exercise, "
            "a.student, a.id").fetchall()
        return [r for r in rows if (exercise is None or r[1] == exercise) and (student is None or r[2] == student)]

    def finals(self, exercise, roster=None):
        """The :class:`~kinbook.classroom.scores.Final` of every student of ``exercise``: the roster's (``missing``
        when they handed nothing in), then those not on it."""
        results = {r.student: r for r in self.results(exercise=exercise)}
        roster = roster if roster is not None else self.roster()
        rule = self.rule(exercise)
        overrides = self.overrides(exercise)
        exts = dict(self.db.execute("SELECT student, due FROM extensions WHERE exercise = ?", (exercise,)).fetchall())
        points = self.points(exercise)
        order = [s.student for s in roster] if roster is not None else []
        order += sorted(set(results) - set(order))
        counts = dict(self.db.execute("SELECT student, COUNT(*) FROM attempts WHERE exercise = ? GROUP BY student",
                                      (exercise,)).fetchall())
        out = []
        for s in order:
            f = final(s, exercise, results.get(s), rule, exts.get(s, ""), overrides.get((exercise, s)), points)
            f.attempts, f.policy = counts.get(s, 0), rule.policy
            out.append(f)
        return out

    def notes(self):
        """{(exercise, student): note} for results that need the instructor's attention."""
        notes = {}
        for e, s, h in self.db.execute("SELECT exercise, student, changed_sha256 FROM submissions WHERE "
                                       "changed_sha256 IS NOT NULL"):
            notes[(e, s)] = f"changed since graded (now sha256 {h[:12]}…; grade again with --force)"
        for e in self.exercises():
            for s in self.stale(e):
                notes[(e, s)] = "graded with an earlier version of the source (grade again with --regrade)"
        return notes

    # ------------------------------------------------------------------------------------------- exports
    def export(self, students=None):
        """Write grades.csv, totals.csv and collection.csv (everything recorded), each atomically. (``students``:
        kept for callers of an earlier kinbook; the feedback pages are :mod:`kinbook.classroom.feedback`'s.)"""
        results = self.results()
        notes = self.notes()
        finals = {}
        for e in {r.exercise for r in results}:
            finals.update({(e, f.student): f for f in self.finals(e) if f.status != "missing"})
        grades, totals = [], []
        for r in results:
            f = finals.get((r.exercise, r.student))
            overrides = {p: o for p, _, _, o in f.parts if o} if f is not None else {}
            for p in r.parts:
                o = overrides.get(p.part)
                shown = _score(p) if o is None else _points(o[0])
                grades.append([r.student, r.exercise, p.part, shown, f"{p.max_score:g}", p.status, p.message,
                               p.reference, _score(p), o[1] if o else ""])
            final_score = _score(r) if f is None or r.status in UNGRADED else _points(f.score)
            totals.append([r.student, r.exercise, final_score, f"{r.max_score:g}", r.status, r.isolation or "",
                           r.sha256, notes.get((r.exercise, r.student), ""), _score(r),
                           f.late_days if f is not None else 0, _points(f.penalty) if f is not None else "0",
                           ";".join(sorted(overrides))])
        write_csv(self.outdir / "grades.csv", COLUMNS, grades)
        write_csv(self.outdir / "totals.csv", TOTALS, totals)
        last = {e: run for e, run in self.db.execute("SELECT exercise, MAX(run) FROM files GROUP BY exercise")}
        rows = []
        for e in sorted(last):
            rows += self.db.execute(f"SELECT {', '.join(FILES)} FROM files WHERE exercise = ? AND run = ? ORDER BY "
                                    "path", (e, last[e])).fetchall()
        write_csv(self.outdir / "collection.csv", FILES, rows)

    def write(self):
        """Export everything (:meth:`export`)."""
        self.export()

    # ----------------------------------------------------------------------------------- older gradebooks
    def _migrate(self):
        """Add what an earlier kinbook's gradebook lacks: columns, and each result as its first attempt."""
        for table, cols in _ADDED.items():
            have = {r[1] for r in self.db.execute(f"PRAGMA table_info({table})")}
            for name, decl in cols:
                if name not in have:
                    self.db.execute(f"ALTER TABLE {table} ADD COLUMN {name} {decl}")
        old = self.db.execute("SELECT s.exercise, s.student, COALESCE(r.source_sha256, '') FROM submissions s LEFT "
                              "JOIN runs r ON r.id = s.run WHERE s.attempt IS NULL").fetchall()
        if not old:
            return
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            for exercise, student, source in old:
                attempt = self.db.execute(
                    "INSERT INTO attempts (exercise, student, submission, sha256, source_sha256, status, message, "
                    "score, max_score, seconds, isolation, run, graded) SELECT exercise, student, submission, sha256, "
                    "?, status, message, score, max_score, seconds, isolation, run, graded FROM submissions WHERE "
                    "exercise = ? AND student = ?", (source, exercise, student)).lastrowid
                self.db.execute(f"INSERT INTO attempt_parts (attempt, position, {_PART_COLS}) SELECT ?, position, "
                                f"{_PART_COLS} FROM parts WHERE exercise = ? AND student = ?",
                                (attempt, exercise, student))
                self.db.execute("UPDATE submissions SET attempt = ?, source_sha256 = ? WHERE exercise = ? AND "
                                "student = ?", (attempt, source, exercise, student))

    def _import_json_results(self):
        """Results stored by kinbook before the database (``.kinbook/results/<exercise>/<student>.json``)."""
        store = self.outdir / ".kinbook" / "results"
        if not store.is_dir() or self.db.execute("SELECT COUNT(*) FROM submissions").fetchone()[0]:
            return
        for f in sorted(store.glob("*/*.json")):
            try:
                d = json.loads(f.read_text(encoding="utf-8"))
                parts = [PartGrade(**{k: p.get(k, "") for k in ("part", "score", "max_score", "status", "message",
                                                                 "html")}) for p in d.pop("parts", [])]
                d = {k: d[k] for k in ("student", "exercise", "submission", "sha256", "status", "message", "seconds")}
                self.record(SubmissionResult(parts=parts, isolation="none", **d))
            except (ValueError, TypeError, KeyError, OSError):
                continue


__all__ += ["Final", "write_csv", "csv_text"]
