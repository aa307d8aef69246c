"""Feedback in Spanish: the reader's refusals (kinbook.core.reader, bounds) are marked messages, written in the
language of the moment when shown, in the book's vocabulary ("fila", "elemento", "restricción motriz"); and no
English reaches a student in Spanish mode — a corpus of wrong and malformed answers is run through every checker
and try-it, and its messages, tables and reprs are searched for English function words."""

import html
import pickle
import re

import numpy as np
import pytest
import sympy as sp

import kinbook
from kinbook import ExpressionError
from kinbook.core.reader import read_expression, read_number
from kinbook.grading import CHECKERS, check_phi, check_value

from .corpus import target
from .generated import exercise_parts, tryit_parts, wrong_answers
from .tryits import all_tryits


@pytest.fixture
def spanish():
    kinbook.set_language("es")
    yield
    kinbook.set_language("en")


def _first(r):
    """The first message up to what was expected (the list of the mechanism's spellings is long)."""
    return re.split(r"; expected |; se esperaba ", r.messages[0])[0]


# ------------------------------------------------------------------------------- the reader's refusals
REFUSALS = [  # a student's row of Φ for joint 1 of the book's Example 13.1, and the first message in both languages
    ("cos(phi2", "answer row 1: not a valid expression ('(' was never closed) at column 4 in 'cos(phi2'",
     "fila 1 de la respuesta: no es una expresión válida (el '(' no se cierra) en la columna 4 de 'cos(phi2'"),
    ("theta2 + 1", "answer row 1: unknown name 'theta2' at column 1 in 'theta2 + 1'",
     "fila 1 de la respuesta: nombre desconocido 'theta2' en la columna 1 de 'theta2 + 1'"),
    ("9**9**9**9", "answer row 1: the exponent 3.8742e+08 is too large (at most 100 in size) at column 4 in "
     "'9**9**9**9'", "fila 1 de la respuesta: el exponente 3.8742e+08 es demasiado grande (su valor absoluto no "
     "puede pasar de 100) en la columna 4 de '9**9**9**9'"),
    ("__import__('os')", "answer row 1: unknown function '__import__' at column 1 in \"__import__('os')\"",
     "fila 1 de la respuesta: función desconocida '__import__' en la columna 1 de \"__import__('os')\""),
    ("x" * 1_000_000, f"answer row 1: the text is too long (1000000 characters, at most 20000) in '{'x' * 59}…'",
     f"fila 1 de la respuesta: el texto es demasiado largo (1000000 caracteres, como mucho 20000) en '{'x' * 59}…'"),
    ("sin(x1, 2)", "answer row 1: sin() takes 1 argument, got 2 at column 1 in 'sin(x1, 2)'",
     "fila 1 de la respuesta: sin() admite 1 argumento, no 2 en la columna 1 de 'sin(x1, 2)'"),
    ("log(x1, 2, 3)", "answer row 1: log() takes 1 or 2 arguments, got 3 at column 1 in 'log(x1, 2, 3)'",
     "fila 1 de la respuesta: log() admite 1 o 2 argumentos, no 3 en la columna 1 de 'log(x1, 2, 3)'"),
    ("2x1", "answer row 1: not a valid expression (invalid decimal literal); write products with * (2*t, not 2t) "
     "at column 1 in '2x1'", "fila 1 de la respuesta: no es una expresión válida (número decimal mal escrito); "
     "escribe los productos con * (2*t, no 2t) en la columna 1 de '2x1'"),
    ("1" * 50, f"answer row 1: a number is too long (more than 40 characters) at column 1 in '{'1' * 50}'",
     f"fila 1 de la respuesta: un número es demasiado largo (más de 40 caracteres) en la columna 1 de '{'1' * 50}'"),
    ("x1.real", "answer row 1: attribute access ('.') is not allowed at column 1 in 'x1.real'",
     "fila 1 de la respuesta: no se permite el acceso a atributos ('.') en la columna 1 de 'x1.real'"),
    ("sqrt(-1)", "answer row 1: a part of the expression is not a real number (≈ 0-1i) at column 1 in 'sqrt(-1)'",
     "fila 1 de la respuesta: una parte de la expresión no es un número real (≈ 0-1i) en la columna 1 de "
     "'sqrt(-1)'"),
    ("1/0", "answer row 1: division by zero at column 1 in '1/0'",
     "fila 1 de la respuesta: división por cero en la columna 1 de '1/0'"),
    ("x1 % 2", "answer row 1: the operator '%' is not allowed at column 1 in 'x1 % 2'",
     "fila 1 de la respuesta: no se permite el operador '%' en la columna 1 de 'x1 % 2'"),
]


@pytest.mark.parametrize("text, en, es", REFUSALS, ids=[t[:16] for t, _, _ in REFUSALS])
def test_a_refused_row_reads_in_the_language_of_the_moment(text, en, es):
    r = check_phi([text, "y1"], target("ch13_example1", "1"))
    assert not r.passed and r.mistakes == (["unknown_symbol"] if text == "theta2 + 1" else ["malformed"])
    assert _first(r) == en
    try:
        kinbook.set_language("es")  # the same result, shown again: translated when shown, not when made
        assert _first(r) == es
    finally:
        kinbook.set_language("en")


