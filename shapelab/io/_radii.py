"""Van der Waals radii of the elements, and the radius given to each atom (Notes §23.1).

:data:`VDW_RADII` is the table of A. Bondi, "van der Waals Volumes and Radii",
*J. Phys. Chem.* **68**, 441–451 (1964), Table I (values in Å), completed for the
main-group elements Bondi does not list (Be, B, Al, Ca, Ge, Rb, Sr, Sb, Cs, Ba, Bi,
Po, At, Rn, Fr, Ra) by M. Mantina, A. C. Chamberlin, R. Valero, C. J. Cramer and
D. G. Truhlar, "Consistent van der Waals Radii for the Whole Main Group",
*J. Phys. Chem. A* **113**, 5806–5812 (2009), Table 12.  Where Bondi has a value it is
kept (Mantina et al. give H 1.10, Li 1.81 and Br 1.83 instead of Bondi's 1.20, 1.82
and 1.85; the rest of their Table 12 is Bondi's).

Most transition metals (Fe, Mn, Co, Mo, ...), the lanthanides and most actinides are in
neither table.  :data:`ALVAREZ_RADII` gives them the radii of one published table that
covers them: S. Alvarez, "A cartography of the van der Waals territories", *Dalton
Trans.* **42**, 8617–8636 (2013), Table 1 -- for those elements only; every radius of
:data:`VDW_RADII` is kept.  A report names each use of it (:func:`radius_notes`).
What no table lists (promethium, the elements after einsteinium, an unknown symbol)
raises unless a ``default_radius`` (or ``radii=``) is given.

The order in which an atom gets its radius (:func:`atom_radii`):

1. ``radii=`` by (residue name, atom name), then by element -- what the user wrote;
2. :data:`VDW_RADII` (Bondi 1964, Mantina et al. 2009; deuterium takes hydrogen's);
3. :data:`ALVAREZ_RADII` (Alvarez 2013), for the elements step 2 lacks;
4. ``default_radius``, for the elements no table lists;
5. otherwise a ValueError naming the element, the atom and its line.

A reader gives its atoms their radii here, with :func:`atom_radii`.
"""

from __future__ import annotations

import numpy as np

from .._toolkit.validate import as_finite_scalar

