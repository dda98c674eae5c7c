"""Critical points of the distance from a viewpoint (notes §23.2, Figure 23.3).

The notes characterise a closed curve C by a viewpoint S and the function

.. math:: F : C \\to \\mathbb{R}, \\qquad F(x) = |x - S|,

whose maxima and minima they call the *critical points* of C; "in 3D the
critical points consist of minima, maxima, and saddle points".  This module
computes them for

* closed **polylines** (exactly: F is convex on every segment, so the maxima sit
  at vertices and a minimum is either a vertex or the foot of the perpendicular
  from S inside a segment),
* closed **parametric curves** ``t -> (x(t), y(t))`` of period 2π (dense sampling,
  then a bracketed root of dF²/dt: exact to round-off on circles and ellipses),
* closed **triangulated surfaces** in 3D (Banchoff's lower-link rule for the
  piecewise-linear extension of F, ties broken by vertex index), where the
  counts obey ``#min - #saddles + #max = χ`` (Euler characteristic),

plus a :func:`signature` and :func:`compare` to compare shapes by their critical
points, and small mesh/curve generators for tests and lessons.

Where the notes are imprecise
-----------------------------
* "Critical points" are defined as the maxima and minima of F, but F is not
  differentiable at the vertices of a polyline (nor at S), so "critical" must be
  read as "local extremum"; on a polyline the minima are often *inside* edges,
  at the foot of the perpendicular from S, while maxima are always at vertices.
* If C is a circle centred at S, F is constant: every point is a (non-isolated)
  extremum and the characterisation says nothing.  :func:`critical_points`
  reports no points and ``degenerate=True`` in that case.
* S "in the area bounded by C" is not needed: F and its extrema are defined for
  any S; only the picture of rays from an interior S to the extrema needs it.
* In 3D the surface must be closed (a 2-manifold) for the count
  ``#min - #saddles + #max = χ`` to hold, and saddles can be *monkey saddles*
  that count with multiplicity k - 1 (k arcs in the lower link).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit import tolerances as tol
from ._toolkit.validate import as_finite_scalar, as_point, as_points, as_positive_int

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = [
    "CriticalPoints",
    "critical_points",
    "Signature",
    "signature",
    "compare",
    "distance_along",
    "polyline",
    "euler_characteristic",
]

_TWO_PI = 2.0 * np.pi


@dataclass(frozen=True, eq=False)
class CriticalPoints:
    """The critical points of ``F(x) = |x - S|`` on a closed curve or surface.

    Attributes
    ----------
    source : str
        ``"polyline"``, ``"parametric"`` or ``"surface"``.
    viewpoint : ndarray, shape (d,)
        The viewpoint S.
    positions : ndarray, shape (k, d)
        The critical points, in order along the curve (by parameter) or by
        vertex index on a surface.
    values : ndarray, shape (k,)
        ``F`` at each critical point.
    kinds : ndarray of str, shape (k,)
        ``"min"``, ``"max"`` or ``"saddle"``.
    parameters : ndarray, shape (k,)
        Polyline: arc-length fraction in [0, 1) from the first vertex.
        Parametric curve: t in [0, 2π).  Surface: the vertex index (as float).
    indices : ndarray of int, shape (k,)
        Polyline: the index of the vertex, or of the first vertex of the segment
        for a minimum inside a segment.  Surface: the vertex index.  Parametric
        curve: -1.
    interior : ndarray of bool, shape (k,)
        Polyline: the point lies strictly inside a segment (always a minimum).
    multiplicities : ndarray of int, shape (k,)
        1, except for a surface saddle whose lower link has k >= 3 arcs
        (a monkey saddle counts k - 1 times).
    degenerate : bool
        F is constant (a circle centred at S): every point is an extremum and
        none is reported.

    See Also
    --------
    critical_points
        Produces it.
    """

    source: str
    viewpoint: np.ndarray
    positions: np.ndarray
    values: np.ndarray
    kinds: np.ndarray
    parameters: np.ndarray
    indices: np.ndarray
    interior: np.ndarray
    multiplicities: np.ndarray
    degenerate: bool = False

    @property
    def minima(self) -> np.ndarray:
        """Positions of the minima."""
        return self.positions[self.kinds == "min"]

    @property
    def maxima(self) -> np.ndarray:
        """Positions of the maxima."""
        return self.positions[self.kinds == "max"]

    @property
    def saddles(self) -> np.ndarray:
        """Positions of the saddles (surfaces only)."""
        return self.positions[self.kinds == "saddle"]

    @property
    def n_min(self) -> int:
        return int(np.count_nonzero(self.kinds == "min"))

    @property
    def n_max(self) -> int:
        return int(np.count_nonzero(self.kinds == "max"))

    @property
    def n_saddle(self) -> int:
        """Saddles counted with multiplicity."""
        return int(self.multiplicities[self.kinds == "saddle"].sum())

    @property
    def euler_characteristic(self) -> int:
        """The Morse count of χ: ``#min - #max`` on a closed curve (always 0, a
        circle's χ) and ``#min - #saddles + #max`` on a closed surface."""
        if self.source == "surface":
            return self.n_min - self.n_saddle + self.n_max
        return self.n_min - self.n_max

    def __len__(self) -> int:
        return int(self.values.size)

    def __repr__(self) -> str:
        extra = f", {self.n_saddle} saddle(s)" if self.source == "surface" else ""
        deg = ", degenerate (F constant)" if self.degenerate else ""
        return (
            f"CriticalPoints({self.source}: {self.n_min} min, {self.n_max} max{extra}, "
            f"χ = {self.euler_characteristic}{deg})"
        )


