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
