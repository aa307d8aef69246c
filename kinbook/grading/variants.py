"""Wrong answers generated from the reference: how the mistake catalogue is detected.

Two families:

* :func:`structural` re-writes one constraint's Φ the way a student gets it wrong — bodies i and j swapped,
  local points swapped, Aᵀ for A, A omitted (local vectors), degrees for radians, a square dropped, a sign
  flipped. Φ_q, ν and γ of these variants are derived by :func:`kinbook.symbolic.derive`, so a student who
  carried such a Φ through the derivation is recognized too.
* :func:`derived` takes any Φ (kinbook's, or the student's own for error carried forward) and derives Φ_q, ν
  or γ the way a student gets *the derivation* wrong — the chain-rule term ∂(A s')/∂φ dropped, A where B
  belongs, ν = +Φ_t, γ with the wrong sign or without 2Φ_qt q̇ or Φ_tt, φ̇ without its square.

A checker compares the student's answer with each variant numerically; a code is reported only when the
answer matches the variant (and the variant differs from the reference).
"""

from __future__ import annotations

import copy
import itertools

import sympy as sp

from ..planar.transforms import A as A_matrix
from ..symbolic import derive

__all__ = ["structural", "derived", "term_variants"]


# --------------------------------------------------------------------------------------------- structural
def structural(mech, c):
    """Wrong versions of constraint ``c``'s Φ rows.

    Returns
    -------
    list of (code, sympy.Matrix of shape (c.n_eq, 1))
    """
    Q = [mech.body_symbols(b.name) for b in c.bodies]
    out = []

    def add(code, rows):
        try:
            out.append((code, sp.Matrix(list(rows))))
        except Exception:  # a variant that cannot be built for this constraint is simply skipped
            pass

    tn = c.type_name
    if tn in ("revolute", "revolute-revolute") and hasattr(c, "s_i"):
        cc = copy.copy(c)
        cc.s_i, cc.s_j = c.s_j, c.s_i
        add("swapped_points", cc.phi(Q))
    if tn in ("translational", "revolute-translational", "gear", "distance-driver", "rack-pinion"):
        swapped = [Q[1], Q[0]] + Q[2:]
        add("swapped_bodies", c.phi(swapped))
    if tn in ("revolute", "translational", "revolute-revolute", "revolute-translational", "distance-driver"):
        cc = copy.copy(c)
        cc._r = lambda Qb, s: sp.Matrix(Qb[:2]) + A_matrix(Qb[2]).T * sp.Matrix(s)
        add("A_transposed", cc.phi(Q))
        cc = copy.copy(c)
        cc._r = lambda Qb, s: sp.Matrix(Qb[:2]) + sp.Matrix(s)
        add("local_vector", cc.phi(Q))
    if tn == "spherical" and hasattr(c, "P_i"):
        from ..spatial.rotations import A_from_p

        def point(Qb, s, transpose=False, local=False):
            A = A_from_p(list(Qb[3:7]))
            A = A.T if transpose else A
            s = sp.Matrix([sp.nsimplify(float(v)) for v in s])
            return sp.Matrix(Qb[:3]) + (s if local else A * s)

        add("swapped_points", point(Q[0], c.P_j) - point(Q[1], c.P_i))
        add("A_transposed", point(Q[0], c.P_i, transpose=True) - point(Q[1], c.P_j, transpose=True))
        add("local_vector", point(Q[0], c.P_i, local=True) - point(Q[1], c.P_j, local=True))
    if tn == "revolute-revolute":
        d = c._r(Q[0], c.s_i) - c._r(Q[1], c.s_j)
        add("missing_square", [d[0] ** 2 + d[1] ** 2 - c.length])
        add("missing_square", [d[0] + d[1] ** 2 - c.length**2])
        add("missing_square", [d[0] ** 2 + d[1] - c.length**2])
    deg = 180 / sp.pi
    if tn == "translational" and c.phi0 != 0:
        cc = copy.copy(c)
        cc.phi0 = c.phi0 * deg
        add("degrees", cc.phi(Q))
    if c.kind == "driver" and getattr(c, "coordinate", "phi") == "phi" and c.f is not None and tn != "distance-driver":
        t = mech.t
        f = c.f
        f0 = f.subs(t, 0)
        for g in (f * deg, f - f0 + f0 * deg):
            cc = copy.copy(c)
            cc.f = sp.expand(g)
            add("degrees", cc.phi(Q))
    if tn in ("ground", "simple"):
        values = c.value if tn == "ground" else None
        if tn == "ground" and values[2] != 0:
            cc = copy.copy(c)
            cc.value = (values[0], values[1], values[2] * deg)
            add("degrees", cc.phi(Q))
        if tn == "simple" and c.coordinate == "phi" and c.value != 0:
            cc = copy.copy(c)
            cc.value = c.value * deg
            add("degrees", cc.phi(Q))
    if tn == "gear":
        pi0, pj0, pk0 = c.phi0
        dk = Q[2][2] - pk0
        add("sign_flip", [((Q[0][2] - pi0) - dk) * c.radius_i - ((Q[1][2] - pj0) - dk) * c.radius_j])
    if tn == "rack-pinion":
        e = (Q[0][2] - c.initial["phi_i"]) * c.radius + (Q[1][0] - c.initial["x_j"])
        if c.sliding:
            e = (Q[0][0] - c.initial["x_i"]) + e
        add("sign_flip", [e])
    return out


