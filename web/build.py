"""Build kinbook's static website from the stored notebooks: the book and the live notebooks.

    python web/build.py book    # Jupyter Book 1 (Sphinx)  -> build/site/        (make book)
    python web/build.py lite    # JupyterLite + Pyodide    -> build/site/live/   (make lite)

Both take whatever notebooks are in chapters/ as they are stored (never executed here: their outputs are
kept true by nbval in `make test`), copy them into a staging folder under build/web/ and adapt the copies:

* the book's pages get an "Open live" link to the same notebook in the live site (``../live/...``), and each
  try-it an instant check below its cell (``data-tryit``: issue 35) — answered in the page by web/instant/'s
  script over mathjs, with the page's JSON written by kinbook.book.instant (run with the lab environment's
  Python, where kinbook is installed: KINBOOK_PYTHON, default .venv/bin/python);
* the live copies get the Pyodide kernel (kernelspec ``python``) and a first cell that installs kinbook
  from the site's own package index (piplite);
* the live site's pages get web/lite/kinbook-live.js, which says in the page when Python (Pyodide) cannot be
  downloaded.

Everything a page needs is served by the site itself: MathJax, kinbook's wheel, and Pyodide — its runtime and
the packages the kernel loads at start, compiled to bytecode (web/pyodide_site.py; only packages a cell installs
later come from the official Pyodide CDN). Nothing here uses the network but web/pyodide_site.py's first
assembly (PyPI): the tools and assets are installed beforehand by `make web-env` (pip, requirements/web.txt; npm
ci, web/package-lock.json).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pyodide_site
from packaging.version import Version

ROOT = Path(__file__).resolve().parent.parent
WEB = ROOT / "web"
STAGE = ROOT / "build" / "web"
SITE = ROOT / "build" / "site"
LIVE = SITE / "live"
VENV = Path(sys.prefix)
NODE_MODULES = VENV / "npm" / "node_modules"   # npm ci of web/package.json (make web-env)
WHEELS = VENV / "wheels"                       # pure-Python wheels for the browser kernel (make web-env)

# The parts of MathJax's es5/ build the book loads: the TeX-to-HTML component and what it loads on demand
# (TeX extensions, fonts, the accessibility menu); not the other combined components (SVG, MathML input).
MATHJAX_PARTS = ("tex-chtml.js", "input", "output/chtml", "a11y", "sre", "ui", "adaptors")

# The page of the live site that opens one notebook (JupyterLite's Notebook interface), from a book page.
LIVE_NOTEBOOK = "../live/notebooks/index.html?path={name}"

# The instant checks (issue 35): mathjs's browser bundle and kinbook's two scripts, served from <site>/instant/ with
# each page's JSON; the first try-it of a page loads the page script, which loads the other two after the page.
INSTANT_SCRIPTS = ("math.js", "kinbook-instant.js", "kinbook-instant-page.js")
TRY_IT_CALL = re.compile(r'kb\.try_it\("([^"]+)"')
INSTANT_STYLE = ("<style>.kinbook-instant{border-left:4px solid #1f6feb;background:#f6f8fa;padding:6px 10px;margin:4px 0 12px}"
                 ".kinbook-instant textarea{width:100%;font-family:monospace;font-size:90%}"
                 ".kinbook-instant-bar{margin:4px 0}.kinbook-instant-lang{float:right}"
                 "[data-verdict=pass]{color:#1a7f37}[data-verdict=fail],[data-verdict=refused]{color:#cf222e}"
                 "[data-verdict=undecided]{color:#9a6700}.kinbook-instant-mistake,.kinbook-instant-hint{color:#24292f}"
                 ".kinbook-instant [data-echo]{overflow-x:auto}"  # a long row's echo scrolls instead of being cut
                 "</style>")
LAB_PYTHON = Path(os.environ.get("KINBOOK_PYTHON", ROOT / ".venv" / "bin" / "python"))

# What the first cell of each live notebook runs. kinbook and ipywidgets (for the sliders), with numpy, scipy,
# sympy and matplotlib, are already there: web/lite/jupyter-lite.json has the kernel load them, compiled, from the
# site's own Pyodide while it starts (loadPyodideOptions; web/pyodide_site.py); %pip only makes sure of them (from
# the site's piplite index). Then matplotlib's font list, which Pyodide builds anew at each visit: here, quietly,
# rather than as a red "Matplotlib is building the font cache" box under the chapter's first plot.
# When kinbook itself cannot be installed (a copy of the site without its wheel), %pip says nothing and the next
# cell would fail with "No module named 'kinbook'": the cell says so plainly instead (its red stderr box).
INSTALL_CELL = """\
# Running in your browser (JupyterLite): this cell makes sure kinbook and ipywidgets are installed.
%pip install -q kinbook ipywidgets
import importlib.util, sys
if importlib.util.find_spec("kinbook") is None:
    print("kinbook could not be installed: this site has no copy of it that your browser could load (its wheel "
          "is missing from the site), so the cells that use kinbook cannot run. The notebook and its stored "
          "outputs are here to read; ask whoever runs the site to publish the whole site folder, then reload.",
          file=sys.stderr)
