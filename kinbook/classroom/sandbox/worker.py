"""The worker: runs one submission's notebook in the sandbox, with nbclient, in a kernel of its own.

Forked by the zygote (:mod:`.zygote`) for each run, inside the sandbox, the worker:

1. reads its job (the code cells to run, the answer names, the limits, the files to put in the submission's
   directory — a copy of the submission) from the job descriptor, bounded;
2. starts a kernel through jupyter_client with a kernelspec whose command is the launcher (:mod:`.launch`):
   the zygote forks the kernel (:mod:`.kernel`), which caps its resources and installs the audit hook before
   any cell;
3. runs the cells with the wall-clock timeout (kernel start-up not counted) and, after the student's cells,
   one cell it appends that prints the named answers as JSON between two random markers
   (:func:`kinbook.classroom.serialize.dumps`); only that cell's output is read;
4. writes one result frame (status, message, answers, cell errors) to the result descriptor and exits.

The worker runs as the student's kernel does (same user, same sandbox), so a student who got past the audit
hook could tamper with it: the grading process treats its result as untrusted, bounded data
(:mod:`.host`), and enforces the time limit itself.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import time
from pathlib import Path

from .protocol import MAX_JOB_BYTES, FrameError, read_frame, write_frame

__all__ = ["main", "preload", "STARTUP_SECONDS", "WORKER_MEMORY_MB", "MAX_OUTPUT_CHARS"]

#: Time allowed to start the kernel, not counted in the timeout.
STARTUP_SECONDS = 60.0
WORKER_MEMORY_MB = 3000
MAX_OUTPUT_CHARS = 5_000_000
MAX_ANSWER_CHARS = 2_000_000
KERNEL_NAME = "kinbook-sandbox"


def preload():
    """The worker's imports (done once, in the zygote)."""
    import jupyter_client  # noqa: F401
    import jupyter_client.kernelspec  # noqa: F401
    import nbclient  # noqa: F401
    import nbformat  # noqa: F401


def _kernel_spec_dir(layout):
    d = Path(layout.work) / "kernels" / KERNEL_NAME
    d.mkdir(parents=True)
    # the launcher: standard library only, no site-packages (starts in milliseconds)
    launch = str(Path(__file__).with_name("launch.py"))
    argv = [sys.executable, "-I", "-S", launch, layout.socket, str(Path(layout.work) / "kernel.pid")]
    spec = {"argv": argv + ["-f", "{connection_file}"], "display_name": "kinbook sandbox", "language": "python"}
    (d / "kernel.json").write_text(json.dumps(spec))
    return Path(layout.work) / "kernels"


def kernel_env(job, layout):
    """The kernel's environment: the sandbox's own (never the grader's), its directories and limits."""
    env = dict(os.environ)
    env.update({"HOME": layout.home, "TMPDIR": layout.tmp, "IPYTHONDIR": str(Path(layout.tmp) / ".ipython"),
                "MPLCONFIGDIR": str(Path(layout.tmp) / ".matplotlib"), "JUPYTER_RUNTIME_DIR": layout.work,
                "KINBOOK_SANDBOX_ROOT": layout.home, "KINBOOK_SANDBOX_TMP": layout.tmp,
                "KINBOOK_SANDBOX_MEMORY_MB": str(float(job["memory_mb"])),
                "KINBOOK_SANDBOX_AUDIT": "0" if job.get("audit_hook") is False else "1",
                "KINBOOK_SANDBOX_CPU_S": str(int(float(job["timeout"]) * 2 + 30))})
    return env


def _read_job(job_fd):
    header, payload = read_frame(job_fd, MAX_JOB_BYTES, timeout=60)
    files, offset = {}, 0
    for name, size in header.pop("files"):
        files[os.path.basename(str(name)) or "file"] = payload[offset:offset + int(size)]
        offset += int(size)
    return header, files


def main(layout, job_fd, result_fd):
    """The worker's whole life (see the module docstring)."""
    import resource

    lim = WORKER_MEMORY_MB * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (lim, lim))  # a flood of output cannot take the worker down
    try:
        job, files = _read_job(job_fd)
    except (FrameError, KeyError, TypeError, ValueError) as exc:
        write_frame(result_fd, {"status": "error", "message": f"the job could not be read: {exc}"[:300]})
        return
    finally:
        os.close(job_fd)
    for name, data in files.items():
        Path(layout.home, name).write_bytes(data)
    result = run(job, layout)
    write_frame(result_fd, result)


