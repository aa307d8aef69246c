"""The sandbox's first process: ``python -m kinbook.classroom.sandbox.zygote LAYOUT JOB RESULT CMD EVENT``
(the last four: descriptors of pipes to and from the grading process).

Running one submission takes two Python processes: the worker (:mod:`.worker`, nbclient) and the kernel
(:mod:`.kernel`: numpy, sympy, IPython, kinbook). Their imports cost more than a submission's cells, so the
*zygote* does them once and forks both processes for every submission. It is started by the grading process
(:class:`kinbook.classroom.sandbox.host.Sandbox`) inside bubblewrap — or, with ``--no-isolation``, as a
plain child process — and serves one submission after another:

``run`` (a line on ``CMD_FD``, which the zygote makes its stdin; events go to ``EVENT_FD``, its stdout)
    fork a new worker, answer ``worker PID``. The worker reads its job from ``JOB_FD``, runs the notebook and
    writes its result to ``RESULT_FD``; when it ends the zygote says ``exit N`` or ``signal N``. The zygote
    itself never reads a job or a result: no submission ever enters its memory, which later kernels inherit.
kernel launch requests (its socket)
    the launcher (:mod:`.launch`, the kernelspec's command, started by the worker) asks for a kernel: the
    zygote forks one that takes the request's environment, directory and limits and runs
    :func:`kinbook.classroom.sandbox.kernel.main` (which caps its memory and installs the audit hook before
    any cell). At most :data:`MAX_KERNELS` per run. When the launcher's connection closes, the kernel is
    killed.
``reset``
    end the run: kill every process but itself (in bubblewrap ``kill(-1)``: all of the sandbox's pid
    namespace, whatever session or process group a student's daemon put itself in; without bubblewrap, every
    process group it started and every orphan it adopted), reap them, empty the writable directories, and
    answer ``clean`` — or ``dirty REASON`` (a process that survived, too many files, a System V IPC object),
    on which the grading process throws the whole sandbox away and starts a new one.
``stop`` or end of file on stdin
    kill everything and exit.

Hardening of the zygote itself: it is not dumpable (a kernel of the same uid can neither trace it nor read
its memory, descriptors or environment through /proc), it is the subreaper of everything below it (orphans
come back to it), each child dies with it (``PR_SET_PDEATHSIG``), and it is single-threaded with no ZeroMQ
context or event loop, so forking it is safe (:func:`serve` checks that its imports started no thread).
"""

from __future__ import annotations

import json
import os
import select
import signal
import socket
import sys
import time
import traceback

from .protocol import SOCKET_NAME, Layout, die_with_parent, set_child_subreaper, set_dumpable

__all__ = ["serve", "MAX_KERNELS", "MAX_REQUEST", "MAX_ENTRIES"]

#: Kernels one run may start (the worker starts one; a second would be a restart after a crash).
MAX_KERNELS = 2
#: Most bytes of one kernel launch request.
MAX_REQUEST = 1 << 20
#: Most files a run may leave in its writable directories; more, and the sandbox is replaced, not emptied.
MAX_ENTRIES = 20_000
FILE_SIZE_LIMIT = 64 * 1024 * 1024
_LIMITS = ("RLIMIT_AS", "RLIMIT_CPU", "RLIMIT_FSIZE", "RLIMIT_DATA", "RLIMIT_STACK", "RLIMIT_CORE",
           "RLIMIT_NOFILE", "RLIMIT_NPROC", "RLIMIT_MEMLOCK", "RLIMIT_RSS")


def _say(line):
    os.write(1, (line + "\n").encode())


def _apply_limits(limits):
    """Take a launch request's resource limits, never looser than the zygote's own."""
    import resource

    inf = resource.RLIM_INFINITY

    def tighter(a, b):
        return b if a == inf else a if b == inf else min(a, b)

    for name, pair in limits.items():
        which = getattr(resource, name, None) if name in _LIMITS else None
        if which is None or not isinstance(pair, list) or len(pair) != 2 or not all(isinstance(v, int) for v in pair):
            continue
        cur_soft, cur_hard = resource.getrlimit(which)
        hard = tighter(pair[1], cur_hard)
        soft = tighter(pair[0], hard)
        resource.setrlimit(which, (soft, hard))


