"""Checkers for hand-built Φ, Φ_q, ν and γ (textbook §13.5–13.8, §14.4–14.5): thin entry points over one
pipeline, each stage its own module:

read (:mod:`~kinbook.grading.read`, the safe reader) → sample (:mod:`~kinbook.grading.sample`, configurations
on the manifold) → evaluate (:mod:`~kinbook.grading.evaluate`, answer and reference) → match
(:mod:`~kinbook.grading.match`, the one equivalence rule) → after-match (the steps the quantity declares,
:mod:`~kinbook.grading.quantities`, :mod:`~kinbook.grading.aftermatch`) → diagnose
(:mod:`~kinbook.grading.diagnose`, the mistake catalogue) → witness (:mod:`~kinbook.grading.witness`, rows checked
again at configurations drawn from the answer) → report (:mod:`~kinbook.grading.report`, a CheckResult translated
when shown).

No verdict depends on the clock: there is no time budget anywhere; answers are bounded in size by the
reader, and evaluated by jets (:mod:`~kinbook.grading.jets`), numerically and deterministically.

Error carried forward: pass the student's own Φ as ``phi=`` to :func:`check_jacobian`, :func:`check_nu` and
:func:`check_gamma`; each row of the answer is then graded against the derivative of the student's own row
as well as against the reference, so that one early mistake costs once.
"""

from __future__ import annotations

import numbers

import numpy as np
import sympy as sp

from . import aftermatch, diagnose, evaluate, match, report, rounding, sample, turns, witness
from ._i18n import Msg
from .quantities import quantity_of
from .read import Refused, as_numbers, read
from .report import CheckResult
from .target import NotATarget, target_for

__all__ = ["check_phi", "check_jacobian", "check_nu", "check_gamma"]


def _target(mechanism, quantity):
    try:
        return target_for(mechanism), None
    except NotATarget as exc:
        return None, report.failed(quantity, Msg("not_a_target", message=str(exc)), "malformed")


def _refused(quantity, exc):
    return report.failed(quantity, Msg(exc.key, **exc.fields), exc.code)


def _options(quantity, target, rtol, at, symbolic):
    """A failed result naming the first checker option that is not what it must be (None when all are)."""
    def bad(name, expected, got):
        text = repr(got)
        text = text if len(text) <= 60 else text[:59] + "…"
        return report.failed(quantity, Msg("bad_option", name=name, expected=expected, got=text), "malformed")

    if rtol is not None:
        ok = isinstance(rtol, (numbers.Real, np.floating, np.integer)) and not isinstance(rtol, (bool, np.bool_))
        if not ok or not np.isfinite(float(rtol)) or not 0 < float(rtol) < 1:
            return bad("rtol", Msg("opt_rtol"), rtol)
    if not isinstance(symbolic, (bool, np.bool_)):
        return bad("symbolic", Msg("opt_bool"), symbolic)
    if at is not None:
        expected = Msg("opt_at", n=target.n)
        if not isinstance(at, dict) or set(at) - {"q", "qd", "t"}:
            return bad("at", expected, at)
        for key, size in (("q", target.n), ("qd", target.n), ("t", None)):
            if key not in at:
                continue
            try:
                v = np.asarray(at[key], dtype=float)
            except (TypeError, ValueError):
                return bad(f"at['{key}']", expected, at[key])
            if (v.shape != (size,) if size else v.shape != ()) or not np.all(np.isfinite(v)):
                return bad(f"at['{key}']", expected, at[key])
    return None


def _order(order, quantity, default):
    order = default if order is None else order
    if order not in ("any", "book"):
        return None, report.failed(quantity, Msg("bad_order", order=order), "malformed")
    return order, None


