"""The worker: runs one submission's notebook in the sandbox, with nbclient, in a kernel of its own.

Forked by the zygote (:mod:`.zygote`) for each run, inside the sandbox, with the run's launch channel, the
worker:

1. reads its job (the code cells to run, the answer names, the timeout, the files to put in the submission's
   directory — a copy of the submission) from the job descriptor, bounded;
2. starts a kernel through jupyter_client with a kernelspec whose command is the launcher (:mod:`.launch`),
   to which it hands the launch channel: the zygote forks the kernel (:mod:`.kernel`), which has its limits
   and the audit hook before any cell;
3. runs the cells — the kernel stopped by its CPU-time limit (``SIGXCPU``: the verdict ``timeout``), a notebook
   that waits instead of computing by a wall-clock backstop (kernel start-up not counted) — and, after each one,
   takes a
   *snapshot* of the named answers (a silent request whose reply carries them as JSON:
   :func:`kinbook.classroom.serialize.dumps`): when a later cell times out, runs out of memory or kills the
   kernel, the answers produced before it are still there to grade. Output is not kept (the grader reads
   answers, not output): only each cell's exception, if any;
4. writes one result frame (status, message, the failing cell, answers, cell errors) to the result descriptor
   and exits. (Before the first cell it writes a ``running`` frame there: a run that fails before it — a kernel
   that did not start — ran nothing of the submission, and the grading process tries it again.)

The worker runs as the student's kernel does (same user, same sandbox), so a student who got past the audit
hook could tamper with it: the grading process treats its result as untrusted, bounded data (:mod:`.host`),
and enforces the time limit itself.
"""

from __future__ import annotations

import ast
import json
import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

from .protocol import ANSWERS, MAX_JOB_BYTES, RUNNING, FrameError, read_frame, read_job, wall_seconds, write_frame

__all__ = ["main", "preload", "STARTUP_SECONDS", "MAX_ANSWER_CHARS", "SNAPSHOT_CHARS"]

#: Time allowed to start the kernel, not counted in the timeout.
STARTUP_SECONDS = 60.0
MAX_ANSWER_CHARS = 2_000_000
#: Characters of one snapshot of the answers read at most (the result frame's bound, less room for the rest).
SNAPSHOT_CHARS = 12 * 1024 * 1024
#: The worker's own address space beyond its size at start: twice the kernel's budget (a message the kernel
#: can build, decoded) and room for nbclient.
WORKER_EXTRA_MB = 1024
KERNEL_NAME = "kinbook-sandbox"


def preload():
    """The worker's imports (done once, in the zygote)."""
    import jupyter_client  # noqa: F401  (preloaded in the zygote: this function's purpose)
    import jupyter_client.kernelspec  # noqa: F401  (preloaded in the zygote: this function's purpose)
    import nbclient  # noqa: F401  (preloaded in the zygote: this function's purpose)
    import nbformat  # noqa: F401  (preloaded in the zygote: this function's purpose)


def _kernel_spec_dir(layout, channel_fd):
    d = Path(layout.work) / "kernels" / KERNEL_NAME
    d.mkdir(parents=True)
    # the launcher: standard library only, no site-packages (starts in milliseconds)
    launch = str(Path(__file__).with_name("launch.py"))
    argv = [sys.executable, "-I", "-S", launch, str(channel_fd), str(Path(layout.work) / "kernel.pid")]
    spec = {"argv": argv, "display_name": "kinbook sandbox", "language": "python"}
    (d / "kernel.json").write_text(json.dumps(spec))
    return Path(layout.work) / "kernels"


def _read_job(job_fd):
    cells, names, timeout, files, setup = read_job(*read_frame(job_fd, MAX_JOB_BYTES, timeout=60))
    return {"cells": cells, "names": names, "timeout": timeout, "setup": setup}, files


def _vm_bytes():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    return 0


def main(layout, job_fd, result_fd, channel_fd, limits):
    """The worker's whole life (see the module docstring)."""
    # a message the kernel builds within its budget, decoded here, must not take the worker down
    lim = _vm_bytes() + int((2 * limits["memory_mb"] + WORKER_EXTRA_MB) * 1024 * 1024)
    resource.setrlimit(resource.RLIMIT_AS, (lim, lim))
    try:
        job, files = _read_job(job_fd)
    except (FrameError, KeyError, TypeError, ValueError) as exc:
        write_frame(result_fd, {"status": "error", "message": f"the job could not be read: {exc}"[:300]})
        return
    finally:
        os.close(job_fd)
    for name, data in files.items():
        Path(layout.home, name).write_bytes(data)
    result = run(job, layout, channel_fd, started=lambda: write_frame(result_fd, {"status": RUNNING}),
                 answered=lambda answers, cell: write_frame(result_fd, {"status": ANSWERS, "cell": cell},
                                                            json.dumps(answers).encode()))
    write_frame(result_fd, result)


