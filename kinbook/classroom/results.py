"""What grading produces: :class:`SubmissionResult` (one submission) made of :class:`PartGrade` (one row of
grades.csv), and the statuses they can have. Imported by both the grader (:mod:`.grade`) and the gradebook
(:mod:`.gradebook`), which do not import each other.

Statuses (one per part; the submission's status is the worst of them):

=================  ==========================================================================================
ok                 the answer was read and checked (its score may be anything from 0 to full)
missing-answer     the variable was not assigned (cell left as released, or it raised before assigning)
error              the answer is not gradable data (or too large to read), or the kernel died
timeout            the notebook used up its ``timeout`` seconds of CPU time (or, waiting instead of computing, did
                   not finish by the wall-clock backstop)
memory             the notebook exceeded its memory budget
tampered           a locked code cell differs from the release (or is missing): not run, 0 points (edited
                   locked text cells are restored from the release instead)
wrong-release      the notebook was released for another student (a copying signal for the instructor), or
                   is the generic release where each student got their own: not run, 0 points
corrupt-notebook   the file is not a readable notebook: not run, 0 points
too-large          the file is over the size or cell-count cap: refused before parsing, 0 points
refused            a symbolic link, hard link, device, FIFO or socket in ``collected/`` (never followed or
                   opened), a file replaced while it was being read, or the exercise's source itself: 0 points
bad-id             the student id taken from the path is too long: not graded (rename and grade again)
duplicate-id       two files give the same student under different spellings (ids equal once case and Unicode
                   forms are folded): neither is graded
grader-error       the grader failed before any code of the notebook ran (a kernel that did not start), each of
                   the times it tried: not graded and no score (blank in every export, not 0; an earlier graded
                   attempt counts meanwhile) — the next runs grade it again, without ``--force``, three runs at
                   most; then the run prints the command that reproduces the failure. A limit a submission can
                   reach before its code runs (size, cells, decoding, the job's frame) is never this: it is the
                   submission's (``too-large``, ``corrupt-notebook``)
=================  ==========================================================================================

Entries of ``collected/`` that are not a student's result are listed, not graded (:mod:`.files`): ``ignored``
(not a notebook, a hidden name, not named after the exercise …) and ``superseded`` (an earlier attempt of a
student whose latest one is graded). A student on the roster with no submission is ``missing`` in the exports.
"""

from __future__ import annotations

import html
from dataclasses import asdict, dataclass, field

__all__ = ["STATUSES", "UNGRADED", "ungraded_notice", "stopped_notice", "PartGrade", "SubmissionResult", "Refused", "worst"]

STATUSES = ("ok", "missing-answer", "error", "timeout", "memory", "tampered", "wrong-release", "corrupt-notebook",
            "too-large", "refused", "bad-id", "duplicate-id", "grader-error")
#: Statuses of a submission that was not graded through no doing of the student's: no score (blank, not 0).
UNGRADED = ("grader-error",)
_SEVERITY = {s: i for i, s in enumerate(STATUSES)}


