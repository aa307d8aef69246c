"""Data that tells mistakes apart (issue 29): 200 variants of each numeric try-it, drawn as kb.another draws
them, admit no slip of the worked answer that passes — the data at which sin = cos, a zero rate under a rate term,
arctan = arctan2 are not drawn — and the notebook's own data tell every slip apart.

Three try-its solve a mechanism at every draw (an instant t drawn from an interval): 50 variants each, so that
`make test` stays within minutes on two busy cores (each took about 2 minutes for 200)."""

import pytest

from kinbook.book.tryits import TRY_ITS
from kinbook.book.tryits.mutations import blind_spots, function_mutants, variant_data

from .mutation_table import get


def _numeric():
    get("13-1/try-1")  # registers the try-its
    return [id for id in TRY_ITS if TRY_ITS[id].ranges and function_mutants(id)]


SOLVING = {"13-5/try-3": 50, "13-7/try-2": 50, "14-5/try-1": 50}
"""Try-its whose every draw solves the mechanism: variants drawn (the others: 200)."""


@pytest.mark.parametrize("id", _numeric())
def test_no_variant_draw_lets_a_slip_pass(id):
    item = TRY_ITS[id]
    assert blind_spots(item, item.data) == []
    for k in range(1, SOLVING.get(id, 200) + 1):
        data = variant_data(item, k)
        assert data is not None, (id, k)
        assert blind_spots(item, data) == [], (id, k, data)
        if k > 5:
            continue
        for m in function_mutants(id):  # the first variants: every slip through the whole check, not a pre-filter
            try:
                answer = m.value(**item.context(), **{n: data[n] for n in item._data_names()})
            except Exception:  # noqa: BLE001 — a slip that cannot run on these data is no answer
                continue
            assert not item.check(answer, data).passed, (id, k, m.operator, data)


def test_another_draws_only_data_that_tell_slips_apart():
    from kinbook.book.tryits import another

    try:
        for k in range(1, 30):  # 13-1/try-2 draws its angle from 15°, 30° … 345°: never 45° nor 225°
            v = another("13-1/try-2", k)
            assert v.data["phi_i_deg"] % 180 != 45, v.data  # sin = cos at 45° and 225° only
    finally:
        another("13-1/try-2", 0)
