"""Planar constraints (textbook §13.5): one class per joint type on a common base.

Each constraint writes its Φ once, symbolically, in :meth:`Constraint.phi`; Φ_q, ν and γ are derived from it by
:mod:`kinbook.core.symbolic`. For speed each type also has a *kernel*: closed-form numpy code that evaluates Φ, Φ_q
and γ for every constraint of that type at once and for many instants at once. The tests check every kernel
against the symbolic derivation at seeded random configurations.

Kernels evaluate the geometric part g(q) of Φ = g(q) − f(t); the prescribed function f(t) of a driver is
applied by the mechanism, so for every constraint here Φ_q = g_q, ν = f'(t) and γ = −(g_q q̇)_q q̇ + f''(t).

Coordinates of the bodies a constraint connects arrive in the kernels as ``Q`` of shape (B, k, nb, 3): B
instants, k constraints of the type, nb bodies per constraint, and (x, y, φ).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..core.constraint import ConstraintBase, lookup_point, sequence
from ..core.reader import read_constant
from ..core.registry import constraint_types
from ..core.symbolic import t as t_symbol
from ..errors import ModelError
from ..i18n import N_
from .transforms import A as A_matrix

__all__ = [
    "Constraint",
    "Simple",
    "Ground",
    "Revolute",
    "Translational",
    "RevoluteRevolute",
    "RevoluteTranslational",
    "Gear",
    "RackPinion",
    "Driver",
    "RelativeAngleDriver",
    "DistanceDriver",
    "CONSTRAINT_TYPES",
]

_COORDS = ("x", "y", "phi")


# ----------------------------------------------------------------------------------------------- numeric helpers
def _point(Qb, s):
    """Global position of local points ``s`` (k, 2) on bodies ``Qb`` (B, k, 3): returns r^P and A s'."""
    c, sn = np.cos(Qb[..., 2]), np.sin(Qb[..., 2])
    As = np.stack([s[:, 0] * c - s[:, 1] * sn, s[:, 0] * sn + s[:, 1] * c], -1)
    return Qb[..., :2] + As, As


def _rot(v):
    """Rotate vectors by +90°: B s' = rot(A s')."""
    return np.stack([-v[..., 1], v[..., 0]], -1)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _sq(w):
    return (w * w)[..., None]


# --------------------------------------------------------------------------------------------------------- base
class Constraint(ConstraintBase):
    """Base class of planar constraints (see :class:`kinbook.core.constraint.ConstraintBase` for the class attributes,
    naming, rows, binding and registration; docs/extending.md for a new type).

    A subclass sets ``type_name``, ``label``, ``n_eq``, ``kind`` and ``roles``, and implements :meth:`phi`
    (the symbolic Φ in the bodies' (x, y, φ): the single source of truth). In :meth:`phi`, ``Q[k]`` is the
    column (x, y, φ) of the body in role k, :meth:`point` the global position r + A(φ) s' of a declared point
    and :meth:`vector` the global components A(φ) s' of a declared vector. A hand-written ``kernel`` with the
    :meth:`params` it needs is an optional optimization.

    Points are given as a point name of the body or a pair (ξ, η); vectors as two point names [P, Q] (from P
    to Q) or a pair of components.
    """

    chapter = "planar"
    COORDS = ("x", "y", "phi")
    roles = ("i", "j")

    def _local(self, role_index, point):
        """Local coordinates (sympy numbers) of ``point`` on the body in ``role_index``.

        ``point`` is a point name or a pair (ξ, η).
        """
        body = self.bodies[role_index]
        if isinstance(point, str):
            return lookup_point(body, point, self)
        try:
            if isinstance(point, (bytes, dict)):
                raise TypeError
            xi, eta = point
        except (TypeError, ValueError):
            raise ModelError(
                f"{self.describe()}: a point on body '{body.name}' must be a point name or a pair (ξ, η), "
                f"got {point!r}"
            ) from None
        where = f"{self.describe()}: a point on body '{body.name}'"
        return (read_constant(xi, where=where, symbolic=True), read_constant(eta, where=where, symbolic=True))

    def _read_point(self, role_index, spec, key):
        return self._local(role_index, spec)

    def _read_vector(self, role_index, spec, key):
        if isinstance(spec, (list, tuple)) and len(spec) == 2 and all(isinstance(p, str) for p in spec):
            P, Q = (self._local(role_index, p) for p in spec)
            v = (Q[0] - P[0], Q[1] - P[1])
        else:
            v = self._local(role_index, spec)
        if v[0] == 0 and v[1] == 0:
            raise ModelError(f"{self.describe()}: `{key}` on body '{self.bodies[role_index].name}' is zero ({spec!r})")
        return v

    def global_point(self, Qb, s):
        return self._r(Qb, s)

    def global_vector(self, Qb, s):
        return A_matrix(Qb[2]) * sp.Matrix(s)

    # helpers for the symbolic hooks
    @staticmethod
    def _r(Qb, s):
        """Symbolic global position r + A(φ) s' of a local point s' on body coordinates Qb."""
        return sp.Matrix(Qb[:2]) + A_matrix(Qb[2]) * sp.Matrix(s)


