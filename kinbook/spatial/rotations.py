"""Orientation of a body in space (textbook §14.1–14.3): direction cosines, Euler angles (z-x-z), Euler
parameters and the matrices E and G.

Conventions (docs/conventions.md): every matrix ``A`` here is *active* and maps local (body) components to
global components, ``s = A s'``; its columns are the body's unit vectors u_ξ, u_η, u_ζ in global components.
Angles are in radians unless a function takes ``degrees=True``. Euler angles are the book's intrinsic
z-x-z sequence: precession ψ about Z, nutation θ about the line of nodes (the rotated x axis), spin φ about
the body's ζ axis, so ``A = Rz(ψ) Rx(θ) Rz(φ)`` (scipy: ``Rotation.from_euler("ZXZ", [ψ, θ, φ])``).
Euler parameters are ``p = [e0, e1, e2, e3]`` with e0 = cos(α/2), [e1, e2, e3] = u sin(α/2).

Numeric functions broadcast over leading dimensions (``p`` of shape (..., 4) gives ``E`` of shape
(..., 3, 4)). ``A_from_p``, ``E``, ``G``, ``a_bar`` and ``skew`` also accept sympy expressions and return
sympy matrices: the symbolic constraints of :mod:`kinbook.spatial.constraints` are written with them.

Unit norm: every function taking Euler parameters checks |p| = 1 within ``P_TOL`` and raises
:class:`~kinbook.errors.InputError` otherwise (it does not silently normalize: a non-unit p is usually a
typing mistake or a lost normalization equation). Call :func:`normalize_p` to normalize on purpose. The
identities that hold for any p (Ep = 0, ∂(Aa)/∂p …) are available off the sphere through ``check=False``.
"""

from __future__ import annotations

import functools
import warnings

import numpy as np
import sympy as sp

from ..errors import InputError, SingularityWarning
from .arrays import array, mm, mv, parts, shapes, show, stack_rows, symbolic, transpose, unit_p, vec3

__all__ = [
    "skew",
    "check_rotation",
    "A_from_axes",
    "A_from_euler",
    "euler_from_A",
    "omega_from_euler_rates",
    "euler_rates_from_omega",
    "p_from_axis_angle",
    "axis_angle_from_p",
    "normalize_p",
    "normalization",
    "A_from_p",
    "p_from_A",
    "E",
    "G",
    "a_bar",
    "A_dot",
    "A_ddot",
    "omega_from_p_dot",
    "p_dot_from_omega",
    "alpha_from_p",
    "dAa_dp",
]

ROTATION_TOL = 1e-6
"""Tolerance on max |AᵀA − I| and |det A − 1| accepted by :func:`check_rotation`."""

SINGULAR_TOL = 1e-9
"""|sin θ| below which the z-x-z Euler angles are treated as singular."""


# ----------------------------------------------------------------------------------------------- validation
# ----------------------------------------------------------------------------------------------- basics
def skew(v):
    """Skew-symmetric matrix ṽ with ṽ w = v × w (textbook §14.4, "parallel vectors").

    Parameters
    ----------
    v : array_like, shape (..., 3), or a sympy sequence of 3

    Returns
    -------
    ndarray, shape (..., 3, 3), or sympy.Matrix

    Examples
    --------
    >>> skew([1.0, 2.0, 3.0]) @ [4.0, 5.0, 6.0]
    array([-3.,  6., -3.])
    """
    if symbolic(v):
        x, y, z = v
        return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    v = vec3(v, "v")
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    o = np.zeros_like(x)
    return np.stack([np.stack([o, -z, y], -1), np.stack([z, o, -x], -1), np.stack([-y, x, o], -1)], -2)


