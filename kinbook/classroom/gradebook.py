"""The gradebook: an SQLite database (``graded/gradebook.sqlite``), and the files exported from it.

Every graded submission is recorded in one transaction (its row in ``submissions`` and one row per part in
``parts``), in WAL mode with full synchronization: a grading run killed at any moment — SIGKILL, the OOM
killer, a power cut — keeps every result recorded before, and the next run finds them and grades only what is
left. Recording one result costs the same whether the database holds 10 results or 10,000 (one indexed
upsert; nothing is re-read).

``grades.csv`` (one row per part), ``totals.csv`` (one row per submission, for an LMS) and
``feedback/<student>.html`` are exports, each written atomically (:func:`kinbook.classroom.files.atomic_write`)
from the database at the end of a run (and when a run is interrupted by SIGTERM or Ctrl-C): never half-written.

Tables: ``runs`` (when, which source — path and sha256 —, kinbook's version, isolation), ``submissions``
(exercise, student, file, sha256, status, message, score, isolation, the run, and ``changed_sha256`` when a
different file was seen after grading) and ``parts``.
"""

from __future__ import annotations

import csv
import html
import io
import json
import sqlite3
import time
from pathlib import Path

from .files import atomic_write
from .results import PartGrade, SubmissionResult

__all__ = ["Gradebook", "COLUMNS", "TOTALS", "DATABASE"]

