"""The student's kernel, forked from the zygote (:mod:`.zygote`) for each submission.

The zygote did the imports once (:func:`preload`: the scientific stack and kinbook, so that imports do not
count against the limits below and read no file once the audit hook is on). In each forked kernel, the zygote
first sets its environment (its own, fixed), directory, CPU time (``RLIMIT_CPU``: the run's timeout, which decides
the verdict; the worker's wall clock is only a backstop), file size, open files and processes, and — where no
control group holds the sandbox together — a
seccomp filter that lets it start threads but no process. Then :func:`main`:

1. initializes ipykernel (reads the connection file, binds its ZeroMQ sockets);
2. caps the address space at *current size + memory budget* (``RLIMIT_AS``: a ``MemoryError`` the notebook
   sees, before the sandbox's control group, if any, would kill the process) and the output it sends
   (:func:`cap_output`);
3. installs :func:`install_audit_hook` — a ``sys.addaudithook`` hook cannot be removed — and only then
   starts serving cells, so that no student code runs before the hook.

The hook is *advisory*: a fence that makes ordinary mistakes and casual attempts fail with a clear
``PermissionError``, not a boundary — code that reaches ``ctypes`` (or any native code) can switch it off. The
boundary is the operating-system sandbox around the zygote and everything it forks (:mod:`.bwrap`, and the
control group of :mod:`.cgroup`), which the tests check with the hook off. Without bubblewrap
(``--no-isolation``) the hook and the limits are all there is.

Environment (set by the zygote): ``KINBOOK_SANDBOX_ROOT`` (the submission's copy: working directory,
writable) and ``KINBOOK_SANDBOX_TMP`` (the private temporary directory, writable). The limits and whether the
hook is installed come from the grading process, never from the environment.
"""

from __future__ import annotations

import contextlib
import os
import resource
import socket
import stat
import sys
import sysconfig
import warnings

import kinbook

__all__ = ["install_audit_hook", "main", "preload"]

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
#: Functions that act without raising an audit event (``pidfd_open`` + ``pidfd_send_signal`` signal another
#: process, ``fork_exec`` starts one, ``mknod``/``mkfifo`` make device nodes and FIFOs, ``memfd_create`` makes
#: files of memory that neither the address-space limit nor a directory's size cap counts);
#: :func:`install_audit_hook` removes them, and refuses to import their modules afresh (deleting a module from
#: ``sys.modules`` and importing it again would bring them back).
UNAUDITED = {"posix": ("pidfd_open", "mknod", "mkfifo", "memfd_create"),
             "os": ("pidfd_open", "mknod", "mkfifo", "memfd_create"),
             "_signal": ("pidfd_send_signal",), "signal": ("pidfd_send_signal",), "_posixsubprocess": ("fork_exec",)}
#: Modules whose import is refused: a subinterpreter (it starts without this hook), and CPython's test helpers
#: (they corrupt memory on purpose).
REFUSED_IMPORTS = frozenset({"_xxsubinterpreters", "_xxinterpchannels", "_xxinterpqueues", "_interpreters",
                             "_interpchannels", "_interpqueues", "_testcapi", "_testinternalcapi",
                             "_testmultiphase", "_testimportmultiple", "_testsinglephase", "_ctypes"})
#: Events whose first argument is a path that must lie inside the temporary directory (writes, deletes,
#: renames, metadata changes).
WRITE_EVENTS = frozenset({
    "os.remove", "os.rmdir", "os.rename", "os.mkdir", "os.chmod", "os.chown", "os.truncate", "os.utime",
    "shutil.rmtree", "shutil.copyfile", "shutil.copytree", "shutil.move", "shutil.make_archive",
    "shutil.unpack_archive", "os.setxattr", "os.removexattr",
})
#: Events whose first argument is a path that may be read (listed) inside the read-only roots too.
READ_EVENTS = frozenset({"os.listdir", "os.scandir", "glob.glob", "glob.glob/2", "os.listxattr", "os.getxattr"})
#: Characters written to descriptors 1 and 2 that a run may send out of the kernel (:func:`cap_output`).
MAX_OUTPUT_CHARS = 100_000
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

    roots.add(os.path.dirname(os.path.abspath(kinbook.__file__)))  # an editable install: the package only
    roots = {os.path.realpath(r) for r in roots} | {os.path.abspath(r) for r in roots}
    return tuple(sorted(r.rstrip("/") + "/" for r in roots if r and r != "/"))


