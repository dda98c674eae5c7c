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
(the dual :math:`H_0`), read by the elder rule: :func:`sealed_at` says when each void
is sealed, :func:`cells_when_sealed` which cells it has then.  :func:`merge_tree` is
the same history kept compact, so that a pocket's cells are read without recomputing
the components (a fast kernel, ``shapelab._engine.mouths``; equal to the two plain
functions, tested).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from .._engine import mouths as _engine
from .._engine.persistence import summary
from .._toolkit.derived import derived
from .._toolkit.unionfind import elder_merges
from .._toolkit.validate import as_positive_int, freeze
from ..filtration import as_filtration

if TYPE_CHECKING:
    from ..balls import Balls
    from ..filtration import Filtration

__all__ = [
    "complement_labels",
    "full_dimensional",
    "sealed_at",
    "cells_when_sealed",
    "merge_tree",
    "lining_of",
    "vertex_values",
]


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
        ``shapelab._engine.persistence.summary(F)``: the values per dimension, and
        ``cell_dual``, the cells on the two sides of every facet (``n``: :math:`\\infty`).
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


def sealed_at(F: Filtration | Balls) -> np.ndarray:
    """When the void of every cell is sealed: the elder rule run backwards (Notes §23.1).

    Run τ from :math:`+\\infty` down: a top simplex (*cell*) joins the complement at
    its entry time, a facet joins the two parts on its sides.  When two parts join,
    the *younger* dies and the elder lives on (the outside :math:`\\infty` is eldest,
    then the cells that fill last).  Forwards, a part that dies at facet :math:`f` is
    sealed off by :math:`f`: a void until its last-filled cell ``r`` fills (never one
    when the two times are equal).  Only facets that seal a void can join two parts
    (the *positive* facets of lesson 11 [1]_; the notes do not name them).

    Parameters
    ----------
    F : Filtration or Balls
        The α-filtration (Balls are filtered first, as for :func:`shapelab.voids`).

    Returns
    -------
    ndarray of float, shape (n_cells,)
        Per cell ``r``, when the part of the complement rooted at ``r`` is sealed off;
        empty when ``F`` has no top simplices.  Kept on ``F``.

    See Also
    --------
    cells_when_sealed
        The void's cells at that moment.
    shapelab.voids
        The voids at one τ, born at ``sealed_at`` of their root.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher and A. Zomorodian, "Topological persistence and
           simplification", *Discrete Comput. Geom.* 28:511-533, 2002.
           doi:10.1007/s00454-002-2885-2

    Examples
    --------
    >>> import numpy as np, shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.ring(12))  # twelve disks on a circle
    >>> sealed, fills = sealed_at(F), F.values(2)
    >>> r = int(np.argmax(fills - sealed))  # the root of the ring's hole
    >>> round(float(sealed[r]), 6), round(float(fills[r]), 6)
    (-0.397114, 8.0)
    """
    F = as_filtration(F, "sealed_at")
    if not full_dimensional(F):
        return np.empty(0)
    return derived(F, "cavities.sealed_at", _sealed_at)


def _sealed_at(F) -> np.ndarray:
    S = summary(F)
    k = S.k
    n = S.values[k].shape[0]
    u, v = S.cell_dual  # per facet: the cells on its two sides (n: the outside)
    age = np.r_[np.arange(n, 0, -1), 0]  # smaller is elder: the outside, then late cells
    sealed = np.full(n, -np.inf)

    def seal(facet, elder, younger, oldest):
        sealed[oldest[younger]] = S.values[k - 1][facet]

    elder_merges(n + 1, u, v, S.pos_facets[::-1], age, seal)
    return freeze(sealed)  # kept on F and read by voids and pockets: read-only


def cells_when_sealed(F: Filtration | Balls, r: int) -> np.ndarray:
    """The cells of the void rooted at cell ``r`` at the moment it is sealed.

    At :math:`\\tau = ` ``sealed_at(F)[r]`` the sealing facet is in :math:`K_\\tau`,
    so the void is the part of the complement that holds ``r``: the facets with a
    larger value are open (facets sealed at the same time close together).

    Parameters
    ----------
    F : Filtration or Balls
        The α-filtration.
    r : int
        A cell (a row of ``F.simplices(d)``), ``0 <= r < n_cells``.

    Returns
    -------
    ndarray of int
        The cell rows, ascending.

    Raises
    ------
    ValueError
        If ``r`` is not a cell of ``F``.

    See Also
    --------
    sealed_at
        When the void is sealed.
    merge_tree
        The same sets without recomputing the components (a fast kernel).

    Examples
    --------
    >>> import numpy as np, shapelab as sl
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> F = sl.alpha_filtration(sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], 0.9))
    >>> r = int(np.argmax(F.values(2) - sealed_at(F)))  # the root of the ring's hole
    >>> len(cells_when_sealed(F, r))  # the hole's ten triangles
    10
    """
    F = as_filtration(F, "cells_when_sealed")
    sealed = sealed_at(F)
    r = as_positive_int(r, "r", minimum=0)
    if r >= sealed.shape[0]:
        raise ValueError(f"r must be a cell of F, 0 <= r < {sealed.shape[0]}, got {r}")
    labels, _ = complement_labels(F, summary(F), float(sealed[r]))
    return np.flatnonzero(labels[:-1] == labels[r])


def merge_tree(F) -> _engine.MergeTree:
    """The merge tree of the complement of ``F`` run backwards in τ (kept on ``F``).

    The fast kernel of :func:`sealed_at` and :func:`cells_when_sealed`: the same pass,
    keeping every part's cells as a run of one leaf order (``shapelab._engine.mouths``).

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
