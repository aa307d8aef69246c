"""Reading a student's answer (first stage of a check): text, sympy objects, a Python function, or numbers.

:func:`read` turns any accepted form into an :class:`Answer`, or raises :class:`Refused` — with a catalogue
code and a message saying what was expected — which the checker turns into a failed result.

* **Text** is read by the team's one safe reader, :func:`kinbook.core.reader.read_expression`: an
  allow-list of names (the mechanism's coordinates, velocities and t, in any of the spellings of
  :meth:`~kinbook.grading.target.Target.symbols`: ``phi2``, ``phi_2``, ``φ2``; ``dphi2``, ``phi2_dot``),
  numbers, + − × ÷ ^ and the reader's functions; bounds on size checked before any arithmetic. Never
  ``sympify``, ``eval`` or ``exec``.
* **sympy objects** a student built in Python are checked against the same bounds
  (:func:`kinbook.core.bounds.check_expression`) and their symbols are matched *by name*: a student who
  writes ``sp.symbols("x1 phi2")`` (without ``real=True``) gets the mechanism's x1 and phi2.
* **A function** ``f(q, t)`` (``f(q, qd, t)`` for γ, or ``f(q)``) is called once per sample instant with
  copies of the coordinates; what it returns must be real numbers of a bounded size. It runs as it is (in a
  notebook, the student's own code in the student's own kernel): nothing times it out.
* **Numbers** (a number, a vector, a matrix) are the values at one configuration: they are only graded
  with ``at=`` (the checker refuses them otherwise: "give the configuration").

Symbolic answers are evaluated by a :class:`~kinbook.grading.jets.Tape` (no code generation); the same tape
gives, for a student's Φ, its Φ_q, ν and γ exactly. A function's are taken by finite differences with
Richardson extrapolation (relative error ~1e-10).

**The answer as read** (STACK's "your last answer was interpreted as"; at the bottom of this file): every check
result carries the student's answer as kinbook read it — typeset in a notebook, plain text in a terminal and in
the feedback pages — shown before the verdict, so that ``sin(phi2)*x1 - …`` typed with a slip is seen as what was
parsed. :func:`echoed` wraps a checker: after it has run, the answer is read again by the checkers' own reader
(:func:`read` for Φ, Φ_q, ν, γ; numbers as an array for the value checkers) and attached to the result
(:attr:`kinbook.grading.report.CheckResult.read`) — lazily: the answer is read again and typeset only when the
result is shown. An answer the reader refuses is not echoed: the result's message says what could not be read.
:func:`tex_name` is the book's notation of a coordinate, the one rule :mod:`kinbook.book.notation` typesets with.
"""

from __future__ import annotations

import functools
import inspect
import numbers
import re
import sys

import numpy as np

from ._i18n import Msg
from .quantities import quantity_of

__all__ = ["Answer", "Refused", "read", "as_numbers", "numbers_of", "echoed", "read_as", "tex_name", "MAX_CHARS"]

MAX_OUTPUT = 100_000
"""The most numbers a student's function may return per call (a guard, not a time limit)."""


def _reader():
    from ..core import reader  # the team's one safe reader

    return reader


def _bounds():
    from ..core import bounds  # the reader's bounds, for sympy answers too

    return bounds


def _limits():
    """The bounds on one entry of an answer: text up to 20 000 characters; a sympy object up to 20 000 distinct
    sub-expressions, 2 000 000 nodes written out as a tree, 400 deep (a γ entry of a spatial joint that sympy
    derived has some 10⁵ tree nodes and a few hundred distinct ones: it is walked as the graph it is)."""
    return _bounds().Limits(length=20_000, nodes=20_000, tree=2_000_000, depth=400)


SYMPY_WORK = 5_000
"""Above this many tree nodes an answer entry is not handed to sympy functions that walk trees (factoring a
row for a message, symbolic confirmation): they are skipped, never the verdict."""


class Refused(Exception):
    """An answer that cannot be graded: a catalogue code, and a message (a text key of
    :mod:`kinbook.grading._i18n` with its fields, translated when shown)."""

    def __init__(self, code, key, **fields):
        super().__init__(key)
        self.code, self.key, self.fields = code, key, fields


