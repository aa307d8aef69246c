"""Workers and kernels forked from the zygote (kinbook.classroom._zygote) keep every guarantee of the sandbox."""

import csv
import json
import os
import secrets
import signal
import subprocess
import sys
import tempfile
import time

import nbformat
import pytest

from kinbook.classroom import grade, grade_submission, sandbox
from kinbook.classroom._zygote import Zygote, supported

from .conftest import SOURCE, submission

pytestmark = pytest.mark.skipif(not supported(), reason="the zygote runs on Linux only")

FULL = 6.0
#: What a kernel sees of itself (the answer is a Symbol named by this JSON: execute() returns it raw).
PROBE = """
import json, os, sys, resource, signal, stat, tempfile, warnings
import numpy as np, sympy as sp
def attempt(f):
    try:
        f()
        return "allowed"
    except PermissionError:
        return "refused"
def kind(fd):
    try:
        mode = os.fstat(fd).st_mode
    except OSError:
        return None
    return "socket" if stat.S_ISSOCK(mode) else "pipe" if stat.S_ISFIFO(mode) else "file" if stat.S_ISREG(mode) \\
        else "device" if stat.S_ISCHR(mode) else "other"
mask = os.umask(0o22); os.umask(mask)
info = {
    "fds": sorted(k for k in map(kind, range(1000)) if k), "stdio": [kind(0), kind(1), kind(2)],
    "signals": {s: str(signal.getsignal(getattr(signal, s))) for s in ("SIGINT", "SIGTERM", "SIGCHLD", "SIGPIPE",
                                                                       "SIGXFSZ", "SIGHUP")},
    "warnings": [str(f) for f in warnings.filters], "flags": str(sys.flags),
    "pid": os.getpid(), "ppid": os.getppid(), "cwd": os.getcwd(), "path0": sys.path[0],
    "argv0": os.path.basename(sys.argv[0]), "env": sorted(os.environ), "home": os.environ["HOME"],
    "tmp": tempfile.gettempdir(), "umask": mask, "rand": float(np.random.rand()),
    "limits": {n: resource.getrlimit(getattr(resource, n)) for n in ("RLIMIT_CPU", "RLIMIT_FSIZE", "RLIMIT_CORE")},
    "as_capped": resource.getrlimit(resource.RLIMIT_AS)[1] != resource.RLIM_INFINITY,
    "read_etc": attempt(lambda: open("/etc/hostname").read()),
    "write_tmp": attempt(lambda: open("/tmp/kinbook-zygote-test", "w")),
    "fork": attempt(os.fork), "kill": attempt(lambda: os.kill(os.getppid(), 0)),
    "setrlimit": attempt(lambda: resource.setrlimit(resource.RLIMIT_CPU, (10**6, 10**6))),
    "connect": attempt(lambda: __import__("socket").socket(1, 5).connect("/tmp/x")),
}
probe = sp.Symbol(json.dumps(info))
"""


def run(code, **kw):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(code)]
    return sandbox.execute(nb, ["probe"], **kw)


def probe(**kw):
    ex = run(PROBE, timeout=30, memory_mb=400, **kw)
    assert ex.status == "ok", ex
    return json.loads(ex.answers["probe"]["data"][0][1])


def from_scratch(monkeypatch):
    monkeypatch.setenv(sandbox.ZYGOTE_ENV, "0")


def ours(marker):
    """Our processes still running: those whose command line names ``marker`` (a private temporary path)."""
    found = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                cmdline = f.read().replace(b"\0", b" ").decode(errors="replace")
            with open(f"/proc/{pid}/stat") as f:
                state = f.read().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if marker in cmdline and state != "Z":
            found.append(cmdline[:200])
    return found


@pytest.fixture
def private_tmp(tmp_path, monkeypatch):
    """Every sandbox, control and zygote directory (so every command line of ours) under a path of our own."""
    d = tmp_path / f"tmp-{secrets.token_hex(4)}"
    d.mkdir()
    monkeypatch.setenv("TMPDIR", str(d))
    monkeypatch.setattr(tempfile, "tempdir", None)
    return str(d)


