"""What an exercise notebook declares: graded parts and per-student parameters.

An instructor writes, in a code cell of the source notebook::

    part("phi", points=4, answer="Phi", check="phi", target=mech.constraint("2"))

* ``answer`` names the variable the student assigns (``Phi = ...``);
* ``check`` names a kinbook checker: ``"phi"``, ``"jacobian"``, ``"nu"``, ``"gamma"`` (``target`` is a
  mechanism or one of its constraints) or ``"value"``, ``"rotation"``, ``"euler_parameters"`` (``expected``
  is the reference value, computed with kinbook in the notebook);
* ``tests=[(answer, code), …]``: question tests — a wrong answer and the mistake code it must be named by, or a
  right answer in another form with ``None`` (run by ``kinbook validate``, :mod:`kinbook.classroom.validate`);
* other keyword arguments go to the checker (``order="book"``, ``rtol=...``, ``angles=True`` …); ``phi="Phi"``
  on a Jacobian, ν or γ part grades it against the student's own Φ (error carried forward).

Run in a notebook, :func:`part` checks the answer at once and shows the :class:`~kinbook.grading.CheckResult`
(formative feedback). While grading, the declaration is read by the grader from the instructor's source — the
student's copy of it is only compared with the released one — and the check runs in the grader's process.

Per-student parameters are one assignment in a cell of their own::

    P = parameters(crank=(1.5, 2.5), omega=[5, 10, 15], defaults={"crank": 2.0, "omega": 10})

The instructor's notebook gets the defaults; ``kinbook variant`` and ``kinbook grade`` replace the call by
the student's literal values (see :mod:`kinbook.classroom.variant`).
"""

from __future__ import annotations

import contextlib
import math
import numbers
import os
import sys
from dataclasses import dataclass, field

from ..errors import GradingError
from ..grading import MISTAKES
from ..grading.item import CHECKERS, Item

__all__ = ["Part", "part", "parameters", "reference_calls", "check_parameters", "recording", "MAX_POINTS"]

#: The most points one part can carry.
MAX_POINTS = 1e6
#: Bounds of a parameters(...) declaration: parameters, values of one list, magnitude of a number.
MAX_PARAMETERS, MAX_CHOICES, MAX_PARAMETER = 100, 10_000, 1e15

@dataclass
class Part:
    """One graded part of an exercise: a :class:`~kinbook.grading.item.Item` with points and a place among the
    hidden checks. Its reference is computed by the instructor's code once per student (the source's cells run
    with the student's parameters), so the item's data are fixed here.

    Attributes
    ----------
    name : str
        Short identifier, the ``part`` column of grades.csv.
    points : float
    answer : str
        Name of the variable the student assigns.
    check : str
        Key of :data:`kinbook.grading.CHECKERS`.
    target : Mechanism or Constraint or None
    expected : object or None
    options : dict
        Keyword arguments of the checker.
    hidden : bool
        Declared between ``### BEGIN HIDDEN CHECKS`` and ``### END HIDDEN CHECKS``.
    tests : list of (answer, code or None)
        The author's question tests: an answer a student may give and the mistake code it must be named by, or
        None for a right answer in another form that must pass (``kinbook validate`` runs them).
    """

    name: str
    points: float
    answer: str
    check: str
    target: object = None
    expected: object = None
    options: dict = field(default_factory=dict)
    hidden: bool = False
    tests: list = field(default_factory=list)

    @property
    def checker(self):
        return CHECKERS[self.check]

    @property
    def reference(self):
        """What the checker grades against: the target, or the expected value."""
        return self.target if self.checker.against == "target" else self.expected

    @property
    def item(self):
        """The graded item this part is."""
        reference = self.reference
        return Item(self.answer, self.checker, lambda: reference, dict(self.options))

    def run(self, value, answers=None):
        """Grade ``value`` with the declared checker; ``answers`` resolves ``phi="Name"`` options."""
        return self.item.check(value, answers=answers)


_recorder: list | None = None


@contextlib.contextmanager
def recording():
    """Collect the parts declared while the block runs (the grader's reading of a source notebook);
    :func:`part` then only records."""
    global _recorder
    previous, _recorder = _recorder, []
    try:
        yield _recorder
    finally:
        _recorder = previous


def _validate(name, points, answer, check, target, expected):
    if not isinstance(name, str) or not name.isidentifier():
        raise GradingError(f"part name must be an identifier, got {name!r}"[:300])
    if (isinstance(points, bool) or not isinstance(points, numbers.Real) or not math.isfinite(points)
            or not 0 <= points <= MAX_POINTS):
        raise GradingError(f"part {name!r}: points must be a finite number from 0 to {MAX_POINTS:g}, got {points!r}"[:300])
    if not isinstance(answer, str) or not answer.isidentifier():
        raise GradingError(f"part {name!r}: answer must name a variable, got {answer!r}")
    if check not in CHECKERS:
        raise GradingError(f"part {name!r}: unknown check {check!r} (one of {', '.join(CHECKERS)})")
    if CHECKERS[check].against == "target" and target is None:
        raise GradingError(f"part {name!r}: check {check!r} needs target= (a mechanism or a constraint)")
    if CHECKERS[check].against == "expected" and expected is None:
        raise GradingError(f"part {name!r}: check {check!r} needs expected= (computed with kinbook)")


def _tests(name, tests):
    """The question tests of part ``name`` as a list of (answer, code or None), each code a catalogued one."""
    if tests is None:
        return []
    if not isinstance(tests, (list, tuple)) or len(tests) > 100:
        raise GradingError(f"part {name!r}: tests must be a list of (answer, mistake code or None), at most 100")
    out = []
    for k, test in enumerate(tests):
        if not isinstance(test, (list, tuple)) or len(test) != 2:
            raise GradingError(f"part {name!r}: test {k + 1} must be (answer, mistake code or None), got "
                               f"{str(test)[:80]!r}")
        answer, code = test
        if code is not None and code not in MISTAKES:
            raise GradingError(f"part {name!r}: test {k + 1} names {str(code)[:40]!r}, which is no mistake code "
                               f"(docs/mistakes.md lists them)")
        out.append((answer, code))
    return out


