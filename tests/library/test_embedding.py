"""Classical MDS against its closed-form guarantees."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab import classical_mds


def _dist(X):
    return np.linalg.norm(X[:, None] - X[None], axis=2)


@settings(max_examples=30, deadline=None)
@given(st.integers(3, 12), st.integers(1, 3), st.integers(0, 10**6))
def test_euclidean_distances_are_reproduced_exactly(k, q, seed):
    """Distances between points of R^q are reproduced by the embedding in q dimensions
    (Gower 1966), and the spectrum has no negative part beyond round-off."""
    X = np.random.default_rng(seed).normal(size=(k, q)) * 3
    D = _dist(X)
    E = classical_mds(D, min(q, k))
    assert np.allclose(_dist(E.points), D, atol=1e-8 * max(D.max(), 1))
    assert E.eigenvalues.min() > -1e-8 * max(D.max(), 1) ** 2
    assert E.explained == pytest.approx(1.0)
    assert np.allclose(E.points.mean(axis=0), 0, atol=1e-9 * max(D.max(), 1))


def test_a_non_euclidean_distance_shows_negative_eigenvalues():
    # the path metric of a 4-cycle with one long chord is not Euclidean
    D = np.array([[0, 1, 2, 1], [1, 0, 1, 2], [2, 1, 0, 1], [1, 2, 1, 0]], float)
    D[0, 2] = D[2, 0] = 2.0
    D[1, 3] = D[3, 1] = 2.0  # the square with both diagonals 2 (> sqrt 2): not Euclidean
    E = classical_mds(D, 2)
    assert E.eigenvalues.min() < -1e-6
    assert np.abs(_dist(E.points) - D).max() > 0.1  # and no planar picture reproduces it


def test_deterministic_signs_and_bad_input():
    X = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 4.0], [1.0, 1.0]])
    a, b = classical_mds(_dist(X)), classical_mds(_dist(X))
    assert np.array_equal(a.points, b.points)
    assert np.all(a.points[np.argmax(np.abs(a.points), axis=0), [0, 1]] > 0)
    with pytest.raises(ValueError, match="square"):
        classical_mds(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="symmetric"):
        classical_mds([[0.0, 1.0], [2.0, 0.0]])
    with pytest.raises(ValueError, match="diagonal"):
        classical_mds([[1.0, 1.0], [1.0, 1.0]])
    with pytest.raises(ValueError, match="finite"):
        classical_mds([[0.0, np.inf], [np.inf, 0.0]])
    with pytest.raises(ValueError, match="dim"):
        classical_mds(_dist(X), 5)
    with pytest.raises(TypeError):
        classical_mds("D")
