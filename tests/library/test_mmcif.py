"""mmCIF through :func:`shapelab.read_structure` (issue 24, item 1).

Oracles, none of them our mmCIF reader:

* gemmi's own structure reader (``gemmi.read_structure``: its model hierarchy, its
  alternate-location removal) on the mmCIF entries of the MDAnalysisTests 2.11.0
  corpus (skipped when the archive of ``course/fetch_corpus.py`` is absent);
* our strict PDB parser, :func:`read_pdb`, on the PDB file of the same entry (the
  corpus ships 1BD2, 3KPR and 3PWP in both formats) and on the shipped PDB files,
  converted to mmCIF *by gemmi* (an independent writer);
* closed forms: a table built in the test (> 99,999 atoms, models, chains) and what
  :func:`write_mmcif` wrote.
"""

from __future__ import annotations

import gzip
import hashlib
import json
import math
import tarfile
from pathlib import Path

import numpy as np
import pytest

import shapelab as sl
from shapelab.datasets import structure_path
from shapelab.io import detect_format, read_pdb, read_structure, write_mmcif, write_pdb

gemmi = pytest.importorskip("gemmi")

ROOT = Path(__file__).resolve().parents[2]
ARCHIVE = ROOT / ".cache" / "corpus" / "archives" / "mdanalysistests-2.11.0.tar.gz"
PREFIX = "mdanalysistests-2.11.0/MDAnalysisTests/data/mmcif/"
# sha256 of the archive members as stored (sha256sum of the extracted files)
MEMBERS = {
    "1BD2.cif.gz": "c814967427aed618b8a91b82ab009d6955226d9d6586bd4feb8901cfabc0f1f5",
    "1BD2.pdb.gz": "469b402a83b1f77f7176f8a6c3d15e8da9bdcc439a4cc817a7d1d2ddfc7c532b",
    "1BD2_short.cif.gz": "64f0b03b4dcbfc835e61e6896c0f8599c4de64919aedf6f4c76e7f5f6017d3a9",
    "1BD2_short.pdb.gz": "cb78375a39f8afe70aa9f2ba1cff99550a2e6db8cc44f8372f567ee91e04010b",
    "1YJP.cif": "c5cf152d076c0f27e8e57a0c6bc560d07e3d7d7c4ee3aab0379368ca63bbf827",
    "1YJP.cif.gz": "15acd38e24ce3ad31e8b60dd95f78c803e5d1e1edb31cc4bd422c94bb16c184b",
    "1YJP_invalid.cif.gz": "ad09f996d65eeeed0f6e00dc14ed854e305127c89cc4cb76330bca648a9c21d0",
    "3KPR.cif.gz": "5a480061c7bb695be89521624ff274b1f34fb35f1ad4370d6173eb40f486d473",
    "3KPR.pdb.gz": "31208bea1dccd386d94a3ae75d3532a58c6a9f15ff1ecc55a9ca6b5f0a5ae306",
    "3PWP.cif.gz": "cc48ffd4424032306eaa96be4a467532bfa7224c60471395b3db50c19b05fde9",
    "3PWP.pdb.gz": "56c4833c5e7b1c0ac04a947bf2c4a79671a30e65fca523a5d2afcd05cead5a7e",
    "5PTI.cif.gz": "696c5f1c04d2633bb268615bb10bfd539d145eec63be363fa3638ed3320ce220",
    "7ETN.cif.gz": "ee7570c6bc6e4ba90f39d5012d8aa18e50dfe6a3f43b131c2cadb954a9e96df9",
    "custom.cif.gz": "af5f6aaa27d7bee8d49ed9ded09c2c0d9a47bb168944d4dfe2e9fb611371d1bd",
    "multimodel_warning.cif.gz": "11a8488c826d7d23d08cb632ca709ba0928151ec36155d80ece3e7c76c22ea1c",
}
ENTRIES = sorted(f for f in MEMBERS if ".cif" in f and "invalid" not in f)
PAIRS = sorted(f[: -len(".pdb.gz")] for f in MEMBERS if f.endswith(".pdb.gz"))
EVERYTHING = dict(hetatm=True, water=True, hydrogens=True, default_radius=2.0)


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    """The mmCIF directory of MDAnalysisTests 2.11.0, extracted in one pass."""
    if not ARCHIVE.exists():
        pytest.skip(f"corpus archive absent ({ARCHIVE}); python -m course.fetch_corpus fetches it")
    manifest = json.loads((ROOT / "benchmarks" / "corpus.json").read_text())
    assert any(a["archive"] == ARCHIVE.name for a in manifest["archives"])
    out = tmp_path_factory.mktemp("mmcif")
    with tarfile.open(ARCHIVE, "r:gz") as tar:
        for m in tar:
            name = m.name[len(PREFIX) :] if m.name.startswith(PREFIX) else None
            if name in MEMBERS:
                (out / name).write_bytes(tar.extractfile(m).read())
    for name, digest in MEMBERS.items():
        assert hashlib.sha256((out / name).read_bytes()).hexdigest() == digest, name
    return out


