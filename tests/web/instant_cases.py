"""Every answer of kinbook's checker corpora, checked by Python, with what the page needs to check it too
(issue 35: one rule, two engines), and every answer of the try-its' mutation run. Run by tests/web/test_instant.py with the lab environment's Python (kinbook
and its test corpora are there, not in .venv-web):

    .venv/bin/python tests/web/instant_cases.py OUT.jsonl

One JSON line per answer: {"id", "source", "spec" (a key into the specs), "text" (the answer as typed in the page,
or null for an answer that is not text: a Python function, or a sympy object too large to type), "python": {"passed", "mistakes"}}; then one line
{"specs": {key: spec}, "grammar": …}.
"""

from __future__ import annotations

import itertools
import json
import math
import sys
from pathlib import Path

import numpy as np
import sympy as sp

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from kinbook import grading  # noqa: E402
from kinbook.book import instant  # noqa: E402
from kinbook.grading.read import tree_size  # noqa: E402

TYPED = 5000
"""Nodes of a sympy answer written out as a tree above which it is not an answer anyone types in a page (sympy's
own derivation of a spatial γ has some 10⁵): such an answer counts with the functions, as not text."""

CHECKS = {"phi": grading.check_phi, "jacobian": grading.check_jacobian, "nu": grading.check_nu,
          "gamma": grading.check_gamma}


def as_text(answer):
    """The answer as a student types it in the page (a list of rows, each a text or a list of texts; numbers as
    Python prints them), or None when it is not text (a function)."""
    def entry(x):
        if isinstance(x, str):
            return x
        if isinstance(x, (bool, np.bool_)):
            raise TypeError
        if isinstance(x, (int, float, np.integer, np.floating)):
            return repr(float(x)) if math.isfinite(float(x)) else "1/0"
        if isinstance(x, sp.Basic):  # a sympy expression: as sympy prints it (** for powers) …
            if tree_size(x) > TYPED:  # … unless sympy built more than anyone types (a derived spatial γ)
                raise TypeError
            return str(x)
        raise TypeError

    def walk(x):
        if hasattr(x, "tolist") and not isinstance(x, str):
            x = x.tolist()
        if isinstance(x, (list, tuple)):
            return [walk(v) for v in x]
        return entry(x)

    try:
        if callable(answer) and not hasattr(answer, "tolist"):
            return None
        value = walk(answer)
    except TypeError:
        return None
    return value if isinstance(value, str) else json.dumps(value, ensure_ascii=False)


class Specs:
    def __init__(self):
        self.by_key, self.keys = {}, {}

    def key(self, ident, make, *args):
        if ident not in self.keys:
            k = f"s{len(self.by_key)}"
            self.by_key[k] = make(*args)
            self.keys[ident] = k
        return self.keys[ident]


def corpus_cases(specs):
    sys.path.insert(0, str(ROOT))
    from tests.grading import corpus, corpus2, corpus3, corpus4

    groups = [("corpus", corpus.CASES, corpus.target), ("corpus2", corpus2.cases(), corpus2.target),
              ("corpus3", corpus3.cases() + corpus3.long_cases() + corpus3.spatial_gap_cases()
               + corpus3.driver_gap_cases(), corpus3.target), ("corpus4", corpus4.cases(), corpus4.target)]
    for source, cases, target_of in groups:
        for case in cases:
            target = target_of(case.mech, case.constraint)
            result = CHECKS[case.check](case.answer, target, **case.options)
            options = {k: v for k, v in case.options.items() if k != "phi"} | (
                {"phi": True} if "phi" in case.options else {})
            ident = (source, case.mech, case.constraint, case.check, json.dumps(options, sort_keys=True, default=str))
            key = specs.key(ident, instant.spec, CHECKS[case.check], target, options)
            yield {"id": case.id, "source": source, "spec": key, "text": as_text(case.answer),
                   "python": {"passed": bool(result.passed), "mistakes": list(result.mistakes)}}


def edge_cases(specs):
    """Issue 30's classes: whole turns of an angle row (corpus_turns), rounded constants (corpus_rounding) and
    degrees or rounded turned constants (corpus_edges) — each answer checked by Python and by the page."""
    from tests.grading import corpus_edges, corpus_rounding, corpus_turns

    groups = [("turns", corpus_turns.cases(), corpus_turns.target, lambda c: "phi", lambda c: c.answer, {}),
              ("rounding", corpus_rounding.cases(), corpus_rounding.target, lambda c: c.check, lambda c: c.answer(), {}),
              ("edges", corpus_edges.cases(), corpus_edges.target, lambda c: c.check, lambda c: c.answer, None)]
    for source, cases, target_of, check_of, answer_of, fixed in groups:
        for case in cases:
            target, check, answer = target_of(case), check_of(case), answer_of(case)
            options = case.options if fixed is None else fixed
            result = CHECKS[check](answer, target, **options)
            shown = {k: v for k, v in options.items() if k != "phi"} | ({"phi": True} if "phi" in options else {})
            ident = (source, getattr(case, "mech", getattr(case, "constant", None)), getattr(case, "constraint", None),
                     check, json.dumps(shown, sort_keys=True, default=str))
            key = specs.key(ident, instant.spec, CHECKS[check], target, shown)
            yield {"id": case.id, "source": source, "spec": key, "text": as_text(answer),
                   "python": {"passed": bool(result.passed), "mistakes": list(result.mistakes)}}


