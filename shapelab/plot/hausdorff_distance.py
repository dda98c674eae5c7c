"""Figures of the Hausdorff distance (Notes §23.2, lesson 14).

* :func:`hausdorff` — two point sets with the witness segments of both directed
  distances and the empty disks that certify them.
* :func:`translation` — matching under translation: centroid against optimum.
* :func:`timings` — a bar chart of measured running times.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax=``
and returns its figure) and computes no geometry beyond calling the library.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.patches import Circle
from numpy.typing import ArrayLike

from ._common import axes
from ._describe import describe
from ._style import COLORS, PAGE, PALETTE, SLIDE, new_figure, style

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..matching import TranslationMatch

__all__ = ["hausdorff", "translation", "timings"]


def hausdorff(
    A: ArrayLike,
    B: ArrayLike,
    *,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    labels: tuple[str, str] = ("A", "B"),
    disks: bool = True,
    title: str | None = None,
) -> Figure:
    """Two planar point sets with the witnesses of both directed Hausdorff distances.

    The segment from ``A[i]`` to its nearest point ``B[j]`` realises h(A, B);
    the disk of that radius around ``A[i]`` holds no point of B in its interior,
    which certifies the value.  Likewise for h(B, A).  The longer segment is
    H(A, B) (notes §23.2).

    Parameters
    ----------
    A, B : array_like, shape (n, 2) and (m, 2)
    ax : Axes, optional
    labels : (str, str)
        Names of the sets (e.g. ``("R", "G")`` as in the notes).
    disks : bool
        Draw the certifying empty disks.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.directed_hausdorff
        The witnesses drawn.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> A, B = rng.normal(size=(20, 2)), rng.normal(size=(15, 2)) + 1.0
    >>> from shapelab.plot import alt_text
    >>> alt_text(hausdorff(A, B))[:38]
    'Two planar point sets, A (20 dots) and'
    """
    from .._toolkit.validate import as_points
    from ..distance import hausdorff_pair

    A = as_points(A, "A", dim=2)
    B = as_points(B, "B", dim=2)
    ab, ba = hausdorff_pair(A, B)
    fig, ax = axes(ax, size=size)
    la, lb = labels
    ca, cb = COLORS["red"], COLORS["green"]
    with style():
        ax.scatter(A[:, 0], A[:, 1], s=22, color=ca, label=la, zorder=3)
        ax.scatter(B[:, 0], B[:, 1], s=22, color=cb, marker="s", label=lb, zorder=3)
        # the two witnesses differ by line style as well as by colour
        for (h, i, j), P, Q, col, name, ls in (
            (ab, A, B, ca, f"h({la}, {lb})", "-"),
            (ba, B, A, cb, f"h({lb}, {la})", (0, (4, 2))),
        ):
            p, q = P[i], Q[j]
            ax.annotate("", xy=q, xytext=p, arrowprops=dict(arrowstyle="-|>", color=col, lw=2.0, ls=ls), zorder=4)
            ax.plot([], [], color=col, lw=2.0, ls=ls, label=f"{name} = {h:.3f}")
            if disks and h > 0:
                ax.add_patch(Circle(p, h, facecolor=col, alpha=0.08, edgecolor=col, lw=0.8, ls="--", zorder=1))
            ax.scatter([p[0]], [p[1]], s=80, facecolor="none", edgecolor=col, linewidth=1.5, zorder=5)
        H = max(ab.distance, ba.distance)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_title(title or f"H({la}, {lb}) = max{{h({la},{lb}), h({lb},{la})}} = {H:.3f}")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=9)
        describe(
            ax,
            (f"{title}: " if title else "")
            + f"Two planar point sets, {la} ({len(A)} dots) and {lb} ({len(B)} squares), with the witnesses of the "
            f"directed Hausdorff distances: h({la}, {lb}) = {ab.distance:.3f} (solid arrow) and "
            f"h({lb}, {la}) = {ba.distance:.3f} (dashed arrow)"
            + (", each with its empty disk" if disks else "")
            + f"; H({la}, {lb}) = {H:.3f}",
        )
    return fig


def translation(
    A: ArrayLike,
    B: ArrayLike,
    match: TranslationMatch,
    *,
    size: tuple[float, float] = SLIDE,
    labels: tuple[str, str] = ("A", "B"),
    title: str | None = None,
) -> Figure:
    """Matching under translation: B moved by the centroid translation and by the
    optimal one, each panel with its Hausdorff witnesses.

    Parameters
    ----------
    A, B : array_like, shape (n, 2) and (m, 2)
    match : TranslationMatch
        From :func:`shapelab.hausdorff_under_translation` on the same sets.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.hausdorff_under_translation
        The match drawn.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> A, B = rng.normal(size=(20, 2)), rng.normal(size=(15, 2)) + 1.0
    >>> import shapelab as sl
    >>> fig = translation(A, B, sl.hausdorff_under_translation(A, B))
    >>> len(fig.axes)
    2
    """
    from .._toolkit.validate import as_points
    from ..matching import TranslationMatch

    if not isinstance(match, TranslationMatch):
        raise TypeError(f"match must be a TranslationMatch, got {type(match).__name__}")
    A = as_points(A, "A", dim=2)
    B = as_points(B, "B", dim=2)
    fig, axes = new_figure(1, 2, size=size)
    la, lb = labels
    hausdorff(
        A,
        B + match.centroid_translation,
        ax=axes[0],
        labels=(la, f"{lb}+t"),
        title=f"centroids aligned: H = {match.centroid_distance:.3f}",
    )
    hausdorff(
        A,
        B + match.optimal_translation,
        ax=axes[1],
        labels=(la, f"{lb}+t"),
        title=f"optimal translation: H = {match.optimal_distance:.3f}",
    )
    with style():
        lims = np.array([a.get_xlim() + a.get_ylim() for a in axes])
        for a in axes:
            a.set_xlim(lims[:, 0].min(), lims[:, 1].max())
            a.set_ylim(lims[:, 2].min(), lims[:, 3].max())
            a.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2, fontsize=8)
        fig.suptitle(title or f"centroid / optimum = {match.ratio:.3f}")
    return fig


_ALGORITHM_COLORS = {
    "brute force": PALETTE[7],
    "k-d tree (scipy)": PALETTE[0],
    "early break (scipy)": PALETTE[1],
    "shapelab": PALETTE[3],
}


def timings(
    seconds: Mapping[str, float],
    *,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    title: str | None = None,
    log: bool = True,
) -> Figure:
    """A horizontal bar chart of measured running times.

    Parameters
    ----------
    seconds : dict
        ``{label: seconds}`` (e.g. ``Timings.seconds`` from
        :func:`shapelab.distance.timings`).  The algorithms of that function keep
        the same colour in every chart.
    log : bool
        Logarithmic time axis (bars start at a third of the fastest time).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.distance.timings
        Measures the times.

    Examples
    --------
    >>> from shapelab.plot import alt_text
    >>> alt_text(timings({"brute force": 0.5, "k-d tree": 0.01}))
    'Running time: a bar chart of 2 running times, each bar labelled: brute force 500.0 ms, k-d tree 10.0 ms.'
    """
    from matplotlib.ticker import LogLocator, NullFormatter

    if not isinstance(seconds, dict) or not seconds:
        raise TypeError("seconds must be a non-empty dict {label: seconds}")
    names = list(seconds)
    vals = np.array([float(seconds[k]) for k in names])
    if not np.all(np.isfinite(vals)) or np.any(vals <= 0):
        raise ValueError("seconds must hold positive finite times")
    fig, ax = axes(ax, size=size)
    spare = iter(c for c in PALETTE if c not in _ALGORITHM_COLORS.values())
    colors = [_ALGORITHM_COLORS.get(k) or next(spare, COLORS["muted"]) for k in names]
    with style():
        y = np.arange(len(names))
        left = vals.min() / 3 if log else 0.0
        ax.barh(y, vals - left, left=left, color=colors)
        ax.set_yticks(y, names)
        ax.invert_yaxis()
        if log:
            ax.set_xscale("log")
            ax.xaxis.set_major_locator(LogLocator(base=10))
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_xlim(left, vals.max() * 12)
        else:
            ax.set_xlim(0, vals.max() * 1.3)
        for k, v in enumerate(vals):
            text = f"{v * 1e3:.1f} ms" if v < 1 else f"{v:.2f} s"
            ax.text(v, k, "  " + text, va="center", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_title(title or "Running time")
        describe(
            ax,
            f"{title or 'Running time'}: a bar chart of {len(names)} running times, each bar labelled: "
            + ", ".join(f"{k} {v * 1e3:.1f} ms" if v < 1 else f"{k} {v:.2f} s" for k, v in zip(names, vals)),
        )
    return fig
