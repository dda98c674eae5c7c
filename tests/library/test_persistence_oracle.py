"""The reduction alone, against GUDHI loaded with *our* simplices and values.

``shapelab.topology`` computes persistence from ``F.simplices``, ``F.values`` and
``F.boundary`` (Kruskal for H0, Alexander duality for H_{d-1}, a cleared and
compressed column reduction for H1 in 3D).  The oracle gives GUDHI's
``SimplexTree`` exactly the same simplices and values (so the geometry is out of
the test) and compares the diagrams per dimension as multisets, after dropping the
round-off pairs (:func:`shapelab.topology.is_roundoff`) on both sides.  Diagrams do
not depend on how ties between equal values are broken (GUDHI and we break them
differently, both faces before cofaces), so grids, with many tied values, are
compared the same way.  Betti curves, voids and tunnels, which read the same
reduction, are checked against GUDHI's intervals on a mid-size protein-like input.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shapelab as sl

from .._oracles import bottleneck, compare, grid_balls, gudhi_diagrams, protein_like, random_balls

gudhi = pytest.importorskip("gudhi")


def assert_same_diagrams(F):
    d = compare(F)
    assert all(v == 0.0 for v in d.values()), d


# ----------------------------------------------------------------- random inputs
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("n", [100, 1000, 10_000])
def test_random_balls_match_gudhi_on_our_simplices(n, dim):
    if dim == 3 and n == 10_000:
        n = 5000  # keeps the test at about a second
    assert_same_diagrams(sl.alpha_filtration(random_balls(n, dim, seed=n + dim)))


@pytest.mark.parametrize("probe", [0.0, 1.4])
def test_protein_like_matches_gudhi_on_our_simplices(probe):
    b = protein_like(2000, seed=3, probe=probe)
    assert_same_diagrams(sl.alpha_filtration(b))


def test_protein_like_generator_is_protein_like():
    b = protein_like(500, seed=0)
    from scipy.spatial import ConvexHull, cKDTree

    d, _ = cKDTree(b.centers).query(b.centers, k=2)
    assert 1.4 < d[:, 1].min() and d[:, 1].max() < 3.5  # bonded neighbours
    assert 0.03 < len(b.centers) / ConvexHull(b.centers).volume < 0.08  # atoms per Å^3
    assert set(np.round(b.radii, 2)) <= {1.52, 1.55, 1.7, 1.8}
    np.testing.assert_array_equal(protein_like(500, seed=0).centers, b.centers)  # seeded


# --------------------------------------------------------- ties: integer grids
@pytest.mark.parametrize("k,dim", [(10, 2), (60, 2), (4, 3), (6, 3)])
@pytest.mark.parametrize("radius", [0.3, 0.5, 0.7])
def test_grids_with_tied_values_match_gudhi(k, dim, radius):
    assert_same_diagrams(sl.alpha_filtration(grid_balls(k, dim, radius)))


def test_grid_with_vacancies_and_element_radii_matches_gudhi():
    """Many exact ties in all dimensions (4 radii, lattice distances) at mid size."""
    rng = np.random.default_rng(0)
    g = grid_balls(60, 2).centers * 1.5
    g = g[rng.random(len(g)) > 0.15]
    r = np.array([1.52, 1.55, 1.7, 1.8])[rng.integers(0, 4, len(g))] + 1.4
    assert_same_diagrams(sl.alpha_filtration(sl.Balls(g, r)))


@settings(max_examples=60, deadline=None)
@given(
    dim=st.sampled_from([2, 3]),
    pts=st.lists(
        st.tuples(st.integers(0, 4), st.integers(0, 4), st.integers(0, 4)), min_size=5, max_size=30, unique=True
    ),
    radii=st.lists(st.integers(0, 3), min_size=30, max_size=30),
)
def test_small_integer_inputs_match_gudhi(dim, pts, radii):
    X = np.unique(np.array(pts, dtype=np.float64)[:, :dim], axis=0)
    if X.shape[0] < dim + 1:
        return
    b = sl.Balls(X, 0.5 * np.array(radii[: X.shape[0]], dtype=np.float64))
    assert_same_diagrams(sl.alpha_filtration(b))


def test_small_explicit_case_with_ties_3d():
    """A 2x2x3 block of unit spacing plus one off-lattice ball: ties in every
    dimension, an H1 class and a void-free filling; the whole diagram is checked."""
    X = np.array(
        [
            [0, 0, 0],
            [1, 0, 0],
            [0, 1, 0],
            [1, 1, 0],
            [0, 0, 1],
            [1, 0, 1],
            [0, 1, 1],
            [1, 1, 1],
            [0, 0, 2],
            [1, 0, 2],
            [0, 1, 2],
            [1, 1, 2],
            [0.5, 0.5, 3.1],
        ],
        dtype=np.float64,
    )
    F = sl.alpha_filtration(sl.Balls(X, 0.3))
    assert_same_diagrams(F)


# ------------------------------------------- readers of the reduction, same oracle
@pytest.fixture(scope="module")
def protein_filtration():
    return sl.alpha_filtration(protein_like(2000, seed=7, probe=0.0))


def _taus_between_values(F, count=60):
    v = np.unique(np.concatenate([F.values(k) for k in range(F.dimension + 1)]))
    v = v[np.isfinite(v)]
    gap = np.diff(v)
    ok = np.flatnonzero(gap > 1e-9 * np.maximum(1.0, np.abs(v[:-1])))
    pick = ok[np.linspace(0, ok.size - 1, count).astype(int)]
    return 0.5 * (v[pick] + v[pick + 1])


def _alive(P, tau):
    return int(np.sum((P[:, 0] <= tau) & (tau < P[:, 1])))


def test_betti_curve_matches_gudhi_intervals(protein_filtration):
    F = protein_filtration
    G = gudhi_diagrams(F)
    taus = _taus_between_values(F)
    curve = F.betti_curve(taus)
    expect = np.array([[_alive(G[k], t) for k in range(4)] for t in taus])
    np.testing.assert_array_equal(curve, expect)
    for i in (0, len(taus) // 2, len(taus) - 1):
        assert F.betti(taus[i]) == tuple(expect[i])


def test_voids_and_tunnels_match_gudhi_intervals(protein_filtration):
    F = protein_filtration
    G = gudhi_diagrams(F)
    for tau in (0.0, 0.5, 1.0, 2.0):
        V = sl.voids(F, tau)
        alive2 = G[2][(G[2][:, 0] <= tau) & (tau < G[2][:, 1])]
        assert bottleneck(np.array([[v.born, v.dies] for v in V]).reshape(-1, 2), alive2) == 0.0
        T = sl.tunnels(F, tau)
        alive1 = G[1][(G[1][:, 0] <= tau) & (tau < G[1][:, 1])]
        assert bottleneck(np.array([[t.birth, t.death] for t in T]).reshape(-1, 2), alive1) == 0.0
        assert len(T) == F.betti(tau)[1]
