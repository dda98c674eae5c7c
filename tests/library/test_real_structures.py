"""Real proteins, end to end: the certified triangulation and the persistence of the
shipped structures against GUDHI's own exact alpha complex (issue 10).

The oracle is independent of our triangulation: GUDHI builds its own (CGAL, exact)
weighted alpha complex from the same balls.  Diagrams are compared after rounding both
to 1e-7 (our values agree with GUDHI's exact ones to ~1e-11), so the comparison is a
multiset equality plus a bottleneck distance on what is left.
"""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl
from shapelab import datasets
from shapelab.cavities import freespace as FS
from shapelab.triangulation import triangulation_report

from .._oracles import bottleneck

gudhi = pytest.importorskip("gudhi")


def gudhi_exact_diagrams(balls, dim=3):
    ac = gudhi.AlphaComplex(points=balls.centers, weights=balls.radii**2, precision="exact")
    st = ac.create_simplex_tree()
    st.compute_persistence(homology_coeff_field=2, min_persistence=0)
    return {k: np.asarray(st.persistence_intervals_in_dimension(k), dtype=float).reshape(-1, 2) for k in range(dim + 1)}


def rounded(P):
    P = np.asarray(P, dtype=float).reshape(-1, 2)
    P = P[P[:, 1] - P[:, 0] > 1e-7]  # round-off pairs, on both sides
    return np.round(P, 7) + 0.0


@pytest.mark.parametrize("name", ["1grm", "1hvr", "t4l-l99a"])
@pytest.mark.parametrize("probe", [0.0, 1.4])
def test_persistence_of_a_real_protein_equals_gudhi_exact(name, probe):
    s = datasets.structure(name)
    balls = sl.Balls(s.balls.centers, s.balls.radii + probe)
    rep = triangulation_report(balls)
    assert rep.method == "qhull", rep.reason  # real data: the filter decides
    ours = sl.alpha_filtration(balls).persistence()
    theirs = gudhi_exact_diagrams(balls)
    for k in range(4):
        a, b = rounded(ours.get(k, np.empty((0, 2)))), rounded(theirs[k])
        assert a.shape[0] == b.shape[0], (k, a.shape, b.shape)
        assert bottleneck(a, b) <= 2e-7, k


# ------------------------------------------------------- reading, against peers
def _plain_text(name, tmp_path):
    import gzip

    path = datasets.structure_path(name)
    data = gzip.open(path).read() if str(path).endswith(".gz") else path.read_bytes()
    out = tmp_path / f"{name}.pdb"
    out.write_bytes(data)
    return out


def _independent_heavy_atoms(path):
    """ATOM records of the first model, one per (chain, residue, insertion, name) (altlocs
    collapsed), without hydrogens: element from columns 77-78, else the first letter of
    the atom name once digits are stripped.  Written without shapelab's reader."""
    seen = set()
    for line in path.read_text().splitlines():
        if line.startswith("ENDMDL"):
            break
        if not line.startswith("ATOM"):
            continue
        name = line[12:16].strip()
        element = line[76:78].strip() if len(line) >= 78 else ""
        element = element or name.lstrip("0123456789")[:1]
        if element.upper() in ("H", "D"):
            continue
        seen.add((line[21], line[22:26], line[26], name))
    return len(seen)


@pytest.mark.parametrize("name", ["1hvr", "4ake", "1ake", "1grm", "t4l-l99a", "1fmo"])
def test_atom_counts_agree_with_freesasa_and_an_independent_reading(name, tmp_path):
    freesasa = pytest.importorskip("freesasa")
    freesasa.setVerbosity(freesasa.silent)
    path = _plain_text(name, tmp_path)
    # every atom of the ATOM records, hydrogens included: freesasa's own PDB reader
    assert (
        len(sl.read_pdb(path, hetatm=False, hydrogens=True))
        == freesasa.Structure(str(path), options={"hydrogen": True}).nAtoms()
    )
    # heavy atoms: a reading written here from the fixed columns
    assert len(sl.read_pdb(path, hetatm=False)) == _independent_heavy_atoms(path)


