"""``kinbook override`` — and its kin ``kinbook due`` and ``kinbook extend``: the instructor's decisions about a course,
stored in the gradebook beside the grades.

None of them changes a graded attempt: they are applied when a score is read (:func:`kinbook.classroom.scores.final`)
— in the exports, the report and the feedback pages — so they survive every regrade, ``--force`` and ``--regrade``.
"""

from __future__ import annotations

from ...errors import GradingError
from ..gradebook import Gradebook
from ..scores import POLICIES, parse_due

__all__ = ["override", "due", "extend"]


def _exercise(book, exercise):
    known = book.exercises()
    if exercise not in known:
        raise GradingError(f"no exercise {exercise!r} in {str(book.outdir)!r} (it has: {', '.join(known) or 'none'})")


def override(gradebook, student, exercise, part, score=None, why="", *, remove=False):
    """Set ``student``'s score on ``part`` of ``exercise`` to ``score`` with the reason ``why`` (shown to the student),
    or remove the override. Returns a line saying what was done."""
    with Gradebook(gradebook) as book:
        _exercise(book, exercise)
        points = dict(book.points(exercise))
        if part not in points:
            raise GradingError(f"{exercise} has no part {part!r} (its parts: {', '.join(points)})")
        if remove:
            book.override(exercise, student, part, None, "")
            return f"{student} {exercise} {part}: override removed"
        if score is None or not str(why).strip():
            raise GradingError("an override needs the score and --why (the reason the student will read)")
        if not 0 <= float(score) <= points[part]:
            raise GradingError(f"{exercise} part {part!r} is worth {points[part]:g}: a score from 0 to {points[part]:g}, "
                               f"got {score:g}")
        roster = book.roster()
        if not book.has(student, exercise) and (roster is None or student not in roster):
            raise GradingError(f"{student!r} has no result for {exercise} and is not on the roster")
        book.override(exercise, student, part, float(score), str(why).strip())
        return f"{student} {exercise} {part}: {float(score):g} / {points[part]:g} ({why.strip()})"


def due(gradebook, exercise, when, *, penalty=None, cap=None, policy=None):
    """Set ``exercise``'s due date (ISO 8601 with its zone), the penalty in percent of its points per started day late,
    the cap, and the attempt policy. Returns a line saying what is now in force."""
    parse_due(when)
    if policy is not None and policy not in POLICIES:
        raise GradingError(f"policy must be one of {', '.join(POLICIES)}, got {policy!r}")
    with Gradebook(gradebook) as book:
        rule = book.set_rule(exercise, due=when, penalty=penalty, cap=cap, policy=policy)
    return (f"{exercise}: due {rule.due}, {rule.penalty:g} % of the points per started day late, at most "
            f"{rule.cap:g} %; policy {rule.policy}")


def extend(gradebook, student, exercise, when, why=""):
    """Give ``student`` their own due date for ``exercise``. Returns a line saying so."""
    parse_due(when)
    with Gradebook(gradebook) as book:
        book.extend(exercise, student, when, why)
    return f"{student} {exercise}: due {when}" + (f" ({why})" if why else "")
