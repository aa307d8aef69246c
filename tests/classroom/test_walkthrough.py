"""The term walkthrough of docs/instructors.md, run command by command (issue 21, "Done when"; issue 20 item 1).

A Canvas course of 40 students takes two exercises: ex01 (the same for everyone) and ex11 (one variant per student).
The class holds correct, wrong (planted catalogue mistakes), missing, late, resubmitted, overridden and copied
submissions, handed in through Canvas's bulk download (its file names, `late` marks, `-1` resubmissions, macOS's
`__MACOSX` entries and a `.DS_Store`), plus a file from a student who is not on the roster. Every command of the
walkthrough's ```sh blocks is run as written, in a course directory, in order — `kinbook` through the console
script's `main` (with `--no-isolation` added to `grade` and `validate`, so that the test also runs where bubblewrap
cannot, and a timeout no finishing notebook reaches on a loaded machine), `python3 -m zipfile` as a process — and a
command of any other kind fails the test.

Then: every student who handed something in is graded and every file is listed in collection.csv; the Canvas and
Moodle files are checked cell by cell against scores computed here, independently of the course layer (each
planted answer run in this process and checked with the exercise's own parts); the report's mistake table against
the mistakes planted; the override survives the walkthrough's `--force` regrade.
"""

import csv
import glob
import json
import os
import re
import shlex
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from kinbook.classroom.answers import mistake_rows
from kinbook.classroom.notebook import load_source, student_notebook
from kinbook.classroom.serialize import decode, dumps
from kinbook.classroom.variant import references, student_parameters
from kinbook.cli import main

from .conftest import ENOUGH

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "instructors.md"
EX01, EX11 = "ex01-revolute-joint-phi", "ex11-rotations-euler-parameters"
N = 40
IDS = [f"s{k:02d}" for k in range(1, N + 1)]
CANVAS_ID = {s: str(1000 + k) for k, s in enumerate(IDS, start=1)}
HEADERS = {EX01: "Exercise 1 (40101)", EX11: "Exercise 11 (40111)"}

# what each student hands in (everyone else: the correct solution, on time, once)
WRONG_OA = ["s05", "s06", "s07", "s08", "s09", "s10"]   # ex01: the sign of A2 s'^P in revolute joint 1
COPIED_01 = ["s14", "s15"]                              # ex01: the same wrong local coordinate in joint 4
WRONG_A = ["s05", "s06", "s07", "s08"]                  # ex11: A transposed
COPIER, COPIED = "s16", "s17"                           # ex11: s16's answers computed with s17's angles
MISSING = {EX01: ["s38", "s39", "s40"], EX11: ["s39", "s40"]}
LATE = {EX01: ["s11", "s12"], EX11: ["s20"]}            # Canvas's `late` mark; s12 has an extension
RESUBMITTED = {EX01: "s13", EX11: "s21"}                # a wrong first file, then a right one Canvas named '-1'
OVERRIDE = ("s05", EX01, "revolute_OA", 3.0)
STRANGER = "9999"                                       # a Canvas user who is not in the roster export


def edit_cell(nb, old, new):
    hits = [c for c in nb.cells if c.cell_type == "code" and old in c.source]
    assert len(hits) == 1, old
    hits[0].source = hits[0].source.replace(old, new)
    return nb


def plant(exercise, student, source, values, wrong=False):
    """The solved notebook ``student`` hands in, with the planted mistakes."""
    nb = student_notebook(source, values, student if values else None, keep_solutions=True)
    if exercise == EX01:
        if wrong or student in WRONG_OA:
            edit_cell(nb, "- A2 * sp.Matrix([-1, 0])", "+ A2 * sp.Matrix([-1, 0])")
        if student in COPIED_01:
            edit_cell(nb, "A4 * sp.Matrix([-1.5, 0])", "A4 * sp.Matrix([1.5, 0])")
    else:
        if wrong or student in WRONG_A:
            edit_cell(nb, "A = Rz(psi) @ Rx(theta) @ Rz(phi)", "A = (Rz(psi) @ Rx(theta) @ Rz(phi)).T")
        if student == COPIER:
            other = student_parameters(source, COPIED)
            edit_cell(nb, "A = Rz(psi) @ Rx(theta) @ Rz(phi)",
                      f"psi, theta, phi = np.radians([{other['psi']}, {other['theta']}, {other['phi']}])\n"
                      "A = Rz(psi) @ Rx(theta) @ Rz(phi)")
    return nb


