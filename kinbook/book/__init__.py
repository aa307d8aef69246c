"""The textbook as data and the notebooks' toolkit: what the book prints, where it is wrong, how to write in
its notation, how to check a printed formula, and the notebooks' "Try it" exercises.

- :mod:`~kinbook.book.printed` — the book's printed numbers and tables, typed once (only as the thing under test)
- :mod:`~kinbook.book.errata` — the one list of the book's errata, stable ids (``"13.6-table-13.2"``), evidence
- :mod:`~kinbook.book.notation` — the book's symbols, its two-body joints, a book-notation LaTeX printer
- :mod:`~kinbook.book.verify` — printed-vs-derived tables, finite-difference and second-derivative checks
- :mod:`~kinbook.book.tryits` — every notebook's "Try it": checker, target and worked answer as data
- :mod:`~kinbook.book.display` — the notebooks' display helpers (``kinbook.notebook_setup()``, ``show``, ``small``,
  ``agrees``) that keep stored outputs free of round-off
"""

from . import display, errata, notation, printed, verify
from .tryits import reveal, try_it

__all__ = ["display", "errata", "notation", "printed", "verify", "try_it", "reveal"]
