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
import os
import shutil
import tempfile
from pathlib import Path

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
from .make_submissions import RIGHT_ANGLE, RIGHT_PHI, WRONG_ANGLE, WRONG_PHI

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
    """The 6.9 MB notebook of DEL characters (in comments: the kernel reads them fast; the job is the same): graded,
    ok 6/6 — before: a 48.5 MB job over the 40 MB frame, grader-error, no score, and tried again at every run."""
    junk = ["#" + "\x7f" * 990_000] * 7
    data = notebook(extra=junk, ensure_ascii=False)
    assert 6_900_000 < len(data) < MAX_NOTEBOOK_BYTES
    path = put(tmp_path / "collected" / "mallory" / "tiny.ipynb", data)
    (r,) = grade(SOURCE, [path.parent.parent], tmp_path / "graded", timeout=ENOUGH, memory=400, isolation=BWRAP)
    assert (r.student, r.status, r.score) == ("mallory", "ok", FULL)


# ================================================================ 2. who and when come from the LMS
@pytest.mark.skipif(not BWRAP, reason="needs bubblewrap")
def test_a_file_naming_a_classmate_is_its_folders_students_and_a_look_alike_zeroes_nobody(tmp_path):
    """mallory's folder holds ``tiny-alice-9.ipynb`` (wrong answers): mallory's attempt, with a signal — alice's own
    correct file still counts (before: alice's latest attempt, 0/6). A folder ``ａｌｉｃｅ`` (full-width) beside
    ``alice``: a look-alike, its own duplicate-id with a signal — alice 6/6 (before: both duplicate-id, alice 0)."""
    c = tmp_path / "collected"
    put(c / "alice" / "tiny.ipynb", notebook())
    put(c / "mallory" / "tiny-alice-9.ipynb", notebook(WRONG_PHI, WRONG_ANGLE))
    put(c / "ａｌｉｃｅ" / "tiny.ipynb", notebook(WRONG_PHI, WRONG_ANGLE))
    said = []
    results = grade(SOURCE, [c], tmp_path / "graded", timeout=ENOUGH, memory=400, isolation=BWRAP,
                    progress=said.append)
    got = {r.student: (r.status, r.score) for r in results}
    assert got == {"alice": ("ok", FULL), "mallory": ("ok", 0.0), "ａｌｉｃｅ": ("duplicate-id", 0.0)}
    by = {r.student: r for r in results}
    assert by["mallory"].signals == [("names-another", "the file's name 'tiny-alice-9.ipynb' names 'alice', not the "
                                                       "student of its folder")]
    assert by["ａｌｉｃｅ"].signals == [("look-alike", "the id 'ａｌｉｃｅ' looks like 'alice'")]
    assert "alice" not in by["ａｌｉｃｅ"].message.replace("ａｌｉｃｅ", "")  # nothing of a classmate on the page
    assert sum(isinstance(s, str) and s.startswith("signal: ") for s in said) == 2
    from kinbook.classroom.gradebook import Gradebook
    from kinbook.classroom.report.tables import copying

    with Gradebook(tmp_path / "graded") as book:
        rows = copying(book, "tiny")
    assert {r["students"] for r in rows if r["kind"] == "an id that is not the file's student's"} == {
        "mallory", "ａｌｉｃｅ"}


def test_a_look_alike_folder_is_not_mapped_to_the_roster_student(tmp_path):
    """With a roster, ``ａｌｉｃｅ/`` beside ``alice/``: alice's own file is her only attempt, the look-alike a
    duplicate-id with a signal (before: the roster mapped both to alice, and the later file counted); ``Alice/``
    (case only) is alice's, as an LMS's export may spell her."""
    from kinbook.classroom.files import collect
    from kinbook.classroom.roster import read_roster

    (tmp_path / "roster.csv").write_text("student,name\nalice,Alice A\nmallory,Mallory M\n")
    roster = read_roster(tmp_path / "roster.csv")
    c = tmp_path / "c"
    put(c / "alice" / "tiny.ipynb", b"{}")
    put(c / "ａｌｉｃｅ" / "tiny.ipynb", b"{}")
    found = {e.path.split("/c/", 1)[1]: e for e in collect([c], "tiny", max_bytes=1000, roster=roster)}
    assert (found["alice/tiny.ipynb"].student, found["alice/tiny.ipynb"].status) == ("alice", None)
    fake = found["ａｌｉｃｅ/tiny.ipynb"]
    assert (fake.student, fake.status, fake.on_roster) == ("ａｌｉｃｅ", "duplicate-id", False)
    assert fake.signals == [("look-alike", "the id 'ａｌｉｃｅ' looks like 'alice'")]
    put(tmp_path / "d" / "Alice" / "tiny.ipynb", b"{}")
    (e,) = collect([tmp_path / "d"], "tiny", max_bytes=1000, roster=roster)
    assert (e.student, e.status, e.on_roster) == ("alice", None, True)