def _key(s, i):
    return (s.chains[i], int(s.residue_numbers[i]), s.insertion_codes[i], s.atom_names[i])


def _gemmi_atoms(path, *, model=0, water=True, hydrogens=True):
    """{(chain, number, icode, name): (xyz, element, hetero, altloc)} of gemmi's model,
    one alternate location per atom (gemmi keeps the first; the counts are what is
    compared where the choice may differ)."""
    st = gemmi.read_structure(str(path))
    if not water:
        st.remove_waters()
    if not hydrogens:
        st.remove_hydrogens()
    st.remove_alternative_conformations()
    out = {}
    for ch in st[model]:
        for res in ch:
            for a in res:
                key = (ch.name, res.seqid.num, res.seqid.icode.strip(), a.name)
                assert key not in out, key
                het = res.het_flag == "H"
                out[key] = ((a.pos.x, a.pos.y, a.pos.z), a.element.name, het, a.altloc.strip("\x00"))
    return out


def _assert_same(p, q, *, ordered=True):
    """Atom for atom: labels, coordinates, elements, radii, alternate location kept,
    occupancy and B-factor (where the first has them)."""
    assert len(p) == len(q)
    if ordered:
        i = j = np.arange(len(p))
    else:  # the same atoms, matched by their identity
        i = np.array(sorted(range(len(p)), key=lambda k: _key(p, k)))
        j = np.array(sorted(range(len(q)), key=lambda k: _key(q, k)))
    for a in ("atom_names", "residue_names", "residue_numbers", "chains", "elements", "hetero"):
        np.testing.assert_array_equal(getattr(p, a)[i], getattr(q, a)[j], err_msg=a)
    for a in ("insertion_codes", "altlocs"):
        np.testing.assert_array_equal(getattr(p, a)[i], getattr(q, a)[j], err_msg=a)
    np.testing.assert_array_equal(p.balls.centers[i], q.balls.centers[j])
    np.testing.assert_array_equal(p.balls.radii[i], q.balls.radii[j])
    for a in ("occupancies", "b_factors"):
        x, y = getattr(p, a)[i], getattr(q, a)[j]
        known = ~np.isnan(x)
        np.testing.assert_array_equal(x[known], y[known], err_msg=a)


# ------------------------------------------------------------------ real entries


@pytest.mark.parametrize("entry", ENTRIES)
def test_entry_has_gemmis_atoms(corpus, entry):
    """Every atom of gemmi's first model, one per alternate location, with gemmi's
    coordinates, element and HETATM flag; and the default selection (no water, no
    hydrogens) counts what gemmi keeps after removing them."""
    path = corpus / entry
    assert detect_format(path) == "mmcif"
    s = read_structure(path, **EVERYTHING)
    ref = _gemmi_atoms(path)
    assert len(s) == len(ref)
    for i in range(len(s)):
        xyz, element, het, alt = ref[_key(s, i)]
        assert s.elements[i].upper() == element.upper()
        assert bool(s.hetero[i]) == het
        if not alt and not s.altlocs[i]:  # where gemmi's choice (the first) may not be ours
            assert tuple(s.balls.centers[i]) == pytest.approx(xyz, abs=5e-4)
    default = read_structure(path, default_radius=2.0)
    assert len(default) == len(_gemmi_atoms(path, water=False, hydrogens=False))
    assert default.model == 1