else:
    import logging
    fonts_log = logging.getLogger("matplotlib.font_manager")
    fonts_log.setLevel(logging.ERROR)
    import matplotlib.font_manager  # matplotlib lists its fonts (once per visit)
    fonts_log.setLevel(logging.NOTSET)"""

LITE_KERNELSPEC = {"name": "python", "display_name": "Python (Pyodide)", "language": "python"}


def notebooks():
    """The chapter notebooks, in file-name order (the textbook's section order)."""
    return sorted((ROOT / "chapters").glob("*.ipynb"))


def _read(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def _write(nb, path):
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        json.dump(nb, f, ensure_ascii=False, indent=1)
        f.write("\n")


def _cell(cell_type, source, cell_id):
    cell = {"cell_type": cell_type, "id": cell_id, "metadata": {}, "source": source}
    if cell_type == "code":
        cell.update(execution_count=None, outputs=[])
    return cell


def _after_title(nb):
    """Index just after the notebook's title cell (a first markdown cell), where inserted cells go."""
    cells = nb["cells"]
    return 1 if cells and cells[0]["cell_type"] == "markdown" else 0


def book_notebook(nb, name):
    """A chapter notebook as a book page: an "Open live" link under the title, and no stored widget state
    (rendering it would load the widget manager from a CDN)."""
    nb["metadata"].pop("widgets", None)
    link = (f'<p class="kinbook-live"><a href="{LIVE_NOTEBOOK.format(name=name)}">▶ Open live</a> — run this '
            "notebook in your browser: no install (JupyterLite; the first start downloads Python, then the "
            "browser keeps it).</p>")
    nb["cells"].insert(_after_title(nb), _cell("markdown", link, "kinbook-open-live"))
    return instant_cells(_html_links(nb), name)


def instant_cells(nb, name):
    """Under each try-it cell (``kb.try_it("13-1/try-1", …)``), its instant check: one ``data-tryit`` element
    with the answer's input, the check button and the verdict; the first one loads the scripts."""
    cells, first = [], True
    for cell in nb["cells"]:
        cells.append(cell)
        found = TRY_IT_CALL.search(_joined(cell["source"])) if cell["cell_type"] == "code" else None
        if found is None:
            continue
        tryit = found.group(1)
        notebook = tryit.split("/")[0]
        scripts = (INSTANT_STYLE + f'<script defer src="../instant/{INSTANT_SCRIPTS[-1]}"></script>' if first else "")
        first = False
        html = (f'<div class="kinbook-instant" data-tryit="{tryit}" data-spec="../instant/{notebook}.json" '
                f'data-live="{LIVE_NOTEBOOK.format(name=name)}">'
                '<textarea rows="3" spellcheck="false" autocomplete="off" aria-label="answer"></textarea>'
                '<div class="kinbook-instant-bar"><button type="button" data-check>Check</button> '
                '<button type="button" data-lang class="kinbook-instant-lang">Español</button> '
                '<small data-note></small></div>'
                '<div data-verdict aria-live="polite"></div><div data-echo></div></div>' + scripts)
        cells.append(_cell("markdown", html, f"kinbook-instant-{tryit.replace('/', '-')}"))
    nb["cells"] = cells
    return nb


_NOTEBOOK_LINK = re.compile(r"(?<=[(\"'])([\w.-]+)\.ipynb(?=[#)\"'])")
"""A link to a sibling notebook (``errata.ipynb#erratum-13.5-ex1``) in Markdown or an HTML output."""


def _html_links(nb):
    """Links between the notebooks (the errata cards and each chapter's list of its errata) point at the book's
    pages: ``errata.ipynb#…`` → ``errata.html#…``. Jupyter Book rewrites links in Markdown it resolves, not in
    stored HTML outputs, nor links with an anchor to another notebook's output."""
    for cell in nb["cells"]:
        if cell["cell_type"] == "markdown":
            cell["source"] = _NOTEBOOK_LINK.sub(r"\1.html", _joined(cell["source"]))
        for out in cell.get("outputs", []):
            if "text/html" in out.get("data", {}):
                out["data"]["text/html"] = _NOTEBOOK_LINK.sub(r"\1.html", _joined(out["data"]["text/html"]))
    return nb


def _joined(value):
    return "".join(value) if isinstance(value, list) else value


def _one_string_outputs(nb):
    """Store every output's text as one string. nbformat allows a list of lines (and nbconvert writes multi-line
    text that way); JupyterLite 0.6 shows such a list joined with commas: ",slider stroke: …" at the start of
    every printed line after the first, and HTML outputs strewn with commas."""
    for cell in nb["cells"]:
        for out in cell.get("outputs", []):
            if "text" in out:
                out["text"] = _joined(out["text"])
            for mime, value in out.get("data", {}).items():
                out["data"][mime] = _joined(value)
    return nb


def lite_notebook(nb):
    """A chapter notebook for JupyterLite: the Pyodide kernel, kinbook installed by the first cell, outputs
    stored as single strings."""
    nb = _one_string_outputs(nb)
    nb["metadata"]["kernelspec"] = dict(LITE_KERNELSPEC)
    nb["metadata"].pop("widgets", None)
    nb["cells"].insert(_after_title(nb), _cell("code", INSTALL_CELL, "kinbook-install"))
    return nb


def _fresh(path):
    if path.exists():
        shutil.rmtree(path)
    path.mkdir(parents=True)
    return path


def _copy_tree(src, dst):
    shutil.copytree(src, dst, dirs_exist_ok=True)


def _run(cmd, **kw):
    print("+", " ".join(str(c) for c in cmd), flush=True)
    subprocess.run([str(c) for c in cmd], check=True, **kw)


def build_book():
    src = _fresh(STAGE / "book")
    for f in ("_config.yml", "_toc.yml", "intro.md"):
        shutil.copy2(WEB / "book" / f, src / f)
    _copy_tree(WEB / "book" / "_ext", src / "_ext")
    for path in notebooks():
        _write(book_notebook(_read(path), path.name), src / "chapters" / path.name)
    (src / "docs").mkdir()
    for path in sorted((ROOT / "docs").glob("*.md")):
        shutil.copy2(path, src / "docs" / path.name)
    # MathJax goes to <site>/mathjax/ through Sphinx's html_extra_path (see web/book/_config.yml)
    mathjax = NODE_MODULES / "mathjax" / "es5"
    if not mathjax.is_dir():
        raise SystemExit(f"{mathjax} is missing: run `make web-env` (npm ci of web/package.json) first")
    (src / "_extra" / "mathjax").mkdir(parents=True)
    for part in MATHJAX_PARTS:
        (shutil.copy2 if part.endswith(".js") else _copy_tree)(mathjax / part, src / "_extra" / "mathjax" / part)
    build_instant(src / "_extra" / "instant")

    out = STAGE / "book-out"
    if out.exists():
        shutil.rmtree(out)
    _run([VENV / "bin" / "jupyter-book", "build", src, "--path-output", out, "--builder", "html", "--quiet"])
    html = out / "_build" / "html"
    # build/site/ is the book; build/site/live/ (make lite) is left in place
    SITE.mkdir(parents=True, exist_ok=True)
    for entry in SITE.iterdir():
        if entry.name != "live":
            shutil.rmtree(entry) if entry.is_dir() and not entry.is_symlink() else entry.unlink()
    for entry in html.iterdir():
        shutil.move(str(entry), SITE / entry.name)
    print(f"book: {SITE}/index.html ({_size(SITE, skip='live')})")


def build_instant(dst):
    """<site>/instant/: mathjs's browser bundle (npm ci of web/package.json), kinbook's page scripts and one JSON
    per notebook with try-its (kinbook.book.instant, run by the lab environment's Python)."""
    bundle = NODE_MODULES / "mathjs" / "lib" / "browser" / "math.js"
    if not bundle.is_file():
        raise SystemExit(f"{bundle} is missing: run `make web-env` (npm ci of web/package.json) first")
    if not LAB_PYTHON.exists():
        raise SystemExit(f"{LAB_PYTHON} is missing: `make install` (kinbook writes the try-its' checks) or set "
                         "KINBOOK_PYTHON")
    dst.mkdir(parents=True)
    shutil.copy2(bundle, dst / "math.js")
    shutil.copy2(bundle.with_name("math.js.LICENSE.txt"), dst / "math.js.LICENSE.txt")
    for script in INSTANT_SCRIPTS[1:]:
        shutil.copy2(WEB / "instant" / script, dst / script)
    # the pages' mutation runs, shared with `make test` (tests/book/test_instant.py) through the checkout's cache
    _run([LAB_PYTHON, "-m", "kinbook.book.instant", dst, ROOT / "build" / "cache" / "instant"], cwd=ROOT)


def kinbook_wheel(dst):
    """Build kinbook's wheel from a clean copy of the package (no stale build/lib, no network)."""
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for f in ("pyproject.toml", "setup.py", "README.md", "LICENSE"):
            shutil.copy2(ROOT / f, tmp / f)
        for d in ("kinbook", "exercises"):  # exercises/ is the package kinbook.exercises (setup.py)
            shutil.copytree(ROOT / d, tmp / d, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        _run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "--no-build-isolation",
              "--disable-pip-version-check", "--wheel-dir", dst, tmp])
    return sorted(Path(dst).glob("kinbook-*.whl"))


def kernel_wheels():
    """The Pyodide kernel's own Python packages (pyodide_kernel, piplite, and the ipykernel and widgetsnbextension
    stand-ins), from the JupyterLite extension installed in the web environment: the newest of each name."""
    pypi = VENV / "share" / "jupyter" / "labextensions" / "@jupyterlite" / "pyodide-kernel-extension" / "static" / "pypi"
    newest = {}
    for whl in pypi.glob("*.whl"):
        name, version = whl.name.split("-")[:2]
        if name not in newest or Version(version) > Version(newest[name].name.split("-")[1]):
            newest[name] = whl
    if "pyodide_kernel" not in newest:
        raise SystemExit(f"{pypi}: no pyodide_kernel wheel (is jupyterlite-pyodide-kernel installed? make web-env)")
    return sorted(newest.values())


def build_lite():
    lite = _fresh(STAGE / "lite")
    for f in ("jupyter_lite_config.json", "jupyter-lite.json"):
        shutil.copy2(WEB / "lite" / f, lite / f)
    # the lab's settings (etc/jupyterlab-overrides.json: no windowed notebook, whose layout left the stored
    # animation players without a picture) apply to the live site too
    shutil.copy2(ROOT / "etc" / "jupyterlab-overrides.json", lite / "overrides.json")
    contents = lite / "contents"
    for path in notebooks():
        _write(lite_notebook(_read(path)), contents / path.name)
    wheels = lite / "wheels"
    wheels.mkdir()
    if not list(WHEELS.glob("*.whl")):
        raise SystemExit(f"{WHEELS} has no wheels: run `make web-env` first")
    with tempfile.TemporaryDirectory() as tmp:
        (kinbook,) = kinbook_wheel(tmp)
        # the site's own wheels, compiled like Pyodide's packages, in the site's Pyodide lockfile so that the
        # kernel loads them while it starts; kinbook keeps its sources too (kb.reveal shows a solution's code)
        site_wheels = [(kinbook, "beside")] + [(w, "replace") for w in WHEELS.glob("*.whl")]
        pyodide = pyodide_site.prepare(VENV / "pyodide", site_wheels + [(w, "replace") for w in kernel_wheels()])
    for whl, _ in site_wheels:   # and in the piplite index, for a cell's %pip install
        shutil.copy2(pyodide / whl.name, wheels / whl.name)

    if LIVE.exists():
        shutil.rmtree(LIVE)
    _run([VENV / "bin" / "jupyter", "lite", "build", "--lite-dir", lite, "--contents", contents,
          "--piplite-wheels", wheels, "--output-dir", LIVE], cwd=lite)
    shutil.copytree(pyodide, LIVE / "static" / "pyodide", ignore=shutil.ignore_patterns("STAMP"))
    _page_script(LIVE)
    print(f"lite: {LIVE}/index.html ({_size(LIVE)})")


# The live site's own script (web/lite/kinbook-live.js), added to the pages that run notebooks.
PAGE_SCRIPT = "kinbook-live.js"
LIVE_APPS = ("lab", "notebooks")


def _page_script(live):
    """Copy web/lite/kinbook-live.js to the live site and load it from the pages of its apps (their index.html
    are JupyterLite's own: the script tag goes before </head>, versioned by the script's digest so that a
    browser cache never keeps an old copy)."""
    script = (WEB / "lite" / PAGE_SCRIPT).read_bytes()
    (live / PAGE_SCRIPT).write_bytes(script)
    tag = f'<script defer src="../{PAGE_SCRIPT}?_={hashlib.sha256(script).hexdigest()[:10]}"></script>\n'
    for app in LIVE_APPS:
        page = live / app / "index.html"
        text = page.read_text(encoding="utf-8")
        if "</head>" not in text:
            raise SystemExit(f"{page}: no </head> to put {PAGE_SCRIPT} before (JupyterLite's page changed?)")
        page.write_text(text.replace("</head>", tag + "  </head>", 1), encoding="utf-8")


def _size(path, skip=None):
    total = n = 0
    for dirpath, dirnames, filenames in os.walk(path):
        if skip and Path(dirpath) == Path(path) and skip in dirnames:
            dirnames.remove(skip)
        for f in filenames:
            total += os.path.getsize(os.path.join(dirpath, f))
            n += 1
    return f"{total / 1e6:.1f} MB in {n} files"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=["book", "lite"])
    args = parser.parse_args(argv)
    {"book": build_book, "lite": build_lite}[args.what]()


if __name__ == "__main__":
    main()
