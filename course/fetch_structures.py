"""Copy the shipped real structures into ``shapelab/data/`` from their PyPI packages.

Run once by a maintainer, never at test or run time (the course stays offline)::

    python -m course.fetch_structures            # fetch, compare with STRUCTURES.json
    python -m course.fetch_structures --write    # ... and write the files and hashes

For each entry of ``shapelab/data/STRUCTURES.json`` it downloads the source package
(``pip download --no-deps``, the exact version recorded; wheels only for pyKVFinder and
openmmtools, the sdist for MDAnalysisTests, which has no wheel), takes the recorded file
out of the archive, and gzips it reproducibly (``mtime=0``, no file name in the header,
level 9) as ``shapelab/data/<file>``.  The uncompressed bytes are the package's file,
byte for byte.  It records both hashes and the atom counts, which
``tests/library/test_datasets.py`` checks against an independent reading of each file.
The packages are *not* dependencies of shapelab.
"""

from __future__ import annotations

import argparse
import gzip
import hashlib
import json
import subprocess
import sys
import tarfile
import tempfile
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "shapelab" / "data"
TABLE = DATA / "STRUCTURES.json"
WATER = {"HOH", "WAT", "H2O", "DOD", "D2O", "TIP", "TIP3", "TIP4", "TIP5", "T3P", "T4P", "T5P", "SOL", "SPC", "SPCE"}


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def download(package: str, version: str, dest: Path) -> Path:
    subprocess.run(
        [sys.executable, "-m", "pip", "download", "--no-deps", "-d", str(dest), f"{package}=={version}"], check=True
    )
    name = package.lower().replace("-", "_")
    found = [p for p in dest.iterdir() if p.name.lower().replace("-", "_").startswith(f"{name}_{version}")]
    if len(found) != 1:
        raise SystemExit(f"expected one archive of {package} {version} in {dest}, found {found}")
    return found[0]


def member(archive: Path, path: str) -> bytes:
    """The file ``path`` (as laid out in the installed package) from a wheel or sdist."""
    if archive.suffix == ".whl":
        with zipfile.ZipFile(archive) as z:
            return z.read(path)
    with tarfile.open(archive) as t:
        for m in t.getmembers():
            if m.name.split("/", 1)[-1] == path:
                return t.extractfile(m).read()
    raise SystemExit(f"{path} not in {archive.name}")


def counts(text: str) -> dict:
    """Atom counts of the first model, by plain column slicing (as the tests do)."""
    n = {"records": 0, "hetatm": 0, "hydrogens": 0, "water": 0}
    for line in text.splitlines():
        rec = line[:6]
        if rec.startswith("END"):
            break
        if rec not in ("ATOM  ", "HETATM"):
            continue
        n["records"] += 1
        n["hetatm"] += rec == "HETATM"
        n["water"] += line[17:21].strip() in WATER
        element = line[76:78].strip() if len(line) > 76 else ""
        name = line[12:16]
        if element:
            n["hydrogens"] += element.upper() in ("H", "D")
        else:  # hydrogen names start with H (or a digit then H) in every convention used here
            n["hydrogens"] += name.strip().lstrip("0123456789")[:1] == "H"
    return n


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="write the files and update the hashes")
    args = ap.parse_args(argv)
    table = json.loads(TABLE.read_text())
    archives: dict = {}
    bad = 0
    with tempfile.TemporaryDirectory() as tmp:
        for entry in table["structures"]:
            src = entry["source"]
            key = (src["package"], src["version"])
            if key not in archives:
                archives[key] = download(*key, Path(tmp))
            raw = member(archives[key], src["path"])
            packed = gzip.compress(raw, compresslevel=9, mtime=0)
            new = {
                "sha256_original": sha256(raw),
                "size_original": len(raw),
                "sha256": sha256(packed),
                "size": len(packed),
                "atoms": counts(raw.decode("latin-1")),
            }
            old = {k: entry.get(k) for k in new}
            same = old == new
            print(
                f"{entry['name']:18} {src['path']:60} {len(raw):>7} -> {len(packed):>6} B  "
                f"{'same' if same else 'CHANGED'}"
            )
            if not same:
                bad += 1
            if args.write:
                (DATA / entry["file"]).write_bytes(packed)
                entry.update(new)
    if args.write:
        TABLE.write_text(json.dumps(table, indent=2, ensure_ascii=False) + "\n")
        return 0
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
