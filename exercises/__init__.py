"""The twelve shipped exercises: instructor source notebooks (docs/instructors.md), installed with kinbook.

In a checkout this folder is ``exercises/``; installed, it is the package ``kinbook.exercises`` (setup.py maps
the one onto the other, in an editable install too), so an instructor who installed kinbook with pip copies
the notebooks out with ``kinbook exercises copy NAME DIR`` — or :func:`copy` — and releases the copy.

>>> from kinbook import exercises
>>> exercises.names()[:2]
['ex01-revolute-joint-phi', 'ex02-planar-joint-types']
>>> exercises.path("ex07").name
'ex07-jacobian.ipynb'
"""

from __future__ import annotations

import os
from importlib import resources

# absolute imports: pytest's doctest collection imports this file as the top-level module ``exercises`` too
from kinbook.core.atomic import atomic_write
from kinbook.errors import InputError, WriteError

__all__ = ["names", "path", "copy"]


def names():
    """Names of the shipped exercises (their file names without ``.ipynb``), in order."""
    return sorted(p.name[:-6] for p in resources.files("kinbook.exercises").iterdir()
                  if p.name.endswith(".ipynb") and p.is_file())


def _name(name):
    """The full name of an exercise given by its full name or a prefix of it only it has (``"ex07"``)."""
    if not isinstance(name, str):
        raise InputError(f"an exercise is named by a string, got {type(name).__name__}")
    available = names()
    if name.endswith(".ipynb"):
        name = name[:-6]
    if name in available:
        return name
    found = [n for n in available if n.startswith(name + "-")] if name else []
    if len(found) == 1:
        return found[0]
    raise InputError(f"no shipped exercise {name[:80]!r} (available: {', '.join(available)}; a prefix such as "
                     "'ex07' is enough)")


def path(name):
    """The shipped notebook of exercise ``name`` (a full name or its ``exNN`` prefix), as a readable resource."""
    return resources.files("kinbook.exercises") / f"{_name(name)}.ipynb"


def copy(name, directory):
    """Copy exercise ``name`` into ``directory`` (created if missing) and return the new file's path.

    An existing file of that name is never overwritten (it may be the instructor's edited copy): it is an
    :class:`~kinbook.errors.InputError`.
    """
    source = path(name)
    directory = os.fspath(directory)
    if os.path.exists(directory) and not os.path.isdir(directory):
        raise InputError(f"cannot copy exercise {source.name!r} into {directory!r}: it is not a directory")
    target = os.path.join(directory, source.name)
    try:  # whole or not at all (a full disk leaves no 0-byte notebook that a retry would refuse to overwrite)
        atomic_write(target, source.read_bytes(), overwrite=False)
    except WriteError as exc:
        if "already exists" in str(exc):
            raise InputError(f"{target!r} already exists: not overwritten (remove it, or copy into another "
                             "directory)") from None
        raise
    return target