# ================================================================================================ Φ
def check_phi(answer, mechanism, *, order="any", rtol=None, at=None, symbolic=False):
    """Check a hand-built constraint vector Φ(q, t).

    Parameters
    ----------
    answer : sympy Matrix, list of expressions or strings, callable ``f(q, t)``, or numbers (with ``at``)
        The student's Φ, in the mechanism's symbols (x1, y1, phi1, …, t; φ1 and phi_1 work too).
    mechanism : Mechanism or Constraint
        A whole mechanism, or one constraint of it (``mech.constraint("3")``) to grade that joint alone.
    order : {"any", "book"}
        "any" (default): Φ is a set of equations — rows may come in any order, each multiplied by any
        nonzero constant, or written in any equivalent form (same zero set and rank where the mechanism is
        assembled). "book": row k must stand for the book's Φ_k.
    rtol : float, optional
        Relative tolerance (default 1e-6; 2e-3 for numbers).
    at : dict, optional
        ``{"q": ..., "t": ...}``: the configuration at which numbers are graded (numbers are refused without).
    symbolic : bool
        Also confirm the matched rows with sympy, for rows small enough (a size budget; the verdict never
        depends on it).

    Returns
    -------
    CheckResult
        One RowResult per answer row (labelled Φ_4 … as in the book), plus one per missing reference row.

    Examples
    --------
    >>> import kinbook
    >>> mech = kinbook.examples.load("ch13_example1")
    >>> check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], mech.constraint("1")).passed
    True
    """
    target, bad = _target(mechanism, "Phi")
    if bad is not None:
        return bad
    order, bad = _order(order, "Phi", "any")
    if bad is not None:
        return bad
    bad = _options("Phi", target, rtol, at, symbolic)
    if bad is not None:
        return bad
    rtol_given = rtol
    try:
        A = read(answer, target, "Phi")
        A = as_numbers(A) if at is not None else A
        if A.kind == "numbers":
            return _numbers("Phi", A, target, at, rtol, order)
        rtol = match.RTOL if rtol is None else rtol
        data = evaluate.phi_data(target, A)
    except Refused as exc:
        return _refused("Phi", exc)
    m = match.match_phi(data, rtol, order, target.wrap, target.turns)
    m.searched = match.vanishing(m, data, rtol)
    diagnose.phi(target, A, data, m, rtol)
    turns.name_whole_turns(target, data, m, rtol)
    witness.phi(target, A, m, rtol)
    result = report.phi_result(target, m, order)
    if symbolic and A.kind == "symbolic":
        result = _confirm(result, target, A, m)
    return rounding.graded(result, A, target, "Phi", answer, lambda M: check_phi(M, mechanism, order=order,
                                                                                  rtol=rtol_given, at=at,
                                                                                  symbolic=symbolic))


# ================================================================================================ Φ_q, ν, γ
def check_jacobian(answer, mechanism, *, phi=None, order=None, rtol=None, at=None, symbolic=False):
    """Check a hand-built Jacobian Φ_q.

    Parameters
    ----------
    answer : sympy Matrix, nested list of expressions or strings, callable ``f(q, t)``, or numbers (with ``at``)
        m × n: one row per equation of Φ, one column per coordinate. For a single constraint the columns may
        be the coordinates of its bodies (x_i, y_i, φ_i, x_j, y_j, φ_j — the book's tables) or all n.
    mechanism : Mechanism or Constraint
    phi : optional
        The student's own Φ (any form :func:`check_phi` accepts). Rows of the answer then follow the
        student's rows, and each is right when it is ∂/∂q of the student's own row (error carried forward)
        or the reference's row with the student's factor.
    order : {"book", "any"}, optional
        Without ``phi``: "book" (default) expects the rows in the book's order; "any" in any order. A row may
        carry the factor −1 (the Jacobian of −Φ_k); any other constant c is named ``scaled`` (the Jacobian of
        c·Φ_k: a factor of the derivative is missing). Pass your own Φ as ``phi=`` to grade against it.
    rtol, at, symbolic
        As for :func:`check_phi`.

    Returns
    -------
    CheckResult
        Per row, the status of every entry (``RowResult.entries``).
    """
    return _derived("Phi_q", answer, mechanism, phi, order, rtol, at, symbolic)


def check_nu(answer, mechanism, *, phi=None, order=None, rtol=None, at=None, symbolic=False):
    """Check the right-hand side ν = −Φ_t of the velocity equations Φ_q q̇ = ν.

    Parameters are those of :func:`check_jacobian`; the answer is a vector of m entries (``f(q, t)`` for a
    function). The factor of a row is the one of the student's Φ row (``phi=``), else 1.
    """
    return _derived("nu", answer, mechanism, phi, order, rtol, at, symbolic)


def check_gamma(answer, mechanism, *, phi=None, order=None, rtol=None, at=None, symbolic=False):
    """Check the right-hand side γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt of the acceleration equations.

    Parameters are those of :func:`check_jacobian`; the answer is a vector of m entries in q, q̇ (dx1, dphi2
    …) and t (``f(q, qd, t)`` for a function). It is compared at assembled configurations with velocities
    that satisfy the velocity equations, so γ simplified with them (the book's φ̇_j = φ̇_i) is right.
    """
    return _derived("gamma", answer, mechanism, phi, order, rtol, at, symbolic)


