"""Grading real submitted notebooks in one batch: tests/classroom/submissions/ (made by make_submissions.py)
and the entries conftest.py makes at test time (links, a FIFO, a device, giant notebooks, clashing and
over-long ids, an nbformat-4.4 notebook)."""

import csv
import os
import re

import pytest

from kinbook.classroom import grade
from kinbook.classroom.files import student_id
from kinbook.classroom.gradebook import COLUMNS, TOTALS

from .conftest import BWRAP, CANARY, CANARY_DIR, ENOUGH, EVIL, LONG_NAME, ODD_NAME, SECRET, SOURCE, submission

FULL = 6.0
ESCAPES = ["unhook", "unaudited", "recon", "writes", "daemon", "leftovers", "hijack", "stamps", "second_kernel"]


def parts(batch, student):
    return {p.part: p for p in batch["results"][student].parts}


def test_good_submission_gets_full_score_among_bad_ones(batch):
    r = batch["results"]["good"]
    assert (r.status, r.score, r.max_score) == ("ok", FULL, FULL)
    assert {p.status for p in r.parts} == {"ok"}
    assert r.isolation.startswith("bubblewrap; " if BWRAP else "none; ")
    assert r.isolation.split("; ")[1] in ("cgroup v1 (memory, pids, cpu)", "cgroup v2 (memory, pids, cpu)",
                                          "rlimits, no fork")


@pytest.mark.parametrize("student, status, score", [
    ("wrong", "ok", 0.0),
    ("partial", "missing-answer", 4.0),
    # a runtime failure costs the parts not answered before it, not those answered before
    ("loop", "timeout", 4.0),
    ("memory", "memory", 4.0),
    ("sys_exit", "missing-answer", 4.0),     # SystemExit is an ordinary error in a kernel: part (a) stands
    ("os_exit", "error", 4.0),               # the kernel is gone: (a) was read after its cell, (b) never was
    ("kill_kernel", "error", 4.0),           # os.kill is refused; raise_signal(SIGKILL) kills the kernel
    ("flood", "ok", FULL),                   # 300,000 lines of output: capped, then graded
    ("exception", "missing-answer", 4.0),
    ("ansi", "missing-answer", 4.0),
    ("fork_hog", "ok", FULL),                # the hook refuses the fork; the answers are right
    ("edited_title", "ok", FULL),            # a locked text cell edited: restored from the release, not refused
    ("classmate", "wrong-release", 0.0),     # released for another student: said so, not "tampered"
    ("hardlink", "refused", 0.0),            # a hard link to the instructor's source
    ("hardlink_classmate", "refused", 0.0),  # a hard link to another file
    ("source_copy", "refused", 0.0),         # the source notebook itself
    ("monkeypatch", "ok", 0.0),              # patched checkers live and die in the student's kernel
    ("patch_serializer", "error", 0.0),      # a forged answer record: not whitelisted data
    ("fake_score", "ok", 0.0),               # what the notebook prints is never read
    ("read_source", "missing-answer", 0.0),  # open() of the instructor's source raises PermissionError
    ("write_outside", "ok", FULL),           # every attempt refused; the answers themselves are right
    ("tampered", "tampered", 0.0),
    ("deleted_cell", "tampered", 0.0),
    ("corrupt", "corrupt-notebook", 0.0),
    ("not_a_notebook", "corrupt-notebook", 0.0),
    ("power_tower", "error", 2.0),           # the tower is refused as too large; the angle is right
    ("many_rows", "error", 2.0),             # 2,000 rows for a joint's 2: refused unchecked; the angle is right
    ("reference", "ok", FULL),               # kinbook's own Φ: correct, and reported (not penalized)
    ("old44", "ok", FULL),                   # re-saved as nbformat 4.4 (no cell ids): not tampered
    ("giant", "too-large", 0.0),             # 20 MB, 150,000 cells: refused before parsing
    ("many_cells", "too-large", 0.0),        # 2,500 cells: refused before parsing
    ("link_source", "refused", 0.0),         # a link to the instructor's source: never followed
    ("link_secret", "refused", 0.0),         # a link to a private file: never followed
    ("linkdir", "refused", 0.0),             # a link to a directory of classmates
    ("fifo", "refused", 0.0),                # a FIFO: never opened (the batch does not hang on it)
    ("José", "ok", FULL),                    # NFC and NFD spellings of one id: two attempts of José's
    ("Ana", "duplicate-id", 0.0),            # Ana and ana, no roster: no spelling more real than the other
    ("ana", "duplicate-id", 0.0),
    ("ｇｏｏｄ", "duplicate-id", 0.0),          # a look-alike of good: a signal; good itself is graded (ok, above)
    (student_id(LONG_NAME)[0], "bad-id", 0.0),
    (student_id(ODD_NAME)[0], "ok", FULL),   # a name that is not UTF-8 (and has control characters)
] + [(name, "ok", FULL) for name in ESCAPES])  # every attempt refused; the answers themselves are right
def test_status_and_score(batch, student, status, score):
    r = batch["results"][student]
    assert r.status == status, r
    assert r.score == score
    assert r.max_score == FULL


