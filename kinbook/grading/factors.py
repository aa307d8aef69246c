"""The real zeros of an answer row's factors, over the whole configuration space (part of the fourth stage,
:mod:`~kinbook.grading.match`): where a row accepted as an equivalent formulation may vanish although its
constraint does not.

A Φ row f(q, t)·Φ_k has the zero set of Φ_k *and* that of f. Searching near the samples finds the zeros of
cos φ2 but not those of (x2 − 100), (y3² − 49), (t − 20) or (φ2 − 40). So every factor of the row (sympy's
``factor_list``) is examined on its own, over the whole domain — the bodies free, every coordinate on the real
line, each Euler parameter in [−1, 1], and t ≥ 0:

* a factor that is a polynomial in one coordinate (or in t) is **solved**: its real roots (numpy's companion
  matrix of its coefficients), those inside the domain;
* any other factor is searched along lines through a few of the target's generic samples, one coordinate (or
  t) moving at a time, over a fixed grid that spans 10⁻³ … 10⁴ on both sides (t: 0 … 10⁴) — each sign change
  is then bisected to the last digit, and each near-touch of zero (a minimum of \\|f\\| that does not change
  sign, as cos φ − 1) refined by golden sections and kept when \\|f\\| is at rounding level there.

The configurations returned are starts: :mod:`~kinbook.grading.equivalence` then holds the row's factor at
zero while the constraint's other answer rows are solved (seeded Newton steps,
:func:`kinbook.grading.sample.zeros`), and calls the factor vanishing where the reference rows it stands for
do not — for no placement the same up to a turn of 2π (:func:`kinbook.grading.sample.placements`).

Bounded, never timed: a row is factored only when it has at most :data:`FACTOR_WORK` operations (sympy's
``count_ops``); a larger row — or a function ``f(q, t)`` with no expression — is searched whole along the same
lines (a deterministic numeric search over the whole domain, not a solve). A polynomial factor is solved only up
to degree :data:`MAX_DEGREE`; above, it is searched. Every search is a fixed number of evaluations.
"""

from __future__ import annotations

import numpy as np

__all__ = ["starts", "FACTOR_WORK", "MAX_DEGREE", "GRID", "BASES"]

FACTOR_WORK = 300
"""Rows with more operations than this are not factored by sympy: they are searched whole."""
MAX_DEGREE = 24
"""Polynomial factors of a higher degree are searched, not solved."""
BASES = 3
"""Generic samples the lines go through."""
_SIDE = np.geomspace(1e-3, 1e4, 160)
GRID = np.concatenate([-_SIDE[::-1], [0.0], _SIDE])
"""Offsets along a line (translations and angles): both sides, 10⁻³ … 10⁴."""
_T_GRID = np.concatenate([[0.0], np.geomspace(1e-3, 1e4, len(GRID) - 1)])
_E_GRID = np.linspace(-1.0, 1.0, len(GRID))
_BISECTIONS = 56
_GOLDEN = 48
_PER_LINE = 2


def _factors(target, answer, k):
    """The non-constant factors of row k (sympy expressions in the mechanism's symbols), or None when the row
    is not factored (a function, or a row above :data:`FACTOR_WORK`)."""
    if answer.kind != "symbolic":
        return None
    expr = answer.entry(target, k)
    if expr is None:
        return None
    import sympy as sp  # import time: sympy only when needed

    if sp.count_ops(expr) > FACTOR_WORK:
        return None
    try:
        _, parts = sp.factor_list(sp.together(expr))
    except (sp.PolynomialError, NotImplementedError, ValueError, TypeError):  # pragma: no cover - searched whole
        return None
    return [f for f, power in parts if power > 0 and f.free_symbols]


def _variables(target, expr_symbols):
    """Indices of the coordinates (and -1 for t) an expression depends on."""
    mech = target.mech
    out = [i for i, s in enumerate(mech.q) if s in expr_symbols]
    if mech.t in expr_symbols:
        out.append(-1)
    return out


