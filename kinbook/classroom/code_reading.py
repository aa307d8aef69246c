"""Reading a notebook's code as data, for :mod:`kinbook.classroom.reference_use`: the names a call or a target
involves, code given as a literal string (``exec("…")``, ``%time …``), cells in IPython's syntax, and the
places where code could assign a variable unseen. Nothing here runs the code: :func:`ast.parse` parses.
"""

from __future__ import annotations

import ast
import re
import sys
from importlib.machinery import PathFinder

__all__ = ["call_name", "dotted", "target_names", "literal_code", "parsed", "installed", "unfollowable",
           "constant_str", "literal_getattr", "value_path", "parse_cell", "Unread", "CODE_MAGICS", "INERT_MAGICS",
           "IPYTHON_CELL_CHARS", "IPYTHON_CELL_ESCAPES", "IPYTHON_NOTEBOOK_CHARS"]

#: Magics whose argument is code run in the notebook's namespace: followed like the cell's own code.
CODE_MAGICS = frozenset({"time", "timeit", "prun", "capture", "debug"})
#: Magics that cannot assign a variable of the notebook: nothing to follow.
INERT_MAGICS = frozenset({"matplotlib", "precision", "pprint", "who", "whos", "who_ls", "lsmagic", "magic", "pwd",
                          "pinfo", "pinfo2", "pdoc", "pdef", "psource", "history", "xmode", "colors", "page",
                          "config", "notebook", "ls", "env"})
#: Calls and attributes through which code can assign any variable of the notebook unseen.
_ASSIGNING_CALLS = frozenset({"exec", "eval", "compile", "run_cell", "run_line_magic", "run_cell_magic", "globals",
                              "vars", "locals", "setattr", "__import__", "import_module", "reload", "execfile"})
_ASSIGNING_ATTRS = frozenset({"user_ns", "user_global_ns", "__dict__", "__globals__", "__builtins__", "f_globals",
                              "f_locals"})
_ASSIGNING_MODULES = frozenset({"__main__", "builtins", "__builtin__", "importlib", "runpy", "inspect"})


def call_name(node):
    f = node.func
    if isinstance(f, ast.Attribute):
        return f.attr, f"{dotted(f.value)}.{f.attr}()"
    if isinstance(f, ast.Name):
        return f.id, f"{f.id}()"
    return None, None


def dotted(node):
    """``a.b(…).c`` for a chain of names, attributes and calls (iteratively: a chain may be thousands long)."""
    suffix = []
    while isinstance(node, (ast.Attribute, ast.Call)) and len(suffix) < 6:
        if isinstance(node, ast.Attribute):
            suffix.append("." + node.attr)
            node = node.value
        else:
            suffix.append("(…)")
            node = node.func
    head = node.id if isinstance(node, ast.Name) else "…"
    return head + "".join(reversed(suffix)) if len(suffix) < 6 else "…" + "".join(reversed(suffix))


def target_names(target):
    """The variables a target (re)binds, and the variables it changes in place (a[i] = …, a.b = …)."""
    bound, changed = [], []
    if isinstance(target, ast.Name):
        bound.append(target.id)
    elif isinstance(target, (ast.Tuple, ast.List)):
        for t in target.elts:
            b, c = target_names(t.value if isinstance(t, ast.Starred) else t)
            bound += b
            changed += c
    elif isinstance(target, (ast.Subscript, ast.Attribute)):
        base = target.value
        while isinstance(base, (ast.Subscript, ast.Attribute)):
            base = base.value
        if isinstance(base, ast.Name):
            changed.append(base.id)
    return bound, changed


def literal_code(call):
    """The code of ``exec("…")``/``eval("…")``, ``get_ipython().run_line_magic("time", "…")`` or
    ``run_cell_magic("capture", "", "…")`` with literal code, parsed: a list of statements, or an expression
    whose value is the call's (``eval``, ``x = %time expr``); None for any other call, or code that is not
    Python (then it counts as code the analysis cannot follow)."""
    name = call_name(call)[0]
    args = call.args
    if not args or not all(isinstance(a, ast.Constant) and isinstance(a.value, str) for a in args):
        return None
    if name in ("exec", "eval") and len(args) == 1 and not call.keywords:
        return parsed(args[0].value, expression=name == "eval")
    if name == "run_line_magic" and len(args) == 2 and args[0].value in CODE_MAGICS:
        words = args[1].value.split(None, 8)
        for k in range(len(words)):  # `%timeit -n 10 -o expr`: the options first
            if k and not words[k - 1].startswith("-") and not words[k - 1].isdigit():
                break
            code = parsed(args[1].value.split(None, k)[-1] if k else args[1].value, expression=True)
            if code is not None:
                return code
        return None
    if name == "run_cell_magic" and len(args) == 3 and args[0].value in CODE_MAGICS:
        return parsed(args[2].value)
    return None


