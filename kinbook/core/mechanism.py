"""The mechanism both chapters share: bodies and constraints, names, the one version counter and cache, the
symbolic model, the numeric interface and the analysis entry points; the book's constraint table.

:mod:`kinbook.planar` and :mod:`kinbook.spatial` subclass :class:`MechanismBase` and add only what depends on the
coordinates: (x, y, φ) per planar body, (x, y, z, e0, e1, e2, e3) per spatial body.
"""

from __future__ import annotations

import html

import numpy as np
import sympy as sp

from ..errors import InputError, ModelError, UnknownBodyError
from . import assembly, diagnose, solve, sweep
from .arrays import real_array
from .constraint import ConstraintBase, lookup_point
from .symbolic import derive
from .symbolic import t as t_symbol

__all__ = ["MechanismBase", "ConstraintTable", "MAX_BODIES"]


MAX_BODIES = 100_000
"""Most bodies in one mechanism (a mechanism file that lists more is refused before it is built)."""


class MechanismBase:
    """Bodies, constraints, the symbolic model and the numeric assembly shared by planar and spatial
    mechanisms. Subclasses set ``COORDS`` (the names of one body's coordinates), ``constraint_base`` (the
    constraint class they accept) and implement ``add_body``.

    The mechanism owns everything derived from it (sizes, symbols, the compiled numeric model, the symbolic
    model, per-constraint derivations, and what other layers store through :meth:`cached`): one ``version``
    counter is bumped by every change, and the one cache is emptied with it.
    """

    COORDS = ()
    POINT_DIM = 2
    constraint_base = ConstraintBase
    kind = "planar"
    KERNELS = ("hand", "compiled")

    def __init__(self, name="mechanism", title=None):
        self.name = name
        self.title = title or name
        self.bodies = []
        self.constraints = []
        self._by_name = {}
        self.version = 0
        self._cache = {}
        self._kernels = "hand"

    # ------------------------------------------------------------------------------------------- building
    def _new_body(self, body):
        if len(self.bodies) >= MAX_BODIES:
            raise ModelError(f"mechanism '{self.name}' already has {MAX_BODIES} bodies, the most kinbook handles")
        if body.name in self._by_name:
            raise ModelError(f"mechanism '{self.name}' already has a body named '{body.name}'")
        self.bodies.append(body)
        self._by_name[body.name] = body
        self._changed()

    def add(self, constraint):
        """Add a constraint; its equations take the next rows of Φ. Returns ``None``."""
        if not isinstance(constraint, self.constraint_base):
            raise ModelError(f"expected a {self.kind} constraint (kinbook.{self.kind}), got {constraint!r}")
        self._add(constraint)

    def _add(self, constraint):
        start = self.constraints[-1].rows.stop if self.constraints else 0
        constraint.rows = slice(start, start + constraint.n_eq)
        if constraint.name is None:
            constraint.name = self._default_name(constraint)
        index = self._constraint_index
        if constraint.name in index["names"]:
            constraint.rows = None
            raise ModelError(f"mechanism '{self.name}' already has a constraint named '{constraint.name}'")
        try:
            constraint.bind(self)
        except Exception:
            constraint.rows = None
            raise
        self.constraints.append(constraint)
        index["names"][constraint.name] = constraint
        index["kinds"][constraint.kind] = index["kinds"].get(constraint.kind, 0) + 1
        self._changed()

    @property
    def _constraint_index(self):
        """The constraints by name and their number by kind, updated by each addition (so that adding a
        constraint costs O(1) and loading is linear in the size of the mechanism); rebuilt after a removal."""
        if "_cindex" not in self.__dict__:
            kinds = {}
            for c in self.constraints:
                kinds[c.kind] = kinds.get(c.kind, 0) + 1
            self.__dict__["_cindex"] = {"names": {c.name: c for c in self.constraints}, "kinds": kinds}
        return self.__dict__["_cindex"]

    def remove(self, name):
        """Remove the constraint called ``name``; the rows of the constraints after it move up. Returns it."""
        c = self.constraint(name)
        self._check_removable(c)
        self.constraints.remove(c)
        self.__dict__.pop("_cindex", None)
        c.rows = None
        start = 0
        for k in self.constraints:
            k.rows = slice(start, start + k.n_eq)
            start += k.n_eq
        self._changed()
        return c

    def _check_removable(self, constraint):
        """Hook: raise ModelError for constraints that belong to a body."""

    def validate(self):
        """Hook: the chapter's checks of the whole mechanism once it is built (the file loader calls it);
        raises :class:`~kinbook.errors.ModelError`. The default checks nothing."""

    def _default_name(self, c):
        index = self._constraint_index
        if c.kind == "joint":
            return str(index["kinds"].get("joint", 0) + 1)
        if c.kind == "driver":
            return f"driver {index['kinds'].get('driver', 0) + 1}"
        taken = index["names"]
        stems = c.name_stems()
        for name in stems:
            if name not in taken:
                return name
        k, name = 1, stems[-1]
        while name in taken:
            k += 1
            name = f"{stems[-1]} {k}"
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
        c = self._constraint_index["names"].get(str(name))
        if c is not None:
            return c
        known = ", ".join(repr(c.name) for c in self.constraints)
        raise ModelError(f"mechanism '{self.name}' has no constraint '{name}' (its constraints: {known})")

    # ------------------------------------------------------------------------------------------- caches
    def _changed(self):
        """Every change of the mechanism comes here: a new version, and nothing derived from the old one."""
        self.version += 1
        self._cache.clear()

    def cached(self, key, build):
        """The value cached under ``key`` for this version of the mechanism, built by ``build()`` when absent.

        The one place where anything derived from the mechanism is kept — by the mechanism itself and by the
        layers above it (the checkers' reference and samples): it is emptied by every change (``version``),
        so nothing stale survives a removed or re-added constraint. Keys are any hashable value; other
        layers use a tuple starting with their own name, e.g. ``("grading", "target", constraint name)``.
        """
        try:
            return self._cache[key]
        except KeyError:
            value = self._cache[key] = build()
            return value

    @property
    def kernels(self):
        """Which numeric path the mechanism evaluates: "hand" (the hand-written kernels where a type has one,
        the default) or "compiled" (every constraint through the kernel compiled from its Φ)."""
        return self._kernels

    @kernels.setter
    def kernels(self, value):
        if value not in self.KERNELS:
            raise InputError(f"`kernels` must be one of {', '.join(self.KERNELS)}, got {value!r}")
        self._kernels = value
        self._changed()

    # ------------------------------------------------------------------------------------------- sizes
    @property
    def n(self):
        """Number of coordinates."""
        return len(self.COORDS) * len(self.bodies)

    @property
    def _counts(self):
        found = self._cache.get("sizes")  # read on every evaluation: the cache without a closure
        if found is None:
            found = self.cached("sizes", lambda: (sum(c.n_eq for c in self.constraints),
                                                  sum(c.n_eq for c in self.constraints if c.kind != "driver")))
        return found

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
            if len(coordinate) != 2:
                raise InputError(f"a coordinate is a name ('{self.coordinate_names()[-1]}') or a pair (body name, "
                                 f"one of {', '.join(self.COORDS)}), got the tuple {coordinate!r}")
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
        return self.cached("q0", lambda: np.array([float(v) for b in self.bodies for v in b.q0])).copy()

    # ------------------------------------------------------------------------------------------- symbols
    @property
    def q(self):
        """Coordinates as a sympy column matrix (x1, y1, …)."""
        return self.cached("q", lambda: sp.Matrix([sp.Symbol(s, real=True) for s in self.coordinate_names()]))

    @property
    def qd(self):
        """Velocities as a sympy column matrix (dx1, dy1, …)."""
        return self.cached("qd", lambda: sp.Matrix([sp.Symbol("d" + s, real=True) for s in self.coordinate_names()]))

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
        rows = list(c.phi(Q, t_symbol))
        if len(rows) != c.n_eq:
            raise ModelError(f"{c.describe()}: phi() returns {len(rows)} rows, the type declares n_eq = {c.n_eq}")
        return sp.Matrix(rows)

    def symbolic(self):
        """Φ, Φ_q, ν and γ as sympy matrices (a :class:`kinbook.core.symbolic.Derivation`), derived from Φ."""
        if not self.bodies:
            raise ModelError(f"mechanism '{self.name}' has no bodies")

        def build():
            Phi = (sp.Matrix.vstack(*[self.constraint_phi(c) for c in self.constraints])
                   if self.constraints else sp.zeros(0, 1))
            return derive(Phi, self.q, self.qd, t_symbol)

        return self.cached("symbolic", build)

    def derivation(self, constraint):
        """Φ, Φ_q, ν and γ of one constraint (a name or the object) with respect to the coordinates of its own
        bodies only (the rows of the book's Jacobian tables), derived by :func:`kinbook.core.symbolic.derive`.

        Returns
        -------
        kinbook.core.symbolic.Derivation
            Its ``q`` lists the coordinates of the constraint's bodies (body i's, then body j's …). Computed
            once per constraint until the mechanism changes.
        """
        c = self._constraint(constraint)

        def build():
            q = sp.Matrix.vstack(*[self.body_symbols(b.name) for b in c.bodies])
            k = [self.index(str(s)) for s in q]
            return derive(self.constraint_phi(c), q, self.qd[k, 0], t_symbol)

        return self.cached(("derivation", c.name), build)

    # ------------------------------------------------------------------------------------------- numerics
    @property
    def compiled(self):
        """The numeric model, compiled once (:func:`kinbook.core.assembly.compile`): (constraint groups by kernel,
        drivers, wrapped rows)."""
        found = self._cache.get("compiled")
        return found if found is not None else self.cached("compiled", self._compile)

    def _compile(self):
        return assembly.compile(self)

    def fixed_bodies(self):
        """Names of the bodies fixed by constraints of their own: time-independent constraints acting on the
        body alone with as many equations as it has coordinates (a ground constraint; three simple
        constraints; in space ground plus normalization)."""
        return [b.name for b, _ in self._own_constraints()]

    def _own_constraints(self):
        """[(body, its fixing constraints)] for the fixed bodies (see :meth:`fixed_bodies`), in body order."""
        own = {}
        for c in self.constraints:
            if c.f is None and len(c.bodies) == 1:
                own.setdefault(c.bodies[0].name, []).append(c)
        ncoord = len(self.COORDS)
        return [(b, own[b.name]) for b in self.bodies if sum(c.n_eq for c in own.get(b.name, [])) == ncoord]

    @property
    def reduction(self):
        """(free rows, free columns) of Φ_q once the *fixed* bodies are set aside, or None if there are none.

        A body is fixed when time-independent constraints acting on it alone have as many equations as it has
        coordinates (a ground constraint, three simple constraints; in space ground plus normalization). Those
        rows involve only its columns, so Φ_q is block-triangular: the body's coordinates stay at their
        assembled values, its q̇ and q̈ are zero, and the rest solves the smaller system of the other rows and
        columns — the same solution at a fraction of the cost of factoring the whole matrix.
        """
        if "reduction" in self._cache:
            return self._cache["reduction"]

        def build():
            ncoord = len(self.COORDS)
            rows, cols = [], []
            for b, cs in self._own_constraints():
                rows += [r for c in cs for r in range(c.rows.start, c.rows.stop)]
                cols += range((b.number - 1) * ncoord, b.number * ncoord)
            if not rows:
                return None
            return np.setdiff1d(np.arange(self.m), rows), np.setdiff1d(np.arange(self.n), cols)

        return self.cached("reduction", build)

    def check_q(self, q, name="q"):
        """``q`` as a float array of shape (n,) or (N, n), finite; :class:`InputError` naming the mechanism,
        the expected shape and the first bad coordinate otherwise."""
        q = real_array(q, name, f"an array of {self.n} numbers", finite=False)  # the coordinate named below
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

    def check_configuration(self, q, name="q", what="this analysis"):
        """``q`` as one configuration, a float array of shape (n,): :meth:`check_q`, and a batch (N, n) refused
        with :class:`InputError` (the analyses at one instant solve for one configuration)."""
        q = self.check_q(q, name)
        if q.ndim != 1:
            raise InputError(f"`{name}` must be one configuration, shape ({self.n},), for {what} of mechanism "
                             f"'{self.name}'; got a batch of shape {q.shape} (Phi, Phi_q and evaluate take batches; "
                             "simulate sweeps many instants)")
        return q

    def check_t(self, t, batch):
        """``t`` as floats of shape (batch,): one number broadcast, or one per instant."""
        t = real_array(t, "t", "a number or an array of numbers")
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
        and columns of the fixed bodies (``reduction``), the system the solvers factor.
        """
        for name, flag in (("jacobian", jacobian), ("sparse", sparse), ("reduced", reduced)):
            if not isinstance(flag, (bool, np.bool_)):  # a truthy text such as "no" would switch it on
                raise InputError(f"`{name}` must be True or False, got {flag!r}"[:200])
        return assembly.evaluate(self, q, t, qd, jacobian=jacobian, sparse=sparse, reduced=reduced)

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
        if qd is None:
            raise InputError(f"`qd` is required: γ of mechanism '{self.name}' depends on the velocities q̇ "
                             f"(an array of {self.n} numbers)")
        return self.evaluate(q, t, qd, jacobian=False)["gamma"]

    def point_local(self, body, point):
        """Local coordinates of a body point, as floats: a point name, or the coordinates themselves
        (``POINT_DIM`` finite numbers)."""
        b = self.body(body)
        if isinstance(point, str):
            return np.array([float(v) for v in lookup_point(b, point)])
        try:
            s = real_array(point, "point")
        except InputError:
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
                f"{self.m - self.m_geometric} driver equation(s), degrees of freedom n − m = {self.dof}"
                + self._overconstrained_note())

    def _overconstrained_note(self):
        """What a negative count means (a set of joints gathered to be tabulated, say, not a mechanism)."""
        if self.dof >= 0:
            return ""
        return (f" < 0: {-self.dof} more equations than coordinates — an overconstrained set of joints, not a "
                f"mechanism that can be assembled")

    def check_drivers(self):
        """Raise :class:`~kinbook.errors.DriverCountError` unless there are exactly as many driver equations
        as degrees of freedom."""
        solve.check_drivers(self)

    def solve_position(self, t=0.0, q0=None, tol=1e-10, max_iter=50, history=False):
        """Newton–Raphson solution of Φ(q, t) = 0 from ``q0`` (default: the bodies' q0); with ``history``,
        ``(q, NewtonHistory)``. See :func:`kinbook.core.solve.solve_position`."""
        return solve.solve_position(self, t, q0=q0, tol=tol, max_iter=max_iter, history=history)

    def solve_velocity(self, q, t=0.0):
        """Solve Φ_q q̇ = ν for q̇."""
        return solve.solve_velocity(self, q, t)

    def solve_acceleration(self, q, qd, t=0.0):
        """Solve Φ_q q̈ = γ for q̈."""
        return solve.solve_acceleration(self, q, qd, t)

    def simulate(self, times, q0=None, tol=1e-10, on_failure="raise", anchor_every=512):
        """Position, velocity and acceleration at every instant of ``times``: a
        :class:`~kinbook.core.sweep.SimulationResult`. See :func:`kinbook.core.sweep.simulate`."""
        return sweep.simulate(self, times, q0=q0, tol=tol, on_failure=on_failure, anchor_every=anchor_every)

    def diagnose(self, q, t=0.0):
        """Rank of Φ_q at ``q`` and, when singular, which constraints are dependent: see
        :func:`kinbook.core.diagnose.diagnose`."""
        return diagnose.diagnose(self, self.check_configuration(q, what="the rank analysis"), t)

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
