"""The live site's own Pyodide (web/pyodide_site.py, make lite): what it serves, and that Pyodide runs it without
compiling a module — Pyodide's Python itself, run by Node, loads the packages the way the browser's kernel does."""

import hashlib
import json
import subprocess
import zipfile
from pathlib import Path

import pytest

from .conftest import ROOT, SITE

STATIC = SITE / "live" / "static" / "pyodide"
CONFIG = SITE / "live" / "jupyter-lite.json"
CDN = "https://cdn.jsdelivr.net/pyodide/v0.27.7/full/"


@pytest.fixture(scope="module")
def lock():
    return json.loads((STATIC / "pyodide-lock.json").read_text())


def startup():
    settings = json.loads(CONFIG.read_text())["jupyter-config-data"]["litePluginSettings"]
    return settings["@jupyterlite/pyodide-kernel-extension:kernel"]["loadPyodideOptions"]["packages"]


def canonical(name):
    return name.lower().replace("_", "-").replace(".", "-")


def test_the_site_serves_what_the_kernel_loads_at_start_and_points_the_rest_at_the_cdn(lock):
    served = {n: p for n, p in lock["packages"].items() if not p["file_name"].startswith("https://")}
    assert {canonical(n) for n in startup()} <= set(served)
    for name, package in served.items():   # each file there, with the digest the lockfile gives (the browser checks)
        assert hashlib.sha256((STATIC / package["file_name"]).read_bytes()).hexdigest() == package["sha256"], name
        for dep in package["depends"]:
            assert canonical(dep) in served, (name, dep)     # nothing the start needs is left to the CDN
    others = [p["file_name"] for n, p in lock["packages"].items() if n not in served]
    assert len(others) > 200 and all(f.startswith(CDN) and f.endswith((".whl", ".zip", ".tar")) for f in others)


def test_the_served_packages_hold_bytecode_in_place_of_sources_and_kinbook_keeps_both(lock):
    for name in ("sympy", "numpy", "matplotlib", "ipython", "pyodide-kernel", "ipywidgets"):
        with zipfile.ZipFile(STATIC / lock["packages"][name]["file_name"]) as z:
            names = z.namelist()
            record = z.read(next(n for n in names if n.endswith(".dist-info/RECORD"))).decode().splitlines()
        pyc = [n for n in names if n.endswith(".pyc")]
        assert pyc and len([n for n in names if n.endswith(".py")]) < len(pyc) / 20, name
        assert sorted(r.split(",")[0] for r in record) == sorted(names), name   # RECORD lists the files it has
    with zipfile.ZipFile(STATIC / lock["packages"]["kinbook"]["file_name"]) as z:
        names = set(z.namelist())
    sources = [n for n in names if n.endswith(".py")]
    assert "kinbook/__init__.py" in sources
    assert {n.rsplit("/", 1)[0] + "/__pycache__/" + n.rsplit("/", 1)[1][:-3] + ".cpython-312.pyc"
            for n in sources} <= names


NODE_CHECK = """
import { loadPyodide } from "PYODIDE_MJS";
const pyodide = await loadPyodide({ indexURL: "STATIC/" });
await pyodide.loadPackage(PACKAGES, { messageCallback: () => {} });
console.log(await pyodide.runPythonAsync(`
import importlib.util, inspect, json, sys
compiled = []
sys.dont_write_bytecode = True
real = importlib.util.source_hash
def spy(data):                    # a module compiled from its source would be hashed first
    compiled.append(len(data))
    return real(data)
importlib.util.source_hash = spy
import importlib._bootstrap_external as be
original = be.SourceLoader.source_to_code
def source_to_code(self, data, path, **kw):
    compiled.append(path)
    return original(self, data, path, **kw)
be.SourceLoader.source_to_code = source_to_code
import sympy, numpy, matplotlib.pyplot, IPython, kinbook, kinbook.planar
from kinbook.book import errata
json.dumps({"compiled": compiled, "sympy": sympy.__spec__.origin, "kinbook": kinbook.__spec__.origin,
            "kinbook_cached": kinbook.__spec__.cached, "source": inspect.getsource(kinbook.planar.Mechanism)[:40],
            "stdlib": __import__("fractions").__spec__.origin})
`));
"""


def test_pyodide_imports_the_start_up_packages_without_compiling_one_module(tmp_path):
    script = tmp_path / "check.mjs"
    runtime = ROOT / ".venv-web" / "npm" / "node_modules" / "pyodide" / "pyodide.mjs"
    script.write_text(NODE_CHECK.replace("PYODIDE_MJS", runtime.as_uri()).replace("STATIC", str(STATIC))
                      .replace("PACKAGES", json.dumps(["sympy", "matplotlib", "ipython", "kinbook"])))
    out = subprocess.run(["node", script], capture_output=True, text=True, timeout=600, check=True).stdout
    result = json.loads(out.strip().splitlines()[-1])
    assert result["compiled"] == [], result["compiled"][:10]
    assert result["sympy"].endswith("site-packages/sympy/__init__.pyc")
    assert result["stdlib"] == "/lib/python312.zip/fractions.pyc"
    assert result["kinbook"].endswith("site-packages/kinbook/__init__.py")        # the source is there...
    assert Path(result["kinbook_cached"]).name == "__init__.cpython-312.pyc"        # ...and its bytecode is used
    assert result["source"].startswith("class Mechanism")                          # kb.reveal reads sources


def test_the_start_up_set_follows_dependencies_by_their_pep_503_names_and_names_what_is_missing():
    import sys

    sys.path.insert(0, str(ROOT / "web"))
    try:
        import pyodide_site
    finally:
        sys.path.remove(str(ROOT / "web"))
    lock = {"packages": {"matplotlib-inline": {"depends": []}, "ipython": {"depends": ["matplotlib_inline"]},
                         "kinbook": {"depends": ["IPython"]}}}
    assert pyodide_site.closure(lock, ["KinBook"]) == ["ipython", "kinbook", "matplotlib-inline"]
    with pytest.raises(SystemExit, match="package 'pandas' is neither in Pyodide"):
        pyodide_site.closure(lock, ["kinbook", "pandas"])
