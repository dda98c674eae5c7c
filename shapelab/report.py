"""A CASTp-style report of the voids and pockets of a molecule, offline (Notes §23.1).

Notes §23.1, "Voids and pockets": a *void* is a bounded component of the complement
of the union of balls; a *pocket* is a dent of the surface that closes into a void
as the balls grow.  :func:`report` finds both in the solvent-accessible (SA) model,
measures each in the SA and in the van der Waals (vdW) model, lists its mouths
(pockets) and the atoms and residues lining it, and :class:`CavityReport` writes the
result as CSV, Markdown and a PDB file with the lining atoms marked -- the tables
that CASTp (Liang, Edelsbrunner & Woodward, "Anatomy of protein pockets and cavities:
measurement of binding site geometry and implications for ligand design", *Protein
Science* 7 (1998) 1884–1897) serves online, computed here without a server.

The command line runs it on a file (:mod:`shapelab.tools.cli`)::

    python -m shapelab report FILE.pdb [--probe 1.4] [--out DIR] [options]

This module is the report itself; it reads no arguments and has no side effects on
import.
"""

from __future__ import annotations

import csv
import io as _stdio
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from ._toolkit.tolerances import LINING_AREA_RTOL
from ._toolkit.validate import as_finite_scalar, as_positive_int

if TYPE_CHECKING:
    from .balls import Balls
    from .io import PDBStructure

__all__ = ["CavityRow", "CavityReport", "report", "check_output"]


# ============================================================================ results
@dataclass(frozen=True)
class CavityRow:
    """One void or pocket of a :class:`CavityReport`.

    Attributes
    ----------
    kind : str
        ``"void"`` or ``"pocket"``.
    id : int
        1, 2, ... over the whole report (voids first, each kind by SA volume,
        largest first); the value that marks the lining atoms in the files of
        :meth:`CavityReport.write`.
    volume_sa, area_sa : float
        Free volume (Å³) of the cavity's Delaunay cells in the SA model and the area
        (Å²) of the SA surface inside them (the cavity's wall; for a pocket the mouth
        is not wall).  Exact.
    volume_vdw, area_vdw : float
        The same cells measured in the vdW model (radii without the probe).  Exact.
    mouths : int
        Connected components of the mouth triangles (0 for a void).
    mouth_area, mouth_perimeter : float
        Free area (Å²) of the mouth triangles in the SA model -- the opening a probe
        centre passes through -- and the length (Å) of its rim, the circle arcs where
        the SA spheres cut the mouth triangles.  0 for a void.
    birth, death : float
        Persistence of the feature in the growth parameter τ (Å²): for a void
        ``Void.born``/``Void.dies``, for a pocket ``Pocket.closes_at``/``fills_at``.
    lining_atoms : tuple of int
        The cavity's *wall atoms*, CASTp's sense of lining: indices (into the
        structure's atoms) of the atoms whose SA sphere bounds the cavity's free space,
        with positive wall area inside its cells.  A sphere can reach into a cell of
        which its atom is no vertex, so this is not ``Pocket.lining`` / ``Void.lining``
        (the *lining atoms*, the cells' vertices): HIV-1 protease's largest pocket
        (1HVR, probe 1.4 Å) has 58 wall atoms of 26 residues and 36 lining atoms of 23
        (lesson 09).
    lining_atom_names : tuple of str
        Their atom names (``""`` for bare balls).
    lining_residues : tuple of (str, str, int)
        ``(chain, residue name, residue number)`` of the distinct residues of the
        lining atoms, in atom order (empty for bare balls).  A residue is told apart
        by its insertion code too, so 52 and 52A are two entries (Kabat numbering);
        ``lining_insertion_codes`` holds their codes.
    lining_insertion_codes : tuple of str
        The insertion code of each entry of ``lining_residues`` (``""`` for none);
        empty when built without them, which :meth:`residue_labels` reads as none.
    score, buriedness, depth, openness : float or None
        With ``report(..., rank="score")``: the ranking score and the features of
        :class:`shapelab.ranking.PocketFeatures` it is made of; None otherwise.

    See Also
    --------
    CavityReport
        The table of rows.
    """

    kind: str
    id: int
    volume_sa: float
    area_sa: float
    volume_vdw: float
    area_vdw: float
    mouths: int
    mouth_area: float
    mouth_perimeter: float
    birth: float
    death: float
    lining_atoms: tuple
    lining_atom_names: tuple
    lining_residues: tuple
    lining_insertion_codes: tuple = ()
    score: float | None = None
    buriedness: float | None = None
    depth: float | None = None
    openness: float | None = None

    @property
    def persistence(self) -> float:
        """``death - birth``, in τ.  Voids and pockets are classes of :math:`H_2` (and of
        the complement), so their pairs are the same over every coefficient field; the
        library computes over :math:`\\mathbb{Z}/2` (:func:`shapelab.persistence.persistence`)."""
        return self.death - self.birth

    def residue_labels(self) -> list[str]:
        """Lining residues as labels, e.g. ``['A:LEU99', 'H:GLY52A']`` (``':LEU99'``
        without chain), as :meth:`shapelab.io.PDBStructure.residue_label` writes them."""
        codes = self.lining_insertion_codes or ("",) * len(self.lining_residues)
        return [f"{c}:{n}{s}{i}" for (c, n, s), i in zip(self.lining_residues, codes)]


