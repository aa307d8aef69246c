"""The answer as it was read (issue 29): every check result shows the student's answer as kinbook read it —
typeset in the notebook, plain text in a terminal and on feedback pages — before the verdict."""

import re

import numpy as np
import pytest

import kinbook
from kinbook.book.tryits import try_it
from kinbook.grading import check_gamma, check_jacobian, check_phi, check_rotation, check_value


@pytest.fixture(scope="module")
def revolute():
    return kinbook.examples.load("ch13_example1").constraint("1")


def test_a_symbolic_answer_is_shown_as_parsed(revolute):
    r = check_phi(["x1 - x2 + sin(phi2)", "y1-y2+cos( phi2 )"], revolute)
    assert r.read[0] == "[x1 - x2 + sin(phi2), y1 - y2 + cos(phi2)]"
    text = repr(r)
    lines = text.splitlines()
    assert lines[1] == "  your answer, as read: [x1 - x2 + sin(phi2), y1 - y2 + cos(phi2)]"
    assert "sin and cos exchanged" in text and text.index("as read") < text.index("sin and cos exchanged")
    html = r._repr_html_()  # the notebook: LaTeX for MathJax in the book's notation, before the verdict
    assert re.search(r"\\\[.*x_\{1\} - x_\{2\} \+ \\sin\{\\left\(\\varphi_\{2\} \\right\)\}.*\\\]", html)
    assert html.index("kb-read") < html.index("score 0.")
    plain = r.html(math=False)  # a feedback page: plain text
    assert "<code>[x1 - x2 + sin(phi2), y1 - y2 + cos(phi2)]</code>" in plain and "\\[" not in plain


def test_derived_quantities_and_numbers_are_echoed(revolute):
    J = check_jacobian([["1", "0", "0", "-1", "0", "-sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]],
                       revolute)
    assert J.read[0].startswith("[[1, 0, 0, -1, 0, -sin(phi2)]")
    g = check_gamma(["cos(phi2)*dphi2**2", "sin(phi2)*dphi2**2"], revolute)
    assert "\\dot{\\varphi}_{2}" in g.read[1]
    v = check_value([0.1 + 0.2, 4e-17], [0.3, 0.0])
    assert v.read == ("[0.3, 0]", r"\begin{bmatrix} 0.3 \\ 0 \end{bmatrix}")  # round-off reads 0
    R = check_rotation(np.eye(3), np.eye(3))
    assert R.read[0] == "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]"


def test_a_refused_answer_is_not_echoed(revolute):
    r = check_phi(["x1 - (x2"], revolute)
    assert r.read is None and "as read" not in repr(r)


def test_a_tryit_result_shows_the_answer_as_read():
    r = try_it("13-1/try-2", [1.0, 2.0])
    assert r.read[0] == "[1, 2]" and "your answer, as read: [1, 2]" in repr(r)
    r = try_it("13-2/try-1", ["x1 + cos(phi1) - x2 + 1.5*cos(phi2)", "y1 - y2"])
    assert r.read is not None and "\\varphi_{1}" in r._repr_html_()
