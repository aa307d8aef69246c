"""One model of a graded item, and the one table of checkers.

An :class:`Item` is what a student is asked for and how it is graded: the name of the variable the answer is
assigned to, the :class:`Checker` that grades it and its options, the reference it is graded against (computed
by kinbook from the item's data), and the data that vary with their ranges. Both faces of grading build on it:

* an exercise's graded part (:class:`kinbook.classroom.parts.Part`) is an item with points and a place among
  the hidden checks;
* a notebook's "Try it" (:class:`kinbook.book.tryits.TryIt`) is an item with a worked answer, a statement, the
  lookalikes printed nearby and the wrong forms it names.

:data:`CHECKERS` names every checker once, with what it grades against: a ``"target"`` (a mechanism or one of
its constraints: Φ, Φ_q, ν, γ) or an ``"expected"`` value computed with kinbook (a number, a rotation, Newton
iterates). :func:`seed_from` and :func:`draw` are the one seeded rule by which data vary — a student's own
parameters and a try-it's ``kb.another`` alike — so that the same seed gives the same data on every machine.
"""

from __future__ import annotations

import decimal
import hashlib
import importlib
import inspect
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ..errors import GradingError
from .quantities import GAMMA, NU, PHI, PHI_Q, Quantity
from .read import echoed

__all__ = ["Checker", "CHECKERS", "checker_for", "Item", "seed_from", "draw", "draw_with"]


_FUNCTIONS = {}
"""The built-in checkers' functions, loaded (and wrapped to echo the answer) when first used."""


@dataclass(frozen=True)
class Checker:
    """A checker by name: ``function(answer, reference, **options)`` → :class:`~kinbook.grading.CheckResult`.

    Attributes
    ----------
    name : str
        The name exercises use (``part(..., check="phi")``).
    module : str or None
        The grading module that defines ``check_<name>`` (loaded when the checker first runs: the table costs
        nothing to import); None for a checker given as ``implementation``.
    against : {"target", "expected"}
        What the reference is: a mechanism or constraint (``target=``), or a value computed with kinbook
        (``expected=``).
    quantity : Quantity or None
        The quantity it grades (:mod:`kinbook.grading.quantities`), for a checker against a target.
    implementation : callable or None
        The function itself (a checker declared outside kinbook.grading, docs/extending.md).
    echo : bool
        Its results carry the answer as it was read (:func:`kinbook.grading.read.echoed`), shown before the verdict.
    """

    name: str
    module: str | None
    against: str
    quantity: Quantity | None = None
    implementation: Callable | None = None
    echo: bool = True

    @property
    def function(self):
        """The checker function: ``implementation``, or ``check_<name>`` of its module, its results carrying the
        answer as read (``echo``)."""
        if self.implementation is not None:
            return self.implementation
        fn = _FUNCTIONS.get(self.name)
        if fn is None:
            fn = getattr(importlib.import_module(f"{__package__}.{self.module}"), self.function_name)
            if self.echo:
                fn = echoed(fn, self.quantity.name if self.quantity is not None else None)
            _FUNCTIONS[self.name] = fn
        return fn

    @property
    def function_name(self):
        return self.implementation.__name__ if self.implementation is not None else "check_" + self.name

    def __call__(self, answer, reference, **options):
        return self.function(answer, reference, **options)

    @property
    def numeric(self):
        """Grades numbers (it takes ``reveal=``: whether the feedback may show the reference value)."""
        return "reveal" in inspect.signature(self.function).parameters


CHECKERS = {c.name: c for c in (
    Checker("phi", "checks", "target", PHI),
    Checker("jacobian", "checks", "target", PHI_Q),
    Checker("nu", "checks", "target", NU),
    Checker("gamma", "checks", "target", GAMMA),
    Checker("value", "values", "expected"),
    Checker("rotation", "rotation_values", "expected"),
    Checker("euler_parameters", "rotation_values", "expected"),
    Checker("iterates", "newton", "expected", echo=False),
)}
"""Every checker, by the name exercises use for it."""


