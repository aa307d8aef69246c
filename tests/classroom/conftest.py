import hashlib
import json
import os
import shutil
import time
import unicodedata

import pytest

from kinbook.classroom import grade
from kinbook.classroom.sandbox import bwrap

# The fixture notebooks are hostile on purpose (infinite loops, memory hogs, os._exit, escape attempts):
# `pytest --nbval` must never run them outside the grader's sandbox.
collect_ignore_glob = ["submissions/*", "source/*"]

HERE = os.path.dirname(__file__)
ROOT = os.path.dirname(os.path.dirname(HERE))
SOURCE = os.path.join(HERE, "source", "tiny.ipynb")
SUBMISSIONS = os.path.join(HERE, "submissions")
CANARY = "/tmp/kinbook-canary.txt"
CANARY_DIR = "/tmp/kinbook-canary-dir"
EVIL = "/tmp/kinbook-evil.txt"
SECRET = "PRIVATE-SECRET-b7e1"
#: Whether the isolation tests can run here; else the reason they are skipped.
BWRAP = bwrap.available()
WHY_NO_BWRAP = "" if BWRAP else f"no operating-system sandbox here: {bwrap._probe()} (install `bubblewrap`)"
needs_bwrap = pytest.mark.skipif(not BWRAP, reason=WHY_NO_BWRAP)
#: The timeout (s) of every grading run whose submissions finish: far beyond what they take on a loaded machine
#: (a few seconds on a quiet one), so that no verdict here depends on the machine's speed.
ENOUGH = 300
#: The timeout (s) of the submissions that never finish (an infinite loop): their verdict is "timeout" at any speed.
RUNAWAY = 5
RUNAWAYS = ("loop",)
#: The student id of the over-long file name (as kinbook.classroom.files.student_id shortens it).
LONG_NAME = "x" * 240
#: A file name that is not UTF-8, with a terminal's escape sequence and a newline in it.
ODD_NAME = os.fsdecode(b"bytes\xff\x1b[2J\nname")


def submission(name):
    return os.path.join(SUBMISSIONS, f"{name}.ipynb")


def checkout_hash():
    """sha256 of every file of the package, the exercises and the classroom tests (what a student would change)."""
    h = hashlib.sha256()
    for top in ("kinbook", "exercises", os.path.join("tests", "classroom")):
        for d, dirs, files in sorted(os.walk(os.path.join(ROOT, top))):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(".pyc"):
                    continue
                path = os.path.join(d, f)
                h.update(path.encode() + b"\0")
                with open(path, "rb") as fh:
                    h.update(fh.read())
    return h.hexdigest()


def descendants(pid):
    """Live processes below ``pid`` (from /proc's parent links; zombies left out)."""
    children = {}
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if fields[0] != "Z":
            children.setdefault(int(fields[1]), []).append(int(name))
    out, stack = [], [pid]
    while stack:
        for c in children.get(stack.pop(), []):
            out.append(c)
            stack.append(c)
    return out