def check_rotation(A, name="A", tol=ROTATION_TOL):
    """Check that ``A`` is a rotation matrix (AᵀA = I and det A = +1) and return it as a float array.

    Parameters
    ----------
    A : array_like, shape (..., 3, 3)
    name : str
        Name used in the error message.
    tol : float
        Accepted max |AᵀA − I| and |det A − 1|.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, columns not orthonormal, or a reflection (det A = −1).

    Notes
    -----
    Textbook §14.1, eqs. 8 and 10. See docs/conventions.md.
    """
    A = array(A, name, (3, 3))
    err = np.abs(np.swapaxes(A, -1, -2) @ A - np.eye(3)).max(axis=(-1, -2)) if A.size else np.zeros(0)
    if np.any(err > tol):
        raise InputError(f"`{name}` is not a rotation matrix: max |{name}ᵀ{name} − I| = {float(np.max(err)):.3g} "
                         f"(its columns must be orthonormal unit vectors), got {show(A)}")
    det = np.linalg.det(A)
    if np.any(np.abs(det - 1.0) > tol):
        raise InputError(f"`{name}` is not a rotation matrix: det {name} = {float(np.ravel(det)[0]):.6g}, expected +1 "
                         f"(a reflection: the body's axes would be left-handed)")
    return A


def A_from_axes(u_xi, u_eta, u_zeta):
    """Direction-cosine matrix from the body's unit vectors (textbook §14.1, eqs. 3–7).

    Parameters
    ----------
    u_xi, u_eta, u_zeta : array_like, shape (..., 3)
        Global components of the body's unit vectors u_(ξ), u_(η), u_(ζ).

    Returns
    -------
    A : ndarray, shape (..., 3, 3)
        Columns u_ξ, u_η, u_ζ: a_ij = u_(local j) · u_(global i); maps local components to global: s = A s'.

    Raises
    ------
    InputError
        The three vectors are not an orthonormal right-handed triad.

    Examples
    --------
    >>> A_from_axes([0, 1, 0], [-1, 0, 0], [0, 0, 1]) @ [1.0, 0.0, 0.0]
    array([0., 1., 0.])
    """
    cols = [vec3(u, n) for u, n in ((u_xi, "u_xi"), (u_eta, "u_eta"), (u_zeta, "u_zeta"))]
    try:
        A = np.stack(np.broadcast_arrays(*cols), -1)
    except ValueError:
        raise InputError(f"u_xi, u_eta, u_zeta must have matching shapes, got {[c.shape for c in cols]}") from None
    return check_rotation(A, "A (columns u_xi, u_eta, u_zeta)")


# ----------------------------------------------------------------------------------------------- Euler angles
def _angle(v, name, degrees):
    a = array(v, name)
    return np.deg2rad(a) if degrees else a


@shapes
def A_from_euler(psi, theta, phi, degrees=False):
    """Rotation matrix from the book's z-x-z Euler angles (textbook §14.2).

    Parameters
    ----------
    psi, theta, phi : float or array_like, shape (...)
        Precession ψ (about global Z), nutation θ (about the line of nodes), spin φ (about the body's ζ).
    degrees : bool
        Angles in degrees instead of radians.

    Returns
    -------
    A : ndarray, shape (..., 3, 3)
        ``A = Rz(ψ) Rx(θ) Rz(φ)``: maps local to global components, s = A s'.

    Notes
    -----
    Textbook §14.2. The book writes the three elementary rotations as passive (global → local) matrices
    and their product A^{21} = A^φ A^θ A^ψ, which is the *transpose* of this A. Equal to scipy's
    ``Rotation.from_euler("ZXZ", [psi, theta, phi]).as_matrix()``. See docs/conventions.md.

    Book errata: both printed A^{21} have s^ψ s^φ, −c^ψ s^φ in the third row where the product gives
    s^ψ s^θ, −c^ψ s^θ; the first one also has the wrong sign on c^ψ s^φ and s^ψ s^φ in its second row, and its
    elementary matrices lack the minus signs (det = cos 2ψ, not a rotation); the second A^θ has cos ψ for
    cos θ and the signs of an active rotation while A^ψ, A^φ are passive.

    Examples
    --------
    >>> A_from_euler(90, 0, 0, degrees=True).round(12) @ [1.0, 0.0, 0.0]
    array([0., 1., 0.])
    """
    psi, theta, phi = (_angle(v, n, degrees) for v, n in ((psi, "psi"), (theta, "theta"), (phi, "phi")))
    cs, ss = np.cos(psi), np.sin(psi)
    ct, st = np.cos(theta), np.sin(theta)
    cp, sp_ = np.cos(phi), np.sin(phi)
    rows = [
        [cs * cp - ss * ct * sp_, -cs * sp_ - ss * ct * cp, ss * st],
        [ss * cp + cs * ct * sp_, -ss * sp_ + cs * ct * cp, -cs * st],
        [st * sp_, st * cp, ct],
    ]
    try:
        rows = [np.broadcast_arrays(*r) for r in rows]
    except ValueError:
        raise InputError("`psi`, `theta` and `phi` must have matching shapes") from None
    return np.stack([np.stack(r, -1) for r in rows], -2)


