"""What a checker grades against: a whole mechanism or one constraint, its reference and its samples.

A :class:`Target` holds kinbook's reference derivation (Φ, Φ_q, ν, γ), the book's row names, and two sets of
sample instants at which answers are compared:

* *generic* samples: random q, q̇ and t. Φ is compared there, because at assembled configurations every
  correct Φ is zero and zero says nothing about the form of a row.
* *assembled* samples: configurations with Φ(q, t) = 0 (a sweep of the mechanism, plus perturbed points
  projected back onto Φ = 0 by minimum-norm Newton steps, so that the bodies a single joint connects move
  in every direction the joint allows), with random q̇. Φ_q, ν and γ are compared there: an answer simplified
  with the help of the constraints themselves is still right.

Targets are cached on their mechanism, so a second check on the same mechanism reuses the compiled
reference and the samples.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..symbolic import derive
from ._i18n import constraint_label, row_name

__all__ = ["Target", "target_for", "Compiled"]

N_GENERIC = 16
N_ASSEMBLED = 16
SEED = 20241121
_CSE_ABOVE = 150  # operations: below this lambdify without common-subexpression elimination (faster to compile)



class Compiled:
    """A sympy matrix compiled once for vectorized evaluation over many instants.

    Constant entries are stored as numbers; only the entries that depend on q, q̇ or t are lambdified, with
    common-subexpression elimination when they are large.

    Parameters
    ----------
    matrix : sympy.Matrix, shape (r, c)
    args : sequence of symbols
        q, q̇ and t, in the order of the columns of the arrays passed when calling.
    """

    def __init__(self, matrix, args):
        matrix = sp.Matrix(matrix)
        self.shape = matrix.shape
        flat = list(matrix)
        self.const = np.zeros(len(flat))
        self.idx = []
        exprs = []
        for k, e in enumerate(flat):
            if not e.free_symbols:
                try:
                    c = complex(e)
                    self.const[k] = c.real if abs(c.imag) <= 1e-12 * (1 + abs(c.real)) else np.nan
                except (TypeError, ValueError, OverflowError):
                    self.const[k] = np.nan
            else:
                self.idx.append(k)
                exprs.append(e)
        self.fn = None
        if exprs:
            self.fn = sp.lambdify(list(args), exprs, modules="numpy", cse=_size(exprs, _CSE_ABOVE) > _CSE_ABOVE)

    def __call__(self, columns, N):
        """Evaluate at ``N`` instants; ``columns`` holds one (N,) array per argument. Returns (N, r, c)."""
        out = np.broadcast_to(self.const, (N, self.const.size)).copy()
        if self.fn is not None:
            with np.errstate(all="ignore"):
                vals = self.fn(*columns)
            for k, v in zip(self.idx, vals):
                v = np.asarray(v)
                if np.iscomplexobj(v):  # sqrt of a negative number …: not a real value, so NaN
                    v = np.where(np.abs(v.imag) > 1e-12 * (1 + np.abs(v.real)), np.nan, v.real)
                out[:, k] = np.broadcast_to(v.astype(float), (N,))
        return out.reshape((N,) + self.shape)


def _size(exprs, limit):
    """Number of nodes of the expression trees, counted up to ``limit`` (count_ops is far slower)."""
    count = 0
    for e in exprs:
        for _ in sp.preorder_traversal(e):
            count += 1
            if count > limit:
                return count
    return count


class Samples:
    """Instants at which answers are evaluated: Q, QD of shape (N, n) and T of shape (N,)."""

    def __init__(self, Q, QD, T):
        self.Q, self.QD, self.T = np.asarray(Q, float), np.asarray(QD, float), np.asarray(T, float)
        self.N = self.Q.shape[0]

    def columns(self):
        return [*self.Q.T, *self.QD.T, self.T]


class Target:
    """A mechanism or one of its constraints, prepared for grading.

    Attributes
    ----------
    mech : Mechanism
    constraint : Constraint or None
        The constraint graded alone, or None for the whole mechanism.
    constraints : list of Constraint
        The constraints whose rows are graded.
    rows : list of int
        0-based rows of the mechanism's Φ that are graded (the book numbers them from 1: Φ_4 …).
    cols : list of int
        Coordinates of Φ_q's columns: every coordinate for a mechanism, the coordinates of the constraint's
        bodies (body i, then j …) for a constraint.
    ref : kinbook.symbolic.Derivation
        The reference, restricted to ``rows``; Φ_q has all n columns.
    """

    def __init__(self, mech, constraint=None):
        self.mech = mech
        self.constraint = constraint
        self.constraints = [constraint] if constraint is not None else list(mech.constraints)
        self.rows = [r for c in self.constraints for r in range(c.rows.start, c.rows.stop)]
        if constraint is None:
            self.cols = list(range(mech.n))
            self.ref = mech.symbolic()
        else:
            q = list(mech.q)
            self.cols = [q.index(s) for b in constraint.bodies for s in mech.body_symbols(b.name)]
            self.ref = derive(mech.constraint_phi(constraint), mech.q, mech.qd, mech.t)
        self.args = [*mech.q, *mech.qd, mech.t]
        self.names = mech.coordinate_names()
        self._compiled = {}
        self._values = {}
        self._samples = {}
        self.store = {}  # caches of other modules (variants)

    # ----------------------------------------------------------------------------------------- naming
    @property
    def m(self):
        return len(self.rows)

    def label(self, k):
        """Book name of the k-th graded row: "Φ_4"."""
        return row_name(self.rows[k])

    def owner(self, k):
        """The constraint owning the k-th graded row."""
        r = self.rows[k]
        for c in self.constraints:
            if c.rows.start <= r < c.rows.stop:
                return c
        return None

    def owner_label(self, k):
        return constraint_label(self.owner(k))

    def symbols(self):
        """Names a student may use: {'x1': x1, …, 'dx1': dx1, …, 't': t}."""
        return {str(s): s for s in self.args}

    # ----------------------------------------------------------------------------------------- numbers
    def compile(self, key, matrix):
        """Compile (once per key) a sympy matrix over this target's arguments."""
        if key not in self._compiled:
            self._compiled[key] = Compiled(matrix, self.args)
        return self._compiled[key]

    def evaluate(self, key, matrix, samples, skey):
        """Values (N, r, c) of a compiled matrix at a named sample set, cached."""
        k = (key, skey)
        if k not in self._values:
            self._values[k] = self.compile(key, matrix)(samples.columns(), samples.N)
        return self._values[k]

    def reference(self, quantity, skey, samples=None):
        """Reference values of "Phi", "Phi_q", "nu" or "gamma" at a sample set: (N, m, 1) or (N, m, n)."""
        samples = samples if samples is not None else self.samples(skey)
        return self.evaluate(("ref", quantity), getattr(self.ref, quantity), samples, skey)

    def samples(self, which):
        """The "generic" or "assembled" sample set."""
        if which not in self._samples:
            rng = np.random.default_rng(SEED + (0 if which == "generic" else 1))
            if which == "generic":
                self._samples[which] = _generic(self.mech, rng)
            else:
                try:
                    found = _assembled(self, rng)
                except Exception:  # a model the solver cannot handle at all
                    found = None
                # Φ_q, ν and γ of a correct answer agree with the reference everywhere, not only where Φ = 0:
                # when too few assembled configurations are found, generic ones still decide soundly
                self._samples[which] = found if found is not None and found.N >= 4 else self.samples("generic")
        return self._samples[which]