def test_adenylate_kinase_superposition_rmsd_equals_scipy():
    """Horn's quaternion and Kabsch's SVD against scipy's Rotation.align_vectors on the
    same centred Cα pairs of the open (4AKE) and closed (1AKE) forms."""
    from scipy.spatial.transform import Rotation

    from shapelab.registration import kabsch

    def c_alpha(name):
        s = datasets.structure(name)
        keep = (s.atom_names == "CA") & ~s.hetero
        return s.balls.centers[keep], s.residue_numbers[keep]

    (o, ro), (c, rc) = c_alpha("4ake"), c_alpha("1ake")
    assert len(o) == 214 and np.array_equal(ro, rc)
    O, C = o - o.mean(axis=0), c - c.mean(axis=0)
    rot, rssd = Rotation.align_vectors(C, O)
    theirs = rssd / np.sqrt(len(O))
    q = sl.optimal_rotation(O, C)
    ours = np.sqrt(np.mean(np.sum((q.rotate(O) - C) ** 2, axis=1)))
    svd = np.sqrt(np.mean(np.sum((O @ kabsch(O, C).T - C) ** 2, axis=1)))
    assert ours == pytest.approx(theirs, rel=1e-9)
    assert svd == pytest.approx(theirs, rel=1e-9)
    assert np.allclose(q.to_matrix(), rot.as_matrix(), atol=1e-9)


# ------------------------------------------------- measures, against peers and sampling
@pytest.mark.parametrize("name", ["1hvr", "4ake", "1grm", "t4l-l99a", "1fmo"])
def test_solvent_accessible_area_equals_freesasa_at_fine_resolution(name):
    """The exact area of the union (short inclusion-exclusion) against freesasa's
    Lee-Richards on the same balls.  Lee-Richards converges as the slices thin: the
    tolerance is three times the change from 500 to 1000 slices (measured per
    structure, not assumed), plus 1e-4 relative."""
    freesasa = pytest.importorskip("freesasa")
    freesasa.setVerbosity(freesasa.silent)
    s = datasets.structure(name, probe=1.4)
    ours = sl.union_measure(s.balls).surface_area

    def lee_richards(slices):
        params = freesasa.Parameters({"algorithm": freesasa.LeeRichards, "n-slices": slices, "probe-radius": 0.0})
        return freesasa.calcCoord(s.balls.centers.ravel(), s.balls.radii, params).totalArea()

    fine, finer = lee_richards(500), lee_richards(1000)
    assert abs(ours - finer) <= 3 * abs(finer - fine) + 1e-4 * finer


def test_pocket_volume_of_the_hiv_active_site_against_sampling_its_cells():
    """The largest pocket of HIV-1 protease without its inhibitor (probe 1.4): its exact
    free volume against points drawn uniformly in its Delaunay cells (each cell chosen
    by volume, then a uniform barycentric point) and kept when no ball covers them.
    Seeded; within 4 standard errors."""
    s = datasets.structure("1hvr", probe=1.4)
    protein = s.select(~(s.hetero & (s.residue_names == "XK2")))
    balls = protein.balls
    site = max(sl.pockets(sl.alpha_filtration(balls)), key=lambda p: p.volume)
    X = balls.centers[site.cells]  # (m, 4, 3)
    vol = np.abs(np.linalg.det(X[:, 1:] - X[:, :1])) / 6
    rng = np.random.default_rng(12)
    n = 200_000
    pick = rng.choice(len(vol), size=n, p=vol / vol.sum())
    bary = rng.dirichlet(np.ones(4), size=n)
    pts = np.einsum("nk,nkd->nd", bary, X[pick])
    from scipy.spatial import cKDTree

    near = cKDTree(balls.centers).query_ball_point(pts, balls.radii.max())
    free = np.array(
        [all(np.linalg.norm(balls.centers[j] - p) >= balls.radii[j] for j in js) for p, js in zip(pts, near)]
    )
    share = free.mean()
    estimate = share * vol.sum()
    se = vol.sum() * np.sqrt(share * (1 - share) / n)
    assert abs(site.volume - estimate) <= 4 * se + 1e-9, (site.volume, estimate, se)


