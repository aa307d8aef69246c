"""The book's notation: its symbols, its two-body joints, and a LaTeX printer that writes kinbook's results
the way the book does (the idea of sympy's ``vlatex``).

kinbook names coordinates ``x1, y1, phi1, dx1 …`` (body numbers); the book writes :math:`x_i, y_i, \\varphi_i,
\\dot x_i` and global point coordinates :math:`x_i^P`. This module translates both ways:

- :data:`S` holds the book's symbols for a joint between bodies *i* and *j* (``S.x_i``, ``S.xP_i`` for
  :math:`x_i^P`, ``S.w_i`` for :math:`\\dot\\varphi_i` …);
- :func:`pair` builds the two-body mechanism of one joint type with symbolic local points (ξ, η), as §13.5
  and §13.6 treat each joint;
- :func:`to_book` rewrites a kinbook expression of such a pair in the book's global point coordinates,
  :func:`from_book` goes back (both checked against each other in ``tests/book``);
- :func:`latex` prints any kinbook expression with the book's names (x_1, φ_1, ẋ_1, e_{0,1}, …);
  :func:`equations` writes a list of rows as :math:`\\Phi_k \\equiv … = 0`; :func:`matrix` a numeric matrix
  without round-off;
- :func:`book_form` writes a pair's Φ, Φ_q or γ as the book does — point coordinates, factored by the joint's
  vectors, γ collected by φ̇ — and :func:`lines` sets rows one per line, broken to fit a notebook column.
"""

from __future__ import annotations

import html
import re
from functools import lru_cache
from types import SimpleNamespace

import numpy as np
import sympy as sp
from sympy.printing.latex import LatexPrinter

from ..errors import InputError
from ..grading.read import tex_name
from ..planar import Mechanism, Revolute, RevoluteRevolute, RevoluteTranslational, Translational
from .display import fmt

__all__ = ["S", "pair", "PAIR_KINDS", "to_book", "from_book", "latex", "html_math", "html_text", "equations", "matrix", "names",
           "book_form", "factored", "lines", "Math", "local_points", "table", "tidy", "spatial_form",
           "SPATIAL_DEFINITIONS"]



def as_sympy(expr):
    """A sympy object of kinbook's own making, as it is (numbers become sympy numbers, lists a Matrix).

    Text is refused: these helpers read the library's expressions, never a reader's text
    (untrusted text goes through :mod:`kinbook.core.reader`)."""
    if isinstance(expr, (sp.Basic, sp.MatrixBase)):
        return expr

    if isinstance(expr, bool) or isinstance(expr, str):
        raise InputError(f"expected a sympy expression, got {type(expr).__name__} {str(expr)[:60]!r} (text is never "
                         "parsed here: kinbook.core.reader reads text)")
    if isinstance(expr, int):
        return sp.Integer(expr)
    if isinstance(expr, (float, np.floating)):
        return sp.Float(float(expr))
    if isinstance(expr, (list, tuple)):
        return sp.Matrix([as_sympy(e) for e in expr]) if not any(isinstance(e, (list, tuple)) for e in expr) \
            else sp.Matrix([[as_sympy(x) for x in row] for row in expr])
    raise InputError(f"expected a sympy expression, got {type(expr).__name__}")

def _sym(name, tex):
    """A real symbol whose LaTeX is ``tex`` (sympy prints a Symbol by its name)."""
    return sp.Symbol(tex if tex else name, real=True)


# ---------------------------------------------------------------------------------------- book symbols
S = SimpleNamespace()
"""The book's symbols for a joint between bodies i and j (planar, §13.5–13.8).

Coordinates ``x_i, y_i, phi_i, x_j, y_j, phi_j``; velocities ``xd_i, yd_i, w_i, xd_j, yd_j, w_j`` (ẋ, ẏ, φ̇);
global point coordinates ``xP_i, yP_i, xQ_i, yQ_i, xP_j, yP_j, xQ_j, yQ_j`` (x_i^P …; the book prints Q as
"o" in its tables); local coordinates ``xiP_i, etaP_i, …`` (ξ_i^P, η_i^P); the link length ``l``.
"""
for _b in "ij":
    setattr(S, f"x_{_b}", _sym(None, f"x_{_b}"))
    setattr(S, f"y_{_b}", _sym(None, f"y_{_b}"))
    setattr(S, f"phi_{_b}", _sym(None, rf"\varphi_{_b}"))
    setattr(S, f"xd_{_b}", _sym(None, rf"\dot{{x}}_{_b}"))
    setattr(S, f"yd_{_b}", _sym(None, rf"\dot{{y}}_{_b}"))
    setattr(S, f"w_{_b}", _sym(None, rf"\dot{{\varphi}}_{_b}"))
    for _p in "PQ":
        setattr(S, f"x{_p}_{_b}", _sym(None, f"x_{_b}^{_p}"))
        setattr(S, f"y{_p}_{_b}", _sym(None, f"y_{_b}^{_p}"))
        setattr(S, f"xi{_p}_{_b}", _sym(None, rf"\xi_{_b}^{_p}"))
        setattr(S, f"eta{_p}_{_b}", _sym(None, rf"\eta_{_b}^{_p}"))
