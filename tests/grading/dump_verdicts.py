"""Dump every verdict of the grading corpora to a text file, to compare two versions of the checkers byte for byte.

    .venv/bin/python -m tests.grading.dump_verdicts out.txt [--quick]

What is run: every case of tests/grading/corpus*.py (as tests/grading/test_corpus.py runs them), every try-it and
exercise part of tests/grading/tryits.py (its right answer and its typed wrong ones), the wrong answers
tests/grading/generated.py makes for every exercise part and try-it, and, for every registered try-it of the
chapter notebooks (kinbook.book.tryits), its worked answer, its wrong forms and its first drawn variant. Each
exercise part is also run through ``Part.run`` (the classroom's path) with its generated wrong answers.

For each: passed, score, mistake codes, then ``repr`` and ``_repr_html_`` of the result in English and in
Spanish (an exception: its type and message). A refactoring that keeps behaviour leaves the file unchanged;
a change of rule shows as a diff naming the cases whose verdict or text moved.
"""

from __future__ import annotations

import sys
import traceback


def _render(result):
    from kinbook import grading

    out = []
    if not hasattr(result, "_repr_html_"):
        return [f"  value: {result!r}"]
    out.append(f"  passed={result.passed!r} score={result.score!r} mistakes={getattr(result, 'mistakes', None)!r}")
    for lang in ("en", "es"):
        grading.set_language(lang)
        try:
            out.append(f"  [{lang}] repr:")
            out += ["    " + line for line in repr(result).splitlines()]
            out.append(f"  [{lang}] html: {result._repr_html_()}")
        finally:
            grading.set_language("en")
    return out


def _run(lines, label, call):
    lines.append(f"## {label}")
    try:
        result = call()
    except Exception as exc:  # noqa: BLE001 — recorded: a crash is a verdict to compare too
        lines.append(f"  raised {type(exc).__name__}: {str(exc)[:400]}")
        return
    lines += _render(result)


def corpus_cases(lines):
    from kinbook import grading

    from . import corpus, corpus2, corpus3, corpus4

    checks = {"phi": grading.check_phi, "jacobian": grading.check_jacobian, "nu": grading.check_nu,
              "gamma": grading.check_gamma}
    cases = ([(c, corpus.target) for c in corpus.CASES] + [(c, corpus2.target) for c in corpus2.cases()]
             + [(c, corpus3.target) for c in corpus3.cases() + corpus3.long_cases() + corpus3.spatial_gap_cases()
                + corpus3.driver_gap_cases()]
             + [(c, corpus4.target) for c in corpus4.cases()])
    for case, target in cases:
        _run(lines, f"corpus {case.id}", lambda c=case, t=target: checks[c.check](
            c.answer, t(c.mech, c.constraint), **c.options))


def new_corpora(lines):
    """The corpora grown for issue 30's rules (absent from a dump of an older version: additions, not changes)."""
    from . import corpus_rounding

    checks = {"phi": "check_phi", "nu": "check_nu", "gamma": "check_gamma", "jacobian": "check_jacobian"}
    from kinbook import grading

    for case in corpus_rounding.cases():
        _run(lines, f"rounding {case.id}", lambda c=case: getattr(grading, checks[c.check])(
            c.answer(), corpus_rounding.target(c)))
    from . import corpus_domain

    for case in corpus_domain.cases():  # far zeros, the whole domain, functions, names, phi=
        _run(lines, f"domain {case.id}", lambda c=case: getattr(grading, checks[c.check])(
            c.answer, corpus_domain.target(c), **c.options))


def tryit_cases(lines):
    from .tryits import all_tryits

    for t in all_tryits():
        _run(lines, f"tryit {t.id} right", lambda t=t: t.check(t.right))
        for k, (answer, code) in enumerate(t.wrong):
            _run(lines, f"tryit {t.id} wrong {k} ({code})", lambda t=t, a=answer: t.check(a))


def generated_cases(lines):
    from .generated import exercise_parts, tryit_parts, wrong_answers
    from .tryits import all_tryits

    for part in exercise_parts() + tryit_parts(all_tryits()):
        for k, (answer, code) in enumerate(wrong_answers(part)):
            _run(lines, f"generated {part.id} {k} ({code})",
                 lambda p=part, a=answer: p.checker(a, p.target, **p.options))


def registry_cases(lines):
    from kinbook.book import tryits

    tryits._load()
    for id_, item in tryits.TRY_ITS.items():
        _run(lines, f"registry {id_} worked", lambda item=item: item.check(item.reference_answer()))
        _run(lines, f"registry {id_} blank", lambda id_=id_: tryits.try_it(id_, ...))
        if item.wrong_forms is not None:
            for k, (rows, code, _, _) in enumerate(item.wrong_forms(**item.data)):
                _run(lines, f"registry {id_} wrong form {k} ({code})", lambda item=item, r=rows: item.check(list(r)))
        if item.lookalikes is not None:
            for k, (value, _) in enumerate(item.lookalikes(**item.data)):
                if hasattr(value, "shape") or isinstance(value, (list, tuple, float, int)):
                    _run(lines, f"registry {id_} lookalike {k}", lambda item=item, v=value: item.check(v))
        if item.ranges:
            try:
                v = tryits.another(id_, 1)
            except Exception as exc:  # noqa: BLE001
                lines.append(f"## registry {id_} variant 1\n  raised {type(exc).__name__}: {str(exc)[:300]}")
                continue
            lines.append(f"## registry {id_} variant 1 data {sorted((k, repr(x)) for k, x in v.data.items())}")
            _run(lines, f"registry {id_} variant 1 worked",
                 lambda item=item, d=v.data: item.check(item.reference_answer(d), d))
            _run(lines, f"registry {id_} variant 1 notebook's answer",
                 lambda item=item, d=v.data: item.check(item.reference_answer(), d))
            tryits.another(id_, 0)


def part_run_cases(lines):
    """The classroom's path: Part.run of every exercise part, with its generated wrong answers."""
    from pathlib import Path

    from kinbook.classroom.variant import references

    from .generated import Part, wrong_answers

    exercises = Path(__file__).resolve().parents[2] / "exercises"
    for path in sorted(exercises.glob("ex*.ipynb")):
        for p in references(path):
            target = p.target if p.target is not None else p.expected
            probe = Part(p.name, p.check, target, {k: v for k, v in p.options.items() if k != "phi"})
            for k, (answer, _) in enumerate(wrong_answers(probe)[:4]):
                _run(lines, f"part.run {path.stem[:4]}/{p.name} {k}", lambda p=p, a=answer: p.run(a, {}))


SECTIONS = [corpus_cases, tryit_cases, registry_cases, part_run_cases, generated_cases, new_corpora]


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    out = argv[0] if argv else "verdicts.txt"
    quick = "--quick" in argv
    lines = []
    for section in SECTIONS[:3] if quick else SECTIONS:
        lines.append(f"# ===== {section.__name__}")
        try:
            section(lines)
        except Exception:  # noqa: BLE001 — a section that cannot be built is reported, the others still run
            lines.append("  section failed:\n" + traceback.format_exc())
    with open(out, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print(f"{sum(line.startswith('## ') for line in lines)} verdicts written to {out}")


if __name__ == "__main__":
    main()