def _result(source, S, pos, val, kinds, par, idx, interior=None, mult=None, degenerate=False):
    order = np.argsort(par, kind="stable")
    k = len(val)
    return CriticalPoints(
        source=source,
        viewpoint=S,
        positions=np.asarray(pos, dtype=float).reshape(k, S.size)[order],
        values=np.asarray(val, dtype=float)[order],
        kinds=np.asarray(kinds, dtype="<U6")[order],
        parameters=np.asarray(par, dtype=float)[order],
        indices=np.asarray(idx, dtype=np.intp)[order],
        interior=(np.zeros(k, dtype=bool) if interior is None else np.asarray(interior, dtype=bool))[order],
        multiplicities=(np.ones(k, dtype=np.intp) if mult is None else np.asarray(mult, dtype=np.intp))[order],
        degenerate=degenerate,
    )


# --------------------------------------------------------------------------- #
# Polylines                                                                    #
# --------------------------------------------------------------------------- #
def closed_vertices(curve, close: bool) -> tuple[np.ndarray, np.ndarray]:
    """The distinct cyclic vertices of a closed polyline, with their original indices."""
    P = as_points(curve, "curve", dim=(2, 3), min_points=2)
    if close:
        if not np.array_equal(P[0], P[-1]):
            P = np.vstack([P, P[:1]])
    elif not np.array_equal(P[0], P[-1]):
        raise ValueError(
            "curve must be closed: repeat the first point at the end "
            f"(first point {P[0].tolist()}, last point {P[-1].tolist()}), or pass close=True"
        )
    V = P[:-1]
    idx = np.arange(V.shape[0])
    # drop repeated consecutive vertices (zero-length segments), cyclically
    keep = np.any(V != np.roll(V, 1, axis=0), axis=1)
    if not keep.any():
        keep[0] = True
    V, idx = V[keep], idx[keep]
    if V.shape[0] < 3:
        raise ValueError(f"curve must have at least 3 distinct vertices, got {V.shape[0]}")
    return V, idx


def _polyline_critical(curve, S: np.ndarray, close: bool) -> CriticalPoints:
    V, orig = closed_vertices(curve, close)
    if S.size != V.shape[1]:
        raise ValueError(f"viewpoint must have {V.shape[1]} coordinates like curve, got {S.size}")
    E = np.roll(V, -1, axis=0) - V  # segment i: V[i] -> V[i+1]
    R = V - S  # from S to each vertex
    L = np.sqrt(np.einsum("ij,ij->i", E, E))
    cum = np.concatenate([[0.0], np.cumsum(L)])
    total = cum[-1]
    fwd = np.einsum("ij,ij->i", R, E)  # dF²/ds along segment i at its start
    bwd = np.einsum("ij,ij->i", R, np.roll(E, 1, axis=0))  # along segment i-1 at its end
    at_s = ~np.any(R != 0, axis=1)
    # F² is a strictly convex quadratic on each segment, so a zero one-sided
    # derivative still means "increasing away from the vertex".
    inc_fwd = fwd >= 0
    inc_bwd = bwd <= 0
    vmin = (inc_fwd & inc_bwd) | at_s
    vmax = (~inc_fwd) & (~inc_bwd) & ~at_s
    tau = -fwd / (L * L)
    smin = (tau > 0) & (tau < 1)
    pos, val, kinds, par, idx, interior = [], [], [], [], [], []
    for mask, kind in ((vmin, "min"), (vmax, "max")):
        i = np.flatnonzero(mask)
        pos.append(V[i])
        val.append(np.sqrt(np.einsum("ij,ij->i", R[i], R[i])))
        kinds += [kind] * i.size
        par.append(cum[i] / total)
        idx.append(orig[i])
        interior.append(np.zeros(i.size, dtype=bool))
    i = np.flatnonzero(smin)
    X = V[i] + tau[i, None] * E[i]
    D = X - S
    pos.append(X)
    val.append(np.sqrt(np.einsum("ij,ij->i", D, D)))
    kinds += ["min"] * i.size
    par.append((cum[i] + tau[i] * L[i]) / total)
    idx.append(orig[i])
    interior.append(np.ones(i.size, dtype=bool))
    return _result(
        "polyline",
        S,
        np.concatenate(pos),
        np.concatenate(val),
        kinds,
        np.concatenate(par),
        np.concatenate(idx),
        np.concatenate(interior),
    )


