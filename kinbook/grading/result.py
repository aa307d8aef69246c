"""Results of a check: :class:`CheckResult` and the per-row :class:`RowResult` it is made of.

Modelled on otter-grader's test results: small frozen dataclasses that render themselves in a notebook
(``_repr_html_``: a table with one coloured line per row of Φ, Φ_q, ν or γ) and print plainly in a terminal.
Their texts are kept as :class:`~kinbook.grading._i18n.Msg` objects and written in the current language
when shown (``messages``, ``repr``, HTML), so switching the language re-renders an existing result.
"""

from __future__ import annotations

import html
from dataclasses import dataclass

from ._i18n import Msg, render

__all__ = ["CheckResult", "RowResult"]

_COLOURS = {"ok": "#d4edda", "wrong": "#f8d7da", "missing": "#fff3cd", "extra": "#fff3cd", "info": "#e2e3e5"}
_SYMBOL = {"ok": "✓", "wrong": "✗", "missing": "∅", "extra": "+", "info": "·"}


@dataclass(frozen=True, init=False)
class RowResult:
    """Verdict on one row of the answer (one equation of Φ, one row of Φ_q, one entry of ν or γ).

    Attributes
    ----------
    label : str
        The book's name of the row the answer row stands for ("Φ_4"), or the answer's own row.
    status : {"ok", "wrong", "missing", "extra"}
    message : str
        In the current language.
    mistake : str or None
        Catalogue code of the mistake found in this row.
    entries : tuple of str
        For Φ_q: one status per column ("ok" or a mistake code).
    score : float
        Credit for this row, in [0, 1].
    """

    _label: object
    status: str
    _message: object
    mistake: str | None
    entries: tuple
    score: float

    def __init__(self, label, status, message="", mistake=None, entries=(), score=0.0):
        object.__setattr__(self, "_label", label)
        object.__setattr__(self, "status", status)
        object.__setattr__(self, "_message", message)
        object.__setattr__(self, "mistake", mistake)
        object.__setattr__(self, "entries", tuple(entries))
        object.__setattr__(self, "score", float(score))

    @property
    def label(self):
        return render(self._label)

    @property
    def message(self):
        return render(self._message) if self._message else ""