def as_numbers(A):
    """A symbolic answer without symbols (["0.5", "-1.2"], typed as text) as the numbers it writes: graded at
    ``at=`` like numbers; any other answer as it is."""
    if A.kind != "symbolic" or any(e.free_symbols for e in A.matrix):
        return A
    return Answer("numbers", array=numbers_of(A.matrix, "answer"))


class Answer:
    """A readable answer.

    Attributes
    ----------
    kind : {"symbolic", "function", "numbers"}
    matrix : sympy.Matrix or None
        The answer as sympy (kind "symbolic").
    array : ndarray or None
        The numbers (kind "numbers"), 2-D.
    """

    def __init__(self, kind, matrix=None, array=None, function=None, nargs=2):
        self.kind, self.matrix, self.array, self.function, self.nargs = kind, matrix, array, function, nargs
        self._tapes = {}
        self._values = {}  # (id(target), id(samples)) -> values, filled by :meth:`prefetch`

    @property
    def shape(self):
        """(rows, columns), or None for a function (known after its first call)."""
        if self.matrix is not None:
            return tuple(self.matrix.shape)
        if self.array is not None:
            return self.array.shape
        return None

    def transposed(self):
        """The same answer with rows and columns exchanged (a row vector given for a column)."""
        if self.kind == "symbolic":
            return Answer("symbolic", matrix=self.matrix.T)
        if self.kind == "numbers":
            return Answer("numbers", array=self.array.T)
        f = self.function
        return Answer("function", function=lambda *a: np.asarray(f(*a)).T, nargs=self.nargs)

    # ------------------------------------------------------------------------------------------- numbers
    def tape(self, target):
        key = id(target)
        if key not in self._tapes:
            from .jets import UnknownSymbol, UnsupportedExpression  # import time: grading.jets loads sympy

            try:
                self._tapes[key] = target.tape(list(self.matrix), aliases=True)
            except UnknownSymbol as exc:
                raise Refused("unknown_symbol", "unknown_symbols", names=exc.name, where=Msg("answer")) from None
            except UnsupportedExpression as exc:
                raise Refused("malformed", "unsupported", what=str(exc)) from None
        return self._tapes[key]

    def entry(self, target, k, col=0):
        """Entry (k, col) in the mechanism's own symbols, for sympy work on it — or None when it is too large for
        functions that walk trees (more than :data:`SYMPY_WORK` nodes written out: such work is skipped)."""
        e = self.matrix[k, col]
        if tree_size(e) > SYMPY_WORK:
            return None
        symbols = target.symbols()
        return e.xreplace({s: symbols[s.name] for s in e.free_symbols if s.name in symbols})

    def prefetch(self, target, sets):
        """Evaluate a symbolic answer at several sample sets in one pass of its tape (its cost is per operation,
        not per instant): :meth:`values` then returns each set's part."""
        if self.kind != "symbolic" or len(sets) < 2:
            return
        from .sample import Samples  # import time: grading.sample loads sympy

        joined = Samples(np.concatenate([s.Q for s in sets]), np.concatenate([s.QD for s in sets]),
                         np.concatenate([s.T for s in sets]))
        V, start = self.values(target, joined), 0
        for s in sets:
            self._values[(id(target), id(s))] = V[start:start + s.N]
            start += s.N

    def values(self, target, s):
        """The answer at the instants of ``s``: (N, rows, columns)."""
        if (id(target), id(s)) in self._values:
            return self._values[(id(target), id(s))]
        if self.kind == "numbers":
            return np.broadcast_to(self.array, (s.N,) + self.array.shape).copy()
        if self.kind == "symbolic":
            rows, cols = self.matrix.shape
            v = self.tape(target)(s.Q, s.QD, s.T)["value"]
            return v.reshape(s.N, rows, cols)
        return _same_shapes([self._call(s.Q[k], s.QD[k], s.T[k], target) for k in range(s.N)])

    def derived(self, target, s):
        """Φ, Φ_q (all n columns), ν and γ of this answer read as Φ(q, t), at the instants of ``s``.

        Returns
        -------
        dict of "Phi" (N, k), "Phi_q" (N, k, n), "nu" (N, k), "gamma" (N, k)
        """
        if self.kind == "symbolic":
            return self.tape(target).derived(s.Q, s.QD, s.T)
        if self.kind == "function":
            return _finite_differences(lambda Q, T: self._batch(Q, T, target), s)
        raise Refused("malformed", "needs_expression")

    def jet(self, target, Q, T):
        """This answer read as rows Φ(q, t) at the instants (Q, T): values (B, k), Φ_q (B, k, n) and Φ_t (B, k)."""
        from .sample import Samples  # import time: grading.sample loads sympy

        s = Samples(Q, np.zeros_like(Q), T)
        if self.kind == "symbolic":
            r = self.tape(target)(s.Q, s.QD, s.T, grad=True, order=1)
            return r["value"], r["grad"], r["d1"]
        d = self.derived(target, s)
        return d["Phi"], d["Phi_q"], -d["nu"]

    def gradient(self, target, s):
        """Φ_q (N, k, n) of this answer read as Φ(q, t): the tape's gradients, or finite differences."""
        if self.kind == "symbolic":
            return self.tape(target)(s.Q, s.QD, s.T, grad=True)["grad"]
        return self.derived(target, s)["Phi_q"]

    def _batch(self, Q, T, target):
        return _same_shapes([self._call(Q[k], np.zeros_like(Q[k]), T[k], target) for k in range(len(Q))])[:, :, 0]

    def _call(self, q, qd, t, target):
        f, nargs = self.function, self.nargs
        sig = "f(q, qd, t)" if nargs >= 3 else ("f(q, t)" if nargs == 2 else "f(q)")

        def call(qq, qqd):
            if nargs >= 3:
                return f(qq.copy(), qqd.copy(), float(t))
            return f(qq.copy(), float(t)) if nargs == 2 else f(qq.copy())

        try:
            out = call(q, qd)
        except Exception as exc:  # a student's function may raise anything
            cols = target.cols
            if len(cols) == len(q):
                raise Refused("malformed", "callable_failed", error=f"{type(exc).__name__}: {exc}",
                              signature=sig) from None
            try:  # a function of the coordinates of the constraint's own bodies only
                out = call(q[cols], qd[cols])
            except Exception:
                raise Refused("malformed", "callable_failed", error=f"{type(exc).__name__}: {exc}",
                              signature=sig) from None
        return numbers_of(out, "callable_result", signature=sig)


