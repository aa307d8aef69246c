"""The 12 shipped exercises refuse and name the mutants of every part (issue 29; tests/book/mutation_table.py),
and their question tests pass."""

from kinbook.classroom.validate.mutations import mutation_tallies

from ..book.mutation_table import EXERCISES, LIMIT, check


def test_every_exercise_part_refuses_and_names_its_mutants():
    tallies, failures = [], []
    for source in EXERCISES:
        found, failed = mutation_tallies(source, variants=1, limit=LIMIT)
        tallies += found
        failures += failed
    assert len({t.item.split(":")[0] for t in tallies}) == len(EXERCISES) == 12
    assert not failures
    check(tallies)
