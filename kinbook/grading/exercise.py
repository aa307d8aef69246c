"""Exercise definitions: a mechanism file, what is asked, points, and per-student parameters.

An :class:`Exercise` is data: which mechanism (a shipped example or a mechanism file), which parts are asked
(Φ, Φ_q, ν, γ of the whole mechanism or of one constraint, or q, q̇, q̈ at an instant), in the book's order or
any order, and how many points each part is worth. Optional :class:`Parameter` entries make every student's
variant different: link lengths, point coordinates or driver speeds drawn from a seed (a student id), only
within ranges where the mechanism assembles — each draw is verified by solving a sweep, and redrawn if the
mechanism does not assemble. Reference answers always come from kinbook.

Examples
--------
>>> ex = Exercise(
...     id="four-bar-joint-3",
...     mechanism="ch13_example1",
...     parts=(Part("a", "Phi", constraint="3"), Part("b", "Phi_q", constraint="3", points=2)),
...     parameters=(Parameter("bodies.coupler.points.A.0", -3.2, -2.8),),
... )
>>> v = ex.variant("student-042")
>>> sorted(v.values) == ["bodies.coupler.points.A.0"]
True
>>> grade = ex.grade({"a": ["x1"]}, seed="student-042")
>>> grade.points, grade.total
(0.0, 3.0)
"""

from __future__ import annotations

import copy
import hashlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, KinbookError
from .checks import check_gamma, check_jacobian, check_nu, check_phi
from .result import CheckResult
from .values import check_value

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

__all__ = ["Exercise", "Part", "Parameter", "Variant", "Grade", "seed_from"]

QUANTITIES = ("Phi", "Phi_q", "nu", "gamma", "q", "qd", "qdd")
_CHECKS = {"Phi": check_phi, "Phi_q": check_jacobian, "nu": check_nu, "gamma": check_gamma}


@dataclass(frozen=True)
class Part:
    """One thing asked.

    Attributes
    ----------
    name : str
        How answers refer to it ("a", "b" …).
    quantity : {"Phi", "Phi_q", "nu", "gamma", "q", "qd", "qdd"}
        Symbolic (or numeric at ``t``) constraint quantities, or positions / velocities / accelerations
        at the instant ``t``.
    constraint : str, optional
        Name of the constraint asked about (``"3"``, ``"driver 1"``); None for the whole mechanism.
    order : {"any", "book"}
        For Φ: any order and scaling of the rows, or the book's order.
    points : float
    t : float, optional
        Instant of numeric parts (q, q̇, q̈, or numbers for Φ_q, ν, γ).
    """

    name: str
    quantity: str
    constraint: str | None = None
    order: str = "any"
    points: float = 1.0
    t: float | None = None

    def __post_init__(self):
        if self.quantity not in QUANTITIES:
            raise InputError(f"part '{self.name}': `quantity` must be one of {', '.join(QUANTITIES)}, "
                             f"got {self.quantity!r}")
        if self.order not in ("any", "book"):
            raise InputError(f"part '{self.name}': `order` must be 'any' or 'book', got {self.order!r}")


@dataclass(frozen=True)
class Parameter:
    """A per-student parameter: a number of the mechanism file drawn uniformly in [low, high].

    Attributes
    ----------
    path : str
        Dotted path into the mechanism file. List items are chosen by their ``name`` or by index:
        ``"bodies.crank.points.A.0"`` (ξ of point A of the crank), ``"constraints.4.length"``,
        ``"constraints.5.f"`` is not numeric and cannot be a parameter.
    low, high : float
    decimals : int
        Values are rounded, so that students read and type them exactly.
    """

    path: str
    low: float
    high: float
    decimals: int = 2


def seed_from(student):
    """A reproducible integer seed from a student id (any string or integer)."""
    if isinstance(student, (int, np.integer)):
        return int(student)
    return int.from_bytes(hashlib.sha256(str(student).encode("utf-8")).digest()[:8], "little")


