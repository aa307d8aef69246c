"""The book's instant checks (issue 35): one rule, two engines.

* Agreement: every answer of kinbook's checker corpora (tests/grading/corpus*.py, tryits.py) and of the try-its'
  mutation run (kinbook.book.instant.tryit_mutants, the notebook's data) is checked by Python
  (kinbook.grading, in the lab environment) and by the page's engine (web/instant/kinbook-instant.js under Node,
  with the site's mathjs). The page never passes what Python refuses, its verdict equals Python's on every answer
  it decides, and it decides at least 95 % of the answers typed as text; the table is printed.
* In chromium, offline: every try-it of every chapter page is one ``data-tryit`` element that answers; a verdict
  comes ≤ 100 ms after "Check" (measured in the page: the median of repeated checks, the first one printed — a
  loaded machine slows the first); a wrong answer names its mistake in English and in Spanish
  (screenshot build/web/screenshots/instant-mistake*.png); the try-its are ready as soon as the page has loaded.
"""

from __future__ import annotations

import collections
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from .conftest import FIGURES, ROOT, SITE, Clock, watch

LAB_PYTHON = Path(os.environ.get("KINBOOK_PYTHON", ROOT / ".venv" / "bin" / "python"))
MATHJS = Path(os.environ.get("VIRTUAL_ENV", ROOT / ".venv-web")) / "npm" / "node_modules" / "mathjs"
CHAPTERS = sorted(p.stem for p in (ROOT / "chapters").glob("*.ipynb"))
TRY_IT = re.compile(r'kb\.try_it\("([^"]+)"')


def _tryits(chapter):
    cells = json.loads((ROOT / "chapters" / f"{chapter}.ipynb").read_text())["cells"]
    return [m.group(1) for c in cells if c["cell_type"] == "code" for m in TRY_IT.finditer("".join(c["source"]))]


# ------------------------------------------------------------------------------------------------ agreement
@pytest.fixture(scope="module")
def verdicts(tmp_path_factory):
    node = shutil.which("node")
    if node is None or not LAB_PYTHON.exists() or not (MATHJS / "package.json").exists():
        pytest.fail(f"needs node, {LAB_PYTHON} (make install) and {MATHJS} (make web-env)")
    tmp = tmp_path_factory.mktemp("instant")
    cases = tmp / "cases.jsonl"
    subprocess.run([LAB_PYTHON, ROOT / "tests" / "web" / "instant_cases.py", cases], check=True, cwd=ROOT)
    out = subprocess.run([node, ROOT / "tests" / "web" / "instant_node.js", cases, MATHJS], check=True,
                         capture_output=True, text=True).stdout
    lines = [json.loads(line) for line in cases.read_text().splitlines()]
    python, specs = lines[:-1], lines[-1]["specs"]
    page = {v["id"]: v for v in map(json.loads, out.splitlines())}
    for c in python:  # an option a try-it never has (phi=: the student's own Φ; at=: numbers at a configuration)
        page[c["id"]]["options"] = not specs[c["spec"]].get("rule", {}).get("decides", True)
    return [(c, page[c["id"]]) for c in python]


def test_the_page_agrees_with_python_on_the_corpora(verdicts):
    rows = collections.defaultdict(collections.Counter)
    false_pass, disagree, errors = [], [], []
    for case, page in verdicts:
        row = rows[case["source"]]
        row["answers"] += 1
        v = page["verdict"]
        if v == "error":
            errors.append((case["id"], page["error"][:300]))
            continue
        if v == "not_text":
            row["not text"] += 1
            continue
        row["typed"] += 1
        if v == "undecided":
            row["undecided"] += 1
            row["of which phi=/at="] += bool(page.get("options"))
            continue
        row["decided"] += 1
        passed = v == "pass"
        if passed and not case["python"]["passed"]:
            false_pass.append(case["id"])
        if passed != case["python"]["passed"]:
            disagree.append((case["id"], v, case["python"], page.get("reasons")))
            row["disagree"] += 1
        elif not passed and page.get("mistake") and page["mistake"] in case["python"]["mistakes"]:
            row["same mistake named"] += 1
    total = sum(rows.values(), collections.Counter())
    cols = ["answers", "not text", "typed", "decided", "undecided", "of which phi=/at=", "disagree",
            "same mistake named"]
    print("\n\nInstant checks: the page's engine (JS, mathjs) beside kinbook.grading (Python)")
    print(f"{'source':10}" + "".join(f"{c:>19}" for c in cols) + f"{'decided %':>11}{'w/o phi=/at=':>14}")
    for name, row in sorted(rows.items()) + [("total", total)]:
        share = 100 * row["decided"] / max(row["typed"], 1)
        plain = 100 * row["decided"] / max(row["typed"] - row["of which phi=/at="], 1)
        print(f"{name:10}" + "".join(f"{row[c]:>19}" for c in cols) + f"{share:>10.1f}%{plain:>13.1f}%")
    print(f"passes where Python refuses: {len(false_pass)}")
    ms = sorted(p["ms"] for _, p in verdicts if p.get("ms") is not None)
    if ms:
        print(f"engine time per answer under Node: median {ms[len(ms) // 2]:.2f} ms, max {ms[-1]:.1f} ms")
    assert errors == [], errors[:5]
    assert false_pass == [], false_pass
    assert disagree == [], disagree[:10]
    corpora = sum((row for name, row in rows.items() if name.startswith("corpus")), collections.Counter())
    print(f"decided: {100 * total['decided'] / total['typed']:.1f} % of every typed answer, "
          f"{100 * corpora['decided'] / corpora['typed']:.1f} % of the checker corpora's, "
          f"{100 * rows['mutants']['decided'] / max(rows['mutants']['typed'], 1):.1f} % of the mutation run's "
          f"({rows['mutants']['same mistake named']} of {rows['mutants']['typed']} named as Python names them)")
    # The issue's target: 95 % of the typed answers — the checker corpora's, the try-its', the mutation run's and the
    # generated rounding answers. Measured 2026-11-29: 98.1 % of all (1638 of 1669), 93.1 % of the corpora's alone
    # (96.3 % without phi=/at=, which no try-it has; 91.6 % before the page mirrored rounding, factors, √ forms,
    # constant combinations and 2ĖĠᵀa rows). What the page leaves to Python is the checker's equivalence rule for Φ
    # where its own rules cannot settle it (a cross product's other rows, a factor that touches zero without
    # changing sign), Φ_q rows combined with coefficients that change with q (the Jacobian of M(q)·Φ), and phi=/at=.
    assert total["decided"] / total["typed"] >= 0.95
    assert rows["mutants"]["decided"] == rows["mutants"]["typed"] > 0
    assert rows["tryits"]["decided"] / rows["tryits"]["typed"] >= 0.95


