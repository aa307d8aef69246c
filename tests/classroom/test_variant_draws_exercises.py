"""The shipped exercises' variant draws refuse data under which a catalogued mutant passes (issue 29): 200 students'
variants of each exercise with parameters, drawn as ``kinbook variant`` and ``kinbook grade`` draw them
(:func:`kinbook.classroom.variant.student_parameters`). Every 5th is re-checked the long way — every mutant of every
part graded by the part's own check, no shortcut — and the draw repeats for the same student. The figures (draws,
students whose variant differs from the draw without the mutant rule) are printed.
"""

from pathlib import Path

import pytest

from kinbook.classroom.mutants import mutant_answer, part_mutants
from kinbook.classroom.notebook import find_parameters, load_source
from kinbook.classroom.variant import _seed, references, student_parameters
from kinbook.grading.item import draw

EXERCISES = sorted((Path(__file__).resolve().parents[2] / "exercises").glob("ex*.ipynb"))
WITH_PARAMETERS = [p for p in EXERCISES if find_parameters(load_source(p).nb) is not None]
STUDENTS = [f"student{k:03d}" for k in range(200)]


def _old_draw(source, student):
    """The draw before the mutant rule: the first seeded values the instructor's code runs with."""
    _, _, ranges, defaults = find_parameters(source.nb)
    for attempt in range(25):
        values = draw(ranges, defaults, _seed(source.exercise, student, attempt))
        try:
            references(source, values)
            return values
        except Exception:  # noqa: BLE001 — the next draw, as the old loop did
            continue
    return None


def test_the_exercises_with_parameters_are_found():
    assert {p.stem[:4] for p in WITH_PARAMETERS} >= {"ex09", "ex11"}


@pytest.mark.parametrize("path", WITH_PARAMETERS, ids=[p.stem[:4] for p in WITH_PARAMETERS])
def test_no_variant_draw_lets_a_catalogued_mutant_pass(path):
    source = load_source(path)
    changed, mutants = 0, 0
    for k, student in enumerate(STUDENTS):
        values = student_parameters(source, student)
        changed += values != _old_draw(source, student)
        if k % 5:
            continue
        assert student_parameters(source, student) == values  # the same student, the same variant
        for p in references(source, values):
            for m in part_mutants(p):
                mutants += 1
                assert not p.run(mutant_answer(m)).passed, (student, values, p.name, m.code, m.operator)
    print(f"\n{path.stem}: {len(STUDENTS)} draws, {changed} differ from the draw without the mutant rule, "
          f"{mutants} mutants re-checked on {len(STUDENTS[::5])} of them: none passes")
