"""Reading a student's answer: sympy expressions, strings, callables or plain numbers.

:func:`read` turns any accepted form into an :class:`Answer`: something that evaluates, vectorized, at a set
of sample instants. A malformed answer is never an exception: :func:`read` returns a :class:`Malformed` that
says what was expected, and the checker turns it into a failed result.

Symbols are matched *by name*: a student who writes ``sp.symbols("x1 phi2")`` (without ``real=True``) gets
the mechanism's x1 and phi2. Accepted spellings of a coordinate: ``phi2``, ``phi_2``, ``φ2``; of a velocity:
``dphi2``, ``phi2_dot``, ``dφ2``.

Size and time caps: an expression tree larger than :data:`MAX_NODES` nodes, or a string longer than
:data:`MAX_CHARS`, is refused; reading and compiling are run under :func:`~._timelimit.run_limited`
(:data:`READ_SECONDS`), and so are calls of a student's function (:data:`CALL_SECONDS` for all samples).
A signal cannot interrupt a single long C-level operation, so strings with towers of integer powers
(``9**9**9``) or huge integer exponents are refused before sympy sees them. Plain numbers and sympy objects
are never evaluated by sympy (``float(expr)`` of a huge tree can take unbounded time): numbers are
recognized by type.
"""

from __future__ import annotations

import inspect
import re
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ._i18n import tr
from ._target import Compiled
from ._timelimit import run_limited

__all__ = ["Answer", "Malformed", "read", "MAX_NODES", "MAX_CHARS", "READ_SECONDS", "CALL_SECONDS"]

_INT = re.compile(r"[+-]?\d{1,15}")
# integer powers that Python would compute exactly, in C, where no signal can stop it: 9**9**9, x**123456
_HUGE_POWER = re.compile(r"\d\s*\)?\s*\*\*\s*\(?\s*\d+\s*\)?\s*\*\*|\*\*\s*\(?\s*\d{5,}")
CALL_SECONDS = 5.0
MAX_NODES = 300_000
MAX_CHARS = 20_000
READ_SECONDS = 3.0


@dataclass
class Malformed:
    """An answer that cannot be graded: a catalogue code and a message saying what was expected."""

    code: str
    message: str


class Answer:
    """A readable answer.

    Attributes
    ----------
    kind : {"symbolic", "callable", "numeric"}
    shape : tuple
        Shape of one evaluation.
    expr : sympy.Matrix or None
        The answer as sympy, when it was given symbolically.
    """

    def __init__(self, kind, shape, evaluate, expr=None):
        self.kind, self.shape, self._evaluate, self.expr = kind, shape, evaluate, expr

    def __call__(self, samples):
        """Values at the instants of ``samples``: an array (N,) + shape, or a :class:`Malformed`."""
        try:
            out = self._evaluate(samples)
        except Exception as exc:  # a student's callable or an odd expression may raise anything
            return Malformed("malformed", tr("evaluation_failed", error=f"{type(exc).__name__}: {exc}"))
        return out


def _alias(name):
    n = name.replace("φ", "phi").replace("ϕ", "phi").replace("\\", "").replace("{", "").replace("}", "")
    m = re.fullmatch(r"(d?)([a-z]+)_?(\d+)(_?dot)?", n)
    if m:
        d = "d" if (m.group(1) or m.group(4)) else ""
        return f"{d}{m.group(2)}{m.group(3)}"
    return n


def _nodes(expr, limit):
    count = 0
    for _ in sp.preorder_traversal(expr):
        count += 1
        if count > limit:
            break
    return count


def _to_matrix(answer, symbols):
    """A sympy Matrix from a Matrix, an expression, a string, or (nested) lists of those; strings are
    parsed here (with the size cap), never by sympy's Matrix constructor."""
    if isinstance(answer, sp.MatrixBase):
        return sp.Matrix(answer.rows, answer.cols, [_leaf(e, symbols) for e in answer])
    if isinstance(answer, np.ndarray):
        answer = answer.tolist()
    if isinstance(answer, (list, tuple)):
        if not answer:
            raise _Refused("wrong_shape", tr("wrong_shape", expected="at least one row", got="[]"))
        if all(isinstance(r, (list, tuple, sp.MatrixBase, np.ndarray)) for r in answer):
            rows = [list(r) for r in answer]
            width = {len(r) for r in rows}
            if len(width) != 1 or 0 in width:
                raise _Refused("wrong_shape", tr("wrong_shape", expected="rows of equal length",
                                                 got=[len(r) for r in rows]))
            return sp.Matrix([[_leaf(e, symbols) for e in r] for r in rows])
        return sp.Matrix([_leaf(e, symbols) for e in answer])
    return sp.Matrix([_leaf(answer, symbols)])