_COLUMNS = (
    "kind",
    "id",
    "volume_sa",
    "area_sa",
    "volume_vdw",
    "area_vdw",
    "mouths",
    "mouth_area",
    "mouth_perimeter",
    "birth",
    "death",
    "persistence",
    "n_lining_atoms",
    "lining_residues",
    "lining_atoms",
)
_RANK_COLUMNS = ("score", "buriedness", "depth", "openness")


@dataclass(frozen=True)
class CavityReport:
    """The voids and pockets of a structure: the rows of :func:`report`.

    Attributes
    ----------
    rows : tuple of CavityRow
    probe : float
        The probe radius (Å) of the SA model.
    name : str
        The structure's name (file stem, or what was passed to :func:`report`).
    tau : float
        The growth time the cavities were found at.
    structure : object
        The :class:`~shapelab.io.PDBStructure` or :class:`~shapelab.Balls` reported
        on (for the PDB output); not compared.
    rank : str
        ``"none"`` (rows in CASTp's order: voids first, each kind by SA volume) or
        ``"score"`` (rows by :func:`shapelab.ranking.rank_score`, best first, with
        the ranking's columns in the CSV and Markdown outputs).
    found : int or None
        How many cavities :func:`report` found before its filters (``min_persistence``,
        ``min_volume``, ``top``); ``len(rows)`` of them are listed.  None: not known
        (a report built by hand), and then the Markdown says nothing of filters.
    filters : str
        The filters applied, as the Markdown names them (``""`` for none).
    method : str
        The pocket definition, ``"growth"`` or ``"flow"`` (:func:`shapelab.pockets`).
    notes : tuple of str
        What the reader should know of the structure's radii, as the Markdown says it
        under "Notes": which atoms took a van der Waals radius of Alvarez (2013) --
        the elements, how many atoms, the table cited -- or ``default_radius``
        (:func:`shapelab.io.radius_notes`); ``()`` for none.

    See Also
    --------
    report
        Produces it.
    shapelab.io.write_mmcif
        How it writes the structure.
    """

    rows: tuple
    probe: float
    name: str
    tau: float = 0.0
    structure: object = field(default=None, compare=False, repr=False)
    rank: str = "none"
    found: int | None = None
    filters: str = ""
    method: str = "growth"
    notes: tuple = ()

    def __len__(self) -> int:
        return len(self.rows)

    @property
    def voids(self) -> tuple:
        """The rows of kind ``"void"``."""
        return tuple(r for r in self.rows if r.kind == "void")

    @property
    def pockets(self) -> tuple:
        """The rows of kind ``"pocket"``."""
        return tuple(r for r in self.rows if r.kind == "pocket")

    # ----------------------------------------------------------------- formats
    def _csv_text(self) -> str:
        buf = _stdio.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        ranked = self.rank != "none"
        w.writerow(_COLUMNS + (_RANK_COLUMNS if ranked else ()))
        for r in self.rows:
            extra = [f"{getattr(r, c):.6f}" for c in _RANK_COLUMNS] if ranked else []
            w.writerow(
                [
                    r.kind,
                    r.id,
                    f"{r.volume_sa:.6f}",
                    f"{r.area_sa:.6f}",
                    f"{r.volume_vdw:.6f}",
                    f"{r.area_vdw:.6f}",
                    r.mouths,
                    f"{r.mouth_area:.6f}",
                    f"{r.mouth_perimeter:.6f}",
                    f"{r.birth:.6f}",
                    f"{r.death:.6f}",
                    f"{r.persistence:.6f}",
                    len(r.lining_atoms),
                    " ".join(r.residue_labels()),
                    " ".join(str(i) for i in r.lining_atoms),
                ]
                + extra
            )
        return buf.getvalue()

    def to_csv(self, path) -> Path:
        """Write the rows as CSV (one row per feature, columns as :class:`CavityRow`)."""
        out = Path(path)
        out.write_text(self._csv_text(), encoding="utf-8")
        return out

    def to_markdown(self) -> str:
        """The rows as a Markdown table headed by the structure's name and the probe."""
        lines = [
            f"## Cavities of {self.name} (probe {self.probe:g} Å, τ = {self.tau:g})",
            "",
            f"{len(self.voids)} voids, {len(self.pockets)} pockets.  Volumes in Å³, areas in Å², "
            "lengths in Å; SA = solvent-accessible model, vdW = van der Waals model; birth and death in τ (Å²), "
            "homology over Z/2 (the same for voids and pockets over every field).",
            "",
            "| kind | id | V SA | A SA | V vdW | A vdW | mouths | mouth area | mouth perimeter "
            "| birth | death | lining atoms | lining residues |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
        ]
        if self.rank != "none":
            lines[2] += "  Last columns: score, buriedness (share of blocked directions), depth (Å), openness."
        dropped = None if self.found is None else self.found - len(self.rows)
        if self.rank != "none" or dropped:
            order = (
                "Ranked best first by shapelab.ranking.rank_score (buriedness² × ln(1 + V SA), the binding-site "
                "default)"
                if self.rank != "none"
                else "In CASTp's order (voids first, by SA volume)"
            )
            if self.method != "growth":
                order += ", pockets by CASTp's discrete flow"
            kept = f"; kept {self.filters}" if self.filters else ""
            told = (
                ""
                if dropped is None
                else f": {len(self.rows)} of {self.found} cavities listed, {dropped} filtered out "
                '(rank="none" without filters, --rank none on the command line, lists them all)'
            )
            lines[4:4] = [f"{order}{kept}{told}.", ""]
        if self.notes:
            lines[-2:-2] = [f"Notes: {'; '.join(self.notes)}.", ""]
        if self.rank != "none":
            lines[-2] += " score | buried | depth | open |"
            lines[-1] += "---:|---:|---:|---:|"
        for r in self.rows:
            lines.append(
                f"| {r.kind} | {r.id} | {r.volume_sa:.2f} | {r.area_sa:.2f} | {r.volume_vdw:.2f} "
                f"| {r.area_vdw:.2f} | {r.mouths} | {r.mouth_area:.2f} | {r.mouth_perimeter:.2f} "
                f"| {r.birth:.3f} | {r.death:.3f} | {len(r.lining_atoms)} | {' '.join(r.residue_labels())} |"
            )
            if self.rank != "none":
                lines[-1] += f" {r.score:.3f} | {r.buriedness:.2f} | {r.depth:.1f} | {r.openness:.2f} |"
        return "\n".join(lines) + "\n"

    def _marks(self):
        """Per atom: the smallest id of the features it lines (0 if none), and all of
        them as ``"1,5"`` (``""`` if none)."""
        import numpy as np

        n = len(_balls_of(self.structure))
        ids = [[] for _ in range(n)]
        for r in sorted(self.rows, key=lambda r: r.id):
            for i in r.lining_atoms:
                ids[i].append(r.id)
        smallest = np.array([f[0] if f else 0 for f in ids], dtype=np.float64)
        return smallest, [",".join(map(str, f)) for f in ids]

    def _labels(self) -> dict:
        """The structure's columns for :func:`~shapelab.io.write_mmcif` and
        :func:`~shapelab.io.write_pdb` (bare balls: carbon atoms)."""
        from .io import PDBStructure

        s = self.structure
        if not isinstance(s, PDBStructure):
            return {"elements": "C"}
        return dict(
            elements=s.elements,
            atom_names=s.atom_names,
            residue_names=s.residue_names,
            residue_numbers=s.residue_numbers,
            chains=s.chains,
            hetero=s.hetero,
            insertion_codes=s.insertion_codes,
            altlocs=s.altlocs,
        )

    def _write_marked_cif(self, path):
        from .io import PDBStructure, write_mmcif

        smallest, every = self._marks()
        s = self.structure
        occ = s.occupancies if isinstance(s, PDBStructure) else None
        return write_mmcif(
            path,
            _balls_of(s),
            **self._labels(),
            occupancies=occ,
            b_factors=smallest,
            extra={"shapelab_feature_ids": every},
            title=f"{_printable(self.name)} cavities, probe {self.probe:g}: B_iso_or_equiv = smallest feature id lined, "
            f"shapelab_feature_ids = all (0 and empty: none)",
            name=f"{self.name}_cavities",
        )

    def _write_marked_pdb(self, path):
        from .io import write_pdb

        smallest, _ = self._marks()
        what = f" cavities, probe {self.probe:g}: B-factor = feature id"
        title = _printable(self.name)[: max(0, 70 - len(what))] + what  # TITLE holds 70 characters
        return write_pdb(path, _balls_of(self.structure), **self._labels(), title=title, b_factors=smallest)

    def pdb_problem(self):
        """Why the marked structure cannot be written as a PDB file, or None if it can.

        The PDB's fixed columns hold at most 99,999 atoms, residue names of three
        characters, chains of two, residue numbers up to 9999, coordinates in
        (-1000, 10000) and B-factors -- here the feature ids -- below 1000; real
        proteins of 11,000 atoms already have more than 1000 pockets and voids.
        The mmCIF file of :meth:`write` has none of these limits.

        Examples
        --------
        >>> from shapelab.datasets import bowl
        >>> rep = report(bowl(), 0.0)
        >>> rep.pdb_problem() is None
        True
        >>> import dataclasses
        >>> many = dataclasses.replace(rep.rows[0], id=1000)
        >>> dataclasses.replace(rep, rows=(many,)).pdb_problem()
        'feature ids up to 1000: the B-factor column (61-66) holds ids up to 999'
        """
        top = max((r.id for r in self.rows), default=0)
        if top > 999:
            return f"feature ids up to {top}: the B-factor column (61-66) holds ids up to 999"
        try:
            self._write_marked_pdb(_stdio.StringIO())
        except ValueError as e:
            return str(e)
        return None

    def write(self, out_dir, stem, *, pdb="auto") -> tuple:
        """Write ``<stem>_cavities.csv``, ``.md``, ``.cif`` (and ``.pdb``) into ``out_dir``, atomically.

        The CSV and Markdown files are the table (:meth:`to_csv`, :meth:`to_markdown`).
        The **mmCIF file** is the marked structure: its ``_atom_site`` table
        (:func:`shapelab.io.write_mmcif`) holds every atom, with the smallest id of
        the features it lines in ``B_iso_or_equiv`` (0 for none) -- the column every
        viewer colours by -- and all of them in the item
        ``_atom_site.shapelab_feature_ids`` (``1,5``; ``.`` for none).  Atom ``i`` of
        the CSV's ``lining_atoms`` is ``_atom_site.id`` ``i + 1``.

        Why mmCIF and not only PDB: the PDB's B-factor column holds numbers below
        1000, and proteins of 11,000–16,000 atoms have more than 1000 voids and
        pockets; the format also holds at most 99,999 atoms (not a ribosome) and
        three-letter residue names.  mmCIF has no fixed widths, so the marked
        structure of any report can be written, and no limit is found only after
        the cavities have been computed.  The PDB file is kept as a convenience for
        tools that read nothing else, with the same marks in its B-factor column,
        wherever the format can hold them (:meth:`pdb_problem`).

        Parameters
        ----------
        out_dir : str or os.PathLike
            An existing directory.
        stem : str
            File name prefix, without directories.
        pdb : {"auto", True, False}, default "auto"
            Write the PDB file: when the format can hold it ("auto"), always (True:
            a ValueError, and nothing written, if it cannot), or never (False).
            Without a PDB file written, an older ``<stem>_cavities.pdb`` in
            ``out_dir`` is removed, so that the files on disk are one report.

        Returns
        -------
        tuple of pathlib.Path
            The CSV, Markdown and mmCIF paths, then the PDB path if it was written.

        Notes
        -----
        All files are first written to temporary files in ``out_dir`` and renamed
        into place only once every one is complete; on any error the temporary files
        are removed and no target file is created or changed.  A target name taken
        by a directory (or anything but a file) is refused before anything is
        written.  Should a rename itself fail (the file system fails), the files
        already renamed are removed, so that no mixture of two reports is left.
        """
        if pdb not in ("auto", True, False):
            raise ValueError(f"pdb must be 'auto', True or False, got {pdb!r}")
        out_dir, stem = _check_target(out_dir, stem)
        problem = None if pdb is False else self.pdb_problem()
        if pdb is True and problem is not None:
            raise ValueError(f"the PDB format cannot hold this report: {problem}")
        with_pdb = pdb is not False and problem is None
        exts = ("csv", "md", "cif", "pdb") if with_pdb else ("csv", "md", "cif")
        targets = [out_dir / f"{stem}_cavities.{ext}" for ext in exts]
        writers = [
            self.to_csv,
            lambda p: Path(p).write_text(self.to_markdown(), encoding="utf-8"),
            self._write_marked_cif,
            self._write_marked_pdb,
        ]
        mask = os.umask(0)
        os.umask(mask)
        mode = 0o666 & ~mask
        temps = []
        try:
            for t, writer in zip(targets, writers):
                fd, tmp = tempfile.mkstemp(dir=out_dir, prefix=f".{t.name}.", suffix=".tmp")
                os.close(fd)
                temps.append(Path(tmp))
                writer(tmp)
                os.chmod(tmp, mode)  # mkstemp's files are private; the report is not
            done = []
            try:
                for tmp, t in zip(temps, targets):
                    os.replace(tmp, t)
                    done.append(t)
            except BaseException:
                for t in done:  # an all-or-nothing result: undo the renames made
                    t.unlink(missing_ok=True)
                raise
        finally:
            for tmp in temps:
                tmp.unlink(missing_ok=True)
        if not with_pdb:
            (out_dir / f"{stem}_cavities.pdb").unlink(missing_ok=True)  # a stale one from another report
        return tuple(targets)


