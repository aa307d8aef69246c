"""Spatial sweep benchmark (issue 8, part 3): the shipped RSUR spatial four-bar, position + velocity +
acceleration at N instants, kinbook's batched sweep against the careful hand-written way (sympy-derived Φ,
Φ_q, ν, γ lambdified with common-subexpression elimination, Newton per instant) in the same run.

kinbook runs with its hand-written kernels and with the kernels compiled from each constraint's Φ
(``mech.kernels = "compiled"``).

Run: .venv/bin/python benchmarks/spatial_sweep.py [N]      (default N = 10000; the peer runs on N/20 instants)
"""

import sys
import time

import numpy as np

import kinbook

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from planar_sweep import hand_written_sweep, lambdified  # noqa: E402  (the same peer as the planar benchmark)


def main(N=10000):
    times = np.linspace(0.0, 1.0, N)
    sweeps = {}
    for kernels in ("hand", "compiled"):
        mech = kinbook.examples.load("spatial_fourbar")
        mech.kernels = kernels
        mech.simulate(times[:50])  # compiles the kernels: not counted
        best = np.inf
        for _ in range(3):
            t0 = time.perf_counter()
            res = mech.simulate(times)
            best = min(best, time.perf_counter() - t0)
        sweeps[kernels] = best, res
    (best, res), (best_c, res_c) = sweeps["hand"], sweeps["compiled"]
    np.testing.assert_allclose(res_c.q, res.q, atol=1e-9)
    np.testing.assert_allclose(res_c.qdd, res.qdd, rtol=1e-6, atol=1e-6)
    t0 = time.perf_counter()
    fns = lambdified(mech)
    t_derive = time.perf_counter() - t0
    sub = times[: max(100, N // 20)]
    t0 = time.perf_counter()
    out = hand_written_sweep(fns, res.q[0], sub)
    t_a = time.perf_counter() - t0
    m = len(sub)
    np.testing.assert_allclose(out[:, 0], res.q[:m], atol=1e-8)
    np.testing.assert_allclose(out[:, 1], res.qd[:m], rtol=1e-6, atol=1e-6)
    k, a = best / N * 1e6, t_a / m * 1e6
    print(f"\nSpatial sweep, RSUR four-bar (n = {mech.n}), position + velocity + acceleration")
    print(f"{'method':45} {'µs / instant':>14} {'kinbook faster by':>18}")
    print(f"{'kinbook simulate (' + str(N) + ' instants)':45} {k:14.1f} {1.0:17.1f}×")
    c = best_c / N * 1e6
    print(f"{'kinbook simulate, kernels compiled from Φ':45} {c:14.1f} {c / k:17.1f}×")
    print(f"{'(a) lambdified sympy + Newton per instant':45} {a:14.1f} {a / k:17.1f}×")
    print(f"(the peer's sympy derivation and lambdify took {t_derive:.1f} s, not counted)")
    print("target: kinbook ≤ 60 µs per instant")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10000)
