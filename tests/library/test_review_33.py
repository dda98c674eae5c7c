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
    "z",
    [
        [[0, 0], [1e14, 0], [0, 1]],  # a right triangle 1e14 long: well conditioned
        [[0, 0], [1, 0], [0.5, 1e-6]],  # thin, not nearly flat
        [[0.0, 0.0, 0.0], [1e-150, 0.0, 0.0], [0.0, 3e-150, 1e-150]],  # tiny
    ],
)
def test_well_conditioned_simplices_agree_with_rationals(z):
    c, rho = sl.orthosphere(z, [0.0] * len(z))
    ce, rhoe = _exact_orthosphere(z, [0] * len(z))
    np.testing.assert_allclose(c, [float(x) for x in ce], rtol=1e-12)
    np.testing.assert_allclose(rho, float(rhoe), rtol=1e-12)


@pytest.mark.parametrize(
    "z",
    [
        [[0, 0], [10**7, 1], [2 * 10**7 + 1, 2]],  # integer, determinant -1: condition ~1e14
        [[0, 0], [1, 0], [0.5, 1e-14]],  # 1e-14 thin
        [[1000, 1000], [1000.1, 1000.2], [1000.3, 1000.6]],  # meant collinear; the floats are not
        # a float t: not exactly collinear; numpy's LU met an exact zero pivot here
        [
            [0.9775674511260357, -0.31055654665915255],
            [-0.3288239040579627, -0.7921467553588982],
            [-0.28628251390590065, -0.7764642289242195],
        ],
    ],
)
def test_nearly_flat_simplices_are_refused_for_what_they_are(z):
    with pytest.raises(ValueError, match="nearly flat") as err:
        sl.orthosphere(z, [0.683, 0.3916, 0.1873])
    assert "affinely dependent" not in str(err.value)


def test_nearly_flat_refusal_is_where_float64_loses_its_digits():
    """Every simplex orthosphere answers is within 1e-5 of the rationals (the threshold
    leaves about 6 digits); near-collinear triples z0 + t (z1 - z0), float t."""
    rng = np.random.default_rng(3)
    answered = 0
    for _ in range(300):
        z0, z1 = rng.normal(size=(2, 2))
        t = rng.uniform(-2, 2)
        z2 = z0 + t * (z1 - z0) + rng.choice([0.0, 1e-13, 1e-9, 1e-6, 1e-3]) * rng.normal(size=2)
        z, w = np.array([z0, z1, z2]), rng.uniform(0, 1, 3)
        try:
            c, rho = sl.orthosphere(z, w)
        except ValueError:
            continue
        answered += 1
        ce, rhoe = _exact_orthosphere(z, w)
        np.testing.assert_allclose(c, [float(x) for x in ce], rtol=1e-5, atol=1e-5 * np.abs(z).max())
    assert answered > 100


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
    # weights large beside tiny edges: the unit is the larger of the two (no w / s^2 overflow)
    c, rho = sl.orthosphere([[0.0, 0.0], [1e-160, 0.0]], [1.0, 1.0])
    assert float(rho) == -1.0  # exactly -1 + 2.5e-321; c to round-off of the sphere's size 1
    np.testing.assert_allclose(c, [5e-161, 0.0], atol=1e-16)
    c, rho = sl.orthosphere([[0.0], [1e-200]], [1e10, 1e10])
    assert float(rho) == -1e10
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
    assert sl.pockets(F, first)  # the first balls: pockets
    # one big ball far away enters first: the union is not empty, and the flask's pocket,
    # not yet lined, is a pocket by the definition (a class sealed later, still outside)
    B0 = sl.datasets.figure_23_2()[0]
    B = sl.Balls(np.vstack([B0.centers, [[36.0, 0.0]]]), np.sqrt(np.r_[B0.weights, 16.0]))
    G = sl.alpha_filtration(B)
    early = sl.pockets(G, -2.0)
    assert any(len(p.cell_ids) == 9 and p.closes_at == pytest.approx(0.5775) for p in early)