@dataclass(frozen=True, init=False)
class CheckResult:
    """The verdict of a checker.

    Attributes
    ----------
    passed : bool
        True when the answer is fully correct (score 1).
    score : float
        Partial credit in [0, 1].
    messages : list of str
        What is right and wrong, in the current language (:func:`kinbook.set_language`).
    mistakes : list of str
        Catalogue codes of the mistakes found, without repetitions, in order of appearance
        (see :mod:`kinbook.grading.catalogue` and docs/mistakes.md).
    rows : tuple of RowResult
        Per-row (and, for Φ_q, per-entry) detail.
    quantity : str
        "Φ", "Φ_q", "ν", "γ" or the name of a value (in the current language).
    columns : tuple of str
        Names of the columns of Φ_q (coordinates), when ``rows`` carry entries.
    read : (str, str or None) or None
        The answer as the checker read it, as plain text and as LaTeX (:mod:`kinbook.grading.echo`), shown before
        the verdict; None when it was not read (a refused answer says why instead).
    """

    passed: bool
    score: float
    notes: tuple
    mistakes: list
    rows: tuple
    _quantity: object
    columns: tuple
    _echo = None

    def __init__(self, passed, score, messages=(), mistakes=(), rows=(), quantity="", columns=()):
        object.__setattr__(self, "passed", bool(passed))
        object.__setattr__(self, "score", float(score))
        object.__setattr__(self, "notes", tuple(messages))
        object.__setattr__(self, "mistakes", list(mistakes))
        object.__setattr__(self, "rows", tuple(rows))
        object.__setattr__(self, "_quantity", quantity)
        object.__setattr__(self, "columns", tuple(columns))

    @property
    def quantity(self):
        return render(self._quantity)

    @property
    def messages(self):
        return [render(m) for m in self.notes]

    def __bool__(self):
        return bool(self.passed)

    @property
    def read(self):
        """The answer as read, ``(text, latex)``, or None (made when first asked for: a result never shown costs
        nothing)."""
        echo = self._echo
        if callable(echo):
            try:
                echo = echo()
            except Exception:  # noqa: BLE001 — an answer that cannot be shown as read is not echoed
                echo = None
            object.__setattr__(self, "_echo", echo)
        return echo

    def echo(self, found):
        """Attach the answer as read: ``(text, latex)``, or a function returning it (or None) when first shown, or
        another CheckResult whose echo this one shares; returns self."""
        if isinstance(found, CheckResult):
            found = found._echo
        object.__setattr__(self, "_echo", found)
        return self

    def __repr__(self):
        word = render(Msg("h.passed" if self.passed else "h.failed"))
        head = f"CheckResult({self.quantity}: {word}, {render(Msg('h.score'))}={self.score:.2f}"
        if self.mistakes:
            head += f", {render(Msg('h.mistakes'))}={self.mistakes}"
        lines = [head + ")"]
        if self.read is not None:
            lines.append(f"  {render(Msg('h.read_as'))}: {self.read[0]}")
        lines += [f"  {m}" for m in self.messages]
        return "\n".join(lines)

    def _repr_html_(self):
        return self.html(math=True)

    def html(self, math=True):
        """The result as HTML: the answer as read first (typeset as LaTeX for MathJax with ``math``, as plain text
        otherwise — a feedback page has no MathJax), then the verdict, the messages and the rows."""
        colour = "#155724" if self.passed else "#721c24"
        verdict = "✓" if self.passed else "✗"
        esc = html.escape
        out = ["<div>"]
        if self.read is not None:
            text, latex = self.read
            shown = f"\\[{esc(latex)}\\]" if math and latex else f"<code>{esc(text)}</code>"
            out.append(f'<p class="kb-read">{esc(render(Msg("h.read_as")))}: {shown}</p>')
        out += [
            f'<p style="color:{colour};font-weight:bold">{verdict} {esc(self.quantity)} — '
            f"{esc(render(Msg('h.score')))} {self.score:.2f}</p>"
        ]
        if self.notes:
            out.append("<ul>" + "".join(f"<li>{esc(m)}</li>" for m in self.messages) + "</ul>")
        if self.rows:
            with_entries = any(r.entries for r in self.rows) and self.columns
            head = f"<th>{esc(render(Msg('h.row')))}</th>"
            if with_entries:
                head += "".join(f"<th>{esc(c)}</th>" for c in self.columns)
            head += f"<th>{esc(render(Msg('h.verdict')))}</th>"
            body = []
            for r in self.rows:
                bg = _COLOURS.get(r.status, "#ffffff")
                cells = f"<td>{esc(r.label)}</td>"
                if with_entries:
                    for e in (r.entries or ("",) * len(self.columns)):
                        c = _COLOURS["ok"] if e == "ok" else (_COLOURS["wrong"] if e else "#ffffff")
                        mark = "✓" if e == "ok" else ("✗" if e else "")
                        cells += f'<td style="background:{c};text-align:center" title="{esc(e)}">{mark}</td>'
                cells += f"<td>{_SYMBOL.get(r.status, '')} {esc(r.message)}</td>"
                body.append(f'<tr style="background:{bg}">{cells}</tr>')
            out.append(f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>")
        if self.mistakes:
            out.append(f"<p>{esc(render(Msg('h.mistakes')))}: "
                       + ", ".join(f"<code>{esc(m)}</code>" for m in self.mistakes) + "</p>")
        out.append("</div>")
        return "".join(out)


def failed(quantity, message, mistake, rows=()):
    """A failed CheckResult with one message and one mistake code (malformed answers)."""
    return CheckResult(False, 0.0, [message], [mistake] if mistake else [], tuple(rows), quantity)
