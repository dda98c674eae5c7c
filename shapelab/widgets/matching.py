"""The critical-points explorer: move the viewpoint S and watch the extrema of
F(x) = |x − S| move, appear and cancel (notes §23.2, Figure 23.3)."""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

import ipywidgets as W
import numpy as np

from .._toolkit.validate import as_point, as_positive_int
from ..plot import alt_text
from . import _frame
from .static import StaticFallback

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import ArrayLike

__all__ = ["critical_points_explorer", "CriticalPointsExplorer"]

_SIZE = (10.0, 4.6)
_DPI = 80


def critical_points_explorer(
    curve: ArrayLike | Callable[[np.ndarray], ArrayLike],
    *,
    viewpoint: ArrayLike | None = None,
    x_range: tuple[float, float] | None = None,
    y_range: tuple[float, float] | None = None,
    steps: int = 60,
    close: bool = False,
) -> CriticalPointsExplorer:
    """Two sliders move the viewpoint S; the figure of Figure 23.3 follows.

    Parameters
    ----------
    curve : array_like or callable
        A closed polyline (n, 2) or a parametric curve ``t -> (x(t), y(t))`` on
        [0, 2π), as for :func:`shapelab.critical_points`.
    viewpoint : array_like, shape (2,), optional
        The initial S; default the centre of the curve's bounding box.
    x_range, y_range : (float, float), optional
        Slider bounds; default the curve's bounding box, enlarged by 20 %.
    steps : int
        Slider resolution.
    close : bool
        Passed to :func:`shapelab.critical_points` for polylines.

    Returns
    -------
    CriticalPointsExplorer
        An ``ipywidgets.VBox``: the two sliders, a status line with the counts and
        the figure.

    See Also
    --------
    shapelab.critical_points
        What is recomputed.
    shapelab.plot.critical_points
        One frame.

    Examples
    --------
    >>> import shapelab as sl
    >>> w = critical_points_explorer(sl.datasets.blob_curve, viewpoint=(0.1, 0.05), steps=10)
    >>> type(w).__name__
    'CriticalPointsExplorer'
    >>> print(w.status.value)
    3 minima, 3 maxima
    """
    from ..critical import closed_vertices, polyline

    if callable(curve):
        P = polyline(curve, 400)
    else:
        P, _ = closed_vertices(curve, close)
    if P.shape[1] != 2:
        raise ValueError(f"curve must be planar (2 coordinates), got {P.shape[1]}")
    steps = as_positive_int(steps, "steps", minimum=2)
    lo, hi = P.min(axis=0), P.max(axis=0)
    pad = 0.2 * (hi - lo)

    def _range(r, k, name):
        if r is None:
            return float(lo[k] - pad[k]), float(hi[k] + pad[k])
        a, b = (float(v) for v in as_point(r, name, dim=2))
        if not a < b:
            raise ValueError(f"{name} must have low < high, got {tuple(r)!r}")
        return a, b

    xr, yr = _range(x_range, 0, "x_range"), _range(y_range, 1, "y_range")
    S = 0.5 * (lo + hi) if viewpoint is None else as_point(viewpoint, "viewpoint", dim=2)
    return CriticalPointsExplorer(curve, S, xr, yr, steps, bool(close))


class CriticalPointsExplorer(StaticFallback, W.VBox):
    """Sliders + figure; see :func:`critical_points_explorer`.

    See Also
    --------
    critical_points_explorer
        Produces it.
    """

    def __init__(self, curve, S, xr, yr, steps, close):
        self._curve = curve
        self._close = close
        kw = dict(continuous_update=False, readout_format=".2f", layout=W.Layout(width="45%"))
        self.sx = W.FloatSlider(
            value=float(np.clip(S[0], *xr)), min=xr[0], max=xr[1], step=(xr[1] - xr[0]) / steps, description="S x", **kw
        )
        self.sy = W.FloatSlider(
            value=float(np.clip(S[1], *yr)), min=yr[0], max=yr[1], step=(yr[1] - yr[0]) / steps, description="S y", **kw
        )
        self.status = W.HTML()
        # a PNG image, not an Output widget: it renders the same in a live kernel, in
        # nbclient/nbval runs and from the stored widget state on the static site
        self.image = _frame.image(_SIZE, dpi=_DPI)
        super().__init__([W.HBox([self.sx, self.sy]), self.status, self.image])
        self.sx.observe(self._redraw, names="value")
        self.sy.observe(self._redraw, names="value")
        self._redraw()

    @property
    def viewpoint(self) -> np.ndarray:
        return np.array([self.sx.value, self.sy.value])

    def figure(self):
        """The current figure (Figure 23.3 for the current viewpoint)."""
        from ..plot.critical import critical_points as plot_critical

        return plot_critical(self._curve, self.result, size=_SIZE)

    def _redraw(self, change=None):
        from ..critical import critical_points

        self.result = critical_points(self._curve, self.viewpoint, close=self._close)
        if self.result.degenerate:
            self.status.value = "F is constant: every point is critical"
        else:
            self.status.value = f"{self.result.n_min} minima, {self.result.n_max} maxima"
        buf = io.BytesIO()
        fig = self.figure()
        fig.savefig(buf, format="png", dpi=_DPI)
        self.alt = alt_text(fig)  # what the frame shows (the static player's alt)
        self.image.value = buf.getvalue()

    def __repr__(self):
        S = self.viewpoint
        return (
            f"CriticalPointsExplorer(S=({S[0]:.2f}, {S[1]:.2f}), {self.result.n_min} minima, "
            f"{self.result.n_max} maxima)"
        )
