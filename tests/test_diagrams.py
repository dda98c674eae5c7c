"""Distances between persistence diagrams (shapelab.diagrams), against GUDHI and brute force."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab.diagrams import bottleneck_distance, wasserstein_distance

gudhi = pytest.importorskip("gudhi")
hera = pytest.importorskip("gudhi.hera")


def _diagrams(max_n=6, ints=True, inf=False):
    coord = st.integers(0, 8).map(float) if ints else st.floats(0, 10, allow_nan=False)

    def point(pair):
        b, length = pair
        return [b, b + length]

    pts = st.lists(st.tuples(coord, coord).map(point), min_size=0, max_size=max_n)
    if not inf:
        return pts.map(lambda L: np.array(L, float).reshape(-1, 2))
    ess = st.lists(coord, min_size=0, max_size=2)
    return st.tuples(pts, ess).map(lambda t: np.array(t[0] + [[b, np.inf] for b in t[1]], float).reshape(-1, 2))


def _brute(D1, D2, p):
    """Every matching of the augmented problem (finite points only), by enumeration."""
    P, Q = D1, D2
    n, m = len(P), len(Q)
    N = n + m
    if N == 0:
        return 0.0

    def cost(i, j):
        if i < n and j < m:
            return max(abs(P[i, 0] - Q[j, 0]), abs(P[i, 1] - Q[j, 1]))
        if i < n:
            return (P[i, 1] - P[i, 0]) / 2 if j - m == i else np.inf
        if j < m:
            return (Q[j, 1] - Q[j, 0]) / 2 if i - n == j else np.inf
        return 0.0

    best = np.inf
    for perm in itertools.permutations(range(N)):
        c = [cost(i, perm[i]) for i in range(N)]
        val = max(c) if p == np.inf else sum(x**p for x in c) ** (1 / p)
        best = min(best, val)
    return best


def _achieved(D1, D2, pairs, p):
    costs = []
    for i, j in pairs:
        if i >= 0 and j >= 0:
            a, b = D1[i], D2[j]
            if np.isinf(a[1]) or np.isinf(b[1]):
                costs.append(abs(a[0] - b[0]))
            else:
                costs.append(max(abs(a[0] - b[0]), abs(a[1] - b[1])))
        elif i >= 0:
            costs.append((D1[i, 1] - D1[i, 0]) / 2)
        else:
            costs.append((D2[j, 1] - D2[j, 0]) / 2)
    costs = np.array(costs)
    if not len(costs):
        return 0.0
    return costs.max() if p == np.inf else float(np.sum(costs**p) ** (1 / p))


@settings(max_examples=200, deadline=None)
@given(_diagrams(inf=True), _diagrams(inf=True))
def test_bottleneck_equals_gudhi_exact(D1, D2):
    ours = bottleneck_distance(D1, D2)
    theirs = gudhi.bottleneck_distance(D1, D2, e=0)
    assert ours == pytest.approx(theirs, abs=1e-12) or (np.isinf(ours) and np.isinf(theirs))


@settings(max_examples=60, deadline=None)
@given(_diagrams(max_n=3), _diagrams(max_n=3), st.sampled_from([1.0, 2.0, np.inf]))
def test_against_brute_force_on_tiny_diagrams(D1, D2, p):
    f = bottleneck_distance if p == np.inf else (lambda a, b: wasserstein_distance(a, b, p=p))
    assert f(D1, D2) == pytest.approx(_brute(D1, D2, p), abs=1e-12)


@settings(max_examples=100, deadline=None)
@given(_diagrams(max_n=8, ints=False), _diagrams(max_n=8, ints=False), st.sampled_from([1.0, 2.0]))
def test_wasserstein_against_hera(D1, D2, p):
    """Against GUDHI's hera (relative error 1e-6).  Hera crashes on empty diagrams and
    diagonal points, so it sees only finite diagrams of points off the diagonal; those
    cases are covered by brute force above."""
    D1, D2 = D1[D1[:, 1] > D1[:, 0]], D2[D2[:, 1] > D2[:, 0]]
    if len(D1) == 0 or len(D2) == 0:
        return
    ours = wasserstein_distance(D1, D2, p=p)
    theirs = hera.wasserstein_distance(D1, D2, order=p, internal_p=np.inf, delta=1e-6)
    assert ours == pytest.approx(theirs, rel=1e-5, abs=1e-9)


@settings(max_examples=100, deadline=None)
@given(_diagrams(inf=True), _diagrams(inf=True), st.sampled_from([1.0, 2.0, np.inf]))
def test_the_matching_returned_achieves_the_distance(D1, D2, p):
    f = bottleneck_distance if p == np.inf else (lambda a, b, **k: wasserstein_distance(a, b, p=p, **k))
    M = f(D1, D2, matching=True)
    if np.isinf(M.distance):
        return
    pairs = M.pairs
    assert sorted(i for i, _ in pairs if i >= 0) == list(range(len(D1)))
    assert sorted(j for _, j in pairs if j >= 0) == list(range(len(D2)))
    assert _achieved(D1, D2, pairs, p) == pytest.approx(M.distance, abs=1e-9)


def test_simple_cases_and_symmetry():
    assert bottleneck_distance([], []) == 0.0 == wasserstein_distance([], [])
    assert bottleneck_distance([[0.0, 2.0]], []) == 1.0
    assert bottleneck_distance([[0.0, np.inf]], []) == np.inf
    assert bottleneck_distance([[0.0, np.inf]], [[3.0, np.inf]]) == 3.0
    rng = np.random.default_rng(0)
    b = rng.uniform(0, 5, 30)
    D1 = np.c_[b, b + rng.uniform(0, 3, 30)]
    b = rng.uniform(0, 5, 25)
    D2 = np.c_[b, b + rng.uniform(0, 3, 25)]
    assert bottleneck_distance(D1, D2) == bottleneck_distance(D2, D1)
    assert wasserstein_distance(D1, D2) == pytest.approx(wasserstein_distance(D2, D1), rel=1e-12)
    assert bottleneck_distance(D1, D1) == 0.0


def test_stability_on_an_alpha_filtration():
    """Cohen-Steiner, Edelsbrunner, Harer (2007): moving every simplex's value by at most
    eps moves the diagrams by at most eps.  Perturb the centres by delta; the values
    ||x - z||^2 - r^2 move by at most 2 R delta + delta^2 (R bounds ||x - z|| over the
    relevant orthocentres), checked against the measured largest change of any value."""
    import shapelab as sl

    rng = np.random.default_rng(5)
    c = rng.uniform(0, 6, (40, 2))
    r = rng.uniform(0.3, 0.8, 40)
    F = sl.alpha_filtration(sl.Balls(c, r))
    for delta in (1e-3, 1e-2, 5e-2):
        G = sl.alpha_filtration(sl.Balls(c + rng.uniform(-delta, delta, c.shape), r))
        for k in (0, 1):
            d = bottleneck_distance(F.persistence()[k], G.persistence()[k])
            # a crude bound on the change of any filtration value: centres move by at most
            # delta*sqrt(2), distances within the 6x6 box are below 6*sqrt(2) + radii
            eps = 2 * (6 * np.sqrt(2) + 1) * delta * np.sqrt(2) + 2 * delta**2
            assert d <= eps


@pytest.mark.parametrize(
    "bad, exc, match",
    [
        ([[1.0, 0.0]], ValueError, "dies before"),
        ([[np.nan, 1.0]], ValueError, "NaN"),
        ([[np.inf, np.inf]], ValueError, "infinite birth"),
        ([[1.0, 2.0, 3.0]], ValueError, "shape"),
        ("ab", TypeError, "D1"),
        (None, TypeError, "D1"),
    ],
)
def test_bad_diagrams_are_refused(bad, exc, match):
    with pytest.raises(exc, match=match):
        bottleneck_distance(bad, [[0.0, 1.0]])


@pytest.mark.parametrize("p, exc", [(0.5, ValueError), (np.inf, ValueError), ("2", TypeError), (True, TypeError)])
def test_bad_order_is_refused(p, exc):
    with pytest.raises(exc, match="p must"):
        wasserstein_distance([[0.0, 1.0]], [[0.0, 2.0]], p=p)


# ------------------------------------------------------- families of diagrams
def test_distance_matrix_is_the_pairwise_distances():
    from shapelab.diagrams import distance_matrix

    rng = np.random.default_rng(3)
    ds = []
    for n in (0, 3, 7, 12):
        b = rng.uniform(0, 1, n)
        ds.append(np.column_stack([b, b + rng.exponential(0.3, n)]))
    for p in (np.inf, 1, 2):
        M = distance_matrix(ds, p=p)
        assert M.shape == (4, 4)
        assert np.array_equal(M, M.T) and np.all(np.diag(M) == 0)
        for i, j in itertools.combinations(range(4), 2):
            ref = gudhi.bottleneck_distance(ds[i], ds[j], e=0) if p == np.inf else brute_or_hera(ds[i], ds[j], p)
            assert M[i, j] == pytest.approx(ref, rel=1e-6, abs=1e-9)
    with pytest.raises(TypeError, match="diagrams"):
        distance_matrix(np.zeros((3, 2)))
    with pytest.raises(ValueError, match=r"diagrams\[1\]"):
        distance_matrix([[[0.0, 1.0]], [[1.0, 0.0]]])


def brute_or_hera(D1, D2, p):
    if len(D1) == 0 and len(D2) == 0:
        return 0.0
    if len(D1) == 0 or len(D2) == 0:  # hera crashes on empty diagrams
        D = D1 if len(D1) else D2
        return float(np.sum(((D[:, 1] - D[:, 0]) / 2) ** p) ** (1 / p))
    return hera.wasserstein_distance(D1, D2, order=p, internal_p=np.inf, delta=1e-9)


@pytest.mark.parametrize("n", [60, 214])
def test_h0_diagrams_with_equal_births_are_fast_and_exact(n):
    """All births 0 (H0 of points): the augmented graph is layered, the input on which
    SciPy's Hopcroft-Karp takes exponential time (scipy#26147); 214 points took 13 s in
    its sparse assignment solver.  Now both distances use graphs without that structure;
    the values are checked against GUDHI and hera."""
    rng = np.random.default_rng(n)
    A = np.column_stack([np.zeros(n), rng.uniform(1, 2, n)])
    B = np.column_stack([np.zeros(n), rng.uniform(1, 2, n)])
    assert bottleneck_distance(A, B) == gudhi.bottleneck_distance(A, B, e=0)
    w = wasserstein_distance(A, B, p=2)
    assert w == pytest.approx(hera.wasserstein_distance(A, B, order=2, internal_p=np.inf, delta=1e-9), rel=1e-6)
    m = bottleneck_distance(A, B, matching=True)
    cost = [
        max(abs(A[i, 0] - B[j, 0]), abs(A[i, 1] - B[j, 1]))
        if i >= 0 and j >= 0
        else ((A[i, 1] - A[i, 0]) / 2 if i >= 0 else (B[j, 1] - B[j, 0]) / 2)
        for i, j in m.pairs
    ]
    assert max(cost) == m.distance
    assert sorted(i for i, _ in m.pairs if i >= 0) == list(range(n))
    assert sorted(j for _, j in m.pairs if j >= 0) == list(range(n))
