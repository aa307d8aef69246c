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
  without round-off.
"""

from __future__ import annotations

import html

import re
from functools import lru_cache
from types import SimpleNamespace

import numpy as np
import sympy as sp

__all__ = ["S", "pair", "PAIR_KINDS", "to_book", "from_book", "latex", "html_math", "equations", "matrix", "names",
           "book_gamma", "Math", "local_points", "table", "tidy"]



def as_sympy(expr):
    """A sympy object of kinbook's own making, as it is (numbers become sympy numbers, lists a Matrix).

    Text is refused: these helpers read the library's expressions, never a reader's text
    (untrusted text goes through :mod:`kinbook.expressions`)."""
    if isinstance(expr, (sp.Basic, sp.MatrixBase)):
        return expr
    if isinstance(expr, bool) or isinstance(expr, str):
        raise TypeError(f"expected a sympy expression, got {type(expr).__name__} {expr!r}")
    if isinstance(expr, int):
        return sp.Integer(expr)
    if isinstance(expr, (float, np.floating)):
        return sp.Float(float(expr))
    if isinstance(expr, (list, tuple)):
        return sp.Matrix([as_sympy(e) for e in expr]) if not any(isinstance(e, (list, tuple)) for e in expr) \
            else sp.Matrix([[as_sympy(x) for x in row] for row in expr])
    raise TypeError(f"expected a sympy expression, got {type(expr).__name__}")

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


@lru_cache(maxsize=None)
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
    from ..planar import Mechanism, Revolute, RevoluteRevolute, RevoluteTranslational, Translational

    if kind not in PAIR_KINDS:
        raise ValueError(f"`kind` must be one of {', '.join(PAIR_KINDS)}, got {kind!r}")
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


def book_gamma(expr, mech):
    """γ (or any velocity-quadratic expression) of a pair in the book's notation, collected by the products
    of angular velocities and factored term by term, as Table 13.5 writes it."""
    g = sp.expand(to_book(expr, mech))
    keys = [S.w_i**2, S.w_i * S.w_j, S.w_j**2, S.w_i, S.w_j]
    return sp.collect(g, keys, func=lambda c: sp.factor(c))


# ----------------------------------------------------------------------------------------- the printer
_COORD = re.compile(r"^(d?)(x|y|z|phi|e0|e1|e2|e3)(\d+)$")
_TEX = {"x": "x", "y": "y", "z": "z", "phi": r"\varphi"}


def names(expr, mech=None):
    """``symbol_names`` for :func:`sympy.latex`: kinbook's coordinate symbols in the book's notation.

    ``x1 → x_1``, ``phi2 → \\varphi_2``, ``dx1 → \\dot{x}_1``, ``e02 → e_{0,2}``; with a mechanism whose
    bodies are named by one letter (``i``, ``j``), that letter is the subscript (``x1 → x_i``).
    """
    letters = {}
    if mech is not None:
        letters = {str(b.number): b.name for b in mech.bodies if len(b.name) == 1 and b.name.isalpha()}
    out = {}
    for s in as_sympy(expr).free_symbols:
        m = _COORD.match(s.name)
        if not m:
            continue
        dot, base, number = m.groups()
        sub = letters.get(number, number)
        if base.startswith("e"):  # Euler parameters e_{0i}: the book's index first, then the body
            head, sub = "e", base[1] + ("," if len(sub) > 1 or sub.isdigit() else "") + sub
        else:
            head = _TEX[base]
        out[s] = (rf"\dot{{{head}}}" if dot else head) + f"_{{{sub}}}"
    return out


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


def latex(expr, mech=None, **kwargs):
    """LaTeX of a kinbook expression in the book's notation (see :func:`names`), numbers tidied (:func:`tidy`)."""
    expr = tidy(expr)
    return sp.latex(expr, symbol_names=names(expr, mech), **kwargs)


def html_math(tex, display=False):
    r"""TeX placed in an HTML output: ``\(…\)`` (or ``\[…\]`` when ``display``), HTML-escaped. These are the
    delimiters both JupyterLab and the static book's MathJax typeset in HTML; ``$…$`` is left as raw text by
    the book (Sphinx enables no dollar delimiters)."""
    left, right = (r"\[", r"\]") if display else (r"\(", r"\)")
    return f"{left}{html.escape(str(tex))}{right}"


def equations(rows, mech=None, first=1, label=r"\Phi"):
    """``rows`` (a sympy column) as the book writes a system: Φ_1 ≡ … = 0, one line each (a LaTeX string)."""
    lines = [rf"{label}_{{{k}}} &\equiv {latex(e, mech)} = 0" for k, e in enumerate(list(rows), start=first)]
    return r"\begin{aligned}" + r"\\ ".join(lines) + r"\end{aligned}"


def matrix(values, digits=4, row_labels=None, column_labels=None):
    """A numeric matrix or vector as a LaTeX array, rounded to ``digits`` decimals without round-off
    (exact zeros as 0, no −0)."""
    from ..notebook import fmt

    a = np.atleast_2d(np.asarray(values, dtype=float))

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
    from IPython.display import Math as _Math

    return _Math(tex)


def local_points(mech):
    """Every point of every body with its local coordinates (ξ, η) — the book lists them for each joint of
    its examples — as a LaTeX array (body number, body, point, ξ_i^P, η_i^P)."""
    rows = []
    for b in mech.bodies:
        for name, value in b.points.items():
            xi, eta = (sp.nsimplify(v, rational=False) if not isinstance(v, sp.Basic) else v for v in value)
            tex = f"{name[0]}_{{{name[1:]}}}" if len(name) == 2 and name[0] == "O" else name
            rows.append(rf"{b.number} & \text{{{b.name}}} & {tex} & {sp.latex(xi)} & {sp.latex(eta)}")
    return (r"\begin{array}{clcrr} i & \text{body} & P & \xi_i^P & \eta_i^P \\ \hline " + r" \\ ".join(rows)
            + r"\end{array}")


def table(M, row_labels, columns=None, mech=None, split=3):
    """A symbolic matrix as the book's tables print it (rows = equations, columns = ∂/∂q), in blocks of
    ``split`` columns to keep a page narrow; returns one LaTeX array per block."""
    M = sp.Matrix(M)
    columns = columns or S.columns
    out = []
    for start in range(0, M.cols, split):
        cols = range(start, min(start + split, M.cols))
        body = r" \\[4pt] ".join(lab + " & " + " & ".join(latex(M[r, c], mech) for c in cols)
                                 for r, lab in enumerate(row_labels))
        out.append(rf"\begin{{array}}{{c|{'c' * len(cols)}}} & " + " & ".join(columns[c] for c in cols)
                   + r" \\ \hline " + body + r"\end{array}")
    return out
