"""A pre-warmed parent for the sandbox's processes: ``python -m kinbook.classroom._zygote SOCKET``.

Running one submission takes two Python processes: the worker (it imports nbclient) and the kernel (numpy,
sympy, IPython, kinbook). Started from scratch, their imports are most of a submission's time. The
*zygote* does these imports once, then forks both processes for every submission:

``worker``
    :func:`kinbook.classroom.sandbox._worker` (requested by the sandbox, :meth:`Zygote.spawn`);
``kernel``
    :func:`kinbook.classroom._kernel.main` (requested by the launcher :mod:`kinbook.classroom._launch`,
    the command of the kernelspec the worker gives jupyter_client).

Each is a new process per submission that goes through the rest of its start-up itself; a kernel in
particular initializes ipykernel, caps its resources from its own size and installs the audit hook before
any student code runs, exactly as a kernel started from scratch.

What the zygote holds
    It is a fresh interpreter (``subprocess``: fork *and* exec), started with a clean environment (that of
    the sandbox's worker), in a private directory. It imports libraries and receives launch requests
    (a role, its arguments — a control directory, a connection file —, an environment, a working
    directory, limits, three file descriptors); nothing else: never an instructor's source notebook,
    solutions or references, never a submission. So neither it nor the processes forked from it can leak
    them.

Protocol
    The zygote listens on a ``SOCK_SEQPACKET`` Unix socket ``SOCKET`` (mode 0600, in the 0700 directory
    made by :class:`Zygote`). A client connects and sends one JSON request ``{"role", "argv", "env",
    "cwd", "umask", "rlimits"}`` with three descriptors attached (``SCM_RIGHTS``). The zygote forks; the
    child starts a new session, takes the descriptors as its stdin, stdout and stderr, the environment,
    working directory, umask and (never looser) resource limits, closes the zygote's own sockets, and runs
    the role. The zygote answers ``pid N``, later ``exit N`` or ``signal N`` when the child ends. If the
    client's connection closes first (it was killed), the zygote kills the child's process group at once.

Lifetime
    Started by the grading process (:class:`Zygote`, through :func:`kinbook.classroom.sandbox.zygote`);
    it serves until its standard input — a pipe from that process — closes: when the grading process
    stops it, or dies. It then kills the process groups of all its children, waits for them, removes its
    directory and exits.

The zygote is single-threaded and creates no ZeroMQ context or event loop, so forking it is safe;
:func:`serve` checks that the imports started no thread.

Differences from processes started from scratch
    They have more modules already imported (the worker's and the kernel's both); the kernels of one
    zygote share its string-hash seed (numpy's global random state is reseeded in each, Python's
    ``random`` reseeds itself); a kernel's CPU-time limit counts from the fork, so the imports no longer
    use it up; ipykernel's parent poller watches the zygote, and the launcher watches the worker.
"""

from __future__ import annotations

import json
import os
import select
import shutil
import signal
import socket
import sys
import tempfile
import traceback

__all__ = ["Zygote", "ZygoteError", "supported", "serve"]

#: Most bytes of one launch request.
MAX_REQUEST = 1 << 20
SOCKET_NAME = "fork.sock"


class ZygoteError(RuntimeError):
    """The zygote could not be started, or did not take a request."""


def supported():
    """Whether this platform can run a zygote (Linux: ``fork``, ``pidfd_open``, descriptor passing)."""
    return (sys.platform.startswith("linux") and hasattr(os, "fork") and hasattr(os, "pidfd_open")
            and hasattr(socket, "SOCK_SEQPACKET") and hasattr(socket, "send_fds"))


