"""The notebook display helpers never let round-off through: exact zeros print the same on every CPU."""

import numpy as np
import pytest

from kinbook.book import display


@pytest.mark.parametrize("noise", [0.0, -0.0, 1.5e-17, -1.5e-17, 9.9e-13, -4e-16])
def test_round_off_prints_as_the_same_zero(noise, capsys):
    display.show(np.array([noise, 0.5]), noise, [noise], (noise,))
    assert capsys.readouterr().out == "[0.  0.5] 0 [0.0] (0.0,)\n"
    assert display.fmt(noise) == "0.0000"
    assert display.small(noise) == "< 1e-12"
    assert display.agrees(noise) == "agrees to within 1e-12"


def test_values_above_the_tolerance_are_kept():
    x = np.array([1e-11, -2e-3, 3.0])
    assert np.array_equal(display.clean(x), x)
    assert display.fmt(-2e-3, 3) == "-0.002"
    assert display.agrees(0.0451) == "differs by 0.045"
    assert display.agrees(22111.7) == "differs by 22112"


def test_clean_leaves_other_objects_alone():
    import sympy as sp

    x = sp.Symbol("x")
    assert display.clean({"a": x, "b": "text", "c": 3, "d": True}) == {"a": x, "b": "text", "c": 3, "d": True}
    assert display.clean(np.arange(3)).dtype.kind == "i"


def test_newton_table_shows_the_solver_iterations_without_round_off():
    import kinbook
    from kinbook.book.verify import newton_table

    m = kinbook.examples.load("ch13_example1")
    q, hist = m.solve_position(0.0, history=True)
    table = newton_table(hist)
    assert len(table.rows) == len(hist) >= 3
    # row k is the iterate q_k: its residual is max |Φ(q_k)|, recomputed here from the mechanism
    k = 1
    assert table.rows[k][1] == display.small(np.abs(m.Phi(hist.q[k], 0.0)).max())
    assert table.rows[-1][1] == "< 1e-12" and np.abs(hist.q[-1] - q).max() == 0
    assert "e-1" not in repr(table).replace("1e-12", "")  # nothing at round-off level is printed


def test_small_as_a_relation_never_reads_equals_less_than():
    assert display.small(-1.5e-17, relation=True) == "< 1e-12"
    assert display.small(3.2e-5, 1e-9, relation=True) == "= 3.2e-05"
    assert display.small(2.35, relation=True) == "= 2.4"
    assert display.small(4.7e-7, 1e-6, relation=True) == "< 1e-6"


def test_stored_notebooks_keep_each_stream_in_one_output():
    """A cell's printed lines are one output (make notebooks coalesces them): split chunks are invisible when
    rendered but make the stored notebook and its diffs read as noise."""
    import json
    import pathlib

    root = pathlib.Path(__file__).resolve().parents[2]
    for path in sorted(root.glob("chapters/*.ipynb")):
        for cell in json.loads(path.read_text())["cells"]:
            outs = cell.get("outputs", [])
            split = [a for a, b in zip(outs, outs[1:]) if a["output_type"] == b["output_type"] == "stream"
                     and a["name"] == b["name"]]
            assert not split, f"{path.name}: a {split[0]['name']} stream split in chunks"
