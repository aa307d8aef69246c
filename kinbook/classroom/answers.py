"""What a feedback page and the class report show of a student's answer: the value as the grader read it, the cell
it was assigned in as the student sees the notebook, and the catalogue mistakes the checker named, row by row.

All of it is bounded text made from data the grader already holds (decoded answers, the submission's cells, the
checker's result): nothing of the student's is run or evaluated here.
"""

from __future__ import annotations

import ast
import re

import numpy as np

__all__ = ["shown_answer", "answer_cell", "mistake_rows", "describe", "MAX_ANSWER_CHARS", "MAX_CELL_CHARS"]

MAX_ANSWER_CHARS = 2000
MAX_CELL_CHARS = 3000


def _clip(text, limit):
    text = "".join(c if (c.isprintable() or c in "\n\t") else "\ufffd" for c in str(text))
    return text if len(text) <= limit else text[:limit - 1] + "…"


def shown_answer(value):
    """A decoded answer as bounded text: a sympy matrix or a nested list row by row, an array with 6 significant
    digits."""
    try:
        if isinstance(value, np.ndarray):
            if value.dtype == object:
                return _clip("\n".join(str(list(r)) if getattr(r, "shape", ()) else str(r) for r in value),
                             MAX_ANSWER_CHARS)
            return _clip(np.array2string(value, precision=6, suppress_small=True, max_line_width=100),
                         MAX_ANSWER_CHARS)
        if hasattr(value, "tolist") and hasattr(value, "shape") and len(getattr(value, "shape", ())) == 2:
            return _clip("\n".join(str(row) for row in value.tolist()), MAX_ANSWER_CHARS)  # a sympy Matrix
        if isinstance(value, list) and value and all(isinstance(r, list) for r in value):
            return _clip("\n".join(str(r) for r in value), MAX_ANSWER_CHARS)
        return _clip(value, MAX_ANSWER_CHARS)
    except Exception:  # an answer that does not print is still graded; only the page shows less
        return "(this answer cannot be shown)"


#: Beyond this much code in a submission, where an answer was assigned is looked up by a plain pattern, not parsed
#: (the grader's time stays bounded on a notebook of 8 MB of code; the feedback then shows less, nothing else).
MAX_PARSED_CHARS = 300_000


def _bound(code, parse):
    """The names ``code`` binds or changes at any level (assignment, augmented or annotated, item or attribute
    assignment, for, :=, import, def, class), or None when it is not parsed (``parse`` False, or it does not parse)."""
    if not parse:
        return None
    try:
        tree = ast.parse(code)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names.update((a.asname or a.name.split(".")[0]) for a in node.names)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
        elif isinstance(node, (ast.Subscript, ast.Attribute)) and isinstance(node.ctx, ast.Store):
            base = node.value  # A[k] = …, A.x = …: the cell changes A
            while isinstance(base, (ast.Subscript, ast.Attribute)):
                base = base.value
            if isinstance(base, ast.Name):
                names.add(base.id)
    return names


def _assigns(code, names, name):
    """Whether a cell (its code, and the names it binds or None) assigns ``name``."""
    if names is not None:
        return name in names
    # (one line at a time, linear in the cell: no part of the pattern runs over a line break)
    return re.search(rf"(?m)^[^\S\n]*{re.escape(name)}[^\S\n]*(?:\[[^\n]*\])?[^\S\n]*[+\-*/@]?=", code) is not None


def _first_line(text):
    for line in str(text).splitlines():
        line = line.strip().lstrip("#").strip()
        if line:
            return line[:100] + ("…" if len(line) > 100 else "")
    return ""


def answer_cell(cells, name, bound=None):
    """Where ``name`` was last assigned, as the student sees the notebook: ``"cell 7 of 12 (after “(a) …”)"``,
    a newline, then the cell's code (bounded); "" when no cell assigns it. ``bound``: each cell's bound names, as
    :func:`describe` computes them once for every part."""
    if bound is None:
        bound = _bindings(cells)
    found = None
    for i, c in enumerate(cells):
        if c.get("cell_type") == "code" and _assigns(c.get("source", ""), bound[i], name):
            found = i
    if found is None:
        return ""
    heading = ""
    for c in reversed(cells[:found]):
        if c.get("cell_type") == "markdown" and _first_line(c.get("source", "")):
            heading = _first_line(c["source"])
            break
    where = f"cell {found + 1} of {len(cells)}" + (f" (after “{heading}”)" if heading else "")
    return where + "\n" + _clip(cells[found].get("source", ""), MAX_CELL_CHARS)


def _bindings(cells):
    parse = sum(len(c.get("source", "")) for c in cells if c.get("cell_type") == "code") <= MAX_PARSED_CHARS
    return [_bound(c.get("source", ""), parse) if c.get("cell_type") == "code" else None for c in cells]


def mistake_rows(result):
    """[(code, row)] of a :class:`~kinbook.grading.CheckResult`: each row's catalogue mistake with the row's label,
    then the result's mistakes found in no single row (row "")."""
    out = []
    for r in getattr(result, "rows", ()):
        code = getattr(r, "mistake", None)
        if code:
            try:
                label = r.label
            except Exception:
                label = ""
            out.append((str(code), str(label)))
    seen = {c for c, _ in out}
    out += [(str(c), "") for c in getattr(result, "mistakes", ()) if c not in seen]
    return out


def describe(grades, parts, decoded, cells):
    """Fill each grade's ``answer`` and ``cell`` (in place) from the decoded answers and the submission's cells."""
    by_name = {p.name: p for p in parts}
    bound = _bindings(cells)
    for g in grades:
        p = by_name.get(g.part)
        if p is None:
            continue
        if p.answer in decoded:
            g.answer = shown_answer(decoded[p.answer])
        g.cell = answer_cell(cells, p.answer, bound)
    return grades
