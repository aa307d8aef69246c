"""A control group per sandbox: the limits that hold for every process of a sandbox together.

The resource limits a kernel sets on itself (``RLIMIT_AS``, ``RLIMIT_CPU`` …) count per process: a student
who forks five children holds five budgets, and a limit that code in the sandbox sets is only as strong as the
code that sets it. A control group (cgroup) is counted and enforced by the host's kernel for the sandbox as a
whole, whatever runs inside: :class:`Cgroup` makes one per sandbox where the host offers one, and the grading
process puts the sandbox's first process into it before that process runs anything
(:meth:`Cgroup.join_in_child`, in the child between ``fork`` and ``exec``); every process forked inside
inherits it and none can leave (the sandbox has no write access to ``/sys/fs/cgroup``).

Where it is made (:func:`create`), in this order:

* **cgroup v2** — the unified hierarchy, when it has the ``memory`` and ``pids`` controllers for a directory
  this process can write: its own cgroup when the controllers are delegated there, else the hierarchy's root
  (as root); limits ``memory.max``, ``memory.swap.max`` (0), ``pids.max``, ``cpu.max``;
* **cgroup v1** — the per-controller hierarchies (``memory``, ``pids``, and ``cpu`` when present), below this
  process's own cgroup in each, where this process may create directories (as root on hosts that mount v1,
  e.g. a v1 host with an empty v2 hierarchy beside it); limits ``memory.limit_in_bytes`` (and
  ``memory.memsw.limit_in_bytes`` when swap is accounted), ``pids.max``, ``cpu.cfs_quota_us``.

When neither can be made (an unprivileged grader without delegation, no cgroup file system), :func:`create`
returns None with the reason, and the sandbox falls back to the resource limits its zygote sets on each kernel
before any student code, plus a seccomp filter that stops the kernel from forking (so that per-process limits
are not multiplied). :attr:`Cgroup.describe` / the sandbox's ``limits`` say which is in force; every result
records it.
"""

from __future__ import annotations

import itertools
import os
import signal
import time

__all__ = ["Cgroup", "create", "unavailable", "machine_memory_mb", "PIDS_MAX"]

#: Tasks (processes and threads) one sandbox may have: a run takes about 22 (bubblewrap, the zygote, the worker,
#: the launcher, the kernel and their threads); the rest is room for a notebook's own, not for a fork bomb — nor
#: for many processes each holding descriptors whose kernel buffers no memory limit counts.
PIDS_MAX = 64
#: One CPU per sandbox (quota per period, in microseconds).
CPU_PERIOD_US = 100_000
CPU_QUOTA_US = 100_000
_V1_CONTROLLERS = ("memory", "pids", "cpu")
_counter = itertools.count(1)


def _mounts():
    """[(mount point, fstype, super options)] of the cgroup file systems, from /proc/self/mountinfo."""
    out = []
    try:
        with open("/proc/self/mountinfo") as f:
            for line in f:
                left, _, right = line.partition(" - ")
                fields, tail = left.split(), right.split()
                if len(fields) > 4 and len(tail) >= 3 and tail[0] in ("cgroup", "cgroup2"):
                    out.append((fields[4].replace("\\040", " "), tail[0], set(tail[2].split(","))))
    except OSError:
        pass
    return out


def _own():
    """{controller or "": path} of this process's cgroups ("" for the unified hierarchy)."""
    out = {}
    try:
        with open("/proc/self/cgroup") as f:
            for line in f:
                _, controllers, path = line.rstrip("\n").split(":", 2)
                for c in controllers.split(",") if controllers else [""]:
                    out[c] = path
    except (OSError, ValueError):
        pass
    return out


def _read(path, default=""):
    try:
        with open(path) as f:
            return f.read()
    except OSError:
        return default


def _write(path, value):
    with open(path, "w") as f:
        f.write(str(value))


def machine_memory_mb():
    """The memory this grading process can have, in MB: the machine's (``MemTotal``), or less when its own
    control group is limited."""
    total = None
    for line in _read("/proc/meminfo").splitlines():
        if line.startswith("MemTotal:"):
            total = int(line.split()[1]) // 1024
    own = _own()
    for mount, fstype, options in _mounts():
        if fstype == "cgroup" and "memory" in options and "memory" in own:
            raw = _read(os.path.join(mount, own["memory"].lstrip("/"), "memory.limit_in_bytes")).strip()
        elif fstype == "cgroup2" and "" in own:
            raw = _read(os.path.join(mount, own[""].lstrip("/"), "memory.max")).strip()
        else:
            continue
        if raw.isdigit() and int(raw) < (1 << 60):
            limit = int(raw) // (1 << 20)
            total = limit if total is None else min(total, limit)
    return total


