"""The catalogue, its documentation and the corpus agree."""

import re
from pathlib import Path

from kinbook import grading
from kinbook.grading import MISTAKES, explain

from . import corpus3, corpus4
from .corpus import CASES

DOC = Path(__file__).resolve().parents[2] / "docs" / "mistakes.md"


def test_every_code_is_documented_and_bilingual():
    text = DOC.read_text(encoding="utf-8")
    documented = set(re.findall(r"^\| `([a-zA-Z0-9_]+)` \|", text, flags=re.M))
    assert documented == set(MISTAKES)
    for code, m in MISTAKES.items():
        (title, hint), (titulo, pista) = explain(code, "en"), explain(code, "es")
        assert title == m.title and hint == m.hint, code
        assert titulo and pista and (titulo, pista) != (title, hint), code  # from the Spanish catalogue


def test_corpus_codes_are_catalogued_and_cover_the_planar_catalogue():
    seen = {code for case in CASES + corpus3.cases() + corpus4.cases() for code in case.mistakes}
    assert seen <= set(MISTAKES)
    # covered elsewhere: test_checks (missing_qt_term, wrong_value), test_spatial (missing_normalization),
    # test_values (scaled, not_orthogonal, not_normalized, swapped_entries)
    elsewhere = {"missing_qt_term", "wrong_value", "missing_normalization", "scaled", "not_orthogonal",
                 "not_normalized", "dependent_row", "eg_jacobian", "book_misprint", "left_handed", "factor_2_missing",
                 "full_angle", "G_for_E", "wrong_frame", "extrinsic_order", "A_for_AT", "scalar_last", "extra_row",
                 "swapped_entries",
                 # numeric try-its (tests/grading/test_tryits.py)
                 "wrong_data", "relative_speed", "rate_exchanged", "angle_rates", "assembly_mode", "not_converged",
                 "newton_step", "lever_arm", "B_for_A",
                 # a try-it's declared wrong form (tests/book/test_tryits.py)
                 "own_arm",
                 # what the mutants found (tests/grading/test_mutants.py)
                 "sin_cos", "other_body", "radians_twice", "arctan_quadrant", "factor_2_extra",
                 # tests/grading/test_domain.py (corpus_domain's names class) and corpus2's s-*-phi-local
                 "zero_row",
                 # tests/grading/test_turns.py (corpus_turns: every angle row of the shipped mechanisms)
                 "whole_turn"}
    assert set(MISTAKES) - seen <= elsewhere, set(MISTAKES) - seen - elsewhere


def test_public_api():
    for name in ("check_phi", "check_jacobian", "check_nu", "check_gamma", "check_value", "check_rotation",
                 "check_euler_parameters", "CheckResult", "set_language", "CHECKERS", "expected"):
        assert name in grading.__all__
