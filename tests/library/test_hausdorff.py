"""Hausdorff distance (notes §23.2): exact against brute force and scipy, witnesses,
symmetry, matching under translation, bad input.

Oracles: an independent brute force (``np.sum`` over a full distance tensor),
scipy's ``directed_hausdorff`` and ``cKDTree``, grid search over translations,
closed forms (translated copies, one-point sets).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from scipy.spatial.distance import directed_hausdorff as scipy_dh

import shapelab
from shapelab.hausdorff import (
    DirectedHausdorff,
    directed_hausdorff,
    hausdorff,
    hausdorff_early_break,
    hausdorff_kdtree,
    hausdorff_pair,
    timings,
)
from shapelab.matching import TranslationMatch, hausdorff_under_translation, reference_point

METHODS = ("auto", "brute", "pruned", "grid")


def brute_directed(A, B):
    """max_i min_j |A_i - B_j| by a full tensor (coordinates summed in order)."""
    D = np.sqrt(((A[:, None, :] - B[None, :, :]) ** 2).sum(axis=-1))
    return D.min(axis=1).max()


def brute_nn(a, B):
    return np.sqrt(((B - a) ** 2).sum(axis=-1)).min()


def sphere(n, rng, noise=0.01, center=(0.0, 0.0, 0.0)):
    x = rng.standard_normal((n, 3))
    x /= np.linalg.norm(x, axis=1, keepdims=True)
    return x + noise * rng.standard_normal((n, 3)) + np.asarray(center)


def assert_witness(A, B, r):
    assert isinstance(r, DirectedHausdorff)
    assert 0 <= r.i < len(A) and 0 <= r.j < len(B)
    # distance == |A[i] - B[j]| and B[j] is a nearest point of B to A[i]
    assert np.sqrt(((A[r.i] - B[r.j]) ** 2).sum()) == r.distance
    assert brute_nn(A[r.i], B) == r.distance


# ----------------------------------------------------------------- small sets
def point_sets(max_n=25):
    dims = st.integers(1, 5)

    def pair(d):
        elems = st.one_of(
            st.floats(-10, 10, allow_nan=False, allow_infinity=False, width=64),
            st.integers(-3, 3).map(float),  # grids: ties and duplicates
        )
        a = hnp.arrays(np.float64, st.tuples(st.integers(1, max_n), st.just(d)), elements=elems)
        b = hnp.arrays(np.float64, st.tuples(st.integers(1, max_n), st.just(d)), elements=elems)
        return st.tuples(a, b)

    return dims.flatmap(pair)


@settings(max_examples=80, deadline=None)
@given(point_sets(), st.sampled_from(METHODS))
def test_directed_equals_brute_force_with_valid_witness(AB, method):
    A, B = AB
    r = directed_hausdorff(A, B, method=method)
    assert r.distance == brute_directed(A, B)
    assert_witness(A, B, r)


@settings(max_examples=60, deadline=None)
@given(point_sets(max_n=60), st.sampled_from(["tree", "subset", "probe"]), st.integers(0, 3))
def test_every_stage_of_the_pruned_algorithm_is_exact(AB, stage, seed):
    """Force each path of the pruned algorithm on small inputs (where ``auto``
    would use brute force), with and without a lower bound from the other side."""
    from shapelab._engine import hausdorff as H

    A, B = AB
    src, dst = H._prepare(A, B)
    best = H._directed_pruned(src, dst, H._Best(), seed=seed, stage=stage)
    assert np.sqrt(best.d2) == brute_directed(A, B)
    assert_witness(A, B, DirectedHausdorff(float(np.sqrt(best.d2)), best.i, best.j))
    floor = brute_directed(B, A) ** 2
    best = H._directed_pruned(src, dst, H._Best(floor), seed=seed, stage=stage)
    assert np.sqrt(max(best.d2, floor)) == max(brute_directed(A, B), np.sqrt(floor))


@settings(max_examples=80, deadline=None)
@given(point_sets(max_n=60), st.integers(0, 6))
def test_coarse_to_fine_stage_is_exact_with_and_without_a_floor(AB, cells_log2):
    """Force the grid levels on small inputs (``auto`` would use brute force), with
    grids from 1 to 64 cells, and with a lower bound from the other direction."""
    from shapelab._engine import hausdorff as H

    A, B = AB
    cells = 1 << cells_log2
    old = H._GRID_CELLS
    try:
        H._GRID_CELLS = cells
        best = H._directed_grid(A, B, H._Best(), H._Grid(A, cells), H._Grid(B, cells), force=True)
        assert np.sqrt(best.d2) == brute_directed(A, B)
        assert_witness(A, B, DirectedHausdorff(float(np.sqrt(best.d2)), best.i, best.j))
        floor = brute_directed(B, A) ** 2
        best = H._directed_grid(A, B, H._Best(floor), force=True)
        assert np.sqrt(max(best.d2, floor)) == max(brute_directed(A, B), np.sqrt(floor))
        if best.i >= 0:
            assert_witness(A, B, DirectedHausdorff(float(np.sqrt(best.d2)), best.i, best.j))
    finally:
        H._GRID_CELLS = old


@pytest.mark.parametrize("offset, scale", [(0.0, 1.0), (1e6, 1.0), (1e6, 1e-6), (-3e5, 1e3), (1e12, 1.0)])
def test_grid_boxes_contain_their_points(offset, scale):
    """The cell boxes are rigorous (widened for round-off) even far from the origin."""
    from shapelab._engine import hausdorff as H

    rng = np.random.default_rng(8)
    P = offset + scale * rng.standard_normal((5000, 3))
    P[:7] = P[7]  # duplicates
    for cells in (1, 7, 2048):
        g = H._Grid(P, cells)
        c, h = g.center[g.cell], g.half[g.cell]
        assert np.all(np.abs(P - c) <= h)
        assert np.all(g.cell[g.rep] == np.arange(g.center.shape[0]))


@settings(max_examples=50, deadline=None)
@given(point_sets(), st.sampled_from(METHODS))
def test_symmetric_distance_is_max_of_directed_and_symmetric(AB, method):
    A, B = AB
    h = hausdorff(A, B, method=method)
    assert h == max(brute_directed(A, B), brute_directed(B, A))
    assert h == hausdorff(B, A, method=method)
    ab, ba = hausdorff_pair(A, B, method=method)
    assert ab.distance == brute_directed(A, B) and ba.distance == brute_directed(B, A)
    assert_witness(A, B, ab)
    assert_witness(B, A, ba)


@settings(max_examples=40, deadline=None)
@given(
    hnp.arrays(
        np.float64,
        st.tuples(st.integers(1, 40), st.integers(1, 4)),
        elements=st.floats(-5, 5, allow_nan=False, width=64),
    ),
    st.randoms(use_true_random=False),
)
def test_identical_sets_and_duplicates_give_zero(A, rnd):
    perm = list(range(len(A)))
    rnd.shuffle(perm)
    B = np.vstack([A[perm], A[:3]])  # a permutation with duplicates: the same set
    for method in METHODS:
        assert hausdorff(A, B, method=method) == 0.0
        r = directed_hausdorff(A, B, method=method)
        assert r.distance == 0.0
        assert_witness(A, B, r)


def test_single_points_and_one_dimension():
    assert hausdorff([[0.0, 0.0]], [[3.0, 4.0]]) == 5.0
    assert directed_hausdorff([[0.0, 0.0]], [[3.0, 4.0]]) == (5.0, 0, 0)
    # 1D: A = {0, 1}, B = {0, 3}: h(A,B) = 1, h(B,A) = 2
    assert directed_hausdorff([[0.0], [1.0]], [[0.0], [3.0]]).distance == 1.0
    assert hausdorff([[0.0], [1.0]], [[0.0], [3.0]]) == 2.0


def test_not_symmetric_when_one_set_contains_the_other():
    A = np.array([[0.0, 0.0], [1.0, 0.0]])
    B = np.array([[0.0, 0.0], [1.0, 0.0], [4.0, 4.0]])
    assert directed_hausdorff(A, B).distance == 0.0
    assert directed_hausdorff(B, A) == (5.0, 2, 1)


@pytest.mark.parametrize("offset, scale", [(1e6, 1.0), (1e6, 1e-6), (0.0, 1e-6), (-3e5, 1e3)])
def test_huge_offsets_and_tiny_scales(offset, scale):
    rng = np.random.default_rng(7)
    A = offset + scale * rng.standard_normal((400, 3))
    B = offset + scale * (rng.standard_normal((500, 3)) + [0.5, 0, 0])
    for method in ("brute", "pruned", "grid"):
        r = directed_hausdorff(A, B, method=method)
        assert r.distance == brute_directed(A, B)
        assert_witness(A, B, r)
        assert hausdorff(A, B, method=method) == max(r.distance, brute_directed(B, A))


# ----------------------------------------------------------------- large sets
@pytest.mark.parametrize("shift", [0.0, 0.3, 3.0])
def test_pruned_equals_scipy_on_sphere_samples(shift):
    """Overlapping (k-d tree stage), touching, and far apart (probe + subset stages)."""
    rng = np.random.default_rng(11)
    A = sphere(12000, rng)
    B = sphere(9000, rng, center=(shift, 0, 0))
    for X, Y in ((A, B), (B, A)):
        r = directed_hausdorff(X, Y)
        ref = scipy_dh(X, Y)
        assert r.distance == ref[0]
        assert_witness(X, Y, r)
    h = hausdorff(A, B)
    assert h == max(scipy_dh(A, B)[0], scipy_dh(B, A)[0])
    assert h == pytest.approx(hausdorff_kdtree(A, B), rel=1e-14)


@pytest.mark.parametrize(
    "d, shift, alone", [(3, 3.0, True), (3, 1.2, True), (2, 2.5, True), (1, 4.0, True), (4, 3.0, False)]
)
def test_apart_sets_are_solved_by_the_grid_levels_alone(d, shift, alone, monkeypatch):
    """Far apart (or touching) the coarse-to-fine stage finishes without the k-d
    tree fallback in d <= 3, and agrees with scipy to the last bit, witness
    included.  (In 4D the grid is too coarse and some level hands over.)"""
    from shapelab._engine import hausdorff as H

    def no_fallback(*args, **kwargs):
        raise AssertionError("fell back to the pruned algorithm")

    if alone:
        monkeypatch.setattr(H, "_directed_pruned", no_fallback)
    rng = np.random.default_rng(30 + d)
    A = rng.standard_normal((30000, d))
    A /= np.linalg.norm(A, axis=1, keepdims=True)
    A += 0.01 * rng.standard_normal(A.shape)
    B = rng.standard_normal((20000, d))
    B /= np.linalg.norm(B, axis=1, keepdims=True)
    B[:, 0] += shift
    for X, Y in ((A, B), (B, A)):
        r = directed_hausdorff(X, Y)
        assert r.distance == scipy_dh(X, Y)[0]
        assert_witness(X, Y, r)
    assert hausdorff(A, B) == max(scipy_dh(A, B)[0], scipy_dh(B, A)[0])


def test_apart_sets_do_not_import_scipy():
    """The first call pays no ``import scipy.spatial`` when no tree is needed."""
    import subprocess
    import sys

    code = (
        "import sys, numpy as np\n"
        "from shapelab import hausdorff\nfrom shapelab.datasets import noisy_sphere\n"
        "A = noisy_sphere(40000, seed=1); B = noisy_sphere(40000, seed=2, center=(3.0, 0, 0))\n"
        "h = hausdorff(A, B)\n"
        "print(h, 'scipy.spatial' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    h, imported = out.stdout.split()
    assert imported == "False"
    A = shapelab.datasets.noisy_sphere(40000, seed=1)
    B = shapelab.datasets.noisy_sphere(40000, seed=2, center=(3.0, 0, 0))
    assert float(h) == max(scipy_dh(A, B)[0], scipy_dh(B, A)[0])


def test_overlapping_sets_fall_back_to_the_tree_with_shared_clouds(monkeypatch):
    """Overlapping at the scale of the cells, the first grid level gives up and both
    directions run the pruned algorithm on the same prepared clouds (one pair of trees)."""
    from shapelab._engine import hausdorff as H

    calls = []
    real = H._prepare

    def spy(A, B):
        calls.append((A.shape[0], B.shape[0]))
        return real(A, B)

    monkeypatch.setattr(H, "_prepare", spy)
    rng = np.random.default_rng(14)
    A, B = sphere(20000, rng), sphere(15000, rng)
    assert hausdorff(A, B) == max(scipy_dh(A, B)[0], scipy_dh(B, A)[0])
    assert calls == [(20000, 15000)]


def test_pruned_on_a_small_cluster_against_a_large_set():
    rng = np.random.default_rng(12)
    A = 0.05 * rng.standard_normal((30000, 2)) + [0.4, 0.1]
    B = rng.uniform(-1, 1, (25000, 2))
    for X, Y in ((A, B), (B, A)):
        r = directed_hausdorff(X, Y)
        assert r.distance == scipy_dh(X, Y)[0]
        assert_witness(X, Y, r)


def test_pruned_on_grids_with_ties():
    g = np.arange(60.0)
    A = np.array(np.meshgrid(g, g)).reshape(2, -1).T  # 3600 grid points
    B = A[(A[:, 0] + A[:, 1]) % 3 != 0] + 0.5  # shifted, thinned
    for X, Y in ((A, B), (B, A)):
        r = directed_hausdorff(X, Y, method="pruned")
        assert r.distance == directed_hausdorff(X, Y, method="brute").distance
        assert_witness(X, Y, r)


def test_comparison_algorithms_agree():
    rng = np.random.default_rng(13)
    A, B = sphere(2000, rng), sphere(1500, rng, center=(0.5, 0, 0))
    t = timings(A, B)
    assert t.agree and set(t.seconds) == {"brute force", "k-d tree (scipy)", "early break (scipy)", "shapelab"}
    assert all(s > 0 for s in t.seconds.values())
    assert hausdorff_early_break(A, B) == hausdorff(A, B)


def test_timings_warm_up_is_not_timed(monkeypatch):
    # a first call that pays for an import (0.26 s against 5 ms for the k-d tree in
    # lesson 14) must not be the time reported: one untimed call, then the best of
    # ``repeat`` timed ones
    import shapelab.distance as dist

    calls = {"kd": 0, "eb": 0}
    clock = iter(range(10**6))

    def kd(A, B):
        calls["kd"] += 1
        return 1.0

    def eb(A, B):
        calls["eb"] += 1
        return 1.0

    def fake_clock():  # every timed call takes 1 "second"
        return float(next(clock))

    monkeypatch.setattr(dist, "hausdorff_kdtree", kd)
    monkeypatch.setattr(dist, "hausdorff_early_break", eb)
    monkeypatch.setattr(dist, "hausdorff", lambda A, B, method=None: 1.0)
    import time

    monkeypatch.setattr(time, "perf_counter", fake_clock)
    t = dist.timings([[0.0, 0.0]], [[1.0, 0.0]], repeat=2, brute=False)
    assert calls == {"kd": 3, "eb": 3}  # one warm-up and two timed runs each
    assert t.seconds["k-d tree (scipy)"] == 1.0
    with pytest.raises(ValueError, match="repeat"):
        dist.timings([[0.0, 0.0]], [[1.0, 0.0]], repeat=0)


def test_public_names():
    # the submodule shadows the lazily exported function; both must compute H
    A, B = [[0.0, 0.0]], [[3.0, 4.0]]
    assert shapelab.hausdorff(A, B) == hausdorff(A, B) == 5.0
    assert shapelab.directed_hausdorff is directed_hausdorff
    assert shapelab.hausdorff_under_translation is hausdorff_under_translation
    assert shapelab.TranslationMatch is TranslationMatch


# ----------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "A, B, words",
    [
        (np.zeros((0, 2)), np.zeros((3, 2)), "A must hold at least 1"),
        (np.zeros((3, 2)), np.zeros((0, 2)), "B must hold at least 1"),
        (np.zeros((3, 2)), np.zeros((3, 3)), "same dimension"),
        ([[0.0, np.nan]], [[0.0, 0.0]], "A must be finite"),
        ([[0.0, 0.0]], [[np.inf, 0.0]], "B must be finite"),
        ([0.0, 1.0], [[0.0, 0.0]], "A must be a 2-D array"),
    ],
)
def test_bad_input_names_the_argument(A, B, words):
    for fn in (hausdorff, directed_hausdorff, hausdorff_under_translation):
        with pytest.raises(ValueError, match=words):
            fn(A, B)


def test_bad_method_and_types():
    with pytest.raises(ValueError, match="method"):
        hausdorff([[0.0]], [[1.0]], method="fast")
    with pytest.raises(TypeError, match="A must"):
        hausdorff("points", [[1.0]])
    with pytest.raises(ValueError, match="tol"):
        hausdorff_under_translation([[0.0]], [[1.0]], tol=0)
    with pytest.raises(ValueError, match="kind"):
        reference_point([[0.0]], kind="median")


# ----------------------------------------------------------------- translation
def test_translated_copy_is_matched_exactly():
    rng = np.random.default_rng(3)
    A = rng.standard_normal((40, 2))
    t0 = np.array([2.5, -1.25])
    B = A[rng.permutation(40)] - t0  # B + t0 == A as sets
    m = hausdorff_under_translation(A, B)
    assert m.optimal_distance <= 1e-12 and m.lower_bound == 0.0
    np.testing.assert_allclose(m.optimal_translation, t0, atol=1e-12)
    np.testing.assert_allclose(m.centroid_translation, t0, atol=1e-12)
    assert m.centroid_distance <= 1e-12 and m.converged  # ratio of round-offs: meaningless


@pytest.mark.parametrize("d", [1, 2])
def test_optimum_is_certified_against_a_grid_search(d):
    rng = np.random.default_rng(20 + d)
    A = rng.standard_normal((25, d))
    B = rng.standard_normal((18, d)) * 0.8 + 2.0
    m = hausdorff_under_translation(A, B, tol=1e-4)
    # independent oracle: H on a grid of translations around the optimum
    h = 0.02
    axes = [np.arange(-1.5, 1.5 + h / 2, h) + m.optimal_translation[k] for k in range(d)]
    grid = np.array(np.meshgrid(*axes, indexing="ij")).reshape(d, -1).T
    vals = np.array([max(brute_directed(A, B + t), brute_directed(B + t, A)) for t in grid])
    assert m.converged
    assert m.lower_bound <= vals.min() + 1e-12  # a true lower bound
    assert m.optimal_distance <= vals.min() + 1e-12  # at least as good as the grid
    assert m.optimal_distance - m.lower_bound <= 1e-4 * m.optimal_distance + 1e-12
    assert m.optimal_distance == max(
        brute_directed(A, B + m.optimal_translation), brute_directed(B + m.optimal_translation, A)
    )


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 10_000), st.integers(1, 3))
def test_reference_points_are_never_better_than_the_optimum_and_bbox_is_bounded(seed, d):
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((rng.integers(1, 30), d))
    B = rng.standard_normal((rng.integers(1, 30), d)) * rng.uniform(0.5, 2) + rng.normal(size=d)
    m = hausdorff_under_translation(A, B, max_evaluations=3000)
    assert m.optimal_distance <= m.centroid_distance + 1e-12
    assert m.optimal_distance <= m.bbox_distance + 1e-12
    assert 0.0 <= m.lower_bound <= m.optimal_distance
    assert m.bound == 1 + np.sqrt(d)
    # proven: bbox alignment <= (1 + sqrt d) * true optimum <= (1 + sqrt d) * found optimum
    assert m.bbox_distance <= m.bound * m.optimal_distance * (1 + 1e-12) + 1e-12
    assert m.centroid_distance == hausdorff(A, B + (A.mean(0) - B.mean(0)))


def test_centroid_alignment_has_no_constant_factor():
    """Piling copies of one point on one side moves the centroid, not the set."""
    A = np.array([[0.0, 0.0], [1.0, 0.0]])
    for k in (1, 10, 1000):
        B = np.vstack([[[0.0, 0.0]], np.tile([[1.0, 0.0]], (k, 1))])  # the same set as A
        m = hausdorff_under_translation(A, B)
        assert m.optimal_distance == 0.0
        assert m.bbox_distance == 0.0
        assert m.centroid_distance == pytest.approx(0.5 - 1 / (k + 1), abs=1e-12)
    assert m.ratio == np.inf


def test_reference_point_kinds():
    P = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [4.0, 2.0]])
    np.testing.assert_allclose(reference_point(P), [3.0, 1.0])
    np.testing.assert_allclose(reference_point(P, "bbox"), [2.0, 1.0])


# ----------------------------------------------------------------- figures
def test_figures_draw_the_witnesses():
    import matplotlib.figure

    from shapelab.plot import matching as pm

    rng = np.random.default_rng(5)
    A, B = rng.standard_normal((20, 2)), rng.standard_normal((15, 2)) + 1
    fig = pm.hausdorff(A, B, labels=("R", "G"))
    assert isinstance(fig, matplotlib.figure.Figure)
    title = fig.axes[0].get_title()
    assert f"{hausdorff(A, B):.3f}" in title
    m = hausdorff_under_translation(A, B)
    assert f"{m.ratio:.3f}" in pm.translation(A, B, m)._suptitle.get_text()
    fig = pm.timings({"a": 0.5, "b": 2.0})
    assert len(fig.axes[0].patches) == 2
    with pytest.raises(ValueError, match="positive"):
        pm.timings({"a": -1.0})
    with pytest.raises(ValueError, match="A must have 2"):
        pm.hausdorff(np.zeros((3, 3)), np.zeros((3, 3)))


def test_shapelab_hausdorff_is_always_the_function():
    """No module is named like the function: importing every submodule, in a fresh
    process, leaves ``shapelab.hausdorff`` the function of the notes."""
    import subprocess
    import sys

    code = (
        "import importlib, pkgutil, shapelab\n"
        "for m in pkgutil.walk_packages(shapelab.__path__, 'shapelab.'):\n"
        "    if not m.name.endswith('__main__'): importlib.import_module(m.name)\n"
        "import types\n"
        "assert isinstance(shapelab.hausdorff, types.FunctionType), type(shapelab.hausdorff)\n"
        "for name in shapelab.__all__:\n"
        "    assert not isinstance(getattr(shapelab, name), types.ModuleType), name\n"
        "print(shapelab.hausdorff([[0.0, 0.0]], [[3.0, 4.0]]))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == "5.0"


@pytest.mark.parametrize("n,m,d,off", [(1, 1, 1, 0.0), (30, 20, 2, 0.0), (400, 300, 3, 0.0), (400, 300, 3, 3.0)])
def test_the_plain_definition_equals_the_engine_bit_for_bit(n, m, d, off):
    """method="plain" (the notes' max-min, read directly) against the engine's kernels."""
    rng = np.random.default_rng(n + m + d)
    A, B = rng.normal(size=(n, d)), rng.normal(size=(m, d)) + off
    for method in ("auto", "brute", "pruned", "grid"):
        assert hausdorff(A, B, method="plain") == hausdorff(A, B, method=method)
        assert directed_hausdorff(A, B, method="plain").distance == directed_hausdorff(A, B, method=method).distance
    assert tuple(directed_hausdorff(A, B, method="plain")) == tuple(directed_hausdorff(A, B, method="brute"))
    assert hausdorff_pair(A, B, method="plain") == hausdorff_pair(A, B, method="brute")
