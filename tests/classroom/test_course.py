"""The course layer (issue 21): roster, attempts and policy, overrides, the late rule, LMS exports, the report, feedback
pages, batch variants and `kinbook validate`. Results are recorded straight into a gradebook here (no grading), except
for validate and the variants, which use the real grader and the shipped exercises."""

import csv
import io
import json
import re

import pytest

from kinbook.classroom.export import CANVAS_IDS, MOODLE_IDS, export
from kinbook.classroom.feedback import write_pages
from kinbook.classroom.gradebook import Gradebook
from kinbook.classroom.report import report, tables
from kinbook.classroom.results import PartGrade, SubmissionResult
from kinbook.classroom.roster import read_roster
from kinbook.classroom.scores import late_days
from kinbook.cli import main
from kinbook.errors import GradingError

from .conftest import ENOUGH, SOURCE

EX = "ex01"
ROSTER = """student,name,lms_id,sis_id,login,email,section
ana,"García, Ana",1001,S1,ana.garcia,ana@uni.example,A
ben,"Okafor, Ben",1002,S2,ben.okafor,ben@uni.example,B
carl,"Li, Carl",1003,S3,carl.li,carl@uni.example,A
"""


def result(student, a, b, *, submitted="", late=False, mistakes=(), answer="x"):
    """A result of exercise EX: part a out of 4, part b out of 2."""
    return SubmissionResult(student, EX, f"collected/{student}.ipynb", student * 8, "ok", "",
                            [PartGrade("a", a, 4.0, "ok", "msg a", answer=answer, mistakes=list(mistakes)),
                             PartGrade("b", b, 2.0, "ok", "msg b", answer="1.0")], 1.0, "none", submitted, "name",
                            late, [], "src")


@pytest.fixture
def course(tmp_path):
    (tmp_path / "roster.csv").write_text(ROSTER)
    book = Gradebook(tmp_path / "graded")
    book.set_roster(read_roster(tmp_path / "roster.csv"))
    book.record(result("ana", 4, 2, submitted="2026-03-01T20:00:00"))
    book.record(result("ben", 1, 2, submitted="2026-03-03T10:00:00", mistakes=[("sign_flip", "Φ_4")]))
    book.record(result("zoe", 2, 0, late=True, mistakes=[("sign_flip", "Φ_5"), ("transposed", "")]))  # off the roster
    yield tmp_path, book
    book.close()


# -------------------------------------------------------------------------------------------------- late rule
def test_late_days_count_started_days_and_respect_zones():
    due = "2026-03-01T23:59+01:00"
    assert late_days("2026-03-01T23:59:00+01:00", due) == 0
    assert late_days("2026-03-01T23:00:00+00:00", due) == 1        # 00:00 in the due date's zone: one minute late
    assert late_days("2026-03-04T00:00:00", due) == 3              # a time from a name: read in the due date's zone
    assert late_days("", due, marked_late=True) == 1               # Canvas said late, no time known
    assert late_days("", "") == 0


def test_penalty_cap_extension_and_policy(course):
    tmp, book = course
    book.set_rule(EX, due="2026-03-01T23:59+01:00", penalty=10, cap=25)
    finals = {f.student: f for f in book.finals(EX)}
    assert (finals["ana"].late_days, finals["ana"].score) == (0, 6.0)
    assert (finals["ben"].late_days, finals["ben"].penalty, finals["ben"].score) == (2, 1.2, 1.8)  # 2 days × 10 % of 6
    assert (finals["zoe"].late_days, finals["zoe"].score) == (1, 1.4)                                # marked late
    assert finals["carl"].status == "missing" and finals["carl"].score == 0
    book.extend(EX, "ben", "2026-03-04T23:59+01:00", "illness")
    assert {f.student: f for f in book.finals(EX)}["ben"].score == 3.0
    book.set_rule(EX, penalty=50)                                    # capped at 25 %: 1.5 points
    assert {f.student: f for f in book.finals(EX)}["zoe"].penalty == 1.5


def test_attempts_latest_or_best(course):
    tmp, book = course
    book.record(result("ana", 1, 0, submitted="2026-03-02T09:00:00"))  # a later, worse attempt
    assert book.results(student="ana")[0].score == 1                    # latest counts
    book.set_rule(EX, policy="best")
    assert book.results(student="ana")[0].score == 6
    history = book.attempts(EX, "ana")
    assert [(h[7], h[9]) for h in history] == [(6.0, 1), (1.0, 0)]      # both kept; the best counts
    (ana,) = [f for f in book.finals(EX) if f.student == "ana"]
    assert (ana.attempts, ana.policy, ana.score) == (2, "best", 6.0)
    write_pages(book, tmp / "fb", ["ana"])
    assert "You handed in 2 files; the best counts." in (tmp / "fb" / "ana" / f"{EX}.html").read_text()


