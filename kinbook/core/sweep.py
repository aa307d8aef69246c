"""Motion over many instants: a kinematic sweep (:func:`simulate`, vectorized over the instants) and the
continuation that follows one assembly branch to its limit (:func:`follow`, :func:`follow_times`).
"""

from __future__ import annotations

import html
import math
from dataclasses import dataclass

import numpy as np

from ..errors import (
    AssemblyError,
    ConvergenceError,
    DeadPointError,
    DriverValueError,
    InputError,
    KinbookError,
    RedundantConstraintsError,
)
from ._linalg import column_scale, scalar_time
from .diagnose import RCOND_MIN, diagnose
from .solve import STEP_TOL, check_drivers, check_tol, solve_acceleration, solve_position, solve_velocity

__all__ = ["simulate", "SimulationResult", "follow", "follow_times", "Continuation"]

MAX_SWEEP_VALUES = 20_000_000
"""Most instants × coordinates in one :func:`simulate` (each of q, q̇, q̈ then takes 160 MB)."""


@dataclass
class SimulationResult:
    """Positions, velocities and accelerations over a sweep of instants.

    Attributes
    ----------
    mechanism
    t : ndarray, shape (N,)
    q, qd, qdd : ndarray, shape (N, n)
    failure : AssemblyError or None
        Set when the sweep stopped early (``on_failure="truncate"``); ``t`` then holds the solved instants only.
    """

    mechanism: object
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    failure: AssemblyError | None = None

    def __len__(self):
        return len(self.t)

    def coordinate(self, name, derivative=0):
        """Time history of one coordinate ('phi3' or (body, 'phi')) or of its first or second derivative
        (``derivative`` 0, 1 or 2)."""
        if isinstance(derivative, bool) or not isinstance(derivative, (int, np.integer)) or derivative not in (0, 1, 2):
            raise InputError(f"`derivative` must be 0 (the coordinate), 1 (its velocity) or 2 (its acceleration), "
                             f"got {derivative!r}"[:200])
        k = self.mechanism.index(name)
        return (self.q, self.qd, self.qdd)[int(derivative)][:, k]

    def position(self, body, point):
        """Global positions of a body point at every instant, shape (N, 2) (planar) or (N, 3) (spatial)."""
        return self.mechanism.point_position(self.q, body, point)

    def velocity(self, body, point):
        """Global velocities of a body point, shape (N, 2) or (N, 3)."""
        return self.mechanism.point_velocity(self.q, self.qd, body, point)

    def acceleration(self, body, point):
        """Global accelerations of a body point, shape (N, 2) or (N, 3)."""
        return self.mechanism.point_acceleration(self.q, self.qd, self.qdd, body, point)

    def _summary(self):
        mech = self.mechanism
        if len(self.t):
            text = (f"sweep of '{mech.name}': {len(self.t)} instants, t from {self.t[0]:.6g} to {self.t[-1]:.6g}; "
                    f"max |Φ| = {np.max(np.abs(mech.Phi(self.q, self.t))):.2g}")
        else:
            text = f"sweep of '{mech.name}': no instant solved"
        if self.failure is not None:
            text += f". Stopped early: {self.failure}"
        return text

    def __repr__(self):
        return f"<SimulationResult: {self._summary()}>"

    def _repr_html_(self):
        return f"<p>{html.escape(self._summary())}</p>"


def _batch_solve(mech, guess, T, tol, max_iter=8):
    """Solve position, velocity and acceleration at many instants at once.

    Newton–Raphson over the whole batch: each iteration evaluates Φ and Φ_q at the instants not yet
    converged and solves the stacked linear systems (numpy's batched LU: one solve costs a third of an
    inverse). Φ_q and ν at the converged configuration then give q̇, and γ there gives q̈. With Taylor guesses
    from a nearby solved instant one step usually suffices. Fixed bodies are set aside
    (:attr:`MechanismBase.reduction`): only the other rows and columns of Φ_q enter the solves.

    Returns (q, qd, qdd, converged); rows that did not converge hold garbage.
    """
    q = guess.copy()
    red = mech.reduction
    rows, cols = red if red is not None else (np.arange(mech.m), np.arange(q.shape[1]))  # ``reduced=True`` Φ_q's
    with np.errstate(all="ignore"):
        J, nu, P, conv = _batch_newton(mech, q, T, tol, max_iter, rows, cols)
        qd, qdd = _batch_rates(mech, q, T, J, nu, P, conv, rows, cols)
    return q, qd, qdd, conv


