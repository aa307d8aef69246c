"""Checkers for hand-built Φ, Φ_q, ν and γ (textbook §13.5–13.8).

Judging is numeric first: the answer and kinbook's reference are evaluated at many instants — generic ones
for Φ, assembled ones (Φ(q, t) = 0) for Φ_q, ν and γ; see :mod:`kinbook.grading._target` — and compared row
by row with a relative tolerance. sympy is used to read and differentiate answers (always under a time
limit, :mod:`kinbook.grading._timelimit`) and, when asked (``symbolic=True``) or when the numeric evidence is
borderline, to confirm an equivalence symbolically within a small budget.

Error carried forward: pass the student's own Φ as ``phi=`` to :func:`check_jacobian`, :func:`check_nu` and
:func:`check_gamma`; their answer is then matched to their own rows and graded against the derivative of
their own Φ, so that one early mistake costs once.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..symbolic import derive
from . import variants as V
from ._i18n import tr
from ._target import Samples, target_for
from ._timelimit import run_limited
from .answers import Malformed, read
from .catalogue import explain
from .result import CheckResult, RowResult, failed

__all__ = ["check_phi", "check_jacobian", "check_nu", "check_gamma"]

RTOL = 1e-6
RTOL_NUMBERS = 2e-3
ATOL = 1e-9
SYMBOLIC_SECONDS = 1.0
_QNAME = {"Phi": "Φ", "Phi_q": "Φ_q", "nu": "ν", "gamma": "γ"}


# ================================================================================================ matching
def _close(a, b, rtol, atol=ATOL):
    """Entry-wise |a − b| ≤ rtol·scale + atol along the sample axis (axis 0); scale is max |b| per row."""
    scale = np.max(np.abs(b)) if b.size else 0.0
    return np.all(np.abs(a - b) <= rtol * scale + atol, axis=0)


def _same(a, b, rtol, atol=ATOL):
    """The whole arrays agree (scale 1)."""
    return bool(np.all(_close(a, b, rtol, atol)))


def _scale_match(a, b, rtol, atol=ATOL):
    """The constant c with a ≈ c b over all samples, or None."""
    bb = float(np.sum(b * b))
    amax = float(np.max(np.abs(a))) if a.size else 0.0
    if bb <= atol**2:
        return None
    c = float(np.sum(a * b)) / bb
    if abs(c) < 1e-9 or amax <= atol:
        return None
    if np.max(np.abs(a - c * b)) <= rtol * max(amax, abs(c) * float(np.max(np.abs(b)))) + atol:
        return _nice(c)
    return None


def _nice(c):
    for r in (1.0, -1.0, 2.0, -2.0, 0.5, -0.5):
        if abs(c - r) < 1e-9 * max(1.0, abs(c)):
            return r
    return c


def _all_pairs(S, R, rtol):
    """Scale matches between every student row (S: N, ms, w) and reference row (R: N, m, w)."""
    ms, m = S.shape[1], R.shape[1]
    C = np.full((ms, m), np.nan)
    for k in range(ms):
        for j in range(m):
            c = _scale_match(S[:, k], R[:, j], rtol)
            if c is not None:
                C[k, j] = c
    return C


def _assign(C, prefer_diagonal=True):
    """Greedy one-to-one assignment from the match matrix: student row → (reference row, scale)."""
    ms, m = C.shape
    taken, out = set(), {}
    if prefer_diagonal:
        for k in range(min(ms, m)):
            if not np.isnan(C[k, k]):
                out[k] = (k, C[k, k])
                taken.add(k)
    for k in range(ms):
        if k in out:
            continue
        for j in range(m):
            if j not in taken and not np.isnan(C[k, j]):
                out[k] = (j, C[k, j])
                taken.add(j)
                break
    return out


def _finite_or_fail(S, quantity, target):
    """A failed result naming the first row with NaN, inf or a complex value; None when all is finite.
    ``S`` has shape (N, rows) or (N, rows, columns)."""
    bad = ~np.isfinite(S)
    if not bad.any():
        return None
    per_row = bad.reshape(bad.shape[0], bad.shape[1], -1).any(axis=(0, 2))
    k = int(np.argmax(per_row))
    where = target.label(k) if k < target.m else tr("your_row", k=k + 1)
    return failed(_QNAME[quantity], tr("not_finite", where=where), "not_finite")


def _mistake_msg(code):
    """Short per-row text: the mistake's title (its hint is given once, by :func:`_hints`)."""
    title, _ = explain(code)
    return tr("row_mistake_short", title=title)


def _hints(codes):
    """One line per mistake code: "title: hint"."""
    out = []
    for code in codes:
        title, hint = explain(code)
        out.append(tr("hint", title=title, hint=hint))
    return out


def _row_prefix(target, k):
    return f"{target.label(k)} — {target.owner_label(k)}"


