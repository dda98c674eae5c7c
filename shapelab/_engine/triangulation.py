"""The exact machinery behind the regular triangulation (Notes §23.1): what
:func:`shapelab.regular_triangulation` and :func:`shapelab.power_diagram` run with
``precision="exact"`` (the default).

The readable algorithm is in :mod:`shapelab.triangulation`; this module computes the
same lower hull of the lifted balls, certifies it exactly and repairs it, so that the
answer is the same on every machine.  A student may skip it.

The power diagram :math:`\\Pi(\\mathbb{P})` assigns to each ball :math:`B_i` the cell

.. math:: \\Pi(B_i) = \\{x : \\pi_i(x) \\le \\pi_j(x) \\ \\forall j\\},

with :math:`\\pi_i` the power distance (:func:`shapelab.power_distance`).  Its dual is
the regular (weighted Delaunay) triangulation :math:`DT(\\mathbb{P})`.  Both come from
the *lifting map*

.. math:: z_i \\mapsto \\hat z_i = (z_i, \\lVert z_i\\rVert^2 - r_i^2) \\in \\mathbb{R}^{d+1}:

the lower facets of the convex hull of the lifted points project to the simplices of
DT, and a ball is *hidden* (empty cell) exactly when its lifted point lies strictly
above that lower hull.  Notes §23.1 call DT the "Delaunay triangulation ... defined by
the set of centers"; for balls of different radii that is imprecise: it is the
*regular* triangulation of the weighted centres, and hidden balls are not vertices.

Implementation notes
--------------------
* **Exact combinatorics.**  Qhull's lower hull is a floating-point *candidate*.
  :mod:`shapelab._engine.certify` checks it with exact predicates (:mod:`shapelab._engine.predicates`:
  a floating-point filter, then Python integers on the input's own binary values
  where the filter cannot decide; ties broken by Simulation of Simplicity on the
  heights, by input order): a tiling of the hull, every interior facet locally
  regular, every ball left out hidden.  Where the certificate fails, the failure is
  repaired *locally* (:func:`shapelab._engine.certify.repair`): the simplices that fail
  and their neighbourhood are re-triangulated by the exact incremental algorithm of
  :mod:`shapelab._engine.incremental` on their points alone, stitched in, and the whole
  is certified again (rounded coordinates, exact translates in a water box, a grid
  patch).  Where the failures are everywhere (grids, co-spherical cages), Qhull's
  ties are not Simulation of Simplicity's: a second candidate lowers each lifted
  height by a small convex decreasing function of the ball's rank in the tie-break
  order (:func:`_tiebreak_candidate`), which breaks the ties of a full lattice (every
  node present, in row-major input order: any order of the axes, either direction)
  the same way; it is certified and repaired locally like the first (centres on a
  lattice take it first).  Where the repair does not certify (co-spherical cages
  such as C60; lattices with holes, in a shuffled, snake or Morton order, with
  round-off noise, or with duplicates of a larger radius later in the input), the
  exact incremental algorithm computes the whole triangulation.
  Either way the result is the unique regular triangulation of the perturbed input:
  the same on every CPU, BLAS and Qhull build.  :func:`shapelab.triangulation.triangulation_report` says
  which road was taken.
* **Blocks (threads), opt-in.**  For 3D input of at least 20,000 balls when
  ``SHAPELAB_THREADS`` is set to 2 or more in the environment, the candidate is computed in slabs
  along the longest axis, each with a halo of points, by one Qhull per slab in
  threads (Qhull releases the GIL).  A slab keeps the tetrahedra that look safe in
  floating point (its orthoball, enlarged by the largest weight, inside the slab, or
  no point outside the slab found below the lifted plane): a filter that chooses a
  candidate, not a proof.  The flat tetrahedra where a cut meets the convex hull
  come from one small Qhull on the open facets' and the hulls' points.  The merged
  candidate passes the same exact certificate (or the local repair), else the
  one-block road runs (also when a block's Qhull fails or its cut needs too many
  tests: nearly flat input, one very large ball).  The certified triangulation is
  unique and its rows are sorted lexicographically on every road, so the result,
  and every sum over it, is the same whatever the thread count.
* **Conditioning.**  Before lifting, the centres are translated to their mean and
  scaled to unit size, and the lifted height is centred and scaled as well.  The lower
  hull is invariant under these maps (an affine change of the height by a function
  of :math:`x` keeps the lower hull's combinatorics), power distances scale by
  :math:`s^2`, and translation does not change them.  This keeps Qhull's relative
  precision for inputs offset by :math:`10^6` or scaled by :math:`10^{-6}`.
* **Lower dimension.**  The affine dimension of the centres is decided exactly
  (:func:`shapelab._engine.predicates.affine_basis`: orientation minors, filtered, then in
  Python integers), never by a rank threshold.  If the centres span an affine
  subspace of dimension :math:`k < d` *exactly* (collinear or coplanar input), they
  are expressed in an orthonormal basis of that subspace (SVD) for Qhull and
  triangulated there; the triangulation then has :math:`k`-simplices as top
  simplices.  The exact predicates then work on the input coordinates along the k
  axes most parallel to the subspace, with heights from all d coordinates.
  Centres that are flat only up to round-off (a line or plane rotated in floating
  point, 1e-12 noise) are full-dimensional, as in GUDHI's exact alpha complex: their
  triangulation has flat-looking slivers, which Qhull often misses (an empty or
  rejected candidate); the exact incremental algorithm computes it then.
* **Qhull options** ``Qt Qbb Q12 Q5 Q8`` (the public ``scipy.spatial.ConvexHull``, which
  always adds ``Qt``): ``Qt`` triangulates merged (non-simplicial) facets, which arise
  for cospherical input such as integer grids (where it can leave flat or
  overlapping tetrahedra, which the certificate rejects); ``Qbb`` rescales the last
  (height) coordinate, which improves precision; ``Q12`` allows the wide facets that
  merging produces on grids instead of raising an error; ``Q5`` (no outer planes)
  and ``Q8`` (no near-inside points) skip bookkeeping that only serves ``Qc``'s list
  of coplanar non-vertices, which we do not use (~15 % faster at 10^5 balls).
  ``Qz`` is a Delaunay-mode option and does not apply to our own lifting.  One
  extra point far above the centroid ("point at infinity", the role
  ``Qz`` plays for Delaunay) makes the hull full-dimensional even when all lifted
  points are coplanar (e.g. four cocircular points).
* **Duplicates.**  Of several balls with the same centre only the one with the
  largest radius can have a non-empty cell; among equal radii the lowest index is
  kept (what Simulation of Simplicity decides: earlier balls are slightly larger).
  The others are reported as hidden.  GUDHI's alpha complex also keeps the largest
  ball, but of equal ones whichever its spatial sort inserts first (of three equal
  balls at indices 1, 2, 4 it keeps 2), so its complex is ours up to that choice.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
from scipy.spatial import ConvexHull, QhullError

from .._toolkit import tolerances as tol
from .._toolkit.geometry import morton_order
from .._toolkit.threads import thread_count
from ..balls import Balls
from .certify import certify, facet_adjacency, repair
from .incremental import incremental_triangulation
from .predicates import WeightedPoints, affine_basis, det, projection_axes

__all__ = ["TriangulationReport", "orthocentres", "triangulate", "triangulate_local"]

_QHULL_OPTIONS = "Qt Qbb Q12 Q5 Q8"
# a rejected candidate with more failing simplices than this fraction is not repaired
# locally: the tie-break candidate (_tiebreak_candidate) is tried first
TIEBREAK_FAILING = 0.01
# centres whose distinct values per axis span a product of at most this many times
# their number lie on a lattice (_on_a_lattice): the tie-break candidate goes first
LATTICE_FILL = 8


# ----------------------------------------------------------------------------------
# The frame: centring, scaling, affine hull
# ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Frame:
    """Internal: the conditioned coordinates a triangulation was computed in.

    ``x`` are the kept (non-duplicate) centres in an orthonormal basis of their
    affine hull, centred and divided by ``scale``; ``w`` their weights divided by
    ``scale**2``.  ``keep`` maps rows of ``x`` to input indices.  Power distances in
    the frame times ``scale**2`` are power distances in the input.
    """

    keep: np.ndarray  # (n_k,) int64 input indices of the non-duplicate balls
    x: np.ndarray  # (n_k, k) conditioned coordinates
    w: np.ndarray  # (n_k,) conditioned weights
    scale: float
    k: int  # affine dimension
    axes: tuple = ()  # k < d: the input axes the exact predicates project to


def _dedupe(centers: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """Indices of balls kept after merging identical centres (largest radius wins,
    lowest index among ties), ascending."""
    n = centers.shape[0]
    if n <= 1:
        return np.arange(n, dtype=np.int64)
    # fast path: a 64-bit hash of the rows; distinct hashes mean distinct rows
    bits = np.ascontiguousarray(centers + 0.0).view(np.uint64)  # + 0.0: -0.0 -> 0.0
    hsh = np.zeros(n, dtype=np.uint64)
    for j in range(bits.shape[1]):
        hsh = (hsh ^ bits[:, j]) * np.uint64(0x9E3779B97F4A7C15)
        hsh ^= hsh >> np.uint64(29)
    sh = np.sort(hsh)
    if not np.any(sh[1:] == sh[:-1]):
        return np.arange(n, dtype=np.int64)
    # sort by centre (lexicographic), then by radius descending, then index ascending
    cols = [np.arange(n), -radii] + [centers[:, j] for j in range(centers.shape[1] - 1, -1, -1)]
    order = np.lexsort(cols)
    c = centers[order]
    first = np.ones(n, dtype=bool)
    first[1:] = np.any(c[1:] != c[:-1], axis=1)
    return np.sort(order[first]).astype(np.int64)


def _frame(balls: Balls) -> _Frame:
    centers, radii = balls.centers, balls.radii
    keep = _dedupe(centers, radii)
    if keep.size == centers.shape[0]:
        c, w = centers, radii**2
    else:
        c, w = centers[keep], radii[keep] ** 2
    if c.shape[0] == 0:
        return _Frame(keep, np.zeros((0, 0)), w, 1.0, -1)
    # the affine dimension, exactly (no rank threshold): k+1 affinely independent
    # centres that span the affine hull of all of them
    basis = affine_basis(c)
    k = len(basis) - 1
    if k == 0:  # a single (distinct) centre
        return _Frame(keep, np.zeros((c.shape[0], 0)), w, 1.0, 0)
    mean = c.mean(axis=0)
    y = c - mean
    scale = float(np.max(np.abs(y)))  # > 0: two distinct centres differ from their mean
    y /= scale
    if k == y.shape[1]:
        return _Frame(keep, y, w / scale**2, scale, k)
    # exactly collinear or coplanar: Qhull's candidate in an orthonormal basis of the
    # flat (SVD); the exact predicates on the input's own coordinates along the k
    # axes the flat projects to one-to-one (and best)
    _, _, vt = np.linalg.svd(y, full_matrices=False)
    y = y @ vt[:k].T
    return _Frame(keep, np.ascontiguousarray(y), w / scale**2, scale, k, projection_axes(c, basis))


# ----------------------------------------------------------------------------------
# Lower hull of the lifted points
# ----------------------------------------------------------------------------------
def _flat_rows(x: np.ndarray, simp: np.ndarray) -> np.ndarray:
    """Mask of top simplices whose projection has (relative) volume ~ 0."""
    k = x.shape[1]
    if k < 2 or simp.shape[0] == 0:
        return np.zeros(simp.shape[0], dtype=bool)
    chunk = 1 << 16
    if simp.shape[0] > chunk:
        return np.concatenate([_flat_rows(x, simp[a : a + chunk]) for a in range(0, simp.shape[0], chunk)])
    X = np.ascontiguousarray(x.T)
    p0 = X[:, simp[:, 0]]
    vec = [X[:, simp[:, i]] - p0 for i in range(1, k + 1)]
    size = np.sqrt(np.prod([np.einsum("km,km->m", v, v) for v in vec], axis=0))
    if k == 2:
        det = vec[0][0] * vec[1][1] - vec[0][1] * vec[1][0]
    else:
        a, b, c = vec
        det = (
            a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0])
        )
    return np.abs(det) <= tol.QHULL_FLAT * size


def _qhull_facets(points: np.ndarray):
    """Facets of the convex hull of ``points`` (Qhull through the public
    ``scipy.spatial.ConvexHull``, options ``_QHULL_OPTIONS``): simplices, neighbours
    and hyperplane equations.

    ``ConvexHull`` also computes the hull's volume and area, which we never use (~15 %
    of Qhull's time); scipy's Qhull wrapper underneath it would skip them, but it is
    private, and a private import breaks with any scipy release."""
    hull = ConvexHull(points, qhull_options=_QHULL_OPTIONS)
    return hull.simplices, hull.neighbors, hull.equations


def _hull_once(x: np.ndarray, h: np.ndarray, perm: np.ndarray):
    n, k = x.shape
    lifted = np.empty((n + 1, k + 1))
    lifted[:n, :k] = x[perm]
    lifted[:n, k] = h[perm]
    # the "point at infinity": far above the centroid, so that the hull is
    # full-dimensional even if all lifted points are coplanar
    lifted[n, :k] = x.mean(axis=0)
    lifted[n, k] = h.max() + 4.0 + 2.0 * (h.max() - h.min())
    try:
        simp, neighbors, equations = _qhull_facets(lifted)
    except QhullError as exc:  # nearly flat centres (a flat initial simplex for Qhull)
        raise RuntimeError(f"Qhull failed on the lifted balls: {exc}") from None
    # Lower facets: downward unit normal.  Vertical facets (normal's last component
    # zero up to round-off) project to flat simplices, e.g. over collinear points on
    # the boundary of the hull, and are not part of DT.  In the conditioned frame a
    # genuine facet this steep would have an orthoradius above ~1e10.
    nz = equations[:, k]
    lower = ~np.any(simp == n, axis=1) & (nz < -tol.QHULL_VERTICAL)
    # Qhull's normal of such a vertical facet can be far from horizontal-zero (we saw
    # -2e-6) when it is computed from points whose projections are coplanar only up
    # to round-off: a steep facet (slope above ~1000) that is flat in projection is
    # vertical.  (These are guesses for a candidate; the certificate decides.)
    steep = np.flatnonzero(lower & (nz > -tol.QHULL_STEEP))
    if steep.size:
        lower[steep[_flat_rows(x[perm], simp[steep])]] = False
    newid = np.cumsum(lower, dtype=np.int32) - 1
    nbr = neighbors[lower]
    nbr = np.where(nbr >= 0, np.where(lower[nbr], newid[nbr], -1), -1).astype(np.int32)
    simp = np.asarray(perm, dtype=np.int32)[simp[lower]]
    order = np.argsort(simp, axis=1)
    simp = np.take_along_axis(simp, order, axis=1)
    nbr = np.take_along_axis(nbr, order, axis=1)
    return simp, nbr


def _lower_hull(x: np.ndarray, w: np.ndarray):
    """Qhull's lower hull of the lifted weighted points (x, w), x of full affine
    dimension k = x.shape[1] >= 1: candidate top simplices (local indices, vertices
    ascending in each row), or ``None`` if Qhull gives up.

    The answer is computed in floating point and is only a *candidate*:
    :func:`triangulate_local` certifies it exactly (:mod:`shapelab._engine.certify`).  On
    co-spherical input (cages, grids) Qhull merges facets and ``Qt`` triangulates
    the merged ones, which can leave overlapping or flat tetrahedra; the certificate
    rejects such an answer and the exact incremental algorithm takes over.
    Returns ``(simp, nbr, perm)``, Qhull's neighbours of the lower facets aligned with
    ``simp`` (-1 across the hull; the certificate verifies them too), and the
    Morton order the points were given to Qhull in.
    """
    n, k = x.shape
    if n == k + 1:  # one simplex, no point can be hidden
        return np.arange(n, dtype=np.int32)[None, :], np.full((1, n), -1, dtype=np.int32), None
    h = np.einsum("ij,ij->i", x, x) - w
    # affine normalisation of the height (keeps the lower hull): centre and scale
    h = h - h.mean()
    hs = float(np.max(np.abs(h)))
    if hs > 0:
        h = h / hs
    perm = morton_order(x)
    try:
        return (*_hull_once(x, h, perm), perm)
    except RuntimeError:
        return None


# ----------------------------------------------------------------------------------
# The candidate in blocks (threads): Qhull on slabs with a halo, merged
# ----------------------------------------------------------------------------------
#: below this many (kept) points blocks are not worth their overhead (the halo, the
#: merge, the thread start: ~10-35 % more CPU); on the idle machine two threads made
#: union_measure 1.05x faster at 24,960 SA balls, 1.19x at 99,840 and 1.37x at
#: 199,680 (benchmarks/results/measure_peers_threads.md)
_BLOCKS_MIN_POINTS = 20_000
#: the halo of a block: this fraction of all points on each side beyond its own slab
#: (and at least ``2 n**(2/3)``, two layers of a cube of ``n`` points)
_BLOCK_HALO = 0.04
#: at most this many point-tetrahedron tests per point of a block near its cuts
#: (proteins need fewer than one); past it the block road gives up
_BLOCK_TEST_BUDGET = 16


def _block_count(n: int, k: int) -> int:
    """How many blocks the candidate triangulation is computed in: the thread count
    (:func:`shapelab._toolkit.threads.thread_count`, ``SHAPELAB_THREADS``) for 3D
    input of at least ``_BLOCKS_MIN_POINTS`` points when ``SHAPELAB_THREADS`` is set
    in the environment, else 1.

    Opt-in: the blocks cost 15-25 % more CPU and up to 70 % more peak memory, and on
    rounded MD systems their merge falls back to one block after the work (measured
    in ``benchmarks/results/measure_peers_threads.md``), so only a caller who asks
    for threads gets them."""
    if k != 3 or n < _BLOCKS_MIN_POINTS or n >= 1 << 21:  # (_facet_keys packs 3 indices in an int64)
        return 1
    if not os.environ.get("SHAPELAB_THREADS", "").strip():
        return 1
    return thread_count(max(1, n // (_BLOCKS_MIN_POINTS // 2)))


def _orthoballs(x: np.ndarray, w: np.ndarray, simp: np.ndarray):
    """Orthocentres ``c`` (m, 3) and squared orthoradii ``rho`` (floating point) of
    the tetrahedra ``simp`` (rows ascending), computed from the row's first vertex in
    a fixed order, so that the same row gives the same bits in every block."""
    z0 = x[simp[:, 0]]
    w0 = w[simp[:, 0]]
    u1, u2, u3 = (x[simp[:, i]] - z0 for i in (1, 2, 3))
    b1, b2, b3 = (0.5 * (np.einsum("ij,ij->i", u, u) + w0 - w[simp[:, i]]) for i, u in ((1, u1), (2, u2), (3, u3)))
    c23, c31, c12 = np.cross(u2, u3), np.cross(u3, u1), np.cross(u1, u2)
    det = np.einsum("ij,ij->i", u1, c23)
    with np.errstate(divide="ignore", invalid="ignore"):
        cp = (b1[:, None] * c23 + b2[:, None] * c31 + b3[:, None] * c12) / det[:, None]
    rho = np.einsum("ij,ij->i", cp, cp) - w0
    return z0 + cp, rho


def _block_plan(x: np.ndarray, nb: int):
    """Split the points along their longest axis ``a`` at quantiles into ``nb`` own
    slabs ``[cuts[j-1], cuts[j])``; block ``j`` holds every point whose coordinate
    ``a`` lies in ``[lo[j], hi[j]]``, its own slab widened by a halo of
    ``max(_BLOCK_HALO * n, 2 n**(2/3))`` points on each side.  Returns ``a, cuts, lo, hi, idx`` (the
    points of each block, ascending)."""
    n = x.shape[0]
    a = int(np.argmax(x.max(axis=0) - x.min(axis=0)))
    order = np.argsort(x[:, a], kind="stable")
    xs = x[order, a]
    cuts = np.array([xs[(j * n) // nb] for j in range(1, nb)])
    halo = max(int(_BLOCK_HALO * n), int(2 * n ** (2 / 3)))  # and two layers of points at least
    lo, hi, idx = [], [], []
    for j in range(nb):
        i0, i1 = max(0, (j * n) // nb - halo), min(n, ((j + 1) * n) // nb + halo)
        lo.append(-np.inf if i0 == 0 else xs[i0])
        hi.append(np.inf if i1 == n else xs[i1 - 1])
        s0, s1 = np.searchsorted(xs, lo[-1], "left"), np.searchsorted(xs, hi[-1], "right")
        idx.append(np.sort(order[s0:s1]))
    return a, cuts, np.array(lo), np.array(hi), idx


def _block_tetrahedra(x, w, plan, j):
    """The tetrahedra of block ``j``'s Qhull candidate that it vouches for (global
    indices, rows ascending), their neighbours and the block's hull vertices;
    ``None`` if Qhull failed, or a sentence if the block gave up (too many points
    outside it to test, see ``_BLOCK_TEST_BUDGET``).

    A tetrahedron's *home* is the block whose own slab holds its orthocentre if that
    block holds all its vertices, else the block whose own slab holds the middle of
    its vertices' extent along the axis; a block keeps only its home tetrahedra
    (every block decides the same for the same row, so none is kept twice).  It
    keeps one when no point outside the block can lie below its lifted plane: a
    point ``p`` has negative power to the orthosphere ``(c, rho)`` only if
    ``|c - z_p|^2 < rho + w_p <= rho + max(w)``, so that ball must lie within the
    block's slab, or else the points outside the block in it are tested.  All of
    this is floating point (the orthoballs, the margins, the power tests): it only
    chooses a candidate, which proves nothing; the exact certificate decides."""
    a, cuts, lo, hi, idx = plan
    ij = idx[j]
    res = _lower_hull(x[ij], w[ij])
    if res is None or res[0].shape[0] == 0:
        return None
    simp = ij[res[0]].astype(np.int64)  # ij ascending: rows stay ascending
    nbr0 = res[1]
    hull_vertices = np.unique(simp[np.nonzero(nbr0 < 0)[0]])
    c, rho = _orthoballs(x, w, simp)
    ca = c[:, a]
    xa = x[simp, a]
    vmin, vmax = xa.min(axis=1), xa.max(axis=1)
    home = np.searchsorted(cuts, ca, "right")
    holds = (lo[home] <= vmin) & (vmax <= hi[home])
    home = np.where(holds, home, np.searchsorted(cuts, 0.5 * (vmin + vmax), "right"))
    mine = np.flatnonzero((home == j) & np.isfinite(rho))
    simp, c, rho, ca = simp[mine], c[mine], rho[mine], ca[mine]
    R = np.sqrt(np.maximum(rho + float(w.max()), 0.0)) * (1 + tol.BLOCK_SLACK)
    unsafe = np.flatnonzero((ca - R < lo[j]) | (ca + R > hi[j]))
    keep = np.ones(simp.shape[0], dtype=bool)
    if unsafe.size:
        out = np.flatnonzero((x[:, a] < lo[j]) | (x[:, a] > hi[j]))
        if out.size:
            from scipy.spatial import cKDTree

            tree = cKDTree(x[out])
            # the balls are counted before they are listed, a chunk at a time: a ball
            # enlarged by a large weight, or the huge orthoballs of a nearly flat
            # input's slivers, can hold most points outside the block for every
            # tetrahedron (quadratic memory); past the budget the block gives up
            budget, total = _BLOCK_TEST_BUDGET * ij.size, 0
            for u in np.array_split(unsafe, -(-unsafe.size // 1024)):
                total += int(tree.query_ball_point(c[u], R[u], return_length=True).sum())
                if total > budget:
                    return "too many points to test near a block's cut"
                _drop_below(x, w, c, rho, out, u, tree.query_ball_point(c[u], R[u], return_sorted=False), keep)
    kept = mine[keep]
    new = np.full(nbr0.shape[0], -1, dtype=np.int64)
    new[kept] = np.arange(kept.size)
    nbr = nbr0[kept]
    return simp[keep], np.where(nbr >= 0, new[np.maximum(nbr, 0)], -1), hull_vertices


def _drop_below(x, w, c, rho, out, u, hits, keep) -> None:
    """Clear ``keep[t]`` for the tetrahedra ``t`` in ``u`` with a point ``out[hits]``
    below their lifted plane (negative power to the orthosphere ``(c[t], rho[t])``,
    in floating point)."""
    lens = np.fromiter(map(len, hits), dtype=np.int64, count=len(hits))
    if lens.sum():
        import itertools

        p = out[np.fromiter(itertools.chain.from_iterable(hits), dtype=np.int64, count=int(lens.sum()))]
        t = np.repeat(u, lens)
        d = c[t] - x[p]
        pw = np.einsum("ij,ij->i", d, d) - rho[t] - w[p]
        keep[t[pw < -tol.BLOCK_POWER * np.abs(rho[t])]] = False


def _facet_keys(simp: np.ndarray, t: np.ndarray, i: np.ndarray, n: int) -> np.ndarray:
    """One int64 per facet (the row ``simp[t]`` without column ``i``), equal iff the
    facets are (``n`` points, fewer than 2**21)."""
    rows = simp[t]
    key = np.zeros(t.size, dtype=np.int64)
    for col in range(simp.shape[1]):
        use = i != col
        key = np.where(use, key * n + rows[:, col], key)
    return key


def _pair_facets(simp, nbr, n):
    """Join the open facets (``nbr == -1``) of ``simp`` that are the same facet of two
    rows (in place); returns the slots ``(t, i)`` left open."""
    t, i = np.nonzero(nbr < 0)
    key = _facet_keys(simp, t, i, n)
    order = np.argsort(key, kind="stable")
    ks = key[order]
    same = np.flatnonzero(ks[1:] == ks[:-1])
    a, b = order[same], order[same + 1]
    nbr[t[a], i[a]] = t[b]
    nbr[t[b], i[b]] = t[a]
    open_ = np.ones(t.size, dtype=bool)
    open_[a] = open_[b] = False
    return t[open_], i[open_]


def _orient(x, f: np.ndarray, apex: np.ndarray) -> np.ndarray:
    """Sign of the orientation of (facet ``f``, ``apex``), floating point."""
    p0 = x[f[:, 0]]
    return np.sign(np.einsum("ij,ij->i", np.cross(x[f[:, 1]] - p0, x[f[:, 2]] - p0), x[apex] - p0))


def _volumes(x, T: np.ndarray) -> np.ndarray:
    """Absolute volumes (times 6) of the tetrahedra ``T``, floating point."""
    p0 = x[T[:, 0]]
    u = np.einsum("ij,ij->i", np.cross(x[T[:, 1]] - p0, x[T[:, 2]] - p0), x[T[:, 3]] - p0)
    return np.abs(u)


def _fill_gaps(x, w, simp, nbr, hull_vertices):
    """Fill the gaps between the blocks' tetrahedra: those whose vertices span
    every block's slab (flat tetrahedra on the convex hull where a cut meets it).
    Their vertices are on the open facets or on the hull, so one small Qhull on
    those points contains them; it is flooded from the open facets, across
    facets that are not open.  Returns ``(simp, nbr)`` grown, or ``None`` if the
    flood does not stay small."""
    n = x.shape[0]
    t, i = _pair_facets(simp, nbr, n)
    if t.size == 0:
        return simp, nbr
    cols = np.array([[c for c in range(4) if c != j] for j in range(4)])
    F = np.take_along_axis(simp[t], cols[i], axis=1)
    V = np.unique(np.concatenate([F.ravel(), hull_vertices]))
    res = _lower_hull(x[V], w[V])
    if res is None or res[0].shape[0] == 0:
        return None
    S, SN = V[res[0]].astype(np.int64), res[1]
    m = S.shape[0]
    st = np.repeat(np.arange(m), 4)
    si = np.tile(np.arange(4), m)
    skey = _facet_keys(S, st, si, n)
    okey = _facet_keys(simp, t, i, n)
    order = np.argsort(skey, kind="stable")
    sk = skey[order]
    # for each open facet, the (at most two) small-Qhull tetrahedra on it
    pos = np.searchsorted(sk, okey)
    seeds, links = [], []
    side = _orient(x, F, simp[t, i])
    for off in (0, 1):
        q = pos + off
        ok = q < sk.size
        ok[ok] = sk[q[ok]] == okey[ok]
        g = order[q[ok]]
        ts, ti = st[g], si[g]
        other = _orient(x, F[ok], S[ts, ti]) == -side[ok]
        seeds.append(ts[other])
        links.append((t[ok][other], i[ok][other], ts[other], ti[other]))
    seeds = np.concatenate(seeds)
    if seeds.size == 0:
        return simp, nbr  # only hull facets are open
    openkeys = np.sort(okey)
    # flood the small triangulation across facets that are not open
    inside = np.zeros(m, dtype=bool)
    inside[seeds] = True
    front = np.unique(seeds)
    limit = max(1000, simp.shape[0] // 20)
    while front.size:
        ft = np.repeat(front, 4)
        fi = np.tile(np.arange(4), front.size)
        nb_ = SN[ft, fi]
        k = _facet_keys(S, ft, fi, n)
        p = np.searchsorted(openkeys, k)
        is_open = (p < openkeys.size) & (openkeys[np.minimum(p, openkeys.size - 1)] == k)
        go = (nb_ >= 0) & ~is_open
        nxt = np.unique(nb_[go])
        nxt = nxt[~inside[nxt]]
        inside[nxt] = True
        front = nxt
        if np.count_nonzero(inside) > limit:
            return None
    add = np.flatnonzero(inside)
    # a leak: where the small Qhull's triangulation differs from the blocks' on the
    # gap's boundary (degenerate input: rounded coordinates), the flood runs into the
    # region the blocks cover; the candidate would fail the certificate and its
    # repair grow large (45,000 simplices on the solvated 1tw7 file, 3x the one-block
    # time), so give up at once.  The gap's volume is the hull's (the small Qhull
    # covers it: it holds the blocks' hull vertices) less the blocks' tetrahedra.
    vs, vb = _volumes(x, S), _volumes(x, simp)
    excess = vs[add].sum() - (vs.sum() - vb.sum())
    if excess > tol.BLOCK_GAP_VOLUME * vs.sum():
        return None
    base = simp.shape[0]
    new = np.full(m, -1, dtype=np.int64)
    new[add] = base + np.arange(add.size)
    anb = SN[add]
    anb = np.where(anb >= 0, new[np.maximum(anb, 0)], -1)
    simp = np.concatenate([simp, S[add]])
    nbr = np.concatenate([nbr, anb])
    for lt, li, ts, ti in links:
        nbr[lt, li] = new[ts]
        nbr[new[ts], ti] = lt
    return simp, nbr


def _lex_order(simp: np.ndarray) -> np.ndarray:
    """``np.lexsort(simp.T[::-1])`` for tetrahedra, faster: one argsort of the first
    three vertices packed in an int64 (fewer than 2**21 points); two tetrahedra of a
    triangulation share at most one facet, so rows with equal keys come in pairs,
    ordered by their last vertex."""
    n = int(simp.max()) + 1
    if simp.shape[1] != 4 or n >= 1 << 21:
        return np.lexsort(simp.T[::-1])
    s = simp.astype(np.int64)
    key = (s[:, 0] * n + s[:, 1]) * n + s[:, 2]
    order = np.argsort(key, kind="stable")
    ks = key[order]
    d = np.flatnonzero(ks[1:] == ks[:-1])
    if d.size > 1 and np.any(d[1:] == d[:-1] + 1):  # pragma: no cover - not a triangulation
        return np.lexsort(simp.T[::-1])
    swap = d[simp[order[d], 3] > simp[order[d + 1], 3]]
    order[swap], order[swap + 1] = order[swap + 1], order[swap].copy()
    return order


def _canonical(simp: np.ndarray, nbr: np.ndarray):
    """The rows of ``simp`` (vertices ascending) sorted lexicographically, and the
    neighbour relation ``nbr`` carried along: the certified triangulation is unique,
    so this order depends on the input alone, not on the road (one Qhull, blocks, a
    repair), and every later sum adds in the same order."""
    m = simp.shape[0]
    if m <= 1:
        return simp, nbr
    order = _lex_order(simp)
    inv = np.empty(m, dtype=np.int32)
    inv[order] = np.arange(m, dtype=np.int32)
    nb = nbr[order]
    return np.ascontiguousarray(simp[order]), np.where(nb >= 0, inv[np.maximum(nb, 0)], nb).astype(nbr.dtype)


def _certified_blocks(balls: Balls, fr: _Frame, nb: int):
    """The candidate computed in ``nb`` blocks by threads (:func:`_block_tetrahedra`)
    and certified exactly: ``((simp, nbr, report), "")``, or ``(None, reason)`` if a
    block's Qhull failed or the merged candidate does not pass the certificate (then
    the caller takes the one-block road)."""
    from concurrent.futures import ThreadPoolExecutor

    plan = _block_plan(fr.x, nb)
    with ThreadPoolExecutor(max_workers=nb) as pool:
        parts = list(pool.map(lambda j: _block_tetrahedra(fr.x, fr.w, plan, j), range(nb)))
    if any(p is None for p in parts):
        return None, "Qhull failed in a block"
    if any(isinstance(p, str) for p in parts):
        return None, next(p for p in parts if isinstance(p, str))
    offsets = np.cumsum([0] + [p[0].shape[0] for p in parts])
    simp = np.concatenate([p[0] for p in parts])
    nbr = np.concatenate([np.where(p[1] >= 0, p[1] + o, -1) for p, o in zip(parts, offsets)])
    filled = _fill_gaps(fr.x, fr.w, simp, nbr, np.concatenate([p[2] for p in parts]))
    if filled is None:
        return None, "the gaps between the blocks did not fill"
    simp, nbr = filled
    P = _exact_points(balls, fr)
    order = morton_order(fr.x)
    simp, nbr = simp.astype(np.int32), nbr.astype(np.int32)
    cert = certify(P, simp, nbr, order=order)
    if not cert.ok:
        # degenerate input (rounded coordinates): the local exact repair, as on the
        # one-block road
        fixed = repair(P, simp, nbr, order=order)
        if fixed is None:
            return None, cert.reason + "; the local repair did not certify"
        simp, cert2, info = fixed
        rep = TriangulationReport("repaired", cert.reason, {**P.stats, **info}, blocks=nb)
        return (simp.astype(np.int32), cert2.neighbors, rep), ""
    return (simp.astype(np.int32), cert.neighbors, TriangulationReport("qhull", "", dict(P.stats), blocks=nb)), ""


def _tiebreak_candidate(x: np.ndarray, w: np.ndarray):
    """A second candidate for input whose ties Qhull breaks its own way: the lower
    hull with each lifted height lowered by a small convex decreasing function of the
    point's rank in the tie-break order (the row order of ``x``; tolerance
    ``QHULL_TIEBREAK``).  Like Simulation of Simplicity, it lowers earlier balls more,
    so the ties of a lattice in its input order (co-spherical cubes: one
    diagonal per face) go the same way; :func:`_certified` certifies and repairs it
    like the first one.  Returns ``(simp, nbr, perm)`` or ``None``."""
    n, k = x.shape
    if n <= k + 1:
        return None
    h = np.einsum("ij,ij->i", x, x) - w
    h = h - h.mean()
    hs = float(np.max(np.abs(h)))
    if hs > 0:
        h = h / hs
    h = h - tol.QHULL_TIEBREAK * (1.0 - np.arange(n) / n) ** 2
    perm = morton_order(x)
    try:
        return (*_hull_once(x, h, perm), perm)
    except RuntimeError:
        return None


@dataclass(frozen=True)
class TriangulationReport:
    """How :func:`regular_triangulation` obtained its answer.

    Attributes
    ----------
    method : str
        ``"qhull"`` (Qhull's lower hull passed the exact certificate),
        ``"repaired"`` (it did not; the simplices that failed and their neighbourhood
        were re-triangulated exactly, :func:`shapelab._engine.certify.repair`, and the
        result passed the certificate) or ``"incremental"`` (the local repair did not
        certify either, or Qhull failed, and the exact incremental algorithm of
        :mod:`shapelab._engine.incremental` computed the whole triangulation).
    reason : str
        Why Qhull's answer was rejected ("" if it was not); for ``"incremental"``
        after a failed repair it ends with "the local repair did not certify".
    counts : dict
        Tests decided by the floating-point filter and exactly, ties broken by
        Simulation of Simplicity; after a repair also ``attempts``,
        ``cavity_simplices`` and ``cavity_points`` (the size of the re-triangulated
        region), and ``tiebreak`` (True) when the tie-break candidate was used.
    blocks : int
        How many blocks (threads) Qhull's candidate came from: 1, or for 3D input of
        at least 20,000 balls with ``SHAPELAB_THREADS`` set to 2 or more in the
        environment (opt-in), that many slabs (at most one per 10,000 balls, none
        from 2**21 balls on) along the longest axis, each with a halo, triangulated by
        Qhull in threads and merged; the merged candidate passed the same exact
        certificate (``"qhull"``) or the local repair (``"repaired"``).  The result
        is the same triangulation, rows in the same order.
    blocks_reason : str
        Why a candidate computed in blocks was rejected ("" if none was), after
        which the one-block road above ran.

    See Also
    --------
    triangulation_report
        Produces this report.
    regular_triangulation
        The triangulation it describes.
    """

    method: str
    reason: str
    counts: dict
    blocks: int = 1
    blocks_reason: str = ""


def _exact_points(balls: Balls, fr: _Frame) -> WeightedPoints:
    axes = None if fr.k == balls.dim else fr.axes
    return WeightedPoints(balls.centers[fr.keep], balls.radii[fr.keep], axes=axes, priority=fr.keep)


def _certified(balls: Balls, fr: _Frame):
    """Top simplices (local indices), neighbours and the report."""
    P = _exact_points(balls, fr)
    lattice = fr.k == balls.dim and _on_a_lattice(balls.centers, fr.keep)
    if lattice:
        fixed = _tiebreak_repair(P, fr)
        if fixed is not None:  # ties everywhere: the tie-break candidate first
            simp, cert, info = fixed
            rep = TriangulationReport("qhull", "", {**P.stats, **info})
            if info["attempts"]:
                why = "the centres lie on a lattice; the tie-break candidate failed the certificate"
                rep = TriangulationReport("repaired", why, rep.counts)
            return simp.astype(np.int32), cert.neighbors, rep
    cand = _lower_hull(fr.x, fr.w)
    reason = "Qhull failed"
    if cand is not None:
        simp, nbr, perm = cand
        if simp.shape[0] == 0:
            # nearly flat centres: every lower facet of the lifted points looked
            # vertical to Qhull (the exact dimension is k, so DT is not empty)
            reason = "Qhull's lower hull is empty"
        else:
            cert = certify(P, simp, nbr, order=perm)
            if cert.ok:
                return simp.astype(np.int32), cert.neighbors, TriangulationReport("qhull", "", dict(P.stats))
            reason = cert.reason
            fixed = _tiebreak_repair(P, fr, simp, nbr, perm, tiebreak=not lattice)
            if fixed is not None:
                simp, cert, info = fixed
                counts = {**P.stats, **info}
                return simp.astype(np.int32), cert.neighbors, TriangulationReport("repaired", reason, counts)
            reason += "; the local repair did not certify"
    order = np.argsort(fr.x[:, 0], kind="stable") if fr.k == 1 else morton_order(fr.x, min_n=0)
    simp = incremental_triangulation(P, order).astype(np.int32)
    nbr, _ = facet_adjacency(simp)
    return simp, nbr, TriangulationReport("incremental", reason, dict(P.stats))


def _on_a_lattice(centers: np.ndarray, keep: np.ndarray) -> bool:
    """True when the centres take so few distinct values along each axis that they
    fill a good part of the product of those values (a grid): many power tests are
    then ties, and Qhull's candidate fails everywhere.  A sample can reject first.
    Only a guess: a wrong one costs a Qhull call and a certificate (then the usual
    road)."""
    c = centers[keep] if keep.size != centers.shape[0] else centers
    for rows in (c[:512], c):
        prod = 1
        for a in range(c.shape[1]):
            prod *= np.unique(rows[:, a]).size
        if prod > LATTICE_FILL * rows.shape[0]:
            return False
    return True


def _tiebreak_repair(P: WeightedPoints, fr: _Frame, simp=None, nbr=None, perm=None, tiebreak=True):
    """The repair of a rejected candidate ``simp`` (if given): locally if few
    simplices fail; otherwise (ties everywhere: grids, cages), unless ``tiebreak`` is
    False (tried already), from the candidate of :func:`_tiebreak_candidate`,
    certified, then repaired locally.  ``(simp, cert, info)`` or ``None``."""
    if simp is not None:
        fixed = repair(P, simp, nbr, order=perm, start=1, max_failing=TIEBREAK_FAILING)
        if fixed is not None:
            return fixed
    if not tiebreak:
        return None
    cand = _tiebreak_candidate(fr.x, fr.w)
    if cand is None or cand[0].shape[0] == 0:
        return None
    simp2, nbr2, perm2 = cand
    cert = certify(P, simp2, nbr2, order=perm2)
    if cert.ok:
        return simp2, cert, {"attempts": 0, "cavity_simplices": 0, "cavity_points": 0, "tiebreak": True}
    fixed = repair(P, simp2, nbr2, order=perm2, start=1)
    if fixed is not None:
        fixed[2]["tiebreak"] = True
    return fixed


def triangulate_local(balls: Balls, report: bool = False):
    """Frame, top simplices in frame-local indices and their neighbours (and, with
    ``report``, the :class:`TriangulationReport`).  Shared with
    :mod:`shapelab._engine.alpha`, which builds the filtration in the same frame."""
    fr = _frame(balls)
    rep = TriangulationReport("trivial", "", {})
    if fr.k < 0:
        out = fr, np.zeros((0, 1), dtype=np.int32), np.zeros((0, 1), dtype=np.int32)
    elif fr.k == 0:  # one distinct centre: keep[0] is the largest ball there
        out = fr, np.zeros((1, 1), dtype=np.int32), np.full((1, 1), -1, dtype=np.int32)
    else:
        nb = _block_count(fr.keep.size, fr.k)
        if nb > 1 and _on_a_lattice(balls.centers, fr.keep):
            nb = 1  # ties everywhere: the tie-break candidate of one block comes first
        got, why = _certified_blocks(balls, fr, nb) if nb > 1 else (None, "")
        if got is not None:
            simp, nbr, rep = got
        else:
            simp, nbr, rep = _certified(balls, fr)
            if why:
                rep = TriangulationReport(rep.method, rep.reason, rep.counts, blocks_reason=why)
        out = fr, *_canonical(simp, nbr)
    return (*out, rep) if report else out


def triangulate(balls: Balls):
    """Frame and top simplices (input indices, rows ascending, lexsorted)."""
    fr, simp, _ = triangulate_local(balls)
    tri = fr.keep[simp].astype(np.int64)
    tri.sort(axis=1)
    if tri.shape[0] > 1:
        tri = tri[np.lexsort(tri.T[::-1])]
    return fr, tri


def orthocentres(balls: Balls, tri: np.ndarray) -> np.ndarray:
    """Orthocentres of full-dimensional simplices, in input coordinates."""
    if tri.shape[0] == 0 or tri.shape[1] != balls.dim + 1:
        return np.zeros((0, balls.dim))
    origin = balls.centers.mean(axis=0)
    z = balls.centers - origin
    w = balls.weights
    p0 = z[tri[:, 0]]
    A = z[tri[:, 1:]] - p0[:, None, :]
    b = 0.5 * (np.einsum("mjk,mjk->mj", A, A) - w[tri[:, 1:]] + w[tri[:, :1]])
    # A sliver (a hull triangle over points collinear up to round-off, which the exact
    # triangulation keeps) has a nearly singular A: its orthocentre is far away and is
    # computed in rational arithmetic.  Other rows: float, with a relative
    # condition guard of 1e-8 (error ~1e-8 of the vertex's distance at worst).
    det = np.linalg.det(A)
    scale = np.prod(np.linalg.norm(A, axis=2), axis=1)
    bad = ~(np.abs(det) > tol.ORTHOCENTRE_CONDITION * scale)
    u = np.empty_like(p0)
    good = ~bad
    if good.any():
        u[good] = np.linalg.solve(A[good], b[good][..., None])[..., 0]
    for t in np.flatnonzero(bad):
        u[t] = _orthocentre_exact(balls, tri[t]) - origin - p0[t]
    return p0 + u + origin


def _orthocentre_exact(balls: Balls, row) -> np.ndarray:
    """The orthocentre of one full-dimensional simplex in rationals, rounded once:
    the solution c of :math:`2(z_j - z_0)\\cdot c = |z_j|^2 - |z_0|^2 - w_j + w_0`."""
    from fractions import Fraction

    Z = [[Fraction(float(v)) for v in balls.centers[i]] for i in row]
    W = [Fraction(float(r)) ** 2 for r in balls.radii[row]]
    d = len(Z[0])
    M = [[2 * (Z[j][a] - Z[0][a]) for a in range(d)] for j in range(1, d + 1)]
    rhs = [sum(v * v for v in Z[j]) - sum(v * v for v in Z[0]) - W[j] + W[0] for j in range(1, d + 1)]
    D = det(M)
    if D == 0:  # pragma: no cover - a certified triangulation has no flat simplex
        raise ValueError("a flat simplex has no orthocentre")
    out = []
    for a in range(d):
        Ma = [r[:a] + [rhs[j]] + r[a + 1 :] for j, r in enumerate(M)]
        out.append(float(det(Ma) / D))
    return np.array(out)
