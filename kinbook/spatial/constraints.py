"""Spatial constraints (textbook §14.4–14.5): one class per joint type on a common base.

Each constraint writes its Φ once, symbolically, in :meth:`Constraint.phi` — the single source of truth;
Φ_q, ν and γ are derived from it by :func:`kinbook.core.symbolic.derive`. For speed each type also has a
*kernel*: closed-form numpy code evaluating Φ, Φ_q and γ for every constraint of that type and many
instants at once, built from the Jacobian blocks of Table 14.1. The tests check every kernel against the
symbolic derivation at seeded random configurations.

Coordinates of the bodies a constraint connects arrive in the kernels as ``Q`` of shape (B, k, nb, 7): B
instants, k constraints of the type, nb bodies per constraint, and (x, y, z, e0, e1, e2, e3).

Every A here is :func:`~kinbook.spatial.rotations.A_from_p`, A = 2[(e0² − ½)I + eeᵀ + e0ẽ], so the
p-blocks of the Jacobian are exactly the book's B_k = 2(E_k s̄'ᴾ_k + s'ᴾ_k p_kᵀ) for points and
C_k = 2(E_k s̄'_k + s'_k p_kᵀ) for vectors (:func:`~kinbook.spatial.rotations.dAa_dp`).

Table 14.1 (the book prints it empty), with s_k = A_k s'_k, d = r_j + A_j s'ᴾ_j − r_i − A_i s'ᴾ_i,
B_k = ∂(A_k s'ᴾ_k)/∂p_k for points and C_k = ∂(A_k s'_k)/∂p_k for vectors::

    Φ                            ∂/∂r_i     ∂/∂p_i                 ∂/∂r_j     ∂/∂p_j
    (n1,1)  s_iᵀ s_j             0ᵀ         s_jᵀ C_i               0ᵀ         s_iᵀ C_j
    (n2,1)  s_iᵀ d               −s_iᵀ      dᵀ C_i − s_iᵀ B_i      s_iᵀ       s_iᵀ B_j
    (s,3)   r_i^P − r_j^P        I          B_i                    −I         −B_j
    (p1,2)  s̃_i s_j  (book)     0          −s̃_j C_i               0          s̃_i C_j
    (p2,2)  s̃_i d    (book)     −s̃_i       −d̃ C_i − s̃_i B_i       s̃_i        s̃_i B_j
    (p1,2)  h_kᵀ s_j (kinbook)   0ᵀ         s_jᵀ C_i(h_k)          0ᵀ         h_kᵀ C_j      (k = 1, 2)
    (p2,2)  h_kᵀ d   (kinbook)   −h_kᵀ      dᵀ C_i(h_k) − h_kᵀ B_i  h_kᵀ      h_kᵀ B_j      (h_k = A_i h'_k)

:meth:`Constraint.blocks` returns these blocks for any constraint; the tests compare them with sympy.

Parallel vectors. The book writes p1 and p2 as "two of the three" rows of s̃_i s_j = 0 without saying
which; any fixed choice of two rows loses rank on a whole circle of directions of s_i: rows 1-2 wherever
s_iz = 0 (the XY plane), rows 1-3 wherever s_iy = 0, rows 2-3 wherever s_ix = 0 (there the dropped row is
no combination of the kept ones, and the kept ones miss a misalignment). kinbook instead uses two
unit vectors h_1, h_2 fixed in body i, perpendicular to s'_i and to each other (h_1 from the coordinate axis
least aligned with s'_i, h_2 = s'_i × h_1 / |s'_i|): s_j ∥ s_i ⇔ h_1ᵀs_j = h_2ᵀs_j = 0. Both rows are
(n1,1) constraints (p2: (n2,1)), well-conditioned in every orientation (their gradients are orthogonal when
s_j ∥ s_i). Like the cross product, they also accept antiparallel vectors.

Drivers: a :class:`RevoluteDriver` prescribes the rotation angle θ of body j relative to body i about a
revolute axis, Φ = θ(q) − f(t) with θ = atan2(g_iᵀ f_j, f_iᵀ f_j); its value is wrapped into (−π, π] by the
mechanism. A :class:`DistanceDriver` prescribes the distance along a translational or cylindrical axis.
"""

