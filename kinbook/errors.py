"""Exceptions raised by kinbook.

Every error kinbook raises on purpose is a :class:`KinbookError`. Messages name the body, point, constraint
or equation row concerned, so that a student reading a traceback in a notebook knows where to look.

The hierarchy::

    KinbookError
    ├── ModelError                 a mechanism that cannot be built as described
    │   ├── UnknownBodyError
    │   ├── UnknownPointError
    │   └── MechanismFileError     a mechanism file (TOML) that cannot be read; names the key
    ├── InputError                 wrong shapes, NaN/inf, values out of their domain
    │   ├── ExpressionError        text that is not an allowed expression (kinbook.core.reader)
    │   └── DriverValueError       a driver's f(t), f'(t) or f''(t) is not finite and real where needed
    ├── DriverCountError           more or fewer drivers than degrees of freedom
    └── AnalysisError              the numbers went wrong during an analysis
        ├── ConvergenceError       Newton-Raphson did not converge
        ├── SingularJacobianError  Φ_q is rank deficient at the configuration
        │   ├── RedundantConstraintsError   ...because geometric constraints repeat each other
        │   └── DeadPointError              ...because a driver cannot move the mechanism any further
        └── AssemblyError          a sweep reached a time at which the mechanism does not assemble
    GradingError                   an exercise notebook or a submission batch that cannot be processed
    │   ├── RosterError            a roster file that cannot be read whole; names the file and the line
    │   ├── GradebookError         a gradebook that cannot be used; names the file and what to do
    │   │   ├── NotAGradebookError       a missing grading directory, or a file that is no gradebook
    │   │   ├── GradebookReadOnlyError   a gradebook (or its directory) kinbook may not write
    │   │   ├── GradebookLockedError     another kinbook run holds it longer than the bounded wait
    │   │   ├── GradebookFullError       the disk is full (also a DiskFullError)
    │   │   └── NewerGradebookError      written by a newer kinbook
    │   └── UnknownNameError       an exercise, student or part the gradebook does not know (closest name given)
    └── WriteError                 a file kinbook was asked to write cannot be written whole; names it
        ├── OverwriteError         ...because it is one of the command's own inputs (both paths named)
        └── DiskFullError          ...because the disk (or the quota) is full; the old file is kept

Warnings::

    KinbookWarning (UserWarning)
    └── SingularityWarning         a result is not unique, e.g. z-x-z Euler angles at sin θ = 0
"""

from __future__ import annotations

__all__ = [
    "KinbookError",
    "ModelError",
    "UnknownBodyError",
    "UnknownPointError",
    "MechanismFileError",
    "InputError",
    "ExpressionError",
    "DriverValueError",
    "DriverCountError",
    "AnalysisError",
    "ConvergenceError",
    "SingularJacobianError",
    "RedundantConstraintsError",
    "DeadPointError",
    "AssemblyError",
    "GradingError",
    "RosterError",
    "GradebookError",
    "NotAGradebookError",
    "GradebookReadOnlyError",
    "GradebookLockedError",
    "GradebookFullError",
    "NewerGradebookError",
    "UnknownNameError",
    "WriteError",
    "OverwriteError",
    "DiskFullError",
    "KinbookWarning",
    "SingularityWarning",
]


class KinbookError(Exception):
    """Base class of every error kinbook raises on purpose.

    Its message may be a marked one (a :class:`kinbook.i18n.Message`, a floor up: anything with
    ``render(lang)``): ``str(err)`` writes it in the language of the moment (:func:`kinbook.set_language`),
    ``err.args[0]`` is its English and ``err.message`` the marked message."""

    def __init__(self, *args):
        self.message = args[0] if args else ""
        if _marked(self.message):
            args = (self.message.render("en"), *args[1:])
        super().__init__(*args)

    def __str__(self):
        message = getattr(self, "message", None)
        return message.render() if _marked(message) else super().__str__()


def _marked(message):
    """A marked message (kinbook.i18n.Message, a floor up), written when shown."""
    return not isinstance(message, str) and hasattr(message, "render")


class ModelError(KinbookError, ValueError):
    """A mechanism (bodies, points, constraints) that cannot be built as described."""


class UnknownBodyError(ModelError, KeyError):
    """A constraint or a query names a body the mechanism does not have."""

    def __str__(self):  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class UnknownPointError(ModelError, KeyError):
    """A constraint or a query names a point its body does not have."""

    def __str__(self):
        return str(self.args[0]) if self.args else ""


class MechanismFileError(ModelError):
    """A mechanism file that cannot be read. The message names the file and the offending key."""


class InputError(KinbookError, ValueError):
    """An argument of the wrong shape, with NaN or inf, or outside its domain."""


class ExpressionError(InputError):
    """Text (from a mechanism file, a student or the command line) that is not an allowed expression, or
    exceeds a bound of :class:`kinbook.core.bounds.Limits`.

    Attributes
    ----------
    where : str or kinbook.i18n.Message
        Where the text came from ("file 'x.toml', key constraints[3].f").
    text : str or None
        The text read (None when the value was not text).
    reason : str
        What is wrong, without the location, in English (for code; the message says it in the reader's language).
    column : int or None
        1-based column of the offending part of ``text``.
    message : str or kinbook.i18n.Message
        The whole message. The reader's are marked messages (:class:`kinbook.i18n.Message`): ``str(err)`` writes
        it in the language of the moment (:func:`kinbook.set_language`), ``err.args[0]`` is its English.
    """

    def __init__(self, message, *, where=None, text=None, reason=None, column=None):
        super().__init__(message)
        if _marked(reason):
            reason = reason.render("en")
        self.where, self.text, self.reason, self.column = where, text, reason, column