@pytest.mark.parametrize("entry", PAIRS)
@pytest.mark.parametrize("selection", [dict(default_radius=2.0), EVERYTHING], ids=["default", "everything"])
def test_entry_reads_as_its_pdb_file(corpus, entry, selection):
    """The wwPDB's mmCIF and PDB files of one entry give the same balls atom for atom
    (auth_ names are the PDB file's), each read by its own parser."""
    p = read_pdb(corpus / f"{entry}.pdb.gz", **selection)
    q = read_structure(corpus / f"{entry}.cif.gz", **selection)
    _assert_same(p, q)


def test_plain_and_gzip_read_the_same(corpus):
    a, b = read_structure(corpus / "1YJP.cif"), read_structure(corpus / "1YJP.cif.gz")
    _assert_same(a, b)
    assert len(a) == 59  # 1YJP: 59 protein atoms, 7 waters


def test_the_second_model(corpus):
    path = corpus / "multimodel_warning.cif.gz"
    st = gemmi.read_structure(str(path))
    assert [m.num for m in st] == [1, 2]
    s2 = read_structure(path, model=2, **EVERYTHING)
    assert s2.model == 2
    assert len(s2) == len(_gemmi_atoms(path, model=1))
    assert len(s2) != len(read_structure(path, **EVERYTHING))
    with pytest.raises(ValueError, match=r"no model 3 .*\[1, 2\]"):
        read_structure(path, model=3)


def test_corpus_invalid_file_names_the_row_and_item(corpus):
    with pytest.raises(ValueError, match=r"1YJP_invalid\.cif\.gz.*row 47 \(id 47\), _atom_site\.group_PDB.*'WRONG'"):
        read_structure(corpus / "1YJP_invalid.cif.gz")


# ------------------------------------------------------------------ shipped PDB files, converted by gemmi

# adk_open and adk_closed have no element columns: gemmi's guess from the atom name is
# not read_pdb's (their hydrogens), so the conversion would test the guess, not mmCIF.
SHIPPED = ["1FMO.pdb.gz", "1grm_single.pdb.gz", "1hvr.pdb.gz", "3mht.pdb.gz", "globule.pdb"]
SHIPPED += ["t4l_l99a_ligand.pdb.gz", "t4l_l99a_receptor.pdb.gz"]


@pytest.mark.parametrize("file", SHIPPED)
@pytest.mark.parametrize("selection", [dict(default_radius=2.0), EVERYTHING], ids=["default", "everything"])
def test_shipped_pdb_converted_by_gemmi(tmp_path, file, selection):
    """gemmi writes the PDB file as mmCIF (grouping atoms by chain, so the order may
    change); read_structure on it gives read_pdb's atoms, matched by identity."""
    src = structure_path("1grm").parent / file
    cif = tmp_path / (file.split(".")[0] + ".cif")
    gemmi.read_structure(str(src)).make_mmcif_document().write_file(str(cif))
    _assert_same(read_pdb(src, **selection), read_structure(cif, **selection), ordered=False)


def test_write_mmcif_reads_back(tmp_path):
    """Our writer's table, read back: every column, alternate locations (1hvr has
    them) and occupancies included."""
    for name in ("1hvr", "3mht"):
        s = read_pdb(structure_path(name), **EVERYTHING)
        path = write_mmcif(
            tmp_path / f"{name}.cif",
            s.balls,
            s.elements,
            atom_names=s.atom_names,
            residue_names=s.residue_names,
            residue_numbers=s.residue_numbers,
            chains=s.chains,
            hetero=s.hetero,
            b_factors=s.b_factors,
            insertion_codes=s.insertion_codes,
            altlocs=s.altlocs,
            occupancies=s.occupancies,
        )
        t = read_structure(path, **EVERYTHING)
        _assert_same(s, t)
        np.testing.assert_array_equal(s.occupancies, t.occupancies)