def _derived(quantity, answer, mechanism, phi, order, rtol, at, symbolic):
    """The pipeline of a derived quantity: read → sample → evaluate → match → the quantity's after-match steps →
    diagnose → (without the student's Φ) the quantity's last steps → witness → report."""
    Q = quantity_of(quantity)
    target, bad = _target(mechanism, quantity)
    if bad is not None:
        return bad
    order, bad = _order(order, quantity, "book")
    if bad is not None:
        return bad
    bad = _options(quantity, target, rtol, at, symbolic)
    if bad is not None:
        return bad
    notes, rtol_given = [], rtol
    try:
        A = read(answer, target, quantity)
        A = as_numbers(A) if at is not None else A
        if A.kind == "numbers" and at is not None:
            return _numbers(quantity, A, target, at, rtol, order)
        constant = A.kind == "numbers"
        rtol = match.RTOL if rtol is None else rtol
        s = target.samples("assembled")
        w = witness.samples(target, A)
        if w is not None:
            A.prefetch(target, [s, w])
        data = evaluate.derived_data(target, A, quantity, s, target.reference("assembled"), rtol)
    except Refused as exc:
        return _refused(quantity, exc)
    if Q.per_coordinate and not data.transposed and data.S.shape[1] == data.S.shape[2] > 1:
        St = np.swapaxes(data.S, 1, 2)
        if match.same(St, data.R, rtol) and not match.same(data.S, data.R, rtol):
            data.S, data.transposed = St, True  # a square matrix given transposed
    own = _own(target, phi, quantity, data, rtol, notes) if phi is not None else None
    if own is not None:
        m = match.match_rows(data.S, data.R, rtol, order, Q.per_coordinate, own["factors"],
                             _own_rows(own, quantity, data))
    else:
        m = match.match_rows(data.S, data.R, rtol, order, Q.per_coordinate)
    aftermatch.run(Q.after_match, target, quantity, data, m, rtol)
    if data.transposed:
        notes.insert(0, Msg("transposed", expected=f"({target.m}, {len(data.cols)})",
                            got=f"({data.S.shape[2]}, {data.S.shape[1]})"))
        if all(r.status == "ok" for r in m.rows) and not m.missing:
            return report.derived_result(target, quantity, m, data, rtol, transposed=True, notes=notes)
    if constant:  # numbers without a configuration: right only as constants valid everywhere (ν = 0 of a joint)
        if own is None:  # the same factor rule as for text: [[0, 0, 2]] for a driver's Φ_q is scaled
            aftermatch.run(Q.without_own, target, quantity, data, m, rtol)
        named = [r for r in m.rows if r.status != "ok"]
        if all(r.status == "wrong" and r.code for r in named) and not m.missing and not data.transposed:
            return report.derived_result(target, quantity, m, data, rtol, notes=notes)  # right, or named as text is
        R = np.asarray(data.R, float)
        if R.size == 0 or np.ptp(R, axis=0).max() > rtol * max(np.abs(R).max(), 1.0):
            return _refused(quantity, Refused("malformed", "needs_configuration"))
        # a constant reference (a driver's Φ_q, a constant-speed ν or γ): the numbers are an answer, diagnosed as one
    diagnose.derived(target, quantity, A, data, m, rtol, own)
    if own is None:
        aftermatch.run(Q.without_own, target, quantity, data, m, rtol)
    witness.derived(target, quantity, A, data, m, rtol, w)
    result = report.derived_result(target, quantity, m, data, rtol, notes=notes,
                                   extra_codes=["transposed"] if data.transposed else [])
    if symbolic and A.kind == "symbolic":
        result = _confirm(result, target, A, m, quantity)
    return rounding.graded(result, A, target, quantity, answer, lambda M: _derived(quantity, M, mechanism, phi, order,
                                                                                   rtol_given, at, symbolic))


def _own(target, phi, quantity, data, rtol, notes):
    """The student's own Φ: factors of its rows and its derived quantities at the assembled samples."""
    try:
        P = read(phi, target, "Phi")
        if P.kind == "numbers":
            raise Refused("malformed", "needs_expression")
        pdata = evaluate.phi_data(target, P)
    except Refused as exc:
        notes.append(Msg("phi_unusable", reason=Msg(exc.key, **exc.fields)))
        return None
    pm = match.match_phi(pdata, rtol, "any", target.wrap, target.turns)
    factors = {r.k: (r.ref, r.factor) for r in pm.rows if r.status == "ok" and r.how == "multiple"}
    for r in pm.rows:
        if r.status == "ok" and r.how == "equivalent":
            factors[r.k] = (r.ref, None)
    s = target.samples("assembled")
    try:
        values = P.derived(target, s)
    except Refused as exc:
        notes.append(Msg("phi_unusable", reason=Msg(exc.key, **exc.fields)))
        return None
    tape = P.tape(target) if P.kind == "symbolic" else None
    return {"factors": factors, "values": values, "tape": tape, "matching": pm}


