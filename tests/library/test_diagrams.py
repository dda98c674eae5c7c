"""Distances between persistence diagrams (shapelab.diagrams), against GUDHI and brute force."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab.diagrams import bottleneck_distance, wasserstein_distance


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


def _lq(x, y, q):
    """The L_q norm of the plane vector (x, y), written out."""
    x, y = abs(x), abs(y)
    if q == np.inf:
        return max(x, y)
    return (x**q + y**q) ** (1 / q)


def _brute(D1, D2, p, q=np.inf):
    """Every matching of the augmented problem (finite points only), by enumeration, with
    the L_q ground metric; a point goes to the diagonal point ((b+d)/2, (b+d)/2)."""
    P, Q = D1, D2
    n, m = len(P), len(Q)
    N = n + m
    if N == 0:
        return 0.0

    def to_diag(b, d):
        return _lq((d - b) / 2, (d - b) / 2, q)

    def cost(i, j):
        if i < n and j < m:
            return _lq(P[i, 0] - Q[j, 0], P[i, 1] - Q[j, 1], q)
        if i < n:
            return to_diag(*P[i]) if j - m == i else np.inf
        if j < m:
            return to_diag(*Q[j]) if i - n == j else np.inf
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


@settings(max_examples=60, deadline=None)
@given(_diagrams(max_n=3), _diagrams(max_n=3), st.sampled_from([1.0, 2.0, np.inf]))
def test_against_brute_force_on_tiny_diagrams(D1, D2, p):
    f = bottleneck_distance if p == np.inf else (lambda a, b: wasserstein_distance(a, b, p=p))
    assert f(D1, D2) == pytest.approx(_brute(D1, D2, p), abs=1e-12)


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
        ([[np.inf, 1.0]], ValueError, "dies before"),
        ([[1.0, -np.inf]], ValueError, "dies before"),
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


# ----------------------------------------------------------------- internal_p (the ground metric)


@settings(max_examples=60, deadline=None)
@given(
    _diagrams(max_n=3),
    _diagrams(max_n=3),
    st.sampled_from([1.0, 2.0, 3.0]),
    st.sampled_from([1.0, 1.5, 2.0, np.inf]),
)
def test_internal_p_against_brute_force_on_tiny_diagrams(D1, D2, p, q):
    assert wasserstein_distance(D1, D2, p=p, internal_p=q) == pytest.approx(_brute(D1, D2, p, q), abs=1e-12)


def test_default_internal_p_is_inf_as_today_and_in_gudhi():
    rng = np.random.default_rng(5)
    b = rng.uniform(0, 5, (2, 12))
    D1, D2 = (np.c_[x, x + rng.uniform(0, 3, 12)] for x in b)
    for p in (1, 2, 3.5):
        assert wasserstein_distance(D1, D2, p=p) == wasserstein_distance(D1, D2, p=p, internal_p=np.inf)
    assert wasserstein_distance(D1[:4], D2[:4], p=2) == pytest.approx(_brute(D1[:4], D2[:4], 2), abs=1e-12)


def test_gudhi_basic_wasserstein_cases():
    """The cases of GUDHI's ``_basic_wasserstein`` (src/python/test/test_wasserstein_distance.py),
    with their expected values; GUDHI's argument ``order`` is our ``p``."""
    diag1 = np.array([[2.7, 3.7], [9.6, 14.0], [34.2, 34.974]])
    diag2 = np.array([[2.8, 4.45], [9.5, 14.1]])
    diag3 = np.array([[0, 2], [4, 6]])
    diag4 = np.array([[0, 3], [4, 8]])
    empty = np.empty((0, 2))

    def w(a, b, q, p):
        return wasserstein_distance(a, b, p=p, internal_p=q)

    for q in (2.0, np.inf):
        for p in (1.0, 2.0):
            assert w(empty, empty, q, p) == 0.0
    assert w(diag3, empty, np.inf, 1) == pytest.approx(2.0, rel=1e-15)
    assert w(diag3, empty, 1.0, 1) == pytest.approx(4.0, rel=1e-15)
    assert w(diag4, empty, 1.0, 2) == pytest.approx(5.0, rel=1e-15)
    assert w(diag4, empty, np.inf, 2) == pytest.approx(2.5, rel=1e-15)
    assert w(diag4, empty, 2.0, 2) == pytest.approx(3.5355339059327378, rel=1e-15)
    assert w(diag1, diag2, 2.0, 1) == pytest.approx(1.4453593023967701, rel=1e-14)
    assert w(diag1, diag2, 2.35, 1.74) == pytest.approx(0.9772734057168739, rel=1e-14)
    assert w(diag1, empty, 2.35, 1.7863) == pytest.approx(3.141592214572228, rel=1e-14)
    assert w(diag3, diag4, 1.0, 1) == pytest.approx(3.0, rel=1e-15)
    assert w(diag3, diag4, np.inf, 1) == pytest.approx(3.0, rel=1e-15)
    for q in (np.inf, 1.0, 4.5):
        assert w(diag3, diag4, q, 2) == pytest.approx(np.sqrt(5), rel=1e-15)
    # points at infinity
    diag5 = np.array([[0, 3], [4, np.inf]])
    diag6 = np.array([[7, 8], [4, 6], [3, np.inf]])
    assert wasserstein_distance(diag4, diag5) == np.inf
    assert w(diag5, diag6, np.inf, 1) == pytest.approx(4.0, rel=1e-15)
    assert wasserstein_distance(diag5, empty) == np.inf
    pairs = wasserstein_distance(diag1, diag2, p=2, internal_p=2, matching=True).pairs
    assert {tuple(e) for e in pairs} == {(0, 0), (1, 1), (2, -1)}
    pairs = wasserstein_distance(diag5, diag6, p=2, internal_p=2, matching=True).pairs
    assert {tuple(e) for e in pairs} == {(0, -1), (-1, 0), (-1, 1), (1, 2)}
    diag7 = np.array([[0, 3], [4, np.inf], [5, np.inf]])
    diag8 = np.array([[0, 1], [0, np.inf], [-np.inf, -np.inf], [np.inf, np.inf]])
    diag9 = np.array([[-np.inf, -np.inf], [np.inf, np.inf]])
    diag10 = np.array([[0, 1], [-np.inf, -np.inf], [np.inf, np.inf]])
    for a, b in ((diag5, diag7), (diag7, empty), (empty, diag7), (diag8, diag9)):
        M = wasserstein_distance(a, b, p=2, internal_p=2, matching=True)
        assert M.distance == np.inf and len(M.pairs) == 0
    M = wasserstein_distance(diag9, diag10, p=1, internal_p=1, matching=True)
    assert M.distance == 1  # (0, 1) goes to the diagonal at L1 distance 1
    assert {tuple(e) for e in M.pairs} == {(0, -1), (1, -1), (-1, 0), (-1, 1), (-1, 2)}
    M = wasserstein_distance(diag9, empty, p=2, internal_p=2, matching=True)
    assert M.distance == 0.0 and {tuple(e) for e in M.pairs} == {(0, -1), (1, -1)}


