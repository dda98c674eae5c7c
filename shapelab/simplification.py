"""Topological simplification by persistence, for functions on a curve.

Notes §23.1 end with *topological simplification*: keep the features that persist and
drop the others.  Lesson 11 does this with a threshold on the persistence diagram.
Edelsbrunner, Letscher and Zomorodian (2002) mean more: a *simplification* is a new
**function** ``g`` close to ``f`` whose critical points are exactly the persistent ones.
On a curve (a path or a closed polygon, as in §23.2's critical points of
:math:`F(x) = |x - S|`) this is short enough to do exactly:

1. pair the minima and maxima of ``f`` by the elder rule (sublevel-set persistence in
   dimension 0; on a closed curve the global minimum and the global maximum stay
   unpaired, the essential classes of :math:`H_0` and :math:`H_1` of the circle);
2. cancel the pairs of persistence below ``epsilon``, the least persistent first: an
   adjacent minimum–maximum pair ``(m, M)`` between a higher maximum ``A`` and a lower
   minimum ``B`` is flattened at the level :math:`c = (f(m) + f(M))/2`, and the stretch
   from ``A`` to ``B`` clamped to be monotone.

Every value moves by at most half the persistence of a cancelled pair, so
:math:`\\|g - f\\|_\\infty \\le \\varepsilon / 2`, and the persistence pairs of ``g`` are
exactly those of ``f`` with persistence at least ``epsilon``, at the same values.  (On
surfaces the same statement holds with :math:`\\varepsilon` in place of
:math:`\\varepsilon / 2` but needs far more machinery; this module stays on curves.)

Ties between equal values are broken by the index along the curve (simulation of
simplicity), so the pairing, and hence the result, does not depend on the platform.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ._toolkit.unionfind import elder_merges
from ._toolkit.validate import as_finite_scalar
from ._toolkit.validate import as_float_array as _as_float_array

__all__ = ["CurvePersistence", "Simplification", "curve_persistence", "simplify"]


@dataclass(frozen=True, eq=False)
class CurvePersistence:
    """Sublevel-set persistence of a function sampled along a curve.

    Attributes
    ----------
    pairs : ndarray, shape (k, 2), int
        ``(minimum, maximum)`` vertex indices of the finite pairs, in order of
        increasing persistence (ties by index).
    birth, death : ndarray, shape (k,)
        ``f`` at the minimum and at the maximum of each pair.
    essential_min : int
        Index of the global minimum (its class of :math:`H_0` never dies).
    essential_max : int or None
        On a closed curve, the index of the global maximum, where the loop closes (the
        class of :math:`H_1` born there never dies); None on an open path.
    closed : bool

    See Also
    --------
    curve_persistence
        Produces it.
    """

    pairs: np.ndarray
    birth: np.ndarray
    death: np.ndarray
    essential_min: int
    essential_max: int | None
    closed: bool

    @property
    def persistence(self) -> np.ndarray:
        """``death - birth`` of every finite pair."""
        return self.death - self.birth

    def diagram(self) -> np.ndarray:
        """The finite points ``(birth, death)`` as an array of shape (k, 2)."""
        return np.column_stack([self.birth, self.death])

    def __len__(self) -> int:
        return len(self.pairs)


@dataclass(frozen=True, eq=False)
class Simplification:
    """The result of :func:`simplify`.

    Attributes
    ----------
    values : ndarray
        The simplified function ``g`` at the same samples as ``f``.
    epsilon : float
        Pairs of persistence below this were cancelled.
    cancelled : ndarray, shape (c, 2), int
        The ``(minimum, maximum)`` pairs of ``f`` that ``g`` no longer has.
    kept : CurvePersistence
        The persistence of ``g``: the pairs of ``f`` with persistence ≥ ``epsilon``.
    error : float
        :math:`\\|g - f\\|_\\infty`, at most ``epsilon / 2``.

    See Also
    --------
    simplify
        Produces it.
    """

    values: np.ndarray
    epsilon: float
    cancelled: np.ndarray
    kept: CurvePersistence
    error: float


def _check_values(values, name: str = "values") -> np.ndarray:
    f = _as_float_array(values, name)
    if f.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of samples along the curve, got shape {f.shape}")
    if f.size < 2:
        raise ValueError(f"{name} must hold at least 2 samples, got {f.size}")
    if not np.all(np.isfinite(f)):
        raise ValueError(f"{name} must be finite (no NaN or inf)")
    return f


def _rank(f: np.ndarray) -> np.ndarray:
    """Strict total order of the samples: by value, ties by index."""
    order = np.lexsort((np.arange(f.size), f))
    rank = np.empty(f.size, dtype=np.int64)
    rank[order] = np.arange(f.size)
    return rank


def _critical(rank: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the local minima and maxima of a strictly ordered sequence."""
    n = rank.size
    idx = np.arange(n)
    if closed:
        left, right = rank[(idx - 1) % n], rank[(idx + 1) % n]
    else:
        big = np.iinfo(np.int64).max
        left = np.r_[big, rank[:-1]]
        right = np.r_[rank[1:], big]
        lo_mins = (rank < left) & (rank < right)
        left_max = np.r_[-1, rank[:-1]]
        right_max = np.r_[rank[1:], -1]
        lo_maxs = (rank > left_max) & (rank > right_max)
        return idx[lo_mins], idx[lo_maxs]
    return idx[(rank < left) & (rank < right)], idx[(rank > left) & (rank > right)]