DATABASE = "gradebook.sqlite"
COLUMNS = ["student", "exercise", "part", "score", "max_score", "status", "message", "reference"]
TOTALS = ["student", "exercise", "score", "max_score", "status", "isolation", "sha256", "note"]
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
"""


def _cell(text):
    """A CSV field a spreadsheet will not read as a formula (messages can quote students' answers)."""
    text = str(text).replace("\n", " ")
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


def _utf8(value):
    """Text SQLite and the UTF-8 exports can store: a lone surrogate (a file name's byte that is not UTF-8, carried
    into a message) is written as an escape instead of failing the whole run."""
    return value.encode("utf-8", "backslashreplace").decode("utf-8") if isinstance(value, str) else value


def _now():
    return time.strftime("%Y-%m-%dT%H:%M:%S%z")


class Gradebook:
    """The grading output directory and its database.

    Parameters
    ----------
    outdir : path
        Created if missing; holds ``gradebook.sqlite`` and the exports.
    """

    def __init__(self, outdir):
        self.outdir = Path(outdir)
        self.outdir.mkdir(parents=True, exist_ok=True)
        self.path = self.outdir / DATABASE
        self.db = sqlite3.connect(str(self.path), timeout=30, isolation_level=None)
        self.db.execute("PRAGMA journal_mode=WAL")
        self.db.execute("PRAGMA synchronous=FULL")
        self.db.executescript(_SCHEMA)
        self._import_json_results()

    def close(self):
        self.db.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ----------------------------------------------------------------------------------------- recording
    def begin_run(self, source, isolation):
        """Record the start of a run; returns its id."""
        from .. import __version__

        cur = self.db.execute("INSERT INTO runs (started, source, source_sha256, exercise, isolation, kinbook) "
                              "VALUES (?, ?, ?, ?, ?, ?)", (_now(), str(source.path), source.sha256, source.exercise,
                                                            isolation, __version__))
        return cur.lastrowid

    def end_run(self, run):
        self.db.execute("UPDATE runs SET finished = ? WHERE id = ?", (_now(), run))

    def graded(self, exercise, student):
        """(sha256, status) of the recorded result, or None."""
        row = self.db.execute("SELECT sha256, status FROM submissions WHERE exercise = ? AND student = ?",
                              (exercise, student)).fetchone()
        return row

    def has(self, student, exercise):
        return self.graded(exercise, student) is not None

    def note_changed(self, exercise, student, sha256):
        """A file different from the graded one was seen for this student (not graded again without --force)."""
        self.db.execute("UPDATE submissions SET changed_sha256 = ? WHERE exercise = ? AND student = ?",
                        (sha256, exercise, student))

    def record(self, result, run=None):
        """Store one submission's result (replacing an earlier one), in one transaction."""
        r = result
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            self.db.execute(
                "INSERT OR REPLACE INTO submissions (exercise, student, submission, sha256, status, message, score, "
                "max_score, seconds, isolation, run, graded, changed_sha256) VALUES (?,?,?,?,?,?,?,?,?,?,?,?,NULL)",
                [_utf8(v) for v in (r.exercise, r.student, r.submission, r.sha256, r.status, r.message, r.score,
                                    r.max_score, r.seconds, r.isolation, run, _now())])
            self.db.execute("DELETE FROM parts WHERE exercise = ? AND student = ?",
                            (_utf8(r.exercise), _utf8(r.student)))
            self.db.executemany(
                "INSERT INTO parts (exercise, student, position, part, score, max_score, status, message, html, "
                "reference) VALUES (?,?,?,?,?,?,?,?,?,?)",
                [[_utf8(v) for v in (r.exercise, r.student, i, p.part, p.score, p.max_score, p.status, p.message,
                                     p.html, p.reference)] for i, p in enumerate(r.parts)])

    # ------------------------------------------------------------------------------------------- reading
    def results(self, student=None):
        """Every recorded result (of one student), ordered by student and exercise."""
        where, args = ("WHERE student = ?", (student,)) if student is not None else ("", ())
        subs = self.db.execute(
            "SELECT exercise, student, submission, sha256, status, message, seconds, isolation FROM submissions "
            f"{where} ORDER BY student, exercise", args).fetchall()
        parts = {}
        for row in self.db.execute(f"SELECT exercise, student, part, score, max_score, status, message, html, reference "
                                   f"FROM parts {where} ORDER BY exercise, student, position", args):
            parts.setdefault((row[0], row[1]), []).append(PartGrade(*row[2:]))
        return [SubmissionResult(s[1], s[0], s[2], s[3], s[4], s[5], parts.get((s[0], s[1]), []), s[6], s[7])
                for s in subs]

    def notes(self):
        """{(exercise, student): note} for submissions whose file changed after they were graded."""
        return {(e, s): f"changed since graded (now sha256 {h[:12]}…; grade again with --force)"
                for e, s, h in self.db.execute("SELECT exercise, student, changed_sha256 FROM submissions "
                                               "WHERE changed_sha256 IS NOT NULL")}

    # ------------------------------------------------------------------------------------------- exports
    def export(self, students=None):
        """Write grades.csv, totals.csv (everything recorded) and the feedback pages of ``students`` (default:
        every student), each atomically."""
        results = self.results()
        notes = self.notes()
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in results:
            for p in r.parts:
                w.writerow([_cell(r.student), _cell(r.exercise), _cell(p.part), f"{p.score:g}", f"{p.max_score:g}",
                            p.status, _cell(p.message), _cell(p.reference)])
        atomic_write(self.outdir / "grades.csv", buf.getvalue())
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(TOTALS)
        for r in results:
            w.writerow([_cell(r.student), _cell(r.exercise), f"{r.score:g}", f"{r.max_score:g}", r.status,
                        r.isolation or "", r.sha256, notes.get((r.exercise, r.student), "")])
        atomic_write(self.outdir / "totals.csv", buf.getvalue())
        mine = {}
        for r in results:
            mine.setdefault(r.student, []).append(r)
        for student in (sorted(mine) if students is None else [s for s in students if s in mine]):
            atomic_write(self.outdir / "feedback" / f"{student}.html", _page(student, mine[student]))

    def write(self):
        """Export everything (:meth:`export`)."""
        self.export()

    # ----------------------------------------------------------------------------------- older gradebooks
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


def _page(student, results):
    body = [f"<h1>Feedback for {html.escape(student)}</h1>"]
    for r in results:
        body.append(f"<h2>{html.escape(r.exercise)}: {r.score:g} / {r.max_score:g}</h2>")
        if r.status != "ok":
            body.append(f"<p><b>status: {html.escape(r.status)}</b> — {html.escape(r.message)}</p>")
        body.append("<table border=1 cellpadding=4><tr><th>part</th><th>score</th><th>status</th>"
                    "<th>answered with kinbook's reference</th></tr>")
        for p in r.parts:
            body.append(f"<tr><td>{html.escape(p.part)}</td><td>{p.score:g} / {p.max_score:g}</td>"
                        f"<td>{html.escape(p.status)}</td><td>{html.escape(p.reference) or '—'}</td></tr>")
        body.append("</table>")
        for p in r.parts:
            body.append(f"<h3>{html.escape(p.part)}</h3>")
            if p.reference:
                body.append(f"<p><i>This answer was computed with kinbook's own reference: "
                            f"{html.escape(p.reference)}.</i></p>")
            # p.html is rendered by kinbook's CheckResult (escaped there); anything else is escaped here
            body.append(p.html if p.html else f"<p>{html.escape(p.message)}</p>")
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>kinbook feedback: "
            f"{html.escape(student)}</title></head><body>{''.join(body)}</body></html>")