def _numbers_samples(target, at):
    """The configuration ``at`` as a one-instant sample set; default: assembled at t = 0."""
    mech = target.mech
    if at is None:
        try:
            q = mech.solve_position(0.0)
            return Samples(q[None], mech.solve_velocity(q, 0.0)[None], [0.0])
        except Exception:  # no drivers (a joint graded alone): the first assembled sample
            s = target.samples("assembled")
            return Samples(s.Q[:1], s.QD[:1], s.T[:1])
    at = dict(at)
    t = float(at.get("t", 0.0))
    q = np.asarray(at["q"], float) if "q" in at else mech.solve_position(t)
    qd = np.asarray(at["qd"], float) if "qd" in at else mech.solve_velocity(q, t)
    return Samples(q[None], qd[None], [t])


def _prepare(answer, target, quantity, shape, at):
    """Read the answer and pick the samples; returns (Answer, samples, skey, rtol) or a failed result."""
    numbers = _looks_numeric(answer)
    A = read(answer, target, quantity, shape, at=at if at is not None else (True if numbers else None))
    if isinstance(A, Malformed):
        return failed(_QNAME[quantity], A.message, A.code)
    if A.kind == "numeric":
        try:
            samples = _numbers_samples(target, at)
        except Exception as exc:
            return failed(_QNAME[quantity], tr("needs_configuration") + f" ({exc})", "malformed")
        return A, samples, ("at", _key(samples)), RTOL_NUMBERS
    skey = "generic" if quantity == "Phi" else "assembled"
    return A, target.samples(skey), skey, RTOL


def _key(samples):
    return hash((samples.Q.tobytes(), samples.QD.tobytes(), samples.T.tobytes()))


def _looks_numeric(answer):
    from .answers import _all_numbers

    if isinstance(answer, (int, float, np.number)):
        return True
    return isinstance(answer, (list, tuple, np.ndarray)) and _all_numbers(answer)


def _values(A, samples, quantity, target):
    S = A(samples)
    if isinstance(S, Malformed):
        return failed(_QNAME[quantity], S.message, S.code)
    S = np.asarray(S, dtype=float)
    if S.ndim == 2:
        S = S[:, :, None]
    return S


def _reference(target, quantity, samples, skey):
    return target.reference(quantity, skey, samples)


# ================================================================================================ Φ
def check_phi(answer, mechanism, *, order="any", rtol=None, at=None, symbolic=False):
    """Check a hand-built constraint vector Φ(q, t).

    Parameters
    ----------
    answer : sympy Matrix, list of expressions or strings, callable ``f(q, t)``, or numbers
        The student's Φ, in the mechanism's symbols (``mech.q``, ``mech.t``: x1, y1, phi1, …, t).
    mechanism : Mechanism or Constraint
        A whole mechanism, or one constraint of it (``mech.constraint("3")``) to grade that joint alone.
    order : {"any", "book"}
        "any" (default): Φ is a set of constraints — rows may come in any order and be multiplied by any
        nonzero constant. "book": row k must be the book's Φ_k (up to a constant factor).
    rtol : float, optional
        Relative tolerance of the numeric comparison (default 1e-6; 2e-3 for numbers).
    at : dict, optional
        ``{"q": ..., "t": ...}``: the configuration at which numeric answers are graded.
    symbolic : bool
        Also confirm the rows judged correct with sympy (``simplify(answer − c·reference) == 0``), within a
        total budget of ``SYMBOLIC_SECONDS``; the verdict itself always rests on the numeric comparison at
        32 configurations (a symbolic proof can time out, a numeric test cannot hang). Only in the main
        thread (see :mod:`kinbook.grading._timelimit`).

    Returns
    -------
    CheckResult
        One :class:`RowResult` per row of the reference (labelled Φ_4 … as in the book), plus one per
        extra row of the answer.

    Examples
    --------
    >>> import kinbook
    >>> mech = kinbook.examples.load("ch13_example1")
    >>> check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], mech.constraint("1")).passed
    True
    """
    try:
        target = target_for(mechanism)
    except TypeError as exc:
        return failed("Φ", str(exc), "malformed")
    if order not in ("any", "book"):
        return failed("Φ", f"`order` must be 'any' or 'book', got {order!r}", "malformed")
    prep = _prepare(answer, target, "Phi", (target.m, 1), at)
    if isinstance(prep, CheckResult):
        return prep
    A, samples, skey, default_rtol = prep
    rtol = default_rtol if rtol is None else rtol
    S = _values(A, samples, "Phi", target)
    if isinstance(S, CheckResult):
        return S
    if S.shape[2] != 1:
        return failed("Φ", tr("wrong_shape", expected=f"({target.m},) or ({target.m}, 1)", got=S.shape[1:]),
                      "wrong_shape")
    bad = _finite_or_fail(S[:, :, 0], "Phi", target)
    if bad is not None:
        return bad
    R = _reference(target, "Phi", samples, skey)
    match = _match_phi_rows(target, A, S, R, samples, skey, rtol)
    result = _phi_result(target, match, S.shape[1], order, A, symbolic)
    if symbolic and A.expr is not None:
        pairs = [(A.expr[k, 0], c * target.ref.Phi[j, 0]) for k, (j, c) in match["ok"].items() if c is not None]
        result = _with_symbolic_note(result, pairs)
    return result


