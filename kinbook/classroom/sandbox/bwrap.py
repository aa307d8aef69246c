"""bubblewrap: whether it works here, and the command that starts a sandbox with it.

bubblewrap (``bwrap``, Debian package ``bubblewrap``; the tool Flatpak uses) builds the sandbox from Linux
namespaces. :func:`command` asks it for:

* a new user namespace with one user, uid/gid 65534 inside, no capabilities, no further user namespaces
  (``--disable-userns``), ``PR_SET_NO_NEW_PRIVS``;
* new pid, network (nothing but a down loopback), IPC, UTS and cgroup namespaces, a new session
  (``--new-session``: no terminal to inject input into), death with its parent (``--die-with-parent``); the
  command runs as the sandbox's pid 1 (``--as-pid-1``): bubblewrap keeps no init of its own inside, which held
  descriptors of the grading process and which no reset could kill;
* a root that is an empty read-only tmpfs holding only: ``/usr`` and the top-level links into it, the Python
  installation, the virtual environment and the kinbook package — all read-only, at their own paths (the
  rest of a checkout, the instructor's files, ``collected/`` and ``graded/`` simply do not exist there) —,
  a new ``/proc`` (its own processes only), a minimal read-only ``/dev``, and three size-capped tmpfs
  directories (:data:`kinbook.classroom.sandbox.protocol.ISOLATED`): the submission's copy, ``/tmp`` and
  the worker's control directory;
* an empty environment plus the few variables of :data:`ENV`;
* a seccomp filter (built with libseccomp, the library Flatpak and systemd use) refusing, with ``EPERM``, the
  system calls a notebook has no use for and that reach the host's kernel state or other processes:
  :data:`DENIED_SYSCALLS` (keyrings — shared by every sandbox of the same uid —, ptrace, cross-process
  memory and descriptors, BPF, perf, io_uring, userfaultfd, mounts and namespaces, modules, IPC objects that
  would outlive a run, and memory files, which no limit counts). Where libseccomp cannot be loaded
  the sandbox runs without it (:func:`seccomp_program` returns None).

The sandbox's user must be unprivileged *on the host* too. Run as root, bubblewrap would map uid 65534
inside to root outside (root's file permissions on what is visible, no ``RLIMIT_NPROC``), so the grading
process, when it is root, starts bubblewrap as user 65534 (``setpriv``, util-linux). Directories that user
cannot traverse on the host (a Python under ``/root``) are first made reachable by an outer bubblewrap, run
as root with only a private mount and pid namespace, that replaces the blocking directory by a tmpfs holding
just the directories needed (nothing of the host changes).
"""

from __future__ import annotations

import functools
import os
import shutil
import stat
import subprocess
import sys

import kinbook

from ...errors import GradingError
from .protocol import ISOLATED, THREAD_ENV
from .seccomp import sandbox_program

__all__ = ["IsolationUnavailable", "check", "command", "readonly_dirs", "seccomp_program", "PACKAGE", "SANDBOX_UID",
           "ENV", "DENIED_SYSCALLS"]

PACKAGE = "bubblewrap"
SANDBOX_UID = 65534
MIN_VERSION = (0, 8, 0)
#: tmpfs sizes (bytes): the submission's copy, /tmp, the control directory
SIZES = {ISOLATED.home: 256 << 20, ISOLATED.tmp: 256 << 20, "/run/kinbook": 32 << 20}
ENV = {
    "PATH": "/usr/local/bin:/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": ISOLATED.home, "TMPDIR": ISOLATED.tmp,
    "USER": "student", "LOGNAME": "student", "PYTHONDONTWRITEBYTECODE": "1", "MALLOC_ARENA_MAX": "2",
    "MPLBACKEND": "Agg", "MPLCONFIGDIR": ISOLATED.tmp + "/.matplotlib", "PYDEVD_DISABLE_FILE_VALIDATION": "1",
    **THREAD_ENV,
}
#: The only ``PATH`` bubblewrap (and ``setpriv``) are started with: never the grader's own, which its processes
#: would otherwise carry, readable in the sandbox's ``/proc``. (``bwrap`` itself is found on the grader's PATH,
#: as a shell would find it.)
SYSTEM_PATH = "/usr/sbin:/usr/bin:/sbin:/bin"
_TOP_LINKS = ("/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32")
DENIED_SYSCALLS = (
    "keyctl", "add_key", "request_key", "ptrace", "process_vm_readv", "process_vm_writev", "kcmp",
    "perf_event_open", "bpf", "userfaultfd", "io_uring_setup", "io_uring_enter", "io_uring_register",
    "mount", "umount2", "pivot_root", "move_mount", "open_tree", "fsopen", "fsmount", "fspick", "setns", "unshare",
    "open_by_handle_at", "name_to_handle_at", "init_module", "finit_module", "delete_module", "kexec_load",
    "kexec_file_load", "swapon", "swapoff", "reboot", "acct", "quotactl", "syslog", "lookup_dcookie",
    # IPC objects outlive their processes in the sandbox's IPC namespace: one run could leave data for the next
    "mq_open", "mq_unlink", "mq_timedsend", "mq_timedreceive", "mq_notify", "mq_getsetattr", "msgget", "shmget",
    "semget",
    # another process's descriptors, copied without any permission check on what they point to (bubblewrap's init
    # holds descriptors of the grading process), and another process's memory advice
    "pidfd_getfd", "process_madvise",
    # memory in no address space and no size-capped directory: a file descriptor each, outside every limit
    "memfd_create", "memfd_secret",
)


