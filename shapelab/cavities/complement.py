"""The complement of the grown union, read through the filtration (Notes §23.1).

The dual complex :math:`K_\\tau` lies inside the union :math:`U_\\tau` of the grown
balls, and :math:`U_\\tau` deformation-retracts onto it (Edelsbrunner 1995), so the
components of :math:`\\mathbb{R}^d \\setminus U_\\tau` correspond one to one to the
components of :math:`\\mathbb{R}^d \\setminus |K_\\tau|`.  Those are read off the
*dual graph of the complement*: its nodes are the top simplices of the regular
triangulation not in :math:`K_\\tau` (the *free cells*) and the outside
:math:`\\infty`; two nodes are joined across every :math:`(d-1)`-simplex not in
:math:`K_\\tau` (an *open face*) that they share.  A component that avoids
:math:`\\infty` is a void; the component of :math:`\\infty` is the outside.

Running τ backwards the complement only grows, so its whole history is one merge tree
(the dual :math:`H_0`): :func:`merge_tree` says when each void is sealed and filled.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from .._engine import mouths as _engine

__all__ = ["complement_labels", "full_dimensional", "merge_tree", "lining_of", "vertex_values"]


def full_dimensional(F) -> bool:
    """``True`` when the filtration has top simplices (``d + 1`` balls in general
    position at least): only then has its complement cells.

    See Also
    --------
    complement_labels
        The components of the complement.
    """
    return int(F.dimension) == F.balls.dim and len(F.values(F.balls.dim)) > 0


def complement_labels(F, S, tau: float) -> tuple[np.ndarray, np.ndarray]:
    """The components of the complement of :math:`K_\\tau` (Notes §23.1).

    Parameters
    ----------
    F : Filtration
        The α-filtration.
    S : object
        Its summary (``shapelab._topology.summary(F)``): the values per dimension and
        ``cell_dual``, the two cells on either side of every facet (``n`` for
        :math:`\\infty`).
    tau : float
        The growth time.

    Returns
    -------
    labels : ndarray, shape (n + 1,)
        A component label for every top simplex and, last, for :math:`\\infty`.
    free : ndarray of bool, shape (n + 1,)
        Which nodes are free cells (not in :math:`K_\\tau`; :math:`\\infty` is free).

    See Also
    --------
    shapelab.cavities.voids
        The components that avoid the outside.

    Examples
    --------
    >>> import numpy as np, shapelab as sl
    >>> from shapelab._engine.persistence import summary
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> F = sl.alpha_filtration(sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], 0.9))
    >>> lab, free = complement_labels(F, summary(F), 0.0)
    >>> int(np.sum(free[:-1] & (lab[:-1] != lab[-1])))  # the free cells of the ring's hole
    10
    """
    k = S.k
    n = S.values[k].shape[0]
    u, v = S.cell_dual  # per facet: the cells on its two sides (n: the outside)
    open_face = S.values[k - 1] > tau
    graph = coo_matrix(
        (np.ones(int(open_face.sum()), dtype=np.int8), (u[open_face], v[open_face])), shape=(n + 1, n + 1)
    )
    _, labels = connected_components(graph, directed=False)
    free = np.append(S.values[k] > tau, True)
    return labels, free


def merge_tree(F) -> _engine.MergeTree:
    """The merge tree of the complement of ``F`` run backwards in τ (kept on ``F``).

    ``kill_value[c]`` is the time the void whose last-filled cell is ``c`` is sealed
    (its ``born``); the tree's leaf runs list a void's cells at every moment.  One
    union–find pass in reverse filtration order (``shapelab._engine.mouths``).

    See Also
    --------
    complement_labels
        The components at one τ.
    """
    return _engine.merge_tree_of(F)


def vertex_values(F, n_balls: int) -> np.ndarray:
    """Entry time of every ball in ``F`` (``inf`` for a ball that never enters).

    See Also
    --------
    lining_of
        The balls that exist at τ.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0.0, 0.0], [3.0, 0.0]], [1.0, 2.0]))
    >>> vertex_values(F, 2).tolist()
    [-1.0, -4.0]
    """
    out = np.full(n_balls, np.inf)
    out[np.asarray(F.simplices(0), dtype=np.int64).ravel()] = F.values(0)
    return out


def lining_of(cells: np.ndarray, tau: float, vval: np.ndarray) -> np.ndarray:
    """The balls lining a region: the vertices of its cells that exist at ``tau``.

    See Also
    --------
    vertex_values
        The entry times ``vval``.
    """
    verts = np.unique(cells)
    return verts[vval[verts] <= tau]
