"""Nothing lost, nothing half-done (issue 31): every command that writes, run against a read-only directory, a full
disk and its own input given as output, fails with one clear line and leaves every input — the gradebook, the roster,
the source, the files it wrote before — exactly as it was.

Each scenario runs twice where the machine allows: on a real small file system (a tmpfs mounted by the test, remounted
read-only or filled up; only as root with mount rights) and with the failure injected (the one writer's ``os.write``
failing with ENOSPC, ``mkstemp`` with EROFS; SQLite opened read-only or capped at its current size). A file system
the test cannot mount skips the first kind, never the second.
"""

import contextlib
import errno
import hashlib
import os
import shutil
import sqlite3
import subprocess
import tempfile

import pytest

from kinbook.classroom import gradebook as gradebook_module
from kinbook.classroom.gradebook import Gradebook
from kinbook.classroom.roster import read_roster
from kinbook.cli import main
from kinbook.core import atomic

from .conftest import SOURCE
from .test_course import EX, ROSTER, result

DUE = "2026-03-01T23:59+01:00"
pytestmark = pytest.mark.filterwarnings("ignore:grading WITHOUT isolation:RuntimeWarning")


# ------------------------------------------------------------------------------------------------- the course
def make_course(top):
    """A course under ``top``: roster.csv, graded/ (a gradebook with three results), tiny.ipynb (a source), and an
    earlier export, report and feedback that a failed run must leave as they were."""
    top = str(top)
    with open(os.path.join(top, "roster.csv"), "w", encoding="utf-8") as f:
        f.write(ROSTER)
    book = Gradebook(os.path.join(top, "graded"))
    book.set_roster(read_roster(os.path.join(top, "roster.csv")))
    book.record(result("ana", 4, 2, submitted="2026-03-01T20:00:00"))
    book.record(result("ben", 1, 2))
    book.close()
    shutil.copy(SOURCE, os.path.join(top, "tiny.ipynb"))
    os.makedirs(os.path.join(top, "out"))
    os.makedirs(os.path.join(top, "collected"))
    shutil.copy(os.path.join(os.path.dirname(SOURCE), "..", "submissions", "good.ipynb"),
                os.path.join(top, "collected", "carl.ipynb"))
    with open(os.path.join(top, "out", "export.csv"), "w") as f:
        f.write("an earlier export\n")
    return top


def snapshot(top):
    """{path: content} of every file below ``top``; a gradebook as the rows a later kinbook would read (its
    database and journal copied aside and dumped), so that SQLite's own files do not count, only what they hold."""
    out = {}
    for d, _dirs, files in os.walk(top):
        for name in files:
            path = os.path.join(d, name)
            rel = os.path.relpath(path, top)
            if name.endswith(("-wal", "-shm")) or name == "filler":
                continue
            if name.endswith(".sqlite"):
                out[rel] = _dump(path)
            else:
                with open(path, "rb") as f:
                    out[rel] = hashlib.sha256(f.read()).hexdigest()
    return out


def _dump(path):
    with tempfile.TemporaryDirectory() as tmp:
        for x in ("", "-wal"):
            if os.path.exists(path + x):
                shutil.copy(path + x, os.path.join(tmp, "g.sqlite" + x))
        db = sqlite3.connect(os.path.join(tmp, "g.sqlite"))
        try:
            return hashlib.sha256("\n".join(db.iterdump()).encode()).hexdigest()
        finally:
            db.close()


def run(capsys, argv):
    status = main(argv)
    err = capsys.readouterr().err.strip()
    return status, err


# every writing command, given where it reads (top: the course) and where it writes (out)
COMMANDS = {
    "export-csv": lambda top, out, g: ["export", "-g", g, "-o", os.path.join(out, "export.csv")],
    "export-canvas": lambda top, out, g: ["export", "--format", "canvas", "-g", g, "-o", os.path.join(out, "c.csv"),
                                          "--header", f"{EX}=Exercise 1 (40101)"],
    "export-moodle": lambda top, out, g: ["export", "--format", "moodle", "-g", g, "-o", os.path.join(out, "m.csv")],
    "report-html": lambda top, out, g: ["report", "-g", g, "-o", os.path.join(out, "report")],
    "report-csv": lambda top, out, g: ["report", "-g", g, "-o", os.path.join(out, "report"), "--format", "csv"],
    "feedback": lambda top, out, g: ["feedback", "-g", g, "--out", os.path.join(out, "feedback")],
    "release": lambda top, out, g: ["release", os.path.join(top, "tiny.ipynb"), "-o", os.path.join(out, "release")],
    "variant": lambda top, out, g: ["variant", os.path.join(top, "tiny.ipynb"), "--student", "ana", "-o",
                                    os.path.join(out, "variants")],
    "variant-roster": lambda top, out, g: ["variant", os.path.join(top, "tiny.ipynb"), "--roster",
                                           os.path.join(top, "roster.csv"), "-o", os.path.join(out, "variants")],
    "exercises-copy": lambda top, out, g: ["exercises", "copy", "ex01", "ex02", os.path.join(out, "exercises")],
}
#: Commands whose only output is the gradebook itself.
IN_PLACE = {
    "due": lambda top, g: ["due", EX, DUE, "--penalty", "10", "-g", g],
    "extend": lambda top, g: ["extend", "ana", EX, "2026-03-05T23:59+01:00", "--why", "ill", "-g", g],
    "override": lambda top, g: ["override", "ben", EX, "a", "3", "--why", "accepted", "-g", g],
    # grading stops when the gradebook cannot record its run, before any submission is run
    "grade": lambda top, g: ["grade", os.path.join(top, "tiny.ipynb"), os.path.join(top, "collected"), "-o", g,
                             "--no-isolation"],
}


