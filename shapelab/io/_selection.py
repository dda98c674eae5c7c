"""Which atoms of a structure are kept: alternate locations, water, HETATM, chains,
hydrogens (Notes §23.1: the van der Waals model of a molecule is its heavy atoms).

The rules are the reader's documented defaults (:func:`shapelab.io.read_pdb`); they act
on :class:`~shapelab.io._structure.AtomRecord` lists, so every reader shares them.
"""

from __future__ import annotations

import math
import os

__all__ = [
    "WATER_RESIDUES",
    "STANDARD_RESIDUES",
    "names_arg",
    "resolve_alternate_locations",
    "select_atoms",
    "kept_structure",
]

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


def names_arg(value, name: str, width: int):
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


def resolve_alternate_locations(records) -> list:
    """The records left when each atom keeps one alternate location.

    Per residue (chain, number, insertion code) with labelled alternatives, the residue
    name of the labelled record of highest occupancy wins (ties: the first seen), and
    the labelled records of its other names are dropped, so that no residue mixes two
    (1EJG's PRO/SER 22).  Per atom, the labelled record of highest occupancy is kept
    (ties: the first label seen).  Unlabelled records are always kept."""
    resname_of = {}
    for r in records:
        if r.altloc:
            key = (r.chain, r.number, r.icode)
            occ = -math.inf if math.isnan(r.occupancy) else r.occupancy
            if key not in resname_of or occ > resname_of[key][1]:
                resname_of[key] = (r.residue, occ)
    best = {}
    for k, r in enumerate(records):
        if r.altloc and r.residue == resname_of[(r.chain, r.number, r.icode)][0]:
            key = (r.chain, r.number, r.icode, r.name)
            occ = -math.inf if math.isnan(r.occupancy) else r.occupancy
            if key not in best or occ > best[key][1]:
                best[key] = (k, occ)
    keep_alt = {k for k, _ in best.values()}
    return [r for k, r in enumerate(records) if not r.altloc or k in keep_alt]


def select_atoms(records, *, chains_wanted, het_keep, water, hydrogens, path, chain, hetatm, read=None) -> list:
    """The records the selection keeps (water by ``water`` alone; HETATM by ``het_keep``:
    True, False or a set of residue names; chains; hydrogens and deuterium), in order.
    An empty result raises, naming the file, the selection and the chains present
    among ``read`` (all the records read, by default ``records``)."""
    read = records if read is None else read
    kept = []
    for r in records:
        if r.residue.upper() in WATER_RESIDUES:
            if not water:
                continue
        elif r.hetero and not (het_keep is True or (het_keep and r.residue in het_keep)):
            continue
        if chains_wanted is not None and r.chain not in chains_wanted:
            continue
        if not hydrogens and r.element in ("H", "D"):
            continue
        kept.append(r)
    if not kept:
        raise ValueError(
            f"{os.fspath(path)!r}: none of its {len(read)} atoms is left by the selection "
            f"(chain={chain!r}, hetatm={hetatm!r}, water={water}, hydrogens={hydrogens}; "
            f"chains present: {sorted({r.chain for r in read})})"
        )
    return kept


def kept_structure(records, *, tables, default_radius, probe, model, where="line", **selection):
    """What every reader does after parsing: keep one alternate location per atom, apply
    the selection (:func:`select_atoms`'s keywords), give each kept atom its radius
    (:func:`shapelab.io._radii.atom_radii`, ``where`` naming the place of an atom in the
    file) and build the :class:`~shapelab.io._structure.PDBStructure`."""
    from ._radii import atom_radii
    from ._structure import structure_from_records

    kept = select_atoms(resolve_alternate_locations(records), read=records, **selection)
    radii, sources = atom_radii(kept, tables, default_radius, where=where)
    return structure_from_records(kept, radii, probe, model, radius_sources=sources)
