"""Per-student parameters and the grader's references.

:func:`student_parameters` draws a student's values from the ranges of the source's ``parameters(...)``
cell (:func:`kinbook.grading.item.draw`) with a seed derived from (exercise, student), so that the same student always gets the same values;
a draw is kept only when the instructor's own code runs with it (the mechanism assembles, the analysis
converges) and no catalogued mutant of any part passes its check there (:func:`kinbook.classroom.mutants.blind_parts`,
the try-its' rule: no 45° for a sin/cos question, no zero rate under a rate term); otherwise the next draw is tried.
A student whose first draw was fine keeps it: the seeds are the same, only a draw that would let a slip pass is
skipped.

:func:`references` is the grader's reading of a source notebook: it runs the source's code — without the
solutions, with the hidden checks — in the grader's process, from the copy read once by
:func:`~kinbook.classroom.notebook.load_source` (compiled once), and returns the declared
:class:`~kinbook.classroom.parts.Part` objects with their targets and expected values computed by kinbook.

"Variant" means one thing in kinbook: a student's own version of an exercise (its parameters drawn for that
student, :func:`variant`).
"""

from __future__ import annotations

import contextlib
import dis
import io
import warnings

from ...errors import GradingError, KinbookError
from ...grading.item import draw, seed_from
from ..ids import check_id
from ..mutants import blind_parts
from ..notebook import find_parameters, grader_code, load_source, student_notebook
from ..parts import parameters, part, recording

__all__ = ["student_parameters", "variant", "references", "check_student_id", "MAX_DRAWS"]

MAX_DRAWS = 25

def check_student_id(student):
    """Return ``student`` (NFC) if it is a student id by the one rule (:func:`kinbook.classroom.ids.check_id`), else
    raise :class:`~kinbook.errors.GradingError`."""
    return check_id(student)


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
            blind = blind_parts(references(source, values))
        except _VariantFails as exc:
            last = exc
            continue
        if not blind:
            return values
        last = "a slip would pass: " + ", ".join(f"{name}: {m.code} ({m.operator})" for name, m in blind[:3])
    raise GradingError(f"{source.exercise}: no parameters for student {student!r} in {MAX_DRAWS} draws make "
                       f"the exercise work (last failure: {last})")


def variant(source, student):
    """The student's own notebook (solutions removed, their parameters written in)."""
    student = check_student_id(student)
    source = load_source(source)
    return student_notebook(source, student_parameters(source, student), student)


def _exit(code=None):
    """``exit()``/``quit()`` in a source's code: SystemExit (refused, naming the cell) without closing the grader's
    stdin, as the interactive helpers of ``site`` do."""
    raise SystemExit(code)


def declared_parts(code):
    """The names of the parts a compiled cell declares, ``part("name", …)`` with the name written out (read from
    the code object's constants: the calls are there whether or not they ran)."""
    names, last = [], None
    for ins in dis.get_instructions(code):
        if ins.opname in ("LOAD_NAME", "LOAD_GLOBAL", "LOAD_ATTR", "LOAD_METHOD") and ins.argval == "part":
            last = "part"
        elif last == "part" and ins.opname == "LOAD_CONST" and isinstance(ins.argval, str):
            names.append(ins.argval)
            last = None
        elif ins.opname not in ("PUSH_NULL", "PRECALL", "CACHE"):
            last = None
    for const in code.co_consts:
        if hasattr(const, "co_code"):
            names += declared_parts(const)
    return names


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
    import matplotlib  # import time: matplotlib only when needed

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # import time: matplotlib only when needed

    ns = {"__name__": "__kinbook_reference__", "part": part, "parameters": parameters,
          "display": lambda *a, **k: None, "exit": _exit, "quit": _exit}
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
                except NameError as exc:
                    # a cell that uses the student's answers: nothing to build from it — unless it declares parts
                    # (they would vanish from the exercise) or is hidden checks (which only build references)
                    lost = sorted(set(declared_parts(compiled)) - {p.name for p in rec[before:]})
                    if kind == "hidden" or lost:
                        what = f"the part(s) {', '.join(lost)} it declares would be lost" if lost else (
                            "its hidden checks stop there")
                        raise GradingError(f"{source.exercise}: cell {index + 1} fails in the grader: NameError: {exc}"
                                           f" — {what}; the grader cannot use the student's names here") from exc
                except GradingError as exc:  # a declaration the instructor must fix (part(points=nan) …)
                    raise GradingError(f"{source.exercise}: cell {index + 1}: {exc}") from exc
                except KinbookError as exc:
                    raise _VariantFails(f"cell {index + 1}: {type(exc).__name__}: {exc}") from exc
                except Exception as exc:
                    raise GradingError(f"{source.exercise}: cell {index + 1} fails in the grader: "
                                       f"{type(exc).__name__}: {exc}") from exc
                except SystemExit:
                    raise GradingError(f"{source.exercise}: cell {index + 1} stops the interpreter (SystemExit: "
                                       "sys.exit, exit() or quit()); a source's code must run "
                                       "to its end — nothing was released, validated or graded") from None
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
