"""The numeric path of a constraint type compiled from its symbolic Φ, and the stacking of composite parts.

A *kernel* evaluates the geometric part g(q) of Φ = g(q) − f(t) for every constraint of one type at once and
for many instants at once: ``kernel(Q, P, Qd=None, jacobian=True) -> (Φ, Φ_q, γ)`` with Q of shape
(B, k, nb, ncoord) (B instants, k constraints of the type, nb bodies each), P a dict of parameter arrays with
a leading axis k, and results of shape (B, k, r), (B, k, r, ncoord·nb) and (B, k, r) (γ only with Qd; Φ_q
None when ``jacobian`` is false). The mechanism applies the drivers' f(t) (:meth:`MechanismBase.evaluate`).

:func:`compiled` builds the kernel of a type from :meth:`Constraint.phi` alone. The constraint's numeric
attributes (its ``parameters``: local points, lengths, radii …) are replaced by symbols, so Φ is written once
per type with symbolic parameters. Φ_q is its Jacobian, and the velocity-quadratic γ = −(Φ_q q̇)_q q̇ is
−d²Φ(q + s q̇)/ds² at s = 0, both differentiated through the nodes of Φ (:func:`_chain`: γ forward, Φ_q in
reverse; the same values as :func:`kinbook.core.symbolic.derive` gives, at a cost linear in the size of Φ); all are
lambdified, the chain of nodes serving as the common-subexpression elimination, into numpy code that
broadcasts over instants (B) and constraints (k), the lambdified functions built when first called. The
compiled kernel is cached per type and per *template*:
the symbolic Φ with symbolic parameters. What is not a declared parameter (the coordinate a simple
constraint fixes, a flag, a profile function ρ(ψ) of a cam) stays in the template, so constraints that
differ there get kernels of their own — always correct, shared as far as the declarations allow.

Hand-written kernels (:mod:`kinbook.planar.constraints`, :mod:`kinbook.spatial.constraints`) are
optimizations of these; the tests hold both equal for every type.
"""

from __future__ import annotations

import copy

import numpy as np
import sympy as sp
from sympy.printing.numpy import NumPyPrinter

from ..errors import ModelError
from .symbolic import t as t_symbol

__all__ = ["compiled", "stacked", "CompiledKernel", "StackedKernel"]

_CACHE_LIMIT = 512
_COMPILED = {}
_STACKED = {}


class CompiledKernel:
    """A kernel lambdified from a type's symbolic Φ with symbolic parameters (see the module notes).

    The functions for Φ; Φ and Φ_q; Φ and γ; and all three are lambdified when first needed.
    """

    optional_jacobian = True

    def __init__(self, exprs, q, params, name):
        self.exprs = list(exprs)
        self.q = list(q)
        self.qd = [sp.Symbol("d" + s.name, real=True) for s in self.q]
        self.params = list(params)
        self.name = name
        self.n_eq = len(self.exprs)
        self._functions = {}

    def __repr__(self):
        return f"<compiled kernel of {self.name}: {self.n_eq} rows, {len(self.params)} parameters>"

    def _function(self, jacobian, gamma):
        key = (jacobian, gamma)
        if key not in self._functions:
            args = self.q + (self.qd if gamma else []) + self.params
            if not (jacobian or gamma):
                self._functions[key] = sp.lambdify(args, self.exprs, modules="numpy", cse=True)
            else:
                chain, phi, jac, gam = _chain(self.exprs, self.q, self.qd, jacobian, gamma)
                out = phi + [e for row in jac for e in row] + gam

                def cse(exprs):  # the chain of nodes is the common-subexpression elimination
                    return chain, out

                self._functions[key] = sp.lambdify(args, out, modules="numpy", cse=cse, printer=_printer())
        return self._functions[key]

    def __call__(self, Q, P, Qd=None, jacobian=True):
        Bn, k, nb, nc = Q.shape
        r, c = self.n_eq, nb * nc
        gamma = Qd is not None
        args = [Q[:, :, b, j] for b in range(nb) for j in range(nc)]
        if gamma:
            args += [Qd[:, :, b, j] for b in range(nb) for j in range(nc)]
        p = P["p"]
        args += [p[:, j] for j in range(p.shape[1])]
        values = self._function(jacobian, gamma)(*args)
        out = np.empty((len(values), Bn, k))
        for i, v in enumerate(values):
            out[i] = v  # constants and (k,) parameter-only entries broadcast
        out = out.transpose(1, 2, 0)
        phi = out[..., :r]
        jac = out[..., r : r + r * c].reshape(Bn, k, r, c) if jacobian else None
        gam = out[..., out.shape[-1] - r :] if gamma else None
        return phi, jac, gam


