"""Reading an instructor's source notebook: solution regions, hidden checks, locked cells, parameters.

The conventions (nbgrader's markers, so instructors already know them):

* ``### BEGIN SOLUTION`` … ``### END SOLUTION`` inside a code cell: the instructor's solution. In the
  student's version the region becomes ``# YOUR CODE HERE`` / ``raise NotImplementedError()``. A cell with a
  solution region is an *answer cell*: the student edits it.
* ``### BEGIN HIDDEN CHECKS`` … ``### END HIDDEN CHECKS``: code the student never gets (typically
  :func:`~kinbook.classroom.part` declarations whose ``expected=`` would give the answer away). Removed from
  the student's version; run only by the grader, in its own process.
* every other cell is *locked*: released read-only (``editable: false``), and its checksum is recorded; a
  submission whose locked cells differ from the release is graded ``tampered``.
* a cell ``NAME = parameters(...)`` holds the per-student parameters (:mod:`kinbook.classroom.variant`).
"""

from __future__ import annotations

import ast
import copy
import hashlib
import json
import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import GradingError

__all__ = [
    "BEGIN_SOLUTION", "END_SOLUTION", "BEGIN_HIDDEN", "END_HIDDEN", "Source", "load_source", "checksum",
    "student_notebook", "locked_checksums", "grader_segments", "find_parameters",
]

BEGIN_SOLUTION = "### BEGIN SOLUTION"
END_SOLUTION = "### END SOLUTION"
BEGIN_HIDDEN = "### BEGIN HIDDEN CHECKS"
END_HIDDEN = "### END HIDDEN CHECKS"
PLACEHOLDER = ("# YOUR CODE HERE", "raise NotImplementedError()")


@dataclass
class Source:
    """An instructor's source notebook.

    Attributes
    ----------
    path : Path
    nb : nbformat.NotebookNode
    exercise : str
        The exercise's identifier: the file name without ``.ipynb``.
    """

    path: Path
    nb: object
    exercise: str

    @property
    def parameters_cell(self):
        """(index, variable name, ranges, defaults) of the parameters cell, or None."""
        return find_parameters(self.nb)


def load_source(path):
    """Read and validate a source notebook; cells get stable ids (``kb-NN``) when they have none."""
    import nbformat

    path = Path(path)
    try:
        nb = nbformat.read(str(path), as_version=4)
    except FileNotFoundError:
        raise GradingError(f"source notebook {str(path)!r} does not exist") from None
    except Exception as exc:
        raise GradingError(f"source notebook {str(path)!r} cannot be read: {exc}") from None
    seen = set()
    for i, cell in enumerate(nb.cells):
        if not cell.get("id") or cell["id"] in seen:
            cell["id"] = f"kb-{i:02d}"
        seen.add(cell["id"])
        if cell.cell_type == "code":
            _regions(cell.source, f"{path.name}, cell {i + 1}")  # validates the markers
    return Source(path, nb, path.stem)


def _regions(code, where):
    """Split code into [(kind, text)] with kind in {"code", "solution", "hidden"}; checks the markers."""
    out, kind, buf = [], "code", []
    for line in code.splitlines():
        marker = line.strip()
        if marker in (BEGIN_SOLUTION, BEGIN_HIDDEN):
            if kind != "code":
                raise GradingError(f"{where}: {marker!r} inside an open region")
            out.append((kind, buf))
            kind, buf = ("solution" if marker == BEGIN_SOLUTION else "hidden"), [line]
            continue
        if marker in (END_SOLUTION, END_HIDDEN):
            want = "solution" if marker == END_SOLUTION else "hidden"
            if kind != want:
                raise GradingError(f"{where}: {marker!r} without its BEGIN marker")
            buf.append(line)
            out.append((kind, buf))
            kind, buf = "code", []
            continue
        buf.append(line)
    if kind != "code":
        raise GradingError(f"{where}: a {kind} region is not closed")
    out.append((kind, buf))
    return [(k, b) for k, b in out if b]


def is_answer_cell(cell):
    return cell.cell_type == "code" and BEGIN_SOLUTION in cell.source


def checksum(cell):
    """Checksum of a locked cell: its type and its source (line endings and trailing blanks normalized)."""
    text = "\n".join(line.rstrip() for line in cell.source.replace("\r\n", "\n").split("\n")).strip()
    return hashlib.sha256(f"{cell.cell_type}\n{text}".encode()).hexdigest()


