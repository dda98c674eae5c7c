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
]
