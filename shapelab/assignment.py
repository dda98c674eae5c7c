r"""Diagram distances as assignment problems (Notes §23.2, shape classification;
Cohen-Steiner, Edelsbrunner and Harer 2007; Kerber, Morozov and Nigmetov 2017).

A matching between two persistence diagrams :math:`A` (:math:`n` points) and
:math:`B` (:math:`m` points) may send a point to the diagonal, at the cost of its
distance to its orthogonal projection.  Adding to :math:`A` the projections of
:math:`B`'s points and to :math:`B` those of :math:`A`'s turns it into a perfect
matching of two sets of :math:`n + m` points, whose cost matrix is

.. math::
   C = \begin{pmatrix} c(a_i, b_j) & c(a_i, \Delta)\ \text{on the diagonal, } \infty \text{ off it} \\
                       c(\Delta, b_j)\ \text{on the diagonal, } \infty \text{ off it} & 0
       \end{pmatrix},

:math:`(n + m) \times (m + n)`: the top-right block lets :math:`a_i` go to its own
projection only, the bottom-left lets :math:`b_j` go to its own, and two projections
match at no cost.  Then

* :math:`W_p(A, B)^p` is the optimal value of the assignment problem with costs
  :math:`C^p` (Hungarian algorithm; ``scipy.optimize.linear_sum_assignment``);
* the bottleneck distance :math:`W_\infty(A, B)` is the smallest entry :math:`\delta`
  of :math:`C` such that a perfect matching uses only entries :math:`\le \delta`
  (feasibility: an assignment of zero cost for the 0/1 matrix :math:`[C > \delta]`).

These are the textbook reductions, written plainly for finite diagrams (every point
dies); :func:`shapelab.wasserstein_distance` and :func:`shapelab.bottleneck_distance`
compute the same distances faster and handle points at infinity.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import linear_sum_assignment

from ._toolkit.validate import as_float_array

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["augmented_cost_matrix", "assignment_distance"]


def _finite_diagram(D, name: str) -> np.ndarray:
    A = as_float_array(D, name).reshape(-1, 2) if np.size(D) else np.zeros((0, 2))
    if not np.all(np.isfinite(A)):
        raise ValueError(
            f"{name} must have finite births and deaths (points at infinity: use shapelab.wasserstein_distance)"
        )
    return A


def _ground(P, Q, q: float) -> np.ndarray:
    diff = np.abs(P[:, None, :] - Q[None, :, :])
    if np.isinf(q):
        return diff.max(axis=2)
    return (diff**q).sum(axis=2) ** (1.0 / q)


def augmented_cost_matrix(D1: ArrayLike, D2: ArrayLike, *, internal_p: float = np.inf) -> np.ndarray:
    """The square cost matrix of the matching problem between two finite diagrams.

    Parameters
    ----------
    D1, D2 : array_like, shape (n, 2) and (m, 2)
        ``(birth, death)`` pairs, all finite; either may be empty.
    internal_p : float
        The ground metric, the :math:`L_q` norm of the plane with ``q = internal_p``
        (default ``inf``: :math:`\\max(|b - b'|, |d - d'|)`).  A point goes to the
        diagonal at :math:`2^{1/q} (d - b)/2`.

    Returns
    -------
    ndarray, shape (n + m, m + n)
        Rows: the points of ``D1``, then the diagonal projections of ``D2``'s points;
        columns: the points of ``D2``, then the projections of ``D1``'s.  Forbidden
        pairs (a point with another point's projection) are ``inf``.

    See Also
    --------
    assignment_distance : solves the assignment problem on it.

    References
    ----------
    .. [1] D. Cohen-Steiner, H. Edelsbrunner and J. Harer, "Stability of persistence
       diagrams", Discrete Comput. Geom. 37 (2007) 103–120, doi:10.1007/s00454-006-1276-5.

    Examples
    --------
    >>> augmented_cost_matrix([[0.0, 2.0]], [[0.0, 3.0]])
    array([[1. , 1. ],
           [1.5, 0. ]])
    """
    A, B = _finite_diagram(D1, "D1"), _finite_diagram(D2, "D2")
    q = float(internal_p)
    if not q >= 1:
        raise ValueError(f"internal_p must be >= 1 (inf allowed), got {internal_p}")
    n, m = len(A), len(B)
    factor = 1.0 if np.isinf(q) else 2.0 ** (1.0 / q)
    C = np.full((n + m, m + n), np.inf)
    C[:n, :m] = _ground(A, B, q)
    C[n:, m:] = 0.0
    C[np.arange(n), m + np.arange(n)] = factor * (A[:, 1] - A[:, 0]) / 2
    C[n + np.arange(m), np.arange(m)] = factor * (B[:, 1] - B[:, 0]) / 2
    return C


def assignment_distance(D1: ArrayLike, D2: ArrayLike, p: float = 1, *, internal_p: float = np.inf) -> float:
    """The p-Wasserstein or bottleneck distance of two finite diagrams by assignment.

    Parameters
    ----------
    D1, D2 : array_like, shape (n, 2) and (m, 2)
        ``(birth, death)`` pairs, all finite.
    p : float
        The order, ``1 <= p``; ``np.inf`` gives the bottleneck distance.
    internal_p : float
        The ground metric (see :func:`augmented_cost_matrix`).

    Returns
    -------
    float
        :math:`(\\min_\\pi \\sum C_{i\\pi(i)}^p)^{1/p}`, or for ``p = inf`` the
        smallest :math:`\\delta` admitting a perfect matching of entries
        :math:`\\le \\delta`.

    See Also
    --------
    augmented_cost_matrix, shapelab.wasserstein_distance, shapelab.bottleneck_distance

    References
    ----------
    .. [1] M. Kerber, D. Morozov and A. Nigmetov, "Geometry helps to compare
       persistence diagrams", ACM J. Exp. Algorithmics 22 (2017) 1.4,
       doi:10.1145/3064175.

    Examples
    --------
    >>> assignment_distance([[0.0, 2.0], [1.0, 3.0]], [[0.0, 2.0]], p=1)
    1.0
    >>> assignment_distance([[0.0, 2.0]], [[0.0, 2.5]], p=np.inf)
    0.5
    """
    p = float(p)
    if not p >= 1:
        raise ValueError(f"p must be >= 1 (inf for the bottleneck distance), got {p}")
    C = augmented_cost_matrix(D1, D2, internal_p=internal_p)
    if C.size == 0:
        return 0.0
    big = np.where(np.isfinite(C), C, 0.0).max() + 1.0
    if np.isinf(p):
        cand = np.unique(C[np.isfinite(C)])
        lo, hi = 0, len(cand) - 1
        while lo < hi:  # the largest finite entry is always feasible (everything to the diagonal)
            mid = (lo + hi) // 2
            bad = (C > cand[mid]).astype(float)
            r, c = linear_sum_assignment(bad)
            if bad[r, c].sum() == 0:
                hi = mid
            else:
                lo = mid + 1
        return float(cand[lo])
    scale = big
    Cp = np.where(np.isfinite(C), (C / scale) ** p, (big / scale) ** p * (len(C) + 1))
    r, c = linear_sum_assignment(Cp)
    return float(scale * Cp[r, c].sum() ** (1.0 / p))
