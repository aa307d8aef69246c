"""The course commands' bad inputs (issue 31), for the corpus (corpus.py): generated, each run through the console
script in the worker's directory on a fresh copy of a small course (a gradebook with two graded students and a
roster, a source notebook), and each checked to leave every input of the command as it was.

A case returns ``(exit status, stderr)`` like the corpus's other command-line cases; when a command changed one of
its inputs the status is :data:`DESTROYED`, so the case fails whatever the message says.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import shutil
import sqlite3

DESTROYED = 99
EX = "ex01"
DUE = "2026-03-01T23:59+01:00"
ROSTER = "student,name,lms_id\nana,\"García, Ana\",1001\nJosé,José Núñez,1002\nben,Ben Okafor,1003\n"
TEMPLATE = "corpus-course-template"


def _template():
    """The course, built once per worker: roster.csv, graded/ (ana and José graded in ex01), tiny.ipynb."""
    if os.path.isdir(TEMPLATE):
        return TEMPLATE
    from kinbook.classroom.gradebook import Gradebook
    from kinbook.classroom.results import PartGrade, SubmissionResult
    from kinbook.classroom.roster import read_roster

    os.makedirs(TEMPLATE + ".tmp")
    with open(os.path.join(TEMPLATE + ".tmp", "roster.csv"), "w", encoding="utf-8") as f:
        f.write(ROSTER)
    book = Gradebook(os.path.join(TEMPLATE + ".tmp", "graded"))
    book.set_roster(read_roster(os.path.join(TEMPLATE + ".tmp", "roster.csv")))
    for student, a in (("ana", 4.0), ("José", 1.0)):
        book.record(SubmissionResult(student, EX, f"collected/{student}.ipynb", "0" * 64, "ok", "",
                                     [PartGrade("a", a, 4.0, "ok", "m"), PartGrade("b", 2.0, 2.0, "ok", "m")], 1.0,
                                     "none"))
    book.close()
    here = os.path.dirname(os.path.abspath(__file__))
    shutil.copy(os.path.join(here, "..", "classroom", "source", "tiny.ipynb"),
                os.path.join(TEMPLATE + ".tmp", "tiny.ipynb"))
    os.rename(TEMPLATE + ".tmp", TEMPLATE)
    return TEMPLATE


def _fresh(cid):
    """A fresh copy of the course for one case: its directory's name (relative to the worker's)."""
    top = f"course-{hashlib.sha256(cid.encode()).hexdigest()[:12]}"
    shutil.rmtree(top, ignore_errors=True)
    shutil.copytree(_template(), top)
    return top


def _state(top):
    out = {}
    for d, _dirs, files in os.walk(top):
        for name in files:
            path = os.path.join(d, name)
            if name.endswith(".sqlite"):
                with contextlib.suppress(sqlite3.Error):
                    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
                    try:
                        out[path] = hashlib.sha256("\n".join(db.iterdump()).encode()).hexdigest()
                    finally:
                        db.close()
                    continue
            if not name.endswith(("-wal", "-shm")):
                with open(path, "rb") as f:
                    out[path] = hashlib.sha256(f.read()).hexdigest()
    return out


def course_cli(cid, argv, prepare=None, keep=True):
    """Run ``kinbook argv`` (``{top}`` in it: the fresh course) after ``prepare(top)``; (status, stderr), the
    status :data:`DESTROYED` when a file of the course changed (``keep``: every file the command did not create)."""
    from kinbook.cli import main

    top = _fresh(cid)
    if prepare is not None:
        prepare(top)
    before = _state(top)
    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        status = main([a.format(top=top) for a in argv])
    after = _state(top)
    changed = sorted(p for p in before if after.get(p) != before[p])
    if keep and changed:
        return DESTROYED, f"input changed: {changed}; stderr: {err.getvalue()}"
    return status, err.getvalue()


# ---------------------------------------------------------------------------------------------- the cases
GRADEBOOK_COMMANDS = {
    "report": ["report", "-g", "{top}/graded", "-o", "{top}/report"],
    "export": ["export", "-g", "{top}/graded", "-o", "{top}/out.csv"],
    "feedback": ["feedback", "-g", "{top}/graded", "--out", "{top}/fb"],
    "due": ["due", EX, DUE, "-g", "{top}/graded"],
    "extend": ["extend", "ana", EX, DUE, "-g", "{top}/graded"],
    "override": ["override", "ana", EX, "a", "1", "--why", "x", "-g", "{top}/graded"],
}


def _write(rel, data):
    def prepare(top):
        path = os.path.join(top, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        for x in ("", "-wal", "-shm"):
            with contextlib.suppress(FileNotFoundError):
                os.remove(path + x)
        with open(path, "wb") as f:
            f.write(data() if callable(data) else data)
    return prepare


def _newer(top):
    db = sqlite3.connect(os.path.join(top, "graded", "gradebook.sqlite"))
    db.execute("PRAGMA user_version = 99")
    db.close()


def _foreign(top):
    _write("graded/gradebook.sqlite", b"")(top)
    db = sqlite3.connect(os.path.join(top, "graded", "gradebook.sqlite"))
    db.execute("CREATE TABLE moz_places (id INTEGER)")
    db.close()


_LOCKS = []


def _locked(top):
    """Another 'run' holds the gradebook (an open exclusive transaction) and the wait is made short."""
    from kinbook.classroom import gradebook

    db = sqlite3.connect(os.path.join(top, "graded", "gradebook.sqlite"), isolation_level=None)
    db.execute("BEGIN EXCLUSIVE")
    _LOCKS.append((db, gradebook.LOCK_WAIT))
    gradebook.LOCK_WAIT = 0.5


def _unlocked(fn):
    def run():
        try:
            return fn()
        finally:
            from kinbook.classroom import gradebook

            while _LOCKS:
                db, wait = _LOCKS.pop()
                db.execute("ROLLBACK")
                db.close()
                gradebook.LOCK_WAIT = wait
    return run


GRADEBOOK_STATES = [
    # (label, prepare, words)
    ("missing-dir", lambda top: shutil.rmtree(os.path.join(top, "graded")), ("no grading directory",)),
    ("no-database", lambda top: os.remove(os.path.join(top, "graded", "gradebook.sqlite")), ("holds no gradebook",)),
    ("empty-file", _write("graded/gradebook.sqlite", b""), ("holds no gradebook",)),
    ("csv-instead", _write("graded/gradebook.sqlite", b'"student","score"\n"ana","4"\n'), ("not a kinbook gradebook",)),
    ("random-bytes", _write("graded/gradebook.sqlite", bytes(range(256)) * 16), ("not a kinbook gradebook",)),
    ("truncated", lambda top: _truncate(top), ("not a kinbook gradebook",)),
    ("another-app", _foreign, ("not a kinbook gradebook", "moz_places")),
    ("newer", _newer, ("newer kinbook",)),
    ("locked", _locked, ("in use by another kinbook run",)),
    ("dir-is-file", lambda top: (shutil.rmtree(os.path.join(top, "graded")), _write("graded", b"x")(top)),
     ("graded",)),
]


def _truncate(top):
    path = os.path.join(top, "graded", "gradebook.sqlite")
    with open(path, "rb") as f:
        head = f.read(1000)
    _write("graded/gradebook.sqlite", head)(top)


BAD_IDS = [("slash", "a/b"), ("dotdot", ".."), ("hidden", ".x"), ("space", "ana b"), ("nul", "a\x00b"),
           ("bidi", "ana\u202eb"), ("long", "a" * 65), ("colon", "a:b"), ("star", "a*b"), ("emoji", "ana😀"),
           ("newline", "ana\nb"), ("backslash", "a\\b")]


def gradebook_cases(Case):
    out = []
    for label, prepare, words in GRADEBOOK_STATES:
        for cmd, argv in GRADEBOOK_COMMANDS.items():
            cid = f"course-gradebook-{label}-{cmd}"
            out.append(Case(cid, "course gradebook",
                            _unlocked(lambda cid=cid, argv=argv, prepare=prepare: course_cli(cid, argv, prepare)),
                            "cli", words, timeout=30))
    return out


def name_cases(Case):
    g = ["-g", "{top}/graded"]
    rows = [
        ("due-typo", ["due", "ex1", DUE, "--penalty", "10", *g], ("no exercise 'ex1'", "did you mean 'ex01'")),
        ("due-unknown", ["due", "zz99", DUE, *g], ("no exercise 'zz99'", "ex01")),
        ("extend-typo-exercise", ["extend", "ana", "ex1", DUE, *g], ("no exercise 'ex1'", "'ex01'")),
        ("extend-unknown-student", ["extend", "anna", EX, DUE, *g], ("no student 'anna'", "did you mean 'ana'")),
        ("override-unknown-student", ["override", "bem", EX, "a", "1", "--why", "x", *g],
         ("no student 'bem'", "did you mean 'ben'")),  # ben: on the roster, not graded
        ("override-unknown-part", ["override", "ana", EX, "c", "1", "--why", "x", *g], ("has no part 'c'",)),
        ("override-typo-exercise", ["override", "ana", "ex1", "a", "1", "--why", "x", *g], ("did you mean 'ex01'",)),
        ("extend-remove-nothing", ["extend", "ana", EX, "--remove", *g], ("no extension",)),
        ("extend-remove-with-date", ["extend", "ana", EX, DUE, "--remove", *g], ("--remove takes no date",)),
        ("extend-no-date", ["extend", "ana", EX, *g], ("due date", "--remove")),
        ("export-unknown-exercise", ["export", "--exercise", "ex1", "-o", "{top}/o.csv", *g], ("'ex1'",)),
    ]
    for label, bad in BAD_IDS:
        rows += [(f"override-id-{label}", ["override", bad, EX, "a", "1", "--why", "x", *g], ("student id",)),
                 (f"extend-id-{label}", ["extend", bad, EX, DUE, *g], ("student id",)),
                 (f"due-exercise-{label}", ["due", bad, DUE, *g], ("exercise name",)),
                 (f"variant-id-{label}", ["variant", "{top}/tiny.ipynb", "--student", bad, "-o", "{top}/v"],
                  ("student id",))]
    out = [Case(f"course-names-{lbl}", "course names", lambda lbl=lbl, argv=argv: course_cli(f"n-{lbl}", argv),
                "cli", words, timeout=30) for lbl, argv, words in rows]
    # what must work: the same student under every spelling the one id rule folds, --remove that exists
    ok = [
        ("override-nfd", ["override", "Jose\u0301", EX, "a", "2", "--why", "accepted", *g], "José ex01 a: 2"),
        ("override-upper", ["override", "JOSÉ", EX, "a", "2", "--why", "accepted", *g], "José ex01 a: 2"),
        ("override-fullwidth", ["override", "ａｎａ", EX, "a", "3", "--why", "accepted", *g], "ana ex01 a: 3"),
    ]
    for lbl, argv, said in ok:
        out.append(Case(f"course-names-{lbl}", "course names",
                        lambda lbl=lbl, argv=argv: _said(f"o-{lbl}", argv), "ok",
                        check=lambda r, said=said: r[0] == 0 and said in r[1], timeout=30))
    out.append(Case("course-names-extend-remove", "course names", lambda: _said("o-remove", [
        "extend", "ana", EX, DUE, *g], then=["extend", "ANA", EX, "--remove", *g]), "ok",
        check=lambda r: r[0] == 0 and "ana ex01: extension removed" in r[1], timeout=30))
    return out


def _said(cid, argv, then=None):
    """(status, stdout) of a command that must work (and of ``then`` after it, in the same course)."""
    from kinbook.cli import main

    top = _fresh(cid)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main([a.format(top=top) for a in argv])
        if then is not None and status == 0:
            out.truncate(0)
            status = main([a.format(top=top) for a in then])
    return status, out.getvalue() + err.getvalue()


def own_input_cases(Case):
    g = ["-g", "{top}/graded"]
    rows = [
        ("export-onto-gradebook", ["export", *g, "-o", "{top}/graded/gradebook.sqlite"], None),
        ("export-onto-journal", ["export", *g, "-o", "{top}/graded/gradebook.sqlite-wal"], None),
        ("export-onto-roster", ["export", *g, "--roster", "{top}/roster.csv", "-o", "{top}/roster.csv"], None),
        ("export-onto-roster-dotted", ["export", *g, "--roster", "{top}/roster.csv", "-o", "{top}/./roster.csv"],
         None),
        ("export-onto-roster-hardlink", ["export", *g, "--roster", "{top}/roster.csv", "-o", "{top}/r2.csv"],
         lambda top: os.link(f"{top}/roster.csv", f"{top}/r2.csv")),
        ("export-onto-gradebook-symlink", ["export", *g, "-o", "{top}/g.csv"],
         lambda top: os.symlink(os.path.abspath(f"{top}/graded/gradebook.sqlite"), f"{top}/g.csv")),
        ("release-onto-source", ["release", "{top}/tiny.ipynb", "-o", "{top}"], None),
        ("variant-onto-source", ["variant", "{top}/tiny.ipynb", "--student", "ana", "-o", "{top}/v"],
         lambda top: (os.makedirs(f"{top}/v"), os.link(f"{top}/tiny.ipynb", f"{top}/v/tiny-ana.ipynb"))),
        ("report-onto-roster", ["report", *g, "--roster", "{top}/roster.csv", "-o", "{top}/rep"],
         lambda top: (os.makedirs(f"{top}/rep"), os.link(f"{top}/roster.csv", f"{top}/rep/index.html"))),
    ]
    return [Case(f"course-own-input-{lbl}", "course own inputs",
                 lambda lbl=lbl, argv=argv, prep=prep: course_cli(f"i-{lbl}", argv, prep), "cli",
                 ("its own input",), timeout=60) for lbl, argv, prep in rows]


ROSTERS = [
    # (label, bytes, words): read by `export --roster` (the roster is read before anything else)
    ("unclosed-quote", b'student,name\nana,"Ana\nbob,Bob\ncarl,Carl\n', ("line 2", "never closed")),
    ("multiline-field", b'student,name\nana,"Ana\nMaria",x\nbob,Bob\n', ("line 2", "runs over lines 2 to 3")),
    ("text-after-quote", b'student,name\nana,"Ana"x\n', ("line 2",)),
    ("xlsx", b"PK\x03\x04\x14\x00\x06\x00\x08\x00\x00\x00!\x00", ("NUL",)),
    ("bad-bytes", b"student\n\x81\x8d\x8f\n", ("line 2", "0x81")),
    ("empty", b"", ("empty",)),
    ("header-only", b"student,name\n", ("no student",)),
    ("no-student-column", b"name,email\nAna,a@x\n", ("no 'student' column",)),
    ("bad-id", b"student\nana/../x\n", ("line 2", "'/'")),
    ("same-id-case", b"student\nana\nANA\n", ("lines 2 and 3",)),
    ("same-id-nfd", "student\nJosé\nJose\u0301\n".encode(), ("lines 2 and 3",)),
    ("no-id", b"student,name\n,Ana\n", ("line 2", "no student id")),
    ("utf16-no-student-column", "name\tx\nAna\t1\n".encode("utf-16"), ("no 'student' column", "name, x")),
    ("too-large", lambda: b"student\n" + b"a" * (21 * 1024 * 1024), ("larger than",)),
]
GOOD_ROSTERS = [
    # (label, bytes, the students): every one must come out, none dropped
    ("cr", b"student,name\rana,Ana\rbob,Bob\r", ["ana", "bob"]),
    ("crlf-bom", b"\xef\xbb\xbfstudent,name\r\nana,Ana\r\nbob,Bob\r\n", ["ana", "bob"]),
    ("utf16-tab", "student\tname\nana\tAna\nJosé\tJosé\n".encode("utf-16"), ["ana", "José"]),
    ("utf16le-nobom", "student;name\nana;Ana\nbob;Bob\n".encode("utf-16-le"), ["ana", "bob"]),
    ("semicolon", "student;name\nana;García, Ana\nbob;Bob\n".encode("cp1252"), ["ana", "bob"]),
    ("huge-field", b"student,name\nana," + b"x" * 200_000 + b"\nbob,Bob\n", ["ana", "bob"]),
    ("quoted-delimiters", b'"student","name"\n"ana","a,b;c"\n"bob","Bob ""B"""\n', ["ana", "bob"]),
]


