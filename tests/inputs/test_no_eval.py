"""No code runs from data: the package calls none of sympify, eval, exec, parse_expr (nor sympy's S(...),
which is sympify) outside the one reader, kinbook.core.reader. Calls are found in the token stream, so a
docstring or comment that names them does not count, and a call spread over lines does."""

import io
import tokenize
from pathlib import Path

import pytest

import kinbook

PACKAGE = Path(kinbook.__file__).parent
FORBIDDEN = {"sympify", "eval", "exec", "parse_expr"}

ALLOWED = {
    "core/reader.py": "the one reader of untrusted text",
    # the instructor's own notebook code, run to build a variant's references (h12 is reworking it)
    "classroom/variant/__init__.py": "instructor code",
    # the library's own worked answers (kinbook.book.tryits), mutated as ASTs for validate --mutations
    "book/tryits/code_mutants.py": "kinbook's own code",
}

# files other engineers are rewriting: they still read text with sympify today (xfail flips when they land)
PENDING = {}


def calls(path):
    """(line, name) of every forbidden call in a Python file."""
    tokens = [t for t in tokenize.generate_tokens(io.StringIO(path.read_text(encoding="utf-8")).readline)
              if t.type not in (tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT)]
    found = []
    for k, tok in enumerate(tokens[:-1]):
        nxt = tokens[k + 1]
        if tok.type != tokenize.NAME or nxt.string != "(":
            continue
        prev = tokens[k - 1].string if k else ""
        before = tokens[k - 2].string if k > 1 else ""
        if tok.string in FORBIDDEN and prev not in ("def", "."):
            found.append((tok.start[0], tok.string))
        elif tok.string in FORBIDDEN and prev == "." and before in ("sp", "sympy", "builtins"):
            found.append((tok.start[0], f"{before}.{tok.string}"))
        elif tok.string == "S" and prev == "." and before in ("sp", "sympy"):
            found.append((tok.start[0], f"{before}.S"))
    return found


FILES = sorted(p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py"))


@pytest.mark.parametrize("name", [
    pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=PENDING[n])) if n in PENDING else n
    for n in FILES if n not in ALLOWED
])
def test_no_code_from_data(name):
    assert calls(PACKAGE / name) == []


def test_the_scan_finds_calls(tmp_path):
    sample = tmp_path / "sample.py"
    sample.write_text('import sympy as sp\n"""sympify(x) in a docstring"""\n# eval(x) in a comment\n'
                      'a = sp.sympify(\n  text)\nb = eval(text)\nc = sp.S(text)\nd = exec (code)\n'
                      'e = ast.literal_eval(text)\ndef eval(x): pass\n')
    assert calls(sample) == [(4, "sp.sympify"), (6, "eval"), (7, "sp.S"), (8, "exec")]


def test_the_allowed_and_pending_files_exist():
    for name in list(ALLOWED) + list(PENDING):
        assert (PACKAGE / name).is_file(), name
