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
*J. Phys. Chem.* **68**, 441–451 (1964), Table I (values in Å).  Elements Bondi does
not list (e.g. Ca, Fe, Mn, Co) raise unless a ``default_radius`` is given.
"""

from __future__ import annotations

import gzip
import math
import os
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._toolkit.validate import as_finite_scalar, as_positive_int, check_balls, readonly
from .balls import Balls

__all__ = ["VDW_RADII", "WATER_RESIDUES", "STANDARD_RESIDUES", "PDBStructure", "read_pdb", "write_pdb", "vdw_radius"]

#: van der Waals radii in Å, Bondi (1964), J. Phys. Chem. 68:441, Table I.
VDW_RADII: dict[str, float] = {
    "H": 1.20,
    "He": 1.40,
    "Li": 1.82,
    "C": 1.70,
    "N": 1.55,
    "O": 1.52,
    "F": 1.47,
    "Ne": 1.54,
    "Na": 2.27,
    "Mg": 1.73,
    "Si": 2.10,
    "P": 1.80,
    "S": 1.80,
    "Cl": 1.75,
    "Ar": 1.88,
    "K": 2.75,
    "Ni": 1.63,
    "Cu": 1.40,
    "Zn": 1.39,
    "Ga": 1.87,
    "As": 1.85,
    "Se": 1.90,
    "Br": 1.85,
    "Kr": 2.02,
    "Pd": 1.63,
    "Ag": 1.72,
    "Cd": 1.58,
    "In": 1.93,
    "Sn": 2.17,
    "Te": 2.06,
    "I": 1.98,
    "Xe": 2.16,
    "Pt": 1.72,
    "Au": 1.66,
    "Hg": 1.55,
    "Tl": 1.96,
    "Pb": 2.02,
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
    """Bondi's van der Waals radius of ``element`` in Å (case-insensitive symbol)."""
    if not isinstance(element, str):
        raise TypeError(f"element must be a str, got {type(element).__name__}")
    key = _UPPER.get(element.strip().upper())
    if key is None:
        raise ValueError(f"element {element!r} is not in Bondi's (1964) table of van der Waals radii")
    return VDW_RADII[key]


#: Residue names (columns 18–21) that are water in PDB, AMBER, CHARMM and GROMACS files.
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
        Centres in Å; radii = van der Waals radius (Bondi 1964, or the ``radii=``
        table of :func:`read_pdb`) + probe.
    atom_names, residue_names, chains, elements : ndarray of str, shape (n,)
        Columns 13–16, 18–21, 22 and 77–78 (element symbols normalised, e.g. ``"Fe"``).
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


