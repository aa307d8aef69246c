"""kinbook.grading.mutants: each operator makes the mistake it names, equal mutants are dropped, and the checkers
name what the mutants of a reference are (issue 29)."""

import numpy as np
import pytest
import sympy as sp

import kinbook
from kinbook.grading import check_gamma, check_jacobian, check_phi, check_value
from kinbook.grading import mutant_names as MN
from kinbook.grading import mutants as MU


@pytest.fixture(scope="module")
def four_bar():
    return kinbook.examples.load("ch13_example1")


def _codes(found):
    return {m.code for m in found} | {c for m in found for c in m.also}


def test_expression_operators_make_their_mistakes():
    x1, x2, p1, p2 = sp.symbols("x1 x2 phi1 phi2", real=True)
    dx1, dx2, dp1, dp2 = sp.symbols("dx1 dx2 dphi1 dphi2", real=True)
    row = x1 + 0.5 * sp.cos(p1) - x2 - 1.5 * sp.cos(p2)
    found = MU.expression_mutants([row], groups=[([x1, p1], [dx1, dp1]), ([x2, p2], [dx2, dp2])],
                                  q=[x1, p1, x2, p2], qd=[dx1, dp1, dx2, dp2], t=sp.Symbol("t"))
    by_op = {m.operator: m.value[0] for m in found}
    assert sp.simplify(by_op["sin↔cos of phi1"] - (x1 + 0.5 * sp.sin(p1) - x2 - 1.5 * sp.cos(p2))) == 0
    other = next(v for k, v in by_op.items() if k.startswith("the other body's angle"))
    assert sp.simplify(other - (x1 + 0.5 * sp.cos(p2) - x2 - 1.5 * sp.cos(p1))) == 0
    assert {"sign_flip", "missing_term", "sin_cos", "degrees", "radians_twice", "other_body",
            "swapped_bodies"} <= _codes(found)
    # Aᵀ for A changes nothing in a row without sin: dropped as equal to the reference
    assert not any(m.code == "A_transposed" for m in found)


def test_a_mutant_equal_to_the_reference_is_dropped():
    x = sp.Symbol("x", real=True)
    same = MU.Mutant("sign_flip", "rewritten", [2 * sp.sin(x) * sp.cos(x)])
    other = MU.Mutant("sin_cos", "swapped", [sp.cos(2 * x)])
    kept = MU.distinct([same, other], [sp.sin(2 * x)])
    assert [m.code for m in kept] == ["sin_cos"]


def test_repeated_wrong_answers_are_counted_once_with_both_readings():
    x = sp.Symbol("x", real=True)
    a = MU.Mutant("sign_flip", "sign", [-sp.sin(x) + 1])
    b = MU.Mutant("A_transposed", "A^T", [1 - sp.sin(x)])
    kept = MU.distinct([a, b], [sp.sin(x) + 1])
    assert len(kept) == 1 and kept[0].also == {"A_transposed"}


def _worked(*, phi_deg, xi):
    phi = np.radians(phi_deg)
    return [xi * np.cos(phi), xi * np.sin(phi) + 2 * xi]


def test_code_operators_and_the_data_that_hides_them():
    runs = [lambda f, d=d: f(**d) for d in ({"phi_deg": 45, "xi": 1.0}, {"phi_deg": 30, "xi": 0.7})]
    from kinbook.book.tryits.code_mutants import code_mutants

    found = code_mutants(_worked, runs=runs)
    codes = _codes(found)
    assert {"sin_cos", "degrees", "radians_twice", "sign_flip", "missing_term", "factor_2_missing"} <= codes
    swap = next(m for m in found if m.operator == "np.cos → np.sin")
    # at 45° sin = cos: this slip is invisible there, visible at 30°
    assert np.allclose(swap.value(phi_deg=45, xi=1.0), _worked(phi_deg=45, xi=1.0))
    assert not np.allclose(swap.value(phi_deg=30, xi=0.7), _worked(phi_deg=30, xi=0.7))


def test_value_mutants():
    A = np.array([[0.6, -0.8], [0.8, 0.6]])
    found = MU.value_mutants(A)
    assert "transposed" in _codes(found)
    assert "sign_flip" in next(m for m in MU.value_mutants(np.array([[0.0, -1.0], [1.0, 0.0]]))
                               if m.code == "transposed" or "transposed" in m.also).also | {"sign_flip"}
    assert all(not np.allclose(m.value, A) for m in found)
    ang = MU.value_mutants(0.7, angles=True)
    assert {"degrees", "radians_twice"} <= _codes(ang)


