"""What a grading run does with each entry of ``collected/`` before any notebook runs.

:func:`intake` checks the source against the gradebook's pin (a changed source stops the run unless
``regrade``), lists every entry (:func:`kinbook.classroom.files.collect`), and decides for each one: grade it, skip
it (this very file was graded already with this source), keep it as history (an earlier attempt), or record why it
is not graded. Every entry becomes a row of the gradebook's ``files`` table and of ``collection.csv``; the lines
printed say what happened to every file that is not simply graded.
"""

from __future__ import annotations

import hashlib
import shlex
from dataclasses import dataclass, field

from ..errors import GradingError
from .choice import several_line
from .enrolment import adopt, check_matches
from .files import collect, read_entry
from .results import UNGRADED, Refused, SubmissionResult

__all__ = ["intake", "Intake", "SourceChanged", "GRADER_RUNS"]

#: Runs that try a file the grader failed on (``grader-error``) before it is left to the instructor, with the command
#: that reproduces the failure (``--force`` tries it again).
GRADER_RUNS = 3
#: Verdicts reached without running anything, which depend on how the run is graded (``--generic``): reached again
#: by every run (it costs no sandbox), never "graded before" — a run with the wrong option leaves nothing behind.
UNRUN = ("tampered", "wrong-release")


class SourceChanged(GradingError):
    """The source differs from the one that graded the gradebook's results of this exercise."""


@dataclass
class Intake:
    """The plan of a run.

    Attributes
    ----------
    todo : list of Entry
        To grade, in order; ``entry.replace`` is the attempt regraded in place (or None: a new attempt).
    refused : list of Entry
        Not gradable, recorded as the student's result (0 points) because the student has no other file.
    skipped : int
    off_roster : list of str
    stale : list of str
        Students whose result was graded with an earlier source and whose file was not among the submissions given.
    """

    todo: list = field(default_factory=list)
    refused: list = field(default_factory=list)
    skipped: int = 0
    off_roster: list = field(default_factory=list)
    stale: list = field(default_factory=list)
    entries: dict = field(default_factory=dict)
    reproduce: tuple = ()


def check_pin(book, src, regrade):
    """Stop (:class:`SourceChanged`) when ``src`` is not the source the gradebook's results were graded with."""
    pin = book.pin(src.exercise)
    if pin is not None and pin[0] != src.sha256 and not regrade:
        n = book.db.execute("SELECT COUNT(*) FROM submissions WHERE exercise = ?", (src.exercise,)).fetchone()[0]
        raise SourceChanged(
            f"{src.exercise}: the source {str(src.path)!r} (sha256 {src.sha256[:12]}…) is not the one that graded the "
            f"{n} result(s) in {str(book.outdir)!r} ({pin[1]!r}, sha256 {pin[0][:12]}…, pinned {pin[2]}). Nothing was "
            "graded. To grade every submission again with the new source, run again with --regrade; to keep the "
            "results, grade with the old source.")


def intake(book, run, src, submissions, *, force=False, regrade=False, policy=None, pattern=None, roster=None,
           max_bytes, progress=None, file_times=False, reproduce=()):
    """Plan a run (see the module docstring) and record every entry that is not graded by it.

    Parameters
    ----------
    book : Gradebook
    run : int
    src : Source
    submissions : list of paths
    force : bool
        Grade again files already graded.
    regrade : bool
        The source changed: grade every file again, and pin the new source.
    policy : str or None
        ``latest`` or ``best``; None keeps the exercise's (default latest). Stored as the exercise's rule.
    pattern : str or None
        ``--id-pattern``: a ready pattern's name or a regular expression.
    roster : Roster or None
        Stored in the gradebook when given; else the stored one (if any) maps the ids.
    reproduce : tuple of str
        The run's options (``--timeout``, ``--memory``, ``--generic`` …) for the command that reproduces a grader
        failure.
    """
    check_pin(book, src, regrade)
    say = progress or (lambda item: None)
    given, roster = roster, roster if roster is not None else book.roster()
    entries = collect(submissions, src.exercise, max_bytes=max_bytes, pattern=pattern, roster=roster,
                      policy=policy or book.rule(src.exercise).policy, file_times=file_times)
    if given is not None:
        check_matches(entries, given)  # a roster whose ids match no file stops here, before anything is stored
        for old, new in book.set_roster(given):
            say(f"re-attached  {old} → {new}: on the new roster, so every result of {old} is now {new}'s (report, "
                f"exports and feedback drop {old})")
    if policy is not None and policy != book.rule(src.exercise).policy:
        book.set_rule(src.exercise, policy=policy)
    policy = book.rule(src.exercise).policy
    book.set_pin(src)
    plan = Intake(reproduce=tuple(reproduce))
    for e in entries:
        _digest(e, src, max_bytes)
        if e.on_roster is False and e.sha256:
            try:
                old = adopt(e, roster, read_entry(e, max_bytes))
            except Refused:  # replaced since it was read: refused when its turn comes
                old = None
            if old is not None:
                say(f"enrolled  {e.path}: {old} is not on the roster, and this notebook was released for "
                    f"{e.student}, who is not either: graded as {e.student} (not on the roster; not a copying signal)")
        if e.on_roster is False and e.student and e.student not in plan.off_roster and e.result:
            plan.off_roster.append(e.student)
        _decide(book, run, src, e, plan, force or regrade, say)
    plan.entries = {e.path: e for e in entries}
    by_student = {}
    for e in plan.todo:
        by_student.setdefault(e.student, []).append(e)
    for student, mine in by_student.items():
        if several_line(student, mine, policy):
            say(several_line(student, mine, policy))
    graded_now = {e.student for e in plan.todo} | {e.student for e in plan.refused}
    plan.stale = [s for s in book.stale(src.exercise) if s not in graded_now]
    if plan.skipped:
        say(f"skipped {plan.skipped} file(s) graded before (the same file with the same source; --force grades them "
            "again)")
    outcomes = {}
    for e in entries:
        outcomes[e.status or "gradable"] = outcomes.get(e.status or "gradable", 0) + 1
    say(f"{len(entries)} entr{'y' if len(entries) == 1 else 'ies'} found: "
        + ", ".join(f"{n} {what}" for what, n in sorted(outcomes.items(), key=lambda kv: -kv[1]))
        + f" — {len(plan.todo)} to grade now (every entry and what became of it: collection.csv)")
    if plan.off_roster:
        say(f"not on the roster ({len(plan.off_roster)}): {', '.join(plan.off_roster[:20])}"
            + (" …" if len(plan.off_roster) > 20 else "") + " — graded, and listed in the report")
    return plan


