"""Naming the mistake (fifth stage of a check): every wrong row is compared with the catalogue's generated
mistakes (:mod:`kinbook.grading.mistakes`) and gets the code of the one it equals — or "wrong_value".

One mistake gets one name across the rows it touches: the variants of a constraint are tried on all of its
wrong rows at once, and the variant that explains the most of them names them all (a sign error on ξ_j that
spoils both rows of a revolute joint is one "sign error", not a "sign error" and an "Aᵀ for A").
"""

from __future__ import annotations

import itertools
import re

import numpy as np
import sympy as sp

from . import mistakes as M
from . import mutant_names, slips
from ._i18n import Msg
from .equivalence import in_span, same, scale_match, scale_of
from .quantities import applies, quantity_of
from .rounding import distinct_leaves

__all__ = ["phi", "derived", "eg_rows", "entries", "term_variants", "where", "MAX_TERMS"]

MAX_TERMS = 16
"""Rows with more terms than this are not searched term by term (a size budget, not a time limit)."""
_MAX_OPS = 400


# ================================================================================================ Φ
def phi(target, answer, data, matching, rtol):
    """Diagnose the wrong rows of a Φ answer in place: each gets the reference row it was meant to be (when
    one is missing) and a code."""
    rows = matching.rows
    for r in rows:
        if r.code == "vanishing_factor" and r.where is not None:
            r.detail = _vanishing_detail(target, answer, r)
    zero = {r.k for r in rows if r.status == "wrong" and r.code is None and _zero_row(answer, data, r.k)}
    wrong = [r for r in rows if r.status == "wrong"]
    free = list(matching.missing)
    if wrong and free:
        _structural_phi(target, data, wrong, free, rtol)
    wrong = [r for r in wrong if r.code is None]
    if wrong and free:
        _alternative_phi(target, data, wrong, free, rtol)
    wrong = [r for r in wrong if r.code is None]
    if wrong and free:
        _terms_phi(target, data, wrong, free, rtol)
    wrong = [r for r in wrong if r.code is None]
    if wrong and free:
        mutant_names.name_phi_rows(target, data, wrong, free, rtol)
    wrong = [r for r in wrong if r.code is None]
    for r in rows:  # a zero row is named as what it is; a mistake that gives 0 too is said beside it
        if r.k in zero and r.code is not None:
            r.detail, r.code, r.erratum = Msg("d.zero_like", code=r.code, ref=target.label(r.ref)), "zero_row", None
    if wrong:
        for r, j in _pair(target, answer, wrong, free):
            r.ref = j
            if j is not None:
                free.remove(j)
                r.code = "zero_row" if r.k in zero else ("masked_row" if r.masked else "wrong_value")
            else:
                r.status, r.code = "extra", "extra_row"
    matching.missing = free
    for r in rows:
        if r.status == "wrong" and r.ref is not None:
            r.context = M.contexts_of(target.owner(r.ref))


def _zero_row(answer, data, k):
    """Answer row k is zero everywhere: a sympy zero, or (a function, numbers) zero with its gradient at every
    sample. No mistake of the catalogue is a zero row: it is named as what it is."""
    if answer.kind == "symbolic":
        return answer.matrix[k, 0] == 0
    return bool(np.all(data.S_G[:, k] == 0.0) and np.all(data.S_M[:, k] == 0.0)
                and np.all(data.grads("generic")[:, k, :] == 0.0))


def symbols_of(expr):
    """The symbols of a student's expression (:func:`kinbook.grading.rounding.distinct_leaves`: each distinct
    sub-expression once — ``free_symbols`` walks the tree, exponential for an expression that shares its parts)."""
    return distinct_leaves([expr], lambda e: e.is_Symbol)


def _book_name(name):
    return name.replace("phi", "φ")


def where(target, Q, names):
    """"φ2 = 1.5708 (90°), x1 = 0.3" for the coordinates ``names`` at the configuration Q (n,)."""
    idx = {n: i for i, n in enumerate(target.names)}
    out = []
    for name in names:
        v = float(Q[idx[name]])
        v = 0.0 if abs(v) < 1e-12 else v  # round-off is zero (x1 = 0, never 3.3e-19)
        text = f"{_book_name(name)} = {v:.6g}"
        if name.startswith("phi"):
            text += f" ({np.degrees(v):.4g}°)"
        out.append(text)
    return ", ".join(out)


