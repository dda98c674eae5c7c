"""Figures of many structures and of trajectories (Notes §23.1, "Voids and pockets").

* :func:`batch_summary` -- the summary of a batch (:func:`shapelab.tools.batch.report_batch`):
  the largest pocket and the largest void of each structure, sorted, failed files
  marked by name.
* :func:`trajectory_volumes` -- a trajectory's measures
  (:func:`shapelab.tools.trajectory.trajectory_measures`): the union's volume and the volume
  of the longest-lived tracked cavities against time.

Both draw what they are given and compute nothing; they read the summary's rows and
the measures' attributes, so that this module imports neither the batch machinery nor
MDAnalysis.
"""

from __future__ import annotations

import csv
import math
import os
from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ._common import axes
from ._describe import describe
from ._style import COLORS, PALETTE, SLIDE, style

if TYPE_CHECKING:
    from collections.abc import Sequence
    from typing import Any

    from matplotlib.axes import Axes

__all__ = ["batch_summary", "trajectory_volumes"]

_POCKET = PALETTE[0]  # blue
_VOID = COLORS["void"]  # vermillion
_FAILED = COLORS["void"]


def _number(v):
    """A summary cell as a float (None, "" and NaN: None)."""
    if v is None or v == "":
        return None
    x = float(v)
    return None if math.isnan(x) else x


