"""Cross-check tables: a printed formula against kinbook's derivation, a derivative against finite differences,
γ against the second time derivative of Φ along a path — each rendered as a small table in a notebook.

Every check evaluates both sides at seeded random states and reports the largest difference in words
(":func:`kinbook.book.display.agrees`"), so the stored output is the same on every CPU.

>>> from kinbook.book import notation, printed, verify
>>> c = verify.compare(printed.TABLES["13.1"][1], notation.pair("r").symbolic().Phi_q, notation.pair("r"))
>>> bool(c.all_agree)
True
"""

from __future__ import annotations

import html

import numpy as np
import sympy as sp

from ..core.assembly import stack_params
from ..errors import InputError
from ..spatial import Mechanism as Spatial
from . import table14
from .display import TOL, agrees, clean, fmt, small, tolerance_text
from .notation import S, as_sympy, from_book, html_math, latex, spatial_form

__all__ = ["Comparison", "compare", "random_states", "jacobian_fd", "gamma_path", "Check", "checks", "solution_table",
           "zero_on_sphere", "rate", "relative_dof", "motion_table", "columns", "Table", "jacobian_table",
           "gamma_table", "fd_jacobian", "sweep_checks", "joint_summary",
           "joint_table", "newton_table"]


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
        return folded(f"<p><b>{html.escape(self.title)}</b> — {html.escape(self.summary())}</p>",
                      f"<table><tr><th></th>{head}</tr>{''.join(body)}</table>",
                      f"entry by entry ({self.errors.size} entries)", show=not self.all_agree)

    def latex_disagreements(self):
        """For every entry that differs, two aligned LaTeX lines "row, column: printed …" and "kinbook …", in
        the book's order of terms (a :func:`~kinbook.book.notation.book_form` ``book_form`` prints factored)."""
        out = []
        for r, c in self.disagreements():
            out.append(rf"\begin{{aligned}}{self.rows[r]},\ {self.columns[c]}:\quad &\text{{printed }} "
                       rf"{latex(self.printed[r, c], book=True)} \\ &\text{{kinbook }} "
                       rf"{latex(self.derived[r, c], book=True)}\end{{aligned}}")
        return out


def compare(printed, derived, mech, *, count=20, seed=1, tol=1e-9, equal=(), title="", columns=None,
            rows=None, book_form=None, up_to_sign=True):
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
    up_to_sign : bool
        A printed row equal to kinbook's times −1 counts as the same row (a constraint Φ = 0 is −Φ = 0); False
        where the sign is the point (γ, ν).

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
    for r in range(printed.rows if up_to_sign else 0):
        plus = (np.abs(p[:, r] - d[:, r]).max(axis=0) < tol).sum()
        minus = (np.abs(p[:, r] + d[:, r]).max(axis=0) < tol).sum()
        signs[r] = -1.0 if minus > plus else 1.0
    errors = np.abs(p * signs[None, :, None] - d).max(axis=0)
    columns = columns or (S.columns if printed.cols == 6 else [f"{k + 1}" for k in range(printed.cols)])
    rows = rows or [rf"\text{{row {r + 1}}}" for r in range(printed.rows)]
    shown = book_form if book_form is not None else derived
    return Comparison(printed, shown, errors, signs, tol, title, columns, rows)


def fd_jacobian(f, x, h=1e-6):
    """The Jacobian of any function ``f`` of a vector at ``x`` by central differences (step ``h``): column k is
    (f(x + h e_k) − f(x − h e_k)) / 2h; ``f`` may return a vector or a matrix (flattened into the rows)."""
    x = np.asarray(x, dtype=float)
    cols = [(np.ravel(f(x + h * e)) - np.ravel(f(x - h * e))) / (2 * h) for e in np.eye(x.size)]
    return np.column_stack(cols)


def jacobian_fd(mech, q, t=0.0, h=1e-6):
    """Largest |Φ_q − central finite differences of Φ| at ``q`` (a number; about h² times the third
    derivatives)."""
    q = np.asarray(q, dtype=float)
    return float(np.abs(mech.Phi_q(q, t) - fd_jacobian(lambda x: mech.Phi(x, t), q, h)).max())