# --------------------------------------------------------------------------- #
# Parametric curves                                                            #
# --------------------------------------------------------------------------- #
def _evaluate(fn: Callable, t: np.ndarray, dim: int | None = None) -> np.ndarray:
    """``fn`` at the parameters ``t`` as an (len(t), d) array.

    ``fn`` may be vectorised (returning ``(x, y)`` arrays, i.e. shape (d, n)) or
    scalar (returning one point per call).
    """
    t = np.asarray(t, dtype=float)
    try:
        if t.size == 1:
            # one parameter: call with a float, which suits both kinds of function (a
            # scalar one given a 1-element array converts it with a DeprecationWarning)
            raise ValueError
        out = np.asarray(fn(t), dtype=float)
        if out.ndim == 2 and out.shape[1] == t.size and (dim is None or out.shape[0] == dim) and t.size != out.shape[0]:
            out = out.T
        elif out.ndim == 2 and out.shape == (t.size, t.size):
            raise ValueError  # ambiguous: fall back to one call per parameter
        elif not (out.ndim == 2 and out.shape[0] == t.size):
            raise ValueError
    except Exception:
        try:
            out = np.array([np.asarray(fn(float(s)), dtype=float).ravel() for s in t])
        except Exception as exc:
            raise ValueError(f"curve(t) failed: {type(exc).__name__}: {exc}") from None
    if out.ndim != 2 or out.shape[1] not in (2, 3):
        raise ValueError(f"curve(t) must return a point with 2 or 3 coordinates, got shape {out.shape[1:]}")
    if not np.all(np.isfinite(out)):
        raise ValueError("curve(t) returned a non-finite value")
    return out


