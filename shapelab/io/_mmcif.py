"""The mmCIF reader: the ``_atom_site`` table of a PDBx/mmCIF file, parsed by gemmi
(Notes §23.1).

gemmi's CIF parser (:func:`gemmi.cif.read_string`) turns the text into a document;
the ``_atom_site`` table of its data block is read here, column by column, into
:class:`~shapelab.io._structure.AtomRecord` rows, which then go through the same
selection (:mod:`shapelab.io._selection`) and radii (:mod:`shapelab.io._radii`) as
the PDB reader's.  BinaryCIF, which gemmi 0.7.5 does not read, has its own reader
(:mod:`shapelab.io._bcif`, biotite's decoder) that follows the same rules.
"""

from __future__ import annotations

import math
import os
import re
from typing import Any

import numpy as np

from ._options import NAME_WIDTHS, ReadOptions
from ._selection import kept_structure
from ._source import chunks, too_large
from ._structure import AtomRecord, PDBStructure

__all__ = [
    "read_mmcif",
    "read_limited",
    "REQUIRED_ITEMS",
    "MMCIF_CHAIN_WIDTH",
    "MMCIF_RESIDUE_WIDTH",
]

#: Widest ``chain=`` name accepted for mmCIF (``auth_asym_id`` of the PDB's large
#: entries reaches 4 characters) and widest ``hetatm=`` residue name (the wwPDB's
#: extended 5-character CCD identifiers).
MMCIF_CHAIN_WIDTH, MMCIF_RESIDUE_WIDTH = NAME_WIDTHS["mmcif"]

_INT = re.compile(r"[+-]?[0-9]+")
# a CIF number: optional sign, digits with an optional point, optional exponent, and an
# optional standard uncertainty in parentheses (``12.345(6)``), which is dropped
_NUMBER = re.compile(r"([+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)(?:\([0-9]+\))?")

# the _atom_site items a table must have: each coordinate, the element, and for the atom,
# residue, chain and residue number the auth_ item the PDB's own tools show or, in a file
# without it, the label_ item (the BinaryCIF reader, shapelab.io._bcif, requires the same)
REQUIRED_ITEMS = (
    ("Cartn_x",),
    ("Cartn_y",),
    ("Cartn_z",),
    ("type_symbol",),
    ("auth_atom_id", "label_atom_id"),
    ("auth_comp_id", "label_comp_id"),
    ("auth_asym_id", "label_asym_id"),
    ("auth_seq_id", "label_seq_id"),
)


def read_limited(path, max_bytes: int) -> bytes:
    """The bytes of a plain or gzip file (recognised by its first two bytes), refused
    with a ValueError as soon as more than ``max_bytes`` have come out of it (after
    decompression): a gzip bomb is never held whole."""
    parts = []
    for chunk, over in chunks(path, max_bytes):
        if over:
            raise too_large(path, max_bytes)
        parts.append(chunk)
    return b"".join(parts)


def _text(cif, v: str) -> str:
    """A CIF value as text: quotes removed, ``?`` and ``.`` (unknown, inapplicable) -> ``""``."""
    return "" if cif.is_null(v) else cif.as_string(v)


def _where(name: str, row: int, ident: str, item: str) -> str:
    at = f" (id {ident})" if ident else ""
    return f"{name!r}: _atom_site row {row}{at}, _atom_site.{item}"


def _number(cif, v: str, name, row, ident, item, *, required: bool) -> float:
    if cif.is_null(v):
        if required:
            raise ValueError(f"{_where(name, row, ident, item)} is {v!r} (unknown): a number is required")
        return math.nan
    t = cif.as_string(v)
    m = _NUMBER.fullmatch(t)
    if m is None:
        raise ValueError(f"{_where(name, row, ident, item)} is not a number: {t!r}")
    x = float(m.group(1))
    if not math.isfinite(x):
        raise ValueError(f"{_where(name, row, ident, item)} must be finite, got {t!r}")
    return x


def _integer(cif, v: str, name, row, ident, item) -> int:
    t = "" if cif.is_null(v) else cif.as_string(v)
    if not _INT.fullmatch(t):
        raise ValueError(f"{_where(name, row, ident, item)} is not an integer: {v!r}")
    return int(t)


def _label(cif, v: str, name, row, ident, item) -> str:
    t = _text(cif, v)
    if not (t.isascii() and t.isprintable()):
        raise ValueError(f"{_where(name, row, ident, item)} is not printable ASCII: {t!r}")
    return t


# a whole column of plain numbers (no quotes, nulls or uncertainties): checked by one
# regular-expression match, converted by numpy; anything else takes the per-value path
_PLAIN = r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_PLAIN_COLUMN = re.compile(rf"{_PLAIN}(?:\n{_PLAIN})*")
_INT_COLUMN = re.compile(r"[+-]?[0-9]+(?:\n[+-]?[0-9]+)*")


