"""The fast kernels behind :mod:`shapelab.hausdorff` (the engine, not required reading).

The algorithm
-------------
Computing ``h(A, B)`` needs, for the maximum only, the nearest-neighbour
distance of every ``a``; most points merely have to be shown *not* to beat the
running maximum ``cmax``, and a single point of B within ``cmax`` of ``a`` is a
proof.  The two classical algorithms each exploit half of this:

* a k-d tree finds every nearest neighbour, fast when the sets overlap, but a
  query from far away visits a large part of the tree (two unit spheres three
  units apart: ~30-800 µs per query);
* the early break of Taha & Hanbury (scipy) shuffles both sets once, then for
  each ``a`` scans B and stops at the first point within ``cmax``; the result is
  exact.  It is fast when the sets are apart, and slow, though not hopeless, when
  they overlap: ``cmax`` is then small, a typical ``a`` scans several per cent of
  B before meeting a point within it, and the work stays a sizeable fraction of
  ``n m`` (two overlapping noisy unit spheres, n = m = 500 to 16000: 9-22 % of
  ``n m`` distances, against 0.1-2.4 % when they are three units apart), not the
  near-linear average of scipy's documentation.

:func:`directed_hausdorff` first tries a cheap bound that tells the regimes apart,
then runs the algorithm suited to it:

0. *Coarse to fine (sets apart).*  Both sets are binned into a grid of about
   2048 cells.  A cell of A whose farthest corner is within ``cmax`` of some
   representative point of B is dropped whole; the points of the other cells
   are tested against the three representatives that bound their cell best
   (one exact distance each), and the cells of B too far from every survivor to
   hold its nearest neighbour are dropped too.  The survivors are binned again,
   finer, until brute force is cheap.  Apart, each level keeps a small part of
   both sets (two noisy unit spheres of 10⁶ points, three units apart: five
   levels, about 5·10⁶ box bounds and distances for H, against 1.1·10⁸
   distances for scipy's early break in both directions, and 4·10⁷ for the
   batched early break below), and no k-d tree, hence no
   ``import scipy.spatial``, is needed.  When the live cells hold
   nearly all of A (the maximum is below the cell size: the sets overlap) the
   first level gives up, having cost two passes over the data, and the steps
   below take over.
1. *Batched early break.*  All points of A are probed at once against a block
   of points of B taken in a fixed random order (one small matrix product per
   block), which gives each ``a`` an upper bound ``u(a)`` on its distance to B.
   The points with the largest ``u`` are evaluated exactly, which gives a lower
   bound ``cmax`` of ``h`` with its witness.  Every ``a`` with ``u(a) <= cmax``
   is eliminated.  The survivors are probed again with a block four times as
   large, and so on.  When the sets are apart this eliminates nearly everything
   after a handful of blocks.
2. *Small tree for clustered survivors.*  Survivors near the maximum cluster
   (the far side of two distant sets); only the points of B within
   ``max sqrt(u)`` of their bounding ball can be their nearest neighbours, a
   small part of B: a k-d tree of that part finishes them exactly.
3. *Bounded k-d tree.*  As soon as a block eliminates less than half of the
   survivors (the sets overlap, so random probes are useless), the survivors
   switch to a k-d tree of B, queried in the spatial order of A (about 3x
   faster than a random order: fewer cache misses).  Only one point in eight
   is queried first; its neighbour serves as a probe for its spatial
   neighbours, which eliminates most of the others; the remaining ones are
   queried with ``distance_upper_bound`` equal to their own upper bound,
   largest first, so that ``cmax`` rises early and most are eliminated before
   they are queried.

For :func:`hausdorff` the second direction starts with ``cmax = h(A, B)``
already known, which usually eliminates almost all of it in the first block.

Exactness: every elimination compares a *rigorous* upper bound (the round-off
of the matrix-product form is bounded and added) with an exact distance, and
every reported distance is recomputed by the direct formula
``sqrt(sum((a - b)**2))``, so the result equals brute force to the last bit
and the witness pair is valid.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .._toolkit import tolerances as tol
from .._toolkit.geometry import kdtree

if TYPE_CHECKING:  # the tree is built by _toolkit.geometry.kdtree, imported on first use
    from scipy.spatial import cKDTree

__all__ = ["METHODS", "directed"]

_EPS = np.finfo(np.float64).eps
#: Problems with at most this many point pairs are solved by brute force.
_BRUTE_PAIRS = 1 << 21
#: Elements of a distance block (rows x columns) computed at once; fits in cache.
_BLOCK = 1 << 16
#: Group size in the k-d tree stage (one query serves a group of neighbours).
_GROUP = 8
#: Cells per grid of the coarse-to-fine stage (each level bins both point sets).
_GRID_CELLS = 2048
#: Point pairs below which the coarse-to-fine stage finishes by brute force.
_LEAF_PAIRS = 1 << 20


# --------------------------------------------------------------------------- #
# Internal machinery                                                           #
# --------------------------------------------------------------------------- #
def _sqdist(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The direct formula ``sum((a - b)**2)`` along the last axis, summed in
    coordinate order (as scipy and a plain loop do): the reference every
    reported distance is computed with."""
    diff = np.asarray(a - b)
    out = diff[..., 0] * diff[..., 0]
    for k in range(1, diff.shape[-1]):
        out = out + diff[..., k] * diff[..., k]
    return out


