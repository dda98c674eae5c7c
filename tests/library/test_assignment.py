"""shapelab.assignment: diagram distances as assignment problems, against the library's
exact distances and a brute force over all matchings."""

import itertools

import numpy as np
import pytest

import shapelab as sl
from shapelab.assignment import assignment_distance, augmented_cost_matrix


def brute(A, B, p):
    """Minimum over all partial injections of A into B, the rest to the diagonal."""
    A, B = np.asarray(A, float).reshape(-1, 2), np.asarray(B, float).reshape(-1, 2)
    n, m = len(A), len(B)
    diag = lambda P: (P[:, 1] - P[:, 0]) / 2
    best = np.inf
    for k in range(min(n, m) + 1):
        for rows in itertools.combinations(range(n), k):
            for cols in itertools.permutations(range(m), k):
                c = [np.abs(A[i] - B[j]).max() for i, j in zip(rows, cols)]
                c += list(diag(A[[i for i in range(n) if i not in rows]]))
                c += list(diag(B[[j for j in range(m) if j not in cols]]))
                c = np.array(c)
                v = c.max(initial=0.0) if np.isinf(p) else (c**p).sum() ** (1 / p)
                best = min(best, v)
    return best


def diagram(rng, n):
    return np.sort(rng.uniform(0, 5, (n, 2)), axis=1)


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("p", [1, 2, np.inf])
def test_brute_force(seed, p):
    rng = np.random.default_rng(seed)
    A, B = diagram(rng, rng.integers(0, 4)), diagram(rng, rng.integers(0, 4))
    assert assignment_distance(A, B, p) == pytest.approx(brute(A, B, p), abs=1e-12)


@pytest.mark.parametrize("seed", range(5))
def test_library(seed):
    rng = np.random.default_rng(100 + seed)
    A, B = diagram(rng, 12), diagram(rng, 9)
    assert assignment_distance(A, B, 1) == pytest.approx(sl.wasserstein_distance(A, B, p=1), rel=1e-12)
    assert assignment_distance(A, B, 2, internal_p=2) == pytest.approx(
        sl.wasserstein_distance(A, B, p=2, internal_p=2), rel=1e-12
    )
    assert assignment_distance(A, B, np.inf) == pytest.approx(sl.bottleneck_distance(A, B), rel=1e-12)


def test_matrix_shape_and_blocks():
    C = augmented_cost_matrix([[0.0, 2.0], [1.0, 5.0]], [[0.0, 3.0]])
    assert C.shape == (3, 3)
    assert C[0, 1] == 1.0 and C[1, 2] == 2.0 and np.isinf(C[0, 2]) and np.isinf(C[1, 1])
    assert C[2, 0] == 1.5 and C[2, 1] == 0.0


def test_empty_and_infinite():
    assert assignment_distance([], [], 1) == 0.0
    with pytest.raises(ValueError):
        assignment_distance([[0.0, np.inf]], [], 1)
    with pytest.raises(ValueError):
        assignment_distance([[0.0, 1.0]], [], 0.5)
