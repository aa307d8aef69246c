"""What planar and spatial mechanisms share: the constraint base class, the per-type index maps and the
fast numeric assembly of Φ, Φ_q, ν and γ, the symbolic model, and the analysis entry points.

:mod:`kinbook.planar` and :mod:`kinbook.spatial` subclass :class:`ConstraintBase` and :class:`MechanismBase`
and add only what depends on the coordinates: (x, y, φ) per planar body, (x, y, z, e0, e1, e2, e3) per
spatial body.
"""

from __future__ import annotations

import html
from functools import cached_property

import numpy as np
import sympy as sp

from . import analysis
from .errors import InputError, ModelError, UnknownBodyError, UnknownPointError
from .symbolic import derive, t as t_symbol, time_derivatives

__all__ = ["ConstraintBase", "ConstraintGroup", "MechanismBase", "ConstraintTable", "time_function", "lookup_point"]


def time_function(f, owner):
    """A driver's prescribed function of time as a sympy expression of ``t`` (a string or an expression)."""
    try:
        expr = sp.sympify(f, locals={"t": t_symbol})
    except (sp.SympifyError, TypeError, SyntaxError):
        raise ModelError(f"{type(owner).__name__}: cannot read the function of time {f!r}") from None
    extra = expr.free_symbols - {t_symbol}
    if extra:
        names = ", ".join(sorted(str(s) for s in extra))
        raise ModelError(f"{type(owner).__name__}: the function of time {f!r} uses unknown symbols {names}")
    return expr


def lookup_point(body, name, context=None):
    """The stored local coordinates of the point called ``name`` on ``body``; ``context`` (a constraint) is
    named in the error."""
    if name not in body.points:
        known = ", ".join(sorted(body.points)) or "none"
        where = f"{context.describe()}: " if context is not None else ""
        raise UnknownPointError(f"{where}body '{body.name}' has no point '{name}' (its points: {known})")
    return body.points[name]


class ConstraintBase:
    """Naming, rows and binding shared by every constraint, planar or spatial.

    A constraint type sets the class attributes, writes its Φ once in :meth:`phi` (the single source of
    truth) and gives a vectorized ``kernel`` with the :meth:`params` it needs.

    Attributes
    ----------
    type_name : str
        Name used in mechanism files and messages ("revolute").
    label : str
        The book's notation (r, t, r-r, s,3, p1,2 …).
    n_eq : int
        Number of equations (rows of Φ).
    kind : {"joint", "simple", "driver", "normalization"}
        Joints are numbered as the book numbers them in its joint tables; drivers are left out of the degrees
        of freedom count.
    angular : bool
        Φ is an angle: the mechanism wraps its value into (−π, π].
    rows : slice or None
        The rows of Φ this constraint occupies, set when it is added to a mechanism.
    mechanism : the mechanism it is bound to, or None.
    """

    type_name = "constraint"
    label = "?"
    n_eq = 0
    kind = "joint"
    angular = False
    kernel = None

    def __init__(self, bodies, name=None, f=None):
        self.body_names = tuple(str(b) for b in bodies)
        self.name = None if name is None else str(name)
        self.f = None if f is None else time_function(f, self)
        self.rows = None
        self.bodies = None
        self.mechanism = None

    def describe(self):
        """Short English description: "revolute joint '3' (rows 8-9 of Φ)"."""
        kind = {"joint": "joint", "driver": "driver", "simple": "constraint", "normalization": "equation"}
        what = f"{self.type_name} {kind.get(self.kind, self.kind)} '{self.name}'"
        if self.rows is not None:
            a, b = self.rows.start + 1, self.rows.stop
            what += f" (row {a} of Φ)" if a == b else f" (rows {a}-{b} of Φ)"
        return what

    def __repr__(self):
        bodies = ", ".join(repr(b) for b in self.body_names)
        return f"{type(self).__name__}({bodies}, name={self.name!r})"

    def bind(self, mechanism):
        """Resolve body and point names against ``mechanism`` (called when the constraint is added)."""
        bodies = [mechanism.body(b, context=self) for b in self.body_names]
        if len({b.name for b in bodies}) != len(bodies):
            raise ModelError(f"{self.describe()} connects body '{bodies[0].name}' to itself")
        self.bodies = bodies
        self._bind_points()
        self.mechanism = mechanism

    def _bind_points(self):
        """Hook: look up named points (and vectors); subclasses with points override it."""

    def phi(self, Q, t=t_symbol):
        """Symbolic Φ of this constraint: a list of ``n_eq`` sympy expressions in the coordinates ``Q`` of its
        bodies (one sympy column per body, in ``self.bodies`` order); a driver's includes − f(t)."""
        raise NotImplementedError

    def params(self):
        """Numeric parameters of this constraint for its kernel: a dict of float arrays."""
        return {}

    def _f_expr(self, t):
        return sp.Integer(0) if self.f is None else self.f.subs(t_symbol, t)