def euler_from_A(A, degrees=False):
    """z-x-z Euler angles (ψ, θ, φ) of a rotation matrix (textbook §14.2).

    Parameters
    ----------
    A : array_like, shape (..., 3, 3)
        Rotation matrix, local to global.
    degrees : bool

    Returns
    -------
    psi, theta, phi : ndarray, shape (...)
        ψ, φ in (−π, π], θ in [0, π].

    Warns
    -----
    SingularityWarning
        When sin θ = 0 (θ = 0 or π, the body's ζ axis along ±Z): the line of nodes is undefined and only
        ψ + φ (θ = 0) or ψ − φ (θ = π) is determined. Documented choice: φ = 0 and ψ carries the whole
        rotation about Z.

    Notes
    -----
    θ = arccos(a33), ψ = atan2(a13, −a23), φ = atan2(a31, a32) for A = Rz(ψ) Rx(θ) Rz(φ).
    """
    A = check_rotation(A)
    a33 = np.clip(A[..., 2, 2], -1.0, 1.0)
    theta = np.arccos(a33)
    st = np.sqrt(A[..., 0, 2] ** 2 + A[..., 1, 2] ** 2)
    singular = st < SINGULAR_TOL
    psi = np.arctan2(A[..., 0, 2], -A[..., 1, 2])
    phi = np.arctan2(A[..., 2, 0], A[..., 2, 1])
    if np.any(singular):
        warnings.warn(
            "euler_from_A: sin θ = 0 (the body's ζ axis is along ±Z), the z-x-z Euler angles are singular: "
            "only ψ ± φ is defined; returning φ = 0 and the whole rotation about Z in ψ",
            SingularityWarning, stacklevel=2,
        )
        # θ = 0: A = Rz(ψ + φ); θ = π: A = Rz(ψ − φ) Rx(π). With φ = 0, ψ = atan2(a21, a11) in both cases.
        psi = np.where(singular, np.arctan2(A[..., 1, 0], A[..., 0, 0]), psi)
        phi = np.where(singular, 0.0, phi)
        theta = np.where(singular, np.where(a33 > 0, 0.0, np.pi), theta)
    out = (psi, theta, phi)
    if degrees:
        out = tuple(np.rad2deg(v) for v in out)
    if np.ndim(out[0]) == 0:
        out = tuple(float(v) for v in out)
    return out


def _euler_matrix(psi, theta, phi, frame):
    """Matrix M with ω = M [ψ̇, θ̇, φ̇] in the given frame."""
    cs, ss, ct, st, cp, sp_ = np.cos(psi), np.sin(psi), np.cos(theta), np.sin(theta), np.cos(phi), np.sin(phi)
    o, i = np.zeros_like(ct), np.ones_like(ct)
    if frame == "global":
        rows = [[o, cs, ss * st], [o, ss, -cs * st], [i, o, ct]]
    else:
        rows = [[st * sp_, cp, o], [st * cp, -sp_, o], [ct, o, i]]
    rows = [np.broadcast_arrays(*r) for r in rows]
    return np.stack([np.stack(r, -1) for r in rows], -2)


