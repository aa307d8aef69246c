"""Cross-check tables: a printed formula against kinbook's derivation, a derivative against finite differences,
γ against the second time derivative of Φ along a path — each rendered as a small table in a notebook.

Every check evaluates both sides at seeded random states and reports the largest difference in words
(":func:`kinbook.notebook.agrees`"), so the stored output is the same on every CPU.

>>> from kinbook.book import notation, printed, verify
>>> c = verify.compare(printed.TABLES["13.1"][1], notation.pair("r").symbolic().Phi_q, notation.pair("r"))
>>> bool(c.all_agree)
True
"""

from __future__ import annotations

import html

import numpy as np
import sympy as sp

from ..notebook import agrees, tolerance_text
from .notation import S, as_sympy, from_book, html_math, latex

__all__ = ["Comparison", "compare", "random_states", "jacobian_fd", "gamma_path", "Check", "checks", "solution_table", "zero_on_sphere", "rate", "relative_dof", "motion_table"]


def _free(mech, *exprs):
    syms = set(mech.q) | set(mech.qd)
    for e in exprs:
        syms |= as_sympy(e).free_symbols
    return sorted(syms, key=str)


def random_states(mech, exprs, count=20, seed=0, equal=()):
    """``count`` seeded random values for every free symbol of ``exprs`` and the mechanism's q, q̇.

    ``equal`` lists pairs of symbols given the same value (e.g. φ̇_j = φ̇_i for the translational joint's γ).
    Returns (symbols, values) with values of shape (count, len(symbols)).
    """
    syms = _free(mech, *exprs)
    values = np.random.default_rng(seed).uniform(-2, 2, size=(count, len(syms)))
    for a, b in equal:
        values[:, syms.index(b)] = values[:, syms.index(a)]
    return syms, values


def _evaluate(expr, syms, values):
    f = sp.lambdify(syms, sp.Matrix(expr), "numpy")
    return np.array([np.array(f(*v), dtype=float) for v in values])


class Comparison:
    """A printed matrix against kinbook's, entry by entry, at random states.

    Attributes
    ----------
    errors : ndarray
        Largest |printed − kinbook| of each entry over the states (after the row signs below).
    signs : ndarray of ±1
        Per row, the factor that makes the printed row fit kinbook's: a row times −1 is the same constraint.
    tol : float
    """

    def __init__(self, printed, derived, errors, signs, tol, title, columns, rows):
        self.printed, self.derived = printed, derived
        self.errors, self.signs, self.tol = errors, signs, tol
        self.title, self.columns, self.rows = title, columns, rows

    @property
    def agree(self):
        return self.errors < self.tol

    @property
    def all_agree(self):
        return bool(np.all(self.agree))

    def disagreements(self):
        """[(row, column), …] of the entries that differ (0-based)."""
        return [tuple(int(i) for i in ij) for ij in np.argwhere(~self.agree)]

    def summary(self):
        n, bad = self.errors.size, int((~self.agree).sum())
        text = f"{n - bad} of {n} entries agree with kinbook (within {tolerance_text(self.tol)})"
        flipped = [r + 1 for r, s in enumerate(self.signs) if s < 0]
        if flipped:
            text += f"; printed row{'s' if len(flipped) > 1 else ''} {', '.join(map(str, flipped))} = −1 × kinbook's"
        return text

    def __repr__(self):
        marks = "\n".join(" ".join("✓" if ok else "✗" for ok in row) for row in self.agree)
        return f"{self.title}: {self.summary()}\n{marks}"

    def _repr_html_(self):
        head = "".join(f"<th>{html_math(c)}</th>" for c in self.columns)
        body = []
        for r, row in enumerate(self.agree):
            cells = "".join(f"<td style='text-align:center;color:{'#155724' if ok else '#b00020'}'>{'✓' if ok else '✗'}"
                            f"</td>" for ok in row)
            body.append(f"<tr><td>{html_math(self.rows[r])}</td>{cells}</tr>")
        return (f"<p><b>{html.escape(self.title)}</b> — {html.escape(self.summary())}</p>"
                f"<table><tr><th></th>{head}</tr>{''.join(body)}</table>")

    def latex_disagreements(self):
        """LaTeX lines "row, column: printed … kinbook …" for every entry that differs."""
        out = []
        for r, c in self.disagreements():
            out.append(rf"{self.rows[r]},\ {self.columns[c]}:\quad \text{{printed }} {sp.latex(self.printed[r, c])}"
                       rf"\qquad \text{{kinbook }} {sp.latex(self.derived[r, c])}")
        return out


