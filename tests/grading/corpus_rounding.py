"""Rounded constants (kinbook.grading.rounding): the exercise's exact constants typed as decimals, in Φ, ν and γ.

Each constant c enters a driver φ1 = c·sin(10t) + c (so that Φ holds c, ν holds 10c and γ holds 100c). The
decimals a student types are made here, apart from kinbook: c is evaluated to 30 digits by mpmath and rounded
with Python's decimal module (half-even) to d significant digits — a correct rounding, which must pass — or
moved by one unit in its last digit, truncated where truncating is not rounding, or cut to 2 digits: none of
those is a rounding, so each must fail (and is named ``not_rounded`` when it is within 2 % of the constant,
the distance kinbook offers that name at, or a rounding to too few digits; further off it is a wrong value; an
integer under 100 is read as an integer).
Digits 3 to 5: a sixth digit one unit off is within the checkers' tolerance (1e-6), and passes.
"""

from __future__ import annotations

from dataclasses import dataclass
from decimal import ROUND_DOWN, ROUND_HALF_EVEN, Decimal
from functools import lru_cache

import mpmath

CONSTANTS = {
    "3*pi/4": lambda: 3 * mpmath.pi / 4,
    "sqrt(3)/2": lambda: mpmath.sqrt(3) / 2,
    "sqrt(5)/2": lambda: mpmath.sqrt(5) / 2,
    "sqrt(2)": lambda: mpmath.sqrt(2),
    "pi/6": lambda: mpmath.pi / 6,
    "2*pi/3": lambda: 2 * mpmath.pi / 3,
}

# the three places c appears: Φ = φ1 − c sin 10t − c, ν = 10c cos 10t, γ = −100c sin 10t
FACTOR = {"phi": 1, "nu": 10, "gamma": 100}


def _digits30(expr):
    mpmath.mp.dps = 40
    return Decimal(mpmath.nstr(CONSTANTS[expr](), 30))


def rounded(value, digits, mode=ROUND_HALF_EVEN):
    """``value`` (a Decimal) to ``digits`` significant digits."""
    exponent = value.adjusted() - digits + 1
    return value.quantize(Decimal(1).scaleb(exponent), rounding=mode)


@dataclass
class Case:
    id: str
    check: str
    constant: str
    typed: str
    passed: bool
    mistakes: list

    def answer(self):
        if self.check == "phi":
            return [f"phi1 - {self.typed}*sin(10*t) - {_base(self.constant)}"]
        if self.check == "nu":
            return [f"{self.typed}*cos(10*t)"]
        return [f"-{self.typed}*sin(10*t)"]


def _base(constant):
    return constant  # the other term of Φ typed exactly: only one decimal per answer is judged


def _expect_wrong(typed, exact):
    near = abs(Decimal(typed) - exact) <= Decimal("0.02") * exact  # the distance docs/mistakes.md states
    return ["not_rounded"] if near else ["wrong_value"]


def _integer(typed):
    return "." not in str(typed)


def _ambiguous(typed):
    """An integer written with trailing zeros (140): how many of its digits are meant is not known — left out."""
    return _integer(typed) and str(typed).endswith("0")


@lru_cache(maxsize=None)
def cases():
    out = []
    for constant in CONSTANTS:
        for check, k in FACTOR.items():
            exact = _digits30(constant) * k
            for d in (3, 4, 5):
                r = rounded(exact, d)
                out.append(Case(f"round-{check}-{constant}-{d}", check, constant, str(r), True, []))
                step = Decimal(1).scaleb(r.adjusted() - d + 1)
                for sign, name in ((1, "up"), (-1, "down")):
                    off = r + sign * step
                    if _ambiguous(off):
                        continue
                    out.append(Case(f"round-{check}-{constant}-{d}-{name}", check, constant, str(off), False,
                                    _expect_wrong(off, exact)))
                cut = rounded(exact, d, ROUND_DOWN)
                if cut != r and not _ambiguous(cut):
                    out.append(Case(f"round-{check}-{constant}-{d}-truncated", check, constant, str(cut), False,
                                    _expect_wrong(cut, exact)))
            two = rounded(exact, 2)
            # an integer under 100 (24 for 10·3π/4) is read as the integer it is: a wrong value, not a rounding
            small = _integer(two) and abs(two) < 100
            out.append(Case(f"round-{check}-{constant}-2-digits", check, constant, str(two), False,
                            ["wrong_value"] if small else ["not_rounded"]))
    return out


@lru_cache(maxsize=None)
def mechanism(constant):
    from kinbook import planar as P

    m = P.Mechanism(f"driver {constant}")
    m.add_body("crank", q0=(0, 0, 0.5))
    m.add(P.Driver("crank", "phi", f"({constant})*sin(10*t) + {constant}", name="d"))
    return m


def target(case):
    return mechanism(case.constant).constraint("d")
