"""Area, volume, voids and pockets along a molecular-dynamics trajectory (Notes §23.1).

Pockets and voids open and close as a protein moves (adenylate kinase closing over its
substrates is the textbook case).  :func:`trajectory_measures` reads a trajectory with
MDAnalysis (Michaud-Agrawal et al. 2011; Gowers et al. 2016), gives every selected atom
a ball of its van der Waals radius plus the probe, and measures each frame exactly: the
union's volume and surface area (:func:`shapelab.union_measure`), its voids
(:func:`shapelab.voids`) and pockets (:func:`shapelab.pockets`).  The cavities are then
followed from frame to frame by the atoms that line them.

MDAnalysis is an optional dependency: ``pip install "shapelab[md]"``.  It is imported
only when a trajectory is read, so ``import shapelab.trajectory`` works without it.

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

import os
import sys
from dataclasses import dataclass

import numpy as np

from ._toolkit.validate import as_finite_scalar, as_positive_int, readonly

__all__ = [
    "trajectory_measures",
    "TrajectoryMeasures",
    "FrameCavity",
    "CavityTrack",
    "track_cavities",
    "selection_radii",
]

_MD_HINT = 'trajectory_measures needs MDAnalysis: pip install "shapelab[md]" (or pip install "MDAnalysis>=2.7")'


def _mdanalysis():
    try:
        import MDAnalysis
    except ImportError as exc:  # pragma: no cover - exercised only without MDAnalysis
        raise ImportError(_MD_HINT) from exc
    return MDAnalysis


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
def _frame_measures(x, radii, probe: float, min_persistence: float = 0.0) -> dict:
    """Area, volume, voids and pockets of one frame's balls (radius ``radii + probe``)."""
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


def _open(topology, trajectory):
    mda = _mdanalysis()
    if isinstance(topology, mda.Universe):
        return topology
    return mda.Universe(topology) if trajectory is None else mda.Universe(topology, trajectory)


def _measure_frames(u, atoms, radii, frames, probe, min_persistence) -> list:
    out = []
    for f in frames:
        ts = u.trajectory[int(f)]
        row = _frame_measures(atoms.positions, radii, probe, min_persistence)
        row.update(frame=int(f), time=float(ts.time))
        out.append(row)
    return out


def _init_worker() -> None:
    """A worker process's initializer: one thread for the free space unless
    ``SHAPELAB_THREADS`` says otherwise (the workers already share out the CPUs)."""
    os.environ.setdefault("SHAPELAB_THREADS", "1")


def _worker_block(topology, trajectory, select, default_radius, frames, probe, min_persistence) -> list:
    """One worker's task: open the trajectory in this process, measure a block of frames."""
    u = _open(topology, trajectory)
    atoms = u.select_atoms(select)
    return _measure_frames(u, atoms, selection_radii(atoms, default_radius), frames, probe, min_persistence)


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


