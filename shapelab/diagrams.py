"""Distances between persistence diagrams: bottleneck and Wasserstein, exact.

Lesson 09 reads one persistence diagram; comparing the shapes of a family (shape
classification, §23.2's first application) needs a distance between diagrams.  Both
distances match the points of one diagram to the points of the other *or to the
diagonal* (a feature of persistence 0), and take

* the **bottleneck distance** :math:`W_\\infty`: the smallest possible largest cost;
* the **Wasserstein distance** :math:`W_p`: the smallest possible
  :math:`(\\sum \\text{cost}^p)^{1/p}`,

where a point moves to another at the L∞ distance :math:`\\max(|b - b'|, |d - d'|)` and to
the diagonal at half its persistence :math:`(d - b)/2` (GUDHI's defaults).  Points that
never die (death ``+inf``) can only be matched to each other, by birth; when the two
diagrams have different numbers of them the distance is ``inf``.

Stability (Cohen-Steiner, Edelsbrunner and Harer 2007): moving every ball's filtration
value by at most ε moves the diagram by at most ε in the bottleneck distance.  For the
weighted α-filtration, whose values are power distances :math:`\\|x - z\\|^2 - r^2`, a
perturbation of the centres or weights bounds the change of every simplex's value; that
bound, not the size of the perturbation itself, is the ε of the theorem.

Both are computed exactly (in floating point, with no approximation factor): the
bottleneck distance by a binary search over the finitely many candidate costs with a
maximum bipartite matching at each step, the Wasserstein distance as an assignment
problem (:func:`scipy.optimize.linear_sum_assignment`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._toolkit.validate import as_float_array

__all__ = ["DiagramMatching", "bottleneck_distance", "wasserstein_distance"]


@dataclass(frozen=True, eq=False)
class DiagramMatching:
    """An optimal matching between two persistence diagrams.

    Attributes
    ----------
    distance : float
        The distance it achieves.
    pairs : ndarray, shape (k, 2), int
        ``(i, j)``: point ``i`` of the first diagram matched to point ``j`` of the
        second; ``j = -1`` (or ``i = -1``) for a point matched to the diagonal.  Every
        point of both diagrams appears exactly once.
    """

    distance: float
    pairs: np.ndarray

    def __repr__(self) -> str:
        return f"DiagramMatching(distance={self.distance:.6g}, pairs={len(self.pairs)})"


def _diagram(D, name: str) -> np.ndarray:
    if D is None:
        raise TypeError(f"{name} must be an array of (birth, death) pairs, got None")
    A = as_float_array(D, name)
    if A.size == 0:
        return np.zeros((0, 2))
    if A.ndim != 2 or A.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2): (birth, death) pairs, got shape {A.shape}")
    if np.isnan(A).any():
        raise ValueError(f"{name} contains NaN")
    if np.isinf(A[:, 0]).any():
        raise ValueError(f"{name} has an infinite birth; only deaths may be +inf")
    if np.any(A[:, 1] < A[:, 0]):
        i = int(np.argmax(A[:, 1] < A[:, 0]))
        raise ValueError(f"{name}[{i}] dies before it is born: {A[i].tolist()}")
    return A


def _split(A):
    ess = np.isinf(A[:, 1])
    return np.flatnonzero(~ess), np.flatnonzero(ess)


def _essential(A, B, ia, ib):
    """Essential points matched by birth order; returns (pairs, costs) or None if unequal."""
    if len(ia) != len(ib):
        return None
    oa = ia[np.argsort(A[ia, 0], kind="stable")]
    ob = ib[np.argsort(B[ib, 0], kind="stable")]
    return np.column_stack([oa, ob]), np.abs(A[oa, 0] - B[ob, 0])


def _costs(P, Q):
    """The (n + m) x (n + m) cost matrix of the augmented problem (L∞ ground cost)."""
    n, m = len(P), len(Q)
    C = np.full((n + m, n + m), np.inf)
    if n and m:
        C[:n, :m] = np.maximum(np.abs(P[:, None, 0] - Q[None, :, 0]), np.abs(P[:, None, 1] - Q[None, :, 1]))
    C[np.arange(n), m + np.arange(n)] = (P[:, 1] - P[:, 0]) / 2  # P_i -> its diagonal copy
    C[n + np.arange(m), np.arange(m)] = (Q[:, 1] - Q[:, 0]) / 2  # diagonal copy of Q_j -> Q_j
    C[n:, m:] = 0.0  # diagonal to diagonal
    return C


def _pairs_from(rows, cols, fa, fb, n, m):
    out = []
    for r, c in zip(rows.tolist(), cols.tolist()):
        if r < n and c < m:
            out.append((int(fa[r]), int(fb[c])))
        elif r < n:
            out.append((int(fa[r]), -1))
        elif c < m:
            out.append((-1, int(fb[c])))
    return out


def bottleneck_distance(D1, D2, *, matching: bool = False):
    """The bottleneck distance between two persistence diagrams, exact.

    Parameters
    ----------
    D1, D2 : array_like, shape (n, 2) and (m, 2)
        ``(birth, death)`` pairs; deaths may be ``+inf``; either may be empty.
    matching : bool
        Also return an optimal matching.

    Returns
    -------
    float, or DiagramMatching if ``matching``
        ``inf`` when the diagrams have different numbers of infinite points.

    Examples
    --------
    >>> bottleneck_distance([[0.0, 2.0]], [[0.0, 2.5]])
    0.5
    >>> bottleneck_distance([[0.0, 2.0]], [])      # to the diagonal: half the persistence
    1.0
    """
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import maximum_bipartite_matching

    A, B = _diagram(D1, "D1"), _diagram(D2, "D2")
    fa, ea = _split(A)
    fb, eb = _split(B)
    ess = _essential(A, B, ea, eb)
    if ess is None:
        return DiagramMatching(np.inf, np.zeros((0, 2), dtype=np.int64)) if matching else float("inf")
    ess_pairs, ess_cost = ess
    P, Q = A[fa], B[fb]
    n, m = len(P), len(Q)
    C = _costs(P, Q)
    best, rows, cols = 0.0, np.zeros(0, int), np.zeros(0, int)
    if n + m:
        cand = np.unique(C[np.isfinite(C)])
        lo, hi = 0, len(cand) - 1  # the largest candidate is always feasible
        while lo < hi:
            mid = (lo + hi) // 2
            G = csr_matrix(C <= cand[mid])
            if (maximum_bipartite_matching(G, perm_type="column") >= 0).sum() == n + m:
                hi = mid
            else:
                lo = mid + 1
        best = float(cand[lo])
        mate = maximum_bipartite_matching(csr_matrix(C <= cand[lo]), perm_type="column")
        rows, cols = np.arange(n + m), mate
    dist = max(best, float(ess_cost.max()) if len(ess_cost) else 0.0)
    if not matching:
        return dist
    pairs = _pairs_from(rows, cols, fa, fb, n, m) + [tuple(map(int, p)) for p in ess_pairs]
    return DiagramMatching(dist, np.array(pairs, dtype=np.int64).reshape(-1, 2))


def wasserstein_distance(D1, D2, p=2, *, matching: bool = False):
    """The p-Wasserstein distance between two persistence diagrams, exact.

    Parameters
    ----------
    D1, D2 : array_like, shape (n, 2) and (m, 2)
        ``(birth, death)`` pairs; deaths may be ``+inf``; either may be empty.
    p : int or float
        The order, ``1 <= p < inf`` (the bottleneck distance is ``p = inf``).
    matching : bool
        Also return an optimal matching.

    Returns
    -------
    float, or DiagramMatching if ``matching``

    Examples
    --------
    >>> wasserstein_distance([[0.0, 2.0], [1.0, 3.0]], [[0.0, 2.0]], p=1)
    1.0
    """
    from scipy.optimize import linear_sum_assignment

    if isinstance(p, bool) or not isinstance(p, (int, float, np.integer, np.floating)):
        raise TypeError(f"p must be a number >= 1, got {type(p).__name__}")
    p = float(p)
    if not (p >= 1) or not np.isfinite(p):
        raise ValueError(f"p must be finite and >= 1 (use bottleneck_distance for p = inf), got {p}")
    A, B = _diagram(D1, "D1"), _diagram(D2, "D2")
    fa, ea = _split(A)
    fb, eb = _split(B)
    ess = _essential(A, B, ea, eb)
    if ess is None:
        return DiagramMatching(np.inf, np.zeros((0, 2), dtype=np.int64)) if matching else float("inf")
    ess_pairs, ess_cost = ess
    P, Q = A[fa], B[fb]
    n, m = len(P), len(Q)
    total = float(np.sum(ess_cost**p))
    rows, cols = np.zeros(0, int), np.zeros(0, int)
    if n + m:
        C = _costs(P, Q) ** p
        big = np.where(np.isfinite(C), C, 0.0).sum() + 1.0  # forbidden: more than any matching
        rows, cols = linear_sum_assignment(np.where(np.isfinite(C), C, big))
        total += float(C[rows, cols].sum())
    dist = total ** (1.0 / p)
    if not matching:
        return dist
    pairs = _pairs_from(rows, cols, fa, fb, n, m) + [tuple(map(int, q)) for q in ess_pairs]
    return DiagramMatching(dist, np.array(pairs, dtype=np.int64).reshape(-1, 2))
