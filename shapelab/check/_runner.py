"""The engine behind every self-check: run a student's function on cases, compare
with the library's answer, and report kindly.

A check never raises because of the student's code and never prints the solution:
it shows the first failing input, the expected value and the received value.
"""

from __future__ import annotations

import signal
import threading
import traceback
from collections.abc import Callable, Iterable
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["CheckResult", "run_check", "allclose", "value"]


@dataclass(frozen=True)
class CheckResult:
    """Outcome of a self-check.

    Attributes
    ----------
    name : str
        What was checked.
    passed : bool
        True when every case agreed with the reference.
    n_cases : int
        How many cases ran (up to and including the first failure).
    message : str
        The friendly message that was printed.
    """

    name: str
    passed: bool
    n_cases: int
    message: str = field(repr=False)

    def __bool__(self) -> bool:
        return self.passed

    def _repr_pretty_(self, p, cycle):  # IPython, when displayed on purpose
        p.text(f"CheckResult({self.name!r}, passed={self.passed})")

    def _ipython_display_(self):
        """Nothing: the check printed its message already.  A check called as the last
        line of a cell would otherwise show its verdict twice."""


def allclose(atol: float = 1e-8, rtol: float = 1e-6) -> Callable[[Any, Any], bool]:
    """A comparison for numbers and arrays, tolerant to float rounding."""

    def compare(expected, received) -> bool:
        try:
            e = np.asarray(expected, dtype=float)
            r = np.asarray(received, dtype=float)
        except (TypeError, ValueError):
            return False
        return e.shape == r.shape and bool(np.allclose(e, r, atol=atol, rtol=rtol, equal_nan=False))

    return compare


def _short(x: Any, limit: int = 300) -> str:
    try:
        if isinstance(x, np.ndarray):
            with np.printoptions(precision=6, suppress=True, threshold=20):
                text = np.array2string(x)
        else:
            text = repr(x)
    except Exception as exc:  # a student's object whose repr fails must not crash the check
        text = f"<a {type(x).__name__} that cannot be shown: {type(exc).__name__}: {exc}>"
    return text if len(text) <= limit else text[: limit - 3] + "..."


class _TooSlow(BaseException):
    """Raised into the student's code when a case runs over its time limit.  A
    BaseException, so that the student's own ``except Exception`` cannot swallow it."""