def _vanishing_detail(target, answer, r):
    """What vanishes where (a row accepted only up to a factor f(q) that is zero somewhere): the factor of a
    symbolic row that is zero there, the coordinates it depends on, and the reference row that is not zero."""
    Q, T, refs = r.where
    j, value = next(((j, v) for j, v in refs.items() if abs(v) > 0), next(iter(refs.items())))
    factor = None
    if answer.kind == "symbolic":
        expr = answer.entry(target, r.k)
        if expr is not None and sp.count_ops(expr) <= 300:
            try:
                _, parts = sp.factor_list(sp.together(expr))
                parts = [f for f, _ in parts if f.free_symbols]
                if len(parts) > 1:
                    vals = target.tape(parts)(Q[None], None, np.array([T]))["value"][0]
                    small = [f for f, v in zip(parts, vals) if abs(v) <= 1e-6 * (1 + float(np.max(np.abs(vals))))]
                    factor = small[0] if small else None
            except Exception:  # pragma: no cover - sympy cannot factor it: named by where it vanishes only
                factor = None
    mech = target.mech
    if factor is not None:
        names = [str(x) for x in mech.q if x in factor.free_symbols]
        factor = factor.xreplace({f: sp.Float(f, 6) for f in factor.atoms(sp.Float)})  # 0.509, not 0.509000229762094
        text = sp.sstr(factor).replace("**", "^")
        at = where(target, Q, names)
        if mech.t in factor.free_symbols:
            at = f"{at}, t = {T:.6g}" if at else f"t = {T:.6g}"
        return Msg("d.vanishing", factor=_book_name(text), where=at, ref=target.label(j),
                   value=f"{value:.3g}")
    owner = target.owner(j)
    ncoord = len(mech.COORDS)
    names = [target.names[ncoord * (b.number - 1) + k] for b in owner.bodies for k in range(ncoord)]
    return Msg("d.vanishing_at", where=where(target, Q, names), ref=target.label(j), value=f"{value:.3g}")


def _variant_values(target, v, which, quantity="Phi"):
    key = (which, quantity)
    if key not in v.cache:
        s = target.samples(which)
        tape = target.tape(v.exprs)
        if not quantity_of(quantity).derived:
            v.cache[key] = tape(s.Q, s.QD, s.T)["value"]
        else:
            d = tape.derived(s.Q, s.QD, s.T)
            v.cache[key] = d
    return v.cache[key]


def _structural_phi(target, data, wrong, free, rtol):
    owners = []
    for j in free:
        c = target.owner(j)
        if c not in owners:
            owners.append(c)
    for c in owners:
        block = target.block(c)
        while True:
            todo = [j for j in block if j in free]
            left = [r for r in wrong if r.code is None]
            if not todo or not left:
                break
            best = None
            for v in M.structural(target, c):
                try:
                    V = _variant_values(target, v, "generic")
                except Exception:  # pragma: no cover - an odd variant is skipped
                    continue
                hits = {}
                used = set()
                agree = 0  # rows the variant leaves as the reference's, where the answer has them right too
                for pos, j in enumerate(block):
                    if not np.all(np.isfinite(V[:, pos])):
                        continue
                    if _phi_equal(V[:, pos], data.R_G[:, j], rtol):
                        agree += j not in todo
                        continue  # the variant equals the reference on this row
                    if j not in todo:
                        continue
                    for r in left:
                        if r.k in used:
                            continue
                        if _phi_equal(data.S_G[:, r.k], V[:, pos], rtol):
                            hits[j] = r
                            used.add(r.k)
                            break
                if hits and (best is None or (len(hits), agree) > (len(best[1]), best[2])):
                    best = (v, hits, agree)
            if best is None:
                break
            v, hits, _ = best
            for j, r in hits.items():
                r.ref, r.code, r.detail, r.erratum = j, v.code, v.detail, v.erratum
                free.remove(j)
                if v.code == "A_transposed" and len(hits) == 1:
                    _also_a_sign(target, data, r, j, rtol)


