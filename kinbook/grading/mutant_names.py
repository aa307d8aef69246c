"""Names for what the mutants find: which catalogue codes name a mutant's wrong answer (:data:`SYNONYMS`), what a
checker's result says of a mutant (:func:`classify`: a blind spot, named, unnamed) and the mutation table
(:class:`Tally`, :func:`format_table`) — and the diagnose stage's use of the mutants
(:mod:`kinbook.grading.mutants`) to name a wrong row the catalogue's own search leaves as "wrong value":
:func:`name_phi_rows` (Φ), :func:`name_derived_row` (ν, γ, a Φ_q row), :func:`name_entries` (one Φ_q entry).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .equivalence import same, scale_match, scale_of
from .mutants import expression_mutants, row_mutants
from .quantities import quantity_of

__all__ = ["SYNONYMS", "EQUIVALENT", "classify", "strictly_named", "passing_mutants", "Tally", "format_table", "name_phi_rows",
           "name_derived_row", "name_entries", "phi_equal"]

SYNONYMS = {
    "sign_flip": {"sign_flip", "nu_sign", "gamma_sign", "A_transposed", "A_for_AT", "swapped_entries", "transposed",
                  "left_handed", "not_orthogonal", "newton_step"},
    "missing_term": {"missing_term", "nu_missing", "missing_qt_term", "missing_tt_term", "missing_chain_rule",
                     "local_vector", "wrong_frame", "missing_square", "rate_exchanged", "relative_speed",
                     "not_orthogonal", "newton_step"},
    "sin_cos": {"sin_cos"},
    "other_body": {"other_body", "swapped_bodies", "swapped_points", "wrong_data"},
    "swapped_bodies": {"swapped_bodies", "other_body", "swapped_points"},
    "degrees": {"degrees"},
    "local_vector": {"local_vector", "missing_chain_rule", "wrong_frame", "missing_term", "book_misprint"},
    "radians_twice": {"radians_twice"},
    "A_transposed": {"A_transposed", "A_for_AT", "transposed"},
    "A_for_AT": {"A_for_AT", "A_transposed", "transposed"},
    "A_for_B": {"A_for_B"},
    "B_for_A": {"B_for_A"},
    "factor_2_missing": {"factor_2_missing", "full_angle", "scaled", "not_orthogonal", "not_normalized"},
    "factor_2_extra": {"factor_2_extra", "scaled", "not_orthogonal", "not_normalized"},
    "missing_square": {"missing_square", "missing_term", "not_orthogonal"},
    "arctan_quadrant": {"arctan_quadrant"},
    "extrinsic_order": {"extrinsic_order", "transposed"},
    "transposed": {"transposed", "A_transposed", "A_for_AT"},
    "swapped_entries": {"swapped_entries", "extrinsic_order", "not_orthogonal"},
    "missing_row": {"missing_row"},
    "extra_row": {"extra_row", "dependent_row"},
    "nu_sign": {"nu_sign", "sign_flip"},
    "gamma_sign": {"gamma_sign", "sign_flip"},
}
"""Mutant code → the catalogue codes that name the wrong answer it makes: the same slip seen in the quantity asked (a
dropped ∂/∂t term of γ is "missing_tt_term", A omitted on one body in γ a missing centripetal term), or by the
property it breaks (one entry's sign in a rotation matrix: "not an orthogonal matrix"; −A: "det A = −1"; a sign in a
Newton update: "not a Newton–Raphson step"). Codes not listed here are named by themselves only.

This is the lenient reading (any code that names the same wrong answer); the strict count of the mutation table is
:data:`EQUIVALENT`'s."""

