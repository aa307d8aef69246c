"""Every notebook "Try it" can be answered and checked: the worked answer passes its own check, the blank
placeholder gets "not answered yet", and the notebooks and the registry agree."""

import ast
import json
import pathlib
import re

import pytest

from kinbook.book import tryits
from kinbook.book.tryits import TRY_ITS, NotAnswered

tryits._load()
CHAPTERS = pathlib.Path(__file__).resolve().parents[2] / "chapters"
CALL = re.compile(r"kb\.try_it\(\"([^\"]+)\",\s*(\w+)\)")


@pytest.mark.parametrize("item", list(TRY_ITS.values()), ids=list(TRY_ITS))
def test_the_worked_answer_passes_and_the_blank_is_not_answered(item):
    result = item.check(item.reference_answer())
    assert result.passed, f"{item.id}: the worked answer fails its own check: {result!r}"
    blank = tryits.try_it(item.id, ...)
    assert isinstance(blank, NotAnswered) and not blank
    assert "not answered yet" in repr(blank) and f'kb.reveal("{item.id}")' in repr(blank)
    shown = tryits.reveal(item.id)
    assert f"{item.answer} =" in shown.code and "return" not in shown.code.splitlines()[-1]


def _notebooks():
    for path in sorted(CHAPTERS.glob("*.ipynb")):
        cells = [c for c in json.loads(path.read_text())["cells"] if c["cell_type"] == "code"]
        yield "-".join(path.stem.split("-")[:2]), ["".join(c["source"]) for c in cells]


def _assigned(source):
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return set()
    return {t.id for node in ast.walk(tree) if isinstance(node, (ast.Assign, ast.For))
            for t in ast.walk(node.targets[0] if isinstance(node, ast.Assign) else node.target) if isinstance(t, ast.Name)}


def test_notebooks_and_registry_agree():
    used = {}
    for notebook, sources in _notebooks():
        for k, src in enumerate(sources):
            for id_, name in CALL.findall(src):
                assert id_.startswith(notebook + "/"), f"{notebook}: cell calls another notebook's {id_}"
                assert id_ not in used, f"{id_} is used twice"
                item = TRY_ITS[id_]
                assert name == item.answer and re.search(rf"^{name} = \.\.\.", src, re.M), \
                    f"{id_}: the cell must start blank, `{item.answer} = ...`"
                head = src[: re.search(rf"^{name} = \.\.\.", src, re.M).start()]  # lines above the blank
                before = set().union(_assigned(head), *(_assigned(s) for s in sources[:k]))
                missing = [p for p in item.solution.__code__.co_varnames[: item.solution.__code__.co_argcount]
                           if p not in before]
                assert not missing, f"{id_}: the worked answer reads {missing}, not defined before its cell"
                others = set().union(*(_assigned(s) for j, s in enumerate(sources) if j != k))
                clash = _assigned(item.solution_code()) & others
                assert not clash, f"{id_}: pasting the worked answer would rebind {sorted(clash)}"
                used[id_] = notebook
    assert sorted(used) == sorted(TRY_ITS), f"registered but not in a notebook: {sorted(set(TRY_ITS) - set(used))}"
