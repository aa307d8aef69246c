"""The one equivalence rule (fourth stage of a check): which rows of an answer stand for which rows of
kinbook's reference, which are dependent on others, which reference rows are missing.

The rule, for all four checkers:

* An answer **row is right** when it is a reference row multiplied by a nonzero constant — the same
  constant at every sample. For Φ any constant (Φ is a set of equations: −Φ_4 or 2Φ_4 is the same
  constraint). For Φ_q, ν and γ the constant is the one of the row of Φ they come from: given by the
  student's own Φ (``phi=``) when there is one — or 1, the reference's own row; otherwise 1 for ν and γ (a
  negated ν or γ *is* the classic sign mistake) and ±1 for Φ_q (the Jacobian of ±Φ_k; another constant c is
  the Jacobian of c·Φ_k, named ``scaled`` by :mod:`~kinbook.grading.aftermatch`). Numbers, text and sympy
  answers follow the same rule.
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

from dataclasses import dataclass, field

import numpy as np

from .equivalence import (
    RTOL,
    RTOL_NUMBERS,
    atol_of,
    equivalents,
    jacobian_equivalents,
    nice,
    same,
    scale_match,
    scale_matrix,
    scale_of,
    still_missing,
    vanishing,
    zero_tol,
)

__all__ = ["RTOL", "RTOL_NUMBERS", "Row", "Matching", "scale_of", "scale_matrix", "match_phi", "match_rows",
           "nice", "same", "scale_match", "atol_of", "zero_tol", "vanishing", "jacobian_equivalents"]


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
    wide: dict = field(default_factory=dict)  # answer row -> (reference row, c, sample): a multiple only in (−π, π], t ≤ 1



def match_phi(data, rtol, order="any", wrap=None, turns=None):
    """Match the rows of an answer Φ to the reference's, constraint by constraint.

    Parameters
    ----------
    data : :class:`~kinbook.grading.evaluate.PhiData`
        The answer and the reference at the generic samples (S_G, R_G), at the target's assembled samples
        (S_M, gR_M, F_M) and, per constraint, at that constraint's own assembled samples (``data.block(i)``).
    order : {"any", "book"}
    wrap : dict
        {reference row: period} of wrapped angle rows.
    turns : dict
        {reference row: 2π} of the other rows that measure an angle: ±1 times the row up to whole turns is
        right too (:func:`~kinbook.grading.equivalence.scale_matrix`).

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
    C = scale_matrix(S_G, R_G, rtol, True, wrap, turns=turns)
    wide = _wide(C, data, rtol, wrap, turns)
    _zero_rows(C, data, rtol)
    rows, taken = _multiples(C, ms, m, order, owner_of)
    # 2. the other rows: an equivalent formulation of one constraint, judged where that constraint alone holds
    rest = [r for r in rows if r.status == "wrong"]
    if rest:
        equivalents(data, rest, blocks, owner_of, taken, rtol)
    _combinations(rows, S_G, rtol)
    _redundant(rows, blocks)
    missing = _coverage(data, rows, blocks, rtol)
    # 6. book order
    if order == "book":
        _mark_moved(rows, m)
    return Matching(rows, sorted(missing), wide=wide)


def _multiples(C, ms, m, order, owner_of):
    """1. Multiples of a reference row (at generic configurations: nothing else holds there): in book order the
    diagonal first, then the first free candidate. Returns the rows and {reference row: answer row} taken."""
    rows = [Row(k, None, "wrong") for k in range(ms)]
    taken = {}
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
    return rows, taken


def _combinations(rows, S_G, rtol):
    """3. Constant combinations among the accepted rows: dependent."""
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


def _redundant(rows, blocks):
    """4. Counting: a constraint has as many independent equations as reference rows; more rows are redundant."""
    for b, refs in enumerate(blocks):
        mine = [r for r in rows if r.status == "ok" and r.owner == b]
        if len(mine) > len(refs):
            keep = sorted(mine, key=lambda r: (r.how != "multiple", r.k))[: len(refs)]
            for r in mine:
                if r not in keep:
                    r.status, r.dependence = "dependent", "redundant"
                    r.depends_on = sorted(o.k for o in mine)


def _coverage(data, rows, blocks, rtol):
    """5. Coverage, per constraint: every reference row a multiple of an answer row, or in the span of the
    accepted rows' gradients where that constraint holds. Returns the reference rows missing."""
    accepted = [r for r in rows if r.status == "ok"]
    covered = {r.ref for r in accepted if r.how == "multiple"}
    missing = []
    for b, refs in enumerate(blocks):
        lack = [j for j in refs if j not in covered]
        eq = [r.k for r in accepted if r.how == "equivalent" and r.owner == b]
        if lack and eq:
            lack = still_missing(data.block(b), refs, lack, [r.ref for r in accepted if r.how == "multiple" and
                                                              r.owner == b], eq, rtol)
        missing += lack
    return missing


