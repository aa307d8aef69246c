"""Expected numbers that know their mistakes: what :func:`~kinbook.grading.check_value`,
:func:`~kinbook.grading.check_rotation` and :func:`~kinbook.grading.check_euler_parameters` compare with.

A plain number or array is an expected value; an :class:`Expected` is one too, carrying the other answers
that are also right (−p for p, the second triple of z-x-z angles) and the wrong answers students give, each
*computed with kinbook's own functions* from the same inputs — the rotation matrix of the angles in degrees,
Aᵀ for A, E for G, χ for χ/2, a point's velocity with A for B, its acceleration without the centripetal
term … — with its catalogue code. A notebook or an exercise builds one in a line::

    from kinbook.grading import check_rotation, expected
    check_rotation(my_A, expected.A_from_euler(psi, theta, phi))

The functions mirror kinbook's (:mod:`kinbook.planar.transforms`, :mod:`kinbook.spatial.rotations`) and take
the same arguments (radians). :meth:`Expected.add` appends a wrong answer of one's own (the value printed a
few cells above, the other assembly mode), :func:`stack` joins several into one answer.
"""

from __future__ import annotations

import dataclasses
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..i18n import N_
from ..planar import transforms as T
from ..spatial import rotations as R
from . import mistakes as M
from ._i18n import Msg, add_texts
from .misprints import book_A_of_p
from .quantities import QUANTITIES
from .target import target_for

__all__ = ["Expected", "stack", "A", "point_position", "point_velocity", "point_acceleration", "A_from_axes",
           "local_components", "global_components", "spatial_point_position", "A_from_euler", "euler_from_A",
           "omega_from_euler_rates", "A_from_p", "p_from_A", "p_from_axis_angle", "omega_from_p_dot",
           "coordinates", "rack_displacement", "planet_speed", "speed", "rr_jacobian_phi", "rr_gamma",
           "constraint_values"]

DEG = 180.0 / np.pi

add_texts({
    "x.term_in": N_("the sign of the term {term} in {row}"),
    "x.other_data": N_("this is {what}"),
    "x.frame_r": N_("r is already in global components: only s' is turned by A"),
    "x.rates": N_("φ̈ and φ̇² exchanged (the slip of the book's example 6)"),
    "x.relative": N_("this is the speed relative to the carrier, φ̇_j − φ̇_k; the question asks for the absolute one"),
    "x.mesh_sign": N_("the sign of the mesh: two external gears turn in opposite senses relative to the carrier"),
    "x.radii_ratio": N_("the ratio of the radii upside down: ρ_j/ρ_i for ρ_i/ρ_j"),
    "x.diameter": N_("the diameter 2ρ used for the radius ρ"),
    "x.factor_2": N_("the 2 of ∂(dᵀd)/∂q = 2dᵀ ∂d/∂q"),
    "x.term": N_("the term {term}"),
    "x.speed_sign": N_("a speed is a length, |v| ≥ 0"),
    "x.E_column": N_("the sign of E's first column, E = [−e, ẽ + e0 I]"),
})


@dataclass
class Expected:
    """An expected value with its alternatives.

    Attributes
    ----------
    value : ndarray
    equivalents : list of (ndarray, Msg)
        Other right answers, with why they are right.
    variants : list of (code, ndarray, detail Msg or None, erratum id or None)
        Wrong answers, most specific first.
    periodic : tuple of int
        Flat indices of angles, compared modulo 2π.
    kind : str
        "value", "rotation", "parameters", "angles", "vector" — what the value is.
    context : tuple of str
        The catalogue contexts its hints are written for (:data:`kinbook.grading.catalogue.CONTEXTS`: "position",
        "speed", "accel", "rack", "gear", "rotation", "angles", "value" …), first match first; default ``kind``.
    """

    value: np.ndarray
    equivalents: list = field(default_factory=list)
    variants: list = field(default_factory=list)
    periodic: tuple = ()
    kind: str = "value"
    context: tuple = ()

    def __array__(self, dtype=None, copy=None):
        return np.asarray(self.value, dtype=dtype)

    def copy(self):
        """A copy whose lists can be changed without touching this one."""
        return dataclasses.replace(self, equivalents=list(self.equivalents), variants=list(self.variants))

    def add(self, code, value, detail=None, erratum=None):
        """Append a wrong answer (code, value, detail, erratum); returns self."""
        self.variants.append((code, _v(value), detail, erratum))
        return self