def seccomp_program():
    """The seccomp filter of the sandbox, as BPF bytes for ``bwrap --seccomp``: every call of
    :data:`DENIED_SYSCALLS` fails with ``EPERM``, the rest is allowed. None without libseccomp."""
    return sandbox_program(DENIED_SYSCALLS)


def seccomp_fd():
    """A descriptor holding :func:`seccomp_program` (for ``--seccomp``), or None; the caller closes it."""
    program = seccomp_program()
    if program is None:
        return None
    fd = os.memfd_create("kinbook-seccomp")
    os.write(fd, program)
    os.lseek(fd, 0, os.SEEK_SET)
    return fd


class IsolationUnavailable(GradingError):
    """bubblewrap is missing, too old, or cannot create the sandbox's namespaces on this host."""


def readonly_dirs():
    """The host directories the sandbox sees read-only: the Python installation, the environment's
    site-packages and the kinbook package (never the rest of a checkout it was installed from)."""
    found = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix,
             os.path.dirname(os.path.realpath(sys.executable)),
             os.path.dirname(os.path.abspath(kinbook.__file__))}
    found |= {p for p in sys.path if p and os.path.isdir(p) and ("site-packages" in p or "dist-packages" in p)}
    found |= {os.path.realpath(p) for p in found}
    found = {os.path.abspath(p) for p in found if os.path.isdir(p) and p != "/"}
    if os.path.isdir("/usr"):
        found.add("/usr")
    out = []
    for p in sorted(found, key=len):  # drop directories already inside another one
        if not any(p == q or p.startswith(q.rstrip("/") + "/") for q in out):
            out.append(p)
    return sorted(out)


def _which(name):
    return shutil.which(name)


def _traversable(st, uid):
    mode = st.st_mode
    return bool(mode & stat.S_IXOTH or (st.st_uid == uid and mode & stat.S_IXUSR)
                or (st.st_gid == uid and mode & stat.S_IXGRP))


def _blocked(dirs, uid):
    """{blocking ancestor: [dirs below it]} for the directories that user ``uid`` cannot reach on the host."""
    out = {}
    for d in dirs:
        parts = d.strip("/").split("/")
        for i in range(1, len(parts)):
            a = "/" + "/".join(parts[:i])
            if not _traversable(os.stat(a), uid):
                out.setdefault(a, []).append(d)
                break
    return out


def _outer(blocked):
    """An outer bubblewrap (run as root, a mount namespace only) in which every blocking directory is a tmpfs
    holding the needed directories below it, so that an unprivileged user can reach them."""
    args = ["--dev-bind", "/", "/"]
    for a, below in sorted(blocked.items()):
        args += ["--tmpfs", a]
        made = set()
        for d in below:
            rel = d[len(a):].strip("/").split("/")
            for i in range(1, len(rel)):
                p = a + "/" + "/".join(rel[:i])
                if p not in made:
                    args += ["--perms", "0755", "--dir", p]
                    made.add(p)
            args += ["--ro-bind", d, d]
    # its own pid namespace: when it dies, the kernel kills everything below it (setpriv's change of user
    # clears the parent-death signal of what it runs, so --die-with-parent alone would not reach that far)
    return [_which("bwrap")] + args + ["--unshare-pid", "--die-with-parent", "--"]


