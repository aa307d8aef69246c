"""Every erratum must stand: the book's version disagrees with kinbook, the corrected one agrees."""

import json
import re
from html import unescape
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


# ------------------------------------------------------------------------------------------- typeset cards
TITLE = re.compile(r"<b>(.*?)</b> <span")
NOTE = re.compile(r"<i>(.*?)</i>")
EVIDENCE = re.compile(r"<p[^>]*>Evidence: (.*?)</p>")
INLINE = re.compile(r"\\\((.*?)\\\)")
RAW_MATH = re.compile(r"[\\$_^{}]|[\u0370-\u03ff\u0300-\u036f∂ᵀ⁰¹²³⁴⁵⁶⁷⁸⁹₀₁₂₃₄₅₆₇₈₉]|\b[A-Za-z]{1,3}'(?![a-z])"
                      r"|(?:^|[\s(])[b-zB-Z](?=[\s,;:)]|$)")
"""A formula typed as text: TeX markup, a Greek letter, an accent, a superscript or subscript digit, a primed name
(ω', phi' — not a possessive), a lone letter (t = 0, the points B, C — "a" and "A" are words, and a letter quoted
as the book prints it, “o”, is prose)."""
CODE = re.compile(r"[\w.]*\b\w+?_[a-z]{2,}\w*(?:\([^)]*\))?")
"""A function named in the prose (kinbook.spatial.euler_rates_from_omega(frame='body'), p_from_A,
point_acceleration): not a formula (a subscript is one letter or a number: x_i, Φ_q, γ_1)."""


def _titles(cards_html):
    return [unescape(t) for t in TITLE.findall(cards_html)]


def _notes(cards_html):
    return [unescape(t) for t in NOTE.findall(cards_html)]


def _evidence(cards_html):
    return [unescape(t) for t in EVIDENCE.findall(cards_html)]


def _prose(cards_html):
    """Every title, evidence and note of the cards: the text around formulas."""
    return _titles(cards_html) + _evidence(cards_html) + _notes(cards_html)


def _raw_math(text):
    return RAW_MATH.findall(CODE.sub(" ", INLINE.sub(" ", text)))


def test_titles_evidence_and_notes_set_their_formulas_as_math():
    """Every card's title (its <b>), evidence and note (its <i>) have their formulas in \\(…\\), which JupyterLab
    (untrusted too), the book's MathJax and `make html` typeset; the prose around them carries no formula as text."""
    cards = errata.table()._repr_html_()
    titles, notes = _titles(cards), _notes(cards)
    assert len(titles) == len(errata.ERRATA) and len(notes) == sum(bool(e.note) for e in errata.ERRATA)
    assert len(_evidence(cards)) == sum(e.evidence is not None for e in errata.ERRATA)
    assert [t for t in _prose(cards) if _raw_math(t)] == []
    assert sum(bool(INLINE.search(t)) for t in titles) >= 35  # a formula in more than half the titles
    # one title spelled out: row 2 of Φ_q q̇ (§13.8), bold Φ with subscript bold q, times q̇ — the book's notation
    card = errata.show("13.8-revolute-Phiq-qd")._repr_html_()
    assert INLINE.findall(_titles(card)[0]) == [r"\boldsymbol\Phi_{\mathbf q}\dot{\mathbf q}"]
    # the old way of writing it fails the check, and a function's name in the prose does not
    assert _raw_math("§13.8, the revolute joint worked step by step: row 2 of Φ_q q̇") == ["Φ", "_", "\u0307"]
    assert _raw_math("§14.2, the first inverse relation (angle rates from phi'), row 2") == ["phi'"]
    assert _raw_math("Example 1 prints −0.7071 (x_2 = −cos 45°)") == ["_"]
    assert _raw_math("kinbook's p_from_A also covers it; the parameters' rates give ω") == ["ω"]


def test_stored_notebooks_show_typeset_cards():
    """The cards stored in the notebooks (errata.ipynb and the chapters that show errata) are the typeset ones."""
    seen = 0
    for path in sorted(ROOT.glob("chapters/*.ipynb")):
        for cell in json.loads(path.read_text())["cells"]:
            for out in cell.get("outputs", []):
                cards = "".join(out.get("data", {}).get("text/html", ""))
                for text in _prose(cards):
                    assert not _raw_math(text), f"{path.name}: {text}"
                    seen += 1
    assert seen >= 3 * len(errata.ERRATA)  # errata.ipynb has every card, the chapters show them again


MATHJAX = ROOT / ".venv-web" / "npm" / "node_modules" / "mathjax"
TEX2MML = """
require(process.argv[2]).init({loader: {load: ['input/tex']}, startup: {typeset: false}}).then(async (MathJax) => {
  const texs = JSON.parse(require('fs').readFileSync(0, 'utf8'));
  const out = [];
  for (const tex of texs) out.push(await MathJax.tex2mmlPromise(tex, {display: false}));
  console.log(JSON.stringify(out));
}).catch((e) => { console.error(e.message); process.exit(1); });
"""


