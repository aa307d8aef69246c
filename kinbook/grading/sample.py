"""Where answers are compared: seeded sample instants (second stage of a check).

Two sets per target, both the same on every run and every machine (seeded):

* *generic* samples — random q, q̇ and t; and a few over the whole domain (angles beyond ±π, t up to 30:
  :func:`generic_wide`), compared apart on their own scale. Φ is compared there: at assembled configurations every correct Φ
  is zero, and zero says nothing about the form of a row. In space the Euler parameters of every body are
  on the unit sphere (where every real configuration has them), so rows that differ only off it agree.
* *assembled* samples — configurations on the constraint manifold: the graded rows vanish and, in space,
  every body's normalization row too (single joints included). They are found by minimum-norm Newton steps
  from perturbed initial guesses, in (q, t) when the rows depend on time (a driver), and kept only where Φ_q
  has its full rank. Their velocities are *consistent*: Φ_q q̇ = ν (a particular solution plus a random
  motion the constraints allow). Φ_q, ν and γ are compared there, so answers simplified with the help of
  the constraints (φ̇_j = φ̇_i in a translational joint, the book's habit) are right, and equivalent
  formulations of Φ are recognised by their zero set and rank.

When too few assembled configurations are found (a model the projection cannot handle), the generic
samples stand in, flagged ``on_manifold = False``: correct answers agree there too; only what needs the
manifold (equivalent formulations, simplifications by the constraints) is then not recognised.
"""

from __future__ import annotations

import itertools

import numpy as np

from ..spatial.random import random_p

__all__ = ["Samples", "generic", "assembled", "at", "zeros", "placements", "wide", "wide_assembled", "spread", "perturbed", "project", "regular", "velocities", "N_GENERIC", "N_WIDE", "generic_wide", "N_ASSEMBLED", "N_SEARCH", "SEED"]

N_GENERIC = 16
N_WIDE = 4
"""Generic samples over the whole domain (:func:`wide`), after the N_GENERIC ones."""
N_ASSEMBLED = 16
SEED = 20241121
N_SEARCH = 48
"""Seeded starts of the search for the zeros of an answer's rows (:func:`zeros`)."""
_NEWTON_STEPS = 40
_TOL = 1e-12


class Samples:
    """Instants at which answers are evaluated: Q, QD of shape (N, n) and T of shape (N,).

    Attributes
    ----------
    on_manifold : bool
        The configurations satisfy the target's constraints (and the velocities their velocity equations).
    """

    def __init__(self, Q, QD, T, on_manifold=False):
        self.Q, self.QD, self.T = np.asarray(Q, float), np.asarray(QD, float), np.asarray(T, float)
        self.N = self.Q.shape[0]
        self.on_manifold = on_manifold

    def take(self, idx):
        return Samples(self.Q[idx], self.QD[idx], self.T[idx], self.on_manifold)