def gamma_path(mech, q, qd, t=0.0, h=1e-4):
    """Largest |Φ̈ + γ| along the straight path q(s) = q + q̇ s (where q̈ = 0, so Φ̈ = Φ_q q̈ − γ = −γ), Φ̈ by
    central finite differences in s."""
    q, qd = np.asarray(q, dtype=float), np.asarray(qd, dtype=float)
    Phi_dd = (mech.Phi(q + h * qd, t) - 2 * mech.Phi(q, t) + mech.Phi(q - h * qd, t)) / h**2
    return float(np.abs(Phi_dd + mech.gamma(q, qd, t)).max())


FOLD_AFTER = 3
"""A table of checks longer than this shows a sentence, the table folded below it (open when a check fails)."""


def folded(sentence, table, what, show=False):
    """A sentence, then ``table`` folded in an HTML ``<details>`` ("show …"), open when ``show`` (a disagreement is
    what the reader came for): a long column of ✓ reads as a lesson's result, not as a test report."""
    return (f"{sentence}<details{' open' if show else ''}><summary style='cursor:pointer;color:#555'>{what}</summary>"
            f"{table}</details>")


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
        table = f"<table>{rows}</table>"
        if len(self) <= FOLD_AFTER:
            return table
        bad = [c for c in self if not c.ok]
        if not bad:
            sentence = f"All {len(self)} checks agree."
        else:
            sentence = (f"{len(self) - len(bad)} of {len(self)} checks agree; not: "
                        + "; ".join(html.escape(c.what) for c in bad) + ".")
        return folded(f"<p>{sentence}</p>", table, f"the {len(self)} checks", show=bool(bad))


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
        for name, a, b in zip(self.mech.coordinate_names(), self.q, self.q_printed):
            if name.startswith("phi"):
                a, b = (np.round(np.degrees(v), 2) % 360 for v in (a, b))
                yield name + " (°)", fmt(a, 2), fmt(b, 2), abs(a - b) > 0.011
            else:
                yield name, fmt(a, self.digits), fmt(b, self.digits), abs(a - b) > 1.1 * 10**-self.digits

    def verdict(self):
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
    Returns a :class:`Checks` table: "allowed" where every row stays 0 (below 1e-9), "forbidden" otherwise, with
    the rows' values after the motion (which row catches it).
    """
    rows = mech.constraint(constraint).rows
    out = Checks()
    for name, (axis, angle, centre, shift) in motions.items():
        moved = mech.moved(q, body, axis, angle, about=centre, shift=shift)
        out.append(_Motion(name, mech.Phi(moved)[rows]))
    return out


class _Motion(Check):
    def __init__(self, what, values):
        self.values = clean(np.round(np.asarray(values, dtype=float), 4))
        super().__init__(what, float(np.abs(values).max()), 1e-9)

    def verdict(self):
        rows = " ".join(f"{v:g}" for v in self.values)
        return f"allowed: Φ = [{rows}]" if self.ok else f"forbidden: Φ = [{rows}]"


class JointSummary:
    """A joint's Φ as the book writes it — §14.4's vector form, part by part, its local vectors as numbers
    (:func:`~kinbook.book.notation.spatial_form`; for a type without one, kinbook's Φ in its bodies' symbols) —,
    its value at a configuration, its number of equations and the relative degrees of freedom it leaves
    (:func:`joint_summary`). The polynomial in the Euler parameters is ``mech.derivation(name).Phi``."""

    def __init__(self, mech, q, constraint):
        c = mech.constraint(constraint) if isinstance(constraint, str) else constraint
        self.constraint, self.q = c, np.asarray(q, dtype=float)
        self.value = mech.Phi(self.q)[c.rows]
        self.dof = relative_dof(mech, self.q)
        form = spatial_form(c, definitions=True)
        if form is not None:
            self.tex = form
            return
        labels = _leaf_labels(c)
        head = rf"\Phi^{{({labels[0]})}}" if len(labels) == 1 else (
            r"\begin{bmatrix}" + r"\\ ".join(rf"\Phi^{{({lab})}}" for lab in labels) + r"\end{bmatrix}")
        Phi = mech.constraint_phi(c)
        self.tex = head + " = " + latex(Phi[0] if c.n_eq == 1 else Phi, mech)

    def text(self):
        c, rows = self.constraint, " ".join(f"{v:g}" for v in clean(np.round(self.value, 4)))
        return (f"at this configuration Φ = [{rows}];  {c.label}: {c.n_eq} equation{'s' if c.n_eq > 1 else ''}, "
                f"{self.dof} relative DOF left")

    def __repr__(self):
        return f"{self.tex}\n{self.text()}"

    def _repr_html_(self):
        return f"<div>{html_math(self.tex, display=True)}</div><p>{html.escape(self.text())}</p>"


def _leaf_labels(c):
    """The book's labels of a constraint's primitive parts, composites of composites flattened: a translational
    joint is (p1,2), (p2,2), (n1,1)."""
    if not c.parts:
        return [c.label]
    return [label for v in c.part_views() for label in _leaf_labels(v)]


def joint_summary(mech, q, constraint):
    """Φ of one joint in the book's notation, its value at ``q`` and what it leaves free (:class:`JointSummary`);
    ``mech`` is the joint between two free bodies, so the relative DOF are n − rank Φ_q − 6."""
    return JointSummary(mech, q, constraint)


# ------------------------------------------------------------------------------- every constraint, three ways
def columns(mech, constraint):
    """The columns of Φ_q that belong to a constraint's bodies (their coordinates, body by body): the columns of
    the book's Jacobian tables."""
    c = mech.constraint(constraint) if isinstance(constraint, str) else constraint
    return [mech.index(str(s)) for b in c.bodies for s in mech.body_symbols(b.name)]


