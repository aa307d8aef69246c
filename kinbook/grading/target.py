"""What a checker grades against: a whole mechanism or one of its constraints (first stage of a check).

A :class:`Target` names the rows of Φ that are graded (the book numbers them from 1: Φ_4 …), the columns of
Φ_q (every coordinate for a mechanism, the coordinates of the constraint's bodies for a constraint), and
evaluates kinbook's reference — Φ, Φ_q, ν and γ — with the mechanism's fast numeric kernels
(:meth:`kinbook.core.mechanism.MechanismBase.evaluate`), never with a symbolic derivation at check time. The
symbolic Φ of the target (for the mistake catalogue and equivalent formulations) is built only when a
diagnosis needs it, and compiled into a :class:`~kinbook.grading.jets.Tape`.

Targets and their samples are kept by the mechanism itself (:meth:`~kinbook.core.mechanism.MechanismBase.cached`),
for its current version: a mechanism that changes (a constraint removed and another added under the same
name) empties that cache, so no stale target can be reached.
"""

from __future__ import annotations

import unicodedata
import weakref

import numpy as np
import sympy as sp

from . import sample
from ._i18n import row_name
from .jets import Tape

__all__ = ["Target", "target_for", "group_target", "NotATarget"]


class NotATarget(TypeError):
    """The object given as the target of a check is not a mechanism or one of its constraints."""


def target_for(obj):
    """The cached :class:`Target` of a mechanism, of one of its constraints (``mech.constraint("3")``), or of
    a pair ``(mechanism, constraint or its name)``.

    Raises
    ------
    NotATarget
    """
    if isinstance(obj, tuple) and len(obj) == 2 and hasattr(obj[0], "constraints") and hasattr(obj[0], "evaluate"):
        mech = obj[0]
        try:
            constraint = mech.constraint(obj[1]) if isinstance(obj[1], str) else obj[1]
        except Exception as exc:  # ModelError naming the known constraints
            raise NotATarget(str(exc)) from None
        if constraint not in mech.constraints:
            raise NotATarget(f"{obj[1]!r} is not a constraint of mechanism '{mech.name}'")
    elif hasattr(obj, "constraints") and hasattr(obj, "evaluate"):
        mech, constraint = obj, None
    elif hasattr(obj, "rows") and getattr(obj, "mechanism", None) is not None:
        mech, constraint = obj.mechanism, obj
        if constraint not in mech.constraints or constraint.rows is None:
            raise NotATarget(f"constraint {constraint.name!r} is no longer part of mechanism '{mech.name}'")
    else:
        raise NotATarget(f"expected a mechanism, one of its constraints (mech.constraint(name)) or a pair "
                         f"(mechanism, constraint name), got {obj!r}")
    # kept by the mechanism, for its current version: every change empties the cache (nothing stale survives
    # a removed or re-added constraint); the target holds the mechanism only weakly (no reference cycle)
    key = ("grading", "target", None if constraint is None else constraint.name)
    return mech.cached(key, lambda: Target(mech, constraint))


def group_target(mech, constraints):
    """The cached :class:`Target` of several constraints of ``mech`` together (where only they and the bodies'
    normalization rows hold): to find which other constraint makes a row true."""
    key = ("grading", "target", tuple(c.name for c in constraints))
    return mech.cached(key, lambda: Target(mech, None, list(constraints)))


