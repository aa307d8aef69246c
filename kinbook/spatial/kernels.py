"""The spatial constraints' hand-written kernels: Φ, Φ_q and γ of every constraint of a type at many instants at
once, from the Jacobian blocks of Table 14.1 (:mod:`kinbook.spatial.constraints` writes the table and each
type's Φ; the tests check every kernel against the symbolic derivation).

A kernel is made of row builders: ``rows_s`` (a spherical joint's three rows), ``rows_n1`` … each returning the
rows' values, their Jacobian and the two parts of γ, stacked by :func:`kernel`. ``Q`` has shape (B, k, nb, 7):
B instants, k constraints of the type, nb bodies per constraint, and (x, y, z, e0, e1, e2, e3).
"""

from __future__ import annotations

import numpy as np

from .arrays import mv

__all__ = ["NCOORD", "kernel", "rows_s", "rows_n1", "rows_n2", "rows_p1", "rows_p2", "rows_ss", "rows_distance",
           "rows_norm", "rows_ground", "rows_angle"]

NCOORD = 7
"""Coordinates of one spatial body: x, y, z, e0, e1, e2, e3."""


# E(p) and ā(a) by fancy indexing: E = [[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]],
# ā = [[0, -a1, -a2, -a3], [a1, 0, a3, -a2], [a2, -a3, 0, a1], [a3, a2, -a1, 0]] (rotations.E, rotations.a_bar)
_E_IDX = np.array([1, 0, 3, 2, 2, 3, 0, 1, 3, 2, 1, 0])
_E_SIGN = np.array([-1.0, 1, -1, 1, -1, 1, 1, -1, -1, -1, 1, 1])
_ABAR_IDX = np.array([0, 1, 2, 3, 1, 0, 3, 2, 2, 3, 0, 1, 3, 2, 1, 0])
_ABAR_SIGN = np.array([0.0, -1, -1, -1, 1, 0, 1, -1, 1, -1, 0, 1, 1, 1, -1, 0])


def _abar_np(a):
    a4 = np.concatenate([np.zeros(a.shape[:-1] + (1,)), a], -1)
    return (a4[..., _ABAR_IDX] * _ABAR_SIGN).reshape(a.shape[:-1] + (4, 4))


def _vtm(v, M):
    """Batched vector-matrix product (…, m) @ (…, m, n) -> (…, n), for small m."""
    out = v[..., 0, None] * M[..., 0, :]
    for r in range(1, v.shape[-1]):
        out += v[..., r, None] * M[..., r, :]
    return out


def _vdot(u, v):
    out = u[..., 0] * v[..., 0]
    for c in range(1, u.shape[-1]):
        out += u[..., c] * v[..., c]
    return out


class _V:
    """A 3-vector quantity of a constraint: value, Jacobian (w.r.t. the constraint's 7·nb coordinates),
    velocity and the velocity-quadratic part of its second derivative (both None without Qd).

    The Jacobian is built on first use (``jac``): an evaluation of Φ or γ alone never builds it."""

    __slots__ = ("val", "_jac", "vel", "quad")

    def __init__(self, val, jac, vel, quad):
        self.val, self._jac, self.vel, self.quad = val, jac, vel, quad

    @property
    def jac(self):
        if callable(self._jac):
            self._jac = self._jac()
        return self._jac

    def __sub__(self, other):
        vel = None if self.vel is None else self.vel - other.vel
        quad = None if self.quad is None else self.quad - other.quad
        return _V(self.val - other.val, lambda: self.jac - other.jac, vel, quad)


# E(p) = Σ_l p_l T_l: the constant tensor T (3, 4, 4) of the linear map p ↦ E(p)
_E_T = np.zeros((3, 4, 4))
_E_T[np.repeat(np.arange(3), 4), np.tile(np.arange(4), 3), _E_IDX] = _E_SIGN
_C_MAPS = {}


