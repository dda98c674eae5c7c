"""The BinaryCIF reader: the ``atom_site`` category of a BinaryCIF file, decoded by
biotite (Notes §23.1).

BinaryCIF is mmCIF's categories and columns, each column a typed array encoded (delta,
run-length, integer packing, fixed point, string tables) and the whole a MessagePack
map.  biotite's :class:`biotite.structure.io.pdbx.BinaryCIFFile` decodes it, column by
column; the ``atom_site`` columns are then read by the rules of the mmCIF reader
(:mod:`shapelab.io._mmcif`: ``auth_*`` labels, ``label_alt_id``, ``pdbx_PDB_model_num``,
...) into the same :class:`~shapelab.io._structure.AtomRecord` rows, which go through
the same selection and radii.  biotite is optional (``pip install "shapelab[bcif]"``)
and imported only when a BinaryCIF file is read.
"""

from __future__ import annotations

import os
import re
from typing import Any

import numpy as np

from ._mmcif import REQUIRED_ITEMS, atom_records, read_limited
from ._options import ReadOptions
from ._selection import kept_structure
from ._structure import PDBStructure

__all__ = ["read_bcif", "INSTALL_HINT"]

#: What to run when biotite, the BinaryCIF decoder, is not installed.
INSTALL_HINT = 'pip install "shapelab[bcif]"'

_INT = re.compile(r"[+-]?[0-9]+")
# a number written as a string: what the mmCIF reader accepts (a CIF number with an optional
# standard uncertainty, dropped), not all that Python's float() does ("1_000", " 1.5", "nan")
_NUMBER = re.compile(r"([+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)(?:\([0-9]+\))?")
_BYTES_PER_ROW = 8  # a decoded float64 column; max_bytes bounds it as it bounds the file
# the atom_site columns read (lower case): only these are decoded, so only these are checked
_OPTIONAL = (
    "id",
    "pdbx_PDB_model_num",
    "occupancy",
    "B_iso_or_equiv",
    "pdbx_PDB_ins_code",
    "label_alt_id",
    "group_PDB",
)
_READ = frozenset(t.lower() for t in (*(t for items in REQUIRED_ITEMS for t in items), *_OPTIONAL))
_PRESENT = 0  # biotite's MaskValue.PRESENT; 1 is "." (inapplicable), 2 is "?" (unknown)


def _biotite_pdbx():
    try:
        import biotite.structure.io.pdbx as pdbx
    except ImportError as e:
        raise ImportError(f"reading BinaryCIF needs biotite, which is not installed ({e}): {INSTALL_HINT}") from None
    return pdbx


def _sizes_checked(pdbx, content, name, max_bytes):
    """Refuse, before anything is decoded, an ``atom_site`` category that would decode to
    more than its file says: a row count past ``max_bytes // 8`` (one float64 column
    larger than the file may be), or a run-length or integer-packing step whose declared
    output (``srcSize``, from which biotite allocates) exceeds the category's rows (or, for
    a string table's offsets, its strings).  A few bytes of run-length encoding can
    otherwise ask for gigabytes, as a gzip bomb would without ``max_bytes``."""
    if not isinstance(content, dict) or not isinstance(content.get("dataBlocks"), list):
        return  # biotite's deserialisation names what is wrong
    for block in content["dataBlocks"]:
        cats = block.get("categories") if isinstance(block, dict) else None
        for cat in cats if isinstance(cats, list) else ():
            if not (isinstance(cat, dict) and str(cat.get("name", "")).lstrip("_").lower() == "atom_site"):
                continue
            where = f"{name!r}: atom_site (data block {block.get('header')})"
            rows = cat.get("rowCount")
            if isinstance(rows, bool) or not isinstance(rows, int) or rows < 0:
                raise ValueError(f"{where} has no valid rowCount: {rows!r}")
            if rows * _BYTES_PER_ROW > max_bytes:
                raise ValueError(
                    f"{where} has {rows} rows: decoded, one column would take more than "
                    f"max_bytes={max_bytes} bytes; pass a larger max_bytes= to read it"
                )
            for col in cat.get("columns") or ():
                if not (isinstance(col, dict) and str(col.get("name", "")).lower() in _READ):
                    continue  # a column never decoded allocates nothing
                item = f"{name!r}: atom_site.{col.get('name')} (data block {block.get('header')})"
                for part in (col.get("data"), col.get("mask")):
                    if isinstance(part, dict):
                        _encodings_checked(part.get("encoding"), rows, item)
                data = col.get("data")
                for enc in data.get("encoding") or () if isinstance(data, dict) else ():
                    if isinstance(enc, dict) and enc.get("kind") == "StringArray":
                        _strings_checked(pdbx, enc, rows, item, max_bytes)


