"""The registry of constraint types, per chapter, and what a type declares: its keys (``points``, ``vectors``,
``numbers``, ``constants``, ``functions``, with ``aliases`` and ``defaults``), the constructor generated from them, and the
composites declared by their ``parts``. :class:`~kinbook.core.constraint.ConstraintBase` calls these when a
subclass is defined; docs/extending.md shows the declarations at work.
"""

from __future__ import annotations

import inspect
from types import MappingProxyType
from typing import NamedTuple

from ..errors import ModelError

__all__ = ["constraint_types", "constraint_class", "KINDS", "MEASURES", "QUANTITIES", "Key", "declared_keys",
           "key_defaults", "default_parameters", "install_init", "declare_composite", "register"]

KINDS = ("joint", "simple", "driver", "normalization")
"""What a constraint can be: joints are numbered as the book numbers them in its joint tables; simple
constraints fix coordinates of one body; drivers are left out of the degrees-of-freedom count;
normalization rows (spatial) belong to one body."""

MEASURES = ("length", "length^2", "angle", "ratio")
"""What a row of Φ can measure (``Constraint.measures``): a distance, a product of two distances (dot and
cross products of body vectors, squared lengths), an angle in radians, or a pure number."""

QUANTITIES = ("length", "radius", "angle")
"""What a numeric parameter of a constraint can be (``Constraint.quantities``): a length that Φ squares, a signed
pitch radius, an angle in radians."""

_REGISTRY = {}

_DECLARATIONS = ("points", "vectors", "numbers", "constants", "functions")


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


class Key(NamedTuple):
    """One declared key of a constraint type.

    ``kind`` is "point", "vector", "number", "constant" or "function"; ``role`` the body role of a point or vector (None
    otherwise); ``attrs`` the attributes its value binds to (the key itself unless the declaration names
    them; several for a key that takes a list of points, such as the two points of an axis); ``var`` the
    variable of a function.
    """

    key: str
    kind: str
    role: str | None
    attrs: tuple
    var: str | None = None

    @property
    def count(self):
        """How many points (vectors) the key takes as a list, or None for one."""
        return len(self.attrs) if len(self.attrs) > 1 else None


def _geometry(key, kind, spec):
    if isinstance(spec, str):
        return Key(key, kind, spec, (key,))
    role, attrs = spec
    return Key(key, kind, role, (attrs,) if isinstance(attrs, str) else tuple(attrs))


def declared_keys(cls):
    """The keys ``cls`` declares, in the order of its constructor: the declarations it inherits first (points,
    vectors, numbers, constants, functions), then its own in the order the class body writes them."""
    own = [n for n in cls.__dict__ if n in _DECLARATIONS]
    keys = []
    for name in [n for n in _DECLARATIONS if n not in own] + own:
        value = getattr(cls, name)
        if name in ("points", "vectors"):
            keys += [_geometry(k, name[:-1], spec) for k, spec in value.items()]
        elif name in ("numbers", "constants"):
            keys += [Key(k, name[:-1], None, (k,)) for k in value]
        else:
            keys += [Key(k, "function", None, (k,), var) for k, var in value.items()]
    return tuple(keys)


def key_defaults(cls):
    """{key: default} of the keys a constructor may leave out: ``defaults``, a ``numbers`` dict, and the keys an
    alias gives (None: the alias fills them in)."""
    out = {k: None for keys in cls.aliases.values() for k in keys}
    out.update(cls.numbers if isinstance(cls.numbers, dict) else {})
    out.update(cls.defaults)
    return out


def default_parameters(cls):
    """The attributes a type's :meth:`phi` reads when it does not say (``parameters``): everything its points,
    vectors, numbers and constants bind (functions stay in the compiled Φ); for a composite, its parts' parameters under
    the composite's names."""
    if cls.parts:
        out = []
        for part, rename in cls.parts:
            out += [rename.get(a, a) for a in part.parameters if rename.get(a, a) not in out]
        return tuple(out)
    return tuple(a for k in cls._keys if k.kind != "function" for a in k.attrs)


_RESERVED = {"name", "f", "self"}