def _v(x):
    return np.asarray(x, dtype=float)


def stack(*parts):
    """Several expected values as one answer (their entries one after the other): each part's wrong answers
    with the other parts right, so "[v, a]" with the centripetal term missing is still named."""
    exps = [p if isinstance(p, Expected) else Expected(_v(p)) for p in parts]
    values = [_v(p.value).ravel() for p in exps]
    out = Expected(np.concatenate(values), kind="vector")
    offset = 0
    for k, p in enumerate(exps):
        for code, v, detail, erratum in p.variants:
            v = _v(v).ravel()
            if v.size == values[k].size:
                out.variants.append((code, np.concatenate(values[:k] + [v] + values[k + 1:]), detail, erratum))
        out.periodic += tuple(offset + i for i in p.periodic)
        offset += values[k].size
        out.context += tuple(c for c in (p.context or (p.kind,)) if c not in out.context)
    return out


def _signs_of_local(fn, s, names=("ξ", "η", "ζ")):
    """Variants of a point's quantity with one local coordinate's sign flipped (s' = [−ξ, η] …)."""
    out = []
    for k in range(len(s)):
        if s[k] != 0:
            t = s.copy()
            t[k] = -t[k]
            out.append(("sign_flip", fn(t), Msg("d.sign_of", what=names[k]), None))
    return out


def _term_flips(r, M, s, factor, terms, rows=("x^P", "y^P")):
    """Variants r + M' s factor with one entry of M negated: one term of one row with the wrong sign."""
    out = []
    for (i, j), term in terms.items():
        if s[j] == 0:
            continue
        W = M.copy()
        W[i, j] = -W[i, j]
        out.append(("sign_flip", r + W @ s * factor, Msg("x.term_in", term=term, row=rows[i]), None))
    return out


# ============================================================================================ planar (13.5)
def _planar():
    return T


def A(phi):
    """A(φ) = [[cos φ, −sin φ], [sin φ, cos φ]] (eq. 7): wrong forms Aᵀ, B(φ), A of φ in degrees."""
    T = _planar()
    return Expected(_v(T.A(phi)), variants=[
        ("transposed", _v(T.A(phi)).T, None, None),
        ("degrees", _v(T.A(phi * DEG)), None, None),
        ("B_for_A", _v(T.B(phi)), None, None),
    ], kind="rotation")


def point_position(r, phi, s_local):
    """r^P = r + A(φ) s' (eq. 5): wrong forms r + Aᵀ s', r + s', r − A s', a local coordinate's or one term's
    sign, φ in degrees, r forgotten, B for A."""
    T = _planar()
    r, s = _v(r), _v(s_local)
    A_, B_ = _v(T.A(phi)), _v(T.B(phi))
    variants = _signs_of_local(lambda t: r + A_ @ t, s)
    variants += [
        ("A_transposed", r + A_.T @ s, None, None),
        ("local_vector", r + s, None, None),
        ("sign_flip", r - A_ @ s, Msg("d.sign_of", what="A s'"), None),
        ("degrees", _v(T.point_position(r, phi * DEG, s)), None, None),
        ("missing_term", A_ @ s, Msg("d.missing_term", term="r"), None),
        ("B_for_A", r + B_ @ s, None, None),
    ]
    variants += _term_flips(r, A_, s, 1.0, {(0, 0): "ξ cos φ", (0, 1): "−η sin φ", (1, 0): "ξ sin φ",
                                           (1, 1): "η cos φ"})
    return Expected(_v(T.point_position(r, phi, s)), variants=variants, kind="vector", context=("position",))


