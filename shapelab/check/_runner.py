"""The engine behind every self-check: run a student's function on cases, compare
with the library's answer, and report kindly.

A check never raises because of the student's code and never prints the solution:
it shows the first failing input, the expected value and the received value.
"""
from __future__ import annotations

import traceback
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

import numpy as np

__all__ = ["CheckResult", "run_check", "allclose"]


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

    def _repr_pretty_(self, p, cycle):  # IPython: show only the verdict line
        p.text(f"CheckResult({self.name!r}, passed={self.passed})")


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
    if isinstance(x, np.ndarray):
        with np.printoptions(precision=6, suppress=True, threshold=20):
            text = np.array2string(x)
    else:
        text = repr(x)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def run_check(
    name: str,
    student: Callable,
    cases: Iterable[tuple],
    reference: Callable,
    compare: Callable[[Any, Any], bool] | None = None,
    *,
    describe: Callable[[tuple], str] | None = None,
    quiet: bool = False,
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
    """
    compare = compare or allclose()
    if not callable(student):
        msg = f"✗ {name}: expected a function, got {type(student).__name__}. Pass the function itself, without calling it."
        if not quiet:
            print(msg)
        return CheckResult(name, False, 0, msg)
    n = 0
    for case in cases:
        n += 1
        shown = describe(case) if describe else ", ".join(_short(a) for a in case)
        expected = reference(*case)
        try:
            received = student(*[np.copy(a) if isinstance(a, np.ndarray) else a for a in case])
        except NotImplementedError:
            msg = f"… {name}: not implemented yet. Replace the placeholder with your code and run the cell again."
            if not quiet:
                print(msg)
            return CheckResult(name, False, n, msg)
        except Exception as exc:  # report, never crash
            where = traceback.extract_tb(exc.__traceback__)[-1]
            msg = (
                f"✗ {name}: your function raised {type(exc).__name__}: {exc}\n"
                f"  on input: {shown}\n  (line {where.lineno}: {where.line})"
            )
            if not quiet:
                print(msg)
            return CheckResult(name, False, n, msg)
        try:
            ok = bool(compare(expected, received))
        except Exception:
            ok = False
        if not ok:
            msg = (
                f"✗ {name}: not quite. First failing input (case {n}):\n  {shown}\n"
                f"  expected: {_short(expected)}\n  received: {_short(received)}"
            )
            if not quiet:
                print(msg)
            return CheckResult(name, False, n, msg)
    msg = f"✓ {name}: correct on all {n} cases."
    if not quiet:
        print(msg)
    return CheckResult(name, True, n, msg)