def _leaf(e, symbols):
    if isinstance(e, str):
        if len(e) > MAX_CHARS:
            raise _Refused("malformed", tr("too_large", size=len(e), limit=MAX_CHARS))
        text = e.replace("φ", "phi").replace("^", "**")
        if _HUGE_POWER.search(text):
            raise _Refused("malformed", tr("too_large", size="a huge integer power", limit="10⁴"))
        plain = text.strip()
        if _INT.fullmatch(plain):  # fast path: most entries of a Jacobian are 0, 1 or -1
            return sp.Integer(int(plain))
        try:
            value = sp.sympify(text, locals=dict(symbols))
        except Exception as exc:  # SympifyError, SyntaxError, TypeError, TokenError, RecursionError …
            raise _Refused("malformed", tr("unparsable", text=_short(e), error=type(exc).__name__)) from None
        return _expr(value, e)
    if isinstance(e, (list, tuple, sp.MatrixBase, np.ndarray)):
        raise _Refused("wrong_shape", tr("wrong_shape", expected="a vector or a matrix", got="nested deeper"))
    if isinstance(e, bool):
        raise _Refused("malformed", tr("bad_type", expected="an expression", type="bool"))
    try:
        value = sp.sympify(e, strict=True)
    except Exception:
        raise _Refused("malformed", tr("bad_type", expected="an expression", type=type(e).__name__)) from None
    return _expr(value, e)


def _expr(value, original):
    """Only expressions go into a Matrix (relations, booleans, sets … are refused)."""
    if not isinstance(value, sp.Expr):
        raise _Refused("malformed", tr("bad_type", expected="an expression", type=type(value).__name__))
    return value


class _Refused(Exception):
    def __init__(self, code, message):
        super().__init__(message)
        self.code, self.message = code, message


def _bind_symbols(M, symbols):
    free = set().union(*(e.free_symbols for e in M)) if len(M) else set()
    repl, unknown = {}, []
    for s in free:
        if s in symbols.values():
            continue
        alias = _alias(s.name)
        if alias in symbols:
            repl[s] = symbols[alias]
        else:
            unknown.append(s.name)
    if unknown:
        allowed = ", ".join(list(symbols)[:3]) + " …, " + "dx1, dy1, dphi1 …, t"
        raise _Refused("unknown_symbol", tr("unknown_symbols", names=", ".join(sorted(unknown)), allowed=allowed))
    return M.xreplace(repl) if repl else M


def read(answer, target, quantity, expected_shape, at=None):
    """Read an answer for ``quantity`` ("Phi", "Phi_q", "nu", "gamma").

    Parameters
    ----------
    answer
        sympy Matrix / expression / list of expressions or strings; a callable ``f(q, t)`` (``f(q, qd, t)``
        for γ) returning numbers; or numbers (evaluated at the configuration ``at``).
    target : Target
    expected_shape : tuple
        Shape of the reference, used to read flat lists and to call functions.
    at : Samples or None
        The configuration at which numbers are graded.

    Returns
    -------
    Answer or Malformed
    """
    if answer is None:
        return Malformed("malformed", _expected_msg(quantity))
    if callable(answer) and not isinstance(answer, (sp.Basic, sp.MatrixBase)):
        return _read_callable(answer, target, quantity)
    if isinstance(answer, (int, float, complex, np.number)) or (
        isinstance(answer, (list, tuple, np.ndarray)) and _all_numbers(answer)
    ):
        return _read_numbers(answer, quantity, at)
    if not isinstance(answer, (str, list, tuple, sp.Basic, sp.MatrixBase, np.ndarray)):
        return Malformed("malformed", tr("bad_type", expected=_expected_msg(quantity), type=type(answer).__name__))
    symbols = target.symbols()

    def work():
        M = _to_matrix(answer, symbols)
        size = sum(_nodes(e, MAX_NODES + 1) for e in M)
        if size > MAX_NODES:
            raise _Refused("malformed", tr("too_large", size=f"> {MAX_NODES}", limit=MAX_NODES))
        M = _bind_symbols(M, symbols)
        if M.shape[0] == 1 and M.shape[1] > 1 and len(expected_shape) == 2 and expected_shape[1] == 1:
            M = M.T  # a row vector for a column quantity
        if any(not isinstance(e, sp.Expr) for e in M):
            raise _Refused("malformed", tr("bad_type", expected=_expected_msg(quantity), type="non-expression"))
        return M, Compiled(M, target.args)

    try:
        got = run_limited(work, READ_SECONDS, on_timeout=lambda: None, required=True)
    except _Refused as exc:
        return Malformed(exc.code, exc.message)
    except (ValueError, TypeError, AttributeError, sp.SympifyError, RecursionError) as exc:
        return Malformed("malformed", tr("unparsable", text=_short(answer), error=f"{type(exc).__name__}: {exc}"))
    if got is None:
        return Malformed("malformed", tr("timeout", seconds=READ_SECONDS))
    M, compiled = got
    return Answer("symbolic", M.shape, lambda s: compiled(s.columns(), s.N), expr=M)


