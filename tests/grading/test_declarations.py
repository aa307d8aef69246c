"""A constraint type written the documented way (docs/extending.md: ``points`` with roles, ``phi``) gets the
checkers' whole catalogue, as a built-in type does: the built-in types are declared the same way, and the
catalogue reads the declaration, not a registry of its own (the architecture review's §3.1 probe)."""

import pytest

from kinbook import planar
from kinbook.grading import check_gamma, check_jacobian, check_phi
from kinbook.grading.mistakes import spec_of


class PinCopy(planar.Constraint):
    """A revolute joint as docs/extending.md teaches to write one."""

    type_name = "test-pin-copy"
    label = "r"
    n_eq = 2
    measures = ("length", "length")
    points = {"point_i": "i", "point_j": "j"}

    def phi(self, Q, t=None):
        return list(self.point(Q, "point_i") - self.point(Q, "point_j"))


def crank(documented):
    """A crank pinned to the ground at O, by the built-in revolute joint or by its documented copy."""
    m = planar.Mechanism("crank")
    m.add_body("ground", points={"O": (0, 0)})
    m.add_body("crank", points={"O": (-1, 0), "A": (1, 0)}, q0=(1, 0, 0.3))
    m.add(planar.Ground("ground"))
    joint = PinCopy("ground", "crank", point_i="O", point_j="O", name="pin") if documented else \
        planar.Revolute("ground", "crank", point="O", name="pin")
    m.add(joint)
    return joint


ANSWERS = {
    "right": ["x1 - x2 + cos(phi2)", "y1 - y2 + sin(phi2)"],
    "A transposed": ["x1 - x2 + cos(phi2)", "y1 - y2 - sin(phi2)"],
    "s' left local": ["x1 - x2 + 1", "y1 - y2"],
    "sign of A s'": ["x1 - x2 - cos(phi2)", "y1 - y2 - sin(phi2)"],
    "sign of a coordinate term": ["x1 + x2 + cos(phi2)", "y1 - y2 + sin(phi2)"],
    "degrees": ["x1 - x2 + cos(pi*phi2/180)", "y1 - y2 + sin(pi*phi2/180)"],
}


def verdict(result):
    return result.passed, result.score, sorted(result.mistakes)


def test_the_probe_a_documented_revolute_names_a_transposed_a():
    result = check_phi(ANSWERS["A transposed"], crank(documented=True))
    assert not result.passed
    assert "A_transposed" in result.mistakes


@pytest.mark.parametrize("answer", sorted(ANSWERS))
def test_a_documented_revolute_grades_exactly_like_the_built_in_one(answer):
    assert verdict(check_phi(ANSWERS[answer], crank(documented=True))) == \
        verdict(check_phi(ANSWERS[answer], crank(documented=False)))


DERIVED = {
    "Φ_q right": (check_jacobian, [["1", "0", "0", "-1", "0", "-sin(phi2)"], ["0", "1", "0", "0", "-1", "cos(phi2)"]]),
    "Φ_q, sign of the φ2 column": (check_jacobian, [["1", "0", "0", "-1", "0", "sin(phi2)"],
                                                   ["0", "1", "0", "0", "-1", "-cos(phi2)"]]),
    "γ right": (check_gamma, ["cos(phi2)*dphi2**2", "sin(phi2)*dphi2**2"]),
    "γ, sign": (check_gamma, ["-cos(phi2)*dphi2**2", "-sin(phi2)*dphi2**2"]),
}


@pytest.mark.parametrize("answer", sorted(DERIVED))
def test_derived_quantities_grade_alike_too(answer):
    check, rows = DERIVED[answer]
    assert verdict(check(rows, crank(documented=True))) == verdict(check(rows, crank(documented=False)))


def test_the_catalogue_reads_the_declaration():
    documented, built_in = spec_of(crank(documented=True)), spec_of(crank(documented=False))
    assert documented.points == (("point_i", 0), ("point_j", 1)) and built_in.points == (("s_i", 0), ("s_j", 1))
    assert documented.frame == built_in.frame == "planar"