def checker_for(checker):
    """The :class:`Checker` of a name of :data:`CHECKERS`, of one of their functions, or ``checker`` itself."""
    if isinstance(checker, Checker):
        return checker
    if isinstance(checker, str):
        return CHECKERS[checker]
    found = next((c for c in CHECKERS.values() if c.function_name == getattr(checker, "__name__", None)
                  and checker in (c.function, getattr(c.function, "__wrapped__", None))), None)
    if found is None:
        raise GradingError(f"{getattr(checker, '__name__', checker)!r} is not a checker of kinbook.grading.CHECKERS")
    return found


@dataclass(frozen=True)
class Item:
    """One graded item: what is asked, against what, by which checker.

    Attributes
    ----------
    answer : str
        Name of the variable the student assigns (``Phi``, ``my_A``).
    checker : Checker
        One of :data:`CHECKERS`.
    target : callable
        ``target(**data)`` returns the checker's reference for the data (a mechanism or constraint, or an
        expected value), computed by the library.
    options : dict
        Keyword arguments of the checker. ``phi="Name"`` names another answer: the student's own Φ, resolved
        by :meth:`check` from ``answers`` (dropped when the student has not assigned it).
    data : dict
        The item's own data (the values its text gives).
    ranges : dict
        For each datum that varies, ``(low, high)`` or a list of values: what :func:`draw` draws from.
    """

    answer: str
    checker: Checker
    target: Callable[..., Any]
    options: dict = field(default_factory=dict)
    data: dict = field(default_factory=dict)
    ranges: dict = field(default_factory=dict)

    def data_for(self, data=None):
        """A copy of ``data``, or of the item's own data when None."""
        return dict(self.data) if data is None else dict(data)

    def reference(self, data=None):
        """The checker's reference for ``data`` (default: the item's own)."""
        return self.target(**self.data_for(data))

    def checker_options(self, answers=None):
        """The checker's options, ``phi="Name"`` replaced by the student's answer of that name (or dropped)."""
        options = dict(self.options)
        if isinstance(options.get("phi"), str):
            own = (answers or {}).get(options["phi"])
            if own is None:
                options.pop("phi")
            else:
                options["phi"] = own
        return options

    def check(self, value, data=None, answers=None):
        """Grade ``value`` for ``data`` (default: the item's own); ``answers`` resolves ``phi="Name"``."""
        return self.checker(value, self.reference(data), **self.checker_options(answers))

    def variant(self, seed):
        """The item's data with the varying ones drawn by :func:`draw` with ``seed``."""
        return draw(self.ranges, self.data, seed)


def seed_from(text):
    """A reproducible 64-bit seed from a text (a student id, an exercise): the first 8 bytes of its sha256."""
    return int.from_bytes(hashlib.sha256(str(text).encode("utf-8")).digest()[:8], "little")


def draw(ranges, defaults, seed):
    """One draw of parameter values from ``ranges`` (as in ``parameters(...)``) with a seeded generator: the
    rule per-student parameters use, shared with the notebooks' ``kb.another``."""
    return draw_with(ranges, defaults, np.random.default_rng(seed))


def draw_with(ranges, defaults, rng):
    """:func:`draw` from a generator: ``(low, high)`` uniformly, rounded to the decimals of ``low`` (at least 2,
    at most 15); a list, one of its items; the other names keep their ``defaults``."""
    out = dict(defaults)
    for name, spec in sorted(ranges.items()):
        if isinstance(spec, tuple) and len(spec) == 2:
            lo, hi = spec
            # the decimals of low (1e-05 has 5, 0.125 three), at least 2, at most 15
            exponent = decimal.Decimal(repr(float(lo))).as_tuple().exponent
            digits = min(15, max(2, -exponent if isinstance(exponent, int) else 0))
            out[name] = round(float(rng.uniform(lo, hi)), digits)
        elif isinstance(spec, list) and spec:
            out[name] = spec[int(rng.integers(len(spec)))]
        else:
            raise GradingError(f"parameters(): {name}= must be (low, high) or a list of values, got {spec!r}")
    return out