def point_velocity(r_dot, phi, phi_dot, s_local):
    """ṙ^P = ṙ + B(φ) s' φ̇ (eq. 10): wrong forms with A for B, without φ̇, with the sign of B s' φ̇ or of a local
    coordinate or of one term, without ṙ or without B s' φ̇, with φ or φ̇ in degrees."""
    T = _planar()
    rd, s = _v(r_dot), _v(s_local)
    A_, B_ = _v(T.A(phi)), _v(T.B(phi))
    Bs = B_ @ s
    variants = [("A_for_B", rd + A_ @ s * phi_dot, None, None)]
    variants += _signs_of_local(lambda t: rd + B_ @ t * phi_dot, s)
    variants += [
        ("missing_term", rd + Bs, Msg("d.missing_term", term="φ̇"), None),
        ("sign_flip", rd - Bs * phi_dot, Msg("d.sign_of", what="B s' φ̇"), None),
        ("missing_term", Bs * phi_dot, Msg("d.missing_term", term="ṙ"), None),
        ("missing_term", rd, Msg("d.missing_term", term="B s' φ̇"), None),
        ("degrees", rd + _v(T.B(phi * DEG)) @ s * phi_dot, None, None),
        ("degrees", rd + Bs * phi_dot * DEG, None, None),
        ("A_transposed", rd + B_.T @ s * phi_dot, None, None),
    ]
    variants += _term_flips(rd, B_, s, phi_dot, {(0, 0): "−ξ sin φ φ̇", (0, 1): "−η cos φ φ̇", (1, 0): "ξ cos φ φ̇",
                                                 (1, 1): "−η sin φ φ̇"})
    return Expected(_v(T.point_velocity(rd, phi, phi_dot, s)), variants=variants, kind="vector", context=("speed",))


def point_acceleration(r_ddot, phi, phi_dot, phi_ddot, s_local):
    """r̈^P = r̈ + B s' φ̈ − A s' φ̇² (eq. 13): wrong forms without either term or without r̈, with +A s' φ̇² or
    −B s' φ̈, with φ̇ for φ̇², with A and B exchanged, with φ̈ and φ̇² exchanged, with a local coordinate's sign,
    with φ in degrees."""
    T = _planar()
    rdd, s = _v(r_ddot), _v(s_local)
    A_, B_ = _v(T.A(phi)), _v(T.B(phi))
    As, Bs = A_ @ s, B_ @ s
    variants = [
        ("missing_term", rdd + Bs * phi_ddot, Msg("d.missing_term", term="−A s' φ̇²"), None),
        ("missing_term", rdd - As * phi_dot**2, Msg("d.missing_term", term="B s' φ̈"), None),
        ("sign_flip", rdd + Bs * phi_ddot + As * phi_dot**2, Msg("d.sign_of", what="A s' φ̇²"), None),
        ("sign_flip", rdd - Bs * phi_ddot - As * phi_dot**2, Msg("d.sign_of", what="B s' φ̈"), None),
        ("missing_square", rdd + Bs * phi_ddot - As * phi_dot, None, None),
        ("A_for_B", rdd + As * phi_ddot - Bs * phi_dot**2, None, None),
        ("rate_exchanged", rdd + Bs * phi_dot**2 - As * phi_ddot, Msg("x.rates"), None),
        ("missing_term", Bs * phi_ddot - As * phi_dot**2, Msg("d.missing_term", term="r̈"), None),
    ]
    variants += _signs_of_local(lambda t: rdd + B_ @ t * phi_ddot - A_ @ t * phi_dot**2, s)
    variants += [("degrees", _v(T.point_acceleration(rdd, phi * DEG, phi_dot, phi_ddot, s)), None, None)]
    return Expected(_v(T.point_acceleration(rdd, phi, phi_dot, phi_ddot, s)), variants=variants, kind="vector",
                    context=("accel",))


