"""Optimal rotation, rigid registration and ICP (shapelab/registration.py; Notes §23.2).

Oracles: the literal sum A = Σ R̄ⱼᵀGⱼ of the notes, Σ⟨q rⱼ q*, gⱼ⟩ by quaternion
products, an SVD (Kabsch with the det fix) written here, SciPy's
``Rotation.align_vectors``, brute-force nearest neighbours, and a plain transcription
of the notes' four ICP steps.
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from shapelab import ICPResult, Quaternion, RigidMotion, icp, optimal_rotation, register
from shapelab.datasets import sample_shape
from shapelab.quaternion import left_matrices, qmul, right_matrices
from shapelab.registration import (
    DegenerateRotationWarning,
    closest_points,
    cross_covariance,
    horn_matrix,
    kabsch,
)

SET = settings(max_examples=30, deadline=None)
seeds = st.integers(0, 2**31 - 1)


def svd_rotation(R, G):
    """Kabsch with the det fix, independent of the library: argmin Σ|X r - g|² over SO(3)."""
    u, _, vt = np.linalg.svd(R.T @ G)
    d = np.sign(np.linalg.det(vt.T @ u.T))
    return vt.T @ np.diag([1, 1, d]) @ u.T


def cost(q: Quaternion, R, G):
    return float(np.sum((q.rotate(R) - G) ** 2))


def random_rotation(rng):
    return Quaternion(*rng.normal(size=4)).normalized()


def noisy_pair(rng, n=50, noise=0.01, centred=True):
    R = rng.normal(size=(n, 3)) * [3.0, 2.0, 1.0]
    if centred:
        R -= R.mean(axis=0)
    q = random_rotation(rng)
    G = q.rotate(R) + noise * rng.normal(size=R.shape)
    if centred:
        G -= G.mean(axis=0)
    return R, G, q


# ----------------------------------------------------------------- Horn's matrix


@SET
@given(seeds)
def test_horn_matrix_equals_the_literal_sum_of_the_notes(seed):
    rng = np.random.default_rng(seed)
    R, G = rng.normal(size=(2, 9, 3))
    literal = np.einsum("nji,njk->ik", right_matrices(R), left_matrices(G))  # Σ R̄ⱼᵀ Gⱼ
    A = horn_matrix(R, G)
    np.testing.assert_allclose(A, literal, atol=1e-12)
    np.testing.assert_allclose(A, A.T, atol=0)
    assert abs(np.trace(A)) < 1e-12
    np.testing.assert_allclose(cross_covariance(R, G), sum(np.outer(r, g) for r, g in zip(R, G)), atol=1e-12)
    # q^T A q = Σ ⟨q r q*, g⟩ for unit q, computed with quaternion products only
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    qc = q * [1, -1, -1, -1]
    rot = [qmul(qmul(q, np.r_[0.0, r]), qc)[1:] for r in R]
    assert np.isclose(q @ A @ q, sum(np.dot(a, g) for a, g in zip(rot, G)), atol=1e-10)


def test_blocked_cross_covariance_on_large_inputs():
    rng = np.random.default_rng(1)
    R, G = rng.normal(size=(2, 3 * 4096 + 17, 3))
    np.testing.assert_allclose(cross_covariance(R, G), np.einsum("ni,nj->ij", R, G), rtol=1e-12, atol=1e-9)
    for name, bad in (("R", np.inf), ("G", np.nan)):
        R2, G2 = R.copy(), G.copy()
        (R2 if name == "R" else G2)[12000, 1] = bad
        with pytest.raises(ValueError, match=rf"{name} must be finite; found {bad} at index \(12000, 1\)"):
            optimal_rotation(R2, G2)


# ----------------------------------------------------------------- optimal rotation


@SET
@given(seeds)
def test_optimal_rotation_agrees_with_svd_and_scipy(seed):
    rng = np.random.default_rng(seed)
    R, G, _ = noisy_pair(rng, noise=0.3)
    q = optimal_rotation(R, G)
    assert np.isclose(q.norm(), 1.0) and q.w >= 0
    np.testing.assert_allclose(q.to_matrix(), svd_rotation(R, G), atol=1e-8)
    np.testing.assert_allclose(q.to_matrix(), kabsch(R, G), atol=1e-8)
    scipy_rot, _ = Rotation.align_vectors(G, R)  # scipy rotates its 2nd argument onto its 1st
    np.testing.assert_allclose(q.to_matrix(), scipy_rot.as_matrix(), atol=1e-8)


@SET
@given(seeds)
def test_optimal_rotation_beats_every_other_rotation(seed):
    rng = np.random.default_rng(seed)
    R, G, _ = noisy_pair(rng, n=12, noise=1.0)
    best = cost(optimal_rotation(R, G), R, G)
    for _ in range(20):
        assert best <= cost(random_rotation(rng), R, G) + 1e-9
    # and it is a stationary point: small perturbations do not help
    q = optimal_rotation(R, G)
    for v in 1e-4 * rng.normal(size=(6, 3)):
        assert best <= cost(Quaternion.from_rotation_vector(v) * q, R, G) + 1e-12


def test_optimal_rotation_recovers_a_known_rotation_from_noisy_data():
    rng = np.random.default_rng(5)
    R, G, q_true = noisy_pair(rng, n=400, noise=0.01)
    q = optimal_rotation(R, G)
    assert np.degrees(q.angle_to(q_true)) < 0.1
    # exact data: exact answer
    R, G, q_true = noisy_pair(rng, n=10, noise=0.0)
    assert optimal_rotation(R, G).same_rotation(q_true, 1e-12)


def test_direction_convention_rotates_R_onto_G():
    q = Quaternion.from_axis_angle([0, 0, 1], np.pi / 2)
    R = np.array([[1.0, 0, 0], [0, 2.0, 0], [0, 0, 3.0]])
    G = q.rotate(R)
    found = optimal_rotation(R, G)
    np.testing.assert_allclose(found.rotate(R), G, atol=1e-14)
    assert optimal_rotation(G, R).same_rotation(q.conjugate(), 1e-14)


def test_scale_invariance_tiny_and_large():
    rng = np.random.default_rng(6)
    R, G, q_true = noisy_pair(rng, n=20, noise=0.0)
    for s in (1e-6, 1e6):
        assert optimal_rotation(s * R, s * G).same_rotation(q_true, 1e-9)


def test_optimal_rotation_does_not_centre_register_does():
    """The notes' formula silently assumes centred sets; register() centres."""
    rng = np.random.default_rng(7)
    R, G, q_true = noisy_pair(rng, n=30, noise=0.0)
    R = R + [3.0, 1.0, -2.0]  # not centred
    G = q_true.rotate(R)
    shift = np.array([5.0, -3.0, 2.0])
    wrong = optimal_rotation(R, G + shift)
    assert np.degrees(wrong.angle_to(q_true)) > 1.0  # off: translation not modelled
    m = register(R, G + shift)
    assert m.rotation.same_rotation(q_true, 1e-10)
    np.testing.assert_allclose(m.translation, shift, atol=1e-10)


