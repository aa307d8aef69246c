"""What the reader says when it refuses a text (:mod:`kinbook.core.reader`): its reasons and hints, marked for
translation where they are written (:mod:`kinbook.i18n`), so that a refusal reads in the language of the moment
when it is shown — "unknown function '__import__'" / "función desconocida '__import__'"."""

from __future__ import annotations

import ast
import re

from ..i18n import N_, Message, get_language
from .bounds import refuse

__all__ = ["HINTS", "REFUSED_NODES", "NOT_FINITE", "fail", "m", "short", "syntax_reason", "unknown"]

# names people try that are refused with a reason and what to write instead
HINTS = {
    "I": N_("complex numbers are not accepted: kinematic quantities are real"),
    "j": N_("complex numbers are not accepted: kinematic quantities are real"),
    "oo": N_("infinity is not a number kinbook can compute with"),
    "inf": N_("infinity is not a number kinbook can compute with"),
    "nan": N_("NaN is not a number kinbook can compute with"),
    "e": N_("Euler's number is written E (exp(1))"),
    "floor": N_("step functions are not accepted: a prescribed motion needs two continuous derivatives (for ν and γ); "
                "drive each phase in its own sweep, or blend smoothly, e.g. (1 - cos(pi*t))/2"),
    "ceiling": N_("step functions are not accepted: a prescribed motion needs two continuous derivatives (for ν and "
                  "γ); drive each phase in its own sweep, or blend smoothly, e.g. (1 - cos(pi*t))/2"),
    "Heaviside": N_("step functions are not accepted: a prescribed motion needs two continuous derivatives (for ν "
                    "and γ); drive each phase in its own sweep, or blend smoothly, e.g. (1 - cos(pi*t))/2"),
    "Piecewise": N_("piecewise functions are not accepted: a prescribed motion needs two continuous derivatives "
                    "(for ν and γ); drive each phase in its own sweep (mechanism.remove / add a driver)"),
    "Min": N_("Min/Max have corners: write a smooth expression, or drive each phase in its own sweep"),
    "Max": N_("Min/Max have corners: write a smooth expression, or drive each phase in its own sweep"),
    "factorial": N_("factorial is not needed in kinematics (and grows too fast to bound)"),
    "gamma": N_("the gamma function is not available (γ of the acceleration equations is not an input)"),
    "DiracDelta": N_("impulses are not accepted: a prescribed motion needs two continuous derivatives"),
}

REFUSED_NODES = {
    ast.Attribute: N_("attribute access ('.') is not allowed"),
    ast.Subscript: N_("subscripts ('[ ]') are not allowed"),
    ast.Compare: N_("comparisons (<, >, ==) are not expressions of a number"),
    ast.BoolOp: N_("'and' / 'or' are not expressions of a number"),
    ast.IfExp: N_("'if … else' is not allowed; a prescribed motion needs two continuous derivatives"),
    ast.Lambda: N_("lambda is not allowed"),
    ast.List: N_("a list is not an expression of a number"),
    ast.Tuple: N_("a tuple is not an expression of a number (a comma where none belongs?)"),
    ast.Set: N_("a set is not an expression of a number"),
    ast.Dict: N_("a dict is not an expression of a number"),
    ast.Starred: N_("'*' unpacking is not allowed"),
    ast.JoinedStr: N_("strings are not expressions of a number"),
    ast.NamedExpr: N_("':=' is not allowed"),
    ast.Await: N_("'await' is not allowed"),
    ast.Yield: N_("'yield' is not allowed"),
    ast.ListComp: N_("comprehensions are not allowed"),
    ast.GeneratorExp: N_("comprehensions are not allowed"),
    ast.SetComp: N_("comprehensions are not allowed"),
    ast.DictComp: N_("comprehensions are not allowed"),
    ast.Slice: N_("slices are not allowed"),
}
NOT_FINITE = Message(N_("a part of the expression has no finite real value"))


def unknown(plain, hinted, name):
    """"unknown name 'x'", with the hint of :data:`HINTS` for the names people try."""
    return m(hinted, name=name, hint=m(HINTS[name])) if name in HINTS else m(plain, name=name)


def short(text, width=60):
    """The text quoted for a message, cut at ``width`` characters."""
    text = str(text)
    return repr(text if len(text) <= width else text[: width - 1] + "…")


def fail(where, text, reason, expected=None, column=None):
    """Refuse ``text``: "where: reason at column N in 'text'; expected …" (marked messages, written when shown)."""
    refuse(where, reason, text=text, shown=short(text), expected=expected, column=column)


def m(template, **fields):
    """A marked message and its fields."""
    return Message(template, **fields)


class _PythonWords(Message):
    """Python's own words on a syntax error kinbook has no translation for: kept in English, left out of a
    sentence in another language (the column still points at the place)."""

    def __init__(self, words):
        super().__init__(words)

    def render(self, lang=None):
        return f" ({self.template})" if (lang or get_language()) == "en" else ""


_SYNTAX = [  # Python's words on a syntax error -> kinbook's, translated
    (re.compile(r"'(?P<char>.)' was never closed"), N_("'{char}' was never closed")),
    (re.compile(r"unmatched '(?P<char>.)'"), N_("unmatched '{char}'")),
    (re.compile(r"closing parenthesis '(?P<close>.)' does not match opening parenthesis '(?P<open>.)'"),
     N_("closing parenthesis '{close}' does not match opening parenthesis '{open}'")),
    (re.compile(r"invalid decimal literal"), N_("invalid decimal literal")),
    (re.compile(r"invalid imaginary literal"), N_("invalid imaginary literal")),
    (re.compile(r"unterminated string literal"), N_("unterminated string literal")),
    (re.compile(r"unterminated triple-quoted string literal"), N_("unterminated triple-quoted string literal")),
    (re.compile(r"leading zeros in decimal integer literals are not permitted"),
     N_("leading zeros in decimal integer literals are not permitted")),
    (re.compile(r"invalid character '(?P<char>.)'"), N_("invalid character '{char}'")),
    (re.compile(r"unexpected character after line continuation character"),
     N_("unexpected character after line continuation character")),
    (re.compile(r"invalid syntax\. Perhaps you forgot a comma\?"), N_("invalid syntax. Perhaps you forgot a comma?")),
    (re.compile(r"source code string cannot contain null bytes"), N_("source code string cannot contain null bytes")),
]


def syntax_reason(message):
    """The reason of a SyntaxError: "not a valid expression ('(' was never closed)"."""
    detail = (message or "").split(" (")[0].split(";")[0]  # (Python's advice on octal does not apply)
    if not detail or detail == "invalid syntax":
        reason = m(N_("not a valid expression"))
    else:
        for pattern, words in _SYNTAX:
            found = pattern.fullmatch(detail)
            if found:
                reason = m(N_("not a valid expression ({detail})"), detail=m(words, **found.groupdict()))
                break
        else:
            reason = m(N_("not a valid expression{python}"), python=_PythonWords(detail))
    if "decimal literal" in (message or "") or "imaginary literal" in (message or ""):
        reason = m(N_("{reason}; write products with * (2*t, not 2t)"), reason=reason)
    return reason