def _also_a_sign(target, data, r, j, rtol):
    """Aᵀ for A that changes one row only can be the same expression as one term's sign slipped (a translational
    joint's cross product written with + for −): both readings are given, not only Aᵀ."""
    G = target.samples("generic")
    row = target.symbolic_phi()[j]
    terms = sp.Add.make_args(row)  # the row as written (a cross product's two products), then expanded
    cands = [(row - 2 * t, t) for t in terms if len(terms) > 1]
    cands += [(e, t) for code, e, t in term_variants(row) if code == "sign_flip" and t is not None]
    for expr, term in cands:
        vals = target.tape([expr])(G.Q, G.QD, G.T)["value"][:, 0]
        if scale_match(data.S_G[:, r.k], vals, rtol) is not None:
            named = _term_detail("sign_flip", term)
            r.detail = Msg("d.or_sign_of_term", term=named.fields["term"], kind=named.fields["kind"])
            return


def _phi_equal(a, b, rtol):
    """Rows of Φ equal up to a constant factor, or both identically zero (a row of constants)."""
    if scale_of(b) <= 1e-12:
        return scale_of(a) <= 1e-12
    return scale_match(a, b, rtol) is not None


def _alternative_phi(target, data, wrong, free, rtol):
    """Wrong rows that are a mistake made on the book's formulation (cross-product rows of a parallel
    constraint): named, and standing for the constraint's next missing row."""
    owners = []
    for j in free:
        c = target.owner(j)
        if c not in owners:
            owners.append(c)
    for c in owners:
        for v in M.alternative_variants(target, c):
            left = [r for r in wrong if r.code is None]
            todo = [j for j in target.block(c) if j in free]
            if not left or not todo:
                break
            try:
                V = _variant_values(target, v, "generic")
            except Exception:  # pragma: no cover
                continue
            for r in left:
                if not todo:
                    break
                if any(_phi_equal(data.S_G[:, r.k], V[:, i], rtol) for i in range(V.shape[1])):
                    j = todo.pop(0)
                    r.ref, r.code, r.detail = j, v.code, v.detail
                    free.remove(j)


def term_variants(expr):
    """Single and double sign flips ("sign_flip") and single dropped terms ("missing_term") of one expression,
    each with the term concerned; none for rows of more than :data:`MAX_TERMS` terms."""
    if sp.count_ops(expr) > _MAX_OPS:
        return []
    terms = sp.Add.make_args(sp.expand(expr))
    k = len(terms)
    if k < 2 or k > MAX_TERMS:
        return []
    total = sp.Add(*terms)
    out = [("sign_flip", total - 2 * terms[a], terms[a]) for a in range(k)]
    if k <= 8:
        out += [("sign_flip", total - 2 * terms[a] - 2 * terms[b], None) for a, b in itertools.combinations(range(k), 2)]
    out += [("missing_term", total - terms[a], terms[a]) for a in range(k)]
    if k <= 8:
        out += [("missing_term", total - terms[a] - terms[b], terms[a] + terms[b])
                for a, b in itertools.combinations(range(k), 2)]
    return out


def _term_detail(code, term):
    """The term named in a row's message; ``kind`` says what sort of term it is without writing it (a try-it shows
    that instead: the term written out is the answer's last step)."""
    if term is None:
        return None

    text = sp.sstr(term).replace("phi", "φ").replace("**", "^")
    return Msg("d.sign_of_term" if code == "sign_flip" else "d.missing_term", term=text, kind=term_kind(term))


def _terms_phi(target, data, wrong, free, rtol):
    G = target.samples("generic")
    for j in list(free):
        left = [r for r in wrong if r.code is None]
        if not left:
            return
        cands = term_variants(target.symbolic_row(j))
        if not cands:
            continue
        vals = target.tape([e for _, e, _ in cands])(G.Q, G.QD, G.T)["value"]
        hits = []
        for i, (code, _, term) in enumerate(cands):
            if np.ptp(vals[:, i]) <= 1e-12 * max(1.0, float(np.abs(vals[:, i]).max())):
                continue  # a variant constant at the samples (pᵀp + 1 on unit p) is a multiple of any constant row
            for r in left:
                c = scale_match(data.S_G[:, r.k], vals[:, i], rtol)
                if c is not None:
                    hits.append((abs(c - 1.0) > 1e-9, i, r, code, term))  # a factor 1 names the term best
        if hits:
            _, _, hit, code, term = min(hits, key=lambda h: h[:2])
            hit.ref, hit.code, hit.detail = j, code, _term_detail(code, term)
            free.remove(j)