def _angle_default(value, body, coord="phi", where="an initial value"):
    """An initial value given explicitly (a number, text such as "pi/4" or a sympy parameter), or taken from
    the body's q0."""
    if value is not None:
        return read_constant(value, where=where, symbolic=True)
    return body.q0[_COORDS.index(coord)]


def _f(v):
    return np.array([float(x) for x in v], dtype=float)


# ----------------------------------------------------------------------------------------------- linear family
def _linear_kernel(Q, P, Qd=None):
    """Φ = C q_sub + c0 for constraints linear in the coordinates (simple, ground, gears, racks, drivers)."""
    Bn, k, nb, _ = Q.shape
    C = P["C"]  # (k, r, 3nb)
    flat = Q.reshape(Bn, k, 3 * nb)
    phi = np.einsum("krc,bkc->bkr", C, flat) + P["c0"]
    jac = np.broadcast_to(C, (Bn,) + C.shape)
    gamma = None if Qd is None else np.zeros((Bn, k, C.shape[1]))
    return phi, jac, gamma


class _Linear(Constraint):
    """Constraints whose Φ is linear in q: the kernel coefficients are read off the symbolic Φ."""

    kernel = staticmethod(_linear_kernel)

    def params(self):
        Q = [sp.Matrix(sp.symbols(f"_x{b} _y{b} _p{b}")) for b in range(len(self.bodies))]
        syms = [s for Qb in Q for s in Qb]
        # Φ = g(q) − f(t): the kernel evaluates g; the mechanism applies f(t)
        exprs = [sp.expand(e + self._f_expr(t_symbol)) for e in self.phi(Q)]
        C = np.array([[float(sp.diff(e, s)) for s in syms] for e in exprs])
        c0 = np.array([float(e.subs({s: 0 for s in syms})) for e in exprs])
        return {"C": C, "c0": c0}


class Simple(_Linear):
    """A simple constraint fixing one coordinate of a body: x_i = c, y_i = c or φ_i = c."""

    type_name = "simple"
    label = "s"
    n_eq = 1
    kind = "simple"
    title = N_("simple constraint")
    roles = ("i",)
    parameters = ("value",)

    def __init__(self, body, coordinate, value=None, name=None):
        if coordinate not in _COORDS:
            raise ModelError(f"simple constraint on body '{body}': coordinate must be one of x, y, phi, "
                             f"got {coordinate!r}")
        super().__init__((body,), name=name)
        self.coordinate = coordinate
        self.measures = ("angle",) if coordinate == "phi" else ("length",)
        where = f"simple constraint on body '{body}' ({coordinate}), value"
        self.value = None if value is None else read_constant(value, where=where, symbolic=True)

    def name_stems(self):
        return (f"simple {self.body_names[0]} {self.coordinate}",)

    def _complete(self):
        if self.value is None:
            self.value = _angle_default(None, self.bodies[0], self.coordinate)

    def phi(self, Q, t=t_symbol):
        return [Q[0][_COORDS.index(self.coordinate)] - self.value]


