"""Try-its of the chapter-14 notebooks (spatial kinematics); see :mod:`kinbook.book.tryits.ch13`."""

from __future__ import annotations
