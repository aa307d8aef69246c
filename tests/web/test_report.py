"""`kinbook report` (issue 21) in a real browser, offline: the instructor's report of a class is one self-contained
page per exercise — its histogram drawn, its tables readable, the part nobody got right standing out — and a page for
the course. The report is made by the lab/test environment's kinbook (`make test-web` installs it first: this
environment has the browser, not numpy), from a class of 30 recorded straight into a gradebook."""

import subprocess
import textwrap

import pytest

from .conftest import ROOT, watch

KINBOOK_PYTHON = ROOT / ".venv" / "bin" / "python"

MAKE_REPORT = textwrap.dedent("""
    import sys
    from kinbook.classroom.gradebook import Gradebook
    from kinbook.classroom.report import report
    from kinbook.classroom.results import PartGrade, SubmissionResult

    out = sys.argv[1]
    book = Gradebook(out + "/graded")
    for k in range(30):  # scores spread; a common mistake on revolute_B; nobody right on whole_phi
        mistakes = ([] if k % 4 else [("sign_flip", "Φ_4")]) + ([("transposed", "")] if k % 5 == 0 else [])
        book.record(SubmissionResult(f"s{k:02d}", "ex01", f"s{k:02d}.ipynb", f"{k:064x}", "ok", "", [
            PartGrade("revolute_OA", 4.0 if k % 3 else 2.0, 4.0, "ok", "", answer=f"[x1 - x2 + {k % 3}]"),
            PartGrade("revolute_B", 3.0 if k % 4 else 1.0, 3.0, "ok", "", mistakes=mistakes,
                      answer="\\n".join(f"[x{j} - x{j + 1} + 3*cos(phi{j}) - 1.5*cos(phi{j + 1})]" for j in range(12))),
            PartGrade("whole_phi", 0.0, 4.0, "ok", "", answer="[0]")], 1.0, "none"))
    book.close()
    report(out + "/graded", out + "/report")
""")


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    if not KINBOOK_PYTHON.exists():
        pytest.fail(f"{KINBOOK_PYTHON} is missing: make install (make test-web does)")
    out = tmp_path_factory.mktemp("report")
    subprocess.run([str(KINBOOK_PYTHON), "-c", MAKE_REPORT, str(out)], check=True, cwd=ROOT)
    return out / "report"


@pytest.mark.parametrize("name", ["ex01", "index"])
def test_the_report_reads_in_a_browser(browser, offline, screenshots, pages, name):
    page = watch(browser.new_page(viewport={"width": 1200, "height": 900}), offline)
    page.goto((pages / f"{name}.html").as_uri(), wait_until="load")
    assert page.locator("img").first.evaluate("i => i.complete && i.naturalWidth") >= 600  # the histogram is drawn
    page.screenshot(path=str(screenshots / f"report-{name}.png"), full_page=True)
    if name == "ex01":
        assert "Nobody got full marks on: whole_phi" in page.inner_text("body")
        first = page.locator("table").nth(1).locator("tr").nth(1).inner_text()  # the most common mistake
        assert "sign_flip" in first and "8" in first
        flagged = page.locator("tr.flag").first.evaluate("r => getComputedStyle(r).backgroundColor")
        assert flagged == "rgb(248, 215, 218)"                                 # the part nobody got right
        assert "30 of 30 students handed in, 0 missing." in page.inner_text("body")
        answer = page.locator("table").nth(1).locator("tr").nth(1).locator("pre")
        assert answer.inner_text().count("\n") == 5                          # six of the twelve rows, each whole:
        assert answer.evaluate("p => p.scrollWidth <= p.clientWidth + 1")      # no row wrapped or cut off
        assert answer.evaluate("p => p.getBoundingClientRect().right") <= 1200  # and inside the window
        assert "12 rows in all" in page.locator("table").nth(1).locator("tr").nth(1).inner_text()
    else:
        assert "ex01" in page.locator("table").first.inner_text()
    page.close()
