"""Every argument of the symbolic checkers is checked, and a bad one is refused with a message that names it and
repeats what was given (issue 22 item 8); inputs that are numbers in another dress are read as numbers."""

import numpy as np
import pytest

import kinbook
from kinbook.grading import check_gamma, check_jacobian, check_nu, check_phi

EX1 = kinbook.examples.load("ch13_example1")
JOINT = EX1.constraint("1")  # x1 − x2 + cos φ2 = 0, y1 − y2 + sin φ2 = 0 (s'_2 = (−1, 0))
RIGHT = ["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"]


@pytest.mark.parametrize("check", [check_phi, check_jacobian, check_nu, check_gamma])
@pytest.mark.parametrize("option, value, text", [
    ("rtol", -1e-6, "`rtol` must be a number between 0 and 1 (a relative tolerance), got -1e-06"),
    ("rtol", 2.0, "`rtol` must be a number between 0 and 1 (a relative tolerance), got 2.0"),
    ("rtol", True, "`rtol` must be a number between 0 and 1 (a relative tolerance), got True"),
    ("rtol", "1e-6", "`rtol` must be a number between 0 and 1 (a relative tolerance), got '1e-6'"),
    ("rtol", float("nan"), "`rtol` must be a number between 0 and 1 (a relative tolerance), got nan"),
    ("symbolic", "yes", "`symbolic` must be True or False, got 'yes'"),
    ("at", [0.0] * 6, "`at` must be a dict {'q': …, 'qd': …, 't': …} with q and qd of the mechanism's 12 "
                      "coordinates, got [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]"),
    ("at", {"x": 1}, "`at` must be a dict"),
    ("at", {"q": [0.0] * 5}, "`at['q']` must be a dict"),
    ("at", {"q": [0.0] * 12, "t": "soon"}, "`at['t']` must be a dict"),
    ("at", {"q": [np.inf] * 12}, "`at['q']` must be a dict"),
    ("order", "random", "`order` must be 'any' or 'book', got 'random'"),
])
def test_a_bad_option_is_refused_by_name(check, option, value, text):
    r = check(RIGHT if check is not check_jacobian else [["1"] * 6] * 2, JOINT, **{option: value})
    assert not r.passed and r.mistakes == ["malformed"], r
    assert text in r.messages[0], r.messages


def test_good_options_are_used():
    assert check_phi(RIGHT, JOINT, rtol=1e-8, symbolic=True, order="book").passed
    assert check_phi(RIGHT, JOINT, rtol=np.float64(1e-4)).passed


def test_a_function_whose_output_changes_shape_is_refused_saying_so():
    def phi(q, t):  # a third row for half the configurations
        rows = [q[0] - q[3] + np.cos(q[5]), q[1] - q[4] + np.sin(q[5])]
        return np.array(rows + [0.0] if q[5] > 0 else rows)

    r = check_phi(phi, JOINT)
    assert not r.passed and r.mistakes == ["wrong_shape"], r
    assert "it must return the same shape every time" in r.messages[0], r
    assert "(2, 1)" in r.messages[0] and "(3, 1)" in r.messages[0], r


def test_numeric_strings_are_numbers():
    """ν of example 1 typed as strings of numbers (ν = 0 for every joint, 100 for the driver φ2 − 3π/4 − 100t),
    in a list or an array; Φ as strings of its values at an assembled configuration (zero), graded at=."""
    nu = ["0"] * 11 + ["100"]
    assert check_nu(nu, EX1).passed
    assert check_nu(np.array(nu), EX1).passed
    q = EX1.solve_position(0.0)
    assert check_phi(np.array(["0.0"] * 12), EX1, at={"q": q, "t": 0.0}).passed
    assert not check_phi(["0.0"] * 12, EX1).passed  # without at=: twelve constant rows, no Φ


def test_a_function_returning_text_says_what_it_returned():
    r = check_phi(lambda q, t: ["a", "b"], JOINT)
    assert not r.passed and r.mistakes == ["malformed"], r
    assert "expected real numbers, got list ['a', 'b']" in r.messages[0], r