def _batch_newton(mech, q, T, tol, max_iter, rows, cols):
    """Newton–Raphson on every instant of the batch at once, ``q`` updated in place. Returns, at each converged
    iterate, the reduced Φ_q, ν and Φ (garbage elsewhere), and which instants converged."""
    Bn = q.shape[0]
    J = np.empty((Bn, len(rows), len(cols)))
    nu = np.empty((Bn, mech.m))
    P = np.empty((Bn, mech.m))  # Φ at the converged iterate, for the step test
    conv = np.zeros(Bn, dtype=bool)
    act = np.arange(Bn)
    for _ in range(max_iter + 1):
        whole = act.size == Bn
        ev = mech.evaluate(q if whole else q[act], T if whole else T[act], reduced=True)
        Phi, Jr = ev["Phi"], ev["Phi_q"]
        res = np.max(np.abs(Phi), axis=1)
        done = res <= tol
        if whole and done.all():  # the usual last iteration: no copies
            conv[:], J, nu, P = True, Jr, ev["nu"], Phi
            break
        k = act[done]
        conv[k] = True
        J[k] = Jr[done]
        nu[k] = ev["nu"][done]
        P[k] = Phi[done]
        keep = ~done & np.isfinite(res)
        act, Phi = act[keep], Phi[keep]
        if act.size == 0:
            break
        Ja = Jr[keep]
        try:
            step = np.linalg.solve(Ja, Phi[:, rows, None])[..., 0]
        except np.linalg.LinAlgError:  # some Φ_q is singular: solve the others one at a time
            step = np.full((len(act), len(cols)), np.nan)
            for i in range(len(act)):
                try:
                    step[i] = np.linalg.solve(Ja[i], Phi[i, rows])
                except np.linalg.LinAlgError:
                    pass
        q[act[:, None], cols] -= step
        ok = np.all(np.isfinite(q[act]), axis=1)
        q[act[~ok]] = 0.0
        act = act[ok]
        if act.size == 0:
            break
    return J, nu, P, conv


def _batch_rates(mech, q, T, J, nu, P, conv, rows, cols):
    """q̇ and q̈ at the converged instants of the batch (one factorization of Φ_q for ν, Φ and a probe of its
    conditioning, then γ); ``conv`` loses the instants whose step or conditioning is not sound."""
    Bn, n = q.shape
    qd, qdd = np.zeros_like(q), np.zeros_like(q)
    k = np.nonzero(conv)[0]
    if not k.size:
        return qd, qdd
    Jk = J if k.size == Bn else J[k]

    def solve(b):
        try:
            x = np.linalg.solve(Jk, b[:, rows, None])[..., 0]
        except np.linalg.LinAlgError:
            return np.full((len(k), n), np.nan)
        full = np.zeros((len(k), n))  # a fixed body's rows have ν = γ = 0: its q̇ and q̈ are zero
        full[:, cols] = x
        return full

    whole = k.size == Bn
    # one factorization, three right-hand sides: ν gives q̇; Φ gives the Newton step from the iterate
    # (its distance to the solution: at most STEP_TOL, as in solve_position); a seeded random vector b
    # gives ‖J̃⁻¹ b‖ ≳ 1/(√n σ_min) of the scaled Φ_q — instants that may be near a singular configuration
    # are left unsolved, for solve_position's exact test
    scale = column_scale(mech)[cols]
    rn = np.sqrt(np.einsum("bij,bij,j->bi", Jk, Jk, scale * scale))
    probe = np.random.default_rng(0).standard_normal(len(rows))
    rhs = np.stack([(nu if whole else nu[k])[:, rows], (P if whole else P[k])[:, rows], probe * rn], -1)
    try:
        X = np.linalg.solve(Jk, rhs)
    except np.linalg.LinAlgError:
        X = np.full(rhs.shape, np.nan)
    v = np.zeros((len(k), n))  # a fixed body's rows have ν = γ = 0: its q̇ and q̈ are zero
    v[:, cols] = X[..., 0]
    step = np.max(np.abs(X[..., 1] / scale), axis=1)
    grow = np.linalg.norm(X[..., 2] / scale, axis=1) / np.linalg.norm(probe)
    # flagged when the estimate puts σ_min/σ_max within a factor 100 of RCOND_MIN (σ_max ≤ √n)
    sound = (step <= STEP_TOL) & (grow * 1e2 * RCOND_MIN * len(cols) < 1)
    v_ok = np.where(np.isfinite(v), v, 0.0)
    a = solve(mech.evaluate(q if whole else q[k], T if whole else T[k], v_ok, jacobian=False)["gamma"])
    qd[k], qdd[k] = v, a
    conv[k] = np.all(np.isfinite(v), axis=1) & np.all(np.isfinite(a), axis=1) & sound
    return qd, qdd


