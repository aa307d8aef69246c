"""Checkers for numeric answers: numbers, vectors and matrices (:func:`check_value`), rotation matrices
(:func:`check_rotation`) and Euler parameters (:func:`check_euler_parameters`).

The expected value is computed by the caller with kinbook — a plain number or array, or an
:class:`~kinbook.grading.expected.Expected` (``kinbook.grading.expected.A_from_euler(ψ, θ, φ)`` …) that also
knows the other right answers (−p, the second triple of Euler angles) and the wrong answers students give,
each computed with kinbook's functions. The checkers compare and diagnose, the same way for every number:
the Expected's named mistakes first; then, for any value, degrees for radians (wherever the answer is the
expected angle in degrees: no flag needed), a transposed matrix, the sign, a plausible factor (2, ½, π …),
and for matrices and parameters their own conditions (orthogonality, det = +1, pᵀp = 1).
"""

from __future__ import annotations

import numpy as np

from ._i18n import Msg
from .expected import DEG, Expected
from .read import Refused, _as_numbers
from .report import fmt, hints
from .result import CheckResult, RowResult

__all__ = ["check_value", "check_rotation", "check_euler_parameters"]

_PLAUSIBLE = (2.0, 0.5, -2.0, -0.5, np.pi, 1 / np.pi, 2 * np.pi, 1 / (2 * np.pi), np.pi / 180, 3.0, 1 / 3)


def _fmt_array(a):
    """Numbers as they are shown: 6 significant digits, no round-off noise, nested brackets."""
    a = np.asarray(a, float)
    if a.ndim == 0 or a.size == 1:
        return fmt(a.ravel()[0])
    if a.ndim == 1:
        return "[" + ", ".join(fmt(x) for x in a) + "]"
    return "[" + ", ".join(_fmt_array(r) for r in a) + "]"


def _close(a, b, rtol, atol, periodic=None):
    d = a - b
    if periodic is not None and periodic.any():
        d = np.where(periodic, (d + np.pi) % (2 * np.pi) - np.pi, d)
    return bool(np.all(np.abs(d) <= atol + rtol * np.max(np.abs(b), initial=0.0)))


def _read(answer, name):
    """The answer as a float array of its own shape (refuses bools, complex values, text, objects)."""
    try:
        arr = _as_numbers(answer, Msg("answer"))
    except Refused as exc:
        return None, exc
    try:
        raw = np.asarray(answer, dtype=float)
    except (TypeError, ValueError):  # a sympy matrix of numbers: as read
        raw = arr
    return (raw if raw.size == arr.size and raw.ndim <= 2 else arr), None


def _failed(name, msg, code):
    return CheckResult(False, 0.0, [msg], [code], (), name)


def _expected(expected):
    if isinstance(expected, Expected):
        return expected
    try:
        value = np.asarray(expected, dtype=float)
    except (TypeError, ValueError):
        return None
    if value.dtype.kind != "f" or value.size == 0:
        return None
    return Expected(value)


def _shape(a, e, name):
    """``a`` reshaped to ``e``'s shape when only singleton axes differ; (a, None) or (None, failed result)."""
    if a.shape == e.shape:
        return a, None
    if a.size == e.size and a.squeeze().shape == e.squeeze().shape:
        return a.reshape(e.shape), None
    if a.ndim == 2 and a.T.shape == e.shape:
        return a, "transposed"
    return None, _failed(name, Msg("wrong_shape", expected=e.shape, got=a.shape), "wrong_shape")


def check_value(answer, expected, *, rtol=1e-3, atol=1e-9, name=None, angles=None, periodic=()):
    """Check a number, vector or matrix against the expected value.

    Parameters
    ----------
    answer : number, array_like, sympy Matrix of numbers
        Real numbers; True/False, complex numbers and text are refused.
    expected : number, array_like or :class:`~kinbook.grading.expected.Expected`
        Computed by the caller with kinbook (an Expected also names the mistakes of that computation).
    rtol, atol : float
        |answer − expected| ≤ atol + rtol · max|expected| entry-wise (the book prints 4–6 significant
        digits, hence the default rtol = 1e-3).
    name : str, optional
        How to call the value in messages ("q̈", "Φ_q at t = 0" …); default "value" ("valor").
    angles : bool, optional
        Kept for compatibility: degrees for radians are diagnosed wherever they occur (``angles=False`` turns
        that off for values that cannot be angles).
    periodic : sequence of int
        Flat indices of entries that are angles, compared modulo 2π (φ = −π/2 and 3π/2 are the same
        orientation).

    Returns
    -------
    CheckResult
        One row per entry (flattened; 1-based positions).

    Examples
    --------
    >>> check_value([1.0, 2.0], [1.0, 2.0001]).passed
    True
    >>> check_value([[1, 3], [2, 4]], [[1, 2], [3, 4]]).mistakes
    ['transposed']
    """
    name = {"en": "value", "es": "valor"} if name is None else name
    exp = _expected(expected)
    if exp is None:
        return _failed(name, Msg("bad_type", expected="numbers", type=type(expected).__name__), "malformed")
    return _check(answer, exp, rtol, atol, name, angles is not False, periodic)


