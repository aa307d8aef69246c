"""Grading benchmark (issue 8, part 5): a class of N submissions of one shipped exercise graded with
``kinbook.classroom.grade(..., jobs=J)``, each in its own sandboxed kernel, the way ``kinbook grade`` does.

Run:  .venv/bin/python benchmarks/grading.py [N] [JOBS] [EXERCISE-PREFIX]      (defaults: 100 2 ex01)

The submissions are the exercise's own solution, written per student (variants where the exercise has
parameters) as a student would hand it in. The script prints the wall time of the batch and, from the
results, where one submission's time goes (sandbox start-up and kernel imports vs the student's cells and
the checks). Target: 100 submissions in ≤ 2 min with two jobs.
"""

from __future__ import annotations

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


def make_class(source_path, n, outdir):
    source = load_source(source_path)
    varied = find_parameters(source.nb) is not None
    for k in range(n):
        student = f"s{k:03d}"
        values = student_parameters(source, student) if varied else None
        nb = student_notebook(source, values, student if varied else None, keep_solutions=True)
        write_notebook(nb, outdir / student / f"{source.exercise}.ipynb")
    return source


def main(n=100, jobs=2, prefix="ex01"):
    src = next((ROOT / "exercises").glob(f"{prefix}*.ipynb"))
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        source = make_class(src, n, tmp / "subs")
        t0 = time.perf_counter()
        results = grade(src, [tmp / "subs"], tmp / "graded", jobs=jobs)
        wall = time.perf_counter() - t0
    statuses = {}
    for r in results:
        statuses[r.status] = statuses.get(r.status, 0) + 1
    full = sum(r.score == r.max_score for r in results)
    each = [r.seconds for r in results]
    print(f"\nGrading {n} submissions of {source.exercise} with jobs = {jobs}")
    print(f"  wall time           {wall:8.1f} s   ({wall / n:.2f} s per submission; target ≤ 120 s for 100)")
    print(f"  per submission      median {statistics.median(each):.2f} s, max {max(each):.2f} s (one job's view)")
    print(f"  statuses            {statuses}; full marks {full}/{n}")


if __name__ == "__main__":
    args = sys.argv[1:]
    main(int(args[0]) if args else 100, int(args[1]) if len(args) > 1 else 2, args[2] if len(args) > 2 else "ex01")
