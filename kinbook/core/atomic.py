"""The one writer of files: whole or not at all, and never over a command's own inputs.

Every file kinbook writes for a user (released notebooks, variants, the gradebook's exports, feedback pages,
reports, exercises copied out, animations) goes through :func:`atomic_write`: the data is written to a temporary
file in the target's directory, synced, then renamed over the target (``os.replace``). A reader — or a disk that
fills up half-way — sees the old file or the new one, never a 0-byte or half-written one.

A command names its inputs (the gradebook, the roster, the source, the collected files) with :func:`protect`, or
checks its planned outputs at once with :func:`refuse_overwrite` before it writes anything: an output that *is* an
input — the same file by device and inode (a hard link, a symbolic link, ``./x`` and ``x``), or the same resolved
path when it does not exist yet — is an :class:`~kinbook.errors.OverwriteError` naming both paths.

Failures are the user's words: a read-only directory or a permission is a :class:`~kinbook.errors.WriteError`, a full
disk or quota a :class:`~kinbook.errors.DiskFullError`, each naming the file.
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import os
import tempfile
from pathlib import Path

from ..errors import DiskFullError, OverwriteError, WriteError

__all__ = ["atomic_write", "write_all", "same_file", "protect", "refuse_overwrite", "write_error", "FULL", "DENIED"]

#: errno values that mean "no room": a full device, a used-up quota, a file too large for the file system.
FULL = {errno.ENOSPC, getattr(errno, "EDQUOT", errno.ENOSPC), errno.EFBIG}
#: errno values that mean "not allowed to write here".
DENIED = {errno.EACCES, errno.EPERM, errno.EROFS}

_PROTECTED = contextvars.ContextVar("kinbook_protected_inputs", default=())


def _umask():
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def same_file(a, b):
    """Whether paths ``a`` and ``b`` name the same file: the same device and inode when both exist (hard and
    symbolic links, ``./x`` and ``x``), else the same fully resolved path."""
    try:
        return os.path.samestat(os.stat(a), os.stat(b))
    except (OSError, ValueError):
        pass
    try:
        return os.path.realpath(a) == os.path.realpath(b)
    except (OSError, ValueError):
        return False


def write_error(exc, path, doing="write"):
    """The :class:`~kinbook.errors.WriteError` (or :class:`~kinbook.errors.DiskFullError`) for an ``OSError`` met while
    writing ``path``, in the user's words."""
    path = str(path)
    code = getattr(exc, "errno", None)
    if code in FULL:
        return DiskFullError(f"cannot {doing} {path!r}: no space left on the device (or the disk quota is used up); "
                             "nothing was half-written — free some space and run the command again", path=path)
    if code in DENIED:
        where = os.path.dirname(os.path.abspath(path)) or "."
        why = "the file system is read-only" if code == errno.EROFS else "permission denied"
        return WriteError(f"cannot {doing} {path!r}: {why} (the directory {where!r} must be writable by you); "
                          "choose another output", path=path)
    reason = getattr(exc, "strerror", None) or str(exc)
    return WriteError(f"cannot {doing} {path!r}: {reason}", path=path)


def _inputs_of(path):
    """(label, input path) of the protected inputs ``path`` is the same file as."""
    return [(label, given) for label, given in _PROTECTED.get() if same_file(path, given)]


def refuse_overwrite(outputs, inputs=(), command="this command"):
    """Raise :class:`~kinbook.errors.OverwriteError` when one of ``outputs`` (paths) is one of ``inputs`` (``(label,
    path)`` pairs, e.g. ``("the gradebook", "graded/gradebook.sqlite")``) or of the inputs :func:`protect` holds.
    Called before anything is written."""
    inputs = list(inputs) + list(_PROTECTED.get())
    for out in outputs:
        for label, given in inputs:
            if given is not None and same_file(out, given):
                raise OverwriteError(f"{command} would write over its own input: the output {str(out)!r} is {label} "
                                     f"{str(given)!r}; nothing was written — choose another output",
                                     path=str(out), input=str(given))


