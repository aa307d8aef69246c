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

A check runs one way through small stages, each one concept in one module. The modules, in pipeline order:

* the face — ``checks`` (check_phi, check_jacobian, check_nu, check_gamma: the pipeline of Φ, Φ_q, ν, γ),
  ``item`` (one graded item and the table of checkers), ``quantities`` (Φ, Φ_q, ν, γ declared once);
* target — ``target`` (what is graded against: a mechanism or one constraint, its cached reference);
* read — ``read`` (the safe reader of answers: text, sympy, a function, numbers; and the answer as it was read,
  shown before the verdict), ``rounding`` (decimals that are the exercise's constants rounded);
* sample — ``sample`` (seeded configurations on the manifold);
* evaluate — ``evaluate`` (answer and reference at the samples), ``jets`` (values and derivatives of an
  expression without deriving it);
* match — ``match`` (the one equivalence rule), ``equivalence`` (when an answer row is a reference row: the
  tolerances and the constant-multiple rule, equivalent formulations and vanishing factors), ``factors`` (the
  real zeros of a row's factors over the whole domain, solved or searched);
* after-match — ``aftermatch`` (the steps a quantity declares);
* diagnose — ``diagnose`` (naming the mistake), ``mistakes`` (wrong answers generated from the reference),
  ``slips`` (more of them), ``misprints`` (the book's misprinted formulas), ``turns`` (a row that measures no
  angle turned by whole turns);
* witness — ``witness`` (rows checked again where no one could have looked);
* diagnose, continued — ``mutant_names`` (names for the slips the mutants stand for);
* report — ``report`` (the verdict: CheckResult, RowResult, and how they are written), ``catalogue`` (every
  mistake's code, title and hint), ``_i18n`` (sentences written when shown);
* numbers — ``numbers`` (read, tolerances, compare entry by entry, name the slip), under ``values``
  (check_value), ``rotation_values`` (check_rotation, check_euler_parameters), ``newton`` (check_iterates) and
  ``expected`` (expected numbers that know their mistakes);
* validation — ``mutants`` (the reference turned into the mistakes students make, each with its code: what
  ``kinbook validate --mutations`` grades through the real checkers);
* outside tools — ``lms`` (nbgrader and otter-grader tests).
"""

import importlib

from .item import CHECKERS

# The names load when first used (PEP 562), as the package face's do: a module that needs only the checker
# table or the item model (the classroom's ``part``, imported in every student's sandboxed kernel) does not load
# the checkers, sympy and the catalogue.
_FROM = {
    "check_phi": "checks", "check_jacobian": "checks", "check_nu": "checks", "check_gamma": "checks",
    "check_value": "values", "check_rotation": "rotation_values", "check_euler_parameters": "rotation_values",
    "nbgrader_score": "lms", "assert_passed": "lms", "CheckResult": "report", "RowResult": "report",
    "MISTAKES": "catalogue", "explain": "catalogue", "set_language": "_i18n", "get_language": "_i18n",
}


_CHECKS = {"check_phi": "phi", "check_jacobian": "jacobian", "check_nu": "nu", "check_gamma": "gamma",
           "check_value": "value", "check_rotation": "rotation", "check_euler_parameters": "euler_parameters"}
"""The package's checkers are the table's: their results show the answer as it was read (:func:`.read.echoed`)."""


def __getattr__(name):
    if name in _CHECKS:
        return CHECKERS[_CHECKS[name]].function
    if name in _FROM:
        return getattr(importlib.import_module(f".{_FROM[name]}", __name__), name)
    if name == "expected":
        return importlib.import_module(".expected", __name__)
    raise AttributeError(f"module 'kinbook.grading' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_FROM) | {"expected"})


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
