"""The one equivalence rule (fourth stage of a check): which rows of an answer stand for which rows of
kinbook's reference, which are dependent on others, which reference rows are missing.

The rule, for all four checkers (issue #14 item 2, issue #13 item 4):

* An answer **row is right** when it is a reference row multiplied by a nonzero constant — the same
  constant at every sample. For Φ any constant (Φ is a set of equations: −Φ_4 or 2Φ_4 is the same
  constraint). For Φ_q, ν and γ the constant is the one of the row of Φ they come from: given by the
  student's own Φ (``phi=``) when there is one; otherwise 1 for ν and γ (a negated ν or γ *is* the
  classic sign mistake), while a Φ_q row, whose entries show their factor, may carry any constant.
* A **Φ row** that is not such a multiple is still right when it is an *equivalent formulation*: it vanishes
  wherever the mechanism is assembled (the assembled samples) and its gradient there lies in the span of the
  reference rows' gradients (and, in space, of the bodies' normalization rows) — the same zero set, locally,
  as √(Δx² + Δy²) − l for (Δx² + Δy²) − l², or the book's cross-product rows s̃_i s_j of a parallel
  constraint for kinbook's two h-rows.
* The **answer set** must have the reference's rank on the manifold: every reference row must be a multiple
  of an answer row, or its gradient must lie in the span of the accepted answer rows' gradients. A row that
  adds nothing is **dependent** and named ("row k depends on row j"): a repeated row or a multiple of one
  (Φ_4 twice, 2·Φ_4), a row that vanishes with its gradient on the manifold (Φ_4², Φ_4·Φ_5), a constant
  combination of other rows. A row whose dependence on others changes from configuration to configuration
  (the book's third cross-product row) is not: it is part of a regular formulation with the right rank.

Everything here works on arrays (samples × rows × columns); nothing reads answers or knows constraint types.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

__all__ = ["RTOL", "RTOL_NUMBERS", "Row", "Matching", "scale_of", "scale_matrix", "match_phi", "match_rows",
           "nice"]

RTOL = 1e-6
"""Relative tolerance of every comparison of symbolic answers and functions."""
RTOL_NUMBERS = 2e-3
"""Relative tolerance for numbers typed from a calculator (the book prints 4-6 significant digits)."""
_NICE = (1.0, -1.0, 2.0, -2.0, 0.5, -0.5, 3.0, -3.0)


def zero_tol(rtol):
    """Relative size below which a row (or a gradient's residual) is zero where a constraint holds. The samples
    are solved to rounding, so a right row is there ~1e-15 of its size: ``rtol``, and never above 1e-6 whatever
    ``rtol`` the caller chose — a length off by 1 in 10⁴ (1.4999 for 1.5) is not a zero (it was 1e3·rtol, so
    1.49 for 1.5 "held" where the mechanism is assembled and was named a masked row or a vanishing factor)."""
    return min(float(rtol), 1e-6)


def nice(c):
    """``c`` rounded to a simple factor when it is one to rounding (1, −1, 2, ½ …)."""
    for r in _NICE:
        if abs(c - r) < 1e-9 * max(1.0, abs(c)):
            return r
    return float(c)


def scale_of(a):
    """Magnitude of a row over the samples (max |value|)."""
    return float(np.max(np.abs(a))) if a.size else 0.0


def _wrap(x, period):
    return (x + period / 2) % period - period / 2


def same(a, b, rtol, period=None):
    """a ≈ b entry-wise over all samples, relative to the larger magnitude of the two."""
    d = a - b
    if period:
        d = _wrap(d, period)
    scale = max(scale_of(a), scale_of(b))
    return bool(np.all(np.abs(d) <= rtol * scale + 1e-12 * max(scale, 1.0) * rtol))


def scale_match(a, b, rtol, free=True, period=None, atol=0.0, zeros=False):
    """The constant c ≠ 0 with a ≈ c·b at every sample (arrays of shape (N,) or (N, w)), or None.

    ``free``: any constant; otherwise only c = 1. A ``period`` (a wrapped angle row) allows c = ±1 only,
    compared modulo the period. ``atol``: differences this small are zero. ``zeros``: a reference row that is
    zero at every sample is matched (c = 1) by an answer row that is zero too.
    """
    if period:
        for c in ((1.0, -1.0) if free else (1.0,)):
            if same(a, c * b, rtol, period):
                return c
        return None
    sb = scale_of(b)
    if sb <= atol:
        return 1.0 if zeros and scale_of(a) <= max(atol, 1e-12) else None
    if not free:
        d = np.max(np.abs(a - b))
        return 1.0 if d <= rtol * max(scale_of(a), sb) + atol else None
    bb = float(np.sum(b * b))
    c = float(np.sum(a * b)) / bb
    if c == 0 or not np.isfinite(c):
        return None
    if np.max(np.abs(a - c * b)) <= rtol * max(scale_of(a), abs(c) * sb) + atol:
        return nice(c)
    return None


def scale_matrix(S, R, rtol, free=True, wrap=None, atol=0.0, zeros=False):
    """Constants C[k, j] with S[:, k] ≈ C·R[:, j] (NaN where there is none). S (N, ms, …), R (N, m, …).

    Vectorized over all pairs (the rule of :func:`scale_match`); wrapped rows are compared one by one."""
    wrap = wrap or {}
    ms, m = S.shape[1], R.shape[1]
    A = np.moveaxis(S, 1, 0).reshape(ms, -1)
    B = np.moveaxis(R, 1, 0).reshape(m, -1)
    sa, sb = np.abs(A).max(axis=1), np.abs(B).max(axis=1)
    C = np.full((ms, m), np.nan)
    with np.errstate(all="ignore"):
        if free:
            c = (A @ B.T) / np.sum(B * B, axis=1)[None, :]
        else:
            c = np.ones((ms, m))
        res = np.abs(A[:, None, :] - c[:, :, None] * B[None, :, :]).max(axis=2)
        tol = rtol * np.maximum(sa[:, None], np.abs(c) * sb[None, :]) + atol
        if not free:
            tol = rtol * np.maximum(sa[:, None], sb[None, :]) + atol
    ok = (res <= tol) & (sb[None, :] > atol) & np.isfinite(c) & (c != 0)
    C[ok] = c[ok]
    if zeros:
        both = (sb[None, :] <= atol) & (sa[:, None] <= max(atol, 1e-12))
        C[both] = 1.0
    for j, period in wrap.items():
        for k in range(ms):
            cc = scale_match(S[:, k], R[:, j], rtol, free, period, atol, zeros)
            C[k, j] = np.nan if cc is None else cc
    if free:
        for k, j in zip(*np.nonzero(np.isfinite(C))):
            C[k, j] = nice(C[k, j])
    return C


def atol_of(R, rtol):
    """The absolute tolerance of a quantity: rtol × its largest entry (at least rounding level)."""
    return rtol * max(scale_of(R), 1e-9)


@dataclass
class Row:
    """The verdict on one answer row (or, with ``k`` None, on a reference row the answer lacks).

    Attributes
    ----------
    k : int or None
        Position of the row in the answer (0-based).
    ref : int or None
        Position of the reference row it stands for (0-based, among the graded rows).
    status : {"ok", "wrong", "dependent", "extra", "missing", "moved"}
    factor : float or None
        The constant c of answer = c·reference.
    how : str
        "multiple", "equivalent" (a different formulation), "own" (follows from the student's Φ), "both".
    depends_on : list
        For "dependent": the answer rows (ints) or reference rows ("Φ_j" labels built later) it depends on,
        and how ("repeat", "function", "combination").
    covers : list of int
        Reference rows an equivalent row stands for.
    code, detail, erratum, entries, score : filled by the diagnosis and the report.
    """

    k: int | None
    ref: int | None
    status: str
    factor: float | None = None
    how: str = "multiple"
    depends_on: list = field(default_factory=list)
    dependence: str = ""
    covers: list = field(default_factory=list)
    code: str | None = None
    detail: tuple | None = None
    erratum: str | None = None
    entries: tuple = ()
    score: float = 0.0
    owner: int | None = None
    masked: list = field(default_factory=list)
    book: bool = False
    where: tuple | None = None


@dataclass
class Matching:
    rows: list
    missing: list  # reference rows (0-based) nobody stands for
    searched: dict = field(default_factory=dict)  # constraint index -> zeros found by the search (vanishing)

    def answer_rows(self, status=None):
        return [r for r in self.rows if r.k is not None and (status is None or r.status == status)]


# ================================================================================================ Φ
def match_phi(data, rtol, order="any", wrap=None):
    """Match the rows of an answer Φ to the reference's, constraint by constraint.

    Parameters
    ----------
    data : :class:`~kinbook.grading.evaluate.PhiData`
        The answer and the reference at the generic samples (S_G, R_G), at the target's assembled samples
        (S_M, gR_M, F_M) and, per constraint, at that constraint's own assembled samples (``data.block(i)``).
    order : {"any", "book"}
    wrap : dict
        {reference row: period} of wrapped angle rows.

    Returns
    -------
    Matching
        Each row's ``owner`` is the constraint (index of ``data.blocks``) it was judged as a row of; ``masked``
        the constraints that alone make a row true where the whole mechanism is assembled.
    """
    S_G, R_G = data.S_G, data.R_G
    wrap = wrap or {}
    ms, m = S_G.shape[1], R_G.shape[1]
    blocks = data.blocks or [list(range(m))]
    owner_of = {j: b for b, refs in enumerate(blocks) for j in refs}
    C = scale_matrix(S_G, R_G, rtol, True, wrap)
    _zero_rows(C, data, rtol)
    rows = [Row(k, None, "wrong") for k in range(ms)]
    taken = {}
    # 1. multiples of a reference row (at generic configurations: nothing else holds there): in book order the
    #    diagonal first, then the first free candidate
    prefer = [(k, k) for k in range(min(ms, m)) if not np.isnan(C[k, k])] if order == "book" else []
    for k, j in prefer:
        rows[k].ref, rows[k].status, rows[k].factor = j, "ok", C[k, j]
        taken[j] = k
    for k in range(ms):
        if rows[k].status == "ok":
            continue
        cands = [j for j in range(m) if not np.isnan(C[k, j])]
        free = [j for j in cands if j not in taken]
        if free:
            j = free[0]
            rows[k].ref, rows[k].status, rows[k].factor = j, "ok", C[k, j]
            taken[j] = k
        elif cands:  # a repeat, or a multiple, of a row already given
            j = cands[0]
            rows[k].status, rows[k].ref, rows[k].factor = "dependent", j, C[k, j]
            rows[k].depends_on, rows[k].dependence = [taken[j]], "repeat"
    for r in rows:
        if r.ref is not None:
            r.owner = owner_of[r.ref]
    # 2. the other rows: an equivalent formulation of one constraint, judged where that constraint alone holds
    rest = [r for r in rows if r.status == "wrong"]
    if rest:
        _equivalents(data, rest, blocks, owner_of, taken, rtol)
    # 3. constant combinations among the accepted rows
    accepted = [r for r in rows if r.status == "ok"]
    for r in accepted:
        if r.how != "equivalent":
            continue
        others = [o for o in accepted if o is not r and o.status == "ok" and (o.how == "multiple" or o.k < r.k)]
        related = [o for o in others if (o.ref in r.covers) or (set(o.covers) & set(r.covers))]
        if related and S_G.shape[0] > len(related) + 3:
            A = S_G[:, [o.k for o in related]]
            coef, *_ = np.linalg.lstsq(A, S_G[:, r.k], rcond=None)
            if np.max(np.abs(A @ coef - S_G[:, r.k])) <= rtol * max(scale_of(S_G[:, r.k]), 1e-300):
                r.status, r.dependence = "dependent", "combination"
                used = [(o.k, c) for o, c in zip(related, coef) if abs(c) > 1e-9]
                r.depends_on = [k for k, _ in used]
                if len(used) == 1:
                    r.dependence, r.factor = "repeat", nice(used[0][1])
    # 4. counting: a constraint has as many independent equations as reference rows; more rows are redundant
    for b, refs in enumerate(blocks):
        mine = [r for r in rows if r.status == "ok" and r.owner == b]
        if len(mine) > len(refs):
            keep = sorted(mine, key=lambda r: (r.how != "multiple", r.k))[: len(refs)]
            for r in mine:
                if r not in keep:
                    r.status, r.dependence = "dependent", "redundant"
                    r.depends_on = sorted(o.k for o in mine)
    # 5. coverage, per constraint: every reference row a multiple of an answer row, or in the span of the
    #    accepted rows' gradients where that constraint holds
    accepted = [r for r in rows if r.status == "ok"]
    covered = {r.ref for r in accepted if r.how == "multiple"}
    missing = []
    for b, refs in enumerate(blocks):
        lack = [j for j in refs if j not in covered]
        eq = [r.k for r in accepted if r.how == "equivalent" and r.owner == b]
        if lack and eq:
            lack = _still_missing(data.block(b), refs, lack, [r.ref for r in accepted if r.how == "multiple" and
                                                              r.owner == b], eq, rtol)
        missing += lack
    # 6. book order
    if order == "book":
        _mark_moved(rows, m)
    return Matching(rows, sorted(missing))


def _zero_rows(C, data, rtol):
    """Reference rows that are zero at every generic sample (a body's normalization pᵀp − 1: the samples' Euler
    parameters are unit): an answer row zero there too is a multiple of one when its gradient is that multiple
    of the reference row's gradient (2pᵀ)."""
    gR = getattr(data, "gR_G", None)
    if gR is None:
        return
    S_G, R_G = data.S_G, data.R_G
    zr = [j for j in range(R_G.shape[1]) if scale_of(R_G[:, j]) <= 1e-12 and scale_of(gR[:, j]) > 0]
    if not zr:
        return
    zs = [k for k in range(S_G.shape[1]) if scale_of(S_G[:, k]) <= 1e-12 and np.all(np.isnan(C[k]))]
    if not zs:
        return
    gS = data.grads("generic")
    for k in zs:
        for j in zr:
            c = scale_match(gS[:, k, :], gR[:, j, :], rtol)
            if c is not None:
                C[k, j] = c


def _equivalents(data, rest, blocks, owner_of, taken, rtol):
    """Rows that are no multiple of a reference row: right when, where one constraint alone holds (its own
    assembled samples), they vanish and their gradient lies in the span of that constraint's rows' gradients
    (and of the bodies' normalization rows). A row that is right only where the *whole* mechanism is assembled
    is "masked": wrong, and the constraints that make it true are named."""
    S_G = data.S_G
    gG = data.grads("generic")
    for r in rest:
        k = r.k
        g_gen = gG[:, k, :]
        gscale = float(np.max(np.linalg.norm(g_gen, axis=1)))
        magnitude = max(scale_of(S_G[:, k]), gscale)
        if magnitude == 0.0:
            continue  # identically zero: wrong
        if len(blocks) > 1 and data.on_manifold and not _whole(data, k, magnitude, gscale, rtol):
            continue  # not even true where the whole mechanism is assembled: wrong for every constraint
        support = np.max(np.abs(g_gen), axis=0) > 1e-9 * max(gscale, 1e-300)
        cols = data.block_cols or [np.ones_like(support)] * len(blocks)
        # the constraints whose bodies hold every coordinate the row moves, those with rows left first; only when
        # there is none, every constraint (a row may carry a factor of another body's coordinates that never
        # vanishes: right, if odd)
        cands = [b for b in range(len(blocks)) if not np.any(support & ~cols[b])] or list(range(len(blocks)))
        cands.sort(key=lambda b: (all(j in taken for j in blocks[b]), b))
        for b in cands:
            B = data.block(b)
            verdict = _judge(B, k, magnitude, gscale, S_G, data.R_G, rtol)
            if verdict is None:
                continue
            r.owner = b
            kind, covers = verdict
            if kind == "equivalent":
                r.status, r.how, r.covers = "ok", "equivalent", covers
                r.ref = next((j for j in covers if j not in taken), covers[0])
            else:
                r.status, r.dependence, r.depends_on = "dependent", kind, covers
            break
        if r.status == "wrong" and data.on_manifold and len(blocks) > 1:
            _masked(data, r, blocks, owner_of, cands, magnitude, gscale, rtol)


def _whole(data, k, magnitude, gscale, rtol):
    """Answer row k vanishes where the whole mechanism is assembled, with its gradient (if not zero) in the span
    of all the reference rows' there: the least a row of any one constraint must do (checked first: cheap)."""
    if scale_of(data.S_M[:, k]) > zero_tol(rtol) * magnitude:
        return False
    g = data.grads("assembled")[:, k, :]
    gnorm = np.linalg.norm(g, axis=1)
    if np.all(gnorm <= zero_tol(rtol) * max(gscale, float(np.max(gnorm)))):
        return True
    basis = np.concatenate([data.gR_M, data.F_M], axis=1) if data.F_M is not None and data.F_M.size else data.gR_M
    return _in_span(g, basis, rtol)[1]


def _judge(B, k, magnitude, gscale, S_G, R_G, rtol):
    """("equivalent", covered rows) / ("function" | "free", depends_on) / None for answer row k in block B."""
    if not B.on_manifold:
        return None
    S = B.S[:, k]
    if not np.all(np.isfinite(S)) or scale_of(S) > zero_tol(rtol) * magnitude:
        return None  # not zero where the constraint holds: wrong (diagnosed later)
    g = B.gS[:, k, :]
    gnorm = np.linalg.norm(g, axis=1)
    gscale = max(gscale, float(np.max(gnorm)))
    if np.all(gnorm <= zero_tol(rtol) * gscale):
        # a power or product of its rows, or else some other function of them (a sum of squares): its rows
        return "function", (_function_of(S_G[:, k], R_G[:, B.refs], rtol, B.refs)
                            or [("ref", j) for j in B.refs])
    basis = np.concatenate([B.gR, B.F], axis=1) if B.F is not None and B.F.size else B.gR
    alpha, inspan = _in_span(g, basis, rtol)
    if not inspan:
        return None
    contrib = np.abs(alpha[:, : len(B.refs)]) * np.linalg.norm(B.gR, axis=2)
    regular = _regular_samples(gnorm)  # where the gradient is at rounding level its coefficients are noise
    covers = [j for i, j in enumerate(B.refs) if np.any(contrib[regular, i] > 1e-3 * gnorm[regular])]
    if not covers:  # a combination of the always-true rows only (a normalization row, given again)
        return "free", []
    return "equivalent", covers


def _masked(data, r, blocks, owner_of, cands, magnitude, gscale, rtol):
    """A row true where the whole mechanism is assembled but not where its own constraint alone holds: which
    constraint it was meant for (``owner``) and which others make it true (``masked``)."""
    k = r.k
    if scale_of(data.S_M[:, k]) > zero_tol(rtol) * magnitude:
        return
    g = data.grads("assembled")[:, k, :]
    gnorm = np.linalg.norm(g, axis=1)
    if np.all(gnorm <= zero_tol(rtol) * max(gscale, float(np.max(gnorm)))):
        return
    basis = np.concatenate([data.gR_M, data.F_M], axis=1) if data.F_M is not None and data.F_M.size else data.gR_M
    alpha, inspan = _in_span(g, basis, rtol)
    if not inspan:
        return
    m = data.gR_M.shape[1]
    contrib = np.abs(alpha[:, :m]) * np.linalg.norm(data.gR_M, axis=2)
    weight = {}
    for j in range(m):
        w = float(np.max(contrib[:, j] / np.maximum(gnorm, 1e-300)))
        if w > 1e-3:
            weight[owner_of[j]] = weight.get(owner_of[j], 0.0) + w
    if not weight:
        return
    mine = [b for b in cands if b in weight] or sorted(weight, key=lambda b: -weight[b])
    r.owner = mine[0]
    r.masked = sorted((b for b in weight if b != r.owner), key=lambda b: -weight[b])
    if not r.masked and data.together is not None:  # the gradients do not tell: try each neighbour with it
        cols = data.block_cols
        near = [b for b in range(len(blocks)) if b != r.owner and np.any(cols[b] & cols[r.owner])]
        for b in near:
            S = data.together(sorted([r.owner, b]))
            if S is not None and np.all(np.isfinite(S[:, k])) and scale_of(S[:, k]) <= zero_tol(rtol) * magnitude:
                r.masked.append(b)
    r.masked = r.masked or [None]


def _still_missing(B, refs, lack, multiples, eq, rtol):
    """Reference rows of one constraint that the accepted rows do not span where it holds; as many as the rank
    lacks (one cross-product row for two h-rows lacks one)."""
    pos = {j: i for i, j in enumerate(refs)}
    # the samples where no accepted row's gradient is at rounding level (a factor of it vanishing there)
    keep = np.all([_regular_samples(np.linalg.norm(B.gS[:, k, :], axis=1)) for k in eq], axis=0)
    if keep.any() and not keep.all():
        B = replace(B, gR=B.gR[keep], gS=B.gS[keep], F=None if B.F is None else B.F[keep])
    parts = [B.gR[:, [pos[j] for j in multiples], :], B.gS[:, eq, :]]
    if B.F is not None and B.F.size:
        parts.append(B.F)
    basis = np.concatenate(parts, axis=1)
    still = [j for j in lack if not _in_span(B.gR[:, pos[j], :], basis, rtol)[1]]
    nf = 0 if B.F is None else B.F.shape[1]
    tol = 1e-8 * max(np.abs(basis[0]).max(), 1e-300)
    acc = np.linalg.matrix_rank(basis[0].T, tol=tol) - (np.linalg.matrix_rank(B.F[0].T) if nf else 0)
    full = np.linalg.matrix_rank(B.gR[0].T, tol=1e-8 * max(np.abs(B.gR[0]).max(), 1e-300))
    deficit = max(full - acc, 0)
    return still[len(still) - deficit:] if deficit < len(still) else still


def vanishing(matching, data, rtol):
    """Rows accepted as an equivalent formulation of a constraint whose zero set is larger than the constraint's:
    a factor f(q) that vanishes somewhere (cos φ2 · Φ_4, e0 · Φ_k). The zeros of the constraint's answer rows are
    searched (seeded Newton, the bodies free: :func:`kinbook.grading.sample.zeros`); where they vanish and a row
    they stand for does not, the row is wrong ("vanishing_factor", ``where`` = that configuration). The book's own
    rows of the constraint (two of the three cross-product rows of a parallel constraint) are its accepted form.

    Returns
    -------
    dict {constraint index: number of configurations found where its answer rows vanish} for the constraints
    searched (what the verdict may then claim).
    """
    searched = {}
    if data.search is None:
        return searched
    for b, refs in enumerate(data.blocks or []):
        mine = [r for r in matching.rows if r.status == "ok" and r.owner == b]
        eq = [r for r in mine if r.how == "equivalent"]
        if not eq:
            continue
        book = data.book(b) if data.book is not None else None
        if book is not None:
            for r in eq:
                if any(scale_match(data.S_G[:, r.k], book[:, i], rtol) is not None for i in range(book.shape[1])):
                    r.book = True
            eq = [r for r in eq if not r.book]
            if not eq:
                continue
        found = data.search(b, [r.k for r in mine])
        if found is None:
            searched[b] = 0
            continue
        Q, T, R = found
        searched[b] = len(Q)
        tol = 1e-6 * max(scale_of(data.R_G[:, refs]), 1.0)
        bad = np.flatnonzero(np.max(np.abs(R), axis=1) > tol)
        if not bad.size:
            continue
        i = int(bad[0])
        pos = {j: p for p, j in enumerate(refs)}
        culprits = [r for r in eq if any(abs(R[i, pos[j]]) > tol for j in r.covers)] or eq
        for r in culprits:
            r.status, r.code, r.how = "wrong", "vanishing_factor", "multiple"
            r.where = (Q[i], T[i], {j: float(R[i, pos[j]]) for j in r.covers})
            r.ref = next(j for j in r.covers if abs(R[i, pos[j]]) > tol) if any(
                abs(R[i, pos[j]]) > tol for j in r.covers) else r.covers[0]
    return searched


def _singular_combinations(matching, S, R, touched, rtol, F, book):
    """Equivalent Φ_q rows of a block: S_block = M(q) R_block (+ normalization rows); where det M changes sign
    between samples (or nearly vanishes) M(q) is singular somewhere — a factor f(q) that vanishes ("vanishing
    factor"), unless the rows are the Jacobian of the book's own formulation."""
    for block in touched:
        mine = [r for r in matching.rows if r.status == "ok" and (r.ref in block or set(r.covers) & set(block))]
        eq = [r for r in mine if r.how == "equivalent"]
        if not eq or len(mine) != len(block):
            continue
        B = book(block) if book is not None else None
        if B is not None:
            eq = [r for r in eq if not any(scale_match(S[:, r.k], B[:, i], rtol) is not None
                                           for i in range(B.shape[1]))]
            if not eq:
                continue
        basis = R[:, block, :] if F is None or not F.size else np.concatenate([R[:, block, :], F], axis=1)
        M = np.stack([_in_span(S[:, r.k, :], basis, rtol)[0][:, : len(block)] for r in mine], axis=1)
        det = np.linalg.det(M)
        size = np.prod(np.linalg.norm(M, axis=2), axis=1)
        rel = det / np.maximum(size, 1e-300)
        if np.all(rel > 1e-6) or np.all(rel < -1e-6):
            continue
        for r in eq:
            coef = M[:, mine.index(r), :]
            if np.ptp(coef / np.where(np.abs(coef[:1]) > 0, coef[:1], 1.0), axis=0).max() > zero_tol(rtol):
                a = int(np.argmax(np.abs(coef).max(axis=0)))
                r.status, r.code, r.how = "wrong", "vanishing_factor", "multiple"
                r.ref, r.factor = block[a], None
                r.where = ("ratio", float(coef[:, a].min()), float(coef[:, a].max()))


def _regular_samples(gn):
    """The samples where a gradient's norm ``gn`` (N,) is not at rounding level (≥ 10⁻³ of its largest)."""
    return gn >= 1e-3 * max(float(np.max(gn, initial=0.0)), 1e-300)


def _in_span(g, basis, rtol):
    """Per sample, the least-squares coefficients of g (N, n) on the rows of basis (N, b, n), and whether
    the residual is at rounding level at every sample."""
    if basis.shape[1] == 0:
        return np.zeros((g.shape[0], 0)), bool(np.all(np.linalg.norm(g, axis=1) == 0))
    alpha = np.einsum("nbi,ni->nb", np.linalg.pinv(np.swapaxes(basis, 1, 2), rcond=1e-10), g)
    res = np.linalg.norm(np.einsum("nbi,nb->ni", basis, alpha) - g, axis=1)
    gn = np.linalg.norm(g, axis=1)
    # a gradient at rounding level at one sample (a factor of the row vanishes there) is in every span
    floor = max(1e-3 * float(np.max(gn, initial=0.0)), 1e-300)
    ok = bool(np.all(res <= zero_tol(rtol) * np.maximum(gn, floor)))
    return alpha, ok


def _function_of(s, R, rtol, refs=None):
    """For a row that vanishes with its gradient on the manifold: the reference rows it is a power or a
    product of (["Φ_j"] as 0-based reference positions: ``refs[i]`` for column i of R), found at the generic
    samples."""
    m = R.shape[1]
    refs = list(range(m)) if refs is None else list(refs)
    for j in range(m):
        for p in (2, 3):
            if scale_match(s, R[:, j] ** p, rtol) is not None:
                return [("ref", refs[j])]
    for a in range(m):
        for b in range(a + 1, m):
            if scale_match(s, R[:, a] * R[:, b], rtol) is not None:
                return [("ref", refs[a]), ("ref", refs[b])]
    return []


def _mark_moved(rows, m):
    """order="book": a right row in another position than the book's is "moved" (half credit)."""
    accepted = [r for r in rows if r.status == "ok"]
    if len(accepted) == len(rows) == m and all(r.how == "multiple" for r in accepted):
        for r in accepted:
            if r.ref != r.k:
                r.status = "moved"
        return
    top = -1
    for r in rows:
        if r.status != "ok":
            continue
        key = r.ref if r.how == "multiple" else min(r.covers)
        if key < top or (r.how == "multiple" and key == top):
            r.status = "moved"
        else:
            top = key


# ================================================================================================ Φ_q, ν, γ
def match_rows(S, R, rtol, order="book", free=False, factors=None, own=None, atol=None):
    """Match the rows of a derived quantity (Φ_q, ν or γ) to the reference.

    Parameters
    ----------
    S, R : ndarray (N, ms, w), (N, m, w)
        Answer and reference at the assembled samples (w columns: 1 for ν and γ).
    order : {"book", "any"}
        Without the student's Φ: "book" pairs answer row k with reference row k (aligning when the counts
        differ); "any" pairs by value.
    free : bool
        Any constant factor per row (Φ_q); otherwise the factor of ``factors`` or 1.
    factors : dict, optional
        {answer row: (reference row, factor)} from the student's Φ (``phi=``): row k must be factor × that
        reference row (or follow from the student's Φ: ``own``).
    own : ndarray (N, ms', w), optional
        The student's own derivation: the rows of Φ_q / ν / γ that follow from their Φ.

    Returns
    -------
    Matching
        Rows with status "ok" (how: "multiple", "own" or "both"), "wrong" (ref set: the row it should have
        been), "extra"; ``missing`` reference rows.
    """
    ms, m = S.shape[1], R.shape[1]
    atol = atol_of(R, rtol) if atol is None else atol
    rows = []
    if factors is not None or own is not None:
        for k in range(ms):
            ref, c = (factors or {}).get(k, (None, None))
            ok_ref = False
            if ref is not None:
                if free:
                    c2 = scale_match(S[:, k], R[:, ref], rtol, True, atol=atol, zeros=True)
                    ok_ref, c = c2 is not None, (c2 if c2 is not None else c)
                elif c is not None:
                    ok_ref = scale_match(S[:, k], c * R[:, ref], rtol, False, atol=atol, zeros=True) is not None
            ok_own = own is not None and k < own.shape[1] and \
                scale_match(S[:, k], own[:, k], rtol, False, atol=atol, zeros=True) is not None
            if ok_ref or ok_own:
                how = "both" if ok_ref and ok_own else ("own" if ok_own else "multiple")
                rows.append(Row(k, ref, "ok", c, how))
            elif ref is None and (own is None or k >= own.shape[1]):
                rows.append(Row(k, None, "extra"))
            else:
                rows.append(Row(k, ref, "wrong", c))
        count = own.shape[1] if own is not None else m
        return Matching(rows, [("own", k) for k in range(ms, count)])
    C = scale_matrix(S, R, rtol, free, atol=atol, zeros=True)
    if order == "any":
        taken = {}
        for k in range(ms):
            cands = [j for j in range(m) if not np.isnan(C[k, j]) and j not in taken]
            if cands:
                taken[cands[0]] = k
                rows.append(Row(k, cands[0], "ok", C[k, cands[0]]))
            else:
                rows.append(Row(k, None, "wrong"))
        free_refs = [j for j in range(m) if j not in taken]
        for r in rows:  # rows matching nothing: diagnosed against the rows left, in order
            if r.status == "wrong" and free_refs:
                r.ref = free_refs.pop(0)
                r.factor = 1.0
        for r in rows:
            if r.status == "wrong" and r.ref is None:
                r.status = "extra"
        return Matching(rows, free_refs)
    # book order
    pairs = _align(C, ms, m) if ms != m else {k: k for k in range(m)}
    used = set()
    for k in range(ms):
        j = pairs.get(k)
        if j is None:
            rows.append(Row(k, None, "extra"))
            continue
        used.add(j)
        c = C[k, j]
        rows.append(Row(k, j, "ok", c) if not np.isnan(c) else Row(k, j, "wrong", 1.0))
    missing = [j for j in range(m) if j not in used]
    if all(r.status != "ok" for r in rows) or any(r.status == "wrong" for r in rows):
        # right rows in another order: the student's Φ was ordered differently
        perm = _permutation(C)
        if perm is not None and ms == m and any(perm[k] != k for k in perm):
            for r in rows:
                if r.status == "wrong" and r.k in perm:
                    r.status, r.ref, r.factor = "moved", perm[r.k], C[r.k, perm[r.k]]
    return Matching(rows, missing)


def _align(C, ms, m):
    """Book order with rows missing or extra: answer rows to reference rows keeping their order."""
    out, j = {}, 0
    for k in range(ms):
        found = next((jj for jj in range(j, m) if not np.isnan(C[k, jj])), None)
        if found is not None:
            out[k] = found
            j = found + 1
        elif j < m and (ms - k) >= (m - j):
            out[k] = j
            j += 1
    return out


def _permutation(C):
    """A one-to-one assignment of every answer row to a reference row it is a multiple of, or None."""
    ms, m = C.shape
    out, taken = {}, set()
    for k in range(ms):
        cands = [j for j in range(m) if not np.isnan(C[k, j]) and j not in taken]
        if not cands:
            return None
        j = k if k in cands else cands[0]
        out[k] = j
        taken.add(j)
    return out


def jacobian_equivalents(matching, S, R, blocks, rtol, F=None, book=None):
    """Φ_q rows of an equivalent formulation: a row that is no constant multiple of a reference row but, at
    every assembled sample, a combination of the rows of one constraint (the Jacobian of M(q)·Φ, e.g. the
    book's cross-product rows of a parallel constraint) is right; reference rows whose gradients the accepted
    rows span are then not missing.

    Parameters
    ----------
    blocks : list of lists of int
        The reference rows of each constraint.
    F : ndarray (N, f, w), optional
        Rows that hold anyway (the normalization rows of a joint graded alone), free to be added.
    book : callable, optional
        ``book(block)`` → the Jacobian rows of the book's own formulation of that constraint (N, r, w), or None.
        Rows of an equivalent formulation whose combination of the constraint's rows changes with q (M(q)·Φ_q)
        are right only if M(q) is regular at every sample (its determinant keeps its sign): the book's own
        rows are its accepted form.
    """
    touched = []
    for r in matching.rows:
        if r.status not in ("wrong", "extra") or r.code is not None:
            continue
        s = S[:, r.k, :]
        if scale_of(s) == 0:
            continue
        order = sorted(blocks, key=lambda b: 0 if r.ref in b else 1)
        for block in order:
            if len(block) < 2 and r.ref not in block:
                pass
            basis = R[:, block, :] if F is None or not F.size else np.concatenate([R[:, block, :], F], axis=1)
            alpha, ok = _in_span(s, basis, rtol)
            alpha = alpha[:, : len(block)]
            if not ok:
                continue
            size = np.abs(alpha) * np.linalg.norm(R[:, block, :], axis=2)
            covers = [j for i, j in enumerate(block) if np.any(size[:, i] > 1e-3 * np.linalg.norm(s, axis=1))]
            if not covers:
                continue
            r.status, r.how, r.covers, r.code = "ok", "equivalent", covers, None
            r.ref = covers[0]
            touched.append(block)
            break
    if not touched:
        return matching
    _singular_combinations(matching, S, R, touched, rtol, F, book)
    accepted = [r for r in matching.rows if r.status == "ok"]
    multiples = {r.ref for r in accepted if r.how == "multiple"}
    basis = S[:, [r.k for r in accepted], :]
    if F is not None and F.size:
        basis = np.concatenate([basis, F], axis=1)
    still = []
    held = {r.ref for r in matching.rows if r.code == "vanishing_factor"}
    for j in sorted(set(matching.missing) | {j for b in touched for j in b} - multiples):
        if j in multiples or j in held:
            continue
        _, ok = _in_span(R[:, j, :], basis, rtol)
        if not ok:
            still.append(j)
    for r in matching.rows:  # wrong rows paired with a reference row that turned out covered
        if r.status == "wrong" and r.ref is not None and r.ref not in still and r.ref not in multiples and \
                r.code != "vanishing_factor":
            r.status, r.code = "extra", None
    matching.missing = still
    return matching
