"""kinbook: computational kinematics of mechanisms in body coordinates, for teaching.

Planar kinematics (textbook chapter 13) lives in :mod:`kinbook.planar`, spatial kinematics with Euler
parameters (chapter 14) in :mod:`kinbook.spatial`; mechanism files are read by
:func:`kinbook.load`, and the book's example mechanisms by :func:`kinbook.examples.load`.
"""

import importlib

from . import errors

# The error names, exported from their one list (kinbook.errors.__all__): `from kinbook import GradingError`.
globals().update((name, getattr(errors, name)) for name in errors.__all__)

__version__ = "0.1.0"

# Subpackages are imported when first used (PEP 562): `import kinbook` itself stays cheap — no sympy, no
# numpy — so a notebook, a command or a browser (Pyodide) starts at once; `kinbook.planar`, `from kinbook
# import spatial`, `kinbook.load(...)` work as before.
_SUBMODULES = ("examples", "exercises", "planar", "spatial", "grading", "core", "book", "files", "classroom")


_FROM = {"load": "files", "loads": "files", "set_language": "i18n", "get_language": "i18n", "notebook_setup": "book.display", "try_it": "book.tryits",
         "reveal": "book.tryits", "another": "book.tryits"}
_RENAMED = {"notebook_setup": "setup"}


def __getattr__(name):
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    if name in _FROM:
        return getattr(importlib.import_module(f".{_FROM[name]}", __name__), _RENAMED.get(name, name))
    raise AttributeError(f"module 'kinbook' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_SUBMODULES) | set(_FROM))


__all__ = [
    "load",
    "loads",
    "examples",
    "planar",
    "grading",
    "set_language",
    "notebook_setup",
    "spatial",
    *errors.__all__,
]