class _Rows:
    """The rows read of the ``_atom_site`` table: their positions and how errors name them."""

    def __init__(self, cif, name, rows, ids):
        self.cif, self.name, self.rows, self.ids = cif, name, rows, ids

    def ident(self, i):
        return "" if self.ids is None else _text(self.cif, self.ids[i])

    def numbers(self, col, item, *, required):
        vals = [col[i] for i in self.rows]
        if vals and _PLAIN_COLUMN.fullmatch("\n".join(vals)):
            out = np.array(vals, dtype=np.float64)
            if np.isfinite(out).all():
                return out.tolist()
        return [_number(self.cif, col[i], self.name, i + 1, self.ident(i), item, required=required) for i in self.rows]

    def integers(self, col, item):
        vals = [col[i] for i in self.rows]
        if vals and _INT_COLUMN.fullmatch("\n".join(vals)):
            return [int(v) for v in vals]
        return [_integer(self.cif, col[i], self.name, i + 1, self.ident(i), item) for i in self.rows]

    def labels(self, col, item):
        cif = self.cif
        vals = [
            "" if v in ("?", ".") else (cif.as_string(v) if v[:1] in ("'", '"', ";") else v)
            for v in (col[i] for i in self.rows)
        ]
        joined = "".join(vals)
        if not (joined.isascii() and joined.isprintable()):
            for i in self.rows:
                _label(cif, col[i], self.name, i + 1, self.ident(i), item)
        return vals


def _parse(path, text: str):
    """gemmi's document of ``text``; its errors name the file and the line."""
    import gemmi

    try:
        return gemmi.cif.read_string(text)
    except (ValueError, RuntimeError) as e:
        msg = str(e)
        m = re.match(r"string:(\d+):(?:\d+\(\d+\):)?", msg)  # line:column(offset):
        if m:
            msg = f"line {m.group(1)}: {msg[m.end() :].strip()}"
        raise ValueError(f"{os.fspath(path)!r} is not a readable mmCIF file: {msg}") from None


def atom_records(rows, c: dict, where, shown) -> list:
    """The :class:`AtomRecord` rows of the ``_atom_site`` rows ``rows``, from columns already
    read (``c``: lists aligned with ``rows`` under the keys group, alt, atom, atom_item, resn,
    chain, num, icode, x, y, z, occ, b, elem), after the checks both CIF readers make: the
    group is ATOM or HETATM, every atom has a name, the type symbol is an element symbol
    (normalised once per distinct symbol).  ``where(item, i)`` names row ``i``'s item in an
    error and ``shown(item, i, k)`` the value it shows (the text mmCIF shows the raw value,
    BinaryCIF the decoded one); ``i`` counts from 0 in the file, ``k`` in ``rows``."""
    group, atom, elem = c["group"], c["atom"], c["elem"]
    symbols = {}  # each distinct type_symbol checked and normalised once
    for k, i in enumerate(rows):
        if group[k] not in ("ATOM", "HETATM"):
            raise ValueError(f"{where('group_PDB', i)} is neither ATOM nor HETATM: {shown('group_PDB', i, k)}")
        if not atom[k]:
            raise ValueError(f"{where(c['atom_item'], i)} is {shown(c['atom_item'], i, k)}: every atom needs a name")
        e = elem[k]
        if e not in symbols:
            if not (e.isascii() and e.isalpha() and len(e) <= 2):
                raise ValueError(f"{where('type_symbol', i)} is not an element symbol: {shown('type_symbol', i, k)}")
            symbols[e] = e[0].upper() + e[1:].lower()
    return [
        AtomRecord(
            int(i) + 1,
            group[k] == "HETATM",
            c["alt"][k],
            atom[k],
            c["resn"][k],
            c["chain"][k],
            c["num"][k],
            c["icode"][k],
            c["x"][k],
            c["y"][k],
            c["z"][k],
            c["occ"][k],
            c["b"][k],
            symbols[elem[k]],
        )
        for k, i in enumerate(rows)
    ]


