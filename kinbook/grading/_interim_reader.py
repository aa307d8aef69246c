"""A stand-in for :mod:`kinbook.expressions` (the team's safe reader) until it is merged.

Same contract — ``read_expression(text, *, symbols, where, limits=None)``, ``check_expression(expr, *, where,
limits=None)``, ``Limits`` and ``ExpressionError`` — and the same method: Python's parser builds a syntax tree
(it runs nothing), the tree is walked against an allow-list, bounds are checked before any arithmetic, and
only then is the sympy object built. Never ``eval``, ``exec`` or ``sympify``. Deleted when the reader lands;
:mod:`kinbook.grading.read` imports the real one first.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass

import sympy as sp

from ..errors import InputError

__all__ = ["read_expression", "check_expression", "Limits", "ExpressionError"]


class ExpressionError(InputError):
    """Text or a sympy tree that is not an allowed expression."""

    def __init__(self, message, *, where=None, text=None, reason=None, column=None):
        super().__init__(message)
        self.where, self.text, self.reason, self.column = where, text, reason, column


@dataclass(frozen=True)
class Limits:
    length: int = 2000
    nodes: int = 1000
    depth: int = 100
    digits: int = 40
    exponent: float = 100
    magnitude: float = 1e300


_FUNCTIONS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "asin": sp.asin, "acos": sp.acos, "atan": sp.atan,
              "atan2": sp.atan2, "sqrt": sp.sqrt, "exp": sp.exp, "log": sp.log, "Abs": sp.Abs, "sign": sp.sign,
              "sen": sp.sin, "abs": sp.Abs, "ln": sp.log}
_CONSTANTS = {"pi": sp.pi, "π": sp.pi, "E": sp.E}
_BINOPS = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
           ast.Div: lambda a, b: a / b, ast.Pow: lambda a, b: a**b, ast.BitXor: lambda a, b: a**b}


def _fail(where, reason, text=None):
    raise ExpressionError(f"{where}: {reason}" + (f" in {text!r}" if text else ""), where=where, text=text,
                          reason=reason)


def read_expression(text, *, symbols, where, functions=None, limits=None):
    limits = limits or Limits()
    if not isinstance(text, str):
        _fail(where, "expected text")
    if len(text) > limits.length:
        _fail(where, f"the text is too long ({len(text)} characters, at most {limits.length})")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, ValueError, MemoryError, RecursionError):
        _fail(where, "cannot read this as a formula", text)
    count = 0
    stack = [(tree.body, 1)]
    while stack:
        node, depth = stack.pop()
        count += 1
        if count > limits.nodes or depth > limits.depth:
            _fail(where, "the expression is too large or nested too deeply", text[:60])
        stack.extend((c, depth + 1) for c in ast.iter_child_nodes(node))
    return _build(tree.body, symbols, where, text, limits)


def _build(node, symbols, where, text, limits):
    def build(n):
        if isinstance(n, ast.Constant) and isinstance(n.value, (int, float)) and not isinstance(n.value, bool):
            if isinstance(n.value, int) and abs(n.value) > 10**limits.digits:
                _fail(where, "a number is too large", text)
            return sp.Integer(n.value) if isinstance(n.value, int) else sp.Float(n.value)
        if isinstance(n, ast.Name):
            if n.id in symbols:
                return symbols[n.id]
            if n.id in _CONSTANTS:
                return _CONSTANTS[n.id]
            _fail(where, f"unknown name {n.id!r}", text)
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, (ast.USub, ast.UAdd)):
            v = build(n.operand)
            return -v if isinstance(n.op, ast.USub) else v
        if isinstance(n, ast.BinOp) and type(n.op) in _BINOPS:
            a, b = build(n.left), build(n.right)
            if isinstance(n.op, (ast.Pow, ast.BitXor)):
                if b.is_Number and abs(float(b)) > limits.exponent:
                    _fail(where, "an exponent is too large", text)
                if a.is_Number and b.is_Number and abs(float(a)) > 1 and float(b) * len(str(a)) > 300:
                    _fail(where, "a number is too large", text)
            out = _BINOPS[type(n.op)](a, b)
            if out.has(sp.zoo, sp.oo, sp.nan):
                _fail(where, "the expression is not finite (a division by zero?)", text)
            return out
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in _FUNCTIONS and not n.keywords:
            return _FUNCTIONS[n.func.id](*[build(a) for a in n.args])
        _fail(where, f"{type(n).__name__} is not allowed in a formula", text)

    try:
        return build(node)
    except (TypeError, ValueError) as exc:
        if isinstance(exc, ExpressionError):
            raise
        _fail(where, f"cannot build the formula ({type(exc).__name__})", text)


def check_expression(expr, *, where, limits=None):
    limits = limits or Limits()
    roots = list(expr) if isinstance(expr, sp.MatrixBase) else [expr]
    count = 0
    stack = [(r, 1) for r in roots]
    while stack:
        node, depth = stack.pop()
        count += 1
        if count > limits.nodes:
            _fail(where, f"the expression is too large (more than {limits.nodes} nodes)")
        if depth > limits.depth:
            _fail(where, f"the expression is nested too deeply (more than {limits.depth} levels)")
        if not isinstance(node, sp.Basic):
            _fail(where, f"a part of the expression is not a sympy object ({type(node).__name__})")
        if node in (sp.zoo, sp.oo, -sp.oo, sp.nan):
            raise ExpressionError(f"{where}: the expression contains {node}, which is not a finite number",
                                  where=where, reason="not finite")
        if isinstance(node, sp.Pow) and node.args[1].is_Number and node.args[1].is_finite \
                and abs(node.args[1]) > limits.exponent:
            _fail(where, f"the exponent {node.args[1]} is too large")
        stack.extend((a, depth + 1) for a in node.args)
