"""The safe expression reader (kinbook.core.reader): what it accepts builds the same sympy object as the
expression written in Python; what it refuses is refused before any arithmetic, with a message naming the
place, and quickly (the bad-input corpus in tests/inputs/ adds hundreds of cases under a hard timeout)."""

import math
import time

import pytest
import sympy as sp

from kinbook.core.bounds import Limits, check_expression
from kinbook.core.reader import ALIASES, FUNCTIONS, read_constant, read_expression, read_number
from kinbook.errors import ExpressionError, InputError, KinbookError

t = sp.Symbol("t", real=True)
x, phi2 = sp.symbols("x2 phi2", real=True)
T = {"t": t}
Q = {"x2": x, "phi2": phi2, "t": t}


# ----------------------------------------------------------------------------------------------- accepted
@pytest.mark.parametrize("text, expected", [
    ("3*pi/4 + 100*t", 3 * sp.pi / 4 + 100 * t),
    ("pi/4 + 100*t", sp.pi / 4 + 100 * t),
    ("2^3", sp.Integer(8)),
    ("2**3", sp.Integer(8)),
    ("-t^2", -t**2),
    ("1/2", sp.Rational(1, 2)),
    ("0.25*t", sp.Float(0.25) * t),
    ("1e-3", sp.Float(1e-3)),
    ("sen(t)", sp.sin(t)),
    ("abs(t - 1)", sp.Abs(t - 1)),
    ("ln(t)", sp.log(t)),
    ("arctan2(t, 1)", sp.atan2(t, 1)),
    ("log(8, 2)", sp.Integer(3)),
    ("π/2", sp.pi / 2),
    ("E", sp.E),
    ("sqrt(2)/2", sp.sqrt(2) / 2),
    ("  t  ", t),
    ("1 - 2 - 3", sp.Integer(-4)),
    ("8/2/2", sp.Integer(2)),
    ("2*3/4*t", sp.Rational(3, 2) * t),
    ("t - -t", 2 * t),
    ("+t", t),
])
def test_reads_what_python_would_build(text, expected):
    assert read_expression(text, symbols=T, where="w") == expected


def test_context_symbols_are_the_callers_objects():
    e = read_expression("x2 - cos(phi2)*t", symbols=Q, where="answer row 1")
    assert e == x - sp.cos(phi2) * t
    assert e.free_symbols == {x, phi2, t}


def test_a_mapping_resolving_spellings_lazily_works():
    class Aliases(dict):
        def __contains__(self, name):
            return super().__contains__(name.replace("_", ""))

        def __getitem__(self, name):
            return super().__getitem__(name.replace("_", ""))

    assert read_expression("phi_2 + x_2", symbols=Aliases(Q), where="w") == phi2 + x


def test_every_function_and_alias_reads():
    for name, (f, counts) in FUNCTIONS.items():
        args = ", ".join(["t"] * counts[0])
        assert read_expression(f"{name}({args})", symbols=T, where="w") == f(*[t] * counts[0])
    for alias, name in ALIASES.items():
        f, counts = FUNCTIONS[name]
        args = ", ".join(["t"] * counts[0])
        assert read_expression(f"{alias}({args})", symbols=T, where="w") == f(*[t] * counts[0])


def test_functions_argument_restricts_or_replaces():
    with pytest.raises(ExpressionError, match="unknown function 'exp'"):
        read_expression("exp(t)", symbols=T, where="w", functions=["sin", "cos"])
    assert read_expression("sen(t)", symbols=T, where="w", functions=["sin"]) == sp.sin(t)
    f = sp.Function("f")
    assert read_expression("f(t)", symbols=T, where="w", functions={"f": (f, (1,))}) == f(t)


def test_long_sums_are_one_level_deep():
    e = read_expression("+".join(["t"] * 400), symbols=T, where="w")
    assert e == 400 * t


