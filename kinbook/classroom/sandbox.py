"""Running one submitted notebook in isolation.

:func:`execute` is called by the grader for each submission:

1. a fresh temporary directory (the *sandbox root*) receives a copy of the submission — the student's code
   sees nothing else of the grader's files; a second, private directory (the *control* directory) holds
   the notebook to run, the kernel's connection file and the result;
2. a worker process (``python sandbox.py CONTROL``, its own session and process group) runs the notebook
   with nbclient in a fresh kernel, :mod:`kinbook.classroom._kernel`, which caps memory and CPU and
   installs the audit hook before any cell runs;
3. after the student's cells, one cell appended by the worker prints the named answers as JSON between two
   random markers (:func:`kinbook.classroom.serialize.dumps`); only that cell's output is read;
4. the parent waits at most ``timeout`` + start-up time, then kills the worker's and the kernel's process
   groups, and reads the worker's result file.

Within :func:`zygote` (``kinbook grade`` uses it), the worker and the kernel are not started from scratch
but forked, for each submission, from a zygote (:mod:`kinbook.classroom._zygote`): a clean process that
did their imports once. The kernelspec's command is then a launcher (:mod:`kinbook.classroom._launch`)
that stands in for the forked kernel (its exit status, its death), and step 4 also kills the forked
kernel's process group. The worker and the kernel still get their own environment, directories, limits
and (for the kernel) audit hook, set up by themselves before any student code runs.

Nothing here raises for a bad submission: the outcome is an :class:`Execution` with a status.
"""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Execution", "execute", "zygote", "STARTUP_SECONDS"]

#: Time allowed to start the kernel (imports of numpy, sympy, kinbook), not counted in the timeout.
STARTUP_SECONDS = 60.0
WORKER_MEMORY_MB = 3000
MAX_OUTPUT_CHARS = 5_000_000
MAX_ANSWER_CHARS = 2_000_000


@dataclass
class Execution:
    """Outcome of running a notebook.

    Attributes
    ----------
    status : {"ok", "timeout", "memory", "error"}
        "ok": every cell was run (some may have raised) and the answers were read.
    message : str
    answers : dict or None
        {name: record or None} as written by :func:`kinbook.classroom.serialize.dumps`.
    errors : list of dict
        One per cell that raised: cell number, exception name and value.
    seconds : float
    """

    status: str
    message: str = ""
    answers: dict | None = None
    errors: list = field(default_factory=list)
    seconds: float = 0.0


def _kill_group(pid):
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError, OSError):
        pass


# ================================================================================================== zygote
#: Set this environment variable to ``0`` to start every worker and kernel from scratch, even within
#: :func:`zygote`.
ZYGOTE_ENV = "KINBOOK_SANDBOX_ZYGOTE"
_zygote_state = {"depth": 0, "handle": None, "failed": False}


@contextlib.contextmanager
def zygote():
    """Within this block, :func:`execute` forks its worker and kernel processes from a pre-warmed zygote.

    The zygote (:mod:`kinbook.classroom._zygote`) is started by the first :func:`execute` call, reused by
    the following ones, and stopped — with any process it still has — when the outermost block ends, or
    when this process dies. Each submission still gets a new worker and a new kernel process, which set up
    their own limits (and the kernel its audit hook). Where a zygote cannot run (not Linux), or with the
    environment variable ``KINBOOK_SANDBOX_ZYGOTE=0``, they are started from scratch as outside the block;
    if the zygote fails to start, a ``RuntimeWarning`` says so and the same happens.

    Examples
    --------
    >>> from kinbook.classroom.sandbox import zygote
    >>> with zygote():  # doctest: +SKIP
    ...     results = [grade_submission(source, s) for s in submissions]
    """
    enable_zygote()
    try:
        yield
    finally:
        _zygote_state["depth"] = max(0, _zygote_state["depth"] - 1)
        if _zygote_state["depth"] == 0:
            stop_zygote()


def enable_zygote():
    """Let :func:`execute` use a zygote in this process until :func:`stop_zygote` (see :func:`zygote`)."""
    _zygote_state["depth"] += 1


def stop_zygote():
    """Stop this process's zygote, if any (it kills its processes first), and use none any more."""
    handle = _zygote_state["handle"]
    _zygote_state.update(depth=0, handle=None, failed=False)
    if handle is not None:
        handle.close()


