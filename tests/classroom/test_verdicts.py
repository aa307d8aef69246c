"""Verdicts that depend on neither the clock nor the machine (issue 20, "every grade accounted for").

* A run that fails before any code of the submission ran (a kernel that died before it answered, a sandbox that
  stopped) is the grader's failure: tried again in a new sandbox, and if it persists recorded as ``grader-error``
  with no score — blank in every export, never a 0 the student did not earn — and graded again by the next run.
* ``timeout`` is decided by the kernel's CPU time, ``memory`` by the control group's counters (out-of-memory kills,
  the limit reached) before any clock: a notebook held at its memory limit until it runs out of time is
  ``memory`` on a quiet machine and on a loaded one.
* The kernel's ZeroMQ sockets are Unix sockets in the run's own directory, never TCP ports of the host.
* The numerical libraries' thread pools are pinned to one thread in every mode, whatever the grader's environment
  says: a pool sized by a server's cores would take a kernel past the sandbox's task limit as it starts.
"""

import csv
import json

import pytest

from kinbook.classroom import grade
from kinbook.classroom.sandbox import Sandbox, host
from kinbook.classroom.sandbox.cgroup import PIDS_MAX
from kinbook.classroom.sandbox.protocol import RUNNING, THREAD_ENV, FrameReader, cpu_seconds, wall_seconds, write_frame

from .conftest import BWRAP, ENOUGH, SOURCE, submission

FULL = 6.0


class _Flaky(Sandbox):
    """A sandbox whose first ``failures`` tries fail as a kernel that died before replying does (before any cell)."""

    failures = 0
    tries = []

    def _run(self, header, payload, timeout, limits):
        _Flaky.tries.append(self.starts)
        if len(_Flaky.tries) <= _Flaky.failures:
            return host.Execution("error", "the notebook could not be run: RuntimeError: Kernel died before "
                                           "replying to kernel_info", before_code=True)
        return super()._run(header, payload, timeout, limits)


@pytest.fixture
def flaky(monkeypatch):
    import importlib

    # patched where it is used: grade.py imports Sandbox when it is imported
    monkeypatch.setattr(importlib.import_module("kinbook.classroom.grade"), "Sandbox", _Flaky)
    _Flaky.tries = []

    def failing(n):
        _Flaky.failures = n
        return _Flaky

    return failing


def test_a_kernel_that_dies_before_any_cell_is_tried_again_in_a_new_sandbox(flaky):
    flaky(1)
    with _Flaky(isolation=BWRAP) as sb:
        ex = sb.run(["x = 1 + 1"], ["x"], timeout=ENOUGH, memory_mb=400)
    assert (ex.status, ex.tries) == ("ok", 2) and ex.answers["x"] is not None
    assert _Flaky.tries == [1, 2]  # the second try in a sandbox started afresh


def test_a_grader_failure_that_persists_is_no_score_and_is_graded_again(flaky, tmp_path):
    """After 1 + GRADER_RETRIES tries: ``grader-error``, blank scores in grades.csv and totals.csv, a line saying
    so; the next run grades the same file again without --force (and, the failure gone, gives the full score)."""
    flaky(1 + host.GRADER_RETRIES)
    said = []
    results = grade(SOURCE, [submission("good")], tmp_path, timeout=ENOUGH, memory=400, isolation=BWRAP,
                    progress=said.append)
    (r,) = results
    assert r.status == "grader-error" and {p.status for p in r.parts} == {"grader-error"}
    assert r.message.startswith(f"the grader could not run the notebook ({1 + host.GRADER_RETRIES} tries; the last: "
                                "the notebook could not be run: RuntimeError: Kernel died before replying")
    assert "not the submission's doing" in r.message
    assert len(_Flaky.tries) == 1 + host.GRADER_RETRIES
    with open(tmp_path / "totals.csv", newline="") as f:
        (row,) = list(csv.DictReader(f))
    assert (row["status"], row["score"], row["max_score"]) == ("grader-error", "", "6")  # not a 0
    with open(tmp_path / "grades.csv", newline="") as f:
        assert {(p["status"], p["score"]) for p in csv.DictReader(f)} == {("grader-error", "")}
    assert any(isinstance(s, str) and s.startswith("not graded, through a failure of the grader's") and "good" in s
               for s in said)
    page = (tmp_path / "feedback" / "good" / "tiny.html").read_text(encoding="utf-8")
    assert "Total: not graded yet / 6" in page and "not your doing" in page and "0 / " not in page
    flaky(0)
    again = grade(SOURCE, [submission("good")], tmp_path, timeout=ENOUGH, memory=400, isolation=BWRAP)
    assert [(r.student, r.status, r.score) for r in again] == [("good", "ok", FULL)]