class Cgroup:
    """One sandbox's control group(s): ``dirs`` maps a controller (``memory``, ``pids``, ``cpu``; ``""`` for
    v2) to its directory."""

    def __init__(self, version, dirs):
        self.version = version
        self.dirs = dirs
        self._procs = []  # descriptors of cgroup.procs, opened before the fork (the child only writes)

    @property
    def describe(self):
        """What is in force, for the gradebook: ``cgroup v1 (memory, pids, cpu)``."""
        controllers = ["memory", "pids"] + (["cpu"] if self.version == "v2" or "cpu" in self.dirs else [])
        return f"cgroup {self.version} ({', '.join(controllers)})"

    # ---------------------------------------------------------------------------------------------- joining
    def prepare_join(self):
        """Open the ``cgroup.procs`` files the child writes to (:meth:`join_in_child`)."""
        self.close_join()
        for d in sorted(set(self.dirs.values())):
            self._procs.append(os.open(os.path.join(d, "cgroup.procs"), os.O_WRONLY | os.O_CLOEXEC))

    def join_in_child(self):
        """Between ``fork`` and ``exec`` (``preexec_fn``): move the calling process into the group(s). Writing
        "0" names the writer; only system calls, so that it is safe in a forked child."""
        for fd in self._procs:
            os.write(fd, b"0")

    def close_join(self):
        for fd in self._procs:
            try:
                os.close(fd)
            except OSError:
                pass
        self._procs = []

    # ---------------------------------------------------------------------------------------------- limits
    def _file(self, controller, v1, v2):
        return os.path.join(self.dirs[controller if self.version == "v1" else ""], v1 if self.version == "v1" else v2)

    def set_memory(self, limit):
        """Memory (bytes) of every process in the group together, page cache and tmpfs files included;
        swap is not allowed beyond it."""
        limit = int(limit)
        if self.version == "v2":
            _write(self._file("memory", "", "memory.max"), limit)
            try:
                _write(self._file("memory", "", "memory.swap.max"), 0)
            except OSError:
                pass
            return
        mem, memsw = self._file("memory", "memory.limit_in_bytes", ""), self._file("memory", "memory.memsw.limit_in_bytes", "")
        have_memsw = os.path.exists(memsw)
        # memsw (memory + swap) may never be below the memory limit: raise it first, lower it last
        if have_memsw:
            try:
                _write(memsw, max(limit, int(_read(mem, "0").strip() or 0)))
            except (OSError, ValueError):
                pass
        _write(mem, limit)
        if have_memsw:
            try:
                _write(memsw, limit)
            except OSError:
                pass

    def set_fixed_limits(self):
        """The limits that do not depend on the run: tasks and CPU."""
        _write(self._file("pids", "pids.max", "pids.max"), PIDS_MAX)
        if self.version == "v2":
            try:
                _write(self._file("cpu", "", "cpu.max"), f"{CPU_QUOTA_US} {CPU_PERIOD_US}")
            except OSError:
                pass
        elif "cpu" in self.dirs:
            try:
                _write(self._file("cpu", "cpu.cfs_period_us", ""), CPU_PERIOD_US)
                _write(self._file("cpu", "cpu.cfs_quota_us", ""), CPU_QUOTA_US)
            except OSError:
                pass

    def memory_usage(self):
        raw = _read(self._file("memory", "memory.usage_in_bytes", "memory.current")).strip()
        return int(raw) if raw.isdigit() else 0

    def oom_kills(self):
        """How many processes the kernel has killed in the group for want of memory (a counter)."""
        text = _read(self._file("memory", "memory.oom_control", "memory.events"))
        for line in text.splitlines():
            key, _, value = line.partition(" ")
            if key == "oom_kill" and value.strip().isdigit():
                return int(value)
        if self.version == "v1":  # kernels before 4.13 have no oom_kill line: failures to charge instead
            raw = _read(self._file("memory", "memory.failcnt", "")).strip()
            return int(raw) if raw.isdigit() else 0
        return 0

    def memory_events(self):
        """``(kills, hits)``: processes the out-of-memory killer stopped in the group (:meth:`oom_kills`), and how
        often its memory reached the limit (v2 ``memory.events`` ``max``, v1 ``memory.failcnt``) — counters of
        the kernel's, read before and after a run, so that a verdict of memory does not depend on the clock."""
        if self.version == "v2":
            hits = 0
            for line in _read(self._file("memory", "", "memory.events")).splitlines():
                key, _, value = line.partition(" ")
                if key == "max" and value.strip().isdigit():
                    hits = int(value)
        else:
            raw = _read(self._file("memory", "memory.failcnt", "")).strip()
            hits = int(raw) if raw.isdigit() else 0
        return self.oom_kills(), hits

    # -------------------------------------------------------------------------------------------- processes
    def pids(self):
        out = set()
        for d in set(self.dirs.values()):
            for word in _read(os.path.join(d, "cgroup.procs")).split():
                if word.isdigit():
                    out.add(int(word))
        return out

    def kill_all(self, wait=2.0):
        """SIGKILL every process in the group (v2: ``cgroup.kill``); True when none is left."""
        deadline = time.monotonic() + wait
        while True:
            left = self.pids()
            if not left:
                return True
            if self.version == "v2" and os.path.exists(os.path.join(self.dirs[""], "cgroup.kill")):
                try:
                    _write(os.path.join(self.dirs[""], "cgroup.kill"), 1)
                except OSError:
                    pass
            for pid in left:
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass
            if time.monotonic() > deadline:
                return False
            time.sleep(0.01)

    def remove(self):
        """Kill what is left and remove the directories (best effort: a directory still busy stays)."""
        self.close_join()
        self.kill_all()
        for d in sorted(set(self.dirs.values()), key=len, reverse=True):
            for _ in range(50):
                try:
                    os.rmdir(d)
                    break
                except FileNotFoundError:
                    break
                except OSError:
                    time.sleep(0.01)


