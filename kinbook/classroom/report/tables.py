"""The report's tables: queries of the gradebook, each a list of dicts (one per row), shown as HTML or written as CSV.

The item analysis is a query because the checkers' mistakes are rows of the gradebook (``mistakes``: attempt, part,
code, row): :func:`mistakes` counts, per part, the students whose counting attempt made each catalogue mistake.
"""

from __future__ import annotations

import math
import os
import statistics

from ...grading.catalogue import MISTAKES, explain
from ..choice import kind_of_file

__all__ = ["scores", "parts", "mistakes", "reference", "copying", "summary", "missing", "not_notebooks", "several",
           "off_roster", "RARE"]

#: An identical answer set shared by more than this share of the class is its common answer, not a copying signal.
RARE = 0.05


def scores(book, exercise, roster=None):
    """One row per student: final score, status, late days, penalty, overridden parts."""
    return [{"student": f.student, "status": f.status, "score": f.score, "max_score": f.max_score, "raw": f.raw,
             "late_days": f.late_days, "penalty": f.penalty, "attempts": f.attempts,
             "overridden": ", ".join(p for p, _, _, o in f.parts if o)} for f in book.finals(exercise, roster)]


def parts(book, exercise):
    """One row per part: submissions graded, mean, share of full marks; ``nobody`` when none got it right."""
    rows = book.db.execute(
        "SELECT p.part, MIN(p.position), COUNT(*), AVG(p.score), MAX(p.max_score), "
        "SUM(CASE WHEN p.score >= p.max_score AND p.max_score > 0 THEN 1 ELSE 0 END) "
        "FROM parts p JOIN submissions s ON s.exercise = p.exercise AND s.student = p.student "
        "WHERE p.exercise = ? GROUP BY p.part ORDER BY MIN(p.position)", (exercise,)).fetchall()
    out = []
    for part, _, n, mean, mx, full in rows:
        out.append({"part": part, "graded": n, "max_score": mx, "mean": round(mean, 3),
                    "mean_share": round(mean / mx, 3) if mx else 0.0, "full_marks": full,
                    "full_share": round(full / n, 3) if n else 0.0, "nobody": full == 0 and n > 0})
    return out


def mistakes(book, exercise, top=5):
    """Per part, the most common catalogue mistakes of the counting attempts: code, title, students, share of the
    part's graded submissions, and an example (a student, the row, their answer)."""
    graded = dict(book.db.execute("SELECT part, COUNT(*) FROM parts WHERE exercise = ? GROUP BY part", (exercise,)))
    position = dict(book.db.execute("SELECT part, MIN(position) FROM parts WHERE exercise = ? GROUP BY part",
                                    (exercise,)))
    rows = book.db.execute(
        "SELECT m.part, m.code, COUNT(DISTINCT m.student), MIN(m.student) FROM mistakes m JOIN submissions s ON "
        "s.attempt = m.attempt WHERE s.exercise = ? GROUP BY m.part, m.code", (exercise,)).fetchall()
    by_part = {}
    for part, code, n, first in rows:
        by_part.setdefault(part, []).append((n, code, first))
    out = []
    for part in sorted(by_part, key=lambda p: position.get(p, 0)):
        for n, code, first in sorted(by_part[part], key=lambda x: (-x[0], x[1]))[:top]:
            row, answer = book.db.execute(
                "SELECT m.row, p.answer FROM mistakes m JOIN submissions s ON s.attempt = m.attempt JOIN parts p ON "
                "p.exercise = s.exercise AND p.student = s.student AND p.part = m.part WHERE s.exercise = ? AND "
                "m.part = ? AND m.code = ? AND m.student = ? ORDER BY m.rowid LIMIT 1",
                (exercise, part, code, first)).fetchone()
            title = explain(code)[0] if code in MISTAKES else code
            out.append({"part": part, "code": code, "title": title, "students": n,
                        "share": round(n / graded[part], 3) if graded.get(part) else 0.0, "example_student": first,
                        "example_row": row, "example_answer": _whole_lines(answer, 2000)})
    return out


def _whole_lines(text, limit):
    """``text`` cut to at most ``limit`` characters at the end of a line (a matrix keeps whole rows)."""
    if len(text) <= limit:
        return text
    head = text[:limit]
    return (head.rsplit("\n", 1)[0] if "\n" in head else head) + "\n…"


def reference(book, exercise):
    """Students whose answers were computed with kinbook's own reference (part, how)."""
    return [{"student": s, "part": p, "how": r} for s, p, r in book.db.execute(
        "SELECT student, part, reference FROM parts WHERE exercise = ? AND reference != '' ORDER BY student, position",
        (exercise,))]