def _printable(name: str) -> str:
    """``name`` in printable ASCII for a file's title: other characters escaped as
    Python writes them (``protéine`` -> ``prot\\xe9ine``, a tab -> ``\\t``), so that
    any name -- a file stem is whatever the file system allows -- can be written."""
    return "".join(c if c.isascii() and c.isprintable() else ascii(c)[1:-1] for c in str(name))


def _balls_of(structure):
    from .balls import Balls
    from .io import PDBStructure

    if structure is None:
        raise ValueError("this CavityReport holds no structure to write")
    balls = structure.balls if isinstance(structure, PDBStructure) else structure
    if not isinstance(balls, Balls):
        raise TypeError(f"cannot write the atoms of {type(structure).__name__}")
    return balls


def _check_target(out_dir, stem):
    """The output directory (must exist) and a plain file-name stem."""
    out_dir = Path(out_dir)
    stem = str(stem)
    if not stem or os.sep in stem or (os.altsep and os.altsep in stem) or stem in (".", ".."):
        raise ValueError(f"stem must be a non-empty file name without directories, got {stem!r}")
    if not out_dir.is_dir():
        raise FileNotFoundError(f"output directory {os.fspath(out_dir)!r} does not exist")
    for ext in ("csv", "md", "cif", "pdb"):  # a rename onto a directory fails half-way
        t = out_dir / f"{stem}_cavities.{ext}"
        if t.is_dir() or (t.exists() and not t.is_file()):
            raise IsADirectoryError(f"{os.fspath(t)!r} is in the way: it is not a file the report could replace")
    return out_dir, stem


