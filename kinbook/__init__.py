"""kinbook: computational kinematics of mechanisms in body coordinates, for teaching.

Planar kinematics (textbook chapter 13) lives in :mod:`kinbook.planar`, spatial kinematics with Euler
parameters (chapter 14) in :mod:`kinbook.spatial`; mechanism files are read by
:func:`kinbook.load`, and the book's example mechanisms by :func:`kinbook.examples.load`.
"""

from . import examples, planar, spatial
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
from .io import load, loads
from . import grading  # noqa: E402  (after the modules it grades with)
from .grading import set_language
from .notebook import setup as notebook_setup

__version__ = "0.1.0"


def __getattr__(name):
    # the notebooks' try-it helpers load the book package only when first used (import kinbook stays light)
    if name in ("try_it", "reveal"):
        from .book import tryits

        return getattr(tryits, name)
    raise AttributeError(f"module 'kinbook' has no attribute {name!r}")

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