from __future__ import annotations

import functools

import numpy as np
import sympy as sp

from ..core.assembly import stack_params
from ..core.constraint import ConstraintBase, lookup_point
from ..core.reader import read_number
from ..core.registry import constraint_types
from ..core.symbolic import t as t_symbol
from ..errors import ModelError, UnknownPointError
from ..i18n import N_
from . import kernels as K
from .kernels import NCOORD
from .rotations import A_from_p as _A_sym
from .rotations import E as _E_sym

__all__ = [
    "Constraint",
    "Normalization",
    "Ground",
    "Normal1",
    "Normal2",
    "Parallel1",
    "Parallel2",
    "Spherical",
    "Universal",
    "Revolute",
    "Cylindrical",
    "Translational",
    "SphericalSpherical",
    "RevoluteDriver",
    "DistanceDriver",
    "CONSTRAINT_TYPES",
]

_COORDS = ("x", "y", "z", "e0", "e1", "e2", "e3")


# ======================================================================================= symbolic building blocks
def _sym_r(Qb):
    return sp.Matrix(Qb[0:3])


@functools.lru_cache(maxsize=1024)
def _times(A, s):
    """The entries of A s' for the nine entries of A (row by row) and the three of s': a product every spatial Φ
    makes once per point and vector, kept because the checkers' mistake catalogue rebuilds each joint's Φ a dozen
    times with the same A and s' (sympy expressions are immutable)."""
    return tuple(sp.Matrix(3, 3, A) * sp.Matrix(s))


def _sym_dot(u, v):
    return (u.T * v)[0]


# ======================================================================================= helpers for parameters
def _floats(v):
    return np.array([float(x) for x in v], dtype=float)


def _perpendiculars(a):
    """Two unit vectors h1, h2 ⊥ a, with (h1, h2, a/|a|) right-handed: h1 from the coordinate axis least
    aligned with a."""
    a = np.asarray(a, dtype=float)
    u = a / np.linalg.norm(a)
    k = int(np.argmin(np.abs(u)))
    e = np.zeros(3)
    e[k] = 1.0
    h1 = np.cross(u, e)
    h1 /= np.linalg.norm(h1)
    h2 = np.cross(u, h1)
    return h1, h2


def _num(v):
    return v if isinstance(v, sp.Basic) else sp.Float(float(v), 17)


def _sym3(v):
    return [_num(x) for x in v]


