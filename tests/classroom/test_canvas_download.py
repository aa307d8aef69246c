"""Issue 20's batch (item 1, "Done when"): a Canvas-style bulk download of 30 students, graded with
``kinbook grade --id-pattern canvas``, grades every student and lists every file.

The download holds what a real one and a real instructor's unpacking leave: Canvas's bulk names
(``lastfirst_[late_]<user id>_<submission id>_<file>``), a browser's second download of a student's file
(``tiny (1).ipynb``: once a corrected file, once the same bytes), Canvas's resubmission suffixes (``tiny-1``,
``tiny-2``), hidden entries (Jupyter's ``.ipynb_checkpoints/``, a desktop's ``.Trash-0/``, macOS's ``__MACOSX/``,
``.DS_Store`` and an AppleDouble ``._…`` file) and a hard link to the instructor's source (``tar -xf`` of an archive
at the course root). The students hand in the committed fixture notebooks: correct (``good``), wrong (``wrong``),
half done (``partial``). Graded in the sandbox where bubblewrap works (else with the audit hook only).
"""

import csv
import hashlib
import os
import re
import shutil
import sqlite3

import pytest

from kinbook.cli import main

from .conftest import BWRAP, ENOUGH, SOURCE, submission

N = 30
IDS = [f"s{k:02d}" for k in range(1, N + 1)]
UID = {s: str(2000 + k) for k, s in enumerate(IDS, start=1)}
SUB = {s: str(70000 + k) for k, s in enumerate(IDS, start=1)}
WRONG, PARTIAL = {"s07", "s08", "s09"}, {"s10", "s11"}
FULL = 6.0                                                      # tiny.ipynb: 4 + 2 points


def canvas(s, file, late=False):
    return f"last{s}first{s}_{'late_' if late else ''}{UID[s]}_{SUB[s]}_{file}"


@pytest.fixture(scope="module")
def download(tmp_path_factory):
    root = tmp_path_factory.mktemp("canvas")
    course, collected = root / "course", root / "collected"
    course.mkdir()
    collected.mkdir()
    shutil.copy(SOURCE, course / "tiny.ipynb")
    (course / "canvas-grades.csv").write_text(
        "Student,ID,SIS User ID,SIS Login ID,Section,Tiny (555)\n    Points Possible,,,,,6\n"
        + "".join(f'"Last{s}, First{s}",{UID[s]},S{s},{s},A,\n' for s in IDS), encoding="utf-8")
    data = {kind: open(submission(kind), "rb").read() for kind in ("good", "wrong", "partial")}
    counting = {}                                               # student -> (file name, kind) that must count

    def put(name, kind):
        (collected / name).write_bytes(data[kind])
        return name, kind

    for s in IDS:
        kind = "wrong" if s in WRONG else "partial" if s in PARTIAL else "good"
        counting[s] = put(canvas(s, "tiny.ipynb", late=s == "s12"), kind)
    # a browser's second download: the student fixed their file and uploaded 'tiny (1).ipynb'
    put(canvas("s03", "tiny.ipynb"), "wrong")
    counting["s03"] = put(canvas("s03", "tiny (1).ipynb"), "good")
    # ... or downloaded the same file twice
    counting["s04"] = put(canvas("s04", "tiny (1).ipynb"), "good")
    # resubmissions: Canvas suffixes the same file name -1, -2 (the latest counts)
    put(canvas("s05", "tiny.ipynb"), "wrong")
    put(canvas("s05", "tiny-1.ipynb"), "partial")
    counting["s05"] = put(canvas("s05", "tiny-2.ipynb"), "good")
    put(canvas("s06", "tiny.ipynb"), "good")
    counting["s06"] = put(canvas("s06", "tiny-1.ipynb"), "wrong")        # a worse resubmission still counts
    # hidden entries: Jupyter's checkpoints, a desktop's trash, macOS's archive leftovers
    (collected / ".ipynb_checkpoints").mkdir()
    (collected / ".ipynb_checkpoints" / canvas("s01", "tiny-checkpoint.ipynb")).write_bytes(data["wrong"])
    (collected / ".Trash-0" / "files").mkdir(parents=True)
    (collected / ".Trash-0" / "files" / canvas("s02", "tiny.ipynb")).write_bytes(data["wrong"])
    (collected / "__MACOSX").mkdir()
    (collected / "__MACOSX" / f"._{canvas('s01', 'tiny.ipynb')}").write_bytes(b"\x00\x05\x16\x07")
    (collected / f"._{canvas('s02', 'tiny.ipynb')}").write_bytes(b"\x00\x05\x16\x07")
    (collected / ".DS_Store").write_bytes(b"\x00\x00\x00\x01Bud1")
    # a hard link to the instructor's source, under the exercise's own name
    os.link(course / "tiny.ipynb", collected / "tiny.ipynb")
    cwd = os.getcwd()
    os.chdir(root)
    try:
        argv = ["grade", "course/tiny.ipynb", "collected/", "-o", "graded/", "--roster", "course/canvas-grades.csv",
                "--id-pattern", "canvas", "--jobs", "2", "--timeout", str(ENOUGH), "--memory", "400"]
        status = main(argv + ([] if BWRAP else ["--no-isolation"]))
    finally:
        os.chdir(cwd)
    assert status == 0
    return {"root": root, "collected": collected, "counting": counting, "data": data,
            "db": sqlite3.connect(root / "graded" / "gradebook.sqlite")}


