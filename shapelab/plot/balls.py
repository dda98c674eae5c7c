"""Figures of balls, power diagrams, dual complexes and filtrations (Notes §23.1).

* :func:`disks` — a union of disks (grown to a time τ of the growth model);
* :func:`power_diagram` — the power cells :math:`\\Pi(B_i)` clipped to a box, hidden
  disks (empty cells) dashed;
* :func:`dual_complex` — Figure 23.1 (i): the disks, the clipped cells
  :math:`B_i \\cap \\Pi(B_i)` and the dual complex K drawn on top;
* :func:`filtration` — Figure 23.1 (ii): every simplex of DT shaded by its entry
  time, with a colourbar (early simplices dark and thick, as in the notes);
* :func:`balls3d`, :func:`complex3d` — the same in 3D with matplotlib's 3D axes;
* :func:`lifting` — the lifting map: disks as points on and below the paraboloid
  :math:`x_3 = |x|^2`, whose lower convex hull projects to the regular triangulation;
* :func:`method_comparison` — times and errors of several methods against a size.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax=``
and returns its figure) and computes no geometry of its own: cells, complexes and
entry times come from :mod:`shapelab.triangulation` and :mod:`shapelab.filtration`.  The
cells :math:`B_i \\cap \\Pi(B_i)` come from :func:`shapelab.triangulation.clipped_cells`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.cm import ScalarMappable
from matplotlib.collections import EllipseCollection, LineCollection, PolyCollection
from matplotlib.colors import BoundaryNorm, Normalize, to_rgba
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from .._toolkit.validate import (
    as_finite_scalar,
    as_positive_int,
    as_tau,
    check_balls,
)
from ..balls import Balls
from ..filtration import as_filtration
from ._common import axes, grown_radii, set_3d_view
from ._describe import describe
from ._style import COLORS, PALETTE, new_figure, style

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.typing import ColorType
    from numpy.typing import ArrayLike

    from ..filtration import Complex, Filtration
    from ..power import PowerDiagram

__all__ = [
    "disks",
    "power_diagram",
    "dual_complex",
    "filtration",
    "balls3d",
    "complex3d",
    "lifting",
    "method_comparison",
    "DualComplexView",
]


# ------------------------------------------------------------------ helpers
def _check_balls(balls, name="balls", dim=None) -> Balls:
    check_balls(balls, name)
    if dim is not None and balls.dim != dim:
        hint = " (use balls3d/complex3d for 3D)" if dim == 2 else " (use disks/dual_complex for 2D)"
        raise ValueError(f"{name} must be {dim}D for this figure, got {balls.dim}D{hint}")
    return balls


def _fmt(x: float) -> str:
    return f"{x:.3g}"


def _plural(n: int, word: str) -> str:
    """``"1 edge"``, ``"3 edges"`` (``vertex`` -> ``vertices``)."""
    if n == 1:
        return f"1 {word}"
    return f"{n} " + ("vertices" if word == "vertex" else "tetrahedra" if word == "tetrahedron" else word + "s")


def _counts(n) -> str:
    """``"13 vertices, 10 edges, 2 triangles"`` from a complex's counts."""
    n = tuple(n) + (0,) * (3 - len(n))
    words = ["vertex", "edge", "triangle", "tetrahedron"]
    parts = [_plural(int(k), w) for k, w in zip(n, words)]
    return ", ".join(parts if len(n) > 3 and n[3] else parts[:3])


def _tau_title(tau: float) -> str:
    alpha = f", α = √τ = {_fmt(np.sqrt(tau))}" if tau >= 0 else " (α = √τ undefined)"
    return f"τ = {_fmt(tau)}{alpha}"


def _limits_2d(ax, centers, radii, bbox=None):
    if bbox is not None:
        lo, hi = np.asarray(bbox, float)
    elif len(centers):
        lo = (centers - radii[:, None]).min(axis=0)
        hi = (centers + radii[:, None]).max(axis=0)
        pad = 0.06 * max(float(np.max(hi - lo)), 1e-12)
        if not np.all(hi - lo > 0):
            pad = max(pad, 1.0)
        lo, hi = lo - pad, hi + pad
    else:
        lo, hi = np.array([-1.0, -1.0]), np.array([1.0, 1.0])
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")


def _disk_collection(ax, centers, radii, **kw):
    coll = EllipseCollection(
        2 * radii,
        2 * radii,
        np.zeros(len(radii)),
        units="xy",
        offsets=centers if len(centers) else np.zeros((0, 2)),
        offset_transform=ax.transData,
        **kw,
    )
    ax.add_collection(coll, autolim=False)
    return coll


def _segments(centers, edges):
    return centers[edges] if len(edges) else np.zeros((0, 2, centers.shape[1]))


