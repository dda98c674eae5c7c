"""Review findings on issue 33's core (helper review, 2026-12-03): each test failed before.

Oracles: exact rationals (fractions) for the orthosphere and its flatness, the exact
triangulation for the fast path on inputs without a hull, and the definition of a
pocket (lined by the union at tau)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import shapelab as sl
from shapelab._engine.persistence import summary
from shapelab.cavities import merge_tree

from .._oracles import exact_orthosphere


def _exact_orthosphere(z, w):
    """c and rho in rationals, of the float64 input (tests._oracles)."""
    Z = [[Fraction(float(x)) for x in p] for p in z]
    return exact_orthosphere(Z, [Fraction(float(x)) for x in w], list(range(len(Z))))


@pytest.mark.parametrize(
    "z, rtol",
    [
        ([[0, 0], [1e14, 0], [0, 1]], 1e-12),  # a right triangle 1e14 long: not flat
        ([[0, 0], [10**7, 1], [2 * 10**7 + 1, 2]], 1e-8),  # integer, det -1: condition ~1e14
        ([[0, 0], [1, 0], [0.5, 1e-14]], 1e-12),  # thin, not flat
        # meant collinear, but the floats are not: condition ~1e12, a float64 solve keeps
        # about 4 digits (the exact path is the engine's, behind precision="exact")
        ([[1000, 1000], [1000.1, 1000.2], [1000.3, 1000.6]], 1e-3),
    ],
)
def test_thin_simplices_are_not_refused_and_agree_with_rationals(z, rtol):
    c, rho = sl.orthosphere(z, [0.0, 0.0, 0.0])
    ce, rhoe = _exact_orthosphere(z, [0, 0, 0])
    np.testing.assert_allclose(c, [float(x) for x in ce], rtol=rtol)
    np.testing.assert_allclose(rho, float(rhoe), rtol=rtol)


def test_flatness_is_exact_on_random_integer_simplices():
    rng = np.random.default_rng(7)
    for d in (2, 3):
        for j in range(1, d + 1):
            z = rng.integers(-3, 4, size=(400, j + 1, d)).astype(float)
            for s in range(400):
                A = [[Fraction(int(x)) for x in (z[s, i] - z[s, 0])] for i in range(1, j + 1)]
                M = np.array(A, dtype=object)
                flat = np.linalg.matrix_rank(M.astype(float)) < j  # small integers: rank exact
                if flat:
                    with pytest.raises(ValueError, match="affinely dependent"):
                        sl.orthosphere(z[s], np.zeros(j + 1))
                else:
                    c, rho = sl.orthosphere(z[s], np.zeros(j + 1))
                    ce, rhoe = _exact_orthosphere(z[s], np.zeros(j + 1))
                    np.testing.assert_allclose(c, [float(x) for x in ce], rtol=1e-9, atol=1e-9)


def test_extreme_scales_neither_underflow_nor_overflow_silently():
    for s in (4e-170, 4e-300, 4e150):
        c, rho = sl.orthosphere([[0.0, 0.0], [s, 0.0]], [0.0, 0.0])
        assert c.tolist() == [s / 2, 0.0] and float(rho) == (s / 2) ** 2
    with pytest.raises(ValueError, match="beyond float64"):
        sl.orthosphere([[0.0, 0.0], [4e160, 0.0]], [0.0, 0.0])  # rho = 4e320


@pytest.mark.parametrize(
    "balls",
    [
        sl.Balls([[0.0, 0.0]], 1.0),
        sl.Balls([[0.0, 0.0, 0.0]], 1.0),
        sl.Balls([[0.0, 0.0], [1.0, 0.0]], 1.0),
        sl.Balls([[0.0, 0.0], [1.0, 0.0], [3.0, 0.0]], [1.0, 0.5, 1.0]),
        sl.Balls([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], 1.0),
        sl.datasets.ring(8, dim=3),  # planar
    ],
    ids=["1 ball 2D", "1 ball 3D", "2 balls 2D", "collinear 2D", "3 balls 3D", "planar ring 3D"],
)
def test_fast_path_on_centres_without_a_hull_is_the_exact_one(balls):
    exact = sl.regular_triangulation(balls)
    assert np.array_equal(sl.regular_triangulation(balls, precision="fast"), exact)
    Fe, Ff = sl.alpha_filtration(balls), sl.alpha_filtration(balls, precision="fast")
    assert Fe.dimension == Ff.dimension
    for k in range(Fe.dimension + 1):  # the same simplices, times to 1e-12 (ties may reorder)
        se, sf = np.asarray(Fe.simplices(k)), np.asarray(Ff.simplices(k))
        oe, of = np.lexsort(se.T[::-1]), np.lexsort(sf.T[::-1])
        assert np.array_equal(se[oe], sf[of])
        np.testing.assert_allclose(np.asarray(Ff.values(k))[of], np.asarray(Fe.values(k))[oe], rtol=1e-12)
    De, Df = sl.power_diagram(balls), sl.power_diagram(balls, precision="fast")
    assert np.array_equal(De.adjacency, Df.adjacency) and np.allclose(De.vertices, Df.vertices)


def test_what_is_kept_on_the_filtration_is_read_only():
    F = sl.alpha_filtration(sl.datasets.figure_23_2()[0])
    before = sl.pockets(F)
    T, S = merge_tree(F), summary(F)
    arrays = [v for v in vars(T).values() if isinstance(v, np.ndarray)]
    arrays += [S.neg_edges, S.pos_facets, *S.cell_dual, *S.values]
    assert arrays and all(not a.flags.writeable for a in arrays)
    with pytest.raises(ValueError, match="read-only"):
        T.order[:] = 0
    assert repr(sl.pockets(F)) == repr(before)


def test_no_growth_pocket_before_the_first_ball():
    F = sl.alpha_filtration(sl.datasets.figure_23_2()[0])
    first = float(np.min(F.values(0)))
    for tau in (-np.inf, -1e308, first - 1e-9):
        assert sl.pockets(F, tau) == ()
    assert all(p.lining.size > 0 for p in sl.pockets(F, first))
