"""An exercise part's mutants (:mod:`kinbook.grading.mutants`) and the answers a student making them hands in: what
``kinbook validate --mutations`` grades (:mod:`kinbook.classroom.validate.mutations`) and what a student's variant
draw refuses (:func:`blind_parts`, :func:`kinbook.classroom.variant.student_parameters`) — by the rule the try-its'
draws use too (:func:`kinbook.grading.mutant_names.passing_mutants`).
"""

from __future__ import annotations

import numpy as np

from ..grading import mutant_names as MN
from ..grading import mutants as MU
from ..grading.item import CHECKERS

__all__ = ["part_mutants", "mutant_answer", "blind_parts"]


def part_mutants(p, limit=None):
    """The mutants of one part's reference (its target's symbolic quantity, or its expected value)."""
    quantity = CHECKERS[p.check].quantity  # Φ, Φ_q, ν or γ for a symbolic check (kinbook.grading.quantities)
    if quantity is None:
        angles = bool(p.options.get("angles")) or getattr(p.expected, "kind", "") == "angles"
        found = MU.value_mutants(p.expected, angles=angles)
        if p.check == "euler_parameters":  # −p is p's other right answer (the same rotation)
            found = [m for m in found if m.operator != "sign of the whole answer"]
        return found
    return MU.reference_mutants(p.target, quantity, limit)


def mutant_answer(mutant):
    """The answer a student making ``mutant``'s mistake hands in: its numbers, or its rows as typed strings."""
    import sympy as sp  # import time: sympy only when needed

    v = mutant.value
    if isinstance(v, (np.ndarray, np.generic, float, int)):
        return v
    M = sp.Matrix(v)
    if M.shape[1] > 1:
        return [[str(M[i, j]) for j in range(M.shape[1])] for i in range(M.shape[0])]
    return [str(M[i, 0]) for i in range(M.shape[0])]


def blind_parts(parts, limit=None):
    """``[(part name, mutant)]`` of the catalogued mutants the parts' own checks pass (their references built for one
    student's values): empty for values that tell every mutant from the answer."""
    out = []
    for p in parts:
        expected = getattr(p, "expected", None)
        try:
            reference = None if expected is None else np.asarray(getattr(expected, "value", expected), float)
        except (TypeError, ValueError):
            reference = None
        out += [(p.name, m) for m in MN.passing_mutants(part_mutants(p, limit), mutant_answer, p.run, reference)]
    return out