def _c_map(a):
    """The constant (k, 4, 12) M with C(p, a) = ∂(A a)/∂p = p·M (C flattened to 12 entries), for local
    vectors a (k, 3): C is linear in p, C_ij = 2 Σ_l p_l (Σ_m T_iml ā_mj + a_i δ_jl). Cached by value."""
    key = (a.shape, a.tobytes())
    M = _C_MAPS.get(key)
    if M is None:
        M = 2 * (np.einsum("iml,kmj->klij", _E_T, _abar_np(a)) + np.einsum("ki,jl->klij", a, np.eye(4)))
        M = M.reshape(len(a), 4, 12)
        if len(_C_MAPS) > 4096:
            _C_MAPS.clear()
        _C_MAPS[key] = M
    return M


def _c_of(p, M):
    """C for p (B, k, 4): (B, k, 3, 4), one (B × 4)·(4 × 12) product per constraint of the group."""
    Bn, k = p.shape[:2]
    out = np.empty((Bn, k, 12))
    for i in range(k):
        np.matmul(p[:, i], M[i], out=out[:, i])
    return out.reshape(Bn, k, 3, 4)


def _body_vec(Q, Qd, b, a, point):
    """A s' (``point`` False) or r + A s' (True) for local components ``a`` (k, 3) on body ``b``.

    With C = ∂(A a)/∂p = 2(Eā + a pᵀ) (Table 14.1's B_k, C_k): A a = ½ C p − a (Euler's theorem for the
    quadratic A(p), whose constant part is −I), (A a)˙ = C ṗ and the velocity-quadratic part of (A a)¨ is
    C(ṗ) ṗ = 2(E(ṗ) ā ṗ + a ṗᵀṗ).
    """
    Bn, k, nb, _ = Q.shape
    M = _c_map(a)
    p = Q[:, :, b, 3:7]
    C = _c_of(p, M)
    val = 0.5 * mv(C, p) - a

    def jac():
        out = np.zeros((Bn, k, 3, NCOORD * nb))
        out[..., NCOORD * b + 3 : NCOORD * b + 7] = C
        if point:
            out[..., NCOORD * b : NCOORD * b + 3] = np.eye(3)
        return out

    vel = quad = None
    if point:
        val = val + Q[:, :, b, :3]
    if Qd is not None:
        pd = Qd[:, :, b, 3:7]
        vel = mv(C, pd)
        if point:
            vel = vel + Qd[:, :, b, :3]
        quad = mv(_c_of(pd, M), pd)
    return _V(val, jac, vel, quad)


def _dot(u, v):
    """One row Φ = uᵀv: returns (phi (B,k), jac: a function returning (B,k,7nb), gamma (B,k) or None)."""
    phi = _vdot(u.val, v.val)

    def jac():
        return _vtm(v.val, u.jac) + _vtm(u.val, v.jac)

    gam = None
    if u.vel is not None:
        gam = -(_vdot(u.quad, v.val) + _vdot(u.val, v.quad)
                + 2 * _vdot(u.vel, v.vel))
    return phi, jac, gam


def _vector_rows(v):
    """Three rows Φ = v (a vector equation)."""
    return [(v.val[..., r], lambda r=r: v.jac[..., r, :], None if v.quad is None else -v.quad[..., r])
            for r in range(3)]


def _stack_rows(rows, jacobian=True):
    """Rows (phi, jac or a function building it, gamma) → stacked arrays; jac None unless ``jacobian``."""
    phi = np.stack([r[0] for r in rows], -1)
    jac = np.stack([r[1]() if callable(r[1]) else r[1] for r in rows], -2) if jacobian else None
    gam = None if rows[0][2] is None else np.stack([r[2] for r in rows], -1)
    return phi, jac, gam


# row builders: (Q, Qd, P) -> list of rows
def rows_s(Q, Qd, P):
    return _vector_rows(_body_vec(Q, Qd, 0, P["Pi"], True) - _body_vec(Q, Qd, 1, P["Pj"], True))


def rows_n1(Q, Qd, P):
    return [_dot(_body_vec(Q, Qd, 0, P["ai"], False), _body_vec(Q, Qd, 1, P["aj"], False))]


