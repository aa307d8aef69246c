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


def test_rotation_against_kinbook_spatial():
    rotations = pytest.importorskip("kinbook.spatial.rotations")
    expected = rotations.A_from_euler(*ANGLES)
    assert check_rotation(A, expected).passed
    p = rotations.p_from_A(expected)
    assert check_euler_parameters(-np.asarray(p), p).passed
