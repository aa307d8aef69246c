"""Expected numbers that know their mistakes: what :func:`~kinbook.grading.check_value`,
:func:`~kinbook.grading.check_rotation` and :func:`~kinbook.grading.check_euler_parameters` compare with.

A plain number or array is an expected value; an :class:`Expected` is one too, carrying the other answers
that are also right (−p for p, the second triple of z-x-z angles) and the wrong answers students give, each
*computed with kinbook's own functions* from the same inputs — the rotation matrix of the angles in degrees,
Aᵀ for A, E for G, χ for χ/2 … — with its catalogue code. A notebook or an exercise builds one in a line::

    from kinbook.grading import check_rotation, expected
    check_rotation(my_A, expected.A_from_euler(psi, theta, phi))

The functions mirror kinbook's (:mod:`kinbook.planar.transforms`, :mod:`kinbook.spatial.rotations`) and take
the same arguments (radians).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ._i18n import Msg

__all__ = ["Expected", "A", "point_position", "point_velocity", "point_acceleration", "A_from_axes",
           "local_components", "global_components", "spatial_point_position", "A_from_euler", "euler_from_A",
           "omega_from_euler_rates", "A_from_p", "p_from_A", "p_from_axis_angle", "omega_from_p_dot"]

DEG = 180.0 / np.pi


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
        "value", "rotation", "parameters", "angles", "vector" — the hint context.
    """

    value: np.ndarray
    equivalents: list = field(default_factory=list)
    variants: list = field(default_factory=list)
    periodic: tuple = ()
    kind: str = "value"

    def __array__(self, dtype=None):
        return np.asarray(self.value, dtype=dtype)


def _v(x):
    return np.asarray(x, dtype=float)


# ============================================================================================ planar (13.5)
def _planar():
    from ..planar import transforms as T

    return T


def A(phi):
    """A(φ) = [[cos φ, −sin φ], [sin φ, cos φ]] (eq. 7): wrong forms Aᵀ, B(φ), A of φ in degrees."""
    T = _planar()
    return Expected(_v(T.A(phi)), variants=[
        ("transposed", _v(T.A(phi)).T, None, None),
        ("degrees", _v(T.A(phi * DEG)), None, None),
        ("A_for_B", _v(T.B(phi)), None, None),
    ], kind="rotation")


def point_position(r, phi, s_local):
    """r^P = r + A(φ) s' (eq. 5): wrong forms r + Aᵀ s', r + s', r − A s', φ in degrees."""
    T = _planar()
    r, s = _v(r), _v(s_local)
    return Expected(_v(T.point_position(r, phi, s)), variants=[
        ("A_transposed", r + _v(T.A(phi)).T @ s, None, None),
        ("local_vector", r + s, None, None),
        ("sign_flip", r - _v(T.A(phi)) @ s, Msg("d.sign_of", what="A s'"), None),
        ("degrees", _v(T.point_position(r, phi * DEG, s)), None, None),
        ("missing_term", _v(T.A(phi)) @ s, Msg("d.missing_term", term="r"), None),
    ], kind="vector")


def point_velocity(r_dot, phi, phi_dot, s_local):
    """ṙ^P = ṙ + B(φ) s' φ̇ (eq. 10): wrong forms with A for B, without φ̇, with the sign of B s' φ̇, without
    ṙ, with φ or φ̇ in degrees."""
    T = _planar()
    rd, s = _v(r_dot), _v(s_local)
    Bs = _v(T.B(phi)) @ s
    return Expected(_v(T.point_velocity(rd, phi, phi_dot, s)), variants=[
        ("A_for_B", rd + _v(T.A(phi)) @ s * phi_dot, None, None),
        ("missing_term", rd + Bs, Msg("d.missing_term", term="φ̇"), None),
        ("sign_flip", rd - Bs * phi_dot, Msg("d.sign_of", what="B s' φ̇"), None),
        ("missing_term", Bs * phi_dot, Msg("d.missing_term", term="ṙ"), None),
        ("degrees", rd + _v(T.B(phi * DEG)) @ s * phi_dot, None, None),
        ("degrees", rd + Bs * phi_dot * DEG, None, None),
    ], kind="vector")


def point_acceleration(r_ddot, phi, phi_dot, phi_ddot, s_local):
    """r̈^P = r̈ + B s' φ̈ − A s' φ̇² (eq. 13): wrong forms without either term, with +A s' φ̇², with φ̇ for φ̇²,
    with A and B exchanged."""
    T = _planar()
    rdd, s = _v(r_ddot), _v(s_local)
    As, Bs = _v(T.A(phi)) @ s, _v(T.B(phi)) @ s
    return Expected(_v(T.point_acceleration(rdd, phi, phi_dot, phi_ddot, s)), variants=[
        ("missing_term", rdd + Bs * phi_ddot, Msg("d.missing_term", term="−A s' φ̇²"), None),
        ("missing_term", rdd - As * phi_dot**2, Msg("d.missing_term", term="B s' φ̈"), None),
        ("sign_flip", rdd + Bs * phi_ddot + As * phi_dot**2, Msg("d.sign_of", what="A s' φ̇²"), None),
        ("missing_square", rdd + Bs * phi_ddot - As * phi_dot, None, None),
        ("A_for_B", rdd + As * phi_ddot - Bs * phi_dot**2, None, None),
    ], kind="vector")


