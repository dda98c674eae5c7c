"""The α-explorer: the growth model with a slider in τ (Notes §23.1)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import ipywidgets as W
import numpy as np

from .._toolkit.validate import (
    as_finite_scalar,
    as_positive_int,
    as_tau,
)
from ..plot import alt_text
from . import _frame
from .static import StaticFallback

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..balls import Balls
    from ..filtration import Filtration

__all__ = [
    "alpha_explorer",
    "AlphaExplorer",
    "power_explorer",
    "PowerExplorer",
    "complex3d_explorer",
    "Complex3DExplorer",
]


def _n(count: int, one: str, many: str | None = None) -> str:
    """``count`` and the noun, singular for one: "1 triangle", "8 edges", "0 triangles"."""
    return f"{count} {one if count == 1 else (many or one + 's')}"


def _default_range(F):
    """From the first vertex's entry to a little after the last change of topology
    (the largest finite death of the persistence diagram); the last entries of DT
    (slivers on the hull) come much later and are left out."""
    vals = np.concatenate([F.values(k) for k in range(F.dimension + 1)]) if F.dimension >= 0 else np.zeros(0)
    vals = vals[np.isfinite(vals)]
    if not vals.size:
        return -1.0, 1.0
    lo = float(vals.min())
    try:
        deaths = np.concatenate([np.asarray(a, dtype=float).reshape(-1, 2)[:, 1] for a in F.persistence().values()])
        deaths = deaths[np.isfinite(deaths)]
        hi = float(deaths.max()) if deaths.size else float(np.quantile(vals, 0.75))
    except (ImportError, NotImplementedError, AttributeError):  # topology not available
        hi = float(np.quantile(vals, 0.75))
    hi = max(hi, 0.0)
    hi = hi + 0.1 * (hi - lo)
    if not hi > lo:
        hi = lo + max(1.0, abs(lo))
    return lo, hi


def alpha_explorer(
    F: Filtration | Balls,
    *,
    tau: float = 0.0,
    tau_range: tuple[float, float] | None = None,
    steps: int = 100,
    show_cells: bool = True,
    show_measure: bool = True,
    bbox: ArrayLike | None = None,
) -> AlphaExplorer:
    """A slider in the growth time τ over the disks grown to :math:`\\sqrt{r_i^2+\\tau}`
    and their dual complex :math:`K_\\tau` (Notes §23.1, Figure 23.1).

    The α-filtration is computed once; each move of the slider only takes
    ``complex_at(τ)`` and moves the artists of the figure (disk radii, clipped cells,
    edges, triangles).  The status line gives τ and the notes' :math:`\\alpha = \\sqrt\\tau`
    (undefined for τ < 0), the numbers of vertices, edges and triangles of
    :math:`K_\\tau`, its Betti numbers, and the area and perimeter of the union.

    Parameters
    ----------
    F : Filtration or Balls
        ``alpha_filtration(balls)`` of 2D disks, or the disks (their filtration is
        then built here, once).
    tau : float
        Initial growth time.
    tau_range : (float, float), optional
        Slider bounds; default from the first vertex's entry time to a little after the
        last change of topology (the largest finite death in ``F.persistence()``).
    steps : int
        Slider resolution.
    show_cells : bool
        Draw the clipped cells :math:`B_i \\cap \\Pi(B_i)`.
    show_measure : bool
        Report the area and perimeter of the union (:func:`shapelab.union_measure`).
    bbox : array_like (2, 2), optional
        The view (and clipping box of the cells).

    Returns
    -------
    AlphaExplorer
        An ``ipywidgets.VBox``: the slider, a status line and the figure.

    See Also
    --------
    shapelab.alpha_filtration
        The filtration explored.
    shapelab.plot.dual_complex
        One frame.

    Examples
    --------
    >>> import shapelab as sl
    >>> w = alpha_explorer(sl.alpha_filtration(sl.datasets.figure_23_1()), steps=10)
    >>> type(w).__name__
    'AlphaExplorer'
    >>> w.slider.value = 0.5  # the figure and the status line follow the slider
    >>> print(w.status.value)
    τ = 0.500 · α = √τ = 0.707 · K: 13 vertices, 12 edges, 2 triangles · Betti (β₀, β₁) = (4, 1) · area 38.98, perimeter 52.52
    """
    from ..filtration import as_filtration
    from ._frame import check_balls, value_range

    if hasattr(F, "centers"):  # the disks: checked before their filtration is built
        check_balls(F, dim=2, who="alpha_explorer", what="disk")
    F = as_filtration(F, "alpha_explorer")
    balls = F.balls
    check_balls(balls, dim=2, who="alpha_explorer", what="disk")
    tau = as_tau(tau, finite=True)
    steps = as_positive_int(steps, "steps", minimum=2)
    lo, hi = _default_range(F) if tau_range is None else value_range(tau_range, "tau_range")
    tau = min(max(tau, lo), hi)
    return AlphaExplorer(balls, F, tau, lo, hi, (hi - lo) / steps, bool(show_cells), bool(show_measure), bbox)


class AlphaExplorer(StaticFallback, W.VBox):
    """Slider + status + figure; see :func:`alpha_explorer`.

    Attributes
    ----------
    slider : ipywidgets.FloatSlider
    status : ipywidgets.HTML
    image : ipywidgets.Image
        The current frame (PNG), redrawn by blitting (``view.png()``).
    view : shapelab.plot.balls.DualComplexView
        The figure's artists; ``view.complex`` is the complex drawn.

    See Also
    --------
    alpha_explorer
        Produces it.
    """

    def __init__(self, balls, F, tau, lo, hi, step, show_cells, show_measure, bbox):
        from ..plot.balls import DualComplexView

        self._balls = balls
        self._F = F
        self._show_measure = show_measure
        self.view = DualComplexView(
            F,
            tau,
            show_cells=show_cells,
            bbox=bbox,
            view_tau=hi,
            title="The disks grown to time τ and their dual complex $K_\\tau$",
        )
        self.slider = W.FloatSlider(
            value=tau,
            min=lo,
            max=hi,
            step=step,
            description="τ",
            continuous_update=False,
            readout_format=".3f",
            layout=W.Layout(width="70%"),
        )
        self.status = W.HTML()
        self.image = _frame.image(self.view.figure.get_size_inches(), dpi=self.view.figure.dpi)
        super().__init__([self.slider, self.status, self.image])
        self.slider.observe(self._on_change, names="value")
        self._on_change()

    @property
    def figure(self):
        return self.view.figure

    def status_text(self) -> str:
        """The status line as plain text."""
        K = self.view.complex
        t = K.tau
        n = K.counts() + (0,) * (3 - len(K.counts()))
        alpha = f"α = √τ = {np.sqrt(t):.3f}" if t >= 0 else "α = √τ undefined (τ < 0)"
        parts = [
            f"τ = {t:.3f}",
            alpha,
            f"K: {_n(n[0], 'vertex', 'vertices')}, {_n(n[1], 'edge')}, {_n(n[2], 'triangle')}",
        ]
        try:
            b = self._F.betti(t)
            parts.append("Betti (β₀, β₁) = " + f"({b[0]}, {b[1]})")
        except (ImportError, NotImplementedError, AttributeError):  # topology not available
            pass
        if self._show_measure:
            from ..measure import union_measure

            m = union_measure(self._F, t)
            parts.append(f"area {m.area:.4g}, perimeter {m.perimeter:.4g}")
        return " · ".join(parts)

    def update(self, tau=None):
        """Recompute at ``tau`` (default: the slider's value) and move the artists
        (the image is refreshed by the slider's callback, or by ``view.png()``)."""
        t = float(self.slider.value) if tau is None else as_tau(tau, finite=True)
        self.view.update(t)
        self.status.value = self.status_text()
        self.alt = alt_text(self.view.figure)  # what the frame shows (the static player's alt)
        return self

    def _on_change(self, change=None):
        self.update()
        self.image.value = self.view.png()

    def __repr__(self):
        return (
            f"AlphaExplorer(n_balls={len(self._balls)}, tau={self.slider.value:.3f}, "
            f"range=({self.slider.min:.3f}, {self.slider.max:.3f}))"
        )


# --------------------------------------------------------------------------- power
def power_explorer(
    balls: Balls,
    *,
    index: int = 0,
    radius: float | None = None,
    radius_range: tuple[float, float] | None = None,
    steps: int = 100,
    mode: str = "diagram",
    bbox: ArrayLike | None = None,
) -> PowerExplorer:
    """Change one disk's radius and watch its power cell (Notes §23.1).

    The power distance :math:`\\pi_i(x) = \\|x - z_i\\|^2 - r_i^2` makes a larger disk
    push the bisectors away from its centre; shrink it far enough and its cell
    :math:`\\Pi(B_i)` empties: the disk is *hidden* and leaves the regular
    triangulation.  With ``mode="dual"`` the figure is Figure 23.1 (i) instead: the
    clipped cells :math:`B_i \\cap \\Pi(B_i)` and the dual complex K, whose edges
    come and go as the disk grows and shrinks.

    Parameters
    ----------
    balls : Balls
        2D disks.
    index : int
        The disk whose radius the slider sets (a second slider picks another).
    radius : float, optional
        Its initial radius; default its own.
    radius_range : (float, float), optional
        Slider bounds, ``0 <= low < high``; default ``(0, 2 max r)``.
    steps : int
        Slider resolution.
    mode : {"diagram", "dual"}
        Draw the power diagram, or the dual complex of Figure 23.1 (i).
    bbox : array_like (2, 2), optional
        The view and clipping box; default from the disks at the largest radius, so
        the frame stays still while the slider moves.

    Returns
    -------
    PowerExplorer
        An ``ipywidgets.VBox``: the two sliders, a status line and the figure.

    See Also
    --------
    shapelab.power_diagram
        The diagram recomputed.
    shapelab.plot.power_diagram
        One frame.

    Examples
    --------
    >>> import shapelab as sl
    >>> w = power_explorer(sl.Balls([[0.0, 0.0], [3.0, 0.0], [1.0, 2.5]], [1.0, 1.5, 0.8]), steps=10)
    >>> type(w).__name__
    'PowerExplorer'
    >>> print(w.status.value)
    disk 0: r = 1.000 · 2 neighbouring cells · no hidden disks
    """
    from .._toolkit.validate import as_bbox, default_bbox
    from ..balls import Balls
    from ._frame import check_balls, value_range

    check_balls(balls, dim=2, who="power_explorer", minimum=2, what="disk")
    if mode not in ("diagram", "dual"):
        raise ValueError(f"mode must be 'diagram' or 'dual', got {mode!r}")
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < len(balls):
        raise ValueError(f"index must be an integer in [0, {len(balls)}), got {index!r}")
    steps = as_positive_int(steps, "steps", minimum=2)
    if radius_range is None:
        lo, hi = 0.0, 2.0 * float(balls.radii.max()) or 1.0
    else:
        lo, hi = value_range(radius_range, "radius_range", nonnegative=True)
    r0 = float(balls.radii[index]) if radius is None else as_finite_scalar(radius, "radius", nonnegative=True)
    if bbox is None:
        bbox = default_bbox(Balls(balls.centers, np.full(len(balls), max(hi, float(balls.radii.max())))))
    else:
        bbox = as_bbox(bbox, 2)
    return PowerExplorer(balls, int(index), min(max(r0, lo), hi), lo, hi, (hi - lo) / steps, mode, bbox)


class PowerExplorer(StaticFallback, W.VBox):
    """Disk selector + radius slider + status + figure; see :func:`power_explorer`.

    Attributes
    ----------
    disk, slider : ipywidgets.IntSlider, ipywidgets.FloatSlider
    status : ipywidgets.HTML
    image : ipywidgets.Image
    diagram : PowerDiagram
        The power diagram drawn now.

    See Also
    --------
    power_explorer
        Produces it.
    """

    SIZE = (7.2, 5.4)

    def __init__(self, balls, index, radius, lo, hi, step, mode, bbox):

        self._balls = balls
        self._radii = balls.radii.copy()
        self._mode = mode
        self._bbox = bbox
        self.disk = W.IntSlider(
            value=index,
            min=0,
            max=len(balls) - 1,
            description="disk",
            continuous_update=False,
            layout=W.Layout(width="30%"),
        )
        self.slider = W.FloatSlider(
            value=radius,
            min=lo,
            max=hi,
            step=step,
            description="radius",
            continuous_update=False,
            readout_format=".3f",
            layout=W.Layout(width="55%"),
        )
        self.status = W.HTML()
        self.image = _frame.image(self.SIZE)
        super().__init__([W.HBox([self.disk, self.slider]), self.status, self.image])
        self.disk.observe(self._on_disk, names="value")
        self.slider.observe(self._redraw, names="value")
        self._redraw()

    @property
    def balls(self):
        """The disks drawn now: the input with the chosen disk's radius replaced."""
        from ..balls import Balls

        r = self._radii.copy()
        r[self.disk.value] = self.slider.value
        return Balls(self._balls.centers, r)

    def _on_disk(self, change):
        # the new disk starts at its own radius; the redraw happens once
        with self.slider.hold_trait_notifications():
            self.slider.value = min(max(float(self._radii[self.disk.value]), self.slider.min), self.slider.max)
        self._redraw()

    def status_text(self) -> str:
        i = self.disk.value
        pd = self.diagram
        parts = [f"disk {i}: r = {self.slider.value:.3f}"]
        if pd.hidden[i]:
            parts.append("its cell is empty: <b>hidden</b>")
        else:
            k = int(np.count_nonzero((pd.adjacency == i).any(axis=1)))
            parts.append(f"{k} neighbouring cells")
        hidden = np.flatnonzero(pd.hidden)
        parts.append(f"hidden disks: {', '.join(map(str, hidden))}" if hidden.size else "no hidden disks")
        if self._mode == "dual":
            from ..filtration import alpha_filtration

            n = alpha_filtration(self.balls).complex_at(0.0).counts()
            n = tuple(n) + (0,) * (3 - len(n))
            parts.append(f"K: {_n(n[0], 'vertex', 'vertices')}, {_n(n[1], 'edge')}, {_n(n[2], 'triangle')}")
        return " · ".join(parts)

    def figure(self):
        """The current figure."""
        from .. import plot

        i = self.disk.value
        if self._mode == "dual":
            fig = plot.dual_complex(
                self.balls,
                0.0,
                bbox=self._bbox,
                labels=True,
                title=f"Disk {i} at radius {self.slider.value:.2f}: cells and dual complex K",
            )
        else:
            fig = plot.power_diagram(
                self.diagram, labels=True, title=f"Disk {i} at radius {self.slider.value:.2f}: the power diagram"
            )
        from matplotlib.patches import Circle

        ax = fig.axes[0]
        ax.add_patch(
            Circle(self._balls.centers[i], self.slider.value, fill=False, lw=2.5, color=plot.COLORS["accent"], zorder=6)
        )
        fig.set_size_inches(*self.SIZE)
        return fig

    def _redraw(self, change=None):
        from ..power import power_diagram
        from . import _frame

        self.diagram = power_diagram(self.balls, bbox=self._bbox)
        self.status.value = self.status_text()
        fig = self.figure()
        self.image.value = _frame.png(fig)
        self.alt = alt_text(fig)  # what the frame shows (the static player's alt)

    def __repr__(self):
        return (
            f"PowerExplorer(n_balls={len(self._balls)}, disk={self.disk.value}, "
            f"radius={self.slider.value:.3f}, mode={self._mode!r})"
        )


# --------------------------------------------------------------------------- 3D
def complex3d_explorer(
    F: Filtration | Balls,
    *,
    tau: float = 0.0,
    tau_range: tuple[float, float] | None = None,
    steps: int = 60,
    azim: float = 35.0,
    elev: float = 20.0,
    show_balls: bool = True,
    resolution: int = 8,
) -> Complex3DExplorer:
    """The growth model in 3D: a slider in τ and one for the view angle (Notes §23.1).

    Draws the balls grown to :math:`\\sqrt{r_i^2+\\tau}` (translucent) and the dual
    complex :math:`K_\\tau`, shaded by entry time, with its numbers of simplices and
    Betti numbers (β₀ components, β₁ tunnels, β₂ voids) in the status line.

    Parameters
    ----------
    F : Filtration or Balls
        ``alpha_filtration(balls)`` of 3D balls, or the balls (their filtration is
        then built here, once).
    tau : float
        Initial growth time.
    tau_range : (float, float), optional
        Slider bounds; default as for :func:`alpha_explorer`.
    steps : int
        Resolution of the τ slider.
    azim, elev : float
        Initial view angles in degrees; the second slider turns the azimuth.
    show_balls : bool
        Draw the grown balls as well as the complex.
    resolution : int
        Sphere resolution of the balls.

    Returns
    -------
    Complex3DExplorer
        An ``ipywidgets.VBox``: the sliders, a status line and the figure.

    See Also
    --------
    shapelab.plot.complex3d
        One frame.
    alpha_explorer
        The same in 2D.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.7, 0.0], [1.0, 0.6, 1.6]], 1.0))
    >>> w = complex3d_explorer(F, steps=10, show_balls=False)
    >>> type(w).__name__
    'Complex3DExplorer'
    >>> print(w.status.value)
    τ = 0.000 · α = √τ = 0.000 · K: 4 vertices, 6 edges, 0 triangles, 0 tetrahedra · β₀ = 1 components, β₁ = 3 tunnels, β₂ = 0 voids
    """
    from ..filtration import as_filtration
    from ._frame import check_balls, value_range

    if hasattr(F, "centers"):  # the balls: checked before their filtration is built
        check_balls(F, dim=3, who="complex3d_explorer")
    F = as_filtration(F, "complex3d_explorer")
    balls = F.balls
    check_balls(balls, dim=3, who="complex3d_explorer")
    tau = as_tau(tau, finite=True)
    azim = as_finite_scalar(azim, "azim")
    elev = as_finite_scalar(elev, "elev")
    steps = as_positive_int(steps, "steps", minimum=2)
    resolution = as_positive_int(resolution, "resolution", minimum=3)
    lo, hi = _default_range(F) if tau_range is None else value_range(tau_range, "tau_range")
    return Complex3DExplorer(
        balls, F, min(max(tau, lo), hi), lo, hi, (hi - lo) / steps, azim % 360.0, elev, bool(show_balls), resolution
    )


class Complex3DExplorer(StaticFallback, W.VBox):
    """τ slider + azimuth slider + status + figure; see :func:`complex3d_explorer`.

    See Also
    --------
    complex3d_explorer
        Produces it.
    """

    SIZE = (7.0, 5.6)

    def __init__(self, balls, F, tau, lo, hi, step, azim, elev, show_balls, resolution):

        self._balls = balls
        self._F = F
        self._elev = elev
        self._show_balls = show_balls
        self._resolution = resolution
        self.slider = W.FloatSlider(
            value=tau,
            min=lo,
            max=hi,
            step=step,
            description="τ",
            continuous_update=False,
            readout_format=".3f",
            layout=W.Layout(width="50%"),
        )
        self.azim = W.FloatSlider(
            value=azim,
            min=0.0,
            max=360.0,
            step=5.0,
            description="turn",
            continuous_update=False,
            readout_format=".0f",
            layout=W.Layout(width="35%"),
        )
        self.status = W.HTML()
        self.image = _frame.image(self.SIZE)
        super().__init__([W.HBox([self.slider, self.azim]), self.status, self.image])
        self.slider.observe(self._redraw, names="value")
        self.azim.observe(self._redraw, names="value")
        self._redraw()

    @property
    def tau(self) -> float:
        return float(self.slider.value)

    def status_text(self) -> str:
        t = self.tau
        n = tuple(self._F.complex_at(t).counts()) + (0,) * 4
        alpha = f"α = √τ = {np.sqrt(t):.3f}" if t >= 0 else "α undefined (τ < 0)"
        b = self._F.betti(t)
        return (
            f"τ = {t:.3f} · {alpha} · K: {_n(n[0], 'vertex', 'vertices')}, {_n(n[1], 'edge')}, "
            f"{_n(n[2], 'triangle')}, {_n(n[3], 'tetrahedron', 'tetrahedra')} · β₀ = {b[0]} components, β₁ = {b[1]} tunnels, β₂ = {b[2]} voids"
        )

    def figure(self):
        from .. import plot

        fig = plot.complex3d(
            self._F,
            tau=self.tau,
            show_balls=self._show_balls,
            elev=self._elev,
            azim=float(self.azim.value),
            resolution=self._resolution,
            title="The balls grown to time τ and their dual complex $K_\\tau$",
        )
        fig.set_size_inches(*self.SIZE)
        return fig

    def _redraw(self, change=None):

        self.status.value = self.status_text()
        fig = self.figure()
        self.image.value = _frame.png(fig)
        self.alt = alt_text(fig)  # what the frame shows (the static player's alt)

    def __repr__(self):
        return (
            f"Complex3DExplorer(n_balls={len(self._balls)}, tau={self.slider.value:.3f}, "
            f"range=({self.slider.min:.3f}, {self.slider.max:.3f}))"
        )