S.l = sp.Symbol("l", positive=True)
S.c = sp.Symbol(r"c", real=True)  # the translational joint's constant φ_i⁰ − φ_j⁰
S.q = sp.Matrix([S.x_i, S.y_i, S.phi_i, S.x_j, S.y_j, S.phi_j])
S.qd = sp.Matrix([S.xd_i, S.yd_i, S.w_i, S.xd_j, S.yd_j, S.w_j])
S.columns = [rf"\partial/\partial {v}" for v in ("x_i", "y_i", r"\varphi_i", "x_j", "y_j", r"\varphi_j")]

PAIR_KINDS = {
    "r": (r"(r,2)", "revolute"),
    "t": (r"(t,2)", "translational"),
    "rr": (r"(r\text{-}r,1)", "revolute–revolute"),
    "rt": (r"(r\text{-}t,1)", "revolute–translational"),
}
"""The four planar joints of §13.5: kind → (the book's superscript, English name)."""


def pair(kind):
    """The two-body mechanism of one planar joint type with symbolic local points, as §13.5–13.8 treat it.

    Body ``i`` (coordinates x1, y1, phi1) carries P (and Q for the translational joint), body ``j`` (x2, y2,
    phi2) carries P (and Q for the revolute–translational joint); their local coordinates are the symbols
    ``S.xiP_i`` … The translational joint is the book's eq. 26 (s_i = r_i^P − r_i^Q, d = r_j^P − r_i^P: ``axis=("P", "Q")``)
    with the constant angle ``S.c``; the revolute–revolute link has length ``S.l``.

    Parameters
    ----------
    kind : {"r", "t", "rr", "rt"}

    Returns
    -------
    kinbook.planar.Mechanism
        Cached: do not add to it.
    """
    if not isinstance(kind, str) or kind not in PAIR_KINDS:
        raise InputError(f"`kind` must be one of {', '.join(PAIR_KINDS)}, got {str(kind)[:40]!r}")
    return _pair(kind)


@lru_cache(maxsize=None)
def _pair(kind):
    points = {"i": "PQ" if kind == "t" else "P", "j": "PQ" if kind == "rt" else "P"}
    m = Mechanism(f"{PAIR_KINDS[kind][1]} pair")
    for b in "ij":
        m.add_body(b, points={p: (getattr(S, f"xi{p}_{b}"), getattr(S, f"eta{p}_{b}")) for p in points[b]})
    m.add({"r": lambda: Revolute("i", "j", point="P"),
           "t": lambda: Translational("i", "j", axis=("P", "Q"), point_j="P", phi0=S.c),
           "rr": lambda: RevoluteRevolute("i", "j", "P", "P", length=S.l),
           "rt": lambda: RevoluteTranslational("i", "j", "P", axis=("P", "Q"))}[kind]())
    return m


def _maps(mech):
    """(read, back): kinbook symbols → book notation at φ = 0, and book notation → kinbook symbols."""
    if not all(hasattr(mech, a) for a in ("q", "qd", "bodies", "body_symbols")):
        raise InputError(f"expected a mechanism (or one of its constraints' two bodies), got {type(mech).__name__}")
    trig, read = {}, dict(zip(mech.q, S.q)) | dict(zip(mech.qd, S.qd))
    back = dict(zip(S.q, mech.q)) | dict(zip(S.qd, mech.qd))
    for body, b in zip(mech.bodies, "ij"):
        x, y, phi = mech.body_symbols(body.name)
        trig |= {sp.sin(phi): 0, sp.cos(phi): 1}
        for p, (xi, eta) in body.points.items():
            X, Y = getattr(S, f"x{p}_{b}"), getattr(S, f"y{p}_{b}")
            read[xi], read[eta] = X - getattr(S, f"x_{b}"), Y - getattr(S, f"y_{b}")
            back[X] = x + xi * sp.cos(phi) - eta * sp.sin(phi)
            back[Y] = y + xi * sp.sin(phi) + eta * sp.cos(phi)
    return (trig, read), back


