"""A certificate that a set of simplices is the regular triangulation (Notes §23.1).

Qhull computes the lower hull of the lifted balls in floating point, and on
co-spherical or nearly degenerate input its answer can be wrong in ways that depend
on the last bits of the coordinates (overlapping tetrahedra, facets that are not
locally regular).  :func:`certify` checks an answer with the exact predicates of
:mod:`shapelab._engine.predicates` (ties broken by Simulation of Simplicity), so that an
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
        exactly (see :attr:`shapelab._engine.predicates.WeightedPoints.stats`).

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
    f = np.flatnonzero(nbr > np.arange(m, dtype=np.int32)[:, None])  # each pair once
    t = f // w
    i = f - t * w
    nb = nbr.ravel()[f]
    # the column of t in its neighbour's row, which must hold t exactly once
    G, t32 = nbr[nb], t.astype(np.int32)
    hits = np.zeros(t.size, dtype=np.int8)
    j = np.zeros(t.size, dtype=np.int64)
    for c in range(w):
        e = G[:, c] == t32
        hits += e
        j[e] = c
    if not np.all(hits == 1):
        return None
    del G
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
        K = K.ravel()
        if not np.array_equal(K[f], K[nb * w + j]):
            return None
        del K
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
    pos = np.full(m * w, -1, dtype=np.int32)
    pos[f] = j
    pos[nb * w + j] = i
    return nbr, pos.reshape(m, w)


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
    shapelab._engine.incremental.incremental_triangulation
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
    # 2. interior facets: opposite sides (each pair once, t1 < t2)
    f = np.flatnonzero(nbr > np.arange(m, dtype=nbr.dtype)[:, None])
    t1 = f // w
    i1 = f - t1 * w
    t2, i2 = nbr.ravel()[f].astype(np.int64), pos.ravel()[f].astype(np.int64)
    del f
    par = lambda i: 1 - 2 * (i % 2)  # noqa: E731  (-1)**i
    if np.any(s[t1] * par(i1) != -s[t2] * par(i2)):
        return _fail("two simplices overlap across a facet", nbr, P)
    # 3. local regularity: the apex of t2 above the lifted hyperplane of t1
    rows = np.empty((t1.size, w + 1), dtype=np.int64)
    rows[:, :w] = simp[t1]
    rows[:, w] = simp.ravel()[t2 * w + i2]
    pw = P.power(rows).astype(np.int64) * s[t1]
    del rows
    if np.any(pw <= 0):
        return _fail(f"{int(np.sum(pw <= 0))} interior facets are not locally regular", nbr, P)
    # 4. closed, locally convex boundary
    why = _boundary_failure(P, simp, nbr)
    if why:
        return _fail(why, nbr, P)
    # 5. one cover: the centroid of simplex 0 lies in one closed simplex
    cover = _count_cover(P, simp, s)
    if cover != 1:
        return _fail(f"the simplices cover a point {cover} times", nbr, P)
    # 6. the centres that are not vertices are inside and hidden
    present = np.zeros(n, dtype=bool)
    present[simp.ravel()] = True
    why = _left_out_failure(P, simp, nbr, s, np.flatnonzero(~present), order)
    if why:
        return _fail(why, nbr, P)
    return Certificate(True, "", nbr, dict(P.stats))


def _left_out_failure(P: WeightedPoints, simp, nbr, s, q: np.ndarray, order=None) -> str:
    """Condition 6 of :func:`certify` for the centres ``q`` that are not vertices:
    each lies in a simplex (located by walking from a nearby start) and is hidden
    there (positive power to its orthosphere).  "" if they are, else why not."""
    if not q.size:
        return ""
    start = _start_simplices(P, simp, q, order)
    loc = _locate(P, simp, nbr, s, q, start)
    if np.any(loc < 0):
        return "a centre that is not a vertex lies outside the triangulation"
    hp = P.power(np.c_[simp[loc], q]).astype(np.int64) * s[loc]
    if np.any(hp <= 0):
        return f"{int(np.sum(hp <= 0))} balls left out are not hidden"
    return ""


def _boundary_failure(P: WeightedPoints, simp: np.ndarray, nbr: np.ndarray) -> str:
    """Condition 4 of :func:`certify` on the facets with no neighbour (``nbr == -1``):
    the first way the boundary is not closed, connected and locally convex, or ""."""
    m, w = simp.shape
    k = w - 1
    n = P.n
    bt, bi = np.nonzero(nbr == -1)
    if k == 1:
        if bt.size != 2:
            return "the boundary of a 1D triangulation must be two points"
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
            return "the boundary is not closed"
        a, b = order[0::2], order[1::2]
        f1, u1, v2 = own[a], extra[a], extra[b]
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        nb_ = F.shape[0]
        ncomp = connected_components(coo_matrix((np.ones(a.size), (own[a], own[b])), shape=(nb_, nb_)), directed=False)[
            0
        ]
        if ncomp != 1:
            return "the boundary is not connected"
        ridge = R[a]
        a1 = apex[f1]
        o_in = P.orient(np.c_[F[f1], a1]).astype(np.int64)
        o_v = P.orient(np.c_[F[f1], v2]).astype(np.int64)
        if np.any(o_v == -o_in):
            return "the boundary is not convex"
        flat = np.flatnonzero(o_v == 0)
        if flat.size:
            ou = P.orient(np.c_[ridge[flat], a1[flat], u1[flat]]).astype(np.int64)
            ov = P.orient(np.c_[ridge[flat], a1[flat], v2[flat]]).astype(np.int64)
            if np.any(ou * ov >= 0):
                return "the boundary folds over itself"
    return ""


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
# (:mod:`shapelab._engine.certify`), the failure is usually *local*: a few flat
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
#    (:func:`shapelab._engine.incremental.incremental_triangulation`) with the *same*
#    predicates and the same symbolic perturbation as the global one;
# 4. its simplices inside the cavity (a flood fill from the cavity's boundary facets,
#    each of which must appear in it) replace the cavity;
# 5. the stitched triangulation is certified again (:func:`_certify_stitched`): the
#    conditions that are per simplex, per facet or per ball left out only where the
#    stitch changed them (the first pass over the candidate vouches for the rest),
#    the global ones (closed, connected, convex boundary; one cover) whole.
#
# Because the final certificate decides exactly what the complete, exact test
# :func:`certify` decides, a repaired answer that passes it *is* the unique regular
# triangulation of the perturbed input: the one the whole-input exact road computes.  If no attempt certifies, :func:`repair` returns
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
    shapelab._engine.certify.certify
        The complete check; a candidate with no failing simplex can still fail it
        (a boundary that is not closed, a double cover).
    """
    first = _first_pass(P, simp, order, neighbors)
    return first.bad, first.nbr, first.pos


