"""What every reader is told: one options type, checked once (Notes §23.1).

:func:`~shapelab.io.read_structure`, :func:`~shapelab.io.read_pdb` and the mmCIF and
BinaryCIF branches take the same keywords -- the probe, the radii and which atoms to
keep.  :meth:`ReadOptions.checked` checks them once, with the same messages for every
reader, and the readers pass the one frozen :class:`ReadOptions` on.
"""

from __future__ import annotations

import os
from collections.abc import Collection, Mapping
from dataclasses import dataclass

import numpy as np

from .._toolkit.validate import as_finite_scalar, as_positive_int
from ._radii import radius_table
from ._selection import names_arg

__all__ = ["ReadOptions", "MAX_PDB_BYTES", "NAME_WIDTHS"]

#: Default ``max_bytes`` of :func:`read_pdb`: 256 MiB of (decompressed) text, some
#: 3 million ATOM records -- thirty times the 99,999 atoms a PDB file can number.
MAX_PDB_BYTES = 256 * 2**20

#: The widest ``chain=`` and ``hetatm=`` names each format holds: columns 21–22 and
#: 18–20 of a PDB record; mmCIF's ``auth_asym_id`` of the PDB's large entries (4
#: characters) and the wwPDB's extended 5-character CCD identifiers.
NAME_WIDTHS = {"pdb": (2, 3), "mmcif": (4, 5), "bcif": (4, 5)}


@dataclass(frozen=True)
class ReadOptions:
    """The reading options of :func:`~shapelab.io.read_structure`, checked and normalised.

    Attributes
    ----------
    probe : float
        Added to every radius (Å), ≥ 0.
    default_radius : float or None
        The radius of an element no table lists (Å), > 0.
    model : int or None
        The model read (None: the first in the file).
    chain, hetatm : as given
        The keywords as the caller gave them (error messages quote them).
    water, hydrogens : bool
        Keep water molecules, hydrogen and deuterium atoms.
    max_bytes : int
        The most (decompressed) bytes read.
    chains_wanted : frozenset of str or None
        The chains kept (None: all).
    het_keep : bool or frozenset of str
        HETATM records kept: all, none, or those of these residue names.
    tables : tuple of dict
        The ``radii=`` table, by element and by (residue, atom).
    format : str
        The format the names were checked for (``"pdb"``, ``"mmcif"``, ``"bcif"``).

    See Also
    --------
    shapelab.io.read_structure
        Documents every keyword.

    Examples
    --------
    >>> o = ReadOptions.checked("x.pdb", "pdb", chain="A", probe=1.4)
    >>> o.probe, o.chains_wanted, o.het_keep
    (1.4, frozenset({'A'}), True)
    >>> ReadOptions.checked("x.pdb", "pdb", chain="ABC")
    Traceback (most recent call last):
    ...
    ValueError: chain must hold strings of at most 2 characters, got 'ABC'
    """

    probe: float
    default_radius: float | None
    model: int | None
    chain: str | Collection[str] | None
    hetatm: bool | Collection[str]
    water: bool
    hydrogens: bool
    max_bytes: int
    chains_wanted: frozenset | None
    het_keep: bool | frozenset
    tables: tuple
    format: str

    @classmethod
    def checked(
        cls,
        path: str | os.PathLike[str],
        format: str,
        *,
        probe: float = 0.0,
        default_radius: float | None = None,
        model: int | None = None,
        chain: str | Collection[str] | None = None,
        hetatm: bool | Collection[str] = True,
        water: bool = False,
        hydrogens: bool = False,
        radii: Mapping | None = None,
        max_bytes: int = MAX_PDB_BYTES,
    ) -> ReadOptions:
        """The keywords of a reader checked, in the order of its signature: TypeError or
        ValueError naming the argument and the value received.

        See Also
        --------
        shapelab.io.read_structure
            What each keyword means.
        """
        if isinstance(path, (bytes, bytearray)) or not isinstance(path, (str, os.PathLike)):
            raise TypeError(f"path must be a str or os.PathLike, got {type(path).__name__}")
        chain_width, residue_width = NAME_WIDTHS[format]
        probe = as_finite_scalar(probe, "probe", nonnegative=True)
        if default_radius is not None:
            default_radius = as_finite_scalar(default_radius, "default_radius", positive=True)
        if model is not None:
            if isinstance(model, bool):
                raise TypeError("model must be an int, got bool")
            model = as_positive_int(model, "model", minimum=0)
        chains_wanted = names_arg(chain, "chain", chain_width)
        if isinstance(hetatm, (bool, np.bool_)):
            het_keep = bool(hetatm)
        else:
            het_keep = names_arg(hetatm, "hetatm", residue_width)
        for flag, fname in ((water, "water"), (hydrogens, "hydrogens")):
            if not isinstance(flag, (bool, np.bool_)):
                raise TypeError(f"{fname} must be a bool, got {type(flag).__name__}")
        tables = radius_table(radii)
        max_bytes = as_positive_int(max_bytes, "max_bytes")
        return cls(
            probe=probe,
            default_radius=default_radius,
            model=model,
            chain=chain,
            hetatm=hetatm,
            water=water,
            hydrogens=hydrogens,
            max_bytes=max_bytes,
            chains_wanted=chains_wanted,
            het_keep=het_keep,
            tables=tables,
            format=format,
        )

    def selection(self, path: str | os.PathLike[str]) -> dict:
        """The keywords of :func:`~shapelab.io._selection.kept_structure` these options
        give (the selection, the radii and the probe), for the file ``path``.

        See Also
        --------
        checked
            Makes the options.
        """
        return dict(
            tables=self.tables,
            default_radius=self.default_radius,
            probe=self.probe,
            chains_wanted=self.chains_wanted,
            het_keep=self.het_keep,
            water=self.water,
            hydrogens=self.hydrogens,
            path=path,
            chain=self.chain,
            hetatm=self.hetatm,
        )
