"""Grading submitted notebooks (``kinbook grade``).

The instructor's source notebook is read once, hashed and its code compiled before any student code runs
(:func:`~kinbook.classroom.notebook.load_source`); the references are built from that in-memory copy, in the
grader's process (:func:`kinbook.classroom.variant.references`). If the file on disk changes during the run,
the run stops (the results recorded until then are kept).

For each submission, found in ``collected/`` without following any link (:func:`kinbook.classroom.files.collect`):
read it once (never modify it), refuse it before parsing when too large, compare its locked cells with the
release (by content, not by cell id), run its code cells in the sandbox (:mod:`kinbook.classroom.sandbox`:
bubblewrap around a kernel with its own audit hook), read the named answers as bounded data
(:mod:`kinbook.classroom.serialize`), and grade them with kinbook's checkers here, in the grader's process.
Which answers came from kinbook's own reference is read from the submitted code
(:mod:`kinbook.classroom.reference_use`) and reported, not penalized. Statuses: :mod:`kinbook.classroom.results`.

A batch records each result in the gradebook (:mod:`kinbook.classroom.gradebook`, SQLite) as soon as it is
graded; a killed run keeps them all and the next run grades only what is left. A submission graded before is
skipped — unless its file changed (another sha256): then it is reported "changed since graded", and graded
again only with ``force``.
"""

from __future__ import annotations

import hashlib
import os
import signal
import sys
import threading
import time
import warnings
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from multiprocessing.util import Finalize

import numpy as np

from ..errors import GradingError, KinbookError
from ..grading.catalogue import MISTAKES, explain
from ..grading.item import seed_from
from .answers import describe, mistake_rows
from .editions import carry_over, class_would_be_tampered, earlier_sources, edition_of, editions
from .feedback import write_pages
from .files import Entry, collect, read_entry, student_id
from .gradebook import Gradebook
from .intake import annotate, check_pin, intake
from .notebook import (
    MAX_FILE_BYTES,
    checksum,
    find_parameters,
    grader_segments,
    load_source,
    parse_submission,
    readable,
)
from .reference_use import as_run, exercise_calls, reference_use
from .release_kind import check_release_kinds, release_kinds, released_for
from .results import STATUSES, PartGrade, Refused, SubmissionResult, stopped_notice, ungraded_notice, worst
from .sandbox import Sandbox
from .sandbox.bwrap import check
from .sandbox.cgroup import machine_memory_mb
from .sandbox.protocol import die_with_parent
from .sanitize import clean, clean_result
from .serialize import decode_answers
from .variant import references, student_parameters

__all__ = ["STATUSES", "PartGrade", "SubmissionResult", "grade_submission", "grade", "check_options",
           "NO_ISOLATION_WARNING"]

#: Entries an answer may have beyond twice its reference's before it is refused unchecked (see _too_large).
MAX_EXTRA_ENTRIES = 16
NO_ISOLATION_WARNING = ("grading WITHOUT isolation (--no-isolation): students' code runs as your user, fenced only "
                        "by an in-process audit hook; recorded as 'isolation: none' in the gradebook")


def _all_parts(parts, status, message):
    return [PartGrade(p.name, 0.0, p.points, status, message) for p in parts]


def _entries(value):
    """Entries of a decoded answer (a number, an array, a sympy matrix, or rows mixing expressions and text)."""
    if isinstance(value, list):
        return sum(len(row) if isinstance(row, list) else 1 for row in value)
    shape = getattr(value, "shape", ())
    return int(np.prod(shape)) if shape else 1


