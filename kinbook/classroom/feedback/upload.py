"""Feedback pages as the LMS takes them back: one zip per exercise, named the way its bulk upload reads names.

``canvas``
    Canvas's "Re-Upload Submissions" (Assignment#generate_comments_from_files, app/models/assignment.rb): each file's
    base name is split at ``_``; the first two parts made only of digits are the student's Canvas user id and the id
    of an attachment of *their submission* (the second number of Canvas's own download name,
    lib/content_zipper.rb); a file whose attachment is not one of the submission's is "quietly ignored". So each page
    is named ``<sortable name, letters only>_<user id>_<attachment id>_<exercise>-feedback.html``, both ids read from
    the name of the file the student handed in (a student with nothing handed in has no submission to comment on).
``moodle``
    Moodle's "Upload multiple feedback files in a zip" (assignfeedback_file_zip_importer::is_valid_filename_for_import,
    mod/assign/feedback/file/importziplib.php): a path part split at ``_`` into at most five pieces must read
    ``<full name>_<participant id>_assignfeedback_file_``; the participant id is the worksheet's Identifier, the
    number Moodle's download names each folder with. So each page is ``<full name>_<participant id>_assignfeedback_file_/
    <exercise>-feedback.html`` (underscores in a name become spaces, so the id stays the second piece).

Students who cannot be named so (no LMS id, nothing handed in) are returned, for the instructor to see.
"""

from __future__ import annotations

import io
import os
import re
import zipfile

from ..files import PUBLIC_FILE, atomic_write

__all__ = ["LAYOUTS", "upload_zip"]

LAYOUTS = ("canvas", "moodle")
_CANVAS_NAME = re.compile(r"^(?:[^_]+)_(?:(?:late|LATE)_)?(?P<user>\d+)_(?P<attachment>\d+)_")
_MOODLE_DIR = re.compile(r"_(?P<participant>\d+)_assignsubmission_[a-z]+_")


def _canvas_name(student, display, path, exercise):
    m = _CANVAS_NAME.match(os.path.basename(path))
    if not m:
        return None
    letters = re.sub(r"[\W\d_]+", "", display.casefold()) or "student"
    return f"{letters}_{m['user']}_{m['attachment']}_{exercise}-feedback.html"


def _moodle_name(student, display, lms_id, path, exercise):
    m = _MOODLE_DIR.search(path)
    participant = lms_id if lms_id.isdigit() else (m["participant"] if m else "")
    if not participant:
        return None
    name = re.sub(r"[_/\\\x00-\x1f]+", " ", display).strip() or student
    return f"{name}_{participant}_assignfeedback_file_/{exercise}-feedback.html"


def upload_zip(book, out, layout, pages):
    """Write ``out/<exercise>-<layout>.zip`` for each exercise from ``pages`` ({(exercise, student): html}).

    Returns
    -------
    (list of Path, list of str)
        The zips written, and "exercise: student (why)" for each page left out.
    """
    roster = book.roster()
    people = {s.student: s for s in roster} if roster is not None else {}
    counting = {(e, s): p for e, s, p in book.db.execute("SELECT exercise, student, submission FROM submissions")}
    files = {e: book.files_of(e) for e in book.exercises()}
    by_exercise, left = {}, []
    for (exercise, student), html in sorted(pages.items()):
        who = people.get(student)
        display = who.display if who is not None else student
        paths = [counting[exercise, student]] if (exercise, student) in counting else []
        paths += [p for p, *_ in files.get(exercise, {}).get(student, [])]
        name = None
        for path in paths:
            if layout == "canvas":
                name = _canvas_name(student, display, path, exercise)
            else:
                name = _moodle_name(student, display, who.lms_id if who is not None else "", path, exercise)
            if name:
                break
        if name is None:
            left.append(f"{exercise}: {student} ({'nothing handed in' if not paths else 'no LMS id in the file name'})")
            continue
        by_exercise.setdefault(exercise, []).append((name, html))
    written = []
    for exercise, items in sorted(by_exercise.items()):
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
            for name, html in items:
                info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))  # no clock in the file
                info.compress_type = zipfile.ZIP_DEFLATED
                info.external_attr = (PUBLIC_FILE & 0xFFFF) << 16
                z.writestr(info, html.encode("utf-8"))
        written.append(atomic_write(os.path.join(out, f"{exercise}-{layout}.zip"), buf.getvalue(), mode=PUBLIC_FILE))
    return written, left
