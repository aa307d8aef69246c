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


# ====================================================================== an exercise's own reference calls (ex11)
import glob  # noqa: E402
import os  # noqa: E402

from kinbook.classroom.notebook import grader_segments, load_source  # noqa: E402
from kinbook.classroom.reference_use import PHI_FAMILY, declared_calls, exercise_calls  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
EX11 = glob.glob(os.path.join(ROOT, "exercises", "ex11-*.ipynb"))[0]
#: The released ex11's code cells before the answers (locked: the instructor's).
EX11_SETUP = ["import numpy as np\n\nimport kinbook.spatial as ks\nfrom kinbook.classroom import parameters, part",
              'P = {"phi": 60.0, "psi": 30.0, "theta": 45.0}',
              'psi, theta, phi = np.radians([P["psi"], P["theta"], P["phi"]])']
#: The Φ exercises' locked set-up.
PHI_SETUP = ["import sympy as sp\nimport kinbook\nmech = kinbook.examples.load('ch13_example1')\n"
             "x1, y1, phi1, x2, y2, phi2 = list(mech.q)[:6]"]
OWN_A = ("def Rz(a):\n    return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])\n"
         "def Rx(a):\n    return np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])\n")


def ex11_calls():
    return exercise_calls([(kind, code) for _, kind, code in grader_segments(load_source(EX11))])


def test_an_exercise_counts_the_functions_its_hidden_checks_use():
    """ex11's hidden checks compute A, p, E Gᵀ and EᵀE with kinbook.spatial's A_from_euler, p_from_A, E and G: those
    are its reference (answers taken from them were reported nowhere: D4); loading a mechanism, which the release
    itself does, is not."""
    calls = ex11_calls()
    assert calls.functions - PHI_FAMILY.functions == {"A_from_euler", "p_from_A", "E", "G"}
    tiny = exercise_calls([(k, c) for _, k, c in grader_segments(load_source(
        os.path.join(ROOT, "tests", "classroom", "source", "tiny.ipynb")))])
    assert tiny.methods - PHI_FAMILY.methods == {"solve_position"} and "load" not in tiny.functions  # not `index`
    declared = declared_calls(['reference_calls("kinbook.spatial.A_from_euler", ".solve_position", "E")'])
    assert declared.functions == {"A_from_euler", "E"} and declared.methods == {"solve_position", "E"}


EVASIONS = [  # (answer, student's cells after the set-up, what is reported)
    ("A", ["A = ks.A_from_euler(psi, theta, phi)"], "ks.A_from_euler() (cell 4)"),
    ("A", ["f = ks.A_from_euler", "A = f(psi, theta, phi)"], "ks.A_from_euler() (cell 4)"),
    ("A", ["from kinbook.spatial import A_from_euler as rot", "A = rot(psi, theta, phi)"],
     "kinbook.spatial.A_from_euler (cell 4)"),
    ("A", ["from kinbook.spatial import *", "A = A_from_euler(psi, theta, phi)"], "A_from_euler() (cell 5)"),
    ("A", ["import kinbook as kb", "A = kb.spatial.A_from_euler(psi, theta, phi)"],
     "kb.spatial.A_from_euler() (cell 5)"),
    ("A", ["from functools import partial", "f = partial(ks.A_from_euler, psi)", "A = f(theta, phi)"],
     "ks.A_from_euler() (cell 5)"),
    ("A", ["A = getattr(ks, 'A_from_euler')(psi, theta, phi)"], "getattr(ks, 'A_from_euler') (cell 4)"),
    ("A", ["ks.A_from_euler(psi, theta, phi)", "A = _"], "ks.A_from_euler() (cell 4)"),
    ("A", ["ks.A_from_euler(psi, theta, phi)", "A = Out[4]"], "ks.A_from_euler() (cell 4)"),
    ("A", ["ks.A_from_euler(psi, theta, phi)", "x = 1", "A = _oh[4]"], "ks.A_from_euler() (cell 4)"),
    ("A", ["def keep(v):\n    global A\n    A = v", "keep(ks.A_from_euler(psi, theta, phi))"],
     "ks.A_from_euler() (cell 5)"),
    ("A", ["try:\n    raise ValueError(ks.A_from_euler(psi, theta, phi))\nexcept ValueError as e:\n    A = e.args[0]"],
     "ks.A_from_euler() (cell 4)"),
    ("A", ["f = lambda: ks.A_from_euler(psi, theta, phi)", "A = f()"], "ks.A_from_euler() (cell 4)"),
    ("A", ["d = {'a': ks.A_from_euler(psi, theta, phi)}", "A = d['a']"], "ks.A_from_euler() (cell 4)"),
    ("A", ["def fill(out, v):\n    out[:] = v", "A = np.zeros((3, 3))", "fill(A, ks.A_from_euler(psi, theta, phi))"],
     "ks.A_from_euler() (cell 6)"),
    ("EGt", ["p = np.array([1.0, 0, 0, 0])", "EGt = ks.E(p) @ ks.G(p).T"], "ks.E() (cell 5)"),
    ("A", ["from operator import attrgetter", "A = attrgetter('A_from_euler')(ks)(psi, theta, phi)"],
     "attrgetter('A_from_euler') (cell 5)"),
    ("A", ["import sys", "m = sys.modules['kinbook.spatial']", "A = m.A_from_euler(psi, theta, phi)"],
     "dynamic code (sys.modules), not followed (cell 5)"),
    ("A", ["from sys import modules as mods", "A = mods['kinbook.spatial'].A_from_euler(psi, theta, phi)"],
     "dynamic code (sys.modules), not followed (cell 5)"),
    ("p", [OWN_A + "A = Rz(psi) @ Rx(theta) @ Rz(phi)", "p = ks.p_from_A(A)"], "ks.p_from_A() (cell 5)"),
]
PHI_EVASIONS = [
    ("Phi", ["from operator import methodcaller", "Phi = methodcaller('symbolic')(mech).Phi"],
     "methodcaller('symbolic') (cell 3)"),
    ("Phi", ["from operator import methodcaller", "f = methodcaller('symbolic')", "Phi = list(map(f, [mech]))[0].Phi"],
     "methodcaller('symbolic') (cell 4)"),
    ("Phi", ["import operator", "Phi = operator.methodcaller('symbolic')(mech).Phi"],
     "methodcaller('symbolic') (cell 3)"),
    ("Phi", ["from functools import partial", "g = partial(mech.constraint_phi, '1')", "Phi = g()"],
     "mech.constraint_phi() (cell 3)"),
    ("Phi", ["s = mech.symbolic", "Phi = s().Phi"], "mech.symbolic() (cell 2)"),
    ("Phi", ["Phi = mech.symbolic.__call__().Phi"], "mech.symbolic() (cell 2)"),
    ("Phi", ["Phi = type(mech).symbolic(mech).Phi"], "type(…).symbolic() (cell 2)"),
    ("Phi", ["Phi = mech.constraint('1').phi()"], "mech.constraint(…).phi() (cell 2)"),
    ("Phi", ["mech.symbolic()", "x = 2", "Phi = _2.Phi"], "mech.symbolic() (cell 2)"),
    ("Phi", ["m = mech", "Phi = m.symbolic().Phi"], "m.symbolic() (cell 3)"),
]