# ---------------------------------------------------------------- disks
def disks(
    balls: Balls,
    *,
    tau: float = 0.0,
    ax: Axes | None = None,
    labels: bool = False,
    title: str | None = None,
    color: ColorType | None = None,
    show_centers: bool = True,
) -> Figure:
    """Draw a union of disks, grown to time ``tau`` (Notes §23.1).

    Parameters
    ----------
    balls : Balls
        2D balls (disks).
    tau : float
        Growth time: radii :math:`\\sqrt{r_i^2 + \\tau}` (disks with
        :math:`r_i^2 + \\tau < 0` are not drawn).
    ax : matplotlib Axes, optional
    labels : bool
        Write each disk's index at its centre.
    title : str, optional
    color : colour, optional
        Fill colour (default the course's ball colour).
    show_centers : bool

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    dual_complex
        With cells and the dual complex.
    Balls.grow
        The grown disks.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = disks(sl.Balls([[0.0, 0.0], [3.0, 0.0]], [1.0, 1.5]), tau=0.5, labels=True)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    2 disks grown to τ = 0.5 (2 born), radii from 1.22 to 1.66, centres marked, each labelled with its index.
    """
    _check_balls(balls, dim=2)
    tau = as_tau(tau, finite=True)
    fig, ax = axes(ax)
    r = grown_radii(balls, tau)
    with style():
        fill = to_rgba(color or COLORS["ball"], 0.35)
        _disk_collection(ax, balls.centers, r, facecolors=[fill], edgecolors=[COLORS["ball_edge"]], linewidths=1.2)
        if show_centers and len(balls):
            ax.scatter(*balls.centers.T, s=10, color=COLORS["complex"], zorder=4)
        if labels:
            for i, c in enumerate(balls.centers):
                ax.annotate(str(i), c, xytext=(3, 3), textcoords="offset points", fontsize=8)
        _limits_2d(ax, balls.centers, r)
        handles = [Patch(facecolor=fill, edgecolor=COLORS["ball_edge"], label="disk")]
        if show_centers:
            handles.append(Line2D([], [], ls="", marker="o", ms=4, color=COLORS["complex"], label="centre"))
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        ax.set_title(title if title is not None else f"{len(balls)} disks" + (f", {_tau_title(tau)}" if tau else ""))
        born = int((r > 0).sum())
        describe(
            ax,
            f"{_plural(len(balls), 'disk')}"
            + (f" grown to τ = {_fmt(tau)} ({born} born)" if tau else "")
            + (f", radii from {_fmt(float(r.min()))} to {_fmt(float(r.max()))}" if len(balls) else "")
            + (", centres marked" if show_centers and len(balls) else "")
            + (", each labelled with its index" if labels else "")
            + (f"; {title}" if title else ""),
        )
    return fig


# -------------------------------------------------------- power diagram
def power_diagram(
    balls_or_diagram: Balls | PowerDiagram,
    *,
    bbox: ArrayLike | None = None,
    ax: Axes | None = None,
    show_disks: bool = True,
    labels: bool = False,
    title: str | None = None,
) -> Figure:
    """Draw the power diagram :math:`\\Pi(\\mathbb{P})` of disks (Notes §23.1).

    Cells are clipped to a box; hidden disks (whose cell is empty) are dashed.

    Parameters
    ----------
    balls_or_diagram : Balls or PowerDiagram
        2D balls, or the result of :func:`shapelab.power_diagram`.
    bbox : array_like (2, 2), optional
        Clipping box when ``balls_or_diagram`` is a Balls.
    ax : matplotlib Axes, optional
    show_disks, labels : bool
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.power_diagram
        The diagram drawn.
    lifting
        The lifting map behind it.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = power_diagram(sl.Balls([[0.0, 0.0], [3.0, 0.0], [1.0, 2.5]], [1.0, 1.5, 0.8]))
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    Power diagram of 3 disks: 3 power cells outlined, no hidden disk.
    """
    from ..power import PowerDiagram
    from ..power import power_diagram as _pd

    if isinstance(balls_or_diagram, PowerDiagram):
        pd = balls_or_diagram
        if bbox is not None:
            raise ValueError("bbox is only used when a Balls is given; the diagram was already clipped")
    else:
        _check_balls(balls_or_diagram, "balls_or_diagram", dim=2)
        pd = _pd(balls_or_diagram, bbox=bbox)
    balls = pd.balls
    _check_balls(balls, "balls_or_diagram", dim=2)
    fig, ax = axes(ax)
    with style():
        polys = [c for c in pd.cells if len(c) >= 3]
        ax.add_collection(
            PolyCollection(
                polys, facecolors=[to_rgba(COLORS["cell"], 0.10)], edgecolors=[COLORS["cell"]], linewidths=1.4, zorder=1
            )
        )
        handles = [Patch(facecolor=to_rgba(COLORS["cell"], 0.10), edgecolor=COLORS["cell"], label="power cell Π(B)")]
        vis = ~pd.hidden
        if show_disks:
            _disk_collection(
                ax,
                balls.centers[vis],
                balls.radii[vis],
                facecolors=[to_rgba(COLORS["ball"], 0.25)],
                edgecolors=[COLORS["ball_edge"]],
                linewidths=1.0,
                zorder=2,
            )
            handles.append(Patch(facecolor=to_rgba(COLORS["ball"], 0.25), edgecolor=COLORS["ball_edge"], label="disk"))
        if pd.hidden.any():
            _disk_collection(
                ax,
                balls.centers[pd.hidden],
                balls.radii[pd.hidden],
                facecolors="none",
                edgecolors=[COLORS["void"]],
                linewidths=1.3,
                linestyles="--",
                zorder=3,
            )
            ax.scatter(*balls.centers[pd.hidden].T, s=18, facecolors="white", edgecolors=COLORS["void"], zorder=4)
            handles.append(Line2D([], [], color=COLORS["void"], ls="--", label="hidden disk (empty cell)"))
        if vis.any():
            ax.scatter(*balls.centers[vis].T, s=10, color=COLORS["complex"], zorder=4)
        if labels:
            for i, c in enumerate(balls.centers):
                ax.annotate(str(i), c, xytext=(3, 3), textcoords="offset points", fontsize=8)
        _limits_2d(ax, balls.centers, balls.radii, bbox=pd.bbox)
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        nh = int(pd.hidden.sum())
        ax.set_title(title if title is not None else f"Power diagram of {len(balls)} disks ({nh} hidden)")
        describe(
            ax,
            f"Power diagram of {_plural(len(balls), 'disk')}: {_plural(len(polys), 'power cell')} outlined, "
            + (f"{_plural(nh, 'hidden disk')} with an empty cell, dashed" if nh else "no hidden disk")
            + (f"; {title}" if title else ""),
        )
    return fig


