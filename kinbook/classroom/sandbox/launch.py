"""The kernelspec's command: ``python -I -S launch.py SOCKET PIDFILE -f CONNECTION_FILE``.

Run by path by the worker's jupyter_client (it imports only the standard library, so it starts in a few
milliseconds). It stands in for the kernel process that jupyter_client would have started, and behaves
like it:

1. sends the zygote (:mod:`.zygote`, its socket ``SOCKET``) a launch request: the kernel's arguments
   (``-f CONNECTION_FILE``), its environment, working directory, umask and resource limits; the zygote forks
   a kernel that takes all of them;
2. writes the kernel's process id to ``PIDFILE``;
3. forwards ``SIGINT`` (an interrupt request) to the kernel;
4. waits for the kernel's end and ends the same way: with its exit code, or killed by the same signal (so
   that the worker sees ``SIGXCPU`` as a timeout, ``SIGKILL`` after a ``MemoryError`` as out of memory).

When this launcher dies (killed by the worker, or at the end of the run), its connection closes and the
zygote kills the kernel's process group at once. When its parent (the worker) goes away, it exits too, as
ipykernel's parent poller makes a kernel do. When the zygote cannot be reached, it exits with status 1 (the
worker then reports a kernel that did not start).
"""

import os
import signal
import socket
import sys

__all__ = ["main", "request", "returncode", "unix_address"]

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


def request(argv):
    """A kernel launch request for the zygote (JSON bytes): its arguments, and this process's environment,
    working directory, umask and resource limits."""
    import json
    import resource

    umask = os.umask(0)
    os.umask(umask)
    limits = {name: list(resource.getrlimit(getattr(resource, name))) for name in _LIMITS
              if hasattr(resource, name)}
    return json.dumps({"role": "kernel", "argv": list(argv), "env": dict(os.environ), "cwd": os.getcwd(),
                       "umask": umask, "rlimits": limits}).encode()


def returncode(status):
    """The zygote's ``exit N`` / ``signal N`` as a ``subprocess`` return code (N, or −N for a signal)."""
    kind, _, number = status.partition(b" ")
    return -int(number) if kind == b"signal" else int(number)


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
        sock.sendall(request(kernel_argv))
        reply = sock.recv(64)
    except OSError:
        reply = b""
    if not reply.startswith(b"pid "):
        os._exit(1)
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
