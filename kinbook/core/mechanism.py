"""What planar and spatial mechanisms share: the constraint family (an abstract base whose subclasses register
themselves by type name, per chapter), the per-type index maps and the fast numeric assembly of Φ, Φ_q, ν
and γ, the symbolic model, and the analysis entry points.

:mod:`kinbook.planar` and :mod:`kinbook.spatial` subclass :class:`ConstraintBase` and :class:`MechanismBase`
and add only what depends on the coordinates: (x, y, φ) per planar body, (x, y, z, e0, e1, e2, e3) per
spatial body. How to add a constraint type: docs/extending.md.
"""

from __future__ import annotations

import abc
import html
import inspect
import numbers
from types import MappingProxyType

import numpy as np
import sympy as sp

from ..errors import InputError, ModelError, UnknownBodyError, UnknownPointError
from . import kernels, solve
from .arrays import real_array
from .reader import check_expression, read_constant, read_expression, read_number
from .symbolic import derive, time_derivatives
from .symbolic import t as t_symbol
from .symbolic import time_function as read_time_function

__all__ = [
    "ConstraintBase",
    "ConstraintGroup",
    "MechanismBase",
    "ConstraintTable",
    "time_function",
    "lookup_point",
    "constraint_types",
    "constraint_class",
    "stack_params",
    "KINDS",
    "MEASURES",
]


MAX_BODIES = 100_000
"""Most bodies in one mechanism (a mechanism file that lists more is refused before it is built)."""


def time_function(f, owner):
    """A driver's prescribed function of time as a sympy expression of ``t`` (text, a number or a sympy
    expression), validated by :func:`kinbook.core.symbolic.time_function`."""
    bodies = ", ".join(f"'{b}'" for b in owner.body_names)
    return read_time_function(f, f"{owner.type_name} on bod{'y' if len(owner.body_names) == 1 else 'ies'} {bodies}, f")


def lookup_point(body, name, context=None):
    """The stored local coordinates of the point called ``name`` on ``body``; ``context`` (a constraint) is
    named in the error."""
    if name not in body.points:
        known = ", ".join(sorted(body.points)) or "none"
        where = f"{context.describe()}: " if context is not None else ""
        raise UnknownPointError(f"{where}body '{body.name}' has no point '{name}' (its points: {known})")
    return body.points[name]


KINDS = ("joint", "simple", "driver", "normalization")
"""What a constraint can be: joints are numbered as the book numbers them in its joint tables; simple
constraints fix coordinates of one body; drivers are left out of the degrees-of-freedom count;
normalization rows (spatial) belong to one body."""

MEASURES = ("length", "length^2", "angle", "ratio")
"""What a row of Φ can measure (``Constraint.measures``): a distance, a product of two distances (dot and
cross products of body vectors, squared lengths), an angle in radians, or a pure number."""

_REGISTRY = {}


def constraint_types(chapter):
    """The registered constraint classes of a chapter, by the ``type`` name used in mechanism files.

    Parameters
    ----------
    chapter : {"planar", "spatial"}

    Returns
    -------
    mapping of str to class
        A read-only view: a type registered later (a subclass defined in a notebook or a test) appears in it.

    Examples
    --------
    >>> import kinbook
    >>> constraint_types("planar")["revolute"]
    <class 'kinbook.planar.constraints.Revolute'>
    """
    return MappingProxyType(_REGISTRY.setdefault(chapter, {}))


def constraint_class(chapter, type_name, where=None, files=False):
    """The constraint class registered as ``type_name`` in ``chapter``; :class:`ModelError` naming the known
    types (and ``where``, when given) otherwise. With ``files``, only the types a mechanism file may declare
    (``in_files``)."""
    types = {k: v for k, v in _REGISTRY.get(chapter, {}).items() if v.in_files or not files}
    if type_name in types:
        return types[type_name]
    known = ", ".join(types) or "none"
    prefix = f"{where}: " if where else ""
    raise ModelError(f"{prefix}`type` must be one of the {chapter} constraint types {known}, got {type_name!r}")


