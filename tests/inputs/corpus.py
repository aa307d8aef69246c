"""The bad-input corpus: several hundred inputs a careless or hostile user can give kinbook, each with the exact
exception class it must get and words its message must contain (the thing concerned: the file and key, the
body, the argument, what was wrong).

Cases are built by :func:`cases` — deterministically: the random choices use ``np.random.default_rng(SEED)`` —
so the test process and the worker process (``worker.py``, which runs them under a watchdog) build the same
list and refer to a case by its id. A case's ``run`` is called in the worker; it either raises (``expect`` is
the exception's class name, which must come from ``kinbook.errors``), or returns a value that ``check``
accepts (``expect == "ok"``), or, for the command line, returns (exit status, stderr) (``expect == "cli"``:
status 2 and one line).

Payloads that would run code write the file ``CANARY`` in the worker's directory: the worker checks after
every case that it does not exist.
"""

from __future__ import annotations

import contextlib
import copy
import functools
import io
import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import sympy as sp

SEED = 20261123
CANARY = "kinbook-corpus-canary"


@dataclass
class Case:
    id: str
    group: str
    run: Callable[[], object]
    expect: str
    words: tuple = ()
    check: Callable[[object], bool] | None = None
    xfail: str | None = None
    timeout: float = 20.0
    extra: dict = field(default_factory=dict)


# ------------------------------------------------------------------------------------------------ payloads
CODE = [
    f"__import__('pathlib').Path('{CANARY}').write_text('x')",
    f"__import__('os').system('touch {CANARY}')",
    f"exec(\"open('{CANARY}', 'w').write('x')\")",
    f"eval(\"__import__('os').system('touch {CANARY}')\")",
    f"open('{CANARY}', 'w')",
    "().__class__.__base__.__subclasses__()",
    "[c for c in ().__class__.__bases__[0].__subclasses__()]",
    "lambda: __import__('os')",
    "__builtins__",
    "globals()",
    "getattr(t, 'real')",
    "t.__class__",
    "compile('1', 'x', 'eval')",
    "exit()",
    "quit()",
    "Symbol('x')",
    "sympify('1')",
    "S('1')",
    "Function('f')(t)",
    "ｅｘｉｔ()",  # full-width letters: Python folds them to exit (NFKC)
    f"breakpoint() or open('{CANARY}','w')",
    "import os",
    "os.system('ls')",
    "__import__",
    "t; import os",
]

HUGE = [
    "9**9**9**9",
    "factorial(10**8)",
    "10**10**10",
    "(t+1)**100000",
    "2**2**2**2**2**2",
    "exp(exp(exp(100)))",
    "10.0**200 * 10.0**200",
    "(" * 1000 + "1" + ")" * 1000,
    "-" * 5000 + "1",
    "1" * 5000,
    "t" * 1_000_000,
    "sin(" * 200 + "t" + ")" * 200,
    "+".join(f"1/{p}**85" for p in (1009, 1013, 1019, 1021, 1031, 1033, 1039, 1049, 1051, 1061, 1063, 1069, 1087,
                                     1091, 1093, 1097, 1103, 1109, 1117, 1123, 1129, 1151, 1153, 1163, 1171)),
    "sqrt(" * 12 + "2" + " - 1)" * 12,
    "log(" * 12 + "3" + ")" * 12,
    "1e400",
    "1/0",
]

HUGE_WORDS = {
    "9**9**9**9": "too large", "factorial(10**8)": "factorial", "10**10**10": "too large",
    "(t+1)**100000": "too large", "2**2**2**2**2**2": "too large", "exp(exp(exp(100)))": "too large",
    "10.0**200 * 10.0**200": "too large", "1e400": "not finite", "1/0": "division by zero",
}


def _short(text):
    return text if len(text) <= 30 else text[:27] + "..."


# ------------------------------------------------------------------------------------------------ helpers
def _raises(fn):
    """Run ``fn``; the corpus expects it to raise."""
    return fn()


def _cli(argv):
    """Run the console script's main in this process: (exit status, stderr)."""
    from kinbook.cli import main

    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        status = main(argv)
    return status, err.getvalue()


@functools.lru_cache(maxsize=None)
def _example_data(name):  # callers deep-copy before mutating
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10: the same parser as tomli
        import tomli as tomllib

    from kinbook import examples

    return tomllib.loads(examples.path(name).read_text(encoding="utf-8"))


PLANAR_ZOO = """
[mechanism]
name = "zoo"
[[bodies]]
name = "ground"
points = { O = [0, 0], P = [0, 0], Q = [1, 0], C = [2, 0] }
[[bodies]]
name = "gear1"
q0 = [0, 0, 0]
points = { O = [0, 0], M = [1, 0] }
[[bodies]]
name = "gear2"
q0 = [3, 0, 0.1]
points = { O = [0, 0], M = [1, 0] }
[[bodies]]
name = "rack"
q0 = [0, -1, 0]
points = { P = [0, 0], Q = [1, 0] }
[[bodies]]
name = "slider"
q0 = [2, 0, 0]
points = { P = [0, 0], A = [0.5, 0] }
[[constraints]]
type = "ground"
body = "ground"
q = [0, 0, 0]
[[constraints]]
type = "simple"
body = "gear1"
coordinate = "x"
value = 0
[[constraints]]
type = "gear"
i = "gear1"
j = "gear2"
k = "ground"
radius_i = 1
radius_j = "2"
phi0 = [0, 0.1, 0]
[[constraints]]
type = "rack-pinion"
i = "gear1"
j = "rack"
radius = 1
sliding = false
initial = { x_i = 0, phi_i = 0, x_j = 0 }
[[constraints]]
type = "translational"
i = "ground"
j = "slider"
axis = ["P", "Q"]
point_j = "P"
phi0 = 0
[[constraints]]
type = "revolute-revolute"
i = "gear2"
j = "slider"
point_i = "M"
point_j = "A"
length = 2.5
[[constraints]]
type = "revolute-translational"
i = "gear2"
j = "rack"
point_i = "O"
axis = ["P", "Q"]
[[constraints]]
type = "driver"
body = "gear1"
coordinate = "phi"
f = "t"
[[constraints]]
type = "relative-driver"
i = "gear1"
j = "gear2"
f = "0.1 + t/2"
[[constraints]]
type = "distance-driver"
i = "ground"
j = "slider"
axis = ["P", "Q"]
point_j = "P"
f = "2 + sin(t)"
"""

SPATIAL_ZOO = """
[mechanism]
kind = "spatial"
name = "spatial_zoo"
[[bodies]]
name = "ground"
q0 = [0, 0, 0, 1, 0, 0, 0]
points = { O = [0, 0, 0], P = [0, 0, 1] }
vectors = { x = [1, 0, 0], y = [0, 1, 0], z = [0, 0, 1] }
[[bodies]]
name = "a"
q0 = [1, 0, 0, 1, 0, 0, 0]
points = { O = [0, 0, 0], P = [1, 0, 0] }
vectors = { x = [1, 0, 0], y = [0, 1, 0], z = [0, 0, 1] }
[[bodies]]
name = "b"
q0 = [2, 0, 0, 1, 0, 0, 0]
points = { O = [0, 0, 0], P = [1, 0, 0] }
vectors = { x = [1, 0, 0], y = [0, 1, 0], z = [0, 0, 1] }
[[constraints]]
type = "ground"
body = "ground"
q = [0, 0, 0, 1, 0, 0, 0]
[[constraints]]
type = "normal-1"
i = "ground"
j = "a"
vector_i = "x"
vector_j = "y"
[[constraints]]
type = "normal-2"
i = "ground"
j = "a"
vector_i = "z"
point_i = "O"
point_j = "P"
[[constraints]]
type = "parallel-1"
i = "a"
j = "b"
vector_i = "z"
vector_j = "z"
[[constraints]]
type = "parallel-2"
i = "a"
j = "b"
vector_i = "x"
point_i = "O"
point_j = "O"
[[constraints]]
type = "spherical"
i = "a"
j = "b"
point_i = "P"
point_j = "O"
[[constraints]]
type = "universal"
i = "a"
j = "b"
point = "O"
vector_i = "y"
vector_j = "z"
[[constraints]]
type = "revolute"
i = "ground"
j = "a"
point = "O"
axis_i = "z"
axis_j = "z"
[[constraints]]
type = "cylindrical"
i = "ground"
j = "b"
point = "O"
axis_i = "x"
axis_j = "x"
[[constraints]]
type = "translational"
i = "ground"
j = "b"
point = "O"
axis_i = "x"
axis_j = "x"
perp_i = "y"
perp_j = "y"
[[constraints]]
type = "spherical-spherical"
i = "a"
j = "b"
point_i = "P"
point_j = "P"
length = 1
[[constraints]]
type = "revolute-driver"
i = "ground"
j = "a"
axis_i = "z"
ref_i = "x"
ref_j = "x"
f = "t"
[[constraints]]
type = "distance-driver"
i = "ground"
j = "b"
axis_i = "x"
point_i = "O"
point_j = "O"
f = "2 + t"
"""


@functools.lru_cache(maxsize=None)
def _zoo_data(text):  # callers deep-copy before mutating
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10: the same parser as tomli
        import tomli as tomllib

    return tomllib.loads(text)


def _build(data, source):
    from kinbook.files import build

    return build(data, source)


def _set(data, path, value):
    d = data
    for key in path[:-1]:
        d = d[key]
    if value is _DELETE:
        del d[path[-1]]
    else:
        d[path[-1]] = value


_DELETE = object()

# ------------------------------------------------------------------------------------------------ groups


