"""Feedback a student can use (``kinbook feedback``): one page per student per exercise.

Each page is one self-contained HTML file (no script, no outside resource): the exercise, the student, when it was
handed in and graded, the total (with the instructor's overrides and the late penalty, each with its reason), and
for every part its score, its status in words, the checker's message next to the student's own answer, and the cell
the answer was assigned in, as the student sees their notebook (its position among all cells, its first line and its
code). ``kinbook feedback --out DIR`` lays them out as ``DIR/<student>/<exercise>.html`` with a
``DIR/<student>/index.html`` per student: a folder per student for a shared drive; ``kinbook feedback --lms canvas``
or ``--lms moodle`` writes one zip per exercise named as the LMS's bulk feedback upload reads names (:mod:`.upload`).
Copying signals and the other students are never on a student's page.
"""

from __future__ import annotations

import html
import os
from pathlib import Path

from ...core.atomic import protect, refuse_overwrite, write_all
from ...errors import GradingError
from ..choice import kind_of_file
from ..files import PUBLIC_DIR, PUBLIC_FILE
from ..gradebook import Gradebook
from ..results import UNGRADED
from .upload import LAYOUTS, upload_zip

__all__ = ["write_pages", "feedback", "page", "STATUS_WORDS", "part_words"]

#: What a submission's status means, for the student.
STATUS_WORDS = {
    "ok": "graded",
    "missing-answer": "some answers were not found: the variable was not assigned, or its cell raised an error first",
    "error": "some answers could not be graded: they are not data the grader reads, or the notebook stopped",
    "timeout": "the notebook did not finish within the time limit",
    "memory": "the notebook used more memory than allowed",
    "tampered": "a cell you were not meant to edit was changed, moved or deleted",
    "wrong-release": "this is not the notebook released for you: start from your own",
    "corrupt-notebook": "the file is not a notebook that can be read",
    "too-large": "the file is too large to be graded",
    "refused": "the file was not read (a link, a special file, or not your own notebook)",
    "bad-id": "the file's name gives no usable student id",
    "duplicate-id": "two files were handed in under different spellings of your name",
    "missing": "nothing was handed in",
    "no-notebook": "no notebook was handed in (a file of another kind was)",
    "grader-error": "not graded yet: the grader failed before your notebook ran (not your doing); it will be "
                    "graded again",
}

