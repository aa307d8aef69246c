"""Grades no student can steer (issue 36): each class of attack on a *grade* — not on the sandbox — with the grade it
must get.

1. Only the grader can fail as the grader: a limit a submission reaches before its code runs is the submission's.
2. Who and when come from the LMS (the folder, the LMS's fields, the file's time), never from a name the student chose.
3. One student never stops a class.
4. The grader's own reading of student text is bounded (linear, or under a limit the submission pays).
5. Answers read before a failure are kept.
6. Reference use is read from what ran, and a student's own code is never called the library's.
"""

import copy
import json

import nbformat
import pytest

from kinbook.classroom import grade
from kinbook.classroom.notebook import (
    MAX_CELL_CHARS,
    MAX_NOTEBOOK_BYTES,
    load_source,
    parse_submission,
    student_notebook,
)
from kinbook.classroom.sandbox.protocol import MAX_JOB_BYTES, job_frame, read_job

from .conftest import BWRAP, ENOUGH, SOURCE
from .make_submissions import RIGHT_ANGLE, RIGHT_PHI

FULL = 6.0


def notebook(a=RIGHT_PHI, b=RIGHT_ANGLE, extra=(), ensure_ascii=True):
    """The tiny exercise's release with answer cells ``a`` and ``b`` and ``extra`` cells of the student's: its bytes."""
    released = student_notebook(load_source(SOURCE))
    ids = [c["id"] for c in released.cells if c.metadata.get("kinbook", {}).get("answer")]
    nb = copy.deepcopy(released)
    for c in nb.cells:
        if c["id"] in ids:
            c.source = a if c["id"] == ids[0] else b
    for k, src in enumerate(extra):
        cell = nbformat.v4.new_code_cell(src)
        cell["id"] = f"student-{k}"
        nb.cells.append(cell)
    return json.dumps(nb, ensure_ascii=ensure_ascii).encode("utf-8", "surrogatepass")


def put(path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    return path


# ================================================================ 1. only the grader can fail as the grader
#: Characters by how their JSON text compares with their UTF-8: 1 byte both (DEL, written raw), escaped in JSON
#: (quotes, controls), multi-byte, outside the BMP, a lone surrogate (escaped: 6 bytes; 3 in surrogatepass UTF-8).
CHARACTERS = ["\x7f", "a", '"', "\\", "\n", "\x00", "\x1f", "é", "\u2028", "\uffff", "\U0001F600", "\ud800"]


@pytest.mark.parametrize("char", CHARACTERS, ids=[f"U+{ord(c):04X}" for c in CHARACTERS])
def test_a_job_never_takes_more_than_twice_its_submission(char):
    """The job's payload (cells as UTF-8, the submission's copy) is at most twice the file, whatever the characters,
    so that a file under the cap always fits the worker's frame (a 6.9 MB notebook of DEL characters once made a
    48.5 MB job, over the old 40 MB limit: "grader-error", no score, retried forever)."""
    for ascii_ in (False, True) if char != "\ud800" else (True,):  # (a lone surrogate is JSON-escaped or not UTF-8)
        data = notebook(extra=[char * 5000], ensure_ascii=ascii_)
        cells = [c["source"] for c in parse_submission(data) if c["cell_type"] == "code"]
        header, payload = job_frame(cells, ["Phi_OA", "angle"], 60.0, {"submission.ipynb": data})
        assert len(payload) <= 2 * len(data)
        assert len(json.dumps(header)) < 64 * 1024
        assert read_job(json.loads(json.dumps(header)), payload)[0] == cells  # what was sent is what runs


def test_the_frame_limit_follows_from_the_submission_cap():
    """At the cap itself: the worst file (every character one byte in the file) fills the job to 2 × cap + header."""
    empty = len(notebook(extra=[""] * 9, ensure_ascii=False))
    per_cell = (MAX_NOTEBOOK_BYTES - empty - 100) // 9
    assert per_cell < MAX_CELL_CHARS
    data = notebook(extra=["\x7f" * per_cell] * 9, ensure_ascii=False)
    assert MAX_NOTEBOOK_BYTES - 1000 < len(data) <= MAX_NOTEBOOK_BYTES
    code = [c["source"] for c in parse_submission(data) if c["cell_type"] == "code"]
    header, payload = job_frame(code, ["Phi_OA", "angle"], 60.0, {"submission.ipynb": data})
    assert len(payload) + len(json.dumps(header)) + 64 <= MAX_JOB_BYTES


@pytest.mark.skipif(not BWRAP, reason="needs bubblewrap")
def test_a_notebook_of_del_characters_under_the_cap_is_graded(tmp_path):
    """The 6.9 MB notebook of DEL characters: graded (its answers right, its DEL cells a SyntaxError of its own):
    ok 6/6 — before: grader-error, no score, and tried again at every run."""
    junk = ["\x7f" * 990_000] * 7
    data = notebook(extra=junk, ensure_ascii=False)
    assert 6_900_000 < len(data) < MAX_NOTEBOOK_BYTES
    path = put(tmp_path / "collected" / "mallory" / "tiny.ipynb", data)
    (r,) = grade(SOURCE, [path.parent.parent], tmp_path / "graded", timeout=ENOUGH, memory=400, isolation=BWRAP)
    assert (r.student, r.status, r.score) == ("mallory", "ok", FULL)
