"""GUDHI comparisons of test_topology.py: the tests that need the peer library as an oracle,
kept apart so that the oracle-free tests run without GUDHI (issue 22)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import shapelab as sl
from shapelab import topology as T
from tests.library.test_topology import (  # noqa: E402
    drop_short,
    points_2d,
    random_balls,
    same_diagram,
)

gudhi = pytest.importorskip("gudhi")


# ----------------------------------------------------------------------------- helpers
class GudhiFiltration:
    """The Filtration accessors over GUDHI's weighted alpha simplex tree.

    Rows of each dimension keep GUDHI's filtration order (a valid filtration order:
    values non-decreasing, faces before cofaces); vertex ids are the point indices.
    """

    def __init__(self, points, radii):
        points = np.asarray(points, dtype=float)
        radii = np.broadcast_to(np.asarray(radii, dtype=float), (len(points),))
        self.balls = sl.Balls(points, radii)
        self.st = gudhi.AlphaComplex(points=points, weights=radii**2).create_simplex_tree()
        by = {}
        for s, f in self.st.get_filtration():
            by.setdefault(len(s) - 1, []).append((sorted(s), f))
        self.dimension = max(by) if by else -1
        self._s, self._v, self._b = {}, {}, {}
        for k, lst in by.items():
            self._s[k] = np.array([s for s, _ in lst], dtype=np.int64).reshape(-1, k + 1)
            self._v[k] = np.array([f for _, f in lst], dtype=float)
        for k in range(1, self.dimension + 1):
            row = {tuple(r): i for i, r in enumerate(self._s[k - 1].tolist())}
            self._b[k] = np.array(
                [[row[tuple(r[:j] + r[j + 1 :])] for j in range(k + 1)] for r in self._s[k].tolist()], dtype=np.int64
            ).reshape(-1, k + 1)

    def simplices(self, k):
        return self._s.get(k, np.empty((0, k + 1), np.int64))

    def values(self, k):
        return self._v.get(k, np.empty(0))

    def boundary(self, k):
        return self._b.get(k, np.empty((0, k + 1), np.int64))

    def gudhi_intervals(self, k, *, drop_roundoff=True):
        """GUDHI's pairs; GUDHI also reports pairs of round-off length between tied
        entry times, which shapelab omits (``topology.is_roundoff``)."""
        self.st.compute_persistence()
        P = np.asarray(self.st.persistence_intervals_in_dimension(k), dtype=float).reshape(-1, 2)
        return P[~T.is_roundoff(self, P[:, 0], P[:, 1])] if drop_roundoff else P


# ------------------------------------------------------------------ persistence vs GUDHI
@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("seed", [0, 1])
def test_persistence_matches_gudhi_via_adapter(d, seed):
    rng = np.random.default_rng(seed)
    p, r = random_balls(rng, 70 if d == 3 else 120, d)
    G = GudhiFiltration(p, r)
    P = T.persistence(G)
    assert sorted(P) == list(range(d + 1))
    for k in range(d + 1):
        assert same_diagram(P[k], G.gudhi_intervals(k)), f"H{k} differs from GUDHI"


@pytest.mark.parametrize("d, n, seed", [(2, 400, 11), (3, 300, 12)])
def test_persistence_matches_gudhi_on_alpha_filtration(d, n, seed):
    rng = np.random.default_rng(seed)
    p, r = random_balls(rng, n, d, spread=n ** (1 / d) * 1.2, rmax=0.9)
    F = sl.alpha_filtration(sl.Balls(p, r))
    P = F.persistence()
    stree = gudhi.AlphaComplex(points=p, weights=r**2).create_simplex_tree()
    stree.compute_persistence()
    for k in range(d + 1):
        ref = np.asarray(stree.persistence_intervals_in_dimension(k), float).reshape(-1, 2)
        # shapelab's and GUDHI's entry times agree to round-off, so pairs of length
        # ~1e-15 may exist on one side only; compare the rest to 1e-9
        assert same_diagram(drop_short(P[k], 1e-10), drop_short(ref, 1e-10)), f"H{k}"
    # the diagram has the right shape: one essential H0 class, no others
    assert np.isinf(P[0][:, 1]).sum() == 1
    assert all(np.all(np.isfinite(P[k])) for k in range(1, d + 1))
    assert all(np.all(P[k][:, 1] > P[k][:, 0]) for k in range(d + 1))


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(pts=points_2d, radii=st.lists(st.sampled_from([0.0, 0.3, 0.5, 1.0]), min_size=16, max_size=16))
def test_persistence_on_degenerate_grids_matches_gudhi(pts, radii):
    """Grid points: many co-circular quadruples and tied entry times."""
    p = np.asarray(pts, float)
    if np.linalg.matrix_rank(p - p[0]) < 2:
        return
    r = np.asarray(radii[: len(p)])
    G = GudhiFiltration(p, r)
    P = T.persistence(G)
    for k in range(3):
        assert same_diagram(P[k], G.gudhi_intervals(k))


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10**6), n=st.integers(5, 25), scale=st.sampled_from([1e-3, 1.0, 50.0]))
def test_persistence_random_3d_matches_gudhi(seed, n, scale):
    rng = np.random.default_rng(seed)
    p = rng.uniform(0, 3, (n, 3)) * scale
    r = rng.uniform(0, 0.9, n) * scale
    G = GudhiFiltration(p, r)
    if G.dimension < 3:
        return
    P = T.persistence(G)
    for k in range(4):
        assert same_diagram(P[k], G.gudhi_intervals(k))


# ----------------------------------------------------------------------- degenerate
def test_collinear_and_coplanar_inputs():
    line = sl.Balls(np.c_[np.arange(6.0), np.zeros(6)], 0.4)
    F = sl.alpha_filtration(line)
    assert F.dimension == 1
    assert F.betti(0.0) == (6, 0, 0)
    assert F.betti(0.1) == (1, 0, 0)
    P = F.persistence()
    assert P[0].shape == (6, 2) and P[1].shape == (0, 2) and P[2].shape == (0, 2)
    # a planar ring of balls in 3D: the complex is 2-dimensional, one tunnel, no void
    t = 2 * np.pi * np.arange(12) / 12
    G = GudhiFiltration(np.c_[3 * np.cos(t), 3 * np.sin(t), np.zeros(12)], 1.0)
    assert G.dimension == 2
    assert T.betti(G, 0.0) == (1, 1, 0, 0)
    P = T.persistence(G)
    for k in range(4):
        assert same_diagram(P[k], G.gudhi_intervals(k))


# ------------------------------------------------------------ the coefficient field
@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("field", [3, 5, 11])
def test_persistence_over_odd_fields_equals_gudhi_in_the_same_field(seed, field):
    """Z/p persistence against GUDHI's reduction of the same simplices and values with
    homology_coeff_field=p: an independent column reduction (GUDHI's, signed, with
    its own orientation), exact equality of the pairs as multisets."""
    gudhi = pytest.importorskip("gudhi")  # noqa: F841
    from .._oracles import bottleneck, gudhi_diagrams, random_balls

    F = sl.alpha_filtration(random_balls(120, 3, seed=seed))
    ours = F.persistence(field=field)
    ref = gudhi_diagrams(F, field=field)
    for k in range(4):
        assert bottleneck(ours[k], ref[k]) == 0.0, (k, field)
