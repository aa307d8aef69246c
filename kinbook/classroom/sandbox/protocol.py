"""What the grading process and the sandbox's processes agree on: directories, descriptors, message frames,
bounds, and two process-lifetime helpers.

Both sides import this module (standard library only); neither imports the other's module, so there is no
import cycle between :mod:`.host` and :mod:`.zygote`.

Channels between the grading process (outside) and the sandbox (inside)
    the command pipe (the zygote's stdin)
        commands, one line each: ``run``, ``reset``, ``stop`` (end of file also stops it);
    the event pipe (the zygote's stdout)
        events, one line each: ``ready``, ``worker PID``, ``exit N`` / ``signal N`` (the worker ended),
        ``clean`` / ``dirty REASON`` (after ``reset``). Both are passed to the zygote as descriptors of their
        own, never as bubblewrap's standard input and output;
    descriptor :data:`JOB_FD` (read end, inside)
        one job frame per ``run``, read by that run's worker only — the zygote never reads it, so no
        submission ever enters the zygote's memory (which every later kernel would inherit);
    descriptor :data:`RESULT_FD` (write end, inside)
        per run, a ``{"status": "running"}`` frame, written by the worker just before it sends the first cell
        to the kernel (a run that ends without it ran no code of the submission: its failure is the grader's,
        and the run is tried again), then one result frame, written by the worker. The grading process reads at most
        :data:`MAX_RESULT_BYTES` of it and treats it as untrusted data (:func:`kinbook.classroom.sandbox.host`
        validates every field).

Nothing else crosses: no file of the grading process is visible inside the sandbox, and no file the
sandbox writes is read by the grading process.
"""

from __future__ import annotations

import ctypes
import json
import math
import os
import select
import signal
import time
from dataclasses import asdict, dataclass

__all__ = ["Layout", "JOB_FD", "RESULT_FD", "MAX_SUBMISSION_BYTES", "MAX_JOB_BYTES", "MAX_RESULT_BYTES", "job_frame",
           "read_job", "RUNNING", "ANSWERS", "FrameError", "write_frame", "ResultReader", "read_frame", "FrameReader", "die_with_parent", "set_dumpable", "set_child_subreaper",
           "cpu_seconds", "wall_seconds", "THREAD_ENV"]

JOB_FD = 3
RESULT_FD = 4
#: The largest submission graded (a larger one is ``too-large``, refused unread: :mod:`kinbook.classroom.notebook`).
MAX_SUBMISSION_BYTES = 8 * 1024 * 1024
#: A job carries the code cells as UTF-8 (never more bytes than they take in the submission's JSON: a character
#: is at least as long there, escaped or not) and a copy of the submission, after a header of a few kilobytes
#: (:func:`job_frame`): a submission under the cap always fits, whatever its characters — a frame limit that
#: does not follow from the cap lets a student's file make the grader fail (a notebook of 6.9 MB of DEL
#: characters, written JSON inside JSON, once took 48.5 MB).
MAX_JOB_BYTES = 2 * MAX_SUBMISSION_BYTES + (1 << 20)
#: The answers (at most 2 MB each, 100 of them in principle; far less in practice) and cell errors.
MAX_RESULT_BYTES = 16 * 1024 * 1024
_MAGIC = b"KBF1"
#: Thread pools of the numerical libraries, pinned to one thread in every process of the sandbox, in every mode: a
#: pool sized by the machine's cores (dozens on a server) would take a kernel past its control group's task
#: limit (:data:`kinbook.classroom.sandbox.cgroup.PIDS_MAX`) as it starts, and the sandbox has one CPU anyway.
THREAD_ENV = {name: "1" for name in (
    "OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS", "NUMEXPR_MAX_THREADS", "NUMBA_NUM_THREADS",
    "RAYON_NUM_THREADS", "TBB_NUM_THREADS")}
#: The status of the worker's first frame: the kernel is up and the first cell is about to be sent.
RUNNING = "running"
#: The status of the worker's frames between ``running`` and its result: the answers as read after a cell (in the
#: payload, kept unread by the grading process until the run ends without a result).
ANSWERS = "answers"


def cpu_seconds(timeout):
    """The kernel's CPU-time limit (``RLIMIT_CPU``) for a run limited to ``timeout`` seconds: the limit that
    decides a verdict of ``timeout``, the same on a quiet machine and a loaded one."""
    return max(1, math.ceil(float(timeout)))


def wall_seconds(timeout):
    """The wall-clock backstop of a run limited to ``timeout`` CPU seconds: it stops a notebook that waits
    (sleeps, blocks) instead of computing, and is far enough beyond the CPU limit that a notebook that computes
    meets that limit first, unless the machine is loaded many times over."""
    return 4.0 * float(timeout) + 60.0


