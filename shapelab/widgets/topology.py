"""The pocket explorer: voids and pockets as the disks grow (Notes §23.1, Figure 23.2)."""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

import ipywidgets as W
import numpy as np

from .._toolkit.validate import as_finite_scalar, as_tau
from ..plot import alt_text
from . import _frame
from .static import StaticFallback

if TYPE_CHECKING:
    from collections.abc import Sequence

    from ..balls import Balls
    from ..filtration import Filtration

__all__ = ["pocket_explorer", "PocketExplorer", "persistence_explorer", "PersistenceExplorer"]

_DPI = 90
_SIZE = (6.8, 5.0)


def _default_range(balls, F):
    """From the moment the smallest ball appears to just after the last feature dies."""
    lo = -float(balls.weights.min())
    P = F.persistence()
    deaths = np.concatenate([np.asarray(a)[:, 1] for a in P.values() if len(a)] or [np.zeros(0)])
    deaths = deaths[np.isfinite(deaths)]
    hi = float(deaths.max()) if len(deaths) else lo + 1.0
    hi = max(hi, lo + 1e-6)
    return lo, hi + 0.1 * (hi - lo)


def pocket_explorer(
    F: Filtration | Balls,
    *,
    tau: float = 0.0,
    tau_range: tuple[float, float] | None = None,
    steps: int = 100,
    min_persistence: float = 1e-9,
    show_complex: bool = False,
) -> PocketExplorer:
    """A slider in τ over the disks grown to :math:`\\sqrt{r^2+\\tau}`, with the holes
    (voids) and the pockets with their mouths at that τ (Notes §23.1, Figure 23.2).

    Drag τ up and watch a pocket's mouth close: the pocket turns into a hole, which
    then fills.  A dent that fills before its mouth closes is never coloured as a
    pocket — the right-hand shape of Figure 23.2.

    Parameters
    ----------
    F : Filtration or Balls
        ``alpha_filtration(balls)`` of 2D disks (3D works too but redraws slowly), or
        the disks (their filtration is then built here, once).
    tau : float
        Initial growth time.
    tau_range : (float, float), optional
        Slider bounds; default from the smallest ball's appearance
        :math:`-\\min r_i^2` to a little after the last finite death.
    steps : int
        Slider resolution.
    min_persistence : float, default 1e-9
        Passed to :func:`shapelab.pockets`; the default hides pockets that close and
        fill at the same τ up to round-off (degenerate, e.g. co-circular, centres).
    show_complex : bool
        Also draw the dual complex :math:`K_\\tau`.

    Returns
    -------
    PocketExplorer
        An ``ipywidgets.VBox`` holding the slider and the figure.

    See Also
    --------
    shapelab.pockets
        The pockets.
    shapelab.plot.pockets
        One frame.

    Examples
    --------
    >>> import shapelab as sl
    >>> w = pocket_explorer(sl.alpha_filtration(sl.datasets.figure_23_2()[0]), steps=10)
    >>> type(w).__name__
    'PocketExplorer'
    >>> print(w.status.value)
    &nbsp;1 pocket, 0 holes
    """
    from ..filtration import as_filtration
    from ._frame import check_balls, value_range

    if hasattr(F, "centers"):  # the balls: checked before their filtration is built
        check_balls(F, dim=None, who="pocket_explorer")
    F = as_filtration(F, "pocket_explorer")
    balls = F.balls
    check_balls(balls, dim=None, who="pocket_explorer")

    tau = as_tau(tau, finite=True)
    lo, hi = _default_range(balls, F) if tau_range is None else value_range(tau_range, "tau_range")
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 2:
        raise ValueError(f"steps must be an integer >= 2, got {steps!r}")
    lo = max(lo, -float(balls.weights.min()))
    tau = min(max(tau, lo), hi)
    min_persistence = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    return PocketExplorer(balls, F, tau, lo, hi, (hi - lo) / steps, min_persistence, bool(show_complex))


