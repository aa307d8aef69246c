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


# ============================================================================ the LMS as it really is (issue 32)
# A second, smaller Canvas course and a Moodle one, with what real downloads hold: a submission of several files (a
# scratch notebook, a blank re-download, two versions), a PDF, an nbformat-3 notebook, a notebook with 9 MB of saved
# output, a student enrolled after the roster was exported (and a newer roster), an assignment worth other points in
# Canvas, a source edited after grading, a Spanish Moodle worksheet. Every expected value is computed here: full
# marks from the exercise's own parts, the planted wrong answer run through them (expected_parts).
LMS_IDS = {"atorres": 2001, "snavarro": 2002, "jcastro": 2003, "aduo": 2004, "palonso": 2005, "nramos": 2006,
           "jlopez": 2007, "xmiss": 2008}
LATE_ID = ("kmensah", 2099)                 # enrolled after the first roster was exported
EX11_POINTS = 12                            # what Canvas says ex11 is worth (kinbook: 10)
HEADERS_LMS = {EX01: "Ejercicio 1 (40101)", EX11: "Ejercicio 11 (40111)"}


def _roster_lines(students):
    lines = ["Student,ID,SIS User ID,SIS Login ID,Section," + ",".join(HEADERS_LMS.values()),
             f'"    Points Possible",,,,,"11,00","{EX11_POINTS},00"']
    return "\n".join(lines + [f'"{s[1:].capitalize()}, {s[0].upper()}",{uid},S{uid},{s},A,,' for s, uid in students])


def _canvas(student, uid, attachment, filename):
    return f"{student[1:]}{student[0]}_{uid}_{attachment}_{filename}"


