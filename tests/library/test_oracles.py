"""shapelab.oracles against closed forms and the library's exact answers: the
naive inclusion–exclusion formula, Monte Carlo, the sampled nerve and the raster."""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import alpha_filtration, union_measure
from shapelab.oracles import (
    intersection_area,
    monte_carlo_union_measure,
    naive_union_area,
    raster_topology,
    sampled_nerve,
)
from tests.library.test_measure import PI, lens_area, random_balls


def test_naive_formula_agrees_and_counts_terms():
    b = random_balls(5, 9, 2, 0.5, 1.3, box=3.0)
    area, n_sub, n_nonzero = naive_union_area(b)
    assert n_sub == 2**9 - 1 and 0 < n_nonzero <= n_sub
    assert area == pytest.approx(union_measure(b).area, rel=1e-10)
    with pytest.raises(ValueError, match="max_balls"):
        naive_union_area(random_balls(5, 20, 2))
    with pytest.raises(ValueError, match="2D"):
        naive_union_area(random_balls(5, 3, 3))


def test_intersection_area_closed_forms():
    assert intersection_area([[0, 0], [1.5, 0]], [1.0, 0.7]) == pytest.approx(lens_area(1.5, 1.0, 0.7), rel=1e-12)
    assert intersection_area([[0, 0], [0.1, 0]], [1.0, 0.5]) == pytest.approx(PI * 0.25, rel=1e-12)
    assert intersection_area([[0, 0], [3, 0]], [1.0, 1.0]) == 0.0
    s = 1.0
    c = s * np.array([[0, 0], [1, 0], [0.5, np.sqrt(3) / 2]])
    assert intersection_area(c, [s, s, s]) == pytest.approx((PI - np.sqrt(3)) * s**2 / 2, rel=1e-12)
    assert intersection_area([[0, 0], [0, 0]], [1.0, 1.0]) == pytest.approx(PI, rel=1e-14)


def test_monte_carlo_helper_within_bound():
    b = random_balls(8, 10, 2)
    est, se = monte_carlo_union_measure(b, 50_000, seed=1)
    assert abs(est - union_measure(b).area) < 4 * se


# ------------------------------------------------------- sampling oracles
def test_sampled_nerve_and_raster_topology_on_figure_23_1():
    from shapelab import datasets

    b = datasets.figure_23_1()
    F = alpha_filtration(b)
    for tau in (-0.3, 0.0, 3.0):  # no simplex enters within the sampling margin of these
        K = F.complex_at(tau)
        ours = {tuple(int(v) for v in s) for k in range(3) for s in K.simplices(k)}
        assert sampled_nerve(b, tau=tau, spacing=0.03) == ours
        assert raster_topology(b, tau=tau, spacing=0.03) == F.betti(tau)[:2]
    with pytest.raises(ValueError, match="2D"):
        raster_topology(random_balls(0, 3, 3))
    with pytest.raises(ValueError, match="spacing"):
        sampled_nerve(b, spacing=1e-5)


def test_truncated_naive_formula():
    b = random_balls(5, 6, 2, 0.8, 1.3, box=2.0)
    full, _, _ = naive_union_area(b)
    one, _, _ = naive_union_area(b, max_order=1)
    two, _, _ = naive_union_area(b, max_order=2)
    assert one == pytest.approx(np.sum(PI * b.radii**2), rel=1e-14)
    pairs = sum(
        lens_area(np.linalg.norm(b.centers[i] - b.centers[j]), b.radii[i], b.radii[j])
        for i in range(6)
        for j in range(i + 1, 6)
    )
    assert two == pytest.approx(one - pairs, rel=1e-12)
    assert naive_union_area(b, max_order=6)[0] == pytest.approx(full, rel=1e-14)