def expected_parts(source, values, nb):
    """{part: (score, max, mistakes)} of a notebook, computed here: its code run in this process, its answers through
    the grader's data path (encoded, decoded) and checked with the exercise's own parts."""
    import matplotlib

    matplotlib.use("Agg")
    parts = references(source, values)
    ns = {"__name__": "__main__"}
    for cell in nb.cells:
        if cell.cell_type == "code":
            exec(compile(cell.source, "planted", "exec"), ns)
    answers = {k: decode(v) for k, v in json.loads(dumps(sorted({p.answer for p in parts}), ns))["answers"].items()}
    out = {}
    for p in parts:
        r = p.run(answers[p.answer], answers)
        out[p.name] = (round(max(0.0, min(1.0, float(r.score))) * p.points, 4), p.points,
                       {code for code, _ in mistake_rows(r)})
    return out


def number(x):
    text = f"{round(x, 2):.2f}"
    return text.rstrip("0").rstrip(".")


@pytest.fixture(scope="module")
def term(tmp_path_factory, monkeypatch_module):
    course = tmp_path_factory.mktemp("course")
    monkeypatch_module.setenv("KINBOOK_SANDBOX_ROOT", str(course))  # part() stays quiet in this process
    lines = ["Student,ID,SIS User ID,SIS Login ID,Section," + ",".join(HEADERS.values()),
             "    Points Possible,,,,,11,10", '"Student, Test",99999,,test_student,Section A,,']
    lines += [f'"Last{s}, First{s}",{CANVAS_ID[s]},S{s[1:]}00,{s},Section {"AB"[k % 2]},,'
              for k, s in enumerate(IDS)]
    (course / "canvas-grades.csv").write_text("\n".join(lines) + "\n", encoding="utf-8-sig")
    expected = {}
    for ex in (EX01, EX11):
        source = load_source(ROOT / "exercises" / f"{ex}.ipynb")     # the walkthrough copies it into the course
        full = {p.name: (p.points, p.points, set()) for p in references(source, student_parameters(source, "s01"))}
        cache = {}
        with zipfile.ZipFile(course / f"submissions-{ex[:4]}.zip", "w") as z:
            for k, s in enumerate(IDS):
                if s in MISSING[ex]:
                    continue
                values = student_parameters(source, s)
                late = "late_" if s in LATE[ex] else ""
                stem = f"last{s}first{s}_{late}{CANVAS_ID[s]}_{50000 + k}"
                upload = f"{ex}-{s}" if values else ex
                if RESUBMITTED[ex] == s:
                    z.writestr(f"{stem}_{upload}.ipynb", json.dumps(plant(ex, s, source, values, wrong=True)))
                    z.writestr(f"__MACOSX/._{stem}_{upload}.ipynb", b"\x00\x05\x16\x07 AppleDouble")
                    upload += "-1"
                nb = plant(ex, s, source, values)
                z.writestr(f"{stem}_{upload}.ipynb", json.dumps(nb))
                planted = s in WRONG_OA + COPIED_01 if ex == EX01 else s in WRONG_A + [COPIER]
                if not planted:
                    expected[ex, s] = full
                    continue
                key = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
                if key not in cache:
                    cache[key] = expected_parts(source, values, nb)
                expected[ex, s] = cache[key]
            z.writestr(".DS_Store", b"\x00\x00\x00\x01Bud1")
            values = student_parameters(source, STRANGER)
            stranger = plant(ex, STRANGER if values else None, source, values)
            z.writestr(f"strangerx_{STRANGER}_60000_{ex}.ipynb", json.dumps(stranger))
    out, err = run_walkthrough(course)
    assert main(["report", "-g", str(course / "graded"), "-o", str(course / "report-csv"), "--format", "csv"]) == 0
    return {"course": course, "expected": expected, "out": out, "err": err}


