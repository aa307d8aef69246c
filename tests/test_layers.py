"""The house has floors and imports point only down: errors → core → planar, spatial → files → examples →
grading → classroom and book (side by side: both build on grading's one model of a graded item, neither on the
other) → cli and the package face. Every import statement counts, the ones inside functions too (read with ast: nothing is
imported). A module may use its own room and the floors below it, never a floor above or a room beside it on its
own floor, and no set of modules may import each other in a circle. No module takes another module's private
name, and no stage branches on a quantity's name (it reads the quantity's declaration).

Files are cut where a concept ends, never at a line count: sizes are a smell to look at, not a rule. Files over
700 lines and functions over 80 are printed by ``python -m tests.test_layers`` (the smell report)."""

import ast
import re
from pathlib import Path

import kinbook

PACKAGE = Path(kinbook.__file__).parent

FLOORS = [
    ("errors",),
    ("i18n",),
    ("core",),
    ("planar", "spatial"),
    ("files",),
    ("examples", "exercises"),
    ("grading",),
    ("classroom", "book"),
    ("cli", "__init__", "__main__"),
]
"""Rooms from the ground up; a module's room is the first part of its name below ``kinbook``."""

FLOOR = {room: k for k, rooms in enumerate(FLOORS) for room in rooms}

VERSION_ONLY = {"__version__"}
"""What a module may take from the package face itself: ``import kinbook`` (its location) or its version. The
face's ``__init__`` has run before any module of the package and imports only the errors; its other names load
lazily, and taking one of them from below would be an upward import."""

PENDING_CIRCLES = {
}
"""Circles known and being removed in another open branch; the test fails when one of them is gone (strike it)."""

MAX_FILE, MAX_FUNCTION = 700, 80
"""Sizes the smell report prints (a smell to look at, not a reason to cut)."""


def module_name(path):
    parts = list(path.relative_to(PACKAGE).with_suffix("").parts)
    parts = ["kinbook", *parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}
MODULES["kinbook.exercises"] = PACKAGE.parent / "exercises" / "__init__.py"  # setup.py maps exercises/ there


def resolve(name, level, here, package):
    """The absolute module a ``from``-import names (``level`` dots relative to the importing module ``here``)."""
    if level == 0:
        return name
    base = here.split(".") if package else here.split(".")[:-1]
    base = base[: len(base) - (level - 1)]
    return ".".join(base + ([name] if name else []))


