"""Reading and writing molecules as balls: a small, strict PDB reader (Notes §23.1).

The notes model a molecule as a union of balls :math:`\\bigcup B_i`, one ball per atom,
with the atom's van der Waals radius.  Adding a *probe* radius :math:`p` to every ball
gives the solvent-accessible model (Lee & Richards 1971): a water molecule of radius
:math:`p` can touch the van der Waals surface exactly where its centre lies on the
boundary of :math:`\\bigcup B(z_i, r_i + p)`.

Only the fixed-column ATOM and HETATM records of the PDB format (wwPDB, *Atomic
Coordinate Entry Format Description*, v3.3) are read; nothing in a file is ever
evaluated or executed.

Radii
-----
:data:`VDW_RADII` is the table of A. Bondi, "van der Waals Volumes and Radii",
*J. Phys. Chem.* **68**, 441–451 (1964), Table I (values in Å), completed for the
main-group elements Bondi does not list (Be, B, Al, Ca, Ge, Rb, Sr, Sb, Cs, Ba, Bi,
Po, At, Rn, Fr, Ra) by M. Mantina, A. C. Chamberlin, R. Valero, C. J. Cramer and
D. G. Truhlar, "Consistent van der Waals Radii for the Whole Main Group",
*J. Phys. Chem. A* **113**, 5806–5812 (2009), Table 12.  Where Bondi has a value it is
kept (Mantina et al. give H 1.10, Li 1.81 and Br 1.83 instead of Bondi's 1.20, 1.82
and 1.85; the rest of their Table 12 is Bondi's).  Most transition metals (Fe, Mn,
Co, Mo, ...) have no consistent van der Waals radius in either table: an atom of
such an element raises unless a ``default_radius`` (or ``radii=``) is given.
"""

from __future__ import annotations

import contextlib
import gzip
import math
import os
import re
import tempfile
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._toolkit.validate import as_finite_scalar, as_positive_int, check_balls, readonly
from .balls import Balls

__all__ = [
    "VDW_RADII",
    "WATER_RESIDUES",
    "STANDARD_RESIDUES",
    "MAX_PDB_BYTES",
    "PDBStructure",
    "read_pdb",
    "write_pdb",
    "write_mmcif",
    "vdw_radius",
]

#: van der Waals radii in Å: Bondi (1964), J. Phys. Chem. 68:441, Table I, and for the
#: main-group elements Bondi does not list (marked M), Mantina et al. (2009),
#: J. Phys. Chem. A 113:5806, Table 12.
VDW_RADII: dict[str, float] = {
    "H": 1.20,
    "He": 1.40,
    "Li": 1.82,
    "Be": 1.53,  # M
    "B": 1.92,  # M
    "C": 1.70,
    "N": 1.55,
    "O": 1.52,
    "F": 1.47,
    "Ne": 1.54,
    "Na": 2.27,
    "Mg": 1.73,
    "Al": 1.84,  # M
    "Si": 2.10,
    "P": 1.80,
    "S": 1.80,
    "Cl": 1.75,
    "Ar": 1.88,
    "K": 2.75,
    "Ca": 2.31,  # M
    "Ni": 1.63,
    "Cu": 1.40,
    "Zn": 1.39,
    "Ga": 1.87,
    "Ge": 2.11,  # M
    "As": 1.85,
    "Se": 1.90,
    "Br": 1.85,
    "Kr": 2.02,
    "Rb": 3.03,  # M
    "Sr": 2.49,  # M
    "Pd": 1.63,
    "Ag": 1.72,
    "Cd": 1.58,
    "In": 1.93,
    "Sn": 2.17,
    "Sb": 2.06,  # M
    "Te": 2.06,
    "I": 1.98,
    "Xe": 2.16,
    "Cs": 3.43,  # M
    "Ba": 2.68,  # M
    "Pt": 1.72,
    "Au": 1.66,
    "Hg": 1.55,
    "Tl": 1.96,
    "Pb": 2.02,
    "Bi": 2.07,  # M
    "Po": 1.97,  # M
    "At": 2.02,  # M
    "Rn": 2.20,  # M
    "Fr": 3.48,  # M
    "Ra": 2.83,  # M
    "U": 1.86,
}
_UPPER = {k.upper(): k for k in VDW_RADII}
#: Every element symbol (to read atom names; radii exist only for those in VDW_RADII).
_SYMBOLS = {
    e.upper(): e
    for e in (
        "H He Li Be B C N O F Ne Na Mg Al Si P S Cl Ar K Ca Sc Ti V Cr Mn Fe Co Ni Cu Zn Ga Ge "
        "As Se Br Kr Rb Sr Y Zr Nb Mo Tc Ru Rh Pd Ag Cd In Sn Sb Te I Xe Cs Ba La Ce Pr Nd Pm Sm "
        "Eu Gd Tb Dy Ho Er Tm Yb Lu Hf Ta W Re Os Ir Pt Au Hg Tl Pb Bi Po At Rn Fr Ra Ac Th Pa U "
        "Np Pu Am Cm Bk Cf Es Fm Md No Lr"
    ).split()
}


def vdw_radius(element: str) -> float:
    """The van der Waals radius of ``element`` in Å (case-insensitive symbol), from :data:`VDW_RADII`.

    Bondi's (1964) value, or for a main-group element Bondi does not list, that of
    Mantina et al. (2009); Notes §23.1 (one ball per atom, of its van der Waals radius).

    Raises
    ------
    ValueError
        For an element in neither table (most transition metals: Fe, Mn, Co, Mo, ...).

    See Also
    --------
    read_pdb : reads these radii; ``default_radius=`` or ``radii=`` for other elements.

    References
    ----------
    A. Bondi, "van der Waals Volumes and Radii", *J. Phys. Chem.* **68**, 441–451 (1964).
    M. Mantina, A. C. Chamberlin, R. Valero, C. J. Cramer, D. G. Truhlar, "Consistent
    van der Waals Radii for the Whole Main Group", *J. Phys. Chem. A* **113**, 5806–5812
    (2009), Table 12.

    Examples
    --------
    >>> vdw_radius("C"), vdw_radius("ca"), vdw_radius("Be")
    (1.7, 2.31, 1.53)
    """
    if not isinstance(element, str):
        raise TypeError(f"element must be a str, got {type(element).__name__}")
    key = _UPPER.get(element.strip().upper())
    if key is None:
        raise ValueError(
            f"element {element!r} is in neither Bondi's (1964) nor Mantina et al.'s (2009) table of van der Waals radii"
        )
    return VDW_RADII[key]


