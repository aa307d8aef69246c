"""The operating-system sandbox (kinbook.classroom.sandbox): what a student's code can see and do in it, and
that nothing outlives it.

The escape fixtures (tests/classroom/submissions/{unhook,unaudited,recon,writes,daemon,leftovers,hijack}.ipynb)
are graded with the rest in tests/classroom/conftest.py's batch, with the audit hook on. Here their cells run
once more in one sandbox with the hook *off* — as if a student had found a way past it — and each reports in
``probe`` what it saw and did: the tests assert that bubblewrap alone held.
"""

import json
import os
import signal
import subprocess
import sys
import time

import nbformat
import pytest

from kinbook.classroom import grade, grade_submission
from kinbook.classroom.notebook import parse_submission
from kinbook.classroom.sandbox import IsolationUnavailable, Sandbox, bwrap

from .conftest import BWRAP, CANARY, ENOUGH, ROOT, RUNAWAY, SOURCE, checkout_hash, descendants, needs_bwrap, submission

GRADER_SECRET = "KINBOOK_TEST_GRADER_SECRET"


def cells_of(name):
    with open(submission(name), "rb") as f:
        data = f.read()
    return [c["source"] for c in parse_submission(data) if c["cell_type"] == "code"], data


ORDER = ("unhook", "unaudited", "recon", "writes", "daemon", "second_kernel", "stamps", "recon", "leftovers", "hijack",
         "recon")


@pytest.fixture(scope="module")
def probes():
    """Each escape fixture's `probe`, run in one sandbox (hook off, except for `unhook`), in the order of
    :data:`ORDER`: the daemon's and the stamps' runs come before a second reconnaissance (``recon_2``), the
    leftovers' and the hijacker's before a third (``recon_3``), which must find nothing of them."""
    if not BWRAP:
        pytest.skip("no operating-system sandbox here")
    os.environ[GRADER_SECRET] = "the grader's environment"
    with open(CANARY, "w") as f:
        f.write("do not delete")
    checkout = checkout_hash()
    out = {}
    try:
        with Sandbox(isolation=True) as sb:
            for name in ORDER:
                cells, data = cells_of(name)
                ex = sb.run(cells, ["probe"], timeout=ENOUGH, memory_mb=400, files={"submission.ipynb": data},
                            audit_hook=name == "unhook")
                assert ex.status == "ok", (name, ex)
                key = name if name not in out else f"{name}_{sum(k.startswith(name) for k in out if 'after' not in k) + 1}"
                out[key] = json.loads(ex.answers["probe"]["data"][0][1])
                out[f"starts_after_{key}"] = sb.starts
                if name == "hijack":  # the pipes between this process and the sandbox
                    out["host_pipes"] = {f"pipe:[{os.fstat(fd).st_ino}]" for fd in (sb.cmd_w, sb.evt_r, sb.job_w,
                                                                                     sb.result_r)}
            out["starts"] = sb.starts
            out["zygote_pid"] = sb.pid
            out["no_fork"] = sb.limits == "rlimits, no fork"  # no control group here (an unprivileged grader)
    finally:
        del os.environ[GRADER_SECRET]
    out["left"] = descendants(os.getpid())
    out["checkout_changed"] = checkout_hash() != checkout
    return out


def refused(value):
    return isinstance(value, str) and value.startswith("refused")


@needs_bwrap
def test_the_hook_cannot_be_switched_off_from_inside(probes):
    p = probes["unhook"]
    assert not p["unhook"].startswith("no hook")  # the hook was there, and refused
    assert refused(p["read_etc"])                # and still refuses after the attempt