def to_book(expr, mech):
    """A kinbook expression of :func:`pair` ``mech`` written in the book's global point coordinates.

    Every entry of Φ, Φ_q and γ depends on the points only through global vectors such as
    x_i^P − x_i = ξ cos φ − η sin φ, so the book's form can be read off at φ_i = φ_j = 0, where ξ = x_i^P − x_i
    and η = y_i^P − y_i; :func:`kinbook.book.verify.compare` confirms the result at random configurations.
    """
    (trig, read), _ = _maps(mech)
    return as_sympy(expr).subs(trig).subs(read, simultaneous=True)


def from_book(expr, mech):
    """An expression in the book's notation (:data:`S`) in the kinbook symbols of :func:`pair` ``mech``, at
    any angle (x_i^P → x_i + ξ cos φ_i − η sin φ_i, …)."""
    _, back = _maps(mech)
    return as_sympy(expr).subs(back, simultaneous=True)


# The book's vectors: (x, y) symbols of the joint points, the bodies' origins and their velocities, in the order
# the book writes a difference (x_i^P − x_i^Q, x_j^P − x_j, x_i^P − x_j^P, ẋ_i − ẋ_j: a joint point before an
# origin, P before Q, i before j). Where a joint's equation names a vector the other way, or prefers another of
# two equal-length forms, _BOOK_VECTORS lists it first (eq. 26's s_i and d = r_j^P − r_i^P, eq. 33's r_i^P − r_j^Q).
_POINTS = [(getattr(S, f"x{p}_{b}"), getattr(S, f"y{p}_{b}")) for p in "PQ" for b in "ij"] + \
    [(S.x_i, S.y_i), (S.x_j, S.y_j), (S.xd_i, S.yd_i), (S.xd_j, S.yd_j)]
_RANK = {s: k for k, pt in enumerate(_POINTS) for s in pt}
_P = {(p, b): (getattr(S, f"x{p}_{b}"), getattr(S, f"y{p}_{b}")) for p in "PQ" for b in "ij"}
_BOOK_VECTORS = {"t": [(_P["P", "i"], _P["Q", "i"]), (_P["P", "j"], _P["P", "i"])],
                 # r-r: the joint vector, then the lever arms O_iP_i, O_jP_j (∂/∂φ entries read as Table 13.5's)
                 "rr": [(_P["P", "i"], _P["P", "j"]), (_P["P", "i"], (S.x_i, S.y_i)), (_P["P", "j"], (S.x_j, S.y_j))],
                 "rt": [(_P["P", "i"], _P["Q", "j"]), (_P["P", "j"], _P["Q", "j"])]}


def _size(expr):
    return sp.count_ops(expr) + sum(1 for a in sp.preorder_traversal(expr) if a.is_Symbol)


def _orient(expr, vectors=()):
    """``expr`` with every difference of two coordinates written in the book's order; the sign moves to the
    term's coefficient, and the terms' common numeric factor is taken out (unevaluated, so sympy keeps it)."""
    order = {(U[k], V[k]) for U, V in vectors for k in (0, 1)}

    def flip(f):   # f = a − b → (sign, the difference the book writes)
        if not (f.is_Add and len(f.args) == 2):
            return 1, f
        a, b = sorted(f.args, key=lambda t: t.could_extract_minus_sign())
        b = -b
        if a not in _RANK or b not in _RANK or (a, b) in order:
            return 1, f
        if (b, a) in order or _RANK[b] < _RANK[a]:
            return -1, sp.Add(b, -a, evaluate=False)
        return 1, f

    terms = []
    for term in sp.Add.make_args(expr):
        coeff, factors = sp.Integer(1), []
        for f in sp.Mul.make_args(term):
            if f.is_Number:
                coeff *= f
                continue
            base, exp = f.as_base_exp()
            sign, base = flip(base)
            coeff *= sign ** exp
            factors.append(base if exp == 1 else sp.Pow(base, exp, evaluate=False))
        terms.append((coeff, factors))
    if len(terms) == 1:
        (c, f), = terms
        return sp.Mul(c, *f, evaluate=False) if f and c != 1 else (f[0] if len(f) == 1 and c == 1 else sp.Mul(c, *f))
    common = sp.gcd_list([c for c, _ in terms]) if all(c.is_Rational for c, _ in terms) else sp.Integer(1)
    if common != 1 and all(c.is_negative for c, _ in terms):   # −2(…), but −(a)(b) − (c)(d) as the book
        common = -common
    inner = sp.Add(*[sp.Mul(c / common, *f, evaluate=False) if c != common else sp.Mul(*f, evaluate=False)
                     for c, f in terms], evaluate=False)
    return inner if common == 1 else sp.Mul(common, inner, evaluate=False)


