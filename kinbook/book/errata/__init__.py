"""The textbook's errata, each with evidence that kinbook computes.

Every entry says where the book is wrong, what it prints, what is correct, and — for numbers and formulas —
a function that measures the discrepancy with kinbook's own derivation or solution. The tests run every
evidence function and assert that the printed version really disagrees and the corrected one agrees, so an
erratum cannot silently become false. The errata notebook renders :func:`table`.

The book's printed numbers and formulas appear here only as the thing under test.
"""

from __future__ import annotations

import html
import re

from ...errors import InputError
from ..notation import html_math, html_text
from . import ch13, ch14
from .erratum import KINDS, Erratum, Evidence

__all__ = ["Erratum", "Evidence", "ERRATA", "BOOK_ORDER", "KINDS", "SHOWN_IN", "table", "show", "get", "anchor", "links",
           "lines"]

BOOK_ORDER = """
13.5-q-elements 13.5-eq4-text 13.5-revolute-words 13.5-eq21 13.5-three-points 13.5-eq24 13.5-eq25 13.5-rt-collinearity
13.5-ex1-eq-ref 13.5-ex1-solution 13.5-ex2-translational 13.5-ex2-l3 13.5-ex2-driver 13.5-motrices
13.5-joint-labels 13.5-ex3-system 13.5-ex3-x2 13.5-ex4-phi8-substituted 13.5-ex4-phi8 13.5-ex4-phi8-system
13.6-q-example1 13.6-previous-chapter 13.6-table-13.1-text 13.6-table-13.2 13.6-table-13.3 13.6-table-13.4 13.7-velocity-rhs
13.7-ex5-reference 13.7-ex5-ground-points 13.7-ex5-phi8-row 13.7-ex5-joint3-working 13.7-ex5-velocities 13.8-revolute-Phiq-qd
13.8-gamma-sign 13.8-table-13.5-rr 13.8-table-13.5-t 13.8-driver-second-derivative 13.8-ex6-point-A
13.8-ex6-joint-label 13.8-ex6-solution-dots 13.8-ex6-point-acceleration 13.8-ex6-accelerations 14.2-termas 14.2-elementary-rotations
14.2-A21-row2-first 14.2-A21-row3 14.2-turns-frames 14.2-A-theta-second 14.2-omega-matrix 14.2-omega-prime 14.2-rates-inverse-first
14.3-euler-theorem 14.3-A-of-p 14.3-p-from-A 14.3-G-row2 14.3-Ep-Gp 14.3-p-dot 14.3-a-bar 14.3-A-ddot-a
14.4-n2-vectors 14.4-n2-primes 14.4-p1-local-form 14.4-p1-two-rows 14.4-universal-primes 14.4-revolute-tilde
14.5-cross-references 14.5-n1-rj 14.5-A-ddot-a 14.5-gamma-n1 14.5-gamma-n1-table
""".split()
"""Every erratum id in the order of the passages in the book (the section, then where in it: an example's slips
after the text before the example, in the example's own order); :data:`ERRATA` follows it."""

ERRATA = sorted(ch13.ERRATA + ch14.ERRATA, key=lambda e: BOOK_ORDER.index(e.id))
"""Every erratum, in the book's order (:data:`BOOK_ORDER`): chapter 13 (:mod:`.ch13`), then chapter 14 (:mod:`.ch14`)."""