_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,sans-serif;max-width:60rem;margin:2rem auto;
padding:0 1rem;color:#1d2125;line-height:1.45}
h1{font-size:1.5rem;margin-bottom:.2rem}h2{font-size:1.15rem;margin-top:2rem;border-bottom:1px solid #ccd;
padding-bottom:.2rem}.meta{color:#555}.total{font-size:1.3rem;font-weight:600;margin:1rem 0}
table{border-collapse:collapse;margin:.5rem 0}td,th{border:1px solid #ccd;padding:.3rem .6rem;text-align:left;
vertical-align:top}th{background:#f1f3f6}.ok{color:#155724}.partial{color:#856404}.bad{color:#721c24}
.note{background:#fff8e1;border-left:4px solid #f0b400;padding:.4rem .8rem;margin:.5rem 0}
pre{background:#f6f8fa;border:1px solid #dde;padding:.5rem;overflow-x:auto;font-size:.85rem;white-space:pre-wrap}
.cols{display:grid;grid-template-columns:1fr 1fr;gap:1rem}.cols>div{min-width:0}
"""



def _pts(x):
    """Points as a student reads them: at most two decimals (7.33, 9.9, 11)."""
    return f"{round(float(x), 2):g}"

def part_words(score, max_score, status):
    """A part's status in words, for the student."""
    if status == "ok":
        if max_score and score >= max_score:
            return "correct", "ok"
        return ("partly correct" if score > 0 else "not correct"), ("partial" if score > 0 else "bad")
    return STATUS_WORDS.get(status, status), "bad"


def _score(final):
    """A final's score as shown: "not graded yet" for a submission the grader could not grade (never a 0)."""
    return "not graded yet" if final.status in UNGRADED else _pts(final.score)


def _e(text):
    return html.escape(str(text))


def _handed_in(final, files):
    """What the page says of the student's files beyond the one graded: a PDF instead of a notebook, a scratch
    notebook or a blank download beside it — never "nothing was handed in" when something was."""
    out = []
    others = [(os.path.basename(p), reason) for p, outcome, reason, _ in files if outcome == "ignored"]
    if final.status == "missing" and others:
        names = ", ".join(n for n, _ in others)
        kinds = sorted({kind_of_file(n) for n, _ in others if not n.endswith(".ipynb")})
        out.append(f"<p class='note'><b>no notebook</b>: you handed in {_e(names)}"
                   + (f" ({_e(', '.join(kinds))}), not a notebook" if kinds else "")
                   + " — kinbook grades Jupyter notebooks (.ipynb) only: hand in the notebook itself.</p>")
    elif others:
        out.append("<p class='meta'>Not graded: " + "; ".join(f"{_e(n)} — {_e(r)}" for n, r in others) + ".</p>")
    return out


def page(final, result, *, name="", graded="", files=()):
    """The HTML page of one student's :class:`~kinbook.classroom.scores.Final` on one exercise (``result`` the
    counting :class:`~kinbook.classroom.results.SubmissionResult`, or None when nothing was handed in; ``files``
    the student's entries of ``collected/``: (path, outcome, reason, run), :meth:`Gradebook.files_of`)."""
    who = name or final.student
    out = [f"<h1>{_e(final.exercise)}</h1>",
           f"<p class='meta'>Feedback for <b>{_e(who)}</b> ({_e(final.student)})"
           + (f" · handed in {_e(final.submitted)}" if final.submitted else "")
           + (f" · graded {_e(graded)}" if graded else "") + "</p>",
           f"<p class='total'>Total: {_score(final)} / {_pts(final.max_score)}</p>"]
    shown = _handed_in(final, files)
    nothing = final.status == "missing" and bool(shown)  # no notebook, but a PDF, a zip …
    if final.status != "ok" and not nothing:
        out.append(f"<p class='note'><b>{_e(final.status)}</b>: {_e(STATUS_WORDS.get(final.status, ''))}"
                   + (f" — {_e(result.message)}" if result is not None and result.message else "") + "</p>")
    out += shown
    last = max((run for *_, run in files), default=None)
    together = sum(1 for _, outcome, _, run in files if outcome in ("graded", "skipped") and run == last)
    if together > 1:
        out.append(f"<p class='meta'>Your submission holds {together} notebooks; each was graded and the best "
                   "counts.</p>")
    elif final.attempts > 1:
        which = "the latest" if final.policy == "latest" else "the best"
        out.append(f"<p class='meta'>You handed in {final.attempts} files; {which} counts.</p>")
    if final.late_days:
        out.append(f"<p class='note'>Handed in {final.late_days} day(s) after the due date ({_e(final.due)}): "
                   f"−{_pts(final.penalty)} point(s), from {_pts(final.raw)}.</p>")
    overrides = [(p, o) for p, _, _, o in final.parts if o]
    for p, (score, why) in overrides:
        out.append(f"<p class='note'>Part <b>{_e(p)}</b>: your instructor set the score to {_pts(score)}"
                   + (f" — {_e(why)}" if why else "") + ".</p>")
    out.append("<table><tr><th>part</th><th>score</th><th>status</th></tr>")
    grades = {p.part: p for p in (result.parts if result is not None else [])}
    for p, score, mx, o in final.parts:
        shown = o[0] if o else score
        words, cls = part_words(shown, mx, grades[p].status if p in grades else ("no-notebook" if nothing else
                                                                                 "missing"))
        shown = "—" if final.status in UNGRADED and not o else _pts(shown)  # not graded: no score, not a 0
        out.append(f"<tr><td>{_e(p)}</td><td>{shown} / {_pts(mx)}{' (set by your instructor)' if o else ''}</td>"
                   f"<td class='{cls}'>{_e(words)}</td></tr>")
    out.append("</table>")
    for p, score, mx, o in final.parts:
        g = grades.get(p)
        if g is None:
            continue
        out.append(f"<h2>{_e(p)}: {'—' if final.status in UNGRADED and not o else _pts(o[0] if o else score)} / "
                   f"{_pts(mx)}</h2>")
        if g.reference:
            out.append(f"<p><i>This answer was computed with kinbook's own reference: {_e(g.reference)}.</i></p>")
        message = g.html if g.html else f"<p>{_e(g.message)}</p>"  # g.html is rendered (escaped) by CheckResult
        mine = f"<pre>{_e(g.answer)}</pre>" if g.answer else "<p><i>(no answer read)</i></p>"
        out.append(f"<div class='cols'><div><h3>The grader says</h3>{message}</div>"
                   f"<div><h3>Your answer</h3>{mine}</div></div>")
        if g.cell:
            where, _, code = g.cell.partition("\n")
            out.append(f"<p class='meta'>Assigned in {_e(where)}</p>" + (f"<pre>{_e(code)}</pre>" if code else ""))
    title = f"{final.exercise}: {who}"
    return (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{_e(title)}</title>"
            f"<style>{_CSS}</style></head><body>{''.join(out)}</body></html>")


def _index(student, name, finals):
    rows = "".join(f"<tr><td><a href='{_e(f.exercise)}.html'>{_e(f.exercise)}</a></td><td>{_score(f)} / "
                   f"{_pts(f.max_score)}</td><td>{_e(STATUS_WORDS.get(f.status, f.status))}</td></tr>" for f in finals)
    total = sum(f.score for f in finals)
    mx = sum(f.max_score for f in finals)
    return (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{_e(name or student)}</title>"
            f"<style>{_CSS}</style></head><body><h1>{_e(name or student)}</h1><p class='total'>"
            f"{'not graded yet' if any(f.status in UNGRADED for f in finals) else _pts(total)} / {_pts(mx)}"
            f"</p><table><tr><th>exercise</th><th>score</th><th>status</th></tr>{rows}</table></body></html>")


#: Feedback is handed out: readable by everyone (0644, directories 0755), like nbgrader's.
_PUBLIC = {"mode": PUBLIC_FILE, "dir_mode": PUBLIC_DIR}


def _pages(book, students=None):
    """``[(student, final, html)]`` of every student's page (of ``students`` only, when given), in the gradebook's
    order of exercises; ``final`` is the :class:`~kinbook.classroom.scores.Final` the page shows."""
    roster = book.roster()
    names = {s.student: s.display for s in roster} if roster is not None else {}
    wanted = None if students is None else set(students)
    out = []
    for exercise in book.exercises():
        results = {r.student: r for r in book.results(exercise=exercise)}
        graded = dict(book.db.execute("SELECT student, graded FROM submissions WHERE exercise = ?", (exercise,)))
        handed = book.files_of(exercise)
        for f in book.finals(exercise, roster):
            if wanted is None or f.student in wanted:
                out.append((f.student, f, page(f, results.get(f.student), name=names.get(f.student, ""),
                                               graded=graded.get(f.student, ""), files=handed.get(f.student, []))))
    return out


def write_pages(book, out, students=None):
    """Write ``out/<student>/<exercise>.html`` and ``out/<student>/index.html`` for ``students`` (default: every
    student of the gradebook and of its roster). Returns the pages written."""
    out = Path(out)
    roster = book.roster()
    names = {s.student: s.display for s in roster} if roster is not None else {}
    mine = {}
    for student, f, text in _pages(book, students):
        mine.setdefault(student, []).append((f, text))
    for old in book.reattached():  # an id a newer roster gave to one of its students: its pages are theirs now
        folder = out / old
        if folder.is_dir() and all(p.suffix == ".html" and p.is_file() for p in folder.iterdir()):
            for p in folder.iterdir():
                p.unlink()
            folder.rmdir()
    files = []
    for student, items in sorted(mine.items()):
        files += [(out / student / f"{f.exercise}.html", text) for f, text in items]
        files.append((out / student / "index.html", _index(student, names.get(student, ""), [f for f, _ in items])))
    refuse_overwrite([p for p, _ in files], book.inputs(), "feedback")
    with protect(*book.inputs()):  # all pages or none: a full disk leaves the earlier pages as they were
        return write_all(files, **_PUBLIC)


def feedback(gradebook, out, lms=None):
    """``kinbook feedback``: every student's pages from the gradebook directory ``gradebook`` into ``out`` — one folder
    per student, or with ``lms`` (``canvas``, ``moodle``) one zip per exercise that the LMS's bulk feedback upload
    takes (:mod:`.upload`). Returns the files written (and, with ``lms``, the pages left out: ``(written, left)``)."""
    with Gradebook(gradebook, create=False) as book:
        if lms is None:
            return write_pages(book, out)

        if lms not in LAYOUTS:
            raise GradingError(f"feedback for an LMS: one of {', '.join(LAYOUTS)}, got {lms!r}")
        with protect(*book.inputs()):
            return upload_zip(book, out, lms, {(f.exercise, student): text for student, f, text in _pages(book)})