def coordinates(q, angles=(), others=()):
    """A whole q (e.g. of Newton–Raphson's solution): its angle entries ``angles`` (0-based) are compared
    modulo 2π (φ − 2π is the same orientation); wrong forms the angles in degrees and each of ``others``
    (code, q, detail) — the other assembly mode, the guess, the value at another instant."""
    q = _v(q)
    out = Expected(q, periodic=tuple(int(k) for k in angles), kind="value", context=("value",))
    deg = q.copy()
    deg[list(angles)] *= DEG
    if len(angles):
        out.add("degrees", deg)
    for code, value, detail in others:
        out.add(code, value, detail)
    return out


def rack_displacement(rho, angle):
    """x_j − x_j⁰ = ρ (φ_i − φ_i⁰) of a rack and pinion (eq. 40): wrong forms the angle in degrees, the
    diameter for the radius, the rack the other way."""
    value = rho * angle
    return Expected(_v(value), variants=[
        ("degrees", _v(rho * angle * DEG), None, None),
        ("scaled", _v(2 * value), Msg("x.diameter"), None),
        ("sign_flip", _v(-value), None, None),
    ], kind="value", context=("rack", "value"))


def planet_speed(w_planet, w_carrier, w_sun, rho_sun, rho_planet):
    """The absolute angular speed of a planet (eq. 38 with a moving carrier), computed by the caller with
    kinbook; wrong forms the speed relative to the carrier, the mesh's sign, the fixed-carrier gear, degrees."""
    k = rho_sun / rho_planet
    rel = w_planet - w_carrier
    return Expected(_v(w_planet), variants=[
        ("relative_speed", _v(rel), Msg("x.relative"), None),
        ("relative_speed", _v(-rel), Msg("x.relative"), None),
        ("sign_flip", _v(w_carrier - rel), Msg("x.mesh_sign"), None),
        ("missing_term", _v(-k * w_sun), Msg("d.missing_term", term="φ̇_k"), None),
        ("swapped_bodies", _v(w_carrier + rel / k**2), Msg("x.radii_ratio"), None),
        ("degrees", _v(w_planet * DEG), None, None),
    ], kind="value", context=("gear", "value"))


def speed(value, others=()):
    """A speed |v| (never negative); wrong forms −|v|, degrees per second, and ``others`` (code, value,
    detail) the caller computed (another point's speed, another body's rate)."""
    out = Expected(_v(value), kind="value", context=("speed", "value"))
    out.add("sign_flip", -value, Msg("x.speed_sign"))
    out.add("degrees", value * DEG)
    for code, v, detail in others:
        out.add(code, v, detail)
    return out


def rr_jacobian_phi(d, Bs, book_zero=True):
    """∂Φ^(r-r)/∂φ_j = −2 dᵀ B_j s'_j, d = r_i^P − r_j^P (the corrected Table 13.3, with ``Bs`` = B_j s'_j): wrong
    forms the book's printed 0 (erratum 13.6-table-13.3), the sign, the 2 forgotten, A for B."""
    d, Bs = _v(d), _v(Bs)
    value = -2 * d @ Bs
    As = np.array([Bs[1], -Bs[0]])  # A s' = −R90 (B s'): B s' turned back by 90°
    out = Expected(_v(value), kind="value", context=("value",))
    if book_zero:
        out.add("book_misprint", 0.0, None, "13.6-table-13.3")
    out.add("sign_flip", -value)
    out.add("scaled", value / 2, Msg("x.factor_2"))
    out.add("A_for_B", -2 * d @ As)
    return out


def rr_gamma(d, d_dot, c):
    """γ^(r-r) = −2ḋᵀḋ − 2dᵀc (Table 13.5 corrected), c = r̈_i^P − r̈_j^P at q̈ = 0: wrong forms either term's
    sign or absence, a term without its 2, γ's sign."""
    d, dd, c = _v(d), _v(d_dot), _v(c)
    t1, t2 = -2 * dd @ dd, -2 * d @ c
    value = t1 + t2
    out = Expected(_v(value), kind="value", context=("value",))
    out.add("gamma_sign", -value)
    out.add("sign_flip", -t1 + t2, Msg("x.term", term="−2ḋᵀḋ"))
    out.add("sign_flip", t1 - t2, Msg("x.term", term="−2dᵀc"))
    out.add("missing_term", t2, Msg("d.missing_term", term="−2ḋᵀḋ"))
    out.add("missing_term", t1, Msg("d.missing_term", term="−2dᵀc"))
    out.add("scaled", t1 / 2 + t2, Msg("x.term", term="−ḋᵀḋ"))
    out.add("scaled", t1 + t2 / 2, Msg("x.term", term="−dᵀc"))
    return out