def test_a_forked_kernel_is_set_up_like_a_fresh_one(monkeypatch):
    with sandbox.zygote():
        forked = [probe(), probe()]
        zygote_pid = sandbox._zygote_state["handle"].pid
    from_scratch(monkeypatch)
    fresh = probe()
    assert sandbox._zygote_state["handle"] is None
    for info in forked:
        assert info["ppid"] == zygote_pid  # really forked
        assert info["pid"] != zygote_pid
    assert fresh["ppid"] != zygote_pid
    for info in forked + [fresh]:
        root = info["cwd"]
        assert os.path.basename(root).startswith("kinbook-sandbox-")
        assert info["path0"] == root and info["home"] == root and info["tmp"] == root
        assert info["argv0"] == "_kernel.py"
        assert info["as_capped"]
        for action in ("read_etc", "write_tmp", "fork", "kill", "setrlimit", "connect"):
            assert info[action] == "refused", (action, info)
    # the same environment, limits, signal dispositions, warning filters; no descriptor of the zygote's
    for key in ("env", "umask", "limits", "fds", "stdio", "signals", "warnings", "flags"):
        assert forked[0][key] == fresh[key], key
    assert forked[0]["rand"] != forked[1]["rand"]  # each kernel its own random state


@pytest.mark.parametrize("code, status, message", [
    ("import signal\nsignal.raise_signal(signal.SIGXCPU)", "timeout", "the notebook used up its CPU time"),
    ("import signal\nsignal.raise_signal(signal.SIGKILL)", "error", "the kernel died (exit code -9)"),
    ("import os\nos._exit(3)", "error", "the kernel died (exit code 3)"),
])
def test_how_a_kernel_ends_reaches_the_worker(monkeypatch, code, status, message):
    """The launcher ends as its forked kernel did (same exit code, same signal): the worker tells them apart."""
    with sandbox.zygote():
        forked = run(code, timeout=30, memory_mb=400)
    from_scratch(monkeypatch)
    fresh = run(code, timeout=30, memory_mb=400)
    assert (forked.status, forked.message) == (fresh.status, fresh.message)
    assert forked.status == status and forked.message.startswith(message)


def test_hostile_submissions_get_the_same_grades_from_scratch(batch, tmp_path, monkeypatch):
    """The batch (tests/classroom/conftest.py) forks its kernels; the same fixtures graded from scratch."""
    from_scratch(monkeypatch)
    students = ["kill_kernel", "os_exit", "memory", "read_source", "write_outside", "patch_serializer"]
    results = grade(SOURCE, [submission(s) for s in students], tmp_path, timeout=5, memory=400, jobs=2)
    for r in results:
        forked = batch["results"][r.student]
        assert (r.status, r.score, r.message) == (forked.status, forked.score, forked.message), r.student
        assert [(p.status, p.score, p.message) for p in r.parts] == \
            [(p.status, p.score, p.message) for p in forked.parts]


@pytest.mark.parametrize("jobs", [1, 2])
def test_no_process_outlives_a_grade(private_tmp, tmp_path, jobs):
    seen = []
    subs = [submission(s) for s in ("good", "os_exit", "kill_kernel")]
    results = grade(SOURCE, subs, tmp_path / "graded", timeout=5, memory=400, jobs=jobs,
                    progress=lambda r: seen.extend(ours(private_tmp)))
    assert {r.student: r.status for r in results} == {"good": "ok", "os_exit": "error", "kill_kernel": "error"}
    assert any("kinbook.classroom._zygote" in c for c in seen)  # the kernels were forked
    assert ours(private_tmp) == []
    assert os.listdir(private_tmp) == []  # sandbox, control and zygote directories are gone


def test_the_zygote_stops_when_its_grading_process_dies(private_tmp, tmp_path, monkeypatch):
    """A grading process that dies without cleaning up: its zygote sees its control pipe close, and stops
    with its workers and kernels."""
    G = sys.modules["kinbook.classroom.grade"]
    original = G._grade_task

    def dying(args):
        if args[1].endswith("not_a_notebook.ipynb"):
            original((args[0], submission("good")) + args[2:])  # starts this process's zygote
            os._exit(1)
        return original(args)

    dying.__module__, dying.__qualname__ = original.__module__, original.__qualname__
    monkeypatch.setattr(G, "_grade_task", dying)
    results = {r.student: r for r in grade(SOURCE, [submission("good"), submission("not_a_notebook")], tmp_path,
                                           timeout=5, memory=400, jobs=2)}
    assert results["good"].score == FULL and results["not_a_notebook"].status == "error"
    for _ in range(100):
        if not ours(private_tmp):
            break
        time.sleep(0.1)
    assert ours(private_tmp) == []
    with open(tmp_path / "grades.csv", newline="") as f:
        assert {r["student"] for r in csv.DictReader(f)} == {"good", "not_a_notebook"}


