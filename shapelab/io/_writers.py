"""Writers: 3D balls and their labels as PDB records or an mmCIF ``_atom_site`` table.

Both validate every column before anything is written and write atomically (a
temporary file beside the target, renamed over it once complete).
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

import numpy as np

from .._toolkit.validate import check_balls
from ..balls import Balls

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["write_pdb", "write_mmcif"]


def _str_column(values, n: int, name: str, width, default, fmt="PDB"):
    if values is None:
        return [default(i) for i in range(n)]
    if isinstance(values, str):
        values = [values] * n
    values = [str(v) for v in (values.tolist() if isinstance(values, np.ndarray) else values)]
    if len(values) != n:
        raise ValueError(f"{name} must have one entry per ball ({n}), got {len(values)}")
    bad = {v for v in set(values) if (width is not None and len(v) > width) or not v.isascii() or not v.isprintable()}
    if bad:
        i = next(i for i, v in enumerate(values) if v in bad)
        size = f"{width}-character " if width is not None else ""
        raise ValueError(f"{name}[{i}] = {values[i]!r} does not fit the {fmt}'s {size}printable ASCII field")
    return values


def _labels(
    balls,
    elements,
    atom_names,
    residue_names,
    residue_numbers,
    chains,
    hetero,
    insertion_codes,
    altlocs,
    b_factors,
    *,
    fmt,
    widths,
):
    """Validate the per-atom columns shared by :func:`write_pdb` and :func:`write_mmcif`."""
    check_balls(balls)
    if balls.dim != 3:
        raise ValueError(f"balls must be 3-dimensional to be written as a {fmt} file, got dim={balls.dim}")
    n = len(balls)
    if n == 0:
        raise ValueError("balls must hold at least one ball")
    elements = _str_column(elements, n, "elements", 2, None, fmt)
    for i, e in enumerate(elements):
        if not (e.isalpha() and 1 <= len(e) <= 2):
            raise ValueError(f"elements[{i}] = {e!r} is not an element symbol")
    elements = [e[0].upper() + e[1:].lower() for e in elements]
    w = widths
    atom_names = _str_column(atom_names, n, "atom_names", w["atom"], lambda i: elements[i].upper(), fmt)
    residue_names = _str_column(residue_names, n, "residue_names", w["residue"], lambda i: "UNK", fmt)
    chains = _str_column(chains, n, "chains", w["chain"], lambda i: "A", fmt)
    insertion_codes = _str_column(insertion_codes, n, "insertion_codes", 1, lambda i: "", fmt)
    altlocs = _str_column(altlocs, n, "altlocs", 1, lambda i: "", fmt)
    if residue_numbers is None:
        residue_numbers = np.arange(1, n + 1)
    residue_numbers = np.asarray(residue_numbers)
    if residue_numbers.shape != (n,) or residue_numbers.dtype.kind not in "iu":
        raise ValueError(f"residue_numbers must be {n} integers")
    hetero = np.zeros(n, bool) if hetero is None else np.asarray(hetero, dtype=bool)
    if hetero.shape != (n,):
        raise ValueError(f"hetero must have shape ({n},), got {hetero.shape}")
    if b_factors is None:
        b_factors = np.zeros(n)
    b_factors = np.asarray(b_factors, dtype=np.float64)
    if b_factors.shape != (n,):
        raise ValueError(f"b_factors must have shape ({n},), got {b_factors.shape}")
    return elements, atom_names, residue_names, residue_numbers, chains, hetero, insertion_codes, altlocs, b_factors


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _write_text(path, text: str):
    """Write ``text`` to a text stream (anything with ``write``), or to the file ``path``
    atomically: a temporary file beside it, renamed over it once complete."""
    if hasattr(path, "write"):
        path.write(text)
        return path
    out = Path(path)
    fd, tmp = tempfile.mkstemp(dir=out.parent, prefix=f".{out.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="ascii", newline="\n") as fh:
            fh.write(text)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp's files are private; a written file is not
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return out


def write_pdb(
    path: str | os.PathLike[str] | TextIO,
    balls: Balls,
    elements: str | Sequence[str] | np.ndarray,
    *,
    atom_names: str | Sequence[str] | np.ndarray | None = None,
    residue_names: str | Sequence[str] | np.ndarray | None = None,
    residue_numbers: ArrayLike | None = None,
    chains: str | Sequence[str] | np.ndarray | None = None,
    hetero: ArrayLike | None = None,
    title: str | None = None,
    b_factors: ArrayLike | None = None,
    insertion_codes: str | Sequence[str] | np.ndarray | None = None,
    altlocs: str | Sequence[str] | np.ndarray | None = None,
) -> Path | TextIO:
    """Write 3D balls as ATOM/HETATM records of a PDB file.

    The PDB format stores no radii: :func:`read_pdb` recovers them from the elements,
    so a round trip preserves radii exactly when they are the radii of :data:`VDW_RADII` or
    :data:`ALVAREZ_RADII` (plus one probe).
    Coordinates are written with three decimals (the format's precision, 0.001 Å).
    The format's fixed columns limit what it holds (at most 99,999 atoms, residue
    names of three characters, B-factors below 1000); :func:`write_mmcif` holds any
    number of atoms and names of any length.

    Parameters
    ----------
    path : str, os.PathLike or text stream
        A file, written atomically (a temporary file beside it renamed over it once
        complete, so a failed write leaves no partial file), or an open text stream.
    balls : Balls
        3D balls; every coordinate must lie in (-1000, 10000) to fit columns 31–54.
    elements : sequence of str or str
        Element symbols (one per ball, or one for all).
    atom_names, residue_names, chains : sequence of str, optional
        At most 4, 3 and 2 characters (chains fill columns 21–22, as
        :func:`read_pdb` reads them).  Default: the element symbol, ``"UNK"``, ``"A"``.
    residue_numbers : sequence of int, optional
        Default: 1, 2, ..., n (one residue per atom).
    hetero : sequence of bool, optional
        True writes HETATM instead of ATOM.
    title : str, optional
        Written as a TITLE record (at most 70 characters).
    b_factors : sequence of float, optional
        Values for the B-factor column (61–66), e.g. a label per atom as
        :func:`shapelab.report` writes; each must fit ``%6.2f``.  Default 0.
    insertion_codes, altlocs : sequence of str, optional
        Columns 27 and 17 (one character or ``""``).  Default blank.

    Returns
    -------
    pathlib.Path or the stream

    Raises
    ------
    ValueError
        What the format cannot hold (the message names the argument), before
        anything is written.

    See Also
    --------
    write_mmcif : the same atoms as an mmCIF ``_atom_site`` table, without limits.
    read_pdb : reads the file back.

    References
    ----------
    wwPDB, *Atomic Coordinate Entry Format Description*, v3.3, ATOM record.

    Examples
    --------
    >>> import tempfile
    >>> from shapelab.io import read_pdb
    >>> with tempfile.TemporaryDirectory() as d:  # removed with what was written in it
    ...     out = write_pdb(Path(d) / "co.pdb", Balls([[0.0, 0.0, 0.0], [1.2, 0.0, 0.0]], 1.5), ["C", "O"])
    ...     s = read_pdb(out)
    >>> len(s), s.balls.radii.tolist()  # the radii come back from the elements
    (2, [1.7, 1.52])
    """
    widths = {"atom": 4, "residue": 3, "chain": 2}
    cols = _labels(
        balls,
        elements,
        atom_names,
        residue_names,
        residue_numbers,
        chains,
        hetero,
        insertion_codes,
        altlocs,
        b_factors,
        fmt="PDB",
        widths=widths,
    )
    elements, atom_names, residue_names, residue_numbers, chains, hetero, insertion_codes, altlocs, b_factors = cols
    n = len(balls)
    if n > 99999:
        raise ValueError(f"the PDB format holds at most 99999 atoms, got {n}")
    c = balls.centers
    if np.any(c <= -999.9995) or np.any(c >= 9999.9995):
        raise ValueError("balls.centers must lie in (-1000, 10000) to fit the PDB's coordinate columns")
    if np.any(residue_numbers < -999) or np.any(residue_numbers > 9999):
        raise ValueError("residue_numbers must lie in [-999, 9999] to fit columns 23-26")
    if not np.all(np.isfinite(b_factors)) or np.any(b_factors <= -99.995) or np.any(b_factors >= 999.995):
        raise ValueError("b_factors must be finite and lie in (-100, 1000) to fit columns 61-66")

    lines = []
    if title is not None:
        t = str(title)
        if len(t) > 70 or not t.isascii() or not t.isprintable():
            raise ValueError("title must be at most 70 printable ASCII characters on one line")
        lines.append(f"TITLE     {t}")
    for i in range(n):
        name = atom_names[i]
        # element symbols right-justified in columns 13-14 (PDB convention)
        if len(name) < 4 and len(elements[i]) == 1:
            name = " " + name
        rec = "HETATM" if hetero[i] else "ATOM"
        lines.append(
            f"{rec:<6}{(i + 1) % 100000:>5} {name:<4}{altlocs[i]:1}{residue_names[i]:>3}{chains[i]:>2}"
            f"{int(residue_numbers[i]):>4}{insertion_codes[i]:1}   {c[i, 0]:8.3f}{c[i, 1]:8.3f}{c[i, 2]:8.3f}"
            f"{1.0:6.2f}{b_factors[i]:6.2f}          {elements[i].upper():>2}"
        )
    lines.append("END")
    return _write_text(path, "\n".join(lines) + "\n")


# ------------------------------------------------------------------------ mmCIF
_CIF_RESERVED = ("data_", "save_", "loop_", "stop_", "global_")


def _cif_token(s: str) -> str:
    """One printable-ASCII value as a CIF 1.1 token: bare when it can be, else quoted
    (``""`` is written ``.``, CIF's "inapplicable", which mmCIF readers read as empty)."""
    if s == "":
        return "."
    if (
        not any(c.isspace() for c in s)
        and s[0] not in "_#$'\"[];"
        and s not in (".", "?")
        and not s.lower().startswith(_CIF_RESERVED)
    ):
        return s
    for q in ("'", '"'):
        # inside quotes, the quote character may appear unless whitespace follows it
        if not any(s[k] == q and (k + 1 == len(s) or s[k + 1].isspace()) for k in range(len(s))):
            return f"{q}{s}{q}"
    return f"\n;{s}\n;\n"  # a text field holds anything on one line


def _cif_floats(a) -> list:
    """Each value as the shortest text that reads back to the same double; NaN as ``?``."""
    return [repr(v) if v == v else "?" for v in np.asarray(a, dtype=np.float64).tolist()]


def _cif_tokens(values) -> list:
    tok = {v: _cif_token(v) for v in set(values)}  # few distinct labels: quote each once
    return [tok[v] for v in values]


def write_mmcif(
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
    insertion_codes=None,
    altlocs=None,
    occupancies=None,
    extra=None,
    name="shapelab",
):
    """Write 3D balls as the ``_atom_site`` table of an mmCIF file.

    mmCIF (PDBx/mmCIF, the wwPDB's archive format since 2014) is a table of
    whitespace-separated values with no fixed widths: any number of atoms, residue
    names and chain identifiers of any length, and B-factors of any size fit, which
    the PDB's fixed columns cannot (see :func:`write_pdb`).  Values are written as
    CIF 1.1 tokens (quoted where a value has spaces or starts like a CIF keyword),
    coordinates and B-factors as the shortest decimal that reads back to the same
    double, so a round trip through a reader such as gemmi is exact.  Radii are not
    stored (Notes §23.1: they come from the elements).

    Parameters
    ----------
    path : str, os.PathLike or text stream
        A file, written atomically (temporary file renamed once complete), or an
        open text stream.
    balls : Balls
        3D balls: their centres are ``Cartn_x/y/z``.
    elements : sequence of str or str
        Element symbols (``type_symbol``), one per ball or one for all.
    atom_names, residue_names, chains : sequence of str, optional
        ``label_``/``auth_atom_id``, ``label_``/``auth_comp_id`` and
        ``label_``/``auth_asym_id``: printable ASCII of any length (``""`` is
        written ``.``).  Default: the element symbol, ``"UNK"``, ``"A"``.
    residue_numbers : sequence of int, optional
        ``auth_seq_id``.  Default 1, 2, ..., n.
    hetero : sequence of bool, optional
        ``group_PDB`` HETATM instead of ATOM.
    title : str, optional
        ``_struct.title``.
    b_factors, occupancies : sequence of float, optional
        ``B_iso_or_equiv`` (default 0) and ``occupancy`` (default 1); NaN is
        written ``?`` (unknown).
    insertion_codes, altlocs : sequence of str, optional
        ``pdbx_PDB_ins_code`` and ``label_alt_id`` (one character or ``""``).
    extra : mapping of str to sequence of str, optional
        More ``_atom_site`` items, one value per atom, e.g.
        ``{"shapelab_feature_ids": [...]}`` (names of letters, digits and ``_``).
    name : str, default ``"shapelab"``
        The data block's name (``data_<name>``; characters other than letters,
        digits, ``-``, ``.`` and ``_`` become ``_``).

    Returns
    -------
    pathlib.Path or the stream

    Raises
    ------
    ValueError
        A label that is not printable ASCII, a column of the wrong length, or
        non-finite coordinates, before anything is written.

    See Also
    --------
    write_pdb : the PDB format, for tools that read nothing else.

    References
    ----------
    wwPDB, *PDBx/mmCIF dictionary*, category ``atom_site``; S. R. Hall, F. H. Allen
    and I. D. Brown, "The Crystallographic Information File (CIF)", *Acta Cryst.*
    A47 (1991) 655–685 (the CIF 1.1 syntax).

    Examples
    --------
    >>> import io
    >>> buf = write_mmcif(io.StringIO(), Balls([[0.0, 1.5, -2.25]], 1.7), "C", residue_names="TIP3")
    >>> print(buf.getvalue().splitlines()[-2])
    ATOM 1 C C . TIP3 A . . ? 0.0 1.5 -2.25 1.0 0.0 1 TIP3 A C 1
    """
    widths = {"atom": None, "residue": None, "chain": None}
    cols = _labels(
        balls,
        elements,
        atom_names,
        residue_names,
        residue_numbers,
        chains,
        hetero,
        insertion_codes,
        altlocs,
        b_factors,
        fmt="mmCIF",
        widths=widths,
    )
    elements, atom_names, residue_names, residue_numbers, chains, hetero, insertion_codes, altlocs, b_factors = cols
    n = len(balls)
    occupancies = np.ones(n) if occupancies is None else np.asarray(occupancies, dtype=np.float64)
    if occupancies.shape != (n,):
        raise ValueError(f"occupancies must have shape ({n},), got {occupancies.shape}")
    if np.any(np.isinf(b_factors)) or np.any(np.isinf(occupancies)):
        raise ValueError("b_factors and occupancies must be finite (or NaN for unknown)")
    extra = {} if extra is None else dict(extra)
    extra_cols = []
    for key, values in extra.items():
        if not (isinstance(key, str) and key and key.replace("_", "a").isalnum() and key.isascii()):
            raise ValueError(f"extra item names must be letters, digits and '_', got {key!r}")
        extra_cols.append((key, _cif_tokens(_str_column(values, n, f"extra[{key!r}]", None, None, "mmCIF"))))
    block = re.sub(r"[^A-Za-z0-9_.-]", "_", str(name)) or "shapelab"
    lines = [f"data_{block}", f"_entry.id {_cif_token(block)}"]
    if title is not None:
        t = str(title)
        if not t.isascii() or not t.isprintable():
            raise ValueError("title must be printable ASCII on one line")
        lines.append(f"_struct.entry_id {_cif_token(block)}")
        lines.append(f"_struct.title {_cif_token(t)}")
    items = (
        "group_PDB id type_symbol label_atom_id label_alt_id label_comp_id label_asym_id label_entity_id "
        "label_seq_id pdbx_PDB_ins_code Cartn_x Cartn_y Cartn_z occupancy B_iso_or_equiv auth_seq_id "
        "auth_comp_id auth_asym_id auth_atom_id pdbx_PDB_model_num"
    ).split() + [k for k, _ in extra_cols]
    lines.append("#")
    lines.append("loop_")
    lines.extend(f"_atom_site.{it}" for it in items)
    names, resn, chain = _cif_tokens(atom_names), _cif_tokens(residue_names), _cif_tokens(chains)
    alt = _cif_tokens(altlocs)
    icode = ["?" if t == "." else t for t in _cif_tokens(insertion_codes)]
    xyz = [_cif_floats(balls.centers[:, k]) for k in range(3)]
    occ, bf = _cif_floats(occupancies), _cif_floats(b_factors)
    group = ["HETATM" if h else "ATOM" for h in hetero.tolist()]
    num = [str(v) for v in residue_numbers.tolist()]
    extras = [vals for _, vals in extra_cols]
    for i in range(n):
        row = [group[i], str(i + 1), elements[i], names[i], alt[i], resn[i], chain[i], ".", ".", icode[i]]
        row += [xyz[0][i], xyz[1][i], xyz[2][i], occ[i], bf[i], num[i], resn[i], chain[i], names[i], "1"]
        row += [vals[i] for vals in extras]
        lines.append(" ".join(row))
    lines.append("#")
    return _write_text(path, "\n".join(lines) + "\n")
