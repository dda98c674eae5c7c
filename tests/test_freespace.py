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
