"""Area, volume, voids and pockets along a molecular-dynamics trajectory, in one process,
in many or on a Dask cluster (Notes §23.1).

Pockets and voids open and close as a protein moves (adenylate kinase closing over its
substrates is the textbook case).  :func:`trajectory_measures` reads a trajectory with
MDAnalysis (Michaud-Agrawal et al. 2011; Gowers et al. 2016), gives every selected atom
a ball of its van der Waals radius plus the probe, and measures each frame exactly: the
union's volume and surface area (:func:`shapelab.union_measure`), its voids
(:func:`shapelab.voids`) and pockets (:func:`shapelab.pockets`).  The cavities are then
followed from frame to frame by the atoms that line them.

MDAnalysis is an optional dependency: ``pip install "shapelab[md]"``.  It is imported
only when a trajectory is read, so ``import shapelab.tools.trajectory`` works without it.

The measures of one frame, the tracking rule and the result types are the core's
(:mod:`shapelab.tracking`, re-exported here); this module reads the trajectory and
runs the frames serially, in worker processes (``jobs=``) or on a Dask cluster
(``client=``, ``scheduler=``), with the same result for each.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from .._toolkit.validate import as_finite_scalar, as_positive_int
from ..tracking import (
    CavityTrack,
    FrameCavity,
    TrajectoryMeasures,
    measure_frames,
    selection_radii,
    track_cavities,
    tracked_measures,
)

if TYPE_CHECKING:
    from dask.distributed import Client
    from MDAnalysis import Universe

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


def _open(topology, trajectory):
    mda = _mdanalysis()
    if isinstance(topology, mda.Universe):
        return topology
    return mda.Universe(topology) if trajectory is None else mda.Universe(topology, trajectory)


def _init_worker() -> None:
    """A worker process's initializer: one thread for the free space unless
    ``SHAPELAB_THREADS`` says otherwise (the workers already share out the CPUs)."""
    os.environ.setdefault("SHAPELAB_THREADS", "1")


def _worker_block(topology, trajectory, select, default_radius, frames, probe, min_persistence) -> list:
    """One worker's task: open the trajectory in this process, measure a block of frames."""
    u = _open(topology, trajectory)
    atoms = u.select_atoms(select)
    return measure_frames(u, atoms, selection_radii(atoms, default_radius), frames, probe, min_persistence)


# ============================================================================ the API
def trajectory_measures(
    topology: str | os.PathLike[str] | Universe,
    trajectory: str | os.PathLike[str] | Sequence[str | os.PathLike[str]] | None = None,
    *,
    select: str = "protein and not name H*",
    probe: float = 1.4,
    start: int = 0,
    stop: int | None = None,
    step: int = 1,
    jobs: int = 1,
    min_overlap: float = 0.5,
    min_persistence: float = 0.0,
    default_radius: float | None = None,
    progress: bool = True,
    client: Client | None = None,
    scheduler: str | None = None,
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

    Examples
    --------
    >>> from shapelab.datasets import trajectory_files
    >>> top, traj = trajectory_files("adk-dims")
    >>> m = trajectory_measures(top, traj, select="resid 1:10", stop=2, progress=False)
    >>> m.n_atoms, m.frame.tolist(), [round(v) for v in m.volume.tolist()]
    (71, [0, 1], [2546, 2559])
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

    from .cluster import cluster_client

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
            from .cluster import cluster_threads, distributed_module

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
                rows += measure_frames(u, atoms, radii, [f], probe, min_persistence)
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
    return tracked_measures(rows, probe, min_overlap, len(atoms))


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