class ConstraintGroup:
    """All constraints sharing a kernel and a number of bodies: index maps and stacked parameters.

    ``cols`` (k, ncoord·nb) and ``rows`` (k, r) place every constraint's block in q and Φ, so assembly is a
    fancy-indexed assignment, with no Python loop over entries.
    """

    def __init__(self, constraints, n, ncoord):
        c0 = constraints[0]
        self.kernel = c0.kernel
        self.constraints = constraints
        self.nb = len(c0.bodies)
        self.ncoord = ncoord
        cols = np.array([[ncoord * (b.number - 1) + k for b in c.bodies for k in range(ncoord)] for c in constraints])
        rows = np.array([list(range(c.rows.start, c.rows.stop)) for c in constraints])
        self.cols, self.rows = cols, rows
        self.jac_rows = np.broadcast_to(rows[:, :, None], rows.shape + (cols.shape[1],)).ravel()
        self.jac_cols = np.broadcast_to(cols[:, None, :], rows.shape + (cols.shape[1],)).ravel()
        self.flat = self.jac_rows * n + self.jac_cols
        plist = [c.params() for c in constraints]
        self.params = {key: np.array([p[key] for p in plist], dtype=float) for key in plist[0]}

    def reduced_index(self, rows, cols, m, n):
        """Where this group's Jacobian entries go in Φ_q restricted to ``rows`` × ``cols``: (mask of the
        entries kept, or None for all; their flat indices). Cached: a mechanism has one reduction."""
        if getattr(self, "_reduced", None) is None:
            rpos, cpos = np.full(m, -1), np.full(n, -1)
            rpos[rows], cpos[cols] = np.arange(len(rows)), np.arange(len(cols))
            r, c = rpos[self.jac_rows], cpos[self.jac_cols]
            keep = (r >= 0) & (c >= 0)
            self._reduced = (None if keep.all() else keep, (r * len(cols) + c)[keep])
        return self._reduced

    def gather(self, q):
        """The coordinates of each constraint's bodies: (B, n) → (B, k, nb, ncoord)."""
        return q[:, self.cols].reshape(q.shape[0], len(self.constraints), self.nb, self.ncoord)


