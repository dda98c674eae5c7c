"""shapelab.report: the CASTp-style table of voids and pockets (Notes §23.1).

Oracles are independent of the report's own computation: β₂ of the filtration, the
fractional inclusion–exclusion of ``Void.volume``, a seeded jittered-grid flood fill
of the free space, brute-force contacts of atoms with the flood-filled void, Monte
Carlo on the mouth triangles and a closed form for one mouth triangle.
"""

from __future__ import annotations

import csv
import importlib
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy import ndimage

import shapelab as sl
from shapelab.datasets import bowl, structure, structure_path

ROOT = Path(__file__).resolve().parents[1]
report_module = importlib.import_module("shapelab.report")


@pytest.fixture(scope="module")
def t4l():
    s = structure("t4l-l99a")
    return s, sl.report(s, 1.4, name="t4l-l99a")


@pytest.fixture(scope="module")
def bowl_report():
    b = bowl()
    return b, sl.report(b, 0.0, name="bowl")


def flood_fill_void(balls, lo, hi, h, offset):
    """Free grid points (outside every ball) in enclosed components of the box grid:
    returns the points of the largest enclosed component."""
    axes = [np.arange(lo[k] + offset[k], hi[k], h) for k in range(3)]
    G = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    covered = np.zeros(G.shape[:3], bool)
    start = np.array([a[0] for a in axes])
    shape = np.array(G.shape[:3])
    for c, r in zip(balls.centers, balls.radii):  # stamp every ball on the grid
        i0 = np.clip(np.floor((c - r - start) / h).astype(int), 0, shape)
        i1 = np.clip(np.ceil((c + r - start) / h).astype(int) + 1, 0, shape)
        if np.any(i1 <= i0):
            continue
        sub = G[i0[0] : i1[0], i0[1] : i1[1], i0[2] : i1[2]]
        covered[i0[0] : i1[0], i0[1] : i1[1], i0[2] : i1[2]] |= ((sub - c) ** 2).sum(-1) <= r * r
    free = ~covered
    lab, n = ndimage.label(free)
    border = set(
        np.unique(
            np.concatenate(
                [
                    lab[0].ravel(),
                    lab[-1].ravel(),
                    lab[:, 0].ravel(),
                    lab[:, -1].ravel(),
                    lab[:, :, 0].ravel(),
                    lab[:, :, -1].ravel(),
                ]
            )
        ).tolist()
    )
    counts = np.bincount(lab.ravel(), minlength=n + 1)
    inner = [c for c in range(1, n + 1) if c not in border]
    best = max(inner, key=lambda c: counts[c])
    return G[lab == best]


def test_void_count_is_beta2(t4l):
    s, rep = t4l
    sa = sl.Balls(s.balls.centers, s.balls.radii + 1.4)
    assert len(rep.voids) == sl.alpha_filtration(sa).betti(0)[2] == 10
    assert all(r.mouths == 0 and r.mouth_area == 0 for r in rep.voids)
    assert all(r.death > 0 >= r.birth for r in rep.voids)


def test_void_volume_matches_fractional_formula(t4l):
    s, rep = t4l
    sa = sl.Balls(s.balls.centers, s.balls.radii + 1.4)
    vols = sorted((v.volume for v in sl.voids(sa)), reverse=True)
    np.testing.assert_allclose([r.volume_sa for r in rep.voids], vols, rtol=1e-9, atol=1e-9)


def test_largest_void_volume_and_lining_by_flood_fill(t4l):
    s, rep = t4l
    sa = sl.Balls(s.balls.centers, s.balls.radii + 1.4)
    big = max(rep.voids, key=lambda r: r.volume_sa)
    assert big.volume_sa == pytest.approx(24.6, abs=0.05)
    # a box around the residues the brief names (not around our cells)
    around = np.isin(s.residue_numbers, [78, 84, 87, 88, 91, 99, 102, 103, 111, 114, 117, 118])
    lo = s.balls.centers[around].min(0) - 1.0
    hi = s.balls.centers[around].max(0) + 1.0
    h = 0.2
    rng = np.random.default_rng(7)
    est, pts = [], None
    for _ in range(4):
        p = flood_fill_void(sa, lo, hi, h, rng.uniform(0, h, 3))
        est.append(len(p) * h**3)
        pts = p if pts is None else pts
    mean, sem = np.mean(est), np.std(est, ddof=1) / 2
    assert abs(big.volume_sa - mean) <= max(4 * sem, 0.03 * mean), (big.volume_sa, est)
    # brute-force lining: atoms whose SA sphere comes within a voxel of the void's free points
    d = np.linalg.norm(s.balls.centers[:, None, :] - pts[None], axis=2) - sa.radii[:, None]
    gap = d.min(axis=1)
    near = {int(s.residue_numbers[i]) for i in np.flatnonzero(gap < 0.5 * h)}
    loose = {int(s.residue_numbers[i]) for i in np.flatnonzero(gap < 2 * h)}
    ours = {r for _, _, r in big.lining_residues}
    assert near <= ours <= loose, (near, ours, loose)
    assert {78, 84, 87, 88, 91, 99, 102, 103, 111, 114, 117, 118} <= ours
    atoms_near = set(np.flatnonzero(gap < 0.5 * h).tolist())
    assert atoms_near <= set(big.lining_atoms) <= set(np.flatnonzero(gap < 2 * h).tolist())
    assert big.lining_atom_names == tuple(s.atom_names[i] for i in big.lining_atoms)