def _summary_rows(summary) -> list:
    """The rows of a BatchSummary, a sequence of mappings, or a summary CSV file."""
    if isinstance(summary, (str, os.PathLike)):
        with open(summary, newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
    elif hasattr(summary, "rows") and not hasattr(summary, "to_dict"):
        rows = list(summary.rows)
    elif hasattr(summary, "to_dict"):  # a pandas DataFrame
        rows = summary.to_dict("records")
    else:
        try:
            rows = list(summary)
        except TypeError:
            rows = None
    if rows is None or not all(isinstance(r, Mapping) for r in rows):
        raise TypeError(
            "summary must be a BatchSummary, a sequence of row dicts, a DataFrame or a summary CSV path, "
            f"got {type(summary).__name__}"
        )
    for k, r in enumerate(rows):
        missing = [c for c in ("path", "status", "largest_pocket_volume", "largest_void_volume") if c not in r]
        if missing:
            raise ValueError(f"summary row {k} has no column {missing[0]!r}")
    return rows


def _name(r) -> str:
    stem = r.get("stem")
    if stem is None or stem == "" or (isinstance(stem, float) and math.isnan(stem)):
        return os.path.basename(str(r["path"])) or str(r["path"])
    return str(stem)


def batch_summary(
    summary: Any, *, log: bool | None = None, max_labels: int = 25, ax: Axes | None = None, title: str | None = None
) -> Figure:
    """The summary of a batch as a figure: largest pocket and void of each structure.

    One row per structure, sorted by the volume of its largest pocket (largest at the
    top; ties by the largest void, then by name), two bars each: the solvent-accessible
    volume (Å³, ``V SA`` of :func:`shapelab.report`) of its largest pocket and of its
    largest void (Notes §23.1).  A structure without a pocket or void has no bar of that
    kind.  Failed files come last, named in vermillion with a ✗ and "failed" (their
    error is in the summary's ``error`` column).  With no structure reported (an empty
    summary, or every file failed) the axes say so, without a legend.  With more than ``max_labels``
    structures, names no longer fit a slide: the figure becomes a rank plot (volume
    against rank, each kind sorted on its own) and the failed files are counted in the
    title instead.

    Parameters
    ----------
    summary : BatchSummary, sequence of dict, pandas.DataFrame, str or os.PathLike
        What :func:`shapelab.tools.batch.report_batch` returns, its rows, or the path of
        the summary CSV it writes.
    log : bool, optional
        A logarithmic volume axis; default: when the positive volumes span more than
        two decades.
    max_labels : int, default 25
        The most structures drawn as named bars (25 keep an 11-point label per row
        on a 16:9 slide).
    ax : matplotlib.axes.Axes, optional
    title : str, optional
        Default: "Largest pocket and void per structure" and the counts.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    TypeError
        ``summary`` of another type.
    ValueError
        A row without the columns ``path``, ``status``, ``largest_pocket_volume`` and
        ``largest_void_volume``, or ``max_labels`` below 1.

    See Also
    --------
    shapelab.tools.batch.report_batch
        Makes the summary.
    trajectory_volumes
        The same quantities along a trajectory.

    References
    ----------
    .. [1] J. Liang, H. Edelsbrunner and C. Woodward, "Anatomy of protein pockets and
       cavities: measurement of binding site geometry and implications for ligand
       design", *Protein Science* 7 (1998) 1884–1897, doi:10.1002/pro.5560070905

    Examples
    --------
    >>> rows = [
    ...     dict(path="a.pdb", stem="a", status="ok", largest_pocket_volume=120.0, largest_void_volume=8.0),
    ...     dict(path="b.pdb", stem="b", status="ok", largest_pocket_volume=300.0, largest_void_volume=None),
    ...     dict(path="c.pdb", stem="c", status="failed", largest_pocket_volume=None, largest_void_volume=None),
    ... ]
    >>> fig = batch_summary(rows)
    >>> [t.get_text() for t in fig.axes[0].get_yticklabels()]
    ['c', 'a', 'b']
    """
    rows = _summary_rows(summary)
    if isinstance(max_labels, bool) or not isinstance(max_labels, (int, np.integer)) or max_labels < 1:
        raise ValueError(f"max_labels must be a positive integer, got {max_labels!r}")
    good, failed = [], []
    for r in rows:
        if r["status"] == "failed":
            failed.append(_name(r))
        else:
            good.append((_name(r), _number(r["largest_pocket_volume"]), _number(r["largest_void_volume"])))
    good.sort(key=lambda g: (-(g[1] or 0.0), -(g[2] or 0.0), g[0]))
    vols = [v for g in good for v in g[1:] if v is not None and v > 0]
    if log is None:
        log = len(vols) > 1 and max(vols) > 100 * min(vols)
    n = len(good) + len(failed)
    counts = f"{len(good)} reported, {len(failed)} failed" if failed else f"{len(good)} structures"
    if title is None:
        title = f"Largest pocket and void per structure ({counts})"
    size = (SLIDE[0], min(SLIDE[1], max(3.2, 0.9 + 0.3 * n))) if n <= max_labels else SLIDE
    fig, ax = axes(ax, size=size)
    with style():
        if n <= max_labels:
            # top to bottom: the largest pocket first, the failed files last
            order = list(reversed(good))
            y_fail = np.arange(len(failed))
            y = np.arange(len(failed), n)
            h = 0.38
            pockets = np.array([0.0 if g[1] is None else g[1] for g in order])
            voids = np.array([0.0 if g[2] is None else g[2] for g in order])
            ax.barh(y + h / 2, pockets, height=h, color=_POCKET, label="largest pocket")
            # hatched: the two kinds differ by more than their colour
            ax.barh(y - h / 2, voids, height=h, color=_VOID, hatch="//", edgecolor="white", label="largest void")
            names = list(reversed(failed)) + [g[0] for g in order]
            ax.set_yticks(np.arange(n), names)
            for k, lab in enumerate(ax.get_yticklabels()):
                if k < len(failed):
                    lab.set_color(_FAILED)
            for k in y_fail:
                ax.annotate(
                    "✗ failed",
                    (0, k),
                    xycoords=ax.get_yaxis_transform(),  # at the axis, whatever the scale
                    xytext=(4, 0),
                    textcoords="offset points",
                    va="center",
                    color=_FAILED,
                    fontsize=10,
                )
            ax.set_ylim(-0.7, n - 0.3)
            ax.set_xlabel("volume V SA (Å³)")
            ax.spines["left"].set_visible(False)
            ax.tick_params(axis="y", length=0)
            if log:
                ax.set_xscale("log")
            if good:
                ax.legend(loc="lower right")
        else:
            for k, (label, col) in enumerate((("largest pocket", _POCKET), ("largest void", _VOID))):
                v = np.sort([g[1 + k] for g in good if g[1 + k] is not None])[::-1]
                ax.plot(
                    np.arange(1, len(v) + 1),
                    v,
                    "o-" if k == 0 else "s--",
                    ms=3,
                    lw=1.2,
                    color=col,
                    label=f"{label} ({len(v)})",
                )
            ax.set_xlabel("rank (structures sorted by volume)")
            ax.set_ylabel("volume V SA (Å³)")
            if log:
                ax.set_yscale("log")
            if good:
                ax.legend(loc="upper right")
        if not good:  # nothing to measure: no empty legend, no axis around 0
            ax.text(0.5, 0.5, "no structure reported", transform=ax.transAxes, ha="center", va="center")
            ax.set_xticks([])
            if n > max_labels:
                ax.set_yticks([])
        ax.set_title(title)
        text = f"{title}: "
        if not good:
            text += "no structure reported"
        else:
            top = good[0]
            pv = [g[1] for g in good if g[1] is not None]
            vv = [g[2] for g in good if g[2] is not None]
            kind = "a bar chart, two bars per structure (voids hatched)" if n <= max_labels else "a rank plot"
            text += (
                f"{kind} of the volume V SA of the largest pocket and void of {len(good)} structures; "
                f"{len(pv)} with a pocket, {len(vv)} with a void; the largest pocket, "
                f"{top[1] or 0:.0f} Å³, in {top[0]}"
            )
        if failed:
            text += f"; {len(failed)} failed: {', '.join(failed[:10])}"
        describe(ax, text)
    return fig


def _track_key(t):
    return (-len(t.frames), -max(t.volumes), t.id)


def trajectory_volumes(
    measures: Any,
    *,
    tracks: int | Sequence[int] = 5,
    time: bool = True,
    ax: Axes | None = None,
    title: str | None = None,
) -> Figure:
    """The volume of the union and of the tracked cavities against time along a trajectory.

    Two panels sharing the time axis: above, the volume (Å³) of the union of the
    solvent-accessible balls of each analysed frame; below, the volume of the
    ``tracks`` cavities followed longest (:class:`shapelab.tools.trajectory.CavityTrack`:
    the most frames, ties by the largest volume then the lower id), one line each, a
    round marker where it is a pocket and a square where it is a void (Notes §23.1).
    A track is drawn only over the frames it is seen in: a gap is a frame where that
    cavity is not found (closed, or lost by the tracking rule).  With ``ax`` given,
    only the lower panel is drawn, into it.

    Parameters
    ----------
    measures : TrajectoryMeasures
        What :func:`shapelab.tools.trajectory.trajectory_measures` returns.
    tracks : int or sequence of int, default 5
        How many tracks (the longest), or the ids of the tracks to draw.
    time : bool, default True
        Time (ps) on the horizontal axis; False: the frame index.
    ax : matplotlib.axes.Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    TypeError
        ``measures`` without the attributes of a TrajectoryMeasures.
    ValueError
        A negative number of tracks, or an id no track has.

    See Also
    --------
    shapelab.tools.trajectory.trajectory_measures
        Computes what is drawn.
    batch_summary
        The same volumes across many structures.

    References
    ----------
    .. [1] J. Liang, H. Edelsbrunner, P. Fu, P. V. Sudhakar, S. Subramaniam, "Analytical
       shape computation of macromolecules: II. Inaccessible cavities in proteins",
       *Proteins* **33**, 18–29 (1998), doi:10.1002/(SICI)1097-0134(19981001)33:1<18::AID-PROT2>3.0.CO;2-H.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> from shapelab.tracking import CavityTrack, TrajectoryMeasures
    >>> z = np.zeros(3)
    >>> track = CavityTrack(0, (0, 1, 2), ("pocket", "void", "pocket"), (50.0, 40.0, 55.0), (0.9, 0.8))
    >>> m = TrajectoryMeasures(frame=np.arange(3), time=2.0 * np.arange(3), area=z, volume=np.array([1000.0, 990.0, 1010.0]),
    ...                        n_voids=z.astype(int), largest_void=z, n_pockets=z.astype(int), cavities=(), tracks=(track,),
    ...                        probe=1.4, min_overlap=0.5, n_atoms=100)
    >>> fig = trajectory_volumes(m)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    2 panels. Top: Volume along the trajectory (SA model): the volume of the union over 3 frames, from 990 to 1010 Å³. Bottom: The volume of 1 tracked cavities against time (ps), one line style per track. track 0: 3 frames, 40 to 55 Å³, 2 as a pocket (dots), 1 as a void (squares).
    """
    if not all(hasattr(measures, a) for a in ("frame", "time", "volume", "tracks")):
        raise TypeError(f"measures must be a TrajectoryMeasures, got {type(measures).__name__}")
    all_tracks = {t.id: t for t in measures.tracks}
    if isinstance(tracks, (int, np.integer)) and not isinstance(tracks, bool):
        if tracks < 0:
            raise ValueError(f"tracks must be a number >= 0 or a list of track ids, got {tracks}")
        chosen = sorted(all_tracks.values(), key=_track_key)[: int(tracks)]
    else:
        try:
            ids = [int(i) for i in tracks]
        except TypeError:
            raise TypeError(f"tracks must be a number or a list of track ids, got {type(tracks).__name__}") from None
        unknown = [i for i in ids if i not in all_tracks]
        if unknown:
            raise ValueError(f"no track has id {unknown[0]}; the ids run from 0 to {len(all_tracks) - 1}")
        chosen = [all_tracks[i] for i in ids]
    frames = np.asarray(measures.frame)
    xs = np.asarray(measures.time if time else measures.frame, dtype=np.float64)
    at = {int(f): x for f, x in zip(frames, xs)}
    xlabel = "time (ps)" if time else "frame"
    if ax is None:
        with style():
            fig = Figure(figsize=SLIDE, layout="constrained")
            top, ax = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": (1, 2)})
    else:
        fig, ax = axes(ax)
        top = None
    with style():
        if top is not None:
            top.plot(xs, np.asarray(measures.volume, dtype=np.float64), color=COLORS["complex"], lw=1.5)
            top.set_ylabel("union (Å³)")
            top.set_title(title if title is not None else "Volume along the trajectory (SA model)")
            vol = np.asarray(measures.volume, dtype=np.float64)
            describe(
                top,
                f"{title if title is not None else 'Volume along the trajectory (SA model)'}: the volume of the "
                f"union over {len(xs)} frames, from {vol.min():.0f} to {vol.max():.0f} Å³",
            )
        for k, t in enumerate(chosen):
            col = PALETTE[k % (len(PALETTE) - 1)]  # black is the union's
            x = np.array([at[f] for f in t.frames])
            v = np.asarray(t.volumes, dtype=np.float64)
            ax.plot(x, v, ("-", "--", "-.", ":")[k % 4], color=col, lw=1.5, label=f"track {t.id}")
            pocket = np.array([kind == "pocket" for kind in t.kinds])
            ax.plot(x[pocket], v[pocket], "o", color=col, ms=4)
            ax.plot(x[~pocket], v[~pocket], "s", color=col, ms=5, mfc="white")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("cavity volume (Å³)")
        if top is None and title is not None:
            ax.set_title(title)
        handles = ax.get_legend_handles_labels()[0]
        if handles:
            kinds = [
                Line2D([], [], ls="", marker="o", color=COLORS["muted"], label="pocket"),
                Line2D([], [], ls="", marker="s", mfc="white", color=COLORS["muted"], label="void"),
            ]
            ax.legend(handles=handles + kinds, loc="upper left", bbox_to_anchor=(1.0, 1.0))
        else:
            ax.legend(handles=[Patch(color="none", label="no cavity tracked")], loc="upper left")
        tracked = "; ".join(
            f"track {t.id}: {len(t.frames)} frames, {min(t.volumes):.0f} to {max(t.volumes):.0f} Å³, "
            f"{sum(k == 'pocket' for k in t.kinds)} as a pocket (dots), {sum(k != 'pocket' for k in t.kinds)} as a void (squares)"
            for t in chosen
        )
        describe(
            ax,
            f"The volume of {len(chosen)} tracked cavities against {xlabel}, one line style per track. "
            + (tracked or "No cavity tracked"),
        )
    return fig