# ============================================================================================ spatial (14.1-14.3)
def _rot():
    return R


def A_from_axes(u_xi, u_eta, u_zeta):
    """A whose columns are the body axes in global components (§14.1): wrong forms the axes as rows (Aᵀ)."""
    R = _rot()
    A_ = _v(R.A_from_axes(u_xi, u_eta, u_zeta))
    return Expected(A_, variants=[("transposed", A_.T, None, None)], kind="rotation")


def local_components(A_, s):
    """s' = Aᵀ s, the body components of a global vector (§14.1): wrong forms A s, s itself (not turned)."""
    A_, s = _v(A_), _v(s)
    return Expected(A_.T @ s, variants=[("A_for_AT", A_ @ s, None, None), ("wrong_frame", s, None, None)],
                    kind="vector", context=("vector", "spatial"))


def global_components(A_, s_local):
    """s = A s', the global components of a body vector: wrong form Aᵀ s'."""
    A_, s = _v(A_), _v(s_local)
    return Expected(A_ @ s, variants=[("A_transposed", A_.T @ s, None, None)], kind="vector",
                    context=("vector", "spatial"))


def spatial_point_position(r, p, s_local):
    """r^P = r + A(p) s' (§14.3): wrong forms r + Aᵀ s', r + s', A (r + s'), r + ½A s' (the book's A without its
    2), r − A s'."""
    R = _rot()
    r, p, s = _v(r), _v(p), _v(s_local)
    A_ = _v(R.A_from_p(p))
    return Expected(r + A_ @ s, variants=[
        ("A_transposed", r + A_.T @ s, None, None),
        ("local_vector", r + s, None, None),
        ("wrong_frame", A_ @ (r + s), Msg("x.frame_r"), None),
        ("book_misprint", r + book_A_of_p(p) @ s, None, "14.3-A-of-p"),
        ("factor_2_missing", r + 0.5 * A_ @ s, None, None),
        ("sign_flip", r - A_ @ s, Msg("d.sign_of", what="A s'"), None),
    ], kind="vector", context=("spatial", "position"))


def A_from_euler(psi, theta, phi):
    """A = A_z(ψ) A_x(θ) A_z(φ) (§14.2, z-x-z): wrong forms Aᵀ, the turns in the reverse (extrinsic) order,
    the angles in degrees."""
    R = _rot()
    A_ = _v(R.A_from_euler(psi, theta, phi))
    return Expected(A_, variants=[
        ("transposed", A_.T, None, None),
        ("extrinsic_order", _v(R.A_from_euler(phi, theta, psi)), None, None),
        ("degrees", _v(R.A_from_euler(psi * DEG, theta * DEG, phi * DEG)), None, None),
    ], kind="rotation")


def euler_from_A(A_):
    """(ψ, θ, φ) of a rotation matrix (§14.2): the other triple (ψ ± π, −θ, φ ± π) is right too; wrong forms
    in degrees, ψ and φ exchanged (the extrinsic reading), the angles of Aᵀ."""
    R = _rot()
    A_ = _v(A_)
    with warnings.catch_warnings():  # at sin θ = 0 only ψ ± φ is defined: the comparison is by A below
        warnings.simplefilter("ignore")
        a = _v(R.euler_from_A(A_))
        at = _v(R.euler_from_A(A_.T))
    other = np.array([a[0] + np.pi, -a[1], a[2] + np.pi])
    return Expected(a, equivalents=[(other, Msg("angles_alternative"))], variants=[
        ("degrees", a * DEG, None, None),
        ("degrees", other * DEG, None, None),
        ("extrinsic_order", a[::-1].copy(), None, None),
        ("extrinsic_order", other[::-1].copy(), None, None),
        ("transposed", at, None, None),
    ], periodic=(0, 1, 2), kind="angles", context=("angles",))