class Refused(Exception):
    """A submission that is not graded, before anything of it is run: ``status`` (one of :data:`STATUSES`, e.g.
    ``refused``, ``too-large``, ``corrupt-notebook``) and a message for the gradebook."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status, self.message = status, message


def ungraded_notice(results):
    """The line saying which of ``results`` the grader could not grade (:data:`UNGRADED`), or ""."""
    ungraded = [r.student for r in results if r.status in UNGRADED]
    if not ungraded:
        return ""
    return (f"not graded, through a failure of the grader's, not theirs ({len(ungraded)}; no score recorded): "
            + ", ".join(ungraded[:20]) + (" …" if len(ungraded) > 20 else "") + " — run the same command again "
            "to grade them (a file the grader fails on in three runs is then left to you, with the command that "
            "reproduces it)")


def stopped_notice(why, kept, of, where):
    """The line of a run stopped by SIGTERM (``why`` the SystemExit its handler raised) or Ctrl-C
    (KeyboardInterrupt): what was kept, where, and how to go on."""
    how = "Ctrl-C" if isinstance(why, KeyboardInterrupt) else "SIGTERM"
    return (f"kinbook: stopped by {how}: {kept} of {of} submission(s) graded in this run are kept in {where} (with "
            "every earlier result); the exports are written now. Run the same command again to grade the rest.")


def worst(statuses, default="ok"):
    """The most severe of ``statuses`` (in the order of :data:`STATUSES`)."""
    return max(statuses, key=lambda s: _SEVERITY[s], default=default)


@dataclass
class PartGrade:
    """One row of grades.csv.

    Attributes
    ----------
    reference : str
        How the student's code obtained the answer from kinbook's own reference, when it did (information for
        the instructor, not a penalty; see :mod:`kinbook.classroom.reference_use`), else "".
    answer : str
        The student's answer as the grader read it (bounded text), for the feedback page and the report.
    cell : str
        Where the answer was assigned, as the student sees the notebook ("cell 7 of 12: (a) Φ of …"), and its code.
    mistakes : list of (code, row)
        Catalogue codes of the mistakes the checker named, each with the row it was found in ("" for the whole
        answer): stored as rows of the gradebook, so that the class report is a query.
    """

    part: str
    score: float
    max_score: float
    status: str
    message: str = ""
    html: str = ""
    reference: str = ""
    answer: str = ""
    cell: str = ""
    mistakes: list = field(default_factory=list)


@dataclass
class SubmissionResult:
    """The grading of one submission.

    Attributes
    ----------
    isolation : str
        ``"bubblewrap"`` (the notebook ran in the operating-system sandbox) or ``"none"`` (``--no-isolation``:
        the audit hook only), then the limits that were in force: ``"bubblewrap; cgroup v1 (memory, pids,
        cpu)"`` (a control group held all the sandbox's processes), ``"bubblewrap; rlimits, no fork"``
        (per-process limits, the kernel unable to fork); ``""`` when nothing was run.
    submitted, submitted_from, late :
        When it was handed in (ISO 8601), read from the LMS (``"lms"``: a pattern's ``time`` group) or the file's
        time (``"file"``), never from a date in a file's name; and whether the LMS marked it late.
    signals : list of (kind, detail)
        Signals for the instructor (never told to the student): ``("released-for", "<other id>")`` for a
        notebook released for another student, ``("names-another", …)`` for a file whose own name names another
        student than its folder's, ``("look-alike", …)`` for an id equal to another student's once case and
        Unicode forms are folded.
    source_sha256 : str
        The source notebook that graded it.
    attempt : int or None
        Its row in the gradebook's history (set when read from the gradebook).
    """

    student: str
    exercise: str
    submission: str
    sha256: str
    status: str
    message: str
    parts: list = field(default_factory=list)
    seconds: float = 0.0
    isolation: str = ""
    submitted: str = ""
    submitted_from: str = ""
    late: bool = False
    signals: list = field(default_factory=list)
    source_sha256: str = ""
    attempt: int | None = None

    @property
    def score(self):
        return round(sum(p.score for p in self.parts), 4)

    @property
    def max_score(self):
        return sum(p.max_score for p in self.parts)

    def to_dict(self):
        return asdict(self)

    def __repr__(self):
        return (f"SubmissionResult({self.student!r}, {self.exercise!r}: {self.status}, "
                f"{self.score:g}/{self.max_score:g})")

    def _repr_html_(self):
        rows = "".join(f"<tr><td>{html.escape(p.part)}</td><td>{p.score:g} / {p.max_score:g}</td>"
                       f"<td>{html.escape(p.status)}</td><td>{html.escape(p.message[:200])}</td></tr>"
                       for p in self.parts)
        return (f"<p><b>{html.escape(self.student)}</b> — {html.escape(self.exercise)}: {self.score:g} / "
                f"{self.max_score:g} ({html.escape(self.status)})</p><table><tr><th>part</th><th>score</th>"
                f"<th>status</th><th>message</th></tr>{rows}</table>")