def test_card_formulas_typeset_in_mathjax(tmp_path):
    """The book's own MathJax 3 (`make web-env` installs it) reads every formula of the titles, evidence and notes: no TeX error, no undefined
    macro (MathJax marks those in red), and the book's bold and accents come out as MathML says they should."""
    import shutil
    import subprocess

    node = shutil.which("node")
    if node is None or not MATHJAX.is_dir():
        pytest.skip("needs node and MathJax 3 (make web-env)")
    cards = errata.table()._repr_html_()
    texs = sorted({m for t in _prose(cards) for m in INLINE.findall(t)}
                  | {errata.lines(f) for e in errata.ERRATA for f in (e.printed, e.correct)})  # the displayed lines
    script = tmp_path / "tex2mml.js"
    script.write_text(TEX2MML)
    run = subprocess.run([node, str(script), str(MATHJAX)], input=json.dumps(texs), capture_output=True, text=True,
                         timeout=120, check=True)
    mml = dict(zip(texs, json.loads(run.stdout)))
    for tex, m in mml.items():
        assert "<merror" not in m and 'mathcolor="red"' not in m, (tex, m)
    # Φ_q q̇: a bold Φ with a bold q below it, then a bold q under a dot
    phi_q = re.sub(r"<mrow[^>]*>|</mrow>|\s+", "", unescape(mml[r"\boldsymbol\Phi_{\mathbf q}\dot{\mathbf q}"]))
    assert '<msub><mimathvariant="bold">Φ</mi><mimathvariant="bold">q</mi></msub>' in phi_q, phi_q
    assert '<mover><mimathvariant="bold">q</mi><mo>˙</mo></mover>' in phi_q, phi_q


# ------------------------------------------------------------------------------------------- order, kinds, links
def _section(e):
    return tuple(int(x) for x in re.search(r"§(\d+)\.(\d+)", e.where).groups())


def test_the_errata_are_in_the_books_order():
    """Sections never go back, and within a section the worked examples come in their own order (example 1's
    slips before example 2's); BOOK_ORDER lists every erratum once."""
    assert sorted(errata.BOOK_ORDER) == sorted(e.id for e in errata.ERRATA)
    assert len(set(errata.BOOK_ORDER)) == len(errata.BOOK_ORDER)
    sections = [_section(e) for e in errata.ERRATA]
    assert sections == sorted(sections), [e.id for e in errata.ERRATA]
    for sec in set(sections):
        examples = [int(m.group(1)) for e in errata.ERRATA if _section(e) == sec
                    for m in [re.search(r"example (\d+)", e.where)] if m]
        assert examples == sorted(examples), (sec, examples)


def test_the_kinds_are_used_by_their_definitions():
    kinds = {e.kind for e in errata.ERRATA}
    assert {"typo", "inconsistency"} <= kinds <= set(errata.KINDS)
    for e in errata.ERRATA:
        if e.kind == "typo":  # one letter, index, prime or accent for another: measured like a formula
            assert e.evidence is not None, e.id


def _chapter_cells():
    for path in sorted((ROOT / "chapters").glob("1*.ipynb")):
        yield path.stem, json.loads(path.read_text())["cells"]


def test_every_card_links_to_its_section_and_every_section_to_its_entries():
    first = {}
    for stem, cells in _chapter_cells():
        for cell in cells:
            if cell["cell_type"] != "code":
                continue
            src = "".join(cell["source"])
            for call in re.findall(r"errata\.show\(([^)]*)\)", src):
                for i in re.findall(r'"([^"]+)"', call):
                    first.setdefault(i, stem)
            for prefix in re.findall(r'errata\.table\("([^"]*)"\)', src):
                for e in errata.ERRATA:
                    if e.id.startswith(prefix):
                        first.setdefault(e.id, stem)
    assert first == errata.SHOWN_IN, "SHOWN_IN must name the notebook that first shows each erratum"
    cards = errata.table()._repr_html_()
    for e in errata.ERRATA:
        home = errata.SHOWN_IN[e.id]
        assert f"id='{errata.anchor(e.id)}'" in cards
        assert f"href='{home}.ipynb#{errata.anchor(e.id)}'" in cards
    for stem, cells in _chapter_cells():
        text = errata.links(stem)
        last = "".join(cells[-1]["source"]) if cells[-1]["cell_type"] == "markdown" else ""
        assert (last == text) if text else "Errata of this section" not in last, stem
        for e in errata.ERRATA:
            if errata.SHOWN_IN[e.id] == stem:
                assert f"(errata.ipynb#{errata.anchor(e.id)})" in last


def test_each_formula_of_a_card_scrolls_on_its_own():
    """A formula wider than the card scrolls in its own box, never the whole page (the only scrollbar at the foot of
    a 30-card group hid the slip it moved)."""
    cards = errata.table()._repr_html_()
    for e in errata.ERRATA:  # a long formula comes in lines that fit a card at 1200 px
        for f in (e.printed, e.correct):
            if errata._as_prose(f) is None:  # words wrap as a paragraph
                for line in errata.lines(f).split(" \\\\ &"):
                    rows = line.split("\\\\") if "bmatrix" in line else [line]  # a matrix: as wide as a row
                    assert max(errata._visible(r) for r in rows) <= 2 * errata.WIDTH, (e.id, line)
    displayed = cards.count("\\[")
    assert displayed == sum(errata._as_prose(f) is None for e in errata.ERRATA for f in (e.printed, e.correct))
    assert cards.count("<div style='overflow-x:auto; overflow-y:hidden; max-width:100%; margin:0 0 2px 0'>\\[") == \
        displayed
