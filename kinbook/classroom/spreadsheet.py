"""Reading a table as spreadsheets write it (the roster's file layer): bytes → text → rows, every line accounted for.

A roster comes from Excel, LibreOffice, Numbers, Google Sheets, Canvas or Moodle, in whatever the instructor's
locale gives:

* **encodings**: UTF-8 with or without a byte-order mark, UTF-16 (Excel's "Unicode Text", with its BOM, or without
  one when the NULs show it), and, for a file that is not UTF-8, the old Windows encoding cp1252;
* **line endings**: LF, CRLF, and the lone CR of old Mac Excel;
* **delimiters**: ``,``, ``;`` (Excel in Spanish, German, French… locales, where ``,`` is the decimal comma) and tab,
  chosen from the header line — the delimiter that splits it most, outside quotes (a one-column file has none);
* **quoted fields** (``"García, Ana"``, ``""`` for a quote), and fields of any size up to the file's.

What cannot be read whole is a :class:`~kinbook.errors.RosterError` naming the file and the line — a quote that is
never closed, a quoted field running over several lines, bytes that are no text — never a row silently dropped or
two students read as one.
"""

from __future__ import annotations

import codecs
import csv
import io

from ..errors import RosterError

__all__ = ["read_rows", "decode_table", "MAX_ROSTER_BYTES", "DELIMITERS"]

MAX_ROSTER_BYTES = 20 * 1024 * 1024
#: The delimiters a spreadsheet's "CSV" or "Text" export uses.
DELIMITERS = (",", ";", "\t")


def _utf16_without_bom(data):
    """'utf-16-le' or 'utf-16-be' when the bytes look like UTF-16 text without a BOM (NULs in every other byte of
    the first line), else None."""
    head = data[:200]
    if len(head) < 4 or len(head) % 2:
        head = head[:len(head) - len(head) % 2]
    even, odd = head[0::2], head[1::2]
    if odd and odd.count(0) >= 0.8 * len(odd) and even.count(0) == 0:
        return "utf-16-le"
    if even and even.count(0) >= 0.8 * len(even) and odd.count(0) == 0:
        return "utf-16-be"
    return None


def decode_table(data, name="the file"):
    """The text of a spreadsheet's export (see the module docstring), line endings made ``\\n``.

    Raises
    ------
    RosterError
        Bytes that are no text in any of the encodings, or NUL characters left in the text (a binary file, an
        ``.xlsx`` given as CSV).
    """
    if data.startswith(codecs.BOM_UTF8):
        encoding, data = "utf-8", data[len(codecs.BOM_UTF8):]
    elif data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        encoding = "utf-16"
    else:
        encoding = _utf16_without_bom(data) or "utf-8"
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError as exc:
        if encoding != "utf-8":
            line = data[:exc.start].count(b"\n\x00" if encoding.endswith("le") else b"\x00\n") + 1
            raise RosterError(f"{name} is not {encoding.upper()} text (line {line}): save it again as CSV UTF-8") \
                from None
        try:
            text = data.decode("cp1252")  # a spreadsheet's "CSV" in the old Windows encoding
        except UnicodeDecodeError as exc2:
            line = data[:exc2.start].count(b"\n") + 1
            raise RosterError(f"{name}, line {line}: byte 0x{data[exc2.start]:02x} is text in neither UTF-8 nor "
                              "Windows-1252: save the file again as CSV UTF-8") from None
    text = text.replace("\r\n", "\n").replace("\r", "\n")
    if "\0" in text:
        line = text[:text.index("\0")].count("\n") + 1
        raise RosterError(f"{name}, line {line}: holds NUL characters — not a text table (an .xlsx or .ods file? "
                          "export it as CSV)")
    return text


def _split_count(line, delimiter):
    """How many times ``delimiter`` occurs in ``line`` outside double quotes."""
    count, quoted = 0, False
    for c in line:
        if c == '"':
            quoted = not quoted
        elif c == delimiter and not quoted:
            count += 1
    return count


def _delimiter(text):
    """The delimiter that splits the first non-blank line most (ties and none: ``,``)."""
    first = next((line for line in text.split("\n") if line.strip()), "")
    counts = {d: _split_count(first, d) for d in DELIMITERS}
    best = max(DELIMITERS, key=lambda d: (counts[d], d == ","))
    return best if counts[best] else ","


def read_rows(path, max_bytes=MAX_ROSTER_BYTES):
    """Every line of the table at ``path`` as a list of fields (a blank line is ``[]``, so that row ``n`` of the
    list is line ``n + 1`` of the file).

    Raises
    ------
    RosterError
        The file cannot be read, is too large, is no text, or has a malformed line (named by its number).
    """
    name = f"roster {str(path)!r}"
    try:
        with open(path, "rb") as f:
            data = f.read(max_bytes + 1)
    except OSError as exc:
        raise RosterError(f"{name} cannot be read: {exc.strerror}") from None
    if len(data) > max_bytes:
        raise RosterError(f"{name} is larger than {max_bytes:,} bytes")
    text = decode_table(data, name)
    delimiter = _delimiter(text)
    rows = []
    limit = csv.field_size_limit()
    csv.field_size_limit(max(limit, len(text) + 1))
    try:
        reader = csv.reader(io.StringIO(text, newline=""), delimiter=delimiter, strict=True)
        while True:
            start = reader.line_num + 1
            try:
                row = next(reader)
            except StopIteration:
                break
            except csv.Error as exc:
                why = _why(exc)
                if reader.line_num > start and not why.startswith("a quote opened"):
                    why = f"a quote opened on this line is never closed on it (the field runs on into line " \
                          f"{reader.line_num})"
                raise RosterError(f"{name}, line {start}: {why}") from None
            if reader.line_num != start:
                raise RosterError(f"{name}, line {start}: a quoted field runs over lines {start} to {reader.line_num} "
                                  "(a quote that is not closed?); no row of a roster spans lines")
            rows.append(row)
    finally:
        csv.field_size_limit(limit)
    return rows


def _why(exc):
    text = str(exc)
    if "unexpected end of data" in text or "EOF" in text:
        return "a quote opened on this line is never closed"
    if "expected" in text and "after" in text:
        return f"a quote in the middle of a field ({text}); write a quote inside a quoted field as \"\""
    return text