# ============================================================================ the API
def trajectory_measures(
    topology,
    trajectory=None,
    *,
    select="protein and not name H*",
    probe=1.4,
    start=0,
    stop=None,
    step=1,
    jobs=1,
    min_overlap=0.5,
    min_persistence=0.0,
    default_radius=None,
    progress=True,
    client=None,
    scheduler=None,
) -> TrajectoryMeasures:
    """Area, volume, voids and pockets of every frame of an MD trajectory (Notes §23.1).

    Each frame's selected atoms become balls of radius van der Waals + ``probe`` (the
    solvent-accessible model of Lee & Richards 1971, as :func:`shapelab.report`); the
    union's volume and surface area are exact (:func:`shapelab.union_measure`), its
    voids and pockets those of the growth model (:func:`shapelab.voids`,
    :func:`shapelab.pockets`) with their free volumes.  Cavities are then tracked
    across frames by the Jaccard index of their lining atoms (:func:`track_cavities`).

    Parameters
    ----------
    topology : str, os.PathLike or MDAnalysis.Universe
        A topology file MDAnalysis reads (PSF, GRO, PDB, TPR, ...), or a Universe
        (then ``trajectory`` must be None).
    trajectory : str, os.PathLike or list of them, optional
        The coordinates (DCD, XTC, TRR, ...); None: those of the topology file.
    select : str, default "protein and not name H*"
        MDAnalysis selection of the atoms made into balls.
    probe : float, default 1.4
        Probe radius (Å) added to every van der Waals radius; 0 gives the vdW model.
    start, stop, step : int, optional
        Frames ``range(start, stop, step)`` of the trajectory (``stop`` None: to the end).
    jobs : int, default 1
        Worker processes (``spawn``); they measure contiguous blocks of frames, each
        block opening the trajectory anew (a Universe given is pickled to them).  The
        frames are measured independently and the tracks are made afterwards, in frame
        order: the result is the same for every ``jobs``.
    min_overlap : float, default 0.5
        Jaccard threshold of the tracking rule, in (0, 1].
    min_persistence : float, default 0.0
        Passed to :func:`shapelab.pockets`.
    default_radius : float, optional
        Radius for an element without a van der Waals radius (see :func:`selection_radii`).
    progress : bool, default True
        Report progress on standard error (a tqdm bar when tqdm is installed).
    client : dask.distributed.Client, optional
        Measure the blocks of frames on this Dask cluster instead of local processes
        (``jobs`` must then be 1): a few blocks per worker thread, each opening the
        trajectory anew on its worker, so the workers must read ``topology`` and
        ``trajectory`` at the same paths (a shared file system; a Universe given is
        pickled, and MDAnalysis pickles file-based Universes by their file names).
        The result is that of ``jobs=1``.  The client is left open.
    scheduler : str, optional
        The address of a Dask scheduler (``"tcp://HOST:8786"``): connect, run as with
        ``client``, disconnect.  Dask is optional: ``pip install "shapelab[dask]"``.

    Returns
    -------
    TrajectoryMeasures
        The per-frame table (frame, time, area, volume, voids, largest void, pockets),
        each frame's cavities and the tracks, in frame order.

    Raises
    ------
    ImportError
        MDAnalysis is not installed (``pip install "shapelab[md]"``), or dask.distributed
        for ``client``/``scheduler`` (``pip install "shapelab[dask]"``).
    TypeError
        An argument of the wrong type (named in the message).
    ValueError
        ``probe`` negative, ``step``/``jobs`` below 1, ``min_overlap`` outside (0, 1],
        a selection with fewer than 4 atoms, an atom without a radius; ``client`` and
        ``scheduler`` both, or either with ``jobs`` > 1.

    See Also
    --------
    track_cavities : the tracking rule.
    shapelab.report : the cavities of one structure, as a table.
    shapelab.union_measure, shapelab.voids, shapelab.pockets : what is measured per frame.

    Notes
    -----
    The radii are those :func:`shapelab.io.read_pdb` gives (Bondi 1964): from the
    topology's elements, or read from the atom names as a PDB reader reads them.
    Tracking follows the previous *analysed* frame: with a large ``step`` a cavity
    that moves much between two analysed frames starts a new track.

    References
    ----------
    .. [1] N. Michaud-Agrawal, E. J. Denning, T. B. Woolf, O. Beckstein, "MDAnalysis: A
       toolkit for the analysis of molecular dynamics simulations", *J. Comput. Chem.*
       **32**, 2319–2327 (2011), doi:10.1002/jcc.21787.
    .. [2] R. J. Gowers et al., "MDAnalysis: A Python package for the rapid analysis of
       molecular dynamics simulations", *Proc. 15th Python in Science Conf.* (SciPy
       2016), 98–105, doi:10.25080/Majora-629e541a-00e.
    .. [3] J. Liang, H. Edelsbrunner, P. Fu, P. V. Sudhakar, S. Subramaniam, "Analytical
       shape computation of macromolecules: II. Inaccessible cavities in proteins",
       *Proteins* **33**, 18–29 (1998), doi:10.1002/(SICI)1097-0134(19981001)33:1<18::AID-PROT2>3.0.CO;2-H.
    """
    if not isinstance(select, str):
        raise TypeError(f"select must be an MDAnalysis selection string, got {type(select).__name__}")
    if isinstance(probe, (bool, np.bool_)) or not isinstance(probe, (int, float, np.integer, np.floating)):
        raise TypeError(f"probe must be a real number (Å), got {type(probe).__name__}")
    probe = as_finite_scalar(probe, "probe", nonnegative=True)
    start = as_positive_int(start, "start", minimum=0)
    if stop is not None:
        stop = as_positive_int(stop, "stop", minimum=0)
    step = as_positive_int(step, "step")
    jobs = as_positive_int(jobs, "jobs")
    min_overlap = as_finite_scalar(min_overlap, "min_overlap", positive=True)
    if min_overlap > 1:
        raise ValueError(f"min_overlap must lie in (0, 1], got {min_overlap}")
    min_persistence = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    if not isinstance(progress, (bool, np.bool_)):
        raise TypeError(f"progress must be a bool, got {type(progress).__name__}")
    mda = _mdanalysis()
    if isinstance(topology, mda.Universe):
        if trajectory is not None:
            raise TypeError("trajectory must be None when topology is an MDAnalysis Universe")
    elif not isinstance(topology, (str, os.PathLike)):
        raise TypeError(f"topology must be a path or an MDAnalysis Universe, got {type(topology).__name__}")
    elif trajectory is not None and not (
        isinstance(trajectory, (str, os.PathLike))
        or (isinstance(trajectory, (list, tuple)) and all(isinstance(t, (str, os.PathLike)) for t in trajectory))
    ):
        raise TypeError(f"trajectory must be a path, a list of paths or None, got {type(trajectory).__name__}")

    from ._toolkit.cluster import cluster_client

    with cluster_client(client, scheduler, jobs, "trajectory_measures") as cluster:
        return _measure(
            topology,
            trajectory,
            select,
            probe,
            start,
            stop,
            step,
            jobs,
            min_overlap,
            min_persistence,
            default_radius,
            progress,
            cluster,
        )


