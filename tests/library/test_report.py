"""shapelab.report (shapelab.report, and the command line shapelab.cli): the CASTp-style table of voids and pockets (Notes §23.1).

Oracles are independent of the report's own computation: β₂ of the filtration, the
fractional inclusion–exclusion of ``Void.volume``, a seeded jittered-grid flood fill
of the free space, brute-force contacts of atoms with the flood-filled void, Monte
Carlo on the mouth triangles and a closed form for one mouth triangle.  The files
written are read back by gemmi, an independent mmCIF and PDB reader.
"""

from __future__ import annotations

import csv
import dataclasses
import importlib
import math
import os
import subprocess
import sys
from pathlib import Path

import gemmi
import numpy as np
import pytest
from scipy import ndimage

import shapelab as sl
from shapelab.datasets import bowl, structure, structure_path

ROOT = Path(__file__).resolve().parents[2]
report_module = importlib.import_module("shapelab.report")
cli = importlib.import_module("shapelab.tools.cli")


def cli_main(argv):
    """The report subcommand of ``python -m shapelab``."""
    return cli.main(["report", *argv])


@pytest.fixture(scope="module")
def t4l():
    s = structure("t4l-l99a")
    return s, sl.report(s, 1.4, name="t4l-l99a", rank="none")  # every cavity, CASTp's order


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


def test_lining_is_the_wall_over_all_atoms_of_the_cells(t4l):
    # the definition, over every contact and every atom: the atoms whose SA wall area
    # inside the feature's cells exceeds the tolerance (nested pockets share cells)
    s, rep = t4l
    sa = sl.Balls(s.balls.centers, s.balls.radii + 1.4)
    F = sl.alpha_filtration(sa)
    simp = np.asarray(F.simplices(3), dtype=np.int64)
    feats = list(sl.voids(F, 0.0)) + list(sl.pockets(F, 0.0))
    fs = sl.freespace.free_space(F, 0.0, simp)
    tol = importlib.import_module("shapelab._toolkit.tolerances").LINING_AREA_RTOL
    expected = set()
    for f in feats:
        inside = np.isin(fs.contact_cell, f.cell_ids)
        per_atom = np.bincount(fs.contact_ball[inside], weights=fs.contact_wall[inside], minlength=len(sa))
        lining = tuple(np.flatnonzero(per_atom > tol * 4.0 * np.pi * sa.radii**2).tolist())
        expected.add((round(float(fs.measure[f.cell_ids].sum()), 6), lining))
    assert {(round(r.volume_sa, 6), r.lining_atoms) for r in rep.rows} == expected
    assert sum(len(r.lining_atoms) for r in rep.rows) > 100


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


def gemmi_atoms(path):
    """Atoms of the first model as gemmi reads the file, in _atom_site.id / serial order."""
    st = gemmi.read_structure(str(path))
    atoms = [
        (a.serial, ch.name, r.name, r.seqid.num, a.name, a.b_iso, a.pos.tolist()) for ch in st[0] for r in ch for a in r
    ]
    return sorted(atoms)


def test_write_and_read_back(t4l, tmp_path):
    s, rep = t4l
    csv_p, md_p, cif_p, pdb_p = rep.write(tmp_path, "t4l")
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "t4l_cavities.cif",
        "t4l_cavities.csv",
        "t4l_cavities.md",
        "t4l_cavities.pdb",
    ]
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
    # the mmCIF file, read by gemmi: the same atoms, labels and marks, coordinates exact
    g = gemmi_atoms(cif_p)
    assert [a[0] for a in g] == list(range(1, len(s) + 1))
    assert [a[2] for a in g] == s.residue_names.tolist() and [a[4] for a in g] == s.atom_names.tolist()
    assert [a[3] for a in g] == s.residue_numbers.tolist()
    np.testing.assert_array_equal([a[5] for a in g], expect)
    np.testing.assert_array_equal([a[6] for a in g], s.balls.centers)
    # and the PDB file read by gemmi carries the same marks
    np.testing.assert_array_equal([a[5] for a in gemmi_atoms(pdb_p)], expect)


