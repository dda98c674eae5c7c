"""Reading and writing molecules as balls: PDB and mmCIF files (Notes §23.1).

The notes model a molecule as a union of balls :math:`\\bigcup B_i`, one ball per atom,
with the atom's van der Waals radius.  Adding a *probe* radius :math:`p` to every ball
gives the solvent-accessible model (Lee & Richards 1971): a water molecule of radius
:math:`p` can touch the van der Waals surface exactly where its centre lies on the
boundary of :math:`\\bigcup B(z_i, r_i + p)`.

:func:`read_structure` reads what the PDB distributes: PDB files (the fixed-column
ATOM and HETATM records of the wwPDB's *Atomic Coordinate Entry Format Description*,
v3.3, read by the strict teaching parser :func:`read_pdb`) and PDBx/mmCIF files (the
``_atom_site`` table, parsed by gemmi), plain or gzip; nothing in a file is ever
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
and 1.85; the rest of their Table 12 is Bondi's).  The elements in neither table --
most transition metals (Fe, Mn, Co, Mo, ...), the lanthanides, most actinides -- take
the radii of S. Alvarez, "A cartography of the van der Waals territories", *Dalton
Trans.* **42**, 8617–8636 (2013), Table 1 (:data:`ALVAREZ_RADII`), and a report says
which atoms did (:func:`radius_notes`).  An atom's radius is, in this order: the
reader's ``radii=`` (by residue and atom name, then by element), Bondi/Mantina,
Alvarez, then ``default_radius``; an element none of them gives (Pm, the elements
after Es, an unknown symbol) raises, naming the element, the file and the line.

Layout
------
A reader is given its keywords checked once, as a :class:`ReadOptions`, and turns a
file into :class:`~shapelab.io._structure.AtomRecord` rows; the rules
every reader shares then keep some of them (:mod:`~shapelab.io._selection`: alternate
locations, water, HETATM, chains, hydrogens) and give each its radius
(:mod:`~shapelab.io._radii`), and the result is a :class:`PDBStructure`:

==========================  ==============================================================
``shapelab.io._read``       :func:`read_structure`: recognises the format
``shapelab.io._options``    :class:`ReadOptions`: the readers' keywords, checked once
``shapelab.io._pdb``        :func:`read_pdb`: the PDB format's fixed columns
``shapelab.io._mmcif``      mmCIF's ``_atom_site`` table (gemmi's CIF parser)
``shapelab.io._selection``  which atoms are kept
``shapelab.io._radii``      :data:`VDW_RADII`, :data:`ALVAREZ_RADII`, :func:`vdw_radius`
``shapelab.io._structure``  :class:`PDBStructure`
``shapelab.io._writers``    :func:`write_pdb`, :func:`write_mmcif`
==========================  ==============================================================

Everything public is imported from ``shapelab.io``; the private modules are its
implementation, as in ``scipy.spatial``.
"""

from __future__ import annotations

from ._options import MAX_PDB_BYTES, ReadOptions
from ._pdb import element_from_name, read_pdb
from ._radii import ALVAREZ_RADII, VDW_RADII, radius_notes, vdw_radius, vdw_radius_source
from ._read import detect_format, read_structure
from ._selection import STANDARD_RESIDUES, WATER_RESIDUES
from ._structure import PDBStructure
from ._writers import write_mmcif, write_pdb

__all__ = [
    "VDW_RADII",
    "ALVAREZ_RADII",
    "WATER_RESIDUES",
    "STANDARD_RESIDUES",
    "MAX_PDB_BYTES",
    "PDBStructure",
    "ReadOptions",
    "read_pdb",
    "read_structure",
    "detect_format",
    "write_pdb",
    "write_mmcif",
    "vdw_radius",
    "vdw_radius_source",
    "radius_notes",
    "element_from_name",
]