def _numeric(c, qc, qdc=None, compiled=False):
    """(Φ_q, γ) of one constraint from its kernel — its own or the one compiled from its symbolic Φ —, at the
    coordinates ``qc`` (and velocities ``qdc``) of its bodies. Drivers: the geometric part g(q) only."""
    nb, nc = len(c.bodies), len(c.COORDS)
    kernel, params = c.numeric(compiled=compiled)
    Qd = None if qdc is None else np.asarray(qdc, dtype=float).reshape(1, 1, nb, nc)
    _, jac, gam = kernel(np.asarray(qc, dtype=float).reshape(1, 1, nb, nc), stack_params([params]), Qd)
    return jac[0, 0], None if gam is None else gam[0, 0]


class Table:
    """A small results table that renders itself: a header and rows of cells, each a string or a
    :class:`Check` (shown as "✓ < 1e-12" or "✗ 0.34")."""

    def __init__(self, header, rows, caption=""):
        self.header, self.rows, self.caption = list(header), [list(r) for r in rows], caption

    @staticmethod
    def _text(cell):
        if isinstance(cell, Check):
            return f"✓ < {tolerance_text(cell.tol)}" if cell.ok else f"✗ {_small(cell.error)}"
        return str(cell)

    @property
    def all_ok(self):
        """True when every check in the table passes."""
        return all(c.ok for r in self.rows for c in r if isinstance(c, Check))

    def __repr__(self):
        cells = [self.header] + [[self._text(c) for c in r] for r in self.rows]
        widths = [max(len(r[k]) for r in cells) for k in range(len(self.header))]
        lines = ["  ".join(t.ljust(w) for t, w in zip(r, widths)).rstrip() for r in cells]
        return "\n".join(lines + ([self.caption] if self.caption else []))

    @staticmethod
    def _style(cell):
        # a verdict ("✓ < 1e-12") is read as one word: in a narrow column it wrapped as "✓ < 1e-" / "12"
        return "text-align:left; white-space:nowrap" if isinstance(cell, Check) else "text-align:left"

    def _repr_html_(self):
        head = "".join(f"<th>{html.escape(h)}</th>" for h in self.header)
        body = "".join("<tr>" + "".join(f"<td style='{self._style(c)}'>{html.escape(self._text(c))}</td>" for c in r)
                       + "</tr>" for r in self.rows)
        caption = f"<p>{html.escape(self.caption)}</p>" if self.caption else ""
        table = f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
        verdicts = [c for r in self.rows for c in r if isinstance(c, Check)]
        if len(self.rows) <= FOLD_AFTER or not verdicts:
            return table + caption
        bad = sum(not c.ok for c in verdicts)
        sentence = (f"All {len(verdicts)} checks of the {len(self.rows)} rows below pass." if not bad else
                    f"{bad} of {len(verdicts)} checks of the {len(self.rows)} rows below fail (marked ✗).")
        return folded(f"<p>{sentence}</p>", table, f"the {len(self.rows)} rows", show=bool(bad)) + caption


def _small(x):
    return small(x, 1e-12)


def _closed_form(c):
    """kinbook.book.table14 for spatial constraints with an entry; None otherwise."""
    if getattr(c, "chapter", None) != "spatial":
        return None
    return table14 if table14.has_entry(c) else None


