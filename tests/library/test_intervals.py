"""shapelab.intervals: Wilson and Clopper–Pearson intervals against scipy's binomtest
and the closed form's defining property."""

import numpy as np
import pytest
from scipy.stats import binom, binomtest, norm

from shapelab.intervals import clopper_pearson_interval, wilson_interval

CASES = [(0, 1), (1, 1), (0, 10), (10, 10), (8, 10), (3, 17), (72, 105), (46, 61), (1, 1000)]


@pytest.mark.parametrize("k,n", CASES)
@pytest.mark.parametrize("confidence", [0.9, 0.95, 0.99])
def test_scipy(k, n, confidence):
    ci = binomtest(k, n).proportion_ci(confidence_level=confidence, method="wilson")
    assert wilson_interval(k, n, confidence) == pytest.approx((ci.low, ci.high), abs=1e-12)
    ci = binomtest(k, n).proportion_ci(confidence_level=confidence, method="exact")
    assert clopper_pearson_interval(k, n, confidence) == pytest.approx((ci.low, ci.high), abs=1e-9)


@pytest.mark.parametrize("k,n", [(8, 10), (72, 105), (3, 17)])
def test_score_test_accepts_exactly_inside(k, n):
    # the Wilson ends are where the score statistic equals z
    z = norm.ppf(0.975)
    for p in wilson_interval(k, n):
        assert abs(k / n - p) == pytest.approx(z * np.sqrt(p * (1 - p) / n), rel=1e-9)


@pytest.mark.parametrize("k,n", [(8, 10), (3, 17)])
def test_clopper_pearson_tails(k, n):
    lo, hi = clopper_pearson_interval(k, n)
    assert binom.sf(k - 1, n, lo) == pytest.approx(0.025, rel=1e-7)  # P(X >= k | lo)
    assert binom.cdf(k, n, hi) == pytest.approx(0.025, rel=1e-7)  # P(X <= k | hi)


def test_known_value():
    lo, hi = wilson_interval(8, 10)
    assert (round(lo, 4), round(hi, 4)) == (0.4902, 0.9433)


def test_not_wald():
    k, n = 46, 61
    p = k / n
    half = norm.ppf(0.975) * np.sqrt(p * (1 - p) / n)
    assert abs(wilson_interval(k, n)[1] - (p + half)) > 0.01


@pytest.mark.parametrize("bad", [(5, 4), (-1, 4), (1, 0), (1.5, 4)])
def test_rejects(bad):
    with pytest.raises((ValueError, TypeError)):
        wilson_interval(*bad)