def _frame(frame):
    if frame not in ("global", "body"):
        raise InputError(f"`frame` must be 'global' or 'body', got {frame!r}")
    return frame


def _euler_args(angles, name, degrees):
    a = array(angles, name, (3,))
    a = np.deg2rad(a) if degrees else a
    return a[..., 0], a[..., 1], a[..., 2]


@shapes
def omega_from_euler_rates(angles, rates, frame="global", degrees=False):
    """Angular velocity from z-x-z Euler angles and their rates (textbook §14.2).

    Parameters
    ----------
    angles : array_like, shape (..., 3)
        (ψ, θ, φ).
    rates : array_like, shape (..., 3)
        (ψ̇, θ̇, φ̇), in rad/s (deg/s with ``degrees=True``; ω is then returned in deg/s too).
    frame : {"global", "body"}
        Components of ω: global (ω) or body (ω').

    Returns
    -------
    omega : ndarray, shape (..., 3)

    Notes
    -----
    ω = ψ̇ u_Z + θ̇ u_N + φ̇ u_ζ, with the line of nodes u_N = [cos ψ, sin ψ, 0]. Body components:
    ω' = [ψ̇ sθ sφ + θ̇ cφ, ψ̇ sθ cφ − θ̇ sφ, ψ̇ cθ + φ̇] (textbook §14.2; its printed matrix has four columns,
    an extra 1 in the third row and, in the first version, +sin φ where −sin φ belongs in the second row of
    both the matrix and its inverse).
    """
    frame = _frame(frame)
    psi, theta, phi = _euler_args(angles, "angles", degrees)
    rates = array(rates, "rates", (3,))
    return np.einsum("...ij,...j->...i", _euler_matrix(psi, theta, phi, frame), rates)


@shapes
def euler_rates_from_omega(angles, omega, frame="global", degrees=False):
    """z-x-z Euler angle rates (ψ̇, θ̇, φ̇) from the angular velocity (textbook §14.2).

    Parameters
    ----------
    angles : array_like, shape (..., 3)
    omega : array_like, shape (..., 3)
        Angular velocity in ``frame`` components.
    frame : {"global", "body"}

    Returns
    -------
    rates : ndarray, shape (..., 3)

    Raises
    ------
    InputError
        At sin θ = 0 the matrix relating rates and ω is singular (ψ̇ and φ̇ are not separately defined): the
        message names θ. Use Euler parameters (:func:`p_dot_from_omega`) there.
    """
    frame = _frame(frame)
    psi, theta, phi = _euler_args(angles, "angles", degrees)
    omega = array(omega, "omega", (3,))
    st = np.sin(theta)
    if np.any(np.abs(st) < SINGULAR_TOL):
        th = float(np.ravel(theta)[np.argmin(np.ravel(np.abs(st)))])
        raise InputError(
            f"Euler angle rates are undefined at θ = {th:.6g} rad (sin θ = 0, the body's ζ axis is along ±Z): "
            "only ψ̇ ± φ̇ is determined by ω; use Euler parameters (p_dot_from_omega) instead"
        )
    cs, ss, ct, cp, sp_ = np.cos(psi), np.sin(psi), np.cos(theta), np.cos(phi), np.sin(phi)
    o, i = np.zeros_like(ct), np.ones_like(ct)
    if frame == "global":
        rows = [[-ss * ct / st, cs * ct / st, i], [cs, ss, o], [ss / st, -cs / st, o]]
    else:
        rows = [[sp_ / st, cp / st, o], [cp, -sp_, o], [-sp_ * ct / st, -cp * ct / st, i]]
    rows = [np.broadcast_arrays(*r) for r in rows]
    M = np.stack([np.stack(r, -1) for r in rows], -2)
    out = np.einsum("...ij,...j->...i", M, omega)
    return out


