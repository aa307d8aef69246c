"""Grading as an unprivileged user (run by .ci/unprivileged-grading): ``python unprivileged_checks.py CHECKOUT``.

A small hostile batch of tests/classroom's fixtures is graded with bubblewrap in user-namespace mode (no setpriv, no
control group: the zygote's per-process limits and its no-fork filter), then the escape probes run again with the
audit hook off. Every check prints one line; the first that fails stops the script with exit status 1.
"""

import csv
import json
import os
import shutil
import sys
import tempfile

CHECKOUT = sys.argv[1]
HERE = os.path.join(CHECKOUT, "tests", "classroom")
SOURCE = os.path.join(HERE, "source", "tiny.ipynb")
SUBMISSIONS = os.path.join(HERE, "submissions")
BATCH = ["good", "wrong", "flood", "exception", "ansi", "classmate", "edited_title", "fork_hog", "write_outside",
         "second_kernel", "stamps", "recon", "daemon", "memory", "os_exit", "tampered"]
EXPECTED = {  # student: (status, score of 6)
    "good": ("ok", 6), "wrong": ("ok", 0), "flood": ("ok", 6), "exception": ("missing-answer", 4),
    "ansi": ("missing-answer", 4), "classmate": ("wrong-release", 0), "edited_title": ("ok", 6),
    "fork_hog": ("ok", 6), "write_outside": ("ok", 6), "second_kernel": ("ok", 6), "stamps": ("ok", 6),
    "recon": ("ok", 6), "daemon": ("ok", 6), "memory": ("memory", 4), "os_exit": ("error", 4),
    "tampered": ("tampered", 0), "loop": ("timeout", 4),
}
CANARY = "/tmp/kinbook-ci-canary.txt"


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what, flush=True)
    if not ok:
        sys.exit(1)


def refused(value):
    return isinstance(value, str) and value.startswith("refused")