def run(job, layout):
    """Run the job's notebook (``job["notebook"]``: nbformat JSON) and read its answers; returns the result."""
    import nbformat
    from jupyter_client import AsyncKernelManager
    from jupyter_client.kernelspec import KernelSpecManager
    from nbclient import NotebookClient
    from nbclient.exceptions import CellTimeoutError, DeadKernelError

    nb = nbformat.reads(job["notebook"], as_version=4)
    nonce = job["nonce"]
    extract = nbformat.v4.new_code_cell(
        "from kinbook.classroom.serialize import dumps as _kb_dumps\n"
        f"print({nonce!r} + _kb_dumps({list(job['names'])!r}, get_ipython().user_ns) + {nonce!r})"
    )
    nb.cells.append(extract)
    ksm = KernelSpecManager(kernel_dirs=[str(_kernel_spec_dir(layout))])
    km = AsyncKernelManager(kernel_name=KERNEL_NAME, kernel_spec_manager=ksm)
    km.connection_file = str(Path(layout.work) / "connection.json")
    timeout = float(job["timeout"])
    deadline = [None]

    def cell_timeout(cell):
        if deadline[0] is None:
            return timeout
        return max(0.5, deadline[0] - time.monotonic())

    client = NotebookClient(nb, km=km, timeout_func=cell_timeout, allow_errors=True, startup_timeout=STARTUP_SECONDS,
                            kernel_name=KERNEL_NAME, record_timing=False, interrupt_on_timeout=False,
                            shutdown_kernel="immediate")
    result = {"status": "error", "message": "", "answers": None, "errors": []}
    t_start = time.monotonic()
    try:
        with client.setup_kernel(env=kernel_env(job, layout), cwd=layout.home):
            deadline[0] = time.monotonic() + timeout
            try:
                for index, cell in enumerate(nb.cells):
                    if cell.cell_type != "code":
                        continue
                    client.execute_cell(cell, index)
                    if _memory_errors_in(cell):
                        raise _OutOfMemory()
                    if index < len(nb.cells) - 1 and sum(len(_output_text(c)) for c in nb.cells) > MAX_OUTPUT_CHARS:
                        for c in nb.cells[:-1]:
                            c.outputs = []
            except _OutOfMemory:
                result.update(status="memory", message="the notebook ran out of memory (MemoryError); it was stopped "
                              "at that cell")
            except CellTimeoutError:
                result.update(status="timeout", message=f"the notebook did not finish within {timeout:g} s")
            except DeadKernelError:
                code = km.provisioner.process.poll() if getattr(km, "provisioner", None) else None
                if code is not None and code < 0 and -code == signal.SIGXCPU:
                    result.update(status="timeout", message="the notebook used up its CPU time")
                elif code is not None and code < 0 and -code == signal.SIGKILL and _memory_errors(nb):
                    result.update(status="memory", message="the notebook ran out of memory")
                else:
                    result.update(status="error", message=f"the kernel died (exit code {code}): the notebook exited "
                                  "or killed its own process before its answers could be read")
            else:
                text = _output_text(nb.cells[-1])  # only the appended cell's own output is read
                a, b = text.find(nonce), text.rfind(nonce)
                if a >= 0 and b > a:
                    try:
                        answers = json.loads(text[a + len(nonce):b])["answers"]
                        for name, rec in list(answers.items()):  # the grader never reads more than this
                            if len(json.dumps(rec)) > MAX_ANSWER_CHARS:
                                answers[name] = {"kind": "unsupported", "type": "an answer larger than "
                                                 f"{MAX_ANSWER_CHARS // 10**6} MB"}
                        result["answers"] = answers
                        result["status"] = "ok"
                    except (ValueError, KeyError, TypeError):
                        result["message"] = "the answers could not be read"
                else:
                    err = _cell_errors(nb)[-1:] if _cell_errors(nb) else []
                    result["message"] = "the answers could not be read" + (
                        f" ({err[0]['ename']}: {err[0]['evalue']})" if err and err[0]["cell"] == len(nb.cells) else "")
    except Exception as exc:  # kernel failed to start, zmq trouble…
        result.update(status="error", message=f"the notebook could not be run: {type(exc).__name__}: {exc}"[:500])
    result["errors"] = [e for e in _cell_errors(nb) if e["cell"] < len(nb.cells)]
    if result["status"] in ("ok", "error") and _memory_errors(nb):
        result.update(status="memory", message="the notebook ran out of memory (MemoryError)")
    result["seconds"] = time.monotonic() - t_start
    return result


def _output_text(cell):
    out = []
    for o in cell.get("outputs", []):
        if o.get("output_type") == "stream" and o.get("name") == "stdout":
            out.append(o.get("text", ""))
    return "".join(out)


def _cell_errors(nb):
    errors = []
    for i, cell in enumerate(nb.cells):
        for o in cell.get("outputs", []):
            if o.get("output_type") == "error":
                errors.append({"cell": i + 1, "ename": str(o.get("ename"))[:100], "evalue": str(o.get("evalue"))[:300]})
    return errors


class _OutOfMemory(Exception):
    pass


def _memory_errors_in(cell):
    return any(o.get("output_type") == "error" and o.get("ename") == "MemoryError" for o in cell.get("outputs", []))


def _memory_errors(nb):
    return any(e["ename"] == "MemoryError" for e in _cell_errors(nb))