# ----------------------------------------------------------------------------------------------- refused
REFUSED = [
    # (text, words the reason must contain)
    ("__import__('os').system('echo hi')", "attribute access"),
    ("__import__('os')", "unknown function '__import__'"),
    ("exit()", "unknown function 'exit'"),
    ("eval('1')", "unknown function 'eval'"),
    ("t.real", "attribute access"),
    ("().__class__", "attribute access"),
    ("[1][0]", "subscripts"),
    ("t > 1", "comparisons"),
    ("t and 1", "'and' / 'or'"),
    ("1 if t else 2", "'if … else'"),
    ("lambda: 1", "lambda"),
    ("'abc'", "str literal"),
    ("b'x'", "bytes literal"),
    ("True", "True is not a number"),
    ("None", "None is not a number"),
    ("1j", "complex numbers"),
    ("I*t", "unknown name 'I' (complex numbers"),
    ("oo", "unknown name 'oo'"),
    ("x", "unknown name 'x'"),
    ("e", "Euler's number is written E"),
    ("floor(t)", "step functions"),
    ("Heaviside(t - 1)", "step functions"),
    ("Piecewise((1, t > 1))", "piecewise"),
    ("factorial(10**8)", "unknown function 'factorial'"),
    ("9**9**9**9", "exponent 3.8742e+08 is too large"),
    ("10**10**10", "exponent 1e+10 is too large"),
    ("(t+1)**100000", "exponent 100000 is too large"),
    ("2**1000", "exponent 1000 is too large"),
    ("exp(1000)", "too large"),
    ("10.0**99 * 10.0**99 * 10.0**99 * 10.0**99", "too large"),
    ("1e400", "not finite"),
    ("1/0", "division by zero"),
    ("t/(1-1)", "division by zero"),
    ("0**-1", "division by zero"),
    ("sqrt(-1)", "not a real number"),
    ("asin(2)", "not a real number"),
    ("log(-1)", "not a real number"),
    ("t % 2", "operator '%'"),
    ("t // 2", "operator '//'"),
    ("t @ t", "operator '@'"),
    ("~t", "operator '~'"),
    ("not t", "operator 'not'"),
    ("2t", "write products with *"),
    ("t(2)", "'t' is not a function"),
    ("sin", "'sin' is a function"),
    ("sin(1, 2)", "sin() takes 1 argument, got 2"),
    ("atan2(1)", "atan2() takes 2 arguments, got 1"),
    ("sin(x=1)", "keyword"),
    ("sin(*t)", "'*' unpacking"),
    ("[t for t in ()]", "comprehensions"),
    ("(t := 1)", "':='"),
    ("f'{t}'", "strings"),
    ("{1: 2}", "dict"),
    ("(1, 2)", "tuple"),
    ("", "empty"),
    ("   ", "empty"),
    ("1 +", "not a valid expression"),
    ("1\x00", "null bytes"),
    ("import os", "not a valid expression"),
    ("(" * 300 + "1" + ")" * 300, "not a valid expression"),
    ("-" * 300 + "1", "nested too deeply"),
    ("sin(" * 150 + "1" + ")" * 150, "nested too deeply"),
    ("1" * 41, "number is too long"),
    ("t" * 6000, "too long (6000 characters"),
    ("+".join(["1"] * 1200), "too large (more than 2000 parts)"),
    ("+".join(f"1/{p}**85" for p in (1009, 1013, 1019, 1021, 1031, 1033, 1039, 1049, 1051, 1061, 1063, 1069,
                                       1087, 1091, 1093, 1097, 1103, 1109, 1117, 1123, 1129, 1151, 1153, 1163,
                                       1171, 1181)), "exact numbers are too large"),
]


@pytest.mark.parametrize("text, reason", REFUSED)
def test_refused_with_a_reason_and_the_place(text, reason):
    with pytest.raises(ExpressionError) as info:
        read_expression(text, symbols=T, where="file 'm.toml', key constraints[3].f")
    err = info.value
    assert str(err).startswith("file 'm.toml', key constraints[3].f: ")
    assert reason in str(err)
    assert err.where == "file 'm.toml', key constraints[3].f" and err.text == text
    assert isinstance(err, InputError) and isinstance(err, KinbookError)


def test_a_column_points_at_the_offending_part():
    with pytest.raises(ExpressionError) as info:
        read_expression("  1 + exit()", symbols=T, where="w")
    assert info.value.column == 7 and "at column 7" in str(info.value)


def test_long_text_is_shortened_in_the_message():
    with pytest.raises(ExpressionError) as info:
        read_expression("t" * 10**6, symbols=T, where="w")
    assert len(str(info.value)) < 200


def test_non_text_is_refused():
    with pytest.raises(ExpressionError, match="expected the text of an expression, got list"):
        read_expression(["t"], symbols=T, where="w")


def test_refusals_take_microseconds_not_seconds():
    # not a speed target (those live in benchmarks/): a hang here would mean evaluation to find out. CPU time,
    # not the clock: a loaded machine is slower, not wrong
    slow = []
    for text, _ in REFUSED:
        start = time.process_time()
        with pytest.raises(ExpressionError):
            read_expression(text, symbols=T, where="w")
        if time.process_time() - start > 1.0:
            slow.append(text[:40])
    assert not slow


def test_nested_numeric_calls_are_computed_at_fixed_precision():
    # sympy's own evaluation asks the sign of such values by adaptive evalf (minutes for eight levels)
    text = "sqrt(" * 8 + "2" + " + 1)" * 8
    value = 2.0
    for _ in range(8):
        value = math.sqrt(value + 1)
    assert read_number(text, where="w") == pytest.approx(value, rel=1e-15)
    e = read_expression("t*" + "sin(" * 3 + "1" + ")" * 3, symbols=T, where="w")
    assert float(e.coeff(t)) == pytest.approx(math.sin(math.sin(math.sin(1))), rel=1e-15)


