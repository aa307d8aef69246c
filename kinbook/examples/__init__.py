"""The textbook's example mechanisms, shipped as mechanism files.

>>> from kinbook import examples
>>> examples.names()[:4]
['ch13_example1', 'ch13_example2', 'ch13_example3', 'ch13_example4']
>>> examples.load("ch13_example1").n
12
"""

from __future__ import annotations

from importlib import resources

from ..errors import MechanismFileError

__all__ = ["load", "names", "path"]


def names():
    """Names of the shipped example mechanisms."""
    return sorted(p.name[:-5] for p in resources.files(__name__).iterdir() if p.name.endswith(".toml"))


def path(name):
    """Path of a shipped example's mechanism file (to read it or copy it as a template)."""
    if not isinstance(name, str) or name not in names():  # never a path outside the package
        raise MechanismFileError(f"no example mechanism {name!r} (available: {', '.join(names())})")
    p = resources.files(__name__) / f"{name}.toml"
    if not p.is_file():
        raise MechanismFileError(f"no example mechanism '{name}' (available: {', '.join(names())})")
    return p


def load(name):
    """Load a shipped example mechanism by name, e.g. ``"ch13_example1"``."""
    from ..files import loads  # import time: files loads numpy and sympy

    p = path(name)
    return loads(p.read_text(encoding="utf-8"), source=f"{name}.toml")