def reader_cases():
    from kinbook.core.bounds import check_expression
    from kinbook.core.reader import read_expression, read_number

    t = sp.Symbol("t", real=True)
    out = []
    where = "corpus context"
    for k, text in enumerate(CODE):
        out.append(Case(f"reader-code-{k}", "code execution", lambda text=text: read_expression(
            text, symbols={"t": t}, where=where), "ExpressionError", (where,)))
        out.append(Case(f"number-code-{k}", "code execution", lambda text=text: read_number(text, where=where),
                        "ExpressionError", (where,)))
    for k, text in enumerate(HUGE):
        words = (where, HUGE_WORDS[text]) if text in HUGE_WORDS else (where,)
        out.append(Case(f"reader-huge-{k}-{_short(text)}", "hang", lambda text=text: read_expression(
            text, symbols={"t": t}, where=where), "ExpressionError", words, timeout=5))
        out.append(Case(f"number-huge-{k}-{_short(text)}", "hang", lambda text=text: read_number(
            text.replace("t", "2"), where=where), "ExpressionError", (where,), timeout=5))
    # seeded fuzz: a valid expression with one forbidden part spliced in at a random place
    rng = np.random.default_rng(SEED)
    atoms = ["t", "2", "pi", "sin(t)", "(t + 1)", "3.5", "E", "cos(2*t)", "sqrt(t**2 + 1)", "atan2(t, 1)"]
    ops = [" + ", " - ", " * ", " / ", "^"]
    bad = ["zz", "% 2", "[0]", "'s'", "== 1", ".real", "lambda x: x", "if t else 1", "**-", "@t", "__x__",
           "open(t)", "not t", "1j", "True", "x_", "$", "t,", ")", "(", "..", "floor(t)", "Heaviside(t)", ";"]
    for k in range(120):
        parts = [atoms[rng.integers(len(atoms))]]
        for _ in range(int(rng.integers(1, 6))):
            parts += [ops[rng.integers(len(ops))], atoms[rng.integers(len(atoms))]]
        pos = int(rng.integers(0, len(parts) + 1))
        b = bad[rng.integers(len(bad))]
        text = "".join(parts[:pos]) + (" " if pos else "") + b + " " + "".join(parts[pos:])
        out.append(Case(f"reader-fuzz-{k}", "syntax and names", lambda text=text, k=k: read_expression(
            text, symbols={"t": t}, where=f"fuzz {k}"), "ExpressionError", (f"fuzz {k}",)))
    for k, (value, word) in enumerate([
        (True, "expected a number, got True"), (None, "got None"), (math.nan, "finite"), (math.inf, "finite"),
        (-math.inf, "finite"), (1j, "complex"), (b"1", "bytes"), ([1.0], "list"), ({"a": 1}, "dict"),
        ({1}, "set"), (object(), "object"), ("", "empty"), ("   ", "empty"), ("t", "unknown name 't'"),
        ("pi*t", "unknown name 't'"), ("sqrt(-1)", "not a real number"), ("asin(2)", "not a real number"),
        ("log(0)", "no finite real value"), (np.bool_(True), "bool"), (np.float64("nan"), "finite"), (10**400, "too large"),
        ("1e-400 * 1e400", "not finite"), (sp.Symbol("x"), "expression of x"), (sp.zoo, "not a finite number"),
        (sp.I, "real"),
    ]):
        out.append(Case(f"number-type-{k}", "wrong types", lambda value=value: read_number(value, where="a key"),
                        "ExpressionError", ("a key", word)))
    x = sp.Symbol("x")
    for k, (make, word) in enumerate([
        (lambda: x**1000, "exponent"), (lambda: sp.Integer(10) ** 400, "too large"),
        (lambda: sp.Add(*[sp.Symbol(f"s{j}") for j in range(3000)]), "too large"),
        (lambda: sp.nan + x, "not a finite"), (lambda: "x + 1", "got str"), (lambda: [x], "got list"),
        (lambda: sp.Float("1.5", 5000), "digits"), (lambda: sp.Rational(1, 10**400), "too large"),
        (lambda: sp.Matrix([[x**500]]), "exponent"), (lambda: None, "got NoneType"),
    ]):
        out.append(Case(f"check-expression-{k}", "sympy trees", lambda make=make: check_expression(
            make(), where="a tree"), "ExpressionError", ("a tree", word)))
    return out


def driver_cases():
    from kinbook.planar import DistanceDriver, Driver, Mechanism, RelativeAngleDriver
    from kinbook.spatial import DistanceDriver as SpatialDistanceDriver
    from kinbook.spatial import RevoluteDriver

    t = sp.Symbol("t", real=True)
    texts = [
        ("1/0", "division by zero"), ("I*t", "unknown name 'I'"), ("t > 1", "comparisons"),
        ("exit()", "unknown function 'exit'"), ("floor(t)", "step functions"), ("Heaviside(t - 1)", "step"),
        ("sign(t)", "jumps"), ("Piecewise((t, t > 1))", "piecewise"), ("Min(t, 1)", "corners"),
        ("w*t", "unknown name 'w'"), ("t/(t - t)", "not finite"), ("", "empty"), ("2t", "products with *"),
        ("t^", "not a valid expression"), ("sin(t, t)", "takes 1"), ("t.diff()", "attribute"),
    ] + [(c, "") for c in CODE[:8]] + [(h, "") for h in HUGE[:6]]
    makers = {
        "driver": lambda f: Driver("bar", "phi", f),
        "relative-driver": lambda f: RelativeAngleDriver("a", "b", f),
        "distance-driver": lambda f: DistanceDriver("a", "b", ("P", "Q"), "P", f),
        "revolute-driver": lambda f: RevoluteDriver("a", "b", "z", f),
        "spatial distance-driver": lambda f: SpatialDistanceDriver("a", "b", "x", "O", "O", f),
    }
    out = []
    rng = np.random.default_rng(SEED + 1)
    for k, (text, word) in enumerate(texts):
        names = list(makers)
        for name in (names if k < 12 else [names[int(rng.integers(len(names)))]]):
            out.append(Case(f"driver-{name}-{k}-{_short(text)}", "drivers",
                            lambda text=text, name=name: makers[name](text), "ExpressionError",
                            (", f:", word) if word else (", f:",), timeout=5))
    for k, (value, word) in enumerate([
        (True, "got True"), (["t"], "list"), ({"t": 1}, "dict"), (math.nan, "finite"), (sp.I * t, "complex"),
        (sp.Heaviside(t), "jumps"), (sp.floor(t), "jumps"), (sp.Symbol("w") * t, "unknown symbols w"),
        (sp.zoo * t, "not a finite"), (t**1000, "exponent"), (sp.Eq(t, 1), "expected an expression"),
    ]):
        out.append(Case(f"driver-object-{k}", "drivers", lambda value=value: Driver("bar", "phi", value),
                        "ExpressionError", ("driver on body 'bar', f", word)))

    def pendulum(f):
        from kinbook.planar import Ground, Revolute

        m = Mechanism("pendulum")
        m.add_body("ground", points={"O": (0, 0)})
        m.add_body("bar", points={"O": (-1, 0)}, q0=(1, 0, 0))
        m.add(Ground("ground"))
        m.add(Revolute("ground", "bar", point="O"))
        m.add(Driver("bar", "phi", f))
        return m

    runtime = [
        ("sqrt(t - 5)", lambda m: m.solve_position(0.0), "no real value at t = 0"),
        ("log(t)", lambda m: m.solve_position(0.0), "is infinite at t = 0"),
        ("1/t", lambda m: m.solve_position(0.0), "at t = 0"),
        ("Abs(t - 0.5)", lambda m: m.solve_acceleration(m.solve_position(0.5), m.solve_velocity(
            m.solve_position(0.5), 0.5), 0.5), "does not exist at t = 0.5 (a kink"),
        ("Abs(t - 0.5)", lambda m: m.simulate([0.0, 0.25, 0.5, 0.75]), "kink"),
        ("sqrt(t)", lambda m: m.solve_velocity(m.solve_position(0.0), 0.0), "first derivative"),
        ("asin(t)", lambda m: m.solve_position(2.0), "no real value at t = 2"),
        ("1/(t - 1)", lambda m: m.simulate(np.linspace(0, 2, 21)), "is infinite at t = 1"),
    ]
    for k, (f, act, word) in enumerate(runtime):
        out.append(Case(f"driver-runtime-{k}-{f}", "drivers", lambda f=f, act=act: act(pendulum(f)),
                        "DriverValueError", ("driver 'driver 1'", word)))
    # a kink that is not hit, and Abs accepted: these work
    out.append(Case("driver-abs-works", "drivers", lambda: pendulum("Abs(t - 0.5)").simulate([0.0, 0.25]).q[-1, 5],
                    "ok", check=lambda v: abs(v - 0.25) < 1e-9))
    return out


def _file_mutations(key, value):
    """(label, new value or _DELETE, expected words) for a key of a mechanism file."""
    payload = [("code", CODE[0], ()), ("huge", "9**9**9**9", ()), ("div0", "1/0", ())]
    types = [("list", ["x"], ()), ("dict", {"a": 1}, ()), ("bool", True, ()), ("nan", math.nan, ())]
    if key in ("i", "j", "k", "body"):
        return [("int", 3, ("must be a string",)), ("list", ["a"], ("must be a string",)),
                ("bool", True, ("must be a string",)), ("missing", "nobody", ("no body 'nobody'",))]
    if key == "name":
        return [("int", 3, ("must be a string",)), ("list", ["a"], ("must be a string",))]
    if key == "type":
        return [("unknown", "hinge", ("`type`", "hinge")), ("list", ["revolute"], ("`type`",)),
                ("int", 3, ("`type`",)), ("empty", "", ("`type`",))]
    if key in ("point", "point_i", "point_j"):
        return [("missing", "nopoint", ("no point 'nopoint'",)), ("short", [1], ()), ("code", CODE[0], ("no point",)),
                ("bool", True, ()), ("dict", {"a": 1}, ())]
    if key in ("axis",):
        return [("text", "PQ", ("axis",)), ("one", ["P"], ("axis",)), ("int", 3, ("axis",))]
    if key in ("axis_i", "axis_j", "vector_i", "vector_j", "perp_i", "perp_j", "ref_i", "ref_j"):
        return [("missing", "novector", ("no vector 'novector'",)), ("zero", [0, 0, 0], ("zero",)),
                ("short", [1, 2], (key,)), ("bool", True, (key,))]
    if key == "f":
        return [(lbl, v, (", f",)) for lbl, v, _ in payload + types] + [
            ("compare", "t > 1", ("comparisons",)), ("complex", "I*t", ("'I'",)), ("step", "floor(t)", ("step",))]
    if key == "coordinate":
        return [("z", "z", ("coordinate",)), ("int", 3, ("coordinate",)), ("list", ["phi"], ("coordinate",))]
    if key in ("length", "radius", "radius_i", "radius_j"):
        zero = [("zero", 0, (key,))] if key != "length" else [("negative", -2, (key, "positive"))]
        return [(lbl, v, (key,)) for lbl, v, _ in payload + types] + zero
    if key in ("phi0", "value"):
        if isinstance(value, list):
            return [("short", [0, 0], ("phi0",)), ("text", "abc", ("phi0",))] + [
                (f"item-{lbl}", [v, 0, 0], ("phi0",)) for lbl, v, _ in payload]
        return [(lbl, v, (key,)) for lbl, v, _ in payload + types]
    if key == "q":
        return [("short", [0, 0], ("q",)), ("text", "abc", ("q",))] + [
            (f"item-{lbl}", [v] + list(value[1:]), ("q",)) for lbl, v, _ in payload]
    if key == "sliding":
        return [("text", "no", ("sliding",)), ("int", 1, ("sliding",))]
    if key == "initial":
        return [("text", "x", ("initial",)), ("unknown", {"bogus": 1}, ("initial", "bogus")),
                ("code", {"x_i": CODE[0]}, ("initial",))]
    return []


