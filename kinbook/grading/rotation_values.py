"""Checkers for rotation matrices (:func:`check_rotation`) and Euler parameters (:func:`check_euler_parameters`):
:mod:`.values`' comparison and diagnosis, with their own conditions (orthogonality, det = +1, pᵀp = 1) and the
other right answers (−p, the second triple of Euler angles)."""

from __future__ import annotations

import numpy as np

from ..errors import InputError, KinbookError
from ..spatial.rotations import p_from_A
from ._i18n import Msg
from .expected import A_from_euler, Expected, p_from_axis_angle
from .misprints import book_A_of_p
from .numbers import (
    close,
    compare,
    expected_of,
    failed,
    name_option,
    read_numbers,
    real_option,
    reveal_option,
    tolerances,
)
from .report import fmt

__all__ = ["check_rotation", "check_euler_parameters"]


def _triple(value, arg):
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"`{arg}` must be three real numbers (radians), got {value!r}") from None
    if arr.shape != (3,) or not np.all(np.isfinite(arr)) or isinstance(value, (bool, np.bool_)):
        raise InputError(f"`{arg}` must be three finite real numbers (radians), got {value!r}")
    return arr


def check_rotation(answer, expected, *, rtol=1e-4, atol=1e-6, angles=None, name="A", reveal=True):
    """Check a 3×3 rotation (direction-cosine) matrix.

    Parameters
    ----------
    answer : array_like, shape (3, 3)
    expected : array_like, shape (3, 3), or Expected
        Computed with kinbook.spatial (it maps local to global components: s = A s'); an Expected
        (``expected.A_from_euler``, ``expected.A_from_p``, ``expected.A_from_axes``) names its mistakes.
    rtol, atol : float
        As in :func:`check_value`.
    angles : (ψ, θ, φ), optional
        The z-x-z Euler angles (radians) the exercise gave: the same as passing
        ``expected.A_from_euler(ψ, θ, φ)``.
    reveal : bool
        As in :func:`check_value`.

    Returns
    -------
    CheckResult
        Mistakes: ``wrong_shape``, ``transposed``, ``degrees``, ``extrinsic_order``, ``factor_2_missing``,
        ``book_misprint``, ``not_orthogonal``, ``left_handed``, ``wrong_value``.

    Raises
    ------
    InputError
        A bad option or expected value; the message names the argument.
    """
    name = name_option(name, "A")
    reveal = reveal_option(reveal)
    base = expected_of(expected)
    if np.asarray(base.value).shape != (3, 3):
        raise InputError(f"`expected` must be a 3×3 matrix, got shape {np.shape(base.value)}")
    if angles is not None:
        triple = _triple(angles, "angles")
        if not isinstance(expected, Expected):
            exp = A_from_euler(*triple)
            if not close(np.asarray(exp.value), np.asarray(base.value, float), 1e-6, 1e-9):
                raise InputError("`angles` do not give `expected`: A_from_euler(*angles) differs from it")
            exp.value = np.asarray(base.value, float)
        else:
            exp = base
    else:
        exp = base
    rtol, atol = tolerances(rtol, atol, exp.value)
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

    a, refused = read_numbers(answer, name)
    if refused is None and a.shape != (3, 3):
        return failed(name, Msg("wrong_shape", expected="(3, 3)", got=a.shape), "wrong_shape")
    return compare(answer, exp, rtol, atol, name, True, None, properties, reveal=reveal)


def _from_matrix(A_):
    """Variants of any rotation matrix: the book's A(p) misprint and ½A, at the p of A."""
    try:
        p = np.asarray(p_from_A(np.asarray(A_, float)), float)
    except (KinbookError, ValueError, np.linalg.LinAlgError):  # not a rotation matrix: no p
        return []
    return [("factor_2_missing", 0.5 * np.asarray(A_), None, "14.3-A-of-p"),
            ("book_misprint", book_A_of_p(p), None, "14.3-A-of-p")]


def check_euler_parameters(answer, expected, *, rtol=1e-4, atol=1e-6, axis=None, angle=None, name="p",
                           reveal=True):
    """Check Euler parameters p = [e0, e1, e2, e3].

    Parameters
    ----------
    answer, expected : array_like, shape (4,)
        ``expected`` computed with kinbook.spatial (or an Expected: ``expected.p_from_axis_angle(u, χ)``,
        ``expected.p_from_A(A)``). p and −p describe the same orientation: both pass.
    rtol, atol : float
        As in :func:`check_value`.
    axis, angle : optional
        The rotation the exercise gave (axis u — three numbers, not zero — and angle χ in radians): the same
        as passing ``expected.p_from_axis_angle(u, χ)``; give both or neither. Without them the axis and angle
        are read from ``expected``.
    reveal : bool
        As in :func:`check_value`.

    Returns
    -------
    CheckResult
        Mistakes: ``wrong_shape``, ``not_normalized``, ``degrees``, ``full_angle``, ``scalar_last``,
        ``wrong_value``.

    Raises
    ------
    InputError
        A bad option or expected value; the message names the argument.
    """
    name = name_option(name, "p")
    reveal = reveal_option(reveal)
    base = expected_of(expected)
    if np.asarray(base.value).size != 4:
        raise InputError(f"`expected` must be 4 Euler parameters, got shape {np.shape(base.value)}")
    value = np.asarray(base.value, float).reshape(4)
    if abs(value @ value - 1.0) > 1e-6:
        raise InputError(f"`expected` must be unit Euler parameters (pᵀp = 1), got pᵀp = {value @ value:.6g}")
    rtol, atol = tolerances(rtol, atol, value)
    if (axis is None) != (angle is None):
        raise InputError("`axis` and `angle` go together: give both (the rotation the exercise gave) or neither")
    if axis is not None:
        axis = _triple(axis, "axis")
        if np.linalg.norm(axis) == 0:
            raise InputError("`axis` must not be the zero vector")
        angle = real_option(angle, "angle")
    if isinstance(expected, Expected):
        exp = base
    else:
        if axis is None:
            e0, e = value[0], value[1:]
            chi = 2 * np.arctan2(np.linalg.norm(e), e0)
            axis = e / np.linalg.norm(e) if np.linalg.norm(e) > 1e-12 else np.array([0.0, 0.0, 1.0])
            angle = chi
        exp = p_from_axis_angle(axis, angle)
        given = np.asarray(exp.value, float)
        if not (close(given, value, 1e-6, 1e-9) or close(-given, value, 1e-6, 1e-9)):
            raise InputError("`axis` and `angle` do not give `expected`: p_from_axis_angle(axis, angle) differs "
                             "from it (and from −expected)")
        exp.value = value
        exp.equivalents = [(-value, Msg("p_negated"))]
    exp.kind = "parameters"

    def normalization(a, e):
        a = a.reshape(-1)
        norm = float(a @ a)
        if norm > 0 and abs(norm - 1.0) > 1e3 * rtol:  # no Euler parameters at all: say so, with pᵀp
            return "not_normalized", Msg("norm_fail", norm=fmt(norm)), None, None
        return None

    a, refused = read_numbers(answer, name)
    if refused is None and a.size != 4:
        return failed(name, Msg("wrong_shape", expected="(4,)", got=a.shape), "wrong_shape")
    if refused is None:
        answer = a.reshape(4)
    exp.value = value
    return compare(answer, exp, rtol, atol, name, True, None, normalization, reveal=reveal)
