"""Students who joined after the roster was exported: whose file it is, and re-attaching them to a newer roster.

A student enrolled after the instructor downloaded the roster has a Canvas user id (or a Moodle participant id)
that the roster does not know. Their variant was made with ``kinbook variant --student kmensah``, and their
notebook's metadata names ``kmensah``. :func:`adopt` makes such a file that student's: when the id in the path is
not on the roster and the release names an id that is not on it either, the file is graded as the student the
release names — "not on the roster", never a copying signal (a release naming a student who *is* on the roster is
still one: someone handed in a classmate's notebook).

When a newer roster is given (``--roster`` on a later ``kinbook grade``), :func:`reattach` moves every result graded
under an id the new roster maps to one of its students (``104531``, Kevin's Canvas id, → ``kmensah``) to that
student, in every table of the gradebook, and drops the orphan id: from then on the report, the exports and the
feedback know one student. A "released for another student" signal naming the student themself goes with it.
"""

from __future__ import annotations

from ..errors import GradingError
from .files import id_key, student_id
from .notebook import parse_submission
from .results import Refused

__all__ = ["adopt", "reattach", "check_matches", "STUDENT_TABLES"]

#: The gradebook's tables with a ``student`` column.
STUDENT_TABLES = ("attempts", "submissions", "parts", "mistakes", "signals", "files", "overrides", "extensions")


def adopt(entry, roster, data):
    """Give ``entry`` (its id not on ``roster``) to the student its release names, when the roster does not know
    that student either. Returns the id it had, or None when nothing changed."""
    if roster is None or entry.on_roster is not False or entry.status is not None:
        return None
    try:
        meta = parse_submission(data, metadata=True)[1]
    except Refused:
        return None
    named = meta.get("student")
    if not isinstance(named, str) or id_key(named) == id_key(entry.student):
        return None
    if roster.find(named) is not None:
        return None  # a classmate's release: the grader says so (wrong-release, a copying signal)
    sid, problem = student_id(named)
    if problem or sid != named:
        return None
    old, entry.student = entry.student, sid
    return old


def check_matches(entries, roster):
    """Stop (:class:`~kinbook.errors.GradingError`) when a roster knows none of the students the files name (at least
    two): the wrong roster, or the wrong ``--roster-id`` column — grading on would make everyone "not on the roster"
    and, for variants, every notebook "released for another student"."""
    named = sorted({e.student for e in entries if e.student and e.status in (None, "superseded")})
    if len(named) < 2 or any(e.on_roster for e in entries):
        return
    sample = ", ".join(named[:5]) + (" …" if len(named) > 5 else "")
    ids = ", ".join(f"{s.student}" + (f" (LMS id {s.lms_id})" if s.lms_id else "") for s in roster.students[:3])
    raise GradingError(f"the roster ({roster.source}, {len(roster)} students) matches none of the {len(named)} "
                       f"students the files name ({sample}); its ids look like {ids or 'nothing'}. Nothing was "
                       "graded: give the roster of this course, or the column that holds the ids the files are "
                       "named with (--roster-id; a Moodle download is named with the worksheet's Identifier, a "
                       "Canvas one with its ID).")


def reattach(book, roster):
    """Move the results of ids that are not on ``roster`` but that it maps to one of its students (an LMS id, an
    e-mail, a login) to that student; returns [(old id, student)]. One transaction."""
    known = {s.student for s in roster}
    ids = {s for (s,) in book.db.execute("SELECT DISTINCT student FROM attempts UNION SELECT DISTINCT student FROM "
                                         "files WHERE student != ''")}
    moved = []
    for old in sorted(ids - known):
        found = roster.find(old, "lms")
        if found is not None and found.student != old:
            moved.append((old, found.student))
    if not moved:
        return []
    with book.db:
        book.db.execute("BEGIN IMMEDIATE")
        for old, new in moved:
            # graded as someone else's release, and it was the student's own: graded again by the next run
            own = "SELECT attempt FROM signals WHERE student = ? AND kind = 'released-for' AND detail = ?"
            book.db.execute(f"UPDATE attempts SET source_sha256 = '' WHERE id IN ({own})", (old, new))
            book.db.execute(f"DELETE FROM signals WHERE attempt IN ({own})", (old, new))
            for table in ("submissions", "parts", "overrides", "extensions"):  # keyed by student: the new one's stay
                book.db.execute(f"DELETE FROM {table} WHERE student = ? AND exercise IN (SELECT exercise FROM {table} "
                                "WHERE student = ?)", (old, new))
            for table in STUDENT_TABLES:
                book.db.execute(f"UPDATE {table} SET student = ? WHERE student = ?", (new, old))
            book.db.execute("INSERT OR REPLACE INTO reattached (old, student) VALUES (?, ?)", (old, new))
        for exercise, student in {(e, new) for _, new in moved for (e,) in book.db.execute(
                "SELECT DISTINCT exercise FROM attempts WHERE student = ?", (new,))}:
            book.select(exercise, student)
    return moved