EQUIVALENT = {
    ("sign_flip", "nu_sign"): "a sign of the whole ν is ν's own sign code",
    ("sign_flip", "gamma_sign"): "a sign of the whole γ is γ's own sign code",
    ("nu_sign", "sign_flip"): "ν's sign is a sign slip",
    ("gamma_sign", "sign_flip"): "γ's sign is a sign slip",
    ("sign_flip", "left_handed"): "−A (every entry's sign) is the left-handed matrix, det = −1",
    ("sign_flip", "not_orthogonal"): "one entry's sign in a rotation matrix breaks AᵀA = I: the property named",
    ("sign_flip", "newton_step"): "a sign in the update Δq = −Φ_q⁻¹Φ is a wrong Newton–Raphson step",
    ("missing_term", "nu_missing"): "ν's only term (−Φ_t) dropped is ν = 0",
    ("missing_term", "missing_qt_term"): "γ's −2Φ_qt q̇ is a term; γ names which one",
    ("missing_term", "missing_tt_term"): "γ's −Φ_tt is a term; γ names which one",
    ("missing_term", "missing_chain_rule"): "the term ∂(A s')/∂φ dropped from a Jacobian entry is the chain rule lost",
    ("missing_term", "relative_speed"): "the carrier's φ̇_k dropped from φ̇_j leaves the speed relative to it",
    ("missing_term", "not_orthogonal"): "a term dropped from a rotation matrix's entry breaks AᵀA = I",
    ("missing_term", "newton_step"): "a term dropped from the update Δq is a wrong Newton–Raphson step",
    ("other_body", "swapped_bodies"): "body i's names for body j's throughout is i and j swapped",
    ("other_body", "swapped_points"): "the bodies' names exchanged moves each point to the other body",
    ("other_body", "wrong_data"): "the notebook prints the other body's value above; its detail names that body",
    ("swapped_bodies", "other_body"): "i and j swapped reads each body's coordinates as the other's",
    ("swapped_bodies", "swapped_points"): "i and j swapped moves each point to the other body",
    ("local_vector", "missing_chain_rule"): "s' for A s' (A left out) differentiates to no ∂A/∂φ term",
    ("local_vector", "wrong_frame"): "s' for A s' is a vector left in the body frame",
    ("local_vector", "missing_term"): "A left out of A s' φ̇² leaves no centripetal term in γ",
    ("A_transposed", "A_for_AT"): "one slip, a transpose: Aᵀ for A named from the other side",
    ("A_transposed", "transposed"): "one slip, a transpose: Aᵀ for A in a matrix answer",
    ("A_for_AT", "A_transposed"): "one slip, a transpose: A for Aᵀ named from the other side",
    ("A_for_AT", "transposed"): "one slip, a transpose: A for Aᵀ in a matrix answer",
    ("transposed", "A_transposed"): "a transposed rotation matrix is Aᵀ for A",
    ("transposed", "A_for_AT"): "a transposed rotation matrix is A for Aᵀ",
    ("factor_2_missing", "scaled"): "a factor 2 lost is the answer off by ½",
    ("factor_2_missing", "full_angle"): "χ/2 computed as χ is the / 2 lost",
    ("factor_2_missing", "not_orthogonal"): "½A is not a rotation matrix",
    ("factor_2_missing", "not_normalized"): "½p is not a unit vector",
    ("factor_2_extra", "scaled"): "a factor 2 too many is the answer off by 2",
    ("factor_2_extra", "not_orthogonal"): "2A is not a rotation matrix",
    ("factor_2_extra", "not_normalized"): "2p is not a unit vector",
    ("missing_square", "not_orthogonal"): "a square lost inside a rotation matrix's entry breaks AᵀA = I",
    ("swapped_entries", "extrinsic_order"): "ψ and φ exchanged are the angles read in the extrinsic order",
    ("swapped_entries", "not_orthogonal"): "two entries of a rotation matrix exchanged break AᵀA = I",
    ("extra_row", "dependent_row"): "the extra row is a combination of the others",
}
"""(the mutant's code, a code the verdict may give instead) → why that code names the same mistake. A mutant counts
as *named strictly* when the verdict names its own code or one of these; a name reached only because the wrong
answer happens to equal another catalogued mistake's value (:func:`classify`'s lenient reading) does not."""



def classify(result, mutant):
    """``"blind"`` when ``result`` (a CheckResult) passed the mutant, ``"named"`` when it names the mutant's mistake
    (:data:`SYNONYMS`), else ``"unnamed"`` — with the names given."""
    if result.passed:
        return "blind", ()
    given = tuple(c for c in (result.mistakes or ()) if c)
    ok = set().union(*(SYNONYMS.get(c, {c}) for c in {mutant.code} | set(mutant.also)))
    if any(c in ok for c in given):
        return "named", given
    return "unnamed", given


def strictly_named(result, mutant):
    """True when ``result`` refuses ``mutant`` with the code it stands for, or a code :data:`EQUIVALENT` declares
    equivalent to it (never through another mutant's or another reading's code)."""
    if result.passed:
        return False
    given = {c for c in (result.mistakes or ()) if c}
    return mutant.code in given or any((mutant.code, c) in EQUIVALENT for c in given)


