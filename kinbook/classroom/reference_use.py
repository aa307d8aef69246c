"""Which answers a student obtained by calling kinbook's own reference — told to the instructor, not penalized.

A student's kernel sees the kinbook library, so ``Phi = mech.symbolic()[0:2, :]`` gives a correct Φ without
deriving anything. Whatever the kernel reports about itself is under the student's control (the kernel runs
their code), so the evidence used here is the one thing the grader can trust: the submitted notebook's code,
read as data (:func:`ast.parse` parses, it runs nothing) in the grader's process.

:func:`reference_use` follows, cell by cell in order, which names hold values that came from the reference:

* what counts as the reference is the exercise's (:class:`ReferenceCalls`, :func:`exercise_calls`): the
  functions and methods it declares with :func:`kinbook.classroom.reference_calls`, or by default those whose
  results reach its hidden checks' ``expected=`` (ex11: ``kinbook.spatial.A_from_euler``, ``p_from_A``, ``E``,
  ``G``) — and always the Φ family, :data:`REFERENCE_CALLS` (``symbolic()``, ``derivation()``,
  ``constraint_phi()``, a constraint's ``phi()``, ``kinbook.symbolic.derive`` …);
* a function counts when it is kinbook's, however it is reached — ``ks.A_from_euler``, ``import kinbook as kb``,
  ``from kinbook.spatial import A_from_euler as rot``, a ``*`` import, ``getattr(ks, "A_from_euler")``, an alias
  ``f = ks.A_from_euler``, ``functools.partial`` —, never a student's own function of the same name;
* a method counts when its object comes from kinbook (``mech`` loaded by a cell, a constraint of it, anything
  computed from them) — through an alias ``s = mech.symbolic``, ``type(mech).symbolic(mech)``,
  ``operator.methodcaller("symbolic")`` applied or mapped to such an object —, never on the student's own
  objects (a class of theirs with a ``phi()`` method); on an object of unknown origin (a function's parameter)
  it counts unless the notebook's own classes define that method;
* a value given as ``expected=`` to a ``part(...)`` in the notebook (a locked cell may compute it in sight);
* anything computed from such a name: assignments, augmented assignments, ``for`` targets, ``with … as``,
  in-place changes (``Phi.extend(ref)``, ``Phi[0] = ref[0]``), IPython's output history (``_``, ``__``,
  ``Out[n]``, ``_oh``, ``_n`` after a cell whose last expression was the reference), a notebook function that
  sets a ``global`` or changes an argument in place called with a reference value, an exception raised with one
  (its handler's ``as`` name);
* kinbook calls in the release's own locked cells are the instructor's (data the exercise hands out), not the
  student's: what those cells define is followed, their calls are not counted.

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
import builtins
import functools
import re
from dataclasses import dataclass
from pathlib import Path

import kinbook

from .code_reading import (
    IPYTHON_NOTEBOOK_CHARS,
    Unread,
    call_name,
    constant_str,
    dotted,
    literal_code,
    literal_getattr,
    parse_cell,
    parsed,
    target_names,
    unfollowable,
    value_path,
)

__all__ = ["reference_use", "as_run", "exercise_calls", "declared_calls", "ReferenceCalls", "PHI_FAMILY", "REFERENCE_CALLS",
           "DYNAMIC_CALLS", "MAX_CODE_CHARS"]

#: Methods (``obj.name(...)``) and functions whose result is kinbook's reference for a graded quantity.
REFERENCE_METHODS = frozenset({"symbolic", "derivation", "constraint_phi", "phi", "derive", "time_derivatives",
                               "references"})
REFERENCE_FUNCTIONS = frozenset({"derive", "time_derivatives", "references"})
REFERENCE_CALLS = REFERENCE_METHODS | REFERENCE_FUNCTIONS
#: Calls whose effect a static reading cannot follow.
DYNAMIC_CALLS = frozenset({"exec", "eval", "compile", "getattr", "__import__", "globals", "vars", "locals",
                           "import_module", "setattr", "__getattribute__"})
_MAX_CELLS = 2000
_BUILTIN_NAMES = frozenset(dir(builtins))
#: Characters of code analysed at most (about a second of the grader's time; a notebook's own code is a few
#: thousand): beyond, every answer is reported "not followed" rather than spending minutes of the grader's time.
MAX_CODE_CHARS = 300_000


@dataclass(frozen=True)
class ReferenceCalls:
    """What counts as kinbook's reference for one exercise.

    Attributes
    ----------
    functions : frozenset of str
        Names of kinbook functions (``A_from_euler``) — counted when called through kinbook (``ks.A_from_euler``,
        ``from kinbook.spatial import A_from_euler as f``), never a student's own function of that name.
    methods : frozenset of str
        Method names (``symbolic``, ``solve_position``) — counted when the object comes from kinbook (``mech``
        loaded with ``kinbook.examples.load``, a constraint of it), never on a student's own object.
    """

    functions: frozenset = frozenset()
    methods: frozenset = frozenset()

    def __or__(self, other):
        return ReferenceCalls(self.functions | other.functions, self.methods | other.methods)


#: The Φ family: what every exercise counts (a Φ, Φ_q, ν or γ part is checked against these).
PHI_FAMILY = ReferenceCalls(REFERENCE_FUNCTIONS, REFERENCE_METHODS)
#: kinbook's own classroom functions (``part``, ``parameters``) are never an answer.
_NOT_REFERENCE = ("kinbook.classroom",)
_HISTORY = frozenset({"_", "__", "___", "Out", "_oh", "output_hist"})
_HISTORY_N = re.compile(r"_\d+$")
_MUTATORS = frozenset({"append", "extend", "insert", "update", "__setitem__", "setdefault", "add", "put"})


class _Flow:
    """What the notebook's code does with kinbook, statement by statement (see the module docstring)."""

    def __init__(self, calls=PHI_FAMILY, locked=()):
        self.calls = calls
        self.locked = frozenset(locked)  # cells of the release, unchanged: the instructor's, never the student's
        self.cell_locked = False
        self.tainted = {}    # name → description of the reference use that reaches it
        self.functions = {}  # function or class name → description, when its code uses the reference
        self.defined = set()  # functions the notebook defines (a student's own ``derive`` is not kinbook's)
        self.bound = set()   # every name the notebook binds at the top level
        self.kb = {}         # name → qualified kinbook name ("kinbook.spatial"), or "" for an object from kinbook
        self.star = False    # ``from kinbook… import *``
        self.own_methods = set()  # method names the notebook's own classes define
        self.own_classes = {}  # class the notebook defines → the methods it defines
        self.own_instances = {}  # name → the notebook's own class it was made by (``m = M(mech)``)
        self.helpers = {}    # name → "methodcaller", "attrgetter", "partial", "sys", "sys.modules"
        self.callers = {}    # name → (helper, attribute), for ``methodcaller("symbolic")`` objects
        self.setters = {}    # function name → (globals it assigns, whether it changes an argument in place)
        self.history = None  # the reference use shown as the last output (IPython's ``_``, ``Out``)
        self.unfollowed = None  # the first place where code could assign any variable unseen

    # ----------------------------------------------------------------------------------------- kinbook names
    def qualify(self, node):
        """The qualified kinbook name an expression stands for (``kinbook.spatial.A_from_euler``), or None."""
        lit = literal_getattr(node)
        if lit is not None:
            base = self.qualify(lit[0])
            return f"{base}.{lit[1]}" if base else None
        if isinstance(node, ast.Name):
            if node.id in self.kb and self.kb[node.id]:
                return self.kb[node.id]
            if self.star and node.id not in self.bound and node.id in self.calls.functions:
                return f"kinbook.{node.id}"
            return None
        if isinstance(node, ast.Attribute):
            base = self.qualify(node.value)
            return f"{base}.{node.attr}" if base else None
        return None

    def from_kinbook(self, node):
        """Whether an expression's value comes from kinbook (a module, or an object built by kinbook)."""
        for sub in ast.walk(node):
            if isinstance(sub, ast.Name) and (sub.id in self.kb or sub.id in self.tainted):
                return True
        return False

    def unknown(self, node):
        """An object the notebook never binds at the top level (a function's parameter): of unknown origin."""
        base = node
        while isinstance(base, (ast.Attribute, ast.Subscript, ast.Call)):
            base = base.func if isinstance(base, ast.Call) else base.value
        return isinstance(base, ast.Name) and base.id not in self.bound and base.id not in _BUILTIN_NAMES

    def reference_method(self, obj, method):
        """Whether ``obj.method`` is kinbook's reference: a reference method of an object from kinbook (or of an
        unknown object, unless the notebook's own classes define a method of that name)."""
        if method not in self.calls.methods or self.own_object(obj, method):
            return False
        if self.from_kinbook(obj):
            return True
        return self.unknown(obj) and method not in self.own_methods

    def own_object(self, obj, method):
        """Whether ``obj`` is an object of the notebook's own class that defines ``method`` itself (``M(mech)``, or
        a name bound to one): its ``method`` is the student's, whatever kinbook objects it was given."""
        if isinstance(obj, ast.Call) and isinstance(obj.func, ast.Name):
            cls = obj.func.id
        elif isinstance(obj, ast.Name):
            cls = self.own_instances.get(obj.id)
        else:
            return False
        return method in self.own_classes.get(cls, ())

    def reference_function(self, node):
        q = self.qualify(node)
        return (q is not None and q.split(".")[0] == "kinbook" and not q.startswith(_NOT_REFERENCE)
                and q.rsplit(".", 1)[-1] in self.calls.functions)

    def _caller(self, node):
        """``(helper, name)`` of a ``methodcaller("name")`` or ``attrgetter("name")`` expression (or of a name bound
        to one), or None."""
        if isinstance(node, ast.Name):
            return self.callers.get(node.id)
        if isinstance(node, ast.Call) and node.args and constant_str(node.args[0]) is not None:
            f = node.func
            helper = self.helpers.get(f.id) if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) \
                else None
            if helper in ("methodcaller", "attrgetter"):
                return helper, constant_str(node.args[0])
        return None

    def _pending(self, caller, cell):
        """The description of a methodcaller/attrgetter of the reference, or None."""
        if caller is None:
            return None
        helper, name = caller
        if name in self.calls.methods or helper == "attrgetter" and name in self.calls.functions:
            return f"{helper}({name!r}) (cell {cell})"
        return None

    # ----------------------------------------------------------------------------------------------- values
    def origin(self, node, cell):
        """The reference use that ``node`` (an expression) depends on, or None."""
        pending = None  # a methodcaller of a reference method: the reference once applied to a kinbook object
        for sub in ast.walk(node):
            if isinstance(sub, ast.Call):
                code = literal_code(sub)
                if code is not None:  # eval("…"), %time …: the code inside is what gives the value
                    found = self.origin(code, cell) if not isinstance(code, list) else self.block(code, cell)
                    if found:
                        return found
                    continue
                name, text = call_name(sub)
                method = isinstance(sub.func, ast.Attribute)
                pending = pending or self._pending(self._caller(sub.func) or self._caller(sub), cell)
                lit = literal_getattr(sub)
                if lit is not None:
                    if not self.cell_locked and (self.reference_method(lit[0], lit[1])
                                                 or self.reference_function(sub)):
                        return f"getattr({dotted(lit[0])}, {lit[1]!r}) (cell {cell})"
                    continue
                if name in self.defined and not method:
                    if name in self.functions:
                        return self.functions[name]
                    continue
                if name in self.functions and not method:
                    return self.functions[name]
                if name in DYNAMIC_CALLS and not method:
                    return f"dynamic code ({name}), not followed (cell {cell})"
            elif isinstance(sub, ast.Attribute):
                if sub.attr in ("__dict__", "__globals__", "__builtins__") or (
                        sub.attr == "modules" and isinstance(sub.value, ast.Name)
                        and self.helpers.get(sub.value.id) == "sys"):
                    return f"dynamic code ({dotted(sub)}), not followed (cell {cell})"
                if self.cell_locked:
                    continue
                if self.reference_method(sub.value, sub.attr):
                    return f"{dotted(sub.value)}.{sub.attr}() (cell {cell})"
                if self.reference_function(sub):
                    return f"{dotted(sub)}() (cell {cell})"
            elif isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load):
                if sub.id in self.tainted:
                    return self.tainted[sub.id]
                pending = pending or self._pending(self.callers.get(sub.id), cell)  # passed on (map(f, …))
                if self.helpers.get(sub.id) == "sys.modules":
                    return f"dynamic code (sys.modules), not followed (cell {cell})"
                if sub.id in self.functions:  # a function or class of the notebook that uses the reference,
                    return self.functions[sub.id]  # passed as a value (map(f, …), A.Phi)
                if self.history and (sub.id in _HISTORY or _HISTORY_N.match(sub.id)):
                    return self.history
                if not self.cell_locked and sub.id not in self.defined and self.reference_function(sub):
                    return f"{sub.id}() (cell {cell})"
        if pending and self.from_kinbook(node) or pending and self.unknown_args(node):
            return pending
        return None

    def unknown_args(self, node):
        return any(isinstance(sub, ast.Name) and sub.id not in self.bound and sub.id not in _BUILTIN_NAMES
                   and isinstance(sub.ctx, ast.Load) for sub in ast.walk(node)
                   if not isinstance(sub, ast.Name) or not self._caller(sub))

    # ------------------------------------------------------------------------------------------- statements
    def _bind(self, name, value, found):
        """``name`` now holds ``value`` (an expression or None) whose reference use is ``found``."""
        self.bound.add(name)
        self.defined.discard(name)
        self.functions.pop(name, None)
        self.setters.pop(name, None)
        if found:
            self.tainted[name] = found
        else:
            self.tainted.pop(name, None)
        caller = self._caller(value) if value is not None else None
        if caller:
            self.callers[name] = caller
        else:
            self.callers.pop(name, None)
        q = self.qualify(value) if value is not None else None
        own = (value.func.id if isinstance(value, ast.Call) and isinstance(value.func, ast.Name)
               and value.func.id in self.own_classes else None)
        if own:
            self.own_instances[name] = own  # an object of the student's own class, whatever it was given
        else:
            self.own_instances.pop(name, None)
        if q:
            self.kb[name] = q
        elif value is not None and (self.from_kinbook(value) or self.unknown(value)):
            self.kb[name] = ""  # from kinbook — or of unknown origin (a name the notebook never binds)
        else:
            self.kb.pop(name, None)
        if isinstance(value, (ast.Name, ast.Attribute)):
            helper = value.id if isinstance(value, ast.Name) else value.attr
            if helper in ("methodcaller", "attrgetter", "partial") or self.helpers.get(helper):
                self.helpers[name] = self.helpers.get(helper, helper)

    def effects(self, stmt, cell):
        """Calls of the notebook's own functions that set a global, or change an argument in place, from a
        reference value given as an argument."""
        for sub in ast.walk(stmt):
            if not (isinstance(sub, ast.Call) and isinstance(sub.func, ast.Name) and sub.func.id in self.setters):
                continue
            args = list(sub.args) + [k.value for k in sub.keywords]
            found = None
            for arg in args:
                found = found or self.origin(arg, cell)
            if not found:
                continue
            names, mutates = self.setters[sub.func.id]
            for name in names:
                self.tainted[name] = found
            if mutates:
                for arg in args:
                    if isinstance(arg, ast.Name):
                        self.tainted.setdefault(arg.id, found)

    def statement(self, stmt, cell):
        for sub in ast.walk(stmt):  # `(Phi := ref)` anywhere in the statement binds Phi
            if isinstance(sub, ast.NamedExpr) and isinstance(sub.target, ast.Name):
                self._bind(sub.target.id, sub.value, self.origin(sub.value, cell))
        self.effects(stmt, cell)
        if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            self._definition(stmt, cell)
        elif isinstance(stmt, (ast.Import, ast.ImportFrom)):
            self._import(stmt, cell)
        elif isinstance(stmt, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            self._assignment(stmt, cell)
        elif isinstance(stmt, (ast.For, ast.AsyncFor)):
            found = self.origin(stmt.iter, cell)
            for name in target_names(stmt.target)[0]:
                self._bind(name, stmt.iter if self.from_kinbook(stmt.iter) else None, found)
            self.block(stmt.body + stmt.orelse, cell)
        elif isinstance(stmt, (ast.With, ast.AsyncWith)):
            self._with(stmt, cell)
        elif isinstance(stmt, (ast.If, ast.While)):
            self.block(stmt.body + stmt.orelse, cell)
        elif isinstance(stmt, ast.Match):
            self.block([s for case in stmt.cases for s in case.body], cell)
        elif isinstance(stmt, (ast.Try, getattr(ast, "TryStar", ast.Try))):
            self._try(stmt, cell)
        elif isinstance(stmt, ast.Expr):
            self._expression(stmt.value, cell)

    def _definition(self, stmt, cell):
        """A function or class: its body, default values, decorators and bases — whatever it returns or sets may be
        the reference."""
        found = None
        if isinstance(stmt, ast.ClassDef):
            self.own_methods |= {f.name for f in stmt.body if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))}
        for part in (stmt.body + stmt.decorator_list
                     + (stmt.bases + [k.value for k in stmt.keywords] if isinstance(stmt, ast.ClassDef)
                        else stmt.args.defaults + [d for d in stmt.args.kw_defaults if d is not None])):
            found = found or self.origin(part, cell)
        self._bind(stmt.name, None, None)
        self.defined.add(stmt.name)
        self.own_classes.pop(stmt.name, None)
        if isinstance(stmt, ast.ClassDef):
            self.own_classes[stmt.name] = {f.name for f in stmt.body
                                           if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))}
        glob = [n for sub in ast.walk(stmt) if isinstance(sub, (ast.Global, ast.Nonlocal)) for n in sub.names]
        if found:
            self.functions[stmt.name] = found
            for name in glob:  # `global Phi` in it: Phi may be set from the reference when it runs
                self.tainted[name] = found
        if not isinstance(stmt, ast.ClassDef):
            params = {a.arg for a in stmt.args.args + stmt.args.posonlyargs + stmt.args.kwonlyargs}
            mutates = any(
                isinstance(sub, ast.Call) and isinstance(sub.func, ast.Attribute) and sub.func.attr in _MUTATORS
                and isinstance(sub.func.value, ast.Name) and sub.func.value.id in params
                or isinstance(sub, (ast.Assign, ast.AugAssign)) and any(
                    isinstance(t, (ast.Subscript, ast.Attribute)) and isinstance(t.value, ast.Name)
                    and t.value.id in params for t in (sub.targets if isinstance(sub, ast.Assign) else [sub.target]))
                for sub in ast.walk(stmt))
            if glob or mutates:
                self.setters[stmt.name] = (glob, mutates)

    def _import(self, stmt, cell):
        module = getattr(stmt, "module", None) or ""
        for alias in stmt.names:
            if alias.name == "*":
                self.star = self.star or module.split(".")[0] == "kinbook"
                continue
            name = alias.asname or alias.name.split(".")[0]
            self._bind(name, None, None)
            if isinstance(stmt, ast.Import):
                qual = alias.name if alias.asname else alias.name.split(".")[0]
            else:
                qual = f"{module}.{alias.name}"
            if qual.split(".")[0] == "kinbook":
                self.kb[name] = qual
                if alias.name in self.calls.functions and not qual.startswith(_NOT_REFERENCE) \
                        and not self.cell_locked:
                    self.functions[name] = f"{module}.{alias.name} (cell {cell})"
            if qual in ("operator.methodcaller", "operator.attrgetter", "functools.partial") \
                    or alias.name in ("operator", "functools", "sys"):
                self.helpers[name] = alias.name.rsplit(".", 1)[-1]
            if qual == "sys.modules":
                self.helpers[name] = "sys.modules"

    def _assignment(self, stmt, cell):
        value = stmt.value
        targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
        found = self.origin(value, cell) if value is not None else None
        for target in targets:
            bound, changed = target_names(target)
            if isinstance(stmt, ast.AugAssign):
                changed, bound = changed + bound, []
            for name in bound:
                self._bind(name, value if len(bound) == 1 and isinstance(target, ast.Name) else
                           (value if value is not None and self.from_kinbook(value) else None), found)
            for name in changed:
                if found:
                    self.tainted.setdefault(name, found)
        self._part_expected(value, cell)

    def _with(self, stmt, cell):
        for item in stmt.items:
            found = self.origin(item.context_expr, cell)
            if item.optional_vars is not None:
                for name in target_names(item.optional_vars)[0]:
                    self._bind(name, None, found)
        self.block(stmt.body, cell)

    def _try(self, stmt, cell):
        self.block(stmt.body, cell)
        raised = None  # a reference value carried by an exception raised in the body: its handler's name
        for sub in ast.walk(ast.Module(body=stmt.body, type_ignores=[])):
            if isinstance(sub, ast.Raise) and sub.exc is not None:
                raised = raised or self.origin(sub.exc, cell)
        for h in stmt.handlers:
            if h.name:
                self._bind(h.name, None, raised)
            self.block(h.body, cell)
        self.block(stmt.orelse + stmt.finalbody, cell)

    def _expression(self, value, cell):
        code = literal_code(value) if isinstance(value, ast.Call) else None
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
            if isinstance(sub, ast.Call) and call_name(sub)[0] == "part":
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

    def cell(self, tree, cell):
        """One cell: its statements, then what IPython keeps of its last expression (``_``, ``Out[n]``)."""
        self.cell_locked = cell in self.locked
        self.block(tree.body, cell)
        last = tree.body[-1] if tree.body else None
        if isinstance(last, ast.Expr):
            found = self.origin(last.value, cell)
            if found:
                self.history = found
        self.cell_locked = False


