"""Regenerate the shipped example PDB file, ``shapelab/data/globule.pdb`` (maintainers only).

    python -m course.example_pdb            # rewrite shapelab/data/globule.pdb
    python -m course.example_pdb OUT.pdb    # write it elsewhere

The file is ``shapelab.datasets.globule_structure(seed=0)`` written with
``shapelab.io.write_pdb``; ``tests/library/test_datasets.py`` checks that the shipped file still
reads back as that structure.
"""

from __future__ import annotations

import sys
from pathlib import Path

from shapelab.datasets import example_pdb, globule_structure
from shapelab.io import write_pdb


def write(path=None) -> Path:
    s = globule_structure(seed=0)
    path = example_pdb() if path is None else Path(path)
    return write_pdb(
        path,
        s.balls,
        s.elements,
        atom_names=s.atom_names,
        residue_names=s.residue_names,
        residue_numbers=s.residue_numbers,
        chains=s.chains,
        title="shapelab globule, datasets.globule_structure(seed=0)",
    )


if __name__ == "__main__":
    print(write(sys.argv[1] if len(sys.argv) > 1 else None))