def imports(name, path):
    """(line, imported kinbook module, names taken or None) for every import in the module, at any depth."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name, None) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = resolve(node.module or "", node.level, name, path.name == "__init__.py")
            for a in node.names:  # `from . import x` imports the submodule x when there is one
                sub = f"{base}.{a.name}"
                found.append((node.lineno, sub, None) if sub in MODULES else (node.lineno, base, {a.name}))
    return [f for f in found if f[1] == "kinbook" or f[1].startswith("kinbook.")]


def existing(module):
    """The module itself, or the nearest package above it that exists."""
    while module not in MODULES and "." in module:
        module = module.rsplit(".", 1)[0]
    return module


def room(module):
    parts = module.split(".")
    return "__init__" if len(parts) == 1 else parts[1]


def face_only(target, names):
    return target == "kinbook" and (names is None or names <= VERSION_ONLY)


def upward(module, target, names):
    """Why importing ``target`` from ``module`` breaks the floors, or None."""
    if face_only(target, names):
        return None
    a, b = room(module), room(existing(target))
    if a == b:
        return None
    if FLOOR[b] > FLOOR[a]:
        return f"floor {FLOOR[a]} ({a}) imports floor {FLOOR[b]} ({b})"
    if FLOOR[b] == FLOOR[a]:
        return f"{a} and {b} stand side by side on floor {FLOOR[a]}"
    return None


GRAPH = {m: sorted({existing(t) for _, t, names in imports(m, p) if not face_only(t, names)} - {m})
         for m, p in MODULES.items()}


def cycles(graph):
    """The strongly connected sets of more than one module (Tarjan's algorithm, iterative), each sorted."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def enter(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        return v, iter(graph.get(v, ()))

    for root in sorted(graph):
        if root in index:
            continue
        work = [enter(root)]
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    work.append(enter(w))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while not comp or comp[-1] != v:
                    comp.append(stack.pop())
                    on.discard(comp[-1])
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def test_every_room_has_a_floor():
    assert {room(m) for m in MODULES} - set(FLOOR) == set()


def test_imports_point_down():
    bad = [f"{MODULES[m].relative_to(PACKAGE.parent)}:{line} imports {target}: {why}"
           for m in MODULES for line, target, names in imports(m, MODULES[m])
           if (why := upward(m, target, names))]
    assert bad == []


def test_no_import_circle():
    found = {frozenset(c): c for c in cycles(GRAPH)}
    assert [c for key, c in found.items() if key not in PENDING_CIRCLES] == []
    assert [sorted(c) for c in PENDING_CIRCLES if c not in found] == [], "no longer a circle: strike it"


def test_the_file_loader_names_no_chapter():
    """Mechanism files name their chapter by its kind; the chapter's own checks run in its Mechanism.validate()."""
    assert [t for _, t, _ in imports("kinbook.files", MODULES["kinbook.files"]) if room(t) in ("planar", "spatial")] == []


def test_the_walk_can_fail():
    assert cycles({"a": ["b"], "b": ["c"], "c": ["a", "d"], "d": []}) == [["a", "b", "c"]]
    assert cycles({"a": ["b"], "b": []}) == []
    assert resolve("errors", 2, "kinbook.core.mechanism", False) == "kinbook.errors"
    assert resolve("", 1, "kinbook.core", True) == "kinbook.core"
    assert upward("kinbook.grading.mistakes", "kinbook.book.errata", {"x"}).startswith("floor 6 (grading)")
    assert upward("kinbook.planar.mechanism", "kinbook.spatial.rotations", {"x"}).endswith("side by side on floor 3")
    assert upward("kinbook.classroom.grade", "kinbook.book.errata", {"x"}).endswith("side by side on floor 7")
    assert upward("kinbook.book.tryits", "kinbook.classroom.variant", {"x"}).endswith("side by side on floor 7")
    assert upward("kinbook.classroom.gradebook", "kinbook", {"__version__"}) is None
    assert upward("kinbook.classroom.gradebook", "kinbook", {"load"}) is not None
    assert upward("kinbook.book.errata", "kinbook.grading.misprints", {"x"}) is None


def sizes(path):
    """(key, size) of the file (lines) and of each function (lines) in it that is too large."""
    text = path.read_text(encoding="utf-8")
    rel = path.relative_to(PACKAGE.parent).as_posix()
    out = [(rel, text.count("\n"))] if text.count("\n") > MAX_FILE else []
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.end_lineno - node.lineno >= MAX_FUNCTION:
            out.append((f"{rel}:{node.name}", node.end_lineno - node.lineno + 1))
    return out


# ------------------------------------------------------------------------------------------ declarations, not branches
QUANTITY_NAMES = {"Phi", "Phi_q", "nu", "gamma", "jacobian"}
"""The graded quantities' names (and the Jacobian checker's): what a stage must not branch on."""


def quantity_branches(path):
    """(line, text) of every comparison with a quantity's name and every table keyed by them that is looked up at
    once (``{"nu": …, "gamma": …}[q]``) — a stage asking "which quantity are you?" instead of reading its
    declaration (kinbook/grading/quantities.py)."""
    def names(node):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return {node.value}
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            return set().union(*(names(e) for e in node.elts)) if node.elts else set()
        return set()

    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Compare) and any(isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn))
                                                 for op in node.ops):
            if any(names(x) & QUANTITY_NAMES for x in [node.left, *node.comparators]):
                out.append((node.lineno, ast.unparse(node)[:80]))
        elif isinstance(node, ast.Subscript) and isinstance(node.value, ast.Dict) and \
                {k.value for k in node.value.keys if isinstance(k, ast.Constant)} & QUANTITY_NAMES:
            out.append((node.lineno, ast.unparse(node)[:80]))
    return out


def test_no_stage_branches_on_a_quantity_name():
    bad = [f"{MODULES[m].relative_to(PACKAGE.parent)}:{line}: {text}" for m in sorted(MODULES)
           if m != "kinbook.grading.quantities" for line, text in quantity_branches(MODULES[m])]
    assert bad == []


