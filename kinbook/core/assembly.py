"""The fast numeric assembly of Φ, Φ_q, ν and γ: constraints grouped by kernel, their index maps into q and Φ,
and one vectorized kernel call per group and batch of instants.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError, ModelError
from .symbolic import time_derivatives

__all__ = ["ConstraintGroup", "stack_params", "compile", "evaluate"]


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


def compile(mech):
    """Group the constraints by kernel (hand-written or compiled from Φ, per ``kernels``), and gather the
    drivers' f(t) with two derivatives and the rows to wrap with their periods."""
    if not mech.bodies:
        raise ModelError(f"mechanism '{mech.name}' has no bodies")
    for b in mech.bodies:  # a body's symbolic point is the body's, not the first joint's that touches it
        for point, coords in b.points.items():
            params = {s for v in coords for s in getattr(v, "free_symbols", ())}
            if params:
                names = ", ".join(sorted(map(str, params)))
                users = [c.describe() for c in mech.constraints if b.name in c.body_names and any(
                    v == point or (isinstance(v, (tuple, list)) and point in v) for v in vars(c).values())]
                used = f" (used by {', '.join(users[:3])})" if users else ""
                raise ModelError(f"mechanism '{mech.name}': body '{b.name}', point '{point}' has symbolic parameters "
                                 f"({names}){used}: substitute numbers before a numeric evaluation")
    for c in mech.constraints:
        params = set()
        # the constraint's own numbers (a radius, phi0, a length given as a symbol for a derivation)
        own = [getattr(c, name, None) for name in type(c).parameters]
        for v in own:
            for x in (v.values() if isinstance(v, dict) else v if isinstance(v, (tuple, list)) else (v,)):
                params |= set(getattr(x, "free_symbols", ()))
        if params:
            names = ", ".join(sorted(map(str, params)))
            raise ModelError(f"{c.describe()} has symbolic parameters ({names}): substitute numbers "
                             "before a numeric evaluation")
    compiled = mech.kernels == "compiled"
    groups = {}
    for c in mech.constraints:
        kernel, params = c.numeric(compiled=compiled)
        groups.setdefault((kernel, len(c.bodies), c.n_eq), []).append((c, params))
    drivers = [(c.rows.stop - 1, *time_derivatives(c.f, where=c.describe()))
               for c in mech.constraints if c.f is not None]
    wrap = [(c.rows.start + r, float(period)) for c in mech.constraints for r, period in sorted(c.wrap.items())]
    wrap = (np.array([r for r, _ in wrap], dtype=int), np.array([p for _, p in wrap], dtype=float))
    ncoord = len(mech.COORDS)
    return ([ConstraintGroup([c for c, _ in g], kernel, [p for _, p in g], mech.n, ncoord)
             for (kernel, _, _), g in groups.items()], drivers, wrap)


def evaluate(mech, q, t=0.0, qd=None, *, jacobian=True, sparse=False, reduced=False):
    """:meth:`MechanismBase.evaluate <kinbook.core.mechanism.MechanismBase.evaluate>`: Φ, Φ_q, ν and γ of
    ``mech`` at one or many instants, one kernel call per group of constraints."""
    q = mech.check_q(q)
    single = q.ndim == 1
    qb = q[None] if single else q
    Bn = qb.shape[0]
    tb = mech.check_t(t, Bn)
    qdb = None
    if qd is not None:
        qd = mech.check_q(qd, "qd")
        qdb = qd[None] if qd.ndim == 1 else qd
        if qdb.shape[0] != Bn:
            raise InputError(f"`qd` has {qdb.shape[0]} rows but `q` has {Bn}")
    m = mech.m
    groups, drivers, wrap = mech.compiled
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
        if sparse and not single:
            raise InputError("a sparse Φ_q is available for one instant at a time")
        out["Phi_q"] = _jacobian(mech, groups, values, Bn, sparse, reduced)
    if single:
        out = {k: (v[0] if isinstance(v, np.ndarray) else v) for k, v in out.items()}
    return out


def _jacobian(mech, groups, values, Bn, sparse, reduced):
    """Φ_q from the groups' flattened blocks ``values``: a CSR matrix (``sparse``, one instant), the rows and
    columns left once the fixed bodies are set aside (``reduced``), or the whole (Bn, m, n) array."""
    m, n = mech.m, mech.n
    if sparse:
        import scipy.sparse as sps  # imported when first needed: scipy adds about half a second to `import kinbook`

        rows = np.concatenate([g.jac_rows for g in groups])
        cols = np.concatenate([g.jac_cols for g in groups])
        data = np.concatenate([v[0] for v in values])
        return sps.csr_matrix((data, (rows, cols)), shape=(m, n))
    if reduced and mech.reduction is not None:
        rows, cols = mech.reduction
        J = np.zeros((Bn, len(rows) * len(cols)))
        for g, v in zip(groups, values):
            keep, flat = g.reduced_index(rows, cols, m, n)
            J[:, flat] = v if keep is None else v[:, keep]
        return J.reshape(Bn, len(rows), len(cols))
    J = np.zeros((Bn, m * n))
    for g, v in zip(groups, values):
        J[:, g.flat] = v
    return J.reshape(Bn, m, n)
