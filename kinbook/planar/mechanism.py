"""Planar mechanisms: bodies with (x, y, φ) and their point kinematics. The assembly, the symbolic model and
the analysis entry points are shared with the spatial half in :mod:`kinbook.core`.

Coordinates are q = [x1, y1, φ1, x2, y2, φ2, …] in the order the bodies were added, as the book numbers its
bodies (ground first in the book's examples). Rows of Φ follow the order in which constraints were added.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..core.mechanism import ConstraintTable, MechanismBase
from ..core.reader import read_constant
from ..errors import ModelError
from . import transforms
from .constraints import Constraint, Revolute

__all__ = ["Body", "Mechanism", "ConstraintTable"]

_COORDS = ("x", "y", "phi")


@dataclass
class Body:
    """A rigid body: a name, named local points (ξ, η) and an initial guess q0 = (x, y, φ).

    ``number`` is the body's 1-based position in the mechanism: the subscript of its coordinates x_i, y_i, φ_i.
    """

    name: str
    points: dict = field(default_factory=dict)
    q0: tuple = (0, 0, 0)
    number: int = 0

    def __post_init__(self):
        if not isinstance(self.points, dict):
            raise ModelError(f"body '{self.name}': `points` must be a table of name = [ξ, η], got {self.points!r}")
        self.points = {str(k): _pair(v, f"point '{k}' of body '{self.name}'") for k, v in dict(self.points).items()}
        q0 = tuple(self.q0)
        if len(q0) != 3:
            raise ModelError(f"body '{self.name}': q0 must have 3 values (x, y, phi), got {len(q0)}")
        self.q0 = tuple(_number(v, f"q0 of body '{self.name}' ({c})") for v, c in zip(q0, _COORDS))


def _number(v, what, symbols=False):
    """A finite real number as a sympy number; with ``symbols``, a symbolic parameter such as ξ_i is accepted
    too (for symbolic derivations; numeric evaluation then refuses the mechanism). Text is read by
    :func:`kinbook.core.reader.read_constant`."""
    return read_constant(v, where=what, symbolic=symbols)


def _pair(v, what):
    try:
        if isinstance(v, (str, bytes, dict)):
            raise TypeError
        a, b = v
    except (TypeError, ValueError):
        raise ModelError(f"{what}: expected a pair (ξ, η), got {v!r}") from None
    return (_number(a, what, symbols=True), _number(b, what, symbols=True))


class Mechanism(MechanismBase):
    """A planar mechanism in body coordinates.

    Build it in code or load it from a mechanism file with :func:`kinbook.load`.

    Examples
    --------
    >>> from kinbook.planar import Mechanism, Ground, Revolute, Driver
    >>> m = Mechanism("pendulum")
    >>> m.add_body("ground", points={"O": (0, 0)})
    >>> m.add_body("bar", points={"O": (-1, 0)}, q0=(1, 0, 0))
    >>> m.add(Ground("ground")); m.add(Revolute("ground", "bar", point="O")); m.add(Driver("bar", "phi", "t"))
    >>> m.dof, m.n, m.m
    (1, 6, 6)
    >>> m.solve_position(t=0.5).round(6)
    array([0.      , 0.      , 0.      , 0.877583, 0.479426, 0.5     ])
    """

    COORDS = _COORDS
    constraint_base = Constraint
    kind = "planar"

    def add_body(self, name, points=None, q0=(0, 0, 0)):
        """Add a body; its coordinates follow those of the bodies already added. Returns ``None``."""
        name = str(name)
        try:
            if isinstance(q0, (str, bytes, dict)):
                raise TypeError
            q0 = tuple(q0)
        except TypeError:
            raise ModelError(f"body '{name}': q0 must be a list (x, y, phi), got {q0!r}") from None
        self._new_body(Body(name, points if points is not None else {}, q0, number=len(self.bodies) + 1))

    def validate(self):
        """Refuse a body joined to two or more bodies only by revolute joints, all at one point: a link of zero
        length (a zero-length crank), which transmits no motion and makes Φ_q singular. Raises
        :class:`~kinbook.errors.ModelError`."""
        joints = {}
        for c in self.constraints:
            for role, body in enumerate(c.bodies or ()):
                joints.setdefault(body.name, []).append((c, role))
        for body in self.bodies:
            held = joints.get(body.name, [])
            pins = [(c, role) for c, role in held if isinstance(c, Revolute)]
            others = [c for c, _ in held if not isinstance(c, Revolute) and c.kind != "driver"]
            if len(pins) < 2 or others:
                continue
            points = {tuple(c.s_i if role == 0 else c.s_j) for c, role in pins}
            partners = {c.bodies[1 - role].name for c, role in pins}
            if len(points) == 1 and len(partners) > 1:
                where = ", ".join(f"'{c.name}'" for c, _ in pins)
                (xi, eta), = points
                raise ModelError(
                    f"body '{body.name}' is a link of zero length: its revolute joints {where} (to bodies "
                    f"{', '.join(sorted(repr(p) for p in partners))}) are all at its point ({xi}, {eta}); a link "
                    "transmits motion only between joints set apart — give the points their distinct coordinates")

    # ------------------------------------------------------------------------------------------- points
    def point_position(self, q, body, point):
        """Global position r^P = r + A s'^P of a body point, shape (2,) or (N, 2)."""
        qb = self._body_q(self.check_q(q), body)
        return transforms.point_position(qb[..., :2], qb[..., 2], self.point_local(body, point))

    def point_velocity(self, q, qd, body, point):
        """Global velocity ṙ^P = ṙ + B s'^P φ̇ of a body point."""
        qb, vb = self._body_q(self.check_q(q), body), self._body_q(self.check_q(qd, "qd"), body)
        return transforms.point_velocity(vb[..., :2], qb[..., 2], vb[..., 2], self.point_local(body, point))

    def point_acceleration(self, q, qd, qdd, body, point):
        """Global acceleration r̈^P = r̈ + B s'^P φ̈ − A s'^P φ̇² of a body point."""
        qb = self._body_q(self.check_q(q), body)
        vb = self._body_q(self.check_q(qd, "qd"), body)
        ab = self._body_q(self.check_q(qdd, "qdd"), body)
        return transforms.point_acceleration(ab[..., :2], qb[..., 2], vb[..., 2], ab[..., 2], self.point_local(body, point))
