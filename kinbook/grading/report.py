"""The verdict (last stage of a check): what a check returns — :class:`CheckResult` and the per-row
:class:`RowResult` it is made of — and how it is written from the matching and the diagnosis.

The results are modelled on otter-grader's test results: small frozen dataclasses that render themselves in a
notebook (``_repr_html_``: a table with one coloured line per row of Φ, Φ_q, ν or γ) and print plainly in a
terminal. Their texts are kept as :class:`~kinbook.grading._i18n.Msg` objects and written in the current language
when shown (``messages``, ``repr``, HTML), so switching the language re-renders an existing result.

Counts and scores come from the same rows: the headline's "k of n rows" counts the rows of the table, and
the score is the mean credit of those rows (half for a right row out of the book's order; for Φ_q the
fraction of a row's nonzero entries that are right). Positions are 1-based everywhere.
"""

from __future__ import annotations

import html
from dataclasses import dataclass

import numpy as np

from ._i18n import Msg, both, constraint_label, render
from ._i18n import constraint_label as cl
from .catalogue import explain
from .quantities import label_of, quantity_of

__all__ = ["CheckResult", "RowResult", "phi_result", "derived_result", "failed", "hints", "fmt"]

PRINTED = {"book_misprint", "gamma_sign", "factor_2_missing"}
"""Codes whose erratum means: the answer is the book's printed (wrong) formula."""


def fmt(x):
    """A number as it is shown: 6 significant digits, round-off to zero (never 2.22045e-16)."""
    x = float(x)
    if abs(x) < 1e-12:
        x = 0.0
    return f"{x:.6g}"


def failed(quantity, message, code):
    """A failed result with one message and one code (an answer that cannot be graded)."""
    return CheckResult(False, 0.0, [message], [code] if code else [], (), label_of(quantity))


def owner_text(target, j):
    return both(lambda lang: constraint_label(target.owner(j), lang))


def hints(codes, contexts):
    """One line per distinct mistake code: "Hint (title): hint", the hint in the notation of its context."""
    out = []
    for code in codes:
        ctx = contexts.get(code, ())
        out.append(both(lambda lang, code=code, ctx=ctx: _hint_line(code, lang, ctx)))
    return out


def _hint_line(code, lang, ctx):
    title, hint = explain(code, lang, ctx)
    return render(Msg("hint", title=title, hint=hint), lang)


def _title(code):
    return both(lambda lang: explain(code, lang)[0])


def mistake_message(row):
    """"wrong — title[: detail]" for a diagnosed row (with the erratum when the answer is the book's misprint)."""
    detail = row.detail
    if row.erratum:
        printed = row.code in PRINTED
        extra = Msg("book_misprint", id=row.erratum) if printed else Msg("d.book_row", id=row.erratum)
        detail = extra if detail is None else [detail, extra]
    if detail is None:
        return Msg("row_mistake", title=_title(row.code))
    return Msg("row_mistake_detail", title=_title(row.code), detail=detail)


def _grouped(messages):
    """Consecutive lines saying the same thing of rows of the same constraint, as one line naming all the rows
    (one sign error over eight rows of γ is one line, not eight)."""
    out = []
    for m in messages:
        prev = out[-1] if out else None
        if isinstance(m, Msg) and isinstance(prev, Msg) and m.key == prev.key and m.key in ("row_line",
                                                                                            "row_line_short"):
            a = {k: v for k, v in m.fields.items() if k != "label"}
            b = {k: v for k, v in prev.fields.items() if k != "label"}
            if a == b:
                out[-1] = Msg(prev.key, **dict(prev.fields, label=_join(prev.fields["label"], m.fields["label"])))
                continue
        out.append(m)
    return out


def _join(a, b):
    if isinstance(a, str) and isinstance(b, str):
        return f"{a}, {b}"
    return both(lambda lang: f"{_render(a, lang)}, {_render(b, lang)}")


def _render(x, lang):
    return render(x, lang)


def _unique(codes):
    out = []
    for c in codes:
        if c and c not in out:
            out.append(c)
    return out