def tree_size(expr):
    """Nodes of a sympy object written out as a tree, computed over its distinct parts (never a tree walk)."""
    bounds = _bounds()
    huge = bounds.Limits(length=10**9, nodes=10**9, depth=10**9, tree=10**30)
    return bounds.check_expression(expr, where="", limits=huge)[1]


def _same_shapes(outputs):
    """A student function's outputs at the sample instants, stacked — refused, saying so, when their shape
    changes from one call to the next (a row that appears only for some q …)."""
    first = outputs[0].shape
    for out in outputs[1:]:
        if out.shape != first:
            raise Refused("wrong_shape", "shape_changes", first=first, then=out.shape)
    return np.stack(outputs)


# ================================================================================================ reading
def read(answer, target, quantity):
    """Read an answer for ``quantity`` ("Phi", "Phi_q", "nu" or "gamma") of ``target``.

    Returns
    -------
    Answer

    Raises
    ------
    Refused
    """
    if answer is None:
        raise Refused("malformed", "expect_answer", signature=_signature(quantity))
    if callable(answer) and not _is_sympy(answer):
        return Answer("function", function=answer, nargs=_nargs(answer, quantity))
    if isinstance(answer, (bool, np.bool_)):
        raise Refused("malformed", "bool_answer")
    if _plain_numbers(answer):
        return Answer("numbers", array=numbers_of(answer, "answer"))
    if not isinstance(answer, (str, list, tuple, np.ndarray)) and not _is_sympy(answer):
        raise Refused("malformed", "bad_type", expected=Msg(f"expect_{quantity}"), type=type(answer).__name__)
    symbols = target.symbols()
    return Answer("symbolic", matrix=_matrix(answer, symbols, quantity))


def _signature(quantity):
    return "f(q, qd, t)" if quantity_of(quantity).velocities else "f(q, t)"