@needs_bwrap
def test_unaudited_processes_and_interpreters_stay_inside(probes):
    p = probes["unaudited"]
    if probes["no_fork"]:                        # without a control group the kernel cannot start a process
        assert refused(p["fork_exec"]) and "Operation not permitted" in p["fork_exec"]
    else:
        uid, *listing = p["fork_exec"]           # a shell did run, hook off, as the sandbox's user
        assert uid == "65534"
        visible = {d.strip("/").split("/")[0] for d in bwrap.readonly_dirs()}
        assert set(listing) <= {"bin", "sbin", "lib", "lib32", "lib64", "libx32", "dev", "proc", "tmp", "home",
                                "run"} | visible
        assert "etc" not in listing
    assert "etc" not in p["subinterpreter"]      # a subinterpreter sees the same root
    assert refused(p["mknod"])                   # no device nodes
    assert p["mkfifo"] == "made"                 # a FIFO in its own directory is harmless (and is wiped)
    if bwrap.seccomp_program() is not None:
        assert refused(p["memfd"])               # no memory outside the address-space limit
    assert all(v != "ok" for v in p["ctypes"].values()), p["ctypes"]  # mount, ptrace, setuid, unshare, keyctl
    if bwrap.seccomp_program() is not None and os.uname().machine in ("x86_64", "aarch64"):
        assert p["ctypes"]["keyctl"] == "EPERM"  # refused by the seccomp filter


@needs_bwrap
def test_reconnaissance_finds_nothing_of_the_grader(probes):
    for key in ("recon", "recon_2", "recon_3"):
        p = probes[key]
        mine = "/home/student/submission.ipynb"  # the student's own copy (its code names what it looks for)
        assert [f for f in p["notebooks"] if f != mine] == []       # no source, collected/, graded/, canary
        assert [f for f in p["solutions"] if f != mine] == []
        for pid, cmd in p["processes"].items():  # the sandbox's own processes only
            assert "bwrap" in cmd or "kinbook" in cmd or cmd == "unreadable", (pid, cmd)
        assert GRADER_SECRET not in p["environ"] and GRADER_SECRET not in p["proc_environ"]
        assert p["network"]["1.1.1.1"] != "connected"
        assert p["uid"] == 65534


@needs_bwrap
def test_writes_outside_reach_nothing(probes):
    p = probes["writes"]
    assert refused(p["package"]) and "Errno" in p["package"]       # read-only
    assert "FileNotFoundError" in p["source"] and "FileNotFoundError" in p["classmate"]  # not there at all
    assert p["collected"] == "none found"
    assert p["canary"] == "written"   # a canary of its own: the sandbox's private /tmp
    assert open(CANARY).read() == "do not delete"
    assert not probes["checkout_changed"]


@needs_bwrap
def test_a_daemon_dies_with_the_run(probes):
    daemon = probes["daemon"]["daemon"]
    if probes["no_fork"]:                                            # without a control group: no process at all
        assert refused(daemon)
        return
    assert daemon.isdigit()                                          # it did start, in its own session
    later = probes["recon_2"]
    assert daemon not in later["processes"]                          # gone at the next submission
    assert probes["starts_after_daemon"] == 1                        # without restarting the sandbox
    assert probes["left"] == []                                      # and nothing is left on the host


@needs_bwrap
def test_the_graders_pipes_are_out_of_reach_and_no_run_answers_for_the_zygote(probes):
    """No process a student's code can see holds a pipe of the grading process (reopened through /proc/PID/fd
    or copied with pidfd_getfd): the hijacker could otherwise answer the grader's "reset" itself, outlive its
    run and read the next student's notebook."""
    p = probes["hijack"]
    found = set(p["descriptors"]["seen"].values()) | set(p["descriptors"]["taken"].values())
    assert len(probes["host_pipes"]) == 4 and not found & probes["host_pipes"], found & probes["host_pipes"]
    if bwrap.seccomp_program() is not None:
        assert p["descriptors"]["taken"] == {}                        # pidfd_getfd: refused by the filter
    assert refused(p["hijack"]), p["hijack"]
    later = probes["recon_3"]
    assert "kinbook-stolen" not in later["leftovers"]               # the next run's notebook was not read


@needs_bwrap
def test_nothing_a_run_leaves_reaches_the_next(probes):
    left = probes["leftovers"]
    assert left["left"] == ["/tmp/kinbook-note", "/home/student/kinbook-note",
                            "/run/kinbook/kinbook-note"]          # written (the sandbox's own directories)
    assert probes["starts_after_hijack"] == 2                    # a file beside the control directory: replaced
    later = probes["recon_3"]["leftovers"]
    assert "kinbook-note" not in later and later.count("work") == 1


