"""kinbook's checkers inside nbgrader and otter-grader tests.

Both tools run an instructor's test code in the student's kernel and look only at how that code ends: nbgrader
gives a test cell the number shown as the cell's result (``execute_result``), full marks when the cell shows
anything else or nothing, and 0 when it raises or writes to stderr; otter passes a test case unless it raises.
A bare :class:`~kinbook.grading.CheckResult` fits neither (shown as a cell's result, nbgrader reads it as "not a
number": full marks), so two helpers turn a checker's verdict into what each tool reads:

- :func:`nbgrader_score` (nbgrader, partial credit): shows the checker's verdict and publishes the credit as the
  cell's result itself, wherever it stands in the cell;
- :func:`assert_passed` (otter, or any exception-based test: all or nothing): raises ``AssertionError`` carrying
  the checker's messages.

Both accept only a ``CheckResult``: a bool, a number or a string is refused, so that a verdict without its
messages (or a score on another scale) cannot be passed on by mistake. docs/lms.md shows complete notebooks.

>>> import kinbook
>>> from kinbook.grading import assert_passed, check_phi
>>> joint = kinbook.examples.load("ch13_example1").constraint("1")
>>> assert_passed(check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], joint))
>>> assert_passed(check_phi(["x1 - x2 - cos(phi2)", "y1 - y2 + sin(phi2)"], joint))
Traceback (most recent call last):
...
AssertionError: CheckResult(Φ: failed, score=0.50, mistakes=['sign_flip'])
  your answer, as read: [x1 - x2 - cos(phi2), y1 - y2 + sin(phi2)]
  Φ: 1 of 2 rows correct (score 0.50).
...
"""

from __future__ import annotations

import math
import numbers

from .report import CheckResult

__all__ = ["nbgrader_score", "assert_passed", "nbgrader_credit"]

# The cells (execute requests) that already published a credit: nbgrader reads only the first result.
_published = set()


def _require_result(result, who):
    if not isinstance(result, CheckResult):
        raise TypeError(
            f"{who}: expected the CheckResult a kinbook checker returns (check_phi(...), check_value(...) …), "
            f"got {type(result).__name__} {result!r:.60}"
        )
    score = result.score
    if isinstance(score, bool) or not isinstance(score, numbers.Real) or not 0.0 <= float(score) <= 1.0:
        raise ValueError(f"{who}: the CheckResult's score must be a number in [0, 1], got {score!r}")
    if not result.passed and float(score) >= 1.0:
        raise ValueError(f"{who}: inconsistent CheckResult: not passed but score {score!r} (mistakes {result.mistakes})")


def nbgrader_credit(result, points):
    """The credit, in points, that :func:`nbgrader_score` publishes for ``result``.

    Parameters
    ----------
    result : CheckResult
    points : int or float
        The test cell's points (positive, finite; not a bool).

    Returns
    -------
    credit : float
        ``points`` when the check passed; otherwise ``result.score * points`` rounded *down* to 0.01, so that a
        failed check never rounds up to full marks.

    Examples
    --------
    >>> from kinbook.grading import CheckResult
    >>> nbgrader_credit(CheckResult(True, 1.0), 4), nbgrader_credit(CheckResult(False, 0.5), 4)
    (4.0, 2.0)
    >>> nbgrader_credit(CheckResult(False, 0.999), 4), nbgrader_credit(CheckResult(False, 2 / 3), 4)
    (3.99, 2.66)
    """
    _require_result(result, "nbgrader_credit")
    if isinstance(points, bool) or not isinstance(points, numbers.Real) or not math.isfinite(points) or points <= 0:
        raise ValueError(f"nbgrader_credit: points must be a positive number (the test cell's points), got {points!r}")
    if result.passed:
        return float(points)
    # round() first absorbs binary noise (0.29 * 100 = 28.999…), floor() then never rounds up
    return math.floor(round(float(result.score) * float(points) * 100, 6)) / 100


class _Credit:
    """What the test cell shows as its result: the credit as a bare number, whatever the display settings."""

    __slots__ = ("text",)

    def __init__(self, credit):
        self.text = repr(float(credit))

    def __repr__(self):
        return self.text

    def _repr_pretty_(self, printer, cycle):
        printer.text(self.text)


def nbgrader_score(result, points):
    """Grade an nbgrader autograder-test cell with a kinbook checker (partial credit).

    Shows the checker's verdict (its messages, as in a notebook) and publishes the credit — ``points`` when the
    check passed, ``result.score * points`` rounded down to 0.01 otherwise — as the cell's result, which is what
    nbgrader reads. The credit is published when the function runs, so it is the cell's result wherever the
    call stands in the cell and whatever the cell ends with; the function returns None.

    Parameters
    ----------
    result : CheckResult
        What a kinbook checker returned (``check_phi(Phi_OA, joint)``). Anything else raises ``TypeError``.
    points : int or float
        The cell's points: **the same number as in the cell's nbgrader metadata** (the "Autograder tests" cell's
        points). nbgrader cannot tell the kernel a cell's metadata; ``nbgrader validate`` on the source notebook
        fails when the two differ (a correct answer scores less than the cell's points, or more).

    Raises
    ------
    TypeError
        ``result`` is not a CheckResult (a bool, a score, a string).
    ValueError
        ``points`` is not a positive number; or the cell ends with ``;`` (IPython would hide the result, and
        nbgrader would give full marks).
    RuntimeError
        Called outside a Jupyter/IPython kernel, or twice in one cell (nbgrader reads only the first result:
        put each graded check in its own test cell).

    Notes
    -----
    nbgrader gives 0 to a test cell that raises or writes to stderr, so an undefined answer variable
    (``NameError``) scores 0. docs/lms.md shows the whole notebook.
    """
    credit = nbgrader_credit(result, points)
    from IPython import get_ipython  # here, not at import: kinbook.grading must import without IPython

    shell = get_ipython()
    if shell is None:
        raise RuntimeError(
            "nbgrader_score publishes the test cell's result and runs only in a Jupyter kernel; "
            "outside one use assert_passed(result)"
        )
    hook = shell.displayhook
    if hook.quiet():
        raise ValueError("nbgrader_score: the test cell ends with ';', which hides the cell's result; remove the ';'")
    header = getattr(shell, "parent_header", None) or {}
    cell = header.get("msg_id") or ("count", shell.execution_count)
    if cell in _published:
        raise RuntimeError(
            "nbgrader_score was already called in this cell: nbgrader reads only the first result, "
            "so give each graded check its own autograder-test cell"
        )
    _published.add(cell)
    from IPython.display import display  # optional dependency: IPython (the grading extra)

    display(result)
    hook(_Credit(credit))


def assert_passed(result):
    """Raise ``AssertionError`` with the checker's messages unless ``result`` passed (otter, pytest, nbgrader).

    For exception-based tests, all or nothing: an otter test case, a pytest test, an nbgrader test cell without
    partial credit. The error's message is the checker's verdict (the catalogued mistakes and hints), which
    otter and nbgrader put in the student's feedback.

    Parameters
    ----------
    result : CheckResult
        What a kinbook checker returned. Anything else raises ``TypeError`` (``assert_passed(result.passed)``
        would drop the messages).
    """
    _require_result(result, "assert_passed")
    if not result.passed:
        raise AssertionError(repr(result))
