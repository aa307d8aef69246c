"""The worked answers' slips: a numeric try-it's worked answer (a small Python function, what ``kb.reveal``
shows) mutated in its own code the way a student slips — ``np.sin`` ↔ ``np.cos`` at one call or throughout,
``np.radians`` left out or applied twice, the sign of one term, one term dropped, a ``.T`` left out or added, A(φ) ↔
B(φ), a name of body i for the one of body j, ``arctan`` for ``arctan2``, a ``/ 2`` or a ``2 *`` lost, a square lost,
``abs`` left out, a chain of turns multiplied in reverse order — each a :class:`kinbook.grading.mutants.Mutant` with
its catalogue code. It lives with the try-its, not in the grading package, because it compiles and runs code: the
library's own worked answers, never a student's.
"""

from __future__ import annotations

import ast
import functools
import inspect
import itertools
import textwrap

import numpy as np

from ...grading.mutants import Mutant, same_values

__all__ = ["code_mutants", "compiled_mutants", "slips", "EVERYWHERE"]


class _Site:
    """One place in a function's AST where an operator applies (found by walking, applied to a fresh copy)."""

    def __init__(self, code, operator, index, apply):
        self.code, self.operator, self.index, self.apply = code, operator, index, apply


def _sites(tree):
    """Every (code, operator, node index, rewrite) the code operators find in ``tree``."""
    nodes = list(ast.walk(tree))
    names = sorted({n.id for n in nodes if isinstance(n, ast.Name)} |
                   {a.arg for n in nodes if isinstance(n, ast.arguments) for a in n.args + n.kwonlyargs})
    out = []
    for k, n in enumerate(nodes):
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute):
            f = n.func.attr
            pair = {"sin": "cos", "cos": "sin", "arcsin": "arccos", "arccos": "arcsin"}.get(f)
            if pair:
                out.append(_Site("sin_cos", f"np.{f} → np.{pair}", k, lambda n, p=pair: _set_attr(n, p)))
            if f == "radians" and n.args:
                out.append(_Site("degrees", "np.radians left out", k, lambda n: n.args[0]))
                out.append(_Site("radians_twice", "np.radians applied twice", k,
                                 lambda n: ast.Call(n.func, [n], [])))
            if f == "arctan2" and len(n.args) == 2:
                out.append(_Site("arctan_quadrant", "np.arctan(y / x) for np.arctan2(y, x)", k,
                                 lambda n: ast.Call(ast.Attribute(n.func.value, "arctan", ast.Load()),
                                                    [ast.BinOp(n.args[0], ast.Div(), n.args[1])], [])))
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "abs" and len(n.args) == 1:
            out.append(_Site("sign_flip", "abs(…) left out (a length's sign)", k, lambda n: n.args[0]))
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in ("A", "B"):
            other = "B" if n.func.id == "A" else "A"
            out.append(_Site("A_for_B" if other == "A" else "B_for_A", f"{n.func.id}(…) → {other}(…)", k,
                             lambda n, o=other: ast.Call(ast.Name(o, ast.Load()), n.args, n.keywords)))
        if isinstance(n, ast.BinOp) and isinstance(n.op, (ast.Add, ast.Sub)):
            flip = ast.Sub() if isinstance(n.op, ast.Add) else ast.Add()
            out.append(_Site("sign_flip", "the sign of a term (+ ↔ −)", k,
                             lambda n, f=flip: ast.BinOp(n.left, f, n.right)))
            out.append(_Site("missing_term", "a term dropped (the right one)", k, lambda n: n.left))
            out.append(_Site("missing_term", "a term dropped (the left one)", k,
                             lambda n: n.right if isinstance(n.op, ast.Add) else ast.UnaryOp(ast.USub(), n.right)))
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, ast.USub):
            out.append(_Site("sign_flip", "a minus sign left out", k, lambda n: n.operand))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Pow) and _const(n.right) == 2:
            out.append(_Site("missing_square", "a square left out", k, lambda n: n.left))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Div) and _const(n.right) == 2:
            out.append(_Site("factor_2_missing", "a / 2 left out", k, lambda n: n.left))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Mult) and 2 in (_const(n.left), _const(n.right)):
            out.append(_Site("factor_2_missing", "a factor 2 left out", k,
                             lambda n: n.right if _const(n.left) == 2 else n.left))
        if isinstance(n, ast.Attribute) and n.attr == "T":
            out.append(_Site("A_for_AT", "a transpose (.T) left out", k, lambda n: n.value))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult):
            if isinstance(n.left, ast.BinOp) and isinstance(n.left.op, ast.MatMult):
                out.append(_Site("extrinsic_order", "the turns multiplied in reverse order", k, _reversed_chain))
            elif not isinstance(n.left, ast.Attribute) or n.left.attr != "T":
                out.append(_Site("A_transposed", "Aᵀ for A (the matrix transposed)", k,
                                 lambda n: ast.BinOp(ast.Attribute(n.left, "T", ast.Load()), ast.MatMult(), n.right)))
    for a, b in _body_pairs(names):
        out.append(_Site("other_body", f"{a} ↔ {b}", None, lambda tree, a=a, b=b: _rename(tree, {a: b, b: a})))
    out += _other_body_entries(nodes)
    if not any(s.code == "radians_twice" for s in out):  # the angles are radians already: np.radians wrongly added
        for k, n in enumerate(nodes):
            if _angle_call(n):
                out.append(_Site("radians_twice", "np.radians applied to an angle in radians", k,
                                 lambda n: ast.Call(n.func, [_radians(n.args[0])] + n.args[1:], n.keywords)))
            if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute) and n.func.attr in _ARC:
                out.append(_Site("radians_twice", f"np.radians of np.{n.func.attr}(…), already in radians", k,
                                 _radians))
    return out