class _Server:
    def __init__(self, layout, job_fd, result_fd, listener):
        self.layout = layout
        self.job_fd, self.result_fd = job_fd, result_fd
        self.listener = listener
        self.pid = os.getpid()
        self.worker = None
        self.kernels = {}    # kernel pid → launcher connection
        self.conns = {}      # connection fd → (socket, kernel pid)
        self.started = 0     # kernels started in this run
        st = os.lstat(layout.socket)
        self.socket_id = (st.st_dev, st.st_ino)  # checked at every reset
        r, w = os.pipe2(os.O_NONBLOCK | os.O_CLOEXEC)
        self.wake = r
        signal.signal(signal.SIGCHLD, lambda signum, frame: None)
        signal.set_wakeup_fd(w, warn_on_full_buffer=False)
        self.poll = select.poll()
        for fd in (0, listener.fileno(), r):
            self.poll.register(fd, select.POLLIN)

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
                elif fd == self.listener.fileno():
                    self._accept()
                elif fd == self.wake:
                    try:
                        while os.read(self.wake, 512):
                            pass
                    except BlockingIOError:
                        pass
                    self._reap()
                elif fd in self.conns:
                    self._launcher_gone(fd)

    def _command(self, word):
        if word == "run":
            self.started = 0
            self.worker = self._fork("worker", None)
            _say(f"worker {self.worker}")
        elif word == "reset":
            why = self._reset()
            _say("clean" if why is None else f"dirty {why}")
        elif word == "stop":
            return False
        return True

    # ---------------------------------------------------------------------------------------------- children
    def _fork(self, role, request):
        pid = os.fork()
        if pid == 0:
            self._child(role, request)  # never returns
        return pid

    def _child(self, role, request):
        code = 1
        try:
            die_with_parent(self.pid)
            os.setsid()
            signal.set_wakeup_fd(-1)
            signal.signal(signal.SIGCHLD, signal.SIG_DFL)
            keep = {2, self.job_fd, self.result_fd} if role == "worker" else set()
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
            if role == "worker":
                from . import worker

                worker.main(self.layout, self.job_fd, self.result_fd)
                code = 0
            else:
                os.environ.clear()
                os.environ.update({str(k): str(v) for k, v in request["env"].items()})
                os.chdir(request["cwd"])
                os.umask(int(request["umask"]) & 0o777)
                _apply_limits(request.get("rlimits", {}))
                import tempfile

                tempfile.tempdir = None
                from . import kernel

                sys.argv = [kernel.__file__] + list(request["argv"])
                sys.path[0] = os.getcwd()  # as ``python -m`` run in the kernel's working directory
                if "numpy.random" in sys.modules:  # each kernel its own random state, as in a fresh process
                    sys.modules["numpy.random"].seed()
                kernel.main(list(request["argv"]), self.layout)
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

    def _accept(self):
        try:
            conn, _ = self.listener.accept()
        except OSError:
            return
        try:
            conn.settimeout(2.0)
            msg = conn.recv(MAX_REQUEST)
            request = json.loads(msg)
            if (not isinstance(request, dict) or request.get("role") != "kernel"
                    or not isinstance(request.get("argv"), list) or not isinstance(request.get("env"), dict)
                    or not isinstance(request.get("cwd"), str) or not isinstance(request.get("umask"), int)):
                raise ValueError("not a kernel request")
            if self.started >= MAX_KERNELS:
                raise ValueError("too many kernels in this run")
            conn.settimeout(None)
        except (OSError, ValueError, TypeError):
            conn.close()
            return
        self.started += 1
        try:
            pid = self._fork("kernel", request)
        except OSError:
            conn.close()
            return
        self.kernels[pid] = conn
        self.conns[conn.fileno()] = (conn, pid)
        self.poll.register(conn.fileno(), select.POLLIN)
        try:
            conn.sendall(b"pid %d" % pid)
        except OSError:
            self._launcher_gone(conn.fileno())

    def _launcher_gone(self, fd):
        conn, pid = self.conns.pop(fd)
        self.poll.unregister(fd)
        self.kernels.pop(pid, None)
        conn.close()
        _kill_group(pid)  # reaped when SIGCHLD says so

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
            conn = self.kernels.pop(pid, None)
            if conn is not None:
                self.conns.pop(conn.fileno(), None)
                try:
                    self.poll.unregister(conn.fileno())
                    conn.sendall(word)
                except (OSError, KeyError):
                    pass
                conn.close()

    # ----------------------------------------------------------------------------------------------- reset
    def _can_kill_all(self):
        """``kill(-1)`` is for bubblewrap's pid namespace only: pid 2 under bwrap's pid 1, not root."""
        if not self.layout.isolated or self.pid != 2 or os.getppid() != 1 or os.getuid() == 0:
            return False
        try:
            with open("/proc/1/comm") as f:
                return f.read().strip() == "bwrap"
        except OSError:
            return False

    def _others(self):
        """Processes other than this one and bubblewrap's init, as seen in /proc (isolated), or this one's
        children (not isolated)."""
        out = []
        for name in os.listdir("/proc"):
            if not name.isdigit() or int(name) == self.pid:
                continue
            if self.layout.isolated:
                if int(name) != 1:
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
        for conn, _ in list(self.conns.values()):
            conn.close()
        self.conns.clear()
        self.kernels.clear()
        self.poll = select.poll()
        for fd in (0, self.listener.fileno(), self.wake):
            self.poll.register(fd, select.POLLIN)
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
        # the control directories are writable by the sandbox's user too: anything left beside them would reach
        # the next submission, and a removed or replaced socket would leave it without a kernel
        parent = os.path.dirname(self.layout.work)
        if self.layout.isolated and os.path.dirname(self.layout.zygote) == parent:
            keep = {os.path.basename(self.layout.work), os.path.basename(self.layout.zygote)}
            if sorted(set(os.listdir(parent)) - keep):
                return f"files were left in {parent}"
        try:
            st = os.lstat(self.layout.socket)
            if (st.st_dev, st.st_ino) != self.socket_id or os.listdir(self.layout.zygote) != [SOCKET_NAME]:
                return "the zygote's socket was replaced"
        except OSError:
            return "the zygote's socket was removed"
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
        import resource

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
    import threading

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
    from . import kernel, worker

    kernel.preload()
    worker.preload()


