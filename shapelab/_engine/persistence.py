"""The fast path behind :mod:`shapelab.persistence`: Betti numbers and persistence of a
filtration (Notes §23.1) without the boundary matrix.

The engine, not required reading: :func:`shapelab.persistence.persistence` states the
standard column reduction in public code and calls :func:`persistence` here through its
``method`` seam (the default, ``method="fast"``); a test holds both equal.
:class:`shapelab.filtration.Filtration`'s methods call these functions directly, so
neither module imports the other back (no import cycle).

Algorithms (Delfinado & Edelsbrunner's incremental method, made array-friendly):

* :math:`H_0` -- Kruskal on the 1-skeleton in filtration order.  An edge is *negative*
  (kills a component) iff it lies in the minimum spanning forest whose edge weights are
  the filtration ranks; SciPy computes that forest in C.  The elder rule pairs each
  negative edge with the younger of the two components it joins.
* :math:`H_{d-1}` -- Alexander duality.  The complement of :math:`K_\\tau` in the
  sphere :math:`S^d` is a graph: one node per top simplex not in :math:`K_\\tau` plus
  one *outside* node, one edge per :math:`(d-1)`-simplex not in :math:`K_\\tau`.
  Running time backwards, that graph only gains nodes and edges, so its components are
  a union–find in reverse filtration order; a :math:`(d-1)`-simplex is *positive*
  (creates a void or hole) iff it lies in the spanning forest of the dual graph taken
  in reverse order.  The pairs are those of the dual :math:`H_0` by the elder rule.
* :math:`\\beta_1` in 3D -- from the Euler characteristic,
  :math:`\\beta_1 = \\beta_0 + \\beta_2 - \\chi`, so Betti curves need no reduction.
* :math:`H_1` pairs in 3D -- the standard column reduction, restricted to the
  *negative* triangles ("clearing") and to the rows of *positive* edges
  ("compression", Bauer, Kerber & Reininghaus 2014).  Columns are Python sets, whose
  symmetric difference runs in C.

Every result is computed once per filtration object and kept on it
(:meth:`~shapelab.filtration.Filtration.derived`).
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import minimum_spanning_tree

from .._toolkit.derived import derived
from .._toolkit.tolerances import PERSISTENCE_ROUNDOFF
from .._toolkit.unionfind import elder_merges
from .._toolkit.validate import as_float_array, as_tau, freeze

__all__ = [
    "Summary",
    "summary",
    "reduce_h1",
    "betti",
    "betti_curve",
    "euler_characteristic_curve",
    "persistence",
    "is_roundoff",
    "ROUNDOFF",
    "as_field",
    "as_z2_matrix",
]


# ---------------------------------------------------------------------------- checks
def _check_filtration(F) -> None:
    for attr in ("dimension", "simplices", "values", "boundary"):
        if not hasattr(F, attr):
            raise TypeError(
                "F must be a Filtration (from shapelab.alpha_filtration) or an object with "
                f".dimension, .simplices(k), .values(k) and .boundary(k); it has no {attr!r} "
                f"(got {type(F).__name__})"
            )


def _ambient_dim(F) -> int:
    balls = getattr(F, "balls", None)
    if balls is not None and hasattr(balls, "dim"):
        return int(balls.dim)
    return max(int(F.dimension), 0)


# --------------------------------------------------------------------- spanning forests
def _spanning_forest(n_nodes: int, u: np.ndarray, v: np.ndarray, reverse: bool = False) -> np.ndarray:
    """Indices of the edges (u, v) in the Kruskal spanning forest, edges taken in index
    order (or in reverse index order if ``reverse``).

    Self-loops never enter the forest; parallel edges may only end at node
    ``n_nodes - 1`` (the outside node of a dual graph).  With distinct weights the
    minimum spanning forest is unique and equals Kruskal's, i.e. the set of edges that
    join two different components when the edges are added in that order.
    """
    m = u.shape[0]
    if m == 0 or n_nodes == 0:
        return np.empty(0, dtype=np.int64)
    order_weight = np.arange(m, 0, -1, dtype=np.float64) if reverse else np.arange(1, m + 1, dtype=np.float64)
    # one stored entry per (row, col): SciPy would sum parallel edges, so keep the
    # lightest of each bundle.  In a triangulation the only parallel edges are the
    # dual edges of hull facets, which all end at the outside node (the largest index).
    a = np.minimum(u, v)
    b = np.maximum(u, v)
    sel = np.flatnonzero(a != b)
    hub = sel[b[sel] == n_nodes - 1]
    if hub.size:
        o = hub[np.lexsort((order_weight[hub], a[hub]))]
        first = np.ones(o.shape[0], dtype=bool)
        first[1:] = a[o][1:] != a[o][:-1]
        sel = np.concatenate((sel[b[sel] != n_nodes - 1], o[first]))
    w = order_weight
    g = coo_matrix((w[sel], (a[sel], b[sel])), shape=(n_nodes, n_nodes)).tocsr()
    t = minimum_spanning_tree(g).tocoo()
    # map the chosen weights back to edge indices
    pos = np.rint(t.data).astype(np.int64)
    return m - pos if reverse else pos - 1


@dataclass(frozen=True)
class Summary:
    """Everything the topology of one filtration needs, computed once."""

    ambient: int
    k: int  # affine dimension of the filtration
    values: tuple  # values(j) for j = 0..k
    neg_edges: np.ndarray  # row indices of edges in the H0 forest (sorted)
    pos_facets: np.ndarray  # row indices of (k-1)-simplices creating H_{k-1} (sorted)
    cell_dual: tuple  # (u, v) dual-edge endpoints per (k-1)-simplex, outside = n_k


def _dual_edges(bnd: np.ndarray, n_facets: int):
    """Endpoints of the dual edge of every facet: the (one or two) top cells containing
    it, and the outside node ``n_cells`` for a facet on the hull."""
    n_cells, kp1 = bnd.shape
    flat = bnd.ravel()
    cell = np.repeat(np.arange(n_cells, dtype=np.int64), kp1)
    order = np.argsort(flat, kind="stable")
    counts = np.bincount(flat, minlength=n_facets)
    if np.any(counts > 2):
        bad = int(np.argmax(counts > 2))
        raise ValueError(f"facet {bad} lies in {counts[bad]} top simplices; F is not a triangulation")
    start = np.concatenate(([0], np.cumsum(counts)[:-1]))
    u = np.full(n_facets, n_cells, dtype=np.int64)
    v = np.full(n_facets, n_cells, dtype=np.int64)
    has = counts >= 1
    u[has] = cell[order[start[has]]]
    two = counts == 2
    v[two] = cell[order[start[two] + 1]]
    return u, v


def _build_summary(F) -> Summary:
    _check_filtration(F)
    ambient = _ambient_dim(F)
    k = int(F.dimension)
    values = tuple(np.asarray(F.values(j), dtype=np.float64) for j in range(max(k, -1) + 1))
    n0 = values[0].shape[0] if k >= 0 else 0
    if k >= 1:
        b1 = np.asarray(F.boundary(1), dtype=np.int64)
        # edge i joins vertex rows b1[i, 0], b1[i, 1]; Kruskal in row order
        neg = np.sort(_spanning_forest(n0, b1[:, 0], b1[:, 1]))
    else:
        neg = np.empty(0, dtype=np.int64)
    if k >= 2:
        bk = np.asarray(F.boundary(k), dtype=np.int64)
        n_cells = bk.shape[0]
        n_fac = values[k - 1].shape[0]
        u, v = _dual_edges(bk, n_fac)
        # reverse filtration order: the last facet first
        pos = np.sort(_spanning_forest(n_cells + 1, u, v, reverse=True))
        dual = (u, v)
    else:
        pos = np.empty(0, dtype=np.int64)
        dual = (np.empty(0, np.int64), np.empty(0, np.int64))
    # kept on F and read by every question asked of it: read-only
    neg, pos, dual = freeze(neg), freeze(pos), tuple(freeze(a) for a in dual)
    return Summary(ambient, k, tuple(freeze(np.asarray(a)) for a in values), neg, pos, dual)


def summary(F) -> Summary:
    """Everything the topology of ``F`` needs (H0 forest, dual forest, values), computed
    once and kept on ``F``.  Shared with :mod:`shapelab.cavities`."""
    return derived(F, "topology.summary", _build_summary)


# ------------------------------------------------------------------------ Betti numbers
def _as_taus(taus) -> np.ndarray:
    if np.ndim(taus) == 0 and not isinstance(taus, (list, tuple)):
        raise ValueError("taus must be a 1-D array of growth times, got a scalar (use betti(F, tau))")
    t = as_float_array(taus, "taus")
    if t.ndim != 1:
        raise ValueError(f"taus must be a 1-D array, got shape {t.shape}")
    if np.any(np.isnan(t)):
        raise ValueError(f"taus must not contain NaN (index {int(np.argmax(np.isnan(t)))})")
    return t


def _count_le(sorted_vals: np.ndarray, taus: np.ndarray) -> np.ndarray:
    return np.searchsorted(sorted_vals, taus, side="right").astype(np.int64)


def _betti_array(S: Summary, taus: np.ndarray) -> np.ndarray:
    out = np.zeros((taus.shape[0], S.ambient + 1), dtype=np.int64)
    k = S.k
    if k < 0:
        return out
    counts = [_count_le(S.values[j], taus) for j in range(k + 1)]
    chi = np.zeros(taus.shape[0], dtype=np.int64)
    for j, c in enumerate(counts):
        chi += c if j % 2 == 0 else -c
    b0 = counts[0].copy()
    if k >= 1:
        b0 -= _count_le(S.values[1][S.neg_edges], taus)
    out[:, 0] = b0
    if k >= 2:
        # components of the complement in S^d, minus one: cells not yet in K plus the
        # outside node, minus the dual forest edges not yet in K
        n_cells = S.values[k].shape[0]
        n_pos = S.pos_facets.shape[0]
        cells_out = n_cells - counts[k]
        pos_out = n_pos - _count_le(S.values[k - 1][S.pos_facets], taus)
        out[:, k - 1] = cells_out - pos_out
    if k == 3:
        # Euler–Poincaré: chi = b0 - b1 + b2
        out[:, 1] = out[:, 0] + out[:, 2] - chi
    return out


def betti(F, tau) -> tuple:
    """The implementation of :func:`shapelab.persistence.betti` on a filtration ``F``."""
    t = as_tau(tau)
    S = summary(F)
    return tuple(int(x) for x in _betti_array(S, np.array([t]))[0])


def betti_curve(F, taus) -> np.ndarray:
    """The implementation of :func:`shapelab.persistence.betti_curve` on a filtration ``F``."""
    t = _as_taus(taus)
    S = summary(F)
    return _betti_array(S, t)


def euler_characteristic_curve(F, taus) -> np.ndarray:
    """The implementation of :func:`shapelab.persistence.euler_characteristic_curve` on a filtration ``F``."""
    _check_filtration(F)
    t = _as_taus(taus)
    chi = np.zeros(t.shape[0], dtype=np.int64)
    for j in range(int(F.dimension) + 1):
        c = _count_le(np.asarray(F.values(j), dtype=np.float64), t)
        chi += c if j % 2 == 0 else -c
    return chi


# -------------------------------------------------------------------------- persistence
def _pairs_h0(S: Summary, F) -> np.ndarray:
    v0 = S.values[0]
    n0 = v0.shape[0]
    if n0 == 0:
        return np.empty((0, 2))
    births, deaths = [], []
    if S.k >= 1:
        b1 = np.asarray(F.boundary(1), dtype=np.int64)
        v1 = S.values[1]
        ages = list(range(n0))  # vertex rows are in filtration order
        dies = []
        young = []

        def rec(e, elder, younger, oldest):
            dies.append(e)
            young.append(oldest[younger])

        parent, oldest = elder_merges(n0, b1[:, 0], b1[:, 1], S.neg_edges, ages, rec)
        births.append(v0[np.asarray(young, dtype=np.int64)])
        deaths.append(v1[np.asarray(dies, dtype=np.int64)])
        roots = [i for i in range(n0) if parent[i] == i]
        ess = np.asarray([oldest[r] for r in roots], dtype=np.int64)
    else:
        ess = np.arange(n0)
    births.append(v0[ess])
    deaths.append(np.full(ess.shape[0], np.inf))
    P = np.column_stack((np.concatenate(births), np.concatenate(deaths)))
    return P[P[:, 1] > P[:, 0]]


def _dual_merges(S: Summary):
    """Reverse-time union–find on the complement: for every positive facet (in reverse
    filtration order) the root cell of the component it kills (the younger one, i.e.
    the one whose last-filled cell comes earlier in the filtration)."""
    k = S.k
    n_cells = S.values[k].shape[0]
    u, v = S.cell_dual
    # age in reverse time: the outside node is the oldest, then cells by decreasing row
    ages = list(range(n_cells, 0, -1)) + [0]
    facets = S.pos_facets[::-1]
    dead_facet, dead_root = [], []

    def rec(e, elder, younger, oldest):
        dead_facet.append(e)
        dead_root.append(oldest[younger])

    elder_merges(n_cells + 1, u, v, facets, ages, rec)
    return np.asarray(dead_facet, dtype=np.int64), np.asarray(dead_root, dtype=np.int64)


def _pairs_top(S: Summary) -> np.ndarray:
    facets, roots = _dual_merges(S)
    P = np.column_stack((S.values[S.k - 1][facets], S.values[S.k][roots])) if facets.size else np.empty((0, 2))
    return P[P[:, 1] > P[:, 0]]


def reduce_h1(S: Summary, F, *, compress: bool = True):
    """Column reduction of the negative triangles of a 3-dimensional filtration.

    Returns ``(edge_rows, triangle_rows, columns)``: each negative triangle's pivot edge
    (the birth of the H1 class it kills) and, when ``compress`` is False, the reduced
    column (a set of edge rows: a cycle born at the pivot edge that bounds at the
    triangle's value).
    """
    n1 = S.values[1].shape[0]
    n2 = S.values[2].shape[0]
    b2 = np.asarray(F.boundary(2), dtype=np.int64)
    neg_tri = np.ones(n2, dtype=bool)
    if S.k == 3:  # in a 2-dimensional complex every triangle kills an H1 class
        neg_tri[S.pos_facets] = False
    tri = np.flatnonzero(neg_tri)
    if compress:
        is_pos = np.ones(n1, dtype=bool)
        is_pos[S.neg_edges] = False
        rows = b2[tri]
        rows = np.where(is_pos[rows], rows, -1)
    else:
        rows = b2[tri]
    # initial pivot of every column: its youngest (remaining) edge
    piv0 = rows.max(axis=1)
    if np.any(piv0 < 0):  # a negative triangle always has a positive edge; be defensive
        keep = piv0 >= 0
        tri, rows, piv0 = tri[keep], rows[keep], piv0[keep]
    rows_l = rows.tolist()
    owner = {}  # pivot edge -> column position (int), or its reduced column (set)
    changed = {}  # column position -> final pivot (-1: reduced to zero), for reduced columns
    get = owner.get
    # Most columns are "apparent": nothing before them owns their pivot, so they are
    # recorded as they are and only materialised as sets when a later column needs them.
    for i, p in enumerate(piv0.tolist()):
        other = get(p)
        if other is None:
            owner[p] = i
            continue
        col = set(rows_l[i])
        col.discard(-1)
        while other is not None:
            if other.__class__ is int:
                o = set(rows_l[other])
                o.discard(-1)
                owner[p] = o
                other = o
            col ^= other
            if not col:
                break
            p = max(col)
            other = get(p)
        if not col:  # cannot happen for a negative triangle; be defensive
            changed[i] = -1
            continue
        owner[p] = col
        changed[i] = p
    final = piv0.copy()
    if changed:
        idx = np.fromiter(changed.keys(), dtype=np.int64, count=len(changed))
        final[idx] = np.fromiter(changed.values(), dtype=np.int64, count=len(changed))
    ok = final >= 0
    return final[ok], tri[ok], _ColumnView(owner, rows_l)


def _oriented_rows(F, tri: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Signs of the edges ``rows`` (shape ``(t, 3)``) in the oriented boundary of the
    triangles ``tri``: with the triangle's vertices ``a < b < c`` (vertex rows) and every
    edge oriented from its smaller vertex to its larger, :math:`\\partial[a, b, c] =
    [b, c] - [a, c] + [a, b]`, so an edge's sign is :math:`(-1)^i` where ``i`` is the
    position of the vertex it misses."""
    b1 = np.asarray(F.boundary(1), dtype=np.int64)
    ends = b1[rows]  # (t, 3, 2)
    verts = np.sort(ends.reshape(len(rows), -1), axis=1)[:, ::2]  # each vertex twice -> a, b, c
    # the vertex an edge misses: the triangle's vertex sum minus the edge's two ends
    missing = verts.sum(axis=1)[:, None] - ends.sum(axis=2)
    pos = (missing[..., None] == verts[:, None, :]).argmax(axis=2)
    return np.where(pos % 2 == 0, 1, -1).astype(np.int64)


def _reduce_h1_mod_p(S: Summary, F, p: int):
    """Pivot pairs ``(edge_rows, triangle_rows)`` of the column reduction of the negative
    triangles of a 3-dimensional filtration over the field :math:`\\mathbb{Z}/p`, ``p`` an
    odd prime.

    The same clearing and compression as :func:`reduce_h1` (both hold over any field:
    which triangles are negative is decided by :math:`\\beta_2`, which is the same over
    every field for a subcomplex of :math:`\\mathbb{R}^3`, and the rows of negative edges
    are zero after the change of basis of the :math:`H_0` reduction, which only adds
    multiples of later rows to rows of negative edges).  Columns are dicts
    ``{edge row: coefficient mod p}`` of the oriented boundary (:func:`_oriented_rows`).
    """
    n2 = S.values[2].shape[0]
    b2 = np.asarray(F.boundary(2), dtype=np.int64)
    neg_tri = np.ones(n2, dtype=bool)
    if S.k == 3:
        neg_tri[S.pos_facets] = False
    tri = np.flatnonzero(neg_tri)
    rows = b2[tri]
    signs = _oriented_rows(F, tri, rows) % p
    is_pos = np.ones(S.values[1].shape[0], dtype=bool)
    is_pos[S.neg_edges] = False
    keep = is_pos[rows]
    rows_l = rows.tolist()
    signs_l = signs.tolist()
    keep_l = keep.tolist()
    owner = {}  # pivot edge -> reduced column (dict), whose pivot coefficient is 1
    piv_e, piv_t = [], []
    for i in range(tri.shape[0]):
        col = {}
        for e, c, k in zip(rows_l[i], signs_l[i], keep_l[i]):
            if k:
                col[e] = c
        while col:
            q = max(col)
            other = owner.get(q)
            if other is None:
                inv = pow(col[q], p - 2, p)
                if inv != 1:
                    col = {e: c * inv % p for e, c in col.items()}
                owner[q] = col
                piv_e.append(q)
                piv_t.append(int(tri[i]))
                break
            f = col[q]
            for e, c in other.items():
                v = (col.get(e, 0) - f * c) % p
                if v:
                    col[e] = v
                else:
                    col.pop(e, None)
    return np.asarray(piv_e, dtype=np.int64), np.asarray(piv_t, dtype=np.int64)


class _ColumnView:
    """Reduced columns by pivot edge, materialising unreduced ones on demand."""

    def __init__(self, owner, rows):
        self._owner = owner
        self._rows = rows

    def __getitem__(self, p):
        c = self._owner[p]
        if c.__class__ is int:
            c = set(self._rows[c])
            c.discard(-1)
        return c


#: relative size of round-off in entry times (:mod:`shapelab._toolkit.tolerances`)
ROUNDOFF = PERSISTENCE_ROUNDOFF


def _all_values_scale(S: Summary) -> float:
    vals = np.concatenate([v[np.isfinite(v)] for v in S.values]) if S.values else np.empty(0)
    return float(np.median(np.abs(vals))) if vals.size else 0.0


def _build_scale(F) -> float:
    """The size of the input in units of τ, for :func:`is_roundoff`: the larger of the
    median :math:`r_i^2` of the vertices and the median :math:`|z_i - z_j|^2 / 4` of
    the edges of the :math:`H_0` spanning forest (the joins of nearest neighbours).

    Geometric, not a median of entry times: nearly flat centres (collinear or
    coplanar up to round-off) have flat slivers whose entry times reach 1e30 on an
    input of unit size, vertices among them, and a median of the values then made
    every finite pair "round-off".  An object without ``balls`` falls back to the
    median :math:`|\\tau|` of all its simplices."""
    S = summary(F)
    balls = getattr(F, "balls", None)
    if S.k < 0:
        return 0.0
    if balls is None or not hasattr(balls, "centers") or not hasattr(balls, "radii"):
        return _all_values_scale(S)
    v = np.asarray(F.simplices(0), dtype=np.int64).ravel()
    out = float(np.median(np.asarray(balls.radii, dtype=np.float64)[v] ** 2))
    if S.k >= 1 and S.neg_edges.size:
        e = np.asarray(F.simplices(1), dtype=np.int64)[S.neg_edges]
        c = np.asarray(balls.centers, dtype=np.float64)
        dz = c[e[:, 0]] - c[e[:, 1]]
        out = max(out, float(np.median(np.einsum("ij,ij->i", dz, dz))) / 4.0)
    return out


def _value_scale(F) -> float:
    return derived(F, "topology.scale", _build_scale)


def is_roundoff(F, births, deaths) -> np.ndarray:
    """The implementation of :func:`shapelab.persistence.is_roundoff` on a filtration ``F``."""
    b = np.asarray(births, dtype=np.float64)
    d = np.asarray(deaths, dtype=np.float64)
    scale = np.maximum(np.maximum(np.abs(b), np.where(np.isfinite(d), np.abs(d), 0.0)), _value_scale(F))
    return (d - b) <= ROUNDOFF * scale


def as_field(field) -> int:
    """The prime ``p`` of the coefficient field :math:`\\mathbb{Z}/p`, validated."""
    if isinstance(field, (bool, np.bool_)) or not isinstance(field, (int, np.integer)):
        raise TypeError(f"field must be a prime number (the coefficient field Z/p), got {field!r}")
    p = int(field)
    if p < 2 or p >= 2**31 or any(p % q == 0 for q in range(2, int(p**0.5) + 1)):
        raise ValueError(f"field must be a prime number below 2**31 (Z/p is a field only for prime p), got {p}")
    return p


def _build_pairs(F, field: int = 2) -> dict:
    S = summary(F)
    out = {j: np.empty((0, 2)) for j in range(S.ambient + 1)}
    if S.k < 0:
        return out
    out[0] = _pairs_h0(S, F)
    if S.k >= 2:
        out[S.k - 1] = _pairs_top(S)
    if S.k == 3:
        if field == 2:
            e, t, _ = reduce_h1(S, F)
        else:
            e, t = _reduce_h1_mod_p(S, F, field)
        P = np.column_stack((S.values[1][e], S.values[2][t])) if e.size else np.empty((0, 2))
        out[1] = P[P[:, 1] > P[:, 0]]
    for j in out:
        a = np.ascontiguousarray(out[j], dtype=np.float64).reshape(-1, 2)
        a = a[~is_roundoff(F, a[:, 0], a[:, 1])]
        a = a[np.lexsort((a[:, 1], a[:, 0]))]
        a.flags.writeable = False
        out[j] = a
    return out


def persistence(F, *, field=2) -> dict:
    """The implementation of :func:`shapelab.persistence.persistence` on a filtration ``F``."""
    p = as_field(field)
    if p == 2:
        return dict(derived(F, "topology.pairs", _build_pairs))
    return dict(derived(F, f"topology.pairs.Z{p}", lambda G: _build_pairs(G, p)))


def as_z2_matrix(D):
    """``D`` (sparse or array_like, square, integer entries) as a list of columns, each
    the set of rows holding an odd entry, and its size."""
    from scipy import sparse

    if D is None or isinstance(D, (str, bytes, bytearray, numbers.Number, np.generic)):
        raise TypeError(f"D must be a square matrix of integers (mod 2), got {type(D).__name__}")
    if sparse.issparse(D):
        M = sparse.csc_matrix(D)
        A = M.data
    else:
        try:
            A = np.asarray(D)
        except (TypeError, ValueError) as exc:
            raise TypeError(f"D must be a square matrix of integers (mod 2), got {type(D).__name__}") from exc
        if A.ndim != 2:
            raise ValueError(f"D must be a square matrix, got shape {A.shape}")
    if not (A.dtype == bool or np.issubdtype(A.dtype, np.number)) or np.issubdtype(A.dtype, np.complexfloating):
        raise TypeError(f"D must be a square matrix of integers (mod 2), got dtype {A.dtype}")
    if not np.all(np.isfinite(A)) or np.any(A != np.round(A)):
        raise ValueError("D must hold integers (its entries are taken mod 2), got a non-integer entry")
    if not sparse.issparse(D):
        M = sparse.csc_matrix(A.astype(np.int64))
    if M.shape[0] != M.shape[1]:
        raise ValueError(f"D must be a square matrix, got shape {M.shape}")
    M = sparse.csc_matrix(M, dtype=np.int64, copy=True)
    M.sum_duplicates()
    M.data %= 2
    M.eliminate_zeros()
    return [set(M.indices[M.indptr[j] : M.indptr[j + 1]].tolist()) for j in range(M.shape[1])], M.shape[0]