# -------------------------------------------------------------------------------------------- file systems
@contextlib.contextmanager
def tmpfs(path, size):
    """A tmpfs of ``size`` mounted at ``path``, or None where the test may not mount one."""
    os.makedirs(path, exist_ok=True)
    if os.geteuid() != 0 or shutil.which("mount") is None:
        yield None
        return
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "kinbook-test", str(path)],
                          capture_output=True)
    if done.returncode != 0:
        yield None
        return
    try:
        yield path
    finally:
        subprocess.run(["umount", "-l", str(path)], capture_output=True)


def fill(path):
    """Fill the file system of ``path`` to the last byte."""
    fd = os.open(os.path.join(path, "filler"), os.O_WRONLY | os.O_CREAT)
    try:
        for size in (1 << 16, 4096, 1):
            with contextlib.suppress(OSError):
                while True:
                    os.write(fd, b"\0" * size)
    finally:
        os.close(fd)


def _errno(code):
    def fail(*args, **kwargs):
        raise OSError(code, os.strerror(code))
    return fail


def _sqlite_patched(monkeypatch, how):
    """SQLite opened read-only (``how`` "ro") or unable to grow past its current size ("full")."""
    real = sqlite3.connect

    def connect(database, *args, **kwargs):
        if how == "ro":
            kwargs["uri"] = True
            return real(f"file:{database}?mode=ro", *args, **kwargs)
        db = real(database, *args, **kwargs)
        pages = db.execute("PRAGMA page_count").fetchone()[0]
        db.execute(f"PRAGMA max_page_count = {max(pages, 1)}")
        return db

    monkeypatch.setattr(gradebook_module.sqlite3, "connect", connect)


# ------------------------------------------------------------------------------------------------ the tests
def _check(status, err, words, before, after):
    assert status == 2, err
    assert "\n" not in err and "Traceback" not in err and "internal error" not in err, err
    for w in words:
        assert w in err, f"{w!r} not in {err!r}"
    assert after == before, "an input changed"


@pytest.mark.parametrize("name", sorted(COMMANDS) + sorted(IN_PLACE))
@pytest.mark.parametrize("how", ["filesystem", "injected"])
def test_read_only(tmp_path, capsys, monkeypatch, name, how):
    top = make_course(tmp_path)
    ro = os.path.join(top, "ro")
    with tmpfs(ro, "2m") as mounted:
        if how == "filesystem" and mounted is None:
            pytest.skip("cannot mount a file system here (needs root and mount rights)")
        g = os.path.join(top, "graded")
        if name in IN_PLACE:
            if mounted:
                shutil.copytree(g, os.path.join(ro, "graded"))
                g = os.path.join(ro, "graded")
        if mounted:
            subprocess.run(["mount", "-o", "remount,ro", ro], check=True)
        else:
            monkeypatch.setattr(atomic.tempfile, "mkstemp", _errno(errno.EROFS))
            monkeypatch.setattr(atomic.Path, "mkdir", _errno(errno.EROFS))
            if name in IN_PLACE:
                _sqlite_patched(monkeypatch, "ro")
        before = snapshot(top)
        argv = IN_PLACE[name](top, g) if name in IN_PLACE else COMMANDS[name](top, ro, g)
        status, err = run(capsys, argv)
        after = snapshot(top)
    words = ("gradebook.sqlite", "read-only") if name in IN_PLACE else ("read-only", ro)
    _check(status, err, words, before, after)


