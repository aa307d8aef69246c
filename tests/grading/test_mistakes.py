"""The catalogue is honest: every mistake generated from the reference, fed back as an answer, is caught and
named with its own code (or a code of the same kind when two mistakes coincide on a constraint), for every
constraint of the book's examples and the corpus mechanisms; and no generator looks at type names."""

import pytest

import kinbook
from kinbook.grading import check_phi
from kinbook.grading import mistakes as M
from kinbook.grading.target import target_for

from . import corpus

MECHS = ["ch13_example1", "ch13_example2", "ch13_example3", "ch13_example4", "gears", "rack", "pendulum",
         "spatial_fourbar"]


def _mech(name):
    return kinbook.examples.load(name) if name.startswith(("ch13", "spatial")) else corpus.mechanism(name)


CONSTRAINTS = [(m, c.name) for m in MECHS for c in _mech(m).constraints]


@pytest.mark.parametrize("mech_name, name", CONSTRAINTS, ids=[f"{m}:{c}" for m, c in CONSTRAINTS])
def test_every_generated_structural_mistake_is_named(mech_name, name):
    mech = _mech(mech_name)
    c = mech.constraint(name)
    t = target_for(c)
    for v in M.structural(t, c):
        r = check_phi(v.exprs, c)
        if r.passed:  # a variant that is the same constraint here (e.g. ξ_i = 0's sign), or an equivalent one
            continue
        # a variant that makes a row 0 is named zero_row, with the mistake that gives 0 said beside it
        zero_named = "zero_row" in r.mistakes and any(f"'{v.code}'" in row.message for row in r.rows)
        assert v.code in r.mistakes or zero_named, (v.code, v.detail, r)


def test_every_constraint_class_has_a_spec_by_class():
    from kinbook.core.registry import constraint_types

    for chapter in ("planar", "spatial"):
        for cls in constraint_types(chapter).values():
            spec = M.spec_of(object.__new__(cls)) if cls.kind != "driver" else None
            assert spec is None or isinstance(spec, M.Spec)
