"""Answers as data: how a student's named answers leave the sandbox and enter the grader.

Inside the student's kernel, :func:`encode` turns each answer into JSON-able data, without parsing or
evaluating anything:

* numbers and numeric arrays → ``{"kind": "array", "shape": [...], "data": [...]}`` (nan/inf as strings);
* sympy expressions and matrices, and (nested) lists mixing expressions, numbers and strings →
  ``{"kind": "sympy", "shape": [r, c], "data": [entry, ...]}`` where an entry is a tree — ``["Symbol", "x1"]``,
  ``["Integer", "3"]``, ``["Rational", "1", "2"]``, ``["Float", "0.5"]``, ``["pi"]``, ``["E"]`` or
  ``[head, tree, ...]`` with ``head`` an operation (``Add``, ``Mul``, ``Pow``) or a function of
  :data:`FUNCTIONS` — or ``["Text", "..."]``, a string as the student typed it;
* anything else → ``{"kind": "unsupported", "type": "..."}``.

In the grader, :func:`decode` rebuilds the value. It never gives anything the student wrote to ``eval``,
``sympify`` or pickle: the record's structure is checked first (shape, number of entries and nodes, depth,
literal sizes, symbol names), then each tree is written out as an expression with every operation
parenthesized and read back by the team's one whitelisting reader,
:func:`kinbook.core.reader.read_expression`, which bounds integer sizes, exponents and the magnitude of every
numeric sub-expression *before* any arithmetic (a tower of powers is refused in microseconds, never computed).
Text entries are handed to the checker as text, which reads them with the same reader.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re

import numpy as np

from ..errors import KinbookError

__all__ = ["encode", "dumps", "decode", "decode_answers", "DecodeError", "FUNCTIONS", "MAX_NODES", "MAX_DEPTH", "MAX_TEXT"]

FUNCTIONS = ("sin", "cos", "tan", "asin", "acos", "atan", "atan2", "exp", "log", "sqrt", "Abs", "sign")
OPERATIONS = ("Add", "Mul", "Pow")
#: Bounds on one answer record (checked on the JSON structure, before anything is built).
MAX_NODES = 50_000
MAX_DEPTH = 90
MAX_DIGITS = 60
MAX_ENTRIES = 100_000
MAX_TEXT = 20_000
_NAME = re.compile(r"^[A-Za-z_\u0370-\u03ff][A-Za-z0-9_\u0370-\u03ff]{0,40}$")


class DecodeError(ValueError):
    """An answer record that cannot be graded; the message says why (and is shown to the student)."""


# ============================================================================================ in the kernel
def _number(x):
    x = float(x)
    if math.isfinite(x):
        return x
    return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")


def _tree(e, sp):
    if isinstance(e, str):
        return ["Text", e[:MAX_TEXT + 1]]
    if isinstance(e, (bool, np.bool_)):
        raise TypeError("a boolean is not a value of a kinematic quantity")
    if isinstance(e, (int, np.integer)):
        return ["Integer", str(int(e))]
    if isinstance(e, (float, np.floating)):
        return ["Float", repr(float(e))]
    if isinstance(e, sp.Symbol):
        return ["Symbol", e.name]
    if isinstance(e, sp.Integer):
        return ["Integer", str(int(e))]
    if isinstance(e, sp.Rational):
        return ["Rational", str(int(e.p)), str(int(e.q))]
    if isinstance(e, sp.Float):
        return ["Float", repr(float(e))]
    if e is sp.pi:
        return ["pi"]
    if e is sp.E:
        return ["E"]
    if isinstance(e, sp.Function) and type(e).__name__ in FUNCTIONS:
        return [type(e).__name__] + [_tree(a, sp) for a in e.args]
    if isinstance(e, (sp.Add, sp.Mul, sp.Pow)):
        return [type(e).__name__] + [_tree(a, sp) for a in e.args]
    if isinstance(e, sp.Function) and len(e.args) == 1 and isinstance(e.args[0], sp.Symbol):
        # x1(t)-style coordinates are graded by name
        return ["Symbol", type(e).__name__]
    raise TypeError(f"{type(e).__name__} is not supported in answers")


def _rows(value, sp):
    """A 2-d list of entries from a matrix, an expression, a string or (nested) lists of those."""
    if isinstance(value, sp.MatrixBase):
        return [[value[i, j] for j in range(value.cols)] for i in range(value.rows)]
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        if value and all(isinstance(r, (list, tuple, sp.MatrixBase, np.ndarray)) for r in value):
            rows = [list(np.asarray(r, dtype=object).ravel()) if not isinstance(r, (list, tuple)) else list(r)
                    for r in value]
            if len({len(r) for r in rows}) != 1:
                raise TypeError("rows of different lengths")
            return rows
        return [[x] for x in value]
    return [[value]]


def encode(value):
    """JSON-able data for one answer (see the module docstring). Runs inside the student's kernel."""
    import sympy as sp  # import time: sympy only when needed

    if isinstance(value, (bool, np.bool_)):
        return {"kind": "unsupported", "type": type(value).__name__}
    if isinstance(value, (int, float, np.number)):
        return {"kind": "array", "shape": [], "data": [_number(value)]}
    if isinstance(value, np.ndarray) and value.dtype != object:
        a = np.asarray(value, dtype=float)
        return {"kind": "array", "shape": list(a.shape), "data": [_number(x) for x in a.ravel()]}
    if isinstance(value, (sp.Basic, sp.MatrixBase, list, tuple, str, np.ndarray)):
        if isinstance(value, (list, tuple, np.ndarray)):
            try:
                arr = np.asarray(value, dtype=float)
            except (TypeError, ValueError):
                arr = None
            if arr is not None and arr.dtype != object:
                return {"kind": "array", "shape": list(arr.shape), "data": [_number(x) for x in arr.ravel()]}
        try:
            rows = _rows(value, sp)
            return {"kind": "sympy", "shape": [len(rows), len(rows[0]) if rows else 0],
                    "data": [_tree(e, sp) for r in rows for e in r]}
        except (TypeError, ValueError, RecursionError) as exc:  # unreadable: graded as a malformed answer
            return {"kind": "unsupported", "type": type(value).__name__, "error": f"{type(exc).__name__}: {exc}"[:300]}
    return {"kind": "unsupported", "type": type(value).__name__}