def _hermite5(t, t0, t1, start, end):
    """Quintic Hermite interpolation at times ``t`` between (q, q̇, q̈) ``start`` at ``t0`` and ``end`` at ``t1``
    (arrays of shape (B, n), one interval per row): exact for polynomials of degree 5."""
    h = (t1 - t0)[:, None]
    s = ((t - t0) / (t1 - t0))[:, None]
    s2, s3 = s * s, s * s * s
    s4, s5 = s3 * s, s3 * s2
    (q0, v0, a0), (q1, v1, a1) = start, end
    return ((1 - 10 * s3 + 15 * s4 - 6 * s5) * q0 + (s - 6 * s3 + 8 * s4 - 3 * s5) * h * v0
            + (0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5) * h * h * a0
            + (10 * s3 - 15 * s4 + 6 * s5) * q1 + (-4 * s3 + 7 * s4 - 3 * s5) * h * v1
            + (0.5 * s3 - s4 + 0.5 * s5) * h * h * a1)


def _driver_text(mech, name, value):
    c = mech.constraint(name)
    angle = (c.measures or (None,))[-1] == "angle"
    return f"driver '{name}' = {value:.6g}" + (f" rad = {np.degrees(value):.2f}°" if angle else "")


def _driver_values(mech, t):
    values = {}
    for c in mech.drivers:
        v = complex(c.f.subs(mech.t, t).evalf())
        values[c.name] = v.real if v.imag == 0 else float("nan")
    return values


def simulate(mech, times, q0=None, tol=1e-10, on_failure="raise", anchor_every=512):
    """Kinematic sweep: position, velocity and acceleration at every instant of ``times``.

    How: a few *anchor* instants are solved one after the other, each from a Taylor prediction
    q + q̇ Δt + ½ q̈ Δt² of the previous one, with anchors close enough that the predicted motion stays small;
    the instants between anchors are then solved in batches (every 64th, every 8th, then all), each batch by
    a vectorized Newton–Raphson over all its instants at once from Taylor predictions of the nearest solved
    instant. A batched solution is accepted only if it lies where the prediction said (so the mechanism
    cannot jump to another assembly branch); anything not accepted is solved one instant at a time.

    Parameters
    ----------
    times : array_like, shape (N,)
        Instants, in the order the mechanism should move through them.
    q0 : array_like, optional
        Initial guess at ``times[0]``. By default the bodies' q0, which describe the mechanism at t = 0: when
        ``times[0]`` is not 0 the motion is first followed from t = 0 to ``times[0]``, so the sweep stays on
        the assembly branch q0 describes.
    tol : float
        Newton–Raphson tolerance on max |Φ_k|.
    on_failure : {"raise", "truncate"}
        What to do when the mechanism cannot be assembled at some instant (for example when a crank is driven
        past a dead point): raise :class:`AssemblyError` (its ``partial`` attribute holds the instants solved
        before) or return the solved instants with ``result.failure`` set.
    anchor_every : int
        Most instants between two anchors. ``anchor_every=1`` solves every instant in sequence.

    Returns
    -------
    SimulationResult
    """
    T, tol = _sweep_args(mech, times, tol, on_failure, anchor_every)
    return _Sweep(mech, T, tol, on_failure).run(q0, anchor_every)