def _d(Q, Qd, P):
    return _body_vec(Q, Qd, 1, P["Pj"], True) - _body_vec(Q, Qd, 0, P["Pi"], True)


def rows_n2(Q, Qd, P):
    return [_dot(_body_vec(Q, Qd, 0, P["ai"], False), _d(Q, Qd, P))]


def rows_p1(Q, Qd, P):
    sj = _body_vec(Q, Qd, 1, P["sj"], False)
    return [_dot(_body_vec(Q, Qd, 0, P[h], False), sj) for h in ("h1", "h2")]


def rows_p2(Q, Qd, P):
    d = _d(Q, Qd, P)
    return [_dot(_body_vec(Q, Qd, 0, P[h], False), d) for h in ("h1", "h2")]


def rows_ss(Q, Qd, P):
    d = _d(Q, Qd, P)
    phi, jac, gam = _dot(d, d)
    return [(phi - P["l"] ** 2, jac, gam)]


def rows_distance(Q, Qd, P):
    return [_dot(_body_vec(Q, Qd, 0, P["u"], False), _d(Q, Qd, P))]


def rows_norm(Q, Qd, P):
    p = Q[:, :, 0, 3:7]
    Bn, k = p.shape[:2]
    jac = np.zeros((Bn, k, NCOORD))
    jac[..., 3:7] = 2 * p
    gam = None if Qd is None else -2 * np.einsum("bki,bki->bk", Qd[:, :, 0, 3:7], Qd[:, :, 0, 3:7])
    return [(np.einsum("bki,bki->bk", p, p) - 1.0, jac, gam)]


def rows_ground(Q, Qd, P):
    """r − r0 (3 rows) and E(p0) p (3 rows): linear in q."""
    q = Q[:, :, 0, :]
    Bn, k = q.shape[:2]
    C = P["C"]  # (k, 6, 7)
    phi = np.einsum("krc,bkc->bkr", C, q) + P["c0"]
    jac = np.broadcast_to(C, (Bn,) + C.shape)
    gam = None if Qd is None else np.zeros((Bn, k, 6))
    return [(phi[..., r], jac[..., r, :], None if gam is None else gam[..., r]) for r in range(6)]


def rows_angle(Q, Qd, P):
    fi, gi, fj = _body_vec(Q, Qd, 0, P["fi"], False), _body_vec(Q, Qd, 0, P["gi"], False), _body_vec(Q, Qd, 1, P["fj"], False)
    c, cq, cg = _dot(fi, fj)
    s, sq, sg = _dot(gi, fj)
    rho = c * c + s * s
    phi = np.arctan2(s, c)

    def jac():
        return (c[..., None] * sq() - s[..., None] * cq()) / rho[..., None]

    gam = None
    if Qd is not None:
        cd = _vdot(fi.vel, fj.val) + _vdot(fi.val, fj.vel)  # ċ = c_q q̇
        sd = _vdot(gi.vel, fj.val) + _vdot(gi.val, fj.vel)
        # θ̈ = θ_q q̈ + (c s̈_quad − s c̈_quad)/ρ − (c ṡ − s ċ)·2(c ċ + s ṡ)/ρ², with s̈_quad = −γ_s
        quad = (-c * sg + s * cg) / rho - (c * sd - s * cd) * 2 * (c * cd + s * sd) / rho**2
        gam = -quad
    return [(phi, jac, gam)]


_KERNELS = {}


def kernel(*builders):
    """The kernel whose rows are those of the row ``builders``, in order; one kernel per tuple of builders.
    ``combine`` lets a composite joint fuse its parts' builders into one kernel
    (:func:`kinbook.core.kernels.stacked`)."""
    if builders in _KERNELS:
        return _KERNELS[builders]

    def kernel(Q, P, Qd=None, jacobian=True):
        rows = []
        for build in builders:
            rows.extend(build(Q, Qd, P))
        return _stack_rows(rows, jacobian)

    kernel.builders = builders
    kernel.combine = kernel
    kernel.optional_jacobian = True
    _KERNELS[builders] = kernel
    return kernel
