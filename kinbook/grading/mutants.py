"""Mutants: the reference answer turned into the mistakes students make, each carrying its catalogue code.

Where :mod:`kinbook.grading.mistakes` makes the mistakes a checker *names*, this module makes the mistakes a
question must *refuse and name*, so that a question can be tested the way a student will break it (``kinbook
validate --mutations``). Three families, one per form of reference (two of them here):

* **expressions** (Φ, Φ_q, ν, γ as sympy rows): each additive term's sign, each term dropped (γ's φ̇² and 2φ̇ terms,
  the ∂/∂t terms of ν and γ), sin ↔ cos of one angle, Aᵀ for A (sin φ → −sin φ), one angle in degrees or in
  radians of radians, the bodies' coordinates exchanged (all of them, or the angle or the rate alone), a factor 2
  lost, a driver row left out or written twice, the whole ν or γ with the wrong sign — and the catalogue's own
  structural mistakes of the constraint (points s_i ↔ s_j, A omitted …, :func:`kinbook.grading.mistakes.structural`);
* **code** (a numeric worked answer, a Python function): the same slips made in its source — made by
  :mod:`kinbook.book.tryits.code_mutants`, with the try-its, because it compiles and runs code (the grading package
  runs none);
* **values** (a number or an array, when nothing else is known): its sign, one entry's sign, degrees, radians of
  radians, a factor 2, the matrix transposed, two entries exchanged.

A mutant equal to the reference *as a function* (on every configuration, for code on every set of data tried) is
dropped: it is not a mistake. One equal to it on the data of a question but not elsewhere is kept — that is what a
blind spot of the data looks like.

What a checker's result says of a mutant (blind spot, named, unnamed) and the mutation table are
:mod:`kinbook.grading.mutant_names`; so is the diagnose stage's use of these mutants to name a wrong row.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np

from .quantities import quantity_of

__all__ = ["Mutant", "mutants", "expression_mutants", "row_mutants", "reference_mutants", "reference_rows", "samples_for",
           "value_mutants", "distinct", "sample", "same_values", "MAX_TERMS"]

MAX_TERMS = 12
"""Rows with more terms than this get no term-by-term mutants (each term's sign and its dropping)."""

DEG = 180.0 / np.pi

@dataclass
class Mutant:
    """One mistake made on a reference.

    Attributes
    ----------
    code : str
        The catalogue code the mistake must be named by (:mod:`kinbook.grading.catalogue`).
    operator : str
        What was done, for the instructor's table ("sin↔cos of phi2", "drop term 3 of row 1").
    value : object
        The wrong answer: sympy rows (a list, or a Matrix for Φ_q), a Python function (code), or an array.
    """

    code: str
    operator: str
    value: object = field(repr=False)
    also: set = field(default_factory=set)
    """Codes of other mistakes that give the same wrong answer (it may be named by any of them)."""


def mutants(reference, **options):
    """The mutants of a reference: :func:`expression_mutants` for sympy rows or a Matrix, :func:`value_mutants` for
    numbers. ``options`` go to the one called. (A worked answer's code is mutated by
    :mod:`kinbook.book.tryits.code_mutants`: the grading package runs no code.)"""
    import sympy as sp  # import time: sympy only when needed

    if isinstance(reference, sp.MatrixBase) or (isinstance(reference, (list, tuple)) and reference
                                               and all(isinstance(x, sp.Basic) for x in reference)):
        return expression_mutants(reference, **options)
    return value_mutants(reference, **options)


# ============================================================================================== expressions
def reference_rows(target, quantity):
    """The library's symbolic reference of a checker's target: ``(rows, q, qd, t, blocks, drivers)``.

    ``target`` is what a checker is given (a mechanism or one of its constraints); ``quantity`` one of "Phi",
    "Phi_q", "nu", "gamma". For a constraint, Φ_q has the columns of its own bodies (the book's tables). ``blocks``
    lists, per constraint, its rows and its bodies' coordinate symbols (with their velocities) — the ``blocks`` of
    :func:`expression_mutants`; ``drivers`` the rows of Φ that drivers write.
    """
    from .target import target_for  # import time: grading.target loads sympy

    t = target_for(target)
    mech = t.mech
    if len(t.constraints) == 1 and t.constraint is not None:
        d = mech.derivation(t.constraint)
    else:
        d = mech.symbolic()
    rows = getattr(d, quantity_of(quantity).name)  # the derivation's own Φ, Φ_q, ν or γ
    q = list(mech.q)

    def groups(c):
        return [(list(mech.body_symbols(b.name)), [mech.qd[q.index(x)] for x in mech.body_symbols(b.name)])
                for b in c.bodies]

    blocks, drivers, row = [], [], 0
    for c in t.constraints:
        block = list(range(row, row + c.n_eq))
        blocks.append((block, groups(c)))
        if c.kind == "driver":
            drivers += block
        row += c.n_eq
    return rows, list(mech.q), list(mech.qd), mech.t, blocks, drivers


def samples_for(target, quantity):
    """(Q, QD, T): the configurations a checker compares ``quantity`` at — generic ones for Φ, assembled ones (with
    velocities that satisfy the velocity equations) for Φ_q, ν and γ (:meth:`kinbook.grading.target.Target.samples`)."""
    from .target import target_for  # import time: grading.target loads sympy

    s = target_for(target).samples("assembled" if quantity_of(quantity).derived else "generic")
    return s.Q, s.QD, s.T


def expression_mutants(rows, *, quantity="Phi", groups=(), blocks=None, drivers=(), structural=(), q=None, qd=None,
                       t=None, rng=0, terms=True, keep_all=False, samples=None, angles=True):
    """Mutants of symbolic rows (a list for Φ, ν, γ; a Matrix for Φ_q), each a :class:`Mutant` whose value has
    the shape of ``rows``; those equal to ``rows`` at every one of a few random points are dropped.

    Parameters
    ----------
    quantity : {"Phi", "Phi_q", "nu", "gamma"}
    groups : list of (coordinates, velocities)
        The symbols of each body (for the bodies', the angles' and the rates' exchanges).
    blocks : list of (row indices, groups), optional
        Instead of ``groups``: the bodies of each constraint and its rows (a whole Φ), exchanged joint by joint.
    drivers : list of int
        Rows of Φ written by drivers (left out, written twice).
    structural : list of (code, rows, what)
        Mistakes made elsewhere (the catalogue's structural variants carried through the derivation), kept when
        they differ from ``rows``.
    terms : bool
        Also each term's sign, each term dropped, a factor 2 lost (False: the other operators only, the ones a
        checker's own term search does not make — :func:`row_mutants`).
    q, qd, t : symbols
        For the equality test (default: the rows' free symbols).
    samples : (Q, QD, T), optional
        The configurations the equality test uses (in the order of ``q``, ``qd``; default: random points).
    angles : bool
        Also the slips made in A(φ) itself — Aᵀ for A, an angle in degrees, the other body's angle —, which in Φ_q,
        ν and γ are made in Φ and carried through the derivation instead (:func:`reference_mutants`).
    """
    import sympy as sp  # import time: sympy only when needed

    M = sp.Matrix(rows) if not isinstance(rows, sp.MatrixBase) else rows
    matrix = isinstance(rows, sp.MatrixBase) and M.shape[1] > 1
    if qd is None:  # the velocities of the bodies named (γ's squared rates)
        qd = [v for _, bg in (blocks if blocks is not None else [(None, groups)]) for _, vs in bg for v in vs]
    out = []

    def add(code, op, N):
        out.append(Mutant(code, op, N if matrix else list(N)))

    def entry_map(f):
        return M.applyfunc(f)

    _term_slips(M, matrix, add, quantity_of(quantity), qd, t, terms)
    _angle_slips(M, add, entry_map, t, angles)
    _body_slips(M, add, blocks if blocks is not None else [(None, groups)], angles)
    # rows: a driver's row left out or written twice; the whole ν or γ with the wrong sign
    if not matrix and terms:
        for i in drivers:
            if i < M.shape[0]:
                rows_ = [M[k, 0] for k in range(M.shape[0])]
                add("missing_row", f"driver row {i + 1} left out", sp.Matrix(rows_[:i] + rows_[i + 1:]))
                add("extra_row", f"driver row {i + 1} written twice", sp.Matrix(rows_[:i + 1] + rows_[i:]))
        Q = quantity_of(quantity)
        if Q.right_hand_side:  # the whole ν or γ with the wrong sign
            add(Q.sign_code, f"−{Q.label}", -M)
    for code, S, what in structural:
        add(code, what, sp.Matrix(S) if not matrix else S)
    return out if keep_all else distinct(out, M, q, qd, t, rng=rng, samples=samples)


def _term_slips(M, matrix, add, quantity, qd, t, terms):
    """Each term's sign, each term dropped (``terms``), a factor 2 lost or (γ's squared rates) doubled — entry by
    entry."""
    import sympy as sp  # import time: sympy only when needed

    for (i, j) in itertools.product(range(M.shape[0]), range(M.shape[1])):
        e = M[i, j]
        if e == 0:
            continue
        parts = sp.Add.make_args(sp.expand(e))
        where = f"({i + 1}, {j + 1})" if matrix else f"row {i + 1}"
        if len(parts) <= MAX_TERMS:
            for k, term in enumerate(parts):
                if len(parts) > 1 and terms:
                    N = M.copy()
                    N[i, j] = e - 2 * term
                    add("sign_flip", f"sign of term {k + 1} of {where}", N)
                    N = M.copy()
                    N[i, j] = e - term
                    add(_dropped_code(term, quantity, qd, t), f"drop term {k + 1} of {where}", N)
                coeff, _ = term.as_coeff_Mul()
                if coeff.is_number and abs(float(coeff)) >= 2 and float(coeff) % 2 == 0:
                    N = M.copy()
                    N[i, j] = e - term / 2
                    add("factor_2_missing", f"factor 2 of term {k + 1} of {where} lost", N)
                elif quantity.velocities and _velocity_degree(term, qd) == 2 and len(parts) > 1:
                    N = M.copy()
                    N[i, j] = e + term
                    add("factor_2_extra", f"term {k + 1} of {where} doubled", N)
        if terms and quantity.right_hand_side and not matrix and M.shape[0] > 1:
            N = M.copy()
            N[i, j] = -e
            add("sign_flip", f"sign of {where}", N)


def _angle_slips(M, add, entry_map, t, in_A):
    """sin ↔ cos of one angle; with ``in_A`` also Aᵀ for A, the angle in degrees, in radians of radians."""
    import sympy as sp  # import time: sympy only when needed

    angles = sorted({a.args[0] for a in M.atoms(sp.sin, sp.cos)}, key=sp.default_sort_key)
    for a in angles:
        swap = {sp.sin(a): sp.Symbol("_c"), sp.cos(a): sp.Symbol("_s")}
        back = {sp.Symbol("_c"): sp.cos(a), sp.Symbol("_s"): sp.sin(a)}
        add("sin_cos", f"sin↔cos of {a}", entry_map(lambda x, s=swap, b=back: x.subs(s).subs(b)))
        if in_A:
            add("A_transposed", f"sin({a}) → −sin({a}) (Aᵀ for A)",
                entry_map(lambda x, a=a: x.subs(sp.sin(a), -sp.sin(a))))
    for s in sorted({x for a in angles for x in a.free_symbols if x != t} if in_A else (), key=sp.default_sort_key):
        for code, f in (("degrees", DEG), ("radians_twice", 1 / DEG)):
            def scaled(x, s=s, f=f):
                return x.replace(lambda y: isinstance(y, (sp.sin, sp.cos)) and y.has(s),
                                 lambda y: y.func(y.args[0].xreplace({s: f * s})))
            add(code, f"{s} {'in degrees' if code == 'degrees' else 'in radians of radians'}", entry_map(scaled))


def _body_slips(M, add, blocks, in_A):
    """The bodies' coordinates exchanged — all of them, the angle alone, the rate alone — within each constraint's
    rows (a whole Φ's bodies are exchanged joint by joint)."""
    for rows_of, body_groups in blocks:
        def within(f, rows_of=rows_of):
            N = M.copy()
            for i in (range(M.shape[0]) if rows_of is None else rows_of):
                for j in range(M.shape[1]):
                    N[i, j] = f(M[i, j])
            return N

        for (qa, va), (qb, vb) in itertools.combinations(body_groups, 2):
            both = dict(zip(qa + va, qb + vb))
            both.update(zip(qb + vb, qa + va))
            if in_A and M.free_symbols & set(both):
                add("swapped_bodies", f"bodies {qa[0]}… ↔ {qb[0]}…", within(lambda x, m=both: x.xreplace(m)))
            ka = [k for k, s in enumerate(qa) if s.name.startswith("phi")]
            if len(ka) == 1:  # planar: the angle, then its rate
                k = ka[0]
                for what, m in (("angle", {qa[k]: qb[k], qb[k]: qa[k], va[k]: vb[k], vb[k]: va[k]}),
                                ("rate", {va[k]: vb[k], vb[k]: va[k]})):
                    if M.free_symbols & set(m) and (in_A or what == "rate"):
                        add("other_body", f"the other body's {what} ({qa[k]}↔{qb[k]})",
                            within(lambda x, m=m: x.xreplace(m)))


def row_mutants(expr, *, quantity="Phi", groups=()):
    """(code, operator, expression) of one row's mistakes that a search over its terms does not make: sin ↔ cos,
    Aᵀ for A, an angle in degrees or radians of radians, the other body's coordinates, angle or rate — for a
    checker naming a wrong row (:mod:`kinbook.grading.diagnose`). Not filtered: the checker compares."""
    return [(m.code, m.operator, m.value[0]) for m in
            expression_mutants([expr], quantity=quantity, groups=groups, terms=False, keep_all=True)]


def reference_mutants(target, quantity, limit=None):
    """Every mutant of a checker's reference (a mechanism or a constraint; ``quantity`` "Phi", "Phi_q", "nu" or
    "gamma"), told apart from it where the checker compares: the slips of :func:`expression_mutants` made in the
    quantity itself, the slips of A(φ) and the catalogue's structural mistakes
    (:func:`kinbook.grading.mistakes.structural`) made in Φ — and, for Φ_q, ν and γ, carried through the
    derivation as a student carries them. ``limit``: at most 3 × ``limit`` are compared (:func:`sample`, every
    code kept), for a caller that grades ``limit`` of them."""
    import sympy as sp  # import time: sympy only when needed

    from ..core.symbolic import derive  # import time: core.symbolic loads sympy
    from .mistakes import structural  # import time: grading.mistakes loads sympy
    from .target import target_for  # import time: grading.target loads sympy

    rows, q, qd, t, blocks, drivers = reference_rows(target, quantity)
    T = target_for(target)
    found = expression_mutants(rows, quantity=quantity, blocks=blocks, drivers=drivers, q=q, qd=qd, t=t,
                               keep_all=True, angles=not quantity_of(quantity).derived)
    phi_level = []
    if len(T.constraints) == 1:
        phi_level += [Mutant(v.code, "catalogue: " + v.code + (f" ({v.detail})" if v.detail is not None else ""),
                             list(v.exprs)) for v in structural(T, T.constraints[0]) if v.code != "book_misprint"]
    Q, QD, TT = samples_for(target, "Phi_q")

    def equivalent(m):  # a Φ that vanishes wherever the mechanism is assembled: another formulation, no mistake
        try:
            V = np.asarray(T.tape(list(sp.Matrix(m.value)))(Q, QD, TT)["value"], float)
        except Exception:  # noqa: BLE001
            return False
        R = np.asarray(T.tape(list(sp.Matrix(Phi_rows)))(Q, QD, TT)["value"], float)
        return V.shape == R.shape and bool(np.all(np.abs(V) <= 1e-8 * (1.0 + np.abs(V).max())))

    Phi_rows = reference_rows(target, "Phi")[0]
    if not quantity_of(quantity).derived:
        found = [m for m in found if not equivalent(m)] + [m for m in phi_level if not equivalent(m)]
    else:
        Phi, _, _, _, _, _ = reference_rows(target, "Phi")
        d = T.mech.derivation(T.constraint) if len(T.constraints) == 1 and T.constraint is not None \
            else T.mech.symbolic()
        in_A = [m for m in expression_mutants(Phi, quantity="Phi", blocks=blocks, terms=False, keep_all=True)
                if m.code != "sin_cos"] + phi_level
        if limit is not None:
            in_A = sample(in_A, limit)
        for m in in_A:
            if equivalent(m):
                continue
            try:
                D = derive(sp.Matrix(m.value), d.q, d.qd, d.t)
            except Exception:  # noqa: BLE001 — a variant that cannot be derived is no test
                continue
            found.append(Mutant(m.code, m.operator + ", carried through the derivation",
                                getattr(D, quantity_of(quantity).name)))
    if limit is not None:
        found = sample(found, 3 * limit)
    return distinct(found, rows, q, qd, t, samples=samples_for(target, quantity))


def _dropped_code(term, quantity, qd, t):
    """The code a dropped term stands for: a ∂/∂t term of γ, the centripetal or Coriolis term, any term."""
    if quantity.velocities and t is not None and term.has(t) and _velocity_degree(term, qd) == 0:
        return "missing_tt_term"
    return "missing_term"


def _velocity_degree(term, qd):
    if not qd:
        return 0
    import sympy as sp  # import time: sympy only when needed

    try:
        return sp.Poly(term, *[v for v in qd if term.has(v)]).total_degree() if any(term.has(v) for v in qd) else 0
    except sp.PolynomialError:
        return 0


def distinct(found, reference, q=None, qd=None, t=None, *, rng=0, points=6, samples=None):
    """``found`` without the mutants equal to ``reference`` — at ``points`` random points, or at ``samples`` = (Q,
    QD, T), the configurations the checker compares at (Φ_q, ν and γ on the assembled ones: a mutant equal there
    is right wherever the mechanism can be) — and with each repeated value counted once: a later mutant equal to
    an earlier one adds its code to the earlier one's :attr:`Mutant.also` (one wrong answer, two readings)."""
    import sympy as sp  # import time: sympy only when needed

    from .jets import Tape  # import time: grading.jets loads sympy

    ref = sp.Matrix(reference)
    syms = sorted(ref.free_symbols | set().union(*[sp.Matrix(m.value).free_symbols for m in found] or [set()]),
                  key=lambda s: s.name)
    if q is None:
        q, qd, t = syms, [], sp.Symbol("t", real=True)
    elif samples is None:
        extra = [s for s in syms if s not in set(q) | set(qd or ()) | {t}]
        q = list(q) + extra
    if samples is not None:
        Q, QD, T = samples
    else:
        gen = np.random.default_rng(rng)
        Q = gen.uniform(-1.3, 1.3, (points, len(q)))
        QD = gen.uniform(-1.3, 1.3, (points, len(qd or ())))
        T = gen.uniform(0.1, 1.1, points)

    def values(M):
        M = sp.Matrix(M)
        flat = [M[i, j] for i in range(M.shape[0]) for j in range(M.shape[1])]
        return np.asarray(Tape(flat, list(q), list(qd or ()), t)(Q, QD if qd else None, T)["value"], float)

    R = values(ref)
    kept, seen = [], []
    for m in found:
        try:
            with np.errstate(all="ignore"):
                V = values(m.value)
        except Exception:  # noqa: BLE001 — a mutant that cannot be evaluated (a division by zero …) is no test
            continue
        if not np.all(np.isfinite(V)) or (V.shape == R.shape and _close(V, R)):
            continue
        twin = next((k for k, W in seen if W.shape == V.shape and _close(V, W)), None)
        if twin is not None:
            twin.also.add(m.code)
            continue
        seen.append((m, V))
        kept.append(m)
    return kept


def same_values(a, b, rtol=1e-9):
    """Two arrays equal to ``rtol`` (relative, with 1 as the smallest scale): the test that tells a mutant from the
    reference."""
    return _close(a, b, rtol)


def _close(a, b, rtol=1e-9):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return bool(np.all(np.abs(a - b) <= rtol * (1.0 + np.maximum(np.abs(a), np.abs(b)))))


# ============================================================================================== values
def value_mutants(value, *, angles=False):
    """Mutants of a number or an array: its sign, one entry's sign, a factor 2, degrees and radians of radians
    (``angles``: the value is an angle or holds angles), the matrix transposed, two entries exchanged. Those equal to
    the value, or to one of its other right answers (an :class:`~kinbook.grading.expected.Expected`'s
    ``equivalents``: −p for p), are dropped; one equal to a catalogued wrong answer of it (its ``variants``) carries
    that code in :attr:`Mutant.also`."""
    v = np.asarray(getattr(value, "value", value), float)
    right = [np.asarray(e, float) for e, _ in getattr(value, "equivalents", ())]
    known = [(code, np.asarray(w, float)) for code, w, *_ in getattr(value, "variants", ())]
    out = [Mutant("sign_flip", "sign of the whole answer", -v),
           Mutant("factor_2_missing", "half the answer", v / 2), Mutant("factor_2_extra", "twice the answer", 2 * v)]
    if v.size > 1:
        for k in range(v.size):
            w = v.copy().ravel()
            w[k] = -w[k]
            out.append(Mutant("sign_flip", f"sign of entry {k + 1}", w.reshape(v.shape)))
    if angles:
        out += [Mutant("degrees", "degrees for radians", v * DEG), Mutant("radians_twice", "radians of radians", v / DEG)]
    out = [Mutant(m.code, m.operator, np.asarray(m.value, float)) for m in out]
    if v.ndim == 2 and v.shape[0] == v.shape[1]:
        out.append(Mutant("transposed", "the matrix transposed", v.T.copy()))
    if v.ndim == 1 and 1 < v.size <= 4:
        for a, b in itertools.combinations(range(v.size), 2):
            w = v.copy()
            w[[a, b]] = w[[b, a]]
            out.append(Mutant("swapped_entries", f"entries {a + 1} and {b + 1} exchanged", w))
    kept = []
    for m in out:
        if _close(m.value, v) or any(e.size == m.value.size and _close(m.value.ravel(), e.ravel()) for e in right):
            continue
        twin = next((k for k in kept if k.value.shape == m.value.shape and _close(m.value, k.value)), None)
        if twin is not None:
            twin.also.add(m.code)
        else:
            m.also |= {code for code, w in known if w.size == m.value.size and _close(m.value.ravel(), w.ravel())}
            kept.append(m)
    return kept


def sample(found, limit):
    """At most ``limit`` of ``found``, every code represented: taken in turn from each code's list (in order), so a
    large Jacobian's hundreds of term slips leave room for its one sin ↔ cos. Deterministic."""
    if len(found) <= limit:
        return list(found)
    by_code = {}
    for m in found:
        by_code.setdefault(m.code, []).append(m)
    queues = [list(v) for v in by_code.values()]
    picked = []
    while len(picked) < limit:
        for q in queues:
            if q and len(picked) < limit:
                # spread over the list: first, last, middle …
                picked.append(q.pop(0 if len(q) % 2 else len(q) // 2))
    order = {id(m): k for k, m in enumerate(found)}
    return sorted(picked, key=lambda m: order[id(m)])
