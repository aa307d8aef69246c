"""An erratum and the evidence that kinbook computes for it, and the small measures the evidence functions share."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..display import small, tolerance_text

__all__ = ["Erratum", "Evidence", "KINDS", "below", "compare"]


@dataclass(frozen=True)
class Evidence:
    """What an evidence function measured.

    Attributes
    ----------
    text : str
        One or two sentences with the numbers; formulas as inline TeX between dollars, in the book's notation.
    printed_error : float
        Size of the discrepancy of the book's version (0 would mean the book is right).
    corrected_error : float
        Size of the discrepancy of the corrected version (should be at rounding level).
    tolerance : float
        What "agrees" means for the corrected version: rounding level for a formula, the printed digits (1e-4)
        where the book's own numbers are part of the comparison.
    """

    text: str
    printed_error: float
    corrected_error: float = 0.0
    tolerance: float = 1e-9


KINDS = ("number", "formula", "sign", "typo", "inconsistency", "wording")
"""What an erratum is, each kind by its definition:

* ``number`` — a printed value that the computation it reports does not give;
* ``formula`` — a wrong formula: a wrong term, factor, point or shape, which changes what is computed;
* ``sign`` — a sign slip alone (in a formula or a number);
* ``typo`` — a slip of the pen in a formula whose intent the text around it states: one letter, index, prime,
  accent or operator written for another (x_4 for x_3, η for ξ, s for s', a dropped tilde or minus);
* ``inconsistency`` — the book prints one thing in two places and the two disagree (an assembled system that
  repeats neither its own row nor that row's slips);
* ``wording`` — wrong words: a reference, a label, a claim in prose, notation."""


@dataclass(frozen=True)
class Erratum:
    """One place where the book differs from what kinbook derives or computes.

    Only what the book prints counts: a passage it strikes through is not printed (a struck-through formula is
    never an erratum, nor is a struck-through sentence the anchor of one)."""

    id: str
    where: str  # the title: prose with inline TeX between dollars, in the book's notation ("$\Phi_8$ simplified")
    printed: str
    correct: str
    kind: str  # one of KINDS
    evidence: Callable[[], Evidence] | None = field(default=None, repr=False)
    note: str = ""  # prose with inline TeX between dollars, as ``where``

    def check(self):
        """Run the evidence function (``None`` for wording errata)."""
        return None if self.evidence is None else self.evidence()


def below(err, tol=1e-12):
    """"< 1e-12" for a residual at round-off level, else its value."""
    return f"< {tolerance_text(tol)}" if abs(err) < tol else f"= {small(err)}"


def compare(samples):
    """max |printed − reference| and max |corrected − reference| over (printed, corrected, reference) rows, each
    three numbers or three arrays of one shape (the maximum is then over every entry)."""
    a = np.array(samples, dtype=float)
    return float(np.max(np.abs(a[:, 0] - a[:, 2]))), float(np.max(np.abs(a[:, 1] - a[:, 2])))
