"""Rounded constants (part of reading an answer): the numbers' own rule, as STACK's NumSigFigs.

A student who types 2.356 for 3π/4, 0.866 for √3/2 or 1.118 for √5/2 has written the exercise's constant
rounded; the book itself prints 4–6 digits. The rule, the same in every checker and whatever the row's scale:

* a decimal of the answer that is a correct rounding, to its own significant digits (at least
  :data:`MIN_DIGITS`), of an exact constant of the exercise — a number of the reference's symbolic rows: 3π/4,
  √3/2, a length, a speed — stands for that constant (:func:`exact`);
* a decimal near such a constant but not a rounding of it (2.357 for 3π/4 = 2.35619…, 0.867 for √3/2), or a
  rounding with fewer digits (2.4), is a mistake of its own: if the answer is right with the constant in its place, it is named ``not_rounded``
  with both values (:func:`named`);
* a decimal that is the exercise's own data (0.7 where the mechanism says 0.7) is that datum, exactly.

Whether a decimal is a rounding is decided on the number as written (its shortest decimal form), never on the
tolerance of the comparison, so a student can predict it.
"""

from __future__ import annotations

import math
import re

from ._i18n import Msg
from .quantities import quantity_of
from .read import Answer
from .report import CheckResult, hints

__all__ = ["distinct_leaves", "MIN_DIGITS", "NEAR", "exact_constants", "significant_digits", "typed_digits", "is_rounding", "exact",
           "graded", "named", "in_degrees"]

MIN_DIGITS = 3
"""The fewest significant digits a rounded constant may have."""

NEAR = 2e-2
"""A decimal within this relative distance of a constant that is not a rounding of it is offered as a
``not_rounded`` slip (the answer is checked again with the constant in its place, so the name is given only when
the answer is right with it): 2 % reaches a slip in the third significant digit of any constant (2.37 or 2.35 for
3π/4, 1.49 for a length 1.5), a misrounding or a miscopied digit; the degrees and the integers of the exercise
use the same distance."""


def significant_digits(x):
    """The significant digits of ``x`` in its shortest decimal form: 2.356 → 4, 0.000123 → 3, 1.05 → 3; zeros at
    either end do not count (120.0 → 2: whether they were meant is not known)."""
    mantissa = repr(abs(float(x))).lower().split("e")[0].replace(".", "")
    return len(mantissa.strip("0"))


def is_rounding(x, c, digits=None):
    """Whether ``x`` is ``c`` rounded to ``digits`` significant digits (default: those of ``x``)."""
    digits = significant_digits(x) if digits is None else digits
    return float(f"{abs(float(c)):.{digits}g}") == abs(float(x)) and math.copysign(1, float(x)) == math.copysign(
        1, float(c))


def exact_constants(target, quantity="Phi"):
    """The exact constants of the graded rows: numbers, and the numeric parts of sums and products (3π/4 in
    φ2 − 3π/4 − 100t, √5/2 in a coefficient), with their negatives — value → sympy number, built once per
    target. For ν and γ, also those of the rows' time derivatives (a driver's 5√3 in ν = 5√3 cos 10t)."""
    key = ("exact_constants", quantity_of(quantity).right_hand_side)
    if key in target.store:
        return target.store[key]
    import sympy as sp  # import time: sympy only when needed

    t = target.mech.t
    symbols = set(target.mech.q) | set(target.mech.qd) | {t}
    rows = list(target.symbolic_phi())
    if quantity_of(quantity).right_hand_side:  # what a driver's f(t) puts in ν and γ
        rows += [sp.diff(row, t, k) for row in list(rows) if t in row.free_symbols for k in (1, 2)]
    found = {}
    nodes = set()
    for row in rows:
        nodes |= row.atoms(sp.Number, sp.Add, sp.Mul)  # each distinct sub-expression once

    def offer(key, c):  # of two forms of one value, the same one in every process (a set's order follows the seed)
        if key not in found or _form(c) < _form(found[key]):
            found[key] = c

    for node in nodes:
        if node.is_Number:
            parts = [node]
        else:  # the numeric part of a sum or a product: 3π/4 of φ2 − 3π/4 − 100t, √5/2 of (√5/2)·cos φ
            numeric = [a for a in node.args if not (a.free_symbols & symbols)]
            parts = [node.func(*numeric)] if numeric else []
        for c in parts:
            if c.is_Integer:
                offer(("integer", int(abs(c))), c)
            if not c.is_number or c.is_Integer or c == 0:
                continue
            try:
                value = float(c)
            except (TypeError, ValueError):
                continue
            if math.isfinite(value):
                offer(value, c)
                offer(-value, -c)
    found = dict(sorted(found.items(), key=lambda kv: (isinstance(kv[0], tuple), kv[0])))
    if not quantity_of(quantity).right_hand_side:
        _turned_constants(target, rows, symbols, found)
    target.store[key] = found
    return found


