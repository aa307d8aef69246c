"""The try-its tested the way a student will break them: every mutant of each try-it's reference
(:mod:`kinbook.grading.mutants`) checked by the try-it's own check, on the notebook's data and on variants drawn as
``kb.another`` draws them (``kinbook validate --mutations --try-its``).

A symbolic try-it (Φ, Φ_q, ν, γ) is mutated in the library's own symbolic reference; a numeric one in the code of
its worked answer (what ``kb.reveal`` shows), run on the same data. A mutant that passes is a **blind spot**: of
the **data** when the mutant's value equals the reference's at those data (the data cannot tell the mistake from
the answer), of the **checker** otherwise.
"""

from __future__ import annotations

import dataclasses
import inspect
from functools import lru_cache

import numpy as np
import sympy as sp

from ...errors import KinbookError
from ...grading import mutant_names as MN
from ...grading import mutants as MU
from ...grading.expected import Expected
from ...grading.item import draw, seed_from
from .code_mutants import code_mutants
from .registry import TRY_ITS, same_data

__all__ = ["MAX_DRAWS", "draw_variant", "variant_data", "function_mutants", "blind_spots", "REFERENCE_DRAWS",
           "item_mutants", "value_slips", "mutation_tally", "mutation_tallies", "answer_of"]

MAX_DRAWS = 25
"""Seeded draws tried for one variant of a try-it before it says none works."""


def draw_variant(item, k):
    """``(data, seed, why not)`` of variant ``k`` (≥ 1) of a try-it, as :func:`another` draws it: the first of
    :data:`MAX_DRAWS` seeded draws that is not the notebook's data, with which the mechanism assembles, and under
    which no slip of the worked answer passes (:func:`blind_spots`: no 45° for a
    sin/cos question, no zero rate under a rate term); ``(None, None, last error)`` when none does."""
    last = None
    for attempt in range(MAX_DRAWS):
        seed = seed_from(f"try-it:{item.id}:{k}:{attempt}")
        data = item.variant(seed)
        if same_data(data, item.data):  # the notebook's own data: not a new variant
            continue
        try:
            item.target(**data)
        except KinbookError as exc:  # the mechanism does not assemble with these data: the next draw
            last = exc
            continue
        if blind_spots(item, data):  # a slip would pass with these data: the next draw
            continue
        return data, seed, None
    return None, None, last


def variant_data(item, k):
    """The data of variant ``k`` of a try-it as ``kb.another(id, k)`` draws them (0: the notebook's), or None."""
    if k == 0 or not item.ranges:
        return dict(item.data) if k == 0 else None
    return draw_variant(item, k)[0]


def _names(item):
    return [p.name for p in inspect.signature(item.solution).parameters.values() if p.kind == p.KEYWORD_ONLY]


def _run(item, data):
    names = _names(item)

    def run(f):
        return f(**item.context(), **{n: data[n] for n in names})

    return run


def answer_of(item, mutant, data):
    """The answer a student making ``mutant``'s mistake hands in for ``data``: the mutated worked answer's value
    (code), or the mutated rows as the strings a student types (symbolic)."""
    v = mutant.value
    if isinstance(v, np.ndarray):
        return v
    if callable(v):
        return _run(item, data)(v)

    M = sp.Matrix(v)
    if M.shape[1] > 1:
        return [[str(M[i, j]) for j in range(M.shape[1])] for i in range(M.shape[0])]
    return [str(M[i, 0]) for i in range(M.shape[0])]


def item_mutants(item, data, datas=None, limit=None):
    """The mutants of a try-it for ``data`` (symbolic: made from the reference at these data; code: from the
    worked answer, told apart from it on ``datas``)."""
    quantity = item.checker.quantity  # Φ, Φ_q, ν or γ for a symbolic checker (kinbook.grading.quantities)
    if quantity is not None:
        return MU.reference_mutants(item.target(**data), quantity, limit)
    runs = [_run(item, d) for d in (datas or [data])]
    return code_mutants(item.solution, runs=runs)


REFERENCE_DRAWS = 6
"""Variants drawn (unfiltered) to tell a code mutant from the worked answer as a function."""


@lru_cache(maxsize=None)
def function_mutants(id):
    """The code mutants of a numeric try-it that differ from its worked answer as functions — on the notebook's data
    or on one of :data:`REFERENCE_DRAWS` raw draws (a symbolic try-it's mutants are made per data: none here)."""
    item = TRY_ITS[id]
    if item.checker.quantity is not None:
        return ()
    datas = [dict(item.data)]
    if item.ranges:
        datas += [draw(item.ranges, item.data, seed_from(f"try-it:{id}:reference:{k}")) for k in range(REFERENCE_DRAWS)]
    runs = [_run(item, d) for d in datas]
    return tuple(code_mutants(item.solution, runs=runs))


