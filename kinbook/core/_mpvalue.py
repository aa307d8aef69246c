"""Numeric values of the reader's trees: mpmath at a fixed precision for exact sympy numbers and the allowed
functions, and complex math for estimates (:mod:`kinbook.core.reader`, which alone uses it)."""

from __future__ import annotations

import cmath
import math

import sympy as sp

__all__ = ["COMPLEX", "MP_BY_NAME", "mp_value"]


def _real(z):
    if z.imag != 0:
        raise ValueError("complex argument")
    return z.real


COMPLEX = {
    "sin": cmath.sin, "cos": cmath.cos, "tan": cmath.tan, "asin": cmath.asin, "acos": cmath.acos,
    "atan": cmath.atan, "atan2": lambda y, x: math.atan2(_real(y), _real(x)), "sqrt": cmath.sqrt,
    "exp": cmath.exp, "log": lambda x, b=math.e: cmath.log(x, b), "Abs": abs,
    "sign": lambda x: float((_real(x) > 0) - (_real(x) < 0)),
}


def mp_value(e, mpmath):
    """mpmath value of a sympy tree of numbers, constants and the functions of :data:`FUNCTIONS`."""
    if isinstance(e, sp.Integer):
        return mpmath.mpf(int(e))
    if isinstance(e, sp.Rational):
        return mpmath.mpf(int(e.p)) / int(e.q)
    if isinstance(e, sp.Float):
        return mpmath.mpf(e._mpf_)
    if e is sp.pi:
        return +mpmath.pi
    if e is sp.E:
        return +mpmath.e
    if e is sp.I:
        return mpmath.mpc(0, 1)
    args = [mp_value(a, mpmath) for a in e.args]
    if isinstance(e, sp.Add):
        return mpmath.fsum(args)
    if isinstance(e, sp.Mul):
        return mpmath.fprod(args)
    if isinstance(e, sp.Pow):
        return mpmath.power(args[0], args[1])
    if isinstance(e, sp.exp):
        return mpmath.exp(args[0])
    f = _MP_FUNCTIONS.get(type(e))
    if f is None:  # a sympy object from Python with other functions: sympy's own evaluation
        return mpmath.mpmathify(complex(e.evalf(20)))
    return f(mpmath)(*args)


_MP_FUNCTIONS = {
    sp.sin: lambda m: m.sin, sp.cos: lambda m: m.cos, sp.tan: lambda m: m.tan, sp.asin: lambda m: m.asin,
    sp.acos: lambda m: m.acos, sp.atan: lambda m: m.atan, sp.log: lambda m: m.log, sp.Abs: lambda m: abs,
    sp.atan2: lambda m: lambda y, x: m.atan2(_mp_real(y), _mp_real(x)),
    sp.sign: lambda m: lambda x: m.sign(_mp_real(x)),
}


MP_BY_NAME = {
    "sin": lambda m: m.sin, "cos": lambda m: m.cos, "tan": lambda m: m.tan, "asin": lambda m: m.asin,
    "acos": lambda m: m.acos, "atan": lambda m: m.atan, "exp": lambda m: m.exp, "sqrt": lambda m: m.sqrt,
    "log": lambda m: lambda x, b=None: m.log(x) if b is None else m.log(x) / m.log(b), "Abs": lambda m: abs,
    "atan2": lambda m: lambda y, x: m.atan2(_mp_real(y), _mp_real(x)),
    "sign": lambda m: lambda x: m.sign(_mp_real(x)),
}


def _mp_real(x):
    if getattr(x, "imag", 0) != 0:
        raise ValueError("complex argument")
    return getattr(x, "real", x)
