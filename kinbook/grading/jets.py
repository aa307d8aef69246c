"""Numbers and derivatives of a sympy expression without deriving it symbolically: a tape of jets.

A checker needs the values of a student's symbolic answer at a few dozen sample instants, and — for error
carried forward and for the mistake catalogue — the Φ_q, ν and γ that follow from a symbolic Φ. Deriving
those with sympy (and compiling them with lambdify) takes from milliseconds to seconds and grows with the
size of the answer; here the expression is instead *compiled once into a tape* — a straight-line program
over its distinct sub-expressions, so common sub-expressions are computed once — and the tape is run with
numpy over all instants at once, carrying for every sub-expression (forward-mode differentiation):

* its value,
* its gradient with respect to the coordinates q (→ Φ_q),
* its first and second derivatives along the straight path (q + s q̇, t + s) (→ ν and γ):
  d/ds Φ = Φ_q q̇ + Φ_t, so ν = −Φ_t = Φ_q q̇ − d/ds Φ; and
  d²/ds² Φ = (Φ_q q̇)_q q̇ + 2Φ_qt q̇ + Φ_tt, so γ = −d²/ds² Φ (textbook §13.8).

The derivatives are exact (up to rounding), in time linear in the size of the tape, deterministic, and
without any code generation. Alternative differentiation *rules* produce the derivation mistakes of the
catalogue from the same tape (:data:`RULES`): cos and sin of a coordinate differentiated as constants (the
chain-rule term ∂(A s')/∂φ dropped) or as themselves (A where B belongs), or chosen coordinates frozen.

Supported: numbers, π and E, the symbols of q, q̇ and t, + − × ÷, powers, and the functions of the safe
reader (:mod:`kinbook.core.reader`): sin cos tan asin acos atan atan2 sqrt exp log Abs sign (plus sinh,
cosh, tanh). Anything else raises :class:`UnsupportedExpression`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

__all__ = ["Tape", "UnsupportedExpression", "RULES"]

RULES = ("exact", "chain_dropped", "A_for_B")
"""Differentiation rules: "exact"; "chain_dropped": d/dφ of cos φ and sin φ (of an argument that depends on
q) taken as 0; "A_for_B": d/dφ cos φ = cos φ and d/dφ sin φ = sin φ (A(φ) where B(φ) = dA/dφ belongs)."""


class UnsupportedExpression(ValueError):
    """A sympy node the tape cannot evaluate (a function outside the reader's list, a relation …)."""


class UnknownSymbol(UnsupportedExpression):
    """A symbol that is none of q, q̇, t (nor an alias of one)."""

    def __init__(self, name):
        super().__init__(f"unknown symbol {name}")
        self.name = name


_UNARY = {
    sp.sin: "sin", sp.cos: "cos", sp.tan: "tan", sp.asin: "asin", sp.acos: "acos", sp.atan: "atan",
    sp.exp: "exp", sp.log: "log", sp.Abs: "Abs", sp.sign: "sign", sp.sinh: "sinh", sp.cosh: "cosh",
    sp.tanh: "tanh",
}


class Tape:
    """Expressions compiled into a tape over the coordinates, velocities and time.

    Parameters
    ----------
    exprs : sequence of sympy expressions
        The entries to evaluate (a matrix is passed flattened).
    q, qd : sequence of sympy symbols
        Coordinates and velocities, in the order of the columns of ``Q`` and ``QD``.
    t : sympy symbol
    aliases : dict, optional
        Other names for those symbols (``{"phi_2": phi2, "x1": x1 …}``): a student's own symbols, matched by
        name.
    """

    def __init__(self, exprs, q, qd, t, aliases=None):
        self.n = len(q)
        self._slots = {}
        self.ops = []  # (kind, payload, depends-on-q)
        self._symbols = {s: ("q", k) for k, s in enumerate(q)}
        self._symbols.update({s: ("qd", k) for k, s in enumerate(qd)})
        self._symbols[t] = ("t", 0)
        self._aliases = {name: self._symbols[sym] for name, sym in (aliases or {}).items() if sym in self._symbols}
        self.outputs = [self._compile(e if isinstance(e, sp.Basic) else sp.Float(float(e))) for e in exprs]

    # ------------------------------------------------------------------------------------------- compiling
    def _add(self, key, op):
        self.ops.append(op)
        self._slots[key] = len(self.ops) - 1
        return len(self.ops) - 1

    def _dep(self, slots):
        ops = self.ops
        for s in slots:
            if ops[s][2]:
                return True
        return False

    def _compile(self, expr):
        """Slot of ``expr``; its sub-expressions are compiled first (iteratively: no recursion limit)."""
        if expr in self._slots:
            return self._slots[expr]
        stack = [(expr, False)]
        while stack:
            node, ready = stack.pop()
            if node in self._slots:
                continue
            if node.is_Atom or not node.args:
                self._leaf(node)
                continue
            if not ready:
                stack.append((node, True))
                for a in node.args:
                    if a not in self._slots:
                        stack.append((a, False))
                continue
            self._node(node)
        return self._slots[expr]

    def _leaf(self, node):
        if node.is_Symbol:
            if node in self._symbols:
                kind, k = self._symbols[node]
            elif node.name in self._aliases:
                kind, k = self._aliases[node.name]
            else:
                raise UnknownSymbol(node.name)
            return self._add(node, (kind, k, kind == "q"))
        if node.is_Number or node.is_NumberSymbol:
            try:
                value = float(node)
            except (TypeError, ValueError, OverflowError):
                value = np.nan  # zoo, nan
            return self._add(node, ("const", value, False))
        if node is sp.S.ImaginaryUnit:
            return self._add(node, ("const", np.nan, False))
        if node in (sp.S.Infinity, sp.S.NegativeInfinity, sp.S.ComplexInfinity, sp.S.NaN):
            return self._add(node, ("const", np.nan, False))
        raise UnsupportedExpression(f"{type(node).__name__} is not a number, a coordinate or t")

    def _node(self, node):
        args = list(map(self._slots.__getitem__, node.args))
        dep = self._dep(args)
        if node.is_Add:
            return self._add(node, ("add", args, dep))
        if node.is_Mul:
            return self._add(node, ("mul", args, dep))
        if node.is_Pow:
            base, exp = node.args
            if exp.is_Number:
                return self._add(node, ("powc", (args[0], float(exp)), dep))
            return self._add(node, ("pow", args, dep))
        if isinstance(node, sp.atan2):
            return self._add(node, ("atan2", args, dep))
        f = _UNARY.get(type(node))
        if f is not None and len(args) == 1:
            return self._add(node, ("fn", (f, args[0]), dep))
        if isinstance(node, sp.log) and len(args) == 2:  # log(x, b) is built by sympy as log(x)/log(b)
            return self._add(node, ("logb", args, dep))
        raise UnsupportedExpression(f"the function {type(node).__name__} is not supported")

    # ------------------------------------------------------------------------------------------- running
    def __call__(self, Q, QD=None, T=None, *, grad=False, order=0, rule="exact", frozen=(), dt=1.0,
                 velocities=None):
        """Run the tape at N instants.

        Parameters
        ----------
        Q : ndarray (N, n)
        QD : ndarray (N, n), optional
            Velocities: the values of the q̇ symbols, and the direction of the path derivatives.
        T : ndarray (N,), optional
        grad : bool
            Also compute the gradients with respect to q.
        order : {0, 1, 2}
            Path derivatives to compute (1: d/ds; 2: d/ds and d²/ds²).
        rule : one of :data:`RULES`
        frozen : collection of int
            Coordinates (indices into q) whose derivatives are taken as zero.
        dt : float
            Rate of t along the path (1: the path (q + s q̇, t + s); 0: time held fixed).
        velocities : ndarray (N, n), optional
            Values of the q̇ symbols when the path direction ``QD`` is something else.

        Returns
        -------
        dict with "value" (N, k), and "grad" (N, k, n), "d1" (N, k), "d2" (N, k) when asked.
        """
        Q = np.asarray(Q, float)
        N = Q.shape[0]
        QD = np.zeros_like(Q) if QD is None else np.asarray(QD, float)
        VEL = QD if velocities is None else np.asarray(velocities, float)
        T = np.zeros(N) if T is None else np.asarray(T, float)
        frozen = set(frozen)
        env = (N, Q, QD, VEL, T, frozen, grad, order, rule, dt)
        V, G, D1, D2 = [], [], [], []
        zero = np.zeros(N)
        with np.errstate(all="ignore"):
            for kind, payload, _dep in self.ops:
                v, g, a, b = self._op(kind, payload, V, G, D1, D2, env)
                if not grad:
                    g = None
                if order < 2:
                    b = None
                if order < 1:
                    a = None
                V.append(np.broadcast_to(v, (N,)) if np.ndim(v) == 0 else v)
                G.append(g)
                D1.append(a)
                D2.append(b)
        out = {"value": np.stack([V[s] for s in self.outputs], -1) if self.outputs else np.zeros((N, 0))}
        if grad:
            out["grad"] = np.stack([G[s] if G[s] is not None else np.zeros((N, self.n)) for s in self.outputs], 1)
        if order >= 1:
            out["d1"] = np.stack([D1[s] if D1[s] is not None else zero for s in self.outputs], -1)
        if order >= 2:
            out["d2"] = np.stack([D2[s] if D2[s] is not None else zero for s in self.outputs], -1)
        return out

    def _op(self, kind, payload, V, G, D1, D2, env):
        """One operation of the tape: its value, gradient and path derivatives (v, g, a, b; None where not
        computed) from those of the operations it uses."""
        N, Q, QD, VEL, T, frozen, grad, order, rule, dt = env
        v = g = a = b = None
        if kind == "const":
            v = np.full(N, payload)
        elif kind == "q":
            v = Q[:, payload]
            if payload not in frozen:
                if grad:
                    g = np.zeros((N, self.n))
                    g[:, payload] = 1.0
                if order:
                    a = QD[:, payload]
        elif kind == "qd":
            v = VEL[:, payload]
        elif kind == "t":
            v = T
            if order and dt:
                a = np.full(N, float(dt))
        elif kind == "add":
            v = 0
            for s in payload:  # a loop, not sum(generator): the tape's hot path (the same additions, in order)
                v = v + V[s]
            g, a, b = _sum_of(G, payload), _sum_of(D1, payload), _sum_of(D2, payload)
        elif kind == "mul":
            s0 = payload[0]
            v, g, a, b = V[s0], G[s0], D1[s0], D2[s0]
            for s in payload[1:]:
                v, g, a, b = _mul((v, g, a, b), (V[s], G[s], D1[s], D2[s]), order)
        elif kind == "powc":
            s, p = payload
            u = V[s]
            v = _power(u, p)
            if p != 0:
                f1 = p * _power(u, p - 1)
                f2 = p * (p - 1) * _power(u, p - 2) if order > 1 else None
                g, a, b = _chain(f1, f2, G[s], D1[s], D2[s], order)
        elif kind == "pow":  # u^w = exp(w log u)
            su, sw = payload
            ju = _unary_jet("log", V[su], G[su], D1[su], D2[su], order)
            v, g, a, b = _mul(ju, (V[sw], G[sw], D1[sw], D2[sw]), order)
            v, g, a, b = _unary_jet("exp", v, g, a, b, order)
        elif kind == "fn":
            name, s = payload
            u = V[s]
            if rule != "exact" and name in ("sin", "cos") and self.ops[s][2]:
                v, g, a, b = _trig_rule(name, u, G[s], D1[s], D2[s], order, rule)
            else:
                v, g, a, b = _unary_jet(name, u, G[s], D1[s], D2[s], order)
        elif kind == "atan2":
            sy, sx = payload
            v, g, a, b = _atan2((V[sy], G[sy], D1[sy], D2[sy]), (V[sx], G[sx], D1[sx], D2[sx]), order)
        elif kind == "logb":
            sx, sb = payload
            num = _unary_jet("log", V[sx], G[sx], D1[sx], D2[sx], order)
            den = _unary_jet("log", V[sb], G[sb], D1[sb], D2[sb], order)
            v, g, a, b = _mul(num, _unary_jet("inv", *den, order), order)
        return v, g, a, b

    def derived(self, Q, QD, T, *, rule="exact", frozen=(), parts=False):
        """Φ, Φ_q, ν and γ of the tape's expressions read as a constraint vector Φ(q, t).

        With ``parts``, also the three terms of γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt: "quad", "qt" and "tt".

        Returns
        -------
        dict with "Phi" (N, k), "Phi_q" (N, k, n), "nu" (N, k), "gamma" (N, k).
        """
        r = self(Q, QD, T, grad=True, order=2, rule=rule, frozen=frozen)
        zero = np.zeros_like(np.asarray(Q, float))
        nu = -self(Q, zero, T, order=1, rule=rule, frozen=frozen, velocities=QD)["d1"]  # −Φ_t, exactly 0 if no t
        out = {"Phi": r["value"], "Phi_q": r["grad"], "nu": nu, "gamma": -r["d2"]}
        if parts:
            quad = -self(Q, QD, T, order=2, rule=rule, frozen=frozen, dt=0.0)["d2"]
            tt = -self(Q, zero, T, order=2, rule=rule, frozen=frozen, velocities=QD)["d2"]
            out.update(quad=quad, tt=tt, qt=out["gamma"] - quad - tt)
        return out


# ================================================================================================ jet algebra
def _sum(parts):
    """The sum of the parts that are not None, left to right (None when all are)."""
    out = None
    for p in parts:
        if p is not None:
            out = p if out is None else out + p
    return out


def _sum_of(values, slots):
    """:func:`_sum` of ``values[s]`` over the slots."""
    out = None
    for s in slots:
        p = values[s]
        if p is not None:
            out = p if out is None else out + p
    return out


def _scale(f, x):
    """f · x, with x None meaning zero; f (N,) broadcast over x (N,) or (N, n)."""
    if x is None:
        return None
    return (f[:, None] if x.ndim == 2 else f) * x


def _mul(x, y, order):
    v1, g1, a1, b1 = x
    v2, g2, a2, b2 = y
    v = v1 * v2
    g = _sum([_scale(v2, g1), _scale(v1, g2)])
    a = _sum([_scale(v2, a1), _scale(v1, a2)])
    b = None
    if order > 1:
        cross = None if a1 is None or a2 is None else 2 * a1 * a2
        b = _sum([_scale(v2, b1), _scale(v1, b2), cross])
    return v, g, a, b


def _chain(f1, f2, g, a, b, order):
    """Derivatives of f(u) from f'(u), f''(u) and those of u."""
    gg = _scale(f1, g)
    aa = _scale(f1, a)
    bb = None
    if order > 1:
        bb = _sum([None if a is None else f2 * a * a, _scale(f1, b)])
    return gg, aa, bb


def _power(u, p):
    if p == int(p):
        return np.power(u, int(p)) if p >= 0 else 1.0 / np.power(u, -int(p))
    return np.power(u, p)  # NaN for a negative base: not a real number


def _unary_jet(name, u, g, a, b, order):
    if name == "sin":
        v, f1, f2 = np.sin(u), np.cos(u), -np.sin(u)
    elif name == "cos":
        v, f1, f2 = np.cos(u), -np.sin(u), -np.cos(u)
    elif name == "tan":
        v = np.tan(u)
        f1 = 1 + v * v
        f2 = 2 * v * f1
    elif name == "exp":
        v = f1 = f2 = np.exp(u)
    elif name == "log":
        v, f1, f2 = np.log(u), 1 / u, -1 / (u * u)
    elif name == "inv":
        v, f1, f2 = 1 / u, -1 / (u * u), 2 / (u * u * u)
    elif name == "asin":
        v, f1 = np.arcsin(u), 1 / np.sqrt(1 - u * u)
        f2 = u * f1**3
    elif name == "acos":
        v, f1 = np.arccos(u), -1 / np.sqrt(1 - u * u)
        f2 = u * f1**3
    elif name == "atan":
        v, f1 = np.arctan(u), 1 / (1 + u * u)
        f2 = -2 * u * f1 * f1
    elif name == "sinh":
        v, f1, f2 = np.sinh(u), np.cosh(u), np.sinh(u)
    elif name == "cosh":
        v, f1, f2 = np.cosh(u), np.sinh(u), np.cosh(u)
    elif name == "tanh":
        v = np.tanh(u)
        f1 = 1 - v * v
        f2 = -2 * v * f1
    elif name == "Abs":
        v, f1, f2 = np.abs(u), np.sign(u), np.zeros_like(u)
    elif name == "sign":
        v, f1, f2 = np.sign(u), np.zeros_like(u), np.zeros_like(u)
    else:  # pragma: no cover - the compiler only emits the names above
        raise UnsupportedExpression(name)
    return (v, *_chain(f1, f2, g, a, b, order))


def _trig_rule(name, u, g, a, b, order, rule):
    v = np.sin(u) if name == "sin" else np.cos(u)
    if rule == "chain_dropped":
        return v, None, None, None
    # "A_for_B": the function is its own derivative
    return (v, *_chain(v, v, g, a, b, order))


def _atan2(y, x, order):
    vy, gy, ay, by = y
    vx, gx, ax, bx = x
    v = np.arctan2(vy, vx)
    r2 = vx * vx + vy * vy
    g = _sum([_scale(vx / r2, gy), _scale(-vy / r2, gx)])
    a = _sum([_scale(vx / r2, ay), _scale(-vy / r2, ax)])
    b = None
    if order > 1:
        ay0 = np.zeros_like(vx) if ay is None else ay
        ax0 = np.zeros_like(vx) if ax is None else ax
        by0 = np.zeros_like(vx) if by is None else by
        bx0 = np.zeros_like(vx) if bx is None else bx
        num = vx * ay0 - vy * ax0
        b = (vx * by0 - vy * bx0) / r2 - num * (2 * vx * ax0 + 2 * vy * ay0) / (r2 * r2)
    return v, g, a, b
