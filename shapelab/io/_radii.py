"""Van der Waals radii of the elements, and the radius given to each atom (Notes §23.1).

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

A reader gives its atoms their radii here, with :func:`atom_radii`.
"""

from __future__ import annotations

import numpy as np

from .._toolkit.validate import as_finite_scalar

__all__ = ["VDW_RADII", "ELEMENT_SYMBOLS", "vdw_radius", "radius_table", "atom_radii"]

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
ELEMENT_SYMBOLS = {
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


def atom_radii(records, tables, default_radius, where="line") -> np.ndarray:
    """The van der Waals radius of each atom record: ``radii=`` by (residue, atom) name,
    then by element, then :data:`VDW_RADII` (deuterium takes hydrogen's), then
    ``default_radius``; an atom with none raises, naming its line (``where`` names
    what :attr:`AtomRecord.line` counts).  ``tables`` is what :func:`radius_table` returns."""
    radii_element, radii_atom = tables
    rad = np.empty(len(records))
    for i, r in enumerate(records):
        e, resn, name = r.element, r.residue, r.name
        eu = e.upper()
        ra = radii_atom.get((resn.upper(), name.upper()))
        if ra is None:
            ra = radii_element.get(eu)
        if ra is None:
            key = _UPPER.get("H" if eu == "D" else eu)  # deuterium: hydrogen's radius
            ra = VDW_RADII[key] if key is not None else default_radius
        if ra is None:
            raise ValueError(
                f"{where} {r.line}: element {e!r} (atom {name!r}, residue {resn} {r.number}) has no van "
                f"der Waals radius in Bondi's (1964) or Mantina et al.'s (2009) table; pass "
                f"default_radius= (or radii=) to use one"
            )
        rad[i] = ra
    return rad
