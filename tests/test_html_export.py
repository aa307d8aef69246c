"""`make html` pages load nothing from a CDN: nbconvert's lab template with kinbook's template on top
(etc/nbconvert/kinbook-html) — the chapters' stored outputs exported as the Makefile exports them."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("name", ["13-4-gears.ipynb", "glossary.ipynb"])
def test_exported_pages_request_nothing_from_another_host(name):
    nbconvert = pytest.importorskip("nbconvert")
    exporter = nbconvert.HTMLExporter(template_name="kinbook-html",
                                      extra_template_basedirs=[str(ROOT / "etc" / "nbconvert")],
                                      mathjax_url="mathjax/MathJax.js")
    body, _ = exporter.from_filename(str(ROOT / "chapters" / name))
    remote = re.findall(r"""(?:src=|href=|import\()["'](https?:[^"']+)""", body)
    assert remote == [], remote
    if name.startswith("13-4"):  # (the page is the notebook: its figures, the animation as an image)
        assert len(re.findall(r'<img[^>]* src="data:image/png', body)) >= 2
    assert "require.js" not in body and "require.min.js" not in body
