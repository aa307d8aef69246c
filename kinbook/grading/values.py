"""Checker for numeric answers: numbers, vectors and matrices (:func:`check_value`); rotation matrices and Euler
parameters are checked in :mod:`.rotation_values` with the same comparison and diagnosis (:mod:`.numbers`).

The expected value is computed by the caller with kinbook — a plain number or array, or an
:class:`~kinbook.grading.expected.Expected` (``kinbook.grading.expected.A_from_euler(ψ, θ, φ)`` …) that also
knows the other right answers (−p, the second triple of Euler angles) and the wrong answers students give,
each computed with kinbook's functions. The checkers compare and diagnose, the same way for every number:
the Expected's named mistakes first; then, for any value, degrees for radians (wherever the answer is the
expected angle in degrees: no flag needed), a transposed matrix, the sign, a plausible factor (2, ½, π, 1000 …)
of a nonzero reference, and for matrices and parameters their own conditions (orthogonality, det = +1,
pᵀp = 1).

``reveal=False`` (the notebooks' try-its) keeps the reference value out of the feedback: a wrong answer is
told which entries are off and how — the sign, too large or too small, the length or the direction of a
vector — and the mistake's name, never the number it should have been.
"""

from __future__ import annotations

import numpy as np

from ..i18n import N_, Message
from .numbers import angles_option, compare, expected_of, name_option, periodic_mask, reveal_option, tolerances

__all__ = ["check_value"]


def check_value(answer, expected, *, rtol=1e-3, atol=1e-9, name=None, angles=None, periodic=(), reveal=True):
    """Check a number, vector or matrix against the expected value.

    Parameters
    ----------
    answer : number, array_like, sympy Matrix of numbers
        Real numbers (texts of numbers, "pi/4", are read by kinbook's reader); True/False, complex numbers and
        other objects are refused.
    expected : number, array_like or :class:`~kinbook.grading.expected.Expected`
        Computed by the caller with kinbook (an Expected also names the mistakes of that computation).
    rtol, atol : float
        |answer − expected| ≤ atol + rtol · max|expected| entry-wise (the book prints 4–6 significant
        digits, hence the default rtol = 1e-3). rtol in [0, 0.1]; atol ≥ 0 and below a tenth of the
        reference's largest entry: a tolerance that would pass a wrong answer is refused.
    name : str or dict, optional
        How to call the value in messages ("q̈", "Φ_q at t = 0" …); default "value" ("valor").
    angles : bool, optional
        Degrees for radians are diagnosed wherever they occur; ``angles=False`` turns that off for values that
        cannot be angles.
    periodic : sequence of int, or boolean mask
        Flat (0-based) indices of entries that are angles, compared modulo 2π (φ = −π/2 and 3π/2 are the same
        orientation); added to the Expected's own.
    reveal : bool
        True (exercises, graded after the deadline): a wrong answer's feedback shows the expected value.
        False (self-tests): it says which entries are off and how, never the expected value.

    Returns
    -------
    CheckResult
        One row per entry (flattened; 1-based positions).

    Raises
    ------
    InputError
        A bad option or expected value; the message names the argument.

    Examples
    --------
    >>> check_value([1.0, 2.0], [1.0, 2.0001]).passed
    True
    >>> check_value([[1, 3], [2, 4]], [[1, 2], [3, 4]]).mistakes
    ['transposed']
    """
    name = name_option(name, Message(N_("value")))
    exp = expected_of(expected)
    e = np.asarray(exp.value, float)
    rtol, atol = tolerances(rtol, atol, e)
    per = periodic_mask(periodic, e.shape) | periodic_mask(tuple(exp.periodic), e.shape)
    return compare(answer, exp, rtol, atol, name, angles_option(angles), per, reveal=reveal_option(reveal))