def passing_mutants(mutants, answer_of, check, reference=None):
    """The mutants whose answer ``check`` passes (``check(answer).passed``): the blind spots of one item at one set
    of data — the one rule by which the try-its' draws (``kb.another``) and the exercises' variant draws refuse data.
    ``answer_of(mutant)`` makes the answer; with the numeric ``reference``, an answer farther from it than any
    checker's tolerance (a fifth of its largest entry; angles modulo 2π; −x too, p's other sign) is not graded, a
    shortcut that skips no mutant a check could pass. A mutant that fails to make an answer is no answer here."""
    ref = None if reference is None else np.asarray(reference, float)
    out = []
    for m in mutants:
        try:
            with np.errstate(all="ignore"):
                answer = answer_of(m)
                if ref is not None and not _may_pass(answer, ref):
                    continue
                if check(answer).passed:
                    out.append(m)
        except Exception:  # noqa: BLE001 — a mutant these data cannot evaluate (or the check refuses as unreadable)
            continue
    return out


def _may_pass(answer, ref):
    try:
        v = np.asarray(answer, float)
    except (TypeError, ValueError):
        return True  # not numbers: the check decides
    if v.size != ref.size:
        return True
    v = v.reshape(ref.shape)
    if not np.all(np.isfinite(v)):
        return False
    tol = 0.2 * max(1.0, float(np.max(np.abs(ref), initial=0.0)))
    near = (np.abs(v - ref) <= tol) | (np.abs(np.mod(v - ref + np.pi, 2 * np.pi) - np.pi) <= tol)
    return bool(np.all(near) or np.all(np.abs(v + ref) <= tol))


@dataclass
class Tally:
    """The outcomes of one item's mutants (a try-it, an exercise part): counts and the cases worth reading."""

    item: str
    mutants: int = 0
    named: int = 0
    strict: int = 0
    catalogue: int = 0
    unnamed: int = 0
    blind: int = 0
    blind_cases: list = field(default_factory=list)
    unnamed_cases: list = field(default_factory=list)

    def add(self, mutant, outcome, given=(), where="", why="", strict=False, catalogue=None):
        """Count one mutant; ``strict``: :func:`strictly_named` of its result; ``catalogue``: the same without the
        names a numeric try-it takes from its worked answer's own code slips (default: ``strict``)."""
        self.mutants += 1
        self.strict += bool(strict)
        self.catalogue += bool(strict if catalogue is None else catalogue)
        if outcome == "named":
            self.named += 1
        elif outcome == "blind":
            self.blind += 1
            self.blind_cases.append(f"{mutant.code} ({mutant.operator}) passes at {where}: {why}")
        else:
            self.unnamed += 1
            self.unnamed_cases.append(f"{mutant.code} ({mutant.operator}) at {where} named "
                                      f"{', '.join(given) or '—'}")


def format_table(tallies, detail=True):
    """The mutation table: one line per item (mutants, named, unnamed, blind spots), the totals, and — with
    ``detail`` — each blind spot and unnamed mutant under its item."""
    w = max([len(t.item) for t in tallies] + [5]) + 2
    lines = [f"{'item':<{w}} {'mutants':>7} {'named':>6} {'strict':>6} {'catal.':>6} {'unnamed':>7} {'blind':>5}"]
    for t in tallies:
        lines.append(f"{t.item:<{w}} {t.mutants:>7} {t.named:>6} {t.strict:>6} {t.catalogue:>6} {t.unnamed:>7} "
                     f"{t.blind:>5}")
        if detail:
            lines += [f"    BLIND   {c}" for c in t.blind_cases]
            lines += [f"    unnamed {c}" for c in t.unnamed_cases]
    n = sum(t.mutants for t in tallies)
    named = sum(t.named for t in tallies)
    strict, cat = sum(t.strict for t in tallies), sum(t.catalogue for t in tallies)
    lines.append(f"{'total':<{w}} {n:>7} {named:>6} {strict:>6} {cat:>6} {sum(t.unnamed for t in tallies):>7} "
                 f"{sum(t.blind for t in tallies):>5}   named {100.0 * named / max(n, 1):.1f} %, strictly "
                 f"{100.0 * strict / max(n, 1):.1f} %, by the catalogue alone {100.0 * cat / max(n, 1):.1f} %")
    return "\n".join(lines)


# ============================================================================================ naming a checker's wrong rows
def phi_equal(a, b, rtol):
    """Rows of Φ equal up to a constant factor, or both identically zero."""
    if scale_of(b) <= 1e-12:
        return scale_of(a) <= 1e-12
    return scale_match(a, b, rtol) is not None


def _finite(V):
    return V is not None and np.all(np.isfinite(V))


