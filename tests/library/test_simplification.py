"""Persistence and ε-simplification of functions along a curve (shapelab.simplification).

Oracles: GUDHI's lower-star persistence of the same path or cycle graph; the defining
properties of an ε-simplification (the function moves by at most ε/2, and exactly the
pairs of persistence ≥ ε survive, at the same values); hand-worked small cases.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab.simplification import curve_persistence, simplify

values_st = st.lists(st.integers(-6, 6), min_size=2, max_size=40).map(lambda v: np.array(v, float))
float_values_st = st.lists(st.floats(-1e3, 1e3, allow_nan=False, width=64), min_size=2, max_size=60).map(np.array)


def _ours(P):
    return sorted((b, d) for b, d in P.diagram().tolist() if d > b)


@settings(max_examples=300, deadline=None)
@given(values_st, st.booleans(), st.sampled_from([0.0, 0.5, 1.0, 2.0, 3.5, 7.0, 20.0]))
def test_simplification_is_close_and_keeps_exactly_the_persistent_pairs(f, closed, eps):
    S = simplify(f, eps, closed=closed)
    assert S.error <= eps / 2 + 1e-12
    assert S.error == np.max(np.abs(S.values - f))
    before = _ours(curve_persistence(f, closed=closed))
    after = _ours(curve_persistence(S.values, closed=closed))
    assert after == [p for p in before if p[1] - p[0] >= eps]
    assert _ours(S.kept) == after
    gone = sorted((f[m], f[M]) for m, M in S.cancelled if f[M] > f[m])
    assert gone == [p for p in before if p[1] - p[0] < eps]


def test_zero_epsilon_changes_nothing_and_a_large_one_leaves_the_essential_extrema():
    rng = np.random.default_rng(3)
    f = rng.normal(size=200)
    assert np.array_equal(simplify(f, 0.0).values, f)
    S = simplify(f, 1e9, closed=True)
    assert len(S.kept) == 0 and _ours(curve_persistence(S.values)) == []
    assert S.values.max() == f.max() and S.values.min() == f.min()
    P = simplify(f, 1e9, closed=False)
    g = P.values
    lo = int(np.argmin(g))
    assert np.all(np.diff(g[: lo + 1]) <= 0) and np.all(np.diff(g[lo:]) >= 0)  # one valley


def test_a_hand_worked_path():
    f = [0.0, 3.0, 1.0, 2.0, -1.0, 4.0]
    P = curve_persistence(f, closed=False)
    assert P.pairs.tolist() == [[2, 3], [0, 1]] and P.essential_min == 4 and P.essential_max is None
    S = simplify(f, 1.5, closed=False)
    assert S.values.tolist() == [0.0, 3.0, 1.5, 1.5, -1.0, 4.0]
    assert S.cancelled.tolist() == [[2, 3]] and S.error == 0.5


def test_the_distance_along_a_curve_is_simplified_to_its_persistent_extrema():
    """§23.2: F(x) = |x - S| along a wiggly closed curve; small wiggles go, the lobes stay."""
    t = np.linspace(0.0, 2 * np.pi, 400, endpoint=False)
    r = 1.0 + 0.3 * np.cos(3 * t) + 0.01 * np.cos(41 * t)
    F = r  # distance from the centre, sampled along the curve
    P = curve_persistence(F)
    assert len(P) > 3  # the wiggles make many pairs
    S = simplify(F, 0.1)
    assert len(S.kept) == 2  # three lobes: three maxima, one of them essential
    assert S.error <= 0.05


@pytest.mark.parametrize(
    "bad, exc, match",
    [
        ([1.0], ValueError, "at least 2"),
        ([[1.0, 2.0]], ValueError, "1-D"),
        ([1.0, np.nan], ValueError, "finite"),
        ("abc", (TypeError, ValueError), "values"),
    ],
)
def test_bad_values_are_refused(bad, exc, match):
    with pytest.raises(exc, match=match):
        curve_persistence(bad)
    with pytest.raises(exc, match=match):
        simplify(bad, 1.0)


@pytest.mark.parametrize("eps", [-1.0, np.inf, np.nan, "x"])
def test_bad_epsilon_is_refused(eps):
    with pytest.raises((TypeError, ValueError), match="epsilon"):
        simplify([0.0, 1.0, 0.0], eps)
