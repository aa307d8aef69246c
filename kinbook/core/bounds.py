"""Bounds on an expression (:class:`Limits`), checked before any arithmetic: on the text and tree the reader
parses (:mod:`kinbook.core.reader`), and on a sympy object built by code (:func:`check_expression`), counted as
a graph so that shared parts count once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import sympy as sp

from ..errors import ExpressionError
from ..i18n import N_, Message, Np_

__all__ = ["Limits", "DEFAULT_LIMITS", "check_expression", "refuse"]


@dataclass(frozen=True)
class Limits:
    """Bounds on an expression; every one is checked before any arithmetic.

    Attributes
    ----------
    length : int
        Characters of the text.
    nodes : int
        Nodes of the syntax tree (for :func:`check_expression`: *distinct* sub-expressions of a sympy object,
        each counted once however often it is shared).
    depth : int
        Nesting depth of the tree (the longest path, for a sympy object).
    tree : int
        For :func:`check_expression`: the size the sympy object would have written out as a tree (shared parts
        counted each time they occur) — computed from the distinct ones, so an enormous tree of few distinct
        parts is refused at once.
    digits : int
        Characters of one numeric literal.
    exponent : float
        Largest |n| of a numeric exponent in a power ``a^n``.
    magnitude : float
        Largest absolute value of any sub-expression made of numbers only (and of any number in a sympy tree).
    bits : int
        Bound on the total size of the exact numbers sympy would build (the literals' sizes, added, and
        multiplied by integer exponents): keeps exact rational arithmetic cheap.
    """

    length: int = 5000
    nodes: int = 2000
    depth: int = 100
    tree: int = 200_000
    digits: int = 40
    exponent: float = 100
    magnitude: float = 1e300
    bits: int = 20000


DEFAULT_LIMITS = Limits()
"""The limits used when a caller gives none: generous for any kinematic expression of the book."""


_SENTENCES = {  # (with a column, with what was expected) -> the sentence of a refusal
    (False, False): N_("{where}: {reason}"),
    (True, False): N_("{where}: {reason} at column {column}"),
    (False, True): N_("{where}: {reason}; expected {expected}"),
    (True, True): N_("{where}: {reason} at column {column}; expected {expected}"),
}
_SENTENCES_IN_TEXT = {
    (False, False): N_("{where}: {reason} in {text}"),
    (True, False): N_("{where}: {reason} at column {column} in {text}"),
    (False, True): N_("{where}: {reason} in {text}; expected {expected}"),
    (True, True): N_("{where}: {reason} at column {column} in {text}; expected {expected}"),
}


def refuse(where, reason, *, code=None, text=None, shown=None, expected=None, column=None):
    """Raise the :class:`~kinbook.errors.ExpressionError` of a refused expression, its sentence marked for
    translation (written in the language of the moment when shown).

    Parameters
    ----------
    where : str or kinbook.i18n.Message
        Where the text came from.
    reason : kinbook.i18n.Message
        What is wrong.
    code : str, optional
        The error's ``reason`` attribute (default: ``reason`` in English).
    text : str, optional
        The text read (the error's ``text``); ``shown``, its quotation in the sentence (``in '…'``).
    expected : kinbook.i18n.Message, optional
        What was expected (``; expected …``).
    column : int, optional
        1-based column of the offending part of the text.
    """
    sentences = _SENTENCES_IN_TEXT if shown is not None else _SENTENCES
    message = Message(sentences[column is not None, expected is not None], where=where, reason=reason,
                      column=column, text=shown, expected=expected)
    raise ExpressionError(message, where=where, text=text, reason=code or reason, column=column)


def check_expression(expr, *, where, limits=None):
    """The bounds of :class:`Limits` on an already-built sympy object (an expression or a matrix), without
    evaluating it: distinct sub-expressions, the size written out as a tree, depth, the magnitude of every
    number, numeric exponents.

    For sympy objects handed over from Python (a student's expression, data decoded by the grader). The object
    is walked as the graph it is — each distinct sub-expression once —, so a long expression that sympy built
    with shared parts (a γ of √(dᵀd) − l: 10⁵ tree nodes, a few hundred distinct) is read in time linear in
    its distinct parts, and one whose tree would be astronomical is refused as soon as its size is known.

    Returns
    -------
    (distinct, tree, depth) : tuple of int

    Raises
    ------
    ExpressionError
        Naming ``where`` and the bound exceeded.
    """
    limits = DEFAULT_LIMITS if limits is None else limits
    if isinstance(expr, (int, float)) and not isinstance(expr, bool):
        if not math.isfinite(expr) or abs(expr) > limits.magnitude:
            refuse(where, Message(N_("expected a finite number of at most {limit:.0e} in size, got {value}"),
                                  limit=limits.magnitude, value=repr(expr)), code="not finite")
        return 1, 1, 1
    if isinstance(expr, sp.MatrixBase):
        roots = list(expr)
    elif isinstance(expr, sp.Basic):
        roots = [expr]
    else:
        refuse(where, Message(N_("expected a sympy expression, got {type}"), type=type(expr).__name__),
               code="not a sympy expression")
    big_bits = math.log2(limits.magnitude)
    done = {}  # sub-expression -> (tree size, depth), once all its parts are done
    entered = set()
    stack = [(r, False) for r in roots]
    tree = depth = 0
    while stack:
        node, ready = stack.pop()
        if node in done:
            continue
        if ready:
            parts = [done[a] for a in node.args]
            size = 1 + sum(p[0] for p in parts)
            level = 1 + max((p[1] for p in parts), default=0)
            if size > limits.tree:
                _too_many_nodes(where, limits.tree)
            if level > limits.depth:
                refuse(where, Message(Np_("the expression is nested too deeply (more than {n} level)",
                                          "the expression is nested too deeply (more than {n} levels)"),
                                      n=limits.depth), code="too deep")
            done[node] = (size, level)
            continue
        if node in entered:
            continue
        if not isinstance(node, sp.Basic):
            refuse(where, Message(N_("a part of the expression is not a sympy object ({type})"),
                                  type=type(node).__name__), code="not sympy")
        entered.add(node)
        if len(entered) > limits.nodes:
            refuse(where, Message(Np_("the expression is too large (more than {n} distinct part)",
                                      "the expression is too large (more than {n} distinct parts)"),
                                  n=limits.nodes), code="too many nodes")
        if isinstance(node, sp.Number) or node in _INFINITIES:
            _check_number(node, where, big_bits, limits)
        elif isinstance(node, sp.Pow):
            e = node.args[1]
            if isinstance(e, sp.Number) and e.is_finite and abs(e) > limits.exponent:
                refuse(where, Message(N_("the exponent {exponent} is too large (at most {limit:g} in size)"),
                                      exponent=str(e), limit=limits.exponent), code="exponent too large")
        stack.append((node, True))
        stack.extend((a, False) for a in node.args if a not in done)
    for r in roots:
        size, level = done[r]
        tree, depth = tree + size, max(depth, level)
    if tree > limits.tree:
        _too_many_nodes(where, limits.tree)
    return len(entered), tree, depth


def _too_many_nodes(where, limit):
    refuse(where, Message(Np_("the expression is too large (more than {n} node written out)",
                              "the expression is too large (more than {n} nodes written out)"), n=limit),
           code="too many nodes")


_INFINITIES = (sp.zoo, sp.oo, -sp.oo, sp.nan)


def _check_number(node, where, big_bits, limits):
    if isinstance(node, sp.Integer):
        bits = int(node).bit_length()
    elif isinstance(node, sp.Rational):
        bits = max(int(node.p).bit_length(), int(node.q).bit_length())
    elif isinstance(node, sp.Float):
        _, man, exp, bc = node._mpf_
        bits = exp + bc if man else 0
        if node._prec > 4096:
            refuse(where, Message(Np_("a number has too many digits ({n} bit)", "a number has too many digits ({n} "
                                      "bits)"), n=node._prec), code="too precise")
    else:  # zoo, oo, nan
        refuse(where, Message(N_("the expression contains {value}, which is not a finite number"), value=str(node)),
               code="not finite")
    if bits > big_bits:
        refuse(where, too_large(limits.magnitude), code="too large")


def too_large(limit):
    """The reason "a number is too large (more than 1e+300)"."""
    return Message(N_("a number is too large (more than {limit:.0e})"), limit=limit)