def dumps(names, namespace):
    """One JSON document with every named answer: ``{"answers": {name: record or null}}``."""
    out = {}
    for name in names:
        if name not in namespace:
            out[name] = None
            continue
        try:
            out[name] = encode(namespace[name])
        except Exception as exc:
            out[name] = {"kind": "unsupported", "type": type(namespace[name]).__name__, "error": str(exc)[:300]}
    return json.dumps({"answers": out}, allow_nan=False)


# ============================================================================================= in the grader
def decode(record, name="answer"):
    """The value of one answer record: a float, an ndarray, a sympy Matrix, or — when some entries are text —
    a list of rows mixing sympy expressions and strings (read by the checker). Raises :class:`DecodeError`."""
    if not isinstance(record, dict) or not isinstance(record.get("kind"), str):
        raise DecodeError("an answer record must be an object with a 'kind'")
    kind = record["kind"]
    if kind == "unsupported":
        t = record.get("type")
        raise DecodeError(f"answers of type {str(t)[:40]!r} cannot be graded: give numbers, a numpy array or "
                          f"sympy expressions/matrices" + (f" ({str(record.get('error'))[:200]})" if record.get("error") else ""))
    shape = record.get("shape")
    data = record.get("data")
    if (not isinstance(shape, list) or len(shape) > 3
            or not all(isinstance(n, int) and not isinstance(n, bool) and 0 <= n <= MAX_ENTRIES for n in shape)
            or not isinstance(data, list) or len(data) > MAX_ENTRIES):
        raise DecodeError("bad shape or data in an answer record")
    size = int(np.prod(shape)) if shape else 1
    if size != len(data):
        raise DecodeError(f"answer record of shape {shape} has {len(data)} entries")
    if kind == "array":
        vals = []
        for x in data:
            if isinstance(x, bool) or not isinstance(x, (int, float, str)):
                raise DecodeError("array entries must be numbers")
            if isinstance(x, str):
                if x not in ("nan", "inf", "-inf"):
                    raise DecodeError("array entries must be numbers")
                x = float(x)
            elif isinstance(x, int) and abs(x) > 10 ** MAX_DIGITS:
                raise DecodeError("an array entry is too large")
            vals.append(float(x))
        a = np.array(vals, dtype=float).reshape(shape)
        return float(a) if not shape else a
    if kind == "sympy":
        import sympy as sp  # import time: sympy only when needed

        if len(shape) != 2:
            raise DecodeError("a sympy answer must have a 2-d shape")
        budget = [MAX_NODES]
        entries = [_entry(t, budget, f"`{name}`, entry {k + 1}") for k, t in enumerate(data)]
        rows = [entries[i * shape[1]:(i + 1) * shape[1]] for i in range(shape[0])]
        if any(isinstance(e, str) for e in entries):
            return rows
        return sp.Matrix(shape[0], shape[1], entries)
    raise DecodeError(f"unknown answer kind {kind[:20]!r}")