def make_collected(root):
    """A `collected/` directory: every committed fixture but the runaways, and the entries that cannot be
    committed; and a `runaway/` directory holding the runaways (graded with a short timeout)."""
    collected = root / "collected"
    collected.mkdir()
    (root / "runaway").mkdir()
    for f in sorted(os.listdir(SUBMISSIONS)):
        shutil.copy(os.path.join(SUBMISSIONS, f), (root / "runaway" if f[:-6] in RUNAWAYS else collected) / f)
    good = open(submission("good"), "rb").read()
    nb = json.loads(good)
    # a 20 MB notebook of 150,000 cells, and a small one with too many cells: refused before parsing
    cell = {"cell_type": "code", "execution_count": None, "metadata": {}, "outputs": [], "source": "x = 1 " * 12}
    (collected / "giant.ipynb").write_text(json.dumps({**nb, "cells": nb["cells"] + [cell] * 150_000}))
    (collected / "many_cells.ipynb").write_text(json.dumps({**nb, "cells": nb["cells"] + [cell] * 2_500}))
    # the same notebook re-saved by an older Jupyter (nbformat 4.4: no cell ids)
    old = {**nb, "nbformat_minor": 4, "cells": [{k: v for k, v in c.items() if k != "id"} for c in nb["cells"]]}
    (collected / "old44.ipynb").write_text(json.dumps(old, indent=1))
    # links (to the source, to a private file, to a directory of classmates), a FIFO, a device node
    secret = root / "private.txt"
    secret.write_text(SECRET)
    os.symlink(SOURCE, collected / "link_source.ipynb")
    os.symlink(secret, collected / "link_secret.ipynb")
    os.symlink(SUBMISSIONS, collected / "linkdir")
    os.mkfifo(collected / "fifo.ipynb")
    try:
        os.mknod(collected / "device.ipynb", 0o20644, os.makedev(1, 3))
    except PermissionError:  # not root: the device case is left out
        pass
    # a hard link to the instructor's source (what `tar -xf` of a student's archive at the course root can make),
    # a hard link between two students' files, and a plain copy of the source
    course = root / "course"
    course.mkdir()
    shutil.copy(SOURCE, course / "tiny.ipynb")
    os.link(course / "tiny.ipynb", collected / "hardlink.ipynb")
    (course / "mine.ipynb").write_bytes(good)
    os.link(course / "mine.ipynb", collected / "hardlink_classmate.ipynb")
    shutil.copy(SOURCE, collected / "source_copy.ipynb")
    # one id in NFC and in NFD (two attempts of José), ids that clash once case is folded with none of them more
    # real than the other (Ana, ana), a look-alike of a classmate (full-width ｇｏｏｄ beside good), and an id too
    # long for a file system's taste
    for form in ("NFC", "NFD"):
        (collected / (unicodedata.normalize(form, "José") + ".ipynb")).write_bytes(good)
    for name in ("Ana", "ana", "ｇｏｏｄ"):
        (collected / f"{name}.ipynb").write_bytes(good)
    (collected / (LONG_NAME + ".ipynb")).write_bytes(good)
    (collected / (ODD_NAME + ".ipynb")).write_bytes(good)
    return collected


@pytest.fixture(scope="session")
def batch(tmp_path_factory):
    """Every fixture submission graded once, two at a time (memory 400 MB), in the sandbox where bubblewrap works
    (else with the audit hook only): `collected/` in one batch with a timeout no finishing notebook reaches, then
    the runaways into the same gradebook with a short one (a re-run grades only what is new)."""
    root = tmp_path_factory.mktemp("hostile")
    collected = make_collected(root)
    out = root / "graded"
    with open(CANARY, "w") as f:
        f.write("do not delete")
    os.makedirs(CANARY_DIR, exist_ok=True)
    if os.path.exists(EVIL):
        os.remove(EVIL)
    files = sorted(str(d / f) for d in (collected, root / "runaway") for f in os.listdir(d))
    before = {f: (open(f, "rb").read(), os.stat(f).st_mtime_ns) for f in files
              if os.path.isfile(f) and not os.path.islink(f) and not f.endswith("fifo.ipynb")}
    checkout = checkout_hash()
    seen = []
    t0 = time.monotonic()
    def progress(item):
        seen.append(item if isinstance(item, str) else item.student)

    results = grade(SOURCE, [collected], out, timeout=ENOUGH, memory=400, jobs=2, isolation=BWRAP, progress=progress)
    results += grade(SOURCE, [root / "runaway"], out, timeout=RUNAWAY, memory=400, jobs=2, isolation=BWRAP,
                     progress=progress)
    seconds = time.monotonic() - t0
    return {"out": out, "results": {r.student: r for r in results}, "before": before, "seconds": seconds,
            "collected": collected, "checkout": checkout, "checkout_after": checkout_hash(),
            "left": descendants(os.getpid()), "progress": seen}
