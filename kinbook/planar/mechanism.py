"""Planar mechanisms: bodies, constraints, the symbolic model and the fast numeric assembly.

Coordinates are q = [x1, y1, φ1, x2, y2, φ2, …] in the order the bodies were added, as the book numbers its
bodies (ground first in the book's examples). Rows of Φ follow the order in which constraints were added.
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sps
import sympy as sp

from ..errors import InputError, ModelError, UnknownBodyError
from ..symbolic import derive, t as t_symbol, time_derivatives
from . import analysis
from .constraints import Constraint

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
        self.q0 = tuple(_number(v, f"q0 of body '{self.name}'") for v in q0)


def _number(v, what, symbols=False):
    """A finite real number as a sympy number; with ``symbols``, a symbolic parameter such as ξ_i is accepted
    too (for symbolic derivations; numeric evaluation then refuses the mechanism)."""
    try:
        e = sp.sympify(v)
    except (sp.SympifyError, TypeError, SyntaxError):
        raise ModelError(f"{what}: cannot read {v!r} as a number") from None
    if symbols and e.free_symbols and isinstance(e, sp.Expr):
        return e
    if e.free_symbols or not e.is_number or not e.is_finite or not e.is_real:
        raise ModelError(f"{what}: expected a finite real number, got {v!r}")
    return e


def _pair(v, what):
    try:
        a, b = v
    except (TypeError, ValueError):
        raise ModelError(f"{what}: expected a pair (ξ, η), got {v!r}") from None
    return (_number(a, what, symbols=True), _number(b, what, symbols=True))


class _Group:
    """All constraints sharing a kernel and a number of bodies: index maps and stacked parameters."""

    def __init__(self, constraints, n):
        c0 = constraints[0]
        self.kernel = c0.kernel
        self.constraints = constraints
        nb = len(c0.bodies)
        cols = np.array([[3 * (b.number - 1) + k for b in c.bodies for k in range(3)] for c in constraints])
        rows = np.array([list(range(c.rows.start, c.rows.stop)) for c in constraints])
        self.cols, self.rows = cols, rows  # (k, 3nb), (k, r)
        self.nb = nb
        self.jac_rows = np.broadcast_to(rows[:, :, None], rows.shape + (cols.shape[1],)).ravel()
        self.jac_cols = np.broadcast_to(cols[:, None, :], rows.shape + (cols.shape[1],)).ravel()
        self.flat = self.jac_rows * n + self.jac_cols
        plist = [c.params() for c in constraints]
        self.params = {key: np.array([p[key] for p in plist], dtype=float) for key in plist[0]}

    def gather(self, q):
        Bn = q.shape[0]
        return q[:, self.cols].reshape(Bn, len(self.constraints), self.nb, 3)


class Mechanism:
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

    def __init__(self, name="mechanism", title=None):
        self.name = name
        self.title = title or name
        self.bodies: list[Body] = []
        self.constraints: list[Constraint] = []
        self._by_name: dict[str, Body] = {}

    # ------------------------------------------------------------------------------------------- building
    def add_body(self, name, points=None, q0=(0, 0, 0)):
        """Add a body; its coordinates follow those of the bodies already added. Returns ``None``."""
        name = str(name)
        if name in self._by_name:
            raise ModelError(f"mechanism '{self.name}' already has a body named '{name}'")
        try:
            q0 = tuple(q0)
        except TypeError:
            raise ModelError(f"body '{name}': q0 must be a list (x, y, phi), got {q0!r}") from None
        body = Body(name, points if points is not None else {}, q0, number=len(self.bodies) + 1)
        self.bodies.append(body)
        self._by_name[name] = body
        self._invalidate()

    def add(self, constraint):
        """Add a constraint; its equations take the next rows of Φ. Returns ``None``."""
        if not isinstance(constraint, Constraint):
            raise ModelError(f"expected a planar constraint, got {constraint!r}")
        start = self.m
        constraint.rows = slice(start, start + constraint.n_eq)
        if constraint.name is None:
            constraint.name = self._default_name(constraint)
        if any(c.name == constraint.name for c in self.constraints):
            raise ModelError(f"mechanism '{self.name}' already has a constraint named '{constraint.name}'")
        try:
            constraint.bind(self)
        except Exception:
            constraint.rows = None
            raise
        self.constraints.append(constraint)
        self._invalidate()

    def remove(self, name):
        """Remove the constraint called ``name``; the rows of the constraints after it move up. Returns it."""
        c = self.constraint(name)
        self.constraints.remove(c)
        c.rows = None
        start = 0
        for k in self.constraints:
            k.rows = slice(start, start + k.n_eq)
            start += k.n_eq
        self._invalidate()
        return c

    def _default_name(self, c):
        if c.kind == "joint":
            return str(sum(1 for k in self.constraints if k.kind == "joint") + 1)
        if c.kind == "driver":
            return f"driver {sum(1 for k in self.constraints if k.kind == 'driver') + 1}"
        base = c.type_name if c.type_name == "ground" else f"{c.type_name} {c.body_names[0]} {c.coordinate}"
        taken = {k.name for k in self.constraints}
        return base if base not in taken else f"{base} {c.body_names[0]}"

    def body(self, name, context=None):
        """The :class:`Body` called ``name``."""
        try:
            return self._by_name[str(name)]
        except KeyError:
            where = f"{context.describe()}: " if context is not None else ""
            known = ", ".join(repr(b.name) for b in self.bodies) or "none"
            raise UnknownBodyError(
                f"{where}mechanism '{self.name}' has no body '{name}' (its bodies: {known})"
            ) from None

    def constraint(self, name):
        """The constraint called ``name``."""
        for c in self.constraints:
            if c.name == str(name):
                return c
        known = ", ".join(repr(c.name) for c in self.constraints)
        raise ModelError(f"mechanism '{self.name}' has no constraint '{name}' (its constraints: {known})")

    def _invalidate(self):
        for attr in ("_compiled", "_symbolic", "q", "qd", "_q0", "_sizes"):
            self.__dict__.pop(attr, None)

    # ------------------------------------------------------------------------------------------- sizes
    @property
    def n(self):
        """Number of coordinates, 3 per body."""
        return 3 * len(self.bodies)

    @property
    def _counts(self):
        if "_sizes" not in self.__dict__:
            self._sizes = (sum(c.n_eq for c in self.constraints),
                           sum(c.n_eq for c in self.constraints if c.kind != "driver"))
        return self._sizes

    @property
    def m(self):
        """Number of constraint equations, drivers included."""
        return self._counts[0]

    @property
    def drivers(self):
        return [c for c in self.constraints if c.kind == "driver"]

    @property
    def m_geometric(self):
        """Number of constraint equations that are not drivers."""
        return self._counts[1]

    @property
    def dof(self):
        """Degrees of freedom n − m of the geometric constraints (drivers excluded)."""
        return self.n - self.m_geometric

    def coordinate_names(self):
        """['x1', 'y1', 'phi1', 'x2', …]"""
        return [f"{c}{b.number}" for b in self.bodies for c in _COORDS]

    def index(self, coordinate):
        """Position in q of a coordinate given as 'phi2' or (body name, 'phi')."""
        if isinstance(coordinate, tuple):
            body, c = coordinate
            if c not in _COORDS:
                raise InputError(f"coordinate must be one of x, y, phi, got {c!r}")
            return 3 * (self.body(body).number - 1) + _COORDS.index(c)
        names = self.coordinate_names()
        if coordinate not in names:
            raise InputError(f"mechanism '{self.name}' has no coordinate {coordinate!r} (it has {names[0]} … {names[-1]})")
        return names.index(coordinate)

    @property
    def q0(self):
        """The initial guess: the bodies' q0 stacked, as floats (a fresh copy)."""
        if "_q0" not in self.__dict__:
            self._q0 = np.array([float(v) for b in self.bodies for v in b.q0])
        return self._q0.copy()

    # ------------------------------------------------------------------------------------------- symbols
    @cached_property
    def q(self):
        """Coordinates as a sympy column matrix: x1, y1, phi1, x2, …"""
        return sp.Matrix([sp.Symbol(s, real=True) for s in self.coordinate_names()])

    @cached_property
    def qd(self):
        """Velocities as a sympy column matrix: dx1, dy1, dphi1, …"""
        return sp.Matrix([sp.Symbol("d" + s, real=True) for s in self.coordinate_names()])

    @property
    def t(self):
        """The time symbol."""
        return t_symbol

    def body_symbols(self, body):
        """(x_i, y_i, φ_i) of a body as a sympy column matrix."""
        k = 3 * (self.body(body).number - 1)
        return self.q[k : k + 3, 0]

    def constraint_phi(self, constraint):
        """Symbolic Φ rows of one constraint (a name or the object), in this mechanism's symbols."""
        c = constraint if isinstance(constraint, Constraint) else self.constraint(constraint)
        Q = [self.body_symbols(b.name) for b in c.bodies]
        return sp.Matrix(c.phi(Q, t_symbol))

    def symbolic(self):
        """Φ, Φ_q, ν and γ as sympy matrices (a :class:`kinbook.symbolic.Derivation`), derived from Φ."""
        if "_symbolic" not in self.__dict__:
            Phi = sp.Matrix.vstack(*[self.constraint_phi(c) for c in self.constraints]) if self.constraints else sp.zeros(0, 1)
            self._symbolic = derive(Phi, self.q, self.qd, t_symbol)
        return self._symbolic

    # ------------------------------------------------------------------------------------------- numerics
    @property
    def _compiled(self):
        if "_compiled" not in self.__dict__:
            if not self.bodies:
                raise ModelError(f"mechanism '{self.name}' has no bodies")
            groups = {}
            for c in self.constraints:
                groups.setdefault((c.kernel, len(c.bodies), c.n_eq), []).append(c)
            for c in self.constraints:
                params = {s for b in c.bodies for p in b.points.values() for v in p for s in v.free_symbols}
                if params:
                    names = ", ".join(sorted(map(str, params)))
                    raise ModelError(f"{c.describe()} has symbolic parameters ({names}): substitute numbers "
                                     "before a numeric evaluation")
            drivers = [(c.rows.stop - 1, *time_derivatives(c.f)) for c in self.constraints if c.f is not None]
            self.__dict__["_compiled"] = ([_Group(g, self.n) for g in groups.values()], drivers)
        return self.__dict__["_compiled"]

    def _check_q(self, q, name="q"):
        try:
            q = np.asarray(q, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"`{name}` must be an array of {self.n} numbers") from None
        if q.shape[-1:] != (self.n,) or q.ndim > 2:
            raise InputError(
                f"`{name}` must have shape ({self.n},) or (N, {self.n}) for mechanism '{self.name}' "
                f"({len(self.bodies)} bodies × 3 coordinates), got {q.shape}"
            )
        bad = ~np.isfinite(q)
        if bad.any():
            k = int(np.argwhere(bad)[0][-1])
            raise InputError(f"`{name}` has a non-finite value in {self.coordinate_names()[k]}: {q[..., k]}")
        return q

    def _check_t(self, t, batch):
        t = np.asarray(t, dtype=float)
        if not np.all(np.isfinite(t)):
            raise InputError(f"`t` must be finite, got {t}")
        if t.ndim > 1 or (t.ndim == 1 and t.shape[0] != batch):
            raise InputError(f"`t` must be a number or have shape ({batch},), got {t.shape}")
        return np.broadcast_to(t, (batch,))

    def evaluate(self, q, t=0.0, qd=None, *, jacobian=True, sparse=False):
        """Evaluate Φ, Φ_q, ν and (when ``qd`` is given) γ at once, for one or many instants.

        This is the fast path every analysis uses. ``q`` has shape (n,) or (N, n); ``t`` is a number or has
        shape (N,).

        Returns
        -------
        dict with 'Phi' (…, m), 'Phi_q' (…, m, n) or a scipy CSR matrix when ``sparse`` (single instant),
        'nu' (…, m) and 'gamma' (…, m).
        """
        q = self._check_q(q)
        single = q.ndim == 1
        qb = q[None] if single else q
        Bn = qb.shape[0]
        tb = self._check_t(t, Bn)
        qdb = None
        if qd is not None:
            qd = self._check_q(qd, "qd")
            qdb = qd[None] if qd.ndim == 1 else qd
            if qdb.shape[0] != Bn:
                raise InputError(f"`qd` has {qdb.shape[0]} rows but `q` has {Bn}")
        m, n = self.m, self.n
        groups, drivers = self._compiled
        Phi = np.zeros((Bn, m))
        gamma = np.zeros((Bn, m)) if qdb is not None else None
        nu = np.zeros((Bn, m))
        values = []
        for g in groups:
            phi, jac, gam = g.kernel(g.gather(qb), g.params, None if qdb is None else g.gather(qdb))
            Phi[:, g.rows] = phi
            if gam is not None:
                gamma[:, g.rows] = gam
            values.append(jac.reshape(Bn, -1))
        for row, f0, f1, f2 in drivers:
            Phi[:, row] -= f0(tb)
            nu[:, row] = f1(tb)
            if gamma is not None:
                gamma[:, row] += f2(tb)
        out = {"Phi": Phi, "nu": nu, "gamma": gamma}
        if jacobian:
            if sparse:
                if not single:
                    raise InputError("a sparse Φ_q is available for one instant at a time")
                rows = np.concatenate([g.jac_rows for g in groups])
                cols = np.concatenate([g.jac_cols for g in groups])
                data = np.concatenate([v[0] for v in values])
                out["Phi_q"] = sps.csr_matrix((data, (rows, cols)), shape=(m, n))
            else:
                J = np.zeros((Bn, m * n))
                for g, v in zip(groups, values):
                    J[:, g.flat] = v
                out["Phi_q"] = J.reshape(Bn, m, n)
        if single:
            out = {k: (v[0] if isinstance(v, np.ndarray) else v) for k, v in out.items()}
        return out

    def Phi(self, q, t=0.0):
        """Numeric Φ(q, t), shape (m,) (or (N, m) for a batch of configurations)."""
        return self.evaluate(q, t, jacobian=False)["Phi"]

    def Phi_q(self, q, t=0.0, sparse=False):
        """Numeric Jacobian Φ_q(q, t), shape (m, n); a scipy CSR matrix when ``sparse``."""
        return self.evaluate(q, t, sparse=sparse)["Phi_q"]

    def nu(self, q, t=0.0):
        """Numeric ν = −Φ_t, the right-hand side of the velocity equations Φ_q q̇ = ν."""
        return self.evaluate(q, t, jacobian=False)["nu"]

    def gamma(self, q, qd, t=0.0):
        """Numeric γ, the right-hand side of the acceleration equations Φ_q q̈ = γ."""
        return self.evaluate(q, t, qd, jacobian=False)["gamma"]

    # ------------------------------------------------------------------------------------------- points
    def point_local(self, body, point):
        """Local coordinates (ξ, η) of a named point, as floats."""
        b = self.body(body)
        if isinstance(point, str):
            if point not in b.points:
                from ..errors import UnknownPointError

                known = ", ".join(sorted(b.points)) or "none"
                raise UnknownPointError(f"body '{b.name}' has no point '{point}' (its points: {known})")
            return np.array([float(v) for v in b.points[point]])
        return np.asarray(point, dtype=float)

    def _body_q(self, arr, body):
        k = 3 * (self.body(body).number - 1)
        return arr[..., k : k + 3]

    def point_position(self, q, body, point):
        """Global position r^P = r + A s'^P of a body point, shape (2,) or (N, 2)."""
        from .transforms import point_position

        qb = self._body_q(self._check_q(q), body)
        return point_position(qb[..., :2], qb[..., 2], self.point_local(body, point))

    def point_velocity(self, q, qd, body, point):
        """Global velocity ṙ^P = ṙ + B s'^P φ̇ of a body point."""
        from .transforms import point_velocity

        qb, vb = self._body_q(self._check_q(q), body), self._body_q(self._check_q(qd, "qd"), body)
        return point_velocity(vb[..., :2], qb[..., 2], vb[..., 2], self.point_local(body, point))

    def point_acceleration(self, q, qd, qdd, body, point):
        """Global acceleration r̈^P = r̈ + B s'^P φ̈ − A s'^P φ̇² of a body point."""
        from .transforms import point_acceleration

        qb = self._body_q(self._check_q(q), body)
        vb = self._body_q(self._check_q(qd, "qd"), body)
        ab = self._body_q(self._check_q(qdd, "qdd"), body)
        return point_acceleration(ab[..., :2], qb[..., 2], vb[..., 2], ab[..., 2], self.point_local(body, point))

    # ------------------------------------------------------------------------------------------- analysis
    def constraint_table(self):
        """The book's joint table: joint number, bodies i and j, type, number of equations, rows of Φ."""
        return ConstraintTable(self)

    def check_drivers(self):
        """Raise :class:`~kinbook.errors.DriverCountError` unless there are exactly as many driver equations
        as degrees of freedom."""
        analysis.check_drivers(self)

    def solve_position(self, t=0.0, q0=None, tol=1e-10, max_iter=50):
        """Newton–Raphson solution of Φ(q, t) = 0 from ``q0`` (default: the bodies' q0). See
        :func:`kinbook.planar.analysis.solve_position`."""
        return analysis.solve_position(self, t, q0=q0, tol=tol, max_iter=max_iter)

    def solve_velocity(self, q, t=0.0):
        """Solve Φ_q q̇ = ν for q̇."""
        return analysis.solve_velocity(self, q, t)

    def solve_acceleration(self, q, qd, t=0.0):
        """Solve Φ_q q̈ = γ for q̈."""
        return analysis.solve_acceleration(self, q, qd, t)

    def simulate(self, times, q0=None, tol=1e-10, on_failure="raise", anchor_every=512):
        """Position, velocity and acceleration at every instant of ``times``: a
        :class:`~kinbook.planar.analysis.SimulationResult`. See :func:`kinbook.planar.analysis.simulate`."""
        return analysis.simulate(self, times, q0=q0, tol=tol, on_failure=on_failure, anchor_every=anchor_every)

    def diagnose(self, q, t=0.0):
        """Rank of Φ_q at ``q`` and, when singular, which constraints are dependent: see
        :func:`kinbook.planar.analysis.diagnose`."""
        return analysis.diagnose(self, q, t)

    def __repr__(self):
        return (f"<Mechanism '{self.name}': {len(self.bodies)} bodies, n = {self.n} coordinates, "
                f"m = {self.m} equations ({len(self.drivers)} drivers), {self.dof} DOF>")


