"""The binding-site benchmark's data (benchmarks/pocket_sites.py, issue 23 item 4).

What is checked: the shipped structures are the bytes the manifest names (sha256 of the
shipped file and of its decompressed content; a source that was not compressed has the
same hash), the fixed dev/test split is the seeded permutation the manifest states, and
the ligand rule keeps and drops what it says on records built by hand, where the answer
is known by construction (atom counts, names, distances).  No timing: the benchmark
itself measures.
"""

from __future__ import annotations

import gzip
import hashlib

import numpy as np
import pytest

from benchmarks import pocket_sites as ps

MANIFEST = ps.load_manifest()
ENTRIES = MANIFEST["structures"]


# ------------------------------------------------------------------ the manifest
def test_at_least_fifty_complexes_each_with_a_site():
    assert len(ENTRIES) >= 50
    assert all(e["n_sites"] >= 1 and len(e["sites"]) == e["n_sites"] for e in ENTRIES)
    ids = [e["id"] for e in ENTRIES]
    assert len(set(ids)) == len(ids)


@pytest.mark.parametrize("entry", ENTRIES, ids=[e["id"] for e in ENTRIES])
def test_shipped_bytes_match_the_manifest(entry):
    data = (ps.DATA / entry["file"]).read_bytes()
    assert hashlib.sha256(data).hexdigest() == entry["sha256"]
    assert len(data) == entry["size"]
    plain = gzip.decompress(data)
    assert hashlib.sha256(plain).hexdigest() == entry["sha256_source_uncompressed"]
    path = entry["source"]["path"]
    if not path.endswith((".gz", ".bz2")):  # shipped compressed from an uncompressed source
        assert entry["sha256_source"] == entry["sha256_source_uncompressed"]
    assert entry["source"].get("commit") or entry["source"].get("version")


def test_every_shipped_file_is_in_the_manifest_and_small():
    files = {p.name for p in ps.DATA.iterdir() if p.name != "manifest.json"}
    assert files == {e["file"] for e in ENTRIES}
    assert sum((ps.DATA / f).stat().st_size for f in files) < 25 * 2**20


def test_split_is_the_seeded_permutation():
    ids = sorted(e["id"] for e in ENTRIES)
    order = np.random.default_rng(MANIFEST["split"]["seed"]).permutation(len(ids))
    dev = {ids[i] for i in order[: round(MANIFEST["split"]["dev_fraction"] * len(ids))]}
    assert dev == {e["id"] for e in ENTRIES if e["split"] == "dev"}
    assert {e["split"] for e in ENTRIES} == {"dev", "test"}
    assert set(ps.structure_ids("dev")) | set(ps.structure_ids("test")) == set(ids)
    assert not set(ps.structure_ids("dev")) & set(ps.structure_ids("test"))


@pytest.mark.parametrize("entry", ENTRIES[::9], ids=[e["id"] for e in ENTRIES[::9]])
def test_rule_on_the_shipped_file_gives_the_manifest_sites(entry):
    sites = ps.read_sites(ps.DATA / entry["file"])["sites"]
    assert [s["ligands"] for s in sites] == [s["ligands"] for s in entry["sites"]]
    assert [s["heavy_atoms"] for s in sites] == [s["heavy_atoms"] for s in entry["sites"]]


def test_split_argument_is_checked():
    with pytest.raises(ValueError, match="split"):
        ps.structure_ids("train")


# ------------------------------------------------------------------ the ligand rule on built records
PROTEIN = np.array([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [3.0, 0.0, 0.0]])


def het(name, n, start, *, polymer=False, step=1.4, chain="A", number="1"):
    """A chain of ``n`` heavy atoms along +y from ``start`` (bonded, 1.4 Å apart)."""
    xyz = np.asarray(start, dtype=np.float64) + np.outer(np.arange(n), [0.0, step, 0.0])
    return ps.HetResidue(name, chain, number, polymer, ("C",) * n, xyz)


def test_six_heavy_atoms_touching_the_protein_is_a_site_five_is_not():
    six = ps.ligand_sites([het("LIG", 6, [0, 3.5, 0])], PROTEIN)
    assert len(six) == 1 and six[0]["heavy_atoms"] == 6 and six[0]["ligands"] == ["A:LIG1"]
    assert ps.ligand_sites([het("LIG", 5, [0, 3.5, 0])], PROTEIN) == []


def test_a_ligand_not_touching_the_protein_is_dropped():
    # nearest atom 4.5 Å from the protein (brute force: the closest pair is the first atom and (0,0,0))
    far = het("LIG", 8, [0, 4.5, 0])
    assert np.min(np.linalg.norm(far.xyz[:, None] - PROTEIN[None], axis=2)) == pytest.approx(4.5)
    assert ps.ligand_sites([far], PROTEIN) == []
    assert len(ps.ligand_sites([het("LIG", 8, [0, 3.9, 0])], PROTEIN)) == 1