def test_the_branch_finder_can_fail(tmp_path):
    f = tmp_path / "m.py"
    f.write_text('if quantity == "Phi_q":\n    pass\nx = q in ("nu", "gamma")\ny = {"nu": 1, "gamma": 2}[q]\n'
                 'z = ev["Phi_q"]\n')
    assert [line for line, _ in quantity_branches(f)] == [1, 3, 4]


# ------------------------------------------------------------------------------------------ private stays private
def private_uses(name, path):
    """(line, "module._name") of every private name of another kinbook module this module takes: imported
    (``from .values import _read``) or reached through an imported module (``sample._spread(...)``). Dunder names
    and a module's own names are not counted; a private *module* with public names (``from ._common import pt``)
    is fine, as in pytransform3d."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out, modules = [], {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("kinbook.") and a.asname:
                    modules[a.asname] = a.name
        elif isinstance(node, ast.ImportFrom):
            base = resolve(node.module or "", node.level, name, path.name == "__init__.py")
            if not (base == "kinbook" or base.startswith("kinbook.")):
                continue
            for a in node.names:
                sub = f"{base}.{a.name}"
                if sub in MODULES:
                    modules[a.asname or a.name] = sub
                elif a.name.startswith("_") and not a.name.startswith("__") and base != name:
                    out.append((node.lineno, f"{base}.{a.name}"))
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in modules \
                and node.attr.startswith("_") and not node.attr.startswith("__") and modules[node.value.id] != name:
            out.append((node.lineno, f"{modules[node.value.id]}.{node.attr}"))
    return out


PRIVATE_PENDING = set()
"""Private names still taken across modules, being made public elsewhere; the test fails when one is gone (strike it)."""


def test_no_module_takes_another_modules_private_name():
    found = {(m, use) for m, p in MODULES.items() for _, use in private_uses(m, p)}
    assert sorted(found - PRIVATE_PENDING) == []
    assert sorted(PRIVATE_PENDING - found) == [], "no longer used: strike it from PRIVATE_PENDING"


def test_the_private_finder_can_fail(tmp_path):
    f = tmp_path / "m.py"
    f.write_text("from .values import _read, check_value\nfrom . import sample\nimport kinbook.core.reader as R\n"
                 "sample._spread(1)\nR._m\nsample.spread\n")
    name = "kinbook.grading.m"
    assert sorted(u for _, u in private_uses(name, f)) == ["kinbook.core.reader._m", "kinbook.grading.sample._spread",
                                                           "kinbook.grading.values._read"]


def _private(attr):
    return attr.startswith("_") and not attr.startswith("__")


def own_private_attributes(tree):
    """The private attribute names a module defines: set on self or cls (``self._x = …``,
    ``object.__setattr__(self, "_x", …)``), or named in a class body (``_x: int``, ``_x = …``, ``def _x``)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    out.add(item.name)
                elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                    out.add(item.target.id)
                elif isinstance(item, ast.Assign):
                    out |= {t.id for t in item.targets if isinstance(t, ast.Name)}
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store) \
                and isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"):
            out.add(node.attr)
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "__setattr__" \
                and len(node.args) >= 2 and isinstance(node.args[1], ast.Constant) \
                and isinstance(node.args[1].value, str):
            out.add(node.args[1].value)
    return {a for a in out if _private(a)}


def private_attribute_uses(trees):
    """{(module, "line: obj._x")} of every ``obj._x`` (obj not self or cls) in a module that does not define ``_x``
    itself, where another kinbook module's class does: ``result._quantity`` in book/tryits reaches into
    grading's CheckResult. Private attributes of other libraries (``sys._getframe``) are not kinbook's to judge."""
    own = {m: own_private_attributes(t) for m, t in trees.items()}
    anywhere = set().union(*own.values())
    found = set()
    for m, tree in trees.items():
        for n in ast.walk(tree):
            if isinstance(n, ast.Attribute) and _private(n.attr) and n.attr in anywhere and n.attr not in own[m] \
                    and not (isinstance(n.value, ast.Name) and n.value.id in ("self", "cls")):
                found.add((m, f"{n.lineno}: {ast.unparse(n)}"))
    return found


def test_no_module_reaches_into_another_modules_private_attributes():
    trees = {m: ast.parse(p.read_text(encoding="utf-8")) for m, p in MODULES.items()}
    assert sorted(private_attribute_uses(trees)) == []


