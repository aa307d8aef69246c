"""How fast the checkers answer (issue #14 item 6): `import kinbook`, the first check on a target in a fresh
process, and the median of later checks.

Run:  .venv/bin/python benchmarks/checkers.py            # every target, then later checks
      .venv/bin/python benchmarks/checkers.py --pairs 5  # planar and spatial first checks, pair by pair, side by side
      .venv/bin/python benchmarks/checkers.py --pairs 5 --load 4  # the same under load: 4 processes spinning
      add --source to compile kinbook from source in each process (what PYTHONDONTWRITEBYTECODE=1 costs)

Each figure of the first part is measured in a new Python process (so nothing is cached or imported yet):
the time of `import kinbook`, then — with the mechanism loaded and evaluated once — the first check of an
answer on one target (the reference, the samples and the student's tape are all built then; for a wrong answer,
the diagnosis too). The answers are a student's hand-written strings or sympy matrices, never kinbook's reference.
Targets: import ≤ 400 ms; first check ≤ 300 ms, and a spatial first check ≤ 3 × the planar first check of the
same kind of answer (:data:`PAIRS`), measured side by side in the same run (on a busy machine the ratio is the
figure to read); later checks ≤ 50 ms (median).
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

FIRST = r"""
import json, time
t0 = time.perf_counter()
import kinbook
t_import = time.perf_counter() - t0
from kinbook import grading
import numpy as np
import sys
sys.path.insert(0, {root!r})
from benchmarks.checkers import CASES
case = CASES[{k}]
mech, target, answer, check, options = case["build"]()
mech.evaluate(mech.q0)  # a student has the mechanism (and kinbook's compiled model) before checking
passed = options.pop("_passed", True)
t0, c0 = time.perf_counter(), time.process_time()
r = getattr(grading, check)(answer, target, **options)
t_first, c_first = time.perf_counter() - t0, time.process_time() - c0
assert r.passed is passed, r
print(json.dumps({{"import": t_import, "first": t_first, "cpu": c_first}}))
"""


def _ex(name, constraint=None):
    import kinbook

    m = kinbook.examples.load(name)
    return m, (m if constraint is None else m.constraint(constraint))


def _ex1_phi():
    from tests.grading.corpus import EX1_PHI_SIMPLE

    m, t = _ex("ch13_example1")
    return m, t, EX1_PHI_SIMPLE, "check_phi", {}


def _ex1_jac():
    from tests.grading.corpus import EX1_JAC

    m, t = _ex("ch13_example1")
    return m, t, EX1_JAC, "check_jacobian", {}


def _ex1_gamma():
    from tests.grading.corpus import EX1_GAMMA

    m, t = _ex("ch13_example1")
    return m, t, EX1_GAMMA, "check_gamma", {}


def _rr_joint_gamma():
    from tests.grading.corpus import _book_rr_gamma

    m, t = _ex("ch13_example3", "3")
    return m, t, _book_rr_gamma(), "check_gamma", {}


def _spatial(constraint, quantity):
    from kinbook.core.symbolic import derive

    m, t = _ex("spatial_fourbar", constraint)
    c = t if constraint is not None else None
    phi = m.constraint_phi(c) if c is not None else m.symbolic().Phi
    d = derive(-phi, m.q, m.qd, m.t)  # the student's own derivation, in the setup (not timed)
    check = {"Phi": "check_phi", "Phi_q": "check_jacobian", "gamma": "check_gamma"}[quantity]
    answer = getattr(d, quantity) if quantity != "Phi" else d.Phi
    if quantity == "gamma":
        answer = -answer
    if quantity == "Phi_q":
        answer = -answer
    return m, t, answer, check, {}


def _spatial_gamma_with_phi():
    """The whole spatial four-bar's γ graded against the student's own Φ (``phi=``): the slowest first check."""
    m, t, answer, check, options = _spatial(None, "gamma")
    return m, t, answer, check, options | {"phi": -m.symbolic().Phi}


def _wrong(build, k, change, passed=False):
    """A case with answer row k changed by ``change`` (a wrong answer: its first check diagnoses it)."""

    def make():
        mech, target, answer, check, options = build()
        rows = list(answer) if not hasattr(answer, "tolist") else [answer[i, :] if answer.shape[1] > 1 else
                                                                   answer[i, 0] for i in range(answer.shape[0])]
        rows[k] = change(rows[k])
        return mech, target, rows, check, options | {"_passed": passed}

    return make


def _six_bar_masked():
    from tests.grading.corpus3 import SIX_BAR, _exercise

    m = _exercise("ex04")
    return m, m, [*SIX_BAR[:16], "phi1 + phi6", SIX_BAR[17]], "check_phi", {"_passed": False}


def _ex1_vanishing():
    from tests.grading.corpus import EX1_PHI_SIMPLE

    m, t = _ex("ch13_example1")
    rows = list(EX1_PHI_SIMPLE)
    rows[3] = f"cos(phi2)*({rows[3]})"
    return m, t, rows, "check_phi", {"_passed": False}


def _ex1_far_zero():
    """A factor whose zero is far from every sample, (x2 − 100): found only by the factors' whole-domain search."""
    from tests.grading.corpus import EX1_PHI_SIMPLE

    m, t = _ex("ch13_example1")
    rows = list(EX1_PHI_SIMPLE)
    rows[3] = f"(x2 - 100)*({rows[3]})"
    return m, t, rows, "check_phi", {"_passed": False}


