"""BinaryCIF through :func:`shapelab.read_structure` (issue 24, item 1).

Oracles, none of them our BinaryCIF reader:

* the text mmCIF of the same entry, read by our mmCIF reader (gemmi's CIF parser): P2Rank's
  test data ships 1FBL and 2W83 in both encodings (tests/data/SOURCES.json), written by the
  PDB's own tools, so the two readings must agree atom for atom, under every selection;
* gemmi's own structure reader (its model hierarchy, its alternate-location removal) on
  the text file: the atom counts;
* round trips through biotite's *writer*: a shipped PDB file and tables built here (models,
  insertion codes, hydrogens, alternate locations, unknown values) are encoded as BinaryCIF
  by biotite (its ``compress`` chooses delta, run-length, fixed-point, string-table
  encodings) and must read back as our PDB or mmCIF reader reads the source.
"""

from __future__ import annotations

import gzip
import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from shapelab.datasets import structure_path
from shapelab.io import detect_format, read_pdb, read_structure

pdbx = pytest.importorskip("biotite.structure.io.pdbx")
gemmi = pytest.importorskip("gemmi")
msgpack = pytest.importorskip("msgpack")  # biotite's container format: used to break files on purpose

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
SOURCES = {e["file"]: e for e in json.loads((DATA / "SOURCES.json").read_text())["from_repositories"]["files"]}
PAIRS = [("1fbl.bcif", "1fbl.cif.gz"), ("2W83.bcif.gz", "2W83.cif.gz")]
EVERYTHING = dict(hetatm=True, water=True, hydrogens=True, default_radius=2.0)
#: per entry: a chain selection and a HETATM selection that keep something
CHAINS = {"1fbl": "A", "2W83": ["B", "E"]}
HETS = {"1fbl": {"ZN", "HTA"}, "2W83": {"GTP", "MG"}}

FLOATS = {"Cartn_x", "Cartn_y", "Cartn_z", "occupancy", "B_iso_or_equiv"}
INTS = {"id", "auth_seq_id", "label_seq_id", "pdbx_PDB_model_num", "label_entity_id", "pdbx_formal_charge"}


def _assert_same(p, q):
    """Atom for atom: labels, coordinates, elements, radii, alternate location kept,
    occupancy and B-factor, model."""
    assert len(p) == len(q)
    for a in (
        "atom_names",
        "residue_names",
        "residue_numbers",
        "chains",
        "elements",
        "hetero",
        "insertion_codes",
        "altlocs",
    ):
        np.testing.assert_array_equal(getattr(p, a), getattr(q, a), err_msg=a)
    np.testing.assert_array_equal(p.balls.centers, q.balls.centers)
    np.testing.assert_array_equal(p.balls.radii, q.balls.radii)
    for a in ("occupancies", "b_factors"):
        np.testing.assert_array_equal(getattr(p, a), getattr(q, a), err_msg=a)  # NaN == NaN here
    assert p.model == q.model and p.probe == q.probe


def _to_bcif(cif_file, out, *, compress=True):
    """Write ``cif_file`` (a biotite CIFFile) as BinaryCIF with biotite: every category,
    numbers as typed arrays, ``.``/``?`` as the column's mask; ``compress`` lets biotite
    choose the encodings (delta, run-length, integer packing, fixed point)."""
    bfile = pdbx.BinaryCIFFile()
    for bname, block in cif_file.items():
        bblock = pdbx.BinaryCIFBlock()
        for cname, cat in block.items():
            cols = {}
            for key, col in cat.items():
                typed = cname == "atom_site"  # other categories' ids may be names ("2W83")
                dtype = np.float64 if typed and key in FLOATS else np.int32 if typed and key in INTS else str
                mask = None if col.mask is None else np.asarray(col.mask.array)
                arr = col.as_array(dtype, masked_value=None if mask is None else ("" if dtype is str else 0))
                cols[key] = pdbx.BinaryCIFColumn(
                    pdbx.BinaryCIFData(arr),
                    None if mask is None or not mask.any() else pdbx.BinaryCIFData(mask.astype(np.uint8)),
                )
            bblock[cname] = pdbx.BinaryCIFCategory(cols)
        bfile[bname] = bblock
    if compress:
        bfile = pdbx.compress(bfile)
    bfile.write(str(out))
    return out


def _cif(path):
    opener = gzip.open if str(path).endswith(".gz") else open
    with opener(path, "rt") as fh:
        return pdbx.CIFFile.read(fh)


# ------------------------------------------------------------------ the shipped files


@pytest.mark.parametrize("file", sorted(SOURCES))
def test_the_shipped_files_are_p2ranks(file):
    e = SOURCES[file]
    data = (DATA / file).read_bytes()
    assert hashlib.sha256(data).hexdigest() == e["sha256"] and len(data) == e["size"]
    assert e["repository"] == "https://github.com/rdk/p2rank" and len(e["commit"]) == 40