@needs_bwrap
def test_no_time_mode_or_extended_attribute_reaches_the_next_run(probes):
    """A directory kept between two runs carried 64 bits in its access time (and 4 KB in an extended attribute
    once the hook was off): the reset clears them, without replacing the sandbox."""
    stamp = 0x7E57_C0DE_1234_5678
    planted = probes["stamps"]["stamp"]
    assert planted["/tmp times"] == stamp                          # planted
    assert probes["starts_after_recon_2"] == 1                     # reset, not replaced
    for d, state in probes["recon_2"]["dirstate"].items():
        assert stamp not in (state["atime"], state["mtime"]), (d, state)
        assert state["xattrs"] == [] or state["xattrs"].startswith("refused"), (d, state)
        assert state["mode"] in ("0o700", "0o1700"), (d, state)  # (jupyter makes its runtime directory sticky)


@needs_bwrap
def test_the_sandboxs_pid_1_is_the_zygote_and_out_of_reach(probes):
    """bubblewrap runs with --as-pid-1: pid 1 is the zygote, not bubblewrap's own init (which held the grader's
    descriptors, its log on fd 2, and could not be killed by a reset); neither its descriptors nor its
    environment can be reached, and it ignores signals sent from inside."""
    for key in ("recon", "recon_2", "recon_3"):
        p = probes[key]["pid1"]
        assert p["comm"] == "python" or p["comm"].startswith("python"), p
        assert all(refused(p[f"fd{fd}"]) for fd in range(4)), p
        assert refused(p["environ"]), p
    assert probes["starts"] == 2 and probes["recon_3"]["pid1"]["kill"] in ("sent", "refused: Operation not permitted")


@needs_bwrap
def test_no_second_kernel_can_be_asked_for(probes):
    """With the hook off, a cell asked the zygote's socket for a second kernel whose start-up ran before any limit
    (1.5 GB taken under --memory 400): there is no socket now, the launch channel is the launcher's alone, and
    the zygote starts one kernel per run."""
    p = probes["second_kernel"]
    assert p["socket_paths"] == "no socket" or all(refused(v) for v in p["socket_paths"].values()), p
    assert all(refused(v) for v in p["channel_fds"].values()), p["channel_fds"]
    assert p["own_fds"] == {}, p["own_fds"]
    if probes["no_fork"]:  # the launcher cannot even be started by the kernel
        assert refused(p["launcher"]), p["launcher"]
    else:
        assert set(p["launcher"].values()) == {1}, p["launcher"]


def _run(code, **kw):
    with Sandbox(isolation=BWRAP) as sb:
        return sb.run([code], ["probe"], timeout=ENOUGH, memory_mb=400, **kw)


@pytest.mark.parametrize("code, status, message", [
    ("import signal\nsignal.raise_signal(signal.SIGXCPU)", "timeout", "the notebook used up its CPU time"),
    ("import signal\nsignal.raise_signal(signal.SIGKILL)", "error", "the kernel died (exit code -9)"),
    ("import os\nos._exit(3)", "error", "the kernel died (exit code 3)"),
])
def test_how_a_kernel_ends_reaches_the_worker(code, status, message):
    """The launcher ends as its forked kernel did (same exit code, same signal): the worker tells them apart."""
    ex = _run(code)
    assert ex.status == status and ex.message.startswith(message)


def test_a_forged_result_is_data_checked_field_by_field():
    from kinbook.classroom.sandbox.host import _validated

    assert _validated({"status": "ok", "answers": {"x": None}, "errors": [{"cell": "1"}, {"cell": 2}]}).errors == [
        {"cell": 2, "ename": "", "evalue": ""}]
    assert _validated({"status": "pwned"}).status == "error"
    assert _validated({"status": "ok", "answers": {str(i): None for i in range(101)}}).status == "error"
    assert _validated({"status": "ok"}).message == "the sandbox returned no answers"


