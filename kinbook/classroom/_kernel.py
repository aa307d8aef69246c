"""The sandboxed kernel: ``python -m kinbook.classroom._kernel -f CONNECTION_FILE``.

Started by :mod:`kinbook.classroom.sandbox` (never by a student), or forked from the zygote
(:mod:`kinbook.classroom._zygote`, which did step 1 once for many kernels). In order:

1. imports the scientific stack and kinbook (so that imports do not count against the limits below and read
   no file once the audit hook is on);
2. initializes ipykernel (reads the connection file, binds its ZeroMQ sockets);
3. caps the address space at *current size + memory budget* (``RLIMIT_AS``), file size (``RLIMIT_FSIZE``)
   and CPU time (``RLIMIT_CPU``, a backstop to the wall-clock timeout);
4. installs :func:`install_audit_hook` — a ``sys.addaudithook`` hook cannot be removed — and only then
   starts serving cells, so that no student code runs before the hook.

Environment (set by the sandbox): ``KINBOOK_SANDBOX_ROOT`` (the submission's temporary directory),
``KINBOOK_SANDBOX_MEMORY_MB``, ``KINBOOK_SANDBOX_CPU_S``.
"""

from __future__ import annotations

import os
import resource
import socket
import stat
import sys
import sysconfig

__all__ = ["install_audit_hook", "main"]

#: Audit events refused whatever their arguments: other processes, the network, native code, introspection
#: that could reach the hook's own state.
DENIED_EVENTS = frozenset({
    "subprocess.Popen", "os.system", "os.exec", "os.posix_spawn", "os.spawn", "os.fork", "os.forkpty",
    "os.kill", "os.killpg", "os.startfile", "pty.spawn", "os.symlink", "os.link", "os.chroot",
    "socket.bind", "socket.connect", "socket.getaddrinfo", "socket.gethostbyname",
    "socket.sendto", "socket.sendmsg", "urllib.Request", "http.client.connect", "ftplib.connect",
    "smtplib.connect", "imaplib.open", "poplib.connect", "telnetlib.Telnet.open", "webbrowser.open",
    "gc.get_objects", "gc.get_referrers", "gc.get_referents", "sys.settrace", "sys.setprofile",
    "sys._current_frames", "sys.set_asyncgen_hooks_firstiter", "code.__new__", "function.__new__",
    "pickle.find_class", "resource.setrlimit", "resource.prlimit",
    "os.setuid", "os.setgid", "mmap.__new__", "fcntl.ioctl", "os.chdir", "os.fchdir",
    "signal.pthread_kill", "os.putenv", "os.unsetenv",
})
DENIED_PREFIXES = ("ctypes.", "_winapi.", "winreg.", "cpython.run_", "sqlite3.")
#: Functions that reach other processes without raising an audit event (``pidfd_open`` +
#: ``pidfd_send_signal`` would signal the grader or the zygote); :func:`install_audit_hook` removes them, and
#: refuses to import their modules afresh (deleting a module from ``sys.modules`` and importing it again
#: would bring them back).
UNAUDITED = {"posix": ("pidfd_open",), "os": ("pidfd_open",), "_signal": ("pidfd_send_signal",),
             "signal": ("pidfd_send_signal",)}
#: Events whose first argument is a path that must lie inside the temporary directory (writes, deletes,
#: renames, metadata changes).
WRITE_EVENTS = frozenset({
    "os.remove", "os.rmdir", "os.rename", "os.mkdir", "os.chmod", "os.chown", "os.truncate", "os.utime",
    "shutil.rmtree", "shutil.copyfile", "shutil.copytree", "shutil.move", "shutil.make_archive",
    "shutil.unpack_archive", "os.setxattr", "os.removexattr",
})
#: Events whose first argument is a path that may be read (listed) inside the read-only roots too.
READ_EVENTS = frozenset({"os.listdir", "os.scandir", "glob.glob", "glob.glob/2", "os.listxattr", "os.getxattr"})
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_TRUNC | os.O_APPEND


