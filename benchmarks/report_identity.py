"""Are the report's tables unchanged by a change?  (issue 24, item 2)

``python -m benchmarks.report_identity OLD_CHECKOUT [--file PDB ...]``

Writes the CSV and Markdown of :func:`shapelab.report` (probe 1.4 Å) for the globule
(``shapelab.datasets.globule_structure``), 1hvr, t4l-l99a, 3mht and 1fmo -- and any
``--file`` read with :func:`shapelab.io.read_structure` -- once with the shapelab of
``OLD_CHECKOUT`` (e.g. ``git worktree add /tmp/old HEAD`` before a change) and once
with this one, each in a fresh process, and compares them byte for byte.  Exit status
0 when every file is identical, 1 otherwise (the differing files are named).

``--rank none`` (or ``score``) passes ``rank=`` to every checkout whose report takes
it: since the report ranks by default, ``--rank none`` compares the unfiltered
table of CASTp's order with that of a checkout from before the ranking.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

_DUMP = """
import inspect, os, sys, pathlib
import shapelab
from shapelab.datasets import globule_structure, structure
from shapelab.io import read_structure
out = pathlib.Path(sys.argv[1])
cases = {"globule": globule_structure()}
cases.update((n, structure(n)) for n in ("1hvr", "t4l-l99a", "3mht", "1fmo"))
cases.update((pathlib.Path(f).stem, read_structure(f)) for f in sys.argv[2:])
rank = os.environ.get("SHAPELAB_IDENTITY_RANK")
kw = dict(rank=rank) if rank and "rank" in inspect.signature(shapelab.report).parameters else {}
for name, s in cases.items():
    r = shapelab.report(s, 1.4, name=name, **kw)
    r.to_csv(out / f"{name}.csv")
    (out / f"{name}.md").write_text(r.to_markdown(), encoding="utf-8")
    print(name, len(r.rows), shapelab.__file__, file=sys.stderr)
"""


def _dump(tree: Path, out: Path, files: list[str], rank: str | None = None) -> None:
    env = dict(os.environ, PYTHONPATH=str(tree), SHAPELAB_IDENTITY_RANK=rank or "")
    subprocess.run([sys.executable, "-c", _DUMP, str(out), *files], check=True, cwd=tempfile.gettempdir(), env=env)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old", type=Path, help="checkout (worktree) of the commit to compare against")
    ap.add_argument("--file", nargs="*", default=[], help="more structure files to compare on")
    ap.add_argument(
        "--rank",
        choices=("none", "score"),
        help="pass rank= to the report of each checkout that has it (default: each checkout's own default)",
    )
    args = ap.parse_args(argv)
    files = [str(Path(f).resolve()) for f in args.file]
    with tempfile.TemporaryDirectory() as d:
        old, new = Path(d, "old"), Path(d, "new")
        old.mkdir()
        new.mkdir()
        _dump(args.old.resolve(), old, files, args.rank)
        _dump(ROOT, new, files, args.rank)
        names = sorted(p.name for p in old.iterdir())
        _, differ, missing = filecmp.cmpfiles(old, new, names, shallow=False)
    for name in differ + missing:
        print(f"DIFFERS: {name}")
    print(f"{len(names) - len(differ) - len(missing)} of {len(names)} files identical")
    return 1 if differ or missing else 0


if __name__ == "__main__":
    sys.exit(main())
