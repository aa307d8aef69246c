"""Grading submitted notebooks (``kinbook grade``).

For each submission: read it (never modify it), compare its locked cells with the release, run it in a
sandbox (:mod:`kinbook.classroom.sandbox`), read the named answers as data
(:mod:`kinbook.classroom.serialize`), and grade them with kinbook's checkers here, in the grader's process,
against references built from the instructor's source (:func:`kinbook.classroom.variant.references`).

Statuses (one per part; the submission's status is the worst of them):

=================  ==========================================================================================
ok                 the answer was read and checked (its score may be anything from 0 to full)
missing-answer     the variable was not assigned (cell left as released, or it raised before assigning)
error              the answer is not gradable data, or the kernel died (``os._exit``, killed itself)
timeout            the notebook did not finish within ``timeout`` seconds
memory             the notebook exceeded its memory budget
tampered           a locked cell differs from the release (or is missing): not run, 0 points
corrupt-notebook   the file is not a readable notebook: not run, 0 points
=================  ==========================================================================================
"""

from __future__ import annotations

import hashlib
import re
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ..errors import GradingError
from .notebook import checksum, find_parameters, load_source, locked_checksums, student_notebook
from .serialize import DecodeError, decode
from .variant import references, student_parameters

__all__ = ["STATUSES", "PartGrade", "SubmissionResult", "grade_submission", "grade", "student_of",
           "MAX_NOTEBOOK_BYTES"]

STATUSES = ("ok", "missing-answer", "error", "timeout", "memory", "tampered", "corrupt-notebook")
_SEVERITY = {s: i for i, s in enumerate(STATUSES)}
MAX_NOTEBOOK_BYTES = 20 * 1024 * 1024


@dataclass
class PartGrade:
    """One row of grades.csv."""

    part: str
    score: float
    max_score: float
    status: str
    message: str = ""
    html: str = ""


@dataclass
class SubmissionResult:
    """The grading of one submission."""

    student: str
    exercise: str
    submission: str
    sha256: str
    status: str
    message: str
    parts: list = field(default_factory=list)
    seconds: float = 0.0

    @property
    def score(self):
        return round(sum(p.score for p in self.parts), 4)

    @property
    def max_score(self):
        return sum(p.max_score for p in self.parts)

    def to_dict(self):
        return asdict(self)

    @classmethod
    def from_dict(cls, d):
        d = dict(d)
        d["parts"] = [PartGrade(**p) for p in d.get("parts", [])]
        return cls(**d)

    def __repr__(self):
        return (f"SubmissionResult({self.student!r}, {self.exercise!r}: {self.status}, "
                f"{self.score:g}/{self.max_score:g})")

    def _repr_html_(self):
        import html

        rows = "".join(f"<tr><td>{html.escape(p.part)}</td><td>{p.score:g} / {p.max_score:g}</td>"
                       f"<td>{html.escape(p.status)}</td><td>{html.escape(p.message[:200])}</td></tr>"
                       for p in self.parts)
        return (f"<p><b>{html.escape(self.student)}</b> — {html.escape(self.exercise)}: {self.score:g} / "
                f"{self.max_score:g} ({html.escape(self.status)})</p><table><tr><th>part</th><th>score</th>"
                f"<th>status</th><th>message</th></tr>{rows}</table>")


def student_of(path, exercise):
    """The student a submission belongs to, from its path: ``<student>/<exercise>.ipynb``,
    ``<exercise>-<student>.ipynb`` (as written by ``kinbook variant``) or ``<student>.ipynb``."""
    path = Path(path)
    stem = path.stem
    if stem == exercise:
        name = path.resolve().parent.name
    elif stem.startswith(exercise + "-"):
        name = stem[len(exercise) + 1:]
    else:
        name = stem
    return re.sub(r"[^A-Za-z0-9._@+-]", "_", name) or "unknown"


def _all_parts(parts, status, message):
    return [PartGrade(p.name, 0.0, p.points, status, message) for p in parts]


def _worst(parts, default="ok"):
    return max((p.status for p in parts), key=lambda s: _SEVERITY[s], default=default)