def _sweep_args(mech, times, tol, on_failure, anchor_every):
    """:func:`simulate`'s arguments checked: (the instants as floats, the tolerance)."""
    if on_failure not in ("raise", "truncate"):
        raise InputError(f"`on_failure` must be 'raise' or 'truncate', got {on_failure!r}")
    check_drivers(mech)
    tol, _ = check_tol(tol, 1)
    if isinstance(anchor_every, bool) or not isinstance(anchor_every, (int, np.integer)) or anchor_every < 1:
        raise InputError(f"`anchor_every` must be a whole number ≥ 1, got {anchor_every!r}")
    if np.ndim(times) != 1 or np.size(times) == 0:
        raise InputError(f"`times` must be a non-empty 1-D array of instants, got shape {np.shape(times)}")
    if np.size(times) * mech.n > MAX_SWEEP_VALUES:
        raise InputError(
            f"`times` has {np.size(times):,} instants × {mech.n} coordinates = {np.size(times) * mech.n:.3g} values, "
            f"more than the {MAX_SWEEP_VALUES:.0e} one sweep holds (each of q, q̇, q̈ would take "
            f"{8 * np.size(times) * mech.n / 1e9:.2g} GB): sweep fewer instants, or in pieces")
    try:
        T = np.asarray(times, dtype=float)
    except (TypeError, ValueError):
        raise InputError("`times` must be an array of numbers") from None
    if not np.all(np.isfinite(T)):
        k = int(np.flatnonzero(~np.isfinite(T))[0])
        raise InputError(f"`times` must be finite, got times[{k}] = {T[k]}")
    return T, tol


