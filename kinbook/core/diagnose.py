"""Why Φ_q is singular (textbook §13.6): the rank of the scaled Jacobian, and which constraints are redundant or
which driver has reached a dead point.

A configuration whose scaled Φ_q is nearly singular is diagnosed — :class:`~kinbook.errors.DeadPointError`,
:class:`~kinbook.errors.RedundantConstraintsError` — never returned as numbers.
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field

import numpy as np

from ..errors import (
    DeadPointError,
    RedundantConstraintsError,
    SingularJacobianError,
)
from ._linalg import column_scale, describe_rows, row_owner, scalar_time, scaled, scaled_rcond

__all__ = ["diagnose", "Diagnosis", "RCOND_MIN", "DIAGNOSE_MAX", "raise_singular"]

RCOND_MIN = 1e-8
"""Φ_q counts as singular when σ_min / σ_max of the *scaled* Φ_q is below this: the coordinates of positions
measured in units of the mechanism's length scale L (:func:`length_scale`), angles and Euler parameters as they
are, then every row divided by its norm. Scaled so, the ratio is the same for a mechanism drawn in metres or in
millimetres; below 1e-8 a velocity would carry relative errors of order 1e-8 / (position error), and the
configuration is within about 1e-8 L of a dead point or a redundancy. Such a configuration is diagnosed
(:class:`~kinbook.errors.DeadPointError`, :class:`~kinbook.errors.RedundantConstraintsError`), never returned as
numbers."""


DIAGNOSE_MAX = 2000
"""Largest number of coordinates for which :func:`diagnose` computes a dense SVD (its cost grows as n³: minutes
beyond a few thousand); larger mechanisms get the sparse estimate of σ_min/σ_max only."""


@dataclass(frozen=True)
class Diagnosis:
    """Rank analysis of Φ_q at one configuration.

    Attributes
    ----------
    kind : {"regular", "redundant", "dead-point", "singular"}
        "redundant": the geometric (non-driver) rows of Φ_q are dependent — some constraints repeat others.
        "dead-point": the geometric rows are independent but a driver row depends on them — the driver cannot
        move the mechanism any further in this configuration.
        "singular": Φ_q is singular, and the mechanism is too large (more than :data:`DIAGNOSE_MAX`
        coordinates) for the dense rank analysis that would tell which rows depend on which.
    rank, size : int
        Numerical rank of Φ_q and its number of rows.
    cond : float
        2-norm condition number of Φ_q (inf when singular, nan when not square).
    rows : list of int
        1-based rows of Φ in the dependency.
    constraints : list of str
        Their constraints' names.
    message : str
    rcond : float
        σ_min / σ_max of the scaled Φ_q, the quantity the verdict compares with :data:`RCOND_MIN`.
    """

    kind: str
    rank: int
    size: int
    cond: float
    rows: list = field(default_factory=list)
    constraints: list = field(default_factory=list)
    message: str = ""
    rcond: float = np.nan

    @property
    def singular(self):
        return self.kind != "regular"

    def __repr__(self):
        return f"Diagnosis({self.kind}: rank {self.rank} of {self.size}, cond {self.cond:.3g})"

    def _repr_html_(self):
        colour = "#2e7d32" if not self.singular else "#c62828"
        return f'<p style="color:{colour}"><b>{html.escape(self.kind)}</b>: {html.escape(self.message)}</p>'


def _left_null_rows(J, rank, rtol=1e-6):
    U, s, _ = np.linalg.svd(J, full_matrices=True)
    null = U[:, rank:]
    weight = np.linalg.norm(null, axis=1)
    return [int(r) for r in np.nonzero(weight > rtol)[0]]


def _rank(s, shape, rtol=RCOND_MIN):
    if s.size == 0:
        return 0
    return int(np.sum(s > rtol * max(s[0], 1e-300)))


def diagnose(mech, q, t=0.0, rtol=RCOND_MIN):
    """Rank analysis of Φ_q(q, t): regular, redundant constraints, or a dead point. Returns a :class:`Diagnosis`.

    The rank is that of the scaled Φ_q (see :data:`RCOND_MIN`): singular values below ``rtol`` times the largest
    do not count, so a configuration within about ``rtol`` L of a dead point is diagnosed as one."""
    t = scalar_time(t)
    if mech.n > DIAGNOSE_MAX:
        return _diagnose_large(mech, q, t, rtol)
    J0 = np.asarray(mech.evaluate(q, t)["Phi_q"])
    m, n = J0.shape
    s0 = np.linalg.svd(J0, compute_uv=False)
    cond = float(s0[0] / s0[-1]) if (m == n and s0[-1] > 0) else (np.inf if m == n else np.nan)
    J = scaled(J0, column_scale(mech))
    s = np.linalg.svd(J, compute_uv=False)
    rank = _rank(s, J.shape, rtol)
    rcond = float(s[-1] / s[0]) if s.size and s[0] > 0 and m == n else (0.0 if m == n else np.nan)
    geo = [r for c in mech.constraints if c.kind != "driver" for r in range(c.rows.start, c.rows.stop)]
    Jg = J[geo]
    sg = np.linalg.svd(Jg, compute_uv=False) if len(geo) else np.zeros(0)
    rank_g = _rank(sg, Jg.shape, rtol)
    where = f"at t = {t:.6g}"
    if rank_g < len(geo):
        rows = [geo[r] for r in _left_null_rows(Jg, rank_g)]
        msg = (f"Φ_q is rank deficient {where} (rank {rank} of {m}): the geometric constraints are redundant — "
               f"{len(geo) - rank_g} equation(s) among rows {_fmt_rows(rows)} repeat what the others impose: "
               f"{describe_rows(mech, rows)}")
        kind = "redundant"
    elif rank < min(m, n) or (m == n and rank < m):
        rows = _left_null_rows(J, rank)
        drivers = [c for c in mech.constraints if c.kind == "driver" and any(c.rows.start <= r < c.rows.stop for r in rows)]
        who = ", ".join(f"'{c.name}'" for c in drivers) or "the drivers"
        msg = (f"Φ_q is singular {where} (rank {rank} of {m}): dead point — the geometric constraints are "
               f"independent but driver {who} cannot move the mechanism further from this configuration; "
               f"dependent rows {_fmt_rows(rows)}: {describe_rows(mech, rows)}")
        kind = "dead-point"
    else:
        rows = []
        msg = f"Φ_q is regular {where}: rank {rank} of {m}, condition number {cond:.4g}"
        kind = "regular"
    names = []
    for r in rows:
        c = row_owner(mech, r)
        if c is not None and c.name not in names:
            names.append(c.name)
    return Diagnosis(kind, rank, m, cond, [r + 1 for r in rows], names, msg, rcond)


def _diagnose_large(mech, q, t, rtol):
    J = mech.evaluate(q, t, sparse=True)["Phi_q"]
    m, n = J.shape
    rcond = scaled_rcond(mech, J) if m == n else np.nan
    if m == n and rcond >= rtol:
        return Diagnosis("regular", m, m, np.nan, [], [], f"Φ_q is regular at t = {t:.6g}: scaled σ_min/σ_max ≈ "
                         f"{rcond:.3g} (estimated; n = {n} coordinates)", rcond=rcond)
    return Diagnosis("singular", -1, m, np.inf, [], [],
                     f"Φ_q is singular at t = {t:.6g} (scaled σ_min/σ_max ≈ {rcond:.3g}, estimated): with n = {n} "
                     f"coordinates, more than {DIAGNOSE_MAX}, the rank analysis that names the dependent rows is "
                     "skipped; diagnose a smaller part of the mechanism to find them", rcond=rcond)


def _fmt_rows(rows):
    return ", ".join(str(r + 1) for r in rows[:20]) + (" …" if len(rows) > 20 else "")


def raise_singular(mech, q, t, context):
    d = diagnose(mech, q, t)
    if d.kind == "regular":  # numerically singular for the LU but not by the SVD's tolerance
        d = Diagnosis("dead-point", d.rank, d.size, d.cond, [], [],
                      f"Φ_q is numerically singular at t = {t:.6g} (condition number {d.cond:.3g}, scaled "
                      f"σ_min/σ_max = {d.rcond:.3g})", d.rcond)
    cls = {"redundant": RedundantConstraintsError, "singular": SingularJacobianError}.get(d.kind, DeadPointError)
    raise cls(f"{context}: {d.message}", rows=d.rows, constraints=d.constraints, rank=d.rank, size=d.size,
              q=np.array(q, dtype=float), t=t)
