"""α-filtration of weighted balls against GUDHI's weighted AlphaComplex (issue 4).

Data: balls at protein-like density, centres uniform in a cube (square in 2D) of side
1.5·N^(1/d), radii uniform in [1.2, 1.9], seeded.  Peer:
``gudhi.AlphaComplex(points, weights=r**2).create_simplex_tree()`` at the default
precision ("safe").  Ours: :func:`shapelab.alpha_filtration`.
"""

from __future__ import annotations

import numpy as np

from benchmarks.harness import Case


def setup(seed, n=10_000, dim=3):
    rng = np.random.default_rng(seed)
    side = 1.5 * n ** (1.0 / dim)
    centers = rng.uniform(0.0, side, size=(n, dim))
    radii = rng.uniform(1.2, 1.9, size=n)
    return centers, radii


def ours(data):
    from shapelab import Balls, alpha_filtration

    centers, radii = data
    return alpha_filtration(Balls(centers, radii))


def peer(data):
    import gudhi

    centers, radii = data
    return gudhi.AlphaComplex(points=centers, weights=radii**2).create_simplex_tree()


def check(ours_result, peer_result) -> str:
    """Simplex counts per dimension must agree; values are compared on the vertices
    and on the top-dimensional simplices by a sorted-multiset comparison."""
    F, st = ours_result, peer_result
    ours_counts = F.counts()
    theirs = [0] * (st.dimension() + 1)
    top_vals = []
    vert_vals = []
    for s, f in st.get_filtration():
        k = len(s) - 1
        theirs[k] += 1
        if k == st.dimension():
            top_vals.append(f)
        elif k == 0:
            vert_vals.append(f)
    if tuple(theirs) != ours_counts:
        return f"MISMATCH: counts ours {ours_counts} gudhi {tuple(theirs)}"
    errs = []
    for mine, their in ((F.values(0), vert_vals), (F.values(F.dimension), top_vals)):
        their = np.sort(np.asarray(their))
        errs.append(np.max(np.abs(np.sort(mine) - their) / np.maximum(1.0, np.abs(their))))
    # GUDHI's default ("safe") precision is itself off by up to ~5e-7 on these inputs
    # (python -m benchmarks.accuracy), so 1e-6 is the tolerance
    tag = "MISMATCH: " if max(errs) > 1e-6 else ""
    return f"{tag}counts equal {ours_counts}; max rel err (sorted values, dims 0 and top) {max(errs):.1e}"


CASES = [
    Case(
        name="alpha_filtration_3d_1e4",
        module="filtration",
        peer_name="gudhi AlphaComplex(weights).create_simplex_tree",
        target=1.0,
        memory_target=1.5,
        params={"n": 10_000, "dim": 3},
        check="check",
        ladder=(1_000, 3_000, 10_000, 30_000, 100_000),
        description="3D weighted alpha filtration, 1e4 balls at protein-like density",
    ),
    Case(
        name="alpha_filtration_3d_1e5",
        module="filtration",
        peer_name="gudhi AlphaComplex(weights).create_simplex_tree",
        target=1.0,
        memory_target=1.5,
        params={"n": 100_000, "dim": 3},
        check="check",
        description="3D weighted alpha filtration, 1e5 balls at protein-like density",
    ),
    Case(
        name="alpha_filtration_2d_1e6",
        module="filtration",
        peer_name="gudhi AlphaComplex(weights).create_simplex_tree",
        target=1.0,
        params={"n": 1_000_000, "dim": 2},
        check="check",
        ladder=(10_000, 30_000, 100_000, 300_000),
        description="2D weighted alpha filtration, 1e6 disks at the analogous density",
    ),
]
