"""The mouth of a region of the complement, and what pockets of both kinds measure
(Notes §23.1; CASTp's "mouth openings").

Let :math:`R` be a set of free cells in the outside component of the complement of
:math:`K_\\tau` (a pocket's region).  In the dual graph of the complement
(:mod:`shapelab.cavities.complement`) delete :math:`R`.  The component of
:math:`\\infty` in what is left is the rest of the outside, :math:`O_R`; the other
components are *crevices*: free cells reachable from :math:`\\infty` only through
:math:`R` (dents in the pocket's own wall).  The *mouth* of :math:`R` is the set of
open faces with one side in :math:`R` and the other in :math:`O_R`: the cut between
:math:`R` and :math:`\\infty`.  Every path out leaves :math:`R` for the last time
through a mouth face, so closing the mouth seals :math:`R` (with its crevices) off,
and a face into a crevice is no opening.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cached_property

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from .._engine import mouths as _engine
from .._engine.persistence import summary
from .freespace import free_measure

__all__ = ["mouth", "mouth_finder", "MeasuredRegion", "simplex_sizes"]


def mouth(F, tau: float, cell_ids) -> np.ndarray:
    """The mouth of the region ``cell_ids`` at ``tau``, by its definition (module docstring).

    Parameters
    ----------
    F : Filtration
        The α-filtration.
    tau : float
        The growth time.
    cell_ids : array_like of int
        The region: rows of ``F.simplices(d)``, free at ``tau`` and in the outside.

    Returns
    -------
    ndarray of int
        Rows of ``F.simplices(d-1)``, ascending.

    See Also
    --------
    mouth_finder
        The same for many regions of one ``(F, tau)``.

    Examples
    --------
    Figure 23.2's flask: its pocket opens through one edge, the neck.

    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.figure_23_2()[0])
    >>> (p,) = sl.pockets(F)
    >>> mouth(F, 0.0, p.cell_ids).tolist() == p.mouth_ids.tolist()
    True
    """
    S = summary(F)
    k = S.k
    n = S.values[k].shape[0]
    u, v = S.cell_dual  # per facet: the cells on its two sides (n: the outside)
    open_face = S.values[k - 1] > tau
    in_region = np.zeros(n + 1, dtype=bool)
    in_region[np.asarray(cell_ids, dtype=np.int64)] = True
    # the complement without R: free cells and the outside glued along open faces
    keep = open_face & ~in_region[u] & ~in_region[v]
    graph = coo_matrix((np.ones(int(keep.sum()), dtype=np.int8), (u[keep], v[keep])), shape=(n + 1, n + 1))
    _, labels = connected_components(graph, directed=False)
    rest_of_outside = labels == labels[n]
    # open faces with one side in R and the other in the rest of the outside
    other = np.where(in_region[u], v, u)
    on_mouth = open_face & (in_region[u] != in_region[v]) & rest_of_outside[other]
    return np.flatnonzero(on_mouth)


def mouth_finder(F, tau: float, precision: str = "exact") -> Callable[[np.ndarray], np.ndarray]:
    """A function ``cell_ids -> mouth`` for many regions of one ``(F, tau)``.

    Parameters
    ----------
    F : Filtration
    tau : float
    precision : {"exact", "fast"}, default "exact"
        ``"exact"``: the engine's certified search (a breadth-first tree from
        :math:`\\infty` numbered in preorder settles most faces at once, a local search
        the rest; built once per ``(F, tau)``), today's path.  ``"fast"``: the plain
        definition, :func:`mouth`, one graph search per region.  Both return the same
        faces (tested).

    Returns
    -------
    callable

    See Also
    --------
    mouth
        The definition.
    """
    if precision == "fast":
        return lambda cell_ids: mouth(F, tau, cell_ids)
    return _engine.OutsideGraph(summary(F), F, tau).mouth


class MeasuredRegion:
    """What :class:`shapelab.Pocket` and :class:`shapelab.FlowPocket` both measure of a
    region of cells at ``tau``: the times of the :class:`shapelab.Cavity`
    protocol, the free volume and the size of the mouth (Notes §23.1).

    The subclass is a dataclass with ``cells``, ``mouth``, ``closes_at``, ``fills_at``,
    ``tau`` and ``balls``; one source for both pocket definitions.

    See Also
    --------
    shapelab.cavities.Pocket, shapelab.cavities.FlowPocket
        The two kinds of pocket.
    """

    @property
    def born(self) -> float:
        """``closes_at``: when the region becomes a void (the :class:`shapelab.Cavity` protocol)."""
        return self.closes_at

    @property
    def dies(self) -> float:
        """``fills_at``: when that void is filled (the :class:`shapelab.Cavity` protocol)."""
        return self.fills_at

    @property
    def persistence(self) -> float:
        """``fills_at - closes_at``: how long the region lives as a void (for a flow pocket,
        0 only at a tie: a sink's orthocentre on one of its facets)."""
        return self.fills_at - self.closes_at

    @cached_property
    def volume(self) -> float:
        """Free space of the region at ``tau`` (exact power-cell decomposition)."""
        return float(free_measure(self.balls, self.tau, self.cells).sum())

    @cached_property
    def mouth_size(self) -> float:
        """Total size of the mouth simplices: length in 2D, area in 3D."""
        return float(simplex_sizes(self.balls.centers[self.mouth]).sum())


def simplex_sizes(centers: np.ndarray) -> np.ndarray:
    """Lengths (2D) or areas (3D) of facets given as ``(q, d, d)`` vertex coordinates.

    See Also
    --------
    MeasuredRegion.mouth_size
        The size of a mouth.

    Examples
    --------
    >>> simplex_sizes(np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])).tolist()
    [0.5]
    """
    c = np.asarray(centers, dtype=np.float64)
    if c.shape[0] == 0:
        return np.zeros(0)
    if c.shape[1] == 2:
        return np.linalg.norm(c[:, 1] - c[:, 0], axis=1)
    return 0.5 * np.linalg.norm(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]), axis=1)
