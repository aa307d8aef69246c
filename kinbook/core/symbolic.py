"""Shared sympy machinery: from a symbolic Φ(q, t) derive Φ_q, ν and γ.

This is the one place where kinbook differentiates constraints. Every constraint, planar or spatial, writes
its Φ once (a list of sympy expressions); everything else is derived here::

    Φ_q = ∂Φ/∂q
    ν   = −Φ_t
    γ   = −(Φ_q q̇)_q q̇ − 2 Φ_qt q̇ − Φ_tt

(textbook §13.7 and §13.8; the sign of γ is the one that makes Φ_q q̈ = γ hold).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ..errors import DriverValueError
from ..i18n import N_, Message
from .arrays import symbolic_leaves
from .bounds import check_expression, refuse
from .reader import read_constant, read_expression

__all__ = ["Derivation", "derive", "time_function", "time_derivatives", "real_or_nan", "derivative_sizes", "DERIVATIVE_PARTS",
           "lambdify_vector"]

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
    symbolic_leaves(Phi, q, qd)  # refuses text, which sympy's Matrix would evaluate as Python
    Phi = sp.Matrix(Phi)
    q = sp.Matrix(q)
    qd = sp.Matrix(qd)
    Phi_q = Phi.jacobian(q)
    Phi_t = Phi.diff(time)
    nu = -Phi_t
    gamma = -(Phi_q * qd).jacobian(q) * qd - 2 * Phi_q.diff(time) * qd - Phi_t.diff(time)
    return Derivation(Phi=Phi, Phi_q=Phi_q, nu=nu, gamma=gamma, q=q, qd=qd, t=time)


#: The largest second derivative of a prescribed function f(t) kinbook derives, in parts of its tree (an upper
#: estimate, :func:`derivative_sizes`): differentiating and compiling one this size takes about a second.
DERIVATIVE_PARTS = 10_000


def _short(text, width=80):
    return repr(text if len(text) <= width else text[: width - 1] + "…")


_NOT_SMOOTH = ("Heaviside", "DiracDelta", "floor", "ceiling", "frac", "Piecewise", "Min", "Max", "sign", "Mod")


def time_function(f, where, time=t):
    """A prescribed function of time, read and validated once, when the driver is built.

    Parameters
    ----------
    f : str, number or sympy expression
        Text is read by :func:`kinbook.core.reader.read_expression` with the one symbol ``t``; a sympy
        expression may use any symbol *named* ``t`` (with or without assumptions).
    where : str
        Named in the messages ("driver on body 'crank', f").

    Returns
    -------
    sympy.Expr
        A real expression of ``time`` only, finite, continuous, whose first and second derivatives sympy
        can write and numpy can evaluate.

    Raises
    ------
    ExpressionError
        What is wrong and what to write instead: unreadable text, other symbols, complex or infinite
        values, steps and jumps (``sign``, ``floor``, ``Heaviside``, ``Piecewise``: a prescribed motion needs
        two continuous derivatives for ν and γ). ``Abs`` is accepted: its kink is reported, as a
        :class:`~kinbook.errors.DriverValueError`, only at an instant an analysis asks f'' there.
    """
    key = (f if isinstance(f, (str, sp.Basic)) else None, time)
    if key[0] is not None and key in _VALID:  # a mechanism of many bodies repeats the same few functions
        return _VALID[key]
    if isinstance(f, str):
        expr = read_expression(f, symbols={"t": time}, where=where)
    elif isinstance(f, sp.Basic):
        check_expression(f, where=where)
        if not isinstance(f, sp.Expr):
            refuse(where, Message(N_("expected an expression of t, got {type} {value}"), type=type(f).__name__,
                                  value=str(f)))
        expr = f.xreplace({s: time for s in f.free_symbols if isinstance(s, sp.Symbol) and s.name == time.name})
        if expr.has(sp.I):
            refuse(where, Message(N_("the function of time {text} is complex; expected a real function of t"),
                                  text=str(f)))
    else:
        expr = read_constant(f, where=where)
    text = f if isinstance(f, str) else str(f)
    extra = sorted(str(s) for s in expr.free_symbols - {time})
    if extra:
        refuse(where, Message(N_("the function of time {text} uses unknown symbols {names}; expected an expression of "
                                 "t alone"), text=repr(text), names=", ".join(extra)), text=text)
    if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
        refuse(where, Message(N_("the function of time {text} is not finite; expected a finite function of t"),
                              text=repr(text)), text=text)
    jumps = sorted({type(a).__name__ for a in sp.preorder_traversal(expr)
                    if isinstance(a, sp.Basic) and type(a).__name__ in _NOT_SMOOTH and a.has(time)})
    if jumps:
        refuse(where, Message(N_("the function of time {text} uses {names}, which jumps: a prescribed motion needs two "
                                 "continuous derivatives (for ν and γ); write a smooth function (a blend such as "
                                 "(1 - cos(pi*t))/2), or drive each phase in its own sweep"), text=repr(text),
                              names=", ".join(jumps)), text=text)
    _check_derivative_size(expr, time, where, text)
    for k in (1, 2):
        d = sp.diff(expr, time, k)
        if d.has(sp.Derivative, sp.Subs):
            refuse(where, Message(N_("sympy cannot differentiate the function of time {text} twice; expected a "
                                     "function built from + - * / ^ and sin, cos, exp …"), text=repr(text)), text=text)
    _check_numpy(expr, time, where, text)
    if key[0] is not None:
        if len(_VALID) > 4096:
            _VALID.clear()
        _VALID[key] = expr
    return expr


_VALID = {}  # (text or expression, time symbol) -> the validated expression


def _check_numpy(expr, time, where, text):
    """Refuse a function that numpy cannot evaluate with its derivatives: they are compiled here (cached) and
    evaluated once, so that a printer gap shows when the driver is built."""
    error = None
    try:
        with np.errstate(all="ignore"):
            for f in _compiled_derivatives(expr, time):
                f(np.array([0.0]))
    except (NameError, TypeError, AttributeError, KeyError) as exc:
        error = f"{type(exc).__name__}: {exc}"
    if error is not None:
        refuse(where, Message(N_("the function of time {text} or a derivative cannot be evaluated by numpy ({error}); "
                                 "write it with + - * / ^ and sin, cos, exp …"), text=repr(text), error=error),
               text=text)


def _check_derivative_size(expr, time, where, text):
    """Refuse, before sympy differentiates, a function whose second derivative would exceed
    :data:`DERIVATIVE_PARTS` (a few hundred bytes of text can take sympy minutes)."""
    size = derivative_sizes(expr, time)[2]
    if size > DERIVATIVE_PARTS:
        refuse(where, Message(N_("the function of time {text} is too involved to differentiate: its second derivative "
                                 "would have up to {size:,} parts (at most {limit:,}); expected a prescribed motion of "
                                 "a few terms (a driver of the book has a few dozen parts)"), text=_short(text),
                              size=size, limit=DERIVATIVE_PARTS), text=text)


def derivative_sizes(expr, time=t):
    """Sizes of ``expr`` and upper estimates of the sizes of its first and second derivatives in ``time``.

    Counted without differentiating — one pass over the tree, each distinct sub-expression once — by the
    rules of differentiation (the product rule of n factors gives n terms of n factors; the chain rule copies
    the argument): ``sin`` nested 99 deep has a second derivative of about 10⁵ parts, a product of 30 factors
    4·10⁴, where a driver of the book has a few dozen. Sizes are tree sizes, as sympy prints (not simplified).

    Returns
    -------
    (int, int, int)
    """
    memo = {}
    stack = [(expr, False)]
    while stack:
        node, ready = stack.pop()
        if node in memo:
            continue
        args = node.args
        if not args or isinstance(node, (sp.Number, sp.NumberSymbol)):
            memo[node] = (node == time, 1, 1, 1)
            continue
        if not ready:
            stack.append((node, True))
            stack.extend((a, False) for a in args if a not in memo)
            continue
        sub = [memo[a] for a in args]
        dep = [x for x in sub if x[0]]
        s0 = 1 + sum(x[1] for x in sub)
        if not dep:
            memo[node] = (False, s0, 1, 1)
            continue
        if isinstance(node, sp.Add):
            s1 = 1 + sum(x[2] for x in dep)
            s2 = 1 + sum(x[3] for x in dep)
        elif isinstance(node, sp.Mul):
            S, m = s0 - 1, len(dep)
            D0, D1, D2 = (sum(x[k] for x in dep) for k in (1, 2, 3))
            s1 = 1 + m + D1 + m * S - D0
            pairs = m * (m - 1) // 2
            s2 = 1 + m + D2 + m * S - D0 + 2 * pairs + (m - 1) * D1 + pairs * S - (m - 1) * D0
        elif isinstance(node, sp.Pow) and not sub[1][0]:
            (_, a0, a1, a2), (_, b0, _, _) = sub
            s1 = a0 + b0 + 5 + a1
            s2 = 3 * (a0 + b0) + 15 + 2 * a1 + a2
        elif isinstance(node, sp.Pow):
            (_, a0, a1, a2), (_, b0, b1, b2) = sub
            s1 = s0 + a0 + b0 + a1 + b1 + a0 + 8
            s2 = 2 * s1 + a2 + b2 + 2 * (a1 + b1) + 3 * (a0 + b0) + 16
        elif len(args) == 1:
            (_, a0, a1, a2), = sub
            g1, g2 = a0 + 8, 2 * a0 + 12
            s1 = 1 + g1 + a1
            s2 = 3 + g2 + 2 * a1 + g1 + a2
        else:
            P = 2 * (s0 - 1) + 10
            s1 = 1 + sum(1 + P + x[2] for x in dep)
            s2 = 1 + sum(2 + 2 * P + x[2] + y[2] for x in dep for y in dep) + sum(1 + P + x[3] for x in dep)
        memo[node] = (True, s0, s1, s2)
    return memo[expr][1:]


def time_derivatives(expr, time=t, where="the prescribed function f(t)"):
    """Compile a prescribed function f(t) with its first two derivatives.

    Returns three callables accepting a float or an ndarray of times, each returning an array of the same
    shape (a constant f broadcasts). Each raises :class:`~kinbook.errors.DriverValueError`, naming ``where``
    and the first such instant, when its value is not a finite real number (``sqrt(t - 5)`` before t = 5;
    f'' at the kink of an ``Abs``, where it does not exist).
    """
    if not isinstance(expr, sp.Basic):  # a number, or text: read (and validated) as a driver would be
        expr = time_function(expr, where, time)
    return tuple(_checked(f, k, expr, where) for k, f in enumerate(_compiled_derivatives(expr, time)))


@functools.lru_cache(maxsize=1024)
def _compiled_derivatives(expr, time):
    """f, f', f'' compiled by lambdify, once per expression (a mechanism of many bodies repeats a few)."""
    funcs = []
    for k in range(3):
        e = sp.diff(expr, time, k)
        f = sp.lambdify(time, e, modules=[{"DiracDelta": _delta}, "numpy"])
        funcs.append(_broadcasting(f, e.free_symbols))
    return tuple(funcs)


