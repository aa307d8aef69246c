"""Running a student's notebook: an operating-system sandbox (bubblewrap) around a kernel with its own fence.

The processes, outermost first:

* the grading process holds one :class:`Sandbox` (:mod:`.host`) and talks to it through pipes only; where the
  host offers one, it puts the sandbox into a control group of its own (:mod:`.cgroup`: the memory of all its
  processes together, its tasks, one CPU) before the sandbox runs anything;
* bubblewrap (:mod:`.bwrap`) builds the sandbox: its own user (uid 65534, unprivileged on the host too), pid,
  network, IPC and UTS namespaces; a read-only root with only the Python environment and kinbook; private
  size-capped tmpfs directories for the submission's copy, ``/tmp`` and the control files;
* the zygote (:mod:`.zygote`), the sandbox's pid 1, imports the libraries once and forks, for each submission,
  a worker (:mod:`.worker`: nbclient) and, over a launch channel made for that run, exactly one kernel
  (:mod:`.kernel`, through the launcher :mod:`.launch`) with the zygote's environment and the grading
  process's limits — without a control group, per-process limits and a seccomp filter that keeps it from forking
  (:mod:`.seccomp`) —, then kills them all and resets the directories before the next submission;
* the kernel caps its address space and installs an audit hook before any of the student's cells: an
  *advisory* fence (clear errors for ordinary attempts; native code can switch it off), never relied on.

What crosses the boundary: a job frame in (the cells, the answer names, the timeout, a copy of the submission)
and a result frame out (status, the answers as JSON data — read after every cell, so that a run stopped by a
later cell keeps them —, cell errors), bounded in size and validated by the grading process. The instructor's
source notebook never enters the sandbox; nothing the sandbox writes is read back.

Without bubblewrap (``Sandbox(isolation=False)``, ``kinbook grade --no-isolation``) the same processes run as
the grader's user, and the audit hook and the limits are the only fence.
"""

from .bwrap import IsolationUnavailable, available
from .host import STARTUP_SECONDS, Execution, Sandbox, SandboxError

__all__ = ["Sandbox", "Execution", "SandboxError", "IsolationUnavailable", "available", "STARTUP_SECONDS"]