def install_audit_hook(root, read_roots, extra_files=("/dev/null", "/dev/urandom", "/dev/random")):
    """Install the audit hook that confines the process to ``root`` (a directory, or a tuple of them).

    * ``open``: writing (or creating) only under ``root``; reading only under ``root``, ``read_roots`` and
      ``extra_files``; file descriptors (ints) are allowed (they were opened under the same rules).
    * deleting, renaming, creating directories, changing metadata: only under ``root``.
    * processes, signals, sockets, ``ctypes``, ``gc`` and trace/profile hooks, code/function construction,
      replacing a function's ``__code__``, ``chdir``, ``setrlimit``: refused; the unaudited functions of
      :data:`UNAUDITED` are removed and their modules cannot be imported afresh; subinterpreters and CPython's
      test modules cannot be imported (:data:`REFUSED_IMPORTS`).

    The hook keeps no mutable state: everything it uses is bound in its closure at installation (builtins
    included), so monkeypatching ``os`` or ``builtins`` afterwards does not change its decisions.
    """
    roots = (root,) if isinstance(root, str) else tuple(root)
    root = tuple(r.rstrip("/") + "/" for r in roots)
    for name, functions in UNAUDITED.items():
        try:
            module = __import__(name)
        except ImportError:
            continue
        for f in functions:
            if hasattr(module, f):
                delattr(module, f)
    hook = _make_hook(root, tuple(read_roots), frozenset(extra_files), os.getcwd(), os.fspath, isinstance,
                      str, bytes, int, PermissionError, DENIED_EVENTS, DENIED_PREFIXES, WRITE_EVENTS,
                      READ_EVENTS, _WRITE_FLAGS, len, int(socket.AF_UNIX), os.stat, stat.S_ISDIR, OSError,
                      frozenset(UNAUDITED) | REFUSED_IMPORTS, frozenset({"__code__"}), hasattr)
    sys.addaudithook(hook)


def _make_hook(roots, read_roots, extra_files, cwd, fspath, isinstance, str, bytes, int, PermissionError,
               denied, denied_prefixes, write_events, read_events, write_flags, len, af_unix, os_stat, s_isdir,
               OSError, refused_imports, refused_attrs, hasattr):
    # Every name used below is a parameter of this factory (a closure cell of the hook), never a global, and the
    # hook is one function with no helpers: a frame it raises in exposes nothing a student could change (a
    # helper function object would be reachable from the traceback and its ``__code__`` replaceable).
    def hook(event, args):
        why = what = None
        if event in denied:
            why, what = event, args[0] if len(args) else ""
        elif event == "socket.__new__":
            # asyncio's self-pipe: a pair of unconnected Unix sockets; connect/bind/sendto stay refused
            if len(args) < 2 or args[1] != af_unix:
                why, what = "network sockets", args[1] if len(args) > 1 else ""
        elif event == "import":
            if len(args) and args[0] in refused_imports:
                why, what = "importing", args[0]
        elif event == "object.__setattr__":
            if len(args) > 1 and args[1] in refused_attrs:
                why, what = "setting", args[1]
        elif event == "open" or event in write_events or event in read_events:
            writing = event in write_events
            candidates = args[:2] if writing else args[:1]
            if event == "open":
                mode, flags = args[1], args[2]
                writing = (isinstance(mode, str) and ("w" in mode or "a" in mode or "x" in mode or "+" in mode)) \
                    or (isinstance(flags, int) and (flags & write_flags) != 0)
            elif writing:
                if len(args) and isinstance(args[0], int):
                    why, what = event, "a file descriptor"  # fchmod/ftruncate/futimes of a file opened read-only
                # dir_fd arguments (-1 when not given): a descriptor would re-anchor a relative path
                if event[:3] == "os." and event != "os.truncate" and len(args) > 1 and isinstance(args[-1], int) \
                        and args[-1] != -1:
                    why, what = event, "dir_fd"
                if event == "os.rename" and len(args) > 2 and isinstance(args[2], int) and args[2] != -1:
                    why, what = event, "dir_fd"
            elif not len(args):
                candidates = (".",)
            for path in candidates:
                if why is not None:
                    break
                if isinstance(path, int) or not (isinstance(path, (str, bytes)) or hasattr(path, "__fspath__")):
                    continue
                path = fspath(path)
                if isinstance(path, bytes):
                    path = path.decode("utf-8", "surrogateescape")
                if path[:1] != "/":
                    path = cwd + "/" + path
                parts = []
                for piece in path.split("/"):
                    if piece == "..":
                        parts[-1:] = []
                    elif piece and piece != ".":
                        parts.append(piece)
                p = "/" + "/".join(parts)
                probe = p + "/"
                if probe.startswith(roots):
                    continue
                if not writing:
                    readable = p in extra_files or probe.startswith(read_roots)
                    if readable and event == "open":
                        # no directory descriptors outside the root: with one, ``dir_fd=`` would make a relative
                        # path (which this hook resolves against the working directory) land elsewhere
                        try:
                            readable = not s_isdir(os_stat(p).st_mode)
                        except OSError:
                            pass
                    if readable:
                        continue
                why, what = ("opening for writing" if writing else "opening") if event == "open" else event, p
        elif event.startswith(denied_prefixes):
            why, what = event, ""
        if why is not None:
            raise PermissionError(f"kinbook sandbox: {why} {str(what)[:200]!r} is not allowed while grading")

    return hook


