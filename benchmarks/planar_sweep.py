"""Planar sweep benchmark (issue 8, part 1): the book's example-2 slider-crank (12 coordinates), position,
velocity and acceleration at N instants over one crank turn, kinbook against its peers in the same run.

Peers:
  (a) the careful hand-written way: sympy-derived Φ, Φ_q, ν, γ lambdified to numpy (with common
      subexpression elimination) and a Newton loop per instant, warm-started from the previous instant;
  (b) scipy.optimize.fsolve per instant with its finite-difference Jacobian (velocity and acceleration
      from the same lambdified Φ_q, ν, γ as (a));
  (c) kimech from PyPI, when installed (`pip install kimech`): its own slider-crank model and sweep.

kinbook runs twice: with its hand-written kernels (the default) and with every constraint evaluated through
the kernel compiled from its symbolic Φ (``mech.kernels = "compiled"``, what a new constraint type without a
hand kernel gets).

Run: .venv/bin/python benchmarks/planar_sweep.py [N]      (default N = 10000; peers (a)-(c) run on a
subset of the instants and are reported per instant, so the ratios compare like with like).
"""

import sys
import time

import numpy as np
import scipy.optimize as so
import sympy as sp

import kinbook


def kinbook_sweep(mech, times):
    return mech.simulate(times)


def lambdified(mech):
    d = mech.symbolic()
    args = (list(mech.q), list(mech.qd), mech.t)
    f = {k: sp.lambdify(args, getattr(d, k), "numpy", cse=True) for k in ("Phi", "Phi_q", "nu", "gamma")}
    zeros = np.zeros(mech.n)
    return (
        lambda q, t: np.asarray(f["Phi"](q, zeros, t), float).ravel(),
        lambda q, t: np.asarray(f["Phi_q"](q, zeros, t), float),
        lambda q, t: np.asarray(f["nu"](q, zeros, t), float).ravel(),
        lambda q, qd, t: np.asarray(f["gamma"](q, qd, t), float).ravel(),
    )


def hand_written_sweep(fns, q0, times, tol=1e-10):
    Phi, Phi_q, nu, gamma = fns
    q = q0.copy()
    out = np.empty((len(times), 3, len(q0)))
    for k, t in enumerate(times):
        for _ in range(50):
            r = Phi(q, t)
            if np.max(np.abs(r)) < tol:
                break
            q = q - np.linalg.solve(Phi_q(q, t), r)
        J = Phi_q(q, t)
        qd = np.linalg.solve(J, nu(q, t))
        out[k] = q, qd, np.linalg.solve(J, gamma(q, qd, t))
    return out


def fsolve_sweep(fns, q0, times):
    Phi, Phi_q, nu, gamma = fns
    q = q0.copy()
    out = np.empty((len(times), 3, len(q0)))
    for k, t in enumerate(times):
        q = so.fsolve(Phi, q, args=(t,), xtol=1e-12)
        J = Phi_q(q, t)
        qd = np.linalg.solve(J, nu(q, t))
        out[k] = q, qd, np.linalg.solve(J, gamma(q, qd, t))
    return out


def kimech_sweep(times):
    """kimech's own slider-crank (crank 2, rod 6), driven at ω = 100 from 45°, over the same instants.
    Returns the slider's x coordinate, velocity and acceleration."""
    from kimech import KinematicDriver, Mechanism, solve  # optional peer: pip install kimech

    m = Mechanism("slider_crank")
    g_o = m.ground.add_point("O", (0.0, 0.0))
    g_s = m.ground.add_point("S", (0.0, 0.0))
    crank, rod, slider = m.add_link("crank"), m.add_link("rod"), m.add_link("slider")
    c_o, c_a = crank.add_point("O", (0.0, 0.0)), crank.add_point("A", (2.0, 0.0))
    r_a, r_b = rod.add_point("A", (0.0, 0.0)), rod.add_point("B", (6.0, 0.0))
    s_b = slider.add_point("B", (0.0, 0.0))
    drive = m.revolute(g_o, c_o, name="input")
    m.revolute(c_a, r_a)
    m.revolute(r_b, s_b)
    m.prismatic(g_s, s_b, axis_a=(1.0, 0.0), axis_b=(1.0, 0.0))
    guess = {crank: (0.0, 0.0, np.pi / 4), rod: (1.414, 1.414, -0.238), slider: (7.245, 0.0, 0.0)}
    driver = KinematicDriver(drive, position=np.pi / 4 + 100 * times, velocity=100.0, acceleration=0.0)
    sol = solve(m, drivers=driver, initial_guess=guess)
    return sol.point_positions(s_b)[:, 0], sol.point_velocities(s_b)[:, 0], sol.point_accelerations(s_b)[:, 0]


def timed(fn, *args, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args)
        best = min(best, time.perf_counter() - t0)
    return best, out


def main(N=10000):
    mech = kinbook.examples.load("ch13_example2")
    times = np.linspace(0.0, 2 * np.pi / 100, N)
    q0 = mech.solve_position(0.0)
    fns = lambdified(mech)
    sub = times[: max(200, N // 10)]

    t_k, res = timed(kinbook_sweep, mech, times)
    compiled = kinbook.examples.load("ch13_example2")
    compiled.kernels = "compiled"  # every constraint through the kernel compiled from its Φ (kinbook.core.kernels)
    compiled.simulate(times[:50])  # compiles the kernels: not counted
    t_c, res_c = timed(kinbook_sweep, compiled, times)
    np.testing.assert_allclose(res_c.q, res.q, atol=1e-9)
    np.testing.assert_allclose(res_c.qdd, res.qdd, rtol=1e-6, atol=1e-6)
    t_a, out_a = timed(hand_written_sweep, fns, q0, sub)
    t_b, out_b = timed(fsolve_sweep, fns, q0, sub, repeat=1)
    m = len(sub)
    # the peers agree with kinbook on the instants they solved
    for out in (out_a, out_b):
        np.testing.assert_allclose(out[:, 0], res.q[:m], atol=1e-8)
        np.testing.assert_allclose(out[:, 1], res.qd[:m], rtol=1e-6, atol=1e-6)
        np.testing.assert_allclose(out[:, 2], res.qdd[:m], rtol=1e-5, atol=1e-3)
    per = {
        "kinbook simulate": t_k / N * 1e6,
        "kinbook simulate, kernels compiled from Φ": t_c / N * 1e6,
        "(a) lambdified sympy + Newton per instant": t_a / m * 1e6,
        "(b) scipy fsolve per instant": t_b / m * 1e6,
    }
    try:
        t_c, (x, v, a) = timed(kimech_sweep, sub, repeat=1)
        B = res.position("slider", "B")[:m, 0]
        np.testing.assert_allclose(x, B, atol=1e-6)
        np.testing.assert_allclose(v, res.velocity("slider", "B")[:m, 0], rtol=1e-5, atol=1e-4)
        per["(c) kimech"] = t_c / m * 1e6
    except ImportError as exc:
        per["(c) kimech"] = None
        print(f"(c) kimech skipped: {exc}")
    print(f"\nPlanar sweep, example-2 slider-crank (n = {mech.n}), position + velocity + acceleration")
    print(f"kinbook over {N} instants; peers over the first {m}\n")
    print(f"{'method':45} {'µs / instant':>14} {'kinbook faster by':>18}")
    for name, us in per.items():
        if us is None:
            continue
        ratio = us / per["kinbook simulate"]
        print(f"{name:45} {us:14.1f} {ratio:17.1f}×")
    print("\ntarget: kinbook ≤ 15 µs per instant and ≥ 8× faster than (a)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10000)
