"""Table 14.1 filled in: the Jacobian blocks and γ of every spatial constraint type in closed form.

What this is, and is not. Table 14.1 reached us empty (its rows were lost in transcription; the legend under it,
B_k = 2(E_k s̄'^P_k + s'^P_k p_kᵀ) and C_k = 2(E_k s̄'_k + s'_k p_kᵀ), survives), and the book works out γ for
(n1,1) only. Notebook 14-5 prints the table as it follows from the book's rule ∂(A a)/∂p = C(p, a) and the
product rule, and a γ table from the velocity-quadratic part C(ṗ, a) ṗ of (A a)¨. This module holds those
printed closed forms once, **as the thing under test, never as a reference**: no checker, try-it or analysis
reads it. kinbook's single source stays each constraint class's symbolic Φ; its kernels and the kernels compiled
from Φ are what :func:`kinbook.book.verify.jacobian_table` and :func:`~kinbook.book.verify.gamma_table` compare
these forms with (and with finite differences), and ``tests/book/test_table14.py`` shows a wrong entry is caught.

The entry of a constraint is found by its class (the primitive types below, through the class hierarchy); a
composite joint (``parts``) stacks the entries of its parts, read from its part views, so a new composite
needs no entry of its own. A type with no entry (a driver, a type added later) gives ``None``.

>>> import numpy as np, kinbook
>>> from kinbook.book import table14, verify
>>> m = kinbook.examples.load("spatial_fourbar")
>>> q = m.solve_position(0.0)
>>> c = m.constraint("A")                                    # the spherical joint between crank and coupler
>>> qc = np.concatenate([m.r(q, b.name).tolist() + m.p(q, b.name).tolist() for b in c.bodies])
>>> bool(np.allclose(table14.jacobian_rows(c, qc), m.Phi_q(q)[c.rows][:, verify.columns(m, c)]))
True
"""

from __future__ import annotations

import numpy as np

from ..spatial import (
    Cylindrical,
    Ground,
    Mechanism,
    Normal1,
    Normal2,
    Parallel1,
    Parallel2,
    Revolute,
    Spherical,
    SphericalSpherical,
    Translational,
    Universal,
    random_p,
)
from ..spatial import constraints as sc
from ..spatial.rotations import A_from_p, E, dAa_dp

__all__ = ["jacobian_rows", "gamma_rows", "has_entry", "ENTRIES", "bench", "bench_states"]

_I3, _Z3 = np.eye(3), np.zeros(3)


class _Body:
    """r, p, ṙ, ṗ of one body, and the rotated vectors of Table 14.1: s = A a, C = ∂(A a)/∂p, c = C(ṗ) ṗ."""

    def __init__(self, q, qd):
        self.r, self.p = q[:3], q[3:7]
        self.rd, self.pd = (None, None) if qd is None else (qd[:3], qd[3:7])
        self.A = A_from_p(self.p, check=False)

    def vec(self, a):
        """(s, C, ṡ, c) of a body-fixed vector a: s = A a, C = ∂(A a)/∂p, ṡ = C ṗ, c = C(ṗ) ṗ."""
        C = dAa_dp(self.p, a)
        if self.pd is None:
            return self.A @ a, C, None, None
        return self.A @ a, C, C @ self.pd, dAa_dp(self.pd, a) @ self.pd

    def point(self, a):
        """(r^P, B, ṙ^P, b) of a point with local coordinates a: r + A a, its B, velocity and b = B(ṗ) ṗ."""
        s, B, sd, b = self.vec(a)
        return self.r + s, B, None if sd is None else self.rd + sd, b


def _d(bi, bj, P_i, P_j):
    """d = r_j^P − r_i^P with its blocks: (d, B_i, B_j, ḋ, b_i, b_j)."""
    ri, Bi, vi, b_i = bi.point(P_i)
    rj, Bj, vj, b_j = bj.point(P_j)
    return rj - ri, Bi, Bj, None if vi is None else vj - vi, b_i, b_j


