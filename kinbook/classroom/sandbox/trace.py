"""Reference use as it ran: calls into kinbook's reference, observed in the student's kernel (issue 36).

The grader reads reference use from the submitted code (:mod:`kinbook.classroom.reference_use`), and a spelling the
reading does not follow — IPython's ``>>>`` prompts, ``;exec``, ``__getattribute__``, ``reduce(getattr, …)``, a
computed ``attrgetter``, a ``match`` class pattern, ``sympify(..., locals=)``, ``timeit(..., globals=)`` — hid it.
Here the calls themselves are seen, whatever spelled them: before the notebook's first cell, the worker has the kernel
run :func:`setup`, which

* seeds every random generator a notebook may use (``random``, ``numpy.random``, sympy's) from the student's id, so
  that a notebook drawing numbers gives each student their own and the same on every run;
* wraps the exercise's reference functions and methods — the names :func:`kinbook.classroom.reference_use
  .exercise_calls` gives, found *in kinbook's own modules and classes only* — so that each call records its result
  and the code cell it ran in (the worker says which after each one). A student's own function or class with the same name is
  never wrapped, so never reported as the library's.

After each cell the worker asks :func:`report` which answers *are* (the very object, not an equal one) a result of
such a call, and in which cell. Identity, not equality: an honest answer typed by hand that happens to equal the
reference is never reported; values that are shared objects whoever makes them (numbers, strings, sympy's atoms and
cached expressions) are never matched. What is kept is bounded (:data:`MAX_RESULTS` results, the latest), and so is
the report the grader reads back (names it asked for, a key of at most 200 characters, a cell number): it is data,
checked field by field by the grading process. It runs inside the sandbox, so a student can forge it — but only to
report a reference use of their own; the reading of the code (above) does not depend on it.
"""

from __future__ import annotations

import collections
import importlib
import json
import pkgutil
import random
import sys
import types

__all__ = ["setup", "report", "load_reference_modules", "MAX_RESULTS", "REFERENCE_PACKAGES"]

#: Results of reference calls kept for :func:`report` (the latest; an older one is forgotten).
MAX_RESULTS = 256
_results = collections.deque(maxlen=MAX_RESULTS)
_wrapped = {}
_cell = [1]  # the code cell running (from 1): set by the worker's reading after each cell


#: The packages whose functions and classes can be the reference (every module of them is imported by the zygote,
#: so that :func:`setup` finds them all before the first cell; kinbook imports its parts lazily).
REFERENCE_PACKAGES = ("kinbook.core", "kinbook.planar", "kinbook.spatial", "kinbook.examples", "kinbook.grading")


def load_reference_modules():
    """Import every module of :data:`REFERENCE_PACKAGES` (and ``kinbook.files``)."""
    importlib.import_module("kinbook.files")
    for package in REFERENCE_PACKAGES:
        module = importlib.import_module(package)
        for info in pkgutil.walk_packages(module.__path__, package + "."):
            importlib.import_module(info.name)


def setup(seed, functions=(), methods=()):
    """Seed the random generators and wrap the reference's ``functions`` (names of kinbook functions) and
    ``methods`` (names of methods of kinbook's classes) — before any cell of the notebook runs."""
    random.seed(seed)
    for name in ("numpy.random", "sympy.core.random"):
        module = sys.modules.get(name)
        if module is not None:
            module.seed(seed % 2**32)
    functions, methods = frozenset(functions), frozenset(methods)
    if not (functions or methods):
        return
    for name, module in list(sys.modules.items()):
        if not (name == "kinbook" or name.startswith("kinbook.")) or name.startswith("kinbook.classroom"):
            continue
        for attr, obj in list(vars(module).items()):
            if isinstance(obj, types.FunctionType) and obj.__name__ in functions and _ours(obj):
                setattr(module, attr, _wrap(obj, f"{obj.__module__}.{obj.__qualname__}"))
            elif isinstance(obj, type) and _ours(obj):
                for method in methods & set(vars(obj)):
                    f = vars(obj)[method]
                    if isinstance(f, types.FunctionType):
                        setattr(obj, method, _wrap(f, f"{obj.__module__}.{obj.__qualname__}.{method}"))


def _ours(obj):
    module = getattr(obj, "__module__", "") or ""
    return (module == "kinbook" or module.startswith("kinbook.")) and not module.startswith("kinbook.classroom")


def _wrap(f, key):
    if f in _wrapped or getattr(f, "_kinbook_traced", False):
        return _wrapped.get(f, f)

    def traced(*args, **kwargs):
        result = f(*args, **kwargs)
        if not any(result is a for a in args) and not any(result is a for a in kwargs.values()):
            _results.append((result, key, _cell[0]))  # (a value handed back as given is not the reference's)
        return result

    for attr in ("__name__", "__qualname__", "__doc__", "__module__"):
        setattr(traced, attr, getattr(f, attr))
    traced._kinbook_traced = True
    _wrapped[f] = traced
    return traced


def _matchable(value):
    """Whether an answer's identity says where it came from: a container or array made for it, not a number, a
    string or a sympy object the library may share with anyone who builds the same one."""
    if value is None or isinstance(value, (bool, int, float, complex, str, bytes)):
        return False
    basic = sys.modules.get("sympy.core.basic")
    matrix = sys.modules.get("sympy.matrices.matrixbase") or sys.modules.get("sympy.matrices.matrices")
    if basic is not None and isinstance(value, basic.Basic):
        return matrix is not None and isinstance(value, getattr(matrix, "MatrixBase", ()))
    return True


def _same(value, result):
    """The very result, or a copy of it: an array or matrix of the same library, shape and entries (``np.array(r)``,
    ``sympify`` of a matrix)."""
    if result is value:
        return True
    shape = getattr(value, "shape", None)
    if (shape is None or getattr(result, "shape", None) != shape or not _matchable(result)
            or type(value).__module__.split(".")[0] != type(result).__module__.split(".")[0]):
        return False
    numpy = sys.modules.get("numpy")
    try:
        if numpy is not None and isinstance(value, numpy.ndarray):
            return value.dtype == result.dtype and bool(numpy.array_equal(value, result))
        return value.tolist() == result.tolist()
    except Exception:  # whatever the student's object does when compared: no match
        return False


def report(names, namespace, cell):
    """JSON text ``{name: [[key, cell, same], …]}``: for each answer name that is the result of a reference call (the
    very object, ``same`` 1, or a copy of an array or matrix, 0), the latest such calls — at most four, the latest
    first — with their function's qualified name and the code cell they ran in (the grader skips the release's
    locked cells).
    ``cell``: the code cell just run (calls from now on are the next one's)."""
    _cell[0] = int(cell) + 1
    out = {}
    for name in names:
        value = namespace.get(name)
        if not _matchable(value):
            continue
        found = []
        for result, key, ran in reversed(_results):
            if _same(value, result):
                found.append([key[:200], ran, int(result is value)])
                if len(found) == 4:
                    break
        if found:
            out[name] = found
    return json.dumps(out)