def test_a_file_name_that_is_not_utf8_is_graded_and_shown_escaped(batch):
    r = batch["results"][student_id(ODD_NAME)[0]]
    assert r.submission.endswith("bytes\\xff\\x1b[2J\\nname.ipynb") and r.submission.isprintable()


def test_a_device_node_is_refused(batch):
    if "device" not in batch["results"]:
        pytest.skip("device nodes can only be made by root")
    assert batch["results"]["device"].status == "refused"


def test_refused_entries_say_why_and_leak_nothing(batch):
    results = batch["results"]
    assert "symbolic link" in results["link_source"].message and "not followed" in results["link_source"].message
    assert "FIFO" in results["fifo"].message
    assert "none of them is graded" in results["ana"].message and "collected" not in results["ana"].message
    assert "looks like the id of another student" in results["ｇｏｏｄ"].message  # (no classmate's path)
    assert results["ｇｏｏｄ"].signals == [("look-alike", "the id 'ｇｏｏｄ' looks like 'good'")]
    assert "characters" in results[student_id(LONG_NAME)[0]].message
    # 20 MB is read (saved outputs do not count against the 8 MB of code and text), its 150,000 cells are not parsed
    assert "2,000 cells" in results["giant"].message and "cells" in results["many_cells"].message
    with open(batch["out"] / "grades.csv", encoding="utf-8") as f:
        text = f.read()
    assert SECRET not in text and "BEGIN SOLUTION" not in text and "solve_position" not in text
    for page in (batch["out"] / "feedback").rglob("*.html"):
        assert SECRET not in page.read_text(encoding="utf-8")


def test_power_tower_is_refused_not_computed(batch):
    p = parts(batch, "power_tower")
    assert p["revolute"].status == "error" and "not gradable data" in p["revolute"].message
    assert p["angle"].status == "ok"


def test_an_answer_far_larger_than_the_reference_is_not_checked(batch):
    p = parts(batch, "many_rows")
    assert p["revolute"].status == "error" and p["revolute"].message.startswith("`Phi_OA` has 2,000 entries where "
                                                                                 "the reference has 2")


def test_answers_taken_from_the_reference_are_reported_not_penalized(batch):
    p = parts(batch, "reference")
    assert p["revolute"].score == 4 and p["revolute"].reference == "mech.constraint_phi() (cell 4)"
    assert p["angle"].reference == ""
    assert all(q.reference == "" for q in batch["results"]["good"].parts)
    rows = [r for r in csv.DictReader(open(batch["out"] / "grades.csv", encoding="utf-8")) if r["student"] == "reference"]
    assert {r["part"]: r["reference"] for r in rows} == {"revolute": "mech.constraint_phi() (cell 4)", "angle": ""}
    page = (batch["out"] / "feedback" / "reference" / "tiny.html").read_text(encoding="utf-8")
    assert "computed with kinbook's own reference: mech.constraint_phi() (cell 4)" in page


