"""Reading an instructor's source notebook: solution regions, hidden checks, locked cells, parameters.

The conventions (nbgrader's markers, so instructors already know them):

* ``### BEGIN SOLUTION`` … ``### END SOLUTION`` inside a code cell: the instructor's solution. In the
  student's version the region becomes ``# YOUR CODE HERE`` / ``raise NotImplementedError()``. A cell with a
  solution region is an *answer cell*: the student edits it.
* ``### BEGIN HIDDEN CHECKS`` … ``### END HIDDEN CHECKS``: code the student never gets (typically
  :func:`~kinbook.classroom.part` declarations whose ``expected=`` would give the answer away). Removed from
  the student's version; run only by the grader, in its own process.
* every other cell is *locked*: released read-only (``editable: false``), and its checksum (type and
  source: not its id or metadata) is recorded; a submission whose locked cells are not all there, unchanged
  and in order, is graded ``tampered``. Cells are matched by content, not by id, so a notebook re-saved in
  nbformat 4.4 (which has no cell ids) is not tampered.
* a cell ``NAME = parameters(...)`` holds the per-student parameters (:mod:`kinbook.classroom.variant`).

The source notebook is the instructor's and is trusted; it is read once (:func:`load_source`: its bytes,
their sha256, the parsed notebook), and the grader runs its code from that in-memory copy, compiled once
(:func:`grader_code`). A submission is student data: :func:`parse_submission` refuses it before parsing when it
is too large, and reads it as plain JSON with a size, cell-count and structure check (no nbformat schema
validation, which can take minutes on a hostile file).
"""

from __future__ import annotations

import ast
import copy
import hashlib
import json
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import GradingError
from .parts import check_parameters
from .results import Refused
from .sandbox.protocol import MAX_SUBMISSION_BYTES

__all__ = [
    "BEGIN_SOLUTION", "END_SOLUTION", "BEGIN_HIDDEN", "END_HIDDEN", "Source", "load_source", "source_from_bytes",
    "checksum",
    "student_notebook", "locked_checksums", "locked_sequence", "missing_locked", "grader_segments", "grader_code",
    "find_parameters", "parse_submission", "readable", "MAX_NOTEBOOK_BYTES", "MAX_FILE_BYTES", "MAX_CELLS",
]