def factored(expr, vectors=()):
    """An expression in the book's symbols (:data:`S`) factored the way the book factors its tables: by the
    vectors it contains (s_i, d, r_i^P − r_i …), each cofactor a difference of coordinates.

    Every vector U − V of two points in ``expr`` is tried (``vectors`` first, so they win a tie): with
    x_U = u + x_V, y_U = v + y_V the expression splits into u·A + v·B + R, and the shortest
    (x_U − x_V)·A + (y_U − y_V)·B + R wins. The result equals ``expr`` (``tests/book`` checks it for every
    planar joint).
    """
    expr = sp.expand(as_sympy(expr))
    best = sp.factor(expr)
    points = [p for p in _POINTS if expr.has(*p)]
    u, v = sp.Dummy("u"), sp.Dummy("v")
    for U, V in list(vectors) + [(U, V) for U in points for V in points if U != V]:
        dx, dy = U[0] - V[0], U[1] - V[1]
        moved = sp.expand(expr.xreplace({U[0]: u + V[0], U[1]: v + V[1]}))
        tu, tv, rest = [], [], []
        for t in sp.Add.make_args(moved):
            (tu if t.has(u) else tv if t.has(v) else rest).append(t)
        if not tu and not tv:
            continue
        back = {u: dx, v: dy}
        A, B, R = (sp.expand(x).xreplace(back) for x in (sp.Add(*tu) / u, sp.Add(*tv) / v, sp.Add(*rest)))
        R = sp.factor(sp.expand(R))
        for t in (0, 1, -1):   # u·A + v·B = u·(A + t·v) + v·(B − t·u): the same value, maybe the book's cofactors
            form = sp.factor(sp.expand(A + t * dy)) * dx + sp.factor(sp.expand(B - t * dx)) * dy + R
            if (_size(form), _foreign(form, vectors)) < (_size(best), _foreign(best, vectors)):
                best = form
    return best


def _foreign(expr, vectors):
    """How many differences in ``expr`` are not components of the preferred ``vectors`` (a tie-break)."""
    own = {frozenset((U[k], V[k])) for U, V in vectors for k in (0, 1)}
    return sum(1 for a in sp.preorder_traversal(expr) if a.is_Add and len(a.args) == 2
               and frozenset(t if not t.could_extract_minus_sign() else -t for t in a.args) not in own)


def _kind(mech):
    return next((k for k in PAIR_KINDS if pair(k) is mech), None)


def book_form(expr, mech=None, kind=None):
    """A kinbook expression (or matrix) of a :func:`pair` ``mech`` as the book writes it: in global point
    coordinates (:func:`to_book`), collected by the angular velocities as Table 13.5 writes γ (φ̇_i², φ̇_i φ̇_j …;
    products with the same coefficient merged, φ̇_i(φ̇_i − 2φ̇_j)), each coefficient :func:`factored` and each
    difference in the book's order. Without ``mech``, ``expr`` is already in the book's symbols (``kind``, a key of
    :data:`PAIR_KINDS`, then says whose vectors to prefer). For printing (:func:`latex`, :func:`lines`): the
    result is partly unevaluated; ``sympy.expand(book_form(e, m) − to_book(e, m))`` is 0."""
    expr = as_sympy(expr)
    kind = kind or (_kind(mech) if mech is not None else None)
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(lambda e: book_form(e, mech, kind))
    vectors = _BOOK_VECTORS.get(kind, ())
    e = sp.expand(to_book(expr, mech) if mech is not None else expr)
    if not e.has(S.w_i, S.w_j):
        return _orient(factored(e, vectors), vectors)
    keys = [S.w_i**2, S.w_i * S.w_j, S.w_j**2, S.w_i, S.w_j, sp.Integer(1)]
    parts = sp.collect(e, keys[:-1], evaluate=False)
    groups = []   # [velocity factor, coefficient]: a product whose coefficient is a number times another's joins it
    for k in keys:
        c = parts.get(k)
        if c is None:
            continue
        for g in groups:
            ratio = sp.cancel(c / g[1])
            if ratio.is_Number and k != 1 and g[0] != 1:
                g[0] = g[0] + ratio * k
                break
        else:
            groups.append([k, c])
    terms = []
    for k, c in groups:
        content, k = sp.factor(k).as_content_primitive()
        c = _orient(factored(sp.expand(content * c), vectors), vectors)
        terms.append(c if k == 1 else sp.Mul(k, c, evaluate=False))
    return sp.Add(*terms, evaluate=False) if len(terms) > 1 else terms[0]