# ================================================================================== in the grading process
class Zygote:
    """A running zygote, seen from the process that started it.

    Parameters
    ----------
    env : dict
        The zygote's whole environment (the sandbox's clean worker environment).
    timeout : float
        Seconds allowed for its imports.

    Raises
    ------
    ZygoteError
        It could not be started, or did not say it was ready in time.

    Attributes
    ----------
    socket : str
        Where clients (:meth:`spawn`, the launcher) connect.
    process : subprocess.Popen
    """

    def __init__(self, env, timeout=60.0):
        import subprocess

        self.owner = os.getpid()
        self.dir = os.path.realpath(tempfile.mkdtemp(prefix="kinbook-zygote-"))
        os.chmod(self.dir, 0o700)
        self.socket = os.path.join(self.dir, SOCKET_NAME)
        env = dict(env, HOME=self.dir)  # no user site-packages of the grader's account
        try:
            with open(os.path.join(self.dir, "zygote.log"), "wb") as log:
                self.process = subprocess.Popen(
                    [sys.executable, "-m", "kinbook.classroom._zygote", self.socket], env=env, cwd=self.dir,
                    stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=log, start_new_session=True)
        except BaseException as exc:  # (also when this process is being terminated)
            shutil.rmtree(self.dir, ignore_errors=True)
            if isinstance(exc, OSError):
                raise ZygoteError(f"the kernel zygote could not be started: {exc}") from None
            raise
        try:
            ready, _, _ = select.select([self.process.stdout], [], [], timeout)
            line = self.process.stdout.readline() if ready else b""
        except BaseException:  # this process is being terminated: so is its zygote
            self.close()
            raise
        self.process.stdout.close()
        if line != b"ready\n":
            try:
                with open(os.path.join(self.dir, "zygote.log"), "rb") as f:
                    why = f.read()[-300:].decode(errors="replace").strip()
            except OSError:
                why = ""
            self.close()
            raise ZygoteError(f"the kernel zygote did not start: {why or 'no answer'}")

    @property
    def pid(self):
        """The zygote's process id."""
        return self.process.pid

    def alive(self):
        """The zygote runs and belongs to this process (not to a process it forked)."""
        return self.owner == os.getpid() and self.process.poll() is None

    def close(self, timeout=10.0):
        """Stop the zygote (it kills its children first) and wait for it; remove its directory."""
        import subprocess

        if self.owner != os.getpid():
            self.forget()
            return
        if self.process.stdin and not self.process.stdin.closed:
            self.process.stdin.close()
        try:
            self.process.wait(timeout)
        except subprocess.TimeoutExpired:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait()
        shutil.rmtree(self.dir, ignore_errors=True)

    def spawn(self, role, argv, env, cwd, stdio):
        """Fork a process of ``role`` (``"worker"``: :func:`kinbook.classroom.sandbox._worker`) from the zygote.

        Parameters
        ----------
        role : str
        argv : list of str
            The role's arguments (the worker's control directory).
        env : dict
            Its whole environment.
        cwd : str
        stdio : sequence of 3 int
            Descriptors that become its standard input, output and error.

        Returns
        -------
        Forked

        Raises
        ------
        ZygoteError
            The zygote did not take the request.
        """
        from ._launch import request, unix_address

        sock = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            unix_address(self.socket, sock.connect)
            socket.send_fds(sock, [request(role, argv, env, cwd)], list(stdio))
            reply = sock.recv(64)
        except OSError as exc:
            sock.close()
            raise ZygoteError(f"the kernel zygote did not answer: {exc}") from None
        if not reply.startswith(b"pid "):
            sock.close()
            raise ZygoteError("the kernel zygote refused the request")
        return Forked(sock, int(reply[4:]))

    def forget(self):
        """In a forked copy of the owner: drop the inherited end of the control pipe, so that the zygote still
        stops when its owner does."""
        if self.process.stdin and not self.process.stdin.closed:
            self.process.stdin.close()
        self.process.returncode = 0  # not ours to wait for


class Forked:
    """A process forked by the zygote for this one, used like a ``subprocess.Popen`` (``pid``, ``wait``,
    ``returncode``).

    Its connection to the zygote stays open until it has ended: if this process dies first, the zygote
    kills the forked process's group.

    Attributes
    ----------
    pid : int
        Also its process group (it starts a new session).
    returncode : int or None
        Once it has ended: its exit code, or −N if it was killed by signal N.
    """

    def __init__(self, sock, pid):
        self._sock = sock
        self.pid = pid
        self.returncode = None

    def wait(self, timeout=None):
        """Wait until the process ends; ``subprocess.TimeoutExpired`` after ``timeout`` seconds."""
        import subprocess

        from ._launch import returncode

        if self.returncode is not None:
            return self.returncode
        self._sock.settimeout(timeout)
        try:
            status = self._sock.recv(64)
        except (socket.timeout, BlockingIOError):
            raise subprocess.TimeoutExpired(f"process {self.pid} forked by the zygote", timeout) from None
        except OSError:
            status = b""
        self._sock.close()
        if status:
            self.returncode = returncode(status)
        else:  # the zygote is gone: make sure that its child is too
            _kill(self.pid)
            self.returncode = -signal.SIGKILL
        return self.returncode