# ----------------------------------------------------------------------------------------------- Euler parameters
@shapes
def p_from_axis_angle(axis, angle, degrees=False):
    """Euler parameters of a rotation by ``angle`` about ``axis`` (textbook §14.3).

    Parameters
    ----------
    axis : array_like, shape (..., 3)
        Rotation axis in global components (= body components: the axis is fixed by the rotation); it is
        normalized here, and must not be zero.
    angle : float or array_like, shape (...)
        Rotation angle α (right-hand rule about ``axis``).

    Returns
    -------
    p : ndarray, shape (..., 4)
        [cos(α/2), u sin(α/2)].

    Examples
    --------
    >>> p_from_axis_angle([0, 0, 1], 180, degrees=True).round(12)
    array([0., 0., 0., 1.])
    """
    axis = vec3(axis, "axis")
    n = np.linalg.norm(axis, axis=-1)
    if np.any(n < 1e-12):
        raise InputError(f"`axis` must be a nonzero vector, got {show(axis)}")
    u = axis / n[..., None]
    a = _angle(angle, "angle", degrees)
    c, s = np.cos(a / 2), np.sin(a / 2)
    try:
        return np.concatenate([np.broadcast_to(c, np.broadcast_shapes(c.shape, u.shape[:-1]))[..., None],
                               u * s[..., None]], -1)
    except ValueError:
        raise InputError(f"`axis` {axis.shape} and `angle` {np.shape(angle)} have incompatible shapes") from None


def axis_angle_from_p(p):
    """Axis u and angle α ∈ [0, π] of the rotation described by unit Euler parameters.

    Returns
    -------
    axis : ndarray, shape (..., 3)
        Unit vector; [1, 0, 0] by convention for the identity (α = 0).
    angle : ndarray, shape (...)
    """
    p = unit_p(p)
    p = np.where(p[..., :1] < 0, -p, p)  # p and −p are the same rotation
    s = np.linalg.norm(p[..., 1:], axis=-1)
    angle = 2 * np.arctan2(s, p[..., 0])
    axis = np.where(s[..., None] > 1e-12, p[..., 1:] / np.maximum(s, 1e-300)[..., None], [1.0, 0.0, 0.0])
    return axis, angle


def normalize_p(p):
    """Euler parameters divided by their norm, shape (..., 4). Raises InputError for p = 0."""
    p = unit_p(p, check=False)
    big = np.max(np.abs(p), axis=-1, keepdims=True)  # divide by it first: |p|² of p = 1e300 overflows
    unit = p / np.where(big > 0, big, 1.0)
    n = np.linalg.norm(unit, axis=-1, keepdims=True)
    if np.any(big * n < 1e-12):
        raise InputError("`p` = 0 cannot be normalized: it describes no rotation")
    return unit / n


def normalization(p):
    """The normalization constraint pᵀp − 1 (zero for valid Euler parameters), shape (...)."""
    if symbolic(p):
        p = sp.Matrix(p)
        return (p.T * p)[0] - 1
    p = unit_p(p, check=False)
    return np.einsum("...i,...i->...", p, p) - 1.0


def E(p, check=True):
    """The 3×4 matrix E(p) of the Euler parameters (textbook §14.3).

    E = [−e, ẽ + e0 I], so that A = E Gᵀ, ω = 2 E ṗ and Ep = 0.

    Parameters
    ----------
    p : array_like, shape (..., 4), or a sympy sequence of 4
    check : bool
        Require |p| = 1 (numeric input only). E is linear in p; pass ``check=False`` to evaluate it at a
        rate ṗ, as in Ė = E(ṗ).

    Returns
    -------
    ndarray, shape (..., 3, 4), or sympy.Matrix
    """
    if symbolic(p):
        e0, e1, e2, e3 = p
        return sp.Matrix([[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]])
    e0, e1, e2, e3 = parts(unit_p(p, check=check))
    return stack_rows([[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]])