def _groups(target, c):
    """Each body's (coordinates, velocities) symbols of constraint ``c`` (for the other body's angle or rate)."""
    mech = target.mech
    q, out = list(mech.q), []
    for b in c.bodies:
        qs = list(mech.body_symbols(b.name))
        out.append((qs, [mech.qd[q.index(x)] for x in qs]))
    return out


def name_phi_rows(target, data, wrong, free, rtol):
    """Wrong rows that are another mutant of a reference row (:func:`kinbook.grading.mutants.row_mutants`: sin ↔
    cos, the other body's angle, an angle in degrees …): named by its code."""
    G = target.samples("generic")
    for j in list(free):
        left = [r for r in wrong if r.code is None]
        if not left:
            return
        cands = row_mutants(target.symbolic_row(j), groups=_groups(target, target.owner(j)))
        if not cands:
            continue
        vals = target.tape([e for _, _, e in cands])(G.Q, G.QD, G.T)["value"]
        for i, (code, _, _) in enumerate(cands):
            if not np.all(np.isfinite(vals[:, i])) or phi_equal(vals[:, i], data.R_G[:, j], rtol):
                continue
            hit = next((r for r in left if phi_equal(data.S_G[:, r.k], vals[:, i], rtol)), None)
            if hit is not None:
                hit.ref, hit.code = j, code
                free.remove(j)
                break


def name_derived_row(target, ex, r, own, S, expected, rtol):
    """The other mutants (:func:`kinbook.grading.mutants.row_mutants`) of the reference's Φ row carried through
    the derivation, and of the expected ν or γ row itself: (code, None, None) of the one the row equals."""
    if r.ref is None or own is not None or isinstance(r.ref, tuple):
        return None
    import sympy as sp  # import time: sympy only when needed

    Phi = target.symbolic_row(r.ref)
    if sp.count_ops(Phi) > 200:
        return None
    groups = _groups(target, target.owner(r.ref))
    f = 1.0 if r.factor is None or np.isnan(r.factor) else r.factor
    s = ex.s
    qty = quantity_of(ex.quantity)
    q_name = qty.name
    cands = row_mutants(f * Phi, groups=groups)
    vals = []
    if cands:
        d = target.tape([e for _, _, e in cands]).derived(s.Q, s.QD, s.T)
        vals += [(code, d["Phi_q"][:, i][:, ex.data.cols] if qty.per_coordinate else d[q_name][:, i][:, None])
                 for i, (code, _, _) in enumerate(cands)]
    if qty.right_hand_side:
        mech = target.mech
        q, qd, t = list(mech.q), list(mech.qd), mech.t
        syms = [x for x in q if x in Phi.free_symbols]
        D = lambda e: sum(sp.diff(e, x) * qd[q.index(x)] for x in syms) + sp.diff(e, t)  # noqa: E731
        expr = f * qty.expression(Phi, D, t)
        own_cands = row_mutants(expr, quantity=q_name, groups=groups)
        if own_cands:
            V = target.tape([e for _, _, e in own_cands])(s.Q, s.QD, s.T)["value"]
            vals += [(code, V[:, i][:, None]) for i, (code, _, _) in enumerate(own_cands)]
    for code, V in vals:
        if _finite(V) and not same(V, expected, rtol) and same(S, V, rtol):
            return code, None, None
    return None


def name_entries(target, ex, r, S, entries, rtol):
    """``entries`` with each wrong entry of a Φ_q row named by the mutant of its own symbolic entry it equals
    (a term's sign or a term dropped, sin ↔ cos, the other body's angle …: :func:`expression_mutants`)."""
    if r.ref is None or isinstance(r.ref, tuple):
        return entries
    import sympy as sp  # import time: sympy only when needed

    Phi = target.symbolic_row(r.ref)
    if sp.count_ops(Phi) > 200:
        return entries
    mech = target.mech
    groups = _groups(target, target.owner(r.ref))
    f = 1.0 if r.factor is None or np.isnan(r.factor) else r.factor
    s = ex.s
    out = list(entries)
    for i, code in enumerate(entries):
        if code != "wrong_value":
            continue
        expr = f * sp.diff(Phi, mech.q[ex.data.cols[i]])
        cands = [(m.code, m.value[0]) for m in expression_mutants([expr], groups=groups, keep_all=True)]
        if not cands:
            continue
        V = target.tape([e for _, e in cands])(s.Q, s.QD, s.T)["value"]
        E = ex.data.R[:, r.ref, i] * f if ex.data.R.ndim == 3 else None
        for k, (c, _) in enumerate(cands):
            if E is not None and same(V[:, k], E, rtol):
                continue
            if same(S[:, i], V[:, k], rtol):
                out[i] = c
                break
    return tuple(out)