# ----------------------------------------------------------------- degenerate inputs


def test_coplanar_points_have_a_unique_answer():
    rng = np.random.default_rng(8)
    P = rng.normal(size=(10, 3))
    P[:, 2] = 0.0
    q_true = random_rotation(rng)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert optimal_rotation(P, q_true.rotate(P)).same_rotation(q_true, 1e-10)


@pytest.mark.parametrize("n", [1, 2, 7])
def test_collinear_points_warn_and_return_an_optimal_rotation(n):
    rng = np.random.default_rng(9)
    line = np.outer(rng.normal(size=n) + 3.0, [1.0, 2.0, 2.0])  # on a line through 0
    q_true = random_rotation(rng)
    G = q_true.rotate(line)
    with pytest.warns(DegenerateRotationWarning, match="not unique"):
        q = optimal_rotation(line, G)
    assert cost(q, line, G) < 1e-18 * (1 + np.sum(G**2)) + 1e-20  # still optimal (zero cost)
    # the undetermined part is a spin about the line; q differs from q_true by one
    assert np.isclose(cost(q, line, G), cost(Quaternion.from_matrix(kabsch(line, G)), line, G), atol=1e-12)


def test_two_points_are_enough_for_optimal_rotation_but_not_register():
    rng = np.random.default_rng(10)
    P = rng.normal(size=(2, 3))  # two independent directions from the origin
    q_true = random_rotation(rng)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert optimal_rotation(P, q_true.rotate(P)).same_rotation(q_true, 1e-10)
    with pytest.warns(DegenerateRotationWarning):  # centred: one direction left
        m = register(P, q_true.rotate(P) + 1.0)
    np.testing.assert_allclose(m.apply(P), q_true.rotate(P) + 1.0, atol=1e-12)


def test_single_point_and_all_zero():
    with pytest.warns(DegenerateRotationWarning):
        m = register([[1.0, 2.0, 3.0]], [[4.0, 5.0, 6.0]])
    np.testing.assert_allclose(m.apply([1.0, 2.0, 3.0]), [4.0, 5.0, 6.0], atol=1e-14)
    with pytest.warns(DegenerateRotationWarning):
        q = optimal_rotation(np.zeros((4, 3)), np.zeros((4, 3)))
    assert q == Quaternion(1.0)


def test_reflection_gives_the_best_proper_rotation_unlike_naive_svd():
    rng = np.random.default_rng(11)
    R = rng.normal(size=(30, 3)) * [3, 2, 1]
    R -= R.mean(axis=0)
    G = R * [1, 1, -1]  # a mirror image: no rotation matches it
    q = optimal_rotation(R, G)
    assert np.isclose(np.linalg.det(q.to_matrix()), 1.0)
    naive = kabsch(R, G, proper=False)
    assert np.isclose(np.linalg.det(naive), -1.0)  # the reflection itself
    assert np.sum((R @ naive.T - G) ** 2) < 1e-20
    best_proper = np.sum((R @ svd_rotation(R, G).T - G) ** 2)
    assert np.isclose(cost(q, R, G), best_proper, rtol=1e-10)
    assert cost(q, R, G) > 1.0


# ----------------------------------------------------------------- register, RigidMotion


@SET
@given(seeds, st.sampled_from([(1.0, 0.0), (1e-6, 0.0), (1e3, 0.0), (1.0, 1e6), (1e3, 1e6), (1e-6, 1e-3)]))
def test_register_recovers_a_known_motion(seed, scale_offset):
    scale, offset = scale_offset  # (offset/scale is what costs digits: the input is rounded)
    rng = np.random.default_rng(seed)
    R = scale * rng.normal(size=(40, 3)) + offset
    q = random_rotation(rng)
    t = scale * rng.normal(size=3)
    truth = RigidMotion(q, t)
    G = truth.apply(R)
    m = register(R, G)
    assert m.rotation.same_rotation(q, 1e-8 + 1e-14 * offset / scale)
    np.testing.assert_allclose(m.apply(R), G, atol=1e-9 * scale + 1e-9 * offset)