def G(p, check=True):
    """The 3×4 matrix G(p) of the Euler parameters (textbook §14.3).

    G = [−e, −ẽ + e0 I], so that A = E Gᵀ, ω' = 2 G ṗ and Gp = 0.

    Notes
    -----
    The book prints the second row as [−e2, e3, e0, e1]; it is [−e2, −e3, e0, e1] (with the printed row,
    Gp = [0, 2 e1 e3, 0] ≠ 0). Same parameters as :func:`E`.
    """
    if symbolic(p):
        e0, e1, e2, e3 = p
        return sp.Matrix([[-e1, e0, e3, -e2], [-e2, -e3, e0, e1], [-e3, e2, -e1, e0]])
    e0, e1, e2, e3 = parts(unit_p(p, check=check))
    return stack_rows([[-e1, e0, e3, -e2], [-e2, -e3, e0, e1], [-e3, e2, -e1, e0]])


def A_from_p(p, check=True):
    """Rotation matrix from Euler parameters (textbook §14.3).

    Parameters
    ----------
    p : array_like, shape (..., 4), or a sympy sequence of 4
        [e0, e1, e2, e3]; must have unit norm (within ``P_TOL``) unless ``check=False``.

    Returns
    -------
    A : ndarray, shape (..., 3, 3), or sympy.Matrix
        Maps local (body) components to global components: s = A s'.

    Notes
    -----
    A = 2 [(e0² − ½) I + e eᵀ + e0 ẽ], with e = [e1, e2, e3]. This is the form every kinbook constraint
    uses; for it ∂(Aa)/∂p = 2(Eā + a pᵀ) exactly (:func:`dAa_dp`). On the unit sphere it equals E Gᵀ
    (E Gᵀ = A + (1 − pᵀp) I elsewhere). The book prints this matrix without the factor 2 and with wrong
    signs in a13, a21 and a32 (its printed matrix is symmetric, which a rotation is not).
    See docs/conventions.md.

    Examples
    --------
    >>> A_from_p([np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)]).round(12) @ [1.0, 0.0, 0.0]
    array([0., 1., 0.])
    """
    if symbolic(p):
        return sp.Matrix(3, 3, _A_entries(*p))
    e0, e1, e2, e3 = parts(unit_p(p, check=check))
    return 2 * stack_rows([
        [e0 * e0 + e1 * e1 - 0.5, e1 * e2 - e0 * e3, e1 * e3 + e0 * e2],
        [e1 * e2 + e0 * e3, e0 * e0 + e2 * e2 - 0.5, e2 * e3 - e0 * e1],
        [e1 * e3 - e0 * e2, e2 * e3 + e0 * e1, e0 * e0 + e3 * e3 - 0.5],
    ])


@functools.lru_cache(maxsize=256, typed=True)
def _A_entries(e0, e1, e2, e3):
    """The nine entries of the symbolic A(p), row by row (sympy expressions are immutable, so one build serves every
    constraint that reads the same body: a spatial Φ reads A(p) once per point and vector, and the checkers' mistake
    catalogue rebuilds each joint's Φ a dozen times). ``typed``: 1 and 1.0 are two keys, as they are two
    expressions."""
    e = sp.Matrix([e1, e2, e3])
    return tuple(2 * ((e0**2 - sp.Rational(1, 2)) * sp.eye(3) + e * e.T + e0 * skew(e)))