@dataclass(frozen=True)
class Layout:
    """Where things are, as the processes in the sandbox see them.

    Attributes
    ----------
    home : str
        The submission's own copy: the kernel's working directory and HOME, writable.
    tmp : str
        A private temporary directory (the sandbox's ``/tmp``), writable.
    work : str
        The worker's control directory (the kernel's connection file and kernelspec).
    isolated : bool
        True inside bubblewrap (own pid namespace, an unprivileged uid, nothing of the host writable).
    """

    home: str
    tmp: str
    work: str
    isolated: bool

    @property
    def connection_file(self):
        """The kernel's connection file (written by the worker's jupyter_client, read by the kernel)."""
        return os.path.join(self.work, "connection.json")

    def to_json(self):
        return json.dumps(asdict(self))

    @classmethod
    def from_json(cls, text):
        return cls(**json.loads(text))


#: The layout inside bubblewrap (every directory a size-capped tmpfs of the sandbox).
ISOLATED = Layout(home="/home/student", tmp="/tmp", work="/run/kinbook/work", isolated=True)


def job_frame(cells, names, timeout, files=None, setup=None):
    """The job of one run as a frame's ``(header, payload)``: the code cells' sources and the files' bytes in the
    payload (the cells as UTF-8, lone surrogates kept), their sizes, the answer names and the kernel's ``setup``
    (the seed and the reference's names: :func:`kinbook.classroom.sandbox.trace.setup`) in the header.

    >>> header, payload = job_frame(["x = 1", "y = '\\x7f'"], ["x"], 5.0, {"a.ipynb": b"{}"})
    >>> read_job(header, payload)[0]
    ['x = 1', "y = '\\x7f'"]
    """
    files = dict(files or {})
    code = [str(c).encode("utf-8", "surrogatepass") for c in cells]
    setup = dict(setup or {})
    header = {"timeout": float(timeout), "names": [str(n) for n in names], "cells": [len(c) for c in code],
              "files": [[os.path.basename(k), len(v)] for k, v in files.items()],
              "setup": {"seed": int(setup.get("seed", 0)), "functions": sorted(map(str, setup.get("functions", ()))),
                        "methods": sorted(map(str, setup.get("methods", ())))}}
    return header, b"".join(code) + b"".join(files.values())


def read_job(header, payload):
    """``(cells, names, timeout, files, setup)`` of a job frame (:func:`job_frame`); :class:`FrameError` when it
    does not hold together."""
    try:
        sizes = [int(n) for n in header["cells"]] + [int(size) for _, size in header["files"]]
        names = [str(n) for n in header["names"]]
        timeout = float(header["timeout"])
        setup = header.get("setup") or {}
        setup = {"seed": int(setup.get("seed", 0)), "functions": [str(f) for f in setup.get("functions", [])],
                 "methods": [str(m) for m in setup.get("methods", [])]}
    except (KeyError, TypeError, ValueError, AttributeError):
        raise FrameError("the job's header is malformed") from None
    if any(n < 0 for n in sizes) or sum(sizes) != len(payload):
        raise FrameError("the job's sizes do not add up to its payload")
    pieces, offset = [], 0
    for n in sizes:
        pieces.append(payload[offset:offset + n])
        offset += n
    cells = [p.decode("utf-8", "surrogatepass") for p in pieces[:len(header["cells"])]]
    files = {os.path.basename(str(name)) or "file": data
             for (name, _), data in zip(header["files"], pieces[len(header["cells"]):])}
    return cells, names, timeout, files, setup


class FrameError(ValueError):
    """A frame that is malformed, too large, or did not arrive in time."""


def write_frame(fd, header, payload=b"", deadline=None):
    """Write ``header`` (a JSON-able dict) and ``payload`` (bytes) to ``fd`` as one frame.

    ``fd`` may be non-blocking; with ``deadline`` (a ``time.monotonic()`` value) the write gives up with
    :class:`FrameError` when it is not done by then (the reader is stuck or gone).
    """
    head = json.dumps(header).encode()
    data = b"%s %d %d\n" % (_MAGIC, len(head), len(payload)) + head + payload
    view = memoryview(data)
    while view:
        if deadline is not None:
            left = deadline - time.monotonic()
            if left <= 0:
                raise FrameError("the other side did not read the frame in time")
            _, ready, _ = select.select([], [fd], [], left)
            if not ready:
                continue
        try:
            n = os.write(fd, view)
        except BlockingIOError:
            continue
        except OSError as exc:
            raise FrameError(f"the frame could not be written: {exc}") from None
        view = view[n:]


