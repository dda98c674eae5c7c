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

Where the notes are imprecise
-----------------------------
* The sequence :math:`\\phi = K^1 \\subset \\dots \\subset K^m = D` is called "the
  dual-complex"; it is the α-*filtration* (of the dual complexes).
* :math:`K^1 = \\emptyset`, yet "the first dual complex is the set of vertices plus
  the two thick edges": the notes mean the first *non-empty* complex shown.
* :math:`D` is "the Delaunay triangulation defined by the set of centers"; for balls
  of different radii it is the *regular* triangulation, and hidden balls are not
  vertices of it (see :mod:`shapelab.power`).
* :math:`\\alpha = \\sqrt{\\tau}` is real only for :math:`\\tau \\ge 0`, while the
  filtration starts at :math:`\\tau = \\min_i(-r_i^2) \\le 0`; we index by τ throughout.
* A vertex does not always enter at :math:`-r_i^2`, when its ball "appears": it
  enters when :math:`B_i(\\tau)` first meets its own cell :math:`\\Pi(B_i)`, which is
  later if a neighbour's power covers :math:`z_i`.
* "The topology of :math:`K(\\mathbb{P})` is the same as that of :math:`\\mathbb{P}`":
  :math:`K` and the union have the same *homotopy type* (nerve theorem), they are
  not homeomorphic (a triangle of :math:`K` can stand for a region of any shape).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from . import _topology
from ._toolkit.geometry import cross, dot
from ._toolkit.tolerances import ENTRY_TIME_RTOL, ENTRY_TIME_SAFETY, GRAM_PINV_RCOND
from ._toolkit.validate import as_bbox, as_tau, check_balls, freeze
from .balls import Balls
from .power import clipped_cells, power_diagram, triangulate_local

__all__ = ["alpha_filtration", "dual_complex", "Filtration", "Complex", "BoundaryMatrix"]


# ----------------------------------------------------------------------------------
# Face enumeration
# ----------------------------------------------------------------------------------
def _drop_cols(w: int):
    """Column lists: for each i, the columns of a w-row without column i."""
    return [[c for c in range(w) if c != i] for i in range(w)]


def _facets_from_neighbours(simp: np.ndarray, nbr: np.ndarray):
    """Facets of top simplices using the neighbour relation (no sorting).

    Each interior facet is shared by exactly two top simplices; the one with the
    smaller index owns it.  Returns ``(facets, boundary)`` (int32) or ``None`` if
    the neighbour relation is inconsistent (then the caller falls back to sorting).
    """
    m, w = simp.shape
    own = nbr < 0
    own |= np.arange(m, dtype=nbr.dtype)[:, None] < nbr
    ids = np.cumsum(own.ravel(), dtype=np.int32).reshape(m, w)
    ids -= 1
    p = np.flatnonzero(~own.ravel())
    t = p // w
    i = p - t * w
    nb = nbr.ravel()[p]
    back = nbr[nb] == t[:, None]
    j = np.argmax(back, axis=1)
    if not np.all(back[np.arange(j.size), j]):
        return None
    del back
    # the shared facet must have the same vertices on both sides (checked by the
    # sums of its vertex indices; the back pointers above were checked exactly)
    fs = simp.sum(axis=1, dtype=np.int64)[:, None] - simp
    if not np.array_equal(fs.ravel()[p], fs[nb, j]):
        return None
    del fs, t, i
    ids.ravel()[p] = ids[nb, j]
    del p, nb, j
    cols = np.array(_drop_cols(w), dtype=np.intp)
    q = np.flatnonzero(own.ravel())
    ro = q // w
    facets = simp[ro[:, None], cols[q - ro * w]]
    return facets, ids


def _unique_facets(simp: np.ndarray, nv: int):
    """All facets of the rows of ``simp`` (vertices ascending): unique facets
    (rows ascending, lexicographically sorted) and the (m, j+1) boundary matrix
    whose column i is the row of the facet opposite vertex i (both int32).

    The facets are encoded as integers (base ``nv``) with the position packed into
    the low bits, so one in-place SIMD ``np.sort`` replaces ``np.unique`` (which
    would ``argsort``: ~8x slower here); everything else is in place or int32.
    """
    m, w = simp.shape
    fw = w - 1
    if fw == 1:  # facets are vertices: a lookup table
        pos = np.full(nv, -1, dtype=np.int32)
        verts = np.flatnonzero(np.bincount(simp.ravel(), minlength=nv)).astype(np.int32)
        pos[verts] = np.arange(verts.size, dtype=np.int32)
        return verts[:, None], pos[simp[:, ::-1]]
    M = m * w
    ib = max(1, int(M - 1).bit_length())
    key_bits = max(1, int(nv - 1).bit_length()) * fw
    if key_bits + ib > 63:  # pragma: no cover - beyond ~2e6 balls in 3D
        allf = np.concatenate([simp[:, c] for c in _drop_cols(w)])
        faces, inv = np.unique(allf, axis=0, return_inverse=True)
        return faces.astype(np.int32), inv.reshape(w, m).T.astype(np.int32)
    base = np.int64(nv)
    packed = np.empty((m, w), dtype=np.int64)  # row-major: position t * w + i
    for i, c in enumerate(_drop_cols(w)):
        col = packed[:, i]
        col[...] = simp[:, c[0]]
        for cc in c[1:]:
            col *= base
            col += simp[:, cc]
    packed = packed.ravel()
    packed <<= np.int64(ib)
    packed |= np.arange(M, dtype=np.int64)
    packed.sort()
    perm = np.empty(M, dtype=np.int32)
    np.bitwise_and(packed, np.int64((1 << ib) - 1), out=perm, casting="unsafe")
    packed >>= np.int64(ib)
    first = np.empty(M, dtype=bool)
    first[0] = True
    np.not_equal(packed[1:], packed[:-1], out=first[1:])
    uniq = packed[first]
    del packed
    rank = np.cumsum(first, dtype=np.int32)
    rank -= 1
    del first
    inv = np.empty(M, dtype=np.int32)
    inv[perm] = rank
    del perm, rank
    faces = np.empty((uniq.size, fw), dtype=np.int32)
    for t in range(fw - 1, -1, -1):
        faces[:, t] = uniq % base
        uniq //= base
    return faces, inv.reshape(m, w)


# ----------------------------------------------------------------------------------
# Smallest orthogonal spheres
# ----------------------------------------------------------------------------------
def _ortho_generic(x: np.ndarray, w: np.ndarray, S: np.ndarray):
    """Orthocentre offset u (from the first vertex) and rho of simplices S by the
    minimum-norm solution of the Gram system (defined for affinely dependent
    vertices too; used only for exactly degenerate simplices, see
    :func:`_orthospheres_certified`)."""
    p0 = x[S[:, 0]]
    w0 = w[S[:, 0]]
    if S.shape[1] == 1:
        return np.zeros_like(p0), -w0
    A = x[S[:, 1:]] - p0[:, None, :]
    b = 0.5 * (np.einsum("mjk,mjk->mj", A, A) - w[S[:, 1:]] + w0[:, None])
    G = np.einsum("mik,mjk->mij", A, A)
    lam = np.einsum("mij,mj->mi", np.linalg.pinv(G, rcond=GRAM_PINV_RCOND), b)
    u = np.einsum("mi,mik->mk", lam, A)
    return u, np.einsum("mk,mk->m", u, u) - w0