def _match_phi_rows(target, A, S, R, samples, skey, rtol):
    """Assign every student row of Φ to a reference row: correct (with its scale), a catalogued mistake,
    or nothing. Returns dict with 'ok' {k: (j, c)}, 'mistake' {k: (j, code)}, 'unmatched' [k], 'free' [j]."""
    C = _all_pairs(S, R, rtol)
    ok = _assign(C)
    free = [j for j in range(R.shape[1]) if j not in {j for j, _ in ok.values()}]
    left = [k for k in range(S.shape[1]) if k not in ok]
    mistakes = {}
    if left and free:
        cand = _phi_variants(target, samples, skey, free)
        for k in list(left):
            for j, code, val in cand:
                if j in free and _scale_match(S[:, k], val, rtol) is not None:
                    mistakes[k] = (j, code)
                    free.remove(j)
                    left.remove(k)
                    break
    if left and free:  # sign flips and dropped terms of the remaining reference rows
        for k in list(left):
            for j in list(free):
                code = _term_match(target, "Phi", target.ref.Phi[j, 0], S[:, k], samples, rtol)
                if code:
                    mistakes[k] = (j, code)
                    free.remove(j)
                    left.remove(k)
                    break
    if left and free:  # equivalent formulations: zero where the mechanism is assembled, same constraint
        for k in list(left):
            j = _equivalent_row(target, A, k, free)
            if j is not None:
                ok[k] = (j, None)
                free.remove(j)
                left.remove(k)
    return {"ok": ok, "mistake": mistakes, "unmatched": left, "free": free}


def _phi_variants(target, samples, skey, rows):
    """(reference row, code, values (N, 1)) of the structural variants of the constraints owning ``rows``."""
    out = []
    owners = []
    for j in rows:
        c = target.owner(j)
        if c not in owners:
            owners.append(c)
    for c in owners:
        base = target.rows.index(c.rows.start)
        for v, (code, M) in enumerate(_structural(target, c)):
            vals = target.evaluate(("struct", c.name, v, "Phi"), M, samples, skey)
            ref = target.reference("Phi", skey, samples)
            for r in range(M.shape[0]):
                j = base + r
                if j in rows and _scale_match(vals[:, r], ref[:, j], RTOL) is None:
                    out.append((j, code, vals[:, r]))
    return out


def _structural(target, c):
    key = ("structural", c.name)
    if key not in target.store:
        target.store[key] = V.structural(target.mech, c)
    return target.store[key]


def _term_match(target, quantity, expr, values, samples, rtol, scale=True):
    """"sign_flip" or "missing_term" when ``values`` match a term variant of ``expr``."""
    variants = V.term_variants(expr)
    if not variants:
        return None
    from ._target import Compiled

    M = sp.Matrix([e for _, e in variants])
    vals = Compiled(M, target.args)(samples.columns(), samples.N)
    for i, (code, _) in enumerate(variants):
        if scale:
            if _scale_match(values, vals[:, i], rtol) is not None:
                return code
        elif _same(values, vals[:, i], rtol):
            return code
    return None


def _equivalent_row(target, A, k, free):
    """A student's row that is not the book's form but defines the same constraint: it vanishes at every
    assembled configuration, and its gradient there lies in the span of one constraint's gradients."""
    if A.expr is None:
        return None
    asm = target.samples("assembled")
    expr = A.expr[k, 0]

    def grad():
        return sp.Matrix([expr]).jacobian(target.mech.q)

    G = run_limited(grad, 1.0, required=False)
    if G is None:
        return None
    from ._target import Compiled

    vals = Compiled(sp.Matrix([expr]), target.args)(asm.columns(), asm.N)[:, 0, 0]
    gv = Compiled(G, target.args)(asm.columns(), asm.N)[:, 0, :]
    if not (np.all(np.isfinite(vals)) and np.all(np.isfinite(gv))):
        return None
    gscale = np.max(np.abs(gv))
    if gscale == 0 or np.max(np.abs(vals)) > 1e-7 * max(1.0, gscale):
        return None
    J = target.reference("Phi_q", "assembled")
    for c in {target.owner(j) for j in free}:
        rows = [target.rows.index(r) for r in range(c.rows.start, c.rows.stop)]
        ok = True
        for b in range(asm.N):
            Jc = J[b][rows]
            coef, *_ = np.linalg.lstsq(Jc.T, gv[b], rcond=None)
            if np.max(np.abs(Jc.T @ coef - gv[b])) > 1e-6 * gscale:
                ok = False
                break
        if ok:
            for j in free:
                if target.owner(j) is c:
                    return j
    return None