class Target:
    """A mechanism or one of its constraints, prepared for grading.

    Attributes
    ----------
    mech : Mechanism
    constraint : Constraint or None
        The constraint graded alone, or None for the whole mechanism.
    constraints : list of Constraint
        The constraints whose rows are graded.
    rows : ndarray of int
        0-based rows of the mechanism's Φ that are graded.
    cols : list of int
        Columns of Φ_q that an answer for this target holds: every coordinate, or the coordinates of the
        constraint's bodies in role order (body i, then j …: the book's tables).
    manifold_rows : ndarray of int
        Rows that vanish at the *assembled* samples: the graded rows and, in space, every body's
        normalization pᵀp − 1 (single joints included: Euler parameters are on the unit sphere).
    """

    def __init__(self, mech, constraint=None, group=None):
        self._mech = weakref.ref(mech)  # nothing here holds the mechanism (or its constraints) strongly
        self.kind = mech.kind
        if group is not None:
            self._index = sorted(mech.constraints.index(c) for c in group)
        else:
            self._index = [mech.constraints.index(constraint)] if constraint is not None else \
                list(range(len(mech.constraints)))
        self._single = constraint is not None
        self.partial = constraint is not None or group is not None
        """Some of the mechanism's constraints only: the other bodies' motion is free, so the samples spread
        over the whole configuration space of these constraints, not around the mechanism's assembly."""
        constraints = [mech.constraints[i] for i in self._index]
        self.rows = np.array([r for c in constraints for r in range(c.rows.start, c.rows.stop)], dtype=int)
        self.n = mech.n
        ncoord = len(mech.COORDS)
        if constraint is None:
            self.cols = list(range(mech.n))
        else:
            self.cols = [ncoord * (b.number - 1) + k for b in constraint.bodies for k in range(ncoord)]
        norm = [r for c in mech.constraints if c.kind == "normalization" for r in range(c.rows.start, c.rows.stop)]
        self.manifold_rows = np.array(sorted(set(self.rows) | set(norm)), dtype=int)
        self.free_rows = np.array(sorted(set(norm) - set(self.rows)), dtype=int)
        self.names = mech.coordinate_names()
        self.wrap = _wrapped_rows(self)
        self.turns = _angle_rows(self)
        """{position among the graded rows: 2π} for the other rows that measure an angle (a driver's φ_i − f(t), a
        slot's φ_i − φ_j − φ⁰, a fixed body's φ_i − c): the same placement up to whole turns, so such a row may
        differ from the reference by 2πk (:func:`~kinbook.grading.equivalence.scale_matrix`)."""
        self.time_dependent = any(c.f is not None for c in mech.constraints
                                  if set(range(c.rows.start, c.rows.stop)) & set(self.manifold_rows))
        self._samples = {}
        self._reference = {}
        self.store = {}  # derived data of later stages (symbolic Φ, variants), keyed by their module

    @property
    def constraints(self):
        """The constraints whose rows are graded."""
        cs = self.mech.constraints
        return [cs[i] for i in self._index]

    @property
    def constraint(self):
        """The constraint graded alone, or None for the whole mechanism."""
        return self.constraints[0] if self._single else None

    @property
    def mech(self):
        mech = self._mech()
        if mech is None:  # pragma: no cover - a target is only used while its mechanism is
            raise RuntimeError("the mechanism of this target was freed")
        return mech

    # ------------------------------------------------------------------------------------------- naming
    @property
    def m(self):
        """Number of graded rows."""
        return len(self.rows)

    def label(self, k):
        """Book name of the k-th graded row: "Φ_4"."""
        return row_name(int(self.rows[k]))

    def owner(self, k):
        """The constraint owning the k-th graded row."""
        r = self.rows[k]
        for c in self.constraints:
            if c.rows.start <= r < c.rows.stop:
                return c
        return None  # pragma: no cover

    def own_target(self, c):
        """The Target of constraint ``c`` graded alone (its own samples: only its rows and the bodies'
        normalization rows hold there) — this target itself when it is that constraint."""
        if self._single and self.constraint is c:
            return self
        return target_for((self.mech, c))

    def block(self, c):
        """Positions (0-based, among the graded rows) of constraint ``c``'s rows."""
        return [k for k, r in enumerate(self.rows) if c.rows.start <= r < c.rows.stop]

    # ------------------------------------------------------------------------------------------- numbers
    def samples(self, which):
        """The "generic", "wide" (generic over the whole domain) or "assembled" :class:`~kinbook.grading.sample.Samples` (seeded: the same every
        time, on every machine)."""
        if which not in self._samples:
            make = {"generic": sample.generic, "wide": sample.generic_wide, "assembled": sample.assembled}[which]
            self._samples[which] = make(self)
        return self._samples[which]

    def reference(self, which):
        """kinbook's Φ (N, m), Φ_q (N, m, n) — all n columns —, ν (N, m) and γ (N, m) at a sample set, from
        the numeric kernels."""
        if which not in self._reference:
            self._reference[which] = self.evaluate(self.samples(which))
        return self._reference[which]

    def evaluate(self, s):
        """kinbook's Φ, Φ_q, ν, γ of the graded rows at the instants of ``s`` (a Samples)."""
        ev = self.mech.evaluate(s.Q, s.T, s.QD)
        return {"Phi": ev["Phi"][:, self.rows], "Phi_q": ev["Phi_q"][:, self.rows, :],
                "nu": ev["nu"][:, self.rows], "gamma": ev["gamma"][:, self.rows],
                "free_q": ev["Phi_q"][:, self.free_rows, :]}

    def manifold(self, Q, T):
        """Φ (B, r) and [Φ_q | Φ_t] (B, r, n + 1) of the manifold rows at (Q, T)."""
        ev = self.mech.evaluate(Q, T)
        rows = self.manifold_rows
        J = np.concatenate([ev["Phi_q"][:, rows, :], -ev["nu"][:, rows, None]], axis=2)
        return ev["Phi"][:, rows], J

    # ------------------------------------------------------------------------------------------- symbolic Φ
    def symbolic_rows(self, c):
        """The symbolic Φ rows of one graded constraint ``c`` (a list), built once — cheaper than the whole
        :meth:`symbolic_phi` when one constraint's rows are wanted."""
        key = ("rows", c.name)
        if key not in self.store:
            if "phi" in self.store:
                self.store[key] = [self.store["phi"][j] for j in self.block(c)]
            else:
                self.store[key] = list(self.mech.constraint_phi(c))
        return self.store[key]

    def symbolic_row(self, j):
        """The symbolic Φ row of the j-th graded row (built with its constraint's rows only)."""
        c = self.owner(j)
        return self.symbolic_rows(c)[self.block(c).index(j)]

    def symbolic_phi(self):
        """The symbolic Φ of the graded rows (a sympy Matrix), built once; for the mistake catalogue."""
        if "phi" not in self.store:
            mech = self.mech
            self.store["phi"] = sp.Matrix.vstack(*[mech.constraint_phi(c) for c in self.constraints])
        return self.store["phi"]

    def tape(self, exprs, key=None, aliases=False):
        """A :class:`~kinbook.grading.jets.Tape` of ``exprs`` over this target's q, q̇ and t (cached by key);
        with ``aliases``, symbols are also matched by name (a student's own symbols)."""
        if key is not None and ("tape", key) in self.store:
            return self.store[("tape", key)]
        mech = self.mech
        tape = Tape(list(exprs), list(mech.q), list(mech.qd), mech.t, self.symbols() if aliases else None)
        if key is not None:
            self.store[("tape", key)] = tape
        return tape

    def symbols(self):
        """The names a student may use, each mapped to the mechanism's symbol: x1, x_1, phi2, phi_2, φ2,
        dx1, dphi2, phi2_dot, ẋ1 … and t."""
        if "symbols" not in self.store:
            mech = self.mech
            out = {"t": mech.t}
            for s, d in zip(mech.q, mech.qd):
                for name in _spellings(s.name):
                    out[name] = s
                for name in _spellings(s.name, velocity=True):
                    out[name] = d
            self.store["symbols"] = out
        return self.store["symbols"]