def test_wrong_answers_get_the_checkers_messages(batch):
    p = parts(batch, "wrong")
    assert p["revolute"].score == 0 and "Φ_4" in p["revolute"].message
    from kinbook.grading.catalogue import explain

    title, hint = explain("wrong_value")  # a hidden check names the mistake with the catalogue's hint, as a
    assert p["angle"].message == f"hidden check: not correct — wrong_value: {title} — {hint}"  # visible one does
    assert hint in p["revolute"].message
    assert "3.356" not in p["angle"].message  # a hidden check does not give its expected value away


def test_monkeypatching_the_checkers_in_the_notebook_changes_nothing(batch):
    p = parts(batch, "monkeypatch")
    assert p["revolute"].status == "ok" and p["revolute"].score == 0 and "Φ_4" in p["revolute"].message
    forged = parts(batch, "patch_serializer")
    assert forged["revolute"].status == "error" and "not allowed" in forged["revolute"].message
    assert forged["angle"].status == "missing-answer"


def test_reading_the_source_is_refused(batch):
    p = parts(batch, "read_source")
    assert p["revolute"].status == "missing-answer"
    # refused by the audit hook (PermissionError) or not there at all: the sandbox binds only the package, so a
    # checkout under /tmp (hidden by the sandbox's private /tmp) has no tests/ inside it
    assert re.match(r"`Phi_OA` is not assigned: cell 4 \(“import os, glob, kinbook”\), under “\*\*\(a\)\*\* Φ of "
                    r"revolute joint 1, in `Phi_OA`\.” raised (PermissionError: kinbook sandbox: opening|"
                    r"FileNotFoundError: \[Errno 2\] No such file or directory)", p["revolute"].message)


def test_nothing_outside_the_sandbox_was_touched(batch):
    assert batch["checkout_after"] == batch["checkout"]  # the package, the source, the classmates' files
    assert os.path.exists(CANARY) and open(CANARY).read() == "do not delete"
    assert os.path.isdir(CANARY_DIR)
    assert not os.path.exists(EVIL)
    assert not os.path.exists("/tmp/kinbook-moved.txt")
    assert not os.path.exists("/tmp/kinbook-daemon-alive")


def test_no_process_is_left_behind(batch):
    assert batch["left"] == []


def test_submissions_are_never_modified(batch):
    for f, (data, mtime) in batch["before"].items():
        assert open(f, "rb").read() == data
        assert os.stat(f).st_mtime_ns == mtime


def test_tampering_is_explained(batch):
    """The cell is named as the student saw it in the release (its position and first line), not by an id."""
    r = batch["results"]["tampered"]
    assert r.message.startswith("1 locked code cell(s) of the released notebook were changed, moved or deleted "
                                "(cell 5 “part(\"revolute\", points=4, answer=\"Phi_OA\", check=\"phi\", ta…”)")
    assert "tiny-04" not in r.message


def test_a_runtime_failure_costs_only_the_parts_not_answered_before_it(batch):
    loop = parts(batch, "loop")
    assert loop["revolute"].status == "ok" and loop["revolute"].score == 4
    assert loop["angle"].status == "timeout"
    # stopped by its CPU time (the kernel's RLIMIT_CPU), not by a clock: the same verdict at any load
    assert loop["angle"].message == ("`angle` was not assigned before the notebook stopped: the notebook used up its "
                                     "CPU time (5 s) at cell 7 (“while True:”), under “**(b)** φ2 at t = 0.01 "
                                     "(radians), in `angle`.”")
    assert batch["results"]["loop"].message == loop["angle"].message.split(": ", 1)[1]
    memory = parts(batch, "memory")
    assert memory["angle"].status == "memory" and "cell 7 (“hog = []”)" in memory["angle"].message
    dead = batch["results"]["os_exit"]
    assert dead.message.startswith("the kernel died (exit code 0) at cell 7 (“import os”)")