@dataclass(frozen=True)
class Exercise:
    """An auto-graded exercise.

    Attributes
    ----------
    id : str
    mechanism : str
        A shipped example name (``"ch13_example1"``) or the path of a mechanism file (TOML).
    parts : tuple of Part
    parameters : tuple of Parameter
    sweep : (t0, t1, n)
        Instants at which every variant must assemble.
    max_tries : int
        Draws attempted before giving up on a seed.
    """

    id: str
    mechanism: str
    parts: tuple
    parameters: tuple = ()
    sweep: tuple = (0.0, 0.06, 13)
    max_tries: int = 50

    @classmethod
    def from_dict(cls, data):
        """An exercise from a plain dict (e.g. an exercise file read with tomllib)::

            id = "four-bar-3"
            mechanism = "ch13_example1"
            [[parts]]
            name = "a"
            quantity = "Phi"
            constraint = "3"
            [[parameters]]
            path = "bodies.coupler.points.A.0"
            low = -3.5
            high = -2.5
        """
        data = dict(data)
        try:
            parts = tuple(Part(**p) for p in data.pop("parts"))
            params = tuple(Parameter(**p) for p in data.pop("parameters", ()))
            if "sweep" in data:
                data["sweep"] = tuple(data["sweep"])
            return cls(parts=parts, parameters=params, **data)
        except (TypeError, KeyError) as exc:
            raise InputError(f"exercise definition: {exc}") from None

    @classmethod
    def from_toml(cls, text):
        """An exercise from the text of an exercise file (see :meth:`from_dict`)."""
        return cls.from_dict(tomllib.loads(text))

    def part(self, name):
        for p in self.parts:
            if p.name == name:
                return p
        raise InputError(f"exercise '{self.id}' has no part '{name}' (parts: "
                         f"{', '.join(p.name for p in self.parts)})")

    @property
    def total(self):
        return float(sum(p.points for p in self.parts))

    def data(self):
        """The mechanism file as a dict."""
        from .. import examples

        if Path(self.mechanism).suffix == ".toml" and Path(self.mechanism).exists():
            text = Path(self.mechanism).read_text(encoding="utf-8")
        else:
            text = examples.path(self.mechanism).read_text(encoding="utf-8")
        return tomllib.loads(text)

    def variant(self, seed=None):
        """The mechanism of one student: parameters drawn from ``seed`` and verified to assemble.

        Raises
        ------
        KinbookError
            No draw within ``max_tries`` assembles over the sweep (the ranges are wrong).
        """
        from ..io import build

        base = self.data()
        if not self.parameters or seed is None:
            return Variant(self, build(base, source=f"{self.mechanism}"), {}, seed)
        rng = np.random.default_rng(seed_from(seed))
        times = self.assembly_times()
        last = None
        for _ in range(self.max_tries):
            data = copy.deepcopy(base)
            values = {}
            for p in self.parameters:
                v = round(float(rng.uniform(p.low, p.high)), p.decimals)
                _set(data, p.path, v)
                values[p.path] = v
            try:
                mech = build(data, source=f"{self.mechanism} (variant)")
                mech.simulate(times)
            except KinbookError as exc:
                last = exc
                continue
            return Variant(self, mech, values, seed)
        raise KinbookError(f"exercise '{self.id}': no draw of the parameters assembles in {self.max_tries} "
                           f"tries (last failure: {last}); narrow the parameter ranges")

    def assembly_times(self):
        """The instants of ``sweep`` at which the file's own mechanism assembles: every variant must assemble
        at all of them (a four-bar that is not a crank-rocker only sweeps part of a turn)."""
        from ..io import build

        mech = build(self.data(), source=self.mechanism)
        res = mech.simulate(np.linspace(*self.sweep[:2], int(self.sweep[2])), on_failure="truncate")
        return np.asarray(res.t)

    def grade(self, answers, seed=None):
        """Grade a student's answers ({part name: answer}) on their variant."""
        return self.variant(seed).grade(answers)