def test_vdw_model_measures_the_same_cells(t4l):
    s, rep = t4l
    for r in rep.rows:
        # the vdW balls are inside the SA balls: more free space in the same cells
        assert r.volume_vdw >= r.volume_sa - 1e-9


def test_mouth_on_bowl_matches_monte_carlo(bowl_report):
    b, rep = bowl_report
    assert len(rep.voids) == 0 and len(rep.pockets) == 1
    (row,) = rep.pockets
    assert row.mouths == 1
    (pocket,) = sl.pockets(b)
    T = b.centers[pocket.mouth]
    rng = np.random.default_rng(3)
    n = 4000
    total, var = 0.0, 0.0
    for tri in T:
        area = 0.5 * np.linalg.norm(np.cross(tri[1] - tri[0], tri[2] - tri[0]))
        w = rng.dirichlet(np.ones(3), n)
        p = w @ tri
        free = sl.power_distance(p, b).min(axis=1) > 0
        f = free.mean()
        total += area * f
        var += area**2 * f * (1 - f) / n
    assert abs(row.mouth_area - total) <= 4 * math.sqrt(var) + 1e-9
    assert row.mouth_area > 1.0 and row.mouth_perimeter > 0


def test_write_and_read_back(t4l, tmp_path):
    s, rep = t4l
    csv_p, md_p, pdb_p = rep.write(tmp_path, "t4l")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t4l_cavities.csv", "t4l_cavities.md", "t4l_cavities.pdb"]
    with open(csv_p, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(rep.rows)
    assert float(rows[0]["volume_sa"]) == pytest.approx(rep.rows[0].volume_sa, abs=1e-6)
    assert rows[0]["lining_residues"].split() == rep.rows[0].residue_labels()
    md = md_p.read_text()
    assert md == rep.to_markdown() and md.count("\n| void |") == len(rep.voids)
    back = sl.read_pdb(pdb_p)
    assert len(back) == len(s)
    marks = back.b_factors
    first = {}
    for r in rep.rows:
        for i in r.lining_atoms:
            first.setdefault(i, r.id)
    expect = np.zeros(len(s))
    expect[list(first)] = list(first.values())
    np.testing.assert_array_equal(marks, expect)
    np.testing.assert_allclose(back.balls.radii, s.balls.radii, atol=0)


def test_write_is_atomic(bowl_report, tmp_path, monkeypatch):
    _, rep = bowl_report

    def boom(*a, **k):
        raise OSError("disk full")

    monkeypatch.setattr(importlib.import_module("shapelab.io"), "write_pdb", boom)
    with pytest.raises(OSError, match="disk full"):
        rep.write(tmp_path, "bowl")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "bad, exc", [(-1.0, ValueError), (float("nan"), ValueError), ("1.4", TypeError), (True, TypeError)]
)
def test_probe_validation(bad, exc):
    with pytest.raises(exc, match="probe"):
        sl.report(sl.Balls(np.zeros((1, 3)), 1.0), bad)


def test_attribute_is_the_function():
    assert callable(sl.report) and sl.report is report_module.report
    assert sl.CavityReport is report_module.CavityReport


def _cli(args, cwd):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run(
        [sys.executable, "-m", "shapelab.report", *args], cwd=cwd, env=env, capture_output=True, text=True, timeout=300
    )


def test_cli_success(tmp_path):
    import gzip

    src = tmp_path / "1grm.pdb"
    src.write_bytes(gzip.decompress(structure_path("1grm").read_bytes()))
    out = tmp_path / "out"
    out.mkdir()
    res = _cli([str(src), "--probe", "1.4", "--out", str(out)], tmp_path)
    assert res.returncode == 0, res.stderr
    assert res.stderr == ""
    assert res.stdout.startswith("## Cavities of 1grm")
    assert sorted(p.name for p in out.iterdir()) == ["1grm_cavities.csv", "1grm_cavities.md", "1grm_cavities.pdb"]
    assert (out / "1grm_cavities.md").read_text() == res.stdout
    assert len(sl.read_pdb(out / "1grm_cavities.pdb")) == len(sl.read_pdb(src, hetatm=False))


@pytest.mark.parametrize(
    "text, words",
    [
        ("ATOM      1  CA  ALA A   1      1.000   xyz     3.000  1.00  0.00           C\n", "line 1"),
        ("", "empty"),
        ("HEADER    nothing here\nEND\n", "no ATOM"),
    ],
)
def test_cli_bad_file_exits_2_and_writes_nothing(tmp_path, text, words):
    src = tmp_path / "bad.pdb"
    src.write_text(text)
    out = tmp_path / "out"
    out.mkdir()
    res = _cli([str(src), "--out", str(out)], tmp_path)
    assert res.returncode == 2
    assert res.stdout == ""
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and words in lines[0]
    assert list(out.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.pdb", "out"]
