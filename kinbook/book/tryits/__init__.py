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
import textwrap
from dataclasses import dataclass, field
from typing import Any, Callable

__all__ = ["TryIt", "NotAnswered", "TRY_ITS", "get", "try_it", "reveal", "register", "is_blank"]

TRY_ITS: dict[str, "TryIt"] = {}
"""Every try-it, by id ("13-1/try-1"), in notebook order."""


@dataclass(frozen=True)
class TryIt:
    """One "Try it" exercise of a chapter notebook.

    Attributes
    ----------
    id : str
        ``"<notebook>/try-<k>"``, e.g. ``"13-2/try-1"``: the notebook's number and the exercise's place in it.
    answer : str
        Name of the notebook variable the student fills in (``"my_Phi"``); unique in its notebook.
    checker : callable
        A :mod:`kinbook.grading` checker, called as ``checker(answer, target, **options)``.
    target : callable
        No arguments; returns the checker's reference (a value, a constraint or a mechanism), computed by
        the library.
    solution : callable
        The worked answer. Its parameters are notebook variables it reads (rebuilt by ``context`` for tests);
        its body, up to the final ``return``, is the code :func:`reveal` shows.
    options : dict
        Keyword arguments of the checker (``name=…``, ``angles=…``).
    context : callable
        No arguments; returns the notebook variables the solution reads, as a dict.
    """

    id: str
    answer: str
    checker: Callable
    target: Callable[[], Any]
    solution: Callable
    options: dict = field(default_factory=dict)
    context: Callable[[], dict] = field(default=dict, repr=False)

    def check(self, answer):
        """Run the checker on ``answer`` (a :class:`kinbook.grading.CheckResult`)."""
        return self.checker(answer, self.target(), **self.options)

    def reference_answer(self):
        """The worked answer's value, computed from the library's context."""
        return self.solution(**self.context())

    def solution_code(self):
        """The worked answer as the notebook code that produces ``self.answer``."""
        lines = textwrap.dedent(inspect.getsource(self.solution)).splitlines()
        body = lines[1:]  # the def line
        if body and body[0].lstrip().startswith(('"""', "'''")):
            body = body[1:]
        while body and not body[-1].strip():
            body.pop()
        last = body[-1].strip()
        if last == f"return {self.answer}":
            body = body[:-1]
        elif last.startswith("return "):
            indent = body[-1][: len(body[-1]) - len(body[-1].lstrip())]
            body[-1] = f"{indent}{self.answer} = {last[len('return '):]}"
        return textwrap.dedent("\n".join(body))


def register(id, answer, checker, target, solution, options=None, context=None):
    """Add a :class:`TryIt` to :data:`TRY_ITS` (used by the chapter modules); returns it."""
    if id in TRY_ITS:
        raise ValueError(f"try-it {id!r} is registered twice")
    item = TryIt(id, answer, checker, target, solution, dict(options or {}), context or dict)
    TRY_ITS[id] = item
    return item


def get(id):
    """The :class:`TryIt` with this id; the error lists the ids of the same notebook."""
    from ...errors import InputError

    _load()
    try:
        return TRY_ITS[id]
    except KeyError:
        notebook = str(id).split("/")[0]
        near = [k for k in TRY_ITS if k.startswith(notebook + "/")] or list(TRY_ITS)[:6]
        raise InputError(f"no try-it {id!r}; expected one of {', '.join(near)}") from None


def _load():
    from . import ch13, ch14  # noqa: F401  (registering)


def is_blank(answer):
    """True while the answer is still the placeholder ``...`` (also inside a list or tuple)."""
    if answer is Ellipsis:
        return True
    if isinstance(answer, (list, tuple)):
        return any(is_blank(a) for a in answer)
    return False


_TEXT = {
    "blank": {
        "en": "{title} is not answered yet: replace <code>...</code> in <code>{answer} = ...</code> with your "
              "answer and run the cell again. Stuck? <code>kb.reveal(\"{id}\")</code> shows a worked answer.",
        "es": "{title} aún no tiene respuesta: sustituya <code>...</code> en <code>{answer} = ...</code> por su "
              "respuesta y ejecute de nuevo la celda. ¿Atascado? <code>kb.reveal(\"{id}\")</code> muestra una "
              "solución.",
    },
    "title": {"en": "Try it {k} ({notebook})", "es": "Pruébelo {k} ({notebook})"},
    "worked": {"en": "A worked answer to {title}", "es": "Una solución de {title}"},
    "uses": {"en": "It uses these variables of the notebook: {names}.",
             "es": "Usa estas variables del cuaderno: {names}."},
}


def _tr(key, **fields):
    from ...grading import get_language

    table = _TEXT[key]
    return (table.get(get_language()) or table["en"]).format(**fields)


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


class Revealed:
    """The worked answer of a try-it, shown as code (``kb.reveal(id)``)."""

    def __init__(self, item):
        self.item = item
        self.code = item.solution_code()
        self.uses = list(inspect.signature(item.solution).parameters)

    def _head(self):
        head = _tr("worked", title=_title(self.item))
        if self.uses:
            head += ". " + _tr("uses", names=", ".join(self.uses))
        return head

    def __repr__(self):
        return f"# {self._head()}\n{self.code}"

    def _repr_html_(self):
        return (f"<p><b>{html.escape(self._head())}</b></p>"
                f"<pre style='background:#f6f8fa; padding:6px 10px'>{html.escape(self.code)}</pre>")


def try_it(id, answer):
    """Check a notebook's try-it answer.

    Parameters
    ----------
    id : str
        The try-it's id, e.g. ``"13-1/try-1"``.
    answer
        What the student wrote; ``...`` (the placeholder) means "not answered yet".

    Returns
    -------
    CheckResult or NotAnswered
        Both display themselves in a notebook.
    """
    item = get(id)
    if is_blank(answer):
        return NotAnswered(item)
    return item.check(answer)


def reveal(id):
    """A worked answer to a try-it, as code to read (and to copy, if you must)."""
    return Revealed(get(id))