# ================================================================================================ Φ
def phi_result(target, matching, order):
    """The CheckResult of a Φ check."""
    rows, messages, codes, contexts, infos = [], [], [], {}, []
    labels = {}
    for r in matching.rows:
        label = target.label(r.ref) if r.ref is not None else Msg("your_row", k=r.k + 1)
        if r.status == "ok":
            if r.how == "equivalent":
                refs = ", ".join(target.label(j) for j in r.covers)
                label = refs if len(r.covers) <= 2 else f"{target.label(r.covers[0])}…"
                own = target.own_target(target.constraints[r.owner])
                N = own.samples("assembled").N
                owner = _constraints_text(target, [r.owner])
                msg = Msg("row_equivalent_book", refs=refs, owner=owner, N=N) if r.book else \
                    Msg("row_equivalent", refs=refs, owner=owner, N=N, S=matching.searched.get(r.owner, 0))
                infos.append(Msg("row_line_short", label=Msg("your_row", k=r.k + 1), text=msg))
            elif r.factor not in (None, 1.0):
                msg = Msg("row_ok_scaled", c=fmt(r.factor))
            else:
                msg = ""
            rows.append(RowResult(label, "ok", msg, None, (), 1.0))
        elif r.status == "moved":
            rows.append(RowResult(label, "wrong", Msg("row_moved", ref=target.label(r.ref)), "row_order", (), 0.5))
            codes.append("row_order")
        elif r.status == "dependent":
            msg = _dependence(target, r)
            rows.append(RowResult(Msg("your_row", k=r.k + 1), "extra", msg, "dependent_row", (), 0.0))
            messages.append(msg)
            codes.append("dependent_row")
        elif r.status == "extra" or (r.status == "wrong" and r.ref is None and r.code in (None, "extra_row")):
            rows.append(RowResult(Msg("your_row", k=r.k + 1), "extra", Msg("row_extra"), "extra_row", (), 0.0))
            messages.append(Msg("row_extra_at", k=r.k + 1))
            codes.append("extra_row")
        else:  # wrong
            code = r.code or ("masked_row" if r.masked else "wrong_value")
            if r.code == "masked_row":
                msg = Msg("row_mistake", title=_title("masked_row"))
            elif r.code:
                msg = mistake_message(r)
            elif r.masked:
                msg = Msg("row_mistake", title=_title("masked_row"))
            else:
                msg = Msg("row_wrong", ref=target.label(r.ref), owner=owner_text(target, r.ref))
            if r.masked:
                msg = Msg("row_masked", text=msg, others=_constraints_text(target, r.masked),
                          owner=_constraints_text(target, [r.owner]))
            rows.append(RowResult(label, "wrong", msg, code, (), 0.0))
            messages.append(Msg("row_line", label=label, owner=owner_text(target, r.ref), text=msg))
            codes.append(code)
            contexts.setdefault(code, getattr(r, "context", ()))
        labels[r.k] = label
    for j in matching.missing:
        code = "missing_normalization" if target.owner(j).kind == "normalization" else "missing_row"
        msg = Msg("row_missing", ref=target.label(j), owner=owner_text(target, j))
        rows.append(RowResult(target.label(j), "missing", msg, code, (), 0.0))
        messages.append(Msg("row_line_short", label=target.label(j), text=msg))
        codes.append(code)
    return _finish("Phi", rows, messages, codes, contexts, target, matching, notes_after=infos)


def _constraints_text(target, blocks):
    """The constraints of ``blocks`` (indices into target.constraints; None: the others), named when shown."""
    cs = target.constraints

    def text(lang):
        return ", ".join(constraint_label(cs[b], lang) if b is not None else render(Msg("the_rest"), lang)
                         for b in blocks)

    return both(text)