@pytest.fixture(scope="module")
def monkeypatch_module():
    mp = pytest.MonkeyPatch()
    yield mp
    mp.undo()


def walkthrough_commands():
    """The commands of the ```sh blocks of the walkthrough (before '## Reference'), in order."""
    text = DOC.read_text(encoding="utf-8").split("\n## Reference", 1)[0]
    commands = []
    for block in re.findall(r"```sh\n(.*?)```", text, flags=re.S):
        commands += [line.strip() for line in block.splitlines() if line.strip() and not line.startswith("#")]
    return commands


def run_walkthrough(course):
    outs, errs = [], []
    cwd = os.getcwd()
    os.chdir(course)
    try:
        for command in walkthrough_commands():
            argv = shlex.split(command)
            argv = [x for a in argv for x in (sorted(glob.glob(a)) if "*" in a else [a])]
            if argv[0] == "kinbook":
                args = argv[1:] + (["--no-isolation", "--timeout", str(ENOUGH)] if argv[1] in ("grade", "validate")
                                   else [])
                import contextlib
                import io

                o, e = io.StringIO(), io.StringIO()
                with contextlib.redirect_stdout(o), contextlib.redirect_stderr(e):
                    status = main(args)
                outs.append(o.getvalue())
                errs.append(e.getvalue())
                assert status == 0, (command, o.getvalue()[-2000:], e.getvalue()[-2000:])
            elif argv[:3] == ["python3", "-m", "zipfile"]:
                subprocess.run([sys.executable] + argv[1:], check=True)
            else:
                raise AssertionError(f"docs/instructors.md has a command the walkthrough test does not run: {command}")
    finally:
        os.chdir(cwd)
    return "\n".join(outs), "\n".join(errs)


def test_the_walkthrough_runs_every_kind_of_command():
    commands = walkthrough_commands()
    kinds = {c.split()[1] for c in commands if c.startswith("kinbook ")}
    assert kinds >= {"exercises", "validate", "release", "variant", "grade", "due", "extend", "override", "report", "export",
                     "feedback"}


def finals(ex, s, expected):
    """The expected (raw, penalty) of a student: planted part scores, the override, the late rule."""
    parts = expected[ex, s]
    raw = sum(v[0] for v in parts.values())
    if (s, ex) == OVERRIDE[:2]:
        raw += OVERRIDE[3] - parts[OVERRIDE[2]][0]
    mx = sum(v[1] for v in parts.values())
    days = 1 if s in LATE[ex] and s != "s12" else 0
    penalty = {EX01: 0.10, EX11: 0.20}[ex] * mx * days
    return max(0.0, raw - penalty)


def test_every_student_is_graded_and_every_file_listed(term):
    """Issue 20's batch: a Canvas download with resubmissions, macOS's hidden entries and a stranger."""
    import sqlite3

    course = term["course"]
    db = sqlite3.connect(course / "graded" / "gradebook.sqlite")
    for ex, folder in ((EX01, "ex01"), (EX11, "ex11")):
        (run,) = db.execute("SELECT MIN(run) FROM files WHERE exercise = ?", (ex,)).fetchone()
        rows = db.execute("SELECT path, student, outcome FROM files WHERE run = ?", (run,)).fetchall()
        listed = sorted(os.path.relpath(path, f"collected/{folder}") for path, _, _ in rows)
        assert listed == sorted(os.listdir(course / "collected" / folder))      # every entry, one row each
        outcome = {}
        for _, student, what in rows:
            outcome.setdefault(what, set()).add(student)
        handed = {s for s in IDS if s not in MISSING[ex]}
        assert outcome["graded"] == handed | {STRANGER}
        assert outcome["superseded"] == {RESUBMITTED[ex]}
        assert outcome["ignored"] == {""}                                       # __MACOSX/ and .DS_Store
        graded = {s for (s,) in db.execute("SELECT student FROM submissions WHERE exercise = ?", (ex,))}
        assert graded == handed | {STRANGER}
    assert "not on the roster (1): 9999" in term["out"]
    assert re.search(r"\d+ entries found: \d+ gradable, 2 ignored, 1 superseded — \d+ to grade now", term["out"])