def test_bad_internal_p_is_refused():
    for q, exc in ((0.5, ValueError), (np.nan, ValueError), ("2", TypeError), (True, TypeError)):
        with pytest.raises(exc, match="internal_p must"):
            wasserstein_distance([[0.0, 1.0]], [[0.0, 2.0]], internal_p=q)


# ----------------------------------------------------------------- points at infinity


def _diagrams_at_infinity(max_n=4):
    """Finite points and all kinds of points at infinity: (b, inf), (-inf, d), (-inf, inf)."""
    coord = st.integers(0, 8).map(float)
    finite = st.tuples(coord, coord).map(lambda t: [t[0], t[0] + t[1]])
    kinds = st.one_of(
        finite,
        coord.map(lambda b: [b, np.inf]),
        coord.map(lambda d: [-np.inf, d]),
        st.just([-np.inf, np.inf]),
    )
    return st.lists(kinds, max_size=max_n).map(lambda L: np.array(L, float).reshape(-1, 2))


def _gudhi_essential_cost(D1, D2, p):
    """GUDHI's own rule, written here: counts per kind must agree, then each kind is
    matched in sorted order of its finite coordinate (p-th powers summed)."""
    total = 0.0
    for kind, col in (((True, False), 0), ((False, True), 1), ((False, False), None)):
        sel = [D[(np.isfinite(D[:, 0]) == kind[0]) & (np.isfinite(D[:, 1]) == kind[1])] for D in (D1, D2)]
        if len(sel[0]) != len(sel[1]):
            return np.inf
        if col is not None:
            c = np.abs(np.sort(sel[0][:, col]) - np.sort(sel[1][:, col]))
            total = max(total, c.max(initial=0.0)) if p == np.inf else total + float(np.sum(c**p))
    return total


def _finite(D):
    return D[np.isfinite(D).all(axis=1)]


def _hera_hangs(D1, D2):
    """Inputs on which hera's Wasserstein (GUDHI 3.13) fails, left to the brute-force tests:
    it crashes (segmentation fault) when a diagram has points at infinity only, and never
    returns when the finite parts are at distance 0 while the points at infinity are not
    (e.g. [[0, 1], [0, inf]] against [[0, 1], [4, inf]])."""
    F1, F2 = _finite(D1), _finite(D2)
    if len(F1) == 0 or len(F2) == 0:
        return True
    has_inf = len(F1) < len(D1) or len(F2) < len(D2)
    return has_inf and wasserstein_distance(F1, F2, p=1) == 0.0


