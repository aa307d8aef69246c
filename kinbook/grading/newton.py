"""Checker of a Newton–Raphson iteration written by a student (notebook 13-3's "your own Newton–Raphson").

The answer is the list of iterates the student's loop produced, the starting guess first. Every step is
checked, not only the result: iterate k + 1 must be q_k + Δq with Φ_q(q_k, t) Δq = −Φ(q_k, t) — kinbook
computes that step from the student's own q_k, so one slip is named where it happens and not carried into
every later step — and the last iterate must be converged and be the solution the guess leads to. A printed
solution pasted as the answer has no iteration to check.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, KinbookError
from ..i18n import N_, Np_
from ._i18n import Msg, add_texts
from .numbers import failed, read_numbers, real_option
from .report import CheckResult, RowResult, fmt, hints

__all__ = ["Problem", "check_iterates"]

add_texts({
    "n.name": N_("Newton–Raphson iterates"),
    "n.iterate": N_("q_{k}"),
    "n.need_list": N_("give every iterate of your loop, the starting guess first (a list of {n}-vectors, e.g. "
                      "`iterates.append(q.copy())` inside the loop): this try-it checks the iteration, not only its "
                      "result"),
    "n.width": N_("each iterate has {n} coordinates; yours have {got}"),
    "n.start": N_("q_0 is not the guess the question gives: start from it"),
    "n.ok": N_("correct: {k} Newton–Raphson steps, converged to the solution"),
    "n.step_ok": N_("a Newton–Raphson step"),
    "n.step_bad": N_("not q_{j} + Δq with Φ_q(q_{j}) Δq = −Φ(q_{j})"),
    "n.step_sign": N_("q_{j} − Δq: the sign of the step"),
    "n.step_chord": N_("Φ_q of the guess kept for every step (evaluate it at q_{j})"),
    "n.step_time": N_("Φ and Φ_q evaluated at t = {t0}, not at the question's t"),
    "n.step_degrees": N_("the angles of q_{k} in degrees"),
    "n.steps_off": Np_("wrong: {n} of your {total} steps is not a Newton–Raphson step",
                       "wrong: {n} of your {total} steps are not Newton–Raphson steps"),
    "n.first_bad": N_("step {k} (q_{j} → q_{k}): {why}"),
    "n.not_converged": N_("after {k} steps max |Φ(q_{k})| = {res}: not converged yet"),
    "n.other_mode": N_("your loop converged, but to the other assembly mode, not the one the guess leads to"),
    "n.too_many": N_("at most {limit} iterates are read; yours are {got}"),
})

MAX_ITERATES = 200


@dataclass(frozen=True)
class Problem:
    """What the iteration solves: Φ(q, t) = 0 of ``mechanism`` at ``t``, from ``guess``."""

    mechanism: object
    t: float
    guess: np.ndarray

    def solution(self):
        return self.mechanism.solve_position(self.t, q0=self.guess)


def _step(mech, q, t):
    return np.linalg.solve(mech.Phi_q(q, t), -mech.Phi(q, t))


def check_iterates(answer, problem, *, tol=1e-8, rtol=1e-6, reveal=False, name=None):
    """Check a list of Newton–Raphson iterates, the guess first.

    Parameters
    ----------
    answer : sequence of array_like, shape (k + 1, n)
        q_0 (the guess), q_1, …, q_k.
    problem : Problem
        The mechanism, the time and the guess.
    tol : float
        The last iterate must have max |Φ| ≤ tol.
    rtol : float
        A step is right when |q_{j+1} − (q_j + Δq)| ≤ rtol · max(1, |Δq|) entry-wise.
    reveal : bool
        Kept for the numeric checkers' interface: the feedback never shows the solution.

    Returns
    -------
    CheckResult
        One row per step; mistakes ``newton_step``, ``degrees``, ``not_converged``, ``assembly_mode``,
        ``wrong_data`` (the guess is not the given one), ``wrong_shape``.
    """
    if not isinstance(problem, Problem):
        raise InputError(f"`problem` must be a kinbook.grading.newton.Problem, got {type(problem).__name__}")
    tol, rtol = real_option(tol, "tol", positive=True), real_option(rtol, "rtol", low=0.0, high=0.1)
    name = Msg("n.name") if name is None else name
    mech, t, guess = problem.mechanism, float(problem.t), np.asarray(problem.guess, float)
    n = guess.size
    if isinstance(answer, (list, tuple)) and len(answer) > MAX_ITERATES:
        return failed(name, Msg("n.too_many", limit=MAX_ITERATES, got=len(answer)), "malformed")
    a, refused = read_numbers(answer, name)
    if refused is not None:
        return failed(name, Msg(refused.key, **refused.fields), refused.code)
    if a.ndim < 2 or a.shape[0] < 2:
        return failed(name, Msg("n.need_list", n=n), "wrong_shape")
    if a.shape[1] != n:
        return failed(name, Msg("n.width", n=n, got=a.shape[1]), "wrong_shape")
    if not np.all(np.isfinite(a)):
        return failed(name, Msg("not_finite", where=name), "not_finite")
    notes, codes = [], []
    angles = [k for k, c in enumerate(mech.coordinate_names()) if c.startswith("phi")]
    if not np.allclose(a[0], guess, rtol=1e-9, atol=1e-9):
        return failed(name, Msg("n.start"), "wrong_data")
    rows, first_bad = _steps(mech, a, t, guess, rtol, angles)
    if first_bad is not None:
        j, code, why = first_bad
        bad = sum(1 for r in rows if r.status != "ok")
        notes.append(Msg("n.steps_off", n=bad, total=len(rows)))
        notes.append(Msg("n.first_bad", k=j + 1, j=j, why=why))
        codes.append(code)
    converged = _last_iterate(problem, a, tol, angles, first_bad is None, notes, codes)
    steps = len(rows)
    good = sum(r.score for r in rows)
    score = 0.5 * good / steps + (0.5 if converged and "assembly_mode" not in codes else 0.0)
    if not codes:
        return CheckResult(True, 1.0, [Msg("n.ok", k=steps)], [], tuple(rows), name)
    codes = list(dict.fromkeys(codes))
    return CheckResult(False, round(score, 6), notes + hints(codes, {c: ("value",) for c in codes}), codes,
                       tuple(rows), name)


def _steps(mech, a, t, guess, rtol, angles):
    """One row per step j → j + 1 of the iterates ``a``, and (j, code, why) of the first wrong one, or None."""
    rows, first_bad = [], None
    for j in range(a.shape[0] - 1):
        try:
            dq = _step(mech, a[j], t)
        except (np.linalg.LinAlgError, KinbookError):
            dq = None
        right = dq is not None and np.all(np.abs(a[j + 1] - (a[j] + dq)) <= rtol * max(1.0, np.abs(dq).max()))
        label = Msg("n.iterate", k=j + 1)
        if right:
            rows.append(RowResult(label, "ok", Msg("n.step_ok"), None, (), 1.0))
            continue
        code, why = _why(mech, a, j, t, guess, dq, rtol, angles)
        rows.append(RowResult(label, "wrong", why, code, (), 0.0))
        if first_bad is None:
            first_bad = (j, code, why)
    return rows, first_bad


def _last_iterate(problem, a, tol, angles, steps_right, notes, codes):
    """Whether the last iterate solves Φ = 0 within ``tol``; adds to ``notes``/``codes`` when it has not converged
    though every step was right, or when it converged to another assembly mode than the reference's."""
    mech, t, last = problem.mechanism, float(problem.t), a[-1]
    try:
        res = float(np.abs(mech.Phi(last, t)).max())
    except KinbookError:
        res = np.inf
    converged = res <= tol
    if not converged and steps_right:
        notes.append(Msg("n.not_converged", k=a.shape[0] - 1, res=fmt(res)))
        codes.append("not_converged")
    elif converged:
        ref = problem.solution()
        d = last - ref
        d[angles] = (d[angles] + np.pi) % (2 * np.pi) - np.pi
        if np.abs(d).max() > 1e-6 * max(1.0, np.abs(ref).max()):
            notes.append(Msg("n.other_mode"))
            codes.append("assembly_mode")
    return converged