def test_alternate_locations_choose_highest_occupancy(tmp_path):
    """Two alternatives of one atom: the one of higher occupancy, whichever comes first
    (read_pdb's rule, on an mmCIF table)."""
    text = _table(
        [
            ("ATOM", "C", "CA", "A", "ALA", "A", "1", "?", "0.0", "0.0", "0.0", "0.4"),
            ("ATOM", "C", "CA", "B", "ALA", "A", "1", "?", "1.0", "0.0", "0.0", "0.6"),
            ("ATOM", "N", "N", ".", "ALA", "A", "1", "?", "2.0", "0.0", "0.0", "1.0"),
        ]
    )
    (tmp_path / "alt.cif").write_text(text)
    s = read_structure(tmp_path / "alt.cif")
    assert s.altlocs.tolist() == ["B", ""]
    assert s.balls.centers[:, 0].tolist() == [1.0, 2.0]


# ------------------------------------------------------------------ built in the test

_HEAD = (
    "group_PDB type_symbol label_atom_id label_alt_id label_comp_id auth_asym_id auth_seq_id "
    "pdbx_PDB_ins_code Cartn_x Cartn_y Cartn_z occupancy"
).split()


def _table(rows, items=_HEAD, extra=""):
    lines = ["data_test", "loop_"] + [f"_atom_site.{t}" for t in items]
    lines += [" ".join(r) for r in rows]
    return "\n".join(lines) + "\n" + extra


def test_more_than_99999_atoms_and_62_chains(tmp_path):
    """A structure the PDB format cannot hold (100,800 atoms in 72 chains of 4-letter
    names), built and written by gemmi: every atom, chain selection by auth_asym_id."""
    st = gemmi.Structure()
    m = gemmi.Model(1)
    n_chains, n_res = 72, 350
    for c in range(n_chains):
        ch = gemmi.Chain(f"C{c:03d}")
        for r in range(n_res):
            res = gemmi.Residue()
            res.name, res.seqid, res.het_flag = "GLY", gemmi.SeqId(r + 1, " "), "A"
            for k, (nm, el) in enumerate((("N", "N"), ("CA", "C"), ("C", "C"), ("O", "O"))):
                a = gemmi.Atom()
                a.name, a.element = nm, gemmi.Element(el)
                a.pos = gemmi.Position(c * 10.0 + k, r * 0.5, 0.25 * k)
                a.occ = 1.0
                res.add_atom(a)
            ch.add_residue(res)
        m.add_chain(ch)
    st.add_model(m)
    st.setup_entities()
    path = tmp_path / "big.cif.gz"
    doc = st.make_mmcif_document()
    with gzip.open(path, "wt") as fh:
        fh.write(doc.as_string())
    s = read_structure(path)
    assert len(s) == n_chains * n_res * 4 == 100_800
    assert len(set(s.chains.tolist())) == 72
    i = len(s) - 1
    assert s.label(i) == "C071:GLY350:O"
    assert tuple(s.balls.centers[i]) == (713.0, 174.5, 0.75)
    assert s.balls.radii[i] == sl.io.vdw_radius("O")
    t = read_structure(path, chain=["C007", "C070"])
    assert len(t) == 2 * n_res * 4 and set(t.chains.tolist()) == {"C007", "C070"}


def test_model_and_chain_selection(tmp_path):
    items = _HEAD + ["pdbx_PDB_model_num"]
    rows = [
        ("ATOM", "C", "CA", ".", "ALA", ch, "1", "?", f"{x}.0", "0.0", "0.0", "1.0", mod)
        for mod in ("3", "5")
        for x, ch in enumerate(("A", "B", "B"))
    ]
    rows.append(("HETATM", "O", "O", ".", "HOH", "B", "9", "?", "9.0", "0.0", "0.0", "1.0", "5"))
    path = tmp_path / "m.cif"
    path.write_text(_table(rows, items))
    assert read_structure(path).model == 3
    s = read_structure(path, model=5, chain="B", water=True)
    assert s.model == 5 and s.chains.tolist() == ["B", "B", "B"]
    assert s.residue_names.tolist() == ["ALA", "ALA", "HOH"]
    assert len(read_structure(path, model=5, chain="B")) == 2  # water dropped by default
    with pytest.raises(ValueError, match="no model 1"):
        read_structure(path, model=1)
    with pytest.raises(ValueError, match=r"none of its 4 atoms is left.*chains present: \['A', 'B'\]"):
        read_structure(path, model=5, chain="Z")


