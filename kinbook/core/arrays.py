"""Numbers handed over from Python as arrays: real, finite, numeric — never text, booleans or complex values
converted silently (numpy would turn "1" into 1.0, True into 1.0 and drop the imaginary part of 1j)."""

from __future__ import annotations

import functools

import numpy as np

from ..errors import InputError, KinbookError

__all__ = ["real_array", "no_overflow", "shapes", "symbolic_leaves"]


def real_array(value, name, what="numeric", finite=True):
    """``value`` as a float ndarray, or :class:`InputError` naming ``name`` and saying what was got.

    Refused: text, booleans, complex numbers, ragged nesting, objects that are not numbers, and (with
    ``finite``) NaN and inf.
    """
    if value is None:  # not "nan" (numpy's reading of None): the argument was not given
        raise InputError(f"`{name}` must be {what}, got None")
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):  # ragged nesting (numpy ≥ 1.24)
        raise InputError(f"`{name}` must be {what}, got {_show(value)}") from None
    kind = a.dtype.kind
    if kind == "O":
        if any(x is None for x in a.flat):
            raise InputError(f"`{name}` must be {what}, got None in {_show(value)}")
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


def shapes(func):
    """Decorator: numpy's broadcasting errors (arguments of incompatible shapes) become an :class:`InputError`
    naming the function and the shapes; overflow as :func:`no_overflow`."""

    @functools.wraps(func)
    @no_overflow
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except KinbookError:
            raise
        except ValueError as exc:
            shown = ", ".join(str(np.shape(a)) for a in args if isinstance(a, (np.ndarray, list, tuple, float, int)))
            raise InputError(f"{func.__name__}: arguments of incompatible shapes {shown} ({exc})") from None

    return wrapper


def symbolic_leaves(*values):
    """True when any of ``values`` (or an entry of a list, tuple, matrix or array of them) is a sympy object —
    the caller then takes its symbolic path — after checking that no entry is text: sympy's Matrix, cos …
    would evaluate text as Python (``sp.Matrix([x, "__import__('os')…"])`` runs it). Sympy entries get the
    bounds of :func:`kinbook.core.bounds.check_expression`."""
    import sympy as sp  # import time: sympy only when needed

    leaves, stack = [], list(values)
    while stack:
        v = stack.pop()
        if isinstance(v, sp.MatrixBase):
            leaves.extend(v)
        elif isinstance(v, (list, tuple)) or (isinstance(v, np.ndarray) and v.dtype.kind == "O"):
            if len(leaves) + len(stack) > 100_000:
                break
            stack.extend(v)
        else:
            leaves.append(v)
    if not any(isinstance(v, sp.Basic) for v in leaves):
        return False
    from .bounds import check_expression  # import time: core.bounds loads sympy

    for v in leaves:
        if isinstance(v, (str, bytes)):
            raise InputError(f"a sympy expression mixed with text {_show(v)}: text is never evaluated; build the "
                             "expression with sympy, or read the text with kinbook.core.reader.read_expression")
        if isinstance(v, sp.Basic):
            check_expression(v, where="a symbolic argument")
    return True