def _alive(pid):
    try:
        os.kill(pid, 0)
        return True
    except ProcessLookupError:
        return False
    except OSError:
        return True


def _sweep(parent):
    """Remove the empty groups left by grading processes that were killed (``kinbook-PID-N`` of a dead PID)."""
    try:
        names = os.listdir(parent)
    except OSError:
        return
    for name in names:
        parts = name.split("-")
        if len(parts) == 3 and parts[0] == "kinbook" and parts[1].isdigit() and not _alive(int(parts[1])):
            try:
                os.rmdir(os.path.join(parent, name))
            except OSError:
                pass


def _make(parent, name):
    _sweep(parent)
    path = os.path.join(parent, name)
    os.mkdir(path, 0o755)
    return path


def _v2(mount, own):
    needed = {"memory", "pids"}
    candidates = []
    if "" in own:
        candidates.append(os.path.join(mount, own[""].lstrip("/")))
    candidates.append(mount)
    why = "cgroup v2: no directory with the memory and pids controllers that this process can write"
    for parent in candidates:
        if not os.access(parent, os.W_OK):
            continue
        available = set(_read(os.path.join(parent, "cgroup.controllers")).split())
        if not needed <= available:
            why = f"cgroup v2: the controllers {', '.join(sorted(needed - available))} are not available in {parent}"
            continue
        enabled = set(_read(os.path.join(parent, "cgroup.subtree_control")).split())
        wanted = (needed | ({"cpu"} & available)) - enabled
        try:
            if wanted:
                _write(os.path.join(parent, "cgroup.subtree_control"), " ".join("+" + c for c in sorted(wanted)))
            path = _make(parent, f"kinbook-{os.getpid()}-{next(_counter)}")
        except OSError as exc:
            why = f"cgroup v2: {parent}: {exc.strerror}"
            continue
        return Cgroup("v2", {"": path}), None
    return None, why


def _v1(mounts, own):
    where = {}
    for mount, fstype, options in mounts:
        if fstype == "cgroup":
            for c in _V1_CONTROLLERS:
                if c in options and c not in where:
                    where[c] = os.path.join(mount, own.get(c, "/").lstrip("/"))
    missing = [c for c in ("memory", "pids") if c not in where]
    if missing:
        return None, f"cgroup v1: no {' or '.join(missing)} hierarchy"
    name = f"kinbook-{os.getpid()}-{next(_counter)}"
    dirs = {}
    try:
        for c, parent in where.items():
            if c not in dirs:
                dirs[c] = _make(parent, name)
    except OSError as exc:
        if all(c in dirs for c in ("memory", "pids")):  # the cpu controller is optional
            return Cgroup("v1", dirs), None
        Cgroup("v1", dirs).remove()
        return None, f"cgroup v1: {exc.strerror} ({exc.filename})"
    return Cgroup("v1", dirs), None


def create():
    """A new control group for one sandbox: ``(Cgroup, None)``, or ``(None, reason)`` where the host offers
    none to this process."""
    if not os.path.isdir("/sys/fs/cgroup"):
        return None, "no cgroup file system (/sys/fs/cgroup)"
    mounts, own = _mounts(), _own()
    reasons = []
    for mount, fstype, _ in mounts:
        if fstype == "cgroup2":
            group, why = _v2(mount, own)
            if group is not None:
                return _ready(group)
            reasons.append(why)
            break
    if any(fstype == "cgroup" for _, fstype, _ in mounts):
        group, why = _v1(mounts, own)
        if group is not None:
            return _ready(group)
        reasons.append(why)
    return None, "; ".join(reasons) or "no cgroup hierarchy is mounted"


def _ready(group):
    try:
        group.set_fixed_limits()
    except OSError as exc:
        group.remove()
        return None, f"cgroup {group.version}: the limits cannot be set ({exc.strerror})"
    return group, None


def unavailable():
    """Why no cgroup can be made here (a sentence), or None when one can (made and removed again)."""
    group, why = create()
    if group is not None:
        group.remove()
    return why
