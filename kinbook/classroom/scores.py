"""A student's final score on an exercise: the graded parts, the instructor's overrides, the late rule.

Pure functions over recorded data (no database, no clock): the gradebook, the exports, the report and the feedback
pages all call :func:`final`, so a score is computed one way everywhere.

The late rule of an exercise (``kinbook due``): a due date (ISO 8601 with its zone), a penalty in percent of the
exercise's points per started day late, and a cap in percent (default 100: the score never goes below 0). A
student's extension replaces the due date for them. A submission the LMS marked late in its name (Canvas) and whose
time is not known to be later counts as one day late — unless the student has an extension (the LMS's mark is for
the LMS's due date).
"""

from __future__ import annotations

import datetime as _dt
import math
from dataclasses import dataclass, field

__all__ = ["Rule", "Final", "final", "late_days", "parse_due", "POLICIES"]

POLICIES = ("latest", "best")


def parse_due(text):
    """An ISO 8601 date and time with its zone (``2026-03-01T23:59+01:00``, ``…Z``) → aware datetime.

    Raises
    ------
    ValueError
        With what to write instead (a time without a zone would depend on the grading machine's clock settings).
    """
    t = str(text).strip()
    if t.endswith(("Z", "z")):
        t = t[:-1] + "+00:00"
    try:
        when = _dt.datetime.fromisoformat(t)
    except ValueError:
        raise ValueError(f"not a date and time: {text!r} (write it as 2026-03-01T23:59+01:00)") from None
    if when.tzinfo is None:
        raise ValueError(f"{text!r} has no time zone: write it with its offset, as 2026-03-01T23:59+01:00 or "
                         "2026-03-01T22:59Z (a zone-less time would depend on the grading machine)")
    return when


@dataclass
class Rule:
    """How an exercise is scored beyond its parts.

    Attributes
    ----------
    due : str
        ISO 8601 with zone, or "" (no due date).
    penalty : float
        Percent of the exercise's points taken per started day late.
    cap : float
        At most this percent of the points is taken.
    policy : str
        ``latest`` or ``best``: which of a student's attempts counts.
    """

    due: str = ""
    penalty: float = 0.0
    cap: float = 100.0
    policy: str = "latest"


def _when(text, zone):
    """A stored submission time → aware datetime (a time read from a name has no zone: the due date's applies)."""
    if not text:
        return None
    when = _dt.datetime.fromisoformat(text)
    return when.replace(tzinfo=zone) if when.tzinfo is None else when


def late_days(submitted, due, marked_late=False):
    """Started days between ``due`` and ``submitted`` (ISO texts), 0 when on time or when either is unknown.

    >>> late_days("2026-03-02T00:30+01:00", "2026-03-01T23:59+01:00")
    1
    >>> late_days("2026-03-03T23:59+01:00", "2026-03-01T23:59+01:00")
    2
    >>> late_days("2026-03-01T10:00+01:00", "2026-03-01T23:59+01:00", marked_late=True)
    1
    """
    if not due:
        return 0
    deadline = parse_due(due)
    when = _when(submitted, deadline.tzinfo)
    if when is None:
        return 1 if marked_late else 0
    seconds = (when - deadline).total_seconds()
    if seconds <= 0:
        return 1 if marked_late else 0
    return math.ceil(seconds / 86400)


@dataclass
class Final:
    """One student's standing on one exercise.

    Attributes
    ----------
    status : str
        The graded submission's status, or ``missing`` (on the roster, nothing handed in).
    parts : list of (part, score, max_score, override or None)
        ``override`` is ``(score, why)`` when the instructor set the part's score.
    raw : float
        The parts' sum (overrides applied), before the late penalty.
    late_days, penalty : int, float
    score : float
        ``raw − penalty``, never below 0.
    due : str
        The due date that applied (the student's extension, or the exercise's).
    attempts : int
        How many files the student handed in (set by the gradebook), of which ``policy`` chose the counting one.
    """

    student: str
    exercise: str
    status: str
    parts: list = field(default_factory=list)
    max_score: float = 0.0
    raw: float = 0.0
    late_days: int = 0
    penalty: float = 0.0
    score: float = 0.0
    submitted: str = ""
    due: str = ""
    attempt: int | None = None
    attempts: int = 0
    policy: str = "latest"


def final(student, exercise, result, rule=None, extension="", overrides=None, points=None):
    """The :class:`Final` of ``result`` (a :class:`~kinbook.classroom.results.SubmissionResult`, or None: missing).

    Parameters
    ----------
    rule : Rule or None
    extension : str
        The student's own due date, or "".
    overrides : dict
        ``{part: (score, why)}``.
    points : list of (part, max_score)
        The exercise's parts, for a student with no result.
    """
    rule = rule or Rule()
    overrides = overrides or {}
    due = extension or rule.due
    if result is None:
        parts = [(name, 0.0, mx, overrides.get(name)) for name, mx in (points or [])]
        raw = sum(o[0] if o else s for _, s, _, o in parts)
        mx = sum(m for _, _, m, _ in parts)
        return Final(student, exercise, "missing", parts, mx, round(raw, 4), 0, 0.0, round(raw, 4), "", due)
    parts = [(p.part, p.score, p.max_score, overrides.get(p.part)) for p in result.parts]
    raw = round(sum(o[0] if o else s for _, s, _, o in parts), 4)
    mx = sum(m for _, _, m, _ in parts)
    days = late_days(result.submitted, due, result.late and not extension)  # the LMS's mark is for its date
    penalty = round(min(rule.cap, days * rule.penalty) / 100.0 * mx, 4) if days else 0.0
    return Final(student, exercise, result.status, parts, mx, raw, days, penalty, round(max(0.0, raw - penalty), 4),
                 result.submitted, due, getattr(result, "attempt", None))
