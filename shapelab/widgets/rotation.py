"""The ICP explorer: step through the iterations of ICP with a slider (Notes §23.2).

All iterations are computed once, by :func:`shapelab.icp` with ``keep_history=True``;
moving the slider only redraws (:func:`shapelab.plot.icp_step` and
:func:`shapelab.plot.icp_convergence`).
"""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

import ipywidgets as W
import numpy as np

from .._toolkit.validate import as_points, as_positive_int
from ..plot import alt_text
from . import _frame
from .static import StaticFallback

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..registration import RigidMotion

__all__ = ["icp_explorer", "ICPExplorer"]

_SIZE = (11.0, 4.6)  # inches
_DPI = 90


def icp_explorer(
    source: ArrayLike,
    target: ArrayLike,
    *,
    max_iter: int = 30,
    tol: float = 0.0,
    accelerate: bool = False,
    init: RigidMotion | None = None,
    max_distance: float | None = None,
    truth: RigidMotion | None = None,
    max_lines: int = 200,
) -> ICPExplorer:
    """A slider over the iterations of ICP, with the step and the convergence plot.

    Parameters
    ----------
    source, target : array_like, shape (n, 3), (m, 3)
        As for :func:`shapelab.icp` (keep them small, a few hundred points).
    max_iter, tol, accelerate, init, max_distance
        Passed to :func:`shapelab.icp`.  ``accelerate`` defaults to False here, so
        each slider position is one plain step of the notes' algorithm.
    truth : RigidMotion, optional
        The true motion, to show the rotation error too.
    max_lines : int
        Correspondence segments drawn at most.

    Returns
    -------
    ICPExplorer
        An ``ipywidgets.VBox``: the slider, a status line and the two figures.

    See Also
    --------
    shapelab.icp
        The iterations.
    shapelab.plot.icp_step
        One frame.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> rng = np.random.default_rng(0)
    >>> target = rng.normal(size=(30, 3))
    >>> source = sl.Quaternion.from_axis_angle([0, 0, 1], 0.3).rotate(target) + rng.normal(0, 0.05, (30, 3))
    >>> w = icp_explorer(source, target, max_iter=5)
    >>> type(w).__name__
    'ICPExplorer'
    >>> print(w.status.value)
    iteration 0 of 4: MSE 0.1651
    """
    from ..registration import RigidMotion, icp

    src = as_points(source, "source", dim=3, min_points=3)
    tgt = as_points(target, "target", dim=3, min_points=3)
    max_lines = as_positive_int(max_lines, "max_lines")
    if truth is not None and not isinstance(truth, RigidMotion):
        raise TypeError(f"truth must be a RigidMotion, got {type(truth).__name__}")
    result = icp(
        src,
        tgt,
        tol=tol,
        max_iter=max_iter,
        init=init,
        max_distance=max_distance,
        accelerate=accelerate,
        keep_history=True,
    )
    return ICPExplorer(src, tgt, result, truth, max_lines)


class ICPExplorer(StaticFallback, W.VBox):
    """Slider + figures; see :func:`icp_explorer`.  ``.result`` is the ICPResult.

    See Also
    --------
    icp_explorer
        Produces it.
    """

    def __init__(self, source, target, result, truth, max_lines):
        self.source, self.target, self.result = source, target, result
        self._truth, self._max_lines = truth, max_lines
        self.slider = W.IntSlider(
            value=0,
            min=0,
            max=result.n_iter,
            step=1,
            description="iteration",
            continuous_update=False,
            layout=W.Layout(width="60%"),
        )
        self.status = W.HTML()
        # a PNG image, not an Output widget: it renders the same in a live kernel, in
        # nbclient/nbval runs and from the stored widget state on the static site
        self.image = _frame.image(_SIZE, dpi=_DPI)
        super().__init__([self.slider, self.status, self.image])
        self.slider.observe(self._redraw, names="value")
        self._redraw()

    @property
    def iteration(self) -> int:
        return int(self.slider.value)

    def _status_text(self) -> str:
        k, r = self.iteration, self.result
        text = f"iteration {k} of {r.n_iter}: MSE {r.mse[k]:.4g}"
        if self._truth is not None:
            err = np.degrees(r.motions[k].rotation.angle_to(self._truth.rotation))
            text += f", rotation error {err:.3f}°"
        if k == r.n_iter:
            text += " (converged)" if r.converged else " (stopped at max_iter)"
        return text

    def figure(self):
        """The current figure: the ICP step (3D) and the convergence plot."""
        from ..plot import new_figure
        from ..plot.rotation import icp_convergence, icp_step

        k = self.iteration
        fig, axes = new_figure(1, 2, size=_SIZE)
        # the left panel must be 3D: replace it
        axes[0].remove()
        ax3 = fig.add_subplot(1, 2, 1, projection="3d")
        icp_step(self.source, self.target, self.result, k, ax=ax3, max_lines=self._max_lines)
        icp_convergence(self.result, truth=self._truth, ax=axes[1], mark=k)
        return fig

    def _redraw(self, change=None):
        self.status.value = self._status_text()
        buf = io.BytesIO()
        fig = self.figure()
        fig.savefig(buf, format="png", dpi=_DPI)
        self.alt = alt_text(fig)  # what the frame shows (the static player's alt)
        self.image.value = buf.getvalue()

    def __repr__(self) -> str:
        return f"ICPExplorer({self._status_text()})"