def test_register_with_noise_agrees_with_svd_and_centroids():
    rng = np.random.default_rng(12)
    R, G, q = noisy_pair(rng, n=200, noise=0.05, centred=False)
    G = G + [1.0, 2.0, 3.0]
    m = register(R, G)
    X = svd_rotation(R - R.mean(0), G - G.mean(0))
    np.testing.assert_allclose(m.rotation_matrix, X, atol=1e-10)
    np.testing.assert_allclose(m.translation, G.mean(0) - X @ R.mean(0), atol=1e-10)
    assert np.degrees(m.rotation.angle_to(q)) < 0.5
    # least squares: nudging the translation only makes it worse
    base = np.sum((m.apply(R) - G) ** 2)
    for d in 1e-3 * np.eye(3):
        assert np.sum((m.apply(R) + d - G) ** 2) > base


def test_rigid_motion_algebra():
    rng = np.random.default_rng(13)
    a = RigidMotion(random_rotation(rng), rng.normal(size=3))
    b = RigidMotion(random_rotation(rng), rng.normal(size=3))
    x = rng.normal(size=(5, 3))
    np.testing.assert_allclose((a @ b).apply(x), a.apply(b.apply(x)), atol=1e-12)  # b first
    np.testing.assert_allclose((a @ b).as_matrix(), a.as_matrix() @ b.as_matrix(), atol=1e-12)
    np.testing.assert_allclose(a.inverse().apply(a.apply(x)), x, atol=1e-12)
    assert (a @ a.inverse()).isclose(RigidMotion.identity(), 1e-12)
    np.testing.assert_allclose(np.linalg.inv(a.as_matrix()), a.inverse().as_matrix(), atol=1e-12)
    assert RigidMotion.from_matrix(a.as_matrix()).isclose(a, 1e-12)
    np.testing.assert_allclose(a.apply(x[0]), a.as_matrix()[:3, :3] @ x[0] + a.as_matrix()[:3, 3])
    assert np.isclose(a.angle, a.rotation.to_axis_angle()[1])


def test_rigid_motion_is_frozen_and_normalises():
    m = RigidMotion(Quaternion(2.0, 0, 0, 0), [1, 2, 3])
    assert m.rotation == Quaternion(1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.translation = np.zeros(3)
    with pytest.raises(ValueError):
        m.translation[0] = 5.0  # read-only array
    assert repr(m) == "RigidMotion(angle=0°, axis=(1, 0, 0), translation=(1, 2, 3))"
    assert RigidMotion([1, 0, 0, 0]).rotation == Quaternion(1.0)


@pytest.mark.parametrize(
    "call, exc, words",
    [
        (lambda: optimal_rotation(np.zeros((3, 3)), np.zeros((4, 3))), ValueError, "R and G must have the same shape"),
        (lambda: optimal_rotation(np.zeros((0, 3)), np.zeros((0, 3))), ValueError, "R must hold at least 1"),
        (lambda: optimal_rotation(np.zeros((3, 2)), np.zeros((3, 2))), ValueError, "R must have 3 columns"),
        (lambda: optimal_rotation(np.zeros((3, 3)), [[0, 0, np.nan]] * 3), ValueError, "G must be finite"),
        (lambda: optimal_rotation(np.full((3, 3), np.inf), np.zeros((3, 3))), ValueError, "R must be finite"),
        (lambda: optimal_rotation(np.full((3, 3), 1e200), np.full((3, 3), 1e200)), ValueError, "overflows"),
        (lambda: register(np.zeros(3), np.zeros(3)), ValueError, "R must be a 2-D array"),
        (lambda: register(np.zeros((4, 3)), np.zeros((5, 3))), ValueError, "same shape"),
        (lambda: RigidMotion(Quaternion(0.0), [0, 0, 0]), ValueError, "rotation is the zero quaternion"),
        (lambda: RigidMotion(None, [0, 0]), ValueError, "translation must have 3"),
        (lambda: RigidMotion([1, 0, 0], None), ValueError, "rotation must have length 4"),
        (lambda: RigidMotion.from_matrix(np.eye(3)), ValueError, r"shape \(4, 4\)"),
        (lambda: RigidMotion().apply(np.zeros((2, 2))), ValueError, "points must have shape"),
        (lambda: RigidMotion() @ 3, TypeError, "unsupported operand"),
    ],
)
def test_bad_input_names_the_argument(call, exc, words):
    with pytest.raises(exc, match=words):
        call()


# ----------------------------------------------------------------- ICP


def notes_icp(source, target, n_steps):
    """The notes' four steps, transcribed plainly (brute-force π, SVD motion), source moving."""
    cur = source.copy()
    total_R, total_t = np.eye(3), np.zeros(3)
    mse = []
    for _ in range(n_steps + 1):
        d2 = ((cur[:, None, :] - target[None, :, :]) ** 2).sum(-1)
        pi = d2.argmin(axis=1)  # step 1
        mse.append(d2[np.arange(len(cur)), pi].mean())
        P, Q = cur, target[pi]
        X = svd_rotation(P - P.mean(0), Q - Q.mean(0))  # step 2
        t = Q.mean(0) - X @ P.mean(0)
        cur = cur @ X.T + t  # step 3
        total_R, total_t = X @ total_R, X @ total_t + t
    return np.array(mse[: n_steps + 1])


def test_plain_icp_is_the_notes_algorithm():
    src = sample_shape("lumpy", 150, seed=1)
    truth = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], np.radians(25)), [0.1, -0.05, 0.2])
    tgt = truth.apply(sample_shape("lumpy", 120, seed=2))
    res = icp(src, tgt, tol=0.0, max_iter=8, accelerate=False)
    np.testing.assert_allclose(res.mse, notes_icp(src, tgt, res.n_iter), rtol=1e-9)


