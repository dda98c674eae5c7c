"""Tests of shapelab.datasets: the geometry each generator promises, checked by
independent means (closed forms, symmetry, a voxel flood fill, GUDHI's weighted alpha
persistence), and the topology the lessons rely on."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import ndimage
from scipy.spatial import cKDTree
from scipy.spatial.distance import pdist, squareform

from shapelab import Balls
from shapelab import datasets as D
from shapelab.datasets.figures import hex_disk

PHI = (1 + 5**0.5) / 2


# ------------------------------------------------------------------ oracles
def bounded_free_components(balls: Balls, tau: float = 0.0, h: float = 0.2) -> int:
    """Voxel oracle: bounded components of the complement of the grown union.

    Independent of any triangulation: voxels whose centre is outside every grown
    ball, 6-connected, minus those touching the padded box.
    """
    lo = balls.centers.min(0) - balls.radii.max() - 2 * h - 1.0
    hi = balls.centers.max(0) + balls.radii.max() + 2 * h + 1.0
    axes = [np.arange(a, b, h) for a, b in zip(lo, hi)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, balls.dim)
    if np.ptp(balls.radii) == 0:  # equal radii: the nearest centre has the least power
        d, _ = cKDTree(balls.centers).query(grid, k=1)
        power = d**2 - balls.radii[0] ** 2
    elif len(balls) <= 64:  # few balls: brute force, in chunks
        power = np.concatenate(
            [
                (((g[:, None, :] - balls.centers[None]) ** 2).sum(-1) - balls.radii**2).min(axis=1)
                for g in np.array_split(grid, max(1, len(grid) // 20000))
            ]
        )
    else:  # radii differ by < 0.3 in our large data sets: the least power is among the 8 nearest
        assert np.ptp(balls.radii) < 0.3
        d, i = cKDTree(balls.centers).query(grid, k=8)
        power = (d**2 - balls.radii[i] ** 2).min(axis=1)
    free = (power > tau).reshape([len(a) for a in axes])
    lab, n = ndimage.label(free)
    faces = [lab.take(0, axis=ax) for ax in range(balls.dim)] + [lab.take(-1, axis=ax) for ax in range(balls.dim)]
    border = set(np.unique(np.concatenate([f.ravel() for f in faces]))) - {0}
    return n - len(border)


def gudhi_pairs(balls: Balls) -> dict:
    gudhi = pytest.importorskip("gudhi")
    st = gudhi.AlphaComplex(points=balls.centers, weights=balls.radii**2).create_simplex_tree()
    st.compute_persistence()
    return {k: np.asarray(st.persistence_intervals_in_dimension(k)).reshape(-1, 2) for k in range(balls.dim)}


def alive(pairs: np.ndarray, tau: float, min_persistence: float = 0.0) -> np.ndarray:
    p = pairs[:, 1] - pairs[:, 0]
    return pairs[(pairs[:, 0] <= tau) & (pairs[:, 1] > tau) & (p > min_persistence)]


def born_later(pairs: np.ndarray, tau: float, min_persistence: float) -> np.ndarray:
    p = pairs[:, 1] - pairs[:, 0]
    return pairs[(pairs[:, 0] > tau) & (p > min_persistence)]


def rotation(axis, angle):
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def same_point_set(A, B, tol=1e-9):
    d, _ = cKDTree(A).query(B)
    return len(A) == len(B) and d.max() < tol


# ---------------------------------------------------------------------- C60
def test_c60_has_60_atoms_and_90_equal_bonds():
    b = D.fullerene_c60()
    assert len(b) == 60 and b.dim == 3
    d = np.sort(pdist(b.centers))
    assert np.allclose(d[:90], 1.4, rtol=1e-12)
    assert d[90] > 1.4 * 1.5  # the next distance (across a hexagon) is clearly longer
    deg = (np.abs(squareform(pdist(b.centers)) - 1.4) < 1e-9).sum(1)
    assert np.all(deg == 3)
    # V - E + F = 2 with 12 pentagons + 20 hexagons
    assert 60 - 90 + (12 + 20) == 2
    assert np.array_equal(np.sort(D.c60_edges(b), axis=None), np.sort(D.c60_edges(), axis=None))
    assert len(D.c60_edges(b)) == 90


def test_c60_icosahedral_symmetry():
    b = D.fullerene_c60(bond_length=2.0)
    c = b.centers
    R = np.linalg.norm(c, axis=1)
    assert np.allclose(R, np.sqrt(9 * PHI**2 + 1), rtol=1e-12)  # closed form, edge 2
    assert np.allclose(c.mean(0), 0, atol=1e-12)
    # 5-fold axis through an icosahedron vertex (0, 1, φ), 3-fold cyclic permutation,
    # 2-fold rotations about the coordinate axes
    for M in (
        rotation([0, 1, PHI], 2 * np.pi / 5),
        np.roll(np.eye(3), 1, axis=0),
        rotation([1, 0, 0], np.pi),
        rotation([0, 0, 1], np.pi),
    ):
        assert same_point_set(c, c @ M.T)
    # and it is not invariant under a generic rotation
    assert not same_point_set(c, c @ rotation([1, 2, 3], 0.3).T, tol=1e-3)


def test_c60_scaling_and_radius():
    b = D.fullerene_c60(bond_length=1.45, atom_radius=1.6)
    assert np.allclose(np.sort(pdist(b.centers))[:90], 1.45)
    assert np.all(b.radii == 1.6)


def test_c60_one_void_voxel_oracle():
    assert bounded_free_components(D.fullerene_c60(), 0.0) == 1
    # with small atoms the faces are open: no void
    assert bounded_free_components(D.fullerene_c60(atom_radius=1.0), 0.0) == 0


def test_c60_void_lifetime_closed_form():
    b = D.fullerene_c60()
    P = gudhi_pairs(b)
    ((born, dies),) = alive(P[2], 0.0)
    R2 = np.sum(b.centers[0] ** 2)
    assert dies == pytest.approx(R2 - 1.7**2, rel=1e-9)  # the centre is covered
    assert born == pytest.approx(1.4**2 - 1.7**2, rel=1e-9)  # the hexagons close
    assert len(alive(P[1], 0.0)) == 0


def test_c60_exactly_one_void_with_shapelab():
    import shapelab

    v = shapelab.voids(D.fullerene_c60(), 0.0)
    assert len(v) == 1
    v = shapelab.voids(D.fullerene_c60(jitter=1e-3), 2.0)
    assert len(v) == 1


@pytest.mark.parametrize("tau", [2.0, 5.0])
def test_c60_one_void_while_it_lives_degenerate(tau):
    import shapelab

    b = D.fullerene_c60()
    assert bounded_free_components(b, tau) == 1
    assert len(shapelab.voids(b, tau)) == 1


def test_jitter_is_seeded_and_small():
    a, b = D.fullerene_c60(jitter=1e-3, seed=3), D.fullerene_c60(jitter=1e-3, seed=3)
    assert np.array_equal(a.centers, b.centers)
    d = np.linalg.norm(a.centers - D.fullerene_c60().centers, axis=1)
    assert 0 < d.max() <= 1e-3
    t = D.nanotube(jitter=1e-3)
    assert np.linalg.norm(t.centers - D.nanotube().centers, axis=1).max() <= 1e-3


# ----------------------------------------------------------------- nanotube
@pytest.mark.parametrize("n,m", [(8, 8), (10, 0), (6, 3)])
def test_nanotube_radius_and_unrolled_lattice(n, m):
    a = 2.46
    b = D.nanotube(n, m, length=10.0)
    R = a * np.sqrt(n * n + n * m + m * m) / (2 * np.pi)
    assert D.nanotube_radius(n, m) == pytest.approx(R)
    rho = np.hypot(b.centers[:, 0], b.centers[:, 1])
    assert np.allclose(rho, R, rtol=1e-12)
    # unroll: arc length s = R*theta, periodic with period 2*pi*R; every bond must be
    # a/sqrt(3) long, across the seam too -- which fails if R does not match (n, m)
    s = R * np.arctan2(b.centers[:, 1], b.centers[:, 0])
    z = b.centers[:, 2]
    P = 2 * np.pi * R
    ds = np.abs(s[:, None] - s[None])
    ds = np.minimum(ds, P - ds)
    dist = np.hypot(ds, z[:, None] - z[None])
    bond = a / np.sqrt(3)
    near = (dist < 1.25 * bond) & (dist > 0)
    assert np.allclose(dist[near], bond, rtol=1e-9)
    interior = (z > 1.5) & (z < 10.0 - 1.5)
    assert np.all(near[interior].sum(1) == 3)
    # graphene density: 2 atoms per cell of area (sqrt(3)/2) a^2; compare the atoms
    # gained by 60 Å more tube, up to one ring of atoms at each end
    gained = len(D.nanotube(n, m, length=70.0)) - len(b)
    expected = 2 * P * 60.0 / (np.sqrt(3) / 2 * a * a)
    assert abs(gained - expected) <= 2 * (n + m)


def test_nanotube_one_tunnel():
    b = D.nanotube()
    P = gudhi_pairs(b)
    assert len(alive(P[1], 0.0, 1e-6)) == 1
    assert len(alive(P[2], 0.0, 1e-6)) == 0
    assert bounded_free_components(b, 0.0, h=0.3) == 0


def test_nanotube_slit_groove_becomes_a_tunnel_only_if_narrow():
    closed = D.nanotube()
    R = D.nanotube_radius(8, 8)
    narrow, wide = D.nanotube(slit=3.0), D.nanotube(slit=22.0)
    assert len(narrow) < len(closed) and len(wide) < len(narrow)
    # removed atoms are exactly those within slit/2 of the line theta = 0 (arc length)
    arc = R * np.abs(np.arctan2(narrow.centers[:, 1], narrow.centers[:, 0]))
    assert arc.min() >= 1.5 - 1e-9
    P = gudhi_pairs(closed)
    ((born0, dies0),) = alive(P[1], 0.0, 1e-6)
    assert dies0 == pytest.approx(R**2 - 1.7**2, rel=1e-9)  # the ring of atoms covers the axis
    g = born_later(gudhi_pairs(narrow)[1], 0.0, 2.0)
    g = g[np.isfinite(g[:, 0]) & (g[:, 0] < 1e6)]
    assert len(g) == 1 and g[0, 1] == pytest.approx(dies0)  # a groove at 0, a tunnel later
    w = gudhi_pairs(wide)[1]
    w = w[(w[:, 1] - w[:, 0] > 2.0) & (w[:, 0] < 1e6)]
    assert len(w) == 0  # a half-pipe never closes


def test_nanotube_one_tunnel_with_shapelab():
    import shapelab

    assert len(shapelab.tunnels(D.nanotube(), 0.0)) == 1
    assert len(shapelab.voids(D.nanotube(), 0.0)) == 0


def test_nanotube_no_late_voids_degenerate():
    import shapelab

    b = D.nanotube()
    for tau in (22.0, 30.0):
        assert bounded_free_components(b, tau, h=0.3) == 0
        assert len(shapelab.voids(b, tau)) == 0


# --------------------------------------------------------------------- bowl
def test_bowl_is_a_pocket():
    b = D.bowl()
    assert np.allclose(np.linalg.norm(b.centers, axis=1), 6.0)
    assert np.all(b.centers[:, 2] < 6.0 * np.cos(np.radians(50)))
    P = gudhi_pairs(b)
    assert len(alive(P[2], 0.0)) == 0  # open at tau = 0 ...
    late = born_later(P[2], 0.0, 5.0)  # ... and closes into a void later
    assert len(late) == 1
    born, dies = late[0]
    assert dies == pytest.approx(36.0 - 1.7**2, rel=0.05)  # the centre is covered last
    assert bounded_free_components(b, 0.0, h=0.3) == 0
    assert bounded_free_components(b, 0.5 * (born + dies), h=0.3) == 1


# ------------------------------------------------------------------ globule
def test_globule_is_deterministic_and_seeded():
    a, b, c = D.globule(0), D.globule(0), D.globule(1)
    assert np.array_equal(a.centers, b.centers) and np.array_equal(a.radii, b.radii)
    assert not (len(a) == len(c) and np.array_equal(a.centers, c.centers))
    assert set(np.unique(a.radii)) <= {1.70, 1.55, 1.52, 1.80}


@pytest.mark.parametrize("seed", [0, 1])
def test_globule_void_pocket_groove(seed):
    b = D.globule(seed)
    P = gudhi_pairs(b)
    # one buried void at tau = 0, and no tunnel yet
    assert len(alive(P[2], 0.0)) == 1
    assert len(alive(P[1], 0.0, 1e-9)) == 0
    # the pocket: a void born later that lives long
    assert len(born_later(P[2], 0.0, 5.0)) >= 1
    # the groove turns into a long-lived tunnel when the slit closes
    g = born_later(P[1], 0.0, 5.0)
    assert len(g) >= 1 and g[:, 0].min() < 6.0


def test_globule_void_voxel_oracle():
    assert bounded_free_components(D.globule(0), 0.0, h=0.35) == 1


def test_globule_structure_matches_globule():
    s = D.globule_structure(0)
    g = D.globule(0)
    # same atoms (reordered along the chain)
    assert same_point_set(s.balls.centers, g.centers, tol=1e-12)
    assert len(np.unique(s.residue_numbers)) == -(-len(g) // 8)
    assert set(s.elements) <= {"C", "N", "O", "S"}


def test_example_pdb_is_the_globule():
    from shapelab import read_pdb

    s = read_pdb(D.example_pdb())
    g = D.globule_structure(0)
    assert len(s) == len(g)
    assert np.abs(s.balls.centers - g.balls.centers).max() <= 5e-4 + 1e-9
    assert np.array_equal(s.balls.radii, g.balls.radii)
    assert list(s.residue_names) == list(g.residue_names)


# -------------------------------------------------------------- 2D figures
def test_figure_23_2_is_deterministic():
    (l1, r1), (l2, r2) = D.figure_23_2(), D.figure_23_2()
    assert np.array_equal(l1.centers, l2.centers) and np.array_equal(r1.centers, r2.centers)
    assert l1.dim == r1.dim == 2


def test_figure_23_2_left_is_a_pocket_right_is_not():
    left, right = D.figure_23_2()
    PL, PR = gudhi_pairs(left), gudhi_pairs(right)
    for P in (PL, PR):  # both dents are open at tau = 0
        assert len(alive(P[1], 0.0)) == 0
    late = born_later(PL[1], 0.0, 1.0)
    assert len(late) == 1
    assert late[0, 0] == pytest.approx(1.0 - 0.65**2, rel=1e-9)  # mouth disks touch
    assert len(born_later(PR[1], 0.0, 1e-6)) == 0  # never a hole: fills from the bottom
    mid = late[0].mean()
    assert bounded_free_components(left, mid, h=0.05) == 1
    assert bounded_free_components(right, mid, h=0.05) == 0


def test_figure_23_2_pockets_with_shapelab():
    import shapelab

    left, right = D.figure_23_2()
    assert len(shapelab.pockets(left, 0.0)) >= 1
    assert len(shapelab.pockets(left, 0.0, min_persistence=1.0)) == 1
    assert len(shapelab.pockets(right, 0.0, min_persistence=1e-6)) == 0


@pytest.mark.parametrize("n,R,r", [(12, 3.0, 1.0), (8, 2.0, 0.9)])
@pytest.mark.parametrize("dim", [2, 3])
def test_ring_hole_lifetime_closed_form(n, R, r, dim):
    b = D.ring(n, radius=R, disk_radius=r, dim=dim)
    assert len(b) == n and b.dim == dim
    P = gudhi_pairs(b)
    ((born, dies),) = alive(P[1], 0.0)
    assert born == pytest.approx(R**2 * np.sin(np.pi / n) ** 2 - r**2, abs=1e-9)
    assert dies == pytest.approx(R**2 - r**2, rel=1e-9)


def test_swiss_cheese_slit_is_biggest_but_least_persistent():
    b = D.swiss_cheese()
    P = gudhi_pairs(b)
    holes = alive(P[1], 0.0)
    assert len(holes) == 4
    # the slit: rectangles 1 x sqrt(3) of co-circular centres, filled at 1 - r^2; its
    # rows touch at 3/4 - r^2 and cut it into short-lived pieces
    assert holes[:, 1].min() == pytest.approx(1.0 - 0.65**2, abs=1e-9)
    pieces = born_later(P[1], 0.0, 1e-6)
    assert np.allclose(pieces[:, 0], 0.75 - 0.65**2) and np.allclose(pieces[:, 1], 1.0 - 0.65**2)
    # ... yet it has the largest area (pixel oracle)
    h = 0.05
    xs, ys = np.arange(-13, 13, h), np.arange(-7, 7, h)
    g = np.stack(np.meshgrid(xs, ys, indexing="ij"), -1).reshape(-1, 2)
    d, _ = cKDTree(b.centers).query(g)
    lab, n = ndimage.label((d > 0.65).reshape(len(xs), len(ys)))

    def area_at(x, y):
        return (lab == lab[int(round((x + 13) / h)), int(round((y + 7) / h))]).sum() * h * h

    slit = area_at(0.0, -3 * np.sqrt(3) / 2)
    rounds = [area_at(-7.0, 2.0), area_at(0.0, 2.0), area_at(7.0, 2.0)]
    assert slit > max(rounds) and rounds[0] < rounds[1] < rounds[2]


def test_nested_pockets_close_at_mouth_then_neck():
    b = D.nested_pockets()
    P = gudhi_pairs(b)
    late = born_later(P[1], 0.0, 1.0)
    assert len(late) == 2
    births = np.sort(late[:, 0])
    assert births[0] == pytest.approx(1.0 - 0.65**2, abs=1e-9)  # the mouth: disks 2 apart
    assert births[1] == pytest.approx(1.5**2 - 0.65**2, abs=1e-9)  # the neck: disks 3 apart
    # the older hole (born at the mouth) lives longer: chamber B is the bigger one
    assert late[np.argmin(late[:, 0]), 1] > late[np.argmax(late[:, 0]), 1]
    assert len(alive(P[1], 0.0)) == 0


def test_mixed_dent_pocket_only_under_probe_growth():
    b = D.mixed_dent()
    assert len(b) == 24 and np.sum(b.radii == 3.0) == 2
    P = gudhi_pairs(b)
    assert len(born_later(P[1], -1.0, 1e-6)) == 0  # the notes' growth: never a hole
    grown = lambda p: Balls(b.centers, b.radii + p)  # noqa: E731  (probe growth)
    assert bounded_free_components(grown(1.5), h=0.02) == 0
    assert bounded_free_components(grown(1.9), h=0.02) == 1  # the mouth has closed first
    assert bounded_free_components(grown(2.3), h=0.02) == 0


def test_figure_23_1_has_two_triangles_at_zero():
    gudhi = pytest.importorskip("gudhi")
    b = D.figure_23_1()
    st = gudhi.AlphaComplex(points=b.centers, weights=b.radii**2).create_simplex_tree()
    tri = [s for s, f in st.get_filtration() if len(s) == 3 and f <= 0]
    assert len(tri) == 2
    assert 10 <= len(b) <= 15


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "call, exc",
    [
        (lambda: D.fullerene_c60(bond_length=0), ValueError),
        (lambda: D.fullerene_c60(atom_radius=-1), ValueError),
        (lambda: D.fullerene_c60(bond_length="1"), TypeError),
        (lambda: D.nanotube(0, 0), ValueError),
        (lambda: D.nanotube(8, -1), ValueError),
        (lambda: D.nanotube(8.5, 0), TypeError),
        (lambda: D.nanotube(8, 8, length=float("nan")), ValueError),
        (lambda: D.bowl(opening=190), ValueError),
        (lambda: D.nanotube(slit=40.0), ValueError),
        (lambda: D.nanotube(slit=-1.0), ValueError),
        (lambda: D.globule(seed=-1), ValueError),
        (lambda: D.globule(seed=None), TypeError),
        (lambda: D.globule(semi_axes=(1, 2)), ValueError),
        (lambda: D.ring(2), ValueError),
        (lambda: D.ring(5, dim=4), ValueError),
        (lambda: D.globule_structure(0, colour="red"), TypeError),
        (lambda: D.swiss_cheese(disk_radius=0), ValueError),
        (lambda: D.nested_pockets(disk_radius=-1), ValueError),
        (lambda: D.mixed_dent(gap="wide"), TypeError),
        (lambda: D.figure_23_2(disk_radius=np.inf), ValueError),
        (lambda: D.bowl(radius=0), ValueError),
    ],
)
def test_bad_input(call, exc):
    with pytest.raises(exc):
        call()


# -------------------------------------------------------------- real structures
import gzip as _gzip  # noqa: E402
import hashlib as _hashlib  # noqa: E402
import json as _json  # noqa: E402
from importlib import resources as _resources  # noqa: E402

_WATER = {"HOH", "WAT", "H2O", "DOD", "D2O", "TIP", "TIP3", "TIP4", "TIP5", "T3P", "T4P", "T5P", "SOL", "SPC", "SPCE"}


def _slice_records(text, hydrogens):
    """An independent reading: ATOM/HETATM records of the first model by column slicing
    (wwPDB v3.3: x/y/z in columns 31-54, residue name 18-20(21), element 77-78).
    Hydrogens are told by the element columns, else by a name whose first letter
    (after digits) is H, which holds for every file shipped.  Waters are dropped."""
    out = []
    for line in text.splitlines():
        if line.startswith("END"):
            break
        if line[:6] not in ("ATOM  ", "HETATM"):
            continue
        if line[17:21].strip() in _WATER:
            continue
        element = line[76:78].strip()
        is_h = element in ("H", "D") if element else line[12:16].strip().lstrip("0123456789")[:1] == "H"
        if is_h and not hydrogens:
            continue
        out.append(
            (
                float(line[30:38]),
                float(line[38:46]),
                float(line[46:54]),
                line[17:21].strip(),
                int(line[22:26]),
                line[21].strip(),
            )
        )
    return out


def _shipped(info):
    return _resources.files("shapelab").joinpath("data", info.file).read_bytes()


def test_structures_table_matches_json():
    raw = _json.loads(_resources.files("shapelab").joinpath("data", "STRUCTURES.json").read_text())
    assert [e["name"] for e in raw["structures"]] == list(D.STRUCTURES)
    assert len(D.STRUCTURES) >= 5
    for name, info in D.STRUCTURES.items():
        assert info.name == name and len(info.sha256) == 64 and len(info.sha256_original) == 64
        assert set(info.source) >= {"package", "version", "archive", "path"}
        assert info.title and info.teaches and info.differences and info.evidence
        assert isinstance(info.differs_from_pdb, bool)
    with pytest.raises(TypeError):
        D.STRUCTURES["x"] = None


def test_structures_cover_the_required_features():
    ids = {info.pdb_id for info in D.STRUCTURES.values()}
    assert {"1HVR", "4AKE", "1AKE", "1GRM", "1FMO"} <= ids
    assert {"1hvr", "4ake", "1ake", "1grm", "t4l-l99a", "1fmo", "1fmo-kvfinder"} <= set(D.STRUCTURES)


@pytest.mark.parametrize("name", list(D.STRUCTURES))
def test_shipped_file_hashes(name):
    info = D.STRUCTURES[name]
    data = _shipped(info)
    assert _hashlib.sha256(data).hexdigest() == info.sha256
    assert len(data) == info.size
    raw = _gzip.decompress(data)
    assert _hashlib.sha256(raw).hexdigest() == info.sha256_original
    assert len(raw) == info.size_original


@pytest.mark.parametrize("name", list(D.STRUCTURES))
def test_shipped_structure_atom_counts_against_column_slicing(name):
    info = D.STRUCTURES[name]
    text = _gzip.decompress(_shipped(info)).decode("latin-1")
    hyd = bool(info.read.get("hydrogens", False))
    want = _slice_records(text, hydrogens=hyd)
    s = D.structure(name)
    assert len(s) == len(want)
    assert np.array_equal(s.balls.centers, np.array([w[:3] for w in want]))
    assert s.residue_names.tolist() == [w[3] for w in want]
    assert s.residue_numbers.tolist() == [w[4] for w in want]
    assert s.chains.tolist() == [w[5] for w in want]
    # and the counts recorded at copy time
    a = info.atoms
    assert len(_slice_records(text, hydrogens=True)) == a["records"] - a["water"]
    assert len(D.structure(name, hydrogens=True, water=True)) == a["records"]
    het = [ln for ln in text.splitlines() if ln.startswith("HETATM")]
    assert len(het) == a["hetatm"]
    het_kept = [ln for ln in het if ln[17:21].strip() not in _WATER and (hyd or ln[76:78].strip() not in ("H", "D"))]
    assert int(s.hetero.sum()) == len(het_kept)
    assert np.all(s.balls.radii > 0) and np.all(np.isfinite(s.balls.centers))


def test_structure_names_and_options():
    s = D.structure("1hvr")
    assert set(s.chains.tolist()) == {"A", "B"}
    assert "XK2" in set(s.residue_names.tolist())
    protein = D.structure("1hvr", hetatm={"CSO"})
    assert "XK2" not in set(protein.residue_names.tolist()) and len(s) - len(protein) == 46
    assert len(D.structure("1hvr", chain="A")) + len(D.structure("1hvr", chain="B")) == len(s)
    assert D.structure(" 1HVR ").balls.centers.shape == s.balls.centers.shape
    assert np.allclose(D.structure("1grm", probe=1.4).balls.radii, D.structure("1grm").balls.radii + 1.4)
    t4 = D.structure("t4l-l99a")
    assert set(t4.residue_names[t4.residue_numbers == 99].tolist()) == {"ALA"}  # L99A
    kv = D.structure("1fmo-kvfinder")
    assert len(set(kv.residue_names.tolist())) == 18 and set(kv.elements.tolist()) == {"H"}
    with pytest.raises(ValueError, match="no shipped structure"):
        D.structure("2xyz")
    with pytest.raises(TypeError):
        D.structure(4)


def test_adenylate_kinase_two_conformations_pair_atom_by_atom():
    a, b = D.structure("4ake"), D.structure("1ake")
    assert len(a) == len(b) == 1656
    assert a.atom_names.tolist() == b.atom_names.tolist()
    assert a.residue_numbers.tolist() == b.residue_numbers.tolist()
    ca = a.atom_names == "CA"
    assert ca.sum() == 214
    # closed is more compact, and the two differ by a large motion (not a copy)
    rg = lambda c: np.sqrt(((c - c.mean(0)) ** 2).sum(1).mean())  # noqa: E731
    assert rg(b.balls.centers) < rg(a.balls.centers) - 2.0
    assert np.abs(a.balls.centers - b.balls.centers).max() > 10.0


def _trajectory_entry():
    raw = _json.loads(_resources.files("shapelab").joinpath("data", "STRUCTURES.json").read_text())
    (entry,) = [e for e in raw["trajectories"] if e["name"] == "adk-dims"]
    return entry


def _dcd_by_numpy(data):
    """An independent reading of a DCD (CHARMM's Fortran-record layout, little-endian):
    the header's frame count, istart, nsavc, and the float32 x, y, z records of every
    frame, as an array (frames, atoms, 3); a frame's unit-cell record (six float64, when
    the header's flag is set) must hold no box (MDAnalysis writes zeros for none)."""

    def records(buf):
        at = 0
        while at < len(buf):
            n = int(np.frombuffer(buf, "<i4", 1, at)[0])
            yield buf[at + 4 : at + 4 + n]
            assert int(np.frombuffer(buf, "<i4", 1, at + 4 + n)[0]) == n
            at += n + 8

    recs = list(records(data))
    head = recs[0]
    assert head[:4] == b"CORD"
    icntrl = np.frombuffer(head, "<i4", 20, 4)
    n_atoms = int(np.frombuffer(recs[2], "<i4", 1)[0])
    per = 4 if icntrl[10] else 3
    assert len(recs) == 3 + per * icntrl[0]
    frames = []
    for i in range(icntrl[0]):
        rec = recs[3 + per * i : 3 + per * (i + 1)]
        if per == 4:
            assert len(rec[0]) == 48 and not np.frombuffer(rec[0], "<f8")[[0, 2, 5]].any()
        xyz = [np.frombuffer(r, "<f4") for r in rec[per - 3 :]]
        assert all(len(c) == n_atoms for c in xyz)
        frames.append(np.stack(xyz, axis=1))
    frames = np.stack(frames)
    return int(icntrl[0]), int(icntrl[1]), int(icntrl[2]), frames


def test_shipped_trajectory_hashes_and_numpy_reading():
    e = _trajectory_entry()
    top, traj = D.trajectory_files("adk-dims")
    assert (top.name, traj.name) == (e["files"]["topology"], e["files"]["trajectory"])
    for key, path in (("topology", top), ("trajectory", traj)):
        assert _hashlib.sha256(path.read_bytes()).hexdigest() == e["sha256"][key]
        assert path.stat().st_size == e["size"][key]
    assert all(len(h) == 64 for h in e["sha256_source"].values())
    assert e["source"]["package"] == "MDAnalysisTests" and e["source"]["version"] == "2.11.0"
    n, istart, nsavc, xyz = _dcd_by_numpy(traj.read_bytes())
    assert n == e["n_frames"] == len(range(*e["frames"])) == 25 and xyz.shape == (25, e["atoms"], 3)
    assert istart * 4 == nsavc  # the first frame's time is a quarter of the step: source frame 0 at 1 ps, dt 4 ps
    # the topology holds the first frame (to the PDB's 3 decimals), heavy atoms only, elements given
    pdb = _slice_records(_gzip.decompress(top.read_bytes()).decode("latin-1"), hydrogens=True)
    assert len(pdb) == e["atoms"] == 1656
    assert np.abs(np.array([p[:3] for p in pdb]) - xyz[0]).max() <= 0.0005 + 1e-6
    lines = [ln for ln in _gzip.decompress(top.read_bytes()).decode().splitlines() if ln.startswith("ATOM")]
    assert {ln[76:78].strip() for ln in lines} == {"C", "N", "O", "S"}
    # the same atoms, in the same order, as the shipped 1ake and 4ake (heavy atoms of the same CHARMM model)
    assert [ln[12:16].strip() for ln in lines] == D.structure("1ake").atom_names.tolist()
    # closed to open: the first frame is near 1ake, the last near 4ake (C-alpha RMSD after a Kabsch fit)
    ca = np.array([ln[12:16].strip() == "CA" for ln in lines])

    def rmsd(a, b):
        a, b = a - a.mean(0), b - b.mean(0)
        u, s, vt = np.linalg.svd(a.T @ b)
        d = np.sign(np.linalg.det(u @ vt))
        return np.sqrt(max(((a**2).sum() + (b**2).sum() - 2 * (s[0] + s[1] + d * s[2])) / len(a), 0.0))

    closed, opened = (D.structure(k).balls.centers[D.structure(k).atom_names == "CA"] for k in ("1ake", "4ake"))
    assert rmsd(xyz[0][ca].astype(float), closed) < 1.0 < rmsd(xyz[0][ca].astype(float), opened) - 5.0
    assert rmsd(xyz[-1][ca].astype(float), opened) < 1.0 < rmsd(xyz[-1][ca].astype(float), closed) - 5.0


def test_shipped_trajectory_read_by_mdanalysis_equals_the_source_frames():
    mda = pytest.importorskip("MDAnalysis")
    import tarfile
    import warnings
    from pathlib import Path

    e = _trajectory_entry()
    top, traj = D.trajectory_files()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # the DCD reader announces a change in 3.0
        u = mda.Universe(str(top), str(traj))
        assert len(u.atoms) == 1656 and len(u.trajectory) == 25
        _, _, _, xyz = _dcd_by_numpy(traj.read_bytes())
        for i, ts in enumerate(u.trajectory):
            assert np.array_equal(u.atoms.positions, xyz[i])
            assert ts.time == pytest.approx(1.0 + 4.0 * i, abs=1e-4)
        archive = Path(__file__).resolve().parents[2] / ".cache" / "corpus" / "archives" / e["source"]["archive"]
        if not archive.exists():
            pytest.skip(f"the corpus archive {archive.name} is not fetched (python -m course.fetch_corpus)")
        with tarfile.open(archive) as tar, __import__("tempfile").TemporaryDirectory() as tmp:
            paths = []
            for key in ("topology", "trajectory"):
                data = tar.extractfile("mdanalysistests-2.11.0/" + e["source"][key]).read()
                assert _hashlib.sha256(data).hexdigest() == e["sha256_source"][key]
                paths.append(Path(tmp) / Path(e["source"][key]).name)
                paths[-1].write_bytes(data)
            src = mda.Universe(*map(str, paths))
            heavy = src.select_atoms(e["select"])
            assert heavy.names.tolist() == u.atoms.names.tolist()
            assert len(src.trajectory) == 98
            for i, f in enumerate(range(*e["frames"])):
                src.trajectory[f]
                assert np.array_equal(heavy.positions, xyz[i])  # bit for bit: float32 copied, not rounded


def test_trajectory_files_bad_input():
    with pytest.raises(ValueError, match="no shipped trajectory"):
        D.trajectory_files("adk")
    with pytest.raises(TypeError, match="name"):
        D.trajectory_files(4)
    assert D.trajectory_files(" ADK-DIMS ") == D.trajectory_files()


def test_l99a_ligand_sits_inside_the_receptor():
    rec, lig = D.structure("t4l-l99a"), D.structure("t4l-l99a-ligand")
    assert len(lig) == 8 and set(lig.elements.tolist()) == {"C"}
    d = np.linalg.norm(lig.balls.centers[:, None] - rec.balls.centers[None], axis=-1)
    # buried: every ligand carbon is within 4.5 Å of some receptor atom, none clashes
    assert d.min() > 2.5 and d.min(axis=1).max() < 4.5
    near = rec.residues(np.flatnonzero(d.min(axis=0) < 4.5))
    # the residues that line the L99A cavity (Eriksson et al. 1992; Morton & Matthews 1995)
    assert {":ALA99", ":LEU84", ":VAL87", ":TYR88", ":LEU118", ":PHE153"} <= set(near)


def test_alpha_filtration_on_a_shipped_structure():
    from shapelab import alpha_filtration
    from shapelab.triangulation import triangulation_report

    s = D.structure("1grm", probe=1.4)
    heavy = s.balls
    f = alpha_filtration(heavy)
    assert f is not None
    report = triangulation_report(heavy)
    assert report.method in ("qhull", "incremental")
    assert isinstance(report.reason, str)


def test_figure_23_2_dents_differ_only_in_the_mouth():
    """Same body, same chamber, same depth: the funnel's dent contains the flask's, and the
    extra points it removes all lie above the chamber's centre (the mouth)."""
    left, right = D.figure_23_2()
    body = {tuple(p) for p in hex_disk(6.0, 1.0)}
    gone_l = body - {tuple(p) for p in left.centers}
    gone_r = body - {tuple(p) for p in right.centers}
    assert gone_l < gone_r
    assert min(y for _, y in gone_l) == min(y for _, y in gone_r)  # equal depth
    assert all(y >= 2.5 for _, y in gone_r - gone_l)  # they differ in the mouth only