def test_a_result_frame_nested_too_deeply_is_unreadable_data():
    """A forged result nested beyond the JSON parser's depth raised RecursionError in the grading process: the
    submission was recorded as a failure of the grader, without its parts."""
    import threading

    from kinbook.classroom.sandbox.protocol import FrameError, read_frame

    r, w = os.pipe()
    nested = {"status": "ok", "answers": {"x": None}}
    frame = json.dumps(nested).replace("null", "[" * 100_000 + "]" * 100_000)
    writer = threading.Thread(target=lambda: (os.write(w, b"KBF1 %d 0\n%s" % (len(frame), frame.encode())),
                                              os.close(w)))
    writer.start()
    with pytest.raises(FrameError, match="nested too deeply"):
        read_frame(r, 1 << 20, timeout=30)
    writer.join()
    os.close(r)


@needs_bwrap
def test_neither_the_source_nor_submissions_enter_the_zygote(tmp_path):
    """The zygote, which every kernel is forked from, never holds the instructor's notebook or a submission:
    jobs go to each run's worker on their own pipe."""
    import secrets

    secret = f"kinbook-secret-{secrets.token_hex(8)}"
    nb = nbformat.read(SOURCE, 4)
    for cell in nb.cells:
        if cell.source.startswith("### BEGIN SOLUTION"):
            cell.source = cell.source.replace("### BEGIN SOLUTION\n", f"### BEGIN SOLUTION\n# {secret}\n")
    src = tmp_path / "tiny.ipynb"
    nbformat.write(nb, str(src))
    student = f"kinbook-student-{secrets.token_hex(8)}"
    sub = nbformat.read(submission("good"), 4)
    sub.cells[-1].source += f"\n# {student}"
    nbformat.write(sub, str(tmp_path / "good.ipynb"))
    with Sandbox() as sb:
        r = grade_submission(src, tmp_path / "good.ipynb", timeout=ENOUGH, memory=400, sandbox=sb)
        zygote = [p for p in descendants(sb.pid) if b"sandbox.zygote" in open(f"/proc/{p}/cmdline", "rb").read()]
        zygote = min(zygote)  # its children (worker, kernel) are gone after the reset; the zygote is the oldest
        try:
            found = [_memory_contains(zygote, s.encode()) for s in (secret, student, "ready")]
        except PermissionError:
            pytest.skip("the zygote's memory cannot be read here (ptrace restrictions)")
    assert r.score == 6.0
    assert found == [False, False, True]  # what it does hold ("ready", its own word) is found


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


def test_without_bubblewrap_grading_refuses_and_names_the_package(tmp_path, monkeypatch):
    from kinbook.cli import main

    monkeypatch.setattr(bwrap, "_probe", lambda: "bubblewrap (`bwrap`) is not installed")
    with pytest.raises(IsolationUnavailable, match=r"apt-get install bubblewrap.*--no-isolation"):
        grade(SOURCE, [submission("corrupt")], tmp_path / "g")
    assert not (tmp_path / "g").exists()  # refused before anything is graded or written
    assert main(["grade", SOURCE, submission("corrupt"), "-o", str(tmp_path / "g")]) == 2


def test_no_isolation_warns_and_is_recorded(tmp_path):
    import csv
    import sqlite3

    seen = []
    with pytest.warns(RuntimeWarning, match="WITHOUT isolation"):
        results = grade(SOURCE, [submission("good")], tmp_path, timeout=ENOUGH, memory=400, isolation=False,
                        progress=seen.append)
    assert results[0].score == 6.0 and results[0].isolation.startswith("none; ")
    assert any(isinstance(s, str) and s.startswith("warning: grading WITHOUT isolation") for s in seen)
    db = sqlite3.connect(tmp_path / "gradebook.sqlite")
    assert db.execute("SELECT isolation FROM runs").fetchall() == [("none",)]
    assert db.execute("SELECT substr(isolation, 1, 6) FROM submissions").fetchall() == [("none; ",)]
    assert [r["isolation"][:6] for r in csv.DictReader(open(tmp_path / "totals.csv"))] == ["none; "]


