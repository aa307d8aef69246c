"""Which answers a student obtained by calling kinbook's own reference — told to the instructor, not penalized.

A student's kernel sees the kinbook library, so ``Phi = mech.symbolic()[0:2, :]`` gives a correct Φ without
deriving anything. Whatever the kernel reports about itself is under the student's control (the kernel runs
their code), so the evidence used here is the one thing the grader can trust: the submitted notebook's code,
read as data (:func:`ast.parse` parses, it runs nothing) in the grader's process.

:func:`reference_use` follows, cell by cell in order, which names hold values that came from the reference:

* a call of a reference function or method — :data:`REFERENCE_CALLS` (``symbolic()``, ``derivation()``,
  ``constraint_phi()``, a constraint's ``phi()``, ``kinbook.symbolic.derive`` …) — or of a function whose
  body makes one;
* a value given as ``expected=`` to a ``part(...)`` in the notebook (a locked cell may compute it in sight);
* anything computed from such a name (assignments, augmented assignments, ``for`` targets, ``with … as``,
  in-place changes such as ``Phi.extend(ref)`` or ``Phi[0] = ref[0]``).

An answer variable whose final value depends on such a name is reported with the call that started the chain
and its cell (``mech.symbolic() (cell 4)``). Code the analysis cannot follow — ``exec``/``eval``/``compile``,
``getattr`` with a computed name, ``globals()``/``vars()``/``__dict__``, ``importlib`` or ``__import__`` — is
reported as such when an answer depends on it ("dynamic code (getattr), not followed").

Limits (documented in docs/instructors.md): a student who prints the reference in a scratch notebook and
types the printed expression in is not detected (no analysis can tell typing from knowing); flows through
containers of other objects, attributes of objects and function arguments are followed only as far as the
rules above go; the report is information for the instructor, not a verdict.
"""

from __future__ import annotations

import ast

__all__ = ["reference_use", "REFERENCE_CALLS", "DYNAMIC_CALLS"]

#: Methods (``obj.name(...)``) and functions whose result is kinbook's reference for a graded quantity.
REFERENCE_METHODS = frozenset({"symbolic", "derivation", "constraint_phi", "phi", "derive", "time_derivatives",
                               "references"})
REFERENCE_FUNCTIONS = frozenset({"derive", "time_derivatives", "references"})
REFERENCE_CALLS = REFERENCE_METHODS | REFERENCE_FUNCTIONS
#: Calls whose effect a static reading cannot follow.
DYNAMIC_CALLS = frozenset({"exec", "eval", "compile", "getattr", "__import__", "globals", "vars", "locals",
                           "import_module", "setattr", "__getattribute__"})
_MAX_CELLS = 2000


def _call_name(node):
    f = node.func
    if isinstance(f, ast.Attribute):
        return f.attr, f"{_dotted(f.value)}.{f.attr}()"
    if isinstance(f, ast.Name):
        return f.id, f"{f.id}()"
    return None, None


def _dotted(node):
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return f"{_dotted(node.value)}.{node.attr}"
    if isinstance(node, ast.Call):
        return f"{_dotted(node.func)}(…)"
    return "…"


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


class _Flow:
    def __init__(self):
        self.tainted = {}   # name → description of the reference use that reaches it
        self.functions = {}  # function name → description, when its body uses the reference
        self.defined = set()  # functions the notebook defines (a student's own ``derive`` is not kinbook's)

    def origin(self, node, cell):
        """The reference use that ``node`` (an expression) depends on, or None."""
        for sub in ast.walk(node):
            if isinstance(sub, ast.Call):
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
            elif isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load) and sub.id in self.tainted:
                return self.tainted[sub.id]
            elif isinstance(sub, ast.Attribute) and sub.attr in ("__dict__", "__globals__", "__builtins__"):
                return f"dynamic code ({sub.attr}), not followed (cell {cell})"
        return None

    def statement(self, stmt, cell):
        if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Lambda)):
            found = None
            for sub in stmt.body if not isinstance(stmt, ast.Lambda) else [stmt.body]:
                found = found or self.origin(sub, cell)
            self.defined.add(stmt.name)
            if found:
                self.functions[stmt.name] = found
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
        if isinstance(stmt, ast.Try):
            self.block(stmt.body + [s for h in stmt.handlers for s in h.body] + stmt.orelse + stmt.finalbody, cell)
            return
        if isinstance(stmt, ast.Expr):
            value = stmt.value
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


def _parse(code):
    lines = [l for l in code.splitlines() if not l.lstrip().startswith(("%", "!"))]
    try:
        return ast.parse("\n".join(lines))
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None


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
    flow = _Flow()
    for index, code in enumerate(cells[:_MAX_CELLS]):
        tree = _parse(code)
        if tree is not None:
            flow.block(tree.body, index + 1)
    return {name: flow.tainted.get(name, "") for name in answers}