class Ground(_Linear):
    """The three simple constraints of a fixed body: x_i = c1, y_i = c2, φ_i = c3 (the book's Φ_1..Φ_3)."""

    type_name = "ground"
    label = "simple"
    n_eq = 3
    kind = "simple"
    title = N_("simple constraints of the fixed body")
    roles = ("i",)
    measures = ("length", "length", "angle")
    per_body = True
    quantities = {"value[2]": "angle"}
    parameters = ("value",)

    def name_stems(self):
        return ("ground", f"ground {self.body_names[0]}")

    def __init__(self, body, q=None, name=None):
        super().__init__((body,), name=name)
        if q is not None:
            q = sequence(q, 3, f"ground constraint on body '{body}', q (x, y, phi)")
            q = tuple(read_constant(v, where=f"ground constraint on body '{body}', q ({c})", symbolic=True)
                      for v, c in zip(q, _COORDS))
        self.value = q

    def _complete(self):
        if self.value is None:
            self.value = tuple(self.bodies[0].q0)
        if len(self.value) != 3:
            raise ModelError(f"{self.describe()}: needs three values (x, y, phi), got {len(self.value)}")

    def phi(self, Q, t=t_symbol):
        return [Q[0][k] - self.value[k] for k in range(3)]


class Gear(_Linear):
    """Cylindrical gear pair i, j on carrier k, eq. 38.

    [(φ_i − φ_i⁰) − (φ_k − φ_k⁰)] ρ_i + [(φ_j − φ_j⁰) − (φ_k − φ_k⁰)] ρ_j = 0

    External gears turn in opposite senses relative to the carrier; for an internal (ring) gear give its
    pitch radius a negative sign. Initial angles default to the bodies' q0.
    """

    type_name = "gear"
    label = "g"
    n_eq = 1
    title = N_("gear pair")
    roles = ("i", "j", "k")
    measures = ("length",)
    quantities = {"radius_i": "radius", "radius_j": "radius", "phi0": "angle"}
    parameters = ("radius_i", "radius_j", "phi0")

    def __init__(self, i, j, k, radius_i, radius_j, phi0=None, name=None):
        super().__init__((i, j, k), name=name)
        where = f"gear between '{i}' and '{j}'"
        self.radius_i = read_constant(radius_i, where=f"{where}, radius_i", symbolic=True)
        self.radius_j = read_constant(radius_j, where=f"{where}, radius_j", symbolic=True)
        self.phi0 = None if phi0 is None else sequence(phi0, 3, f"{where}, phi0 (initial angles of i, j, k)")

    def _complete(self):
        given = self.phi0 if self.phi0 is not None else (None, None, None)
        self.phi0 = tuple(_angle_default(v, b, where=f"{self.describe()}: phi0 of body '{b.name}'")
                          for v, b in zip(given, self.bodies))
        if self.radius_i == 0 or self.radius_j == 0:
            raise ModelError(f"{self.describe()}: pitch radii must be nonzero, got radius_i = {self.radius_i}, "
                             f"radius_j = {self.radius_j}")

    def phi(self, Q, t=t_symbol):
        pi0, pj0, pk0 = self.phi0
        dk = Q[2][2] - pk0
        return [((Q[0][2] - pi0) - dk) * self.radius_i + ((Q[1][2] - pj0) - dk) * self.radius_j]


class RackPinion(_Linear):
    """Rack and pinion: pinion i, rack j sliding along the global x axis.

    Fixed pinion (eq. 40):    (φ_i − φ_i⁰) ρ_i − (x_j − x_j⁰) = 0
    Sliding pinion (eq. 42):  (x_i − x_i⁰) + (φ_i − φ_i⁰) ρ_i − (x_j − x_j⁰) = 0

    Initial values default to the bodies' q0.
    """

    type_name = "rack-pinion"
    label = "rp"
    n_eq = 1
    title = N_("rack-and-pinion")
    measures = ("length",)
    quantities = {"radius": "radius", "initial[phi_i]": "angle"}
    parameters = ("radius", "initial")

    def __init__(self, i, j, radius, sliding=False, initial=None, name=None):
        super().__init__((i, j), name=name)
        where = f"rack-pinion between '{i}' and '{j}'"
        self.radius = read_constant(radius, where=f"{where}, radius", symbolic=True)
        if not isinstance(sliding, (bool, np.bool_)):
            raise ModelError(f"{where}: `sliding` must be true or false, got {sliding!r}")
        self.sliding = bool(sliding)
        if initial is not None:
            if not isinstance(initial, dict):
                raise ModelError(f"{where}: `initial` must be a table of x_i, phi_i, x_j, got {initial!r}")
            unknown = sorted(set(initial) - {"x_i", "phi_i", "x_j"})
            if unknown:
                raise ModelError(f"{where}: `initial` has unknown key '{unknown[0]}' (accepted: x_i, phi_i, x_j)")
        self.initial = initial

    def _complete(self):
        bi, bj = self.bodies
        given = dict(self.initial or {})
        where = f"{self.describe()}: initial"
        self.initial = {
            "x_i": _angle_default(given.get("x_i"), bi, "x", f"{where} x_i"),
            "phi_i": _angle_default(given.get("phi_i"), bi, "phi", f"{where} phi_i"),
            "x_j": _angle_default(given.get("x_j"), bj, "x", f"{where} x_j"),
        }
        if self.radius == 0:
            raise ModelError(f"{self.describe()}: the pinion's pitch radius must be nonzero")

    def phi(self, Q, t=t_symbol):
        e = (Q[0][2] - self.initial["phi_i"]) * self.radius - (Q[1][0] - self.initial["x_j"])
        if self.sliding:
            e = (Q[0][0] - self.initial["x_i"]) + e
        return [e]


