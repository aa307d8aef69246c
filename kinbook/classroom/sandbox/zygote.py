"""The sandbox's first process: ``python -m kinbook.classroom.sandbox.zygote LAYOUT JOB RESULT CMD EVENT``
(the last four: descriptors of pipes to and from the grading process).

Running one submission takes two Python processes: the worker (:mod:`.worker`, nbclient) and the kernel
(:mod:`.kernel`: numpy, sympy, IPython, kinbook). Their imports cost more than a submission's cells, so the
*zygote* does them once and forks both processes for every submission. It is started by the grading process
(:class:`kinbook.classroom.sandbox.host.Sandbox`) inside bubblewrap — as the sandbox's pid 1 (``--as-pid-1``:
no other process of the sandbox is beyond its reach) — or, with ``--no-isolation``, as a plain child process,
and serves one submission after another:

``run LIMITS`` (a line on ``CMD_FD``, which the zygote makes its stdin; events go to ``EVENT_FD``, its stdout)
    ``LIMITS`` is JSON from the grading process: the kernel's memory budget, CPU seconds, whether the audit
    hook is installed and whether the kernel may fork (only where a control group holds the sandbox's
    processes together, :mod:`.cgroup`). The zygote makes a *launch channel* (a socket pair), forks a new
    worker that holds one end, and answers ``worker PID``. The worker reads its job from ``JOB_FD``, runs the
    notebook and writes its result to ``RESULT_FD``; when it ends the zygote says ``exit N`` or ``signal N``.
    The zygote itself never reads a job or a result: no submission ever enters its memory, which later
    kernels inherit.
the launch channel
    the only way to a kernel, and good for one: the launcher (:mod:`.launch`, the kernelspec's command, started
    by the worker with the channel's end) writes ``launch``; the zygote forks a kernel that takes nothing from
    the request — its arguments, environment (:func:`kernel_environment`), directory, umask and limits are the
    zygote's own and the grading process's — applies the limits, and runs
    :func:`kinbook.classroom.sandbox.kernel.main` (which caps its address space and installs the audit hook
    before any cell). A second request on the channel is ignored; there is no socket anyone else could reach.
    When the launcher's end closes, the kernel is killed.
``reset``
    end the run: kill every process but itself (in bubblewrap ``kill(-1)`` from pid 1: all of the sandbox's
    pid namespace, whatever session or process group a student's daemon put itself in; without bubblewrap,
    every process group it started and every orphan it adopted), reap them, empty the writable directories and
    reset what else of them a run could set (their mode, times and extended attributes), and answer ``clean``
    — or ``dirty REASON`` (a process that survived, too many files, a System V IPC object), on which the
    grading process throws the whole sandbox away and starts a new one.
``stop`` or end of file on stdin
    kill everything and exit.

Hardening of the zygote itself: it is not dumpable (a kernel of the same uid can neither trace it nor read
its memory, descriptors or environment through /proc), it is the subreaper of everything below it (orphans
come back to it), each child dies with it (``PR_SET_PDEATHSIG``), and it is single-threaded with no ZeroMQ
context or event loop, so forking it is safe (:func:`serve` checks that its imports started no thread).
"""

from __future__ import annotations

import gc
import json
import os
import resource
import select
import signal
import socket
import sys
import tempfile
import threading
import time
import traceback

from . import kernel, worker
from .protocol import THREAD_ENV, Layout, die_with_parent, set_child_subreaper, set_dumpable
from .seccomp import NoFork

__all__ = ["serve", "kernel_environment", "MAX_ENTRIES", "NPROC", "NOFILE"]

#: Most files a run may leave in its writable directories; more, and the sandbox is replaced, not emptied.
MAX_ENTRIES = 20_000
FILE_SIZE_LIMIT = 64 * 1024 * 1024
#: Processes the sandbox's user may have (inside bubblewrap only: elsewhere the count is the grader's user's).
NPROC = 128
#: Open files a kernel may have (its own sockets and files take about 60): each descriptor can pin kernel
#: memory outside every address-space limit (a socket's queued data).
NOFILE = 1024
#: The kernel is the first process the out-of-memory killer picks in a full control group, the worker next.
OOM_SCORE = {"kernel": 1000, "worker": 500}
_BASE_ENV = {}