def _strings_checked(pdbx, enc, rows, item, max_bytes):
    """A string table decodes to ``rows`` strings as wide as its longest (numpy's
    fixed-width strings, 4 bytes a character): one string of a megabyte in a table of a
    thousand rows would take 4 GB."""
    try:
        offsets = pdbx.BinaryCIFData.deserialize({"data": enc["offsets"], "encoding": enc["offsetEncoding"]}).array
        longest = int(np.diff(np.asarray(offsets, dtype=np.int64)).max(initial=0))
    except Exception:  # biotite's decoding of the column names what is wrong
        return
    if rows * 4 * max(longest, 1) > max_bytes:
        raise ValueError(
            f"{item}: its longest string has {longest} characters; decoded, its {rows} rows would take "
            f"more than max_bytes={max_bytes} bytes; pass a larger max_bytes= to read it"
        )


def _encodings_checked(encodings, limit, item):
    """Each run-length or integer-packing step of a column declares at most ``2 * limit + 2``
    values: ``limit`` values decoded, or the (value, run length) pairs of a run-length step."""
    most = 2 * limit + 2
    for enc in encodings if isinstance(encodings, list) else ():
        if not isinstance(enc, dict):
            continue
        kind = enc.get("kind")
        if kind in ("RunLength", "IntegerPacking"):
            size = enc.get("srcSize")
            if isinstance(size, bool) or not isinstance(size, int) or not 0 <= size <= most:
                raise ValueError(
                    f"{item}: its {kind} encoding declares srcSize={size!r} values, more than the "
                    f"{most} the category's rows allow"
                )
        elif kind == "StringArray":  # indices, one a row; offsets, one a distinct string and one more
            _encodings_checked(enc.get("dataEncoding"), limit, item)
            strings = enc.get("stringData")
            more = len(strings) if isinstance(strings, str) else 0
            _encodings_checked(enc.get("offsetEncoding"), limit + more + 1, item)