class MechanismBase:
    """Bodies, constraints, the symbolic model and the numeric assembly shared by planar and spatial
    mechanisms. Subclasses set ``COORDS`` (the names of one body's coordinates), ``constraint_base`` (the
    constraint class they accept) and implement ``add_body``."""

    COORDS = ()
    POINT_DIM = 2
    constraint_base = ConstraintBase
    kind = "planar"

    def __init__(self, name="mechanism", title=None):
        self.name = name
        self.title = title or name
        self.bodies = []
        self.constraints = []
        self._by_name = {}

    # ------------------------------------------------------------------------------------------- building
    def _new_body(self, body):
        if body.name in self._by_name:
            raise ModelError(f"mechanism '{self.name}' already has a body named '{body.name}'")
        self.bodies.append(body)
        self._by_name[body.name] = body
        self._invalidate()

    def add(self, constraint):
        """Add a constraint; its equations take the next rows of Φ. Returns ``None``."""
        if not isinstance(constraint, self.constraint_base):
            raise ModelError(f"expected a {self.kind} constraint (kinbook.{self.kind}), got {constraint!r}")
        self._add(constraint)

    def _add(self, constraint):
        start = self.m
        constraint.rows = slice(start, start + constraint.n_eq)
        if constraint.name is None:
            constraint.name = self._default_name(constraint)
        if any(c.name == constraint.name for c in self.constraints):
            constraint.rows = None
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
        self._check_removable(c)
        self.constraints.remove(c)
        c.rows = None
        start = 0
        for k in self.constraints:
            k.rows = slice(start, start + k.n_eq)
            start += k.n_eq
        self._invalidate()
        return c

    def _check_removable(self, constraint):
        """Hook: raise ModelError for constraints that belong to a body."""

    def _default_name(self, c):
        if c.kind == "joint":
            return str(sum(1 for k in self.constraints if k.kind == "joint") + 1)
        if c.kind == "driver":
            return f"driver {sum(1 for k in self.constraints if k.kind == 'driver') + 1}"
        taken = {k.name for k in self.constraints}
        if c.type_name == "ground" and "ground" not in taken:
            return "ground"
        base = " ".join([c.type_name, c.body_names[0]] + ([c.coordinate] if hasattr(c, "coordinate") else []))
        k, name = 1, base
        while name in taken:
            k += 1
            name = f"{base} {k}"
        return name

    def body(self, name, context=None):
        """The body called ``name``."""
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
        for attr in ("_compiled", "_symbolic", "q", "qd", "_q0", "_sizes", "_reduction", "_derivations"):
            self.__dict__.pop(attr, None)

    # ------------------------------------------------------------------------------------------- sizes
    @property
    def n(self):
        """Number of coordinates."""
        return len(self.COORDS) * len(self.bodies)

    @property
    def _counts(self):
        if "_sizes" not in self.__dict__:
            self._sizes = (sum(c.n_eq for c in self.constraints),
                           sum(c.n_eq for c in self.constraints if c.kind != "driver"))
        return self._sizes

    @property
    def m(self):
        """Number of rows of Φ, drivers included."""
        return self._counts[0]

    @property
    def m_geometric(self):
        """Number of rows of Φ that are not drivers."""
        return self._counts[1]

    @property
    def drivers(self):
        return [c for c in self.constraints if c.kind == "driver"]

    @property
    def dof(self):
        """Degrees of freedom n − m of the equations that are not drivers."""
        return self.n - self.m_geometric

    def coordinate_names(self):
        """Names of the coordinates in q order: 'x1', 'y1', …"""
        return [f"{c}{b.number}" for b in self.bodies for c in self.COORDS]

    def index(self, coordinate):
        """Position in q of a coordinate given by name ('phi2') or as (body name, 'phi')."""
        if isinstance(coordinate, tuple):
            body, c = coordinate
            if c not in self.COORDS:
                raise InputError(f"coordinate must be one of {', '.join(self.COORDS)}, got {c!r}")
            return len(self.COORDS) * (self.body(body).number - 1) + self.COORDS.index(c)
        names = self.coordinate_names()
        if coordinate not in names:
            raise InputError(f"mechanism '{self.name}' has no coordinate {coordinate!r} "
                             f"(it has {names[0]} … {names[-1]})")
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
        """Coordinates as a sympy column matrix (x1, y1, …)."""
        return sp.Matrix([sp.Symbol(s, real=True) for s in self.coordinate_names()])

    @cached_property
    def qd(self):
        """Velocities as a sympy column matrix (dx1, dy1, …)."""
        return sp.Matrix([sp.Symbol("d" + s, real=True) for s in self.coordinate_names()])

    @property
    def t(self):
        """The time symbol."""
        return t_symbol

    def body_symbols(self, body):
        """A body's coordinates as a sympy column matrix."""
        k = len(self.COORDS) * (self.body(body).number - 1)
        return self.q[k : k + len(self.COORDS), 0]

    def _constraint(self, constraint):
        return constraint if isinstance(constraint, ConstraintBase) else self.constraint(constraint)

    def constraint_phi(self, constraint):
        """Symbolic Φ rows of one constraint (a name or the object), in this mechanism's symbols."""
        c = self._constraint(constraint)
        Q = [self.body_symbols(b.name) for b in c.bodies]
        return sp.Matrix(c.phi(Q, t_symbol))

    def symbolic(self):
        """Φ, Φ_q, ν and γ as sympy matrices (a :class:`kinbook.symbolic.Derivation`), derived from Φ."""
        if "_symbolic" not in self.__dict__:
            Phi = (sp.Matrix.vstack(*[self.constraint_phi(c) for c in self.constraints])
                   if self.constraints else sp.zeros(0, 1))
            self._symbolic = derive(Phi, self.q, self.qd, t_symbol)
        return self._symbolic

    # ------------------------------------------------------------------------------------------- numerics
    @property
    def _compiled(self):
        if "_compiled" not in self.__dict__:
            if not self.bodies:
                raise ModelError(f"mechanism '{self.name}' has no bodies")
            for c in self.constraints:
                params = {s for b in c.bodies for p in b.points.values() for v in p
                          for s in getattr(v, "free_symbols", ())}
                if params:
                    names = ", ".join(sorted(map(str, params)))
                    raise ModelError(f"{c.describe()} has symbolic parameters ({names}): substitute numbers "
                                     "before a numeric evaluation")
            groups = {}
            for c in self.constraints:
                groups.setdefault((c.kernel, len(c.bodies), c.n_eq), []).append(c)
            drivers = [(c.rows.stop - 1, *time_derivatives(c.f)) for c in self.constraints if c.f is not None]
            wrap = np.array([c.rows.start for c in self.constraints if c.angular], dtype=int)
            ncoord = len(self.COORDS)
            self.__dict__["_compiled"] = ([ConstraintGroup(g, self.n, ncoord) for g in groups.values()], drivers, wrap)
        return self.__dict__["_compiled"]

    @property
    def _reduction(self):
        """(free rows, free columns) of Φ_q once the *fixed* bodies are set aside, or None if there are none.

        A body is fixed when time-independent constraints acting on it alone have as many equations as it has
        coordinates (a ground constraint, three simple constraints; in space ground plus normalization). Those
        rows involve only its columns, so Φ_q is block-triangular: the body's coordinates stay at their
        assembled values, its q̇ and q̈ are zero, and the rest solves the smaller system of the other rows and
        columns — the same solution at a fraction of the cost of factoring the whole matrix.
        """
        if "_reduction" not in self.__dict__:
            ncoord = len(self.COORDS)
            own = {}
            for c in self.constraints:
                if c.f is None and len(c.bodies) == 1:
                    own.setdefault(c.bodies[0].name, []).append(c)
            rows, cols = [], []
            for b in self.bodies:
                cs = own.get(b.name, [])
                if sum(c.n_eq for c in cs) == ncoord:
                    rows += [r for c in cs for r in range(c.rows.start, c.rows.stop)]
                    cols += range((b.number - 1) * ncoord, b.number * ncoord)
            red = None
            if rows:
                red = (np.setdiff1d(np.arange(self.m), rows), np.setdiff1d(np.arange(self.n), cols))
            self.__dict__["_reduction"] = red
        return self.__dict__["_reduction"]

    def _check_q(self, q, name="q"):
        try:
            q = np.asarray(q, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"`{name}` must be an array of {self.n} numbers") from None
        if q.shape[-1:] != (self.n,) or q.ndim > 2:
            raise InputError(
                f"`{name}` must have shape ({self.n},) or (N, {self.n}) for mechanism '{self.name}' "
                f"({len(self.bodies)} bodies × {len(self.COORDS)} coordinates), got {q.shape}"
            )
        bad = ~np.isfinite(q)
        if bad.any():
            k = int(np.argwhere(bad)[0][-1])
            raise InputError(f"`{name}` has a non-finite value in {self.coordinate_names()[k]}: {q[..., k]}")
        return q

    def _check_t(self, t, batch):
        try:
            t = np.asarray(t, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"`t` must be a number or an array of numbers, got {t!r}") from None
        if not np.all(np.isfinite(t)):
            raise InputError(f"`t` must be finite, got {t}")
        if t.ndim > 1 or (t.ndim == 1 and t.shape[0] != batch):
            raise InputError(f"`t` must be a number or have shape ({batch},), got {t.shape}")
        return np.broadcast_to(t, (batch,))

    def evaluate(self, q, t=0.0, qd=None, *, jacobian=True, sparse=False, reduced=False):
        """Evaluate Φ, Φ_q, ν and (when ``qd`` is given) γ at once, for one or many instants.

        This is the fast path every analysis uses: one kernel call per constraint type, vectorized over the
        constraints of that type and over the instants.

        Parameters
        ----------
        q : array_like, shape (n,) or (N, n)
        t : float or array_like, shape (N,)
        qd : array_like, same shape as ``q``, optional

        Returns
        -------
        dict with 'Phi' (…, m), 'Phi_q' (…, m, n) — a scipy CSR matrix when ``sparse`` (one instant) —
        'nu' (…, m) and 'gamma' (…, m) (None without ``qd``). With ``reduced``, 'Phi_q' leaves out the rows
        and columns of the fixed bodies (``_reduction``), the system the solvers factor.
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
        groups, drivers, wrap = self._compiled
        Phi = np.zeros((Bn, m))
        gamma = np.zeros((Bn, m)) if qdb is not None else None
        nu = np.zeros((Bn, m))
        values = []
        for g in groups:
            Qg, Qdg = g.gather(qb), None if qdb is None else g.gather(qdb)
            if jacobian or not getattr(g.kernel, "optional_jacobian", False):
                phi, jac, gam = g.kernel(Qg, g.params, Qdg)
            else:  # Φ or γ alone: a kernel that builds Φ_q lazily skips it
                phi, jac, gam = g.kernel(Qg, g.params, Qdg, jacobian=False)
            Phi[:, g.rows] = phi
            if gam is not None:
                gamma[:, g.rows] = gam
            values.append(None if jac is None else jac.reshape(Bn, -1))
        for row, f0, f1, f2 in drivers:
            Phi[:, row] -= f0(tb)
            nu[:, row] = f1(tb)
            if gamma is not None:
                gamma[:, row] += f2(tb)
        if wrap.size:
            Phi[:, wrap] = np.mod(Phi[:, wrap] + np.pi, 2 * np.pi) - np.pi
        out = {"Phi": Phi, "nu": nu, "gamma": gamma}
        if jacobian:
            if sparse:
                if not single:
                    raise InputError("a sparse Φ_q is available for one instant at a time")
                import scipy.sparse as sps  # imported when first needed (see analysis._solve)

                rows = np.concatenate([g.jac_rows for g in groups])
                cols = np.concatenate([g.jac_cols for g in groups])
                data = np.concatenate([v[0] for v in values])
                out["Phi_q"] = sps.csr_matrix((data, (rows, cols)), shape=(m, n))
            elif reduced and self._reduction is not None:
                rows, cols = self._reduction
                J = np.zeros((Bn, len(rows) * len(cols)))
                for g, v in zip(groups, values):
                    keep, flat = g.reduced_index(rows, cols, m, n)
                    J[:, flat] = v if keep is None else v[:, keep]
                out["Phi_q"] = J.reshape(Bn, len(rows), len(cols))
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

    def point_local(self, body, point):
        """Local coordinates of a body point, as floats: a point name, or the coordinates themselves
        (``POINT_DIM`` finite numbers)."""
        b = self.body(body)
        if isinstance(point, str):
            return np.array([float(v) for v in lookup_point(b, point)])
        try:
            s = np.asarray(point, dtype=float)
        except (TypeError, ValueError):
            s = None
        if s is None or s.shape != (self.POINT_DIM,) or not np.all(np.isfinite(s)):
            raise InputError(f"a point on body '{b.name}' must be a point name or {self.POINT_DIM} finite numbers, "
                             f"got {point!r}")
        return s

    def _body_q(self, arr, body):
        k = len(self.COORDS) * (self.body(body).number - 1)
        return arr[..., k : k + len(self.COORDS)]

    # ------------------------------------------------------------------------------------------- analysis
    def constraint_table(self):
        """The book's joint table: joint number, bodies i and j, type, number of equations, rows of Φ."""
        return ConstraintTable(self)

    def _type_cell(self, c):
        return c.label

    def _table_footer(self):
        return (f"n = {self.n} coordinates, m = {self.m_geometric} geometric equations + "
                f"{self.m - self.m_geometric} driver equation(s), degrees of freedom n − m = {self.dof}")

    def check_drivers(self):
        """Raise :class:`~kinbook.errors.DriverCountError` unless there are exactly as many driver equations
        as degrees of freedom."""
        analysis.check_drivers(self)

    def solve_position(self, t=0.0, q0=None, tol=1e-10, max_iter=50):
        """Newton–Raphson solution of Φ(q, t) = 0 from ``q0`` (default: the bodies' q0). See
        :func:`kinbook.analysis.solve_position`."""
        return analysis.solve_position(self, t, q0=q0, tol=tol, max_iter=max_iter)

    def solve_velocity(self, q, t=0.0):
        """Solve Φ_q q̇ = ν for q̇."""
        return analysis.solve_velocity(self, q, t)

    def solve_acceleration(self, q, qd, t=0.0):
        """Solve Φ_q q̈ = γ for q̈."""
        return analysis.solve_acceleration(self, q, qd, t)

    def simulate(self, times, q0=None, tol=1e-10, on_failure="raise", anchor_every=512):
        """Position, velocity and acceleration at every instant of ``times``: a
        :class:`~kinbook.analysis.SimulationResult`. See :func:`kinbook.analysis.simulate`."""
        return analysis.simulate(self, times, q0=q0, tol=tol, on_failure=on_failure, anchor_every=anchor_every)

    def diagnose(self, q, t=0.0):
        """Rank of Φ_q at ``q`` and, when singular, which constraints are dependent: see
        :func:`kinbook.analysis.diagnose`."""
        return analysis.diagnose(self, q, t)

    def __repr__(self):
        prefix = "" if self.kind == "planar" else f"{self.kind} "
        return (f"<{prefix}Mechanism '{self.name}': {len(self.bodies)} bodies, n = {self.n} coordinates, "
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
                str(joint) if c.kind == "joint" else c.kind,
                c.name,
                numbers[0],
                ", ".join(numbers[1:]) or "—",
                mechanism._type_cell(c),
                str(c.n_eq),
                f"Φ_{first}" if first == last else f"Φ_{first}–Φ_{last}",
            ))

    def __repr__(self):
        widths = [max(len(h), *(len(r[k]) for r in self.rows)) if self.rows else len(h)
                  for k, h in enumerate(self.columns)]

        def line(cells):
            return "  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip()

        rows = [line(self.columns), line("-" * w for w in widths)] + [line(r) for r in self.rows]
        return "\n".join(rows + [self.mechanism._table_footer()])

    def _repr_html_(self):
        head = "".join(f"<th>{html.escape(h)}</th>" for h in self.columns)
        body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in r) + "</tr>" for r in self.rows)
        foot = html.escape(self.mechanism._table_footer())
        return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table><p>{foot}</p>"
