"""One entry point for the formats the PDB distributes: :func:`read_structure`
(Notes §23.1).

The format is recognised from the file's first bytes (after gzip decompression),
the extension deciding only what the content leaves open; the PDB branch is
:func:`~shapelab.io.read_pdb`, the mmCIF branch :func:`~shapelab.io._mmcif.read_mmcif`
(gemmi's CIF parser), the BinaryCIF branch :func:`~shapelab.io._bcif.read_bcif`
(biotite's BinaryCIF decoder, optional), and all three feed the same selection and radii.
"""

from __future__ import annotations

import gzip
import os
import zlib
from collections.abc import Collection, Mapping

from ._bcif import read_bcif
from ._mmcif import read_mmcif
from ._options import MAX_PDB_BYTES, ReadOptions
from ._pdb import read_pdb_with
from ._structure import PDBStructure

__all__ = ["read_structure", "detect_format", "FORMATS"]

#: The values of ``format=``: what :func:`read_structure` can be told a file is.
FORMATS = ("pdb", "mmcif", "bcif")

_SNIFF = 2**16  # bytes looked at (after decompression) to recognise a format
_MMCIF_SUFFIXES = (".cif", ".mmcif", ".mcif")
_BCIF_SUFFIXES = (".bcif",)


def _head(path) -> bytes:
    """The first bytes of the file, decompressed if it is gzip (b"" if unreadable gzip:
    the reader then names the error)."""
    with open(path, "rb") as raw:
        start = raw.read(2)
        raw.seek(0)
        if start != b"\x1f\x8b":
            return raw.read(_SNIFF)
        try:
            with gzip.GzipFile(fileobj=raw, mode="rb") as fh:
                return fh.read(_SNIFF)
        except (OSError, EOFError, zlib.error):
            return b""


def _by_extension(path) -> str:
    name = os.fspath(path).lower()
    if name.endswith(".gz"):
        name = name[:-3]
    if name.endswith(_MMCIF_SUFFIXES):
        return "mmcif"
    if name.endswith(_BCIF_SUFFIXES):
        return "bcif"
    return "pdb"


def detect_format(path) -> str:
    """``"pdb"``, ``"mmcif"`` or ``"bcif"``: what :func:`read_structure` reads ``path`` as.

    By content first (after gzip decompression and a UTF-8 byte-order mark): a
    MessagePack map holding ``dataBlocks`` is BinaryCIF; text whose first token,
    after blank and ``#`` comment lines, starts with ``data_`` is mmCIF; other
    non-blank content is PDB, unless the name ends in ``.bcif`` (or ``.bcif.gz``):
    then the BinaryCIF reader says what is wrong with it.  A file with no content to go by (empty, blank, an
    unreadable gzip stream) is named by its extension (``.cif``, ``.mmcif``,
    ``.mcif`` -> mmCIF; ``.bcif`` -> BinaryCIF; anything else -> PDB, each with an
    optional ``.gz``), so that its reader reports what is wrong with it.

    See Also
    --------
    read_structure
        Reads the file by this answer (or by its ``format=``).

    References
    ----------
    .. [1] wwPDB, *PDBx/mmCIF Dictionary*, https://mmcif.wwpdb.org (the ``data_``
       block of an mmCIF file).
    .. [2] D. Sehnal, S. Bittrich, S. Velankar, J. Koča, R. Svobodová, S. K. Burley
       and A. S. Rose, "BinaryCIF and CIFTools -- Lightweight, efficient and extensible
       macromolecular data management", *PLoS Comput. Biol.* **16**(10), e1008247
       (2020), doi:10.1371/journal.pcbi.1008247.

    Examples
    --------
    >>> from shapelab.datasets import structure_path
    >>> detect_format(structure_path("1hvr"))
    'pdb'
    """
    head = _head(path)
    if head[:1] and (0x80 <= head[0] <= 0x8F or head[0] in (0xDE, 0xDF)) and b"dataBlocks" in head:
        return "bcif"
    if head.startswith(b"\xef\xbb\xbf"):
        head = head[3:]
    for line in head.splitlines():
        token = line.strip()
        if not token or token.startswith(b"#"):
            continue
        if token[:5].lower() == b"data_":
            return "mmcif"
        # neither BinaryCIF nor mmCIF by content: PDB, unless the name says BinaryCIF (a
        # damaged .bcif is then reported as BinaryCIF, not as a PDB file without atoms)
        return "bcif" if _by_extension(path) == "bcif" else "pdb"
    return _by_extension(path)


