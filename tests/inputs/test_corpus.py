"""The bad-input corpus (tests/inputs/corpus.py), each case run in a worker process under a hard timeout.

Every case asserts the exact exception class (from kinbook.errors) and words of its message that name the
thing concerned, or the value / exit status the input must give. A case that does not answer within its
timeout fails as a hang (the worker is killed and a new one started); one that ends the worker fails as such;
one that creates the canary file fails as code execution.

A case's timeout counts the worker's CPU time, not the clock, so that a loaded machine (slower, not wrong) does
not fail a case; a case that blocks without computing (a FIFO opened for reading) is caught by a wall-clock
bound far beyond it (:data:`WALL_FACTOR`).
"""

import json
import os
import selectors
import subprocess
import sys
import time

import pytest

from . import corpus

WORKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "worker.py")
CASES = corpus.cases()
#: A case that has not answered after this many times its timeout of wall-clock time (at least WALL_MIN s) is
#: a hang even if it used no CPU time.
WALL_FACTOR, WALL_MIN = 10, 120.0


def cpu_seconds(pid):
    """CPU time (user + system, its waited-for children included) of a live process, from /proc; None where there
    is no /proc (the wall-clock bound then decides alone)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return sum(int(x) for x in fields[11:15]) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


class Worker:
    """One long-lived worker process (imports once; cases take milliseconds), restarted after a hang."""

    def __init__(self, directory):
        self.directory = directory
        self.proc = None

    def start(self):
        log = open(os.path.join(self.directory, "worker-stderr.log"), "ab")
        self.proc = subprocess.Popen([sys.executable, WORKER], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=log, cwd=self.directory, text=True, bufsize=1)
        log.close()
        ready = self._line(180)
        if ready is None or "ready" not in ready:
            raise RuntimeError(f"the corpus worker did not start: {ready!r}")

    def _line(self, timeout):
        sel = selectors.DefaultSelector()
        sel.register(self.proc.stdout, selectors.EVENT_READ)
        try:
            if not sel.select(timeout):
                return None
        finally:
            sel.close()
        line = self.proc.stdout.readline()
        return json.loads(line) if line else {"outcome": "died", "returncode": self.proc.wait(10)}

    def run(self, cid, timeout):
        if self.proc is None or self.proc.poll() is not None:
            self.start()
        cpu0 = cpu_seconds(self.proc.pid)
        wall_end = time.monotonic() + max(WALL_FACTOR * timeout, WALL_MIN)
        self.proc.stdin.write(cid + "\n")
        self.proc.stdin.flush()
        while (out := self._line(0.25)) is None:
            cpu = cpu_seconds(self.proc.pid)
            used = None if cpu is None or cpu0 is None else cpu - cpu0
            if (used is not None and used > timeout) or time.monotonic() > wall_end:
                self.stop()
                return {"outcome": "hang", "timeout": timeout, "cpu_seconds": used}
        if out.get("outcome") == "died":
            self.proc = None
        return out

    def stop(self):
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(10)
        self.proc = None


@pytest.fixture(scope="module")
def worker(tmp_path_factory):
    w = Worker(str(tmp_path_factory.mktemp("corpus")))
    yield w
    w.stop()


def test_the_corpus_is_large_seeded_and_covers_every_group():
    assert len(CASES) >= 500
    assert [c.id for c in corpus.cases()] == [c.id for c in CASES]  # the same list every time (seeded)
    groups = {c.group for c in CASES}
    assert groups >= {"code execution", "hang", "syntax and names", "wrong types", "sympy trees", "drivers",
                      "file keys", "file structure", "python api", "public functions", "singular configurations",
                      "command line", "checkers", "complex values", "older open cases", "course gradebook", "course names",
                      "course own inputs", "course rosters", "course sources"}


@pytest.mark.parametrize("case", [
    pytest.param(c, id=c.id, marks=[pytest.mark.xfail(strict=True, reason=c.xfail)] if c.xfail else [])
    for c in CASES
])
def test_case(case, worker):
    res = worker.run(case.id, case.timeout)
    assert res["outcome"] not in ("hang", "died"), f"{case.id}: {res}"
    assert not res["canary"], f"{case.id}: the input ran code (the canary file was written)"
    if case.expect == "ok":
        assert res["outcome"] == "returned", f"{case.id} raised {res.get('cls')}: {res.get('message')}"
        assert res["checked"], f"{case.id}: wrong value {res['value']}"
        return
    if case.expect == "cli":
        assert res["outcome"] == "returned", f"{case.id} raised {res.get('cls')}: {res.get('message')}"
        err = res["stderr"].strip()
        assert res["status"] == 2, f"{case.id}: exit status {res['status']}, stderr {err!r}"
        assert "\n" not in err and "Traceback" not in err, f"{case.id}: not one line: {err!r}"
        for w in case.words:
            assert w in err, f"{case.id}: {w!r} not in {err!r}"
        return
    assert res["outcome"] == "raised", f"{case.id}: no error, returned {res.get('value')}"
    assert res["module"] == "kinbook.errors", f"{case.id}: raw {res['cls']}: {res['message']}\n{res.get('traceback')}"
    assert res["cls"] == case.expect, f"{case.id}: {res['cls']} instead of {case.expect}: {res['message']}"
    for w in case.words:
        assert w in res["message"], f"{case.id}: {w!r} not in {res['message']!r}"
