"""Every answer of the corpus gets exactly the verdict, score and mistake codes it states; the corpus covers
what the issue asks for; its correct answers are right by an independent derivation; verdicts repeat."""

import numpy as np
import pytest
import sympy as sp

from kinbook import grading
from kinbook.core.symbolic import derive

from . import corpus, corpus2, corpus3, corpus4

CHECKS = {
    "phi": grading.check_phi,
    "jacobian": grading.check_jacobian,
    "nu": grading.check_nu,
    "gamma": grading.check_gamma,
}

CASES = ([(case, corpus.target) for case in corpus.CASES] + [(case, corpus2.target) for case in corpus2.cases()]
         + [(case, corpus3.target) for case in corpus3.cases() + corpus3.long_cases()
                                                  + corpus3.spatial_gap_cases() + corpus3.driver_gap_cases()]
         + [(case, corpus4.target) for case in corpus4.cases()])


def _run(case, target):
    return CHECKS[case.check](case.answer, target(case.mech, case.constraint), **case.options)


@pytest.mark.parametrize("case, target", CASES, ids=[c.id for c, _ in CASES])
def test_corpus(case, target):
    result = _run(case, target)
    assert isinstance(result, grading.CheckResult)
    assert result.passed is case.passed, repr(result)
    if case.score is not None:
        assert result.score == pytest.approx(case.score, abs=1e-6), repr(result)
    assert result.mistakes == case.mistakes, repr(result)
    assert 0.0 <= result.score <= 1.0
    assert result.messages


def test_the_corpus_is_large_and_covers_every_joint_type_and_quantity():
    assert len(CASES) >= 300
    wrong = [c for c, _ in CASES if not c.passed]
    named = [c for c in wrong if c.mistakes != ["wrong_value"]]
    assert len(named) / len(wrong) >= 0.95, [c.id for c in wrong if c not in named]
    for kind in ("rev", "trans", "rr", "rt", "gear", "rack", "driver", "sph", "n1", "n2", "p1", "uni", "cyl"):
        for check in ("phi", "jac", "nu", "gamma"):
            assert any(f"{kind}-{check}" in c.id for c, _ in CASES), (kind, check)


def test_verdicts_do_not_depend_on_the_run():
    """The same answers twice (the second time with every cache of the mechanisms emptied): the same
    verdicts, scores, mistakes and messages. Nothing reads a clock."""
    sample = CASES[::7]
    first = [_run(c, t) for c, t in sample]
    for case, target in sample:
        obj = target(case.mech, case.constraint)
        getattr(obj, "mechanism", obj)._changed()
    second = [_run(c, t) for c, t in sample]
    for a, b in zip(first, second):
        assert (a.passed, a.score, a.mistakes, a.messages) == (b.passed, b.score, b.mistakes, b.messages)


# ------------------------------------------------------------------ the corpus' correct answers, derived apart
_PLANAR = {"p-rev": corpus2.rev_phi, "p-trans": corpus2.trans_phi, "p-rr": corpus2.rr_phi, "p-rt": corpus2.rt_phi}


@pytest.mark.parametrize("mech", sorted(_PLANAR))
def test_the_book_tables_typed_in_the_corpus_are_the_derivatives_of_the_typed_phi(mech):
    """Tables 13.1-13.5 as typed (corrected where errata say so) equal sympy's Φ_q and γ of the typed Φ —
    no kinbook reference involved. γ of the translational joint (the book's) holds where φ̇_j = φ̇_i."""
    names = "x1 y1 phi1 x2 y2 phi2".split()
    q = sp.symbols(names)
    qd = sp.symbols(["d" + n for n in names])
    t = sp.Symbol("t")
    env = dict(zip(names, q)) | {"d" + n: s for n, s in zip(names, qd)} | {"t": t}

    def parse(text):
        from kinbook.core.reader import read_expression

        return read_expression(text, symbols=env, where="the corpus")

    phi = [parse(r) for r in _PLANAR[mech]()]
    d = derive(phi, q, qd, t)
    kind = mech[2:]
    jac = {"rev": corpus2.rev_jac, "trans": corpus2.trans_jac, "rr": corpus2.rr_jac, "rt": corpus2.rt_jac}[kind]()
    gam = {"rev": corpus2.rev_gamma, "trans": corpus2.trans_gamma, "rr": corpus2.rr_gamma, "rt": corpus2.rt_gamma}[kind]()
    rng = np.random.default_rng(11)
    for _ in range(5):
        at = dict(zip(q, rng.uniform(-2, 2, 6))) | dict(zip(qd, rng.normal(size=6))) | {t: 0.3}
        if kind == "trans":
            at[qd[5]] = at[qd[2]]
        J = np.array(d.Phi_q.subs(at), dtype=float)
        Jt = np.array([[float(parse(e).subs(at)) for e in row] for row in jac])
        assert np.allclose(J, Jt), (mech, J, Jt)
        g = np.array(d.gamma.subs(at), dtype=float).ravel()
        gt = np.array([float(parse(e).subs(at)) for e in gam])
        assert np.allclose(g, gt), (mech, g, gt)