def _too_large(p, decoded):
    """Why an answer (or the student's own Φ it is checked against) is too much larger than the part's
    reference to be checked, or None. A checker's time grows with the answer's rows (each one is compared with
    each reference row and its catalogued variants: 100 rows against a four-bar's Φ took 46 s of the grader's
    time, 2,000 rows some 15 minutes), and an answer with more than twice the reference's entries is wrong
    whatever they are."""
    from ..grading.target import NotATarget, target_for  # import time: grading.target loads sympy

    try:
        if p.checker.against == "target":
            target = target_for(p.target)
            own = len(target.rows)
            reference = own * (len(target.cols) if p.checker.quantity.per_coordinate else 1)
        else:
            reference, own = _entries(np.asarray(p.expected, dtype=object)), None
    except (NotATarget, KinbookError, ValueError, TypeError):  # a reference the checker will reject itself
        return None
    names = [(p.answer, reference)]
    if own and isinstance(p.options.get("phi"), str):
        names.append((p.options["phi"], own))
    for name, size in names:
        limit = 2 * size + MAX_EXTRA_ENTRIES
        if name in decoded and _entries(decoded[name]) > limit:
            return (f"`{name}` has {_entries(decoded[name]):,} entries where the reference has {size:,}: an answer "
                    f"of more than {limit:,} is not checked")
    return None


def check_memory(memory):
    """Refuse a memory budget (MB) that is not positive or more than this machine has (before anything runs)."""
    have = machine_memory_mb()
    if not memory > 0:
        raise GradingError(f"--memory must be a positive number of megabytes, got {memory!r}")
    if have is not None and memory > have:
        raise GradingError(f"--memory {memory:g} MB is more than this machine has ({have:,} MB): each notebook "
                           f"may use at most {have:,} MB (and --jobs N runs N notebooks at once)")


def check_options(*, timeout=None, memory=None, jobs=None, **flags):
    """The grading options as the command line checks them, for callers of the library too: ``timeout`` and
    ``memory`` positive finite numbers, ``jobs`` a whole number from 1 to 1024, every flag True or False (a
    truthy text such as ``"no"`` would switch it on). Raises :class:`~kinbook.errors.GradingError` naming the
    option."""
    for name, value in (("timeout", timeout), ("memory", memory)):
        if value is None:
            continue
        ok = not isinstance(value, (bool, np.bool_)) and isinstance(value, (int, float, np.integer, np.floating))
        if not ok or not np.isfinite(value) or value <= 0:
            raise GradingError(f"`{name}` must be a positive finite number, got {value!r}"[:200])
    if jobs is not None and (isinstance(jobs, (bool, np.bool_)) or not isinstance(jobs, (int, np.integer))
                             or not 1 <= jobs <= 1024):
        raise GradingError(f"`jobs` must be a whole number from 1 to 1024, got {jobs!r}"[:200])
    for name, value in flags.items():
        if not isinstance(value, (bool, np.bool_)):
            raise GradingError(f"`{name}` must be True or False, got {value!r}"[:200])


def _contents(entries, with_entries=False):
    """The bytes of each entry that can still be read (the others are refused when their turn comes); with
    ``with_entries``, (student, bytes)."""
    for entry in entries:
        data, refused = _read_again(entry)
        if refused is None:
            yield (entry.student, data) if with_entries else data


def _refused(source, entry, status, message, isolation=""):
    parts = references(source)
    return SubmissionResult(entry.student, source.exercise, entry.path, "", status, message,
                            _all_parts(parts, status, message), 0.0, isolation)


def _needs_a_real_machine():
    """Grading runs each submission in sandboxed processes: a browser (Pyodide, JupyterLite) cannot start one."""
    if sys.platform == "emscripten":
        raise GradingError(
            "grading needs a real machine: `kinbook grade` runs each submission in its own sandboxed process "
            "(bubblewrap, on Linux), and a browser (Pyodide, JupyterLite) cannot start processes. In the browser, "
            "kinbook's checkers (kinbook.grading.check_phi, …) still give feedback on your answers.")