def tryit_cases(specs):
    from tests.grading import tryits

    for t in tryits.all_tryits():
        item = getattr(t, "item", None)
        if item is not None:
            key = specs.key(("tryit", t.id), instant.tryit_spec, item)
        else:
            key = specs.key(("tryit", t.id), instant.spec, t.checker, t.target(), t.options)
        answers = [("right", t.right)] + [(f"wrong-{k}", a) for k, (a, _) in enumerate(t.wrong)]
        for label, answer in answers:
            result = t.check(answer)
            yield {"id": f"{t.id}/{label}", "source": "tryits", "spec": key, "text": as_text(answer),
                   "python": {"passed": bool(result.passed), "mistakes": list(result.mistakes)}}


def mutation_cases(specs):
    """The mutation run's answers (kinbook.book.instant.tryit_mutants: each try-it's mutants on the notebook's data,
    checked by the try-it's own check), against the try-it's page spec."""
    from kinbook.book.tryits import TRY_ITS, get

    get("13-1/try-1")
    for id, item in TRY_ITS.items():
        key = specs.key(("tryit", id), instant.tryit_spec, item)
        for k, (m, answer, result) in enumerate(instant.tryit_mutants(item)):
            yield {"id": f"{id}/mutant-{k}", "source": "mutants", "spec": key, "text": as_text(answer),
                   "mutant": m.code, "python": {"passed": bool(result.passed), "mistakes": list(result.mistakes)}}


def rounding_cases(specs):
    """The rounding rule (kinbook.grading.rounding), generated: each symbolic try-it's reference rows (Φ, ν, γ) with
    one exact constant of the exercise at a time written as a decimal — rounded to 2, 3, 4 and 6 significant digits,
    and off by 0.1 % and by 1 % — checked by the try-it's own check and by the page."""
    import sympy as sp

    from kinbook.book.tryits import TRY_ITS, get
    from kinbook.grading import rounding
    from kinbook.grading.mutants import reference_rows
    from kinbook.grading.target import target_for

    get("13-1/try-1")
    for id, item in TRY_ITS.items():
        quantity = item.checker.quantity
        if quantity is None or quantity.name == "Phi_q":
            continue
        key = specs.key(("tryit", id), instant.tryit_spec, item)
        target = item.target(**dict(item.data))
        rows = list(sp.Matrix(reference_rows(target, quantity.name)[0]))
        constants = [c for v, c in rounding.exact_constants(target_for(target), quantity.name).items()
                     if not isinstance(v, tuple) and v > 0 and not c.is_Integer]
        for n, c in enumerate(sorted(constants, key=float)[:4]):
            x = float(c)
            for label, value in [(f"{d} digits", float(f"{x:.{d}g}")) for d in (2, 3, 4, 6)] + [
                    ("off 0.1 %", float(f"{x * 1.001:.6g}")), ("off 1 %", float(f"{x * 1.01:.6g}"))]:
                new = [r.xreplace({c: sp.Float(value), -c: -sp.Float(value)}) for r in rows]
                if new == rows:
                    continue
                answer = [str(r) for r in new]
                result = item.check(answer)
                yield {"id": f"{id}/rounding-{n}-{label}", "source": "rounding", "spec": key, "text": as_text(answer),
                       "python": {"passed": bool(result.passed), "mistakes": list(result.mistakes)}}


def main(out):
    specs = Specs()
    with open(out, "w", encoding="utf-8") as f:
        for k, case in enumerate(itertools.chain(corpus_cases(specs), edge_cases(specs), tryit_cases(specs),
                                                       mutation_cases(specs), rounding_cases(specs))):
            f.write(json.dumps(case, ensure_ascii=False, allow_nan=False) + "\n")
            f.flush()
            if k % 50 == 0:
                print(f"instant_cases: {k} answers checked by Python", file=sys.stderr, flush=True)
        f.write(json.dumps({"specs": specs.by_key, "grammar": instant.grammar()}, ensure_ascii=False, allow_nan=False)
                + "\n")


if __name__ == "__main__":
    main(sys.argv[1])