def generic(target):
    """Random configurations (Euler parameters of unit norm), velocities and times."""
    rng = np.random.default_rng(SEED)
    n, N = target.n, N_GENERIC
    Q = rng.uniform(-3.0, 3.0, (N, n))
    if target.kind == "planar":
        Q[:, 2::3] = rng.uniform(-np.pi, np.pi, (N, n // 3))
    else:
        nb = n // 7
        Q.reshape(N, nb, 7)[:, :, 3:] = random_p(N * nb, rng).reshape(N, nb, 4)
    QD = rng.normal(0.0, 2.0, (N, n))
    T = rng.uniform(0.0, 1.0, N)
    return Samples(Q, QD, T)


def generic_wide(target):
    """The generic samples over the whole domain (:func:`wide`, seeded): a Φ row is a multiple of a reference row
    only if it is that multiple here too, compared on its own scale here (a row's size at t = 30 must not
    loosen the comparison at the other samples)."""
    return wide(target, np.random.default_rng(SEED + 3), N_WIDE)


def wide(target, rng, count):
    """Configurations over the whole domain: angles beyond ±π (π … 4π either way) and t from a wide range
    (1 … 30) — where ``atan2(sin φ2, cos φ2)`` is not φ2 and a product of (t − tₖ) over instants in [0, 1] is
    large. Translations as :func:`spread`; Euler parameters of unit norm."""
    Q = spread(target, rng, count)
    if target.kind == "planar":
        nb = target.n // 3
        Q[:, 2::3] = rng.choice([-1.0, 1.0], (count, nb)) * rng.uniform(np.pi, 4 * np.pi, (count, nb))
    return Samples(Q, rng.normal(0.0, 2.0, Q.shape), rng.uniform(1.0, 30.0, count))


def assembled(target):
    """Configurations on the target's constraint manifold with consistent velocities (see the module)."""
    rng = np.random.default_rng(SEED + 1)
    q0 = target.mech.q0
    base, _, ok = project(target, q0[None], np.zeros(1))
    base = base if ok.all() else q0[None]
    found_Q, found_T = [], []
    for size in ((None,) if getattr(target, "partial", False) else ()) + (0.25, 0.6):
        idx = rng.integers(0, len(base), 2 * N_ASSEMBLED)
        starts = spread(target, rng, 2 * N_ASSEMBLED) if size is None else perturbed(target, rng, base[idx], size)
        Q, T, ok = project(target, starts, rng.uniform(0.0, 0.3, len(starts)))
        Q, T = regular(target, Q[ok], T[ok])
        found_Q.append(Q)
        found_T.append(T)
        if sum(len(x) for x in found_Q) >= N_ASSEMBLED:
            break
        if len(Q):
            base = Q
    Q, T = np.vstack(found_Q), np.concatenate(found_T)
    if len(Q) < 4:
        return generic(target)
    pick = np.linspace(0, len(Q) - 1, min(N_ASSEMBLED, len(Q))).round().astype(int)
    Q, T = Q[pick], T[pick]
    if target.time_dependent:
        WQ, WT = wide_assembled(target, Q, np.random.default_rng(SEED + 4))
        Q, T = np.vstack([Q, WQ]), np.concatenate([T, WT])
    QD = velocities(target, Q, T, rng)
    return Samples(Q, QD, T, on_manifold=True)


def wide_assembled(target, base, rng, count=None):
    """Up to ``count`` (:data:`N_WIDE`) assembled configurations at instants t from 1 to 30 (the rows depend on
    time): from the assembled ones, projected in q at that t (a driver's angle then far beyond ±π)."""
    count = N_WIDE if count is None else count
    starts = base[rng.integers(0, len(base), 2 * count)]
    T = rng.uniform(1.0, 30.0, len(starts))
    Q, T, ok = project(target, starts, T, hold_t=True)
    Q, T = regular(target, Q[ok], T[ok])
    return Q[:count], T[:count]


def zeros(target, F, count=N_SEARCH, starts=None):
    """Configurations where the rows ``F`` vanish (with the bodies' normalization rows, in space): seeded
    minimum-norm Newton searches from starts spread over the whole configuration space and around the target's
    assembled samples — in (q, t) when the target's rows depend on time.

    Parameters
    ----------
    F : callable
        ``F(Q, T) -> (values (B, r), gradients (B, r, n), time derivatives (B, r))``.
    starts : (Q (K, n), T (K,)), optional
        Where to start instead (the zeros of one factor of a row: :func:`kinbook.grading.factors.starts`).

    Returns
    -------
    Q (K, n), T (K,) : the starts that converged (t ≥ 0: time starts at 0).
    """
    if starts is None:
        rng = np.random.default_rng(SEED + 2)
        Q = [spread(target, rng, count // 2)]
        base = target.samples("assembled").Q
        Q.append(perturbed(target, rng, base[rng.integers(0, len(base), count - count // 2)], 0.8))
        Q = np.vstack(Q)
        T = rng.uniform(0.0, 1.0, len(Q))
    else:
        Q, T = np.array(starts[0], float), np.array(starts[1], float)
    norm = np.array([r for c in target.mech.constraints if c.kind == "normalization"
                     for r in range(c.rows.start, c.rows.stop)], dtype=int)
    with_t = target.time_dependent
    ok = np.zeros(len(Q), bool)
    active = np.arange(len(Q))
    with np.errstate(all="ignore"):
        for _ in range(_NEWTON_STEPS):
            v, g, d = F(Q[active], T[active])
            J = np.concatenate([g, d[:, :, None]], axis=2)
            if norm.size:
                ev = target.mech.evaluate(Q[active], T[active])
                v = np.concatenate([v, ev["Phi"][:, norm]], axis=1)
                Jn = np.concatenate([ev["Phi_q"][:, norm, :], np.zeros((len(active), len(norm), 1))], axis=2)
                J = np.concatenate([J, Jn], axis=1)
            if not with_t:
                J = J[:, :, :-1]
            res = np.abs(v).max(axis=1)
            scale = 1.0 + np.abs(Q[active]).max(axis=1) + np.abs(J).max(axis=(1, 2))
            done = np.isfinite(res) & (res < 1e-11 * scale)
            ok[active[done]] = True
            keep = ~done & np.isfinite(res) & (res < 1e6) & np.all(np.isfinite(J), axis=(1, 2))
            active, v, J = active[keep], v[keep], J[keep]
            if not len(active):
                break
            step = _min_norm_step(J, v)
            Q[active] -= step[:, : target.n]
            if with_t:
                T[active] -= step[:, -1]
    ok &= T >= 0.0
    return Q[ok], T[ok]


def placements(target, Q, T, cols=None):
    """The configurations that place every body as (Q, T) does: each planar angle of the coordinates ``cols``
    (default all) turned by a whole number of turns (−2 … 2), each spatial body's Euler parameters negated.

    Returns
    -------
    Q (K·P, n), T (K·P,) : for each configuration its P placements, the configuration itself first.
    """
    Q = np.atleast_2d(np.asarray(Q, float))
    T = np.asarray(T, float).reshape(-1)
    cols = range(target.n) if cols is None else cols
    ncoord = 3 if target.kind == "planar" else 7
    if target.kind == "planar":
        axes = sorted({c for c in cols if c % ncoord == 2})
        steps = [m * 2 * np.pi for m in (0, 1, -1, 2, -2)]
    else:
        axes = sorted({c // ncoord for c in cols})
        steps = [1.0, -1.0]
    axes = axes[:4]  # at most 5**4 (or 2**4) placements per configuration
    shifts = list(itertools.product(steps, repeat=len(axes)))
    out = np.repeat(Q, len(shifts), axis=0).reshape(len(Q), len(shifts), -1)
    for p, shift in enumerate(shifts):
        for a, d in zip(axes, shift):
            if target.kind == "planar":
                out[:, p, a] += d
            else:
                out[:, p, ncoord * a + 3: ncoord * a + 7] *= d
    return out.reshape(-1, Q.shape[1]), np.repeat(T, len(shifts))


def at(target, configuration):
    """One instant given by the caller: ``{"q": …, "qd": …, "t": …}`` (missing q̇ solved when possible)."""
    mech = target.mech
    conf = dict(configuration)
    t = float(conf.get("t", 0.0))
    q = np.asarray(conf["q"], float) if "q" in conf else mech.solve_position(t)
    if "qd" in conf:
        qd = np.asarray(conf["qd"], float)
    else:
        qd = velocities(target, q[None], np.array([t]), np.random.default_rng(SEED))[0]
    return Samples(q[None], qd[None], np.array([t]), on_manifold=False)


# ---------------------------------------------------------------------------------------------- helpers
def spread(target, rng, count):
    """Starts anywhere in the configuration space (a joint graded alone: its bodies may be anywhere)."""
    n = target.n
    Q = rng.uniform(-3.0, 3.0, (count, n))
    if target.kind == "planar":
        Q[:, 2::3] = rng.uniform(-np.pi, np.pi, (count, n // 3))
    else:
        Q.reshape(count, n // 7, 7)[:, :, 3:] = random_p(count * (n // 7), rng).reshape(count, n // 7, 4)
    return Q


def perturbed(target, rng, base, size):
    count, n = base.shape
    Q = base + rng.normal(0.0, size, (count, n))
    if target.kind == "spatial":
        P = Q.reshape(count, n // 7, 7)[:, :, 3:]
        P /= np.linalg.norm(P, axis=2, keepdims=True)
    return Q


def project(target, Q, T, steps=_NEWTON_STEPS, hold_t=False):
    """Minimum-norm Newton steps onto the manifold rows, in (q, t) when they depend on time (in q alone with
    ``hold_t``)."""
    Q, T = Q.copy(), T.copy()
    with_t = target.time_dependent and not hold_t
    ok = np.zeros(len(Q), bool)
    active = np.arange(len(Q))
    for _ in range(steps):
        F, J = target.manifold(Q[active], T[active])
        if not with_t:
            J = J[:, :, :-1]
        res = np.abs(F).max(axis=1) if F.size else np.zeros(len(active))
        done = np.isfinite(res) & (res < _TOL * (1.0 + np.abs(Q[active]).max(axis=1)))
        ok[active[done]] = True
        keep = ~done & np.isfinite(res) & (res < 1e6)
        active, F, J = active[keep], F[keep], J[keep]
        if not len(active):
            break
        step = _min_norm_step(J, F)
        Q[active] -= step[:, : target.n]
        if with_t:
            T[active] -= step[:, -1]
    if ok.any():  # one more step: from a residual of 1e-12 to rounding level
        idx = np.flatnonzero(ok)
        F, J = target.manifold(Q[idx], T[idx])
        if not with_t:
            J = J[:, :, :-1]
        step = _min_norm_step(J, F)
        if np.all(np.isfinite(step)):
            Q[idx] -= step[:, : target.n]
            if with_t:
                T[idx] -= step[:, -1]
    return Q, T, ok


def _min_norm_step(J, F):
    """The minimum-norm solutions x of J x = F (batched): Jᵀ(J Jᵀ)⁻¹F where J has full row rank (a Cholesky-
    sized solve), the pseudo-inverse where it does not (redundant rows)."""
    JJ = J @ np.swapaxes(J, 1, 2)
    step = np.full((J.shape[0], J.shape[2]), np.nan)
    try:
        y = np.linalg.solve(JJ, F[..., None])[..., 0]
        step = np.einsum("bji,bj->bi", J, y)
    except np.linalg.LinAlgError:
        pass
    bad = ~np.all(np.isfinite(step), axis=1)
    if bad.any():
        step[bad] = np.einsum("bij,bj->bi", np.linalg.pinv(J[bad], rcond=1e-10), F[bad])
    step[~np.isfinite(step)] = 0.0
    return step


def regular(target, Q, T):
    """Keep the configurations where Φ_q of the manifold rows has the largest rank found, well conditioned."""
    if len(Q) == 0:
        return Q, T
    F, J = target.manifold(Q, T)
    J = J[:, :, :-1]
    s = np.linalg.svd(J, compute_uv=False)
    if s.shape[1] == 0:
        return Q, T
    rel = s / np.maximum(s[:, :1], 1e-300)
    rank = (rel > 1e-9).sum(axis=1)
    full = rank.max()
    good = (rank == full) & (rel[:, full - 1] > 1e-6)
    return Q[good], T[good]


def velocities(target, Q, T, rng):
    """q̇ with Φ_q q̇ = ν on the manifold rows: the minimum-norm solution plus a random allowed motion."""
    ev = target.mech.evaluate(Q, T)
    rows = target.manifold_rows
    J, nu = ev["Phi_q"][:, rows, :], ev["nu"][:, rows]
    pinv = np.linalg.pinv(J)
    particular = np.einsum("bij,bj->bi", pinv, nu)
    z = rng.normal(0.0, 2.0, Q.shape)
    free = z - np.einsum("bij,bj->bi", pinv, np.einsum("bij,bj->bi", J, z))
    return particular + free
