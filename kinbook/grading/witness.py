"""Rows checked again where no one could have looked (after the diagnosis): configurations drawn from the
answer's own digest.

The samples of :mod:`~kinbook.grading.sample` are seeded with a constant — a verdict must not depend on the
run — and the seed is in the source, so a student who reads it can write a row that equals the reference at
exactly those configurations and nowhere else (Φ_4 + 10⁻⁶·∏(y1 − y1ₖ) over the sampled y1ₖ; γ + c·∏(t − tₖ)).
Every row accepted as the reference's row (a constant multiple of it) is compared once more at a few
configurations whose seed is a digest of the answer itself: the same answer meets the same configurations on
every run and every machine, and no answer can be written to agree at configurations chosen from its own text.
A row that fails there is right only at the samples (``only_at_samples``): wrong, and its row and joint named.

Answers given as a function ``f(q, t)`` are witnessed the same way, from a digest of the function's own code
(its bytecode, names, constants and closure: :func:`code_text`) — deterministic, and a function cannot be written
to agree at configurations drawn from its own code. Half of the witness's configurations are over the whole
domain (angles beyond ±π, t from 1 to 30): a driver padded with 10⁻⁴·∏(t − tₖ) over the sampled instants, or
``atan2(sin φ2, cos φ2)`` for φ2, is caught there.
"""

from __future__ import annotations

import hashlib
import types

import numpy as np

from . import mistakes as M
from . import sample
from ._i18n import Msg
from .diagnose import where
from .equivalence import scale_match, turned_multiple, wrapped, zero_tol
from .quantities import quantity_of
from .read import Refused

__all__ = ["phi", "derived", "samples", "code_text", "N_WITNESS"]

N_WITNESS = 4
"""Configurations drawn from the answer's digest."""


def _seed(answer, target):
    """A 64-bit seed from the answer's evaluation tape (its distinct operations, in order): the answer's text; for
    a function, its own code (:func:`code_text`)."""
    if answer.kind == "function":
        text = code_text(answer.function).encode()
    else:
        tape = answer.tape(target)
        text = repr((answer.shape, tape.ops)).encode()
    return int.from_bytes(hashlib.sha256(text).digest()[:8], "little")


def code_text(f, depth=0):
    """A function's own code as text, the same on every run: its bytecode, names and constants (nested functions
    and the values its closure holds included, to a bounded depth) — what the student wrote, not where it was
    loaded. A callable without code (a builtin, an object) gives its type's name."""
    f = getattr(f, "__func__", f)
    code = getattr(f, "__code__", None)
    if code is None:
        call = type(f).__dict__.get("__call__")
        code = getattr(call, "__code__", None)
        if code is None:
            return type(f).__qualname__
    parts = [_code_part(code, depth)]
    for cell in getattr(f, "__closure__", None) or ():
        try:
            value = cell.cell_contents
        except ValueError:
            continue
        parts.append(code_text(value, depth + 1) if callable(value) and depth < 3 else _plain(value))
    defaults = getattr(f, "__defaults__", None)
    if defaults:
        parts.append(repr(tuple(_plain(d) for d in defaults)))
    return "|".join(parts)


def _code_part(code, depth):
    consts = tuple(_code_part(c, depth + 1) if isinstance(c, types.CodeType) and depth < 8 else _plain(c)
                   for c in code.co_consts)
    return repr((code.co_code.hex(), code.co_names, code.co_varnames, consts))


def _plain(value):
    """A value as text without addresses (repr of an object can hold its id)."""
    if isinstance(value, (int, float, complex, str, bytes, bool, type(None))):
        return repr(value)
    if isinstance(value, (tuple, list)):
        return repr(tuple(_plain(v) for v in value[:64]))
    if isinstance(value, np.ndarray) and value.size <= 4096:
        return repr((value.dtype.str, value.shape, value.tobytes().hex()))
    return type(value).__qualname__


def _generic(target, seed):
    """Configurations drawn from the seed: half where :func:`~kinbook.grading.sample.spread` draws, half over the
    whole domain (angles beyond ±π, t up to 30: :func:`~kinbook.grading.sample.wide`)."""
    rng = np.random.default_rng(seed)
    half = N_WITNESS // 2
    Q = sample.spread(target, rng, N_WITNESS - half)
    near = sample.Samples(Q, rng.normal(0.0, 2.0, Q.shape), rng.uniform(0.0, 1.0, len(Q)))
    far = sample.wide(target, rng, half)
    return sample.Samples(np.vstack([near.Q, far.Q]), np.vstack([near.QD, far.QD]), np.concatenate([near.T, far.T]))