@pytest.mark.parametrize("bcif, cif", PAIRS)
def test_the_format_is_recognised(bcif, cif):
    assert detect_format(DATA / bcif) == "bcif"
    assert detect_format(DATA / cif) == "mmcif"


def _selections(entry):
    return [
        {},
        dict(hetatm=False),
        dict(water=True),
        dict(hetatm=HETS[entry]),
        dict(chain=CHAINS[entry]),
        dict(chain=CHAINS[entry], hetatm=False, model=1),
        EVERYTHING,
        dict(probe=1.4, water=True),
        dict(default_radius=1.8, hydrogens=True),
    ]


@pytest.mark.parametrize("bcif, cif", PAIRS)
def test_binary_cif_reads_as_its_text_mmcif(bcif, cif):
    """The PDB's two encodings of one entry: the same atoms, labels, coordinates (the
    file's three decimals, the same floats), radii, occupancies and B-factors, under every
    selection."""
    entry = bcif.split(".")[0]
    for kw in _selections(entry):
        b = read_structure(DATA / bcif, **kw)
        t = read_structure(DATA / cif, **kw)
        assert len(b) > 0, kw
        _assert_same(b, t)
    # coordinates at the file's precision: thousandths of an angstrom
    c = read_structure(DATA / bcif, **EVERYTHING).balls.centers
    np.testing.assert_allclose(c * 1000, np.round(c * 1000), atol=1e-6)


def test_the_selections_select_something():
    """The comparisons above are not vacuous: 2W83's selections differ from each other
    (alternate locations, five chains, waters, ligands)."""
    path = DATA / "2W83.bcif.gz"
    n = {k: len(read_structure(path, **kw)) for k, kw in (("default", {}), ("no_het", dict(hetatm=False)))}
    n["water"] = len(read_structure(path, water=True))
    n["chains"] = len(read_structure(path, chain=CHAINS["2W83"]))
    assert n["no_het"] < n["default"] < n["water"] and n["chains"] < n["default"]
    s = read_structure(path)
    assert set(s.altlocs) == {"", "A"} and set(s.chains) == {"A", "B", "C", "D", "E"}


@pytest.mark.parametrize("bcif, cif", PAIRS)
def test_atom_counts_are_gemmis(bcif, cif):
    """gemmi's structure reader on the text file (first model, first conformer of every
    atom): the same count, with and without waters."""
    st = gemmi.read_structure(str(DATA / cif))
    st.remove_alternative_conformations()
    everything = sum(len(r) for ch in st[0] for r in ch)
    assert len(read_structure(DATA / bcif, **EVERYTHING)) == everything
    st.remove_waters()
    no_water = sum(len(r) for ch in st[0] for r in ch)
    assert no_water < everything
    assert len(read_structure(DATA / bcif, **{**EVERYTHING, "water": False})) == no_water


def test_plain_and_gzip_binary_cif_read_alike(tmp_path):
    raw = (DATA / "1fbl.bcif").read_bytes()
    gz = tmp_path / "1fbl.bcif.gz"
    gz.write_bytes(gzip.compress(raw, mtime=0))
    unnamed = tmp_path / "1fbl.dat"  # the content decides, not the name
    unnamed.write_bytes(raw)
    for p in (gz, unnamed):
        assert detect_format(p) == "bcif"
        _assert_same(read_structure(p, **EVERYTHING), read_structure(DATA / "1fbl.bcif", **EVERYTHING))
    plain = tmp_path / "2W83.bcif"
    plain.write_bytes(gzip.decompress((DATA / "2W83.bcif.gz").read_bytes()))
    _assert_same(read_structure(plain), read_structure(DATA / "2W83.bcif.gz"))


# ------------------------------------------------------------------ round trips through biotite's writer


@pytest.mark.parametrize("compress", [True, False])
def test_biotite_written_binary_cif_of_a_text_mmcif(tmp_path, compress):
    """2W83's text mmCIF, re-encoded by biotite (all categories), reads as the text."""
    out = _to_bcif(_cif(DATA / "2W83.cif.gz"), tmp_path / "2W83_biotite.bcif", compress=compress)
    for kw in _selections("2W83"):
        _assert_same(read_structure(out, **kw), read_structure(DATA / "2W83.cif.gz", **kw))


