"""Source notebooks, releases, answers as data, the audit hook — without running submissions."""

import json
import os
import subprocess
import sys

import nbformat
import numpy as np
import pytest
import sympy as sp

from kinbook.classroom import part, release
from kinbook.classroom.notebook import load_source, locked_checksums, student_notebook
from kinbook.classroom.serialize import DecodeError, decode, dumps, encode
from kinbook.classroom.variant import references
from kinbook.cli import main
from kinbook.errors import GradingError, OverwriteError

from .conftest import BWRAP, SOURCE


def test_release_replaces_solutions_and_drops_hidden_checks(tmp_path):
    (path,) = release([SOURCE], tmp_path)
    nb = nbformat.read(str(path), 4)
    text = "\n".join(c.source for c in nb.cells)
    assert "BEGIN SOLUTION" not in text and "sp.cos(phi2)" not in text
    assert "HIDDEN" not in text and 'part("angle"' not in text and "solve_position" not in text
    assert text.count("raise NotImplementedError()") == 2
    locked = [c for c in nb.cells if c.metadata["kinbook"].get("locked")]
    assert all(c.metadata["editable"] is False for c in locked)
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    assert manifest["tiny"]["locked"] == locked_checksums(nb)
    assert [p["part"] for p in manifest["tiny"]["parts"]] == ["revolute", "angle"]
    assert [p["hidden"] for p in manifest["tiny"]["parts"]] == [False, True]


def test_release_refuses_to_overwrite_its_source(tmp_path):
    import shutil

    src = tmp_path / "tiny.ipynb"
    shutil.copy(SOURCE, src)
    before = src.read_bytes()
    with pytest.raises(OverwriteError, match="release would write over its own input.*is the source"):
        release([src], tmp_path)
    assert src.read_bytes() == before and sorted(os.listdir(tmp_path)) == ["tiny.ipynb"]


def test_references_come_from_kinbook_in_the_grader():
    parts = references(load_source(SOURCE))
    assert [(p.name, p.points, p.check, p.hidden) for p in parts] == [
        ("revolute", 4.0, "phi", False), ("angle", 2.0, "value", True)]
    assert parts[1].expected == pytest.approx(3 * np.pi / 4 + 1.0)


def test_solution_notebook_has_no_markers():
    nb = student_notebook(load_source(SOURCE), keep_solutions=True)
    text = "\n".join(c.source for c in nb.cells)
    assert "sp.cos(phi2)" in text and "###" not in text


def test_unclosed_region_is_an_error(tmp_path):
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("### BEGIN SOLUTION\nx = 1")])
    nbformat.write(nb, str(tmp_path / "bad.ipynb"))
    with pytest.raises(GradingError, match="not closed"):
        load_source(tmp_path / "bad.ipynb")


def test_part_declarations_are_validated():
    with pytest.raises(GradingError, match="unknown check 'phii'"):
        part("a", 1, answer="x", check="phii", target=object())
    with pytest.raises(GradingError, match="needs expected="):
        part("a", 1, answer="x", check="value")


@pytest.mark.parametrize("value", [
    1.5, 3, np.float64(2.0), np.arange(6.0).reshape(2, 3), [1.0, float("nan")], [[1, 2], [3, 4]],
])
def test_numbers_round_trip(value):
    rec = json.loads(json.dumps(encode(value)))
    np.testing.assert_array_equal(np.asarray(decode(rec), float), np.asarray(value, float))


def test_sympy_round_trip():
    x1, phi2 = sp.symbols("x1 phi2")
    M = sp.Matrix([x1 - sp.cos(phi2) / 2 + sp.pi, sp.atan2(x1, 2) * sp.exp(-phi2) + sp.Rational(1, 3)])
    back = decode(json.loads(dumps(["M"], {"M": M}))["answers"]["M"])
    assert back.shape == (2, 1)
    assert back == M.subs({x1: sp.Symbol("x1"), phi2: sp.Symbol("phi2")})  # the same tree, rebuilt