@pytest.mark.parametrize("name", ["HOH", "ZN", "SO4", "GOL", "EDO", "PEG", "ACT", "DMS", "MPD", "NAG", "MAN", "BMA"])
def test_water_ions_additives_and_glycans_are_not_ligands(name):
    assert name in ps.EXCLUDED or name in ps.WATER
    assert ps.ligand_sites([het(name, 14, [0, 3.5, 0])], PROTEIN) == []


def test_modified_and_polymer_residues_are_not_ligands():
    mse = het("MSE", 8, [0, 3.5, 0])
    assert ps.ligand_sites([mse], PROTEIN, modres={"MSE"}) == []
    assert ps.ligand_sites([het("XYZ", 8, [0, 3.5, 0], polymer=True)], PROTEIN) == []
    # peptide-bonded to the chain: an atom 1.33 Å from a backbone C
    link = np.array([[0.0, 3.5 - 1.33, 0.0]])
    assert ps.ligand_sites([het("XYZ", 8, [0, 3.5, 0])], PROTEIN, polymer_link_xyz=link) == []
    # a covalent ligand on a side chain (not a backbone N/C/P/O3') stays a ligand
    assert len(ps.ligand_sites([het("XYZ", 8, [0, 3.5, 0])], PROTEIN, polymer_link_xyz=np.zeros((0, 3)))) == 1


def test_bonded_het_groups_are_one_ligand():
    a = het("AAA", 3, [0, 3.5, 0], number="1")
    bonded = het("BBB", 3, [0, 3.5 + 3 * 1.4 + 0.1, 0], number="2")  # 1.5 Å from a's last atom
    sites = ps.ligand_sites([a, bonded], PROTEIN)
    assert len(sites) == 1 and sites[0]["heavy_atoms"] == 6 and sites[0]["names"] == ["AAA", "BBB"]
    apart = het("BBB", 3, [0, 3.5 + 2 * 1.4 + 2.5, 0], number="2")  # 2.5 Å: not bonded, 3 + 3 atoms
    assert ps.ligand_sites([a, apart], PROTEIN) == []


def test_ligands_within_four_angstrom_are_one_site():
    protein = np.array([[0.0, 0.0, 0.0], [3.5, 0.0, 0.0], [20.0, 0.0, 0.0]])
    a = het("AAA", 6, [0, 3.0, 0], number="1")
    near = het("BBB", 6, [3.5, 3.0, 0], number="2")  # 3.5 Å from a, atom by atom
    far = het("BBB", 6, [20.0, 3.0, 0], number="2")
    one = ps.ligand_sites([a, near], protein)
    assert len(one) == 1 and one[0]["ligands"] == ["A:AAA1", "A:BBB2"] and one[0]["heavy_atoms"] == 12
    two = ps.ligand_sites([a, far], protein)
    assert [s["ligands"] for s in two] == [["A:AAA1"], ["A:BBB2"]]


def test_centres_from_lining_is_the_centroid():
    xyz = np.arange(30, dtype=np.float64).reshape(10, 3)
    lining = [[0, 3, 7], [9]]
    got = ps.centres_from_lining(lining, xyz)
    np.testing.assert_allclose(got, [xyz[[0, 3, 7]].sum(axis=0) / 3, xyz[9]])


@pytest.mark.parametrize("pid,name", [("1xdn", "MSE"), ("1atp", "TPO"), ("1hvr", "CSO")])
def test_protein_only_input_keeps_the_modified_residues_of_the_chain(tmp_path, pid, name):
    # the PDB writes MSE, TPO... as HETATM; dropping them would cut holes in the chain
    # that every method would report as pockets.  Oracle: the residue's heavy atoms,
    # counted by text in the shipped file (first alternate location, first model).
    entry = next(e for e in ENTRIES if e["id"] == pid)
    text = gzip.decompress((ps.DATA / entry["file"]).read_bytes()).decode()
    model = text.split("\nENDMDL")[0].splitlines()
    want = sum(
        1
        for line in model
        if line.startswith("HETATM") and line[17:20] == name and line[16] in " A" and line[76:78].strip() != "H"
    )
    assert want > 0
    out = ps.protein_only_pdb(ps.DATA / entry["file"], tmp_path / "p.pdb").read_text().splitlines()
    assert sum(1 for line in out if line.startswith("ATOM") and line[17:20] == name) == want
    assert not any(line.startswith("HETATM") for line in out)
    assert ps.read_sites(ps.DATA / entry["file"])["protein_atoms"] == sum(1 for line in out if line.startswith("ATOM"))
