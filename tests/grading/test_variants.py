"""The catalogue is honest: every generated mistake, fed back as an answer, is caught and named; every
reference, fed back as an answer, passes. Runs over every constraint of every corpus mechanism."""

import pytest
import sympy as sp

from kinbook.grading import check_gamma, check_jacobian, check_nu, check_phi
from kinbook.grading import variants as V
from kinbook.symbolic import derive

from .corpus import mechanism

MECHS = ["ch13_example1", "ch13_example2", "ch13_example3", "ch13_example4", "gears", "rack", "pendulum"]
CONSTRAINTS = [(m, c.name) for m in MECHS for c in mechanism(m).constraints]


def _strings(M):
    return [[str(e) for e in M.row(k)] for k in range(M.rows)]


@pytest.mark.parametrize("mech_name, name", CONSTRAINTS, ids=[f"{m}:{c}" for m, c in CONSTRAINTS])
def test_reference_as_strings_passes_and_structural_mistakes_are_named(mech_name, name):
    mech = mechanism(mech_name)
    c = mech.constraint(name)
    d = derive(mech.constraint_phi(c), mech.q, mech.qd, mech.t)
    assert check_phi(_strings(d.Phi), c).passed
    assert check_jacobian(_strings(d.Phi_q), c).passed
    assert check_nu(_strings(d.nu), c).passed
    assert check_gamma(_strings(d.gamma), c).passed
    seen = []
    for code, M in V.structural(mech, c):
        r = check_phi(_strings(M), c)
        if r.passed:  # the variant coincides with the reference here (e.g. Aᵀ with η = 0 on a row)
            assert sp.simplify(M - d.Phi).is_zero_matrix or all(
                sp.simplify(M[k] + d.Phi[k]) == 0 or sp.simplify(M[k] - d.Phi[k]) == 0 for k in range(M.rows))
            continue
        assert code in r.mistakes or set(r.mistakes) & set(seen), (code, r)
        seen.append(code)


@pytest.mark.parametrize("mech_name", MECHS)
def test_derivation_mistakes_are_named(mech_name):
    mech = mechanism(mech_name)
    d = mech.symbolic()
    checks = {"Phi_q": check_jacobian, "nu": check_nu, "gamma": check_gamma}
    for quantity, check in checks.items():
        earlier = []
        for code, M in V.derived(d.Phi, d.q, d.qd, d.t, quantity):
            if (M - getattr(d, quantity)).is_zero_matrix:
                continue
            r = check(M, mech)
            assert not r.passed, (quantity, code)
            assert code in r.mistakes or set(r.mistakes) & set(earlier), (quantity, code, r)
            earlier.append(code)