def _field_float(line: str, a: int, b: int, what: str, lineno: int) -> float:
    text = line[a:b]
    try:
        v = float(text)
    except ValueError:
        raise ValueError(f"line {lineno}: could not read {what} from columns {a + 1}-{b}: {text.strip()!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"line {lineno}: {what} must be finite, got {text.strip()!r}")
    return v


def _optional_float(line: str, a: int, b: int, what: str, lineno: int) -> float:
    """A float from columns a+1..b, NaN if they are blank or absent."""
    if not line[a:b].strip():
        return math.nan
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


def _read_text(path) -> str:
    raw = Path(path).read_bytes()
    if raw[:2] == b"\x1f\x8b":
        try:
            raw = gzip.decompress(raw)
        except (OSError, EOFError, zlib.error) as e:
            raise ValueError(f"{os.fspath(path)!r} is not a readable gzip file: {e}") from None
    if not raw.strip():
        raise ValueError(f"{os.fspath(path)!r} is empty: no ATOM or HETATM records")
    return raw.decode("latin-1")  # never fails; non-ASCII bytes then fail as bad fields


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
) -> PDBStructure:
    """Read the atoms of a PDB file as balls (Notes §23.1: a molecule is a union of balls).

    Parameters
    ----------
    path : str or os.PathLike
        The PDB file, plain or gzip-compressed (recognised by its first bytes).
    probe : float, default 0
        Probe radius :math:`p \\ge 0` added to every van der Waals radius; ``probe=1.4``
        (water) gives the solvent-accessible model.
    default_radius : float, optional
        Van der Waals radius for elements missing from Bondi's table (and from
        ``radii``).  Without it, such an element raises.
    model : int, optional
        Serial number of the MODEL to read (columns 11–14 of the MODEL record).
        Default: the first model.  Atoms outside any MODEL block count as model 1.
    chain : str or collection of str, optional
        Keep only these chain identifiers (column 22; ``""`` is the blank chain).
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
        Van der Waals radii (Å) that take precedence over Bondi's: keys are element
        symbols (``{"Fe": 2.0}``) or ``(residue name, atom name)`` pairs
        (``{("ALA", "CB"): 1.9}``), the latter winning.  Matching ignores case.

    Returns
    -------
    PDBStructure
        The atoms in file order, with residue names, numbers, insertion codes and
        chains, so that reports can name the residues lining a feature.

    Raises
    ------
    ValueError
        Empty file or no atoms, or no atoms left by the selection; a truncated or
        malformed ATOM/HETATM or MODEL record (the message starts with ``"line N:"``);
        a requested model that is absent; an element without a radius.  Nothing is
        returned in part: any error in the model read fails the whole call.
    FileNotFoundError, IsADirectoryError
        If ``path`` cannot be opened.

    Notes
    -----
    * ATOM and HETATM records are read by the PDB's fixed columns: name 13–16,
      alternate location 17, residue name 18–21 (column 21 holds the fourth letter
      some programs write), chain 22, residue number 23–26, insertion code 27,
      x/y/z 31–38/39–46/47–54, occupancy 55–60, B-factor 61–66, element 77–78.
      A record must reach column 54.  Every record of the model read is parsed
      before any selection is applied, so a malformed line fails even if it would
      have been filtered out.
    * The element comes from columns 77–78; if blank, from the atom name
      (:func:`_element_from_name`).
    * Reading stops at the first ``END``, or at the ``ENDMDL`` of the model read.
    * Alternate locations: for each atom (chain, residue number, insertion code,
      atom name) with labelled alternatives, the one of highest occupancy is kept;
      ties go to the label seen first.  Unlabelled records are always kept.
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
    chains_wanted = _names_arg(chain, "chain", 1)
    if isinstance(hetatm, (bool, np.bool_)):
        het_keep = bool(hetatm)
    else:
        het_keep = _names_arg(hetatm, "hetatm", 4)
    for flag, fname in ((water, "water"), (hydrogens, "hydrogens")):
        if not isinstance(flag, (bool, np.bool_)):
            raise TypeError(f"{fname} must be a bool, got {type(flag).__name__}")
    radii_element, radii_atom = _radius_table(radii)
    text = _read_text(path)

    recs = []  # one tuple per ATOM/HETATM record of the model read
    target = model  # the MODEL serial wanted (None: the first one met)
    current = None  # serial of the open MODEL block (None: outside any)
    models_seen = []
    for lineno, line in enumerate(text.splitlines(), start=1):
        rec = line[:6].rstrip()
        if rec == "END":
            break
        if rec == "MODEL":
            if current is not None:
                raise ValueError(f"line {lineno}: MODEL record inside MODEL {current} (missing ENDMDL)")
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
        here = 1 if current is None else current
        if (target if target is not None else 1) != here:
            continue
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
            num = int(num_text)
        except ValueError:
            raise ValueError(
                f"line {lineno}: could not read the residue number from columns 23-26: {num_text.strip()!r}"
            ) from None
        name = line[12:16]
        resname = line[17:21].strip()
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
                line[21].strip(),
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

    if model is not None and model not in models_seen and not (model == 1 and recs):
        raise ValueError(f"{os.fspath(path)!r} has no MODEL {model} (models read before END: {models_seen or 'none'})")
    if not recs:
        raise ValueError(f"{os.fspath(path)!r} holds no ATOM or HETATM records (before END/ENDMDL)")

    # alternate locations: per atom, the highest occupancy (ties: the first label seen)
    best = {}
    for k, r in enumerate(recs):
        if r[2]:
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
                f"der Waals radius in Bondi's (1964) table; pass default_radius= (or radii=) "
                f"to use one"
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


def _str_column(values, n: int, name: str, width: int, default):
    if values is None:
        return [default(i) for i in range(n)]
    if isinstance(values, str):
        values = [values] * n
    values = list(values)
    if len(values) != n:
        raise ValueError(f"{name} must have one entry per ball ({n}), got {len(values)}")
    out = []
    for i, v in enumerate(values):
        s = str(v)
        if len(s) > width or not s.isascii() or any(c in s for c in "\r\n"):
            raise ValueError(f"{name}[{i}] = {s!r} does not fit the PDB's {width}-character ASCII field")
        out.append(s)
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
) -> Path:
    """Write 3D balls as ATOM/HETATM records of a PDB file.

    The PDB format stores no radii: :func:`read_pdb` recovers them from the elements,
    so a round trip preserves radii exactly when they are Bondi radii (plus one probe).
    Coordinates are written with three decimals (the format's precision, 0.001 Å).

    Parameters
    ----------
    path : str or os.PathLike
    balls : Balls
        3D balls; every coordinate must lie in (-1000, 10000) to fit columns 31–54.
    elements : sequence of str or str
        Element symbols (one per ball, or one for all).
    atom_names, residue_names, chains : sequence of str, optional
        Default: the element symbol, ``"UNK"``, ``"A"``.
    residue_numbers : sequence of int, optional
        Default: 1, 2, ..., n (one residue per atom).
    hetero : sequence of bool, optional
        True writes HETATM instead of ATOM.
    title : str, optional
        Written as a TITLE record (at most 70 characters).
    b_factors : sequence of float, optional
        Values for the B-factor column (61–66), e.g. a label per atom as
        :func:`shapelab.report` writes; each must fit ``%6.2f``.  Default 0.

    Returns
    -------
    pathlib.Path
    """
    check_balls(balls)
    if balls.dim != 3:
        raise ValueError(f"balls must be 3-dimensional to be written as a PDB file, got dim={balls.dim}")
    n = len(balls)
    if n == 0:
        raise ValueError("balls must hold at least one ball")
    if n > 99999:
        raise ValueError(f"the PDB format holds at most 99999 atoms, got {n}")
    c = balls.centers
    if np.any(c <= -999.9995) or np.any(c >= 9999.9995):
        raise ValueError("balls.centers must lie in (-1000, 10000) to fit the PDB's coordinate columns")
    elements = _str_column(elements, n, "elements", 2, None)
    for i, e in enumerate(elements):
        if not (e.isalpha() and 1 <= len(e) <= 2):
            raise ValueError(f"elements[{i}] = {e!r} is not an element symbol")
    elements = [e[0].upper() + e[1:].lower() for e in elements]
    atom_names = _str_column(atom_names, n, "atom_names", 4, lambda i: elements[i].upper())
    residue_names = _str_column(residue_names, n, "residue_names", 3, lambda i: "UNK")
    chains = _str_column(chains, n, "chains", 1, lambda i: "A")
    if residue_numbers is None:
        residue_numbers = np.arange(1, n + 1)
    residue_numbers = np.asarray(residue_numbers)
    if residue_numbers.shape != (n,) or residue_numbers.dtype.kind not in "iu":
        raise ValueError(f"residue_numbers must be {n} integers")
    if np.any(residue_numbers < -999) or np.any(residue_numbers > 9999):
        raise ValueError("residue_numbers must lie in [-999, 9999] to fit columns 23-26")
    hetero = np.zeros(n, bool) if hetero is None else np.asarray(hetero, dtype=bool)
    if hetero.shape != (n,):
        raise ValueError(f"hetero must have shape ({n},), got {hetero.shape}")

    if b_factors is None:
        b_factors = np.zeros(n)
    b_factors = np.asarray(b_factors, dtype=np.float64)
    if b_factors.shape != (n,):
        raise ValueError(f"b_factors must have shape ({n},), got {b_factors.shape}")
    if not np.all(np.isfinite(b_factors)) or np.any(b_factors <= -99.995) or np.any(b_factors >= 999.995):
        raise ValueError("b_factors must be finite and lie in (-100, 1000) to fit columns 61-66")

    lines = []
    if title is not None:
        t = str(title)
        if len(t) > 70 or not t.isascii() or "\n" in t:
            raise ValueError("title must be at most 70 ASCII characters on one line")
        lines.append(f"TITLE     {t}")
    for i in range(n):
        name = atom_names[i]
        # element symbols right-justified in columns 13-14 (PDB convention)
        if len(name) < 4 and len(elements[i]) == 1:
            name = " " + name
        rec = "HETATM" if hetero[i] else "ATOM"
        lines.append(
            f"{rec:<6}{(i + 1) % 100000:>5} {name:<4} {residue_names[i]:>3} {chains[i]:1}"
            f"{int(residue_numbers[i]):>4}    {c[i, 0]:8.3f}{c[i, 1]:8.3f}{c[i, 2]:8.3f}"
            f"{1.0:6.2f}{b_factors[i]:6.2f}          {elements[i].upper():>2}"
        )
    lines.append("END")
    out = Path(path)
    out.write_text("\n".join(lines) + "\n", encoding="ascii")
    return out
