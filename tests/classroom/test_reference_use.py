"""Which answers came from kinbook's own reference, read from the submitted code
(kinbook.classroom.reference_use)."""

import pytest

from kinbook.classroom.reference_use import reference_use


@pytest.mark.parametrize("cells, expected", [
    (["Phi = mech.symbolic().Phi"], "mech.symbolic() (cell 1)"),
    (["d = mech.derivation('3')", "Phi = d[2]"], "mech.derivation() (cell 1)"),
    (["c = mech.constraint('1')", "Phi = sp.Matrix(c.phi(Q))"], "c.phi() (cell 2)"),
    (["from kinbook.core.symbolic import derive as dv", "Phi = dv(P, q, qd).Phi_q"], "kinbook.core.symbolic.derive (cell 1)"),
    (["def mine():\n    return mech.symbolic()", "Phi = mine()"], "mech.symbolic() (cell 1)"),
    (["Phi = []", "for row in mech.symbolic().Phi:\n    Phi.append(row)"], "mech.symbolic() (cell 2)"),
    (["Phi = []", "Phi.extend(mech.constraint_phi('1'))"], "mech.constraint_phi() (cell 2)"),
    (["Phi = sp.zeros(2, 1)", "Phi[0] = mech.symbolic().Phi[0]"], "mech.symbolic() (cell 2)"),
    (["f = getattr(mech, 'sym' + 'bolic')", "Phi = f()"], "dynamic code (getattr), not followed (cell 1)"),
    (["exec('Phi = 1')"], ""),  # nothing assigned Phi that the analysis can see: nothing reported
    (["q = mech.solve_position(0.5)\npart('x', 1, answer='Phi', check='value', expected=q[2])", "Phi = q[2]"],
     "the expected value of a part(...) (cell 1)"),
])
def test_reference_calls_are_followed_to_the_answer(cells, expected):
    assert reference_use(cells, ["Phi"]) == {"Phi": expected}


@pytest.mark.parametrize("cells", [
    ["Phi = sp.Matrix([x1 - x2 + sp.cos(phi2), y1 - y2 + sp.sin(phi2)])"],
    ["ref = mech.symbolic()", "Phi = sp.Matrix([x1 - x2])"],          # computed, then not used
    ["Phi = mech.symbolic()", "Phi = sp.Matrix([x1 - x2])"],          # overwritten by the student's own
    ["def phi(t):\n    return 2 * t", "Phi = phi(3)"],                # a function of their own named phi
    ["q = mech.solve_position(0.5)", "Phi = q[mech.index('phi2')]"],  # the library as a tool, not the answer key
    ["%matplotlib inline\nPhi = 1", "this is not python ("],
])
def test_own_work_is_not_reported(cells):
    assert reference_use(cells, ["Phi"]) == {"Phi": ""}


def test_deep_chains_are_followed_without_recursion():
    """A chain of thousands of attributes made the analysis raise RecursionError: the grader failed on that
    submission (no part was recorded)."""
    found = reference_use(["Phi = mech" + ".b" * 900 + ".symbolic()"], ["Phi"])
    assert found["Phi"].endswith(".b.symbolic() (cell 1)")


def test_too_much_code_is_reported_not_analysed():
    """8 MB of code took the analysis minutes of the grader's time; past MAX_CODE_CHARS it says so instead."""
    from kinbook.classroom.reference_use import MAX_CODE_CHARS

    cells = ["Phi = mech.symbolic()", "x = 1\n" * (MAX_CODE_CHARS // 6 + 1)]
    assert reference_use(cells, ["Phi"]) == {"Phi": f"not followed: {sum(map(len, cells)):,} characters of code "
                                                    f"(at most {MAX_CODE_CHARS:,} are analysed)"}


@pytest.mark.parametrize("cells, expected", [
    # IPython syntax made the whole cell unparsable, so the analysis skipped it
    (["Phi = mech.symbolic()\ny = %time 1"], "mech.symbolic() (cell 1)"),
    (["%time Phi = mech.symbolic()"], "mech.symbolic() (cell 1)"),
    (["Phi = %timeit -o mech.symbolic()"], "mech.symbolic() (cell 1)"),
    (["%%capture out\nPhi = mech.symbolic()"], "mech.symbolic() (cell 1)"),
    (["exec('Phi = mech.symbolic()')"], "mech.symbolic() (cell 1)"),
    (["Phi = eval('mech.symbolic()')"], "mech.symbolic() (cell 1)"),
    # the reference reached through a class, a default value, a global, a walrus, a match, a function passed on
    (["class A:\n    Phi = mech.symbolic()", "Phi = A.Phi"], "mech.symbolic() (cell 1)"),
    (["def f(x=mech.symbolic()):\n    return x", "Phi = f()"], "mech.symbolic() (cell 1)"),
    (["def f():\n    global Phi\n    Phi = mech.symbolic()", "f()"], "mech.symbolic() (cell 1)"),
    (["if (Phi := mech.symbolic()) is None:\n    pass"], "mech.symbolic() (cell 1)"),
    (["match 1:\n    case _:\n        Phi = mech.symbolic()"], "mech.symbolic() (cell 1)"),
    (["def g(i):\n    return mech.symbolic()[i]", "Phi = list(map(g, range(2)))"], "mech.symbolic() (cell 1)"),
    # code that could assign the answer unseen: said so, whatever the answer's own cell shows
    (["exec(bytes.fromhex('50686920').decode() + '= 1')", "Phi = 1"],
     "not followed: code that could assign it unseen (exec, cell 1)"),
    (["open('m.py', 'w').write('import kinbook')", "from m import Phi"],
     "not followed: code that could assign it unseen (import of 'm', which is not an installed module, cell 2)"),
    (["%run helper.py", "Phi = 1"], "not followed: code that could assign it unseen (%run, cell 1)"),
    (["get_ipython().user_ns['Phi'] = mech.symbolic()"], "not followed: code that could assign it unseen (user_ns, "
                                                          "cell 1)"),
])
def test_tricks_do_not_hide_the_reference(cells, expected):
    assert reference_use(cells, ["Phi"]) == {"Phi": expected}


@pytest.mark.parametrize("cells", [
    ["import numpy as np\nimport sympy as sp\nfrom kinbook.classroom import part", "Phi = sp.Matrix([1])"],
    ["%matplotlib inline\n%precision 3\nx = !ls\nmech.symbolic?", "Phi = 1"],
    ["%%time\nPhi = 2 * 3"],
])
def test_ordinary_notebook_syntax_is_not_flagged(cells):
    assert reference_use(cells, ["Phi"]) == {"Phi": ""}
