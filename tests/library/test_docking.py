"""docking_score: buried area (exact, closed forms) and clashes."""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl
from shapelab import Quaternion, RigidMotion
from shapelab.docking import docking_score


def _cap(r, h):
    return 2 * np.pi * r * h  # area of a spherical cap of height h


@pytest.mark.parametrize("r1, r2, d", [(1.0, 1.0, 1.5), (1.5, 1.0, 2.0), (2.0, 0.7, 1.6)])
def test_buried_area_of_two_overlapping_balls_is_the_two_caps(r1, r2, d):
    """Closed form: each ball loses the cap the other covers, of height r - t with
    t = (d^2 + r1^2 - r2^2) / 2d the distance from its centre to the radical plane."""
    s = docking_score(sl.Balls([[0.0, 0, 0]], r1), sl.Balls([[d, 0, 0]], r2), tolerance=10.0)
    t1 = (d**2 + r1**2 - r2**2) / (2 * d)
    t2 = d - t1
    assert s.buried_area == pytest.approx(_cap(r1, r1 - t1) + _cap(r2, r2 - t2), rel=1e-12)
    assert s.clash == 0.0 and s.score == pytest.approx(s.buried_area)


def test_touching_and_apart_bury_nothing_and_clashes_count_depth():
    a = sl.Balls([[0.0, 0, 0]], 1.0)
    assert docking_score(a, sl.Balls([[2.0, 0, 0]], 1.0)).buried_area == pytest.approx(0.0, abs=1e-12)
    assert docking_score(a, sl.Balls([[5.0, 0, 0]], 1.0)).buried_area == pytest.approx(0.0, abs=1e-12)
    s = docking_score(a, sl.Balls([[1.0, 0, 0]], 1.0), tolerance=0.5, penalty=2.0)
    assert s.clash == pytest.approx(0.5) and s.score == pytest.approx(s.buried_area - 1.0)


def test_the_motion_moves_b_and_a_common_motion_changes_nothing():
    rng = np.random.default_rng(3)
    A = sl.Balls(rng.uniform(0, 6, (30, 3)), rng.uniform(1.2, 1.8, 30))
    B = sl.Balls(rng.uniform(0, 6, (25, 3)) + [4.0, 0, 0], rng.uniform(1.2, 1.8, 25))
    m = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], 0.7), [0.5, -1.0, 0.2])
    s1 = docking_score(A, B, m)
    moved_b = sl.Balls(m.apply(B.centers), B.radii)
    assert docking_score(A, moved_b).score == pytest.approx(s1.score, rel=1e-9)
    g = RigidMotion(Quaternion.from_axis_angle([0, 1, 1], 1.1), [3.0, 2.0, 1.0])
    s2 = docking_score(sl.Balls(g.apply(A.centers), A.radii), sl.Balls(g.apply(moved_b.centers), B.radii))
    assert s2.buried_area == pytest.approx(s1.buried_area, rel=1e-9, abs=1e-9)
    assert s2.clash == pytest.approx(s1.clash, rel=1e-12)
    # symmetric in A and B
    s3 = docking_score(moved_b, A)
    assert s3.buried_area == pytest.approx(s1.buried_area, rel=1e-9, abs=1e-9)


def test_a_key_fits_its_lock_best():
    """A lock: a layer of balls with a hole (nine balls removed); the key: a ball that
    fills it.  The key in the hole scores best among poses moved out of it, up, down or
    sideways (sideways it clashes with the rim); far away it buries nothing."""
    g = np.arange(-4, 5) * 1.2
    X, Y = np.meshgrid(g, g)
    layer = np.c_[X.ravel(), Y.ravel(), np.zeros(X.size)]
    lock = sl.Balls(layer[np.linalg.norm(layer - [0, 0, 1.0], axis=1) > 2.2], 1.0)
    key = sl.Balls([[0.0, 0.0, 0.0]], 1.9)
    poses = [(0.0, 0.0, 0.0), (0.0, 0.0, 0.6), (0.0, 0.0, -0.6), (0.6, 0.0, 0.0), (0.6, 0.6, 0.0), (0.0, 0.0, 6.0)]
    scores = {p: docking_score(lock, key, RigidMotion(None, p)).score for p in poses}
    assert max(scores, key=scores.get) == (0.0, 0.0, 0.0), scores
    assert scores[(0.0, 0.0, 6.0)] == pytest.approx(0.0, abs=1e-9)
    assert docking_score(lock, key, RigidMotion(None, (0.6, 0.6, 0.0))).clash > 0


