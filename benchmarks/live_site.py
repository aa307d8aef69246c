"""Live site (JupyterLite) time to interactive, first and second visit, and where the time goes (issue 25 item 6).

Run:  .venv-web/bin/python benchmarks/live_site.py [REPS] [--uncompiled] [--no-preload]
      (default: 2 repetitions; needs make book lite)

``--uncompiled`` serves the official Pyodide distribution as it is (web/pyodide_site.py's dist/: sources only) in
place of the site's compiled copy, as the site did before; ``--no-preload`` drops ``loadPyodideOptions`` from the
site's jupyter-lite.json: the kernel then loads numpy, sympy, matplotlib and scipy one after another in the first
cell (``%pip install kinbook`` pulls them in). The same build, for the comparison.

The site as built, served from 127.0.0.1 like a static host (tests/web: Cache-Control max-age=600), in Debian's
chromium driven by Playwright, every other host refused. Each
repetition starts an empty browser profile (first visit: nothing cached) and opens the live notebook again in the
same profile (second visit: warm HTTP cache, the case the target is about).

1. **Components** — a bare page with Pyodide alone, on the main thread, each step timed in the page:
   ``loadPyodide``; ``loadPackage`` and ``import`` of numpy, sympy, matplotlib (the font cache separately), scipy;
   kinbook's wheel from the site and the imports of a chapter's first cell.
2. **The live notebook** (13-3), as a student meets it: the notebook shown; the first cell (it installs kinbook
   and imports what the chapter needs, in the background while the student reads); the chapter's own first code
   cell (its imports): **time to interactive** is when that cell has run, counted from the page load.

Wall-clock figures depend on what else runs on the machine: the load average is printed with them, and the browser's
CPU seconds (which do not grow with other work) next to the wall time.
"""

from __future__ import annotations

import json
import os
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.web.conftest import (  # noqa: E402
    Clock,
    RefusingProxy,
    StaticServer,
    _browser_args,
    site_copy,
)

NOTEBOOK = "13-3-position-analysis.ipynb"
IMPORT_CELL_MARKER = "kb.notebook_setup()"   # the chapter's first code cell ends with it
INTERACTIVE = "chapter's first code cell done = interactive"

# The bare-Pyodide page: each step's wall time, measured in the page (performance.now()), into window.bench.
BENCH_PAGE = """<!doctype html><meta charset="utf-8"><title>pyodide steps</title>
<script src="static/pyodide/pyodide.js"></script>
<script>
const WHEEL = new URL(WHEEL_PATH, location.href).href, IMPORTS = IMPORTS_CODE;
window.bench = (async () => {
  const out = {}, t = () => performance.now() / 1000;
  let t0 = t();
  const py = await loadPyodide({indexURL: "static/pyodide/"});
  out["loadPyodide"] = t() - t0;
  const step = async (name, packages, code) => {
    let t1 = t();
    if (packages.length) await py.loadPackage(packages, {messageCallback: () => {}});
    out[name + ": load"] = t() - t1;
    t1 = t();
    await py.runPythonAsync(code);
    out[name + ": import"] = t() - t1;
  };
  await step("numpy", ["numpy"], "import numpy");
  await step("sympy (+ mpmath)", ["sympy"], "import sympy");
  await step("matplotlib, font cache", ["matplotlib"], "import matplotlib.font_manager");
  await step("matplotlib.pyplot", [], "import matplotlib.pyplot");
  await step("scipy (+ openblas)", ["scipy"], "import scipy.linalg, scipy.sparse.linalg");
  await step("kinbook wheel (micropip)", ["micropip"],
             "import micropip\\nawait micropip.install(" + JSON.stringify(WHEEL) + ", deps=False)");
  await step("the chapter's kinbook imports", [], IMPORTS);
  out["total"] = t() - t0;
  return out;
})();
</script>"""

IMPORTS = """import kinbook as kb
from kinbook.book import errata, printed, verify
from kinbook.book.notation import equations, latex, local_points
from kinbook.planar import plotting
kb.notebook_setup()"""


def load_average():
    return os.getloadavg()[0]


def components(context, server):
    page = context.new_page()
    page.set_default_timeout(600_000)
    page.goto(f"{server.url}/live/bench.html")
    result = page.evaluate("() => window.bench")
    page.close()
    return result


def code_cell(page, marker):
    return page.locator(".jp-Notebook .jp-CodeCell", has_text=marker).first


def run(page, cell):
    """Run a cell (click its prompt, the toolbar's run button) and wait for its execution count."""
    cell.locator(".jp-InputPrompt").click()
    page.locator(".jp-Toolbar [data-command='notebook:run-cell-and-select-next']").first.click()
    prompt = cell.locator(".jp-InputPrompt")
    page.wait_for_function("p => /\\[\\d+\\]/.test(p.textContent)", arg=prompt.element_handle(), timeout=600_000)


