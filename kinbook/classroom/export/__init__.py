"""``kinbook export``: the gradebook as a file an LMS imports as it is.

One row per student, one column per exercise, the score that counts (the counting attempt, the instructor's overrides,
the late penalty: :func:`kinbook.classroom.scores.final`), rounded to ``decimals``:

``canvas``
    Canvas's gradebook CSV (Grades → Import): ``Student, ID, SIS User ID, SIS Login ID, Section``, then one column
    per exercise headed ``<assignment> (<assignment id>)`` — Canvas fills the assignment whose id is in the
    parentheses, and creates a new one for a header without one — and, under the header, the ``Points Possible`` row.
    Rows come from the roster (Canvas matches them by ``ID``, its user id). Canvas keeps an existing assignment's
    own points: when the roster (Canvas's export) says the assignment is worth other points than the exercise, the
    export stops and names both — or, with ``scale``, writes the scores scaled to Canvas's points.
``moodle``
    Moodle's grade import CSV (Grades → Import → CSV file): the identifier columns of Moodle's own export (``First
    name, Last name, ID number, Institution, Department, Email address``), then one column per exercise headed
    ``Assignment: <name> (Real)``. On import, map ``Email address`` (or ``ID number``) to the user and each column
    to its grade item.
``csv``
    kinbook's own: ``student, name, section, sis_id, lms_id, email``, then per exercise its score, status, days late
    and penalty, and the total.

A student on the roster who handed nothing in is ``missing``: 0, or an empty cell with ``missing="blank"``.
Students graded but not on the roster cannot be imported (the LMS does not know them): they are returned, for the
instructor to see, and left out of Canvas and Moodle files.
"""

from __future__ import annotations

import re
from pathlib import Path

from ...core.atomic import protect, refuse_overwrite
from ...errors import GradingError
from ..gradebook import Gradebook, write_csv
from ..results import UNGRADED
from ..roster import Student

__all__ = ["export", "FORMATS", "CANVAS_IDS", "MOODLE_IDS"]

FORMATS = ("canvas", "moodle", "csv")
#: Canvas's identifying columns, in its order.
CANVAS_IDS = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]
#: The identifying columns of Moodle's grade export (and import).
MOODLE_IDS = ["First name", "Last name", "ID number", "Institution", "Department", "Email address"]
_CANVAS_HEADER = re.compile(r"^.+ \(\d+\)$")


def _number(value, decimals):
    text = f"{round(float(value), decimals):.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def export(gradebook, out, fmt="csv", *, exercises=None, decimals=2, missing="zero", headers=None, roster=None,
           scale=False):
    """Write the gradebook's scores as ``fmt`` into ``out``.

    Parameters
    ----------
    gradebook : path
        The grading output directory (``graded/``).
    out : path
        The file to write.
    fmt : {"canvas", "moodle", "csv"}
    exercises : list of str, optional
        Default: every exercise of the gradebook, in order.
    decimals : int
        Scores are rounded to this many decimals (0 to 6).
    missing : {"zero", "blank"}
    headers : dict, optional
        ``{exercise: column header}``: Canvas ``"Exercise 11 (4242)"`` (the LMS's assignment name and id), Moodle
        ``"Assignment: Exercise 11 (Real)"``.
    roster : Roster, optional
        Default: the one stored by ``kinbook grade --roster``.
    scale : bool
        Canvas: where the roster says an assignment is worth other points than kinbook's exercise (its ``Points
        Possible``), write the scores scaled to the LMS's points. Without it such a mismatch stops the export.

    Returns
    -------
    (Path, list of str)
        The file written, and the students left out (graded but not on the roster).
    """
    if fmt not in FORMATS:
        raise GradingError(f"export format must be one of {', '.join(FORMATS)}, got {fmt!r}")
    if not 0 <= int(decimals) <= 6:
        raise GradingError(f"decimals must be 0 to 6, got {decimals!r}")
    if missing not in ("zero", "blank"):
        raise GradingError(f"missing must be 'zero' or 'blank', got {missing!r}")
    headers = dict(headers or {})
    with Gradebook(gradebook, create=False) as book:
        known = book.exercises()
        exercises = list(exercises) if exercises else known
        unknown = [e for e in exercises if e not in known]
        if unknown:
            raise GradingError(f"no exercise {', '.join(map(repr, unknown))} in {str(gradebook)!r} (it has: "
                               f"{', '.join(known) or 'none'})")
        bad = [e for e in headers if e not in exercises]
        if bad:
            raise GradingError(f"a header is given for {', '.join(map(repr, bad))}, which is not exported")
        roster = roster if roster is not None else book.roster()
        finals = {e: {f.student: f for f in book.finals(e, roster)} for e in exercises}
        inputs = book.inputs() + [("the roster", getattr(roster, "path", None))]
    refuse_overwrite([out], inputs, "export")
    with protect(*inputs):
        return _write(out, fmt, exercises, finals, roster, headers, decimals, missing, scale)


