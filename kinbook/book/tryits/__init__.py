"""The notebooks' "Try it" exercises as data: what the student writes, how it is checked, a worked answer.

A try-it cell in a chapter notebook is blank::

    my_A = ...                      # your answer
    kb.try_it("13-1/try-1", my_A)

:func:`try_it` shows "not answered yet" while the answer is still ``...`` and otherwise runs the checker
registered here against a reference that the library computes (never one typed in the notebook).
:func:`reveal` prints the worked answer, which lives here as a small function: its body is the code shown,
and the test suite runs it through the same check (``tests/book/test_tryits.py``).

Each :class:`TryIt` keeps its checker, its target and the checker's options as data, so other tests can
re-run the check with typical wrong answers (``TRY_ITS["13-2/try-1"].check(wrong)``).
"""

from __future__ import annotations

import html
import inspect
import linecache
import sys

import numpy as np

from ...errors import InputError
from ...grading import get_language
from ...grading.report import CheckResult
from ...i18n import N_, Message, translate
from .mutations import draw_variant
from .registry import TRY_ITS, TryIt, register, same_data, table_text, text_message

__all__ = ["TryIt", "NotAnswered", "Variant", "TRY_ITS", "get", "try_it", "reveal", "another", "register",
           "is_blank"]


def get(id):
    """The :class:`TryIt` with this id; the error lists the ids of the same notebook."""
    _load()
    try:
        return TRY_ITS[id]
    except KeyError:
        notebook = str(id).split("/")[0]
        near = [k for k in TRY_ITS if k.startswith(notebook + "/")] or list(TRY_ITS)[:6]
        raise InputError(Message(N_("no try-it {id}; expected one of {ids}"), id=repr(id),
                                 ids=", ".join(near))) from None


def _load():
    from . import ch13, ch14  # noqa: F401  (registering on first use: the chapters' try-its take ~0.2 s to import)


def is_blank(answer):
    """True while the answer is still the placeholder ``...`` (also inside a list or tuple)."""
    if answer is Ellipsis:
        return True
    if isinstance(answer, (list, tuple)):
        return any(is_blank(a) for a in answer)
    return False


def _tr(key, **fields):
    return table_text(key, get_language(), **fields)


def _title(item):
    notebook, _, k = item.id.partition("/try-")
    return _tr("title", k=k, notebook=notebook)


class NotAnswered:
    """What :func:`try_it` returns while the answer is still ``...``: a notice, not an error."""

    passed = False
    score = 0.0

    def __init__(self, item):
        self.item = item

    def __bool__(self):
        return False

    def _text(self):
        return _tr("blank", title=_title(self.item), answer=self.item.answer, id=self.item.id)

    def __repr__(self):
        return html.unescape(self._text().replace("<code>", "`").replace("</code>", "`"))

    def _repr_html_(self):
        return ('<div style="border-left:4px solid #b8860b; background:#fff8e1; padding:4px 10px">'
                f"{self._text()}</div>")


def _explanation(item):
    """Why the worked answer is what it is, in the language of the moment (a marked message of the catalogue)."""
    return translate(item.explanation) if item.explanation else ""


class Revealed:
    """The worked answer of a try-it, shown as code (``kb.reveal(id)``), with why, for the data in use."""

    def __init__(self, item, data=None):
        self.item = item
        self.data = item.data_for(data)
        self.code = item.solution_code(self.data)
        self.uses = [p.name for p in inspect.signature(item.solution).parameters.values()
                     if p.kind != p.KEYWORD_ONLY]
        self.why = _explanation(item)

    def _head(self):
        head = _tr("worked", title=_title(self.item))
        if not same_data(self.data, self.item.data):
            head += " " + _tr("with_data", data=self.item.stated(self.data))
        if self.uses:
            head += ". " + _tr("uses", names=", ".join(self.uses))
        return head

    def __repr__(self):
        out = f"# {self._head()}\n{self.code}"
        if self.why:
            out += f"\n\n{_tr('why')}: {self.why}"
        return out

    def _repr_html_(self):
        out = (f"<p><b>{html.escape(self._head())}</b></p>"
               f"<pre style='background:#f6f8fa; padding:6px 10px'>{html.escape(self.code)}</pre>")
        if self.why:
            out += f"<p><b>{html.escape(_tr('why'))}.</b> {html.escape(self.why)}</p>"
        return out


