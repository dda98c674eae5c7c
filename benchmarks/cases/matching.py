"""Hausdorff distance of 10⁶ × 10⁶ points in 3D against scipy (issue 3).

Data: two independent samples of the unit sphere, 10⁶ points each, uniform in
direction with isotropic Gaussian noise σ = 0.01, seeded; in the "apart" regime
the second sample is shifted by 3 along x.

Ours: :func:`shapelab.hausdorff` (one adaptive algorithm for both regimes: grid
levels with cell bounds when the sets are apart; when the first level shows they
overlap, batched early break switching to a bounded k-d tree).  The cold call
includes the import of each side's modules (``scipy.spatial`` for both peers;
ours imports it only when a tree is needed).

Peers: the issue asks for "no slower than the faster of scipy's
``directed_hausdorff`` (both directions) and a two-way ``cKDTree`` query, in both
regimes", and states which is faster in each (k-d tree when the samples
overlap, early break when they are apart).  Each regime therefore has one case
against that faster peer:

* ``hausdorff_sphere_overlap_1e6``: two-way ``cKDTree(B).query(A)`` and
  ``cKDTree(A).query(B)`` (default construction, ``workers=-1``);
* ``hausdorff_sphere_apart_1e6``: ``max(directed_hausdorff(A, B)[0],
  directed_hausdorff(B, A)[0])`` (scipy's early break, default seed 0).

The slower peer of each regime is not a repeated case: the issue states it is
5-250 times slower (early break with overlap ~18 s, k-d tree apart ~150 s on
its machine), and five processes each running it twice (warm-up + timed call)
would take about an hour.  It is measured once, outside the harness, with
``python -m benchmarks.cases.matching --slow-peers`` (the k-d tree of the apart
regime is extrapolated from 2·10⁴ queries, disclosed as such).
"""

from __future__ import annotations

import numpy as np

from benchmarks.harness import Case


def setup(seed, n=1_000_000, shift=0.0, noise=0.01):
    rng = np.random.default_rng(seed)

    def sample():
        x = rng.standard_normal((n, 3))
        x /= np.linalg.norm(x, axis=1, keepdims=True)
        return x + noise * rng.standard_normal((n, 3))

    A = sample()
    B = sample()
    B[:, 0] += shift
    return A, B


def ours(data):
    from shapelab import hausdorff

    A, B = data
    return hausdorff(A, B)


def peer_kdtree(data):
    from scipy.spatial import cKDTree

    A, B = data
    hab = cKDTree(B).query(A, k=1, workers=-1)[0].max()
    hba = cKDTree(A).query(B, k=1, workers=-1)[0].max()
    return float(max(hab, hba))


def peer_early_break(data):
    from scipy.spatial.distance import directed_hausdorff

    A, B = data
    return float(max(directed_hausdorff(A, B)[0], directed_hausdorff(B, A)[0]))


def check(ours_result, peer_result) -> str:
    if ours_result == peer_result:
        return f"H = {ours_result:.12g}, equal to the last bit"
    rel = abs(ours_result - peer_result) / max(abs(peer_result), 1e-300)
    tag = "MISMATCH: " if rel > 1e-12 else ""
    return f"{tag}H = {ours_result:.12g}, peer {peer_result:.12g}, rel. diff {rel:.1e}"


CASES = [
    Case(
        name="hausdorff_sphere_overlap_1e6",
        module="matching",
        peer_name="scipy cKDTree two-way query (faster peer when overlapping)",
        target=1.0,
        repeats=5,
        params={"shift": 0.0},
        ladder=(10_000, 30_000, 100_000, 300_000, 1_000_000),
        peer="peer_kdtree",
        check="check",
        description="H of two noisy unit-sphere samples, 10⁶ points each, overlapping",
    ),
    Case(
        name="hausdorff_sphere_apart_1e6",
        module="matching",
        peer_name="scipy directed_hausdorff both ways (faster peer when apart)",
        target=1.0,
        repeats=5,
        params={"shift": 3.0},
        ladder=(10_000, 30_000, 100_000, 300_000, 1_000_000, 3_000_000),
        peer="peer_early_break",
        check="check",
        description="H of two noisy unit-sphere samples, 10⁶ points each, 3 units apart",
    ),
]


def _slow_peers() -> None:  # pragma: no cover - a one-off measurement
    """Time the slower peer of each regime once (see the module docstring)."""
    import time

    from scipy.spatial import cKDTree
    from scipy.spatial.distance import directed_hausdorff

    A, B = setup(0, shift=0.0)
    t0 = time.perf_counter()
    directed_hausdorff(A, B)
    directed_hausdorff(B, A)
    print(f"overlap, scipy early break (both ways, one run): {time.perf_counter() - t0:.1f} s")
    A, B = setup(0, shift=3.0)
    k = 20_000
    total = 0.0
    for X, Y in ((A, B), (B, A)):
        t0 = time.perf_counter()
        tree = cKDTree(Y)
        build = time.perf_counter() - t0
        t0 = time.perf_counter()
        tree.query(X[:k], k=1, workers=-1)
        total += build + (time.perf_counter() - t0) * len(X) / k
    print(f"apart, cKDTree two-way (extrapolated from {k} queries per direction): {total:.0f} s")


if __name__ == "__main__":  # pragma: no cover
    import sys

    if "--slow-peers" in sys.argv:
        _slow_peers()