# ================================================================================================ parameters
def find_parameters(nb):
    """(index, name, ranges, defaults) of the cell ``NAME = parameters(..., defaults={...})``, or None."""
    found = None
    for i, cell in enumerate(nb.cells):
        if cell.cell_type != "code" or "parameters(" not in cell.source:
            continue
        try:
            tree = ast.parse(cell.source)
        except SyntaxError:
            continue
        for node in tree.body:
            if (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)
                    and isinstance(node.value, ast.Call)
                    and (getattr(node.value.func, "id", None) == "parameters"
                         or getattr(node.value.func, "attr", None) == "parameters")):
                if found is not None:
                    raise GradingError("a notebook can have only one parameters(...) cell")
                if len(tree.body) != 1:
                    raise GradingError(f"cell {i + 1}: the parameters(...) assignment must be alone in its cell")
                try:
                    kw = {k.arg: ast.literal_eval(k.value) for k in node.value.keywords}
                    args = [ast.literal_eval(a) for a in node.value.args]
                except ValueError:
                    raise GradingError(f"cell {i + 1}: parameters(...) takes literal values only") from None
                defaults = args[0] if args else kw.pop("defaults", {})
                kw.pop("defaults", None)
                found = (i, node.targets[0].id, kw, defaults)
    return found


def parameters_code(name, values, student=None):
    """The source of a parameters cell with literal values."""
    who = f"  # parameters of student {student!r}" if student is not None else ""
    return f"{name} = {json.dumps(values, sort_keys=True)}{who}"


# ============================================================================================ student copies
def _replace_solutions(code):
    out = []
    for kind, lines in _regions(code, "cell"):
        if kind == "solution":
            indent = re.match(r"\s*", lines[0]).group(0)
            out += [indent + p for p in PLACEHOLDER]
        elif kind == "hidden":
            continue
        else:
            out += lines
    return "\n".join(out)


def _strip_markers(code):
    """Solutions kept, markers removed; hidden checks removed."""
    out = []
    for kind, lines in _regions(code, "cell"):
        if kind == "solution":
            out += lines[1:-1]
        elif kind == "code":
            out += lines
    return "\n".join(out)


def student_notebook(source, values=None, student=None, keep_solutions=False):
    """The notebook a student receives (or, with ``keep_solutions``, its solved counterpart).

    Parameters
    ----------
    source : Source
    values : dict or None
        The parameters' values; None keeps the instructor's ``parameters(...)`` call (defaults).
    student : str or None
        Recorded in the notebook's metadata and the parameters cell.
    keep_solutions : bool
        Keep the solutions (without markers); used to check that an exercise's own solution scores full.
    """
    nb = copy.deepcopy(source.nb)
    params = find_parameters(nb)
    cells = []
    for i, cell in enumerate(nb.cells):
        if cell.cell_type == "code":
            if params is not None and i == params[0] and values is not None:
                cell.source = parameters_code(params[1], values, student)
            elif BEGIN_SOLUTION in cell.source or BEGIN_HIDDEN in cell.source:
                cell.source = _strip_markers(cell.source) if keep_solutions else _replace_solutions(cell.source)
                if not cell.source.strip():
                    continue  # a cell that held hidden checks only
            cell.outputs = []
            cell.execution_count = None
        answer = cell.cell_type == "code" and source.nb.cells[i].cell_type == "code" and is_answer_cell(source.nb.cells[i])
        meta = {k: v for k, v in cell.metadata.items() if k not in ("kinbook", "editable", "deletable", "nbgrader")}
        meta["kinbook"] = {"answer": True} if answer else {"locked": True}
        if not answer:
            meta["editable"] = False
            meta["deletable"] = False
        cell.metadata = meta
        cells.append(cell)
    nb.cells = cells
    nb.metadata["kinbook"] = {"exercise": source.exercise, "student": student, "parameters": values}
    nb.metadata["kinbook"]["locked"] = locked_checksums(nb)
    return nb


def locked_checksums(nb):
    """{cell id: checksum} of the locked cells of a student notebook."""
    return {c["id"]: checksum(c) for c in nb.cells if c.get("metadata", {}).get("kinbook", {}).get("locked")}


# ================================================================================================ grader view
def grader_segments(source, values=None):
    """The code the grader runs to build the references: [(cell index, kind, code)] where kind is "code"
    or "hidden"; solution regions are left out, the parameters cell gets ``values``."""
    params = find_parameters(source.nb)
    out = []
    for i, cell in enumerate(source.nb.cells):
        if cell.cell_type != "code":
            continue
        if params is not None and i == params[0] and values is not None:
            out.append((i, "code", parameters_code(params[1], values)))
            continue
        for kind, lines in _regions(cell.source, f"cell {i + 1}"):
            if kind == "solution":
                continue
            code = "\n".join(l for l in lines if not l.lstrip().startswith(("%", "!")))
            if code.strip():
                out.append((i, kind, code))
    return out