def compare(printed, derived, mech, *, count=20, seed=1, tol=1e-9, equal=(), title="", columns=None,
            rows=None, book_form=None):
    """Compare a printed matrix (in the book's symbols :data:`S`) with kinbook's (in the mechanism's symbols).

    Parameters
    ----------
    printed : sympy.Matrix
        As printed, in the book's notation.
    derived : sympy.Matrix
        kinbook's derivation for the :func:`~kinbook.book.notation.pair` ``mech``.
    mech : Mechanism
    count, seed : int
        How many random states, and the seed.
    tol : float
    equal : sequence of (Symbol, Symbol)
        Book symbols given the same value (``[(S.w_i, S.w_j)]``).
    title, columns, rows : str, list of str
        How the table is labelled (LaTeX for columns and rows).
    book_form : sympy.Matrix, optional
        kinbook's derivation written in the book's notation, shown next to a printed entry that differs.

    Returns
    -------
    Comparison
    """
    printed, derived = sp.Matrix(printed), sp.Matrix(derived)
    as_kinbook = from_book(printed, mech)
    eq = [(from_book(a, mech), from_book(b, mech)) for a, b in equal]
    syms, values = random_states(mech, [as_kinbook, derived], count, seed, eq)
    p, d = _evaluate(as_kinbook, syms, values), _evaluate(derived, syms, values)
    signs = np.ones(printed.rows)
    for r in range(printed.rows):
        plus = (np.abs(p[:, r] - d[:, r]).max(axis=0) < tol).sum()
        minus = (np.abs(p[:, r] + d[:, r]).max(axis=0) < tol).sum()
        signs[r] = -1.0 if minus > plus else 1.0
    errors = np.abs(p * signs[None, :, None] - d).max(axis=0)
    columns = columns or (S.columns if printed.cols == 6 else [f"{k + 1}" for k in range(printed.cols)])
    rows = rows or [rf"\text{{row {r + 1}}}" for r in range(printed.rows)]
    shown = book_form if book_form is not None else derived
    return Comparison(printed, shown, errors, signs, tol, title, columns, rows)


def jacobian_fd(mech, q, t=0.0, h=1e-6):
    """Largest |Φ_q − central finite differences of Φ| at ``q`` (a number; about h² times the third
    derivatives)."""
    q = np.asarray(q, dtype=float)
    cols = [(mech.Phi(q + h * e, t) - mech.Phi(q - h * e, t)) / (2 * h) for e in np.eye(mech.n)]
    return float(np.abs(mech.Phi_q(q, t) - np.column_stack(cols)).max())


def gamma_path(mech, q, qd, t=0.0, h=1e-4):
    """Largest |Φ̈ + γ| along the straight path q(s) = q + q̇ s (where q̈ = 0, so Φ̈ = Φ_q q̈ − γ = −γ), Φ̈ by
    central finite differences in s."""
    q, qd = np.asarray(q, dtype=float), np.asarray(qd, dtype=float)
    Phi_dd = (mech.Phi(q + h * qd, t) - 2 * mech.Phi(q, t) + mech.Phi(q - h * qd, t)) / h**2
    return float(np.abs(Phi_dd + mech.gamma(q, qd, t)).max())


class Check:
    """One line of a cross-check table: what was compared, the largest difference, the tolerance."""

    def __init__(self, what, error, tol):
        self.what, self.error, self.tol = what, float(error), tol

    @property
    def ok(self):
        return self.error < self.tol

    def verdict(self):
        return agrees(self.error, self.tol)

    def text(self):
        return f"{'✓' if self.ok else '✗'} {self.what}: {self.verdict()}"

    def __repr__(self):
        return self.text()


class Checks(list):
    """A list of :class:`Check` that displays as a table."""

    def __repr__(self):
        return "\n".join(c.text() for c in self)

    def _repr_html_(self):
        rows = "".join(f"<tr><td>{'✓' if c.ok else '✗'}</td><td style='text-align:left'>{html.escape(c.what)}</td>"
                       f"<td style='text-align:left'>{html.escape(c.verdict())}</td></tr>" for c in self)
        return f"<table>{rows}</table>"


def checks(*items):
    """A displayable table from (what, error, tol) triples."""
    return Checks(Check(*i) for i in items)


