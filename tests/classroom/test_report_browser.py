"""`kinbook report`'s pages looked at in a browser (issue 21): Debian's chromium driven by Playwright, as `make
test-web` does, with every request that is not the page itself refused and counted (a report must be one
self-contained file). Screenshots go to build/web/screenshots/report-*.png. Skipped where Playwright or chromium is
missing (`make test` has neither; run it with the web tools: `.venv-web/bin/python -m pytest
tests/classroom/test_report_browser.py`)."""

import os
from pathlib import Path

import pytest

from kinbook.classroom.gradebook import Gradebook
from kinbook.classroom.report import report
from kinbook.classroom.results import PartGrade, SubmissionResult

playwright = pytest.importorskip("playwright.sync_api")
ROOT = Path(__file__).resolve().parents[2]
SHOTS = ROOT / "build" / "web" / "screenshots"
CHROMIUM = next((p for p in ("/usr/lib/chromium/chromium", "/usr/bin/chromium") if Path(p).exists()), None)
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="no chromium here: apt-get install chromium")


def class_of(book, n=30):
    """A class of ``n`` on a three-part exercise: scores spread, a common mistake on part b, nobody right on c."""
    for k in range(n):
        a = 4.0 if k % 3 else 2.0
        b = 3.0 if k % 4 else 1.0
        mistakes = [] if k % 4 else [("sign_flip", "Φ_4")]
        if k % 5 == 0:
            mistakes.append(("transposed", ""))
        book.record(SubmissionResult(f"s{k:02d}", "ex01", f"s{k:02d}.ipynb", f"{k:064x}", "ok", "", [
            PartGrade("revolute_OA", a, 4.0, "ok", "", answer=f"[x1 - x2 + {k % 3}]"),
            PartGrade("revolute_B", b, 3.0, "ok", "", answer="[x3 - x4]", mistakes=mistakes),
            PartGrade("whole_phi", 0.0, 4.0, "ok", "", answer="[0]")], 1.0, "none"))


def test_the_report_reads_in_a_browser(tmp_path):
    book = Gradebook(tmp_path / "graded")
    class_of(book)
    book.close()
    report(tmp_path / "graded", tmp_path / "report")
    SHOTS.mkdir(parents=True, exist_ok=True)
    outside = []
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"] if os.geteuid() == 0 else [])
        page = browser.new_page(viewport={"width": 1200, "height": 900})
        page.route("**/*", lambda route: (route.continue_() if route.request.url.startswith("file://")
                                          else (outside.append(route.request.url), route.abort())))
        for name in ("ex01", "index"):
            page.goto((tmp_path / "report" / f"{name}.html").as_uri())
            img = page.locator("img").first
            assert img.evaluate("i => i.complete && i.naturalWidth") >= 600   # the histogram is drawn
            page.screenshot(path=str(SHOTS / f"report-{name}.png"), full_page=True)
        page.goto((tmp_path / "report" / "ex01.html").as_uri())
        text = page.inner_text("body")
        assert "Nobody got full marks on: whole_phi" in text
        rows = page.locator("table").nth(1).locator("tr")              # the mistakes table
        assert "sign_flip" in rows.nth(1).inner_text() and "8" in rows.nth(1).inner_text()
        flagged = page.locator("tr.flag").first.evaluate("r => getComputedStyle(r).backgroundColor")
        assert flagged == "rgb(248, 215, 218)"                          # the part nobody got right stands out
        browser.close()
    assert outside == []
