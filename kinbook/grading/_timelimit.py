"""Time limits for sympy work on students' answers.

sympy can take unbounded time on a pathological expression (simplify, expand, even lambdify of a deeply
nested tree). A thread with a timeout cannot be killed, so checkers use a SIGALRM interval timer instead: the
handler raises :class:`TimeLimitExceeded` (a ``BaseException``, so that sympy's internal ``except Exception``
clauses cannot swallow it) in the main thread, which abandons the sympy call.

The timer is only armed where it is safe: in the main thread, on platforms with ``signal.setitimer`` (not
Windows), and when no other interval timer is running (pytest-timeout, for example, may use one). Elsewhere
the limit is not enforced and checkers rely on the size caps alone (``MAX_NODES`` in
:mod:`kinbook.grading.answers`) and skip optional symbolic confirmations.

In a browser (Pyodide, ``sys.platform == "emscripten"``) there are no signals: :mod:`signal` is imported only
when a timer can be armed, so that importing :mod:`kinbook.grading` never touches it.
"""

from __future__ import annotations

import sys
import threading

__all__ = ["TimeLimitExceeded", "can_limit", "run_limited"]


class TimeLimitExceeded(BaseException):
    """Raised inside a sympy call when its time budget is exhausted."""


def can_limit():
    """True when :func:`run_limited` can actually interrupt work in this thread."""
    if sys.platform == "emscripten" or threading.current_thread() is not threading.main_thread():
        return False
    import signal

    if not hasattr(signal, "setitimer"):
        return False
    return signal.getitimer(signal.ITIMER_REAL)[0] == 0.0


def _raise(signum, frame):
    raise TimeLimitExceeded()


def run_limited(fn, seconds, on_timeout=None, required=False):
    """Run ``fn()`` with a time budget.

    Parameters
    ----------
    fn : callable
        Work to do (typically a sympy call).
    seconds : float
        Budget.
    on_timeout : callable or None
        Called (with no arguments) to build the return value when the budget is exhausted.
    required : bool
        When the limit cannot be enforced in this thread: run ``fn`` anyway (True) or return
        ``on_timeout()`` without trying (False: for optional work such as symbolic confirmation).
    """
    if not can_limit():
        if required:
            return fn()
        return on_timeout() if on_timeout else None
    import signal

    old = signal.signal(signal.SIGALRM, _raise)
    try:
        try:
            signal.setitimer(signal.ITIMER_REAL, seconds)
            return fn()
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0.0)
    except TimeLimitExceeded:
        return on_timeout() if on_timeout else None
    finally:
        signal.signal(signal.SIGALRM, old)
