"""After the match: the steps a quantity declares (:attr:`~kinbook.grading.quantities.Quantity.after_match`,
:attr:`~kinbook.grading.quantities.Quantity.without_own`), each a function ``step(target, quantity, data, m,
rtol)`` that changes the matching in place:

* :func:`eg_rows` — spatial Φ_q rows 2Eā where 2(Eā + apᵀ) belongs, named before equivalents are sought;
* :func:`jacobian_equivalents` — Φ_q rows that are combinations of a joint's reference rows, right where the
  joint's rows may be recombined;
* :func:`factored_rows` — a Φ_q row c × the reference row with c ≠ ±1: the Jacobian of c·Φ_k (``scaled``);
* :func:`exchanged_rows` — ν and γ rows in each other's places: exchanged, not moved.
"""

from __future__ import annotations

from . import diagnose, match
from . import mistakes as M
from ._i18n import Msg
from .report import fmt

__all__ = ["STEPS", "eg_rows", "jacobian_equivalents", "factored_rows", "exchanged_rows"]


def eg_rows(target, quantity, data, m, rtol):
    """2Eā without 2apᵀ (:func:`kinbook.grading.diagnose.eg_rows`)."""
    diagnose.eg_rows(target, data, m, rtol)


def jacobian_equivalents(target, quantity, data, m, rtol):
    """Rows that recombine a joint's reference rows (:func:`kinbook.grading.match.jacobian_equivalents`), the
    book's own forms of each block included."""
    F = target.reference("assembled")["free_q"][:, :, data.cols]
    blocks = [target.block(c) for c in target.constraints]

    def book(block):
        c = target.constraints[blocks.index(block)]
        return M.book_form(target, c, "assembled", jacobian=data.cols)

    match.jacobian_equivalents(m, data.S, data.R, blocks, rtol, F, book)


def factored_rows(target, quantity, data, m, rtol):
    """A Φ_q row that is c × the reference row with c ≠ ±1 is the Jacobian of c·Φ_k: Φ_k is given (the book's
    form), so its derivative keeps every factor — a forgotten 2 of ∂(dᵀd)/∂q is a mistake, not a
    reformulation (−1, the sign of Φ_k, stays free). With ``phi=`` the student's own factor rules."""
    for r in m.rows:
        c = r.factor
        if r.status == "ok" and r.how == "multiple" and c is not None and abs(abs(c) - 1.0) > 1e-6:
            r.status, r.code, r.score = "wrong", "scaled", 0.0
            r.detail = Msg("d.jacobian_of", c=fmt(c), ref=target.label(r.ref))


def exchanged_rows(target, quantity, data, m, rtol):
    """Rows of ν and γ are tied to the rows of Φ they come from: the right rows in each other's places (sin and
    cos exchanged between the x and y rows of γ) are a mistake of those rows — named as exchanged, no credit —
    not the half-credit "rows out of the book's order" of a Φ. Φ_q keeps that half credit: its rows show which
    coordinate each entry belongs to."""
    for r in m.rows:
        if r.status == "moved" and r.k is not None and r.k < target.m:
            other = r.ref
            r.status, r.code, r.score, r.ref = "wrong", "swapped_entries", 0.0, r.k
            r.detail = Msg("d.row_of", other=target.label(other), row=target.label(r.k))
            r.context = M.contexts_of(target.owner(r.k), quantity)


STEPS = {f.__name__: f for f in (eg_rows, jacobian_equivalents, factored_rows, exchanged_rows)}
"""The steps by the names quantities declare."""


def run(names, target, quantity, data, m, rtol):
    """Run the named steps in order."""
    for name in names:
        STEPS[name](target, quantity, data, m, rtol)
