"""Scale benchmark (issue 8, part 2): one position solve of a planar chain of N bodies closed in loops —
four-bar loops in series sharing their rockers (rocker k and rocker k+1 pivot on the ground one unit apart
and a coupler joins their tips) — with sparse assembly and sparse LU.

N = 2M + 1 bodies for M loops, one degree of freedom, driven by the first rocker's angle. Every loop is a
parallelogram, so in the solution every rocker has the driver's angle: the check needs no reference solver.

Run: .venv/bin/python benchmarks/planar_scale.py
"""

import time

import numpy as np

from kinbook.planar import Driver, Ground, Mechanism, Revolute

THETA = 1.1  # driver angle, radians


def chain(M):
    m = Mechanism(f"chain{M}")
    m.add_body("ground", points={f"O{k}": (k, 0) for k in range(M + 1)})
    rng = np.random.default_rng(M)
    for k in range(M + 1):  # rockers: pivot at local (0, 0), tip at (1, 0); initial guess off by up to 0.1 rad
        a = 0.9 + 0.2 * rng.random()
        m.add_body(f"R{k}", points={"O": (0, 0), "T": (1, 0)}, q0=(k, 0, a))
    for k in range(M):  # couplers: ends at local (±0.5, 0)
        m.add_body(f"C{k}", points={"L": (-0.5, 0), "R": (0.5, 0)}, q0=(k + 0.5 + np.cos(1), np.sin(1), 0))
    m.add(Ground("ground"))
    for k in range(M + 1):
        m.add(Revolute("ground", f"R{k}", point_i=f"O{k}", point_j="O"))
    for k in range(M):
        m.add(Revolute(f"R{k}", f"C{k}", point_i="T", point_j="L"))
        m.add(Revolute(f"C{k}", f"R{k+1}", point_i="R", point_j="T"))
    m.add(Driver("R0", "phi", str(THETA)))
    return m


def main():
    print(f"{'bodies N':>9} {'coordinates n':>14} {'solve (ms)':>11} {'iterations check':>17}")
    sizes, times = [], []
    for M in (50, 150, 500, 1000, 1500):
        mech = chain(M)
        mech.Phi(mech.q0)  # compile the index maps once, outside the timing
        best = np.inf
        for _ in range(3):
            t0 = time.perf_counter()
            q = mech.solve_position(0.0)
            best = min(best, time.perf_counter() - t0)
        rockers = [mech.index((f"R{k}", "phi")) for k in range(M + 1)]
        assert np.allclose(q[rockers], THETA, atol=1e-9)
        sizes.append(len(mech.bodies))
        times.append(best)
        print(f"{len(mech.bodies):9d} {mech.n:14d} {best * 1e3:11.1f} {'rockers = θ ✓':>17}")
    slope = np.polyfit(np.log(sizes), np.log(times), 1)[0]
    at_1000 = np.interp(1000, sizes, times) * 1e3
    print(f"\nlog-log slope of time against N: {slope:.2f} (target ≤ 1.2); about {at_1000:.1f} ms at N = 1000 "
          f"(target ≤ 50 ms)")


if __name__ == "__main__":
    main()
