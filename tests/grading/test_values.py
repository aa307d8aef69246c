"""Numeric answers: numbers, vectors, matrices, rotation matrices and Euler parameters."""

import numpy as np
import pytest

from kinbook.grading import check_euler_parameters, check_rotation, check_value


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


ANGLES = (0.3, 0.7, -0.4)  # ψ, θ, φ
A = rz(ANGLES[0]) @ rx(ANGLES[1]) @ rz(ANGLES[2])
AXIS = np.array([1.0, 2.0, 2.0]) / 3.0
CHI = 0.9
P = np.concatenate([[np.cos(CHI / 2)], AXIS * np.sin(CHI / 2)])


@pytest.mark.parametrize("answer, expected, passed, mistakes, kw", [
    (1.0004, 1.0, True, [], {}),
    ([1.0, 2.0], [1.0, 2.0001], True, [], {}),
    ([[1, 2], [3, 4]], [[1, 2], [3, 4]], True, [], {}),
    ([1.0, 2.1], [1.0, 2.0], False, ["wrong_value"], {}),
    ([-1.0, -2.0], [1.0, 2.0], False, ["sign_flip"], {}),
    ([2.0, 4.0], [1.0, 2.0], False, ["scaled"], {}),
    ([[1, 3], [2, 4]], [[1, 2], [3, 4]], False, ["transposed"], {}),
    ([[1, 2, 3]], [[1], [2], [3]], True, [], {}),  # a row for a column vector of numbers: accepted
    ([[1, 2, 3], [4, 5, 6]], [[1, 4], [2, 5], [3, 6]], False, ["transposed"], {}),
    ([1.0, 2.0, 3.0], [1.0, 2.0], False, ["wrong_shape"], {}),
    ([np.nan, 1.0], [1.0, 1.0], False, ["not_finite"], {}),
    ("abc", [1.0], False, ["malformed"], {}),
    ([57.29578, 114.59156], [1.0, 2.0], False, ["degrees"], {"angles": True}),
    ([[1.0], [2.0]], [1.0, 2.0], True, [], {}),
])
def test_check_value(answer, expected, passed, mistakes, kw):
    r = check_value(answer, expected, **kw)
    assert (r.passed, r.mistakes) == (passed, mistakes), repr(r)


@pytest.mark.parametrize("answer, expected, detail", [
    ([1.0, -2.0, 3.0], [1.0, 2.0, 3.0], "the sign of value[2]"),
    ([[1.0, 2.0], [-3.0, 4.0]], [[1.0, 2.0], [3.0, 4.0]], "the sign of value[2, 1]"),
    ([2.0, 1.0, 3.0], [1.0, 2.0, 3.0], "value[1] and value[2] are exchanged"),
    ([[3.0, 4.0], [1.0, 2.0], [5.0, 6.0]], [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]], "rows 1 and 2 are exchanged"),
    ([[2.0, 1.0, 3.0], [5.0, 4.0, 6.0]], [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], "columns 1 and 2 are exchanged"),
])
def test_some_entries_negated_or_two_exchanged_are_named(answer, expected, detail):
    r = check_value(answer, expected)
    code = "sign_flip" if "sign" in detail else "swapped_entries"
    assert r.mistakes == [code], repr(r)
    assert any(str(n) == detail for n in r.notes), [str(n) for n in r.notes]
    right = sum(1 for a, e in zip(np.ravel(answer), np.ravel(expected)) if a == e)
    assert r.score == pytest.approx(right / np.size(expected))


def test_an_entry_changed_otherwise_is_still_a_wrong_value():
    assert check_value([1.0, 2.5, 3.0], [1.0, 2.0, 3.0]).mistakes == ["wrong_value"]
    assert check_value([3.0, 1.0, 2.0], [1.0, 2.0, 3.0]).mistakes == ["wrong_value"]  # not one exchange


