"""Tests of shapelab.io: the PDB reader and writer."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from shapelab import Balls
from shapelab.io import VDW_RADII, read_pdb, vdw_radius, write_pdb


def atom(serial=1, name=" CA ", resn="ALA", chain="A", resi=1, x=0.0, y=0.0, z=0.0,
         element="C", rec="ATOM", alt=" "):
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
    p = write(tmp_path, [
        "HEADER    TEST",
        "REMARK   1 anything at all, even ATOM in the middle",
        atom(1, " N  ", element="N", x=1.0, y=2.0, z=3.0),
        atom(2, " CA ", element="C", x=-1.5, y=0.25, z=1e3 - 0.001),
        "TER",
        atom(3, "ZN  ", resn="ZN", element="ZN", rec="HETATM", resi=101, x=5, y=5, z=5),
        "CONECT    1    2",
        "END",
    ])
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
    for e, r in {"H": 1.20, "C": 1.70, "N": 1.55, "O": 1.52, "P": 1.80, "S": 1.80,
                 "F": 1.47, "Cl": 1.75, "Br": 1.85, "I": 1.98, "Se": 1.90}.items():
        assert VDW_RADII[e] == r
        assert vdw_radius(e.upper()) == r and vdw_radius(e.lower()) == r
    with pytest.raises(ValueError, match="Bondi"):
        vdw_radius("Fe")


def test_endmdl_reads_only_the_first_model(tmp_path):
    p = write(tmp_path, [
        "MODEL        1", atom(1, x=1), atom(2, x=2), "ENDMDL",
        "MODEL        2", atom(1, x=10), atom(2, x=20), atom(3, x=30), "ENDMDL", "END",
    ])
    s = read_pdb(p)
    assert s.balls.centers[:, 0].tolist() == [1.0, 2.0]


def test_end_stops_reading(tmp_path):
    p = write(tmp_path, [atom(1), "END", "this line is garbage and must not be read"])
    assert len(read_pdb(p)) == 1


def test_alternate_locations_keep_the_first(tmp_path):
    p = write(tmp_path, [
        atom(1, " N  ", element="N"),
        atom(2, " CB ", alt="A", x=1), atom(3, " CB ", alt="B", x=2),
        atom(4, " CG ", alt="A", x=3), atom(5, " CG ", alt="B", x=4),
    ])
    assert read_pdb(p).balls.centers[:, 0].tolist() == [0.0, 1.0, 3.0]


def test_element_from_atom_name_when_columns_blank(tmp_path):
    def bare(name, resn="ALA"):
        return atom(1, name, resn=resn)[:66]  # cut before the element columns
    cases = {" CA ": "C", " N  ": "N", " OG1": "O", "1HG2": "H", "HG21": "H", " SD ": "S",
             "CL  ": "Cl", "BR  ": "Br"}
    for name, want in cases.items():
        p = write(tmp_path, [bare(name)])
        assert read_pdb(p).elements[0] == want, name
    # "CA  " left-justified is calcium, which Bondi does not list
    p = write(tmp_path, [bare("CA  ", "CA")])
    with pytest.raises(ValueError, match="'Ca'"):
        read_pdb(p)
    assert read_pdb(p, default_radius=2.0).balls.radii[0] == 2.0


# --------------------------------------------------------------- errors
def test_unknown_element(tmp_path):
    p = write(tmp_path, [atom(1), atom(2, "FE  ", resn="HEM", element="FE", rec="HETATM")])
    with pytest.raises(ValueError, match=r"line 2: element 'Fe'.*default_radius"):
        read_pdb(p)
    s = read_pdb(p, default_radius=2.0, probe=0.5)
    assert s.balls.radii.tolist() == [1.7 + 0.5, 2.0 + 0.5]


@pytest.mark.parametrize("bad, what", [
    (lambda l: l[:40], "truncated"),
    (lambda l: l[:30] + "   1.x.0" + l[38:], "x"),
    (lambda l: l[:38] + "     nan" + l[46:], "finite"),
    (lambda l: l[:46] + "        " + l[54:], "z"),
    (lambda l: l[:22] + "12A " + l[26:], "residue number"),
    (lambda l: l[:76] + "C1", "element"),
])
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
    p = write_pdb(tmp_path / "rt.pdb", b, elements, atom_names=names, residue_names=["GLY"] * n,
                  residue_numbers=np.arange(n) - 5, chains="B", hetero=het, title="round trip")
    s = read_pdb(p)
    assert np.abs(s.balls.centers - c).max() <= 5e-4 + 1e-9
    assert np.array_equal(s.balls.radii, b.radii)
    assert list(s.elements) == list(elements)
    assert list(s.atom_names) == names
    assert list(s.residue_numbers) == list(range(-5, n - 5))
    assert set(s.chains) == {"B"} and np.array_equal(s.hetero, het)
    # and a second round trip is exact
    p2 = write_pdb(tmp_path / "rt2.pdb", s.balls, s.elements, atom_names=s.atom_names,
                   residue_names=s.residue_names, residue_numbers=s.residue_numbers,
                   chains=s.chains, hetero=s.hetero, title="round trip")
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
    with pytest.raises(TypeError):
        write_pdb(tmp_path / "a.pdb", np.zeros((1, 3)), "C")


# --------------------------------------------------------------- fuzz
_LINE = st.one_of(
    st.text(max_size=90),
    st.builds(lambda head, rest: head + rest,
              st.sampled_from(["ATOM  ", "HETATM", "END", "ENDMDL", "MODEL ", "REMARK"]),
              st.text(alphabet=st.sampled_from(list(" 0123456789.-+eEnaifCNOSHZ\t\x00é")), max_size=84)),
    st.builds(lambda ln, cut: ln[:cut],
              st.builds(atom, x=st.floats(-999, 9999), y=st.floats(-999, 9999), z=st.floats(-999, 9999),
                        element=st.sampled_from(["C", "N", "O", "FE", "XX", "  "])),
              st.integers(0, 80)),
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