@dataclass
class Variant:
    """One student's mechanism and the reference answers drawn from it."""

    exercise: Exercise
    mechanism: object
    values: dict
    seed: object = None

    def target(self, part):
        mech = self.mechanism
        return mech if part.constraint is None else mech.constraint(part.constraint)

    def reference(self, part):
        """kinbook's answer to a part: a sympy matrix (Φ, Φ_q, ν, γ) or an array (q, q̇, q̈ at t)."""
        part = self.exercise.part(part) if isinstance(part, str) else part
        mech = self.mechanism
        if part.quantity in ("q", "qd", "qdd"):
            res = mech.simulate([0.0, part.t] if part.t else [0.0])
            return {"q": res.q, "qd": res.qd, "qdd": res.qdd}[part.quantity][-1]
        if part.constraint is None:
            return getattr(mech.symbolic(), part.quantity)
        from ..symbolic import derive

        d = derive(mech.constraint_phi(part.constraint), mech.q, mech.qd, mech.t)
        return getattr(d, part.quantity)

    def check(self, part, answer, phi=None):
        """Check one answer; ``phi`` is the student's own Φ for error carried forward."""
        part = self.exercise.part(part) if isinstance(part, str) else part
        if part.quantity in ("q", "qd", "qdd"):
            angles = [k for k, c in enumerate(self.mechanism.coordinate_names()) if c.startswith("phi")]
            return check_value(answer, self.reference(part), name=part.quantity,
                               periodic=angles if part.quantity == "q" else ())
        options = {}
        if part.t is not None:
            mech = self.mechanism
            res = mech.simulate([0.0, part.t] if part.t else [0.0])
            options["at"] = {"q": res.q[-1], "qd": res.qd[-1], "t": part.t}
        if part.quantity == "Phi":
            return check_phi(answer, self.target(part), order=part.order, **options)
        if phi is not None:
            options["phi"] = phi
        return _CHECKS[part.quantity](answer, self.target(part), **options)

    def grade(self, answers):
        """Grade every part; a Φ answer is carried forward into the Φ_q, ν and γ parts of the same target."""
        results = {}
        phis = {p.constraint: answers[p.name] for p in self.exercise.parts
                if p.quantity == "Phi" and p.name in answers}
        for p in self.exercise.parts:
            if p.name not in answers:
                results[p.name] = CheckResult(False, 0.0, [f"part '{p.name}': no answer"], [], (), p.quantity)
                continue
            phi = phis.get(p.constraint) if p.quantity in ("Phi_q", "nu", "gamma") else None
            results[p.name] = self.check(p, answers[p.name], phi=phi)
        return Grade(self.exercise, results)


@dataclass(frozen=True)
class Grade:
    """Results of every part and the points they earn."""

    exercise: Exercise
    results: dict = field(default_factory=dict)

    @property
    def points(self):
        return float(sum(self.results[p.name].score * p.points for p in self.exercise.parts
                         if p.name in self.results))

    @property
    def total(self):
        return self.exercise.total

    def __repr__(self):
        lines = [f"Grade({self.exercise.id}: {self.points:g} / {self.total:g})"]
        for p in self.exercise.parts:
            r = self.results.get(p.name)
            if r is not None:
                lines.append(f"  {p.name} ({p.quantity}, {p.points:g} pt): score {r.score:.2f}"
                             + (f" {r.mistakes}" if r.mistakes else ""))
        return "\n".join(lines)

    def _repr_html_(self):
        return "".join(f"<h4>{p.name}</h4>" + self.results[p.name]._repr_html_()
                       for p in self.exercise.parts if p.name in self.results)


def _set(data, path, value):
    parts = path.split(".")
    node = data
    for k, key in enumerate(parts):
        last = k == len(parts) - 1
        if isinstance(node, list):
            found = None
            for item in node:
                if isinstance(item, dict) and item.get("name") == key:
                    found = item
            if found is None:
                try:
                    idx = int(key)
                except ValueError:
                    raise InputError(f"parameter path '{path}': no item named '{key}'") from None
                if last:
                    node[idx] = value
                    return
                found = node[idx]
            node = found
        elif isinstance(node, dict):
            if key not in node:
                raise InputError(f"parameter path '{path}': no key '{key}'")
            if last:
                node[key] = value
                return
            node = node[key]
        else:
            raise InputError(f"parameter path '{path}': '{key}' is not inside a table or a list")
