"""Which answers a student obtained by calling kinbook's own reference — told to the instructor, not penalized.

A student's kernel sees the kinbook library, so ``Phi = mech.symbolic()[0:2, :]`` gives a correct Φ without
deriving anything. Whatever the kernel reports about itself is under the student's control (the kernel runs
their code), so the evidence used here is the one thing the grader can trust: the submitted notebook's code,
read as data (:func:`ast.parse` parses, it runs nothing) in the grader's process.

:func:`reference_use` follows, cell by cell in order, which names hold values that came from the reference:

* a call of a reference function or method — :data:`REFERENCE_CALLS` (``symbolic()``, ``derivation()``,
  ``constraint_phi()``, a constraint's ``phi()``, ``kinbook.core.symbolic.derive`` …) — or of a function whose
  body makes one;
* a value given as ``expected=`` to a ``part(...)`` in the notebook (a locked cell may compute it in sight);
* anything computed from such a name (assignments, augmented assignments, ``for`` targets, ``with … as``,
  in-place changes such as ``Phi.extend(ref)`` or ``Phi[0] = ref[0]``).

An answer variable whose final value depends on such a name is reported with the call that started the chain
and its cell (``mech.symbolic() (cell 4)``). Code the analysis cannot follow — ``getattr`` with a computed name,
``globals()``/``vars()``/``__dict__``, ``importlib`` or ``__import__`` — is reported as such when an answer
depends on it ("dynamic code (getattr), not followed").

The cells are read as the kernel runs them: IPython's own input transformation first (``%time``, ``!ls``,
``x = %timeit …`` are not Python, and a cell holding one would otherwise be skipped whole); the code given to
``%time``/``%timeit``/``%%capture``/``%%time`` and to ``exec``/``eval`` as a literal string is followed like the
cell's own. Code that could assign any variable unseen — ``exec`` of a computed string, other magics
(``%run``), ``setattr``/``globals()``, ``get_ipython().user_ns``, ``import __main__``, an import of a module
that is not installed (a file the notebook wrote) — makes every answer that has no reference use of its own
"not followed" (with the first such place), so that it cannot hide one.

Limits (documented in docs/instructors.md): a student who prints the reference in a scratch notebook and
types the printed expression in is not detected (no analysis can tell typing from knowing); flows through
containers of other objects, attributes of objects and function arguments are followed only as far as the
rules above go; the report is information for the instructor, not a verdict.
"""

from __future__ import annotations

import ast
import re
import sys

__all__ = ["reference_use", "REFERENCE_CALLS", "DYNAMIC_CALLS", "MAX_CODE_CHARS"]

#: Methods (``obj.name(...)``) and functions whose result is kinbook's reference for a graded quantity.
REFERENCE_METHODS = frozenset({"symbolic", "derivation", "constraint_phi", "phi", "derive", "time_derivatives",
                               "references"})
REFERENCE_FUNCTIONS = frozenset({"derive", "time_derivatives", "references"})
REFERENCE_CALLS = REFERENCE_METHODS | REFERENCE_FUNCTIONS
#: Calls whose effect a static reading cannot follow.
DYNAMIC_CALLS = frozenset({"exec", "eval", "compile", "getattr", "__import__", "globals", "vars", "locals",
                           "import_module", "setattr", "__getattribute__"})
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
_MAX_CELLS = 2000
#: Characters of code analysed at most (about a second of the grader's time; a notebook's own code is a few
#: thousand): beyond, every answer is reported "not followed" rather than spending minutes of the grader's time.
MAX_CODE_CHARS = 300_000


def _call_name(node):
    f = node.func
    if isinstance(f, ast.Attribute):
        return f.attr, f"{_dotted(f.value)}.{f.attr}()"
    if isinstance(f, ast.Name):
        return f.id, f"{f.id}()"
    return None, None


def _dotted(node):
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


