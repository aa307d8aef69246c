"""The constraint family both chapters share: an abstract base whose subclasses register themselves by type name,
per chapter; the keys a type declares (``points``, ``vectors``, ``numbers``, ``functions``) and the constructor
generated from them; composites declared by their ``parts``.

:mod:`kinbook.planar` and :mod:`kinbook.spatial` subclass :class:`ConstraintBase` and add only what depends on
the coordinates. How to add a constraint type: docs/extending.md.
"""

from __future__ import annotations

import abc
import inspect
import numbers
from types import MappingProxyType

import sympy as sp

from ..errors import ModelError, UnknownPointError
from . import kernels
from .reader import check_expression, read_constant, read_expression, read_number
from .symbolic import t as t_symbol
from .symbolic import time_function as read_time_function

__all__ = ["ConstraintBase", "time_function", "lookup_point", "constraint_types", "constraint_class", "KINDS",
           "MEASURES"]


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
