"""The ``kinbook`` console script: thin wrappers over library functions.

Each command takes its defaults from the library function it wraps, so behaviour is defined once and the library
is usable without the CLI.

Every argument is validated before any work (finite or positive numbers, paths that exist, student ids that are
safe file names): a bad one gets one line, ``kinbook <command>: error: …``, and exit status 2; so does any
:class:`~kinbook.errors.KinbookError`. No traceback is shown unless ``--debug`` is given (an unexpected error, a
bug, exits with status 1 and says so).
"""

from __future__ import annotations

import argparse
import inspect
import json
import os
import re
import sys
import time

import numpy as np

from . import examples
from .errors import KinbookError
from .files import load

__all__ = ["main", "build_parser", "student_id"]



class _UsageError(Exception):
    """A bad command line: reported in one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # a value that starts with '-' and a digit is a number, not an option: `-t -1e-3` (argparse before 3.13 took
        # only -1 and -0.5 for numbers); an expression starting with '-' is written `-t=-pi/4`
        self._negative_number_matcher = re.compile(r"^-\.?[0-9]")

    def error(self, message):
        raise _UsageError(f"{self.prog}: error: {message} (see {self.prog} --help)")


# ----------------------------------------------------------------------------------------- argument types
def _number(text, expected):
    """A number from the command line, read by the one reader of untrusted text (so ``-t pi/4`` works)."""
    from .core.reader import ExpressionError, read_number  # import time: loaded when the command runs

    try:
        return read_number(text, where="the argument")
    except ExpressionError:
        raise argparse.ArgumentTypeError(f"expected {expected}, got {text[:80]!r}") from None


def finite(text):
    """A finite number (argparse type): ``2.5``, ``pi/4``."""
    return _number(text, "a finite number")


def positive(text):
    """A positive finite number (argparse type)."""
    value = _number(text, "a positive finite number")
    if value <= 0:
        raise argparse.ArgumentTypeError(f"expected a positive finite number, got {text!r}")
    return value


def count(text):
    """A whole number from 1 to 1024 (argparse type)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number from 1 to 1024, got {text!r}") from None
    if not 1 <= value <= 1024:
        raise argparse.ArgumentTypeError(f"expected a whole number from 1 to 1024, got {value}")
    return value


def student_id(text):
    """A student id by the one rule (:func:`kinbook.classroom.ids.check_id`): Unicode letters and digits, NFC."""
    from .classroom.ids import check_id  # import time: loaded when the command runs

    try:
        return check_id(text)
    except KinbookError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def exercise_name(text):
    """An exercise's name: the source notebook's file name without ``.ipynb`` (the student-id rule: one safe file
    name)."""
    from .classroom.ids import check_id  # import time: loaded when the command runs

    try:
        return check_id(text, what="exercise name")
    except KinbookError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _checked(text, check):
    """``text`` when ``check(text)`` accepts it; its ValueError or KinbookError as argparse's error."""
    try:
        check(text)
    except (ValueError, KinbookError) as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def id_pattern(text):
    """A ready pattern's name or a regular expression with a student or lms group (argparse type)."""
    from .classroom.naming import compile_pattern  # import time: loaded when the command runs

    return _checked(text, compile_pattern)


def existing_file(text):
    """The path of an existing file (argparse type)."""
    if not text or "\0" in text:
        raise argparse.ArgumentTypeError(f"not a file name: {text!r}")
    if not os.path.isfile(text):
        raise argparse.ArgumentTypeError(f"no such file: {text!r}" if not os.path.exists(text)
                                         else f"not a file: {text!r}")
    return text


def existing_path(text):
    """The path of an existing file or directory (argparse type)."""
    if not text or "\0" in text:
        raise argparse.ArgumentTypeError(f"not a file name: {text!r}")
    if not os.path.exists(text):
        raise argparse.ArgumentTypeError(f"no such file or directory: {text!r}")
    return text


def output_dir(text):
    """A directory to write into: missing (it is created) or an existing directory."""
    if not text or "\0" in text:
        raise argparse.ArgumentTypeError(f"not a directory name: {text!r}")
    if os.path.exists(text) and not os.path.isdir(text):
        raise argparse.ArgumentTypeError(f"exists and is not a directory: {text!r}")
    return text