def file_cases():
    out = []
    sources = [(n, lambda n=n: _example_data(n)) for n in
               ("ch13_example1", "ch13_example2", "ch13_example3", "ch13_example4", "spatial_fourbar",
                "spatial_slider_crank")]
    sources += [("zoo", lambda: _zoo_data(PLANAR_ZOO)), ("spatial_zoo", lambda: _zoo_data(SPATIAL_ZOO))]
    rng = np.random.default_rng(SEED + 2)
    for name, load in sources:
        data = load()
        src = f"{name}.toml"
        # bodies
        for b, body in enumerate(data["bodies"]):
            where = f"bodies[{b}]"
            slots = [(("bodies", b, "name"), "name", ("int", 3, ("must be a string",)))]
            if "q0" in body:
                q0 = body["q0"]
                choices = (("code", CODE[0]), ("huge", "9**9**9**9"), ("nan", math.nan), ("list", [1]),
                           ("bool", True), ("text", "t"))
                for c in rng.choice(len(choices), size=2, replace=False):
                    lbl, v = choices[c]
                    j = int(rng.integers(len(q0)))
                    slots.append(((("bodies", b, "q0", j)), "q0", (f"{lbl}{j}", v, ("q0",))))
                slots.append((("bodies", b, "q0"), "q0", ("whole-short", q0[:2], ("q0",))))
            for pname, pt in list(body.get("points", {}).items())[:1]:
                choices = (("code", CODE[1]), ("short", [1]), ("huge", "10**10**10"), ("dict", {"a": 1}))
                lbl, v = choices[int(rng.integers(len(choices)))]
                new = v if lbl in ("short", "dict") else [v] + list(pt[1:])
                slots.append((("bodies", b, "points", pname), "points", (f"{pname}-{lbl}", new,
                                                                         (f"point '{pname}'",))))
            if b == 1:
                slots.append((("bodies", b, "points"), "points", ("int", 3, ("points",))))
            if b == 0:
                slots.append((("bodies", b, "bogus"), "bogus", ("unknown", 1, ("unknown key 'bogus'",))))
            for path, key, (lbl, v, words) in slots:
                out.append(_file_case(name, load, path, v, f"file-{name}-{where}-{key}-{lbl}",
                                      (src, where) + tuple(words)))
        # constraints
        for c, spec in enumerate(data.get("constraints", [])):
            where = f"constraints[{c}]"
            for key, value in spec.items():
                options = _file_mutations(key, value)
                if not options:
                    continue
                lbl, v, words = options[int(rng.integers(len(options)))]  # one per key and constraint, seeded
                out.append(_file_case(name, load, ("constraints", c, key), v,
                                      f"file-{name}-{where}-{key}-{lbl}", (src, where) + tuple(words)))
            if c % 3 == 0:
                out.append(_file_case(name, load, ("constraints", c, "pont"), "O",
                                      f"file-{name}-{where}-unknown-key", (src, where, "unknown key 'pont'")))
            required = [k for k in spec if k in ("i", "j", "body", "f", "length", "coordinate")]
            if required:
                key = required[int(rng.integers(len(required)))]
                out.append(_file_case(name, load, ("constraints", c, key), _DELETE,
                                      f"file-{name}-{where}-missing-{key}", (src, where, f"missing key '{key}'")))
    return out


def _file_case(name, load, path, value, cid, words):
    def run():
        data = copy.deepcopy(load())
        _set(data, path, value)
        return _build(data, f"{name}.toml")

    return Case(cid, "file keys", run, "MechanismFileError", words, timeout=10)


def file_structure_cases(tmpdir_name="corpus-files"):
    import kinbook

    def loads(text, source="m.toml"):
        return kinbook.loads(text, source=source)

    def load_bytes(raw, name="m.toml"):
        import os
        import tempfile

        d = tempfile.mkdtemp()
        p = os.path.join(d, name)
        with open(p, "wb") as fh:
            fh.write(raw)
        return kinbook.load(p)

    good = _zoo_data(PLANAR_ZOO)
    rows = [
        ("not-toml", lambda: loads("[[bodies]\nname = 'a'"), ("m.toml", "not valid TOML")),
        ("not-utf8", lambda: load_bytes(b"[mechanism]\nname = '\xff'\n"), ("m.toml", "not UTF-8")),
        ("utf16", lambda: load_bytes("[mechanism]".encode("utf-16")), ("m.toml", "not UTF-8")),
        ("binary", lambda: load_bytes(bytes(range(256))), ("m.toml",)),
        ("empty", lambda: loads(""), ("m.toml", "[[bodies]]")),
        ("no-bodies", lambda: loads("[mechanism]\nname = 'x'\n"), ("m.toml", "[[bodies]]")),
        ("bodies-int", lambda: loads("bodies = 3\n"), ("m.toml", "bodies", "array of tables")),
        ("bodies-strings", lambda: loads("bodies = ['a']\n"), ("m.toml", "bodies[0]", "table")),
        ("constraints-text", lambda: loads("constraints = 'x'\n[[bodies]]\nname = 'a'\n"),
         ("m.toml", "constraints", "array of tables")),
        ("top-unknown", lambda: loads("[[bodies]]\nname = 'a'\n[extra]\nx = 1\n"), ("m.toml", "extra")),
        ("mechanism-unknown", lambda: loads("[mechanism]\nknd = 'planar'\n[[bodies]]\nname = 'a'\n"),
         ("m.toml", "mechanism.knd")),
        ("kind-int", lambda: loads("[mechanism]\nkind = 3\n[[bodies]]\nname = 'a'\n"), ("m.toml", "mechanism.kind")),
        ("kind-unknown", lambda: loads("[mechanism]\nkind = 'fluid'\n[[bodies]]\nname = 'a'\n"),
         ("m.toml", "mechanism.kind", "fluid")),
        ("kind-list", lambda: loads("[mechanism]\nkind = ['planar']\n[[bodies]]\nname = 'a'\n"),
         ("m.toml", "mechanism.kind")),
        ("name-list", lambda: loads("[mechanism]\nname = [1]\n[[bodies]]\nname = 'a'\n"), ("m.toml", "mechanism.name")),
        ("title-int", lambda: loads("[mechanism]\ntitle = 1\n[[bodies]]\nname = 'a'\n"), ("m.toml", "mechanism.title")),
        ("body-no-name", lambda: loads("[[bodies]]\nq0 = [0, 0, 0]\n"), ("m.toml", "bodies[0]", "missing key 'name'")),
        ("body-dup", lambda: loads("[[bodies]]\nname = 'a'\n[[bodies]]\nname = 'a'\n"),
         ("m.toml", "bodies[1]", "already has a body named 'a'")),
        ("constraint-dup-name", lambda: loads("[[bodies]]\nname = 'a'\n[[constraints]]\ntype = 'ground'\nbody = 'a'\n"
                                               "name = 'g'\n[[constraints]]\ntype = 'simple'\nbody = 'a'\n"
                                               "coordinate = 'x'\nname = 'g'\n"),
         ("m.toml", "constraints[1]", "already has a constraint named 'g'")),
        ("no-type", lambda: loads("[[bodies]]\nname = 'a'\n[[constraints]]\nbody = 'a'\n"),
         ("m.toml", "constraints[0]", "`type`")),
        ("deep-array", lambda: loads("x = " + "[" * 3000 + "]" * 3000 + "\n"), ("m.toml",)),
        ("too-big", lambda: loads(" " * (16 * 2**20 + 1)), ("m.toml", "larger than")),
        ("bytes-text", lambda: kinbook.loads(b"[[bodies]]\nname = 'a'\n"), ("expected the text",)),
        ("missing-file", lambda: kinbook.load("/nonexistent/m.toml"), ("/nonexistent/m.toml", "cannot read")),
        ("directory", lambda: kinbook.load("/"), ("cannot read",)),
        ("nul-path", lambda: kinbook.load("a\0b.toml"), ("not a usable file name",)),
        ("path-int", lambda: kinbook.load(3), ("expected the path",)),
        ("too-many-bodies", lambda: _build({"bodies": [{"name": f"b{k}"} for k in range(100_001)]}, "m.toml"),
         ("m.toml", "bodies", "100000")),
        ("zero-length-crank", lambda: loads(_example_file("ch13_example1").replace(
            "points = { OA = [-1, 0], A = [1, 0] }", "points = { OA = [0, 0], A = [0, 0] }")),
         ("m.toml", "body 'crank'", "zero length")),
        ("example-traversal", lambda: kinbook.examples.load("../io"), ("no example mechanism",)),
        ("example-list", lambda: kinbook.examples.load(["ch13_example1"]), ("no example mechanism",)),
        ("ground-q-huge", lambda: _build(_mutated(good, ("constraints", 0, "q", 0), "9**9**9**9"), "m.toml"),
         ("m.toml", "constraints[0]", "too large")),
    ]
    out = [Case(f"file-structure-{label}", "file structure", fn, "MechanismFileError", words, timeout=10)
           for label, fn, words in rows]
    # a symbolic parameter (for a derivation) loads; a numeric analysis names it instead of a raw TypeError
    for k, (path, value, who) in enumerate([
        (("constraints", 2, "radius_i"), "rho", "gear joint"), (("constraints", 4, "phi0"), "c", "translational"),
        (("constraints", 5, "length"), "l", "revolute-revolute"), (("constraints", 6, "point_i"), ["xi", 0],
                                                                     "revolute-translational"),
        (("constraints", 1, "value"), "v", "simple constraint"), (("constraints", 3, "radius"), "r", "rack-pinion"),
        (("constraints", 0, "q"), [0, "y0", 0], "ground constraint"), (("bodies", 1, "points", "M"), ["xi", 0], ""),
    ]):
        name = value if isinstance(value, str) else next(v for v in value if isinstance(v, str))
        out.append(Case(f"file-symbolic-{k}-{path[-1]}", "file keys",
                        lambda path=path, value=value: (lambda m: m.Phi(m.q0))(
                            _build(_mutated(good, path, value), "zoo.toml")),
                        "ModelError", (who, f"symbolic parameters ({name})")))
    return out