def grade_submission(source, submission, *, student=None, timeout=60.0, memory=1000, generic=False,
                     reveal_hidden=False, isolation=True, sandbox=None):
    """Grade one submitted notebook.

    Parameters
    ----------
    source : path or Source
        The instructor's source notebook.
    submission : path
        The submitted notebook (read once, never modified; a link, device or FIFO is refused, not followed).
    student : str, optional
        Default: from the path (``<student>/<exercise>.ipynb``, ``<exercise>-<student>.ipynb`` or
        ``<student>.ipynb``).
    timeout : float
        CPU seconds for running the notebook (the kernel's; a wall-clock backstop stops one that waits).
    memory : float
        Megabytes the notebook may allocate.
    generic : bool
        The exercise has parameters but students got the generic release (defaults), not variants.
    reveal_hidden : bool
        Put the checkers' full messages (which may quote the expected value) of hidden checks in the
        gradebook and the feedback; by default they only say whether the answer is correct.
    isolation : bool
        Run the notebook inside bubblewrap (the default; :class:`~kinbook.classroom.sandbox.IsolationUnavailable`
        where it cannot be). False: the audit hook and resource limits only.
    sandbox : kinbook.classroom.sandbox.Sandbox, optional
        A running sandbox to use (a batch keeps one per grading process); by default one is started for this
        call and stopped after it.

    Returns
    -------
    SubmissionResult
    """
    check_options(timeout=timeout, memory=memory, generic=generic, reveal_hidden=reveal_hidden, isolation=isolation)
    _needs_a_real_machine()
    check_memory(memory)
    source = load_source(source)
    entries = collect([submission], source.exercise, max_bytes=MAX_FILE_BYTES)
    entry = entries[0] if entries else Entry(str(submission), ".", (os.path.basename(str(submission)),), None,
                                             "unknown", "refused", "not found")
    if student is not None:
        entry.student, bad = student_id(student)
        if bad and not entry.status:
            entry.status, entry.message = "bad-id", bad
    if entry.status:
        return _refused(source, entry, entry.status, entry.message)
    try:
        data = read_entry(entry, MAX_FILE_BYTES)
    except Refused as exc:
        return _refused(source, entry, exc.status, exc.message)
    if sandbox is None:
        with Sandbox(isolation) as sb:
            return clean_result(_grade_bytes(source, entry, data, timeout=timeout, memory=memory, generic=generic,
                                             reveal_hidden=reveal_hidden, sandbox=sb))
    return clean_result(_grade_bytes(source, entry, data, timeout=timeout, memory=memory, generic=generic,
                                     reveal_hidden=reveal_hidden, sandbox=sandbox))