def _target_names(target):
    """The variables a target (re)binds, and the variables it changes in place (a[i] = …, a.b = …)."""
    bound, changed = [], []
    if isinstance(target, ast.Name):
        bound.append(target.id)
    elif isinstance(target, (ast.Tuple, ast.List)):
        for t in target.elts:
            b, c = _target_names(t.value if isinstance(t, ast.Starred) else t)
            bound += b
            changed += c
    elif isinstance(target, (ast.Subscript, ast.Attribute)):
        base = target.value
        while isinstance(base, (ast.Subscript, ast.Attribute)):
            base = base.value
        if isinstance(base, ast.Name):
            changed.append(base.id)
    return bound, changed


def _literal_code(call):
    """The code of ``exec("…")``/``eval("…")``, ``get_ipython().run_line_magic("time", "…")`` or
    ``run_cell_magic("capture", "", "…")`` with literal code, parsed: a list of statements, or an expression
    whose value is the call's (``eval``, ``x = %time expr``); None for any other call, or code that is not
    Python (then it counts as code the analysis cannot follow)."""
    name = _call_name(call)[0]
    args = call.args
    if not args or not all(isinstance(a, ast.Constant) and isinstance(a.value, str) for a in args):
        return None
    if name in ("exec", "eval") and len(args) == 1 and not call.keywords:
        return _parsed(args[0].value, expression=name == "eval")
    if name == "run_line_magic" and len(args) == 2 and args[0].value in CODE_MAGICS:
        words = args[1].value.split(None, 8)
        for k in range(len(words)):  # `%timeit -n 10 -o expr`: the options first
            if k and not words[k - 1].startswith("-") and not words[k - 1].isdigit():
                break
            code = _parsed(args[1].value.split(None, k)[-1] if k else args[1].value, expression=True)
            if code is not None:
                return code
        return None
    if name == "run_cell_magic" and len(args) == 3 and args[0].value in CODE_MAGICS:
        return _parsed(args[2].value)
    return None


def _parsed(code, expression=False):
    """Statements (a list), or with ``expression`` an expression when ``code`` is one; None when not Python."""
    try:
        return ast.parse(code, mode="eval").body if expression else ast.parse(code).body
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return _parsed(code) if expression else None


def _installed(module):
    """Whether the top-level module ``module`` is found in the grader's environment (searched, never imported):
    a module the notebook wrote to its own directory is not."""
    if module in sys.builtin_module_names or module in sys.modules:
        return True
    from importlib.machinery import PathFinder

    try:
        return PathFinder.find_spec(module, [p for p in sys.path if p not in ("", ".")]) is not None
    except (ImportError, ValueError):
        return False


def _unfollowable(tree, cell):
    """The first place in ``tree`` where code could assign any variable unseen, described, or None."""
    for sub in ast.walk(tree):
        if isinstance(sub, ast.Call):
            name = _call_name(sub)[0]
            if name in _ASSIGNING_CALLS and _literal_code(sub) is None:
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
                if top in _ASSIGNING_MODULES or not _installed(top):
                    return f"import of {top!r}, which is not an installed module, cell {cell}"
    return None