_CURRENT: dict = {}
"""The variant each try-it is checked against: id → (k, data); absent = the notebook's data."""


def _data_of(item):
    return _CURRENT.get(item.id, (0, item.data))[1]


def try_it(id, answer):
    """Check a notebook's try-it answer (against the variant drawn last by :func:`another`, if any).

    Parameters
    ----------
    id : str
        The try-it's id, e.g. ``"13-1/try-1"``.
    answer
        What the student wrote; ``...`` (the placeholder) means "not answered yet".

    Returns
    -------
    CheckResult or NotAnswered
        Both display themselves in a notebook. A wrong number is described (which entries, how they are off,
        the mistake's name), never given: only :func:`reveal` shows the answer.
    """
    item = get(id)
    if is_blank(answer):
        return NotAnswered(item)
    result = item.check(answer, _data_of(item))
    if result.passed and item.library:
        name = item.library_answer(_caller_source())
        if name is not None:
            return _library_answer(result, name)
    return result


def _caller_source():
    """The source of the cell (or file) that called :func:`try_it`: IPython keeps each cell's code in linecache."""
    frame = sys._getframe(2)
    return "".join(linecache.getlines(frame.f_code.co_filename, frame.f_globals))


def _library_answer(result, name):
    """A right answer computed by kinbook itself: said so, not a plain "correct" (the exercise is to build it)."""
    note = text_message("library", name=name)
    return CheckResult(True, result.score, [note], [], result.rows, result.quantity_msg, result.columns)


def reveal(id):
    """A worked answer to a try-it (for the variant in use), as code to read — and why it is so."""
    item = get(id)
    return Revealed(item, _data_of(item))


class Variant:
    """A try-it with other data (``kb.another(id)``): shows the data; ``variant.data`` holds them."""

    def __init__(self, item, k, data, seed):
        self.item, self.k, self.data, self.seed = item, k, dict(data), seed

    def __getitem__(self, key):
        return self.data[key]

    def _lines(self):
        title = _title(self.item)
        if not self.item.ranges:
            return [_tr("no_variants", title=title)]
        if self.k == 0:
            return [_tr("variant_zero", title=title, data=self.item.stated(self.data))]
        return [_tr("variant_title", title=title, k=self.k) + " — " + _tr("variant_data", data=self.item.stated(
            self.data)), _tr("variant_how", id=self.item.id, answer=self.item.answer, seed=self.seed)]

    def __repr__(self):
        return "\n".join(html.unescape(t.replace("<code>", "`").replace("</code>", "`")) for t in self._lines())

    def _repr_html_(self):
        lines = self._lines()
        body = f"<b>{html.escape(lines[0])}</b>" + "".join(f"<br>{t}" for t in lines[1:])
        return f'<div style="border-left:4px solid #1f6feb; background:#eef5ff; padding:4px 10px">{body}</div>'


def another(id, k=None):
    """Draw a fresh variant of a try-it: the same question with other data, drawn by the seeded generator
    the exercises' per-student parameters use (:func:`kinbook.grading.item.draw`). :func:`try_it` and
    :func:`reveal` then use it.

    Parameters
    ----------
    id : str
        The try-it's id.
    k : int, optional
        Which variant: 1, 2, … (the same k gives the same data, on every machine); 0 is the notebook's data.
        Default: the one after the variant in use.

    Returns
    -------
    Variant
        Shows the data (and the seed it was drawn with).
    """
    item = get(id)
    if k is None:
        k = _CURRENT.get(id, (0, None))[0] + 1
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 0:
        raise InputError(Message(N_("kb.another({id}, k): k must be a whole number ≥ 0 (0 = the notebook's data), got "
                                    "{k}"), id=repr(id), k=repr(k)))
    k = int(k)
    if k == 0 or not item.ranges:
        _CURRENT.pop(id, None)
        return Variant(item, 0, item.data, None)

    data, seed, last = draw_variant(item, k)
    if data is not None:
        _CURRENT[id] = (k, data)
        return Variant(item, k, data, seed)
    raise InputError(Message(N_("{id}: no data drawn for variant {k} works ({last})"), id=id, k=k,
                             last=last.message if last is not None else None))
