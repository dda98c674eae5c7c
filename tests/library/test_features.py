"""coarse_align: the first stage of two-stage matching, then ICP."""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import Quaternion, RigidMotion, icp
from shapelab.datasets import sample_shape
from shapelab.features import coarse_align


def _err(m, truth):
    return float(np.degrees(m.rotation.angle_to(truth.rotation)))


@pytest.mark.parametrize("angle", [60.0, 120.0, 150.0, 175.0])
@pytest.mark.parametrize("axis", [(1.0, 2.0, 3.0), (0.0, 1.0, 0.0), (-1.0, 0.5, 0.2)])
def test_two_stages_recover_motions_plain_icp_misses(angle, axis):
    R = sample_shape("lumpy", 500, seed=1)
    truth = RigidMotion(Quaternion.from_axis_angle(axis, np.radians(angle)), [0.3, -0.2, 0.5])
    G = truth.apply(sample_shape("lumpy", 450, seed=2))  # other samples of the same surface
    best = coarse_align(R, G)[0].motion
    refined = icp(R, G, init=best, max_iter=100)
    assert _err(refined.motion, truth) < 10.0  # lesson 15's criterion: two samples of one surface differ


def test_plain_icp_fails_where_two_stages_succeed():
    """The negative control: from the identity, ICP stops in a wrong minimum at 150°."""
    R = sample_shape("lumpy", 500, seed=1)
    truth = RigidMotion(Quaternion.from_axis_angle((1.0, 2.0, 3.0), np.radians(150)), [0.3, -0.2, 0.5])
    G = truth.apply(sample_shape("lumpy", 450, seed=2))
    assert _err(icp(R, G, max_iter=100).motion, truth) > 10.0
    assert _err(icp(R, G, init=coarse_align(R, G)[0].motion, max_iter=100).motion, truth) < 10.0


def test_exact_copies_are_matched_exactly():
    R = sample_shape("lumpy", 300, seed=4)
    truth = RigidMotion(Quaternion.from_axis_angle((0.3, -1.0, 0.4), 2.5), [1.0, 2.0, 3.0])
    G = truth.apply(R)
    out = icp(R, G, init=coarse_align(R, G)[0].motion)
    assert out.motion.isclose(truth, atol=1e-8)


def test_candidates_are_ranked_and_proper():
    R = sample_shape("lumpy", 200, seed=5)
    G = RigidMotion(Quaternion.from_axis_angle((1, 1, 0), 1.0), [0, 0, 1]).apply(R)
    cands = coarse_align(R, G)
    scores = [c.score for c in cands]
    assert scores == sorted(scores)
    assert {c.feature for c in cands} == {"axes", "critical"}
    assert sum(c.feature == "axes" for c in cands) == 4  # the proper sign choices
    for c in cands:
        M = c.motion.rotation_matrix
        assert np.allclose(M @ M.T, np.eye(3), atol=1e-9) and np.linalg.det(M) > 0
    assert len(coarse_align(R, G, features="axes")) == 4


def test_a_symmetric_shape_gives_candidates_without_crashing():
    R = sample_shape("sphere", 200, seed=1)
    cands = coarse_align(R, R + 1.0)
    assert cands and all(np.isfinite(c.score) for c in cands)


@pytest.mark.parametrize(
    "kwargs, exc, match",
    [
        (dict(R=np.zeros((3, 3))), ValueError, "R"),
        (dict(G=np.zeros((10, 2))), ValueError, "G"),
        (dict(features=("bumps",)), ValueError, "features"),
        (dict(features=()), ValueError, "features"),
    ],
)
def test_bad_input(kwargs, exc, match):
    args = dict(R=sample_shape("lumpy", 50, seed=1), G=sample_shape("lumpy", 50, seed=2))
    args.update(kwargs)
    with pytest.raises(exc, match=match):
        coarse_align(args.pop("R"), args.pop("G"), **args)


def test_two_stage_figure_draws_one_panel_per_stage_and_rejects_bad_stages():
    from shapelab import plot
    from shapelab.datasets import sample_shape

    R = sample_shape("lumpy", 200, seed=1)
    truth = RigidMotion(Quaternion.from_axis_angle([1.0, 2.0, 3.0], np.radians(150)), [0.3, 0.0, 0.0])
    G = truth.apply(R)
    best = coarse_align(R, G)[0]
    fig = plot.two_stage(R, G, {"start": RigidMotion(), "stage 1": best.motion, "stage 2": icp(R, G, init=best.motion)})
    assert [ax.get_title() for ax in fig.axes] == ["start", "stage 1", "stage 2"]
    assert all(ax.name == "3d" for ax in fig.axes)
    with pytest.raises(TypeError, match="stages"):
        plot.two_stage(R, G, {"x": np.eye(3)})
    with pytest.raises(TypeError, match="stages"):
        plot.two_stage(R, G, {})