def _read_roots():
    """Directories student code may read: the Python installation and its packages (nothing else)."""
    roots = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix}
    for key in ("stdlib", "platstdlib", "purelib", "platlib"):
        try:
            roots.add(sysconfig.get_paths()[key])
        except KeyError:
            pass
    roots.update(p for p in sys.path if p and os.path.isdir(p) and "site-packages" in p)
    import kinbook

    roots.add(os.path.dirname(os.path.abspath(kinbook.__file__)))  # an editable install: the package only
    roots = {os.path.realpath(r) for r in roots} | {os.path.abspath(r) for r in roots}
    return tuple(sorted(r.rstrip("/") + "/" for r in roots if r and r != "/"))


def install_audit_hook(root, read_roots, extra_files=("/dev/null", "/dev/urandom", "/dev/random")):
    """Install the audit hook that confines the process to ``root``.

    * ``open``: writing (or creating) only under ``root``; reading only under ``root``, ``read_roots`` and
      ``extra_files``; file descriptors (ints) are allowed (they were opened under the same rules).
    * deleting, renaming, creating directories, changing metadata: only under ``root``.
    * processes, signals, sockets, ``ctypes``, ``gc`` and trace/profile hooks, code/function construction,
      ``chdir``, ``setrlimit``: refused; the unaudited ``pidfd_open`` / ``pidfd_send_signal`` are removed
      (:data:`UNAUDITED`) and their modules cannot be imported afresh.

    The hook keeps no mutable state: everything it uses is bound in its closure at installation (builtins
    included), so monkeypatching ``os`` or ``builtins`` afterwards does not change its decisions.
    """
    root = root.rstrip("/") + "/"
    for name, functions in UNAUDITED.items():
        module = __import__(name)
        for f in functions:
            if hasattr(module, f):
                delattr(module, f)
    hook = _make_hook(root, tuple(read_roots), frozenset(extra_files), os.getcwd(), os.fspath, isinstance,
                      str, bytes, int, PermissionError, DENIED_EVENTS, DENIED_PREFIXES, WRITE_EVENTS,
                      READ_EVENTS, _WRITE_FLAGS, len, int(socket.AF_UNIX), os.stat, stat.S_ISDIR, OSError,
                      frozenset(UNAUDITED))
    sys.addaudithook(hook)


def _make_hook(root, read_roots, extra_files, cwd, fspath, isinstance, str, bytes, int, PermissionError,
               denied, denied_prefixes, write_events, read_events, write_flags, len, af_unix, os_stat, s_isdir,
               OSError, pinned):
    # Every name used below is a parameter of this factory (a closure cell of the hook), never a global.
    def norm(path):
        if isinstance(path, int):
            return None
        path = fspath(path)
        if isinstance(path, bytes):
            path = path.decode("utf-8", "surrogateescape")
        if not path.startswith("/"):
            path = cwd + "/" + path
        parts = []
        for piece in path.split("/"):
            if piece == "" or piece == ".":
                continue
            if piece == "..":
                if parts:
                    parts.pop()
                continue
            parts.append(piece)
        return "/" + "/".join(parts)

    def inside(path, prefixes):
        p = path + "/"
        for prefix in prefixes:
            if p.startswith(prefix):
                return True
        return False

    def refuse(event, what):
        raise PermissionError(f"kinbook sandbox: {event} {str(what)[:200]!r} is not allowed while grading")

    def hook(event, args):
        if event in denied:
            refuse(event, args[0] if len(args) else "")
        if event == "socket.__new__":
            # asyncio's self-pipe: a pair of unconnected Unix sockets; connect/bind/sendto stay refused
            if len(args) < 2 or args[1] != af_unix:
                refuse("network sockets", args[1] if len(args) > 1 else "")
            return
        for prefix in denied_prefixes:
            if event.startswith(prefix):
                refuse(event, "")
        if event == "import" and len(args) and args[0] in pinned:
            refuse("importing afresh", args[0])
        if event == "open":
            path, mode, flags = args
            p = norm(path)
            if p is None:
                return
            writing = False
            if isinstance(mode, str):
                for c in "wax+":
                    if c in mode:
                        writing = True
            if isinstance(flags, int) and flags & write_flags:
                writing = True
            if inside(p, (root,)):
                return
            if not writing and (inside(p, read_roots) or p in extra_files):
                # no directory descriptors outside the root: with one, ``dir_fd=`` would make a relative
                # path (which this hook resolves against the working directory) land elsewhere
                try:
                    is_dir = s_isdir(os_stat(p).st_mode)
                except OSError:
                    is_dir = False
                if not is_dir:
                    return
            refuse("opening" + (" for writing" if writing else ""), p)
        elif event in write_events:
            if len(args) and isinstance(args[0], int):
                refuse(event, "a file descriptor")  # fchmod/ftruncate/futimes of a file opened read-only
            # dir_fd arguments (-1 when not given): a descriptor would re-anchor a relative path
            if event.startswith("os.") and event != "os.truncate" and len(args) > 1 and isinstance(args[-1], int) \
                    and args[-1] != -1:
                refuse(event, "dir_fd")
            if event == "os.rename" and len(args) > 2 and isinstance(args[2], int) and args[2] != -1:
                refuse(event, "dir_fd")
            for a in args[:2]:
                if isinstance(a, (str, bytes)) or hasattr(a, "__fspath__"):
                    p = norm(a)
                    if p is not None and not inside(p, (root,)):
                        refuse(event, p)
        elif event in read_events:
            a = args[0] if len(args) else "."
            if isinstance(a, (str, bytes)) or hasattr(a, "__fspath__"):
                p = norm(a)
                if p is not None and not inside(p, (root,)) and not inside(p, read_roots):
                    refuse(event, p)

    return hook


