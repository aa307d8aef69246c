"""Every try-it and every shipped exercise tested the way a student breaks it (issue 29): the mutants of each
reference (kinbook.grading.mutants) graded by the real check on the notebook's data and on a drawn variant — no
mutant passes (0 blind spots) and at least 95 % are named by the code they stand for; and no variant draw admits
data under which a slip of the worked answer passes.

Run time: a sample of at most LIMIT mutants per part and data (every code kept), one variant besides the
notebook's (or the source's) data; the figures printed by ``kinbook validate --mutations`` with the defaults are in
docs/instructors.md and benchmarks/README.md.
"""

from pathlib import Path

import pytest

from kinbook.book.tryits import TRY_ITS, get
from kinbook.book.tryits.mutations import blind_spots, function_mutants, mutation_tallies, variant_data
from kinbook.grading.mutants import format_table

LIMIT = 40
EXERCISES = sorted((Path(__file__).resolve().parents[2] / "exercises").glob("ex*.ipynb"))


@pytest.fixture(scope="module")
def tryit_tallies():
    get("13-1/try-1")
    return mutation_tallies(variants=1, limit=LIMIT)


@pytest.fixture(scope="module")
def exercise_tallies():
    from kinbook.classroom.validate.mutations import mutation_tallies as exercise

    tallies, failures = [], []
    for source in EXERCISES:
        found, failed = exercise(source, variants=1, limit=LIMIT)
        tallies += found
        failures += failed
    return tallies, failures


def _check(tallies):
    text = format_table(tallies)
    n = sum(t.mutants for t in tallies)
    named = sum(t.named for t in tallies)
    assert sum(t.blind for t in tallies) == 0, text
    assert n > 0 and named >= 0.95 * n, text
    return n, named


def test_every_tryit_refuses_and_names_its_mutants(tryit_tallies):
    assert len(tryit_tallies) == len(TRY_ITS) == 36
    n, _ = _check(tryit_tallies)
    assert n >= 1000  # every try-it has mutants: no table is empty by accident
    assert all(t.mutants for t in tryit_tallies if t.item not in ("13-6/try-2",)), format_table(tryit_tallies, False)


def test_every_exercise_part_refuses_and_names_its_mutants(exercise_tallies):
    tallies, failures = exercise_tallies
    assert len({t.item.split(":")[0] for t in tallies}) == len(EXERCISES) == 12
    assert not failures
    _check(tallies)


def _numeric():
    get("13-1/try-1")  # registers the try-its
    return [id for id in TRY_ITS if TRY_ITS[id].ranges and function_mutants(id)]


NUMERIC = _numeric()


@pytest.mark.parametrize("id", NUMERIC)
def test_no_variant_draw_lets_a_slip_pass(id):
    """200 variants of each numeric try-it, drawn as kb.another draws them: none admits a passing slip (the data
    at which sin = cos, a zero rate under a rate term, arctan = arctan2 are not drawn), and the notebook's own data
    tell every slip apart."""
    item = TRY_ITS[id]
    assert blind_spots(item, item.data) == []
    for k in range(1, 201):
        data = variant_data(item, k)
        assert data is not None, (id, k)
        assert blind_spots(item, data) == [], (id, k, data)
        if k > 10:
            continue
        for m in function_mutants(id):  # the first variants: every slip through the whole check, not a pre-filter
            try:
                answer = m.value(**item.context(), **{n: data[n] for n in item._data_names()})
            except Exception:  # noqa: BLE001 — a slip that cannot run on these data is no answer
                continue
            assert not item.check(answer, data).passed, (id, k, m.operator, data)