def _client_class():
    from nbclient import NotebookClient  # optional dependency: nbclient (the grading extra)

    class Client(NotebookClient):
        """nbclient, keeping of a cell's outputs only its exception."""

        def output(self, outs, msg, display_id, cell_index):
            if msg.get("msg_type") != "error":
                return None
            return super().output(outs, msg, display_id, cell_index)

    return Client


def run(job, layout, channel_fd, started=None, answered=None):
    """Run the job's code cells (``job["cells"]``: their sources) and read its answers;
    returns the result. ``started`` is called once the kernel is up, before the first cell is sent to it;
    ``answered(answers, cell)`` whenever the answers read after a cell changed, so that they reach the grading
    process before whatever may stop this worker (its memory, the sandbox's full directories, a kill)."""
    import nbformat  # optional dependency: nbformat (the grading extra)
    from jupyter_client import AsyncKernelManager  # optional dependency: jupyter_client (the grading extra)
    from jupyter_client.kernelspec import KernelSpecManager  # optional dependency: jupyter_client (the grading extra)
    from jupyter_core.utils import run_sync  # optional dependency: jupyter_core (the grading extra)

    # optional dependency: nbclient (the grading extra)
    from nbclient.exceptions import CellTimeoutError, DeadKernelError

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in job["cells"]])
    names = list(job["names"])
    ksm = KernelSpecManager(kernel_dirs=[str(_kernel_spec_dir(layout, channel_fd))])
    # the kernel's ZeroMQ sockets are Unix sockets in the run's own control directory, not TCP ports: ports chosen
    # here and bound by the kernel later could be taken meanwhile by any process of the host (without bubblewrap,
    # on a busy machine: the kernel then died before it answered kernel_info)
    km = AsyncKernelManager(kernel_name=KERNEL_NAME, kernel_spec_manager=ksm, transport="ipc",
                            ip=os.path.join(layout.work, "kernel"))
    km.connection_file = layout.connection_file
    timeout = float(job["timeout"])  # the kernel's CPU seconds (its RLIMIT_CPU, set by the zygote)
    wall = wall_seconds(timeout)       # the backstop for a notebook that waits instead of computing
    deadline = [None]
    late = f"the notebook did not finish within {wall:g} s (the wall-clock limit beside its {timeout:g} s of CPU time)"

    def left():
        return wall if deadline[0] is None else max(0.5, deadline[0] - time.monotonic())

    client = _client_class()(nb, km=km, timeout_func=lambda cell: left(), allow_errors=True,
                             startup_timeout=STARTUP_SECONDS, kernel_name=KERNEL_NAME, record_timing=False,
                             interrupt_on_timeout=False, shutdown_kernel="immediate")
    snapshot = _Snapshot(names)
    result = {"status": "error", "message": "", "answers": None, "errors": [], "cell": None}
    t_start = time.monotonic()
    try:
        # (the launcher's standard streams go nowhere: it is dumpable, so a process of the sandbox could reopen
        # them through /proc, and the worker's stderr is a pipe to the grading process)
        with client.setup_kernel(env=dict(os.environ), cwd=layout.home, pass_fds=(channel_fd,),
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL):
            os.close(channel_fd)  # the launcher holds it now; the kernel never does
            deadline[0] = time.monotonic() + wall
            index = -1
            if started is not None:
                started()  # no code of the submission has run before this
            if job.get("setup"):  # seeds and the reference's calls observed, before the first cell
                run_sync(snapshot.setup)(client, job["setup"], left())
            try:
                for index, cell in enumerate(nb.cells):
                    client.execute_cell(cell, index)
                    if _memory_error(cell):
                        result.update(status="memory", message="the notebook ran out of memory (MemoryError)",
                                      cell=index + 1)
                        break
                    before = snapshot.answers
                    if not run_sync(snapshot.take)(client, left(), index + 1):
                        result.update(status="timeout", message=late, cell=index + 1)
                        break
                    if answered is not None and snapshot.answers is not before:
                        answered(snapshot.answers, index + 1)
                else:
                    result["status"] = "ok"
            except CellTimeoutError:
                result.update(status="timeout", message=late, cell=index + 1)
            except DeadKernelError:
                result.update(_why_dead(km, nb, timeout), cell=index + 1)
    except Exception as exc:  # kernel failed to start, zmq trouble…
        result.update(status="error", message=f"the notebook could not be run: {type(exc).__name__}: {exc}"[:500])
    result["answers"] = snapshot.answers
    result["reference"] = snapshot.reference
    if result["status"] == "ok" and snapshot.answers is None:
        result.update(status="error", message="the answers could not be read" + (
            f" ({snapshot.problem})" if snapshot.problem else ""))
    result["errors"] = _cell_errors(nb)
    result["seconds"] = time.monotonic() - t_start
    return result


