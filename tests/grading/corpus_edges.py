"""Edges of the rounding and turning rules, written apart from kinbook's checker: constants in degrees rounded as a
calculator shows them, constants of angle rows turned by whole turns and rounded, ν and γ in degrees.

Every decimal is made here with mpmath (30 digits) and Python's decimal module (half-even), from the exercise's
own constants (the drivers' f(t) of the shipped mechanisms, a gear's φ⁰): the expectation follows from the
number alone —

* **degrees**: c·180/π correctly rounded to 3–6 significant digits, typed where c belongs, is the slip of degrees
  for radians (named ``degrees``), and so is the same value moved by one unit in its last digit when it stays
  within 2 % of c·180/π (a degrees value miscopied: ``degrees`` still; further off, ``wrong_value``); c itself
  rounded to 4 digits in radians is right;
* **turned constants**: the constant of a row that measures an angle turned by ±2π (5π/4 for −3π/4, 2π for 0),
  rounded to 3–5 digits, is right; moved by one unit in its last digit (within 2 %) it is ``not_rounded``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from decimal import ROUND_HALF_EVEN, Decimal
from functools import lru_cache

import mpmath
import sympy as sp

import kinbook


@dataclass
class Case:
    id: str
    check: str
    mech: str
    constraint: str
    answer: list
    passed: bool
    mistakes: list
    options: dict = field(default_factory=dict)


def _decimal(x):
    mpmath.mp.dps = 40
    if isinstance(x, sp.Basic):
        x = mpmath.mpf(str(sp.N(x, 35)))
    return Decimal(mpmath.nstr(mpmath.mpf(x), 30))


def rounded(value, digits):
    """``value`` (mpmath/sympy number) to ``digits`` significant digits, as text."""
    d = _decimal(value)
    exponent = d.adjusted() - digits + 1
    return str(d.quantize(Decimal(1).scaleb(exponent), rounding=ROUND_HALF_EVEN))


def moved(text):
    """The decimal ``text`` one unit up in its last digit (no rounding of the value it rounded)."""
    d = Decimal(text)
    return str(d + Decimal(1).scaleb(d.as_tuple().exponent))


def degrees(c):
    """c (sympy, radians) in degrees, to 30 digits (mpmath)."""
    mpmath.mp.dps = 40
    return mpmath.mpf(str(sp.N(c, 35))) * 180 / mpmath.pi


_PLANETARY_GEAR = ("ch13_planetary-phi0", 'q0 = [3, 0, 0]', 'q0 = [3, 0, 0.5]')


def mechanism(name):
    if name == _PLANETARY_GEAR[0]:
        from kinbook.files import loads

        text = kinbook.examples.path("ch13_planetary").read_text(encoding="utf-8")
        return loads(text.replace(_PLANETARY_GEAR[1], _PLANETARY_GEAR[2]), source="ch13_planetary-phi0.toml")
    return kinbook.examples.load(name)


def target(case):
    return mechanism(case.mech).constraint(case.constraint)


# the drivers φ_i − (a·g(t) + b) of the shipped mechanisms, one per distinct f
DRIVERS = [("ch13_example1", "driver 1"), ("ch13_example2", "driver 1"), ("quick_return", "driver 1"),
           ("six_bar", "driver 1"), ("steering", "driver 1"), ("planetary", "driver 2")]


def _parts(c):
    """f = a·g(t) + b of a driver, read with sympy."""
    t = c.mechanism.t
    f = sp.sympify(c.f)
    b = f.subs(t, 0)
    motion = sp.expand(f - b)
    a, g = motion.as_coeff_Mul()
    return sp.nsimplify(a), g, b


def _near_degrees(typed, value):
    return ["degrees"] if abs(mpmath.mpf(typed) - value) <= 0.02 * abs(value) else ["wrong_value"]


def degree_cases():
    out = []
    for name, joint in DRIVERS:
        m = mechanism(name)
        c = m.constraint(joint)
        angle = f"phi{c.bodies[0].number}"
        a, g, b = _parts(c)
        row = lambda rate, const, angle=angle, g=g: f"{angle} - {rate}*{g} - {const}"  # noqa: E731
        base = f"{name}-{joint.replace(' ', '')}"
        exact_b = str(b)
        for digits in (3, 4, 5):
            typed = rounded(degrees(a), digits)
            out.append(Case(f"deg-{base}-rate-{digits}", "phi", name, joint, [row(typed, exact_b)], False,
                            ["degrees"]))
        typed = moved(rounded(degrees(a), 4))
        out.append(Case(f"deg-{base}-rate-moved", "phi", name, joint, [row(typed, exact_b)], False,
                        _near_degrees(typed, degrees(a))))
        if b != 0:
            typed_b = rounded(degrees(b), 4)
            out.append(Case(f"deg-{base}-both-4", "phi", name, joint,
                            [row(rounded(degrees(a), 4), typed_b)], False, ["degrees"]))
            out.append(Case(f"rad-{base}-const-4", "phi", name, joint, [row(str(a), rounded(b, 4))], True, []))
        # ν = a·g'(t): the rate in degrees
        t = m.t
        nu = sp.diff(a * g, t)
        k, rest = nu.as_coeff_Mul()
        out.append(Case(f"deg-{base}-nu-4", "nu", name, joint, [f"{rounded(degrees(k), 4)}*{rest}"], False,
                        ["degrees"]))
        out.append(Case(f"rad-{base}-nu-4", "nu", name, joint, [f"{rounded(k, 4)}*{rest}"], True, []))
    # a gear's φ⁰ (0.5 rad, the planet's q0): in degrees, rounded
    g = next(c for c in mechanism(_PLANETARY_GEAR[0]).constraints if c.type_name == "gear")
    rows = [str(r) for r in mechanism(_PLANETARY_GEAR[0]).constraint_phi(g)]
    for digits in (3, 4, 6):
        typed = rounded(degrees(sp.Rational(1, 2)), digits)
        out.append(Case(f"deg-gear-phi0-{digits}", "phi", _PLANETARY_GEAR[0], g.name,
                        [rows[0].replace("0.5", typed)], False, ["degrees"]))
    typed = moved(rounded(degrees(sp.Rational(1, 2)), 4))
    out.append(Case("deg-gear-phi0-moved", "phi", _PLANETARY_GEAR[0], g.name, [rows[0].replace("0.5", typed)], False,
                    _near_degrees(typed, degrees(sp.Rational(1, 2)))))
    return out


def turned_cases():
    """The constant of an angle row turned by ±2π (exact with sympy), rounded: right; moved by a unit: not_rounded."""
    out = []
    for name, joint in DRIVERS[:4]:
        c = mechanism(name).constraint(joint)
        angle = f"phi{c.bodies[0].number}"
        a, g, b = _parts(c)
        for n in (1, -1):
            turned = -b + 2 * n * sp.pi  # the row φ − a·g − b + 2πn
            for digits in (3, 4, 5):
                typed = rounded(turned, digits)
                sign = "+" if turned > 0 else "-"
                out.append(Case(f"turn-{name}-{n:+d}-{digits}", "phi", name, joint,
                                [f"{angle} - {a}*{g} {sign} {typed.lstrip('-')}"], True, []))
            typed = moved(rounded(abs(turned), 4))
            sign = "+" if turned > 0 else "-"
            out.append(Case(f"turn-{name}-{n:+d}-moved", "phi", name, joint,
                            [f"{angle} - {a}*{g} {sign} {typed}"], False, ["not_rounded"]))
    first = "(-x3 + x4)*sin(phi3) - (-y3 + y4)*cos(phi3)"
    for digits in (3, 4, 5):
        out.append(Case(f"turn-slot-{digits}", "phi", "quick_return", "4",
                        [first, f"phi3 - phi4 - {rounded(2 * sp.pi, digits)}"], True, []))
    return out


@lru_cache(maxsize=None)
def cases():
    return degree_cases() + turned_cases()