def read_structure(
    path: str | os.PathLike[str],
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
    format: str | None = None,
) -> PDBStructure:
    """Read the atoms of a PDB, mmCIF or BinaryCIF file as balls (Notes §23.1: a
    molecule is a union of balls).

    One entry point for what the PDB distributes: PDB files (plain or gzip, hybrid-36
    residue numbers past 9999), read by :func:`read_pdb`'s strict fixed-column
    parser; PDBx/mmCIF files (plain or gzip), the PDB's archive format since 2014
    and the only one for entries of more than 99,999 atoms or 62 chains, parsed by
    gemmi; and BinaryCIF files (plain or gzip), the same categories and columns
    encoded as MessagePack, which the RCSB and PDBe serve, decoded by biotite (an
    optional dependency: ``pip install "shapelab[bcif]"``).  All three give
    :class:`~shapelab.io._structure.AtomRecord` rows to the same selection (model,
    chains, HETATM, water, hydrogens, alternate locations) and the same radii, so one
    entry read from any format gives the same balls.

    Parameters
    ----------
    path : str or os.PathLike
        The file.  Its format is recognised by its content (see
        :func:`detect_format`): gzip by its first two bytes; then mmCIF by a first
        token ``data_...``, BinaryCIF by a MessagePack map holding ``dataBlocks``,
        anything else as PDB (as BinaryCIF if named ``.bcif``, so that a damaged
        BinaryCIF file is reported as one).  Otherwise the extension (``.cif``,
        ``.mmcif``, ``.bcif``, optionally ``.gz``) decides only for a file whose
        content says nothing (empty or blank).
    probe, default_radius, hetatm, water, hydrogens, radii, max_bytes
        As in :func:`read_pdb`.  For mmCIF and BinaryCIF, ``max_bytes`` bounds the
        whole (decompressed) file, which is held in memory while it is parsed (for
        BinaryCIF, also the ``atom_site`` row count times 8 bytes: one decoded
        column), and ``hetatm`` names may have up to 5 characters (the wwPDB's extended CCD
        identifiers).
    model : int, optional
        The model read: the MODEL serial of a PDB file, ``pdbx_PDB_model_num`` of an
        mmCIF or BinaryCIF one.  Default: the first model in the file.
    chain : str or collection of str, optional
        Keep only these chains: columns 21–22 of a PDB file, ``auth_asym_id``
        (up to 4 characters) of an mmCIF or BinaryCIF file.
    format : {None, "pdb", "mmcif", "bcif"}, optional
        Force a reader instead of recognising the format.

    Returns
    -------
    PDBStructure
        The atoms of the model read, in file order.  For mmCIF and BinaryCIF,
        ``model`` is the ``pdbx_PDB_model_num`` read (1 if the table has no such
        column).

    Raises
    ------
    ValueError
        Everything :func:`read_pdb` raises for a PDB file.  For mmCIF: an empty
        file; a CIF syntax error, such as a loop whose values do not fill its last
        row (``"line N: ..."``, gemmi's line); no ``_atom_site`` table, or none of
        its ``Cartn_x``, ``Cartn_y``, ``Cartn_z``, ``type_symbol``, atom, residue,
        chain or residue-number columns; a value that is not what its item needs
        (a coordinate that is not a number or is ``?``, a residue number that is not
        an integer, ``group_PDB`` other than ATOM or HETATM, ...), named as
        ``"_atom_site row N (id I), _atom_site.ITEM"``; an absent model.  For
        BinaryCIF: an empty file, an unreadable gzip stream, bytes that are not a
        MessagePack map of ``dataBlocks``, no ``atom_site`` category or a required
        column missing (as for mmCIF), a column that cannot be decoded (or whose
        mask holds a value other than 0, 1 for ``.``, 2 for ``?``) or whose
        length is not the category's row count (``"atom_site.ITEM (data block
        B)"``), a run-length or integer-packing step declaring more values than the
        rows allow or a string table whose longest string times the rows passes
        ``max_bytes`` (refused before anything is decoded: a few bytes could
        otherwise ask for gigabytes), and the same per-value errors as mmCIF, named
        as ``"atom_site row N (id I), atom_site.ITEM"``.  Every message names the file.  Nothing is
        returned in part: any error in the model read fails the whole call.
    ImportError
        A BinaryCIF file when biotite is not installed; the message says
        ``pip install "shapelab[bcif]"``.
    FileNotFoundError, IsADirectoryError
        If ``path`` cannot be opened.

    See Also
    --------
    read_pdb
        The PDB branch, and the full account of the selection and the radii.
    detect_format
        How the format is recognised.
    write_mmcif, write_pdb
        The writers; :func:`write_mmcif`'s output reads back through this function.
    gemmi.read_structure
        gemmi's own reader of both formats (it builds a model hierarchy; here only
        gemmi's CIF parser is used, and the ``_atom_site`` table is read by the
        rules above).
    biotite.structure.io.pdbx.BinaryCIFFile
        biotite's BinaryCIF file, whose per-column decoding the BinaryCIF branch uses
        (``biotite.structure.io.pdbx.get_structure`` builds biotite's own atom
        array; here the ``atom_site`` columns are read by the rules above).

    Notes
    -----
    * **auth, not label.**  mmCIF gives every atom two sets of identifiers: the
      ``label_*`` ones of the PDBx/mmCIF dictionary (``label_asym_id`` names one
      entity instance, so a chain's waters and ligands each get their own;
      ``label_seq_id`` is ``.`` outside polymers) and the ``auth_*`` ones the authors
      gave, which are what PDB files, the RCSB and PDBe pages and most programs
      show.  Chains are ``auth_asym_id``, residue numbers ``auth_seq_id`` with the
      insertion code ``pdbx_PDB_ins_code``, residue and atom names ``auth_comp_id``
      and ``auth_atom_id``; a ``label_*`` column is used only when the ``auth_*``
      one is absent.  So an entry read from its PDB and its mmCIF file gives the
      same labels.
    * The element is ``type_symbol`` (required; no guessing from the atom name,
      whose alignment means nothing in mmCIF); the alternate location is
      ``label_alt_id``; ``group_PDB`` HETATM marks hetero atoms (ATOM if the column
      is absent); ``occupancy`` and ``B_iso_or_equiv`` are NaN if absent or ``?``.
      A number may carry a standard uncertainty (``12.345(6)``), which is dropped.
    * The first data block holding ``_atom_site`` is read.  gemmi reports no line
      for a loop's values, so errors name the row (1-based, in file order) and its
      ``_atom_site.id``; :attr:`AtomRecord.line` is that row.
    * A file cut short inside a row is a CIF syntax error; one cut exactly at the
      end of a row is indistinguishable from a shorter table (as a PDB file cut
      before its ``END``).
    * BinaryCIF (``.bcif``, the MessagePack encoding of mmCIF [4]_ that the RCSB's
      ModelServer and PDBe serve) holds the same ``atom_site`` columns as typed,
      encoded arrays (delta, run-length, integer packing, fixed point, string
      tables); biotite [5]_ decodes each column (gemmi 0.7.5 has no BinaryCIF
      reader), and the columns are read by the same rules: a ``.`` or ``?`` value is
      the column's mask, and coordinates come out at the file's precision (its
      fixed-point factor, usually 1000: the same floats as the text mmCIF's).

    References
    ----------
    .. [1] M. Wojdyr, "GEMMI: A library for structural biology", *Journal of Open
       Source Software* **7**(73), 4200 (2022), doi:10.21105/joss.04200.
    .. [2] wwPDB, *PDBx/mmCIF Dictionary* (mmcif_pdbx_v50.dic), category
       ``atom_site``, https://mmcif.wwpdb.org.
    .. [3] J. D. Westbrook and P. M. D. Fitzgerald, "The PDB format, mmCIF formats,
       and other data formats", in *Structural Bioinformatics*, P. E. Bourne and
       H. Weissig (eds.), Wiley (2003).
    .. [4] D. Sehnal, S. Bittrich, S. Velankar, J. Koča, R. Svobodová, S. K. Burley
       and A. S. Rose, "BinaryCIF and CIFTools -- Lightweight, efficient and extensible
       macromolecular data management", *PLoS Comput. Biol.* **16**(10), e1008247
       (2020), doi:10.1371/journal.pcbi.1008247.
    .. [5] P. Kunzmann and K. Hamacher, "Biotite: a unifying open source computational
       biology framework in Python", *BMC Bioinformatics* **19**, 346 (2018),
       doi:10.1186/s12859-018-2367-z.

    Examples
    --------
    >>> import os, tempfile
    >>> from shapelab.datasets import structure_path
    >>> from shapelab.io import read_pdb, write_mmcif
    >>> s = read_structure(structure_path("1hvr"), chain="A", hetatm={"CSO"})  # PDB
    >>> tmp = tempfile.TemporaryDirectory()  # removed at the end
    >>> path = os.path.join(tmp.name, "1hvr_A.cif")
    >>> _ = write_mmcif(path, s.balls, s.elements, atom_names=s.atom_names,
    ...                 residue_names=s.residue_names, residue_numbers=s.residue_numbers,
    ...                 chains=s.chains, hetero=s.hetero)
    >>> detect_format(path)
    'mmcif'
    >>> t = read_structure(path)
    >>> len(t), t.residue_label(0), bool((t.balls.centers == s.balls.centers).all())
    (757, 'A:PRO1', True)
    >>> tmp.cleanup()
    """
    if isinstance(path, (bytes, bytearray)) or not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or os.PathLike, got {type(path).__name__}")
    if format is None:
        fmt = detect_format(path)
    elif isinstance(format, str) and format.lower() in FORMATS:
        fmt = format.lower()
    else:
        raise ValueError(f"format must be None or one of {FORMATS}, got {format!r}")
    reader = {"pdb": read_pdb_with, "mmcif": read_mmcif, "bcif": read_bcif}[fmt]
    try:
        options = ReadOptions.checked(
            path,
            fmt,
            probe=probe,
            default_radius=default_radius,
            model=model,
            chain=chain,
            hetatm=hetatm,
            water=water,
            hydrogens=hydrogens,
            radii=radii,
            max_bytes=max_bytes,
        )
        return reader(path, options)
    except ValueError as e:  # every message names the file ("line N: ..." of read_pdb too)
        name = os.fspath(path)
        if name in str(e):
            raise
        raise ValueError(f"{name!r}: {e}") from None