def _phi_result(target, match, ms, order, A, symbolic):
    rows, mistakes, messages = [], [], []
    by_ref = {}
    for k, (j, c) in match["ok"].items():
        by_ref[j] = ("ok", k, c)
    for k, (j, code) in match["mistake"].items():
        by_ref[j] = ("mistake", k, code)
    paired = _pair_wrong_rows(target, A, match["unmatched"], match["free"])
    credit = 0.0
    moved = False
    for j in range(target.m):
        label = f"{target.label(j)}"
        owner = target.owner_label(j)
        if j in by_ref and by_ref[j][0] == "ok":
            _, k, c = by_ref[j]
            if c is None:
                msg = tr("row_equivalent", ref=label)
            elif k != j and order == "book":
                msg = tr("row_ok_moved", ref=label)
            elif c != 1.0:
                msg = tr("row_ok_scaled", c=c)
            else:
                msg = tr("row_ok")
            if order == "book" and k != j:
                moved = True
                rows.append(RowResult(label, "wrong", msg, "row_order", score=0.5))
                credit += 0.5
            else:
                rows.append(RowResult(label, "ok", msg if msg != tr("row_ok") else "", score=1.0))
                credit += 1.0
        elif j in by_ref:
            _, k, code = by_ref[j]
            rows.append(RowResult(label, "wrong", _mistake_msg(code), code))
            mistakes.append(code)
            messages.append(f"{label} — {owner}: {_mistake_msg(code)}")
        elif j in paired:
            rows.append(RowResult(label, "wrong", tr("row_wrong", ref=label, owner=owner), "wrong_value"))
            mistakes.append("wrong_value")
            messages.append(f"{label}: " + tr("row_wrong", ref=label, owner=owner))
        else:
            code = "missing_normalization" if target.owner(j).type_name == "normalization" else "missing_row"
            rows.append(RowResult(label, "missing", tr("row_missing", ref=label, owner=owner), code))
            mistakes.append(code)
            messages.append(f"{label}: " + tr("row_missing", ref=label, owner=owner))
    extra = ms - target.m
    if extra > 0:
        for k in range(extra):
            rows.append(RowResult(f"+{k + 1}", "extra", tr("row_extra"), "extra_row"))
        mistakes.append("extra_row")
        messages.append(tr("row_extra") + f" (×{extra})")
    if moved:
        mistakes.append("row_order")
        messages.insert(0, tr("row_order_msg"))
    total = target.m + max(0, extra)
    score = credit / total if total else 0.0
    passed = score >= 1.0 - 1e-12 and not mistakes
    n_ok = sum(1 for r in rows if r.status == "ok")
    head = (tr("all_correct", what="Φ", n=target.m) if passed
            else tr("summary", what="Φ", ok=n_ok, n=target.m, score=score))
    mistakes = _unique(mistakes)
    return CheckResult(passed, round(score, 6), [head] + messages + _hints(mistakes), mistakes, tuple(rows), "Φ")


def _symbolic_zero(pairs, seconds=None):
    """True when sympy proves every a − b == 0 within the budget; False when it cannot (time-out, or a
    difference it does not reduce to 0)."""
    seconds = SYMBOLIC_SECONDS if seconds is None else seconds

    def work():
        return all(sp.simplify(sp.expand_trig(a - b)) == 0 for a, b in pairs)

    return bool(run_limited(work, seconds, on_timeout=lambda: False, required=False))


def _with_symbolic_note(result, pairs):
    from dataclasses import replace

    if not pairs:
        return result
    note = tr("symbolic_confirmed") if _symbolic_zero(pairs) else tr("symbolic_unconfirmed", n=len(pairs))
    return replace(result, messages=list(result.messages) + [note])


def _pair_wrong_rows(target, A, unmatched, free):
    """Which reference rows the unmatched answer rows were meant to be: by the coordinates they use (for
    symbolic answers), else in order. Returns {reference row: answer row}; unpaired reference rows are
    missing, unpaired answer rows are extra."""
    if not unmatched or not free:
        return {}
    if A.expr is None:
        return dict(zip(free, unmatched))
    cand = []
    for k in unmatched:
        sk = A.expr[k, 0].free_symbols
        for j in free:
            sj = target.ref.Phi[j, 0].free_symbols
            overlap = len(sk & sj) / max(1, len(sk | sj))
            cand.append((-overlap, abs(k - j), j, k))
    out, used = {}, set()
    for _, _, j, k in sorted(cand):
        if j not in out and k not in used:
            out[j] = k
            used.add(k)
    return out


def _unique(codes):
    out = []
    for c in codes:
        if c and c not in out:
            out.append(c)
    return out


