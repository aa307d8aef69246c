"""The live notebooks (make lite) in a real browser, offline: a student opens a chapter notebook, runs the cell
that installs kinbook, imports it, simulates a mechanism, gets a checker's feedback on a wrong answer and moves
the explorer's slider. The site as built, Pyodide included (live/static/pyodide/: web/pyodide_site.py), served
from 127.0.0.1 with every other host refused."""

import re

import pytest

from .conftest import ANIMATED, FIGURES, SCREENSHOTS, Clock, StaticServer, plays, site_copy, watch

NOTEBOOK = "13-3-position-analysis.ipynb"

# What the student types, cell by cell, after the install cell. Each prints a line the test reads back.
SIMULATE = """\
# [live test] simulate
import numpy as np
import kinbook
mech = kinbook.examples.load("ch13_example2")
sweep = mech.simulate(np.linspace(0, 2 * np.pi / 100, 361))
print("stroke end:", round(float(sweep.position("slider", "B")[:, 0].max()), 6))"""
# the slider-crank's stroke ends where crank (2) and rod (6) are aligned: x_B = 2 + 6 = 8
STROKE_END = "stroke end: 8.0"

CHECK_WRONG = """\
# [live test] a wrong answer
from kinbook.grading import check_phi
m1 = kinbook.examples.load("ch13_example1")
result = check_phi(["x1 - x2 - cos(phi2)", "y1 - y2 + sin(phi2)"], m1.constraint("1"))
display(result)
print("mistakes:", result.mistakes)"""
# the answer is the revolute joint's Φ with the sign of one term flipped (the right one has + cos(phi2))
MISTAKE = "sign_flip"

TRY_IT = """\
# [live test] a try-it
import kinbook as kb
kb.try_it("13-1/try-2", [1.5 + 0.8, -0.5 + 0.3])"""
# 13-1's Try it 2 answered with the local vector s' added to r (no A): the mistake is named, the reference
# r + A s' = [1.85355, 0.27782] is never shown (a try-it's value comes only through kb.reveal)
TRY_IT_MISTAKE = "local instead of global vector"
TRY_IT_REFERENCE = ("1.85", "0.277", "0.278")

EXPLORER = """\
# [live test] explorer
from kinbook.planar import plotting
explorer = plotting.explorer(m1)
explorer"""

# The budget: the first notebook is interactive (kinbook installed and imported) within 60 s of the
# page load. The figures are printed (wall clock, and the browser's CPU time, which does not depend on what else
# shares the machine), not asserted: no verdict here depends on the clock.


def code_cell(page, marker):
    """The code cell whose text contains `marker` (cells are found by their text, not their position: the
    notebook renders only the cells near the viewport)."""
    return page.locator(".jp-Notebook .jp-CodeCell", has_text=marker).first


def select(page, cell):
    cell.locator(".jp-InputPrompt").click()
    page.wait_for_function("c => c.classList.contains('jp-mod-active')", arg=cell.element_handle())


def toolbar(page, command):
    page.locator(f".jp-Toolbar [data-command='{command}']").first.click()


def run_and_wait(page, cell, timeout):
    """Run `cell` (the toolbar's run button) and wait until its prompt shows an execution count."""
    select(page, cell)
    toolbar(page, "notebook:run-cell-and-select-next")
    prompt = cell.locator(".jp-InputPrompt")
    try:
        page.wait_for_function("p => /\\[\\d+\\]/.test(p.textContent)", arg=prompt.element_handle(),
                               timeout=timeout * 1000)
    except Exception:
        cell.scroll_into_view_if_needed()
        page.screenshot(path=str(SCREENSHOTS / "live-timeout.png"))
        raise
    return cell.locator(".jp-OutputArea")


def add_cell_below(page, cell, code, timeout=300):
    """Insert a code cell below `cell` (command mode `b`), type `code`, run it; returns the new cell.
    `code` starts with a comment naming it, by which the cell is found again."""
    marker = code.splitlines()[0]
    select(page, cell)
    toolbar(page, "notebook:insert-cell-below")
    page.locator(".jp-Notebook .jp-Cell.jp-mod-active .cm-content").click()
    page.keyboard.insert_text(code)
    new = code_cell(page, marker)
    run_and_wait(page, new, timeout)
    return new


def open_notebook(context, site, seen):
    page = watch(context.new_page(), seen)
    page.set_default_timeout(120_000)
    clock = Clock()
    page.goto(f"{site.url}/live/notebooks/index.html?path={NOTEBOOK}")
    install = code_cell(page, "%pip install")
    install.wait_for()
    # the kernel (Pyodide in a web worker) has started
    page.locator(".jp-Notebook-ExecutionIndicator[data-status='idle']").wait_for(timeout=600_000)
    return page, clock, install


def install_and_import(page, install):
    """Run the notebook's first code cell (it installs kinbook from the site) and import kinbook."""
    run_and_wait(page, install, timeout=600)
    probe = add_cell_below(page, install, '# probe\nimport kinbook\nprint("kinbook", kinbook.__version__)')
    text = probe.locator(".jp-OutputArea").inner_text()
    assert re.search(r"kinbook \d+\.\d+", text), text
    return probe