def _form(c):
    """Which of two forms of one value stands for it: the exercise's own decimal first (a datum as written), then
    the shorter, then by text."""
    text = str(c)
    return not c.is_Float, len(text), text


def _turned_constants(target, rows, symbols, found):
    """The constant of a row that measures an angle turned by whole turns (−3π/4 + 2π = 5π/4 for φ2 − 3π/4 − 100t,
    2π for φ3 − φ4): the row turned is the same placement (``Target.turns``), so its constant is the exercise's too."""
    import sympy as sp  # import time: sympy only when needed

    for k in getattr(target, "turns", {}):
        c0 = rows[k].subs({s: 0 for s in symbols})
        if not c0.is_number:
            continue
        for n in (1, -1, 2, -2):
            c = c0 + 2 * n * sp.pi  # exact: c0 is the row's exact constant (0 + 2nπ is 2nπ already)
            value = float(c)
            found.setdefault(value, c)
            found.setdefault(-value, -c)


_LITERAL = re.compile(r"(?<![\w.])(\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?(?![\w.])")


def typed_digits(raw):
    """Significant digits of every decimal literal in the texts of a raw answer, by value: ``"2.35620"`` → {2.3562:
    6} (trailing zeros after the point count, as written)."""
    out = {}
    texts = [raw] if isinstance(raw, str) else list(_texts(raw))
    for text in texts:
        for m in _LITERAL.finditer(text[:20_000]):
            literal = m.group(0)
            digits = literal.lower().split("e")[0]
            if "." in digits:
                count = len(digits.replace(".", "").lstrip("0"))
            else:
                count = len(digits.strip("0"))
            try:
                value = float(literal)
            except ValueError:  # pragma: no cover - the pattern is a number
                continue
            out[value] = max(out.get(value, 0), count)
    return out


def _texts(raw, depth=0):
    if isinstance(raw, str):
        yield raw
    elif isinstance(raw, (list, tuple)) and depth < 3:
        for x in raw[:10_000]:
            yield from _texts(x, depth + 1)


def distinct_leaves(exprs, keep):
    """The distinct sub-expressions of ``exprs`` (sympy) for which ``keep(e)`` holds, walking each distinct
    sub-expression once: a derived γ is a graph of a few hundred nodes that written out as a tree has 10⁵."""
    seen, found, stack = set(), set(), list(exprs)
    while stack:
        e = stack.pop()
        if e in seen:
            continue
        seen.add(e)
        if keep(e):
            found.add(e)
        stack.extend(e.args)
    return found


def _data_numbers(target):
    """The numbers written in the graded rows themselves (their decimals and integers), built once per target."""
    if "data_numbers" not in target.store:
        import sympy as sp  # import time: sympy only when needed

        target.store["data_numbers"] = set().union(*(row.atoms(sp.Number) for row in target.symbolic_phi()))
    return target.store["data_numbers"]


def exact(answer, target, quantity="Phi", raw=None):
    """A symbolic answer with each decimal that is a correct rounding of an exact constant replaced by that
    constant; and the near misses ``[(decimal, constant)]`` (decimals near a constant that are no rounding of it).
    The digits of a decimal are those typed when ``raw`` (the answer as given) holds it as text, else those of its
    shortest form. Other answers are returned as they are."""
    if answer.kind != "symbolic":
        return answer, []
    import sympy as sp  # import time: sympy only when needed

    typed = typed_digits(raw) if raw is not None else {}
    numbers = [x for x in distinct_leaves(answer.matrix, lambda e: e.is_Number) if x.is_Float or (x.is_Integer and abs(x) >= 100)]
    if numbers:  # decimals that are the exercise's own data, as written: nothing to judge (kinbook's own rows)
        data = _data_numbers(target)
        numbers = [x for x in numbers if x not in data]
    if not numbers:
        return answer, []
    constants = exact_constants(target, quantity)
    swap, near = {}, []
    for f in sorted(numbers, key=_order):
        x = float(f)
        if x == 0 or (f.is_Integer and ("integer", int(abs(f))) in constants):
            continue  # an integer of the exercise's own
        if x in constants and isinstance(constants[x], sp.Float):
            continue  # the exercise's own datum, as written
        digits = typed.get(abs(x), significant_digits(x))
        best = None
        for value, c in constants.items():
            if isinstance(value, tuple):  # an integer of the exercise (pᵀp − 1): a decimal near it is no rounding
                n = value[1]
                if n and not f.is_Integer and abs(abs(x) - n) <= NEAR * n and abs(x) != n:
                    if best is None or abs(abs(x) - n) < abs(abs(best[0]) - abs(x)):
                        best = (math.copysign(n, x), sp.Integer(n if x > 0 else -n))
                continue
            if value == x:
                continue
            rounded = is_rounding(x, value, digits)
            if rounded and digits >= MIN_DIGITS:
                swap[f] = c
                best = None
                break
            if not rounded and abs(value - x) > NEAR * abs(value):
                continue  # far from this constant: another number
            if best is None or abs(value - x) < abs(best[0] - x):
                best = (value, c)  # near it, or a rounding with too few digits
        if f not in swap and best is not None:
            near.append((f, best[1]))
    if swap:
        answer = Answer("symbolic", matrix=answer.matrix.xreplace(swap))
    return answer, near