def _why(mech, a, j, t, guess, dq, rtol, angles):
    """(code, Msg) of a wrong step j → j + 1."""
    nxt = a[j + 1]

    def near(x):
        return x is not None and np.all(np.abs(nxt - x) <= rtol * max(1.0, np.abs(x - a[j]).max()))

    deg = nxt.copy()
    deg[angles] = np.radians(deg[angles])
    if dq is not None and np.all(np.abs(deg - (a[j] + dq)) <= rtol * max(1.0, np.abs(dq).max())) and angles:
        return "degrees", Msg("n.step_degrees", k=j + 1)
    if dq is not None and near(a[j] - dq):
        return "newton_step", Msg("n.step_sign", j=j)
    try:
        chord = a[j] + np.linalg.solve(mech.Phi_q(guess, t), -mech.Phi(a[j], t))
    except (np.linalg.LinAlgError, KinbookError):
        chord = None
    if j > 0 and near(chord):
        return "newton_step", Msg("n.step_chord", j=j)
    if t != 0:
        try:
            at0 = a[j] + _step(mech, a[j], 0.0)
        except (np.linalg.LinAlgError, KinbookError):
            at0 = None
        if near(at0):
            return "wrong_data", Msg("n.step_time", t0=0)
    return "newton_step", Msg("n.step_bad", j=j)