def target_for(target):
    """The cached :class:`Target` of a mechanism, or of a constraint bound to a mechanism
    (``mech.constraint("3")``)."""
    if isinstance(target, tuple) and len(target) == 2 and hasattr(target[0], "constraint"):
        mech = target[0]  # (mechanism, constraint or its name): for constraints that do not know their mechanism
        try:
            constraint = mech.constraint(target[1]) if isinstance(target[1], str) else target[1]
        except Exception as exc:
            raise TypeError(str(exc)) from None
        if constraint not in mech.constraints:
            raise TypeError(f"{target[1]!r} is not a constraint of mechanism '{mech.name}'")
    elif hasattr(target, "constraints") and hasattr(target, "symbolic"):
        mech, constraint = target, None
    elif hasattr(target, "rows") and getattr(target, "mechanism", None) is not None:
        mech, constraint = target.mechanism, target
    else:
        raise TypeError(
            f"expected a mechanism, one of its constraints (mech.constraint(name)) or a pair (mechanism, "
            f"constraint name), got {target!r}"
        )
    # cached on the mechanism itself: mechanism ↔ targets is then one reference cycle that the garbage
    # collector frees with the mechanism (a module-level cache would keep every graded mechanism alive)
    per_mech = mech.__dict__.setdefault("_kinbook_grading_targets", {})
    key = (None if constraint is None else constraint.name, mech.n, mech.m, len(mech.constraints))
    if key not in per_mech:
        per_mech[key] = Target(mech, constraint)
    return per_mech[key]


