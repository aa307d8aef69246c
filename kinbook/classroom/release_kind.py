"""Which release a submission is — the generic release, the student's own variant, another student's — read from
the notebook as data (never run), before any of its code runs.

The instructor's mistake (most students handed in the other kind of release than the one graded) stops a run:
:func:`check_release_kinds`, one vote per student. A student's own mistake or copying is that student's verdict:
:func:`released_for` (``wrong-release``, never ``tampered``).
"""

from __future__ import annotations

import re

from ..errors import GradingError
from .files import id_key
from .notebook import parse_submission
from .results import Refused
from .sanitize import clean

__all__ = ["release_kind", "release_kinds", "check_release_kinds", "released_for"]


def release_kind(data):
    """"generic" or "student" as the notebook's kinbook metadata says, None when it cannot tell."""
    try:
        meta = parse_submission(data, metadata=True)[1]
    except Refused:
        return None
    if "student" not in meta:
        return None
    return "generic" if meta["student"] is None else "student"


def release_kinds(entries, read):
    """{student: the kinds of release of their files that can still be read} — ``read(entry)`` gives ``(bytes,
    refusal)``; a file that cannot be read is refused when its turn comes."""
    kinds = {}
    for entry in entries:
        data, refused = read(entry)
        if refused is None:
            kinds.setdefault(entry.student, set()).add(release_kind(data))
    return kinds


def check_release_kinds(kinds, per_student, exercise):
    """Stop before any grading when most *students* handed in the other kind of release than the one graded: the
    generic release graded per student (every student would be refused), or per-student variants graded with
    ``--generic``. That is the instructor's mistake, not the students'. Each student is one vote, whatever number
    of files they handed in: one student's three copies of the generic release are that student's problem
    (``wrong-release``), never a stop of the class."""
    wanted = "student" if per_student else "generic"
    votes = [k - {None} for k in kinds.values() if k - {None}]
    known = len(votes)
    wrong = sum(1 for k in votes if wanted not in k)
    if not known or wrong * 2 <= known:
        return
    if per_student:
        raise GradingError(f"{wrong} of {known} students handed in {exercise}'s generic release (made by "
                           "`kinbook release`), not their per-student variants: grade them with --generic. Nothing "
                           "was graded.")
    raise GradingError(f"{wrong} of {known} students handed in per-student variants of {exercise} (made by "
                       "`kinbook variant`): grade them without --generic. Nothing was graded.")


RELEASED_FOR = re.compile(r"#[^\S\n]*parameters of student (['\"])(.{1,200}?)\1[^\S\n]*$", re.MULTILINE)


def released_for(meta, cells, student, per_student, generic=False):
    """``(why, other student)`` when the notebook is not this student's release, else ``(None, None)``: the
    notebook released for another student (its metadata or its parameters cell name them: a copying signal for
    the instructor, not tampering), or the generic release where each student got their own (no other student)."""
    named = meta.get("student") if isinstance(meta.get("student"), str) else None
    if named is None:
        for c in cells:
            if c["cell_type"] == "code":
                m = RELEASED_FOR.search(c["source"])
                if m:
                    named = m.group(2)
                    break
    if named is not None and id_key(named) != id_key(student):
        return f"this notebook was released for {clean(named, 80)}, not for {student}", named
    if per_student and "student" in meta and meta["student"] is None:
        return f"this is the exercise's generic release, not the notebook released for {student}", None
    if generic and named is not None:  # the student's own variant, graded as the generic release: not run,
        return (f"this is the notebook released for {student} (a per-student variant), and the exercise was graded "
                "as its generic release (--generic): grade it without --generic"), None  # never called tampered
    return None, None
