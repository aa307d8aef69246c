"""Files of the instructor's workflow: the one atomic writer, and reading ``collected/`` as untrusted input.

:func:`atomic_write` is how every file kinbook produces for an instructor is written (released notebooks,
the manifest, the gradebook's exports): a temporary file in the same directory, flushed and synced, then
``os.replace`` — a reader sees the old file or the new one, never half of one.

:func:`collect` walks the submissions an instructor names. Whatever is inside a named directory was put
there by students, so it is treated as hostile:

* entries are listed through directory descriptors, never through paths; symbolic links, devices, FIFOs and
  sockets are refused per entry (status ``refused``) and never followed or opened;
* a file is opened relative to its directory's descriptor with ``O_NOFOLLOW | O_NONBLOCK`` and must be the
  very regular file that was listed (same device and inode: a file swapped for a link, a FIFO or another file
  between listing and reading is refused), no larger than the size cap (``too-large``, before reading);
* the student id comes from the path (:func:`student_id`): Unicode NFC, letters, digits and ``._@+-``, at most
  :data:`MAX_ID_CHARS` characters; ids that are too long (``bad-id``) or that clash once case and Unicode
  compatibility forms are folded (``duplicate-id``) are reported per entry, and the batch goes on.
"""

from __future__ import annotations

import hashlib
import os
import stat
import tempfile
import unicodedata
from dataclasses import dataclass
from pathlib import Path

from .results import Refused

__all__ = ["atomic_write", "Entry", "collect", "read_entry", "shown", "student_id", "MAX_ID_CHARS"]

MAX_ID_CHARS = 64
_ID_EXTRA = "._@+-"