# ======================================================================================== killing the grader
#: The kill test's timeout: `good` must finish within it on a loaded machine and `loop` must reach it (burning a core)
KILL_TEST_TIMEOUT = 4 * RUNAWAY
#: How long the processes a killed grader started may take to go, on a loaded machine (on a quiet one: well
#: under a second)
EXIT_WINDOW = 30.0


def _grader(out, subs, jobs):
    cmd = [sys.executable, "-m", "kinbook.cli", "grade", SOURCE, *subs, "-o", str(out),
           "--timeout", str(KILL_TEST_TIMEOUT),
           "--memory", "400", "--jobs", str(jobs), *([] if BWRAP else ["--no-isolation"])]
    # Ctrl-C's default restored in the grader: a test run started in the background of a script inherits SIGINT
    # ignored (POSIX), and a grader that ignores it, as it should then, is not what this test kills
    return subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))


def _running_kernels(family):
    """Processes forked by a zygote (workers, kernels) among ``family``."""
    return [p for p in family if "sandbox.zygote" in _cmdline(p) and "sandbox.zygote" in _cmdline(_ppid(p))]


def test_killing_the_grader_leaves_no_process_and_the_next_run_resumes(tmp_path):
    """`kinbook grade` killed (SIGKILL with two grading processes; SIGTERM and Ctrl-C with one) while notebooks
    run: soon after (at most EXIT_WINDOW s on a loaded machine) nothing it started is left — pool processes, sandboxes, zygotes, kernels —; what was
    recorded before stays; running the same command again grades only what is left, with complete CSV files."""
    import csv
    import sqlite3

    subs = [submission(s) for s in ("corrupt", "good", "loop")]
    runs = {signal.SIGKILL: _grader(tmp_path / "kill", subs, 2), signal.SIGTERM: _grader(tmp_path / "term", subs, 1),
            signal.SIGINT: _grader(tmp_path / "int", subs, 1)}
    deadline = time.monotonic() + 600  # (a hang's bound: a loaded machine starts kernels slowly)
    pending = dict(runs)
    while pending and time.monotonic() < deadline:
        for signum, proc in list(pending.items()):
            family = descendants(proc.pid)
            if _running_kernels(family):
                os.kill(proc.pid, signum)
                t0 = time.monotonic()
                while time.monotonic() - t0 < EXIT_WINDOW and [p for p in family if _alive(p)]:
                    time.sleep(0.05)
                left = [(p, _cmdline(p)[:60]) for p in family if _alive(p)]
                assert left == [], (signum, left)
                proc.wait(30)
                del pending[signum]
        time.sleep(0.1)
    assert not pending, f"the graders never started a kernel: {pending}"
    recorded = {}
    for name in ("kill", "term", "int"):
        db = sqlite3.connect(tmp_path / name / "gradebook.sqlite")
        recorded[name] = {s for (s,) in db.execute("SELECT student FROM submissions")}
        assert "corrupt" in recorded[name]  # recorded before the kill
        db.close()
    assert (tmp_path / "term" / "grades.csv").exists() and (tmp_path / "int" / "totals.csv").exists()  # exported
    again = _grader(tmp_path / "kill", subs, 2)
    out, _ = again.communicate(timeout=300)
    assert again.returncode == 0, out
    # what was recorded before the kill is skipped (corrupt, and good too when it finished before the kill)
    assert f"skipped {len(recorded['kill'])} file(s) graded before" in out, (recorded, out)
    with open(tmp_path / "kill" / "totals.csv", newline="") as f:
        totals = {r["student"]: r for r in csv.DictReader(f)}
    assert set(totals) == {"corrupt", "good", "loop"}
    assert totals["good"]["score"] == "6" and totals["loop"]["status"] == "timeout"


def _cmdline(pid):
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            return f.read().replace(b"\0", b" ").decode(errors="replace")
    except OSError:
        return ""