def _write(out, fmt, exercises, finals, roster, headers, decimals, missing, scale=False):
    students = list(roster) if roster is not None else []
    on_roster = {s.student for s in students}
    graded = sorted({s for e in exercises for s in finals[e]} - on_roster)
    if fmt == "csv":
        rows = students + [Student(s) for s in graded]
        return _kinbook_csv(out, exercises, finals, rows, decimals, missing), []
    if roster is None:
        raise GradingError(f"a {fmt} file needs the roster (its LMS ids): give --roster (Canvas's gradebook export "
                           "or Moodle's, as downloaded), or grade with --roster first")

    if fmt == "canvas":
        return _canvas(out, exercises, finals, students, headers, decimals, missing, roster.points, scale), graded
    return _moodle(out, exercises, finals, students, headers, decimals, missing), graded


def _cell(f, decimals, missing, factor=1.0):
    """A score cell: the final score (times ``factor``: scaled to the LMS's points), or "" for no row (or a missing
    student with ``missing="blank"``, or a submission the grader could not grade)."""
    if f is None or (f.status == "missing" and missing == "blank") or f.status in UNGRADED:
        return ""
    return _number(f.score * factor, decimals)


def _canvas(out, exercises, finals, students, headers, decimals, missing, lms_points, scale):
    cols = []
    for e in exercises:
        h = headers.get(e, e)
        if not _CANVAS_HEADER.match(h):
            offer = (f"; the roster's Canvas assignments: {', '.join(map(repr, lms_points))}" if lms_points else "")
            raise GradingError(f"Canvas header {h!r} of {e!r} has no assignment id: write it as it appears in "
                               "Canvas's gradebook export, 'Exercise 11 (4242)' (--header EXERCISE='NAME (ID)')"
                               + offer)
        cols.append(h)
    mine = [max((f.max_score for f in finals[e].values()), default=0) for e in exercises]
    factors, differ = [], []
    for e, h, kb in zip(exercises, cols, mine):
        lms = lms_points.get(h)
        if lms is None or abs(lms - kb) <= 1e-9 * max(1.0, kb):
            factors.append((1.0, kb))
            continue
        differ.append(f"{e} is worth {_number(kb, decimals)} points in kinbook and {_number(lms, decimals)} in Canvas "
                      f"({h!r}, its Points Possible in the roster)")
        factors.append((lms / kb if kb else 1.0, lms))
    if differ and not scale:
        raise GradingError("; ".join(differ) + ". Canvas keeps its own points for an existing assignment, so full "
                           "marks would read as less: export with --scale to write the scores scaled to Canvas's "
                           "points, or change the assignment's points in Canvas and download the roster again. "
                           "Nothing was written.")
    points = [_number(top, decimals) for _, top in factors]
    rows = [["    Points Possible", "", "", "", ""] + points]
    for s in students:
        rows.append([s.name or s.display, s.lms_id, s.sis_id, s.login, s.section]
                    + [_cell(finals[e].get(s.student), decimals, missing, k) for e, (k, _) in zip(exercises, factors)])
    return write_csv(Path(out), CANVAS_IDS + cols, rows)


def _moodle(out, exercises, finals, students, headers, decimals, missing):
    cols = [headers.get(e, f"Assignment: {e} (Real)") for e in exercises]
    rows = []
    for s in students:
        first, last = s.names()
        rows.append([first, last, s.sis_id, "", "", s.email]
                    + [_cell(finals[e].get(s.student), decimals, missing) for e in exercises])
    return write_csv(Path(out), MOODLE_IDS + cols, rows)


def _kinbook_csv(out, exercises, finals, students, decimals, missing):
    header = ["student", "name", "section", "sis_id", "lms_id", "email"]
    for e in exercises:
        header += [e, f"{e} max", f"{e} status", f"{e} days late", f"{e} penalty", f"{e} overridden"]
    header += ["total", "total max"]
    rows = []
    for s in students:
        row = [s.student, s.display, s.section, s.sis_id, s.lms_id, s.email]
        total = mx = 0.0
        ungraded = False  # a total with a submission the grader could not grade is no total: blank
        for e in exercises:
            f = finals[e].get(s.student)
            if f is None:
                row += ["", "", "", "", "", ""]
                continue
            blank = (f.status == "missing" and missing == "blank") or f.status in UNGRADED
            row += ["" if blank else _number(f.score, decimals), _number(f.max_score, decimals), f.status,
                    f.late_days, _number(f.penalty, decimals), ";".join(p for p, _, _, o in f.parts if o)]
            total += f.score
            mx += f.max_score
            ungraded = ungraded or f.status in UNGRADED
        rows.append(row + ["" if ungraded else _number(total, decimals), _number(mx, decimals)])
    return write_csv(Path(out), header, rows)