def decode_answers(answers, names):
    """({name: value}, {name: why}) of the ``names`` among the answers a kernel reported (``{name: record}``
    or None): each read by :func:`decode` as bounded data, or refused with the reason."""
    decoded, problems = {}, {}
    for name in names:
        rec = (answers or {}).get(name)
        if rec is None:
            continue
        try:
            decoded[name] = decode(rec, name)
        except DecodeError as exc:
            problems[name] = str(exc)
    return decoded, problems


def _entry(t, budget, where):
    """One entry: a string (as the student typed it), or a tree read back through the safe reader."""
    if isinstance(t, list) and len(t) == 2 and t[0] == "Text":
        if not isinstance(t[1], str) or len(t[1]) > MAX_TEXT:
            raise DecodeError(f"{where}: a text answer longer than {MAX_TEXT} characters")
        return t[1]
    names = set()
    pieces = []
    _text(t, 0, budget, names, pieces)
    from ..core import bounds, reader  # import time: core loads sympy

    reserved = set(reader.FUNCTIONS) | set(reader.ALIASES) | set(reader.CONSTANTS)
    clash = sorted(names & reserved)
    if clash:
        raise DecodeError(f"{where}: a symbol is named like a function or constant ({clash[0]!r})")
    import sympy as sp  # import time: sympy only when needed

    limits = dataclasses.replace(bounds.DEFAULT_LIMITS, length=40 * MAX_NODES, nodes=MAX_NODES, digits=MAX_DIGITS + 1,
                                 depth=2 * MAX_DEPTH + 10)
    try:
        return reader.read_expression("".join(pieces), symbols={n: sp.Symbol(n) for n in names}, where=where,
                                           limits=limits)
    except KinbookError as exc:
        raise DecodeError(f"the answer is not gradable data: {getattr(exc, 'reason', None) or exc}") from None


def _text(t, depth, budget, names, out):
    """Write tree ``t`` as an expression (every operation parenthesized) into ``out``, checking its structure."""
    budget[0] -= 1
    if budget[0] < 0:
        raise DecodeError(f"expression larger than {MAX_NODES} nodes")
    if depth > MAX_DEPTH:
        raise DecodeError(f"expression deeper than {MAX_DEPTH}")
    if not isinstance(t, list) or not t or not isinstance(t[0], str):
        raise DecodeError("malformed expression tree")
    head, args = t[0], t[1:]
    if head == "Symbol":
        if len(args) != 1 or not isinstance(args[0], str) or not _NAME.match(args[0]):
            raise DecodeError("bad symbol name")
        names.add(args[0])
        out.append(args[0])
    elif head in ("Integer", "Rational"):
        if len(args) != (1 if head == "Integer" else 2) or not all(
                isinstance(a, str) and re.fullmatch(r"-?\d{1,%d}" % MAX_DIGITS, a) for a in args):
            raise DecodeError("bad integer")
        if head == "Rational" and int(args[1]) == 0:
            raise DecodeError("zero denominator")
        out.append(f"({args[0]})" if head == "Integer" else f"(({args[0]})/({args[1]}))")
    elif head == "Float":
        # (the length first: the pattern backtracks quadratically on a long string of digits that does not match)
        if len(args) != 1 or not isinstance(args[0], str) or len(args[0]) > 40 \
                or not re.fullmatch(r"-?(\d+\.?\d*(e[-+]?\d+)?|inf|nan)", args[0]):
            raise DecodeError("bad float")
        out.append(f"({args[0]})")
    elif head in ("pi", "E"):
        if args:
            raise DecodeError("constants take no arguments")
        out.append(head)
    elif head in OPERATIONS or head in FUNCTIONS:
        if head == "Pow" and len(args) != 2 or head != "Pow" and not args or head in FUNCTIONS and len(args) > 2:
            raise DecodeError(f"bad arity for {head}")
        sep = {"Add": " + ", "Mul": "*", "Pow": ")**("}.get(head, ", ")
        out.append("(" if head in OPERATIONS else f"{head}(")
        for k, a in enumerate(args):
            if k:
                out.append(sep)
            _text(a, depth + 1, budget, names, out)
        out.append(")")
    else:
        raise DecodeError(f"operation {head[:30]!r} is not allowed in answers")