def _launch(z, tmp_path):
    """A launcher started as jupyter_client starts the kernelspec's command; returns it and its kernel's pid."""
    from jupyter_client.connect import write_connection_file

    root, control = tmp_path / "root", tmp_path / "control"
    root.mkdir(parents=True)
    control.mkdir()
    connection, _ = write_connection_file(str(control / "connection.json"))
    spec = json.loads((sandbox._kernel_spec_dir(control, z.socket) / "kinbook-sandbox" / "kernel.json").read_text())
    argv = [a.replace("{connection_file}", connection) for a in spec["argv"]]
    env = sandbox._kernel_env({"root": str(root), "memory_mb": 400.0, "timeout": 10.0}, control)
    launcher = subprocess.Popen(argv, env=env, cwd=str(root), stdin=subprocess.PIPE, start_new_session=True)
    pidfile = control / "kernel-fork.pid"
    for _ in range(300):
        if pidfile.exists():
            break
        time.sleep(0.1)
    kernel = int(pidfile.read_text())
    with open(f"/proc/{kernel}/stat") as f:
        assert int(f.read().rsplit(")", 1)[1].split()[1]) == z.pid  # the kernel's parent is the zygote
    return launcher, kernel


def gone(pid, seconds=10.0):
    for _ in range(int(seconds * 10)):
        if not os.path.exists(f"/proc/{pid}"):
            return True
        time.sleep(0.1)
    return False


def test_killing_the_launcher_kills_its_kernel(tmp_path):
    z = Zygote(sandbox._worker_env())
    try:
        launcher, kernel = _launch(z, tmp_path / "a")
        launcher.kill()
        launcher.wait()
        assert gone(kernel)

        launcher, kernel = _launch(z, tmp_path / "b")  # and the other way round: the launcher dies as its kernel
        os.kill(kernel, signal.SIGKILL)
        assert launcher.wait(30) == -signal.SIGKILL

        launcher, kernel = _launch(z, tmp_path / "c")  # stopping the zygote stops its kernels
    finally:
        z.close()
    assert gone(kernel)
    assert launcher.wait(30) == -signal.SIGKILL
    assert z.process.returncode == 0 and not os.path.exists(z.dir)


def test_the_zygote_never_holds_the_instructors_source(tmp_path):
    """The zygote is a fresh interpreter that only ever receives launch requests: the instructor's notebook,
    which the grading process reads, is not in its memory, environment or command line."""
    secret = f"kinbook-secret-{secrets.token_hex(8)}"
    nb = nbformat.read(SOURCE, 4)
    for cell in nb.cells:
        if cell.source.startswith("### BEGIN SOLUTION"):
            cell.source = cell.source.replace("### BEGIN SOLUTION\n", f"### BEGIN SOLUTION\n# {secret}\n")
    src = tmp_path / "tiny.ipynb"
    nbformat.write(nb, str(src))
    with sandbox.zygote():
        r = grade_submission(src, submission("good"), timeout=10, memory=400)
        z = sandbox._zygote_state["handle"]
        assert z is not None and z.alive()
        for what in ("cmdline", "environ"):
            with open(f"/proc/{z.pid}/{what}", "rb") as f:
                text = f.read()
            assert secret.encode() not in text and str(src).encode() not in text
        try:
            found = _memory_contains(z.pid, secret.encode())
            control = _memory_contains(z.pid, z.socket.encode())  # what it does hold is found
        except PermissionError:
            pytest.skip("the zygote's memory cannot be read here (ptrace restrictions)")
    assert r.score == FULL
    assert control and not found


def _memory_contains(pid, needle):
    with open(f"/proc/{pid}/maps") as maps, open(f"/proc/{pid}/mem", "rb", buffering=0) as mem:
        for line in maps:
            fields = line.split()
            start, end = (int(x, 16) for x in fields[0].split("-"))
            if "r" not in fields[1] or (len(fields) > 5 and fields[5] in ("[vvar]", "[vsyscall]", "[vvar_vclock]")):
                continue
            try:
                mem.seek(start)
                if needle in mem.read(end - start):
                    return True
            except (OSError, ValueError, OverflowError):
                continue
    return False


def test_without_a_zygote_the_worker_and_launcher_fall_back(monkeypatch):
    """A zygote that cannot be reached: the worker is started from scratch, and the launcher runs the kernel
    itself (``python -m kinbook.classroom._kernel``)."""
    from kinbook.classroom._zygote import ZygoteError

    class Unreachable:
        socket = "/nonexistent/kinbook-zygote/fork.sock"

        def spawn(self, *args):
            raise ZygoteError("unreachable")

    monkeypatch.setattr(sandbox, "_zygote_handle", lambda: Unreachable())
    ex = run("import os\nprobe = os.getpid()", timeout=30, memory_mb=400)
    assert ex.status == "ok" and ex.answers["probe"]["kind"] == "array"


def test_grading_one_submission_starts_no_zygote():
    r = grade_submission(SOURCE, submission("wrong"), timeout=10, memory=400)
    assert r.status == "ok" and sandbox._zygote_state["handle"] is None
