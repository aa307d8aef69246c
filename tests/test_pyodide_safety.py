"""kinbook in a browser (Pyodide, issue #16): importing kinbook and kinbook.grading, and running a checker, never
touch what a browser lacks — resource limits, processes, signals — and grading a class says it needs a real
machine.

Pyodide itself runs in `make test-web`; here a fresh CPython runs kinbook with an import statement that refuses
those modules to any module of kinbook (numpy, matplotlib and sympy may import them: Pyodide has the modules,
only using them fails).
"""

import subprocess
import sys
import textwrap

import pytest

from kinbook.errors import GradingError

BLOCKED = ("resource", "signal", "subprocess", "multiprocessing", "_posixsubprocess")

HARNESS = textwrap.dedent("""
    import builtins, sys
    BLOCKED = set({blocked!r})
    real_import = builtins.__import__

    def guarded(name, globals=None, locals=None, fromlist=(), level=0):
        importer = (globals or {{}}).get("__name__") or ""
        if level == 0 and name.split(".")[0] in BLOCKED and importer.split(".")[0] == "kinbook":
            raise ImportError(f"{{importer}} imports {{name}}, which a browser (Pyodide) does not have")
        return real_import(name, globals, locals, fromlist, level)

    builtins.__import__ = guarded
""")


def run(code):
    script = HARNESS.format(blocked=BLOCKED) + textwrap.dedent(code)
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)


def test_import_kinbook_and_check_an_answer_without_signals_or_processes():
    done = run("""
        import kinbook, kinbook.grading
        from kinbook.grading import check_phi
        mech = kinbook.examples.load("ch13_example1")
        wrong = check_phi(["x1 - x2 - cos(phi2)", "y1 - y2 + sin(phi2)"], mech.constraint("1"))
        right = check_phi(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"], mech.constraint("1"))
        print(wrong.passed, wrong.mistakes, right.passed)
    """)
    assert done.returncode == 0, done.stderr[-3000:]
    # the answer flips the sign of cos(phi2) in the first row of the revolute joint
    assert done.stdout.split("\n")[-2] == "False ['sign_flip'] True"


def test_the_guard_refuses_a_kinbook_module_that_starts_processes():
    """The harness can fail: the classroom's sandbox starts processes, and importing it is refused."""
    done = run("import kinbook.classroom.sandbox")
    assert done.returncode != 0
    assert "which a browser (Pyodide) does not have" in done.stderr


@pytest.mark.parametrize("entry", ["grade", "grade_submission"])
def test_grading_in_a_browser_says_it_needs_a_real_machine(monkeypatch, tmp_path, entry):
    from kinbook import classroom

    monkeypatch.setattr(sys, "platform", "emscripten")
    submission = tmp_path / "submission.ipynb"
    with pytest.raises(GradingError, match="grading needs a real machine"):
        getattr(classroom, entry)(tmp_path / "exercise.ipynb", [submission] if entry == "grade" else submission)
