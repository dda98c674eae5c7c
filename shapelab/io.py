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

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._validate import as_finite_scalar
from .balls import Balls

__all__ = ["VDW_RADII", "PDBStructure", "read_pdb", "write_pdb", "vdw_radius"]

#: van der Waals radii in Å, Bondi (1964), J. Phys. Chem. 68:441, Table I.
VDW_RADII: dict[str, float] = {
    "H": 1.20, "He": 1.40,
    "Li": 1.82, "C": 1.70, "N": 1.55, "O": 1.52, "F": 1.47, "Ne": 1.54,
    "Na": 2.27, "Mg": 1.73, "Si": 2.10, "P": 1.80, "S": 1.80, "Cl": 1.75, "Ar": 1.88,
    "K": 2.75, "Ni": 1.63, "Cu": 1.40, "Zn": 1.39, "Ga": 1.87, "As": 1.85, "Se": 1.90,
    "Br": 1.85, "Kr": 2.02,
    "Pd": 1.63, "Ag": 1.72, "Cd": 1.58, "In": 1.93, "Sn": 2.17, "Te": 2.06, "I": 1.98,
    "Xe": 2.16,
    "Pt": 1.72, "Au": 1.66, "Hg": 1.55, "Tl": 1.96, "Pb": 2.02, "U": 1.86,
}
_UPPER = {k.upper(): k for k in VDW_RADII}
#: Every element symbol (to read atom names; radii exist only for those in VDW_RADII).
_SYMBOLS = {e.upper(): e for e in (
    "H He Li Be B C N O F Ne Na Mg Al Si P S Cl Ar K Ca Sc Ti V Cr Mn Fe Co Ni Cu Zn Ga Ge "
    "As Se Br Kr Rb Sr Y Zr Nb Mo Tc Ru Rh Pd Ag Cd In Sn Sb Te I Xe Cs Ba La Ce Pr Nd Pm Sm "
    "Eu Gd Tb Dy Ho Er Tm Yb Lu Hf Ta W Re Os Ir Pt Au Hg Tl Pb Bi Po At Rn Fr Ra Ac Th Pa U "
    "Np Pu Am Cm Bk Cf Es Fm Md No Lr").split()}


def vdw_radius(element: str) -> float:
    """Bondi's van der Waals radius of ``element`` in Å (case-insensitive symbol)."""
    if not isinstance(element, str):
        raise TypeError(f"element must be a str, got {type(element).__name__}")
    key = _UPPER.get(element.strip().upper())
    if key is None:
        raise ValueError(f"element {element!r} is not in Bondi's (1964) table of van der Waals radii")
    return VDW_RADII[key]


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a, copy=True)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class PDBStructure:
    """Atoms of the first model of a PDB file, as balls plus their labels.

    Attributes
    ----------
    balls : Balls
        Centres in Å; radii = van der Waals radius (Bondi 1964) + probe.
    atom_names, residue_names, chains, elements : ndarray of str, shape (n,)
        Columns 13–16, 18–20, 22 and 77–78 (element symbols normalised, e.g. ``"Fe"``).
    residue_numbers : ndarray of int64, shape (n,)
        Columns 23–26.
    hetero : ndarray of bool, shape (n,)
        True for HETATM records.
    probe : float
        The probe radius that was added to every van der Waals radius.
    """

    balls: Balls
    atom_names: np.ndarray
    residue_names: np.ndarray
    residue_numbers: np.ndarray
    chains: np.ndarray
    elements: np.ndarray
    hetero: np.ndarray
    probe: float = 0.0

    def __len__(self) -> int:
        return len(self.balls)

    def __repr__(self) -> str:
        n_res = len(set(zip(self.chains.tolist(), self.residue_numbers.tolist())))
        return f"PDBStructure(n_atoms={len(self)}, n_residues={n_res}, probe={self.probe})"

    def label(self, i: int) -> str:
        """A human-readable label of atom ``i``, e.g. ``'A:LEU12:CD1'``."""
        i = int(i)
        return (f"{self.chains[i]}:{self.residue_names[i]}{self.residue_numbers[i]}:"
                f"{self.atom_names[i]}")


def _element_from_name(name: str) -> str:
    """Guess an element from a PDB atom name (columns 13–16).

    PDB convention: the element symbol is right-justified in columns 13–14, so
    ``" CA "`` is an alpha carbon and ``"CA  "`` is calcium.  Four-character hydrogen
    names (``"HG21"``, ``"1HG2"``) are hydrogens.
    """
    name4 = name.ljust(4)[:4]
    first, second = name4[0], name4[1]
    if first == " " or first.isdigit():
        return second if second.isalpha() else ""
    if first.upper() == "H" and len(name4.strip()) == 4:
        return "H"
    two = (first + second).strip()
    if len(two) == 2 and two.upper() in _SYMBOLS:
        return _SYMBOLS[two.upper()]
    return first.upper() if first.isalpha() else ""


def _field_float(line: str, a: int, b: int, what: str, lineno: int) -> float:
    text = line[a:b]
    try:
        v = float(text)
    except ValueError:
        raise ValueError(
            f"line {lineno}: could not read {what} from columns {a + 1}-{b}: {text.strip()!r}"
        ) from None
    if not math.isfinite(v):
        raise ValueError(f"line {lineno}: {what} must be finite, got {text.strip()!r}")
    return v