def _delta(u, order=0):
    """DiracDelta for numpy: 0 away from its point; not a number at it (f'' of a kink does not exist)."""
    u = np.asarray(u, dtype=float)
    return np.where(u == 0, np.nan, 0.0)


_WHAT = ("the value", "the first derivative", "the second derivative")


def _checked(f, k, expr, where):
    def call(tt):
        with np.errstate(all="ignore"):
            v = f(tt)
        if not np.all(np.isfinite(v)):
            v = np.asarray(v, dtype=float)
            first = int(np.flatnonzero(~np.isfinite(v))[0])
            t_bad = float(np.broadcast_to(np.asarray(tt, dtype=float), v.shape).flat[first])
            got = float(v.flat[first])
            why = (f"has no real value at t = {t_bad:.6g} (it is complex or undefined there)" if np.isnan(got)
                   else f"is infinite at t = {t_bad:.6g}")
            if np.isnan(got) and k == 2:
                why = f"does not exist at t = {t_bad:.6g} (a kink: the slope jumps there)"
            raise DriverValueError(
                f"{where}: {_WHAT[k]} of f(t) = {expr} {why}; expected a finite real value at every instant "
                "analysed: analyse only instants where f is smooth, or write a smooth f", t=t_bad)
        return v

    return call


def real_or_nan(value):
    """``value`` as a float array; an entry with a nonzero imaginary part (``sqrt(-t**2)``, ``I*t``) becomes NaN — no
    real value — instead of losing its imaginary part with numpy's ComplexWarning, so that the caller names it."""
    v = np.asarray(value)
    if np.iscomplexobj(v):
        with np.errstate(all="ignore"):
            return np.where(v.imag == 0, v.real, np.nan)
    return v.astype(float, copy=False)


def _broadcasting(f, free):
    if free:
        return lambda tt: real_or_nan(f(tt)) + np.zeros_like(tt, dtype=float)
    value = real_or_nan(f(0.0))
    return lambda tt: np.full(np.shape(tt), value, dtype=float)


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
