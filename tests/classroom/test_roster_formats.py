"""A roster as every spreadsheet writes it (issue 31 item 4): one roster written in every combination of encoding
(UTF-8 with and without BOM, UTF-16 LE/BE with and without BOM, cp1252), line ending (LF, CRLF, CR), delimiter
(, ; tab) and quoting (minimal, all) reads as the same students; the same roster with one malformed line, in every
combination, is a RosterError naming that line — never a student dropped."""

import codecs
import csv
import io
import itertools

import pytest

from kinbook.classroom.roster import read_roster
from kinbook.errors import RosterError

STUDENTS = [
    ("ana", "García, Ana"),             # the delimiter inside a field
    ("jose", "José Núñez"),
    ("siobhan", "Siobhan O'Brien-Smith"),
    ("xwang", "王小明"),                 # not in cp1252: left out of that encoding's roster
    ("quote", 'Ana "la jefa" Ruiz'),    # quotes inside a field
    ("semi", "Pérez; Juan"),
    ("tabby", "Tab\tby"),
    ("huge", "x" * 200_000),            # over csv's default field limit (131,072)
    ("Émile", "Émile Zola"),            # a Unicode id
]
ENCODINGS = {  # name: (codec, BOM written in front)
    "utf-8": ("utf-8", b""),
    "utf-8-bom": ("utf-8", codecs.BOM_UTF8),
    "utf-16-le-bom": ("utf-16-le", codecs.BOM_UTF16_LE),
    "utf-16-be-bom": ("utf-16-be", codecs.BOM_UTF16_BE),
    "utf-16-le": ("utf-16-le", b""),
    "utf-16-be": ("utf-16-be", b""),
    "cp1252": ("cp1252", b""),
}
ENDINGS = {"lf": "\n", "crlf": "\r\n", "cr": "\r"}
DELIMITERS = {"comma": ",", "semicolon": ";", "tab": "\t"}
QUOTING = {"minimal": csv.QUOTE_MINIMAL, "all": csv.QUOTE_ALL}
COMBINATIONS = list(itertools.product(ENCODINGS, ENDINGS, DELIMITERS, QUOTING))


def students_for(encoding):
    codec = ENCODINGS[encoding][0]
    out = []
    for sid, name in STUDENTS:
        try:
            (sid + name).encode(codec)
        except UnicodeEncodeError:
            continue
        out.append((sid, name))
    return out


def roster_bytes(encoding, ending, delimiter, quoting, rows=None):
    buf = io.StringIO()
    w = csv.writer(buf, delimiter=DELIMITERS[delimiter], lineterminator=ENDINGS[ending], quoting=QUOTING[quoting])
    w.writerow(["student", "name"])
    w.writerows(rows if rows is not None else students_for(encoding))
    codec, bom = ENCODINGS[encoding]
    return bom + buf.getvalue().encode(codec)


def shown(name):
    """What the roster keeps of a name: printable characters, at most 200 (kinbook.classroom.roster.MAX_FIELD)."""
    return "".join(c for c in name if c.isprintable()).strip()[:200]


def test_the_combinations_are_many():
    assert len(COMBINATIONS) == 7 * 3 * 3 * 2


@pytest.mark.parametrize("encoding,ending,delimiter,quoting", COMBINATIONS)
def test_every_spreadsheet_layout_reads_as_the_same_students(tmp_path, encoding, ending, delimiter, quoting):
    path = tmp_path / "roster.csv"
    path.write_bytes(roster_bytes(encoding, ending, delimiter, quoting))
    got = [(s.student, s.name) for s in read_roster(path)]
    assert got == [(sid, shown(name)) for sid, name in students_for(encoding)]


@pytest.mark.parametrize("encoding,ending,delimiter,quoting", COMBINATIONS)
def test_a_malformed_line_is_named_in_every_layout(tmp_path, encoding, ending, delimiter, quoting):
    d, eol = DELIMITERS[delimiter], ENDINGS[ending]
    good = roster_bytes(encoding, ending, delimiter, quoting, rows=[("ana", "Ana"), ("bob", "Bob"), ("carl", "Carl")])
    codec, bom = ENCODINGS[encoding]
    text = good[len(bom):].decode(codec)
    lines = text.split(eol)
    lines[1] = f'ana{d}"Ana'  # a quote opened on line 2 and never closed: Bob and Carl must not vanish into it
    path = tmp_path / "roster.csv"
    path.write_bytes(bom + eol.join(lines).encode(codec))
    with pytest.raises(RosterError, match="line 2: a quote opened on this line is never closed"):
        read_roster(path)


@pytest.mark.parametrize("raw,words", [
    (b"student,name\nana,Ana\nbob,\"Bob\nsmith\"\ncarl,Carl\n", "line 3: a quoted field runs over lines 3 to 4"),
    (b"student,name\nana,A\"na\"x\n", None),                                  # a quote inside an unquoted field: kept
    (b"student,name\nana,\"Ana\"x\n", "line 2"),                             # text after a closing quote
    (b"PK\x03\x04\x00\x00binary", "line 1: holds NUL characters"),           # an .xlsx given as CSV
    (b"student\n\x81\x8d\n", "line 2: byte 0x81"),                            # neither UTF-8 nor cp1252
])
def test_malformed_files_name_the_line(tmp_path, raw, words):
    path = tmp_path / "roster.csv"
    path.write_bytes(raw)
    if words is None:
        assert [s.student for s in read_roster(path)] == ["ana"]
        return
    with pytest.raises(RosterError, match=words):
        read_roster(path)


def test_ids_that_are_one_student_under_the_key_are_a_clash(tmp_path):
    path = tmp_path / "roster.csv"
    path.write_text("student\nJosé\nJOSE\u0301\n", encoding="utf-8")  # NFD and upper case: the same student
    with pytest.raises(RosterError, match="lines 2 and 3 have the same id"):
        read_roster(path)
