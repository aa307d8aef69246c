"""The chapter-13 try-its refuse and name their mutants (issue 29; tests/book/mutation_table.py)."""

from .mutation_table import check, tryit_tallies


def test_chapter_13_tryits_refuse_and_name_their_mutants():
    tallies = tryit_tallies("13")
    assert len(tallies) == 21
    check(tallies)