def _indexed(name, idx):
    """"A[1, 2]" — in every language when the name is translated."""
    suffix = "[" + ", ".join(str(int(i) + 1) for i in idx) + "]" if len(idx) else ""
    if isinstance(name, dict):
        return {lang: text + suffix for lang, text in name.items()}
    return name + suffix


def _check(answer, exp, rtol, atol, name, degrees=True, periodic=(), extra=None):
    e = np.asarray(exp.value, dtype=float)
    a, refused = _read(answer, name)
    if refused is not None:
        return _failed(name, Msg(refused.key, **refused.fields), refused.code)
    a, problem = _shape(a, e, name)
    if isinstance(problem, CheckResult):
        return problem
    if not np.all(np.isfinite(a)):
        return _failed(name, Msg("not_finite", where=name), "not_finite")
    per = np.zeros(e.size, bool)
    per[list(periodic or exp.periodic)] = True
    per = per.reshape(e.shape)
    if problem == "transposed":
        ok = _close(a.T, e, rtol, atol)
        msg = Msg("transposed", expected=e.shape, got=a.shape)
        notes = [msg] + ([Msg("transposed_right")] if ok else [])
        return CheckResult(False, 0.5 if ok else 0.0, notes + hints(["transposed"], {"transposed": (exp.kind,)}),
                           ["transposed"], (), name)
    if _close(a, e, rtol, atol, per):
        return CheckResult(True, 1.0, [Msg("value_ok")], [], _rows(a, e, rtol, atol, per, name, None), name)
    for value, why in exp.equivalents:
        if _close(a, np.asarray(value, float).reshape(e.shape), rtol, atol, per):
            return CheckResult(True, 1.0, [why], [], (), name)
    code, detail, erratum, note = _diagnose(a, e, exp, rtol, atol, per, degrees, extra, name)
    err = np.abs(a - e)
    if per.any():
        err = np.where(per, np.abs((a - e + np.pi) % (2 * np.pi) - np.pi), err)
    where = np.unravel_index(int(np.argmax(err)), err.shape) if err.ndim else ()
    where_text = _indexed(name, where)
    head = Msg("value_wrong", expected=_fmt_array(e), got=_fmt_array(a), err=fmt(err.max()), where=where_text)
    notes = [head]
    if note is not None:
        notes.append(note)
    if erratum:
        from .report import PRINTED

        notes.append(Msg("book_misprint", id=erratum) if code in PRINTED else Msg("d.book_row", id=erratum))
    if detail is not None:
        notes.append(detail)
    rows = _rows(a, e, rtol, atol, per, name, code)
    # a mistake of some entries (an entry's sign, two entries exchanged) keeps the credit of the right ones
    global_codes = code not in ("wrong_value", "sign_flip", "swapped_entries")
    good = sum(1 for r in rows if r.status == "ok")
    score = 0.0 if global_codes or not rows else good / len(rows)
    codes = [code]
    return CheckResult(False, round(score, 6), notes + hints(codes, {c: (exp.kind,) for c in codes}), codes,
                       tuple(rows), name)


def _rows(a, e, rtol, atol, per, name, code):
    if a.size > 64:
        return []
    scale = np.max(np.abs(e), initial=0.0)
    rows = []
    for idx in np.ndindex(e.shape):
        x, y = a[idx], e[idx]
        d = x - y
        if per[idx]:
            d = (d + np.pi) % (2 * np.pi) - np.pi
        good = abs(d) <= atol + rtol * scale
        label = _indexed(name, idx)
        rows.append(RowResult(label, "ok" if good else "wrong", "" if good else
                              Msg("value_entry", got=fmt(x), expected=fmt(y)), None if good else (code or "wrong_value"),
                              (), 1.0 if good else 0.0))
    return rows


