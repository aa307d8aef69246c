"""Wrong answers generated from the reference: how the mistake catalogue is detected.

Every catalogued mistake is *made* here, on kinbook's own constraint, and the student's answer is compared
with the result: a code is reported only when the answer is that mistake. Two families:

* **Structural** variants re-write one constraint's Φ the way a student gets it wrong, by changing what goes
  into the constraint's own :meth:`phi` — never by re-typing its formula: the local points of bodies i and j
  exchanged, the bodies exchanged, Aᵀ for A (φ → −φ in A(φ); e → −e in A(p)), A omitted (φ = 0; p =
  [1, 0, 0, 0]), the sign of one local coordinate, of a whole A s' or of a coordinate term, l for l², a
  pitch radius with the wrong sign, angles in degrees, the book's misprinted forms (with their erratum id).
  Their Φ_q, ν and γ come from the jets of their tapes: a student who carried such a Φ through a correct
  derivation is recognised in every quantity.
* **Derivation** variants take a Φ (kinbook's, or the student's own for error carried forward) and derive
  Φ_q, ν or γ the way a student gets *the derivation* wrong: the chain-rule term ∂(A s')/∂φ dropped, A where
  B belongs, ν = +Φ_t, γ with the wrong sign, without 2Φ_qt q̇ or Φ_tt, φ̇ without its square.

What a constraint class offers the catalogue is read from its declaration (the points and vectors its Φ reads,
by body role; its lengths, radii and angles), so a type written the documented way gets the catalogue of a
built-in one; what only the catalogue knows (book forms, swaps, hint contexts) is registered by class in
:data:`SPECS`, looked up along the class's MRO, never by type name.
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from .. import planar as P
from .. import spatial as S
from . import slips
from ._i18n import Msg
from .misprints import EX4_PHI8, book_n1_acceleration
from .quantities import for_quantities, quantity_of
from .slips import book_A_rows, n1_own_arm, n2_without_dC

__all__ = ["Variant", "Spec", "SPECS", "spec_of", "structural", "alternative_variants", "contexts_of", "register",
           "length_factors", "book_form", "book_rows"]

DEG = 180.0 / np.pi


@dataclass
class Spec:
    """What the catalogue knows about a constraint class.

    ``points``, ``vectors``, ``angles``, ``radii``, ``lengths``, ``frame``: from the class (:func:`spec_of`).

    Attributes
    ----------
    points : tuple of (attribute, role index)
        Local points read by :meth:`phi` (planar (ξ, η), spatial (ξ, η, ζ)).
    vectors : tuple of (attribute, role index)
        Local vectors (spatial: axes, arms) read by :meth:`phi`.
    swap_points : tuple of (attribute, attribute)
        Pairs of points of bodies i and j that a student may exchange.
    swap_bodies : bool
        The roles of i and j are not symmetric: exchanging the bodies is a mistake of its own.
    angles : tuple of str
        Attributes holding angles (a number, a tuple, a dict entry "attr[key]").
    radii : tuple of str
        Attributes holding pitch radii (a sign mistake per radius).
    lengths : tuple of str
        Attributes holding a length l that Φ squares (l for l² is a mistake).
    driver_angle : bool
        The driver prescribes an angle: f(t) in degrees is a mistake.
    frame : {"planar", "spatial", None}
        Aᵀ for A and A omitted are generated (for classes with points or vectors).
    context : tuple of str
        Hint contexts of the class (catalogue contexts: "gear", "rack", "driver" …).
    book : tuple of callables
        ``f(c) -> (changes, erratum id, code)``: the book's misprinted forms of Φ as attribute changes.
    extra : tuple of callables
        ``f(target, c, Q) -> [(code, Φ rows, detail, erratum)]``: other structural variants.
    alternative : callable or None
        ``f(c, Q) -> rows``: the book's own formulation when kinbook writes the constraint another way (the
        cross-product rows s̃_i s_j of a parallel constraint); its mistakes are recognised too.
    derived_book : tuple of callables
        ``f(target, c, samples, reference, quantity) -> [(row in c's block, values, erratum)]``: the book's
        misprinted Jacobian entries and γ rows, made from kinbook's own reference values at the samples; each
        declares the quantities it is made for (:func:`kinbook.grading.quantities.for_quantities`).
    derived_slips : tuple of callables
        ``f(target, c, samples, reference, quantity) -> [(row in c's block, values, code, detail)]``: a student's
        slips in deriving Φ_q, ν or γ made the same way (n2's dᵀC_i left out), declared the same way.
    """

    points: tuple = ()
    vectors: tuple = ()
    swap_points: tuple = ()
    swap_bodies: bool = False
    angles: tuple = ()
    radii: tuple = ()
    lengths: tuple = ()
    driver_angle: bool = False
    frame: str | None = None
    context: tuple = ()
    book: tuple = ()
    extra: tuple = ()
    derived_book: tuple = ()
    derived_slips: tuple = ()
    alternative: object = None


SPECS = {}
"""Constraint class → its registered :class:`Spec` (filled by :func:`register` and :func:`_defaults`)."""

_DERIVED = {}


def register(cls, spec):
    """Declare what only the catalogue knows of ``cls`` and its subclasses: book forms, swaps, hint contexts."""
    SPECS[cls] = spec
    _DERIVED.clear()


def spec_of(c):
    """The Spec of a constraint: what its class declares, with what is registered for it or its nearest base."""
    cls = type(c)
    if cls not in _DERIVED:
        if not SPECS:
            _defaults()
        generic = Spec(context=("driver",) if c.kind == "driver" else ())
        _DERIVED[cls] = _declared(cls, next((SPECS[k] for k in cls.__mro__ if k in SPECS), generic))
    return _DERIVED[cls]


def _declared(cls, spec):
    """``spec`` with what the class declares: the points and vectors :meth:`phi` reads, the numeric
    ``quantities``, and the chapter's frame when it has points or vectors."""
    points, vectors = (cls.declared(k) if hasattr(cls, "declared") else () for k in ("point", "vector"))
    of = lambda kind: tuple(a for a, q in getattr(cls, "quantities", {}).items() if q == kind)  # noqa: E731
    return dataclasses.replace(spec, points=points, vectors=vectors, lengths=of("length"), radii=of("radius"),
                               angles=of("angle"), frame=cls.chapter if points or vectors else None)


def contexts_of(c, quantity=None):
    """Hint contexts for a mistake found in a row of ``c``: the class's, then the quantity's, then the chapter."""
    ctx = list(spec_of(c).context)
    if c.kind == "driver" and "driver" not in ctx:
        ctx.append("driver")
    if c.kind == "normalization":
        ctx.append("normalization")
    chapter = getattr(c, "chapter", None) or ("spatial" if len(getattr(c, "COORDS", ())) == 7 or _is_spatial(c)
                                              else "planar")
    if chapter == "spatial":  # the speed and acceleration hints write planar formulas (eqs. 10, 13)
        ctx.append(chapter)
    hint = quantity_of(quantity).hint_context if quantity is not None else None
    if hint:
        ctx.append(hint)
    if chapter != "spatial":
        ctx.append(chapter)
    return tuple(ctx)


def _is_spatial(c):
    mech = getattr(c, "mechanism", None)
    return getattr(mech, "kind", "planar") == "spatial"


@dataclass
class Variant:
    """One generated mistake of one constraint.

    Attributes
    ----------
    code : str
        Catalogue code.
    exprs : list of sympy expressions
        The variant's Φ rows (the constraint's rows, in order), in the mechanism's symbols.
    detail : Msg or None
        What exactly (named after the title: "the sign of η_j").
    erratum : str or None
        Id of the book's erratum when the variant is the book's printed (wrong) formula.
    """

    code: str
    exprs: list
    detail: object = None
    erratum: str | None = None
    cache: dict = field(default_factory=dict, repr=False)
    derived: bool = True
    """Also tried on Φ_q, ν and γ (A left local on one body is, in γ, a missing term: named so there)."""


# ============================================================================================ structural
def structural(target, c):
    """The structural variants of constraint ``c`` (cached on the target)."""
    key = ("variants", tuple(target.block(c)))
    if key in target.store:
        return target.store[key]
    out = []
    try:
        out = list(_structural(target, c))
    finally:
        target.store[key] = out
    return out


def _phi(target, c, Q=None, **changes):
    """Φ rows of a copy of ``c`` with attributes changed, at body coordinates ``Q`` (default: the mechanism's
    symbols of c's bodies)."""
    mech = target.mech
    cc = copy.copy(c)
    cc.__dict__.pop("_views", None)
    cc.__dict__.pop("_template", None)
    for name, value in changes.items():
        if "[" in name:
            attr, k = name[:-1].split("[")
            d = dict(getattr(cc, attr))
            d[k] = value
            setattr(cc, attr, d)
        else:
            setattr(cc, name, value)
    if Q is None:
        Q = [mech.body_symbols(b.name) for b in c.bodies]
    return list(cc.phi(Q, mech.t))


def _neg(v, k=None):
    out = list(v) if not isinstance(v, np.ndarray) else v.copy()
    if isinstance(out, np.ndarray):
        if k is None:
            return -out
        out[k] = -out[k]
        return out
    if k is None:
        return tuple(-x for x in out)
    out[k] = -out[k]
    return tuple(out)


def _is_zero(x):
    try:
        return float(x) == 0.0
    except (TypeError, ValueError):
        return False


def _coords(c):
    return ("ξ", "η", "ζ")


def _add(code, exprs, detail=None, erratum=None):
    yield Variant(code, exprs, detail, erratum)


def _safe(fn):
    try:
        return fn()
    except Exception:  # a variant that cannot be built for this constraint is skipped
        return None


def _structural(target, c):
    """The catalogue's structural variants of constraint ``c``, in a fixed order: exchanged points and bodies,
    A transposed or omitted, signs, degrees, the book's printed forms."""
    spec = spec_of(c)
    Q = [target.mech.body_symbols(b.name) for b in c.bodies]
    names = [b.name for b in c.bodies]
    yield from _exchanged(target, c, spec, Q)
    yield from _frames(target, c, spec, Q, names)
    yield from _signs(target, c, spec, Q, names)
    yield from _degrees_and_forms(target, c, spec, Q)


def _exchanged(target, c, spec, Q):
    """Exchanged points, bodies, radii."""
    mech, add, safe = target.mech, _add, _safe
    for a, b in spec.swap_points:
        e = safe(lambda a=a, b=b: _phi(target, c, **{a: getattr(c, b), b: getattr(c, a)}))
        if e is not None:
            yield from add("swapped_points", e)
    if spec.swap_bodies and len(Q) >= 2:
        e = safe(lambda: list(c.phi([Q[1], Q[0]] + Q[2:], mech.t)))
        if e is not None:
            yield from add("swapped_bodies", e)
    if len(spec.radii) == 2:
        a, b = spec.radii
        e = safe(lambda: _phi(target, c, **{a: getattr(c, b), b: getattr(c, a)}))
        if e is not None:
            yield from add("swapped_bodies", e)


def _frames(target, c, spec, Q, names):
    """Aᵀ for A, A omitted, the book's A(p)."""
    mech, add, safe = target.mech, _add, _safe
    # Aᵀ for A, A omitted — on every body, then on one body only (the ground's A transposed …): made from the
    # constraint's own rows by substitution in A (cheap), never by re-deriving them
    if spec.frame and (spec.points or spec.vectors):
        base = safe(lambda: list(c.phi(Q, mech.t)))
        if base is not None:
            everyone = list(range(len(Q)))
            for code in ("A_transposed", "local_vector"):
                e = safe(lambda code=code: _frame_variant(base, Q, everyone, code, spec.frame))
                if e is not None:
                    yield from add(code, e)
            if len(Q) >= 2:
                for role in everyone:
                    for code, what in (("A_transposed", "Aᵀ"), ("local_vector", "s'")):
                        e = safe(lambda code=code, role=role: _frame_variant(base, Q, [role], code, spec.frame))
                        if e is not None:
                            yield Variant(code, e, Msg("d.on_body", what=what, body=names[role]),
                                          derived=code == "A_transposed")
            if spec.frame == "planar":  # sin φ and cos φ exchanged in every A(φ) (eq. 5 misremembered)
                e = safe(lambda: _frame_variant(base, Q, everyone, "sin_cos", spec.frame))
                if e is not None:
                    yield from add("sin_cos", e)
            if len(Q) == 2 and (spec.frame == "planar" or _both_arms(c, spec)):
                # one body's A read with the other body's angle (φ_j for φ_i; p_j for p_i), or both; in space
                # only where both bodies carry an arm (a point at a body's origin leaves its A out of the rows)
                for roles in ([0], [1], [0, 1]):
                    e = safe(lambda roles=roles: _other_angle(base, Q, roles, spec.frame))
                    if e is not None:
                        detail = (Msg("d.angles_exchanged") if len(roles) == 2 else
                                  Msg("d.other_angle", body=names[roles[0]], other=names[1 - roles[0]]))
                        yield Variant("other_body", e, detail)
        if spec.frame == "spatial":  # the matrix §14.3 prints for A(p), copied into the joint
            e = safe(lambda: book_A_rows(c, Q, mech.t))
            if e is not None:
                yield from add("book_misprint", e, None, "14.3-A-of-p")


def _signs(target, c, spec, Q, names):
    """The sign of one local coordinate, of a whole A s', of a coordinate term, of a radius; a length for its
    square."""
    mech, add, safe, roles = target.mech, _add, _safe, "ijk"
    # the sign of one local coordinate, of a whole A s', of a coordinate term
    for attr, role in spec.points + spec.vectors:
        v = getattr(c, attr, None)
        if v is None:
            continue
        for k, x in enumerate(v):
            if _is_zero(x):
                continue
            e = safe(lambda attr=attr, k=k: _phi(target, c, **{attr: _neg(getattr(c, attr), k)}))
            if e is not None:
                coord = f"{_coords(c)[k]}_{roles[role]}"
                yield from add("sign_flip", e, Msg("d.sign_of", what=Msg("d.coordinate", name=coord,
                                                                              body=names[role])))
        if sum(1 for x in v if not _is_zero(x)) > 1:
            e = safe(lambda attr=attr: _phi(target, c, **{attr: _neg(getattr(c, attr))}))
            if e is not None:
                yield from add("sign_flip", e, Msg("d.sign_of", what=f"A_{roles[role]} s'_{roles[role]}"))
    if spec.points:
        nxyz = 2 if spec.frame == "planar" else 3
        for role in range(len(Q)):
            for k in range(nxyz):
                Qs = [sp.Matrix(x) for x in Q]
                Qs[role][k] = -Qs[role][k]
                e = safe(lambda Qs=Qs: list(c.phi(Qs, mech.t)))
                if e is not None:
                    coord = "xyz"[k] + "_" + roles[role]
                    yield from add("sign_flip", e, Msg("d.sign_of", what=coord))
    for attr in spec.radii:
        e = safe(lambda attr=attr: _phi(target, c, **{attr: -getattr(c, attr)}))
        if e is not None:
            yield from add("sign_flip", e, Msg("d.sign_of", what=Msg("d.radius", body=names[spec.radii.index(attr)])))
    for attr in spec.lengths:
        e = safe(lambda attr=attr: _phi(target, c, **{attr: sp.sqrt(getattr(c, attr))}))
        if e is not None:
            yield from add("missing_square", e, Msg("d.length_not_squared"))
        e = safe(lambda attr=attr: _phi(target, c, **{attr: 0}))
        if e is not None:
            yield from add("missing_term", e, Msg("d.length_dropped"))


def _degrees_and_forms(target, c, spec, Q):
    """Degrees for radians (a constant angle, a driver's function), a driver's sign, the book's printed forms
    and the type's own extra variants."""
    mech, add, safe = target.mech, _add, _safe
    # degrees
    for attr in spec.angles:
        e = safe(lambda attr=attr: _degrees(target, c, attr))
        if e is not None:
            yield from add("degrees", e, Msg("d.constant_degrees", name=_angle_name(attr)))
    if c.kind == "driver" and spec.driver_angle and getattr(c, "f", None) is not None:
        f = c.f
        f0 = f.subs(mech.t, 0)
        for g, detail in ((f * DEG, Msg("d.function_degrees")), (f - f0 + f0 * DEG, Msg("d.constant_degrees",
                                                                                         name="φ⁰")),
                          (f0 + (f - f0) * DEG, Msg("d.motion_degrees"))):
            e = safe(lambda g=g: _phi(target, c, f=sp.expand(g)))
            if e is not None:
                yield from add("degrees", e, detail)
        e = safe(lambda: _phi(target, c, f=-f))
        if e is not None:
            yield from add("sign_flip", e, Msg("d.sign_of", what="f(t)"))
    # the book's printed forms
    for book in spec.book:
        made = safe(lambda book=book: book(c))
        if not made:
            continue
        changes, erratum, code = made
        e = safe(lambda changes=changes: _phi(target, c, **changes))
        if e is not None:
            yield from add(code, e, None, erratum)
    for extra in spec.extra:
        for item in safe(lambda extra=extra: list(extra(target, c, Q))) or ():
            yield from add(*item)


def _frame_variant(rows, Q, roles, code, frame):
    """Rows with A(φ) / A(p) of the bodies ``roles`` transposed ("A_transposed": sin φ → −sin φ; e → −e) or
    left out ("local_vector": φ → 0 in A; p → [1, 0, 0, 0]); a planar row that reads an angle directly (a
    translational joint's φ_i − φ_j) keeps it — only A holds trigonometric functions of φ."""
    if frame == "planar":
        out = []
        swap = {sp.sin: sp.cos, sp.cos: sp.sin}
        for r in rows:
            for role in roles:
                phi = Q[role][2]
                if code == "sin_cos":
                    r = r.replace(lambda e, phi=phi: isinstance(e, (sp.sin, sp.cos)) and e.has(phi),
                                  lambda e: swap[e.func](e.args[0]))
                elif code == "A_transposed":
                    r = r.replace(lambda e, phi=phi: isinstance(e, sp.sin) and e.has(phi),
                                  lambda e, phi=phi: sp.sin(e.args[0].xreplace({phi: -phi})))
                else:
                    r = r.replace(lambda e, phi=phi: isinstance(e, (sp.sin, sp.cos)) and e.has(phi),
                                  lambda e, phi=phi: e.func(e.args[0].xreplace({phi: 0})))
            out.append(r)
        return out
    sub = {}
    for role in roles:
        e0, e1, e2, e3 = Q[role][3:7]
        sub.update({e1: -e1, e2: -e2, e3: -e3} if code == "A_transposed" else {e0: 1, e1: 0, e2: 0, e3: 0})
    return [r.xreplace(sub) for r in rows]


def _both_arms(c, spec):
    """Every local point or vector of the constraint is nonzero (each body's A enters its rows)."""
    arms = [getattr(c, attr, None) for attr, _ in spec.points + spec.vectors]
    return bool(arms) and all(v is not None and not all(_is_zero(x) for x in v) for v in arms)


def _other_angle(rows, Q, roles, frame):
    """Rows with the A of the bodies ``roles`` built from the other body's orientation (planar: φ_j for φ_i
    inside the trigonometric functions; spatial: p_j for p_i; both roles: the two exchanged). None when the rows
    do not change (no A on those bodies)."""

    sub = {}
    for role in roles:
        mine, other = (Q[role][2:3], Q[1 - role][2:3]) if frame == "planar" else (Q[role][3:7], Q[1 - role][3:7])
        sub.update(zip(mine, other))
    if frame == "planar":
        out = [r.replace(lambda e: isinstance(e, (sp.sin, sp.cos)) and e.has(*sub),
                         lambda e: e.func(e.args[0].xreplace(sub))) for r in rows]
    else:
        out = [r.xreplace(sub) for r in rows]
    return None if all(a == b for a, b in zip(out, rows)) else out


def _angle_name(attr):
    return {"phi0": "φ⁰", "value[2]": "φ⁰", "value": "φ⁰"}.get(attr, attr)


def _degrees(target, c, attr):
    """Φ with the angle attribute ``attr`` (phi0, value, value[2], a tuple entry, initial[phi_i]) in degrees."""
    if attr.endswith("]") and "[" in attr:
        base, key = attr[:-1].split("[")
        cur = getattr(c, base)
        if isinstance(cur, dict):
            if _is_zero(cur[key]):
                return None
            return _phi(target, c, **{attr: cur[key] * DEG})
        k = int(key)
        cur = list(cur)
        if _is_zero(cur[k]):
            return None
        cur[k] = cur[k] * DEG
        return _phi(target, c, **{base: tuple(cur)})
    cur = getattr(c, attr)
    if isinstance(cur, (tuple, list)):
        if all(_is_zero(x) for x in cur):
            return None
        return _phi(target, c, **{attr: tuple(x * DEG for x in cur)})
    if _is_zero(cur):
        return None
    return _phi(target, c, **{attr: cur * DEG})


def length_factors(c, limit=12):
    """The lengths of constraint ``c``'s own geometry a row may be multiplied by (:func:`slips.length_factors`)."""
    return slips.length_factors(c, spec_of(c), limit)


# ============================================================================================ the registry
def _defaults():
    register(P.Revolute, Spec(swap_points=(("s_i", "s_j"),)))
    register(P.Translational, Spec(swap_bodies=True, book=(_book_translational_origin,),
                                   extra=(_book_translational_dot,), derived_book=(_book_table_13_2, _book_gamma_t)))
    register(P.RevoluteRevolute, Spec(swap_points=(("s_i", "s_j"),), derived_book=(_book_table_13_3, _book_gamma_rr)))
    register(P.RevoluteTranslational, Spec(swap_bodies=True, extra=(_book_ex4_phi8,),
                                           derived_book=(_book_table_13_4,)))
    register(P.Gear, Spec(context=("gear",), book=(_gear_carrier_start,), extra=(_gear_fixed_carrier,)))
    register(P.RackPinion, Spec(swap_bodies=True, context=("rack",), extra=(_rack_sliding,)))
    register(P.Driver, Spec(driver_angle=True, context=("driver",)))
    register(P.RelativeAngleDriver, Spec(swap_bodies=True, driver_angle=True, context=("driver",)))
    register(P.DistanceDriver, Spec(swap_bodies=True, context=("driver",)))
    register(P.Simple, Spec(extra=(_simple_degrees,)))
    register(S.Spherical, Spec(swap_points=(("P_i", "P_j"),)))
    register(S.SphericalSpherical, Spec(swap_points=(("P_i", "P_j"),)))
    register(S.Universal, Spec(swap_points=(("P_i", "P_j"),), derived_book=(_book_gamma_n1,)))
    register(S.Revolute, Spec(swap_points=(("P_i", "P_j"),)))
    register(S.Normal1, Spec(derived_book=(_book_gamma_n1,), derived_slips=(n1_own_arm,)))
    register(S.Normal2, Spec(swap_bodies=True, derived_slips=(n2_without_dC,)))
    register(S.Parallel1, Spec(alternative=_cross_p1))
    register(S.Parallel2, Spec(swap_bodies=True, alternative=_cross_p2))
    register(S.Cylindrical, Spec(swap_bodies=True))
    register(S.Translational, Spec(swap_bodies=True))
    register(S.RevoluteDriver, Spec(driver_angle=True, swap_bodies=True, context=("driver",)))
    register(S.DistanceDriver, Spec(swap_bodies=True, context=("driver",)))


def _book_translational_origin(c):
    """Eqs. 23.a-26 print s_i = r_i^P − r_i^O: the body origin O for the second axis point Q."""
    if all(_is_zero(x) for x in c.s_Qi):
        return None
    return {"s_Qi": (0, 0)}, "13.5-eq25", "book_misprint"


def _book_translational_dot(target, c, Q):
    """§13.5 before eq. 24: "multiplicando escalarmente" read literally, s_i · d instead of s_i × d."""
    s = c.global_point(Q[0], c.s_Pi) - c.global_point(Q[0], c.s_Qi)
    d = c.global_point(Q[1], c.s_Pj) - c.global_point(Q[0], c.s_Pi)
    rows = list(c.phi(Q, target.mech.t))
    yield ("book_misprint", [s[0] * d[0] + s[1] * d[1], rows[1]], None, "13.5-eq24")


def _book_ex4_phi8(target, c, Q):
    """§13.5, example 4 prints its Φ_8 simplified with the ground's φ_1 = 0, and wrongly (erratum 13.5-ex4-phi8):
    the printed row, for that example's joint."""
    if target.mech.name != "ch13_example4" or c.name != "3":
        return
    symbols = target.symbols()
    printed = EX4_PHI8
    yield ("book_misprint", [printed.xreplace({x: symbols[x.name] for x in printed.free_symbols})], None,
           "13.5-ex4-phi8")


def _gear_carrier_start(c):
    """Eq. 37 misread with φ′ = φ − φ_k: φ_k⁰ left out (the book starts φ′ at φ⁰, so eq. 37 itself is right)."""
    pi0, pj0, pk0 = c.phi0
    if _is_zero(pk0):
        return None
    return {"phi0": (pi0, pj0, 0)}, None, "missing_term"


def _gear_fixed_carrier(target, c, Q):
    """Eq. 36 (a fixed carrier) used with a moving one: the carrier's turn missing."""
    Qs = [sp.Matrix(x) for x in Q]
    Qs[2][2] = c.phi0[2]
    yield ("missing_term", list(c.phi(Qs, target.mech.t)), None, None)


def _rack_sliding(target, c, Q):
    """The sliding pinion's x_i − x_i⁰ (eq. 42) forgotten."""
    if c.sliding:
        yield ("missing_term", _phi(target, c, sliding=False), None, None)


def _simple_degrees(target, c, Q):
    if getattr(c, "coordinate", None) == "phi" and not _is_zero(c.value):
        yield ("degrees", _phi(target, c, value=c.value * DEG), Msg("d.constant_degrees", name="φ⁰"), None)


# ============================================================================================ the book's tables
def _planar_points(target, c, s, names):
    """Global positions (N, 2) of the constraint's local points ``names`` (attributes) at the samples."""
    mech = target.mech
    out = {}
    for attr, role in names:
        b = c.bodies[role].name
        out[attr] = mech.point_position(s.Q, b, [float(x) for x in getattr(c, attr)])
    return out


def _cols(target, c):
    ncoord = len(target.mech.COORDS)
    return [[ncoord * (b.number - 1) + k for k in range(ncoord)] for b in c.bodies]


@for_quantities("Phi_q")
def _book_table_13_2(target, c, s, ref, quantity):
    """Table 13.2 prints ∂Φ_1/∂φ_j of the translational joint with x_i, y_i for x_j, y_j."""
    P = _planar_points(target, c, s, (("s_Pi", 0), ("s_Qi", 0), ("s_Pj", 1)))
    ci, cj = _cols(target, c)
    sx, sy = (P["s_Pi"] - P["s_Qi"]).T
    pj = P["s_Pj"]
    printed = (pj[:, 0] - s.Q[:, ci[0]]) * sx + (pj[:, 1] - s.Q[:, ci[1]]) * sy
    row = ref["Phi_q"][:, target.block(c)[0]].copy()
    row[:, cj[2]] = printed
    return [(0, row, "13.6-table-13.2")]


@for_quantities("Phi_q")
def _book_table_13_3(target, c, s, ref, quantity):
    """Table 13.3 prints the r-r joint's ∂/∂φ_i and ∂/∂φ_j as expressions that reduce to zero."""
    ci, cj = _cols(target, c)
    row = ref["Phi_q"][:, target.block(c)[0]].copy()
    row[:, ci[2]] = 0.0
    row[:, cj[2]] = 0.0
    return [(0, row, "13.6-table-13.3")]


@for_quantities("Phi_q")
def _book_table_13_4(target, c, s, ref, quantity):
    """Tables 13.4 and 13.5 print the r-t joint's ∂Φ/∂φ_j with x_i, y_i for x_j, y_j."""
    P = _planar_points(target, c, s, (("s_Pi", 0), ("s_Pj", 1), ("s_Qj", 1)))
    ci, cj = _cols(target, c)
    sx, sy = (P["s_Pj"] - P["s_Qj"]).T
    pi = P["s_Pi"]
    printed = (pi[:, 1] - s.Q[:, ci[1]]) * sy + (pi[:, 0] - s.Q[:, ci[0]]) * sx
    row = ref["Phi_q"][:, target.block(c)[0]].copy()
    row[:, cj[2]] = printed
    return [(0, row, "13.6-table-13.4")]


@for_quantities("gamma")
def _book_gamma_rr(target, c, s, ref, quantity):
    """Table 13.5 prints the r-r joint's γ with −2(ẏ_i − ẏ_j) for −2(ẏ_i − ẏ_j)²."""
    ci, cj = _cols(target, c)
    dy = s.QD[:, ci[1]] - s.QD[:, cj[1]]
    return [(0, ref["gamma"][:, target.block(c)[0]] + 2 * dy**2 - 2 * dy, "13.8-table-13.5-rr")]


@for_quantities("gamma")
def _book_gamma_t(target, c, s, ref, quantity):
    """Table 13.5 prints γ_1 of the translational joint with +2[…]φ̇_i for −2[…]φ̇_i."""
    P = _planar_points(target, c, s, (("s_Pi", 0), ("s_Qi", 0)))
    ci, cj = _cols(target, c)
    a, b = (P["s_Pi"] - P["s_Qi"]).T
    vel = a * (s.QD[:, ci[0]] - s.QD[:, cj[0]]) + b * (s.QD[:, ci[1]] - s.QD[:, cj[1]])
    return [(0, ref["gamma"][:, target.block(c)[0]] + 4 * vel * s.QD[:, ci[2]], "13.8-table-13.5-t")]


@for_quantities("gamma")
def _book_gamma_n1(target, c, s, ref, quantity):
    """§14.5's γ of Φ^(n1,1): without −2(s_jᵀs'_i)ṗ_iᵀṗ_i − 2(s_iᵀs'_j)ṗ_jᵀṗ_j (its printed misprints
    corrected: 14.5-gamma-n1-table), and as printed (14.5-gamma-n1)."""
    ci, cj = _cols(target, c)
    row = c.n_eq - 1  # the n1 row: a normal-1 constraint's only row, a universal joint's last
    _, _, rhs, extra = book_n1_acceleration(np.asarray(c.a_i, float), s.Q[:, ci[3:]], s.QD[:, ci[3:]],
                                            np.asarray(c.a_j, float), s.Q[:, cj[3:]], s.QD[:, cj[3:]])
    g = ref["gamma"][:, target.block(c)[0] + row]
    return [(row, g + extra, "14.5-gamma-n1-table"), (row, rhs, "14.5-gamma-n1")]


# ============================================================================================ the book's formulation
def _cross_p1(c, Q):
    """The book's Φ^(p1,2) = s̃_i s_j (all three rows)."""
    return list(c.global_vector(Q[0], c.a_i).cross(c.global_vector(Q[1], c.a_j)))


def _cross_p2(c, Q):
    """The book's Φ^(p2,2) = s̃_i d (all three rows)."""
    d = c.global_point(Q[1], c.P_j) - c.global_point(Q[0], c.P_i)
    return list(c.global_vector(Q[0], c.a_i).cross(d))


def book_rows(c, Q, t):
    """The constraint's rows in the book's formulation: its parts' (a composite), its class's alternative,
    or its own Φ."""
    if getattr(c, "parts", ()):
        return [e for v in c.part_views() for e in book_rows(v, Q, t)]
    alt = spec_of(c).alternative
    return list(alt(c, Q)) if alt is not None else list(c.phi(Q, t))


def book_form(target, c, which="generic", jacobian=None):
    """The book's own rows of ``c`` (its cross-product rows s̃_i s_j where kinbook writes h-rows) at the target's
    samples ``which`` (N, r) — or their Jacobian (N, r, len(jacobian)) in the columns ``jacobian`` —, or None
    when the book writes ``c`` as kinbook does."""
    if not _has_alternative(c):
        return None
    key = ("book-form", tuple(target.block(c)), which, None if jacobian is None else tuple(jacobian))
    if key not in target.store:
        mech = target.mech
        rows = book_rows(c, [mech.body_symbols(b.name) for b in c.bodies], mech.t)
        s = target.samples(which)
        out = target.tape(rows)(s.Q, s.QD, s.T, grad=jacobian is not None)
        target.store[key] = out["value"] if jacobian is None else out["grad"][:, :, list(jacobian)]
    return target.store[key]


def _has_alternative(c):
    if getattr(c, "parts", ()):
        return any(_has_alternative(v) for v in c.part_views())
    return spec_of(c).alternative is not None


def alternative_variants(target, c):
    """Structural variants of the book's formulation of ``c`` (when kinbook writes it another way): Aᵀ for A,
    A omitted, the points exchanged, the sign of A_j s'_j. Their rows do not stand row by row for kinbook's."""
    key = ("alt-variants", tuple(target.block(c)))
    if key in target.store:
        return target.store[key]
    out = []
    if _has_alternative(c):
        mech = target.mech
        t = mech.t
        Q = [mech.body_symbols(b.name) for b in c.bodies]
        QT = [sp.Matrix([*q[:4], -q[4], -q[5], -q[6]]) for q in Q]
        QL = [sp.Matrix([*q[:3], 1, 0, 0, 0]) for q in Q]

        def copy_of(**changes):
            cc = copy.copy(c)
            cc.__dict__.pop("_views", None)
            cc.__dict__.update(changes)
            return cc

        makers = [("A_transposed", lambda: book_rows(c, QT, t), None),
                  ("local_vector", lambda: book_rows(c, QL, t), None)]
        if hasattr(c, "P_i") and hasattr(c, "P_j"):
            makers.append(("swapped_points", lambda: book_rows(copy_of(P_i=c.P_j, P_j=c.P_i), Q, t), None))
            makers.append(("sign_flip", lambda: book_rows(copy_of(P_j=-np.asarray(c.P_j, float)), Q, t),
                           Msg("d.sign_of", what="A_j s'_j")))
        for code, make, detail in makers:
            try:
                out.append(Variant(code, make(), detail))
            except Exception:  # pragma: no cover - a variant that cannot be built here
                pass
    target.store[key] = out
    return out
