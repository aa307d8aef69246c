"""Regenerate the fixture notebooks: ``python tests/classroom/make_submissions.py``.

``source/tiny.ipynb`` is a two-part instructor notebook; every file in ``submissions/`` is its released
version (``kinbook.classroom.release``) with the answer cells filled in by a (mostly ill-behaved) student.
The files are committed: the tests grade these real notebooks, they do not build them.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import nbformat

HERE = Path(__file__).parent
SOURCE = HERE / "source" / "tiny.ipynb"
OUT = HERE / "submissions"

SETUP = '''import numpy as np
import sympy as sp
import kinbook
from kinbook.classroom import part
mech = kinbook.examples.load("ch13_example1")
x1, y1, phi1, x2, y2, phi2 = list(mech.q)[:6]'''

RIGHT_PHI = "Phi_OA = sp.Matrix([x1 - x2 + sp.cos(phi2), y1 - y2 + sp.sin(phi2)])"
RIGHT_ANGLE = "angle = float(3 * np.pi / 4 + 100 * 0.01)"
WRONG_PHI = "Phi_OA = sp.Matrix([x1 + x2 + sp.cos(phi2), y1 + y2])"
WRONG_ANGLE = "angle = 1.0"


def make_source():
    cells = [
        nbformat.v4.new_markdown_cell("# Tiny exercise (test fixture)\nΦ of revolute joint 1 of example 1, and the "
                                      "crank angle at t = 0.01."),
        nbformat.v4.new_code_cell(SETUP),
        nbformat.v4.new_markdown_cell("**(a)** Φ of revolute joint 1, in `Phi_OA`."),
        nbformat.v4.new_code_cell("### BEGIN SOLUTION\n" + RIGHT_PHI + "\n### END SOLUTION"),
        nbformat.v4.new_code_cell('part("revolute", points=4, answer="Phi_OA", check="phi", target=mech.constraint("1"))'),
        nbformat.v4.new_markdown_cell("**(b)** φ2 at t = 0.01 (radians), in `angle`."),
        nbformat.v4.new_code_cell("### BEGIN SOLUTION\n" + RIGHT_ANGLE + "\n### END SOLUTION"),
        nbformat.v4.new_code_cell(
            "### BEGIN HIDDEN CHECKS\n"
            "q = mech.solve_position(0.01)\n"
            'part("angle", points=2, answer="angle", check="value", expected=q[mech.index("phi2")], angles=True)\n'
            "### END HIDDEN CHECKS"),
    ]
    nb = nbformat.v4.new_notebook(cells=cells)
    for i, c in enumerate(nb.cells):
        c["id"] = f"tiny-{i:02d}"
    nb.metadata["kernelspec"] = {"name": "kinbook", "display_name": "kinbook", "language": "python"}
    SOURCE.parent.mkdir(exist_ok=True)
    nbformat.write(nb, str(SOURCE))


#: file name → (code of answer cell (a), code of answer cell (b), extra code cells appended at the end)
CASES = {
    "good": (RIGHT_PHI, RIGHT_ANGLE, []),
    "wrong": (WRONG_PHI, WRONG_ANGLE, []),
    "partial": (RIGHT_PHI, "# I did not finish\nraise NotImplementedError()", []),
    "loop": (RIGHT_PHI, "while True:\n    pass", []),
    "memory": (RIGHT_PHI, "hog = []\nwhile True:\n    hog.append(np.ones(10**6))", []),
    "sys_exit": (RIGHT_PHI, "import sys\nsys.exit('bye')\n" + RIGHT_ANGLE, []),
    "os_exit": (RIGHT_PHI, "import os\nos._exit(0)\n" + RIGHT_ANGLE, []),
    "kill_kernel": (RIGHT_PHI, "import os, signal\ntry:\n    os.kill(os.getpid(), signal.SIGKILL)\nexcept PermissionError:\n"
                               "    pass\nsignal.raise_signal(signal.SIGKILL)", []),
    "monkeypatch": (WRONG_PHI, WRONG_ANGLE, [
        "import kinbook.grading, kinbook.classroom.parts\n"
        "from kinbook.grading import CheckResult\n"
        "always = lambda *a, **k: CheckResult(True, 1.0, ['perfect'])\n"
        "for name in ['check_phi', 'check_value', 'check_jacobian', 'check_nu', 'check_gamma']:\n"
        "    setattr(kinbook.grading, name, always)\n"
        "kinbook.classroom.parts.Part.run = lambda self, *a, **k: always()"]),
    "patch_serializer": (WRONG_PHI, WRONG_ANGLE, [
        "import kinbook.classroom.serialize as s\n"
        "s.dumps = lambda names, ns: ('{\"answers\": {\"Phi_OA\": {\"kind\": \"sympy\", \"shape\": [1, 1], '\n"
        "                             '\"data\": [[\"__import__\", [\"Symbol\", \"os\"]]]}, \"score\": 6}}')"]),
    "fake_score": (WRONG_PHI, WRONG_ANGLE, [
        "print('Score: 6/6 (100%)')\n"
        "print('{\"answers\": {\"Phi_OA\": {\"kind\": \"array\", \"shape\": [], \"data\": [0]}}}')\n"
        "from IPython.display import display, HTML\ndisplay(HTML('<b>All tests passed</b>'))"]),
    "read_source": (
        "import os, glob, kinbook\n"
        "repo = os.path.dirname(os.path.dirname(kinbook.__file__))\n"
        "stolen = open(os.path.join(repo, 'tests', 'classroom', 'source', 'tiny.ipynb')).read()\n"
        "Phi_OA = sp.Matrix([x1 - x2 + sp.cos(phi2), y1 - y2 + sp.sin(phi2)])",
        "import os\nfound = os.listdir('/')\n" + RIGHT_ANGLE, []),
    "write_outside": (RIGHT_PHI, RIGHT_ANGLE, [
        "import os, shutil\nopen('inside.txt', 'w').write('mine')  # allowed: the temporary copy\n"
        "for attempt in [lambda: open('/tmp/kinbook-evil.txt', 'w').write('pwned'),\n"
        "                lambda: os.remove('/tmp/kinbook-canary.txt'),\n"
        "                lambda: os.rename('/tmp/kinbook-canary.txt', '/tmp/kinbook-moved.txt'),\n"
        "                lambda: shutil.rmtree('/tmp/kinbook-canary-dir'),\n"
        "                lambda: os.system('touch /tmp/kinbook-evil.txt'),\n"
        "                lambda: __import__('subprocess').run(['touch', '/tmp/kinbook-evil.txt']),\n"
        "                lambda: __import__('socket').create_connection(('example.org', 80))]:\n"
        "    try:\n        attempt()\n    except PermissionError as e:\n        print('blocked:', e)\n"
        "raise RuntimeError('still graded: the answers above were assigned')"]),
}


def main():
    make_source()
    sys.path.insert(0, str(HERE.parents[1]))
    from kinbook.classroom.notebook import load_source, student_notebook

    released = student_notebook(load_source(SOURCE))
    OUT.mkdir(exist_ok=True)
    answer_ids = [c["id"] for c in released.cells if c.metadata.get("kinbook", {}).get("answer")]
    for name, (a, b, extra) in CASES.items():
        nb = copy.deepcopy(released)
        for c in nb.cells:
            if c["id"] == answer_ids[0]:
                c.source = a
            elif c["id"] == answer_ids[1]:
                c.source = b
        for k, src in enumerate(extra):
            cell = nbformat.v4.new_code_cell(src)
            cell["id"] = f"student-{k}"
            nb.cells.append(cell)
        nbformat.write(nb, str(OUT / f"{name}.ipynb"))
    nb = copy.deepcopy(released)  # tampered: a locked cell edited to make the check pass
    for c in nb.cells:
        if c["id"] == answer_ids[0]:
            c.source = WRONG_PHI
        if "part(\"revolute\"" in c.source:
            c.source = c.source.replace("points=4", "points=400")
    nbformat.write(nb, str(OUT / "tampered.ipynb"))
    nb = copy.deepcopy(released)  # a locked cell deleted
    nb.cells = [c for c in nb.cells if "mech = kinbook" not in c.source]
    nbformat.write(nb, str(OUT / "deleted_cell.ipynb"))
    (OUT / "corrupt.ipynb").write_text('{"cells": [{"cell_type": "code", "source": "Phi_OA = 1"', encoding="utf-8")
    (OUT / "not_a_notebook.ipynb").write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00 binary garbage")


if __name__ == "__main__":
    main()