def grade_submission(source, submission, *, student=None, timeout=60.0, memory=1000, generic=False,
                     reveal_hidden=False):
    """Grade one submitted notebook.

    Parameters
    ----------
    source : path or Source
        The instructor's source notebook.
    submission : path
        The submitted notebook (read, never modified).
    student : str, optional
        Default: from the path (:func:`student_of`).
    timeout : float
        Wall-clock seconds for running the notebook.
    memory : float
        Megabytes the notebook may allocate.
    generic : bool
        The exercise has parameters but students got the generic release (defaults), not variants.
    reveal_hidden : bool
        Put the checkers' full messages (which may quote the expected value) of hidden checks in the
        gradebook and the feedback; by default they only say whether the answer is correct.

    Returns
    -------
    SubmissionResult
    """
    import nbformat

    t0 = time.monotonic()
    source = load_source(source) if not hasattr(source, "nb") else source
    submission = Path(submission)
    student = student or student_of(submission, source.exercise)
    values = None
    if find_parameters(source.nb) is not None and not generic:
        values = student_parameters(source, student)
    parts = references(source, values)

    def done(status, message, grades):
        return SubmissionResult(student, source.exercise, str(submission), digest, status, message, grades,
                                round(time.monotonic() - t0, 3))

    digest = ""
    try:
        data = submission.read_bytes()
        digest = hashlib.sha256(data).hexdigest()
        if len(data) > MAX_NOTEBOOK_BYTES:
            raise ValueError(f"larger than {MAX_NOTEBOOK_BYTES // 2**20} MB")
        nb = nbformat.reads(data.decode("utf-8"), as_version=4)
        if not isinstance(nb.get("cells"), list) or any(
                not isinstance(c, dict) or not isinstance(c.get("source"), str) for c in nb.cells):
            raise ValueError("no list of cells")
    except Exception as exc:
        msg = f"not a readable notebook: {type(exc).__name__}: {str(exc)[:200]}"
        return done("corrupt-notebook", msg, _all_parts(parts, "corrupt-notebook", msg))

    expected = locked_checksums(student_notebook(source, values, student if values is not None else None))
    got = {c.get("id"): c for c in nb.cells}
    changed = [cid for cid, h in expected.items() if cid not in got or checksum(got[cid]) != h]
    if changed:
        where = ", ".join(changed[:5]) + (" …" if len(changed) > 5 else "")
        msg = (f"{len(changed)} locked cell(s) were changed or deleted ({where}); the notebook was not run. "
               "Start again from the released notebook and only edit the answer cells.")
        return done("tampered", msg, _all_parts(parts, "tampered", msg))

    from .sandbox import execute

    run = nbformat.v4.new_notebook()
    run.cells = [nbformat.v4.new_code_cell(c.source) for c in nb.cells if c.get("cell_type") == "code"]
    names = sorted({p.answer for p in parts} | {p.options["phi"] for p in parts if isinstance(p.options.get("phi"), str)})
    ex = execute(run, names, timeout=timeout, memory_mb=memory, files={"submission.ipynb": data})
    if ex.status != "ok":
        return done(ex.status, ex.message, _all_parts(parts, ex.status, ex.message))

    decoded, problems = {}, {}
    for name in names:
        rec = (ex.answers or {}).get(name)
        if rec is None:
            continue
        try:
            decoded[name] = decode(rec)
        except DecodeError as exc:
            problems[name] = str(exc)
    errors = {e["cell"]: f"{e['ename']}: {e['evalue']}" for e in ex.errors}
    grades = []
    for p in parts:
        if p.answer in problems:
            grades.append(PartGrade(p.name, 0.0, p.points, "error", f"`{p.answer}`: {problems[p.answer]}"))
            continue
        if p.answer not in decoded:
            hint = ""
            if errors:
                hint = " (exceptions in code cells " + ", ".join(str(c) for c in sorted(errors)[:5]) + ")"
            grades.append(PartGrade(p.name, 0.0, p.points, "missing-answer", f"`{p.answer}` is not assigned{hint}"))
            continue
        try:
            result = p.run(decoded[p.answer], decoded)
        except Exception as exc:  # a checker should not raise; if it does, the part is not lost silently
            grades.append(PartGrade(p.name, 0.0, p.points, "error", f"the checker failed: {type(exc).__name__}: {exc}"))
            continue
        score = round(max(0.0, min(1.0, float(result.score))) * p.points, 4)
        if p.hidden and not reveal_hidden:  # the verdict, not the expected value, of a hidden check
            verdict = "correct" if result.passed else "not correct" + (
                f" (mistakes: {', '.join(result.mistakes)})" if result.mistakes else "")
            grades.append(PartGrade(p.name, score, p.points, "ok", f"hidden check: {verdict}"))
            continue
        grades.append(PartGrade(p.name, score, p.points, "ok", " | ".join(result.messages)[:1000],
                                result._repr_html_()))
    status = _worst(grades)
    message = "" if status == "ok" else next(g.message for g in grades if g.status == status)
    return done(status, message, grades)


# ================================================================================================== batch
def _expand(submissions, exercise):
    """Files as given; directories searched for notebooks of this exercise (``<exercise>.ipynb``,
    ``<exercise>-<student>.ipynb``), or for every notebook when none is named after the exercise."""
    out = []
    for s in submissions:
        s = Path(s)
        if s.is_dir():
            found = sorted(p for p in s.rglob("*.ipynb") if ".ipynb_checkpoints" not in p.parts)
            named = [p for p in found if p.stem == exercise or p.stem.startswith(exercise + "-")]
            out += named or found
        else:
            out.append(s)
    return out