def _mutated(data, path, value):
    data = copy.deepcopy(data)
    _set(data, path, value)
    return data


def _example_file(name):
    from kinbook import examples

    return examples.path(name).read_text(encoding="utf-8")


def api_cases():
    import kinbook
    from kinbook import planar, spatial

    loaded = {}

    def ex(name="ch13_example1", fresh=False):
        """The example, loaded once for the cases that only read it (their inputs fail validation, or
        analyse without changing it); ``fresh`` for a case that changes it."""
        if fresh or name not in loaded:
            m = kinbook.examples.load(name)
            if fresh:
                return m
            loaded[name] = m
        return loaded[name]

    m1 = "mechanism 'ch13_example1'"
    rows = []

    def add(label, fn, expect, words):
        rows.append(Case(f"api-{label}", "python api", fn, expect, words))

    bad_q = [("short", np.zeros(5), "shape"), ("complex", np.zeros(12) + 1j, "complex"), ("text", ["a"] * 12, "text"),
             ("nan", np.r_[np.zeros(11), np.nan], "phi4"), ("bool", [True] * 12, "booleans"),
             ("3d", np.zeros((2, 2, 12)), "shape"), ("ragged", [[0] * 12, [0]], "`q`"), ("none", None, "`q`"),
             ("dict", {"q": 1}, "`q`")]
    for lbl, q, word in bad_q:
        add(f"Phi-q-{lbl}", lambda q=q: ex().Phi(q), "InputError", ("`q`", word))
        add(f"Phi_q-q-{lbl}", lambda q=q: ex().Phi_q(q), "InputError", ("`q`", word))
        add(f"solve_velocity-q-{lbl}", lambda q=q: ex().solve_velocity(q), "InputError", ("`q`", word))
        if q is not None:  # q0=None is the default guess
            add(f"q0-{lbl}", lambda q=q: ex().solve_position(0.0, q0=q), "InputError", ("`q0`",))
    bad_t = [("text", "0", "text"), ("nan", np.nan, "finite"), ("inf", np.inf, "finite"), ("bool", True, "booleans"),
             ("complex", 1j, "complex"), ("list", [0, 1], "one number"), ("none", None, "`t`")]
    for lbl, t, word in bad_t:
        add(f"solve_position-t-{lbl}", lambda t=t: ex().solve_position(t), "InputError", ("`t`", word))
        add(f"diagnose-t-{lbl}", lambda t=t: ex().diagnose(ex().q0, t), "InputError", ("`t`",))
        add(f"nu-t-{lbl}", lambda t=t, lbl=lbl: ex().nu(ex().q0, t) if lbl != "list" else ex().nu(ex().q0, [[0]]),
            "InputError", ("`t`",))
    for lbl, tol in (("inf", np.inf), ("zero", 0), ("negative", -1e-9), ("text", "1e-9"), ("bool", True),
                     ("nan", np.nan), ("none", None)):
        add(f"tol-{lbl}", lambda tol=tol: ex().solve_position(0.0, tol=tol), "InputError", ("`tol`", "positive"))
        add(f"simulate-tol-{lbl}", lambda tol=tol: ex().simulate([0.0, 0.1], tol=tol), "InputError", ("`tol`",))
    for lbl, it in (("zero", 0), ("huge", 10**9), ("float", 2.5), ("bool", True), ("text", "5")):
        add(f"max_iter-{lbl}", lambda it=it: ex().solve_position(0.0, max_iter=it), "InputError", ("`max_iter`",))
    for lbl, times, word in (("2d", np.zeros((2, 2)), "1-D"), ("empty", [], "non-empty"), ("nan", [0, np.nan], "times[1]"),
                             ("text", ["a", "b"], "numbers"), ("scalar", 0.5, "1-D"),
                             ("huge", np.zeros(2_000_000), "more than")):
        add(f"simulate-times-{lbl}", lambda times=times: ex().simulate(times), "InputError", ("`times`", word))
    add("simulate-on_failure", lambda: ex().simulate([0, 0.1], on_failure="ignore"), "InputError", ("`on_failure`",))
    add("simulate-anchor", lambda: ex().simulate([0, 0.1], anchor_every=0), "InputError", ("`anchor_every`",))
    add("body-unknown", lambda: ex().point_position(ex().q0, "nobody", "A"), "UnknownBodyError", (m1, "nobody"))
    add("point-unknown", lambda: ex().point_position(ex().q0, "crank", "Z"), "UnknownPointError", ("crank", "'Z'"))
    add("point-coords-text", lambda: ex().point_position(ex().q0, "crank", ["a", "b"]), "InputError", ("crank",))
    add("point-coords-nan", lambda: ex().point_position(ex().q0, "crank", [np.nan, 0]), "InputError", ("crank",))
    add("index-unknown", lambda: ex().index("phi9"), "InputError", (m1, "phi9"))
    add("index-tuple", lambda: ex().index(("crank", "z")), "InputError", ("coordinate",))
    add("constraint-unknown", lambda: ex().constraint("99"), "ModelError", (m1, "'99'"))
    add("remove-unknown", lambda: ex(fresh=True).remove("99"), "ModelError", (m1, "'99'"))
    add("add-wrong-kind", lambda: ex(fresh=True).add(spatial.Spherical("ground", "crank", point="OA")), "ModelError",
        ("planar constraint",))
    add("add-object", lambda: ex(fresh=True).add("revolute"), "ModelError", ("planar constraint",))
    add("body-dup", lambda: ex(fresh=True).add_body("crank"), "ModelError", ("already has a body named 'crank'",))
    add("body-q0-text", lambda: ex(fresh=True).add_body("new", q0="0,0,0"), "ModelError", ("body 'new'", "q0"))
    add("body-q0-short", lambda: ex(fresh=True).add_body("new", q0=(0, 0)), "ModelError", ("body 'new'", "q0"))
    add("body-q0-code", lambda: ex(fresh=True).add_body("new", q0=(0, CODE[0], 0)), "ExpressionError", ("q0 of body 'new'",))
    add("body-points-list", lambda: ex(fresh=True).add_body("new", points=[(0, 0)]), "ModelError", ("body 'new'", "points"))
    add("body-point-triple", lambda: ex(fresh=True).add_body("new", points={"A": (0, 0, 0)}), "ModelError", ("point 'A'",))
    add("body-point-code", lambda: ex(fresh=True).add_body("new", points={"A": (CODE[1], 0)}), "ExpressionError", ("point 'A'",))
    add("gamma-qd-short", lambda: ex().gamma(ex().q0, np.zeros(3)), "InputError", ("`qd`",))
    add("evaluate-sparse-batch", lambda: ex().evaluate(np.zeros((2, 12)), sparse=True), "InputError", ("sparse",))
    add("driver-count", lambda: (lambda m: (m.remove("driver 1"), m.solve_position(0.0)))(ex(fresh=True)),
        "DriverCountError",
        (m1, "degree"))
    # planar constructors
    P = planar
    for lbl, fn, expect, words in [
        ("simple-coordinate", lambda: P.Simple("a", "z"), "ModelError", ("coordinate",)),
        ("simple-value-code", lambda: P.Simple("a", "x", CODE[0]), "ExpressionError", ("simple constraint", "value")),
        ("ground-q-short", lambda: P.Ground("a", q=(0, 0)), "ModelError", ("ground", "q")),
        ("ground-q-text", lambda: P.Ground("a", q="000"), "ModelError", ("ground", "q")),
        ("revolute-nopoint", lambda: P.Revolute("a", "b"), "ModelError", ("revolute joint", "point")),
        ("translational-axis", lambda: P.Translational("a", "b", axis="PQ", point_j="P"), "ModelError", ("axis",)),
        ("translational-phi0", lambda: P.Translational("a", "b", ("P", "Q"), "P", phi0="9**9**9**9"),
         "ExpressionError", ("phi0", "too large")),
        ("rr-length-zero", lambda: P.RevoluteRevolute("a", "b", "P", "P", length=0), "ModelError", ("length",)),
        ("rr-length-code", lambda: P.RevoluteRevolute("a", "b", "P", "P", length=CODE[3]), "ExpressionError",
         ("length",)),
        ("rr-length-list", lambda: P.RevoluteRevolute("a", "b", "P", "P", length=[1]), "ExpressionError",
         ("length",)),
        ("rt-axis", lambda: P.RevoluteTranslational("a", "b", "P", axis=3), "ModelError", ("axis",)),
        ("gear-radius", lambda: P.Gear("a", "b", "c", "1/0", 1), "ExpressionError", ("radius_i",)),
        ("gear-phi0", lambda: P.Gear("a", "b", "c", 1, 1, phi0=(0, 0)), "ModelError", ("phi0",)),
        ("rack-sliding", lambda: P.RackPinion("a", "b", 1, sliding="no"), "ModelError", ("sliding",)),
        ("rack-initial", lambda: P.RackPinion("a", "b", 1, initial={"y": 0}), "ModelError", ("initial", "'y'")),
        ("rack-radius", lambda: P.RackPinion("a", "b", radius=True), "ExpressionError", ("radius",)),
        ("driver-coordinate", lambda: P.Driver("a", "theta", "t"), "ModelError", ("coordinate",)),
        ("distance-axis", lambda: P.DistanceDriver("a", "b", axis=("P",), point_j="P", f="t"), "ModelError", ("axis",)),
    ]:
        add(f"planar-{lbl}", fn, expect, words)
    S = spatial
    sm = "spatial_fourbar"
    for lbl, fn, expect, words in [
        ("ground-q", lambda: S.Ground("a", q="x"), "ModelError", ("`q`",)),
        ("ss-length", lambda: ex(sm, fresh=True).add(S.SphericalSpherical("crank", "rocker", "A", "B", length="-1")), "ModelError",
         ("length", "positive")),
        ("ss-length-code", lambda: ex(sm, fresh=True).add(S.SphericalSpherical("crank", "rocker", "A", "B", length=CODE[0])),
         "ExpressionError", ("length",)),
        ("spherical-point", lambda: ex(sm, fresh=True).add(S.Spherical("crank", "rocker", point_i=[1, 2], point_j="B")),
         "ModelError", ("point_i",)),
        ("spherical-point-code", lambda: ex(sm, fresh=True).add(S.Spherical("crank", "rocker", point_i=[CODE[0], 0, 0],
                                                                point_j="B")), "ExpressionError", ("point_i",)),
        ("revolute-axis-zero", lambda: ex(sm, fresh=True).add(S.Revolute("crank", "rocker", [0, 0, 0], "axis", point_i="A",
                                                             point_j="B")), "ModelError", ("axis_i", "zero")),
        ("body-q0-short", lambda: ex(sm, fresh=True).add_body("new", q0=(0, 0, 0)), "ModelError", ("body 'new'", "q0")),
        ("body-q0-zero-p", lambda: ex(sm, fresh=True).add_body("new", q0=(0, 0, 0, 0, 0, 0, 0)), "ModelError", ("body 'new'",)),
        ("body-vector-zero", lambda: ex(sm, fresh=True).add_body("new", vectors={"v": (0, 0, 0)}), "ModelError", ("vector 'v'",)),
        ("body-points-text", lambda: ex(sm, fresh=True).add_body("new", points="A"), "ModelError", ("points",)),
        ("body-point-code", lambda: ex(sm, fresh=True).add_body("new", points={"A": (CODE[0], 0, 0)}), "ExpressionError",
         ("point 'A'",)),
        ("q-not-unit", lambda: ex(sm).A(np.r_[ex(sm).q0[:3], 2, 0, 0, 0, ex(sm).q0[7:]], "ground"), "InputError",
         ("body 'ground'", "unit")),
        ("moved-axis", lambda: ex(sm).moved(ex(sm).q0, "crank", axis=(0, 0, 0)), "InputError", ("axis",)),
        ("normalization-add", lambda: ex(sm, fresh=True).add(S.Normalization("crank")), "ModelError", ("normalization",)),
        ("jacobian-blocks-batch", lambda: ex(sm).jacobian_blocks("A", np.zeros((2, 28))), "InputError", ("`q`",)),
    ]:
        add(f"spatial-{lbl}", fn, expect, words)
    return rows