#: Residue names that are water in PDB, AMBER, CHARMM and GROMACS files (``TIP`` is how
#: CHARMM's ``TIP3`` reads: :func:`read_pdb` takes column 21 as part of the chain).
WATER_RESIDUES = frozenset(
    {
        "HOH",
        "WAT",
        "H2O",
        "DOD",
        "D2O",
        "TIP",
        "TIP3",
        "TIP4",
        "TIP5",
        "T3P",
        "T4P",
        "T5P",
        "SOL",
        "SPC",
        "SPCE",
    }
)
#: Polymer residue names (amino acids with the protonation variants of AMBER and CHARMM,
#: caps, nucleotides): their atoms are only H, C, N, O, S, P or Se, which decides the
#: element of a left-justified atom name such as CHARMM's ``"CA  "`` (carbon, not calcium).
STANDARD_RESIDUES = (
    frozenset(
        (
            "ALA ARG ASN ASP CYS GLN GLU GLY HIS ILE LEU LYS MET PHE PRO SER THR TRP TYR VAL "
            "HSD HSE HSP HID HIE HIP HSC CYX CYM ASH GLH LYN ARN MSE SEC PYL ACE NME NH2 NMA "
            "DA DC DG DT DU DI A C G U I RA RC RG RU"
        ).split()
    )
    | WATER_RESIDUES
)
# two-letter guesses kept even in a polymer residue (a halogen or Se is a real atom there)
_POLYMER_TWO_LETTER = {"Se", "Cl", "Br"}


def _fill(a, n, default, dtype):
    return readonly(np.full(n, default, dtype=dtype) if a is None else np.asarray(a, dtype=dtype))


@dataclass(frozen=True, eq=False)
class PDBStructure:
    """Atoms of one model of a PDB file, as balls plus their labels.

    Attributes
    ----------
    balls : Balls
        Centres in Å; radii = van der Waals radius (:data:`VDW_RADII`: Bondi 1964 and
        Mantina et al. 2009, or the ``radii=`` table of :func:`read_pdb`) + probe.
    atom_names, residue_names, chains, elements : ndarray of str, shape (n,)
        Columns 13–16, 18–20, 21–22 and 77–78 (element symbols normalised, e.g.
        ``"Fe"``); see :func:`read_pdb` for column 21.
    residue_numbers : ndarray of int64, shape (n,)
        Columns 23–26.
    hetero : ndarray of bool, shape (n,)
        True for HETATM records.
    probe : float
        The probe radius that was added to every van der Waals radius.
    insertion_codes, altlocs : ndarray of str, shape (n,)
        Columns 27 and 17 (``""`` when blank): a residue is identified by chain,
        number and insertion code; ``altlocs`` is the alternate location kept.
    occupancies, b_factors : ndarray of float64, shape (n,)
        Columns 55–60 and 61–66 (NaN when blank).
    model : int or None
        Serial of the MODEL that was read (None if the file has no MODEL record).

    The last five default to blanks/NaN for structures built in code.

    See Also
    --------
    read_pdb
        Produces it.
    write_pdb
        Writes it back.
    """

    balls: Balls
    atom_names: np.ndarray
    residue_names: np.ndarray
    residue_numbers: np.ndarray
    chains: np.ndarray
    elements: np.ndarray
    hetero: np.ndarray
    probe: float = 0.0
    insertion_codes: np.ndarray | None = None
    altlocs: np.ndarray | None = None
    occupancies: np.ndarray | None = None
    b_factors: np.ndarray | None = None
    model: int | None = None

    def __post_init__(self):
        n = len(self.balls)
        for name, default, dtype in (
            ("insertion_codes", "", str),
            ("altlocs", "", str),
            ("occupancies", np.nan, np.float64),
            ("b_factors", np.nan, np.float64),
        ):
            a = _fill(getattr(self, name), n, default, dtype)
            if a.shape != (n,):
                raise ValueError(f"{name} must have shape ({n},), got {a.shape}")
            object.__setattr__(self, name, a)

    def __len__(self) -> int:
        return len(self.balls)

    def __repr__(self) -> str:
        n_res = len(set(zip(self.chains.tolist(), self.residue_numbers.tolist(), self.insertion_codes.tolist())))
        return f"PDBStructure(n_atoms={len(self)}, n_residues={n_res}, probe={self.probe})"

    def label(self, i: int) -> str:
        """A human-readable label of atom ``i``, e.g. ``'A:LEU12:CD1'``."""
        i = int(i)
        return f"{self.residue_label(i)}:{self.atom_names[i]}"

    def residue_label(self, i: int) -> str:
        """The residue of atom ``i``, e.g. ``'A:LEU99'`` or ``'B:GLY52A'`` (insertion code)."""
        i = int(i)
        return f"{self.chains[i]}:{self.residue_names[i]}{self.residue_numbers[i]}{self.insertion_codes[i]}"

    def residues(self, indices=None) -> list[str]:
        """Distinct residue labels of the atoms ``indices`` (all atoms by default), in
        file order: what a report lists as the lining residues of a feature.

        Examples
        --------
        >>> from shapelab.datasets import structure
        >>> s = structure("t4l-l99a")
        >>> s.residues([i for i in range(len(s)) if s.residue_numbers[i] == 99])
        [':ALA99']
        """
        idx = range(len(self)) if indices is None else np.unique(np.asarray(indices, dtype=np.int64))
        seen = dict.fromkeys(self.residue_label(i) for i in idx)
        return list(seen)

    def c_alpha(self) -> "PDBStructure":
        """The α-carbons (atom name ``CA`` in ATOM records): one atom per amino-acid
        residue, the usual points for superposing protein chains (Notes §23.2).

        Examples
        --------
        >>> from shapelab.datasets import structure
        >>> ca = structure("4ake").c_alpha()
        >>> len(ca), ca.residue_label(0)
        (214, ':MET1')
        """
        return self.select((self.atom_names == "CA") & ~self.hetero)

    def select(self, mask) -> "PDBStructure":
        """The atoms where ``mask`` (booleans, or indices) holds, as a new structure.

        Examples
        --------
        >>> from shapelab.datasets import structure
        >>> s = structure("1hvr")
        >>> protein = s.select(~s.hetero | (s.residue_names == "CSO"))  # drop the inhibitor
        >>> len(s) - len(protein)
        46
        """
        m = np.asarray(mask)
        if m.dtype == bool:
            if m.shape != (len(self),):
                raise ValueError(f"mask must have shape ({len(self)},), got {m.shape}")
            idx = np.flatnonzero(m)
        else:
            idx = m.astype(np.int64).ravel()
        return PDBStructure(
            balls=self.balls[idx],
            atom_names=readonly(self.atom_names[idx]),
            residue_names=readonly(self.residue_names[idx]),
            residue_numbers=readonly(self.residue_numbers[idx]),
            chains=readonly(self.chains[idx]),
            elements=readonly(self.elements[idx]),
            hetero=readonly(self.hetero[idx]),
            probe=self.probe,
            insertion_codes=self.insertion_codes[idx],
            altlocs=self.altlocs[idx],
            occupancies=self.occupancies[idx],
            b_factors=self.b_factors[idx],
            model=self.model,
        )


