"""Files of the instructor's workflow: the one atomic writer, and reading ``collected/`` as untrusted input.

:func:`atomic_write` (:mod:`kinbook.core.atomic`, re-exported here) is how every file kinbook produces for an
instructor is written (released notebooks, the manifest, the gradebook's exports): a temporary file in the same
directory, flushed and synced, then ``os.replace`` — a reader sees the old file or the new one, never half of one.

:func:`collect` walks the submissions an instructor names. Whatever is inside a named directory was put
there by students, so it is treated as hostile:

* entries are listed through directory descriptors, never through paths; symbolic links, devices, FIFOs and
  sockets are refused per entry (status ``refused``) and never followed or opened;
* a file is opened relative to its directory's descriptor with ``O_NOFOLLOW | O_NONBLOCK`` and must be the
  very regular file that was listed (same device and inode: a file swapped for a link, a FIFO or another file
  between listing and reading is refused), no larger than the size cap (``too-large``, before reading);
* the student id comes from the path (:func:`kinbook.classroom.ids.id_from_path`): Unicode NFC, letters, digits and ``._@+-``, at most
  :data:`MAX_ID_CHARS` characters; ids that are too long (``bad-id``) or that clash once case and Unicode
  compatibility forms are folded (``duplicate-id``) are reported per entry, and the batch goes on.
"""

from __future__ import annotations

import datetime as _dt
import os
import stat
import unicodedata
from dataclasses import dataclass, field

from ..core.atomic import atomic_write  # the one writer (re-exported: the classroom's callers import it from here)
from .choice import choose, kind_of_file
from .ids import MAX_ID_CHARS, id_key
from .ids import id_from_path as student_id  # the one id rule (kinbook.classroom.ids); this name kept for callers
from .naming import compile_pattern, read_name
from .results import Refused

__all__ = ["atomic_write", "PUBLIC_FILE", "PUBLIC_DIR", "Entry", "collect", "read_entry", "shown", "student_id",
           "id_key", "file_time", "MAX_ID_CHARS"]



#: Files and directories an instructor hands out (releases, feedback pages): readable by everyone, as nbgrader
#: makes them, whatever the umask.
PUBLIC_FILE, PUBLIC_DIR = 0o644, 0o755


def shown(path):
    """``path`` as text that every file, database and terminal takes: bytes that are not UTF-8 (Python keeps them
    as lone surrogates, which SQLite and a UTF-8 file refuse) and control characters (a newline, a terminal's
    escape sequences) are written as escapes.

    >>> shown("collected/bad\\udcff\\x1b[2J\\n.ipynb")
    'collected/bad\\\\xff\\\\x1b[2J\\\\n.ipynb'
    """
    text = os.fsencode(path).decode("utf-8", "backslashreplace")
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def file_time(seconds):
    """A file's modification time (seconds since 1970) as ISO 8601 in UTC. A time no calendar holds (past the
    year 9999, before the year 1, not a number) is read as the latest or the earliest time there is: the
    submission's problem — late, not a crash of the run.

    >>> file_time(0)
    '1970-01-01T00:00:00+00:00'
    >>> file_time(10**12)
    '9999-12-31T23:59:59+00:00'
    """
    try:
        return _dt.datetime.fromtimestamp(int(seconds), _dt.timezone.utc).isoformat()
    except (ValueError, OverflowError, OSError):
        edge = _dt.datetime.max if not seconds < 0 else _dt.datetime.min
        return edge.replace(microsecond=0, tzinfo=_dt.timezone.utc).isoformat()


@dataclass
class Entry:
    """One entry found by :func:`collect`: a submission to grade, or a file that is not, with the reason.

    Attributes
    ----------
    path : str
        For messages and the gradebook (never opened by this path): :func:`shown`, so that a file name that is
        not UTF-8 or holds control characters cannot break the gradebook or the instructor's terminal.
    root : str
        The directory (or file) the instructor named; ``parts`` lead from it to the file.
    parts : tuple of str
    ident : tuple or None
        (device, inode, size) as listed.
    student : str
        The kinbook id ("" for an entry that names no student).
    status, message : str or None
        None for a submission to grade; else why it is not graded: ``ignored`` (not a notebook, a hidden name, not
        named after the exercise …), ``superseded`` (an earlier attempt of a student whose latest one is graded),
        ``refused`` (a link, a device, a hard link, the instructor's own source …), ``too-large``, ``bad-id``,
        ``duplicate-id``.
    submitted : str
        When it was handed in (ISO 8601): the LMS's (a pattern's ``time`` group; no zone: read in the due date's)
        or the file's time (:func:`file_time`), never a date the student wrote in a file's name.
    submitted_from : str
        ``"lms"``, ``"file"`` or "". (Gradebooks made before issue 36 may hold ``"name"``.)
    late : bool
        The LMS marked it late in its name.
    attempt : int
        The attempt number read from the name (0: none).
    on_roster : bool or None
        None when no roster was given.
    result : bool
        Whether the entry stands for its student in the gradebook (a file refused beside a gradable one of the same
        student does not: it is listed, not graded).
    order : tuple
        Where the file stands among its student's own files: the LMS's submission number and attempt time, the
        attempt suffix and date of its name (:attr:`kinbook.classroom.naming.Name.order`), then its file time and
        path.
    """

    path: str
    root: str
    parts: tuple
    ident: tuple | None
    student: str
    status: str | None = None
    message: str | None = None
    submitted: str = ""
    submitted_from: str = ""
    late: bool = False
    attempt: int = 0
    on_roster: bool | None = None
    result: bool = True
    mtime: float = 0.0
    sha256: str = ""
    replace: int | None = None
    base: str = ""
    signals: list = field(default_factory=list)
    order: tuple = ()
    _named: bool | None = None