def test_strings_cross_as_text_and_are_never_parsed_by_sympy():
    """A string is not parsed in the kernel (no sympify there either): it reaches the checker as the student
    typed it, and the checker reads it with the safe reader."""
    rec = json.loads(json.dumps(encode(["x1 + sin(phi2)^2", 0])))
    assert rec == {"kind": "sympy", "shape": [2, 1], "data": [["Text", "x1 + sin(phi2)^2"], ["Integer", "0"]]}
    assert decode(rec) == [["x1 + sin(phi2)^2"], [sp.Integer(0)]]
    hostile = encode(["__import__('os').system('touch /tmp/kinbook-evil.txt')"])
    assert decode(hostile) == [["__import__('os').system('touch /tmp/kinbook-evil.txt')"]]


def test_a_power_tower_is_refused_in_microseconds():
    """Unevaluated powers, each within every per-node cap, that would take minutes to evaluate."""
    import time

    big = sp.Integer(10 ** 40)
    tower = sp.Pow(big, sp.Pow(big, sp.Pow(big, 99, evaluate=False), evaluate=False), evaluate=False)
    rec = encode(sp.Matrix([tower * sp.Symbol("x1"), tower]))
    t0 = time.process_time()  # CPU time, not the clock: a loaded machine is slower, not wrong
    with pytest.raises(DecodeError, match="not gradable data"):
        decode(rec)
    assert time.process_time() - t0 < 0.5  # (in practice well under a millisecond)


@pytest.mark.parametrize("record, match", [
    ({"kind": "sympy", "shape": [1, 1], "data": [["eval", ["Symbol", "x"]]]}, "not allowed"),
    ({"kind": "sympy", "shape": [1, 1], "data": [["Symbol", "__import__('os')"]]}, "bad symbol"),
    ({"kind": "sympy", "shape": [1, 1], "data": [["Integer", "9" * 500]]}, "bad integer"),
    ({"kind": "sympy", "shape": [1, 1], "data": [["Pow", ["Symbol", "x"], ["Integer", "100000"]]]}, "exponent"),
    ({"kind": "sympy", "shape": [1, 1], "data": [["Symbol", "sin"]]}, "named like a function"),
    ({"kind": "sympy", "shape": [1, 1], "data": [["Text", "x" * 30000]]}, "longer than"),
    ({"kind": "sympy", "shape": [1, 1], "data": [["Float", "1e400"]]}, "not gradable"),
    ({"kind": "array", "shape": [2], "data": [1, "os.system('x')"]}, "numbers"),
    ({"kind": "array", "shape": [3], "data": [1, 2]}, "entries"),
    ({"kind": "pickle", "shape": [], "data": ["gASV"]}, "unknown answer kind"),
    ({"kind": "unsupported", "type": "function"}, "cannot be graded"),
    ("not a dict", "must be an object"),
])
def test_decode_refuses_anything_but_whitelisted_data(record, match):
    with pytest.raises(DecodeError, match=match):
        decode(record)


def test_decode_caps_depth():
    t = ["Symbol", "x"]
    for _ in range(500):
        t = ["sin", t]
    with pytest.raises(DecodeError, match="deeper"):
        decode({"kind": "sympy", "shape": [1, 1], "data": [t]})


