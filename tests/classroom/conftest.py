import os

import pytest

from kinbook.classroom import grade

# The fixture notebooks are hostile on purpose (infinite loops, memory hogs, os._exit): `pytest --nbval` must
# never run them outside the grader's sandbox.
collect_ignore_glob = ["submissions/*", "source/*"]

HERE = os.path.dirname(__file__)
SOURCE = os.path.join(HERE, "source", "tiny.ipynb")
SUBMISSIONS = os.path.join(HERE, "submissions")
CANARY = "/tmp/kinbook-canary.txt"
CANARY_DIR = "/tmp/kinbook-canary-dir"
EVIL = "/tmp/kinbook-evil.txt"


def submission(name):
    return os.path.join(SUBMISSIONS, f"{name}.ipynb")


@pytest.fixture(scope="session")
def batch(tmp_path_factory):
    """Every fixture submission graded once, in one batch, two at a time (timeout 5 s, memory 400 MB)."""
    out = tmp_path_factory.mktemp("graded")
    with open(CANARY, "w") as f:
        f.write("do not delete")
    os.makedirs(CANARY_DIR, exist_ok=True)
    if os.path.exists(EVIL):
        os.remove(EVIL)
    files = sorted(os.path.join(SUBMISSIONS, f) for f in os.listdir(SUBMISSIONS) if f.endswith(".ipynb"))
    before = {f: (open(f, "rb").read(), os.stat(f).st_mtime_ns) for f in files}
    import time

    t0 = time.monotonic()
    results = grade(SOURCE, files, out, timeout=5, memory=400, jobs=2)
    seconds = time.monotonic() - t0
    return {"out": out, "results": {r.student: r for r in results}, "before": before, "seconds": seconds,
            "files": files}