def _element_from_name(name: str, residue: str | None = None) -> str:
    """Guess an element from a PDB atom name (columns 13–16).

    PDB convention: the element symbol is right-justified in columns 13–14, so
    ``" CA "`` is an alpha carbon and ``"CA  "`` is calcium.  Four-character hydrogen
    names (``"HG21"``, ``"1HG2"``) are hydrogens.  Programs such as CHARMM write
    names left-justified (``"CA  "``, ``"HE1 "``); in a polymer residue
    (:data:`STANDARD_RESIDUES`, given as ``residue``) the first letter is then the
    element, since those residues hold no calcium or helium.
    """
    name4 = name.ljust(4)[:4]
    first, second = name4[0], name4[1]
    if first == " " or first.isdigit():
        return second if second.isalpha() else ""
    if first.upper() == "H" and len(name4.strip()) == 4:
        return "H"
    two = (first + second).strip()
    if len(two) == 2 and two.upper() in _SYMBOLS:
        sym = _SYMBOLS[two.upper()]
        if residue is None or residue not in STANDARD_RESIDUES or sym in _POLYMER_TWO_LETTER:
            return sym
    return first.upper() if first.isalpha() else ""


_H36_UPPER = frozenset("0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ")
_H36_LOWER = frozenset("0123456789abcdefghijklmnopqrstuvwxyz")


def _residue_number(text: str) -> int:
    """Columns 23–26: a decimal integer, or hybrid-36 past 9999 (``A000`` = 10000, as
    gemmi and VMD write and read it; ``a000`` follows ``ZZZZ``).  Anything else raises."""
    t = text.strip()
    if len(text) == 4 and text[0].isalpha() and text.isascii():
        for alphabet, offset in ((_H36_UPPER, 10000), (_H36_LOWER, 10000 + 26 * 36**3)):
            if set(text) <= alphabet:
                return int(text, 36) - 10 * 36**3 + offset
        raise ValueError(text)
    if not re.fullmatch(r"[+-]?[0-9]+", t):  # not int()'s "1_00" (100) nor its spaces
        raise ValueError(text)
    return int(t)