#: A submission whose code and text (saved outputs left out) are larger than this is not graded (``too-large``); the
#: sandbox's job frame is sized from it, so that a notebook under it always fits.
MAX_NOTEBOOK_BYTES = MAX_SUBMISSION_BYTES
#: A file larger than this is refused unread (``too-large``), saved outputs included.
MAX_FILE_BYTES = 128 * 1024 * 1024
#: A submission with more cells than this is refused (``too-large``).
MAX_CELLS = 2000
MAX_CELL_CHARS = 1_000_000

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
    sha256 : str
        Of the bytes read (once) from ``path``.
    data : bytes
        Those bytes (kept in the gradebook, so that a later edit can be graded against this edition).
    """

    path: Path
    nb: object
    exercise: str
    sha256: str = ""
    compiled: dict = field(default_factory=dict, repr=False, compare=False)
    data: bytes = field(default=b"", repr=False, compare=False)

    def __getstate__(self):  # code objects do not pickle: a copy in another process compiles again
        return {**self.__dict__, "compiled": {}}

    def changed_on_disk(self):
        """Whether the file at ``path`` no longer holds the bytes that were read (edited, replaced, removed)."""
        try:
            return hashlib.sha256(Path(self.path).read_bytes()).hexdigest() != self.sha256
        except OSError:
            return True



def load_source(path):
    """Read (once) and validate a source notebook; cells get stable ids (``kb-NN``) when they have none."""
    if isinstance(path, Source):
        return path
    path = Path(path)
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise GradingError(f"source notebook {str(path)!r} does not exist") from None
    except OSError as exc:
        raise GradingError(f"source notebook {str(path)!r} cannot be read: {exc.strerror}") from None
    return source_from_bytes(data, path)


def source_from_bytes(data, path):
    """:func:`load_source` of bytes read already (an earlier source the gradebook kept); ``path`` names it."""
    import nbformat  # optional dependency: nbformat (the grading extra)

    path = Path(path)
    try:
        nb = nbformat.reads(data.decode("utf-8"), as_version=4)
    except Exception as exc:
        raise GradingError(f"source notebook {str(path)!r} cannot be read: {exc}") from None
    seen = set()
    for i, cell in enumerate(nb.cells):
        if not cell.get("id") or cell["id"] in seen:
            cell["id"] = f"kb-{i:02d}"
        seen.add(cell["id"])
        if cell.cell_type == "code":
            _regions(cell.source, f"{path.name}, cell {i + 1}")  # validates the markers
            _compiles(cell.source, f"source notebook {str(path)!r}, cell {i + 1}")
    try:
        find_parameters(nb)  # validated once, here, with the file named
    except GradingError as exc:
        raise GradingError(f"{path.name}: {exc}") from None
    return Source(path, nb, path.stem, hashlib.sha256(data).hexdigest(), data=bytes(data))


def runnable(code):
    """A cell's code as Python runs it: IPython's ``%magic`` and ``!shell`` lines left out."""
    return "\n".join(line for line in code.splitlines() if not line.lstrip().startswith(("%", "!")))


def _compiles(code, where):
    """A source cell must compile whole (its solution included): a cell that does not — a missing ``)`` in the
    hidden checks — would silently lose the parts it declares."""
    try:
        compile(runnable(code), where, "exec")
    except SyntaxError as exc:
        line = f"line {exc.lineno}: " if exc.lineno else ""
        raise GradingError(f"{where} is not valid Python: it does not compile ({line}{exc.msg}: "
                           f"{(exc.text or '').strip()[:80]!r}); fix the cell — nothing was released, validated or "
                           "graded") from None
    except ValueError as exc:  # a NUL character in the code
        raise GradingError(f"{where} is not valid Python: it does not compile ({exc})") from None


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
    """Checksum of a locked cell: its type and its source (line endings and trailing blanks normalized) — not
    its id, outputs or metadata."""
    source = cell["source"]
    if isinstance(source, list):
        source = "".join(source)
    text = "\n".join(line.rstrip() for line in source.replace("\r\n", "\n").split("\n")).strip()
    return hashlib.sha256(f"{cell['cell_type']}\n{text}".encode()).hexdigest()


# ================================================================================================ parameters
def find_parameters(nb):
    """(index, name, ranges, defaults) of the cell ``NAME = parameters(..., defaults={...})``, or None."""
    found = None
    for i, cell in enumerate(nb.cells):
        if cell.cell_type != "code" or "parameters(" not in cell.source:
            continue
        try:
            tree = ast.parse(cell.source)
        except (SyntaxError, ValueError, RecursionError, MemoryError) as exc:
            if _ASSIGNS_PARAMETERS.search(cell.source):  # the parameters cell itself: never copied unread
                where = f" (line {exc.lineno}: {exc.msg})" if isinstance(exc, SyntaxError) else ""
                raise GradingError(f"cell {i + 1}: the parameters(...) cell is not valid Python{where}") from None
            continue  # another cell that mentions parameters( (a magic such as %matplotlib does not parse)
        for node in tree.body:
            if (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)
                    and isinstance(node.value, ast.Call)
                    and (getattr(node.value.func, "id", None) == "parameters"
                         or getattr(node.value.func, "attr", None) == "parameters")):
                if found is not None:
                    raise GradingError("a notebook can have only one parameters(...) cell")
                if len(tree.body) != 1:
                    raise GradingError(f"cell {i + 1}: the parameters(...) assignment must be alone in its cell")
                if any(k.arg is None for k in node.value.keywords) or len(node.value.args) > 1:
                    raise GradingError(f"cell {i + 1}: parameters(...) takes the defaults and keyword arguments "
                                       "only (no ** or more positional arguments)")
                try:
                    kw = {k.arg: ast.literal_eval(k.value) for k in node.value.keywords}
                    args = [ast.literal_eval(a) for a in node.value.args]
                except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
                    raise GradingError(f"cell {i + 1}: parameters(...) takes literal values only") from None
                defaults = args[0] if args else kw.pop("defaults", {})
                kw.pop("defaults", None)
                check_parameters(kw, defaults, where=f"cell {i + 1}: parameters(...)")
                found = (i, node.targets[0].id, kw, defaults)
    return found


_ASSIGNS_PARAMETERS = re.compile(r"(?m)^[^\S\n]*[A-Za-z_]\w*[^\S\n]*=[^\S\n]*(?:\w+\.)?parameters[^\S\n]*\(")


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
    """{cell id: checksum} of the locked cells of a student notebook (for the release's manifest)."""
    return dict(locked_sequence(nb))


def locked_sequence(nb):
    """[(cell id, checksum)] of the locked cells of a student notebook, in order."""
    return [(c["id"], checksum(c)) for c in nb.cells if c.get("metadata", {}).get("kinbook", {}).get("locked")]


def missing_locked(expected, cells):
    """The ids of the locked cells (``expected``: :func:`locked_sequence`) that ``cells`` (a submission's) do not
    hold unchanged and in order; [] when every one is there. Cells are matched by checksum, not by id."""
    sums = [checksum(c) for c in cells]
    missing, at = [], 0
    for cid, h in expected:
        try:
            at = sums.index(h, at) + 1
        except ValueError:
            missing.append(cid)
    return missing


# ================================================================================================ submissions
def readable(data):
    """The bytes the grader reads of a submitted file: an nbformat-3 notebook upgraded to nbformat 4 (nbformat's own
    converter), and a file over :data:`MAX_NOTEBOOK_BYTES` without its saved outputs (outputs are never graded: a
    notebook that printed 400,000 lines is graded on its code). Anything else is returned as it is, for
    :func:`parse_submission` to read or refuse.

    Raises
    ------
    Refused
        ``too-large`` over :data:`MAX_FILE_BYTES`; ``corrupt-notebook`` when nbformat cannot convert it.
    """
    if len(data) > MAX_FILE_BYTES:
        raise Refused("too-large", f"the file has {len(data):,} bytes (at most {MAX_FILE_BYTES:,}, saved outputs "
                                   "included); not read")
    big = len(data) > MAX_NOTEBOOK_BYTES
    if not big and not re.search(rb'"nbformat"\s*:\s*3\b', data[-4096:] + data[:4096]):
        return data
    if data.count(b'"cell_type"') > MAX_CELLS:
        raise Refused("too-large", f"the notebook has more than {MAX_CELLS:,} cells; not read")
    try:  # each cell's outputs are dropped as soon as the cell is read: at most one cell's outputs in memory
        nb = json.loads(data.decode("utf-8"), object_pairs_hook=_without_outputs)
    except (UnicodeDecodeError, ValueError, RecursionError):
        return data
    if not isinstance(nb, dict):
        return data
    cells = nb.get("cells")
    if nb.get("nbformat") == 3 and isinstance(nb.get("worksheets"), list):
        cells = [c for ws in nb["worksheets"] if isinstance(ws, dict) and isinstance(ws.get("cells"), list)
                 for c in ws["cells"]]
    for c in cells if isinstance(cells, list) else []:
        if isinstance(c, dict) and "outputs" in c:
            c["outputs"] = []
            if "execution_count" in c:
                c["execution_count"] = None
            c.pop("prompt_number", None)
    if nb.get("nbformat") == 3:
        if len(cells or ()) > MAX_CELLS:
            raise Refused("too-large", f"the notebook has more than {MAX_CELLS:,} cells; not read")

        import nbformat  # optional dependency: nbformat (the grading extra)

        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                nb = nbformat.convert(nbformat.from_dict(nb), 4)
        except Exception as exc:
            raise Refused("corrupt-notebook", f"an nbformat-3 notebook that nbformat cannot convert to nbformat 4: "
                                              f"{type(exc).__name__}: {str(exc)[:200]}") from None
    return json.dumps(nb).encode("utf-8")


def _without_outputs(pairs):
    """A JSON object as read, less a cell's saved ``outputs`` (an object with a ``cell_type`` is a cell)."""
    obj = dict(pairs)
    if "cell_type" in obj and "outputs" in obj:
        obj["outputs"] = []
    return obj


def parse_submission(data, metadata=False):
    """The cells of a submitted notebook (bytes): a list of ``{"cell_type", "source", "id"}`` dicts — and,
    with ``metadata``, also its ``kinbook`` metadata (a dict, empty when absent): ``(cells, metadata)``.

    Made :func:`readable` first (nbformat 3 upgraded; saved outputs dropped from a large file); refused when that is
    larger than :data:`MAX_NOTEBOOK_BYTES` or holds more than :data:`MAX_CELLS` cells (``too-large``); read as JSON, which must be an nbformat-4 notebook whose cells have a type and a
    source (``corrupt-notebook``). Nothing in it is run or evaluated here.

    Raises
    ------
    Refused
    """
    data = readable(data)
    if len(data) > MAX_NOTEBOOK_BYTES:
        raise Refused("too-large", f"the notebook has {len(data):,} bytes of code and text, saved outputs left out "
                                   f"(at most {MAX_NOTEBOOK_BYTES:,}); not read")
    if data.count(b'"cell_type"') > MAX_CELLS:
        raise Refused("too-large", f"the notebook has more than {MAX_CELLS:,} cells; not read")
    try:
        nb = json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise Refused("corrupt-notebook", f"not a readable notebook: {type(exc).__name__}: {str(exc)[:200]}") from None
    if not isinstance(nb, dict) or nb.get("nbformat") != 4 or not isinstance(nb.get("cells"), list):
        raise Refused("corrupt-notebook", "not a readable notebook: not an nbformat-4 notebook with a list "
                                "of cells")
    if len(nb["cells"]) > MAX_CELLS:
        raise Refused("too-large", f"the notebook has more than {MAX_CELLS:,} cells; not read")
    cells = []
    for i, c in enumerate(nb["cells"]):
        source = c.get("source") if isinstance(c, dict) else None
        if isinstance(source, list) and all(isinstance(line, str) for line in source):
            source = "".join(source)
        if not isinstance(source, str) or c.get("cell_type") not in ("code", "markdown", "raw"):
            raise Refused("corrupt-notebook", f"not a readable notebook: cell {i + 1} has no type or source")
        if len(source) > MAX_CELL_CHARS:
            raise Refused("too-large", f"cell {i + 1} has more than {MAX_CELL_CHARS:,} characters; not read")
        cells.append({"cell_type": c["cell_type"], "source": source, "id": str(c.get("id", ""))[:64]})
    if metadata:
        meta = nb.get("metadata")
        meta = meta.get("kinbook") if isinstance(meta, dict) else None
        return cells, (meta if isinstance(meta, dict) else {})
    return cells


# ================================================================================================ grader view
def grader_code(source, values=None):
    """:func:`grader_segments` compiled: [(cell index, kind, code object or None)] — None for code that does not
    stand alone (around a solution region). Compiled once per source (the parameters cell, which depends on
    ``values``, once per values), from the in-memory copy."""
    out = []
    params = find_parameters(source.nb)
    for index, kind, code in grader_segments(source, values):
        key = (index, kind, code) if params is not None and index == params[0] else (index, kind)
        if key not in source.compiled:
            try:
                source.compiled[key] = compile(code, f"<{source.exercise} cell {index + 1}>", "exec")
            except SyntaxError as exc:
                if kind == "hidden":  # the hidden checks stand alone: their parts must not vanish
                    raise GradingError(f"{source.exercise}: the hidden checks of cell {index + 1} do not compile on "
                                       f"their own (line {exc.lineno}: {exc.msg})") from None
                if re.search(r"\bpart\s*\(", code):  # a declaration the grader would never see
                    raise GradingError(f"{source.exercise}: cell {index + 1} declares part(...) in code that does not "
                                       f"stand alone without its solution region (line {exc.lineno}: {exc.msg}); put "
                                       "the declaration in a cell, or a region, of its own") from None
                source.compiled[key] = None
        out.append((index, kind, source.compiled[key]))
    return out


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
            code = runnable("\n".join(lines))
            if code.strip():
                out.append((i, kind, code))
    return out
