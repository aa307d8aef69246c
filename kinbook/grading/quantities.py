"""The four graded quantities — Φ, Φ_q, ν, γ — declared once.

A :class:`Quantity` says what varies from one quantity to the next: how it is derived from the mechanism, how its
rows may be scaled (its factor rule), the sign mistake and the other catalogue entries that belong to it, and the
steps that run after the rows are matched. The stages (read, evaluate, match, diagnose, witness, report) and the
catalogue read these declarations; none of them asks which quantity it has by its name. Adding a quantity means
declaring one more here (docs/extending.md).

The factor rules (§13.2: Φ(q, t) = 0 is a set of equations):

* Φ: a row may carry any nonzero constant (−1 included);
* Φ_q: the factor −1 only (the Jacobian of −Φ_k is right); another constant c is the Jacobian of c·Φ_k with a
  factor of the derivative missing (``scaled``), unless the student's own Φ (``phi=``) carries it;
* ν and γ: their rows follow the rows of Φ they come from — factor 1, or the factor of the student's own Φ row.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

__all__ = ["Quantity", "QUANTITIES", "PHI", "PHI_Q", "NU", "GAMMA", "quantity_of", "label_of", "for_quantities",
           "applies"]


@dataclass(frozen=True)
class Quantity:
    """What one graded quantity is and how its answers are graded.

    Attributes
    ----------
    name : str
        Its key in the evaluated dicts of a target and a tape (``"Phi_q"``).
    label : str
        The book's symbol (``"Φ_q"``).
    derived : bool
        Derived from Φ (Φ_q, ν, γ): graded at assembled configurations, against the student's own Φ with
        ``phi=``.
    per_coordinate : bool
        One entry per coordinate (Φ_q): a matrix, whose answer may come transposed, whose entries are graded one
        by one and shown in columns, and whose rows are matched up to any constant before the factor rule names
        a wrong one.
    right_hand_side : bool
        A right-hand side of the velocity or acceleration equations (ν, γ): each row is tied to the Φ row it
        comes from (its factor is that row's; rows in each other's places are exchanged, not moved); a link
        length or a forgotten 2 is a plausible factor; numbers without a configuration may be right as constants.
    q_derivative : bool
        Made by differentiating with respect to q (Φ_q, γ): the chain-rule slips and the book's printed tables
        apply.
    velocities : bool
        Depends on q̇ (γ): an answer is ``f(q, qd, t)``, and its parts (q̇-quadratic, q̇t, tt) are mistakes of
        their own.
    sign_code : str
        The catalogue's code for the whole row with the wrong sign.
    zero_code : str or None
        The catalogue's code for a row of zeros (ν of a driver forgotten).
    degrees : bool
        Numbers given in degrees are a slip to name (ν of an angle driver).
    turns : bool
        Its rows measure the placement itself (Φ): a row that measures an angle (``Target.turns``) is right turned
        by whole turns, in every form of answer — expressions, and numbers given at a configuration.
    hint_context : str or None
        The hint context of its mistakes (``"speed"``, ``"accel"``).
    value : callable
        ``value(mech, q, qd, t)``: the mechanism's own numbers at one state.
    expression : callable or None
        ``expression(Phi_row, D, t)``: the symbolic reference row from a Φ row (``D`` the total time
        derivative), for the right-hand sides.
    after_match : tuple of str
        Steps (:data:`kinbook.grading.aftermatch.STEPS`) run on the matching before the rows are diagnosed.
    without_own : tuple of str
        Steps run after the diagnosis when the student gave no Φ of their own.
    """

    name: str
    label: str
    derived: bool = True
    per_coordinate: bool = False
    right_hand_side: bool = False
    q_derivative: bool = False
    velocities: bool = False
    sign_code: str = "sign_flip"
    zero_code: str | None = None
    degrees: bool = False
    turns: bool = False
    hint_context: str | None = None
    value: Callable = field(default=None, repr=False)
    expression: Callable | None = field(default=None, repr=False)
    after_match: tuple = ()
    without_own: tuple = ()

    def __str__(self):
        return self.name


PHI = Quantity("Phi", "Φ", derived=False, turns=True, value=lambda mech, q, qd, t: mech.Phi(q, t))
PHI_Q = Quantity("Phi_q", "Φ_q", per_coordinate=True, q_derivative=True,
                 value=lambda mech, q, qd, t: mech.Phi_q(q, t),
                 after_match=("eg_rows", "jacobian_equivalents"), without_own=("factored_rows",))
NU = Quantity("nu", "ν", right_hand_side=True, sign_code="nu_sign", zero_code="nu_missing", degrees=True,
              hint_context="speed", value=lambda mech, q, qd, t: mech.nu(q, t),
              expression=lambda Phi, D, t: -Phi.diff(t), without_own=("exchanged_rows",))
GAMMA = Quantity("gamma", "γ", right_hand_side=True, q_derivative=True, velocities=True, sign_code="gamma_sign",
                 hint_context="accel", value=lambda mech, q, qd, t: mech.gamma(q, qd, t),
                 expression=lambda Phi, D, t: -D(D(Phi)), without_own=("exchanged_rows",))

QUANTITIES = {q.name: q for q in (PHI, PHI_Q, NU, GAMMA)}
"""The quantities by name."""

_BY_LABEL = {q.label: q for q in QUANTITIES.values()}


def quantity_of(quantity, default=None):
    """The :class:`Quantity` of a name (``"Phi_q"``), of a label (``"Φ_q"``) or the quantity itself; ``default``
    for anything else (a KeyError without one)."""
    if isinstance(quantity, Quantity):
        return quantity
    text = str(quantity)
    found = QUANTITIES.get(text) or _BY_LABEL.get(text, default)
    if found is None:
        raise KeyError(f"no quantity {text!r} (one of {', '.join(QUANTITIES)})")
    return found


def label_of(name):
    """The book's symbol of a quantity's name; any other name (a value's) as it is."""
    q = QUANTITIES.get(name) if isinstance(name, str) else None
    return q.label if q is not None else name


def for_quantities(*names):
    """Declare which quantities a catalogue entry (a misprinted table, a derivation slip) is made for::

        @for_quantities("Phi_q")
        def _book_table_13_2(target, c, s, ref, quantity): ...
    """
    for name in names:
        quantity_of(name)  # a typo fails at import

    def mark(fn):
        fn.quantities = tuple(names)
        return fn

    return mark


def applies(entry, quantity):
    """Whether a catalogue entry declared with :func:`for_quantities` is made for ``quantity``."""
    return quantity_of(quantity).name in getattr(entry, "quantities", ())