def main():
    from kinbook.classroom import grade
    from kinbook.classroom.notebook import parse_submission
    from kinbook.classroom.sandbox import Sandbox, bwrap

    check(os.geteuid() != 0, f"running as an unprivileged user (uid {os.geteuid()})")
    check(bwrap.available(), f"bubblewrap works here in user-namespace mode ({bwrap._probe() or 'yes'})")
    with open(CANARY, "w") as f:
        f.write("do not delete")
    root = tempfile.mkdtemp(prefix="kinbook-ci-")
    collected, runaway = os.path.join(root, "collected"), os.path.join(root, "runaway")
    os.makedirs(collected)
    os.makedirs(runaway)
    for name in BATCH:
        shutil.copy(os.path.join(SUBMISSIONS, f"{name}.ipynb"), collected)
    shutil.copy(os.path.join(SUBMISSIONS, "loop.ipynb"), runaway)
    out = os.path.join(root, "graded")
    results = grade(SOURCE, [collected], out, timeout=300, memory=400, jobs=2)
    results += grade(SOURCE, [runaway], out, timeout=5, memory=400, jobs=2)
    got = {r.student: (r.status, r.score) for r in results}
    for student, want in sorted(EXPECTED.items()):
        check(got.get(student) == want, f"{student}: {got.get(student)} (expected {want})")
    limits = {r.isolation for r in results if r.isolation}  # ("" for a notebook refused before running)
    check(limits == {"bubblewrap; rlimits, no fork"}, f"limits recorded: {sorted(limits)}")
    with open(os.path.join(out, "grades.csv"), newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    check(all(not (field[:1] in "=+-@") for row in rows for field in row if field), "no formula in grades.csv")
    check(open(CANARY).read() == "do not delete", "the canary outside the sandbox is untouched")

    def probe(sb, name, **kw):
        with open(os.path.join(SUBMISSIONS, f"{name}.ipynb"), "rb") as f:
            data = f.read()
        cells = [c["source"] for c in parse_submission(data) if c["cell_type"] == "code"]
        return sb.run(cells, ["probe", "held", "angle"], timeout=120, memory_mb=400, files={"submission.ipynb": data},
                      audit_hook=False, **kw)

    with Sandbox() as sb:
        ex = probe(sb, "fork_hog")
        check(ex.limits == "rlimits, no fork" and ex.answers["held"] is None and ex.answers["angle"] is not None,
              f"hook off: five 300 MB children cannot be forked ({ex.limits}, {ex.errors[:1]})")
        ex = probe(sb, "second_kernel")
        p = json.loads(ex.answers["probe"]["data"][0][1])
        paths = p["socket_paths"]
        check((paths == "no socket" or all(refused(v) for v in paths.values()))
              and all(refused(v) for v in p["channel_fds"].values()) and p["own_fds"] == {},
              f"hook off: no second kernel can be asked for ({p})")
        ex = probe(sb, "stamps")
        ex = probe(sb, "recon")
        p = json.loads(ex.answers["probe"]["data"][0][1])
        pid1 = p["pid1"]
        check(all(refused(pid1[f"fd{fd}"]) for fd in range(4)) and refused(pid1["environ"]),
              f"hook off: pid 1 ({pid1['comm']}) — its descriptors (the grader's log) and environment are out of reach")
        stamp = 0x7E57_C0DE_1234_5678
        clean = all(stamp not in (s["atime"], s["mtime"]) and not s["xattrs"] for s in p["dirstate"].values())
        check(clean, "hook off: no time or extended attribute of the kept directories reaches the next run")
        check(not [f for f in p["notebooks"] if f != "/home/student/submission.ipynb"],
              "hook off: no notebook, gradebook or canary of the grader's is visible")
        check(p["network"]["1.1.1.1"] != "connected", "hook off: no network")
    steering(root)
    shutil.rmtree(root, ignore_errors=True)
    os.remove(CANARY)


def steering(root):
    """Issue 36, as the unprivileged grader: grades no student can steer (tests/classroom/test_steering.py)."""
    import copy

    import nbformat

    from kinbook.classroom import grade
    from kinbook.classroom.notebook import load_source, student_notebook
    from kinbook.classroom.sandbox import Sandbox

    sys.path.insert(0, HERE)
    from make_submissions import RIGHT_ANGLE, RIGHT_PHI, WRONG_ANGLE, WRONG_PHI

    released = student_notebook(load_source(SOURCE))
    ids = [c["id"] for c in released.cells if c.metadata.get("kinbook", {}).get("answer")]

    def put(path, a=RIGHT_PHI, b=RIGHT_ANGLE, extra=()):
        nb = copy.deepcopy(released)
        for c in nb.cells:
            if c["id"] in ids:
                c.source = a if c["id"] == ids[0] else b
        for k, src in enumerate(extra):
            cell = nbformat.v4.new_code_cell(src)
            cell["id"] = f"student-{k}"
            nb.cells.append(cell)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(json.dumps(nb, ensure_ascii=False).encode("utf-8"))

    c = os.path.join(root, "steering")
    put(os.path.join(c, "alice", "tiny.ipynb"))
    put(os.path.join(c, "mallory", "tiny-alice-9.ipynb"), WRONG_PHI, WRONG_ANGLE)
    put(os.path.join(c, "\uff41\uff4c\uff49\uff43\uff45", "tiny.ipynb"), WRONG_PHI, WRONG_ANGLE)
    put(os.path.join(c, "del", "tiny.ipynb"), extra=["#" + "\x7f" * 990_000] * 7)
    put(os.path.join(c, "prompt", "tiny.ipynb"), ">>> Phi_OA = mech.constraint_phi('1')")
    results = {r.student: r for r in grade(SOURCE, [c], os.path.join(root, "steering-graded"), timeout=300,
                                           memory=400, jobs=2)}
    got = {k: (r.status, r.score) for k, r in results.items()}
    want = {"alice": ("ok", 6), "mallory": ("ok", 0), "\uff41\uff4c\uff49\uff43\uff45": ("duplicate-id", 0),
            "del": ("ok", 6), "prompt": ("ok", 6)}
    check(got == want, f"steering: a classmate's name, a look-alike, 6.9 MB of DEL, a hidden spelling: {got}")
    check(results["prompt"].parts[0].reference.endswith("constraint_phi() (cell 4, as run)"),
          f"steering: reference use seen as it ran ({results['prompt'].parts[0].reference!r})")
    with Sandbox() as sb:
        ex = sb.run(["x = [1, 2]", "import os, signal\nos.kill(-1, signal.SIGKILL)"], ["x"], timeout=120,
                    memory_mb=400, audit_hook=False)
    check(ex.answers is not None and ex.answers.get("x") is not None,
          f"steering: hook off, a worker killed by the notebook: the answers read before are kept ({ex.status})")


if __name__ == "__main__":
    main()