def part(name, points, *, answer, check, target=None, expected=None, tests=None, **options):
    """Declare a graded part (see the module docstring); in a notebook, check the answer now.

    ``tests=[(answer, code), …]`` are the author's question tests: each wrong ``answer`` must be refused and named
    ``code`` (a catalogue code), each one with ``None`` for its code must pass — ``kinbook validate`` runs them.

    Returns
    -------
    CheckResult or None
        In a notebook the verdict is displayed (every ``part`` of a cell shows its own) and None is
        returned; elsewhere the verdict is returned. None while grading or when ``answer`` is not assigned.
    """
    _validate(name, points, answer, check, target, expected)
    p = Part(name, float(points), answer, check, target, expected, dict(options), tests=_tests(name, tests))
    if _recorder is not None:
        _recorder.append(p)
        return None
    if os.environ.get("KINBOOK_SANDBOX_ROOT"):
        return None  # grading: the grader checks, from the source, in its own process
    ns = _user_namespace()
    if answer not in ns:
        print(f"part {name!r} ({points:g} points): assign `{answer} = ...` above, then run this cell again")
        return None
    answers = {k: ns[k] for k in [options.get("phi")] if isinstance(k, str) and k in ns}
    result = p.run(ns[answer], answers)
    shell = _shell()
    if shell is None:
        return result
    from IPython.display import display  # optional dependency: IPython (the grading extra)

    display(result)
    return None


def _shell():
    ipython = sys.modules.get("IPython")
    return ipython.get_ipython() if ipython is not None else None


def _user_namespace():
    shell = _shell()
    return shell.user_ns if shell is not None else vars(sys.modules["__main__"])


def parameters(defaults=None, **ranges):
    """Per-student parameters: ``(low, high)`` draws uniformly (rounded to 2 decimals, or to the number of
    decimals of ``low``), a list draws one item. In the instructor's notebook: returns ``defaults``.

    >>> parameters(crank=(1.5, 2.5), defaults={"crank": 2.0})
    {'crank': 2.0}
    """
    check_parameters(ranges, defaults)
    return dict(defaults or {})


def _parameter_value(value):
    """Whether ``value`` can be a parameter's value: a finite real number (not a bool) or a short text — what
    a variant writes into the student's notebook as a literal."""
    if isinstance(value, str):
        return len(value) <= 200
    return (isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)
            and abs(value) <= MAX_PARAMETER)


def check_parameters(ranges, defaults, where="parameters()"):
    """Check a ``parameters(...)`` declaration; raise :class:`~kinbook.errors.GradingError` naming ``where`` and
    the parameter.

    ``ranges``: name → ``(low, high)`` (finite numbers, low ≤ high) or a non-empty list of values (numbers or
    short texts); ``defaults``: name → value, one for every name of ``ranges``.
    """
    def bad(message):
        raise GradingError(f"{where}: {message}"[:500])

    if defaults is None:
        defaults = {}
    if not isinstance(defaults, dict):
        bad(f"defaults must be a dict of name: value, got {type(defaults).__name__}")
    if not isinstance(ranges, dict):
        bad(f"the ranges must be keyword arguments, got {type(ranges).__name__}")
    if len(ranges) + len(defaults) > MAX_PARAMETERS:
        bad(f"more than {MAX_PARAMETERS} parameters")
    for name, value in defaults.items():
        if not isinstance(name, str) or not name.isidentifier():
            bad(f"a parameter's name must be an identifier, got {name!r}")
        if not _parameter_value(value):
            bad(f"the default of {name} must be a finite number or a short text, got {value!r}")
    for name, spec in ranges.items():
        if isinstance(spec, tuple):
            if len(spec) != 2 or not all(_parameter_value(v) and not isinstance(v, str) for v in spec):
                bad(f"{name}=(low, high) needs two finite numbers, got {spec!r}")
            if spec[0] > spec[1]:
                bad(f"{name}=(low, high) has low > high: {spec!r}")
        elif isinstance(spec, list):
            if not 1 <= len(spec) <= MAX_CHOICES or not all(_parameter_value(v) for v in spec):
                bad(f"{name}=[…] needs 1 to {MAX_CHOICES} values, each a finite number or a short text, got "
                    f"{spec!r}")
        else:
            bad(f"{name}= must be (low, high) or a list of values, got {spec!r}")
        if name not in defaults:
            bad(f"no default for {name} (defaults={{'{name}': …}})")


def reference_calls(*names):
    """Declare what counts as kinbook's reference in this exercise (reported when an answer comes from it).

    ``"kinbook.spatial.A_from_euler"`` names a kinbook function (counted however it is reached: ``ks.A_from_euler``,
    an alias, ``functools.partial`` …), ``".solve_position"`` a method (counted on objects from kinbook only), a bare
    ``"E"`` both. Without a declaration, the grader counts the kinbook functions and methods whose results reach the
    hidden checks' ``expected=`` values; the Φ family (``symbolic()``, ``derivation()``, a constraint's ``phi()`` …)
    always counts. The grader reads the declaration from the source's code (literal strings); running it does
    nothing.

    >>> reference_calls("kinbook.spatial.A_from_euler", ".solve_position")
    """
    for name in names:
        if not isinstance(name, str) or not name.strip("."):
            raise GradingError(f"reference_calls() takes names as strings, got {name!r}")
    return None
