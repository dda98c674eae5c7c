"""shapelab.freespace: exact free area against a scan-line oracle (more checks of the
free space through Void.volume and Pocket.volume live in test_cavities.py)."""

from __future__ import annotations

import numpy as np

import shapelab as sl
from shapelab import freespace as FS
from tests.test_cavities import free_area_scanline, random_balls


def test_free_measure_matches_scanline_oracle_2d():
    balls = random_balls(9, 30, 2, spread=4.0, rmax=1.0)
    F = sl.alpha_filtration(balls)
    rng = np.random.default_rng(0)
    cells = F.simplices(2)[F.values(2) > 0.0]
    cells = cells[rng.choice(len(cells), size=min(6, len(cells)), replace=False)]
    # plus two arbitrary (non-Delaunay) triangles
    cells = np.vstack([cells, [[0, 5, 9], [3, 17, 22]]])
    for tau in (0.3,):
        got = FS.free_measure(balls, tau, cells)
        ref = [free_area_scanline(balls.centers[c], balls.centers, np.sqrt(balls.weights + tau)) for c in cells]
        assert np.allclose(got, ref, rtol=1e-9, atol=1e-11)
        assert np.any(np.asarray(ref) > 1e-3)


def test_free_points_lie_in_the_cells_and_outside_every_grown_ball():
    balls = random_balls(3, 25, 2, spread=4.0, rmax=1.0)
    F = sl.alpha_filtration(balls)
    cells = F.simplices(2)[-10:]  # the last to fill: free space left at tau = 0
    tau = 0.0
    pts = FS.free_points(balls, tau, cells, 2000, np.random.default_rng(0))
    assert pts.shape[1] == 2 and len(pts) > 0
    assert np.all(sl.power_distance(pts, balls).min(axis=1) > tau)
    # inside some cell: barycentric coordinates all >= 0 (up to round-off)
    X = balls.centers[cells]
    inside = np.zeros(len(pts), bool)
    for T in X:
        lam = np.linalg.solve(np.vstack([T.T, np.ones(3)]), np.vstack([pts.T, np.ones(len(pts))]))
        inside |= np.all(lam >= -1e-12, axis=0)
    assert inside.all()