def mechanism_arg(text):
    """A shipped example's name or the path of a mechanism file."""
    if text in examples.names():
        return text
    try:
        return existing_file(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(
            f"{text!r} is neither a mechanism file nor a shipped example ({', '.join(examples.names())})") from None


def _mechanism(name):
    return examples.load(name) if name in examples.names() else load(name)


def _cmd_table(args):
    mech = _mechanism(args.mechanism)
    print(mech)
    print(mech.constraint_table())


def _cmd_solve(args):
    mech = _mechanism(args.mechanism)
    q = mech.solve_position(args.t)
    qd = mech.solve_velocity(q, args.t)
    qdd = mech.solve_acceleration(q, qd, args.t)
    print(f"{'coordinate':>10} {'q':>14} {'q̇':>14} {'q̈':>14}")
    for name, a, b, c in zip(mech.coordinate_names(), q, qd, qdd):
        extra = f"   ({np.degrees(a):.2f}°)" if name.startswith("phi") else ""
        print(f"{name:>10} {a:14.6g} {b:14.6g} {c:14.6g}{extra}")


def _cmd_examples(args):
    for name in examples.names():
        print(f"{name:20} {examples.load(name).title}")


def _default(fn, name):
    """A library function's default for ``name``: the CLI defines no behaviour of its own."""
    return inspect.signature(fn).parameters[name].default


def _cmd_release(args):
    from .classroom import release  # import time: loaded when the command runs

    for path in release(args.source, args.output):
        print(path)


def _cmd_variant(args):
    from .classroom import write_variant  # import time: loaded when the command runs

    if args.student:
        print(write_variant(args.source, args.student, args.output))
        return
    from .classroom.release import write_variants  # import time: loaded when the command runs
    from .classroom.roster import read_roster  # import time: loaded when the command runs

    roster = read_roster(args.roster, args.roster_id)
    t0 = time.perf_counter()
    written = write_variants(args.source, [s.student for s in roster], args.output)
    print(f"wrote {len(written)} variant(s) into {os.path.join(args.output, '')} in {time.perf_counter() - t0:.1f} s")


# ---------------------------------------------------------------------------------------------- the course
def _cmd_validate(args):
    from .classroom.roster import read_roster  # import time: loaded when the command runs
    from .classroom.validate import validate  # import time: loaded when the command runs

    if args.source is None and not args.try_its:
        raise SystemExit("kinbook validate: give a SOURCE notebook, or --mutations --try-its")
    students = [s.student for s in read_roster(args.roster, args.roster_id)] if args.roster and args.source else None
    if args.mutations:
        return _mutations(args, students)
    checks = validate(args.source, students=students, timeout=args.timeout, memory=args.memory,
                      isolation=not args.no_isolation, progress=print)
    print(f"valid: {len(checks)} notebook(s) graded as expected")


def _mutations(args, students):
    """``kinbook validate --mutations``: the mutation tables, exit status 1 on a blind spot or a failed test."""
    from .grading.mutant_names import format_table  # import time: loaded when the command runs

    tallies, failures = [], []
    if args.source is not None:
        from .classroom.validate.mutations import mutation_tallies  # import time: loaded when the command runs

        found, failures = mutation_tallies(args.source, students=students, variants=args.variants, limit=args.limit)
        tallies += found
    if args.try_its:
        # import time: loaded when the command runs
        from .book.tryits.mutations import mutation_tallies as tryit_tallies

        tallies += tryit_tallies(None if args.try_its == ["all"] else args.try_its, variants=args.variants,
                                 limit=args.limit)
    print(format_table(tallies))
    for f in failures:
        print(f"FAIL {f}")
    blind = sum(t.blind for t in tallies)
    if blind or failures:
        print(f"not valid: {blind} blind spot(s), {len(failures)} failed question test(s)")
        return 1
    print("valid: no mutant passes")
    return 0


def _cmd_override(args):
    from .classroom.override import override  # import time: loaded when the command runs

    print(override(args.gradebook, args.student, args.exercise, args.part, args.score, args.why, remove=args.remove))


def _cmd_due(args):
    from .classroom.override import due  # import time: loaded when the command runs

    print(due(args.gradebook, args.exercise, args.when, penalty=args.penalty, cap=args.cap, policy=args.policy))


def _cmd_extend(args):
    from .classroom.override import extend  # import time: loaded when the command runs

    print(extend(args.gradebook, args.student, args.exercise, args.when, args.why, remove=args.remove))


def _cmd_export(args):
    from .classroom.export import export  # import time: loaded when the command runs
    from .classroom.roster import read_roster  # import time: loaded when the command runs

    roster = read_roster(args.roster, args.roster_id) if args.roster else None
    headers = dict(h.split("=", 1) for h in args.header)
    path, left = export(args.gradebook, args.output, args.format, exercises=args.exercise or None,
                        decimals=args.decimals, missing=args.missing, headers=headers, roster=roster,
                        scale=args.scale)
    print(f"wrote {path}")
    if left:
        print(f"not in the file: {len(left)} student(s) graded but not on the roster: {', '.join(left[:20])}"
              + (" …" if len(left) > 20 else ""))


def _cmd_report(args):
    from .classroom.report import report  # import time: loaded when the command runs
    from .classroom.roster import read_roster  # import time: loaded when the command runs

    roster = read_roster(args.roster, args.roster_id) if args.roster else None
    written = report(args.gradebook, args.output, args.format, roster=roster)
    print(f"wrote {len(written)} file(s) into {os.path.dirname(str(written[-1])) if written else args.output}/")


def _cmd_feedback(args):
    from .classroom.feedback import feedback  # import time: loaded when the command runs

    if args.lms:
        written, left = feedback(args.gradebook, args.out, lms=args.lms)
        for path in written:
            print(f"wrote {path} (upload it in {args.lms.capitalize()}: "
                  + ("Assignment → Re-Upload Submissions)" if args.lms == "canvas" else
                     "View all submissions → Grading action → Upload multiple feedback files in a zip)"))
        if left:
            print(f"not in the zips ({len(left)}): " + "; ".join(left[:20]) + (" …" if len(left) > 20 else ""))
        return
    written = feedback(args.gradebook, args.out)
    print(f"wrote {len(written)} page(s) into {os.path.join(args.out, '')} (one folder per student)")


def header_arg(text):
    """EXERCISE=COLUMN HEADER (argparse type)."""
    if "=" not in text or not text.split("=", 1)[0] or not text.split("=", 1)[1]:
        raise argparse.ArgumentTypeError(f"expected EXERCISE=HEADER, got {text!r}")
    return text


def score_arg(text):
    """A score: a finite number ≥ 0 (argparse type)."""
    value = _number(text, "a number ≥ 0")
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected a number ≥ 0, got {text!r}")
    return value


def percent(text):
    """A percentage from 0 to 100 (argparse type)."""
    value = _number(text, "a percentage from 0 to 100")
    if not 0 <= value <= 100:
        raise argparse.ArgumentTypeError(f"expected a percentage from 0 to 100, got {text!r}")
    return value


def when_arg(text):
    """A date and time with its zone (argparse type)."""
    from .classroom.scores import parse_due  # import time: loaded when the command runs

    return _checked(text, parse_due)


def _course_parsers(sub):
    """The course's commands: validate, override, due, extend, export, report, feedback."""
    from .classroom.export import FORMATS as EXPORTS  # import time: loaded when the command runs
    from .classroom.report import FORMATS as REPORTS  # import time: loaded when the command runs
    from .classroom.validate import validate  # import time: loaded when the command runs

    def gradebook(p):
        p.add_argument("-g", "--gradebook", type=output_dir, default="graded",
                       help="the grading output directory, holding gradebook.sqlite (default: %(default)s)")

    def roster(p):
        p.add_argument("--roster", type=existing_file, help="the roster (default: the one stored by kinbook grade)")
        p.add_argument("--roster-id", metavar="COLUMN", help="the roster's column holding the kinbook id")

    p = sub.add_parser("validate", help="grade a source's own solution (and variants) and its blank release")
    p.add_argument("source", type=existing_file, nargs="?", help="instructor source notebook")
    p.add_argument("--mutations", action="store_true",
                   help="grade every mutant of every part's reference (the mistakes students make) instead: a table "
                   "per part, exit status 1 when one passes (a blind spot)")
    p.add_argument("--try-its", nargs="+", metavar="ID",
                   help="with --mutations: the notebooks' try-its (ids such as 13-1/try-2, or all)")
    p.add_argument("--variants", type=int, default=2,
                   help="with --mutations: variants tried besides the source's data (default: %(default)s)")
    p.add_argument("--limit", type=int, default=60,
                   help="with --mutations: mutants per part and data at most, every code kept (default: %(default)s)")
    roster(p)
    p.add_argument("--timeout", type=positive, default=_default(validate, "timeout"),
                   help="CPU seconds per notebook's kernel; one that waits instead of computing is "
                   "stopped at 4 times that plus a minute of wall-clock time (default: %(default)s)")
    p.add_argument("--memory", type=positive, default=_default(validate, "memory"),
                   help="megabytes a notebook may allocate (default: %(default)s)")
    p.add_argument("--no-isolation", action="store_true", help="run without the bubblewrap sandbox (audit hook only)")
    p.set_defaults(func=_cmd_validate)
    p = sub.add_parser("override", help="set a part's score by hand, with the reason (kept across regrades)")
    p.add_argument("student", type=student_id)
    p.add_argument("exercise", type=exercise_name, help="the exercise (the source notebook's name without .ipynb)")
    p.add_argument("part")
    p.add_argument("score", type=score_arg, nargs="?", help="the part's score (omit with --remove)")
    p.add_argument("--why", default="", help="the reason, shown to the student on their feedback page (required)")
    p.add_argument("--remove", action="store_true", help="remove the override: the graded score counts again")
    gradebook(p)
    p.set_defaults(func=_cmd_override)
    p = sub.add_parser("due", help="set an exercise's due date, late penalty and attempt policy")
    p.add_argument("exercise", type=exercise_name, help="the exercise (the source notebook's name without .ipynb)")
    p.add_argument("when", type=when_arg, help="due date and time with its zone: 2026-03-01T23:59+01:00")
    p.add_argument("--penalty", type=percent, help="percent of the points taken per started day late")
    p.add_argument("--cap", type=percent, help="at most this percent is taken (default 100)")
    p.add_argument("--policy", choices=("latest", "best"), help="which attempt counts")
    gradebook(p)
    p.set_defaults(func=_cmd_due)
    p = sub.add_parser("extend", help="give one student their own due date for an exercise")
    p.add_argument("student", type=student_id)
    p.add_argument("exercise", type=exercise_name, help="the exercise (the source notebook's name without .ipynb)")
    p.add_argument("when", type=when_arg, nargs="?",
                   help="their due date, with its zone (omit with --remove; 'none' is refused: use --remove)")
    p.add_argument("--why", default="", help="the reason, for the record")
    p.add_argument("--remove", action="store_true", help="take the extension back: the exercise's due date applies")
    gradebook(p)
    p.set_defaults(func=_cmd_extend)
    p = sub.add_parser("export", help="write the scores as a file Canvas or Moodle imports, or as CSV")
    p.add_argument("--format", choices=EXPORTS, default="csv", help="canvas, moodle or csv (default: %(default)s)")
    p.add_argument("-o", "--output", required=True, help="the file to write")
    gradebook(p)
    roster(p)
    p.add_argument("--exercise", action="append", type=exercise_name, help="an exercise to export (repeat; default all)")
    p.add_argument("--header", action="append", default=[], type=header_arg,
                   help="EXERCISE=COLUMN: the LMS's column for an exercise, Canvas 'Exercise 1 (4242)' (repeat)")
    p.add_argument("--decimals", type=int, choices=range(7), default=2, help="decimals of the scores (default 2)")
    p.add_argument("--missing", choices=("zero", "blank"), default="zero",
                   help="a roster student with no submission gets 0 (default) or an empty cell")
    p.add_argument("--scale", action="store_true", help="Canvas: where the roster's Points Possible differ from the "
                   "exercise's points, write the scores scaled to Canvas's points (without it, the export stops)")
    p.set_defaults(func=_cmd_export)
    p = sub.add_parser("report", help="the class report: scores, parts, most common mistakes, copying signals")
    gradebook(p)
    roster(p)
    p.add_argument("-o", "--output", type=output_dir, help="directory (default: GRADEBOOK/report)")
    p.add_argument("--format", choices=REPORTS, default="html", help="html pages or csv tables (default: %(default)s)")
    p.set_defaults(func=_cmd_report)
    p = sub.add_parser("feedback", help="write every student's feedback pages, one folder per student")
    gradebook(p)
    p.add_argument("--out", type=output_dir, required=True, help="directory: OUT/<student>/<exercise>.html")
    p.add_argument("--lms", choices=("canvas", "moodle"), help="instead, one zip per exercise for the LMS's bulk "
                   "feedback upload: OUT/<exercise>-canvas.zip (Re-Upload Submissions) or OUT/<exercise>-moodle.zip "
                   "(Upload multiple feedback files in a zip)")
    p.set_defaults(func=_cmd_feedback)


def _cmd_grade(args):
    from .classroom import grade  # import time: loaded when the command runs
    from .classroom.results import UNGRADED  # import time: loaded when the command runs

    def progress(item):
        if isinstance(item, str):
            print(item)
        else:
            score = "-" if item.status in UNGRADED else f"{item.score:g}"  # not graded: no score, not a 0
            print(f"{item.student:20} {item.status:16} {score}/{item.max_score:g}  ({item.seconds:.1f} s)"
                  + (f"  {item.message[:100]}" if item.status != "ok" else ""))

    results = grade(args.source, args.submissions, args.output, timeout=args.timeout, memory=args.memory,
                    jobs=args.jobs, force=args.force, generic=args.generic, reveal_hidden=args.reveal_hidden,
                    isolation=not args.no_isolation, progress=progress, **_course_options(args))
    out = args.output.rstrip("/") or "."
    print(f"graded {len(results)} submission(s); gradebook {out}/gradebook.sqlite (grades.csv, totals.csv; every "
          f"file and what became of it in collection.csv), feedback in {out}/feedback/")
    if results:  # the scores above are the grader's: say which instructor's decisions still stand on them
        from .classroom.gradebook import Gradebook  # import time: loaded when the command runs

        with Gradebook(args.output) as book:
            kept = book.overrides(results[0].exercise)
        kept = [f"{s} {p} = {score:g}" for r in results for (_, s), parts in kept.items() if s == r.student
                for p, (score, _) in sorted(parts.items())]
        if kept:
            print(f"overrides kept (the scores above are the grader's; export, report and feedback apply them): "
                  f"{', '.join(kept)}")


def _course_options(args):
    """grade's options for a course: the roster, how ids are read, the attempt policy, a changed source."""
    from .classroom.roster import read_roster  # import time: loaded when the command runs

    roster = read_roster(args.roster, args.roster_id) if args.roster else None
    return dict(regrade=args.regrade, policy=args.policy, id_pattern=args.id_pattern, roster=roster,
                file_times=args.file_times, released_from=args.released_from)


def _course_arguments(p):
    from .classroom.naming import PATTERNS  # import time: loaded when the command runs

    p.add_argument("--roster", type=existing_file, help="the course's roster: kinbook's roster.csv, or a Canvas or "
                   "Moodle export as downloaded (stored in the gradebook; see docs/instructors.md)")
    p.add_argument("--roster-id", metavar="COLUMN", help="the roster's column holding the kinbook id")
    p.add_argument("--id-pattern", metavar="REGEX", type=id_pattern, help="read student ids from the paths with this regular expression "
                   "(named groups student or lms, time, late, attempt, file), or a ready one: "
                   + ", ".join(PATTERNS))
    p.add_argument("--policy", choices=("latest", "best"), help="which of a student's attempts counts (default: the "
                   "exercise's stored policy, else latest; with latest only the latest file is graded)")
    p.add_argument("--file-times", action="store_true", help="a submission's time (for the late rule) from its "
                   "file's modification time when the LMS gives none (never from a date in a file's name) — only where the "
                   "download kept the times")
    p.add_argument("--regrade", action="store_true", help="the source changed since the gradebook's results were "
                   "graded: grade every submission again with it (without this, such a run stops)")
    p.add_argument("--released-from", metavar="SOURCE", action="append", default=[], type=existing_file,
                   help="an earlier version of the source that students' notebooks were released from (the "
                   "gradebook keeps those it graded with): each submission is checked against its own release and "
                   "graded under the current source")


# ------------------------------------------------------------------------------------- kinbook exercises
def _cmd_exercises_list(args):
    from . import exercises  # import time: loaded when the command runs

    for name in exercises.names():
        with exercises.path(name).open("rb") as f:
            title = next((c["source"] for c in json.load(f)["cells"] if c["cell_type"] == "markdown"), "")
        title = "".join(title).strip().splitlines()[0].lstrip("# ") if title else ""
        print(f"{name:36} {title}")


def _cmd_exercises_copy(args):
    from . import exercises  # import time: loaded when the command runs

    for name in args.names:  # every name and target checked before anything is copied
        target = os.path.join(args.directory, exercises.path(name).name)
        if os.path.lexists(target):
            raise KinbookError(f"{target!r} already exists: not overwritten (remove it, or copy into another "
                               "directory); nothing was copied")
    for name in args.names:
        print(exercises.copy(name, args.directory))


def _add_exercises(sub):
    p = sub.add_parser("exercises", help="list the shipped exercises, or copy them out to edit and release")
    cmds = p.add_subparsers(dest="action", metavar="{list,copy}", required=True, parser_class=_Parser)
    cmds.add_parser("list", help="the shipped exercises and their titles").set_defaults(func=_cmd_exercises_list)
    c = cmds.add_parser("copy", help="copy shipped exercises into a directory (never overwriting a file)")
    c.add_argument("names", nargs="+", metavar="NAME", help="an exercise's name or its prefix (ex01 ... ex12)")
    c.add_argument("directory", type=output_dir, metavar="DIR", help="where to copy them (created if missing)")
    c.set_defaults(func=_cmd_exercises_copy)


#: Modules of the `grading` extra: a command that needs one when it is missing says how to install it.
GRADING_EXTRA = {"nbformat", "nbclient", "jupyter_client", "ipykernel", "IPython"}


def build_parser():
    from . import __version__  # import time: loaded when the command runs

    parser = _Parser(prog="kinbook", description="Kinematics of mechanisms in body coordinates.")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")
    parser.add_argument("--version", action="version", version=f"kinbook {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    p = sub.add_parser("examples", help="list the shipped example mechanisms")
    p.set_defaults(func=_cmd_examples)
    p = sub.add_parser("table", help="print a mechanism's constraint table")
    p.add_argument("mechanism", type=mechanism_arg, help="a mechanism file or the name of a shipped example")
    p.set_defaults(func=_cmd_table)
    p = sub.add_parser("solve", help="solve position, velocity and acceleration at one instant")
    p.add_argument("mechanism", type=mechanism_arg, help="a mechanism file or the name of a shipped example")
    p.add_argument("-t", type=finite, default=0.0, help="time, a number or an expression such as pi/4 (default 0)")
    p.set_defaults(func=_cmd_solve)

    from .classroom import grade, release, write_variant  # import time: loaded when the command runs

    p = sub.add_parser("release", help="write the students' versions of exercise notebooks")
    p.add_argument("source", nargs="+", type=existing_file, help="instructor source notebooks")
    p.add_argument("-o", "--output", type=output_dir, default=_default(release, "outdir"),
                   help="output directory (default: %(default)s)")
    p.set_defaults(func=_cmd_release)
    p = sub.add_parser("variant", help="write students' own versions, with their own parameters")
    p.add_argument("source", type=existing_file, help="instructor source notebook")
    who = p.add_mutually_exclusive_group(required=True)
    who.add_argument("--student", type=student_id,
                     help="student identifier (as in the collected submissions): letters and digits of any script, . _ @ + -")
    who.add_argument("--roster", type=existing_file, help="every student of a roster, in one run")
    p.add_argument("--roster-id", metavar="COLUMN", help="the roster's column holding the kinbook id")
    p.add_argument("-o", "--output", type=output_dir, default=_default(write_variant, "outdir"),
                   help="output directory (default: %(default)s)")
    p.set_defaults(func=_cmd_variant)
    p = sub.add_parser("grade", help="grade submitted notebooks in sandboxes and write the gradebook")
    p.add_argument("source", type=existing_file, help="instructor source notebook")
    p.add_argument("submissions", nargs="+", type=existing_path, help="submitted notebooks or directories of them")
    p.add_argument("-o", "--output", type=output_dir, default=_default(grade, "outdir"),
                   help="output directory (default: %(default)s)")
    p.add_argument("--timeout", type=positive, default=_default(grade, "timeout"),
                   help="CPU seconds per notebook's kernel; one that waits instead of computing is "
                   "stopped at 4 times that plus a minute of wall-clock time (default: %(default)s)")
    p.add_argument("--memory", type=positive, default=_default(grade, "memory"),
                   help="megabytes a notebook may allocate (default: %(default)s)")
    p.add_argument("--jobs", type=count, default=_default(grade, "jobs"),
                   help="notebooks graded in parallel, 1 to 1024 (default: %(default)s)")
    p.add_argument("--force", action="store_true", help="grade again submissions already in the gradebook")
    p.add_argument("--generic", action="store_true",
                   help="students got the generic release (default parameters), not per-student variants")
    p.add_argument("--reveal-hidden", action="store_true",
                   help="give the checkers' full messages for hidden checks too (they may quote the expected value)")
    p.add_argument("--no-isolation", action="store_true",
                   help="grade without the bubblewrap sandbox (audit hook only; recorded as 'isolation: none')")
    _course_arguments(p)
    p.set_defaults(func=_cmd_grade)
    _add_exercises(sub)
    _course_parsers(sub)
    return parser


def main(argv=None):
    """Entry point of the ``kinbook`` console script. Returns the exit status: 0, 2 for a bad command line or
    input (one line on stderr), 1 for an unexpected error (a bug: the traceback with ``--debug``)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    debug = "--debug" in argv
    argv = [a for a in argv if a != "--debug"]  # accepted anywhere on the line
    try:
        args = build_parser().parse_args(argv)
        from .core.atomic import protect  # import time: loaded when the command runs

        with protect(*_inputs(args)):  # no file a command writes may be one it reads
            status = args.func(args)
    except _UsageError as exc:
        print(exc, file=sys.stderr)
        return 2
    except SystemExit as exc:  # --help, --version
        return exc.code if isinstance(exc.code, int) else 0
    except KeyboardInterrupt:
        print("kinbook: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # `kinbook exercises list | head`: the reader left; say nothing, as `ls` would
        _silence_stdout()
        return 128 + 13  # the status a shell gives a command SIGPIPE stopped
    except (KinbookError, OSError, UnicodeError) as exc:
        if debug:
            raise
        print(f"kinbook: error: {_one_line(exc)}", file=sys.stderr)
        return 2
    except Exception as exc:  # a bug: say so in one line, the traceback with --debug
        if debug:
            raise
        missing = exc.name if isinstance(exc, ModuleNotFoundError) else None
        if missing and missing.split(".")[0] in GRADING_EXTRA:  # not a bug: an extra not installed
            command = argv[0] if argv else ""
            print(f"kinbook: error: `kinbook {command}` needs {missing}, which comes with the grading extra: "
                  "pip install 'kinbook[grading]'", file=sys.stderr)
            return 2
        print(f"kinbook: internal error: {type(exc).__name__}: {_one_line(exc)} (run with --debug for the "
              "traceback, and please report it)", file=sys.stderr)
        return 1
    return status if isinstance(status, int) else 0  # a command's own verdict (validate --mutations: 1)


def _inputs(args):
    """``(label, path)`` of the files a command reads (its source, roster, submissions, mechanism, the gradebook's
    database): :func:`kinbook.core.atomic.protect` refuses any output that is one of them."""
    out = []
    for name, label in (("source", "the source"), ("roster", "the roster"), ("submissions", "a submission"),
                        ("mechanism", "the mechanism file")):
        given = getattr(args, name, None)
        for p in ([given] if isinstance(given, str) else given or []):
            if isinstance(p, str) and os.path.isfile(p):
                out.append((label, p))
    book = getattr(args, "gradebook", None) or (args.output if getattr(args, "command", "") == "grade" else None)
    if book:
        out += [("the gradebook", os.path.join(book, f"gradebook.sqlite{x}")) for x in ("", "-wal", "-shm")]
    return out


def _silence_stdout():
    """Point stdout at /dev/null so the interpreter's final flush does not fail a second time (the recipe in
    the ``signal`` module's documentation)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def _one_line(exc):
    text = " ".join(str(exc).split())
    return text if len(text) <= 2000 else text[:1999] + "…"


if __name__ == "__main__":
    sys.exit(main())