def _big_output(nb, megabytes):
    import nbformat

    text = "".join(f"line {k}: a printed line of a runaway loop, saved with the notebook\n" for k in range(20_000))
    cell = nbformat.v4.new_code_cell("for k in range(400000):\n    print(k)")
    cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text=text * (megabytes * 2 ** 20 // len(text) + 1))]
    nb.cells.append(cell)
    return nb


def _v3(nb):
    import nbformat

    return nbformat.convert(nbformat.from_dict(json.loads(json.dumps(nb))), 3)


def _quiet_main(argv):
    import contextlib
    import io

    o, e = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(o), contextlib.redirect_stderr(e):
        status = main(argv)
    return status, o.getvalue(), e.getvalue()


@pytest.fixture(scope="module")
def lms_term(tmp_path_factory, monkeypatch_module):
    course = tmp_path_factory.mktemp("lms")
    monkeypatch_module.setenv("KINBOOK_SANDBOX_ROOT", str(course))
    src01 = load_source(ROOT / "exercises" / f"{EX01}.ipynb")
    src11 = load_source(ROOT / "exercises" / f"{EX11}.ipynb")
    (course / "exercises").mkdir()
    for src in (src01, src11):
        (course / "exercises" / src.path.name).write_bytes(src.data)
    (course / "canvas-week1.csv").write_text(_roster_lines(LMS_IDS.items()) + "\n", encoding="utf-8-sig")
    (course / "canvas-week5.csv").write_text(_roster_lines([*LMS_IDS.items(), LATE_ID]) + "\n", encoding="utf-8-sig")
    solved = plant(EX01, None, src01, None)
    blank = student_notebook(src01, None, None)
    wrong = plant(EX01, None, src01, None, wrong=True)
    ex01 = course / "collected" / "ex01"
    ex01.mkdir(parents=True)
    files = {("atorres", 1, f"{EX01}.ipynb"): solved, ("snavarro", 1, f"{EX01}.ipynb"): solved,
             ("snavarro", 2, "borrador.ipynb"): blank, ("jcastro", 1, f"{EX01}.ipynb"): solved,
             ("jcastro", 2, f"{EX01} (1).ipynb"): blank, ("aduo", 1, f"{EX01}.ipynb"): wrong,
             ("aduo", 2, "Ex01.ipynb"): solved, ("nramos", 1, f"{EX01}.ipynb"): _v3(solved),
             ("jlopez", 1, f"{EX01}.ipynb"): _big_output(plant(EX01, None, src01, None), 9),
             ("kmensah", 1, f"{EX01}.ipynb"): solved}
    for (s, k, name), nb in files.items():
        uid = dict([*LMS_IDS.items(), LATE_ID])[s]
        (ex01 / _canvas(s, uid, 7_000_000 + 10 * uid + k, name)).write_text(json.dumps(nb), encoding="utf-8")
    (ex01 / _canvas("palonso", 2005, 7_020_051, f"{EX01}.pdf")).write_bytes(b"%PDF-1.4 a notebook printed to PDF")
    ex11 = course / "collected" / "ex11"
    ex11.mkdir(parents=True)
    for s, uid in (("atorres", 2001), LATE_ID):
        nb = plant(EX11, s, src11, student_parameters(src11, s))
        (ex11 / _canvas(s, uid, 7_100_000 + uid, f"{EX11}-{s}.ipynb")).write_text(json.dumps(nb), encoding="utf-8")
    # a Moodle course: the grading worksheet in Spanish, a folder per student
    (course / "hoja-de-calificaciones.csv").write_text(
        "Identificador,Nombre completo,Dirección de correo,Estado,Calificación,Calificación máxima\n"
        '"Participante 2387101",Carlos Pérez,carlos.perez@alumnos.uni.es,Enviado,,11\n'
        '"Participante 2387107",Jorge Castro,jorge.castro@alumnos.uni.es,Enviado,,11\n'
        '"Participante 2387108",Beatriz Ortiz,beatriz.ortiz@alumnos.uni.es,Enviado,,11\n', encoding="utf-8")
    moodle = course / "collected-moodle" / "ex01"
    for folder, name, nb in (("Carlos Pérez_2387101", f"{EX01}.ipynb", solved),
                             ("Jorge Castro_2387107", f"{EX01}.ipynb", solved),
                             ("Jorge Castro_2387107", f"{EX01} (1).ipynb", blank)):
        (moodle / f"{folder}_assignsubmission_file_").mkdir(parents=True, exist_ok=True)
        (moodle / f"{folder}_assignsubmission_file_" / name).write_text(json.dumps(nb), encoding="utf-8")
    (moodle / "Beatriz Ortiz_2387108_assignsubmission_file_").mkdir()
    (moodle / "Beatriz Ortiz_2387108_assignsubmission_file_" / "entrega.pdf").write_bytes(b"%PDF-1.4")
    (moodle / "Beatriz Ortiz_2387108_assignsubmission_onlinetext_").mkdir()
    (moodle / "Beatriz Ortiz_2387108_assignsubmission_onlinetext_" / "onlinetext.html").write_text("<p>hecho</p>")

    grading = ["--no-isolation", "--timeout", str(ENOUGH), "--id-pattern", "canvas"]
    runs = {}
    cwd = os.getcwd()
    os.chdir(course)
    try:
        def run(name, argv):
            runs[name] = _quiet_main(argv)
            return runs[name]

        run("grade01", ["grade", f"exercises/{EX01}.ipynb", "collected/ex01/", "-o", "graded/", "--roster",
                        "canvas-week1.csv", *grading])
        run("grade11", ["grade", f"exercises/{EX11}.ipynb", "collected/ex11/", "-o", "graded/", *grading])
        run("feedback1", ["feedback", "-g", "graded/", "--out", "feedback/"])
        run("week5", ["grade", f"exercises/{EX01}.ipynb", "collected/ex01/", "-o", "graded/", "--roster",
                      "canvas-week5.csv", *grading])
        run("report", ["report", "-g", "graded/", "-o", "report/", "--format", "csv"])
        run("feedback", ["feedback", "-g", "graded/", "--out", "feedback/"])
        run("upload", ["feedback", "-g", "graded/", "--out", "upload/", "--lms", "canvas"])
        headers = [x for e, h in HEADERS_LMS.items() for x in ("--header", f"{e}={h}")]
        run("export_stop", ["export", "--format", "canvas", "-g", "graded/", "-o", "stopped.csv", *headers])
        run("export", ["export", "--format", "canvas", "-g", "graded/", "-o", "canvas-import.csv", "--scale",
                       *headers])
        run("moodle", ["grade", f"exercises/{EX01}.ipynb", "collected-moodle/ex01/", "-o", "graded-moodle/",
                       "--roster", "hoja-de-calificaciones.csv", "--no-isolation", "--timeout", str(ENOUGH),
                       "--id-pattern", "moodle"])
        run("moodle_upload", ["feedback", "-g", "graded-moodle/", "--out", "upload-moodle/", "--lms", "moodle"])
        # the instructor edits a visible part's points after grading, then regrades
        edited = (course / "exercises" / f"{EX01}.ipynb")
        edited.write_text(edited.read_text(encoding="utf-8").replace(
            'part(\\"whole_phi\\", points=4', 'part(\\"whole_phi\\", points=5'), encoding="utf-8")
        run("edited", ["grade", f"exercises/{EX01}.ipynb", "collected/ex01/", "-o", "graded/", *grading])
        run("regrade", ["grade", f"exercises/{EX01}.ipynb", "collected/ex01/", "-o", "graded/", "--regrade",
                        *grading])
        # … and a colleague grades the same downloads with the edited source in a gradebook of their own
        run("fresh", ["grade", f"exercises/{EX01}.ipynb", "collected/ex01/", "-o", "graded-fresh/", *grading])
        (course / "released.ipynb").write_bytes(src01.data)
        run("released_from", ["grade", f"exercises/{EX01}.ipynb", "collected/ex01/", "-o", "graded-fresh/",
                              "--released-from", "released.ipynb", *grading])
    finally:
        os.chdir(cwd)
    full01 = sum(p.points for p in references(src01))
    return {"course": course, "runs": runs, "full01": full01, "src01": src01, "src11": src11,
            "wrong_edited": expected_parts(load_source(course / "exercises" / f"{EX01}.ipynb"), None, wrong)}


def _rows(path):
    return list(csv.reader(open(path, encoding="utf-8")))


def test_lms_one_submission_is_one_set_of_files(lms_term):
    """Item 2: the notebook named after the exercise, else the one with answers; several graded, the best kept."""
    status, out, err = lms_term["runs"]["grade01"]
    assert status == 0, err
    assert re.search(r"ignored +\S+borrador\.ipynb: another notebook of snavarro's submission, not named after the "
                     r"exercise", out)
    assert re.search(rf"ignored +\S+{re.escape(EX01)} \(1\)\.ipynb: a blank copy of the release", out)
    assert re.search(r"several +aduo: 2 notebooks graded, the best counts", out)
    assert re.search(r"ignored +\S+\.pdf: a PDF, not a notebook \(\.ipynb\): not graded", out)
    course = lms_term["course"]
    (several,) = [r for r in csv.DictReader(open(course / "report" / f"{EX01}-several.csv")) if r["student"] == "aduo"]
    assert "Ex01.ipynb (counts)" in several["files"] and f"{EX01}.ipynb (graded)" in several["files"]
    scratch = {r["student"]: r["files"] for r in csv.DictReader(open(course / "report" / f"{EX01}-several.csv"))}
    assert "borrador.ipynb (ignored: another notebook" in scratch["snavarro"]
    assert f"{EX01} (1).ipynb (ignored: a blank copy" in scratch["jcastro"]
    page = (course / "feedback" / "aduo" / f"{EX01}.html").read_text(encoding="utf-8")
    assert "Your submission holds 2 notebooks; each was graded and the best counts." in page
    page = (course / "feedback" / "snavarro" / f"{EX01}.html").read_text(encoding="utf-8")
    assert "Not graded: " in page and "borrador.ipynb — another notebook of snavarro&#x27;s submission" in page
    # the wrong version of aduo's was graded, as planted (its own score, under the source as last edited), and did
    # not count
    db = __import__("sqlite3").connect(course / "graded" / "gradebook.sqlite")
    scores = sorted(s for (s,) in db.execute("SELECT score FROM attempts WHERE exercise = ? AND student = 'aduo'",
                                             (EX01,)))
    wrong = lms_term["wrong_edited"]
    assert scores == [pytest.approx(sum(v[0] for v in wrong.values()), abs=1e-4), lms_term["full01"] + 1]
    assert wrong["whole_phi"][2] == {"sign_flip"} and wrong["whole_phi"][1] == 5


def test_lms_a_pdf_is_named_never_nothing(lms_term):
    course = lms_term["course"]
    page = (course / "feedback" / "palonso" / f"{EX01}.html").read_text(encoding="utf-8")
    assert "nothing was handed in" not in page
    assert f"you handed in {_canvas('palonso', 2005, 7_020_051, EX01)}.pdf (a PDF), not a notebook" in page
    rows = list(csv.DictReader(open(course / "report" / f"{EX01}-not_notebooks.csv")))
    assert [(r["student"], r["what"]) for r in rows] == [("palonso", "a PDF, not a notebook")]
    # the Moodle student who handed in a PDF and an online text
    page = (course / "graded-moodle" / "feedback" / "beatriz.ortiz@alumnos.uni.es" / f"{EX01}.html").read_text()
    assert "you handed in entrega.pdf, onlinetext.html (a PDF, a web page (an online text)), not a notebook" in page


def test_lms_readable_work_is_graded(lms_term):
    """Item 5: nbformat 3 and 9 MB of saved output: graded on their answers."""
    course = lms_term["course"]
    totals = {r["student"]: r for r in csv.DictReader(open(course / "graded" / "totals.csv")) if r["exercise"] == EX01}
    first = {r[3]: r for r in _rows(course / "canvas-import.csv")[2:]}
    assert first["nramos"][5] == first["jlopez"][5] == number(lms_term["full01"])
    assert os.path.getsize(next((course / "collected" / "ex01").glob("*_2007_*"))) > 9 * 2 ** 20
    assert totals["nramos"]["status"] == totals["jlopez"]["status"] == "ok"


def test_lms_late_enrolment_and_a_newer_roster(lms_term):
    """Item 3: kmensah's variant names him: his, not on the roster, no copying signal; week 5's roster re-attaches
    his Canvas id, which disappears from report, exports and feedback."""
    runs = lms_term["runs"]
    assert "not on the roster (1): kmensah" in runs["grade11"][1]
    assert "copying signal: " not in runs["grade11"][1] and "wrong-release" not in runs["grade11"][1]
    assert re.search(r"enrolled +\S+_2099_\S+: 2099 is not on the roster, and this notebook was released for kmensah, "
                     r"who is not either: graded as kmensah", runs["grade11"][1])
    assert "not on the roster (1): 2099" in runs["grade01"][1]
    assert "re-attached  2099 → kmensah" in runs["week5"][1]
    course = lms_term["course"]
    assert not list(csv.DictReader(open(course / "report" / f"{EX11}-copying.csv")))
    for name in ("scores", "several", "not_notebooks"):
        assert "2099" not in (course / "report" / f"{EX01}-{name}.csv").read_text()
    assert "2099" not in os.listdir(course / "feedback") and "kmensah" in os.listdir(course / "feedback")
    assert "not in the file" not in runs["export"][1]


def test_lms_points_as_canvas_has_them(lms_term):
    """Item 4: Canvas's 12 points for ex11 (kinbook: 10) stop the export; --scale writes scores out of 12."""
    status, out, err = lms_term["runs"]["export_stop"]
    assert status == 2 and f"{EX11} is worth 10 points in kinbook and 12 in Canvas ('{HEADERS_LMS[EX11]}'" in err
    assert not (lms_term["course"] / "stopped.csv").exists()
    full01 = number(lms_term["full01"])
    want = [["Student", "ID", "SIS User ID", "SIS Login ID", "Section", *HEADERS_LMS.values()],
            ["    Points Possible", "", "", "", "", "11", str(EX11_POINTS)]]
    for s, uid in [*LMS_IDS.items(), LATE_ID]:
        ex01 = "0" if s in ("palonso", "xmiss") else full01
        ex11 = str(EX11_POINTS) if s in ("atorres", "kmensah") else "0"
        want.append([f"{s[1:].capitalize()}, {s[0].upper()}", str(uid), f"S{uid}", s, "A", ex01, ex11])
    assert _rows(lms_term["course"] / "canvas-import.csv") == want


def test_lms_a_regrade_after_an_edit_is_safe(lms_term):
    """Item 1: whole_phi 4 → 5 points. The stop says --regrade; the regrade checks each notebook against its release
    and grades it under the new source (12 points, nobody tampered, no feedback quoting points=5); a gradebook
    that never saw the release refuses, naming the source's cell."""
    runs, course = lms_term["runs"], lms_term["course"]
    assert runs["edited"][0] == 2 and "run again with --regrade" in runs["edited"][2]
    status, out, err = runs["regrade"]
    assert status == 0, err
    assert "tampered" not in out
    totals = {r["student"]: r for r in csv.DictReader(open(course / "graded" / "totals.csv")) if r["exercise"] == EX01}
    for s in ("atorres", "snavarro", "jcastro", "aduo", "nramos", "jlopez", "kmensah"):
        assert (totals[s]["score"], totals[s]["max_score"], totals[s]["status"]) == (
            number(lms_term["full01"] + 1), number(lms_term["full01"] + 1), "ok"), s
    for page in (course / "graded" / "feedback").rglob(f"{EX01}.html"):
        text = page.read_text(encoding="utf-8")
        assert "points=5" not in text and "tampered" not in text and "not meant to edit" not in text, page
    status, out, err = runs["fresh"]
    assert status == 2
    assert re.search(r"8 of 8 submissions do not hold the locked cells of exercises/ex01-revolute-joint-phi\.ipynb as "
                     r"it is now — its cell 12 \(“part\(\"whole_phi\", points=5, .*” ?\) differs from the notebook "
                     r"the students were given", err), err
    assert "Nothing was graded" in err
    status, out, err = runs["released_from"]
    assert status == 0 and "tampered" not in out and out.count(f"ok               {number(lms_term['full01'] + 1)}/")


def test_lms_feedback_zips_are_named_as_the_lms_reads_them(lms_term):
    """Item 7: Canvas's Re-Upload Submissions takes the first two all-digit parts of a file's name (split at '_') as
    the user id and an attachment of their submission; Moodle's zip import splits each path part at '_' into at
    most 5 pieces: full name, participant id, 'assignfeedback', 'file'."""
    course = lms_term["course"]
    downloads = {}
    for path in (course / "collected" / "ex01").iterdir():
        user, attachment = [x for x in path.name.split("_") if x.isdigit()][:2]
        downloads.setdefault(user, set()).add(attachment)
    with zipfile.ZipFile(course / "upload" / f"{EX01}-canvas.zip") as z:
        names = z.namelist()
    users = {}
    for name in names:
        user, attachment = [x for x in os.path.basename(name).split("_") if x.isdigit()][:2]
        assert attachment in downloads[user], name
        users[user] = name
    assert sorted(users) == sorted(str(u) for s, u in [*LMS_IDS.items(), LATE_ID] if s != "xmiss")
    assert "Nothing was handed in" not in lms_term["runs"]["upload"][1] and "xmiss" in lms_term["runs"]["upload"][1]
    with zipfile.ZipFile(course / "upload-moodle" / f"{EX01}-moodle.zip") as z:
        names = z.namelist()
    info = [n.split("/")[0].split("_", 4) for n in names]
    assert sorted((i[1], i[2], i[3]) for i in info) == [(p, "assignfeedback", "file") for p in
                                                         ("2387101", "2387107", "2387108")]
    assert {i[0] for i in info} == {"Carlos Pérez", "Jorge Castro", "Beatriz Ortiz"}


def test_lms_spanish_moodle_worksheet_and_a_roster_that_matches_nobody(lms_term, tmp_path):
    """Item 6: the Spanish worksheet maps participants (Jorge's real notebook graded, his blank '(1)' listed); a roster
    whose ids match no file stops the run before anything is stored."""
    status, out, err = lms_term["runs"]["moodle"]
    assert status == 0, err
    assert re.search(r"jorge\.castro@alumnos\.uni\.es +ok +11/11", out) and "not on the roster" not in out
    from kinbook.classroom.roster import read_roster

    roster = read_roster(lms_term["course"] / "hoja-de-calificaciones.csv")
    assert (roster.source, [(s.student, s.lms_id, s.display) for s in roster][0]) == (
        "moodle", ("carlos.perez@alumnos.uni.es", "2387101", "Carlos Pérez"))
    wrong = tmp_path / "otro-curso.csv"
    wrong.write_text('Identificador,Nombre completo,Dirección de correo\n"Participante 1",A B,a@x.es\n'
                     '"Participante 2",C D,c@x.es\n', encoding="utf-8")
    status, out, err = _quiet_main(["grade", str(ROOT / "exercises" / f"{EX01}.ipynb"),
                                    str(lms_term["course"] / "collected-moodle" / "ex01"), "-o", str(tmp_path / "g"),
                                    "--roster", str(wrong), "--id-pattern", "moodle", "--no-isolation"])
    assert status == 2 and "matches none of the 2 students the files name" in err
    import sqlite3

    db = sqlite3.connect(tmp_path / "g" / "gradebook.sqlite")
    assert db.execute("SELECT COUNT(*) FROM roster").fetchone() == (0,)
    assert db.execute("SELECT COUNT(*) FROM attempts").fetchone() == (0,)


def test_lms_ex11_asks_for_e0_nonnegative(lms_term):
    """ex11 (b) says e0 ≥ 0: −p is the same orientation, and a sign error for this question."""
    src = lms_term["src11"]
    values = student_parameters(src, "s01")
    nb = plant(EX11, "s01", src, values)
    edit_cell(nb, "p = np.concatenate([[e0], e])", "p = -np.concatenate([[e0], e])")
    parts = expected_parts(src, values, nb)
    assert parts["p"] == (0.0, 3, {"sign_flip"})
    assert parts["A"][0] == 3 and parts["EGt"][0] == 2   # the rest, computed from p's own sign, stays right


def test_lms_sigterm_says_what_was_kept(lms_term, tmp_path, capsys):
    import signal

    from kinbook.classroom import grade

    def stop(item):
        if not isinstance(item, str):
            os.kill(os.getpid(), signal.SIGTERM)

    files = sorted((lms_term["course"] / "collected" / "ex01").glob("*_2001_*")) + sorted(
        (lms_term["course"] / "collected" / "ex01").glob("*_2006_*"))
    with pytest.raises(SystemExit) as stopped:
        grade(lms_term["src01"].path, files, tmp_path / "g", isolation=False, timeout=ENOUGH, progress=stop,
              id_pattern="canvas")
    assert stopped.value.code == 128 + signal.SIGTERM
    err = capsys.readouterr().err
    assert "stopped by SIGTERM: 1 of 2 submission(s) graded in this run are kept in" in err
    assert "Run the same command again to grade the rest." in err
    rows = list(csv.DictReader(open(tmp_path / "g" / "totals.csv")))
    assert [r["score"] for r in rows] == [number(lms_term["full01"])]


def test_totals_and_grades_carry_overrides_and_late_penalties(term):
    """totals.csv's score is the one that counts — the same number as the LMS files — beside the grader's."""
    course, expected = term["course"], term["expected"]
    totals = {(r["student"], r["exercise"]): r for r in csv.DictReader(open(course / "graded" / "totals.csv"))}
    for ex in (EX01, EX11):
        for s in IDS:
            if s in MISSING[ex]:
                continue
            row = totals[s, ex]
            raw = sum(v[0] for v in expected[ex, s].values())
            assert (row["score"], row["grader_score"]) == (number(finals(ex, s, expected)), f"{round(raw, 4):g}"), s
            late = s in LATE[ex] and s != "s12"
            assert (row["late_days"], row["penalty"] != "0") == (str(int(late)), late), s
    assert totals["s05", EX01]["overridden"] == "revolute_OA"
    grades = {(r["student"], r["exercise"], r["part"]): r for r in csv.DictReader(open(course / "graded" / "grades.csv"))}
    row = grades["s05", EX01, "revolute_OA"]
    assert (row["score"], row["override"]) == ("3", "sign convention of the sketch accepted")
    assert row["grader_score"] == f"{expected[EX01, 's05']['revolute_OA'][0]:g}"


def test_feedback_zip_for_canvas_reupload(term):
    """docs' `kinbook feedback --lms canvas`: one zip per exercise; each page's name gives Canvas the student's user id
    and an attachment id of their own submission (the download's name), as generate_comments_from_files reads it."""
    course = term["course"]
    for ex, folder in ((EX01, "ex01"), (EX11, "ex11")):
        attachments = {}
        for name in os.listdir(course / "collected" / folder):
            digits = [x for x in name.split("_") if x.isdigit()]
            if len(digits) >= 2:
                attachments.setdefault(digits[0], set()).add(digits[1])
        with zipfile.ZipFile(course / "upload" / f"{ex}-canvas.zip") as z:
            names = z.namelist()
            page = z.read(next(n for n in names if f"_{CANVAS_ID['s11']}_" in n)).decode("utf-8") if ex == EX01 else ""
        users = {}
        for name in names:
            user, attachment = [x for x in name.split("_") if x.isdigit()][:2]
            assert attachment in attachments[user], name
            users[user] = name
        assert sorted(users) == sorted([CANVAS_ID[s] for s in IDS if s not in MISSING[ex]] + [STRANGER])
        if page:
            assert "1 day(s) after the due date" in page


# Moodle's grading worksheet as its language packs write it (projectestac/moodle-langpacks: moodle.php 'fullname',
# 'email', 'idnumber'; assign.php 'recordid', 'hiddenuser'), transcribed by hand, one language a row.
WORKSHEETS = {
    "en": ("Identifier", "Full name", "Email address", "Participant"),
    "es": ("Identificador", "Nombre completo", "Dirección de correo", "Participante"),
    "ca": ("Identificador", "Nom complet", "Adreça electrònica", "Participant"),
    "gl": ("Identificador", "Nome completo", "Enderezo de correo", "Participante"),
    "pt": ("Identificador", "Nome completo", "E-mail", "Participante"),
    "fr": ("Identifiant", "Nom complet", "Adresse de courriel", "Participant"),
    "it": ("Identificativo", "Nome", "Indirizzo email", "Partecipante"),
    "de": ("ID", "Vollständiger Name", "E-Mail-Adresse", "Teilnehmer/in"),
    "nl": ("Identificatie", "Volledige naam", "E-mailadres", "Deelnemer"),
    "eu": ("Identifikatzailea", "Izen osoa", "Helbide elektronikoa", "Partaidea"),
}


@pytest.mark.parametrize("lang", sorted(WORKSHEETS))
def test_moodle_worksheet_in_each_language(lang, tmp_path):
    from kinbook.classroom.roster import read_roster

    ident, name, email, participant = WORKSHEETS[lang]
    path = tmp_path / "worksheet.csv"
    path.write_text(f'"{ident}","{name}","{email}",Estado\n"{participant} 2387101","José Núñez",jose.nunez@uni.es,x\n'
                    f'"{participant} 2387102","王小明",wang.xiaoming@uni.es,x\n', encoding="utf-8")
    roster = read_roster(path)
    assert roster.source == "moodle"
    assert [(s.student, s.lms_id, s.display) for s in roster] == [
        ("jose.nunez@uni.es", "2387101", "José Núñez"), ("wang.xiaoming@uni.es", "2387102", "王小明")]
    assert roster.find("2387102", "lms").student == "wang.xiaoming@uni.es"       # how a download's folder maps


def test_canvas_export_with_first_and_last_names_and_decimal_commas(tmp_path):
    """Canvas's headers are English in every locale (lib/gradebook_exporter.rb); its "show first and last names"
    setting writes LastName, FirstName; a decimal-comma locale writes 10,00 and may separate with ';'."""
    from kinbook.classroom.roster import read_roster

    path = tmp_path / "canvas.csv"
    path.write_text('LastName;FirstName;ID;SIS User ID;SIS Login ID;Section;Ejercicio 9 (40109)\n'
                    '"    Points Possible";;;;;;10,00\nStudent;Test;999;;;S;\nTorres;Ana;1001;20231001;atorres;A;\n',
                    encoding="utf-8-sig")
    roster = read_roster(path)
    assert (roster.source, roster.points) == ("canvas", {"Ejercicio 9 (40109)": 10.0})
    assert [(s.student, s.lms_id, s.display) for s in roster] == [("atorres", "1001", "Ana Torres")]


def test_a_newer_roster_takes_back_a_false_copying_signal(tmp_path):
    """A gradebook where a late enrolee's variant was graded under their Canvas id, as someone else's release (a
    copying signal, 0): the roster that knows them moves every result to them, drops the signal and the orphan id,
    and leaves the attempt to be graded again (its source mark cleared), while an ordinary result of theirs stays."""
    from kinbook.classroom.gradebook import Gradebook
    from kinbook.classroom.results import PartGrade, SubmissionResult
    from kinbook.classroom.roster import Roster, Student

    book = Gradebook(tmp_path)
    wrong = SubmissionResult("2099", EX11, "c/mensahk_2099_1_x.ipynb", "aa" * 32, "wrong-release",
                             "this notebook was released for kmensah, not for 2099",
                             [PartGrade("A", 0.0, 3.0, "wrong-release", "")], signals=[("released-for", "kmensah")],
                             source_sha256="s" * 64)
    book.record(wrong, run=1)
    book.record(SubmissionResult("2099", EX01, "c/mensahk_2099_2_y.ipynb", "bb" * 32, "ok", "",
                                 [PartGrade("whole_phi", 4.0, 4.0, "ok", "")], source_sha256="t" * 64), run=1)
    book.override(EX01, "2099", "whole_phi", 3.5, "late enrolment")
    moved = book.set_roster(Roster([Student("atorres", lms_id="2001"), Student("kmensah", lms_id="2099")]))
    assert moved == [("2099", "kmensah")]
    tables = ("attempts", "submissions", "parts", "mistakes", "signals", "files", "overrides", "extensions")
    assert [t for t in tables if book.db.execute(f"SELECT COUNT(*) FROM {t} WHERE student = '2099'").fetchone()[0]] == []
    assert book.db.execute("SELECT COUNT(*) FROM signals").fetchone() == (0,)
    assert book.attempt_of(EX11, "kmensah", "aa" * 32)[1] == ""            # graded again by the next run
    assert book.attempt_of(EX01, "kmensah", "bb" * 32)[1] == "t" * 64      # an ordinary result: kept as it was
    assert book.overrides(EX01, "kmensah") == {(EX01, "kmensah"): {"whole_phi": (3.5, "late enrolment")}}
    assert book.reattached() == {"2099": "kmensah"}


def test_a_student_who_did_tamper_is_told_about_their_own_release():
    """After an edit, a notebook that matches no release is tampered — and the message quotes the release the
    student got (their cell as released), never a cell of the edit they cannot have seen."""
    from kinbook.classroom.editions import carry_over, edition_of, editions
    from kinbook.classroom.notebook import source_from_bytes

    old = load_source(ROOT / "exercises" / f"{EX01}.ipynb")
    new = source_from_bytes(old.data.replace(b'part(\\"whole_phi\\", points=4', b'part(\\"whole_phi\\", points=5'),
                            old.path)
    assert new.sha256 != old.sha256
    honest = plant(EX01, None, old, None)
    cells = [{"cell_type": c.cell_type, "source": c.source, "id": c["id"]} for c in honest.cells]
    candidates = editions(new, [old], None, None)
    edition, missing = edition_of(cells, candidates)
    assert (edition.source is old, missing) == (True, [])                  # the release this student got
    carried = carry_over(cells, edition, candidates[0])
    assert candidates[0].missing_code(carried) == []                       # now a notebook of the edited source
    assert [c["source"] for c in carried if "whole_phi" in c["source"]] == [
        c.source for c in candidates[0].nb.cells if "whole_phi" in c.source]
    assert [c["source"] for c in carried if c["cell_type"] == "code" and "Phi_OA =" in c["source"]] == [
        c.source for c in honest.cells if c.cell_type == "code" and "Phi_OA =" in c.source]   # their answers kept
    tampered = [c for c in cells if "part(\"revolute_OA\"" not in c["source"]]          # they deleted a locked cell
    edition, missing = edition_of(tampered, candidates)
    assert edition.source is old and len(missing) == 1
    (cell,) = [c for c in edition.code_locked if c["id"] in missing]
    assert edition.cell_name(cell).startswith("cell 6 “part(\"revolute_OA\", points=3")
    assert "points=5" not in edition.cell_name(cell)
