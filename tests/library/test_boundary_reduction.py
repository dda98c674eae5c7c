"""Filtration.boundary_matrix and topology.reduce_boundary (the persistence algorithm of
lesson 11), and the self-check check.boundary_reduction.

Oracles: the boundary matrix is compared with the filtration's own facets and order;
the pairs read off the reduction are compared with ``F.persistence()`` and with GUDHI's
weighted alpha complex in Z/2; the lowest ones are compared with a brute-force rank
formula (the pairing lemma) and with a reduction that adds columns in random order.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import sparse
from shapelab.topology import is_roundoff, reduce_boundary

import shapelab as sl
from shapelab import check


def _filtration(seed, n, dim):
    rng = np.random.default_rng(seed)
    return sl.alpha_filtration(sl.Balls(rng.uniform(0.0, 4.0, (n, dim)), rng.uniform(0.3, 0.9, n)))


def _pairs(F, B, low):
    j = np.flatnonzero(low >= 0)
    ess = np.setdiff1d(np.flatnonzero(low < 0), low[j])
    out = {}
    for k in range(F.balls.dim + 1):
        fin = j[B.dims[low[j]] == k]
        e = ess[B.dims[ess] == k]
        P = np.vstack(
            [
                np.column_stack((B.values[low[fin]], B.values[fin])),
                np.column_stack((B.values[e], np.full(e.size, np.inf))),
            ]
        )
        P = P[(P[:, 1] > P[:, 0]) & ~is_roundoff(F, P[:, 0], P[:, 1])]
        out[k] = P[np.lexsort((P[:, 1], P[:, 0]))]
    return out


def _rank2(M):
    M = np.array(M, dtype=np.uint8) % 2
    r = 0
    for c in range(M.shape[1]):
        rows = np.flatnonzero(M[r:, c]) if r < M.shape[0] else []
        if len(rows) == 0:
            continue
        p = r + rows[0]
        M[[r, p]] = M[[p, r]]
        for q in np.flatnonzero(M[:, c]):
            if q != r:
                M[q] ^= M[r]
        r += 1
    return r


CASES = [(0, 6, 2), (1, 9, 2), (2, 7, 3), (3, 10, 3)]


@pytest.mark.parametrize("seed,n,dim", CASES)
def test_boundary_matrix_is_the_filtrations_boundary_in_its_order(seed, n, dim):
    F = _filtration(seed, n, dim)
    B = F.boundary_matrix()
    D = B.matrix.toarray()
    assert D.dtype == np.uint8 and D.shape == (len(F), len(F))
    assert not np.tril(D).any()  # strictly upper triangular: faces first
    assert np.all(np.diff(B.values) >= 0)
    key = {(int(k), int(r)): i for i, (k, r) in enumerate(zip(B.dims, B.rows))}
    assert len(key) == len(F)
    for j, (k, r) in enumerate(zip(B.dims, B.rows)):
        assert B.values[j] == F.values(int(k))[r]
        verts = set(F.simplices(int(k))[r].tolist())
        rows = set(np.flatnonzero(D[:, j]).tolist())
        if k == 0:
            assert rows == set()
            continue
        # the facets by their vertices, found among the (k-1)-simplices
        facets = {
            i
            for i, (kk, rr) in enumerate(zip(B.dims, B.rows))
            if kk == k - 1 and set(F.simplices(int(kk))[rr].tolist()) < verts
        }
        assert rows == facets and len(rows) == k + 1


def test_boundary_matrix_of_one_ball_and_read_only():
    B = sl.alpha_filtration(sl.Balls([[0.0, 0.0, 0.0]], [1.0])).boundary_matrix()
    assert B.matrix.shape == (1, 1) and B.matrix.nnz == 0 and B.dims.tolist() == [0]
    with pytest.raises(ValueError):
        B.values[0] = 1.0


@pytest.mark.parametrize("seed,n,dim", CASES)
def test_reduction_pairs_equal_persistence_and_gudhi(seed, n, dim):
    gudhi = pytest.importorskip("gudhi")
    F = _filtration(seed, n, dim)
    B = F.boundary_matrix()
    R, low = reduce_boundary(B.matrix)
    P = _pairs(F, B, low)
    lib = F.persistence()
    ac = gudhi.AlphaComplex(points=F.balls.centers, weights=F.balls.radii**2)
    st = ac.create_simplex_tree()
    st.compute_persistence(homology_coeff_field=2)
    for k in range(dim + 1):
        np.testing.assert_allclose(P[k], lib[k], rtol=1e-9, atol=1e-12)
        g = np.asarray(st.persistence_intervals_in_dimension(k)).reshape(-1, 2)
        g = g[(g[:, 1] > g[:, 0]) & ~is_roundoff(F, g[:, 0], g[:, 1])]
        g = g[np.lexsort((g[:, 1], g[:, 0]))]
        np.testing.assert_allclose(P[k], g, rtol=1e-7, atol=1e-9)


@pytest.mark.parametrize("seed,n,dim", CASES[:3])
def test_lowest_ones_satisfy_the_pairing_lemma_and_any_order(seed, n, dim):
    F = _filtration(seed, n, dim)
    D = F.boundary_matrix().matrix.toarray()
    R, low = reduce_boundary(D)
    N = len(D)
    r = {}

    def rank(i, j):
        if j < 0 or i >= N:
            return 0
        if (i, j) not in r:
            r[i, j] = _rank2(D[i:, : j + 1])
        return r[i, j]

    for j in range(N):
        for i in range(j):
            assert (low[j] == i) == (rank(i, j) - rank(i + 1, j) - rank(i, j - 1) + rank(i + 1, j - 1) == 1)
    # R = D V: every column a cycle, and reduced
    Rd = R.toarray().astype(np.int64)
    assert not ((D.astype(np.int64) @ Rd) % 2).any()
    nz = low[low >= 0]
    assert nz.size == np.unique(nz).size
    # additions of earlier columns in random order reach the same lowest ones
    rng = np.random.default_rng(seed)
    M = D.copy()

    def lows(M):
        return np.array([np.flatnonzero(M[:, c])[-1] if M[:, c].any() else -1 for c in range(N)])

    while True:
        L = lows(M)
        cand = [(i, j) for j in range(N) for i in range(j) if L[j] >= 0 and L[i] == L[j]]
        if not cand:
            break
        i, j = cand[rng.integers(len(cand))]
        M[:, j] ^= M[:, i]
    assert np.array_equal(lows(M), low)


def test_reduce_boundary_inputs():
    D = np.array([[0, 0, 1], [0, 0, 1], [0, 0, 0]])
    R, low = reduce_boundary(sparse.csr_matrix(D))
    assert low.tolist() == [-1, -1, 1] and isinstance(R, sparse.csc_matrix)
    assert reduce_boundary(D * 3)[1].tolist() == [-1, -1, 1]  # entries mod 2
    assert reduce_boundary(np.zeros((0, 0)))[1].size == 0
    with pytest.raises(ValueError, match="square"):
        reduce_boundary(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="integers"):
        reduce_boundary(np.full((2, 2), 0.5))
    with pytest.raises(TypeError, match="D must"):
        reduce_boundary(np.array([["a", "b"], ["c", "d"]]))


# ------------------------------------------------------------------ the self-check
def _right(D):
    R = np.array(D, dtype=np.uint8)
    owner = {}
    for j in range(R.shape[1]):
        while R[:, j].any():
            i = int(np.flatnonzero(R[:, j])[-1])
            if i not in owner:
                owner[i] = j
                break
            R[:, j] ^= R[:, owner[i]]
    return R


def _no_reduction(D):
    return np.array(D)


def _later_columns(D):  # adds a later column to an earlier one: lows may look distinct, R is not D V
    R = np.array(D, dtype=np.uint8)
    n = R.shape[0]
    for j in range(n - 1, -1, -1):
        for k in range(j + 1, n):
            if R[:, j].any() and R[:, k].any() and np.flatnonzero(R[:, j])[-1] == np.flatnonzero(R[:, k])[-1]:
                R[:, j] ^= R[:, k]
    return R


def _lows_only(D):  # right lowest ones, garbage above them: the columns are not cycles
    R = _right(D)
    out = np.zeros_like(R)
    for j in range(R.shape[1]):
        if R[:, j].any():
            out[np.flatnonzero(R[:, j])[-1], j] = 1
    return out


def test_boundary_reduction_check_passes_the_right_answer(capsys):
    assert check.boundary_reduction(_right).passed
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize("wrong", [_no_reduction, _later_columns, _lows_only, lambda D: None, lambda D: 0])
def test_boundary_reduction_check_refuses_mistakes(wrong):
    r = check.boundary_reduction(wrong, quiet=True)
    assert not r.passed


# ------------------------------------------------------- second reading (issue 21)
def _right_then_later(D):  # the right R, then a later column added to an earlier one with a higher low
    R = _right(D)
    low = [int(np.flatnonzero(c)[-1]) if c.any() else -1 for c in R.T]
    for j in range(R.shape[1]):
        k = next((k for k in range(j + 1, R.shape[1]) if 0 <= low[k] < low[j]), None)
        if k is not None:
            R[:, j] ^= R[:, k]
    return R


def test_check_refuses_a_later_column_that_keeps_the_lowest_ones():
    # the lowest ones are right and D R = 0 still holds, but R is not D V with V upper triangular
    D = check.topology._hand_made_matrices()[-1]
    R = _right_then_later(D)
    assert (
        np.array_equal([int(np.flatnonzero(c)[-1]) if c.any() else -1 for c in R.T], reduce_boundary(D)[1])
        and not ((D.astype(int) @ R) % 2).any()
    )
    r = check.boundary_reduction(_right_then_later, quiet=True)
    assert not r.passed and "not column" in r.message and "earlier columns" in r.message


def test_later_column_additions_can_swap_the_lowest_ones():
    # exercise 5's model answer: vertices 0, 1, 2, edges 01, 02; add 02 to 01, then reduce 02 by it
    D = np.zeros((5, 5), dtype=np.uint8)
    D[[0, 1], 3] = D[[0, 2], 4] = 1
    M = D.copy()
    M[:, 3] ^= M[:, 4]
    M[:, 4] ^= M[:, 3]
    lows = [int(np.flatnonzero(c)[-1]) if c.any() else -1 for c in M.T]
    assert lows == [-1, -1, -1, 2, 1] and reduce_boundary(D)[1].tolist() == [-1, -1, -1, 1, 2]


def _clearing(D):  # the twist: zero the column of each lowest one found (a valid shortcut)
    R = np.array(D, dtype=np.uint8)
    owner = {}
    for j in range(R.shape[1]):
        while R[:, j].any():
            i = int(np.flatnonzero(R[:, j])[-1])
            if i not in owner:
                owner[i] = j
                R[:, i] = 0
                break
            R[:, j] ^= R[:, owner[i]]
    return R


@pytest.mark.parametrize(
    "right",
    [_clearing, lambda D: _right(D).tolist(), lambda D: _right(D).astype(bool), lambda D: reduce_boundary(D)[0]],
    ids=["clearing", "list", "bool", "sparse"],
)
def test_check_passes_right_answers_in_other_forms(right):
    # a list of lists (also [] for the empty matrix), booleans, a scipy.sparse matrix, clearing
    assert check.boundary_reduction(right, quiet=True).passed


def test_check_says_what_is_wrong():
    msg = check.boundary_reduction(lambda D: reduce_boundary(D)[1], quiet=True).message
    assert "expected shape" in msg
    msg = check.boundary_reduction(lambda D: np.array(D), quiet=True).message
    assert "what is wrong: the lowest one of column" in msg and "not reduced" in msg


@pytest.mark.parametrize("bad", [None, "D", b"D", 3, 2.5, np.int64(1)])
def test_reduce_boundary_refuses_none_with_a_type_error(bad):
    with pytest.raises(TypeError, match="D must"):
        reduce_boundary(bad)


def test_check_refuses_a_wrong_shape_on_the_empty_matrix():
    # the first case is the 0 x 0 matrix: [] is its reduction, an array of shape (1, 0) is not
    r = check.boundary_reduction(lambda D: np.ones((1, 0)) if D.size == 0 else _right(D), quiet=True)
    assert not r.passed and "expected shape (0, 0)" in r.message