@pytest.mark.parametrize("compress", [True, False])
def test_biotite_written_binary_cif_of_a_shipped_pdb(tmp_path, compress):
    """1HVR (with its hydrogens), read by biotite's PDB reader and written by its BinaryCIF
    writer, reads as our strict PDB parser reads the PDB file.  biotite holds coordinates
    as float32, so the file's precision is float32's: each number read is the PDB's value
    or that value rounded to float32 (whichever the writer's encoding stored)."""
    pdb = pytest.importorskip("biotite.structure.io.pdb")
    with gzip.open(structure_path("1hvr"), "rt") as fh:
        atoms = pdb.PDBFile.read(fh).get_structure(model=1, extra_fields=["b_factor", "occupancy"])
    bfile = pdbx.BinaryCIFFile()
    pdbx.set_structure(bfile, atoms)
    out = tmp_path / "1hvr.bcif"
    (pdbx.compress(bfile) if compress else bfile).write(str(out))

    def same_to_float32(got, want):
        assert got.shape == want.shape
        assert np.all((got == want) | (got == want.astype(np.float32).astype(np.float64)))

    for kw in (EVERYTHING, {}, dict(chain="B", hetatm=False)):
        b, p = read_structure(out, **kw), read_pdb(structure_path("1hvr"), **kw)
        for a in ("atom_names", "residue_names", "residue_numbers", "chains", "elements", "hetero"):
            np.testing.assert_array_equal(getattr(b, a), getattr(p, a), err_msg=a)
        np.testing.assert_array_equal(b.balls.radii, p.balls.radii)
        for got, want in (
            (b.balls.centers, p.balls.centers),
            (b.b_factors, p.b_factors),
            (b.occupancies, p.occupancies),
        ):
            same_to_float32(got, want)
    assert (read_structure(out, **EVERYTHING).elements == "H").sum() == 330


_HEAD = (
    "group_PDB",
    "id",
    "type_symbol",
    "label_atom_id",
    "label_alt_id",
    "label_comp_id",
    "label_asym_id",
    "label_seq_id",
    "pdbx_PDB_ins_code",
    "Cartn_x",
    "Cartn_y",
    "Cartn_z",
    "occupancy",
    "B_iso_or_equiv",
    "auth_seq_id",
    "auth_asym_id",
    "pdbx_PDB_model_num",
)


def _row(k, model, *, group="ATOM", el="C", name="CA", alt=".", res="ALA", chain="A", seq=1, icode="?", xyz=None):
    x, y, z = xyz or (f"{k * 1.5:.3f}", f"{-k * 0.25:.3f}", f"{model + k / 8:.3f}")
    occ = "?" if k % 7 == 3 else "0.50" if alt != "." else "1.00"
    b = "." if k % 5 == 4 else f"{10 + k:.2f}"
    return (group, str(k), el, name, alt, res, chain, str(seq), icode, x, y, z, occ, b, str(seq), chain, str(model))


def _table(rows, items=_HEAD):
    lines = ["data_test", "loop_"] + [f"_atom_site.{t}" for t in items] + [" ".join(r) for r in rows]
    return "\n".join(lines) + "\n"


def _rich_table():
    """Two models; insertion codes; hydrogens; alternate locations; waters and a ligand;
    unknown occupancies, inapplicable B-factors; a 4-letter chain; quoted names."""
    rows = []
    for model in (1, 2):
        k = 0
        for chain in ("A", "BB", "C123"):
            for seq, icode in ((1, "?"), (2, "?"), (2, "A"), (3, "?")):
                for name, el in (("N", "N"), ("CA", "C"), ("H", "H"), ('"O1\'"', "O")):
                    k += 1
                    rows.append(_row(k, model, el=el, name=name, chain=chain, seq=seq, icode=icode))
            for alt in ("A", "B"):
                k += 1
                rows.append(_row(k, model, name="CB", alt=alt, chain=chain, seq=4, res="SER"))
            k += 1
            rows.append(_row(k, model, group="HETATM", el="O", name="O", res="HOH", chain=chain, seq=100))
            k += 1
            rows.append(_row(k, model, group="HETATM", el="ZN", name="ZN", res="ZN", chain=chain, seq=101))
    return _table(rows)


def test_biotite_written_binary_cif_of_a_built_table(tmp_path):
    """What the shipped entries lack (models, insertion codes, hydrogens, masks, long chain
    names, primed atom names): the table as text, read by our mmCIF reader, and as biotite's
    BinaryCIF, read by our BinaryCIF reader, agree under every selection."""
    text = tmp_path / "rich.cif"
    text.write_text(_rich_table())
    out = _to_bcif(pdbx.CIFFile.read(str(text)), tmp_path / "rich.bcif")
    sels = [
        {},
        dict(model=2),
        dict(model=2, hydrogens=True, water=True),
        dict(chain="C123"),
        dict(chain=["A", "BB"], hetatm=False),
        dict(hetatm={"ZN"}, hydrogens=True),
        EVERYTHING,
    ]
    for kw in sels:
        b, t = read_structure(out, **kw), read_structure(text, **kw)
        assert len(b) > 0
        _assert_same(b, t)
    s = read_structure(out, **EVERYTHING)
    assert s.model == 1 and read_structure(out, model=2).model == 2
    assert "A" in set(s.insertion_codes) and "O1'" in set(s.atom_names) and "C123" in set(s.chains)
    assert np.isnan(s.occupancies).any() and np.isnan(s.b_factors).any()
    assert not np.isnan(s.occupancies).all()
    with pytest.raises(ValueError, match=r"rich\.bcif' has no model 3 \(pdbx_PDB_model_num holds: \[1, 2\]\)"):
        read_structure(out, model=3)


