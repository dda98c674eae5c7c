"""Write shapelab/data/gudhi_reference.json: GUDHI's diagrams of the lessons' inputs.

    python -m course.peer_values

GUDHI is not a requirement of the course (it has no wheel for Linux ARM64, and at
3.13 its macOS wheels need macOS 14), so :mod:`shapelab.peers` falls back on these values when it
is not installed.  Run this with GUDHI installed (the ``test`` extra) after changing
a lesson's input; ``tests/library/test_peers.py`` checks the file against GUDHI.
"""

from __future__ import annotations

import json
import sys
from datetime import date
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TARGET = ROOT / "shapelab" / "data" / "gudhi_reference.json"

#: (kind, recipe of the points, params): the inputs of lesson 19's cross-check
INPUTS = [
    ("delaunay_cech", ("torus", 400, 5), {}),
    ("voxels", ("torus", 400, 5), {"side": 0.05, "pad": 0.7}),
]


def main() -> int:
    import gudhi

    from shapelab import peers
    from shapelab.datasets import sample_shape

    entries = []
    for kind, (shape, n, seed), params in INPUTS:
        X = sample_shape(shape, n, seed=seed)
        got = peers.delaunay_cech_diagrams(X) if kind == "delaunay_cech" else peers.voxel_diagrams(X, **params)
        assert got.computed
        entries.append(
            {
                "kind": kind,
                "input": f"shapelab.datasets.sample_shape({shape!r}, {n}, seed={seed})",
                "params": params,
                "points": X.tolist(),
                "diagrams": {str(p): D.tolist() for p, D in got.diagrams.items()},
            }
        )
    data = {
        "what": "persistence diagrams over Z/2 computed by GUDHI for the inputs of lesson 19 (shapelab.peers)",
        "gudhi_version": gudhi.__version__,
        "command": "python -m course.peer_values",
        "date": date.today().isoformat(),
        "entries": entries,
    }
    TARGET.write_text(json.dumps(data, allow_nan=True) + "\n", encoding="utf-8")
    print(f"{TARGET.relative_to(ROOT)}: {len(entries)} entries, GUDHI {gudhi.__version__}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
