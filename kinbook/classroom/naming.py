"""Who handed in a file, when, and which attempt it is — read from its path.

A path below ``collected/`` is read one of two ways:

* with a **pattern** (``kinbook grade --id-pattern``): a regular expression searched in the path relative to the
  directory the instructor named (``/`` between directories). Its named groups say what the name holds:

  ==============  ===============================================================================================
  ``student``     the kinbook id
  ``lms``         an LMS id (Canvas's user id, Moodle's participant id), mapped to a kinbook id by the roster
  ``time``        when it was handed in (``2026-03-01-23-59-00``, ``20260301T2359``, ``2026-03-01 23:59`` …)
  ``late``        non-empty when the LMS marked the file late
  ``attempt``     the attempt's number (a higher number is a later attempt)
  ``file``        the file's own name, where attempt suffixes are looked for as well
  ==============  ===============================================================================================

  Ready patterns (:data:`PATTERNS`) are given by name: ``canvas``, ``moodle``, ``blackboard``.
* without one (the default): ``<student>/<exercise>.ipynb``, ``<exercise>-<student>.ipynb`` (what ``kinbook
  variant`` writes) or ``<student>.ipynb``.

Either way the suffixes a browser or an LMS adds to a file handed in again are read as an attempt of the same
student, never as another student: ``name (1).ipynb`` (a browser's second download), ``name-1.ipynb`` (Canvas, a
file uploaded again under the same name) and a trailing timestamp. A trailing ``-<number>`` is read as an attempt
only when the number has at most two digits and, with a roster, when the name with it is not itself on the roster.

**Who and when come from the LMS, never from a name the student chose** (issue 36). A file in a folder is the
folder's student's, whatever its own name says: ``mallory/ex01-alice.ipynb`` is mallory's, and the name naming
alice is a signal for the instructor (:attr:`Name.names`), never an attempt of alice's. A file's own name (the part
a student typed, or that a browser made) gives at most the order of one student's own attempts; the time of a
submission is the LMS's — a pattern's ``time`` group, the LMS's ``late`` mark — or the file's (``--file-times``),
never a date written in the file's name. Only in the flat layout (``<exercise>-<student>.ipynb`` with no folder) is
the name the only place an id can come from: collect into folders, or give the LMS's pattern, where students name
their own files.
"""

from __future__ import annotations

import datetime as _dt
import re
from dataclasses import dataclass

from ..errors import GradingError

__all__ = ["PATTERNS", "Name", "read_name", "compile_pattern", "parse_time", "NamingError"]

#: Ready patterns for LMS bulk downloads (``--id-pattern canvas``).
PATTERNS = {
    # Canvas "Download Submissions": <lastfirst>_[late_]<user id>_<submission id>_<file name as uploaded>, the file
    # name with '-1', '-2' … when the student uploaded a file of the same name again
    "canvas": r"(?:^|/)(?P<name>[^/_]+)_(?:(?P<late>late|LATE)_)?(?P<lms>\d+)_(?P<submission>\d+)_(?P<file>[^/]+)$",
    # Moodle "Download all submissions": a folder '<Full Name>_<participant id>_assignsubmission_file_' (or _onlinetext_) holding the
    # files (or, flat, the files named with that prefix)
    "moodle": r"(?:^|/)(?P<name>[^/]+?)_(?P<lms>\d+)_assignsubmission_(?:file|onlinetext)_(?:/(?:.*/)?)?(?P<file>[^/]*)$",
    # Blackboard "Download Assignment": <assignment>_<username>_attempt_<yyyy-mm-dd-hh-mm-ss>[_<file name>]
    "blackboard": r"(?:^|/)[^/]*?_(?P<student>[^_/]+)_attempt_(?P<time>\d{4}-\d{2}-\d{2}-\d{2}-\d{2}-\d{2})"
                  r"(?:_(?P<file>[^/]+))?$",
}

_GROUPS = {"student", "lms", "time", "late", "attempt", "file", "name", "submission"}
_BROWSER = re.compile(r"^(?P<base>.*?)\s*\((?P<n>\d{1,3})\)$")  # 'name (1)'
_SUFFIX = re.compile(r"^(?P<base>.+?)-(?P<n>\d{1,2})$")       # 'name-1'
_STAMP = re.compile(r"^(?P<base>.+?)[-_ ](?P<time>\d{4}-?\d{2}-?\d{2}(?:[T_ -]?\d{2}[-:.h]?\d{2}(?:[-:.]?\d{2})?)?)$")
_TIME = re.compile(r"^(\d{4})-?(\d{2})-?(\d{2})(?:[T_ -]?(\d{2})[-:.h]?(\d{2})(?:[-:.]?(\d{2}))?)?$")


class NamingError(GradingError):
    """A pattern the instructor gave that cannot be used (reported before anything is read)."""


@dataclass
class Name:
    """What a path says about its file.

    Attributes
    ----------
    raw : str or None
        The student's id as written in the path (before the roster maps it), or None when the path names none.
    key : str
        ``"student"`` (``raw`` is a kinbook id) or ``"lms"`` (an LMS id, for the roster to map).
    time : datetime.datetime or None
        From the name (naive: the zone of the due date applies).
    late : bool
        The LMS marked the file late.
    attempt : int
        0 for a first attempt; higher for later ones.
    exercise_named : bool or None
        Whether the file is named after the exercise (None: the pattern decides, not the name).
    why : str
        When ``raw`` is None: why no student could be read.
    base : str
        The file's name without its attempt suffixes.
    names : str or None
        Another id the file's own name names (``mallory/ex01-alice.ipynb``): a signal, not an id (the caller
        compares it with the folder's by :func:`kinbook.classroom.files.id_key`).
    order : tuple
        The LMS's order of the file among a student's files (Canvas's submission number), then the order the name
        gives (its attempt suffix, a date in it): used only to sort one student's own files.
    """

    raw: str | None
    key: str = "student"
    time: _dt.datetime | None = None
    late: bool = False
    attempt: int = 0
    exercise_named: bool | None = None
    why: str = ""
    base: str = ""
    names: str | None = None
    order: tuple = ()


