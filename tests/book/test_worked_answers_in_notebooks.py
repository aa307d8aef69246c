"""Every worked answer runs where it is shown: a stuck student pastes ``kb.reveal(id)``'s code into the try-it cell of
its notebook, in place of ``my_X = ...``, and runs it. This test does exactly that for every try-it of every chapter
notebook: it runs the notebook's code cells in order in one namespace (the notebook's own, as a kernel keeps it), and
at each try-it cell runs the revealed code — the text the student reads, not the function behind it — followed by the
cell's own ``kb.try_it(...)`` line, which must pass.

A relative import in a worked answer (``from ...spatial import E``), a name the notebook never defines or a variable
the notebook binds differently all fail here, as they would in the notebook."""

from __future__ import annotations

import json
import linecache
import os
import pathlib
import re

import numpy as np
import pytest

CHAPTERS = pathlib.Path(__file__).resolve().parents[2] / "chapters"
CALL = re.compile(r"^kb\.try_it\(\"([^\"]+)\",\s*(\w+)\)\s*$", re.M)


def _code_cells(path):
    return ["".join(c["source"]) for c in json.loads(path.read_text())["cells"] if c["cell_type"] == "code"]


NOTEBOOKS = [p for p in sorted(CHAPTERS.glob("*.ipynb")) if any(CALL.search(s) for s in _code_cells(p))]


def pasted(source, id_, answer, code):
    """The try-it cell with the worked answer pasted over its blank line ``answer = ...``."""
    blank = re.compile(rf"^{re.escape(answer)} = \.\.\..*$", re.M)
    assert blank.search(source), f"{id_}: no blank line `{answer} = ...` in its cell"
    return blank.sub(lambda _: code, source, count=1)


@pytest.mark.filterwarnings("ignore:Animation was deleted without rendering")
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_every_worked_answer_pasted_into_its_cell_passes(path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import kinbook as kb

    monkeypatch.chdir(path.parent)
    monkeypatch.setitem(os.environ, "MPLBACKEND", "Agg")
    from IPython.display import display

    namespace = {"__name__": "__main__", "display": display}  # IPython's kernel puts display() in every namespace
    checked, failures = [], []
    printing = np.get_printoptions()  # the notebook's kinbook.notebook_setup() sets numpy's: the other tests' are kept
    try:
        for k, source in enumerate(_code_cells(path)):
            calls = CALL.findall(source)
            if not calls:
                exec(compile(source, f"{path.name} cell {k}", "exec"), namespace)
                plt.close("all")
                continue
            (id_, answer), = calls
            code = kb.reveal(id_).code
            cell = pasted(source, id_, answer, code)
            checked.append(id_)
            cell = CALL.sub(lambda m: f"__result__ = {m.group(0)}", cell)
            name = f"<{path.name} cell {k}: {id_}, worked answer pasted>"
            linecache.cache[name] = (len(cell), None, cell.splitlines(True), name)  # as IPython keeps a cell's code
            try:
                exec(compile(cell, name, "exec"), namespace)
            except Exception as exc:  # noqa: BLE001 — the student's traceback, reported with the code pasted
                failures.append(f"{id_}: the worked answer raises {type(exc).__name__}: {exc}\n--- pasted cell ---\n"
                                f"{cell}")
                exec(compile(source, f"{path.name} cell {k}", "exec"), namespace)  # the blank cell: go on
                continue
            result = namespace.pop("__result__")
            if not result.passed:
                failures.append(f"{id_}: the worked answer, pasted into its cell, fails its try-it: {result!r}")
            elif "kinbook's own answer" in " ".join(result.messages):
                failures.append(f"{id_}: the worked answer calls the library's own answer: {result!r}")
    finally:
        plt.close("all")
        kb.set_language("en")
        np.set_printoptions(**printing)
    assert checked, f"{path.name}: no try-it checked"
    assert not failures, f"{len(failures)} of {len(checked)} worked answers fail where they are shown:\n" + \
        "\n".join(failures)