def test_auth_names_win_over_label_names(tmp_path):
    items = ["type_symbol", "label_atom_id", "auth_atom_id", "label_comp_id", "auth_comp_id"]
    items += ["label_asym_id", "auth_asym_id", "label_seq_id", "auth_seq_id", "Cartn_x", "Cartn_y", "Cartn_z"]
    row = ("C", "CA", "CA", "ALA", "ALA", "C", "A", "1", "27", "1.0", "2.0", "3.0")
    path = tmp_path / "auth.cif"
    path.write_text(_table([row], items))
    s = read_structure(path)
    assert s.label(0) == "A:ALA27:CA" and not s.hetero[0] and s.model == 1
    assert math.isnan(s.occupancies[0])


# ------------------------------------------------------------------ malformed input

_GOOD = ("ATOM", "C", "CA", ".", "ALA", "A", "1", "?", "1.0", "2.0", "3.0", "1.0")


@pytest.mark.parametrize(
    "text, match",
    [
        ("", r"bad\.cif' is empty"),
        ("   \n\n", r"bad\.cif' is empty"),
        (_table([_GOOD, _GOOD[:7]]), r"bad\.cif' is not a readable mmCIF file: line \d+: Wrong number of values"),
        (_table([_GOOD, _GOOD[:3] + ("'ALA",)]), r"bad\.cif' is not a readable mmCIF file: line \d+: unterminated"),
        (
            _table([_GOOD[:8] + ("2.0", "3.0", "1.0")], [t for t in _HEAD if t != "Cartn_x"]),
            r"no _atom_site\.Cartn_x column",
        ),
        (
            _table([_GOOD, _GOOD[:8] + ("1.O", "2.0", "3.0", "1.0")]),
            r"row 2, _atom_site\.Cartn_x is not a number: '1\.O'",
        ),
        (_table([_GOOD[:8] + ("1.0", "?", "3.0", "1.0")]), r"row 1, _atom_site\.Cartn_y is '\?' \(unknown\)"),
        (_table([_GOOD[:8] + ("1.0", "2.0", "inf", "1.0")]), r"row 1, _atom_site\.Cartn_z is not a number"),
        (_table([_GOOD[:6] + ("1A",) + _GOOD[7:]]), r"row 1, _atom_site\.auth_seq_id is not an integer: '1A'"),
        (_table([_GOOD[:11] + ("one",)]), r"row 1, _atom_site\.occupancy is not a number"),
        (_table([("ATOM", "C1", *_GOOD[2:])]), r"_atom_site\.type_symbol is not an element symbol"),
        ("data_x\n_cell.length_a 10\n", r"has no _atom_site table"),
    ],
)
def test_malformed_mmcif_names_file_and_field(tmp_path, text, match):
    path = tmp_path / "bad.cif"
    path.write_text(text)
    with pytest.raises(ValueError, match=match):
        read_structure(path)


def test_missing_columns_are_named(tmp_path):
    for drop in ("Cartn_x", "Cartn_y", "Cartn_z", "type_symbol", "label_atom_id", "auth_asym_id"):
        items = [t for t in _HEAD if t != drop]
        rows = [tuple(v for t, v in zip(_HEAD, _GOOD) if t != drop)]
        path = tmp_path / "drop.cif"
        path.write_text(_table(rows, items))
        with pytest.raises(
            ValueError, match=rf"drop\.cif.*no (_atom_site\.\w+ or )?_atom_site\.{drop}( or _atom_site\.\w+)? column"
        ):
            read_structure(path)


