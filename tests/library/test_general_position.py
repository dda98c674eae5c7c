"""shapelab.general_position: exact ties against a float circle test on integer input,
and the triangulation's tie-break (a fan from the first ball)."""

import itertools

import numpy as np
import pytest

import shapelab as sl
from shapelab.general_position import cospherical_subsets


def cocircular_float(P):
    """Integer points: the 4x4 in-circle determinant is an integer, exact in float64."""
    out = []
    for s in itertools.combinations(range(len(P)), 4):
        M = np.array([[1.0, *P[i], P[i] @ P[i]] for i in s])
        if round(np.linalg.det(M)) == 0:
            out.append(s)
    return out


def test_grid():
    g = np.array([[i, j] for i in range(4) for j in range(3)], float)
    got = cospherical_subsets(sl.Balls(g, 0.6)).tolist()
    assert [tuple(s) for s in got] == cocircular_float(g)
    assert len(got) > 0


def test_generic_has_none():
    b = sl.Balls(np.random.default_rng(0).uniform(0, 1, (8, 2)), 0.3)
    assert cospherical_subsets(b).shape == (0, 4)


def test_weights_matter():
    sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    assert len(cospherical_subsets(sl.Balls(sq, [0.5, 0.5, 0.5, 0.5]))) == 1
    assert len(cospherical_subsets(sl.Balls(sq, [0.5, 0.5, 0.5, 0.25]))) == 0


def test_3d_cube():
    cube = np.array(list(itertools.product([0.0, 1.0], repeat=3)))
    assert len(cospherical_subsets(sl.Balls(cube, 0.5))) == 56  # every 5 corners lie on the circumsphere


@pytest.mark.parametrize("seed", range(5))
def test_tie_break_is_a_fan_from_the_first(seed):
    h = np.array([[5, 0], [3, 4], [-3, 4], [-5, 0], [-3, -4], [3, -4]], float)
    order = np.random.default_rng(seed).permutation(6)
    T = sl.regular_triangulation(sl.Balls(h[order], 1.0)).tolist()
    assert len(T) == 4 and all(0 in t for t in T)
    again = sl.regular_triangulation(sl.Balls(h[order], 1.0)).tolist()
    assert T == again
