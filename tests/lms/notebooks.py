"""The source notebooks of docs/lms.md, built from its code blocks, and the three submissions graded from them.

The tests grade exactly what the page tells an instructor to write: each ```python block is a code cell and
each ```text block a raw cell, in the page's order, under the section's heading.
"""

import os
import re
import subprocess
import sys

import nbformat

DOC = os.path.join(os.path.dirname(__file__), os.pardir, os.pardir, "docs", "lms.md")
_BLOCK = re.compile(r"^```(python|text)\n(.*?)^```$", re.M | re.S)

# A wrong answer (row 1 with a sign error) and the rows kinbook's checker is given in the test's own process to
# know which messages the feedback must carry.
WRONG_ROWS = ["x1 - x2 - cos(phi2)", "y1 - y2 + sin(phi2)"]
WRONG_CELL = "from sympy import cos, sin\nPhi_OA = sp.Matrix([" + ", ".join(WRONG_ROWS) + "])"
STUDENTS = ("correct", "wrong", "blank")


def expected(answer, **options):
    """kinbook's verdict on ``answer`` in the test's own process: what the tool's feedback must carry.

    Called once first to warm up: kinbook's checkers still read answers under a 3 s wall-clock budget
    (issue #14), which a loaded machine's first, cold call can exceed.
    """
    import kinbook
    from kinbook.grading import check_phi

    joint = kinbook.examples.load("ch13_example1").constraint("1")
    check_phi(answer, joint, **options)
    return check_phi(answer, joint, **options)


def blocks(section):
    """(kind, source) of every python/text block under the page's '## <section>' heading."""
    with open(DOC, encoding="utf-8") as f:
        text = f.read()
    start = text.index(f"\n## {section}\n")
    end = text.find("\n## ", start + 1)
    return [(kind, source.rstrip("\n")) for kind, source in _BLOCK.findall(text[start : end if end > 0 else None])]


def _notebook(cells):
    nb = nbformat.v4.new_notebook(cells=cells)
    # what `make lab` writes: the tools must find (nbgrader) or replace (otter) this kernel
    nb.metadata["kernelspec"] = {"name": "kinbook", "display_name": "Python (kinbook)", "language": "python"}
    return nb


_NBGRADER_ROLES = {  # first line of the block -> nbgrader cell metadata
    "# setup cell": dict(grade=False, solution=False, locked=True),
    "# answer cell": dict(grade=False, solution=True, locked=False),
    "# test cell": dict(grade=True, solution=False, locked=True),
    "# hidden test cell": dict(grade=True, solution=False, locked=True),
}


def nbgrader_source():
    """The nbgrader source notebook; each cell's grade_id is its role ("test", "hidden_test" …)."""
    cells = []
    for kind, source in blocks("nbgrader"):
        if kind != "python":
            continue
        role = source.split(":", 1)[0]
        meta = dict(_NBGRADER_ROLES[role], schema_version=3, grade_id=role[2:].replace(" cell", "").replace(" ", "_"))
        if meta["grade"]:
            meta["points"] = int(re.search(r"points=(\d+)", source).group(1))
        cell = nbformat.v4.new_code_cell(source)
        cell.metadata["nbgrader"] = meta
        cells.append(cell)
    return _notebook(cells)


def nbgrader_solution():
    """The answer cell's solution, between nbgrader's markers."""
    source = next(c.source for c in nbgrader_source().cells if c.metadata.nbgrader["grade_id"] == "answer")
    return source.split("### BEGIN SOLUTION\n")[1].split("\n### END SOLUTION")[0]


def otter_source():
    """The otter-assign source notebook."""
    make = {"python": nbformat.v4.new_code_cell, "text": nbformat.v4.new_raw_cell}
    return _notebook([make[kind](source) for kind, source in blocks("otter-grader")])


def otter_solution():
    source = next(c.source for c in otter_source().cells if c.source.endswith("# SOLUTION"))
    return source.removesuffix("# SOLUTION").rstrip()


def answers(solution):
    """Each student's answer cell: None leaves the released cell as it is (unanswered)."""
    return {"correct": solution, "wrong": WRONG_CELL, "blank": None}


def tool_env(home):
    """The environment the tools run in: this venv's scripts first (nbgrader calls `alembic`), and a private
    HOME so that no Jupyter configuration or kernel of the machine's user takes part."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("JUPYTER")}
    env["HOME"] = str(home)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    return env


def run(args, cwd, env, check=True):
    """Run a tool's command line; on failure the assertion shows its output."""
    proc = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True, timeout=600)
    if check:
        assert proc.returncode == 0, f"{' '.join(args)} failed ({proc.returncode}):\n{proc.stdout}\n{proc.stderr}"
    return proc