def copying(book, exercise):
    """Copying signals, saying what is identical and never more: notebooks released for another student (recorded
    by the grader), and a few students (2, up to :data:`RARE` of the class) whose answers to every part are
    identical — listed when at least one of those answers is wrong, or when the exercise's correct answers differ
    from student to student (per-student variants), so that the same correct answer from a class on one version, or
    the same common mistake made by many, is not a signal."""
    out = [{"kind": "released for another student", "students": s, "what": f"the notebook was released for {d}"}
           for s, d in book.db.execute(
               "SELECT g.student, g.detail FROM signals g JOIN submissions s ON s.attempt = g.attempt WHERE "
               "s.exercise = ? AND g.kind = 'released-for' ORDER BY g.student", (exercise,))]
    flagged = {r["students"] for r in out}
    out += [{"kind": "released for another student", "students": s, "what": m}
            for s, m in book.db.execute("SELECT student, message FROM submissions WHERE exercise = ? AND status = "
                                        "'wrong-release' ORDER BY student", (exercise,)) if s not in flagged]
    out += [{"kind": "an id that is not the file's student's", "students": s, "what": d}
            for s, d in book.db.execute(
                "SELECT DISTINCT student, detail FROM signals WHERE exercise = ? AND kind IN ('look-alike', "
                "'names-another') ORDER BY student, detail", (exercise,))]
    answers = {}
    for student, part, answer, score, mx in book.db.execute(
            "SELECT student, part, answer, score, max_score FROM parts WHERE exercise = ? ORDER BY student, position",
            (exercise,)):
        answers.setdefault(student, []).append((part, answer, score, mx))
    groups = {}
    for student, items in answers.items():
        if all(a for _, a, _, _ in items):
            groups.setdefault(tuple((p, a) for p, a, _, _ in items), []).append(student)
    correct = [k for k, v in answers.items() if all(s >= m for _, _, s, m in v)]
    distinct_correct = len({tuple(a for _, a, _, _ in answers[s]) for s in correct})
    variants = len(correct) >= 2 and distinct_correct > len(correct) / 2
    few = max(2, math.ceil(RARE * len(answers)))
    for students in sorted(groups.values()):
        if not 2 <= len(students) <= few:
            continue  # one student, or a set so many share that it is the class's common answer, not a signal
        items = answers[students[0]]
        wrong = [p for p, _, s, m in items if s < m]
        if not wrong and not variants:
            continue
        names = ", ".join(p for p, _, _, _ in items)
        what = f"identical answers to every part ({names})"
        what += f", wrong ones included (part {', '.join(wrong)})" if wrong else ", where each student's version differs"
        out.append({"kind": "identical answers", "students": ", ".join(students), "what": what})
    return out


def missing(book, exercise, roster):
    """Students on the roster with nothing handed in (a PDF or a zip handed in instead is :func:`not_notebooks`)."""
    files = book.files_of(exercise)
    return [f.student for f in book.finals(exercise, roster) if f.status == "missing" and not files.get(f.student)]


def not_notebooks(book, exercise, roster):
    """Students with no notebook graded who handed in something else: the files and what they are."""
    files = book.files_of(exercise)
    out = []
    for f in book.finals(exercise, roster):
        if f.status == "missing" and files.get(f.student):
            names = [os.path.basename(p) for p, *_ in files[f.student]]
            out.append({"student": f.student, "files": ", ".join(names),
                        "what": ", ".join(sorted({kind_of_file(n) for n in names})) + ", not a notebook"})
    return out


def several(book, exercise):
    """Students whose submission held several notebooks: each file, what became of it, and the one that counts."""
    counting = dict(book.db.execute("SELECT student, submission FROM submissions WHERE exercise = ?", (exercise,)))
    out = []
    for student, files in book.files_of(exercise).items():
        last = max(run for *_, run in files)
        notebooks = [(p, o, r) for p, o, r, run in files if p.endswith(".ipynb") and run == last]
        if len(notebooks) < 2:
            continue
        shown = []
        for p, outcome, reason in notebooks:
            what = "counts" if p == counting.get(student) else ("graded" if outcome in ("graded", "skipped")
                                                                 else f"{outcome}: {reason}")
            shown.append(f"{os.path.basename(p)} ({what})")
        out.append({"student": student, "files": "; ".join(shown)})
    return out


def off_roster(book, exercise, roster):
    """Students graded who are not on the roster."""
    if roster is None:
        return []
    return sorted({r.student for r in book.results(exercise=exercise)} - {s.student for s in roster})


def summary(book, exercises, roster=None):
    """One row per exercise: students, handed in, missing, mean and median score, share of full marks."""
    out = []
    for e in exercises:
        finals = book.finals(e, roster)
        handed = [f for f in finals if f.status != "missing"]
        scores = [f.score for f in handed]
        mx = max((f.max_score for f in finals), default=0.0)
        out.append({"exercise": e, "students": len(finals), "handed_in": len(handed),
                    "missing": len(finals) - len(handed), "max_score": mx,
                    "mean": round(statistics.fmean(scores), 3) if scores else 0.0,
                    "median": round(statistics.median(scores), 3) if scores else 0.0,
                    "full_marks": sum(1 for s in scores if mx and s >= mx),
                    "late": sum(1 for f in handed if f.late_days)})
    return out