def _short(answer):
    text = str(answer)
    return text if len(text) < 80 else text[:77] + "..."


def _expected_msg(quantity):
    sig = "f(q, qd, t)" if quantity == "gamma" else "f(q, t)"
    return tr("expect_symbolic", symbols="x1, y1, phi1 …, dx1 …, t", signature=sig)


def _flat(a):
    if isinstance(a, (list, tuple)):
        for x in a:
            yield from _flat(x)
    elif isinstance(a, sp.MatrixBase):
        yield from a
    else:
        yield a


def _all_numbers(a):
    """Plain numbers only (never evaluates a sympy expression: that can take unbounded time)."""
    if isinstance(a, np.ndarray) and a.dtype != object:
        return a.dtype.kind in "biuf" and a.size > 0
    items = list(_flat(a.tolist() if isinstance(a, np.ndarray) else a))
    if not items or not all(isinstance(x, (int, float, np.number)) and not isinstance(x, bool)
                            or (isinstance(x, sp.Number)) for x in items):
        return False
    try:
        arr = np.asarray(a, dtype=float)
    except Exception:
        return False
    if arr.dtype == object:
        try:
            arr = arr.astype(float)
        except (TypeError, ValueError):
            return False
    return arr.dtype.kind in "biuf"


def _as_matrix_shape(arr):
    arr = np.asarray(arr, dtype=float)
    if arr.ndim == 0:
        arr = arr.reshape(1, 1)
    elif arr.ndim == 1:
        arr = arr.reshape(-1, 1)
    return arr


def _read_numbers(answer, quantity, at):
    if at is None:
        return Malformed("malformed", tr("needs_configuration"))
    arr = _as_matrix_shape(answer)
    return Answer("numeric", arr.shape, lambda s: np.broadcast_to(arr, (s.N,) + arr.shape).copy())


def _read_callable(f, target, quantity):
    try:
        params = [p for p in inspect.signature(f).parameters.values()
                  if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
        nargs = len(params)
    except (TypeError, ValueError):
        nargs = 3 if quantity == "gamma" else 2
    sig = "f(q, qd, t)" if nargs >= 3 else ("f(q, t)" if nargs == 2 else "f(q)")
    cols = target.cols

    def call(qv, qdv, tv):
        if nargs >= 3:
            return f(qv, qdv, tv)
        if nargs == 2:
            return f(qv, tv)
        return f(qv)

    def evaluate(samples):
        out = []
        for k in range(samples.N):
            q, qd, t = samples.Q[k], samples.QD[k], float(samples.T[k])
            try:
                v = call(q.copy(), qd.copy(), t)
            except Exception as exc:
                if len(cols) == len(q):
                    raise RuntimeError(tr("callable_failed", error=f"{type(exc).__name__}: {exc}", signature=sig))
                try:  # a function of the constraint's own bodies' coordinates only
                    v = call(q[cols].copy(), qd[cols].copy(), t)
                except Exception:
                    raise RuntimeError(tr("callable_failed", error=f"{type(exc).__name__}: {exc}",
                                          signature=sig)) from None
            v = np.asarray(v, dtype=float) if not isinstance(v, sp.MatrixBase) else np.array(v.evalf(), dtype=float)
            out.append(_as_matrix_shape(v))
        shapes = {o.shape for o in out}
        if len(shapes) != 1:
            raise RuntimeError(tr("wrong_shape", expected="the same shape at every call", got=sorted(shapes)))
        return np.stack(out)

    def guarded(samples):
        timeout = Malformed("malformed", tr("timeout", seconds=CALL_SECONDS))
        try:
            return run_limited(lambda: evaluate(samples), CALL_SECONDS, on_timeout=lambda: timeout, required=True)
        except RuntimeError as exc:
            return Malformed("malformed", str(exc))
        except Exception as exc:
            return Malformed("malformed", tr("callable_failed", error=f"{type(exc).__name__}: {exc}",
                                             signature=sig))

    return Answer("callable", None, guarded)
