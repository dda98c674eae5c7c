"""Figures of shape classification (Notes §23.2, lesson 19): a family of point sets, the
matrix of distances between their diagrams, its planar embedding, and the stability
of the distances under perturbation.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax=``
and returns its figure) and computes no geometry beyond calling the library.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ._common import axes
from ._describe import describe
from ._style import PAGE, PALETTE, SLIDE, new_figure, style

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["point_clouds", "distance_matrix", "embedding", "stability"]


def _class_colors(labels):
    names = list(dict.fromkeys(labels))
    return names, {c: PALETTE[k % len(PALETTE)] for k, c in enumerate(names)}


def point_clouds(
    clouds: Mapping[str, ArrayLike], *, size: tuple[float, float] = SLIDE, elev: float = 20.0, azim: float = 35.0
) -> Figure:
    """Small multiples of 3D point sets, one panel each (a family of shapes).

    Parameters
    ----------
    clouds : dict of str → array_like, shape (n, 3)
        Panel title → points.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.datasets.shape_family
        A family of shapes to draw.

    Examples
    --------
    >>> from shapelab.datasets import sample_shape
    >>> from shapelab.plot import alt_text
    >>> fig = point_clouds({"sphere": sample_shape("sphere", 100), "torus": sample_shape("torus", 100)})
    >>> alt_text(fig)
    '2 panels. Left: 3D view of sphere, 100 points. Right: 3D view of torus, 100 points.'
    """
    from .._toolkit.validate import as_points

    if not isinstance(clouds, dict) or not clouds:
        raise TypeError("clouds must be a non-empty dict of title -> (n, 3) points")
    pts = {str(k): as_points(v, f"clouds[{k!r}]", dim=3) for k, v in clouds.items()}
    fig, axes = new_figure(1, len(pts), size=size, projection="3d")
    with style():
        for k, (ax, (title, X)) in enumerate(zip(np.atleast_1d(axes), pts.items(), strict=True)):
            ax.scatter(*X.T, s=6, color=PALETTE[k % len(PALETTE)], depthshade=True, linewidths=0)
            h = np.abs(X - X.mean(axis=0)).max()
            c = X.mean(axis=0)
            ax.set_xlim(c[0] - h, c[0] + h)
            ax.set_ylim(c[1] - h, c[1] + h)
            ax.set_zlim(c[2] - h, c[2] + h)
            ax.set_box_aspect((1, 1, 1))
            ax.view_init(elev=elev, azim=azim)
            ax.set_title(title)
            ax.set_xticklabels([])
            ax.set_yticklabels([])
            ax.set_zticklabels([])
            describe(ax, f"3D view of {title}, {len(X)} points")
    return fig


def distance_matrix(
    D: ArrayLike,
    labels: Sequence[str],
    *,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    title: str | None = None,
    unit: str = "",
) -> Figure:
    """A distance matrix between the shapes of a family, as a heat map grouped by class.

    Parameters
    ----------
    D : array_like, shape (k, k)
    labels : sequence of str, length k
        The class of each shape; rows of one class should be contiguous.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.diagrams.distance_matrix
        The distances drawn.
    embedding
        The same distances in the plane.

    Examples
    --------
    >>> import numpy as np
    >>> from shapelab.plot import alt_text
    >>> D = np.array([[0.0, 1.0, 4.0], [1.0, 0.0, 4.0], [4.0, 4.0, 0.0]])
    >>> alt_text(distance_matrix(D, ["a", "a", "b"]))[:30]
    'Distances between the shapes: '
    """
    D = np.asarray(D, float)
    labels = [str(s) for s in labels]
    if D.ndim != 2 or D.shape != (len(labels), len(labels)):
        raise ValueError(f"D must be a square matrix with one row per label, got {D.shape} and {len(labels)} labels")
    fig, ax = axes(ax, size=size)
    names, _ = _class_colors(labels)
    with style():
        im = ax.imshow(D, cmap="magma_r", interpolation="nearest")
        fig.colorbar(im, ax=ax, label=f"distance{f' ({unit})' if unit else ''}")
        starts = [labels.index(c) for c in names]
        ends = [len(labels) - labels[::-1].index(c) for c in names]
        mids = [(a + b - 1) / 2 for a, b in zip(starts, ends, strict=True)]
        for b in ends[:-1]:
            ax.axhline(b - 0.5, color="white", lw=1.5)
            ax.axvline(b - 0.5, color="white", lw=1.5)
        ax.set_xticks(mids, names, rotation=30, ha="right")
        ax.set_yticks(mids, names)
        ax.set_title(title or "Distances between the shapes")
        within = [D[a:b, a:b][~np.eye(b - a, dtype=bool)] for a, b in zip(starts, ends, strict=True)]
        inner = np.concatenate([w for w in within if w.size]) if any(w.size for w in within) else np.zeros(0)
        mask = np.zeros(D.shape, bool)
        for a, b in zip(starts, ends, strict=True):
            mask[a:b, a:b] = True
        outer = D[~mask]
        u = f" {unit}" if unit else ""
        describe(
            ax,
            f"{title or 'Distances between the shapes'}: a heat map of the {len(labels)} × {len(labels)} distances "
            f"between the shapes, grouped into {len(names)} classes ({', '.join(names)})"
            + (f"; within a class at most {inner.max():.3g}{u}" if inner.size else "")
            + (f", between classes at least {outer.min():.3g}{u}" if outer.size else ""),
        )
    return fig


def embedding(
    points: ArrayLike,
    labels: Sequence[str],
    *,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    title: str | None = None,
) -> Figure:
    """Shapes as points in the plane (:func:`shapelab.classical_mds`), coloured by class.

    Parameters
    ----------
    points : array_like, shape (k, 2)
    labels : sequence of str, length k

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.classical_mds
        The embedding drawn.
    distance_matrix
        The distances embedded.

    Examples
    --------
    >>> import numpy as np
    >>> from shapelab.plot import alt_text
    >>> fig = embedding(np.array([[0.0, 0.0], [0.1, 0.0], [2.0, 1.0]]), ["a", "a", "b"])
    >>> alt_text(fig)[:40]
    'The family in the plane (classical MDS):'
    """
    from .._toolkit.validate import as_points

    X = as_points(points, "points", dim=2)
    labels = [str(s) for s in labels]
    if len(labels) != len(X):
        raise ValueError(f"labels must have one entry per point, got {len(labels)} for {len(X)} points")
    fig, ax = axes(ax, size=size)
    names, colors = _class_colors(labels)
    markers = "osD^vP*X"
    with style():
        for k, c in enumerate(names):
            P = X[[i for i, s in enumerate(labels) if s == c]]
            ax.scatter(*P.T, s=70, color=colors[c], marker=markers[k % len(markers)], label=c, edgecolors="white")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False)
        ax.set_xlabel("first coordinate")
        ax.set_ylabel("second coordinate")
        ax.set_title(title or "The family in the plane (classical MDS)")
        describe(
            ax,
            f"{title or 'The family in the plane (classical MDS)'}: {len(X)} shapes as points in the plane, one "
            f"marker shape per class: " + ", ".join(f"{c} ({labels.count(c)})" for c in names),
        )
    return fig


def stability(
    perturbation: ArrayLike,
    distances: Mapping[str, ArrayLike],
    *,
    ax: Axes | None = None,
    size: tuple[float, float] = PAGE,
    title: str | None = None,
    unit: str = "",
) -> Figure:
    """The stability theorem at work: diagram distance against the perturbation's size.

    Parameters
    ----------
    perturbation : array_like, shape (k,)
        Sizes δ > 0 of the perturbations (drawn on log axes).
    distances : dict of str → array_like, shape (k,)
        Label → the bottleneck distance measured at each δ.  Zero distances are drawn
        at the bottom of the axes.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.bottleneck_distance
        The distances drawn.

    References
    ----------
    .. [1] D. Cohen-Steiner, H. Edelsbrunner and J. Harer, "Stability of persistence
           diagrams", *Discrete Comput. Geom.* 37:103-120, 2007.
           doi:10.1007/s00454-006-1276-5

    Examples
    --------
    >>> from shapelab.plot import alt_text
    >>> fig = stability([0.01, 0.1], {"H0": [0.005, 0.05], "H1": [0.002, 0.03]})
    >>> alt_text(fig)[:50]
    'Stability: the diagrams move no more than the poin'
    """
    x = np.asarray(perturbation, float).ravel()
    if x.size == 0 or not np.all(np.isfinite(x)) or np.any(x <= 0):
        raise ValueError("perturbation must hold positive finite sizes")
    if not isinstance(distances, dict) or not distances:
        raise TypeError("distances must be a non-empty dict of label -> distances")
    fig, ax = axes(ax, size=size)
    with style():
        ax.plot(x, x, color="black", lw=1.5, ls="--", label="bound: distance = δ")
        floor = x.min() / 30
        for k, (label, y) in enumerate(distances.items()):
            y = np.asarray(y, float).ravel()
            if y.shape != x.shape:
                raise ValueError(f"distances[{label!r}] must have one value per perturbation")
            ax.plot(x, np.maximum(y, floor), marker="os^D"[k % 4], color=PALETTE[k % len(PALETTE)], label=label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        u = f" ({unit})" if unit else ""
        ax.set_xlabel(f"perturbation δ{u}")
        ax.set_ylabel(f"bottleneck distance{u}")
        ax.legend(loc="upper left", frameon=False)
        ax.set_title(title or "Stability: the diagrams move no more than the points")
        below = all(np.all(np.asarray(y, float).ravel() <= x * (1 + 1e-9)) for y in distances.values())
        describe(
            ax,
            f"{title or 'Stability: the diagrams move no more than the points'}: on log axes, the bottleneck distance "
            f"against the perturbation δ from {x.min():.3g} to {x.max():.3g}, one line and marker shape for each of "
            f"{', '.join(map(str, distances))}, under the dashed bound distance = δ; "
            + ("every distance is at most δ" if below else "some distance exceeds δ"),
        )
    return fig
