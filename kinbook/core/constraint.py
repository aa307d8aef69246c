"""The constraint family both chapters share: an abstract base whose subclasses register themselves by type name,
per chapter (:mod:`kinbook.core.registry`), bind the keys they declare (``points``, ``vectors``, ``numbers``,
``functions``) and write their Φ; composites stack the rows of their ``parts``.

:mod:`kinbook.planar` and :mod:`kinbook.spatial` subclass :class:`ConstraintBase` and add only what depends on
the coordinates. How to add a constraint type: docs/extending.md.
"""

from __future__ import annotations

import abc
import numbers

import sympy as sp

from ..errors import ModelError, UnknownPointError
from . import kernels, registry
from .bounds import check_expression
from .reader import read_constant, read_expression, read_number
from .symbolic import t as t_symbol
from .symbolic import time_function as read_time_function

__all__ = ["ConstraintBase", "time_function", "lookup_point", "sequence"]


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
    title : str
        Its name in messages and tables, in English (``"revolute joint"``): kinbook's own types mark it
        ``N_("revolute joint")`` and the package's catalogue holds its Spanish (par de revolución); a title the
        catalogue does not have is shown as written.
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
        coordinates, read in :meth:`phi` with :meth:`point` and :meth:`vector`. ``{key: (role, attribute)}``
        binds them to another attribute (the value as given stays under the key); ``{key: (role, (a, b))}``
        takes a list of two points (vectors) and binds them to ``a`` and ``b`` (the two points of an axis).
    numbers : tuple or dict
        File keys of numeric parameters (a dict gives defaults); bound to sympy numbers.
    constants : tuple
        File keys of parameters kept exact (``"3*pi/4"`` stays π·3/4) that may also be symbolic (a sympy symbol,
        or text naming one: ``"l/2"``) for a symbolic derivation; read when the constraint is made
        (:func:`kinbook.core.reader.read_constant`), so a bad value is refused there. One whose ``quantities``
        entry is ``"length"`` must be positive. A key in ``defaults`` with None may be left out (None, for
        :meth:`_complete` to fill in).
    functions : dict
        ``{key: variable}``: file keys of functions of one variable, written as expressions in it
        (``"2 + cos(psi)"``); bound to a sympy Lambda, called in :meth:`phi` as ``self.profile(ψ)``.
    aliases : dict
        ``{alias: (key, …)}``: a key that gives several others at once, when they are not given themselves
        (``point`` for both ``point_i`` and ``point_j``).
    defaults : dict
        ``{key: value}``: keys the constructor may leave out. With None the key stays unbound (its attributes
        None) and the type's :meth:`_complete` fills them in (an axis perpendicular by default, a value from
        the bodies' q0).
    quantities : dict
        ``{attribute: "length" | "radius" | "angle"}``: what a numeric parameter is, for the checkers (a length
        that Φ squares, a signed pitch radius, an angle); ``"attr[key]"`` names an entry of a tuple or dict.
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
    constants = ()
    functions = {}
    aliases = {}
    defaults = {}
    quantities = {}
    parameters = ()
    kernel = None
    owner = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        own = cls.__dict__
        if own.get("parts"):
            registry.declare_composite(cls, ConstraintBase)
        cls._keys = registry.declared_keys(cls)
        if "parameters" not in own and (cls._keys or own.get("parts")):
            cls.parameters = registry.default_parameters(cls)
        if (cls._keys or own.get("type_name") is not None) and _inherits_declared_init(cls):
            registry.install_init(cls, ConstraintBase)
        if own.get("type_name") is not None:
            registry.register(cls)

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
        noun = kind.get(self.kind, self.kind)
        title = self.type_name if self.type_name.split("_")[-1] == noun else f"{self.type_name} {noun}"
        what = f"{title} '{self.name}'"  # "driver 'driver 1'", not "driver driver …"
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

    def _take_keys(self, given):
        """Keep the declared keys as given (``self.specs``) for :meth:`bind`: an alias gives the keys left
        out, and a key that takes a list of points must have as many."""
        given, cls = dict(given), type(self)
        for alias, keys in cls.aliases.items():
            value = given.pop(alias, None)
            given.update({k: value for k in keys if given.get(k) is None})
            if any(given.get(k) is None for k in keys):
                which = ("both " if len(keys) == 2 else "all of ") + " and ".join(f"`{k}`" for k in keys)
                raise ModelError(f"{self._where()}: give `{alias}` or {which}")
        for k in cls._keys:
            if k.count and given.get(k.key) is not None:
                body = self.body_names[cls.roles.index(k.role)]
                given[k.key] = sequence(given[k.key], k.count, f"{self._where()}: {k.key} "
                                         f"({_COUNT.get(k.count, k.count)} {k.kind}s of '{body}')")
            if k.attrs != (k.key,) and k.key in given:
                setattr(self, k.key, given[k.key])
            if k.kind == "constant":
                setattr(self, k.key, self._read_constant(given.get(k.key), k.key))
        self.specs = given

    def _read_constant(self, value, key):
        """A declared constant as given: exact, possibly symbolic; None when it may be left out."""
        cls = type(self)
        if value is None and key in cls.defaults and cls.defaults[key] is None:
            return None
        where = f"{self._where()}, {key}"  # read as it is given: a symbol for a symbolic derivation, too
        value = read_constant(value, where=where, symbolic=True)
        if cls.quantities.get(key) == "length" and value.is_positive is False:  # ≤ 0, or a symbol known not > 0
            raise ModelError(f"{where} must be a positive number, got {value}")
        return value

    def _where(self):
        """The constraint named by its bodies, before it has a name or rows: "revolute joint between 'a' and
        'b'"."""
        title = self.title or str(self.type_name)
        names = self.body_names
        if len(names) == 1:
            return f"{title} on body '{names[0]}'"
        return f"{title} between '{names[0]}' and '{names[1]}'"

    def _bind_points(self):
        """Bind the declared keys to the bodies (points and vectors to their local coordinates, numbers and
        functions to sympy), then :meth:`_complete` the rest."""
        specs = getattr(self, "specs", None) or {}
        for k in type(self)._keys if specs else ():
            if k.kind == "constant":  # read when the constraint was made
                continue
            value = specs.get(k.key)
            if value is None and k.key in type(self).defaults and type(self).defaults[k.key] is None:
                for attr in k.attrs:
                    setattr(self, attr, None)
                continue
            if k.kind in ("point", "vector"):
                read = self._read_point if k.kind == "point" else self._read_vector
                role = self.roles.index(k.role)
                values = [read(role, v, k.key) for v in value] if k.count else [read(role, value, k.key)]
                for attr, v in zip(k.attrs, values):
                    setattr(self, attr, v)
            elif k.kind == "number":
                setattr(self, k.key, self._read_number(value, k.key))
            else:
                setattr(self, k.key, self._read_function(value, k.var, k.key))
        self._complete()

    def _complete(self):
        """Hook: what follows from the bound keys (perpendiculars of an axis, a default from the bodies' q0)
        and the checks that need the bodies. The default has nothing to add."""
        return None

    @classmethod
    def declared(cls, kind):
        """(attribute, role index) of each declared ``kind`` ("point" or "vector") that :meth:`phi` reads (the
        type's ``parameters``): what the checkers may vary."""
        reads = set(cls.parameters)
        return tuple((a, cls.roles.index(k.role)) for k in cls._keys if k.kind == kind for a in k.attrs if a in reads)

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
        return self.global_point(Q[self.roles.index(self.points[key])], getattr(self, key))

    def vector(self, Q, key):
        """Symbolic global components of the declared body-fixed vector ``key`` (A s')."""
        return self.global_vector(Q[self.roles.index(self.vectors[key])], getattr(self, key))

    def global_point(self, Qb, s):
        raise NotImplementedError

    def global_vector(self, Qb, s):
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

    def composite_phi(self, Q, t=t_symbol):
        return [e for v in self.part_views() for e in v.phi(Q, t)]

    def composite_params(self):
        return {k: v for view in self.part_views() for k, v in view.params().items()}


_OWN_STATE = {"_views", "_template", "wrap", "measures", "owner", "offset", "rows"}
"""Attributes a composite does not share with its part views (what the views take from their own class)."""

_COUNT = {2: "two", 3: "three"}


def sequence(value, n, where):
    """``value`` as a tuple of ``n`` items (a list or tuple, not text or a table)."""
    if not isinstance(value, (list, tuple)) or len(value) != n:
        got = f"{len(value)} values" if isinstance(value, (list, tuple)) else f"{type(value).__name__} {value!r}"
        raise ModelError(f"{where}: expected a list of {n} values, got {got}")
    return tuple(value)


def _inherits_declared_init(cls):
    """True unless the class or a base between it and ConstraintBase writes its own ``__init__``."""
    for klass in cls.__mro__:
        if "__init__" in klass.__dict__:
            return klass is ConstraintBase or getattr(klass.__dict__["__init__"], "declared", False)
    return False