@pytest.mark.parametrize("answer, cells, expected", EVASIONS)
def test_answers_taken_from_an_exercises_reference_are_reported(answer, cells, expected):
    found = reference_use(EX11_SETUP + cells, [answer], calls=ex11_calls(), locked=[1, 2, 3])
    assert found == {answer: expected}


@pytest.mark.parametrize("answer, cells, expected", PHI_EVASIONS)
def test_the_phi_family_reached_every_other_way_is_reported(answer, cells, expected):
    assert reference_use(PHI_SETUP + cells, [answer], locked=[1]) == {answer: expected}


INNOCENT = [  # (set-up, answer, cells): look-alikes of the reference that are the student's own work
    (EX11_SETUP, "A", [OWN_A + "A = Rz(psi) @ Rx(theta) @ Rz(phi)"]),
    (EX11_SETUP, "A", [OWN_A + "def A_from_euler(a, b, c):\n    return Rz(a) @ Rx(b) @ Rz(c)",
                       "A = A_from_euler(psi, theta, phi)"]),
    (EX11_SETUP, "A", ["from kinbook.spatial import *", OWN_A + "def A_from_euler(a, b, c):\n"
                       "    return Rz(a) @ Rx(b) @ Rz(c)", "A = A_from_euler(psi, theta, phi)"]),
    (EX11_SETUP, "EGt", ["e0, e = 1.0, np.zeros(3)", "E = np.column_stack([-e, e0 * np.eye(3)])\n"
                         "G = np.column_stack([-e, e0 * np.eye(3)])", "EGt = E @ G.T"]),
    (EX11_SETUP, "A", [OWN_A + "A = Rz(psi) @ Rx(theta) @ Rz(phi)", "A", "A = _"]),
    (EX11_SETUP, "A", ["note = 'ks.A_from_euler(psi, theta, phi)'", OWN_A + "A = Rz(psi) @ Rx(theta) @ Rz(phi)"]),
    (EX11_SETUP, "A", [OWN_A + "A = Rz(psi) @ Rx(theta) @ Rz(phi)", "print(A - ks.A_from_euler(psi, theta, phi))"]),
    (PHI_SETUP, "Phi", ["class J:\n    def phi(self):\n        return sp.Matrix([x1 - x2])", "Phi = J().phi()"]),
    (PHI_SETUP, "Phi", ["class Mine:\n    def symbolic(self):\n        return sp.Matrix([x1])", "m = Mine()",
                        "Phi = m.symbolic()"]),
    (PHI_SETUP, "Phi", ["from operator import methodcaller", "class J:\n    def phi(self):\n        return 1",
                        "Phi = methodcaller('phi')(J())"]),
    (PHI_SETUP, "Phi", ["Phi = sp.Matrix([x1 - x2 + sp.cos(phi2)])", "print(Phi - mech.symbolic().Phi[0:1, :])"]),
    (PHI_SETUP, "Phi", ["expr = x1 - x2", "Phi = sp.Matrix([sp.diff(expr, x1)])"]),
    (PHI_SETUP, "Phi", ["from operator import attrgetter", "Phi = sp.Matrix([attrgetter('real')(x1 - x2)])"]),
    (PHI_SETUP, "Phi", ["import sys", "v = sys.version_info", "Phi = sp.Matrix([x1 - x2])"]),
    (PHI_SETUP, "Phi", ["class J:\n    def phi(self):\n        return sp.Matrix([x1])\n    def both(self):\n"
                        "        return self.phi()", "Phi = J().both()"]),
    # a locked cell of the release that computes with kinbook (data it hands out): the instructor's, not the student's
    (PHI_SETUP + ["ref_q = mech.symbolic()"], "Phi", ["Phi = sp.Matrix([x1 - x2])"]),
]


@pytest.mark.parametrize("setup, answer, cells", INNOCENT)
def test_look_alikes_of_the_reference_are_not_reported(setup, answer, cells):
    calls = ex11_calls() if setup is EX11_SETUP else None
    assert reference_use(setup + cells, [answer], calls=calls, locked=range(1, len(setup) + 1)) == {answer: ""}


def test_the_corpus_is_large_enough():
    assert len(EVASIONS) + len(PHI_EVASIONS) >= 20 and len(INNOCENT) >= 10