def _pool_worker_init():
    # a pool that breaks terminates its processes (SIGTERM): exit through the `finally` clauses, which kill
    # the sandbox's processes and remove its temporary directories
    import signal
    import sys
    from multiprocessing.util import Finalize

    from .sandbox import enable_zygote, stop_zygote

    signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(1))
    # this process's workers and kernels are forked from a zygote of its own, stopped (with what it still runs)
    # when the process exits; were it killed outright, the zygote would see its control pipe close and stop
    enable_zygote()
    Finalize(None, stop_zygote, exitpriority=100)


def _grade_task(args):
    source, submission, student, timeout, memory, generic, reveal_hidden = args
    try:
        return grade_submission(source, submission, student=student, timeout=timeout, memory=memory,
                                generic=generic, reveal_hidden=reveal_hidden)
    except GradingError:
        raise
    except Exception as exc:  # the grader itself failed on this submission: record it, keep the batch
        return SubmissionResult(student, Path(source).stem, str(submission), "", "error",
                                f"the grader failed: {type(exc).__name__}: {exc}", [], 0.0)


def grade(source, submissions, outdir="graded", *, timeout=60.0, memory=1000, jobs=1, force=False,
          generic=False, reveal_hidden=False, progress=None):
    """Grade a batch of submissions of one exercise and write the gradebook.

    Parameters
    ----------
    source : path
        The instructor's source notebook.
    submissions : list of paths
        Notebooks, or directories searched for ``*.ipynb``.
    outdir : path
        Receives ``grades.csv``, ``totals.csv``, ``feedback/<student>.html`` and ``.kinbook/`` (one result
        file per graded submission, so that a re-run skips what is already graded).
    timeout, memory :
        Per submission: wall-clock seconds and megabytes.
    jobs : int
        Submissions graded in parallel (a process pool). Each grading process forks the sandbox's worker
        and kernel processes from a pre-warmed zygote of its own (:func:`kinbook.classroom.sandbox.zygote`),
        stopped when the batch ends.
    force : bool
        Grade again submissions already graded.
    generic, reveal_hidden : bool
        See :func:`grade_submission`.
    progress : callable, optional
        Called with each :class:`SubmissionResult` (or a skip notice string) as it completes.

    Returns
    -------
    list of SubmissionResult
        The submissions graded in this run (not the skipped ones).
    """
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    from . import gradebook
    from .sandbox import zygote

    src = load_source(source)
    references(src)  # an exercise that cannot be graded stops here, before any submission is run
    book = gradebook.Gradebook(outdir)
    tasks, seen = [], {}
    for sub in _expand(submissions, src.exercise):
        student = student_of(sub, src.exercise)
        if student in seen:
            raise GradingError(f"two submissions for student {student!r} of {src.exercise}: {seen[student]} and {sub}")
        seen[student] = sub
        if not force and book.has(student, src.exercise):
            if progress:
                progress(f"skipped {student}: already graded (use --force to grade again)")
            continue
        tasks.append((str(src.path), str(sub), student, float(timeout), float(memory), bool(generic),
                      bool(reveal_hidden)))
    results = []

    def record(res):
        book.record(res)
        results.append(res)
        if progress:
            progress(res)

    def run_pool(batch, workers):
        """Run tasks in one process pool; returns the tasks whose process died (BrokenProcessPool)."""
        left = {t[1]: t for t in batch}
        try:
            with ProcessPoolExecutor(max_workers=workers, initializer=_pool_worker_init) as pool:
                futures = {pool.submit(_grade_task, t): t for t in batch}
                for fut in as_completed(futures):
                    t = futures[fut]
                    try:
                        res = fut.result()
                    except BrokenProcessPool:
                        continue
                    except GradingError:
                        raise
                    except Exception as exc:
                        res = SubmissionResult(t[2], src.exercise, t[1], "", "error",
                                               f"the grader failed: {type(exc).__name__}: {exc}", [], 0.0)
                    left.pop(t[1], None)
                    record(res)
        except BrokenProcessPool:
            pass
        return list(left.values())

    if jobs <= 1:
        with zygote():  # workers and kernels forked from one pre-warmed process (kinbook.classroom._zygote)
            for t in tasks:
                record(_grade_task(t))
    else:
        # a grading process that dies takes the pool's other submissions with it: those are graded again,
        # each in a pool of its own, so that only the culprit is lost (and recorded as an error)
        for t in run_pool(tasks, int(jobs)):
            for lost in run_pool([t], 1):
                msg = "the grading process died while grading this notebook"
                record(SubmissionResult(lost[2], src.exercise, lost[1], "", "error", msg,
                                        _all_parts(references(src), "error", msg), 0.0))
    book.write()
    return results
