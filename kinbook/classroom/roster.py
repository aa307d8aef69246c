"""The roster: who is in the course, and how each student is called by kinbook and by the LMS.

``kinbook grade|export|report --roster FILE`` reads one of:

* **kinbook's own** ``roster.csv``, with a header row naming its columns (any order, any case):

  ===========  =================================================================================================
  ``student``  the kinbook id (required): the name of the student's folder or file in ``collected/``, the id their
               variant was made for (letters, digits and ``._@+-``)
  ``name``     the name to show (default: the id); ``first`` and ``last`` may be given instead or as well
  ``lms_id``   the LMS's id: Canvas's user id ("ID"), Moodle's participant id — what bulk downloads are named with
  ``sis_id``   the institution's id ("SIS User ID" in Canvas, "ID number" in Moodle)
  ``login``    the login ("SIS Login ID" in Canvas, "Username" in Moodle)
  ``email``    the e-mail address
  ``section``  the section or group
  ===========  =================================================================================================

* a **Canvas gradebook export** as downloaded (Grades → Export: ``Student, ID, SIS User ID, SIS Login ID,
  Section, …``; the ``Points Possible`` row and Canvas's test student are skipped). kinbook id: the SIS Login ID,
  else the SIS User ID, else the Canvas ID;
* a **Moodle** grading worksheet (Assignment → Download grading worksheet: ``Identifier`` = "Participant 123",
  ``Full name``, ``Email address`` …) or gradebook / participants export (``First name, Last name, ID number,
  Email address`` …). kinbook id: the ID number, else the username, else the e-mail address.

``--roster-id COLUMN`` names the column that holds the kinbook id instead.
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass, fields

from ..errors import GradingError
from .files import id_key, student_id

__all__ = ["Student", "Roster", "read_roster", "MAX_ROSTER_BYTES"]

MAX_ROSTER_BYTES = 20 * 1024 * 1024
MAX_FIELD = 200


@dataclass
class Student:
    """One row of the roster."""

    student: str
    name: str = ""
    first: str = ""
    last: str = ""
    lms_id: str = ""
    sis_id: str = ""
    login: str = ""
    email: str = ""
    section: str = ""

    @property
    def display(self):
        return self.name or " ".join(x for x in (self.first, self.last) if x) or self.student

    def names(self):
        """(first, last) for an LMS that wants them apart."""
        if self.first or self.last:
            return self.first, self.last
        if "," in self.name:  # Canvas's sortable name, "Garcia, Ana"
            last, first = (x.strip() for x in self.name.split(",", 1))
            return first, last
        words = self.name.split()
        return (" ".join(words[:-1]), words[-1]) if len(words) > 1 else (self.name, "")


FIELDS = [f.name for f in fields(Student)]


class Roster:
    """The students of a course, looked up by any of their ids.

    Parameters
    ----------
    students : list of Student
    source : str
        What it was read from (``kinbook``, ``canvas``, ``moodle``), for messages.
    points : dict
        ``{assignment column: points}``: what the LMS says each assignment is worth (Canvas's ``Points Possible``
        row, under columns such as ``Exercise 9 (40109)``), for the export to compare with kinbook's points.
    """

    def __init__(self, students, source="kinbook", points=None):
        self.students = list(students)
        self.source = source
        self.points = dict(points or {})
        self.by_id = {s.student: s for s in self.students}
        lookup, clash = {}, set()
        for s in self.students:
            keys = {("student", id_key(s.student))}
            for f in ("lms_id", "sis_id", "login", "email"):
                value = getattr(s, f)
                if value:
                    keys.add(("lms", value.strip().casefold()))
                    keys.add(("student", id_key(value)))
            if s.email and "@" in s.email:
                keys.add(("student", id_key(s.email.split("@", 1)[0])))
            for k in keys:
                if k in lookup and lookup[k] is not s:
                    clash.add(k)
                lookup[k] = s
        for k in clash:
            del lookup[k]
        self._lookup = lookup

    def __len__(self):
        return len(self.students)

    def __iter__(self):
        return iter(self.students)

    def __contains__(self, sid):
        return sid in self.by_id

    def find(self, raw, key="student"):
        """The roster's student for an id read from a path (``key`` "student" or "lms"), or None."""
        if key == "lms":
            return self._lookup.get(("lms", raw.strip().casefold())) or self._lookup.get(("student", id_key(raw)))
        return self._lookup.get(("student", id_key(raw))) or self._lookup.get(("lms", raw.strip().casefold()))

    def knows(self, text):
        """Whether ``text`` is one of the roster's ids (so a ``-1`` at its end is not an attempt number)."""
        return self.find(text) is not None


def _clean(value):
    value = "".join(c for c in str(value or "") if c.isprintable()).strip()
    return value[:MAX_FIELD]


def _canonical(header):
    return re.sub(r"[^a-z0-9]+", " ", header.casefold()).strip()


_KINBOOK = {"student": "student", "id": "student", "kinbook id": "student", "name": "name", "display name": "name",
            "first": "first", "first name": "first", "last": "last", "last name": "last", "lms id": "lms_id",
            "lms": "lms_id", "sis id": "sis_id", "sis": "sis_id", "login": "login", "username": "login",
            "email": "email", "e mail": "email", "email address": "email", "section": "section", "group": "section"}
