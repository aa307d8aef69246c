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


@pytest.mark.parametrize("item", [i for i in TRY_ITS.values() if i.ranges], ids=[k for k, i in TRY_ITS.items() if i.ranges])
def test_another_draws_fresh_data_checked_and_revealed_the_same_way(item):
    """kb.another: the same k gives the same data (seeded), other data than the notebook's; the variant's worked
    answer passes, the notebook's answer is named as the answer for other data, kb.reveal shows the variant's
    data; k = 0 goes back to the notebook."""
    from kinbook.book.tryits import another, reveal, try_it

    try:
        seen = []
        for k in (1, 2):
            v = another(item.id, k)
            assert repr(v.data) != repr(item.data) and repr(another(item.id, k).data) == repr(v.data)
            assert str(v.seed) in repr(v) and item.stated(v.data) in repr(v)
            result = try_it(item.id, item.reference_answer(v.data))
            assert result.passed, (v.data, result)
            if item.reference_answer(v.data) is not None:
                old = try_it(item.id, item.reference_answer())
                assert not old.passed
            shown = reveal(item.id)
            assert shown.code.splitlines()[0] == item.solution_code(v.data).splitlines()[0]
            seen.append(v.data)
        assert repr(seen[0]) != repr(seen[1])
    finally:
        another(item.id, 0)
    assert try_it(item.id, item.reference_answer()).passed


def test_another_draws_the_next_variant_and_refuses_a_bad_k():
    from kinbook.book.tryits import another
    from kinbook.errors import InputError

    try:
        first, second = another("13-5/try-3"), another("13-5/try-3")
        assert (first.k, second.k) == (1, 2)
        with pytest.raises(InputError, match="k must be a whole number"):
            another("13-5/try-3", -1)
        assert "no other data" in repr(another("14-5/try-2"))
    finally:
        another("13-5/try-3", 0)


def test_a_copied_printed_answer_is_named_other_data():
    from kinbook.book.tryits import get

    r = get("13-3/try-1").check(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"])   # the book's crank, printed above
    assert r.mistakes == ["wrong_data"] and "printed above" in r.messages[0]
