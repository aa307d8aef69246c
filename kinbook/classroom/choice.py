"""Which of a student's files is graded: one LMS submission is a set of files, not a series of attempts.

A Canvas or Moodle submission may hold several files: the notebook and a scratch ``borrador.ipynb``, the notebook
and the release downloaded again, blank (``… (1).ipynb``), the notebook and a PDF of it. :func:`choose` decides
among the notebooks of one student, in this order:

1. a notebook **named after the exercise** (``ex01-revolute-joint-phi.ipynb``, ``Ex01.ipynb``, a variant's
   ``ex11-…-<student>.ipynb``) is preferred to one that is not (the scratch notebook is listed, not graded);
2. a notebook **with answers** is preferred to a blank one (every answer cell as released: the release downloaded
   again);
3. of what is left, under ``--policy latest`` an earlier attempt (Canvas's ``-1``, a browser's ``(1)``) is kept as
   history; **several candidates of the same standing are all graded and the best counts** — the student is not
   guessed at; ``--policy best`` grades every attempt and counts the best.

Files that are not notebooks (a PDF, a zip, Moodle's online text) are tied to their student when the path names one
(:func:`kind_of_file` says what they are), so that the report and the feedback say "handed in a PDF, not a
notebook", never "nothing handed in".
"""

from __future__ import annotations

import json
import os

from .notebook import PLACEHOLDER
from .results import Refused

__all__ = ["choose", "named_after", "has_answers", "kind_of_file", "several_line"]

_KINDS = {".pdf": "a PDF", ".zip": "a zip archive", ".html": "a web page (an online text)", ".htm": "a web page",
          ".py": "a Python file", ".docx": "a Word document", ".doc": "a Word document", ".txt": "a text file",
          ".png": "an image", ".jpg": "an image", ".jpeg": "an image", ".ipynb_checkpoints": "Jupyter's checkpoints"}


def kind_of_file(name):
    """What a file that is not a notebook is, for a person: "a PDF", "a zip archive" …"""
    return _KINDS.get(os.path.splitext(str(name))[1].casefold(), "a file that is not a notebook")


def named_after(base, exercise):
    """Whether a file's stem (attempt suffixes removed) names the exercise: ``ex01-revolute-joint-phi``,
    ``Ex01`` (the exercise's first word), ``ex11-…-<student>``."""
    b, e = base.casefold().strip(), exercise.casefold()
    return bool(b) and (b == e or b.startswith(e + "-") or e.startswith(b + "-"))


def has_answers(data):
    """Whether a notebook (bytes) has an answer cell edited: False for the release as downloaded (every cell marked
    as an answer still holds ``# YOUR CODE HERE`` / ``raise NotImplementedError()``); True when it cannot tell."""
    try:
        nb = json.loads(data.decode("utf-8"))
        cells = nb["cells"]
    except (ValueError, UnicodeDecodeError, KeyError, TypeError, RecursionError):
        return True
    answers = []
    for c in cells if isinstance(cells, list) else []:
        meta = c.get("metadata") if isinstance(c, dict) else None
        if isinstance(meta, dict) and isinstance(meta.get("kinbook"), dict) and meta["kinbook"].get("answer"):
            source = c.get("source", "")
            answers.append("".join(source) if isinstance(source, list) else str(source))
    if not answers:
        return True
    blank = "\n".join(PLACEHOLDER)
    return any("\n".join(line.strip() for line in a.strip().splitlines()) != blank for a in answers)


def choose(same, policy, exercise, read):
    """Decide among one student's entries ``same`` (those with ``status`` None are gradable): set ``status`` and
    ``message`` of the ones not graded — ``ignored`` (a scratch notebook, a blank download: listed, not an attempt)
    or ``superseded`` (an earlier attempt, kept as history). ``read(entry)`` gives an entry's bytes (or raises
    :class:`~kinbook.classroom.results.Refused`)."""
    good = [e for e in same if e.status is None]
    if len(good) < 2:
        return
    named = [e for e in good if named_after(e.base, exercise)]
    if named and len(named) < len(good):
        shown = ", ".join(os.path.basename(e.path) for e in named)
        for e in good:
            if e not in named:
                e.status, e.result = "ignored", False
                e.message = (f"another notebook of {e.student}'s submission, not named after the exercise ({shown} "
                             "is): not graded")
        good = named
    if len(good) > 1:
        filled = {}
        for e in good:
            try:
                filled[id(e)] = has_answers(read(e))
            except Refused:
                filled[id(e)] = True
        with_answers = [e for e in good if filled[id(e)]]
        if with_answers and len(with_answers) < len(good):
            shown = ", ".join(os.path.basename(e.path) for e in with_answers)
            for e in good:
                if e not in with_answers:
                    e.status, e.result = "ignored", False
                    e.message = (f"a blank copy of the release (no answer cell edited) beside {shown}: not graded")
            good = with_answers
    if policy == "latest" and len(good) > 1:
        # the LMS's attempt time, then the name's attempt suffix (a browser's "(1)", Canvas's "-1" for a file uploaded
        # again under its name); not Canvas's attachment id (a download holds the current submission only: its
        # files are one submission, named by attachment — lib/content_zipper.rb), nor the file time or path
        order = {id(e): e.order[1:-2] for e in good}
        last = max(order.values())
        later = [e for e in good if order[id(e)] == last]
        for e in good:
            if order[id(e)] != last:
                e.status, e.result = "superseded", False
                e.message = (f"an earlier attempt of {e.student} than {later[-1].path} (policy: latest)")


def several_line(student, entries, policy):
    """The line a run prints for a student with several notebooks graded, or ""."""
    graded = [e for e in entries if e.status is None]
    if len(graded) < 2:
        return ""
    names = ", ".join(os.path.basename(e.path) for e in graded)
    why = "policy: best" if policy == "best" else "files of one submission"
    return f"several   {student}: {len(graded)} notebooks graded, the best counts ({why}): {names}"
