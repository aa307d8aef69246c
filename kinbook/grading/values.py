"""Checkers for numeric answers: numbers, vectors and matrices (:func:`check_value`), rotation matrices
(:func:`check_rotation`) and Euler parameters (:func:`check_euler_parameters`).

The expected value is computed by the caller with kinbook (``kinbook.planar`` or ``kinbook.spatial``); these
checkers compare and diagnose: wrong shape, transposed, sign, a constant factor, degrees for radians, a
non-orthogonal A, p vs −p (both valid), p not normalized.
"""

from __future__ import annotations

import numpy as np

from ._i18n import tr
from .catalogue import explain
from .result import CheckResult, RowResult, failed

__all__ = ["check_value", "check_rotation", "check_euler_parameters"]


def _hint(code):
    title, hint = explain(code)
    return tr("hint", title=title, hint=hint)


def _array(x):
    """Float array from numbers / nested lists / sympy matrices; None if impossible or empty."""
    try:
        if hasattr(x, "evalf") and hasattr(x, "shape"):
            x = x.evalf()
        a = np.array(x, dtype=float)
    except (TypeError, ValueError):
        return None
    return a


def _close(a, b, rtol, atol):
    return bool(np.all(np.abs(a - b) <= atol + rtol * np.max(np.abs(b), initial=0.0)))


def _fmt(a):
    return np.array2string(np.asarray(a), precision=5, suppress_small=True, separator=", ",
                           max_line_width=10_000).replace("\n", "")


def check_value(answer, expected, *, rtol=1e-3, atol=1e-9, name="value", angles=False, periodic=()):
    """Check a number, vector or matrix against the expected value.

    Parameters
    ----------
    answer : number, array_like, sympy Matrix
    expected : number or array_like
        Computed by the caller with kinbook.
    rtol, atol : float
        Tolerances: |answer − expected| ≤ atol + rtol · max|expected| entry-wise (the book prints 4–6
        significant digits, hence the default rtol = 1e-3).
    name : str
        How to call the value in messages ("q̈", "Φ_q at t = 0" …).
    angles : bool
        The value holds angles or angular velocities: degrees instead of radians is diagnosed.
    periodic : sequence of int
        Flat indices of entries that are angles: they are compared modulo 2π (φ = −π/2 and 3π/2 are the
        same orientation).

    Returns
    -------
    CheckResult
        One row per entry (flattened) when the shapes agree.

    Examples
    --------
    >>> check_value([1.0, 2.0], [1.0, 2.0001]).passed
    True
    >>> check_value([[1, 3], [2, 4]], [[1, 2], [3, 4]]).mistakes
    ['transposed']
    """
    exp = _array(expected)
    if exp is None:
        return failed(name, f"`expected` must be numbers, got {expected!r}", "malformed")
    a = _array(answer)
    if a is None:
        return failed(name, tr("bad_type", expected=f"numbers of shape {exp.shape}", type=type(answer).__name__),
                      "malformed")
    if a.shape != exp.shape:
        if a.size == exp.size and (a.squeeze().shape == exp.squeeze().shape):
            a = a.reshape(exp.shape)
        elif a.ndim == 2 and a.T.shape == exp.shape:
            ok = _close(a.T, exp, rtol, atol)
            msg = tr("transposed", expected=exp.shape, got=a.shape) + ("; " + tr("transposed_right") if ok else "")
            return CheckResult(False, 0.5 if ok else 0.0, [msg, _hint("transposed")], ["transposed"], (), name)
        else:
            return failed(name, tr("wrong_shape", expected=exp.shape, got=a.shape), "wrong_shape")
    if not np.all(np.isfinite(a)):
        return failed(name, tr("not_finite", where=name), "not_finite")
    if len(periodic):
        flat, ref = a.ravel().copy(), exp.ravel()
        idx = np.asarray(periodic, dtype=int)
        flat[idx] = ref[idx] + (flat[idx] - ref[idx] + np.pi) % (2 * np.pi) - np.pi
        a = flat.reshape(a.shape)
    if _close(a, exp, rtol, atol):
        return CheckResult(True, 1.0, [tr("value_ok")], [], (), name)
    mistakes, messages = [], []
    if a.ndim == 2 and a.shape[0] == a.shape[1] and _close(a.T, exp, rtol, atol):
        mistakes.append("transposed")
        messages.append(tr("transposed_right"))
    elif angles and _close(a, np.degrees(exp), rtol, atol):
        mistakes.append("degrees")
    elif np.max(np.abs(exp)) > atol and _close(a, -exp, rtol, atol):
        mistakes.append("sign_flip")
    else:
        flat_a, flat_e = a.ravel(), exp.ravel()
        ee = float(flat_e @ flat_e)
        c = float(flat_a @ flat_e) / ee if ee > 0 else 0.0
        if c != 0 and _close(a, c * exp, rtol, atol):
            mistakes.append("scaled")
            messages.append(tr("value_scaled", c=c))
    err = np.abs(a - exp)
    where = np.unravel_index(int(np.argmax(err)), err.shape) if err.ndim else ()
    messages.insert(0, tr("value_wrong", expected=_fmt(exp), got=_fmt(a), err=float(err.max()),
                          where=str(tuple(int(i) for i in where)) if where else name))
    rows = []
    if a.ndim <= 1 and a.size <= 64:
        scale = np.max(np.abs(exp), initial=0.0)
        for i, (x, y) in enumerate(zip(np.atleast_1d(a), np.atleast_1d(exp))):
            good = abs(x - y) <= atol + rtol * scale
            code = None if good else (mistakes or ["wrong_value"])[0]
            rows.append(RowResult(f"{name}[{i + 1}]", "ok" if good else "wrong",
                                  "" if good else f"{x:.6g} ≠ {y:.6g}", code, score=1.0 if good else 0.0))
    good = 1.0 - float(np.mean(err > atol + rtol * np.max(np.abs(exp), initial=0.0)))
    score = 0.0 if mistakes else good
    mistakes = mistakes or ["wrong_value"]
    return CheckResult(False, round(score, 6), messages + [_hint(c) for c in mistakes], mistakes, tuple(rows), name)


