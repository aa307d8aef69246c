"""The kernelspec's command: ``python -I -S launch.py CHANNEL_FD PIDFILE``.

Run by path by the worker's jupyter_client (it imports only the standard library, so it starts in a few
milliseconds), with ``CHANNEL_FD`` — the worker's end of the run's launch channel, a socket pair the zygote
made for this run (:mod:`.zygote`) — passed down to it. It stands in for the kernel process that
jupyter_client would have started, and behaves like it:

1. writes ``launch`` on the channel; the zygote forks the run's one kernel, with arguments, environment,
   directory and limits of its own (nothing of this process's), and answers ``pid N``;
2. writes the kernel's process id to ``PIDFILE``;
3. forwards ``SIGINT`` (an interrupt request) to the kernel;
4. waits for the kernel's end and ends the same way: with its exit code, or killed by the same signal (so
   that the worker sees ``SIGXCPU`` as a timeout, ``SIGKILL`` after a ``MemoryError`` as out of memory).

When this launcher dies (killed by the worker, or at the end of the run), the channel closes and the zygote
kills the kernel's process group at once. When its parent (the worker) goes away, it exits too, as ipykernel's
parent poller makes a kernel do. When the zygote does not answer, it exits with status 1 (the worker then
reports a kernel that did not start).
"""

import os
import resource
import signal
import socket
import sys

__all__ = ["main", "returncode"]


def returncode(status):
    """The zygote's ``exit N`` / ``signal N`` as a ``subprocess`` return code (N, or −N for a signal)."""
    kind, _, number = status.partition(b" ")
    return -int(number) if kind == b"signal" else int(number)


def _end_like(status):
    """Exit as the kernel did: ``b"exit N"`` → exit code N; ``b"signal N"`` → killed by signal N."""
    code = returncode(status)
    if code < 0:
        number = -code

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
    """Launch the run's kernel through the channel at descriptor ``argv[0]``; ``argv[1]`` is the pid file."""
    fd, pidfile = int(argv[0]), argv[1]
    try:
        sock = socket.socket(fileno=fd)
        sock.sendall(b"launch")
        sock.settimeout(60.0)
        reply = sock.recv(64)
    except OSError:
        reply = b""
    if not reply.startswith(b"pid ") or not reply[4:].isdigit():
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
