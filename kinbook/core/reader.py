"""The one reader of untrusted text: every expression kinbook takes from a mechanism file, a student or the
command line is read here, and nowhere else.

How (PrairieLearn's symbolic input is the model): the text is parsed by Python's own parser into an abstract
syntax tree (:mod:`ast`, which only parses — it runs nothing), the tree is walked against an allow-list, and
only a tree that passed is built into a sympy object. Nothing is ever given to ``eval``, ``exec`` or
``sympy.sympify``. Every bound is checked *before* any arithmetic, so a hostile input is refused in
microseconds instead of being evaluated to find out that it is too big.

What an expression may contain
------------------------------
- numbers: ``2``, ``-0.5``, ``1e-3`` (decimal integers and floats; no complex ``1j``);
- the names of the context — the ``symbols`` argument (``t`` in a driver, the coordinates in an answer) —
  and the constants ``pi`` (also ``π``) and ``E`` (Euler's number);
- ``+ - * /``, powers written ``^`` or ``**``, unary minus, parentheses;
- calls of the functions in :data:`FUNCTIONS`: ``sin cos tan asin acos atan atan2 sqrt exp log Abs sign``,
  and the spellings in :data:`ALIASES` (the book's Spanish ``sen``, ``abs``, ``ln``, ``arctan`` …).

Nothing else: no attribute access (``x.real``), no subscripts, no other calls, no keywords, comparisons,
conditionals, strings, lambdas or names outside the context; products need their ``*`` (``2*t``, not ``2t``).

Bounds (:mod:`kinbook.core.bounds`), checked on the text and the tree before sympy sees anything: length, tree
nodes, nesting depth, digits of a literal, a numeric exponent's size (``x**100000``: no kinematic expression
needs it), the magnitude of every all-number sub-expression (``10**10**10``, ``exp(1000)`` are refused).
The built expression must be finite: ``1/0`` is refused.
"""

from __future__ import annotations

import ast
import math
import numbers
import operator
import re
from collections.abc import Mapping

import mpmath
import sympy as sp

from ..errors import ExpressionError
from ..i18n import N_, Np_
from ._mpvalue import COMPLEX, MP_BY_NAME, mp_value
from .bounds import DEFAULT_LIMITS, check_expression, refuse, too_large
from .refusals import HINTS, NOT_FINITE, REFUSED_NODES, fail, short, syntax_reason, unknown
from .refusals import m as _m

__all__ = ["read_expression", "read_number", "read_constant", "FUNCTIONS", "ALIASES", "CONSTANTS", "ExpressionError"]

FUNCTIONS = {
    "sin": (sp.sin, (1,)),
    "cos": (sp.cos, (1,)),
    "tan": (sp.tan, (1,)),
    "asin": (sp.asin, (1,)),
    "acos": (sp.acos, (1,)),
    "atan": (sp.atan, (1,)),
    "atan2": (sp.atan2, (2,)),
    "sqrt": (sp.sqrt, (1,)),
    "exp": (sp.exp, (1,)),
    "log": (sp.log, (1, 2)),
    "Abs": (sp.Abs, (1,)),
    "sign": (sp.sign, (1,)),
}
"""The functions an expression may call: name → (sympy function, accepted numbers of arguments).
``log(x, b)`` is the logarithm of x in base b; ``atan2(y, x)`` the angle of the point (x, y)."""

ALIASES = {
    "sen": "sin",  # the textbook's (Spanish) spelling
    "asen": "asin",
    "arcsen": "asin",
    "arcsin": "asin",
    "arccos": "acos",
    "arctan": "atan",
    "arctan2": "atan2",
    "tg": "tan",
    "ln": "log",
    "abs": "Abs",
}
"""Other spellings accepted for the functions of :data:`FUNCTIONS`."""

CONSTANTS = {"pi": sp.pi, "π": sp.pi, "E": sp.E}
"""Named constants: π and Euler's number e (written ``E``, as sympy does, so that ``e`` stays free)."""

_OPERATORS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Pow: "^"}
_BINOP_NAMES = {ast.Mod: "%", ast.FloorDiv: "//", ast.MatMult: "@", ast.BitAnd: "&", ast.BitOr: "|",
                ast.LShift: "<<", ast.RShift: ">>", ast.BitXor: "xor"}