def _chain(exprs, q, qd, jacobian=True, gamma=True):
    """Φ, Φ_q and γ = −d²Φ(q + s q̇)/ds² at s = 0 (the velocity-quadratic term; Φ has no t) through the
    nodes of Φ: Φ is cut into its nodes (every sum, product, power and function application gets a name) and
    each node's partial derivatives with respect to its arguments are taken once. γ follows by second-order
    forward differentiation (each node's first and second derivatives along q̇ from its arguments'), Φ_q by
    reverse accumulation (each row's adjoint of every node it depends on, from the nodes that use it).

    Returns (replacements, phi, jac, gamma): the replacements define the nodes, their derivatives and adjoints
    in order; Φ (r expressions), Φ_q (r lists of len(q); empty when ``jacobian`` is false) and γ (r; empty when
    ``gamma`` is false) are expressions in them. The cost is linear in the size of Φ (times r for Φ_q), where
    differentiating the expanded Φ is not: sympy's Jacobian of the spatial types repeats every product rule
    through A(p) s', and the Hessian contraction −(Φ_q q̇)_q q̇ of the atan2 of a spatial rotation driver grows
    to some 10⁵ operations.
    """
    chain, memo, partials = [], {}, {}
    nodes, names1, names2 = sp.numbered_symbols("_c"), sp.numbered_symbols("_v"), sp.numbered_symbols("_a")
    first, second = dict(zip(q, qd)), {}  # first: every symbol that depends on q (nodes and coordinates)

    def derivatives(e, name):
        if e.is_Add:  # its arguments are nodes, coordinates or numbers
            args = [a for a in e.args if a in first]
            partials[name] = [(a, sp.Integer(1)) for a in args]
            if not gamma:
                return sp.Integer(len(args)), 0  # nonzero when the node depends on q
            return sp.Add(*[first[a] for a in args]), sp.Add(*[second[a] for a in args if a in second])
        product = e.is_Mul and all(a.is_Atom for a in e.args)  # distinct factors: ∂/∂a is the product of the rest
        args = [a for a in (e.args if product else e.free_symbols) if a in first]
        partials[name] = [(a, e.func(*[b for b in e.args if b != a]) if product else sp.diff(e, a)) for a in args]
        if not gamma:
            return sp.Integer(len(args)), 0  # nonzero when the node depends on q
        d1 = sp.Add(*[d * first[a] for a, d in partials[name]])
        d2 = sp.Add(*[d * second[a] for a, d in partials[name] if a in second])
        for m, a in enumerate(args):
            for b in args[m + 1 if product else m:]:
                h = sp.Mul(*[c for c in e.args if c != a and c != b]) if product else sp.diff(e, a, b)
                if h != 0:
                    d2 += (1 if a == b else 2) * h * first[a] * first[b]
        return d1, d2

    def visit(e):
        if e.is_Atom or e in memo:
            return memo.get(e, e)
        node = e.func(*[visit(a) for a in e.args]) if all(isinstance(a, sp.Expr) for a in e.args) else e
        name = memo[e] = next(nodes)
        chain.append((name, node))
        d1, d2 = derivatives(node, name)
        if d1 != 0:
            first[name] = next(names1)
            if gamma:
                chain.append((first[name], d1))
        if d2 != 0:
            second[name] = next(names2)
            chain.append((second[name], d2))
        return name

    phi = [visit(e) for e in exprs]
    gam = [-second.get(r, sp.Integer(0)) if isinstance(r, sp.Symbol) else sp.Integer(0) for r in phi] if gamma else []
    jac = []
    if jacobian:
        order = [name for name, _ in chain if name in partials]  # the nodes, each after its arguments
        adjoints = sp.numbered_symbols("_b")
        for r in phi:
            adj = {r: sp.Integer(1)} if r in first else {}
            for name in reversed(order):
                if name not in adj:
                    continue
                a_n = adj.pop(name)
                if not a_n.is_Atom:  # named once, used by every argument of the node
                    b = next(adjoints)
                    chain.append((b, a_n))
                    a_n = b
                for a, d in partials[name]:
                    adj[a] = adj.get(a, 0) + a_n * d
            jac.append([adj.get(s, sp.Integer(0)) for s in q])
    return chain, phi, jac, gam


def _printer():
    """lambdify's numpy printer, writing the terms of a sum in the order sympy stores them — a fixed order;
    sorting them for display, the default, took half the time of printing a kernel."""
    return NumPyPrinter({"fully_qualified_modules": False, "inline": True, "allow_unknown_functions": True,
                         "user_functions": {}, "order": "none"})


def _symbolize(value, symbols, numbers):
    """``value`` with every number replaced by a new symbol (appended to ``symbols``, its float value to
    ``numbers``); tuples, lists, dicts and 1-D arrays are followed, anything else is kept."""
    if isinstance(value, dict):
        return {k: _symbolize(v, symbols, numbers) for k, v in value.items()}
    if isinstance(value, (tuple, list)) or (isinstance(value, np.ndarray) and value.ndim == 1):
        return tuple(_symbolize(v, symbols, numbers) for v in value)
    if value is None or isinstance(value, (bool, str)):
        return value
    number = float(value)  # TypeError for a symbolic parameter: reported by the caller
    s = sp.Symbol(f"_k{len(symbols)}", real=True)
    symbols.append(s)
    numbers.append(number)
    return s