def _grade_bytes(source, entry, data, *, timeout, memory, generic, reveal_hidden, sandbox, earlier=()):
    """Grade the bytes of one submission (read already) with a running sandbox."""
    t0 = time.monotonic()
    student = entry.student
    digest = hashlib.sha256(data).hexdigest()
    values = None
    if find_parameters(source.nb) is not None and not generic:
        values = student_parameters(source, student)
    parts = references(source, values)
    isolation = "bubblewrap" if sandbox.isolation else "none"

    def done(status, message, grades, ran=None):
        return SubmissionResult(student, source.exercise, entry.path, digest, status, message, grades,
                                round(time.monotonic() - t0, 3), f"{isolation}; {ran}" if ran else "")

    if digest == source.sha256:
        msg = "the file is the exercise's source notebook itself, not a submission: not run"
        return done("refused", msg, _all_parts(parts, "refused", msg))
    try:
        data = readable(data)  # what the sandbox gets too: nbformat 4, no 50 MB of saved output
        cells, meta = parse_submission(data, metadata=True)
    except Refused as exc:
        return done(exc.status, exc.message, _all_parts(parts, exc.status, exc.message))
    other, named = released_for(meta, cells, student, values is not None, generic=generic and values is None
                                 and find_parameters(source.nb) is not None)
    if other:
        res = done("wrong-release", other, _all_parts(parts, "wrong-release", other))
        if named is not None:  # a copying signal, for the instructor's report
            res.signals = [("released-for", clean(named, 80))]
        return res
    candidates = editions(source, earlier, values, student)
    edition, missing = edition_of(cells, candidates)
    if missing:
        where = [edition.cell_name(c) for c in edition.code_locked if c["id"] in missing]
        shown = "; ".join(where[:3]) + (f"; and {len(where) - 3} more" if len(where) > 3 else "")
        msg = (f"{len(where)} locked code cell(s) of the released notebook were changed, moved or deleted "
               f"({shown}); the notebook was not run. Start again from the released notebook and only edit the "
               "answer cells.")
        return done("tampered", msg, _all_parts(parts, "tampered", msg))
    # locked text (markdown) cells a student edited are restored from the release, as nbgrader does: they are
    # never run, so only the code cells are checked, and the text they read is the release's
    restored = edition.missing_text(cells)
    if not edition.current:  # released from an earlier source: its locked cells become the current source's
        cells = carry_over(cells, edition, candidates[0])
        edition = candidates[0]
    code_locked = edition.code_locked

    code = [c["source"] for c in cells if c["cell_type"] == "code"]
    names = sorted({p.answer for p in parts} | {p.options["phi"] for p in parts if isinstance(p.options.get("phi"), str)})
    calls = _reference_calls(source)
    setup = {"seed": seed_from(f"{source.exercise}:{student}"), "functions": sorted(calls.functions),
             "methods": sorted(calls.methods)}
    ex = sandbox.run(code, names, timeout=timeout, memory_mb=memory, files={"submission.ipynb": data}, setup=setup)
    limits = ex.limits or getattr(sandbox, "limits", "")
    if ex.status != "ok" and ex.answers is None and ex.cell is None:
        return done(ex.status, ex.message, _all_parts(parts, ex.status, ex.message), ran=limits)

    decoded, problems = decode_answers(ex.answers, names)
    stopped = None
    if ex.status != "ok":
        where = f" at {_cell_name(cells, ex.cell)}" if ex.cell else ""
        stopped = (ex.status, f"{ex.message}{where}" + (f"; {_raised(cells, ex.errors, ex.cell)}"
                                                          if _raised(cells, ex.errors, ex.cell) else ""))
    locked_sums = {checksum(c) for c in code_locked}
    mine = [i for i, c in enumerate((c for c in cells if c["cell_type"] == "code"), 1) if checksum(c) in locked_sums]
    numbers = [i for i, c in enumerate(cells, 1) if c["cell_type"] == "code"]  # as the student sees them
    used = reference_use(code, [p.answer for p in parts], calls=calls, locked=mine, numbers=numbers)
    as_run(used, ex.reference, locked=mine, numbers=numbers)
    grades = [_part_grade(p, decoded, problems, stopped, cells, ex.errors, used, reveal_hidden) for p in parts]
    describe(grades, parts, decoded, cells)
    status = worst([g.status for g in grades] + ([stopped[0]] if stopped else []))
    if stopped is not None:
        message = stopped[1]
    else:
        message = "" if status == "ok" else next(g.message for g in grades if g.status == status)
    if restored:
        note = (f"{len(restored)} locked text cell(s) edited in the notebook were restored from the release "
                "(only answer cells are yours to edit)")
        message = f"{message}; {note}" if message else note
    return done(status, message, grades, ran=limits)