def roster_cases(Case):
    out = []
    for label, raw, words in ROSTERS:
        argv = ["export", "-g", "{top}/graded", "--roster", "{top}/r.csv", "-o", "{top}/out.csv"]
        out.append(Case(f"course-roster-{label}", "course rosters",
                        lambda label=label, raw=raw, argv=argv: course_cli(f"r-{label}", argv, _write("r.csv", raw)),
                        "cli", words, timeout=30))
    for label, raw, students in GOOD_ROSTERS:
        out.append(Case(f"course-roster-reads-{label}", "course rosters", lambda raw=raw: _roster(raw), "ok",
                        check=lambda got, students=students: got == students, timeout=30))
    return out


def _roster(raw):
    from kinbook.classroom.roster import read_roster

    with open("corpus-roster.csv", "wb") as f:
        f.write(raw)
    return [s.student for s in read_roster("corpus-roster.csv")]


def _source_with(cell_source, hidden=False):
    """tiny.ipynb with one more code cell (in hidden checks when ``hidden``)."""
    import json

    def prepare(top):
        path = os.path.join(top, "tiny.ipynb")
        with open(path, encoding="utf-8") as f:
            nb = json.load(f)
        code = f"### BEGIN HIDDEN CHECKS\n{cell_source}\n### END HIDDEN CHECKS" if hidden else cell_source
        nb["cells"].append({"cell_type": "code", "metadata": {}, "execution_count": None, "outputs": [],
                            "source": code})
        with open(path, "w", encoding="utf-8") as f:
            json.dump(nb, f)
    return prepare