class Driver(_Linear):
    """Driving constraint on one coordinate: q_k − f(t) = 0, e.g. φ_2 − (3π/4 + 100 t) = 0."""

    type_name = "driver"
    label = "d"
    n_eq = 1
    kind = "driver"
    title = N_("driver")
    roles = ("i",)

    def __init__(self, body, coordinate, f, name=None):
        if coordinate not in _COORDS:
            raise ModelError(f"driver on body '{body}': coordinate must be one of x, y, phi, got {coordinate!r}")
        super().__init__((body,), name=name, f=f)
        self.coordinate = coordinate
        self.measures = ("angle",) if coordinate == "phi" else ("length",)

    def phi(self, Q, t=t_symbol):
        return [Q[0][_COORDS.index(self.coordinate)] - self._f_expr(t)]


class RelativeAngleDriver(_Linear):
    """Relative rotation driver: φ_j − φ_i − f(t) = 0."""

    type_name = "relative-driver"
    label = "d"
    n_eq = 1
    kind = "driver"
    title = N_("relative-angle driver")
    measures = ("angle",)

    def phi(self, Q, t=t_symbol):
        return [Q[1][2] - Q[0][2] - self._f_expr(t)]


# ---------------------------------------------------------------------------------------------- revolute (r,2)
def _revolute_kernel(Q, P, Qd=None):
    rPi, Ai = _point(Q[:, :, 0], P["si"])
    rPj, Aj = _point(Q[:, :, 1], P["sj"])
    phi = rPi - rPj
    Bn, k = phi.shape[:2]
    jac = np.zeros((Bn, k, 2, 6))
    jac[:, :, 0, 0] = jac[:, :, 1, 1] = 1.0
    jac[:, :, 0, 3] = jac[:, :, 1, 4] = -1.0
    jac[:, :, :, 2] = _rot(Ai)
    jac[:, :, :, 5] = -_rot(Aj)
    gamma = None
    if Qd is not None:
        gamma = Ai * _sq(Qd[:, :, 0, 2]) - Aj * _sq(Qd[:, :, 1, 2])
    return phi, jac, gamma


class Revolute(Constraint):
    """Revolute joint (r,2), eqs. 17–18: r_i + A_i s'_i^P − r_j − A_j s'_j^P = 0.

    Parameters
    ----------
    i, j : str
        Body names.
    point : str, optional
        Name of the joint point when both bodies call it the same.
    point_i, point_j : str or (ξ, η), optional
        The joint point on each body.
    """

    type_name = "revolute"
    label = "r"
    n_eq = 2
    title = N_("revolute joint")
    measures = ("length", "length")
    points = {"point_i": ("i", "s_i"), "point_j": ("j", "s_j")}
    aliases = {"point": ("point_i", "point_j")}
    parameters = ("s_i", "s_j")
    kernel = staticmethod(_revolute_kernel)

    def phi(self, Q, t=t_symbol):
        return list(self._r(Q[0], self.s_i) - self._r(Q[1], self.s_j))

    def params(self):
        return {"si": _f(self.s_i), "sj": _f(self.s_j)}


