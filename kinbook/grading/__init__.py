"""Auto-grading of students' hand-built Φ, Φ_q, ν, γ and numeric answers.

>>> import kinbook
>>> from kinbook.grading import check_phi
>>> mech = kinbook.examples.load("ch13_example1")
>>> r = check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], mech.constraint("1"))
>>> r.passed, r.score
(True, 1.0)

Public API: :func:`check_phi`, :func:`check_jacobian`, :func:`check_nu`, :func:`check_gamma`,
:func:`check_value`, :func:`check_rotation`, :func:`check_euler_parameters`, :data:`CHECKERS` (the checkers by
name), :class:`CheckResult`, :mod:`expected` (expected numbers that name their mistakes), the mistake
catalogue (:data:`MISTAKES`, :func:`explain`), the feedback language (:func:`set_language`), and
:func:`nbgrader_score` and :func:`assert_passed` for nbgrader and otter-grader tests (:mod:`.lms`). Exercises
(graded parts, per-student parameters) are declared in notebooks with :mod:`kinbook.classroom`.

A check runs one way through small stages, each its own module: read (the safe reader) → sample → evaluate
→ match (the one equivalence rule) → diagnose (the mistake catalogue) → report (:mod:`kinbook.grading.checks`).
"""

from . import checks, expected, rotation_values, values
from ._i18n import get_language, set_language
from .catalogue import MISTAKES, explain
from .echo import echoed
from .lms import assert_passed, nbgrader_score
from .result import CheckResult, RowResult

# the package's checkers show the answer as they read it, before the verdict (kinbook.grading.echo)
check_phi = echoed(checks.check_phi, "Phi")
check_jacobian = echoed(checks.check_jacobian, "Phi_q")
check_nu = echoed(checks.check_nu, "nu")
check_gamma = echoed(checks.check_gamma, "gamma")
check_value = echoed(values.check_value)
check_rotation = echoed(rotation_values.check_rotation)
check_euler_parameters = echoed(rotation_values.check_euler_parameters)

CHECKERS = {
    "phi": check_phi,
    "jacobian": check_jacobian,
    "nu": check_nu,
    "gamma": check_gamma,
    "value": check_value,
    "rotation": check_rotation,
    "euler_parameters": check_euler_parameters,
}
"""The checkers by the names exercises use for them."""

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
    "CHECKERS",
    "CheckResult",
    "RowResult",
    "MISTAKES",
    "explain",
    "expected",
    "set_language",
    "get_language",
]