def declared_calls(code):
    """What ``reference_calls("kinbook.spatial.A_from_euler", ".solve_position", "E")`` calls in ``code``
    declare (literal strings only), or None when there is none."""
    found = None
    for tree in (parsed(c) for c in code):
        for sub in ast.walk(ast.Module(body=tree or [], type_ignores=[])):
            if isinstance(sub, ast.Call) and call_name(sub)[0] == "reference_calls":
                found = found or ReferenceCalls()
                for arg in sub.args:
                    text = constant_str(arg)
                    if not text:
                        continue
                    name = text.rsplit(".", 1)[-1]
                    if text.startswith("."):
                        found |= ReferenceCalls(methods=frozenset({name}))
                    elif "." in text:
                        found |= ReferenceCalls(functions=frozenset({name}))
                    else:
                        found |= ReferenceCalls(frozenset({name}), frozenset({name}))
    return found


def exercise_calls(segments):
    """What counts as the reference in one exercise, read from its source's code (never run here).

    Parameters
    ----------
    segments : list of (kind, code)
        The source's code as the grader reads it (:func:`kinbook.classroom.notebook.grader_segments`): kind
        ``"code"`` or ``"hidden"``.

    Returns
    -------
    ReferenceCalls
        What the source declares with :func:`kinbook.classroom.reference_calls`, if it does; else the kinbook
        functions and methods whose results reach a hidden check's ``expected=`` (through assignments, along the
        values — not through indices) — and always the Φ family.
    """
    declared = declared_calls([code for _, code in segments])
    if declared is not None:
        return PHI_FAMILY | declared
    flow = _Flow()
    deps = {}
    found, visible = set(), set()

    def calls_in(expr, path=True):
        out = set()
        for sub in (value_path(expr) if path else ast.walk(expr)):
            if isinstance(sub, ast.Call):
                q = flow.qualify(sub.func)
                if q is not None:
                    if q.split(".")[0] == "kinbook" and not q.startswith(_NOT_REFERENCE):
                        out.add(("f", q.rsplit(".", 1)[-1]))
                elif isinstance(sub.func, ast.Attribute) and flow.from_kinbook(sub.func.value):
                    out.add(("m", sub.func.attr))
            elif isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load):
                out |= deps.get(sub.id, set())
        return out

    for kind, code in segments:
        tree = parsed(code)
        for stmt in tree or []:
            if kind != "hidden":
                visible |= calls_in(stmt, path=False)
            for sub in ast.walk(stmt):
                if isinstance(sub, ast.Assign):
                    through = calls_in(sub.value)
                    for target in sub.targets:
                        for name in target_names(target)[0]:
                            deps[name] = through
                elif kind == "hidden" and isinstance(sub, ast.Call) and call_name(sub)[0] == "part":
                    for k in sub.keywords:
                        if k.arg == "expected":
                            found |= calls_in(k.value)
            flow.statement(stmt, 0)
    found -= visible  # what the release's own code calls is a tool it hands out (loading the mechanism …)
    return PHI_FAMILY | ReferenceCalls(frozenset(n for k, n in found if k == "f"),
                                       frozenset(n for k, n in found if k == "m" and kinbook_method(n)))