# ======================================================================================= base class
class Constraint(ConstraintBase):
    """Base class of spatial constraints (see :class:`kinbook.core.constraint.ConstraintBase` for the class attributes,
    naming, rows, binding and registration; docs/extending.md for a new type).

    A subclass declares the points and vectors it reads (and derives what follows from them in
    :meth:`_complete`) and implements :meth:`phi` (the symbolic Φ in the bodies' (x, y, z, e0, e1, e2, e3): the single source of
    truth). In :meth:`phi`, :meth:`point` is the global position r + A(p) s' of a declared point and
    :meth:`vector` the global components A(p) s' of a declared vector. A ``kernel`` built from the row
    builders of this module, with the :meth:`params` it reads, is an optional optimization. Its ``label`` is
    the book's notation: "s,3", "p1,2", "s,3 + p1,2" …

    Points are given as a point name of the body or three local coordinates; vectors as a vector name, two
    point names [P, Q] (from P to Q) or three components.
    """

    chapter = "spatial"
    COORDS = _COORDS

    def _read_point(self, role_index, spec, key):
        return self._point(role_index, spec, key)

    def _read_vector(self, role_index, spec, key):
        return self._vector(role_index, spec, key)

    def rotation(self, Qb):
        """The rotation matrix A(p) of a body from its symbols ``Qb`` = (x, y, z, e0, e1, e2, e3): kinbook's
        :func:`~kinbook.spatial.rotations.A_from_p`. Every row of Φ reads A through this hook, so a subclass (or
        the mistake catalogue, on a copy) may build Φ with another matrix without re-typing it."""
        return _A_sym(list(Qb[3:7]))

    def global_point(self, Qb, s):
        return _sym_r(Qb) + self.global_vector(Qb, s)

    def global_vector(self, Qb, s):
        return sp.Matrix(_times(tuple(self.rotation(Qb)), tuple(_sym3(s))))

    def _distance(self, Q, Pi, Pj):
        """d = r_j^P − r_i^P (global), between local points P_i of the first body and P_j of the second."""
        return self.global_point(Q[1], Pj) - self.global_point(Q[0], Pi)

    def _point(self, role, spec, what="point"):
        """Local coordinates (floats, shape (3,)) of a point: a point name or a triple (ξ, η, ζ)."""
        body = self.bodies[role]
        if isinstance(spec, str):
            return _floats(lookup_point(body, spec, self))
        return _triple(spec, f"{self.describe()}: {what} on body '{body.name}' must be a point name or a "
                             f"triple (ξ, η, ζ)")

    def _vector(self, role, spec, what="vector"):
        """Local components (floats, shape (3,)) of a body-fixed vector: a vector name, a pair of point
        names [P, Q] (the vector from P to Q) or a triple of components. Must be nonzero."""
        body = self.bodies[role]
        if isinstance(spec, str):
            if spec not in body.vectors:
                known = ", ".join(sorted(body.vectors)) or "none"
                raise UnknownPointError(
                    f"{self.describe()}: body '{body.name}' has no vector '{spec}' (its vectors: {known}; "
                    f"a vector can also be given as two point names [P, Q] or as three components)"
                )
            v = _floats(body.vectors[spec])
        elif isinstance(spec, (list, tuple)) and len(spec) == 2 and all(isinstance(s, str) for s in spec):
            v = self._point(role, spec[1], what) - self._point(role, spec[0], what)
        else:
            v = _triple(spec, f"{self.describe()}: {what} on body '{body.name}' must be a vector name, two "
                              f"point names or three components")
        if np.linalg.norm(v) < 1e-12:
            raise ModelError(f"{self.describe()}: {what} on body '{body.name}' is zero ({spec!r})")
        return v

    def blocks(self, q):
        """Jacobian blocks of this constraint in the layout of Table 14.1, from the fast kernel.

        Parameters
        ----------
        q : array_like, shape (7·nb,)
            Coordinates of this constraint's bodies, in ``self.bodies`` order.

        Returns
        -------
        dict
            ``{"r_i": (n_eq, 3), "p_i": (n_eq, 4), "r_j": …, "p_j": …}`` (one pair per body role).
        """
        nb = len(self.body_names)
        q = np.asarray(q, dtype=float).reshape(1, 1, nb, NCOORD)
        kernel, params = self.numeric()
        _, jac, _ = kernel(q, stack_params([params]))
        jac = jac[0, 0]
        out = {}
        for b, role in enumerate("ijk"[:nb]):
            out[f"r_{role}"] = jac[:, NCOORD * b : NCOORD * b + 3]
            out[f"p_{role}"] = jac[:, NCOORD * b + 3 : NCOORD * b + 7]
        return out


def _triple(v, message):
    if not isinstance(v, (list, tuple, np.ndarray)) or len(v) != 3:
        raise ModelError(f"{message}, got {v!r}")
    return np.array([read_number(x, where=message.split(" must ")[0]) for x in v], dtype=float)


# ======================================================================================= one-body constraints
class Normalization(Constraint):
    """Euler parameter normalization of one body: pᵀp − 1 = 0 (textbook §14.5).

    The mechanism adds one per body when the body is added; it counts as a geometric equation.
    """

    type_name = "normalization"
    label = "pᵀp−1"
    n_eq = 1
    kind = "normalization"
    title = N_("Euler-parameter normalization")
    roles = ("i",)
    measures = ("ratio",)
    per_body = True
    in_files = False
    kernel = staticmethod(K.kernel(K.rows_norm))

    def phi(self, Q, t=t_symbol):
        p = sp.Matrix(Q[0][3:7])
        return [(p.T * p)[0] - 1]