def _field_float(line: str, a: int, b: int, what: str, lineno: int) -> float:
    text = line[a:b]
    try:
        if "_" in text:  # float() reads "1_000" as 1000.0; no PDB number has one
            raise ValueError(text)
        v = float(text)
    except ValueError:
        raise ValueError(f"line {lineno}: could not read {what} from columns {a + 1}-{b}: {text.strip()!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"line {lineno}: {what} must be finite, got {text.strip()!r}")
    return v


def _optional_float(line: str, a: int, b: int, what: str, lineno: int) -> float:
    """A float from columns a+1..b, NaN if they are blank or absent; refused if the
    line ends inside them (a right-justified number cut short: ``"  0.50"`` -> ``"  0"``)."""
    if not line[a:b].strip():
        return math.nan
    if len(line) < b:
        raise ValueError(
            f"line {lineno}: {what} in columns {a + 1}-{b} is cut short by the end of the line: {line[a:b]!r}"
        )
    return _field_float(line, a, b, what, lineno)


def _radius_table(radii):
    """Validate ``radii=``: {element or (residue, atom): radius} -> two dicts."""
    if radii is None:
        return {}, {}
    if not hasattr(radii, "items"):
        raise TypeError(f"radii must be a mapping (element or (residue, atom) -> Å), got {type(radii).__name__}")
    by_element, by_atom = {}, {}
    for key, value in radii.items():
        r = as_finite_scalar(value, f"radii[{key!r}]", positive=True)
        if isinstance(key, str) and key.strip():
            by_element[key.strip().upper()] = r
        elif isinstance(key, tuple) and len(key) == 2 and all(isinstance(k, str) and k.strip() for k in key):
            by_atom[(key[0].strip().upper(), key[1].strip().upper())] = r
        else:
            raise TypeError(
                f"radii keys must be element symbols or (residue name, atom name) pairs of str, got {key!r}"
            )
    return by_element, by_atom


def _names_arg(value, name: str, width: int):
    """None, one str, or an iterable of str -> frozenset of stripped names (or None)."""
    if value is None:
        return None
    items = [value] if isinstance(value, str) else value
    try:
        items = list(items)
    except TypeError:
        raise TypeError(f"{name} must be a str or a collection of str, got {type(value).__name__}") from None
    out = set()
    for v in items:
        if not isinstance(v, str) or len(v.strip()) > width:
            raise ValueError(f"{name} must hold strings of at most {width} characters, got {v!r}")
        out.add(v.strip())
    return frozenset(out)


#: Default ``max_bytes`` of :func:`read_pdb`: 256 MiB of (decompressed) text, some
#: 3 million ATOM records -- thirty times the 99,999 atoms a PDB file can number.
MAX_PDB_BYTES = 256 * 2**20
_CHUNK = 2**20  # bytes read (or decompressed) at a time
_MAX_LINE = 2**16  # a PDB record has 80 columns; a longer "line" is not PDB text
_EOL = re.compile(rb"\r\n|\r|\n")
_BOM = b"\xef\xbb\xbf"


def _pdb_lines(path, max_bytes: int):
    """Yield ``(line number, text)`` of a plain or gzip file, streamed.

    Lines end with LF, CRLF or CR; a UTF-8 byte-order mark before the first line is
    dropped; text is decoded as Latin-1 (one character per byte, so that the PDB's
    columns are byte columns).  At most ``_CHUNK`` bytes (plus one unfinished line of
    at most ``_MAX_LINE``) are held at a time, and reading stops with a ValueError as
    soon as more than ``max_bytes`` bytes have come out of the file (after
    decompression): a gzip bomb is refused after ``max_bytes``, never held whole.
    """
    name = os.fspath(path)
    with open(path, "rb") as raw:
        gz = raw.read(2) == b"\x1f\x8b"
        raw.seek(0)
        fh = gzip.GzipFile(fileobj=raw, mode="rb") if gz else raw
        total, lineno, pending, skip_lf = 0, 0, b"", False
        while True:
            try:
                chunk = fh.read(min(_CHUNK, max_bytes + 1 - total))
            except (OSError, EOFError, zlib.error) as e:
                if not gz:
                    raise
                raise ValueError(f"{name!r} is not a readable gzip file: {e}") from None
            if not chunk:
                break
            total += len(chunk)
            over = total > max_bytes
            if over:  # the lines that end within the limit are still read: END may be one
                chunk = chunk[: len(chunk) - (total - max_bytes)]
            if skip_lf and chunk[:1] == b"\n":  # the LF of a CRLF split between two chunks
                chunk = chunk[1:]
            data = pending + chunk
            skip_lf = data[-1:] == b"\r"
            parts = _EOL.split(data)
            pending = parts.pop()
            if len(pending) > _MAX_LINE:
                raise ValueError(
                    f"line {lineno + len(parts) + 1} of {name!r} is longer than {_MAX_LINE} characters: not PDB text"
                )
            for part in parts:
                lineno += 1
                if lineno == 1 and part.startswith(_BOM):
                    part = part[len(_BOM) :]
                yield lineno, part.decode("latin-1")
            if over:
                what = "decompresses to" if gz else "holds"
                raise ValueError(
                    f"{name!r} {what} more than max_bytes={max_bytes} bytes before its first END "
                    f"(or the ENDMDL of the model read); pass a larger max_bytes= to read it"
                )
        if pending:
            lineno += 1
            if lineno == 1 and pending.startswith(_BOM):
                pending = pending[len(_BOM) :]
            yield lineno, pending.decode("latin-1")


def _check_text(line: str, lineno: int, rec: str, path) -> None:
    """Refuse a record with a byte no writer can represent, non-ASCII anywhere, or a
    control character (tab, NUL, ...) before its trailing whitespace: the record is
    read by fixed columns, and a tab shifts every column after it (``"ATOM\t"`` for
    ``"ATOM  "`` moves the sign of x out of columns 31-38)."""
    if not line.isascii():
        col, ch = next((k, c) for k, c in enumerate(line) if not c.isascii())
        raise ValueError(
            f"line {lineno}: {rec} record of {os.fspath(path)!r} has the non-ASCII byte "
            f"0x{ord(ch):02x} in column {col + 1} (PDB records are ASCII; a non-ASCII name "
            f"could be read but neither written to PDB nor safely to mmCIF)"
        )
    for a, b, what in _TEXT_FIELDS:
        field = line[a:b]
        if not field.isprintable():
            raise ValueError(
                f"line {lineno}: {rec} record of {os.fspath(path)!r} has a control character "
                f"in the {what} (columns {a + 1}-{b}): {field!r}"
            )
    body = line.rstrip()
    if not body.isprintable():
        col, ch = next((k, c) for k, c in enumerate(body) if not c.isprintable())
        raise ValueError(
            f"line {lineno}: {rec} record of {os.fspath(path)!r} has a control character "
            f"{ch!r} in column {col + 1} (PDB records are fixed columns, which a tab shifts)"
        )


# text fields kept by read_pdb: (start, end, name), 0-based half-open columns
_TEXT_FIELDS = (
    (12, 16, "atom name"),
    (16, 17, "alternate location"),
    (17, 20, "residue name"),
    (20, 22, "chain identifier"),
    (26, 27, "insertion code"),
)


def read_pdb(
    path,
    *,
    probe=0.0,
    default_radius=None,
    model=None,
    chain=None,
    hetatm=True,
    water=False,
    hydrogens=False,
    radii=None,
    max_bytes=MAX_PDB_BYTES,
) -> PDBStructure:
    """Read the atoms of a PDB file as balls (Notes §23.1: a molecule is a union of balls).

    Parameters
    ----------
    path : str or os.PathLike
        The PDB file, plain or gzip-compressed (recognised by its first bytes),
        streamed: memory grows with the atoms kept, not with the file.
    probe : float, default 0
        Probe radius :math:`p \\ge 0` added to every van der Waals radius; ``probe=1.4``
        (water) gives the solvent-accessible model.
    default_radius : float, optional
        Van der Waals radius for elements missing from :data:`VDW_RADII` (Bondi 1964
        and Mantina et al. 2009: most transition metals, e.g. Fe, Mn, Co, Mo) and from
        ``radii``.  Without it, such an element raises.
    model : int, optional
        Serial number of the MODEL to read (columns 11–14 of the MODEL record).
        Default: the first model.  A file without MODEL records is model 1; ATOM or
        HETATM records outside any MODEL block followed by a MODEL record are
        refused (which model they belong to is not said; gemmi refuses them too).
    chain : str or collection of str, optional
        Keep only these chain identifiers (columns 21–22, one or two characters;
        ``""`` is the blank chain).
    hetatm : bool or collection of str, default True
        Keep HETATM records (ligands, ions, modified residues): all (True), none
        (False), or only those whose residue name is in the collection, e.g.
        ``{"CSO"}`` keeps a modified cysteine and drops an inhibitor.  Water is
        governed by ``water`` alone.
    water : bool, default False
        Keep water molecules (residue names in :data:`WATER_RESIDUES`, ATOM or
        HETATM).  Crystallographic waters are not part of the van der Waals model of
        a protein, so they are dropped by default.
    hydrogens : bool, default False
        Keep hydrogen (and deuterium) atoms.  The van der Waals model of the notes
        uses heavy atoms with united-atom-like radii, and X-ray entries mostly have
        no hydrogens, so they are dropped by default.
    radii : mapping, optional
        Van der Waals radii (Å) that take precedence over :data:`VDW_RADII`: keys are element
        symbols (``{"Fe": 2.0}``) or ``(residue name, atom name)`` pairs
        (``{("ALA", "CB"): 1.9}``), the latter winning.  Matching ignores case.
    max_bytes : int, default :data:`MAX_PDB_BYTES` (256 MiB)
        Most bytes of text read before the first ``END`` (or the ``ENDMDL`` of the
        model read), that line included, counted after decompression; a file with
        more is refused as soon as the limit is passed, without being held in
        memory.  What follows the ``END`` is never read.

    Returns
    -------
    PDBStructure
        The atoms in file order, with residue names, numbers, insertion codes and
        chains, so that reports can name the residues lining a feature.

    Raises
    ------
    ValueError
        Empty file or no atoms, or no atoms left by the selection; a truncated or
        malformed ATOM/HETATM or MODEL record (the message starts with ``"line N:"``),
        including one with a non-ASCII byte anywhere (what no writer could write
        back), a control character such as a tab before its trailing whitespace
        (which shifts the fixed columns), a number cut short by the end of the line
        or written with ``_`` (the message names the file and the column); atoms
        outside any MODEL block before a MODEL record; a requested model that is absent; an element without a radius;
        an unreadable gzip stream; more than ``max_bytes`` of text.  Nothing is
        returned in part: any error in the model read fails the whole call.
    FileNotFoundError, IsADirectoryError
        If ``path`` cannot be opened.

    See Also
    --------
    write_pdb
        The writer.
    vdw_radius
        The radii given to the atoms.
    gemmi.read_structure
        A full reader of PDB and mmCIF files.

    Notes
    -----
    * ATOM and HETATM records are read by the PDB's fixed columns: name 13–16,
      alternate location 17, residue name 18–20, chain 21–22, residue number 23–26,
      insertion code 27, x/y/z 31–38/39–46/47–54, occupancy 55–60, B-factor 61–66,
      element 77–78.  A record must reach column 54.  Every record of the model read
      is parsed before any selection is applied, so a malformed line fails even if
      it would have been filtered out.
    * **Column 21** belongs to the chain identifier, as in gemmi's PDB reader
      (``read_string(line + 20, 2)``) and the wwPDB's large-structure files, whose
      two-character chains (``AA``, ``B1``: the ribosome 4V8R) fill columns 21–22;
      the residue name is columns 18–20 only.  The wwPDB format leaves column 21
      blank, so standard files read the same either way.  Programs that write a
      fourth residue letter there (CHARMM's ``TIP3``) therefore read as residue
      ``TIP`` of chain ``3``, exactly as gemmi reads them: water is still water
      (``TIP`` is in :data:`WATER_RESIDUES`), and CHARMM's own chain-like name is
      the segment identifier of columns 73–76, which is not read.
    * The file is streamed line by line (LF, CRLF or CR line ends); a UTF-8
      byte-order mark before the first record is ignored.
    * The element comes from columns 77–78; if blank, from the atom name
      (:func:`_element_from_name`).
    * Reading stops at the first ``END``, or at the ``ENDMDL`` of the model read.
    * Alternate locations: for each atom (chain, residue number, insertion code,
      atom name) with labelled alternatives, the one of highest occupancy is kept;
      ties go to the label seen first.  Unlabelled records are always kept.  Where
      the alternatives are different residues (a point mutation modelled as
      alternate locations, e.g. PRO or SER 22 of 1EJG), the residue name of the
      labelled record of highest occupancy is chosen first (ties: the first seen)
      and the labelled records of the other names are dropped, so that one residue
      is kept whole and never mixed with the extra atoms of the other, as gemmi's
      ``remove_alternative_conformations`` keeps one.
    * Other records (HEADER, REMARK, ANISOU, TER, CONECT, ...) are ignored.

    Examples
    --------
    >>> from shapelab.datasets import structure_path
    >>> s = read_pdb(structure_path("1hvr"), chain="A", hetatm={"CSO"})  # no inhibitor
    >>> len(s), s.residue_label(0), sorted(set(s.elements.tolist()))
    (757, 'A:PRO1', ['C', 'N', 'O', 'S'])
    """
    if isinstance(path, (bytes, bytearray)) or not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or os.PathLike, got {type(path).__name__}")
    probe = as_finite_scalar(probe, "probe", nonnegative=True)
    if default_radius is not None:
        default_radius = as_finite_scalar(default_radius, "default_radius", positive=True)
    if model is not None:
        if isinstance(model, bool):
            raise TypeError("model must be an int, got bool")
        model = as_positive_int(model, "model", minimum=0)
    chains_wanted = _names_arg(chain, "chain", 2)
    if isinstance(hetatm, (bool, np.bool_)):
        het_keep = bool(hetatm)
    else:
        het_keep = _names_arg(hetatm, "hetatm", 3)
    for flag, fname in ((water, "water"), (hydrogens, "hydrogens")):
        if not isinstance(flag, (bool, np.bool_)):
            raise TypeError(f"{fname} must be a bool, got {type(flag).__name__}")
    radii_element, radii_atom = _radius_table(radii)
    max_bytes = as_positive_int(max_bytes, "max_bytes")

    recs = []  # one tuple per ATOM/HETATM record of the model read
    target = model  # the MODEL serial wanted (None: the first one met)
    current = None  # serial of the open MODEL block (None: outside any)
    models_seen = []
    loose = None  # line of the first ATOM/HETATM record outside any MODEL block
    blank = True  # no character but whitespace seen so far
    with contextlib.closing(_pdb_lines(path, max_bytes)) as lines:  # closed at END, on error too
        for lineno, line in lines:
            blank = blank and not line.strip()
            rec = line[:6].rstrip()
            if rec == "END":
                break
            if rec == "MODEL":
                if current is not None:
                    raise ValueError(f"line {lineno}: MODEL record inside MODEL {current} (missing ENDMDL)")
                if loose is not None:
                    raise ValueError(
                        f"line {lineno}: MODEL record after ATOM/HETATM records outside any MODEL "
                        f"(from line {loose}): which model they belong to is not said"
                    )
                field = line[6:].strip()
                if field:
                    try:
                        current = int(field.split()[0])
                    except ValueError:
                        raise ValueError(
                            f"line {lineno}: could not read the model serial from the MODEL record: {field!r}"
                        ) from None
                else:
                    current = len(models_seen) + 1
                models_seen.append(current)
                if target is None:
                    target = current
                continue
            if rec == "ENDMDL":
                if current is None or current == target:
                    break
                current = None
                continue
            if rec not in ("ATOM", "HETATM"):
                continue
            if current is None and loose is None:
                loose = lineno
            here = 1 if current is None else current
            if (target if target is not None else 1) != here:
                continue
            _check_text(line, lineno, rec, path)
            if len(line) < 54:
                raise ValueError(
                    f"line {lineno}: truncated {rec} record (needs at least 54 columns for "
                    f"the coordinates, got {len(line.rstrip())})"
                )
            x = _field_float(line, 30, 38, "x", lineno)
            y = _field_float(line, 38, 46, "y", lineno)
            z = _field_float(line, 46, 54, "z", lineno)
            occ = _optional_float(line, 54, 60, "the occupancy", lineno)
            bfac = _optional_float(line, 60, 66, "the B-factor", lineno)
            num_text = line[22:26]
            try:
                num = _residue_number(num_text)
            except ValueError:
                raise ValueError(
                    f"line {lineno}: could not read the residue number from columns 23-26 "
                    f"(an integer, or hybrid-36 above 9999): {num_text.strip()!r}"
                ) from None
            name = line[12:16]
            resname = line[17:20].strip()
            e = line[76:78].strip() if len(line) >= 77 else ""
            if e:
                if not (e.isascii() and e.isalpha()):
                    raise ValueError(f"line {lineno}: element in columns 77-78 is not a symbol: {e!r}")
                e = e[0].upper() + e[1:].lower()
            else:
                e = _element_from_name(name, resname.upper())
                if not e:
                    raise ValueError(
                        f"line {lineno}: no element in columns 77-78 and none can be read from the atom name {name!r}"
                    )
            icode = line[26].strip() if len(line) > 26 else ""
            recs.append(
                (
                    lineno,
                    rec == "HETATM",
                    line[16].strip(),
                    name.strip(),
                    resname,
                    line[20:22].strip(),
                    num,
                    icode,
                    x,
                    y,
                    z,
                    occ,
                    bfac,
                    e,
                )
            )

    if blank:
        raise ValueError(f"{os.fspath(path)!r} is empty: no ATOM or HETATM records")
    if model is not None and model not in models_seen and not (model == 1 and recs):
        raise ValueError(f"{os.fspath(path)!r} has no MODEL {model} (models read before END: {models_seen or 'none'})")
    if not recs:
        raise ValueError(f"{os.fspath(path)!r} holds no ATOM or HETATM records (before END/ENDMDL)")

    # alternate residues (a point mutation, 1EJG's PRO/SER 22): per residue, the name
    # of the labelled record of highest occupancy (ties: the first seen); the labelled
    # records of its other names are dropped, so that no residue mixes two
    resname_of = {}
    for r in recs:
        if r[2]:
            key = (r[5], r[6], r[7])
            occ = -math.inf if math.isnan(r[11]) else r[11]
            if key not in resname_of or occ > resname_of[key][1]:
                resname_of[key] = (r[4], occ)
    # alternate locations: per atom, the highest occupancy (ties: the first label seen)
    best = {}
    for k, r in enumerate(recs):
        if r[2] and r[4] == resname_of[(r[5], r[6], r[7])][0]:
            key = (r[5], r[6], r[7], r[3])
            occ = -math.inf if math.isnan(r[11]) else r[11]
            if key not in best or occ > best[key][1]:
                best[key] = (k, occ)
    keep_alt = {k for k, _ in best.values()}

    kept = []
    for k, r in enumerate(recs):
        if r[2] and k not in keep_alt:
            continue
        is_water = r[4].upper() in WATER_RESIDUES
        if is_water:
            if not water:
                continue
        elif r[1] and not (het_keep is True or (het_keep and r[4] in het_keep)):
            continue
        if chains_wanted is not None and r[5] not in chains_wanted:
            continue
        if not hydrogens and r[13] in ("H", "D"):
            continue
        kept.append(r)
    if not kept:
        raise ValueError(
            f"{os.fspath(path)!r}: none of its {len(recs)} atoms is left by the selection "
            f"(chain={chain!r}, hetatm={hetatm!r}, water={water}, hydrogens={hydrogens}; "
            f"chains present: {sorted({r[5] for r in recs})})"
        )

    rad = np.empty(len(kept))
    for i, r in enumerate(kept):
        lineno, e, resn, name = r[0], r[13], r[4], r[3]
        eu = e.upper()
        ra = radii_atom.get((resn.upper(), name.upper()))
        if ra is None:
            ra = radii_element.get(eu)
        if ra is None:
            key = _UPPER.get("H" if eu == "D" else eu)  # deuterium: hydrogen's radius
            ra = VDW_RADII[key] if key is not None else default_radius
        if ra is None:
            raise ValueError(
                f"line {lineno}: element {e!r} (atom {name!r}, residue {resn} {r[6]}) has no van "
                f"der Waals radius in Bondi's (1964) or Mantina et al.'s (2009) table; pass "
                f"default_radius= (or radii=) to use one"
            )
        rad[i] = ra
    col = list(zip(*kept))
    balls = Balls(np.array([c[8:11] for c in kept], dtype=np.float64), rad + probe)
    return PDBStructure(
        balls=balls,
        atom_names=readonly(np.array(col[3], dtype=str)),
        residue_names=readonly(np.array(col[4], dtype=str)),
        residue_numbers=readonly(np.array(col[6], dtype=np.int64)),
        chains=readonly(np.array(col[5], dtype=str)),
        elements=readonly(np.array(col[13], dtype=str)),
        hetero=readonly(np.array(col[1], dtype=bool)),
        probe=probe,
        insertion_codes=np.array(col[7], dtype=str),
        altlocs=np.array(col[2], dtype=str),
        occupancies=np.array(col[11], dtype=np.float64),
        b_factors=np.array(col[12], dtype=np.float64),
        model=target if models_seen else None,
    )


def _str_column(values, n: int, name: str, width, default, fmt="PDB"):
    if values is None:
        return [default(i) for i in range(n)]
    if isinstance(values, str):
        values = [values] * n
    values = [str(v) for v in (values.tolist() if isinstance(values, np.ndarray) else values)]
    if len(values) != n:
        raise ValueError(f"{name} must have one entry per ball ({n}), got {len(values)}")
    bad = {v for v in set(values) if (width is not None and len(v) > width) or not v.isascii() or not v.isprintable()}
    if bad:
        i = next(i for i, v in enumerate(values) if v in bad)
        size = f"{width}-character " if width is not None else ""
        raise ValueError(f"{name}[{i}] = {values[i]!r} does not fit the {fmt}'s {size}printable ASCII field")
    return values


def _labels(
    balls,
    elements,
    atom_names,
    residue_names,
    residue_numbers,
    chains,
    hetero,
    insertion_codes,
    altlocs,
    b_factors,
    *,
    fmt,
    widths,
):
    """Validate the per-atom columns shared by :func:`write_pdb` and :func:`write_mmcif`."""
    check_balls(balls)
    if balls.dim != 3:
        raise ValueError(f"balls must be 3-dimensional to be written as a {fmt} file, got dim={balls.dim}")
    n = len(balls)
    if n == 0:
        raise ValueError("balls must hold at least one ball")
    elements = _str_column(elements, n, "elements", 2, None, fmt)
    for i, e in enumerate(elements):
        if not (e.isalpha() and 1 <= len(e) <= 2):
            raise ValueError(f"elements[{i}] = {e!r} is not an element symbol")
    elements = [e[0].upper() + e[1:].lower() for e in elements]
    w = widths
    atom_names = _str_column(atom_names, n, "atom_names", w["atom"], lambda i: elements[i].upper(), fmt)
    residue_names = _str_column(residue_names, n, "residue_names", w["residue"], lambda i: "UNK", fmt)
    chains = _str_column(chains, n, "chains", w["chain"], lambda i: "A", fmt)
    insertion_codes = _str_column(insertion_codes, n, "insertion_codes", 1, lambda i: "", fmt)
    altlocs = _str_column(altlocs, n, "altlocs", 1, lambda i: "", fmt)
    if residue_numbers is None:
        residue_numbers = np.arange(1, n + 1)
    residue_numbers = np.asarray(residue_numbers)
    if residue_numbers.shape != (n,) or residue_numbers.dtype.kind not in "iu":
        raise ValueError(f"residue_numbers must be {n} integers")
    hetero = np.zeros(n, bool) if hetero is None else np.asarray(hetero, dtype=bool)
    if hetero.shape != (n,):
        raise ValueError(f"hetero must have shape ({n},), got {hetero.shape}")
    if b_factors is None:
        b_factors = np.zeros(n)
    b_factors = np.asarray(b_factors, dtype=np.float64)
    if b_factors.shape != (n,):
        raise ValueError(f"b_factors must have shape ({n},), got {b_factors.shape}")
    return elements, atom_names, residue_names, residue_numbers, chains, hetero, insertion_codes, altlocs, b_factors


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _write_text(path, text: str):
    """Write ``text`` to a text stream (anything with ``write``), or to the file ``path``
    atomically: a temporary file beside it, renamed over it once complete."""
    if hasattr(path, "write"):
        path.write(text)
        return path
    out = Path(path)
    fd, tmp = tempfile.mkstemp(dir=out.parent, prefix=f".{out.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="ascii", newline="\n") as fh:
            fh.write(text)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp's files are private; a written file is not
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return out


def write_pdb(
    path,
    balls: Balls,
    elements,
    *,
    atom_names=None,
    residue_names=None,
    residue_numbers=None,
    chains=None,
    hetero=None,
    title=None,
    b_factors=None,
    insertion_codes=None,
    altlocs=None,
):
    """Write 3D balls as ATOM/HETATM records of a PDB file.

    The PDB format stores no radii: :func:`read_pdb` recovers them from the elements,
    so a round trip preserves radii exactly when they are the radii of :data:`VDW_RADII` (plus one probe).
    Coordinates are written with three decimals (the format's precision, 0.001 Å).
    The format's fixed columns limit what it holds (at most 99,999 atoms, residue
    names of three characters, B-factors below 1000); :func:`write_mmcif` holds any
    number of atoms and names of any length.

    Parameters
    ----------
    path : str, os.PathLike or text stream
        A file, written atomically (a temporary file beside it renamed over it once
        complete, so a failed write leaves no partial file), or an open text stream.
    balls : Balls
        3D balls; every coordinate must lie in (-1000, 10000) to fit columns 31–54.
    elements : sequence of str or str
        Element symbols (one per ball, or one for all).
    atom_names, residue_names, chains : sequence of str, optional
        At most 4, 3 and 2 characters (chains fill columns 21–22, as
        :func:`read_pdb` reads them).  Default: the element symbol, ``"UNK"``, ``"A"``.
    residue_numbers : sequence of int, optional
        Default: 1, 2, ..., n (one residue per atom).
    hetero : sequence of bool, optional
        True writes HETATM instead of ATOM.
    title : str, optional
        Written as a TITLE record (at most 70 characters).
    b_factors : sequence of float, optional
        Values for the B-factor column (61–66), e.g. a label per atom as
        :func:`shapelab.report` writes; each must fit ``%6.2f``.  Default 0.
    insertion_codes, altlocs : sequence of str, optional
        Columns 27 and 17 (one character or ``""``).  Default blank.

    Returns
    -------
    pathlib.Path or the stream

    Raises
    ------
    ValueError
        What the format cannot hold (the message names the argument), before
        anything is written.

    See Also
    --------
    write_mmcif : the same atoms as an mmCIF ``_atom_site`` table, without limits.
    read_pdb : reads the file back.

    References
    ----------
    wwPDB, *Atomic Coordinate Entry Format Description*, v3.3, ATOM record.
    """
    widths = {"atom": 4, "residue": 3, "chain": 2}
    cols = _labels(
        balls,
        elements,
        atom_names,
        residue_names,
        residue_numbers,
        chains,
        hetero,
        insertion_codes,
        altlocs,
        b_factors,
        fmt="PDB",
        widths=widths,
    )
    elements, atom_names, residue_names, residue_numbers, chains, hetero, insertion_codes, altlocs, b_factors = cols
    n = len(balls)
    if n > 99999:
        raise ValueError(f"the PDB format holds at most 99999 atoms, got {n}")
    c = balls.centers
    if np.any(c <= -999.9995) or np.any(c >= 9999.9995):
        raise ValueError("balls.centers must lie in (-1000, 10000) to fit the PDB's coordinate columns")
    if np.any(residue_numbers < -999) or np.any(residue_numbers > 9999):
        raise ValueError("residue_numbers must lie in [-999, 9999] to fit columns 23-26")
    if not np.all(np.isfinite(b_factors)) or np.any(b_factors <= -99.995) or np.any(b_factors >= 999.995):
        raise ValueError("b_factors must be finite and lie in (-100, 1000) to fit columns 61-66")

    lines = []
    if title is not None:
        t = str(title)
        if len(t) > 70 or not t.isascii() or not t.isprintable():
            raise ValueError("title must be at most 70 printable ASCII characters on one line")
        lines.append(f"TITLE     {t}")
    for i in range(n):
        name = atom_names[i]
        # element symbols right-justified in columns 13-14 (PDB convention)
        if len(name) < 4 and len(elements[i]) == 1:
            name = " " + name
        rec = "HETATM" if hetero[i] else "ATOM"
        lines.append(
            f"{rec:<6}{(i + 1) % 100000:>5} {name:<4}{altlocs[i]:1}{residue_names[i]:>3}{chains[i]:>2}"
            f"{int(residue_numbers[i]):>4}{insertion_codes[i]:1}   {c[i, 0]:8.3f}{c[i, 1]:8.3f}{c[i, 2]:8.3f}"
            f"{1.0:6.2f}{b_factors[i]:6.2f}          {elements[i].upper():>2}"
        )
    lines.append("END")
    return _write_text(path, "\n".join(lines) + "\n")


# ------------------------------------------------------------------------ mmCIF
_CIF_RESERVED = ("data_", "save_", "loop_", "stop_", "global_")


def _cif_token(s: str) -> str:
    """One printable-ASCII value as a CIF 1.1 token: bare when it can be, else quoted
    (``""`` is written ``.``, CIF's "inapplicable", which mmCIF readers read as empty)."""
    if s == "":
        return "."
    if (
        not any(c.isspace() for c in s)
        and s[0] not in "_#$'\"[];"
        and s not in (".", "?")
        and not s.lower().startswith(_CIF_RESERVED)
    ):
        return s
    for q in ("'", '"'):
        # inside quotes, the quote character may appear unless whitespace follows it
        if not any(s[k] == q and (k + 1 == len(s) or s[k + 1].isspace()) for k in range(len(s))):
            return f"{q}{s}{q}"
    return f"\n;{s}\n;\n"  # a text field holds anything on one line


def _cif_floats(a) -> list:
    """Each value as the shortest text that reads back to the same double; NaN as ``?``."""
    return [repr(v) if v == v else "?" for v in np.asarray(a, dtype=np.float64).tolist()]


def _cif_tokens(values) -> list:
    tok = {v: _cif_token(v) for v in set(values)}  # few distinct labels: quote each once
    return [tok[v] for v in values]


def write_mmcif(
    path,
    balls: Balls,
    elements,
    *,
    atom_names=None,
    residue_names=None,
    residue_numbers=None,
    chains=None,
    hetero=None,
    title=None,
    b_factors=None,
    insertion_codes=None,
    altlocs=None,
    occupancies=None,
    extra=None,
    name="shapelab",
):
    """Write 3D balls as the ``_atom_site`` table of an mmCIF file.

    mmCIF (PDBx/mmCIF, the wwPDB's archive format since 2014) is a table of
    whitespace-separated values with no fixed widths: any number of atoms, residue
    names and chain identifiers of any length, and B-factors of any size fit, which
    the PDB's fixed columns cannot (see :func:`write_pdb`).  Values are written as
    CIF 1.1 tokens (quoted where a value has spaces or starts like a CIF keyword),
    coordinates and B-factors as the shortest decimal that reads back to the same
    double, so a round trip through a reader such as gemmi is exact.  Radii are not
    stored (Notes §23.1: they come from the elements).

    Parameters
    ----------
    path : str, os.PathLike or text stream
        A file, written atomically (temporary file renamed once complete), or an
        open text stream.
    balls : Balls
        3D balls: their centres are ``Cartn_x/y/z``.
    elements : sequence of str or str
        Element symbols (``type_symbol``), one per ball or one for all.
    atom_names, residue_names, chains : sequence of str, optional
        ``label_``/``auth_atom_id``, ``label_``/``auth_comp_id`` and
        ``label_``/``auth_asym_id``: printable ASCII of any length (``""`` is
        written ``.``).  Default: the element symbol, ``"UNK"``, ``"A"``.
    residue_numbers : sequence of int, optional
        ``auth_seq_id``.  Default 1, 2, ..., n.
    hetero : sequence of bool, optional
        ``group_PDB`` HETATM instead of ATOM.
    title : str, optional
        ``_struct.title``.
    b_factors, occupancies : sequence of float, optional
        ``B_iso_or_equiv`` (default 0) and ``occupancy`` (default 1); NaN is
        written ``?`` (unknown).
    insertion_codes, altlocs : sequence of str, optional
        ``pdbx_PDB_ins_code`` and ``label_alt_id`` (one character or ``""``).
    extra : mapping of str to sequence of str, optional
        More ``_atom_site`` items, one value per atom, e.g.
        ``{"shapelab_feature_ids": [...]}`` (names of letters, digits and ``_``).
    name : str, default ``"shapelab"``
        The data block's name (``data_<name>``; characters other than letters,
        digits, ``-``, ``.`` and ``_`` become ``_``).

    Returns
    -------
    pathlib.Path or the stream

    Raises
    ------
    ValueError
        A label that is not printable ASCII, a column of the wrong length, or
        non-finite coordinates, before anything is written.

    See Also
    --------
    write_pdb : the PDB format, for tools that read nothing else.

    References
    ----------
    wwPDB, *PDBx/mmCIF dictionary*, category ``atom_site``; S. R. Hall, F. H. Allen
    and I. D. Brown, "The Crystallographic Information File (CIF)", *Acta Cryst.*
    A47 (1991) 655–685 (the CIF 1.1 syntax).

    Examples
    --------
    >>> import io
    >>> buf = write_mmcif(io.StringIO(), Balls([[0.0, 1.5, -2.25]], 1.7), "C", residue_names="TIP3")
    >>> print(buf.getvalue().splitlines()[-2])
    ATOM 1 C C . TIP3 A . . ? 0.0 1.5 -2.25 1.0 0.0 1 TIP3 A C 1
    """
    widths = {"atom": None, "residue": None, "chain": None}
    cols = _labels(
        balls,
        elements,
        atom_names,
        residue_names,
        residue_numbers,
        chains,
        hetero,
        insertion_codes,
        altlocs,
        b_factors,
        fmt="mmCIF",
        widths=widths,
    )
    elements, atom_names, residue_names, residue_numbers, chains, hetero, insertion_codes, altlocs, b_factors = cols
    n = len(balls)
    occupancies = np.ones(n) if occupancies is None else np.asarray(occupancies, dtype=np.float64)
    if occupancies.shape != (n,):
        raise ValueError(f"occupancies must have shape ({n},), got {occupancies.shape}")
    if np.any(np.isinf(b_factors)) or np.any(np.isinf(occupancies)):
        raise ValueError("b_factors and occupancies must be finite (or NaN for unknown)")
    extra = {} if extra is None else dict(extra)
    extra_cols = []
    for key, values in extra.items():
        if not (isinstance(key, str) and key and key.replace("_", "a").isalnum() and key.isascii()):
            raise ValueError(f"extra item names must be letters, digits and '_', got {key!r}")
        extra_cols.append((key, _cif_tokens(_str_column(values, n, f"extra[{key!r}]", None, None, "mmCIF"))))
    block = re.sub(r"[^A-Za-z0-9_.-]", "_", str(name)) or "shapelab"
    lines = [f"data_{block}", f"_entry.id {_cif_token(block)}"]
    if title is not None:
        t = str(title)
        if not t.isascii() or not t.isprintable():
            raise ValueError("title must be printable ASCII on one line")
        lines.append(f"_struct.entry_id {_cif_token(block)}")
        lines.append(f"_struct.title {_cif_token(t)}")
    items = (
        "group_PDB id type_symbol label_atom_id label_alt_id label_comp_id label_asym_id label_entity_id "
        "label_seq_id pdbx_PDB_ins_code Cartn_x Cartn_y Cartn_z occupancy B_iso_or_equiv auth_seq_id "
        "auth_comp_id auth_asym_id auth_atom_id pdbx_PDB_model_num"
    ).split() + [k for k, _ in extra_cols]
    lines.append("#")
    lines.append("loop_")
    lines.extend(f"_atom_site.{it}" for it in items)
    names, resn, chain = _cif_tokens(atom_names), _cif_tokens(residue_names), _cif_tokens(chains)
    alt = _cif_tokens(altlocs)
    icode = ["?" if t == "." else t for t in _cif_tokens(insertion_codes)]
    xyz = [_cif_floats(balls.centers[:, k]) for k in range(3)]
    occ, bf = _cif_floats(occupancies), _cif_floats(b_factors)
    group = ["HETATM" if h else "ATOM" for h in hetero.tolist()]
    num = [str(v) for v in residue_numbers.tolist()]
    extras = [vals for _, vals in extra_cols]
    for i in range(n):
        row = [group[i], str(i + 1), elements[i], names[i], alt[i], resn[i], chain[i], ".", ".", icode[i]]
        row += [xyz[0][i], xyz[1][i], xyz[2][i], occ[i], bf[i], num[i], resn[i], chain[i], names[i], "1"]
        row += [vals[i] for vals in extras]
        lines.append(" ".join(row))
    lines.append("#")
    return _write_text(path, "\n".join(lines) + "\n")