class ConstraintBase(abc.ABC):
    """A constraint type of either chapter: naming, rows, binding, registration and the numeric path.

    A new type is one subclass of :class:`kinbook.planar.Constraint` or :class:`kinbook.spatial.Constraint`
    that sets ``type_name`` and ``n_eq``, declares what it reads from a mechanism file (``points``,
    ``vectors``, ``numbers``, ``functions``) and writes :meth:`phi`, its Φ — the single source of truth.
    Everything else follows from that (docs/extending.md): the class registers itself under ``type_name``
    in its chapter (mechanism files find it there), Φ_q, ν and γ are derived by :mod:`kinbook.core.symbolic`, and
    the numeric path is compiled from :meth:`phi` (:mod:`kinbook.core.kernels`) unless the type gives a
    hand-written ``kernel`` as an optimization (tested equal to the compiled one).

    Class attributes
    ----------------
    type_name : str
        Name in mechanism files and messages ("revolute"); setting it registers the class.
    label : str
        The book's notation (r, t, r-r, s,3, p1,2 …).
    n_eq : int
        Number of equations (rows of Φ).
    kind : {"joint", "simple", "driver", "normalization"}
    title : dict
        ``{"en": "revolute joint", "es": "par de revolución"}`` for messages and tables.
    roles : tuple of str
        The roles of the bodies it connects, in order ("i", "j").
    measures : tuple or None
        What each row measures, one of :data:`MEASURES` per row (None: not known).
    wrap : dict
        ``{row: period}``: rows whose value jumps by a period (an angle from atan2: 2π) and is wrapped by the
        mechanism into (−period/2, period/2].
    per_body : bool
        The constraint belongs to its one body and is named after it (ground, normalization).
    in_files : bool
        Mechanism files may declare it (False for the normalization rows a spatial body brings itself).
    parts : tuple
        A composite joint: the constraint classes whose rows it stacks, each optionally with a dict renaming
        the part's attributes to the composite's (``(Normal1, {"a_i": "hp_i"})``). ``n_eq``, ``label``,
        ``wrap``, ``measures``, :meth:`phi` and the kernel follow from the parts.
    points, vectors : dict
        ``{key: role}``: file keys naming a point (a vector) of the body in that role; bound to the local
        coordinates, read in :meth:`phi` with :meth:`point` and :meth:`vector`.
    numbers : tuple or dict
        File keys of numeric parameters (a dict gives defaults); bound to sympy numbers.
    functions : dict
        ``{key: variable}``: file keys of functions of one variable, written as expressions in it
        (``"2 + cos(psi)"``); bound to a sympy Lambda, called in :meth:`phi` as ``self.profile(ψ)``.
    parameters : tuple of str
        Attributes that :meth:`phi` reads and that hold numbers (the declared keys by default): the compiled
        path makes them symbols, so one compiled kernel serves every constraint of the type.
    kernel : callable or None
        Hand-written vectorized kernel ``kernel(Q, P, Qd=None) -> (Φ, Φ_q, γ)`` with the :meth:`params` it
        reads.

    Instance attributes
    -------------------
    rows : slice or None
        The rows of Φ it occupies, set when it is added to a mechanism.
    bodies : list of bodies, or None before it is bound; mechanism : the mechanism it is bound to, or None.
    """

    chapter = None
    COORDS = ()
    type_name = None
    label = "?"
    n_eq = 0
    kind = "joint"
    title = None
    roles = ("i", "j")
    measures = None
    wrap = {}
    per_body = False
    in_files = True
    parts = ()
    points = {}
    vectors = {}
    numbers = ()
    functions = {}
    parameters = ()
    kernel = None
    owner = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        own = cls.__dict__
        if own.get("parts"):
            _declare_composite(cls)
        declared = _declared_keys(cls)
        if declared and "parameters" not in own:
            cls.parameters = tuple(k for k in declared if k not in cls.functions)
        if declared and _inherits_base_init(cls):
            _install_init(cls, declared)
        if own.get("type_name") is not None:
            _register(cls)

    def __init__(self, bodies, name=None, f=None):
        self.body_names = tuple(str(b) for b in bodies)
        self.name = None if name is None else str(name)
        self.f = None if f is None else time_function(f, self)
        self.rows = None
        self.bodies = None
        self.mechanism = None

    # ------------------------------------------------------------------------------------------- naming
    def describe(self):
        """Short English description: "revolute joint '3' (rows 8-9 of Φ)"."""
        if self.owner is not None:
            return self.owner.describe()
        kind = {"joint": "joint", "driver": "driver", "simple": "constraint", "normalization": "equation"}
        what = f"{self.type_name} {kind.get(self.kind, self.kind)} '{self.name}'"
        if self.rows is not None:
            a, b = self.rows.start + 1, self.rows.stop
            what += f" (row {a} of Φ)" if a == b else f" (rows {a}-{b} of Φ)"
        return what

    def name_stems(self):
        """Default names for an unnamed constraint that is neither a joint nor a driver, in order of
        preference (the mechanism numbers the last one when all are taken)."""
        return (f"{self.type_name} {self.body_names[0]}",)

    def __repr__(self):
        bodies = ", ".join(repr(b) for b in self.body_names)
        return f"{type(self).__name__}({bodies}, name={self.name!r})"

    # ------------------------------------------------------------------------------------------- binding
    def bind(self, mechanism):
        """Resolve body and point names against ``mechanism`` (called when the constraint is added)."""
        bodies = [mechanism.body(b, context=self) for b in self.body_names]
        if len({b.name for b in bodies}) != len(bodies):
            raise ModelError(f"{self.describe()} connects body '{bodies[0].name}' to itself")
        self.bodies = bodies
        self.__dict__.pop("_views", None)
        self.__dict__.pop("_template", None)
        self._bind_points()
        if self.parts:
            self._bind_parts()
        self.mechanism = mechanism

    def _bind_points(self):
        """Hook: resolve named points, vectors and parameters. The default binds the declared keys; a type
        with its own ``__init__`` overrides it."""
        specs = getattr(self, "specs", None)
        if not specs:
            return
        for key, role in self.points.items():
            setattr(self, key, self._read_point(self.roles.index(role), specs[key], key))
        for key, role in self.vectors.items():
            setattr(self, key, self._read_vector(self.roles.index(role), specs[key], key))
        for key in self.numbers:
            setattr(self, key, self._read_number(specs[key], key))
        for key, var in self.functions.items():
            setattr(self, key, self._read_function(specs[key], var, key))

    def _read_point(self, role_index, spec, key):
        """Chapter hook: local coordinates of the point ``spec`` of the body in ``role_index``."""
        raise NotImplementedError

    def _read_vector(self, role_index, spec, key):
        """Chapter hook: local components of the body-fixed vector ``spec``."""
        raise NotImplementedError

    def _read_number(self, value, key):
        """A finite real number from a file key (a number, or text read by the safe reader)."""
        if isinstance(value, str):  # the one reader of untrusted text
            return sp.Float(read_number(value, where=f"{self.describe()}, key {key}"), 17)
        if isinstance(value, sp.Number):
            e = value
        elif isinstance(value, numbers.Integral) and not isinstance(value, bool):
            e = sp.Integer(int(value))
        elif isinstance(value, numbers.Real) and not isinstance(value, bool):
            e = sp.Float(float(value), 17)
        else:
            raise ModelError(f"{self.describe()}: `{key}` must be a number, got {value!r}")
        if not (e.is_real and e.is_finite):
            raise ModelError(f"{self.describe()}: `{key}` must be a finite real number, got {value!r}")
        return e

    def _read_function(self, value, var, key):
        """A function of one variable: an expression in ``var`` (text, read by the safe reader, or sympy), or a
        Python callable building one; returns a sympy Lambda."""
        x = sp.Symbol(var, real=True)
        where = f"{self.describe()}, key {key}"
        if isinstance(value, str):  # the one reader of untrusted text
            expr = read_expression(value, symbols={var: x}, where=where)
        elif isinstance(value, sp.Lambda):
            expr = value(x)
        elif isinstance(value, sp.Expr):
            expr = value.subs({s: x for s in value.free_symbols if s.name == var})
        elif callable(value):  # Python code of the caller's own: what it returns is still checked
            expr = value(x)
            if isinstance(expr, str):
                expr = read_expression(expr, symbols={var: x}, where=where)
            elif isinstance(expr, sp.Basic):
                check_expression(expr, where=where)
            else:
                expr = read_constant(expr, where=where)
        else:
            raise ModelError(f"{where}: expected an expression in {var}, got {value!r}")
        extra = expr.free_symbols - {x}
        if extra:
            raise ModelError(f"{where}: the function of {var} uses unknown symbols "
                             f"{', '.join(sorted(map(str, extra)))}")
        return sp.Lambda(x, expr)

    # ------------------------------------------------------------------------------------------- Φ
    @abc.abstractmethod
    def phi(self, Q, t=t_symbol):
        """Symbolic Φ of this constraint: a list of ``n_eq`` sympy expressions in the coordinates ``Q`` of its
        bodies (one sympy column per body, in ``self.bodies`` order); a driver's includes − f(t)."""

    def point(self, Q, key):
        """Symbolic global position of the declared point ``key`` (r + A s')."""
        return self._global_point(Q[self.roles.index(self.points[key])], getattr(self, key))

    def vector(self, Q, key):
        """Symbolic global components of the declared body-fixed vector ``key`` (A s')."""
        return self._global_vector(Q[self.roles.index(self.vectors[key])], getattr(self, key))

    def _global_point(self, Qb, s):
        raise NotImplementedError

    def _global_vector(self, Qb, s):
        raise NotImplementedError

    def _f_expr(self, t):
        return sp.Integer(0) if self.f is None else self.f.subs(t_symbol, t)

    # ------------------------------------------------------------------------------------------- numerics
    def params(self):
        """Numeric parameters of this constraint for its hand-written kernel: a dict of float arrays."""
        return {}

    def numeric(self, compiled=False):
        """The fast numeric path of this constraint: (kernel, parameters).

        The type's hand-written ``kernel`` and :meth:`params` when it has one and ``compiled`` is false;
        otherwise the kernel compiled from :meth:`phi` (one per type, shared by every constraint of the type,
        :func:`kinbook.core.kernels.compiled`). A composite stacks the numeric paths of its parts.
        """
        if self.parts:
            return kernels.stacked([v.numeric(compiled) for v in self.part_views()])
        if self.kernel is not None and not compiled:
            return self.kernel, self.params()
        return kernels.compiled(self)

    # ------------------------------------------------------------------------------------------- composites
    def part_views(self):
        """The parts of a composite as constraints of the part types that read this one's attributes
        (renamed as ``parts`` says), each occupying its rows; empty for a primitive type."""
        if not self.parts:
            return []
        views = self.__dict__.get("_views")
        if views is None or views[0].owner is not self:  # none yet, or those of the original of a copy
            views, start = [], 0
            for cls, rename in self.parts:
                v = object.__new__(cls)
                v.__dict__.update((k, x) for k, x in self.__dict__.items() if k not in _OWN_STATE)
                for attr, own in rename.items():
                    setattr(v, attr, getattr(self, own))
                v.owner, v.offset, v.rows = self, start, None
                start += cls.n_eq
                views.append(v)
            self.__dict__["_views"] = views
        return views

    def _bind_parts(self):
        views = self.part_views()
        self.wrap = {v.offset + r: p for v in views for r, p in v.wrap.items()}
        measures = [v.measures for v in views]
        self.measures = None if any(m is None for m in measures) else tuple(x for m in measures for x in m)

    def _composite_phi(self, Q, t=t_symbol):
        return [e for v in self.part_views() for e in v.phi(Q, t)]

    def _composite_params(self):
        return {k: v for view in self.part_views() for k, v in view.params().items()}