class Ground(Constraint):
    """A fixed body: r_i = r⁰ (3 rows) and E(p⁰) p_i = 0 (3 rows).

    E(p⁰) p = 0 together with the body's normalization pᵀp = 1 leaves p = ±p⁰. Unlike fixing three of the
    four Euler parameters (singular when the free one is zero), these rows are orthonormal for every p⁰.
    For p⁰ = [1, 0, 0, 0] they read e1 = e2 = e3 = 0.

    Parameters
    ----------
    body : str
    q : sequence of 7 numbers, optional
        The fixed (x, y, z, e0, e1, e2, e3); default: the body's q0.
    """

    type_name = "ground"
    label = "ground"
    n_eq = 6
    kind = "simple"
    title = N_("simple constraints of the fixed body")
    roles = ("i",)
    measures = ("length",) * 3 + ("ratio",) * 3
    per_body = True
    parameters = ("r0", "p0")
    kernel = staticmethod(K.kernel(K.rows_ground))

    def name_stems(self):
        return ("ground", f"ground {self.body_names[0]}")

    def __init__(self, body, q=None, name=None):
        super().__init__((body,), name=name)
        if q is not None and not isinstance(q, (list, tuple, np.ndarray)):
            raise ModelError(f"ground constraint on body '{body}': `q` must be a list of 7 values "
                             f"(x, y, z, e0, e1, e2, e3), got {q!r}")
        self.value = None if q is None else list(q)

    def _complete(self):
        body = self.bodies[0]
        if self.value is None:
            value = np.array([float(v) for v in body.q0])
        else:
            if len(self.value) != NCOORD:
                raise ModelError(f"{self.describe()}: `q` needs 7 values (x, y, z, e0, e1, e2, e3), "
                                 f"got {len(self.value)}")
            value = np.array([read_number(v, where=f"{self.describe()}: q ({c})")
                              for v, c in zip(self.value, ("x", "y", "z", "e0", "e1", "e2", "e3"))])
            n = np.linalg.norm(value[3:])
            if n < 1e-12:
                raise ModelError(f"{self.describe()}: the Euler parameters of `q` are zero")
            value[3:] /= n
        self.r0, self.p0 = value[:3], value[3:]

    def phi(self, Q, t=t_symbol):
        r = sp.Matrix(Q[0][0:3]) - sp.Matrix(_sym3(self.r0))
        e = _E_sym(_sym3(self.p0)) * sp.Matrix(Q[0][3:7])
        return list(r) + list(e)

    def params(self):
        C = np.zeros((6, 7))
        C[:3, :3] = np.eye(3)
        e0, e1, e2, e3 = self.p0
        C[3:, 3:] = [[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]]
        return {"C": C, "c0": np.concatenate([-self.r0, np.zeros(3)])}


# ======================================================================================= two-body primitives
class Normal1(Constraint):
    """Normal-1 (n1,1): two body-fixed vectors stay perpendicular, s_iᵀ s_j = 0 (textbook §14.4).

    Parameters
    ----------
    i, j : str
    vector_i, vector_j : str, [str, str] or 3 numbers
        s'_i on body i and s'_j on body j: a vector name, two point names [P, Q] (from P to Q), or local
        components.
    """

    type_name = "normal-1"
    label = "n1,1"
    n_eq = 1
    title = N_("normal-1 constraint")
    measures = ("length^2",)
    vectors = {"vector_i": ("i", "a_i"), "vector_j": ("j", "a_j")}
    parameters = ("a_i", "a_j")
    kernel = staticmethod(K.kernel(K.rows_n1))

    def phi(self, Q, t=t_symbol):
        return [_sym_dot(self.global_vector(Q[0], self.a_i), self.global_vector(Q[1], self.a_j))]

    def params(self):
        return {"ai": self.a_i, "aj": self.a_j}


class Normal2(Constraint):
    """Normal-2 (n2,1): a vector of body i stays perpendicular to d = r_j^P − r_i^P, s_iᵀ d = 0 (§14.4).

    Parameters
    ----------
    i, j : str
    vector_i : vector spec on body i (see :class:`Normal1`)
    point_i, point_j : str or 3 numbers
        The ends of d: P_i on body i, P_j on body j.
    """

    type_name = "normal-2"
    label = "n2,1"
    n_eq = 1
    title = N_("normal-2 constraint")
    measures = ("length^2",)
    vectors = {"vector_i": ("i", "a_i")}
    points = {"point_i": ("i", "P_i"), "point_j": ("j", "P_j")}
    parameters = ("a_i", "P_i", "P_j")
    kernel = staticmethod(K.kernel(K.rows_n2))

    def phi(self, Q, t=t_symbol):
        d = self._distance(Q, self.P_i, self.P_j)
        return [_sym_dot(self.global_vector(Q[0], self.a_i), d)]

    def params(self):
        return {"ai": self.a_i, "Pi": self.P_i, "Pj": self.P_j}