@contextlib.contextmanager
def protect(*inputs):
    """Within the block, :func:`atomic_write` refuses to replace any of ``inputs`` (``(label, path)`` pairs; a
    ``None`` path is skipped)."""
    token = _PROTECTED.set(_PROTECTED.get() + tuple((label, os.fspath(p)) for label, p in inputs if p is not None))
    try:
        yield
    finally:
        _PROTECTED.reset(token)


def _write_all(fd, data):
    view = memoryview(data)
    while view:
        n = os.write(fd, view)
        view = view[n:]


def _stage(path, data, mode, dir_mode):
    """Write ``data`` to a synced temporary file beside ``path``; returns its name (nothing replaced yet)."""
    path = Path(path)
    refuse_overwrite([path], command="kinbook")
    if path.is_dir():
        raise WriteError(f"cannot write {str(path)!r}: it is a directory", path=str(path))
    payload = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    try:
        missing = [p for p in reversed(path.parents) if not p.exists()]
        path.parent.mkdir(parents=True, exist_ok=True)
        if dir_mode is not None:
            for d in missing:
                os.chmod(d, dir_mode)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    except FileExistsError:
        raise WriteError(f"cannot write {str(path)!r}: a directory on its way is a file", path=str(path)) from None
    except OSError as exc:
        raise write_error(exc, path) from None
    try:
        try:
            os.fchmod(fd, (0o666 & ~_umask()) if mode is None else mode)
            _write_all(fd, payload)
            os.fsync(fd)
        finally:
            os.close(fd)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError):
            raise write_error(exc, path) from None
        raise
    return tmp


def _commit(tmp, path, overwrite=True):
    try:
        if overwrite:
            os.replace(tmp, path)
        else:  # no-clobber and still atomic: a second name for the whole file, made only if none exists
            try:
                os.link(tmp, path)
            finally:
                os.unlink(tmp)
    except FileExistsError:
        raise _exists(path) from None
    except OSError as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise write_error(exc, path) from None


def _exists(path):
    return WriteError(f"{str(path)!r} already exists: not overwritten (remove it, or write into another directory)",
                      path=str(path))


def atomic_write(path, data, mode=None, dir_mode=None, *, overwrite=True):
    """Write ``data`` (str, as UTF-8, or bytes) to ``path`` whole or not at all.

    Parameters
    ----------
    path : path
        The file to write; its missing directories are created.
    data : str or bytes
    mode : int, optional
        The file's permissions (default: what ``open`` would give, 0666 less the umask).
    dir_mode : int, optional
        The permissions of the directories this call creates (default: ``mkdir``'s).
    overwrite : bool
        False: an existing ``path`` is kept and a :class:`~kinbook.errors.WriteError` says so.

    Returns
    -------
    Path

    Raises
    ------
    OverwriteError
        ``path`` is an input the caller protects (:func:`protect`).
    WriteError, DiskFullError
        The directory cannot be written, or the disk is full; the old file (or none) is left as it was.
    """
    if not overwrite and os.path.lexists(path):
        raise _exists(path)  # said before anything is written
    _commit(_stage(path, data, mode, dir_mode), path, overwrite)
    return Path(path)


def write_all(files, mode=None, dir_mode=None):
    """Write several files all or none: every one is first written whole to its temporary file (a full disk, a
    read-only directory or a protected input stops here, and every temporary file is removed: nothing was changed),
    then each is renamed into place. ``files``: ``[(path, data)]``. Returns the paths, in order.

    The renames cannot run out of space; only a crash between two of them leaves some files new and some old —
    each of them whole."""
    files = [(Path(p), d) for p, d in files]
    seen = {}
    for p, _ in files:
        key = os.path.normcase(os.path.abspath(p))
        if key in seen:
            raise WriteError(f"two of the files to write are one file: {str(seen[key])!r} and {str(p)!r}", path=str(p))
        seen[key] = p
    staged = []
    try:
        for p, d in files:
            staged.append((_stage(p, d, mode, dir_mode), p))
    except BaseException:
        for tmp, _ in staged:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        raise
    for i, (tmp, p) in enumerate(staged):
        try:
            _commit(tmp, p)
        except BaseException:
            for later, _ in staged[i + 1:]:
                with contextlib.suppress(OSError):
                    os.unlink(later)
            raise
    return [p for _, p in staged]