# --------------------------------------------------------------------------------------------- derived
def _trig(mode):
    """cos and sin look-alikes whose derivatives follow ``mode``: "zero" (chain rule dropped) or "A"
    (the derivative of A taken as A itself)."""

    class C(sp.Function):
        nargs = 1

        def fdiff(self, argindex=1):
            return sp.S.Zero if mode == "zero" else C(self.args[0])

    class S(sp.Function):
        nargs = 1

        def fdiff(self, argindex=1):
            return sp.S.Zero if mode == "zero" else S(self.args[0])

    C.__name__, S.__name__ = f"_C_{mode}", f"_S_{mode}"
    return C, S


_TRIG = {mode: _trig(mode) for mode in ("zero", "A")}


def _wrapped(Phi, q, mode):
    C, S = _TRIG[mode]
    qs = set(q)
    return Phi.replace(
        lambda e: isinstance(e, (sp.cos, sp.sin)) and bool(e.args[0].free_symbols & qs),
        lambda e: (C if isinstance(e, sp.cos) else S)(e.args[0]),
    )


def _unwrapped(M, mode):
    C, S = _TRIG[mode]
    return M.replace(C, sp.cos).replace(S, sp.sin)


def derived(Phi, q, qd, t, quantity):
    """Wrong derivations of ``quantity`` ("Phi_q", "nu" or "gamma") from a symbolic Φ.

    Returns
    -------
    list of (code, sympy.Matrix) with the shape of the quantity.
    """
    Phi = sp.Matrix(Phi)
    q, qd = sp.Matrix(q), sp.Matrix(qd)
    out = []
    if quantity == "Phi_q":
        for code, mode in (("missing_chain_rule", "zero"), ("A_for_B", "A")):
            out.append((code, _unwrapped(_wrapped(Phi, q, mode).jacobian(q), mode)))
    elif quantity == "nu":
        Phi_t = Phi.diff(t)
        out.append(("nu_sign", Phi_t))
        out.append(("nu_missing", sp.zeros(*Phi_t.shape)))
    elif quantity == "gamma":
        Phi_q = Phi.jacobian(q)
        Phi_t = Phi.diff(t)
        quad = -(Phi_q * qd).jacobian(q) * qd
        qt = -2 * Phi_q.diff(t) * qd
        tt = -Phi_t.diff(t)
        gamma = quad + qt + tt
        out.append(("gamma_sign", -gamma))
        out.append(("missing_qt_term", quad + tt))
        out.append(("missing_tt_term", quad + qt))
        out.append(("gamma_sign", -quad + qt + tt))  # the book's +(Φ_q q̇)_q q̇ with the driver terms right
        qds = set(qd)
        unsquared = gamma.replace(lambda e: e.is_Pow and e.exp == 2 and e.base in qds, lambda e: e.base)
        out.append(("missing_square", unsquared))
        zero = _wrapped(Phi, q, "zero")
        d = derive(zero, q, qd, t)
        out.append(("missing_chain_rule", _unwrapped(d.gamma, "zero")))
    return out


# --------------------------------------------------------------------------------------------- terms
def term_variants(expr, max_single=16, max_double=8):
    """Sign flips and dropped terms of one expression.

    Returns
    -------
    list of (code, expression): single and (for few terms) double sign flips as "sign_flip", single
    dropped terms as "missing_term".
    """
    terms = sp.Add.make_args(sp.expand(expr))
    k = len(terms)
    out = []
    if k < 2 or k > max_single:
        return out
    total = sp.Add(*terms)
    for a in range(k):
        out.append(("sign_flip", total - 2 * terms[a]))
    if k <= max_double:
        for a, b in itertools.combinations(range(k), 2):
            out.append(("sign_flip", total - 2 * terms[a] - 2 * terms[b]))
    for a in range(k):
        out.append(("missing_term", total - terms[a]))
    return out