class _Cloud:
    """One point set prepared for distance blocks and k-d tree queries.

    With ``c`` a common centre, ``leftT`` holds the columns ``[x - c, 1]`` and
    ``rightT`` the columns ``[-2 (y - c), |y - c|^2]``, so that
    ``left_i . right_j = |x_i - y_j|^2 - |x_i - c|^2``: a block of squared
    distances is one small matrix product plus a row constant.  Both are stored
    transposed, (d + 1, n), so that reductions run along contiguous rows.
    """

    def __init__(self, points: np.ndarray, center: np.ndarray):
        self.points = points
        self.center = center
        n, d = points.shape
        self.leftT = np.empty((d + 1, n))
        xcT = self.leftT[:d]
        np.subtract(points.T, center[:, None], out=xcT)
        self.leftT[d] = 1.0
        self.sq = xcT[0] * xcT[0]
        for k in range(1, d):
            self.sq += xcT[k] * xcT[k]
        self.sqmax = float(self.sq.max())
        self.rightT = np.empty((d + 1, n))
        np.multiply(xcT, -2.0, out=self.rightT[:d])
        self.rightT[d] = self.sq
        self._tree = None
        self._rank = None

    @property
    def tree(self) -> cKDTree:
        if self._tree is None:
            # The sliding-midpoint tree builds 2-3x faster than the balanced one
            # and answers queries on sampled surfaces as fast or faster.
            self._tree = kdtree(self.points, balanced_tree=False, compact_nodes=False)
        return self._tree

    @property
    def rank(self) -> np.ndarray:
        """Position of each point in the k-d tree's (spatially coherent) order."""
        if self._rank is None:
            idx = self.tree.indices
            self._rank = np.empty(idx.size, dtype=np.intp)
            self._rank[idx] = np.arange(idx.size)
        return self._rank


