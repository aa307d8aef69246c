"""The grading process's side of the sandbox: :class:`Sandbox` (start, run one notebook, reset, stop).

One :class:`Sandbox` serves one grading process: it starts the zygote (:mod:`.zygote`) — inside bubblewrap
(:mod:`.bwrap`), or, with ``isolation=False``, as a plain child process — once, then for every submission:

1. sets the run's memory limit on the sandbox's control group, when it has one (:mod:`.cgroup`), and sends
   ``run`` with the kernel's limits; the zygote forks a worker and says its pid;
2. writes the job frame (the code cells, the answer names, the timeout, the submission's copy) on the job
   pipe;
3. waits, at most ``timeout`` + start-up allowance, for the worker's result frame on the result pipe and for
   the worker's end; reads at most :data:`~.protocol.MAX_RESULT_BYTES` and validates every field
   (:func:`_validated`): the result is data written by a process in the student's reach;
4. sends ``reset``: the zygote kills everything the run started (in bubblewrap, every process of the pid
   namespace but itself — a ``setsid`` daemon included) and empties the writable directories. If it does not
   answer ``clean`` in time, the whole sandbox is killed and the next run starts a new one;
5. when the run ended before the worker's ``running`` frame (written just before the first cell is sent to the
   kernel: nothing of the submission ran — a kernel that died as it started, a sandbox that stopped), tries it
   again in a new sandbox, :data:`GRADER_RETRIES` times at most, then says ``grader-error``: not the student's
   doing, and no verdict on the notebook.

Verdicts come from what the sandbox counted before any clock: the kernel's CPU time (its ``RLIMIT_CPU`` is the
run's timeout), the control group's out-of-memory kills and memory-limit hits; the wall clock is a backstop for
a notebook that waits instead of computing (:func:`~.protocol.wall_seconds`).

Killing the sandbox: the zygote's process group (the outermost ``bwrap`` with ``--die-with-parent`` at every
level; without bubblewrap the zygote itself, whose children die with it), and every process left in its
control group. If the grading process itself dies (SIGKILL, the OOM killer), the kernel delivers the same
deaths (``PR_SET_PDEATHSIG``): nothing outlives it.

Limits: a control group per sandbox where the host offers one (memory for all its processes together, tasks,
one CPU), else per-process resource limits set by the zygote on each kernel, with a seccomp filter that keeps
the kernel from forking (:mod:`.seccomp`); :attr:`Sandbox.limits` says which, and every result records it.
What the sandbox writes on its standard error (bubblewrap's messages, tracebacks) comes through a pipe this
process drains, keeping the last few kilobytes for its error messages.
"""

from __future__ import annotations

import json
import os
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import weakref
from dataclasses import dataclass, field

from ...errors import GradingError
from ..sanitize import clean
from . import bwrap
from . import cgroup as cgroups
from .protocol import (
    ISOLATED,
    MAX_JOB_BYTES,
    MAX_RESULT_BYTES,
    FrameError,
    Layout,
    ResultReader,
    cpu_seconds,
    job_frame,
    wall_seconds,
    write_frame,
)

__all__ = ["Execution", "Sandbox", "SandboxError", "STARTUP_SECONDS", "STATUSES"]

#: Seconds allowed for the zygote's imports (once per sandbox) and for a kernel to start (per submission).
STARTUP_SECONDS = 60.0
#: Statuses a worker's result can have.
WORKER_STATUSES = ("ok", "timeout", "memory", "error")
#: Statuses an execution can have: the worker's, and ``grader-error`` — the run failed before any code of the
#: submission ran (a kernel that did not start, a sandbox that stopped), :data:`GRADER_RETRIES` times more after
#: the first: nothing to grade, and not the student's doing; and ``too-large`` — a job over the frame limit, which
#: only a submission over the size cap can make (:data:`~.protocol.MAX_JOB_BYTES`): the submission's, not run.
STATUSES = WORKER_STATUSES + ("grader-error", "too-large")
#: Times a run that failed before any code of the submission ran is tried again, each in a new sandbox.
GRADER_RETRIES = 2
_MAX_ANSWERS = 100
_MAX_ERRORS = 200
#: Memory of the sandbox beyond its zygote's and the notebook's budget: the worker, the launcher and the
#: kernel's own start-up (its private pages), output in transit.
OVERHEAD_MB = 256
#: Memory the sandbox may use while its zygote imports the libraries (before the first run sets the limit).
STARTUP_MB = 1024
_ERR_TAIL = 4096