def test_classify():
    m = MU.Mutant("missing_term", "drop", [sp.Integer(0)])
    assert MN.classify(check_value(1.0, 1.0), m)[0] == "blind"
    assert MN.classify(check_value(-2.0, 2.0), MU.Mutant("sign_flip", "s", -2.0))[0] == "named"
    assert MN.classify(check_value(1.37, 2.0), MU.Mutant("sign_flip", "s", 1.37)) == ("unnamed", ("wrong_value",))


@pytest.mark.parametrize("quantity, checker", [("Phi", check_phi), ("Phi_q", check_jacobian),
                                               ("gamma", check_gamma)])
def test_the_checkers_name_the_mutants_of_a_revolute_joint(four_bar, quantity, checker):
    c = four_bar.constraint("2")
    found = MU.reference_mutants(c, quantity)
    assert found
    named = 0
    for m in found:
        M = sp.Matrix(m.value)
        answer = ([[str(M[i, j]) for j in range(M.shape[1])] for i in range(M.shape[0])] if M.shape[1] > 1
                  else [str(e) for e in M])
        outcome, given = MN.classify(checker(answer, c), m)
        assert outcome != "blind", (m.code, m.operator)
        named += outcome == "named"
    assert named >= 0.9 * len(found)


def test_sample_keeps_every_code():
    found = [MU.Mutant("sign_flip", str(k), k) for k in range(50)] + [MU.Mutant("sin_cos", "s", 0)]
    picked = MU.sample(found, 10)
    assert len(picked) == 10 and "sin_cos" in {m.code for m in picked}


def test_format_table_totals():
    t = MN.Tally("x")
    t.add(MU.Mutant("sin_cos", "s", 0), "named")
    t.add(MU.Mutant("sign_flip", "s", 0), "blind", where="the notebook's data", why="the data")
    text = MN.format_table([t])
    assert "BLIND" in text and "named 50.0 %" in text


def test_the_new_codes_are_named_on_realistic_answers(four_bar):
    """sin_cos, other_body, radians_twice, arctan_quadrant, factor_2_extra: each named on the answer a student
    writes, by the checker (never the generic 'wrong value')."""
    from kinbook.book.tryits import TRY_ITS, get

    c = four_bar.constraint("4")  # revolute coupler–rocker
    rows = [str(e) for e in four_bar.constraint_phi(c)]
    a, b = (f"phi{body.number}" for body in c.bodies)
    swapped = [r.replace(a, "PHI").replace(b, a).replace("PHI", b) for r in rows]  # each point turned by the other angle
    assert check_phi(swapped, c).mistakes == ["other_body"]
    one_angle = [r.replace(f"sin({a})", "SIN").replace(f"cos({a})", f"sin({a})").replace("SIN", f"cos({a})")
                 for r in rows]
    assert check_phi(one_angle, c).mistakes == ["sin_cos"]
    g = [str(e) for e in four_bar.derivation(c).gamma]
    doubled = [e.replace(f"d{a}**2", f"2*d{a}**2") for e in g]
    assert "factor_2_extra" in check_gamma(doubled, c).mistakes
    get("13-1/try-1")
    item = TRY_ITS["13-1/try-2"]
    d = item.data
    phi = np.radians(np.radians(d["phi_i_deg"]))
    twice = [d["x_Oi"] + d["xi_Q"] * np.cos(phi) - d["eta_Q"] * np.sin(phi),
             d["y_Oi"] + d["xi_Q"] * np.sin(phi) + d["eta_Q"] * np.cos(phi)]
    assert item.check(twice).mistakes == ["radians_twice"]
    item = TRY_ITS["14-2/try-3"]
    A = np.asarray(item.data["A_given"])
    quadrant = [np.arctan(A[0, 2] / -A[1, 2]), np.arccos(A[2, 2]), np.arctan2(A[2, 0], A[2, 1])]
    assert item.check(quadrant).mistakes == ["arctan_quadrant"]


def test_the_theta_rate_slip_no_longer_passes():
    """14-2 Try it 2 had θ̇ = 0, where both θ̇ terms with the wrong sign passed (review s4, FALSE-PASS 3)."""
    from kinbook.book.tryits import TRY_ITS, get

    get("13-1/try-1")
    item = TRY_ITS["14-2/try-2"]
    d = item.data
    th, ph = np.radians([d["theta_deg"], d["phi_deg"]])
    wrong = [np.sin(th) * np.sin(ph) * d["psi_rate"] - np.cos(ph) * d["theta_rate"],
             np.sin(th) * np.cos(ph) * d["psi_rate"] + np.sin(ph) * d["theta_rate"],
             np.cos(th) * d["psi_rate"] + d["phi_rate"]]
    assert not item.check(wrong).passed
