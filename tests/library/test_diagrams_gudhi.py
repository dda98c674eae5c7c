"""GUDHI comparisons of test_diagrams.py: the tests that need the peer library as an oracle,
kept apart so that the oracle-free tests run without GUDHI (issue 22)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab.diagrams import bottleneck_distance, wasserstein_distance
from tests.library.test_diagrams import (  # noqa: E402
    _diagrams,
    _diagrams_at_infinity,
    _hera_hangs,
)

gudhi = pytest.importorskip("gudhi")
hera = pytest.importorskip("gudhi.hera")


@settings(max_examples=200, deadline=None)
@given(_diagrams(inf=True), _diagrams(inf=True))
def test_bottleneck_equals_gudhi_exact(D1, D2):
    ours = bottleneck_distance(D1, D2)
    theirs = gudhi.bottleneck_distance(D1, D2, e=0)
    assert ours == pytest.approx(theirs, abs=1e-12) or (np.isinf(ours) and np.isinf(theirs))


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


def _assert_wasserstein_equals_hera(D1, D2, p, q):
    """Ours against hera's (relative error 1e-6): hera sees only non-empty diagrams of
    points off the diagonal, and inputs on which it hangs are left out."""
    D1, D2 = D1[D1[:, 1] > D1[:, 0]], D2[D2[:, 1] > D2[:, 0]]
    if len(D1) == 0 or len(D2) == 0 or _hera_hangs(D1, D2):
        return
    ours = wasserstein_distance(D1, D2, p=p, internal_p=q)
    theirs = hera.wasserstein_distance(D1, D2, order=p, internal_p=q, delta=1e-7)
    assert ours == pytest.approx(theirs, rel=1e-5, abs=1e-9) or (np.isinf(ours) and np.isinf(theirs))


@settings(max_examples=100, deadline=None)
@given(
    _diagrams(max_n=8, ints=False, inf=True),
    _diagrams(max_n=8, ints=False, inf=True),
    st.sampled_from([1.0, 2.0]),
    st.sampled_from([1.0, 2.0, np.inf]),
)
def test_internal_p_against_hera(D1, D2, p, q):
    """Against hera's ``internal_p`` (relative error 1e-6), points at infinity included
    (hera sees only non-empty diagrams of points off the diagonal, see above)."""
    _assert_wasserstein_equals_hera(D1, D2, p, q)


def test_internal_p_on_random_diagrams_against_hera():
    rng = np.random.default_rng(23)
    for _ in range(6):
        D = []
        for n in rng.integers(5, 40, 2):
            b = rng.uniform(0, 5, n)
            D.append(np.c_[b, b + rng.exponential(1.0, n)])
        for p in (1, 2):
            for q in (1, 2, np.inf):
                theirs = hera.wasserstein_distance(D[0], D[1], order=p, internal_p=q, delta=1e-9)
                assert wasserstein_distance(D[0], D[1], p=p, internal_p=q) == pytest.approx(theirs, rel=1e-7)


@settings(max_examples=200, deadline=None)
@given(_diagrams_at_infinity(), _diagrams_at_infinity())
def test_bottleneck_with_births_at_minus_infinity_equals_gudhi(D1, D2):
    ours = bottleneck_distance(D1, D2)
    theirs = gudhi.bottleneck_distance(D1, D2, e=0)
    assert ours == pytest.approx(theirs, abs=1e-12) or (np.isinf(ours) and np.isinf(theirs))


@settings(max_examples=60, deadline=None)
@given(
    _diagrams_at_infinity(max_n=6),
    _diagrams_at_infinity(max_n=6),
    st.sampled_from([1.0, 2.0]),
    st.sampled_from([1.0, 2.0, np.inf]),
)
def test_wasserstein_with_births_at_minus_infinity_against_hera(D1, D2, p, q):
    _assert_wasserstein_equals_hera(D1, D2, p, q)


def test_gudhi_handle_essential_parts_cases():
    """GUDHI's test_handle_essential_parts: the essential part costs 2 (order 1), the
    finite part 1; a third (b, inf) point makes the distance infinite."""
    inf = np.inf
    ess = [[2, inf], [3, inf], [-inf, 8], [-inf, 12], [-inf, -inf], [inf, inf], [-inf, inf], [-inf, inf]]
    diag1 = np.array([[0, 1], [3, 5]] + ess, float)
    diag2 = np.array([[0, 2], [3, 5]] + ess, float)
    diag2[3], diag2[5] = [4, inf], [-inf, 11]
    diag3 = np.insert(diag2, 4, [6, inf], axis=0)
    M = wasserstein_distance(diag1, diag2, p=1, matching=True)
    assert M.distance == 3.0
    expected = {(4, 4), (5, 5), (2, 2), (3, 3), (8, 8), (9, 9), (6, -1), (7, -1), (-1, 6), (-1, 7)}
    assert expected <= {tuple(e) for e in M.pairs}  # GUDHI's essential matching, plus the finite part
    assert bottleneck_distance(diag1, diag2) == 1.0 == gudhi.bottleneck_distance(diag1, diag2, e=0)
    assert wasserstein_distance(diag1, diag3, p=1) == np.inf
    assert bottleneck_distance(diag1, diag3) == np.inf == gudhi.bottleneck_distance(diag1, diag3, e=0)