def command(argv, env=None, seccomp=None):
    """The command that runs ``argv`` (a program visible in the sandbox, with its arguments) in a new sandbox.

    Parameters
    ----------
    argv : list of str
    env : dict, optional
        Extra environment variables inside (beyond :data:`ENV`).
    seccomp : int, optional
        A descriptor holding the seccomp filter (:func:`seccomp_fd`), passed to the new process.

    Returns
    -------
    list of str
        To be started with a minimal environment, ``cwd="/"``, in a new session (see
        :class:`kinbook.classroom.sandbox.host.Sandbox`).
    """
    bwrap = _which("bwrap")
    ro = readonly_dirs()
    inner = [bwrap, "--unshare-all", "--unshare-user", "--disable-userns", "--uid", str(SANDBOX_UID),
             "--gid", str(SANDBOX_UID), "--hostname", "sandbox", "--die-with-parent", "--new-session", "--as-pid-1", "--clearenv"]
    for k, v in {**ENV, **(env or {})}.items():
        inner += ["--setenv", k, v]
    for top in _TOP_LINKS:
        if os.path.islink(top):
            inner += ["--symlink", os.readlink(top), top]
        elif os.path.isdir(top) and top not in ro:
            inner += ["--ro-bind", top, top]
    # bubblewrap mounts in argument order: a directory below one of the private tmpfs directories (a checkout
    # and its venv cloned under /tmp) is bound after that tmpfs, which would otherwise hide it
    def below_private(d):
        return any(d.startswith(path.rstrip("/") + "/") for path in SIZES)

    for d in ro:
        if not below_private(d):
            inner += ["--ro-bind", d, d]
    inner += ["--proc", "/proc", "--dev", "/dev"]
    for path, size in SIZES.items():
        inner += ["--size", str(size), "--perms", "0700", "--tmpfs", path]
    for d in ro:
        if below_private(d):
            inner += ["--ro-bind", d, d]
    inner += ["--remount-ro", "/dev", "--remount-ro", "/", "--chdir", ISOLATED.home]
    if seccomp is not None:
        inner += ["--seccomp", str(seccomp)]
    inner += ["--"] + list(argv)
    if os.geteuid() != 0:
        return inner  # bubblewrap runs as this (unprivileged) user; 65534 inside maps to it
    drop = [_which("setpriv") or "setpriv", f"--reuid={SANDBOX_UID}", f"--regid={SANDBOX_UID}",
            "--clear-groups", "--inh-caps=-all", "--bounding-set=-all", "--"]
    blocked = _blocked(ro, SANDBOX_UID)
    return (_outer(blocked) if blocked else []) + drop + inner


def _version(bwrap):
    try:
        out = subprocess.run([bwrap, "--version"], capture_output=True, text=True, timeout=10).stdout
        return tuple(int(x) for x in out.split()[-1].split(".")[:3])
    except (OSError, ValueError, IndexError, subprocess.TimeoutExpired):
        return None


@functools.lru_cache(maxsize=None)
def _probe():
    """None when a sandbox can be started here, else why not (a sentence)."""
    if not sys.platform.startswith("linux"):
        return f"{sys.platform} has no Linux namespaces"
    bwrap = _which("bwrap")
    if bwrap is None:
        return "bubblewrap (`bwrap`) is not installed"
    version = _version(bwrap)
    if version is None or version < MIN_VERSION:
        found = ".".join(map(str, version)) if version else "an unreadable version"
        return f"bubblewrap {'.'.join(map(str, MIN_VERSION))} or newer is needed (found {found})"
    if os.geteuid() == 0 and _which("setpriv") is None:
        return "`setpriv` (Debian package util-linux) is needed to run bubblewrap as an unprivileged user"
    probe = "import sys, os; sys.stdout.write(str(os.getuid()))"
    try:
        res = subprocess.run(command([sys.executable, "-I", "-S", "-c", probe]), capture_output=True, text=True,
                             timeout=60, cwd="/", env={"PATH": SYSTEM_PATH},
                             stdin=subprocess.DEVNULL)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"bubblewrap could not be run: {exc}"
    if res.returncode != 0 or res.stdout.strip() != str(SANDBOX_UID):
        why = (res.stderr.strip().splitlines() or ["no message"])[-1][:300]
        return f"bubblewrap cannot create the sandbox here ({why})"
    return None


def check():
    """Raise :class:`IsolationUnavailable` (with what to install or enable) when no sandbox can be started here."""
    why = _probe()
    if why is not None:
        raise IsolationUnavailable(
            f"grading needs an operating-system sandbox, and {why}. Install the Debian/Ubuntu package "
            f"`{PACKAGE}` (apt-get install {PACKAGE}; Fedora: dnf install {PACKAGE}) on a Linux host with user "
            "namespaces enabled (sysctl kernel.unprivileged_userns_clone=1 / user.max_user_namespaces > 0), or "
            "pass --no-isolation to grade with the in-process fence only (students' code then runs as your user; "
            "see docs/instructors.md)")


def available():
    """Whether :func:`check` passes."""
    return _probe() is None