class PocketExplorer(StaticFallback, W.VBox):
    """Slider + figure; see :func:`pocket_explorer`.

    See Also
    --------
    pocket_explorer
        Produces it.
    """

    def __init__(self, balls, F, tau, lo, hi, step, min_persistence, show_complex):
        self._balls = balls
        self._F = F
        self._minp = min_persistence
        self._show_complex = show_complex
        self.slider = W.FloatSlider(
            value=tau,
            min=lo,
            max=hi,
            step=step,
            description="τ",
            continuous_update=False,
            readout_format=".2f",
            layout=W.Layout(width="60%"),
        )
        self.status = W.HTML()
        # a PNG image, not an Output widget: it renders the same in a live kernel, in
        # nbclient/nbval runs and from the stored widget state on the static site
        self.image = _frame.image(_SIZE, dpi=_DPI)
        super().__init__([W.HBox([self.slider, self.status]), self.image])
        self.slider.observe(self._redraw, names="value")
        self._redraw()

    @property
    def tau(self) -> float:
        return float(self.slider.value)

    def features(self):
        """``(pockets, voids)`` at the slider's τ."""
        import shapelab

        t = self.tau
        return (shapelab.pockets(self._F, t, min_persistence=self._minp), shapelab.voids(self._F, t))

    def figure(self):
        """The current figure (:func:`shapelab.plot.pockets` at the slider's τ)."""
        from ..plot.topology import pockets as plot_pockets

        P, V = self.features()
        return plot_pockets(self._F, self.tau, pockets=P, voids=V, show_complex=self._show_complex)

    def _redraw(self, change=None):
        P, V = self.features()
        word = "hole" if self._balls.dim == 2 else "void"
        self.status.value = (
            f"&nbsp;{len(P)} pocket{'' if len(P) == 1 else 's'}, {len(V)} {word}{'' if len(V) == 1 else 's'}"
        )
        buf = io.BytesIO()
        fig = self.figure()
        fig.savefig(buf, format="png", dpi=_DPI)
        self.alt = alt_text(fig)  # what the frame shows (the static player's alt)
        self.image.value = buf.getvalue()

    def __repr__(self):
        return (
            f"PocketExplorer(n_balls={len(self._balls)}, tau={self.slider.value:.2f}, "
            f"range=({self.slider.min:.2f}, {self.slider.max:.2f}))"
        )


# --------------------------------------------------------------------------- persistence
def persistence_explorer(
    F: Filtration | Balls,
    *,
    threshold: float = 0.0,
    threshold_range: tuple[float, float] | None = None,
    steps: int = 100,
    dims: int | Sequence[int] | None = None,
) -> PersistenceExplorer:
    """Topological simplification with a slider (Notes §23.1, "big voids against small ones").

    Features whose persistence (death − birth) is below the threshold are what
    simplification removes: they are greyed out in the persistence diagram (left) and
    left out of the barcode (right); the status line counts what is kept in each
    dimension.

    Parameters
    ----------
    F : Filtration or Balls
        An α-filtration (:func:`shapelab.alpha_filtration`), or the balls (their
        filtration is built once and kept with them, as for :func:`shapelab.voids`);
        its pairs over :math:`\\mathbb{Z}/2` (:meth:`~shapelab.Filtration.persistence`).
    threshold : float
        Initial persistence threshold, >= 0.
    threshold_range : (float, float), optional
        Slider bounds; default from 0 to the largest finite persistence.
    steps : int
        Slider resolution.
    dims : int or sequence of int, optional
        Homology dimensions to show (default: those with at least one feature).

    Returns
    -------
    PersistenceExplorer
        An ``ipywidgets.VBox``: the slider, a status line and the figure.

    See Also
    --------
    shapelab.persistence.persistence
        The pairs.
    shapelab.plot.persistence_diagram
        One frame.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher and A. Zomorodian, "Topological persistence and
           simplification", *Discrete Comput. Geom.* 28:511-533, 2002.
           doi:10.1007/s00454-002-2885-2

    Examples
    --------
    >>> import shapelab as sl
    >>> w = persistence_explorer(sl.alpha_filtration(sl.datasets.figure_23_1()), steps=10)
    >>> type(w).__name__
    'PersistenceExplorer'
    >>> print(w.status.value)
    persistence ≥ 0.000 keeps 13 of 13 in H0, 8 of 8 in H1
    """
    from ..balls import Balls
    from ..filtration import Filtration, as_filtration

    if isinstance(F, Balls):
        F = as_filtration(F, "persistence_explorer")
    if not isinstance(F, Filtration):
        raise TypeError(
            f"persistence_explorer: F must be a Filtration (shapelab.alpha_filtration(balls)) or a shapelab.Balls, "
            f"got {type(F).__name__}"
        )
    threshold = as_finite_scalar(threshold, "threshold", nonnegative=True)
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 2:
        raise ValueError(f"steps must be an integer >= 2, got {steps!r}")
    P = F.persistence()
    if dims is None:  # the dimensions that have features (a 2D input has no H2)
        dims = tuple(k for k in sorted(P) if len(P[k])) or tuple(sorted(P))
    else:
        dims = (dims,) if isinstance(dims, (int, np.integer)) and not isinstance(dims, bool) else tuple(dims)
        bad = [k for k in dims if k not in P]
        if bad:
            raise ValueError(f"dims must be among {sorted(P)}, got {list(dims)!r}")
    if threshold_range is None:
        pers = np.concatenate([np.diff(np.asarray(P[k]).reshape(-1, 2), axis=1).ravel() for k in dims] or [np.zeros(0)])
        pers = pers[np.isfinite(pers)]
        lo, hi = 0.0, (float(pers.max()) * 1.05 if pers.size else 1.0)
    else:
        from ._frame import value_range

        lo, hi = value_range(threshold_range, "threshold_range", nonnegative=True)
    return PersistenceExplorer(P, dims, min(max(threshold, lo), hi), lo, hi, (hi - lo) / steps)