def _own_rows(own, quantity, data):
    v = own["values"][quantity]
    if quantity_of(quantity).per_coordinate:
        return v[:, :, data.cols] if data.cols else v
    return v[:, :, None]


# ================================================================================================ numbers
def _numbers(quantity, A, target, at, rtol, order):
    """Numbers: the values at the configuration ``at`` (refused without it)."""
    if at is None:
        raise Refused("malformed", "needs_configuration")
    if not isinstance(at, dict):
        raise Refused("malformed", "bad_configuration", at=type(at).__name__, error="expected a dict")
    try:
        s = sample.at(target, at)
    except Exception as exc:  # a KinbookError from the solver, a KeyError, a shape error …
        raise Refused("malformed", "bad_configuration", at="{…}", error=str(exc)) from None
    rtol = match.RTOL_NUMBERS if rtol is None else rtol
    ref = target.evaluate(s)
    V = A.values(target, s)
    if quantity_of(quantity).per_coordinate:
        V, transposed = evaluate.orient(V, target, quantity)
        cols = list(range(target.n)) if V.shape[2] == target.n else list(target.cols)
        data = evaluate.DerivedData(V, ref[quantity][:, :, cols], cols, transposed)
    else:
        S = evaluate.column(V, target, quantity)
        data = evaluate.DerivedData(S[:, :, None], ref[quantity][:, :, None], [])
    Q = quantity_of(quantity)
    angles = {"wrap": target.wrap, "turns": target.turns} if Q.turns else {}  # a turn of a body: the same placement
    m = match.match_rows(data.S, data.R, rtol, order, False, **angles)
    _numbers_diagnosis(quantity, data, m, rtol)
    if Q.turns:
        turns.name_turned_rows(target, data.S[:, :, 0], data.R[:, :, 0], m.rows, rtol, free=False)
    return report.derived_result(target, quantity, m, data, rtol, transposed=data.transposed and all(
        r.status == "ok" for r in m.rows))


def _numbers_diagnosis(quantity, data, m, rtol):
    Q = quantity_of(quantity)
    for r in m.rows:
        if r.status != "wrong" or r.ref is None:
            continue
        S, E = data.S[:, r.k], data.R[:, r.ref]
        if scale_of_nonzero(E) and match.same(S, -E, rtol):
            r.code = Q.sign_code
        elif Q.degrees and scale_of_nonzero(E) and match.same(S, E * 180 / np.pi, rtol):
            r.code = "degrees"
        elif Q.zero_code and np.all(S == 0):
            r.code = Q.zero_code
        else:
            r.code = "wrong_value"
        if Q.per_coordinate:
            r.entries, r.score = diagnose.entries(S, E, rtol, None, [])


def scale_of_nonzero(E):
    return match.scale_of(E) > 1e-12


# ================================================================================================ sympy
_CONFIRM_OPS = 200


def _confirm(result, target, A, m, quantity="Phi"):
    """Confirm matched rows symbolically where they are small (a size budget: larger ones are only compared
    numerically, which decides the verdict anyway)."""
    Q = quantity_of(quantity)
    pairs, skipped = [], 0
    for r in m.rows:
        if r.status != "ok" or r.how != "multiple" or r.ref is None:
            continue
        ref = target.symbolic_row(r.ref)
        if not Q.derived:
            pairs.append((A.entry(target, r.k), r.factor * ref))
        else:
            mech = target.mech
            cols = [mech.q[c] for c in target.cols] if A.shape[1] == len(target.cols) else list(mech.q)
            if Q.per_coordinate:
                for i, x in enumerate(cols):
                    pairs.append((A.entry(target, r.k, i), (r.factor or 1.0) * sp.diff(ref, x)))
            else:
                skipped += 1
    ok, unconfirmed = True, skipped
    for a, b in pairs:
        if a is None:  # too large to hand to sympy
            unconfirmed += 1
            continue
        d = a - b
        if sp.count_ops(d) > _CONFIRM_OPS:
            unconfirmed += 1
            continue
        if sp.expand(sp.expand_trig(d).rewrite(sp.exp)) != 0:
            unconfirmed += 1
    note = Msg("symbolic_confirmed") if ok and not unconfirmed else \
        Msg("symbolic_unconfirmed", n=unconfirmed, N=target.samples("assembled").N)
    return CheckResult(result.passed, result.score, list(result.notes) + [note], result.mistakes, result.rows,
                       result.quantity_msg, result.columns)
