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
    finally:
        another("13-5/try-3", 0)


def test_every_try_it_has_other_data_to_draw():
    assert not [i.id for i in TRY_ITS.values() if not i.ranges], "kb.another has nothing to draw for these"


def test_a_copied_printed_answer_is_named_other_data():
    from kinbook.book.tryits import get

    r = get("13-3/try-1").check(["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"])   # the book's crank, printed above
    assert r.mistakes == ["wrong_data"] and "printed above" in r.messages[0]


# ------------------------------------------------------------------------------------- hints that give nothing away
def _rows_of(answer):
    import sympy as sp

    if isinstance(answer, sp.MatrixBase):
        return [answer[k, :] if answer.shape[1] > 1 and answer.shape[0] > 1 else answer[k]
                for k in range(answer.shape[0])] if answer.shape[1] == 1 else None
    if isinstance(answer, (list, tuple)) and all(isinstance(a, str) for a in answer):
        return [sp.sympify(a) for a in answer]
    return None


SYMBOLIC = [i for i in TRY_ITS.values() if "reveal" not in __import__("inspect").signature(i.checker).parameters
            and i.checker.function_name in ("check_phi", "check_nu", "check_gamma")]


@pytest.mark.parametrize("item", SYMBOLIC, ids=[i.id for i in SYMBOLIC])
def test_a_dropped_or_flipped_term_is_described_never_written(item):
    """Every row of the worked answer with one of its terms dropped or its sign flipped (the checkers' own term
    variants): the feedback names what kind of term, never the term itself (which would be the answer's last step)."""
    import sympy as sp

    from kinbook.grading.diagnose import term_variants

    rows = _rows_of(item.reference_answer())
    if rows is None:
        pytest.skip("the worked answer is not a list of rows")
    tried = 0
    varied = [k for k, row in enumerate(rows) if len(sp.Add.make_args(sp.expand(row))) > 1][:3]
    for k in varied:
        for _code, wrong, term in [v for v in term_variants(sp.expand(rows[k])) if v[2] is not None][:4]:
            answer = [str(r) for r in rows]
            answer[k] = str(wrong)
            result = item.check(answer)
            if result.passed:  # a flip the row's own identity absorbs (sin² + cos²): not a slip
                continue
            tried += 1
            text = " ".join(result.messages + [r.message for r in result.rows])
            written = sp.sstr(term).replace("phi", "φ").replace("**", "^")
            assert written not in text, f"{item.id}: the feedback writes the term {written}: {text}"
            assert not re.search(r"the term (?!with the wrong sign)", text), f"{item.id}: {text}"
    if not tried:
        pytest.skip(f"{item.id}: its rows have more terms than the checkers vary one by one")


NUMERIC = [i for i in TRY_ITS.values() if i.checker.function_name == "check_value"]


@pytest.mark.parametrize("item", NUMERIC, ids=[i.id for i in NUMERIC])
def test_a_scaled_value_names_the_step_not_the_factor(item):
    """The worked answer times each factor a slip can put on a value (2, ½, π, 2π, 1/(2π), π/180, 1000 …): never
    "multiplied by 0.159155" — that ratio gives the answer — but the step to check."""
    import numpy as np

    from kinbook.grading.numbers import PLAUSIBLE_FACTORS
    from kinbook.grading.report import fmt

    value = np.asarray(item.reference_answer(), float)
    for c in PLAUSIBLE_FACTORS:
        result = item.check(value * c)
        assert not result.passed
        text = " ".join(result.messages)
        for x in (c, 1 / c):
            if len(fmt(abs(x))) >= 4:  # 0.159155, 6.28319, 0.0174533: a ratio to invert (a 2 names a slip)
                assert fmt(x) not in text, f"{item.id} ×{c}: {text}"
        assert "multiplied by" not in text, f"{item.id} ×{c}: {text}"


def test_the_scaled_step_names_the_slip():
    r = tryits.get("13-4/try-3").check(0.25)          # 90/360 of a turn: 2π forgotten
    assert r.mistakes == ["scaled"] and "where an angle is put in radians" in r.messages[1]
    assert "0.159155" not in repr(r)