def test_the_lms_files_leave_an_ungraded_submission_blank(flaky, tmp_path):
    from kinbook.classroom.export import export

    flaky(9)
    grade(SOURCE, [submission("good")], tmp_path, timeout=ENOUGH, memory=400, isolation=BWRAP)
    export(tmp_path, tmp_path / "grades-kinbook.csv", fmt="csv")
    with open(tmp_path / "grades-kinbook.csv", newline="") as f:
        (row,) = list(csv.DictReader(f))
    exercise = next(k for k in row if k.endswith(" status"))[:-len(" status")]
    assert (row[exercise], row[f"{exercise} status"], row["total"]) == ("", "grader-error", "")


def test_a_result_written_without_the_running_frame_is_the_graders():
    """The worker writes ``running`` before it sends the first cell; a result without it ran nothing of the
    submission — whatever it says (a student who got past every fence writes after ``running``, never before)."""
    import os

    r, w = os.pipe()
    write_frame(w, {"status": RUNNING})
    write_frame(w, {"status": "ok", "answers": {}})
    os.close(w)
    reader = FrameReader(1 << 20)
    while reader.feed(r):
        pass
    assert reader.frame[0] == {"status": "running"}
    second = FrameReader(1 << 20)
    second.push(reader.rest)
    assert second.frame[0] == {"status": "ok", "answers": {}}
    os.close(r)


class _Counters:
    """A control group's memory counters, as a test sets them."""

    def __init__(self, kills, hits):
        self.events = (kills, hits)

    def memory_events(self):
        return self.events


@pytest.mark.parametrize("after, reached, status", [
    ((0, 0), True, None),
    ((1, 1), False, "memory"),   # a process killed at the limit: memory, whatever the run's own verdict
    ((0, 4), True, "memory"),    # held at the limit and then out of time: memory, not timeout
    ((0, 4), False, None),       # a run that finished: having touched the limit is no verdict
])
def test_memory_is_decided_by_the_control_groups_counters_before_the_clock(after, reached, status):
    sb = Sandbox(isolation=False)
    sb.cgroup = _Counters(*after)
    ex = sb._out_of_memory((0, 0), reached=reached)
    assert (ex.status if ex else None) == status
    sb.cgroup = None


def test_timeout_is_the_kernels_cpu_time_and_the_clock_only_a_backstop():
    """The kernel's RLIMIT_CPU is the timeout itself; the wall clock stops only a notebook that waits, far beyond."""
    assert [cpu_seconds(t) for t in (0.2, 5, 5.5, 60)] == [1, 5, 6, 60]
    assert all(wall_seconds(t) >= 4 * t + 60 for t in (1, 5, 60, 300))


@pytest.mark.parametrize("isolation", [False, True] if BWRAP else [False])
def test_a_cpu_bound_loop_is_stopped_by_its_cpu_time(isolation):
    with Sandbox(isolation=isolation) as sb:
        ex = sb.run(["x = 1", "while True:\n    pass"], ["x"], timeout=3, memory_mb=400)
    assert (ex.status, ex.cell) == ("timeout", 2)
    assert ex.message == "the notebook used up its CPU time (3 s)"  # the kernel's limit, not the clock's
    assert ex.answers["x"] is not None  # read after the cell before