def _part_grade(p, decoded, problems, stopped, cells, errors, used, reveal_hidden):
    """The grade of part ``p``: its answer refused, never assigned (before the notebook ``stopped``, or with the
    cell that raised), too large, or checked (a hidden check shows its verdict only)."""
    if p.answer in problems:
        return PartGrade(p.name, 0.0, p.points, "error", f"`{p.answer}`: {problems[p.answer]}")
    if p.answer not in decoded:
        if stopped is not None:
            return PartGrade(p.name, 0.0, p.points, stopped[0],
                             f"`{p.answer}` was not assigned before the notebook stopped: {stopped[1]}")
        why = _raised(cells, errors)
        return PartGrade(p.name, 0.0, p.points, "missing-answer",
                         f"`{p.answer}` is not assigned" + (f": {why}" if why else ""))
    too_large = _too_large(p, decoded)
    if too_large:
        return PartGrade(p.name, 0.0, p.points, "error", too_large)
    try:
        result = p.run(decoded[p.answer], decoded)
    except Exception as exc:  # a checker should not raise; if it does, the part is not lost silently
        return PartGrade(p.name, 0.0, p.points, "error", f"the checker failed: {type(exc).__name__}: {exc}")
    score = round(max(0.0, min(1.0, float(result.score))) * p.points, 4)
    if p.hidden and not reveal_hidden:  # the verdict, not the expected value, of a hidden check
        return PartGrade(p.name, score, p.points, "ok", _hidden_verdict(result), "", used[p.answer],
                         mistakes=mistake_rows(result))
    return PartGrade(p.name, score, p.points, "ok", " | ".join(result.messages)[:1000],
                     result.html(math=False), used[p.answer], mistakes=mistake_rows(result))


_CALLS = {}


def _reference_calls(source):
    """What counts as kinbook's reference in this exercise (:func:`~.reference_use.exercise_calls`), once per
    source."""
    if source.sha256 not in _CALLS:
        _CALLS[source.sha256] = exercise_calls([(kind, code) for _, kind, code in grader_segments(source)])
    return _CALLS[source.sha256]


def _first_line(text, limit=60):
    for line in str(text).splitlines():
        if line.strip():
            return clean(line.strip(), limit)
    return ""


def _cell_name(cells, code_index):
    """The code cell ``code_index`` (from 1, among code cells) as the student sees it: its position among all
    cells, its first line and the heading above it."""
    seen = 0
    for position, cell in enumerate(cells, 1):
        if cell["cell_type"] != "code":
            continue
        seen += 1
        if seen == code_index:
            heading = ""
            for above in reversed(cells[:position - 1]):
                if above["cell_type"] == "markdown" and above["source"].strip():
                    lines = [line for line in above["source"].splitlines() if line.strip()]
                    titled = [line for line in lines if line.lstrip().startswith("#")]
                    heading = _first_line((titled or lines)[0].lstrip("# "))
                    break
            first = _first_line(cell["source"])
            return (f"cell {position}" + (f" (“{first}”" if first else " (empty") + ")"
                    + (f", under “{heading}”" if heading else ""))
    return f"code cell {code_index}"


def _raised(cells, errors, only=None):
    """The first cell that raised (or cell ``only``), named, with its exception: a sentence, or ""."""
    errors = [e for e in errors if only is None or e["cell"] == only]
    if not errors:
        return ""
    e = errors[0]
    more = f" (and {len(errors) - 1} more cell(s) raised)" if len(errors) > 1 and only is None else ""
    evalue = clean(e["evalue"], 300)
    return f"{_cell_name(cells, e['cell'])} raised {clean(e['ename'], 100)}" + (f": {evalue}" if evalue else "") + more


def _hidden_verdict(result):
    """A hidden check's feedback: the verdict and, for each mistake found, its name and hint from the
    catalogue — never the checker's messages, which may quote the expected value."""
    if result.passed:
        return "hidden check: correct"
    out = "hidden check: not correct"
    hints = []
    for code in result.mistakes:
        if code in MISTAKES:
            title, hint = explain(code)
            hints.append(f"{code}: {title}" + (f" — {hint}" if hint else ""))
        else:
            hints.append(code)
    return out + (" — " + " | ".join(hints) if hints else "")


# ================================================================================================== batch
_state = {}


def _pool_init(source, isolation):
    """In each grading process of the pool: die with the batch's process, keep one sandbox for the run."""
    die_with_parent(os.getppid())
    # a pool that breaks terminates its processes (SIGTERM): exit through the `finally` clauses, which stop
    # the sandbox (everything in it is killed)
    signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(1))
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the batch's to handle: it stops the pool
    _state.update(source=source, sandbox=Sandbox(isolation))
    Finalize(None, _state["sandbox"].close, kwargs={"wait": True}, exitpriority=100)