# --------------------------------------------------------- dual complex
class DualComplexView:
    """The artists of Figure 23.1 (i) at one growth time, updatable in place.

    Created by :func:`dual_complex`; :meth:`update` moves the drawing to another τ by
    changing the artists (disk radii, clip circles, edge segments, triangles) instead
    of drawing a new figure, which is what :func:`shapelab.widgets.alpha_explorer`
    calls on every slider move.

    Attributes
    ----------
    figure, ax : the matplotlib figure and axes
    filtration : Filtration
    complex : Complex
        The dual complex currently drawn.

    Parameters are those of :func:`dual_complex`, plus ``legend`` (bool) and
    ``view_tau``: the largest τ the view should have room for.

    See Also
    --------
    dual_complex
        Produces it.
    """

    def __init__(
        self,
        F,
        tau=0.0,
        *,
        ax=None,
        show_cells=True,
        show_disks=True,
        bbox=None,
        labels=False,
        title=None,
        legend=True,
        view_tau=None,
    ):
        F = as_filtration(F, "DualComplexView")
        balls = F.balls
        _check_balls(balls, dim=2)
        tau = as_tau(tau, finite=True)
        self.balls = balls
        self.filtration, self.complex = F, F.complex_at(tau)
        self.figure, self.ax = axes(ax)
        self._title = title
        ax = self.ax
        r = grown_radii(balls, tau)
        with style():
            self._disks = None
            disk_face = "none" if show_cells else to_rgba(COLORS["ball"], 0.3)
            if show_disks:
                # with the cells shown, the disks' outlines are thin and light: inside the union
                # they are not boundaries, the cells' edges are (Figure 23.1 (i))
                edge = to_rgba(COLORS["ball_edge"], 0.45) if show_cells else COLORS["ball_edge"]
                self._disks = _disk_collection(
                    ax,
                    balls.centers,
                    r,
                    facecolors=[disk_face],
                    edgecolors=[edge],
                    linewidths=0.8 if show_cells else 1.0,
                    zorder=3,
                )
            self._cells = None
            if show_cells and len(balls):
                self._cell_bbox = self._cell_box(balls, bbox)
                self._cells = PolyCollection(
                    [], facecolors=[to_rgba(COLORS["cell"], 0.25)], edgecolors=["#8A4B00"], linewidths=2.0, zorder=3.5
                )
                ax.add_collection(self._cells, autolim=False)
                self._set_cells(tau)
            self._tri = PolyCollection(
                [],
                facecolors=[to_rgba(COLORS["triangle"], 0.55)],
                edgecolors=[COLORS["triangle"]],
                linewidths=0.6,
                zorder=4,
            )
            ax.add_collection(self._tri, autolim=False)
            self._edges = LineCollection([], colors=[COLORS["complex"]], linewidths=1.6, zorder=5)
            ax.add_collection(self._edges, autolim=False)
            self._verts = ax.scatter([], [], s=14, color=COLORS["complex"], zorder=6)
            if labels:
                for i, c in enumerate(balls.centers):
                    ax.annotate(str(i), c, xytext=(3, 3), textcoords="offset points", fontsize=8)
            lim_r = np.maximum(r, balls.radii)
            if view_tau is not None:  # keep room for the disks grown up to view_tau
                lim_r = np.maximum(lim_r, grown_radii(balls, as_tau(view_tau, "view_tau", finite=True)))
            _limits_2d(ax, balls.centers, lim_r, bbox=bbox)
            if legend:
                handles = []
                if show_disks:
                    handles.append(
                        Patch(
                            facecolor=disk_face,
                            label="disk $B_i$",
                            edgecolor=to_rgba(COLORS["ball_edge"], 0.45) if show_cells else COLORS["ball_edge"],
                        )
                    )
                if show_cells:
                    handles.append(
                        Patch(
                            facecolor=to_rgba(COLORS["cell"], 0.30),
                            edgecolor="#8A4B00",
                            linewidth=2.0,
                            label="$B_i \\cap \\Pi(B_i)$",
                        )
                    )
                handles += [
                    Line2D([], [], color=COLORS["complex"], marker="o", ms=4, lw=1.6, label="vertex, edge of K"),
                    Patch(
                        facecolor=to_rgba(COLORS["triangle"], 0.55), edgecolor=COLORS["triangle"], label="triangle of K"
                    ),
                ]
                ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        self._set_complex(self.complex)

    @staticmethod
    def _cell_box(balls, bbox):
        if bbox is not None:
            return bbox
        # cells are clipped by the disks; the box only has to hold the largest disks shown
        span = float(np.ptp(balls.centers, axis=0).max()) if len(balls) > 1 else 1.0
        pad = 2.0 * float(balls.radii.max()) + span + 1.0
        return np.array([balls.centers.min(axis=0) - pad, balls.centers.max(axis=0) + pad])

    def _set_cells(self, tau):
        polys = self.filtration.clipped_cells(tau, bbox=self._cell_bbox, arc_resolution=72)
        self._cells.set_verts([p for p in polys if len(p) >= 3])

    def _set_complex(self, K):
        c = self.balls.centers
        self._tri.set_verts(list(_segments(c, K.simplices(2))) if K.dimension >= 2 else [])
        self._edges.set_segments(list(_segments(c, K.simplices(1))) if K.dimension >= 1 else [])
        v = K.simplices(0)[:, 0] if K.dimension >= 0 else np.zeros(0, dtype=np.int64)
        self._verts.set_offsets(c[v] if len(v) else np.zeros((0, 2)))
        n = K.counts() + (0,) * (3 - len(K.counts()))
        self.ax.set_title(
            self._title
            if self._title is not None
            else f"Dual complex K at {_tau_title(K.tau)}\n{n[0]} vertices, {n[1]} edges, {n[2]} triangles"
        )
        describe(
            self.ax,
            f"The dual complex of the {_plural(len(self.balls), 'disk')} at τ = {_fmt(K.tau)}: {_counts(n)}"
            + (", drawn over the disks and their clipped power cells" if self._cells is not None else "")
            + (f"; {self._title}" if self._title else ""),
        )

    # ---------------------------------------------------- fast re-rendering
    def _dynamic(self):
        arts = [a for a in (self._disks, self._cells, self._tri, self._edges, self._verts) if a is not None]
        return sorted(arts, key=lambda a: a.get_zorder())

    def render(self) -> np.ndarray:
        """Render the figure to an RGBA array, redrawing only what moves.

        The first call draws the static part (axes, ticks, legend) once and keeps it;
        later calls restore it and draw the disks, cells and complex on top
        (blitting).  Used by the α-explorer, where it keeps an update well under
        100 ms for a few hundred disks.  With an automatic title (``title=None``) the
        title changes with τ, so the whole figure is drawn instead.
        """
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        fig = self.figure
        if not isinstance(fig.canvas, FigureCanvasAgg):
            FigureCanvasAgg(fig)
        canvas = fig.canvas
        if self._title is None:
            canvas.draw()
            return np.asarray(canvas.buffer_rgba())
        size = canvas.get_width_height()
        if getattr(self, "_background", None) is None or self._background_size != size:
            if fig.get_layout_engine() is not None:
                # lay out once, then freeze: later frames only move artists
                canvas.draw()
                fig.set_layout_engine("none")
            dyn = self._dynamic()
            vis = [a.get_visible() for a in dyn]
            for a in dyn:
                a.set_visible(False)
            canvas.draw()
            self._background = canvas.copy_from_bbox(fig.bbox)
            self._background_size = size
            for a, v in zip(dyn, vis):
                a.set_visible(v)
        canvas.restore_region(self._background)
        renderer = canvas.get_renderer()
        for a in self._dynamic():
            if a.get_visible():
                a.draw(renderer)
        return np.asarray(canvas.buffer_rgba())

    def png(self) -> bytes:
        """The current frame as PNG bytes (see :meth:`render`)."""
        import io

        from PIL import Image

        buf = io.BytesIO()
        Image.fromarray(self.render()).save(buf, format="png", compress_level=1)
        return buf.getvalue()

    def update(self, tau) -> "DualComplexView":
        """Redraw at growth time ``tau``: only ``complex_at(tau)`` is computed."""
        tau = as_tau(tau, finite=True)
        r = grown_radii(self.balls, tau)
        if self._disks is not None:
            self._disks.set_widths(2 * r)
            self._disks.set_heights(2 * r)
        if self._cells is not None:
            self._set_cells(tau)
        self.complex = self.filtration.complex_at(tau)
        self._set_complex(self.complex)
        return self


