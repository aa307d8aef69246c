"""The book's page titles (browser tabs) carry no raw TeX: web/book/_ext/plain_titles.py writes each chapter
heading's formula in Unicode. Every chapter notebook's first heading is put through it."""

import importlib.util
import json
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("plain_titles", ROOT / "web" / "book" / "_ext" / "plain_titles.py")
plain_titles = importlib.util.module_from_spec(spec)
spec.loader.exec_module(plain_titles)


def test_the_three_formula_titles():
    t = plain_titles.plain_title
    assert t(r"13-6 · Velocity analysis: \(\boldsymbol\Phi_{\mathbf q}\,\dot{\mathbf q} = \nu\)") == \
        "13-6 · Velocity analysis: Φ_q q̇ = ν"
    assert t(r"13-7 · Acceleration analysis: \(\boldsymbol\Phi_{\mathbf q}\,\ddot{\mathbf q} = \gamma\)") == \
        "13-7 · Acceleration analysis: Φ_q q̈ = γ"
    assert t("a &amp; b") == "a &amp; b"


def test_no_chapter_title_keeps_tex():
    for path in sorted((ROOT / "chapters").glob("*.ipynb")):
        cells = json.loads(path.read_text())["cells"]
        heading = next(line for c in cells if c["cell_type"] == "markdown" for line in "".join(c["source"]).splitlines()
                       if line.startswith("# "))
        title = plain_titles.plain_title(heading[2:].replace("$", r"\(", 1).replace("$", r"\)", 1))
        assert not re.search(r"[\\${}]", title), (path.name, title)