# ------------------------------------------------------------------ malformed files


def _good(tmp_path):
    """A small biotite-written BinaryCIF (two models) and its MessagePack map."""
    text = tmp_path / "small.cif"
    text.write_text(_table([_row(k, 1) for k in range(1, 6)] + [_row(k, 2) for k in range(1, 6)]))
    out = _to_bcif(pdbx.CIFFile.read(str(text)), tmp_path / "small.bcif")
    return out, msgpack.unpackb(out.read_bytes())


def _columns(doc):
    return {c["name"]: c for c in doc["dataBlocks"][0]["categories"][0]["columns"]}


def _write(tmp_path, doc, name="bad.bcif"):
    path = tmp_path / name
    path.write_bytes(msgpack.packb(doc))
    return path


def test_a_small_file_reads(tmp_path):
    out, _ = _good(tmp_path)
    _assert_same(read_structure(out, model=2), read_structure(tmp_path / "small.cif", model=2))


def test_no_atom_site_category(tmp_path):
    _, doc = _good(tmp_path)
    doc["dataBlocks"][0]["categories"][0]["name"] = "_atom_sight"
    with pytest.raises(ValueError, match=r"bad\.bcif' has no atom_site category \(data blocks: \['test'\]\)"):
        read_structure(_write(tmp_path, doc))


@pytest.mark.parametrize(
    "drop, match",
    [
        (("Cartn_y",), r"no atom_site\.Cartn_y column"),
        (("type_symbol",), r"no atom_site\.type_symbol column"),
        (("auth_seq_id", "label_seq_id"), r"no atom_site\.auth_seq_id or atom_site\.label_seq_id column"),
    ],
)
def test_a_required_column_missing(tmp_path, drop, match):
    _, doc = _good(tmp_path)
    cat = doc["dataBlocks"][0]["categories"][0]
    cat["columns"] = [c for c in cat["columns"] if c["name"] not in drop]
    with pytest.raises(ValueError, match=rf"bad\.bcif': the atom_site category has {match} \(data block test\)"):
        read_structure(_write(tmp_path, doc))


def test_label_columns_stand_in_for_auth_ones(tmp_path):
    """As in mmCIF: without auth_seq_id, label_seq_id is the residue number."""
    _, doc = _good(tmp_path)
    cat = doc["dataBlocks"][0]["categories"][0]
    cat["columns"] = [c for c in cat["columns"] if c["name"] != "auth_seq_id"]
    assert list(read_structure(_write(tmp_path, doc)).residue_numbers) == [1] * 5


@pytest.mark.parametrize("column", ["Cartn_y", "auth_asym_id", "label_alt_id", "pdbx_PDB_model_num"])
def test_a_column_of_the_wrong_length(tmp_path, column):
    """A column spliced from a file of one row fewer: named, with both lengths."""
    _, doc = _good(tmp_path)
    text = tmp_path / "short.cif"
    text.write_text(_table([_row(k, 1) for k in range(1, 6)] + [_row(k, 2) for k in range(1, 5)]))
    short = msgpack.unpackb(_to_bcif(pdbx.CIFFile.read(str(text)), tmp_path / "short.bcif").read_bytes())
    cat = doc["dataBlocks"][0]["categories"][0]
    cat["columns"] = [_columns(short)[column] if c["name"] == column else c for c in cat["columns"]]
    with pytest.raises(
        ValueError,
        match=rf"bad\.bcif': atom_site\.{column} \(data block test\) has \(9,\) values where the category has 10 rows",
    ):
        read_structure(_write(tmp_path, doc))


def test_an_undecodable_column(tmp_path):
    _, doc = _good(tmp_path)
    _columns(doc)["Cartn_x"]["data"]["encoding"] = [{"kind": "NoSuchEncoding"}]
    with pytest.raises(ValueError, match=r"bad\.bcif': atom_site\.Cartn_x \(data block test\) cannot be decoded"):
        read_structure(_write(tmp_path, doc))
    _, doc = _good(tmp_path)
    _columns(doc)["Cartn_z"]["data"]["data"] = b"\x00\x01\x02"  # bytes that do not fill one value
    with pytest.raises(ValueError, match=r"bad\.bcif': atom_site\.Cartn_z \(data block test\) cannot be decoded"):
        read_structure(_write(tmp_path, doc))


