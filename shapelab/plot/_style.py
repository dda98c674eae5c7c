"""One style for every figure of the course.

Figures are built on :class:`matplotlib.figure.Figure` directly, never through
``pyplot``'s global state, so a plotting function returns its figure without also
drawing it a second time in a notebook, and the same call serves the lessons, the
book, the slides and ``python -m course.figures``.

The palette is Okabe & Ito's colour-blind-safe set (Okabe, M. and Ito, K., *Color
Universal Design*, 2008); sequential data uses ``viridis``/``cividis``.
"""

from __future__ import annotations

from contextlib import contextmanager
from typing import TYPE_CHECKING

import matplotlib
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from matplotlib.axes import Axes

__all__ = ["PALETTE", "COLORS", "SEQUENTIAL", "SLIDE", "PAGE", "RC", "new_figure", "style", "thin_3d_ticks"]

#: Okabe-Ito palette, in the order used for categories.
PALETTE = (
    "#0072B2",  # blue
    "#E69F00",  # orange
    "#009E73",  # bluish green
    "#D55E00",  # vermillion
    "#CC79A7",  # reddish purple
    "#56B4E9",  # sky blue
    "#F0E442",  # yellow
    "#000000",  # black
)

#: Named roles, so that every figure means the same thing by the same colour.
COLORS = {
    "ball": "#56B4E9",  # disks and balls
    "ball_edge": "#0072B2",
    "cell": "#E69F00",  # power cells
    "complex": "#000000",  # vertices and edges of K
    "triangle": "#009E73",  # 2-simplices
    "void": "#D55E00",  # voids, holes, pockets
    "mouth": "#CC79A7",
    "red": "#D55E00",  # the notes' red point set R
    "green": "#009E73",  # the notes' green point set G
    "accent": "#E69F00",
    "muted": "#999999",
}

SEQUENTIAL = "viridis"

#: Figure sizes in inches: 16:9 for slides, a narrower one for the book's pages.
SLIDE = (10.0, 5.625)
PAGE = (8.0, 4.5)

RC = {
    "font.size": 11,
    "axes.titlesize": 12,
    "axes.labelsize": 11,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.prop_cycle": matplotlib.cycler(color=list(PALETTE)),
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "savefig.bbox": "tight",
    "legend.frameon": False,
    "image.cmap": SEQUENTIAL,
    "svg.hashsalt": "shapelab",  # deterministic SVG ids
    "svg.fonttype": "none",
    "pdf.fonttype": 42,
    "path.simplify": True,
}


@contextmanager
def style() -> Iterator[None]:
    """Context manager applying the course style to figures created inside it."""
    with matplotlib.rc_context(RC):
        yield


def new_figure(
    nrows: int = 1,
    ncols: int = 1,
    *,
    size: tuple[float, float] = PAGE,
    projection: str | None = None,
    **subplot_kw: Any,
) -> tuple[Figure, Any]:
    """Create a styled figure with a grid of axes.

    Returns
    -------
    fig : matplotlib.figure.Figure
    axes : Axes or ndarray of Axes (squeezed like ``plt.subplots``)

    Examples
    --------
    >>> fig, axes = new_figure(1, 2, size=SLIDE)
    >>> type(fig).__name__, len(axes)
    ('Figure', 2)
    >>> tuple(round(float(x), 2) for x in fig.get_size_inches())
    (10.0, 5.62)
    """
    with style():
        fig = Figure(figsize=size, layout="constrained")
        kw = dict(subplot_kw)
        if projection is not None:
            kw["projection"] = projection
        axes = fig.subplots(nrows, ncols, squeeze=True, subplot_kw=kw or None)
    if projection == "3d":
        for ax in fig.axes:
            thin_3d_ticks(ax)
    return fig, axes


def thin_3d_ticks(ax: Axes, nbins: int = 4) -> None:
    """At most ``nbins + 1`` labelled ticks per axis of a 3D axes: matplotlib's default
    crowds a slide-size 3D plot with overlapping numbers."""
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(nbins=nbins))
