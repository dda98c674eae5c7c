"""Smallest orthogonal spheres with a certificate of their accuracy (Notes §23.1).

The exact machinery behind :func:`shapelab.alpha_filtration` with ``precision="exact"``
(the default).  The formula itself is :func:`shapelab.triangulation.orthosphere`: the
point of a simplex's affine hull with equal power to all its balls, from a small linear
system.  Here the same system is solved in float64 on the input's own numbers with a
first-order error bound per simplex (:func:`_orthospheres`); where the bound cannot
certify the value to relative accuracy ``ENTRY_TIME_RTOL`` or the sign of a barycentric
coordinate (the attached test), the simplex is recomputed in long double and then in
exact rational arithmetic (:func:`_exact_rows`), rounded once.  A student may skip it.
"""

from __future__ import annotations

import math

import numpy as np

from .._toolkit.geometry import cross, dot
from .._toolkit.tolerances import ENTRY_TIME_RTOL, ENTRY_TIME_SAFETY, GRAM_PINV_RCOND
from ..balls import Balls
from .faces import drop_cols

__all__ = ["orthospheres_certified"]


def _ortho_generic(x: np.ndarray, w: np.ndarray, S: np.ndarray):
    """Orthocentre offset u (from the first vertex) and rho of simplices S by the
    minimum-norm solution of the Gram system (defined for affinely dependent
    vertices too; used only for exactly degenerate simplices, see
    :func:`orthospheres_certified`)."""
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
        meaningless and must be recomputed (:func:`orthospheres_certified`).

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


def orthospheres_certified(balls: Balls, fr, S: np.ndarray):
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
    for i, cols in enumerate(drop_cols(S.shape[1])):
        F = Sf[:, cols]
        uf, rf = _ortho_generic(x, w, F)
        d = x[F[:, 0]] + uf - x[Sf[:, i]]
        att[idx, i] = np.einsum("mk,mk->m", d, d) - w[Sf[:, i]] < rf
