"""The options of a grading run, checked for callers of the library as the command line checks them."""

from __future__ import annotations

import numpy as np

from ..errors import GradingError

__all__ = ["check_options"]


def check_options(*, timeout=None, memory=None, jobs=None, **flags):
    """The grading options as the command line checks them, for callers of the library too: ``timeout`` and
    ``memory`` positive finite numbers, ``jobs`` a whole number from 1 to 1024, every flag True or False (a
    truthy text such as ``"no"`` would switch it on). Raises :class:`~kinbook.errors.GradingError` naming the
    option."""
    for name, value in (("timeout", timeout), ("memory", memory)):
        if value is None:
            continue
        ok = not isinstance(value, (bool, np.bool_)) and isinstance(value, (int, float, np.integer, np.floating))
        if not ok or not np.isfinite(value) or value <= 0:
            raise GradingError(f"`{name}` must be a positive finite number, got {value!r}"[:200])
    if jobs is not None and (isinstance(jobs, (bool, np.bool_)) or not isinstance(jobs, (int, np.integer))
                             or not 1 <= jobs <= 1024):
        raise GradingError(f"`jobs` must be a whole number from 1 to 1024, got {jobs!r}"[:200])
    for name, value in flags.items():
        if not isinstance(value, (bool, np.bool_)):
            raise GradingError(f"`{name}` must be True or False, got {value!r}"[:200])