def _preload():
    """Import what nearly every exercise uses, before the limits and the hook (matplotlib stays lazy:
    it is only imported by the notebooks that plot)."""
    import warnings

    warnings.filterwarnings("ignore")
    os.environ.setdefault("MPLBACKEND", "Agg")
    import numpy  # noqa: F401
    import sympy

    import IPython.core.logger  # noqa: F401  (imported lazily by IPython at the first cell)
    import stack_data  # noqa: F401  (tracebacks)

    import kinbook  # noqa: F401
    import kinbook.classroom.parts  # noqa: F401
    import kinbook.classroom.serialize  # noqa: F401

    sympy.lambdify([sympy.Symbol("x")], sympy.sin(sympy.Symbol("x")) ** 2, "numpy")(0.5)
    warnings.resetwarnings()


def _vm_bytes():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    return 0


def main(argv=None, *, forked=False):
    """Start the sandboxed kernel (steps 1–4 of the module docstring) and serve cells until shut down.

    Parameters
    ----------
    argv : list of str, optional
        ipykernel's arguments (``-f CONNECTION_FILE``); default ``sys.argv[1:]``.
    forked : bool
        This process was forked from the zygote (:mod:`kinbook.classroom._zygote`), which did step 1; its
        parent is the zygote, which ipykernel's parent poller then watches.
    """
    argv = sys.argv[1:] if argv is None else argv
    root = os.path.realpath(os.environ["KINBOOK_SANDBOX_ROOT"])
    memory_mb = float(os.environ.get("KINBOOK_SANDBOX_MEMORY_MB", "0"))
    cpu_s = int(float(os.environ.get("KINBOOK_SANDBOX_CPU_S", "0")))
    os.chdir(root)
    options = ["--HistoryManager.enabled=False", "--IPKernelApp.quiet=False"]
    if forked:
        # ipykernel read JPY_PARENT_PID when the zygote imported it: say which parent to watch
        options.append(f"--IPKernelApp.parent_handle={os.getppid()}")
    else:
        _preload()
    from ipykernel.kernelapp import IPKernelApp

    app = IPKernelApp.instance()
    app.initialize(options + list(argv))
    try:
        app.shell.InteractiveTB.set_mode("Plain")  # cheap tracebacks: the grader reads only exception names
    except Exception:
        pass
    read_roots = _read_roots()
    if memory_mb > 0:
        limit = _vm_bytes() + int(memory_mb * 1024 * 1024)
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    if cpu_s > 0:
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_s, cpu_s + 5))
    resource.setrlimit(resource.RLIMIT_FSIZE, (64 * 1024 * 1024, 64 * 1024 * 1024))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    install_audit_hook(root, read_roots)
    app.start()


if __name__ == "__main__":
    main()