# ----------------------------------------------------------------------------------------- the printer
def names(expr, mech=None):
    """``symbol_names`` for :func:`sympy.latex`: kinbook's coordinate symbols in the book's notation.

    ``x1 → x_1``, ``phi2 → \\varphi_2``, ``dx1 → \\dot{x}_1``, ``e02 → e_{0,2}``; with a mechanism whose
    bodies are named by one letter (``i``, ``j``), that letter is the subscript (``x1 → x_i``). The rule is the
    checkers' (:func:`kinbook.grading.read.tex_name`): the answer as read and the book's pages write alike.
    """
    letters = {}
    if mech is not None:
        letters = {str(b.number): b.name for b in mech.bodies if len(b.name) == 1 and b.name.isalpha()}
    return {s: tex for s in as_sympy(expr).free_symbols if (tex := tex_name(s.name, letters)) is not None}


def tidy(expr, digits=10):
    """``expr`` with its floating-point numbers written as a person would: 2.0 → 2, 1.2000000000000002 → 1.2
    (``digits`` significant digits), so a derived expression prints as the book writes it.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> tidy(2.0 * x + 1.2000000000000002 * x**2 - 0.5)
    1.2*x**2 + 2*x - 0.5
    """
    expr = as_sympy(expr)
    floats = expr.atoms(sp.Float)
    if not floats:
        return expr
    repl = {}
    for f in floats:
        v = float(f)
        repl[f] = sp.Integer(round(v)) if v == round(v) else sp.Float(f"{v:.{digits}g}", digits)
    return expr.xreplace(repl)


class _BookPrinter(LatexPrinter):
    """sympy's LaTeX printer with the book's habits: in a sum the positive terms first (x_j^P − x_i, not
    −x_i + x_j^P); in a product the number, then the plain symbols, then the bracketed sums; and unevaluated
    products (:func:`book_form`) kept as built."""

    def parts(self, expr):
        """(numeric coefficient, [factors]) of a product, through nested unevaluated products."""
        coeff, factors = sp.Integer(1), []
        for f in sp.Mul.make_args(expr):
            if f.is_Number:
                coeff *= f
            elif f.is_Mul:
                c, fs = self.parts(f)
                coeff, factors = coeff * c, factors + fs
            else:
                factors.append(f)
        return coeff, factors

    def product(self, coeff, factors):
        plain = [f for f in factors if not (f.is_Add or (f.is_Pow and f.base.is_Add))]
        rest = [f for f in factors if f not in plain]
        plain = sp.Mul(*plain)
        texts = [LatexPrinter._print_Mul(self, plain) if plain.is_Mul else self._print(plain)] if plain != 1 else []
        for f in rest:
            base, exp = f.as_base_exp()
            texts.append(rf"\left({self._print(base)}\right)" + (f"^{{{self._print(exp)}}}" if exp != 1 else ""))
        head = "" if coeff == 1 else "-" if coeff == -1 else self._print(coeff) + " "
        return head + " ".join(texts) if texts else self._print(coeff)

    def terms(self, expr):
        """The terms of a sum in the book's order, each as (sign, LaTeX without its sign)."""
        out = []
        args = list(sp.Add.make_args(expr)) if expr.is_Add else [expr]
        for term in args:
            coeff, factors = self.parts(term)
            out.append(("-" if coeff < 0 else "+", self.product(abs(coeff), factors)))
        return sorted(out, key=lambda t: t[0] == "-")

    def _print_Add(self, expr, order=None):
        out = ""
        for k, (sign, tex) in enumerate(self.terms(expr)):
            out += (("-" if sign == "-" else "") if k == 0 else f" {sign} ") + tex
        return out

    def _print_Mul(self, expr):
        coeff, factors = self.parts(expr)
        return self.product(coeff, factors)