def test_numbers_for_a_formula_of_t_are_read_at_t0_not_called_malformed():
    item = tryits.get("13-6/try-1")
    right_now = item.check([0.0] * 8 + [100.0])      # ν at t = 0 of this very driver: right, but only there
    assert right_now.mistakes == ["only_at_samples"] and "at t = 0 only" in right_now.messages[0]
    wrong_sign = item.check([0.0] * 8 + [-100.0])
    assert wrong_sign.mistakes == ["nu_sign"] and "read as the values at t = 0" in wrong_sign.messages[0]
    assert "malformed" not in wrong_sign.mistakes and "at=" not in repr(wrong_sign)


def test_a_copied_printed_row_is_named_before_any_term_diagnosis():
    r = tryits.get("13-6/try-1").check(["0"] * 8 + ["100"])   # ν of the book's driver, printed above
    assert r.mistakes == ["wrong_data"] and "printed above" in r.messages[0]
    r = tryits.get("13-7/try-1").check(["(-1*cos(phi2))*(-dphi2**2)", "(-1*sin(phi2))*(-dphi2**2)"])
    assert r.mistakes == ["wrong_data"] and "printed above" in r.messages[0]


def test_a_library_one_liner_is_named_kinbooks_own_answer():
    """A cell that asks kinbook for the answer (``mech.gamma(...)[7]``) passes, named as kinbook's answer with the
    request to build it; the worked answer, built by hand, gets a plain "correct"."""
    import linecache

    import kinbook as kb

    mech = tryits.get("13-7/try-2").context()["mech"]
    cells = {"library": "q_t = mech.solve_position(0.004)\nqd_t = mech.solve_velocity(q_t, 0.004)\n"
                        "my_gamma_8 = mech.gamma(q_t, qd_t, 0.004)[7]\nresult = kb.try_it('13-7/try-2', my_gamma_8)\n",
             "by hand": tryits.reveal("13-7/try-2").code + "\nresult = kb.try_it('13-7/try-2', my_gamma_8)\n"}
    seen = {}
    for what, src in cells.items():
        name = f"<cell {what}>"
        linecache.cache[name] = (len(src), None, src.splitlines(True), name)
        ns = {"mech": mech, "kb": kb, "np": __import__("numpy")}
        exec(compile(src, name, "exec"), ns)
        seen[what] = ns["result"]
    assert seen["library"].passed and "kinbook's own answer (gamma)" in seen["library"].messages[0]
    assert seen["by hand"].passed and "kinbook's own answer" not in repr(seen["by hand"])


def test_the_own_arm_in_the_n1_row_is_named_not_a_missing_chain_rule():
    """14-5 try-it 2 with s_3ᵀC_3, s_4ᵀC_4 in the universal joint's n1 row (each body's own arm)."""
    import sympy as sp

    from kinbook.spatial import A_from_p, E, a_bar

    item = tryits.get("14-5/try-2")
    mech = item.context()["mech"]
    right = item.reference_answer()
    par_3, par_4 = sp.Matrix(mech.body_symbols("coupler")[3:]), sp.Matrix(mech.body_symbols("rocker")[3:])
    dAa = lambda p, a: 2 * (E(p) * a_bar(sp.Matrix(a)) + sp.Matrix(a) * p.T)  # noqa: E731
    arm_3, arm_4 = A_from_p(par_3) * sp.Matrix([0, 1, 0]), A_from_p(par_4) * sp.Matrix([1, 0, 0])
    z = sp.zeros(1, 3)
    own = sp.Matrix.hstack(z, arm_3.T * dAa(par_3, [0, 1, 0]), z, arm_4.T * dAa(par_4, [1, 0, 0]))
    r = item.check(sp.Matrix.vstack(right[:3, :], own))
    assert r.mistakes == ["own_arm"] and "chain-rule" not in repr(r) and "s_4ᵀC_3" in repr(r)
    assert 0 < r.score < 1