def _zxz(psi, theta, phi):
    """A = Rz(ψ) Rx(θ) Rz(φ), the book's z-x-z Euler angles (kinbook.spatial.rotations.A_from_euler)."""
    try:
        from ..spatial.rotations import A_from_euler

        return np.asarray(A_from_euler(psi, theta, phi), dtype=float)
    except Exception:  # kinbook.spatial missing or changed: the same product, written out
        def rz(a):
            c, s = np.cos(a), np.sin(a)
            return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])

        def rx(a):
            c, s = np.cos(a), np.sin(a)
            return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])

        return rz(psi) @ rx(theta) @ rz(phi)


def check_rotation(answer, expected, *, rtol=1e-4, atol=1e-6, angles=None, name="A"):
    """Check a 3×3 rotation (direction-cosine) matrix.

    Parameters
    ----------
    answer : array_like, shape (3, 3)
    expected : array_like, shape (3, 3)
        Computed with kinbook.spatial (it maps local to global components: s = A s').
    angles : (ψ, θ, φ), optional
        The z-x-z Euler angles (radians) the exercise gave; with them, an A computed from the angles in
        degrees is diagnosed as ``degrees``.

    Returns
    -------
    CheckResult
        Mistakes: ``wrong_shape``, ``not_orthogonal``, ``transposed`` (Aᵀ for A: the inverse rotation),
        ``degrees``, ``wrong_value``.
    """
    a, exp = _array(answer), _array(expected)
    if exp is None or exp.shape != (3, 3):
        return failed(name, f"`expected` must be a 3×3 matrix, got {expected!r}", "malformed")
    if a is None:
        return failed(name, tr("bad_type", expected="a 3×3 matrix", type=type(answer).__name__), "malformed")
    if a.shape != (3, 3):
        return failed(name, tr("wrong_shape", expected="(3, 3)", got=a.shape), "wrong_shape")
    if not np.all(np.isfinite(a)):
        return failed(name, tr("not_finite", where=name), "not_finite")
    if _close(a, exp, rtol, atol):
        return CheckResult(True, 1.0, [tr("value_ok")], [], (), name)
    mistakes, messages = [], []
    orth = float(np.max(np.abs(a.T @ a - np.eye(3))))
    det = float(np.linalg.det(a))
    if _close(a.T, exp, rtol, atol):
        mistakes.append("transposed")
        messages.append(tr("transposed_right"))
    elif angles is not None and _close(a, _zxz(*np.degrees(np.asarray(angles, float))), rtol, atol):
        mistakes.append("degrees")
    if orth > 1e3 * rtol or abs(det - 1.0) > 1e3 * rtol:
        mistakes.append("not_orthogonal")
        messages.append(tr("orthogonal_fail", err=orth) if orth > 1e3 * rtol else tr("det_fail", det=det))
    if not mistakes:
        mistakes.append("wrong_value")
    err = np.abs(a - exp)
    messages.insert(0, tr("value_wrong", expected=_fmt(exp), got=_fmt(a), err=float(err.max()),
                          where=str(tuple(int(i) for i in np.unravel_index(int(np.argmax(err)), err.shape)))))
    return CheckResult(False, 0.0, messages + [_hint(c) for c in mistakes], mistakes, (), name)