def _assembled(target, seed):
    """A few configurations where the target's rows hold, near its assembled samples (None when too few): near
    those at t < 1, and — the rows depending on time — near those over the whole domain (t from 1 to 30,
    :func:`~kinbook.grading.sample.wide_assembled`), moved in t too."""
    base = target.samples("assembled")
    if not base.on_manifold:
        return None
    rng = np.random.default_rng(seed)
    near = np.flatnonzero(base.T < 1.0)
    far = np.flatnonzero(base.T >= 1.0)
    near = near if len(near) else np.arange(base.N)
    idx = near[rng.integers(0, len(near), 2 * N_WITNESS)]
    starts = sample.perturbed(target, rng, base.Q[idx], 0.05)
    T = rng.uniform(0.0, 2.0, len(idx))  # the projection moves t too where the rows depend on it (a driver)
    Q, T, ok = sample.project(target, starts, T, steps=10)
    Q, T = sample.regular(target, Q[ok], T[ok])
    if len(Q) < 2:
        return None
    Q, T = Q[:N_WITNESS], T[:N_WITNESS]
    if target.time_dependent and len(far):
        idx = far[rng.integers(0, len(far), N_WITNESS)]
        starts = sample.perturbed(target, rng, base.Q[idx], 0.05)
        WT = np.maximum(base.T[idx] + rng.uniform(-0.5, 0.5, len(idx)), 1.0)
        WQ, WT, ok = sample.project(target, starts, WT, steps=10)
        WQ, WT = sample.regular(target, WQ[ok], WT[ok])
        Q, T = np.vstack([Q, WQ[: N_WITNESS // 2]]), np.concatenate([T, WT[: N_WITNESS // 2]])
    return sample.Samples(Q, sample.velocities(target, Q, T, rng), T, on_manifold=True)


def _where(target, s, i, names):
    text = where(target, s.Q[i], names)
    if target.time_dependent or names == []:
        text = f"{text}, t = {s.T[i]:.6g}" if text else f"t = {s.T[i]:.6g}"
    return text


def _names_of(target, k):
    c = target.owner(k)
    ncoord = len(target.mech.COORDS)
    return [target.names[ncoord * (b.number - 1) + i] for b in c.bodies for i in range(ncoord)]


def _reject(target, r, s, i, quantity):
    r.status, r.code, r.score, r.how = "wrong", "only_at_samples", 0.0, "multiple"
    r.detail = Msg("d.only_at_samples", ref=target.label(r.ref), where=_where(target, s, i, _names_of(target, r.ref)))
    r.context = M.contexts_of(target.owner(r.ref), quantity)


def phi(target, answer, matching, rtol):
    """Φ rows accepted as a multiple of a reference row, compared again at configurations drawn from the answer's
    digest (generic ones, as the match compared them, half of them over the whole domain). A row that was a
    multiple at the generic samples but not at the seeded ones over the whole domain (``matching.wide``) and is
    named nothing more precise is ``only_at_samples`` too, at the configuration where it differs most."""
    _wide_only(target, matching, rtol)
    rows = [r for r in matching.rows if r.status == "ok" and r.how == "multiple" and r.ref is not None
            and r.factor is not None]
    if answer.kind == "numbers" or not rows:
        return
    s = _generic(target, _seed(answer, target))
    S = _values(answer, target, s)
    if S is None:
        return
    S = S[:, :, 0]
    R = target.evaluate(s)["Phi"]
    R_G = target.reference("generic")["Phi"]
    for r in rows:
        a, b = S[:, r.k], r.factor * R[:, r.ref]
        if not np.all(np.isfinite(a)):
            continue  # the row is not defined there (a square root of a negative): its match stands
        # rounding is zero: a row zero at every sample (pᵀp − 1 on unit p) is ~1e-16 here, its answer too
        atol = rtol * max(abs(r.factor) * float(np.abs(R_G[:, r.ref]).max()), 1e-9)
        if scale_match(a, b, rtol, free=False, period=target.wrap.get(r.ref), atol=atol, zeros=True) is None and not (
                r.ref in target.turns and _same_placement(target, answer, s, r, a, b, rtol)):
            i = int(np.argmax(np.abs(a - b)))
            _reject(target, r, s, i, "Phi")


def _same_placement(target, answer, s, r, a, b, rtol):
    """A row that measures an angle, accepted as c·Φ_k, that is not c·Φ_k at the witness's configurations ``s``:
    still the same placement when it is c·(Φ_k + one whole number of turns) there, or — its turns changing from
    configuration to configuration (atan2(sin φ1, cos φ1) for φ1) — when it vanishes, at every configuration, at
    a turn (−2 … 2) of the configuration moved along one of the row's angles to where Φ_k is zero.
    atan2(sin φ2, cos φ2) − 3π/4 − 100t does not once 100t > π/4."""
    period = target.turns[r.ref] * abs(r.factor)
    if turned_multiple(a, b, rtol, period, free=False)[1][0]:
        return True
    scale = max(float(np.abs(a).max()), float(np.abs(b).max()), 1.0)
    if not np.all(np.abs(wrapped(a - b, period)) <= rtol * scale):
        return False
    ref = target.evaluate(s)
    J = ref["Phi_q"][:, r.ref, :]
    col = int(np.argmax(np.abs(J[0])))  # an angle of the row (its coefficient ±1)
    if not np.allclose(np.abs(J[:, col]), 1.0):
        return False
    Q = s.Q.copy()
    Q[:, col] -= ref["Phi"][:, r.ref] / J[:, col]
    turns = (0, 1, -1, 2, -2)
    QT = np.repeat(Q, len(turns), axis=0)
    QT[:, col] += np.tile(np.array(turns, float) * target.turns[r.ref], len(Q))
    V = _values(answer, target, sample.Samples(QT, np.zeros_like(QT), np.repeat(s.T, len(turns))))
    if V is None:
        return True  # not defined there: its match stands
    least = np.abs(V[:, r.k, 0]).reshape(len(Q), len(turns)).min(axis=1)
    return bool(np.all(least <= zero_tol(rtol) * scale))


def _wide_only(target, matching, rtol):
    if not matching.wide:
        return
    s = target.samples("wide")
    for r in matching.rows:
        if r.k not in matching.wide or r.status != "wrong" or r.code not in (None, "wrong_value"):
            continue
        j, c, i = matching.wide[r.k]
        if r.ref is not None and r.ref != j:
            continue
        r.ref, r.factor = j, c
        _reject(target, r, s, i, "Phi")


def _values(answer, target, s):
    """The answer at the witness's configurations, or None where it cannot be read there (a function that raises
    or changes its shape at an angle beyond ±π): its match stands, as a row not defined there."""
    try:
        return answer.values(target, s)
    except Refused:
        return None


def samples(target, answer):
    """Where a Φ_q, ν or γ answer is compared again: assembled configurations drawn from its digest (velocities
    consistent, as at the samples), or None (a function, numbers, a target with no assembled samples)."""
    if answer.kind == "numbers":
        return None
    return _assembled(target, _seed(answer, target))


def derived(target, quantity, answer, data, matching, rtol, s):
    """Φ_q, ν or γ rows accepted as the reference's, compared again at the configurations ``s`` of
    :func:`samples`."""
    rows = [r for r in matching.rows if r.status == "ok" and r.how in ("multiple", "reference") and r.ref is not None
            and not isinstance(r.ref, tuple)]
    if s is None or not rows:
        return
    V = _values(answer, target, s)
    if V is None:
        return
    ref = target.evaluate(s)
    per_coordinate = quantity_of(quantity).per_coordinate
    if per_coordinate:
        if data.transposed:
            V = np.swapaxes(V, 1, 2)
        S, R = V, ref[quantity][:, :, data.cols]
    else:
        S = V[:, :, 0] if V.shape[2] == 1 else V[:, 0, :]
        R = ref[quantity]
    scale = max(float(np.abs(data.R).max()), 1e-9)
    for r in rows:
        c = 1.0 if r.factor is None else r.factor
        a, b = S[:, r.k], c * R[:, r.ref]
        if not np.all(np.isfinite(a)):
            continue
        if np.max(np.abs(a - b)) > rtol * max(float(np.abs(a).max()), float(np.abs(b).max())) + rtol * scale:
            i = int(np.argmax(np.abs(a - b).reshape(len(a), -1).max(axis=1)))
            _reject(target, r, s, i, quantity)
            if per_coordinate:
                r.entries = tuple("ok" if np.allclose(a[:, j], b[:, j], rtol=rtol, atol=rtol * scale) else
                                  "only_at_samples" for j in range(a.shape[1]))