def _dependence(target, r):
    if r.dependence == "redundant":
        others = [k for k in r.depends_on if k != r.k]
        return Msg("row_depends_redundant", k=r.k + 1, rows=", ".join(str(k + 1) for k in others),
                   owner=_constraints_text(target, [r.owner]), n=len(target.block(target.constraints[r.owner])))
    if r.dependence == "repeat":
        times = "" if r.factor in (None, 1.0) else Msg("times", c=fmt(r.factor))
        return Msg("row_depends_repeat", k=r.k + 1, j=r.depends_on[0] + 1, times=times)
    if r.dependence == "combination":
        return Msg("row_depends_combination", k=r.k + 1, rows=", ".join(str(j + 1) for j in r.depends_on))
    if r.dependence == "free":
        return Msg("row_depends_free", k=r.k + 1, what=both(lambda lang: _free_what(target, lang)))
    refs = [target.label(j) for _, j in r.depends_on] if r.depends_on else []
    return Msg("row_depends_function", k=r.k + 1, rows=", ".join(refs) if refs else "?")


def _free_what(target, lang):
    mech = target.mech
    names = [cl(c, lang) for c in mech.constraints if c.kind == "normalization"
             and set(range(c.rows.start, c.rows.stop)) & set(target.free_rows)]
    return names[0] if len(names) == 1 else " / ".join(names)


def _finish(quantity, rows, messages, codes, contexts, target, matching=None, entries=False, transposed=False,
            columns=(), notes_after=()):
    what = quantity_of(quantity).label
    total = len(rows)
    score = sum(r.score for r in rows) / total if total else 0.0
    codes = _unique(codes)
    passed = not codes and total > 0 and score >= 1.0 - 1e-12
    n_ok = sum(1 for r in rows if r.status == "ok")
    half = sum(1 for r in rows if r.mistake == "row_order")
    if passed:
        equivalent = matching is not None and any(getattr(r, "how", "") == "equivalent" for r in matching.rows)
        own = matching is not None and sum(1 for r in matching.rows if getattr(r, "how", "") == "own")
        if equivalent:
            head = Msg("all_correct_equivalent", what=what, n=total, m=target.m)
        elif own:
            head = Msg("all_consistent", what=what, n=total, k=own)
        else:
            head = Msg("all_correct", what=what, n=total)
    elif transposed:
        head = Msg("summary_transposed", what=what, n=total, score=score)
    elif entries:
        eok, en = entries
        head = Msg("summary_entries", what=what, ok=n_ok, n=total, eok=eok, en=en, score=score)
    elif half:
        head = Msg("summary_half", what=what, ok=n_ok, n=total, half=half, score=score)
    else:
        head = Msg("summary", what=what, ok=n_ok, n=total, score=score)
    notes = [head] + _grouped(list(messages)) + list(notes_after) + hints(codes, contexts)
    return CheckResult(passed, round(score, 6), notes, codes, tuple(rows), what, tuple(columns))