@settings(max_examples=100, deadline=None)
@given(_diagrams_at_infinity(), _diagrams_at_infinity(), st.sampled_from([1.0, 2.0, np.inf]))
def test_points_at_infinity_are_priced_by_their_finite_coordinate(D1, D2, p):
    ess = _gudhi_essential_cost(D1, D2, p)
    if p == np.inf:
        ours = bottleneck_distance(D1, D2)
        expected = max(ess, _brute(_finite(D1), _finite(D2), p))
    else:
        ours = wasserstein_distance(D1, D2, p=p)
        expected = (ess + _brute(_finite(D1), _finite(D2), p) ** p) ** (1 / p)
    assert ours == pytest.approx(expected, abs=1e-12) or (np.isinf(ours) and np.isinf(expected))
    if np.isfinite(ours):
        f = bottleneck_distance if p == np.inf else (lambda a, b, **k: wasserstein_distance(a, b, p=p, **k))
        M = f(D1, D2, matching=True)
        assert sorted(i for i, _ in M.pairs if i >= 0) == list(range(len(D1)))
        assert sorted(j for _, j in M.pairs if j >= 0) == list(range(len(D2)))
        for i, j in M.pairs:  # a point at infinity goes to one of its own kind
            if i >= 0 and j >= 0:
                assert (np.isfinite(D1[i]) == np.isfinite(D2[j])).all()


def test_gudhi_basic_bottleneck_case():
    """GUDHI's test_basic_bottleneck (src/python/test/test_bottleneck_distance.py)."""
    diag1 = [[2.7, 3.7], [9.6, 14.0], [34.2, 34.974], [3.0, np.inf]]
    diag2 = [[2.8, 4.45], [9.5, 14.1], [3.2, np.inf]]
    assert bottleneck_distance(diag1, diag2) == 0.75


def test_points_at_infinity_simple_cases():
    inf = np.inf
    assert bottleneck_distance([[-inf, 1.0]], [[-inf, 3.0]]) == 2.0
    assert bottleneck_distance([[-inf, 1.0]], [[0.0, 3.0]]) == inf  # a (-inf, d) needs a partner
    assert bottleneck_distance([[-inf, 1.0]], [[0.0, inf]]) == inf  # of its own kind
    assert bottleneck_distance([[-inf, inf]], [[-inf, inf]]) == 0.0
    assert bottleneck_distance([[-inf, inf]], [[0.0, inf]]) == inf
    assert wasserstein_distance([[-inf, 1.0], [-inf, 5.0]], [[-inf, 4.5], [-inf, 1.2]], p=1) == pytest.approx(0.7)
    for D in ([[-inf, -inf]], [[inf, inf]]):  # on the diagonal
        assert bottleneck_distance(D, []) == 0.0 == wasserstein_distance(D, [])
        assert bottleneck_distance(D + [[0.0, 2.0]], [[0.0, 2.5]]) == 0.5


@pytest.mark.parametrize("c", [1e200, 1e-200, 2.0**-1070])
def test_distances_scale_with_the_diagrams(c):
    """Both distances are homogeneous of degree 1: W(cA, cB) = c W(A, B).  Costs to the
    power p overflowed (1e200: SciPy's 'cost matrix is infeasible') or underflowed to a
    zero distance (1e-200)."""
    A = np.array([[0.0, 4.0], [0.0, 1.0], [1.0, 3.0], [2.0, np.inf]])
    B = np.array([[0.0, 3.0], [0.5, 2.5], [1.0, np.inf]])
    for p, q in ((1, np.inf), (2, np.inf), (2, 1), (3.5, 2)):
        ref = wasserstein_distance(A, B, p, internal_p=q)
        assert wasserstein_distance(A * c, B * c, p, internal_p=q) == pytest.approx(ref * c, rel=1e-12, abs=0)
    assert bottleneck_distance(A * c, B * c) == pytest.approx(bottleneck_distance(A, B) * c, rel=1e-12, abs=0)


def test_huge_persistence_and_huge_orders():
    """(d - b)/2 overflowed for (-1e308, 1e308) (bottleneck inf, Wasserstein a SciPy error);
    cost**p overflowed for p = 1e6 (closed form: the pair costs hypot(1, 0.5) < sqrt 2)."""
    assert bottleneck_distance([[-1e308, 1e308]], []) == 1e308
    assert wasserstein_distance([[-1e308, 1e308]], [], 1) == 1e308
    assert wasserstein_distance([[0, 2]], [[1, 2.5]], 1e6, internal_p=2) == pytest.approx(np.hypot(1, 0.5), rel=1e-12)
    assert wasserstein_distance([[0, 3], [1, 2]], [[0, 2]], 1000) == pytest.approx(1.0, rel=1e-12)