def read_pdb(path, *, probe=0.0, default_radius=None) -> PDBStructure:
    """Read the atoms of a PDB file as balls (Notes §23.1: a molecule is a union of balls).

    Parameters
    ----------
    path : str or os.PathLike
        The PDB file.
    probe : float, default 0
        Probe radius :math:`p \\ge 0` added to every van der Waals radius; ``probe=1.4``
        (water) gives the solvent-accessible model.
    default_radius : float, optional
        Van der Waals radius for elements missing from Bondi's table.  Without it,
        such an element raises.

    Returns
    -------
    PDBStructure

    Raises
    ------
    ValueError
        Empty file or no atoms; a truncated or malformed ATOM/HETATM record (the message
        starts with ``"line N:"``); an element without a radius.
    FileNotFoundError, IsADirectoryError
        If ``path`` cannot be opened.

    Notes
    -----
    * ATOM and HETATM records are read by the PDB's fixed columns: name 13–16,
      alternate location 17, residue name 18–20, chain 22, residue number 23–26,
      x/y/z 31–38/39–46/47–54, element 77–78.  A record must reach column 54.
    * The element comes from columns 77–78; if blank, from the atom name
      (:func:`_element_from_name`).
    * Reading stops at the first ``END`` or ``ENDMDL``, so only the first model of an
      NMR ensemble is read.
    * Of alternate locations only the blank one and the first label seen
      (usually ``A``) are kept.
    * Other records (HEADER, REMARK, ANISOU, TER, CONECT, ...) are ignored.
    """
    if isinstance(path, (bytes, bytearray)) or not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or os.PathLike, got {type(path).__name__}")
    probe = as_finite_scalar(probe, "probe", nonnegative=True)
    if default_radius is not None:
        default_radius = as_finite_scalar(default_radius, "default_radius", positive=True)
    raw = Path(path).read_bytes()
    if not raw.strip():
        raise ValueError(f"{os.fspath(path)!r} is empty: no ATOM or HETATM records")
    text = raw.decode("latin-1")  # never fails; non-ASCII bytes then fail as bad fields

    xyz, names, resn, resi, chain, elem, het, where = [], [], [], [], [], [], [], []
    altloc_kept = None
    for lineno, line in enumerate(text.splitlines(), start=1):
        rec = line[:6].rstrip()
        if rec in ("END", "ENDMDL"):
            break
        if rec not in ("ATOM", "HETATM"):
            continue
        if len(line) < 54:
            raise ValueError(
                f"line {lineno}: truncated {rec} record (needs at least 54 columns for "
                f"the coordinates, got {len(line.rstrip())})"
            )
        alt = line[16]
        if alt != " ":
            if altloc_kept is None:
                altloc_kept = alt
            elif alt != altloc_kept:
                continue
        x = _field_float(line, 30, 38, "x", lineno)
        y = _field_float(line, 38, 46, "y", lineno)
        z = _field_float(line, 46, 54, "z", lineno)
        num_text = line[22:26]
        try:
            num = int(num_text)
        except ValueError:
            raise ValueError(
                f"line {lineno}: could not read the residue number from columns 23-26: "
                f"{num_text.strip()!r}"
            ) from None
        name = line[12:16]
        e = line[76:78].strip() if len(line) >= 77 else ""
        if e:
            if not (e.isascii() and e.isalpha()):
                raise ValueError(f"line {lineno}: element in columns 77-78 is not a symbol: {e!r}")
            e = e[0].upper() + e[1:].lower()
        else:
            e = _element_from_name(name)
            if not e:
                raise ValueError(
                    f"line {lineno}: no element in columns 77-78 and none can be read "
                    f"from the atom name {name!r}"
                )
        xyz.append((x, y, z))
        names.append(name.strip())
        resn.append(line[17:20].strip())
        resi.append(num)
        chain.append(line[21].strip())
        elem.append(e)
        het.append(rec == "HETATM")
        where.append(lineno)

    if not xyz:
        raise ValueError(f"{os.fspath(path)!r} holds no ATOM or HETATM records (before END/ENDMDL)")

    radii = np.empty(len(elem))
    for i, e in enumerate(elem):
        key = _UPPER.get(e.upper())
        if key is not None:
            radii[i] = VDW_RADII[key]
        elif default_radius is not None:
            radii[i] = default_radius
        else:
            raise ValueError(
                f"line {where[i]}: element {e!r} (atom {names[i]!r}, residue {resn[i]} {resi[i]}) has no van der "
                f"Waals radius in Bondi's (1964) table; pass default_radius= to use one"
            )
    balls = Balls(np.array(xyz, dtype=np.float64), radii + probe)
    return PDBStructure(
        balls=balls,
        atom_names=_readonly(np.array(names, dtype=str)),
        residue_names=_readonly(np.array(resn, dtype=str)),
        residue_numbers=_readonly(np.array(resi, dtype=np.int64)),
        chains=_readonly(np.array(chain, dtype=str)),
        elements=_readonly(np.array(elem, dtype=str)),
        hetero=_readonly(np.array(het, dtype=bool)),
        probe=probe,
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


def write_pdb(path, balls: Balls, elements, *, atom_names=None, residue_names=None,
              residue_numbers=None, chains=None, hetero=None, title=None) -> Path:
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

    Returns
    -------
    pathlib.Path
    """
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be a shapelab.Balls, got {type(balls).__name__}")
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
            f"{1.0:6.2f}{0.0:6.2f}          {elements[i].upper():>2}"
        )
    lines.append("END")
    out = Path(path)
    out.write_text("\n".join(lines) + "\n", encoding="ascii")
    return out