def test_an_exception_is_named_with_its_cell_and_text(batch):
    p = parts(batch, "exception")
    assert p["revolute"].score == 4
    assert p["angle"].message.startswith("`angle` is not assigned: cell 7 (“e0 = np.ones(1)”), under “**(b)** φ2 at "
                                         "t = 0.01 (radians), in `angle`.” raised ValueError: all the input array")


def test_an_output_flood_is_capped_and_graded_the_same_way_every_time(batch, tmp_path):
    from kinbook.classroom import grade_submission

    again = grade_submission(SOURCE, submission("flood"), timeout=ENOUGH, memory=400, isolation=BWRAP)
    first = batch["results"]["flood"]
    assert (again.status, again.score) == (first.status, first.score) == ("ok", FULL)


def test_a_locked_text_cell_edited_is_restored_and_a_classmates_notebook_is_named(batch):
    r = batch["results"]["edited_title"]
    assert r.score == FULL and "1 locked text cell(s) edited in the notebook were restored from the release" in r.message
    r = batch["results"]["classmate"]
    assert r.message == "this notebook was released for chen.wei, not for classmate"
    assert r.signals == [("released-for", "chen.wei")]  # the copying signal, in the gradebook for the instructor
    import sqlite3

    db = sqlite3.connect(batch["out"] / "gradebook.sqlite")
    assert ("classmate", "released-for", "chen.wei") in db.execute("SELECT student, kind, detail FROM signals").fetchall()
    assert "copying signal: classmate submitted a notebook that was not released for them" in " ".join(
        s for s in batch["progress"] if isinstance(s, str))


def test_links_and_copies_of_the_source_are_refused(batch):
    results = batch["results"]
    assert results["hardlink"].message.startswith("a hard link (one of 2 names of the same file")
    assert results["hardlink_classmate"].status == "refused"
    assert "identical to the instructor's source notebook" in results["source_copy"].message


def test_text_a_student_controls_is_inert_everywhere(batch):
    """Escapes that would set the terminal's title or overwrite a line, a carriage return that starts a formula
    row in a spreadsheet, bidirectional controls: stored, exported and printed as visible escapes."""
    import sqlite3

    r = batch["results"]["ansi"]
    message = parts(batch, "ansi")["angle"].message
    assert "\\x1b]0;pwned\\x07\\x1b[2K\\rok 6/6\\r\\n=cmd|' /C calc'!A0 \\u202egnp.exe\\u2028next" in message
    bad = set("\x1b\r\x07\u202e\u2028")
    db = sqlite3.connect(batch["out"] / "gradebook.sqlite")
    stored = " ".join(m for (m,) in db.execute("SELECT message FROM parts")) + r.message
    assert not bad & set(stored)
    raw = (batch["out"] / "grades.csv").read_bytes()
    assert b"\r" not in raw and b"\x1b" not in raw
    for line in raw.decode().splitlines():
        assert line.startswith('"') and line.endswith('"'), line   # every field quoted
    with open(batch["out"] / "grades.csv", newline="", encoding="utf-8") as f:
        for row in csv.reader(f):
            assert not any(field[:1] in "=+-@" for field in row if field), row