def _n1(bi, bj, a_i, a_j):
    """(n1,1), s_iᵀ s_j: [0ᵀ, s_jᵀ C_i, 0ᵀ, s_iᵀ C_j];  γ = −s_jᵀ c_i − s_iᵀ c_j − 2 ṡ_iᵀ ṡ_j."""
    s_i, C_i, sd_i, c_i = bi.vec(a_i)
    s_j, C_j, sd_j, c_j = bj.vec(a_j)
    row = np.r_[_Z3, s_j @ C_i, _Z3, s_i @ C_j]
    gamma = None if sd_i is None else -s_j @ c_i - s_i @ c_j - 2 * sd_i @ sd_j
    return row[None], gamma


def _n2(bi, bj, a_i, P_i, P_j):
    """(n2,1), s_iᵀ d: [−s_iᵀ, dᵀC_i − s_iᵀB_i, s_iᵀ, s_iᵀB_j];  γ = −dᵀc_i − s_iᵀ(b_j − b_i) − 2 ṡ_iᵀ ḋ."""
    s_i, C_i, sd_i, c_i = bi.vec(a_i)
    d, B_i, B_j, dd, b_i, b_j = _d(bi, bj, P_i, P_j)
    row = np.r_[-s_i, d @ C_i - s_i @ B_i, s_i, s_i @ B_j]
    gamma = None if sd_i is None else -d @ c_i - s_i @ (b_j - b_i) - 2 * sd_i @ dd
    return row[None], gamma


def _normal1(c, bi, bj):
    return [_n1(bi, bj, c.a_i, c.a_j)]


def _normal2(c, bi, bj):
    return [_n2(bi, bj, c.a_i, c.P_i, c.P_j)]


def _parallel1(c, bi, bj):
    """(p1,2) as kinbook writes it: two (n1,1) rows h_kᵀ s_j with h_1, h_2 ⊥ s_i fixed in body i."""
    return [_n1(bi, bj, h, c.a_j) for h in (c.h1, c.h2)]


def _parallel2(c, bi, bj):
    """(p2,2): two (n2,1) rows h_kᵀ d."""
    return [_n2(bi, bj, h, c.P_i, c.P_j) for h in (c.h1, c.h2)]


def _spherical(c, bi, bj):
    """(s,3), r_i + A_i s'_i − r_j − A_j s'_j: [I, B_i, −I, −B_j];  γ = −b_i + b_j."""
    d, B_i, B_j, dd, b_i, b_j = _d(bi, bj, c.P_i, c.P_j)
    rows = np.hstack([_I3, B_i, -_I3, -B_j])
    return [(rows, None if dd is None else -b_i + b_j)]


def _spherical_spherical(c, bi, bj):
    """(s-s,1), dᵀd − l²: [−2dᵀ, −2dᵀB_i, 2dᵀ, 2dᵀB_j];  γ = −2dᵀ(b_j − b_i) − 2ḋᵀḋ."""
    d, B_i, B_j, dd, b_i, b_j = _d(bi, bj, c.P_i, c.P_j)
    row = np.r_[-2 * d, -2 * d @ B_i, 2 * d, 2 * d @ B_j]
    return [(row[None], None if dd is None else -2 * d @ (b_j - b_i) - 2 * dd @ dd)]


def _normalization(c, b):
    """pᵀp − 1: [0ᵀ, 2pᵀ];  γ = −2ṗᵀṗ."""
    return [(np.r_[_Z3, 2 * b.p][None], None if b.pd is None else -2 * b.pd @ b.pd)]


def _ground(c, b):
    """r − r⁰ and E(p⁰) p: [[I, 0], [0, E(p⁰)]];  γ = 0."""
    rows = np.block([[_I3, np.zeros((3, 4))], [np.zeros((3, 3)), E(c.p0, check=False)]])
    return [(rows, None if b.pd is None else np.zeros(6))]


ENTRIES = {
    sc.Normalization: _normalization,
    sc.Ground: _ground,
    sc.Normal1: _normal1,
    sc.Normal2: _normal2,
    sc.Parallel1: _parallel1,
    sc.Parallel2: _parallel2,
    sc.Spherical: _spherical,
    sc.SphericalSpherical: _spherical_spherical,
}
"""The primitive constraint classes and their entry of the table (composites stack their parts')."""


def _entry(c):
    if c.parts:
        return None
    for cls in type(c).__mro__:
        if cls in ENTRIES:
            return ENTRIES[cls]
    return None