def _vm_bytes():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    return 0


def preload():
    """Import what nearly every exercise uses, before the limits and the hook (in the zygote, once: the kernels
    forked from it share these pages). matplotlib's font list is built here too, so that a plotting cell does
    not rebuild it in every kernel."""
    warnings.filterwarnings("ignore")
    os.environ.setdefault("MPLBACKEND", "Agg")
    import IPython.core.logger  # noqa: F401  (imported lazily by IPython at the first cell)
    import numpy  # noqa: F401  (preloaded in the zygote, as sympy)
    import stack_data  # noqa: F401  (tracebacks)
    import sympy  # preloaded in the zygote (this function's purpose), not when the module is imported

    import kinbook.classroom.parts  # noqa: F401  (preloaded in the zygote, as sympy)
    import kinbook.classroom.sandbox.trace  # preloaded in the zygote, as sympy
    import kinbook.classroom.serialize  # noqa: F401  (preloaded in the zygote, as sympy)

    kinbook.classroom.sandbox.trace.load_reference_modules()  # (for the reference's calls to be observed)

    sympy.lambdify([sympy.Symbol("x")], sympy.sin(sympy.Symbol("x")) ** 2, "numpy")(0.5)
    import matplotlib  # preloaded in the zygote, as sympy

    matplotlib.use("Agg")
    import ipykernel.debugger  # noqa: F401  (what IPKernelApp.initialize imports)
    import ipykernel.ipkernel  # noqa: F401  (preloaded in the zygote, as sympy)
    import ipykernel.kernelapp  # noqa: F401  (preloaded in the zygote, as sympy)
    import ipykernel.zmqshell  # noqa: F401  (preloaded in the zygote, as sympy)
    import matplotlib.font_manager  # noqa: F401  (builds the font list once)
    import matplotlib.pyplot  # noqa: F401  (preloaded in the zygote, as sympy)

    warnings.resetwarnings()


def cap_output(limit=MAX_OUTPUT_CHARS):
    """Send the notebook's printed output nowhere: the grader reads answers, not output (the worker keeps only
    each cell's exception). ``sys.stdout`` and ``sys.stderr`` become the null device (a ``print`` is one C-level
    write: a 300,000-line flood costs a fraction of a second and no memory, and is graded like any other
    notebook); what reaches descriptors 1 and 2 directly (C code, ``os.write``) still goes through ipykernel's
    streams, of which at most ``limit`` characters leave the kernel."""
    written = [0]
    for stream in (sys.stdout, sys.stderr):
        write = getattr(stream, "write", None)
        if write is None:
            continue

        def capped(text, write=write):
            n = len(text) if isinstance(text, str) else 0
            if written[0] >= limit:
                return n
            written[0] += n
            return write(text[:limit - written[0] + n])

        stream.write = capped
    null = open(os.devnull, "w")
    sys.stdout = sys.stderr = null


def main(argv, layout, memory_mb, audit=True):
    """Start the kernel (steps 1–3 of the module docstring) and serve cells until shut down.

    Parameters
    ----------
    argv : list of str
        ipykernel's arguments (``-f CONNECTION_FILE``).
    layout : kinbook.classroom.sandbox.protocol.Layout
        Where the submission's copy and the temporary directory are.
    memory_mb : float
        What the notebook may allocate beyond the kernel's own footprint (its address-space cap).
    audit : bool
        Install the audit hook (False only when the grading process asks for it: the tests of what the
        operating-system sandbox holds on its own).

    The other limits (CPU time, file size, open files, processes) are set by the zygote before this runs.
    """
    root = os.path.realpath(os.environ["KINBOOK_SANDBOX_ROOT"])
    tmp = os.path.realpath(os.environ.get("KINBOOK_SANDBOX_TMP", root))
    os.chdir(root)
    # ipykernel read JPY_PARENT_PID when the zygote imported it: say which parent to watch (the zygote)
    options = ["--HistoryManager.enabled=False", "--IPKernelApp.quiet=False",
               f"--IPKernelApp.parent_handle={os.getppid()}"]
    from ipykernel.kernelapp import IPKernelApp  # optional dependency: ipykernel (the grading extra)

    app = IPKernelApp.instance()
    app.initialize(options + list(argv))
    try:
        app.shell.InteractiveTB.set_mode("Plain")  # cheap tracebacks: the grader reads only exception names
    except Exception:
        pass
    try:  # IPython 9 copies every write to stdout/stderr into the history's memory ("tee"): not here
        app.shell._tee = lambda channel: contextlib.nullcontext()
    except Exception:
        pass
    cap_output()
    read_roots = _read_roots()
    if memory_mb > 0:
        limit = _vm_bytes() + int(memory_mb * 1024 * 1024)
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    if audit:
        install_audit_hook((root, tmp), read_roots)
    app.start()
