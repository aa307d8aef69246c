"""Numbers handed over from Python as arrays: real, finite, numeric — never text, booleans or complex values
converted silently (numpy would turn "1" into 1.0, True into 1.0 and drop the imaginary part of 1j)."""

from __future__ import annotations

import functools

import numpy as np

from .errors import InputError

__all__ = ["real_array", "no_overflow"]


def real_array(value, name, what="numeric", finite=True):
    """``value`` as a float ndarray, or :class:`InputError` naming ``name`` and saying what was got.

    Refused: text, booleans, complex numbers, ragged nesting, objects that are not numbers, and (with
    ``finite``) NaN and inf.
    """
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):  # ragged nesting (numpy ≥ 1.24)
        raise InputError(f"`{name}` must be {what}, got {_show(value)}") from None
    kind = a.dtype.kind
    if kind == "O":
        try:
            a = a.astype(float)
        except (TypeError, ValueError):
            raise InputError(f"`{name}` must be {what}, got {_show(value)}") from None
        kind = "f"
    if kind == "c":
        raise InputError(f"`{name}` must be real, got complex values {_show(value)}")
    if kind not in "iuf":
        got = {"b": "booleans", "U": "text", "S": "bytes", "M": "dates", "m": "time spans"}.get(kind, a.dtype.name)
        raise InputError(f"`{name}` must be {what}, got {got} {_show(value)}")
    a = a.astype(float, copy=False)
    if finite and not np.all(np.isfinite(a)):
        raise InputError(f"`{name}` must be finite (no NaN or inf), got {_show(a)}")
    return a


def _show(value, width=80):
    text = np.array2string(value, precision=6, threshold=20) if isinstance(value, np.ndarray) else repr(value)
    return text if len(text) <= width else text[: width - 1] + "…"


def no_overflow(func):
    """Decorator: a result that overflows (finite arguments too large, such as φ̇ = 1e200 squared) is an
    :class:`InputError` naming the function, not an array of inf."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            with np.errstate(over="raise"):
                return func(*args, **kwargs)
        except FloatingPointError:
            raise InputError(f"{func.__name__}: the arguments are too large, the result overflows") from None

    return wrapper