# ================================================================================================ Φ_q, ν, γ
def check_jacobian(answer, mechanism, *, phi=None, order=None, rtol=None, at=None, symbolic=False):
    """Check a hand-built Jacobian Φ_q.

    Parameters
    ----------
    answer : sympy Matrix, nested list of expressions or strings, callable ``f(q, t)``, or numbers
        m × n: one row per equation of Φ, one column per coordinate. For a single constraint the columns may
        be the coordinates of its bodies (x_i, y_i, φ_i, x_j, y_j, φ_j) or all n coordinates.
    mechanism : Mechanism or Constraint
    phi : optional
        The student's own Φ (any form :func:`check_phi` accepts). Rows of the answer are then matched to the
        student's rows, and graded against ∂Φ/∂q of the student's Φ (error carried forward) as well as
        against the book.
    order : {"book", "any"}, optional
        Without ``phi``: "book" (default) expects the book's rows in the book's order; "any" accepts rows in
        any order, each multiplied by a nonzero constant (as the corresponding row of Φ may have been).
    rtol, at, symbolic
        As for :func:`check_phi`.

    Returns
    -------
    CheckResult
        Per row, the status of every entry (``RowResult.entries``).
    """
    return _check_derived("Phi_q", answer, mechanism, phi, order, rtol, at, symbolic)


def check_nu(answer, mechanism, *, phi=None, order=None, rtol=None, at=None, symbolic=False):
    """Check the right-hand side ν = −Φ_t of the velocity equations Φ_q q̇ = ν.

    Parameters are those of :func:`check_jacobian`; the answer is a vector of m entries (``f(q, t)`` for a
    callable).
    """
    return _check_derived("nu", answer, mechanism, phi, order, rtol, at, symbolic)


def check_gamma(answer, mechanism, *, phi=None, order=None, rtol=None, at=None, symbolic=False):
    """Check the right-hand side γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt of the acceleration equations.

    Parameters are those of :func:`check_jacobian`; the answer is a vector of m entries in q, q̇ (dx1, dphi2
    …) and t (``f(q, qd, t)`` for a callable).
    """
    return _check_derived("gamma", answer, mechanism, phi, order, rtol, at, symbolic)


class _Expected:
    """What each answer row is graded against: own[k] (from the student's Φ) and/or true[k] (the book's
    row j scaled by c)."""

    def __init__(self):
        self.own = None  # sympy Derivation of the student's Φ
        self.true = {}  # k -> (j, c)
        self.count = None  # number of rows expected
        self.note = None