def parsed(code, expression=False):
    """Statements (a list), or with ``expression`` an expression when ``code`` is one; None when not Python."""
    try:
        return ast.parse(code, mode="eval").body if expression else ast.parse(code).body
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return parsed(code) if expression else None


def installed(module):
    """Whether the top-level module ``module`` is found in the grader's environment (searched, never imported):
    a module the notebook wrote to its own directory is not."""
    if module in sys.builtin_module_names or module in sys.modules:
        return True

    try:
        return PathFinder.find_spec(module, [p for p in sys.path if p not in ("", ".")]) is not None
    except (ImportError, ValueError):
        return False


def unfollowable(tree, cell):
    """The first place in ``tree`` where code could assign any variable unseen, described, or None."""
    for sub in ast.walk(tree):
        if isinstance(sub, ast.Call):
            name = call_name(sub)[0]
            if name in _ASSIGNING_CALLS and literal_code(sub) is None:
                what = name
                if name in ("run_line_magic", "run_cell_magic") and sub.args and isinstance(sub.args[0], ast.Constant):
                    magic = str(sub.args[0].value)
                    if magic in INERT_MAGICS:
                        continue
                    what = ("%%" if name == "run_cell_magic" else "%") + magic
                return f"{what}, cell {cell}"
        elif isinstance(sub, ast.Attribute) and sub.attr in _ASSIGNING_ATTRS:
            return f"{sub.attr}, cell {cell}"
        elif isinstance(sub, ast.Name) and sub.id in _ASSIGNING_MODULES:
            return f"{sub.id}, cell {cell}"
        elif isinstance(sub, (ast.Import, ast.ImportFrom)):
            if isinstance(sub, ast.ImportFrom) and sub.level:
                return f"a relative import, cell {cell}"
            modules = [sub.module] if isinstance(sub, ast.ImportFrom) else [a.name for a in sub.names]
            for module in modules:
                top = (module or "").split(".")[0]
                if top in _ASSIGNING_MODULES or not installed(top):
                    return f"import of {top!r}, which is not an installed module, cell {cell}"
    return None


def constant_str(node):
    return node.value if isinstance(node, ast.Constant) and isinstance(node.value, str) else None


def literal_getattr(node):
    """``getattr(obj, "name")`` as ``(obj, "name")``, or None."""
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "getattr"
            and len(node.args) >= 2 and constant_str(node.args[1]) is not None):
        return node.args[0], constant_str(node.args[1])
    return None


def value_path(node):
    """The nodes an expression's value depends on: all but subscripts' indices (``q[mech.index("phi2")]`` takes
    its value from ``q``; the index only selects)."""
    stack = [node]
    while stack:
        sub = stack.pop()
        yield sub
        for name, child in ast.iter_fields(sub):
            if isinstance(sub, ast.Subscript) and name == "slice":
                continue
            if isinstance(child, ast.AST):
                stack.append(child)
            elif isinstance(child, list):
                stack.extend(c for c in child if isinstance(c, ast.AST))


#: IPython's transformation of a cell costs (lines × magics): it is applied only to a cell that is not plain
#: Python, of at most this many characters and escape lines, and to this many characters in a notebook at most;
#: beyond, the cell is reported as code the analysis does not read.
IPYTHON_CELL_CHARS = 10_000
IPYTHON_CELL_ESCAPES = 10
IPYTHON_NOTEBOOK_CHARS = 20_000
#: A line that IPython would transform (a magic, a shell escape, ``x = %time …``, ``obj?``). Linear in the cell: no
#: part of it can run over a line break (``^\s*`` could, and on ``(`` plus 60,000 newlines it cost seconds of the
#: grader's time per cell, quadratically).
_ESCAPE = re.compile(r"^[^\S\n]*[%!]|=[^\S\n]*[%!]|\?[^\S\n]*$", re.MULTILINE)


def parse_cell(code, budget):
    """The cell's syntax tree as the kernel runs it, or None when it does not run (not Python); raises
    :class:`Unread` when it holds IPython syntax beyond ``budget`` (characters left to transform, a list)."""
    try:
        return ast.parse(code)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        pass
    escapes = len(_ESCAPE.findall(code))
    if not escapes:
        return None
    if len(code) > IPYTHON_CELL_CHARS or escapes > IPYTHON_CELL_ESCAPES or len(code) > budget[0]:
        raise Unread()
    budget[0] -= len(code)
    try:  # magics, shell escapes and `?` help become Python as the kernel makes them before compiling
        # optional dependency: IPython (the grading extra)
        from IPython.core.inputtransformer2 import TransformerManager

        code = TransformerManager().transform_cell(code)
    except Exception:  # IPython missing, or a cell it cannot transform: the kernel could not run it either
        return None
    try:
        return ast.parse(code)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None


class Unread(Exception):
    pass
