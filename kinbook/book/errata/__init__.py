"""The textbook's errata, each with evidence that kinbook computes.

Every entry says where the book is wrong, what it prints, what is correct, and — for numbers and formulas —
a function that measures the discrepancy with kinbook's own derivation or solution. The tests run every
evidence function and assert that the printed version really disagrees and the corrected one agrees, so an
erratum cannot silently become false. The errata notebook renders :func:`table`.

The book's printed numbers and formulas appear here only as the thing under test.
"""

from __future__ import annotations

import html

from ...errors import InputError
from ..notation import html_math, html_text
from . import ch13, ch14
from .erratum import KINDS, Erratum, Evidence

__all__ = ["Erratum", "Evidence", "ERRATA", "KINDS", "table", "show", "get"]

ERRATA = ch13.ERRATA + ch14.ERRATA
"""Every erratum, in the book's order: chapter 13 (:mod:`.ch13`), then chapter 14 (:mod:`.ch14`)."""


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
                     f"<p style='margin:0'>The book prints: {html_math(e.printed, display=True)}</p>",
                     f"<p style='margin:0'>Correct: {html_math(e.correct, display=True)}</p>"]
            if ev is not None:
                parts.append(f"<p style='margin:4px 0 0 0'>Evidence: {html_text(ev.text)}</p>")
            if e.note:
                parts.append(f"<p style='margin:4px 0 0 0'><i>{html_text(e.note)}</i></p>")
            cards.append("<div style='text-align:left; border-left:4px solid #c62828; padding:4px 10px; "
                         "margin:10px 0; background:#fdf6f6'>" + "".join(parts) + "</div>")
        return "".join(cards)


def show(*ids):
    """The errata with these ids, evidence computed (what a chapter notebook displays)."""
    return ErrataTable([get(i) for i in ids])


def table(prefix=""):
    """The errata whose id starts with ``prefix`` (e.g. "13", "14.3"; all by default), evidence computed."""
    return ErrataTable([e for e in ERRATA if e.id.startswith(prefix)])
