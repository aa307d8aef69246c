"""``kinbook report``: what the class did, for the instructor.

One self-contained HTML page per exercise (``<exercise>.html``: nothing loaded from elsewhere, the plots embedded as
PNG) and one for the course (``index.html``):

* the distribution of scores (a matplotlib histogram) and of the course totals;
* per part: the mean, the share of full marks, and a flag on the parts nobody got right (a question to look at);
* **the most common catalogue mistakes per part** — "38 % of the class used the global vector in γ" — with the
  number of students, the share, and an example (a student, the row, their answer): a query of the gradebook's
  ``mistakes`` rows (:mod:`.tables`);
* the students whose answers were computed with kinbook's own reference;
* copying signals, saying exactly what is identical (a notebook released for another student, identical answers to
  every part) and never more;
* the students on the roster with nothing handed in, and those graded but not on the roster.

``--format csv`` writes the same tables as CSV files (``course.csv``, ``<exercise>-parts.csv``,
``<exercise>-mistakes.csv`` …).
"""

from __future__ import annotations

import base64
import html
import io
from pathlib import Path

import numpy as np

from ...core.atomic import protect, refuse_overwrite, write_all
from ...errors import GradingError
from ..gradebook import Gradebook, csv_text
from . import tables

__all__ = ["report", "FORMATS"]

FORMATS = ("html", "csv")