CASES = [
    {"name": "planar Φ, example 1 (12 rows)", "build": _ex1_phi},
    {"name": "planar Φ_q, example 1", "build": _ex1_jac},
    {"name": "planar γ, example 1", "build": _ex1_gamma},
    {"name": "planar γ, r-r joint (book table)", "build": _rr_joint_gamma},
    {"name": "spatial Φ, universal joint B", "build": lambda: _spatial("B", "Phi")},
    {"name": "spatial Φ_q, revolute joint O_A", "build": lambda: _spatial("O_A", "Phi_q")},
    {"name": "spatial γ, universal joint B", "build": lambda: _spatial("B", "gamma")},
    {"name": "spatial Φ, whole four-bar (28 rows)", "build": lambda: _spatial(None, "Phi")},
    {"name": "spatial Φ_q, whole four-bar", "build": lambda: _spatial(None, "Phi_q")},
    {"name": "spatial γ, whole four-bar, with phi=", "build": _spatial_gamma_with_phi},
    {"name": "wrong: spatial γ, whole four-bar, one sign", "build": _wrong(lambda: _spatial(None, "gamma"), 20,
                                                                            lambda e: -e)},
    {"name": "wrong: spatial Φ, whole four-bar, one sign", "build": _wrong(lambda: _spatial(None, "Phi"), 20,
                                                                            lambda e: -2 * e + 1)},
    {"name": "wrong: planar Φ, six-bar, a masked row", "build": _six_bar_masked},
    {"name": "wrong: planar Φ, example 1, a vanishing factor", "build": _ex1_vanishing},
    {"name": "wrong: planar Φ, example 1, a factor zero far away", "build": _ex1_far_zero},
    {"name": "wrong: planar Φ, example 1, one sign", "build": _wrong(_ex1_phi, 7, lambda e: f"-2*({e}) + 1")},
    {"name": "wrong: planar γ, example 1, one sign", "build": _wrong(_ex1_gamma, 7, lambda e: f"-({e})")},
]


_PYC = {}


def _environment(source=False):
    """The fresh processes' environment. By default kinbook's bytecode is compiled once beforehand into a cache of
    this run (``PYTHONPYCACHEPREFIX``), as an installed package has it (pip compiles it): the first check then
    measures what it does, not the compiling of some 25 modules from source, which a shell with
    ``PYTHONDONTWRITEBYTECODE=1`` pays in every process (about half the first check at load 4). ``source``: that
    environment as it is."""
    env = dict(os.environ)
    if source:
        return env
    if "prefix" not in _PYC:
        _PYC["prefix"] = tempfile.mkdtemp(prefix="kinbook-pyc-")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = _PYC["prefix"]
    if "done" not in _PYC:
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "kinbook"), str(ROOT / "benchmarks"),
                        str(ROOT / "tests")], env=env, cwd=ROOT, check=True, capture_output=True)
        _PYC["done"] = True
    return env


def first_check(k, source=False):
    """One first check (case ``k``) in a fresh process: {"import": s, "first": s}."""
    code = FIRST.format(root=str(ROOT), k=k)
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True,
                         env=_environment(source))
    return json.loads(res.stdout.strip().splitlines()[-1])


def first_checks(source=False):
    return [(case["name"], first_check(k, source)) for k, case in enumerate(CASES)]


PAIRS = [
    ("a right answer", "planar Φ, example 1 (12 rows)", "spatial γ, whole four-bar, with phi="),
    ("a wrong Φ (one row −2·row + 1)", "wrong: planar Φ, example 1, one sign", "wrong: spatial Φ, whole four-bar, one sign"),
    ("a wrong γ (one row's sign)", "wrong: planar γ, example 1, one sign", "wrong: spatial γ, whole four-bar, one sign"),
]
"""The side-by-side pairs, like for like: the same kind of answer (right, or with the same slip) graded on a planar
target and on the slowest spatial one. A wrong answer's first check also runs the diagnosis (the catalogue, the
roundings, the witness), which a right one never does: the ratio of a wrong spatial answer to a *right* planar one
mixes that cost with the spatial one, so it is printed apart ("any answer to a right planar one")."""