# ================================================================================================ Φ_q, ν, γ
def derived_result(target, quantity, matching, data, rtol, transposed=False, notes=(), extra_codes=()):
    """The CheckResult of a Φ_q, ν or γ check."""
    rows, messages, codes, contexts = [], [], list(extra_codes), {}
    per_coordinate = quantity_of(quantity).per_coordinate
    columns = tuple(_book(target.names[c]) for c in data.cols) if per_coordinate else ()
    e_ok = e_n = 0
    for r in matching.rows:
        label = target.label(r.ref) if r.ref is not None and not isinstance(r.ref, tuple) else Msg("your_row", k=r.k + 1)
        width = data.S.shape[2]
        if r.status == "ok":
            if r.how == "own":
                msg = Msg("consistent_not_correct")
                messages.append(Msg("row_line_short", label=label, text=msg))
            elif r.how == "both":
                msg = Msg("consistent_correct")
            elif r.how == "reference":
                msg = Msg("correct_not_consistent")
                messages.append(Msg("row_line_short", label=label, text=msg))
            elif r.how == "equivalent":
                msg = Msg("row_equivalent_jacobian", refs=", ".join(target.label(j) for j in r.covers), N=data.S.shape[0])
            elif per_coordinate and r.factor not in (None, 1.0):
                msg = Msg("row_ok_jacobian_scaled", c=fmt(r.factor), ref=target.label(r.ref))
            else:
                msg = ""
            entries = ("ok",) * width if per_coordinate else ()
            if per_coordinate:
                nz = _nonzero(data.R[:, r.ref] if r.ref is not None else data.S[:, r.k])
                e_ok += nz
                e_n += nz
            rows.append(RowResult(label, "ok", msg, None, entries, 1.0))
        elif r.status == "moved":
            rows.append(RowResult(label, "wrong", Msg("row_moved", ref=target.label(r.ref)), "row_order", (), 0.5))
            codes.append("row_order")
        elif r.status == "extra":
            rows.append(RowResult(Msg("your_row", k=r.k + 1), "extra", Msg("row_extra"), "extra_row", (), 0.0))
            messages.append(Msg("row_extra_at", k=r.k + 1))
            codes.append("extra_row")
        else:
            code = r.code or "wrong_value"
            msg = mistake_message(r) if r.code else Msg("row_wrong", ref=target.label(r.ref) if r.ref is not None
                                                        else "?", owner=owner_text(target, r.ref)
                                                        if r.ref is not None else "")
            if per_coordinate and r.entries:
                bad = [f"∂/∂{columns[i]}" for i, e in enumerate(r.entries) if e != "ok"]
                msg = Msg("row_with_entries", text=msg, entries=", ".join(bad))
                expected = data.R[:, r.ref] if r.ref is not None else None
                if expected is not None:
                    relevant = _relevant(data.S[:, r.k], expected)
                    e_n += len(relevant)
                    e_ok += sum(1 for i in relevant if r.entries[i] == "ok")
            rows.append(RowResult(label, "wrong", msg, code, r.entries, r.score))
            owner = owner_text(target, r.ref) if r.ref is not None and not isinstance(r.ref, tuple) else ""
            messages.append(Msg("row_line", label=label, owner=owner, text=msg) if owner
                            else Msg("row_line_short", label=label, text=msg))
            codes.append(code)
            contexts.setdefault(code, getattr(r, "context", ()))
            for e in r.entries:
                if e not in ("ok", code):
                    codes.append(e)
                    contexts.setdefault(e, getattr(r, "context", ()))
    for j in matching.missing:
        if isinstance(j, tuple):  # a row of the student's own Φ with no row here
            msg = Msg("row_missing_own", k=j[1] + 1)
            rows.append(RowResult(Msg("your_row", k=j[1] + 1), "missing", msg, "missing_row", (), 0.0))
            messages.append(msg)
            codes.append("missing_row")
            continue
        code = "missing_normalization" if target.owner(j).kind == "normalization" else "missing_row"
        msg = Msg("row_missing", ref=target.label(j), owner=owner_text(target, j))
        rows.append(RowResult(target.label(j), "missing", msg, code, (), 0.0))
        messages.append(Msg("row_line_short", label=target.label(j), text=msg))
        codes.append(code)
    if transposed:
        codes.insert(0, "transposed")
        rows = [RowResult(r._label, "wrong", Msg("transposed_right"), "transposed", r.entries, 0.5) for r in rows]
        messages = [Msg("transposed_right")]
    with_entries = per_coordinate and any(r.entries and r.status == "wrong" for r in rows) and not transposed
    return _finish(quantity, rows, messages, codes, contexts, target, matching,
                   entries=(e_ok, e_n) if with_entries else False, transposed=transposed, columns=columns,
                   notes_after=notes)


def _nonzero(row):
    return int(np.sum(np.max(np.abs(row), axis=0) > 1e-12)) if row.ndim == 2 else 1


def _relevant(s, e):
    return [i for i in range(s.shape[-1]) if np.max(np.abs(e[:, i])) > 1e-12 or np.max(np.abs(s[:, i])) > 1e-12]


def _book(name):
    """Coordinate names in the book's notation: phi2 → φ2."""
    return name.replace("phi", "φ")


# ================================================================================================ the results
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

    @property
    def label_msg(self):
        """The label as kept: a :class:`~kinbook.grading._i18n.Msg` (or str), written when shown — for a new
        RowResult that says the same of the same row."""
        return self._label

    @property
    def message_msg(self):
        """The message as kept (a Msg, a str, or a list of them), written when shown."""
        return self._message


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
        The answer as the checker read it, as plain text and as LaTeX (:func:`kinbook.grading.read.echoed`), shown before
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
    def quantity_msg(self):
        """The quantity's name as kept (a Msg or str), written when shown — for a new CheckResult of the same
        quantity."""
        return self._quantity

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
