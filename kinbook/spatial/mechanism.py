"""Spatial mechanisms: bodies with Euler parameters, constraints, the symbolic model and the fast numeric
assembly (textbook §14.5).

Coordinates are q = [x1, y1, z1, e01, e11, e21, e31, x2, …]: seven per body, in the order the bodies were
added. Each :meth:`Mechanism.add_body` also adds that body's normalization equation pᵀp − 1 = 0 (a row of
kind "normalization", counted as geometric), so rows of Φ follow the order of the ``add_body`` and ``add``
calls. A mechanism file lists its bodies first, so its normalization rows come first.

The assembly, the symbolic model and the analysis entry points (Newton–Raphson, velocity, acceleration,
sweeps, diagnosis) are shared with the planar half in :mod:`kinbook.core`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from ..core.mechanism import ConstraintTable, MechanismBase
from ..core.reader import read_constant
from ..errors import InputError, ModelError
from . import rotations, transforms
from .arrays import P_TOL, shapes, vec3
from .constraints import NCOORD, Constraint, Normalization

__all__ = ["Body", "Mechanism", "ConstraintTable"]

_COORDS = ("x", "y", "z", "e0", "e1", "e2", "e3")
_IDENTITY = (0, 0, 0, 1, 0, 0, 0)


def _number(v, what):
    return read_constant(v, where=what)


def _triple(v, what):
    try:
        if isinstance(v, (str, bytes, dict)):
            raise TypeError
        a, b, c = v
    except (TypeError, ValueError):
        raise ModelError(f"{what}: expected three numbers (ξ, η, ζ), got {v!r}") from None
    return (_number(a, what), _number(b, what), _number(c, what))


@dataclass
class Body:
    """A rigid body: a name, named local points (ξ, η, ζ), named local vectors and an initial guess
    q0 = (x, y, z, e0, e1, e2, e3).

    The Euler parameters of q0 are an initial guess for Newton–Raphson: they are *normalized* here
    (divided by their norm, so [1, 0, 0, 1] means a 90° turn about z); p = 0 raises ModelError.
    ``number`` is the body's 1-based position: the subscript of x_i … e3_i.
    """

    name: str
    points: dict = field(default_factory=dict)
    q0: tuple = _IDENTITY
    vectors: dict = field(default_factory=dict)
    number: int = 0

    def __post_init__(self):
        for what, table in (("points", self.points), ("vectors", self.vectors)):
            if not isinstance(table, dict):
                raise ModelError(f"body '{self.name}': `{what}` must be a table of name = [ξ, η, ζ], got {table!r}")
        self.points = {str(k): _triple(v, f"point '{k}' of body '{self.name}'") for k, v in dict(self.points).items()}
        self.vectors = {str(k): _triple(v, f"vector '{k}' of body '{self.name}'") for k, v in dict(self.vectors).items()}
        for k, v in self.vectors.items():
            if all(x == 0 for x in v):
                raise ModelError(f"vector '{k}' of body '{self.name}' is zero")
        if not isinstance(self.q0, (list, tuple, np.ndarray)) or len(self.q0) != NCOORD:
            got = f"{len(self.q0)}" if isinstance(self.q0, (list, tuple, np.ndarray)) else repr(self.q0)
            raise ModelError(f"body '{self.name}': q0 must have 7 values (x, y, z, e0, e1, e2, e3), got {got}")
        q0 = [_number(v, f"q0 of body '{self.name}' ({c})") for v, c in zip(self.q0, _COORDS)]
        norm = sp.sqrt(sum(v**2 for v in q0[3:]))
        if float(norm) < 1e-12:
            raise ModelError(f"body '{self.name}': the Euler parameters of q0 are all zero (they describe no rotation)")
        if norm != 1:
            q0[3:] = [sp.Float(float(v / norm), 17) for v in q0[3:]]
        self.q0 = tuple(q0)


class Mechanism(MechanismBase):
    """A spatial mechanism in body coordinates with Euler parameters (textbook §14.5).

    Build it in code or load it from a mechanism file (``kind = "spatial"``) with :func:`kinbook.load`.

    Examples
    --------
    >>> from kinbook.spatial import Mechanism, Ground, Revolute, RevoluteDriver
    >>> m = Mechanism("pendulum")
    >>> m.add_body("ground", points={"O": (0, 0, 0)})
    >>> m.add_body("bar", points={"O": (-1, 0, 0), "T": (1, 0, 0)}, q0=(1, 0, 0, 1, 0, 0, 0))
    >>> m.add(Ground("ground"))
    >>> m.add(Revolute("ground", "bar", point="O", axis_i=(0, 0, 1), axis_j=(0, 0, 1)))
    >>> m.add(RevoluteDriver("ground", "bar", axis_i=(0, 0, 1), f="t"))
    >>> m.n, m.m, m.dof
    (14, 14, 1)
    >>> m.point_position(m.solve_position(t=0.5), "bar", "T").round(6)  # 2 (cos 0.5, sin 0.5, 0)
    array([1.755165, 0.958851, 0.      ])
    """

    COORDS = _COORDS
    POINT_DIM = 3
    constraint_base = Constraint
    kind = "spatial"

    # ------------------------------------------------------------------------------------------- building
    def add_body(self, name, points=None, q0=_IDENTITY, vectors=None):
        """Add a body and its normalization equation pᵀp − 1 = 0. Returns ``None``.

        Parameters
        ----------
        name : str
        points : dict of name -> (ξ, η, ζ), optional
            Local coordinates of named points.
        q0 : sequence of 7 numbers
            Initial guess (x, y, z, e0, e1, e2, e3); p is normalized (see :class:`Body`).
        vectors : dict of name -> 3 components, optional
            Named body-fixed vectors (axes of joints), local components.
        """
        name = str(name)
        self._new_body(Body(name, {} if points is None else points, q0, {} if vectors is None else vectors,
                            number=len(self.bodies) + 1))
        self._add(Normalization(name, name=f"normalization {name}"))

    def add(self, constraint):
        """Add a constraint; its equations take the next rows of Φ. Returns ``None``."""
        if isinstance(constraint, Normalization):
            raise ModelError("normalization equations are added with their body by add_body; do not add them")
        super().add(constraint)

    def _check_removable(self, c):
        if c.kind == "normalization":
            raise ModelError(f"{c.describe()} belongs to body '{c.body_names[0]}' and cannot be removed")

    def jacobian_blocks(self, constraint, q):
        """The Jacobian blocks Φ_r_i, Φ_p_i, Φ_r_j, Φ_p_j of one constraint at ``q`` (Table 14.1).

        Parameters
        ----------
        constraint : str or Constraint
        q : array_like, shape (n,)

        Returns
        -------
        dict
            ``{"r_i": (n_eq, 3), "p_i": (n_eq, 4), "r_j": (n_eq, 3), "p_j": (n_eq, 4)}`` (only "r_i", "p_i" for a
            one-body constraint).
        """
        c = self._constraint(constraint)
        q = self.check_q(q)
        if q.ndim != 1:
            raise InputError(f"`q` must be one configuration of shape ({self.n},), got {q.shape}")
        return c.blocks(np.concatenate([self._body_q(q, b.name) for b in c.bodies]))

    # ------------------------------------------------------------------------------------------- bodies and points
    def _pq(self, q, body, name="q", unit=True):
        qb = self._body_q(self.check_q(q, name), body)
        if unit:
            norm = np.linalg.norm(qb[..., 3:], axis=-1)
            if np.any(np.abs(norm - 1) > P_TOL):
                raise InputError(f"`{name}`: the Euler parameters of body '{body}' do not have unit norm "
                                 f"(|p| = {float(np.ravel(norm)[0]):.9g}); solve the position first")
        return qb

    def r(self, q, body):
        """Global position of the body's origin, shape (3,) or (N, 3)."""
        return self._pq(q, body, unit=False)[..., :3].copy()

    def p(self, q, body):
        """Euler parameters of the body, shape (4,) or (N, 4)."""
        return self._pq(q, body, unit=False)[..., 3:].copy()

    def A(self, q, body):
        """Rotation matrix of the body (local → global), shape (3, 3) or (N, 3, 3)."""
        return rotations.A_from_p(self._pq(q, body)[..., 3:])

    def moved(self, q, body, axis=(0.0, 0.0, 1.0), angle=0.0, about=None, shift=(0.0, 0.0, 0.0)):
        """``q`` with one body moved rigidly: turned by ``angle`` about the line through ``about`` along
        ``axis`` (global), then shifted by ``shift``. The other bodies stay where they are.

        A quick way to test a joint: a motion it allows keeps its rows of Φ at zero, a motion it forbids
        does not (notebook 14-4). The body's Euler parameters are composed (p_turn ⊗ p), so they stay
        continuous with the original ones.

        Parameters
        ----------
        q : array_like, shape (n,)
        body : str
        axis : array_like, shape (3,)
            Direction of the rotation axis (any length but zero).
        angle : float
            Radians, right-handed about ``axis``.
        about : array_like, shape (3,), optional
            A point on the axis; default the body's reference point r.
        shift : array_like, shape (3,), or 0

        Returns
        -------
        ndarray, shape (n,)

        Examples
        --------
        >>> import numpy as np, kinbook
        >>> m = kinbook.examples.load("spatial_fourbar")
        >>> q = m.moved(m.q0, "crank", axis=(0, 0, 1), angle=np.pi / 2, about=(0, 0, 0))
        >>> A0, A1 = m.point_position(m.q0, "crank", "A"), m.point_position(q, "crank", "A")
        >>> bool(np.allclose(A1, [-A0[1], A0[0], A0[2]]))  # a quarter turn about Z
        True
        """
        q = self.check_q(q)
        if q.ndim != 1:
            raise InputError(f"`q` must be one configuration of shape ({self.n},), got {q.shape}")
        b = self.body(body)
        k = NCOORD * (b.number - 1)
        turn = rotations.p_from_axis_angle(axis, angle)
        r, p = q[k : k + 3], q[k + 3 : k + 7]
        centre = r if about is None else vec3(about, "about")
        R = rotations.A_from_p(turn)
        out = q.copy()
        if np.ndim(shift) == 0 and shift == 0:
            shift = (0.0, 0.0, 0.0)
        out[k : k + 3] = centre + R @ (r - centre) + vec3(shift, "shift")
        t0, t = turn[0], turn[1:]
        e0, e = p[0], p[1:]
        out[k + 3] = t0 * e0 - t @ e  # Euler parameters compose like quaternions: A(p_turn ⊗ p) = A(p_turn) A(p)
        out[k + 4 : k + 7] = t0 * e + e0 * t + np.cross(t, e)
        return out

    @shapes
    def point_position(self, q, body, point):
        """Global position r^P = r + A s'^P of a body point, shape (3,) or (N, 3)."""
        qb = self._pq(q, body)
        return transforms.point_position(qb[..., :3], qb[..., 3:], self.point_local(body, point))

    @shapes
    def point_velocity(self, q, qd, body, point):
        """Global velocity ṙ^P = ṙ + ∂(A s'^P)/∂p ṗ (= ṙ + ω × A s'^P) of a body point."""
        qb, vb = self._pq(q, body), self._pq(qd, body, "qd", unit=False)
        return transforms.point_velocity(vb[..., :3], qb[..., 3:], vb[..., 3:], self.point_local(body, point))

    @shapes
    def point_acceleration(self, q, qd, qdd, body, point):
        """Global acceleration r̈^P = r̈ + ∂(A s')/∂p p̈ + ∂(A s')/∂p|_ṗ ṗ (= r̈ + α × s + ω × (ω × s))."""
        qb, vb = self._pq(q, body), self._pq(qd, body, "qd", unit=False)
        ab = self._pq(qdd, body, "qdd", unit=False)
        return transforms.point_acceleration(ab[..., :3], qb[..., 3:], vb[..., 3:], ab[..., 3:],
                                             self.point_local(body, point))

    @shapes
    def angular_velocity(self, q, qd, body, frame="global"):
        """Angular velocity of a body: ω = 2 E ṗ (global) or ω' = 2 G ṗ (body components), shape (…, 3)."""
        qb, vb = self._pq(q, body), self._pq(qd, body, "qd", unit=False)
        return rotations.omega_from_p_dot(qb[..., 3:], vb[..., 3:], frame)

    @shapes
    def angular_acceleration(self, q, qdd, body, frame="global"):
        """Angular acceleration of a body: α = 2 E p̈ (global) or α' = 2 G p̈ (body), shape (…, 3)."""
        qb, ab = self._pq(q, body), self._pq(qdd, body, "qdd", unit=False)
        return rotations.alpha_from_p(qb[..., 3:], ab[..., 3:], frame)

    # ------------------------------------------------------------------------------------------- tables
    def _type_cell(self, c):
        return f"{c.type_name} ({c.label})"

    def _table_footer(self):
        n_norm = sum(1 for c in self.constraints if c.kind == "normalization")
        return (f"n = {self.n} coordinates, m = {self.m_geometric - n_norm} geometric + {n_norm} normalization + "
                f"{self.m - self.m_geometric} driver equations, DOF = n − geometric − normalization = {self.dof}"
                + self._overconstrained_note())
