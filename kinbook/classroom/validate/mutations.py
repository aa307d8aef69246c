"""``kinbook validate --mutations SOURCE``: the exercise tested the way a student will break it.

Every part's reference is turned into the mistakes students make (:mod:`kinbook.grading.mutants`: each term's
sign, sin ↔ cos, the other body's angle, a term dropped, degrees, a factor 2, Aᵀ for A, a driver row left out …)
and each mutant is graded by the part's own check (:meth:`kinbook.classroom.parts.Part.run`, what ``kinbook grade``
runs), on the source's data and on the variants of a few sample students. A mutant that passes is a **blind spot**;
one refused with "wrong value" or with another mistake's name is **unnamed**. The author's own question tests
(``part(..., tests=[...])``) are run too: each wrong answer must be refused and named by its declared code, each
right answer in another form must pass.
"""

from __future__ import annotations

from ...grading import mutant_names as MN
from ...grading import mutants as MU
from ...grading.item import CHECKERS

__all__ = ["mutation_tallies", "part_mutants"]

ANGLES = ("rotation", "euler_parameters")


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


def _answer(mutant):
    import numpy as np
    import sympy as sp

    v = mutant.value
    if isinstance(v, (np.ndarray, np.generic, float, int)):
        return v
    M = sp.Matrix(v)
    if M.shape[1] > 1:
        return [[str(M[i, j]) for j in range(M.shape[1])] for i in range(M.shape[0])]
    return [str(M[i, 0]) for i in range(M.shape[0])]


def mutation_tallies(source, *, students=None, variants=2, limit=None, progress=None):
    """Per part, a :class:`~kinbook.grading.mutants.Tally` of its mutants on the source's data and on the variants
    of ``students`` (default: the first ``variants`` of :data:`~kinbook.classroom.validate.SAMPLE_STUDENTS` when
    the exercise has parameters); and the question tests' failures.

    Returns
    -------
    (list of Tally, list of str)
    """
    from ..notebook import find_parameters, load_source
    from ..variant import references, student_parameters
    from . import SAMPLE_STUDENTS, question_tests

    src = load_source(source)
    datas = [("the source's data", None)]
    if find_parameters(src.nb) is not None:
        for s in (list(students) if students else list(SAMPLE_STUDENTS[:variants])):
            datas.append((f"{s}'s variant", student_parameters(src, s)))
    tallies, failures = {}, []
    for where, values in datas:
        for p in references(src, values):
            tally = tallies.setdefault(p.name, MN.Tally(f"{src.exercise}:{p.name}"))
            found = part_mutants(p, limit)
            if limit is not None:
                found = MU.sample(found, limit)
            for m in found:
                result = p.run(_answer(m))
                outcome, given = MN.classify(result, m)
                strict = MN.strictly_named(result, m)
                tally.add(m, outcome, given, where, "the checker lets it through", strict=strict, catalogue=strict)
            failures += [text for ok, text in question_tests(p, where) if not ok]
    out = list(tallies.values())
    if progress:
        for t in out:
            progress(t)
    return out, failures
