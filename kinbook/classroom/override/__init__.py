"""``kinbook override`` — and its kin ``kinbook due`` and ``kinbook extend``: the instructor's decisions about a course,
stored in the gradebook beside the grades.

None of them changes a graded attempt: they are applied when a score is read (:func:`kinbook.classroom.scores.final`)
— in the exports, the report and the feedback pages — so they survive every regrade, ``--force`` and ``--regrade``.

Each names what it changes by the gradebook's own names: an exercise the gradebook does not know (``ex1`` for
``ex01``), a student who is neither graded nor on the roster, a part the exercise does not have, is an
:class:`~kinbook.errors.UnknownNameError` giving the closest known name — a typo never becomes a new exercise or
student. Students are matched under the one id rule (:mod:`kinbook.classroom.ids`): ``ANA`` finds ``ana``.
"""

from __future__ import annotations

from ...errors import GradingError, UnknownNameError
from ..gradebook import Gradebook
from ..ids import check_id, closest, find_id
from ..scores import POLICIES, parse_due

__all__ = ["override", "due", "extend", "known_exercise", "known_student"]


def _unknown(lead, name, known):
    near = closest(name, known)
    hint = f": did you mean {near!r}?" if near else ""
    shown = ", ".join(sorted(known)[:12]) + (" …" if len(known) > 12 else "") if known else "none"
    return UnknownNameError(f"{lead}{hint} (known: {shown})", name=name, closest=near)


def known_exercise(book, exercise):
    """``exercise`` as the gradebook knows it (graded, pinned or given a rule), else
    :class:`~kinbook.errors.UnknownNameError` with the closest name."""
    known = book.exercises()
    found = find_id(check_id(exercise, "exercise name"), known)
    if found is None:
        raise _unknown(f"no exercise {exercise!r} in the gradebook {str(book.path)!r}", exercise, known)
    return found


def known_student(book, student, exercise=None):
    """``student`` as the gradebook knows them (on the stored roster, or with an attempt — of ``exercise`` when
    given — under any spelling with the same :func:`~kinbook.classroom.ids.id_key`), else
    :class:`~kinbook.errors.UnknownNameError` with the closest id."""
    student = check_id(student)
    roster = book.roster()
    known = {s.student for s in roster} if roster is not None else set()
    known |= {a[2] for a in book.attempts(exercise=exercise)}
    found = find_id(student, known)
    if found is None:
        what = f"graded in {exercise}" if exercise else "graded"
        raise _unknown(f"no student {student!r} in the gradebook {str(book.path)!r} (neither {what} nor on the "
                       "roster)", student, known)
    return found


def override(gradebook, student, exercise, part, score=None, why="", *, remove=False):
    """Set ``student``'s score on ``part`` of ``exercise`` to ``score`` with the reason ``why`` (shown to the student),
    or remove the override. Returns a line saying what was done."""
    if not remove and (score is None or not str(why).strip()):
        raise GradingError("an override needs the score and --why (the reason the student will read)")
    with Gradebook(gradebook, create=False) as book:
        exercise = known_exercise(book, exercise)
        points = dict(book.points(exercise))
        if part not in points:
            raise _unknown(f"{exercise} has no part {part!r}", part, list(points))
        student = known_student(book, student, exercise)
        if remove:
            if part not in book.overrides(exercise, student).get((exercise, student), {}):
                raise GradingError(f"{student} {exercise} {part}: there is no override to remove")
            book.override(exercise, student, part, None, "")
            return f"{student} {exercise} {part}: override removed"
        if not 0 <= float(score) <= points[part]:
            raise GradingError(f"{exercise} part {part!r} is worth {points[part]:g}: a score from 0 to {points[part]:g}, "
                               f"got {score:g}")
        book.override(exercise, student, part, float(score), str(why).strip())
        return f"{student} {exercise} {part}: {float(score):g} / {points[part]:g} ({why.strip()})"


def due(gradebook, exercise, when, *, penalty=None, cap=None, policy=None):
    """Set ``exercise``'s due date (ISO 8601 with its zone), the penalty in percent of its points per started day late,
    the cap, and the attempt policy. Returns a line saying what is now in force."""
    parse_due(when)
    if policy is not None and policy not in POLICIES:
        raise GradingError(f"policy must be one of {', '.join(POLICIES)}, got {policy!r}")
    with Gradebook(gradebook, create=False) as book:
        exercise = known_exercise(book, exercise)
        rule = book.set_rule(exercise, due=when, penalty=penalty, cap=cap, policy=policy)
    return (f"{exercise}: due {rule.due}, {rule.penalty:g} % of the points per started day late, at most "
            f"{rule.cap:g} %; policy {rule.policy}")


def extend(gradebook, student, exercise, when=None, why="", *, remove=False):
    """Give ``student`` their own due date for ``exercise`` — or, with ``remove``, take it back (the exercise's due
    date applies again). Returns a line saying so."""
    if remove and when is not None:
        raise GradingError("extend --remove takes no date: the exercise's own due date applies again")
    if not remove:
        if when is None:
            raise GradingError("extend needs the student's due date (or --remove to take an extension back)")
        parse_due(when)
    with Gradebook(gradebook, create=False) as book:
        exercise = known_exercise(book, exercise)
        student = known_student(book, student)
        if remove:
            if not book.extension(exercise, student):
                raise GradingError(f"{student} has no extension for {exercise}: nothing to remove")
            book.extend(exercise, student, "", "")
            return f"{student} {exercise}: extension removed (due {book.rule(exercise).due or 'date not set'})"
        book.extend(exercise, student, when, why)
    return f"{student} {exercise}: due {when}" + (f" ({why})" if why else "")
