"""Plumbing shared by the figure modules of :mod:`shapelab.plot`: the axes a figure
draws into, grown radii, 3D views.  Private (as the figure modules' own helpers are);
its names are public so that the modules can share them."""

from __future__ import annotations

import numpy as np

from ._style import PAGE, new_figure

__all__ = ["axes", "grown_radii", "set_3d_view"]


def axes(ax, *, size=PAGE, projection=None, planar: bool = False):
    """``(figure, ax)``: a new figure of ``size`` when ``ax`` is None, else ``ax`` and its
    figure.  A given ``ax`` must be 3D when ``projection="3d"``, and 2D when
    ``planar`` (a figure of planar points)."""
    if ax is None:
        return new_figure(size=size, projection=projection)
    is_3d = getattr(ax, "name", "") == "3d"
    if projection == "3d" and not is_3d:
        raise ValueError("ax must be a 3D axes (projection='3d') for this figure")
    if planar and projection is None and is_3d:
        raise ValueError("ax must be a 2D axes for planar points")
    return ax.get_figure(), ax


def grown_radii(balls, tau: float) -> np.ndarray:
    """Radii :math:`\\sqrt{r_i^2 + \\tau}` at time τ (:meth:`shapelab.Balls.grow`); a ball
    whose radius would be imaginary (not yet born) gets 0."""
    return np.sqrt(np.clip(balls.weights + tau, 0.0, None))


def set_3d_view(ax, lo, hi, elev: float, azim: float, *, cube: bool = False) -> None:
    """Limits ``[lo, hi]`` on the three axes, the view angles and axis labels; with
    ``cube`` the box is a cube (equal aspect), else its aspect follows ``hi - lo``."""
    lo, hi = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect((1, 1, 1) if cube else tuple(np.maximum(hi - lo, 1e-12)))
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