def _stamped(tmp_path, name, mtime):
    path = put(tmp_path / name, b"{}")
    os.utime(path, (mtime, mtime))
    return path


@pytest.mark.parametrize("layout, pattern", [
    ("ana/tiny_2026-02-01.ipynb", None),
    ("tiny-ana-2026-02-01T0000.ipynb", None),
    ("Ana García_123456_assignsubmission_file_/tiny_2026-02-01.ipynb", "moodle"),
    ("garciaana_123456_789_tiny_2026-02-01.ipynb", "canvas"),
])
def test_the_time_is_the_lms_or_the_files_never_a_date_the_student_wrote(tmp_path, layout, pattern):
    """An upload named ``…_2026-02-01.ipynb`` handed in on 2026-02-06: 2026-02-06 with --file-times (late), nothing
    without (before: 2026-02-01, on time, in Moodle's layout and the default one)."""
    from kinbook.classroom.files import collect

    handed_in = 1_770_336_000  # 2026-02-06T00:00:00Z
    _stamped(tmp_path / "c", layout, handed_in)
    (e,) = collect([tmp_path / "c"], "tiny", max_bytes=1000, pattern=pattern, file_times=True)
    assert (e.submitted, e.submitted_from) == ("2026-02-06T00:00:00+00:00", "file")
    (e,) = collect([tmp_path / "c"], "tiny", max_bytes=1000, pattern=pattern)
    assert e.submitted == ""


def test_a_time_the_lms_writes_in_its_own_field_is_read():
    from kinbook.classroom.naming import compile_pattern, read_name

    name = read_name(("HW_ana_attempt_2026-02-06-00-00-00_tiny_2026-02-01.ipynb",), "tiny", "c",
                     compile_pattern("blackboard"))
    assert (name.raw, name.time.isoformat()) == ("ana", "2026-02-06T00:00:00")


def test_canvas_attachment_ids_are_files_of_one_submission(tmp_path):
    """Canvas's download holds a student's current submission only, each file named by its attachment id
    (lib/content_zipper.rb): two notebooks of one standing are both graded and the best counts; the id orders
    nothing, and a name's attempt suffix orders only the student's own files."""
    from kinbook.classroom.files import collect

    c = tmp_path / "c"
    put(c / "garciaana_123456_900_tiny.ipynb", b"{}")
    put(c / "garciaana_123456_901_tiny.ipynb", b"{}")
    put(c / "ruizluis_123457_905_tiny.ipynb", b"{}")
    put(c / "ruizluis_123457_902_tiny-1.ipynb", b"{}")    # Canvas's "-1": the same name uploaded again
    found = {e.path.rsplit("/", 1)[1]: e.status for e in collect([c], "tiny", max_bytes=1000, pattern="canvas")}
    assert found == {"garciaana_123456_900_tiny.ipynb": None, "garciaana_123456_901_tiny.ipynb": None,
                     "ruizluis_123457_905_tiny.ipynb": "superseded", "ruizluis_123457_902_tiny-1.ipynb": None}


