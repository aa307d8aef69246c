"""Per-student parameters and the grader's references.

:func:`student_parameters` draws a student's values from the ranges of the source's ``parameters(...)``
cell (:func:`kinbook.grading.item.draw`) with a seed derived from (exercise, student), so that the same student always gets the same values;
a draw is kept only when the instructor's own code runs with it (the mechanism assembles, the analysis
converges); otherwise the next draw is tried.

:func:`references` is the grader's reading of a source notebook: it runs the source's code — without the
solutions, with the hidden checks — in the grader's process, from the copy read once by
:func:`~kinbook.classroom.notebook.load_source` (compiled once), and returns the declared
:class:`~kinbook.classroom.parts.Part` objects with their targets and expected values computed by kinbook.

"Variant" means one thing in kinbook: a student's own version of an exercise (its parameters drawn for that
student, :func:`variant`).
"""

from __future__ import annotations

import contextlib
import io
import re
import warnings

from ...errors import GradingError, KinbookError
from ...grading.item import draw, seed_from
from ..notebook import find_parameters, grader_code, load_source, student_notebook
from ..parts import parameters, part, recording

__all__ = ["student_parameters", "variant", "references", "check_student_id", "STUDENT_ID", "MAX_DRAWS"]

MAX_DRAWS = 25

STUDENT_ID = re.compile(r"[A-Za-z0-9][A-Za-z0-9._@+-]{0,127}")
"""A student identifier a variant is written for: letters, digits and ``. _ @ + -``, starting with a letter or
digit, at most 128 characters — so that it is always one safe file name (no ``/``, no ``..`` on its own, no
hidden file)."""


def check_student_id(student):
    """Return ``student`` if it matches :data:`STUDENT_ID`, else raise :class:`~kinbook.errors.GradingError`."""
    if not isinstance(student, str) or not STUDENT_ID.fullmatch(student):
        raise GradingError(f"a student id must be letters, digits and . _ @ + - (starting with a letter or digit, at "
                           f"most 128 characters), got {str(student)[:80]!r}")
    return student


def _seed(exercise, student, attempt):
    return seed_from(f"{exercise}:{student}:{attempt}")


def student_parameters(source, student):
    """The parameter values of ``student`` (a dict), or None when the exercise has no parameters."""
    source = load_source(source)
    found = find_parameters(source.nb)
    if found is None:
        return None
    _, _, ranges, defaults = found
    last = None
    for attempt in range(MAX_DRAWS):
        values = draw(ranges, defaults, _seed(source.exercise, student, attempt))
        try:
            references(source, values)
            return values
        except _VariantFails as exc:
            last = exc
    raise GradingError(f"{source.exercise}: no parameters for student {student!r} in {MAX_DRAWS} draws make "
                       f"the exercise work (last failure: {last})")


def variant(source, student):
    """The student's own notebook (solutions removed, their parameters written in)."""
    check_student_id(student)
    source = load_source(source)
    return student_notebook(source, student_parameters(source, student), student)


class _VariantFails(GradingError):
    """The instructor's code fails with these parameters (a KinbookError: no assembly, no convergence…)."""


_cache = {}


def references(source, values=None):
    """The parts a source declares, with their references, for the given parameter values.

    Returns
    -------
    list of Part
        In declaration order; ``hidden`` is set on parts declared in hidden checks.
    """
    source = load_source(source)
    key = (source.sha256, repr(sorted((values or {}).items())))
    if key in _cache:
        return _cache[key]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ns = {"__name__": "__kinbook_reference__", "part": part, "parameters": parameters,
          "display": lambda *a, **k: None}
    parts = []
    try:
        with recording() as rec, warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()):
            warnings.simplefilter("ignore")
            for index, kind, compiled in grader_code(source, values):
                if compiled is None:
                    continue  # code around a solution region that does not stand alone
                before = len(rec)
                try:
                    exec(compiled, ns)  # the instructor's own code (trusted), never the student's
                except NameError:
                    pass  # a cell that uses the student's answers: nothing to build from it
                except GradingError as exc:  # a declaration the instructor must fix (part(points=nan) …)
                    raise GradingError(f"{source.exercise}: cell {index + 1}: {exc}") from exc
                except KinbookError as exc:
                    raise _VariantFails(f"cell {index + 1}: {type(exc).__name__}: {exc}") from exc
                except Exception as exc:
                    raise GradingError(f"{source.exercise}: cell {index + 1} fails in the grader: "
                                       f"{type(exc).__name__}: {exc}") from exc
                for p in rec[before:]:
                    p.hidden = kind == "hidden"
            parts = list(rec)
    finally:
        plt.close("all")
    names = [p.name for p in parts]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise GradingError(f"{source.exercise}: parts declared twice: {', '.join(sorted(dup))}")
    if not parts:
        raise GradingError(f"{source.exercise}: the notebook declares no part(...)")
    _cache[key] = parts
    return parts