def _zygote_handle():
    """This process's zygote (a :class:`kinbook.classroom._zygote.Zygote`), started if need be; None when the
    worker and kernel start from scratch."""
    from . import _zygote

    state = _zygote_state
    if state["depth"] <= 0 or state["failed"] or os.environ.get(ZYGOTE_ENV, "1") == "0" \
            or not _zygote.supported():
        return None
    handle = state["handle"]
    if handle is not None and not handle.alive():
        handle.close()
        handle = state["handle"] = None
    if handle is None:
        try:
            handle = state["handle"] = _zygote.Zygote(_worker_env(), timeout=STARTUP_SECONDS)
        except _zygote.ZygoteError as exc:
            import warnings

            state["failed"] = True
            warnings.warn(f"{exc}; kernels are started from scratch", RuntimeWarning, stacklevel=3)
            return None
    return handle


def _start_worker(control, zygote, log):
    """The worker process: forked by the zygote, or started from scratch (also when the zygote fails)."""
    env = _worker_env()
    if zygote is not None:
        from ._zygote import ZygoteError

        with open(os.devnull, "rb") as null_in, open(os.devnull, "wb") as null_out:
            try:
                return zygote.spawn("worker", [str(control)], env, str(control),
                                    (null_in.fileno(), null_out.fileno(), log.fileno()))
            except ZygoteError:
                pass
    # run this file directly (not ``-m``): the worker needs neither kinbook nor sympy, only nbclient
    boot = ("import sys, runpy; sys.modules['rfc3987_syntax'] = None; sys.argv[1:] = [%r]; "
            "runpy.run_path(%r, run_name='__main__')" % (str(control), __file__))
    return subprocess.Popen([sys.executable, "-c", boot], env=env, cwd=str(control), stdin=subprocess.DEVNULL,
                            stdout=subprocess.DEVNULL, stderr=log, start_new_session=True)


def _forget_zygote_in_child():
    # a process forked from this one (a grading pool's process) must neither use nor stop this zygote, and
    # must not keep its control pipe open (the zygote stops when that pipe closes)
    handle = _zygote_state["handle"]
    _zygote_state.update(depth=0, handle=None, failed=False)
    if handle is not None:
        handle.forget()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_zygote_in_child)


def execute(nb, answer_names, *, timeout=60.0, memory_mb=1000, files=None):
    """Run notebook ``nb`` (a NotebookNode, student's cells only) in a sandbox and read ``answer_names``.

    Parameters
    ----------
    nb : nbformat.NotebookNode
    answer_names : list of str
    timeout : float
        Wall-clock seconds for the student's cells (kernel start-up not included).
    memory_mb : float
        Memory the student's code may allocate beyond the kernel's own footprint (address-space limit).
    files : dict, optional
        {name: bytes} copied into the sandbox root (the submission itself, for example).
    """
    import nbformat

    t0 = time.monotonic()
    root = Path(tempfile.mkdtemp(prefix="kinbook-sandbox-")).resolve()
    control = Path(tempfile.mkdtemp(prefix="kinbook-control-")).resolve()
    os.chmod(control, 0o700)
    try:
        for name, data in (files or {}).items():
            (root / Path(name).name).write_bytes(data)
        nonce = secrets.token_hex(16)
        zygote = _zygote_handle()
        job = {"root": str(root), "timeout": float(timeout), "memory_mb": float(memory_mb), "nonce": nonce,
               "names": list(answer_names), "zygote": zygote.socket if zygote else None}
        (control / "job.json").write_text(json.dumps(job))
        nbformat.write(nb, str(control / "run.ipynb"))
        with open(control / "worker.log", "wb") as log:
            proc = _start_worker(control, zygote, log)
        limit = float(timeout) + STARTUP_SECONDS + 15.0
        killed = False
        try:
            proc.wait(limit)
        except subprocess.TimeoutExpired:
            killed = True
        finally:  # also when this process is being terminated: no worker or kernel outlives the call
            _kill_group(proc.pid)
            for pidfile in (control / "kernel.pid", control / "kernel-fork.pid"):  # launcher, forked kernel
                if pidfile.exists():
                    try:
                        _kill_group(int(pidfile.read_text().strip()))
                    except ValueError:
                        pass
            proc.wait()
        seconds = time.monotonic() - t0
        result_file = control / "result.json"
        if killed and not result_file.exists():
            return Execution("timeout", f"the notebook did not finish within {timeout:g} s", seconds=seconds)
        try:
            res = json.loads(result_file.read_text())
        except (OSError, ValueError):
            log = (control / "worker.log").read_text(errors="replace")[-500:] if (control / "worker.log").exists() else ""
            return Execution("error", f"the grading worker stopped without a result (exit {proc.returncode}) {log}".strip(),
                             seconds=seconds)
        return Execution(res.get("status", "error"), res.get("message", ""), res.get("answers"),
                         res.get("errors", []), seconds)
    finally:
        shutil.rmtree(root, ignore_errors=True)
        shutil.rmtree(control, ignore_errors=True)