class _ParallelMixin:
    """The h_1, h_2 ⊥ s_i of a parallel constraint, fixed in body i, from its vector a_i."""

    def _complete(self):
        self.h1, self.h2 = _perpendiculars(self.a_i)
        super()._complete()


class Parallel1(_ParallelMixin, Constraint):
    """Parallel-1 (p1,2): two body-fixed vectors stay parallel, s_i × s_j = 0 (textbook §14.4).

    Written as h_1ᵀ s_j = h_2ᵀ s_j = 0 with h_1, h_2 ⊥ s_i fixed in body i (see the module notes): two
    independent rows in every orientation.

    Parameters
    ----------
    i, j : str
    vector_i, vector_j : vector specs (see :class:`Normal1`)
    """

    type_name = "parallel-1"
    label = "p1,2"
    n_eq = 2
    title = N_("parallel-1 constraint")
    measures = ("length", "length")
    vectors = {"vector_i": ("i", "a_i"), "vector_j": ("j", "a_j")}
    parameters = ("h1", "h2", "a_j")
    kernel = staticmethod(K.kernel(K.rows_p1))

    def phi(self, Q, t=t_symbol):
        sj = self.global_vector(Q[1], self.a_j)
        return [_sym_dot(self.global_vector(Q[0], h), sj) for h in (self.h1, self.h2)]

    def params(self):
        return {"h1": self.h1, "h2": self.h2, "sj": self.a_j}


class Parallel2(_ParallelMixin, Constraint):
    """Parallel-2 (p2,2): a vector of body i stays parallel to d = r_j^P − r_i^P, s_i × d = 0 (§14.4).

    Written as h_1ᵀ d = h_2ᵀ d = 0 with h_1, h_2 ⊥ s_i fixed in body i.
    """

    type_name = "parallel-2"
    label = "p2,2"
    n_eq = 2
    title = N_("parallel-2 constraint")
    measures = ("length", "length")
    vectors = {"vector_i": ("i", "a_i")}
    points = {"point_i": ("i", "P_i"), "point_j": ("j", "P_j")}
    parameters = ("h1", "h2", "P_i", "P_j")
    kernel = staticmethod(K.kernel(K.rows_p2))

    def phi(self, Q, t=t_symbol):
        d = self._distance(Q, self.P_i, self.P_j)
        return [_sym_dot(self.global_vector(Q[0], h), d) for h in (self.h1, self.h2)]

    def params(self):
        return {"h1": self.h1, "h2": self.h2, "Pi": self.P_i, "Pj": self.P_j}


# ======================================================================================= joints
class Spherical(Constraint):
    """Spherical joint (s,3): r_i + A_i s'ᴾ_i − r_j − A_j s'ᴾ_j = 0 (textbook §14.4).

    Parameters
    ----------
    i, j : str
    point : str, optional
        The joint centre when both bodies call it the same.
    point_i, point_j : str or 3 numbers, optional
    """

    type_name = "spherical"
    label = "s,3"
    n_eq = 3
    title = N_("spherical joint")
    measures = ("length", "length", "length")
    points = {"point_i": ("i", "P_i"), "point_j": ("j", "P_j")}
    aliases = {"point": ("point_i", "point_j")}
    parameters = ("P_i", "P_j")
    kernel = staticmethod(K.kernel(K.rows_s))

    def phi(self, Q, t=t_symbol):
        return list(self.global_point(Q[0], self.P_i) - self.global_point(Q[1], self.P_j))

    def params(self):
        return {"Pi": self.P_i, "Pj": self.P_j}


class Universal(Spherical):
    """Universal (Hooke) joint (s,3 + n1,1): a spherical joint whose cross arms stay perpendicular (§14.4).

    Parameters
    ----------
    i, j : str
    point, point_i, point_j : the centre P of the cross (see :class:`Spherical`)
    vector_i, vector_j : vector specs
        The cross arms: s'_i on body i, s'_j on body j; s_iᵀ s_j = 0.
    """

    type_name = "universal"
    title = N_("universal joint")
    parts = (Spherical, Normal1)
    vectors = Normal1.vectors