def function_cases():
    """Every public function of the planar and spatial transforms and rotations, each argument given bad
    values (a seeded sample of the combinations)."""
    import inspect

    from kinbook.planar import transforms as PT
    from kinbook.spatial import rotations as R
    from kinbook.spatial import transforms as ST

    bad = [("text", "x", "`"), ("numtext", "1", "text"), ("none", None, "`"), ("nan", np.nan, "finite"),
           ("inf", np.inf, "finite"), ("complex", np.array([1j, 0, 0]), "complex"), ("bool", True, "booleans"),
           ("dict", {}, "`"), ("ragged", [[1, 2], [3]], "`"), ("object", object(), "`"), ("mat-nan", np.full((3, 3), np.nan),
                                                                                      "finite"),
           ("mixed-text", [sp.Symbol("x"), "__import__('os')", 0, 0], "text")]
    good = {"phi": 0.3, "r": [1.0, 2.0], "s_local": [1.0, 0.0], "r_dot": [0.0, 1.0], "phi_dot": 0.5,
            "phi_ddot": 0.1, "r_ddot": [0.0, 0.0]}
    sgood = {"v": [1.0, 0, 0], "A": np.eye(3), "u_xi": [1.0, 0, 0], "u_eta": [0, 1.0, 0], "u_zeta": [0, 0, 1.0],
             "psi": 0.1, "theta": 0.5, "angles": [0.1, 0.5, 0.2], "rates": [0.1, 0.2, 0.3], "omega": [0.1, 0.2, 0.3],
             "axis": [0, 0, 1.0], "angle": 0.3, "p": [1.0, 0, 0, 0], "p_dot": [0.0, 0.1, 0, 0],
             "p_ddot": [0.0, 0.0, 0.1, 0], "a": [1.0, 2.0, 3.0], "r": [0.0, 0, 0], "r_dot": [0.0, 0, 0],
             "r_ddot": [0.0, 0, 0], "s_local": [1.0, 0, 0], "phi": 0.2}
    combos = []
    for mod, g in ((PT, good), (R, sgood), (ST, sgood)):
        for name in mod.__all__:
            f = getattr(mod, name)
            if not callable(f):
                continue
            params = [p.name for p in inspect.signature(f).parameters.values() if p.default is inspect.Parameter.empty]
            for p in params:
                for lbl, value, word in bad:
                    combos.append((mod.__name__.split(".", 1)[-1], name, f, params, p, lbl, value, word, g))
    rng = np.random.default_rng(SEED + 3)
    keep = sorted(rng.choice(len(combos), size=min(160, len(combos)), replace=False))
    out = []
    for k in keep:
        modname, name, f, params, p, lbl, value, word, g = combos[k]
        args = {q: g[q] for q in params}
        args[p] = value
        words = ("__import__",) if lbl == "mixed-text" else (f"`{p}`", word) if word != "`" else (f"`{p}`",)
        out.append(Case(f"function-{modname}.{name}-{p}-{lbl}", "public functions",
                        lambda f=f, args=args: f(**args), "InputError", words))
    # correct answers where a naive formula returns garbage
    out.append(Case("function-normalize_p-huge", "public functions", lambda: R.normalize_p([1e300] * 4), "ok",
                    check=lambda v: np.allclose(v, 0.5)))
    out.append(Case("function-normalize_p-tiny", "public functions", lambda: R.normalize_p([1e-13, 0, 0, 0]),
                    "InputError", ("`p` = 0",)))
    out.append(Case("function-point_acceleration-overflow", "public functions",
                    lambda: PT.point_acceleration([0, 0], 0.0, 1e300, 0.0, [1.0, 0]), "InputError", ("overflows",)))
    return out


def singular_cases():
    import kinbook

    def dead_centre():
        text = _example_file("ch13_example2").replace(
            'body = "crank"\ncoordinate = "phi"\nf = "pi/4 + 100*t"', 'body = "slider"\ncoordinate = "x"\nf = "8 - t"')
        return kinbook.loads(text, source="dead.toml")

    def redundant():  # x2 fixed twice, y2 once, φ2 free: square, and Φ_q singular
        from kinbook.planar import Ground, Mechanism, Simple

        m = Mechanism("twice")
        m.add_body("ground")
        m.add_body("bar", q0=(1, 0, 0.3))
        m.add(Ground("ground"))
        m.add(Simple("bar", "x", 1, name="x once"))
        m.add(Simple("bar", "x", 1, name="x twice"))
        m.add(Simple("bar", "y", 0, name="y"))
        return m

    def zero_crank_python():  # built in Python, not refused at load: the singular Φ_q is diagnosed
        from kinbook.planar import Driver, Ground, Mechanism, Revolute

        m = Mechanism("zero crank")
        m.add_body("ground", points={"OA": (0, 0), "OB": (3, 0)})
        m.add_body("crank", points={"OA": (0, 0), "A": (0, 0)}, q0=(0, 0, 2.4))
        m.add_body("coupler", points={"A": (-3, 0), "B": (3, 0)}, q0=(1.6, 1.8, 0.1))
        m.add_body("rocker", points={"B": (-1.5, 0), "OB": (1.5, 0)}, q0=(3.6, 1.3, 4.3))
        m.add(Ground("ground"))
        for i, j, p in (("ground", "crank", "OA"), ("ground", "rocker", "OB"), ("crank", "coupler", "A"),
                        ("coupler", "rocker", "B")):
            m.add(Revolute(i, j, point=p))
        m.add(Driver("crank", "phi", "3*pi/4 + t"))
        return m

    rows = [
        ("dead-centre-solve", lambda: dead_centre().solve_position(0.0), "DeadPointError", ("dead point", "t = 0")),
        ("dead-centre-sweep", lambda: dead_centre().simulate(np.linspace(0, 1, 11)), "AssemblyError",
         ("t = 0", "dead point")),
        ("dead-centre-crossing", lambda: kinbook.loads(_example_file("ch13_example2").replace(
            'body = "crank"\ncoordinate = "phi"\nf = "pi/4 + 100*t"',
            'body = "slider"\ncoordinate = "x"\nf = "8 - (t - 1)**2"'), source="x.toml").simulate(
            np.linspace(0, 2, 41)), "AssemblyError", ("t = 1", "dead point")),
        ("redundant", lambda: redundant().solve_position(0.0), "RedundantConstraintsError",
         ("twice", "redundant", "x once", "x twice")),
        ("overconstrained", lambda: (lambda m: (m.remove("driver 1"), m.add(__import__("kinbook").planar.Simple(
            "crank", "x", 0)), m.add(__import__("kinbook").planar.Simple("crank", "y", 0)), m.solve_position(0.0)))(
            kinbook.examples.load("ch13_example1")), "DriverCountError", ("overconstrained",)),
        ("zero-crank", lambda: zero_crank_python().solve_position(0.0), "RedundantConstraintsError",
         ("zero crank", "redundant")),
    ]
    out = [Case(f"singular-{lbl}", "singular configurations", fn, expect, words, timeout=30)
           for lbl, fn, expect, words in rows]

    def large_singular():  # 700 bodies (2,100 coordinates): the sparse path, no dense SVD
        from kinbook.planar import Simple

        lines = ['[[bodies]]\nname = "ground"\npoints = { O = [0, 0] }\n']
        lines += [f'[[bodies]]\nname = "b{k}"\nq0 = [{k - 0.5}, 0, 0]\npoints = {{ L = [-0.5, 0], R = [0.5, 0] }}\n'
                  for k in range(1, 700)]
        lines.append('[[constraints]]\ntype = "ground"\nbody = "ground"\n')
        lines += [f'[[constraints]]\ntype = "revolute"\ni = "{"ground" if k == 1 else f"b{k - 1}"}"\nj = "b{k}"\n'
                  f'point_i = "{"O" if k == 1 else "R"}"\npoint_j = "L"\n' for k in range(1, 700)]
        lines += [f'[[constraints]]\ntype = "driver"\nbody = "b{k}"\ncoordinate = "phi"\nf = "0.1*t"\n'
                  for k in range(1, 699)]
        m = kinbook.loads("".join(lines), source="chain.toml")
        m.add(Simple("b1", "phi", 0, name="phi1 again"))  # the same row as driver 1: Φ_q is singular
        return m.solve_position(0.0)

    def diagnose_dead_point():
        m = dead_centre()
        q = m.q0
        q[:] = [0, 0, 0, 1, 0, 0, 5, 0, 0, 8, 0, 0]  # the dead centre itself: crank and rod along x
        return m.diagnose(q, 0.0).kind

    out.append(Case("singular-large", "singular configurations", large_singular, "SingularJacobianError",
                    ("chain", "n = 2100 coordinates", "rank analysis"), timeout=60))
    out.append(Case("singular-diagnose-dead-centre", "singular configurations", diagnose_dead_point, "ok",
                    check=lambda kind: kind == "dead-point"))
    def exact_crank_angle(x):
        """φ of the crank (2) with the rod (6) when the slider is at x: 2 cos φ + √(36 − 4 sin² φ) = x,
        solved by bisection in 60-digit arithmetic (independent of kinbook)."""
        import mpmath

        with mpmath.workdps(60):
            def f(phi):
                return 2 * mpmath.cos(phi) + mpmath.sqrt(36 - 4 * mpmath.sin(phi) ** 2) - mpmath.mpf(x)

            return float(mpmath.findroot(f, (mpmath.mpf("1e-9"), mpmath.mpf("0.1")), solver="bisect"))

    # 1e-6 before the dead centre: Newton's |Φ| test alone stopped 8e-8 rad away from the solution
    out.append(Case("singular-near-dead-centre-accurate", "singular configurations",
                    lambda: dead_centre().solve_position(1e-6)[5], "ok",
                    check=lambda phi: abs(phi - exact_crank_angle(8 - 1e-6)) < 1e-10))
    return out