def _grade_task(args):
    entry, data, options = args
    source, sandbox = _state["source"], _state["sandbox"]
    try:
        return _grade_bytes(source, entry, data, sandbox=sandbox, **options)
    except GradingError:
        raise
    except Exception as exc:  # the grader itself failed on this submission: record it, keep the batch
        return SubmissionResult(entry.student, source.exercise, entry.path, hashlib.sha256(data).hexdigest(), "error",
                                f"the grader failed: {type(exc).__name__}: {exc}", [], 0.0)


def grade(source, submissions, outdir="graded", *, timeout=60.0, memory=1000, jobs=1, force=False,
          generic=False, reveal_hidden=False, isolation=True, progress=None, regrade=False, policy=None,
          id_pattern=None, roster=None, file_times=False, released_from=()):
    """Grade a batch of submissions of one exercise and record them in the gradebook.

    Parameters
    ----------
    source : path
        The instructor's source notebook (read once, at the start).
    submissions : list of paths
        Notebooks, or directories searched for ``*.ipynb`` (links, devices and FIFOs in them are refused).
    outdir : path
        Receives ``gradebook.sqlite`` and its exports ``grades.csv``, ``totals.csv``, ``feedback/<student>.html``.
    timeout, memory :
        Per submission: CPU seconds of the notebook's kernel (a notebook that waits instead of computing is
        stopped by a wall-clock backstop, :func:`kinbook.classroom.sandbox.protocol.wall_seconds`) and megabytes.
    jobs : int
        Submissions graded in parallel (a process pool). Each grading process keeps one sandbox, whose zygote
        forks a fresh worker and kernel for every submission and resets everything after it.
    force : bool
        Grade again files already graded (a file not graded before — a new attempt — is always graded).
    regrade : bool
        The source changed since the gradebook's results of this exercise were graded (a run stops otherwise):
        grade every file again with the new source.
    policy : {"latest", "best"} or None
        Which of a student's attempts counts (stored as the exercise's rule; default: the stored one, else
        latest). With latest, only the latest file of each student is graded; the others are kept as history.
    id_pattern : str or None
        How to read student ids (and attempts, times) from the paths: a regular expression or a ready pattern
        (``canvas``, ``moodle``, ``blackboard``; :mod:`kinbook.classroom.naming`).
    roster : Roster or None
        The course's students (:func:`kinbook.classroom.roster.read_roster`): maps LMS ids to kinbook ids, and is
        stored in the gradebook for the exports and the report.
    file_times : bool
        Take a submission's time from its file's modification time when its name gives none (for the late rule);
        only where the download kept the times.
    released_from : list of paths
        Earlier sources students' notebooks may come from, beside those kept (:mod:`kinbook.classroom.editions`).
    generic, reveal_hidden : bool
        See :func:`grade_submission`.
    isolation : bool
        Run the notebooks inside bubblewrap (default). Where it is not available,
        :class:`~kinbook.classroom.sandbox.IsolationUnavailable` is raised before anything is graded; False grades
        with the audit hook only, warns, and records ``isolation: none``.
    progress : callable, optional
        Called with each :class:`SubmissionResult` (or a notice string) as it completes.

    Returns
    -------
    list of SubmissionResult
        The submissions graded in this run (not the skipped ones).
    """
    check_options(timeout=timeout, memory=memory, jobs=jobs, force=force, generic=generic,
                  reveal_hidden=reveal_hidden, isolation=isolation, regrade=regrade)
    _needs_a_real_machine()
    check_memory(memory)
    src = load_source(source)
    references(src)  # an exercise that cannot be graded stops here, before any submission is run
    if isolation:
        check()
    else:
        warnings.warn(NO_ISOLATION_WARNING, RuntimeWarning, stacklevel=2)
        if progress:
            progress("warning: " + NO_ISOLATION_WARNING)
    book = Gradebook(outdir)
    with book.failures():  # closed on any error; SQLite's (a full disk, another run's lock) in the instructor's words
        check_pin(book, src, regrade)
        run = book.begin_run(src, "bubblewrap" if isolation else "none")
        options = dict(timeout=float(timeout), memory=float(memory), generic=bool(generic),
                       reveal_hidden=bool(reveal_hidden), earlier=tuple(earlier_sources(book, src, released_from)))
        plan = _plan(book, run, src, submissions, options, force=force, regrade=regrade, policy=policy,
                     pattern=id_pattern, roster=roster, progress=progress, file_times=file_times,
                     reproduce=_options_shown(timeout, memory, generic, isolation))
        return _grade_run(src, book, run, plan, options, jobs=jobs, isolation=isolation, generic=generic,
                          progress=progress)


