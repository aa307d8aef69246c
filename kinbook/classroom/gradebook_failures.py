"""What can go wrong with a gradebook file, in the instructor's words (:class:`kinbook.classroom.gradebook.Gradebook`
opens through these).

* a grading directory that does not exist, or holds no gradebook, is refused by every command but ``grade`` — a
  mistyped ``-g`` never makes an empty gradebook (:func:`must_exist`);
* another kinbook run that holds the gradebook is waited for, a bounded time and saying so (:func:`wait_for_lock`);
* every ``sqlite3`` or ``OSError`` met on the gradebook becomes a :class:`~kinbook.errors.GradebookError` subclass that
  names the file and what to do (:func:`gradebook_error`): not a gradebook, read-only, locked, full disk.
"""

from __future__ import annotations

import errno
import os
import sqlite3
import sys
import time

from ..errors import (
    GradebookError,
    GradebookFullError,
    GradebookLockedError,
    GradebookReadOnlyError,
    NotAGradebookError,
)

__all__ = ["must_exist", "wait_for_lock", "gradebook_error"]

DATABASE = "gradebook.sqlite"


def must_exist(outdir, path):
    """A command that reads a gradebook refuses a missing one instead of creating it empty."""
    if not outdir.exists():
        raise NotAGradebookError(f"no grading directory {str(outdir)!r} (a mistyped -g?): give the directory kinbook "
                                 "grade wrote, which holds gradebook.sqlite; nothing was created")
    if not outdir.is_dir():
        raise NotAGradebookError(f"the grading directory {str(outdir)!r} is a file, not a directory: give the "
                                 "directory that holds gradebook.sqlite (-g)")
    if not path.is_file() or path.stat().st_size == 0:
        raise NotAGradebookError(f"{str(outdir)!r} holds no gradebook ({DATABASE}): give the directory kinbook grade "
                                 "wrote (-g), or grade first; nothing was created")


def wait_for_lock(book, notify):
    """Wait, a bounded time and saying so, while another run holds the gradebook's write lock."""
    deadline = time.monotonic() + book.wait
    said = False
    while True:
        try:
            book.db.execute("BEGIN IMMEDIATE")
            book.db.execute("ROLLBACK")
            return
        except sqlite3.OperationalError as exc:
            if "locked" not in str(exc) and "busy" not in str(exc):
                raise
            if time.monotonic() >= deadline:
                raise GradebookLockedError(
                    f"the gradebook {str(book.path)!r} is in use by another kinbook run ({_holder(book)}) — waited "
                    f"{book.wait:g} s; let it finish, or stop it, and run this command again (nothing was "
                    "changed)") from None
            if not said:
                (notify or _stderr)(f"kinbook: the gradebook {str(book.path)!r} is in use by another kinbook run "
                                    f"({_holder(book)}); waiting up to {book.wait:g} s for it …")
                said = True
            time.sleep(0.2)


def _holder(book):
    """Which run holds the gradebook, as far as it says: the latest grading run not finished (a reader sees it while
    the other run writes, in WAL mode), else a command that hangs."""
    try:
        row = book.db.execute("SELECT exercise, started FROM runs WHERE finished IS NULL ORDER BY id DESC "
                              "LIMIT 1").fetchone()
    except sqlite3.Error:
        row = None
    if row:
        return f"probably the grading of {row[0]} started {row[1]}, not finished"
    return "a grading still going on, or a command that hangs"


def _stderr(line):
    print(line, file=sys.stderr, flush=True)


def gradebook_error(exc, path):
    """The :class:`~kinbook.errors.GradebookError` for an ``sqlite3.Error`` or ``OSError`` met on the gradebook
    ``path``: in the instructor's words, naming the file and what to do. Nothing recorded before is lost (every
    result is its own transaction)."""
    if isinstance(exc, GradebookError):
        return exc
    path = str(path)
    text = str(exc).lower()
    code = getattr(exc, "errno", None)
    if "full" in text or code in (errno.ENOSPC, getattr(errno, "EDQUOT", errno.ENOSPC)):
        return GradebookFullError(f"the gradebook {path!r} cannot grow: the disk (or the quota) is full; every result "
                                  "recorded before is kept — free some space and run the command again", path=path)
    if "readonly" in text or "read-only" in text or code in (errno.EACCES, errno.EPERM, errno.EROFS) or (
            "unable to open" in text and not os.access(os.path.dirname(path) or ".", os.W_OK)):
        return GradebookReadOnlyError(f"the gradebook {path!r} cannot be written: it or its directory is read-only "
                                      "(permissions, a read-only disk); kinbook needs to write beside it (its journal) "
                                      "— make the directory writable, or work on a copy")
    if "locked" in text or "busy" in text:
        return GradebookLockedError(f"the gradebook {path!r} is in use by another kinbook run; let it finish, or stop "
                                    "it, and run this command again (nothing was changed)")
    if "not a database" in text or "malformed" in text or "encrypted" in text:
        return NotAGradebookError(f"{path!r} is not a kinbook gradebook (another file, or a damaged one): "
                                  f"{exc}; it was not changed — restore it from a backup, or move it away to start a "
                                  "new one")
    if "disk i/o" in text:
        return GradebookFullError(f"the gradebook {path!r} could not be written (disk I/O error: a full or failing "
                                  "disk?); every result recorded before is kept — check the disk and run the command "
                                  "again", path=path)
    return GradebookError(f"the gradebook {path!r} cannot be used: {type(exc).__name__}: {exc}")