def _spellings(name, velocity=False):
    """x1 → x1, x_1; phi2 → phi2, phi_2, φ2, φ_2, ϕ2; e02 → e02, e0_2; with ``velocity`` the q̇ names:
    dx1, dx_1, x1_dot, xdot1 …"""
    stem = name.rstrip("0123456789")
    num = name[len(stem):]
    stems = [stem]
    if stem == "phi":
        stems += ["φ", "ϕ"]
    bases = {f"{s}{num}" for s in stems} | {f"{s}_{num}" for s in stems}
    if not velocity:
        return sorted(bases)
    out = set()
    for b in bases:
        out |= {f"d{b}", f"{b}_dot", f"{b}dot"}
    for s in stems:
        out |= {f"{s}dot{num}", f"{s}_dot_{num}", f"d{s}_{num}"}
        # the dot above as the book writes it: ẋ1, ẋ_1, φ̇2 (a combining dot; the parser reads names in NFKC,
        # which composes x + ◌̇ into ẋ)
        dotted = unicodedata.normalize("NFKC", f"{s}\u0307")
        out |= {f"{dotted}{num}", f"{dotted}_{num}"}
    return sorted(out)


def _angle_rows(target):
    """{position among the graded rows: 2π} for the rows the constraints declare to measure an angle
    (``Constraint.measures``) that the mechanism does not wrap already."""
    out = {}
    for c in target.constraints:
        for r, measure in enumerate(c.measures or ()):
            k = int(np.searchsorted(target.rows, c.rows.start + r))
            if measure == "angle" and k not in target.wrap:
                out[k] = 2 * np.pi
    return out


def _wrapped_rows(target):
    """{position among the graded rows: period} for rows whose value the mechanism wraps (an angle)."""
    out = {}
    for c in target.constraints:
        for r, period in (c.wrap or {}).items():
            out[int(np.searchsorted(target.rows, c.rows.start + r))] = float(period)
    return out