def _printer(expr, mech=None):
    return _BookPrinter({"symbol_names": names(expr, mech)})


def latex(expr, mech=None, book=False, **kwargs):
    """LaTeX of a kinbook expression in the book's notation (see :func:`names`), numbers tidied (:func:`tidy`);
    with ``book=True`` also in the book's order of terms and factors (for :func:`book_form` results)."""
    if book:
        return _printer(expr, mech).doprint(expr)
    expr = tidy(expr)
    return sp.latex(expr, symbol_names=names(expr, mech), **kwargs)


def _width(tex):
    """A rough count of the glyphs ``tex`` shows (sub- and superscripts count half)."""
    tex = re.sub(r"\\(left|right|displaystyle)", "", tex)
    small = sum(len(re.sub(r"\\[a-zA-Z]+", "x", m)) for m in re.findall(r"[_^]\{([^{}]*)\}", tex))
    tex = re.sub(r"[_^]\{[^{}]*\}", "", tex)
    tex = re.sub(r"\\dot\{([^{}]*)\}", r"\1", tex)
    tex = re.sub(r"\\[a-zA-Z]+", "x", tex)
    return len(re.sub(r"[{}\s]", "", tex)) + small / 2


def lines(rows, labels, mech=None, width=58, relation="="):
    """Rows (in the book's symbols, e.g. from :func:`book_form`) as the book sets a system: one row per line,
    aligned at ``relation``; a row wider than ``width`` glyphs continues on the next line after a whole term, so
    it fits a notebook column (about 58 glyphs at 900 px). Returns one LaTeX ``aligned`` block."""
    out = []
    for label, row in zip(labels, rows):
        row = as_sympy(row)
        printer = _printer(row, mech)
        line, current = [], ""
        for k, (sign, tex) in enumerate(printer.terms(row) if row.is_Add else [("+", printer.doprint(row))]):
            piece = (("-" if sign == "-" else "") if k == 0 else f" {sign} ") + tex
            if current and _width(current + piece) > width:
                line.append(current)
                current = r"\quad " + piece.lstrip()
            else:
                current += piece
        line.append(current)
        out.append(rf"{label} &{relation} " + r" \\ &\phantom{=}".join(line))
    return r"\begin{aligned}" + r" \\ ".join(out) + r"\end{aligned}"


def html_math(tex, display=False):
    r"""TeX placed in an HTML output: ``\(…\)`` (or ``\[…\]`` when ``display``), HTML-escaped. These are the
    delimiters both JupyterLab and the static book's MathJax typeset in HTML; ``$…$`` is left as raw text by
    the book (Sphinx enables no dollar delimiters)."""
    left, right = (r"\[", r"\]") if display else (r"\(", r"\)")
    return f"{left}{html.escape(str(tex))}{right}"


def html_text(text):
    r"""Prose with inline math between dollars, as a notebook's Markdown writes it ("row 2 of
    $\boldsymbol\Phi_{\mathbf q}\dot{\mathbf q}$"), as HTML: the prose escaped, each formula set with
    :func:`html_math` so that JupyterLab (trusted or not), the static book and ``nbconvert --to html`` typeset it.

    Raises
    ------
    InputError
        A dollar without its partner (the formula would show as raw TeX).
    """
    parts = str(text).split("$")
    if len(parts) % 2 == 0:
        raise InputError(f"html_text: an unpaired $ in {str(text)[:80]!r}")
    return "".join(html_math(p) if k % 2 else html.escape(p) for k, p in enumerate(parts))


def equations(rows, mech=None, first=1, label=r"\Phi"):
    """``rows`` (a sympy column) as the book writes a system: Φ_1 ≡ … = 0, one line each (a LaTeX string)."""
    if not isinstance(rows, (list, tuple, sp.MatrixBase)):
        raise InputError(f"equations: `rows` must be a sympy column or a list of expressions, got {type(rows).__name__}")
    lines = [rf"{label}_{{{k}}} &\equiv {latex(e, mech)} = 0" for k, e in enumerate(list(rows), start=first)]
    return r"\begin{aligned}" + r"\\ ".join(lines) + r"\end{aligned}"


