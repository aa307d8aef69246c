"""Notebook helpers: one set-up call, and outputs that do not depend on the CPU.

A stored notebook is re-validated with nbval on other machines, whose BLAS and SIMD kernels round
differently: a value that is zero in exact arithmetic comes out as ``0.0`` on one CPU, ``-1.5e-17`` on
another. Everything a chapter notebook prints therefore goes through this module:

- :func:`setup` (``kinbook.notebook_setup()``) sets numpy's print options, makes arrays and floats that
  are the value of a cell display through :func:`clean`, sets the figure defaults and the feedback language;
- :func:`clean` turns every entry below a tolerance (``TOL = 1e-12``) into an exact ``0.0`` — no ``-0.``,
  no ``1e-17``;
- :func:`show` is ``print`` with every number cleaned first;
- :func:`agrees` and :func:`small` write evidence as "agrees to within 1e-12" or "< 1e-12" instead of the
  machine's round-off.

Examples
--------
>>> import numpy as np
>>> clean(np.array([-1.5e-17, 0.25, 3e-13]))
array([0.  , 0.25, 0.  ])
>>> agrees(8.9e-16), agrees(0.045)
('agrees to within 1e-12', 'differs by 0.045')
>>> small(3.2e-5), small(4e-17)
('3.2e-05', '< 1e-12')
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from ..core.sweep import SimulationResult
from ..errors import InputError
from ..grading import set_language

__all__ = ["TOL", "setup", "clean", "show", "agrees", "small", "fmt", "tolerance_text", "sweep_both_ways", "time_axes"]

TOL = 1e-12
"""Below this magnitude a computed value is shown as 0 (round-off of an exact zero)."""

PRECISION = 4
"""Decimals numpy prints in a notebook (the book prints four)."""


def _real(x, name, function):
    """``x`` as a float, or :class:`~kinbook.errors.InputError` naming the helper and the argument."""
    if not isinstance(x, (bool, str, bytes)):
        try:
            return float(x)
        except (TypeError, ValueError, OverflowError):
            pass
    raise InputError(f"{function}: `{name}` must be a real number, got {type(x).__name__} {str(x)[:60]!r}")


def _tolerance(tol, function):
    value = _real(tol, "tol", function)
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{function}: `tol` must be a positive finite number, got {tol!r}")
    return value


def _digits(digits, function, low=0, high=17):
    if isinstance(digits, bool) or not isinstance(digits, numbers.Integral) or not low <= digits <= high:
        raise InputError(f"{function}: `digits` must be a whole number from {low} to {high}, got {digits!r}")
    return int(digits)


def tolerance_text(tol):
    """A tolerance as people write it: ``1e-12`` (not ``1e-12`` padded as ``1.0e-12`` or ``1e-012``).

    >>> tolerance_text(1e-12), tolerance_text(5e-7), tolerance_text(0.001), tolerance_text(0.5)
    ('1e-12', '5e-7', '1e-3', '0.5')
    """
    tol = _tolerance(tol, "tolerance_text")
    if tol >= 0.01:
        return f"{tol:g}"
    mantissa, exponent = f"{tol:.0e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _clean_scalar(v, tol):
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Number):
        return v
    if isinstance(v, numbers.Integral):
        return v
    if isinstance(v, complex):
        return complex(_clean_scalar(v.real, tol), _clean_scalar(v.imag, tol))
    f = float(v)
    return 0.0 if abs(f) < tol else f


def clean(x, tol=TOL):
    """``x`` with every number of magnitude below ``tol`` replaced by an exact ``0.0``.

    Parameters
    ----------
    x : float, ndarray, or a list, tuple or dict of them
        Anything else (strings, sympy objects, integers) is returned unchanged.
    tol : float

    Returns
    -------
    The same kind of object. Floating-point arrays are copied; ``-0.0`` becomes ``0.0``.

    >>> clean([1e-20, -0.0, 2.5, "text"])
    [0.0, 0.0, 2.5, 'text']
    """
    if isinstance(x, np.ndarray):
        if x.dtype.kind == "f":
            out = np.where(np.abs(x) < tol, 0.0, x)
            return out + 0.0  # -0.0 + 0.0 == +0.0
        if x.dtype.kind == "c":
            return clean(x.real, tol) + 1j * clean(x.imag, tol)
        return x
    if isinstance(x, np.generic) and x.dtype.kind in "fc":
        return type(x)(_clean_scalar(x.item(), tol))
    if isinstance(x, list):
        return [clean(v, tol) for v in x]
    if isinstance(x, tuple) and not hasattr(x, "_fields"):
        return tuple(clean(v, tol) for v in x)
    if isinstance(x, dict):
        return {k: clean(v, tol) for k, v in x.items()}
    return _clean_scalar(x, tol)


def show(*values, sep=" ", end="\n", tol=TOL):
    """``print`` for notebooks: every number and array is passed through :func:`clean` first.

    A float is written with up to 10 significant digits, an array with numpy's print options (four decimals
    after :func:`setup`), so nothing the CPU rounds differently reaches the stored output.

    >>> show("residual:", np.array([1e-17, -2e-16]), "angle:", -0.0)
    residual: [0. 0.] angle: 0
    """
    parts = []
    for v in values:
        v = clean(v, tol)
        if isinstance(v, float):
            parts.append(f"{v:.10g}")
        else:
            parts.append(str(v))
    print(*parts, sep=sep, end=end)


def fmt(x, digits=PRECISION, tol=TOL):
    """One number with ``digits`` decimals, never ``-0.0000``.

    >>> fmt(-1e-17), fmt(2 / 3), fmt(-0.00004, 4)
    ('0.0000', '0.6667', '0.0000')
    """
    x, digits, tol = _real(x, "x", "fmt"), _digits(digits, "fmt"), _tolerance(tol, "fmt")
    text = f"{clean(x, tol):.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text


def small(x, tol=TOL, digits=2, *, relation=False):
    """A residual or error: its magnitude with ``digits`` significant digits, or ``"< tol"`` below ``tol``.

    With ``relation=True`` the text completes a label as a relation — ``"= 0.045"`` or ``"< 1e-12"`` — so a line
    such as ``show("max|E p|", small(x, relation=True))`` never reads "max|E p| = < 1e-12".

    >>> small(-0.0451), small(float("nan")), small(0.0451, relation=True), small(1e-17, relation=True)
    ('0.045', 'nan', '= 0.045', '< 1e-12')
    """
    x, tol, digits = abs(_real(x, "x", "small")), _tolerance(tol, "small"), _digits(digits, "small", 1)
    if math.isnan(x):
        return "= nan" if relation else "nan"
    if x < tol:
        return f"< {tolerance_text(tol)}"
    text = f"{x:.0f}" if x >= 10**digits else f"{x:.{digits}g}"
    return f"= {text}" if relation else text


def agrees(error, tol=TOL):
    """Evidence in words: ``"agrees to within 1e-12"`` when ``error < tol``, else ``"differs by …"``.

    >>> agrees(3e-7, tol=1e-6)
    'agrees to within 1e-6'
    """
    error, tol = abs(_real(error, "error", "agrees")), _tolerance(tol, "agrees")
    if error < tol:
        return f"agrees to within {tolerance_text(tol)}"
    return f"differs by {small(error, tol, 2 if error < 1 else 4)}"


# ----------------------------------------------------------------------------------------------- setup
def _plain_array(arr, p, cycle):
    p.text(repr(clean(arr)))


def _plain_float(x, p, cycle):
    p.text(f"{clean(float(x)):.10g}")


def setup(language=None, *, precision=PRECISION):
    """Prepare a notebook: call once, in the first code cell (``kinbook.notebook_setup()``).

    - numpy prints ``precision`` decimals and no scientific notation for small numbers;
    - an array or a float that is the value of a cell is displayed through :func:`clean`;
    - checkers give their feedback in ``language`` ("en" or "es", :func:`kinbook.set_language`).

    Parameters
    ----------
    language : {"en", "es"}, optional
        Default: leave the current language as it is (English unless changed).
    precision : int
    """
    np.set_printoptions(precision=precision, suppress=True)
    if language is not None:
        set_language(language)
    try:
        from IPython import get_ipython  # optional dependency
    except ImportError:  # pragma: no cover - outside Jupyter
        return
    ip = get_ipython()
    if ip is None:
        return
    plain = ip.display_formatter.formatters["text/plain"]
    plain.for_type(np.ndarray, _plain_array)
    for kind in (float, np.floating):
        plain.for_type(kind, _plain_float)


def sweep_both_ways(mech, backward, forward):
    """Sweep a mechanism from t = 0 backwards and forwards until it stops assembling, as one time history.

    Both sweeps start at t = 0, so they keep the assembly mode of the solution there (a sweep started at a limit
    position may continue on either branch).

    Parameters
    ----------
    mech : Mechanism
    backward, forward : array_like
        Instants from 0 down, and from 0 up (each starting at 0).

    Returns
    -------
    SimulationResult
        The solved instants in increasing time; ``failure`` is the forward sweep's.
    """
    back = mech.simulate(backward, on_failure="truncate")
    fwd = mech.simulate(forward, on_failure="truncate")
    join = [np.r_[getattr(back, a)[:0:-1], getattr(fwd, a)] for a in ("t", "q", "qd", "qdd")]
    return SimulationResult(mech, *join, failure=fwd.failure)


def time_axes(*axes, unit="s"):
    """Label the horizontal axis of each plot as time with its unit, ``t (s)``."""
    for ax in axes:
        ax.set_xlabel(f"$t$ ({unit})")
