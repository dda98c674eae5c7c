"""The α-explorer: the growth model with a slider in τ (Notes §23.1)."""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from .._validate import as_finite_scalar, as_positive_int

__all__ = ["alpha_explorer", "AlphaExplorer"]


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


def alpha_explorer(balls, *, tau=0.0, tau_range=None, steps=100, filtration=None, show_cells=True,
                   show_measure=True, bbox=None):
    """A slider in the growth time τ over the disks grown to :math:`\\sqrt{r_i^2+\\tau}`
    and their dual complex :math:`K_\\tau` (Notes §23.1, Figure 23.1).

    The α-filtration is computed once; each move of the slider only takes
    ``complex_at(τ)`` and moves the artists of the figure (disk radii, clipped cells,
    edges, triangles).  The status line gives τ and the notes' :math:`\\alpha = \\sqrt\\tau`
    (undefined for τ < 0), the numbers of vertices, edges and triangles of
    :math:`K_\\tau`, its Betti numbers, and the area and perimeter of the union.

    Parameters
    ----------
    balls : Balls
        2D disks.
    tau : float
        Initial growth time.
    tau_range : (float, float), optional
        Slider bounds; default from the first vertex's entry time to a little after the
        last change of topology (the largest finite death in ``F.persistence()``).
    steps : int
        Slider resolution.
    filtration : Filtration, optional
        ``alpha_filtration(balls)`` if already computed.
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
    """
    from ..balls import Balls
    from ..filtration import alpha_filtration

    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be a shapelab.Balls, got {type(balls).__name__}")
    if balls.dim != 2:
        raise ValueError(f"alpha_explorer draws disks: balls must be 2D, got {balls.dim}D (see plot.complex3d for 3D)")
    if len(balls) == 0:
        raise ValueError("balls must hold at least one disk")
    tau = as_finite_scalar(tau, "tau")
    steps = as_positive_int(steps, "steps", minimum=2)
    F = alpha_filtration(balls) if filtration is None else filtration
    if tau_range is None:
        lo, hi = _default_range(F)
    else:
        try:
            lo, hi = (as_finite_scalar(v, "tau_range") for v in tau_range)
        except (TypeError, ValueError):
            raise TypeError("tau_range must be a pair (low, high) of finite numbers") from None
        if not lo < hi:
            raise ValueError(f"tau_range must have low < high, got {tuple(tau_range)!r}")
    tau = min(max(tau, lo), hi)
    return AlphaExplorer(balls, F, tau, lo, hi, (hi - lo) / steps, bool(show_cells), bool(show_measure), bbox)


class AlphaExplorer(W.VBox):
    """Slider + status + figure; see :func:`alpha_explorer`.

    Attributes
    ----------
    slider : ipywidgets.FloatSlider
    status : ipywidgets.HTML
    image : ipywidgets.Image
        The current frame (PNG), redrawn by blitting (``view.png()``).
    view : shapelab.plot.balls.DualComplexView
        The figure's artists; ``view.complex`` is the complex drawn.
    """

    def __init__(self, balls, F, tau, lo, hi, step, show_cells, show_measure, bbox):
        from ..plot.balls import DualComplexView

        self._balls = balls
        self._F = F
        self._show_measure = show_measure
        self.view = DualComplexView(balls, tau, filtration=F, show_cells=show_cells, bbox=bbox, view_tau=hi,
                                    title="The disks grown to time τ and their dual complex $K_\\tau$")
        self.slider = W.FloatSlider(value=tau, min=lo, max=hi, step=step, description="τ",
                                    continuous_update=False, readout_format=".3f",
                                    layout=W.Layout(width="70%"))
        self.status = W.HTML()
        width, height = self.view.figure.get_size_inches() * self.view.figure.dpi
        self.image = W.Image(format="png", layout=W.Layout(width=f"{int(width)}px", height=f"{int(height)}px"))
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
        parts = [f"τ = {t:.3f}", alpha, f"K: {n[0]} vertices, {n[1]} edges, {n[2]} triangles"]
        try:
            b = self._F.betti(t)
            parts.append("Betti (β₀, β₁) = " + f"({b[0]}, {b[1]})")
        except (ImportError, NotImplementedError, AttributeError):  # topology not available
            pass
        if self._show_measure:
            from ..measure import union_measure

            m = union_measure(self._balls, tau=t, filtration=self._F)
            parts.append(f"area {m.area:.4g}, perimeter {m.perimeter:.4g}")
        return " · ".join(parts)

    def update(self, tau=None):
        """Recompute at ``tau`` (default: the slider's value) and move the artists
        (the image is refreshed by the slider's callback, or by ``view.png()``)."""
        t = float(self.slider.value) if tau is None else as_finite_scalar(tau, "tau")
        self.view.update(t)
        self.status.value = self.status_text()
        return self

    def _on_change(self, change=None):
        self.update()
        self.image.value = self.view.png()

    def __repr__(self):
        return (f"AlphaExplorer(n_balls={len(self._balls)}, tau={self.slider.value:.3f}, "
                f"range=({self.slider.min:.3f}, {self.slider.max:.3f}))")