def compile_pattern(pattern):
    """A ready pattern's name or a regular expression → compiled pattern (None stays None)."""
    if pattern is None:
        return None
    text = PATTERNS.get(pattern, pattern)
    try:
        rx = re.compile(text)
    except re.error as exc:
        raise NamingError(f"--id-pattern {pattern!r} is not a regular expression: {exc}") from None
    groups = set(rx.groupindex)
    if not groups & {"student", "lms"}:
        raise NamingError(f"--id-pattern {pattern!r} has no group (?P<student>…) or (?P<lms>…): it cannot say whose "
                          f"file it is (ready patterns: {', '.join(PATTERNS)})")
    unknown = groups - _GROUPS
    if unknown:
        raise NamingError(f"--id-pattern {pattern!r}: unknown group(s) {', '.join(sorted(unknown))} (known: "
                          f"{', '.join(sorted(_GROUPS))})")
    return rx


def parse_time(text):
    """A time written in a file name (``2026-03-01-23-59-00``, ``20260301T2359``, ``2026-03-01``) → naive datetime,
    or None when it is not one."""
    m = _TIME.match(text.strip())
    if not m:
        return None
    y, mo, d, h, mi, s = (int(g) if g else 0 for g in m.groups())
    try:
        return _dt.datetime(y, mo, d, h, mi, s)
    except ValueError:
        return None


def _strip_attempt(stem, keep=None):
    """(base, attempt number, time) of a file stem or id with a browser's, an LMS's or a timestamp suffix.

    ``keep(text)`` says whether a text is an id on its own (on the roster): then a ``-N`` suffix is part of it.
    """
    attempt, time = 0, None
    m = _BROWSER.match(stem)
    if m and m["base"]:
        stem, attempt = m["base"], int(m["n"])
    m = _STAMP.match(stem)
    if m and parse_time(m["time"]) is not None and not (keep and keep(stem)):
        stem, time = m["base"], parse_time(m["time"])
    m = _SUFFIX.match(stem)
    if m and not (keep and keep(stem)):
        stem, attempt = m["base"], max(attempt, int(m["n"]))
    return stem, attempt, time


def read_name(parts, exercise, root_name, pattern=None, keep=None):
    """Read ``parts`` (the path below the named directory, as a tuple) → :class:`Name`.

    Parameters
    ----------
    parts : tuple of str
    exercise : str
    root_name : str
        The named directory's own name (the student of a file named after the exercise directly in it).
    pattern : compiled regular expression or None
    keep : callable or None
        ``keep(text)`` is True for a text that is an id on the roster (its ``-N`` ending is not an attempt).
    """
    filename = parts[-1]
    stem = filename[:-len(".ipynb")] if filename.endswith(".ipynb") else filename
    if pattern is not None:
        m = pattern.search("/".join(parts))
        if not m:
            return Name(None, why=f"does not match the --id-pattern {pattern.pattern!r}")
        g = {k: v for k, v in m.groupdict().items() if v is not None}
        key = "student" if g.get("student") else "lms"
        raw = g.get("student") or g.get("lms")
        if not raw:
            return Name(None, why="the --id-pattern matched no student id")
        fstem = g.get("file", stem)
        fstem = fstem[:-len(".ipynb")] if fstem.endswith(".ipynb") else fstem
        base, attempt, stamp = _strip_attempt(fstem)
        if g.get("attempt", "").isdigit():
            attempt = int(g["attempt"])
        time = parse_time(g["time"]) if g.get("time") else None  # the LMS's field, never a date in the file's name
        lms_order = int(g["submission"]) if g.get("submission", "").isdigit() and len(g["submission"]) < 30 else -1
        return Name(raw, key, time, bool(g.get("late")), attempt, None, base=base,
                    order=(lms_order, _stamp(time), attempt, _stamp(stamp)))
    base, attempt, stamp = _strip_attempt(stem)
    order = (-1, "", attempt, _stamp(stamp))
    if len(parts) > 1:  # in a folder: the folder's student's file, whatever its name says
        owner, named, exercise_named = parts[-2], None, base == exercise
        if not exercise_named and stem.startswith(exercise + "-"):
            named, attempt, stamp = _strip_attempt(stem[len(exercise) + 1:], keep)
            exercise_named, base, order = True, exercise, (-1, "", attempt, _stamp(stamp))
        elif not exercise_named and keep is not None and keep(base) and base != owner:
            named = base  # '<classmate>.ipynb' in mallory's folder
        if named == owner:
            named = None  # (the same id in another case or Unicode form: told apart by the caller's id key)
        return Name(owner, "student", None, False, attempt, exercise_named, base=base, names=named, order=order)
    if base == exercise:
        return Name(root_name, "student", None, False, attempt, True, base=base, order=order)
    if stem.startswith(exercise + "-"):
        rest, attempt, stamp = _strip_attempt(stem[len(exercise) + 1:], keep)
        return Name(rest, "student", None, False, attempt, True, base=exercise, order=(-1, "", attempt, _stamp(stamp)))
    raw, attempt, stamp = _strip_attempt(stem, keep)
    return Name(raw, "student", None, False, attempt, False, base=raw, order=(-1, "", attempt, _stamp(stamp)))


def _stamp(time):
    return time.isoformat() if time is not None else ""