def install_init(cls, base):
    """Give a declarative type its constructor: the body roles, the required keys, ``f`` for a driver, the keys
    that may be left out (an alias just before the keys it gives), then ``name``."""
    P = inspect.Parameter
    keys = [k.key for k in cls._keys]
    defaults = key_defaults(cls)
    bad = [k for k in keys if not k.isidentifier() or k in _RESERVED or k in cls.roles or hasattr(base, k)]
    bad += [a for a in cls.aliases if not a.isidentifier() or a in _RESERVED or a in cls.roles or a in keys]
    if bad or len(set(keys)) != len(keys):
        raise ModelError(f"constraint class {cls.__name__}: declared key {(bad or [keys])[0]!r} clashes with a name "
                         "the constraint uses itself")
    params = [P(r, P.POSITIONAL_OR_KEYWORD) for r in cls.roles]
    params += [P(k, P.POSITIONAL_OR_KEYWORD) for k in keys if k not in defaults]
    if cls.kind == "driver":
        params.append(P("f", P.POSITIONAL_OR_KEYWORD))
    for k in keys:
        params += [P(a, P.POSITIONAL_OR_KEYWORD, default=None) for a, given in cls.aliases.items() if given[0] == k]
        if k in defaults:
            params.append(P(k, P.POSITIONAL_OR_KEYWORD, default=defaults[k]))
    params.append(P("name", P.POSITIONAL_OR_KEYWORD, default=None))
    sig = inspect.Signature(params)
    taken = [p.name for p in params if p.name not in cls.roles and p.name not in ("f", "name")]

    def __init__(self, *args, **kwargs):
        try:
            bound = sig.bind(*args, **kwargs)
        except TypeError as exc:
            raise ModelError(f"{cls.type_name or cls.__name__} constraint: {exc}") from None
        bound.apply_defaults()
        a = bound.arguments
        base.__init__(self, [a[r] for r in cls.roles], name=a["name"], f=a.get("f"))
        self._take_keys({k: a[k] for k in taken})

    __init__.__signature__ = inspect.Signature([P("self", P.POSITIONAL_OR_KEYWORD), *params])
    __init__.__qualname__ = f"{cls.__qualname__}.__init__"
    __init__.__doc__ = f"Constraint {cls.type_name or cls.__name__} between the bodies in roles {', '.join(cls.roles)}."
    __init__.declared = True
    cls.__init__ = __init__


def declare_composite(cls, base):
    """Complete a composite from its ``parts``: the number of rows, the label, the rows to wrap, the measures,
    and Φ and the parameters stacked from the parts."""
    parts = []
    for p in cls.parts:
        part, rename = (p, {}) if isinstance(p, type) else (p[0], dict(p[1]))
        if not (isinstance(part, type) and issubclass(part, base)):
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
        cls.phi = base.composite_phi
    if "params" not in cls.__dict__:
        cls.params = base.composite_params


def register(cls):
    """Check a type's declarations and enter it in its chapter's registry under ``type_name``."""
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
    for k in cls._keys:
        if k.role is not None and k.role not in cls.roles:
            raise ModelError(f"{where} ('{name}'): key '{k.key}' is on role {k.role!r}, not one of {cls.roles}")
    if not set(cls.quantities.values()) <= set(QUANTITIES):
        raise ModelError(f"{where} ('{name}'): `quantities` must be one of {', '.join(QUANTITIES)} each, got "
                         f"{cls.quantities!r}")
    title = cls.__dict__.get("title")
    if title is None:
        word = {"joint": "joint", "driver": "driver", "simple": "constraint", "normalization": "equation"}[cls.kind]
        cls.title = f"{name} {word}"
    elif not isinstance(title, str) or not title.strip():
        raise ModelError(f"{where} ('{name}'): `title` must be a text, its English (\"cam and follower\"; kinbook's "
                         f"own types mark it N_(\"…\"), their Spanish in the package's catalogue), got {title!r}")
    types = _REGISTRY.setdefault(chapter, {})
    old = types.get(name)
    if old is not None and (old.__module__, old.__qualname__) != (cls.__module__, cls.__qualname__):
        raise ModelError(f"{where}: the {chapter} constraint type '{name}' is already "
                         f"{old.__module__}.{old.__qualname__}")
    types[name] = cls  # the same class defined again (a notebook cell run twice) replaces itself