def _digest(e, src, max_bytes):
    """Read a gradable entry once for its sha256 (a file identical to the source is refused)."""
    e.sha256 = ""
    if e.status not in (None, "superseded"):
        return
    try:
        e.sha256 = hashlib.sha256(read_entry(e, max_bytes)).hexdigest()
    except Refused as exc:
        e.status, e.message = exc.status, exc.message
        return
    if e.sha256 == src.sha256:
        e.status, e.message, e.result = "refused", "identical to the instructor's source notebook: not graded", True


def _decide(book, run, src, e, plan, force, say):
    """What becomes of one entry: a row of the ``files`` table, and the plan's todo, refused or skipped."""
    ex, digest = src.exercise, e.sha256
    if e.status == "ignored":
        book.record_file(run, ex, e, "ignored", e.message)
        say(f"ignored   {e.path}: {e.message}")
        return
    if e.status == "superseded":
        if book.attempt_of(ex, e.student, digest) is None:
            book.record(_history(src, e), run)
        book.record_file(run, ex, e, "superseded", e.message, digest)
        say(f"history   {e.path}: {e.message}")
        return
    previous = book.attempt_of(ex, e.student, digest)
    if e.status is not None and not e.result:  # refused beside a gradable file of the same student: listed
        book.record_file(run, ex, e, e.status, e.message, digest)
        say(f"{e.status:9} {e.path}: {e.message}")
    elif e.status is not None:  # refused, and the student's only file: their result
        if previous is not None and not force:
            plan.skipped += 1
            book.record_file(run, ex, e, "skipped", "recorded before: " + e.message)
            return
        e.replace = previous[0] if previous is not None else None
        plan.refused.append(e)
        book.record_file(run, ex, e, e.status, e.message, digest)
    elif (previous is not None and previous[2] in UNGRADED and not force
          and book.runs_graded(ex, e.student, digest) >= GRADER_RUNS):
        plan.skipped += 1
        command = " ".join(shlex.quote(str(a)) for a in (
            "kinbook", "grade", src.path, e.path, "-o", "kinbook-reproduce", *plan.reproduce))
        why = (f"the grader failed on this file in {GRADER_RUNS} runs (not the student's doing; no score): not tried "
               f"again without --force — reproduce it with: {command}")
        book.record_file(run, ex, e, "skipped", why, digest)
        say(f"grader-error {e.path}: {why}")
    elif (previous is not None and previous[1] == src.sha256 and previous[2] not in ("superseded", *UNGRADED, *UNRUN)
          and not force):
        plan.skipped += 1
        book.record_file(run, ex, e, "skipped", "graded before (same file, same source)", digest)
    else:
        e.replace = previous[0] if previous is not None else None
        book.record_file(run, ex, e, "graded", "", digest)
        plan.todo.append(e)


def _history(src, e):
    """An earlier attempt kept, ungraded, as history."""
    return SubmissionResult(e.student, src.exercise, e.path, e.sha256, "superseded", e.message, [], 0.0, "",
                            e.submitted, e.submitted_from, e.late, [], src.sha256)


def annotate(result, plan, src):
    """Stamp a result with what the plan knows of its file (time, late mark, the source); returns the attempt to
    replace, or None."""
    e = plan.entries.get(result.submission)
    result.source_sha256 = src.sha256
    if e is None:
        return None
    result.submitted, result.submitted_from, result.late = e.submitted, e.submitted_from, e.late
    result.signals = list(result.signals) + [s for s in e.signals if s not in result.signals]
    return e.replace
