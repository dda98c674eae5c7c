"""GUDHI comparisons of test_cavities.py: the tests that need the peer library as an oracle,
kept apart so that the oracle-free tests run without GUDHI (issue 22)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shapelab as sl
from shapelab import cavities as C
from shapelab import topology as T
from shapelab.cavities import freespace as FS
from tests.library.test_cavities import (  # noqa: E402
    fibonacci_sphere,
    monte_carlo_free,
    ring,
    winding_parity,
)

gudhi = pytest.importorskip("gudhi")
from tests.library.test_topology_gudhi import GudhiFiltration  # noqa: E402


@pytest.mark.parametrize("source", ["shapelab", "gudhi"])
def test_ring_of_disks_hole_area_closed_form(source):
    """N equal disks of radius r on a circle of radius R, neighbours overlapping, no
    triple overlaps, no disk reaching a non-adjacent polygon edge.  Inside the
    polygon P of the centres each disk covers the sector of the interior angle
    θ = π - 2π/N, neighbouring sectors overlap in half a lens, so

        hole = area(P) - N θ r²/2 + N lens(s)/2,  s = 2R sin(π/N),
        area(P) = N R² sin(2π/N)/2,  lens(s) = 2r² acos(s/2r) - (s/2)√(4r² - s²).

    It is born when neighbours touch, τ = s²/4 - r², and dies when the centre is
    covered, τ = R² - r² (all centres co-circular: a degenerate input)."""
    N, R, r = 8, 3.0, 1.2
    s = 2 * R * np.sin(np.pi / N)
    assert s < 2 * r < 2 * R * np.sin(2 * np.pi / N) and s * np.sin(2 * np.pi / N) > r
    balls = ring(N, R, r, phase=0.3)
    F = sl.alpha_filtration(balls) if source == "shapelab" else GudhiFiltration(balls.centers, balls.radii)
    theta = np.pi - 2 * np.pi / N
    lens = 2 * r * r * np.arccos(s / (2 * r)) - s / 2 * np.sqrt(4 * r * r - s * s)
    hole = N * R * R * np.sin(2 * np.pi / N) / 2 - N * theta * r * r / 2 + N * lens / 2
    vs = C.voids(F, 0.0)
    assert len(vs) == 1
    v = vs[0]
    assert v.volume == pytest.approx(hole, rel=1e-12)
    assert v.born == pytest.approx(s * s / 4 - r * r, rel=1e-9)
    assert v.dies == pytest.approx(R * R - r * r, rel=1e-9)
    assert sorted(v.lining.tolist()) == list(range(N))
    # grown a bit further, the closed form holds with r² + τ
    tau = 0.1
    rt = np.sqrt(r * r + tau)
    lens_t = 2 * rt * rt * np.arccos(s / (2 * rt)) - s / 2 * np.sqrt(4 * rt * rt - s * s)
    hole_t = N * R * R * np.sin(2 * np.pi / N) / 2 - N * theta * rt * rt / 2 + N * lens_t / 2
    assert C.voids(F, tau)[0].volume == pytest.approx(hole_t, rel=1e-12)


@pytest.mark.parametrize("source", ["shapelab", "gudhi"])
def test_cage_of_balls_has_one_void_with_monte_carlo_volume(source):
    c = fibonacci_sphere(70, 3.0)  # exactly co-spherical centres: a degenerate DT
    balls = sl.Balls(c, 1.0)
    F = sl.alpha_filtration(balls) if source == "shapelab" else GudhiFiltration(c, 1.0)
    vs = sl.voids(F, 0.0)
    assert len(vs) == 1
    v = vs[0]
    est, sigma = monte_carlo_free(balls, 0.0, v.cells, 200_000, seed=1)
    assert abs(v.volume - est) < 5 * sigma
    # a crude bound: inside the sphere of radius 3 - 1 there is no ball
    assert v.volume > 4 / 3 * np.pi * 2.0**3
    # it fills when the sphere's centre, at distance 3 from every centre, is covered:
    # 1 + tau = 3^2
    assert v.dies == pytest.approx(9 - 1, rel=1e-9)


# ----------------------------------------------------------------------- degenerate
@settings(max_examples=6, deadline=None)
@given(holes=st.sets(st.tuples(st.integers(1, 4), st.integers(1, 4)), min_size=1, max_size=3))
def test_grid_with_holes_voids_equal_betti(holes):
    """Integer grid (all quadruples co-circular), some points removed; GUDHI adapter."""
    g = np.array([(i, j) for i in range(6) for j in range(6) if (i, j) not in holes], dtype=float)
    G = GudhiFiltration(g, 0.55)
    for tau in (0.0, 0.1, 0.3):
        vs = C.voids(G, tau)
        assert len(vs) == T.betti(G, tau)[1]
        for v in vs:
            assert v.volume > 0
            assert v.volume == pytest.approx(FS.free_measure(G.balls, tau, v.cells).sum(), rel=1e-9, abs=1e-12)


def test_flat_inputs_have_no_voids_but_can_have_tunnels():
    t = 2 * np.pi * np.arange(12) / 12
    flat = sl.Balls(np.c_[3 * np.cos(t), 3 * np.sin(t), np.zeros(12)], 1.0)
    G = GudhiFiltration(flat.centers, flat.radii)
    assert C.voids(G, 0.0) == ()
    assert C.pockets(G, 0.0) == ()
    tn = C.tunnels(G, 0.0)
    assert len(tn) == 1 and winding_parity(tn[0].cycle, flat.centers) == 1
    line = sl.Balls(np.c_[np.arange(5.0), np.zeros(5)], 0.3)
    assert sl.voids(line, 0.0) == () and sl.pockets(line, 0.0) == ()
