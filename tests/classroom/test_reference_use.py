"""Which answers came from kinbook's own reference, read from the submitted code
(kinbook.classroom.reference_use)."""

import pytest

from kinbook.classroom.reference_use import reference_use


@pytest.mark.parametrize("cells, expected", [
    (["Phi = mech.symbolic().Phi"], "mech.symbolic() (cell 1)"),
    (["d = mech.derivation('3')", "Phi = d[2]"], "mech.derivation() (cell 1)"),
    (["c = mech.constraint('1')", "Phi = sp.Matrix(c.phi(Q))"], "c.phi() (cell 2)"),
    (["from kinbook.symbolic import derive as dv", "Phi = dv(P, q, qd).Phi_q"], "kinbook.symbolic.derive (cell 1)"),
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