PLANAR_BODY = 3
"""Coordinates of a planar body in q (x, y, φ): q[k ± 3] is the same coordinate of the neighbouring body."""


def _other_body_entries(nodes):
    """A planar q's entry (q0[8], q1[6:8]) read one body off (q0[5], q1[3:5]): the wrong body's angle, rate or
    origin, as a student reads it from the notebook's q. Only names that begin with q; a shift out of range
    fails to run and is dropped."""
    out = []
    for k, n in enumerate(nodes):
        if not (isinstance(n, ast.Subscript) and isinstance(n.value, ast.Name) and n.value.id.startswith("q")):
            continue
        for step in (-PLANAR_BODY, PLANAR_BODY):
            if _const(n.slice) is not None and _const(n.slice) + step >= 0:
                out.append(_Site("other_body", f"{n.value.id}[{_const(n.slice)}] → [{_const(n.slice) + step}]", k,
                                 lambda n, s=step: ast.Subscript(n.value, ast.Constant(_const(n.slice) + s), n.ctx)))
            elif (isinstance(n.slice, ast.Slice) and _const(n.slice.lower) is not None
                  and _const(n.slice.upper) is not None and _const(n.slice.lower) + step >= 0):
                out.append(_Site("other_body", f"{n.value.id}[a:b] one body off", k,
                                 lambda n, s=step: ast.Subscript(n.value, ast.Slice(
                                     ast.Constant(_const(n.slice.lower) + s), ast.Constant(_const(n.slice.upper) + s)),
                                     n.ctx)))
    return out


def _angle_call(n):
    """np.sin(x), np.cos(x), A(φ), B(φ): a call whose first argument is an angle in radians."""
    if not isinstance(n, ast.Call) or not n.args:
        return False
    f = n.func
    return ((isinstance(f, ast.Attribute) and f.attr in ("sin", "cos"))
            or (isinstance(f, ast.Name) and f.id in ("A", "B")))


_ARC = ("arctan2", "arctan", "arccos", "arcsin")
"""numpy's inverse trigonometric functions: their results are radians."""


def _radians(x):
    return ast.Call(ast.Attribute(ast.Name("np", ast.Load()), "radians", ast.Load()), [x], [])


EVERYWHERE = ("sin_cos", "arctan_quadrant", "degrees", "radians_twice", "A_for_B", "B_for_A")
"""Code slips that are also made at every place they apply at once (a method, not a typo)."""


def _const(n):
    return n.value if isinstance(n, ast.Constant) and isinstance(n.value, (int, float)) else None


def _set_attr(n, attr):
    return ast.Call(ast.Attribute(n.func.value, attr, ast.Load()), n.args, n.keywords)


def _reversed_chain(n):
    items = []

    def walk(x):
        if isinstance(x, ast.BinOp) and isinstance(x.op, ast.MatMult):
            walk(x.left)
            walk(x.right)
        else:
            items.append(x)

    walk(n)
    out = items[-1]
    for x in reversed(items[:-1]):
        out = ast.BinOp(out, ast.MatMult(), x)
    return out


def _body_pairs(names):
    """Pairs of names that differ only in a body's mark: a digit (phi2, phi3), i/j (w_i, w_j), 1/2 (xi_1A)."""
    out = []
    for a, b in itertools.combinations(names, 2):
        if len(a) != len(b):
            continue
        diff = [k for k in range(len(a)) if a[k] != b[k]]
        if len(diff) != 1:
            continue
        x, y = a[diff[0]], b[diff[0]]
        if (x.isdigit() and y.isdigit()) or {x, y} == {"i", "j"}:
            out.append((a, b))
    return out