class PersistenceExplorer(StaticFallback, W.VBox):
    """Threshold slider + status + diagram and barcode; see :func:`persistence_explorer`.

    See Also
    --------
    persistence_explorer
        Produces it.
    """

    SIZE = (10.0, 4.6)

    def __init__(self, pairs, dims, threshold, lo, hi, step):

        self._P = pairs
        self._dims = dims
        self.slider = W.FloatSlider(
            value=threshold,
            min=lo,
            max=hi,
            step=step,
            description="threshold",
            continuous_update=False,
            readout_format=".3f",
            layout=W.Layout(width="60%"),
        )
        self.status = W.HTML()
        self.image = _frame.image(self.SIZE)
        super().__init__([self.slider, self.status, self.image])
        self.slider.observe(self._redraw, names="value")
        self._redraw()

    @property
    def threshold(self) -> float:
        return float(self.slider.value)

    def kept(self) -> dict:
        """``{k: number of features with persistence >= threshold}`` (essential ones always stay)."""
        out = {}
        for k in self._dims:
            a = np.asarray(self._P[k]).reshape(-1, 2)
            out[k] = int(np.count_nonzero(a[:, 1] - a[:, 0] >= self.threshold))
        return out

    def status_text(self) -> str:
        kept = self.kept()
        total = {k: len(np.asarray(self._P[k]).reshape(-1, 2)) for k in self._dims}
        return f"persistence ≥ {self.threshold:.3f} keeps " + ", ".join(
            f"{kept[k]} of {total[k]} in H{k}" for k in self._dims
        )

    def figure(self):
        from ..plot import new_figure
        from ..plot.topology import barcode, persistence_diagram

        fig, (a, b) = new_figure(1, 2, size=self.SIZE)
        t = self.threshold
        persistence_diagram(
            self._P,
            dims=self._dims,
            min_persistence=t if t > 0 else None,
            ax=a,
            title="Diagram: greyed points are removed",
        )
        barcode(self._P, dims=self._dims, min_persistence=t, ax=b, title="Barcode")
        return fig

    def _redraw(self, change=None):

        self.status.value = self.status_text()
        fig = self.figure()
        self.image.value = _frame.png(fig)
        self.alt = alt_text(fig)  # what the frame shows (the static player's alt)

    def __repr__(self):
        return f"PersistenceExplorer(dims={self._dims}, threshold={self.threshold:.3f})"