# ------------------------------------------------------------------------------------------------ the page
def _open(browser, seen, url):
    page = watch(browser.new_page(viewport={"width": 1100, "height": 900}), seen)
    clock = Clock()
    page.goto(url, wait_until="load")
    loaded = clock()
    page.wait_for_function("() => [...document.querySelectorAll('[data-tryit]')].every(b => b.dataset.ready)")
    return page, loaded, clock()


CHECK_AND_TIME = """async ([id, text]) => {
    const box = document.querySelector(`[data-tryit="${id}"]`);
    box.querySelector('textarea').value = text;
    const out = box.querySelector('[data-verdict]');
    out.removeAttribute('data-verdict');
    out.setAttribute('data-verdict', '');
    const t0 = performance.now();
    const done = new Promise(resolve => new MutationObserver((_, obs) => {
        if (out.getAttribute('data-verdict')) { obs.disconnect(); resolve(performance.now() - t0); }
    }).observe(out, {attributes: true}));
    box.querySelector('[data-check]').click();
    return await done;
}"""


def _check(page, tryit, text):
    ms = page.evaluate(CHECK_AND_TIME, [tryit, text])
    box = page.locator(f'[data-tryit="{tryit}"]')
    return box, box.locator("[data-verdict]").get_attribute("data-verdict"), ms


@pytest.mark.parametrize("chapter", [c for c in CHAPTERS if _tryits(c)])
def test_every_tryit_answers_in_the_page(browser, site, offline, chapter):
    page, loaded, ready = _open(browser, offline, f"{site.url}/chapters/{chapter}.html")
    ids = _tryits(chapter)
    assert page.eval_on_selector_all("[data-tryit]", "bs => bs.map(b => b.dataset.tryit)") == ids
    for tryit in ids:
        box, verdict, ms = _check(page, tryit, "0")
        assert verdict in ("fail", "refused", "undecided"), (tryit, verdict)
        assert box.locator("[data-verdict]").inner_text().strip()
    print(f"\n{chapter}: load {loaded:.2f} s, every try-it ready {ready:.2f} s")
    slowest = FIGURES.get("_slowest", (0.0, 0.0, ""))
    if ready >= slowest[1]:
        FIGURES["_slowest"] = (loaded, ready, chapter)
        FIGURES["book page, slowest of the chapters: load / every try-it ready"] = \
            f"{loaded:.2f} s / {ready:.2f} s ({chapter})"
    page.close()