def check_output(structure, out_dir, stem) -> None:
    """Check, before computing a report, that its files can be written.

    Raises what :meth:`CavityReport.write` would raise for reasons known before the
    cavities are found: an output directory that is missing or not writable (a
    temporary file is created in it and removed), a bad ``stem``, a file name
    of the report taken by a directory, or atom labels
    the mmCIF writer refuses (a dry run of :func:`shapelab.io.write_mmcif` on the
    unmarked structure).  What is left -- the number of features -- can only limit
    the optional PDB file, never the mmCIF one.  The command line runs this first.

    See Also
    --------
    CavityReport.write
        Writes what this checks.

    Examples
    --------
    >>> import tempfile
    >>> from shapelab.datasets import bowl
    >>> with tempfile.TemporaryDirectory() as d:
    ...     check_output(bowl(), d, "bowl")
    >>> check_output(bowl(), "/no/such/dir", "bowl")
    Traceback (most recent call last):
    ...
    FileNotFoundError: output directory '/no/such/dir' does not exist
    """
    out_dir, stem = _check_target(out_dir, stem)
    fd, tmp = tempfile.mkstemp(dir=out_dir, prefix=f".{stem}_cavities.", suffix=".tmp")
    os.close(fd)
    os.unlink(tmp)
    CavityReport(rows=(), probe=0.0, name=stem, structure=structure)._write_marked_cif(_stdio.StringIO())