def matrix(values, digits=4, row_labels=None, column_labels=None):
    """A numeric matrix or vector as a LaTeX array, rounded to ``digits`` decimals without round-off
    (exact zeros as 0, no −0)."""
    try:
        a = np.atleast_2d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        a = None
    if a is None or a.ndim != 2:
        raise InputError(f"matrix: `values` must be a vector or a matrix of real numbers, got {str(values)[:60]!r}")

    def cell(v):
        text = fmt(v, digits)
        return text.rstrip("0").rstrip(".") if "." in text else text

    rows = [[cell(v) for v in r] for r in a]
    if row_labels is not None:
        rows = [[lab] + r for lab, r in zip(row_labels, rows)]
    head = ""
    if column_labels is not None:
        head = (" & " if row_labels is not None else "") + " & ".join(column_labels) + r" \\ \hline "
    spec = ("c|" if row_labels is not None else "") + "r" * a.shape[1]
    return rf"\begin{{array}}{{{spec}}}" + head + r" \\ ".join(" & ".join(r) for r in rows) + r"\end{array}"


def Math(tex):
    """IPython's ``Math`` display object (imported lazily so the library does not need IPython)."""
    if not isinstance(tex, str):
        raise InputError(f"Math: expected LaTeX text, got {type(tex).__name__}")
    from IPython.display import Math as _Math  # optional dependency: IPython (the grading extra)

    return _Math(tex)


def local_points(mech):
    """Every point of every body with its local coordinates (ξ, η) — the book lists them for each joint of
    its examples — as a LaTeX array (body number, body, point, ξ_i^P, η_i^P)."""
    if not hasattr(mech, "bodies"):
        raise InputError(f"local_points: expected a mechanism, got {type(mech).__name__}")
    rows = []
    for b in mech.bodies:
        for name, value in b.points.items():
            xi, eta = (sp.nsimplify(v, rational=False) if not isinstance(v, sp.Basic) else v for v in value)
            tex = f"{name[0]}_{{{name[1:]}}}" if len(name) == 2 and name[0] == "O" else name
            rows.append(rf"{b.number} & \text{{{b.name}}} & {tex} & {sp.latex(xi)} & {sp.latex(eta)}")
    return (r"\begin{array}{clcrr} i & \text{body} & P & \xi_i^P & \eta_i^P \\ \hline " + r" \\ ".join(rows)
            + r"\end{array}")


def table(M, row_labels, columns=None, mech=None, width=58):
    """A symbolic matrix as the book's tables print it (rows = equations, columns = ∂/∂q), entries in the book's
    order of terms (:func:`book_form` results print factored), in blocks of as many columns as fit ``width``
    glyphs (see :func:`lines`); returns one LaTeX array per block."""
    M = sp.Matrix(M)
    columns = columns or S.columns
    tex = [[latex(M[r, c], mech, book=True) for c in range(M.cols)] for r in range(M.rows)]
    colw = [max(_width(columns[c]), *(_width(tex[r][c]) for r in range(M.rows))) + 2 for c in range(M.cols)]
    blocks, start = [], 0
    while start < M.cols:
        stop = start + 1
        while stop < M.cols and max(_width(x) for x in row_labels) + sum(colw[start:stop + 1]) <= width:
            stop += 1
        blocks.append(range(start, stop))
        start = stop
    out = []
    for cols in blocks:
        body = r" \\[4pt] ".join(lab + " & " + " & ".join(tex[r][c] for c in cols) for r, lab in enumerate(row_labels))
        out.append(rf"\begin{{array}}{{c|{'c' * len(cols)}}} & " + " & ".join(columns[c] for c in cols)
                   + r" \\ \hline " + body + r"\end{array}")
    return out


