"""kinbook.book.instant: the data a book page checks its try-its with (issue 35). The page's engine itself is run
against Python's verdicts by tests/web/test_instant.py (make test-web: Node and chromium)."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from kinbook.book import instant
from kinbook.book.tryits import TRY_ITS, get
from kinbook.core import reader

get("13-1/try-1")
IDS = list(TRY_ITS)
NOTEBOOKS = sorted({i.split("/")[0] for i in IDS})
CACHE = Path(__file__).resolve().parents[2] / "build" / "cache" / "instant"
"""The checkout's cache of the pages' JSON (git-ignored, removed by make clean): what this run computes, the book build
(web/build.py, after make test in CI) reads instead of making the try-its' mutation runs again."""


@pytest.fixture(scope="module")
def pages():
    return {nb: json.loads(instant.page_text(nb, CACHE)) for nb in NOTEBOOKS}


def test_the_pages_cache_is_read_under_its_key_only(tmp_path, monkeypatch):
    """A page's text with a cache: computed and stored under the key of what makes it; read back under that key (a
    planted text comes back as it is: the cache is used); under another key — a source or a version changed —
    computed again, never the stale text, whose folder is removed."""
    nb = "13-1"
    fresh = json.dumps(instant.page(nb), ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    assert instant.page_text(nb, tmp_path) == fresh
    stored = tmp_path / instant.cache_key() / f"{nb}.json"
    assert stored.read_text(encoding="utf-8") == fresh
    stored.write_text('{"planted": true}', encoding="utf-8")
    assert instant.page_text(nb, tmp_path) == '{"planted": true}'
    monkeypatch.setattr(instant, "cache_key", lambda: "another-key")
    assert instant.page_text(nb, tmp_path) == fresh
    assert [p.name for p in tmp_path.iterdir()] == ["another-key"]
    assert (tmp_path / "another-key" / f"{nb}.json").read_text(encoding="utf-8") == fresh


def test_the_cache_key_changes_with_every_file_of_the_package_and_the_versions(tmp_path, monkeypatch):
    """The key covers the code, the try-its' data, the shipped examples, the translations, a new file, the versions
    of numpy and sympy and the CPU kernels chosen; a copy of the package has the package's key."""
    import sympy

    import kinbook

    package = Path(kinbook.__file__).parent
    copy = tmp_path / "kinbook"
    shutil.copytree(package, copy, ignore=shutil.ignore_patterns("__pycache__"))
    key = instant.cache_key(copy)
    assert key == instant.cache_key(package)
    for name in ("book/tryits/ch14.py", "grading/checks.py", "examples/spatial_fourbar.toml",
                 "locale/es/LC_MESSAGES/kinbook.mo"):
        original = (copy / name).read_bytes()
        (copy / name).write_bytes(original + b"\n")
        assert instant.cache_key(copy) != key, name
        (copy / name).write_bytes(original)
    assert instant.cache_key(copy) == key
    (copy / "book" / "extra.py").write_text("")
    assert instant.cache_key(copy) != key
    (copy / "book" / "extra.py").unlink()
    for module in (np, sympy):
        with monkeypatch.context() as m:
            m.setattr(module, "__version__", module.__version__ + ".post1")
            assert instant.cache_key(copy) != key, module.__name__
    with monkeypatch.context() as m:  # make test-cpu's BLAS kernels
        m.setenv("OPENBLAS_CORETYPE", "Prescott")
        assert instant.cache_key(copy) != key
    assert instant.cache_key(copy) == key


def test_the_grammar_is_the_readers():
    g = instant.grammar()
    assert g["functions"] == {name: list(counts) for name, (_, counts) in reader.FUNCTIONS.items()}
    assert g["aliases"] == reader.ALIASES
    assert g["constants"] == {"pi": pytest.approx(np.pi), "π": pytest.approx(np.pi), "E": pytest.approx(np.e)}


def test_every_tryit_has_its_check_in_its_page_with_texts_in_both_languages(pages):
    for nb, page in pages.items():
        assert sorted(page["tryits"]) == sorted(i for i in IDS if i.startswith(nb + "/"))
        for key, texts in page["ui"].items():
            assert texts["en"] and texts["es"], key
        assert page["ui"]["check"]["es"] == "Comprobar"
        for spec in page["tryits"].values():
            for m in spec["mistakes"]:
                assert m["title"]["en"] and m["title"]["es"] and m["hint"]["es"] != "", m["code"]


@pytest.mark.parametrize("id", [i for i in IDS if get(i).checker.function_name in ("check_value", "check_rotation",
                                                                               "check_euler_parameters")])
def test_numbers_the_worked_answer_meets_the_pages_rule(pages, id):
    """The worked answer (computed apart, by the try-it's own solution code) is within the page's tolerance of the
    page's value, and no catalogued mistake of the page is that close to it."""
    spec = pages[id.split("/")[0]]["tryits"][id]
    a = np.asarray(get(id).reference_answer(), float).ravel()
    e = np.asarray(spec["value"], float).ravel()
    tol = spec["rule"]["atol"] + spec["rule"]["rtol"] * np.abs(e).max()
    assert np.abs(a - e).max() <= tol
    for m in spec["mistakes"]:
        v = np.asarray(m["values"], float).ravel()
        if v.size == e.size and np.abs(v - e).max() > tol:
            assert np.abs(a - v).max() > tol, m["code"]


@pytest.mark.parametrize("id", [i for i in IDS if get(i).checker.function_name in ("check_phi", "check_nu", "check_gamma")
                                and all(isinstance(r, str) for r in np.ravel(get(i).reference_answer()))])
def test_rows_the_worked_answer_is_the_reference_at_the_pages_points(pages, id):
    """The worked answer's rows, read by kinbook's reader and evaluated by sympy at the page's points, are the
    reference's values there (a constant factor per row for Φ)."""
    import sympy as sp

    spec = pages[id.split("/")[0]]["tryits"][id]
    rows = list(np.ravel(get(id).reference_answer()))
    symbols = {name: sp.Symbol(name) for name in spec["names"]}
    P = spec["points"]["samples"]
    R = np.asarray(spec["reference"]["samples"], float)
    for k, text in enumerate(rows):
        expr = reader.read_expression(text, symbols=symbols, where="worked answer")
        values = []
        for i, t in enumerate(P["t"]):
            env = {}
            for name, (kind, j) in spec["names"].items():
                env[symbols[name]] = t if kind == "t" else P[kind][i][j]
            values.append(float(expr.xreplace(env).evalf()))
        values = np.array(values)
        ratio = values @ R[:, k] / (R[:, k] @ R[:, k]) if spec["quantity"] == "Phi" else 1.0
        assert np.allclose(values, ratio * R[:, k], rtol=1e-9, atol=1e-9), (id, k)


@pytest.mark.parametrize("id", ["13-3/try-1", "13-6/try-1", "13-7/try-1", "13-5/try-1"])
def test_the_mutation_run_is_in_the_page_named_as_python_names_it(pages, id):
    """Every mutant of the try-it that its check refuses is a mistake of the page, with the code Python names it by
    and its values: the mutant's answer as a student types it, read by kinbook's reader and evaluated by sympy at
    the page's points (at its first ``points`` of them) — the stored values; a mutant Python passes is not there."""
    import sympy as sp

    spec = pages[id.split("/")[0]]["tryits"][id]
    mine = [m for m in spec["mistakes"] if m.get("points")]
    run = instant.tryit_mutants(get(id))
    refused = [(m, a, r) for m, a, r in run if not r.passed]
    assert run and len(mine) == len(refused)
    symbols = {name: sp.Symbol(name) for name in spec["names"]}
    order = list(symbols)
    P = spec["points"]["samples"]
    for stored, (m, answer, result) in zip(mine, refused):
        assert stored["code"] == (result.mistakes[0] if result.mistakes else m.code)
        K = stored["points"]
        args = [[t if spec["names"][n][0] == "t" else P[spec["names"][n][0]][i][spec["names"][n][1]] for n in order]
                for i, t in enumerate(P["t"][:K])]
        entries = np.array(answer, dtype=object)
        values = np.empty((K,) + entries.shape)
        for index, text in np.ndenumerate(entries):
            expr = reader.read_expression(text, symbols=symbols, where="mutant")
            f = sp.lambdify([symbols[n] for n in order], expr, "math", dummify=True)
            values[(slice(None),) + index] = [f(*a) for a in args]
        assert np.allclose(values, np.asarray(stored["values"], float), rtol=1e-7, atol=1e-9), (id, m.operator)
