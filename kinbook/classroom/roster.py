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

import re
import unicodedata
from dataclasses import dataclass, fields

from ..errors import RosterError
from .ids import RULE, id_key, id_problem
from .spreadsheet import MAX_ROSTER_BYTES, read_rows

__all__ = ["Student", "Roster", "read_roster", "MAX_ROSTER_BYTES"]

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


_KINBOOK = {"student": "student", "id": "student", "kinbook id": "student", "name": "name", "display name": "name",
            "first": "first", "first name": "first", "last": "last", "last name": "last", "lms id": "lms_id",
            "lms": "lms_id", "sis id": "sis_id", "sis": "sis_id", "login": "login", "username": "login",
            "email": "email", "e mail": "email", "email address": "email", "section": "section", "group": "section"}
# Canvas writes its gradebook export's headers in English whatever the user's language (lib/gradebook_exporter.rb:
# literal "Student", "ID", "SIS User ID", "SIS Login ID", "Section", "    Points Possible"; "LastName", "FirstName"
# instead of "Student" with the "show first and last names" setting); only its numbers follow the locale ("10,00").
_CANVAS = {"student": "name", "lastname": "last", "firstname": "first", "id": "lms_id", "sis user id": "sis_id",
           "sis login id": "login", "section": "section", "integration id": None}

# Moodle writes its headers in the user's language, from its language strings: the grading worksheet's
# get_string('recordid', 'assign'), get_string('fullname'), and the identity fields' names ('email', 'idnumber',
# 'username'); the grade export's 'firstname', 'lastname'. English (moodle/moodle lang/en), and es, ca, gl, pt, fr,
# it, de, nl, eu as their language packs have them (projectestac/moodle-langpacks, moodle.php and assign.php).
_MOODLE_WORDS = {
    "lms_id": ["Identifier", "Identificador", "Identifiant", "Identificativo", "Identificatie", "Identifikatzailea",
               "ID"],
    "name": ["Full name", "Nombre completo", "Nom complet", "Nome completo", "Vollständiger Name", "Volledige naam",
             "Izen osoa"],
    "first": ["First name", "Nombre", "Nom", "Nome", "Prénom", "Vorname", "Voornaam", "Izena"],
    "last": ["Last name", "Surname", "Apellido(s)", "Cognoms", "Apelido", "Apelidos", "Nom de famille", "Cognome",
             "Nachname", "Achternaam", "Abizena(k)"],
    "sis_id": ["ID number", "Número de ID", "Número ID", "Número de identificação (ID)", "Numéro d’identification",
               "Codice identificativo", "ID-Nummer", "Nummer (ID)", "ID zenbakia"],
    "login": ["Username", "Nombre de usuario", "Nom d'usuari", "Nome de usuario", "Nome de utilizador",
              "Nom d’utilisateur", "Anmeldename", "Gebruikersnaam", "Erabiltzaile-izena"],
    "email": ["Email address", "Dirección de correo", "Adreça electrònica", "Enderezo de correo", "E-mail",
              "Adresse de courriel", "Indirizzo email", "E-Mail-Adresse", "E-mailadres", "Helbide elektronikoa"],
    "section": ["Group", "Groups", "Grupo", "Grupos", "Grup", "Grups", "Groupe", "Groupes", "Gruppo", "Gruppi",
                "Gruppe", "Gruppen", "Groep", "Groepen", "Taldea", "Taldeak"],
}


def _canonical(header):
    text = unicodedata.normalize("NFKD", header.casefold())
    text = "".join(c for c in text if not unicodedata.combining(c))
    return re.sub(r"[^a-z0-9]+", " ", text).strip()


_MOODLE = {_canonical(w): f for f, words in _MOODLE_WORDS.items() for w in words}
#: Headers that say "Moodle" on their own (German's bare "ID" does not: kinbook's own roster may have one).
_MOODLE_MARKS = {_canonical(w) for f in ("lms_id", "name") for w in _MOODLE_WORDS[f] if w != "ID"}


def _format(header):
    """(source, column mapping) of a roster's header: Canvas's, Moodle's (in any of its languages above) or
    kinbook's."""
    if "sis login id" in header and ({"student", "lastname"} & set(header) or "sis user id" in header):
        return "canvas", _CANVAS
    firsts = {_canonical(w) for w in _MOODLE_WORDS["first"]}
    emails = {_canonical(w) for w in _MOODLE_WORDS["email"]}
    if _MOODLE_MARKS & set(header) or (emails & set(header) and firsts & set(header)):
        return "moodle", _MOODLE
    return "kinbook", _KINBOOK


def _values(source, cols, row, n):
    """{field: text} of a roster row, or None for a row that is not a student (blank, Canvas's extra rows)."""
    if not any(c.strip() for c in row):
        return None
    values = {f: _clean(row[i]) if i < len(row) else "" for f, i in cols.items()}
    if source == "canvas":
        if "points possible" in row[0].casefold() or (not values.get("lms_id") and n <= 3):
            return None  # the 'Points Possible' (and posting policy) rows under the header
        if (values.get("name", "").casefold() in ("student, test", "test student")
                or (values.get("last", ""), values.get("first", "")) == ("Student", "Test")):
            return None  # Canvas's own test student
    if source == "moodle":  # "Participant 123", "Participante 123", "Teilnehmer/in 123": the number
        m = re.fullmatch(r"\D*?(\d+)", values.get("lms_id", ""))
        if m:
            values["lms_id"] = m.group(1)
    return values


def _check_id(path, n, sid, id_column, seen):
    if not sid:
        raise RosterError(f"roster {str(path)!r}, line {n}: no student id"
                          + (f" in column {id_column!r}" if id_column else ""))
    problem = id_problem(unicodedata.normalize("NFC", sid))
    if problem:
        raise RosterError(f"roster {str(path)!r}, line {n}: {problem}, got {sid[:80]!r} — a student id must be {RULE}; "
                          "choose another column with --roster-id")
    if id_key(sid) in seen:
        raise RosterError(f"roster {str(path)!r}: lines {seen[id_key(sid)]} and {n} have the same id {sid!r} (ids that "
                          "differ only in case or Unicode form are one student)")
    seen[id_key(sid)] = n


def read_roster(path, id_column=None):
    """Read a roster file (see the module docstring) → :class:`Roster`.

    Raises
    ------
    RosterError
        Naming the file, the row and the column of what cannot be used (no id, an id that is not a safe file name,
        two rows with one id).
    """
    rows = read_rows(path)
    if not rows:
        raise RosterError(f"roster {str(path)!r} is empty")
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
            raise RosterError(f"roster {str(path)!r} has no column {id_column!r} (--roster-id); its columns: "
                               f"{', '.join(rows[0])}")
        chosen = header.index(want)
    elif source == "kinbook" and "student" not in cols:
        raise RosterError(f"roster {str(path)!r} has no 'student' column (the kinbook id); its columns: "
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
        values["student"] = sid = unicodedata.normalize("NFC", sid)
        students.append(Student(**{f: values.get(f, "") for f in FIELDS}))
    if not students:
        raise RosterError(f"roster {str(path)!r} has a header and no student (its columns: {', '.join(rows[0])})")
    roster = Roster(students, source, points)
    roster.path = str(path)  # an input: no command writes over it (kinbook.core.atomic.protect)
    return roster


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
