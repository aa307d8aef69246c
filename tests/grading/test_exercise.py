"""Exercise definitions: per-student variants that assemble, reference answers from kinbook, grading."""

import numpy as np
import pytest

from kinbook import InputError, KinbookError
from kinbook.grading import Exercise, Parameter, Part
from kinbook.grading.exercise import seed_from

EX = Exercise(
    id="four-bar",
    mechanism="ch13_example1",
    parts=(
        Part("a", "Phi", constraint="3"),
        Part("b", "Phi_q", constraint="3", points=2),
        Part("c", "gamma", constraint="3"),
        Part("d", "q", t=0.01),
    ),
    parameters=(Parameter("bodies.coupler.points.A.0", -3.5, -2.5), Parameter("bodies.coupler.points.B.0", 2.5, 3.5)),
)


def test_variants_are_reproducible_and_differ_between_students():
    a, b = EX.variant("alice"), EX.variant("alice")
    assert a.values == b.values
    assert EX.variant("bob").values != a.values
    assert seed_from("alice") == seed_from("alice") and seed_from(7) == 7


def test_every_variant_assembles_where_the_book_mechanism_does():
    times = EX.assembly_times()
    assert len(times) >= 5
    for student in ("s1", "s2", "s3", "s4"):
        v = EX.variant(student)
        res = v.mechanism.simulate(times)
        assert np.abs(v.mechanism.Phi(res.q, res.t)).max() < 1e-8


def test_impossible_ranges_are_reported():
    bad = Exercise("bad", "ch13_example1", (Part("a", "Phi"),),
                   (Parameter("bodies.coupler.points.A.0", -40, -39),), max_tries=3)
    with pytest.raises(KinbookError, match="narrow the parameter ranges"):
        bad.variant("x")


def test_grading_a_student_with_error_carried_forward():
    v = EX.variant("carol")
    xi = v.values["bodies.coupler.points.A.0"]
    # the student swaps the local points in Φ and differentiates that Φ correctly
    phi = [f"x2 + {xi}*cos(phi2) - x3 - cos(phi3)", f"y2 + {xi}*sin(phi2) - y3 - sin(phi3)"]
    jac = [["1", "0", f"-({xi})*sin(phi2)", "-1", "0", "sin(phi3)"],
           ["0", "1", f"({xi})*cos(phi2)", "0", "-1", "-cos(phi3)"]]
    gamma = [f"({xi})*cos(phi2)*dphi2**2 - cos(phi3)*dphi3**2", f"({xi})*sin(phi2)*dphi2**2 - sin(phi3)*dphi3**2"]
    q = v.reference("d")
    grade = v.grade({"a": phi, "b": jac, "c": gamma, "d": q})
    assert grade.results["a"].mistakes == ["swapped_points"]
    assert grade.results["b"].passed and grade.results["c"].passed
    assert grade.points == 4.0 and grade.total == 5.0
    assert "four-bar: 4 / 5" in repr(grade)


def test_references_come_from_kinbook():
    v = EX.variant("dave")
    assert v.reference("b").shape == (2, 12)
    assert v.reference("d").shape == (12,)
    assert v.check("d", v.reference("d") + 1).mistakes == ["wrong_value"]


def test_bad_definitions():
    with pytest.raises(InputError, match="quantity"):
        Part("a", "Phi_x")
    with pytest.raises(InputError, match="no part"):
        EX.part("z")
    bad = Exercise("bad", "ch13_example1", (Part("a", "Phi"),), (Parameter("bodies.nobody.points.A.0", 1, 2),))
    with pytest.raises(InputError, match="nobody"):
        bad.variant("x")


def test_exercise_from_an_exercise_file():
    ex = Exercise.from_toml('''
id = "four-bar-3"
mechanism = "ch13_example1"
[[parts]]
name = "a"
quantity = "Phi"
constraint = "3"
order = "book"
points = 2
[[parameters]]
path = "bodies.coupler.points.A.0"
low = -3.5
high = -2.5
''')
    assert ex.total == 2.0 and ex.parts[0].order == "book" and ex.parameters[0].high == -2.5
    with pytest.raises(InputError, match="exercise definition"):
        Exercise.from_dict({"id": "x", "mechanism": "ch13_example1"})


def test_angles_in_q_are_compared_modulo_two_pi():
    v = EX.variant("erin")
    q = v.reference("d").copy()
    q[11] -= 2 * np.pi
    assert v.check("d", q).passed