def check_euler_parameters(answer, expected, *, rtol=1e-4, atol=1e-6, axis=None, angle=None, name="p"):
    """Check Euler parameters p = [e0, e1, e2, e3].

    Parameters
    ----------
    answer, expected : array_like, shape (4,)
        ``expected`` computed with kinbook.spatial. p and −p describe the same orientation: both pass.
    axis, angle : optional
        The rotation the exercise gave (unit axis u, angle χ in radians); with them, p computed from χ in
        degrees is diagnosed as ``degrees``.

    Returns
    -------
    CheckResult
        Mistakes: ``wrong_shape``, ``not_normalized`` (right direction, pᵀp ≠ 1), ``degrees``,
        ``wrong_value``.
    """
    a, exp = _array(answer), _array(expected)
    if exp is None or exp.shape not in ((4,), (4, 1)):
        return failed(name, f"`expected` must have 4 entries, got {expected!r}", "malformed")
    exp = exp.reshape(4)
    if a is None:
        return failed(name, tr("bad_type", expected="4 numbers [e0, e1, e2, e3]", type=type(answer).__name__),
                      "malformed")
    if a.size != 4:
        return failed(name, tr("wrong_shape", expected="(4,)", got=a.shape), "wrong_shape")
    a = a.reshape(4)
    if not np.all(np.isfinite(a)):
        return failed(name, tr("not_finite", where=name), "not_finite")
    if _close(a, exp, rtol, atol):
        return CheckResult(True, 1.0, [tr("value_ok")], [], (), name)
    if _close(a, -exp, rtol, atol):
        return CheckResult(True, 1.0, [tr("p_negated")], [], (), name)
    norm = float(a @ a)
    mistakes, messages = [], []
    if norm > 0 and abs(norm - 1.0) > 1e3 * rtol:
        u = a / np.sqrt(norm)
        if _close(u, exp, rtol, atol) or _close(u, -exp, rtol, atol):
            mistakes.append("not_normalized")
        messages.append(tr("norm_fail", norm=norm))
    if not mistakes and axis is not None and angle is not None:
        chi = np.degrees(float(angle))
        u = np.asarray(axis, float) / np.linalg.norm(axis)
        p_deg = np.concatenate([[np.cos(chi / 2)], u * np.sin(chi / 2)])
        if _close(a, p_deg, rtol, atol) or _close(a, -p_deg, rtol, atol):
            mistakes.append("degrees")
    if not mistakes and "norm_fail" not in messages:
        mistakes.append("wrong_value")
    if not mistakes:
        mistakes.append("wrong_value")
    messages.insert(0, tr("value_wrong", expected=_fmt(exp), got=_fmt(a), err=float(np.max(np.abs(a - exp))),
                          where=name))
    return CheckResult(False, 0.0, messages + [_hint(c) for c in mistakes], mistakes, (), name)
