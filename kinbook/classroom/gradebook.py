"""The gradebook: ``grades.csv``, ``totals.csv`` and one HTML feedback file per student.

Every graded submission is first stored as its own result file (``.kinbook/results/<exercise>/<student>.json``,
written atomically), then the CSV files and the student's feedback page are rebuilt from all result files and
replaced atomically (temporary file + ``os.replace``). A grading process that dies therefore loses at most
the submission it was working on, and ``grades.csv`` is never half-written.
"""

from __future__ import annotations

import csv
import html
import io
import json
import os
import tempfile
from pathlib import Path

from .grade import SubmissionResult

__all__ = ["Gradebook", "atomic_write", "COLUMNS"]

COLUMNS = ["student", "exercise", "part", "score", "max_score", "status", "message"]


def atomic_write(path, text):
    """Write ``text`` to ``path`` through a temporary file in the same directory and ``os.replace``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _cell(text):
    """A CSV field a spreadsheet will not read as a formula (messages can quote students' answers)."""
    text = str(text).replace("\n", " ")
    return "'" + text if text[:1] in ("=", "+", "-", "@") else text


class Gradebook:
    """The grading output directory."""

    def __init__(self, outdir):
        self.outdir = Path(outdir)
        self.store = self.outdir / ".kinbook" / "results"

    def _file(self, student, exercise):
        return self.store / exercise / f"{student}.json"

    def has(self, student, exercise):
        return self._file(student, exercise).exists()

    def record(self, result):
        """Store one submission's result and rebuild that student's feedback page and the CSV files."""
        atomic_write(self._file(result.student, result.exercise), json.dumps(result.to_dict(), indent=1))
        self.write_feedback(result.student)
        self.write_csv()

    def results(self):
        out = []
        if not self.store.exists():
            return out
        for f in sorted(self.store.glob("*/*.json")):
            try:
                out.append(SubmissionResult.from_dict(json.loads(f.read_text(encoding="utf-8"))))
            except (ValueError, TypeError, KeyError):
                continue
        return out

    def write(self):
        """Rebuild every output file."""
        self.write_csv()
        for student in sorted({r.student for r in self.results()}):
            self.write_feedback(student)

    def write_csv(self):
        results = self.results()
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in results:
            for p in r.parts:
                w.writerow([_cell(r.student), r.exercise, p.part, f"{p.score:g}", f"{p.max_score:g}", p.status,
                            _cell(p.message)])
        atomic_write(self.outdir / "grades.csv", buf.getvalue())
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["student", "exercise", "score", "max_score", "status"])
        for r in results:
            w.writerow([_cell(r.student), r.exercise, f"{r.score:g}", f"{r.max_score:g}", r.status])
        atomic_write(self.outdir / "totals.csv", buf.getvalue())

    def write_feedback(self, student):
        mine = [r for r in self.results() if r.student == student]
        body = [f"<h1>Feedback for {html.escape(student)}</h1>"]
        for r in mine:
            body.append(f"<h2>{html.escape(r.exercise)}: {r.score:g} / {r.max_score:g}</h2>")
            if r.status != "ok":
                body.append(f"<p><b>status: {html.escape(r.status)}</b> — {html.escape(r.message)}</p>")
            body.append("<table border=1 cellpadding=4><tr><th>part</th><th>score</th><th>status</th></tr>")
            for p in r.parts:
                body.append(f"<tr><td>{html.escape(p.part)}</td><td>{p.score:g} / {p.max_score:g}</td>"
                            f"<td>{html.escape(p.status)}</td></tr>")
            body.append("</table>")
            for p in r.parts:
                body.append(f"<h3>{html.escape(p.part)}</h3>")
                # p.html is rendered by kinbook's CheckResult (escaped there); anything else is escaped here
                body.append(p.html if p.html else f"<p>{html.escape(p.message)}</p>")
        page = ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>kinbook feedback: "
                f"{html.escape(student)}</title></head><body>{''.join(body)}</body></html>")
        atomic_write(self.outdir / "feedback" / f"{student}.html", page)