def test_write_is_atomic(bowl_report, tmp_path, monkeypatch):
    _, rep = bowl_report

    def boom(*a, **k):
        raise OSError("disk full")

    io_module = importlib.import_module("shapelab.io")
    for writer in ("write_pdb", "write_mmcif"):
        with monkeypatch.context() as m:
            m.setattr(io_module, writer, boom)
            with pytest.raises(OSError, match="disk full"):
                rep.write(tmp_path, "bowl")
        assert list(tmp_path.iterdir()) == []
    # pdb=False writes no PDB file, and removes one a former report left
    (tmp_path / "bowl_cavities.pdb").write_text("stale")
    assert [p.suffix for p in rep.write(tmp_path, "bowl", pdb=False)] == [".csv", ".md", ".cif"]
    assert sorted(p.suffix for p in tmp_path.iterdir()) == [".cif", ".csv", ".md"]
    with pytest.raises(ValueError, match="pdb"):
        rep.write(tmp_path, "bowl", pdb="yes")


def _synthetic_report(n_atoms, n_features, seed=0):
    """A report built by hand (no cavities computed): n_atoms labelled atoms with
    four-letter residue names, two-character chains and residue numbers past 9999,
    and n_features rows whose lining atoms overlap."""
    rng = np.random.default_rng(seed)
    centers = rng.uniform(-50, 50, (n_atoms, 3))
    resn = np.array(["TIP3", "HSD", "ALA", "POPC"])[np.arange(n_atoms) % 4]
    chains = np.array(["AA", "B", "C1", ""])[(np.arange(n_atoms) // 7) % 4]
    s = sl.io.PDBStructure(
        balls=sl.Balls(centers, 1.7),
        atom_names=np.array(["C1", "O5'", "CA", "N"])[np.arange(n_atoms) % 4],
        residue_names=resn,
        residue_numbers=np.arange(n_atoms, dtype=np.int64) // 3 + 1,
        chains=chains,
        elements=np.full(n_atoms, "C"),
        hetero=np.arange(n_atoms) % 5 == 0,
    )
    rows = []
    for k in range(n_features):
        lining = tuple(sorted(set(rng.integers(0, n_atoms, 5).tolist())))
        rows.append(
            report_module.CavityRow(
                kind="void" if k < 10 else "pocket",
                id=k + 1,
                volume_sa=1.0,
                area_sa=1.0,
                volume_vdw=2.0,
                area_vdw=2.0,
                mouths=0 if k < 10 else 1,
                mouth_area=0.0,
                mouth_perimeter=0.0,
                birth=-1.0,
                death=1.0,
                lining_atoms=lining,
                lining_atom_names=tuple(s.atom_names[i] for i in lining),
                lining_residues=(),
            )
        )
    return s, report_module.CavityReport(rows=tuple(rows), probe=1.4, name="synthetic", structure=s)


def test_pdb_problem_names_each_limit():
    def one(n_atoms, **labels):
        s = sl.io.PDBStructure(
            balls=sl.Balls(np.zeros((n_atoms, 3)), 1.7),
            atom_names=np.full(n_atoms, "CA"),
            residue_names=np.full(n_atoms, labels.get("resn", "ALA")),
            residue_numbers=np.full(n_atoms, labels.get("resi", 1)),
            chains=np.full(n_atoms, labels.get("chain", "A")),
            elements=np.full(n_atoms, "C"),
            hetero=np.zeros(n_atoms, bool),
        )
        row = _synthetic_report(3, 1)[1].rows[0]
        row = dataclasses.replace(row, id=labels.get("id", 1), lining_atoms=(0,))
        return report_module.CavityReport(rows=(row,), probe=1.4, name="x", structure=s).pdb_problem()

    assert one(5) is None and one(5, id=999, chain="AB", resi=9999) is None
    assert one(5, id=1000) == "feature ids up to 1000: the B-factor column (61-66) holds ids up to 999"
    assert one(100_000) == "the PDB format holds at most 99999 atoms, got 100000"
    assert "'TIP3'" in one(5, resn="TIP3") and "'ABC'" in one(5, chain="ABC")
    assert "[-999, 9999]" in one(5, resi=10_000)


def test_report_beyond_the_pdb_format_round_trips_through_gemmi(tmp_path):
    # > 1000 features, > 99,999 atoms, four-letter residue names, two-letter chains
    s, rep = _synthetic_report(100_123, 1_205)
    problem = rep.pdb_problem()
    assert problem == "feature ids up to 1205: the B-factor column (61-66) holds ids up to 999"
    with pytest.raises(ValueError, match="PDB format cannot hold"):
        rep.write(tmp_path, "big", pdb=True)
    assert list(tmp_path.iterdir()) == []  # refused before anything was written
    paths = rep.write(tmp_path, "big")
    mask = os.umask(0)
    os.umask(mask)
    assert {p.stat().st_mode & 0o777 for p in paths} == {0o666 & ~mask}  # not mkstemp's private 0o600
    assert [p.name for p in paths] == ["big_cavities.csv", "big_cavities.md", "big_cavities.cif"]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(p.name for p in paths)
    # the oracle: every feature an atom lines, from the rows (the smallest is the mark)
    lines = {}
    for r in rep.rows:
        for i in r.lining_atoms:
            lines.setdefault(i, []).append(r.id)
    smallest = np.zeros(len(s))
    for i, ids in lines.items():
        smallest[i] = min(ids)
    assert smallest.max() > 1000
    g = gemmi_atoms(paths[2])
    assert len(g) == len(s) and [a[0] for a in g] == list(range(1, len(s) + 1))
    assert [a[1] for a in g] == s.chains.tolist()
    assert [a[2] for a in g] == s.residue_names.tolist()
    assert [a[3] for a in g] == s.residue_numbers.tolist()
    assert [a[4] for a in g] == s.atom_names.tolist()
    np.testing.assert_array_equal([a[5] for a in g], smallest)
    np.testing.assert_array_equal([a[6] for a in g], s.balls.centers)
    block = gemmi.cif.read(str(paths[2])).sole_block()
    table = block.find("_atom_site.", ["id", "group_PDB", "shapelab_feature_ids"])
    every = {int(row[0]): row.str(2) for row in table}
    assert every == {i + 1: ",".join(map(str, sorted(lines.get(i, [])))) for i in range(len(s))}
    assert [row[1] == "HETATM" for row in table] == s.hetero.tolist()
    with open(paths[0], newline="") as fh:
        assert len(list(csv.DictReader(fh))) == 1_205


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
        [sys.executable, "-m", "shapelab", "report", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
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
    assert sorted(p.name for p in out.iterdir()) == [
        "1grm_cavities.cif",
        "1grm_cavities.csv",
        "1grm_cavities.md",
        "1grm_cavities.pdb",
    ]
    assert (out / "1grm_cavities.md").read_text() == res.stdout
    assert len(sl.read_pdb(out / "1grm_cavities.pdb")) == len(sl.read_pdb(src))
    assert gemmi.read_structure(str(out / "1grm_cavities.cif"))[0].count_atom_sites() == len(sl.read_pdb(src))


def test_cli_table_equals_the_library(tmp_path):
    # the CLI reads with read_pdb's defaults: its table is report(read_pdb(path))'s
    path = structure_path("1grm")
    with_het, without = sl.read_pdb(path), sl.read_pdb(path, hetatm=False)
    assert len(with_het) > len(without)  # the file has HETATM atoms, so the defaults matter
    lib = sl.report(with_het, 1.4, name="1grm_single")
    lib_no_het = sl.report(without, 1.4, name="1grm_single")
    assert lib.to_markdown() != lib_no_het.to_markdown()
    for args, expect in (([], lib), (["--no-hetatm"], lib_no_het)):
        out = tmp_path / ("a" if not args else "b")
        out.mkdir()
        res = _cli([str(path), "--out", str(out), *args], tmp_path)
        assert res.returncode == 0 and res.stderr == "", res.stderr
        assert res.stdout == expect.to_markdown()
        assert (out / "1grm_single_cavities.csv").read_text() == expect._csv_text()


def test_cli_flags_map_to_read_pdb(monkeypatch, tmp_path):
    seen = {}

    def fake_read_pdb(path, **kw):
        seen.clear()
        seen.update(kw)
        raise ValueError("stop here")

    monkeypatch.setattr(importlib.import_module("shapelab.io"), "read_structure", fake_read_pdb)
    main = cli_main
    defaults = dict(chain=None, model=None, hetatm=True, water=False, hydrogens=False, default_radius=None)
    assert main(["x.pdb"]) == 2 and seen == defaults
    assert main(["x.pdb", "--hetatm"]) == 2 and seen == defaults
    assert main(["x.pdb", "--no-hetatm", "--water", "--hydrogens", "--chain", "AA", "--chain", "B"]) == 2
    assert seen == dict(defaults, hetatm=False, water=True, hydrogens=True, chain=["AA", "B"])
    assert main(["x.pdb", "--hetatm", "CSO", "--hetatm", "ZN", "--model", "2", "--default-radius", "2"]) == 2
    assert seen == dict(defaults, hetatm={"CSO", "ZN"}, model=2, default_radius=2.0)
    with pytest.raises(SystemExit):
        main(["x.pdb", "--no-hetatm", "--hetatm", "CSO"])


def _cage_pdb(tmp_path, residue_number="   1"):
    """A small PDB file: an icosahedron of 12 carbons around one ion of promethium (HETATM;
    no table of shapelab.io has a van der Waals radius for Pm: the CLI needs --default-radius)."""
    phi = (1 + 5**0.5) / 2
    ico = [(0.0, a, b * phi) for a in (-1, 1) for b in (-1, 1)]
    ico = [p for q in ico for p in (q, (q[1], q[2], q[0]), (q[2], q[0], q[1]))]
    lines = [
        f"ATOM  {k + 1:>5}  C{k % 10}  CAG A{residue_number}    {2.2 * x:8.3f}{2.2 * y:8.3f}{2.2 * z:8.3f}"
        f"  1.00  0.00           C"
        for k, (x, y, z) in enumerate(ico)
    ]
    lines.append(f"HETATM   13 PM    PM A 101    {0:8.3f}{0:8.3f}{0:8.3f}  1.00  0.00          PM")
    p = tmp_path / "cage.pdb"
    p.write_text("\n".join(lines) + "\nEND\n")
    return p


def test_cli_checks_the_output_before_computing(monkeypatch, tmp_path, capsys):
    def no_report(*a, **k):
        raise AssertionError("the report was computed")

    monkeypatch.setattr(report_module, "report", no_report)
    src = _cage_pdb(tmp_path)
    assert cli_main([str(src), "--out", str(tmp_path / "missing"), "--default-radius", "2"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: output directory") and err.count("\n") == 1
    # an element without a radius is found when reading, and the message names the flag
    assert cli_main([str(src), "--out", str(tmp_path)]) == 2
    assert "--default-radius" in capsys.readouterr().err
    if os.geteuid() != 0:  # root writes anywhere
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o500)
        try:
            assert cli_main([str(src), "--out", str(ro), "--default-radius", "2"]) == 2
            assert "Permission denied" in capsys.readouterr().err
            assert list(ro.iterdir()) == []
        finally:
            ro.chmod(0o700)


def _metal_ions_pdb(tmp_path):
    """The 12-carbon cage of _cage_pdb, and outside it six metal ions as HETATM records
    (Mn2+ as in 1ATP, Zn, Fe, Cu, Co, Mo): Mn, Fe, Co and Mo are in neither Bondi's nor
    Mantina et al.'s table, Zn and Cu are Bondi's."""
    lines = _cage_pdb(tmp_path).read_text().splitlines()[:12]
    ions = [("MN", "MN"), ("ZN", "ZN"), ("FE", "FE"), ("CU", "CU"), ("CO", "CO"), ("MO", "MOO")]
    for k, (el, resn) in enumerate(ions):
        x = 8.0 * (k + 1)
        lines.append(
            f"HETATM{14 + k:>5} {el:<4} {resn:>3} A{201 + k:>4}    {x:8.3f}{0:8.3f}{0:8.3f}  1.00  0.00          {el}"
        )
    p = tmp_path / "metals.pdb"
    p.write_text("\n".join(lines) + "\nEND\n")
    return p


ALVAREZ_NOTE = (
    "Notes: van der Waals radii of Alvarez (2013) for 4 atoms (Co 1, Fe 1, Mn 1, Mo 1), elements Bondi (1964) "
    'and Mantina et al. (2009) do not list: S. Alvarez, "A cartography of the van der Waals territories", '
    "Dalton Trans. 42, 8617-8636 (2013), Table 1."
)


def test_report_notes_name_the_alvarez_radii(tmp_path):
    import warnings

    src = _metal_ions_pdb(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the tables used are stated, never warned about
        s = sl.read_structure(src)
        rep = sl.report(s, 1.4, name="metals")
    assert rep.notes == sl.io.radius_notes(s) and len(rep.notes) == 1
    md = rep.to_markdown()
    assert ALVAREZ_NOTE in md.splitlines()
    # the notes stand before the table; the table itself is unchanged
    assert md.replace(ALVAREZ_NOTE + "\n\n", "") == dataclasses.replace(rep, notes=()).to_markdown()
    # no note where every radius is Bondi's or Mantina et al.'s, nor for bare balls
    assert sl.report(structure("1grm"), 1.4).notes == ()
    assert sl.report(bowl(), 0.0).notes == ()
    # default_radius= is named too
    rep = sl.report(sl.read_pdb(_cage_pdb(tmp_path), default_radius=2.0), 0.5)
    assert rep.notes == ("default_radius=2 Å for 1 atom (Pm 1), elements no table of radii lists",)


def test_cli_reports_metal_ions_at_the_defaults(tmp_path):
    src = _metal_ions_pdb(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    res = _cli([str(src), "--out", str(out)], tmp_path)
    assert res.returncode == 0, res.stderr
    assert res.stderr == ""
    assert ALVAREZ_NOTE in res.stdout.splitlines()
    assert (out / "metals_cavities.md").read_text() == res.stdout
    assert sorted(p.name for p in out.iterdir()) == [f"metals_cavities.{e}" for e in ("cif", "csv", "md", "pdb")]
    st = gemmi.read_structure(str(out / "metals_cavities.cif"))
    assert sorted(a.element.name for r in st[0]["A"] for a in r if r.het_flag == "H") == [
        "Co",
        "Cu",
        "Fe",
        "Mn",
        "Mo",
        "Zn",
    ]


def test_cli_refuses_an_element_no_table_lists(tmp_path):
    src = _cage_pdb(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    res = _cli([str(src), "--out", str(out)], tmp_path)
    assert res.returncode == 2 and res.stdout == "" and list(out.iterdir()) == []
    assert res.stderr == (
        f"error: {str(src)!r}: line 13: element 'Pm' (atom 'PM', residue PM 101) has no van der Waals radius in "
        "Bondi's (1964), Mantina et al.'s (2009) or Alvarez's (2013) table; pass default_radius= (or radii=) to use "
        "one (on the command line: --default-radius R)\n"
    )


def test_cli_without_a_pdb_file_says_why(tmp_path, capsys):
    # residue number A000 (hybrid-36: 10000) does not fit the PDB's columns 23-26
    src = _cage_pdb(tmp_path, residue_number="A000")
    out = tmp_path / "out"
    out.mkdir()
    (out / "cage_cavities.pdb").write_text("a stale file of another run")
    assert cli_main([str(src), "--out", str(out), "--default-radius", "2"]) == 0
    cap = capsys.readouterr()
    assert cap.err.startswith("note: no cage_cavities.pdb (residue_numbers") and cap.err.count("\n") == 1
    assert sorted(p.name for p in out.iterdir()) == ["cage_cavities.cif", "cage_cavities.csv", "cage_cavities.md"]
    st = gemmi.read_structure(str(out / "cage_cavities.cif"))
    assert sorted(r.seqid.num for r in st[0]["A"] for a in r) == [101] + [10000] * 12
    assert (out / "cage_cavities.md").read_text() == cap.out


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


@pytest.mark.parametrize("name", ["protéine", "a\tb", "x" * 60, "it's #1 ;x", 'say "hi"\n'])
def test_any_name_writes_every_file(bowl_report, tmp_path, name):
    # the name goes into the files' titles: a non-ASCII, control or long one used to
    # make the mmCIF writer refuse the report and pdb_problem refuse the PDB file
    _, rep = bowl_report
    rep = dataclasses.replace(rep, name=name)
    assert rep.pdb_problem() is None
    paths = rep.write(tmp_path, "s")
    assert [p.suffix for p in paths] == [".csv", ".md", ".cif", ".pdb"]
    block = gemmi.cif.read(str(paths[2])).sole_block()
    title = gemmi.cif.as_string(block.find_value("_struct.title"))
    shown = name.encode("ascii", "backslashreplace").decode().replace("\t", "\\t").replace("\n", "\\n")
    assert title.startswith(f"{shown} cavities, probe 0:")
    assert gemmi.read_structure(str(paths[2]))[0].count_atom_sites() == len(bowl_report[0])
    head = paths[3].read_text().splitlines()[0]
    assert head.startswith("TITLE     ") and len(head) <= 80 and head.endswith("B-factor = feature id")
    assert len(sl.read_pdb(paths[3])) == len(bowl_report[0])


def test_cli_any_file_name(tmp_path):
    src = _cage_pdb(tmp_path)
    for name, stem in (("protéine.pdb", "protéine"), ("..pdb", "structure"), ("a\tb.ent", "a\tb")):
        out = tmp_path / f"out{len(stem)}"
        out.mkdir()
        p = src.rename(tmp_path / name)
        assert cli_main([str(p), "--out", str(out), "--default-radius", "2"]) == 0
        assert sorted(f.name for f in out.iterdir()) == [f"{stem}_cavities.{e}" for e in ("cif", "csv", "md", "pdb")]
        src = p


def test_lining_residues_tell_insertion_codes_apart(tmp_path):
    # residues 52 and 52A (Kabat numbering; 1OSM has 163A-163I) are two residues: the
    # report used to list one, its labels dropping the insertion code
    src = _cage_pdb(tmp_path, residue_number="  52")
    lines = src.read_text().splitlines()
    lines = [ln[:26] + "A" + ln[27:] if ln.startswith("ATOM") and k % 2 else ln for k, ln in enumerate(lines)]
    src.write_text("\n".join(lines) + "\n")
    s = sl.read_pdb(src, default_radius=2.0)
    assert sorted(set(s.insertion_codes.tolist())) == ["", "A"]
    rep = sl.report(s, 0.5, rank="none")  # 20 pockets, one per face: three carbons and the ion (all small)
    both = 0
    for row in rep.rows:
        expect = list(dict.fromkeys(s.residue_label(i) for i in row.lining_atoms))
        assert row.residue_labels() == expect
        assert len(row.lining_residues) == len(row.lining_insertion_codes) == len(expect)
        assert all(len(t) == 3 for t in row.lining_residues)  # (chain, name, number) as before
        assert f"| {' '.join(expect)} |" in rep.to_markdown()
        both += {"A:CAG52", "A:CAG52A"} <= set(expect)
    assert both > 0


@pytest.mark.parametrize("ext", ["csv", "md", "cif", "pdb"])
def test_a_target_that_is_a_directory_is_found_before_writing(bowl_report, tmp_path, ext):
    # a directory in the way of one file made the renames fail half-way, and undoing
    # them deleted the earlier report's files; check_output passed, so the CLI computed
    _, rep = bowl_report
    old = {e: f"old {e}" for e in ("csv", "md", "cif", "pdb") if e != ext}
    for e, text in old.items():
        (tmp_path / f"bowl_cavities.{e}").write_text(text)
    (tmp_path / f"bowl_cavities.{ext}").mkdir()
    for call in (lambda: rep.write(tmp_path, "bowl"), lambda: report_module.check_output(bowl(), tmp_path, "bowl")):
        with pytest.raises(IsADirectoryError, match=f"bowl_cavities.{ext}"):
            call()
        assert {e: (tmp_path / f"bowl_cavities.{e}").read_text() for e in old} == old
        assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
            f"bowl_cavities.{e}" for e in ("csv", "md", "cif", "pdb")
        )


def test_import_changes_no_global_state():
    """``import shapelab`` (and the report) installs no warnings filter and runs no
    program: the command line lives in shapelab.cli alone."""
    code = (
        "import warnings, sys; before = list(warnings.filters); "
        "import shapelab, shapelab.report; shapelab.report; "
        "assert warnings.filters == before, warnings.filters[:3]; "
        "assert 'shapelab.tools.cli' not in sys.modules and 'shapelab.tools' not in sys.modules"
    )
    code = (
        "import os, logging, warnings, sys, numpy; env = dict(os.environ); "
        "handlers, level = list(logging.root.handlers), logging.root.level; err = numpy.geterr(); " + code + "; "
        "assert dict(os.environ) == env and numpy.geterr() == err; "
        "assert logging.root.handlers == handlers and logging.root.level == level; "
        "assert 'matplotlib' not in sys.modules"
    )
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize(
    "module, code, words",
    [
        ("shapelab.tools.cli", 0, "usage: python -m shapelab"),
        ("shapelab.cli", 0, "usage: python -m shapelab"),  # the old path (shapelab._MOVED)
        ("shapelab.report", 1, "python -m shapelab report FILE"),
    ],
)
def test_running_a_module_is_never_a_silent_no_op(module, code, words):
    """``python -m shapelab.cli --help`` printed nothing and ``python -m
    shapelab.report FILE`` did nothing, both with status 0 (issue 22, review)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    r = subprocess.run([sys.executable, "-m", module, "--help"], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == code and words in r.stdout + r.stderr, (r.returncode, r.stdout, r.stderr)


def test_cli_needs_a_command(tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        cli.main([])
    assert e.value.code == 2
    assert "COMMAND" in capsys.readouterr().err
