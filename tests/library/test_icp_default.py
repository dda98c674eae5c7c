"""``icp``'s default is the notes' four steps, literally (issue 33): no acceleration
step unless ``accelerate=True``."""

from __future__ import annotations

import importlib

import numpy as np
import pytest
from scipy.spatial import cKDTree

import shapelab as sl
from shapelab import Quaternion, RigidMotion, icp, register
from shapelab.datasets import sample_shape

icp_module = importlib.import_module("shapelab.icp")  # ``shapelab.icp`` is the function


def _pair(seed: int = 3):
    src = sample_shape("lumpy", 300, seed=seed)
    true = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], np.radians(20)), [0.1, 0.0, 0.05])
    tgt = true.apply(src) + np.random.default_rng(seed).normal(scale=0.01, size=src.shape)
    return src, tgt


def _four_steps(src, tgt, tol, max_iter):
    """The notes' algorithm written out: closest points, register, move, repeat."""
    tree = cKDTree(tgt)
    motion = RigidMotion()
    d, j = tree.query(motion.apply(src))
    mse = [np.mean(d * d)]
    for _ in range(max_iter):
        moved = motion.apply(src)
        motion = register(moved, tgt[j]) @ motion  # step 2, then step 3
        d, j = tree.query(motion.apply(src))  # step 1 of the next iteration
        mse.append(np.mean(d * d))
        if mse[-2] - mse[-1] < tol:  # step 4
            break
    return motion, np.array(mse)


def test_the_default_equals_a_hand_written_four_step_loop():
    src, tgt = _pair()
    # tol sits in a wide gap of this pair's decreases (9.9e-5, then 1.4e-7), so the
    # stop does not hang on rounding: at the fixed point itself the decrease is at
    # the level of the last bit and its sign differs between summation orders,
    # CPUs and BLAS builds (the CI machine stopped one step before this one did)
    tol = 3e-6
    res = icp(src, tgt, tol=tol, max_iter=80)
    motion, mse = _four_steps(src, tgt, tol, 80)
    decrease = -np.diff(mse)
    assert decrease[-1] < tol / 10 and np.all(decrease[:-1] > 10 * tol)  # the gap
    assert res.n_iter == len(mse) - 1
    np.testing.assert_allclose(res.mse, mse, rtol=1e-9, atol=0)
    assert res.motion.isclose(motion, atol=1e-9)


def test_the_default_makes_no_acceleration_step(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("the default ran an accelerated step")

    monkeypatch.setattr(icp_module, "Anderson", refuse)
    src, tgt = _pair(4)
    assert icp(src, tgt, max_iter=20).n_iter >= 1
    with pytest.raises(AssertionError, match="accelerated"):
        icp(src, tgt, max_iter=20, accelerate=True)


def test_acceleration_is_an_option_to_the_same_fixed_point_in_fewer_steps():
    src, tgt = _pair(5)
    plain = icp(src, tgt, tol=1e-12, max_iter=300)
    fast = icp(src, tgt, tol=1e-12, max_iter=300, accelerate=True)
    assert fast.n_iter < plain.n_iter
    assert fast.motion.isclose(plain.motion, atol=1e-5)


def test_old_import_paths_give_the_same_objects():
    from shapelab.registration import ICPResult, optimal_rotation
    from shapelab.registration import RigidMotion as R2
    from shapelab.registration import icp as icp2

    assert icp2 is sl.icp is icp_module.icp
    assert R2 is sl.RigidMotion and optimal_rotation is sl.optimal_rotation
    assert ICPResult is sl.ICPResult
    importlib.import_module("shapelab.hausdorff")
    assert callable(sl.icp) and callable(sl.hausdorff)  # the functions, not the modules
