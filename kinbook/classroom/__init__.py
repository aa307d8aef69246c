"""The instructor's side of kinbook: author, release, grade.

* :func:`part` and :func:`parameters` — what an exercise notebook declares (:mod:`.parts`);
* :func:`release` — students' versions of source notebooks (:mod:`.release`);
* :func:`variant` — one student's version with their own parameters (:mod:`.variant`);
* :func:`grade` — in pipeline order: account for every file of ``collected/`` (:mod:`.intake`, :mod:`.files`,
  :mod:`.naming`, :mod:`.roster` read through :mod:`.spreadsheet`, student ids by the one rule of :mod:`.ids`),
  choose which of a student's files is graded (:mod:`.choice`: one LMS submission is a set of files), give a late
  enrolee's file to them and re-attach them to a newer roster (:mod:`.enrolment`), check each notebook against the
  release its student got and carry it over to an edited source (:mod:`.editions`), run submissions in the sandbox
  (:mod:`.sandbox`: bubblewrap), grade their answers, record every attempt in the gradebook (:mod:`.gradebook`,
  SQLite; its failures in the instructor's words: :mod:`.gradebook_failures`) and export grades.csv, totals.csv,
  collection.csv and the feedback pages (every file through :mod:`kinbook.core.atomic`: whole or not at all, never
  over an input);
* the course, one subpackage per command: :mod:`.override` (``override``, ``due``, ``extend``, applied by
  :mod:`.scores`), :mod:`.export` (Canvas, Moodle, CSV), :mod:`.report` (the class report), :mod:`.feedback`
  (a folder per student, or a zip per exercise for the LMS's bulk upload: :mod:`.feedback.upload`),
  :mod:`.validate` (an exercise through the real grader). They are imported where used,
  so that a student's kernel that imports ``part`` stays light.

See docs/instructors.md (a term, step by step) and the README's "For instructors" section.
"""

import sys as _sys

# jsonschema (imported by nbformat) spends ~5 s compiling an IRI grammar from the optional package
# rfc3987_syntax; notebooks never use that format, so the grader's processes skip it.
if "jsonschema" not in _sys.modules:
    _sys.modules.setdefault("rfc3987_syntax", None)

from .grade import grade, grade_submission  # noqa: E402
from .parts import Part, parameters, part, reference_calls  # noqa: E402
from .release import release, write_variant  # noqa: E402
from .results import STATUSES, SubmissionResult  # noqa: E402
from .variant import student_parameters, variant  # noqa: E402

# (nbformat and nbclient are imported inside the functions that need them, so that a student's kernel that
# imports ``part`` stays light)

__all__ = ["part", "parameters", "reference_calls", "Part", "release", "write_variant", "variant", "student_parameters", "grade",
           "grade_submission", "SubmissionResult", "STATUSES"]
