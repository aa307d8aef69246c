"""Every erratum must stand: the book's version disagrees with kinbook, the corrected one agrees."""

import json
import re
from pathlib import Path

import pytest

from kinbook.book import errata

ROOT = Path(__file__).resolve().parents[2]
COMPUTED = [e for e in errata.ERRATA if e.evidence is not None]


@pytest.mark.parametrize("erratum", COMPUTED, ids=[e.id for e in COMPUTED])
def test_evidence_holds(erratum):
    ev = erratum.check()
    assert ev.printed_error > 1e-2, f"{erratum.id}: the book's version agrees with kinbook after all"
    # formulas agree to rounding; where the book's own printed digits take part, to those digits
    assert ev.tolerance <= 1e-9 or ev.tolerance <= 2e-4 and erratum.kind != "wording"
    assert ev.corrected_error < ev.tolerance


def test_ids_are_unique_and_every_entry_is_complete():
    ids = [e.id for e in errata.ERRATA]
    assert len(ids) == len(set(ids))
    for e in errata.ERRATA:
        assert e.where and e.printed and e.correct and e.kind in errata.KINDS
        assert e.kind == "wording" or e.evidence is not None  # a number, formula or sign slip is measured
        assert "struck" not in e.where.lower()  # a passage the book strikes through is not printed


def test_entries_that_were_wrong_stay_gone():
    """Eq. 37 is right (the book defines φ′ by its rate and takes φ′(0) = φ⁰); the normalization equation of
    §14.5 is in a struck-through passage: neither is an erratum."""
    ids = {e.id for e in errata.ERRATA}
    assert "13.5-eq37" not in ids and "14.5-normalization" not in ids


def test_table_renders_every_entry():
    t = errata.table("13")
    html = t._repr_html_()
    assert html.count("border-left") == len([e for e in errata.ERRATA if e.id.startswith("13")])
    assert "|AB| = 6.092" in repr(t)


DOLLAR_TEX = re.compile(r"\$[^$]*\\[A-Za-z]+[^$]*\$")


def test_html_outputs_carry_math_the_static_book_typesets():
    """The book's MathJax (Sphinx's) reads \\(…\\) and \\[…\\] in HTML outputs, never $…$: a table with $\\Phi$
    shows raw TeX on the website while looking fine in JupyterLab."""
    for html in (errata.table("13")._repr_html_(), errata.table("14")._repr_html_()):
        assert "\\(" in html or "\\[" in html
        assert not DOLLAR_TEX.search(html), DOLLAR_TEX.search(html).group(0)[:80]
    stored = sorted(ROOT.glob("chapters/*.ipynb")) + sorted(ROOT.glob("exercises/**/*.ipynb"))
    for path in stored:
        for cell in json.loads(path.read_text())["cells"]:
            for out in cell.get("outputs", []):
                found = DOLLAR_TEX.search("".join(out.get("data", {}).get("text/html", "")))
                assert not found, f"{path.name}: $…$ in an HTML output: {found.group(0)[:80]}"