class SandboxError(GradingError):
    """The sandbox could not be started (not a submission's fault)."""


@dataclass
class Execution:
    """Outcome of running a notebook.

    Attributes
    ----------
    status : {"ok", "timeout", "memory", "error", "grader-error"}
        "ok": every cell was run (some may have raised) and the answers were read; "grader-error": the sandbox
        failed before any code of the submission ran, every time it was tried (:data:`GRADER_RETRIES`).
    message : str
    answers : dict or None
        {name: record or None} as written by :func:`kinbook.classroom.serialize.dumps` (not yet decoded): after
        the last cell, or — when a cell timed out, ran out of memory or ended the kernel — after the last cell
        before it; None when none was read.
    errors : list of dict
        One per cell that raised: cell number (among the code cells run, from 1), exception name and value.
    seconds : float
    cell : int or None
        The code cell (from 1) at which the run stopped (timeout, memory, a dead kernel), if it did.
    limits : str
        The limits in force (:attr:`Sandbox.limits`).
    before_code : bool
        The run ended before the worker said it sends the first cell: nothing of the submission ran, so the
        failure is the grader's (tried again by :meth:`Sandbox.run`).
    tries : int
        How many times the notebook was run (more than 1 after failures of the grader's).
    reference : dict
        {answer name: [(the reference function's qualified name, the code cell it ran in, whether the answer is its
        very result or an equal copy), …]} (the latest first, at most four) for the answers that are the result of a
        call into the exercise's reference, as observed in the kernel (:mod:`.trace`).
    """

    status: str
    message: str = ""
    answers: dict | None = None
    errors: list = field(default_factory=list)
    seconds: float = 0.0
    cell: int | None = None
    limits: str = ""
    before_code: bool = False
    tries: int = 1
    reference: dict = field(default_factory=dict)


def _text(value, limit):
    return value[:limit] if isinstance(value, str) else ""


def _validated(header):
    """An :class:`Execution`'s fields from a result frame, every one checked (type, size), or an error."""
    status = header.get("status")
    if status not in WORKER_STATUSES:
        return Execution("error", "the sandbox returned a result that is not one (no valid status)")
    answers = header.get("answers")
    if answers is not None:
        if (not isinstance(answers, dict) or len(answers) > _MAX_ANSWERS
                or not all(isinstance(k, str) and len(k) <= 100 for k in answers)):
            return Execution("error", "the sandbox returned malformed answers")
    errors = []
    raw = header.get("errors")
    for e in (raw if isinstance(raw, list) else [])[:_MAX_ERRORS]:
        if isinstance(e, dict) and isinstance(e.get("cell"), int) and not isinstance(e.get("cell"), bool):
            errors.append({"cell": e["cell"], "ename": _text(e.get("ename"), 100), "evalue": _text(e.get("evalue"), 300)})
    if status == "ok" and answers is None:
        return Execution("error", "the sandbox returned no answers")
    cell = header.get("cell")
    cell = cell if isinstance(cell, int) and not isinstance(cell, bool) and 0 < cell <= 1_000_000 else None
    reference = {}
    raw = header.get("reference")
    for name, entries in (raw.items() if isinstance(raw, dict) else ()):
        if isinstance(name, str) and answers is not None and name in answers and isinstance(entries, list):
            kept = [(e[0][:200], e[1], e[2] == 1) for e in entries[:4]
                    if isinstance(e, list) and len(e) == 3 and isinstance(e[0], str) and isinstance(e[1], int)
                    and not isinstance(e[1], bool) and 0 < e[1] <= 1_000_000 and e[2] in (0, 1)]
            if kept:
                reference[name] = kept
    return Execution(status, _text(header.get("message"), 500), answers, errors, cell=cell, reference=reference)


