"""shapelab.oracles.voxel_complement: the bounded components of the complement of a
union of balls, counted on voxels, against Alexander duality (β2 of the α-complex,
lesson 07) and, for β1, against GUDHI's cubical homology of the voxelized complement."""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import Balls, alpha_filtration, datasets, voids
from shapelab.oracles import voxel_complement


@pytest.fixture(scope="module")
def c60():
    return datasets.fullerene_c60()


def test_one_ball_has_no_void_and_its_volume_is_the_balls():
    b = Balls(np.zeros((1, 3)), np.array([1.0]))
    labels, axes = voxel_complement(b, tau=0.0, spacing=0.05)
    assert labels.max() == 1
    assert np.count_nonzero(labels == 0) * 0.05**3 == pytest.approx(4 / 3 * np.pi, rel=0.01)
    assert all(len(a) == n for a, n in zip(axes, labels.shape))


@pytest.mark.parametrize("spacing", [0.2, 0.1])
def test_c60_voids_are_beta2_away_from_events(c60, spacing):
    # C60's events: -2.89, -2.4, -1.47, -0.93 and 9.1455; every tau below is >= 0.27 from them
    F = alpha_filtration(c60)
    for tau in (-2.0, -1.2, 0.0, 4.0, 8.0, 10.0):
        labels, _ = voxel_complement(c60, tau=tau, spacing=spacing)
        assert labels.max() - 1 == F.betti(tau)[2] == len(voids(F, tau))


def test_c60_void_volume_matches_the_exact_free_space(c60):
    (void,) = voids(alpha_filtration(c60), 0.0)
    labels, _ = voxel_complement(c60, tau=0.0, spacing=0.1)
    assert np.count_nonzero(labels == 2) * 0.1**3 == pytest.approx(void.volume, rel=0.02)


def test_two_cages_count_two_voids_then_one():
    c, small = datasets.fullerene_c60(), datasets.fullerene_c60(atom_radius=0.8)
    two = Balls(np.vstack([c.centers, small.centers + [16.0, 0.0, 0.0]]), np.r_[c.radii, small.radii])
    counts = [int(voxel_complement(two, tau=t, spacing=0.2)[0].max()) - 1 for t in (-1.8, 0.0, 2.5, 9.6, 12.0)]
    assert counts == [0, 1, 2, 1, 0]


@pytest.mark.parametrize("tau", [-2.0, -1.2, 0.0])
def test_beta1_of_the_voxel_complement_is_beta1_of_K(c60, tau):
    """Alexander duality in degree 1: β1(R³ \\ U) = β1(U) = β1(K).  The complement's
    voxels as closed cubes (26-connected, as voxel_complement labels them) in GUDHI's
    cubical complex; inside the grid's box the complement has β2 = 1 (the box's shell)."""
    gudhi = pytest.importorskip("gudhi")
    labels, _ = voxel_complement(c60, tau=tau, spacing=0.15)
    cc = gudhi.CubicalComplex(top_dimensional_cells=(labels == 0).astype(float))
    cc.compute_persistence()
    b0, b1, b2 = cc.persistent_betti_numbers(0.0, 0.0)[:3]
    beta = alpha_filtration(c60).betti(tau)
    assert (b0, b1, b2) == (1 + beta[2], beta[1], beta[0])


def test_refuses_2d_balls_and_bad_spacing(c60):
    with pytest.raises(ValueError, match="3D"):
        voxel_complement(datasets.ring(6), tau=0.0)
    with pytest.raises(ValueError, match="spacing"):
        voxel_complement(c60, spacing=-0.1)
    with pytest.raises(ValueError, match="spacing"):
        voxel_complement(c60, spacing=1e-3)


def test_stamped_union_is_the_brute_force_union_on_the_returned_grid():
    """The per-ball boxes miss no voxel and add none: on random balls (some empty at τ,
    some far apart, three spacings) the union's voxels are exactly those whose centre is
    in a grown ball, computed over the whole grid, the union never touches the grid's
    border, and the labels count the components of the complement as a full flood fill
    does."""
    from scipy import ndimage

    rng = np.random.default_rng(5)
    for _ in range(40):
        n = int(rng.integers(1, 8))
        centers = rng.normal(size=(n, 3)) * rng.choice([0.5, 2.0, 10.0])
        radii = rng.uniform(0.0, 2.0, n)
        tau, h = float(rng.uniform(-2.0, 2.0)), float(rng.choice([0.13, 0.3]))
        labels, axes = voxel_complement(Balls(centers, radii), tau=tau, spacing=h)
        if not np.any(radii**2 + tau >= 0):
            assert labels.shape == (1, 1, 1) and labels.max() == 1
            continue
        X, Y, Z = np.meshgrid(*axes, indexing="ij")
        inside = np.zeros(X.shape, dtype=bool)
        for c, w in zip(centers, radii**2 + tau):
            inside |= (X - c[0]) ** 2 + (Y - c[1]) ** 2 + (Z - c[2]) ** 2 <= w
        assert np.array_equal(labels == 0, inside)
        for face in (inside[0], inside[-1], inside[:, 0], inside[:, -1], inside[:, :, 0], inside[:, :, -1]):
            assert not face.any()
        assert ndimage.label(~inside, structure=np.ones((3, 3, 3)))[1] == labels.max()