def why(course, got, want, student_of):
    """For a failed cell-by-cell comparison: what the gradebook says of the students whose rows differ."""
    students = {student_of(w) for g, w in zip(got, want) if g != w}
    rows = []
    for name in ("totals.csv", "grades.csv"):
        rows += [dict(r) for r in csv.DictReader(open(course / "graded" / name, encoding="utf-8"))
                 if r["student"] in students and (name == "totals.csv" or r["status"] != "ok")]
    return rows


def test_canvas_file_cell_by_cell(term):
    course, expected = term["course"], term["expected"]
    got = list(csv.reader(open(course / "canvas-import.csv", encoding="utf-8")))
    want = [["Student", "ID", "SIS User ID", "SIS Login ID", "Section", HEADERS[EX01], HEADERS[EX11]],
            ["    Points Possible", "", "", "", "", "11", "10"]]
    for k, s in enumerate(IDS):
        want.append([f"Last{s}, First{s}", CANVAS_ID[s], f"S{s[1:]}00", s, f"Section {'AB'[k % 2]}"]
                    + [("0" if s in MISSING[ex] else number(finals(ex, s, expected))) for ex in (EX01, EX11)])
    assert got == want, why(course, got, want, lambda row: row[3])


def test_moodle_file_cell_by_cell(term):
    course, expected = term["course"], term["expected"]
    got = list(csv.reader(open(course / "moodle-import.csv", encoding="utf-8")))
    want = [["First name", "Last name", "ID number", "Institution", "Department", "Email address",
             f"Assignment: {EX01} (Real)", f"Assignment: {EX11} (Real)"]]
    for s in IDS:
        want.append([f"First{s}", f"Last{s}", f"S{s[1:]}00", "", "", ""]
                    + [("0" if s in MISSING[ex] else number(finals(ex, s, expected))) for ex in (EX01, EX11)])
    assert got == want, why(course, got, want, lambda row: row[0].removeprefix("First"))


def test_the_report_shows_the_mistakes_planted(term):
    course, expected = term["course"], term["expected"]
    for ex in (EX01, EX11):
        counts = {}
        for (e, _), parts in expected.items():
            if e == ex:
                for part, (_, _, codes) in parts.items():
                    for code in codes:
                        counts[part, code] = counts.get((part, code), 0) + 1
        rows = list(csv.DictReader(open(course / "report-csv" / f"{ex}-mistakes.csv", encoding="utf-8")))
        by_part = {}
        for part, code in counts:
            by_part.setdefault(part, []).append((-counts[part, code], code))
        want = [(part, code, str(-n)) for part in by_part for n, code in sorted(by_part[part])[:5]]
        assert sorted((r["part"], r["code"], r["students"]) for r in rows) == sorted(want)
    # the mistakes as planted, by hand: who made which, in which part (the sign of a term is a sign error wherever
    # the row is checked; A transposed; s16's answers are right for another student's angles, so plain wrong values)
    planted = {(EX01, "revolute_OA", "sign_flip"): WRONG_OA, (EX01, "revolute_B", "sign_flip"): COPIED_01,
               (EX01, "revolute_B_order", "sign_flip"): COPIED_01,
               (EX01, "whole_phi", "sign_flip"): sorted(WRONG_OA + COPIED_01),
               (EX11, "A", "transposed"): WRONG_A, (EX11, "A", "wrong_value"): [COPIER]}
    for (ex, part, code), students in planted.items():
        rows = {(r["part"], r["code"]): r for r in csv.DictReader(open(course / "report-csv" / f"{ex}-mistakes.csv"))}
        row = rows[part, code]
        assert (int(row["students"]), row["example_student"]) == (len(students), students[0]), (ex, part, code)
        assert row["example_answer"] and row["title"] != code                  # an example, and the mistake's name
    for ex in (EX01, EX11):                                                    # the page shows the same table
        page = (course / "report" / f"{ex}.html").read_text(encoding="utf-8")
        assert "data:image/png;base64," in page
        section = page.split("<h2>Most common mistakes, per part</h2>", 1)[1].split("<h2>", 1)[0]
        shown = [[re.sub(r"<[^>]+>", "", c) for c in re.findall(r"<td[^>]*>(.*?)</td>", tr, flags=re.S)]
                 for tr in re.findall(r"<tr>(.*?)</tr>", section, flags=re.S)[1:]]
        rows = list(csv.DictReader(open(course / "report-csv" / f"{ex}-mistakes.csv", encoding="utf-8")))
        assert [(c[0], c[1], c[3], c[5]) for c in shown] == [(r["part"], r["code"], r["students"],
                                                               r["example_student"]) for r in rows]


