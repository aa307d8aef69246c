"""Auto-grading of students' hand-built Φ, Φ_q, ν, γ and numeric answers (issue #4).

>>> import kinbook
>>> from kinbook.grading import check_phi
>>> mech = kinbook.examples.load("ch13_example1")
>>> r = check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], mech.constraint("1"))
>>> r.passed, r.score
(True, 1.0)

Public API: :func:`check_phi`, :func:`check_jacobian`, :func:`check_nu`, :func:`check_gamma`,
:func:`check_value`, :func:`check_rotation`, :func:`check_euler_parameters`, :class:`CheckResult` and the
mistake catalogue (:data:`MISTAKES`, :func:`explain`); :func:`nbgrader_score` and :func:`assert_passed` for
nbgrader and otter-grader tests (:mod:`.lms`). Exercises (graded parts, per-student parameters) are
declared in notebooks with :mod:`kinbook.classroom`.
"""

from ._i18n import get_language, set_language
from .catalogue import MISTAKES, explain
from .checks import check_gamma, check_jacobian, check_nu, check_phi
from .lms import assert_passed, nbgrader_score
from .result import CheckResult, RowResult
from .values import check_euler_parameters, check_rotation, check_value

__all__ = [
    "check_phi",
    "check_jacobian",
    "check_nu",
    "check_gamma",
    "check_value",
    "check_rotation",
    "check_euler_parameters",
    "nbgrader_score",
    "assert_passed",
    "CheckResult",
    "RowResult",
    "MISTAKES",
    "explain",
    "set_language",
    "get_language",
]
