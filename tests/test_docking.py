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