class SolutionTable:
    """kinbook's solution next to a printed one, coordinate by coordinate (angles in degrees in [0°, 360°), for
    reading only), with the residual Φ(q_printed) that says whether the printed solution assembles."""

    def __init__(self, mech, q, q_printed, t=0.0, digits=4):
        self.mech, self.t, self.digits = mech, t, digits
        self.q, self.q_printed = np.asarray(q, dtype=float), np.asarray(q_printed, dtype=float)
        self.residual = mech.Phi(self.q_printed, t)

    def _rows(self):
        from ..notebook import fmt

        for name, a, b in zip(self.mech.coordinate_names(), self.q, self.q_printed):
            if name.startswith("phi"):
                a, b = (np.round(np.degrees(v), 2) % 360 for v in (a, b))
                yield name + " (°)", fmt(a, 2), fmt(b, 2), abs(a - b) > 0.011
            else:
                yield name, fmt(a, self.digits), fmt(b, self.digits), abs(a - b) > 1.1 * 10**-self.digits

    def verdict(self):
        from ..notebook import small

        worst = int(np.argmax(np.abs(self.residual)))
        size = float(np.abs(self.residual[worst]))
        if size < 2e-4:  # the printed values carry four decimals
            return "the printed solution satisfies Φ = 0 to its four printed decimals"
        return (f"the printed solution does not assemble: max |Φ_k(q_printed)| = {small(size, 1e-4, 3)} "
                f"(row Φ_{worst + 1})")

    def __repr__(self):
        lines = [f"{'':>9} {'kinbook':>10} {'book':>10}"]
        lines += [f"{n:>9} {a:>10} {b:>10}{'  ←' if differ else ''}" for n, a, b, differ in self._rows()]
        return "\n".join(lines + [self.verdict()])

    def _repr_html_(self):
        marked = " style='background:#fdecea'"
        rows = "".join(f"<tr{marked if differ else ''}><td>{html.escape(n)}</td><td>{a}</td><td>{b}</td></tr>"
                       for n, a, b, differ in self._rows())
        return (f"<table><tr><th></th><th>kinbook</th><th>book</th></tr>{rows}</table>"
                f"<p>{html.escape(self.verdict())}</p>")


def solution_table(mech, q, q_printed, t=0.0):
    """A :class:`SolutionTable` of kinbook's ``q`` and the book's printed ``q_printed``."""
    return SolutionTable(mech, q, q_printed, t)


_BASES = {}


def zero_on_sphere(M, p, pd=None, pdd=None):
    """True when every entry of the polynomial matrix ``M`` vanishes for all unit Euler parameters ``p`` (and,
    if given, rates with pᵀṗ = 0 and pᵀp̈ = −ṗᵀṗ, as along any motion): the entries are reduced modulo a
    Gröbner basis of those constraints. Fast where ``sympy.simplify`` with e_0 = √(1 − e_1² − e_2² − e_3²) is slow.

    >>> import sympy as sp
    >>> from kinbook.spatial import A_from_p
    >>> p = sp.Matrix(sp.symbols("e0:4", real=True))
    >>> zero_on_sphere(A_from_p(p).T * A_from_p(p) - sp.eye(3), p)
    True
    """
    p = sp.Matrix(p)
    ideal = [(p.T * p)[0] - 1]
    gens = list(p)
    if pd is not None:
        pd = sp.Matrix(pd)
        ideal.append((p.T * pd)[0])
        gens += list(pd)
        if pdd is not None:
            pdd = sp.Matrix(pdd)
            ideal.append((p.T * pdd)[0] + (pd.T * pd)[0])
            gens += list(pdd)
    key = tuple(gens)
    if key not in _BASES:
        _BASES[key] = sp.groebner(ideal, *gens, order="grevlex")
    basis = _BASES[key]

    def parts(e):  # other symbols (a vector's components …) are coefficients: reduce each coefficient
        e = sp.expand(e)
        extra = sorted(e.free_symbols - set(gens), key=str)
        return sp.Poly(e, *extra).coeffs() if extra else [e]

    return all(basis.reduce(c)[1] == 0 for e in sp.Matrix(M) for c in parts(e))


def rate(M, p, pd):
    """d/dt of a matrix of polynomials in p along ṗ (the chain rule Σ_k ∂M/∂e_k ṗ_k), with p, ṗ symbols."""
    M = sp.Matrix(M)
    return sum((M.diff(p[k]) * pd[k] for k in range(len(p))), sp.zeros(*M.shape))


def relative_dof(mech, q, body_dof=6):
    """Relative degrees of freedom a joint leaves between two bodies at ``q``: n − rank(Φ_q) − ``body_dof``
    (the free motion of the first body)."""
    return int(mech.n - np.linalg.matrix_rank(mech.Phi_q(q)) - body_dof)


def motion_table(mech, q, constraint, motions, body="j"):
    """The constraint's rows after each rigid motion of ``body``: which motions the joint allows.

    ``motions`` maps a description to (axis, angle, centre, shift), as :meth:`Mechanism.moved` takes them.
    Returns a :class:`Checks`-like table: "allowed" where every row stays 0 (below 1e-9), "forbidden" otherwise.
    """
    rows = mech.constraint(constraint).rows
    out = Checks()
    for name, (axis, angle, centre, shift) in motions.items():
        moved = mech.moved(q, body, axis, angle, about=centre, shift=shift)
        out.append(_Motion(name, float(np.abs(mech.Phi(moved)[rows]).max())))
    return out


class _Motion(Check):
    def __init__(self, what, error):
        super().__init__(what, error, 1e-9)

    def verdict(self):
        from ..notebook import small

        return "allowed: Φ stays 0" if self.ok else f"forbidden: max |Φ| = {small(self.error)}"