def test_a_student_runs_the_live_notebook(profile, site, offline, screenshots):
    site_before, pyodide_before = site.bytes_sent(), site.bytes_sent("/live/static/pyodide/")
    page, clock, install = open_notebook(profile, site, offline)
    t_open = clock()
    last = install_and_import(page, install)
    t_interactive, cpu = clock(), clock.cpu()
    pyodide = site.bytes_sent("/live/static/pyodide/") - pyodide_before
    own = site.bytes_sent() - site_before - pyodide
    print(f"\nfirst visit: notebook shown {t_open:.1f} s and kinbook installed and imported {t_interactive:.1f} s "
          f"after the page load ({cpu:.1f} s of browser CPU); served {own / 1e6:.1f} MB "
          f"of the site + {pyodide / 1e6:.1f} MB of Pyodide")
    FIGURES["live site (JupyterLite), first visit: notebook shown / interactive"] = \
        f"{t_open:.1f} s / {t_interactive:.1f} s ({(own + pyodide) / 1e6:.0f} MB served)"

    assert page.locator("#kinbook-no-python").count() == 0  # Python was downloaded: no banner says otherwise

    last = add_cell_below(page, last, SIMULATE)
    assert STROKE_END in last.locator(".jp-OutputArea").inner_text()

    last = add_cell_below(page, last, CHECK_WRONG)
    feedback = last.locator(".jp-OutputArea")
    assert feedback.locator("table").count() >= 1, "no feedback table"
    assert MISTAKE in feedback.inner_text()
    echo = feedback.locator(".kb-read")  # the answer as read, before the verdict (issue 29), typeset by the page
    assert echo.count() == 1 and "your answer, as read" in echo.inner_text(), feedback.inner_text()
    feedback.scroll_into_view_if_needed()
    page.screenshot(path=str(screenshots / "live-checker.png"))

    last = add_cell_below(page, last, TRY_IT)
    feedback = last.locator(".jp-OutputArea")
    text = feedback.inner_text()
    assert TRY_IT_MISTAKE in text and "wrong" in text, text
    assert "your answer, as read" in feedback.locator(".kb-read").inner_text(), text
    assert not [x for x in TRY_IT_REFERENCE if x in text], text
    feedback.scroll_into_view_if_needed()
    page.screenshot(path=str(screenshots / "live-try-it.png"))

    last = add_cell_below(page, last, EXPLORER)
    out = last.locator(".jp-OutputArea")
    status = out.locator(".widget-html-content").first
    status.wait_for()
    page.wait_for_function("s => s.textContent.includes('cond')", arg=status.element_handle())
    before_status = status.inner_text()
    image = out.locator(".widget-image").first
    before_image = image.get_attribute("src")
    handle = out.locator(".widget-slider .noUi-handle").first
    box = handle.bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] / 2 - 60, box["y"] + box["height"] / 2, steps=6)
    page.mouse.up()
    page.wait_for_function("([s, old]) => s.textContent !== old && s.textContent.includes('cond')",
                           arg=[status.element_handle(), before_status], timeout=120_000)
    page.wait_for_function("([i, old]) => i.src !== old", arg=[image.element_handle(), before_image],
                           timeout=120_000)
    print(f"explorer: {before_status!r} -> {status.inner_text()!r}")
    # the first cell read matplotlib's fonts quietly: no "building the font cache" box under a plot
    assert "font cache" not in page.locator(".jp-Notebook").inner_text()
    out.scroll_into_view_if_needed()
    page.screenshot(path=str(screenshots / "live-slider.png"))
    page.close()


def test_a_second_visit_uses_the_browser_cache(profile, site, offline):
    """After the first visit (previous test, same browser profile), the site's files come from the cache."""
    served_before, log_before = site.bytes_sent(), len(site.log)
    page, clock, install = open_notebook(profile, site, offline)
    install_and_import(page, install)
    t, cpu = clock(), clock.cpu()
    again = site.bytes_sent() - served_before
    print(f"\nsecond visit: kinbook installed and imported {t:.1f} s after the page load ({cpu:.1f} s of browser "
          f"CPU); {again / 1e6:.2f} MB served")
    FIGURES["live site (JupyterLite), second visit: interactive"] = f"{t:.1f} s ({again / 1e6:.2f} MB served)"
    again_files = sorted(((n, path) for path, kind, n in site.log[log_before:] if kind == "body"), reverse=True)
    assert again < 1e6, f"{again / 1e6:.1f} MB served again: the browser cache was not used: {again_files[:8]}"
    page.close()