def _parametric_critical(fn: Callable, S: np.ndarray, n_samples: int) -> CriticalPoints:
    from scipy.optimize import brentq, minimize_scalar

    t = np.arange(n_samples) * (_TWO_PI / n_samples)
    X = _evaluate(fn, t)
    dim = X.shape[1]
    if S.size != dim:
        raise ValueError(f"viewpoint must have {dim} coordinates like curve(t), got {S.size}")
    # periodicity check: x(2π) must equal x(0)
    end = _evaluate(fn, np.array([_TWO_PI]), dim)[0]
    scale = float(np.abs(X).max()) + 1.0
    if np.abs(end - X[0]).max() > tol.CURVE_CLOSED * scale:
        raise ValueError("curve must be closed: curve(2π) differs from curve(0); parametrise it on [0, 2π)")

    def F(s):
        return float(np.sqrt(np.sum((_evaluate(fn, np.atleast_1d(s), dim)[0] - S) ** 2)))

    Fk = np.sqrt(np.sum((X - S) ** 2, axis=1))
    spread = Fk.max() - Fk.min()
    if spread <= tol.CURVE_FLAT * max(Fk.max(), tol.UNDERFLOW_FLOOR):
        empty = np.empty((0, dim))
        return _result("parametric", S, empty, [], [], [], [], degenerate=True)
    h = tol.CURVE_STEP

    def g(s):  # d/dt of F²/2 = (x(t) - S) . x'(t), x' by a 4th-order central difference
        pts = _evaluate(fn, s + h * np.array([-2.0, -1.0, 0.0, 1.0, 2.0]), dim)
        dx = (pts[0] - 8 * pts[1] + 8 * pts[3] - pts[4]) / (12 * h)
        return float(np.dot(pts[2] - S, dx))

    prev, nxt = np.roll(Fk, 1), np.roll(Fk, -1)
    found = []
    for kind, mask in (("min", (Fk < prev) & (Fk <= nxt)), ("max", (Fk > prev) & (Fk >= nxt))):
        for k in np.flatnonzero(mask):
            a, b = t[k] - _TWO_PI / n_samples, t[k] + _TWO_PI / n_samples
            ga, gb = g(a), g(b)
            sign = 1.0 if kind == "min" else -1.0
            if sign * ga < 0 < sign * gb:
                s = brentq(g, a, b, xtol=tol.CURVE_ROOT_XTOL, rtol=4 * np.finfo(float).eps, maxiter=200)
            else:
                res = minimize_scalar(
                    lambda x, sign=sign: sign * F(x),
                    bounds=(a, b),
                    method="bounded",
                    options={"xatol": tol.CURVE_MIN_XATOL},
                )
                s = float(res.x)
            if sign * F(s) > sign * Fk[k]:  # never worse than the sample
                s = float(t[k])
            s = s % _TWO_PI
            if _TWO_PI - s < tol.CURVE_WRAP:  # round-off just below 2π is t = 0
                s = 0.0
            found.append((s, kind))
    found.sort()
    # merge duplicates (a refined extremum found from two neighbouring samples)
    merged = []
    for s, kind in found:
        if merged and merged[-1][1] == kind and abs(s - merged[-1][0]) < tol.CURVE_MERGE:
            continue
        merged.append((s, kind))
    if (
        len(merged) > 1
        and merged[0][1] == merged[-1][1]
        and abs(merged[0][0] + _TWO_PI - merged[-1][0]) < tol.CURVE_MERGE
    ):
        merged.pop()
    ts = np.array([s for s, _ in merged])
    pos = _evaluate(fn, ts, dim) if ts.size else np.empty((0, dim))
    val = np.sqrt(np.sum((pos - S) ** 2, axis=1))
    return _result("parametric", S, pos, val, [k for _, k in merged], ts, -np.ones(ts.size, dtype=np.intp))


# --------------------------------------------------------------------------- #
# Surfaces                                                                     #
# --------------------------------------------------------------------------- #
def _as_faces(faces, n_vertices: int) -> np.ndarray:
    if isinstance(faces, (str, bytes)):
        raise TypeError(f"faces must be an integer array of shape (f, 3), got {type(faces).__name__}")
    arr = np.asarray(faces)
    if arr.dtype.kind not in "iu":
        if arr.dtype.kind == "f" and arr.size and np.all(np.isfinite(arr)) and np.all(arr == np.round(arr)):
            arr = arr.astype(np.intp)
        else:
            raise TypeError(f"faces must hold integer vertex indices, got dtype {arr.dtype}")
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"faces must have shape (f, 3), got {arr.shape}")
    if arr.shape[0] < 4:
        raise ValueError(f"faces must describe a closed surface (at least 4 triangles), got {arr.shape[0]}")
    arr = arr.astype(np.intp)
    if arr.min() < 0 or arr.max() >= n_vertices:
        raise ValueError(f"faces must index vertices 0..{n_vertices - 1}, got values in [{arr.min()}, {arr.max()}]")
    if np.any((arr[:, 0] == arr[:, 1]) | (arr[:, 1] == arr[:, 2]) | (arr[:, 0] == arr[:, 2])):
        raise ValueError("faces must not repeat a vertex within a triangle")
    return arr


