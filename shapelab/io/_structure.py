"""A structure's atoms as balls plus their labels: :class:`PDBStructure`, and the
:class:`AtomRecord` rows every reader produces on the way (Notes §23.1)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .._toolkit.validate import readonly
from ..balls import Balls

__all__ = ["PDBStructure", "AtomRecord", "structure_from_records"]


class AtomRecord(NamedTuple):
    """One atom as a reader found it, before selection and radii."""

    line: int
    hetero: bool
    altloc: str
    name: str
    residue: str
    chain: str
    number: int
    icode: str
    x: float
    y: float
    z: float
    occupancy: float
    b_factor: float
    element: str


def _fill(a, n, default, dtype):
    return readonly(np.full(n, default, dtype=dtype) if a is None else np.asarray(a, dtype=dtype))


@dataclass(frozen=True, eq=False)
class PDBStructure:
    """Atoms of one model of a PDB file, as balls plus their labels.

    Attributes
    ----------
    balls : Balls
        Centres in Å; radii = van der Waals radius (:data:`VDW_RADII`: Bondi 1964 and
        Mantina et al. 2009; :data:`ALVAREZ_RADII`: Alvarez 2013 for the elements they
        lack; or the ``radii=`` table or ``default_radius`` of :func:`read_pdb`) + probe.
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
    radius_sources : ndarray of str, shape (n,)
        Where each atom's van der Waals radius came from, a key of
        :data:`~shapelab.io._radii.RADIUS_SOURCES`: ``"radii"`` (the reader's
        ``radii=``), ``"bondi"``, ``"mantina"``, ``"alvarez"`` (the tables, in the
        order of :func:`~shapelab.io._radii.atom_radii`) or ``"default"``
        (``default_radius=``); ``""`` when not known.  A report's notes name the atoms
        that took an Alvarez (2013) radius or the default
        (:func:`~shapelab.io._radii.radius_notes`).

    The last six default to blanks/NaN for structures built in code.

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
    radius_sources: np.ndarray | None = None

    def __post_init__(self):
        n = len(self.balls)
        for name, default, dtype in (
            ("insertion_codes", "", str),
            ("altlocs", "", str),
            ("occupancies", np.nan, np.float64),
            ("b_factors", np.nan, np.float64),
            ("radius_sources", "", str),
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
            radius_sources=self.radius_sources[idx],
        )


def structure_from_records(records, radii, probe: float, model, radius_sources=None) -> PDBStructure:
    """The :class:`PDBStructure` of the kept ``records`` with van der Waals ``radii``
    (from the tables ``radius_sources`` names), every radius grown by ``probe``."""
    col = list(zip(*records))
    balls = Balls(np.array([(r.x, r.y, r.z) for r in records], dtype=np.float64), radii + probe)
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
        model=model,
        radius_sources=radius_sources,
    )
