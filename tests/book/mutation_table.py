"""What the mutation tables of the try-its and the exercises share (issue 29): every mutant of each reference
(kinbook.grading.mutants) graded by the real check on the notebook's (or the source's) data and on one drawn variant
— no mutant passes (0 blind spots) and at least 95 % are named by the code they stand for. The tables are split by
chapter (test_mutations_13, test_mutations_14, tests/classroom/test_mutations_exercises) so that pytest-xdist runs
them side by side; ``kinbook validate --mutations`` with its defaults (two variants, 60 mutants per part and data)
prints the figures kept in docs/instructors.md and benchmarks/README.md.
"""

from pathlib import Path

from kinbook.book.tryits import TRY_ITS, get
from kinbook.book.tryits.mutations import mutation_tallies
from kinbook.grading.mutant_names import format_table

LIMIT = 30
"""Mutants per part (or try-it) and data at most, every code kept (run time)."""
EXERCISES = sorted((Path(__file__).resolve().parents[2] / "exercises").glob("ex*.ipynb"))


def tryit_tallies(chapter):
    get("13-1/try-1")  # registers the try-its
    return mutation_tallies([id for id in TRY_ITS if id.startswith(chapter + "-")], variants=1, limit=LIMIT)


def check(tallies):
    """0 blind spots, ≥ 95 % named strictly (the verdict names the mutant's own code or a declared equivalent,
    kinbook.grading.mutant_names.EQUIVALENT), no item without mutants; the table in the failure message."""
    text = format_table(tallies)
    n = sum(t.mutants for t in tallies)
    named = sum(t.named for t in tallies)
    assert sum(t.blind for t in tallies) == 0, text
    assert n > 0 and sum(t.strict for t in tallies) >= 0.95 * n, text
    assert all(t.mutants for t in tallies), format_table(tallies, detail=False)
    return n, named