# ============================================================================================ spatial (14.1-14.3)
def _rot():
    from ..spatial import rotations as R

    return R


def A_from_axes(u_xi, u_eta, u_zeta):
    """A whose columns are the body axes in global components (§14.1): wrong forms the axes as rows (Aᵀ)."""
    R = _rot()
    A_ = _v(R.A_from_axes(u_xi, u_eta, u_zeta))
    return Expected(A_, variants=[("transposed", A_.T, None, None)], kind="rotation")


def local_components(A_, s):
    """s' = Aᵀ s, the body components of a global vector (§14.1): wrong form A s."""
    A_, s = _v(A_), _v(s)
    return Expected(A_.T @ s, variants=[("A_for_AT", A_ @ s, None, None)], kind="vector")


def global_components(A_, s_local):
    """s = A s', the global components of a body vector: wrong form Aᵀ s'."""
    A_, s = _v(A_), _v(s_local)
    return Expected(A_ @ s, variants=[("A_transposed", A_.T @ s, None, None)], kind="vector")


def spatial_point_position(r, p, s_local):
    """r^P = r + A(p) s' (§14.3): wrong forms r + Aᵀ s', r + s', r + ½A… (the book's A without its 2)."""
    R = _rot()
    r, p, s = _v(r), _v(p), _v(s_local)
    A_ = _v(R.A_from_p(p))
    return Expected(r + A_ @ s, variants=[
        ("A_transposed", r + A_.T @ s, None, None),
        ("local_vector", r + s, None, None),
        ("book_misprint", r + _book_A_of_p(p) @ s, None, "14.3-A-of-p"),
        ("factor_2_missing", r + 0.5 * A_ @ s, None, None),
    ], kind="vector")


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
    import warnings

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
        ("transposed", at, None, None),
    ], periodic=(0, 1, 2), kind="angles")


def omega_from_euler_rates(angles, rates, frame="global"):
    """ω (global) or ω' (body) from z-x-z angle rates (§14.2): wrong forms the other frame, degrees."""
    R = _rot()
    other = "body" if frame == "global" else "global"
    w = _v(R.omega_from_euler_rates(angles, rates, frame=frame))
    return Expected(w, variants=[
        ("wrong_frame", _v(R.omega_from_euler_rates(angles, rates, frame=other)), None, None),
        ("degrees", w * DEG, None, None),
        ("degrees", _v(R.omega_from_euler_rates(_v(angles) * DEG, rates, frame=frame)), None, None),
    ], kind="vector")


def _book_A_of_p(p):
    """The matrix §14.3 prints for A(p) (erratum 14.3-A-of-p): symmetric, without the factor 2."""
    e0, e1, e2, e3 = _v(p)
    return np.array([
        [e0**2 + e1**2 - 0.5, e1 * e2 - e0 * e3, e1 * e3 - e0 * e2],
        [e1 * e2 - e0 * e3, e0**2 + e2**2 - 0.5, e2 * e3 - e0 * e1],
        [e1 * e3 - e0 * e2, e2 * e3 - e0 * e1, e0**2 + e3**2 - 0.5],
    ])


def A_from_p(p):
    """A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ] (§14.3): wrong forms ½·A's bracket (the factor 2 missing), the book's
    printed matrix, Aᵀ."""
    R = _rot()
    p = _v(p)
    A_ = _v(R.A_from_p(p))
    return Expected(A_, variants=[
        ("factor_2_missing", 0.5 * A_, None, "14.3-A-of-p"),
        ("book_misprint", _book_A_of_p(p), None, "14.3-A-of-p"),
        ("transposed", A_.T, None, None),
    ], kind="rotation")


def p_from_A(A_):
    """Euler parameters of a rotation matrix (§14.3): −p is right too; wrong forms e0 last, p of Aᵀ."""
    R = _rot()
    A_ = _v(A_)
    p = _v(R.p_from_A(A_))
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
    """ω = 2Eṗ (global) or ω' = 2Gṗ (body) (§14.3): wrong forms G for E (or E for G), without the 2."""
    R = _rot()
    p, pd = _v(p), _v(p_dot)
    other = "body" if frame == "global" else "global"
    w = _v(R.omega_from_p_dot(p, pd, frame=frame))
    return Expected(w, variants=[
        ("G_for_E", _v(R.omega_from_p_dot(p, pd, frame=other)), None, None),
        ("factor_2_missing", 0.5 * w, None, None),
    ], kind="vector")
