"""What ``import shapelab`` loads (issue 25, item 3: nothing is imported before it is needed).

Each check runs in a fresh interpreter (the test session has long imported everything)
and reads ``sys.modules`` after the import.  The packages listed are the heavy ones a
notebook, the command line or a batch only needs for some calls: plotting, widgets,
mmCIF, trajectories, clusters, progress bars, the peers.
"""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: never imported by ``import shapelab``
HEAVY = (
    "numpy",
    "scipy",
    "scipy.spatial",
    "scipy.sparse",
    "matplotlib",
    "gemmi",
    "biotite",
    "ipywidgets",
    "IPython",
    "MDAnalysis",
    "dask",
    "distributed",
    "tqdm",
    "gudhi",
    "freesasa",
    "pandas",
    "pyarrow",
)
#: only needed by figures, widgets, mmCIF, trajectories, clusters, peers
OPTIONAL = tuple(m for m in HEAVY if m not in ("numpy", "scipy", "scipy.spatial", "scipy.sparse"))


def _loaded(code: str) -> set[str]:
    """The modules of HEAVY present in sys.modules after running ``code`` in a fresh python."""
    probe = f"{code}\nimport sys, json\nprint(json.dumps([m for m in {list(HEAVY)!r} if m in sys.modules]))"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("MPLBACKEND", None)
    r = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return set(json.loads(r.stdout.strip().splitlines()[-1]))


def test_import_shapelab_imports_nothing_heavy():
    assert _loaded("import shapelab") == set()


def test_the_top_level_names_stay_lazy():
    """Listing the package (dir, __all__, the version) does not import what the names hold."""
    assert _loaded("import shapelab as sl\nsl.__version__, dir(sl), sl.__all__") == set()


@pytest.mark.parametrize(
    "code",
    [
        # the first geometry call: union measure of a shipped protein
        "import shapelab as sl\nsl.union_measure(sl.datasets.structure('1hvr').balls)",
        # a PDB file read and reported, as the command line does
        "import shapelab as sl\ns = sl.read_structure(sl.datasets.structure_path('1hvr'))\nsl.report(s, 1.4)",
        # the modules behind the command line and the batch, imported without running them
        "import shapelab.tools.cli, shapelab.tools.batch, shapelab.report, shapelab.io, shapelab.tools.trajectory",
    ],
    ids=["union_measure", "read_and_report", "cli_batch_modules"],
)
def test_geometry_imports_no_optional_package(code):
    """The computations need numpy and scipy, never figures, widgets, gemmi, MDAnalysis,
    dask, tqdm or the peers: those come with the calls that use them."""
    assert _loaded(code) & set(OPTIONAL) == set()


def test_pdb_and_mmcif_never_import_biotite():
    """biotite (the optional BinaryCIF decoder, ``shapelab[bcif]``) comes only with a
    BinaryCIF file: reading PDB and mmCIF files, detecting any format, never imports it."""
    data = ROOT / "tests" / "data"
    code = (
        "import shapelab as sl\n"
        f"sl.read_structure({str(data / '1fbl.cif.gz')!r})\n"
        "sl.read_structure(sl.datasets.structure_path('1hvr'))\n"
        f"sl.io.detect_format({str(data / '1fbl.bcif')!r})"
    )
    assert "biotite" not in _loaded(code)
    if importlib.util.find_spec("biotite") is not None:  # the check can fail: a BinaryCIF file does import it
        assert "biotite" in _loaded(f"import shapelab as sl\nsl.read_structure({str(data / '1fbl.bcif')!r})")


def test_the_probe_can_fail():
    """The check sees a heavy import when there is one (so the tests above can fail)."""
    assert {"matplotlib", "numpy"} <= _loaded("import shapelab.plot\nshapelab.plot.new_figure")