def _function_table(functions):
    if functions is None:
        return FUNCTIONS, ALIASES
    if isinstance(functions, Mapping):
        table = {}
        for name, f in functions.items():
            if isinstance(f, tuple):
                table[name] = f
            else:
                nargs = getattr(f, "nargs", None)
                counts = tuple(sorted(nargs)) if isinstance(nargs, sp.FiniteSet) and len(nargs) < 5 else (1, 2, 3)
                table[name] = (f, counts)
        return table, {}
    names = list(functions)
    unknown = [n for n in names if n not in FUNCTIONS and n not in ALIASES]
    if unknown:
        raise ValueError(f"`functions`: unknown function name(s) {', '.join(unknown)} (known: {', '.join(FUNCTIONS)})")
    table = {ALIASES.get(n, n): FUNCTIONS[ALIASES.get(n, n)] for n in names}
    aliases = {a: f for a, f in ALIASES.items() if f in table}
    return table, aliases


def read_expression(text, *, symbols, where, functions=None, limits=None):
    """Read an expression from untrusted text, against an allow-list.

    Parameters
    ----------
    text : str
        The expression, e.g. ``"pi/4 + 100*t"`` or ``"x2 - cos(phi2)"``. ``^`` means power.
    symbols : Mapping[str, sympy.Symbol]
        The names allowed in this context and the symbols they stand for (any Mapping: a class that
        resolves spellings such as ``phi_2`` lazily in ``__contains__`` / ``__getitem__`` works).
    where : str
        Says where the text came from, for the messages: ``"file 'x.toml', key constraints[3].f"``.
    functions : Mapping[str, callable] or iterable of str, optional
        Default :data:`FUNCTIONS` (with :data:`ALIASES`). An iterable of names restricts the default set; a
        mapping name → sympy function (or (function, accepted argument counts)) replaces it.
    limits : Limits, optional
        Default :data:`DEFAULT_LIMITS`.

    Returns
    -------
    sympy.Expr

    Raises
    ------
    ExpressionError
        The text is not an expression of the allowed form, or exceeds a bound; the message names ``where``,
        says what is wrong and where in the text, and what was expected.

    Examples
    --------
    >>> import sympy as sp
    >>> t = sp.Symbol("t", real=True)
    >>> read_expression("3*pi/4 + 100*t", symbols={"t": t}, where="driver f")
    100*t + 3*pi/4
    >>> read_expression("2^10 - sen(0)", symbols={}, where="a number")
    1024
    >>> read_expression("__import__('os')", symbols={}, where="q0[0]")
    Traceback (most recent call last):
    ...
    kinbook.errors.ExpressionError: q0[0]: unknown function '__import__' at column 1 in "__import__('os')"; expected a number or an expression of numbers with + - * / ^, the functions sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, log, Abs, sign and the constants pi, E
    """
    limits = DEFAULT_LIMITS if limits is None else limits
    if not isinstance(text, str):
        refuse(where, _m(N_("expected the text of an expression, got {type}"), type=type(text).__name__),
               code="not a string")
    if len(text) > limits.length:  # before anything that reads the whole text
        fail(where, text, _m(Np_("the text is too long ({n} character, at most {limit})",
                                  "the text is too long ({n} characters, at most {limit})"), n=len(text),
                              limit=limits.length))
    reader = _Reader(text, symbols, where, functions, limits)
    if not reader.source:
        reader.fail(_m(N_("the text is empty")), reader.expected())
    try:
        tree = ast.parse(reader.source, mode="eval")
    except SyntaxError as exc:
        column = reader.column(char=exc.offset - 1) if exc.offset and exc.lineno == 1 else None
        reader.fail(syntax_reason(exc.msg), reader.expected(), column=column)
    except (ValueError, RecursionError, MemoryError):  # null bytes, or nesting beyond the parser's stack
        reader.fail(_m(N_("not a valid expression (unreadable characters or nesting too deep)")))
    reader.walk(tree.body)
    expr = reader.build(tree.body)
    if not isinstance(expr, sp.Expr):
        reader.fail(_m(N_("not an expression of a number (got {type})"), type=type(expr).__name__))
    if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
        reader.fail(_m(N_("the expression is not finite (a division by zero?)")), _m(N_("a finite expression")))
    return expr


