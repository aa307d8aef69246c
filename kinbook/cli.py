"""The ``kinbook`` console script: thin wrappers over library functions.

Each command takes its defaults from the library function it wraps, so behaviour is defined once and the library
is usable without the CLI.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from . import examples
from .errors import KinbookError
from .io import load

__all__ = ["main"]


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
    import inspect

    return inspect.signature(fn).parameters[name].default


def _cmd_release(args):
    from .classroom import release

    for path in release(args.source, args.output):
        print(path)


def _cmd_variant(args):
    from .classroom import write_variant

    print(write_variant(args.source, args.student, args.output))


def _cmd_grade(args):
    from .classroom import grade

    def progress(item):
        if isinstance(item, str):
            print(item)
        else:
            print(f"{item.student:20} {item.status:16} {item.score:g}/{item.max_score:g}  ({item.seconds:.1f} s)"
                  + (f"  {item.message[:100]}" if item.status != "ok" else ""))

    results = grade(args.source, args.submissions, args.output, timeout=args.timeout, memory=args.memory,
                    jobs=args.jobs, force=args.force, generic=args.generic, reveal_hidden=args.reveal_hidden,
                    isolation=not args.no_isolation, progress=progress)
    print(f"graded {len(results)} submission(s); gradebook in {args.output}/grades.csv, feedback in "
          f"{args.output}/feedback/")


def build_parser():
    parser = argparse.ArgumentParser(prog="kinbook", description="Kinematics of mechanisms in body coordinates.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("examples", help="list the shipped example mechanisms")
    p.set_defaults(func=_cmd_examples)
    p = sub.add_parser("table", help="print a mechanism's constraint table")
    p.add_argument("mechanism", help="a mechanism file or the name of a shipped example")
    p.set_defaults(func=_cmd_table)
    p = sub.add_parser("solve", help="solve position, velocity and acceleration at one instant")
    p.add_argument("mechanism", help="a mechanism file or the name of a shipped example")
    p.add_argument("-t", type=float, default=0.0, help="time (default 0)")
    p.set_defaults(func=_cmd_solve)

    from .classroom import grade, release, write_variant

    p = sub.add_parser("release", help="write the students' versions of exercise notebooks")
    p.add_argument("source", nargs="+", help="instructor source notebooks")
    p.add_argument("-o", "--output", default=_default(release, "outdir"), help="output directory (default: %(default)s)")
    p.set_defaults(func=_cmd_release)
    p = sub.add_parser("variant", help="write one student's version, with their own parameters")
    p.add_argument("source", help="instructor source notebook")
    p.add_argument("--student", required=True, help="student identifier (as in the collected submissions)")
    p.add_argument("-o", "--output", default=_default(write_variant, "outdir"), help="output directory (default: %(default)s)")
    p.set_defaults(func=_cmd_variant)
    p = sub.add_parser("grade", help="grade submitted notebooks in sandboxes and write the gradebook")
    p.add_argument("source", help="instructor source notebook")
    p.add_argument("submissions", nargs="+", help="submitted notebooks or directories of them")
    p.add_argument("-o", "--output", default=_default(grade, "outdir"), help="output directory (default: %(default)s)")
    p.add_argument("--timeout", type=float, default=_default(grade, "timeout"),
                   help="wall-clock seconds per notebook (default: %(default)s)")
    p.add_argument("--memory", type=float, default=_default(grade, "memory"),
                   help="megabytes a notebook may allocate (default: %(default)s)")
    p.add_argument("--jobs", type=int, default=_default(grade, "jobs"), help="notebooks graded in parallel (default: %(default)s)")
    p.add_argument("--force", action="store_true", help="grade again submissions already in the gradebook")
    p.add_argument("--generic", action="store_true",
                   help="students got the generic release (default parameters), not per-student variants")
    p.add_argument("--reveal-hidden", action="store_true",
                   help="give the checkers' full messages for hidden checks too (they may quote the expected value)")
    p.add_argument("--no-isolation", action="store_true",
                   help="grade without the bubblewrap sandbox (audit hook only; recorded as 'isolation: none')")
    p.set_defaults(func=_cmd_grade)
    return parser


def main(argv=None):
    """Entry point of the ``kinbook`` console script. Returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        args.func(args)
    except KinbookError as exc:
        print(f"kinbook: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