# ========================================================================= compute
def _mouth_counts(mouths) -> list:
    """Number of mouths of each pocket: its mouth triangles grouped into components
    through shared edges (one graph for all pockets, whose triangles are kept apart)."""
    import numpy as np
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    tris = [np.sort(np.asarray(m, dtype=np.int64).reshape(-1, 3), axis=1) for m in mouths]
    sizes = np.array([len(t) for t in tris], dtype=np.int64)
    q = int(sizes.sum())
    if q == 0:
        return [0] * len(tris)
    t = np.concatenate(tris)
    owner = np.repeat(np.arange(len(tris)), sizes)
    # an edge is (pocket, a, b): triangles of two pockets never share one
    edges = np.concatenate([np.column_stack([owner, t[:, i], t[:, j]]) for i, j in ((0, 1), (0, 2), (1, 2))])
    _, eid = np.unique(edges, axis=0, return_inverse=True)
    eid = eid.ravel()
    ne = int(eid.max()) + 1
    g = coo_matrix((np.ones(3 * q), (np.tile(np.arange(q), 3), q + eid)), shape=(q + ne, q + ne))
    _, lab = connected_components(g, directed=False)
    per = np.unique(np.column_stack([owner, lab[:q]]), axis=0)[:, 0]
    return np.bincount(per, minlength=len(tris)).tolist()


def _contacts_of(rows, first, by_cell):
    """Indices, ascending, of the contacts in the (sorted, distinct) cell ``rows``:
    the contacts sorted by cell are ``by_cell``, those of row ``r`` at
    ``first[r]:first[r + 1]``.  Linear in the answer, not in all the contacts."""
    import numpy as np

    lo, hi = first[rows], first[rows + 1]
    size = hi - lo
    if not size.sum():
        return np.zeros(0, np.int64)
    at = np.repeat(lo - np.concatenate([[0], np.cumsum(size)[:-1]]), size) + np.arange(size.sum())
    return np.sort(by_cell[at])