def p_from_A(A):
    """Euler parameters of a rotation matrix, robust for every rotation (textbook §14.3).

    Parameters
    ----------
    A : array_like, shape (..., 3, 3)

    Returns
    -------
    p : ndarray, shape (..., 4)
        Unit Euler parameters with e0 ≥ 0 (p and −p describe the same rotation).

    Notes
    -----
    From tr A = 4e0² − 1 and a_ii = 2(e0² + e_i²) − 1: 4e0² = 1 + tr A, 4e_i² = 1 + 2a_ii − tr A (the book
    prints e0² = (p + 1)/4 for (t + 1)/4 and defines t through the unknown e's instead of as
    t = tr A = a11 + a22 + a33). The book then divides by e0 (e1 = (a32 − a23)/(4e0) …), which fails for 180° rotations. Here the largest of the
    four squares is taken from the diagonal and the other three from the off-diagonal sums and differences
    (a32 − a23 = 4e0e1, a21 + a12 = 4e1e2, …), so the divisor is never smaller than ½.
    """
    A = check_rotation(A)
    tr = A[..., 0, 0] + A[..., 1, 1] + A[..., 2, 2]
    sq = np.stack([1 + tr, 1 + 2 * A[..., 0, 0] - tr, 1 + 2 * A[..., 1, 1] - tr, 1 + 2 * A[..., 2, 2] - tr], -1) / 4
    k = np.argmax(sq, axis=-1)
    a = lambda i, j: A[..., i, j]  # noqa: E731
    # 4 e_a e_b for every pair
    prod = {
        (0, 1): a(2, 1) - a(1, 2), (0, 2): a(0, 2) - a(2, 0), (0, 3): a(1, 0) - a(0, 1),
        (1, 2): a(1, 0) + a(0, 1), (1, 3): a(0, 2) + a(2, 0), (2, 3): a(2, 1) + a(1, 2),
    }
    p = np.zeros(A.shape[:-2] + (4,))
    for branch in range(4):
        big = np.sqrt(np.maximum(sq[..., branch], 0.0))
        cand = [None] * 4
        cand[branch] = big
        for other in range(4):
            if other != branch:
                key = (min(branch, other), max(branch, other))
                cand[other] = prod[key] / (4 * np.maximum(big, 1e-300))
        p = np.where((k == branch)[..., None], np.stack(cand, -1), p)
    p = np.where(p[..., :1] < 0, -p, p)
    return p / np.linalg.norm(p, axis=-1, keepdims=True)


def a_bar(a):
    """The 4×4 matrix ā of a 3-vector a (textbook §14.3): ā = [[0, −aᵀ], [a, −ã]].

    It satisfies G(p)ᵀ a = ā p for every p, hence ∂(Aa)/∂p = 2(Eā + a pᵀ).

    Notes
    -----
    The book's block form [[0, −aᵀ], [a, −ã]] is right; its element-by-element matrix printed next to it
    has +ã in the lower-right block (row 2 printed as [a1, 0, −a3, a2], correct [a1, 0, a3, −a2]).
    """
    if symbolic(a):
        a1, a2, a3 = a
        return sp.Matrix([[0, -a1, -a2, -a3], [a1, 0, a3, -a2], [a2, -a3, 0, a1], [a3, a2, -a1, 0]])
    a = vec3(a, "a")
    a1, a2, a3 = a[..., 0], a[..., 1], a[..., 2]
    o = np.zeros_like(a1)
    return stack_rows([[o, -a1, -a2, -a3], [a1, o, a3, -a2], [a2, -a3, o, a1], [a3, a2, -a1, o]])


@shapes
def A_dot(p, p_dot):
    """Time derivative of A: Ȧ = 2 E Ġᵀ = 2 Ė Gᵀ (textbook §14.3), shape (..., 3, 3).

    Parameters
    ----------
    p : array_like, shape (..., 4)
        Unit Euler parameters.
    p_dot : array_like, shape (..., 4)
        ṗ; it must satisfy pᵀṗ = 0 (the derivative of the normalization) for the identity to hold.
    """
    p = unit_p(p)
    pd = unit_p(p_dot, "p_dot", check=False)
    _tangent(p, pd)
    return 2 * mm(E(p), transpose(G(pd, check=False)))


@shapes
def A_ddot(p, p_dot, p_ddot):
    """Second time derivative of A: Ä = 2 Ė Ġᵀ + 2 E G̈ᵀ (textbook §14.3), shape (..., 3, 3).

    Applied to a vector: Ä a = 2 Ė Ġᵀ a + 2 E ā p̈. ṗ must satisfy pᵀṗ = 0 and p̈ must satisfy
    pᵀp̈ = −ṗᵀṗ (the first and second derivatives of the normalization).
    """
    p = unit_p(p)
    pd = unit_p(p_dot, "p_dot", check=False)
    pdd = unit_p(p_ddot, "p_ddot", check=False)
    _tangent(p, pd)
    r = np.einsum("...i,...i->...", p, pdd) + np.einsum("...i,...i->...", pd, pd)
    if np.any(np.abs(r) > 1e-6 * (1 + np.einsum("...i,...i->...", pd, pd))):
        raise InputError(f"`p_ddot` must satisfy pᵀp̈ + ṗᵀṗ = 0 (second derivative of pᵀp = 1), got {show(r)}")
    return 2 * mm(E(pd, check=False), transpose(G(pd, check=False))) + 2 * mm(E(p), transpose(G(pdd, check=False)))