_OWN_STATE = {"_views", "_template", "wrap", "measures", "owner", "offset", "rows"}
"""Attributes a composite does not share with its part views (what the views take from their own class)."""


def _declared_keys(cls):
    keys = [*cls.points, *cls.vectors, *cls.numbers, *cls.functions]
    return tuple(keys)


def _inherits_base_init(cls):
    """True unless the class or a base between it and ConstraintBase writes its own ``__init__``."""
    for klass in cls.__mro__:
        if "__init__" in klass.__dict__:
            return klass is ConstraintBase or getattr(klass.__dict__["__init__"], "declared", False)
    return False


_RESERVED = {"name", "f", "self"}


def _install_init(cls, keys):
    """Give a declarative type its constructor: the body roles, then every declared key, then ``name``."""
    P = inspect.Parameter
    defaults = cls.numbers if isinstance(cls.numbers, dict) else {}
    bad = [k for k in keys if not k.isidentifier() or k in _RESERVED or k in cls.roles or hasattr(ConstraintBase, k)]
    if bad or len(set(keys)) != len(keys):
        raise ModelError(f"constraint class {cls.__name__}: declared key {(bad or [keys])[0]!r} clashes with a name "
                         "the constraint uses itself")
    params = [P(r, P.POSITIONAL_OR_KEYWORD) for r in cls.roles]
    required = [k for k in keys if k not in defaults]
    params += [P(k, P.POSITIONAL_OR_KEYWORD) for k in required]
    if cls.kind == "driver":
        params.append(P("f", P.POSITIONAL_OR_KEYWORD))
    params += [P(k, P.POSITIONAL_OR_KEYWORD, default=defaults[k]) for k in keys if k in defaults]
    params.append(P("name", P.POSITIONAL_OR_KEYWORD, default=None))
    sig = inspect.Signature(params)

    def __init__(self, *args, **kwargs):
        try:
            bound = sig.bind(*args, **kwargs)
        except TypeError as exc:
            raise ModelError(f"{cls.type_name or cls.__name__} constraint: {exc}") from None
        bound.apply_defaults()
        a = bound.arguments
        ConstraintBase.__init__(self, [a[r] for r in cls.roles], name=a["name"], f=a.get("f"))
        self.specs = {k: a[k] for k in keys}

    __init__.__signature__ = inspect.Signature([P("self", P.POSITIONAL_OR_KEYWORD), *params])
    __init__.__qualname__ = f"{cls.__qualname__}.__init__"
    __init__.__doc__ = f"Constraint {cls.type_name or cls.__name__} between the bodies in roles {', '.join(cls.roles)}."
    __init__.declared = True
    cls.__init__ = __init__