def _order(x):
    """The order numbers are judged in — by value, then by form (100 before 100.0) —, the same in every process (a
    set's order follows the hash seed)."""
    return float(x), not x.is_Integer, str(x)


def graded(result, answer, target, quantity, raw, recheck):
    """The verdict under the rounding rule: a failed ``result`` of a symbolic answer with decimals is checked
    again (``recheck(matrix)``) with the exercise's constants in place of their correct roundings, and its near
    misses are named (:func:`named`). A right answer costs nothing here: only a failed one is looked at again."""
    if result.passed or answer.kind != "symbolic":
        return result
    exact_answer, near = exact(answer, target, quantity, raw)
    if exact_answer is not answer:
        result = recheck(exact_answer.matrix)
        if result.passed:
            return result
    result = named(result, near, lambda swap: recheck(exact_answer.matrix.xreplace(swap)))
    if "degrees" in result.mistakes or "not_rounded" in result.mistakes:
        return result
    return in_degrees(result, exact_answer, target, quantity, raw, recheck)


def in_degrees(result, answer, target, quantity, raw, recheck):
    """A failed ``result`` named ``degrees`` when decimals of the answer are exact constants of the exercise
    converted to degrees and rounded (to at least :data:`MIN_DIGITS` significant digits, as typed), or within
    :data:`NEAR` of them: 28.65 for 0.5 rad, 5730 (or 5731) for a rate of 100 rad/s, 30.00 for π/6. The answer is checked again with each such decimal replaced
    by the exact value in degrees (c·180/π); the name is the one the catalogue then gives (a constant, a rate, the
    whole function in degrees), with the decimals named beside it. Otherwise ``result`` as it is."""
    import sympy as sp  # import time: sympy only when needed
    if result.passed or answer.kind != "symbolic":
        return result

    typed = typed_digits(raw) if raw is not None else {}
    numbers = sorted((x for x in distinct_leaves(answer.matrix, lambda e: e.is_Number)
                      if x.is_Float or (x.is_Integer and abs(x) >= 100)), key=_order)
    if not numbers:
        return result
    constants = [(float(c), c) for c in _angles_and_rates(target, quantity)]
    swap, notes = {}, []
    for f in numbers:
        x = float(f)
        digits = typed.get(abs(x), significant_digits(x))
        if x == 0 or digits < MIN_DIGITS:
            continue
        for value, c in constants:
            deg = math.degrees(value)
            if is_rounding(x, deg, digits) or abs(x - deg) <= NEAR * abs(deg):
                swap[f] = c * 180 / sp.pi
                notes.append(Msg("d.degrees_value", got=repr(abs(x)) if f.is_Float else str(abs(int(f))),
                                 expected=_text(abs(c))))
                break
    if not swap:
        return result
    try:
        again = recheck(answer.matrix.xreplace(swap))
    except Exception:  # noqa: BLE001 — a repaired answer the checker cannot read: nothing to name
        return result
    if again.passed or "degrees" not in again.mistakes:
        return result
    shown = list(again.notes)
    return CheckResult(False, again.score, shown[:1] + notes + shown[1:], again.mistakes, again.rows, again.quantity_msg,
                       again.columns)


def _angles_and_rates(target, quantity):
    """The exercise's constants a student may convert to degrees: its exact constants and integers, positive and
    negative (3π/4, 0.5, 100)."""
    import sympy as sp  # import time: sympy only when needed

    out = []
    for value, c in exact_constants(target, quantity).items():
        if isinstance(value, tuple):
            if value[1]:
                out += [sp.Integer(value[1]), -sp.Integer(value[1])]
        else:
            out.append(c)
    return out


def named(result, near, recheck):
    """A failed ``result`` named ``not_rounded`` when the answer passes with the near-miss decimals replaced by the
    constants they are close to (``recheck(swap)`` runs the check again); else ``result`` as it is."""
    if result.passed or not near:
        return result

    swap = dict(near)
    try:
        again = recheck(swap)
    except Exception:  # noqa: BLE001 — a repaired answer the checker cannot read: nothing to name
        return result
    if not again.passed:
        return result
    notes = [Msg("d.not_rounded", value=repr(abs(float(f))), exact=_text(c if float(c) > 0 else -c),
                 digits=significant_digits(f)) for f, c in near]
    return CheckResult(False, result.score, notes + hints(["not_rounded"], {}), ["not_rounded"], result.rows,
                       result.quantity_msg, result.columns)


def _text(c):
    """An exact constant as a student types it: 3*pi/4, sqrt(3)/2, 1.5 (a datum as the exercise gives it)."""
    if c.is_Float:
        return repr(float(c))
    return str(c)