@SET
@given(
    seeds,
    st.floats(0, 120),
    st.booleans(),
    st.sampled_from([None, 0.3, 2.0]),
    st.sampled_from(["lumpy", "cube", "sphere"]),
)
def test_icp_cost_never_increases(seed, degrees, accelerate, max_distance, kind):
    rng = np.random.default_rng(seed)
    src = sample_shape(kind, 120, seed=seed)
    truth = RigidMotion(
        Quaternion.from_axis_angle(rng.normal(size=3) + 0.1, np.radians(degrees)), 0.2 * rng.normal(size=3)
    )
    tgt = truth.apply(sample_shape(kind, 100, seed=seed + 1))
    res = icp(src, tgt, tol=0.0, max_iter=30, accelerate=accelerate, max_distance=max_distance)
    assert np.all(np.diff(res.mse) <= 0), res.mse
    assert res.mse.shape == (res.n_iter + 1,) and len(res.motions) == res.n_iter + 1
    # mse[k] really is the closest-point cost of motion k (capped at max_distance)
    for k in (0, res.n_iter):
        d = np.sqrt(((res.motions[k].apply(src)[:, None] - tgt[None]) ** 2).sum(-1)).min(1)
        if max_distance is not None:
            d = np.minimum(d, max_distance)
        assert np.isclose(res.mse[k], np.mean(d**2), rtol=1e-9, atol=1e-15)


def test_icp_correspondence_is_brute_force_nearest():
    src = sample_shape("lumpy", 200, seed=3)
    tgt = sample_shape("lumpy", 180, seed=4) + 0.05
    res = icp(src, tgt, keep_history=True, max_iter=5)
    moved = res.motion.apply(src)
    d2 = ((moved[:, None] - tgt[None]) ** 2).sum(-1)
    np.testing.assert_allclose(d2[np.arange(len(src)), res.correspondence], d2.min(1), rtol=1e-12)
    assert res.correspondences.shape == (res.n_iter + 1, len(src))
    np.testing.assert_array_equal(res.correspondences[-1], res.correspondence)
    idx, d = closest_points(moved, tgt, max_distance=0.01)
    assert np.all((idx == -1) == (np.sqrt(d2.min(1)) > 0.01))
    assert np.all(d[idx == -1] == 0.01)


@pytest.mark.parametrize("accelerate", [True, False])
def test_icp_recovers_a_known_motion_on_a_non_symmetric_shape(accelerate):
    src = sample_shape("lumpy", 2000, seed=1)
    truth = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], np.radians(20)), [0.1, -0.05, 0.2])
    # same sampling: exact recovery
    res = icp(src, truth.apply(src), tol=1e-14, max_iter=200, accelerate=accelerate)
    assert res.converged and np.degrees(res.motion.rotation.angle_to(truth.rotation)) < 1e-4
    np.testing.assert_allclose(res.motion.translation, truth.translation, atol=1e-5)
    assert np.all(res.correspondence == np.arange(2000))
    # independent samplings of the same surface: close, limited by the sampling
    res = icp(src, truth.apply(sample_shape("lumpy", 2000, seed=2)), tol=0, max_iter=200, accelerate=accelerate)
    assert np.degrees(res.motion.rotation.angle_to(truth.rotation)) < 2.0


def test_acceleration_needs_fewer_iterations():
    src = sample_shape("lumpy", 1500, seed=1)
    truth = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], np.radians(20)), [0.1, -0.05, 0.2])
    tgt = truth.apply(src)
    fast = icp(src, tgt, tol=1e-12, max_iter=300, accelerate=True)
    slow = icp(src, tgt, tol=1e-12, max_iter=300)
    assert fast.converged and slow.converged and fast.n_iter < slow.n_iter


def test_icp_fails_on_symmetric_shapes_documented():
    truth = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], np.radians(60)), [0.1, -0.05, 0.2])
    # a cube: ICP settles in a symmetric pose, 90 degrees off, with a small cost all the same
    src, tgt = sample_shape("cube", 1500, seed=1), sample_shape("cube", 1500, seed=2)
    res = icp(src, truth.apply(tgt), max_iter=200)
    err = np.degrees(res.motion.rotation.angle_to(truth.rotation))
    assert res.converged and err > 30
    at_truth = icp(src, truth.apply(tgt), max_iter=0, init=truth).mse[0]
    assert res.mse[-1] < 1.2 * at_truth  # the cost cannot tell the wrong pose from the right one
    # that pose differs from the truth by a symmetry of the cube (a signed permutation)
    sym = (truth.inverse() @ res.motion).rotation_matrix
    np.testing.assert_allclose(np.abs(sym).sum(axis=0), 1.0, atol=0.05)
    # a sphere: every rotation fits, ICP does not rotate at all
    src, tgt = sample_shape("sphere", 1500, seed=1), sample_shape("sphere", 1500, seed=2)
    res = icp(src, truth.apply(tgt), max_iter=200)
    assert res.converged and np.degrees(res.motion.rotation.angle_to(truth.rotation)) > 50
    at_truth = icp(src, truth.apply(tgt), max_iter=0, init=truth).mse[0]
    assert res.mse[-1] < 1.2 * at_truth  # ... while the cost is as good as at the truth


def test_icp_init_and_max_iter_zero():
    src = sample_shape("lumpy", 300, seed=1)
    truth = RigidMotion(Quaternion.from_axis_angle([0, 0, 1], np.radians(170)), [1.0, 0, 0])
    tgt = truth.apply(src)
    res = icp(src, tgt, max_iter=0, init=truth)
    assert res.n_iter == 0 and not res.converged and res.mse[0] < 1e-20
    assert res.motion is truth
    res = icp(
        src, tgt, tol=1e-14, init=RigidMotion(Quaternion.from_axis_angle([0, 0, 1], np.radians(160)), [1.0, 0, 0])
    )
    assert np.degrees(res.motion.rotation.angle_to(truth.rotation)) < 1e-3
    assert isinstance(res, ICPResult) and "converged=True" in repr(res)