def _line(target, base_q, base_t, v):
    """The grid of a line through (base_q, base_t) along variable v: (Q (G, n), T (G,), values of v (G,))."""
    name = "t" if v < 0 else target.names[v]
    if v < 0:
        values = _T_GRID
    elif name.startswith("e") and target.kind == "spatial":
        values = _E_GRID
    else:
        values = base_q[v] + GRID
    Q = np.repeat(base_q[None], len(values), axis=0)
    T = np.full(len(values), base_t)
    if v < 0:
        T = values.copy()
    else:
        Q[:, v] = values
    return Q, T, values


def _put(Q, T, v, x):
    """Set variable v (an array of indices, -1 for t) to x in the configurations (Q, T), row by row."""
    v, x = np.broadcast_to(v, np.shape(x)), np.asarray(x, float)
    Q, T = np.atleast_2d(Q), np.atleast_1d(T)
    rows = np.arange(len(x))
    on_t = v < 0
    T[rows[on_t]] = x[on_t]
    Q[rows[~on_t], v[~on_t]] = x[~on_t]


def _roots_on_lines(F, lines):
    """Zeros of F along lines [(Q (G, n), T (G,), v, values (G,), start)], all lines in one batch: sign changes
    bisected, near-touches (a local minimum of |f| below 1 % of the line's largest value) refined by golden
    sections and kept at rounding level. Returns, per line, at most :data:`_PER_LINE` zeros (nearest the line's
    start first)."""
    if not lines:
        return []
    G = len(lines[0][3])
    Q = np.concatenate([ln[0] for ln in lines])
    T = np.concatenate([ln[1] for ln in lines])
    V = np.array([ln[2] for ln in lines])
    X = np.stack([ln[3] for ln in lines])
    with np.errstate(all="ignore"):
        f = F(Q, T).reshape(len(lines), G)
    ok = np.isfinite(f)
    scale = np.max(np.where(ok, np.abs(f), 0.0), axis=1)
    found = [[] for _ in lines]
    # an exact zero counts where its neighbours are not zero too (exp(x2) underflows to 0 far out: no root)
    z = ok & (f == 0.0)
    pad = np.ones((len(lines), 1), bool)
    isolated = z & ~np.concatenate([pad, z[:, :-1]], axis=1) & ~np.concatenate([z[:, 1:], pad], axis=1)
    for li, i in zip(*np.nonzero(isolated)):
        found[li].append(float(X[li, i]))
    li, i = np.nonzero(ok[:, :-1] & ok[:, 1:] & (np.sign(f[:, :-1]) * np.sign(f[:, 1:]) < 0))
    if li.size:
        lo, hi, flo = X[li, i].copy(), X[li, i + 1].copy(), f[li, i].copy()
        q, t = Q[li * G + i].copy(), T[li * G + i].copy()
        with np.errstate(all="ignore"):
            for _ in range(_BISECTIONS):
                mid = 0.5 * (lo + hi)
                _put(q, t, V[li], mid)
                fm = F(q, t)
                left = np.sign(fm) == np.sign(flo)
                lo, flo, hi = np.where(left, mid, lo), np.where(left, fm, flo), np.where(left, hi, mid)
        for a, x in zip(li, 0.5 * (lo + hi)):
            found[a].append(float(x))
    af = np.where(ok, np.abs(f), np.inf)
    mins = (af[:, 1:-1] <= af[:, :-2]) & (af[:, 1:-1] <= af[:, 2:]) & (af[:, 1:-1] > 0) & \
        (af[:, 1:-1] < 1e-2 * scale[:, None])
    li, i = np.nonzero(mins)
    i = i + 1
    if li.size:
        lo, hi = X[li, i - 1].copy(), X[li, i + 1].copy()
        g = 0.5 * (np.sqrt(5.0) - 1.0)
        q, t = Q[np.repeat(li * G + i, 2)].copy(), T[np.repeat(li * G + i, 2)].copy()
        vv = np.repeat(V[li], 2)
        with np.errstate(all="ignore"):
            for _ in range(_GOLDEN):
                x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
                _put(q, t, vv, np.stack([x1, x2], axis=1).reshape(-1))
                ff = np.abs(F(q, t)).reshape(-1, 2)
                left = ff[:, 0] <= ff[:, 1]
                hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
            x = 0.5 * (lo + hi)
            _put(q[::2], t[::2], V[li], x)
            fx = np.abs(F(q[::2], t[::2]))
        for a, xx, fxx in zip(li, x, fx):
            if fxx <= 1e-10 * scale[a]:
                found[a].append(float(xx))
    out = []
    for line, xs in zip(lines, found):
        base = line[4] if len(line) > 4 else 0.0
        out.append(sorted(xs, key=lambda x: abs(x - base))[:_PER_LINE])
    return out


