"""Student ids: one rule for every command (grade, override, due, extend, variant, export, feedback, the roster).

A student id is what kinbook calls a student: the name of their folder or file in ``collected/``, the name of their
variant, their folder of feedback pages. So it must always be one safe file name, and the same student must be the
same id whatever spreadsheet, file system or keyboard it came through:

* it is **NFC-normalized** (``José`` typed on a Mac and on Windows is one id);
* it holds **letters and digits of any script** (with their combining marks) and ``. _ @ + -``, does not start with
  ``.`` (no hidden file, no ``..``) and has 1 to :data:`MAX_ID_CHARS` characters;
* two ids with the same :func:`id_key` — **NFKC and case folded**: ``ANA`` and ``ana``, ``ｊｏｓé`` (full-width) and
  ``josé`` — are the same student: a command given one spelling finds the other (:func:`find_id`), and two rows or
  files under both are a clash, never two students.

:func:`check_id` is the rule for an id a person types (a command's argument, a roster's cell); :func:`id_from_path`
makes an id of any name read from a path (a character outside the rule becomes ``_``).

>>> check_id("Jose\\u0301")
'José'
>>> id_key("ANA") == id_key("ana"), id_key("ｊｏｓé") == id_key("josé")
(True, True)
>>> id_from_path("a b/c")
('a_b_c', None)
"""

from __future__ import annotations

import difflib
import hashlib
import unicodedata

from ..errors import GradingError

__all__ = ["MAX_ID_CHARS", "RULE", "check_id", "id_problem", "id_key", "id_from_path", "find_id", "closest"]

MAX_ID_CHARS = 64
_EXTRA = "._@+-"
#: The rule in words, for messages.
RULE = (f"letters and digits (any script), and . _ @ + -, not starting with '.', 1 to {MAX_ID_CHARS} characters")


def _allowed(c, first):
    if c in _EXTRA:
        return True
    cat = unicodedata.category(c)
    return cat[0] in "LN" or (not first and cat[0] == "M")


def id_problem(text, what="a student id"):
    """Why ``text`` (already NFC) is not a student id (or whatever ``what`` names under the same rule), or None."""
    if not isinstance(text, str):
        return f"{what} is text, got {type(text).__name__}"
    if not text:
        return f"{what} cannot be empty"
    if len(text) > MAX_ID_CHARS:
        return f"{what} has at most {MAX_ID_CHARS} characters, this one {len(text)}"
    if text.startswith("."):
        return f"{what} cannot start with '.' (a hidden file, or '..')"
    bad = next((c for i, c in enumerate(text) if not _allowed(c, i == 0)), None)
    if bad is not None:
        return f"{what} cannot hold {bad!r} (U+{ord(bad):04X})"
    return None


def check_id(text, what="student id"):
    """``text`` NFC-normalized when it is a valid student id, else :class:`~kinbook.errors.GradingError` saying
    why and what the rule is (``what``: "exercise name" for an exercise, named by the same rule)."""
    norm = unicodedata.normalize("NFC", text) if isinstance(text, str) else text
    problem = id_problem(norm, f"a {what}")
    if problem is not None:
        shown = repr(norm[:80]) if isinstance(norm, str) else repr(norm)[:80]
        raise GradingError(f"{problem}, got {shown}: a {what} must be {RULE}")
    return norm


def id_key(text):
    """The key under which ids are one student: NFKC, case folded. Ids with the same key are the same student for
    a file system, a spreadsheet and every command."""
    return unicodedata.normalize("NFKC", str(text)).casefold()


def id_from_path(name):
    """The student id for a name taken from a path: ``(id, problem)`` with problem None or a message.

    NFC-normalized; characters outside the rule become ``_``; no leading dot. Longer than :data:`MAX_ID_CHARS`: the
    id is shortened (with a hash of the whole name, so that it stays unique) and the problem says why it is not
    graded.

    >>> id_from_path("José")
    ('José', None)
    """
    name = unicodedata.normalize("NFC", str(name))
    sid = "".join(c if _allowed(c, i == 0) else "_" for i, c in enumerate(name)).lstrip(".") or "unknown"
    if len(sid) > MAX_ID_CHARS:
        digest = hashlib.sha256(name.encode("utf-8", "surrogateescape")).hexdigest()[:8]
        return f"{sid[:40]}…{digest}", (f"the student id taken from the path has {len(sid)} characters (at most "
                                        f"{MAX_ID_CHARS}): rename the file or directory and grade again")
    return sid, None


def find_id(text, known):
    """The id of ``known`` that is ``text`` under :func:`id_key` (``text`` itself when it is there), or None."""
    if text in known:
        return text
    key = id_key(text)
    return next((k for k in known if id_key(k) == key), None)


def closest(text, known):
    """The known name closest to ``text`` (difflib), or None — for "did you mean" in messages."""
    known = list(known)
    by_key = {id_key(k): k for k in known}
    found = difflib.get_close_matches(id_key(text), list(by_key), n=1, cutoff=0.6)
    return by_key[found[0]] if found else None