def _rename(tree, mapping):
    class R(ast.NodeTransformer):
        def visit_Name(self, node):
            if node.id in mapping:
                return ast.copy_location(ast.Name(mapping[node.id], node.ctx), node)
            return node

    return R().visit(tree)


def _function_tree(fn):
    src = textwrap.dedent(inspect.getsource(fn))
    return ast.parse(src)


@functools.lru_cache(maxsize=128)
def compiled_mutants(fn):
    """Every syntactic code mutant of ``fn``: (code, operator, function) — compiled once, in ``fn``'s module."""
    tree = _function_tree(fn)
    out = []
    sites = [[site] for site in _sites(tree)]
    nodes = list(ast.walk(tree))
    for code in EVERYWHERE:  # a method's slip made at every place it applies (arctan for both arctan2 …)
        group = [site for site in _sites(tree) if site.code == code and site.index is not None]
        if len(group) > 1:
            sites.append(group)
        by_angle = {}  # … and at every place one angle is used (sin θ and cos θ exchanged in R_x(θ) only)
        for site in group:
            n = nodes[site.index]
            if isinstance(n, ast.Call) and n.args:
                by_angle.setdefault(ast.dump(n.args[0]), []).append(site)
        sites += [g for g in by_angle.values() if 1 < len(g) < len(group)]
    for group in sites:
        fresh = _function_tree(fn)
        if group[0].index is None:
            new = group[0].apply(fresh)
        else:
            nodes = list(ast.walk(fresh))
            new = fresh
            for site in group:
                node = nodes[site.index]
                new = _replace(new, node, site.apply(node))
        site = group[0] if len(group) == 1 else _Site(group[0].code, f"{group[0].code}: everywhere", None, None)
        ast.fix_missing_locations(new)
        try:
            ns = {}
            exec(compile(new, f"<mutant of {fn.__name__}>", "exec"), fn.__globals__, ns)  # the library's own code
            out.append((site.code, site.operator, ns[fn.__name__]))
        except Exception:  # noqa: BLE001 — an operator that does not make valid code here
            continue
    return tuple(out)


def code_mutants(fn, *, runs=(), rng=0):
    """Mutants of a function's code (a numeric worked answer): each a :class:`Mutant` whose value is the mutated
    function, compiled in ``fn``'s module. ``runs`` is a list of callables ``run(f) -> value`` (the function
    called with one set of data each, the first being the question's own); a mutant whose values equal ``fn``'s in
    every run is dropped, as is one that fails to run on the question's data, and one whose values repeat an
    earlier mutant's."""
    refs = []
    for run in runs:
        try:
            refs.append(np.asarray(run(fn), float))
        except Exception:  # noqa: BLE001 — a set of data the reference itself cannot run: not compared
            refs.append(None)
    out, seen = [], []
    for code, operator, f in compiled_mutants(fn):
        vals, same = [], True
        for run, ref in zip(runs, refs):
            try:
                with np.errstate(all="ignore"):
                    v = np.asarray(run(f), float)
            except Exception:  # noqa: BLE001 — a mutant that fails to run
                v = None
            vals.append(v)
            if ref is not None and (v is None or v.shape != ref.shape or not same_values(v, ref)):
                same = False
        if runs and (vals[0] is None or same):
            continue
        key = [None if v is None else np.round(v, 9).tobytes() for v in vals]
        twin = next((m for k, m in seen if k == key), None)
        if twin is not None:
            twin.also.add(code)
            continue
        out.append(Mutant(code, operator, f))
        seen.append((key, out[-1]))
    return out


_SLIPS: dict = {}
_SLIPS_KEPT = 256


def slips(fn, call, key):
    """(code, operator, value) of ``fn``'s code mutants at one set of data, those whose value differs from ``fn``'s
    there: ``call(f)`` runs a function with the data, ``key`` names the data (a text). Kept for the last
    :data:`_SLIPS_KEPT` keys — a numeric try-it names these wrong answers at every check."""
    k = (fn, key)
    if k not in _SLIPS:
        if len(_SLIPS) >= _SLIPS_KEPT:
            _SLIPS.pop(next(iter(_SLIPS)))
        try:
            _SLIPS[k] = tuple((m.code, m.operator, np.asarray(call(m.value), float))
                              for m in code_mutants(fn, runs=[call]))
        except Exception:  # noqa: BLE001 — a worked answer that cannot be mutated names nothing more
            _SLIPS[k] = ()
    return _SLIPS[k]


def _replace(tree, old, new):
    class R(ast.NodeTransformer):
        def generic_visit(self, node):
            if node is old:
                return new
            return super().generic_visit(node)

    if tree is old:
        return new
    return R().visit(tree)