# ------------------------------------------------------------------------------------- spatial joints, the book's way
_SPATIAL_FORMS = {
    # type name: (Φ as §14.4 writes it, [(the book's symbol, attribute)] of the local data it needs)
    "Normal1": (r"\mathbf s_i^T\mathbf s_j", [(r"\mathbf s'_i", "a_i"), (r"\mathbf s'_j", "a_j")]),
    "Normal2": (r"\mathbf s_i^T\mathbf d", [(r"\mathbf s'_i", "a_i"), (r"\mathbf s'^P_i", "P_i"),
                                            (r"\mathbf s'^P_j", "P_j")]),
    "Parallel1": (r"\begin{bmatrix}\mathbf h_1^T\mathbf s_j\\ \mathbf h_2^T\mathbf s_j\end{bmatrix}",
                  [(r"\mathbf h'_1", "h1"), (r"\mathbf h'_2", "h2"), (r"\mathbf s'_j", "a_j")]),
    "Parallel2": (r"\begin{bmatrix}\mathbf h_1^T\mathbf d\\ \mathbf h_2^T\mathbf d\end{bmatrix}",
                  [(r"\mathbf h'_1", "h1"), (r"\mathbf h'_2", "h2"), (r"\mathbf s'^P_i", "P_i"),
                   (r"\mathbf s'^P_j", "P_j")]),
    "Spherical": (r"\mathbf r_i + \mathbf A_i\mathbf s'^P_i - \mathbf A_j\mathbf s'^P_j - \mathbf r_j",
                  [(r"\mathbf s'^P_i", "P_i"), (r"\mathbf s'^P_j", "P_j")]),
    "SphericalSpherical": (r"\mathbf d^T\mathbf d - l^2", [(r"\mathbf s'^P_i", "P_i"), (r"\mathbf s'^P_j", "P_j"),
                                                          ("l", "l")]),
}

SPATIAL_DEFINITIONS = (r"\mathbf s_k = \mathbf A_k\mathbf s'_k,\ \ \mathbf h_k = \mathbf A_i\mathbf h'_k \perp \mathbf s_i,\ \ "
                       r"\mathbf A_k = \mathbf A(\mathbf p_k)\ \text{(§14.3)}",
                       r"\mathbf d = \mathbf r_j + \mathbf A_j\mathbf s'^P_j - \mathbf r_i - \mathbf A_i\mathbf s'^P_i")
"""What the symbols of :func:`spatial_form` stand for (§14.4)."""


def _number(x):
    x = float(x)
    return f"{0.0 if abs(x) < 5e-13 else x:.10g}"


def _local(value):
    value = np.atleast_1d(np.asarray(value, dtype=float))
    if value.size == 1:
        return _number(value[0])
    return r"[" + r",\ ".join(_number(x) for x in value) + r"]^T"


def _leaves(c):
    return [c] if not c.parts else [leaf for v in c.part_views() for leaf in _leaves(v)]


_TRANSLATIONAL_N1 = (r"\mathbf h_i^T\mathbf h_j", [(r"\mathbf h'_i", "a_i"), (r"\mathbf h'_j", "a_j")])


def spatial_form(constraint, definitions=False):
    """A spatial joint's Φ as §14.4 writes it — in vectors (s_iᵀs_j, s_iᵀd, r_i + A_i s'^P_i − A_j s'^P_j − r_j,
    the translational joint's h_iᵀh_j, and kinbook's two rows h_1ᵀs_j, h_2ᵀs_j for the book's s̃_i s_j = 0) —
    part by part, each with its local vectors as numbers; LaTeX (an ``aligned`` block, with a last row saying what
    the symbols stand for when ``definitions``), or None for a type the book does not write so (drivers, the
    normalization)."""
    rows = []
    for leaf in _leaves(constraint):
        form = _SPATIAL_FORMS.get(type(leaf).__name__)
        if form is None:
            return None
        if type(leaf).__name__ == "Normal1" and type(getattr(leaf, "owner", None)).__name__ == "Translational":
            form = _TRANSLATIONAL_N1
        tex, data = form
        values = [f"{sym} = {_local(getattr(leaf, attr))}" for sym, attr in data]
        rows.append(rf"\Phi^{{({leaf.label})}} &= {tex},")
        # the local data under the formula, two to a line: the block stays narrow enough for a book page
        rows += [r"&\qquad " + r",\quad ".join(values[k:k + 2]) for k in range(0, len(values), 2)]
    body = r"\\ ".join(rows)
    if definitions:
        body += r"\\[3pt] &\text{with } " + SPATIAL_DEFINITIONS[0] + r",\\ &\phantom{\text{with }}" + SPATIAL_DEFINITIONS[1]
    return r"\begin{aligned}" + body + r"\end{aligned}"