def _say(line):
    os.write(1, (line + "\n").encode())


def kernel_environment(layout):
    """The kernel's environment: the zygote's own (the sandbox's fixed one, never a request's) and its
    directories."""
    env = dict(_BASE_ENV or os.environ)
    env.update(THREAD_ENV)  # whatever the zygote was started with
    env.update({"HOME": layout.home, "TMPDIR": layout.tmp, "IPYTHONDIR": os.path.join(layout.tmp, ".ipython"),
                "MPLCONFIGDIR": os.path.join(layout.tmp, ".matplotlib"), "JUPYTER_RUNTIME_DIR": layout.work,
                "KINBOOK_SANDBOX_ROOT": layout.home, "KINBOOK_SANDBOX_TMP": layout.tmp})
    return env


def _limits(text):
    """The run's limits from the grading process's ``run`` command (validated: it is trusted, but a malformed
    line must not fork a kernel without limits)."""
    try:
        raw = json.loads(text)
        limits = {"memory_mb": float(raw["memory_mb"]), "cpu_s": int(raw["cpu_s"]), "audit": bool(raw["audit"]),
                  "fork": bool(raw["fork"])}
    except (ValueError, KeyError, TypeError):
        return None
    if not (0 < limits["memory_mb"] < 1 << 24 and 0 < limits["cpu_s"] < 1 << 24):
        return None
    return limits


def _set_limits(limits, isolated):
    """The kernel's resource limits, set by the zygote in the forked kernel before anything else runs (the
    address-space cap follows once the kernel has started: :func:`kinbook.classroom.sandbox.kernel.main`)."""
    cpu = limits["cpu_s"]
    resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 5))
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_SIZE_LIMIT, FILE_SIZE_LIMIT))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    hard = resource.getrlimit(resource.RLIMIT_NOFILE)[1]
    nofile = NOFILE if hard == resource.RLIM_INFINITY or hard > NOFILE else hard
    resource.setrlimit(resource.RLIMIT_NOFILE, (nofile, nofile))
    if isolated:  # the whole sandbox is this submission's: a fork bomb stops here
        resource.setrlimit(resource.RLIMIT_NPROC, (NPROC, NPROC))


def _oom_score(role):
    try:
        with open("/proc/self/oom_score_adj", "w") as f:
            f.write(str(OOM_SCORE[role]))
    except OSError:
        pass