def jacobian_table(mech, qs, *, h=1e-6, tol=1e-12, fd_tol=1e-8):
    """Every constraint's rows of Φ_q checked three ways at the configurations ``qs``.

    For each constraint of ``mech``: kinbook's Φ_q (its rows, the columns of its bodies) against central finite
    differences of Φ (step ``h``), against the closed form of Table 14.1 (:mod:`kinbook.book.table14`, spatial
    types) and against the kernel compiled from the type's symbolic Φ (sympy). Each cell is the largest
    absolute difference over ``qs``; "—" where the table has no entry.

    Parameters
    ----------
    mech : Mechanism
    qs : sequence of array_like, shape (n,)
        Configurations (Euler parameters need not be unit: every formula holds off the sphere).

    Returns
    -------
    Table
    """
    qs = [np.asarray(q, dtype=float) for q in qs]
    found = _jacobian_checks(mech, qs, mech.constraints, h, tol, fd_tol)
    rows = [[c.name, f"({c.label})", str(c.n_eq), *checks] for c, checks in found]
    return Table(["constraint", "type", "rows", "kernel − finite differences", "kernel − Table 14.1",
                  "kernel − sympy"], rows, f"Largest absolute difference over {len(qs)} configurations.")


def _jacobian_checks(mech, qs, constraints, h, tol, fd_tol):
    """[(constraint, [fd check, table check or "—", sympy check]), …] over the configurations ``qs``."""
    kernel_J = [mech.Phi_q(q) for q in qs]
    fd_J = [fd_jacobian(mech.Phi, q, h) for q in qs]
    out = []
    for c in constraints:
        cols, table = columns(mech, c), _closed_form(c)
        err = {"fd": 0.0, "table": 0.0, "sympy": 0.0}
        for q, J_all, fd in zip(qs, kernel_J, fd_J):
            J = J_all[c.rows][:, cols]
            err["fd"] = max(err["fd"], np.abs(J - fd[c.rows][:, cols]).max())
            # with velocities, so the one compiled function also serves gamma_table
            err["sympy"] = max(err["sympy"], np.abs(J - _numeric(c, q[cols], 0 * q[cols], compiled=True)[0]).max())
            if table is not None:
                err["table"] = max(err["table"], np.abs(J - table.jacobian_rows(c, q[cols])).max())
        out.append((c, [Check("fd", err["fd"], fd_tol), Check("table", err["table"], tol) if table is not None else "—",
                        Check("sympy", err["sympy"], tol)]))
    return out


def joint_table(joints, *, h=1e-6, tol=1e-12, fd_tol=1e-8):
    """One row per joint, each in its own two-body mechanism at an assembled configuration: its type, label and
    equations, the relative DOF it leaves, max |Φ| there, and its Jacobian rows against finite differences,
    Table 14.1 and sympy (as :func:`jacobian_table`).

    Parameters
    ----------
    joints : mapping of str to (Mechanism, q)
        The joint's name in its mechanism → the mechanism and a configuration that satisfies the joint.

    Returns
    -------
    Table
    """
    rows = []
    for name, (mech, q) in joints.items():
        q = np.asarray(q, dtype=float)
        c = mech.constraint(name)
        (_, checks), = _jacobian_checks(mech, [q], [c], h, tol, fd_tol)
        rows.append([c.type_name, f"({c.label})", str(c.n_eq), str(relative_dof(mech, q)),
                     Check("Φ", np.abs(mech.Phi(q)[c.rows]).max(), tol), *checks])
    return Table(["joint", "type", "equations", "relative DOF", "max |Φ|", "kernel − finite differences",
                  "kernel − Table 14.1", "kernel − sympy"], rows)