def _why_dead(km, nb, timeout):
    """The verdict on a kernel that died during a cell, from its exit: its CPU time used up, killed where the notebook
    ran out of memory, else an error (the grading process tells a kernel its control group killed for memory)."""
    code = km.provisioner.process.poll() if getattr(km, "provisioner", None) else None
    if code is not None and code < 0 and -code == signal.SIGXCPU:
        return {"status": "timeout", "message": f"the notebook used up its CPU time ({timeout:g} s)"}
    if code is not None and code < 0 and -code == signal.SIGKILL and _memory_errors(nb):
        return {"status": "memory", "message": "the notebook ran out of memory"}
    return {"status": "error", "message": f"the kernel died (exit code {code})", "exit": code}


class _Snapshot:
    """The named answers as they stand after each cell (the last good reading is kept), and which of them are the
    very results of the reference's calls (:mod:`.trace`)."""

    def __init__(self, names):
        self.expression = (f"__import__('kinbook.classroom.serialize', fromlist=['dumps']).dumps({names!r}, "
                           "get_ipython().user_ns)")
        self.trace = (f"__import__('kinbook.classroom.sandbox.trace', fromlist=['report']).report({names!r}, "
                      "get_ipython().user_ns, {cell})")
        self.names = list(names)
        self.text = None
        self.answers = None
        self.problem = ""
        self.reference = {}

    async def setup(self, client, setup, timeout):
        """Have the kernel seed its generators and observe the reference's calls (:func:`.trace.setup`)."""
        code = (f"__import__('kinbook.classroom.sandbox.trace', fromlist=['setup']).setup({int(setup['seed'])!r}, "
                f"{list(setup['functions'])!r}, {list(setup['methods'])!r})")
        return await self._ask(client, code, {}, timeout) is not None

    async def take(self, client, timeout, cell=0):
        """Ask the kernel for the answers after code cell ``cell``; False when no reply came within ``timeout``
        seconds."""
        trace = self.trace.replace("{cell}", str(int(cell)))
        reply = await self._ask(client, "", {"kinbook": self.expression, "trace": trace}, timeout)
        if reply is None:
            return False
        found = reply.get("content", {}).get("user_expressions", {})
        self._read(found.get("kinbook", {}))
        self._read_trace(found.get("trace", {}))
        return True

    async def _ask(self, client, code, expressions, timeout):
        kc = client.kc
        msg_id = kc.execute(code, silent=True, store_history=False, user_expressions=expressions)
        end = time.monotonic() + timeout
        while True:
            remaining = end - time.monotonic()
            if remaining <= 0:
                return None
            try:
                reply = await kc.get_shell_msg(timeout=remaining)
            except Exception:  # queue.Empty (timeout), a dead kernel
                return None
            if reply.get("parent_header", {}).get("msg_id") == msg_id:
                return reply

    def _read_trace(self, value):
        text = value.get("data", {}).get("text/plain") if value.get("status") == "ok" else None
        if not isinstance(text, str) or len(text) > 64 * 1024:
            return
        try:
            found = json.loads(ast.literal_eval(text))
        except (ValueError, SyntaxError, MemoryError, RecursionError):
            return
        if isinstance(found, dict):
            self.reference = {}  # as the answers stand now
            for name in self.names:
                entries = found.get(name)
                entries = [[e[0][:200], e[1], e[2]] for e in (entries if isinstance(entries, list) else [])[:4]
                           if isinstance(e, list) and len(e) == 3 and isinstance(e[0], str) and isinstance(e[1], int)
                           and e[2] in (0, 1)]
                if entries:
                    self.reference[name] = entries

    def _read(self, value):
        if value.get("status") != "ok":
            self.problem = f"{str(value.get('ename'))[:100]}: {str(value.get('evalue'))[:300]}"
            return
        text = value.get("data", {}).get("text/plain")
        if not isinstance(text, str) or len(text) > SNAPSHOT_CHARS or text == self.text:
            return
        self.text = text
        try:
            answers = json.loads(ast.literal_eval(text))["answers"]
            for name, rec in list(answers.items()):  # the grader never reads more than this
                if len(json.dumps(rec)) > MAX_ANSWER_CHARS:
                    answers[name] = {"kind": "unsupported", "type": "an answer larger than "
                                     f"{MAX_ANSWER_CHARS // 10**6} MB"}
            self.answers = answers
        except (ValueError, KeyError, TypeError, SyntaxError, MemoryError, RecursionError):
            self.problem = "the answers could not be read"


def _cell_errors(nb):
    errors = []
    for i, cell in enumerate(nb.cells):
        for o in cell.get("outputs", []):
            if o.get("output_type") == "error":
                errors.append({"cell": i + 1, "ename": str(o.get("ename"))[:100], "evalue": str(o.get("evalue"))[:300]})
    return errors


def _memory_error(cell):
    return any(o.get("output_type") == "error" and o.get("ename") == "MemoryError" for o in cell.get("outputs", []))


def _memory_errors(nb):
    return any(e["ename"] == "MemoryError" for e in _cell_errors(nb))