def test_check_value_partial_credit_per_entry():
    r = check_value([1.0, 2.0, 3.0, 5.0], [1.0, 2.0, 3.0, 4.0])
    assert r.score == pytest.approx(0.75)
    assert [row.status for row in r.rows] == ["ok", "ok", "ok", "wrong"]


def test_rotation():
    assert check_rotation(A, A).passed
    assert check_rotation(A.T, A).mistakes == ["transposed"]
    skewed = A.copy()
    skewed[0, 0] += 0.3
    r = check_rotation(skewed, A)
    assert r.mistakes == ["not_orthogonal"]
    deg = rz(np.degrees(ANGLES[0])) @ rx(np.degrees(ANGLES[1])) @ rz(np.degrees(ANGLES[2]))
    assert check_rotation(deg, A, angles=ANGLES).mistakes == ["degrees"]
    assert check_rotation(A[:2], A).mistakes == ["wrong_shape"]
    assert check_rotation(rz(0.5), A).mistakes == ["wrong_value"]


def test_euler_parameters():
    assert check_euler_parameters(P, P).passed
    r = check_euler_parameters(-P, P)
    assert r.passed and "−p" in r.messages[0]
    assert check_euler_parameters(2 * P, P).mistakes == ["not_normalized"]
    assert check_euler_parameters(-3 * P, P).mistakes == ["not_normalized"]
    chi = np.degrees(CHI)
    p_deg = np.concatenate([[np.cos(chi / 2)], AXIS * np.sin(chi / 2)])
    assert check_euler_parameters(p_deg, P, axis=AXIS, angle=CHI).mistakes == ["degrees"]
    assert check_euler_parameters(P[:3], P).mistakes == ["wrong_shape"]
    assert check_euler_parameters([1, 0, 0, 0], P).mistakes == ["wrong_value"]


@pytest.mark.parametrize("seed", range(8))
def test_euler_parameters_when_the_question_asks_for_e0_nonnegative(seed):
    """ex11 (b): "with e0 ≥ 0". −p is the same orientation and a sign error for that question; the other catalogued
    forms keep their names; a half turn (e0 = 0) has both signs right."""
    from kinbook.grading import expected

    rotations = pytest.importorskip("kinbook.spatial.rotations")
    rng = np.random.default_rng(seed)
    A_ = rotations.A_from_euler(*rng.uniform(0.1, 1.4, 3))
    p = np.asarray(rotations.p_from_A(A_))
    assert p[0] > 0 and np.allclose(rotations.A_from_p(p), A_)                       # the e0 ≥ 0 representative
    asked = expected.p_from_A(A_, e0_nonnegative=True)
    assert check_euler_parameters(p, asked).passed
    r = check_euler_parameters(-p, asked)
    assert (r.passed, r.score, r.mistakes) == (False, 0.0, ["sign_flip"])
    assert check_euler_parameters(np.r_[p[1:], p[0]], asked).mistakes == ["scalar_last"]
    assert check_euler_parameters(-p, expected.p_from_A(A_)).passed                   # without the option: −p is right
    half = rotations.A_from_p(np.r_[0.0, 0.6, 0.0, 0.8])                             # a half turn about (0.6, 0, 0.8)
    q = np.asarray(rotations.p_from_A(half))
    assert check_euler_parameters(q, expected.p_from_A(half, e0_nonnegative=True)).passed
    assert check_euler_parameters(-q, expected.p_from_A(half, e0_nonnegative=True)).passed


def test_rotation_against_kinbook_spatial():
    rotations = pytest.importorskip("kinbook.spatial.rotations")
    expected = rotations.A_from_euler(*ANGLES)
    assert check_rotation(A, expected).passed
    p = rotations.p_from_A(expected)
    assert check_euler_parameters(-np.asarray(p), p).passed


