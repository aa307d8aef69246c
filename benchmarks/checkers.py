"""Median time of check_jacobian and check_gamma on the book's example 1 (four-bar, 12 coordinates).

Run:  .venv/bin/python benchmarks/checkers.py

The answers are a student's hand-written strings (rows of the book's tables), so every run includes
parsing, lambdifying and evaluating the answer at all sample configurations. The first call on a mechanism
also builds the reference and the samples (cached afterwards); it is reported separately.
Targets (issue #4): Φ_q < 100 ms, γ < 300 ms median.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import kinbook  # noqa: E402
from kinbook.grading import check_gamma, check_jacobian, check_phi  # noqa: E402
from tests.grading.corpus import EX1_GAMMA, EX1_JAC, EX1_PHI_SIMPLE  # noqa: E402


def median_ms(fn, repeat=30):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
        assert result.passed, result
    return 1e3 * statistics.median(times)


def main():
    mech = kinbook.examples.load("ch13_example1")
    t0 = time.perf_counter()
    check_jacobian(EX1_JAC, mech)
    first = 1e3 * (time.perf_counter() - t0)
    print(f"first check on the mechanism (reference + samples): {first:7.1f} ms")
    print(f"check_phi       median: {median_ms(lambda: check_phi(EX1_PHI_SIMPLE, mech)):7.1f} ms")
    print(f"check_jacobian  median: {median_ms(lambda: check_jacobian(EX1_JAC, mech)):7.1f} ms   (target < 100 ms)")
    print(f"check_gamma     median: {median_ms(lambda: check_gamma(EX1_GAMMA, mech)):7.1f} ms   (target < 300 ms)")
    print(f"check_jacobian with the student's Φ (error carried forward) median: "
          f"{median_ms(lambda: check_jacobian(EX1_JAC, mech, phi=EX1_PHI_SIMPLE), 10):7.1f} ms")


if __name__ == "__main__":
    main()
