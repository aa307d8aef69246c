"""seccomp filters, built with libseccomp (the library Flatpak, systemd and bubblewrap's users build theirs with).

Two filters:

* :func:`sandbox_program` — the whole sandbox's, given to ``bwrap --seccomp``: the system calls of
  :data:`kinbook.classroom.sandbox.bwrap.DENIED_SYSCALLS` fail with ``EPERM``;
* :class:`NoFork` — loaded by the zygote into each kernel it forks when no control group holds the sandbox's
  processes together (:mod:`.cgroup`): the kernel may start threads but no process (``clone`` without
  ``CLONE_THREAD``, ``fork``, ``vfork`` fail with ``EPERM``; ``clone3``, whose flags a filter cannot read, fails
  with ``ENOSYS``, on which the C library starts its threads with ``clone``). Per-process limits then cannot be
  multiplied by forking.

Where libseccomp cannot be loaded, both are None: the sandbox runs without them, and says so.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import errno
import functools
import os

__all__ = ["sandbox_program", "NoFork"]

_ALLOW = 0x7FFF0000
_EPERM = 0x00050000 | errno.EPERM
_ENOSYS = 0x00050000 | errno.ENOSYS
_MASKED_EQ = 7          # SCMP_CMP_MASKED_EQ
_CLONE_THREAD = 0x00010000


class _ArgCmp(ctypes.Structure):
    _fields_ = [("arg", ctypes.c_uint), ("op", ctypes.c_int), ("datum_a", ctypes.c_uint64),
                ("datum_b", ctypes.c_uint64)]


@functools.lru_cache(maxsize=None)
def _lib():
    try:
        lib = ctypes.CDLL(ctypes.util.find_library("seccomp") or "libseccomp.so.2")
    except OSError:
        return None
    lib.seccomp_init.restype = ctypes.c_void_p
    lib.seccomp_init.argtypes = [ctypes.c_uint32]
    lib.seccomp_rule_add_array.argtypes = [ctypes.c_void_p, ctypes.c_uint32, ctypes.c_int, ctypes.c_uint,
                                           ctypes.POINTER(_ArgCmp)]
    lib.seccomp_syscall_resolve_name.argtypes = [ctypes.c_char_p]
    lib.seccomp_export_bpf.argtypes = [ctypes.c_void_p, ctypes.c_int]
    lib.seccomp_load.argtypes = [ctypes.c_void_p]
    lib.seccomp_release.argtypes = [ctypes.c_void_p]
    return lib


def _context(rules):
    """A libseccomp context (default: allow) with ``rules``: [(syscall name, action, [(arg, mask, value)])];
    None when libseccomp is missing or refuses a rule. Names this architecture does not have are skipped."""
    lib = _lib()
    if lib is None:
        return None
    ctx = lib.seccomp_init(_ALLOW)
    if not ctx:
        return None
    for name, action, conditions in rules:
        nr = lib.seccomp_syscall_resolve_name(name.encode())
        if nr < 0:
            continue
        args = (_ArgCmp * max(1, len(conditions)))(*[_ArgCmp(a, _MASKED_EQ, m, v) for a, m, v in conditions])
        if lib.seccomp_rule_add_array(ctx, action, nr, len(conditions), args) != 0:
            lib.seccomp_release(ctx)
            return None
    return ctx


@functools.lru_cache(maxsize=None)
def sandbox_program(denied):
    """BPF bytes refusing (``EPERM``) every system call named in ``denied`` (a tuple), or None."""
    ctx = _context([(name, _EPERM, []) for name in denied])
    if ctx is None:
        return None
    lib = _lib()
    try:
        fd = os.memfd_create("kinbook-seccomp")
        try:
            if lib.seccomp_export_bpf(ctx, fd) != 0:
                return None
            os.lseek(fd, 0, os.SEEK_SET)
            return os.read(fd, 1 << 20)
        finally:
            os.close(fd)
    finally:
        lib.seccomp_release(ctx)


class NoFork:
    """The no-process filter, built once (in the zygote) and loaded into each kernel (:meth:`load`, in the
    forked child, before any student code)."""

    RULES = (("clone", _EPERM, [(0, _CLONE_THREAD, 0)]), ("fork", _EPERM, []), ("vfork", _EPERM, []),
             ("clone3", _ENOSYS, []))

    def __init__(self):
        self.ctx = _context(self.RULES)

    @property
    def available(self):
        return self.ctx is not None

    def load(self):
        """Install the filter on the calling process (and its future threads); also sets no_new_privs."""
        if self.ctx is None or _lib().seccomp_load(self.ctx) != 0:
            raise OSError("the no-fork seccomp filter could not be loaded")
