"""The PDB reader: ATOM and HETATM records by the format's fixed columns (Notes §23.1).

Only the fixed-column ATOM and HETATM records of the PDB format (wwPDB, *Atomic
Coordinate Entry Format Description*, v3.3) are read; nothing in a file is ever
evaluated or executed.  The records become :class:`~shapelab.io._structure.AtomRecord`
rows; which are kept (:mod:`shapelab.io._selection`) and their radii
(:mod:`shapelab.io._radii`) are decided by the rules every reader shares.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
from collections.abc import Collection, Mapping

from ._options import MAX_PDB_BYTES, ReadOptions
from ._radii import ELEMENT_SYMBOLS
from ._selection import STANDARD_RESIDUES, kept_structure
from ._source import chunks, too_large
from ._structure import AtomRecord, PDBStructure

__all__ = ["MAX_PDB_BYTES", "read_pdb", "read_pdb_with", "element_from_name"]

# two-letter guesses kept even in a polymer residue (a halogen or Se is a real atom there)
_POLYMER_TWO_LETTER = {"Se", "Cl", "Br"}


def element_from_name(name: str, residue: str | None = None) -> str:
    """Guess an element from a PDB atom name (columns 13–16).

    PDB convention: the element symbol is right-justified in columns 13–14, so
    ``" CA "`` is an alpha carbon and ``"CA  "`` is calcium.  Four-character hydrogen
    names (``"HG21"``, ``"1HG2"``) are hydrogens.  Programs such as CHARMM write
    names left-justified (``"CA  "``, ``"HE1 "``); in a polymer residue
    (:data:`STANDARD_RESIDUES`, given as ``residue``) the first letter is then the
    element, since those residues hold no calcium or helium.

    See Also
    --------
    read_pdb : uses it when columns 77–78 are blank.
    shapelab.tools.trajectory.selection_radii : uses it for MD topologies without elements.

    Examples
    --------
    >>> element_from_name(" CA "), element_from_name("CA  "), element_from_name("CA  ", "ALA")
    ('C', 'Ca', 'C')
    """
    name4 = name.ljust(4)[:4]
    first, second = name4[0], name4[1]
    if first == " " or first.isdigit():
        return second if second.isalpha() else ""
    if first.upper() == "H" and len(name4.strip()) == 4:
        return "H"
    two = (first + second).strip()
    if len(two) == 2 and two.upper() in ELEMENT_SYMBOLS:
        sym = ELEMENT_SYMBOLS[two.upper()]
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


_MAX_LINE = 2**16  # a PDB record has 80 columns; a longer "line" is not PDB text
_EOL = re.compile(rb"\r\n|\r|\n")
_BOM = b"\xef\xbb\xbf"


# the first byte of a MessagePack map (fixmap, map16, map32), as Latin-1: how a BinaryCIF
# file starts (its first line also names its dataBlocks)
_MSGPACK_MAPS = frozenset(chr(b) for b in (*range(0x80, 0x90), 0xDE, 0xDF))


def _pdb_lines(path, max_bytes: int):
    """Yield ``(line number, text)`` of a plain or gzip file, streamed.

    Lines end with LF, CRLF or CR; a UTF-8 byte-order mark before the first line is
    dropped; text is decoded as Latin-1 (one character per byte, so that the PDB's
    columns are byte columns).  At most :data:`~shapelab.io._source.CHUNK` bytes (plus one unfinished line of
    at most ``_MAX_LINE``) are held at a time, and reading stops with a ValueError as
    soon as more than ``max_bytes`` bytes have come out of the file (after
    decompression): a gzip bomb is refused after ``max_bytes``, never held whole.
    """
    name = os.fspath(path)
    lineno, pending, skip_lf = 0, b"", False
    for chunk, over in chunks(path, max_bytes):
        # when over, the lines that end within the limit are still read: END may be one
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
            raise too_large(path, max_bytes, " before its first END (or the ENDMDL of the model read)")
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
        Van der Waals radius for the elements no table lists: neither ``radii`` nor
        :data:`VDW_RADII` (Bondi 1964, Mantina et al. 2009) nor :data:`ALVAREZ_RADII`
        (Alvarez 2013, which gives the transition metals Fe, Mn, Co, Mo, ... their
        radii; the report's notes name each use).  Promethium, the elements after
        einsteinium and unknown symbols (``X``) are left.  Without it, such an element
        raises, naming the tables, the element and its line.  The order is ``radii``,
        the tables, ``default_radius``: to give a listed element another radius, pass
        ``radii={"Fe": 2.0}``.
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
        Van der Waals radii (Å) that take precedence over every table (and over
        ``default_radius``): keys are element
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
        chains, so that reports can name the residues lining a feature, and the table
        each radius came from (``radius_sources``, which a report's notes name).

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
    radius_notes
        What a report says of them.
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
      (:func:`element_from_name`).
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
    * Radii, in this order: ``radii`` by (residue, atom) name, then by element;
      Bondi (1964), or Mantina et al. (2009) for the main-group elements Bondi lacks
      (:data:`VDW_RADII`); Alvarez (2013), Table 1, for the elements neither lists
      (:data:`ALVAREZ_RADII`: Sc-Co, Y-Rh, La-Lu but Pm, Hf-Ir, Ac-Es but U); then
      ``default_radius``.  No warning is emitted: the table used is recorded per atom
      and stated in a report's notes (:func:`radius_notes`).

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
    >>> from shapelab.datasets import structure_path
    >>> s = read_pdb(structure_path("1hvr"), chain="A", hetatm={"CSO"})  # no inhibitor
    >>> len(s), s.residue_label(0), sorted(set(s.elements.tolist()))
    (757, 'A:PRO1', ['C', 'N', 'O', 'S'])
    """
    options = ReadOptions.checked(
        path,
        "pdb",
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
    return read_pdb_with(path, options)


def read_pdb_with(path: str | os.PathLike[str], options: ReadOptions) -> PDBStructure:
    """:func:`read_pdb` with its keywords already checked (the PDB branch of
    :func:`~shapelab.io.read_structure`).

    See Also
    --------
    read_pdb
        Documents the options.
    """
    model, max_bytes = options.model, options.max_bytes
    recs = []  # one tuple per ATOM/HETATM record of the model read
    target = model  # the MODEL serial wanted (None: the first one met)
    current = None  # serial of the open MODEL block (None: outside any)
    models_seen = []
    loose = None  # line of the first ATOM/HETATM record outside any MODEL block
    blank = True  # no character but whitespace seen so far
    with contextlib.closing(_pdb_lines(path, max_bytes)) as lines:  # closed at END, on error too
        for lineno, line in lines:
            if blank and line.startswith("data_"):
                raise ValueError(
                    f"line {lineno}: {os.fspath(path)!r} is an mmCIF file (it starts with a data_ block), "
                    f"not PDB: read it with shapelab.read_structure"
                )
            if lineno == 1 and line[:1] in _MSGPACK_MAPS and "dataBlocks" in line:
                raise ValueError(
                    f"line 1: {os.fspath(path)!r} is a BinaryCIF file (a MessagePack map of dataBlocks), "
                    f"not PDB: read it with shapelab.read_structure"
                )
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
                e = element_from_name(name, resname.upper())
                if not e:
                    raise ValueError(
                        f"line {lineno}: no element in columns 77-78 and none can be read from the atom name {name!r}"
                    )
            icode = line[26].strip() if len(line) > 26 else ""
            recs.append(
                AtomRecord(
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

    return kept_structure(recs, model=target if models_seen else None, **options.selection(path))
