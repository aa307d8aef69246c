"""Answers as data: how a student's named answers leave the sandbox and enter the grader.

Inside the student's kernel, :func:`encode` turns each answer into JSON-able data:

* numbers and numeric arrays → ``{"kind": "array", "shape": [...], "data": [...]}`` (nan/inf as strings);
* sympy expressions, matrices, and lists mixing expressions, numbers and strings (strings are parsed by
  sympy *inside the sandbox*) → ``{"kind": "sympy", "shape": [r, c], "data": [tree, ...]}`` where a tree is
  ``["Symbol", "x1"]``, ``["Integer", "3"]``, ``["Rational", "1", "2"]``, ``["Float", "0.5"]``,
  ``["pi"]``, ``["E"]`` or ``[head, tree, ...]`` with ``head`` an operation (``Add``, ``Mul``, ``Pow``) or a
  function of :data:`FUNCTIONS`;
* anything else → ``{"kind": "unsupported", "type": "..."}``.

In the grader, :func:`decode` rebuilds the value with its own small reader: a whitelist of heads, caps on
size, depth and digits, no ``eval``, no ``sympify`` of text, no pickle.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np

__all__ = ["encode", "dumps", "decode", "DecodeError", "FUNCTIONS", "MAX_NODES", "MAX_DEPTH"]

FUNCTIONS = ("sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan", "atan2", "sinh", "cosh",
             "tanh", "exp", "log", "sqrt", "Abs", "sign")
OPERATIONS = ("Add", "Mul", "Pow")
MAX_NODES = 50_000
MAX_DEPTH = 200
MAX_DIGITS = 60
MAX_ENTRIES = 100_000
_NAME = re.compile(r"^[A-Za-z_\u0370-\u03ff][A-Za-z0-9_\u0370-\u03ff]{0,40}$")


class DecodeError(ValueError):
    """An answer record that is not one :func:`encode` writes."""


# ============================================================================================ in the kernel
def _number(x):
    x = float(x)
    if math.isfinite(x):
        return x
    return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")


def _tree(e, sp):
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


def encode(value):
    """JSON-able data for one answer (see the module docstring). Runs inside the student's kernel."""
    import sympy as sp

    if isinstance(value, (bool, int, float, np.number)) and not isinstance(value, np.bool_):
        return {"kind": "array", "shape": [], "data": [_number(value)]}
    if isinstance(value, np.ndarray) and value.dtype != object:
        a = np.asarray(value, dtype=float)
        return {"kind": "array", "shape": list(a.shape), "data": [_number(x) for x in a.ravel()]}
    if isinstance(value, (sp.Basic, sp.MatrixBase, list, tuple, str, np.ndarray)):
        try:
            arr = np.asarray(value, dtype=float) if not isinstance(value, (sp.Basic, sp.MatrixBase, str)) else None
        except (TypeError, ValueError):
            arr = None
        if arr is not None and arr.dtype != object:
            return {"kind": "array", "shape": list(arr.shape), "data": [_number(x) for x in arr.ravel()]}
        try:
            M = _as_matrix(value, sp)
            return {"kind": "sympy", "shape": list(M.shape), "data": [_tree(sp.sympify(e), sp) for e in M]}
        except Exception as exc:  # unreadable: graded as a malformed answer
            return {"kind": "unsupported", "type": type(value).__name__, "error": f"{type(exc).__name__}: {exc}"[:300]}
    return {"kind": "unsupported", "type": type(value).__name__}


def _as_matrix(value, sp):
    if isinstance(value, sp.MatrixBase):
        return value
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        if value and all(isinstance(r, (list, tuple, sp.MatrixBase)) for r in value):
            return sp.Matrix([[_entry(x, sp) for x in r] for r in value])
        return sp.Matrix([_entry(x, sp) for x in value])
    return sp.Matrix([_entry(value, sp)])


def _entry(x, sp):
    if isinstance(x, str):
        return sp.sympify(x.replace("^", "**"))
    return sp.sympify(x)


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
def decode(record):
    """The value of one answer record: a float, an ndarray or a sympy Matrix. Raises :class:`DecodeError`."""
    if not isinstance(record, dict) or not isinstance(record.get("kind"), str):
        raise DecodeError("an answer record must be an object with a 'kind'")
    kind = record["kind"]
    if kind == "unsupported":
        t = record.get("type")
        raise DecodeError(f"answers of type {str(t)[:40]!r} cannot be graded: give numbers, a numpy array or "
                          f"sympy expressions/matrices" + (f" ({str(record.get('error'))[:200]})" if record.get("error") else ""))
    shape = record.get("shape")
    data = record.get("data")
    if (not isinstance(shape, list) or len(shape) > 3 or not all(isinstance(n, int) and 0 <= n <= MAX_ENTRIES for n in shape)
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
            vals.append(float(x))
        a = np.array(vals, dtype=float).reshape(shape)
        return float(a) if not shape else a
    if kind == "sympy":
        import sympy as sp

        if len(shape) != 2:
            raise DecodeError("a sympy answer must have a 2-d shape")
        budget = [MAX_NODES]
        entries = [_rebuild(t, sp, 0, budget) for t in data]
        return sp.Matrix(shape[0], shape[1], entries)
    raise DecodeError(f"unknown answer kind {kind[:20]!r}")


def _rebuild(t, sp, depth, budget):
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
        return sp.Symbol(args[0])
    if head in ("Integer", "Rational"):
        if len(args) != (1 if head == "Integer" else 2) or not all(
                isinstance(a, str) and re.fullmatch(r"-?\d{1,%d}" % MAX_DIGITS, a) for a in args):
            raise DecodeError("bad integer")
        if head == "Integer":
            return sp.Integer(int(args[0]))
        if int(args[1]) == 0:
            raise DecodeError("zero denominator")
        return sp.Rational(int(args[0]), int(args[1]))
    if head == "Float":
        if len(args) != 1 or not isinstance(args[0], str) or len(args[0]) > 40:
            raise DecodeError("bad float")
        try:
            return sp.Float(float(args[0]))
        except ValueError:
            raise DecodeError("bad float") from None
    if head in ("pi", "E"):
        if args:
            raise DecodeError("constants take no arguments")
        return sp.pi if head == "pi" else sp.E
    if head in OPERATIONS:
        if len(args) < (2 if head == "Pow" else 1) or (head == "Pow" and len(args) != 2):
            raise DecodeError(f"bad arity for {head}")
        sub = [_rebuild(a, sp, depth + 1, budget) for a in args]
        if head == "Pow" and sub[1].is_Number and abs(float(sub[1])) > 64:
            raise DecodeError("exponent too large")
        return getattr(sp, head)(*sub)
    if head in FUNCTIONS:
        sub = [_rebuild(a, sp, depth + 1, budget) for a in args]
        if len(sub) != (2 if head == "atan2" else 1):
            raise DecodeError(f"bad arity for {head}")
        return getattr(sp, head)(*sub)
    raise DecodeError(f"operation {head[:30]!r} is not allowed in answers")