@dataclass(frozen=True)
class _FirstPass:
    """What :func:`failing_simplices` found, kept for the local re-certificate
    (:func:`_certify_stitched`): the candidate ``simp``, its verified facet adjacency
    ``nbr``/``pos``, orientations ``s``, the failing simplices ``bad``, and the balls
    left out ``q`` with the simplex ``loc`` each was located in (-1 if none) and
    whether it is hidden there (``hidden``)."""

    simp: np.ndarray
    nbr: np.ndarray
    pos: np.ndarray
    s: np.ndarray
    bad: np.ndarray
    q: np.ndarray
    loc: np.ndarray
    hidden: np.ndarray


def _first_pass(P: WeightedPoints, simp: np.ndarray, order=None, neighbors=None) -> _FirstPass:
    """:func:`failing_simplices`, with what it computed on the way."""
    simp = np.asarray(simp, dtype=np.int64)
    m, w = simp.shape
    k = w - 1
    given = None if neighbors is None or k < 1 or m == 0 else _verified_neighbors(simp, neighbors)
    nbr, pos = given if given is not None else facet_adjacency(simp)
    bad = np.zeros(m, dtype=bool)
    z = np.zeros(0, dtype=np.int64)
    if m == 0 or k < 1:
        return _FirstPass(simp, nbr, pos, np.zeros(m, dtype=np.int64), bad, z, z, z.astype(bool))
    bad |= np.any(nbr == -2, axis=1)
    s = P.orient(simp).astype(np.int64)
    bad |= s == 0
    f = np.flatnonzero(nbr > np.arange(m, dtype=nbr.dtype)[:, None])  # pairs once, t1 < t2
    t1 = f // w
    i1 = f - t1 * w
    t2, i2 = nbr.ravel()[f].astype(np.int64), pos.ravel()[f].astype(np.int64)
    del f
    par = lambda i: 1 - 2 * (i % 2)  # noqa: E731
    good = (s[t1] != 0) & (s[t2] != 0)
    over = good & (s[t1] * par(i1) != -s[t2] * par(i2))
    bad[t1[over]] = True
    bad[t2[over]] = True
    g = np.flatnonzero(good & ~over)
    if g.size:
        rows = np.empty((g.size, w + 1), dtype=np.int64)
        rows[:, :w] = simp[t1[g]]
        rows[:, w] = simp.ravel()[t2[g] * w + i2[g]]
        pw = P.power(rows).astype(np.int64) * s[t1[g]]
        del rows
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
    loc, hidden = np.full(q.size, -1, dtype=np.int64), np.zeros(q.size, dtype=bool)
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
                got = _locate_safe(P, sub, nb2, s[sane], q[okst], st[okst])
                # -1 (not located) stays -1: sane[-1] would be the last sane simplex
                loc[okst] = np.where(got >= 0, sane[np.maximum(got, 0)], -1)
        inside = loc >= 0
        if inside.any():
            li = loc[inside]
            hp = P.power(np.c_[simp[li], q[inside]]).astype(np.int64) * s[li]
            bad[li[hp <= 0]] = True
            hidden[inside] = hp > 0
        # not located (outside, or walked into a failure): the simplices at its start
        bad[start[~inside]] = True
    return _FirstPass(simp, nbr, pos, s, bad, q, loc, hidden)


