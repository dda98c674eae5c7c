"""The standard column reduction in public code (:mod:`shapelab.persistence`) against the
engine's fast path and against brute-force ranks (issue 33)."""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl
from shapelab.persistence import boundary_columns, filtration_order, persistence, reduce_columns


def _balls(dim: int, n: int, seed: int) -> sl.Balls:
    rng = np.random.default_rng(seed)
    return sl.Balls(rng.uniform(0, 4, (n, dim)), rng.uniform(0.1, 0.6, n))


@pytest.mark.parametrize("field", [2, 3])
@pytest.mark.parametrize("dim,n", [(2, 40), (3, 30)])
@pytest.mark.parametrize("seed", range(4))
def test_the_reduction_equals_the_fast_path(dim, n, seed, field):
    F = sl.alpha_filtration(_balls(dim, n, seed))
    fast = persistence(F, field=field)
    plain = persistence(F, field=field, method="reduction")
    assert fast.keys() == plain.keys()
    for k in fast:
        assert np.array_equal(fast[k], plain[k]), k  # bit for bit, as arrays


def test_the_default_is_the_fast_path_and_a_wrong_method_is_refused():
    F = sl.alpha_filtration(_balls(2, 12, 0))
    assert all(np.array_equal(F.persistence()[k], persistence(F)[k]) for k in F.persistence())
    with pytest.raises(ValueError, match="method"):
        persistence(F, method="gudhi")


def _rank_mod_p(M: np.ndarray, p: int) -> int:
    """Rank over Z/p by Gaussian elimination (brute force)."""
    A = M.copy() % p
    rank, rows, cols = 0, A.shape[0], A.shape[1]
    for c in range(cols):
        piv = next((r for r in range(rank, rows) if A[r, c]), None)
        if piv is None:
            continue
        A[[rank, piv]] = A[[piv, rank]]
        A[rank] = A[rank] * pow(int(A[rank, c]), p - 2, p) % p
        for r in range(rows):
            if r != rank and A[r, c]:
                A[r] = (A[r] - A[r, c] * A[rank]) % p
        rank += 1
    return rank


@pytest.mark.parametrize("field", [2, 3])
@pytest.mark.parametrize("dim,n,seed", [(2, 9, 1), (2, 10, 2), (3, 8, 3), (3, 9, 4)])
def test_betti_numbers_of_the_pairs_equal_brute_force_ranks(dim, n, seed, field):
    """beta_k(K_tau) = n_k - rank d_k - rank d_{k+1}, with the ranks of the boundary
    matrices restricted to the simplices entered by tau, against the pairs alive at tau."""
    F = sl.alpha_filtration(_balls(dim, n, seed))
    dims, _, values = filtration_order(F)
    cols = boundary_columns(F, field)
    N = len(cols)
    D = np.zeros((N, N), dtype=np.int64)
    for j, col in enumerate(cols):
        for i, c in col.items():
            D[i, j] = c
    pairs = persistence(F, field=field, method="reduction")
    taus = np.unique(values)
    for tau in (taus[:-1] + taus[1:]) / 2:
        inside = values <= tau
        for k in range(int(F.dimension) + 1):
            ck = inside & (dims == k)
            rk = _rank_mod_p(D[np.ix_(inside & (dims == k - 1), ck)], field) if k else 0
            rk1 = _rank_mod_p(D[np.ix_(ck, inside & (dims == k + 1))], field)
            brute = int(ck.sum()) - rk - rk1
            P = pairs[k]
            alive = int(np.count_nonzero((P[:, 0] <= tau) & (tau < P[:, 1])))
            assert alive == brute, (k, tau)


def test_reduce_columns_pairs_the_hollow_triangle_and_its_filling():
    # vertices 0, 1, 2; edges 01, 02, 12; the triangle 012
    cols = [{}, {}, {}, {0: 1, 1: 1}, {0: 1, 2: 1}, {1: 1, 2: 1}, {3: 1, 4: 1, 5: 1}]
    assert reduce_columns(cols).tolist() == [-1, -1, -1, 1, 2, -1, 5]
    # over Z/3 with the oriented boundary: the same pairs
    cols3 = [{}, {}, {}, {0: 2, 1: 1}, {0: 2, 2: 1}, {1: 2, 2: 1}, {3: 1, 4: 2, 5: 1}]
    assert reduce_columns(cols3, 3).tolist() == [-1, -1, -1, 1, 2, -1, 5]
