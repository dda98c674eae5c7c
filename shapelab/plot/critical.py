"""Figures of critical points (Notes §23.2, lesson 13).

* :func:`critical_points` — Figure 23.3: a closed curve, the viewpoint S, the rays
  from S to the extrema of F(x) = |x − S|, and F plotted along the curve.
* :func:`critical_surface` — the 3D remark: a closed surface shaded by F with its
  minima, saddles and maxima.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax=``
and returns its figure) and computes no geometry beyond calling the library.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.ticker import MaxNLocator
from numpy.typing import ArrayLike

from ._common import axes
from ._describe import describe
from ._style import COLORS, PAGE, PALETTE, SLIDE, new_figure, style

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..critical import CriticalPoints

__all__ = ["critical_points", "critical_surface"]

_KIND_STYLE = {
    "min": dict(color=PALETTE[0], marker="v", label="minimum"),
    "max": dict(color=PALETTE[3], marker="^", label="maximum"),
    "saddle": dict(color=PALETTE[1], marker="X", label="saddle"),
}


def _check_result(result, sources):
    from ..critical import CriticalPoints

    if not isinstance(result, CriticalPoints):
        raise TypeError(f"result must be a CriticalPoints from shapelab.critical_points, got {type(result).__name__}")
    if result.source not in sources:
        raise ValueError(f"result comes from a {result.source}; this figure needs one of {sources}")


def critical_points(
    curve: Callable[[np.ndarray], np.ndarray] | ArrayLike,
    result: CriticalPoints,
    *,
    ax: Axes | None = None,
    profile_ax: Axes | None = None,
    profile: bool = True,
    rays: bool = True,
    title: str | None = None,
    size: tuple[float, float] = SLIDE,
    n: int = 600,
) -> Figure:
    """Figure 23.3: a closed curve seen from S, with its critical points.

    Parameters
    ----------
    curve : array_like or callable
        The closed polyline or parametric curve given to
        :func:`shapelab.critical_points`.
    result : CriticalPoints
        Its critical points (the viewpoint is ``result.viewpoint``).
    ax : Axes, optional
        Draw the curve panel here (then the profile goes to ``profile_ax`` if
        given, and is omitted otherwise).
    profile_ax : Axes, optional
        Where to draw F along the curve when ``ax`` is given.
    profile : bool
        Add the second panel, F along the curve, when creating the figure.
    rays : bool
        Draw the segments from S to each extremum.
    title : str, optional
    size : (float, float)
        Figure size when creating the figure.
    n : int
        Samples used to draw a parametric curve and the profile.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.critical_points
        The points drawn.
    critical_surface
        On a surface.

    Examples
    --------
    >>> import shapelab as sl
    >>> from shapelab.critical import polyline
    >>> from shapelab.datasets import ellipse_curve
    >>> hexagon = polyline(ellipse_curve(2.0, 1.2), 6)
    >>> fig = critical_points(hexagon, sl.critical_points(hexagon, (0.4, 0.3)))
    >>> len(fig.axes), sl.plot.alt_text(fig)[:40]
    (2, '2 panels. Left: A closed planar curve an')
    """
    from ..critical import distance_along, polyline

    _check_result(result, ("polyline", "parametric"))
    if ax is None:
        if profile:
            fig, (ax, profile_ax) = new_figure(1, 2, size=size)
        else:
            fig, ax = new_figure(size=size)
    else:
        fig = ax.get_figure()
    if callable(curve):
        P = polyline(curve, n)
        param_label = "parameter t"
    else:
        P = np.asarray(curve, dtype=float)
        if not np.array_equal(P[0], P[-1]):
            P = np.vstack([P, P[:1]])
        param_label = "arc length (fraction of the perimeter)"
    S = result.viewpoint
    with style():
        ax.plot(P[:, 0], P[:, 1], color=COLORS["complex"], lw=1.6, zorder=2, label="curve C")
        if not callable(curve):
            ax.plot(P[:-1, 0], P[:-1, 1], ".", color=COLORS["complex"], ms=3, zorder=2)
        for kind in ("min", "max"):
            sel = result.kinds == kind
            X = result.positions[sel]
            st = _KIND_STYLE[kind]
            if rays:
                for x in X:
                    ax.plot([S[0], x[0]], [S[1], x[1]], color=st["color"], lw=0.9, ls="--", alpha=0.8, zorder=1)
            ax.scatter(
                X[:, 0],
                X[:, 1],
                s=70,
                color=st["color"],
                marker=st["marker"],
                zorder=4,
                edgecolor="white",
                linewidth=0.6,
                label=f"{st['label']} ({int(sel.sum())})",
            )
        ax.scatter(
            [S[0]],
            [S[1]],
            s=90,
            color=COLORS["accent"],
            marker="*",
            zorder=5,
            edgecolor="black",
            linewidth=0.5,
            label="viewpoint S",
        )
        ax.annotate("S", S[:2], xytext=(6, 6), textcoords="offset points", fontsize=11)
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        deg = " — F constant: every point is critical" if result.degenerate else ""
        ax.set_title(title or f"Critical points of F(x) = |x − S|{deg}")
        ax.legend(
            loc="upper left",
            bbox_to_anchor=(1.0, 1.0) if profile_ax is None else (0.0, -0.2),
            ncol=1 if profile_ax is None else 2,
            fontsize=9,
        )
        if profile_ax is not None:
            s, F = distance_along(curve, S, n=n)
            pax = profile_ax
            pax.plot(s, F, color=COLORS["complex"], lw=1.4)
            for kind in ("min", "max"):
                sel = result.kinds == kind
                st = _KIND_STYLE[kind]
                pax.scatter(
                    result.parameters[sel],
                    result.values[sel],
                    s=55,
                    color=st["color"],
                    marker=st["marker"],
                    zorder=4,
                    edgecolor="white",
                    linewidth=0.6,
                )
                for p in result.parameters[sel]:
                    pax.axvline(p, color=st["color"], lw=0.6, ls=":", zorder=0)
            pax.set_xlabel(param_label)
            pax.set_ylabel("F = |x − S|")
            pax.set_title("F along the curve")
            describe(
                pax,
                f"F = |x − S| along the curve against the {param_label}, from {float(np.min(F)):.3g} to "
                f"{float(np.max(F)):.3g}, its minima and maxima marked with down and up triangles",
            )
        n_min, n_max = int((result.kinds == "min").sum()), int((result.kinds == "max").sum())
        describe(
            ax,
            f"A closed planar curve and the viewpoint S = ({S[0]:.3g}, {S[1]:.3g}), a star: the critical points of "
            f"the distance from S, {n_min} minima (down triangles) and {n_max} maxima (up triangles)"
            + (", joined to S by dashed rays" if rays else "")
            + ("; F is constant, every point is critical" if result.degenerate else ""),
        )
    return fig


def critical_surface(
    vertices: ArrayLike,
    faces: ArrayLike,
    result: CriticalPoints,
    *,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    elev: float = 20.0,
    azim: float = -60.0,
    title: str | None = None,
    colorbar: bool = True,
) -> Figure:
    """A closed surface shaded by F = |x − S| with its minima, saddles and maxima.

    Parameters
    ----------
    vertices, faces : array_like
        The mesh given to :func:`shapelab.critical_points`.
    result : CriticalPoints
        From a surface (``faces=`` given).
    ax : Axes3D, optional
    elev, azim : float
        The camera.
    title : str, optional
    colorbar : bool

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    critical_points
        On a curve.

    Examples
    --------
    >>> import shapelab as sl
    >>> from shapelab.datasets import torus
    >>> V, F = torus(12, 6)
    >>> fig = critical_surface(V, F, sl.critical_points(V, (3.0, 0.5, 0.2), faces=F))
    >>> sl.plot.alt_text(fig)[:40]
    '3D view of a surface shaded by the dista'
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    _check_result(result, ("surface",))
    V = np.asarray(vertices, dtype=float)
    F = np.asarray(faces, dtype=np.intp)
    fig, ax = axes(ax, size=size, projection="3d")
    S = result.viewpoint
    h = np.sqrt(np.sum((V - S) ** 2, axis=1))
    with style():
        norm = Normalize(h.min(), h.max())
        cmap = colormaps["viridis"]
        coll = Poly3DCollection(
            V[F], facecolors=cmap(norm(h[F].mean(axis=1))), edgecolor=(0, 0, 0, 0.12), linewidth=0.2, alpha=0.55
        )
        ax.add_collection3d(coll)
        for kind in ("min", "saddle", "max"):
            sel = result.kinds == kind
            st = _KIND_STYLE[kind]
            X = result.positions[sel]
            count = int(result.multiplicities[sel].sum())
            ax.scatter(
                X[:, 0],
                X[:, 1],
                X[:, 2],
                s=60,
                color=st["color"],
                marker=st["marker"],
                edgecolor="black",
                linewidth=0.4,
                depthshade=False,
                label=f"{st['label']} ({count})",
            )
        ax.scatter(
            [S[0]],
            [S[1]],
            [S[2]],
            s=90,
            color=COLORS["accent"],
            marker="*",
            edgecolor="black",
            linewidth=0.5,
            depthshade=False,
            label="viewpoint S",
        )
        lo, hi = V.min(axis=0), V.max(axis=0)
        c, r = 0.5 * (lo + hi), 0.5 * float((hi - lo).max())
        ax.set_xlim(c[0] - r, c[0] + r)
        ax.set_ylim(c[1] - r, c[1] + r)
        ax.set_zlim(c[2] - r, c[2] + r)
        ax.set_box_aspect((1, 1, 1))
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            axis.set_major_locator(MaxNLocator(4))
            axis.set_tick_params(labelsize=8)
        ax.view_init(elev=elev, azim=azim)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        chi = result.euler_characteristic
        ax.set_title(title or f"#min − #saddle + #max = {result.n_min} − {result.n_saddle} + {result.n_max} = {chi}")
        ax.legend(loc="upper left", fontsize=9)
        if colorbar:
            sm = ScalarMappable(norm=norm, cmap=cmap)
            fig.colorbar(sm, ax=ax, shrink=0.6, label="F = |x − S|")
        describe(
            ax,
            f"3D view of a surface shaded by the distance F from a viewpoint S (a star), with its critical points: "
            f"{result.n_min} minima, {result.n_saddle} saddles and {result.n_max} maxima, each kind with its own "
            f"marker; #min − #saddle + #max = {chi}, the Euler characteristic",
        )
    return fig
