"""Shared sympy machinery: from a symbolic Φ(q, t) derive Φ_q, ν and γ.

This is the one place where kinbook differentiates constraints. Every constraint, planar or spatial, writes
its Φ once (a list of sympy expressions); everything else is derived here::

    Φ_q = ∂Φ/∂q
    ν   = −Φ_t
    γ   = −(Φ_q q̇)_q q̇ − 2 Φ_qt q̇ − Φ_tt

(textbook §13.7 and §13.8; the sign of γ is the one that makes Φ_q q̈ = γ hold).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

__all__ = ["Derivation", "derive", "time_derivatives", "lambdify_vector"]

t = sp.Symbol("t", real=True)
"""The time symbol shared by every mechanism."""


@dataclass(frozen=True)
class Derivation:
    """Φ and the quantities derived from it, as sympy column matrices.

    Attributes
    ----------
    Phi : sympy.Matrix, shape (m, 1)
    Phi_q : sympy.Matrix, shape (m, n)
    nu : sympy.Matrix, shape (m, 1)
        Right-hand side of the velocity equations, ν = −Φ_t.
    gamma : sympy.Matrix, shape (m, 1)
        Right-hand side of the acceleration equations.
    q, qd : sympy.Matrix, shape (n, 1)
        The coordinates and their time derivatives the derivation used.
    t : sympy.Symbol
    """

    Phi: sp.Matrix
    Phi_q: sp.Matrix
    nu: sp.Matrix
    gamma: sp.Matrix
    q: sp.Matrix
    qd: sp.Matrix
    t: sp.Symbol

    def _repr_latex_(self):
        rows = [
            (r"\Phi", self.Phi),
            (r"\Phi_{\mathbf{q}}", self.Phi_q),
            (r"\nu", self.nu),
            (r"\gamma", self.gamma),
        ]
        body = r" \\ ".join(f"{name} &= {sp.latex(value)}" for name, value in rows)
        return r"$\begin{aligned}" + body + r"\end{aligned}$"


def derive(Phi, q, qd, time=t):
    """Derive Φ_q, ν and γ from Φ.

    Parameters
    ----------
    Phi : sympy.Matrix or sequence of sympy expressions
        The constraint functions Φ(q, t).
    q, qd : sympy.Matrix or sequence of symbols, length n
        Coordinates and velocities.
    time : sympy.Symbol
        The time symbol Φ may depend on.

    Returns
    -------
    Derivation

    Examples
    --------
    >>> import sympy as sp
    >>> x, dx = sp.symbols("x dx")
    >>> d = derive([x**2 - sp.sin(t)], [x], [dx])
    >>> d.Phi_q, d.nu, d.gamma
    (Matrix([[2*x]]), Matrix([[cos(t)]]), Matrix([[-2*dx**2 - sin(t)]]))
    """
    Phi = sp.Matrix(Phi)
    q = sp.Matrix(q)
    qd = sp.Matrix(qd)
    Phi_q = Phi.jacobian(q)
    Phi_t = Phi.diff(time)
    nu = -Phi_t
    gamma = -(Phi_q * qd).jacobian(q) * qd - 2 * Phi_q.diff(time) * qd - Phi_t.diff(time)
    return Derivation(Phi=Phi, Phi_q=Phi_q, nu=nu, gamma=gamma, q=q, qd=qd, t=time)


def time_derivatives(expr, time=t):
    """Compile a prescribed function f(t) with its first two derivatives.

    Returns three callables accepting a float or an ndarray of times, each returning an array of the same
    shape (a constant f broadcasts).
    """
    expr = sp.sympify(expr)
    funcs = []
    for k in range(3):
        e = sp.diff(expr, time, k)
        f = sp.lambdify(time, e, modules="numpy")
        funcs.append(_broadcasting(f, e.free_symbols))
    return tuple(funcs)


def _broadcasting(f, free):
    if free:
        return lambda tt: np.asarray(f(tt), dtype=float) + np.zeros_like(tt, dtype=float)
    value = float(f(0.0))
    return lambda tt: np.full(np.shape(tt), value)


def lambdify_vector(exprs, args):
    """Lambdify a list of expressions with common-subexpression elimination into one callable returning a
    float array of shape (len(exprs),).

    Parameters
    ----------
    exprs : sequence of sympy expressions
    args : sequence of symbols or sequences of symbols, as for :func:`sympy.lambdify`.
    """
    exprs = list(exprs)
    f = sp.lambdify(args, exprs, modules="numpy", cse=True)

    def call(*values):
        return np.array(f(*values), dtype=float)

    return call
