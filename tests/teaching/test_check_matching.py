"""Self-checks of lessons 13–14 (shapelab/check/matching.py).

For every check: an independent correct student function passes, a plausible wrong
one fails with the first failing input in the message, and a crashing one is
reported, not raised.
"""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import check


def _dist(A, B):
    A, B = np.asarray(A, float), np.asarray(B, float)
    return np.sqrt(((A[:, None, :] - B[None, :, :]) ** 2).sum(axis=-1))


# ----------------------------------------------------------------- student solutions
def directed_right(A, B):
    return _dist(A, B).min(axis=1).max()


def directed_swapped(A, B):  # max over B of min over A: h(B, A)
    return _dist(A, B).min(axis=0).max()


def directed_max_max(A, B):  # the largest distance, not the max-min
    return _dist(A, B).max()


def hausdorff_right(A, B):
    D = _dist(A, B)
    return max(D.min(axis=1).max(), D.min(axis=0).max())


def hausdorff_one_sided(A, B):
    return directed_right(A, B)


def hausdorff_min_of_both(A, B):
    D = _dist(A, B)
    return min(D.min(axis=1).max(), D.min(axis=0).max())


def maxima_right(P, S):
    V = np.asarray(P, float)[:-1]
    R = V - S
    E = np.roll(V, -1, axis=0) - V
    fwd = (R * E).sum(axis=1)  # slope of F² leaving towards the next vertex
    bwd = (R * np.roll(E, 1, axis=0)).sum(axis=1)  # slope arriving from the previous one
    return np.sort(np.linalg.norm(R, axis=1)[(fwd < 0) & (bwd > 0)])


def maxima_by_neighbours(P, S):  # compares vertices only: misses dips inside segments
    V = np.asarray(P, float)[:-1]
    F = np.linalg.norm(V - S, axis=1)
    return np.sort(F[(F >= np.roll(F, 1)) & (F >= np.roll(F, -1))])


def minima_right(P, S):
    V = np.asarray(P, float)[:-1]
    R = V - S
    E = np.roll(V, -1, axis=0) - V
    fwd = (R * E).sum(axis=1)
    bwd = (R * np.roll(E, 1, axis=0)).sum(axis=1)
    out = list(np.linalg.norm(R, axis=1)[(fwd >= 0) & (bwd <= 0)])
    tau = -fwd / (E * E).sum(axis=1)
    inside = (tau > 0) & (tau < 1)
    out += list(np.linalg.norm(V[inside] + tau[inside, None] * E[inside] - S, axis=1))
    return np.sort(out)


def minima_vertices_only(P, S):
    V = np.asarray(P, float)[:-1]
    F = np.linalg.norm(V - S, axis=1)
    return np.sort(F[(F <= np.roll(F, 1)) & (F <= np.roll(F, -1))])


def maxima_non_strict(P, S):  # a zero slope taken for a turn: a regular vertex counted
    V = np.asarray(P, float)[:-1]
    R = V - S
    E = np.roll(V, -1, axis=0) - V
    fwd = (R * E).sum(axis=1)
    bwd = (R * np.roll(E, 1, axis=0)).sum(axis=1)
    return np.sort(np.linalg.norm(R, axis=1)[(fwd <= 0) & (bwd >= 0)])


def minima_closed_feet(P, S):  # feet on the closed edge: a foot at a vertex counted twice
    V = np.asarray(P, float)[:-1]
    R = V - S
    E = np.roll(V, -1, axis=0) - V
    fwd = (R * E).sum(axis=1)
    bwd = (R * np.roll(E, 1, axis=0)).sum(axis=1)
    out = list(np.linalg.norm(R, axis=1)[(fwd >= 0) & (bwd <= 0)])
    tau = -fwd / (E * E).sum(axis=1)
    inside = (tau >= 0) & (tau <= 1)
    out += list(np.linalg.norm(V[inside] + tau[inside, None] * E[inside] - S, axis=1))
    return np.sort(out)


def crashing(*args):
    raise RuntimeError("oops")


def not_implemented(*args):
    raise NotImplementedError


# ----------------------------------------------------------------- tests
@pytest.mark.parametrize(
    "check_fn, right, wrongs",
    [
        (check.directed_hausdorff, directed_right, [directed_swapped, directed_max_max, hausdorff_right]),
        (check.hausdorff, hausdorff_right, [hausdorff_one_sided, hausdorff_min_of_both, directed_max_max]),
        (check.critical_points, maxima_right, [maxima_by_neighbours, minima_right, maxima_non_strict]),
    ],
)
def test_right_passes_and_wrong_fails(check_fn, right, wrongs, capsys):
    res = check_fn(right)
    assert res.passed and res.n_cases >= 6
    assert "✓" in capsys.readouterr().out
    for wrong in wrongs:
        res = check_fn(wrong)
        out = capsys.readouterr().out
        assert not res.passed, wrong.__name__
        assert "First failing input" in out and "expected" in out and "received" in out


def test_minima_contract(capsys):
    assert check.critical_points(minima_right, kind="min")
    assert not check.critical_points(minima_closed_feet, kind="min")  # second reading (issue 21)
    assert not check.critical_points(minima_vertices_only, kind="min")
    assert not check.critical_points(maxima_right, kind="min")
    with pytest.raises(ValueError, match="kind"):
        check.critical_points(minima_right, kind="saddle")


@pytest.mark.parametrize("check_fn", [check.directed_hausdorff, check.hausdorff, check.critical_points])
def test_crashes_and_placeholders_are_reported_not_raised(check_fn, capsys):
    res = check_fn(crashing)
    assert not res.passed and "RuntimeError" in res.message
    res = check_fn(not_implemented)
    assert not res.passed and "not implemented" in res.message
    res = check_fn(42)
    assert not res.passed and "expected a function" in res.message


def test_quiet_mode_prints_nothing(capsys):
    res = check.hausdorff(hausdorff_right, quiet=True)
    assert res.passed and capsys.readouterr().out == ""


def test_student_function_does_not_mutate_the_cases():
    def mutating(A, B):
        A[:] = 0.0
        return hausdorff_right(A, B)

    # a function that zeroes its input still sees fresh copies on every case
    res = check.hausdorff(mutating, quiet=True)
    assert not res.passed  # zeroed A gives the wrong distance...
    assert check.hausdorff(hausdorff_right, quiet=True).passed  # ...and the cases are intact
