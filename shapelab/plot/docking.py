"""Figures of docking (Notes §23.2, lesson 18): the score over a grid of poses, and one
pose with its contacts and clashes.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax=``
and returns its figure) and computes no geometry beyond calling the library.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ._common import axes
from ._describe import describe
from ._style import COLORS, PAGE, style

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["docking_landscape", "docking_pose"]


def docking_landscape(
    angles: ArrayLike,
    shifts: ArrayLike,
    scores: ArrayLike,
    *,
    marks: Mapping[str, tuple[float, float]] | None = None,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    title: str | None = None,
) -> Figure:
    """The docking score on a grid of poses (:meth:`shapelab.Docking.landscape`), as a heat map.

    Parameters
    ----------
    angles : array_like, shape (a,)
        Turns in radians (drawn in degrees, horizontally).
    shifts : array_like, shape (s,)
        Shifts in Å (vertically).
    scores : array_like, shape (a, s)
        ``scores[i, j]`` at ``angles[i]``, ``shifts[j]``.
    marks : dict of str → (angle, shift), optional
        Poses to mark (angle in radians), e.g. the crystal pose and the one found.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.Docking
        The scores.

    Examples
    --------
    >>> import numpy as np
    >>> from shapelab.plot import alt_text
    >>> angles, shifts = np.radians(np.arange(-180, 180, 45)), np.arange(-2.0, 2.1, 1.0)
    >>> scores = np.cos(angles)[:, None] - 0.1 * shifts[None, :] ** 2
    >>> fig = docking_landscape(angles, shifts, scores, marks={"crystal": (0.0, 0.0)})
    >>> alt_text(fig)[:30]
    'Docking score landscape: a hea'
    """
    A = np.degrees(np.asarray(angles, float).ravel())
    S = np.asarray(shifts, float).ravel()
    Z = np.asarray(scores, float)
    if Z.shape != (len(A), len(S)):
        raise ValueError(f"scores must have shape (len(angles), len(shifts)) = {(len(A), len(S))}, got {Z.shape}")
    if not (np.all(np.isfinite(Z)) and np.all(np.isfinite(A)) and np.all(np.isfinite(S))):
        raise ValueError("angles, shifts and scores must be finite")
    fig, ax = axes(ax, size=size)
    with style():
        lo = np.percentile(Z, 5)  # clashes make some scores hugely negative: clip the colour scale
        mesh = ax.pcolormesh(A, S, Z.T, shading="nearest", cmap="viridis", vmin=lo, vmax=Z.max())
        fig.colorbar(mesh, ax=ax, label="score: buried area − penalty × clash (Å²)")
        styles = iter([("*", "white", 18), ("o", COLORS["red"], 10), ("s", COLORS["green"], 9), ("D", "black", 8)])
        for label, (a, s) in (marks or {}).items():
            m, c, z = next(styles, ("x", "black", 9))
            ax.plot(np.degrees(a), s, marker=m, color=c, markersize=z, markeredgecolor="black", ls="", label=label)
        if marks:
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncols=len(marks), frameon=False)
        ax.set_xlabel("turn about the ligand's axis (°)")
        ax.set_ylabel("shift (Å)")
        ax.set_title(title or "Docking score landscape")
        i, j = np.unravel_index(int(np.argmax(Z)), Z.shape)
        describe(
            ax,
            f"{title or 'Docking score landscape'}: a heat map of the docking score over turns from {A.min():.0f}° "
            f"to {A.max():.0f}° and shifts from {S.min():.3g} to {S.max():.3g} Å; the best score, {Z.max():.3g} Å², "
            f"at a turn of {A[i]:.0f}° and a shift of {S[j]:.3g} Å"
            + (f"; marked: {', '.join(marks)}" if marks else ""),
        )
    return fig


def docking_pose(
    receptor: ArrayLike,
    crystal: ArrayLike,
    docked: ArrayLike,
    *,
    radius: float = 8.0,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    title: str | None = None,
    elev: float = 20.0,
    azim: float = 35.0,
) -> Figure:
    """A docked ligand against the crystal pose, among the receptor atoms near it.

    Parameters
    ----------
    receptor : array_like, shape (n, 3)
        Receptor atom centres; those within ``radius`` of a crystal ligand atom are drawn.
    crystal, docked : array_like, shape (m, 3)
        The ligand's atom centres in the crystal and as docked.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.Docking
        The poses.

    Examples
    --------
    >>> import numpy as np
    >>> from shapelab.plot import alt_text
    >>> rng = np.random.default_rng(0)
    >>> receptor, ligand = rng.normal(size=(50, 3)) * 5, rng.normal(size=(8, 3))
    >>> alt_text(docking_pose(receptor, ligand, ligand + 0.5))[:38]
    '3D view of a docked ligand (8 atoms, s'
    """
    from scipy.spatial import cKDTree

    from .._toolkit.validate import as_points

    receptor = as_points(receptor, "receptor", dim=3)
    crystal = as_points(crystal, "crystal", dim=3)
    docked = as_points(docked, "docked", dim=3)
    near = cKDTree(crystal).query(receptor, distance_upper_bound=radius)[0] < np.inf
    fig, ax = axes(ax, size=size, projection="3d")
    with style():
        R = receptor[near]
        ax.scatter(*R.T, s=14, color=COLORS["muted"], alpha=0.25, linewidths=0, depthshade=False, label="receptor")
        ax.scatter(*crystal.T, s=70, color=COLORS["green"], alpha=0.9, linewidths=0, label="crystal pose")
        ax.scatter(*docked.T, s=30, color=COLORS["red"], alpha=0.95, marker="D", linewidths=0, label="docked")
        c = crystal.mean(axis=0)
        h = radius * 0.9
        ax.set_xlim(c[0] - h, c[0] + h)
        ax.set_ylim(c[1] - h, c[1] + h)
        ax.set_zlim(c[2] - h, c[2] + h)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False, markerscale=1.2)
        if title:
            ax.set_title(title)
        rmsd = float(np.sqrt(((docked - crystal) ** 2).sum(axis=1).mean())) if docked.shape == crystal.shape else None
        describe(
            ax,
            (f"{title}: " if title else "")
            + f"3D view of a docked ligand ({len(docked)} atoms, small diamonds) over its crystal pose (large dots), "
            f"among the {int(near.sum())} receptor atoms within {radius:g} Å"
            + (f"; RMSD {rmsd:.2f} Å" if rmsd is not None else ""),
        )
    return fig