@functools.lru_cache(maxsize=1)
def _kinbook_text():
    return "\n".join(p.read_text(encoding="utf-8", errors="replace") for p in Path(kinbook.__file__).parent.rglob("*.py")
                     if "sandbox" not in p.parts)


@functools.lru_cache(maxsize=None)
def kinbook_method(name):
    """Whether one of kinbook's classes has a public method ``name`` (``solve_position``, ``phi`` …; read from
    its source, nothing imported): a method call counts as the reference only under such a name, not as
    ``.max()`` of an array computed with kinbook."""
    return not name.startswith("_") and re.search(rf"^[ \t]+def {re.escape(name)}\(\s*(self|cls)\b", _kinbook_text(),
                                                  re.MULTILINE) is not None


def reference_use(cells, answers, calls=None, locked=(), numbers=None):
    """For each answer name, how its value came from kinbook's reference, or "" (see the module docstring).

    Parameters
    ----------
    cells : list of str
        The submission's code cells, in order (the cells that were run).
    answers : iterable of str
        Answer variable names.
    calls : ReferenceCalls, optional
        What counts as the reference (default: the Φ family; an exercise's own: :func:`exercise_calls`).
    locked : iterable of int
        Cells (from 1) that are the release's own, unchanged: the instructor's code, whose kinbook calls are not the
        student's (what they define is followed all the same).
    numbers : list of int, optional
        The number the student sees for each cell (its position among all the notebook's cells, markdown
        included); by default 1, 2, 3 … The descriptions name cells by these numbers.

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
    numbers = list(numbers) if numbers is not None else list(range(1, len(cells) + 1))
    flow = _Flow(PHI_FAMILY | calls if calls is not None else PHI_FAMILY,
                 {numbers[i - 1] for i in locked if 0 < i <= len(numbers)})
    budget = [IPYTHON_NOTEBOOK_CHARS]
    for index, code in enumerate(cells[:_MAX_CELLS]):
        try:
            tree = parse_cell(code, budget)
        except Unread:
            flow.unfollowed = flow.unfollowed or f"IPython syntax the analysis does not read, cell {numbers[index]}"
            continue
        if tree is None:
            continue
        try:
            flow.cell(tree, numbers[index])
            flow.unfollowed = flow.unfollowed or unfollowable(tree, numbers[index])
        except RecursionError:  # code nested beyond what the analysis follows: said so, not a grader failure
            return {name: f"not followed: code nested too deeply (cell {numbers[index]})" for name in answers}
    unseen = f"not followed: code that could assign it unseen ({flow.unfollowed})" if flow.unfollowed else ""
    return {name: flow.tainted.get(name) or unseen for name in answers}


def as_run(used, observed, locked=(), numbers=None):
    """Add to ``used`` (:func:`reference_use`'s answer, changed in place) the reference use observed as the notebook
    ran (:mod:`kinbook.classroom.sandbox.trace`): ``observed`` is ``{name: [(function, code cell, same object), …]}``.
    An answer the code shows no use for (or could not follow) reads "….constraint_phi() (cell 5, as run)" — "as run:
    equal to its result" for a copy; calls in the release's ``locked`` code cells do not count; what the code shows
    is never replaced. ``numbers``: each code cell's position among all cells, as the student sees them."""
    for name, calls in observed.items():
        seen = [(key, cell, same) for key, cell, same in calls
                if cell not in locked and (numbers is None or 0 < cell <= len(numbers))]
        if name in used and seen and (not used[name] or used[name].startswith("not followed")):
            key, cell, same = seen[0]
            shown = numbers[cell - 1] if numbers is not None else cell
            used[name] = f"{key}() (cell {shown}, as run" + ("" if same else ": equal to its result") + ")"
    return used