def _worker_env():
    keep = ("PATH", "LANG", "LC_ALL", "PYTHONPATH", "SYSTEMROOT", "TMPDIR")
    env = {k: os.environ[k] for k in keep if k in os.environ}
    env.update({"PYTHONDONTWRITEBYTECODE": "1", "MALLOC_ARENA_MAX": "2", "OPENBLAS_NUM_THREADS": "1",
                "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "MPLBACKEND": "Agg", "PYDEVD_DISABLE_FILE_VALIDATION": "1"})
    return env


# ================================================================================================== worker
def _kernel_spec_dir(control, zygote_socket=None):
    d = control / "kernels" / "kinbook-sandbox"
    d.mkdir(parents=True)
    if zygote_socket:  # the launcher: standard library only, no site-packages (starts in milliseconds)
        launch = str(Path(__file__).with_name("_launch.py"))
        argv = [sys.executable, "-I", "-S", launch, zygote_socket, str(control / "kernel-fork.pid")]
    else:
        argv = [sys.executable, "-m", "kinbook.classroom._kernel"]
    spec = {"argv": argv + ["-f", "{connection_file}"], "display_name": "kinbook sandbox", "language": "python"}
    (d / "kernel.json").write_text(json.dumps(spec))
    return control / "kernels"


def _kernel_env(job, control):
    root = job["root"]
    env = _worker_env()
    env.update({"HOME": root, "TMPDIR": root, "IPYTHONDIR": str(Path(root) / ".ipython"), "MPLCONFIGDIR": str(Path(root) / ".mpl"),
                "JUPYTER_RUNTIME_DIR": str(control), "KINBOOK_SANDBOX_ROOT": root,
                "KINBOOK_SANDBOX_MEMORY_MB": str(job["memory_mb"]),
                "KINBOOK_SANDBOX_CPU_S": str(int(job["timeout"] * 2 + 30))})
    return env


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


def _worker(control):
    """Run the notebook of ``control`` (a directory) and write ``result.json`` there.

    The worker process's whole job: started from scratch (``python sandbox.py CONTROL``) or forked from
    the zygote (its ``worker`` role); its kernels likewise (``job["zygote"]`` chooses the kernelspec).
    """
    import resource

    import nbformat
    from jupyter_client import AsyncKernelManager
    from jupyter_client.kernelspec import KernelSpecManager
    from nbclient import NotebookClient
    from nbclient.exceptions import CellTimeoutError, DeadKernelError

    control = Path(control)
    job = json.loads((control / "job.json").read_text())
    lim = WORKER_MEMORY_MB * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (lim, lim))  # a flood of output cannot take the grader down
    nb = nbformat.read(str(control / "run.ipynb"), as_version=4)
    nonce = job["nonce"]
    extract = nbformat.v4.new_code_cell(
        "from kinbook.classroom.serialize import dumps as _kb_dumps\n"
        f"print({nonce!r} + _kb_dumps({job['names']!r}, get_ipython().user_ns) + {nonce!r})"
    )
    nb.cells.append(extract)
    ksm = KernelSpecManager(kernel_dirs=[str(_kernel_spec_dir(control, job.get("zygote")))])
    km = AsyncKernelManager(kernel_name="kinbook-sandbox", kernel_spec_manager=ksm)
    km.connection_file = str(control / "connection.json")
    deadline = [None]

    def cell_timeout(cell):
        if deadline[0] is None:
            return job["timeout"]
        return max(0.5, deadline[0] - time.monotonic())

    client = NotebookClient(nb, km=km, timeout_func=cell_timeout, allow_errors=True, startup_timeout=STARTUP_SECONDS,
                            kernel_name="kinbook-sandbox", record_timing=False, interrupt_on_timeout=False,
                            shutdown_kernel="immediate")
    result = {"status": "error", "message": "", "answers": None, "errors": []}
    t_start = time.monotonic()
    try:
        with client.setup_kernel(env=_kernel_env(job, control), cwd=job["root"]):
            try:
                pid = km.provisioner.process.pid
                (control / "kernel.pid").write_text(str(pid))
            except AttributeError:
                pass
            deadline[0] = time.monotonic() + job["timeout"]
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
                result.update(status="timeout", message=f"the notebook did not finish within {job['timeout']:g} s")
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
                        result["answers"] = {str(k)[:100]: v for k, v in list(answers.items())[:100]}
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
    tmp = control / "result.json.tmp"
    tmp.write_text(json.dumps(result))
    os.replace(tmp, control / "result.json")


class _OutOfMemory(Exception):
    pass


def _memory_errors_in(cell):
    return any(o.get("output_type") == "error" and o.get("ename") == "MemoryError" for o in cell.get("outputs", []))


def _memory_errors(nb):
    return any(e["ename"] == "MemoryError" for e in _cell_errors(nb))


if __name__ == "__main__":
    _worker(sys.argv[1])