def serve(layout, job_fd, result_fd):
    """Import the kernels' and workers' libraries, listen, say ``ready`` and serve until stdin closes."""
    import gc
    import resource

    set_dumpable(False)
    set_child_subreaper()
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    if hard == resource.RLIM_INFINITY or hard > FILE_SIZE_LIMIT:
        resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_SIZE_LIMIT, FILE_SIZE_LIMIT))
    for d in (layout.home, layout.tmp, layout.work, layout.zygote):
        os.makedirs(d, mode=0o700, exist_ok=True)
    _preload()
    if _LIFELINE[0] is not None:
        _LIFELINE[0].end()
    if not _single_threaded():
        raise RuntimeError("the imports started a thread: forking would not be safe")
    gc.freeze()  # the imported objects stay shared with the forked processes (no copy-on-write by the collector)
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    from .launch import unix_address

    unix_address(layout.socket, listener.bind)
    os.chmod(layout.socket, 0o600)
    listener.listen(16)
    server = _Server(layout, job_fd, result_fd, listener)
    try:
        _say("ready")
        server.run()
    except BrokenPipeError:
        pass
    finally:
        server.shutdown()
        listener.close()


class _Lifeline:
    """Exit at once if stdin (a pipe from the grading process) reaches end of file while the imports run.

    The grading process may die while bubblewrap is still setting the sandbox up, before bubblewrap's own
    parent-death signals are in place; the zygote then starts without anyone to serve. Its stdin's end of file
    says so (the write end was the grading process's), and it exits before the slow imports — taking the
    sandbox with it. A thread, stopped (and joined) before the zygote forks anything.
    """

    def __init__(self):
        import threading

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
    layout = Layout.from_json(argv[0])
    job_fd, result_fd = int(argv[1]), int(argv[2])
    # commands in, events out: pipes passed as descriptors of their own (bubblewrap's init keeps its stdin and
    # stdout, where a student's process could take them), made this process's 0 and 1
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