class _Flow:
    def __init__(self):
        self.tainted = {}   # name → description of the reference use that reaches it
        self.functions = {}  # function or class name → description, when its code uses the reference
        self.defined = set()  # functions the notebook defines (a student's own ``derive`` is not kinbook's)
        self.unfollowed = None  # the first place where code could assign any variable unseen

    def origin(self, node, cell):
        """The reference use that ``node`` (an expression) depends on, or None."""
        for sub in ast.walk(node):
            if isinstance(sub, ast.Call):
                code = _literal_code(sub)
                if code is not None:  # eval("…"), %time …: the code inside is what gives the value
                    found = self.origin(code, cell) if not isinstance(code, list) else self.block(code, cell)
                    if found:
                        return found
                    continue
                name, text = _call_name(sub)
                method = isinstance(sub.func, ast.Attribute)
                if name in self.defined and not method:
                    if name in self.functions:
                        return self.functions[name]
                    continue
                if name in self.functions:
                    return self.functions[name]
                if (name in REFERENCE_METHODS) if method else (name in REFERENCE_FUNCTIONS):
                    return f"{text} (cell {cell})"
                if name in DYNAMIC_CALLS:
                    return f"dynamic code ({name}), not followed (cell {cell})"
            elif isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load):
                if sub.id in self.tainted:
                    return self.tainted[sub.id]
                if sub.id in self.functions:  # a function or class of the notebook that uses the reference,
                    return self.functions[sub.id]  # passed as a value (map(f, …), A.Phi)
            elif isinstance(sub, ast.Attribute) and sub.attr in ("__dict__", "__globals__", "__builtins__"):
                return f"dynamic code ({sub.attr}), not followed (cell {cell})"
        return None

    def statement(self, stmt, cell):
        for sub in ast.walk(stmt):  # `(Phi := ref)` anywhere in the statement binds Phi
            if isinstance(sub, ast.NamedExpr) and isinstance(sub.target, ast.Name):
                found = self.origin(sub.value, cell)
                if found:
                    self.tainted[sub.target.id] = found
                else:
                    self.tainted.pop(sub.target.id, None)
        if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            # its body, default values, decorators and bases: whatever it returns or sets may be the reference
            found = None
            for part in (stmt.body + stmt.decorator_list
                         + (stmt.bases + [k.value for k in stmt.keywords] if isinstance(stmt, ast.ClassDef)
                            else stmt.args.defaults + [d for d in stmt.args.kw_defaults if d is not None])):
                found = found or self.origin(part, cell)
            self.defined.add(stmt.name)
            if found:
                self.functions[stmt.name] = found
                for sub in ast.walk(stmt):  # `global Phi` in it: Phi may be set from the reference when it runs
                    if isinstance(sub, (ast.Global, ast.Nonlocal)):
                        for name in sub.names:
                            self.tainted[name] = found
            else:
                self.functions.pop(stmt.name, None)
            return
        if isinstance(stmt, (ast.Import, ast.ImportFrom)):
            module = getattr(stmt, "module", None) or ""
            for alias in stmt.names:
                name = alias.asname or alias.name.split(".")[0]
                self.defined.discard(name)
                if alias.name in REFERENCE_FUNCTIONS:
                    self.functions[name] = f"{module}.{alias.name} (cell {cell})"
            return
        if isinstance(stmt, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            value = stmt.value
            targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
            found = self.origin(value, cell) if value is not None else None
            for target in targets:
                bound, changed = _target_names(target)
                if isinstance(stmt, ast.AugAssign):
                    changed, bound = changed + bound, []
                for name in bound:
                    if found:
                        self.tainted[name] = found
                    else:
                        self.tainted.pop(name, None)
                for name in changed:
                    if found:
                        self.tainted.setdefault(name, found)
            self._part_expected(value, cell)
            return
        if isinstance(stmt, (ast.For, ast.AsyncFor)):
            found = self.origin(stmt.iter, cell)
            if found:
                for name in _target_names(stmt.target)[0]:
                    self.tainted[name] = found
            self.block(stmt.body + stmt.orelse, cell)
            return
        if isinstance(stmt, (ast.With, ast.AsyncWith)):
            for item in stmt.items:
                found = self.origin(item.context_expr, cell)
                if found and item.optional_vars is not None:
                    for name in _target_names(item.optional_vars)[0]:
                        self.tainted[name] = found
            self.block(stmt.body, cell)
            return
        if isinstance(stmt, (ast.If, ast.While)):
            self.block(stmt.body + stmt.orelse, cell)
            return
        if isinstance(stmt, ast.Match):
            self.block([s for case in stmt.cases for s in case.body], cell)
            return
        if isinstance(stmt, (ast.Try, getattr(ast, "TryStar", ast.Try))):
            self.block(stmt.body + [s for h in stmt.handlers for s in h.body] + stmt.orelse + stmt.finalbody, cell)
            return
        if isinstance(stmt, ast.Expr):
            value = stmt.value
            code = _literal_code(value) if isinstance(value, ast.Call) else None
            if code is not None:  # exec("…"), %time …, %%capture
                if isinstance(code, list):
                    self.block(code, cell)
                else:
                    self.statement(ast.Expr(code), cell)
                return
            self._part_expected(value, cell)
            # an in-place change: answer.extend(ref), answer.append(ref), answer.__setitem__ …
            if isinstance(value, ast.Call) and isinstance(value.func, ast.Attribute):
                base = value.func.value
                while isinstance(base, (ast.Attribute, ast.Subscript)):
                    base = base.value
                found = None
                for arg in list(value.args) + [k.value for k in value.keywords]:
                    found = found or self.origin(arg, cell)
                if found and isinstance(base, ast.Name):
                    self.tainted.setdefault(base.id, found)

    def _part_expected(self, node, cell):
        """``part(..., expected=X)``: the variable X (or X[…], X.attr) holds the reference value of that part."""
        if node is None:
            return
        for sub in ast.walk(node):
            if isinstance(sub, ast.Call) and _call_name(sub)[0] == "part":
                for k in sub.keywords:
                    if k.arg == "expected":
                        base = k.value
                        while isinstance(base, (ast.Subscript, ast.Attribute)):
                            base = base.value
                        if isinstance(base, ast.Name):
                            self.tainted[base.id] = f"the expected value of a part(...) (cell {cell})"

    def block(self, stmts, cell):
        for s in stmts:
            self.statement(s, cell)


#: IPython's transformation of a cell costs (lines × magics): it is applied only to a cell that is not plain
#: Python, of at most this many characters and escape lines, and to this many characters in a notebook at most;
#: beyond, the cell is reported as code the analysis does not read.
IPYTHON_CELL_CHARS = 10_000
IPYTHON_CELL_ESCAPES = 10
IPYTHON_NOTEBOOK_CHARS = 20_000
_ESCAPE = re.compile(r"^\s*[%!]|=\s*[%!]|\?\s*$", re.MULTILINE)


def _parse(code, budget):
    """The cell's syntax tree as the kernel runs it, or None when it does not run (not Python); raises
    :class:`_Unread` when it holds IPython syntax beyond ``budget`` (characters left to transform, a list)."""
    try:
        return ast.parse(code)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        pass
    escapes = len(_ESCAPE.findall(code))
    if not escapes:
        return None
    if len(code) > IPYTHON_CELL_CHARS or escapes > IPYTHON_CELL_ESCAPES or len(code) > budget[0]:
        raise _Unread()
    budget[0] -= len(code)
    try:  # magics, shell escapes and `?` help become Python as the kernel makes them before compiling
        from IPython.core.inputtransformer2 import TransformerManager

        code = TransformerManager().transform_cell(code)
    except Exception:  # IPython missing, or a cell it cannot transform: the kernel could not run it either
        return None
    try:
        return ast.parse(code)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None


class _Unread(Exception):
    pass


def reference_use(cells, answers):
    """For each answer name, how its value came from kinbook's reference, or "" (see the module docstring).

    Parameters
    ----------
    cells : list of str
        The submission's code cells, in order (the cells that were run).
    answers : iterable of str
        Answer variable names.

    Returns
    -------
    dict
        {name: description or ""}.

    Examples
    --------
    >>> reference_use(["ref = mech.symbolic()", "Phi = ref[0:2, :]", "angle = 1.0"], ["Phi", "angle"])
    {'Phi': 'mech.symbolic() (cell 1)', 'angle': ''}
    """
    size = sum(len(code) for code in cells[:_MAX_CELLS])
    if size > MAX_CODE_CHARS:
        why = f"not followed: {size:,} characters of code (at most {MAX_CODE_CHARS:,} are analysed)"
        return {name: why for name in answers}
    flow = _Flow()
    budget = [IPYTHON_NOTEBOOK_CHARS]
    for index, code in enumerate(cells[:_MAX_CELLS]):
        try:
            tree = _parse(code, budget)
        except _Unread:
            flow.unfollowed = flow.unfollowed or f"IPython syntax the analysis does not read, cell {index + 1}"
            continue
        if tree is None:
            continue
        try:
            flow.block(tree.body, index + 1)
            flow.unfollowed = flow.unfollowed or _unfollowable(tree, index + 1)
        except RecursionError:  # code nested beyond what the analysis follows: said so, not a grader failure
            return {name: f"not followed: code nested too deeply (cell {index + 1})" for name in answers}
    unseen = f"not followed: code that could assign it unseen ({flow.unfollowed})" if flow.unfollowed else ""
    return {name: flow.tainted.get(name) or unseen for name in answers}