def _edges(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Undirected edges (sorted pairs, unique) and how many faces hold each."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    e.sort(axis=1)
    uniq, inverse, counts = np.unique(e, axis=0, return_inverse=True, return_counts=True)
    return uniq, counts, inverse.ravel()


def _check_closed_manifold(faces: np.ndarray, n_vertices: int) -> tuple[int, int]:
    """Raise unless ``faces`` is a closed 2-manifold using every vertex; return (E, V)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    edges, counts, inverse = _edges(faces)
    if np.any(counts != 2):
        bad = edges[np.flatnonzero(counts != 2)[0]]
        c = counts[np.flatnonzero(counts != 2)[0]]
        raise ValueError(
            f"faces must form a closed surface: every edge must bound exactly 2 triangles, "
            f"but edge {bad.tolist()} bounds {c}"
        )
    used = np.zeros(n_vertices, dtype=bool)
    used[faces.ravel()] = True
    if not used.all():
        raise ValueError(f"vertices[{int(np.flatnonzero(~used)[0])}] is not used by any face")
    # Each vertex's star must be one disk: its corners (face, vertex) are connected
    # through the edges at the vertex.  Corner id = 3 * face + position.
    F = faces.shape[0]
    nE = edges.shape[0]
    # for each edge, the two (face, position) pairs of its endpoints in each face
    pos_a = np.concatenate([np.zeros(F), np.ones(F), 2 * np.ones(F)]).astype(np.intp)
    pos_b = np.concatenate([np.ones(F), 2 * np.ones(F), np.zeros(F)]).astype(np.intp)
    face_of = np.tile(np.arange(F), 3)
    order = np.argsort(inverse, kind="stable")  # the two occurrences of each edge are adjacent
    o1, o2 = order[0::2], order[1::2]
    rows, cols = [], []
    for p1 in (pos_a, pos_b):
        for p2 in (pos_a, pos_b):
            v1 = faces[face_of[o1], p1[o1]]
            v2 = faces[face_of[o2], p2[o2]]
            same = v1 == v2
            rows.append(3 * face_of[o1][same] + p1[o1][same])
            cols.append(3 * face_of[o2][same] + p2[o2][same])
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    graph = coo_matrix((np.ones(rows.size), (rows, cols)), shape=(3 * F, 3 * F))
    n_comp, labels = connected_components(graph, directed=False)
    if n_comp != n_vertices:
        # find a vertex whose corners fall into several components
        corner_vertex = faces.ravel()
        lab = labels[np.arange(3 * F)]
        pairs = np.unique(np.stack([corner_vertex, lab], axis=1), axis=0)
        v, c = np.unique(pairs[:, 0], return_counts=True)
        bad = int(v[np.argmax(c)])
        raise ValueError(
            f"faces must form a 2-manifold: the triangles around vertex {bad} do not form a single disk "
            "(a pinched vertex)"
        )
    return nE, n_vertices


def euler_characteristic(vertices: ArrayLike, faces: ArrayLike) -> int:
    """χ = V - E + F of a closed triangulated surface (2 for a sphere, 0 for a torus).

    An independent check of the critical-point count of :func:`critical_points`.

    See Also
    --------
    critical_points
        Minima minus saddles plus maxima equal χ (Morse).

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> from shapelab.datasets import torus
    >>> V, T = torus(24, 12)
    >>> euler_characteristic(V, T)
    0
    >>> import numpy as np
    >>> # the boundary of a tetrahedron, a sphere
    >>> euler_characteristic(np.eye(4)[:, :3], [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    2
    """
    V = as_points(vertices, "vertices", dim=3, min_points=4)
    Fc = _as_faces(faces, V.shape[0])
    nE, nV = _check_closed_manifold(Fc, V.shape[0])
    return int(nV - nE + Fc.shape[0])


def _surface_critical(vertices, faces, S: np.ndarray) -> CriticalPoints:
    V = as_points(vertices, "vertices", dim=3, min_points=4)
    if S.size != 3:
        raise ValueError(f"viewpoint must have 3 coordinates like vertices, got {S.size}")
    Fc = _as_faces(faces, V.shape[0])
    _check_closed_manifold(Fc, V.shape[0])
    n = V.shape[0]
    D = V - S
    height = np.sqrt(D[:, 0] * D[:, 0] + D[:, 1] * D[:, 1] + D[:, 2] * D[:, 2])
    # simulation of simplicity: order by (F, index); rank is a strict total order
    rank = np.empty(n, dtype=np.intp)
    rank[np.lexsort((np.arange(n), height))] = np.arange(n)
    deg = np.zeros(n, dtype=np.intp)
    both_low = np.zeros(n, dtype=np.intp)
    both_up = np.zeros(n, dtype=np.intp)
    mixed = np.zeros(n, dtype=np.intp)
    for c in range(3):  # corner c of every face; its link edge joins the other two
        v, x, y = Fc[:, c], Fc[:, (c + 1) % 3], Fc[:, (c + 2) % 3]
        lx, ly = rank[x] < rank[v], rank[y] < rank[v]
        deg += np.bincount(v, minlength=n)
        both_low += np.bincount(v, weights=lx & ly, minlength=n).astype(np.intp)
        both_up += np.bincount(v, weights=~lx & ~ly, minlength=n).astype(np.intp)
        mixed += np.bincount(v, weights=lx ^ ly, minlength=n).astype(np.intp)
    is_min = both_up == deg
    is_max = both_low == deg
    arcs = mixed // 2  # each arc of the lower link has two ends on mixed link edges
    is_saddle = ~is_min & ~is_max & (arcs >= 2)
    idx = np.flatnonzero(is_min | is_max | is_saddle)
    kinds = np.where(is_min[idx], "min", np.where(is_max[idx], "max", "saddle"))
    mult = np.where(is_saddle[idx], arcs[idx] - 1, 1)
    return _result("surface", S, V[idx], height[idx], kinds, idx.astype(float), idx, mult=mult)


# --------------------------------------------------------------------------- #
# Public entry point                                                           #
# --------------------------------------------------------------------------- #
def critical_points(
    curve: ArrayLike | Callable[[np.ndarray], ArrayLike],
    viewpoint: ArrayLike,
    *,
    faces: ArrayLike | None = None,
    close: bool = False,
    n_samples: int = 4096,
) -> CriticalPoints:
    """Minima and maxima (and saddles) of F(x) = |x - S| (notes §23.2, Figure 23.3).

    Parameters
    ----------
    curve : array_like or callable
        One of

        * an (n, 2) or (n, 3) **closed polyline**: the first point repeated at the
          end (or pass ``close=True`` to have it appended);
        * a **parametric curve**: a callable ``t -> (x(t), y(t))`` of period 2π,
          vectorised (``t`` an array, returning the coordinate arrays) or scalar;
        * the (n, 3) **vertices** of a closed triangulated surface, with ``faces``.
    viewpoint : array_like, shape (d,)
        The viewpoint S.  It need not lie inside the curve.
    faces : array_like of int, shape (f, 3), optional
        Triangles of a closed surface (every edge in exactly two triangles, every
        vertex's triangles forming one disk).
    close : bool
        Polylines only: append the first point if the last one differs.
    n_samples : int
        Parametric curves only: samples of [0, 2π) used to bracket the extrema;
        two extrema closer than 2π / n_samples may be missed.

    Returns
    -------
    CriticalPoints

    Raises
    ------
    ValueError
        A polyline that is not closed, fewer than 3 distinct vertices, a
        non-finite coordinate, a viewpoint of the wrong dimension, or faces that
        do not form a closed surface (the message names the argument).

    See Also
    --------
    signature
        A scale-invariant summary of the critical values.
    euler_characteristic
        The alternating count the critical points obey.

    Notes
    -----
    *Polylines.*  ``F²`` restricted to a segment is a strictly convex quadratic,
    so F is strictly convex on each segment: maxima are at vertices where F
    decreases into both segments; minima are at vertices where it increases into
    both, or at the foot of the perpendicular from S when that foot lies strictly
    inside a segment.  Minima and maxima alternate, so there are as many of each.
    F is not differentiable at vertices: "critical" means "local extremum".

    *Parametric curves.*  Local extrema of F on the samples are refined to roots
    of ``d(F²/2)/dt = (x(t) - S)·x'(t)`` (brentq, derivative by a 4th-order
    finite difference), exact to round-off on circles and ellipses.  If F is
    constant (a circle centred at S) every point is critical: none is returned
    and ``degenerate`` is True.

    *Surfaces.*  F is extended linearly over the triangles and ties are broken
    by vertex index (simulation of simplicity).  A vertex is a minimum if no
    neighbour is lower, a maximum if all are, regular if the lower neighbours form
    one arc of the link, and a saddle of multiplicity k - 1 if they form k >= 2
    arcs (Banchoff).  Then ``#min - #saddles + #max = χ`` (2 for a sphere, 0 for a
    torus), checked by :attr:`CriticalPoints.euler_characteristic`.

    References
    ----------
    .. [1] J. Milnor, *Morse Theory*, Annals of Mathematics Studies 51, Princeton
           University Press, 1963.
    .. [2] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> import numpy as np
    >>> from shapelab.datasets import ellipse_curve
    >>> # seen from its centre, an ellipse has two minima (the ends of the minor axis) and two maxima
    >>> cp = critical_points(ellipse_curve(2.0, 1.0), [0.0, 0.0])
    >>> cp.n_min, cp.n_max, np.round(np.sort(cp.values), 6).tolist()
    (2, 2, [1.0, 1.0, 2.0, 2.0])
    """
    if faces is not None:
        S = as_point(viewpoint, "viewpoint")
        return _surface_critical(curve, faces, S)
    if callable(curve):
        S = as_point(viewpoint, "viewpoint", dim=(2, 3))
        n_samples = as_positive_int(n_samples, "n_samples", minimum=16)
        return _parametric_critical(curve, S, n_samples)
    S = as_point(viewpoint, "viewpoint", dim=(2, 3))
    return _polyline_critical(curve, S, bool(close))


def distance_along(
    curve: ArrayLike | Callable[[np.ndarray], ArrayLike], viewpoint: ArrayLike, *, n: int = 1000, close: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """F along the curve, for plots of F against the parameter.

    Returns ``(parameters, values)``: for a polyline, arc-length fractions in
    [0, 1] (n points, uniformly in arc length, plus every vertex); for a
    parametric curve, t in [0, 2π] (n + 1 points).

    See Also
    --------
    critical_points
        The extrema of this function.

    Examples
    --------
    >>> import numpy as np
    >>> from shapelab.datasets import ellipse_curve
    >>> t, F = distance_along(ellipse_curve(2.0, 1.0), [0.0, 0.0], n=8)
    >>> np.round(t[:3], 4).tolist(), np.round(F[:3], 4).tolist()
    ([0.0, 0.7854, 1.5708], [2.0, 1.5811, 1.0])
    """
    n = as_positive_int(n, "n", minimum=2)
    if callable(curve):
        S = as_point(viewpoint, "viewpoint", dim=(2, 3))
        t = np.linspace(0.0, _TWO_PI, n + 1)
        X = _evaluate(curve, t)
        return t, np.sqrt(np.sum((X - S) ** 2, axis=1))
    S = as_point(viewpoint, "viewpoint", dim=(2, 3))
    V, _ = closed_vertices(curve, close)
    P = np.vstack([V, V[:1]])
    L = np.sqrt(np.sum(np.diff(P, axis=0) ** 2, axis=1))
    cum = np.concatenate([[0.0], np.cumsum(L)])
    s = np.union1d(np.linspace(0.0, cum[-1], n), cum)
    X = np.column_stack([np.interp(s, cum, P[:, k]) for k in range(P.shape[1])])
    return s / cum[-1], np.sqrt(np.sum((X - S) ** 2, axis=1))


# --------------------------------------------------------------------------- #
# Signatures                                                                   #
# --------------------------------------------------------------------------- #
@dataclass(frozen=True, eq=False)
class Signature:
    """A scale-invariant summary of the critical points of a shape.

    Attributes
    ----------
    kinds : tuple of str
        Curves: the kinds in order along the curve, starting at the global
        maximum.  Surfaces: sorted by value.
    values : ndarray
        The values F divided by the global maximum, in the same order.
    cyclic : bool
        True for curves (the sequence is cyclic and may be read backwards).

    See Also
    --------
    signature
        Produces it.
    """

    kinds: tuple
    values: np.ndarray
    cyclic: bool

    def __repr__(self) -> str:
        pairs = ", ".join(f"{k} {v:.3f}" for k, v in zip(self.kinds, self.values))
        return f"Signature({pairs})"


def _cancel_pairs(kinds: list, vals: list, tolerance: float) -> tuple[list, list]:
    """Cancel adjacent min-max pairs of a cyclic alternating sequence whose values
    differ by less than ``tolerance``, the closest pair first (1D persistence
    simplification: removing the closest pair keeps the sequence alternating
    and every remaining point an extremum)."""
    kinds, vals = list(kinds), list(vals)
    while len(vals) > 2:
        gaps = [abs(vals[i] - vals[(i + 1) % len(vals)]) for i in range(len(vals))]
        i = int(np.argmin(gaps))
        if gaps[i] >= tolerance:
            break
        j = (i + 1) % len(vals)
        for k in sorted((i, j), reverse=True):
            del kinds[k], vals[k]
    return kinds, vals


def signature(result: CriticalPoints, *, tolerance: float = 0.0) -> Signature:
    """The signature of a shape seen from its viewpoint: normalised critical values.

    Parameters
    ----------
    result : CriticalPoints
    tolerance : float
        Curves only: first cancel neighbouring min-max pairs whose normalised
        values differ by less than this (small wiggles, e.g. the extra pairs a
        coarse polyline or noise creates), the closest pair first.

    Returns
    -------
    Signature
        For a curve, the cyclic sequence ``(kind, F / max F)`` along the curve,
        starting at the global maximum: invariant under rotating or scaling the
        (shape, viewpoint) pair and under the choice of starting point.  For a
        surface, the values sorted.

    See Also
    --------
    compare
        Compares two signatures.
    critical_points
        The critical points summarised.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> from shapelab.datasets import ellipse_curve
    >>> s = signature(critical_points(ellipse_curve(2.0, 1.0), [0.0, 0.0]))
    >>> [str(k) for k in s.kinds], s.values.round(3).tolist()
    (['max', 'min', 'max', 'min'], [1.0, 0.5, 1.0, 0.5])
    """
    if not isinstance(result, CriticalPoints):
        raise TypeError(f"result must be a CriticalPoints, got {type(result).__name__}")
    tolerance = as_finite_scalar(tolerance, "tolerance", nonnegative=True)
    if len(result) == 0:
        return Signature((), np.empty(0), result.source != "surface")
    vmax = float(result.values.max())
    vals = result.values / vmax if vmax > 0 else result.values.copy()
    if result.source == "surface":
        order = np.lexsort((result.kinds, vals))
        return Signature(tuple(result.kinds[order]), vals[order], False)
    kinds, vl = _cancel_pairs(list(result.kinds), list(vals), tolerance)
    vals = np.array(vl)
    start = int(np.argmax(vals))
    order = np.roll(np.arange(vals.size), -start)
    return Signature(tuple(np.array(kinds)[order]), vals[order], True)


def compare(a: CriticalPoints | Signature, b: CriticalPoints | Signature) -> float:
    """Compare two shapes by their critical points: 0 for identical signatures.

    Parameters
    ----------
    a, b : CriticalPoints or Signature

    Returns
    -------
    float
        If both have the same sequence of kinds (curves: up to the cyclic shift
        and the direction of travel), the largest difference of the normalised
        values under the best alignment; ``inf`` if the numbers of minima,
        maxima or saddles differ (the shapes are then told apart combinatorially).

    See Also
    --------
    signature
        What is compared.
    shapelab.diagrams.bottleneck_distance
        A stable comparison of persistence diagrams instead.

    Examples
    --------
    >>> from shapelab.datasets import ellipse_curve
    >>> a = critical_points(ellipse_curve(2.0, 1.0), [0.0, 0.0])
    >>> b = critical_points(ellipse_curve(4.0, 2.0), [0.0, 0.0])  # the same shape, twice as large
    >>> c = critical_points(ellipse_curve(3.0, 1.0), [0.0, 0.0])
    >>> round(compare(a, b), 9), compare(a, c) > 0
    (0.0, True)
    """
    sa = a if isinstance(a, Signature) else signature(a)
    sb = b if isinstance(b, Signature) else signature(b)
    if len(sa.kinds) != len(sb.kinds) or sorted(sa.kinds) != sorted(sb.kinds):
        return float("inf")
    if len(sa.kinds) == 0:
        return 0.0
    if not (sa.cyclic and sb.cyclic):
        if sa.kinds != sb.kinds:
            # same counts, different order of values: compare per kind, sorted
            out = 0.0
            for kind in set(sa.kinds):
                va = np.sort(sa.values[np.array(sa.kinds) == kind])
                vb = np.sort(sb.values[np.array(sb.kinds) == kind])
                out = max(out, float(np.abs(va - vb).max()))
            return out
        return float(np.abs(sa.values - sb.values).max())
    best = float("inf")
    ka = np.array(sa.kinds)
    for vals_b, kinds_b in ((sb.values, np.array(sb.kinds)), (sb.values[::-1], np.array(sb.kinds)[::-1])):
        for shift in range(len(ka)):
            kb = np.roll(kinds_b, shift)
            if np.array_equal(ka, kb):
                best = min(best, float(np.abs(sa.values - np.roll(vals_b, shift)).max()))
    return best


# --------------------------------------------------------------------------- #
# Sampling a parametric curve (the example curves and meshes are in datasets)   #
# --------------------------------------------------------------------------- #
def polyline(fn: Callable, n: int = 200) -> np.ndarray:
    """Sample a parametric closed curve at n points of [0, 2π): a closed polyline
    of shape (n + 1, d), the first point repeated at the end.

    See Also
    --------
    critical_points
        Takes the polyline.

    Examples
    --------
    >>> import numpy as np
    >>> P = polyline(lambda t: np.c_[np.cos(t), np.sin(t)], 4)
    >>> P.shape, bool(np.array_equal(P[0], P[-1]))
    ((5, 2), True)
    >>> np.round(P[1], 6).tolist()
    [0.0, 1.0]
    """
    n = as_positive_int(n, "n", minimum=3)
    t = np.arange(n) * (_TWO_PI / n)
    X = _evaluate(fn, t)
    return np.vstack([X, X[:1]])