# ------------------------------------------------------------------------------------------ translational (t,2)
def _translational_kernel(Q, P, Qd=None):
    Qi, Qj = Q[:, :, 0], Q[:, :, 1]
    rPi, Api = _point(Qi, P["sPi"])
    rQi, _ = _point(Qi, P["sQi"])
    rPj, Apj = _point(Qj, P["sPj"])
    s = rPi - rQi  # the book's s_i = r_i^P − r_i^Q (eq. 23.a, with Q for the printed O)
    d = rPj - rPi
    Bn, k = s.shape[:2]
    phi = np.stack([_cross(s, d), Qi[..., 2] - Qj[..., 2] - P["c"]], -1)
    jac = np.zeros((Bn, k, 2, 6))
    jac[:, :, 0, 0], jac[:, :, 0, 1] = s[..., 1], -s[..., 0]
    jac[:, :, 0, 2] = -_dot(s, rPj - Qi[..., :2])
    jac[:, :, 0, 3], jac[:, :, 0, 4] = -s[..., 1], s[..., 0]
    jac[:, :, 0, 5] = _dot(s, Apj)
    jac[:, :, 1, 2], jac[:, :, 1, 5] = 1.0, -1.0
    gamma = None
    if Qd is not None:
        wi, wj = Qd[:, :, 0, 2], Qd[:, :, 1, 2]
        s_dot = _rot(s) * wi[..., None]
        d_dot = Qd[:, :, 1, :2] + _rot(Apj) * wj[..., None] - Qd[:, :, 0, :2] - _rot(Api) * wi[..., None]
        d_dd = -Apj * _sq(wj) + Api * _sq(wi)
        g1 = -(_cross(-s * _sq(wi), d) + 2 * _cross(s_dot, d_dot) + _cross(s, d_dd))
        gamma = np.stack([g1, np.zeros_like(g1)], -1)
    return phi, jac, gamma


class Translational(Constraint):
    """Translational joint (t,2), eq. 26.

    Two points P_i, Q_i of body i on the line of translation and a point P_j of body j on the same line stay
    aligned, and the bodies keep their relative angle::

        Φ_1 = (r_i^P − r_i^Q) × (r_j^P − r_i^P) = 0
        Φ_2 = φ_i − φ_j − (φ_i⁰ − φ_j⁰) = 0

    with the book's signs: s_i = r_i^P − r_i^Q (eq. 23.a, which prints the body origin O where Q belongs:
    erratum 13.5-eq25), d = r_j^P − r_i^P (eq. 23.b), so Table 13.2's Jacobian and Table 13.5's γ apply as
    printed where they are right.

    Parameters
    ----------
    i, j : str
    axis : (point, point)
        P_i and Q_i on body i.
    point_j : str or (ξ, η)
        P_j on body j.
    phi0 : float, optional
        φ_i⁰ − φ_j⁰; defaults to the bodies' q0.
    """

    type_name = "translational"
    label = "t"
    n_eq = 2
    title = N_("translational joint")
    measures = ("length^2", "angle")
    points = {"axis": ("i", ("s_Pi", "s_Qi")), "point_j": ("j", "s_Pj")}
    constants = ("phi0",)
    defaults = {"phi0": None}
    quantities = {"phi0": "angle"}
    parameters = ("s_Pi", "s_Qi", "s_Pj", "phi0")
    kernel = staticmethod(_translational_kernel)

    def _complete(self):
        if self.s_Pi == self.s_Qi:
            raise ModelError(f"{self.describe()}: the two axis points on body '{self.bodies[0].name}' coincide")
        if self.phi0 is None:
            self.phi0 = self.bodies[0].q0[2] - self.bodies[1].q0[2]

    def phi(self, Q, t=t_symbol):
        s = self._r(Q[0], self.s_Pi) - self._r(Q[0], self.s_Qi)  # the book's s_i = r_i^P − r_i^Q (eq. 23.a)
        d = self._r(Q[1], self.s_Pj) - self._r(Q[0], self.s_Pi)
        return [s[0] * d[1] - s[1] * d[0], Q[0][2] - Q[1][2] - self.phi0]

    def params(self):
        return {"sPi": _f(self.s_Pi), "sQi": _f(self.s_Qi), "sPj": _f(self.s_Pj), "c": float(self.phi0)}