def _plan(book, run, src, submissions, options, **how):
    """:func:`kinbook.classroom.intake.intake`, then the check that the class holds a release of the source; when
    either stops the run, nothing was graded and the pin stays the source the results were graded with."""
    pinned = book.pin(src.exercise)
    try:
        plan = intake(book, run, src, submissions, max_bytes=MAX_FILE_BYTES, **how)
        per_student = find_parameters(src.nb) is not None and not options["generic"]
        why = class_would_be_tampered(src, (d for d in _contents(plan.todo, with_entries=True)), options["earlier"],
                                      per_student)
        if why:
            raise GradingError(f"{src.exercise}: {why}")
    except GradingError:
        book.unpin(src.exercise, pinned)
        book.end_run(run)
        raise  # book.failures() closes the gradebook
    return plan


def _options_shown(timeout, memory, generic, isolation):
    """A run's options as ``kinbook grade`` takes them (for the command that reproduces a failure)."""
    return (("--timeout", f"{float(timeout):g}", "--memory", f"{float(memory):g}") + (("--generic",) if generic else ())
            + (() if isolation else ("--no-isolation",)))


def _grade_run(src, book, run, plan, options, *, jobs, isolation, generic, progress):
    """Grade what ``plan`` holds in ``run`` of ``book``: each result recorded as it completes (made inert, the
    source checked unchanged), then the exports and the feedback pages, then the notices."""
    results, touched = [], set()

    def record(res):
        res = clean_result(res)  # everything a student controls, made inert before it is stored or printed
        book.record(res, run, replace=annotate(res, plan, src))
        results.append(res)
        touched.add(res.student)
        if progress:
            progress(res)
            if res.status == "wrong-release":
                progress(f"copying signal: {res.student} submitted a notebook that was not released for them "
                         f"({res.message})")
            for kind, detail in res.signals:
                if kind in ("look-alike", "names-another"):
                    progress(f"signal: {res.student}: {detail}")
        if src.changed_on_disk():
            raise GradingError(f"the source notebook {str(src.path)!r} changed during grading; the run was stopped "
                               "(every result recorded so far is kept). Grade again once it is final.")

    # an instructor's mistake (the generic release graded per student, or variants with --generic) stops the run
    # here, before any grading
    if find_parameters(src.nb) is not None:
        check_release_kinds(release_kinds(plan.todo, _read_again), not generic, src.exercise)
    touched.update(e.student for e in plan.entries.values() if e.student)  # a PDF's student gets a page too
    for entry in plan.refused:
        record(_refused(src, entry, entry.status, entry.message))
    todo = plan.todo

    previous_handler = None
    if _main_thread():
        previous_handler = signal.signal(signal.SIGTERM, _on_sigterm)
    try:
        if jobs <= 1 or len(todo) <= 1:
            with Sandbox(isolation) as sb:
                for entry in todo:
                    record(_one(src, entry, options, sb))
        else:
            _run_pool(src, todo, options, int(jobs), isolation, record)
    except (KeyboardInterrupt, SystemExit) as exc:
        if isinstance(exc, KeyboardInterrupt) or exc.code == 128 + signal.SIGTERM:
            print(stopped_notice(exc, len(results), len(todo) + len(plan.refused), book.path), file=sys.stderr)
        raise
    finally:
        if previous_handler is not None:
            signal.signal(signal.SIGTERM, previous_handler)
        book.end_run(run)
        try:
            book.export()
            write_pages(book, book.outdir / "feedback", touched)
        finally:
            book.close()
    if progress and ungraded_notice(results):
        progress(ungraded_notice(results))
    if plan.stale and progress:
        progress(f"graded with the earlier source and not regraded ({len(plan.stale)}; their files were not given): "
                 + ", ".join(plan.stale[:20]) + (" …" if len(plan.stale) > 20 else ""))
    return results