def test_what_was_expected_and_the_hints_are_spanish_too(spanish):
    r = check_phi(["floor(t)"], target("ch13_example1", "1"))
    assert r.messages[0].startswith(
        "fila 1 de la respuesta: función desconocida 'floor' (no se admiten funciones escalón: un movimiento "
        "prescrito necesita dos derivadas continuas (para ν y γ); analiza cada fase en su propio barrido, con su "
        "propia restricción motriz, o enlázalas de forma suave, p. ej. (1 - cos(pi*t))/2) en la columna 1 de "
        "'floor(t)'; se esperaba una expresión de t, x1, "), r.messages[0]
    assert r.messages[0].endswith(" con + - * / ^, las funciones sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, "
                                  "log, Abs, sign y las constantes pi, E")


def test_numbers_typed_as_text_are_refused_in_spanish(spanish):
    assert check_value("abc", [1.0]).messages[0].startswith(
        "respuesta: nombre desconocido 'abc' en la columna 1 de 'abc'; se esperaba un número o una expresión de "
        "números con + - * / ^")
    assert check_value(["1", "pi/"], [1.0, 2.0]).messages[0].startswith(
        "respuesta[2]: no es una expresión válida en 'pi/'; se esperaba un número")
    assert check_value([1.0, lambda: 1], [1.0, 2.0]).messages[0] == (
        "la respuesta: se esperaban números reales (un número, una lista o un array), se recibió un objeto list con "
        "elementos de tipo float, function")


def test_a_sympy_power_in_a_list_is_bounded_before_numpy_evaluates_it():
    """complex(x**10**6) expands a polynomial of degree 10⁶ (minutes): each sympy entry of a list of numbers goes
    through the reader's bounds first."""
    x = sp.Symbol("x")
    r = check_value([x**10**6], [1.0])
    assert r.mistakes == ["malformed"]
    assert r.messages[0] == "the answer: the exponent 1000000 is too large (at most 100 in size)"


def test_a_reader_error_is_written_when_shown():
    """str(err) follows the language; its args (and so a pickled copy's) keep the English; `where` given as
    plain text (a mechanism file's key) stays as given."""
    phi = sp.Symbol("phi2")
    with pytest.raises(ExpressionError) as info:
        read_expression("cos(phi2", symbols={"phi2": phi}, where="file 'm.toml', key constraints[3].f")
    err = info.value
    en = ("file 'm.toml', key constraints[3].f: not a valid expression ('(' was never closed) at column 4 in "
          "'cos(phi2'; expected an expression of phi2 with + - * / ^, the functions sin, cos, tan, asin, acos, atan, "
          "atan2, sqrt, exp, log, Abs, sign and the constants pi, E")
    assert str(err) == en and err.args == (en,) and err.column == 4
    assert err.reason == "not a valid expression ('(' was never closed)"
    copy = pickle.loads(pickle.dumps(err))
    try:
        kinbook.set_language("es")
        es = ("file 'm.toml', key constraints[3].f: no es una expresión válida (el '(' no se cierra) en la columna 4 "
              "de 'cos(phi2'; se esperaba una expresión de phi2 con + - * / ^, las funciones sin, cos, tan, asin, "
              "acos, atan, atan2, sqrt, exp, log, Abs, sign y las constantes pi, E")
        assert str(err) == es and str(copy) == es
        assert err.args == (en,) and err.reason == "not a valid expression ('(' was never closed)"
        with pytest.raises(ExpressionError, match=r"^q0\[1\]: se esperaba un número, se recibió True$"):
            read_number(True, where="q0[1]")
    finally:
        kinbook.set_language("en")
    assert str(err) == en


def test_python_words_without_a_translation_stay_english_and_leave_spanish_alone():
    """A syntax error kinbook has no words for (Python's "too many nested parentheses") keeps Python's words in
    English and is left out in Spanish, where the column still points at the place.
    """
    text = "(" * 201 + "1" + ")" * 201
    with pytest.raises(ExpressionError) as info:
        read_expression(text, symbols={}, where="q0[1]")
    assert str(info.value).startswith("q0[1]: not a valid expression (too many nested parentheses) at column 201 in")
    try:
        kinbook.set_language("es")
        assert str(info.value).startswith("q0[1]: no es una expresión válida en la columna 201 de")
    finally:
        kinbook.set_language("en")


# ------------------------------------------------------------------------------- no English in Spanish feedback
ENGLISH = re.compile(r"\b(the|is|are|not|expected|got|row|rows|of|and|with|your|answer|wrong|must|should|at|in|to|"
                     r"from|by|for|has|have|this|that|which|only|be|was|were|an|it|its|than|or|entry|column|number|"
                     r"unknown|function|name|too|large|missing|extra|correct|value|values|shape|give|use|score|"
                     r"verdict|passed|failed|mistakes)\b")
"""English words that are not Spanish ones: any of them in Spanish feedback is English leaking."""