class _Sweep:
    """One sweep (:func:`simulate`): its instants, the solutions found so far and which instants they solve."""

    def __init__(self, mech, T, tol, on_failure):
        self.mech, self.T, self.tol, self.on_failure = mech, T, tol, on_failure
        N, n = len(T), mech.n
        self.Q, self.QD, self.QDD = np.zeros((N, n)), np.zeros((N, n)), np.zeros((N, n))
        self.solved = np.zeros(N, dtype=bool)

    def run(self, q0, anchor_every):
        """1. anchors, in sequence, spaced so that the predicted motion between two stays small; 2. everything
        between anchors, in batches."""
        mech, T = self.mech, self.T
        if q0 is None and T[0] != 0.0:
            # the bodies' q0 is a guess for t = 0: follow the motion from there to times[0], so that the sweep
            # starts on the assembly branch the guess describes (a direct solve far from t = 0 may land on the
            # other branch)
            try:
                lead = simulate(mech, np.linspace(0.0, T[0], 257), q0=mech.q0, tol=self.tol,
                                anchor_every=anchor_every)
                q0 = lead.q[-1]
            except (AssemblyError, DriverValueError):  # f(t) may be undefined between 0 and times[0]
                q0 = None
        err = self.solve_one(0, [None if q0 is None else np.asarray(q0, dtype=float)])
        if err is not None:
            return self.fail(0, err)
        stopped = self.anchors(max(1, int(anchor_every)))
        if stopped is None:
            stopped = self.fill(len(T))
        if stopped is not None:
            return stopped
        return SimulationResult(mech, T.copy(), self.Q, self.QD, self.QDD)

    def anchors(self, limit):
        """Solve anchor after anchor up to the last instant; a failed result when the mechanism stops."""
        mech, T, Q, QD, QDD, solved = self.mech, self.T, self.Q, self.QD, self.QDD, self.solved
        N, p = len(T), 0
        while p < N - 1:
            speed = np.max(np.abs(QD[p])) + 1e-300
            scale = 1.0 + np.max(np.abs(Q[p]))
            reach = np.searchsorted(T, T[p] + 0.1 * scale / speed, side="right") - 1 if np.all(np.diff(T) > 0) \
                else p + 1
            a = int(min(N - 1, p + limit, max(p + 1, reach)))
            guess = self.predict(p, a)
            # the batched solver on this one instant: three evaluations of Φ (solve_one makes five), and
            # solve_one's diagnosis only when it fails
            q, qd, qdd, conv = _batch_solve(mech, guess[None], T[a : a + 1], self.tol)
            if conv[0] and (a == p + 1 or self.plausible(q[0], guess, Q[p])):
                Q[a], QD[a], QDD[a], solved[a] = q[0], qd[0], qdd[0], True
                p = a
                continue
            if self.solve_one(a, [guess]) is None and (a == p + 1 or self.plausible(Q[a], guess, Q[p])):
                p = a
                continue
            solved[a] = False
            stopped = self.fill(p + 1)
            if stopped is not None:
                return stopped
            for k in range(p + 1, a + 1):  # step one instant at a time to the next anchor
                e = self.solve_one(k, [self.predict(k - 1, k), Q[k - 1]])
                if e is not None:
                    stopped = self.fill(k)
                    return stopped if stopped is not None else self.fail(k, e)
            p = a
        return None

    def solve_one(self, k, guesses):
        """Solve instant k from the first guess that converges; the last error when none does."""
        mech, T = self.mech, self.T
        last = None
        for g in guesses:
            try:
                q = solve_position(mech, T[k], q0=g, tol=self.tol, max_iter=25)
                qd = solve_velocity(mech, q, T[k])
                qdd = solve_acceleration(mech, q, qd, T[k])
            except (ConvergenceError, DeadPointError, RedundantConstraintsError) as exc:
                last = exc
                continue
            self.Q[k], self.QD[k], self.QDD[k] = q, qd, qdd
            self.solved[k] = True
            return None
        return last

    def predict(self, j, k):
        """Taylor's prediction of instant k from the solved instant j."""
        dt = self.T[k] - self.T[j]
        return self.Q[j] + self.QD[j] * dt + 0.5 * self.QDD[j] * dt * dt

    @staticmethod
    def plausible(q, guess, base):
        """The solution is where the Taylor prediction put it, relative to the motion from the base."""
        err = np.max(np.abs(q - guess), axis=-1)
        step = np.max(np.abs(q - base), axis=-1)
        return err <= 0.1 * step + 1e-7 * (1 + np.max(np.abs(q), axis=-1))

    def fail(self, k, cause):
        """The sweep stops at instant k: an AssemblyError raised, or the instants before it returned."""
        mech, T, Q = self.mech, self.T, self.Q
        partial = SimulationResult(mech, T[:k].copy(), Q[:k].copy(), self.QD[:k].copy(), self.QDD[:k].copy())
        drivers = _driver_values(mech, T[k])
        dv = ", ".join(_driver_text(mech, name, v) for name, v in drivers.items())
        text = f"mechanism '{mech.name}' cannot be assembled at t = {T[k]:.6g} ({dv})"
        if isinstance(cause, ConvergenceError):
            text += f": Newton–Raphson finds no configuration there (max |Φ| = {cause.residual:.3g} after " \
                    f"{cause.iterations} iterations)"
        elif cause is not None:
            text += f": {str(cause).split(': ', 1)[-1]}"
        if k:
            first, last = diagnose(mech, Q[0], T[0]), diagnose(mech, Q[k - 1], T[k - 1])
            text += f". The last assembled instant is t = {T[k - 1]:.6g}, where cond(Φ_q) = {last.cond:.3g}"
            if last.cond > 5 * first.cond:
                text += (f" (it was {first.cond:.3g} at t = {T[0]:.6g}): the driver has reached a dead point, a "
                         "limit position beyond which the mechanism does not assemble")
        err = AssemblyError(text, t=float(T[k]), drivers=drivers, partial=partial, cause=cause)
        if self.on_failure == "raise":
            raise err
        partial.failure = err
        return partial

    def batch(self, indices):
        """Solve the given unsolved instants at once. The guess interpolates between the solved instants on
        either side (quintic Hermite through q, q̇, q̈ at both: good enough that most instants of the last
        batch need no Newton step at all), or extrapolates from the one before (Taylor)."""
        T, Q, QD, QDD, solved = self.T, self.Q, self.QD, self.QDD, self.solved
        indices = indices[~solved[indices]]
        if indices.size == 0:
            return
        done = np.nonzero(solved)[0]
        pos = np.searchsorted(done, indices) - 1
        ok = pos >= 0
        indices, pos = indices[ok], pos[ok]
        base = done[pos]
        dt = (T[indices] - T[base])[:, None]
        guess = Q[base] + QD[base] * dt + 0.5 * QDD[base] * dt * dt
        between = pos + 1 < len(done)
        if between.any():
            k, k0, k1 = indices[between], base[between], done[pos[between] + 1]
            guess[between] = _hermite5(T[k], T[k0], T[k1], (Q[k0], QD[k0], QDD[k0]), (Q[k1], QD[k1], QDD[k1]))
        q, qd, qdd, conv = _batch_solve(self.mech, guess, T[indices], self.tol)
        conv &= self.plausible(q, guess, Q[base])
        good = indices[conv]
        Q[good], QD[good], QDD[good] = q[conv], qd[conv], qdd[conv]
        solved[good] = True

    def fill(self, upto):
        """Solve every instant before ``upto``: batches of decreasing stride, then stragglers in sequence."""
        for stride in (64, 8, 1):
            idx = np.arange(0, upto, stride)
            if idx.size:
                self.batch(idx)
        for k in np.nonzero(~self.solved[:upto])[0]:
            e = self.solve_one(k, [self.predict(k - 1, k), self.Q[k - 1]])
            if e is not None:
                return self.fail(k, e)
        return None


