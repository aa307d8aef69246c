"""The figures of issue 22's "Done when", over the whole corpus: false accepts, false rejects, crashes, answers
named otherwise than the corpus states, per class; and the share of generated wrong answers that get only the
generic "wrong value".

    .venv/bin/python -m tests.grading.figures            # everything (a few minutes on a quiet machine)
    .venv/bin/python -m tests.grading.figures --corpus   # the typed corpus only

The corpus (tests/grading/corpus.py, corpus2.py, corpus3.py, corpus4.py) states each answer's verdict, derived
apart from kinbook (geometry, sympy by hand, finite differences); tests/grading/test_corpus.py asserts each of
them. The generated wrong answers (tests/grading/generated.py: every graded part of ex01–ex12 and every try-it)
and the typed wrong answers of the try-its (tests/grading/tryits.py) must all fail, at most 1 in 10 with only
"wrong value"; tests/grading/test_tryits.py asserts that.
"""

from __future__ import annotations

import sys
import traceback
from collections import Counter, defaultdict

from kinbook import grading

CHECKS = {"phi": grading.check_phi, "jacobian": grading.check_jacobian, "nu": grading.check_nu,
          "gamma": grading.check_gamma}

CLASSES = (
    ("opt-", "every option and input (issue 22 item 8)"),
    ("mask-", "masking: true only because of another constraint"),
    ("factor-", "factors that vanish (and that do not)"),
    ("redundant-", "redundant rows"),
    ("long-", "long-but-correct γ (and a hostile one)"),
    ("gap-", "the spatial (and driver) catalogue gaps"),
    ("hostile-", "a hostile student: forms, hidden rows, near misses, duplicates"),
    ("", "the rest: every joint type and quantity, the book's forms"),
)


def corpus_cases():
    """[(case, target function)] of the whole typed corpus."""
    from . import corpus, corpus2, corpus3, corpus4

    return ([(c, corpus.target) for c in corpus.CASES] + [(c, corpus2.target) for c in corpus2.cases()]
            + [(c, corpus3.target) for c in corpus3.cases() + corpus3.long_cases() + corpus3.spatial_gap_cases()
               + corpus3.driver_gap_cases()]
            + [(c, corpus4.target) for c in corpus4.cases()])


def class_of(case_id):
    return next(name for prefix, name in CLASSES if case_id.startswith(prefix))


def judge(case, target):
    """("ok" | "false accept" | "false reject" | "crash" | "misnamed", detail)."""
    try:
        r = CHECKS[case.check](case.answer, target(case.mech, case.constraint), **case.options)
    except Exception:  # noqa: BLE001 — counted, and shown
        return "crash", traceback.format_exc(limit=3)
    if r.passed and not case.passed:
        return "false accept", repr(r)
    if not r.passed and case.passed:
        return "false reject", repr(r)
    if r.mistakes != case.mistakes or (case.score is not None and abs(r.score - case.score) > 1e-6):
        return "misnamed", f"got {r.mistakes} score {r.score:.4f}, the corpus says {case.mistakes} {case.score}"
    return "ok", ""


def corpus_figures(out=print):
    cases = corpus_cases()
    per = defaultdict(Counter)
    bad = []
    for case, target in cases:
        verdict, detail = judge(case, target)
        per[class_of(case.id)][verdict] += 1
        per[class_of(case.id)]["right" if case.passed else "wrong"] += 1
        if verdict != "ok":
            bad.append((case.id, verdict, detail))
    total = Counter()
    out(f"typed corpus: {len(cases)} answers")
    out(f"  {'class':<62} {'answers':>7} {'right':>5} {'wrong':>5} {'f.acc':>5} {'f.rej':>5} {'crash':>5} "
        f"{'misnamed':>8}")
    for _, name in CLASSES:
        c = per[name]
        total.update(c)
        n = c["right"] + c["wrong"]
        out(f"  {name:<62} {n:>7} {c['right']:>5} {c['wrong']:>5} {c['false accept']:>5} {c['false reject']:>5} "
            f"{c['crash']:>5} {c['misnamed']:>8}")
    out(f"  {'all':<62} {len(cases):>7} {total['right']:>5} {total['wrong']:>5} {total['false accept']:>5} "
        f"{total['false reject']:>5} {total['crash']:>5} {total['misnamed']:>8}")
    for case_id, verdict, detail in bad:
        out(f"  ! {case_id}: {verdict}: {detail[:400]}")
    return total


def generated_figures(out=print):
    """Every generated wrong answer of every exercise part and try-it, and every typed wrong answer of the
    try-its: accepted, crashed, generic."""
    from .generated import exercise_parts, tryit_parts, wrong_answers
    from .tryits import all_tryits

    tryits = all_tryits()
    figures = {}
    total = generic = accepted = crashed = 0
    generic_where = Counter()
    for p in tryit_parts(tryits) + exercise_parts():
        for answer, _code in wrong_answers(p):
            total += 1
            try:
                r = p.checker(answer, p.target, **p.options)
            except Exception:  # noqa: BLE001
                crashed += 1
                continue
            accepted += r.passed
            if not r.passed and r.mistakes == ["wrong_value"]:
                generic += 1
                generic_where[p.id] += 1
    figures["generated"] = (total, accepted, crashed, generic)
    out(f"generated wrong answers (every exercise part and try-it): {total}, accepted {accepted}, "
        f"crashed {crashed}, only 'wrong value' {generic} ({generic / max(total, 1):.1%}) {dict(generic_where)}")
    total = generic = accepted = crashed = rejected_right = 0
    for t in tryits:
        try:
            rejected_right += not t.check(t.right).passed
        except Exception:  # noqa: BLE001
            crashed += 1
        for answer, _code in t.wrong:
            total += 1
            try:
                r = t.check(answer)
            except Exception:  # noqa: BLE001
                crashed += 1
                continue
            accepted += r.passed
            generic += (not r.passed) and r.mistakes == ["wrong_value"]
    figures["typed"] = (total, accepted, crashed, generic)
    out(f"typed wrong answers of the try-its and exercise parts: {total}, accepted {accepted}, crashed {crashed}, "
        f"only 'wrong value' {generic} ({generic / max(total, 1):.1%}); right answers refused {rejected_right} "
        f"of {len(tryits)}")
    return figures


def main(argv):
    total = corpus_figures()
    bad = total["false accept"] + total["false reject"] + total["crash"] + total["misnamed"]
    if "--corpus" not in argv:
        figures = generated_figures()
        for n, acc, crash, generic in figures.values():
            bad += acc + crash + (generic > n / 10)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