@pytest.mark.skipif(not os.path.isdir("/dev/shm"), reason="needs a tmpfs (ext4 holds no time past the year 2446)")
def test_a_file_time_past_the_year_9999_is_that_submissions_problem(tmp_path):
    """One file dated in the year 33658: that file reads as handed in at the end of time (late), and the run grades
    everyone (before: ``internal error: ValueError`` and nobody graded)."""
    from kinbook.classroom.files import collect

    d = tempfile.mkdtemp(dir="/dev/shm")
    try:
        far = _stamped(Path(d), "eve/tiny.ipynb", 10**12)
        _stamped(Path(d), "ana/tiny.ipynb", 1_770_336_000)
        assert os.stat(far).st_mtime == 10**12
        found = {e.student: e.submitted for e in collect([d], "tiny", max_bytes=1000, file_times=True)}
        assert found == {"eve": "9999-12-31T23:59:59+00:00", "ana": "2026-02-06T00:00:00+00:00"}
        with pytest.warns(RuntimeWarning):  # (corrupt notebooks: nothing runs)
            results = grade(SOURCE, [d], tmp_path / "graded", isolation=False, file_times=True)
        assert sorted((r.student, r.status) for r in results) == [("ana", "corrupt-notebook"),
                                                                  ("eve", "corrupt-notebook")]
    finally:
        shutil.rmtree(d)


# ================================================================ 3. one student never stops a class
def _ex11():
    return os.path.join(os.path.dirname(SOURCE), "..", "..", "..", "exercises",
                        "ex11-rotations-euler-parameters.ipynb")


@pytest.mark.skipif(not BWRAP, reason="needs bubblewrap")
def test_one_students_copies_of_the_generic_release_never_stop_the_class(tmp_path):
    """alice and bob hand in their variants (correct), mallory three copies of the generic release (policy best):
    alice and bob 10/10, mallory's three files wrong-release (before: rc 2, "Nothing was graded"); and --generic, which
    would wrong the class, is refused with the right advice (before: advised, and it made alice and bob tampered)."""
    from kinbook.classroom import student_parameters
    from kinbook.classroom.release import write_notebook
    from kinbook.errors import GradingError

    src = _ex11()
    source = load_source(src)
    subs = tmp_path / "subs"
    for student in ("alice", "bob"):
        write_notebook(student_notebook(source, student_parameters(source, student), student, keep_solutions=True),
                       subs / student / f"{source.exercise}.ipynb")
    for copy_ in ("", " (1)", " (2)"):
        write_notebook(student_notebook(source, keep_solutions=True), subs / "mallory" / f"{source.exercise}{copy_}.ipynb")
    out = tmp_path / "graded"
    results = grade(src, [subs], out, timeout=ENOUGH, memory=600, jobs=2, isolation=BWRAP, policy="best")
    got = sorted((r.student, r.status, r.score) for r in results)
    assert got == [("alice", "ok", 10.0), ("bob", "ok", 10.0)] + [("mallory", "wrong-release", 0.0)] * 3
    with pytest.raises(GradingError, match=r"2 of 3 students handed in per-student variants .* without --generic"):
        grade(src, [subs], out, timeout=ENOUGH, memory=600, isolation=BWRAP, generic=True, force=True)


@pytest.mark.skipif(not BWRAP, reason="needs bubblewrap")
def test_grading_with_the_wrong_release_option_never_calls_an_honest_student_tampered(tmp_path):
    """Graded with --generic, alice's own variant is not run and says why (wrong-release, never tampered); the next run
    without --generic grades her again — not "graded before" — and she gets 10/10."""
    from kinbook.classroom import student_parameters
    from kinbook.classroom.release import write_notebook

    src = _ex11()
    source = load_source(src)
    subs = tmp_path / "subs"
    write_notebook(student_notebook(source, student_parameters(source, "alice"), "alice", keep_solutions=True),
                   subs / "alice" / f"{source.exercise}.ipynb")
    write_notebook(student_notebook(source), subs / "carol" / f"{source.exercise}.ipynb")
    out = tmp_path / "graded"
    first = {r.student: r for r in grade(src, [subs], out, timeout=ENOUGH, memory=600, isolation=BWRAP,
                                         generic=True)}
    assert first["alice"].status == "wrong-release" and "grade it without --generic" in first["alice"].message
    assert (first["carol"].status, first["carol"].score) == ("missing-answer", 0.0)  # the generic release, blank
    again = {r.student: (r.status, r.score) for r in grade(src, [subs], out, timeout=ENOUGH, memory=600,
                                                           isolation=BWRAP)}
    assert again == {"alice": ("ok", 10.0)}  # carol's: graded before