_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,sans-serif;max-width:72rem;margin:1.5rem auto;
padding:0 1rem;color:#1d2125;line-height:1.4}h1{font-size:1.6rem}h2{font-size:1.2rem;margin-top:2rem;
border-bottom:1px solid #ccd;padding-bottom:.2rem}table{border-collapse:collapse;margin:.5rem 0;font-size:.92rem}
td,th{border:1px solid #ccd;padding:.3rem .6rem;text-align:left;vertical-align:top}th{background:#f1f3f6}
td.n{text-align:right;font-variant-numeric:tabular-nums}.flag{background:#f8d7da;color:#721c24;font-weight:600}
.muted{color:#666}img{max-width:100%;height:auto;border:1px solid #eee}code,pre{font-size:.85rem}
pre{margin:0;white-space:pre}td.nowrap{white-space:nowrap}nav a{margin-right:1rem}
table{max-width:100%}td{overflow-wrap:anywhere}td pre{max-width:20rem;overflow-x:auto}
"""


def _e(value):
    return html.escape(str(value))


#: The lines of a student's answer the mistake table shows (a whole Φ has a dozen rows: the rest is counted).
ANSWER_LINES = 6


def _number(v):
    """A count as it is; a score with two decimals (10.33, 11.00), so that a column reads at a glance."""
    return str(v) if isinstance(v, int) else f"{v:.2f}"


def _answer(text):
    """A student's answer as the mistake table shows it: its first :data:`ANSWER_LINES` lines, whole, and how many
    more there are."""
    lines = str(text).splitlines() or [""]
    shown = "\n".join(lines[:ANSWER_LINES])
    more = f"<div class='muted'>… {len(lines)} rows in all</div>" if len(lines) > ANSWER_LINES else ""
    return f"<pre>{_e(shown)}</pre>{more}"


def _table(rows, columns, numeric=(), flag=None, nowrap=()):
    """An HTML table of ``rows`` (dicts) with ``columns`` [(key, heading)]."""
    if not rows:
        return "<p class='muted'>none</p>"
    head = "".join(f"<th>{_e(h)}</th>" for _, h in columns)
    body = []
    for r in rows:
        cls = " class='flag'" if flag and flag(r) else ""
        cells = []
        for k, _ in columns:
            v = r[k]
            if k.endswith("share"):
                v = f"{100 * v:.0f} %"
            if k == "example_answer":
                cells.append(f"<td>{_answer(v)}</td>")
            elif k in numeric:
                cells.append(f"<td class='n'>{_e(_number(v))}</td>")
            else:
                cells.append(f"<td class='nowrap'>{_e(v)}</td>" if k in nowrap else f"<td>{_e(v)}</td>")
        body.append(f"<tr{cls}>{''.join(cells)}</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


def _histogram(values, top, title, xlabel):
    """A histogram of ``values`` on [0, top], as an embedded PNG (<img> with a data: URI)."""
    import matplotlib  # import time: matplotlib only when needed

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # import time: matplotlib only when needed

    fig, ax = plt.subplots(figsize=(8, 3.2), dpi=100)
    try:
        top = max(float(top), max(values, default=0.0), 1.0)
        # one bar per whole point, centred on it (up to 25 points; wider bins beyond), so that a bar reads "about
        # 7 points"; a dashed line marks full marks
        width = max(1, int(np.ceil(top / 25)))
        edges = np.arange(-width / 2, top + width, width)
        ax.hist(values, bins=edges, color="#4a78b5", edgecolor="white")
        ax.axvline(top, color="#555", linestyle="--", linewidth=1)
        ax.annotate("full marks", (top, 1), xycoords=("data", "axes fraction"), xytext=(0, 3),
                    textcoords="offset points", ha="center", va="bottom", fontsize=9, color="#555")
        ax.set_xlim(edges[0], edges[-1])
        ax.xaxis.get_major_locator().set_params(integer=True)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("students")
        ax.set_title(title)
        ax.yaxis.get_major_locator().set_params(integer=True)
        fig.tight_layout()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", metadata={"Software": None})
    finally:
        plt.close(fig)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    return f"<img alt='{_e(title)}' src='data:image/png;base64,{data}'>"


def _page(title, body):
    return (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{_e(title)}</title>"
            f"<style>{_CSS}</style></head><body>{body}</body></html>")


def _exercise_tables(book, exercise, roster):
    return {"scores": tables.scores(book, exercise, roster), "parts": tables.parts(book, exercise),
            "mistakes": tables.mistakes(book, exercise), "reference": tables.reference(book, exercise),
            "copying": tables.copying(book, exercise), "missing": tables.missing(book, exercise, roster),
            "not_notebooks": tables.not_notebooks(book, exercise, roster), "several": tables.several(book, exercise),
            "off_roster": tables.off_roster(book, exercise, roster)}


def _exercise_page(exercise, t):
    handed = [r for r in t["scores"] if r["status"] != "missing"]
    top = max((r["max_score"] for r in t["scores"]), default=0)
    enrolled = len(t["scores"]) - len(t["off_roster"])
    other = len(t["not_notebooks"])
    line = (f"{enrolled - len(t['missing']) - other} of {enrolled} students handed in, {len(t['missing'])} missing"
            + (f", {other} handed in no notebook but another file" if other else ""))
    if t["off_roster"]:
        line += f"; {len(t['off_roster'])} more not on the roster"
    out = [f"<nav><a href='index.html'>← the course</a></nav><h1>{_e(exercise)}</h1>", f"<p>{_e(line)}.</p>",
           _histogram([r["score"] for r in handed], top, f"{exercise}: scores", "score"),
           "<h2>Parts</h2>",
           _table(t["parts"], [("part", "part"), ("graded", "graded"), ("max_score", "points"), ("mean", "mean"),
                               ("mean_share", "mean / points"), ("full_marks", "full marks"),
                               ("full_share", "share of full marks")],
                  numeric={"graded", "max_score", "mean", "full_marks"}, flag=lambda r: r["nobody"])]
    nobody = [r["part"] for r in t["parts"] if r["nobody"]]
    if nobody:
        out.append(f"<p class='flag'>Nobody got full marks on: {_e(', '.join(nobody))} — worth a look at the "
                   "question.</p>")
    out += ["<h2>Most common mistakes, per part</h2>",
            _table(t["mistakes"], [("part", "part"), ("code", "mistake"), ("title", "what it is"),
                                   ("students", "students"), ("share", "share of the part's submissions"),
                                   ("example_student", "for example"), ("example_row", "row"),
                                   ("example_answer", "their answer")], numeric={"students"},
                   nowrap={"part", "code", "title", "example_row"}),
            "<h2>Answers computed with kinbook's reference</h2>",
            _table(t["reference"], [("student", "student"), ("part", "part"), ("how", "how")]),
            "<h2>Copying signals</h2><p class='muted'>What is identical, as found; not a verdict.</p>",
            _table(t["copying"], [("kind", "signal"), ("students", "students"), ("what", "what is identical")]),
            "<h2>Missing</h2>", f"<p>{_e(', '.join(t['missing'])) or 'none'}</p>",
            "<h2>Handed in something other than a notebook</h2>",
            _table(t["not_notebooks"], [("student", "student"), ("files", "files"), ("what", "what they are")]),
            "<h2>Several notebooks in one submission</h2>",
            _table(t["several"], [("student", "student"), ("files", "files, and what became of each")]),
            "<h2>Not on the roster</h2>", f"<p>{_e(', '.join(t['off_roster'])) or 'none'}</p>",
            "<h2>Every student</h2>",
            _table(t["scores"], [("student", "student"), ("status", "status"), ("score", "score"),
                                 ("max_score", "of"), ("attempts", "files handed in"), ("late_days", "days late"),
                                 ("penalty", "penalty"), ("overridden", "overridden parts")],
                   numeric={"score", "max_score", "attempts", "late_days", "penalty"}, nowrap={"student"})]
    return _page(f"kinbook report: {exercise}", "".join(out))


def _course_page(summary, totals, top):
    rows = [{**r, "exercise": r["exercise"]} for r in summary]
    links = "".join(f"<li><a href='{_e(r['exercise'])}.html'>{_e(r['exercise'])}</a></li>" for r in summary)
    body = ["<h1>The course</h1>", f"<ul>{links}</ul>",
            _histogram(list(totals.values()), top, "course totals", "total score"),
            "<h2>Exercises</h2>",
            _table(rows, [("exercise", "exercise"), ("students", "students"), ("handed_in", "handed in"),
                          ("missing", "missing"), ("late", "late"), ("max_score", "points"), ("mean", "mean"),
                          ("median", "median"), ("full_marks", "full marks")],
                   numeric={"students", "handed_in", "missing", "late", "max_score", "mean", "median",
                            "full_marks"})]
    return _page("kinbook report: the course", "".join(body))


def report(gradebook, out=None, fmt="html", *, exercises=None, roster=None):
    """Write the report of the gradebook directory ``gradebook`` into ``out`` (default ``<gradebook>/report``).

    Returns
    -------
    list of Path
        The files written.
    """
    if fmt not in FORMATS:
        raise GradingError(f"report format must be one of {', '.join(FORMATS)}, got {fmt!r}")
    out = Path(out) if out is not None else Path(gradebook) / "report"
    files = []
    with Gradebook(gradebook, create=False) as book:
        roster = roster if roster is not None else book.roster()
        exercises = list(exercises) if exercises else book.exercises()
        summary = tables.summary(book, exercises, roster)
        totals, top = {}, 0.0
        for e in exercises:
            t = _exercise_tables(book, e, roster)
            top += max((r["max_score"] for r in t["scores"]), default=0)
            for r in t["scores"]:
                totals[r["student"]] = totals.get(r["student"], 0.0) + r["score"]
            if fmt == "html":
                files.append((out / f"{e}.html", _exercise_page(e, t)))
                continue
            for name in ("scores", "parts", "mistakes", "reference", "copying", "not_notebooks", "several"):
                rows = t[name]
                cols = list(rows[0]) if rows else {"scores": ["student", "status", "score"], "parts": ["part"],
                                                   "mistakes": ["part", "code", "students"],
                                                   "reference": ["student", "part", "how"],
                                                   "copying": ["kind", "students", "what"],
                                                   "not_notebooks": ["student", "files", "what"],
                                                   "several": ["student", "files"]}[name]
                files.append((out / f"{e}-{name}.csv", csv_text(cols, [[r[c] for c in cols] for r in rows])))
        if fmt == "html":
            files.append((out / "index.html", _course_page(summary, totals, top)))
        else:
            cols = list(summary[0]) if summary else ["exercise"]
            files.append((out / "course.csv", csv_text(cols, [[r[c] for c in cols] for r in summary])))
        inputs = book.inputs() + [("the roster", getattr(roster, "path", None))]
    refuse_overwrite([p for p, _ in files], inputs, "report")
    with protect(*inputs):  # every page or none
        return write_all(files)