def side_by_side(rounds=5, source=False):
    """Each pair of :data:`PAIRS` in fresh processes, planar then spatial, ``rounds`` times: the ratio of each pair
    is measured under the same load. Returns [(pair name, [(planar, spatial), ...] per round)]."""
    names = [c["name"] for c in CASES]
    out = {label: [] for label, _, _ in PAIRS}
    for _ in range(rounds):
        for label, planar, spatial in PAIRS:
            out[label].append((first_check(names.index(planar), source), first_check(names.index(spatial), source)))
    return list(out.items())


def busy(count):
    """``count`` processes that spin on a core each (``--load N``): the machine made busy on purpose, so that the
    ratios are measured under load as well as quiet, in one run. Returns them, to be killed."""
    return [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(count)]


def print_side_by_side(rounds, source=False, load=0):
    spinners = busy(load)
    try:
        rows = side_by_side(rounds, source)
    finally:
        for p in spinners:
            p.kill()
            p.wait()
    print(f"side by side, fresh processes{' (compiling from source)' if source else ''}"
          f"{f', with {load} spinning processes' if load else ''}: the planar first check, then the spatial one "
          "(ms, ratio spatial / planar; target ≤ 3×)")
    for key, what in (("first", "wall clock"), ("cpu", "CPU time of the process (other processes' turns left out)")):
        print(f" {what}:")
        for label, pairs in rows:
            ratios = [s[key] / p[key] for p, s in pairs]
            print(f"  {label:32s} " + "  ".join(f"{1e3 * p[key]:4.0f}/{1e3 * s[key]:4.0f}" for p, s in pairs)
                  + f"   median {statistics.median(ratios):.2f}× (worst {max(ratios):.2f}×)")
        right = rows[0][1]
        strict = [max(s[key] for _, pairs in rows for s in [pairs[k][1]]) / right[k][0][key]
                  for k in range(len(right))]
        print(f"  any answer to a right planar one: the slowest spatial first check / the right planar one, median "
              f"{statistics.median(strict):.2f}× (a wrong planar answer alone is "
              f"{statistics.median([pairs[k][0][key] / right[k][0][key] for _, pairs in rows[1:] for k in range(len(right))]):.2f}×)")


def later_checks(repeat=20):
    from kinbook import grading

    out = []
    for case in CASES:
        mech, target, answer, check, options = case["build"]()
        passed = options.pop("_passed", True)
        fn = getattr(grading, check)
        assert fn(answer, target, **options).passed is passed
        times = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            fn(answer, target, **options)
            times.append(time.perf_counter() - t0)
        out.append((case["name"], statistics.median(times)))
    return out


def main():
    source = "--source" in sys.argv
    if "--pairs" in sys.argv:
        load = int(sys.argv[sys.argv.index("--load") + 1]) if "--load" in sys.argv else 0
        print_side_by_side(int(sys.argv[sys.argv.index("--pairs") + 1]), source, load)
        return
    print("first check on a target, fresh process each (ms)        import   first   (targets 400 / 300)"
          + ("   [compiling from source]" if source else ""))
    imports, firsts = [], []
    for name, r in first_checks(source):
        imports.append(r["import"])
        firsts.append(r["first"])
        print(f"  {name:52s} {1e3 * r['import']:6.0f}  {1e3 * r['first']:6.0f}   (CPU {1e3 * r['cpu']:4.0f})")
    print(f"  worst: import {1e3 * max(imports):.0f} ms ({max(imports) / 0.4:.2f} × target), first check "
          f"{1e3 * max(firsts):.0f} ms ({max(firsts) / 0.3:.2f} × target)")
    names = [c["name"] for c in CASES]
    for label, planar, spatial in PAIRS:
        p, q = firsts[names.index(planar)], firsts[names.index(spatial)]
        print(f"  {label}: spatial {1e3 * q:.0f} ms / planar {1e3 * p:.0f} ms = {q / p:.1f}× (target ≤ 3×)")
    worst = max(range(len(firsts)), key=firsts.__getitem__)
    print(f"  slowest of all: {CASES[worst]['name']}, {max(firsts) / firsts[0]:.1f} × the right planar first check "
          f"({1e3 * firsts[0]:.0f} ms; --pairs N measures the ratios side by side)")
    print("later checks, median of 20 (ms)                                (target 50)")
    later = later_checks()
    for name, t in later:
        print(f"  {name:52s} {1e3 * t:6.1f}")
    worst = max(t for _, t in later)
    print(f"  worst: {1e3 * worst:.1f} ms ({worst / 0.05:.2f} × target)")


if __name__ == "__main__":
    main()