# -------------------------------------------------------------------------------------------------- overrides
def test_overrides_are_checked_shown_and_kept(course, capsys):
    tmp, book = course
    g = str(tmp / "graded")
    assert main(["override", "ben", EX, "a", "3.5", "--why", "the sign convention was ambiguous", "-g", g]) == 0
    assert main(["override", "ben", EX, "nope", "1", "--why", "x", "-g", g]) == 2
    assert main(["override", "ben", EX, "a", "5", "--why", "x", "-g", g]) == 2    # part a is worth 4
    assert main(["override", "ben", EX, "a", "1", "-g", g]) == 2                   # no reason
    err = capsys.readouterr().err
    assert "no part 'nope'" in err and "from 0 to 4" in err and "--why" in err
    book.record(result("ben", 0, 0))                                               # a regrade: the override stays
    (ben,) = [f for f in book.finals(EX) if f.student == "ben"]
    assert ben.raw == 3.5 and ben.parts[0][3] == (3.5, "the sign convention was ambiguous")
    write_pages(book, tmp / "fb")
    page = (tmp / "fb" / "ben" / f"{EX}.html").read_text()
    assert "your instructor set the score to 3.5 — the sign convention was ambiguous" in page
    assert main(["override", "ben", EX, "a", "--remove", "-g", g]) == 0
    assert [f for f in book.finals(EX) if f.student == "ben"][0].raw == 0


# -------------------------------------------------------------------------------------------------- exports
# The formats as their LMS writes them (an import takes its own export's layout), checked against the sources
# (2026-11-26):
# - Canvas: lib/gradebook_exporter.rb in instructure/canvas-lms writes the header `Student, ID, [SIS User ID,]
#   SIS Login ID, [Integration ID, Root Account,] Section`, then one `Assignment#title_with_id` column per assignment
#   ("<title> (<id>)"; the importer matches an assignment by that id), then a second row whose first cell is
#   "    Points Possible" (four spaces) with the assignments' points; its spec fixture
#   spec/fixtures/gradebooks/basic_course_with_sis_login_id.csv imports the same layout without SIS User ID.
# - Moodle: grade/export/lib.php's `format_column_name` names a column "<module name>: <item name> (<display
#   type>)" — "Assignment: Essay 1 (Real)" — after the user fields `First name, Last name, ID number, Institution,
#   Department, Email address`, the header Moodle's own CSV import test reads (grade/import/csv/tests/
#   load_data_test.php); its import maps one identifying column (ID number, e-mail …) to the user.
CANVAS_EXAMPLE = """Student,ID,SIS User ID,SIS Login ID,Section,Assignment 1 (12345)
    Points Possible,,,,,10
"Lastname, Firstname",1234,SIS123,login123,Section 1,9
"""
MOODLE_EXAMPLE = """First name,Last name,ID number,Institution,Department,Email address,Assignment: Essay 1 (Real)
Firstname,Lastname,SIS123,,,student@example.com,9.00
"""


def rows_of(path):
    return list(csv.reader(io.StringIO(open(path, encoding="utf-8").read())))


def test_canvas_export_has_the_documented_layout_cell_by_cell(course):
    tmp, book = course
    book.set_rule(EX, due="2026-03-01T23:59+01:00", penalty=10)
    book.override(EX, "ana", "b", 1.25, "b half right")
    path, left = export(tmp / "graded", tmp / "canvas.csv", "canvas", headers={EX: "Exercise 1 (4242)"}, decimals=1)
    doc = list(csv.reader(io.StringIO(CANVAS_EXAMPLE)))
    got = rows_of(path)
    assert got[0][:5] == doc[0][:5] == CANVAS_IDS
    assert got[1][0] == doc[1][0] and got[1][1:5] == doc[1][1:5] == [""] * 4      # "    Points Possible"
    assert got[0][5] == "Exercise 1 (4242)"
    assert all(re.fullmatch(r".+ \((\d+)\)", h) for h in (doc[0][5], got[0][5]))         # "<title> (<id>)"
    assert got[1:] == [["    Points Possible", "", "", "", "", "6"],
                       ["García, Ana", "1001", "S1", "ana.garcia", "A", "5.2"],    # 4 + 1.25 overridden, rounded
                       ["Okafor, Ben", "1002", "S2", "ben.okafor", "B", "1.8"],    # 3, two days late: − 1.2
                       ["Li, Carl", "1003", "S3", "carl.li", "A", "0"]]            # missing
    assert left == ["zoe"]                                                         # graded, not on the roster
    with pytest.raises(GradingError, match="no assignment id"):
        export(tmp / "graded", tmp / "c2.csv", "canvas", headers={EX: "Exercise 1"})
    export(tmp / "graded", tmp / "blank.csv", "canvas", headers={EX: "Exercise 1 (4242)"}, missing="blank")
    assert rows_of(tmp / "blank.csv")[4][5] == ""