def dual_complex(
    F: Filtration | Balls,
    tau: float = 0.0,
    *,
    ax: Axes | None = None,
    show_cells: bool = True,
    show_disks: bool = True,
    bbox: ArrayLike | None = None,
    labels: bool = False,
    title: str | None = None,
) -> Figure:
    """Figure 23.1 (i): disks, clipped cells :math:`B_i \\cap \\Pi(B_i)` and the dual
    complex K on top (Notes §23.1).

    Parameters
    ----------
    F : Filtration or Balls
        ``alpha_filtration(balls)`` of 2D balls, or the balls (their filtration is
        then built for this figure).
    tau : float
        Growth time; 0 draws the balls as given.
    ax : matplotlib Axes, optional
    show_cells, show_disks, labels : bool
    bbox : array_like (2, 2), optional
        Box for the power cells and the view.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.dual_complex
        The complex drawn.
    filtration
        All simplices by entry time.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.figure_23_1())
    >>> fig = dual_complex(F, tau=0.0)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    The dual complex of the 13 disks at τ = 0: 13 vertices, 10 edges, 2 triangles, drawn over the disks and their clipped power cells.
    """
    return DualComplexView(
        F, tau, ax=ax, show_cells=show_cells, show_disks=show_disks, bbox=bbox, labels=labels, title=title
    ).figure