def _kind(mode):
    for test, word in ((stat.S_ISLNK, "a symbolic link"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISCHR, "a device"),
                       (stat.S_ISBLK, "a device"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return word
    return "not a regular file"


#: Policies that choose among a student's attempts.
POLICIES = ("latest", "best")


def collect(paths, exercise, *, max_bytes, pattern=None, roster=None, policy="latest", file_times=False):
    """Every entry below ``paths`` (files, or directories searched through), each with its student or the reason it is
    not graded.

    In a directory, without a pattern, the notebooks named after the exercise (``<exercise>.ipynb``,
    ``<exercise>-<student>.ipynb``, with attempt suffixes) are taken, or every notebook when none is; the others are
    listed ``ignored``. Entries that are links, devices, FIFOs, sockets or hard links are ``refused`` (never followed
    or opened), files over ``max_bytes`` ``too-large``; hidden names, Jupyter's checkpoints and files that are not
    notebooks ``ignored``. The student's id, the attempt and the time come from the path
    (:func:`kinbook.classroom.naming.read_name`, ``pattern`` an ``--id-pattern``) and, with a ``roster``
    (:class:`kinbook.classroom.roster.Roster`), are mapped to the roster's kinbook id. Several attempts of one student:
    with ``policy`` "latest" the latest is graded and the others are ``superseded``; with "best" all are graded.
    A submission's time comes from the LMS (a pattern's ``time`` group), or with ``file_times`` from the file's
    modification time, never from a date in a name the student chose (the file's time is kept only where
    the download kept it: ``unzip`` does, Python's ``zipfile`` does not).

    Returns
    -------
    list of Entry
        In a stable order (by path).
    """
    if policy not in POLICIES:
        raise ValueError(f"policy must be one of {', '.join(POLICIES)}, got {policy!r}")
    rx = compile_pattern(pattern)
    found = []  # (parts, root, stat or None, problem)
    for given in paths:
        given = os.fspath(given)
        root = os.path.dirname(given) or "."
        try:
            st = os.lstat(given)
        except OSError as exc:
            found.append(((os.path.basename(given),), root, None, ("refused", f"cannot be read: {exc.strerror}")))
            continue
        if stat.S_ISDIR(os.stat(given).st_mode):  # the directory the instructor named: followed if a link
            found += _walk(given)
        else:
            found.append(((os.path.basename(given),), root, st, _problem(os.path.basename(given), st, True)))
    entries = [_entry(parts, root, st, problem, exercise, rx, roster, max_bytes, file_times)
               for parts, root, st, problem in found]
    if rx is None and any(e._named for e in entries):
        for e in entries:
            if e._named is False and e.status is None:
                e.status, e.result = "ignored", False
                e.message = (f"not named after the exercise {exercise!r} (other notebooks here are): not graded; "
                             "rename it, or give --id-pattern")
    _attempts(entries, policy, exercise, max_bytes)
    return sorted(entries, key=lambda e: e.path)


def _entry(parts, root, st, problem, exercise, rx, roster, max_bytes, file_times):
    """The :class:`Entry` of one listed path: its student, attempt and time read from the path, or why not."""
    readable = st is not None and problem is None
    e = Entry(shown(os.path.join(root, *parts)), root, parts, (st.st_dev, st.st_ino, st.st_size) if readable else None,
              "")
    if problem is not None and problem[0] == "ignored":
        e.status, e.message, e.result = problem[0], problem[1], False
        if st is not None and not parts[-1].startswith(".") and not parts[-1].endswith(".ipynb"):
            _owner(e, parts, root, exercise, rx, roster)  # a PDF, a zip: whose it is, for the report and feedback
        return e
    if st is not None:
        e.mtime = st.st_mtime
    name = read_name(parts, exercise, os.path.basename(os.path.realpath(root)), rx,
                     roster.knows if roster is not None else None)
    e._named, e.attempt, e.late, e.base = name.exercise_named, name.attempt, name.late, name.base
    if name.time is not None:  # the LMS's own field (a pattern's `time` group), never a date the student wrote
        e.submitted, e.submitted_from = name.time.isoformat(), "lms"
    elif st is not None and file_times:
        e.submitted, e.submitted_from = file_time(st.st_mtime), "file"
    e.order = name.order + (e.mtime, e.path)
    if name.names is not None and id_key(name.names) != id_key(name.raw):
        e.signals.append(("names-another", f"the file's name {shown(parts[-1])!r} names {shown(name.names)!r}, "
                                           f"not the student of its folder"))
    if name.raw is None:
        # a link, a device or a hard link (the instructor's source unpacked into collected/) says so, named or not
        e.status, e.message = problem if problem is not None else ("ignored", f"no student: the path {name.why}")
        e.result = False
        return e
    known = roster.find(name.raw, name.key) if roster is not None else None
    if known is not None and _look_alike(name.raw, known.student):
        known = None  # 'ａｌｉｃｅ' is not alice: only the same letters, in any case or Unicode form, are
    if known is not None:
        e.student, e.on_roster = known.student, True
    else:
        e.student, bad = student_id(name.raw)
        e.on_roster = False if roster is not None else None
        if bad and problem is None:
            problem = ("bad-id", bad)
    if problem is not None:
        e.status, e.message = problem
    elif e.ident[2] > max_bytes:
        e.status, e.message = "too-large", f"the file has {e.ident[2]:,} bytes (at most {max_bytes:,}); not read"
    return e


def _owner(e, parts, root, exercise, rx, roster):
    """Tie a file that is not a notebook to its student, when its path names one surely (an ``--id-pattern``, a
    student's folder, or an id on the roster); its status stays ``ignored``."""
    name = read_name(parts, exercise, os.path.basename(os.path.realpath(root)), rx,
                     roster.knows if roster is not None else None)
    if name.raw is None:
        return
    known = roster.find(name.raw, name.key) if roster is not None else None
    if known is None and rx is None and len(parts) < 2:
        return  # a loose file beside the notebooks: its name is not a student's for sure
    e.student = known.student if known is not None else student_id(name.raw)[0]
    e.on_roster = (known is not None) if roster is not None else None
    e.message = f"{kind_of_file(parts[-1])}, not a notebook (.ipynb): not graded"


def _look_alike(raw, sid):
    """Whether ``raw`` meets the roster's ``sid`` only through Unicode compatibility forms (full-width letters,
    ligatures, superscripts …): a look-alike, not the student (case and NFC/NFD are the same student's)."""
    nfc = unicodedata.normalize("NFC", raw).casefold()
    return id_key(raw) == id_key(sid) and nfc != unicodedata.normalize("NFC", sid).casefold()


def _attempts(entries, policy, exercise, max_bytes):
    """Group the entries of one student (ids compared by :func:`id_key`), then choose among their files. Spellings
    that only meet once folded: the real student's (on the roster; else the one spelling that is its own NFKC form)
    keeps their files, and a look-alike (``ａｌｉｃｅ`` beside ``alice``) is a signal and a ``duplicate-id`` of its own
    — never a clash that zeroes the real one. Only where no spelling can be told real (``Ana`` and ``ana``, no
    roster) are all of them ``duplicate-id``. Several notebooks of one id are one submission's files or attempts
    (:func:`kinbook.classroom.choice.choose`)."""
    by_key = {}
    for e in entries:
        if e.student and e.status not in ("ignored",):
            by_key.setdefault(id_key(e.student), []).append(e)
    for same in by_key.values():
        spellings = {e.student for e in same}
        if len(spellings) > 1:
            real = {e.student for e in same if e.on_roster} or {
                sid for sid in spellings if unicodedata.normalize("NFKC", sid) == sid}
            if len(real) != 1:
                for e in same:
                    e.status, e.message = "duplicate-id", (
                        f"the id {e.student!r} is spelled differently by another submission (equal once case and "
                        "Unicode forms are folded): none of them is graded; rename the folders or give a roster")
                continue
            (real,) = real
            for e in same:
                if e.student != real:
                    e.status, e.message = "duplicate-id", (
                        f"the id {e.student!r} looks like the id of another student (equal once case and Unicode "
                        "forms are folded): not graded")
                    e.signals.append(("look-alike", f"the id {e.student!r} looks like {real!r}"))
            same = [e for e in same if e.student == real]
        if len(same) < 2:
            continue
        good = sorted((e for e in same if e.status is None), key=lambda e: e.order)
        if good:
            for e in same:
                if e.status is not None:
                    e.result = False
                    e.message += f" (another file of {e.student} is graded)"
            choose(good, policy, exercise, lambda e: read_entry(e, max_bytes))
        else:
            for e in same[:-1]:
                e.result = False


def _problem(name, st, named_by_instructor=False):
    """(status, reason) for a listed entry that is not read, or None."""
    if stat.S_ISLNK(st.st_mode) or not stat.S_ISREG(st.st_mode):
        return "refused", f"{_kind(st.st_mode)}: not followed"
    if not named_by_instructor and name.startswith("."):
        return "ignored", "a hidden name (editors and archives leave these): not read"
    if not named_by_instructor and not name.endswith(".ipynb"):
        return "ignored", "not a notebook (.ipynb): not read"
    if st.st_nlink > 1:
        return "refused", (f"a hard link (one of {st.st_nlink} names of the same file, maybe the instructor's source or "
                           "a classmate's file): not read")
    return None


_SPECIAL_DIRS = {".ipynb_checkpoints": "Jupyter's autosaved checkpoints: not read",
                 "__MACOSX": "macOS archive metadata (made by unzipping on a Mac): not read",
                 "__pycache__": "Python's cache: not read"}


def _walk(top):
    """(parts, root, stat, problem) of every entry below ``top`` (directories that are not searched included)."""
    out = []
    try:
        fd = os.open(top, os.O_RDONLY | os.O_DIRECTORY)
    except OSError as exc:
        return [((os.path.basename(top),), os.path.dirname(top) or ".", None,
                 ("refused", f"cannot be read: {exc.strerror}"))]
    stack = [(fd, ())]
    while stack:
        dfd, prefix = stack.pop()
        try:
            with os.scandir(dfd) as it:
                listing = sorted(((e.name, e.stat(follow_symlinks=False)) for e in it), key=lambda x: x[0])
        except OSError:
            listing = []
        for name, st in listing:
            parts = prefix + (name,)
            if stat.S_ISDIR(st.st_mode):
                if name in _SPECIAL_DIRS or name.startswith("."):
                    out.append((parts, top, None, ("ignored", _SPECIAL_DIRS.get(
                        name, "a hidden directory (its name starts with '.'): not searched"))))
                    continue
                try:
                    sub = os.open(name, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=dfd)
                except OSError as exc:
                    out.append((parts, top, None, ("refused", f"directory cannot be read: {exc.strerror}")))
                    continue
                if (os.fstat(sub).st_dev, os.fstat(sub).st_ino) != (st.st_dev, st.st_ino):
                    os.close(sub)
                    out.append((parts, top, None, ("refused", "the directory changed while it was listed")))
                    continue
                stack.append((sub, parts))
            else:
                out.append((parts, top, st, _problem(name, st)))
        os.close(dfd)
    return out


def read_entry(entry, max_bytes):
    """The bytes of ``entry``, opened without following any link and checked to be the file that was listed.

    Raises
    ------
    Refused
    """
    flags = os.O_RDONLY | os.O_NOFOLLOW | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    dirs = []
    try:
        dfd = os.open(entry.root, os.O_RDONLY | os.O_DIRECTORY)
        dirs.append(dfd)
        for part in entry.parts[:-1]:
            dfd = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=dfd)
            dirs.append(dfd)
        fd = os.open(entry.parts[-1], flags, dir_fd=dfd)
    except OSError as exc:
        raise Refused("refused", f"cannot be opened as a regular file ({exc.strerror}): not read") from None
    finally:
        for d in dirs:
            os.close(d)
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise Refused("refused", f"{_kind(st.st_mode)}: not read")
        if entry.ident is not None and (st.st_dev, st.st_ino) != entry.ident[:2]:
            raise Refused("refused", "the file was replaced after it was listed: not read")
        if st.st_nlink > 1:  # another name of a file elsewhere (the instructor's source, a classmate's notebook)
            raise Refused("refused", f"a hard link (this file has {st.st_nlink} names): not read — submit a copy")
        if st.st_size > max_bytes:
            raise Refused("too-large", f"the file has {st.st_size:,} bytes (at most {max_bytes:,}); not read")
        chunks, total = [], 0
        while True:
            chunk = os.read(fd, 1 << 20)
            if not chunk:
                break
            total += len(chunk)
            if total > max_bytes:
                raise Refused("too-large", f"the file has more than {max_bytes:,} bytes; not read")
            chunks.append(chunk)
        return b"".join(chunks)
    finally:
        os.close(fd)
