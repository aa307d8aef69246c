"""Kinematic analysis at one instant (textbook §13.6–13.8, §14.5): position by Newton–Raphson, velocity and
acceleration.

The functions take any mechanism built on :class:`kinbook.core.mechanism.MechanismBase` (planar or spatial): they
use only its numeric interface (``evaluate``, ``n``, ``m``, ``constraints`` …).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import (
    ConvergenceError,
    DriverCountError,
    InputError,
)
from ._linalg import (
    SPARSE_ABOVE,
    column_scale,
    condition_number,
    describe_rows,
    evaluate_jacobian,
    row_owner,
    scalar_time,
    scaled_rcond,
    solve_linear,
)
from .diagnose import RCOND_MIN, raise_singular

__all__ = ["check_drivers", "solve_position", "solve_velocity", "solve_acceleration", "NewtonHistory", "STEP_TOL",
           "check_tol"]

STEP_TOL = 1e-8
"""Newton–Raphson has converged when max |Φ| ≤ ``tol`` *and* the Newton step from the iterate, the estimate of
its distance to the solution, is at most this (positions in units of L, angles in radians, Euler parameters as
they are): near a singular configuration a small |Φ| alone can leave q far from the solution."""


def check_drivers(mech):
    """Raise :class:`DriverCountError` unless Φ is square: as many driver equations as degrees of freedom."""
    n, m_geo = mech.n, mech.m_geometric
    k = mech.m - m_geo
    if mech.m == n:
        return
    dof = n - m_geo
    names = ", ".join(f"'{c.name}'" for c in mech.drivers) or "none"
    if dof < 0:
        repeated = _repeated(mech)
        raise DriverCountError(
            f"mechanism '{mech.name}' has {m_geo} geometric constraint equations for only n = {n} coordinates: "
            f"it is overconstrained by {-dof} equation(s) before any driver (drivers: {names})"
            + (f"; these repeat what each other impose: {repeated}" if repeated else "")
        )
    hints = _free_motions(mech) if k < dof else []
    raise DriverCountError(
        f"mechanism '{mech.name}' has n = {n} coordinates and {m_geo} geometric constraint equations, so "
        f"{dof} degree(s) of freedom, but {k} driver equation(s) ({names}): "
        + ("add" if k < dof else "remove") + f" {abs(dof - k)} driver(s) so that Φ has as many rows as q"
        + "".join(f"; {h}" for h in hints)
    )


def _repeated(mech):
    """The geometric constraints whose rows of Φ_q at q0 depend on each other (a joint written twice), described;
    "" when it cannot be told (a hint only: the count is the error)."""
    if not mech.bodies or mech.n > 2000:
        return ""
    try:
        with np.errstate(all="ignore"):
            J = np.asarray(mech.evaluate(mech.q0, 0.0)["Phi_q"], dtype=float)
        geo = [r for c in mech.constraints if c.kind != "driver" for r in range(c.rows.start, c.rows.stop)]
        Jg = J[geo]
        if not np.all(np.isfinite(Jg)):
            return ""
        U, sv, _ = np.linalg.svd(Jg, full_matrices=True)
        rank = int(np.sum(sv > 1e-9 * max(sv[0], 1e-300))) if sv.size else 0
        if rank == len(geo):
            return ""
        weight = np.linalg.norm(U[:, rank:], axis=1)
        return describe_rows(mech, [geo[i] for i in np.nonzero(weight > 1e-6)[0]])
    except Exception:  # noqa: BLE001 - a hint only
        return ""


def _free_motions(mech):
    """Why a mechanism has more degrees of freedom than drivers, when its structure says so: bodies that no
    constraint holds (their position columns of Φ_q are zero), and no ground (all bodies translate together
    without changing Φ). Read from Φ_q at q0; nothing when it cannot be evaluated there."""
    if not mech.bodies or mech.n > 2000:
        return []
    try:
        with np.errstate(all="ignore"):
            J = np.asarray(mech.evaluate(mech.q0, 0.0)["Phi_q"], dtype=float)
    except Exception:  # noqa: BLE001 - a hint only: the count above is the error
        return []
    if not np.all(np.isfinite(J)):
        return []
    width, dim = len(mech.COORDS), mech.POINT_DIM
    scale = max(1.0, float(np.abs(J).max()) if J.size else 1.0)
    hints = []
    loose = [b.name for b in mech.bodies
             if not np.any(np.abs(J[:, width * (b.number - 1): width * (b.number - 1) + dim]) > 1e-12 * scale)]
    if loose:
        hints.append(f"bod{'y' if len(loose) == 1 else 'ies'} {', '.join(repr(b) for b in loose[:8])} "
                     f"appear{'s' if len(loose) == 1 else ''} in no constraint (free to move: connect "
                     f"{'it' if len(loose) == 1 else 'them'} with a joint)")
    held = [b for b in mech.bodies if b.name not in loose]
    if held:
        for axis in range(dim):
            v = np.zeros(mech.n)
            for b in held:
                v[width * (b.number - 1) + axis] = 1.0
            if np.abs(J @ v).max(initial=0.0) > 1e-9 * scale:
                break
        else:  # every connected body can translate along every axis at once: nothing is fixed
            hints.append("no body is fixed to the ground (the whole mechanism can translate freely): add a ground "
                         "constraint for the fixed body")
    return hints


@dataclass(frozen=True)
class NewtonHistory:
    """The iterations of one Newton–Raphson solution (:func:`solve_position` with ``history=True``), one
    entry per iterate q_k — the last is the solution returned.

    Attributes
    ----------
    q : ndarray, shape (k, n)
        The iterates, from the initial guess on.
    residual : ndarray, shape (k,)
        max |Φ(q_k, t)|.
    step : ndarray, shape (k,)
        max |Δq_k| of the Newton step Φ_q Δq = −Φ from q_k (for the last iterate: the step not taken, the
        estimate of its distance to the exact solution).
    cond : ndarray, shape (k,)
        2-norm condition number of Φ_q(q_k) (nan for a sparse system of more than 2000 coordinates).
    t : float
    """

    q: np.ndarray
    residual: np.ndarray
    step: np.ndarray
    cond: np.ndarray
    t: float = 0.0

    def __len__(self):
        return len(self.residual)

    def _rows(self):
        return [(str(k), f"{r:.3e}", f"{s:.3e}", f"{c:.4g}") for k, (r, s, c) in
                enumerate(zip(self.residual, self.step, self.cond))]

    def __repr__(self):
        head = f"Newton–Raphson at t = {self.t:.6g}: {len(self)} iterates\n"
        lines = [f"{'k':>3} {'max |Φ|':>10} {'max |Δq|':>10} {'cond(Φ_q)':>10}"]
        lines += [f"{k:>3} {r:>10} {s:>10} {c:>10}" for k, r, s, c in self._rows()]
        return head + "\n".join(lines)

    def _repr_html_(self):
        head = "".join(f"<th>{h}</th>" for h in ("k", "max |Φ|", "max |Δq|", "cond(Φ_q)"))
        body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>" for row in self._rows())
        return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def check_tol(tol, max_iter):
    try:
        tol_ok = isinstance(tol, (int, float, np.floating, np.integer)) and not isinstance(tol, bool) \
            and np.isfinite(tol) and tol > 0
    except TypeError:
        tol_ok = False
    if not tol_ok:
        raise InputError(f"`tol` must be a positive finite number (max |Φ| at convergence), got {tol!r}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)) or not 1 <= max_iter <= 10_000:
        raise InputError(f"`max_iter` must be a whole number from 1 to 10000, got {max_iter!r}")
    return float(tol), int(max_iter)


def solve_position(mech, t=0.0, q0=None, tol=1e-10, max_iter=50, history=False):
    """Solve Φ(q, t) = 0 by Newton–Raphson.

    Parameters
    ----------
    t : float
    q0 : array_like, shape (n,), optional
        Initial guess; default: the bodies' q0.
    tol : float
        Positive and finite. Convergence when max |Φ_k| ≤ tol and the Newton step from the iterate is at most
        :data:`STEP_TOL` (positions in units of the mechanism's length scale).
    max_iter : int
        From 1 to 10000.
    history : bool
        Also return the iterations, a :class:`NewtonHistory` (q, max |Φ|, step, cond(Φ_q) per iterate), for a
        notebook to show how Newton–Raphson converges (quadratically, or slowly near a singular configuration).

    Returns
    -------
    q : ndarray, shape (n,)
    history : NewtonHistory
        Only with ``history=True``: the function returns ``(q, history)``.

    Raises
    ------
    DriverCountError
        Φ is not square.
    ConvergenceError
        No convergence within ``max_iter`` iterations; the message gives the residual and the worst rows (its
        ``history`` attribute holds the iterations when ``history=True``).
    RedundantConstraintsError, DeadPointError
        Φ_q is singular at an iterate, or nearly singular at the solution (scaled σ_min/σ_max below
        :data:`RCOND_MIN`), or Newton–Raphson only creeps towards a solution where Φ_q is nearly singular.
    """
    check_drivers(mech)
    t = scalar_time(t)
    tol, max_iter = check_tol(tol, max_iter)
    if not isinstance(history, (bool, np.bool_)):  # a truthy text such as "no" would switch it on
        raise InputError(f"`history` must be True or False, got {history!r}"[:200])
    q = mech.q0 if q0 is None else np.array(mech.check_q(q0, "q0"), dtype=float)
    if q.ndim != 1:
        raise InputError(f"`q0` must have shape ({mech.n},), got {q.shape}")
    cols = column_scale(mech)
    context = f"Newton–Raphson for mechanism '{mech.name}'"
    record = [] if history else None
    res, it = np.inf, 0
    for it in range(max_iter + 1):
        ev = evaluate_jacobian(mech, q, t)
        Phi, J = ev["Phi"], ev["Phi_q"]
        res = float(np.max(np.abs(Phi))) if Phi.size else 0.0
        if not np.isfinite(res) or res > 1e12:
            break
        dq = solve_linear(J, -Phi)
        if dq is None:
            raise_singular(mech, q, t, f"{context}, iteration {it + 1}")
        step = float(np.max(np.abs(dq / cols))) if dq.size else 0.0
        if record is not None:
            record.append((q.copy(), res, float(np.max(np.abs(dq))) if dq.size else 0.0, condition_number(J)))
        if res <= tol and step <= STEP_TOL:
            if scaled_rcond(mech, J, cols) < RCOND_MIN:
                raise_singular(mech, q, t, f"{context}: the solution at t = {t:.6g}")
            return (q, _history(record, t)) if history else q
        if it == max_iter:
            break
        q = q + dq
    if np.all(np.isfinite(q)) and np.isfinite(res) and res <= 1e12 and scaled_rcond(mech, J, cols) < 1e2 * RCOND_MIN:
        raise_singular(mech, q, t, f"{context} creeps towards a solution after {it} iterations "
                                    f"(max |Φ| = {res:.3g}) where Φ_q is nearly singular")
    worst = np.argsort(-np.abs(Phi))[:3] if np.all(np.isfinite(Phi)) else np.nonzero(~np.isfinite(Phi))[0][:3]
    detail = "; ".join(f"row {r + 1} = {Phi[r]:.3g} ({row_owner(mech, r).describe()})" for r in worst)
    err = ConvergenceError(
        f"Newton–Raphson did not converge for mechanism '{mech.name}' at t = {t:.6g}: after {it} iterations "
        f"max |Φ| = {res:.3g} (tol = {tol:g}). Largest residuals: {detail}. "
        + _assembly_gap(mech, mech.q0 if q0 is None else np.array(q0, dtype=float), t, tol),
        iterations=it, residual=res, q=q,
    )
    err.history = _history(record, t) if history else None
    raise err


def _assembly_gap(mech, q0, t, tol):
    """Why Newton–Raphson failed, in words: a bounded least-squares search (min |Φ|²) from ``q0`` either reaches
    Φ = 0 (q0 was too far from a solution) or stops at a residual that no configuration nearby removes — the
    mechanism cannot be assembled, and the constraints left unsatisfied are named (a loop whose links cannot
    close). Nothing is returned as a solution: only the message changes."""
    vague = "The mechanism may not assemble there, or q0 is too far from a solution."
    if mech.n > 500 or not np.all(np.isfinite(q0)):
        return vague
    from scipy.optimize import least_squares  # import time: scipy only when needed

    def phi(x):
        return mech.evaluate(x, t, jacobian=False)["Phi"]

    def jac(x):
        return np.asarray(mech.evaluate(x, t)["Phi_q"])

    try:
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fit = least_squares(phi, q0, jac=jac, method="trf", max_nfev=50 * (1 + min(mech.n, 40)))
        Phi = phi(fit.x)
    except Exception:  # noqa: BLE001 - words for a message only
        return vague
    if not np.all(np.isfinite(Phi)):
        return vague
    res = float(np.max(np.abs(Phi))) if Phi.size else 0.0
    if res <= max(1e3 * tol, 1e-8):
        return (f"A solution exists nearby (a least-squares search from q0 reaches max |Φ| = {res:.1e}): q0 is "
                "too far from it for Newton–Raphson; start from a closer q0.")
    owners = []
    for r in np.argsort(-np.abs(Phi)):
        if abs(Phi[r]) < 0.1 * res:
            break
        c = row_owner(mech, r)
        if c.describe() not in owners:
            owners.append(c.describe())
    return (f"The mechanism cannot be assembled at t = {t:.6g}: the closest configuration a least-squares search "
            f"from q0 finds still leaves max |Φ| = {res:.3g}, in {', '.join(owners[:4])} — these constraints "
            "cannot all hold (a loop whose links are too short or too long to close, a point or length mistyped, "
            "or a driver value the mechanism cannot reach).")


def _history(record, t):
    q, res, step, cond = zip(*record) if record else ((), (), (), ())
    return NewtonHistory(np.array(q), np.array(res), np.array(step), np.array(cond), t)


def solve_velocity(mech, q, t=0.0):
    """Solve the velocity equations Φ_q q̇ = ν (§13.7). Returns q̇, shape (n,)."""
    check_drivers(mech)
    t = scalar_time(t)
    q = mech.check_configuration(q, what="the velocity analysis")
    ev = evaluate_jacobian(mech, q, t)
    qd = solve_linear(ev["Phi_q"], ev["nu"])
    if qd is None or scaled_rcond(mech, ev["Phi_q"]) < RCOND_MIN:
        raise_singular(mech, q, t, f"velocity analysis of mechanism '{mech.name}'")
    return qd


def solve_acceleration(mech, q, qd, t=0.0):
    """Solve the acceleration equations Φ_q q̈ = γ (§13.8). Returns q̈, shape (n,)."""
    check_drivers(mech)
    t = scalar_time(t)
    q = mech.check_configuration(q, what="the acceleration analysis")
    if qd is None:
        raise InputError(f"`qd` is required: the acceleration analysis of mechanism '{mech.name}' needs the "
                         f"velocities q̇ (solve_velocity gives them)")
    qd = mech.check_configuration(qd, "qd", what="the acceleration analysis")
    ev = mech.evaluate(q, t, qd, sparse=mech.n > SPARSE_ABOVE)
    qdd = solve_linear(ev["Phi_q"], ev["gamma"])
    if qdd is None or scaled_rcond(mech, ev["Phi_q"]) < RCOND_MIN:
        raise_singular(mech, q, t, f"acceleration analysis of mechanism '{mech.name}'")
    return qdd