SHOWN_IN = {
    "13.5-q-elements": "13-1-transformation-matrix",
    "13.5-eq4-text": "13-1-transformation-matrix",
    "13.5-revolute-words": "13-2-joints",
    "13.5-eq21": "13-2-joints",
    "13.5-three-points": "13-2-joints",
    "13.5-eq24": "13-2-joints",
    "13.5-eq25": "13-2-joints",
    "13.5-rt-collinearity": "13-2-joints",
    "13.5-ex1-eq-ref": "13-3-position-analysis",
    "13.5-ex1-solution": "13-3-position-analysis",
    "13.5-ex2-translational": "13-3-position-analysis",
    "13.5-ex2-l3": "13-3-position-analysis",
    "13.5-ex2-driver": "13-3-position-analysis",
    "13.5-motrices": "13-3-position-analysis",
    "13.5-joint-labels": "13-3-position-analysis",
    "13.5-ex3-system": "13-3-position-analysis",
    "13.5-ex3-x2": "13-3-position-analysis",
    "13.5-ex4-phi8-substituted": "13-3-position-analysis",
    "13.5-ex4-phi8": "13-3-position-analysis",
    "13.5-ex4-phi8-system": "13-3-position-analysis",
    "13.6-q-example1": "13-5-jacobian",
    "13.6-previous-chapter": "13-5-jacobian",
    "13.6-table-13.1-text": "13-5-jacobian",
    "13.6-table-13.2": "13-5-jacobian",
    "13.6-table-13.3": "13-5-jacobian",
    "13.6-table-13.4": "13-5-jacobian",
    "13.7-velocity-rhs": "13-6-velocity-analysis",
    "13.7-ex5-reference": "13-6-velocity-analysis",
    "13.7-ex5-ground-points": "13-5-jacobian",
    "13.7-ex5-phi8-row": "13-5-jacobian",
    "13.7-ex5-joint3-working": "13-5-jacobian",
    "13.7-ex5-velocities": "13-6-velocity-analysis",
    "13.8-revolute-Phiq-qd": "13-7-acceleration-analysis",
    "13.8-gamma-sign": "13-7-acceleration-analysis",
    "13.8-table-13.5-rr": "13-7-acceleration-analysis",
    "13.8-table-13.5-t": "13-7-acceleration-analysis",
    "13.8-driver-second-derivative": "13-7-acceleration-analysis",
    "13.8-ex6-point-A": "13-7-acceleration-analysis",
    "13.8-ex6-joint-label": "13-7-acceleration-analysis",
    "13.8-ex6-solution-dots": "13-7-acceleration-analysis",
    "13.8-ex6-point-acceleration": "13-7-acceleration-analysis",
    "13.8-ex6-accelerations": "13-7-acceleration-analysis",
    "14.2-termas": "14-2-euler-angles",
    "14.2-elementary-rotations": "14-2-euler-angles",
    "14.2-A21-row2-first": "14-2-euler-angles",
    "14.2-A21-row3": "14-2-euler-angles",
    "14.2-turns-frames": "14-2-euler-angles",
    "14.2-A-theta-second": "14-2-euler-angles",
    "14.2-omega-matrix": "14-2-euler-angles",
    "14.2-omega-prime": "14-2-euler-angles",
    "14.2-rates-inverse-first": "14-2-euler-angles",
    "14.3-euler-theorem": "14-3-euler-parameters",
    "14.3-A-of-p": "14-3-euler-parameters",
    "14.3-p-from-A": "14-3-euler-parameters",
    "14.3-G-row2": "14-3-euler-parameters",
    "14.3-Ep-Gp": "14-3-euler-parameters",
    "14.3-p-dot": "14-3-euler-parameters",
    "14.3-a-bar": "14-3-euler-parameters",
    "14.3-A-ddot-a": "14-3-euler-parameters",
    "14.4-n2-vectors": "14-4-spatial-constraints",
    "14.4-n2-primes": "14-4-spatial-constraints",
    "14.4-p1-local-form": "14-4-spatial-constraints",
    "14.4-p1-two-rows": "14-4-spatial-constraints",
    "14.4-universal-primes": "14-4-spatial-constraints",
    "14.4-revolute-tilde": "14-4-spatial-constraints",
    "14.5-cross-references": "14-5-spatial-analysis",
    "14.5-n1-rj": "14-5-spatial-analysis",
    "14.5-A-ddot-a": "14-5-spatial-analysis",
    "14.5-gamma-n1": "14-5-spatial-analysis",
    "14.5-gamma-n1-table": "14-5-spatial-analysis",
}
"""The chapter notebook (file name without .ipynb) that shows each erratum where the book's passage is rebuilt;
its card links there, and that notebook lists its errata with links to their cards on the errata page
(tests/book/test_errata.py checks both against the notebooks)."""