@dataclass(frozen=True)
class Continuation:
    """How far following the motion toward an instant got (:func:`follow`).

    Attributes
    ----------
    t : float
        The instant reached: the one asked for when ``reached``, else the *limit*, the last instant at which the
        mechanism still assembles on the branch that was followed (within ``min_step`` of where it stops).
    q : ndarray, shape (n,), or None
        The configuration at ``t`` (None when not even the start assembles).
    reached : bool
    failure : KinbookError or None
        Why the next step past the limit failed (no convergence, a dead point …).
    """

    t: float
    q: np.ndarray | None
    reached: bool
    failure: KinbookError | None = None


_STEP_ERRORS = (KinbookError, np.linalg.LinAlgError, FloatingPointError)


def follow(mech, t_to, *, t_from, q_from, max_step, min_step=None):
    """Follow the assembly of ``mech`` from a solution ``q_from`` at ``t_from`` to ``t_to`` by continuation.

    Position solves (Newton–Raphson from the previous solution) in steps of at most ``max_step``, halved
    whenever a step fails, so the solution stays on the assembly branch of ``q_from``. When steps shorter
    than ``min_step`` still fail, the mechanism stops there: the result holds the last configuration that
    assembled, the *limit* (at a dead point, the limit position the driver cannot move past).

    Parameters
    ----------
    t_to, t_from : float
    q_from : array_like, shape (n,)
        A solution at ``t_from``.
    max_step : float
        Largest step in t (> 0).
    min_step : float, optional
        Precision of the limit in t; default ``max_step / 1024``.

    Returns
    -------
    Continuation
    """
    t_from, t_to, max_step = scalar_time(t_from), scalar_time(t_to), float(max_step)
    if not max_step > 0:
        raise InputError(f"`max_step` must be positive, got {max_step}")
    min_step = max_step / 1024 if min_step is None else float(min_step)
    q, t = np.array(mech.check_q(q_from), dtype=float), t_from
    step, last = max_step, None
    while t != t_to:
        h = min(step, abs(t_to - t))
        t_next = t_to if h == abs(t_to - t) else t + math.copysign(h, t_to - t)
        try:
            q = mech.solve_position(t_next, q0=q, max_iter=15)
            t = t_next
        except _STEP_ERRORS as exc:
            last = exc if isinstance(exc, KinbookError) else None
            if step <= min_step:
                return Continuation(t, q, False, last)
            step /= 2
    return Continuation(t, q, True, None)


def follow_times(mech, times, *, t0=0.0, q0=None, max_step):
    """Configurations at many instants, all on the assembly branch of the solution at ``t0``.

    The motion is followed (:func:`follow`) from the assembly at ``t0`` (solved from ``q0``, default the
    bodies' q0) upward through the instants after ``t0`` in increasing order, and downward through those
    before it. Past a limit the mechanism does not assemble on that branch: every farther instant gets that
    limit. When nothing assembles at ``t0``, each instant is solved on its own from ``q0``.

    Returns
    -------
    list of Continuation, one per instant of ``times``, in their order.
    """
    times = [scalar_time(v) for v in np.atleast_1d(times)]
    try:
        start = solve_position(mech, t0, q0=q0)
    except KinbookError:
        out = []
        for t in times:
            try:
                out.append(Continuation(t, solve_position(mech, t, q0=q0), True))
            except KinbookError as exc:
                out.append(Continuation(t, None, False, exc))
        return out
    out = [None] * len(times)
    up = sorted((k for k, t in enumerate(times) if t >= t0), key=lambda k: times[k])
    down = sorted((k for k, t in enumerate(times) if t < t0), key=lambda k: -times[k])
    for order in (up, down):
        at = Continuation(t0, start, True)
        for k in order:
            if at.reached:
                at = follow(mech, times[k], t_from=at.t, q_from=at.q, max_step=max_step)
            out[k] = at
    return out