# ------------------------------------------------------------------------------------ revolute-revolute (r-r,1)
def _rr_kernel(Q, P, Qd=None):
    rPi, Ai = _point(Q[:, :, 0], P["si"])
    rPj, Aj = _point(Q[:, :, 1], P["sj"])
    d = rPi - rPj
    phi = (_dot(d, d) - P["l"] ** 2)[..., None]
    Bn, k = d.shape[:2]
    jac = np.zeros((Bn, k, 1, 6))
    jac[:, :, 0, 0:2] = 2 * d
    jac[:, :, 0, 2] = 2 * _dot(d, _rot(Ai))
    jac[:, :, 0, 3:5] = -2 * d
    jac[:, :, 0, 5] = -2 * _dot(d, _rot(Aj))
    gamma = None
    if Qd is not None:
        wi, wj = Qd[:, :, 0, 2], Qd[:, :, 1, 2]
        d_dot = Qd[:, :, 0, :2] + _rot(Ai) * wi[..., None] - Qd[:, :, 1, :2] - _rot(Aj) * wj[..., None]
        d_dd = -Ai * _sq(wi) + Aj * _sq(wj)
        gamma = (-2 * _dot(d_dot, d_dot) - 2 * _dot(d, d_dd))[..., None]
    return phi, jac, gamma


class RevoluteRevolute(Constraint):
    """Revolute–revolute composite joint (r-r,1), eq. 32: (x_i^P − x_j^P)² + (y_i^P − y_j^P)² − l² = 0.

    The link between P_i and P_j (length l) is not modelled as a body.
    """

    type_name = "revolute-revolute"
    label = "r-r"
    n_eq = 1
    title = N_("revolute-revolute joint")
    measures = ("length^2",)
    points = {"point_i": ("i", "s_i"), "point_j": ("j", "s_j")}
    constants = ("length",)
    quantities = {"length": "length"}
    parameters = ("s_i", "s_j", "length")
    kernel = staticmethod(_rr_kernel)

    def phi(self, Q, t=t_symbol):
        d = self._r(Q[0], self.s_i) - self._r(Q[1], self.s_j)
        return [d[0] ** 2 + d[1] ** 2 - self.length**2]

    def params(self):
        return {"si": _f(self.s_i), "sj": _f(self.s_j), "l": float(self.length)}


# -------------------------------------------------------------------------------- revolute-translational (r-t,1)
def _rt_kernel(Q, P, Qd=None):
    Qi, Qj = Q[:, :, 0], Q[:, :, 1]
    rPi, Api = _point(Qi, P["sPi"])
    rPj, _ = _point(Qj, P["sPj"])
    rQj, Aqj = _point(Qj, P["sQj"])
    d = rPi - rQj
    s = rPj - rQj
    Bn, k = d.shape[:2]
    phi = _cross(d, s)[..., None]
    jac = np.zeros((Bn, k, 1, 6))
    jac[:, :, 0, 0], jac[:, :, 0, 1] = s[..., 1], -s[..., 0]
    jac[:, :, 0, 2] = -_dot(Api, s)
    jac[:, :, 0, 3], jac[:, :, 0, 4] = -s[..., 1], s[..., 0]
    jac[:, :, 0, 5] = _dot(s, rPi - Qj[..., :2])
    gamma = None
    if Qd is not None:
        wi, wj = Qd[:, :, 0, 2], Qd[:, :, 1, 2]
        d_dot = Qd[:, :, 0, :2] + _rot(Api) * wi[..., None] - Qd[:, :, 1, :2] - _rot(Aqj) * wj[..., None]
        s_dot = _rot(s) * wj[..., None]
        d_dd = -Api * _sq(wi) + Aqj * _sq(wj)
        gamma = (-(_cross(d_dd, s) + 2 * _cross(d_dot, s_dot) + _cross(d, -s * _sq(wj))))[..., None]
    return phi, jac, gamma