def curve_persistence(values: npt.ArrayLike, *, closed: bool = True) -> CurvePersistence:
    """Persistence of the sublevel sets of ``f`` along a path or a closed curve.

    Parameters
    ----------
    values : array_like, shape (n,)
        ``f`` at the vertices of the curve, in order (a closed curve does not repeat its
        first vertex), e.g. from :func:`shapelab.critical.distance_along`.
    closed : bool
        True for a closed curve (vertex ``n - 1`` is joined to vertex 0).

    Returns
    -------
    CurvePersistence

    See Also
    --------
    simplify
        Removes the pairs of small persistence.
    critical_points
        The critical points of a distance function.

    Notes
    -----
    The piecewise-linear function on the path or cycle graph, filtered by sublevel
    sets (lower-star filtration): components are born at minima and die at maxima,
    where the younger of the two merging components dies (the elder rule, notes §23.1
    and lesson 11).  Union–find over the vertices in increasing order, O(n log n).

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher and A. Zomorodian, "Topological persistence and
           simplification", *Discrete Comput. Geom.* 28:511-533, 2002.
           doi:10.1007/s00454-002-2885-2
    .. [2] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> P = curve_persistence([0.0, 3.0, 1.0, 2.0, -1.0, 4.0], closed=False)
    >>> P.diagram().tolist()
    [[1.0, 2.0], [0.0, 3.0]]
    """
    f = _check_values(values)
    closed = bool(closed)
    n = f.size
    rank = _rank(f)
    order = np.argsort(rank)
    # the lower-star filtration: vertex v enters at its rank, with the edges to its
    # neighbours already in (lower rank), left neighbour first
    later = np.repeat(order, 2)
    nbr = later + np.tile([-1, 1], n)
    if closed:
        nbr %= n
    inside = (nbr >= 0) & (nbr < n)
    later, nbr = later[inside], nbr[inside]
    keep = (nbr != later) & (rank[nbr] < rank[later])
    later, nbr = later[keep], nbr[keep]

    pairs = []

    def merged(e, elder, younger, oldest):
        # the younger component, born at its minimum, dies at the vertex that joins it
        # to the elder one (a vertex merging into its own component is no pair)
        if oldest[younger] != later[e]:
            pairs.append((oldest[younger], int(later[e])))

    elder_merges(n, later, nbr, np.arange(later.size), rank.tolist(), merged)
    last = int(order[-1]) if n else None
    essential_min = int(order[0])
    essential_max = int(last) if closed else None
    if pairs:
        P = np.array(pairs, dtype=np.int64)
        pers = f[P[:, 1]] - f[P[:, 0]]
        keep = np.lexsort((P[:, 0], pers))
        P = P[keep]
    else:
        P = np.empty((0, 2), dtype=np.int64)
    return CurvePersistence(P, f[P[:, 0]].copy(), f[P[:, 1]].copy(), essential_min, essential_max, closed)