def omega_from_euler_rates(angles, rates, frame="global"):
    """ω (global) or ω' (body) from z-x-z angle rates (§14.2): wrong forms the other frame, the rates
    themselves, degrees."""
    R = _rot()
    other = "body" if frame == "global" else "global"
    w = _v(R.omega_from_euler_rates(angles, rates, frame=frame))
    return Expected(w, variants=[
        ("wrong_frame", _v(R.omega_from_euler_rates(angles, rates, frame=other)), None, None),
        ("angle_rates", _v(rates), None, None),
        ("degrees", w * DEG, None, None),
        ("degrees", _v(R.omega_from_euler_rates(_v(angles) * DEG, rates, frame=frame)), None, None),
    ], kind="vector", context=("omega", "vector"))


def A_from_p(p):
    """A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ] (§14.3): wrong forms ½·A's bracket (the factor 2 missing), the book's
    printed matrix, Aᵀ."""
    R = _rot()
    p = _v(p)
    A_ = _v(R.A_from_p(p))
    return Expected(A_, variants=[
        ("factor_2_missing", 0.5 * A_, None, "14.3-A-of-p"),
        ("book_misprint", book_A_of_p(p), None, "14.3-A-of-p"),
        ("transposed", A_.T, None, None),
    ], kind="rotation")


def p_from_A(A_, e0_nonnegative=False):
    """Euler parameters of a rotation matrix (§14.3): −p is right too; wrong forms e0 last, p of Aᵀ.

    With ``e0_nonnegative`` (a question that asks for e0 ≥ 0), −p is not the answer asked for: a ``sign_flip``,
    not an equivalent (when e0 = 0 both signs stay right)."""
    R = _rot()
    A_ = _v(A_)
    p = _v(R.p_from_A(A_))
    if e0_nonnegative and p[0] > 1e-9:
        return Expected(p, variants=[
            ("sign_flip", -p, None, None),
            ("scalar_last", np.r_[p[1:], p[0]], None, None),
            ("scalar_last", -np.r_[p[1:], p[0]], None, None),
            ("transposed", _v(R.p_from_A(A_.T)), None, None),
        ], kind="parameters")
    return Expected(p, equivalents=[(-p, Msg("p_negated"))], variants=[
        ("scalar_last", np.r_[p[1:], p[0]], None, None),
        ("scalar_last", -np.r_[p[1:], p[0]], None, None),
        ("transposed", _v(R.p_from_A(A_.T)), None, None),
    ], kind="parameters")


def p_from_axis_angle(axis, angle):
    """p = [cos(χ/2), u sin(χ/2)] for a turn χ about u (§14.3): −p is right too; wrong forms χ for χ/2, χ in
    degrees, u not made unit, e0 last."""
    R = _rot()
    u = _v(axis)
    p = _v(R.p_from_axis_angle(u, angle))
    un = u / np.linalg.norm(u)
    full = np.r_[np.cos(angle), un * np.sin(angle)]
    deg = np.r_[np.cos(angle * DEG / 2), un * np.sin(angle * DEG / 2)]
    raw = np.r_[np.cos(angle / 2), u * np.sin(angle / 2)]
    out = Expected(p, equivalents=[(-p, Msg("p_negated"))], kind="parameters")
    for code, v in (("full_angle", full), ("degrees", deg), ("not_normalized", raw),
                    ("scalar_last", np.r_[p[1:], p[0]])):
        out.variants += [(code, v, None, None), (code, -v, None, None)]
    return out


def omega_from_p_dot(p, p_dot, frame="global"):
    """ω = 2Eṗ (global) or ω' = 2Gṗ (body) (§14.3): wrong forms G for E (or E for G), without the 2, E with its
    first column's sign flipped."""
    R = _rot()
    p, pd = _v(p), _v(p_dot)
    other = "body" if frame == "global" else "global"
    w = _v(R.omega_from_p_dot(p, pd, frame=frame))
    M = _v(R.E(p) if frame == "global" else R.G(p))
    M[:, 0] = -M[:, 0]
    return Expected(w, variants=[
        ("G_for_E", _v(R.omega_from_p_dot(p, pd, frame=other)), None, None),
        ("factor_2_missing", 0.5 * w, None, None),
        ("sign_flip", 2 * M @ pd, Msg("x.E_column"), None),
    ], kind="vector", context=("omega", "vector"))


