"""More of the catalogue's generated mistakes (:mod:`kinbook.grading.mistakes`), each made from kinbook's own
constraint — its rows, or its reference values at the samples — the way a student gets it wrong:

* :func:`book_A_rows` — a spatial joint's Φ written with the matrix §14.3 prints for A(p) (erratum 14.3-A-of-p);
* :func:`cross_term_flipped` — γ with the sign of its cross terms (the products of body i's and body j's
  velocities, 2ṡ_iᵀṡ_j …) changed;
* :func:`n2_without_dC` — the Jacobian of Φ^(n2,1) = s_iᵀd without dᵀC_i, the derivative of s_i (s_i treated as
  constant, only d differentiated);
* :func:`n1_own_arm` — the Jacobian of Φ^(n1,1) = s_iᵀs_j with each body's own arm in its p columns;
* :func:`length_factors` — the lengths of a constraint's own geometry a row may be multiplied by.
"""

from __future__ import annotations

import copy

import numpy as np

from ..spatial.rotations import dAa_dp
from ._i18n import Msg
from .misprints import book_A_of_p
from .quantities import for_quantities

__all__ = ["book_A_rows", "cross_term_flipped", "n2_without_dC", "n1_own_arm", "length_factors"]


def book_A_rows(c, Q, t):
    """The rows of spatial constraint ``c`` at body symbols ``Q`` with every A(p) replaced by the book's printed
    matrix (no factor 2, symmetric): what a student who copies §14.3's A(p) into a joint writes."""
    printed = copy.copy(c)
    printed.rotation = lambda Qb: book_A_of_p(list(Qb[3:7]))  # the constraint's rotation hook, on a copy
    return list(printed.phi(Q, t))


def cross_term_flipped(tape, row, s, expected, factor=1.0, bodies=()):
    """γ of ``tape``'s output ``row`` (expected values (N, 1)) with the sign of its cross terms changed: the
    part of −(Φ_q q̇)_q q̇ that multiplies a velocity of one body by a velocity of another. ``bodies`` are the
    constraint's bodies' columns (one list per body). None when there is no cross term."""
    if len(bodies) < 2:
        return None
    whole = -tape(s.Q, s.QD, s.T, order=2, dt=0.0)["d2"][:, row]
    alone = 0.0
    for cols in bodies:
        QD = np.zeros_like(s.QD)
        QD[:, cols] = s.QD[:, cols]
        alone = alone - tape(s.Q, QD, s.T, order=2, dt=0.0, velocities=s.QD)["d2"][:, row]
    cross = factor * (whole - alone)
    if np.max(np.abs(cross)) <= 1e-9 * max(1.0, float(np.max(np.abs(expected)))):
        return None
    return expected - 2 * cross[:, None]


@for_quantities("Phi_q")
def n2_without_dC(target, c, s, ref, quantity):
    """Φ_q of Φ^(n2,1) = s_iᵀd with the derivative of s_i = A_i a'_i left out of its p_i columns: the row minus
    dᵀ ∂(A_i a'_i)/∂p_i (Table 14.1's dᵀC_i)."""
    mech = target.mech
    ci, cj = ([7 * (b.number - 1) + k for k in range(7)] for b in c.bodies)
    pi = s.Q[:, ci[3:]]
    d = mech.point_position(s.Q, c.bodies[1].name, np.asarray(c.P_j, float)) - \
        mech.point_position(s.Q, c.bodies[0].name, np.asarray(c.P_i, float))
    dC = np.einsum("ni,nij->nj", d, dAa_dp(pi, np.asarray(c.a_i, float)))
    row = ref["Phi_q"][:, target.block(c)[0]].copy()
    row[:, ci[3:]] -= dC
    return [(0, row, "missing_chain_rule", "dC")]


@for_quantities("Phi_q")
def n1_own_arm(target, c, s, ref, quantity):
    """Φ_q of Φ^(n1,1) = s_iᵀs_j with each body's own arm in its p columns: s_iᵀC_i for s_jᵀC_i, s_jᵀC_j for
    s_iᵀC_j (C_k = ∂(A_k a'_k)/∂p_k, Table 14.1) — the product rule applied with the wrong factor kept."""

    ci, cj = ([7 * (b.number - 1) + k for k in range(7)] for b in c.bodies)
    out = ref["Phi_q"][:, target.block(c)[0]].copy()
    for cols, a in ((ci, c.a_i), (cj, c.a_j)):
        p = s.Q[:, cols[3:]]
        C = dAa_dp(p, np.asarray(a, float))
        own = 0.5 * np.einsum("nij,nj->ni", C, p)  # A a = ½ C p: A(p) a is quadratic in p
        out[:, cols[3:]] = np.einsum("ni,nij->nj", own, C)
    return [(0, out, "own_arm", None)]


def length_factors(c, spec, limit=12):
    """The lengths of constraint ``c``'s own geometry a student may multiply a row by: the length attributes
    of its class (the r-r joint's l), the distances between the named points of each of its bodies (a crank's
    O_A–A) and each named point's distance from its body's origin, then the constraint's own local points
    (their distances on one body, their norms) — ``[(value, detail Msg)]`` named in the mechanism's notation,
    without 0, 1 and repeated values, at most ``limit``. None for a constraint without points or lengths. ``spec``:
    the constraint's :class:`~kinbook.grading.mistakes.Spec`."""
    out = []

    def add(value, detail):
        try:
            value = float(value)
        except (TypeError, ValueError):
            return
        if not np.isfinite(value) or value <= 1e-9 or abs(value - 1.0) <= 1e-9:
            return
        if any(abs(value - v) <= 1e-9 * value for v, _ in out):
            return
        out.append((value, detail))

    if not (spec.points or spec.vectors or spec.lengths):
        return out  # a row of angles (a driver, a gear, a normalization): no length of it is plausible
    names = [b.name for b in getattr(c, "bodies", ())]
    for attr in spec.lengths:
        add(getattr(c, attr, None), Msg("d.factor_joint_length", name=attr))
    for body in getattr(c, "bodies", ()):
        points = list((getattr(body, "points", None) or {}).items())
        for k, (a, pa) in enumerate(points):
            for b, pb in points[k + 1:]:
                add(np.linalg.norm(np.asarray(pa, float) - np.asarray(pb, float)),
                    Msg("d.factor_length", a=a, b=b, body=body.name))
        for a, pa in points:
            add(np.linalg.norm(np.asarray(pa, float)), Msg("d.factor_radius", point=a, body=body.name))
    local = []  # the constraint's own local points (s'_i^P …): their distances and their norms
    for attr, role in spec.points:
        v = getattr(c, attr, None)
        if v is not None and role < len(names):
            try:
                local.append((attr, role, np.asarray([float(x) for x in v])))
            except (TypeError, ValueError):  # a symbolic coordinate: no number to try
                pass
    for k, (a, role, pa) in enumerate(local):
        for b, role_b, pb in local[k + 1:]:
            if role_b == role:
                add(np.linalg.norm(pa - pb), Msg("d.factor_local_pair", a=a, b=b, body=names[role]))
        add(np.linalg.norm(pa), Msg("d.factor_local", a=a, body=names[role]))
    return out[:limit]
