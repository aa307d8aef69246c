"""The one sanitizer for text a student controls, before kinbook stores, prints or exports it.

A student controls more text than their answers: file and directory names, exception messages, the reprs their
objects give, the first lines of their cells. Any of it can reach the gradebook, the instructor's terminal, a
spreadsheet or a feedback page. :func:`clean` makes it inert everywhere:

* C0 and C1 control characters and DEL (a terminal's escape sequences — ANSI colours, OSC window titles,
  cursor moves that overwrite a line —, carriage returns that start a new row in a spreadsheet, newlines
  that start a fake line of output), the line and paragraph separators U+2028/U+2029, and the bidirectional
  controls (U+061C, U+200E/F, U+202A–U+202E, U+2066–U+2069: "Trojan Source" reordering) are written as
  visible escapes (``\\x1b``, ``\\u202e``);
* bytes that are not UTF-8 (lone surrogates from a file name) as ``\\xff``.

:func:`csv_field` is :func:`clean` plus the spreadsheet guard: a field that starts like a formula (``=``,
``+``, ``-``, ``@``, a tab or a carriage return) gets a leading apostrophe. kinbook's CSV files are written
with every field quoted (``csv.QUOTE_ALL``).

>>> clean("ok\\x1b]0;pwned\\x07 6/6\\r\\n=cmd|' /C calc'!A0")
"ok\\\\x1b]0;pwned\\\\x07 6/6\\\\r\\\\n=cmd|' /C calc'!A0"
>>> csv_field("=1+1")
"'=1+1"
"""

from __future__ import annotations

import dataclasses

__all__ = ["clean", "clean_lines", "csv_field", "clean_result", "BIDI_CONTROLS", "MULTILINE"]

#: Bidirectional formatting characters.
BIDI_CONTROLS = frozenset("\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")
_SEPARATORS = frozenset("\u2028\u2029")
_FORMULA = ("=", "+", "-", "@", "\t", "\r")


def _unsafe(c):
    o = ord(c)
    return o < 0x20 or 0x7F <= o < 0xA0 or c in BIDI_CONTROLS or c in _SEPARATORS or 0xD800 <= o < 0xE000


_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _escape(c):
    if c in _NAMED:
        return _NAMED[c]
    o = ord(c)
    if 0xD800 <= o < 0xE000:  # a byte that was not UTF-8 (surrogateescape)
        return f"\\x{o - 0xDC00:02x}" if 0xDC80 <= o < 0xDD00 else f"\\u{o:04x}"
    return f"\\x{o:02x}" if o < 0x100 else f"\\u{o:04x}"


def clean(text, limit=None):
    """``text`` (any value: str() of it) with every unsafe character written as a visible escape; at most
    ``limit`` characters (an ellipsis marks a cut)."""
    text = text if isinstance(text, str) else str(text)
    if any(_unsafe(c) for c in text):
        text = "".join(_escape(c) if _unsafe(c) else c for c in text)
    if limit is not None and len(text) > limit:
        text = text[:max(0, limit - 1)] + "…"
    return text


def clean_lines(text, limit=None):
    """:func:`clean` line by line, the newlines kept: for text shown as lines in a page (a student's answer, the code
    of their cell), never printed to a terminal nor written to a CSV field as such."""
    text = text if isinstance(text, str) else str(text)
    text = "\n".join(clean(line) for line in text.split("\n"))
    if limit is not None and len(text) > limit:
        text = text[:max(0, limit - 1)] + "…"
    return text


#: Fields of a result holding several lines (the student's answer and cell, the checker's own HTML): cleaned line by
#: line, so that a feedback page shows them as lines.
MULTILINE = frozenset({"answer", "cell", "html"})


def csv_field(value):
    """A CSV field that no spreadsheet reads as a formula or splits into rows."""
    text = clean(value)
    return "'" + text if text[:1] in _FORMULA else text


def clean_result(result):
    """A :class:`~kinbook.classroom.results.SubmissionResult` whose text fields (and its parts') are
    :func:`clean`."""
    def fix(obj):
        changes = {f.name: (clean_lines if f.name in MULTILINE else clean)(getattr(obj, f.name))
                   for f in dataclasses.fields(obj) if isinstance(getattr(obj, f.name), str)}
        return dataclasses.replace(obj, **changes)

    out = fix(result)
    out.parts = [fix(p) for p in result.parts]
    return out