PROBE = """
import json, os, threading, numpy as np
a = np.random.default_rng(0).random((400, 400))
for _ in range(5):
    a = a @ a / 400                                  # BLAS, with as many threads as it was allowed
tasks = len(os.listdir('/proc/self/task'))
connection = json.load(open(os.environ['JUPYTER_RUNTIME_DIR'] + '/connection.json'))
probe = json.dumps({"env": {k: os.environ.get(k) for k in %r}, "tasks": tasks,
                    "transport": connection["transport"], "ip": connection["ip"]})
""" % (sorted(THREAD_ENV),)


@pytest.mark.parametrize("isolation", [False, True] if BWRAP else [False])
def test_thread_pools_are_pinned_whatever_the_graders_environment(isolation, monkeypatch):
    """The grader started with a many-core server's settings (and an affinity-free BLAS would size its pool by the
    cores): in the kernel every pool variable says 1, and the kernel's threads stay few, far under the sandbox's
    task limit (PIDS_MAX counts threads, of the worker and the zygote too)."""
    for name in THREAD_ENV:
        monkeypatch.setenv(name, "96")
    with Sandbox(isolation=isolation) as sb:
        ex = sb.run([PROBE], ["probe"], timeout=ENOUGH, memory_mb=400, audit_hook=False)
    assert ex.status == "ok", ex
    probe = json.loads(ex.answers["probe"]["data"][0][1])
    assert probe["env"] == {k: "1" for k in THREAD_ENV}
    assert probe["tasks"] <= PIDS_MAX // 4, probe   # ipykernel's own threads (11 or 12), no pool per core
    # the kernel's sockets are Unix sockets in the run's own directory: no TCP port of the host that another
    # process could take between the worker choosing it and the kernel binding it (a kernel "died before replying
    # to kernel_info" that way, without bubblewrap, on a busy machine)
    assert probe["transport"] == "ipc" and probe["ip"].startswith(sb.layout.work + "/"), probe



def test_a_file_the_grader_keeps_failing_on_is_left_to_the_instructor_with_the_command(flaky, tmp_path,
                                                                                    monkeypatch):
    """Issue 36: a grader-error is tried again by the next runs, GRADER_RUNS at most; then the run skips it and
    prints the command that reproduces it (no run costs the class its time forever). Meanwhile the student's earlier
    graded attempt counts, not the blank."""
    from kinbook.classroom.intake import GRADER_RUNS

    monkeypatch.setattr(host, "GRADER_RETRIES", 0)
    collected = tmp_path / "collected"
    collected.mkdir()
    (collected / "good.ipynb").write_bytes(open(submission("wrong"), "rb").read())
    out = tmp_path / "graded"
    flaky(0)
    assert [(r.status, r.score) for r in grade(SOURCE, [collected], out, timeout=ENOUGH, memory=400,
                                               isolation=BWRAP)] == [("ok", 0.0)]
    (collected / "good.ipynb").write_bytes(open(submission("good"), "rb").read())  # a new attempt
    flaky(10**6)
    for _ in range(GRADER_RUNS):
        (r,) = grade(SOURCE, [collected], out, timeout=ENOUGH, memory=400, isolation=BWRAP)
        assert r.status == "grader-error"
        with open(out / "totals.csv", newline="") as f:
            (row,) = list(csv.DictReader(f))
        assert (row["status"], row["score"]) == ("ok", "0")  # the graded attempt, not a blank
    tries = len(_Flaky.tries)
    said = []
    assert grade(SOURCE, [collected], out, timeout=ENOUGH, memory=400, isolation=BWRAP, progress=said.append) == []
    assert len(_Flaky.tries) == tries  # not tried a fourth time
    (line,) = [s for s in said if isinstance(s, str) and s.startswith("grader-error")]
    assert f"failed on this file in {GRADER_RUNS} runs" in line
    assert f"kinbook grade {SOURCE} {collected / 'good.ipynb'} -o kinbook-reproduce --timeout {ENOUGH:g} --memory 400" \
        in line
    flaky(0)
    (r,) = grade(SOURCE, [collected], out, timeout=ENOUGH, memory=400, isolation=BWRAP, force=True)
    assert (r.status, r.score) == ("ok", FULL)