@pytest.mark.parametrize("name", sorted(COMMANDS) + sorted(IN_PLACE))
@pytest.mark.parametrize("how", ["filesystem", "injected"])
def test_full_disk(tmp_path, capsys, monkeypatch, name, how):
    top = make_course(tmp_path)
    small = os.path.join(top, "small")
    with tmpfs(small, "4m") as mounted:
        if how == "filesystem" and mounted is None:
            pytest.skip("cannot mount a file system here (needs root and mount rights)")
        g = os.path.join(top, "graded")
        out = small if mounted else os.path.join(top, "out")
        if mounted:
            if name in IN_PLACE:
                shutil.copytree(g, os.path.join(small, "graded"))
                g = os.path.join(small, "graded")
            shutil.copy(os.path.join(top, "out", "export.csv"), os.path.join(small, "export.csv"))
            fill(small)
        else:
            def full(fd, data):
                os.write(fd, bytes(data[: len(data) // 2]))  # half of it fits, then the disk is full
                raise OSError(errno.ENOSPC, "No space left on device")

            monkeypatch.setattr(atomic, "_write_all", full)
            if name in IN_PLACE:
                _sqlite_patched(monkeypatch, "full")
        before = snapshot(top)
        argv = IN_PLACE[name](top, g) if name in IN_PLACE else COMMANDS[name](top, out, g)
        status, err = run(capsys, argv)
        after = snapshot(top)
        leftovers = [f for d, _, fs in os.walk(top) for f in fs if f.endswith(".tmp")]
    _check(status, err, ("full",) if name in IN_PLACE else ("no space left",), before, after)
    assert not leftovers, leftovers


OWN_INPUT = {
    # command: (how the output is made one of the inputs, argv)
    "export-onto-gradebook": lambda top: ["export", "-g", f"{top}/graded", "-o", f"{top}/graded/gradebook.sqlite"],
    "export-onto-roster": lambda top: ["export", "-g", f"{top}/graded", "--roster", f"{top}/roster.csv", "-o",
                                       f"{top}/./roster.csv"],
    "export-onto-roster-link": lambda top: (os.link(f"{top}/roster.csv", f"{top}/out/linked.csv"),
                                            ["export", "-g", f"{top}/graded", "--roster", f"{top}/roster.csv",
                                             "--format", "moodle", "-o", f"{top}/out/linked.csv"])[1],
    "export-onto-gradebook-symlink": lambda top: (os.symlink(f"{top}/graded/gradebook.sqlite", f"{top}/out/g.csv"),
                                                  ["export", "-g", f"{top}/graded", "-o", f"{top}/out/g.csv"])[1],
    "report-onto-roster": lambda top: (os.makedirs(f"{top}/out/r"), os.link(f"{top}/roster.csv",
                                                                           f"{top}/out/r/index.html"),
                                       ["report", "-g", f"{top}/graded", "--roster", f"{top}/roster.csv", "-o",
                                        f"{top}/out/r"])[2],
    "feedback-onto-gradebook": lambda top: (os.makedirs(f"{top}/out/f/ana"),
                                            os.symlink(f"{top}/graded/gradebook.sqlite", f"{top}/out/f/ana/index.html"),
                                            ["feedback", "-g", f"{top}/graded", "--out", f"{top}/out/f"])[2],
    "release-onto-source": lambda top: ["release", f"{top}/tiny.ipynb", "-o", top],
    "variant-onto-source": lambda top: (os.link(f"{top}/tiny.ipynb", f"{top}/out/tiny-ana.ipynb"),
                                        ["variant", f"{top}/tiny.ipynb", "--student", "ana", "-o", f"{top}/out"])[1],
    "variant-roster-onto-roster": lambda top: (os.link(f"{top}/roster.csv", f"{top}/out/tiny-carl.ipynb"),
                                               ["variant", f"{top}/tiny.ipynb", "--roster", f"{top}/roster.csv", "-o",
                                                f"{top}/out"])[1],
}


@pytest.mark.parametrize("name", sorted(OWN_INPUT))
def test_own_input_as_output(tmp_path, capsys, name):
    top = make_course(tmp_path)
    argv = OWN_INPUT[name](top)
    before = snapshot(top)
    listing = sorted(os.listdir(os.path.join(top, "out")))
    status, err = run(capsys, argv)
    _check(status, err, ("its own input",), before, snapshot(top))
    assert sorted(os.listdir(os.path.join(top, "out"))) == listing, "something was written"
    with Gradebook(os.path.join(top, "graded"), create=False) as book:  # still a gradebook, every result there
        assert sorted(r.student for r in book.results()) == ["ana", "ben"]


def test_exercises_copy_never_overwrites_and_copies_all_or_none(tmp_path, capsys):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "ex02-planar-joint-types.ipynb").write_text("my edited copy")
    status, err = run(capsys, ["exercises", "copy", "ex01", "ex02", str(out)])
    assert status == 2 and "already exists" in err and "nothing was copied" in err
    assert sorted(os.listdir(out)) == ["ex02-planar-joint-types.ipynb"]
    assert (out / "ex02-planar-joint-types.ipynb").read_text() == "my edited copy"


def test_a_mistyped_gradebook_directory_is_refused_and_not_created(tmp_path, capsys):
    make_course(tmp_path)
    for argv in (["report", "-g", "gradde"], ["export", "-g", "gradde", "-o", "x.csv"],
                 ["feedback", "-g", "gradde", "--out", "fb"], ["due", EX, DUE, "-g", "gradde"],
                 ["extend", "ana", EX, DUE, "-g", "gradde"], ["override", "ana", EX, "a", "1", "--why", "x",
                                                                 "-g", "gradde"]):
        status, err = run(capsys, [a if a != "gradde" else str(tmp_path / "gradde") for a in argv])
        assert status == 2 and "no grading directory" in err and "gradde" in err, (argv, err)
        assert not (tmp_path / "gradde").exists()