@pytest.mark.parametrize(
    "kwargs, exc, match",
    [
        (dict(A=None), TypeError, "A must"),
        (dict(motion="x"), TypeError, "motion"),
        (dict(penalty=-1.0), ValueError, "penalty"),
        (dict(tolerance=np.nan), ValueError, "tolerance"),
    ],
)
def test_bad_input(kwargs, exc, match):
    args = dict(A=sl.Balls([[0.0, 0, 0]], 1.0), B=sl.Balls([[1.0, 0, 0]], 1.0))
    args.update(kwargs)
    A, B = args.pop("A"), args.pop("B")
    with pytest.raises(exc, match=match):
        docking_score(A, B, **args)
    with pytest.raises(ValueError, match="3D"):
        docking_score(sl.Balls([[0.0, 0]], 1.0), sl.Balls([[1.0, 0]], 1.0))


# ------------------------------------------------------------------ Docking
def _key_and_lock():
    """A block of unit balls (three layers, jittered) with an L-shaped well in its top two
    layers, and the L-shaped key that fills the well."""
    grid = np.array([[x, y, z] for x in range(-3, 5) for y in range(-3, 5) for z in (0, 1, 2)], float) * 1.6
    grid += np.random.default_rng(7).uniform(-0.05, 0.05, grid.shape)
    key_cells = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [0, 2]], float) * 1.6
    hole = np.zeros(len(grid), bool)
    for c in key_cells:
        hole |= (np.linalg.norm(grid[:, :2] - c, axis=1) < 0.2) & (grid[:, 2] > 1.0)
    lock = sl.Balls(grid[~hole], 1.0)
    key = sl.Balls(grid[hole], 1.0)
    return lock, key


@pytest.mark.parametrize("seed", range(4))
def test_docking_score_equals_the_global_formula(seed):
    """The local score (receptor balls near the ligand only) against docking_score, the
    union of everything, at random poses near and in the lock."""
    lock, key = _key_and_lock()
    rng = np.random.default_rng(seed)
    dock = sl.Docking(lock, key, probe=0.4)
    for _ in range(5):
        m = RigidMotion(Quaternion.from_rotation_vector(rng.normal(size=3) * 0.5), rng.normal(size=3))
        a, b = dock.score(m), docking_score(lock, key, m, probe=0.4)
        assert a.buried_area == pytest.approx(b.buried_area, rel=1e-9, abs=1e-9)
        assert a.clash == pytest.approx(b.clash, rel=1e-12, abs=1e-12)
        assert a.score == pytest.approx(b.score, rel=1e-9, abs=1e-9)


def test_refine_never_loses_and_search_docks_the_key():
    lock, key = _key_and_lock()
    dock = sl.Docking(lock, key, probe=0.4)
    true = dock.score()
    start = RigidMotion(Quaternion.from_axis_angle([0, 0, 1], 0.3), [0.6, -0.4, 1.0])
    refined = dock.refine(start, max_evals=150)
    assert refined.score.score >= dock.score(start).score
    assert refined.evaluations <= 150
    # two stages: the site is where the key was; the search must put it back
    site = key.centers
    best = dock.search(site, n_starts=4, max_evals=150)[0]
    moved = best.motion.apply(key.centers)
    assert best.score.score >= true.score - 1e-6 * abs(true.score)
    assert sl.hausdorff(moved, key.centers) < 0.5


def test_landscape_peaks_at_the_true_pose():
    lock, key = _key_and_lock()
    dock = sl.Docking(lock, key, probe=0.4)
    angles, shifts = np.radians([-40.0, -20.0, 0.0, 20.0, 40.0]), np.array([-1.0, 0.0, 1.0])
    L = dock.landscape(angles, shifts, axis=[0, 0, 1], direction=[1, 0, 0])
    assert L.shape == (5, 3)
    assert np.unravel_index(np.argmax(L), L.shape) == (2, 1)
    assert L[2, 1] == pytest.approx(dock.score().score)


@pytest.mark.parametrize(
    "call, exc, match",
    [
        (lambda d: d.score(np.eye(4)), TypeError, "motion"),
        (lambda d: d.refine(max_evals=0), ValueError, "max_evals"),
        (lambda d: d.search(np.zeros((2, 3))), ValueError, "site"),
        (lambda d: d.landscape([0.0], [0.0], axis=[0, 0, 0], direction=[1, 0, 0]), ValueError, "axis"),
        (lambda d: d.landscape([np.nan], [0.0], axis=[0, 0, 1], direction=[1, 0, 0]), ValueError, "angles"),
    ],
)
def test_docking_bad_input(call, exc, match):
    lock, key = _key_and_lock()
    with pytest.raises(exc, match=match):
        call(sl.Docking(lock, key))
    with pytest.raises(TypeError, match="receptor"):
        sl.Docking(np.zeros((3, 3)), key)
    with pytest.raises(ValueError, match="probe"):
        sl.Docking(lock, key, probe=-1.0)
