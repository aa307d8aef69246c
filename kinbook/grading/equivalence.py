"""When an answer row is the reference's row (the fourth stage, :mod:`~kinbook.grading.match`, and every stage
after it): the comparison rule — the tolerances and the constant-multiple rule, at the bottom of this file — and
equivalent formulations.

A row that is no multiple of a reference row is judged where its own constraint alone holds — it must vanish
there with its gradient in the span of that constraint's rows' gradients (and of the bodies' normalization rows);
a row true only where the whole mechanism is assembled is *masked*; the zeros of accepted rows are searched for a
factor that vanishes; Φ_q rows may be combinations of one constraint's rows.

Everything here works on arrays (samples × rows × columns); nothing reads answers or knows constraint types.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

__all__ = ["vanishing", "jacobian_equivalents", "equivalents", "still_missing", "in_span",
           "RTOL", "RTOL_NUMBERS", "zero_tol", "nice", "scale_of", "same", "scale_match", "scale_matrix", "atol_of", "wrapped", "turned_multiple"]


def equivalents(data, rest, blocks, owner_of, taken, rtol):
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
    return in_span(g, basis, rtol)[1]


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
    alpha, inspan = in_span(g, basis, rtol)
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
    alpha, inspan = in_span(g, basis, rtol)
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


def still_missing(B, refs, lack, multiples, eq, rtol):
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
    still = [j for j in lack if not in_span(B.gR[:, pos[j], :], basis, rtol)[1]]
    nf = 0 if B.F is None else B.F.shape[1]
    tol = 1e-8 * max(np.abs(basis[0]).max(), 1e-300)
    acc = np.linalg.matrix_rank(basis[0].T, tol=tol) - (np.linalg.matrix_rank(B.F[0].T) if nf else 0)
    full = np.linalg.matrix_rank(B.gR[0].T, tol=1e-8 * max(np.abs(B.gR[0]).max(), 1e-300))
    deficit = max(full - acc, 0)
    return still[len(still) - deficit:] if deficit < len(still) else still


def vanishing(matching, data, rtol):
    """Rows accepted as an equivalent formulation of a constraint whose zero set is larger than the constraint's:
    a factor f(q, t) that vanishes somewhere in the configuration space (cos φ2 · Φ_4, e0 · Φ_k, (x2 − 100) · Φ_4,
    (t − 20) · Φ_12). The zeros of the constraint's answer rows are found from two kinds of starts: seeded ones
    spread over the configuration space and around the assembly (:func:`kinbook.grading.sample.zeros`), and the
    zeros of each factor of each such row, solved or searched over the whole domain — every coordinate on the
    real line, t ≥ 0 (:mod:`kinbook.grading.factors`); from each, Newton steps solve the constraint's other answer
    rows. Where they all vanish and a row they stand for does not — at no placement the same up to turns of 2π
    (:func:`kinbook.grading.sample.placements`: an angle written with atan2 vanishes at φ3 − φ4 = 2π, the same
    placement) — the row is wrong ("vanishing_factor", ``where`` = that configuration). The book's own rows of
    the constraint (two of the three cross-product rows of a parallel constraint) are its accepted form.

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
        ks = [r.k for r in mine]
        tol = 1e-6 * max(scale_of(data.R_G[:, refs]), 1.0)
        found = [f for f in [data.search(b, ks)] if f is not None]
        if not found or not np.any(np.max(np.abs(found[0][2]), axis=1) > tol):
            # nothing wrong near the samples: every factor's zeros over the whole domain (the costlier search)
            found += [f for f in [data.search(b, ks, k=r.k) for r in eq] if f is not None]
        if not found:
            searched[b] = 0
            continue
        Q, T, R = (np.concatenate(x) for x in zip(*found))
        searched[b] = len(Q)
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
            alpha, ok = in_span(s, basis, rtol)
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
        _, ok = in_span(R[:, j, :], basis, rtol)
        if not ok:
            still.append(j)
    for r in matching.rows:  # wrong rows paired with a reference row that turned out covered
        if r.status == "wrong" and r.ref is not None and r.ref not in still and r.ref not in multiples and \
                r.code != "vanishing_factor":
            r.status, r.code = "extra", None
    matching.missing = still
    return matching


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
        M = np.stack([in_span(S[:, r.k, :], basis, rtol)[0][:, : len(block)] for r in mine], axis=1)
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


def in_span(g, basis, rtol):
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


# ================================================================================================ the comparison rule
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


def wrapped(x, period):
    """``x`` wrapped into [−period/2, period/2)."""
    return (x + period / 2) % period - period / 2


def same(a, b, rtol, period=None):
    """a ≈ b entry-wise over all samples, relative to the larger magnitude of the two."""
    d = a - b
    if period:
        d = wrapped(d, period)
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


def scale_matrix(S, R, rtol, free=True, wrap=None, atol=0.0, zeros=False, turns=None):
    """Constants C[k, j] with S[:, k] ≈ C·R[:, j] (NaN where there is none). S (N, ms, …), R (N, m, …).

    Vectorized over all pairs (the rule of :func:`scale_match`); wrapped rows are compared one by one. ``turns``
    ({reference row: period}, the rows that measure an angle): an answer row that is no multiple of such a row
    is still a multiple of it (c = 1 only, unless ``free``) turned by the same whole number of periods at every
    sample (:func:`turned_multiple`)."""
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
    for j, period in (turns or {}).items():
        c, n = turned_multiple(A, B[j], rtol, period, free)
        fill = (n != 0) & np.isnan(C[:, j])
        C[fill, j] = c[fill]
    if free:
        for k, j in zip(*np.nonzero(np.isfinite(C))):
            C[k, j] = nice(C[k, j])
    return C


def turned_multiple(A, b, rtol, period, free=True):
    """Per row of ``A`` (k, N): the constant c and the whole number n ≠ 0 of periods with A ≈ c·(b + n·period) at
    every sample — c and n the same at all of them — or n = 0 where there are none. c is 1 unless ``free``.

    An angle row turned by whole turns places the bodies as the row does: φ3 − φ4 + 2π, φ4 − φ3 + 2π and
    2(φ2 − 3π/4 − 100t + 2π) vanish where a turn of a body makes φ3 − φ4 (the driver's row) vanish. A number
    of turns that changes from sample to sample is another row: atan2(sin φ2, cos φ2) − 3π/4 − 100t equals
    φ2 − 3π/4 − 100t up to turns that follow φ2, and has no zero once 100t > π/4."""
    A = np.atleast_2d(A)
    b = np.asarray(b, float).reshape(-1)
    with np.errstate(all="ignore"):
        if free:
            bc = b - b.mean()
            c = ((A - A.mean(axis=1, keepdims=True)) @ bc) / float(bc @ bc)
        else:
            c = np.ones(len(A))
        d = A - c[:, None] * b[None, :]  # c·n·period, the same at every sample
        off = d.mean(axis=1)
        n = np.round(off / (c * period))
        scale = np.maximum(np.abs(A).max(axis=1), np.abs(c) * np.abs(b).max())
        tol = rtol * scale + 1e-12 * np.maximum(scale, 1.0) * rtol
        ok = (np.all(np.abs(d - off[:, None]) <= tol[:, None], axis=1) & (np.abs(off - c * n * period) <= tol)
              & np.isfinite(c) & (c != 0) & np.isfinite(n))
    return np.where(ok, c, np.nan), np.where(ok, n, 0.0)


def atol_of(R, rtol):
    """The absolute tolerance of a quantity: rtol × its largest entry (at least rounding level)."""
    return rtol * max(scale_of(R), 1e-9)