def _measure(
    topology,
    trajectory,
    select,
    probe,
    start,
    stop,
    step,
    jobs,
    min_overlap,
    min_persistence,
    default_radius,
    progress,
    cluster,
) -> TrajectoryMeasures:
    """The body of :func:`trajectory_measures`, its arguments checked; ``cluster`` a Dask client or None."""
    u = _open(topology, trajectory)
    atoms = u.select_atoms(select)
    if len(atoms) < 4:
        raise ValueError(f"select {select!r} picks {len(atoms)} atoms; at least 4 are needed")
    radii = selection_radii(atoms, default_radius)
    frames = list(range(*slice(start, stop, step).indices(len(u.trajectory))))
    bar = _Progress(len(frames), bool(progress))
    rows: list = []
    try:
        if cluster is not None:
            from ._toolkit.cluster import cluster_threads, distributed_module

            distributed = distributed_module("trajectory_measures")
            n = min(4 * cluster_threads(cluster), len(frames))
            blocks = [b.tolist() for b in np.array_split(np.asarray(frames), n)] if frames else []
            args = (topology, trajectory, select, default_radius)
            futs = [cluster.submit(_worker_block, *args, b, probe, min_persistence, pure=False) for b in blocks]
            try:
                for fut in distributed.as_completed(futs, loop=cluster.loop):
                    got = fut.result()
                    rows += got
                    bar.update(len(got))
            except BaseException:
                cluster.cancel(futs)
                raise
            rows.sort(key=lambda r: r["frame"])
        elif jobs == 1 or len(frames) <= 1:
            for f in frames:
                rows += _measure_frames(u, atoms, radii, [f], probe, min_persistence)
                bar.update()
        else:
            import multiprocessing as mp
            from concurrent.futures import ProcessPoolExecutor, as_completed

            # a few blocks per worker, so that progress moves; each block opens the trajectory anew
            blocks = [b.tolist() for b in np.array_split(np.asarray(frames), min(4 * jobs, len(frames)))]
            args = (topology, trajectory, select, default_radius)
            with ProcessPoolExecutor(
                max_workers=min(jobs, len(blocks)), mp_context=mp.get_context("spawn"), initializer=_init_worker
            ) as pool:
                futs = [pool.submit(_worker_block, *args, b, probe, min_persistence) for b in blocks]
                for fut in as_completed(futs):
                    got = fut.result()
                    rows += got
                    bar.update(len(got))
            rows.sort(key=lambda r: r["frame"])
    finally:
        bar.close()
    return _assemble(rows, probe, min_overlap, len(atoms))


def _assemble(rows, probe, min_overlap, n_atoms) -> TrajectoryMeasures:
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


class _Progress:
    """tqdm on stderr when it is installed, else a ``k/n frames`` line now and then."""

    def __init__(self, total: int, enabled: bool):
        self.total, self.done, self.enabled, self.bar = total, 0, enabled, None
        if enabled:
            try:
                from tqdm import tqdm
            except ImportError:
                tqdm = None
            if tqdm is not None:
                self.bar = tqdm(total=total, unit="frame", file=sys.stderr, dynamic_ncols=True)

    def update(self, k: int = 1) -> None:
        self.done += k
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.update(k)
        else:
            print(f"{self.done}/{self.total} frames", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