@pytest.mark.parametrize(
    "row, match",
    [
        (_row(3, 1, xyz=("1.0", "?", "3.0")), r"atom_site row 3 \(id 3\), atom_site\.Cartn_y is '\?' \(unknown\)"),
        (_row(3, 1, xyz=("1.0", "2.0", ".")), r"atom_site row 3 \(id 3\), atom_site\.Cartn_z is '\.' \(unknown\)"),
        (_row(3, 1, group="ATOMS"), r"atom_site row 3 \(id 3\), atom_site\.group_PDB is neither ATOM nor HETATM"),
        (_row(3, 1, el="C1"), r"atom_site row 3 \(id 3\), atom_site\.type_symbol is not an element symbol: 'C1'"),
        (_row(3, 1, name="?"), r"atom_site row 3 \(id 3\), atom_site\.label_atom_id is empty"),
    ],
)
def test_a_bad_value_is_named_by_row_and_column(tmp_path, row, match):
    """The mmCIF reader refuses the same values, as the text says."""
    text = tmp_path / "bad.cif"
    text.write_text(_table([_row(1, 1), _row(2, 1), row, _row(4, 1)]))
    out = _to_bcif(pdbx.CIFFile.read(str(text)), tmp_path / "bad.bcif")
    with pytest.raises(ValueError, match=rf"bad\.bcif': {match}"):
        read_structure(out)
    with pytest.raises(ValueError):
        read_structure(text)


def test_a_masked_residue_number_is_refused(tmp_path):
    text = tmp_path / "bad.cif"
    r = list(_row(2, 1))
    r[_HEAD.index("auth_seq_id")] = "?"
    text.write_text(_table([_row(1, 1), tuple(r)]))
    out = _to_bcif(pdbx.CIFFile.read(str(text)), tmp_path / "bad.bcif")
    with pytest.raises(
        ValueError, match=r"bad\.bcif': atom_site row 2 \(id 2\), atom_site\.auth_seq_id is not an integer"
    ):
        read_structure(out)


@pytest.mark.parametrize(
    "data, match",
    [
        (b"\x81\xaadataBlocks", "is not a readable BinaryCIF file"),  # a map cut after its key
        (b"\x81\xaadataBlocks\xc0", "is not a readable BinaryCIF file"),  # dataBlocks: nil
        (b"\x81\xaadataBlocks\x90\x00", "is not a readable BinaryCIF file"),  # trailing bytes
        (b"\x81\xa1x\x90", "is not a readable BinaryCIF file"),  # a map without dataBlocks
        (b"", "is empty"),
    ],
)
def test_not_binary_cif(tmp_path, data, match):
    path = tmp_path / "bad.bcif"
    path.write_bytes(data)
    with pytest.raises(ValueError, match=rf"bad\.bcif' {match}"):
        read_structure(path, format="bcif")