def test_stored_animations_play_in_the_live_notebooks(browser, site, offline, screenshots):
    """The live notebooks are untrusted (JupyterLite trusts only what a session computes): a stored animation is
    an animated PNG, which plays untrusted (the JavaScript player was a broken image strewn with commas)."""
    for chapter in ANIMATED:
        page = watch(browser.new_page(viewport={"width": 1280, "height": 1000}), offline)
        page.goto(f"{site.url}/live/notebooks/index.html?path={chapter}.ipynb")
        cells = page.locator(".jp-Notebook .jp-CodeCell", has_text="animation_png(")
        cells.first.wait_for(timeout=120_000)
        for k in range(cells.count()):
            out = cells.nth(k).locator(".jp-OutputArea-output")
            img = out.locator("img")
            assert img.count() == 1 and plays(page, img), f"animation {k + 1} of {chapter} does not play"
            assert out.first.inner_text().strip() == "", "text beside the animation (stray commas?)"
        # printed text keeps its lines (JupyterLite showed a stored list of lines joined by commas)
        streams = page.locator(".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stdout']")
        texts = [streams.nth(k).inner_text() for k in range(streams.count())]
        assert texts and not [t for t in texts if "\n," in t], [t for t in texts if "\n," in t][:3]
        page.screenshot(path=str(screenshots / f"live-{chapter}-animation.png"))
        page.close()


def test_without_python_the_page_says_so(browser, proxy, screenshots, tmp_path):
    """When Python cannot be downloaded (here a copy of the site without its static/pyodide/pyodide.js: a host
    that dropped it, or offline), the page says so in a banner at its foot, under a menu bar that stays usable,
    instead of cells waiting at [*] forever."""
    copy = site_copy(tmp_path / "site")
    (copy / "live" / "static" / "pyodide" / "pyodide.js").unlink()
    server = StaticServer(copy)
    before = len(proxy.requests)
    try:
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        page.goto(f"{server.url}/live/notebooks/index.html?path=13-1-transformation-matrix.ipynb")
        banner = page.locator("#kinbook-no-python")
        banner.wait_for(timeout=120_000)
        text = banner.inner_text()
        assert "Python could not be downloaded" in text and server.url.split("//")[1] in text, text
        assert "answered 404" in text and "missing its copy of Python" in text, text
        # the banner says the notebook and its stored outputs are there to read: they are, above it
        page.locator(".jp-Notebook .jp-Cell").first.wait_for(timeout=120_000)
        page.locator(".jp-Notebook .jp-MarkdownOutput h1").first.wait_for(timeout=120_000)
        box = banner.bounding_box()
        menu = page.locator("#jp-menu-panel, .jp-MenuBar, #top-panel").first.bounding_box()
        assert box["y"] + box["height"] == pytest.approx(800, abs=1), box    # at the foot of the window
        assert menu is None or menu["y"] + menu["height"] <= box["y"], (menu, box)   # the menu bar uncovered
        page.screenshot(path=str(screenshots / "live-no-python.png"))
        page.close()
    finally:
        server.close()
    assert proxy.requests[before:] == []


def test_the_page_names_what_it_loads_and_for_how_long(browser, site, proxy, screenshots):
    """While Python starts, a notice at the foot of the page names what is loading (Pyodide and the packages the
    kernel loads) and counts the seconds; past its threshold (set to 0 here: every start is "slow") it says the
    start is slow but going. It goes when the kernel answers."""
    before = len(proxy.requests)
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    context.add_init_script("window.kinbookSlowAfter = 0;")
    page = context.new_page()
    page.goto(f"{site.url}/live/notebooks/index.html?path=13-1-transformation-matrix.ipynb")
    notice = page.locator("#kinbook-starting")
    notice.wait_for(timeout=120_000)
    page.wait_for_function("() => /with .*numpy.*kinbook/.test(document.querySelector('#kinbook-starting')"
                           "?.textContent || '')", timeout=60_000)
    text = notice.inner_text()
    assert "Starting Python (Pyodide) with" in text and "sympy" in text and "s so far" in text, text
    assert "slower than usual" in text and "still going" in text, text
    page.screenshot(path=str(screenshots / "live-starting-notice.png"))
    notice.wait_for(state="detached", timeout=600_000)      # the kernel answered: the notice is gone
    assert page.locator("#kinbook-no-python").count() == 0
    context.close()
    assert proxy.requests[before:] == []


def test_a_missing_kinbook_wheel_is_said_plainly(browser, proxy, screenshots, tmp_path):
    """A copy of the site without kinbook's wheel: the install cell says that kinbook could not be installed (not a
    silent cell, then "No module named 'kinbook'" in the next one)."""
    copy = site_copy(tmp_path / "site")
    wheels = list((copy / "live").rglob("kinbook-*.whl"))
    assert wheels, "the built site has no kinbook wheel to remove"
    for wheel in wheels:
        wheel.unlink()
    server = StaticServer(copy)
    before = len(proxy.requests)
    try:
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        page.set_default_timeout(120_000)
        page.goto(f"{server.url}/live/notebooks/index.html?path={NOTEBOOK}")
        install = code_cell(page, "%pip install")
        install.wait_for()
        page.locator("#kinbook-starting").wait_for(state="detached", timeout=600_000)
        out = run_and_wait(page, install, timeout=600)
        text = out.inner_text()
        assert "kinbook could not be installed" in text and "wheel" in text, text
        assert "No module named" not in text, text
        page.screenshot(path=str(screenshots / "live-no-kinbook-wheel.png"))
        page.close()
    finally:
        server.close()
    assert proxy.requests[before:] == []