class Revolute(_ParallelMixin, Spherical):
    """Revolute joint (s,3 + p1,2): a point on the axis is shared and the axes stay parallel (§14.4).

    Parameters
    ----------
    i, j : str
    point, point_i, point_j : a point on the joint axis (see :class:`Spherical`)
    axis_i, axis_j : vector specs
        The joint axis in body i and in body j.
    """

    type_name = "revolute"
    title = N_("revolute joint")
    parts = (Spherical, Parallel1)
    vectors = {"axis_i": ("i", "a_i"), "axis_j": ("j", "a_j")}


class Cylindrical(_ParallelMixin, Constraint):
    """Cylindrical joint (p1,2 + p2,2): parallel axes, and P_j stays on the axis of body i (§14.4).

    Parameters
    ----------
    i, j : str
    axis_i, axis_j : vector specs
    point_i, point_j : points on the axis, P_i on body i and P_j on body j (they may coincide).
    """

    type_name = "cylindrical"
    title = N_("cylindrical joint")
    parts = (Parallel1, Parallel2)
    vectors = {"axis_i": ("i", "a_i"), "axis_j": ("j", "a_j")}
    points = Spherical.points
    aliases = Spherical.aliases


class Translational(Cylindrical):
    """Translational (prismatic) joint (p1,2 + p2,2 + n1,1): a cylindrical joint whose relative rotation is
    locked by two vectors h_i, h_j perpendicular to the axis that stay perpendicular (§14.4).

    Parameters
    ----------
    i, j, axis_i, axis_j, point, point_i, point_j : as :class:`Cylindrical`
    perp_i, perp_j : vector specs, optional
        h_i on body i and h_j on body j. Default h_i: a vector ⊥ axis_i; default h_j: the vector of body j
        that is perpendicular to both h_i and the axis at the bodies' q0 (so the joint holds its q0
        relative orientation).
    """

    type_name = "translational"
    title = N_("translational joint")
    parts = (Cylindrical, (Normal1, {"a_i": "hp_i", "a_j": "hp_j"}))
    vectors = {**Cylindrical.vectors, "perp_i": "i", "perp_j": "j"}
    defaults = {"perp_i": None, "perp_j": None}

    def _complete(self):
        super()._complete()
        self.hp_i = self.h1 if self.perp_i is None else self.perp_i
        u, h = self.a_i / np.linalg.norm(self.a_i), self.hp_i / np.linalg.norm(self.hp_i)
        if np.linalg.norm(np.cross(u, h)) < 1e-6:
            raise ModelError(f"{self.describe()}: perp_i is parallel to the axis; it must be perpendicular to it")
        if self.perp_j is None:
            Ai, Aj = (_A_q0(b) for b in self.bodies)
            g = Ai @ np.cross(self.a_i / np.linalg.norm(self.a_i), self.hp_i / np.linalg.norm(self.hp_i))
            self.hp_j = Aj.T @ g
        else:
            self.hp_j = self.perp_j


def _A_q0(body):
    """Rotation matrix of a body at its q0 (whose p the Body has normalized)."""
    return _A_sym(np.array([float(v) for v in body.q0[3:]]))


class SphericalSpherical(Constraint):
    """Spherical–spherical composite joint (s-s,1): a massless link of length l between P_i and P_j,
    dᵀd − l² = 0 (the spatial counterpart of the planar revolute–revolute joint)."""

    type_name = "spherical-spherical"
    label = "s-s,1"
    n_eq = 1
    title = N_("spherical-spherical joint")
    measures = ("length^2",)
    points = {"point_i": ("i", "P_i"), "point_j": ("j", "P_j")}
    numbers = ("length",)
    quantities = {"l": "length"}  # the l that Φ squares (the checkers name l for l²)
    parameters = ("P_i", "P_j", "l")
    kernel = staticmethod(K.kernel(K.rows_ss))

    def _complete(self):
        self.l = float(self.length)
        if not self.l > 0:
            raise ModelError(f"{self.describe()}: length must be a positive number, got {self.specs['length']!r}")

    def phi(self, Q, t=t_symbol):
        d = self._distance(Q, self.P_i, self.P_j)
        return [_sym_dot(d, d) - _num(self.l) ** 2]

    def params(self):
        return {"Pi": self.P_i, "Pj": self.P_j, "l": self.l}


