"""A certificate that a set of simplices is the regular triangulation (Notes §23.1).

Qhull computes the lower hull of the lifted balls in floating point, and on
co-spherical or nearly degenerate input its answer can be wrong in ways that depend
on the last bits of the coordinates (overlapping tetrahedra, facets that are not
locally regular).  :func:`certify` checks an answer with the exact predicates of
:mod:`shapelab.exact.predicates` (ties broken by Simulation of Simplicity), so that an
answer that passes is *the* regular triangulation of the (symbolically perturbed)
input, whatever machine computed it:

1. every top simplex has non-zero orientation (exact);
2. every facet lies in one or two top simplices; the two simplices of an interior
   facet lie on opposite sides of it;
3. every interior facet is *locally regular*: the lifted apex of one simplex lies
   strictly above the lifted hyperplane of the other (the power test);
4. the boundary (the facets in one simplex) is closed and locally convex: at every
   ridge of it, the neighbouring boundary facet does not bend outwards, and two
   coplanar neighbours do not fold over each other;
5. the centroid of one simplex lies in exactly one closed simplex: with 2 and 4
   the simplices cover every point of their union the same number of times, so they
   tile it exactly once, and with 4 the union is the convex hull of the vertices;
6. every centre that is not a vertex lies in a simplex (so the hull is the hull of
   all centres) and strictly above its lifted hyperplane: the ball is hidden.

By the *Delaunay lemma* (for weights: Edelsbrunner and Shah 1996), a triangulation
of the convex hull whose facets are all locally regular is the regular
triangulation, and 6 shows its vertex set is right.  Each condition is decided
exactly, so the certificate is a function of the input alone.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._toolkit.tolerances import COVER_PREFILTER
from .incremental import incremental_triangulation
from .predicates import WeightedPoints, det

__all__ = ["Certificate", "certify", "facet_adjacency", "failing_simplices", "repair"]


@dataclass(frozen=True)
class Certificate:
    """The outcome of :func:`certify`.

    Attributes
    ----------
    ok : bool
        True when every condition holds.
    reason : str
        The first condition that failed ("" when ``ok``).
    neighbors : ndarray of int32, shape (m, k+1)
        ``neighbors[t, i]``: the simplex across the facet of ``t`` opposite its
        ``i``-th vertex, or -1 on the boundary (computed, not taken from Qhull).
    counts : dict
        How many tests were decided by the floating-point filter and how many
        exactly (see :attr:`shapelab.exact.predicates.WeightedPoints.stats`).

    See Also
    --------
    certify
        Produces it.
    """

    ok: bool
    reason: str
    neighbors: np.ndarray
    counts: dict


def _row_keys(F: np.ndarray, n: int) -> np.ndarray:
    """One integer per row of ``F`` (entries in [0, n)), equal iff the rows are."""
    F = np.asarray(F, dtype=np.int64)
    if F.shape[1] * max(1, int(n).bit_length()) <= 62:
        key = np.zeros(F.shape[0], dtype=np.int64)
        for c in range(F.shape[1]):
            key *= np.int64(n)
            key += F[:, c]
        return key
    return np.unique(F, axis=0, return_inverse=True)[1].ravel()  # pragma: no cover - > 2e6 balls


def _group(keys: np.ndarray):
    """``order, inv, cnt``: a sorting permutation of the keys, the rank of each key
    among the distinct keys, and their counts."""
    order = np.argsort(keys)
    ks = keys[order]
    first = np.r_[True, ks[1:] != ks[:-1]]
    rank = np.cumsum(first) - 1
    inv = np.empty(keys.size, dtype=np.int64)
    inv[order] = rank
    return order, inv, np.bincount(rank)


def facet_adjacency(simp: np.ndarray):
    """Facets of the rows of ``simp`` (vertices ascending in each row).

    Returns
    -------
    nbr : (m, k+1) int32
        The simplex across each facet, -1 if none, or -2 where a facet lies in more
        than two simplices.
    pos : (m, k+1) int32
        For an interior facet, its column in the neighbour's row (else -1).

    See Also
    --------
    certify
        Uses it to test local regularity.
    """
    m, w = simp.shape
    nbr = np.full((m, w), -1, dtype=np.int32)
    pos = np.full((m, w), -1, dtype=np.int32)
    if m == 0 or w == 1:
        return nbr, pos
    cols = [[c for c in range(w) if c != i] for i in range(w)]
    allf = np.concatenate([simp[:, c] for c in cols]).astype(np.int64)  # (w*m, w-1), block i = facet opp. i
    order, inv, cnt = _group(_row_keys(allf, int(simp.max()) + 1))
    owner_t = np.tile(np.arange(m), w)
    owner_i = np.repeat(np.arange(w), m)
    c = cnt[inv[order]]
    multi = c > 2
    if np.any(multi):
        bad = order[multi]
        nbr[owner_t[bad], owner_i[bad]] = -2
    starts = np.flatnonzero(np.r_[True, inv[order][1:] != inv[order][:-1]])
    pairs = starts[cnt[inv[order[starts]]] == 2]
    a, b = order[pairs], order[pairs + 1]
    nbr[owner_t[a], owner_i[a]] = owner_t[b]
    nbr[owner_t[b], owner_i[b]] = owner_t[a]
    pos[owner_t[a], owner_i[a]] = owner_i[b]
    pos[owner_t[b], owner_i[b]] = owner_i[a]
    return nbr, pos


def _fail(reason, nbr, P):
    return Certificate(False, reason, nbr, dict(P.stats))


def _locate(P: WeightedPoints, simp, nbr, s, q: np.ndarray, start: np.ndarray):
    """Visibility walk of the points ``q`` (local indices) from the simplices
    ``start``: the closed simplex containing each point, or -1 (outside the union,
    or no convergence)."""
    m, w = simp.shape
    cur = start.astype(np.int64).copy()
    out = np.full(q.size, -1, dtype=np.int64)
    active = np.arange(q.size)
    for step in range(4 * m + 16):
        if active.size == 0:
            break
        t = cur[active]
        qa = q[active]
        sg = np.empty((active.size, w), dtype=np.int8)
        for i in range(w):
            rows = simp[t].astype(np.int64).copy()
            rows[:, i] = qa
            sg[:, i] = P.orient(rows)
        sg *= s[t][:, None]
        neg = sg < 0
        done = ~neg.any(axis=1)
        out[active[done]] = t[done]
        go = ~done
        # cross a negative facet; which one rotates with the step (no cycles)
        o = step % w
        first = np.argmax(np.roll(neg[go], -o, axis=1), axis=1)
        col = (first + o) % w
        nxt = nbr[t[go], col]
        lost = nxt < 0
        cur[active[go]] = nxt
        keep = active[go][~lost]
        active = keep
    return out


def _verified_neighbors(simp: np.ndarray, hint: np.ndarray):
    """``(nbr, pos)`` from a neighbour relation given with the simplices (Qhull's),
    after checking it: symmetric, and both sides of each pair see the same facet.
    ``None`` if it is not consistent."""
    m, w = simp.shape
    hint = np.asarray(hint)
    if m == 0 or hint.shape != simp.shape or hint.min(initial=0) < -1 or hint.max(initial=-1) >= m:
        return None
    if w > 1 and not np.all(simp[:, 1:] > simp[:, :-1]):
        return None
    nbr = hint.astype(np.int32, copy=False)
    t, i = np.nonzero(nbr > np.arange(m, dtype=np.int32)[:, None])  # each pair once
    nb = nbr[t, i]
    back = nbr[nb] == t[:, None].astype(np.int32)
    if not np.all(back.sum(axis=1) == 1):
        return None
    j = np.argmax(back, axis=1)
    # same facet on both sides: compare the facets' packed integer keys (exact)
    n = int(simp.max()) + 1
    if (w - 1) * max(1, n.bit_length()) <= 62:
        K = np.empty((m, w), dtype=np.int64)
        for a in range(w):
            key = np.zeros(m, dtype=np.int64)
            for c in range(w):
                if c != a:
                    key *= np.int64(n)
                    key += simp[:, c]
            K[:, a] = key
        if not np.array_equal(K[t, i], K[nb, j]):
            return None
    else:  # pragma: no cover - beyond ~2e6 balls: compare the vertex sets
        St, Sn = simp[t], simp[nb]
        eq = St[:, :, None] == Sn[:, None, :]
        inS, inN = eq.any(axis=2), eq.any(axis=1)
        ar = np.arange(t.size)
        if not (np.all(inS.sum(axis=1) == w - 1) and not inS[ar, i].any() and not inN[ar, j].any()):
            return None
    # every slot is either paired (seen from one side above) or on the boundary
    if np.count_nonzero(nbr >= 0) != 2 * t.size:
        return None
    pos = np.full((m, w), -1, dtype=np.int32)
    pos[t, i] = j
    pos[nb, j] = i
    return nbr, pos


def certify(P: WeightedPoints, simp: np.ndarray, neighbors=None, order=None) -> Certificate:
    """Check that ``simp`` is the regular triangulation of the weighted points ``P``.

    Parameters
    ----------
    P : WeightedPoints
        The weighted centres (local indices), with their exact predicates.
    simp : ndarray of int, shape (m, k+1)
        The candidate top simplices, vertices ascending in each row.
    neighbors : ndarray of int, shape (m, k+1), optional
        A neighbour relation that came with the candidate (Qhull's).  It is checked
        (symmetric, same facet on both sides), and then a facet cannot lie in three
        simplices unless one of them is a boundary facet: condition 4 with a
        *connected* boundary excludes that (a connected, closed, locally convex
        surface bounds one convex body, van Heijenoort 1952, and the cover is 1 on
        both sides of an interior facet).  Without it the facets are sorted.

    Returns
    -------
    Certificate

    See Also
    --------
    regular_triangulation
        Certifies Qhull's candidate with this.
    shapelab.exact.incremental.incremental_triangulation
        The exact fallback when it fails.

    References
    ----------
    .. [1] H. Edelsbrunner and N. R. Shah, "Incremental topological flipping works for
           regular triangulations", *Algorithmica* 15:223-241, 1996.
           doi:10.1007/BF01975867
    .. [2] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity: a technique to
           cope with degenerate cases in geometric algorithms", *ACM Trans. Graph.*
           9(1):66-104, 1990. doi:10.1145/77635.77639
    .. [3] J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast robust
           geometric predicates", *Discrete Comput. Geom.* 18:305-363, 1997.
           doi:10.1007/PL00009321
    """
    simp = np.asarray(simp, dtype=np.int64)
    m, w = simp.shape
    k = w - 1
    n = P.n
    given = None if neighbors is None or k < 1 or m == 0 else _verified_neighbors(simp, neighbors)
    nbr, pos = given if given is not None else facet_adjacency(simp)
    if k == 0:
        ok = m == 1
        return Certificate(ok, "" if ok else "a single centre needs one vertex", nbr, dict(P.stats))
    if m == 0:
        return _fail("no simplices", nbr, P)
    if np.any(nbr == -2):
        return _fail("a facet lies in more than two simplices", nbr, P)
    # 1. orientation
    s = P.orient(simp).astype(np.int64)
    if np.any(s == 0):
        return _fail(f"{int(np.sum(s == 0))} simplices have zero volume", nbr, P)
    # 2. interior facets: opposite sides
    t1, i1 = np.nonzero(nbr >= 0)
    keep = t1 < nbr[t1, i1]
    t1, i1 = t1[keep], i1[keep]
    t2, i2 = nbr[t1, i1].astype(np.int64), pos[t1, i1].astype(np.int64)
    par = lambda i: 1 - 2 * (i % 2)  # noqa: E731  (-1)**i
    if np.any(s[t1] * par(i1) != -s[t2] * par(i2)):
        return _fail("two simplices overlap across a facet", nbr, P)
    # 3. local regularity: the apex of t2 above the lifted hyperplane of t1
    rows = np.concatenate([simp[t1], simp[t2, i2][:, None]], axis=1)
    pw = P.power(rows).astype(np.int64) * s[t1]
    if np.any(pw <= 0):
        return _fail(f"{int(np.sum(pw <= 0))} interior facets are not locally regular", nbr, P)
    # 4. closed, locally convex boundary
    bt, bi = np.nonzero(nbr == -1)
    if k == 1:
        if bt.size != 2:
            return _fail("the boundary of a 1D triangulation must be two points", nbr, P)
    else:
        cols = [[c for c in range(w) if c != i] for i in range(w)]
        F = np.take_along_axis(simp[bt], np.array(cols)[bi], axis=1)  # boundary facets
        apex = simp[bt, bi]
        # ridges: facet minus one vertex
        rc = [[c for c in range(k) if c != j] for j in range(k)]
        R = np.concatenate([F[:, c] for c in rc])
        own = np.tile(np.arange(F.shape[0]), k)
        extra = np.concatenate([F[:, j] for j in range(k)])
        order, inv, cnt = _group(_row_keys(R, n))
        if np.any(cnt != 2):
            return _fail("the boundary is not closed", nbr, P)
        a, b = order[0::2], order[1::2]
        f1, u1, v2 = own[a], extra[a], extra[b]
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        nb_ = F.shape[0]
        ncomp = connected_components(coo_matrix((np.ones(a.size), (own[a], own[b])), shape=(nb_, nb_)), directed=False)[
            0
        ]
        if ncomp != 1:
            return _fail("the boundary is not connected", nbr, P)
        ridge = R[a]
        a1 = apex[f1]
        o_in = P.orient(np.c_[F[f1], a1]).astype(np.int64)
        o_v = P.orient(np.c_[F[f1], v2]).astype(np.int64)
        if np.any(o_v == -o_in):
            return _fail("the boundary is not convex", nbr, P)
        flat = np.flatnonzero(o_v == 0)
        if flat.size:
            ou = P.orient(np.c_[ridge[flat], a1[flat], u1[flat]]).astype(np.int64)
            ov = P.orient(np.c_[ridge[flat], a1[flat], v2[flat]]).astype(np.int64)
            if np.any(ou * ov >= 0):
                return _fail("the boundary folds over itself", nbr, P)
    # 5. one cover: the centroid of simplex 0 lies in one closed simplex
    cover = _count_cover(P, simp, s)
    if cover != 1:
        return _fail(f"the simplices cover a point {cover} times", nbr, P)
    # 6. the centres that are not vertices are inside and hidden
    present = np.zeros(n, dtype=bool)
    present[simp.ravel()] = True
    q = np.flatnonzero(~present)
    if q.size:
        start = _start_simplices(P, simp, q, order)
        loc = _locate(P, simp, nbr, s, q, start)
        if np.any(loc < 0):
            return _fail("a centre that is not a vertex lies outside the triangulation", nbr, P)
        hp = P.power(np.c_[simp[loc], q]).astype(np.int64) * s[loc]
        if np.any(hp <= 0):
            return _fail(f"{int(np.sum(hp <= 0))} balls left out are not hidden", nbr, P)
    return Certificate(True, "", nbr, dict(P.stats))


def _start_simplices(P, simp, q, order=None):
    """For each query point, a simplex incident to a vertex near it: its nearest
    vertex (KD-tree), or, given a spatially coherent ``order`` of the points (the
    Morton order Qhull was fed), the vertex next to it in that order."""
    present = np.zeros(P.n, dtype=bool)
    present[simp.ravel()] = True
    inc = np.full(P.n, -1, dtype=np.int64)
    inc[simp.ravel()] = np.repeat(np.arange(simp.shape[0]), simp.shape[1])
    if order is not None and len(order) == P.n:
        order = np.asarray(order)
        rank = np.empty(P.n, dtype=np.int64)
        rank[order] = np.arange(P.n)
        vr = np.sort(rank[present])
        j = np.clip(np.searchsorted(vr, rank[q]), 0, vr.size - 1)
        return inc[order[vr[j]]]
    from scipy.spatial import cKDTree

    verts = np.flatnonzero(present)
    _, j = cKDTree(P.u[verts]).query(P.u[q])
    return inc[verts[j]]


def _count_cover(P: WeightedPoints, simp, s) -> int:
    """The number of closed simplices containing the centroid of ``simp[0]``, decided
    exactly (float bounding boxes, one coordinate at a time, pick the candidates)."""
    m, w = simp.shape
    k = w - 1
    U = P.u
    c = U[simp[0]].mean(axis=0)
    margin = COVER_PREFILTER * (np.abs(U[simp[0]] - c).max() + np.abs(c).max())
    cand = np.arange(m)
    for a in range(k):
        X = U[simp[cand], a]
        lo, hi = X[:, 0].copy(), X[:, 0].copy()
        for j in range(1, w):
            np.minimum(lo, X[:, j], out=lo)
            np.maximum(hi, X[:, j], out=hi)
        cand = cand[(lo <= c[a] + margin) & (hi >= c[a] - margin)]
    # exact: points scaled by (k+1), the centroid as the sum of simplex 0's vertices
    ui = [P.exact_u(int(i)) for i in simp[0]]
    cs = tuple(sum(p[a] for p in ui) for a in range(k))
    count = 0
    for t in cand:
        pts = [tuple((k + 1) * v for v in P.exact_u(int(i))) for i in simp[t]]
        inside = True
        for i in range(w):
            rep = list(pts)
            rep[i] = cs
            if det([[a - b for a, b in zip(p, rep[0])] for p in rep[1:]]) * int(s[t]) < 0:
                inside = False
                break
        count += inside
    return count


# ----------------------------------------------------------------------------------
# Local repair
# ----------------------------------------------------------------------------------
# Local repair of a candidate regular triangulation (Notes §23.1).
#
# Where Qhull's floating-point lower hull fails its exact certificate
# (:mod:`shapelab.exact.certify`), the failure is usually *local*: a few flat
# tetrahedra where Qhull triangulated a merged facet of exactly co-planar or
# co-spherical centres (coordinates rounded to 0.001 Å), a few facets that are not
# locally regular under Simulation of Simplicity.  Instead of recomputing the whole
# triangulation with the exact incremental algorithm, :func:`repair` re-triangulates
# only a *cavity* around the failures:
#
# 1. :func:`failing_simplices` marks the simplices that break a local condition of the
#    certificate: zero volume, a facet in more than two simplices, two simplices on the
#    same side of their common facet, a facet that is not locally regular, a boundary
#    facet that is not convex, a ball left out that is not hidden (or lies outside);
# 2. the cavity is these simplices, then with their neighbours across a facet, then
#    grown by one ring of vertex stars per further attempt;
# 3. the regular triangulation of the cavity's vertices (and of the balls left out that
#    lie in it) is computed by the exact incremental algorithm
#    (:func:`shapelab.exact.incremental.incremental_triangulation`) with the *same*
#    predicates and the same symbolic perturbation as the global one;
# 4. its simplices inside the cavity (a flood fill from the cavity's boundary facets,
#    each of which must appear in it) replace the cavity;
# 5. the stitched triangulation is certified again, whole.
#
# Because the final certificate is the same complete, exact test, a repaired answer
# that passes it *is* the unique regular triangulation of the perturbed input: the one
# the whole-input exact road computes.  If no attempt certifies, :func:`repair` returns
# ``None`` and the caller falls back to the whole-input exact road.


def failing_simplices(P: WeightedPoints, simp: np.ndarray, order=None, neighbors=None):
    """The simplices of a candidate triangulation that break a local condition of
    the certificate (Notes §23.1).

    Parameters
    ----------
    P : WeightedPoints
        The weighted centres and their exact predicates.
    simp : ndarray of int, shape (m, k+1)
        Candidate top simplices, vertices ascending in each row.
    order : array of int, optional
        A spatially coherent order of the points (speeds up locating the balls left
        out).
    neighbors : ndarray of int, shape (m, k+1), optional
        A neighbour relation that came with the candidate (Qhull's); used, after the
        check of :func:`certify`, instead of sorting the facets.

    Returns
    -------
    bad : ndarray of bool, shape (m,)
        Simplices with zero volume, with a facet in more than two simplices, on the
        same side of a common facet as their neighbour, across a facet that is not
        locally regular, owning a boundary facet that is not convex, or containing
        (or next to) a ball left out that is not hidden.
    nbr : ndarray of int32, shape (m, k+1)
        The facet adjacency of ``simp`` (:func:`facet_adjacency`).
    pos : ndarray of int32, shape (m, k+1)
        For an interior facet, its column in the neighbour's row (else -1).

    See Also
    --------
    repair
        Re-triangulates the neighbourhood of these simplices.
    shapelab.exact.certify.certify
        The complete check; a candidate with no failing simplex can still fail it
        (a boundary that is not closed, a double cover).
    """
    simp = np.asarray(simp, dtype=np.int64)
    m, w = simp.shape
    k = w - 1
    given = None if neighbors is None or k < 1 or m == 0 else _verified_neighbors(simp, neighbors)
    nbr, pos = given if given is not None else facet_adjacency(simp)
    bad = np.zeros(m, dtype=bool)
    if m == 0 or k < 1:
        return bad, nbr, pos
    bad |= np.any(nbr == -2, axis=1)
    s = P.orient(simp).astype(np.int64)
    bad |= s == 0
    t1, i1 = np.nonzero(nbr >= 0)
    keep = t1 < nbr[t1, i1]
    t1, i1 = t1[keep], i1[keep]
    t2, i2 = nbr[t1, i1].astype(np.int64), pos[t1, i1].astype(np.int64)
    par = lambda i: 1 - 2 * (i % 2)  # noqa: E731
    good = (s[t1] != 0) & (s[t2] != 0)
    over = good & (s[t1] * par(i1) != -s[t2] * par(i2))
    bad[t1[over]] = True
    bad[t2[over]] = True
    g = np.flatnonzero(good & ~over)
    if g.size:
        rows = np.concatenate([simp[t1[g]], simp[t2[g], i2[g]][:, None]], axis=1)
        pw = P.power(rows).astype(np.int64) * s[t1[g]]
        nr = g[pw <= 0]
        bad[t1[nr]] = True
        bad[t2[nr]] = True
    # boundary facets: convex at every ridge (only where both facets' simplices are sane)
    bt, bi = np.nonzero(nbr == -1)
    if k >= 2 and bt.size:
        cols = np.array([[c for c in range(w) if c != i] for i in range(w)])
        F = np.take_along_axis(simp[bt], cols[bi], axis=1)
        apex = simp[bt, bi]
        rc = [[c for c in range(k) if c != j] for j in range(k)]
        R = np.concatenate([F[:, c] for c in rc])
        own = np.tile(np.arange(F.shape[0]), k)
        extra = np.concatenate([F[:, j] for j in range(k)])
        ordr, inv, cnt = _group(_row_keys(R, P.n))
        # ridges in other than two boundary facets: their simplices are bad
        odd = cnt[inv] != 2
        bad[bt[own[odd]]] = True
        pairs = np.flatnonzero(cnt == 2)
        if pairs.size:
            starts = np.searchsorted(inv[ordr], pairs)
            a, b = ordr[starts], ordr[starts + 1]
            f1, u1, v2 = own[a], extra[a], extra[b]
            a1 = apex[f1]
            o_in = P.orient(np.c_[F[f1], a1]).astype(np.int64)
            o_v = P.orient(np.c_[F[f1], v2]).astype(np.int64)
            nc = (o_v == -o_in) | (o_in == 0)
            flat = np.flatnonzero((o_v == 0) & (o_in != 0))
            if flat.size:  # co-planar neighbours must not fold over each other
                ridge = R[a[flat]]
                ou = P.orient(np.c_[ridge, a1[flat], u1[flat]]).astype(np.int64)
                ov = P.orient(np.c_[ridge, a1[flat], v2[flat]]).astype(np.int64)
                nc[flat[ou * ov >= 0]] = True
            bad[bt[f1[nc]]] = True
            bad[bt[own[b][nc]]] = True
    # balls left out: inside and hidden
    present = np.zeros(P.n, dtype=bool)
    present[simp.ravel()] = True
    q = np.flatnonzero(~present)
    if q.size:
        ok = ~bad & (s != 0)
        sane = np.flatnonzero(ok)
        start = _start_simplices(P, simp, q, order)
        loc = np.full(q.size, -1, dtype=np.int64)
        if sane.size:
            # walk in the sane part only (the walk needs consistent orientations)
            sub = simp[sane]
            remap = np.full(m, -1, dtype=np.int64)
            remap[sane] = np.arange(sane.size)
            nb2 = np.where(nbr >= 0, remap[np.maximum(nbr, 0)], -1)[sane].astype(np.int32)
            st = remap[start]
            okst = st >= 0
            if okst.any():
                loc[okst] = sane[_locate_safe(P, sub, nb2, s[sane], q[okst], st[okst])]
        inside = loc >= 0
        if inside.any():
            li = loc[inside]
            hp = P.power(np.c_[simp[li], q[inside]]).astype(np.int64) * s[li]
            bad[li[hp <= 0]] = True
        # not located (outside, or walked into a failure): the simplices at its start
        bad[start[~inside]] = True
    return bad, nbr, pos


def _locate_safe(P, simp, nbr, s, q, start):
    out = _locate(P, simp, nbr, s, q, start)
    return np.where(out >= 0, out, -1)


def _grow(simp: np.ndarray, nbr: np.ndarray, mask: np.ndarray, n: int, attempt: int) -> np.ndarray:
    """The cavity of attempt 0, 1, 2, ...: the ``mask`` simplices, then with their
    facet neighbours, then grown by the stars of the vertices of the previous one."""
    out = mask.copy()
    if attempt == 0:
        return out
    nb = nbr[out]
    out[nb[nb >= 0]] = True
    for _ in range(attempt - 1):
        vm = np.zeros(n, dtype=bool)
        vm[simp[out].ravel()] = True
        out = np.any(vm[simp], axis=1)
    return out


def _inside_part(P, simp, nbr, pos, cav, comp, local):
    """The simplices of ``local`` (the regular triangulation of the points of the
    cavity component ``comp``, simplex ids) that lie in it, and its links across the
    component's boundary facets ``(seed, seed column, kept simplex, kept column)``;
    ``None`` if a boundary facet is not a facet of ``local`` or the flood fill from
    the boundary leaks out of the component."""
    m, w = local.shape
    if m == 0:
        return None
    lnbr, lpos = facet_adjacency(local)
    cn = nbr[comp].astype(np.int64)
    r, cc = np.nonzero((cn >= 0) & ~cav[np.maximum(cn, 0)])
    ct = comp[r]
    if ct.size == 0:
        z = np.zeros(0, dtype=np.int64)
        return np.arange(m), z, z, z, z
    kt = nbr[ct, cc].astype(np.int64)
    kc = pos[ct, cc].astype(np.int64)
    cols = np.array([[c for c in range(w) if c != i] for i in range(w)])
    F = np.take_along_axis(simp[ct], cols[cc], axis=1)
    lf = np.concatenate([local[:, c] for c in cols])
    keys_l = _row_keys(lf, P.n)
    keys_f = _row_keys(F, P.n)
    srt = np.argsort(keys_l, kind="stable")
    ks = keys_l[srt]
    a = np.minimum(np.searchsorted(ks, keys_f), ks.size - 1)
    if not np.all(ks[a] == keys_f):
        return None
    t_a, c_a = srt[a] % m, srt[a] // m
    # the local simplex on the cavity's side of the facet (the side of its apex)
    o_cav = P.orient(np.c_[F, simp[ct, cc]]).astype(np.int64)
    o_a = P.orient(np.c_[F, local[t_a, c_a]]).astype(np.int64)
    other = lnbr[t_a, c_a].astype(np.int64)
    opos = lpos[t_a, c_a].astype(np.int64)
    same = o_a == o_cav
    seed = np.where(same, t_a, other)
    sc = np.where(same, c_a, opos)
    outside = np.where(same, other, t_a)
    if np.any(seed < 0) or np.any(o_cav == 0):
        return None
    blocked = np.zeros((m, w), dtype=bool)
    blocked[seed, sc] = True
    inside = np.zeros(m, dtype=bool)
    stack = np.unique(seed).tolist()
    inside[stack] = True
    L = lnbr.tolist()
    B = blocked.tolist()
    while stack:
        t = stack.pop()
        row, brow = L[t], B[t]
        for j in range(w):
            u = row[j]
            if u >= 0 and not brow[j] and not inside[u]:
                inside[u] = True
                stack.append(u)
    outside = outside[outside >= 0]
    if inside[outside].any():
        return None
    return np.flatnonzero(inside), seed, sc, kt, kc


def _assemble(simp, nbr, cav, parts):
    """The kept simplices and the inside parts of the cavity's components'
    triangulations, with their neighbour relation."""
    kept = np.flatnonzero(~cav)
    nk = kept.size
    old_id = np.full(simp.shape[0], -1, dtype=np.int64)
    old_id[kept] = np.arange(nk)
    kn = nbr[kept].astype(np.int64)
    rows, nbrs = [simp[kept].astype(np.int64)], [np.where(kn >= 0, old_id[np.maximum(kn, 0)], -1)]
    links = []
    off = nk
    for local, (ins, seed, sc, kt, kc) in parts:
        lnbr = facet_adjacency(local)[0]
        loc_id = np.full(local.shape[0], -1, dtype=np.int64)
        loc_id[ins] = off + np.arange(ins.size)
        ln = lnbr[ins].astype(np.int64)
        rows.append(local[ins])
        nbrs.append(np.where(ln >= 0, loc_id[np.maximum(ln, 0)], -1))
        links.append((loc_id[seed], sc, old_id[kt], kc))
        off += ins.size
    new = np.concatenate(rows)
    nn = np.concatenate(nbrs)
    for a, ac, b, bc in links:  # across the cavity's boundary
        nn[b, bc] = a
        nn[a, ac] = b
    return new, nn.astype(np.int32)


def _components(simp, mask, n):
    """The simplices of ``mask`` grouped by connected component (sharing a vertex)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    ids = np.flatnonzero(mask)
    w = simp.shape[1]
    rows = np.repeat(np.arange(ids.size), w)
    g = coo_matrix((np.ones(rows.size), (rows, simp[ids].ravel())), shape=(ids.size, n)).tocsr()
    nc, lab = connected_components(g @ g.T, directed=False)
    order = np.argsort(lab, kind="stable")
    cuts = np.flatnonzero(np.diff(lab[order])) + 1
    return np.split(ids[order], cuts)


def repair(
    P: WeightedPoints,
    simp: np.ndarray,
    neighbors=None,
    order=None,
    attempts: int = 4,
    max_fraction=0.25,
    failing=None,
    start: int = 0,
):
    """Repair a candidate regular triangulation locally (Notes §23.1).

    Parameters
    ----------
    P : WeightedPoints
        The weighted centres and their exact predicates.
    simp : ndarray of int, shape (m, k+1)
        The candidate (Qhull's lower hull), vertices ascending in each row.
    neighbors : ndarray of int, shape (m, k+1), optional
        Qhull's neighbour relation of the candidate (checked before use).
    order : array of int, optional
        A spatially coherent order of all points (Morton), for the insertions and the
        point location.
    attempts : int
        Cavities tried: the failing simplices, then with their facet neighbours, then
        grown by one ring of vertex stars at a time.
    max_fraction : float
        Give up (return ``None``) when a cavity holds more than this fraction of the
        points: re-triangulating most of the input locally costs as much as the whole.
    failing : tuple, optional
        What :func:`failing_simplices` returned for this candidate, if the caller
        computed it already.
    start : int
        The first attempt (1: begin with the failing simplices' facet neighbours,
        which saves a whole certificate where the failing simplices alone are too
        tight a cavity, as on rounded MD systems).

    Returns
    -------
    (simp, certificate, info) or None
        The certified triangulation, its :class:`~shapelab.exact.certify.Certificate`
        and a dict (``attempts``, ``cavity_simplices``, ``cavity_points``); ``None``
        if no attempt certifies (the caller then runs the whole-input exact road).

    See Also
    --------
    failing_simplices
        Where the cavity starts.
    shapelab.exact.incremental.incremental_triangulation
        Re-triangulates the cavity, and the whole input if this fails.
    shapelab.exact.certify.certify
        Decides whether the repaired triangulation is the regular one.

    References
    ----------
    .. [1] H. Edelsbrunner and N. R. Shah, "Incremental topological flipping works for
           regular triangulations", *Algorithmica* 15:223-241, 1996.
           doi:10.1007/BF01975867
    .. [2] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity: a technique to
           cope with degenerate cases in geometric algorithms", *ACM Trans. Graph.*
           9(1):66-104, 1990. doi:10.1145/77635.77639
    """
    simp = np.asarray(simp, dtype=np.int64)
    m, w = simp.shape
    if m == 0 or w < 2:
        return None
    bad, nbr, pos = failing_simplices(P, simp, order, neighbors) if failing is None else failing
    if not bad.any():
        return None  # nothing local to repair: the failure is global
    n = P.n
    present = np.zeros(n, dtype=bool)
    present[simp.ravel()] = True
    missing = np.flatnonzero(~present)
    rank = None
    if order is not None and len(order) == n:
        rank = np.empty(n, dtype=np.int64)
        rank[np.asarray(order)] = np.arange(n)
    near = _missing_near(P, simp, missing) if missing.size else None
    cav = bad.copy()
    grow = bad.copy()
    done: dict = {}
    for attempt in range(start, attempts):
        if attempt:
            cav |= _grow(simp, nbr, grow, n, 1 if attempt == 1 else 2)
        vm = np.zeros(n, dtype=bool)
        vm[simp[cav].ravel()] = True
        if np.all(cav) or np.count_nonzero(vm) > max_fraction * n:
            return None  # not local: the whole-input road is as fast
        parts, grow = [], np.zeros(m, dtype=bool)
        npts = 0
        for comp in _components(simp, cav, n):
            key = comp.tobytes()
            if key not in done:
                pts = np.unique(simp[comp])
                if near is not None:
                    vc = np.zeros(n, dtype=bool)
                    vc[pts] = True
                    pts = np.union1d(pts, missing[vc[near]])
                pts = pts[np.argsort(rank[pts], kind="stable")] if rank is not None else pts
                try:
                    local = incremental_triangulation(P, pts)
                    part = _inside_part(P, simp, nbr, pos, cav, comp, local)
                except ValueError:  # the component's points are flat
                    part = None
                done[key] = (local, part, pts.size) if part is not None else None
            got = done[key]
            if got is None:
                grow[comp] = True
            else:
                parts.append(got[:2])
                npts += got[2]
        if grow.any():
            continue
        new, nn = _assemble(simp, nbr, cav, parts)
        cert = certify(P, new, nn, order=order)
        if cert.ok:
            info = {"attempts": attempt + 1 - start, "cavity_simplices": int(cav.sum()), "cavity_points": int(npts)}
            return new, cert, info
        grow = cav.copy()
    return None


def _missing_near(P, simp, missing):
    """The nearest vertex of ``simp`` to each ball left out: a ball left out takes
    part in the re-triangulation of the cavity that holds its nearest vertex."""
    from scipy.spatial import cKDTree

    present = np.zeros(P.n, dtype=bool)
    present[simp.ravel()] = True
    verts = np.flatnonzero(present)
    _, j = cKDTree(P.u[verts]).query(P.u[missing])
    return verts[j]
