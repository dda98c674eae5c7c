"""Area of a union of balls: the short inclusion–exclusion formula against freesasa
(issue 4).

Data: 5,000 balls at protein-like density, centres uniform in a cube of side
1.5·N^(1/3), radii uniform in [1.2, 1.9], seeded.  Ours: ``union_measure(balls)``,
which *includes* building the α-filtration (the dual complex is part of the method,
so this is the fair comparison).  Peer: freesasa's Lee–Richards algorithm at 100
slices per atom, probe radius 0 (so that it measures the same union of balls), one
thread.  The accuracy note compares the two surface areas: ours is exact to
round-off, Lee–Richards has a discretisation error.

``union_measure_vs_voronota`` (issue 25): the SA balls of real assemblies (rotated
copies of 1hvr, probe 1.4 Å) against Voronota-LT, the other exact code (radical
tessellation in C++); the check asks for the same area and volume to 1e-9 and the
ladder runs from 1,560 to 199,680 atoms.  ``python -m benchmarks.measure_peers``
adds freesasa and zsasa with an accuracy column.
"""

from __future__ import annotations

import numpy as np

from benchmarks.harness import Case


def setup(seed, n=5_000):
    rng = np.random.default_rng(seed)
    side = 1.5 * n ** (1.0 / 3.0)
    centers = rng.uniform(0.0, side, size=(n, 3))
    radii = rng.uniform(1.2, 1.9, size=n)
    return centers, radii


def ours(data):
    from shapelab import Balls, union_measure

    centers, radii = data
    return union_measure(Balls(centers, radii))


def peer(data):
    import freesasa

    freesasa.setVerbosity(freesasa.silent)
    centers, radii = data
    params = freesasa.Parameters(
        {"algorithm": freesasa.LeeRichards, "n-slices": 100, "probe-radius": 0.0, "n-threads": 1}
    )
    return freesasa.calcCoord(centers.ravel(), radii, params)


def check(ours_result, peer_result) -> str:
    ours_area = ours_result.surface_area
    theirs = peer_result.totalArea()
    per_ball = np.array([peer_result.atomArea(i) for i in range(len(ours_result.ball_boundary))])
    worst = np.max(np.abs(ours_result.ball_boundary - per_ball))
    # Lee-Richards at 100 slices is good to ~1e-4 relative in total area
    tag = "MISMATCH: " if abs(ours_area - theirs) > 1e-3 * theirs else ""
    return (
        f"{tag}surface area ours {ours_area:.6f} vs freesasa LR(100) {theirs:.6f}: "
        f"rel diff {abs(ours_area - theirs) / theirs:.1e}; worst per-ball diff {worst:.1e} Å²; "
        f"our volume {ours_result.volume:.3f}"
    )


CASES = [
    Case(
        name="union_measure_3d_5000",
        module="measure",
        peer_name="freesasa Lee-Richards (100 slices, probe 0, 1 thread)",
        target=0.5,
        params={"n": 5_000},
        check="check",
        ladder=(500, 1_000, 2_000, 5_000, 20_000),
        description="surface area + volume of 5,000 balls at protein-like density, filtration included",
    ),
]


# --------------------------------------------------------------------------------------
# The exact union measure against Voronota-LT (issue 25, items 1 and 4; issue 24's
# scaling curves): the same SA balls of real assemblies, one thread each.
def setup_assembly(seed, atoms=24_960):
    """SA balls (Bondi + 1.4 Å) of ``atoms / 1560`` rotated copies of 1hvr
    (:func:`benchmarks.cases.report.assembly`, the rungs of report_scaling)."""
    from benchmarks.cases.report import assembly

    return assembly(seed, atoms).balls


def ours_sa(balls):
    from shapelab import union_measure

    return union_measure(balls)


def peer_voronota(balls):
    """Voronota-LT's radical tessellation of the vdW balls with probe 1.4 (the same SA
    balls; the Python bindings are not built with OpenMP: one thread).  Building its
    list of balls from the arrays is timed too (what a Python caller pays); the area
    and volume are summed from the cells while the tessellation, which owns them, is
    alive."""
    import voronotalt

    vdw = balls.radii - 1.4
    bl = [voronotalt.Ball(x, y, z, r) for (x, y, z), r in zip(balls.centers.tolist(), vdw.tolist())]
    rt = voronotalt.RadicalTessellation(bl, probe=1.4)
    cells = rt.cells
    return np.array([c.sas_area for c in cells]), np.array([c.volume for c in cells])


def check_voronota(ours_result, peer_result) -> str:
    area, vol = peer_result
    ra = abs(ours_result.surface_area - area.sum()) / ours_result.surface_area
    rv = abs(ours_result.volume - vol.sum()) / ours_result.volume
    worst = float(np.max(np.abs(ours_result.ball_boundary - area)))
    tag = "MISMATCH: " if max(ra, rv) > 1e-9 else ""
    return (
        f"{tag}area ours {ours_result.surface_area:.6f} vs Voronota-LT {area.sum():.6f} (rel {ra:.1e}), "
        f"volume rel {rv:.1e}, worst per-atom area diff {worst:.1e} Å²"
    )


CASES.append(
    Case(
        name="union_measure_vs_voronota",
        module="measure",
        peer_name="Voronota-LT (voronotalt, exact, 1 thread)",
        target=1.0,
        params={"atoms": 24_960},
        setup="setup_assembly",
        ours="ours_sa",
        peer="peer_voronota",
        check="check_voronota",
        ladder=(1_560, 6_240, 24_960, 99_840, 199_680),
        ladder_param="atoms",
        description="exact SASA + volume of 16 rotated copies of 1hvr (SA balls, probe 1.4); ladder 10^3..2*10^5",
    )
)