def _check_derived(quantity, answer, mechanism, phi, order, rtol, at, symbolic):
    qn = _QNAME[quantity]
    try:
        target = target_for(mechanism)
    except TypeError as exc:
        return failed(qn, str(exc), "malformed")
    order = order or "book"
    if order not in ("any", "book"):
        return failed(qn, f"`order` must be 'any' or 'book', got {order!r}", "malformed")
    m = target.m
    width = len(target.cols) if quantity == "Phi_q" else 1
    prep = _prepare(answer, target, quantity, (m, width), at)
    if isinstance(prep, CheckResult):
        return prep
    A, samples, skey, default_rtol = prep
    rtol = default_rtol if rtol is None else rtol
    S = _values(A, samples, quantity, target)
    if isinstance(S, CheckResult):
        return S
    R = _reference(target, quantity, samples, skey)
    cols = list(range(R.shape[2]))
    mistakes, messages = [], []
    transposed_penalty = False
    # ------------------------------------------------------------------ shape
    if quantity == "Phi_q":
        full, sub = target.mech.n, len(target.cols)
        w = S.shape[2]
        if w == sub:
            cols = _best_columns(target, S, R, rtol)
        elif w == full:
            cols = list(range(full))
        elif S.shape[1] in (sub, full) and w != S.shape[1]:
            mistakes.append("transposed")
            expected = f"({m}, {sub})"
            messages.append(tr("transposed", expected=expected, got=f"({S.shape[1]}, {w})"))
            S = np.swapaxes(S, 1, 2)
            cols = _best_columns(target, S, R, rtol) if S.shape[2] == sub else list(range(full))
            transposed_penalty = True
        else:
            return failed(qn, tr("wrong_shape", expected=f"({m}, {sub})", got=S.shape[1:]), "wrong_shape")
        R = R[:, :, cols]
    elif S.shape[2] != 1:
        if S.shape[1] == 1 and S.shape[2] > 1:
            S = np.swapaxes(S, 1, 2)
        else:
            return failed(qn, tr("wrong_shape", expected=f"({m},)", got=S.shape[1:]), "wrong_shape")
    bad = _finite_or_fail(S, quantity, target)
    if bad is not None:
        return bad
    # ------------------------------------------------------------------ what each row is graded against
    exp = _Expected()
    if phi is not None:
        _from_student_phi(exp, phi, target, quantity, rtol, messages)
    if exp.count is None:
        if order == "any":
            exp.true = _assign(_all_pairs(S, R, rtol))
            free = [j for j in range(m) if j not in {j for j, _ in exp.true.values()}]
            for k in range(S.shape[1]):  # rows matching nothing: diagnosed against the rows left, in order
                if k not in exp.true and free:
                    exp.true[k] = (free.pop(0), 1.0)
        else:
            exp.true = {k: (k, 1.0) for k in range(min(S.shape[1], m))}
        exp.count = m
    ms = S.shape[1]
    own_vals = None
    if exp.own is not None:
        own_vals = _own_values(exp.own, quantity, target, samples, cols)
    # book order with a different number of rows: align monotonically to find missing / extra rows
    if phi is None and order == "book" and ms != m:
        exp.true = _align(S, R, rtol)
    rows, credit = [], 0.0
    own_only = 0
    sym_pairs = []
    used_ref = set()
    for k in range(ms):
        label_k = _answer_label(target, exp, k)
        own_row = None if own_vals is None or k >= own_vals.shape[1] else own_vals[:, k]
        tj = exp.true.get(k)
        true_row = None if tj is None else tj[1] * R[:, tj[0]]
        if tj is not None:
            used_ref.add(tj[0])
        ok_own = own_row is not None and _same(S[:, k], own_row, rtol)
        ok_true = true_row is not None and _same(S[:, k], true_row, rtol)
        if ok_own or ok_true:
            if exp.own is not None:
                msg = tr("consistent_correct") if ok_own and ok_true else (
                    tr("consistent_not_correct") if ok_own else tr("correct_not_consistent"))
            else:
                msg = ""
            rows.append(RowResult(label_k, "ok", msg, entries=_ok_entries(quantity, len(cols)), score=1.0))
            credit += 1.0
            if symbolic and A.expr is not None:
                ref_expr = _expected_matrix_row(exp, quantity, target, k, tj, ok_own, cols)
                if ref_expr is not None:
                    sym_pairs += list(zip(A.expr[k, :], ref_expr))
            if exp.own is not None and not (ok_own and ok_true):
                own_only += ok_own
                messages.append(f"{label_k}: {msg}")
            continue
        expected_row = own_row if own_row is not None else true_row
        if expected_row is None:
            rows.append(RowResult(label_k, "extra", tr("row_extra"), "extra_row"))
            mistakes.append("extra_row")
            continue
        code, entries, score = _diagnose_row(quantity, target, exp, k, tj, S[:, k], expected_row, samples,
                                             skey, cols, rtol)
        mistakes.append(code)
        text = _mistake_msg(code)
        if entries and quantity == "Phi_q" and code in ("wrong_value", "sign_flip"):
            bad_cols = [_book(target.names[cols[i]]) for i, e in enumerate(entries) if e != "ok"]
            text += "; " + tr("entries_wrong", entries=", ".join(f"∂/∂{n}" for n in bad_cols))
        owner = _owner_text(target, tj)
        rows.append(RowResult(label_k, "wrong", text, code, entries, score))
        messages.append(f"{label_k} — {owner}{text}")
        credit += score
    missing = [j for j in range(m) if j not in used_ref] if phi is None else []
    if exp.count is not None and phi is not None and ms < exp.count:
        missing = list(range(ms, exp.count))
    for j in missing:
        label = target.label(j) if j < m else f"row {j + 1}"
        owner = target.owner_label(j) if j < m else ""
        code = "missing_normalization" if j < m and target.owner(j).type_name == "normalization" else "missing_row"
        rows.append(RowResult(label, "missing", tr("row_missing", ref=label, owner=owner), code))
        mistakes.append(code)
        messages.append(f"{label}: " + tr("row_missing", ref=label, owner=owner))
    # a square matrix given transposed: recognized when the transpose is right
    if quantity == "Phi_q" and "transposed" not in mistakes and ms == S.shape[2] and credit < ms:
        St = np.swapaxes(S, 1, 2)
        if St.shape == R.shape and _same(St, R, rtol):
            rows = [RowResult(r.label, "wrong", tr("transposed_right"), "transposed") for r in rows]
            mistakes, credit = ["transposed"], 0.5 * ms
            messages = [tr("transposed", expected=str(R.shape[1:]), got=str(S.shape[1:])), tr("transposed_right")]
    if phi is None and order == "book" and credit < ms and "transposed" not in mistakes and ms == m:
        # right rows in another order or scale: the student's Φ was ordered differently
        perm = _assign(_all_pairs(S, R, rtol))
        if len(perm) == m and any(j != k for k, (j, _) in perm.items()):
            rows = [RowResult(_answer_label(target, exp, k), "wrong", tr("row_order_hint"), "row_order")
                    for k in range(ms)]
            mistakes, credit = ["row_order"], 0.5 * ms
            messages = [tr("row_order_hint")]
    total = max(exp.count, ms)
    score = credit / total if total else 0.0
    if transposed_penalty:
        score *= 0.5
    mistakes = _unique(mistakes)
    passed = not mistakes and score >= 1.0 - 1e-12
    n_ok = sum(1 for r in rows if r.status == "ok")
    if passed and own_only:
        head = tr("all_consistent", what=qn, n=total, k=own_only)
    elif passed:
        head = tr("all_correct", what=qn, n=total)
    else:
        head = tr("summary", what=qn, ok=n_ok, n=total, score=score)
    colnames = tuple(_book(target.names[c]) for c in cols) if quantity == "Phi_q" else ()
    if symbolic and sym_pairs:
        messages.append(tr("symbolic_confirmed") if _symbolic_zero(sym_pairs)
                        else tr("symbolic_unconfirmed", n=len(sym_pairs)))
    return CheckResult(passed, round(score, 6), [head] + messages + _hints(mistakes), mistakes, tuple(rows), qn,
                       colnames)