def cli_cases():
    ex = "ch13_example1"
    rows = [
        ("t-nan", ["solve", ex, "-t", "nan"], ("-t", "finite")),
        ("t-inf", ["solve", ex, "-t", "inf"], ("-t", "finite")),
        ("t-text", ["solve", ex, "-t", "abc"], ("-t",)),
        ("t-code", ["solve", ex, "-t", CODE[0]], ("-t",)),
        ("mechanism-missing", ["solve", "/nonexistent.toml"], ("mechanism", "/nonexistent.toml")),
        ("mechanism-dir", ["table", "/"], ("mechanism",)),
        ("variant-traversal", ["variant", "/etc/hostname", "--student", "x/../../escaped"], ("--student",)),
        ("variant-dotdot", ["variant", "/etc/hostname", "--student", ".."], ("--student",)),
        ("variant-hidden", ["variant", "/etc/hostname", "--student", ".bashrc"], ("--student",)),
        ("variant-slash", ["variant", "/etc/hostname", "--student", "/root"], ("--student",)),
        ("variant-nul", ["variant", "/etc/hostname", "--student", "a\x00b"], ("--student",)),
        ("variant-long", ["variant", "/etc/hostname", "--student", "a" * 200], ("--student",)),
        ("variant-source-missing", ["variant", "/nonexistent.ipynb", "--student", "ana"], ("source",)),
        ("grade-missing-submission", ["grade", "/etc/hostname", "/nonexistent"], ("submissions", "/nonexistent")),
        ("grade-timeout-negative", ["grade", "/etc/hostname", "/tmp", "--timeout", "-1"], ("--timeout",)),
        ("grade-timeout-zero", ["grade", "/etc/hostname", "/tmp", "--timeout", "0"], ("--timeout",)),
        ("grade-memory-nan", ["grade", "/etc/hostname", "/tmp", "--memory", "nan"], ("--memory",)),
        ("grade-jobs-zero", ["grade", "/etc/hostname", "/tmp", "--jobs", "0"], ("--jobs",)),
        ("grade-jobs-huge", ["grade", "/etc/hostname", "/tmp", "--jobs", "100000"], ("--jobs",)),
        ("grade-jobs-float", ["grade", "/etc/hostname", "/tmp", "--jobs", "1.5"], ("--jobs",)),
        ("grade-output-file", ["grade", "/etc/hostname", "/tmp", "-o", "/etc/hostname"], ("--output",)),
        ("release-missing", ["release", "/nonexistent.ipynb"], ("source",)),
        ("unknown-command", ["frobnicate"], ("frobnicate",)),
        ("no-command", [], ("command",)),
        ("unknown-option", ["solve", ex, "--bogus"], ("--bogus",)),
        ("bad-file", ["table", "__BADFILE__"], ("bad.toml", "not UTF-8")),
        ("file-code", ["table", "__CODEFILE__"], ("code.toml", "q0")),
        ("dead-centre", ["solve", "__DEADFILE__"], ("dead point",)),
    ]
    out = []
    for lbl, argv, words in rows:
        out.append(Case(f"cli-{lbl}", "command line", lambda argv=argv: _cli(_files(argv)), "cli", words, timeout=20))
    return out


def _files(argv):
    """Replace the placeholders by files written in the worker's directory."""
    files = {
        "__BADFILE__": ("bad.toml", b"[mechanism]\nname = '\xff'\n"),
        "__CODEFILE__": ("code.toml", _example_file("ch13_example1").replace(
            'q0 = [-0.7, 0.7, "3*pi/4"]', f'q0 = [-0.7, 0.7, "{CODE[1]}"]').encode()),
        "__DEADFILE__": ("dead.toml", _example_file("ch13_example2").replace(
            'body = "crank"\ncoordinate = "phi"\nf = "pi/4 + 100*t"',
            'body = "slider"\ncoordinate = "x"\nf = "8 - t"').encode()),
    }
    out = []
    for a in argv:
        if a in files:
            name, raw = files[a]
            with open(name, "wb") as fh:
                fh.write(raw)
            a = name
        out.append(a)
    return out


def checker_cases():
    """Checker-side items of issue 13 (the one equivalence rule of issue 14): numbers must be real, and an
    answer set must have the reference's zero set and rank (a duplicated or scaled-duplicate row fails)."""
    import kinbook
    from kinbook.grading import check_phi, check_value

    def phi_rows(change):
        m = kinbook.examples.load("ch13_example1")
        P = list(m.symbolic().Phi)
        return check_phi(change(P), m).passed

    rows = [
        ("check_value-bool", lambda: check_value(True, 1.0).passed),
        ("check_value-complex", lambda: check_value(np.array([1 + 0.5j, 2.0]), np.array([1.0, 2.0])).passed),
        ("check_phi-duplicate-row", lambda: phi_rows(lambda P: P[:4] + [P[3]] + P[5:])),
        ("check_phi-scaled-duplicate", lambda: phi_rows(lambda P: P[:4] + [2 * P[3]] + P[5:])),
    ]
    return [Case(f"checker-{lbl}", "checkers", fn, "ok", check=lambda passed: passed is False) for lbl, fn in rows]


# ------------------------------------------------------------------------------------------ issue 23's classes
def _driver_file(f):
    """ch13_example1 with the crank's driver f(t) replaced."""
    text = _example_file("ch13_example1")
    assert 'f = "3*pi/4 + 100*t"' in text
    return text.replace('f = "3*pi/4 + 100*t"', f'f = "{f}"')


def derivative_cases():
    """Drivers within every reader limit whose derivatives sympy would take minutes to write: refused by the
    estimate of their size before any differentiation (kinbook.core.symbolic.derivative_sizes)."""
    import kinbook
    from kinbook.planar import Driver

    texts = {
        "sin-99": "sin(" * 99 + "t" + ")" * 99,
        "exp-60": "exp(" * 60 + "t/100" + ")" * 60,
        "tower-40": "^".join(["t"] * 40),
        "product-30": "*".join(f"(t + {k})" for k in range(1, 31)),
        "product-of-powers": "*".join(f"(t + {k})^(t + {k})" for k in range(1, 13)),
        "atan-chain": "atan(" * 50 + "t" + ")" * 50,
    }
    out = []
    for label, f in texts.items():
        out.append(Case(f"derivative-file-{label}", "derivatives", lambda f=f: kinbook.loads(_driver_file(f), source="d.toml"),
                        "MechanismFileError", ("d.toml", "constraints[5]", "too involved to differentiate"), timeout=20))
        out.append(Case(f"derivative-api-{label}", "derivatives", lambda f=f: Driver("crank", "phi", f),
                        "ExpressionError", ("driver on body 'crank', f", "second derivative would have up to"),
                        timeout=20))
    # a driver of the book's size, and a longer legitimate one, load and solve
    for label, f in (("book", "3*pi/4 + 100*t"), ("blend", "3*pi/4 + 100*t + 0.1*(1 - cos(pi*t))/2*sin(3*t)*exp(-t)")):
        out.append(Case(f"derivative-ok-{label}", "derivatives",
                        lambda f=f: kinbook.loads(_driver_file(f), source="d.toml").solve_velocity(
                            kinbook.loads(_driver_file(f), source="d.toml").solve_position(0.0))[5],
                        "ok", check=lambda v: abs(v - 100.0) < 1e-6, timeout=20))
    return out


def literal_cases():
    """Float literals past the magnitude bound, integer/float forms the docs do not describe (hex, octal, binary,
    underscores), sums deep enough to have exhausted Python's recursion, and columns after non-ASCII text."""
    import kinbook
    from kinbook.core.reader import read_expression, read_number

    t = sp.Symbol("t", real=True)
    ex1 = _example_file("ch13_example1")
    deep = "sin(" * 50 + "+".join(["1"] * 900) + ")" * 50
    rows = [
        ("number-1e308", lambda: read_number("1e308", where="w"), "ExpressionError", ("w", "too large")),
        ("number-neg-1e308", lambda: read_number("-1e308", where="w"), "ExpressionError", ("w", "too large")),
        ("point-1e308", lambda: kinbook.loads(ex1.replace("OA = [-1, 0]", "OA = [-1e308, 0]"), source="p.toml"),
         "MechanismFileError", ("p.toml", "bodies[1]", "too large")),
        ("q0-1e308", lambda: kinbook.loads(ex1.replace('q0 = [-0.7, 0.7, "3*pi/4"]', 'q0 = [1e308, 0.7, "3*pi/4"]'),
                                           source="q.toml"), "MechanismFileError", ("q.toml", "too large")),
        ("point-1e300-solve", lambda: kinbook.loads(ex1.replace("OA = [-1, 0]", "OA = [-1e300, 0]"),
                                                    source="p.toml").solve_position(0.0),
         "ConvergenceError", ("ch13_example1", "revolute joint '1'")),
        ("hex", lambda: read_number("0x10", where="w"), "ExpressionError", ("w", "'0x10'", "decimal")),
        ("octal", lambda: read_number("0o17", where="w"), "ExpressionError", ("w", "'0o17'", "decimal")),
        ("binary", lambda: read_expression("0b101*t", symbols={"t": t}, where="w"), "ExpressionError",
         ("'0b101'", "decimal")),
        ("underscore", lambda: read_number("1_000", where="w"), "ExpressionError", ("'1_000'", "decimal")),
        ("leading-zero", lambda: read_number("007", where="w"), "ExpressionError", ("w", "not a valid")),
        ("column-after-pi", lambda: read_number("ππ + foo", where="w"), "ExpressionError", ("at column 6",)),
        ("column-after-dot", lambda: read_expression("  ẋ1 ^ 2 + foo", symbols={"ẋ1": t}, where="w"),
         "ExpressionError", ("at column 12",)),
        ("column-after-caret", lambda: read_expression("t^2^t + t^3 + zz", symbols={"t": t}, where="w"),
         "ExpressionError", ("unknown name 'zz' at column 15",)),
        ("deep-sum-driver", lambda: kinbook.loads(_driver_file("sin(" * 30 + "+".join(["t"] * 960) + ")" * 30),
                                                  source="d.toml"), "MechanismFileError", ("d.toml", "too involved")),
    ]
    out = [Case(f"literal-{lbl}", "literals and recursion", fn, expect, words, timeout=20)
           for lbl, fn, expect, words in rows]
    # 900 terms inside 50 calls: evaluated without recursion (mpmath at fixed precision)
    out.append(Case("literal-deep-sum-number", "literals and recursion", lambda: read_number(deep, where="w"), "ok",
                    check=lambda v: abs(v - _nested_sin(900.0, 50)) < 1e-9))
    out.append(Case("literal-deep-sum-cli", "literals and recursion", lambda: _cli(["solve", "ch13_example2", "-t", deep]),
                    "ok", check=lambda r: r[0] == 0, timeout=20))
    out.append(Case("literal-decimals-ok", "literals and recursion", lambda: read_number(".5e3 + 5. + 1e-3", where="w"),
                    "ok", check=lambda v: abs(v - 505.001) < 1e-12))
    return out