class DriverValueError(InputError):
    """A driver's prescribed function f(t), or its first or second derivative, is not a finite real number
    at an instant where an analysis needs it (``sqrt(t - 5)`` at t = 0, ``Abs(t - 1)``'s kink at t = 1).

    Attributes
    ----------
    t : float
        The first such instant.
    """

    def __init__(self, message, *, t=None):
        super().__init__(message)
        self.t = t


class DriverCountError(KinbookError):
    """The number of driving constraints differs from the number of degrees of freedom."""


class AnalysisError(KinbookError):
    """An analysis (position, velocity, acceleration, sweep) could not produce a trustworthy answer."""


class ConvergenceError(AnalysisError):
    """Newton-Raphson stopped without reaching the tolerance.

    Attributes
    ----------
    iterations : int
    residual : float
        Infinity norm of Φ at the last iterate.
    q : ndarray
        The last iterate.
    """

    def __init__(self, message, *, iterations=None, residual=None, q=None):
        super().__init__(message)
        self.iterations = iterations
        self.residual = residual
        self.q = q


class SingularJacobianError(AnalysisError):
    """Φ_q is singular or rank deficient at the configuration.

    Attributes
    ----------
    rows : list of int
        1-based rows of Φ that take part in the dependency.
    constraints : list of str
        Names of the constraints owning those rows.
    rank, size : int
        Numerical rank of Φ_q and its number of rows.
    """

    def __init__(self, message, *, rows=(), constraints=(), rank=None, size=None, q=None, t=None):
        super().__init__(message)
        self.rows = list(rows)
        self.constraints = list(constraints)
        self.rank = rank
        self.size = size
        self.q = q
        self.t = t


class RedundantConstraintsError(SingularJacobianError):
    """The geometric constraints are linearly dependent: some of them repeat what others impose."""


class DeadPointError(SingularJacobianError):
    """The geometric constraints are independent but a driver cannot move the mechanism further."""


class AssemblyError(AnalysisError):
    """A sweep reached an instant at which the mechanism cannot be assembled.

    Attributes
    ----------
    t : float
        First instant that failed.
    drivers : dict
        Value of each driver's prescribed function at ``t``.
    partial : SimulationResult or None
        The instants solved before the failure.
    """

    def __init__(self, message, *, t=None, drivers=None, partial=None, cause=None):
        super().__init__(message)
        self.t = t
        self.drivers = dict(drivers or {})
        self.partial = partial
        self.cause = cause


class GradingError(KinbookError):
    """An exercise notebook (source, release, variant) or a grading run that cannot be processed as asked.
    A bad *submission* is never an exception: it gets a status in the gradebook."""


class RosterError(GradingError):
    """A roster that cannot be read whole: its encoding, a malformed line (named by its number), a row without a
    usable id. No student is ever dropped silently."""


class GradebookError(GradingError):
    """A gradebook (``graded/gradebook.sqlite``) that cannot be used as asked. The message names the file and what
    to do; nothing recorded in it is lost."""


class NotAGradebookError(GradebookError):
    """The grading directory does not exist (a mistyped ``-g``), or its ``gradebook.sqlite`` is not a kinbook
    gradebook (another file, a damaged one)."""


class GradebookReadOnlyError(GradebookError):
    """The gradebook or its directory cannot be written by this user (permissions, a read-only mount)."""


class GradebookLockedError(GradebookError):
    """Another kinbook run holds the gradebook for longer than the bounded wait."""


class NewerGradebookError(GradebookError):
    """A gradebook written by a newer kinbook, whose tables this one does not know."""


class UnknownNameError(GradingError):
    """An exercise, student or part a command names that the gradebook does not know; the message gives the
    closest known name.

    Attributes
    ----------
    name : str
    closest : str or None
    """

    def __init__(self, message, *, name=None, closest=None):
        super().__init__(message)
        self.name, self.closest = name, closest


class WriteError(KinbookError):
    """A file kinbook was asked to write cannot be written whole. Files are written through a temporary file and
    a rename (:func:`kinbook.core.atomic.atomic_write`): the old file, or none, is left — never half of one.

    Attributes
    ----------
    path : str
        The file that was to be written.
    """

    def __init__(self, message, *, path=None):
        super().__init__(message)
        self.path = path


class OverwriteError(WriteError):
    """The file to write is one of the command's own inputs (the gradebook, the roster, the source, a collected
    file): refused before anything is written.

    Attributes
    ----------
    input : str
        The input it would have replaced.
    """

    def __init__(self, message, *, path=None, input=None):
        super().__init__(message, path=path)
        self.input = input


class DiskFullError(WriteError):
    """No space is left on the device (or the quota is used up) while writing; the old file is kept."""


class GradebookFullError(GradebookError, DiskFullError):
    """The gradebook cannot grow: the disk or the quota is full. Every result recorded before is kept."""


class KinbookWarning(UserWarning):
    """Base class of the warnings kinbook issues."""


class SingularityWarning(KinbookWarning):
    """A result at a singular configuration is one documented choice among many (e.g. Euler angles at
    sin θ = 0, where only ψ ± φ is determined)."""