class _Columns:
    """The ``atom_site`` columns of one data block, decoded on demand; every error names
    the file, the category and the column (and the row, for a value)."""

    def __init__(self, name, category, block_name, n):
        self.name, self.category, self.block_name, self.n = name, category, block_name, n
        self.present = {k.lower(): k for k in category.keys()}  # CIF names ignore case
        self.ids = None

    def has(self, item):
        return item.lower() in self.present

    def where(self, item, row=None):
        if row is None:
            return f"{self.name!r}: atom_site.{item} (data block {self.block_name})"
        ident = "" if self.ids is None else f" (id {self.ids[row]})"
        return f"{self.name!r}: atom_site row {row + 1}{ident}, atom_site.{item}"

    def decoded(self, item):
        """``(values, mask)``: the column's array and its mask (None if all present)."""
        key = self.present[item.lower()]
        try:
            column = self.category[key]
            values = column.as_array()
            mask = None if column.mask is None else np.asarray(column.mask.array)
        except Exception as e:  # a malformed encoding: biotite raises what numpy or msgpack raise
            cause = e.__cause__ or e.__context__  # biotite's DeserializationError wraps the reason
            why = f"{type(e).__name__}: {e}" + ("" if cause is None else f" ({type(cause).__name__}: {cause})")
            raise ValueError(f"{self.where(item)} cannot be decoded: {why}") from None
        if mask is not None and not np.isin(mask, (0, 1, 2)).all():
            bad = mask[~np.isin(mask, (0, 1, 2))][0]
            raise ValueError(
                f"{self.where(item)} has a mask value {int(bad)}: a BinaryCIF mask holds 0 (present), "
                f"1 ('.') or 2 ('?')"
            )
        values = np.asarray(values)
        if self.n is None and values.ndim == 1:
            return values, mask
        if values.ndim != 1 or len(values) != self.n or (mask is not None and mask.shape != (self.n,)):
            got = values.shape if mask is None or mask.shape == values.shape else f"{values.shape}, mask {mask.shape}"
            raise ValueError(
                f"{self.where(item)} has {got} values where the category has {self.n} rows (atom_site.Cartn_x)"
            )
        if mask is not None and (mask == _PRESENT).all():
            mask = None
        return values, mask

    def numbers(self, item, rows, *, required):
        values, mask = self.decoded(item)
        values, mask = values[rows], None if mask is None else mask[rows]
        if values.dtype.kind in "iuf":
            out = values.astype(np.float64)
        else:  # numbers written as strings: each must read as one (with an optional uncertainty)
            out = np.empty(len(values))
            for k, v in enumerate(values):
                if mask is not None and mask[k] != _PRESENT:
                    out[k] = np.nan
                    continue
                match = _NUMBER.fullmatch(str(v))
                if match is None:
                    raise ValueError(f"{self.where(item, rows[k])} is not a number: {str(v)!r}")
                out[k] = float(match.group(1))
        if mask is not None:
            absent = mask != _PRESENT
            if required and absent.any():
                k = int(np.flatnonzero(absent)[0])
                what = "." if mask[k] == 1 else "?"
                raise ValueError(f"{self.where(item, rows[k])} is {what!r} (unknown): a number is required")
            out[absent] = np.nan
        bad = ~np.isfinite(out) & (np.ones(len(out), bool) if mask is None else mask == _PRESENT)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise ValueError(f"{self.where(item, rows[k])} must be finite, got {str(values[k])!r}")
        return out.tolist()

    def integers(self, item, rows):
        values, mask = self.decoded(item)
        values, mask = values[rows], None if mask is None else mask[rows]
        absent = np.empty(0, int) if mask is None else np.flatnonzero(mask != _PRESENT)
        if len(absent):  # only the rows read count: another model's "?" is not this one's
            k = int(absent[0])
            what = "." if mask[k] == 1 else "?"
            raise ValueError(f"{self.where(item, rows[k])} is not an integer: {what!r}")
        if values.dtype.kind in "iu":
            return values.astype(np.int64).tolist()
        out = []
        for k, v in enumerate(values):
            t = str(v)
            if values.dtype.kind == "f" and np.isfinite(v) and v == int(v):
                t = str(int(v))
            if not _INT.fullmatch(t):
                raise ValueError(f"{self.where(item, rows[k])} is not an integer: {t!r}")
            out.append(int(t))
        return out

    def labels(self, item, rows):
        values, mask = self.decoded(item)
        values = values[rows].astype(str)
        if mask is not None:
            values[mask[rows] != _PRESENT] = ""
        out = values.tolist()
        joined = "".join(out)
        if not (joined.isascii() and joined.isprintable()):
            for k, t in enumerate(out):
                if not (t.isascii() and t.isprintable()):
                    raise ValueError(f"{self.where(item, rows[k])} is not printable ASCII: {t!r}")
        return out