@contextmanager
def _time_limit(seconds: float | None):
    """Interrupt the block after ``seconds`` (POSIX, main thread: where a kernel runs
    cells).  Elsewhere, or with ``seconds=None``, there is no limit."""
    usable = (
        seconds is not None and hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
    )
    if not usable:
        yield
        return

    def fire(signum, frame):
        raise _TooSlow

    previous = signal.signal(signal.SIGALRM, fire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _finish(name: str, passed: bool, n: int, msg: str, quiet: bool) -> CheckResult:
    if not quiet:
        print(msg)
    return CheckResult(name, passed, n, msg)


def run_check(
    name: str,
    student: Callable,
    cases: Iterable[tuple],
    reference: Callable,
    compare: Callable[[Any, Any], bool] | None = None,
    *,
    describe: Callable[[tuple], str] | None = None,
    quiet: bool = False,
    time_limit: float | None = 10.0,
) -> CheckResult:
    """Run ``student(*case)`` against ``reference(*case)`` for every case.

    Parameters
    ----------
    name : str
        Shown in the message, e.g. ``"quaternion product"``.
    student : callable
        The student's function.
    cases : iterable of tuple
        Positional arguments for each call, edge cases first.
    reference : callable
        The library's answer for the same arguments.
    compare : callable, optional
        ``compare(expected, received) -> bool``; defaults to :func:`allclose`.
    describe : callable, optional
        Formats a case for the message; defaults to ``repr`` of the arguments.
    quiet : bool
        Do not print; only return the result.
    time_limit : float or None
        Seconds one case may take before the check stops it and reports a loop that
        never ends (POSIX main thread only); None for no limit.

    Examples
    --------
    >>> cases = [(0.0,), (2.0,), (-3.0,)]
    >>> ok = run_check("square", lambda x: x * x, cases, lambda x: x**2)
    ✓ square: correct on all 3 cases.
    >>> bad = run_check("square", lambda x: 2 * x, cases, lambda x: x**2)
    ✗ square: not quite. First failing input (case 3):
      -3.0
      expected: 9.0
      received: -6.0
    >>> ok.passed, bad.passed, bad.n_cases
    (True, False, 3)
    """
    compare = compare or allclose()
    if not callable(student):
        msg = f"✗ {name}: expected a function, got {type(student).__name__}. Pass the function itself, without calling it."
        return _finish(name, False, 0, msg, quiet)
    n = 0
    for case in cases:
        n += 1
        shown = describe(case) if describe else ", ".join(_short(a) for a in case)
        expected = reference(*case)
        try:
            with _time_limit(time_limit):
                received = student(*[np.copy(a) if isinstance(a, np.ndarray) else a for a in case])
        except _TooSlow:
            msg = (
                f"✗ {name}: your function ran for more than {time_limit:g} s on input: {shown}\n"
                f"  Is there a loop that never ends?"
            )
            return _finish(name, False, n, msg, quiet)
        except NotImplementedError:
            msg = f"… {name}: not implemented yet. Replace the placeholder with your code and run the cell again."
            return _finish(name, False, n, msg, quiet)
        except Exception as exc:  # report, never crash
            where = traceback.extract_tb(exc.__traceback__)[-1]
            msg = (
                f"✗ {name}: your function raised {type(exc).__name__}: {exc}\n"
                f"  on input: {shown}\n  (line {where.lineno}: {where.line})"
            )
            return _finish(name, False, n, msg, quiet)
        try:
            ok = bool(compare(expected, received))
        except Exception:
            ok = False
        if not ok:
            msg = (
                f"✗ {name}: not quite. First failing input (case {n}):\n  {shown}\n"
                f"  expected: {_short(expected)}\n  received: {_short(received)}"
            )
            return _finish(name, False, n, msg, quiet)
    msg = f"✓ {name}: correct on all {n} cases."
    return _finish(name, True, n, msg, quiet)


def _hint(received, expected, rtol: float, atol: float) -> str | None:
    """None if ``received`` matches ``expected``, else a hint that does not give the
    expected value away."""
    if isinstance(expected, (bool, np.bool_, str)):
        if type(received) is not type(expected) and not (
            isinstance(expected, (bool, np.bool_)) and isinstance(received, (bool, np.bool_))
        ):
            return f"expected a {type(expected).__name__}, got a {type(received).__name__}"
        return None if received == expected else "that is not the answer"
    try:
        if isinstance(received, (str, bytes)):  # "0.25" would parse; it is not a number
            raise TypeError
        e = np.asarray(expected, dtype=float)
        r = np.asarray(received, dtype=float)
    except (TypeError, ValueError):
        return f"expected a number or an array of numbers, got a {type(received).__name__}"
    if e.shape != r.shape:
        return f"expected {'a single number' if e.ndim == 0 else f'shape {e.shape}'}, got shape {r.shape}"
    if not np.all(np.isfinite(r)) and np.all(np.isfinite(e)):
        return "yours contains NaN or inf"
    close = np.isclose(r, e, rtol=rtol, atol=atol)
    if np.all(close):
        return None
    if e.ndim == 0:
        return "yours is too large" if r > e else "yours is too small"
    first = tuple(int(i) for i in np.argwhere(~close)[0])
    return f"{int(np.count_nonzero(~close))} of {e.size} entries differ, the first at index {first[0] if len(first) == 1 else first}"


def value(
    name: str, received: Any, expected: Any, *, rtol: float = 1e-6, atol: float = 1e-9, quiet: bool = False
) -> CheckResult:
    """Check a computed answer against the library's value, without revealing it.

    For exercises whose answer is a value (a number, an array, a truth value) rather
    than a function.  On a mismatch it says how the answer is off ("too large",
    "3 of 10 entries differ", "expected shape (2,)"), never what it should be.

    Parameters
    ----------
    name : str
        What is checked, shown in the message.
    received
        The student's answer.
    expected
        The library's answer (numbers and arrays compare with ``rtol``/``atol``;
        truth values and strings exactly).
    rtol, atol : float
        Tolerances for numbers.
    quiet : bool
        Do not print; only return the result.

    Examples
    --------
    >>> ok = value("the answer", 0.5, 0.5)
    ✓ the answer: correct.
    >>> low = value("the answer", 0.4, 0.5)
    ✗ the answer: not quite: yours is too small.
    >>> shape = value("the answer", [1, 2], [1, 2, 3])
    ✗ the answer: not quite: expected shape (3,), got shape (2,).
    """
    hint = _hint(received, expected, rtol, atol)
    if hint is None:
        return _finish(name, True, 1, f"✓ {name}: correct.", quiet)
    return _finish(name, False, 1, f"✗ {name}: not quite: {hint}.", quiet)
