"""docs/mechanism-files.md quotes what each mistake in a file gets: the quotes must be what kinbook says; its two
tables of constraint types are the registry (every type a file may name, its class and its keys)."""

import inspect
import re
from pathlib import Path

import pytest

import kinbook
from kinbook import MechanismFileError

DOC = (Path(__file__).resolve().parents[2] / "docs" / "mechanism-files.md").read_text(encoding="utf-8")
BASE = kinbook.examples.path("ch13_example1").read_text(encoding="utf-8")
Q0 = 'q0 = [-0.7, 0.7, "3*pi/4"]'
F = 'f = "3*pi/4 + 100*t"'

ROWS = [
    (Q0, 'q0 = [-0.7, 0.7, "9**9**9**9"]',
     "q0 of body 'crank' (phi): the exponent 3.8742e+08 is too large (at most 100 in size) at column 4 in '9**9**9**9'"),
    (Q0, "q0 = [-0.7, 0.7, nan]", "q0 of body 'crank' (phi): expected a finite number, got nan"),
    (Q0, "q0 = [-0.7, 0.7]", "bodies[1] ('crank'): body 'crank': q0 must have 3 values (x, y, phi), got 2"),
    (Q0, 'q0 = [-0.7, 0.7, "3pi/4"]', "write products with * (2*t, not 2t) at column 1 in '3pi/4'"),
    (F, 'f = "1/0"', "constraints[5] (type 'driver'): driver on body 'crank', f: division by zero at column 1 in '1/0'"),
    (F, 'f = "I*t"', "f: unknown name 'I' (complex numbers are not accepted: kinematic quantities are real)"),
    (F, 'f = "t > 1"', "f: comparisons (<, >, ==) are not expressions of a number at column 1 in 't > 1'"),
    (F, 'f = "exit()"', "f: unknown function 'exit' at column 1 in 'exit()'"),
    (F, 'f = "floor(t)"', "f: unknown function 'floor' (step functions are not accepted"),
    (F, 'f = "sign(t - 1)"', "f: the function of time 'sign(t - 1)' uses sign, which jumps"),
    (F, 'f = "w*t"', "f: unknown name 'w' at column 1 in 'w*t'"),
    ("points = { OA = [-1, 0], A = [1, 0] }", "points = { OA = [0, 0], A = [0, 0] }",
     "body 'crank' is a link of zero length: its revolute joints '1', '3' (to bodies 'coupler', 'ground') are all "
     "at its point (0, 0)"),
    ('point = "OA"', 'point = ["OA"]', "a point on body 'ground' must be a point name or a pair (ξ, η), got ['OA']"),
    ('j = "crank"', "j = 2", "`j` must be a string (a body name), got int 2"),
    ('point = "OA"', 'pont = "OA"', "unknown key 'pont' (accepted keys: i, j, point, point_i, point_j, name)"),
]


@pytest.mark.parametrize("old, new, quote", ROWS, ids=[r[1] for r in ROWS])
def test_the_documented_message_is_the_real_one(old, new, quote):
    assert old in BASE and quote in DOC
    with pytest.raises(MechanismFileError) as info:
        kinbook.loads(BASE.replace(old, new, 1), source="fourbar.toml")
    assert str(info.value).startswith("fourbar.toml: ") and quote in str(info.value)


# ------------------------------------------------------------------------------------------ the type tables
def type_tables():
    """docs/mechanism-files.md's two tables of constraint types (planar, then spatial): {type: (class name, keys
    it names, rows or None)}."""
    tables, rows = [], None
    for line in DOC.splitlines():
        if line.startswith("| `type` |"):
            header = [c.strip().split()[0].strip("`") for c in line.strip("|").split("|")]
            rows = {}
            tables.append(rows)
            continue
        if rows is None or not line.startswith("|"):
            rows = None
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        if cells[0].startswith("`"):
            entry = dict(zip(header, cells))
            n = entry.get("rows")
            keys = set(re.findall(r"`(\w+)`", re.sub(r"\([^)]*\)", "", entry["keys"])))  # not the remarks' words
            rows[entry["type"].strip("`")] = (entry["class"].strip("`"), keys, int(n) if n else None)
    return tables


@pytest.mark.parametrize("chapter", ["planar", "spatial"])
def test_the_type_tables_are_the_registry(chapter):
    from kinbook import planar, spatial  # noqa: F401  (registering their types)
    from kinbook.core.registry import constraint_types

    planar_table, spatial_table = type_tables()
    table = {"planar": planar_table, "spatial": spatial_table}[chapter]
    types = {name: cls for name, cls in constraint_types(chapter).items()
             if cls.in_files and cls.__module__.startswith("kinbook.")}  # not a test's own types
    assert sorted(table) == sorted(types)
    for name, (class_name, keys, n_eq) in table.items():
        cls = types[name]
        assert class_name == cls.__name__, name
        accepted = set(inspect.signature(cls).parameters) - {"name"}
        implied = {k for alias in keys & set(cls.aliases) for k in cls.aliases[alias]}
        assert keys <= accepted and accepted - keys <= implied, (name, sorted(accepted - keys - implied))
        assert n_eq in (None, cls.n_eq), name