def read_mmcif(path: str | os.PathLike[str], options: ReadOptions | None = None, **keywords: Any) -> PDBStructure:
    """Read the ``_atom_site`` table of an mmCIF file (plain or gzip) as balls.

    The options are those of :func:`~shapelab.io.read_structure`, which documents
    them; this is its mmCIF branch.  Give them checked (``options``, a
    :class:`~shapelab.io.ReadOptions`) or as keywords.
    """
    if options is None:
        options = ReadOptions.checked(path, "mmcif", **keywords)
    elif keywords:
        raise TypeError(f"give the options or keywords, not both (got {sorted(keywords)})")
    model, max_bytes = options.model, options.max_bytes

    import gemmi

    cif = gemmi.cif
    name = os.fspath(path)
    data = read_limited(path, max_bytes)
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    if not data.strip():
        raise ValueError(f"{name!r} is empty: no data block and no _atom_site table")
    if data[:1] and (0x80 <= data[0] <= 0x8F or data[0] in (0xDE, 0xDF)) and b"dataBlocks" in data[: 2**16]:
        raise ValueError(
            f"{name!r} is a BinaryCIF file (a MessagePack map of dataBlocks), not mmCIF text: "
            f"read it with shapelab.read_structure (format=None or 'bcif')"
        )
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data[: e.start].count(b"\n") + 1
        raise ValueError(f"{name!r}: line {line}: byte 0x{data[e.start]:02x} is not UTF-8 text") from None
    doc = _parse(path, text)
    blocks = [b for b in doc if b.find_mmcif_category("_atom_site.")]
    if not blocks:
        raise ValueError(f"{name!r} has no _atom_site table (data blocks: {[b.name for b in doc]})")
    block = blocks[0]
    present = {t.lower() for t in block.find_mmcif_category("_atom_site.").tags}  # CIF tags ignore case
    for items in REQUIRED_ITEMS:
        if not any(f"_atom_site.{t}".lower() in present for t in items):
            raise ValueError(
                f"{name!r}: the _atom_site table has no _atom_site.{' or _atom_site.'.join(items)} column "
                f"(data block {block.name})"
            )

    def column(item):
        key = f"_atom_site.{item}"
        return list(block.find_values(key)) if key.lower() in present else None

    def first(*items):
        for it in items:
            col = column(it)
            if col is not None:
                return it, col
        return None, None

    xs, ys, zs = column("Cartn_x"), column("Cartn_y"), column("Cartn_z")
    n = len(xs)
    if n == 0:
        raise ValueError(f"{name!r}: the _atom_site table has no rows")
    ids = column("id")
    el_item, els = "type_symbol", column("type_symbol")
    at_item, ats = first("auth_atom_id", "label_atom_id")
    rn_item, rns = first("auth_comp_id", "label_comp_id")
    ch_item, chs = first("auth_asym_id", "label_asym_id")
    sq_item, sqs = first("auth_seq_id", "label_seq_id")
    mods = column("pdbx_PDB_model_num")

    # the model of each row; the one read is the first met unless model= says
    if mods is not None:
        row_model = _Rows(cif, name, range(n), ids).integers(mods, "pdbx_PDB_model_num")
        models_seen = list(dict.fromkeys(row_model))
    else:
        row_model, models_seen = None, [1]
    target = models_seen[0] if model is None else model
    if target not in models_seen:
        raise ValueError(f"{name!r} has no model {target} (pdbx_PDB_model_num holds: {models_seen})")
    rows = range(n) if row_model is None else [i for i, m in enumerate(row_model) if m == target]
    read = _Rows(cif, name, rows, ids)

    x = read.numbers(xs, "Cartn_x", required=True)
    y = read.numbers(ys, "Cartn_y", required=True)
    z = read.numbers(zs, "Cartn_z", required=True)
    col = column("occupancy")
    occ = [math.nan] * len(rows) if col is None else read.numbers(col, "occupancy", required=False)
    col = column("B_iso_or_equiv")
    bf = [math.nan] * len(rows) if col is None else read.numbers(col, "B_iso_or_equiv", required=False)
    num = read.integers(sqs, sq_item)
    atom = read.labels(ats, at_item)
    resn = read.labels(rns, rn_item)
    ch = read.labels(chs, ch_item)
    col = column("pdbx_PDB_ins_code")
    icode = [""] * len(rows) if col is None else read.labels(col, "pdbx_PDB_ins_code")
    col = column("label_alt_id")
    alt = [""] * len(rows) if col is None else read.labels(col, "label_alt_id")
    groups = column("group_PDB")
    group = ["ATOM"] * len(rows) if groups is None else read.labels(groups, "group_PDB")
    elem = read.labels(els, el_item)
    raw = {"group_PDB": groups, at_item: ats, "type_symbol": els}  # the text as written, shown in errors
    recs = atom_records(
        rows,
        dict(
            group=group,
            alt=alt,
            atom=atom,
            atom_item=at_item,
            resn=resn,
            chain=ch,
            num=num,
            icode=icode,
            x=x,
            y=y,
            z=z,
            occ=occ,
            b=bf,
            elem=elem,
        ),
        where=lambda item, i: _where(name, i + 1, read.ident(i), item),
        shown=lambda item, i, k: repr(raw[item][i]),
    )

    return kept_structure(recs, model=target, where=f"{name!r}: _atom_site row", **options.selection(path))
