"""Grading benchmark (issues 8 and 12): a class of N submissions of one shipped exercise graded with
``kinbook.classroom.grade(..., jobs=J)``, the way ``kinbook grade`` does — in the bubblewrap sandbox, and
without it (``isolation=False``) for the ratio — and the gradebook's cost per recorded result.

Run:  .venv/bin/python benchmarks/grading.py [N] [JOBS] [EXERCISE-PREFIX]      (defaults: 100 2 ex01)
      .venv/bin/python benchmarks/grading.py --recording [MAX]                 (default: 6000 results)

The submissions are the exercise's own solution, written per student (variants where the exercise has
parameters) as a student would hand it in. Targets: ≤ 0.6 s per submission at jobs = 2 with isolation on;
recording cost per result flat from 100 to 6,000 results. The machine's load is printed with the figures:
other work on the 2 cores changes the wall times (the ratio, from the same run, is steadier).
"""

from __future__ import annotations

import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from kinbook.classroom import grade, student_parameters  # noqa: E402
from kinbook.classroom.notebook import find_parameters, load_source, student_notebook  # noqa: E402
from kinbook.classroom.release import write_notebook  # noqa: E402
from kinbook.classroom.sandbox import available  # noqa: E402


def make_class(source_path, n, outdir):
    source = load_source(source_path)
    varied = find_parameters(source.nb) is not None
    for k in range(n):
        student = f"s{k:03d}"
        values = student_parameters(source, student) if varied else None
        nb = student_notebook(source, values, student if varied else None, keep_solutions=True)
        write_notebook(nb, outdir / student / f"{source.exercise}.ipynb")
    return source


def load():
    return "load average {:.1f} / {:.1f} / {:.1f}".format(*os.getloadavg())


def cpu_seconds():
    """CPU time of this process and of every process it (and its descendants) started and reaped."""
    import resource

    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def batch(src, subs, outdir, jobs, isolation):
    before = load()
    cpu0 = cpu_seconds()
    t0 = time.perf_counter()
    results = grade(src, [subs], outdir, jobs=jobs, isolation=isolation)
    wall = time.perf_counter() - t0
    batch.cpu = cpu_seconds() - cpu0
    statuses = {}
    for r in results:
        statuses[r.status] = statuses.get(r.status, 0) + 1
    return wall, results, statuses, before, load()


def main(n=100, jobs=2, prefix="ex01"):
    src = next((ROOT / "exercises").glob(f"{prefix}*.ipynb"))
    modes = ([True] if available() else []) + [False]
    walls = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        source = make_class(src, n, tmp / "subs")
        print(f"\nGrading {n} submissions of {source.exercise} with jobs = {jobs}")
        for isolation in modes:
            wall, results, statuses, before, after = batch(src, tmp / "subs", tmp / f"graded-{isolation}", jobs,
                                                           isolation)
            walls[isolation] = wall
            full = sum(r.score == r.max_score for r in results)
            each = [r.seconds for r in results]
            name = "bubblewrap sandbox" if isolation else "no isolation (audit hook only)"
            print(f"  {name}")
            print(f"    wall time         {wall:8.1f} s   ({wall / n:.2f} s per submission)")
            print(f"    per submission    median {statistics.median(each):.2f} s, max {max(each):.2f} s (one job's view)")
            if isolation:  # bwrap's monitor exits without reaping its pid 1: the sandbox's CPU time is not counted
                print("    CPU time          (not counted: bubblewrap's processes are not reaped by their parents)")
            else:
                print(f"    CPU time          {batch.cpu / n:.2f} s per submission, all processes (the wall time on "
                      f"{jobs} idle cores would be about {batch.cpu / n / jobs:.2f} s)")
            print(f"    statuses          {statuses}; full marks {full}/{n}")
            print(f"    machine           {before} before, {after} after")
    if len(walls) == 2:
        print(f"  isolation costs     ×{walls[True] / walls[False]:.2f} the unisolated wall time")
    else:
        print("  (bubblewrap is not available here: the isolated run was skipped)")


def recording(limit=6000):
    """Cost of recording one result in the gradebook as it fills up: flat (one indexed transaction)."""
    from kinbook.classroom.gradebook import Gradebook
    from kinbook.classroom.results import PartGrade, SubmissionResult

    def result(k):
        return SubmissionResult(f"s{k:05d}", "ex01", f"collected/s{k:05d}/ex01.ipynb", f"{k:064x}", "ok", "",
                                [PartGrade(p, 1.0, 2.0, "ok", "Φ is correct: all 2 rows match" * 3, "<table>" * 40)
                                 for p in ("a", "b", "c")], 0.8, "bubblewrap")

    marks = [m for m in (100, 500, 1000, 2000, 4000, 6000, 12000) if m <= limit]
    print(f"\nRecording results in the gradebook (SQLite, WAL), up to {limit:,} results: ms per result, median "
          "of 100")
    print(f"  {'results held':>13} {'synchronous=FULL (as graded)':>30} {'without fsync (the database work)':>36}")
    with tempfile.TemporaryDirectory() as tmp:
        books = [Gradebook(Path(tmp) / "full"), Gradebook(Path(tmp) / "nosync")]
        books[1].db.execute("PRAGMA synchronous=OFF")
        k = 0
        for mark in marks:
            times = ([], [])
            while k < mark:
                for book, spent in zip(books, times):
                    t0 = time.perf_counter()
                    book.record(result(k))
                    spent.append(time.perf_counter() - t0)
                k += 1
            print(f"  {mark - 100:>13,} {1000 * statistics.median(times[0][-100:]):30.2f} "
                  f"{1000 * statistics.median(times[1][-100:]):36.3f}")
        t0 = time.perf_counter()
        books[0].export([])
        print(f"  exporting grades.csv and totals.csv for {k:,} results: {time.perf_counter() - t0:.2f} s (once per run)")
        for book in books:
            book.close()
    print(f"  {load()}")


if __name__ == "__main__":
    args = sys.argv[1:]
    if args and args[0] == "--recording":
        recording(int(args[1]) if len(args) > 1 else 6000)
    else:
        main(int(args[0]) if args else 100, int(args[1]) if len(args) > 1 else 2, args[2] if len(args) > 2 else "ex01")