def _polynomial_roots(f, symbol):
    """Real roots of f as a polynomial in ``symbol`` alone, or None when it is not one (or its degree is
    above :data:`MAX_DEGREE`)."""
    import sympy as sp  # import time: sympy only when needed

    try:
        p = sp.Poly(f, symbol)
    except sp.PolynomialError:
        return None
    if p.degree() < 1 or p.degree() > MAX_DEGREE or any(not c.is_number for c in p.all_coeffs()):
        return None
    c = np.array([complex(x) for x in p.all_coeffs()])
    if not np.all(np.isfinite(c)) or np.any(np.abs(c.imag) > 0):
        return None
    r = np.roots(c.real)
    return sorted(float(x.real) for x in r if abs(x.imag) <= 1e-9 * max(1.0, abs(x)))


def _in_domain(target, v, x):
    if v < 0:
        return x >= 0.0
    if target.kind == "spatial" and target.names[v].startswith("e"):
        return abs(x) <= 1.0
    return True


def starts(target, answer, k, cols=None, bases=BASES):
    """Configurations where a factor of answer row ``k`` vanishes, spread over the whole domain (see the
    module): ``(Q (K, n), T (K,))``, deterministic, at most a few per factor, line and generic sample. ``cols``:
    the coordinates a row searched whole is moved along (its constraint's bodies'; default all)."""
    s = target.samples("generic")
    B = min(bases, s.N)
    parts = _factors(target, answer, k)
    out_Q, out_T = [], []
    if parts is None:  # searched whole: the row itself along each coordinate of the constraint's bodies and t
        def F(Q, T):
            return answer.jet(target, Q, T)[0][:, k]

        variables = list(range(target.n) if cols is None else cols) + ([-1] if target.time_dependent else [])
        _search(target, F, s, B, variables, out_Q, out_T)
        return _stack(target, out_Q, out_T)
    import sympy as sp  # import time: sympy only when needed

    mech = target.mech
    for f in parts:
        variables = _variables(target, f.free_symbols)
        if not variables:
            continue
        if len(variables) == 1:
            v = variables[0]
            roots = _polynomial_roots(f, mech.t if v < 0 else mech.q[v])
            if roots is not None:
                roots = [x for x in roots if _in_domain(target, v, x)]
                for b in range(B):
                    for x in roots[:_PER_LINE]:
                        q, t = s.Q[b].copy(), np.array([s.T[b]], float)
                        _put(q, t, v, np.array([x]))
                        out_Q.append(q)
                        out_T.append(float(t[0]))
                continue
        tape = target.tape([f], key=("factor", sp.srepr(f)))

        def F(Q, T, tape=tape):
            return tape(Q, None, T)["value"][:, 0]

        _search(target, F, s, B, variables, out_Q, out_T)
    return _stack(target, out_Q, out_T)


def _search(target, F, s, B, variables, out_Q, out_T):
    """The lines through the first B samples of ``s`` along each variable, searched in one batch; the zeros inside
    the domain appended to (out_Q, out_T)."""
    keys, lines = [], []
    for b in range(B):
        for v in variables:
            keys.append((b, v))
            Q, T, values = _line(target, s.Q[b], s.T[b], v)
            lines.append((Q, T, v, values, s.T[b] if v < 0 else s.Q[b][v]))
    for (b, v), xs in zip(keys, _roots_on_lines(F, lines)):
        for x in xs:
            if _in_domain(target, v, x):
                q, t = s.Q[b].copy(), np.array([s.T[b]], float)
                _put(q, t, v, np.array([x]))
                out_Q.append(q)
                out_T.append(float(t[0]))


def _stack(target, Q, T):
    if not Q:
        return np.zeros((0, target.n)), np.zeros(0)
    return np.array(Q, float), np.array(T, float)