# ------------------------------------------------------------ filtration
def filtration(
    F: Filtration | Balls,
    *,
    tau: float | None = None,
    ax: Axes | None = None,
    cmap: str = "cividis",
    show_disks: bool = False,
    title: str | None = None,
) -> Figure:
    """Figure 23.1 (ii): the simplices of DT shaded by entry time (Notes §23.1).

    Early simplices are dark and drawn thick, late ones light and thin, as in the
    notes' figure; a colourbar gives the entry time τ.

    Parameters
    ----------
    F : Filtration or Balls
        ``alpha_filtration`` of 2D balls, or the balls (their filtration is built once
        and kept with them).
    tau : float, optional
        Draw only the simplices present at this time (default: all of DT).
    ax : matplotlib Axes, optional
    cmap : str
        A sequential colour map.
    show_disks : bool
        Also draw the input disks, faintly.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.alpha_filtration
        The filtration drawn.
    dual_complex
        One time.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.figure_23_1())
    >>> fig = filtration(F, tau=0.5)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    The α-filtration of 13 disks (τ = 0.5, α = √τ = 0.707): 13 vertices, 12 edges, 2 triangles, shaded by entry time in deciles, early simplices dark and thick, late ones light and thin; entry times from -0.489 to 0.482.
    """
    from ..filtration import Filtration

    if isinstance(F, Balls):
        F = as_filtration(F, "plot.filtration")
    if not isinstance(F, Filtration):
        raise TypeError(f"F must be a shapelab Filtration (alpha_filtration(balls)) or Balls, got {type(F).__name__}")
    _check_balls(F.balls, "F.balls", dim=2)
    t = np.inf if tau is None else as_tau(tau, finite=True)
    K = F.complex_at(t)
    c = F.balls.centers
    fig, ax = axes(ax)
    with style():
        shown = [K.values(k) for k in (1, 2) if K.dimension >= k]
        vals = np.concatenate(shown) if shown else np.zeros(0)
        vals = vals[np.isfinite(vals)]
        # entry times are very unevenly spread (a few hull slivers enter very late):
        # colour by decile of entry time, so that the order of entry is what shows
        bounds = np.unique(np.quantile(vals, np.linspace(0, 1, 11))) if vals.size else np.array([0.0, 1.0])
        if bounds.size < 2:
            bounds = np.array([bounds[0] - 0.5, bounds[0] + 0.5])
        norm = BoundaryNorm(bounds, 256)
        if show_disks:
            _disk_collection(
                ax,
                c,
                F.balls.radii,
                facecolors="none",
                edgecolors=[to_rgba(COLORS["muted"], 0.6)],
                linewidths=0.8,
                zorder=0,
            )
        if K.dimension >= 2:
            tri = PolyCollection(
                list(_segments(c, K.simplices(2))), array=K.values(2), cmap=cmap, norm=norm, edgecolors="none", zorder=1
            )
            ax.add_collection(tri)
        if K.dimension >= 1:
            ev = K.values(1)
            lw = 0.6 + 2.6 * (1 - np.searchsorted(bounds, ev, side="right") / bounds.size)
            edges = LineCollection(
                list(_segments(c, K.simplices(1))), array=ev, cmap=cmap, norm=norm, linewidths=lw, zorder=2
            )
            ax.add_collection(edges)
        if K.dimension >= 0:
            ax.scatter(*c[K.simplices(0)[:, 0]].T, s=12, color=COLORS["complex"], zorder=3)
        sm = ScalarMappable(norm=norm, cmap=cmap)
        cb = fig.colorbar(sm, ax=ax, shrink=0.85, spacing="uniform", ticks=bounds, format="%.3g")
        cb.set_label("entry time τ (deciles; early: dark and thick)")
        _limits_2d(ax, c, F.balls.radii if show_disks else np.zeros(len(c)))
        n = K.counts() + (0,) * (3 - len(K.counts()))
        what = "all of DT" if tau is None else _tau_title(t)
        ax.set_title(
            title
            if title is not None
            else f"α-filtration shaded by entry time ({what})\n{n[0]} vertices, {n[1]} edges, {n[2]} triangles"
        )
        first = f"{_fmt(float(vals.min()))} to {_fmt(float(vals.max()))}" if vals.size else "none"
        describe(
            ax,
            f"The α-filtration of {_plural(len(F.balls), 'disk')} ({what}): {_counts(n)}, shaded by entry time "
            f"in deciles, early simplices dark and thick, late ones light and thin; entry times from {first}"
            + (f"; {title}" if title else ""),
        )
    return fig


# ------------------------------------------------------------------- 3D
def _bounds_3d(centers, radii):
    if not len(centers):
        return -np.ones(3), np.ones(3)
    lo = (centers - radii[:, None]).min(axis=0)
    hi = (centers + radii[:, None]).max(axis=0)
    ext = float(np.max(hi - lo))
    pad = 0.05 * ext if ext > 0 else 1.0
    lo, hi = lo - pad, hi + pad
    # cubic box so that spheres look round
    mid, half = (lo + hi) / 2, np.max(hi - lo) / 2
    return mid - half, mid + half


def _sphere_quads(centers, radii, resolution):
    """Quadrilaterals approximating spheres, and their outward normals (for shading)."""
    u = np.linspace(0, 2 * np.pi, 2 * resolution + 1)
    v = np.linspace(0, np.pi, resolution + 1)
    uu, vv = np.meshgrid(u, v)
    unit = np.stack([np.cos(uu) * np.sin(vv), np.sin(uu) * np.sin(vv), np.cos(vv)], axis=-1)
    q = np.stack([unit[:-1, :-1], unit[:-1, 1:], unit[1:, 1:], unit[1:, :-1]], axis=2).reshape(-1, 4, 3)
    normals = q.mean(axis=1)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    quads = centers[:, None, None, :] + radii[:, None, None, None] * q[None]
    return quads.reshape(-1, 4, 3), np.tile(normals, (len(centers), 1))


def _shade(color, normals, alpha):
    light = np.array([-0.4, -0.5, 0.77])
    light /= np.linalg.norm(light)
    k = 0.45 + 0.55 * np.clip(normals @ light, 0, 1)
    base = np.array(to_rgba(color))[:3]
    rgb = np.clip(base[None] * k[:, None] + 0.12 * (1 - k[:, None]), 0, 1)
    return np.column_stack([rgb, np.full(len(k), alpha)])


