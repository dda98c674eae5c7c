"""shapelab.peers: GUDHI's diagrams computed live, or the shipped values without GUDHI.

Oracles: GUDHI itself (the test extra installs it) for the shipped file; the
α-filtration's own diagrams (the Delaunay–Čech and α filtrations have the same
diagrams, Bauer and Edelsbrunner 2017); the voxels' tolerance side·√3.
"""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest

import shapelab as sl
from shapelab import peers
from shapelab.datasets import sample_shape

TORUS = ("torus", 400, 5)


@pytest.fixture
def no_gudhi(monkeypatch):
    """Make ``import gudhi`` fail, as on a student's machine."""
    monkeypatch.setitem(sys.modules, "gudhi", None)


def _torus():
    shape, n, seed = TORUS
    return sample_shape(shape, n, seed=seed)


def _same(a, b):
    for p in (0, 1, 2):
        assert a[p].shape == b[p].shape, p
        np.testing.assert_array_equal(a[p], b[p])


def test_shipped_values_equal_gudhi():
    pytest.importorskip("gudhi")
    X = _torus()
    live = peers.delaunay_cech_diagrams(X)
    assert live.computed and "computed now" in live.source
    vox = peers.voxel_diagrams(X, 0.05, 0.7)
    data = json.loads((peers.resources.files("shapelab") / "data" / peers.REFERENCE_FILE).read_text())
    import gudhi

    if data["gudhi_version"] != gudhi.__version__:
        pytest.skip(f"shipped values are GUDHI {data['gudhi_version']}'s, this is {gudhi.__version__}")
    kinds = {e["kind"]: e for e in data["entries"]}
    _same(live.diagrams, peers._as_diagrams(kinds["delaunay_cech"]["diagrams"]))
    _same(vox.diagrams, peers._as_diagrams(kinds["voxels"]["diagrams"]))


def test_without_gudhi_the_shipped_values_say_so(no_gudhi):
    X = _torus()
    cech = peers.delaunay_cech_diagrams(X)
    assert not cech.computed
    assert "shipped values" in cech.source and "GUDHI 3." in cech.source and "course.peer_values" in cech.source
    vox = peers.voxel_diagrams(X, 0.05, 0.7)
    assert not vox.computed and len(vox[0]) > 0


def test_shipped_delaunay_cech_equals_the_alpha_diagrams(no_gudhi):
    # independent of GUDHI's code: our α-filtration in the radius scale
    X = _torus()
    cech = peers.delaunay_cech_diagrams(X)
    pairs = sl.alpha_filtration(sl.Balls(X, 0.0)).persistence()
    for p in (0, 1, 2):
        ours = np.sqrt(np.maximum(np.asarray(pairs[p], dtype=float), 0.0))
        assert sl.bottleneck_distance(ours, cech[p]) < 1e-9


def test_shipped_voxels_are_within_their_tolerance(no_gudhi):
    X = _torus()
    vox = peers.voxel_diagrams(X, 0.05, 0.7)
    pairs = sl.alpha_filtration(sl.Balls(X, 0.0)).persistence()
    for p in (0, 1, 2):
        ours = np.sqrt(np.maximum(np.asarray(pairs[p], dtype=float), 0.0))
        assert sl.bottleneck_distance(ours, vox[p]) <= 0.05 * np.sqrt(3)


def test_other_input_without_gudhi_raises_and_says_how(no_gudhi):
    X = _torus() + 1e-6
    with pytest.raises(ModuleNotFoundError, match="pip install gudhi"):
        peers.delaunay_cech_diagrams(X)
    with pytest.raises(ModuleNotFoundError, match="voxel_diagrams"):
        peers.voxel_diagrams(_torus(), 0.1, 0.7)  # the shipped grid has side 0.05


@pytest.mark.parametrize("side, pad", [(0.0, 0.7), (-1.0, 0.7), (np.nan, 0.7), (0.05, -0.1)])
def test_bad_grid_parameters(side, pad):
    with pytest.raises(ValueError, match="side|pad"):
        peers.distance_grid(_torus(), side, pad)


def test_distance_grid_against_brute_force():
    X = np.random.default_rng(0).uniform(0, 1, (20, 3))
    G = peers.distance_grid(X, 0.25, 0.1)
    axes = [np.arange(lo - 0.1, hi + 0.1 + 0.25, 0.25) for lo, hi in zip(X.min(0), X.max(0))]
    assert G.shape == tuple(len(a) for a in axes)
    y = np.array([axes[0][1], axes[1][2], axes[2][0]])
    assert G[1, 2, 0] == pytest.approx(np.linalg.norm(X - y, axis=1).min(), abs=1e-12)


@pytest.mark.parametrize("n", [1, 5])
def test_one_point_has_one_component(n):
    # GUDHI leaves out the top dimension of a simplex tree unless asked: a single point (or
    # one point repeated) had no H0 pair at all (review of issue 32)
    pytest.importorskip("gudhi")
    cech = peers.delaunay_cech_diagrams(np.zeros((n, 3)))
    np.testing.assert_array_equal(cech[0], [[0.0, np.inf]])
    assert len(cech[1]) == len(cech[2]) == 0
