"""The static book (make book) in a real browser, offline: every chapter is a page in the table of contents,
its math is typeset by the site's own MathJax (no raw TeX left), its figures load, its animations play with
their icons, and each page links to the same notebook in the live site."""

import json
import re
from pathlib import Path
from urllib.parse import parse_qs, urljoin, urlsplit

import pytest

from .conftest import ANIMATED, ROOT, SITE, plays, watch

CHAPTERS = sorted(p.stem for p in (ROOT / "chapters").glob("*.ipynb"))

# TeX left in the visible text of a page, outside code: a control word such as \frac or \Phi, or $$.
RAW_TEX = re.compile(r"\\[A-Za-z]{2,}|\$\$")

# The text a reader sees (rendered, not hidden), outside code and typeset math.
VISIBLE_TEXT_OUTSIDE_CODE_AND_MATH = """() => {
    const skip = 'pre, code, script, style, mjx-container, .highlight, textarea, noscript';
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    const out = [];
    while (walker.nextNode()) {
        const el = walker.currentNode.parentElement;
        if (!el || el.closest(skip) || !el.getClientRects().length) continue;
        if (getComputedStyle(el).visibility === 'hidden') continue;
        out.push(walker.currentNode.textContent);
    }
    return out.join(' ');
}"""

# MathJax's entry points (a combined component such as tex-chtml.js, or MathJax 2's MathJax.js)
MATHJAX_ENTRY = "script[src*='/tex-' i], script[src*='/mml-' i], script[src*='MathJax.js' i]"


def open_page(browser, seen, url):
    page = watch(browser.new_page(viewport={"width": 1280, "height": 900}), seen)
    page.goto(url, wait_until="load")
    page.wait_for_function("() => window.MathJax && MathJax.startup && MathJax.startup.promise")
    page.evaluate("() => MathJax.startup.promise")
    return page


def test_every_chapter_is_a_page_in_the_table_of_contents(browser, site, offline):
    page = open_page(browser, offline, f"{site.url}/index.html")
    nav = page.eval_on_selector_all("nav.bd-docs-nav a.reference", "links => links.map(a => a.getAttribute('href'))")
    pages = [Path(urlsplit(h).path).stem for h in nav]
    assert [p for p in pages if p in CHAPTERS] == CHAPTERS, "chapters missing or out of the files' order"
    assert pages.index("13-1-transformation-matrix") < pages.index("14-1-direction-cosines") < pages.index("errata")
    assert "instructors" in pages
    if (ROOT / "docs" / "glossary.md").exists() or (ROOT / "chapters" / "glossary.ipynb").exists():
        assert "glossary" in pages
    page.close()


@pytest.mark.parametrize("chapter", CHAPTERS)
def test_chapter_page_math_figures_and_live_link(browser, site, offline, chapter):
    page = open_page(browser, offline, f"{site.url}/chapters/{chapter}.html")
    # one MathJax, the site's own (MathJax 3 from <site>/mathjax/), and it typeset the page
    entries = page.eval_on_selector_all(MATHJAX_ENTRY, "s => s.map(e => e.src)")
    assert len(entries) == 1 and entries[0].startswith(f"{site.url}/mathjax/tex-chtml.js"), entries
    assert page.evaluate("MathJax.version").startswith("3.")
    notebook = json.loads((ROOT / "chapters" / f"{chapter}.ipynb").read_text())
    sources = "".join("".join(c["source"]) for c in notebook["cells"] if c["cell_type"] == "markdown")
    outputs = json.dumps([c.get("outputs", []) for c in notebook["cells"]])
    has_math = "$" in sources or "text/latex" in outputs
    n_math = page.locator("mjx-container").count()
    assert n_math > 0 or not has_math, "the page has TeX but MathJax typeset none of it"
    leftover = RAW_TEX.findall(page.evaluate(VISIBLE_TEXT_OUTSIDE_CODE_AND_MATH))
    assert leftover == [], f"raw TeX on the page: {leftover[:10]}"
    # every image (figures and animation frames) loaded
    broken = page.eval_on_selector_all("main img", "imgs => imgs.filter(i => !(i.complete && i.naturalWidth > 0))"
                                                   ".map(i => i.src.slice(0, 80))")
    assert broken == []
    n_png = outputs.count('"image/png"')
    assert page.locator("main img").count() >= n_png
    # "Open live" goes to this notebook in the live site
    href = page.get_attribute("p.kinbook-live a", "href")
    target = urlsplit(urljoin(page.url, href))
    assert target.path == "/live/notebooks/index.html"
    assert parse_qs(target.query)["path"] == [f"{chapter}.ipynb"]
    if (SITE / "live").exists():
        assert (SITE / "live" / "files" / f"{chapter}.ipynb").exists()
    page.close()


@pytest.mark.parametrize("chapter", ANIMATED)
def test_stored_animations_play(browser, site, offline, screenshots, chapter):
    """An animation is an animated PNG: the page shows it as an image, which plays with no script."""
    page = open_page(browser, offline, f"{site.url}/chapters/{chapter}.html")
    cells = page.locator("div.cell", has=page.locator("pre", has_text="animation_png("))
    assert cells.count() >= 1
    for k in range(cells.count()):
        img = cells.nth(k).locator(".cell_output img")
        assert img.count() == 1 and plays(page, img), f"animation {k + 1} of {chapter} does not play"
    assert page.locator(".cell_output script").count() == 0
    page.screenshot(path=str(screenshots / f"book-{chapter}-animation.png"))
    page.close()


def test_no_page_loads_thebe_or_links_a_missing_page(site):
    """Thebe (a launcher from a public CDN, unused: the live path is JupyterLite) is on no page, and every
    relative link of every page leads to a file of the site (the instructors page linked docs/lms, left out)."""
    dead = []
    for page in sorted(SITE.rglob("*.html")):
        if "live" in page.relative_to(SITE).parts or "_static" in page.parts:
            continue
        text = page.read_text(encoding="utf-8")
        assert "thebe" not in text.lower() and "unpkg.com" not in text, page
        for href in re.findall(r'<a [^>]*href="([^"]+)"', text):
            href = href.split("#")[0].split("?")[0]
            if not href or re.match(r"[a-z][a-z0-9+.-]*:", href):  # in-page anchors, other sites, mailto:
                continue
            target = (page.parent / href).resolve()
            if not target.exists():
                dead.append(f"{page.relative_to(SITE)} -> {href}")
    assert dead == [], dead


def test_screenshot_of_a_page_with_math(browser, site, offline, screenshots):
    page = open_page(browser, offline, f"{site.url}/chapters/{CHAPTERS[0]}.html")
    page.locator("main mjx-container").nth(3).scroll_into_view_if_needed()
    page.screenshot(path=str(screenshots / "book-page.png"))
    page.close()
