"""The answer as it was read (STACK's "your last answer was interpreted as"): every check result carries the
student's answer as kinbook read it — typeset in a notebook, plain text in a terminal and in the feedback pages —
shown before the verdict, so that ``sin(phi2)*x1 - …`` typed with a slip is seen as what was parsed.

:func:`echoed` wraps a checker: after it has run, the answer is read again by the checkers' own reader
(:func:`kinbook.grading.read.read` for Φ, Φ_q, ν, γ; numbers as an array for the value checkers) and attached to the
result (:attr:`kinbook.grading.report.CheckResult.read`) — lazily: the answer is read again and typeset only when the
result is shown. An answer the reader refuses is not echoed: the result's message says what could not be read.
"""

from __future__ import annotations

import functools
import re

import numpy as np

__all__ = ["echoed", "read_as", "MAX_CHARS"]

MAX_CHARS = 2000
"""An echo longer than this is cut (with "…")."""

_COORD = re.compile(r"^(d?)(x|y|z|phi|e0|e1|e2|e3)(\d+)$")
_TEX = {"x": "x", "y": "y", "z": "z", "phi": r"\varphi"}


def _names(M):
    """sympy.latex ``symbol_names`` in the book's notation: x1 → x_{1}, phi2 → \\varphi_{2}, dphi2 → \\dot{\\varphi}_{2},
    e02 → e_{0,2}."""
    out = {}
    for s in M.free_symbols:
        m = _COORD.match(s.name)
        if not m:
            continue
        dot, base, number = m.groups()
        head, sub = (("e", f"{base[1]},{number}") if base.startswith("e") else (_TEX[base], number))
        out[s] = (rf"\dot{{{head}}}" if dot else head) + f"_{{{sub}}}"
    return out


def _cut(text):
    return text if len(text) <= MAX_CHARS else text[:MAX_CHARS - 1] + "…"


def read_as(value):
    """``(text, latex)`` of an answer as read: a sympy Matrix (rows of expressions) or numbers; None otherwise."""
    import sympy as sp

    if isinstance(value, sp.MatrixBase):
        M = value.applyfunc(lambda e: e.xreplace({f: (sp.Integer(0) if abs(f) < 1e-12 else sp.Float(f, 6))
                                                  for f in e.atoms(sp.Float)}))
        rows = [[sp.sstr(M[i, j]) for j in range(M.shape[1])] for i in range(M.shape[0])]
        text = "[" + ", ".join(r[0] if len(r) == 1 else "[" + ", ".join(r) + "]" for r in rows) + "]"
        if sum(sp.count_ops(e) for e in M) > 600:
            return _cut(text), None
        return _cut(text), sp.latex(M, symbol_names=_names(M), mat_delim="[")
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None
    if a.ndim > 2 or a.size > 400 or not np.all(np.isfinite(a)):
        return None
    # round-off is zero (4e-17 beside 0.33 reads 0): an echo is identical on every machine
    a = np.where(np.abs(a) <= 1e-12 * max(1.0, float(np.abs(a).max(initial=0.0))), 0.0, a)
    fmt = lambda x: f"{x:.6g}"  # noqa: E731
    text = np.array2string(a, formatter={"float_kind": fmt}, separator=", ", max_line_width=10**6).replace("\n", "")
    if a.ndim == 0:
        return text, fmt(float(a))
    rows = a.reshape(-1, 1) if a.ndim == 1 else a
    body = r" \\ ".join(" & ".join(fmt(x) for x in r) for r in rows)
    return _cut(text), r"\begin{bmatrix} " + body + r" \end{bmatrix}"


def echoed(checker, quantity=None):
    """``checker`` with the answer as read attached to its result (``quantity``: "Phi", "Phi_q", "nu", "gamma" for
    the symbolic checkers, None for the value checkers)."""
    @functools.wraps(checker)
    def check(answer, reference, *args, **kwargs):
        result = checker(answer, reference, *args, **kwargs)
        if getattr(result, "_echo", None) is None and "malformed" not in (result.mistakes or ()):
            kept = answer.copy() if isinstance(answer, np.ndarray) else answer  # as it was when checked
            result.echo(lambda: read_as(_read(kept, reference, quantity)))  # read again only when shown
        return result

    return check


def _read(answer, reference, quantity):
    if quantity is None:
        return answer
    from .read import read
    from .target import target_for

    A = read(answer, target_for(reference), quantity)
    return A.matrix if A.kind == "symbolic" else getattr(A, "array", None)