def live_visit(context, server):
    page = context.new_page()
    page.set_default_timeout(600_000)
    clock = Clock()
    page.goto(f"{server.url}/live/notebooks/index.html?path={NOTEBOOK}")
    first = code_cell(page, "%pip install")
    first.wait_for()
    shown = clock()
    run(page, first)
    installed = clock()
    run(page, code_cell(page, IMPORT_CELL_MARKER))
    interactive, cpu = clock(), clock.cpu()
    stderr = page.locator(".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stderr']").count()
    page.close()
    return {"notebook shown": shown, "first cell (install + imports) done": installed,
            INTERACTIVE: interactive, "browser CPU s": cpu,
            "stderr boxes": stderr}


def table(rows, title):
    names = list(rows[0])
    print(f"\n{title}")
    print(f"| step | {' | '.join(f'run {k + 1}' for k in range(len(rows)))} | median |")
    print("|---|" + "---:|" * (len(rows) + 1))
    for n in names:
        values = [r[n] for r in rows]
        print(f"| {n} | {' | '.join(f'{v:.2f}' for v in values)} | {statistics.median(values):.2f} |")


def kernel_settings(copy, change):
    """Apply ``change`` to the Pyodide kernel's settings in the copy's jupyter-lite.json."""
    config_path = copy / "live" / "jupyter-lite.json"
    config = json.loads(config_path.read_text())
    change(config["jupyter-config-data"]["litePluginSettings"]["@jupyterlite/pyodide-kernel-extension:kernel"])
    config_path.unlink()  # a hard link into build/site/: write a new file
    config_path.write_text(json.dumps(config, indent=2))


def without_preload(copy):
    kernel_settings(copy, lambda settings: settings.pop("loadPyodideOptions", None))


def uncompiled(copy):
    """The site as it was: the official distribution, sources only (web/pyodide_site.py's dist/), in place of the
    compiled copy, and the kernel's start loading only official packages (kinbook and ipywidgets then come from
    the first cell's %pip)."""
    static = copy / "live" / "static" / "pyodide"
    shutil.rmtree(static)
    shutil.copytree(ROOT / ".venv-web" / "pyodide" / "dist", static, copy_function=os.link)
    official = json.loads((static / "pyodide-lock.json").read_text())["packages"]

    def official_only(settings):
        options = settings.get("loadPyodideOptions")
        if options:
            options["packages"] = [n for n in options["packages"] if n in official]
    kernel_settings(copy, official_only)


def main(reps=2, preload=True, compiled=True):
    from playwright.sync_api import sync_playwright

    with tempfile.TemporaryDirectory() as tmp:
        copy = site_copy(Path(tmp) / "site")
        if not compiled:
            uncompiled(copy)
        if not preload:
            without_preload(copy)
        wheel = next((copy / "live" / "pypi").glob("kinbook-*.whl"))
        (copy / "live" / "bench.html").write_text(
            BENCH_PAGE.replace("WHEEL_PATH", json.dumps(f"pypi/{wheel.name}")).replace("IMPORTS_CODE", json.dumps(IMPORTS)))
        proxy, server = RefusingProxy(), StaticServer(copy)
        print(f"Pyodide's packages compiled: {'yes' if compiled else 'no (--uncompiled)'}; "
              f"packages preloaded while the kernel starts: {'yes' if preload else 'no (--no-preload)'}; "
              f"load average at start: {load_average():.2f} (2 cores)")
        parts, first, second = [], [], []
        with sync_playwright() as pw:
            for k in range(reps):
                with tempfile.TemporaryDirectory() as profile:
                    context = pw.chromium.launch_persistent_context(profile, viewport={"width": 1280, "height": 1000},
                                                                    **_browser_args(proxy))
                    first.append(live_visit(context, server))
                    second.append(live_visit(context, server))
                    parts.append(components(context, server))
                    context.close()
                print(f"  repetition {k + 1}: interactive {first[-1][INTERACTIVE]:.1f} s (first visit), "
                      f"{second[-1][INTERACTIVE]:.1f} s (second); load average {load_average():.2f}")
        server.close()
        proxy.shutdown()
        assert proxy.requests == [], proxy.requests
    table(parts, "Bare Pyodide, seconds per step (warm cache: measured after the two visits)")
    table(first, "Live notebook 13-3, first visit (empty browser cache), seconds after the page load")
    table(second, "Live notebook 13-3, second visit (warm browser cache), seconds after the page load")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(int(args[0]) if args else 2, preload="--no-preload" not in sys.argv, compiled="--uncompiled" not in sys.argv)
