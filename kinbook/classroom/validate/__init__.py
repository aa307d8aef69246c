"""``kinbook validate SOURCE``: an exercise is checked through the real grader before students get it.

Like ``nbgrader validate`` and ``otter assign``: the source's own solution — the generic one, and each student's
variant when the exercise has per-student parameters (the roster's students, or a few sample ids) — is written as a
student would hand it in and graded by :func:`kinbook.classroom.grade_submission`, in the sandbox; every part must get
full marks. Then the released notebook, blank as a student gets it, is graded too: it must fail cleanly — no points,
every part ``missing-answer`` (not a crash of the grader, a timeout, a tampered cell or a corrupt notebook), which also
shows that no locked cell gives an answer away.

Then the author's question tests (``part(..., tests=[(answer, code), …])``) are run on the source's data: each wrong
answer must be refused and named by its code, each right one (code ``None``) must pass — and a part whose tests
hold a right answer must be declared in the hidden checks, where no student reads it. ``kinbook validate
--mutations`` adds the generated tests (:mod:`kinbook.classroom.validate.mutations`).
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from ...errors import GradingError
from ..grade import grade_submission
from ..notebook import find_parameters, load_source, student_notebook
from ..release import write_notebook
from ..sandbox import Sandbox
from ..variant import references, student_parameters

__all__ = ["validate", "Check", "SAMPLE_STUDENTS", "question_tests"]

#: Ids whose variants are checked when no roster is given.
SAMPLE_STUDENTS = ("validate-a", "validate-b", "validate-c")


@dataclass
class Check:
    """One notebook graded by ``validate``: what it is, its result, and what is wrong with it ("" when right)."""

    what: str
    score: float
    max_score: float
    problems: list = field(default_factory=list)

    @property
    def ok(self):
        return not self.problems

    def __str__(self):
        head = f"{'ok  ' if self.ok else 'FAIL'} {self.what}: {self.score:g}/{self.max_score:g}"
        return head + "".join(f"\n       {p}" for p in self.problems)


def _solution(result):
    return [f"part {p.part}: {p.score:g}/{p.max_score:g} ({p.status}) {p.message[:300]}"
            for p in result.parts if p.score < p.max_score] or ([result.message] if result.status != "ok" else [])


def _blank(result):
    problems = [f"part {p.part} gets {p.score:g} point(s) from the blank notebook (a locked cell gives the answer?)"
                for p in result.parts if p.score > 0]
    problems += [f"part {p.part}: {p.status} — {p.message[:300]} (a blank notebook must fail cleanly: missing-answer)"
                 for p in result.parts if p.status not in ("missing-answer", "ok")]
    return problems


def question_tests(p, where="the source's data"):
    """The outcomes of a part's own question tests (``part(..., tests=[...])``): a list of (ok, text)."""
    out = []
    for k, (answer, expect) in enumerate(p.tests):
        result = p.run(answer)
        if expect is None:
            ok = result.passed
            text = f"test {k + 1} (a right answer) {'passes' if ok else 'is refused: ' + ', '.join(result.mistakes)}"
        else:
            ok = not result.passed and expect in (result.mistakes or ())
            got = "passes" if result.passed else "is named " + (", ".join(result.mistakes) or "—")
            text = f"test {k + 1} (must be named {expect}) {got}"
        out.append((ok, f"part {p.name} at {where}: {text}"))
    return out


def _question_tests(src):
    """A Check of the parts' own question tests on the source's data (None when no part declares any)."""
    parts = [p for p in references(src) if p.tests]
    if not parts:
        return None
    problems, n = [], 0
    for p in parts:
        results = question_tests(p)
        n += len(results)
        problems += [text for ok, text in results if not ok]
        if not p.hidden and any(code is None for _, code in p.tests):
            problems.append(f"part {p.name}: a right answer among its tests is shown to students — declare the "
                            f"part with its tests between ### BEGIN HIDDEN CHECKS and ### END HIDDEN CHECKS")
    return Check(f"the question tests ({n})", n - len([x for x in problems if " test " in x]), n, problems)


def validate(source, *, students=None, timeout=60.0, memory=1000, isolation=True, progress=None):
    """Grade the source's solutions and its blank release (see the module docstring).

    Parameters
    ----------
    students : list of str, optional
        Whose variants to check (default: :data:`SAMPLE_STUDENTS` when the exercise has parameters).
    progress : callable, optional
        Called with each :class:`Check` as it is done.

    Returns
    -------
    list of Check

    Raises
    ------
    GradingError
        When any check fails (after all were run), listing them.
    """
    src = load_source(source)
    references(src)  # an exercise whose own code fails stops here, with the cell named
    has_params = find_parameters(src.nb) is not None
    who = list(students) if students else (list(SAMPLE_STUDENTS) if has_params else [])
    checks = []
    with tempfile.TemporaryDirectory(prefix="kinbook-validate-") as tmp, Sandbox(isolation) as sb:
        def run(nb, student, what, judge, generic=False):
            path = write_notebook(nb, Path(tmp) / (student or "solution") / f"{src.exercise}.ipynb")
            r = grade_submission(src, path, student=student or "solution", timeout=timeout, memory=memory,
                                 generic=generic, reveal_hidden=True, sandbox=sb)
            c = Check(what, r.score, r.max_score, judge(r))
            checks.append(c)
            if progress:
                progress(c)

        run(student_notebook(src, None, None, keep_solutions=True), None, "the solution (generic release)",
            _solution, generic=True)
        for s in who:
            values = student_parameters(src, s)
            run(student_notebook(src, values, s, keep_solutions=True), s, f"the solution of {s}'s variant", _solution)
        run(student_notebook(src), None, "the released notebook, blank", _blank, generic=True)
        if has_params and who:
            run(student_notebook(src, student_parameters(src, who[0]), who[0]), who[0],
                f"{who[0]}'s variant, blank", _blank)
    c = _question_tests(src)
    if c is not None:
        checks.append(c)
        if progress:
            progress(c)
    bad = [c for c in checks if not c.ok]
    if bad:
        raise GradingError(f"{src.exercise} is not valid: " + "; ".join(f"{c.what}: {c.problems[0]}" for c in bad))
    return checks