# ============================================================================================ constraints, as numbers
def constraint_values(constraint, quantity, q, qd=None, t=0.0, rows=None):
    """Φ, Φ_q, ν or γ of one constraint at one state, as numbers (an exercise asking for the values at a test
    configuration), with the catalogue's mistakes of that constraint carried through to the same numbers:
    each structural variant (:func:`kinbook.grading.mistakes.structural`: points exchanged, Aᵀ for A, A left
    out, a local coordinate's sign, the book's misprints …), the derivation slips (A treated as constant, A for
    B), γ's sign, the book's +(Φ_q q̇)_q q̇.

    Parameters
    ----------
    constraint : Constraint
        One constraint of a mechanism (``mech.constraint("B")``).
    quantity : {"Phi", "Phi_q", "nu", "gamma"}
    q, qd : array_like, shape (n,)
        The state (``qd`` for γ).
    rows : int or sequence of int, optional
        Which of the constraint's rows (0-based; default all; an int gives one number).

    Returns
    -------
    Expected
        ``value``: the mechanism's own numbers (Φ_q with all n columns); variants as above.
    """
    if not isinstance(quantity, str) or quantity not in QUANTITIES:
        raise InputError(f"`quantity` must be 'Phi', 'Phi_q', 'nu' or 'gamma', got {quantity!r}")
    target = target_for(constraint)
    mech = target.mech
    q = _v(q)
    qd = np.zeros_like(q) if qd is None else _v(qd)
    Q, QD, T = q[None, :], qd[None, :], np.array([float(t)])
    block = list(range(len(target.block(constraint)))) if rows is None else rows  # an int: one number
    sl = slice(constraint.rows.start, constraint.rows.stop)
    Qty = QUANTITIES[quantity]
    value = _v(Qty.value(mech, q, qd, t)[sl])[block]

    def pick(d):
        return _v(d[quantity][0])[block]

    out = Expected(value, kind="value", context=M.contexts_of(constraint, quantity))
    if Qty.right_hand_side:  # the whole right-hand side negated first: a variant that negates a
        out.add(Qty.sign_code, -value)  # one-row constraint (a vector's sign) is the same number
    for v in M.structural(target, constraint):
        try:
            d = target.tape(v.exprs).derived(Q, QD, T)
        except Exception:  # noqa: BLE001 — a variant the tape cannot evaluate is not offered
            continue
        out.add(v.code, pick(d), v.detail, v.erratum)
    if Qty.q_derivative:
        tape = target.tape(list(target.symbolic_phi()))
        if target.kind == "planar":
            rules = [("chain_dropped", "missing_chain_rule", ()), ("A_for_B", "A_for_B", ())]
        else:  # A(p) differentiated as a constant: the p columns frozen
            p_cols = [7 * b + k for b in range(target.n // 7) for k in range(3, 7)]
            rules = [("exact", "missing_chain_rule", tuple(p_cols))]
        for rule, code, frozen in rules:
            d = tape.derived(Q, QD, T, rule=rule, frozen=frozen)
            out.add(code, pick(d))
        if Qty.velocities:
            d = tape.derived(Q, QD, T, parts=True)
            printed = None if target.kind == "spatial" else "13.8-gamma-sign"
            out.add("gamma_sign", _v(-d["quad"][0] + d["qt"][0] + d["tt"][0])[block], None, printed)
            out.add("missing_qt_term", _v(d["quad"][0] + d["tt"][0])[block])
            out.add("missing_tt_term", _v(d["quad"][0] + d["qt"][0])[block])
    if Qty.zero_code:
        out.add(Qty.zero_code, np.zeros_like(value))
    return out
