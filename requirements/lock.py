"""The pinned environment of `make lab` / `make test` for every supported Python: requirements/constraints.txt.

    python requirements/lock.py           re-pin: resolve kinbook[lab,test] for each Python interval, preferring
                                          the current pins, and write one file with markers (`make lock`)
    python requirements/lock.py --check   the pins resolve kinbook[lab,test], from wheels only, on each interval's
                                          lowest Python and on Debian 12's 3.11.2, and pin every package
                                          installed (`make check-lock`, CI)

Run with uv (https://docs.astral.sh/uv/) and packaging importable: `make lock` / `make check-lock` make a small
venv with both (.venv-tools, pinned in requirements/tools.txt). Resolving for a Python needs no interpreter of
that version: `uv pip compile --python-version` evaluates markers and Requires-Python for it (pip's own
`--python-version` does not evaluate a requirement's markers for the target).

Why intervals: a package's newest release may need a newer Python than kinbook supports (numpy 2.3 needs 3.11,
soupsieve 3.0.2 needs 3.11.5 while Debian 12 ships 3.11.2). Each interval below is resolved for its *lowest*
version (Requires-Python is a lower bound, so what resolves there resolves for the whole interval); a package
pinned alike on neighbouring intervals gets one line, the others a line per run of intervals with a marker.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile

from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
LOCK = os.path.join(HERE, "constraints.txt")
#: Lowest version of each interval [this, next); the last one is open-ended.
BOUNDS = ("3.10", "3.11", "3.11.5", "3.12", "3.13", "3.14")
#: Versions the check resolves for besides the bounds: Debian 12's own Python.
ALSO_CHECKED = ("3.11.2",)
EXTRAS = ("lab", "test")
PLATFORM = "x86_64-manylinux_2_28"
HEADER = """\
# Pinned test and lab environment for kinbook (Linux x86_64), for every Python from 3.10 on: `make lab` and
# `make test` install kinbook[lab,test] with these as pip constraints, so that outputs stored in notebooks (sympy
# printing, numpy formatting) match on every machine. A package whose pin depends on the Python version has one
# line per range, with a marker. Regenerate with `make lock` (requirements/lock.py); `make check-lock` checks it.
"""


def _full(version):
    parts = version.split(".")
    return ".".join(parts + ["0"] * (3 - len(parts)))


def _environment(version):
    full = _full(version)
    return {"python_version": ".".join(full.split(".")[:2]), "python_full_version": full,
            "sys_platform": "linux", "platform_system": "Linux", "platform_machine": "x86_64",
            "os_name": "posix", "implementation_name": "cpython", "platform_python_implementation": "CPython"}


def read_pins(path=LOCK):
    """[(canonical name, version, marker or None, the line)] of a lock file."""
    pins = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            req = Requirement(line)
            (spec,) = req.specifier
            pins.append((canonicalize_name(req.name), spec.version, req.marker, line))
    return pins


def pins_for(version, pins):
    """{name: version} of the pins that apply on Python ``version``."""
    env = _environment(version)
    out = {}
    for name, v, marker, _line in pins:
        if marker is None or marker.evaluate(env):
            if name in out and out[name] != v:
                raise SystemExit(f"{LOCK}: two pins of {name} apply on Python {version}: {out[name]} and {v}")
            out[name] = v
    return out


def compile_for(version, constraints=None, preferences=None):
    """uv's resolution of kinbook[lab,test] on Python ``version`` (Linux x86_64, wheels only): {name: version}."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "resolved.txt")
        cmd = ["uv", "pip", "compile", os.path.join(ROOT, "pyproject.toml"), *[f"--extra={e}" for e in EXTRAS],
               "--python-version", version, "--python-platform", PLATFORM, "--only-binary", ":all:",
               "--no-header", "--no-annotate", "--quiet", "-o", out]
        if preferences:  # uv keeps the versions already in its output file when they still resolve
            with open(out, "w", encoding="utf-8") as f:
                f.writelines(f"{n}=={v}\n" for n, v in sorted(preferences.items()))
        if constraints:
            cfile = os.path.join(tmp, "constraints.txt")
            with open(cfile, "w", encoding="utf-8") as f:
                f.writelines(f"{n}=={v}\n" for n, v in sorted(constraints.items()))
            cmd += ["-c", cfile]
        res = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
        if res.returncode != 0:
            return None, res.stderr.strip()
        resolved = {}
        with open(out, encoding="utf-8") as f:
            for line in f:
                m = re.match(r"([A-Za-z0-9._-]+)==([^\s;]+)", line.strip())
                if m and canonicalize_name(m.group(1)) != "kinbook":
                    resolved[canonicalize_name(m.group(1))] = m.group(2)
        return resolved, ""


def _marker(lo, hi):
    parts = []
    if lo > 0:
        parts.append(f'python_full_version >= "{_full(BOUNDS[lo])}"')
    if hi < len(BOUNDS):
        parts.append(f'python_full_version < "{_full(BOUNDS[hi])}"')
    return " and ".join(parts)


def lock():
    old = read_pins() if os.path.exists(LOCK) else []
    per = []
    for version in BOUNDS:
        resolved, err = compile_for(version, preferences=pins_for(version, old))
        if resolved is None:
            raise SystemExit(f"kinbook[{','.join(EXTRAS)}] does not resolve on Python {version}:\n{err}")
        per.append(resolved)
        print(f"Python {version}: {len(resolved)} packages", file=sys.stderr)
    lines = []
    for name in sorted(set().union(*per)):
        runs, start = [], 0
        versions = [p.get(name) for p in per]
        for i in range(1, len(versions) + 1):
            if i == len(versions) or versions[i] != versions[start]:
                if versions[start] is not None:
                    runs.append((start, i, versions[start]))
                start = i
        for lo, hi, v in runs:
            marker = _marker(lo, hi)
            lines.append(f"{name}=={v}" + (f"; {marker}" if marker else ""))
    with open(LOCK, "w", encoding="utf-8") as f:
        f.write(HEADER + "".join(line + "\n" for line in lines))
    print(f"wrote {LOCK}: {len(lines)} lines", file=sys.stderr)


def check():
    pins = read_pins()
    failed = []
    for version in sorted(set(BOUNDS) | set(ALSO_CHECKED), key=lambda v: tuple(map(int, _full(v).split(".")))):
        pinned = pins_for(version, pins)
        resolved, err = compile_for(version, constraints=pinned)
        if resolved is None:
            failed.append(f"Python {version}: the pins do not resolve:\n{err}")
            continue
        loose = sorted(n for n in resolved if n not in pinned)
        if loose:
            failed.append(f"Python {version}: installed but not pinned: {', '.join(loose)}")
            continue
        print(f"Python {version}: kinbook[{','.join(EXTRAS)}] resolves with {len(resolved)} pinned packages")
    if failed:
        raise SystemExit("\n".join(failed) + "\n(re-pin with `make lock`)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="check the lock instead of writing it")
    args = parser.parse_args(argv)
    check() if args.check else lock()


if __name__ == "__main__":
    main()