PAGE = "errata"
"""The errata notebook (chapters/errata.ipynb)."""


def anchor(erratum_id):
    """The HTML id of an erratum's card: ``erratum-13.5-ex1-solution``."""
    return f"erratum-{erratum_id}"


def get(erratum_id):
    """The erratum with this id."""
    for e in ERRATA:
        if e.id == erratum_id:
            return e
    raise InputError(f"no erratum {str(erratum_id)[:80]!r}: the ids are {', '.join(e.id for e in ERRATA)}")


class ErrataTable:
    """All errata with their evidence computed; renders as an HTML table in a notebook."""

    def __init__(self, errata):
        self.rows = [(e, e.check()) for e in errata]

    def __repr__(self):
        lines = []
        for e, ev in self.rows:
            lines.append(f"[{e.id}] {e.where}\n  printed: {e.printed}\n  correct: {e.correct}")
            if ev is not None:
                lines.append(f"  evidence: {ev.text}")
            if e.note:
                lines.append(f"  note: {e.note}")
        return "\n".join(lines)

    def _repr_html_(self):
        cards = []
        for e, ev in self.rows:
            parts = [f"<p style='margin:0 0 4px 0'><b>{html_text(e.where)}</b> "
                     f"<span style='color:#777'>[{html.escape(e.id)}, {e.kind}]</span></p>",
                     f"<p style='margin:0'>The book prints:</p>{_formula(e.printed)}",
                     f"<p style='margin:0'>Correct:</p>{_formula(e.correct)}"]
            # a long inline formula cannot wrap: its paragraph scrolls, not the card
            if ev is not None:
                parts.append(f"<p style='margin:4px 0 0 0; overflow-x:auto'>Evidence: {html_text(ev.text)}</p>")
            if e.note:
                parts.append(f"<p style='margin:4px 0 0 0; overflow-x:auto'><i>{html_text(e.note)}</i></p>")
            parts.append(_links(e))
            cards.append(f"<div id='{anchor(e.id)}' style='text-align:left; border-left:4px solid #c62828; "
                         "padding:4px 10px; margin:10px 0; background:#fdf6f6; max-width:100%; box-sizing:border-box'>"
                         + "".join(parts) + "</div>")
        return "".join(cards)


def _formula(tex):
    """A displayed formula, broken into lines where it is long (:func:`lines`), in a box of its own that scrolls
    sideways should a line still be wider than the card (the card's other formulas and text stay put; a scrollbar
    at the foot of a long page would hide which formula it moves). Words (``\\text{…}`` with at most short math
    between) are set as a paragraph that wraps."""
    prose = _as_prose(tex)
    if prose is not None:
        return f"<p style='margin:0 0 4px 1.5em'>{prose}</p>"
    return (f"<div style='overflow-x:auto; overflow-y:hidden; max-width:100%; margin:0 0 2px 0'>"
            f"{html_math(lines(tex), display=True)}</div>")


def _as_prose(tex):
    """HTML for a "formula" that is words — ``\\text{…}`` groups with short math between them — or None."""
    parts, k, words = [], 0, 0
    while k < len(tex):
        j = tex.find("\\text{", k)
        if j < 0:
            parts.append(("math", tex[k:]))
            break
        parts.append(("math", tex[k:j]))
        depth, m = 0, j + 5
        while m < len(tex):
            depth += {"{": 1, "}": -1}.get(tex[m], 0)
            if depth == 0:
                break
            m += 1
        parts.append(("text", tex[j + 6:m]))
        words += m - j - 6
        k = m + 1
    math = [p.strip().strip("\\ ").strip() for kind, p in parts if kind == "math"]
    if words < 40 or words < 2 * sum(len(p) for p in math):
        return None
    return "".join(html.escape(p) if kind == "text" else (html_math(p.strip()) if p.strip().strip("\\ ").strip()
                                                          else " ") for kind, p in parts)


WIDTH = 54
"""About how many characters of a formula fit a line of a card at 1200 px (the book's text column is 600 px wide;
a TeX command counts as one)."""


