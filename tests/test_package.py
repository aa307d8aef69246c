"""kinbook as an installed package: its version, its shipped exercises, the extras a command needs, and the public
names of every module (``__all__``)."""

import ast
import filecmp
import importlib
import json
import os
import pkgutil
import re
import sys

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10: the same parser as tomli
    import tomli as tomllib

import pytest

import kinbook
from kinbook import exercises
from kinbook.cli import main
from kinbook.errors import InputError

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_the_version_is_written_once_and_shown_by_the_command(capsys):
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        pyproject = tomllib.load(f)
    assert "version" in pyproject["project"]["dynamic"] and "version" not in pyproject["project"]
    assert pyproject["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "kinbook.__version__"}
    assert re.fullmatch(r"\d+\.\d+\.\d+", kinbook.__version__)
    assert main(["--version"]) == 0
    assert capsys.readouterr().out == f"kinbook {kinbook.__version__}\n"


def test_the_changelog_has_an_unreleased_section():
    text = open(os.path.join(ROOT, "CHANGELOG.md"), encoding="utf-8").read()
    assert "## Unreleased" in text


def test_the_license_file_is_the_one_the_metadata_names():
    pyproject = open(os.path.join(ROOT, "pyproject.toml"), encoding="utf-8").read()
    assert 'license = "MIT"' in pyproject and 'license-files = ["LICENSE"]' in pyproject
    assert open(os.path.join(ROOT, "LICENSE"), encoding="utf-8").read().startswith("MIT License")


def test_the_twelve_exercises_are_the_package_data():
    on_disk = sorted(f[:-6] for f in os.listdir(os.path.join(ROOT, "exercises")) if f.endswith(".ipynb"))
    assert exercises.names() == on_disk and len(on_disk) == 12
    assert exercises.path("ex07").name == "ex07-jacobian.ipynb"
    assert exercises.path("ex07-jacobian.ipynb") == exercises.path("ex07-jacobian")


@pytest.mark.parametrize("name, words", [
    ("ex99", "no shipped exercise 'ex99'"),
    ("ex", "no shipped exercise 'ex'"),     # a prefix that several share
    ("", "no shipped exercise ''"),
    ("../pyproject", "no shipped exercise '../pyproject'"),
    ("/etc/passwd", "no shipped exercise '/etc/passwd'"),
    (7, "an exercise is named by a string, got int"),
])
def test_an_unknown_exercise_is_named_with_the_list(name, words):
    with pytest.raises(InputError, match=re.escape(words)) as err:
        exercises.path(name)
    if isinstance(name, str):
        assert "ex01-revolute-joint-phi" in str(err.value)


def test_exercises_copy_never_overwrites(tmp_path, capsys):
    assert main(["exercises", "copy", "ex01", "ex12", str(tmp_path / "course")]) == 0
    out = capsys.readouterr().out.split()
    assert [os.path.basename(p) for p in out] == ["ex01-revolute-joint-phi.ipynb", "ex12-spatial-joints.ipynb"]
    assert filecmp.cmp(out[0], os.path.join(ROOT, "exercises", "ex01-revolute-joint-phi.ipynb"), shallow=False)
    (tmp_path / "course" / "ex01-revolute-joint-phi.ipynb").write_text("mine")
    assert main(["exercises", "copy", "ex01", str(tmp_path / "course")]) == 2
    assert "already exists: not overwritten" in capsys.readouterr().err
    assert (tmp_path / "course" / "ex01-revolute-joint-phi.ipynb").read_text() == "mine"
    # every name is checked before anything is copied
    assert main(["exercises", "copy", "ex02", "ex99", str(tmp_path / "other")]) == 2
    assert "no shipped exercise 'ex99'" in capsys.readouterr().err and not (tmp_path / "other").exists()
    (tmp_path / "file").write_text("")
    assert main(["exercises", "copy", "ex02", str(tmp_path / "file")]) == 2
    assert "exists and is not a directory" in capsys.readouterr().err


def test_exercises_list_gives_names_and_titles(capsys):
    assert main(["exercises", "list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == exercises.names()
    with exercises.path("ex07").open() as f:
        title = json.load(f)["cells"][0]["source"]
    assert lines[6].split(None, 1)[1] == "".join(title).splitlines()[0].lstrip("# ")


def test_a_command_whose_extra_is_missing_says_which_extra(capsys, monkeypatch):
    import kinbook.cli as cli

    def release(args):
        raise ModuleNotFoundError("No module named 'nbformat'", name="nbformat")

    monkeypatch.setattr(cli, "_cmd_release", release)
    assert main(["release", os.path.join(ROOT, "exercises", "ex01-revolute-joint-phi.ipynb")]) == 2
    err = capsys.readouterr().err
    assert err == ("kinbook: error: `kinbook release` needs nbformat, which comes with the grading extra: "
                   "pip install 'kinbook[grading]'\n")


def test_a_missing_module_outside_the_extras_is_a_bug(capsys, monkeypatch):
    import kinbook.cli as cli

    def table(args):
        raise ModuleNotFoundError("No module named 'kinbook.nothing'", name="kinbook.nothing")

    monkeypatch.setattr(cli, "_cmd_table", table)
    assert main(["table", "ch13_example1"]) == 1
    assert "internal error: ModuleNotFoundError" in capsys.readouterr().err


# ----------------------------------------------------------------------------------------------------- __all__
def _public_modules():
    """Every module of the package whose name has no part starting with an underscore."""
    out = ["kinbook", "kinbook.exercises"]  # (mapped onto exercises/: not under kinbook.__path__)
    for info in pkgutil.walk_packages(kinbook.__path__, "kinbook."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            out.append(info.name)
    return out


def _defined_names(path):
    """Top-level names a module binds (functions, classes, assignments, imports) — read from its source."""
    tree = ast.parse(open(path, encoding="utf-8").read())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in node.targets if isinstance(node, ast.Assign) else [node.target]:
                names |= {n.id for n in ast.walk(target) if isinstance(n, ast.Name)}
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names |= {(a.asname or a.name).split(".")[0] for a in node.names}
    return names


MODULES = _public_modules()


def test_every_public_module_is_found():
    assert {"kinbook.cli", "kinbook.exercises", "kinbook.planar", "kinbook.grading", "kinbook.classroom"} <= set(MODULES)


@pytest.mark.parametrize("name", MODULES)
def test_every_public_module_declares_all(name):
    """``__all__`` names the module's public surface: present, a list of unique strings, each one defined (read
    from the source, so that nothing is imported to check it — a package's lazily imported submodules count)."""
    spec = importlib.util.find_spec(name)
    path = spec.origin
    tree = ast.parse(open(path, encoding="utf-8").read())
    found = [n for n in tree.body if isinstance(n, (ast.Assign, ast.AnnAssign)) and any(
        isinstance(t, ast.Name) and t.id == "__all__" for t in (n.targets if isinstance(n, ast.Assign) else [n.target]))]
    assert found, f"{name} ({os.path.relpath(path, ROOT)}) has no __all__"
    value = found[-1].value
    lazy = "__getattr__" in _defined_names(path)  # names given by a module __getattr__ (PEP 562)
    if lazy or not isinstance(value, (ast.List, ast.Tuple)) or not all(
            isinstance(e, ast.Constant) and isinstance(e.value, str) for e in value.elts):
        # a computed __all__ (e.g. [*mod.__all__, ...]) or lazy names: check the imported module's
        module = importlib.import_module(name)
        listed = list(module.__all__)
        missing = [n for n in listed if not hasattr(module, n)]
    else:
        listed = [e.value for e in value.elts]
        subpackages = {m.rpartition(".")[2] for m in MODULES if m.rpartition(".")[0] == name}
        missing = [n for n in listed if n not in _defined_names(path) | subpackages]
    assert len(listed) == len(set(listed)), f"{name}.__all__ repeats a name"
    assert not missing, f"{name}.__all__ lists names it does not define: {missing}"
    assert all(isinstance(n, str) for n in listed)


def test_kinbook_all_resolves_lazily():
    """kinbook's own __all__ holds names it imports lazily (PEP 562): each one is reachable."""
    for n in kinbook.__all__:
        assert getattr(kinbook, n) is not None, n
    assert kinbook.exercises.names() == exercises.names()  # `import kinbook; kinbook.exercises`, as examples


def test_ruff_lints_the_notebooks_code():
    """ruff reads the chapters' and exercises' code cells too (its notebook support), not only .py files."""
    import shutil
    import subprocess

    ruff = shutil.which("ruff", path=os.path.dirname(sys.executable)) or shutil.which("ruff")
    if ruff is None:
        pytest.skip("ruff is not installed here (it comes with the test extra)")
    files = subprocess.run([ruff, "check", "--show-files", ROOT], capture_output=True, text=True, check=True).stdout
    linted = {os.path.relpath(line.strip(), ROOT) for line in files.splitlines() if line.strip().endswith(".ipynb")}
    for folder in ("chapters", "exercises"):
        notebooks = {os.path.join(folder, f) for f in os.listdir(os.path.join(ROOT, folder)) if f.endswith(".ipynb")}
        assert notebooks and notebooks <= linted, notebooks - linted


def test_the_package_imports_on_python_3_10():
    """tomllib is new in 3.11: every import of it in kinbook falls back to tomli (a dependency below 3.11), so that
    the lowest Python the metadata names can import every module (tryits/ch13.py could not)."""
    bare = []
    for info in pkgutil.walk_packages(kinbook.__path__, "kinbook."):
        path = importlib.util.find_spec(info.name).origin
        tree = ast.parse(open(path, encoding="utf-8").read())
        guarded = {id(n) for t in ast.walk(tree) if isinstance(t, ast.Try) and any(
            isinstance(h.type, ast.Name) and h.type.id in ("ImportError", "ModuleNotFoundError") for h in t.handlers)
            for n in ast.walk(t) if t.body and n in [x for b in t.body for x in ast.walk(b)]}
        for node in ast.walk(tree):
            if isinstance(node, ast.Import) and any(a.name == "tomllib" for a in node.names) and id(node) not in guarded:
                bare.append(f"{os.path.relpath(path, ROOT)}:{node.lineno}")
    assert bare == []