class _Reader:
    """One reading: the text, its context, and the walk and build over its tree."""

    def __init__(self, text, symbols, where, functions, limits):
        self.text, self.symbols, self.where, self.limits = text, symbols, where, limits
        self.table, self.aliases = _function_table(functions)
        stripped = text.lstrip()
        self.offset = len(text) - len(stripped)  # columns in messages count in the text as given
        body = stripped.rstrip()
        self.source = body.replace("^", "**")
        # a column of the parsed source -> a column of the text: each '^' became two characters, and the parser
        # counts a node's column in UTF-8 bytes (two for π, three for ẋ)
        self.chars = [i for i, ch in enumerate(body) for _ in range(2 if ch == "^" else 1)] + [len(body)]
        self.encoded = self.source.encode("utf-8")
        self.value = {}  # id(node) -> float estimate of a numeric sub-expression, or None
        self.calls = {}  # id(node) -> nesting depth of function calls in the sub-expression
        self.bits = {}  # id(node) -> bound on the bits of the exact numbers sympy builds for the sub-expression

    def fail(self, reason, expected=None, node=None, column=None):
        """Refuse the text for ``reason`` (a marked message), at a node or a column."""
        if column is None and node is not None:
            column = self.column(node=node)
        fail(self.where, self.text, reason, expected, column=column)

    def column(self, node=None, char=None):
        """The 1-based column, in characters of the text as given, of a node (or of a character of the
        parsed source)."""
        if node is not None:
            char = len(self.encoded[:node.col_offset].decode("utf-8", errors="ignore"))
        return self.chars[max(0, min(char, len(self.chars) - 1))] + 1 + self.offset

    def literal(self, node):
        """The text of a numeric literal, as written."""
        return self.encoded[node.col_offset:node.end_col_offset].decode("utf-8", errors="replace")

    def expected(self):
        symbols = self.symbols
        functions = ", ".join(self.table)
        if not symbols:
            return _m(N_("a number or an expression of numbers with + - * / ^, the functions {functions} and the "
                         "constants pi, E"), functions=functions)
        names = ", ".join(list(symbols)[:8]) + (" …" if len(symbols) > 8 else "")
        return _m(N_("an expression of {names} with + - * / ^, the functions {functions} and the constants pi, E"),
                  names=names, functions=functions)

    # ------------------------------------------------------------------------------------------- walk
    def walk(self, root):
        """Check the tree against the allow-list and the bounds, iteratively (no recursion on a deep tree),
        evaluating nothing but float estimates of numeric sub-expressions (bounded work per node)."""
        limits = self.limits
        count = 0
        stack = [(root, 1, False)]
        while stack:
            node, depth, visited = stack.pop()
            if visited:
                self.calls[id(node)] = max((self.calls[id(c)] for c in ast.iter_child_nodes(node)
                                            if id(c) in self.calls), default=0) + isinstance(node, ast.Call)
                self.value[id(node)] = self.estimate(node)
                self.bits[id(node)] = self.exact_bits(node)
                continue
            count += 1
            if count > limits.nodes:
                self.fail(_m(Np_("the expression is too large (more than {n} part)",
                                 "the expression is too large (more than {n} parts)"), n=limits.nodes))
            if depth > limits.depth:
                self.fail(_m(Np_("the expression is nested too deeply (more than {n} level)",
                                 "the expression is nested too deeply (more than {n} levels)"), n=limits.depth),
                          node=node)
            stack.append((node, depth, True))
            for c in self.children(node):
                # a chain a + b - c + … (or a * b / c …) is one level, however long: sums of many terms
                # are legitimate, and the build flattens them without recursion
                chain = isinstance(c, ast.BinOp) and c is getattr(node, "left", None) and _family(c) == _family(node)
                stack.append((c, depth if chain else depth + 1, False))

    def children(self, node):
        table, aliases, symbols = self.table, self.aliases, self.symbols
        if isinstance(node, ast.Constant):
            v = node.value
            if isinstance(v, bool) or v is None or v is Ellipsis:
                self.fail(_m(N_("{value} is not a number"), value=repr(v)), node=node)
            if isinstance(v, complex):
                self.fail(_m(HINTS["I"]), node=node)
            if not isinstance(v, (int, float)):
                self.fail(_m(N_("a {type} literal is not an expression of a number"), type=type(v).__name__),
                          self.expected(), node)
            width = (node.end_col_offset or 0) - node.col_offset if node.end_lineno == node.lineno else None
            if width is None or width > self.limits.digits:
                self.fail(_m(Np_("a number is too long (more than {n} character)",
                                 "a number is too long (more than {n} characters)"), n=self.limits.digits), node=node)
            written = self.literal(node)
            if not _DECIMAL.fullmatch(written):  # Python also reads 0x1f, 0o17, 0b101, 1_000
                self.fail(_m(N_("the number {number} is not written in decimal digits"), number=repr(written)),
                          _m(N_("a decimal number such as 12, -0.5 or 1e-3")), node)
            if isinstance(v, float) and not math.isfinite(v):
                self.fail(_m(N_("a number is not finite (too large for a float)")), node=node)
            if abs(v) > self.limits.magnitude:  # before any arithmetic: 1e308 squared overflows
                self.fail(too_large(self.limits.magnitude), node=node)
            return ()
        if isinstance(node, ast.Name):
            name = node.id
            if name in symbols or name in CONSTANTS:
                return ()
            if name in table or name in aliases:
                self.fail(_m(N_("'{name}' is a function: call it, as in {name}(…)"), name=name), node=node)
            self.fail(unknown(N_("unknown name '{name}'"), N_("unknown name '{name}' ({hint})"), name),
                      self.expected(), node)
        if isinstance(node, ast.BinOp):
            if type(node.op) not in _OPERATORS:
                op = _BINOP_NAMES.get(type(node.op), type(node.op).__name__)
                self.fail(_m(N_("the operator '{op}' is not allowed"), op=op), _m(N_("+ - * / ^")), node)
            return (node.left, node.right)
        if isinstance(node, ast.UnaryOp):
            if not isinstance(node.op, (ast.USub, ast.UAdd)):
                op = {ast.Not: "not", ast.Invert: "~"}.get(type(node.op), type(node.op).__name__)
                self.fail(_m(N_("the operator '{op}' is not allowed"), op=op), _m(N_("+ - * / ^ and unary minus")),
                          node)
            return (node.operand,)
        if isinstance(node, ast.Call):
            func = node.func
            if not isinstance(func, ast.Name):
                what = REFUSED_NODES[ast.Attribute] if isinstance(func, ast.Attribute) else \
                    N_("this kind of call is not allowed")
                self.fail(_m(what), _m(N_("a call of one of {functions}"), functions=", ".join(table)), node)
            name = aliases.get(func.id, func.id)
            if name not in table:
                if func.id in symbols or func.id in CONSTANTS:
                    self.fail(_m(N_("'{name}' is not a function (a product needs its *: {name}*(…))"), name=func.id),
                              node=node)
                self.fail(unknown(N_("unknown function '{name}'"), N_("unknown function '{name}' ({hint})"), func.id),
                          self.expected(), node)
            if node.keywords:
                self.fail(_m(N_("{name}() takes no keyword arguments"), name=func.id), node=node)
            counts = table[name][1]
            if len(node.args) not in counts:
                self.fail(_m(Np_("{name}() takes {want} argument, got {got}", "{name}() takes {want} arguments, got {got}"),
                             name=func.id, want=_m(N_("{a} or {b}"), a=counts[0], b=counts[1]) if len(counts) == 2 else
                             ", ".join(map(str, counts)), n=max(counts), got=len(node.args)), node=node)
            return tuple(node.args)
        for cls, reason in REFUSED_NODES.items():
            if isinstance(node, cls):
                self.fail(_m(reason), self.expected(), node)
        self.fail(_m(N_("'{type}' is not allowed"), type=type(node).__name__), self.expected(), node)

    def estimate(self, node):
        """A floating-point (complex) estimate of a sub-expression made of numbers only — None when it has
        symbols — and the checks of exponent and magnitude that need it. Float arithmetic: it cannot hang."""
        value, limits = self.value, self.limits
        big = limits.magnitude
        if isinstance(node, ast.Constant):
            return complex(node.value)
        if isinstance(node, ast.Name):
            const = CONSTANTS.get(node.id)
            return complex(const) if const is not None else None
        if isinstance(node, ast.UnaryOp):
            v = value[id(node.operand)]
            return None if v is None else (-v if isinstance(node.op, ast.USub) else v)
        if isinstance(node, ast.BinOp):
            a, b = value[id(node.left)], value[id(node.right)]
            op = type(node.op)
            if op is ast.Pow and b is not None and abs(b) > limits.exponent:
                shown = f"{b.real:.6g}" if b.imag == 0 else f"{b:.6g}"
                self.fail(_m(N_("the exponent {exponent} is too large (at most {limit:g} in size)"), exponent=shown,
                             limit=limits.exponent), node=node)
            if a is None or b is None:
                return None
            if op is ast.Pow and a == 0 and b.real < 0:
                self.fail(_m(N_("division by zero (0 to a negative power)")), node=node)
            if op is ast.Div and b == 0:
                self.fail(_m(N_("division by zero")), node=node)
            compute = {ast.Pow: lambda: a**b, ast.Div: lambda: a / b, ast.Mult: lambda: a * b,
                       ast.Add: lambda: a + b, ast.Sub: lambda: a - b}[op]
        elif isinstance(node, ast.Call):
            args = [value[id(a)] for a in node.args]
            name = self.aliases.get(node.func.id, node.func.id)
            if any(a is None for a in args) or name not in COMPLEX or self.table.get(name) is not FUNCTIONS.get(name):
                return None
            compute = lambda: COMPLEX[name](*args)  # noqa: E731
        else:
            return None
        try:
            r = complex(compute())
        except (OverflowError, ZeroDivisionError):
            self.fail(_m(N_("{too_large}, or a division by zero"), too_large=too_large(big)), node=node)
        except (ValueError, TypeError):  # atan2 or sign of a complex number, or a domain error
            r = complex(math.nan, math.nan)
        if math.isnan(r.real) or math.isnan(r.imag):
            self.fail(NOT_FINITE, _m(N_("real numbers")), node)
        if not (math.isfinite(r.real) and math.isfinite(r.imag)) or abs(r) > big:
            self.fail(too_large(big), node=node)
        if abs(r.imag) > 1e-9 * max(1.0, abs(r.real)):
            self.fail(_m(N_("a part of the expression is not a real number (≈ {value})"),
                         value=f"{r.real:.6g}{r.imag:+.6g}i"),
                      _m(N_("real numbers (kinematic quantities are real)")), node)
        return complex(r.real, 0.0) if r.imag else r

    def exact_bits(self, node):
        """A bound on the size, in bits, of the exact rational numbers sympy will build for this sub-expression
        (its coefficients): sums and products add sizes, an integer power multiplies them. Without it,
        ``1/1009**85 + 1/1013**85 + …`` builds a common denominator of 10⁵ digits, a quadratic cost."""
        bits = self.bits
        if isinstance(node, ast.Constant):
            n = int(abs(node.value)).bit_length() if isinstance(node.value, int) else 64
        elif isinstance(node, ast.Name):
            n = 0
        elif isinstance(node, ast.UnaryOp):
            n = bits[id(node.operand)]
        elif isinstance(node, ast.BinOp):
            a, b = bits[id(node.left)], bits[id(node.right)]
            exponent = self.value.get(id(node.right))
            if isinstance(node.op, ast.Pow) and exponent is not None:
                n = a * max(1, math.ceil(abs(exponent))) + b
            else:
                n = a + b
        elif isinstance(node, ast.Call):
            n = sum(bits[id(a)] for a in node.args)
        else:
            n = 0
        if n > self.limits.bits:
            self.fail(_m(Np_("the exact numbers are too large (more than {n} bit in all)",
                             "the exact numbers are too large (more than {n} bits in all)"), n=self.limits.bits),
                      node=node)
        return n

    # ------------------------------------------------------------------------------------------- build
    def build(self, node):
        """The sympy object of a tree that passed :meth:`walk` (depth bounded there, so recursion is safe)."""
        if isinstance(node, ast.Constant):
            v = node.value
            return sp.Integer(v) if isinstance(v, int) else sp.Float(v)
        if isinstance(node, ast.Name):
            return self.symbols[node.id] if node.id in self.symbols else CONSTANTS[node.id]
        if isinstance(node, ast.UnaryOp):
            operand = self.build(node.operand)
            return -operand if isinstance(node.op, ast.USub) else operand
        if isinstance(node, ast.BinOp):
            family = _family(node)
            if family is None:  # a power
                return sp.Pow(self.build(node.left), self.build(node.right))
            # the left spine of a chain a + b - c + … in one Add (one Mul for a * b / c …), built iteratively
            parts, left = [], node
            while isinstance(left, ast.BinOp) and _family(left) == family:
                right = self.build(left.right)
                if isinstance(left.op, ast.Sub):
                    right = -right
                elif isinstance(left.op, ast.Div):
                    right = sp.Pow(right, -1)
                parts.append(right)
                left = left.left
            parts.append(self.build(left))
            return (sp.Add if family == "add" else sp.Mul)(*reversed(parts))
        name = self.aliases.get(node.func.id, node.func.id)
        if self.value.get(id(node)) is not None and self.calls[id(node)] > 1:
            # a call of numbers inside a call of numbers (sqrt(sin(1))): sympy's automatic evaluation asks the
            # sign of such values by adaptive evalf, which can take minutes (sqrt(sqrt(…(2) - 1) - 1)); the
            # value is computed at a fixed precision instead
            return self.float_value(node)
        return self.table[name][0](*[self.build(a) for a in node.args])

    def float_value(self, node):
        """A numeric call as a sympy Float of 20 digits, computed by mpmath on the tree at fixed precision."""
        with mpmath.workdps(30):
            try:
                z = mpmath.mpc(self.mp(node, mpmath))
            except (ValueError, ZeroDivisionError, OverflowError, TypeError):
                z = mpmath.mpc(mpmath.nan)
            if not (mpmath.isfinite(z.real) and mpmath.isfinite(z.imag)) or abs(z.imag) > 1e-20 * max(1, abs(z.real)):
                self.fail(NOT_FINITE, _m(N_("real numbers")), node)
            return sp.Float(z.real, 20)

    def mp(self, root, mpmath):
        """mpmath value of a numeric sub-tree (it passed the walk: numbers, constants, + - * / ^, calls),
        computed iteratively: a sum of a thousand terms is a left spine a thousand nodes deep."""
        value = {}
        stack = [(root, False)]
        while stack:
            node, ready = stack.pop()
            if isinstance(node, ast.Constant):
                value[id(node)] = mpmath.mpf(node.value) if isinstance(node.value, float) else mpmath.mpf(int(node.value))
            elif isinstance(node, ast.Name):
                value[id(node)] = +mpmath.pi if CONSTANTS[node.id] is sp.pi else +mpmath.e
            elif not ready:
                stack.append((node, True))
                stack.extend((c, False) for c in self.children_of(node))
            elif isinstance(node, ast.UnaryOp):
                v = value[id(node.operand)]
                value[id(node)] = -v if isinstance(node.op, ast.USub) else v
            elif isinstance(node, ast.BinOp):
                a, b = value[id(node.left)], value[id(node.right)]
                value[id(node)] = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
                                   ast.Div: operator.truediv, ast.Pow: mpmath.power}[type(node.op)](a, b)
            else:
                name = self.aliases.get(node.func.id, node.func.id)
                value[id(node)] = MP_BY_NAME[name](mpmath)(*[value[id(a)] for a in node.args])
        return value[id(root)]

    @staticmethod
    def children_of(node):
        """The operands of a node that passed the walk."""
        if isinstance(node, ast.UnaryOp):
            return (node.operand,)
        if isinstance(node, ast.BinOp):
            return (node.left, node.right)
        if isinstance(node, ast.Call):
            return tuple(node.args)
        return ()