def test_icp_all_pairs_beyond_max_distance_stops():
    src = sample_shape("lumpy", 100, seed=1)
    res = icp(src, src + 10.0, max_distance=0.5)
    assert res.n_iter == 0 and not res.converged and np.all(res.correspondence == -1)
    assert res.mse[0] == 0.25


@pytest.mark.parametrize(
    "kwargs, exc, words",
    [
        (dict(source=np.zeros((0, 3))), ValueError, "source must hold at least 3"),
        (dict(target=np.zeros((2, 3))), ValueError, "target must hold at least 3"),
        (dict(source=np.zeros((5, 2))), ValueError, "source must have 3 columns"),
        (dict(target=np.full((5, 3), np.nan)), ValueError, "target must be finite"),
        (dict(tol=-1.0), ValueError, "tol must be non-negative"),
        (dict(tol=np.inf), ValueError, "tol must be finite"),
        (dict(max_iter=-1), ValueError, "max_iter must be at least 0"),
        (dict(max_iter=2.5), TypeError, "max_iter must be an integer"),
        (dict(init=np.eye(4)), TypeError, "init must be a RigidMotion"),
        (dict(max_distance=0.0), ValueError, "max_distance must be positive"),
        (dict(accelerate="yes"), TypeError, "accelerate must be True or False"),
    ],
)
def test_icp_bad_input(kwargs, exc, words):
    args = dict(source=sample_shape("lumpy", 10, seed=0), target=sample_shape("lumpy", 10, seed=1))
    args.update(kwargs)
    with pytest.raises(exc, match=words):
        icp(args.pop("source"), args.pop("target"), **args)


def test_sample_shape():
    for kind in ("lumpy", "ellipsoid", "sphere", "cube"):
        p = sample_shape(kind, 50, seed=3)
        assert p.shape == (50, 3) and np.array_equal(p, sample_shape(kind, 50, seed=3))
    assert np.allclose(np.linalg.norm(sample_shape("sphere", 20), axis=1), 1.0)
    assert np.allclose(np.abs(sample_shape("cube", 20)).max(axis=1), 1.0)
    e = sample_shape("ellipsoid", 20)
    assert np.allclose(((e / [1.0, 0.75, 0.55]) ** 2).sum(1), 1.0)
    t = sample_shape("torus", 40, seed=2)  # on the torus of radii 1 and 0.4 about z
    assert np.allclose((np.hypot(t[:, 0], t[:, 1]) - 1.0) ** 2 + t[:, 2] ** 2, 0.4**2)
    with pytest.raises(ValueError, match="kind must be one of"):
        sample_shape("klein bottle", 10)