def _template(c):
    """(key, parameter values) of a bound constraint: its Φ with symbolic parameters, cached on it."""
    found = c.__dict__.get("_template")
    if found is not None:
        return found
    tmpl = copy.copy(c)
    tmpl.f = None  # the kernel evaluates g(q); the mechanism subtracts f(t)
    symbols, numbers = [], []
    for name in type(c).parameters:
        try:
            setattr(tmpl, name, _symbolize(getattr(c, name), symbols, numbers))
        except (TypeError, ValueError):
            raise ModelError(f"{c.describe()} has a symbolic parameter ({name} = {getattr(c, name)!r}): substitute "
                             "numbers before a numeric evaluation") from None
    nb, nc = len(c.bodies), len(c.COORDS)
    Q = [sp.Matrix([sp.Symbol(f"_q{b}_{j}", real=True) for j in range(nc)]) for b in range(nb)]
    exprs = [sp.Add(e) for e in tmpl.phi(Q, t_symbol)]  # an int row (0) as sympy; text is refused, not eval'd
    if len(exprs) != c.n_eq:
        raise ModelError(f"{c.describe()}: phi() returns {len(exprs)} rows, the type declares n_eq = {c.n_eq}")
    if any(e.has(t_symbol) for e in exprs):
        raise ModelError(f"{c.describe()}: phi() depends on t other than through the driver's f(t), which the "
                         "mechanism applies; write Φ = g(q) − f(t) with f given as `f`")
    extra = set().union(*(e.free_symbols for e in exprs)) - set(symbols) - {s for Qb in Q for s in Qb}
    if extra:
        raise ModelError(f"{c.describe()} has symbolic parameters ({', '.join(sorted(map(str, extra)))}): "
                         "substitute numbers before a numeric evaluation")
    key = (type(c), nb, tuple(exprs))
    found = key, np.array(numbers, dtype=float), [s for Qb in Q for s in Qb], symbols
    c.__dict__["_template"] = found
    return found


def compiled(c):
    """The kernel of constraint ``c`` compiled from its :meth:`phi`, and its parameters ``{"p": (P,)}``.

    Constraints of one type whose Φ differ only in their declared ``parameters`` share one kernel (see the
    module notes), so a mechanism evaluates all of them in one call.
    """
    key, values, q, symbols = _template(c)
    kernel = _COMPILED.get(key)
    if kernel is None:
        if len(_COMPILED) >= _CACHE_LIMIT:
            _COMPILED.clear()
        kernel = _COMPILED[key] = CompiledKernel(key[2], q, symbols, f"'{c.type_name}' ({type(c).__name__})")
    return kernel, {"p": values}


class StackedKernel:
    """The kernel of a composite joint: its parts' kernels, their rows stacked in order."""

    optional_jacobian = True

    def __init__(self, kernels):
        self.kernels = tuple(kernels)

    def __repr__(self):
        return f"<stacked kernel of {len(self.kernels)} parts>"

    def __call__(self, Q, P, Qd=None, jacobian=True):
        phis, jacs, gams = [], [], []
        for k, kernel in enumerate(self.kernels):
            Pk = P[k]
            if jacobian or not getattr(kernel, "optional_jacobian", False):
                phi, jac, gam = kernel(Q, Pk, Qd)
            else:
                phi, jac, gam = kernel(Q, Pk, Qd, jacobian=False)
            phis.append(phi)
            jacs.append(jac)
            gams.append(gam)
        jac = np.concatenate(jacs, axis=-2) if jacobian else None
        gam = None if Qd is None else np.concatenate(gams, axis=-1)
        return np.concatenate(phis, axis=-1), jac, gam


def stacked(numerics):
    """(kernel, parameters) of a composite from its parts' ``numeric()`` pairs; one kernel object per
    combination of part kernels, so every composite of a type is evaluated in one call.

    Parts whose kernels are built from row builders that can be combined (``kernel.builders`` and
    ``kernel.combine``, the spatial row algebra) are fused into one kernel over one parameter dict when their
    parameters agree on every name they share — one pass over the shared body quantities instead of one per
    part."""
    ks = tuple(k for k, _ in numerics)
    combine = getattr(ks[0], "combine", None)
    if combine is not None and all(getattr(k, "combine", None) is combine for k in ks):
        merged = {}
        for _, p in numerics:
            for name, v in p.items():
                if name in merged and not np.array_equal(merged[name], v):
                    break
                merged[name] = v
            else:
                continue
            break
        else:
            return combine(*(b for k in ks for b in k.builders)), merged
    kernel = _STACKED.get(ks)
    if kernel is None:
        kernel = _STACKED[ks] = StackedKernel(ks)
    return kernel, {k: p for k, (_, p) in enumerate(numerics)}
