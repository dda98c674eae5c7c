"""Distances between persistence diagrams: bottleneck and Wasserstein, exact.

Lesson 11 reads one persistence diagram; comparing the shapes of a family (shape
classification, §23.2's first application) needs a distance between diagrams.  Both
distances match the points of one diagram to the points of the other *or to the
diagonal* (a feature of persistence 0), and take

* the **bottleneck distance** :math:`W_\\infty`: the smallest possible largest cost;
* the **Wasserstein distance** :math:`W_p`: the smallest possible
  :math:`(\\sum \\text{cost}^p)^{1/p}`,

where a point moves to another at the L∞ distance :math:`\\max(|b - b'|, |d - d'|)` and to
the diagonal at half its persistence :math:`(d - b)/2` (GUDHI's defaults;
:func:`wasserstein_distance` takes any :math:`L_q` ground metric, ``internal_p``).

Points at infinity (essential points), as GUDHI treats them: a point that never dies,
:math:`(b, +\\infty)`, can only be matched to another such point, at cost
:math:`|b - b'|`; a point born at :math:`-\\infty`, :math:`(-\\infty, d)` (as in a
sublevel-set filtration that starts with something already there, or an extended
diagram), only to another such point, at cost :math:`|d - d'|`; and
:math:`(-\\infty, +\\infty)` only to another :math:`(-\\infty, +\\infty)`, at cost 0.
Each family is matched in sorted order, which is optimal on a line.  When the two
diagrams have different numbers of points in one family the distance is ``inf``.
:math:`(-\\infty, -\\infty)` and :math:`(+\\infty, +\\infty)` lie on the diagonal: they
cost nothing and are matched to it (GUDHI's ``wasserstein_distance`` and
``bottleneck_distance`` do the same).

Stability (Cohen-Steiner, Edelsbrunner and Harer 2007): moving every ball's filtration
value by at most ε moves the diagram by at most ε in the bottleneck distance.  For the
weighted α-filtration, whose values are power distances :math:`\\|x - z\\|^2 - r^2`, a
perturbation of the centres or weights bounds the change of every simplex's value; that
bound, not the size of the perturbation itself, is the ε of the theorem.

Both are computed exactly (in floating point, with no approximation factor): the
bottleneck distance by a binary search over the finitely many candidate costs with a
maximum bipartite matching at each step, the Wasserstein distance as an assignment
problem, on a sparse graph when most points lie near the diagonal.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.validate import as_float_array

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike

__all__ = ["DiagramMatching", "bottleneck_distance", "wasserstein_distance", "distance_matrix"]


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

    See Also
    --------
    bottleneck_distance
        Produces it.
    wasserstein_distance
        Produces it.
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
    if np.any(A[:, 1] < A[:, 0]):
        i = int(np.argmax(A[:, 1] < A[:, 0]))
        raise ValueError(f"{name}[{i}] dies before it is born: {A[i].tolist()}")
    return A


def _rescale(A, B):
    """A and B divided by a power of two near their largest finite coordinate, and that
    power: both distances are homogeneous of degree 1, and scaling by 2^k is exact, so
    persistences and differences such as 1e308 - (-1e308) no longer overflow."""
    fin = np.concatenate([A[np.isfinite(A)], B[np.isfinite(B)]])
    big = float(np.abs(fin).max()) if fin.size else 0.0
    if big == 0.0:
        return A, B, 1.0
    s = float(np.ldexp(1.0, np.frexp(big)[1] - 1))  # a power of two <= big: finite
    return A / s, B / s, s


def _split(A):
    """The finite points, and the families of points at infinity (see the module docstring).

    Returns ``finite, families, diagonal``: ``families`` lists the indices of the points
    ``(b, +inf)``, ``(-inf, d)`` and ``(-inf, +inf)`` with the coordinate that prices a
    match in each (0, 1, or None: all cost 0); ``diagonal`` the points
    ``(-inf, -inf)`` and ``(+inf, +inf)``, which lie on the diagonal.
    """
    fin_b, fin_d = np.isfinite(A[:, 0]), np.isfinite(A[:, 1])
    finite = np.flatnonzero(fin_b & fin_d)
    families = [
        (np.flatnonzero(fin_b & ~fin_d), 0),  # (b, +inf): dies never, priced by birth
        (np.flatnonzero(~fin_b & fin_d), 1),  # (-inf, d): born at -inf, priced by death
        (np.flatnonzero(~fin_b & (A[:, 1] == np.inf) & (A[:, 0] == -np.inf)), None),
    ]
    diagonal = np.flatnonzero(~fin_b & ~fin_d & (A[:, 0] == A[:, 1]))
    return finite, families, diagonal


def _essential(A, B, sa, sb):
    """Points at infinity, each family matched in sorted order (optimal on a line for every
    order p); returns (pairs, costs), or None when a family has unequal sizes."""
    (_, fam_a, diag_a), (_, fam_b, diag_b) = sa, sb
    pairs, costs = [], []
    for (ia, col), (ib, _) in zip(fam_a, fam_b):
        if len(ia) != len(ib):
            return None
        if col is None:
            pairs.append(np.column_stack([ia, ib]))
            costs.append(np.zeros(len(ia)))
            continue
        oa = ia[np.argsort(A[ia, col], kind="stable")]
        ob = ib[np.argsort(B[ib, col], kind="stable")]
        pairs.append(np.column_stack([oa, ob]))
        costs.append(np.abs(A[oa, col] - B[ob, col]))
    minus = np.full(len(diag_a), -1), np.full(len(diag_b), -1)
    pairs += [np.column_stack([diag_a, minus[0]]), np.column_stack([minus[1], diag_b])]
    return np.concatenate(pairs).astype(np.int64).reshape(-1, 2), np.concatenate(costs)


def _costs(P, Q, q=np.inf):
    """The point-to-point L_q costs (n, m) and the costs to the diagonal of P and Q.

    The L_q distance of (b, d) to the diagonal is reached at its orthogonal projection
    ((b+d)/2, (b+d)/2) (the norm is symmetric and convex): :math:`2^{1/q}(d - b)/2`.
    """
    n, m = len(P), len(Q)
    PQ = np.zeros((n, m))
    if n and m:
        db, dd = np.abs(P[:, None, 0] - Q[None, :, 0]), np.abs(P[:, None, 1] - Q[None, :, 1])
        PQ = np.maximum(db, dd)
        if q == 1:
            PQ = db + dd
        elif q == 2:
            PQ = np.hypot(db, dd)
        elif q != np.inf:  # scaled by the larger difference: no overflow or underflow
            with np.errstate(invalid="ignore", divide="ignore"):
                r = np.where(PQ > 0, np.minimum(db, dd) / np.where(PQ > 0, PQ, 1.0), 0.0)
            PQ = PQ * (1.0 + r**q) ** (1.0 / q)
    k = 1.0 if q == np.inf else 2.0 ** (1.0 / q)
    return PQ, (P[:, 1] - P[:, 0]) / 2 * k, (Q[:, 1] - Q[:, 0]) / 2 * k


def _graph(n, m, ii, jj, keep_p, keep_q, weights=None):
    """The sparse augmented bipartite graph (Efrat, Itai and Katz 2001).

    Rows are the points of P (``0..n-1``) and the diagonal copies of Q's points
    (``n + j``); columns are the points of Q (``0..m-1``) and the diagonal copies of P's
    (``m + i``).  Edges: P_i–Q_j for the pairs (ii, jj); P_i to its own diagonal copy
    where ``keep_p``; Q_j's diagonal copy to Q_j where ``keep_q``; and the diagonal copy
    of Q_j to that of P_i for the same pairs (ii, jj) only.  That last restriction loses
    nothing: in any perfect matching the copies left over are those of matched pairs
    P_i–Q_j, and they can be paired with each other (at cost 0).  It keeps the graph
    sparse where the complete diagonal-to-diagonal block would add n·m edges.
    """
    from scipy.sparse import csr_matrix

    ip, iq = np.flatnonzero(keep_p), np.flatnonzero(keep_q)
    r = np.concatenate([ii, ip, n + iq, n + jj])
    c = np.concatenate([jj, m + ip, iq, m + ii])
    if weights is None:
        w = np.ones(len(r), dtype=np.int8)
    else:
        w = np.concatenate(weights)
    return csr_matrix((w, (r, c)), shape=(n + m, n + m))


_DENSE_LIMIT = 4000  # (n + m)^2 float64 costs: 128 MB at the limit


def _min_cost_matching(PQ, hp, hq, p):
    """An optimal matching for the p-Wasserstein cost of the augmented problem.

    A pair P_i–Q_j is worth an edge only if it is cheaper than sending both to the
    diagonal (otherwise exchanging it for two diagonal edges never costs more), so the
    graph is sparse when most points are noise near the diagonal.  Up to a few thousand
    points the dense Jonker–Volgenant solver (:func:`scipy.optimize.linear_sum_assignment`)
    is used all the same: SciPy's sparse solver checks feasibility with a Hopcroft–Karp
    that can take exponential time on this layered graph (scipy/scipy#26147; measured:
    13 s on two 214-point diagrams).  Beyond, the dense matrix would not fit, and the
    sparse solver is the only option.
    """
    from scipy.optimize import linear_sum_assignment
    from scipy.sparse.csgraph import min_weight_full_bipartite_matching

    n, m = PQ.shape[0], len(hq)
    cp, dp, dq = PQ**p, hp**p, hq**p
    worth = cp < dp[:, None] + dq[None, :]
    if n + m <= _DENSE_LIMIT:
        # the same graph as a dense matrix, absent edges priced out (6x faster than the
        # complete graph on 400-point diagrams)
        big = cp.sum() + dp.sum() + dq.sum() + 1.0  # more than any matching costs
        C = np.full((n + m, n + m), big)
        C[:n, :m] = np.where(worth, cp, big)
        C[np.arange(n), m + np.arange(n)] = dp
        C[n + np.arange(m), np.arange(m)] = dq
        C[n:, m:] = np.where(worth.T, 0.0, big)
        return linear_sum_assignment(C)
    ii, jj = np.nonzero(worth)
    # sparse solvers drop zero weights: shift every weight by 1; every perfect matching
    # has n + m edges, so the optimum does not move
    w = [cp[ii, jj] + 1.0, dp + 1.0, dq + 1.0, np.ones(len(ii))]
    G = _graph(n, m, ii, jj, np.ones(n, bool), np.ones(m, bool), weights=w)
    return min_weight_full_bipartite_matching(G)


def _matched_costs(match, PQ, hp, hq):
    """The L∞ cost of every edge of a matching of the augmented graph."""
    rows, cols = match
    n, m = PQ.shape[0], len(hq)
    cost = np.zeros(len(rows))
    pq = (rows < n) & (cols < m)
    cost[pq] = PQ[rows[pq], cols[pq]]
    tp = (rows < n) & (cols >= m)
    cost[tp] = hp[rows[tp]]
    tq = (rows >= n) & (cols < m)
    cost[tq] = hq[cols[tq]]
    return cost


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


def _cover(n, m, ii, jj, need_p, need_q):
    """A matching of the bipartite graph P–Q with edges (ii, jj) that covers every P_i
    with ``need_p`` and every Q_j with ``need_q``, as a list of pairs (i, j); None if
    there is none.

    The decision problem of the bottleneck distance at a threshold δ: the points that
    cannot go to the diagonal (half their persistence exceeds δ) must be matched to a
    point of the other diagram within δ; all others can go to the diagonal.  By the
    Mendelsohn–Dulmage theorem such a matching exists if and only if one matching covers
    the needed points of P and another those of Q; the two are combined component by
    component of their union (paths and cycles).  Each is a maximum bipartite matching
    (Hopcroft–Karp) on a graph with only the needed points on one side: small, and
    without the layered diagonal-copy structure of the usual augmented graph, on which
    SciPy's Hopcroft–Karp can take exponential time (scipy/scipy#26147).
    """
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import maximum_bipartite_matching

    def side(need, rows, cols, n_cols):
        idx = np.flatnonzero(need)
        if not len(idx):
            return {}
        pos = np.full(len(need), -1)
        pos[idx] = np.arange(len(idx))
        keep = need[rows]
        if not np.all(np.isin(idx, rows[keep])):  # a needed point without any edge
            return None
        G = csr_matrix((np.ones(int(keep.sum()), np.int8), (pos[rows[keep]], cols[keep])), shape=(len(idx), n_cols))
        mate = maximum_bipartite_matching(G, perm_type="column")
        if np.any(mate < 0):
            return None
        return dict(zip(idx.tolist(), mate.tolist()))

    m1 = side(need_p, ii, jj, m)  # P_i -> Q_j
    if m1 is None:
        return None
    m2 = side(need_q, jj, ii, n)  # Q_j -> P_i
    if m2 is None:
        return None
    # combine (Mendelsohn–Dulmage): walk each component of M1 ∪ M2 (degree <= 2)
    p1, q1 = dict(m1), {j: i for i, j in m1.items()}
    q2, p2 = dict(m2), {i: j for j, i in m2.items()}
    seen_p, seen_q, out = set(), set(), []
    for start in list(p1) + [q2[j] for j in q2]:
        if start in seen_p:
            continue
        comp_p, comp_q, stack = set(), set(), [("p", start)]
        while stack:
            kind, v = stack.pop()
            if kind == "p":
                if v in comp_p:
                    continue
                comp_p.add(v)
                stack += [("q", w) for w in (p1.get(v), p2.get(v)) if w is not None]
            else:
                if v in comp_q:
                    continue
                comp_q.add(v)
                stack += [("p", w) for w in (q1.get(v), q2.get(v)) if w is not None]
        seen_p |= comp_p
        seen_q |= comp_q
        first = [(i, p1[i]) for i in comp_p if i in p1]
        covered = {j for _, j in first}
        if all(j in covered for j in comp_q if need_q[j]):
            out += first  # M1 covers the component's needed points of both sides
        else:
            out += [(q2[j], j) for j in comp_q if j in q2]
    for j, i in q2.items():  # components reached only from Q (no needed P on them)
        if j not in seen_q:
            out.append((i, j))
    return sorted(out)


def bottleneck_distance(D1: ArrayLike, D2: ArrayLike, *, matching: bool = False) -> float | DiagramMatching:
    """The bottleneck distance between two persistence diagrams, exact.

    Parameters
    ----------
    D1, D2 : array_like, shape (n, 2) and (m, 2)
        ``(birth, death)`` pairs; births may be ``-inf`` and deaths ``+inf`` (see the
        module docstring); either may be empty.
    matching : bool
        Also return an optimal matching.

    Returns
    -------
    float, or DiagramMatching if ``matching``
        ``inf`` when the diagrams have different numbers of points at infinity of
        one kind (:math:`(b, \\infty)`, :math:`(-\\infty, d)` or
        :math:`(-\\infty, \\infty)`); the matching is then empty.

    See Also
    --------
    wasserstein_distance, distance_matrix

    References
    ----------
    .. [1] GUDHI, ``gudhi.bottleneck_distance`` (the same conventions for points at
       infinity); Notes §23.2 (shape classification).

    Examples
    --------
    >>> bottleneck_distance([[0.0, 2.0]], [[0.0, 2.5]])
    0.5
    >>> bottleneck_distance([[0.0, 2.0]], [])      # to the diagonal: half the persistence
    1.0
    >>> bottleneck_distance([[-np.inf, 1.0], [0.0, np.inf]], [[-np.inf, 1.5], [0.2, np.inf]])
    0.5
    """
    A, B = _diagram(D1, "D1"), _diagram(D2, "D2")
    A, B, scale = _rescale(A, B)
    sa, sb = _split(A), _split(B)
    fa, fb = sa[0], sb[0]
    ess = _essential(A, B, sa, sb)
    if ess is None:
        return DiagramMatching(np.inf, np.zeros((0, 2), dtype=np.int64)) if matching else float("inf")
    ess_pairs, ess_cost = ess
    P, Q = A[fa], B[fb]
    n, m = len(P), len(Q)
    best, pairs = 0.0, []
    if n + m:
        PQ, hp, hq = _costs(P, Q)
        # every point is matched at a cost at least its cheapest option (lower bound), and
        # matching everything to the diagonal is always possible (upper bound)
        low = max(
            np.minimum(hp, PQ.min(axis=1)).max() if n and m else (hp.max() if n else 0.0),
            np.minimum(hq, PQ.min(axis=0)).max() if n and m else (hq.max() if m else 0.0),
        )
        high = max(hp.max() if n else 0.0, hq.max() if m else 0.0)
        flat = PQ.ravel()
        edges = np.flatnonzero(flat <= high)
        edges = edges[np.argsort(flat[edges], kind="stable")]
        edge_cost = flat[edges]
        cand = edge_cost[np.searchsorted(edge_cost, low) :]
        cand = np.unique(np.concatenate([cand, hp[(hp >= low) & (hp <= high)], hq[(hq >= low) & (hq <= high)], [high]]))

        def cover(delta):
            k = np.searchsorted(edge_cost, delta, side="right")  # the edges of cost <= delta
            ii, jj = np.divmod(edges[:k], m) if m else (np.zeros(0, np.int64), np.zeros(0, np.int64))
            return _cover(n, m, ii, jj, hp > delta, hq > delta)

        lo, hi = 0, len(cand) - 1  # the largest candidate is always feasible
        while lo < hi:
            mid = (lo + hi) // 2
            if cover(cand[mid]) is not None:
                hi = mid
            else:
                lo = mid + 1
        best = float(cand[lo])
        if matching:
            matched = cover(cand[lo])
            in_p = {i for i, _ in matched}
            in_q = {j for _, j in matched}
            pairs = [(int(fa[i]), int(fb[j])) for i, j in matched]
            pairs += [(int(fa[i]), -1) for i in range(n) if i not in in_p]
            pairs += [(-1, int(fb[j])) for j in range(m) if j not in in_q]
    dist = max(best, float(ess_cost.max()) if len(ess_cost) else 0.0) * scale
    if not matching:
        return dist
    pairs += [tuple(map(int, p)) for p in ess_pairs]
    return DiagramMatching(dist, np.array(pairs, dtype=np.int64).reshape(-1, 2))


def wasserstein_distance(
    D1: ArrayLike, D2: ArrayLike, p: float = 2, *, internal_p: float = np.inf, matching: bool = False
) -> float | DiagramMatching:
    """The p-Wasserstein distance between two persistence diagrams, exact.

    :math:`W_p = \\min_\\pi (\\sum \\lVert x - \\pi(x)\\rVert_q^p)^{1/p}` over the
    matchings :math:`\\pi` of the points of both diagrams to each other or to the
    diagonal, with the :math:`L_q` norm of the plane, :math:`q` = ``internal_p``, as the
    ground metric (Notes §23.2, shape classification).

    Parameters
    ----------
    D1, D2 : array_like, shape (n, 2) and (m, 2)
        ``(birth, death)`` pairs; births may be ``-inf`` and deaths ``+inf`` (see the
        module docstring); either may be empty.
    p : int or float
        The order, ``1 <= p < inf`` (the bottleneck distance is ``p = inf``).
        Default 2 (GUDHI's default order is 1).
    internal_p : float
        The ground metric on the plane, the :math:`L_q` norm with ``q = internal_p``,
        ``1 <= q <= inf``.  Default ``inf`` (:math:`\\max(|b-b'|, |d-d'|)`), as GUDHI.
        A point goes to the diagonal at :math:`2^{1/q}\\,(d - b)/2`, its
        :math:`L_q` distance to its orthogonal projection.  Points at infinity are
        priced by their finite coordinate alone, whatever ``internal_p``.
    matching : bool
        Also return an optimal matching.

    Returns
    -------
    float, or DiagramMatching if ``matching``
        ``inf`` when the diagrams have different numbers of points at infinity of one
        kind; the matching is then empty.

    See Also
    --------
    bottleneck_distance, distance_matrix

    References
    ----------
    .. [1] GUDHI, ``gudhi.wasserstein.wasserstein_distance`` and
       ``gudhi.hera.wasserstein_distance`` (``order``, ``internal_p``, points at
       infinity), which the tests use as oracles.

    Examples
    --------
    >>> wasserstein_distance([[0.0, 2.0], [1.0, 3.0]], [[0.0, 2.0]], p=1)
    1.0
    >>> wasserstein_distance([[0.0, 3.0], [4.0, 8.0]], [], p=2, internal_p=1)  # GUDHI's test
    5.0
    """
    if isinstance(p, bool) or not isinstance(p, (int, float, np.integer, np.floating)):
        raise TypeError(f"p must be a number >= 1, got {type(p).__name__}")
    p = float(p)
    if not (p >= 1) or not np.isfinite(p):
        raise ValueError(f"p must be finite and >= 1 (use bottleneck_distance for p = inf), got {p}")
    if isinstance(internal_p, bool) or not isinstance(internal_p, (int, float, np.integer, np.floating)):
        raise TypeError(f"internal_p must be a number >= 1 or inf, got {type(internal_p).__name__}")
    q = float(internal_p)
    if not (q >= 1):
        raise ValueError(f"internal_p must be >= 1 (inf allowed), got {q}")
    A, B = _diagram(D1, "D1"), _diagram(D2, "D2")
    A, B, scale = _rescale(A, B)
    sa, sb = _split(A), _split(B)
    fa, fb = sa[0], sb[0]
    ess = _essential(A, B, sa, sb)
    if ess is None:
        return DiagramMatching(np.inf, np.zeros((0, 2), dtype=np.int64)) if matching else float("inf")
    ess_pairs, ess_cost = ess
    P, Q = A[fa], B[fb]
    n, m = len(P), len(Q)
    PQ, hp, hq = _costs(P, Q, q) if n + m else (np.zeros((0, 0)), np.zeros(0), np.zeros(0))
    # costs divided by the largest one before the p-th power: c^p neither overflows
    # (1e200^2, or 3^1000) nor underflows to a zero distance (1e-200^2)
    top = max((float(c.max()) for c in (PQ, hp, hq, ess_cost) if c.size), default=0.0)
    if top > 0.0:
        PQ, hp, hq, ess_cost = PQ / top, hp / top, hq / top, ess_cost / top
    rows, cols = np.zeros(0, int), np.zeros(0, int)
    used = ess_cost
    if n + m:
        rows, cols = _min_cost_matching(PQ, hp, hq, p)
        used = np.concatenate([ess_cost, _matched_costs((rows, cols), PQ, hp, hq)])
    # the matching's cost, again scaled by its own largest term (for a huge p the
    # matching problem's c^p may underflow; its value is still computed in full)
    cm = float(used.max()) if used.size else 0.0
    dist = cm * float(np.sum((used / cm) ** p)) ** (1.0 / p) * top * scale if cm > 0 else 0.0
    if not matching:
        return dist
    pairs = _pairs_from(rows, cols, fa, fb, n, m) + [tuple(map(int, e)) for e in ess_pairs]
    return DiagramMatching(dist, np.array(pairs, dtype=np.int64).reshape(-1, 2))


def distance_matrix(diagrams: Sequence[ArrayLike], *, p: float = np.inf) -> np.ndarray:
    """Pairwise distances between persistence diagrams: a family compared at once.

    Parameters
    ----------
    diagrams : sequence of array_like, each shape (n_i, 2)
        ``(birth, death)`` pairs, one diagram per shape (one homology dimension).
    p : float
        ``inf`` (default) for :func:`bottleneck_distance`, else the order of
        :func:`wasserstein_distance`.

    Returns
    -------
    ndarray, shape (k, k)
        Symmetric, zero on the diagonal.

    See Also
    --------
    bottleneck_distance
        One pair.
    wasserstein_distance
        One pair.
    classical_mds
        Embeds the matrix in the plane.

    References
    ----------
    .. [1] D. Cohen-Steiner, H. Edelsbrunner and J. Harer, "Stability of persistence
           diagrams", *Discrete Comput. Geom.* 37:103-120, 2007.
           doi:10.1007/s00454-006-1276-5

    Examples
    --------
    >>> distance_matrix([[[0.0, 2.0]], [[0.0, 2.5]], []]).tolist()
    [[0.0, 0.5, 1.0], [0.5, 0.0, 1.25], [1.0, 1.25, 0.0]]
    """
    if isinstance(diagrams, np.ndarray) and diagrams.ndim == 2:
        raise TypeError("diagrams must be a sequence of diagrams, not one diagram")
    try:
        ds = [_diagram(D, f"diagrams[{i}]") for i, D in enumerate(diagrams)]
    except TypeError as e:
        if "diagrams[" in str(e):
            raise
        raise TypeError(f"diagrams must be a sequence of (n, 2) arrays, got {type(diagrams).__name__}") from e
    if isinstance(p, bool) or not isinstance(p, (int, float, np.integer, np.floating)):
        raise TypeError(f"p must be a number >= 1 or inf, got {type(p).__name__}")
    k = len(ds)
    out = np.zeros((k, k))
    for i in range(k):
        for j in range(i + 1, k):
            d = bottleneck_distance(ds[i], ds[j]) if p == np.inf else wasserstein_distance(ds[i], ds[j], p)
            out[i, j] = out[j, i] = d
    return out