def _visible(tex):
    """About how many characters ``tex`` sets: a command counts as one, braces and scripts' marks as none."""
    tex = re.sub(r"\\(sin|cos|tan|sen|operatorname\{\w+\})(?![A-Za-z])", "xxx", tex)   # set as three letters
    return len(re.sub(r"[{}^_]", "", re.sub(r"\\[A-Za-z]+|\\[,;:! ]", "x", tex)))


def _split_top(tex, seps):
    """``tex`` cut at the separators ``seps`` that stand outside every brace and parenthesis; each cut keeps its
    separator at the start of the next part (at the end of the part for a comma)."""
    parts, depth, start, k = [], 0, 0, 0
    while k < len(tex):
        c = tex[k]
        if c == "\\" and tex[k + 1:k + 5] in ("left", "righ"):
            k += 5
            continue
        if tex.startswith("\\begin{", k) or tex.startswith("\\end{", k):  # a matrix is one piece
            depth += 1 if tex[k + 1] == "b" else -1
        if c in "{([":
            depth += 1
        elif c in "})]":
            depth -= 1
        elif depth == 0:
            for sep in seps:
                if tex.startswith(sep, k) and k > start:
                    cut = k + len(sep) if sep.startswith(",") else k
                    parts.append(tex[start:cut].strip())
                    start = cut
                    k += len(sep) - 1
                    break
        k += 1
    parts.append(tex[start:].strip())
    return [p for p in parts if p]


def lines(tex):
    """A long formula as several lines: first at its top-level list separators (``,\\ ``, ``\\quad``), then a part
    still too long at its top-level + and − signs. A formula that fits is returned as it is."""
    if _visible(tex) <= WIDTH:
        return tex
    out = []
    for part in _split_top(tex, (",\\ ", ",\\quad", ",\\qquad", "\\quad", "\\ \\text{")):
        words = re.fullmatch(r"(\\ )?\\text\{(.*)\}", part)
        if words and _visible(part) > WIDTH and "; " in words.group(2):  # a long remark: one clause a line
            clauses = words.group(2).split("; ")
            out += [f"\\text{{{c}{';' if k < len(clauses) - 1 else ''}}}" for k, c in enumerate(clauses)]
        elif _visible(part) > WIDTH:
            terms = _split_top(part, (" - ", " + ", " = "))
            line = ""
            for term in terms:
                if line and _visible(line + term) > WIDTH:
                    out.append(line)
                    line = "\\qquad " + term
                else:
                    line = f"{line} {term}".strip()
            out.append(line)
        else:
            out.append(part)
    if len(out) == 1:
        return tex
    return "\\begin{aligned}" + " \\\\ ".join("&" + line for line in out) + "\\end{aligned}"


def _links(e):
    """The card's way back: to the notebook that rebuilds the book's passage, and to the card on the errata page."""
    home = SHOWN_IN.get(e.id)
    out = []
    if home:
        out.append(f"<a href='{home}.ipynb#{anchor(e.id)}'>the passage, rebuilt in notebook {home[:4]}</a>")
    out.append(f"<a href='{PAGE}.ipynb#{anchor(e.id)}'>this erratum among all errata</a>")
    return f"<p style='margin:4px 0 0 0; font-size:90%'>{' · '.join(out)}</p>"


def show(*ids):
    """The errata with these ids, evidence computed (what a chapter notebook displays)."""
    return ErrataTable([get(i) for i in ids])


def table(prefix=""):
    """The errata whose id starts with ``prefix`` (e.g. "13", "14.3"; all by default), evidence computed."""
    return ErrataTable([e for e in ERRATA if e.id.startswith(prefix)])


def links(notebook):
    """Markdown: the errata a chapter notebook shows, each a link to its card on the errata page (the cell that
    closes every chapter notebook with errata)."""
    ids = [i for i, home in SHOWN_IN.items() if home == notebook]
    if not ids:
        return ""
    items = ", ".join(f"[{i}]({PAGE}.ipynb#{anchor(i)})" for i in ids)
    return (f"**Errata of this section.** {items} — each with the evidence kinbook computes, on the "
            f"[errata page]({PAGE}.ipynb).")