# ======================================================================================= drivers
class RevoluteDriver(Constraint):
    """Rotation driver about a revolute axis: θ(q) − f(t) = 0.

    θ is the angle from the reference vector f_i of body i to the reference vector f_j of body j, measured
    about the axis u_i of body i (right-hand rule): θ = atan2(g_iᵀ f_j, f_iᵀ f_j), with f_i made
    perpendicular to u_i and g_i = u_i × f_i. The mechanism wraps Φ into (−π, π], so f(t) may grow without
    bound (a crank turning many times). Φ_q is regular while f_j is not parallel to the axis.

    Parameters
    ----------
    i, j : str
    axis_i : vector spec on body i
    f : str or number
        θ as a function of time, radians (e.g. ``"pi/4 + 2*pi*t"``).
    ref_i, ref_j : vector specs, optional
        Default ref_i: a vector ⊥ axis_i; default ref_j: the vector of body j that coincides with ref_i at
        the bodies' q0, so that θ(q0) = 0.
    """

    type_name = "revolute-driver"
    label = "d"
    n_eq = 1
    kind = "driver"
    title = N_("revolute driver")
    measures = ("angle",)
    wrap = {0: 2 * np.pi}
    vectors = {"axis_i": ("i", "a_i"), "ref_i": "i", "ref_j": "j"}
    defaults = {"ref_i": None, "ref_j": None}
    parameters = ("f_i", "g_i", "f_j")
    kernel = staticmethod(K.kernel(K.rows_angle))

    def _complete(self):
        u = self.a_i / np.linalg.norm(self.a_i)
        fi = _perpendiculars(u)[0] if self.ref_i is None else self.ref_i
        fi = fi - u * (u @ fi)
        if np.linalg.norm(fi) < 1e-9:
            raise ModelError(f"{self.describe()}: ref_i is parallel to the axis")
        self.f_i = fi / np.linalg.norm(fi)
        self.g_i = np.cross(u, self.f_i)
        if self.ref_j is None:
            Ai, Aj = (_A_q0(b) for b in self.bodies)
            self.f_j = Aj.T @ (Ai @ self.f_i)
        else:
            self.f_j = self.ref_j

    def phi(self, Q, t=t_symbol):
        fj = self.global_vector(Q[1], self.f_j)
        c = _sym_dot(self.global_vector(Q[0], self.f_i), fj)
        s = _sym_dot(self.global_vector(Q[0], self.g_i), fj)
        return [sp.atan2(s, c) - self._f_expr(t)]

    def params(self):
        return {"fi": self.f_i, "gi": self.g_i, "fj": self.f_j}


class DistanceDriver(Constraint):
    """Distance driver along a translational or cylindrical axis: u_iᵀ(r_j^P − r_i^P) − f(t) = 0.

    u_i is the unit vector of ``axis_i`` fixed in body i; the driver prescribes the distance of P_j from
    P_i measured along it.
    """

    type_name = "distance-driver"
    label = "d"
    n_eq = 1
    kind = "driver"
    title = N_("distance driver")
    measures = ("length",)
    vectors = {"axis_i": ("i", "a_i")}
    points = {"point_i": ("i", "P_i"), "point_j": ("j", "P_j")}
    parameters = ("u", "P_i", "P_j")
    kernel = staticmethod(K.kernel(K.rows_distance))

    def _complete(self):
        self.u = self.a_i / np.linalg.norm(self.a_i)

    def phi(self, Q, t=t_symbol):
        d = self._distance(Q, self.P_i, self.P_j)
        return [_sym_dot(self.global_vector(Q[0], self.u), d) - self._f_expr(t)]

    def params(self):
        return {"u": self.u, "Pi": self.P_i, "Pj": self.P_j}


CONSTRAINT_TYPES = constraint_types("spatial")
"""Constraint classes by the ``type`` name used in mechanism files: a live, read-only view of the spatial
registry (normalization rows are added by the mechanism, one per body, and cannot be declared)."""