def report(
    structure: PDBStructure | Balls,
    probe: float = 1.4,
    *,
    tau: float = 0.0,
    min_persistence: float | None = None,
    name: str | None = None,
    rank: str = "score",
    min_volume: float | None = None,
    top: int | None = None,
    method: str = "growth",
) -> CavityReport:
    """Voids and pockets of a molecule, measured as CASTp does (Notes §23.1).

    The cavities are found in the solvent-accessible (SA) model, balls of radius
    van der Waals radius + ``probe``, with :func:`shapelab.voids` and
    :func:`shapelab.pockets` on its α-filtration (Notes §23.1, "Voids and pockets";
    Liang, Edelsbrunner & Woodward 1998).  For each one the report gives

    * **SA volume and area**: the free volume of the cavity's Delaunay cells (what no
      SA ball covers: the space a probe centre can occupy) and the area of the SA
      surface inside those cells, i.e. the part of the union's boundary facing into
      the cavity.  Both are exact, from :func:`shapelab.cavities.freespace.free_space`: the
      power-cell decomposition :math:`U \\cap t = \\bigsqcup_i B_i \\cap \\Pi_i \\cap t`
      in closed form, the wall by the divergence theorem on each clipped ball.  For a
      void the volume equals ``Void.volume``; for a pocket ``Pocket.volume``.
    * **vdW volume and area**: the *same cells* (the same region of space) measured
      in the van der Waals model -- the space inside them that no vdW ball covers, and
      the area of the vdW surface inside them.  Exact, by the same code.
    * **mouths** (pockets): the mouth triangles of ``Pocket.mouth`` grouped into
      components through shared edges; their free area in the SA model (the
      opening a probe centre passes through) and the length of its rim.
    * **lining atoms and residues**: atoms with positive SA wall area in the cells.
    * **persistence**: birth and death of the feature in τ (a void's or pocket's pair:
      the same over every coefficient field, :math:`\\mathbb{Z}/2` as everywhere in
      shapelab; :func:`shapelab.persistence.persistence`).

    Parameters
    ----------
    structure : shapelab.io.PDBStructure or Balls
        From :func:`shapelab.read_pdb` or :func:`shapelab.datasets.structure`; its
        balls minus its own ``probe`` are the vdW balls.  Bare 3D :class:`Balls`
        are taken as vdW balls (no atom or residue names).
    probe : float, default 1.4
        Probe radius (Å) added to every vdW radius for the SA model; 1.4 is water.
    tau : float, default 0.0
        Growth time of the SA model at which cavities are found and measured (the
        vdW model is always measured as given).
    min_persistence : float, optional
        Keep features with ``death - birth >= min_persistence``.  Default 0 with
        ``rank="none"``, :data:`shapelab.ranking.DEFAULT_MIN_PERSISTENCE` with
        ``rank="score"``.
    name : str, optional
        Name shown in the outputs (default ``"structure"``).
    rank : {"score", "none"}, default "score"
        ``"score"`` (the default): voids and pockets together, best first by
        :func:`shapelab.ranking.rank_score` (what predicts a binding site), cavities
        under :data:`~shapelab.ranking.DEFAULT_MIN_VOLUME` dropped, and four more
        columns (score, buriedness, depth, openness); ids follow the rank, 1 the
        best (equal scores: the larger SA volume first, then CASTp's order).
        ``"none"``: every feature, in CASTp's order (voids first, each kind by SA
        volume, largest first), the table of the report before rankings existed,
        byte for byte.  The Markdown says in one line how the rows are ranked and
        filtered, and how many cavities were filtered out.
    min_volume : float, optional
        Keep features with SA volume ``>= min_volume`` (Å³).  Default 0 with
        ``rank="none"``, :data:`shapelab.ranking.DEFAULT_MIN_VOLUME` with ``rank="score"``.
    top : int, optional
        Keep at most this many features, the first in the report's order (default all).
    method : {"growth", "flow"}, default "growth"
        The pocket definition (:func:`shapelab.pockets`): the notes' growth model or
        CASTp's discrete flow.  Both are measured, filtered and ranked alike.

    Returns
    -------
    CavityReport
        With ``notes`` on the radii of a :class:`~shapelab.io.PDBStructure`: which
        atoms took a van der Waals radius of Alvarez (2013), Table 1 (the transition
        metals, lanthanides and actinides Bondi 1964 and Mantina et al. 2009 lack:
        Fe, Mn, Co, Mo, ...), or ``default_radius`` (:func:`shapelab.io.radius_notes`),
        which the Markdown prints above the table.

    Raises
    ------
    TypeError
        ``probe`` is not a real number, or ``structure`` is neither a
        PDBStructure nor Balls.
    ValueError
        ``probe`` negative or not finite; balls not 3-dimensional; ``rank`` not
        ``"none"`` or ``"score"``; ``method`` not ``"growth"`` or ``"flow"``; a
        filter negative or not finite, ``top`` below 1.

    See Also
    --------
    voids
        The voids.
    pockets
        The pockets.
    shapelab.io.read_structure
        Reads a structure (PDB or mmCIF) as balls.
    shapelab.ranking.rank_score
        The score of ``rank="score"``.

    Notes
    -----
    *Which pocket is the site.*  A protein has hundreds of pockets, most of them
    dents between a few atoms.  By default (``rank="score"``) the report orders
    them by :func:`shapelab.ranking.rank_score`, buriedness² × ln(1 + SA volume),
    and drops those under 10 Å³ (``min_volume``; ``min_persistence`` 0).  What the
    default optimises: top-(N + 2) DCA recall (a listed cavity's lining centroid
    within 4 Å of a ligand atom among the first N + 2, N the structure's ligand
    sites) with a median of fewer than 20 cavities listed per structure.  It was
    chosen on the development split of the pocket benchmark only (34 structures:
    top-(N + 2) 75.4 %, median 14 listed; ``python -m benchmarks.pocket_ranking``,
    ``benchmarks/results/pocket_ranking_dev.md``).  On the held-out test split (52
    structures, 105 sites, measured once afterwards) it finds 68.6 % of the sites
    among the top N + 2 (57.1 % among the top N) with a median of 16 cavities
    listed, below the 75 % aimed at; ``python -m benchmarks.pocket_sites``
    reproduces it.  ``rank="none"`` lists every cavity, unfiltered, in CASTp's
    order.

    *Same as CASTp.*  Cavities are regions of empty Delaunay cells of the SA model:
    CASTp's voids are exactly the bounded components of the complement of the SA
    union found through the α-shape; SA volumes and areas are of the space a probe
    centre can reach, measured analytically over those cells (CASTp uses the
    fractional inclusion–exclusion of Liang et al.; here the exact power-cell
    decomposition, which agrees for voids and, unlike the fractional sum, is
    also exact on a pocket's cells, whose mouth is not covered).

    *Different from CASTp.*  (1) Pockets: CASTp finds them by the *discrete flow*
    of Edelsbrunner, Facello and Liang (1998) on the empty Delaunay cells of the
    α-shape (a cell flows into the neighbour across a facet that separates it from its
    own orthocentre, and a pocket is a group of cells whose flow does not reach the
    outside); here a pocket is the
    growth-model pocket of Notes §23.1 (a dent that closes into a void later in the
    filtration), its cells those of the void it becomes.  The two coincide for the
    clear-cut cases but not in general (nested pockets are all listed here; shallow
    dents that never close are no pocket here).  (2) The second volume: CASTp reports
    the *molecular-surface* (Richards/Connolly) volume, bounded by the surface the
    probe sphere sweeps out; here it is the vdW free space of the same cells, bounded
    by the bare vdW spheres.  It counts crevices between atoms inside the cells that
    the probe cannot reach and omits the parts of the probe's sweep beyond the cells,
    so it is not MS volume and no inequality holds between them in general; both
    exceed the SA volume.  (3) Mouth area is the free area of the mouth triangles in
    the SA model, perimeter the length of its rim (CASTp gives SA and MS mouth areas
    and circumferences).

    References
    ----------
    .. [1] J. Liang, H. Edelsbrunner, P. Fu, P. V. Sudhakar and S. Subramaniam,
           "Analytical shape computation of macromolecules: II. Inaccessible cavities in
           proteins", *Proteins* 33(1):18-29, 1998.
    .. [2] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
           construction of pockets in macromolecules", *Discrete Appl. Math.* 88:83-102,
           1998. doi:10.1016/S0166-218X(98)00067-5
    .. [3] W. Tian, C. Chen, X. Lei, J. Zhao and J. Liang, "CASTp 3.0: computed atlas of
           surface topography of proteins", *Nucleic Acids Res.* 46(W1):W363-W367, 2018.
           doi:10.1093/nar/gky473

    Examples
    --------
    >>> from shapelab.datasets import bowl
    >>> rep = report(bowl(), 0.0, name="bowl")  # the bowl's dent is one pocket
    >>> len(rep), rep.rows[0].kind, rep.rows[0].mouths, round(rep.rows[0].volume_sa, 1)
    (1, 'pocket', 1, 367.8)
    """
    import math

    import numpy as np

    from .balls import Balls
    from .cavities import pockets as find_pockets
    from .cavities import voids as find_voids
    from .cavities.freespace import free_area, free_space
    from .filtration import alpha_filtration
    from .io import PDBStructure, radius_notes
    from .ranking import DEFAULT_MIN_PERSISTENCE, DEFAULT_MIN_VOLUME, pocket_features, rank_order, rank_score

    if method not in ("growth", "flow"):
        raise ValueError(f"method must be 'growth' or 'flow', got {method!r}")
    if rank not in ("none", "score"):
        raise ValueError(f"rank must be 'none' or 'score', got {rank!r}")
    if min_persistence is None:
        min_persistence = 0.0 if rank == "none" else DEFAULT_MIN_PERSISTENCE
    if min_volume is None:
        min_volume = 0.0 if rank == "none" else DEFAULT_MIN_VOLUME
    min_persistence = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    min_volume = as_finite_scalar(min_volume, "min_volume", nonnegative=True)
    if top is not None:
        top = as_positive_int(top, "top")
    if isinstance(probe, (bool, np.bool_)) or not isinstance(probe, (int, float, np.integer, np.floating)):
        raise TypeError(f"probe must be a real number (Å), got {type(probe).__name__}")
    probe = float(probe)
    if not math.isfinite(probe) or probe < 0:
        raise ValueError(f"probe must be a finite non-negative radius (Å), got {probe!r}")
    if isinstance(structure, PDBStructure):
        balls = structure.balls
        vdw_r = balls.radii - structure.probe
    elif isinstance(structure, Balls):
        balls = structure
        vdw_r = balls.radii
    else:
        raise TypeError(f"structure must be a PDBStructure or Balls, got {type(structure).__name__}")
    if balls.dim != 3:
        raise ValueError(f"report needs 3D balls (atoms), got dim={balls.dim}")
    name = "structure" if name is None else str(name)
    vdw = Balls(balls.centers, np.maximum(vdw_r, 0.0))
    sa = Balls(balls.centers, vdw.radii + probe)
    F = alpha_filtration(sa)
    # every cavity, then the persistence filter (the same test as pockets(min_persistence=)),
    # so that the report can say how many it leaves out
    V_all = find_voids(F, tau)
    P_all = find_pockets(F, tau, method=method)
    V = [v for v in V_all if v.persistence >= min_persistence]
    P = [p for p in P_all if p.persistence >= min_persistence]
    feats = [("void", v, v.born, v.dies) for v in V] + [("pocket", p, p.closes_at, p.fills_at) for p in P]

    ids = np.unique(np.concatenate([f.cell_ids for _, f, _, _ in feats])) if feats else np.zeros(0, np.int64)
    simp = np.asarray(F.simplices(3), dtype=np.int64)
    fs_sa = free_space(F, tau, simp[ids])
    fs_vdw = free_space(vdw, 0.0, simp[ids])
    # every mouth triangle once: its free area and rim in the SA model
    mouths = [
        np.sort(np.asarray(f.mouth, dtype=np.int64).reshape(-1, 3), axis=1) for k, f, _, _ in feats if k == "pocket"
    ]
    tris = np.unique(np.concatenate(mouths), axis=0) if mouths else np.zeros((0, 3), np.int64)
    fa = free_area(F, tau, tris)
    mouth_count = dict(zip((id(p) for p in P), _mouth_counts([p.mouth for p in P])))
    tri_row = {tuple(t): k for k, t in enumerate(tris.tolist())}

    # the SA wall contacts grouped by cell row (stably, so each group keeps the
    # contacts' order): a feature gathers its own instead of scanning all of them
    by_cell = np.argsort(fs_sa.contact_cell, kind="stable")
    first = np.searchsorted(fs_sa.contact_cell[by_cell], np.arange(len(ids) + 1))

    labelled = isinstance(structure, PDBStructure)
    raw = []
    for kind, f, birth, death in feats:
        rows = np.searchsorted(ids, f.cell_ids).astype(np.int64)  # its rows of fs_sa, in its own order
        sel = _contacts_of(np.unique(rows), first, by_cell)
        # the wall area per lining candidate, summed in contact order as a bincount over all atoms would
        balls, at = np.unique(fs_sa.contact_ball[sel], return_inverse=True)
        per_ball = np.bincount(at.ravel(), weights=fs_sa.contact_wall[sel], minlength=len(balls))
        lining = balls[per_ball > LINING_AREA_RTOL * 4.0 * np.pi * sa.radii[balls] ** 2]
        n_mouths, m_area, m_rim = 0, 0.0, 0.0
        if kind == "pocket":
            n_mouths = mouth_count[id(f)]
            mrows = [
                tri_row[tuple(t)] for t in np.sort(np.asarray(f.mouth, dtype=np.int64).reshape(-1, 3), axis=1).tolist()
            ]
            m_area, m_rim = float(fa.measure[mrows].sum()), float(fa.wall[mrows].sum())
        if labelled:
            s = structure
            names = tuple(str(s.atom_names[i]) for i in lining)
            keys = dict.fromkeys(
                (str(s.chains[i]), str(s.residue_names[i]), int(s.residue_numbers[i]), str(s.insertion_codes[i]))
                for i in lining
            )
            res, codes = tuple(k[:3] for k in keys), tuple(k[3] for k in keys)
        else:
            names = ("",) * len(lining)
            res, codes = (), ()
        raw.append(
            dict(
                kind=kind,
                volume_sa=float(fs_sa.measure[rows].sum()),
                area_sa=float(fs_sa.wall[rows].sum()),
                volume_vdw=float(fs_vdw.measure[rows].sum()),
                area_vdw=float(fs_vdw.wall[rows].sum()),
                mouths=n_mouths,
                mouth_area=m_area,
                mouth_perimeter=m_rim,
                birth=float(birth),
                death=float(death),
                lining_atoms=tuple(int(i) for i in lining),
                lining_atom_names=names,
                lining_residues=res,
                lining_insertion_codes=codes,
            )
        )
    # CASTp's order (voids first, each kind by SA volume; a stable sort), the order of
    # rank="none" and the last tie-break of rank="score" (after the score, then volume)
    raw.sort(key=lambda d: (d["kind"] != "void", -d["volume_sa"]))
    if min_volume > 0:
        raw = [d for d in raw if d["volume_sa"] >= min_volume]
    if rank == "none":
        raw = raw[:top]
    else:
        # the features of the cavities the filters keep only: the rays cost
        # O(cavities x atoms within reach), and most cavities are under min_volume
        feat = pocket_features(
            vdw,
            [d["lining_atoms"] for d in raw],
            volume=[d["volume_sa"] for d in raw],
            area=[d["area_sa"] for d in raw],
            mouth_area=[d["mouth_area"] for d in raw],
            persistence=[d["death"] - d["birth"] for d in raw],
        )
        score = rank_score(feat)
        order = rank_order(feat, min_persistence=0.0, min_volume=0.0, top=top)  # filtered above
        raw = [
            dict(
                raw[k],
                score=float(score[k]),
                buriedness=float(feat.buriedness[k]),
                depth=float(feat.depth[k]),
                openness=float(feat.openness[k]),
            )
            for k in order.tolist()
        ]
    rows = tuple(CavityRow(id=k + 1, **d) for k, d in enumerate(raw))
    kept = [f"persistence ≥ {min_persistence:g} Å²" if min_persistence > 0 else ""]
    kept += [f"SA volume ≥ {min_volume:g} Å³" if min_volume > 0 else "", f"the first {top}" if top else ""]
    kept = ", ".join(k for k in kept if k)
    return CavityReport(
        rows=rows,
        probe=probe,
        name=name,
        tau=float(tau),
        structure=structure,
        rank=rank,
        found=len(V_all) + len(P_all),
        filters=kept,
        method=method,
        notes=radius_notes(structure) if labelled else (),
    )


# ============================================================ not a program
if __name__ == "__main__":  # python -m shapelab.report: say where the command line is
    import sys

    sys.exit("shapelab.report is the report, not a program: run python -m shapelab report FILE")