def _locate_safe(P, simp, nbr, s, q, start):
    out = _locate(P, simp, nbr, s, q, start)
    return np.where(out >= 0, out, -1)


def _certify_stitched(P: WeightedPoints, first: _FirstPass, cav: np.ndarray, new, nn, order=None) -> Certificate:
    """:func:`certify` for a stitched triangulation, re-checking only what changed.

    ``new`` is what :func:`_assemble` makes of the candidate ``first.simp`` and the
    cavity ``cav``: rows ``[0, nk)`` are the kept simplices ``first.simp[~cav]`` in
    their order (neighbour slots re-linked only where they pointed into the
    cavity), rows ``[nk, M)`` the new simplices, ``nn`` the neighbour relation.  The
    answer (``ok``) is that of ``certify(P, new, nn, order)``; only the first failed
    condition named in ``reason`` may differ when several fail.  It relies on what
    the first pass over the candidate, :func:`_first_pass`, established.

    Why it is enough to re-check the changed part (conditions as in :func:`certify`):

    * the neighbour relation (what :func:`_verified_neighbors` checks): a kept slot
      that did not point into the cavity is unchanged, and it and its partner were
      verified, symmetric and on the same facet, by the first pass.  Checked here:
      every slot of a new simplex and every re-linked kept slot points to a row that
      points back exactly once, across the same facet (so every non-negative slot is
      paired, as the whole check requires).  If that fails (or ``new`` does not
      start with the kept simplices), the whole :func:`certify` decides, which then
      sorts the facets itself;
    * 1 (orientation) is per simplex: kept simplices are not failing, so non-zero in
      the first pass (``first.s``); the new ones are tested;
    * 2 and 3 (opposite sides, local regularity) are per interior facet: a facet
      between two kept simplices is one of the first pass, which marked both
      simplices of any facet that failed; the facets with a new simplex on either
      side are tested;
    * 4 (closed, connected, locally convex boundary) is global (connectivity) and is
      re-checked whole; it costs in proportion to the boundary only;
    * 5 (one cover) is global: with 2 and 4 holding everywhere the cover is the same
      at every point, so one point suffices, as in :func:`certify` (a bounding-box
      filter, then a few exact tests);
    * 6 (balls left out) is per ball: a ball left out by the candidate and still
      left out, located by the first pass in a kept simplex and hidden there, is
      still inside that closed simplex and above its lifted hyperplane; every other
      ball left out (including vertices of the candidate that the repair hid) is
      located in ``new`` and tested.

    See Also
    --------
    certify
        The whole check, which this replaces after :func:`repair` stitches.
    """
    new = np.asarray(new, dtype=np.int64)
    nn = np.asarray(nn)
    simp, nbr = first.simp, first.nbr
    M, w = new.shape
    kept = np.flatnonzero(~cav)
    nk = kept.size
    if (
        M == 0
        or w < 2
        or cav.shape != first.bad.shape
        or np.any(first.bad & ~cav)
        or nn.shape != new.shape
        or nn.min(initial=0) < -1
        or nn.max(initial=-1) >= M
        or not np.array_equal(new[:nk], simp[kept])
    ):
        return certify(P, new, nn, order=order)  # not stitched as expected: whole
    nn = nn.astype(np.int32, copy=False)
    if not np.all(new[nk:, 1:] > new[nk:, :-1]):
        return certify(P, new, nn, order=order)  # not stitched as expected: whole
    # slots to check: every slot of a new row, and the kept slots that pointed into
    # the cavity (re-linked)
    ko = nbr[kept].astype(np.int64)
    rel = (ko >= 0) & cav[np.maximum(ko, 0)]
    old_id = np.full(simp.shape[0], -1, dtype=np.int64)
    old_id[kept] = np.arange(nk)
    if not np.array_equal(nn[:nk][~rel], np.where(ko >= 0, old_id[np.maximum(ko, 0)], -1)[~rel]):
        return certify(P, new, nn, order=order)  # not stitched as expected: whole
    kt, ki = np.nonzero(rel)
    nt = np.repeat(np.arange(nk, M), w)
    ni = np.tile(np.arange(w), M - nk)
    t = np.concatenate([kt, nt])
    i = np.concatenate([ki, ni])
    u = nn[t, i].astype(np.int64)
    paired = u >= 0
    t, i, u = t[paired], i[paired], u[paired]
    back = nn[u] == t[:, None]
    if not np.all(back.sum(axis=1) == 1):
        return certify(P, new, nn, order=order)  # not stitched as expected: whole
    j = np.argmax(back, axis=1)
    # the same facet on both sides: the vertex sets without the opposite vertices
    same = (new[t].sum(axis=1) - new[t, i]) == (new[u].sum(axis=1) - new[u, j])
    eq = new[t][:, :, None] == new[u][:, None, :]
    same &= (eq.any(axis=2).sum(axis=1) == w - 1) & ~eq[np.arange(t.size), i].any(axis=1)
    if not np.all(same):
        return certify(P, new, nn, order=order)  # not stitched as expected: whole
    # 1. orientation
    s = np.empty(M, dtype=np.int64)
    s[:nk] = first.s[kept]
    s[nk:] = P.orient(new[nk:]) if M > nk else 0
    if np.any(s[nk:] == 0):
        return _fail(f"{int(np.sum(s[nk:] == 0))} simplices have zero volume", nn, P)
    # 2, 3. the interior facets with a new simplex on one side (each pair once)
    partner_checked = (u >= nk) | rel[np.minimum(u, nk - 1), j] if nk else np.ones(u.size, dtype=bool)
    keep = ~partner_checked | (t < u)
    t1, i1, t2, i2 = t[keep], i[keep], u[keep], j[keep]
    par = lambda a: 1 - 2 * (a % 2)  # noqa: E731  (-1)**a
    if np.any(s[t1] * par(i1) != -s[t2] * par(i2)):
        return _fail("two simplices overlap across a facet", nn, P)
    if t1.size:
        pw = P.power(np.concatenate([new[t1], new[t2, i2][:, None]], axis=1)).astype(np.int64) * s[t1]
        if np.any(pw <= 0):
            return _fail(f"{int(np.sum(pw <= 0))} interior facets are not locally regular", nn, P)
    # 4. the boundary, whole
    why = _boundary_failure(P, new, nn)
    if why:
        return _fail(why, nn, P)
    # 5. one cover
    cover = _count_cover(P, new, s)
    if cover != 1:
        return _fail(f"the simplices cover a point {cover} times", nn, P)
    # 6. balls left out: those not already shown hidden in a kept simplex
    present = np.zeros(P.n, dtype=bool)
    present[new.ravel()] = True
    done = np.zeros(P.n, dtype=bool)
    ok = first.hidden & (first.loc >= 0)
    ok[ok] = ~cav[first.loc[ok]]
    done[first.q[ok]] = True
    why = _left_out_failure(P, new, nn, s, np.flatnonzero(~present & ~done), order)
    if why:
        return _fail(why, nn, P)
    return Certificate(True, "", nn, dict(P.stats))


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
    max_failing: float = 1.0,
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
    max_failing : float
        Give up (return ``None``) when more than this fraction of the candidate's
        simplices fail, before any re-triangulation: the caller has a better
        candidate for input that fails nearly everywhere (grids).
    start : int
        The first attempt (1: begin with the failing simplices' facet neighbours,
        which saves a whole certificate where the failing simplices alone are too
        tight a cavity, as on rounded MD systems).

    Returns
    -------
    (simp, certificate, info) or None
        The certified triangulation, its :class:`~shapelab._engine.certify.Certificate`
        and a dict (``attempts``, ``cavity_simplices``, ``cavity_points``); ``None``
        if no attempt certifies (the caller then runs the whole-input exact road).

    See Also
    --------
    failing_simplices
        Where the cavity starts.
    shapelab._engine.incremental.incremental_triangulation
        Re-triangulates the cavity, and the whole input if this fails.
    shapelab._engine.certify.certify
        The conditions the repaired triangulation must pass (re-checked only where
        the stitch changed them, the global ones whole).

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
    first = _first_pass(P, simp, order, neighbors)
    bad, nbr, pos = first.bad, first.nbr, first.pos
    if not bad.any():
        return None  # nothing local to repair: the failure is global
    if np.count_nonzero(bad) > max_failing * m:
        return None  # failing nearly everywhere: not local
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
        cert = _certify_stitched(P, first, cav, new, nn, order=order)
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