class RevoluteTranslational(Constraint):
    """Revolute–translational composite joint (r-t,1), eq. 33.

    P_i (the revolute axis, on body i) stays on the line through P_j and Q_j of body j::

        (r_i^P − r_j^Q) × (r_j^P − r_j^Q) = 0
    """

    type_name = "revolute-translational"
    label = "r-t"
    n_eq = 1
    title = N_("revolute-translational joint")
    measures = ("length^2",)
    points = {"point_i": ("i", "s_Pi"), "axis": ("j", ("s_Pj", "s_Qj"))}
    parameters = ("s_Pi", "s_Pj", "s_Qj")
    kernel = staticmethod(_rt_kernel)

    def _complete(self):
        if self.s_Pj == self.s_Qj:
            raise ModelError(f"{self.describe()}: the two axis points on body '{self.bodies[1].name}' coincide")

    def phi(self, Q, t=t_symbol):
        d = self._r(Q[0], self.s_Pi) - self._r(Q[1], self.s_Qj)
        s = self._r(Q[1], self.s_Pj) - self._r(Q[1], self.s_Qj)
        return [d[0] * s[1] - d[1] * s[0]]

    def params(self):
        return {"sPi": _f(self.s_Pi), "sPj": _f(self.s_Pj), "sQj": _f(self.s_Qj)}


# --------------------------------------------------------------------------------- distance along a slide axis
def _distance_kernel(Q, P, Qd=None):
    Qi, Qj = Q[:, :, 0], Q[:, :, 1]
    rPi, Api = _point(Qi, P["sPi"])
    rQi, _ = _point(Qi, P["sQi"])
    rPj, Apj = _point(Qj, P["sPj"])
    u = (rQi - rPi) / P["len"][:, None]
    d = rPj - rPi
    Bn, k = d.shape[:2]
    phi = _dot(u, d)[..., None]
    jac = np.zeros((Bn, k, 1, 6))
    jac[:, :, 0, 0:2] = -u
    jac[:, :, 0, 2] = _dot(_rot(u), d) - _dot(u, _rot(Api))
    jac[:, :, 0, 3:5] = u
    jac[:, :, 0, 5] = _dot(u, _rot(Apj))
    gamma = None
    if Qd is not None:
        wi, wj = Qd[:, :, 0, 2], Qd[:, :, 1, 2]
        u_dot = _rot(u) * wi[..., None]
        d_dot = Qd[:, :, 1, :2] + _rot(Apj) * wj[..., None] - Qd[:, :, 0, :2] - _rot(Api) * wi[..., None]
        d_dd = -Apj * _sq(wj) + Api * _sq(wi)
        gamma = (-(_dot(-u * _sq(wi), d) + 2 * _dot(u_dot, d_dot) + _dot(u, d_dd)))[..., None]
    return phi, jac, gamma


class DistanceDriver(Constraint):
    """Driver of a translational joint: the distance of P_j from P_i along the axis P_i→Q_i equals f(t).

    Φ = u_i · (r_j^P − r_i^P) − f(t), with u_i the unit vector from P_i to Q_i.
    """

    type_name = "distance-driver"
    label = "d"
    n_eq = 1
    kind = "driver"
    title = N_("distance driver")
    measures = ("length",)
    points = {"axis": ("i", ("s_Pi", "s_Qi")), "point_j": ("j", "s_Pj")}
    parameters = ("s_Pi", "s_Qi", "s_Pj", "axis_length")
    kernel = staticmethod(_distance_kernel)

    def _complete(self):
        self.axis_length = sp.sqrt((self.s_Qi[0] - self.s_Pi[0]) ** 2 + (self.s_Qi[1] - self.s_Pi[1]) ** 2)
        if self.axis_length == 0:
            raise ModelError(f"{self.describe()}: the two axis points on body '{self.bodies[0].name}' coincide")

    def phi(self, Q, t=t_symbol):
        u = (self._r(Q[0], self.s_Qi) - self._r(Q[0], self.s_Pi)) / self.axis_length
        d = self._r(Q[1], self.s_Pj) - self._r(Q[0], self.s_Pi)
        return [u.dot(d) - self._f_expr(t)]

    def params(self):
        return {"sPi": _f(self.s_Pi), "sQi": _f(self.s_Qi), "sPj": _f(self.s_Pj), "len": float(self.axis_length)}


CONSTRAINT_TYPES = constraint_types("planar")
"""Constraint classes by the ``type`` name used in mechanism files: a live, read-only view of the planar
registry (every subclass of :class:`Constraint` that sets ``type_name`` appears in it)."""