# Error model of the floating-point orthospheres (see _orthospheres, Notes).
#: A value computed in floating point is accepted when its first-order error bound,
#: times _SAFETY, is at most _RTOL times the value itself (relative to the quantity,
#: whatever the input's extent); otherwise the row is recomputed in higher precision.
_RTOL = ENTRY_TIME_RTOL
#: Factor on the first-order bounds for the neglected second-order terms and the
#: small constants of the rounding analysis.
_SAFETY = ENTRY_TIME_SAFETY


def _orthospheres(x: np.ndarray, w: np.ndarray, S: np.ndarray):
    """Smallest orthogonal spheres of the simplices S (rows of local indices), with a
    certificate of their accuracy.

    Parameters
    ----------
    x, w : ndarray
        Positions and weights, taken as exact (float64 or longdouble; the
        arithmetic is done in ``x.dtype``).  Positions may be rounded differences
        of exact inputs: the bound counts a relative error of eps in the edges.
    S : ndarray, shape (m, j+1)

    Returns
    -------
    rho : (m,) float
        The squared radius (common power distance) of the smallest orthogonal
        sphere; ``-w`` for vertices.
    att : (m, j+1) bool
        ``att[s, i]``: the facet of simplex ``s`` opposite its vertex ``S[s, i]`` is
        *attached* (not Gabriel) with respect to that vertex, i.e. the vertex has
        negative power with respect to the facet's smallest orthogonal sphere.
    bad : (m,) bool
        Rows whose ``rho`` is not certified to relative accuracy ``_RTOL``, or whose
        attachment (the sign of some :math:`\\lambda_v`) is not certified, or whose
        linear system is (numerically) singular.  Their ``rho``/``att`` are
        meaningless and must be recomputed (:func:`_orthospheres_certified`).

    Notes
    -----
    Notes §23.1 (the smallest orthogonal sphere and the Gabriel test).  Write the
    orthocentre as :math:`c = \\sum_i \\lambda_i z_i` (barycentric).  Along the line
    through the facet's orthocentre :math:`c_f` orthogonal to the facet,
    :math:`\\pi_v(c_f) - \\rho_f = 2t\\,n\\cdot(z_v - c_f)` where :math:`c = c_f + tn`;
    so the facet opposite :math:`v` is attached iff :math:`c` and :math:`z_v` lie on
    opposite sides of it, i.e. iff :math:`\\lambda_v < 0`.  This replaces one power
    test per (simplex, facet) pair by the barycentric coordinates of one point.

    With edge vectors :math:`a_i = z_i - z_0` as the rows of :math:`A`, the offset
    :math:`u = c - z_0` solves :math:`A u = \\beta`,
    :math:`\\beta_i = (|a_i|^2 - w_i + w_0)/2`, in the span of the rows, and
    :math:`\\rho = |u|^2 - w_0`, :math:`(\\lambda_1..\\lambda_j) = A^{+T} u`.  The
    error bound is the first-order perturbation bound of this system: with
    :math:`N \\ge \\lVert A^+\\rVert_F` (from the determinant the solve computes
    anyway; :math:`N\\lVert A\\rVert_F` estimates the condition number of the small
    system), :math:`E_A = (\\sqrt j + 4)\\,\\epsilon\\lVert A\\rVert_F` and
    :math:`E_\\beta = \\epsilon\\,(5\\lVert A\\rVert_F^2 + 4\\sum w)` the roundings of the
    arithmetic counted as errors of :math:`A` and :math:`\\beta` (the inputs are
    exact binary numbers),

    .. math:: |\\delta u| \\le \\frac{N (E_\\beta + c E_A |u|)}{1 - c N E_A},\\quad
              |\\delta\\rho| \\le (2|u| + |\\delta u|)|\\delta u|
              + 2\\epsilon(|u|^2 + w_0),\\quad
              |\\delta\\lambda| \\le \\frac{N(|\\delta u| + E_A|\\lambda|_1)}{1 - cNE_A},

    (c = 2 when the simplex is not full-dimensional: the row space turns too).  A
    nearly flat simplex has a large N, a simplex whose orthosphere has power near 0
    a small :math:`|\\rho|` against :math:`|u|^2 + w_0`, a simplex whose orthocentre
    is near a facet a small :math:`|\\lambda_v|`; each is flagged by the bound
    relative to its own quantity, not by a fixed cutoff on the determinant: a
    row is accepted iff ``_SAFETY`` times the bound is at most ``_RTOL`` |ρ| and
    below every :math:`|\\lambda_v|` (so the Gabriel test is exact), with
    :math:`cNE_A < 1/2` and magnitudes far from overflow and underflow.
    """
    m, w1 = S.shape
    j = w1 - 1
    k = x.shape[1]
    eps = float(np.finfo(x.dtype).eps)
    X = np.ascontiguousarray(x.T)
    w0 = w[S[:, 0]]
    if j == 0:
        return -w0, np.zeros((m, 1), dtype=bool), np.zeros(m, dtype=bool)
    P0 = X[:, S[:, 0]]
    vec = [X[:, S[:, i]] - P0 for i in range(1, w1)]  # each (k, m)
    nrm2 = [dot(v, v) for v in vec]
    wv = [w[S[:, i]] for i in range(1, w1)]
    beta = [0.5 * (nrm2[i] - wv[i] + w0) for i in range(j)]  # u . a_i = beta_i
    s = sum(nrm2)  # |A|_F^2
    nA = np.sqrt(s)
    lam = np.empty((w1, m), dtype=x.dtype)
    turn = 1.0  # c in the bound: 2 when the row space of A can turn (j < k)
    # N: a bound on ||A^+||_F (the condition number is N |A|)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if j == 1:
            a2 = nrm2[0]
            ok = a2 > 0
            det = np.where(ok, a2, 1.0)
            t = beta[0] / det
            uu = t * t * a2
            lam[1] = t
            N = 1.0 / np.sqrt(det)
            turn = 1.0 if k == 1 else 2.0
        elif j == 2 and k == 2:
            a, c = vec
            det = a[0] * c[1] - a[1] * c[0]
            ok = det != 0
            det = np.where(ok, det, 1.0)
            ux = (beta[0] * c[1] - beta[1] * a[1]) / det
            uy = (a[0] * beta[1] - c[0] * beta[0]) / det
            uu = ux * ux + uy * uy
            lam[1] = (ux * c[1] - uy * c[0]) / det
            lam[2] = (a[0] * uy - a[1] * ux) / det
            N = nA / np.abs(det)  # ||A^-1||_F = ||adj A||_F / |det|, ||adj A||_F = |A|_F
        elif j == 2 and k == 3:
            a, c = vec
            n = cross(a, c)
            nn = dot(n, n)
            ok = nn > 0
            nn = np.where(ok, nn, 1.0)
            ad = [q / nn for q in cross(c, n)]  # dual basis of (a, c) in their plane
            cd = [q / nn for q in cross(n, a)]
            u = [beta[0] * ad[t] + beta[1] * cd[t] for t in range(3)]
            uu = dot(u, u)
            lam[1] = dot(u, ad)
            lam[2] = dot(u, cd)
            N = nA / np.sqrt(nn)  # the dual basis: |a*| = |c| / |n|, |c*| = |a| / |n|
            turn = 2.0
        elif j == 3 and k == 3:
            a, b, c = vec
            bc, ca, ab = cross(b, c), cross(c, a), cross(a, b)
            det = dot(a, bc)
            ok = det != 0
            det = np.where(ok, det, 1.0)
            u = [(beta[0] * bc[t] + beta[1] * ca[t] + beta[2] * ab[t]) / det for t in range(3)]
            uu = dot(u, u)
            lam[1] = dot(u, bc) / det
            lam[2] = dot(u, ca) / det
            lam[3] = dot(u, ab) / det
            # ||A^-1||_F = ||adj A||_F / |det| <= |A|_F^2 / (sqrt(3) |det|)
            N = s / (math.sqrt(3.0) * np.abs(det))
        else:  # pragma: no cover - j > k cannot happen
            raise AssertionError("simplex dimension exceeds the ambient dimension")
        rho = uu - w0
        lam[0] = 1.0 - lam[1:].sum(axis=0)
        att = (lam < 0).T

        # -- the certificate (first-order error bounds, see Notes) --------------
        # The inputs are exact; the roundings of the arithmetic (a few eps relative
        # to |A|, to |beta| <= (s + ws) / 2 and to |u|^2 + w0) act as errors EA of A
        # and EB of beta.
        ws = sum(wv) + j * w0
        EA = ((math.sqrt(j) + 4.0) * eps) * nA
        EB = (5.0 * eps) * s + (4.0 * eps) * ws
        g = (turn * N) * EA  # < 1/2: the perturbed system stays regular
        amp = N / (1.0 - g)
        un = np.sqrt(uu)
        du = amp * (EB + turn * EA * un)
        drho = (2.0 * un + du) * du + (2.0 * eps) * (uu + w0)
        absl = np.abs(lam)
        l1 = absl[1:].sum(axis=0)
        # one bound for every barycentric coordinate (that of lambda_0 = 1 - sum);
        # amp * du also covers the rounding of lambda from u (3 eps N |u|)
        dlam = ((j + 1) * amp) * (2.0 * du + EA * l1) + eps * (1.0 + l1)
        # magnitudes in the range where rounding is relative (no overflow, no
        # subnormal products: the products of the solve are of order (s + ws)^2)
        fi = np.finfo(x.dtype)
        mag = s + ws
        bad = ~((mag > math.sqrt(float(fi.tiny)) / eps) & (mag < math.sqrt(float(fi.max)) * eps))
        bad |= ~ok | ~(g < 0.5) | ~(_SAFETY * drho <= _RTOL * np.abs(rho))
        bad |= ~(absl.min(axis=0) > _SAFETY * dlam)
    return rho, att, bad


