"""The sandbox's kernel command when kernels are forked from a zygote (:mod:`kinbook.classroom._zygote`).

``python -I -S _launch.py SOCKET PIDFILE -f CONNECTION_FILE`` (run by path: it imports only the standard
library, so it starts in a few milliseconds). It stands in for the kernel process that jupyter_client
started before, and behaves like it:

1. sends the zygote its kernel arguments (``-f CONNECTION_FILE``), its environment, working directory, umask
   and resource limits, and its standard streams (``SCM_RIGHTS``); the zygote forks a kernel that takes all
   of them (:func:`kinbook.classroom._zygote.serve`);
2. writes the kernel's process id to ``PIDFILE`` (the sandbox kills that process group at the end, as well
   as this launcher's);
3. forwards ``SIGINT`` (an interrupt request) to the kernel;
4. waits for the kernel's end and ends the same way: with its exit code, or killed by the same signal (so
   that the worker sees ``SIGXCPU`` as a timeout, ``SIGKILL`` after a ``MemoryError`` as out of memory).

When this launcher dies (killed by the worker, by the sandbox's process-group kill), its connection closes
and the zygote kills the kernel's process group at once: no kernel outlives its launcher. When its parent
(the worker) goes away, it exits too, as ipykernel's parent poller makes a kernel do. When the zygote
cannot be reached, it runs the kernel command used without a zygote instead (``python -m
kinbook.classroom._kernel``, in this very process).
"""

import os
import signal
import socket
import sys

_LIMITS = ("RLIMIT_AS", "RLIMIT_CPU", "RLIMIT_FSIZE", "RLIMIT_DATA", "RLIMIT_STACK", "RLIMIT_CORE",
           "RLIMIT_NOFILE", "RLIMIT_NPROC", "RLIMIT_MEMLOCK", "RLIMIT_RSS")


def unix_address(path, call):
    """``call(address)`` with ``path`` as an ``AF_UNIX`` address — through ``/proc/self/fd`` when the path is
    longer than such addresses may be (a deep ``TMPDIR``)."""
    if len(os.fsencode(path)) < 100:
        return call(path)
    fd = os.open(os.path.dirname(path) or ".", os.O_PATH | os.O_DIRECTORY)
    try:
        return call(f"/proc/self/fd/{fd}/{os.path.basename(path)}")
    finally:
        os.close(fd)


def request(role, argv, env=None, cwd=None):
    """A launch request for the zygote (JSON bytes): what to run (``role``, ``argv``), with which environment
    and working directory (default: this process's), and this process's umask and resource limits."""
    import json
    import resource

    umask = os.umask(0)
    os.umask(umask)
    limits = {name: list(resource.getrlimit(getattr(resource, name))) for name in _LIMITS
              if hasattr(resource, name)}
    return json.dumps({"role": role, "argv": list(argv), "env": dict(os.environ if env is None else env),
                       "cwd": os.getcwd() if cwd is None else cwd, "umask": umask, "rlimits": limits}).encode()


def returncode(status):
    """The zygote's ``exit N`` / ``signal N`` as a ``subprocess`` return code (N, or −N for a signal)."""
    kind, _, number = status.partition(b" ")
    return -int(number) if kind == b"signal" else int(number)


def _fallback(kernel_argv):
    """Run the kernel without the zygote: this process becomes ``python -m kinbook.classroom._kernel``."""
    os.execv(sys.executable, [sys.executable, "-m", "kinbook.classroom._kernel"] + list(kernel_argv))


def _end_like(status):
    """Exit as the kernel did: ``b"exit N"`` → exit code N; ``b"signal N"`` → killed by signal N."""
    code = returncode(status)
    if code < 0:
        number = -code
        import resource

        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))  # a mirrored SIGXCPU or SIGSEGV dumps no core
        try:
            signal.signal(number, signal.SIG_DFL)
            signal.pthread_sigmask(signal.SIG_UNBLOCK, [number])
        except (OSError, ValueError):
            pass
        os.kill(os.getpid(), number)
        os._exit(128 + number)  # a signal whose default action is not to terminate
    os._exit(code & 0xFF)


def main(argv):
    """Launch one kernel through the zygote at ``argv[0]``; ``argv[1]`` is the pid file, the rest the kernel's
    arguments."""
    path, pidfile, kernel_argv = argv[0], argv[1], argv[2:]
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    try:
        unix_address(path, sock.connect)
        socket.send_fds(sock, [request("kernel", kernel_argv)], [0, 1, 2])
        reply = sock.recv(64)
    except OSError:
        reply = b""
    if not reply.startswith(b"pid "):
        sock.close()
        _fallback(kernel_argv)
    pid = int(reply[4:])
    tmp = pidfile + ".tmp"
    with open(tmp, "w") as f:
        f.write(str(pid))
    os.replace(tmp, pidfile)
    signal.signal(signal.SIGINT, lambda signum, frame: os.kill(pid, signal.SIGINT))
    parent = os.getppid()
    sock.settimeout(1.0)
    while True:
        try:
            status = sock.recv(64)
            break
        except socket.timeout:
            if os.getppid() != parent:  # the worker is gone: so is this launcher, and with it the kernel
                os._exit(1)
        except OSError:
            status = b""
            break
    if not status:  # the zygote is gone without a word: its kernel must not stay behind
        try:
            os.killpg(pid, signal.SIGKILL)
        except OSError:
            pass
        os._exit(1)
    _end_like(status)


if __name__ == "__main__":
    main(sys.argv[1:])
