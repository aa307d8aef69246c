"""Whole turns (part of the diagnosis of Φ): a row that measures a length, written with 2πk added.

A row that measures an angle may differ from the reference by whole turns (the match accepts it:
:func:`~kinbook.grading.equivalence.turned_multiple` with ``Target.turns``); a length may not. An answer row that
is a multiple of a length row plus 2πk — the turn of an angle row put on the wrong row, or a wrap of an
angle applied where there is none — is named ``whole_turn`` with the number of turns. Numbers of Φ given at a
configuration follow the same rule, row by row.
"""

from __future__ import annotations

import numpy as np

from ._i18n import Msg
from .equivalence import nice, turned_multiple

__all__ = ["TURN", "name_whole_turns", "name_turned_rows"]

TURN = 2 * np.pi


def name_whole_turns(target, data, matching, rtol):
    """Rows named ``wrong_value`` against a reference row that is no angle, that are a multiple of that row turned
    by whole turns at every generic sample: ``whole_turn``."""
    name_turned_rows(target, data.S_G, data.R_G, matching.rows, rtol)


def name_turned_rows(target, S, R, rows, rtol, free=True):
    """:func:`name_whole_turns` on values ``S`` (N, answer rows) and ``R`` (N, reference rows) — the generic samples
    of an expression, or numbers at one configuration (``free=False``: the row itself turned, no factor)."""
    for r in rows:
        if r.status != "wrong" or r.code != "wrong_value" or r.ref is None:
            continue
        if r.ref in target.turns or r.ref in target.wrap:
            continue
        c, n = turned_multiple(S[:, r.k], R[:, r.ref], rtol, TURN, free)
        if n[0]:
            r.code = "whole_turn"
            r.detail = Msg("d.whole_turn", ref=target.label(r.ref), row=_turned(target.label(r.ref), c[0], n[0]))


def _turned(label, c, n):
    """c·(Φ_k + 2πn) as a student reads it: Φ_4 + 2π, −(Φ_4 − 4π), 2·(Φ_4 + 2π)."""
    m = 2 * abs(int(n))
    inner = f"{label} {'+' if n > 0 else '−'} {m}π"
    c = nice(c)
    if c == 1:
        return inner
    if c == -1:
        return f"−({inner})"
    return f"{c:g}·({inner})"