def _diagnose(a, e, exp, rtol, atol, per, degrees, extra, name="value"):
    """(code, detail, erratum, note) of a wrong answer."""
    for code, value, detail, erratum in exp.variants:
        v = np.asarray(value, float)
        if v.shape != e.shape and v.size == e.size:
            v = v.reshape(e.shape)
        if v.shape == e.shape and not _close(v, e, rtol, atol, per) and _close(a, v, rtol, atol, per):
            return code, detail, erratum, None
    if extra is not None:
        found = extra(a, e)
        if found is not None:
            return found
    if a.ndim == 2 and a.shape[0] == a.shape[1] and _close(a.T, e, rtol, atol):
        return "transposed", None, None, Msg("transposed_right")
    nz = np.abs(e) > max(atol, 1e-12)
    if degrees and nz.any():
        # the answer in degrees where it differs (angles among other entries: q = [x, y, φ])
        wrong = ~np.isclose(a, e, rtol=rtol, atol=atol)
        deg = np.isclose(a, e * DEG, rtol=rtol, atol=atol * DEG)
        if per.any():
            deg |= per & np.isclose(np.mod(a, 360.0), np.mod(e * DEG, 360.0), rtol=rtol, atol=1e-3)
        if wrong.any() and np.all(deg[wrong]) and np.all(nz[wrong]):
            return "degrees", None, None, None
    if nz.any() and _close(a, -e, rtol, atol):
        return "sign_flip", None, None, None
    found = _entry_signs(a, e, rtol, atol, per, name) or _exchanged(a, e, rtol, atol, name)
    if found is not None:
        return found
    flat_a, flat_e = a.ravel(), e.ravel()
    ee = float(flat_e @ flat_e)
    c = float(flat_a @ flat_e) / ee if ee > 0 else 0.0
    if c not in (0.0, 1.0) and np.isfinite(c) and _close(a, c * e, rtol, atol):
        several = int(nz.sum()) >= 2
        if several or any(abs(c - p) <= 1e-3 * abs(p) for p in _PLAUSIBLE):
            return "scaled", Msg("value_scaled", c=fmt(c)), None, None
    return "wrong_value", None, None, None


def _wrong_entries(a, e, rtol, atol, per):
    scale = np.max(np.abs(e), initial=0.0)
    d = a - e
    if per.any():
        d = np.where(per, (d + np.pi) % (2 * np.pi) - np.pi, d)
    return np.abs(d) > atol + rtol * scale, scale


def _entry_signs(a, e, rtol, atol, per, name):
    """Some entries (not all) with the opposite sign, the others right: "sign_flip", naming them."""
    wrong, scale = _wrong_entries(a, e, rtol, atol, per)
    if not wrong.any() or wrong.all():
        return None
    flipped = np.abs(a + e) <= atol + rtol * scale
    if not np.all(flipped[wrong]) or not np.all(np.abs(e[wrong]) > max(atol, 1e-12)):
        return None
    where = [_indexed(name, idx) for idx in zip(*np.nonzero(wrong))] if a.ndim else [name]
    return "sign_flip", Msg("value_signs", where=where), None, None


def _exchanged(a, e, rtol, atol, name):
    """Two entries of a vector, or two rows or two columns of a matrix, exchanged (and nothing else wrong):
    "swapped_entries", naming them."""
    per = np.zeros(e.shape, bool)
    if a.ndim == 1 or (a.ndim == 2 and 1 in a.shape):
        flat_a, flat_e = a.ravel(), e.ravel()
        wrong, _ = _wrong_entries(flat_a, flat_e, rtol, atol, per.ravel())
        idx = np.nonzero(wrong)[0]
        if len(idx) == 2:
            i, j = idx
            swapped = flat_e.copy()
            swapped[[i, j]] = swapped[[j, i]]
            if _close(flat_a, swapped, rtol, atol):
                return "swapped_entries", Msg("value_exchanged", a=_indexed(name, (i,)), b=_indexed(name, (j,))), \
                    None, None
        return None
    if a.ndim != 2:
        return None
    for axis, key in ((0, "value_rows_exchanged"), (1, "value_cols_exchanged")):
        A, E = (a, e) if axis == 0 else (a.T, e.T)
        wrong = [k for k in range(E.shape[0]) if not _close(A[k], E[k], rtol, atol)]
        if len(wrong) == 2:
            i, j = wrong
            if _close(A[i], E[j], rtol, atol) and _close(A[j], E[i], rtol, atol):
                return "swapped_entries", Msg(key, a=i + 1, b=j + 1), None, None
    return None