def _nested_sin(x, depth):
    for _ in range(depth):
        x = math.sin(x)
    return x


def file_kind_cases():
    """kinbook.load on what is not a regular file: refused without opening it for a blocking read."""
    import os

    import kinbook

    def fifo():
        if os.path.exists("m-fifo.toml"):
            os.remove("m-fifo.toml")
        os.mkfifo("m-fifo.toml")
        return kinbook.load("m-fifo.toml")

    rows = [("fifo", fifo, ("m-fifo.toml", "FIFO", "not a regular file")),
            ("dev-zero", lambda: kinbook.load("/dev/zero"), ("/dev/zero", "device")),
            ("dev-null", lambda: kinbook.load("/dev/null"), ("/dev/null", "device")),
            ("directory", lambda: kinbook.load("/tmp"), ("/tmp", "directory"))]
    return [Case(f"file-kind-{lbl}", "non-regular files", fn, "MechanismFileError", words, timeout=10)
            for lbl, fn, words in rows]


def _exercise_variant(name, label, cell_match, edit):
    """A copy of a shipped exercise, in the worker's directory, with one cell edited: ``edit(source)``."""
    import json

    from kinbook import exercises

    with exercises.path(name).open(encoding="utf-8") as f:
        nb = json.load(f)
    index = next(i for i, c in enumerate(nb["cells"]) if c["cell_type"] == "code" and cell_match in "".join(c["source"]))
    nb["cells"][index]["source"] = edit("".join(nb["cells"][index]["source"]))
    path = f"{label}.ipynb"
    with open(path, "w", encoding="utf-8") as f:
        json.dump(nb, f)
    return path, index + 1


def declaration_cases():
    """Exercise declarations an instructor can get wrong, refused at release with the file and the cell named,
    and student ids that are not one safe file name, refused by the library as by the command line."""
    import re

    from kinbook.classroom import release, write_variant

    def released(name, label, cell_match, edit):
        path, cell = _exercise_variant(name, label, cell_match, edit)
        try:
            release(path, "released")
        except Exception as exc:
            if f"cell {cell}" not in str(exc):
                raise AssertionError(f"cell {cell} is not named: {exc}") from None
            raise

    points = lambda value: lambda src: re.sub(r"points=\d+", f"points={value}", src, count=1)  # noqa: E731
    ranges = lambda new: lambda src: re.sub(r"omega=\([^)]*\)", new, src, count=1)  # noqa: E731
    rows = [
        ("points-nan", "ex01", "part(", points('float("nan")'), ("points", "nan")),
        ("points-inf", "ex01", "part(", points("1e400"), ("points", "inf")),
        ("points-negative", "ex01", "part(", points("-3"), ("points", "-3")),
        ("points-bool", "ex01", "part(", points("True"), ("points", "True")),
        ("points-text", "ex01", "part(", points('"3"'), ("points", "'3'")),
        ("range-reversed", "ex09", "parameters(", ranges("omega=(140.0, 60.0)"), ("omega", "low > high")),
        ("range-text", "ex09", "parameters(", ranges("omega=(60.0, 'x')"), ("omega", "two finite numbers")),
        ("range-huge", "ex09", "parameters(", ranges("omega=(-1e308, 1e308)"), ("omega", "two finite numbers")),
        ("range-three", "ex09", "parameters(", ranges("omega=(1.0, 2.0, 3.0)"), ("omega", "two finite numbers")),
        ("range-empty-list", "ex09", "parameters(", ranges("omega=[]"), ("omega", "1 to")),
        ("range-dict", "ex09", "parameters(", ranges("omega={'a': 1}"), ("omega", "(low, high) or a list")),
        ("range-no-default", "ex09", "parameters(", ranges("omega=(60.0, 140.0), zeta=(1.0, 2.0)"),
         ("no default for zeta",)),
        ("default-none", "ex09", "parameters(", lambda src: src.replace("defaults={", "defaults={'w': None, ", 1),
         ("default of w",)),
        ("not-python", "ex09", "parameters(", lambda src: src.replace(")", ",,)", 1), ("not valid Python",)),
        ("not-literal", "ex09", "parameters(", ranges("omega=(60.0, abs(-140.0))"), ("literal values",)),
        ("double-star", "ex09", "parameters(", lambda src: src.replace("parameters(", "parameters(**{'a': 1}, ", 1),
         ("keyword arguments only",)),
    ]
    out = [Case(f"declaration-{lbl}", "exercise declarations",
                lambda name=name, lbl=lbl, match=match, edit=edit: released(name, lbl, match, edit),
                "GradingError", (lbl, *words), timeout=60)
           for lbl, name, match, edit, words in rows]

    def variant_for(student):
        from kinbook import exercises

        return write_variant(exercises.path("ex09"), student, "variants")

    for lbl, student in (("traversal", "x/../../escaped"), ("dotdot", ".."), ("hidden", ".bashrc"),
                         ("absolute", "/root"), ("nul", "a\x00b"), ("long", "a" * 200), ("empty", ""), ("none", None),
                         ("int", 7)):
        out.append(Case(f"declaration-student-{lbl}", "exercise declarations",
                        lambda student=student: variant_for(student), "GradingError", ("student id",), timeout=60))
    return out


def method_cases():
    """Mechanism methods given a batch where one configuration is solved, a missing q̇, a derivative order that
    is no order, an empty mechanism, truthy texts for flags."""
    import kinbook
    from kinbook.classroom import grade
    from kinbook.planar import Mechanism

    loaded = {}

    def ex():
        if "m" not in loaded:
            loaded["m"] = kinbook.examples.load("ch13_example1")
        return loaded["m"]

    def sweep():
        if "s" not in loaded:
            loaded["s"] = ex().simulate(np.linspace(0, 0.01, 3))
        return loaded["s"]

    batch = lambda: np.tile(ex().q0, (2, 1))  # noqa: E731
    rows = [
        ("solve_velocity-batch", lambda: ex().solve_velocity(batch()), "InputError", ("`q`", "one configuration")),
        ("solve_acceleration-batch", lambda: ex().solve_acceleration(batch(), batch()), "InputError",
         ("`q`", "one configuration")),
        ("diagnose-batch", lambda: ex().diagnose(batch()), "InputError", ("`q`", "one configuration")),
        ("gamma-qd-none", lambda: ex().gamma(ex().q0, None), "InputError", ("`qd`", "required")),
        ("solve_acceleration-qd-none", lambda: ex().solve_acceleration(ex().q0, None), "InputError",
         ("`qd`", "required")),
        ("solve_acceleration-qd-batch", lambda: ex().solve_acceleration(ex().q0, batch()), "InputError",
         ("`qd`", "one configuration")),
        ("empty-symbolic", lambda: Mechanism("empty").symbolic(), "ModelError", ("'empty'", "no bodies")),
        ("empty-solve", lambda: Mechanism("empty").solve_position(0.0), "ModelError", ("'empty'", "no bodies")),
        ("history-text", lambda: ex().solve_position(0.0, history="no"), "InputError", ("`history`", "'no'")),
        ("evaluate-sparse-text", lambda: ex().evaluate(ex().q0, sparse="no"), "InputError", ("`sparse`",)),
        ("grade-force-text", lambda: grade("/etc/hostname", ["/tmp"], "g", force="no"), "GradingError",
         ("`force`", "'no'")),
        ("grade-isolation-text", lambda: grade("/etc/hostname", ["/tmp"], "g", isolation="false"), "GradingError",
         ("`isolation`",)),
        ("grade-timeout-text", lambda: grade("/etc/hostname", ["/tmp"], "g", timeout="5"), "GradingError",
         ("`timeout`",)),
        ("grade-jobs-zero", lambda: grade("/etc/hostname", ["/tmp"], "g", jobs=0), "GradingError", ("`jobs`",)),
    ]
    for d in (-1 / 3, 3, -1, 1.5, True, "1", None):
        rows.append((f"derivative-{d!r}", lambda d=d: sweep().coordinate("phi2", derivative=d), "InputError",
                     ("`derivative`",)))
    return [Case(f"method-{lbl}", "mechanism methods", fn, expect, words, timeout=30)
            for lbl, fn, expect, words in rows]