__all__ = [
    "VDW_RADII",
    "ALVAREZ_RADII",
    "ELEMENT_SYMBOLS",
    "RADIUS_SOURCES",
    "vdw_radius",
    "vdw_radius_source",
    "radius_table",
    "atom_radii",
    "radius_notes",
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

#: van der Waals radii in Å of the elements :data:`VDW_RADII` lacks, from S. Alvarez,
#: "A cartography of the van der Waals territories", Dalton Trans. 42:8617-8636 (2013),
#: doi:10.1039/C3DT50599E, Table 1 (radii from the distribution of non-bonded
#: distances in the Cambridge Structural Database).  Only the elements neither Bondi
#: nor Mantina et al. list are taken; the table has none for Pm nor past Es.  The
#: values were read from two independent transcriptions of Table 1 that agree on every
#: one of them: ASE 3.29.0 (ase/data/vdw_alvarez.py) and mendeleev 1.3.0
#: (``vdw_radius_alvarez``, in pm).  Alvarez marks the values of Ac, Pa, Cm, Bk, Cf and
#: Es as of larger uncertainty.
ALVAREZ_RADII: dict[str, float] = {
    "Sc": 2.58,
    "Ti": 2.46,
    "V": 2.42,
    "Cr": 2.45,
    "Mn": 2.45,
    "Fe": 2.44,
    "Co": 2.40,
    "Y": 2.75,
    "Zr": 2.52,
    "Nb": 2.56,
    "Mo": 2.45,
    "Tc": 2.44,
    "Ru": 2.46,
    "Rh": 2.44,
    "La": 2.98,
    "Ce": 2.88,
    "Pr": 2.92,
    "Nd": 2.95,
    "Sm": 2.90,
    "Eu": 2.87,
    "Gd": 2.83,
    "Tb": 2.79,
    "Dy": 2.87,
    "Ho": 2.81,
    "Er": 2.83,
    "Tm": 2.79,
    "Yb": 2.80,
    "Lu": 2.74,
    "Hf": 2.63,
    "Ta": 2.53,
    "W": 2.57,
    "Re": 2.49,
    "Os": 2.48,
    "Ir": 2.41,
    "Ac": 2.80,  # larger uncertainty
    "Th": 2.93,
    "Pa": 2.88,  # larger uncertainty
    "Np": 2.82,
    "Pu": 2.81,
    "Am": 2.83,
    "Cm": 3.05,  # larger uncertainty
    "Bk": 3.40,  # larger uncertainty
    "Cf": 3.05,  # larger uncertainty
    "Es": 2.70,  # larger uncertainty
}
_ALVAREZ_UPPER = {k.upper(): k for k in ALVAREZ_RADII}

#: Where an atom's radius came from, as :attr:`PDBStructure.radius_sources` names it:
#: key -> the table (or keyword) it names.  ``""``: not known (a structure built in code).
RADIUS_SOURCES = {
    "radii": "the radii= table",
    "bondi": "Bondi (1964)",
    "mantina": "Mantina et al. (2009)",
    "alvarez": "Alvarez (2013)",
    "default": "default_radius=",
}
_MANTINA = {"Be", "B", "Al", "Ca", "Ge", "Rb", "Sr", "Sb", "Cs", "Ba", "Bi", "Po", "At", "Rn", "Fr", "Ra"}
#: The tables, as the messages name them.
TABLES = "Bondi's (1964), Mantina et al.'s (2009) or Alvarez's (2013) table"
#: Alvarez (2013) in full, as a report's notes cite it.
ALVAREZ_CITATION = (
    'S. Alvarez, "A cartography of the van der Waals territories", Dalton Trans. 42, 8617-8636 (2013), Table 1'
)
#: Every element symbol (to read atom names; radii exist only for those in VDW_RADII and
#: ALVAREZ_RADII).
ELEMENT_SYMBOLS = {
    e.upper(): e
    for e in (
        "H He Li Be B C N O F Ne Na Mg Al Si P S Cl Ar K Ca Sc Ti V Cr Mn Fe Co Ni Cu Zn Ga Ge "
        "As Se Br Kr Rb Sr Y Zr Nb Mo Tc Ru Rh Pd Ag Cd In Sn Sb Te I Xe Cs Ba La Ce Pr Nd Pm Sm "
        "Eu Gd Tb Dy Ho Er Tm Yb Lu Hf Ta W Re Os Ir Pt Au Hg Tl Pb Bi Po At Rn Fr Ra Ac Th Pa U "
        "Np Pu Am Cm Bk Cf Es Fm Md No Lr"
    ).split()
}


def _table_key(element: str):
    """(source key, symbol) of ``element``'s radius in the tables, or None."""
    eu = element.strip().upper()
    key = _UPPER.get(eu)
    if key is not None:
        return ("mantina" if key in _MANTINA else "bondi"), key
    key = _ALVAREZ_UPPER.get(eu)
    if key is not None:
        return "alvarez", key
    return None


def vdw_radius(element: str) -> float:
    """The van der Waals radius of ``element`` in Å (case-insensitive symbol).

    Bondi's (1964) value (:data:`VDW_RADII`), or for a main-group element Bondi does not
    list, that of Mantina et al. (2009); for an element in neither (most transition
    metals, the lanthanides, most actinides), that of Alvarez (2013), Table 1
    (:data:`ALVAREZ_RADII`).  Notes §23.1: one ball per atom, of its van der Waals
    radius.  :func:`vdw_radius_source` says which table gave it.

    Raises
    ------
    ValueError
        For an element in none of the three tables (Pm, the elements after Es, an
        unknown symbol).

    See Also
    --------
    vdw_radius_source : which table the radius is from.
    read_pdb : reads these radii; ``default_radius=`` or ``radii=`` for other elements.

    References
    ----------
    A. Bondi, "van der Waals Volumes and Radii", *J. Phys. Chem.* **68**, 441–451 (1964).
    M. Mantina, A. C. Chamberlin, R. Valero, C. J. Cramer, D. G. Truhlar, "Consistent
    van der Waals Radii for the Whole Main Group", *J. Phys. Chem. A* **113**, 5806–5812
    (2009), Table 12.
    S. Alvarez, "A cartography of the van der Waals territories", *Dalton Trans.* **42**,
    8617–8636 (2013), Table 1.  doi:10.1039/C3DT50599E

    Examples
    --------
    >>> vdw_radius("C"), vdw_radius("ca"), vdw_radius("Be"), vdw_radius("Fe")
    (1.7, 2.31, 1.53, 2.44)
    """
    if not isinstance(element, str):
        raise TypeError(f"element must be a str, got {type(element).__name__}")
    found = _table_key(element)
    if found is None:
        raise ValueError(f"element {element!r} has no van der Waals radius in {TABLES}")
    source, key = found
    return ALVAREZ_RADII[key] if source == "alvarez" else VDW_RADII[key]


def vdw_radius_source(element: str) -> str:
    """Which table :func:`vdw_radius` takes ``element``'s radius from: ``"Bondi (1964)"``,
    ``"Mantina et al. (2009)"`` or ``"Alvarez (2013)"`` (the values of :data:`RADIUS_SOURCES`).

    Raises
    ------
    ValueError
        As :func:`vdw_radius`, for an element in none of the tables.

    See Also
    --------
    vdw_radius : the radius.
    radius_notes : what a report says of the radii of a structure's atoms.

    Examples
    --------
    >>> vdw_radius_source("C"), vdw_radius_source("Ba"), vdw_radius_source("mn")
    ('Bondi (1964)', 'Mantina et al. (2009)', 'Alvarez (2013)')
    """
    vdw_radius(element)  # the same refusals
    return RADIUS_SOURCES[_table_key(element)[0]]


def radius_table(radii):
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


def atom_radii(records, tables, default_radius, where="line") -> tuple:
    """The van der Waals radius of each atom record and where it came from.

    In this order: ``radii=`` by (residue, atom) name, then by element;
    :data:`VDW_RADII` (deuterium takes hydrogen's); :data:`ALVAREZ_RADII`;
    ``default_radius``.  An atom with none raises, naming its line (``where`` names what
    :attr:`AtomRecord.line` counts) and the tables.  ``tables`` is what
    :func:`radius_table` returns.  Returns the radii (float64) and, per atom, the key of
    :data:`RADIUS_SOURCES` that gave each."""
    radii_element, radii_atom = tables
    rad = np.empty(len(records))
    src = []
    for i, r in enumerate(records):
        e, resn, name = r.element, r.residue, r.name
        eu = e.upper()
        ra = radii_atom.get((resn.upper(), name.upper()))
        if ra is None:
            ra = radii_element.get(eu)
        source = "radii"
        if ra is None:
            found = _table_key("H" if eu == "D" else eu)  # deuterium: hydrogen's radius
            if found is not None:
                source, key = found
                ra = ALVAREZ_RADII[key] if source == "alvarez" else VDW_RADII[key]
            elif default_radius is not None:
                source, ra = "default", default_radius
        if ra is None:
            raise ValueError(
                f"{where} {r.line}: element {e!r} (atom {name!r}, residue {resn} {r.number}) has no van "
                f"der Waals radius in {TABLES}; pass default_radius= (or radii=) to use one"
            )
        rad[i] = ra
        src.append(source)
    return rad, np.array(src, dtype=str)


def radius_notes(structure) -> tuple:
    """What a report says of the radii of ``structure``'s atoms: one note for the atoms
    that took an Alvarez (2013) radius (which elements, how many atoms, the table
    cited) and one for those that took ``default_radius`` (``()`` when neither did, or
    for a structure without :attr:`~PDBStructure.radius_sources`).  :func:`shapelab.report`
    puts them in :attr:`CavityReport.notes <shapelab.report.CavityReport.notes>`,
    which its Markdown prints above the table.  Nothing is warned: the notes are the
    record.

    See Also
    --------
    vdw_radius_source : which table an element's radius is from.
    read_pdb : records the table of each atom (``radius_sources``).
    shapelab.report : the report that carries the notes.

    References
    ----------
    S. Alvarez, "A cartography of the van der Waals territories", *Dalton Trans.* **42**,
    8617–8636 (2013), Table 1.  doi:10.1039/C3DT50599E

    Examples
    --------
    >>> from shapelab.datasets import structure
    >>> radius_notes(structure("1hvr"))
    ()
    """
    sources = getattr(structure, "radius_sources", None)
    if sources is None or not len(sources):
        return ()
    elements = np.asarray(structure.elements)
    notes = []
    for key in ("alvarez", "default"):
        mask = sources == key
        if not mask.any():
            continue
        names, counts = np.unique(elements[mask], return_counts=True)
        n = int(mask.sum())
        atoms = f"{n} atom{'s' if n != 1 else ''}"
        each = ", ".join(f"{e} {c}" for e, c in zip(names.tolist(), counts.tolist()))
        if key == "alvarez":
            notes.append(
                f"van der Waals radii of Alvarez (2013) for {atoms} ({each}), elements Bondi (1964) and "
                f"Mantina et al. (2009) do not list: {ALVAREZ_CITATION}"
            )
        else:
            r = np.unique(np.round(np.asarray(structure.balls.radii)[mask] - structure.probe, 6))
            value = ", ".join(f"{v:g}" for v in r.tolist())
            notes.append(f"default_radius={value} Å for {atoms} ({each}), elements no table of radii lists")
    return tuple(notes)
