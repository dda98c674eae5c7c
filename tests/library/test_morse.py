"""shapelab.morse: the critical points of the power distance, against the definition
(all subsets, no triangulation), the Euler characteristic, persistence and a grid."""

import numpy as np
import pytest

import shapelab as sl
from shapelab.morse import critical_points_by_subsets, power_critical_points


def random_balls(seed, n=10, dim=2):
    rng = np.random.default_rng(seed)
    return sl.Balls(rng.uniform(0, 4, (n, dim)), rng.uniform(0.2, 0.9, n))


@pytest.mark.parametrize("seed", range(6))
def test_filtration_equals_definition(seed):
    b = random_balls(seed)
    a, c = power_critical_points(b), critical_points_by_subsets(b)
    assert a.simplices == c.simplices
    np.testing.assert_allclose(a.values, c.values, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(a.positions, c.positions, rtol=1e-12, atol=1e-12)


def test_three_dimensions():
    b = random_balls(3, n=8, dim=3)
    assert power_critical_points(b).simplices == critical_points_by_subsets(b).simplices


@pytest.mark.parametrize("seed", range(4))
def test_euler_and_persistence(seed):
    b = random_balls(seed, n=14)
    F = sl.alpha_filtration(b)
    cp = power_critical_points(F)
    assert cp.euler_characteristic == 1
    for k, D in F.persistence().items():
        for birth, death in np.asarray(D):  # every birth and finite death is a critical value of the right index
            assert np.isclose(cp.values[cp.index == k], birth, rtol=0, atol=1e-12).any()
            if np.isfinite(death):
                assert np.isclose(cp.values[cp.index == k + 1], death, rtol=0, atol=1e-12).any()


def test_values_are_the_power_distance_at_the_points():
    b = random_balls(1)
    cp = power_critical_points(b)
    f = np.array([sl.power_distance(y, b).min() for y in cp.positions])
    np.testing.assert_allclose(f, cp.values, atol=1e-12)


def test_maximum_is_a_grid_maximum():
    # three disks with an acute triangle of centres: the one maximum of f inside the triangle
    b = sl.Balls([[0.0, 0.0], [4.0, 0.0], [1.5, 3.0]], [1.0, 1.3, 0.8])
    cp = power_critical_points(b)
    assert cp.counts == (3, 3, 1)
    s = np.linspace(0, 1, 301)
    u, v = np.meshgrid(s, s)
    keep = (u + v <= 1).ravel()
    P = (
        b.centers[0]
        + np.outer(u.ravel(), b.centers[1] - b.centers[0])
        + np.outer(v.ravel(), b.centers[2] - b.centers[0])
    )[keep]
    f = np.min(((P[:, None, :] - b.centers[None]) ** 2).sum(-1) - b.radii**2, axis=1)
    top = cp.values[cp.index == 2][0]
    assert top - 0.05 < f.max() <= top + 1e-12  # f has a kink at its maximum: grid error ~ slope × spacing


def test_obtuse_triangle_has_no_maximum():
    b = sl.Balls([[0.0, 0.0], [4.0, 0.0], [2.0, 0.5]], 0.5)
    cp = power_critical_points(b)
    assert cp.counts == (3, 2, 0)
    assert cp.counts == critical_points_by_subsets(b).counts


def test_hidden_ball_is_no_minimum():
    b = sl.Balls([[0.0, 0.0], [0.1, 0.0], [3.0, 0.0]], [2.0, 0.2, 1.0])  # ball 1 lies inside ball 0
    assert all(1 not in s for s in power_critical_points(b).simplices)
    assert power_critical_points(b).simplices == critical_points_by_subsets(b).simplices


def test_degenerate_cage_has_no_critical_tetrahedron():
    # lesson 06: the void of C60 dies at the centre, where 12 balls tie exactly
    cp = power_critical_points(sl.datasets.fullerene_c60())
    assert cp.counts[3] == 0


def test_rejects_non_balls():
    with pytest.raises(TypeError):
        critical_points_by_subsets(np.zeros((3, 2)))