def test_moodle_export_has_the_documented_layout_cell_by_cell(course):
    tmp, book = course
    path, _ = export(tmp / "graded", tmp / "moodle.csv", "moodle", decimals=2)
    doc = list(csv.reader(io.StringIO(MOODLE_EXAMPLE)))
    got = rows_of(path)
    assert got[0][:6] == doc[0][:6] == MOODLE_IDS
    assert all(re.fullmatch(r"Assignment: .+ \(Real\)", h) for h in (doc[0][6], got[0][6]))
    assert got == [MOODLE_IDS + [f"Assignment: {EX} (Real)"],
                   ["Ana", "García", "S1", "", "", "ana@uni.example", "6"],
                   ["Ben", "Okafor", "S2", "", "", "ben@uni.example", "3"],
                   ["Carl", "Li", "S3", "", "", "carl@uni.example", "0"]]


def test_kinbook_csv_lists_everyone_and_refuses_an_lms_file_without_a_roster(tmp_path):
    book = Gradebook(tmp_path / "graded")
    book.record(result("ana", 4, 2))
    path, _ = export(tmp_path / "graded", tmp_path / "all.csv")
    assert rows_of(path)[1][:7] == ["ana", "ana", "", "", "", "", "6"]
    with pytest.raises(GradingError, match="needs the roster"):
        export(tmp_path / "graded", tmp_path / "c.csv", "canvas")
    with pytest.raises(GradingError, match="no exercise 'ex99'"):
        export(tmp_path / "graded", tmp_path / "c.csv", exercises=["ex99"])


# -------------------------------------------------------------------------------------------------- report
def test_report_tables_are_queries_of_the_rows(course):
    tmp, book = course
    parts = {r["part"]: r for r in tables.parts(book, EX)}
    assert parts["a"]["full_marks"] == 1 and parts["a"]["mean"] == round(7 / 3, 3)
    assert parts["b"]["nobody"] is False
    mistakes = tables.mistakes(book, EX)
    assert [(m["part"], m["code"], m["students"]) for m in mistakes] == [("a", "sign_flip", 2), ("a", "transposed", 1)]
    assert mistakes[0]["share"] == round(2 / 3, 3) and mistakes[0]["example_student"] == "ben"
    assert mistakes[0]["example_row"] == "Φ_4" and mistakes[0]["title"] != "sign_flip"
    assert tables.missing(book, EX, book.roster()) == ["carl"]
    assert tables.off_roster(book, EX, book.roster()) == ["zoe"]


def test_copying_signals_say_what_is_identical(tmp_path):
    book = Gradebook(tmp_path)
    book.record(result("ana", 4, 2, answer="[x1 - x2]"))
    book.record(result("bob", 4, 2, answer="[x1 - x2]"))            # the same correct answers: not a signal
    book.record(result("cy", 1, 2, answer="[x1 + x2]"))
    book.record(result("dee", 1, 2, answer="[x1 + x2]"))            # the same wrong answer
    r = result("eve", 4, 2, answer="[x1 - x2]")
    r.signals = [("released-for", "ana")]
    book.record(r)
    signals = tables.copying(book, EX)
    assert {(s["kind"], s["students"]) for s in signals} == {("identical answers", "cy, dee"),
                                                             ("released for another student", "eve")}
    (same,) = [s for s in signals if s["kind"] == "identical answers"]
    assert same["what"] == "identical answers to every part (a, b), wrong ones included (part a)"


def test_report_pages_and_csv(course):
    tmp, book = course
    written = report(tmp / "graded", tmp / "report")
    assert sorted(p.name for p in written) == [f"{EX}.html", "index.html"]
    page = (tmp / "report" / f"{EX}.html").read_text()
    assert page.count("data:image/png;base64,") == 1 and "http" not in page.replace("https://", "")  # self-contained
    assert "sign_flip" in page and "Nobody got full marks" not in page
    assert "<p>2 of 3 students handed in, 1 missing; 1 more not on the roster.</p>" in page   # zoe is not on it
    assert "<td class='n'>4.00</td>" in page                      # ben's 3.5 + 0.5: scores with two decimals
    book.record(result("abe", 1, 2, mistakes=[("sign_flip", "Φ_4")], answer="\n".join(f"[x{k}]" for k in range(12))))
    report(tmp / "graded", tmp / "report")
    page = (tmp / "report" / f"{EX}.html").read_text()            # abe's 12 rows: the example now
    assert "<pre>[x0]\n[x1]\n[x2]\n[x3]\n[x4]\n[x5]</pre><div class='muted'>… 12 rows in all</div>" in page
    report(tmp / "graded", tmp / "rcsv", "csv")
    mistakes = list(csv.DictReader(open(tmp / "rcsv" / f"{EX}-mistakes.csv")))
    assert [(m["code"], m["students"]) for m in mistakes] == [("sign_flip", "3"), ("transposed", "1")]