def _nargs(f, quantity):
    try:
        params = [p for p in inspect.signature(f).parameters.values()
                  if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
        return max(1, len(params))
    except (TypeError, ValueError):
        return 3 if quantity_of(quantity).velocities else 2


def _is_sympy(x):
    sp = sys.modules.get("sympy")
    return sp is not None and isinstance(x, (sp.Basic, sp.MatrixBase))


def _flat(a):
    if isinstance(a, (list, tuple)):
        for x in a:
            yield from _flat(x)
    elif isinstance(a, np.ndarray):
        yield from a.ravel().tolist()
    elif _is_sympy(a) and hasattr(a, "shape"):
        yield from a
    else:
        yield a


def _is_number(x):
    """A Python or numpy number (a sympy number is a formula: it is read as one)."""
    return isinstance(x, (numbers.Number, np.number)) and not isinstance(x, (bool, np.bool_)) and not _is_sympy(x)


def _plain_numbers(a):
    """True for a number or (nested) lists / arrays of numbers only (never evaluates a sympy object)."""
    if _is_number(a):
        return True
    if isinstance(a, np.ndarray) and a.dtype != object:
        return a.size > 0 and a.dtype.kind not in "USV"  # an array of text is read as text
    if isinstance(a, (list, tuple, np.ndarray)):
        items = list(_flat(a))
        return bool(items) and all(_is_number(x) for x in items)
    return False


def numbers_of(value, what, **fields):
    """Real finite-or-not numbers as a 2-D float array; refuses bools, complex values, ragged or huge data."""
    where = what if isinstance(what, Msg) else Msg(what)
    if _is_sympy(value):
        import sympy as sp  # import time: sympy only when needed

        if isinstance(value, sp.MatrixBase):
            value = [[_sympy_number(e, where) for e in value.row(k)] for k in range(value.rows)]
        else:
            value = _sympy_number(value, where)
    elif isinstance(value, (list, tuple, np.ndarray)) and any(_is_sympy(x) for x in _flat(value)):
        # sympy numbers in a list: each bounded before numpy evaluates it (complex(x**10**6) expands a polynomial)
        value = _sympy_numbers(value, where)
    if isinstance(value, (bool, np.bool_)) or (isinstance(value, (list, tuple)) and
                                                 any(isinstance(x, (bool, np.bool_)) for x in _flat(value))):
        raise Refused("malformed", "bool_answer")
    try:
        arr = np.asarray(value)
    except (ValueError, TypeError):
        raise Refused("wrong_shape", "ragged") from None
    if arr.dtype == object:
        if any(x is None for x in arr.flat):  # not "complex numbers" (what None becomes on the way)
            raise Refused("malformed", "not_numbers", what=what, got=describe(value), **fields)
        try:
            arr = arr.astype(complex)
        except OverflowError:  # an integer beyond every float: 10**400
            raise Refused("not_finite", "not_finite", where=where) from None
        except (TypeError, ValueError):
            raise Refused("malformed", "not_numbers", what=what, got=describe(value), **fields) from None
    if arr.dtype.kind == "b":
        raise Refused("malformed", "bool_answer")
    if arr.dtype.kind == "c":
        if np.any(arr.imag != 0):
            raise Refused("malformed", "complex_answer")
        arr = arr.real
    if arr.dtype.kind not in "iuf":
        raise Refused("malformed", "not_numbers", what=what, got=describe(value), **fields)
    if arr.size > MAX_OUTPUT:
        raise Refused("malformed", "too_many_numbers", n=arr.size, limit=MAX_OUTPUT)
    if arr.ndim > 2:
        squeezed = arr.squeeze()
        if squeezed.ndim > 2:
            raise Refused("wrong_shape", "too_many_axes", shape=arr.shape)
        arr = squeezed
    arr = np.asarray(arr, float)
    if arr.ndim == 0:
        arr = arr.reshape(1, 1)
    elif arr.ndim == 1:
        arr = arr.reshape(-1, 1)
    return arr


def describe(value, width=40):
    """What was received, for a message: its type (an array's dtype and shape) and the start of its repr."""
    text = repr(value)
    text = text if len(text) <= width else text[: width - 1] + "…"
    if isinstance(value, np.ndarray):
        return f"{type(value).__name__} of dtype {value.dtype}, shape {value.shape}: {text}"
    return f"{type(value).__name__} {text}"


def _sympy_numbers(value, where):
    """A (nested) list of numbers and sympy objects, each sympy one bounded and evaluated (:func:`_sympy_number`)."""
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [_sympy_numbers(x, where) for x in value]
    if _is_sympy(value):
        return _sympy_numbers(value.tolist(), where) if hasattr(value, "shape") else _sympy_number(value, where)
    return value


def _sympy_number(e, where):
    ex = _reader()
    try:  # bounded before sympy walks it (is_number, free_symbols and evaluation walk the tree)
        _bounds().check_expression(e, where=where, limits=_limits())
    except ex.ExpressionError as err:
        raise Refused("malformed", "reader", message=err.message) from None
    if getattr(e, "is_number", False) and not e.free_symbols:
        try:
            c = complex(e)
        except (TypeError, ValueError, OverflowError):
            return np.nan
        return c if c.imag else c.real
    raise Refused("malformed", "returns_symbols")


def _matrix(answer, symbols, quantity):
    """A sympy Matrix from text, sympy objects or (nested) lists of those and numbers."""
    import sympy as sp  # import time: sympy only when needed

    if isinstance(answer, sp.MatrixBase):
        M = _sympy_matrix(answer)
        return M.T if M.rows == 1 and M.cols > 1 and not quantity_of(quantity).per_coordinate else M
    if isinstance(answer, np.ndarray):
        rows = _rows(answer.tolist())
    elif isinstance(answer, (list, tuple)):
        rows = _rows(list(answer))
    else:
        rows = [[answer]]
    entries = []
    for i, row in enumerate(rows):
        out = []
        for j, e in enumerate(row):
            where = Msg("answer_row", i=i + 1) if len(row) == 1 else Msg("answer_entry", i=i + 1, j=j + 1)
            out.append(_entry(e, symbols, where))
        entries.append(out)
    M = sp.Matrix(entries)
    if M.rows == 1 and M.cols > 1 and not quantity_of(quantity).per_coordinate:
        M = M.T  # a row vector for a column quantity
    return M


def _sympy_matrix(M):
    """A student's sympy Matrix: one walk of the reader's bounds over all its entries (bounded in total)."""
    import sympy as sp  # import time: sympy only when needed

    ex = _reader()
    entries = M.tolist()
    for i, row in enumerate(entries):
        for j, e in enumerate(row):
            if not isinstance(e, sp.Expr) or isinstance(e, sp.MatrixBase):
                where = Msg("answer_entry", i=i + 1, j=j + 1)
                raise Refused("malformed", "not_an_expression", where=where, type=type(e).__name__)
    limits = _limits()
    try:
        _bounds().check_expression(M, where=Msg("answer"), limits=type(limits)(
            length=limits.length, nodes=limits.nodes * max(1, min(len(M), 50)), depth=limits.depth,
            tree=limits.tree * max(1, min(len(M), 50))))
    except ex.ExpressionError as err:
        raise _reader_refused(err) from None
    return sp.ImmutableMatrix(M)


def _reader_refused(err):
    """The reader's refusal of an entry (its message, written in the language of the moment when shown), with the
    catalogue code of its cause."""
    reason = str(err.reason or "")
    code = "not_finite" if reason == "not finite" else "unknown_symbol" if reason.startswith("unknown name") \
        else "malformed"
    return Refused(code, "reader", message=err.message)


def _rows(items):
    if not items:
        raise Refused("wrong_shape", "empty_answer")
    nested = [isinstance(r, (list, tuple, np.ndarray)) or (_is_sympy(r) and hasattr(r, "shape")) for r in items]
    if all(nested):
        rows = [list(_flat_row(r)) for r in items]
        widths = {len(r) for r in rows}
        if len(widths) != 1 or 0 in widths:
            raise Refused("wrong_shape", "ragged")
        return rows
    if any(nested):
        raise Refused("wrong_shape", "ragged")
    return [[x] for x in items]


def _flat_row(r):
    if isinstance(r, np.ndarray):
        return r.ravel().tolist()
    if _is_sympy(r):
        return list(r)
    for x in r:
        if isinstance(x, (list, tuple, np.ndarray)) or (_is_sympy(x) and hasattr(x, "shape")):
            raise Refused("wrong_shape", "nested_deeper")
    return list(r)


def _entry(e, symbols, where):
    import sympy as sp  # import time: sympy only when needed

    ex = _reader()
    if isinstance(e, str):
        if not e.strip():
            raise Refused("malformed", "empty_text", where=where)
        try:
            return ex.read_expression(e, symbols=symbols, where=where, limits=_limits())
        except ex.ExpressionError as err:
            raise _reader_refused(err) from None
    if isinstance(e, (bool, np.bool_)):
        raise Refused("malformed", "bool_answer")
    if _is_number(e):
        if isinstance(e, (complex, np.complexfloating)):
            if e.imag != 0:
                raise Refused("malformed", "complex_answer")
            e = e.real
        try:
            value = float(e)
        except OverflowError:  # an integer beyond every float: 10**400
            raise Refused("not_finite", "not_finite", where=where) from None
        if not np.isfinite(value):
            raise Refused("not_finite", "not_finite", where=where)
        return sp.Integer(int(e)) if isinstance(e, (numbers.Integral, np.integer)) else sp.Float(value)
    if not isinstance(e, sp.Basic):
        raise Refused("malformed", "bad_entry", where=where, type=type(e).__name__)
    if not isinstance(e, sp.Expr) or isinstance(e, sp.MatrixBase):
        raise Refused("malformed", "not_an_expression", where=where, type=type(e).__name__)
    try:
        _bounds().check_expression(e, where=where, limits=_limits())
    except ex.ExpressionError as err:
        raise _reader_refused(err) from None
    return e  # its symbols are matched by name when it is taped (Answer.tape)


# ================================================================================================ derivatives
def _finite_differences(F, s, h=1e-3):
    """Φ, Φ_q, ν, γ of a numeric Φ(q, t) (vectorized F(Q, T) -> (N, k)) by central differences with one
    Richardson extrapolation (error O(h⁴))."""
    Q, QD, T = s.Q, s.QD, s.T
    N, n = Q.shape
    phi = F(Q, T)
    k = phi.shape[1]

    def d1(direction_q, direction_t, step):
        return (F(Q + step * direction_q, T + step * direction_t)
                - F(Q - step * direction_q, T - step * direction_t)) / (2 * step)

    def rich1(dq, dt):
        return (4 * d1(dq, dt, h / 2) - d1(dq, dt, h)) / 3

    def d2(step):
        return (F(Q + step * QD, T + step) - 2 * phi + F(Q - step * QD, T - step)) / (step * step)

    jac = np.zeros((N, k, n))
    for j in range(n):
        e = np.zeros((N, n))
        e[:, j] = 1.0
        jac[:, :, j] = rich1(e, np.zeros(N))
    phi_t = rich1(np.zeros((N, n)), np.ones(N))
    gamma = -(4 * d2(h / 2) - d2(h)) / 3
    return {"Phi": phi, "Phi_q": jac, "nu": -phi_t, "gamma": gamma}


# ================================================================================================ the answer as read
MAX_CHARS = 2000
"""An echo longer than this is cut (with "…")."""

_COORD = re.compile(r"^(d?)(x|y|z|phi|e0|e1|e2|e3)(\d+)$")
_TEX = {"x": "x", "y": "y", "z": "z", "phi": r"\varphi"}


def tex_name(name, letters=None):
    """The book's LaTeX for one of kinbook's coordinate names, or None for any other name: x1 → x_{1},
    phi2 → \\varphi_{2}, dphi2 → \\dot{\\varphi}_{2}, e02 → e_{0,2}. ``letters`` (body number → one-letter
    name) writes a body's letter as the subscript: x1 → x_{i}, e01 → e_{0i}. The one rule of the notation, for the
    answer as read here and for the book's pages (:func:`kinbook.book.notation.names`)."""
    m = _COORD.match(name)
    if not m:
        return None
    dot, base, number = m.groups()
    sub = (letters or {}).get(number, number)
    if base.startswith("e"):  # Euler parameters e_{0i}: the book's index first, then the body
        head, sub = "e", base[1] + ("," if len(sub) > 1 or sub.isdigit() else "") + sub
    else:
        head = _TEX[base]
    return (rf"\dot{{{head}}}" if dot else head) + f"_{{{sub}}}"


def _names(M):
    """sympy.latex ``symbol_names`` in the book's notation (:func:`tex_name`)."""
    return {s: tex for s in M.free_symbols if (tex := tex_name(s.name)) is not None}


def _cut(text):
    return text if len(text) <= MAX_CHARS else text[:MAX_CHARS - 1] + "…"


def read_as(value):
    """``(text, latex)`` of an answer as read: a sympy Matrix (rows of expressions) or numbers; None otherwise."""
    import sympy as sp  # import time: sympy only when needed

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
    from .target import target_for  # import time: the target loads sympy and the chapters; item.py imports echoed

    A = read(answer, target_for(reference), quantity)
    return A.matrix if A.kind == "symbolic" else getattr(A, "array", None)