# ================================================================================================ rotations
def check_rotation(answer, expected, *, rtol=1e-4, atol=1e-6, angles=None, name="A"):
    """Check a 3×3 rotation (direction-cosine) matrix.

    Parameters
    ----------
    answer : array_like, shape (3, 3)
    expected : array_like, shape (3, 3), or Expected
        Computed with kinbook.spatial (it maps local to global components: s = A s'); an Expected
        (``expected.A_from_euler``, ``expected.A_from_p``, ``expected.A_from_axes``) names its mistakes.
    angles : (ψ, θ, φ), optional
        The z-x-z Euler angles (radians) the exercise gave: the same as passing
        ``expected.A_from_euler(ψ, θ, φ)``.

    Returns
    -------
    CheckResult
        Mistakes: ``wrong_shape``, ``transposed``, ``degrees``, ``extrinsic_order``, ``factor_2_missing``,
        ``book_misprint``, ``not_orthogonal``, ``left_handed``, ``wrong_value``.
    """
    from .expected import A_from_euler

    if angles is not None and not isinstance(expected, Expected):
        exp = A_from_euler(*np.asarray(angles, float))
        exp.value = np.asarray(expected, float) if _expected(expected) is not None else exp.value
    else:
        exp = _expected(expected)
    if exp is None or np.asarray(exp.value).shape != (3, 3):
        return _failed(name, Msg("wrong_shape", expected="(3, 3)", got=np.shape(expected)), "malformed")
    exp.kind = "rotation"
    if not any(v[0] == "book_misprint" for v in exp.variants):
        exp.variants = list(exp.variants) + _from_matrix(exp.value)

    def properties(a, e):
        if a.shape != (3, 3):
            return None
        orth = float(np.max(np.abs(a.T @ a - np.eye(3))))
        det = float(np.linalg.det(a))
        if orth <= 1e3 * rtol and det < 0:
            return "left_handed", Msg("det_fail", det=fmt(det)), None, None
        if orth > 1e3 * rtol:
            return "not_orthogonal", Msg("orthogonal_fail", err=fmt(orth)), None, None
        return None

    a, refused = _read(answer, name)
    if refused is None and a.shape != (3, 3):
        return _failed(name, Msg("wrong_shape", expected="(3, 3)", got=a.shape), "wrong_shape")
    return _check(answer, exp, rtol, atol, name, True, (), properties)


def _from_matrix(A_):
    """Variants of any rotation matrix: the book's A(p) misprint and ½A, at the p of A."""
    try:
        from ..spatial.rotations import p_from_A
        from .expected import _book_A_of_p

        p = np.asarray(p_from_A(np.asarray(A_, float)), float)
    except Exception:  # not a rotation matrix: no p
        return []
    return [("factor_2_missing", 0.5 * np.asarray(A_), None, "14.3-A-of-p"),
            ("book_misprint", _book_A_of_p(p), None, "14.3-A-of-p")]


def check_euler_parameters(answer, expected, *, rtol=1e-4, atol=1e-6, axis=None, angle=None, name="p"):
    """Check Euler parameters p = [e0, e1, e2, e3].

    Parameters
    ----------
    answer, expected : array_like, shape (4,)
        ``expected`` computed with kinbook.spatial (or an Expected: ``expected.p_from_axis_angle(u, χ)``,
        ``expected.p_from_A(A)``). p and −p describe the same orientation: both pass.
    axis, angle : optional
        The rotation the exercise gave (axis u, angle χ in radians): the same as passing
        ``expected.p_from_axis_angle(u, χ)``. Without them the axis and angle are read from ``expected``.

    Returns
    -------
    CheckResult
        Mistakes: ``wrong_shape``, ``not_normalized``, ``degrees``, ``full_angle``, ``scalar_last``,
        ``wrong_value``.
    """
    from .expected import p_from_axis_angle

    base = _expected(expected)
    if base is None or np.asarray(base.value).size != 4:
        return _failed(name, Msg("wrong_shape", expected="(4,)", got=np.shape(expected)), "malformed")
    value = np.asarray(base.value, float).reshape(4)
    if isinstance(expected, Expected):
        exp = expected
    else:
        if axis is None or angle is None:
            e0, e = value[0], value[1:]
            chi = 2 * np.arctan2(np.linalg.norm(e), e0)
            axis = e / np.linalg.norm(e) if np.linalg.norm(e) > 1e-12 else np.array([0.0, 0.0, 1.0])
            angle = chi
        exp = p_from_axis_angle(axis, angle)
        exp.value = value
        exp.equivalents = [(-value, Msg("p_negated"))]
    exp.kind = "parameters"

    def normalization(a, e):
        a = a.reshape(-1)
        norm = float(a @ a)
        if norm > 0 and abs(norm - 1.0) > 1e3 * rtol:
            u = a / np.sqrt(norm)
            if np.allclose(u, e.reshape(-1), rtol=rtol, atol=atol) or np.allclose(u, -e.reshape(-1), rtol=rtol,
                                                                                   atol=atol):
                return "not_normalized", Msg("norm_fail", norm=fmt(norm)), None, None
        return None

    a, refused = _read(answer, name)
    if refused is None and a.size != 4:
        return _failed(name, Msg("wrong_shape", expected="(4,)", got=a.shape), "wrong_shape")
    if refused is None:
        answer = a.reshape(4)
    exp.value = value
    return _check(answer, exp, rtol, atol, name, True, (), normalization)