def read_bcif(path: str | os.PathLike[str], options: ReadOptions | None = None, **keywords: Any) -> PDBStructure:
    """Read the ``atom_site`` category of a BinaryCIF file (plain or gzip) as balls.

    The options are those of :func:`~shapelab.io.read_structure`, which documents
    them; this is its BinaryCIF branch (given checked, as a
    :class:`~shapelab.io.ReadOptions`, or as keywords).  The columns are decoded by
    biotite's :class:`~biotite.structure.io.pdbx.BinaryCIFFile` and read by the mmCIF
    reader's rules, so a BinaryCIF file and the text mmCIF of the same entry give the
    same atoms.
    """
    if options is None:
        options = ReadOptions.checked(path, "bcif", **keywords)
    elif keywords:
        raise TypeError(f"give the options or keywords, not both (got {sorted(keywords)})")
    pdbx = _biotite_pdbx()
    name = os.fspath(path)
    data = read_limited(path, options.max_bytes)
    if not data:
        raise ValueError(f"{name!r} is empty: no BinaryCIF data blocks and no atom_site category")
    import msgpack  # biotite's own dependency, for the container

    try:
        content = msgpack.unpackb(data, use_list=True, raw=False)  # as BinaryCIFFile.read does
    except Exception as e:  # msgpack's errors (ExtraData, FormatError, ...)
        raise ValueError(
            f"{name!r} is not a readable BinaryCIF file (a MessagePack map of dataBlocks): {type(e).__name__}: {e}"
        ) from None
    _sizes_checked(pdbx, content, name, options.max_bytes)
    try:
        doc = pdbx.BinaryCIFFile.deserialize(content)
        block_names = list(doc.keys())
    except Exception as e:  # msgpack's errors (ExtraData, FormatError, ...) or a map without dataBlocks
        raise ValueError(
            f"{name!r} is not a readable BinaryCIF file (a MessagePack map of dataBlocks): {type(e).__name__}: {e}"
        ) from None
    category = block_name = None
    for bname in block_names:
        try:
            block = doc[bname]
            key = next((k for k in block.keys() if k.lower() == "atom_site"), None)  # CIF names ignore case
            if key is not None:
                category, block_name = block[key], bname
                break
        except Exception as e:
            raise ValueError(
                f"{name!r}: data block {bname!r} is not readable BinaryCIF: {type(e).__name__}: {e}"
            ) from None
    if category is None:
        raise ValueError(f"{name!r} has no atom_site category (data blocks: {block_names})")
    present = {k.lower() for k in category.keys()}
    for items in REQUIRED_ITEMS:
        if not any(t.lower() in present for t in items):
            raise ValueError(
                f"{name!r}: the atom_site category has no atom_site.{' or atom_site.'.join(items)} column "
                f"(data block {block_name})"
            )
    cols = _Columns(name, category, block_name, None)
    n = len(cols.decoded("Cartn_x")[0])  # the category's row count: every column read must match it
    if n == 0:
        raise ValueError(f"{name!r}: the atom_site category has no rows")
    cols.n = n
    if cols.has("id"):
        ids, _ = cols.decoded("id")
        cols.ids = ids.astype(str).tolist()

    def first(*items):
        return next(it for it in items if cols.has(it))

    everything = np.arange(n)
    if cols.has("pdbx_PDB_model_num"):
        row_model = cols.integers("pdbx_PDB_model_num", everything)
        models_seen = list(dict.fromkeys(row_model))
    else:
        row_model, models_seen = None, [1]
    target = models_seen[0] if options.model is None else options.model
    if target not in models_seen:
        raise ValueError(f"{name!r} has no model {target} (pdbx_PDB_model_num holds: {models_seen})")
    rows = everything if row_model is None else np.flatnonzero(np.asarray(row_model) == target)
    m = len(rows)

    x = cols.numbers("Cartn_x", rows, required=True)
    y = cols.numbers("Cartn_y", rows, required=True)
    z = cols.numbers("Cartn_z", rows, required=True)
    occ = cols.numbers("occupancy", rows, required=False) if cols.has("occupancy") else [np.nan] * m
    bf = cols.numbers("B_iso_or_equiv", rows, required=False) if cols.has("B_iso_or_equiv") else [np.nan] * m
    sq_item = first("auth_seq_id", "label_seq_id")
    num = cols.integers(sq_item, rows)
    at_item = first("auth_atom_id", "label_atom_id")
    atom = cols.labels(at_item, rows)
    resn = cols.labels(first("auth_comp_id", "label_comp_id"), rows)
    ch = cols.labels(first("auth_asym_id", "label_asym_id"), rows)
    icode = cols.labels("pdbx_PDB_ins_code", rows) if cols.has("pdbx_PDB_ins_code") else [""] * m
    alt = cols.labels("label_alt_id", rows) if cols.has("label_alt_id") else [""] * m
    group = cols.labels("group_PDB", rows) if cols.has("group_PDB") else ["ATOM"] * m
    elem = cols.labels("type_symbol", rows)
    shown = {"group_PDB": lambda k: repr(group[k]), at_item: lambda k: "empty", "type_symbol": lambda k: repr(elem[k])}
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
        where=cols.where,
        shown=lambda item, i, k: shown[item](k),
    )
    return kept_structure(recs, model=target, where=f"{name!r}: atom_site row", **options.selection(path))