def _free_share(balls, pts, chunk=200_000):
    """Whether each point lies outside every ball: exact, by the k-d tree's nearest
    centres (a covering ball is within the largest radius; points with more centres
    that close than were asked for are checked against all of them)."""
    from scipy.spatial import cKDTree

    tree = cKDTree(balls.centers)
    rmax = float(balls.radii.max())
    k = 24
    free = np.empty(len(pts), dtype=bool)
    for s in range(0, len(pts), chunk):
        p = pts[s : s + chunk]
        d, j = tree.query(p, k=k, distance_upper_bound=rmax)
        ok = j < len(balls)
        r = np.where(ok, balls.radii[np.minimum(j, len(balls) - 1)], 0.0)
        f = ~np.any(ok & (d < r), axis=1)
        full = np.flatnonzero(np.isfinite(d[:, -1]))  # k centres within rmax: maybe more
        for i in full:
            f[i] = np.all(np.linalg.norm(balls.centers - p[i], axis=1) >= balls.radii)
        free[s : s + chunk] = f
    return free


@pytest.mark.parametrize("name", ["1hvr", "4ake", "1ake", "1grm", "t4l-l99a", "1fmo"])
def test_every_cavity_volume_against_sampling_its_cells(name):
    """Every void and pocket of every shipped protein (probe 1.4), in both models of
    the report: the exact free volume of its cells (``free_space``, what the report
    sums) against points drawn uniformly in those cells and kept when no ball covers
    them.  Seeded; within 5 standard errors, or below 10/n of the cells' volume when
    no sample is free, and the errors summed over all cavities within 5 of their
    standard errors (a bias of a fraction of a percent fails).  The report's rows are
    those sums."""
    s = datasets.structure(name)
    vdw = sl.Balls(s.balls.centers, s.balls.radii - s.probe)
    sa = sl.Balls(s.balls.centers, vdw.radii + 1.4)
    F = sl.alpha_filtration(sa)
    feats = list(sl.voids(F, 0.0)) + list(sl.pockets(F, 0.0))
    assert feats
    rep = sl.report(s, probe=1.4, rank="none")  # every cavity, unfiltered
    rng = np.random.default_rng(7)
    n = 3000
    got = {"sa": [], "vdw": []}
    bias = {"sa": [0.0, 0.0], "vdw": [0.0, 0.0]}  # sum of (exact - estimate), of se²
    for f in feats:
        X = sa.centers[f.cells]
        vol = np.abs(np.linalg.det(X[:, 1:] - X[:, :1])) / 6
        pick = rng.choice(len(vol), size=n, p=vol / vol.sum())
        pts = np.einsum("nk,nkd->nd", rng.dirichlet(np.ones(4), size=n), X[pick])
        for model, balls in (("sa", F), ("vdw", vdw)):
            exact = FS.free_space(balls, 0.0, f.cells).measure.sum()
            got[model].append(exact)
            share = _free_share(sa if model == "sa" else vdw, pts).mean()
            est, se = share * vol.sum(), vol.sum() * np.sqrt(share * (1 - share) / n)
            if share == 0:
                assert -1e-9 <= exact <= 10 / n * vol.sum(), (model, exact, vol.sum())
            else:
                assert abs(exact - est) <= 5 * se + 1e-9, (model, exact, est, se)
            bias[model][0] += exact - est
            bias[model][1] += se * se
    # summed over all cavities, a bias of a fraction of a percent would show
    for model, (diff, var) in bias.items():
        assert abs(diff) <= 5 * np.sqrt(var) + 1e-9, (model, diff, np.sqrt(var))
    # the report's volumes are these sums (rows sorted by kind and volume)
    assert sorted(round(r.volume_sa, 6) for r in rep.rows) == sorted(round(v, 6) for v in got["sa"])
    assert sorted(round(r.volume_vdw, 6) for r in rep.rows) == sorted(round(v, 6) for v in got["vdw"])