def _pair(target, answer, wrong, free):
    """Which reference rows the remaining wrong rows were meant to be: by the coordinates they use (symbolic
    answers), else in order; rows left over are extra."""
    free = list(free)
    if answer.kind == "symbolic" and free:
        cand = []
        for r in wrong:
            sk = {x.name for x in symbols_of(answer.matrix[r.k, 0])}
            for j in free:
                sj = {x.name for x in target.symbolic_row(j).free_symbols}
                overlap = len(sk & sj) / max(1, len(sk | sj))
                cand.append((-overlap, abs(r.k - j), j, r.k))
        out, used_j, used_k = {}, set(), set()
        for _, _, j, k in sorted(cand):
            if j not in used_j and k not in used_k:
                out[k] = j
                used_j.add(j)
                used_k.add(k)
        return [(r, out.get(r.k)) for r in wrong]
    pairs = []
    for r in wrong:
        pairs.append((r, free.pop(0) if free else None))
    return pairs


# ================================================================================================ Φ_q, ν, γ
class _Expected:
    """What each wrong row is graded against and the candidates (generated mistakes) for it."""

    def __init__(self, target, quantity, data, samples):
        self.target, self.quantity, self.data, self.s = target, quantity, data, samples
        self._hdiag = {}

    def ref_tape(self, c):
        """The tape of constraint c's reference rows (one constraint's Φ only: building the whole mechanism's
        symbolic Φ for one wrong row costs the first check most of its time)."""
        return self.target.tape(self.target.symbolic_rows(c), key=("phi", c.name))

    def rule_values(self, tape_key, tape, rule, frozen=()):
        key = ("rule", tape_key, rule, tuple(frozen))
        store = self.target.store
        if key not in store:
            s = self.s
            store[key] = tape.derived(s.Q, s.QD, s.T, rule=rule, frozen=frozen, parts=True)
        return store[key]

    def pick(self, d, row):
        """Row ``row`` of a derived dict, in the answer's columns: (N, w)."""
        q = self.quantity
        if quantity_of(q).per_coordinate:
            return d[q][:, row, :][:, self.data.cols]
        return d[q][:, row][:, None]