# =========================================================================================== in the zygote
def _kill(pid):
    """Kill the process group of a forked child (the process itself if it has no group of its own yet)."""
    try:
        os.killpg(pid, signal.SIGKILL)
    except OSError:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


def _exit_code(exc):
    code = exc.code
    if code is None:
        return 0
    if isinstance(code, int):
        return code & 0xFF
    print(code, file=sys.stderr)
    return 1


class _Server:
    """The zygote's loop: accept launch requests, fork, relay how each child ended."""

    def __init__(self, listener, path):
        self.listener = listener
        self.path = path
        self.poll = select.poll()
        self.poll.register(0, select.POLLIN)  # the control pipe: any event (data, end of file) means stop
        self.poll.register(listener.fileno(), select.POLLIN)
        self.conns = {}   # connection fd → (socket, child pid)
        self.pidfds = {}  # pidfd → (child pid, connection fd or None)

    def run(self):
        try:
            while True:
                for fd, _ in self.poll.poll():
                    if fd == 0:
                        return
                    if fd == self.listener.fileno():
                        self._accept()
                    elif fd in self.conns:
                        self._client_gone(fd)
                    elif fd in self.pidfds:
                        self._reap(fd)
        finally:
            self._shutdown()

    def _accept(self):
        try:
            conn, _ = self.listener.accept()
        except OSError:
            return
        fds = []
        try:
            conn.settimeout(10.0)
            msg, fds, flags, _ = socket.recv_fds(conn, MAX_REQUEST, 3)
            if flags & (socket.MSG_TRUNC | socket.MSG_CTRUNC) or len(fds) != 3:
                raise ValueError("truncated request")
            request = json.loads(msg)
            if request.get("role") not in _ROLES:
                raise ValueError("unknown role")
            conn.settimeout(None)
        except (OSError, ValueError, TypeError, AttributeError):
            for fd in fds:
                os.close(fd)
            conn.close()
            return
        try:
            pid = os.fork()
        except OSError:  # no more processes for now: the client falls back to starting one itself
            pid = None
        if pid == 0:
            self._child(request, fds, conn)  # never returns
        for fd in fds:
            os.close(fd)
        if pid is None:
            conn.close()
            return
        pidfd = os.pidfd_open(pid)
        self.pidfds[pidfd] = (pid, conn.fileno())
        self.poll.register(pidfd, select.POLLIN)
        self.conns[conn.fileno()] = (conn, pid)
        self.poll.register(conn.fileno(), select.POLLIN)
        try:
            conn.sendall(b"pid %d" % pid)
        except OSError:
            self._client_gone(conn.fileno())

    def _client_gone(self, fd):
        conn, pid = self.conns.pop(fd)
        self.poll.unregister(fd)
        conn.close()
        _kill(pid)  # reaped (and its pidfd closed) when the pidfd says it is gone

    def _reap(self, pidfd):
        pid, fd = self.pidfds.pop(pidfd)
        self.poll.unregister(pidfd)
        os.close(pidfd)
        _, status = os.waitpid(pid, 0)
        if fd in self.conns and self.conns[fd][1] == pid:
            conn, _ = self.conns.pop(fd)
            self.poll.unregister(fd)
            if os.WIFSIGNALED(status):
                word = b"signal %d" % os.WTERMSIG(status)
            else:
                word = b"exit %d" % os.waitstatus_to_exitcode(status)
            try:
                conn.sendall(word)
            except OSError:
                pass
            conn.close()

    def _shutdown(self):
        for pid, _ in self.pidfds.values():
            _kill(pid)
        for pidfd in list(self.pidfds):  # each client learns that its child was killed (a launcher dies the same way)
            self._reap(pidfd)
        for conn, _ in self.conns.values():
            conn.close()
        self.conns.clear()
        self.listener.close()
        try:
            os.unlink(self.path)
        except OSError:
            pass

    def _child(self, request, fds, conn):
        """In the forked child: leave the zygote behind, take the client's place, run the role (never returns)."""
        code = 1
        try:
            os.setsid()
            self.listener.close()
            conn.close()
            for other, _ in self.conns.values():
                other.close()
            for pidfd in self.pidfds:
                os.close(pidfd)
            for target, fd in enumerate(fds):
                os.dup2(fd, target)
                os.close(fd)
            os.environ.clear()
            os.environ.update(request["env"])
            for key, value in _IMPORTED_ENV[request["role"]].items():
                os.environ.setdefault(key, value)
            os.chdir(request["cwd"])
            os.umask(int(request["umask"]))
            _apply_limits(request["rlimits"])
            tempfile.tempdir = None  # the temporary directory comes from the new environment
            code = _ROLES[request["role"]](list(request["argv"]))
        except SystemExit as exc:
            code = _exit_code(exc)
        except BaseException:
            traceback.print_exc()
            code = 1
        finally:
            for stream in (sys.__stdout__, sys.__stderr__):
                try:
                    stream.flush()
                except Exception:
                    pass
            os._exit(code)