def _best_columns(target, S, R, rtol):
    """Columns of a single constraint's Φ_q: its bodies in role order (i, j, k — the book's tables) or in
    the mechanism's order; whichever the answer follows best."""
    roles = list(target.cols)
    ordered = sorted(roles)
    if ordered == roles:
        return roles

    def fit(cols):
        Rc = R[:, :, cols]
        return sum(int(np.sum(_close(S[:, k], Rc[:, k], rtol))) for k in range(min(S.shape[1], Rc.shape[1])))

    return ordered if fit(ordered) > fit(roles) else roles


def _expected_matrix_row(exp, quantity, target, k, tj, ok_own, cols):
    """The sympy row an answer row was judged equal to (own derivation or the book's, scaled)."""
    if ok_own and exp.own is not None:
        M = getattr(exp.own, quantity)
    elif tj is not None and tj[0] < target.m:
        M = tj[1] * getattr(target.ref, quantity)
        k = tj[0]
    else:
        return None
    row = M[k, :]
    return [row[c] for c in cols] if quantity == "Phi_q" else list(row)


def _book(name):
    """Coordinate names in the book's notation: phi2 → φ2."""
    return name.replace("phi", "φ")


def _ok_entries(quantity, width):
    return ("ok",) * width if quantity == "Phi_q" else ()


def _owner_text(target, tj):
    if tj is None or tj[0] >= target.m:
        return ""
    return f"{target.owner_label(tj[0])}: "



def _answer_label(target, exp, k):
    tj = exp.true.get(k)
    if tj is not None and tj[0] < target.m:
        return target.label(tj[0])
    return tr("your_row", k=k + 1)


def _align(S, R, rtol):
    """Book order with rows missing or extra: match answer rows to reference rows keeping their order."""
    out, j = {}, 0
    ms, m = S.shape[1], R.shape[1]
    for k in range(ms):
        found = None
        for jj in range(j, m):
            if _same(S[:, k], R[:, jj], rtol):
                found = jj
                break
        if found is not None:
            out[k] = (found, 1.0)
            j = found + 1
        elif j < m and (ms - k) >= (m - j):
            out[k] = (j, 1.0)
            j += 1
    return out


def _from_student_phi(exp, phi, target, quantity, rtol, messages):
    """Read the student's Φ: derive from it (error carried forward) and match its rows to the book's."""
    gen = target.samples("generic")
    P = read(phi, target, "Phi", (target.m, 1))
    if isinstance(P, Malformed):
        messages.append(tr("phi_unusable", reason=P.message))
        return
    SP = P(gen)
    if isinstance(SP, Malformed) or not np.all(np.isfinite(np.asarray(SP, float))):
        messages.append(tr("phi_unusable", reason=getattr(SP, "message", "NaN")))
        return
    SP = np.asarray(SP, float)
    if SP.ndim == 2:
        SP = SP[:, :, None]
    if SP.shape[2] != 1:
        messages.append(tr("phi_unusable", reason=tr("wrong_shape", expected=f"({target.m},)", got=SP.shape[1:])))
        return
    R = target.reference("Phi", "generic")
    exp.true = _assign(_all_pairs(SP, R, RTOL))
    exp.count = SP.shape[1]
    if P.expr is not None:
        mech = target.mech
        own = run_limited(lambda: derive(P.expr, mech.q, mech.qd, mech.t), 3.0, required=False)
        if own is None:
            own = run_limited(lambda: derive(P.expr, mech.q, mech.qd, mech.t), 3.0, required=True) \
                if not _can_limit() else None
        exp.own = own


def _can_limit():
    from ._timelimit import can_limit

    return can_limit()


def _own_values(own, quantity, target, samples, cols):
    from ._target import Compiled

    M = getattr(own, quantity)
    vals = Compiled(M, target.args)(samples.columns(), samples.N)
    if quantity == "Phi_q":
        vals = vals[:, :, cols]
    return vals