def _main_thread():
    return threading.current_thread() is threading.main_thread()


def _on_sigterm(signum, frame):
    # unwinds like Ctrl-C: the pool is killed, the exports written, the process exits with 128 + SIGTERM
    raise SystemExit(128 + signum)


def _read_again(entry):
    """The entry's bytes, read now (a file replaced since it was listed is refused)."""
    try:
        return read_entry(entry, MAX_FILE_BYTES), None
    except Refused as exc:
        return None, exc


def _one(src, entry, options, sandbox):
    data, refused = _read_again(entry)
    if refused is not None:
        return _refused(src, entry, refused.status, refused.message)
    try:
        return _grade_bytes(src, entry, data, sandbox=sandbox, **options)
    except GradingError:
        raise
    except Exception as exc:
        return SubmissionResult(entry.student, src.exercise, entry.path, hashlib.sha256(data).hexdigest(), "error",
                                f"the grader failed: {type(exc).__name__}: {exc}", [], 0.0)


def _run_pool(src, todo, options, jobs, isolation, record):
    """Grade ``todo`` in a process pool, at most ``2 * jobs`` submissions read ahead; a grading process that dies
    takes its submissions with it: those are graded again, each in a pool of its own, so that only the culprit
    is lost (and recorded as an error)."""
    def one_pool(batch, workers):
        lost = []
        pool = ProcessPoolExecutor(max_workers=workers, initializer=_pool_init, initargs=(src, isolation))
        try:
            pending = {}
            queue = list(batch)
            broken = False
            while queue or pending:
                while queue and len(pending) < 2 * workers and not broken:
                    entry = queue.pop(0)
                    data, refused = _read_again(entry)
                    if refused is not None:
                        record(_refused(src, entry, refused.status, refused.message))
                        continue
                    try:
                        pending[pool.submit(_grade_task, (entry, data, options))] = entry
                    except BrokenProcessPool:
                        queue.insert(0, entry)
                        broken = True
                if not pending:
                    break
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                for fut in finished:
                    entry = pending.pop(fut)
                    try:
                        res = fut.result()
                    except BrokenProcessPool:
                        lost.append(entry)
                        broken = True
                        continue
                    except GradingError:
                        raise
                    except Exception as exc:
                        res = SubmissionResult(entry.student, src.exercise, entry.path, "", "error",
                                               f"the grader failed: {type(exc).__name__}: {exc}", [], 0.0)
                    record(res)
                if broken:
                    lost += queue
                    queue = []
        except BaseException:
            _kill_pool(pool)
            raise
        else:
            pool.shutdown(wait=True)
        return lost

    for entry in one_pool(todo, jobs):
        for culprit in one_pool([entry], 1):
            msg = "the grading process died while grading this notebook"
            record(SubmissionResult(culprit.student, src.exercise, culprit.path, "", "error", msg,
                                    _all_parts(references(src), "error", msg), 0.0))


def _kill_pool(pool):
    """Stop a pool at once: its processes are killed (their sandboxes die with them)."""
    for p in list(getattr(pool, "_processes", {}).values()):
        try:
            p.kill()
        except Exception:
            pass
    pool.shutdown(wait=False, cancel_futures=True)