_CHUNK = 8192


def _orthospheres_chunked(x: np.ndarray, w: np.ndarray, S: np.ndarray):
    """:func:`_orthospheres` in blocks of rows, which bounds the memory of its
    temporaries (~60 float arrays of the block size) at no measurable cost."""
    m = S.shape[0]
    if m <= _CHUNK:
        return _orthospheres(x, w, S)
    rho = np.empty(m, dtype=x.dtype)
    att = np.empty((m, S.shape[1]), dtype=bool)
    bad = np.empty(m, dtype=bool)
    for a in range(0, m, _CHUNK):
        sl = slice(a, a + _CHUNK)
        rho[sl], att[sl], bad[sl] = _orthospheres(x, w, S[sl])
    return rho, att, bad


def _local_rows(balls: Balls, fr, S: np.ndarray, dtype):
    """Positions (relative to each row's first vertex) and weights of the rows S
    (frame-local indices) from the input's centres and weights, in ``dtype``: the
    differences are rounded relative to the simplex's own size, whatever the
    input's offset.  Returns ``(x, w, S')``, one block of ``j + 1`` positions per
    row."""
    m, w1 = S.shape
    idx = fr.keep[S]
    c = balls.centers[idx].astype(dtype)  # (m, w1, d)
    c -= c[:, :1, :].copy()
    w = balls.weights[idx].astype(dtype)  # the float64 r^2, exactly
    return c.reshape(m * w1, -1), w.ravel(), np.arange(m * w1).reshape(m, w1)