def _p_columns(target):
    """Columns (into q) of every body's Euler parameters (spatial)."""
    if target.kind != "spatial":
        return []
    return [7 * b + k for b in range(target.n // 7) for k in range(3, 7)]


def derived(target, quantity, answer, data, matching, rtol, own=None):
    """Diagnose the wrong rows of a Φ_q, ν or γ answer in place (code, entries, score).

    ``own``: with the student's Φ, a dict with its "tape" (or None for a function), "values" (its derived
    quantities at the samples) — derivation mistakes are then made on it as well.
    """
    s = target.samples("assembled")
    Q = quantity_of(quantity)
    ex = _Expected(target, quantity, data, s)
    wrong = [r for r in matching.rows if r.status == "wrong"]
    if not wrong:
        return
    # derivation mistakes first (a Jacobian without the chain rule is named so, even where it equals the
    # Jacobian of a Φ written without A), then structural mistakes carried through, one name per constraint
    cands = {}
    for r in wrong:
        r.context = M.contexts_of(target.owner(r.ref), quantity) if r.ref is not None and \
            not isinstance(r.ref, tuple) else (quantity,)
        expected = _expected_row(ex, r, own)
        if r.code == "vanishing_factor":  # named by the matching: f(q) × the reference row
            _, lo, hi = r.where
            r.detail = Msg("d.vanishing_jacobian", ref=target.label(r.ref), lo=f"{lo:.3g}", hi=f"{hi:.3g}")
            cands[r.k] = (expected, [])
            continue
        cands[r.k] = (expected, _candidates(target, ex, r, own, expected))
        S = data.S[:, r.k]
        hit = next(((code, detail, err) for code, V, detail, err in cands[r.k][1]
                    if _finite(V) and not same(V, expected, rtol) and same(S, V, rtol)), None)
        if hit is not None:
            r.code, r.detail, r.erratum = hit
    by_owner = {}
    for r in wrong:
        if r.code is None and r.ref is not None and not isinstance(r.ref, tuple) and r.how != "own":
            by_owner.setdefault(target.owner(r.ref), []).append(r)
    for c, rows in by_owner.items():
        _structural_derived(target, ex, c, rows, rtol)
        if Q.per_coordinate:
            _variant_spans(target, ex, c, [r for r in rows if r.code is None], rtol)
    for r in wrong:
        expected, cand = cands[r.k]
        S = data.S[:, r.k]
        if not Q.per_coordinate:
            if r.code is None:
                hit = _terms_derived(target, ex, r, own, S, expected, rtol) or \
                    mutant_names.name_derived_row(target, ex, r, own, S, expected, rtol)
                r.code, r.detail, r.erratum = hit if hit is not None else ("wrong_value", None, None)
            r.score = 0.0
            continue
        r.entries, r.score = entries(S, expected, rtol, r.code, cand)
        if r.code is None:
            named = [e for e in r.entries if e not in ("ok", "wrong_value")]
            hit = None if named else (_terms_derived(target, ex, r, own, S, expected, rtol)
                                      or mutant_names.name_derived_row(target, ex, r, own, S, expected, rtol))
            if hit is not None:  # the Jacobian of Φ with a term's sign flipped or a term dropped
                r.code, r.detail, r.erratum = hit
                r.entries, r.score = entries(S, expected, rtol, r.code, cand)
            elif not named:  # a slip inside the wrong entries themselves (a term's sign, sin ↔ cos …)
                r.entries = mutant_names.name_entries(target, ex, r, S, r.entries, rtol)
                named = [e for e in r.entries if e not in ("ok", "wrong_value")]
                r.code = named[0] if named else "wrong_value"
            else:
                r.code = named[0]


def eg_rows(target, data, matching, rtol):
    """Spatial Φ_q rows that differ from the reference only by multiples of the bodies' normalization
    gradients 2pᵀ in their p-columns: ∂(EGᵀa)/∂p = 2Eā where ∂(A a)/∂p = 2(Eā + apᵀ) belongs."""
    if target.kind != "spatial":
        return
    s = target.samples("assembled")
    cols = data.cols
    bodies = sorted({c // 7 for c in cols})
    for r in matching.rows:
        if r.status != "wrong" or r.ref is None or isinstance(r.ref, tuple):
            continue
        f = 1.0 if r.factor is None or np.isnan(r.factor) else r.factor
        D = data.S[:, r.k] - f * data.R[:, r.ref]
        scale = max(scale_of(data.R[:, r.ref]), 1e-300)
        if scale_of(D) <= rtol * scale:
            continue
        rest = D.copy()
        for b in bodies:
            pc = [i for i, c in enumerate(cols) if 7 * b + 3 <= c < 7 * b + 7]
            if len(pc) != 4:
                continue
            p = s.Q[:, 7 * b + 3: 7 * b + 7]
            coef = np.einsum("ni,ni->n", rest[:, pc], p) / np.einsum("ni,ni->n", p, p)
            rest[:, pc] -= coef[:, None] * p
        if scale_of(rest) <= 1e2 * rtol * scale:
            r.code, r.erratum = "eg_jacobian", None  # the book prints 2(Eā + apᵀ): a student slip, not a misprint
            r.entries, r.score = entries(data.S[:, r.k], f * data.R[:, r.ref], rtol, "eg_jacobian", [])


def _finite(V):
    return V is not None and np.all(np.isfinite(V))


def _expected_row(ex, r, own):
    if r.how in ("own",) or (own is not None and r.ref is None):
        return own["values"][ex.quantity][:, r.k][:, None] if not quantity_of(ex.quantity).per_coordinate else \
            own["values"][ex.quantity][:, r.k, :][:, ex.data.cols]
    f = 1.0 if r.factor is None or (isinstance(r.factor, float) and np.isnan(r.factor)) else r.factor
    return f * ex.data.R[:, r.ref]


def _candidates(target, ex, r, own, expected):
    """(code, values (N, w), detail, erratum) of the derivation mistakes for row r, most specific first."""
    q = ex.quantity
    Q = quantity_of(q)
    out = []
    late = [(Q.sign_code, -expected, None, None)]
    if Q.right_hand_side:  # a plausible factor: a link length of the row's constraint (multiplied through), a
        # forgotten 2 (a Φ row halved, −ṗᵀṗ for −2ṗᵀṗ) — without phi= the factor is 1; any other is "wrong value"
        owner = target.owner(r.ref) if r.ref is not None and not isinstance(r.ref, tuple) else None
        lengths = M.length_factors(owner) if owner is not None else []
        late += [("scaled", c * expected, Msg("d.multiplied_by", c=fmt_factor(c), what=what), None)
                 for c, what in lengths]
        late += [("scaled", c * expected, Msg("d.factor", c=fmt_factor(c)), None) for c in (2.0, 0.5)
                 if not any(abs(c - v) <= 1e-9 for v, _ in lengths)]
    f = 1.0 if r.factor is None or (isinstance(r.factor, float) and np.isnan(r.factor)) else r.factor
    sources = []
    if own is not None and own.get("tape") is not None and r.k < own["values"]["Phi"].shape[1]:
        sources.append(("own", own["tape"], r.k, 1.0))
    if r.ref is not None:
        try:
            c = target.owner(r.ref)
            sources.append((("phi", c.name), ex.ref_tape(c), target.block(c).index(r.ref), f))
        except Exception:  # pragma: no cover - a reference that cannot be taped
            pass
    if r.ref is not None and not isinstance(r.ref, tuple) and Q.q_derivative:
        c = target.owner(r.ref)
        pos = target.block(c).index(r.ref)
        ref = target.reference("assembled")
        for book in M.spec_of(c).derived_book:
            if not applies(book, q):
                continue
            try:
                made = book(target, c, ex.s, ref, q)
            except Exception:  # pragma: no cover - a misprint that cannot be made here
                made = []
            for row, values, erratum in made:
                if row == pos:
                    V = values[:, ex.data.cols] if Q.per_coordinate else values[:, None]
                    out.append(("book_misprint", f * V, None, erratum))
        for slip in M.spec_of(c).derived_slips:
            if not applies(slip, q):
                continue
            for row, values, code, detail in slip(target, c, ex.s, ref, q):
                if row == pos:
                    V = values[:, ex.data.cols] if Q.per_coordinate else values[:, None]
                    out.append((code, f * V, Msg("d.dC_missing") if detail == "dC" else None, None))
    owner = target.owner(r.ref) if r.ref is not None and not isinstance(r.ref, tuple) else None
    if owner is not None and Q.per_coordinate:
        out += _rotation_columns_exchanged(target, ex, owner, expected)
    if owner is not None and owner.kind == "normalization" and Q.right_hand_side:
        # pᵀp − 1: γ = −2ṗᵀṗ, nothing of A in it — its zero γ is the term forgotten, not a chain rule
        out.append(("missing_term", np.zeros_like(expected), Msg("d.missing_term", term="−2ṗᵀṗ"), None))
        sources = []
    for key, tape, row, factor in sources:
        rules = _rules(target)
        exact = ex.rule_values(key, tape, "exact")
        for rule, code, frozen in rules:
            d = ex.rule_values(key, tape, rule, frozen)
            out.append((code, factor * ex.pick(d, row), None, None))
        if Q.zero_code:
            out.append((Q.zero_code, np.zeros_like(expected), None, None))
        if Q.velocities:
            quad = factor * exact["quad"][:, row][:, None]
            qt = factor * exact["qt"][:, row][:, None]
            tt = factor * exact["tt"][:, row][:, None]
            # the book prints γ without its minus sign in §13.8 only: the erratum is cited for planar rows
            late.insert(0, ("gamma_sign", -quad + qt + tt, None,
                            "13.8-gamma-sign" if target.kind == "planar" else None))
            out.append(("missing_qt_term", quad + tt, None, None))
            if key != "own":
                ncoord = len(target.mech.COORDS)
                bodies = [[ncoord * (b.number - 1) + k for k in range(ncoord)] for b in owner.bodies]
                V = slips.cross_term_flipped(tape, row, ex.s, expected, factor, bodies)
                if V is not None:
                    out.append(("sign_flip", V, Msg("d.sign_of", what=Msg("d.cross_terms")), None))
            out.append(("missing_tt_term", quad + qt, None, None))
            H = _hdiag(ex, key, tape)
            QD = ex.s.QD
            unsq = factor * (np.einsum("bkn,bn->bk", H, QD**2) - np.einsum("bkn,bn->bk", H, QD))[:, row][:, None]
            out.append(("missing_square", expected + unsq, None, None))
    return late + out


def _rotation_columns_exchanged(target, ex, c, expected):
    """A Φ_q row whose two bodies' rotation columns (φ_i ↔ φ_j; p_i ↔ p_j) hold each other's entries: B s'
    differentiated right but written under the other body's angle — the right numbers in the wrong places."""
    bodies = getattr(c, "bodies", ())
    if len(bodies) != 2:
        return []
    ncoord = len(target.mech.COORDS)
    rot = range(2, 3) if ncoord == 3 else range(3, 7)
    cols = list(ex.data.cols)
    at = [[cols.index(ncoord * (b.number - 1) + k) for k in rot if ncoord * (b.number - 1) + k in cols] for b in bodies]
    if len(at[0]) != len(rot) or len(at[1]) != len(rot):
        return []
    V = expected.copy()
    V[:, at[0] + at[1]] = expected[:, at[1] + at[0]]
    return [("swapped_entries", V, Msg("d.rotation_columns"), None)]


def fmt_factor(c):
    return "½" if c == 0.5 else f"{c:g}"


def _rules(target):
    """The derivation mistakes as tape rules: (rule, code, frozen coordinates)."""
    if target.kind == "planar":
        return [("chain_dropped", "missing_chain_rule", ()), ("A_for_B", "A_for_B", ())]
    return [("exact", "missing_chain_rule", tuple(_p_columns(target)))]


def _hdiag(ex, key, tape):
    """H_kk = ∂²Φ/∂q_k² at the samples (N, rows, n): the diagonal of (Φ_q q̇)_q."""
    if key not in ex._hdiag:
        s = ex.s
        N, n = s.Q.shape
        H = np.zeros((N, len(tape.outputs), n))
        used = {payload for kind, payload, _ in tape.ops if kind == "q"}  # the other columns' H_kk are 0
        for k in sorted(used):
            e = np.zeros_like(s.Q)
            e[:, k] = 1.0
            H[:, :, k] = tape(s.Q, e, s.T, order=2, dt=0.0, velocities=s.QD)["d2"]
        ex._hdiag[key] = H
    return ex._hdiag[key]


def _structural_derived(target, ex, c, rows, rtol):
    """Structural variants of constraint c carried through the derivation, tried on its wrong rows at once."""
    block = target.block(c)
    best = None
    for v in M.structural(target, c):
        if not v.derived:
            continue
        try:
            d = _variant_values(target, v, "assembled", ex.quantity)
        except Exception:  # pragma: no cover
            continue
        hits = []
        for r in rows:
            pos = block.index(r.ref)
            f = 1.0 if r.factor is None or np.isnan(r.factor) else r.factor
            V = f * ex.pick(d, pos)
            if not _finite(V) or same(V, f * ex.data.R[:, r.ref], rtol):
                continue
            if same(ex.data.S[:, r.k], V, rtol):
                hits.append(r)
        if hits and (best is None or len(hits) > len(best[1])):
            best = (v, hits)
    if best is not None:
        v, hits = best
        for r in hits:
            r.code, r.detail, r.erratum = v.code, v.detail, v.erratum


def _variant_spans(target, ex, c, rows, rtol):
    """Φ_q rows of a mistaken formulation: at every sample a combination of one variant's rows (and the
    normalization rows of a joint graded alone) — e.g. Aᵀ for A in the book's cross-product rows."""
    if not rows:
        return
    F = target.reference("assembled")["free_q"][:, :, ex.data.cols]
    blocks = []
    tape = ex.ref_tape(c)
    for rule, code, frozen in (_rules(target)):
        D = ex.rule_values(("phi", c.name), tape, rule, frozen)["Phi_q"][:, :, ex.data.cols]
        blocks.append((M.Variant(code, []), D))
    for v in list(M.structural(target, c)) + list(M.alternative_variants(target, c)):
        if not v.derived:
            continue
        try:
            blocks.append((v, _variant_values(target, v, "assembled", "Phi_q")["Phi_q"][:, :, ex.data.cols]))
        except Exception:  # pragma: no cover
            continue
    for v, D in blocks:
        left = [r for r in rows if r.code is None]
        if not left:
            return
        if not np.all(np.isfinite(D)):
            continue
        basis = np.concatenate([D, F], axis=1) if F.size else D
        for r in left:
            s = ex.data.S[:, r.k]
            if scale_of(s) == 0:
                continue
            _, ok = in_span(s, basis, rtol)
            if ok:
                r.code, r.detail, r.erratum = v.code, v.detail, v.erratum


def _terms_derived(target, ex, r, own, S, expected, rtol):
    """Sign flips and dropped terms of the symbolic expected row (ν, γ), or of the Φ row a Φ_q row is the
    Jacobian of — derived with sympy only for small rows."""
    if r.ref is None or own is not None:
        return None

    Phi = target.symbolic_row(r.ref)
    if sp.count_ops(Phi) > 60:
        return None
    mech = target.mech
    q, qd, t = list(mech.q), list(mech.qd), mech.t
    syms = [x for x in q if x in Phi.free_symbols]
    D = lambda e: sum(sp.diff(e, x) * qd[q.index(x)] for x in syms) + sp.diff(e, t)  # noqa: E731
    f = 1.0 if r.factor is None or np.isnan(r.factor) else r.factor
    s = ex.s
    Q = quantity_of(ex.quantity)
    if Q.per_coordinate:  # the terms of Φ's row: their Jacobians
        cands = term_variants(f * Phi)
        if not cands:
            return None
        vals = target.tape([e for _, e, _ in cands]).derived(s.Q, s.QD, s.T)[Q.name][:, :, ex.data.cols]
    else:
        expr = Q.expression(Phi, D, t)
        cands = term_variants(f * expr)
        if not cands:
            return None
        vals = target.tape([e for _, e, _ in cands])(s.Q, s.QD, s.T)["value"][:, :, None]
    for i, (code, _, term) in enumerate(cands):
        V = vals[:, i]
        if not same(V, expected, rtol) and same(S, V, rtol):
            return code, _term_detail(code, term), None
    return None


def entries(S, E, rtol, row_code, cands):
    """Per entry of a Φ_q row: "ok", or the code of the candidate that reproduces it; and the row's credit
    (the fraction of its nonzero entries that are right)."""
    w = S.shape[1]
    scale = max(scale_of(E), scale_of(S))
    out = []
    for i in range(w):
        si, ei = S[:, i], E[:, i]
        if np.all(np.abs(si - ei) <= rtol * scale + 1e-12):
            out.append("ok")
            continue
        code = "wrong_value"
        if scale_of(ei) > 1e-12 and same(si, -ei, rtol):
            code = "sign_flip"
        for ccode, V, _, _ in cands:
            if V is not None and V.shape == S.shape and same(si, V[:, i], rtol) and not same(V[:, i], ei, rtol):
                code = ccode
                break
        if row_code is not None and code == "wrong_value":
            code = row_code
        out.append(code)
    relevant = [i for i in range(w) if scale_of(E[:, i]) > 1e-12 or scale_of(S[:, i]) > 1e-12]
    good = sum(1 for i in relevant if out[i] == "ok")
    return tuple(out), (good / len(relevant) if relevant else 0.0)


def term_kind(term):
    """What sort of term a sympy term of a row is, as a Msg that does not write it: a constant, a term of time
    alone (a driver's function), quadratic or linear in the velocities, of a body's rotation or of its origin —
    with the bodies it involves ("a term quadratic in the velocities, of body 2")."""
    names = {s.name for s in term.free_symbols}
    velocities = [n for n in names if n.startswith("d") and n != "t"]
    coordinates = [n[1:] if n in velocities else n for n in names if n != "t"]
    bodies = sorted({int(m.group(2)) for n in coordinates if (m := re.fullmatch(r"(e[0-3]|[a-z]+)(\d+)", n))})
    if not names:
        kind = "k.constant"
    elif names == {"t"}:
        kind = "k.time"
    elif velocities:
        vel = [v for v in term.free_symbols if v.name in velocities]
        deg = max(sp.Poly(a, *vel).total_degree() for a in sp.Add.make_args(sp.expand(term)))
        kind = "k.velocity_squared" if deg >= 2 else "k.velocity"
    elif any(n.startswith(("phi", "e0", "e1", "e2", "e3", "psi", "theta")) for n in names):
        kind = "k.rotation"
    else:
        kind = "k.origin"
    what = Msg(kind)
    if bodies:
        return Msg("k.of_bodies", what=what, bodies=", ".join(str(b) for b in bodies), n=len(bodies))
    return what
