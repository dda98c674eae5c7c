"""The self-check engine, shapelab/check/_runner.py (issue 6, "Self-checks").

Its promises to a student: it says "correct" for a right function; for a wrong one it
shows the first failing input with the expected and received values; it reports, and
never raises, the student's exception; it treats ``NotImplementedError`` (the student
edition's placeholder) as "not implemented yet"; it explains a non-callable; and it
never prints the reference solution.
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from shapelab.check import CheckResult, allclose, run_check


def reference_norm(v):
    # a distinctive line that must never reach the student: SECRET-REFERENCE-LINE
    squared_sum_of_components = float(np.sum(np.asarray(v, dtype=float) ** 2))
    return np.sqrt(squared_sum_of_components)


CASES = [
    (np.array([0.0, 5.0]),),
    (np.array([0.0, 0.0]),),
    (np.array([1.0, -1.0]),),  # the 1-norm (a classic mistake) fails here first
    (np.array([-6.0, 8.0]),),
]


def _run(student, capsys, cases=CASES, reference=reference_norm, **kw):
    result = run_check("vector norm", student, cases, reference, **kw)
    printed = capsys.readouterr()
    return result, printed.out, printed.err


def test_correct_function_says_correct(capsys):
    result, out, err = _run(lambda v: np.linalg.norm(v), capsys)
    assert isinstance(result, CheckResult)
    assert result.passed and bool(result)
    assert result.n_cases == len(CASES)
    assert "✓" in out and "correct" in out and "✗" not in out
    assert out.strip() == result.message
    assert err == ""


def test_wrong_function_shows_first_failing_input_expected_and_received(capsys):
    def one_norm(v):
        return float(np.sum(np.abs(v)))  # right on cases 1-2, wrong on case 3

    result, out, _ = _run(one_norm, capsys)
    assert not result.passed
    assert result.n_cases == 3, "stops at the first failing case"
    assert "✗" in out and "case 3" in out
    assert "[ 1. -1.]" in out, "shows the failing input"
    assert f"expected: {np.sqrt(2.0)!r}" in out
    assert "received: 2.0" in out
    assert "[-6.  8.]" not in out, "only the first failure is shown"


def test_student_exception_is_reported_not_raised(capsys):
    def crashes_on_zero(v):
        return float(np.linalg.norm(v) / np.linalg.norm(v) * np.linalg.norm(v)) if v.any() else 1 // 0

    result, out, _ = _run(crashes_on_zero, capsys)
    assert not result.passed
    assert result.n_cases == 2
    assert "ZeroDivisionError" in out and "[0. 0.]" in out
    assert "1 // 0" in out, "points at the student's own line"


@pytest.mark.parametrize("exc", [KeyError("x"), ValueError("bad"), IndexError(), RecursionError()])
def test_any_exception_kind_is_reported(exc, capsys):
    def raiser(v):
        raise exc

    result, out, _ = _run(raiser, capsys)
    assert not result.passed and type(exc).__name__ in out


def test_not_implemented_is_kind(capsys):
    def placeholder(v):
        raise NotImplementedError("your code here")

    result, out, _ = _run(placeholder, capsys)
    assert not result.passed
    assert "not implemented yet" in out
    assert "✗" not in out and "Traceback" not in out


@pytest.mark.parametrize("not_a_function", [5.0, np.array([1.0]), None, "norm"])
def test_non_callable_is_explained(not_a_function, capsys):
    result, out, _ = _run(not_a_function, capsys)
    assert not result.passed and result.n_cases == 0
    assert "expected a function" in out and type(not_a_function).__name__ in out


def test_wrong_type_or_shape_of_answer_is_a_failure_not_a_crash(capsys):
    for answer in ("five", [1.0, 2.0], None, {"a": 1}, np.array([[5.0]])):
        result, out, _ = _run(lambda v, a=answer: a, capsys)
        assert not result.passed and "received:" in out


def test_compare_that_raises_counts_as_failure(capsys):
    def bad_compare(expected, received):
        raise RuntimeError("comparison exploded")

    result, out, _ = _run(lambda v: np.linalg.norm(v), capsys, compare=bad_compare)
    assert not result.passed and result.n_cases == 1 and "expected:" in out


def test_student_cannot_corrupt_the_cases(capsys):
    cases = [(np.array([3.0, 1.0, 2.0]),), (np.array([5.0, 4.0]),)]
    before = [c[0].copy() for c in cases]

    def sorts_in_place(v):
        v.sort()  # mutates its argument, still returns the right value
        v[0] = v[0]
        return np.linalg.norm(v)

    result, _, _ = _run(sorts_in_place, capsys, cases=cases)
    assert result.passed
    for (after,), orig in zip(cases, before):
        np.testing.assert_array_equal(after, orig)


def test_reference_source_is_never_printed(capsys):
    source_lines = [line.strip() for line in inspect.getsource(reference_norm).splitlines()[1:] if line.strip()]

    def calls_reference_wrongly(v):
        return reference_norm(v) + 1.0

    def raises(v):
        raise ValueError("nope")

    def placeholder(v):
        raise NotImplementedError

    printed = ""
    for student in (np.linalg.norm, calls_reference_wrongly, raises, placeholder, 3.0):
        result, out, err = _run(student, capsys)
        printed += out + err + result.message + repr(result)
    for line in source_lines:
        assert line not in printed, f"the reference's source leaked: {line!r}"
    assert "SECRET-REFERENCE-LINE" not in printed


@pytest.mark.xfail(
    strict=True,
    reason="_runner shows the LAST traceback line, which is inside the reference when the "
    "student's function calls it and it raises; it should show the student's own line",
)
def test_exception_inside_a_library_call_points_at_the_students_line(capsys):
    def calls_reference_with_a_string(v):
        return reference_norm("not a vector")  # raises inside reference_norm

    result, out, _ = _run(calls_reference_with_a_string, capsys)
    assert not result.passed and "ValueError" in out
    assert "squared_sum_of_components" not in out


def test_long_inputs_are_shortened(capsys):
    big = np.arange(10_000, dtype=float)
    result, out, _ = _run(lambda v: 0.0, capsys, cases=[(big,)])
    assert not result.passed
    assert "..." in out and len(out) < 2_000


def test_quiet_prints_nothing(capsys):
    result, out, _ = _run(lambda v: 0.0, capsys, quiet=True)
    assert out == "" and not result.passed and "expected" in result.message


def test_result_repr_is_short_and_deterministic():
    r = run_check("x", lambda v: np.linalg.norm(v), CASES, reference_norm, quiet=True)
    assert repr(r) == "CheckResult(name='x', passed=True, n_cases=4)"


def test_allclose_semantics():
    eq = allclose(atol=1e-8, rtol=1e-6)
    assert eq(1.0, 1.0 + 1e-9)
    assert not eq(1.0, 1.001)
    assert not eq([1.0, 2.0], [1.0, 2.0, 3.0]), "shape mismatch"
    assert not eq(np.zeros((2, 2)), np.zeros(4)), "same size, different shape"
    assert not eq(np.nan, np.nan), "NaN is never a right answer"
    assert not eq(1.0, "one")
    assert not eq(1.0, None)
    assert eq(np.array([1.0, 2.0]), [1.0, 2.0]), "lists and arrays compare by value"


def test_endless_loop_is_stopped_and_reported(capsys):
    import signal
    import time

    def forever(v):
        while True:  # the student's own broad except must not swallow the stop
            try:
                time.sleep(0.01)
            except Exception:
                pass

    def sentinel(signum, frame):  # pragma: no cover - never fires
        pass

    previous = signal.signal(signal.SIGALRM, sentinel)
    try:
        t0 = time.perf_counter()
        result, out, err = _run(forever, capsys, time_limit=0.3)
        assert time.perf_counter() - t0 < 5
        assert not result.passed and result.n_cases == 1
        assert "more than 0.3 s" in out and "never ends" in out and err == ""
        # the alarm is switched off and the caller's handler restored
        assert signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)
        assert signal.getsignal(signal.SIGALRM) is sentinel
    finally:
        signal.signal(signal.SIGALRM, previous)


def test_unprintable_answer_is_a_failure_not_a_crash(capsys):
    class Weird:
        def __repr__(self):
            raise RuntimeError("no repr")

    result, out, err = _run(lambda v: Weird(), capsys)
    assert not result.passed
    assert "cannot be shown" in out and "RuntimeError" in out and err == ""


# ------------------------------------------------------------------ check.value
from shapelab import check  # noqa: E402


@pytest.mark.parametrize(
    "received, expected",
    [
        (1.0 + 1e-12, 1.0),
        (np.array([1.0, 2.0]), [1.0, 2.0]),
        ((1, 4, 0), (1, 4, 0)),
        (True, True),
        (np.True_, True),
    ],
)
def test_value_accepts_the_right_answer(received, expected, capsys):
    r = check.value("answer", received, expected)
    assert r.passed and capsys.readouterr().out.strip() == "✓ answer: correct."


@pytest.mark.parametrize(
    "received, expected, hint",
    [
        (3.5, 1.8271, "too large"),
        (0.5, 1.8271, "too small"),
        (np.array([1.0, 9.0, 3.0]), np.array([1.0, 2.5, 3.0]), "1 of 3 entries differ, the first at index 1"),
        (np.zeros(3), np.zeros(2), "expected shape (2,), got shape (3,)"),
        (np.zeros(2), 0.25, "expected a single number"),
        (float("nan"), 0.25, "NaN or inf"),
        ("0.25", 0.25, "expected a number"),
        (False, True, "that is not the answer"),
        (1, True, "expected a bool"),
    ],
)
def test_value_hints_without_revealing(received, expected, hint, capsys):
    r = check.value("answer", received, expected)
    out = capsys.readouterr().out
    assert not r.passed and out.startswith("✗ answer: not quite") and hint in out
    for shown in np.atleast_1d(np.asarray(expected, dtype=float)).tolist():
        if shown not in (0.0, 1.0, 3.0):  # values also in the student's own answer or the shape
            assert f"{shown}" not in out and f"{shown:g}" not in out