def test_grades_and_totals_csv(batch):
    with open(batch["out"] / "grades.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == COLUMNS
    assert len(rows) == 2 * len(batch["results"])  # every submission, refused ones included
    good = {r["part"]: r for r in rows if r["student"] == "good"}
    assert good["revolute"]["score"] == "4" and good["angle"]["max_score"] == "2"
    assert {r["status"] for r in rows} >= {"ok", "timeout", "memory", "error", "tampered", "missing-answer",
                                             "corrupt-notebook", "too-large", "refused", "duplicate-id", "bad-id",
                                             "wrong-release"}
    with open(batch["out"] / "totals.csv", newline="", encoding="utf-8") as f:
        totals = list(csv.DictReader(f))
    assert list(totals[0]) == TOTALS and len(totals) == len(batch["results"])
    ran = {t["student"]: t["isolation"] for t in totals}
    assert ran["good"].startswith("bubblewrap; " if BWRAP else "none; ") and ran["link_source"] == ""
    assert not [p for p in os.listdir(batch["out"]) if p.endswith(".tmp")]


def test_feedback_folder_per_student(batch):
    fb = batch["out"] / "feedback"
    assert sorted(os.listdir(fb)) == sorted(batch["results"])
    assert sorted(os.listdir(fb / "wrong")) == ["index.html", "tiny.html"]
    page = (fb / "wrong" / "tiny.html").read_text(encoding="utf-8")
    assert "revolute" in page and "<table" in page
    assert "Phi_OA = sp.Matrix([x1 + x2 + sp.cos(phi2), y1 + y2])" in page  # the student's own cell, as written
    # the answer as the grader read it, in plain text before the verdict (a feedback page has no MathJax; issue 29)
    assert 'your answer, as read: <code>[x1 + x2 + cos(phi2), y1 + y2]</code>' in page
    assert page.index("your answer, as read") < page.index("score 0.")


def test_rerun_skips_graded_submissions_unless_forced(batch, tmp_path):
    skipped = []
    again = grade(SOURCE, [submission("good"), submission("corrupt")], batch["out"], timeout=ENOUGH, memory=400,
                  isolation=BWRAP, progress=skipped.append)
    assert again == [] and any("skipped 2 file(s) graded before" in str(s) for s in skipped)
    forced = grade(SOURCE, [submission("corrupt")], batch["out"], force=True, isolation=BWRAP)
    assert [r.status for r in forced] == ["corrupt-notebook"]


def test_batch_throughput(batch):
    """A figure, not a verdict (speed targets live in benchmarks/: a loaded machine is slower, not wrong)."""
    n = len(batch["results"])
    print(f"\ngraded {n} submissions in {batch['seconds']:.1f} s with jobs=2")


def test_a_dying_grading_process_loses_nothing_else(tmp_path, monkeypatch):
    """A grading process killed in the middle of a submission (here: on purpose) is replaced; the submission
    is retried once, then recorded as `error`; the others are graded and grades.csv is complete."""
    import sys

    G = sys.modules["kinbook.classroom.grade"]  # (the package attribute `grade` is the function)

    original = G._grade_task

    def dying(args):
        if args[0].path.endswith("not_a_notebook.ipynb"):
            os._exit(1)
        return original(args)

    dying.__module__, dying.__qualname__ = original.__module__, original.__qualname__
    monkeypatch.setattr(G, "_grade_task", dying)
    subs = [submission("good"), submission("not_a_notebook"), submission("corrupt")]
    results = {r.student: r for r in grade(SOURCE, subs, tmp_path, timeout=ENOUGH, memory=400, jobs=2,
                                           isolation=BWRAP)}
    assert results["good"].score == FULL
    assert results["corrupt"].status == "corrupt-notebook"
    assert results["not_a_notebook"].status == "error" and "died" in results["not_a_notebook"].message
    with open(tmp_path / "grades.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert {r["student"] for r in rows} == {"good", "not_a_notebook", "corrupt"}
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".tmp")]


def test_reveal_hidden_gives_the_full_messages(tmp_path):
    from kinbook.classroom import grade_submission

    r = grade_submission(SOURCE, submission("wrong"), timeout=ENOUGH, memory=400, reveal_hidden=True,
                         isolation=BWRAP)
    angle = {p.part: p for p in r.parts}["angle"]
    assert "3.356" in angle.message and angle.html