class _Server:
    def __init__(self, layout, job_fd, result_fd, no_fork):
        self.layout = layout
        self.job_fd, self.result_fd = job_fd, result_fd
        self.no_fork = no_fork
        self.pid = os.getpid()
        self.worker = None
        self.limits = None
        self.channel = None  # the zygote's end of this run's launch channel
        self.kernel = None   # the run's kernel, once launched
        r, w = os.pipe2(os.O_NONBLOCK | os.O_CLOEXEC)
        self.wake = r
        signal.signal(signal.SIGCHLD, lambda signum, frame: None)
        signal.set_wakeup_fd(w, warn_on_full_buffer=False)
        self._poll()

    def _poll(self):
        self.poll = select.poll()
        for fd in (0, self.wake):
            self.poll.register(fd, select.POLLIN)
        if self.channel is not None:
            self.poll.register(self.channel.fileno(), select.POLLIN)

    # ------------------------------------------------------------------------------------------- main loop
    def run(self):
        commands = b""
        while True:
            try:
                events = self.poll.poll()
            except InterruptedError:
                continue
            for fd, _ in events:
                if fd == 0:
                    chunk = os.read(0, 4096)
                    if not chunk:
                        return
                    commands += chunk
                    while b"\n" in commands:
                        line, commands = commands.split(b"\n", 1)
                        if not self._command(line.decode(errors="replace").strip()):
                            return
                elif fd == self.wake:
                    try:
                        while os.read(self.wake, 512):
                            pass
                    except BlockingIOError:
                        pass
                    self._reap()
                elif self.channel is not None and fd == self.channel.fileno():
                    self._from_channel()

    def _command(self, line):
        word, _, rest = line.partition(" ")
        if word == "run":
            self._close_channel()
            self.limits = _limits(rest)
            if self.limits is None:
                _say("refused")
                return True
            mine, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
            self.kernel = None
            try:
                self.worker = self._fork("worker", theirs)
            finally:
                theirs.close()
            self.channel = mine
            self._poll()
            _say(f"worker {self.worker}")
        elif word == "reset":
            why = self._reset()
            _say("clean" if why is None else f"dirty {why}")
        elif word == "stop":
            return False
        return True

    # ---------------------------------------------------------------------------------------------- children
    def _fork(self, role, channel=None):
        pid = os.fork()
        if pid == 0:
            self._child(role, channel)  # never returns
        return pid

    def _child(self, role, channel):
        code = 1
        try:
            die_with_parent(self.pid)
            os.setsid()
            signal.set_wakeup_fd(-1)
            signal.signal(signal.SIGCHLD, signal.SIG_DFL)
            keep = {2, self.job_fd, self.result_fd, channel.fileno()} if role == "worker" else set()
            null = os.open(os.devnull, os.O_RDWR)
            for target in (0, 1, 2):
                if target not in keep:
                    os.dup2(null, target)
            os.close(null)
            for fd in _open_fds():
                if fd > 2 and fd not in keep:
                    try:
                        os.close(fd)
                    except OSError:
                        pass
            _oom_score(role)
            if role == "worker":
                worker.main(self.layout, self.job_fd, self.result_fd, channel.detach(), self.limits)
                code = 0
            else:
                limits = self.limits
                os.environ.clear()
                os.environ.update(kernel_environment(self.layout))
                os.chdir(self.layout.home)
                os.umask(0o077)
                _set_limits(limits, self.layout.isolated)
                if not limits["fork"] and self.no_fork.available:  # no control group: per-process limits
                    self.no_fork.load()                                # must not be multiplied by forking

                tempfile.tempdir = None

                argv = ["-f", self.layout.connection_file]
                sys.argv = [kernel.__file__] + argv
                sys.path[0] = os.getcwd()  # as ``python -m`` run in the kernel's working directory
                if "numpy.random" in sys.modules:  # each kernel its own random state, as in a fresh process
                    sys.modules["numpy.random"].seed()
                kernel.main(argv, self.layout, memory_mb=limits["memory_mb"], audit=limits["audit"])
                code = 0
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        except BaseException:
            traceback.print_exc()
        finally:
            for stream in (sys.__stdout__, sys.__stderr__):
                try:
                    stream.flush()
                except Exception:
                    pass
            os._exit(code & 0xFF)

    def _from_channel(self):
        """The launcher's request (once per run), or its end (its connection closed): the kernel goes too."""
        try:
            msg = self.channel.recv(64)
        except OSError:
            msg = b""
        if not msg:
            self._close_channel()
            return
        if msg != b"launch" or self.kernel is not None or self.limits is None:
            return  # exactly one launch per run
        try:
            self.kernel = self._fork("kernel")
        except OSError:
            self._close_channel()
            return
        try:
            self.channel.sendall(b"pid %d" % self.kernel)
        except OSError:
            self._close_channel()

    def _close_channel(self):
        if self.channel is not None:
            self.channel.close()
            self.channel = None
            self._poll()
        if self.kernel is not None:
            _kill_group(self.kernel)  # reaped when SIGCHLD says so

    def _reap(self):
        while True:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            word = b"signal %d" % os.WTERMSIG(status) if os.WIFSIGNALED(status) else \
                b"exit %d" % os.waitstatus_to_exitcode(status)
            if pid == self.worker:
                self.worker = None
                _say(word.decode())
            if pid == self.kernel:
                self.kernel = None
                if self.channel is not None:
                    try:
                        self.channel.sendall(word)
                    except OSError:
                        pass

    # ----------------------------------------------------------------------------------------------- reset
    def _can_kill_all(self):
        """``kill(-1)`` is for the sandbox's own pid namespace only: the zygote as its pid 1, not root."""
        return self.layout.isolated and self.pid == 1 and os.getuid() != 0

    def _others(self):
        """Processes other than this one, as seen in /proc (isolated: the sandbox's pid namespace), or this
        one's children (not isolated)."""
        out = []
        for name in os.listdir("/proc"):
            if not name.isdigit() or int(name) == self.pid:
                continue
            if self.layout.isolated:
                out.append(int(name))
                continue
            try:
                with open(f"/proc/{name}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
                if int(fields[1]) == self.pid:
                    out.append(int(name))
            except (OSError, ValueError, IndexError):
                continue
        return out

    def _reset(self):
        self._close_channel()
        self.kernel = self.limits = None
        deadline = time.monotonic() + 3.0
        left = []
        while time.monotonic() < deadline:
            if self._can_kill_all():
                try:
                    os.kill(-1, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            else:
                for pid in ([self.worker] if self.worker else []) + self._others():
                    _kill_group(pid)
            self.worker = None  # (its end is not reported: the run is over)
            self._reap()
            left = [p for p in self._others() if not _zombie(p)]
            if not left:
                break
            time.sleep(0.02)
        if left:
            return f"processes still running after the run: {left[:5]}"
        budget = [MAX_ENTRIES]
        for d in (self.layout.home, self.layout.tmp, self.layout.work):
            if not _empty(d, budget):
                return f"more than {MAX_ENTRIES} files were left in the writable directories"
        # the control directory's parent is writable by the sandbox's user too: anything left beside it would
        # reach the next submission
        parent = os.path.dirname(self.layout.work)
        if self.layout.isolated:
            if sorted(set(os.listdir(parent)) - {os.path.basename(self.layout.work)}):
                return f"files were left in {parent}"
        # what else of the directories a run could set, and the next run read: their mode, extended attributes
        # and times (a directory's access time alone carries 64 bits)
        for d in (self.layout.home, self.layout.tmp, self.layout.work) + ((parent,) if self.layout.isolated else ()):
            why = _scrub(d)
            if why:
                return why
        if self.layout.isolated:
            for kind in ("shm", "msg", "sem"):
                try:
                    with open(f"/proc/sysvipc/{kind}") as f:
                        if len(f.read().strip().splitlines()) > 1:
                            return f"a System V IPC object ({kind}) was left"
                except OSError:
                    pass
        return None

    def shutdown(self):
        self._reset()


def _scrub(directory):
    """Reset a kept directory's mode (0700), extended attributes and access and modification times; the reason
    when it cannot be done."""
    try:
        os.chmod(directory, 0o700)
        for name in os.listxattr(directory, follow_symlinks=False):
            os.removexattr(directory, name, follow_symlinks=False)
        os.utime(directory, ns=(0, 0), follow_symlinks=False)
    except OSError as exc:
        return f"{directory} could not be reset: {exc.strerror}"
    return None


def _zombie(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except (OSError, IndexError):
        return True


def _kill_group(pid):
    try:
        os.killpg(pid, signal.SIGKILL)
    except OSError:
        pass
    try:
        os.kill(pid, signal.SIGKILL)
    except OSError:
        pass


def _open_fds():
    try:
        return sorted(int(fd) for fd in os.listdir("/proc/self/fd"))
    except OSError:
        return range(3, min(resource.getrlimit(resource.RLIMIT_NOFILE)[0], 4096))


def _empty(directory, budget):
    """Remove everything inside ``directory`` (kept, mode 0700) without following links; False when more than
    ``budget[0]`` entries had to go (the rest is left: the sandbox is replaced then)."""
    os.makedirs(directory, mode=0o700, exist_ok=True)
    os.chmod(directory, 0o700)
    dev = os.lstat(directory).st_dev
    stack = [(directory, False)]
    holding = set()  # directories that lead to a read-only mount: kept
    while stack:
        path, listed = stack.pop()
        if listed:
            if path != directory and path not in holding:
                os.rmdir(path)
            continue
        stack.append((path, True))
        try:
            if path not in holding:
                os.chmod(path, 0o700)
            entries = list(os.scandir(path))
        except OSError:
            return False
        for entry in entries:
            budget[0] -= 1
            if budget[0] < 0:
                return False
            if entry.is_dir(follow_symlinks=False):
                if entry.stat(follow_symlinks=False).st_dev != dev:
                    # the environment bound read-only below this directory (a checkout and its venv under
                    # /tmp): the mount and the directories leading to it stay, everything else goes
                    parent = path
                    while parent != directory and parent not in holding:
                        holding.add(parent)
                        parent = os.path.dirname(parent)
                    continue
                stack.append((entry.path, False))
            else:
                os.unlink(entry.path)
    return True


_LIFELINE = [None]


def _single_threaded(settle=2.0):
    """True when this process has one thread. A joined thread can stay listed in /proc/self/task for a moment
    after ``join`` returns (its OS thread is still exiting), so a count above one is looked at again for up to
    ``settle`` seconds before it is believed."""
    if threading.active_count() != 1:
        return False
    deadline = time.monotonic() + settle
    while True:
        try:
            if len(os.listdir("/proc/self/task")) == 1:
                return True
        except OSError:
            return True  # no /proc: threading's count above is all there is
        if time.monotonic() > deadline:
            return False
        time.sleep(0.005)


def _preload():
    """Import what the kernels and the workers use, once."""
    kernel.preload()
    worker.preload()


def serve(layout, job_fd, result_fd):
    """Import the kernels' and workers' libraries, listen, say ``ready`` and serve until stdin closes."""
    set_dumpable(False)
    set_child_subreaper()
    # pid 1 of the sandbox receives from inside only the signals it handles: none but SIGCHLD (Python's own SIGINT
    # handler would let a student's process end the zygote with a KeyboardInterrupt)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    if hard == resource.RLIM_INFINITY or hard > FILE_SIZE_LIMIT:
        resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_SIZE_LIMIT, FILE_SIZE_LIMIT))
    for d in (layout.home, layout.tmp, layout.work):
        os.makedirs(d, mode=0o700, exist_ok=True)

    no_fork = NoFork()  # built before any kernel is forked (libseccomp is not loaded into kernels otherwise)
    _preload()
    if _LIFELINE[0] is not None:
        _LIFELINE[0].end()
    if not _single_threaded():
        raise RuntimeError("the imports started a thread: forking would not be safe")
    gc.freeze()  # the imported objects stay shared with the forked processes (no copy-on-write by the collector)
    server = _Server(layout, job_fd, result_fd, no_fork)
    try:
        _say("ready" if no_fork.available else "ready no-seccomp")
        server.run()
    except BrokenPipeError:
        pass
    finally:
        server.shutdown()


class _Lifeline:
    """Exit at once if stdin (a pipe from the grading process) reaches end of file while the imports run.

    The grading process may die while bubblewrap is still setting the sandbox up, before bubblewrap's own
    parent-death signals are in place; the zygote then starts without anyone to serve. Its stdin's end of file
    says so (the write end was the grading process's), and it exits before the slow imports — taking the
    sandbox with it. A thread, stopped (and joined) before the zygote forks anything.
    """

    def __init__(self):
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._watch, daemon=True)
        self.thread.start()

    def _watch(self):
        poll = select.poll()
        poll.register(0, select.POLLIN | select.POLLHUP)
        while not self.stop.is_set():
            if poll.poll(50):  # nothing is written before "ready": readable or hung up means end of file
                os._exit(1)

    def end(self):
        self.stop.set()
        self.thread.join()


def main(argv):
    _BASE_ENV.update(os.environ)  # the sandbox's fixed environment, before any import adds to it
    os.environ.update(THREAD_ENV)  # (the grading process gave them; libraries imported from here on read them)
    layout = Layout.from_json(argv[0])
    job_fd, result_fd = int(argv[1]), int(argv[2])
    # commands in, events out: pipes passed as descriptors of their own, made this process's 0 and 1
    for fd, target in ((int(argv[3]), 0), (int(argv[4]), 1)):
        os.dup2(fd, target)
        os.close(fd)
    for fd in (job_fd, result_fd):
        os.set_inheritable(fd, False)  # the zygote's children inherit them only when asked (the worker)
    if not layout.isolated:  # (in bubblewrap, --die-with-parent at every level)
        die_with_parent()
    _LIFELINE[0] = _Lifeline()
    try:
        serve(layout, job_fd, result_fd)
    except Exception:
        traceback.print_exc()
        os._exit(1)


if __name__ == "__main__":
    main(sys.argv[1:])