def _clean_env(extra=None):
    """The zygote's environment without bubblewrap: nothing of the grader's but the interpreter's search path."""
    keep = ("PATH", "LANG", "LC_ALL", "PYTHONPATH", "SYSTEMROOT")
    env = {k: os.environ[k] for k in keep if k in os.environ}
    env.update({k: v for k, v in bwrap.ENV.items() if k not in ("PATH", "LANG", "HOME", "TMPDIR", "MPLCONFIGDIR")})
    env.update(extra or {})
    return env


class Sandbox:
    """The sandbox of one grading process (see the module docstring).

    Parameters
    ----------
    isolation : bool
        Run the zygote (and so every worker and kernel) inside bubblewrap. Without it the audit hook and the
        resource limits are the only fence.
    cgroup : bool or None
        Hold the sandbox's processes in a control group of their own: None (default) where the host offers
        one, False never (the per-process limits then; for tests of that fallback), True or fail
        (:class:`SandboxError`).

    Raises
    ------
    kinbook.classroom.sandbox.bwrap.IsolationUnavailable
        (from :meth:`start`) isolation was asked for and bubblewrap cannot provide it here.

    Examples
    --------
    >>> with Sandbox() as sb:  # doctest: +SKIP
    ...     ex = sb.run(["x = 1 + 1"], ["x"], timeout=10)
    >>> ex.status, ex.answers["x"]["data"]  # doctest: +SKIP
    ('ok', [2.0])
    """

    def __init__(self, isolation=True, cgroup=None):
        self.isolation = bool(isolation)
        self.want_cgroup = cgroup
        self.cgroup = None
        self.cgroup_problem = ""
        self.seccomp = True  # the zygote's no-fork filter (it says at start-up when it has none)
        self.proc = None
        self.owner = os.getpid()
        self.private = None
        self.starts = 0
        self.err_r = None
        self.err_tail = b""
        _live.add(self)

    # ------------------------------------------------------------------------------------------ lifetime
    def __enter__(self):
        return self

    def __exit__(self, kind, value, tb):
        self.close(wait=kind is None)

    @property
    def pid(self):
        """The process id of the sandbox's outermost process (bwrap, or the zygote without isolation)."""
        return None if self.proc is None else self.proc.pid

    @property
    def limits(self):
        """The limits in force, in words (recorded with every result): the control group, or the per-process
        resource limits and whether kernels may fork."""
        if self.cgroup is not None:
            return self.cgroup.describe
        return "rlimits, no fork" if self.seccomp else "rlimits (forks not limited: no libseccomp)"

    def alive(self):
        return self.proc is not None and self.owner == os.getpid() and self.proc.poll() is None

    def start(self):
        """Start the zygote (a no-op when it runs); :class:`SandboxError` when it does not say ``ready``."""
        if self.alive():
            return
        self.close()
        if self.isolation:
            bwrap.check()
        if self.isolation:
            layout = ISOLATED  # nothing of the sandbox is on the host's disk
        else:
            self.private = os.path.realpath(tempfile.mkdtemp(prefix="kinbook-grader-"))
            os.chmod(self.private, 0o700)
            layout = Layout(home=os.path.join(self.private, "home"), tmp=os.path.join(self.private, "tmp"),
                            work=os.path.join(self.private, "work"), isolated=False)
        self.layout = layout
        if self.want_cgroup is not False:
            self.cgroup, self.cgroup_problem = cgroups.create()
            if self.cgroup is None and self.want_cgroup:
                raise SandboxError(f"no control group for the sandbox: {self.cgroup_problem}")
        job_r, self.job_w = os.pipe()
        self.result_r, result_w = os.pipe()
        self.job_r = job_r  # kept: the job pipe is drained here at every reset
        # the zygote's commands and events travel on pipes of their own, never on bubblewrap's stdin and stdout
        cmd_r, self.cmd_w = os.pipe()
        self.evt_r, evt_w = os.pipe()
        # the sandbox's own messages (bubblewrap's, tracebacks): a pipe drained here, never a file of ours that a
        # process inside could reopen through /proc
        self.err_r, err_w = os.pipe()
        self.err_tail = b""
        argv = [sys.executable, "-s", "-m", "kinbook.classroom.sandbox.zygote", layout.to_json(), str(job_r),
                str(result_w), str(cmd_r), str(evt_w)]
        keep = [job_r, result_w, cmd_r, evt_w]
        if self.isolation:
            seccomp = bwrap.seccomp_fd()
            if seccomp is not None:
                keep.append(seccomp)
            cmd, env, cwd = bwrap.command(argv, seccomp=seccomp), {"PATH": bwrap.SYSTEM_PATH}, "/"
        else:
            seccomp = None
            cmd, cwd = argv, self.private
            env = _clean_env({"HOME": layout.home, "TMPDIR": layout.tmp,
                              "MPLCONFIGDIR": os.path.join(layout.tmp, ".matplotlib")})
        join = None
        if self.cgroup is not None:
            if not self._set_memory(STARTUP_MB):
                self.close()
                raise SandboxError("the sandbox's control group refused its memory limit")
            self.cgroup.prepare_join()
            join = self.cgroup.join_in_child
        _spawning[0] = True  # (a preexec_fn runs the at-fork handlers: _forget_in_child must leave them alone)
        try:
            self.proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=err_w,
                                         env=env, cwd=cwd, pass_fds=keep, start_new_session=True,
                                         preexec_fn=join)
        except (OSError, subprocess.SubprocessError) as exc:
            self.close()
            raise SandboxError(f"the sandbox could not be started: {exc}") from None
        finally:
            _spawning[0] = False
            for fd in (result_w, cmd_r, evt_w, err_w):
                os.close(fd)
            if seccomp is not None:
                os.close(seccomp)
            if self.cgroup is not None:
                self.cgroup.close_join()
        self.starts += 1
        for fd in (self.job_w, self.result_r, self.job_r, self.evt_r, self.cmd_w, self.err_r):
            os.set_blocking(fd, False)
        self.events = b""
        try:
            line = self._event(time.monotonic() + STARTUP_SECONDS)
        except BaseException:  # (also when this process is being terminated)
            self.close()
            raise
        if line not in ("ready", "ready no-seccomp"):
            why = self._log_tail()
            self.close()
            raise SandboxError(f"the sandbox did not start: {why or 'no answer'}")
        self.seccomp = line == "ready"

    def close(self, wait=False):
        """Stop the sandbox (everything in it is killed) and remove its private directory and control group.

        ``wait``: let the zygote stop by itself first (at most 2 s), so that every process is reaped by its
        parent — at the end of a batch; by default (and when interrupted) it is killed at once: nothing in the
        sandbox has anything to save."""
        if self.proc is not None:
            if self.owner == os.getpid():
                if wait and self.alive() and self._send("stop"):
                    try:
                        self.proc.wait(2.0)
                    except subprocess.TimeoutExpired:
                        pass
                self._kill()
            self._close_pipes()
            self.proc = None
        if self.cgroup is not None and self.owner == os.getpid():
            self.cgroup.remove()  # what is left in it is killed first
        self.cgroup = None
        if self.private and self.owner == os.getpid():
            shutil.rmtree(self.private, ignore_errors=True)
        self.private = None

    def _kill(self):
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except OSError:
            pass
        try:
            self.proc.kill()
        except OSError:
            pass
        if self.cgroup is not None:
            self.cgroup.kill_all()
        self.proc.wait()

    def _close_pipes(self):
        for name in ("job_w", "job_r", "result_r", "cmd_w", "evt_r", "err_r"):
            fd = getattr(self, name, None)
            if fd is not None:
                try:
                    os.close(fd)
                except OSError:
                    pass
            setattr(self, name, None)

    def forget(self):
        """In a forked copy of the owner: drop the inherited descriptors without stopping the sandbox."""
        self._close_pipes()
        if self.proc is not None:
            self.proc.returncode = 0  # not ours to wait for
            self.proc = None
        if self.cgroup is not None:
            self.cgroup.close_join()
        self.cgroup = None
        self.private = None

    def _drain(self):
        """Read what the sandbox wrote on its standard error (it must never block on a full pipe); keep the end."""
        if self.err_r is None:
            return
        try:
            while True:
                chunk = os.read(self.err_r, 1 << 16)
                if not chunk:
                    break
                self.err_tail = (self.err_tail + chunk)[-_ERR_TAIL:]
        except (BlockingIOError, OSError):
            pass

    def _log_tail(self):
        self._drain()
        return bwrap_text(self.err_tail)[-400:]

    def _set_memory(self, megabytes):
        """The control group's memory limit: what it uses now plus ``megabytes``; False when refused."""
        try:
            self.cgroup.set_memory(self.cgroup.memory_usage() + int(megabytes * (1 << 20)))
            return True
        except OSError:
            return False

    # -------------------------------------------------------------------------------------------- events
    def _event(self, deadline):
        """The zygote's next event line, or "" when none came by ``deadline`` (or it is gone)."""
        fd = self.evt_r
        while b"\n" not in self.events:
            left = deadline - time.monotonic()
            if left <= 0:
                return ""
            ready, _, _ = select.select([fd, self.err_r], [], [], left)
            if self.err_r in ready:
                self._drain()
            if fd in ready:
                try:
                    chunk = os.read(fd, 4096)
                except BlockingIOError:
                    continue
                if not chunk:
                    return ""
                self.events += chunk
                if len(self.events) > 1 << 16:
                    return ""
        line, self.events = self.events.split(b"\n", 1)
        return line.decode(errors="replace").strip()

    def _send(self, line):
        try:  # a command is a few bytes: a pipe too full to take it means a zygote that no longer reads
            data = line.encode() + b"\n"
            return os.write(self.cmd_w, data) == len(data)
        except (OSError, TypeError):
            return False

    # ----------------------------------------------------------------------------------------------- run
    def run(self, cells, names, *, timeout=60.0, memory_mb=1000, files=None, audit_hook=True, setup=None):
        """Run code cells in a fresh worker and kernel; read the named answers.

        Parameters
        ----------
        cells : list of str
            The code cells' sources, in order.
        names : list of str
            Answer variables to read after each cell (the last reading is the result).
        timeout : float
            CPU seconds the kernel may use (its ``RLIMIT_CPU``: the limit that decides ``timeout``, whatever the
            machine's load); a notebook that waits instead of computing is stopped by a wall-clock backstop
            (:func:`~.protocol.wall_seconds`; kernel start-up not included).
        memory_mb : float
            Memory the code may allocate beyond the kernel's own footprint: the kernel's address-space
            limit, and — with a control group — the sandbox's memory beyond what it uses before the run
            (plus :data:`OVERHEAD_MB` for the worker and the kernel's start-up), whatever the processes.
        files : dict, optional
            {name: bytes} put in the submission's directory (a copy of the submission, for example).
        audit_hook : bool
            Install the kernel's audit hook (always, when grading). False only to test what the
            operating-system sandbox holds on its own.
        setup : dict, optional
            ``{"seed": int, "functions": [...], "methods": [...]}``: the seed of the notebook's random generators
            and the reference's calls to observe (:func:`.trace.setup`), before the first cell.

        Returns
        -------
        Execution
        """
        t0 = time.monotonic()
        header, payload = job_frame(cells, names, timeout, files, setup)
        if len(payload) > MAX_JOB_BYTES - (1 << 20):  # (only a caller past the submission cap gets here)
            return Execution("too-large", f"the notebook's code and its copy take {len(payload):,} bytes (at most "
                                          f"{MAX_JOB_BYTES - (1 << 20):,} in a job): not run", seconds=0.0)
        limits = {"memory_mb": float(memory_mb), "cpu_s": cpu_seconds(timeout), "audit": bool(audit_hook)}
        for tries in range(1, GRADER_RETRIES + 2):
            if tries > 1:
                self.close()  # a new sandbox for the next try
            try:
                self.start()
            except SandboxError:
                if tries <= GRADER_RETRIES:
                    continue
                raise  # the sandbox cannot be started any more: nothing can be graded
            limits["fork"] = self.cgroup is not None or not self.seccomp
            in_force = self.limits
            try:
                ex = self._run(header, payload, float(timeout), limits)
            finally:
                self._reset()
            if not ex.before_code:
                break
        if ex.before_code:
            ex.status, ex.message, ex.answers, ex.cell = "grader-error", (
                f"the grader could not run the notebook ({tries} tries; the last: {ex.message}) — not the "
                "submission's doing: grade it again"), None, None
        ex.tries = tries
        ex.seconds = time.monotonic() - t0
        ex.limits = in_force
        return ex

    def _run(self, header, payload, timeout, limits):
        """One try of :meth:`run`. Before the worker's ``running`` frame, every failure is the grader's
        (``before_code``); after it, a verdict on the notebook, decided by what the sandbox counted — its control
        group's out-of-memory kills and memory-limit hits, the kernel's CPU time — before any clock."""
        memory = (0, 0)
        if self.cgroup is not None:
            memory = self.cgroup.memory_events()
            if not self._set_memory(limits["memory_mb"] + OVERHEAD_MB):
                return _grader("the sandbox's control group refused the memory limit")
        if not self._send("run " + json.dumps(limits)):
            return _grader("the sandbox stopped before the notebook could be run")
        word = self._event(time.monotonic() + 30)
        if not word.startswith("worker "):
            return _grader(f"the sandbox did not start a worker ({word or 'no answer'})")
        try:
            write_frame(self.job_w, header, payload, deadline=time.monotonic() + 30)
        except FrameError as exc:
            return _grader(f"the job could not be handed to the sandbox: {exc}")
        reading = ResultReader(self.result_r)
        try:
            ended, early = self._wait(reading, timeout, memory)
        except FrameError as exc:
            return _kept((Execution if reading.started else _grader)(
                "error", f"the sandbox returned an unreadable result: {exc}"), reading)
        if early is not None:
            return _kept(early, reading)
        frame = reading.reader.frame
        if not reading.started:  # whatever the worker said: nothing of the submission ran
            said = _validated(frame[0]).message if frame is not None else f"it ended: {ended}"
            return _grader(said or "the kernel did not start")
        if frame is None:  # the worker stopped (killed at the memory limit, the sandbox's directories full …)
            return _kept(self._out_of_memory(memory) or Execution(
                "error", f"the grading worker stopped without a result ({ended})"), reading)
        ex = _validated(frame[0])
        oom = self._out_of_memory(memory, reached=ex.status == "timeout")
        if oom is not None and ex.status in ("ok", "error", "timeout"):
            # a process of the notebook was killed at the memory limit: the kernel itself (the answers read before
            # it are kept) or a child it forked (the run went on, without what the child held); or the notebook,
            # held at the limit, ran out of time there — memory, at any speed of the machine
            ex.status, ex.message = "memory", oom.message
        return ex

    def _wait(self, reading, timeout, memory):
        """Read the worker's frames until its result, its end, or the backstop: ``(ended, early)`` — the worker's
        end event (or None), and an Execution when the run is decided without a result."""
        wall = wall_seconds(timeout)
        deadline = time.monotonic() + wall + STARTUP_SECONDS + 15.0
        ended = None
        while reading.reader.frame is None:
            if ended is not None:  # what the worker wrote before it ended (bounded: others may write too)
                reading.feed(chunks=2 * (MAX_RESULT_BYTES >> 16) + 2)
                break
            left = deadline - time.monotonic()
            if left <= 0:
                if not reading.started:
                    return ended, _grader(f"no cell was sent to the kernel within {wall + STARTUP_SECONDS + 15:g} s")
                return ended, self._out_of_memory(memory) or Execution(
                    "timeout", f"the notebook did not finish within {wall:g} s")
            ready, _, _ = select.select([self.result_r, self.evt_r, self.err_r], [], [], min(left, 1.0))
            if self.err_r in ready:
                self._drain()
            if self.result_r in ready:
                reading.feed()
            if self.evt_r in ready or b"\n" in self.events:
                word = self._event(time.monotonic() + 0.1)
                if word.startswith(("exit ", "signal ")):
                    ended = word
                elif word == "" and self.proc.poll() is not None:
                    if not reading.started:
                        return ended, _grader("the sandbox stopped before the notebook's first cell")
                    return ended, self._out_of_memory(memory) or Execution(
                        "error", "the sandbox stopped while running the notebook")
        return ended, None

    def _out_of_memory(self, before, reached=True):
        """An Execution "memory" when the control group's out-of-memory killer struck since ``before``
        (:meth:`~.cgroup.Cgroup.memory_events`), or — with ``reached``, for a run that did not finish — its memory
        limit was reached."""
        if self.cgroup is None:
            return None
        kills, hits = self.cgroup.memory_events()
        if kills > before[0]:
            return Execution("memory", "the notebook went over its memory limit (a process was stopped by the "
                                       "sandbox's control group)")
        if reached and hits > before[1]:
            return Execution("memory", "the notebook reached its memory limit (the sandbox's control group held it "
                                       "there)")
        return None

    def _reset(self):
        """End the run (see the module docstring); a sandbox that does not come back clean is thrown away."""
        if not self.alive():
            self.close()
            return
        ok = self._send("reset")
        deadline = time.monotonic() + 15.0
        while ok:
            word = self._event(deadline)
            if not word.startswith(("exit ", "signal ")):  # the worker's end, when it came after its result
                ok = word == "clean"
                break
        for fd in (self.result_r, self.job_r):  # nothing of this run reaches the next one
            try:
                while os.read(fd, 1 << 16):
                    pass
            except (BlockingIOError, OSError):
                pass
        self._drain()
        if not ok:
            self.close()