# ================================================================ 4. the grader's own reading is bounded
def _reading(data):
    """Everything the grading process does with a submission's text outside the sandbox: parse it, look for whom it
    was released for, follow reference use, find where each answer was assigned and name the cells."""
    import importlib

    from kinbook.classroom.answers import describe
    from kinbook.classroom.reference_use import reference_use
    from kinbook.classroom.release_kind import released_for
    from kinbook.classroom.results import PartGrade
    from kinbook.classroom.variant import references

    g = importlib.import_module("kinbook.classroom.grade")
    src = load_source(SOURCE)
    parts = references(src)
    cells, meta = parse_submission(data, metadata=True)
    released_for(meta, cells, "ana", False)
    code = [c["source"] for c in cells if c["cell_type"] == "code"]
    reference_use(code, [p.answer for p in parts], calls=g._reference_calls(src), locked=[],
                  numbers=list(range(1, len(code) + 1)))
    describe([PartGrade(p.name, 0.0, p.points, "missing-answer", "") for p in parts], parts, {}, cells)
    g._cell_name(cells, len(code))


def _cpu(f, *args):
    import time

    best = float("inf")
    for _ in range(2):
        t0 = time.process_time()
        f(*args)
        best = min(best, time.process_time() - t0)
    return best


#: The analyses' cap (a notebook's code beyond it is not parsed) and one cell's (beyond the cap: read by patterns).
AT_CAP = 299_000
WORST = {  # each the worst known input of a reader of student text, at a cap
    "paren-newlines": "(" + "\n" * AT_CAP,                  # ^\s* (IPython escapes, assignments): 46 s at 60,000
    "paren-newlines-1M": "(" + "\n" * (MAX_CELL_CHARS - 10),  # the same beyond the parsing cap (patterns only)
    "spaces": " " * AT_CAP,
    "equals-spaces": "=" + " " * AT_CAP,
    "questions": "?" * AT_CAP,
    "item-brackets": "Phi_OA[" + "[" * AT_CAP,
    "nested": "(" * AT_CAP,
    "chain": "".join(f"a{i} = a{i - 1}\n" for i in range(1, 40_000))[:AT_CAP],
    "rows": "Phi_OA = [" + "1," * (AT_CAP // 2 - 10) + "]",
    "magics": ("%time x = 1\n" * (AT_CAP // 12)),
    "released-for": ("# parameters of student '" + "a' " * 60) * (AT_CAP // 200),
}


@pytest.fixture(scope="module")
def plain_reading():
    return _cpu(_reading, notebook(extra=[("x = 1\n" * (AT_CAP // 6))]))


@pytest.mark.parametrize("name", sorted(WORST))
def test_the_graders_reading_of_the_worst_text_costs_what_a_plain_notebook_does(name, plain_reading):
    """The grading process's own reading of each worst input costs at most 3 × a plain notebook of the same size's
    (a ratio, never a budget in seconds: the same on any machine). Before, ``(`` plus 60,000 newlines cost 28 s of
    CPU here against 0.6 s (x 50), and about 19 minutes at the 300,000-character cap."""
    data = notebook(extra=[WORST[name]])
    assert len(data) <= MAX_NOTEBOOK_BYTES
    assert _cpu(_reading, data) <= 3 * plain_reading


def test_decoding_an_answer_reads_a_long_number_only_once(monkeypatch):
    """A float answer of 2,000,000 digits that does not match (``1…1x``) is refused by its length, before any pattern
    reads it (before: the pattern ran first and backtracked quadratically, ~16 s at 20,000 digits). Counted: the
    characters the decoder's patterns are given."""
    import re

    import kinbook.classroom.serialize as serialize
    from kinbook.classroom.serialize import decode_answers

    read = []

    class Counting:
        def __getattr__(self, name):
            return getattr(re, name)

        @staticmethod
        def fullmatch(pattern, text, *args):
            read.append(len(text))
            return re.fullmatch(pattern, text, *args)

    monkeypatch.setattr(serialize, "re", Counting())
    evil = {"x": {"kind": "sympy", "shape": [1, 1], "data": [["Float", "1" * 2_000_000 + "x"]]}}
    assert decode_answers(evil, ["x"])[1] == {"x": "bad float"}
    assert sum(read) <= 40


# ================================================================ 5. answers read before a failure are kept
FILL = """for d in ('/tmp', '/home/student', '.'):
    try:
        with open(d + '/fill', 'wb') as f:
            while True:
                f.write(b'x' * 2**20)
    except OSError as e:
        print(d, e)"""


@pytest.mark.skipif(not BWRAP, reason="needs bubblewrap")
def test_a_notebook_that_fills_its_directories_keeps_the_answers_read_before(tmp_path):
    """Right answers, then /tmp and the home directory filled to their caps, then memory: memory, 6/6 (the answers
    read before the failing cell are graded; the issue saw "memory 0/11")."""
    path = put(tmp_path / "collected" / "ana" / "tiny.ipynb",
               notebook(extra=[FILL, "hog = []\nwhile True:\n    hog.append(bytearray(2**20))"]))
    (r,) = grade(SOURCE, [path.parent.parent], tmp_path / "graded", timeout=ENOUGH, memory=300, isolation=BWRAP)
    assert (r.status, r.score) == ("memory", FULL)


class _Unhooked(__import__("kinbook.classroom.sandbox", fromlist=["Sandbox"]).Sandbox):
    """A sandbox running notebooks without the audit hook: what a student who switched it off can do."""

    def run(self, cells, names, **kw):
        return super().run(cells, names, **{**kw, "audit_hook": False})


@pytest.mark.skipif(not BWRAP, reason="needs bubblewrap")
def test_answers_read_before_the_worker_is_killed_are_graded(tmp_path, monkeypatch):
    """With the audit hook off, a notebook kills every process of the sandbox it may signal (its worker included)
    after its answers were read: the worker never writes a result, and the answers it sent after each cell are
    graded — error, 6/6 (before: error, 0/6: nothing was kept when the worker died)."""
    import importlib

    # patched where it is used: grade.py imports Sandbox when it is imported
    monkeypatch.setattr(importlib.import_module("kinbook.classroom.grade"), "Sandbox", _Unhooked)
    path = put(tmp_path / "collected" / "ana" / "tiny.ipynb",
               notebook(extra=["import os, signal\nos.kill(-1, signal.SIGKILL)"]))
    (r,) = grade(SOURCE, [path.parent.parent], tmp_path / "graded", timeout=ENOUGH, memory=400, isolation=BWRAP)
    assert (r.status, r.score) == ("error", FULL), r.message
    assert "the answers read after code cell" in r.message


# ================================================================ 6. reference use read from what ran
RIGHT_BY_HAND = "sp.Matrix([x1 - x2 + sp.cos(phi2), y1 - y2 + sp.sin(phi2)])"
#: Φ of joint 1 taken from kinbook's reference, in spellings the reading of the code does not follow (each full marks
#: with an empty reference column before).
HIDDEN = {
    "prompt": ">>> Phi_OA = mech.constraint_phi('1')",
    "indented": "    Phi_OA = mech.constraint_phi('1')",
    "semicolon-exec": ";exec Phi_OA = mech.constraint_phi('1')",
    "bare-time": "time Phi_OA = mech.constraint_phi('1')",
    "getattribute": "Phi_OA = mech.__getattribute__('constraint_phi')('1')",
    "object-getattribute": "Phi_OA = object.__getattribute__(mech, 'constraint_phi')('1')",
    "reduce-getattr": "import functools\nPhi_OA = functools.reduce(getattr, ['constraint_phi'], mech)('1')",
    "attrgetter": "import operator\nPhi_OA = operator.attrgetter('constraint' + '_phi')(mech)('1')",
    "match-class": "match mech:\n    case object(constraint_phi=f):\n        Phi_OA = f('1')",
    "sympify-locals": "Phi_OA = sp.sympify(\"m.constraint_phi('1')\", locals={'m': mech})",
    "timeit-globals": "import timeit\nout = {}\ntimeit.timeit(\"out['P'] = m.constraint_phi('1')\", "
                      "globals={'m': mech, 'out': out}, number=1)\nPhi_OA = out['P']",
}
#: A student's own code with the library's names: never reported as the library's.
OWN = {
    "own-method": f"class Mine:\n    def constraint_phi(self, k):\n        return {RIGHT_BY_HAND}\n"
                  "Phi_OA = Mine().constraint_phi('1')",
    "own-function": f"def constraint_phi(k):\n    return {RIGHT_BY_HAND}\nPhi_OA = constraint_phi('1')",
    "own-joint": f"class Joint:\n    def __init__(self, *a):\n        pass\n    def symbolic(self):\n"
                 f"        return {RIGHT_BY_HAND}\nPhi_OA = Joint(1, 2).symbolic()",
    "own-phi": f"class C:\n    def phi(self):\n        return {RIGHT_BY_HAND}\nPhi_OA = C().phi()",
    # an object of the student's own class that holds kinbook's mechanism: its own method is still the student's
    # (before: "m.constraint_phi() (cell 4)", read from the code)
    "own-wrapper": f"class M:\n    def __init__(self, mech):\n        self.mech = mech\n"
                   f"    def constraint_phi(self, k):\n        return {RIGHT_BY_HAND}\n"
                   "m = M(mech)\nPhi_OA = m.constraint_phi('1')",
    "by-hand": f"Phi_OA = {RIGHT_BY_HAND}",
}


@pytest.fixture(scope="module")
def reference_batch(tmp_path_factory):
    if not BWRAP:
        pytest.skip("needs bubblewrap")
    root = tmp_path_factory.mktemp("reference")
    for name, code in {**HIDDEN, **OWN, "checked": f"Phi_OA = {RIGHT_BY_HAND}\n"
                                                  "assert mech.constraint_phi('1') == Phi_OA"}.items():
        put(root / "c" / name / "tiny.ipynb", notebook(code))
    return {r.student: r for r in grade(SOURCE, [root / "c"], root / "graded", timeout=ENOUGH, memory=400, jobs=2,
                                        isolation=BWRAP)}


@pytest.mark.parametrize("student", sorted(HIDDEN))
def test_reference_use_is_seen_however_it_is_spelled(reference_batch, student):
    r = reference_batch[student]
    assert (r.status, r.score) == ("ok", FULL)  # reported, not penalized
    assert r.parts[0].reference == "kinbook.core.mechanism.MechanismBase.constraint_phi() (cell 4, as run)"


@pytest.mark.parametrize("student", sorted(OWN))
def test_a_students_own_code_is_never_reported_as_the_librarys(reference_batch, student):
    r = reference_batch[student]
    assert (r.status, r.score, [p.reference for p in r.parts]) == ("ok", FULL, ["", ""])


def test_an_answer_checked_against_the_reference_says_so(reference_batch):
    """Typed by hand, then compared with the reference in the same cell: reported as equal to its result (for the
    instructor's judgement; the very object would read "as run")."""
    assert reference_batch["checked"].parts[0].reference == (
        "kinbook.core.mechanism.MechanismBase.constraint_phi() (cell 4, as run: equal to its result)")


@pytest.mark.skipif(not BWRAP, reason="needs bubblewrap")
def test_random_generators_are_seeded_from_the_student():
    """random, numpy.random and sympy's generator: the same numbers for one student on every run, others for
    another student (before: numpy's from the clock, sympy's the same for everyone)."""
    from kinbook.classroom.sandbox import Sandbox
    from kinbook.classroom.variant import seed_from

    cells = ["import random, numpy as np, sympy.core.random as sr\n"
             "r = [random.random(), float(np.random.random()), sr.random()]"]
    draws = {}
    with Sandbox(BWRAP) as sb:
        for student in ("ana", "ben", "ana"):
            ex = sb.run(cells, ["r"], timeout=ENOUGH, memory_mb=400, setup={"seed": seed_from(f"tiny:{student}")})
            draws.setdefault(student, []).append(ex.answers["r"]["data"])
    assert draws["ana"][0] == draws["ana"][1]
    assert all(a != b for a, b in zip(draws["ana"][0], draws["ben"][0]))