# -------------------------------------------------------------------------------------------------- variants, validate
def test_variants_for_a_roster_in_one_run(tmp_path, capsys):
    import glob
    import os

    (tmp_path / "roster.csv").write_text(ROSTER)
    ex11 = sorted(glob.glob(os.path.join(os.path.dirname(SOURCE), "..", "..", "..", "exercises", "ex11*.ipynb")))[0]
    assert main(["variant", ex11, "--roster", str(tmp_path / "roster.csv"), "-o", str(tmp_path / "v")]) == 0
    names = sorted(p.name for p in (tmp_path / "v").iterdir())
    assert names == [f"ex11-rotations-euler-parameters-{s}.ipynb" for s in ("ana", "ben", "carl")]
    params = {json.load(open(tmp_path / "v" / n))["metadata"]["kinbook"]["parameters"]["psi"] for n in names}
    assert len(params) == 3 and "wrote 3 variant(s)" in capsys.readouterr().out


def test_validate_grades_the_solution_and_the_blank_release(tmp_path, capsys):
    assert main(["validate", SOURCE, "--no-isolation", "--timeout", str(ENOUGH)]) == 0
    out = capsys.readouterr().out
    assert "ok   the solution (generic release): 6/6" in out and "ok   the released notebook, blank: 0/6" in out
    broken = tmp_path / "tiny.ipynb"
    nb = json.load(open(SOURCE))
    for cell in nb["cells"]:
        if "angle = float" in "".join(cell["source"]):
            cell["source"] = "### BEGIN SOLUTION\nangle = float('nan') + undefined_name\n### END SOLUTION"
    broken.write_text(json.dumps(nb))
    assert main(["validate", str(broken), "--no-isolation", "--timeout", str(ENOUGH)]) == 2
    captured = capsys.readouterr()
    assert "FAIL the solution (generic release): 4/6" in captured.out and "part angle: 0/2" in captured.out
    assert "tiny is not valid" in captured.err


def test_a_roster_file_is_checked(tmp_path):
    f = tmp_path / "r.csv"
    f.write_text("name,email\nAna,ana@x\n")
    with pytest.raises(GradingError, match="no 'student' column"):
        read_roster(f)
    f.write_text("student\nana/../x\n")
    with pytest.raises(GradingError, match="line 2: a student id cannot hold '/'.*'ana/../x'"):
        read_roster(f)


def test_the_cell_an_answer_was_assigned_in():
    from kinbook.classroom.answers import MAX_PARSED_CHARS, answer_cell

    cells = [{"cell_type": "markdown", "source": "**(a)** Φ of joint 1, in `Phi`."},
             {"cell_type": "code", "source": "Phi = [1]"},
             {"cell_type": "code", "source": "for k in range(1):\n    Phi[k] = 2"},
             {"cell_type": "markdown", "source": "**(b)**"},
             {"cell_type": "code", "source": "p = (q := 3)\nimport numpy as np"}]
    assert answer_cell(cells, "Phi") == "cell 3 of 5 (after “**(a)** Φ of joint 1, in `Phi`.”)\nfor k in range(1):\n" \
                                        "    Phi[k] = 2"
    assert answer_cell(cells, "q").startswith("cell 5 of 5 (after “**(b)**”)") and answer_cell(cells, "zz") == ""
    big = [{"cell_type": "code", "source": "x = 1\n" * (MAX_PARSED_CHARS // 6 + 1)}, {"cell_type": "code",
                                                                                     "source": "Phi = 2"}]
    assert answer_cell(big, "Phi") == "cell 2 of 2\nPhi = 2"  # past the parsing budget: found by its pattern


def test_multiline_fields_keep_their_lines_and_lose_their_escapes():
    from kinbook.classroom.sanitize import clean_result

    r = clean_result(result("ana", 4, 2, answer="[x1 - x2]\n[y1 \x1b[2J- y2]\u202e"))
    assert r.parts[0].answer == "[x1 - x2]\n[y1 \\x1b[2J- y2]\\u202e"   # one row a line; escapes made visible
    assert clean_result(result("ana", 4, 2)).parts[0].message == "msg a"
