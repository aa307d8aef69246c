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
from ..mutants import mutant_answer, part_mutants
from ..notebook import find_parameters, load_source
from ..variant import references, student_parameters
from . import SAMPLE_STUDENTS, question_tests

__all__ = ["mutation_tallies", "part_mutants"]


def mutation_tallies(source, *, students=None, variants=2, limit=None, progress=None):
    """Per part, a :class:`~kinbook.grading.mutants.Tally` of its mutants on the source's data and on the variants
    of ``students`` (default: the first ``variants`` of :data:`~kinbook.classroom.validate.SAMPLE_STUDENTS` when
    the exercise has parameters); and the question tests' failures.

    Returns
    -------
    (list of Tally, list of str)
    """
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
                result = p.run(mutant_answer(m))
                outcome, given = MN.classify(result, m)
                strict = MN.strictly_named(result, m)
                tally.add(m, outcome, given, where, "the checker lets it through", strict=strict, catalogue=strict)
            failures += [text for ok, text in question_tests(p, where) if not ok]
    out = list(tallies.values())
    if progress:
        for t in out:
            progress(t)
    return out, failures