# ----------------------------------------------------------------------------------------------- numbers
@pytest.mark.parametrize("value, expected", [
    (3, 3.0), (-2.5, -2.5), ("pi/4", math.pi / 4), ("3*pi/4", 3 * math.pi / 4), ("2^-3", 0.125),
    ("sqrt(2)", math.sqrt(2)), ("atan2(1, -1)", 3 * math.pi / 4), ("1e-400", 0.0), ("-0.0", 0.0),
])
def test_read_number(value, expected):
    assert read_number(value, where="q0[2]") == expected


@pytest.mark.parametrize("value, reason", [
    (True, "expected a number, got True"),
    (None, "expected a number, got None"),
    (math.nan, "expected a finite number, got nan"),
    (math.inf, "expected a finite number, got inf"),
    ("t", "unknown name 't'"),
    ([1, 2], "got list"),
    ({"a": 1}, "got dict"),
    ("sqrt(-2)", "not a real number"),
    (10**400, "too large"),
])
def test_read_number_refuses(value, reason):
    with pytest.raises(ExpressionError) as info:
        read_number(value, where="bodies[1].q0[2]")
    assert str(info.value).startswith("bodies[1].q0[2]: ") and reason in str(info.value)


def test_read_constant_keeps_exact_values():
    assert read_constant("3*pi/4", where="w") == 3 * sp.pi / 4
    assert read_constant(2, where="w") == sp.Integer(2)
    assert read_constant(sp.pi / 3, where="w") == sp.pi / 3
    with pytest.raises(ExpressionError, match="expected a number, got an expression of xi"):
        read_constant(sp.Symbol("xi"), where="w")


# ----------------------------------------------------------------------------------------------- sympy trees
def test_check_expression_accepts_ordinary_trees():
    check_expression(x**2 + sp.cos(phi2) / 3, where="w")
    check_expression(sp.Matrix([[x, 1], [0, phi2]]), where="w")
    check_expression(2.5, where="w")


@pytest.mark.parametrize("make, reason", [
    (lambda: x**1000, "exponent 1000 is too large"),
    (lambda: sp.Integer(10) ** 400, "too large"),
    (lambda: sp.Rational(1, 10**400), "too large"),
    (lambda: sp.Add(*[sp.Symbol(f"s{k}") for k in range(3000)]), "too large (more than 2000 distinct parts)"),
    (lambda: sp.zoo * x, "not a finite number"),
    (lambda: sp.nan, "not a finite number"),
    (lambda: sp.Float("1.5", 2000), "too many digits"),
    (lambda: "x + 1", "expected a sympy expression, got str"),
    (lambda: True, "expected a sympy expression, got bool"),
    (lambda: math.inf, "finite number"),
])
def test_check_expression_refuses(make, reason):
    with pytest.raises(ExpressionError) as info:
        check_expression(make(), where="answer row 2")
    assert str(info.value).startswith("answer row 2: ") and reason in str(info.value)


def test_check_expression_counts_shared_parts_once():
    """A sympy object is a graph: its distinct parts are bounded (and walked once), its size written out as a
    tree is computed from them — so a long expression with shared parts passes, and one whose tree would be
    astronomical is refused as soon as its size is known, in time linear in its distinct parts."""
    shared = x
    for _ in range(40):  # 2⁴⁰ nodes written out, 80 distinct parts
        shared = sp.sin(shared) + sp.cos(shared)
    with pytest.raises(ExpressionError, match=r"too large \(more than 200000 nodes written out\)"):
        check_expression(shared, where="w", limits=Limits(depth=1000))  # a walk of the tree would never end
    long = x
    for _ in range(12):  # 3 · 2¹² tree nodes, 36 distinct parts
        long = sp.sin(long) * long
    distinct, tree, depth = check_expression(long, where="w", limits=Limits(depth=1000, tree=10**6))
    assert distinct < 40 < 10_000 < tree and depth == 25


def test_check_expression_depth():
    e = x
    for _ in range(150):
        e = sp.sin(e)
    with pytest.raises(ExpressionError, match="nested too deeply"):
        check_expression(e, where="w")


def test_limits_are_parameters():
    small = Limits(length=10, exponent=3)
    with pytest.raises(ExpressionError, match="too long"):
        read_expression("t + t + t + t", symbols=T, where="w", limits=small)
    with pytest.raises(ExpressionError, match="exponent 4 is too large"):
        read_expression("t^4", symbols=T, where="w", limits=small)