class ConstraintTable:
    """The constraint table of a mechanism, in the book's layout; renders as HTML in a notebook."""

    columns = ("Joint", "Name", "Body i", "Body j", "Type", "Equations", "Rows of Φ")

    def __init__(self, mechanism):
        self.mechanism = mechanism
        self.rows = []
        joint = 0
        for c in mechanism.constraints:
            if c.kind == "joint":
                joint += 1
            numbers = [str(b.number) for b in c.bodies]
            first, last = c.rows.start + 1, c.rows.stop
            self.rows.append((
                str(joint) if c.kind == "joint" else ("simple" if c.kind == "simple" else "driver"),
                c.name,
                numbers[0],
                ", ".join(numbers[1:]) or "—",
                c.label,
                str(c.n_eq),
                f"Φ_{first}" if first == last else f"Φ_{first}–Φ_{last}",
            ))

    def __repr__(self):
        widths = [max(len(h), *(len(r[k]) for r in self.rows)) if self.rows else len(h)
                  for k, h in enumerate(self.columns)]
        line = lambda cells: "  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip()
        mech = self.mechanism
        foot = (f"n = {mech.n} coordinates, m = {mech.m_geometric} geometric equations + "
                f"{mech.m - mech.m_geometric} driver equations, DOF = {mech.dof}")
        return "\n".join([line(self.columns), line("-" * w for w in widths)] + [line(r) for r in self.rows] + [foot])

    def _repr_html_(self):
        head = "".join(f"<th>{html.escape(h)}</th>" for h in self.columns)
        body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in r) + "</tr>" for r in self.rows)
        mech = self.mechanism
        foot = (f"n = {mech.n} coordinates, m = {mech.m_geometric} geometric equations + "
                f"{mech.m - mech.m_geometric} driver equation(s), degrees of freedom n − m = {mech.dof}")
        return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table><p>{html.escape(foot)}</p>"
