"""The α-filtration of a union of balls and its dual complexes (Notes §23.1).

Grow every ball :math:`B_i = (z_i, r_i)` to radius :math:`\\sqrt{r_i^2 + \\tau}`.  The
dual complex at time :math:`\\tau` is the nerve of the clipped cells

.. math:: K(\\tau) = \\{\\sigma \\subseteq DT : \\textstyle\\bigcap_{i\\in\\sigma}
          B_i(\\tau) \\cap \\Pi(B_i) \\neq \\emptyset\\},

and as :math:`\\tau` runs from :math:`-\\infty` to :math:`+\\infty` these complexes form
a nested sequence :math:`\\emptyset \\subset K^1 \\subset \\dots \\subset K^m = DT`.
Notes §23.1 call this sequence "the dual-complex"; the usual name is the
(weighted) *α-filtration*, and the notes' :math:`\\alpha` is :math:`\\sqrt{\\tau}`.

Each simplex :math:`\\sigma` of DT has an *entry time*: the least :math:`\\tau` with
:math:`\\sigma \\in K(\\tau)`.  It is computed from two ingredients:

* the *smallest orthogonal sphere* of :math:`\\sigma`: the point :math:`c_\\sigma` of
  the affine hull of :math:`\\sigma` with equal power distance to all its balls, and
  that common power :math:`\\rho_\\sigma = \\pi_i(c_\\sigma)` (for a vertex,
  :math:`c = z_i` and :math:`\\rho = -r_i^2`);
* the Gabriel test: :math:`\\sigma` is *attached* (not Gabriel) if some vertex
  :math:`v` of a coface has :math:`\\pi_v(c_\\sigma) < \\rho_\\sigma`, i.e. another ball
  claims :math:`c_\\sigma` before :math:`\\sigma`'s balls reach it.

Then, from the top dimension down, an unattached simplex enters at
:math:`\\rho_\\sigma` and an attached one enters with its earliest coface.  This is the
rule of GUDHI's ``AlphaComplex`` with weights, and the values agree with it to
round-off (tested).  In the weighted case the rule also applies to vertices: a ball
whose centre is covered by a neighbour's power enters later than :math:`-r_i^2`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .balls import Balls
from .power import _triangulate

__all__ = ["alpha_filtration", "dual_complex", "Filtration", "Complex"]


# ----------------------------------------------------------------------------------
# Face enumeration with integer keys
# ----------------------------------------------------------------------------------
def _unique_facets(simp: np.ndarray, nv: int):
    """All facets of the rows of ``simp`` (vertices ascending): unique facets
    (lexicographically sorted, ascending rows) and the (m, j+1) boundary matrix whose
    column i is the facet opposite vertex i."""
    m, w = simp.shape  # w = j + 1 vertices, facets have w - 1
    fw = w - 1
    if fw == 0:
        raise ValueError("vertices have no facets")
    # facet opposite column i: drop column i (stays ascending)
    cols = [np.delete(np.arange(w), i) for i in range(w)]
    if fw == 1:
        keys = np.concatenate([simp[:, 1], simp[:, 0]])  # facet opposite i: the other vertex
        uniq, inv = np.unique(keys, return_inverse=True)
        return uniq[:, None].astype(np.int64), inv.reshape(w, m).T.astype(np.int64)
    if float(nv) ** fw < 2.0**62:
        base = np.int64(nv)
        keys = np.empty((w, m), dtype=np.int64)
        for i, c in enumerate(cols):
            k = simp[:, c[0]].astype(np.int64)
            for cc in c[1:]:
                k = k * base + simp[:, cc]
            keys[i] = k
        uniq, inv = np.unique(keys.ravel(), return_inverse=True)
        faces = np.empty((uniq.size, fw), dtype=np.int64)
        rest = uniq.copy()
        for t in range(fw - 1, -1, -1):
            faces[:, t] = rest % base
            rest //= base
        return faces, inv.reshape(w, m).T.astype(np.int64)
    allf = np.concatenate([simp[:, c] for c in cols])  # pragma: no cover - huge n
    faces, inv = np.unique(allf, axis=0, return_inverse=True)  # pragma: no cover
    return faces.astype(np.int64), inv.reshape(w, m).T.astype(np.int64)  # pragma: no cover


# ----------------------------------------------------------------------------------
# Smallest orthogonal spheres
# ----------------------------------------------------------------------------------
def _orthospheres(x: np.ndarray, w: np.ndarray, S: np.ndarray):
    """Centre offsets u (relative to the first vertex) and squared radii rho of the
    smallest orthogonal spheres of the simplices S (rows of local vertex indices).

    The centre ``c = x[S[:,0]] + u`` lies in the affine hull of the simplex and has
    equal power to all its weighted vertices; ``rho`` is that common power.
    """
    m, w1 = S.shape
    j = w1 - 1
    k = x.shape[1]
    p0 = x[S[:, 0]]
    w0 = w[S[:, 0]]
    if j == 0:
        return np.zeros((m, k)), -w0.copy()
    A = x[S[:, 1:]] - p0[:, None, :]          # (m, j, k)
    b = 0.5 * (np.einsum("mjk,mjk->mj", A, A) - w[S[:, 1:]] + w0[:, None])  # u . a_i = b_i
    if j == 1:
        a = A[:, 0]
        aa = np.einsum("mk,mk->m", a, a)
        u = (b[:, 0] / aa)[:, None] * a
        flat = np.zeros(m, dtype=bool)
    elif j == 2 and k == 2:
        a, c = A[:, 0], A[:, 1]
        det = a[:, 0] * c[:, 1] - a[:, 1] * c[:, 0]
        scale = np.sqrt(np.einsum("mk,mk->m", a, a) * np.einsum("mk,mk->m", c, c))
        flat = np.abs(det) <= 1e-12 * scale
        det = np.where(flat, 1.0, det)
        u = np.empty((m, 2))
        u[:, 0] = (b[:, 0] * c[:, 1] - b[:, 1] * a[:, 1]) / det
        u[:, 1] = (a[:, 0] * b[:, 1] - c[:, 0] * b[:, 0]) / det
    elif j == 2 and k == 3:
        a, c = A[:, 0], A[:, 1]
        nrm = np.cross(a, c)
        nn = np.einsum("mk,mk->m", nrm, nrm)
        scale = np.einsum("mk,mk->m", a, a) * np.einsum("mk,mk->m", c, c)
        flat = nn <= 1e-24 * scale
        nn = np.where(flat, 1.0, nn)
        u = (b[:, :1] * np.cross(c, nrm) + b[:, 1:2] * np.cross(nrm, a)) / nn[:, None]
    elif j == 3 and k == 3:
        a, c, e = A[:, 0], A[:, 1], A[:, 2]
        ce, ea, ac = np.cross(c, e), np.cross(e, a), np.cross(a, c)
        det = np.einsum("mk,mk->m", a, ce)
        scale = np.sqrt(np.einsum("mk,mk->m", a, a) * np.einsum("mk,mk->m", c, c)
                        * np.einsum("mk,mk->m", e, e))
        flat = np.abs(det) <= 1e-12 * scale
        det = np.where(flat, 1.0, det)
        u = (b[:, :1] * ce + b[:, 1:2] * ea + b[:, 2:3] * ac) / det[:, None]
    else:  # pragma: no cover - j > k cannot happen
        raise AssertionError("simplex dimension exceeds the ambient dimension")
    if np.any(flat):
        # Degenerate (flat) simplices that Qhull's triangulation of cospherical input
        # may contain: the least-squares (minimum-norm) orthocentre in their span.
        idx = np.flatnonzero(flat)
        Af = A[idx]
        G = np.einsum("mik,mjk->mij", Af, Af)
        lam = np.einsum("mij,mj->mi", np.linalg.pinv(G, rcond=1e-10), b[idx])
        u[idx] = np.einsum("mi,mik->mk", lam, Af)
    rho = np.einsum("mk,mk->m", u, u) - w0
    return u, rho


# ----------------------------------------------------------------------------------
# Results
# ----------------------------------------------------------------------------------
def _ro(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a


def _check_k(k, dim_max: int) -> int:
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, (int, np.integer)):
        raise TypeError(f"k must be an integer dimension, got {type(k).__name__}")
    k = int(k)
    if not 0 <= k <= dim_max:
        raise ValueError(f"k must be between 0 and {dim_max}, got {k}")
    return k


def _check_tau(tau) -> float:
    if isinstance(tau, (bool, np.bool_)):
        raise TypeError("tau must be a real number, got bool")
    try:
        t = float(tau)
    except (TypeError, ValueError):
        raise TypeError(f"tau must be a real number, got {type(tau).__name__}") from None
    if math.isnan(t):
        raise ValueError("tau must not be NaN")
    return t


class _SimplicialMixin:
    """Accessors shared by :class:`Filtration` and :class:`Complex`."""

    def simplices(self, k: int) -> np.ndarray:
        """The k-simplices, shape (n_k, k+1), int64 indices into ``balls``.

        Vertices ascend within each row; rows are in filtration order
        (non-decreasing entry time, ties broken lexicographically).  For
        ``dimension < k <= d`` the array is empty.
        """
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return _ro(np.zeros((0, k + 1), dtype=np.int64))
        return self._simplices[k][: self._counts[k]]

    def values(self, k: int) -> np.ndarray:
        """Entry times τ of the k-simplices, shape (n_k,), non-decreasing."""
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return _ro(np.zeros(0))
        return self._values[k][: self._counts[k]]

    def boundary(self, k: int) -> np.ndarray:
        """Facet rows of the k-simplices, shape (n_k, k+1), for k >= 1.

        Entry ``[i, j]`` is the row index into ``simplices(k-1)`` of the facet of
        simplex ``i`` opposite its vertex ``simplices(k)[i, j]``.
        """
        k = _check_k(k, self.balls.dim)
        if k == 0:
            raise ValueError("k must be >= 1 for boundary(k): vertices have no facets")
        if k > self.dimension:
            return _ro(np.zeros((0, k + 1), dtype=np.int64))
        return self._boundary[k][: self._counts[k]]

    def __len__(self) -> int:
        return int(sum(self._counts))

    def counts(self) -> tuple:
        """Number of simplices per dimension, ``(n_0, ..., n_dimension)``."""
        return tuple(int(c) for c in self._counts)


@dataclass(frozen=True, eq=False, repr=False)
class Complex(_SimplicialMixin):
    """The dual complex :math:`K(\\tau)` of the balls grown by ``tau`` (Notes §23.1).

    A sub-complex of the regular triangulation: the simplices whose entry time is at
    most ``tau``.  Obtain it with :meth:`Filtration.complex_at` or
    :func:`dual_complex`.

    Attributes
    ----------
    balls : Balls
    tau : float
    dimension : int
        Largest k with a k-simplex (-1 if empty).
    """

    balls: Balls
    tau: float
    dimension: int
    _simplices: tuple
    _values: tuple
    _boundary: tuple
    _counts: tuple

    def euler_characteristic(self) -> int:
        """:math:`\\chi(K) = \\sum_k (-1)^k n_k`."""
        return int(sum((-1) ** k * int(c) for k, c in enumerate(self._counts)))

    def __repr__(self) -> str:
        return f"Complex(tau={self.tau!r}, counts={self.counts()})"


@dataclass(frozen=True, eq=False, repr=False)
class Filtration(_SimplicialMixin):
    """The α-filtration (Notes §23.1, "the dual-complex") of a set of balls.

    Every simplex of the regular triangulation DT with the growth time τ at which it
    enters the dual complex of the balls of radii :math:`\\sqrt{r_i^2+\\tau}`.  The notes'
    :math:`\\alpha` is :math:`\\sqrt{\\tau}`.  Values agree (to round-off) with GUDHI's
    ``AlphaComplex(points=centers, weights=radii**2)``.

    Attributes
    ----------
    balls : Balls
    dimension : int
        Largest k with a k-simplex (-1 if there are no balls).
    """

    balls: Balls
    dimension: int
    _simplices: tuple
    _values: tuple
    _boundary: tuple
    _counts: tuple

    def complex_at(self, tau) -> Complex:
        """The dual complex :math:`K(\\tau)`: all simplices with entry time ≤ ``tau``.

        ``tau`` may be ``±inf``; ``complex_at(inf)`` is the whole triangulation and
        ``complex_at(0.0)`` the dual complex of the balls as given.
        """
        t = _check_tau(tau)
        counts = tuple(int(np.searchsorted(v, t, side="right")) for v in self._values)
        dim = max((k for k, c in enumerate(counts) if c > 0), default=-1)
        return Complex(self.balls, t, dim, self._simplices, self._values, self._boundary, counts)

    def betti(self, tau) -> tuple:
        """Betti numbers of :math:`K(\\tau)` (see :func:`shapelab.topology.betti`)."""
        from .topology import betti

        return betti(self, tau)

    def betti_curve(self, taus) -> np.ndarray:
        """Betti numbers at each τ (see :func:`shapelab.topology.betti_curve`)."""
        from .topology import betti_curve

        return betti_curve(self, taus)

    def persistence(self) -> dict:
        """Persistence diagrams (see :func:`shapelab.topology.persistence`)."""
        from .topology import persistence

        return persistence(self)

    def __repr__(self) -> str:
        return f"Filtration(n_balls={len(self.balls)}, dimension={self.dimension}, counts={self.counts()})"


# ----------------------------------------------------------------------------------
# The algorithm
# ----------------------------------------------------------------------------------
def _empty_filtration(balls: Balls) -> Filtration:
    d = balls.dim
    simp = tuple(_ro(np.zeros((0, k + 1), dtype=np.int64)) for k in range(d + 1))
    vals = tuple(_ro(np.zeros(0)) for _ in range(d + 1))
    bnd = (None,) + tuple(_ro(np.zeros((0, k + 1), dtype=np.int64)) for k in range(1, d + 1))
    return Filtration(balls, -1, simp, vals, bnd, tuple(0 for _ in range(d + 1)))


def alpha_filtration(balls: Balls) -> Filtration:
    """The α-filtration of the balls: every simplex of DT with its entry time τ.

    Parameters
    ----------
    balls : Balls

    Returns
    -------
    Filtration

    Notes
    -----
    Notes §23.1 (the growth model).  Algorithm (GUDHI's, in vectorised form):

    1. DT by the lifting map (:func:`shapelab.regular_triangulation`).
    2. For every simplex the smallest orthogonal sphere :math:`(c_\\sigma, \\rho_\\sigma)`.
    3. From the top dimension down: a facet :math:`\\tau` of :math:`\\sigma` opposite
       the vertex :math:`v` is *attached* if :math:`\\pi_v(c_\\tau) < \\rho_\\tau`;
       attached simplices enter with their earliest coface, the others at
       :math:`\\rho_\\tau`.  Vertices enter at :math:`-r_i^2` unless attached.
    4. A final pass raises any value that round-off left below a face's value.

    Values are computed in the centred and scaled frame of the triangulation and
    scaled back (:math:`\\tau` scales with :math:`s^2`, translation leaves it fixed).
    """
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be a shapelab.Balls, got {type(balls).__name__}")
    fr, tri = _triangulate(balls)
    if tri.shape[0] == 0:
        return _empty_filtration(balls)
    n = len(balls)
    dim = tri.shape[1] - 1
    # local indices into the frame (keep is ascending, so rows stay ascending)
    loc = np.full(n, -1, dtype=np.int64)
    loc[fr.keep] = np.arange(fr.keep.size)
    nv = fr.keep.size
    x, w = fr.x, fr.w

    faces = [None] * (dim + 1)
    bnd = [None] * (dim + 1)
    faces[dim] = loc[tri]
    for j in range(dim, 0, -1):
        faces[j - 1], bnd[j] = _unique_facets(faces[j], nv)

    if dim == 0:
        vals = [-w[faces[0][:, 0]]]
    else:
        cen = [None] * (dim + 1)
        rho = [None] * (dim + 1)
        for j in range(dim + 1):
            cen[j], rho[j] = _orthospheres(x, w, faces[j])
        vals = [None] * (dim + 1)
        vals[dim] = rho[dim]
        for j in range(dim, 0, -1):
            S, B = faces[j], bnd[j]
            F = faces[j - 1]
            nf = F.shape[0]
            fidx = B.ravel()                      # facet of (sigma, column i)
            vopp = S.ravel()                      # the vertex opposite that facet
            f0 = F[fidx, 0]
            c = x[f0] + cen[j - 1][fidx]           # facet's orthocentre
            dv = c - x[vopp]
            pw = np.einsum("mk,mk->m", dv, dv) - w[vopp]
            att = pw < rho[j - 1][fidx]
            attached = np.zeros(nf, dtype=bool)
            attached[fidx[att]] = True
            cof = np.full(nf, np.inf)
            np.minimum.at(cof, fidx, np.repeat(vals[j], j + 1))
            vals[j - 1] = np.where(attached, cof, rho[j - 1])
        # make the filtration non-decreasing against round-off (GUDHI does the same)
        for j in range(1, dim + 1):
            vals[j] = np.maximum(vals[j], vals[j - 1][bnd[j]].max(axis=1))

    s2 = fr.scale**2
    # filtration order: by value, ties lexicographic (rows are already lex-sorted)
    simp_out, vals_out, bnd_out = [], [], [None]
    inv_prev = None
    for j in range(dim + 1):
        v = vals[j] * s2
        order = np.argsort(v, kind="stable")
        simp_out.append(_ro(fr.keep[faces[j][order]]))
        vals_out.append(_ro(np.ascontiguousarray(v[order])))
        if j >= 1:
            bnd_out.append(_ro(inv_prev[bnd[j][order]]))
        inv_prev = np.empty(order.size, dtype=np.int64)
        inv_prev[order] = np.arange(order.size)
    for j in range(dim + 1, balls.dim + 1):
        simp_out.append(_ro(np.zeros((0, j + 1), dtype=np.int64)))
        vals_out.append(_ro(np.zeros(0)))
        bnd_out.append(_ro(np.zeros((0, j + 1), dtype=np.int64)))
    counts = tuple(int(a.shape[0]) for a in simp_out)
    return Filtration(balls, dim, tuple(simp_out), tuple(vals_out), tuple(bnd_out), counts)


def dual_complex(balls: Balls) -> Complex:
    """The dual complex K of the union of the balls as given (Notes §23.1).

    Same as ``alpha_filtration(balls).complex_at(0.0)``: the nerve of the clipped
    cells :math:`B_i \\cap \\Pi(B_i)`.
    """
    return alpha_filtration(balls).complex_at(0.0)
