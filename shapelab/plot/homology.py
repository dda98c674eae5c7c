"""Small simplicial complexes drawn in the plane, chains on them, boundary matrices (lesson 02)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection

from ._describe import describe
from ._style import COLORS, PAGE, new_figure, style

if TYPE_CHECKING:
    from collections.abc import Iterable, Mapping, Sequence

    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike

__all__ = ["simplicial_complex", "boundary_matrix"]


def _n(k: int, word: str) -> str:
    return f"{k} {word}" + ("" if k == 1 else "s")


def simplicial_complex(
    simplices: Iterable[Sequence[int]],
    positions: Mapping[int, ArrayLike] | ArrayLike,
    *,
    chain: Iterable[Sequence[int]] | None = None,
    ax: Axes | None = None,
    title: str | None = None,
    labels: bool = True,
) -> Figure:
    """Draw an abstract simplicial complex at given vertex positions in the plane.

    Triangles are filled (translucent, so overlapping ones, as in a drawing of a
    tetrahedron's boundary, show through), edges are black lines and vertices dots
    with their labels. A ``chain`` (edges, or triangles) is drawn on top in vermillion.

    Parameters
    ----------
    simplices : iterable of tuple of int
        The complex (a vertex is ``(i,)``, an edge ``(i, j)``, a triangle ``(i, j, k)``;
        tetrahedra are not drawn).
    positions : dict or array_like
        ``positions[i]`` is the (x, y) of vertex ``i``.
    chain : iterable of tuple of int, optional
        A chain to highlight.
    ax : matplotlib Axes, optional
    title : str, optional
    labels : bool, default True
        Write the vertex labels.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.homology.closure : builds a complex from its largest simplices.
    boundary_matrix : the matrix of the boundary map.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1.

    Examples
    --------
    >>> import shapelab as sl
    >>> square = sl.closure([(0, 1, 2), (0, 2, 3)])
    >>> fig = simplicial_complex(square, [(0, 0), (1, 0), (1, 1), (0, 1)], chain=[(0, 1), (1, 2)])
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    a simplicial complex of 4 vertices, 5 edges, 2 triangles, triangles shaded green; a chain of 2 simplices drawn thick in vermillion.
    """
    S = sorted({tuple(sorted(int(v) for v in s)) for s in simplices}, key=lambda s: (len(s), s))
    pos = {
        int(i): np.asarray(p, dtype=float)
        for i, p in (positions.items() if isinstance(positions, dict) else enumerate(positions))
    }
    by_dim = {k: [s for s in S if len(s) == k + 1] for k in range(4)}
    unplaced = sorted({v for s in S for v in s} - set(pos))
    if unplaced:
        raise ValueError(f"positions: no position for vertex {unplaced[0]}")
    if ax is None:
        fig, ax = new_figure(size=(PAGE[0] / 2, PAGE[1]))
    fig = ax.figure
    with style():
        tris = [[pos[v] for v in t] for t in by_dim[2]]
        if tris:
            ax.add_collection(PolyCollection(tris, facecolors=COLORS["triangle"], alpha=0.25, edgecolors="none"))
        segs = [[pos[a], pos[b]] for a, b in by_dim[1]]
        if segs:
            ax.add_collection(LineCollection(segs, colors=COLORS["complex"], linewidths=1.2))
        c = sorted({tuple(sorted(int(v) for v in s)) for s in chain}) if chain is not None else []
        c_tris = [[pos[v] for v in t] for t in c if len(t) == 3]
        c_segs = [[pos[a], pos[b]] for a, b in (t for t in c if len(t) == 2)]
        if c_tris:
            ax.add_collection(PolyCollection(c_tris, facecolors=COLORS["void"], alpha=0.45, edgecolors="none"))
        if c_segs:
            ax.add_collection(LineCollection(c_segs, colors=COLORS["void"], linewidths=3.5))
        xy = np.array([pos[s[0]] for s in by_dim[0]]) if by_dim[0] else np.zeros((0, 2))
        ax.plot(xy[:, 0], xy[:, 1], "o", color=COLORS["complex"], ms=5, zorder=3)
        if labels:
            for (v,) in by_dim[0]:
                ax.annotate(str(v), pos[v], xytext=(4, 4), textcoords="offset points", fontsize=9)
        if len(xy):
            lo, hi = xy.min(axis=0), xy.max(axis=0)
            pad = 0.12 * max(float((hi - lo).max()), 1.0)
            ax.set_xlim(lo[0] - pad, hi[0] + pad)
            ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        for spine in ax.spines.values():
            spine.set_visible(False)
        if title:
            ax.set_title(title)
    counts = ", ".join(_n(len(by_dim[k]), w) for k, w in ((0, "vertex"), (1, "edge"), (2, "triangle")))
    counts = counts.replace("vertexs", "vertices")
    text = f"{title + ': ' if title else ''}a simplicial complex of {counts}" + (
        ", triangles shaded green" if tris else ""
    )
    if c:
        text += f"; a chain of {_n(len(c), 'simplex').replace('simplexs', 'simplices')} drawn thick in vermillion"
    describe(ax, text)
    return fig


def boundary_matrix(
    M: ArrayLike,
    rows: Sequence[Sequence[int]],
    columns: Sequence[Sequence[int]],
    *,
    ax: Axes | None = None,
    title: str | None = None,
) -> Figure:
    """Draw a 0/1 boundary matrix as a grid, a filled square for each 1, rows and
    columns labelled by their simplices.

    Parameters
    ----------
    M : array_like, shape (m, n)
        The matrix, e.g. :func:`shapelab.homology.boundary_matrix`.
    rows, columns : list of tuple of int
        The simplices of the rows (dimension k − 1) and of the columns (dimension k),
        e.g. :func:`shapelab.homology.k_simplices`.
    ax : matplotlib Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.homology.boundary_matrix : computes it.
    simplicial_complex : the complex it comes from.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §IV.2 (matrix reduction).

    Examples
    --------
    >>> import shapelab as sl
    >>> triangle = sl.closure([(0, 1, 2)])
    >>> M = sl.boundary_matrix(triangle, 1)
    >>> fig = boundary_matrix(M, sl.k_simplices(triangle, 0), sl.k_simplices(triangle, 1))
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    a 3 by 3 boundary matrix over Z/2, 6 ones (column 01 has ones in rows 0, 1; column 02 has ones in rows 0, 2; column 12 has ones in rows 1, 2).
    """
    from matplotlib.colors import ListedColormap

    A = np.asarray(M, dtype=np.uint8) % 2
    if A.ndim != 2 or A.shape != (len(rows), len(columns)):
        raise ValueError(
            f"M: expected shape ({len(rows)}, {len(columns)}) for the rows and columns given, got {A.shape}"
        )
    name = lambda s: "".join(str(v) for v in s) if all(0 <= v < 10 for v in s) else "-".join(map(str, s))  # noqa: E731
    if ax is None:
        fig, ax = new_figure(size=(PAGE[0] / 2, PAGE[1]))
    fig = ax.figure
    with style():
        ax.imshow(A, cmap=ListedColormap(["white", COLORS["ball_edge"]]), vmin=0, vmax=1, aspect="equal")
        ax.set_xticks(range(len(columns)), [name(s) for s in columns], rotation=90 if len(columns) > 8 else 0)
        ax.set_yticks(range(len(rows)), [name(s) for s in rows])
        ax.set_xticks(np.arange(-0.5, len(columns)), minor=True)
        ax.set_yticks(np.arange(-0.5, len(rows)), minor=True)
        ax.grid(which="minor", color=COLORS["muted"], lw=0.5)
        ax.grid(which="major", visible=False)
        ax.tick_params(which="minor", length=0)
        for i, j in zip(*np.nonzero(A)):
            ax.text(j, i, "1", ha="center", va="center", color="white", fontsize=9)
        if title:
            ax.set_title(title)
    ones = "; ".join(
        f"column {name(columns[j])} has ones in rows " + ", ".join(name(rows[i]) for i in np.flatnonzero(A[:, j]))
        for j in range(A.shape[1])
        if A[:, j].any()
    )
    describe(
        ax,
        f"{title + ': ' if title else ''}a {A.shape[0]} by {A.shape[1]} boundary matrix over Z/2, "
        f"{int(A.sum())} ones" + (f" ({ones})" if A.shape[1] <= 12 and ones else ""),
    )
    return fig
