"""Real proteins, end to end: the certified triangulation and the persistence of the
shipped structures against GUDHI's own exact alpha complex (issue 10).

The oracle is independent of our triangulation: GUDHI builds its own (CGAL, exact)
weighted alpha complex from the same balls.  Diagrams are compared after rounding both
to 1e-7 (our values agree with GUDHI's exact ones to ~1e-11), so the comparison is a
multiset equality plus a bottleneck distance on what is left.
"""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl
from shapelab import datasets
from shapelab.power import triangulation_report

from ._oracles import bottleneck

gudhi = pytest.importorskip("gudhi")


def gudhi_exact_diagrams(balls, dim=3):
    ac = gudhi.AlphaComplex(points=balls.centers, weights=balls.radii**2, precision="exact")
    st = ac.create_simplex_tree()
    st.compute_persistence(homology_coeff_field=2, min_persistence=0)
    return {k: np.asarray(st.persistence_intervals_in_dimension(k), dtype=float).reshape(-1, 2) for k in range(dim + 1)}


def rounded(P):
    P = np.asarray(P, dtype=float).reshape(-1, 2)
    P = P[P[:, 1] - P[:, 0] > 1e-7]  # round-off pairs, on both sides
    return np.round(P, 7) + 0.0


@pytest.mark.parametrize("name", ["1grm", "1hvr", "t4l-l99a"])
@pytest.mark.parametrize("probe", [0.0, 1.4])
def test_persistence_of_a_real_protein_equals_gudhi_exact(name, probe):
    s = datasets.structure(name)
    balls = sl.Balls(s.balls.centers, s.balls.radii + probe)
    rep = triangulation_report(balls)
    assert rep.method == "qhull", rep.reason  # real data: the filter decides
    ours = sl.alpha_filtration(balls).persistence()
    theirs = gudhi_exact_diagrams(balls)
    for k in range(4):
        a, b = rounded(ours.get(k, np.empty((0, 2)))), rounded(theirs[k])
        assert a.shape[0] == b.shape[0], (k, a.shape, b.shape)
        assert bottleneck(a, b) <= 2e-7, k
