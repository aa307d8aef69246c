"""The path of one wrong planar answer through kinbook: how many kinbook modules it crosses and how many kinbook
calls it makes, counted with ``sys.setprofile`` (kinbook frames only, in a fresh process).

Run:  .venv/bin/python benchmarks/grading_path.py

The answer is the architecture review's: ``check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 - sin(phi2)"],
mech.constraint("1"))`` on ``ch13_example1`` (Aᵀ for A: ``A_transposed``, score 0.5), on a freshly loaded
mechanism, then again with the target cached, then ``repr`` of the verdict. The figures are counts, not
times: they do not depend on the machine. Target: ≤ 15 modules for the fresh wrong answer.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TARGET_MODULES = 15
"""The issue's target: the fresh wrong answer crosses at most this many kinbook modules."""
TARGET_CALLS = 4674
"""... and fewer kinbook calls than this (the count when the target was set)."""

RUN = r"""
import json, sys
import kinbook
from kinbook.grading import check_phi
mech = kinbook.examples.load("ch13_example1")
answer = ["x1 - x2 + cos(phi2)", "y1 - y2 - sin(phi2)"]
# everything the check may import is imported first: the count is of calls, not of first imports
check_phi(answer, kinbook.examples.load("ch13_example1").constraint("1"))

def trace(call):
    modules, order, calls = set(), [], [0]

    def prof(frame, event, arg):
        if event != "call":
            return
        name = frame.f_globals.get("__name__", "")
        if name == "kinbook" or name.startswith("kinbook."):
            calls[0] += 1
            if name not in modules:
                modules.add(name)
                order.append(name)

    sys.setprofile(prof)
    try:
        out = call()
    finally:
        sys.setprofile(None)
    return out, {"modules": len(modules), "calls": calls[0], "order": order}

r, fresh = trace(lambda: check_phi(answer, mech.constraint("1")))
_, cached = trace(lambda: check_phi(answer, mech.constraint("1")))
_, shown = trace(lambda: repr(r))
print(json.dumps({"mistakes": r.mistakes, "score": r.score, "fresh": fresh, "cached": cached, "repr": shown}))
"""


def measure():
    out = subprocess.run([sys.executable, "-c", RUN], cwd=ROOT, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main():
    m = measure()
    print(f"one wrong planar Φ (ch13_example1, joint 1, Aᵀ for A): {m['mistakes']}, score {m['score']}")
    for key, what in (("fresh", "fresh mechanism"), ("cached", "target cached"), ("repr", "repr of the verdict")):
        f = m[key]
        print(f"  {what:22s} {f['modules']:3d} kinbook modules, {f['calls']:6,d} kinbook calls")
    fresh = m["fresh"]
    ok_m, ok_c = fresh["modules"] <= TARGET_MODULES, fresh["calls"] < TARGET_CALLS
    print(f"  target: ≤ {TARGET_MODULES} modules ({'met' if ok_m else 'NOT met'}: {fresh['modules']}), "
          f"< {TARGET_CALLS:,d} calls ({'met' if ok_c else 'NOT met'}: {fresh['calls']:,d})")
    print("  modules of the fresh check, first visits in order:")
    print("    " + " → ".join(name.removeprefix("kinbook.") for name in m["fresh"]["order"]))


if __name__ == "__main__":
    main()