def test_a_row_cut_short_at_the_end_of_the_file(tmp_path):
    """A download cut inside the last row: a syntax error naming gemmi's line."""
    text = _table([_GOOD] * 3)
    cut = text[: text.rindex("2.0")]  # last row: 9 of its 12 values
    path = tmp_path / "cut.cif.gz"
    path.write_bytes(gzip.compress(cut.encode()))
    with pytest.raises(ValueError, match=r"cut\.cif\.gz' is not a readable mmCIF file: line \d+"):
        read_structure(path)


def test_a_radius_error_names_the_row(tmp_path):
    path = tmp_path / "pm.cif"
    path.write_text(_table([_GOOD, ("HETATM", "PM", "PM", ".", "PM", "A", "2", "?", "0", "0", "0", "1")]))
    with pytest.raises(ValueError, match=r"pm\.cif': _atom_site row 2: element 'Pm'.*Alvarez's.*default_radius="):
        read_structure(path)
    assert read_structure(path, default_radius=2.0).balls.radii.tolist() == [1.7, 2.0]


def test_metal_ions_take_alvarez_radii_and_say_so(tmp_path):
    """mmCIF (gemmi's parser) gives a metal ion the radius read_pdb gives it, and the notes
    name the table: Fe and Mn from Alvarez (2013), Zn from Bondi (1964)."""
    rows = [_GOOD] + [
        ("HETATM", el, el, ".", el, "A", str(2 + k), "?", str(3.0 * (k + 1)), "0", "0", "1")
        for k, el in enumerate(["FE", "MN", "ZN", "MN"])
    ]
    path = tmp_path / "ions.cif"
    path.write_text(_table(rows))
    s = read_structure(path)
    assert s.elements.tolist() == ["C", "Fe", "Mn", "Zn", "Mn"]
    assert s.balls.radii.tolist() == [1.7, 2.44, 2.45, 1.39, 2.45]
    assert s.radius_sources.tolist() == ["bondi", "alvarez", "alvarez", "bondi", "alvarez"]
    (note,) = sl.io.radius_notes(s)
    assert note.startswith("van der Waals radii of Alvarez (2013) for 3 atoms (Fe 1, Mn 2), ")
    assert "Dalton Trans. 42, 8617-8636 (2013), Table 1" in note
    pdb = tmp_path / "ions.pdb"
    write_pdb(pdb, s.balls, s.elements, atom_names=s.atom_names, residue_names=s.residue_names, hetero=s.hetero)
    p = read_pdb(pdb)
    assert p.balls.radii.tolist() == s.balls.radii.tolist()
    assert p.radius_sources.tolist() == s.radius_sources.tolist()


def test_max_bytes_bounds_the_decompressed_text(tmp_path):
    path = tmp_path / "big.cif.gz"
    path.write_bytes(gzip.compress(_table([_GOOD] * 2000).encode()))
    assert len(read_structure(path)) == 2000
    with pytest.raises(ValueError, match="decompresses to more than max_bytes=1000"):
        read_structure(path, max_bytes=1000)


# ------------------------------------------------------------------ format recognition


def _bcif() -> bytes:
    """The head of a BinaryCIF file: a MessagePack map {encoder, version, dataBlocks: []}."""

    def s(t):
        return bytes([0xA0 | len(t)]) + t.encode()

    return b"\x83" + s("encoder") + s("test") + s("version") + s("0.3.0") + s("dataBlocks") + b"\x90"


@pytest.mark.parametrize("name", ["x.bcif", "x.bcif.gz", "x.cif", "x.dat"])
def test_binary_cif_is_recognised_by_its_content(tmp_path, name):
    """Whatever its name, a MessagePack map of dataBlocks goes to the BinaryCIF reader
    (tests/library/test_bcif.py), whose message here names the missing category."""
    pytest.importorskip("biotite")
    path = tmp_path / name
    data = _bcif()
    path.write_bytes(gzip.compress(data) if name.endswith(".gz") else data)
    assert detect_format(path) == "bcif"
    with pytest.raises(ValueError, match=rf"{name}' has no atom_site category \(data blocks: \[\]\)"):
        read_structure(path)


