"""The chapter-14 try-its refuse and name their mutants (issue 29; tests/book/mutation_table.py)."""

from .mutation_table import check, tryit_tallies


def test_chapter_14_tryits_refuse_and_name_their_mutants():
    tallies = tryit_tallies("14")
    assert len(tallies) == 15
    check(tallies)
