"""Batch variants benchmark (issue 21 item 5): ``kinbook variant SOURCE --roster roster.csv`` for a class of N, in
one process, against the one-call-per-student loop it replaces (each call a fresh ``kinbook variant --student``).

Run:  .venv/bin/python benchmarks/variants.py [N] [EXERCISE-PREFIX ...]      (defaults: 300 ex09 ex11)

Each exercise with per-student parameters is timed as the instructor runs it: the console script, from the start of
the process (imports included) to the last notebook written. The one-call-per-student figure is measured on
the first 10 students and scaled to N. Target: 300 students ≤ 30 s on a quiet 2-core machine. The load average is
printed with the figures: other work on the 2 cores changes the wall times; the batch's CPU time (user + system, one
process) is what its wall time would be on a quiet machine, and does not grow with the load.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KINBOOK = Path(sys.executable).with_name("kinbook")


def timed(args):
    """Wall seconds of one kinbook process (and, as ``timed.cpu``, its CPU seconds: user + system)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([str(KINBOOK), *args], check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    timed.cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    prefixes = sys.argv[2:] or ["ex09", "ex11"]
    print(f"load average {os.getloadavg()[0]:.1f}; {n} students")
    print(f"| exercise | `variant --roster` ({n}) | its CPU time | per student | one call per student ({n}, scaled "
          "from 10) | ratio |")
    print("|---|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        roster = Path(tmp) / "roster.csv"
        roster.write_text("student,name\n" + "".join(f"s{k:03d},Student {k}\n" for k in range(n)))
        for prefix in prefixes:
            (source,) = sorted((ROOT / "exercises").glob(f"{prefix}*.ipynb"))
            out = Path(tmp) / prefix
            batch = timed(["variant", str(source), "--roster", str(roster), "-o", str(out)])
            cpu = timed.cpu
            assert len(list(out.glob("*.ipynb"))) == n
            single = sum(timed(["variant", str(source), "--student", f"s{k:03d}", "-o", str(out / "one")])
                         for k in range(10)) / 10 * n
            print(f"| {source.stem} | {batch:.1f} s | {cpu:.1f} s | {1000 * batch / n:.0f} ms | {single:.0f} s | "
                  f"{single / batch:.0f}× |")


if __name__ == "__main__":
    main()