def test_a_truncated_file(tmp_path):
    raw = (DATA / "1fbl.bcif").read_bytes()
    cut = tmp_path / "cut.bcif"
    cut.write_bytes(raw[: len(raw) // 2])
    assert detect_format(cut) == "bcif"
    with pytest.raises(ValueError, match=r"cut\.bcif' is not a readable BinaryCIF file"):
        read_structure(cut)
    gz = (DATA / "2W83.bcif.gz").read_bytes()
    cutgz = tmp_path / "cut.bcif.gz"
    cutgz.write_bytes(gz[: len(gz) // 2])
    with pytest.raises(ValueError, match=r"cut\.bcif\.gz' is not a readable gzip file"):
        read_structure(cutgz, format="bcif")


def test_max_bytes_bounds_the_decompressed_file(tmp_path):
    with pytest.raises(ValueError, match=r"2W83\.bcif\.gz' decompresses to more than max_bytes=1000"):
        read_structure(DATA / "2W83.bcif.gz", max_bytes=1000)


def test_the_arguments_are_checked_before_reading():
    with pytest.raises(ValueError, match="probe"):
        read_structure(DATA / "1fbl.bcif", probe=-1.0)
    with pytest.raises(TypeError, match="water must be a bool"):
        read_structure(DATA / "1fbl.bcif", water="yes")


# ------------------------------------------------------------------ biotite stays optional


def _run(code):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)


def test_without_biotite_the_error_says_what_to_install():
    """With biotite made unimportable: PDB and mmCIF still read; BinaryCIF raises an
    ImportError naming the extra."""
    code = f"""
import sys
sys.modules["biotite"] = None
import shapelab as sl
print(len(sl.read_structure({str(DATA / "1fbl.cif.gz")!r})))
print(len(sl.read_structure(sl.datasets.structure_path("1hvr"))))
try:
    sl.read_structure({str(DATA / "1fbl.bcif")!r})
except ImportError as e:
    print("ImportError:", e)
"""
    r = _run(code)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.strip().splitlines()
    assert lines[0] == str(len(read_structure(DATA / "1fbl.cif.gz")))
    assert lines[2].startswith("ImportError: reading BinaryCIF needs biotite")
    assert 'pip install "shapelab[bcif]"' in lines[2]


def test_the_probe_can_fail():
    """The subprocess above does see biotite when it is importable."""
    r = _run(f"import shapelab as sl\nprint(len(sl.read_structure({str(DATA / '1fbl.bcif')!r})))")
    assert r.returncode == 0 and int(r.stdout) == len(read_structure(DATA / "1fbl.bcif"))


# ------------------------------------------------------------------ second reading (breaking it)


def test_a_masked_integer_in_another_model_does_not_stop_this_one(tmp_path):
    """A '?' residue number in model 2 is model 2's error: model 1 reads, as in mmCIF (the
    reader once raised an IndexError here)."""
    bad = list(_row(4, 2))
    bad[_HEAD.index("auth_seq_id")] = "?"
    text = tmp_path / "m.cif"
    text.write_text(_table([_row(k, 1) for k in range(1, 4)] + [_row(k, 2) for k in range(1, 4)] + [tuple(bad)]))
    out = _to_bcif(pdbx.CIFFile.read(str(text)), tmp_path / "m.bcif")
    _assert_same(read_structure(out, model=1, **EVERYTHING), read_structure(text, model=1, **EVERYTHING))
    with pytest.raises(
        ValueError, match=r"m\.bcif': atom_site row 7 \(id 4\), atom_site\.auth_seq_id is not an integer"
    ):
        read_structure(out, model=2)
    with pytest.raises(ValueError, match=r"auth_seq_id is not an integer"):
        read_structure(text, model=2)


def _with_column(tmp_path, item, column, name="s.bcif"):
    """The small two-model file with one atom_site column replaced."""
    out, _ = _good(tmp_path)
    f = pdbx.BinaryCIFFile.read(str(out))
    cat = f["test"]["atom_site"]
    cols = {k: cat[k] for k in cat.keys()}
    cols[item] = column
    f["test"]["atom_site"] = pdbx.BinaryCIFCategory(cols)
    f.write(str(tmp_path / name))
    return tmp_path / name


@pytest.mark.parametrize("value", ["1_000", " 1.5", "1.5 ", "nan", "infinity", "0x10", "\uff11"])
def test_a_number_written_as_a_string_is_what_mmcif_accepts(tmp_path, value):
    """Coordinates stored as strings are read by the CIF number syntax of the mmCIF
    reader, not by Python's float() (which takes "1_000", " 1.5", "nan", full-width digits)."""
    col = pdbx.BinaryCIFColumn(pdbx.BinaryCIFData(np.array([value] + ["1.0"] * 9)))
    path = _with_column(tmp_path, "Cartn_x", col)
    with pytest.raises(ValueError, match=r"s\.bcif': atom_site row 1 \(id 1\), atom_site\.Cartn_x is not a number: "):
        read_structure(path)
    if value.strip() == value and value.isascii():  # the same token, unquoted, in the text mmCIF
        text = tmp_path / "s.cif"
        text.write_text(_table([_row(1, 1, xyz=(value, "2.0", "3.0")), _row(2, 1)]))
        with pytest.raises(ValueError, match=r"_atom_site\.Cartn_x is not a number"):
            read_structure(text)


def test_a_number_with_an_uncertainty_as_a_string(tmp_path):
    col = pdbx.BinaryCIFColumn(pdbx.BinaryCIFData(np.array(["1.25(3)", "-2e1"] + ["1.0"] * 8)))
    s = read_structure(_with_column(tmp_path, "Cartn_x", col), hydrogens=True)
    assert list(s.balls.centers[:2, 0]) == [1.25, -20.0]


def test_every_encoding_reads_as_the_text(tmp_path):
    """Each BinaryCIF encoding chosen explicitly (fixed point into float64 and float32, delta,
    integer packing of 1 and 2 bytes, signed and unsigned, run-length, interval
    quantization, string tables with run-length indices and delta offsets, run-length
    masks) on negative residue numbers, insertion codes and alternate locations of equal
    occupancy, in two models: the same atoms as the text mmCIF."""
    enc = pytest.importorskip("biotite.structure.io.pdbx.encoding")
    rows, k = [], 0
    for model in (1, 2):
        for seq, icode in ((-5, "?"), (-5, "A"), (-4, "?"), (0, "?"), (3, "B")):
            for alt in ("A", "B") if seq == 0 else (".",):
                k += 1
                rows.append(_row(k, model, seq=seq, icode=icode, alt=alt, name="CA" if alt == "." else "CB"))
    text = tmp_path / "enc.cif"
    text.write_text(_table(rows))
    f64, f32, i32 = enc.TypeCode.FLOAT64, enc.TypeCode.FLOAT32, enc.TypeCode.INT32

    def packed(n, unsigned=False):
        return [enc.IntegerPackingEncoding(byte_count=n, is_unsigned=unsigned), enc.ByteArrayEncoding()]

    chains = {
        "Cartn_x": [enc.FixedPointEncoding(1000, src_type=f64), enc.DeltaEncoding(), *packed(2)],
        "Cartn_y": [enc.FixedPointEncoding(1000, src_type=f64), *packed(1)],
        "Cartn_z": [enc.FixedPointEncoding(1000, src_type=f32), enc.ByteArrayEncoding()],
        "occupancy": [enc.IntervalQuantizationEncoding(0.0, 1.0, 101, src_type=f64), enc.RunLengthEncoding()]
        + [enc.ByteArrayEncoding()],
        "auth_seq_id": [enc.DeltaEncoding(src_type=i32), enc.RunLengthEncoding(), *packed(1)],
        "label_seq_id": [enc.RunLengthEncoding(), enc.ByteArrayEncoding()],
        "pdbx_PDB_model_num": [enc.RunLengthEncoding(), *packed(2, unsigned=True)],
        "id": [enc.DeltaEncoding(), *packed(1, unsigned=True)],
    }
    cols = {}
    for key, col in pdbx.CIFFile.read(str(text))["test"]["atom_site"].items():
        mask = None if col.mask is None else np.asarray(col.mask.array)
        if key in chains:
            dtype = np.float64 if key.startswith(("Cartn", "occupancy")) else np.int32
            arr, chain = col.as_array(dtype, masked_value=None if mask is None else 0), chains[key]
        else:
            arr = col.as_array(str, masked_value=None if mask is None else "")
            chain = [
                enc.StringArrayEncoding(
                    data_encoding=[enc.RunLengthEncoding(), *packed(1)],
                    offset_encoding=[enc.DeltaEncoding(), *packed(1)],
                )
            ]
        m = None
        if mask is not None and mask.any():
            m = pdbx.BinaryCIFData(mask.astype(np.uint8), [enc.RunLengthEncoding(), enc.ByteArrayEncoding()])
        cols[key] = pdbx.BinaryCIFColumn(pdbx.BinaryCIFData(arr, chain), m)
    bfile, block = pdbx.BinaryCIFFile(), pdbx.BinaryCIFBlock()
    block["atom_site"] = pdbx.BinaryCIFCategory(cols)
    bfile["test"] = block
    out = tmp_path / "enc.bcif"
    bfile.write(str(out))
    kinds = {e["kind"] for c in _columns(msgpack.unpackb(out.read_bytes())).values() for e in c["data"]["encoding"]}
    assert kinds == {
        "FixedPoint",
        "Delta",
        "IntegerPacking",
        "ByteArray",
        "RunLength",
        "IntervalQuantization",
        "StringArray",
    }
    for kw in ({}, dict(model=2), EVERYTHING, dict(model=2, **EVERYTHING)):
        b = read_structure(out, **kw)
        _assert_same(b, read_structure(text, **kw))
        assert list(b.residue_numbers) == [-5, -5, -4, 0, 3] and list(b.insertion_codes) == ["", "A", "", "", "B"]
    assert read_structure(out).altlocs[3] == "A" and read_structure(out, model=2).altlocs[3] == "B"  # '?' loses


def _bomb(tmp_path, item, data, encoding, name="bomb.bcif"):
    _, doc = _good(tmp_path)
    _columns(doc)[item]["data"] = {"data": data, "encoding": encoding}
    return _write(tmp_path, doc, name)


@pytest.mark.parametrize(
    "encoding, match",
    [
        ([{"kind": "RunLength", "srcType": 3, "srcSize": 2**31 - 1}, {"kind": "ByteArray", "type": 3}], "RunLength"),
        ([{"kind": "RunLength", "srcType": 3}, {"kind": "ByteArray", "type": 3}], "RunLength"),  # sums the runs
        (
            [{"kind": "IntegerPacking", "byteCount": 1, "isUnsigned": False, "srcSize": 2**31 - 1}]
            + [{"kind": "ByteArray", "type": 1}],
            "IntegerPacking",
        ),
    ],
)
def test_an_encoding_that_asks_for_more_than_the_rows_is_refused_before_decoding(
    tmp_path, encoding, match, monkeypatch
):
    """A few bytes of run-length encoding (value 1, 2**31 - 1 times) would have biotite
    allocate gigabytes: the declared sizes are checked against the category's rowCount
    first, and nothing is decoded."""
    data = np.array([1, 2**31 - 1], "<i4").tobytes()
    path = _bomb(tmp_path, "pdbx_PDB_model_num", data, encoding)
    bcif = pytest.importorskip("biotite.structure.io.pdbx.bcif")

    def never(*a, **k):
        raise AssertionError("decoded")

    monkeypatch.setattr(bcif, "decode_stepwise", never)
    with pytest.raises(
        ValueError,
        match=rf"bomb\.bcif': atom_site\.pdbx_PDB_model_num \(data block test\): its {match} encoding declares srcSize=",
    ):
        read_structure(path)


def test_a_row_count_past_max_bytes_is_refused(tmp_path):
    """A row count whose decoded float64 column would exceed max_bytes, refused as the
    file itself would be."""
    _, doc = _good(tmp_path)
    doc["dataBlocks"][0]["categories"][0]["rowCount"] = 2**40
    path = _write(tmp_path, doc)
    with pytest.raises(
        ValueError, match=r"bad\.bcif': atom_site \(data block test\) has 1099511627776 rows: decoded, one"
    ):
        read_structure(path)


def test_read_pdb_and_the_mmcif_reader_name_binary_cif():
    for file in ("1fbl.bcif", "2W83.bcif.gz"):
        with pytest.raises(
            ValueError, match=rf"line 1: '.*{file}' is a BinaryCIF file .*read it with shapelab\.read_structure"
        ):
            read_pdb(DATA / file)
        with pytest.raises(ValueError, match=rf"{file}' is a BinaryCIF file .*not mmCIF text: read it with"):
            read_structure(DATA / file, format="mmcif")


def test_a_damaged_file_named_bcif_is_reported_as_binary_cif(tmp_path):
    """Content decides, but content that is neither BinaryCIF nor mmCIF in a file named
    .bcif goes to the BinaryCIF reader, which says what is wrong (it was read as a PDB
    file: "holds no ATOM or HETATM records"); the same bytes named .pdb stay PDB."""
    for name, data in (("junk.bcif", b"junk"), ("junk.bcif.gz", gzip.compress(b"\x00\x01junk"))):
        (tmp_path / name).write_bytes(data)
        assert detect_format(tmp_path / name) == "bcif"
        with pytest.raises(ValueError, match=rf"{name}' is not a readable BinaryCIF file"):
            read_structure(tmp_path / name)
    (tmp_path / "junk.pdb").write_bytes(b"junk")
    assert detect_format(tmp_path / "junk.pdb") == "pdb"


def test_a_long_string_in_a_string_table_is_refused_before_decoding(tmp_path, monkeypatch):
    """biotite decodes a string table into fixed-width strings as wide as its longest: one
    string of 2**20 characters in 10 rows is 40 MiB (4 bytes a character), past
    max_bytes=2**24 though the file is a megabyte; refused from the offsets alone."""
    long = "C" * 2**20
    col = pdbx.BinaryCIFColumn(pdbx.BinaryCIFData(np.array([long] + ["C"] * 9)))
    path = _with_column(tmp_path, "type_symbol", col, name="wide.bcif")
    bcif = pytest.importorskip("biotite.structure.io.pdbx.bcif")
    decode = bcif.decode_stepwise

    def only_offsets(data, encoding):  # the offsets may be decoded (they are small), the column not
        if any(type(e).__name__ == "StringArrayEncoding" for e in encoding):
            raise AssertionError("decoded")
        return decode(data, encoding)

    monkeypatch.setattr(bcif, "decode_stepwise", only_offsets)
    with pytest.raises(
        ValueError, match=r"wide\.bcif': atom_site\.type_symbol \(data block test\): its longest string has 1048576"
    ):
        read_structure(path, max_bytes=2**24)
    monkeypatch.undo()
    with pytest.raises(ValueError, match=r"type_symbol is not an element symbol"):  # read, then refused
        read_structure(path, max_bytes=2**26)


def test_real_binary_cif_files_read_within_the_size_checks():
    """The checks refuse nothing the PDB's tools wrote: the shipped files read at a max_bytes
    of 4 times their decompressed size."""
    for file in ("1fbl.bcif", "2W83.bcif.gz"):
        size = (
            len(gzip.decompress((DATA / file).read_bytes())) if file.endswith(".gz") else (DATA / file).stat().st_size
        )
        assert len(read_structure(DATA / file, max_bytes=4 * size, **EVERYTHING)) > 1000


def test_a_mask_value_that_is_not_binary_cifs(tmp_path):
    """A mask holds 0, 1 ('.') or 2 ('?'); a 5 was read as '?' (and as NaN in an optional column)."""
    for item in ("Cartn_x", "occupancy"):
        _, doc = _good(tmp_path)
        _columns(doc)[item]["mask"] = {"data": b"\x00" * 9 + b"\x05", "encoding": [{"kind": "ByteArray", "type": 4}]}
        with pytest.raises(ValueError, match=rf"bad\.bcif': atom_site\.{item} \(data block test\) has a mask value 5"):
            read_structure(_write(tmp_path, doc), model=2, hydrogens=True)


def test_an_undecodable_column_says_why(tmp_path):
    """biotite wraps the reason in a DeserializationError; the message carries it."""
    _, doc = _good(tmp_path)
    _columns(doc)["Cartn_x"]["data"]["data"] = "not bytes"
    with pytest.raises(ValueError, match=r"Cartn_x \(data block test\) cannot be decoded: .*\(TypeError: "):
        read_structure(_write(tmp_path, doc))


def test_category_names_ignore_case(tmp_path):
    """CIF names ignore case, as the mmCIF reader's do: _ATOM_SITE is atom_site."""
    _, doc = _good(tmp_path)
    doc["dataBlocks"][0]["categories"][0]["name"] = "_ATOM_Site"
    _assert_same(read_structure(_write(tmp_path, doc), model=2), read_structure(tmp_path / "small.cif", model=2))
    text = (tmp_path / "small.cif").read_text().replace("_atom_site.", "_ATOM_SITE.")
    (tmp_path / "upper.cif").write_text(text)
    assert len(read_structure(tmp_path / "upper.cif", model=2)) == len(read_structure(tmp_path / "small.cif", model=2))