def test_content_decides_the_format(tmp_path):
    """mmCIF text named .pdb is read as mmCIF, PDB text named .cif as PDB; an empty file
    goes by its extension, so its reader's message is the one seen."""
    mm = tmp_path / "really_mmcif.pdb"
    mm.write_text("# a comment\n\n" + _table([_GOOD]))
    assert detect_format(mm) == "mmcif" and len(read_structure(mm)) == 1
    s = read_pdb(structure_path("1grm"))
    pdb = write_pdb(tmp_path / "really_pdb.cif", s.balls, s.elements, atom_names=s.atom_names)
    assert detect_format(pdb) == "pdb" and len(read_structure(pdb)) == len(s)
    for name, fmt in (("e.cif", "mmcif"), ("e.mmcif.gz", "mmcif"), ("e.bcif", "bcif"), ("e.pdb", "pdb"), ("e", "pdb")):
        (tmp_path / name).write_bytes(b"")
        assert detect_format(tmp_path / name) == fmt
    with pytest.raises(ValueError, match=r"e\.cif' is empty"):
        read_structure(tmp_path / "e.cif")
    assert read_structure(mm, format="mmcif").model == 1
    with pytest.raises(ValueError, match="format must be None or one of"):
        read_structure(mm, format="xyz")


def test_read_structure_on_pdb_is_read_pdb():
    for name in ("1hvr", "4ake"):
        path = structure_path(name)
        assert detect_format(path) == "pdb"
        _assert_same(read_pdb(path, **EVERYTHING), read_structure(path, **EVERYTHING))
    assert sl.read_structure is read_structure


def test_cli_reads_mmcif(tmp_path, capsys):
    """``python -m shapelab report`` on the mmCIF and the PDB file of one structure
    prints the same table."""
    from shapelab.tools.cli import main

    s = read_pdb(structure_path("1grm"))
    kw = dict(atom_names=s.atom_names, residue_names=s.residue_names, residue_numbers=s.residue_numbers)
    kw.update(chains=s.chains, hetero=s.hetero)
    write_pdb(tmp_path / "g.pdb", s.balls, s.elements, **kw)
    write_mmcif(tmp_path / "g.cif", s.balls, s.elements, **kw)
    out = {}
    for ext in ("pdb", "cif"):
        (tmp_path / ext).mkdir()
        assert main(["report", str(tmp_path / f"g.{ext}"), "--out", str(tmp_path / ext)]) == 0
        out[ext] = capsys.readouterr().out
        assert (tmp_path / ext / "g_cavities.csv").exists()
    assert out["pdb"] == out["cif"]


def test_a_pdb_error_names_the_file_too(tmp_path):
    path = tmp_path / "bad.pdb"
    path.write_text("ATOM      1  CA  ALA A   1      1.0OO   2.000   3.000  1.00  0.00           C\n")
    with pytest.raises(ValueError, match=r"^'[^']*bad\.pdb': line 1: could not read x from columns 31-38"):
        read_structure(path)
    with pytest.raises(ValueError, match=r"^line 1: could not read x"):  # read_pdb's own message
        read_pdb(path)


def test_tags_ignore_case(tmp_path):
    """CIF tags are case-insensitive (CIF 1.1, Hall, Allen and Brown 1991)."""
    items = ["TYPE_SYMBOL", "cartn_x", "Cartn_Y", "CARTN_Z", "label_atom_id", "label_comp_id"]
    items += ["label_asym_id", "Auth_Seq_Id"]
    path = tmp_path / "case.cif"
    path.write_text(_table([("C", "1", "2", "3", "CA", "ALA", "A", "5")], items))
    s = read_structure(path)
    assert s.label(0) == "A:ALA5:CA" and s.balls.centers.tolist() == [[1.0, 2.0, 3.0]]


def test_read_pdb_points_an_mmcif_file_to_read_structure(tmp_path):
    p = tmp_path / "x.pdb"
    p.write_text("data_1ABC\nloop_\n_atom_site.id\n1\n")
    with pytest.raises(ValueError, match=r"line 1: .*mmCIF file.*read_structure"):
        sl.read_pdb(p)