def test_audit_hook_confines_a_process(tmp_path):
    """The hook of the sandboxed kernel, installed in a throw-away interpreter."""
    code = f"""
import os, sys, builtins, gc
from kinbook.classroom.sandbox.kernel import install_audit_hook, _read_roots
os.chdir({str(tmp_path)!r})
install_audit_hook({str(tmp_path)!r}, _read_roots())
def attempt(f):
    try:
        f(); return 'allowed'
    except PermissionError:
        return 'refused'
os.path.realpath = lambda p: {str(tmp_path)!r}   # monkeypatching os does not change the hook's decisions
out = dict(
    write_inside=attempt(lambda: open('ok.txt', 'w').write('x')),
    read_inside=attempt(lambda: open('ok.txt').read()),
    read_stdlib=attempt(lambda: open(os.__file__).read()),
    read_etc=attempt(lambda: open('/etc/hostname').read()),
    dotdot=attempt(lambda: open('../' * 10 + 'etc/hostname').read()),
    write_tmp=attempt(lambda: open('/tmp/kinbook-hook-test', 'w')),
    os_open=attempt(lambda: os.open('/tmp/kinbook-hook-test', os.O_WRONLY | os.O_CREAT)),
    remove=attempt(lambda: os.remove('/tmp/kinbook-hook-test')),
    listdir=attempt(lambda: os.listdir('/')),
    symlink=attempt(lambda: os.symlink('/etc', 'etc')),
    system=attempt(lambda: os.system('true')),
    fork=attempt(lambda: os.fork()),
    gc=attempt(lambda: gc.get_objects()),
    chdir=attempt(lambda: os.chdir('/')),
    dir_fd=attempt(lambda: os.open(os.path.dirname(os.__file__), os.O_RDONLY)),
    remove_dir_fd=attempt(lambda: os.remove('x', dir_fd=os.open('.', os.O_RDONLY))),
    fchmod=attempt(lambda: os.chmod(os.open(os.__file__, os.O_RDONLY), 0o777)),
    mkdir_inside=attempt(lambda: os.mkdir('sub')),
    pidfd=str(hasattr(os, 'pidfd_open') or hasattr(__import__('signal'), 'pidfd_send_signal')),
    fresh_posix=attempt(lambda: (sys.modules.pop('posix'), __import__('posix'))),
    mkfifo=str(hasattr(os, 'mkfifo') or hasattr(os, 'mknod')),
    subinterpreter=attempt(lambda: __import__('_xxsubinterpreters')),
    code=attempt(lambda: setattr(attempt, '__code__', (lambda f: 'allowed').__code__)),
)
print(out)
"""
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    out = eval(res.stdout.strip().splitlines()[-1])  # our own subprocess's dict of words, not student text
    assert out == dict(write_inside="allowed", read_inside="allowed", read_stdlib="allowed", read_etc="refused",
                       dotdot="refused", write_tmp="refused", os_open="refused", remove="refused",
                       listdir="refused", symlink="refused", system="refused", fork="refused", gc="refused",
                       chdir="refused", dir_fd="refused", remove_dir_fd="refused", fchmod="refused",
                       mkdir_inside="allowed", pidfd="False", fresh_posix="refused", mkfifo="False",
                       subinterpreter="refused", code="refused")


def test_cli_variant(tmp_path, capsys):
    import os

    ex11 = os.path.join(os.path.dirname(SOURCE), "..", "..", "..", "exercises", "ex11-rotations-euler-parameters.ipynb")
    assert main(["variant", ex11, "--student", "alice", "-o", str(tmp_path)]) == 0
    out = tmp_path / "ex11-rotations-euler-parameters-alice.ipynb"
    assert str(out) in capsys.readouterr().out
    assert "parameters of student 'alice'" in "".join(c.source for c in nbformat.read(str(out), 4).cells)


def test_cli_errors_are_reported_not_raised(tmp_path, capsys):
    assert main(["release", str(tmp_path / "nope.ipynb"), "-o", str(tmp_path)]) == 2
    assert "no such file" in capsys.readouterr().err


def test_cli_release(tmp_path, capsys):
    assert main(["release", SOURCE, "-o", str(tmp_path)]) == 0
    assert (tmp_path / "tiny.ipynb").exists()
    extra = [] if BWRAP else ["--no-isolation"]
    corrupt = tmp_path / "corrupt.ipynb"  # a missing path is a usage error (exit 2); a corrupt file is graded
    corrupt.write_text("{not a notebook")
    assert main(["grade", SOURCE, str(corrupt), "-o", str(tmp_path / "g")] + extra) == 0
    assert "corrupt-notebook" in (tmp_path / "g" / "grades.csv").read_text()


def test_collected_directories_yield_this_exercise_only(tmp_path):
    from kinbook.classroom.files import collect

    for student in ("alice", "bob"):
        (tmp_path / student).mkdir()
        (tmp_path / student / "ex01.ipynb").write_text("{}")
        (tmp_path / student / "ex02.ipynb").write_text("{}")
    (tmp_path / "ex01-carol.ipynb").write_text("{}")
    found = collect([tmp_path], "ex01", max_bytes=1000)
    assert sorted(e.student for e in found if e.status is None) == ["alice", "bob", "carol"]
    others = sorted((e.path[len(str(tmp_path)) + 1:], e.status) for e in found if e.status is not None)
    assert others == [("alice/ex02.ipynb", "ignored"), ("bob/ex02.ipynb", "ignored")]  # listed, not dropped
    flat = tmp_path / "flat"
    flat.mkdir()
    (flat / "dave.ipynb").write_text("{}")
    assert [e.student for e in collect([flat], "ex01", max_bytes=1000)] == ["dave"]