def test_the_private_attribute_finder_can_fail():
    result = ast.parse("class CheckResult:\n    def __init__(self, q):\n        object.__setattr__(self, '_quantity', q)\n"
                       "        self._echo = None\n    def echo(self, other):\n        return other._echo\n")
    user = ast.parse("def f(result, sys):\n    self = result\n    return result._quantity, sys._getframe, self._echo\n")
    found = private_attribute_uses({"kinbook.grading.report": result, "kinbook.book.tryits": user})
    assert found == {("kinbook.book.tryits", "3: result._quantity")}


# ------------------------------------------------------------------------------------------ imports at the top
def in_function_imports(source):
    """(line, statement, reason) of every import inside a function. The reason is the comment on the statement's
    lines or the line above it, a bare ``noqa`` not counted: an import stays in a function only where it breaks a
    real cost (import time of a heavy or optional dependency, a module preloaded on purpose) and says which."""
    lines = source.splitlines()
    found = {}
    for f in ast.walk(ast.parse(source)):
        if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for n in ast.walk(f):
                if isinstance(n, (ast.Import, ast.ImportFrom)) and n.lineno not in found:
                    comments = [line.split("#", 1)[1] for line in lines[n.lineno - 1:n.end_lineno] if "#" in line]
                    above = lines[n.lineno - 2].strip() if n.lineno > 1 else ""
                    comments += [above[1:]] if above.startswith("#") else []
                    reason = " ".join(re.sub(r"noqa(: [A-Z0-9, ]+)?", "", c).strip(" ()") for c in comments).strip()
                    found[n.lineno] = (n.lineno, ast.unparse(n), reason)
    return sorted(found.values())


def worked_answers():
    """{(file, first line, last line)} of the try-its' worked answers (``solution``): their body is the code
    ``kb.reveal`` shows and a student pastes into the notebook, so their imports are the answer's own — absolute,
    and without a comment that the student would read."""
    import inspect

    from kinbook.book import tryits

    tryits._load()
    out = set()
    for item in tryits.TRY_ITS.values():
        lines, first = inspect.getsourcelines(item.solution)
        out.add((Path(inspect.getsourcefile(item.solution)).resolve(), first, first + len(lines) - 1))
    return out


def test_every_in_function_import_says_why():
    shown = worked_answers()
    missing = [f"{m}:{line}: {text}" for m, p in MODULES.items()
               for line, text, reason in in_function_imports(p.read_text(encoding="utf-8")) if len(reason) < 8
               and not any(p.resolve() == f and a <= line <= b for f, a, b in shown)]
    assert missing == []


def test_no_in_function_import_repeats_one_at_the_top():
    shown = worked_answers()
    repeated = []
    for m, p in MODULES.items():
        source = p.read_text(encoding="utf-8")
        top = {ast.unparse(n) for n in ast.parse(source).body if isinstance(n, (ast.Import, ast.ImportFrom))}
        repeated += [f"{m}:{line}: {text}" for line, text, _ in in_function_imports(source) if text in top
                     and not any(p.resolve() == f and a <= line <= b for f, a, b in shown)]
    assert repeated == []


def test_the_import_reason_finder_can_fail():
    source = ("import os\n\ndef f():\n    import os\n    import sympy  # import time: sympy only when needed\n"
              "    import numpy  # noqa: F401\n    # optional dependency: IPython\n    import IPython\n")
    assert [(line, bool(reason)) for line, _, reason in in_function_imports(source)] == [
        (4, False), (5, True), (6, False), (8, True)]


def smell_report():
    """Lines of the files over MAX_FILE and of the functions over MAX_FUNCTION, largest first."""
    found = [item for p in MODULES.values() for item in sizes(p)]
    return sorted(found, key=lambda kv: -kv[1])


if __name__ == "__main__":
    print(f"smells (files over {MAX_FILE} lines, functions over {MAX_FUNCTION}): look at them, cut only at a concept")
    for key, n in smell_report():
        print(f"  {n:5d}  {key}")


def test_the_grading_docstring_names_every_grading_module_once():
    """grading/__init__.py lists its modules, in pipeline order, each with its stage: the list is the map."""
    import re

    import kinbook.grading

    named = re.findall(r"``(\w+)``", kinbook.grading.__doc__.split("The modules, in pipeline order:")[1])
    modules = sorted(p.stem for p in (PACKAGE / "grading").glob("*.py") if p.stem != "__init__")
    assert sorted(named) == modules