def test_copying_signals_say_what_is_identical(term):
    course = term["course"]
    for ex, pair in ((EX01, COPIED_01), (EX11, [COPIER, COPIED])):
        rows = list(csv.DictReader(open(course / "report-csv" / f"{ex}-copying.csv", encoding="utf-8")))
        groups = [r for r in rows if r["kind"] == "identical answers"]
        assert ", ".join(pair) in [g["students"] for g in groups], groups
    (s16,) = [r for r in csv.DictReader(open(course / "report-csv" / f"{EX11}-copying.csv"))
              if r["students"] == f"{COPIER}, {COPIED}"]
    assert s16["what"].startswith("identical answers to every part (A, p, EGt, EtE)")


def test_the_override_survives_the_force_regrade(term):
    course = term["course"]
    assert re.findall(r"graded (\d+) submission", term["out"])[-1] == "1"      # the --force regrade of s05
    assert "overrides kept (the scores above are the grader's; export, report and feedback apply them): s05 " \
           "revolute_OA = 3" in term["out"]                                   # and it says the override stands
    import sqlite3

    db = sqlite3.connect(course / "graded" / "gradebook.sqlite")
    (graded_runs,) = db.execute("SELECT COUNT(*) FROM runs WHERE exercise = ?", (EX01,)).fetchone()
    assert graded_runs == 2                                            # the first grading and the --force one
    assert db.execute("SELECT score, why FROM overrides").fetchall() == [
        (3.0, "sign convention of the sketch accepted")]
    page = (course / "feedback" / OVERRIDE[0] / f"{EX01}.html").read_text(encoding="utf-8")
    assert "your instructor set the score to 3 — sign convention of the sketch accepted" in page


def test_feedback_is_one_folder_per_student(term):
    course = term["course"]
    assert sorted(os.listdir(course / "feedback")) == sorted(IDS + [STRANGER])
    assert sorted(os.listdir(course / "feedback" / "s11")) == [f"{EX01}.html", f"{EX11}.html", "index.html"]
    late = (course / "feedback" / "s11" / f"{EX01}.html").read_text(encoding="utf-8")
    assert "1 day(s) after the due date" in late and "−1.1 point(s)" in late
    again = (course / "feedback" / RESUBMITTED[EX01] / f"{EX01}.html").read_text(encoding="utf-8")
    assert "You handed in 2 files; the latest counts." in again
    missing = (course / "feedback" / "s40" / f"{EX11}.html").read_text(encoding="utf-8")
    assert "nothing was handed in" in missing
    wrong = (course / "feedback" / "s06" / f"{EX01}.html").read_text(encoding="utf-8")
    assert "+ A2 * sp.Matrix([-1, 0])" in wrong                        # the student's own cell, as they wrote it
    assert "<pre>[x1 - x2 - cos(phi2)]\n[y1 - y2 - sin(phi2)]</pre>" in wrong  # their answer, one row a line
    assert "COPIER" not in wrong and "identical" not in (course / "feedback" / COPIER / f"{EX11}.html").read_text()