SOURCES = [
    # (label, cell, hidden, words)
    ("syntax-error", "x = (1 + 2", False, ("does not compile",)),
    ("hidden-syntax-error", 'part("extra", points=2, answer="x", check="value", expected=(1.0)', True,
     ("does not compile",)),
    ("sys-exit", "import sys\nsys.exit(0)", False, ("stops the interpreter",)),
    ("exit", "exit()", False, ("stops the interpreter",)),
    ("hidden-exit", "raise SystemExit(3)", True, ("stops the interpreter",)),
    ("hidden-name-error", 'y = undefined_name\npart("extra", points=2, answer="x", check="value", expected=1.0)', True,
     ("NameError", "extra")),
    ("name-error-loses-part", 'y = undefined_name\npart("extra", points=2, answer="x", check="value", expected=1.0)',
     False, ("NameError", "extra")),
    ("hidden-zero-division", "1 / 0", True, ("ZeroDivisionError",)),
    ("nul-in-code", "x = 1\x00", False, ("does not compile",)),
]


def source_cases(Case):
    out = []
    for label, cell, hidden, words in SOURCES:
        for cmd, argv in (("release", ["release", "{top}/tiny.ipynb", "-o", "{top}/rel"]),
                          ("validate", ["validate", "{top}/tiny.ipynb", "--no-isolation"])):
            out.append(Case(f"course-source-{label}-{cmd}", "course sources",
                            lambda label=label, argv=argv, cell=cell, hidden=hidden: course_cli(
                                f"s-{label}-{argv[0]}", argv, _source_with(cell, hidden), keep=False),
                            "cli", ("cell",) + words, timeout=60))
    return out


def cases(Case):
    return gradebook_cases(Case) + name_cases(Case) + own_input_cases(Case) + roster_cases(Case) + source_cases(Case)