def test_every_student_is_graded_with_the_file_that_counts(download):
    db, counting, data = download["db"], download["counting"], download["data"]
    rows = {s: (sha, status, score) for s, sha, status, score in db.execute(
        "SELECT student, sha256, status, score FROM submissions WHERE exercise = 'tiny'")}
    assert sorted(rows) == IDS                                                 # 30 students, no one else
    for s, (name, kind) in counting.items():
        sha, status, score = rows[s]
        assert sha == hashlib.sha256(data[kind]).hexdigest(), (s, name)        # the latest attempt is graded
        assert (status, score) == {"good": ("ok", FULL), "wrong": ("ok", 0.0),
                                   "partial": ("missing-answer", 4.0)}[kind], s
    attempts = dict(db.execute("SELECT student, COUNT(*) FROM attempts WHERE exercise = 'tiny' GROUP BY student"))
    assert attempts["s05"] == 3 and attempts["s06"] == 2 and attempts["s03"] == 2   # earlier files kept as history


def test_every_file_is_listed_with_what_became_of_it(download):
    root, collected = download["root"], download["collected"]
    rows = list(csv.DictReader(open(root / "graded" / "collection.csv", encoding="utf-8")))
    listed = sorted(os.path.relpath(r["path"], "collected") for r in rows)
    assert listed == sorted(os.listdir(collected))                             # every entry: one row each
    db_rows = download["db"].execute("SELECT path, student, outcome, reason FROM files WHERE exercise = 'tiny'")
    assert sorted(os.path.relpath(p, "collected") for p, _, _, _ in db_rows) == listed   # and in the gradebook
    outcome = {os.path.relpath(r["path"], "collected"): (r["outcome"], r["student"], r["reason"]) for r in rows}
    graded = {n for n, (o, _, _) in outcome.items() if o == "graded"}
    assert graded == {name for name, _ in download["counting"].values()}
    superseded = sorted(n for n, (o, _, _) in outcome.items() if o == "superseded")
    assert superseded == sorted([canvas("s03", "tiny.ipynb"), canvas("s04", "tiny.ipynb"),
                                 canvas("s05", "tiny.ipynb"), canvas("s05", "tiny-1.ipynb"),
                                 canvas("s06", "tiny.ipynb")])
    assert all(outcome[n][1] in IDS for n in superseded)                       # attempts of a student, not students
    for hidden in (".ipynb_checkpoints", ".Trash-0", "__MACOSX", ".DS_Store", f"._{canvas('s02', 'tiny.ipynb')}"):
        assert outcome[hidden][0] == "ignored" and outcome[hidden][2], hidden  # with the reason
    assert outcome["tiny.ipynb"][0] == "refused" and "hard link" in outcome["tiny.ipynb"][2]


def test_the_run_says_what_it_did_not_grade(download, capsys):
    # the printed summary of a re-run (nothing new to grade) still accounts for every entry
    root = download["root"]
    cwd = os.getcwd()
    os.chdir(root)
    try:
        capsys.readouterr()
        assert main(["grade", "course/tiny.ipynb", "collected/", "-o", "graded/", "--id-pattern", "canvas",
                     "--timeout", str(ENOUGH)] + ([] if BWRAP else ["--no-isolation"])) == 0
    finally:
        os.chdir(cwd)
    out = capsys.readouterr().out
    n = len(os.listdir(download["collected"]))
    assert f"{n} entries found: {N} gradable, 5 ignored, 5 superseded, 1 refused — 0 to grade now" in out, out
    assert f"skipped {N} file(s) graded before" in out
    listed = re.findall(r"^(ignored|history|refused) +collected/(.+?): ", out, flags=re.M)
    assert len(listed) == n - N and ("refused", "tiny.ipynb") in listed       # each entry not graded, printed