def simplify(values: npt.ArrayLike, epsilon: float, *, closed: bool = True) -> Simplification:
    """ε-simplification of a function along a curve (Edelsbrunner, Letscher and
    Zomorodian 2002): the nearby function with only the persistent critical points.

    Parameters
    ----------
    values : array_like, shape (n,)
        ``f`` at the vertices of the curve, in order.
    epsilon : float
        Cancel every minimum–maximum pair of persistence ``< epsilon`` (≥ 0).
    closed : bool
        True for a closed curve.

    Returns
    -------
    Simplification
        ``g`` with :math:`\\|g - f\\|_\\infty \\le \\varepsilon/2` whose persistence pairs
        are exactly those of ``f`` with persistence ≥ ``epsilon``, at the same values.
        ``g`` may have flat stretches (where a pair was cancelled); a flat stretch is no
        critical point.

    See Also
    --------
    curve_persistence
        The pairs it cancels.

    Notes
    -----
    The least persistent pair is always a pair of *adjacent* critical points ``m, M``
    of the alternating sequence of minima and maxima, between a maximum ``A`` with
    :math:`f(A) \\ge f(M)` and a minimum ``B`` with :math:`f(B) \\le f(m)`.  Cancelling
    it sets :math:`c = (f(m) + f(M))/2` and makes ``f`` monotone from ``A`` to ``B``:
    values between ``A`` and ``m`` below ``c`` are raised to ``c``, values between ``M``
    and ``B`` above ``c`` lowered to ``c``, values between ``m`` and ``M`` set to ``c``.
    Only values strictly between ``A`` and ``B`` change, by at most half the
    persistence; the sequence of critical points loses ``m`` and ``M`` and stays
    alternating, so the next cancellation is of the same kind.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher and A. Zomorodian, "Topological persistence and
           simplification", *Discrete Comput. Geom.* 28:511-533, 2002.
           doi:10.1007/s00454-002-2885-2

    Examples
    --------
    >>> S = simplify([0.0, 3.0, 1.0, 2.0, -1.0, 4.0], 1.5, closed=False)
    >>> S.values.tolist(), S.error
    ([0.0, 3.0, 1.5, 1.5, -1.0, 4.0], 0.5)
    """
    f = _check_values(values)
    eps = as_finite_scalar(epsilon, "epsilon", nonnegative=True)
    closed = bool(closed)
    n = f.size
    g = f.copy()
    rank = _rank(f)
    mins, maxs = _critical(rank, closed)
    is_min = np.zeros(n, bool)
    is_min[mins] = True
    seq = [int(i) for i in np.sort(np.r_[mins, maxs])]  # alternating, in order along the curve
    if closed:
        # the global minimum and maximum carry the essential classes: never cancelled
        protected = {int(np.argmin(rank)), int(np.argmax(rank))}
    else:
        # an end of a path that is a maximum joins one component and kills none: it takes
        # no part in a pair, and the sequence then starts and ends with a minimum
        seq = [i for i in seq if is_min[i] or 0 < i < n - 1]
        protected = set()
    cancelled = []
    while True:
        L = len(seq)
        best = None
        for k in range(L if closed else L - 1):
            i, j = seq[k], seq[(k + 1) % L]
            if i in protected or j in protected:
                continue
            m, M = (i, j) if is_min[i] else (j, i)
            p = f[M] - f[m]
            if p >= eps:
                continue
            key = (p, rank[M] - rank[m], min(i, j))
            if best is None or key < best[0]:
                best = (key, k)
        if best is None:
            break
        k = best[1]
        i, j = seq[k], seq[(k + 1) % L]
        m, M = (i, j) if is_min[i] else (j, i)
        c = 0.5 * (f[m] + f[M])
        prev = seq[k - 1] if (closed or k > 0) else None
        nxt = seq[(k + 2) % L] if (closed or k + 2 < L) else None
        walk = _arc(0 if prev is None else prev, n - 1 if nxt is None else nxt, n, closed)
        pos_i, pos_j = walk.index(i), walk.index(j)
        lo = 0 if prev is None else 1  # the neighbouring critical points keep their values
        hi = len(walk) if nxt is None else len(walk) - 1
        # along the walk: prev -> i -> j -> nxt; monotone overall once the pair is gone
        down = bool(is_min[i])  # max -> m -> M -> min: non-increasing; else non-decreasing
        for t in range(lo, hi):
            v = walk[t]
            if pos_i <= t <= pos_j:
                g[v] = c
            elif (t < pos_i) == down:
                g[v] = max(g[v], c)
            else:
                g[v] = min(g[v], c)
        cancelled.append((m, M))
        for t in sorted({k, (k + 1) % L}, reverse=True):
            del seq[t]
    kept = _kept_persistence(f, g, cancelled, closed)
    C = np.array(cancelled, dtype=np.int64).reshape(-1, 2)
    return Simplification(g, eps, C, kept, float(np.max(np.abs(g - f))))


def _arc(i: int, j: int, n: int, closed: bool) -> list:
    """Vertex indices from ``i`` to ``j`` inclusive, walking forward along the curve."""
    if i <= j:
        return list(range(i, j + 1))
    if not closed:
        raise ValueError("an open path is walked forward only")
    return list(range(i, n)) + list(range(0, j + 1))


def _kept_persistence(f, g, cancelled, closed) -> CurvePersistence:
    P = curve_persistence(f, closed=closed)
    gone = {tuple(map(int, p)) for p in cancelled}
    keep = np.array([tuple(map(int, p)) not in gone for p in P.pairs], dtype=bool)
    pairs = P.pairs[keep]
    return CurvePersistence(
        pairs, g[pairs[:, 0]].copy(), g[pairs[:, 1]].copy(), P.essential_min, P.essential_max, closed
    )