def _ppid(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return int(f.read().rsplit(")", 1)[1].split()[1])
    except (OSError, ValueError, IndexError):
        return -1


def _alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_an_environment_under_tmp_is_bound_after_the_private_tmp(monkeypatch):
    """A checkout cloned under /tmp (a newcomer's `git clone` into a temporary directory) keeps its venv and
    kinbook visible: bubblewrap mounts in argument order, so their read-only binds must follow the sandbox's
    private /tmp, which would hide them (the sandbox then failed with "execvp …/.venv/bin/python")."""
    from kinbook.classroom.sandbox import bwrap

    venv, pkg = "/tmp/clone/.venv", "/tmp/clone/kinbook"
    monkeypatch.setattr(bwrap, "readonly_dirs", lambda: ["/opt/python", "/usr", pkg, venv])
    monkeypatch.setattr(bwrap, "_which", lambda name: f"/usr/bin/{name}")
    monkeypatch.setattr(bwrap.os, "geteuid", lambda: 1000)   # (as root, the same command follows setpriv)
    inner = bwrap.command(["/tmp/clone/.venv/bin/python"])
    tmpfs = inner.index("/tmp", inner.index("--tmpfs") - 1)
    assert inner[tmpfs - 1] == "--tmpfs"
    for d in (venv, pkg):
        assert inner.index(d) > tmpfs and inner[inner.index(d) - 1] == "--ro-bind"
    assert inner.index("/opt/python") < tmpfs     # the rest keeps its place


# ================================================================================ limits without the audit hook
def _cgroup_or_skip():
    from kinbook.classroom.sandbox import cgroup

    why = cgroup.unavailable()
    if why:
        pytest.skip(f"no control group for a sandbox here: {why}")


@needs_bwrap
def test_a_fork_hog_is_stopped_by_the_control_group_with_the_hook_off():
    """Five children of 300 MB each (1.5 GB) under a 400 MB budget, the hook off: the sandbox's control group
    counts them together, and the out-of-memory killer stops them; the answers assigned before are graded."""
    _cgroup_or_skip()
    cells, data = cells_of("fork_hog")
    with Sandbox() as sb:
        ex = sb.run(cells, ["Phi_OA", "angle", "held"], timeout=60, memory_mb=400, audit_hook=False)
    assert ex.status == "memory", ex
    assert ex.answers["Phi_OA"] is not None and ex.answers["angle"] is not None
    held = ex.answers["held"]
    assert held is None or held["data"][0] < 5, held   # never all five
    assert ex.limits in ("cgroup v1 (memory, pids, cpu)", "cgroup v2 (memory, pids, cpu)")


@needs_bwrap
def test_without_a_control_group_the_kernel_cannot_fork():
    """The fallback where the host offers no control group (an unprivileged grader): per-process limits set by
    the zygote, and a seccomp filter that keeps the kernel from multiplying them by forking."""
    from kinbook.classroom.sandbox import seccomp

    if not seccomp.NoFork().available:
        pytest.skip("libseccomp is not available here")
    cells, data = cells_of("fork_hog")
    with Sandbox(cgroup=False) as sb:
        ex = sb.run(cells, ["Phi_OA", "angle", "held"], timeout=60, memory_mb=400, audit_hook=False)
    assert ex.limits == "rlimits, no fork"
    assert ex.status == "ok" and ex.answers["held"] is None and ex.answers["angle"] is not None
    assert [(e["ename"], e["evalue"]) for e in ex.errors] == [("PermissionError", "[Errno 1] Operation not permitted")]


@pytest.mark.parametrize("memory", [4000])
def test_a_large_memory_budget_grades(memory, tmp_path):
    """--memory above about 2.1 GB gave the whole class 0 (the worker's own cap reached the kernel through its
    launch request); the kernel's limits are now the zygote's and the grading process's only."""
    r = grade_submission(SOURCE, submission("good"), timeout=30, memory=memory, isolation=BWRAP)
    assert (r.status, r.score) == ("ok", 6.0), r


def test_a_memory_budget_beyond_the_machine_is_refused(tmp_path):
    from kinbook.classroom.sandbox.cgroup import machine_memory_mb
    from kinbook.cli import main
    from kinbook.errors import GradingError

    too_much = machine_memory_mb() + 1
    with pytest.raises(GradingError, match=rf"--memory {too_much} MB is more than this machine has"):
        grade(SOURCE, [submission("good")], tmp_path / "g", memory=too_much, isolation=BWRAP)
    assert not (tmp_path / "g").exists()
    assert main(["grade", SOURCE, submission("good"), "-o", str(tmp_path / "g"), "--memory", str(too_much)]) == 2


@needs_bwrap
def test_bubblewrap_gets_a_fixed_path_and_a_stderr_pipe(monkeypatch, tmp_path):
    """The grader's PATH is not given to bubblewrap (its processes carried it, readable through the sandbox's
    /proc/1/environ), and what bubblewrap writes on its standard error goes to a pipe the grader drains."""
    monkeypatch.setenv("PATH", f"{tmp_path}/kinbook-grader-path:{os.environ['PATH']}")
    with Sandbox() as sb:
        sb.start()
        with open(f"/proc/{sb.pid}/environ", "rb") as f:
            env = dict(v.split(b"=", 1) for v in f.read().split(b"\0") if v)
        stderr = os.readlink(f"/proc/{sb.pid}/fd/2")
        assert "--as-pid-1" in open(f"/proc/{sb.pid}/cmdline", "rb").read().decode(errors="replace").split("\0") \
            or any("--as-pid-1" in open(f"/proc/{p}/cmdline", "rb").read().decode(errors="replace")
                   for p in descendants(sb.pid))
    assert env == {b"PATH": bwrap.SYSTEM_PATH.encode()}
    assert stderr.startswith("pipe:")


def test_a_cgroup_v2_hierarchy_is_used_where_its_controllers_are_delegated(tmp_path, monkeypatch):
    """The cgroup v2 path on a host that has one (this machine mounts v1 beside an empty v2): a directory with the
    memory and pids controllers that this process may write gets the sandbox's group, with its limits."""
    from kinbook.classroom.sandbox import cgroup

    grader = tmp_path / "user.slice" / "grader"
    grader.mkdir(parents=True)
    (grader / "cgroup.controllers").write_text("cpuset cpu io memory pids\n")
    (grader / "cgroup.subtree_control").write_text("")
    monkeypatch.setattr(cgroup, "_mounts", lambda: [(str(tmp_path), "cgroup2", {"rw"})])
    monkeypatch.setattr(cgroup, "_own", lambda: {"": "/user.slice/grader"})
    group, why = cgroup.create()
    assert why is None and group.version == "v2" and group.describe == "cgroup v2 (memory, pids, cpu)"
    d = group.dirs[""]
    assert os.path.dirname(d) == str(grader) and os.path.basename(d).startswith(f"kinbook-{os.getpid()}-")
    assert (grader / "cgroup.subtree_control").read_text() == "+cpu +memory +pids"
    assert open(os.path.join(d, "pids.max")).read() == "64" and open(os.path.join(d, "cpu.max")).read() == \
        "100000 100000"
    group.set_memory(123 << 20)
    assert open(os.path.join(d, "memory.max")).read() == str(123 << 20)
    assert open(os.path.join(d, "memory.swap.max")).read() == "0"
    with open(os.path.join(d, "memory.events"), "w") as f:
        f.write("low 0\nhigh 0\nmax 3\noom 1\noom_kill 1\n")
    assert group.oom_kills() == 1
    assert group.memory_events() == (1, 3)  # killed once; held at the limit three times
    (grader / "cgroup.controllers").write_text("cpuset io\n")  # not delegated: said so, and rlimits instead
    group, why = cgroup.create()
    assert group is None and "memory, pids are not available" in why


def test_text_printed_by_kinbook_grade_is_inert(tmp_path, capsys):
    """What `kinbook grade` prints of a student's text (an exception message with a terminal's escapes, a carriage
    return, bidirectional controls) cannot set the window title, overwrite a line or print a fake one."""
    from kinbook.cli import main

    code = main(["grade", SOURCE, submission("ansi"), "-o", str(tmp_path / "g"), "--timeout", "300", "--memory", "400",
                 *([] if BWRAP else ["--no-isolation"])])
    out = capsys.readouterr().out
    assert code == 0 and "missing-answer" in out
    assert not set("\x1b\r\x07\u202e\u2028") & set(out), repr(out)