@pytest.mark.parametrize("kw, arg", [
    ({"rtol": -1}, "rtol"), ({"rtol": 0.5}, "rtol"), ({"rtol": "1e-3"}, "rtol"), ({"rtol": np.nan}, "rtol"),
    ({"atol": -1e-9}, "atol"), ({"atol": 10.0}, "atol"), ({"atol": True}, "atol"),
    ({"periodic": [5]}, "periodic"), ({"periodic": [0.5]}, "periodic"), ({"periodic": [[0, 1]]}, "periodic"),
    ({"periodic": [True]}, "periodic"), ({"angles": "yes"}, "angles"), ({"reveal": "no"}, "reveal"),
    ({"name": 3}, "name"),
])
def test_a_bad_option_is_refused_naming_it(kw, arg):
    """A tolerance that would fail a right answer ("expected 1, got 1") or pass a wrong one, an index numpy would
    trip on: an InputError naming the argument, never a verdict."""
    from kinbook.errors import InputError

    with pytest.raises(InputError, match=f"`{arg}`"):
        check_value([1.0, 2.0], [1.0, 2.0], **kw)


@pytest.mark.parametrize("call, arg", [
    (lambda: check_rotation(A, A, angles=(1.0, 2.0)), "angles"),
    (lambda: check_rotation(A, A, angles=(0.1, 0.2, 0.3)), "angles"),
    (lambda: check_rotation(A, A[:2]), "expected"),
    (lambda: check_euler_parameters(P, P, axis=AXIS), "axis"),
    (lambda: check_euler_parameters(P, P, axis=[0, 0, 0], angle=1.0), "axis"),
    (lambda: check_euler_parameters(P, P, axis=AXIS, angle="x"), "angle"),
    (lambda: check_euler_parameters(P, P, axis=[1, 0, 0], angle=CHI), "axis"),
    (lambda: check_euler_parameters(P, 2 * P), "expected"),
    (lambda: check_value(1.0, np.nan), "expected"),
    (lambda: check_value(1.0, "abc"), "expected"),
])
def test_rotation_and_parameter_options_are_validated(call, arg):
    from kinbook.errors import InputError

    with pytest.raises(InputError, match=f"`{arg}`"):
        call()


def test_periodic_compares_angles_modulo_a_turn_and_numeric_strings_are_read():
    assert check_value([1.0, 0.5 - 2 * np.pi], [1.0, 0.5], periodic=[1]).passed
    assert check_value([1.0, 0.5 - 2 * np.pi], [1.0, 0.5], periodic=[False, True]).passed
    assert not check_value([1.0, 0.5 - 2 * np.pi], [1.0, 0.5]).passed
    assert check_value(["pi/4", "-0.5"], [np.pi / 4, -0.5]).passed
    r = check_value({"a": 1}, [1.0])
    assert r.mistakes == ["malformed"] and "dict" in r.messages[0]


def test_without_reveal_a_wrong_number_is_described_never_given():
    exp = [1.2345678, -2.3456789]
    for wrong in ([1.0, -2.3456789], [-1.2345678, 2.3456789], [12.0, -2.3456789], [0.0, 0.0]):
        r = check_value(wrong, exp, reveal=False)
        text = " ".join(r.messages + [row.message for row in r.rows])
        assert not r.passed and "1.23457" not in text and "2.34568" not in text, text
    r = check_value([1.0, -2.3456789], exp, reveal=False)
    assert "value[1] is too small" in r.messages[0] and r.rows[1].status == "ok"
    assert "wrong sign" in check_value(-1.5, 1.5, reveal=False).messages[0]
    assert "expected [1.23457, -2.34568]" in check_value([1.0, -2.3456789], exp).messages[0]   # exercises: reveal


def test_multiplied_by_only_for_a_plausible_factor_of_a_nonzero_value():
    assert check_value([0.0, 0.0], [3.0, 4.0]).mistakes == ["wrong_value"]          # v of a fixed point: not "× 0"
    assert check_value([1.37 * 3, 1.37 * 4], [3.0, 4.0]).mistakes == ["wrong_value"]   # not a plausible factor
    assert check_value([1.5, 2.0], [3.0, 4.0]).mistakes == ["scaled"]
    assert check_value([3000.0, 4000.0], [3.0, 4.0]).mistakes == ["scaled"]