def _generic(mech, rng):
    n = mech.n
    Q = rng.uniform(-3.0, 3.0, (N_GENERIC, n))
    if mech.kind == "planar":  # angles φ_i in one turn
        Q[:, 2::3] = rng.uniform(-np.pi, np.pi, (N_GENERIC, n // 3))
    else:  # Euler parameters on the unit sphere, where every real configuration has them
        for k in range(n // 7):
            p = rng.normal(size=(N_GENERIC, 4))
            Q[:, 7 * k + 3 : 7 * k + 7] = p / np.linalg.norm(p, axis=1, keepdims=True)
    QD = rng.normal(0.0, 3.0, (N_GENERIC, n))
    T = rng.uniform(0.0, 0.05, N_GENERIC)
    return Samples(Q, QD, T)


def _assembled(target, rng):
    mech, rows = target.mech, np.array(target.rows)
    starts, times = [], []
    try:
        res = mech.simulate(np.linspace(0.0, 0.06, 9), on_failure="truncate")
        starts, times = list(res.q), list(res.t)
    except Exception:  # no drivers, dead point at t = 0 …: start from the bodies' q0
        pass
    if not starts:
        try:
            starts, times = [mech.solve_position(0.0)], [0.0]
        except Exception:
            starts, times = [mech.q0], [0.0]
    starts, times = np.array(starts), np.array(times)
    k = rng.integers(0, len(starts), 3 * N_ASSEMBLED)
    Q = starts[k] + rng.normal(0.0, 0.4, (3 * N_ASSEMBLED, mech.n))
    T = times[k] + rng.uniform(-0.005, 0.005, 3 * N_ASSEMBLED)
    ok = np.zeros(len(Q), bool)
    for _ in range(40):
        ev = mech.evaluate(Q, T)
        F, J = ev["Phi"][:, rows], ev["Phi_q"][:, rows, :]
        res = np.abs(F).max(axis=1)
        ok = res < 1e-11
        if ok.all():
            break
        dq = np.einsum("bij,bj->bi", np.linalg.pinv(J), F)
        Q = Q - dq
        Q[~np.isfinite(Q)] = 0.0
    good = Q[ok]
    good_t = T[ok]
    # exact sweep points first (they are the configurations of the book's sweep), then projected ones
    Qa = np.vstack([starts[: N_ASSEMBLED // 2], good])[:N_ASSEMBLED] if len(starts) else good[:N_ASSEMBLED]
    Ta = np.concatenate([times[: N_ASSEMBLED // 2], good_t])[:N_ASSEMBLED]
    if len(starts) and np.abs(mech.evaluate(Qa[: min(len(starts), N_ASSEMBLED // 2)],
                                             Ta[: min(len(starts), N_ASSEMBLED // 2)])["Phi"][:, rows]).max() > 1e-8:
        Qa, Ta = good[:N_ASSEMBLED], good_t[:N_ASSEMBLED]
    QD = rng.normal(0.0, 3.0, Qa.shape)
    return Samples(Qa, QD, Ta)