def _declare_composite(cls):
    parts = []
    for p in cls.parts:
        part, rename = (p, {}) if isinstance(p, type) else (p[0], dict(p[1]))
        if not (isinstance(part, type) and issubclass(part, ConstraintBase)):
            raise ModelError(f"composite {cls.__name__}: parts must be constraint classes, got {part!r}")
        parts.append((part, rename))
    cls.parts = tuple(parts)
    cls.n_eq = sum(p.n_eq for p, _ in parts)
    if "label" not in cls.__dict__:
        cls.label = " + ".join(p.label for p, _ in parts)
    wrap, start = {}, 0
    for p, _ in parts:
        wrap.update({start + r: v for r, v in p.wrap.items()})
        start += p.n_eq
    cls.wrap = wrap
    if "measures" not in cls.__dict__:
        ms = [p.measures for p, _ in parts]
        cls.measures = None if any(m is None for m in ms) else tuple(x for m in ms for x in m)
    if "phi" not in cls.__dict__:
        cls.phi = ConstraintBase._composite_phi
    if "params" not in cls.__dict__:
        cls.params = ConstraintBase._composite_params


def _register(cls):
    name, chapter = cls.type_name, cls.chapter
    where = f"constraint class {cls.__module__}.{cls.__qualname__}"
    if chapter is None:
        raise ModelError(f"{where}: subclass kinbook.planar.Constraint or kinbook.spatial.Constraint")
    if not isinstance(name, str) or not name:
        raise ModelError(f"{where}: `type_name` must be a non-empty string, got {name!r}")
    if getattr(cls.phi, "__isabstractmethod__", False):
        raise ModelError(f"{where} ('{name}'): write its Φ in phi(self, Q, t)")
    if not isinstance(cls.n_eq, int) or cls.n_eq < 1:
        raise ModelError(f"{where} ('{name}'): `n_eq` must be a positive integer, got {cls.n_eq!r}")
    if cls.kind not in KINDS:
        raise ModelError(f"{where} ('{name}'): `kind` must be one of {', '.join(KINDS)}, got {cls.kind!r}")
    if cls.measures is not None and (len(cls.measures) != cls.n_eq or not set(cls.measures) <= set(MEASURES)):
        raise ModelError(f"{where} ('{name}'): `measures` needs one of {', '.join(MEASURES)} per row "
                         f"({cls.n_eq}), got {cls.measures!r}")
    if any(not (0 <= r < cls.n_eq) for r in cls.wrap):
        raise ModelError(f"{where} ('{name}'): `wrap` names rows outside 0..{cls.n_eq - 1}: {cls.wrap!r}")
    for key, role in [*cls.points.items(), *cls.vectors.items()]:
        if role not in cls.roles:
            raise ModelError(f"{where} ('{name}'): key '{key}' is on role {role!r}, not one of {cls.roles}")
    if cls.__dict__.get("title") is None:
        word = {"joint": "joint", "driver": "driver", "simple": "constraint", "normalization": "equation"}[cls.kind]
        cls.title = {"en": f"{name} {word}", "es": f"{name} {word}"}
    types = _REGISTRY.setdefault(chapter, {})
    old = types.get(name)
    if old is not None and (old.__module__, old.__qualname__) != (cls.__module__, cls.__qualname__):
        raise ModelError(f"{where}: the {chapter} constraint type '{name}' is already "
                         f"{old.__module__}.{old.__qualname__}")
    types[name] = cls  # the same class defined again (a notebook cell run twice) replaces itself


