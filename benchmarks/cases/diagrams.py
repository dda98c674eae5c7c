"""Distances between persistence diagrams (issue 14): ours against GUDHI, exact both.

Data: the H1 diagrams of two random ball sets (500 balls each, about 1,000 points per diagram, radii in
[1.2, 1.9], the topology benchmark's generator with two seeds), built untimed in setup.

* ``bottleneck_h1_500``: :func:`shapelab.bottleneck_distance` against
  ``gudhi.bottleneck_distance(D1, D2, e=0)`` (exact).
* ``wasserstein_h1_500``: :func:`shapelab.wasserstein_distance` (p = 2, exact) against
  ``gudhi.hera.wasserstein_distance`` at a relative error of 1e-6 (the peer is
  approximate; the check allows that error).
"""

from __future__ import annotations

import numpy as np

from benchmarks.harness import Case


def setup(seed, n=2000):
    from shapelab import Balls, alpha_filtration

    out = []
    for k in range(2):
        rng = np.random.default_rng(2 * seed + k)
        side = 1.5 * n ** (1.0 / 3.0)
        b = Balls(rng.uniform(0.0, side, (n, 3)), rng.uniform(1.2, 1.9, n))
        D = np.asarray(alpha_filtration(b).persistence()[1], dtype=float)
        out.append(D[np.isfinite(D[:, 1]) & (D[:, 1] > D[:, 0])])
    return {"D1": out[0], "D2": out[1]}


def ours_bottleneck(data):
    from shapelab import bottleneck_distance

    return bottleneck_distance(data["D1"], data["D2"])


def peer_bottleneck(data):
    import gudhi

    return gudhi.bottleneck_distance(data["D1"], data["D2"], e=0)


def ours_wasserstein(data):
    from shapelab import wasserstein_distance

    return wasserstein_distance(data["D1"], data["D2"], p=2)


def peer_wasserstein(data):
    from gudhi.hera import wasserstein_distance

    return wasserstein_distance(data["D1"], data["D2"], order=2, internal_p=np.inf, delta=1e-6)


def check_exact(a, b) -> str:
    if a != b:
        raise AssertionError(f"bottleneck ours {a!r} != GUDHI {b!r}")
    return f"bottleneck {a:.6g}, equal to GUDHI's exact value"


def check_rel(a, b) -> str:
    if not abs(a - b) <= 1e-5 * max(abs(b), 1e-12):
        raise AssertionError(f"wasserstein ours {a!r} vs hera {b!r}")
    return f"W2 {a:.6g} vs hera {b:.6g} (rel diff {abs(a - b) / max(abs(b), 1e-300):.1e})"


CASES = [
    Case(
        name="bottleneck_h1_500",
        module="diagrams",
        peer_name="gudhi.bottleneck_distance(e=0)",
        target=None,
        params={"n": 500},
        ours="ours_bottleneck",
        peer="peer_bottleneck",
        check="check_exact",
        description="bottleneck distance between the H1 diagrams of two 500-ball sets",
    ),
    Case(
        name="wasserstein_h1_500",
        module="diagrams",
        peer_name="gudhi.hera.wasserstein_distance (delta 1e-6)",
        target=None,
        params={"n": 500},
        ours="ours_wasserstein",
        peer="peer_wasserstein",
        check="check_rel",
        description="2-Wasserstein distance between the H1 diagrams of two 500-ball sets",
    ),
]