def structure_cases():
    """Structural mistakes whose diagnosis names the culprit: no ground, a body in no constraint, a loop that
    cannot close, a symbolic point blamed on its body (not on the first joint that touches the body)."""
    import re

    import kinbook

    ex1 = _example_file("ch13_example1")
    no_ground = re.sub(r'\[\[constraints\]\]\ntype = "ground"\n[^\[]*', "", ex1, count=1)
    loose = ex1 + '\n[[bodies]]\nname = "loose"\nq0 = [1, 1, 0]\n'
    short = ex1.replace("B = [-1.5, 0], OB = [1.5, 0]", "B = [-0.2, 0], OB = [0.2, 0]")
    spatial = _example_file("spatial_fourbar")
    spatial_loose = spatial + '\n[[bodies]]\nname = "loose"\nq0 = [1, 1, 1, 1, 0, 0, 0]\n'
    rows = [
        ("no-ground", lambda: kinbook.loads(no_ground, source="ng.toml").solve_position(0.0), "DriverCountError",
         ("ch13_example1", "no body is fixed to the ground")),
        ("loose-body", lambda: kinbook.loads(loose, source="l.toml").solve_position(0.0), "DriverCountError",
         ("body 'loose' appears in no constraint",)),
        ("loose-body-spatial", lambda: kinbook.loads(spatial_loose, source="l.toml").solve_position(0.0),
         "DriverCountError", ("body 'loose' appears in no constraint",)),
        ("loop-cannot-close", lambda: kinbook.loads(short, source="s.toml").solve_position(0.0), "ConvergenceError",
         ("cannot be assembled", "revolute joint '4'", "revolute joint '2'")),
    ]
    out = [Case(f"structure-{lbl}", "structural diagnoses", fn, expect, words, timeout=30)
           for lbl, fn, expect, words in rows]
    good = _zoo_data(PLANAR_ZOO)
    out.append(Case("structure-symbolic-point-body", "structural diagnoses",
                    lambda: _build(_mutated(good, ("bodies", 1, "points", "M"), ["xi", 0]), "zoo.toml").Phi(
                        _build(good, "zoo.toml").q0),
                    "ModelError", ("body '", "point 'M'", "symbolic parameters (xi)")))
    return out


def helper_cases():
    """The book's and the notebooks' helpers given what they do not take: a named InputError, not a bare
    TypeError / KeyError / ValueError from inside."""
    import sympy as sp

    from kinbook.book import display, errata, notation, verify

    rows = [
        ("errata-get-unknown", lambda: errata.get("nope"), ("no erratum 'nope'",)),
        ("errata-get-int", lambda: errata.get(3), ("no erratum '3'",)),
        ("errata-get-list", lambda: errata.get(["a"]), ("no erratum",)),
        ("notation-pair-list", lambda: notation.pair(["r"]), ("`kind`",)),
        ("notation-pair-unknown", lambda: notation.pair("q"), ("`kind`", "'q'")),
        ("notation-latex-text", lambda: notation.latex("x + 1"), ("sympy expression", "str")),
        ("notation-latex-dict", lambda: notation.latex({"a": 1}), ("sympy expression", "dict")),
        ("notation-tidy-text", lambda: notation.tidy("2.0*x"), ("sympy expression",)),
        ("notation-equations-none", lambda: notation.equations(None), ("`rows`",)),
        ("notation-matrix-text", lambda: notation.matrix("a"), ("`values`",)),
        ("notation-matrix-dict", lambda: notation.matrix({"a": 1}), ("`values`",)),
        ("notation-local_points-text", lambda: notation.local_points("ch13_example1"), ("expected a mechanism",)),
        ("notation-to_book-text", lambda: notation.to_book(sp.Symbol("x"), "ch13_example1"), ("expected a mechanism",)),
        ("notation-Math-int", lambda: notation.Math(3), ("LaTeX text",)),
    ]
    for fname in ("fmt", "small", "agrees"):
        for lbl, value in (("text", "a"), ("none", None), ("list", [1, 2]), ("complex", 1j), ("symbol", sp.Symbol("x"))):
            rows.append((f"display-{fname}-{lbl}", lambda f=fname, v=value: getattr(display, f)(v), (f"{fname}:",)))
    rows += [
        ("display-fmt-digits", lambda: display.fmt(1.0, digits=-1), ("`digits`",)),
        ("display-small-tol", lambda: display.small(1.0, tol=float("nan")), ("`tol`",)),
        ("display-tolerance_text-text", lambda: display.tolerance_text("a"), ("`tol`",)),
        ("display-tolerance_text-nan", lambda: display.tolerance_text(float("nan")), ("`tol`",)),
        ("display-newton_table-list", lambda: verify.newton_table([1, 2]), ("solve_position",)),
    ]
    return [Case(f"helper-{lbl}", "book helpers", fn, "InputError", words) for lbl, fn, words in rows]


def drift_cases():
    """Smaller drift: the documented spellings accepted, the tolerances of a checker finite, a negative time
    on the command line read as a number."""
    import kinbook
    from kinbook.grading import check_gamma, check_rotation

    def dotted():
        m = kinbook.examples.load("ch13_example1")
        return check_gamma(["ẋ1 - ẋ_1", "φ̇2 - phi2_dot"], m.constraint("1"))

    return [
        Case("drift-dotted-names", "drift", dotted, "ok", check=lambda r: r is not None and "unknown" not in str(r)),
        Case("drift-check_rotation-rtol-nan", "drift", lambda: check_rotation(2 * np.eye(3), np.eye(3), rtol=math.nan),
             "InputError", ("`rtol`",)),
        Case("drift-check_rotation-atol-nan", "drift", lambda: check_rotation(2 * np.eye(3), np.eye(3), atol=math.nan),
             "InputError", ("`atol`",)),
        Case("drift-cli-negative-time", "drift", lambda: _cli(["solve", "ch13_example2", "-t", "-1e-3"]), "ok",
             check=lambda r: r[0] == 0, timeout=20),
        Case("drift-cli-negative-expression", "drift", lambda: _cli(["solve", "ch13_example2", "-t=-pi/400"]), "ok",
             check=lambda r: r[0] == 0, timeout=20),
    ]


def older_cases():
    """The earlier corpora's cases still open at issue 31: a tuple that is no (body, coordinate) pair, point kinematics
    with shapes that do not broadcast, None given for a number, an integer beyond every float in a try-it, a joint
    written twice."""
    import kinbook
    from kinbook.planar import transforms

    ex = functools.lru_cache(maxsize=1)(lambda: kinbook.examples.load("ch13_example1"))
    text = _example_file("ch13_example1")
    joint = next(b for b in text.split("[[constraints]]") if 'type = "revolute"' in b)
    rows = [
        ("index-one", lambda: ex().index(("crank",)), "InputError", ("('crank',)", "pair")),
        ("index-three", lambda: ex().index(("crank", "phi", "x")), "InputError", ("pair",)),
        ("point_position-shapes", lambda: transforms.point_position(np.zeros((3, 2)), np.zeros(4), np.zeros((5, 2))),
         "InputError", ("point_position", "incompatible shapes", "(3, 2), (4,), (5, 2)")),
        ("point_velocity-shapes", lambda: transforms.point_velocity(np.zeros((3, 2)), np.zeros(4), np.zeros(4),
                                                                    np.zeros((5, 2))), "InputError",
         ("point_velocity", "incompatible shapes")),
        ("point_position-none", lambda: transforms.point_position(None, 0.0, [1.0, 0.0]), "InputError",
         ("`r`", "got None")),
        ("A-none", lambda: transforms.A(None), "InputError", ("`phi`", "got None")),
        ("solve-t-none", lambda: ex().solve_position(None), "InputError", ("`t`", "got None")),
        ("joint-twice", lambda: kinbook.loads(text + "\n[[constraints]]" + joint, source="twice.toml")
         .solve_position(0.0), "DriverCountError", ("overconstrained", "revolute joint '1'", "revolute joint '5'")),
    ]
    out = [Case(f"older-{lbl}", "older open cases", fn, expect, words, timeout=30) for lbl, fn, expect, words in rows]

    def try_it(answer):
        return kinbook.try_it("13-1/try-1", answer)

    for lbl, answer, word in (("huge-int", 10**400, "not_finite"), ("huge-int-list", [[10**400, 0], [0, 1]],
                                                                      "not_finite"),
                              ("none", None, "malformed"), ("none-in-list", [[None, 0], [0, 1]], "malformed")):
        out.append(Case(f"older-try_it-{lbl}", "older open cases", lambda a=answer: try_it(a), "ok",
                        check=lambda r, word=word: (not r.passed and word in r.mistakes
                                                    and "has complex numbers" not in str(r)), timeout=30))
    return out


def complex_cases():
    """A driver whose f(t), f' or f'' is complex where the analysis needs a real number (issue 31 item 7): a
    DriverValueError naming the expression and the instant, never numpy's ComplexWarning and a real part."""
    import kinbook

    rows = [  # (label, f, what is analysed, words)
        ("sqrt-negative-square", "3*pi/4 + 100*t + sqrt(-t^2)", ("position", 0.5), ("f(t)", "no real value",
                                                                                 "t = 0.5")),
        ("sqrt-negative", "3*pi/4 + sqrt(t - 5)", ("position", 1.0), ("f(t)", "no real value", "t = 1")),
        ("log-negative", "3*pi/4 + log(t - 2)", ("position", 1.0), ("f(t)", "no real value", "t = 1")),
        ("asin-out", "asin(t + 2)", ("position", 0.25), ("f(t)", "no real value", "t = 0.25")),
        ("power-fraction", "3*pi/4 + (t - 3)^(1/3)", ("position", 1.0), ("f(t)", "no real value", "t = 1")),
        ("velocity", "3*pi/4 + t*sqrt(t^2 - 4)", ("velocity", 1.0), ("f(t)", "no real value", "t = 1")),
        ("sweep", "3*pi/4 + 100*t + sqrt(-t^2)", ("sweep", 0.0), ("f(t)", "no real value", "t = 0.1")),
    ]

    def analyse(f, what, t):
        m = kinbook.loads(_driver_file(f), source="cx.toml")
        if what == "position":
            return m.solve_position(t)
        if what == "velocity":
            return m.solve_velocity(m.solve_position(3.0), t)  # a configuration where f is real; f' at t is not
        return m.simulate(np.linspace(0.1, 1.0, 10))

    return [Case(f"complex-{lbl}", "complex values", lambda f=f, what=what: analyse(f, *what), "DriverValueError",
                 words, timeout=60) for lbl, f, what, words in rows]


def course_cases():
    """Issue 31's classes: the course commands' gradebooks, names, own inputs, rosters and sources
    (tests/inputs/course_cases.py)."""
    try:
        from . import course_cases as course
    except ImportError:  # the worker imports this file as the top-level module `corpus`
        import course_cases as course
    return course.cases(Case)


def cases():
    """All cases, in a fixed order with unique ids."""
    out = (reader_cases() + driver_cases() + file_cases() + file_structure_cases() + api_cases()
           + function_cases() + singular_cases() + cli_cases() + checker_cases() + derivative_cases()
           + literal_cases() + file_kind_cases() + declaration_cases() + method_cases() + structure_cases()
           + helper_cases() + drift_cases() + older_cases() + complex_cases() + course_cases())
    ids = [c.id for c in out]
    dup = {i for i in ids if ids.count(i) > 1}
    assert not dup, f"duplicate case ids: {sorted(dup)[:5]}"
    return out
