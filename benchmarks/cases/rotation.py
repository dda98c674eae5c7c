"""Rotations and ICP (issue 3, "Performance"): Horn's optimal rotation against SciPy,
and ICP against Open3D.

``optimal_rotation_1e6``
    ``shapelab.optimal_rotation(R, G)`` against ``scipy``'s
    ``Rotation.align_vectors(G, R)`` (SciPy rotates its *second* argument onto its
    first) on 10⁶ paired, centred, noisy points.  Target: ratio ≤ 0.2.

``icp_1e5``
    Wall time to bring a rotation error below 0.05°, ``shapelab.icp`` against
    Open3D's ``registration_icp`` (point-to-point).  Data: the non-symmetric
    "lumpy" closed surface of :func:`shapelab.datasets.sample_shape`, sampled
    twice independently with 10⁵ points each; the target is rotated 20° about
    (1, 2, 3)/√14 and shifted by (0.1, −0.05, 0.2).  Both sides use the same
    maximum correspondence distance (1.0, generous: the shape is ~2 units long and
    the largest initial displacement ~0.5) and the same stopping rule: **the
    smallest number of iterations whose result is within 0.05° of the true
    rotation**.  Neither side can test the error between iterations, so ``setup``
    finds that number for each side (Open3D by stepping it one iteration at a time —
    point-to-point ICP is memoryless, so k single steps equal one run of k steps —
    and shapelab from one run's recorded motions), and the timed call runs exactly
    that many iterations, tree construction included.  The calibration is cached in
    the temp directory (it takes ~100 Open3D iterations) and keyed by the data.

    Accuracy floor: with two independent samplings the exact ICP fixed point is not
    the true motion; here it lies ≈0.03° away (seed 0), so 0.05° is reachable by
    both sides.  If it were not, ``check`` reports "not reached" and the case is a
    miss, not a silent pass.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile

import numpy as np

from benchmarks.harness import Case

THRESHOLD_DEG = 0.05
AXIS = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
ANGLE_DEG = 20.0
SHIFT = np.array([0.1, -0.05, 0.2])
CAP = 400  # iterations: give up beyond this


# --------------------------------------------------------------------------- optimal rotation


def setup_rotation(seed: int = 0, n: int = 1_000_000):
    from shapelab import Quaternion

    rng = np.random.default_rng(seed)
    R = rng.normal(size=(n, 3)) * [3.0, 2.0, 1.0]
    R -= R.mean(axis=0)
    q = Quaternion(*rng.normal(size=4)).normalized()
    G = q.rotate(R) + 0.05 * rng.normal(size=R.shape)
    G -= G.mean(axis=0)
    return {"R": R, "G": G, "q": q}


def ours_rotation(data):
    from shapelab import optimal_rotation

    return optimal_rotation(data["R"], data["G"]).to_matrix()


def peer_rotation(data):
    from scipy.spatial.transform import Rotation

    rot, _ = Rotation.align_vectors(data["G"], data["R"])
    return rot.as_matrix()


def check_rotation(ours, peer) -> str:
    from shapelab import Quaternion

    deg = np.degrees(Quaternion.from_matrix(ours).angle_to(Quaternion.from_matrix(peer)))
    tag = "MISMATCH: " if deg > 1e-6 else ""
    return f"{tag}ours vs scipy rotation differ by {deg:.1e}°"


# --------------------------------------------------------------------------- ICP


def _truth():
    from shapelab import Quaternion, RigidMotion

    return RigidMotion(Quaternion.from_axis_angle(AXIS, np.radians(ANGLE_DEG)), SHIFT)


def _error_deg(matrix, truth) -> float:
    from shapelab import Quaternion

    return float(np.degrees(Quaternion.from_matrix(matrix[:3, :3], atol=1e-6).angle_to(truth.rotation)))


def _calibrate(src, tgt, max_distance, truth) -> dict:
    """Smallest iteration counts reaching THRESHOLD_DEG for both sides (cached)."""
    import open3d as o3d

    from shapelab import icp

    key = hashlib.sha1()
    for a in (src, tgt):
        key.update(np.ascontiguousarray(a).tobytes())
    key.update(f"{max_distance}|{THRESHOLD_DEG}|{CAP}|{o3d.__version__}|v2".encode())
    path = os.path.join(tempfile.gettempdir(), f"shapelab-bench-icp-{key.hexdigest()[:16]}.json")
    if os.path.exists(path):
        with open(path) as fh:
            return json.load(fh)

    res = icp(src, tgt, tol=0.0, max_iter=CAP, max_distance=max_distance)
    errs = [float(np.degrees(m.rotation.angle_to(truth.rotation))) for m in res.motions]
    k_ours = next((k for k, e in enumerate(errs) if e < THRESHOLD_DEG), None)

    reg = o3d.pipelines.registration
    ps = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(src))
    pt = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(tgt))
    T = np.eye(4)
    k_peer = None
    best = _error_deg(T, truth)
    for k in range(1, CAP + 1):
        T = reg.registration_icp(
            ps,
            pt,
            max_distance,
            T,
            reg.TransformationEstimationPointToPoint(),
            reg.ICPConvergenceCriteria(relative_fitness=0.0, relative_rmse=0.0, max_iteration=1),
        ).transformation
        best = min(best, _error_deg(T, truth))
        if _error_deg(T, truth) < THRESHOLD_DEG:
            k_peer = k
            break
    out = {"k_ours": k_ours, "k_peer": k_peer, "floor_ours": min(errs), "best_peer": best}
    with open(path, "w") as fh:
        json.dump(out, fh)
    return out


def setup_icp(seed: int = 0, n: int = 100_000, max_distance: float = 1.0):
    import open3d as o3d

    from shapelab.datasets import sample_shape

    truth = _truth()
    src = sample_shape("lumpy", n, seed=2 * seed + 1)
    tgt = truth.apply(sample_shape("lumpy", n, seed=2 * seed + 2))
    cal = _calibrate(src, tgt, max_distance, truth)
    return {
        "src": src,
        "tgt": tgt,
        "truth": truth,
        "max_distance": max_distance,
        "k_ours": cal["k_ours"] or CAP,
        "k_peer": cal["k_peer"] or CAP,
        "cal": cal,
        "pcd_src": o3d.geometry.PointCloud(o3d.utility.Vector3dVector(src)),
        "pcd_tgt": o3d.geometry.PointCloud(o3d.utility.Vector3dVector(tgt)),
    }


def ours_icp(data):
    from shapelab import icp

    res = icp(data["src"], data["tgt"], tol=0.0, max_iter=data["k_ours"], max_distance=data["max_distance"])
    return {
        "k": res.n_iter,
        "err": float(np.degrees(res.motion.rotation.angle_to(data["truth"].rotation))),
        "cal": data["cal"],
    }


def peer_icp(data):
    import open3d as o3d

    reg = o3d.pipelines.registration
    res = reg.registration_icp(
        data["pcd_src"],
        data["pcd_tgt"],
        data["max_distance"],
        np.eye(4),
        reg.TransformationEstimationPointToPoint(),
        reg.ICPConvergenceCriteria(relative_fitness=0.0, relative_rmse=0.0, max_iteration=data["k_peer"]),
    )
    return {"k": data["k_peer"], "err": _error_deg(res.transformation, data["truth"])}


def check_icp(ours, peer) -> str:
    def side(name, r):
        ok = "reached" if r["err"] < THRESHOLD_DEG else "NOT reached"
        return f"{name}: {r['k']} it, {r['err']:.4f}° ({ok})"

    tag = "MISMATCH: " if ours["err"] >= THRESHOLD_DEG else ""  # ours must reach the goal
    return f"{tag}{side('ours', ours)}; {side('open3d', peer)}; ours' fixed point {ours['cal']['floor_ours']:.4f}°"


CASES = [
    Case(
        name="optimal_rotation_1e6",
        module="rotation",
        peer_name="scipy Rotation.align_vectors",
        target=0.2,
        params={"n": 1_000_000},
        setup="setup_rotation",
        ours="ours_rotation",
        peer="peer_rotation",
        check="check_rotation",
        ladder=(10_000, 100_000, 1_000_000, 3_000_000),
        description="Horn's optimal rotation of 10^6 paired, centred, noisy points",
    ),
    Case(
        name="icp_1e5",
        module="rotation",
        peer_name="open3d registration_icp (point-to-point)",
        target=1.0,
        params={"n": 100_000, "max_distance": 1.0},
        setup="setup_icp",
        ours="ours_icp",
        peer="peer_icp",
        check="check_icp",
        description="ICP to < 0.05° on two independent 10^5-point samplings of a lumpy surface",
    ),
]
