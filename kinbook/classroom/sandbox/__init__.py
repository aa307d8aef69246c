"""Running a student's notebook: an operating-system sandbox (bubblewrap) around a kernel with its own fence.

The processes, outermost first:

* the grading process holds one :class:`Sandbox` (:mod:`.host`) and talks to it through pipes only;
* bubblewrap (:mod:`.bwrap`) builds the sandbox: its own user (uid 65534, unprivileged on the host too), pid,
  network, IPC and UTS namespaces; a read-only root with only the Python environment and kinbook; private
  size-capped tmpfs directories for the submission's copy, ``/tmp`` and the control files;
* the zygote (:mod:`.zygote`), the sandbox's first process, imports the libraries once and forks, for each
  submission, a worker (:mod:`.worker`: nbclient) and a kernel (:mod:`.kernel`, started through the launcher
  :mod:`.launch`), then kills them all and empties the directories before the next submission;
* the kernel caps its own memory, CPU time, file sizes and processes and installs an audit hook before any
  of the student's cells: the second fence.

What crosses the boundary: a job frame in (the cells, the answer names, the limits, a copy of the submission)
and a result frame out (status, answers as JSON data, cell errors), bounded in size and validated by the
grading process. The instructor's source notebook never enters the sandbox; nothing the sandbox writes is read
back.

Without bubblewrap (``Sandbox(isolation=False)``, ``kinbook grade --no-isolation``) the same processes run as
the grader's user, and the audit hook and the limits are the only fence.
"""

from .bwrap import IsolationUnavailable, available
from .host import STARTUP_SECONDS, Execution, Sandbox, SandboxError

__all__ = ["Sandbox", "Execution", "SandboxError", "IsolationUnavailable", "available", "STARTUP_SECONDS"]