def _prepare(A: np.ndarray, B: np.ndarray) -> tuple[_Cloud, _Cloud]:
    # A common centre near the data keeps the matrix-product form accurate (the
    # round-off margin scales with the squared radius about it).  Any centre is
    # correct; the bounding box of a subsample is cheap and good enough.
    sub = np.vstack([A[:: max(1, A.shape[0] // 2048)], B[:: max(1, B.shape[0] // 2048)]])
    center = 0.5 * (sub.min(axis=0) + sub.max(axis=0))
    return _Cloud(A, center), _Cloud(B, center)


class _Best:
    """The running maximum (squared) with its witness pair."""

    __slots__ = ("d2", "i", "j")

    def __init__(self, floor2: float = -1.0):
        self.d2, self.i, self.j = floor2, -1, -1

    def offer(self, d2: np.ndarray, rows: np.ndarray, cols: np.ndarray) -> None:
        if d2.size:
            k = int(np.argmax(d2))
            if d2[k] > self.d2:
                self.d2, self.i, self.j = float(d2[k]), int(rows[k]), int(cols[k])


def _margin(src: _Cloud, dst: _Cloud) -> float:
    """A rigorous bound on the round-off of one entry of ``left @ right.T + sq``."""
    d = src.points.shape[1]
    return 8.0 * (d + 4) * _EPS * (src.sqmax + dst.sqmax) + tol.UNDERFLOW_FLOOR


def _upper(raw: np.ndarray, rows_sq: np.ndarray, margin: float, d: int) -> np.ndarray:
    """Turn block minima (``min_j left_i . right_j``) into rigorous upper bounds of
    the direct-formula squared distance."""
    return (raw + rows_sq) * (1.0 + 4.0 * (d + 2) * _EPS) + margin


def _block_min(src: _Cloud, rows: np.ndarray, dst: _Cloud, cols: np.ndarray) -> np.ndarray:
    """For each of ``rows``: ``min_j left_row . right_j`` over ``cols`` (the probes),
    block by block: ``(k, d+1) @ (d+1, rows)`` then a minimum down the columns."""
    L = src.leftT if rows.size == src.points.shape[0] else src.leftT[:, rows]  # rows: sorted, unique
    R = np.ascontiguousarray(dst.rightT[:, cols].T)
    out = np.empty(rows.size)
    step = max(256, _BLOCK // max(1, cols.size))
    for s in range(0, rows.size, step):
        np.min(R @ L[:, s : s + step], axis=0, out=out[s : s + step])
    return out


def _exact_rows(src: _Cloud, rows: np.ndarray, dst: _Cloud) -> tuple[np.ndarray, np.ndarray]:
    """Exact nearest neighbours (direct formula) of ``src[rows]`` in ``dst`` by brute force.

    The matrix-product form finds, for each row, every column within twice the
    round-off margin of the row minimum; those few candidates are re-evaluated
    with the direct formula, so the result is the brute-force minimum exactly.
    """
    rows = np.asarray(rows, dtype=np.intp)
    d2 = np.empty(rows.size)
    nn = np.empty(rows.size, dtype=np.intp)
    if rows.size == 0:
        return d2, nn
    m = dst.points.shape[0]
    margin = 2.0 * _margin(src, dst) + 8.0 * (src.points.shape[1] + 2) * _EPS * (src.sqmax + dst.sqmax)
    R = dst.rightT
    step = max(1, _BLOCK // m)
    for s in range(0, rows.size, step):
        r = rows[s : s + step]
        D = src.leftT[:, r].T @ R
        mn = D.min(axis=1)
        ri, cj = np.nonzero(D <= (mn + margin)[:, None])
        exact = _sqdist(src.points[r[ri]], dst.points[cj])
        # per row: the smallest exact value, the smallest index among ties
        order = np.lexsort((cj, exact, ri))
        first = np.ones(order.size, dtype=bool)
        first[1:] = ri[order[1:]] != ri[order[:-1]]
        pick = order[first]
        d2[s : s + step] = exact[pick]
        nn[s : s + step] = cj[pick]
    return d2, nn


def _directed_brute(src: _Cloud, dst: _Cloud, best: _Best) -> _Best:
    rows = np.arange(src.points.shape[0])
    d2, nn = _exact_rows(src, rows, dst)
    best.offer(d2, rows, nn)
    return best


def _workers(n_queries: int) -> int:
    """Threads for a k-d tree query: starting threads costs more than small batches."""
    return -1 if n_queries >= 8192 else 1


def _refine_tree(
    src: _Cloud,
    rows: np.ndarray,
    d2: np.ndarray,
    nn: np.ndarray,
    points: np.ndarray,
    tree: cKDTree,
    index: np.ndarray | None = None,
):
    """Make k-d tree answers bit-exact.

    The tree's own distances may differ from the direct formula in the last bit,
    so for each row every point of the tree within ``sqrt(d2) (1 + 1e-12)`` is
    re-evaluated with the direct formula (usually one point).  ``index`` maps the
    tree's points to indices of the destination set when the tree holds a subset.
    """
    out_d2, out_nn = d2.copy(), nn.copy()
    for t, (i, v) in enumerate(zip(rows, d2)):
        r = np.sqrt(v) * (1.0 + tol.DISTANCE_TIE_REL) + tol.UNDERFLOW_FLOOR
        cand = np.asarray(tree.query_ball_point(src.points[i], r), dtype=np.intp)
        if cand.size:
            e = _sqdist(src.points[i], points[cand])
            glob = cand if index is None else index[cand]
            k = np.lexsort((glob, e))[0]
            out_d2[t], out_nn[t] = e[k], glob[k]
    return out_d2, out_nn


def _query_exact(
    src: _Cloud,
    rows: np.ndarray,
    ub: np.ndarray,
    points: np.ndarray,
    tree: cKDTree,
    index: np.ndarray | None,
    best: _Best,
) -> None:
    """Exact nearest neighbours of ``src[rows]`` (each within ``sqrt(ub)``) in a
    tree over ``points``; offer the results to ``best``."""
    bound = float(np.sqrt(ub.max())) * (1.0 + tol.DISTANCE_REACH_REL) + tol.UNDERFLOW_FLOOR
    dist, j = tree.query(src.points[rows], k=1, workers=_workers(rows.size), distance_upper_bound=bound)
    j = np.asarray(j, dtype=np.intp)
    bad = ~np.isfinite(dist)
    if bad.any():  # cannot happen (ub is a valid bound); stay safe anyway
        _, j2 = tree.query(src.points[rows[bad]], k=1)
        j[bad] = j2
    d2 = _sqdist(src.points[rows], points[j])
    # only the largest value matters: refine the rows that may tie with it
    hi = d2 >= max(best.d2, float(d2.max())) * (1.0 - tol.DISTANCE_TIE_REL)
    if hi.any():
        d2h, jh = _refine_tree(src, rows[hi], d2[hi], j[hi], points, tree, index)
        best.offer(d2h, rows[hi], jh)


def _subset_stage(src: _Cloud, alive: np.ndarray, u: np.ndarray, dst: _Cloud, best: _Best, force: bool = False) -> bool:
    """Finish a *clustered* set of survivors with a small tree.

    Every survivor ``a`` has its nearest neighbour within ``sqrt(u(a))``, so only
    the points of ``dst`` in the ball around the survivors' bounding ball matter.
    When the survivors cluster (the far side of two distant sets) this is a small
    part of ``dst``.  Returns False (doing nothing) when the ball holds more than
    a quarter of ``dst``.
    """
    P = src.points[alive]
    center = 0.5 * (P.min(axis=0) + P.max(axis=0))
    radius = float(np.sqrt(_sqdist(P, center).max()))
    reach = radius + float(np.sqrt(u[alive].max()))
    reach = reach * (1.0 + tol.DISTANCE_REACH_REL) + tol.UNDERFLOW_FLOOR
    # |b - center|^2 from the prepared columns in one pass: with e = center - c,
    # |b - c|^2 - 2 (b - c).e + |e|^2; the round-off margin keeps it a superset
    e = center - dst.center
    ee = float(e @ e)
    d2c = np.r_[e, 1.0] @ dst.rightT + ee
    slack = 8.0 * (e.size + 4) * _EPS * (dst.sqmax + ee) + tol.UNDERFLOW_FLOOR
    inside = np.flatnonzero(d2c <= reach * reach + slack)
    if inside.size > dst.points.shape[0] // 4 and not force:
        return False
    if inside.size == 0:  # impossible: every survivor has a neighbour inside
        return False
    pts = dst.points[inside]
    tree = kdtree(pts, balanced_tree=False, compact_nodes=False)
    order = np.argsort(-u[alive], kind="stable")
    rows, ub = alive[order], u[alive][order]
    pos, batch = 0, 64
    while pos < rows.size:
        r, b = rows[pos : pos + batch], ub[pos : pos + batch]
        sel = b > best.d2
        if sel.any():
            _query_exact(src, r[sel], b[sel], pts, tree, inside, best)
        pos += batch
        batch *= 4
    return True


def _tree_stage(src: _Cloud, alive: np.ndarray, u: np.ndarray, dst: _Cloud, best: _Best) -> _Best:
    """Finish ``alive`` (with upper bounds ``u``) with the k-d tree of ``dst``."""
    tree = dst.tree
    if alive.size > src.points.shape[0] // 8:  # spatial order without sorting
        mask = np.zeros(src.points.shape[0], dtype=bool)
        mask[alive] = True
        idx = src.tree.indices
        S = idx[mask[idx]]
    else:
        S = alive[np.argsort(src.rank[alive], kind="stable")]
    uS = u[S]
    reps_pos = np.arange(0, S.size, _GROUP)
    reps = S[reps_pos]
    _, jr = tree.query(src.points[reps], k=1, workers=_workers(reps.size))
    jr = np.asarray(jr, dtype=np.intp)
    dr2 = _sqdist(src.points[reps], dst.points[jr])
    # A representative's value is exact (up to ties): a valid lower bound of h.
    top = int(np.argmax(dr2))
    if dr2[top] > best.d2:
        e2, ej = _refine_tree(src, reps[top : top + 1], dr2[top : top + 1], jr[top : top + 1], dst.points, tree)
        best.offer(e2, reps[top : top + 1], ej)
    # Each point tries the neighbours of the representatives of its own group and
    # of the two adjacent groups (second-order tight for smooth sets).  Groups are
    # consecutive, so the candidates are three shifted copies of ``repeat(jr)``.
    PT = np.ascontiguousarray(src.points[S].T)
    QT = np.ascontiguousarray(dst.points[jr].T)
    ng = reps.size
    for off in (0, -1, 1):
        sel = np.clip(np.arange(ng) + off, 0, ng - 1)
        C = np.repeat(QT[:, sel], _GROUP, axis=1)[:, : S.size]
        diff = PT[0] - C[0]
        cand = diff * diff
        for k in range(1, PT.shape[0]):
            diff = PT[k] - C[k]
            cand += diff * diff
        np.minimum(uS, cand, out=uS)
    keep = uS > best.d2
    keep[reps_pos] = dr2 > best.d2  # representatives are known exactly
    S, uS = S[keep], uS[keep]
    if S.size == 0:
        return best
    order = np.argsort(-uS, kind="stable")
    S, uS = S[order], uS[order]
    pos, batch = 0, 256
    while pos < S.size:
        rows, ub = S[pos : pos + batch], uS[pos : pos + batch]
        sel = ub > best.d2
        if sel.any():
            _query_exact(src, rows[sel], ub[sel], dst.points, tree, None, best)
        pos += batch
        batch *= 2
    return best


def _directed_pruned(src: _Cloud, dst: _Cloud, best: _Best, seed: int = 0, stage: str | None = None) -> _Best:
    """Batched early break, switching to a bounded k-d tree when the sets overlap
    (see the module docstring).

    ``stage`` forces a path after the first block, for tests on small inputs:
    ``"tree"``, ``"subset"``, or ``"probe"`` (blocks until every point of dst was
    a probe).
    """
    n, d = src.points.shape
    m = dst.points.shape[0]
    margin = _margin(src, dst)
    perm = np.random.default_rng(seed).permutation(m)
    alive = np.arange(n)
    u = np.full(n, np.inf)
    used = 0
    k = 8
    first = True
    while alive.size:
        if stage is None and (alive.size <= 16 or alive.size * (m - used) <= 2 * _BLOCK):
            rest = alive[u[alive] > best.d2]
            d2, nn = _exact_rows(src, rest, dst)
            best.offer(d2, rest, nn)
            break
        probes = perm[used : used + k]
        used += probes.size
        raw = _block_min(src, alive, dst, probes)
        full = alive.size == n  # alive is sorted and unique: all rows, skip the gathers
        if full:
            u = np.minimum(u, _upper(raw, src.sq, margin, d))
            ua = u
        else:
            ua = np.minimum(u[alive], _upper(raw, src.sq[alive], margin, d))
            u[alive] = ua
        before = alive.size
        # Exact value of the most promising point(s): a lower bound with a
        # witness.  Costs one scan of dst, so only when a block costs as much.
        if first or alive.size * probes.size >= m:
            t = min(2 if first else 1, alive.size)
            top = alive[np.argpartition(-ua, t - 1)[:t]]
            d2, nn = _exact_rows(src, top, dst)
            best.offer(d2, top, nn)
            u[top] = -np.inf  # known exactly
            ua = u if full else u[alive]
            first = False
        alive = np.flatnonzero(ua > best.d2) if full else alive[ua > best.d2]
        if used >= m:  # every point of dst probed: u is the (rounded) distance
            d2, nn = _exact_rows(src, alive, dst)
            best.offer(d2, alive, nn)
            break
        # Blocks grow 4x: when the sets are apart the survivors then shrink about
        # 4x per block (a point at depth delta below cmax survives K probes with
        # probability ~exp(-c delta K)).  Much less means random probes cannot see
        # the nearest neighbours: the sets overlap and the k-d tree takes over.
        if stage == "tree":
            return _tree_stage(src, alive, u, dst, best) if alive.size else best
        if stage == "subset":
            if alive.size:
                _subset_stage(src, alive, u, dst, best, force=True)
            break
        slow = alive.size > 0.5 * before
        if (
            stage is None
            and 0 < alive.size <= min(65536, n // 4 + 4096)
            and (slow or alive.size <= 4096)
            and _subset_stage(src, alive, u, dst, best)
        ):
            break
        if stage is None and slow and alive.size > 64:
            return _tree_stage(src, alive, u, dst, best)
        k = min(m - used, 4 * k)
    return best


# --------------------------------------------------------------------------- #
# Coarse-to-fine stage: cells bound whole groups of points                     #
# --------------------------------------------------------------------------- #
def _colmin_max(P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Column minima and maxima of a C-ordered (n, d) array, fast: reducing axis 0
    directly walks the array with a stride of d and is ~10x slower."""
    n, d = P.shape
    k = (n // 64) * 64
    lo, hi = [], []
    if k:
        H = P[:k].reshape(-1, 64 * d)
        lo.append(H.min(axis=0).reshape(64, d).min(axis=0))
        hi.append(H.max(axis=0).reshape(64, d).max(axis=0))
    if k < n:
        lo.append(P[k:].min(axis=0))
        hi.append(P[k:].max(axis=0))
    return np.min(lo, axis=0), np.max(hi, axis=0)


class _Grid:
    """A point set binned into a uniform grid of about ``_GRID_CELLS`` cells over its
    bounding box.

    Each occupied cell is described by a box (centre ``center``, half-widths
    ``half``) that provably contains its points: the boxes are widened by a
    round-off allowance on the coordinates' magnitude.  ``rep`` holds one point of
    each occupied cell (its largest index) and ``cell`` the occupied-cell number
    of every point.
    """

    __slots__ = ("points", "center", "half", "rep", "cell")

    def __init__(self, points: np.ndarray, cells: int = _GRID_CELLS):
        n, d = points.shape
        lo, hi = _colmin_max(points)
        ext = hi - lo
        # cells per axis proportional to the extent (an axis of zero extent gets one)
        pos = ext > 0
        g = np.ones(d, dtype=np.int64)
        if pos.any():
            k = int(pos.sum())
            vol = float(np.prod(ext[pos] / ext[pos].max()))
            side = (cells / vol) ** (1.0 / k) / ext[pos].max()
            g[pos] = np.clip(np.floor(ext[pos] * side), 1, 1 << 20).astype(np.int64)
            while float(np.prod(g.astype(float))) > 4.0 * cells:  # elongated boxes: cap the total
                g = np.maximum(1, g // 2)
        width = np.where(pos, ext / g, 1.0)
        inv = 1.0 / width
        top = (g - 1).astype(float)
        strides = np.ones(d)
        for k in range(d - 2, -1, -1):
            strides[k] = strides[k + 1] * g[k + 1]
        # cell numbers in chunks that stay in cache (large temporaries cost page faults)
        key = np.empty(n, dtype=np.intp)
        step = 1 << 15
        buf = np.empty((min(step, n), d))
        for s in range(0, n, step):
            b = buf[: min(step, n - s)]
            np.subtract(points[s : s + step], lo, out=b)  # >= 0: lo is the minimum
            np.multiply(b, inv, out=b)
            np.floor(b, out=b)
            np.minimum(b, top, out=b)
            key[s : s + step] = b @ strides  # integers below 2**53: exact
        total = int(np.prod(g))
        occ_mask = np.zeros(total, dtype=bool)
        occ_mask[key] = True
        occ = np.flatnonzero(occ_mask)
        number = np.empty(total, dtype=np.intp)
        number[occ] = np.arange(occ.size)
        self.cell = number[key]
        rep = np.empty(occ.size, dtype=np.intp)
        rep[self.cell] = np.arange(n)  # the last write wins: some point of each cell
        self.rep = rep
        idx = np.array(np.unravel_index(occ, tuple(int(x) for x in g))).T.reshape(-1, d)  # (cells, d)
        # Rigorous boxes: the cell number of a point is off by at most a few units in
        # the last place of (p - lo) / width, and the corners lo + c * width are
        # rounded too; both are covered by widening with ``slack``.
        slack = 16.0 * _EPS * (np.abs(lo) + np.abs(hi) + ext) + tol.UNDERFLOW_FLOOR
        lo_box = lo + idx * width
        hi_box = lo + (idx + 1) * width
        self.center = 0.5 * (lo_box + hi_box)
        self.half = 0.5 * (hi_box - lo_box) + 2.0 * slack
        self.points = points


#: Relative allowance for the round-off of box bounds (far above the few ulps needed).
_REL = tol.DISTANCE_BOX_REL
#: Representative points of D tried against every point of a live cell of S.
_PROBES = 3


def _cell_pairs(gS: _Grid, gD: _Grid, rows: np.ndarray | None = None, probes: int = 0):
    """Bounds between occupied cells X of ``gS`` (all, or ``rows``) and the cells of ``gD``.

    With ``probes`` > 0, returns ``ub2``: for each X, a rigorous upper bound of
    ``min_b |a - b|^2`` over every ``a`` in X (the farthest corner of X from a
    representative point of ``gD``), and the ``probes`` cells of ``gD`` whose
    representatives gave the smallest bounds.  With ``probes`` = 0, returns the
    matrix of squared distances between the boxes (lower bounds), one row per X.
    """
    cX, hX = gS.center, gS.half
    if rows is not None:
        cX, hX = cX[rows], hX[rows]
    nX, nY = cX.shape[0], gD.center.shape[0]
    if probes:
        Y, hY = gD.points[gD.rep], None
        ub2 = np.empty(nX)
        near = np.empty((nX, min(probes, nY)), dtype=np.intp)
    else:
        Y, hY = gD.center, gD.half
        out = np.empty((nX, nY))
    step = max(1, (1 << 16) // nY)
    t = np.empty((min(step, nX), nY))
    for s in range(0, nX, step):
        cx, hx = cX[s : s + step], hX[s : s + step]
        tt = t[: cx.shape[0]]
        M = np.zeros((cx.shape[0], nY)) if probes else out[s : s + step]
        if not probes:
            M[...] = 0.0
        for k in range(cX.shape[1]):
            np.subtract(Y[None, :, k], cx[:, None, k], out=tt)
            np.abs(tt, out=tt)
            if probes:  # farthest corner of the box from the point
                tt += hx[:, None, k]
            else:  # gap between the boxes
                tt -= hx[:, None, k]
                tt -= hY[None, :, k]
                np.maximum(tt, 0.0, out=tt)
            tt *= tt
            M += tt
        if probes:
            M.min(axis=1, out=ub2[s : s + step])
            q = near.shape[1]
            near[s : s + step] = np.argpartition(M, q - 1, axis=1)[:, :q] if q < nY else np.arange(nY)
    if probes:
        return ub2 * (1.0 + _REL) + tol.UNDERFLOW_FLOOR, near
    out *= 1.0 - _REL
    return out


def _nearest_exact(p: np.ndarray, D: np.ndarray, idx: np.ndarray | None = None) -> tuple[float, int]:
    """The direct-formula nearest neighbour of one point in ``D`` (or in ``D[idx]``,
    ``idx`` increasing and holding every nearest neighbour): its squared distance
    and index in D, the smallest among ties."""
    d2 = _sqdist(D if idx is None else D[idx], p)
    j = int(np.argmin(d2))
    return float(d2[j]), (j if idx is None else int(idx[j]))


def _offer_mapped(best: _Best, sub: _Best, si: np.ndarray | None, di: np.ndarray | None) -> None:
    if sub.i >= 0 and sub.d2 > best.d2:
        best.d2 = sub.d2
        best.i = int(sub.i if si is None else si[sub.i])
        best.j = int(sub.j if di is None else di[sub.j])


def _grid_level(S: np.ndarray, gS: _Grid, D: np.ndarray, gD: _Grid, best: _Best, si, di, force: bool = False):
    """One level of :func:`_directed_grid`: returns the points of S that may still
    beat ``best`` and the points of D that may be their nearest neighbours (index
    arrays), or None, None when nothing is left, or ``(rows, None)`` when the
    live cells hold nearly all of S (no progress to expect)."""
    ub2, near = _cell_pairs(gS, gD, probes=_PROBES)
    # A lower bound with its witness: the exact distance of a point of the cell
    # with the loosest upper bound (when the sets are apart, the farthest one).
    for x in (int(np.argmax(ub2)),):
        if ub2[x] > best.d2:
            i = int(gS.rep[x])
            # the nearest neighbour of a point of X lies in a box of D within sqrt(ub2[X])
            L = _cell_pairs(gS, gD, rows=np.array([x]))
            near_cells = L[0] <= ub2[x] * (1.0 + _REL)
            d2, j = _nearest_exact(S[i], D, np.flatnonzero(near_cells[gD.cell]))
            if d2 > best.d2:
                best.d2 = d2
                best.i = i if si is None else int(si[i])
                best.j = j if di is None else int(di[j])
    live = ub2 > best.d2
    if not live.any():
        return None, None
    # Points of live cells: an exact distance to the representatives of the
    # cells of D that bound their cell best is an upper bound of their own.
    rows = np.flatnonzero(live[gS.cell])
    if rows.size > 0.9 * S.shape[0] and not force:
        return rows, None  # the sets overlap at the scale of the cells: give up early
    cell = gS.cell[rows]
    P = S[rows]
    u = None
    for q in range(near.shape[1]):
        v = _sqdist(P, D[gD.rep[near[cell, q]]])
        u = v if u is None else np.minimum(u, v, out=u)
    keep = u > best.d2
    rows, cell, u = rows[keep], cell[keep], u[keep]
    if rows.size == 0:
        return None, None
    # per live cell, the largest upper bound of its surviving points
    ucell = np.full(ub2.size, -np.inf)
    np.maximum.at(ucell, cell, u)
    cells = np.flatnonzero(ucell > -np.inf)
    L = _cell_pairs(gS, gD, rows=cells)
    # a point's nearest neighbour lies within sqrt(u) of it, in a box of D that near
    reach = (L <= (ucell[cells] * (1.0 + _REL))[:, None]).any(axis=0)
    return rows, np.flatnonzero(reach[gD.cell])


def _directed_grid(
    A: np.ndarray,
    B: np.ndarray,
    best: _Best,
    gA: _Grid | None = None,
    gB: _Grid | None = None,
    clouds=None,
    force: bool = False,
) -> _Best:
    """h(A, B) coarse to fine, in the spirit of a dual-tree branch and bound.

    Each level bins both sets into about ``_GRID_CELLS`` cells.  A cell of A whose
    every point is provably within the running maximum of some point of B (its
    farthest corner from a representative of a cell of B) is dropped whole; the
    points of the other cells are tested against the few representatives that
    bound their cell best (one exact distance each); the cells of B too far from
    every surviving point to hold its nearest neighbour are dropped too.  The
    survivors are binned again, finer, and so on, until few pairs are left for
    brute force.

    When the sets are apart the maximum is realised on a small part of A (the
    side facing away from B), so each level keeps a small fraction of both sets.
    When they overlap, nothing can be dropped (the maximum is below the cell
    size) and the first level hands the problem to :func:`_directed_pruned`.
    Exact: every bound is rigorous, and the survivors' nearest neighbours (which
    lie in the kept points of B) are computed as in brute force.  ``clouds()``,
    if given, returns the prepared ``(A, B)`` for a fallback on the whole problem
    (shared by both directions of :func:`hausdorff`, with their k-d trees).
    ``force`` keeps binning small problems (for tests).
    """
    S, D = A, B
    si = di = None  # indices of S and D in A and B (None: all, in order)
    gS, gD = gA, gB
    while True:
        nS, nD = S.shape[0], D.shape[0]
        if nS * nD <= _LEAF_PAIRS and not (force and nS > 1 and nD > 1):
            src, dst = _prepare(S, D)
            _offer_mapped(best, _directed_brute(src, dst, _Best(best.d2)), si, di)
            return best
        gS = gS if gS is not None else _Grid(S)
        gD = gD if gD is not None else _Grid(D)
        ks, kd = _grid_level(S, gS, D, gD, best, si, di, force)
        if ks is None:
            return best
        if kd is None or ks.size * kd.size > 0.5 * nS * nD and not (force and (ks.size < nS or kd.size < nD)):
            # no progress: the sets overlap at this scale
            src, dst = clouds() if (clouds is not None and si is None and di is None) else _prepare(S, D)
            _offer_mapped(best, _run(src, dst, _Best(best.d2), "auto"), si, di)
            return best
        S, D = S[ks], D[kd]
        si = ks if si is None else si[ks]
        di = kd if di is None else di[kd]
        gS = gD = None


#: the values of the ``method`` seam the engine runs
METHODS = ("auto", "brute", "pruned", "grid")


def _run(src: _Cloud, dst: _Cloud, best: _Best, method: str) -> _Best:
    n, m = src.points.shape[0], dst.points.shape[0]
    if method == "brute" or (method == "auto" and n * m <= _BRUTE_PAIRS):
        return _directed_brute(src, dst, best)
    return _directed_pruned(src, dst, best)


class _Problem:
    """A pair (A, B) with what both directions can share: the grids of the
    coarse-to-fine stage and the prepared clouds (with their k-d trees) of the
    fallback, each made on first use."""

    def __init__(self, A: np.ndarray, B: np.ndarray, method: str):
        self.A, self.B, self.method = A, B, method
        self._grids = [None, None]
        self._clouds = None

    def _pair(self):
        if self._clouds is None:
            self._clouds = _prepare(self.A, self.B)
        return self._clouds

    def _grid(self, k: int) -> _Grid:
        if self._grids[k] is None:
            self._grids[k] = _Grid(self.B if k else self.A)
        return self._grids[k]

    def directed(self, swap: bool, best: _Best) -> _Best:
        """h(A, B) (or h(B, A) if ``swap``), offered to ``best``."""
        n, m = self.A.shape[0], self.B.shape[0]
        if self.method == "brute" or (self.method == "auto" and n * m <= _BRUTE_PAIRS):
            a, b = self._pair()
            return _directed_brute(b, a, best) if swap else _directed_brute(a, b, best)
        if self.method == "pruned":
            a, b = self._pair()
            return _directed_pruned(b, a, best) if swap else _directed_pruned(a, b, best)

        def clouds():
            a, b = self._pair()
            return (b, a) if swap else (a, b)

        if swap:
            return _directed_grid(self.B, self.A, best, self._grid(1), self._grid(0), clouds)
        return _directed_grid(self.A, self.B, best, self._grid(0), self._grid(1), clouds)


def directed(A: np.ndarray, B: np.ndarray, method: str, swap: bool = False, floor2: float = -1.0, problem=None):
    """``(d2, i, j)``: the squared directed distance h(A, B) (h(B, A) if ``swap``) with its
    witness, exact; ``floor2`` a known lower bound of the square (pruning only)."""
    prob = _Problem(A, B, method) if problem is None else problem
    best = prob.directed(swap, _Best(floor2))
    return best.d2, best.i, best.j, prob