def balls3d(
    balls: Balls,
    *,
    tau: float = 0.0,
    ax: Axes | None = None,
    resolution: int = 10,
    alpha: float = 0.35,
    color: ColorType | None = None,
    elev: float = 20.0,
    azim: float = 35.0,
    title: str | None = None,
) -> Figure:
    """Draw 3D balls as shaded low-resolution spheres (Notes §23.1).

    Parameters
    ----------
    balls : Balls
        3D balls.
    tau : float
        Growth time (radii :math:`\\sqrt{r_i^2 + \\tau}`).
    ax : 3D matplotlib Axes, optional
    resolution : int
        Quadrilaterals per sphere: 2·resolution around, resolution from pole to pole.
    alpha : float
        Opacity of the spheres.
    color : colour, optional
    elev, azim : float
        View angles.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    complex3d
        The dual complex in 3D.
    shapelab.plot.view3d
        An interactive view.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = balls3d(sl.Balls([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], [1.0, 1.2]), resolution=6)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    3D view of 2 balls as shaded spheres, seen from elevation 20°, azimuth 35°.
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    _check_balls(balls, dim=3)
    tau = as_tau(tau, finite=True)
    resolution = as_positive_int(resolution, "resolution", minimum=3)
    alpha = as_finite_scalar(alpha, "alpha")
    fig, ax = axes(ax, projection="3d")
    r = grown_radii(balls, tau)
    live = r > 0
    with style():
        quads, normals = _sphere_quads(balls.centers[live], r[live], resolution)
        coll = Poly3DCollection(
            quads, facecolors=_shade(color or COLORS["ball"], normals, alpha), edgecolors="none", linewidths=0
        )
        ax.add_collection3d(coll)
        set_3d_view(ax, *_bounds_3d(balls.centers, r), elev, azim)
        ax.legend(
            handles=[Patch(facecolor=to_rgba(color or COLORS["ball"], 0.6), label="ball")],
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
        )
        ax.set_title(title if title is not None else f"{len(balls)} balls" + (f", {_tau_title(tau)}" if tau else ""))
        describe(
            ax,
            f"3D view of {_plural(len(balls), 'ball')} as shaded spheres"
            + (f" grown to τ = {_fmt(tau)}" if tau else "")
            + f", seen from elevation {_fmt(elev)}°, azimuth {_fmt(azim)}°"
            + (f"; {title}" if title else ""),
        )
    return fig


def complex3d(
    complex_or_filtration: Complex | Filtration | Balls,
    *,
    tau: float | None = None,
    ax: Axes | None = None,
    show_balls: bool = False,
    cmap: str = "cividis",
    elev: float = 20.0,
    azim: float = 35.0,
    resolution: int = 8,
    title: str | None = None,
) -> Figure:
    """Draw a 3D dual complex: vertices, edges (lines), triangles (Notes §23.1).

    Parameters
    ----------
    complex_or_filtration : Complex, Filtration or Balls
        With a Filtration, the complex at ``tau`` (default 0) is drawn with its
        simplices shaded by entry time and a colourbar; Balls stand for their
        filtration (built once and kept with them); a Complex is drawn in the
        course colours.
    tau : float, optional
        Only with a Filtration or Balls.
    ax : 3D matplotlib Axes, optional
    show_balls : bool
        Also draw the balls grown to τ, translucent.
    cmap : str
    elev, azim : float
    resolution : int
        Sphere resolution when ``show_balls``.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    balls3d
        The balls.
    shapelab.dual_complex
        The complex drawn.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.7, 0.0], [1.0, 0.6, 1.6]], 1.0))
    >>> fig = complex3d(F, tau=0.5)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    3D view of the dual complex of 4 balls at τ = 0.5: 4 vertices, 6 edges, 4 triangles, 1 tetrahedron, simplices shaded by entry time.
    """
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    from ..filtration import Complex, Filtration

    if isinstance(complex_or_filtration, Balls):
        complex_or_filtration = as_filtration(complex_or_filtration, "plot.complex3d")
    if isinstance(complex_or_filtration, Filtration):
        t = 0.0 if tau is None else as_tau(tau, finite=True)
        K, shaded = complex_or_filtration.complex_at(t), True
    elif isinstance(complex_or_filtration, Complex):
        if tau is not None:
            raise ValueError("tau is only used with a Filtration; a Complex already has its tau")
        K, shaded = complex_or_filtration, False
    else:
        raise TypeError(
            f"complex_or_filtration must be a Complex, a Filtration or Balls, got {type(complex_or_filtration).__name__}"
        )
    balls = _check_balls(K.balls, "complex_or_filtration.balls", dim=3)
    c = balls.centers
    fig, ax = axes(ax, projection="3d")
    r = grown_radii(balls, K.tau) if np.isfinite(K.tau) else balls.radii
    with style():
        vals = [K.values(k) for k in (1, 2) if K.dimension >= k]
        vals = np.concatenate(vals) if vals else np.zeros(0)
        vals = vals[np.isfinite(vals)]
        lo, hi = (float(vals.min()), float(vals.max())) if vals.size else (0.0, 1.0)
        norm = Normalize(lo, hi if hi > lo else lo + 1.0)
        sm = ScalarMappable(norm=norm, cmap=cmap)
        handles = []
        if show_balls:
            live = r > 0
            quads, normals = _sphere_quads(c[live], r[live], resolution)
            ax.add_collection3d(
                Poly3DCollection(
                    quads, facecolors=_shade(COLORS["ball"], normals, 0.12), edgecolors="none", linewidths=0
                )
            )
            handles.append(Patch(facecolor=to_rgba(COLORS["ball"], 0.3), label="ball"))
        if K.dimension >= 2:
            T = K.simplices(2)
            fc = sm.to_rgba(K.values(2), alpha=0.45) if shaded else [to_rgba(COLORS["triangle"], 0.4)]
            ax.add_collection3d(
                Poly3DCollection(c[T], facecolors=fc, edgecolors=[to_rgba(COLORS["triangle"], 0.5)], linewidths=0.3)
            )
            handles.append(Patch(facecolor=to_rgba(COLORS["triangle"], 0.4), label=f"{len(T)} triangles"))
        if K.dimension >= 1:
            E = K.simplices(1)
            ec = sm.to_rgba(K.values(1)) if shaded else [COLORS["complex"]]
            ax.add_collection3d(Line3DCollection(c[E], colors=ec, linewidths=1.2))
            handles.append(Line2D([], [], color=COLORS["complex"], lw=1.2, label=f"{len(E)} edges"))
        if K.dimension >= 0:
            v = K.simplices(0)[:, 0]
            ax.scatter(*c[v].T, s=10, color=COLORS["complex"], depthshade=False)
            handles.append(Line2D([], [], ls="", marker="o", ms=4, color=COLORS["complex"], label=f"{len(v)} vertices"))
        if shaded:
            cb = fig.colorbar(sm, ax=ax, shrink=0.7, pad=0.12)
            cb.set_label("entry time τ")
        set_3d_view(ax, *_bounds_3d(c, r if show_balls else np.zeros(len(c))), elev, azim)
        n = K.counts() + (0,) * (4 - len(K.counts()))
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(-0.25, 1.0))
        ax.set_title(
            title
            if title is not None
            else f"Dual complex K at {_tau_title(K.tau) if np.isfinite(K.tau) else 'τ = ∞ (all of DT)'}\n"
            f"{n[0]} vertices, {n[1]} edges, {n[2]} triangles, {n[3]} tetrahedra"
        )
        when = f"τ = {_fmt(K.tau)}" if np.isfinite(K.tau) else "τ = ∞ (all of DT)"
        describe(
            ax,
            f"3D view of the dual complex of {_plural(len(balls), 'ball')} at {when}: {_counts(n)}"
            + (", simplices shaded by entry time" if shaded else "")
            + (", over the translucent balls" if show_balls else "")
            + (f"; {title}" if title else ""),
        )
    return fig


# --------------------------------------------------------------- lifting map
def lifting(
    balls: Balls, *, ax: Axes | None = None, elev: float = 18.0, azim: float = -60.0, title: str | None = None
) -> Figure:
    """The lifting map of disks (Notes §23.1, the power diagram and DT).

    The disk :math:`(z_i, r_i)` is lifted to the point
    :math:`(z_i, \\lVert z_i \\rVert^2 - r_i^2)`, on the paraboloid
    :math:`x_3 = \\lVert x \\rVert^2` when :math:`r_i = 0` and :math:`r_i^2` below it
    otherwise.  The lower convex hull of the lifted points projects to the regular
    triangulation (drawn both on the hull and in the plane below); hidden disks are
    the lifted points strictly above the hull.  The power distance is the vertical
    distance from the paraboloid point above x down to the *polar plane*
    :math:`h_i` of the lifted point (not a plane through it: :math:`h_i` lies
    :math:`r_i^2` above the paraboloid at :math:`z_i`, the lifted point :math:`r_i^2`
    below): :math:`\\pi_i(x) = \\lVert x \\rVert^2 - (2 z_i \\cdot x - \\lVert z_i
    \\rVert^2 + r_i^2)`.

    Parameters
    ----------
    balls : Balls
        2D disks.
    ax : 3D matplotlib Axes, optional
    elev, azim : float
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    power_diagram
        The projected lower hull.
    shapelab.regular_triangulation
        The triangulation.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = lifting(sl.Balls([[0.0, 0.0], [3.0, 0.0], [1.0, 2.5]], [1.0, 1.5, 0.8]))
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    The lifting map of 3 disks: each disk lifted to a point on or below the paraboloid; the lower convex hull of the lifted points (1 triangle) projects to the regular triangulation drawn in the plane below; no disk is hidden.
    """
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    from ..power import power_diagram as _pd
    from ..power import regular_triangulation

    _check_balls(balls, dim=2)
    fig, ax = axes(ax, projection="3d")
    c = balls.centers
    h = np.einsum("ij,ij->i", c, c) - balls.weights
    lifted = np.column_stack([c, h])
    with style():
        if len(balls):
            lo, hi = c.min(axis=0) - 0.5, c.max(axis=0) + 0.5
            g0, g1 = np.meshgrid(np.linspace(lo[0], hi[0], 25), np.linspace(lo[1], hi[1], 25))
            ax.plot_wireframe(g0, g1, g0**2 + g1**2, color=COLORS["muted"], linewidth=0.4, alpha=0.5)
            floor = min(float(h.min()), 0.0) - 0.15 * (float(np.ptp(h)) + 1.0)
            tri = regular_triangulation(balls) if len(balls) >= 3 else np.zeros((0, 3), dtype=np.int64)
            hidden = _pd(balls).hidden
            if tri.shape[1] == 3 and len(tri):
                ax.add_collection3d(
                    Poly3DCollection(
                        lifted[tri],
                        facecolors=[to_rgba(COLORS["triangle"], 0.35)],
                        edgecolors=[COLORS["triangle"]],
                        linewidths=0.8,
                    )
                )
                flat = np.concatenate([c[tri], np.full(tri.shape + (1,), floor)], axis=2)
                edges = np.concatenate([flat[:, [0, 1]], flat[:, [1, 2]], flat[:, [2, 0]]])
                ax.add_collection3d(Line3DCollection(edges, colors=[COLORS["complex"]], linewidths=0.7))
            drops = np.stack([lifted, np.column_stack([c, np.full(len(c), floor)])], axis=1)
            ax.add_collection3d(
                Line3DCollection(drops, colors=[to_rgba(COLORS["muted"], 0.7)], linewidths=0.6, linestyles=":")
            )
            vis = ~hidden
            ax.scatter(*lifted[vis].T, s=18, color=COLORS["ball_edge"], depthshade=False)
            if hidden.any():
                ax.scatter(*lifted[hidden].T, s=30, facecolors="white", edgecolors=COLORS["void"], depthshade=False)
            ax.set_zlim(floor, float(max(h.max(), (hi**2).sum())))
            ax.set_xlim(lo[0], hi[0])
            ax.set_ylim(lo[1], hi[1])
        ax.view_init(elev=elev, azim=azim)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel(r"$|z|^2 - r^2$")
        ax.legend(
            handles=[
                Line2D([], [], color=COLORS["muted"], lw=0.6, label=r"paraboloid $x_3 = |x|^2$"),
                Line2D([], [], ls="", marker="o", ms=5, color=COLORS["ball_edge"], label="lifted disk"),
                Line2D(
                    [], [], ls="", marker="o", ms=6, mfc="white", mec=COLORS["void"], label="hidden: above the hull"
                ),
                Patch(
                    facecolor=to_rgba(COLORS["triangle"], 0.35), edgecolor=COLORS["triangle"], label="lower convex hull"
                ),
                Line2D([], [], color=COLORS["complex"], lw=0.7, label="its projection: DT"),
            ],
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
        )
        ax.set_title(
            title if title is not None else "The lifting map: the lower hull projects to the regular triangulation"
        )
        if len(balls):
            describe(
                ax,
                f"The lifting map of {_plural(len(balls), 'disk')}: each disk lifted to a point on or below the "
                f"paraboloid; the lower convex hull of the lifted points ({_plural(len(tri), 'triangle')}) projects "
                f"to the regular triangulation drawn in the plane below; "
                + (
                    f"{_plural(int(hidden.sum()), 'hidden disk')} lifted above the hull, as open circles"
                    if hidden.any()
                    else "no disk is hidden"
                )
                + (f"; {title}" if title else ""),
            )
    return fig


# ------------------------------------------------------- method comparison
def method_comparison(
    sizes: ArrayLike,
    seconds: dict[str, ArrayLike],
    errors: dict[str, ArrayLike] | None = None,
    *,
    xlabel: str = "number of disks n",
    ax: Axes | None = None,
    title: str | None = None,
) -> Figure:
    """Times (and errors) of several methods against the input size, on log axes.

    Parameters
    ----------
    sizes : array_like, shape (m,)
    seconds : dict
        ``{method name: (m,) array of times in seconds}`` (NaN where not run).
    errors : dict, optional
        ``{method name: (m,) array of absolute errors}``; drawn in a second panel.
    xlabel, title : str
    ax : matplotlib Axes, optional
        Only without ``errors`` (one panel).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.plot.matching.timings
        A bar chart of times.

    Examples
    --------
    >>> import shapelab as sl
    >>> import numpy as np
    >>> sizes = np.array([10, 100, 1000])
    >>> fig = method_comparison(sizes, {"exact": 1e-5 * sizes, "Monte Carlo": 1e-3 * np.ones(3)},
    ...                         {"exact": np.full(3, 1e-12), "Monte Carlo": 1e-2 / np.sqrt(sizes)})
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    2 panels. Left: Log-scale time in seconds of 2 methods against number of disks n, one line and marker shape per method: exact 0.0001 at 10 to 0.01 at 1000; Monte Carlo 0.001 at 10 to 0.001 at 1000. Right: Log-scale absolute error of 2 methods against number of disks n, one line and marker shape per method: exact 1e-12 at 10 to 1e-12 at 1000; Monte Carlo 0.0032 at 10 to 0.00032 at 1000.
    """
    n = np.asarray(sizes, dtype=float)
    if errors is not None and ax is not None:
        raise ValueError("ax can only be given for a single panel (without errors)")
    if ax is None:
        fig, axes = new_figure(1, 2 if errors else 1)
        axes = np.atleast_1d(axes)
    else:
        fig, axes = ax.get_figure(), np.array([ax])
    markers = "osD^v"
    names = list(seconds) + [k for k in (errors or {}) if k not in seconds]
    look = {name: (PALETTE[j % len(PALETTE)], markers[j % len(markers)]) for j, name in enumerate(names)}
    with style():
        for panel, data, label in ((0, seconds, "time (s)"), (1, errors, "absolute error")):
            if data is None:
                continue
            a = axes[panel]
            for name, vals in data.items():
                v = np.asarray(vals, dtype=float)
                if v.shape != n.shape:
                    raise ValueError(f"{name!r} has {v.shape[0]} values for {n.shape[0]} sizes")
                ok = np.isfinite(v) & (v > 0)
                a.plot(n[ok], v[ok], color=look[name][0], marker=look[name][1], label=name)
            a.set_yscale("log")
            a.set_xlabel(xlabel)
            a.set_ylabel(label)
            a.legend()
        axes[0].set_title(title if title is not None else "Cost of the methods")
        if errors is not None:
            axes[1].set_title("Accuracy (against the exact value)")
        for panel, data, what in ((0, seconds, "time in seconds"), (1, errors, "absolute error")):
            if data is None:
                continue
            ends = []
            for name, vals in data.items():
                v = np.asarray(vals, dtype=float)
                ok = np.flatnonzero(np.isfinite(v) & (v > 0))
                if len(ok):
                    ends.append(f"{name} {v[ok[0]]:.2g} at {n[ok[0]]:g} to {v[ok[-1]]:.2g} at {n[ok[-1]]:g}")
            describe(
                axes[panel],
                f"Log-scale {what} of {len(data)} methods against {xlabel}, one line and marker shape per method: "
                + "; ".join(ends),
            )
    return fig