def _exact_rows(C: np.ndarray, W: np.ndarray, rows: np.ndarray, scale: float):
    """Smallest orthogonal spheres of simplices in exact arithmetic (Notes §23.1).

    Parameters
    ----------
    C, W : ndarray
        Input centres and weights (``balls.weights``, the float64 :math:`r^2` that
        GUDHI is given too).  Float64 numbers are exact binary fractions.
    rows : ndarray, shape (m, j+1)
        Input indices of the simplices.
    scale : float
        The frame's scale: the powers are returned divided by ``scale**2``.

    Returns
    -------
    rho : (m,) float64
        :math:`\\rho / \\text{scale}^2`, correctly rounded (one rounding of the exact
        rational number: Python's ``int / int``).
    att : (m, j+1) bool
        :math:`\\lambda_v < 0`, exactly.
    flat : (m,) bool
        Rows whose vertices are affinely dependent (:math:`\\det G = 0`); their
        ``rho``/``att`` are undefined.

    Notes
    -----
    Each row's numbers are scaled by a common power of two to integers (mantissa
    and exponent from ``np.frexp``), the Gram system :math:`G\\lambda = \\beta`,
    :math:`G = AA^T`, :math:`\\beta_i = (|a_i|^2 - w_i + w_0)/2`, is solved by its
    adjugate, :math:`\\lambda_i = N_i / (2\\det G)` with :math:`N = \\operatorname{adj}(G)\\,2\\beta`,
    and :math:`\\rho = \\lambda\\cdot\\beta - w_0`.  The integers are int64 where a
    bound on the rows' magnitudes shows that no result can overflow
    (:func:`_small_row_integers`: grids and other dyadic input near the origin), else
    Python integers in NumPy object arrays (vectorised over rows; unbounded, so no
    overflow whatever the exponents).
    """
    m, w1 = rows.shape
    j = w1 - 1
    c = C[rows]  # (m, w1, d)
    wt = W[rows]  # (m, w1)
    mc, ec = np.frexp(c)
    mw, ew = np.frexp(wt)
    Mc = (mc * 2.0**53).astype(np.int64)  # c = Mc * 2**(ec - 53), exactly
    Mw = (mw * 2.0**53).astype(np.int64)
    ec = np.where(Mc == 0, np.iinfo(np.int32).max, ec.astype(np.int64) - 53)
    ew = np.where(Mw == 0, np.iinfo(np.int32).max, ew.astype(np.int64) - 53)
    # one exponent E per row: c * 2**-E and w * 2**-2E are integers
    E = np.minimum(ec.reshape(m, -1).min(axis=1), ew.min(axis=1) // 2)
    E = np.where(E == np.iinfo(np.int32).max, 0, E)
    sc = np.where(Mc == 0, 0, ec - E[:, None, None])
    sw = np.where(Mw == 0, 0, ew - 2 * E[:, None])
    small = _small_row_integers(Mc, ec, Mw, ew, j)
    if small is not None:  # int64 suffices for every intermediate (grids, halves)
        X, Wi, E = small
    else:
        X = Mc.astype(object) << sc.astype(object)
        Wi = Mw.astype(object) << sw.astype(object)
    A = [X[:, i + 1, :] - X[:, 0, :] for i in range(j)]
    G = [[None] * j for _ in range(j)]
    for s_ in range(j):
        for t_ in range(s_, j):
            G[s_][t_] = G[t_][s_] = (A[s_] * A[t_]).sum(axis=1)
    b2 = [G[i][i] - Wi[:, i + 1] + Wi[:, 0] for i in range(j)]  # 2 beta, scaled
    if j == 1:
        det = G[0][0]
        adj = [[1]]
    elif j == 2:
        det = G[0][0] * G[1][1] - G[0][1] * G[1][0]
        adj = [[G[1][1], -G[0][1]], [-G[1][0], G[0][0]]]
    else:
        (g00, g01, g02), (g10, g11, g12), (g20, g21, g22) = G
        c00 = g11 * g22 - g12 * g21
        c01 = g12 * g20 - g10 * g22
        c02 = g10 * g21 - g11 * g20
        det = g00 * c00 + g01 * c01 + g02 * c02
        adj = [
            [c00, g02 * g21 - g01 * g22, g01 * g12 - g02 * g11],
            [c01, g00 * g22 - g02 * g20, g02 * g10 - g00 * g12],
            [c02, g01 * g20 - g00 * g21, g00 * g11 - g01 * g10],
        ]
    Nl = [sum(adj[s_][t_] * b2[t_] for t_ in range(j)) for s_ in range(j)]  # lam = N / (2 det)
    den = 2 * det
    # rho * 2**-2E = lam . b2 / 2 - W0 = (N . b2 - 2 den W0) / (2 den)
    num = sum(p * q for p, q in zip(Nl, b2)) - 2 * den * Wi[:, 0]
    sp, sq = float(scale).as_integer_ratio()
    flat = np.array([d == 0 for d in det.tolist()], dtype=bool)
    rho = np.zeros(m)
    done = _small_quotients(num, den, E, sp, sq, rho) if small is not None else np.zeros(m, dtype=bool)
    for t_, (nu, de, e) in enumerate(zip(num.tolist(), den.tolist(), E.tolist())):
        if de != 0 and not done[t_]:
            nu, de = nu * sq * sq, 2 * de * sp * sp
            rho[t_] = (nu << 2 * e) / de if e >= 0 else nu / (de << -2 * e)
    lam_num = [den - sum(Nl)] + Nl  # signs of lam_0..lam_j (den >= 0)
    att = np.stack([np.array([v < 0 for v in q.tolist()], dtype=bool) for q in lam_num], axis=1)
    return rho, att, flat


def _small_quotients(num, den, E, sp: int, sq: int, rho) -> np.ndarray:
    """``rho = num sq^2 2^(2E) / (2 den sp^2)`` for int64 rows of :func:`_exact_rows`
    where numerator and denominator are exact in float64 (below 2**53): one IEEE
    division, correctly rounded as Python's ``int / int``, times a power of two (exact
    in the normal range).  Fills ``rho`` there; returns the mask of rows done."""
    if sp >= 2**26 or sq >= 2**26:
        return np.zeros(num.shape, dtype=bool)
    a, b = float(sq * sq), float(2 * sp * sp)
    ok = (den != 0) & (np.abs(num) < 2.0**53 / a) & (np.abs(den) < 2.0**53 / b)
    with np.errstate(all="ignore"):
        q = np.ldexp((num * (sq * sq)).astype(np.float64) / (den * (2 * sp * sp)).astype(np.float64), 2 * E)
    ok &= np.isfinite(q) & ((q == 0) | (np.abs(q) >= np.finfo(np.float64).tiny))
    rho[ok] = q[ok]
    return ok


def _small_row_integers(Mc, ec, Mw, ew, j: int):
    """For :func:`_exact_rows`: the rows' centres and weights as int64 integers at
    the coarsest common scale of each row (trailing zero bits dropped, so dyadic
    input gives small integers), with the row exponents ``E``; ``None`` unless a
    bound shows that no intermediate of the adjugate solve can reach 2**62."""
    big = np.iinfo(np.int32).max
    m = Mc.shape[0]

    def low(M, e):  # exponent of the lowest set bit; 'big' for zero
        a = np.abs(M)
        lb = np.log2((a & -a).astype(np.float64), where=a != 0, out=np.zeros(a.shape))
        return np.where(a == 0, big, e + lb.astype(np.int64))

    lc, lw = low(Mc, ec), low(Mw, ew)
    E = np.minimum(lc.reshape(m, -1).min(axis=1), lw.min(axis=1) // 2)
    E = np.where(E == big, 0, E)
    # magnitudes in units 2**E (floats: only a bound; a row mixing tiny and huge
    # values overflows to inf here and takes the object road, without a warning)
    with np.errstate(over="ignore"):
        ac = np.abs(Mc) * np.exp2(np.where(Mc == 0, 0, ec - E[:, None, None]).astype(np.float64))
        aw = np.abs(Mw) * np.exp2(np.where(Mw == 0, 0, ew - 2 * E[:, None]).astype(np.float64))
    if not (np.all(ac < 2.0**60) and np.all(aw < 2.0**60)):
        return None
    a = 2.0 * ac.max(axis=(1, 2))  # |A| entries
    wm = aw.max(axis=1)
    g = 3.0 * a * a  # |G|
    bb = g + 2.0 * wm  # |2 beta|
    det_m = 6.0 * g**j
    n_m = 3.0 * 2.0 * g ** (j - 1) * bb
    num_m = 3.0 * n_m * bb + 4.0 * det_m * wm
    if not np.all(np.maximum(num_m, 4.0 * det_m + 3.0 * n_m) < 2.0**61):
        return None
    sc = np.where(Mc == 0, 0, ec - E[:, None, None])
    sw = np.where(Mw == 0, 0, ew - 2 * E[:, None])
    lcs = np.where(Mc == 0, 0, lc - ec)  # trailing zeros
    lws = np.where(Mw == 0, 0, lw - ew)
    X = (Mc >> lcs) << (sc + lcs)
    Wi = (Mw >> lws) << (sw + lws)
    return X, Wi, E


def _orthospheres_certified(balls: Balls, fr, S: np.ndarray):
    """Smallest orthogonal spheres and attachment of the rows S (frame-local
    indices), each certified (Notes §23.1).

    Returns ``(rho, att)`` as :func:`_orthospheres` does, ``rho`` in frame units
    (divided by ``fr.scale**2``).

    1. All rows, vectorised, in float64 on the input's own centres and weights
       (``balls.centers``, ``balls.weights``: exact binary numbers, so the only
       errors are the kernel's own roundings, relative to each simplex's size and
       not to the input's extent or offset), with the error bound of
       :func:`_orthospheres`.  On random input this decides > 99.9 % of the rows.
    2. The rows the bound rejects, vectorised, from the input centres relative to
       each row's first vertex in ``np.longdouble`` (80-bit on x86-64, 11 more bits;
       skipped where it is plain double), with the same bound.
    3. The rows still rejected in exact rational arithmetic (:func:`_exact_rows`),
       rounded once to float64: nearly flat simplices, orthospheres of power 0 or
       nearly so, and orthocentres on or near a facet (exact ties of the Gabriel
       test, as on integer grids).

    A row whose vertices are exactly affinely dependent (which a certified regular
    triangulation never yields as a top simplex; kept as a guard) gets the
    minimum-norm orthosphere of its span and a facet-by-facet power test.
    """
    m = S.shape[0]
    if S.shape[1] == 1:
        return -fr.w[S[:, 0]], np.zeros((m, 1), dtype=bool)
    # 1. float64 on the input's own numbers (exact: no rounding before the kernel's)
    identity = fr.keep.size == len(balls)
    c = balls.centers if identity else balls.centers[fr.keep]
    w = balls.weights if identity else balls.weights[fr.keep]
    rho, att, bad = _orthospheres_chunked(c, w, S)
    s2 = fr.scale * fr.scale
    if s2 != 1.0:
        rho /= s2
    idx = np.flatnonzero(bad)
    if idx.size == 0:
        return rho, att
    # 2. long double, where it is longer than double
    ld = np.longdouble
    if np.finfo(ld).eps < np.finfo(np.float64).eps:
        for a in range(0, idx.size, _CHUNK):
            sub = idx[a : a + _CHUNK]
            xl, wl, Sl = _local_rows(balls, fr, S[sub], ld)
            r, at, bd = _orthospheres(xl, wl, Sl)
            rho[sub] = (r / (ld(fr.scale) * ld(fr.scale))).astype(np.float64)
            att[sub] = at
            bad[sub] = bd
        idx = np.flatnonzero(bad)
        if idx.size == 0:
            return rho, att
    # 3. exact
    for a in range(0, idx.size, _CHUNK):
        sub = idx[a : a + _CHUNK]
        r, at, fl = _exact_rows(balls.centers, balls.weights, fr.keep[S[sub]], fr.scale)
        rho[sub] = r
        att[sub] = at
        bad[sub] = fl
    flat = np.flatnonzero(bad)
    if flat.size:
        _flat_rows_guard(fr, S, flat, rho, att)
    return rho, att


def _flat_rows_guard(fr, S: np.ndarray, idx: np.ndarray, rho: np.ndarray, att: np.ndarray) -> None:
    """Rows of exactly affinely dependent vertices: the minimum-norm orthocentre in
    their span and the power test done facet by facet (in place)."""
    Sf = S[idx]
    x, w = np.asarray(fr.x, dtype=np.float64), np.asarray(fr.w, dtype=np.float64)
    _, r = _ortho_generic(x, w, Sf)
    rho[idx] = r
    for i, cols in enumerate(_drop_cols(S.shape[1])):
        F = Sf[:, cols]
        uf, rf = _ortho_generic(x, w, F)
        d = x[F[:, 0]] + uf - x[Sf[:, i]]
        att[idx, i] = np.einsum("mk,mk->m", d, d) - w[Sf[:, i]] < rf


# ----------------------------------------------------------------------------------
# Results
# ----------------------------------------------------------------------------------
def _check_k(k, dim_max: int) -> int:
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, (int, np.integer)):
        raise TypeError(f"k must be an integer dimension, got {type(k).__name__}")
    k = int(k)
    if not 0 <= k <= dim_max:
        raise ValueError(f"k must be between 0 and {dim_max}, got {k}")
    return k


class _SimplicialMixin:
    """Accessors shared by :class:`Filtration` and :class:`Complex`."""

    def simplices(self, k: int) -> np.ndarray:
        """The k-simplices, shape (n_k, k+1), int32 indices into ``balls``.

        int32, as in ``scipy.spatial.Delaunay.simplices``: it halves the memory of
        the filtration (a ball index never needs more; ``Balls`` holds fewer than
        2**31 balls in any machine's memory).

        Vertices ascend within each row; rows are in filtration order
        (non-decreasing entry time, ties broken lexicographically).  For
        ``dimension < k <= d`` the array is empty.
        """
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return freeze(np.zeros((0, k + 1), dtype=np.int32))
        return self._simplices[k][: self._counts[k]]

    def values(self, k: int) -> np.ndarray:
        """Entry times τ of the k-simplices, shape (n_k,), non-decreasing."""
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return freeze(np.zeros(0))
        return self._values[k][: self._counts[k]]

    def boundary(self, k: int) -> np.ndarray:
        """Facet rows of the k-simplices, shape (n_k, k+1), int32, for k >= 1.

        Entry ``[i, j]`` is the row index into ``simplices(k-1)`` of the facet of
        simplex ``i`` opposite its vertex ``simplices(k)[i, j]``.
        """
        k = _check_k(k, self.balls.dim)
        if k == 0:
            raise ValueError("k must be >= 1 for boundary(k): vertices have no facets")
        if k > self.dimension:
            return freeze(np.zeros((0, k + 1), dtype=np.int32))
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

    See Also
    --------
    dual_complex
        Builds it.
    Filtration.complex_at
        The complex of a filtration at τ.
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


class BoundaryMatrix(NamedTuple):
    """The boundary matrix of a filtration over :math:`\\mathbb{Z}/2`
    (:meth:`Filtration.boundary_matrix`).

    Column (and row) ``i`` is the simplex ``F.simplices(dims[i])[rows[i]]``, which
    enters at ``values[i]``.

    See Also
    --------
    Filtration.boundary_matrix : builds it.
    shapelab.topology.reduce_boundary : reduces it.
    """

    #: (n, n) ``scipy.sparse.csc_matrix`` of 0/1 (uint8): entry ``[i, j]`` is 1 when
    #: simplex ``i`` is a facet of simplex ``j``.
    matrix: object
    #: (n,) int64: the dimension of each simplex.
    dims: np.ndarray
    #: (n,) int64: its row in ``F.simplices(dims[i])``.
    rows: np.ndarray
    #: (n,) float64: its entry time τ, non-decreasing.
    values: np.ndarray


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

    See Also
    --------
    alpha_filtration
        Builds it.
    shapelab.topology.persistence
        Its persistence pairs.
    """

    balls: Balls
    dimension: int
    _simplices: tuple
    _values: tuple
    _boundary: tuple
    _counts: tuple
    #: Results derived from the filtration (persistence pairs, merge tree, cycles,
    #: edge lookups), by key; filled on first use by :meth:`derived`.
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def derived(self, key: str, build):
        """A result derived from this filtration, built on first use and kept on it.

        The filtration owns what is computed from it (Notes §23.1: one filtration,
        many questions -- Betti numbers at every τ, persistence, voids, pockets and
        tunnels), so the modules that answer them (:mod:`shapelab.topology`,
        :mod:`shapelab.cavities`) store their intermediate results here instead of
        in module-level caches: they live exactly as long as the filtration.

        Parameters
        ----------
        key : str
            Names the result (e.g. ``"topology.summary"``); one key, one builder.
        build : callable
            ``build(F)`` computes the result from this filtration.  Results must be
            treated as read-only: every later caller gets the same object.

        Returns
        -------
        object
            ``build(self)``, computed once per filtration.

        Notes
        -----
        A copy with nothing derived yet (to time a computation from scratch) is
        ``dataclasses.replace(F)``: it shares the simplices and entry times.
        """
        try:
            return self._derived[key]
        except KeyError:
            return self._derived.setdefault(key, build(self))

    def clipped_cells(self, tau=0.0, *, bbox=None, arc_resolution: int = 96) -> tuple:
        """The cells :math:`B_i(\\tau) \\cap \\Pi(B_i)` of 2D balls as polygons (Notes
        §23.1, Figure 23.1): :func:`shapelab.power.clipped_cells` with the power
        diagram of these balls computed once per filtration and box and kept on it,
        so that a drawing at many τ (a slider) clips the same diagram.

        Parameters
        ----------
        tau : float
            Growth time (finite).
        bbox : array_like (2, 2), optional
            The box the power cells are clipped to; it must hold the grown disks.
            By default the disks' box at ``tau`` padded by 1 (a new diagram per τ).
        arc_resolution : int
            Points per full circle on the arcs.

        Returns
        -------
        tuple of ndarray
            One (k_i, 2) counter-clockwise polygon per ball, (0, 2) when empty.
        """
        balls = check_balls(self.balls, "F.balls", dim=2)
        t = as_tau(tau, finite=True)
        if bbox is None:
            w = balls.weights + max(t, 0.0)
            r = np.sqrt(w)[:, None]
            bbox = (
                np.array([(balls.centers - r).min(axis=0) - 1.0, (balls.centers + r).max(axis=0) + 1.0])
                if len(balls)
                else np.array([[0.0, 0.0], [1.0, 1.0]])
            )
        box = as_bbox(bbox, 2)
        diagram = self.derived(f"power.diagram[{box.tobytes().hex()}]", lambda F: power_diagram(F.balls, bbox=box))
        return clipped_cells(balls, tau=t, diagram=diagram, arc_resolution=arc_resolution)

    def complex_at(self, tau) -> Complex:
        """The dual complex :math:`K(\\tau)`: all simplices with entry time ≤ ``tau``.

        ``tau`` may be ``±inf``; ``complex_at(inf)`` is the whole triangulation and
        ``complex_at(0.0)`` the dual complex of the balls as given.
        """
        t = as_tau(tau)
        counts = tuple(int(np.searchsorted(v, t, side="right")) for v in self._values)
        dim = max((k for k, c in enumerate(counts) if c > 0), default=-1)
        return Complex(self.balls, t, dim, self._simplices, self._values, self._boundary, counts)

    def attached(self, k: int) -> np.ndarray:
        """Which k-simplices are *attached*: enter with a coface, not at their own time.

        Parameters
        ----------
        k : int
            Dimension, ``0 <= k <= balls.dim``.

        Returns
        -------
        ndarray of bool, shape (n_k,)
            Aligned with :meth:`simplices` and :meth:`values`: ``True`` where the
            k-simplex is attached.  Top-dimensional simplices are never attached.

        Notes
        -----
        Notes §23.1 (the growth model).  Let :math:`(c_\\sigma, \\rho_\\sigma)` be the
        smallest orthogonal sphere of :math:`\\sigma`: the point of the affine hull of
        :math:`\\sigma` with equal power :math:`\\rho_\\sigma` from all its balls.
        :math:`\\sigma` is *unattached* if no other ball is closer to :math:`c_\\sigma`
        in power, :math:`\\pi_v(c_\\sigma) \\ge \\rho_\\sigma` for every vertex
        :math:`v` of a coface (equivalently, of every ball); then
        :math:`c_\\sigma` lies in the power face dual to :math:`\\sigma` and
        :math:`\\sigma` enters at :math:`\\rho_\\sigma`.  Otherwise it is *attached*:
        its cells first meet at a point of that face where the power is higher than
        :math:`\\rho_\\sigma`, on the boundary of the face, i.e. together with a
        coface, and it enters at the earliest entry time of its cofaces [1]_, [2]_.
        The test is exact (the sign of a barycentric coordinate of the coface's
        orthocentre, certified or in rational arithmetic); in a tie
        (:math:`\\pi_v(c_\\sigma) = \\rho_\\sigma`) the simplex counts as unattached,
        and both rules give the same time.  A vertex is attached when a neighbour's
        power covers its centre (:math:`c = z_i`, :math:`\\rho = -r_i^2`).

        Computed on first use (one more pass over the triangulation) and kept on
        the filtration.

        See Also
        --------
        values : the entry times; ``values(k)[attached(k)]`` are coface times.
        shapelab.power_distance : :math:`\\pi_v(x)`.

        References
        ----------
        .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete
           Comput. Geom.* 13 (1995) 415-440.
        .. [2] H. Edelsbrunner and J. L. Harer, *Computational Topology*, AMS, 2010,
           §III.4 (alpha complexes).

        Examples
        --------
        Three unit disks on an obtuse triangle: the orthogonal circle of the long
        edge is centred at (2, 0) with :math:`\\rho = 2^2 - 1 = 3`, and the third
        centre has power :math:`1 - 1 = 0 < 3` there, so the edge is attached and
        enters with the triangle (circumcentre (2, -1.5), :math:`6.25 - 1`):

        >>> import shapelab as sl
        >>> F = sl.alpha_filtration(sl.Balls([[0, 0], [4, 0], [2, 1]], 1.0))
        >>> F.simplices(1).tolist()
        [[0, 2], [1, 2], [0, 1]]
        >>> F.attached(1).tolist()
        [False, False, True]
        >>> F.values(1).tolist(), F.values(2).tolist()
        ([0.25, 0.25, 5.25], [5.25])
        """
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return freeze(np.zeros(0, dtype=bool))
        return self.derived("filtration.attached", _attached_flags)[k]

    def betti(self, tau) -> tuple:
        """Betti numbers of :math:`K(\\tau)` (see :func:`shapelab.topology.betti`)."""
        return _topology.betti(self, tau)

    def betti_curve(self, taus) -> np.ndarray:
        """Betti numbers at each τ (see :func:`shapelab.topology.betti_curve`)."""
        return _topology.betti_curve(self, taus)

    def boundary_matrix(self) -> BoundaryMatrix:
        """The boundary matrix :math:`D` of the filtration over :math:`\\mathbb{Z}/2`,
        columns and rows in filtration order (Notes §23.1, "Voids and pockets").

        Every simplex of the filtration is one column and one row, ordered by entry
        time, then dimension, then row of :meth:`simplices` (the order in which
        :func:`shapelab.topology.persistence` reads the filtration).  Column ``j`` holds
        the boundary of simplex ``j``: a 1 in the row of each of its facets.

        Returns
        -------
        BoundaryMatrix
            ``(matrix, dims, rows, values)``: the (n, n) ``scipy.sparse.csc_matrix``
            of 0/1 (uint8), and for each column its dimension, its row in
            ``simplices(dims[i])`` and its entry time τ.

        See Also
        --------
        shapelab.topology.reduce_boundary : the standard column reduction of ``D``.
        shapelab.topology.persistence : the pairs, computed without this matrix.

        Notes
        -----
        A face enters no later than its cofaces, and at a tie the lower dimension
        comes first, so :math:`D` is strictly upper triangular.  Reducing its columns
        (:func:`shapelab.topology.reduce_boundary`) pairs the simplices that create a
        homology class with those that destroy one [1]_, [2]_.  Dense, it has
        :math:`n^2` entries: meant for small filtrations (lessons, tests).

        References
        ----------
        .. [1] H. Edelsbrunner, D. Letscher, A. Zomorodian, "Topological persistence and
           simplification", Discrete Comput. Geom. 28 (2002) 511-533.
        .. [2] H. Edelsbrunner, J. Harer, *Computational Topology: An Introduction*,
           AMS (2010), §VII.1.

        Examples
        --------
        >>> import shapelab as sl
        >>> F = sl.alpha_filtration(sl.Balls([[0, 0], [2, 0], [1, 1.5]], [0.5, 0.5, 0.5]))
        >>> B = F.boundary_matrix()
        >>> B.dims.tolist()
        [0, 0, 0, 1, 1, 1, 2]
        >>> F.simplices(1).tolist()  # the two sides of length 1.80 enter first
        [[0, 2], [1, 2], [0, 1]]
        >>> B.matrix.toarray()
        array([[0, 0, 0, 1, 0, 1, 0],
               [0, 0, 0, 0, 1, 1, 0],
               [0, 0, 0, 1, 1, 0, 0],
               [0, 0, 0, 0, 0, 0, 1],
               [0, 0, 0, 0, 0, 0, 1],
               [0, 0, 0, 0, 0, 0, 1],
               [0, 0, 0, 0, 0, 0, 0]], dtype=uint8)
        """
        from scipy.sparse import csc_matrix

        top = self.dimension
        dims = np.concatenate([np.full(int(self._counts[k]), k, dtype=np.int64) for k in range(top + 1)] or [[]])
        rows = np.concatenate([np.arange(int(self._counts[k]), dtype=np.int64) for k in range(top + 1)] or [[]])
        values = np.concatenate([np.asarray(self.values(k), dtype=np.float64) for k in range(top + 1)] or [[]])
        dims, rows = dims.astype(np.int64), rows.astype(np.int64)
        order = np.lexsort((rows, dims, values))
        dims, rows, values = dims[order], rows[order], values[order]
        n = order.size
        pos = [np.empty(int(self._counts[k]), dtype=np.int64) for k in range(top + 1)]
        for k in range(top + 1):
            pos[k][rows[dims == k]] = np.flatnonzero(dims == k)
        r_idx, c_idx = [], []
        for k in range(1, top + 1):
            cols = np.flatnonzero(dims == k)
            facets = np.asarray(self.boundary(k), dtype=np.int64)[rows[cols]]
            r_idx.append(pos[k - 1][facets].ravel())
            c_idx.append(np.repeat(cols, k + 1))
        r = np.concatenate(r_idx) if r_idx else np.zeros(0, dtype=np.int64)
        c = np.concatenate(c_idx) if c_idx else np.zeros(0, dtype=np.int64)
        D = csc_matrix((np.ones(r.size, dtype=np.uint8), (r, c)), shape=(n, n))
        D.sort_indices()
        for a in (dims, rows, values):
            a.flags.writeable = False
        return BoundaryMatrix(D, dims, rows, values)

    def persistence(self, *, field=2) -> dict:
        """Persistence diagrams over :math:`\\mathbb{Z}/p`, ``p = field`` (default 2; see
        :func:`shapelab.topology.persistence`)."""
        return _topology.persistence(self, field=field)

    def __repr__(self) -> str:
        return f"Filtration(n_balls={len(self.balls)}, dimension={self.dimension}, counts={self.counts()})"


def as_filtration(F, who: str):
    """The filtration a function works on: ``F`` itself, or ``alpha_filtration(F)``
    when ``F`` is a :class:`~shapelab.Balls` (built once and kept with the balls:
    :meth:`shapelab.Balls.derived`).  The one input rule of the library.

    ``F`` may also be any object with the filtration's accessors and ``.balls``
    (``dimension``, ``simplices(k)``, ``values(k)``, ``boundary(k)``).  ``who`` names
    the calling function in the error message.
    """
    if isinstance(F, Balls):
        return F.derived("filtration.alpha", alpha_filtration)
    missing = [a for a in ("balls", "dimension", "simplices", "values", "boundary") if not hasattr(F, a)]
    if missing or not isinstance(F.balls, Balls):
        what = f"it has no {missing[0]!r}" if missing else "its .balls is not a shapelab.Balls"
        raise TypeError(
            f"{who}: F must be a Filtration (shapelab.alpha_filtration(balls)) or a shapelab.Balls; "
            f"{what} (got {type(F).__name__})"
        )
    return F


# ----------------------------------------------------------------------------------
# The algorithm
# ----------------------------------------------------------------------------------
def _empty_filtration(balls: Balls) -> Filtration:
    d = balls.dim
    simp = tuple(freeze(np.zeros((0, k + 1), dtype=np.int32)) for k in range(d + 1))
    vals = tuple(freeze(np.zeros(0)) for _ in range(d + 1))
    bnd = (None,) + tuple(freeze(np.zeros((0, k + 1), dtype=np.int32)) for k in range(1, d + 1))
    return Filtration(balls, -1, simp, vals, bnd, tuple(0 for _ in range(d + 1)))


def alpha_filtration(balls: Balls) -> Filtration:
    """The α-filtration of the balls: every simplex of DT with its entry time τ.

    Parameters
    ----------
    balls : Balls

    Returns
    -------
    Filtration

    See Also
    --------
    dual_complex
        The complex at one growth time.
    Filtration
        What it returns.
    regular_triangulation
        The triangulation it filters.

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

    Accuracy: step 2 is computed from the input's own float64 numbers (centres and
    ``balls.weights``) with a forward error bound per simplex; where the bound does
    not certify the value to relative accuracy 1e-9 or the sign of every
    barycentric coordinate (nearly flat simplices, powers near 0, orthocentres on a
    facet), the simplex is recomputed in long double and then in exact rational
    arithmetic (:func:`_orthospheres_certified`).  So each value is within 1e-9
    (typically a few ulp) of the exact value for the float64 input, exact zeros
    are exact, and the Gabriel test is exact.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053
    .. [2] H. Edelsbrunner and E. P. Mücke, "Three-dimensional alpha shapes", *ACM Trans.
           Graph.* 13(1):43-72, 1994. doi:10.1145/174462.156635
    """
    check_balls(balls)
    res = _entry_times(balls)
    if res is None:
        return _empty_filtration(balls)
    fr, faces, bnd, vals, dim = res

    # 5. filtration order per dimension, back to input indices and scale
    s2 = fr.scale**2
    simp_out, vals_out, bnd_out = [], [], [None]
    inv_prev = None
    identity = fr.keep.size == len(balls)  # no duplicate centres: local = input
    for j in range(dim + 1):
        v = vals[j] * s2 if s2 != 1.0 else vals[j]
        # local indices are ordered like input indices (keep is ascending), so the
        # lexicographic tie-break can use them
        order = _filtration_order(v, faces[j])
        out = np.empty(faces[j].shape, dtype=np.int32)
        if identity and faces[j].dtype == out.dtype:  # gather straight into the output
            np.take(faces[j], order, axis=0, out=out)
        else:
            out[...] = fr.keep[faces[j][order]]
        simp_out.append(freeze(out))
        vals_out.append(freeze(np.take(v, order)))
        faces[j] = vals[j] = v = None  # free as we go
        if j >= 1:
            out = np.take(bnd[j], order, axis=0).astype(np.int32, copy=False)
            np.take(inv_prev, out, out=out)  # (out= is buffered: in place is safe)
            bnd_out.append(freeze(out))
            bnd[j] = None
        inv_prev = np.empty(order.size, dtype=np.int32)
        inv_prev[order] = np.arange(order.size, dtype=np.int32)
        del order
    for j in range(dim + 1, balls.dim + 1):
        simp_out.append(freeze(np.zeros((0, j + 1), dtype=np.int32)))
        vals_out.append(freeze(np.zeros(0)))
        bnd_out.append(freeze(np.zeros((0, j + 1), dtype=np.int32)))
    counts = tuple(int(a.shape[0]) for a in simp_out)
    return Filtration(balls, dim, tuple(simp_out), tuple(vals_out), tuple(bnd_out), counts)


def _entry_times(balls: Balls, *, with_attached: bool = False):
    """Steps 1-4 of :func:`alpha_filtration`: faces, boundary matrices and entry times
    per dimension, in frame-local indices and units (``None`` if there are no balls).
    With ``with_attached``, a sixth item: the attachment flags per dimension (the
    top dimension's all False), aligned with the faces."""
    fr, simp, nbr = triangulate_local(balls)
    if simp.shape[0] == 0:
        return None
    dim = simp.shape[1] - 1
    nv = fr.keep.size
    w = fr.w

    # 1. all faces, top-down, with boundary matrices (local vertex indices)
    faces = [None] * (dim + 1)
    bnd = [None] * (dim + 1)
    faces[dim] = simp
    for j in range(dim, 0, -1):
        res = _facets_from_neighbours(simp, nbr) if (j == dim and j >= 2) else None
        faces[j - 1], bnd[j] = res if res is not None else _unique_facets(faces[j], nv)

    # 2. smallest orthogonal spheres and attachment, 3. top-down propagation
    vals = [None] * (dim + 1)
    flags = [None] * dim + [np.zeros(faces[dim].shape[0], dtype=bool)]
    rho, att = _orthospheres_certified(balls, fr, faces[dim])
    vals[dim] = rho
    for j in range(dim, 0, -1):
        B = bnd[j]
        if j > 1:
            rho_f, att_f = _orthospheres_certified(balls, fr, faces[j - 1])
        else:
            rho_f, att_f = -w[faces[0][:, 0]], None
        nf = faces[j - 1].shape[0]
        attached = np.zeros(nf, dtype=bool)
        attached[B[att]] = True
        cof = np.full(nf, np.inf)
        for i in range(j + 1):
            np.minimum.at(cof, B[:, i], vals[j])
        vals[j - 1] = np.where(attached, cof, rho_f)
        if with_attached:
            flags[j - 1] = attached
        del cof, attached
        att = att_f
    # 4. non-decreasing against round-off (GUDHI's make_filtration_non_decreasing)
    for j in range(1, dim + 1):
        for i in range(j + 1):
            np.maximum(vals[j], vals[j - 1][bnd[j][:, i]], out=vals[j])
    if with_attached:
        return fr, faces, bnd, vals, dim, flags
    return fr, faces, bnd, vals, dim


def _attached_flags(F: Filtration) -> tuple:
    """The attachment flag of every simplex of ``F``, per dimension, in the order of
    ``F.simplices(k)`` (what :meth:`Filtration.attached` returns): the entry times
    are recomputed with the flags and sorted exactly as :func:`alpha_filtration`
    sorts them, and the rows are checked to be ``F``'s own."""
    res = _entry_times(F.balls, with_attached=True)
    if res is None:
        return ()
    fr, faces, _, vals, dim, flags = res
    s2 = fr.scale**2
    out = []
    for j in range(dim + 1):
        v = vals[j] * s2 if s2 != 1.0 else vals[j]
        order = _filtration_order(v, faces[j])
        rows = fr.keep[faces[j][order]]
        if not np.array_equal(rows, F.simplices(j)):  # pragma: no cover - F built elsewhere
            raise ValueError("F: its simplices are not those of alpha_filtration(F.balls)")
        out.append(freeze(flags[j][order]))
    return tuple(out)


def simplices_up_to(balls: Balls, select) -> list:
    """The simplices whose entry times ``v`` (input units) pass ``select(v)`` (a
    boolean array), per dimension (input indices, unordered), without building the
    :class:`Filtration`: what :func:`shapelab.union_measure` needs.  Same entry times
    as :func:`alpha_filtration`.  ``select`` must be monotone (if it accepts v, it
    accepts every smaller value), so that the result is a complex.  Shared with
    :mod:`shapelab.measure`; not in ``__all__``."""
    res = _entry_times(balls)
    if res is None:
        return []
    fr, faces, _, vals, dim = res
    s2 = fr.scale**2
    out = []
    for j in range(dim + 1):
        v = vals[j] * s2 if s2 != 1.0 else vals[j]
        rows = faces[j][select(v)]
        if rows.shape[0] == 0:
            break
        out.append(fr.keep[rows] if fr.keep.size != len(balls) else rows)
    return out


def _filtration_order(v: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Permutation sorting by value, ties broken lexicographically by the rows.

    One ``np.lexsort`` on integer keys: the order-preserving integer image of the
    values (``-0.0`` counted as ``0.0``, so equal floats give equal keys) and the rows
    packed into as few int64 words as their columns fit in (most significant column
    first).  Rows are distinct, so the order is total and does not depend on the
    algorithm; ``lexsort`` is stable besides.
    """
    m = v.size
    if m == 0:
        return np.zeros(0, dtype=np.int64)
    key = (v + 0.0).view(np.int64)  # + 0.0: -0.0 -> 0.0
    if np.any(key < 0):  # negative floats: reversed, below the positive ones
        key = np.where(key < 0, np.int64(-(2**63)) - key - 1, key)
    w = rows.shape[1]
    bits = max(1, int(rows.max()).bit_length())
    per = max(1, 62 // bits)  # columns per int64 word
    words = []
    for a in range(0, w, per):
        word = rows[:, a].astype(np.int64)
        for c in range(a + 1, min(w, a + per)):
            word <<= np.int64(bits)
            word |= rows[:, c]
        words.append(word)
    return np.lexsort(words[::-1] + [key])


def dual_complex(balls: Balls) -> Complex:
    """The dual complex K of the union of the balls as given (Notes §23.1).

    Same as ``alpha_filtration(balls).complex_at(0.0)``: the nerve of the clipped
    cells :math:`B_i \\cap \\Pi(B_i)`.

    See Also
    --------
    alpha_filtration
        Every growth time at once.
    shapelab.oracles.sampled_nerve
        The same nerve by sampling, an oracle.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053
    """
    return alpha_filtration(balls).complex_at(0.0)
