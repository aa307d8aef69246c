"""The textbook as data: what it prints, where it is wrong, and how to write in its notation.

:mod:`kinbook.book.errata` is the one list of the book's errata (stable ids such as ``"13.6-table-13.2"``),
each with evidence that kinbook computes. Notebooks, checkers and tests cite errata by id.
"""

from . import errata

__all__ = ["errata"]