def has_entry(c):
    """True when the table gives constraint ``c`` its rows (every part of a composite has an entry)."""
    if c.parts:
        return all(has_entry(v) for v in c.part_views())
    return _entry(c) is not None


def _rows(c, q, qd):
    if c.parts:
        parts = [_rows(v, q, qd) for v in c.part_views()]
        return None if any(p is None for p in parts) else [r for p in parts for r in p]
    entry = _entry(c)
    if entry is None:
        return None
    nb = len(c.bodies)
    q = np.asarray(q, dtype=float).reshape(nb, 7)
    qd = None if qd is None else np.asarray(qd, dtype=float).reshape(nb, 7)
    bodies = [_Body(q[k], None if qd is None else qd[k]) for k in range(nb)]
    return entry(c, *bodies)


def jacobian_rows(c, q):
    """The constraint's rows of Φ_q from the table, with respect to its own bodies' coordinates.

    Parameters
    ----------
    c : kinbook.spatial.Constraint
        Bound to a mechanism.
    q : array_like, shape (7·nb,)
        (r, p) of the constraint's bodies, in ``c.bodies`` order (p need not be unit: the formulas hold for
        any p).

    Returns
    -------
    ndarray, shape (n_eq, 7·nb), or None when the type has no entry.
    """
    rows = _rows(c, q, None)
    return None if rows is None else np.vstack([np.atleast_2d(j) for j, _ in rows])


def gamma_rows(c, q, qd):
    """The constraint's γ from the table at (q, q̇) of its bodies (as :func:`jacobian_rows`); None when the
    type has no entry."""
    rows = _rows(c, q, qd)
    return None if rows is None else np.concatenate([np.atleast_1d(g) for _, g in rows])


# ---------------------------------------------------------------------------------------------- the test bench
def bench():
    """Notebook 14-5's test bench: two free bodies i and j with one constraint of every spatial type between
    them (n1, n2, p1, p2, s, s-s, universal, revolute, cylindrical, translational) and a ground on body i.

    It does not assemble (the constraints contradict each other); it is a place to evaluate every type's
    rows at the same configurations.
    """
    m = Mechanism("test bench: one constraint of each type")
    m.add_body("i", points={"P": (0, 0, 1), "B": (1, 0, 0)}, vectors={"s": (0, 0, 1), "h": (1, 0, 0)},
               q0=(0.5, -0.2, 1.0, 0.9, 0.1, -0.3, 0.2))  # q0: the ground constraint's r⁰, p⁰
    m.add_body("j", points={"P": (0, 1, 0), "B": (-1, 0, 0)}, vectors={"s": (0, 0, 1), "h": (0, 1, 0)})
    two = dict(vector_i="s", point_i="B", point_j="B")
    for c in [Normal1("i", "j", vector_i="s", vector_j="s", name="n1"), Normal2("i", "j", **two, name="n2"),
              Parallel1("i", "j", vector_i="s", vector_j="s", name="p1"), Parallel2("i", "j", **two, name="p2"),
              Spherical("i", "j", point="P", name="s"),
              SphericalSpherical("i", "j", point_i="P", point_j="B", length=1.3, name="s-s"),
              Universal("i", "j", vector_i="s", vector_j="h", point="P", name="universal"),
              Revolute("i", "j", axis_i="s", axis_j="s", point="P", name="revolute"),
              Cylindrical("i", "j", axis_i="s", axis_j="s", point_i="P", point_j="B", name="cylindrical"),
              Translational("i", "j", axis_i="s", axis_j="s", point_i="P", point_j="B", perp_i="h", perp_j="h",
                            name="translational"),
              Ground("i", name="ground")]:
        m.add(c)
    return m


def bench_states(mech, seed=145, scales=((1.0, 1.0), (1.25, 0.8))):
    """Seeded random states (q, q̇, q̈) of a two-body mechanism, one per entry of ``scales``: random positions,
    random unit Euler parameters times the scales (so p off the unit sphere too: the formulas hold for any p),
    random velocities and accelerations."""
    rng = np.random.default_rng(seed)
    out = []
    for scale in scales:
        q = rng.uniform(-1, 1, (2, 7))
        q[:, 3:] = random_p(2, rng) * np.array(scale)[:, None]
        out.append((q.ravel(), rng.uniform(-2, 2, mech.n), rng.uniform(-2, 2, mech.n)))
    return out