def _kept(ex, reading):
    """``ex`` of a run that ended without the worker's result, with the answers the worker sent before it stopped
    (validated as a result's are): answers read before a failure are graded, whatever the failure."""
    if not ex.before_code and ex.answers is None and reading.answers is not None:
        answers = _validated({"status": "error", "answers": reading.kept()})
        if not answers.message and answers.answers is not None:
            ex.answers = answers.answers
            if reading.answers[1]:
                ex.message += f" (the answers read after code cell {reading.answers[1]} are graded)"
    return ex


def _grader(*args):
    """An Execution that failed before any code of the submission ran (``message``, or ``status, message``)."""
    status, message = args if len(args) == 2 else ("error", args[0])
    return Execution(status, message, before_code=True)


def bwrap_text(data):
    """Bytes the sandbox wrote, as printable text (control characters escaped)."""
    return clean(data.decode("utf-8", "replace")).strip()


_live = weakref.WeakSet()
_spawning = [False]


def _forget_in_child():
    if _spawning[0]:  # the child of subprocess.Popen, about to exec the sandbox: it needs these descriptors
        return
    # a process forked from this one (a grading pool's process) must neither use nor stop these sandboxes
    for sb in list(_live):
        if sb.owner != os.getpid():
            sb.forget()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_in_child)