def stack_params(plist):
    """The parameters of k constraints sharing a kernel, stacked: dicts of float arrays (nested for composites)
    → one dict whose arrays have a leading axis k."""
    first = plist[0]
    if isinstance(first, dict):
        return {key: stack_params([p[key] for p in plist]) for key in first}
    return np.array(plist, dtype=float)


class ConstraintGroup:
    """All constraints sharing a kernel and a number of bodies: index maps and stacked parameters.

    ``cols`` (k, ncoord·nb) and ``rows`` (k, r) place every constraint's block in q and Φ, so assembly is a
    fancy-indexed assignment, with no Python loop over entries.
    """

    def __init__(self, constraints, kernel, plist, n, ncoord):
        self.kernel = kernel
        self.constraints = constraints
        self.nb = len(constraints[0].bodies)
        self.ncoord = ncoord
        cols = np.array([[ncoord * (b.number - 1) + k for b in c.bodies for k in range(ncoord)] for c in constraints])
        rows = np.array([list(range(c.rows.start, c.rows.stop)) for c in constraints])
        self.cols, self.rows = cols, rows
        self.jac_rows = np.broadcast_to(rows[:, :, None], rows.shape + (cols.shape[1],)).ravel()
        self.jac_cols = np.broadcast_to(cols[:, None, :], rows.shape + (cols.shape[1],)).ravel()
        self.flat = self.jac_rows * n + self.jac_cols
        self.params = stack_params(plist)

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
    def _compiled(self):
        found = self._cache.get("compiled")
        return found if found is not None else self.cached("compiled", self._compile)

    def _compile(self):
        """Group the constraints by kernel (hand-written or compiled from Φ, per ``kernels``), and gather the
        drivers' f(t) with two derivatives and the rows to wrap with their periods."""
        if not self.bodies:
            raise ModelError(f"mechanism '{self.name}' has no bodies")
        for c in self.constraints:
            params = {s for b in c.bodies for p in b.points.values() for v in p
                      for s in getattr(v, "free_symbols", ())}
            # and the constraint's own numbers (a radius, phi0, a length given as a symbol for a derivation)
            own = [getattr(c, name, None) for name in type(c).parameters]
            for v in own:
                for x in (v.values() if isinstance(v, dict) else v if isinstance(v, (tuple, list)) else (v,)):
                    params |= set(getattr(x, "free_symbols", ()))
            if params:
                names = ", ".join(sorted(map(str, params)))
                raise ModelError(f"{c.describe()} has symbolic parameters ({names}): substitute numbers "
                                 "before a numeric evaluation")
        compiled = self.kernels == "compiled"
        groups = {}
        for c in self.constraints:
            kernel, params = c.numeric(compiled=compiled)
            groups.setdefault((kernel, len(c.bodies), c.n_eq), []).append((c, params))
        drivers = [(c.rows.stop - 1, *time_derivatives(c.f, where=c.describe()))
                   for c in self.constraints if c.f is not None]
        wrap = [(c.rows.start + r, float(period)) for c in self.constraints for r, period in sorted(c.wrap.items())]
        wrap = (np.array([r for r, _ in wrap], dtype=int), np.array([p for _, p in wrap], dtype=float))
        ncoord = len(self.COORDS)
        return ([ConstraintGroup([c for c, _ in g], kernel, [p for _, p in g], self.n, ncoord)
                 for (kernel, _, _), g in groups.items()], drivers, wrap)

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
    def _reduction(self):
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
        return self._check_q(q, name)

    def _check_q(self, q, name="q"):
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

    def _check_t(self, t, batch):
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
        wrap_rows, periods = wrap
        if wrap_rows.size:
            Phi[:, wrap_rows] = np.mod(Phi[:, wrap_rows] + 0.5 * periods, periods) - 0.5 * periods
        out = {"Phi": Phi, "nu": nu, "gamma": gamma}
        if jacobian:
            if sparse:
                if not single:
                    raise InputError("a sparse Φ_q is available for one instant at a time")
                import scipy.sparse as sps  # imported when first needed (see solve._solve)

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
        :class:`~kinbook.core.solve.SimulationResult`. See :func:`kinbook.core.solve.simulate`."""
        return solve.simulate(self, times, q0=q0, tol=tol, on_failure=on_failure, anchor_every=anchor_every)

    def diagnose(self, q, t=0.0):
        """Rank of Φ_q at ``q`` and, when singular, which constraints are dependent: see
        :func:`kinbook.core.solve.diagnose`."""
        return solve.diagnose(self, q, t)

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