def _diagnose_row(quantity, target, exp, k, tj, s, e, samples, skey, cols, rtol):
    """Name the mistake in one wrong row. Returns (code, entries, score)."""
    width = s.shape[-1]
    if quantity != "Phi_q" and exp.own is None and _same(s, -e, rtol) and np.max(np.abs(e)) > ATOL:
        return ("gamma_sign" if quantity == "gamma" else "nu_sign"), (), 0.0
    cands = []  # (code, values (N, w))
    if exp.own is not None:
        cands += _own_variants(exp, quantity, target, samples, cols, k)
    elif tj is not None and tj[0] < target.m:
        j, c = tj
        for code, vals in _ref_variants(target, quantity, samples, skey, cols, j):
            cands.append((code, c * vals))
    for code, vals in cands:
        if not _same(vals, e, rtol) and _same(s, vals, rtol):
            entries = _entries_like(quantity, width, s, e, rtol, code)
            return code, entries, _entry_score(s, e, entries)
    if quantity != "Phi_q":
        if _same(s, -e, rtol) and np.max(np.abs(e)) > ATOL:
            return ("gamma_sign" if quantity == "gamma" else "nu_sign" if quantity == "nu" else "sign_flip"), (), 0.0
        expr = _expected_expr(exp, quantity, target, k, tj)
        if expr is not None:
            code = _term_match(target, quantity, expr, s, samples, rtol, scale=False)
            if code:
                return code, (), 0.0
        return "wrong_value", (), 0.0
    # Φ_q: entry by entry
    entries = []
    codes = []
    for i in range(width):
        si, ei = s[:, i], e[:, i]
        if _same(si, ei, rtol, ATOL + rtol * np.max(np.abs(e))):
            entries.append("ok")
            continue
        code = "wrong_value"
        if np.max(np.abs(ei)) > ATOL and _same(si, -ei, rtol):
            code = "sign_flip"
        else:
            for ccode, vals in cands:
                if _same(si, vals[:, i], rtol) and not _same(vals[:, i], ei, rtol):
                    code = ccode
                    break
        entries.append(code)
        codes.append(code)
    named = [c for c in codes if c != "wrong_value"]
    return (named[0] if named else "wrong_value"), tuple(entries), _entry_score(s, e, entries)


def _entry_score(s, e, entries):
    """Partial credit of a Φ_q row: the fraction of its nonzero entries (in the answer or the reference)
    that are right."""
    if not entries:
        return 0.0
    relevant = [i for i in range(len(entries))
                if np.max(np.abs(e[:, i])) > ATOL or np.max(np.abs(s[:, i])) > ATOL]
    good = sum(1 for i in relevant if entries[i] == "ok")
    return good / len(relevant) if relevant else 0.0


def _entries_like(quantity, width, s, e, rtol, code):
    if quantity != "Phi_q":
        return ()
    return tuple("ok" if _same(s[:, i], e[:, i], rtol) else code for i in range(width))


def _expected_expr(exp, quantity, target, k, tj):
    if exp.own is not None:
        M = getattr(exp.own, quantity)
        return M[k, 0] if k < M.shape[0] else None
    if tj is None or tj[0] >= target.m:
        return None
    j, c = tj
    return c * getattr(target.ref, quantity)[j, 0]


def _own_variants(exp, quantity, target, samples, cols, k):
    from ._target import Compiled

    key = ("own-variants", quantity)
    if getattr(exp, "_cache", None) is None:
        exp._cache = {}
    if key not in exp._cache:
        mech = target.mech
        got = run_limited(lambda: V.derived(exp.own.Phi, mech.q, mech.qd, mech.t, quantity), 3.0,
                          on_timeout=lambda: [], required=False) or []
        vals = []
        for code, M in got:
            v = Compiled(M, target.args)(samples.columns(), samples.N)
            vals.append((code, v[:, :, cols] if quantity == "Phi_q" else v))
        exp._cache[key] = vals
    return [(code, v[:, k]) for code, v in exp._cache[key] if k < v.shape[1]]


def _ref_variants(target, quantity, samples, skey, cols, j):
    """Variants of reference row j: derivation mistakes, then structural mistakes carried through."""
    key = ("derived", quantity)
    if key not in target.store:
        ref = target.ref
        target.store[key] = V.derived(ref.Phi, ref.q, ref.qd, ref.t, quantity)
    out = []
    for v, (code, M) in enumerate(target.store[key]):
        vals = target.evaluate(("derived", quantity, v), M, samples, skey)
        out.append((code, vals[:, j][:, cols] if quantity == "Phi_q" else vals[:, j]))
    c = target.owner(j)
    base = target.rows.index(c.rows.start)
    for v, (code, M) in enumerate(_structural(target, c)):
        dkey = ("struct-derived", c.name, v)
        if dkey not in target.store:
            mech = target.mech
            target.store[dkey] = derive(M, mech.q, mech.qd, mech.t)
        D = target.store[dkey]
        vals = target.evaluate(("struct", c.name, v, quantity), getattr(D, quantity), samples, skey)
        r = j - base
        out.append((code, vals[:, r][:, cols] if quantity == "Phi_q" else vals[:, r]))
    return out