def _wide(C, data, rtol, wrap, turns=None):
    """A multiple at the generic samples is one only if it is the same multiple at the samples over the whole
    domain (angles beyond ±π, t up to 30), compared there on their own scale: ``atan2(sin φ2, cos φ2)`` is φ2
    only in (−π, π]. A row not defined there (a square root of a negative) keeps its match.

    Returns {answer row: (reference row, constant, the sample where it differs most)} of the multiples dropped (named by the witness)."""
    S_W, R_W = getattr(data, "S_W", None), getattr(data, "R_W", None)
    dropped = {}
    if S_W is None or R_W is None or not np.isfinite(C).any():
        return dropped
    CW = scale_matrix(np.nan_to_num(S_W), R_W, rtol, True, wrap, turns=turns)
    for k, j in zip(*np.nonzero(np.isfinite(C))):
        if not np.all(np.isfinite(S_W[:, k])) or scale_of(R_W[:, j]) == 0.0:
            continue
        if not (np.isfinite(CW[k, j]) and abs(CW[k, j] - C[k, j]) <= 1e-6 * abs(C[k, j])):
            i = int(np.argmax(np.abs(S_W[:, k] - C[k, j] * R_W[:, j])))
            dropped.setdefault(int(k), (int(j), float(C[k, j]), i))
            C[k, j] = np.nan
    return dropped


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


def match_rows(S, R, rtol, order="book", free=False, factors=None, own=None, atol=None, wrap=None, turns=None):
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
    wrap, turns : dict, optional
        {reference row: period} of rows that measure an angle (numbers of Φ at a configuration): a value off by
        whole periods is the same placement (:func:`~kinbook.grading.equivalence.scale_matrix`).

    Returns
    -------
    Matching
        Rows with status "ok" (how: "multiple", "own" or "both"), "wrong" (ref set: the row it should have
        been), "extra"; ``missing`` reference rows.
    """
    ms, m = S.shape[1], R.shape[1]
    atol = atol_of(R, rtol) if atol is None else atol
    if factors is not None or own is not None:
        return _rows_of_own(S, R, rtol, free, factors, own, atol)
    C = scale_matrix(S, R, rtol, free, wrap=wrap, atol=atol, zeros=True, turns=turns)
    if order == "any":
        return _rows_by_value(C, ms, m)
    return _rows_in_book_order(C, ms, m)


def _rows_of_own(S, R, rtol, free, factors, own, atol):
    """With the student's Φ: row k must be its factor × the reference row it stands for, or follow from the
    student's own Φ (``own``); the reference row itself is right too ("reference": correct, although it does not
    follow from their Φ)."""
    ms, m = S.shape[1], R.shape[1]
    rows = []
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
        elif ref is not None and not free and \
                scale_match(S[:, k], R[:, ref], rtol, False, atol=atol, zeros=True) is not None:
            rows.append(Row(k, ref, "ok", 1.0, "reference"))  # the reference's own row: right, not from their Φ
        elif ref is None and (own is None or k >= own.shape[1]):
            rows.append(Row(k, None, "extra"))
        else:
            rows.append(Row(k, ref, "wrong", c))
    _moved_own(rows, S, R, rtol, free, factors, own, atol)
    count = own.shape[1] if own is not None else m
    return Matching(rows, [("own", k) for k in range(ms, count)])


def _moved_own(rows, S, R, rtol, free, factors, own, atol):
    """With the student's Φ: a wrong row that is right for *another* row of their Φ (γ rows in the book's order
    under a Φ in another order) is "moved" (the rows' order), not a wrong value."""
    for r in rows:
        if r.status != "wrong":
            continue
        for k2 in range(len(rows)):
            if k2 == r.k:
                continue
            ref, c = (factors or {}).get(k2, (None, None))
            hit = own is not None and k2 < own.shape[1] and \
                scale_match(S[:, r.k], own[:, k2], rtol, False, atol=atol, zeros=True) is not None
            if not hit and ref is not None:
                c2 = scale_match(S[:, r.k], R[:, ref], rtol, free, atol=atol, zeros=True) if free else (
                    1.0 if c is not None and scale_match(S[:, r.k], c * R[:, ref], rtol, False, atol=atol,
                                                         zeros=True) is not None else None)
                hit = c2 is not None
            if hit and scale_of(S[:, r.k]) > atol:
                r.status, r.ref = "moved", ref
                break


def _rows_by_value(C, ms, m):
    """"any" order: each answer row paired with the first free reference row it is a multiple of."""
    rows = []
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


def _rows_in_book_order(C, ms, m):
    """"book" order: answer row k paired with reference row k (aligned when the counts differ)."""
    rows = []
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