#: A numeric literal as the docs describe it: decimal digits, a decimal point, an exponent (no 0x, 0o, 0b, no _)
_DECIMAL = re.compile(r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")


def _family(node):
    op = type(getattr(node, "op", None))
    return "add" if op in (ast.Add, ast.Sub) else "mul" if op in (ast.Mult, ast.Div) else None


# ------------------------------------------------------------------------------------------------ numbers
class _Parameters(Mapping):
    """Any plain name as a sympy Symbol of that name: the symbolic parameters (ξ, l, ρ …) a derivation may
    keep in a mechanism's data. Function and constant names keep their meaning."""

    def __contains__(self, name):
        return isinstance(name, str) and name.isidentifier() and not name.startswith("_") and \
            name not in FUNCTIONS and name not in ALIASES and name not in CONSTANTS and name not in HINTS

    def __getitem__(self, name):
        if name not in self:
            raise KeyError(name)
        return sp.Symbol(name)

    def __iter__(self):
        return iter(())

    def __len__(self):
        return 0


def read_constant(value, *, where, symbolic=False, limits=None):
    """A finite real number, kept exact as a sympy number: ``3``, ``0.5`` or a string such as ``"3*pi/4"``
    (read by :func:`read_expression` with no symbols).

    Parameters
    ----------
    value : int, float, str or sympy number
        Not a bool.
    where : str
        Named in the messages.
    symbolic : bool
        Also accept symbolic parameters: a sympy expression with symbols, or text naming them (``"xi"``,
        ``"l/2"``), for symbolic derivations; numeric analyses then refuse the mechanism.

    Returns
    -------
    sympy.Expr
        A number (``sp.pi/4`` stays exact, so symbolic displays show π), or with ``symbolic`` an expression.

    Raises
    ------
    ExpressionError
    """
    if isinstance(value, bool) or value is None:
        refuse(where, _m(N_("expected a number, got {value}"), value=repr(value)), code="not a number")
    magnitude = (limits or DEFAULT_LIMITS).magnitude
    too_big = _m(N_("the number is too large (more than {limit:.0e})"), limit=magnitude)
    if isinstance(value, int):
        if abs(value) > magnitude:
            refuse(where, too_big, code="too large")
        return sp.Integer(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            refuse(where, _m(N_("expected a finite number, got {value}"), value=repr(value)), code="not finite")
        if abs(value) > magnitude:  # a float from a file or a caller, as a literal
            refuse(where, too_big, code="too large")
        return sp.Float(value)
    if isinstance(value, str):
        expr = read_expression(value, symbols=_Parameters() if symbolic else {}, where=where, limits=limits)
    elif isinstance(value, sp.Basic):
        check_expression(value, where=where, limits=limits)
        expr = value
    else:
        if isinstance(value, numbers.Real) and not isinstance(value, numbers.Integral):  # numpy floats …
            return read_constant(float(value), where=where, limits=limits)
        if isinstance(value, numbers.Integral):
            return read_constant(int(value), where=where, limits=limits)
        refuse(where, _m(N_("expected a number or the text of one (such as \"pi/4\"), got {type} {value}"),
                         type=type(value).__name__, value=short(value)), code="not a number")
    if symbolic and isinstance(expr, sp.Expr) and expr.free_symbols:
        if expr.has(sp.I, sp.zoo, sp.oo, -sp.oo, sp.nan):
            refuse(where, _m(N_("expected a real parameter, got {value}"), value=short(value)), code="not real",
                   text=value if isinstance(value, str) else None)
        return expr
    if not isinstance(expr, sp.Expr) or expr.free_symbols:
        names = ", ".join(sorted(map(str, getattr(expr, "free_symbols", ())))) or type(expr).__name__
        refuse(where, _m(N_("expected a number, got an expression of {names}: {value}"), names=names,
                         value=short(value)), code="not a number", text=value if isinstance(value, str) else None)
    _real_value(expr, value, where)
    return expr


def _real_value(expr, value, where):
    """The value of a numeric sympy expression as a float, computed by mpmath at a fixed 30 digits (sympy's
    adaptive ``evalf`` can take minutes on nested logarithms of negative numbers); refuses complex and
    non-finite values."""
    with mpmath.workdps(30):
        try:
            z = mp_value(expr, mpmath)
        except (ValueError, ZeroDivisionError, OverflowError, TypeError):
            z = mpmath.nan
        z = mpmath.mpc(z)
        finite = mpmath.isfinite(z.real) and mpmath.isfinite(z.imag)
        if not finite or abs(z.imag) > mpmath.mpf(10) ** -25 * max(1, abs(z.real)):
            got = mpmath.nstr(z, 6) if finite else _m(N_("not finite"))
            refuse(where, _m(N_("expected a finite real number, got {value} ({got})"), value=short(value), got=got),
                   code="not real", text=value if isinstance(value, str) else None)
        return float(z.real)


def read_number(value, *, where, limits=None):
    """A finite real number as a float: an int or float (not a bool), or the text of one (``"pi/4"``).

    Raises
    ------
    ExpressionError
        Not a number, not finite, not real, or an expression of names; the message names ``where``.

    Examples
    --------
    >>> read_number("pi/4", where="phi0")
    0.7853981633974483
    >>> read_number(True, where="length")
    Traceback (most recent call last):
    ...
    kinbook.errors.ExpressionError: length: expected a number, got True
    """
    if isinstance(value, float) and math.isfinite(value):
        return value
    expr = read_constant(value, where=where, limits=limits)
    return _real_value(expr, value, where)