def atomic_write(path, data):
    """Write ``data`` (str or bytes) to ``path`` through a temporary file in the same directory and
    ``os.replace``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode("utf-8") if isinstance(data, str) else data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def shown(path):
    """``path`` as text that every file, database and terminal takes: bytes that are not UTF-8 (Python keeps them
    as lone surrogates, which SQLite and a UTF-8 file refuse) and control characters (a newline, a terminal's
    escape sequences) are written as escapes.

    >>> shown("collected/bad\\udcff\\x1b[2J\\n.ipynb")
    'collected/bad\\\\xff\\\\x1b[2J\\\\n.ipynb'
    """
    text = os.fsencode(path).decode("utf-8", "backslashreplace")
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def student_id(name):
    """The student id for a name taken from a path: ``(id, problem)`` with problem None or a message.

    NFC-normalized; characters other than letters, digits and ``._@+-`` become ``_``; no leading dot.
    Longer than :data:`MAX_ID_CHARS`: the id is shortened (with a hash of the whole name, so that it stays
    unique) and the problem says why it is not graded.

    >>> student_id("José")
    ('José', None)
    >>> student_id("a b/c")
    ('a_b_c', None)
    """
    name = unicodedata.normalize("NFC", str(name))
    sid = "".join(c if (c.isalnum() or c in _ID_EXTRA) else "_" for c in name).lstrip(".") or "unknown"
    if len(sid) > MAX_ID_CHARS:
        digest = hashlib.sha256(name.encode("utf-8", "surrogateescape")).hexdigest()[:8]
        return f"{sid[:40]}…{digest}", (f"the student id taken from the path has {len(sid)} characters (at most "
                                        f"{MAX_ID_CHARS}): rename the file or directory and grade again")
    return sid, None


def id_key(sid):
    """Ids with the same key are the same student for a file system or a spreadsheet (case, Unicode forms)."""
    return unicodedata.normalize("NFKC", sid).casefold()


@dataclass
class Entry:
    """One submission found by :func:`collect`.

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
    status, message : str or None
        Why the entry is not graded (``refused``, ``too-large``, ``bad-id``, ``duplicate-id``), or None.
    """

    path: str
    root: str
    parts: tuple
    ident: tuple | None
    student: str
    status: str | None = None
    message: str | None = None


def _kind(mode):
    for test, word in ((stat.S_ISLNK, "a symbolic link"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISCHR, "a device"),
                       (stat.S_ISBLK, "a device"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return word
    return "not a regular file"


def _name_of(root, parts, exercise):
    """The student's name from a file's path: ``<student>/<exercise>.ipynb``, ``<exercise>-<student>.ipynb`` or
    ``<student>.ipynb``."""
    stem = parts[-1][:-len(".ipynb")] if parts[-1].endswith(".ipynb") else parts[-1]
    if stem == exercise:
        return parts[-2] if len(parts) > 1 else os.path.basename(os.path.realpath(root))
    if stem.startswith(exercise + "-"):
        return stem[len(exercise) + 1:]
    return stem


def collect(paths, exercise, *, max_bytes):
    """The submissions of ``exercise`` among ``paths`` (files, or directories searched through).

    In a directory, the notebooks named after the exercise (``<exercise>.ipynb``, ``<exercise>-<student>.ipynb``)
    are taken, or every notebook when none is. Entries that are links, devices, FIFOs or sockets — notebooks,
    or directories a student could have made — are returned refused, as are files over ``max_bytes``.

    Returns
    -------
    list of Entry
        In a stable order (by path).
    """
    found = []  # (parts, root, ident or None, problem)
    for given in paths:
        given = os.fspath(given)
        try:
            st = os.lstat(given)
        except OSError as exc:
            found.append(((os.path.basename(given),), os.path.dirname(given) or ".", None,
                          ("refused", f"cannot be read: {exc.strerror}")))
            continue
        if stat.S_ISDIR(os.stat(given).st_mode):  # the directory the instructor named: followed if a link
            found += _walk(given)
        elif stat.S_ISREG(st.st_mode):
            found.append(((os.path.basename(given),), os.path.dirname(given) or ".", (st.st_dev, st.st_ino, st.st_size),
                          None))
        else:
            found.append(((os.path.basename(given),), os.path.dirname(given) or ".", None,
                          ("refused", f"{_kind(st.st_mode)}: not read")))
    named = [f for f in found if f[0][-1] in (f"{exercise}.ipynb",) or f[0][-1].startswith(exercise + "-")]
    if named:
        found = named + [f for f in found if f[3] is not None and f not in named and not f[0][-1].endswith(".ipynb")]
    entries = []
    for parts, root, ident, problem in found:
        sid, bad = student_id(_name_of(root, parts, exercise))
        e = Entry(shown(os.path.join(root, *parts)), root, parts, ident, sid)
        if problem is not None:
            e.status, e.message = problem
        elif ident[2] > max_bytes:
            e.status, e.message = "too-large", f"the file has {ident[2]:,} bytes (at most {max_bytes:,}); not read"
        elif bad:
            e.status, e.message = "bad-id", bad
        entries.append(e)
    by_key = {}
    for e in entries:
        by_key.setdefault(id_key(e.student), []).append(e)
    for same in by_key.values():
        if len(same) > 1:
            for e in same:
                others = ", ".join(o.path for o in same if o is not e)[:300]
                e.status, e.message = "duplicate-id", (f"more than one submission for student {e.student!r} (also "
                                                       f"{others}); none of them is graded")
    return sorted(entries, key=lambda e: e.path)


def _walk(top):
    """(parts, root, ident, problem) of the notebooks below ``top`` and of every entry that is refused."""
    out = []
    try:
        fd = os.open(top, os.O_RDONLY | os.O_DIRECTORY)
    except OSError as exc:
        return [((os.path.basename(top),), os.path.dirname(top) or ".", None, ("refused", f"cannot be read: {exc.strerror}"))]
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
            if name == ".ipynb_checkpoints" or (name.startswith(".") and stat.S_ISDIR(st.st_mode)):
                continue
            if stat.S_ISDIR(st.st_mode):
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
            elif stat.S_ISREG(st.st_mode):
                if name.endswith(".ipynb"):
                    out.append((parts, top, (st.st_dev, st.st_ino, st.st_size), None))
            else:  # a link, a FIFO, a device, a socket: never followed, never opened
                out.append((parts, top, None, ("refused", f"{_kind(st.st_mode)}: not followed")))
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