def test_paired_superposition_does_not_import_scipy():
    """The first call of optimal_rotation / register pays no ``import scipy`` (cold
    start: only ICP and closest_points need a k-d tree), and closest_points works."""
    import subprocess
    import sys

    code = (
        "import sys, numpy as np\n"
        "from shapelab import optimal_rotation, register, Quaternion\n"
        "rng = np.random.default_rng(0); R = rng.normal(size=(500, 3))\n"
        "q = Quaternion.from_axis_angle([1.0, 2.0, 3.0], 0.7); G = q.rotate(R)\n"
        "print(optimal_rotation(R, G).angle_to(q), register(R, G + 1.0).translation[0],\n"
        "      any(m == 'scipy' or m.startswith('scipy.') for m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    angle, shift, imported = out.stdout.split()
    assert imported == "False"
    assert float(angle) < 1e-7 and abs(float(shift) - 1.0) < 1e-9
    from shapelab.registration import closest_points

    idx, d = closest_points(np.array([[0.0, 0, 0], [5.0, 0, 0]]), np.array([[0.1, 0, 0], [4.0, 0, 0]]))
    assert idx.tolist() == [0, 1] and d == pytest.approx([0.1, 1.0])


# ----------------------------------------------------------------- weights and the sensitivity matrix
# Oracles: SciPy's Rotation.align_vectors(a, b, weights, return_sensitivity=True), which
# rotates b onto a (so ours (R, G) is SciPy's (G, R)); its own test cases
# (scipy/spatial/transform/tests/test_rotation.py); integer weights as repeated points;
# a weighted SVD written here.


def weighted_svd_motion(R, G, w):
    """argmin Σ w |X r + t - g|² over rigid motions, by weighted centroids and Kabsch."""
    cr, cg = w @ R / w.sum(), w @ G / w.sum()
    X = svd_rotation((R - cr) * w[:, None], G - cg)
    return X, cg - X @ cr


@SET
@given(seeds)
def test_weighted_rotation_and_sensitivity_equal_scipy(seed):
    rng = np.random.default_rng(seed)
    R, G, _ = noisy_pair(rng, n=int(rng.integers(3, 40)), noise=0.3, centred=False)
    w = rng.uniform(0, 3, len(R))
    q, S = optimal_rotation(R, G, w, return_sensitivity=True)
    rot, _, S_ref = Rotation.align_vectors(G, R, w, return_sensitivity=True)
    np.testing.assert_allclose(q.to_matrix(), rot.as_matrix(), atol=1e-9)
    np.testing.assert_allclose(S, S_ref, rtol=1e-8, atol=1e-12 * np.abs(S_ref).max())
    np.testing.assert_allclose(S, S.T, atol=1e-14 * np.abs(S).max())
    assert np.all(np.linalg.eigvalsh(S) > 0)
    q1, S1 = optimal_rotation(R, G, return_sensitivity=True)  # unweighted: all ones
    rot1, _, S1_ref = Rotation.align_vectors(G, R, return_sensitivity=True)
    np.testing.assert_allclose(S1, S1_ref, rtol=1e-8, atol=1e-12 * np.abs(S1_ref).max())
    assert q1 == optimal_rotation(R, G)


@SET
@given(seeds)
def test_weighted_register_equals_weighted_svd_and_scipy(seed):
    rng = np.random.default_rng(seed)
    R, G, _ = noisy_pair(rng, n=25, noise=0.5, centred=False)
    G = G + rng.normal(size=3) * 10
    w = rng.uniform(0, 2, len(R))
    m, S = register(R, G, w, return_sensitivity=True)
    X, t = weighted_svd_motion(R, G, w)
    np.testing.assert_allclose(m.rotation_matrix, X, atol=1e-9)
    np.testing.assert_allclose(m.translation, t, atol=1e-9)
    cr, cg = w @ R / w.sum(), w @ G / w.sum()
    rot, _, S_ref = Rotation.align_vectors(G - cg, R - cr, w, return_sensitivity=True)
    np.testing.assert_allclose(m.rotation_matrix, rot.as_matrix(), atol=1e-9)
    np.testing.assert_allclose(S, S_ref, rtol=1e-8)
    # the weighted cost is minimal: no other motion does better
    best = np.sum(w * np.sum((m.apply(R) - G) ** 2, axis=1))
    for _ in range(10):
        other = RigidMotion(random_rotation(rng), rng.normal(size=3)) @ m
        assert best <= np.sum(w * np.sum((other.apply(R) - G) ** 2, axis=1)) + 1e-9


def test_integer_weights_repeat_points_and_zero_weights_drop_them():
    rng = np.random.default_rng(21)
    R, G, _ = noisy_pair(rng, n=9, noise=0.4, centred=False)
    k = np.array([1, 3, 0, 2, 1, 0, 4, 1, 2])
    rep = np.repeat(np.arange(9), k)
    assert optimal_rotation(R, G, k).same_rotation(optimal_rotation(R[rep], G[rep]), 1e-12)
    assert register(R, G, k).isclose(register(R[rep], G[rep]), atol=1e-12)
    keep = k > 0
    assert register(R, G, keep.astype(float)).isclose(register(R[keep], G[keep]), atol=1e-12)
    assert register(R, G, 7.5 * np.ones(9)).isclose(register(R, G), atol=1e-12)  # only ratios count


def test_scipy_rssd_sensitivity_case():
    """scipy's test_align_vectors_rssd_sensitivity, with the arguments swapped."""
    a = np.array([[0, 1, 0], [0, 1, 1], [0, 1, 1]], float)
    b = np.array([[1, 0, 0], [1, 1.1, 0], [1, 0.9, 0]])
    q, S = optimal_rotation(b, a, return_sensitivity=True)
    np.testing.assert_allclose(S, [[0.2, 0, 0], [0, 1.5, 1], [0, 1, 1]], atol=1e-6)
    rssd = np.sqrt(np.sum((q.rotate(b) - a) ** 2))
    assert np.isclose(rssd, 0.141421356237308, atol=1e-6)


def test_scipy_scaled_weights_case():
    """scipy's test_align_vectors_scaled_weights: scaling all weights changes neither the
    rotation nor the sensitivity."""
    n = 10
    a = Rotation.random(n, rng=0).apply([1, 0, 0])
    b = Rotation.random(n, rng=1).apply([1, 0, 0])
    q1, S1 = optimal_rotation(b, a, np.ones(n), return_sensitivity=True)
    q2, S2 = optimal_rotation(b, a, 2 * np.ones(n), return_sensitivity=True)
    assert q1.same_rotation(q2, 1e-12)
    np.testing.assert_allclose(S1, S2, rtol=1e-12)


@pytest.mark.parametrize("c", [1e300, 1e154, 1e-160, 1e-300, 5e-324])
def test_extreme_weight_scales_change_nothing(c):
    """Only the weights' ratios count: constant weights of any finite positive size give
    the unweighted rotation, translation and sensitivity.  (r_j w_j overflowed for 1e300,
    zeta ~ w^3 for 1e154 gave a NaN sensitivity, 1e-160 an infinite one, and 5e-324
    rounded the weighted points to a different rotation.)"""
    rng = np.random.default_rng(11)
    R = rng.normal(size=(7, 3))
    G = Rotation.random(rng=3).apply(R) + 0.01 * rng.normal(size=(7, 3))
    w = np.full(7, c)
    q0, S0 = optimal_rotation(R, G, return_sensitivity=True)
    q1, S1 = optimal_rotation(R, G, w, return_sensitivity=True)
    assert q1.same_rotation(q0, 1e-12)
    np.testing.assert_allclose(S1, S0, rtol=1e-12, atol=0)
    m0, T0 = register(R, G, return_sensitivity=True)
    m1, T1 = register(R, G, w, return_sensitivity=True)
    assert m1.isclose(m0, 1e-12)
    np.testing.assert_allclose(T1, T0, rtol=1e-12, atol=0)


@pytest.mark.parametrize("c", [1e100, 1e150, 1e-100, 1e-150])
def test_sensitivity_of_huge_and_tiny_coordinates(c):
    """S is homogeneous of degree -1 in M = Σ r gᵀ, so scaling both sets by c divides it
    by c²; it was NaN (zeta ~ s³ overflowed) or infinite (underflowed)."""
    rng = np.random.default_rng(12)
    R = rng.normal(size=(6, 3))
    G = Rotation.random(rng=4).apply(R) + 0.01 * rng.normal(size=(6, 3))
    _, S0 = optimal_rotation(R, G, return_sensitivity=True)
    q, S = optimal_rotation(R * c, G * c, return_sensitivity=True)
    np.testing.assert_allclose(S * c * c, S0, rtol=1e-12, atol=0)


def test_scipy_noise_case_and_the_sensitivity_is_the_covariance():
    """scipy's test_align_vectors_noise, then a Monte Carlo check of what the matrix means:
    the covariance of the error's rotation vector is σ² S (in the frame of G)."""
    rng = np.random.default_rng(146972845698875399755764481408308808739)
    n = 100
    rot = Rotation.random(rng=rng)
    vectors = rng.normal(size=(n, 3))
    result = rot.apply(vectors)
    sigma = np.deg2rad(1)
    noisy = Rotation.from_rotvec(rng.normal(size=(n, 3), scale=sigma)).apply(result)
    q, S = optimal_rotation(vectors, noisy, return_sensitivity=True)
    est = Rotation.from_quat(q.as_array()[[1, 2, 3, 0]])
    assert np.all(np.abs((rot * est.inv()).as_rotvec()) < 1.5 * sigma)
    assert np.all(np.abs(np.diag(S) * sigma) < 1.5 * sigma)
    # Monte Carlo: isotropic noise of std s on G, weights w_j ∝ 1/var_j
    rng = np.random.default_rng(4)
    R = rng.normal(size=(30, 3)) * [3, 2, 1]
    w = rng.uniform(0.5, 2, 30)
    q_true = random_rotation(rng)
    s = 1e-3
    errs = []
    for _ in range(2000):
        G = q_true.rotate(R) + rng.normal(size=R.shape) * (s / np.sqrt(w))[:, None]
        q = optimal_rotation(R, G, w)
        errs.append((q_true * q.conjugate()).to_rotation_vector())
    cov = np.cov(np.array(errs).T)
    _, S = optimal_rotation(R, q_true.rotate(R), w, return_sensitivity=True)
    # SciPy: covariance = S times the harmonic mean of the variances s²/w_j, i.e. s²/mean(w)
    # (the radial part of isotropic noise does not move the rotation)
    h = len(w) / np.sum(w / s**2)
    np.testing.assert_allclose(cov, h * S, atol=0.1 * h * np.abs(S).max())
    assert not np.allclose(cov, s**2 * S, atol=0.1 * h * np.abs(S).max())  # the mean weight matters


def test_scipy_no_rotation_no_noise_and_improper_cases():
    x = np.array([[1.0, 2, 3], [4, 5, 6]])
    assert optimal_rotation(x, x.copy()).isclose(Quaternion(1.0), 1e-12)
    rng = np.random.default_rng(14697284569885399755764481408308808739)
    c = Rotation.random(rng=rng)
    b = rng.normal(size=(5, 3))
    q = optimal_rotation(b, c.apply(b))
    np.testing.assert_allclose(q.to_matrix(), c.as_matrix(), atol=1e-12)
    x = np.array([[0.89299824, -0.44372674, 0.0752378], [0.60221789, -0.47564102, -0.6411702]])
    y = np.array([[0.02386536, -0.82176463, 0.5693271], [-0.27654929, -0.95191427, -0.1318321]])
    np.testing.assert_allclose(optimal_rotation(y, x).rotate(y), x, atol=1e-6)  # issue #10444


@pytest.mark.parametrize(
    "weights, exc, words",
    [
        ([1.0, -1.0, 1.0], ValueError, r"weights must be non-negative, got weights\[1\] = -1.0"),
        ([1.0, 1.0], ValueError, r"weights must have one value per point pair \(3\), got 2"),
        ([[1.0, 1.0, 1.0]], ValueError, "weights must be a 1-D array"),
        ([0.0, 0.0, 0.0], ValueError, "weights must not all be zero"),
        ([1.0, np.nan, 1.0], ValueError, "weights must be finite"),
        ([1.0, np.inf, 1.0], ValueError, "weights must be finite"),
        ("abc", TypeError, "weights"),
    ],
)
def test_bad_weights_name_the_argument(weights, exc, words):
    R = np.eye(3)
    for f in (optimal_rotation, register):
        with pytest.raises(exc, match=words):
            f(R, R, weights)


def test_sensitivity_of_a_degenerate_optimum_is_refused():
    # scipy: "Cannot return sensitivity matrix with an infinite weight or one vector pair"
    with pytest.raises(ValueError, match="sensitivity matrix is undefined"):
        optimal_rotation([[1.0, 2, 3]], [[1.0, 2, 3]], return_sensitivity=True)
    with pytest.raises(ValueError, match="sensitivity matrix is undefined"):
        register(np.outer([1.0, 2, 3], [1, 1, 0]), np.outer([1.0, 2, 3], [0, 1, 1]), return_sensitivity=True)


# ----------------------------------------------------------------- the smallest optimal rotation


def smallest_turn(u, v):
    """The rotation of smallest angle taking direction u to direction v, written out:
    about u × v by the angle between them (None when opposite: not unique)."""
    u, v = u / np.linalg.norm(u), v / np.linalg.norm(v)
    axis = np.cross(u, v)
    angle = np.arctan2(np.linalg.norm(axis), u @ v)
    if np.linalg.norm(axis) < 1e-15:
        return Quaternion(1.0) if u @ v > 0 else None
    return Quaternion.from_axis_angle(axis, angle)


@SET
@given(seeds, st.integers(1, 7))
def test_degenerate_input_gives_the_smallest_optimal_rotation(seed, n):
    rng = np.random.default_rng(seed)
    u, v = rng.normal(size=3), rng.normal(size=3)
    R = np.outer(rng.uniform(0.5, 3, n), u)  # on a line through the origin
    G = np.outer(rng.uniform(0.5, 3, n), v)
    with pytest.warns(DegenerateRotationWarning, match="smallest angle"):
        q = optimal_rotation(R, G)
    assert q.same_rotation(smallest_turn(u, v), 1e-9)
    # every rotation spun about the target line is optimal too, and none is smaller
    for phi in np.linspace(-np.pi, np.pi, 13):
        other = Quaternion.from_axis_angle(v, phi) * q
        assert np.isclose(cost(other, R, G), cost(q, R, G), rtol=1e-9, atol=1e-9)
        assert other.angle_to(Quaternion(1.0)) >= q.angle_to(Quaternion(1.0)) - 1e-12
    if n == 1:  # SciPy's align_vectors on one pair is the same smallest turn
        scipy_rot, _ = Rotation.align_vectors(G, R)
        np.testing.assert_allclose(q.to_matrix(), scipy_rot.as_matrix(), atol=1e-9)


def test_scipy_parallel_and_primary_only_cases():
    """scipy's test_align_vectors_parallel and _primary_only (one pair), swapped."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegenerateRotationWarning)
        q = optimal_rotation([[0.0, 1, 0]], [[1.0, 0, 0]])
        np.testing.assert_allclose(q.to_matrix(), [[0, 1, 0], [-1, 0, 0], [0, 0, 1]], atol=1e-12)
        assert optimal_rotation([[1.0, 0, 0]], [[1.0, 0, 0]]) == Quaternion(1.0)
        mats_a = Rotation.random(100, rng=0).as_matrix()
        mats_b = Rotation.random(100, rng=1).as_matrix()
        for ma, mb in zip(mats_a, mats_b):
            a, b = ma[0], mb[0]
            q = optimal_rotation([b], [a])
            np.testing.assert_allclose(q.rotate(b), a, atol=1e-12)
            np.testing.assert_allclose(q.to_matrix(), Rotation.align_vectors(a, b)[0].as_matrix(), atol=1e-12)


def test_opposite_directions_give_a_half_turn():
    with pytest.warns(DegenerateRotationWarning):
        q = optimal_rotation([[1.0, 2, 3]], [[-2.0, -4, -6]])
    assert np.isclose(q.angle_to(Quaternion(1.0)), np.pi)
    np.testing.assert_allclose(q.rotate([1.0, 2, 3]), [-1.0, -2, -3], atol=1e-12)


@pytest.mark.parametrize("n", [1, 2, 5])
def test_register_of_a_set_onto_itself_is_the_identity(n):
    rng = np.random.default_rng(n)
    X = np.outer(rng.normal(size=n), [1.0, -2.0, 0.5]) + [3.0, 1.0, -2.0]  # collinear
    with pytest.warns(DegenerateRotationWarning):
        m = register(X, X)
    assert m.rotation == Quaternion(1.0)
    np.testing.assert_allclose(m.translation, 0.0, atol=1e-14)
    with pytest.warns(DegenerateRotationWarning):
        m = register(X, X + [1.0, 2.0, 3.0])  # a pure translation stays one
    assert m.rotation == Quaternion(1.0)
    np.testing.assert_allclose(m.translation, [1.0, 2.0, 3.0], atol=1e-13)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegenerateRotationWarning)
        assert optimal_rotation([[1.0, 0, 0]], [[1.0, 0, 0]]) == Quaternion(1.0)


def test_mirror_image_with_equal_singular_values_gives_the_smallest_optimal_rotation():
    """Not collinear, yet not unique: G = R mirrored in z with R's spread equal in y and z
    gives M = diag(4, 1, -1), for which tr(X M) = 4 for every rotation X about x, so the
    identity is optimal and the smallest.  Moved by P and followed by Q, the optimal set
    is Q·(rotations about P x): brute force over that circle."""
    R = np.array([[2.0, 0, 0], [0, 1, 0], [0, 0, 1]])
    G = R * [1, 1, -1]
    with pytest.warns(DegenerateRotationWarning, match="mirrors"):
        q = optimal_rotation(R, G)
    assert q.same_rotation(Quaternion.identity(), 1e-12)
    P = Rotation.random(rng=3).as_matrix()
    Q = Rotation.from_rotvec([0.3, 0.2, -0.1]).as_matrix()
    with pytest.warns(DegenerateRotationWarning):
        q = optimal_rotation(R @ P.T, G @ P.T @ Q.T)
    phi = np.linspace(-np.pi, np.pi, 200_001)
    circle = Rotation.from_matrix(Q @ Rotation.from_rotvec(np.outer(phi, P[:, 0])).as_matrix())
    assert q.to_axis_angle()[1] <= circle.magnitude().min() + 1e-9
    cost = np.sum((R @ P.T @ q.to_matrix().T - G @ P.T @ Q.T) ** 2)
    assert cost == pytest.approx(np.sum((R @ P.T @ Q.T - G @ P.T @ Q.T) ** 2), abs=1e-12)


def test_coplanar_and_unique_optima_are_unchanged():
    """Where λ1 > λ2 the answer is the top eigenvector of A exactly as before (bit for bit)."""
    rng = np.random.default_rng(31)
    for P in (rng.normal(size=(10, 3)) * [1, 1, 0], rng.normal(size=(20, 3))):
        G = random_rotation(rng).rotate(P) + 0.01 * rng.normal(size=P.shape)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            q = optimal_rotation(P, G)
        lam, vec = np.linalg.eigh(horn_matrix(P, G))
        top = vec[:, 3] if vec[0, 3] >= 0 else -vec[:, 3]
        assert np.array_equal(q.as_array(), top / np.linalg.norm(top))
        np.testing.assert_allclose(q.to_matrix(), Rotation.align_vectors(G, P)[0].as_matrix(), atol=1e-9)