def _tangent(p, pd):
    r = np.einsum("...i,...i->...", p, pd)
    if np.any(np.abs(r) > 1e-6 * (1 + np.linalg.norm(pd, axis=-1))):
        raise InputError(f"`p_dot` must satisfy pᵀṗ = 0 (derivative of the normalization pᵀp = 1), got pᵀṗ = {show(r)}")


@shapes
def omega_from_p_dot(p, p_dot, frame="global"):
    """Angular velocity from Euler parameter rates: ω = 2 E ṗ, ω' = 2 G ṗ (textbook §14.3).

    Parameters
    ----------
    p, p_dot : array_like, shape (..., 4)
    frame : {"global", "body"}

    Returns
    -------
    omega : ndarray, shape (..., 3)
    """
    frame = _frame(frame)
    p = unit_p(p)
    pd = unit_p(p_dot, "p_dot", check=False)
    _tangent(p, pd)
    M = E(p) if frame == "global" else G(p)
    return 2 * mv(M, pd)


@shapes
def p_dot_from_omega(p, omega, frame="global"):
    """Euler parameter rates from the angular velocity: ṗ = ½ Eᵀ ω = ½ Gᵀ ω' (textbook §14.3).

    Returns ṗ, shape (..., 4), which satisfies pᵀṗ = 0.
    """
    frame = _frame(frame)
    p = unit_p(p)
    w = vec3(omega, "omega")
    M = E(p) if frame == "global" else G(p)
    return 0.5 * mv(transpose(M), w)


@shapes
def alpha_from_p(p, p_ddot, frame="global"):
    """Angular acceleration from Euler parameters: α = 2 E p̈, α' = 2 G p̈ (Ė ṗ = Ġ ṗ = 0).

    Returns
    -------
    alpha : ndarray, shape (..., 3)
    """
    frame = _frame(frame)
    p = unit_p(p)
    pdd = unit_p(p_ddot, "p_ddot", check=False)
    M = E(p) if frame == "global" else G(p)
    return 2 * mv(M, pdd)


@shapes
def dAa_dp(p, a, form="A"):
    """Partial derivative ∂(A a)/∂p of a rotated constant vector a with respect to p (textbook §14.3).

    Parameters
    ----------
    p : array_like, shape (..., 4)
        Any Euler parameters: the formula is exact off the unit sphere too (no norm check).
    a : array_like, shape (..., 3)
        Local components of a constant vector.
    form : {"A", "EG"}
        Which expression of A is differentiated. "A": the form of :func:`A_from_p`,
        2[(e0² − ½)I + eeᵀ + e0ẽ], for which ∂(Aa)/∂p = 2(Eā + a pᵀ) (the book's formula). "EG": the
        homogeneous form E Gᵀ, for which ∂(E Gᵀ a)/∂p = 2 E ā. Both agree in value on the unit sphere,
        but their derivatives differ by 2 a pᵀ because E Gᵀ = A + (1 − pᵀp) I.

    Returns
    -------
    ndarray, shape (..., 3, 4)
    """
    if form not in ("A", "EG"):
        raise InputError(f"`form` must be 'A' or 'EG', got {form!r}")
    p = unit_p(p, check=False)
    a = vec3(a, "a")
    out = 2 * mm(E(p, check=False), a_bar(a))
    if form == "A":
        out = out + 2 * a[..., :, None] * p[..., None, :]
    return out
