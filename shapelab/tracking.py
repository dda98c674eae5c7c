"""Cavities along a molecular-dynamics trajectory: each frame measured, the cavities
followed from frame to frame (Notes §23.1).

Pockets and voids open and close as a protein moves (adenylate kinase closing over its
substrates is the textbook case).  Each frame's selected atoms become balls of their van
der Waals radius plus the probe (:func:`selection_radii`), and the frame is measured
exactly (:func:`frame_measures`): the union's volume and surface area
(:func:`shapelab.union_measure`), its voids (:func:`shapelab.voids`) and pockets
(:func:`shapelab.pockets`).  The cavities are then followed from frame to frame by the
atoms that line them (:func:`track_cavities`), and :func:`tracked_measures` puts the
frames and the tracks into one :class:`TrajectoryMeasures`.

This module reads no file and imports no MDAnalysis: a frame is an array of positions
and the atoms an MDAnalysis ``AtomGroup`` given by the caller.  Reading a trajectory,
in one process, in many or on a Dask cluster, is the research tool
:func:`shapelab.trajectory_measures` (:mod:`shapelab.tools.trajectory`), which calls
these functions.

Tracking rule
-------------
Each analysed frame's cavities (voids and pockets together) are matched to those of the
*previous analysed frame* by the Jaccard index of their lining atoms (indices into the
selection, the same atoms in every frame):
:math:`J(A, B) = |A \\cap B| / |A \\cup B|`.  Pairs with :math:`J \\ge` ``min_overlap``
are taken greedily, largest :math:`J` first (ties: the earlier cavity of each frame),
each cavity at most once; a matched cavity continues its predecessor's track, an
unmatched one starts a new track.  A pocket that closes into a void keeps its track
(its ``kinds`` then read ``"pocket"`` then ``"void"``).

Limits of the rule: a cavity that splits continues on one branch only (the other
starts a new track), two that merge continue one track and end the other; a cavity
absent from one analysed frame (a flicker, or ``step`` too large for the motion) ends
its track and comes back as a new one; the threshold is a choice, not a property of
the protein (0.5: more than half of the union of the two linings is shared).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._toolkit.validate import as_finite_scalar, readonly

__all__ = [
    "TrajectoryMeasures",
    "FrameCavity",
    "CavityTrack",
    "track_cavities",
    "selection_radii",
    "frame_measures",
    "measure_frames",
    "tracked_measures",
]


@dataclass(frozen=True)
class FrameCavity:
    """One void or pocket of one frame.

    Attributes
    ----------
    frame : int
        The trajectory frame (index into the whole trajectory).
    kind : str
        ``"void"`` or ``"pocket"``.
    lining : ndarray, int
        Indices (into the selected atoms) of the balls lining it (``Void.lining``,
        ``Pocket.lining``).
    volume : float
        Its free volume (Å³) in the SA model (``Void.volume``, ``Pocket.volume``).
    track : int
        The id of its :class:`CavityTrack`.

    See Also
    --------
    trajectory_measures : makes them.
    shapelab.Void, shapelab.Pocket : the cavities of one structure.
    """

    frame: int
    kind: str
    lining: np.ndarray
    volume: float
    track: int = -1


@dataclass(frozen=True)
class CavityTrack:
    """A cavity followed across consecutive analysed frames.

    Attributes
    ----------
    id : int
        Its number, in order of first appearance.
    frames : tuple of int
        The frames it is seen in, consecutive analysed frames.
    kinds : tuple of str
        ``"void"`` or ``"pocket"`` in each of these frames.
    volumes : tuple of float
        Its volume (Å³) in each of these frames.
    overlaps : tuple of float
        The Jaccard index of its lining with that of the frame before (one fewer than
        ``frames``).

    See Also
    --------
    track_cavities : the rule that makes them.
    """

    id: int
    frames: tuple
    kinds: tuple
    volumes: tuple
    overlaps: tuple

    def __len__(self) -> int:
        return len(self.frames)


@dataclass(frozen=True)
class TrajectoryMeasures:
    """Per-frame measures of a trajectory and its cavities tracked across frames.

    Attributes
    ----------
    frame, time : ndarray
        The frames analysed (indices into the trajectory) and their times (ps, as
        MDAnalysis reports them).
    area, volume : ndarray
        Surface area (Å²) and volume (Å³) of the union of the balls (radius: van der
        Waals radius + ``probe``), exact.
    n_voids, n_pockets : ndarray, int
        The number of voids and of pockets in each frame.
    largest_void : ndarray
        The volume (Å³) of the largest void of each frame, 0 without a void.
    cavities : tuple of tuple of FrameCavity
        Each frame's voids then pockets (in the order of :func:`shapelab.voids` and
        :func:`shapelab.pockets`), with their track ids.
    tracks : tuple of CavityTrack
        The cavities followed across frames (:func:`track_cavities`).
    probe, min_overlap : float
        The probe radius (Å) and the Jaccard threshold used.
    n_atoms : int
        The number of selected atoms (balls per frame).

    See Also
    --------
    trajectory_measures : computes it.
    """

    frame: np.ndarray
    time: np.ndarray
    area: np.ndarray
    volume: np.ndarray
    n_voids: np.ndarray
    largest_void: np.ndarray
    n_pockets: np.ndarray
    cavities: tuple
    tracks: tuple
    probe: float
    min_overlap: float
    n_atoms: int

    def __len__(self) -> int:
        return len(self.frame)

    def rows(self) -> list:
        """The per-frame table as a list of dicts (frame, time, area, volume, voids,
        largest_void, pockets), in frame order."""
        return [
            {
                "frame": int(self.frame[i]),
                "time": float(self.time[i]),
                "area": float(self.area[i]),
                "volume": float(self.volume[i]),
                "voids": int(self.n_voids[i]),
                "largest_void": float(self.largest_void[i]),
                "pockets": int(self.n_pockets[i]),
            }
            for i in range(len(self))
        ]

    def to_pandas(self):
        """The per-frame table as a :class:`pandas.DataFrame` (needs pandas)."""
        import pandas as pd

        return pd.DataFrame(self.rows())


# ============================================================================ radii
def _pdb_name(name: str, residue: str) -> str:
    """An MD atom name in the PDB's columns 13-16, as MDAnalysis' PDB writer places it:
    names of four characters as they are, shorter ones after one blank, except an ion
    named as its residue (``CA`` in ``CA``), left-justified."""
    if len(name) >= 4:
        return name[:4]
    if name == residue:
        return name.ljust(4)
    return (" " + name).ljust(4)


def selection_radii(atoms, default_radius=None) -> np.ndarray:
    """The van der Waals radius of each atom of an MDAnalysis AtomGroup (Notes §23.1).

    The element is the topology's ``elements`` when it has them, otherwise read from the
    atom name as :func:`shapelab.io.read_pdb` reads a name (:func:`shapelab.io.element_from_name`,
    the name placed in columns 13-16 as MDAnalysis writes it); its radius is
    :func:`shapelab.io.vdw_radius` (Bondi 1964, Mantina et al. 2009, and Alvarez 2013 for
    the transition metals, lanthanides and actinides those two lack).

    Parameters
    ----------
    atoms : MDAnalysis.AtomGroup
        The atoms.
    default_radius : float, optional
        The radius of an element no table lists (Pm, past Es, an unknown symbol);
        without it such an atom raises.

    Returns
    -------
    ndarray
        One radius (Å) per atom, float64.

    Raises
    ------
    ValueError
        An atom whose element cannot be read or has no radius (naming the atom).

    See Also
    --------
    shapelab.io.vdw_radius : the table.
    shapelab.io.read_pdb : the same radii for a PDB file.

    References
    ----------
    A. Bondi, "van der Waals Volumes and Radii", *J. Phys. Chem.* **68**, 441–451 (1964).
    M. Mantina, A. C. Chamberlin, R. Valero, C. J. Cramer, D. G. Truhlar, "Consistent
    van der Waals Radii for the Whole Main Group", *J. Phys. Chem. A* **113**, 5806–5812
    (2009), Table 12.
    S. Alvarez, "A cartography of the van der Waals territories", *Dalton Trans.* **42**,
    8617–8636 (2013), Table 1.
    """
    from .io import element_from_name, vdw_radius

    if default_radius is not None:
        default_radius = as_finite_scalar(default_radius, "default_radius", positive=True)
    names = [str(n) for n in atoms.names]
    resnames = [str(r).upper() for r in atoms.resnames]
    elements = None
    if hasattr(atoms, "elements"):
        els = [str(e).strip() for e in atoms.elements]
        if all(els):
            elements = els
    if elements is None:
        elements = [element_from_name(_pdb_name(n.strip(), r), r) for n, r in zip(names, resnames)]
    rad = np.empty(len(names), dtype=np.float64)
    for i, e in enumerate(elements):
        try:
            rad[i] = vdw_radius(e) if e else float("nan")
        except ValueError:
            rad[i] = float("nan")
        if not rad[i] == rad[i]:
            if default_radius is None:
                raise ValueError(
                    f"atom {i} of the selection (name {names[i]!r}, residue {resnames[i]}, element {e!r}) has no "
                    f"van der Waals radius in Bondi's (1964), Mantina et al.'s (2009) or Alvarez's (2013) table; "
                    "pass default_radius="
                )
            rad[i] = default_radius
    return rad


# ============================================================================ one frame
def frame_measures(x, radii, probe: float, min_persistence: float = 0.0) -> dict:
    """Area, volume, voids and pockets of one frame's balls (Notes §23.1).

    Parameters
    ----------
    x : array_like, shape (n, 3)
        The atoms' positions in this frame (Å).
    radii : array_like, shape (n,)
        Their van der Waals radii (Å), :func:`selection_radii`.
    probe : float
        Probe radius (Å) added to every radius.
    min_persistence : float, default 0.0
        Passed to :func:`shapelab.pockets`.

    Returns
    -------
    dict
        ``area`` and ``volume`` of the union of the balls (exact,
        :func:`shapelab.union_measure`), and ``cavities``: one ``(kind, lining,
        volume)`` per void then per pocket, ``kind`` ``"void"`` or ``"pocket"``,
        ``lining`` the indices of the balls lining it.

    See Also
    --------
    measure_frames : this for the frames of a trajectory.
    shapelab.union_measure, shapelab.voids, shapelab.pockets : what is measured.

    Examples
    --------
    >>> import numpy as np
    >>> row = frame_measures(np.eye(3) * 1.0, [1.0, 1.0, 1.0], probe=0.0)
    >>> round(row["volume"], 3), row["cavities"]
    (11.205, [])
    """
    from .balls import Balls
    from .cavities import pockets, voids
    from .filtration import alpha_filtration
    from .measure import union_measure

    F = alpha_filtration(Balls(np.asarray(x, dtype=np.float64), np.asarray(radii, dtype=np.float64) + probe))
    m = union_measure(F)
    vs = voids(F)
    ps = pockets(F, min_persistence=min_persistence)
    return {
        "area": float(m.boundary),
        "volume": float(m.measure),
        "cavities": [("void", np.asarray(v.lining, dtype=np.int64), float(v.volume)) for v in vs]
        + [("pocket", np.asarray(p.lining, dtype=np.int64), float(p.volume)) for p in ps],
    }


def measure_frames(u, atoms, radii, frames, probe: float, min_persistence: float = 0.0) -> list:
    """:func:`frame_measures` of each of ``frames``, in order: the serial path.

    Parameters
    ----------
    u : MDAnalysis.Universe
        The trajectory, already open.
    atoms : MDAnalysis.AtomGroup
        The selected atoms of ``u``.
    radii : array_like, shape (len(atoms),)
        Their van der Waals radii (:func:`selection_radii`).
    frames : iterable of int
        The frames measured (indices into ``u.trajectory``).
    probe, min_persistence : float
        As in :func:`frame_measures`.

    Returns
    -------
    list of dict
        One :func:`frame_measures` row per frame, with its ``frame`` and ``time``.

    See Also
    --------
    tracked_measures : the rows made into a :class:`TrajectoryMeasures`.
    shapelab.trajectory_measures : opens the trajectory and runs this, serially or in parallel.
    """
    out = []
    for f in frames:
        ts = u.trajectory[int(f)]
        row = frame_measures(atoms.positions, radii, probe, min_persistence)
        row.update(frame=int(f), time=float(ts.time))
        out.append(row)
    return out


# ============================================================================ tracking
def _jaccard(a: np.ndarray, b: np.ndarray) -> float:
    inter = np.intersect1d(a, b, assume_unique=True).size
    union = a.size + b.size - inter
    return inter / union if union else 0.0


def track_cavities(linings, min_overlap: float = 0.5) -> list:
    """Follow cavities across frames by the overlap of their lining atoms.

    Parameters
    ----------
    linings : sequence of sequence of array_like of int
        For each frame in order, the lining atoms of each of its cavities.
    min_overlap : float, default 0.5
        The least Jaccard index :math:`|A\\cap B|/|A\\cup B|` of two linings for a
        cavity to continue one of the frame before; in (0, 1].

    Returns
    -------
    ids : list of list of int
        For each frame, the track id of each cavity (ids count from 0 in order of
        first appearance).
    overlaps : list of list of float
        For each frame, the Jaccard index of each cavity with the one it continues
        (NaN where it starts a track).

    See Also
    --------
    trajectory_measures : tracks the voids and pockets of a trajectory with it.

    Notes
    -----
    Pairs of consecutive frames are matched greedily, largest Jaccard index first
    (ties broken by the earlier cavity of the earlier frame, then of the later one),
    each cavity at most once; an unmatched cavity starts a new track.  A split
    continues on one branch only, a merge ends one of the two tracks, and a cavity
    missing from one frame starts a new track when it comes back (module docstring).

    References
    ----------
    .. [1] P. Jaccard, "The distribution of the flora in the alpine zone", *New Phytologist*
       **11**, 37–50 (1912), doi:10.1111/j.1469-8137.1912.tb05611.x.

    Examples
    --------
    >>> ids, _ = track_cavities([[[1, 2, 3]], [[2, 3, 4], [7, 8]], [[7, 8, 9]]])
    >>> ids
    [[0], [0, 1], [1]]
    """
    min_overlap = as_finite_scalar(min_overlap, "min_overlap", positive=True)
    if min_overlap > 1:
        raise ValueError(f"min_overlap must lie in (0, 1], got {min_overlap}")
    sets = [[np.unique(np.asarray(c, dtype=np.int64)) for c in frame] for frame in linings]
    ids: list = []
    overlaps: list = []
    next_id = 0
    for t, frame in enumerate(sets):
        cur = [-1] * len(frame)
        ov = [float("nan")] * len(frame)
        if t > 0:
            prev = sets[t - 1]
            pairs = [
                (-j, a, b)
                for a, pa in enumerate(prev)
                for b, cb in enumerate(frame)
                if (j := _jaccard(pa, cb)) >= min_overlap
            ]
            used = set()
            for negj, a, b in sorted(pairs):
                if a in used or cur[b] != -1:
                    continue
                used.add(a)
                cur[b] = ids[t - 1][a]
                ov[b] = -negj
        for b in range(len(frame)):
            if cur[b] == -1:
                cur[b] = next_id
                next_id += 1
        ids.append(cur)
        overlaps.append(ov)
    return ids, overlaps


def tracked_measures(rows, probe: float, min_overlap: float, n_atoms: int) -> TrajectoryMeasures:
    """The measured frames, their cavities tracked (:func:`track_cavities`), as one table.

    Parameters
    ----------
    rows : list of dict
        The frames in frame order, as :func:`measure_frames` gives them.
    probe : float
        The probe radius the frames were measured with (Å).
    min_overlap : float
        Jaccard threshold of the tracking rule, in (0, 1].
    n_atoms : int
        The number of balls per frame.

    Returns
    -------
    TrajectoryMeasures

    See Also
    --------
    track_cavities : the tracking rule.

    Examples
    --------
    >>> import numpy as np
    >>> rows = [dict(frame=f, time=2.0 * f, area=1.0, volume=1.0,
    ...              cavities=[("void", np.array([1, 2, 3]), 0.5)]) for f in (0, 1)]
    >>> m = tracked_measures(rows, probe=1.4, min_overlap=0.5, n_atoms=4)
    >>> len(m), m.n_voids.tolist(), [len(t) for t in m.tracks]
    (2, [1, 1], [2])
    """
    ids, overlaps = track_cavities([[c[1] for c in r["cavities"]] for r in rows], min_overlap)
    cavities = []
    by_track: dict = {}
    for r, fid, fov in zip(rows, ids, overlaps):
        these = []
        for (kind, lining, vol), tid, ov in zip(r["cavities"], fid, fov):
            these.append(FrameCavity(r["frame"], kind, readonly(lining, np.int64), vol, tid))
            by_track.setdefault(tid, []).append((r["frame"], kind, vol, ov))
        cavities.append(tuple(these))
    tracks = tuple(
        CavityTrack(
            tid,
            tuple(e[0] for e in v),
            tuple(e[1] for e in v),
            tuple(e[2] for e in v),
            tuple(e[3] for e in v[1:]),
        )
        for tid, v in sorted(by_track.items())
    )

    def col(key, dtype=np.float64):
        return readonly(np.array([r[key] for r in rows], dtype=dtype), dtype)

    nv = [sum(c[0] == "void" for c in r["cavities"]) for r in rows]
    largest = [max([c[2] for c in r["cavities"] if c[0] == "void"], default=0.0) for r in rows]
    return TrajectoryMeasures(
        frame=col("frame", np.int64),
        time=col("time"),
        area=col("area"),
        volume=col("volume"),
        n_voids=readonly(np.array(nv, dtype=np.int64), np.int64),
        largest_void=readonly(np.array(largest, dtype=np.float64), np.float64),
        n_pockets=readonly(np.array([len(r["cavities"]) - k for r, k in zip(rows, nv)], dtype=np.int64), np.int64),
        cavities=tuple(cavities),
        tracks=tracks,
        probe=float(probe),
        min_overlap=float(min_overlap),
        n_atoms=int(n_atoms),
    )