def test_a_named_mistake_in_time_in_english_and_spanish(browser, site, offline, screenshots):
    """13-1/try-1 (A(120°)) answered with the angle in degrees: the page names the mistake, with its hint, in
    ≤ 100 ms; the right answer passes; in Spanish the same."""
    page, loaded, ready = _open(browser, offline, f"{site.url}/chapters/13-1-transformation-matrix.html")
    wrong = "[[cos(120), -sin(120)], [sin(120), cos(120)]]"
    times = []
    for _ in range(5):
        box, verdict, ms = _check(page, "13-1/try-1", wrong)
        times.append(ms)
    assert verdict == "fail"
    assert box.locator("[data-mistake]").get_attribute("data-mistake") == "degrees"
    assert "Hint" in box.inner_text()
    page.wait_for_function("b => b.querySelector('[data-echo] mjx-container')", arg=box.element_handle())
    box.scroll_into_view_if_needed()
    box.screenshot(path=str(screenshots / "instant-mistake.png"))
    _, right, ms_right = _check(page, "13-1/try-1", "[[cos(2*pi/3), -sin(2*pi/3)], [sin(2*pi/3), cos(2*pi/3)]]")
    assert right == "pass"
    box.locator("[data-lang]").click()
    _, verdict, _ = _check(page, "13-1/try-1", wrong)
    assert verdict == "fail" and "Pista" in box.inner_text()
    page.wait_for_function("b => b.querySelector('[data-echo] mjx-container')", arg=box.element_handle())
    box.screenshot(path=str(screenshots / "instant-mistake-es.png"))
    times.append(ms_right)
    median = sorted(times)[len(times) // 2]
    print(f"\n13-1/try-1, verdict after Check: first {times[0]:.1f} ms, median of {len(times)} {median:.1f} ms, worst "
          f"{max(times):.1f} ms; page load {loaded:.2f} s, try-its ready {ready:.2f} s")
    FIGURES["instant check, 13-1/try-1 (numbers): verdict after Check"] = \
        f"median {median:.1f} ms, first {times[0]:.1f} ms, worst {max(times):.1f} ms (budget 100 ms)"
    FIGURES["book page 13-1: load / every try-it ready (interactive)"] = f"{loaded:.2f} s / {ready:.2f} s"
    assert median <= 100
    page.close()


def test_symbolic_tryit_and_a_form_the_page_leaves_to_python(browser, site, offline, screenshots):
    page, _, _ = _open(browser, offline, f"{site.url}/chapters/13-2-joints.html")
    right = "x1 + cos(phi1) - x2 + 1.5*cos(phi2) + 0.2*sin(phi2)\ny1 + sin(phi1) - y2 + 1.5*sin(phi2) - 0.2*cos(phi2)"
    times = []
    for _ in range(5):
        _, verdict, ms = _check(page, "13-2/try-1", right)
        times.append(ms)
    median = sorted(times)[len(times) // 2]
    print(f"\n13-2/try-1 (Φ of a revolute joint), verdict after Check: first {times[0]:.1f} ms, median of 5 "
          f"{median:.1f} ms, worst {max(times):.1f} ms")
    FIGURES["instant check, 13-2/try-1 (Φ rows): verdict after Check"] = \
        f"median {median:.1f} ms, first {times[0]:.1f} ms, worst {max(times):.1f} ms (budget 100 ms)"
    assert verdict == "pass" and median <= 100
    _, verdict, _ = _check(page, "13-2/try-1", right.replace("- 0.2*cos", "+ 0.2*cos"))
    assert verdict == "fail"
    d2 = "((x1 + 2*cos(phi1) - x2 + 0.5*sin(phi2))^2 + (y1 + 2*sin(phi1) - y2 - 0.5*cos(phi2))^2)"
    _, verdict, _ = _check(page, "13-2/try-3", f"sqrt{d2} - 3")  # √(d²) − 3: the same zero set as d² − 9
    assert verdict == "pass"
    _, verdict, _ = _check(page, "13-2/try-3", f"({d2} - 9)*(1 + {d2})")  # times a factor that is never zero
    assert verdict == "pass"
    box, verdict, _ = _check(page, "13-2/try-3", f"({d2} - 9)*cos(phi1)")  # a factor that changes sign
    assert verdict == "fail" and box.locator("[data-mistake]").get_attribute("data-mistake") == "vanishing_factor"
    box.scroll_into_view_if_needed()
    box.screenshot(path=str(screenshots / "instant-vanishing-factor.png"))
    # times d², which touches zero without changing sign (where the points meet): the checker's zero-set search
    box, verdict, _ = _check(page, "13-2/try-3", f"({d2} - 9)*{d2}")
    assert verdict == "undecided"
    href = box.locator("a.kinbook-instant-python").get_attribute("href")
    assert href.startswith("../live/notebooks/index.html?path=13-2-joints.ipynb")
    _, verdict, _ = _check(page, "13-2/try-1", "__import__('os').system('ls')")
    assert verdict == "refused"
    page.close()


def test_the_site_serves_the_instant_checks_itself():
    folder = SITE / "instant"
    assert (folder / "math.js").is_file() and (folder / "kinbook-instant.js").is_file()
    for chapter in CHAPTERS:
        ids = _tryits(chapter)
        if ids:
            data = json.loads((folder / f"{chapter.split('-')[0]}-{chapter.split('-')[1]}.json").read_text())
            assert sorted(data["tryits"]) == sorted(ids)
            for spec in data["tryits"].values():
                for mistake in spec["mistakes"]:
                    assert mistake["title"]["es"] and mistake["hint"]["es"], mistake["code"]