NOT_PROSE = re.compile(
    r"'[^']*'|\"[^\"]*\"|`[^`]*`"  # quoted: the student's text, a name, code
    r"|\b[\w.]+(?:-[\w.]+)+\b"  # an identifier such as the erratum 14.3-A-of-p
    r"|\b\w+="  # a keyword argument (at=, phi=)
    r"|\b(?:tipo|objeto|recibió) \w+(?:, \w+)*"  # Python type names: "de tipo float, function", "se recibió str"
    r"|\w+(?:Error|Exception): .*? al llamarla")  # a student's function's own exception, as Python wrote it
"""What is not prose in a message, and is left as it is in any language."""

MALFORMED = ["cos(phi2", "theta2 + 1", "9**9**9**9", "__import__('os')", "x" * 1_000_000, "", "   ", "2x1",
             "sin(1, 2)", "log(1, 2, 3)", "x1.real", "[1, 2]", "1/0", "floor(t)", "e", "I", "oo", "nan", "Min(1, 2)",
             "10**400", "log(-1)", "sqrt(-1)", "1e999", "0x1f", "0777", "(x1]", "x1)", "lambda: 1", "a if b else c",
             "x1 == 1", "f(x y)", "'abc'", "x1 % 2", "not x1", "1" * 50, "sin(x=1)", "x1(2)", "sin", "{1}", "x:=1",
             "atan2(1)", "\x00", "1 +* 2", "'", "2j", "abc\\", "+".join(["x1"] * 7000), "(" * 300 + "1" + ")" * 300]
"""Malformed text: every kind of refusal of the reader and its bounds."""

_X = sp.Symbol("x1")
OBJECTS = [None, True, 1 + 2j, object(), [[1], [1, 2]], [[[1]]], {}, sp.Eq(_X, 1), sp.oo, sp.zoo, sp.nan,
           lambda q, t: 1 / 0, lambda q, t: "abc", lambda q, t: np.zeros(10**6), lambda: 1, sp.Symbol("zz"), np.nan,
           [], [np.inf], sp.Matrix([[1, 2]]), _X**10**6, sp.Float(1, 5000), sp.FiniteSet(1), [sp.Integer(2)**2**20],
           [1.0] * 100_001, np.array(["a", "b"]), [[1, 2], [3, 4]], [1.0, lambda: 1], ["1", "x1"]]
"""Malformed objects a student may hand in from Python."""


def _english_in(text):
    return sorted(set(ENGLISH.findall(NOT_PROSE.sub(" ", text))))


def _shown(r):
    """Everything a result shows: its messages, its table (HTML without tags) and its repr."""
    table = re.sub(r"<[^>]+>", " ", html.unescape(r._repr_html_()))
    return [*r.messages, table, repr(r)]


def _corpus():
    """(label, a function giving the result) for every answer of the corpus."""
    joint = target("ch13_example1", "1")
    out = []
    for name in ("phi", "jacobian", "nu", "gamma"):
        for k, a in enumerate(MALFORMED + OBJECTS):
            answer = [a] if isinstance(a, str) else a
            out.append((f"{name} #{k}", lambda c=CHECKERS[name], a=answer: c(a, joint)))
        out.append((f"{name} numbers", lambda c=CHECKERS[name]: c([1.0, 2.0], joint)))
    for name, reference in (("value", [1.0, 2.0]), ("rotation", np.eye(3)), ("euler_parameters", [1.0, 0, 0, 0])):
        for k, a in enumerate(MALFORMED + OBJECTS):
            out.append((f"{name} #{k}", lambda c=CHECKERS[name], a=a, e=reference: c(a, e)))
    tryits = all_tryits()
    for t in tryits:  # the chapters' try-its and the exercises' parts, with the wrong answers typed for them
        for k, (a, _) in enumerate(t.wrong):
            out.append((f"{t.id} wrong #{k}", lambda t=t, a=a: t.check(a)))
        for k, a in enumerate(MALFORMED[:12]):
            out.append((f"{t.id} malformed #{k}", lambda t=t, a=a: t.check([a])))
    for p in exercise_parts() + tryit_parts(tryits):  # and the wrong answers generated from kinbook's reference
        for k, (a, _) in enumerate(wrong_answers(p)):
            out.append((f"{p.id} generated #{k}", lambda p=p, a=a: CHECKERS[p.check](a, p.target, **p.options)))
    return out


def test_no_english_reaches_a_student_in_spanish():
    """Every answer of the corpus, checked in Spanish: no English word in its messages, table or repr outside
    quotations, identifiers and Python's own words. The same results shown in English are searched the same way,
    so the search is seen to find English where there is some."""
    corpus = _corpus()
    assert len(corpus) > 2000
    leaks, english = {}, 0
    for label, run in corpus:
        try:
            kinbook.set_language("es")
            r = run()
            for text in _shown(r):
                for line in text.splitlines():
                    if _english_in(line):
                        leaks.setdefault(line[:200], (label, _english_in(line)))
        finally:
            kinbook.set_language("en")
        english += any(_english_in(m) for m in r.messages)
    assert not leaks, "\n".join(f"{v} | {k}" for k, v in leaks.items())
    assert english > 0.9 * len(corpus)
