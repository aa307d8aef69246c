"""kinbook: computational kinematics of mechanisms in body coordinates, for teaching.

Planar kinematics (textbook chapter 13) lives in :mod:`kinbook.planar`, spatial kinematics with Euler
parameters (chapter 14) in :mod:`kinbook.spatial`; mechanism files are read by
:func:`kinbook.load`, and the book's example mechanisms by :func:`kinbook.examples.load`.
"""

import importlib

from .errors import (
    AnalysisError,
    AssemblyError,
    ConvergenceError,
    DeadPointError,
    DriverCountError,
    DriverValueError,
    ExpressionError,
    InputError,
    KinbookError,
    MechanismFileError,
    ModelError,
    RedundantConstraintsError,
    SingularJacobianError,
    UnknownBodyError,
    UnknownPointError,
)

__version__ = "0.1.0"

# Subpackages are imported when first used (PEP 562): `import kinbook` itself stays cheap — no sympy, no
# numpy — so a notebook, a command or a browser (Pyodide) starts at once; `kinbook.planar`, `from kinbook
# import spatial`, `kinbook.load(...)` work as before.
_SUBMODULES = ("examples", "exercises", "planar", "spatial", "grading", "core", "book", "files", "classroom")


_FROM = {"load": "files", "loads": "files", "notebook_setup": "book.display", "try_it": "book.tryits",
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


def set_language(lang):
    """Choose the language of grading feedback ("en" or "es"): see :func:`kinbook.grading.set_language`."""
    from .grading._i18n import set_language as _set

    _set(lang)


__all__ = [
    "load",
    "loads",
    "examples",
    "planar",
    "grading",
    "set_language",
    "notebook_setup",
    "spatial",
    "KinbookError",
    "ModelError",
    "UnknownBodyError",
    "UnknownPointError",
    "MechanismFileError",
    "InputError",
    "ExpressionError",
    "DriverValueError",
    "DriverCountError",
    "AnalysisError",
    "ConvergenceError",
    "SingularJacobianError",
    "RedundantConstraintsError",
    "DeadPointError",
    "AssemblyError",
]
