"""The whole cavity report (issue: shapelab.report) against freesasa's Lee–Richards.

Data: the largest shipped protein, 1fmo (protein kinase A with its inhibitor,
heavy atoms, HETATM kept; ``1fmo-kvfinder`` is larger but holds KVFinder's cavity
points, not a molecule), SA radii = Bondi + 1.4 Å.  Ours: ``shapelab.report(s, 1.4)``
-- the α-filtration, voids and pockets, exact SA and vdW volumes and areas of every
cavity, mouths and lining atoms.  Peer: freesasa's Lee–Richards at 100 slices per
atom on the same balls (vdW radii, probe 1.4, one thread), the usual first step of a
solvent-accessibility report.  The two compute different things; the ratio says
what the full report costs next to one SASA run.
"""

from __future__ import annotations

from benchmarks.harness import Case


def setup(seed, name="1fmo"):
    from shapelab.datasets import structure

    return structure(name)


def assembly(seed, atoms=1560, base="1hvr"):
    """An assembly of about ``atoms`` heavy atoms: copies of the shipped protein
    ``base`` (1hvr, 1560 atoms) on a cubic grid, 2 Å apart at their bounding spheres,
    each turned by a random rotation (seeded).  Translated copies alone are not used:
    their hull facets come out parallel, the exact certificate of the triangulation
    rejects Qhull's answer ("the boundary is not convex") and the exact incremental
    algorithm (ten times slower) is timed instead of the report.  Returns a
    :class:`~shapelab.io.PDBStructure` whose labels are those of the copies."""
    import dataclasses

    import numpy as np
    from scipy.spatial.transform import Rotation

    from shapelab import Balls
    from shapelab.datasets import structure

    s = structure(base)
    c = s.balls.centers - s.balls.centers.mean(0)
    k = max(1, round(atoms / len(c)))
    step = 2.0 * float(np.sqrt((c * c).sum(1)).max()) + 2.0
    side = int(np.ceil(k ** (1 / 3) - 1e-9))
    grid = np.array([(i, j, m) for i in range(side) for j in range(side) for m in range(side)][:k], float) * step
    rng = np.random.default_rng(seed)
    parts = [c] + [c @ Rotation.random(random_state=rng).as_matrix().T + o for o in grid[1:]]
    balls = Balls(np.concatenate(parts), np.tile(s.balls.radii, k))
    per_atom = {
        f.name: np.tile(getattr(s, f.name), k)
        for f in dataclasses.fields(s)
        if isinstance(getattr(s, f.name), np.ndarray) and len(getattr(s, f.name)) == len(c)
    }
    return dataclasses.replace(s, balls=balls, **per_atom)


def ours(s):
    import shapelab

    return shapelab.report(s, 1.4)


def peer(s):
    import freesasa

    freesasa.setVerbosity(freesasa.silent)
    params = freesasa.Parameters(
        {"algorithm": freesasa.LeeRichards, "n-slices": 100, "probe-radius": 1.4, "n-threads": 1}
    )
    return freesasa.calcCoord(s.balls.centers.ravel(), s.balls.radii - s.probe, params)


def check(ours_result, peer_result) -> str:
    v = ours_result.voids
    p = ours_result.pockets
    return (
        f"{len(v)} voids (largest {max((r.volume_sa for r in v), default=0):.2f} Å³ SA), "
        f"{len(p)} pockets; freesasa LR(100) SASA {peer_result.totalArea():.1f} Å²"
    )


CASES = [
    Case(
        name="report_1fmo",
        module="report",
        peer_name="freesasa Lee-Richards (100 slices, probe 1.4, 1 thread)",
        target=3.0,
        check="check",
        description="full cavity report (voids, pockets, SA+vdW measures, mouths, lining) of 1fmo",
    ),
    Case(
        name="report_assembly",
        module="report",
        peer_name="freesasa Lee-Richards (100 slices, probe 1.4, 1 thread)",
        target=3.0,
        setup="assembly",
        params={"atoms": 24960},
        check="check",
        description="full cavity report of an assembly of 16 rotated copies of 1hvr (24,960 atoms)",
        ladder=(1560, 6240, 24960, 99840, 199680),
        ladder_param="atoms",
    ),
]