def blind_spots(item, data):
    """The mutants of a numeric try-it its own check passes at ``data``: the slips these data cannot tell from the
    worked answer (an empty list for data that tell every one apart)."""
    try:
        ref = np.asarray(item.reference_answer(data), float)
    except Exception:  # noqa: BLE001 — data the worked answer cannot run on are refused elsewhere
        return []
    try:
        usable = item.check(ref, data).passed
    except Exception:  # noqa: BLE001 — a reference the checker refuses (a γ of 1e-31: every rate zero)
        usable = False
    if not usable:
        return [MU.Mutant("wrong_value", "the worked answer itself is not accepted at these data", None)]
    return MN.passing_mutants(function_mutants(item.id), lambda m: answer_of(item, m, data),
                              lambda answer: item.check(answer, data), reference=ref)


def _angles(item):
    return bool(item.options.get("angles"))


def _expected(item, data):
    """The try-it's expected value with its other right answers and catalogued wrong ones (an Expected), or its
    worked answer's value."""
    found = item.target(**data)
    return found if isinstance(found, Expected) else _value_of(item, data)


def value_slips(item, data):
    """The slips of a numeric try-it's value on ``data`` (for a worked answer with few code operators, a
    column_stack): the value mutants of its expected value, without −p for Euler parameters (p's other right
    answer)."""
    return [v for v in MU.value_mutants(_expected(item, data), angles=_angles(item))
            if not (item.checker.name == "euler_parameters" and v.operator == "sign of the whole answer")]


def _value_of(item, data):
    return np.asarray(item.reference_answer(data), float)


def mutation_tally(item, variants=2, limit=None):
    """A :class:`~kinbook.grading.mutants.Tally` of one try-it: its mutants checked on the notebook's data and on
    ``variants`` drawn variants."""
    datas = [d for d in (variant_data(item, k) for k in range(variants + 1)) if d is not None]
    tally = MN.Tally(item.id)
    quantity = item.checker.quantity  # Φ, Φ_q, ν or γ for a symbolic checker (kinbook.grading.quantities)
    shared = None if quantity is not None else item_mutants(item, datas[0], datas)
    for k, data in enumerate(datas):
        where = "the notebook's data" if k == 0 else f"variant {k} ({item.stated(data)})"
        found = list(shared) if shared is not None else item_mutants(item, data, limit=limit)
        if shared is not None and len(shared) < 3:  # a worked answer with few operators: its value's slips too
            found += value_slips(item, data)
        if limit is not None:
            found = MU.sample(found, limit)
        for m in found:
            try:
                answer = answer_of(item, m, data)
            except Exception:  # noqa: BLE001 — a code mutant that fails on these data: not an answer here
                continue
            result = item.check(answer, data)
            outcome, given = MN.classify(result, _readings(item, data, m, answer) if quantity is None else m)
            why = ""
            if outcome == "blind":
                why = "the checker lets it through"
                if quantity is None:
                    try:
                        if np.allclose(np.asarray(answer, float), _value_of(item, data), rtol=1e-3, atol=1e-9):
                            why = "the data cannot tell it apart (the same value)"
                    except (TypeError, ValueError):
                        pass
            strict = MN.strictly_named(result, m)
            # a numeric try-it names its worked answer's code slips — the very mutants counted here: counted apart
            alone = MN.strictly_named(item.check(answer, data, slips=False), m) if quantity is None and strict else strict
            tally.add(m, outcome, given, where, why, strict=strict, catalogue=alone)
    return tally


def _readings(item, data, m, answer):
    """``m`` with the codes of the try-it's catalogued wrong answers its value equals (one wrong number, two readings:
    −e0 at χ = 120° is also χ for χ/2)."""
    X = item.target(**data)
    if not isinstance(X, Expected):
        return m
    try:
        a = np.asarray(answer, float).ravel()
    except (TypeError, ValueError):
        return m
    codes = {code for code, w, *_ in X.variants
             if np.asarray(w).size == a.size and np.allclose(np.asarray(w, float).ravel(), a, rtol=1e-6, atol=1e-9)}
    return dataclasses.replace(m, also=set(m.also) | codes) if codes else m


def mutation_tallies(ids=None, variants=2, limit=None, progress=None):
    """Tallies of the try-its ``ids`` (default: all of them, in notebook order)."""
    from . import ch13, ch14  # noqa: F401  (registering the try-its on first use: ~0.2 s to import)

    out = []
    for id in ids or list(TRY_ITS):
        t = mutation_tally(TRY_ITS[id], variants, limit)
        out.append(t)
        if progress:
            progress(t)
    return out