def test_releases_and_feedback_are_readable_by_others(tmp_path):
    """Released notebooks, the manifest and feedback pages were written 0600: copied to a shared hub folder, the
    students could not open them. They are 0644 (their new directories 0755) whatever the umask, like nbgrader's;
    the gradebook's other exports follow the umask."""
    import stat

    from kinbook.classroom import write_variant
    from kinbook.classroom.feedback import write_pages
    from kinbook.classroom.gradebook import Gradebook
    from kinbook.classroom.results import PartGrade, SubmissionResult

    from .conftest import ROOT

    def mode(p):
        return stat.S_IMODE(os.stat(p).st_mode)

    old = os.umask(0o077)
    try:
        out = tmp_path / "course" / "release"
        written = release([SOURCE], out)
        variant = write_variant(os.path.join(ROOT, "exercises", "ex09-point-kinematics.ipynb"), "alice",
                                tmp_path / "course" / "variants" / "alice")
        with Gradebook(tmp_path / "graded") as book:
            book.record(SubmissionResult("alice", "tiny", "x.ipynb", "0" * 64, "ok", "", [PartGrade("a", 1, 1, "ok")]))
            pages = write_pages(book, tmp_path / "graded" / "feedback")
            book.export()
    finally:
        os.umask(old)
    assert [mode(p) for p in written + [out / "manifest.json", variant] + pages] == [0o644] * (3 + len(pages))
    assert mode(out) == mode(tmp_path / "course") == mode(variant.parent) == 0o755
    assert mode(tmp_path / "graded" / "feedback") == mode(tmp_path / "graded" / "feedback" / "alice") == 0o755
    assert mode(tmp_path / "graded" / "grades.csv") == 0o600  # (umask 077: the instructor's own files stay private)


# ------------------------------------------------------------------- readable work (issue 32 item 5)
def _cells_of(data):
    from kinbook.classroom.notebook import parse_submission

    return [(c["cell_type"], c["source"]) for c in parse_submission(data)]


def test_an_nbformat3_notebook_is_read_as_its_nbformat4_self():
    nb = student_notebook(load_source(SOURCE), keep_solutions=True)
    v4 = json.dumps(nb).encode()
    v3 = json.dumps(nbformat.convert(nbformat.from_dict(json.loads(v4)), 3)).encode()
    assert b'"worksheets"' in v3 and _cells_of(v3) == _cells_of(v4)


@pytest.mark.parametrize("version", [3, 4])
def test_saved_outputs_do_not_count_against_the_size_limit(version):
    from kinbook.classroom.notebook import MAX_NOTEBOOK_BYTES, readable
    from kinbook.classroom.results import Refused

    nb = student_notebook(load_source(SOURCE), keep_solutions=True)
    line = "0123456789 a line the notebook printed\n"
    cell = nbformat.v4.new_code_cell("while True: print(k)")
    cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text=line * (MAX_NOTEBOOK_BYTES // len(line) + 9))]
    nb.cells.append(cell)
    small = json.loads(json.dumps(nb))
    if version == 3:
        nb = nbformat.convert(nbformat.from_dict(json.loads(json.dumps(nb))), 3)
    data = json.dumps(nb).encode()
    assert len(data) > MAX_NOTEBOOK_BYTES
    got = readable(data)
    assert len(got) < 100_000 and b"a line the notebook printed" not in got
    small["cells"][-1]["outputs"] = []
    assert _cells_of(data) == _cells_of(json.dumps(small).encode())
    code = json.loads(json.dumps(small))
    code["cells"][-1]["source"] = "x = 1\n" * (MAX_NOTEBOOK_BYTES // 6 + 9)     # code, not output: still too large
    with pytest.raises(Refused, match=r"bytes of code and text, saved outputs left out \(at most 8,388,608\)"):
        _cells_of(json.dumps(code).encode())