def _apply_limits(limits):
    """Take the launcher's resource limits, never looser than the zygote's own."""
    import resource

    for name, (soft, hard) in limits.items():
        which = getattr(resource, name, None)
        if which is None:
            continue
        cur_soft, cur_hard = resource.getrlimit(which)
        inf = resource.RLIM_INFINITY

        def tighter(a, b):
            return b if a == inf else a if b == inf else min(a, b)

        hard = tighter(hard, cur_hard)
        soft = tighter(soft, hard)
        resource.setrlimit(which, (soft, hard))


def _run_kernel(argv):
    """The ``kernel`` role: what ``python -m kinbook.classroom._kernel ARGV`` does after its imports."""
    from . import _kernel

    sys.argv = [_kernel.__file__] + argv
    sys.path[0] = os.getcwd()  # as ``python -m`` run in the kernel's working directory
    if "numpy.random" in sys.modules:  # each kernel its own random state, as in a fresh process
        sys.modules["numpy.random"].seed()
    _kernel.main(argv, forked=True)
    return 0


def _run_worker(argv):
    """The ``worker`` role: what ``sandbox.py CONTROL`` does (run one notebook with nbclient)."""
    from . import sandbox

    sys.argv = [sandbox.__file__] + argv
    sandbox._worker(argv[0])
    return 0


_ROLES = {"kernel": _run_kernel, "worker": _run_worker}
#: Environment variables that a role's imports set (debugpy: ``PYDEVD_USE_FRAME_EVAL``); a process started
#: from scratch would set them after receiving its environment, so a forked one gets them back.
_IMPORTED_ENV = {"kernel": {}, "worker": {}}


def _added(before):
    return {k: v for k, v in os.environ.items() if before.get(k) != v}


def _single_threaded():
    try:
        return len(os.listdir("/proc/self/task")) == 1
    except OSError:
        import threading

        return threading.active_count() == 1


def serve(path):
    """Import the kernels' libraries, listen on ``path``, print ``ready`` and serve until stdin closes."""
    import gc

    from . import _kernel
    from ._launch import unix_address

    env = dict(os.environ)
    _kernel._preload()  # the kernels' imports (kinbook.classroom skips the slow IRI grammar of jsonschema)
    import ipykernel.debugger  # noqa: F401  (what IPKernelApp.initialize imports)
    import ipykernel.ipkernel  # noqa: F401
    import ipykernel.kernelapp  # noqa: F401
    import ipykernel.zmqshell  # noqa: F401

    _IMPORTED_ENV["kernel"] = _added(env)
    env = dict(os.environ)
    import jupyter_client  # noqa: F401  (the workers' imports)
    import jupyter_client.kernelspec  # noqa: F401
    import nbclient  # noqa: F401
    import nbformat  # noqa: F401

    _IMPORTED_ENV["worker"] = _added(env)

    if not _single_threaded():
        raise ZygoteError("the imports started a thread: forking would not be safe")
    os.close(os.pidfd_open(os.getpid()))  # fails early where the kernel is too old for pidfds
    gc.freeze()  # the imported objects stay shared with the forked kernels (no copy-on-write by the collector)
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    unix_address(path, listener.bind)
    os.chmod(path, 0o600)
    listener.listen(16)
    try:
        sys.stdout.write("ready\n")
        sys.stdout.flush()
    except BrokenPipeError:  # whoever started the zygote is gone already
        listener.close()
    else:
        _Server(listener, path).run()
    finally:
        # the directory is the zygote's (its owner removes it too, unless it was killed)
        shutil.rmtree(os.path.dirname(path), ignore_errors=True)


if __name__ == "__main__":
    serve(sys.argv[1])