class FrameReader:
    """Incremental reader of one frame from a (non-blocking) descriptor, with a size bound.

    Feed it with :meth:`feed` whenever the descriptor is readable; :attr:`frame` is ``(header, payload)``
    once complete, and :attr:`rest` what followed it. More than ``limit`` bytes, or a malformed prefix, raise
    :class:`FrameError`.
    """

    def __init__(self, limit):
        self.limit = limit
        self.buf = bytearray()
        self.need = None  # (header bytes, payload bytes) once the prefix line is read
        self.frame = None
        self.rest = b""  # what came after the frame (bounded by ``limit``)
        self.eof = False

    def feed(self, fd):
        """Read what is available; returns False at end of file."""
        try:
            chunk = os.read(fd, 1 << 16)
        except BlockingIOError:
            return True
        if not chunk:
            self.eof = True
            return False
        self.push(chunk)
        return True

    def push(self, chunk):
        """Take bytes (read from the descriptor, or what followed the previous frame)."""
        if self.frame is not None:
            if len(self.rest) <= self.limit:  # kept for a reader of the next frame; else drained and ignored
                self.rest += chunk
            return
        self.buf += chunk
        if len(self.buf) > self.limit + 64:
            raise FrameError(f"more than {self.limit // 2**20} MB")
        if self.need is None:
            end = self.buf.find(b"\n", 0, 64)
            if end < 0:
                if len(self.buf) >= 64:
                    raise FrameError("no frame header")
                return
            parts = bytes(self.buf[:end]).split(b" ")
            if len(parts) != 3 or parts[0] != _MAGIC or not parts[1].isdigit() or not parts[2].isdigit():
                raise FrameError("no frame header")
            self.need = (int(parts[1]), int(parts[2]))
            if sum(self.need) > self.limit:
                raise FrameError(f"more than {self.limit // 2**20} MB")
            del self.buf[:end + 1]
        h, p = self.need
        if len(self.buf) >= h + p:
            try:
                header = json.loads(bytes(self.buf[:h]))
            except (ValueError, RecursionError):  # nested deeper than the parser goes: data, not a grader failure
                raise FrameError("the frame header is not JSON (or nested too deeply)") from None
            if not isinstance(header, dict):
                raise FrameError("the frame header is not an object")
            self.frame = (header, bytes(self.buf[h:h + p]))
            self.rest = bytes(self.buf[h + p:])
            self.buf = bytearray()


def read_frame(fd, limit, timeout=None):
    """Read one frame from blocking or non-blocking ``fd``: ``(header, payload)``; :class:`FrameError` when it is
    malformed, larger than ``limit`` bytes, cut short, or not complete within ``timeout`` seconds."""
    reader = FrameReader(limit)
    deadline = None if timeout is None else time.monotonic() + timeout
    while reader.frame is None:
        if deadline is not None:
            left = deadline - time.monotonic()
            if left <= 0:
                raise FrameError("no frame in time")
            ready, _, _ = select.select([fd], [], [], left)
            if not ready:
                continue
        if not reader.feed(fd) and reader.frame is None:
            raise FrameError("the frame was cut short")
    return reader.frame


# ================================================================================== process lifetime (Linux)
_PR_SET_PDEATHSIG = 1
_PR_SET_DUMPABLE = 4
_PR_SET_CHILD_SUBREAPER = 36


def _prctl(option, value):
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(option, value, 0, 0, 0) == 0
    except (OSError, AttributeError):  # not Linux
        return False


def die_with_parent(parent_pid=None):
    """Have the kernel kill this process (SIGKILL) when its parent dies (``PR_SET_PDEATHSIG``).

    ``parent_pid`` is the parent expected; if it is already gone (it died before the call), this process
    exits at once. Returns whether the kernel took the request (Linux only).
    """
    ok = _prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL))
    if parent_pid is not None and os.getppid() != parent_pid:
        os._exit(1)
    return ok


def set_dumpable(flag):
    """``PR_SET_DUMPABLE``: a process that is not dumpable cannot be traced, nor its memory, descriptors or
    environment read through /proc, by other processes of the same user (without CAP_SYS_PTRACE)."""
    return _prctl(_PR_SET_DUMPABLE, 1 if flag else 0)


def set_child_subreaper():
    """``PR_SET_CHILD_SUBREAPER``: orphans among this process's descendants become its children (so that it
    can reap — and find — a daemon a student left behind)."""
    return _prctl(_PR_SET_CHILD_SUBREAPER, 1)


class ResultReader:
    """The worker's frames on the result pipe, as the grading process reads them from ``fd``: its ``running`` frame
    (:attr:`started`), the answers read after each cell that changed them (the last kept as bytes, unread until
    :meth:`kept`), then its result (``reader.frame``)."""

    def __init__(self, fd):
        self.fd = fd
        self.reader = FrameReader(MAX_RESULT_BYTES)
        self.started = False
        self.answers = None  # (payload, cell) of the last answers frame

    def kept(self):
        """The answers of the last ``answers`` frame, parsed (still to be validated), or None."""
        if self.answers is None:
            return None
        try:
            return json.loads(self.answers[0])
        except (ValueError, RecursionError):
            return None

    def _next(self):
        """Frames the worker sends before its result: taken here, the reader made ready for the next one."""
        while self.reader.frame is not None:
            header, payload = self.reader.frame
            if not self.started and header == {"status": RUNNING}:
                self.started = True  # from here on, the submission's code runs
            elif self.started and header.get("status") == ANSWERS:
                cell = header.get("cell")
                self.answers = (payload, cell if isinstance(cell, int) and not isinstance(cell, bool) else None)
            else:
                return
            rest, self.reader = self.reader.rest, FrameReader(MAX_RESULT_BYTES)
            self.reader.push(rest)

    def feed(self, chunks=1):
        for _ in range(chunks):
            try:
                chunk = os.read(self.fd, 1 << 16)
            except BlockingIOError:
                return
            if not chunk:
                return
            self.reader.push(chunk)
            self._next()