_CANVAS = {"student": "name", "id": "lms_id", "sis user id": "sis_id", "sis login id": "login", "section": "section",
           "integration id": None}
_MOODLE = {"identifier": "lms_id", "full name": "name", "first name": "first", "last name": "last",
           "id number": "sis_id", "username": "login", "email address": "email", "group": "section",
           "groups": "section"}


def _format(header):
    """(source, column mapping) of a roster's header: Canvas's, Moodle's or kinbook's."""
    if {"sis user id", "sis login id"} & set(header) and "student" in header:
        return "canvas", _CANVAS
    if "identifier" in header or ("email address" in header and "first name" in header) or "full name" in header:
        return "moodle", _MOODLE
    return "kinbook", _KINBOOK


def _values(source, cols, row, n):
    """{field: text} of a roster row, or None for a row that is not a student (blank, Canvas's extra rows)."""
    if not any(c.strip() for c in row):
        return None
    values = {f: _clean(row[i]) if i < len(row) else "" for f, i in cols.items()}
    if source == "canvas":
        if "points possible" in values.get("name", "").casefold() or (not values.get("lms_id") and n <= 3):
            return None  # the 'Points Possible' (and posting policy) rows under the header
        if values.get("name", "").casefold() in ("student, test", "test student"):
            return None  # Canvas's own test student
    if source == "moodle" and values.get("lms_id", "").casefold().startswith("participant"):
        values["lms_id"] = values["lms_id"].split()[-1]
    return values


def _check_id(path, n, sid, id_column, seen):
    if not sid:
        raise GradingError(f"roster {str(path)!r}, row {n}: no student id"
                           + (f" in column {id_column!r}" if id_column else ""))
    fixed, problem = student_id(sid)
    if problem or fixed != sid:
        raise GradingError(f"roster {str(path)!r}, row {n}: the id {sid!r} is not a safe file name (letters, "
                           f"digits and ._@+- only, at most 64 characters); choose another column with --roster-id")
    if id_key(sid) in seen:
        raise GradingError(f"roster {str(path)!r}: rows {seen[id_key(sid)]} and {n} have the same id {sid!r}")
    seen[id_key(sid)] = n


def read_roster(path, id_column=None):
    """Read a roster file (see the module docstring) → :class:`Roster`.

    Raises
    ------
    GradingError
        Naming the file, the row and the column of what cannot be used (no id, an id that is not a safe file name,
        two rows with one id).
    """
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_ROSTER_BYTES + 1)
    except OSError as exc:
        raise GradingError(f"roster {str(path)!r} cannot be read: {exc.strerror}") from None
    if len(data) > MAX_ROSTER_BYTES:
        raise GradingError(f"roster {str(path)!r} is larger than {MAX_ROSTER_BYTES:,} bytes")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("cp1252", "replace")  # a spreadsheet's "CSV" in the old Windows encoding
    try:
        dialect = csv.Sniffer().sniff(text[:4096], delimiters=",;\t")
    except csv.Error:
        dialect = csv.excel
    rows = list(csv.reader(io.StringIO(text), dialect))
    if not rows:
        raise GradingError(f"roster {str(path)!r} is empty")
    header = [_canonical(h) for h in rows[0]]
    source, mapping = _format(header)
    cols = {}
    for i, h in enumerate(header):
        f = mapping.get(h)
        if f and f not in cols:
            cols[f] = i
    chosen = None
    if id_column is not None:
        want = _canonical(id_column)
        if want not in header:
            raise GradingError(f"roster {str(path)!r} has no column {id_column!r} (--roster-id); its columns: "
                               f"{', '.join(rows[0])}")
        chosen = header.index(want)
    elif source == "kinbook" and "student" not in cols:
        raise GradingError(f"roster {str(path)!r} has no 'student' column (the kinbook id); its columns: "
                           f"{', '.join(rows[0])} — see docs/instructors.md, or name the id column with --roster-id")
    students, seen = [], {}
    points = _points_possible(rows, header, mapping) if source == "canvas" else {}
    for n, row in enumerate(rows[1:], start=2):
        values = _values(source, cols, row, n)
        if values is None:
            continue
        if chosen is not None:
            sid = _clean(row[chosen]) if chosen < len(row) else ""
        else:
            sid = {"kinbook": values.get("student", ""),
                   "canvas": values.get("login") or values.get("sis_id") or values.get("lms_id", "")}.get(
                source, values.get("sis_id") or values.get("login") or values.get("email", ""))
        _check_id(path, n, sid, id_column, seen)
        values["student"] = sid
        students.append(Student(**{f: values.get(f, "") for f in FIELDS}))
    return Roster(students, source, points)


_ASSIGNMENT = re.compile(r"^.+ \(\d+\)$")


def _points_possible(rows, header, mapping):
    """``{assignment column: points}`` from the ``Points Possible`` row of a Canvas export (``10.00``, or ``10,00``
    in a decimal-comma locale's export)."""
    for row in rows[1:4]:
        if row and "points possible" in row[0].casefold():
            out = {}
            for i, h in enumerate(rows[0]):
                if header[i] in mapping or not _ASSIGNMENT.match(h.strip()) or i >= len(row):
                    continue
                try:
                    out[_clean(h)] = float(row[i].strip().replace(",", "."))
                except ValueError:
                    continue
            return out
    return {}