def gamma_table(mech, states, *, h=1e-4, tol=1e-12, fd_tol=1e-6):
    """Every constraint's γ checked three ways at the states ``states`` = [(q, q̇, q̈), …].

    For each constraint: kinbook's γ against the kernel compiled from the symbolic Φ (sympy); against
    Φ_q q̈ − Φ̈, with Φ̈ the second central difference of Φ along the path q + q̇ s + q̈ s²/2 (relative to
    max(1, |γ|)); and against the γ table of :mod:`kinbook.book.table14`. Geometric constraints (no driver).

    Returns
    -------
    Table
    """
    rows = []
    for c in mech.constraints:
        cols, table = columns(mech, c), _closed_form(c)
        err = {"fd": 0.0, "table": 0.0, "sympy": 0.0}
        for q, qd, qdd in states:
            q, qd, qdd = (np.asarray(v, dtype=float) for v in (q, qd, qdd))
            gam = mech.gamma(q, qd)[c.rows]
            path = lambda s, q=q, qd=qd, qdd=qdd: q + qd * s + 0.5 * qdd * s**2  # noqa: E731
            Phi_dd = (mech.Phi(path(h)) - 2 * mech.Phi(q) + mech.Phi(path(-h)))[c.rows] / h**2
            fd = mech.Phi_q(q)[c.rows] @ qdd - Phi_dd
            err["fd"] = max(err["fd"], np.abs(gam - fd).max() / max(1.0, np.abs(gam).max()))
            err["sympy"] = max(err["sympy"], np.abs(gam - _numeric(c, q[cols], qd[cols], compiled=True)[1]).max())
            if table is not None:
                err["table"] = max(err["table"], np.abs(gam - table.gamma_rows(c, q[cols], qd[cols])).max())
        rows.append([c.name, f"({c.label})", Check("sympy", err["sympy"], tol), Check("fd", err["fd"], fd_tol),
                     Check("table", err["table"], tol) if table is not None else "—"])
    return Table(["constraint", "type", "kernel − sympy", "kernel − (Φ_q q̈ − d²Φ/ds²), relative", "kernel − γ table"],
                 rows, f"Largest difference over {len(states)} states (q, q̇, q̈).")


def sweep_checks(result, tol=1e-3):
    """Checks of a sweep that any correct solution passes, as (what, error, tol) triples for :func:`checks`:
    q̇ against dq/dt and q̈ against dq̇/dt (second-order finite differences along the solved instants, relative
    to the largest value), and for Euler parameters |p_i| = 1, p_iᵀṗ_i = 0, p_iᵀp̈_i + ṗ_iᵀṗ_i = 0 (every body).

    The finite differences are limited by the time step: ``tol`` bounds their relative error.
    """
    t, q, qd, qdd = result.t, result.q, result.qd, result.qdd
    grad = lambda y: np.gradient(y, t, axis=0, edge_order=2)  # noqa: E731
    rel = lambda a, b: float(np.abs(a - b).max() / max(np.abs(b).max(), 1e-300))  # noqa: E731
    out = [("all of q̇ against dq/dt (relative)", rel(grad(q), qd), tol),
           ("all of q̈ against dq̇/dt (relative)", rel(grad(qd), qdd), tol)]
    mech = result.mechanism
    if isinstance(mech, Spatial):
        p, pd, pdd = ([mech.p(x, b.name) for b in mech.bodies] for x in (q, qd, qdd))
        dot = lambda a, b: np.einsum("...i,...i->...", a, b)  # noqa: E731
        worst = lambda f: float(max(np.abs(f(*v)).max() for v in zip(p, pd, pdd)))  # noqa: E731
        out += [("|p_i| = 1, every body", worst(lambda a, b, c: np.linalg.norm(a, axis=-1) - 1), 1e-9),
                ("p_iᵀṗ_i = 0", worst(lambda a, b, c: dot(a, b)), 1e-12),
                ("p_iᵀp̈_i + ṗ_iᵀṗ_i = 0", worst(lambda a, b, c: dot(a, c) + dot(b, b)), 1e-12)]
    return out


def newton_table(history, tol=TOL):
    """The iterations of ``solve_position(..., history=True)`` as a table that prints no round-off.

    One row per iterate k: max |Φ(q_k)| and max |Δq_k| as :func:`small` writes them (below ``tol``: "< 1e-12"),
    and cond(Φ_q(q_k)) to three significant digits, so the stored output is the same on every CPU.

    Returns
    -------
    Table
    """
    if not all(hasattr(history, a) for a in ("residual", "step", "cond", "t")):
        raise InputError(f"newton_table: expected the history of solve_position(..., history=True), got "
                         f"{type(history).__name__}")
    rows = [[str(k), small(r, tol), small(s, tol), f"{c:.3g}"]
            for k, (r, s, c) in enumerate(zip(history.residual, history.step, history.cond))]
    return Table(["k", "max |Φ|", "max |Δq|", "cond(Φ_q)"], rows,
                 f"Newton–Raphson at t = {history.t:g}: {len(history)} iterates, Φ_q Δq = −Φ at each.")
