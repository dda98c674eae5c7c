"""The union measure's machinery (not required reading).

* the dual complex just before τ from the certified entry times, without sorting them
  into a Filtration (:func:`complex_before`), and the tie rule (:data:`TIE_TOL`);
* the simplices in cache-sized blocks, in coordinates relative to each simplex's first
  centre (:func:`relative_blocks`);
* vector helpers on the component-first layout (``(d, m)``: one row per coordinate,
  one column per simplex): norms, unit vectors, angles by ``atan2``, orthocentres by
  closed-form solves;
* flat top simplices of the dual complex, whose pieces are the limits of the general
  closed forms of :mod:`shapelab.measure`, found through the affine dependency of
  their centres (``precision="exact"``; the closed forms are passed in).
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from .._toolkit import tolerances as tol
from .._toolkit.geometry import cross, dot
from .alpha import entry_times

__all__ = [
    "FLAT_TOL",
    "TIE_TOL",
    "angle",
    "arc_angle",
    "before",
    "complex_before",
    "flat_limits",
    "flatness",
    "norm",
    "orthocenter",
    "pieces_flat",
    "relative_blocks",
    "tangent_angle",
    "towards",
    "unit",
]

#: A simplex with entry time v is in the complex measured at τ iff
#: ``v + TIE_TOL * |v| < tau``: K is taken just before τ, and a simplex entering
#: within TIE_TOL of τ *relative to its own entry time* counts as entering after τ.
#: The entry times are certified to relative accuracy ``ENTRY_TIME_RTOL`` (1e-9;
#: exact zeros are exact), which TIE_TOL must exceed so that simplices whose exact
#: entry times tie at τ are all left out (``shapelab/_toolkit/tolerances.py``,
#: ``tests/library/test_tolerances.py``).  At exact ties (tangent balls, cospherical
#: centres whose orthosphere has power exactly τ) round-off would otherwise decide
#: their membership one by one; the intersections of the simplices so left out have
#: measure of order :math:`(\mathrm{TIE\_TOL}\,|\tau|)^{d/2}` or less at τ, and
#: attached pairs, which enter together, are left out together.
TIE_TOL = tol.MEASURE_TIE

_BLOCK = 8192


# ================================================================ the complex
def before(values: np.ndarray, tau: float) -> np.ndarray:
    """Which entry times count as before τ: ``v + TIE_TOL * |v| < tau`` (see
    :data:`TIE_TOL`).  The left side increases with v, so the selection is closed
    under faces (a face enters no later than its cofaces)."""
    return values + TIE_TOL * np.abs(values) < tau


def complex_before(balls, tau: float) -> list:
    """The simplices entering before ``tau`` (:func:`before`), per dimension (input
    indices, in the engine's face order), from the certified entry times of
    :func:`shapelab.alpha_filtration` without building the Filtration: same values,
    same comparison, no sorting."""
    res = entry_times(balls)
    if res is None:
        return []
    fr, faces, _, vals, dim = res
    s2 = fr.scale**2
    out = []
    for j in range(dim + 1):
        v = vals[j] * s2 if s2 != 1.0 else vals[j]
        rows = faces[j][before(v, tau)]
        if rows.shape[0] == 0:
            break
        out.append(fr.keep[rows] if fr.keep.size != len(balls) else rows)
    return out


def relative_blocks(centers: np.ndarray, st: np.ndarray):
    """Yield ``(cols, Z)`` for the simplices ``st`` (shape (k+1, m), one column per
    simplex) in blocks of :data:`_BLOCK` columns: ``Z`` (k+1, d, block) holds the
    centres relative to each simplex's first centre, component-first (exact for huge
    offsets).  In blocks, the ~100 temporaries of a block stay in cache and are reused
    from the heap instead of being mapped (and page-faulted) afresh."""
    ZT = np.ascontiguousarray(np.asarray(centers).T)  # (d, n): gathers per coordinate are contiguous
    k1, d = st.shape[0], ZT.shape[0]
    for a in range(0, st.shape[1], _BLOCK):
        sb = st[:, a : a + _BLOCK]
        Z = np.empty((k1, d, sb.shape[1]))
        for i in range(d):
            z0 = ZT[i].take(sb[0])
            for v in range(k1):
                np.subtract(ZT[i].take(sb[v]), z0, out=Z[v, i])
        yield slice(a, a + _BLOCK), Z


# ============================================================ vector helpers
def norm(a):
    """|a| per column."""
    return np.sqrt(dot(a, a))


def unit(a, fallback=None):
    """a / |a|; the zero vector stays zero (or becomes ``fallback``)."""
    n = norm(a)
    ok = n > 0
    u = a / np.where(ok, n, 1.0)
    if fallback is not None:
        u = np.where(ok, u, fallback)
    return u


def cross_norm(a, b):
    """|a x b| for 2- or 3-vectors."""
    if a.shape[0] == 2:
        return np.abs(a[0] * b[1] - a[1] * b[0])
    return norm(cross(a, b))


def angle(a, b):
    """The angle between vectors a and b in [0, pi], accurately (atan2)."""
    return np.arctan2(cross_norm(a, b), dot(a, b))


def tangent_angle(um, uk, p):
    r"""The angle between the projections of ``um`` and ``uk`` on the plane orthogonal
    to the unit vector ``p``: ``angle(um - (um.p) p, uk - (uk.p) p)`` without forming
    them.  The projections' cross product is parallel to p, of length
    :math:`|\det(u_m, u_k, p)|`, and their dot product is
    :math:`u_m\cdot u_k - (u_m\cdot p)(u_k\cdot p)`."""
    return np.arctan2(np.abs(dot(cross(um, uk), p)), dot(um, uk) - dot(um, p) * dot(uk, p))


def towards(u, w):
    """The unit vector perpendicular to the unit vector ``u`` in span(u, w), on w's side."""
    return unit(w - dot(w, u) * u)


def arc_angle(center, p, q, bisector):
    """Angle (0..2pi) of the arc from p to q on a circle about ``center``, on the side
    of the chord pq that ``bisector`` points to (continuous as the chord shrinks)."""
    chord = q - p
    c = norm(chord)
    qhat = unit(chord)
    n = bisector - dot(bisector, qhat) * qhat
    n = unit(n, fallback=unit(bisector))
    return 2.0 * np.arctan2(0.5 * c, dot(0.5 * (p + q) - center, n))


def solve_ortho(E, b):
    """x with E[i] . x = b[i] for the rows E[i] (each (d, m)), x in span(E).

    Closed forms for 1, 2 (Gram) and 3 (triple product) rows; returns x and the
    determinant (0 for degenerate simplices, where x is set to 0)."""
    k = len(E)
    if k == 1:
        g = dot(E[0], E[0])
        det = g
        x = E[0] * (b[0] / np.where(g != 0, g, 1.0))
    elif k == 2:
        g11, g12, g22 = dot(E[0], E[0]), dot(E[0], E[1]), dot(E[1], E[1])
        det = g11 * g22 - g12 * g12
        s = np.where(det != 0, det, 1.0)
        l1 = (b[0] * g22 - b[1] * g12) / s
        l2 = (g11 * b[1] - g12 * b[0]) / s
        x = l1 * E[0] + l2 * E[1]
    else:
        c23, c31, c12 = cross(E[1], E[2]), cross(E[2], E[0]), cross(E[0], E[1])
        det = dot(E[0], c23)
        s = np.where(det != 0, det, 1.0)
        x = (b[0] * c23 + b[1] * c31 + b[2] * c12) / s
    x = np.where(det != 0, x, 0.0)
    return x, det


def orthocenter(Z, W, idx=None):
    """Orthocentre y of the simplices with local vertices ``idx`` (default all):
    the point of the affine hull with equal power to all their balls, its power,
    and the solve's determinant (:func:`shapelab.orthosphere`, component-first)."""
    idx = list(range(Z.shape[0])) if idx is None else list(idx)
    z0 = Z[idx[0]]
    E = [Z[i] - z0 for i in idx[1:]]
    b = [0.5 * (dot(e, e) + W[idx[0]] - W[i]) for e, i in zip(E, idx[1:])]
    x, det = solve_ortho(E, b)
    return z0 + x, dot(x, x) - W[idx[0]], det


#: A top simplex whose volume is below this fraction of (longest edge)^d is treated
#: as flat: its orthocentre would be determined by rounding noise only.  Relative to
#: the simplex's own size (scale- and translation-invariant); the pieces of a flat
#: simplex are the limits of the general formulas (:func:`pieces_flat`).
FLAT_TOL = tol.MEASURE_FLAT


def flatness(Z):
    """|det(edges)| / (longest edge)^d of top simplices."""
    k1 = Z.shape[0]
    E = [Z[i] - Z[0] for i in range(1, k1)]
    det = np.abs(E[0][0] * E[1][1] - E[0][1] * E[1][0]) if k1 == 3 else np.abs(dot(E[0], cross(E[1], E[2])))
    L = np.max(np.stack([np.sqrt(dot(Z[b] - Z[a], Z[b] - Z[a])) for a, b in combinations(range(k1), 2)]), axis=0)
    return np.where(L > 0, det / np.where(L > 0, L, 1.0) ** (k1 - 1), 0.0)


def flat_limits(Z, W, R, d, P, S, edge_pieces, triangle_pieces) -> None:
    """Replace, in place, the pieces ``P, S`` of the flat top simplices among ``Z``
    (:func:`flatness` below :data:`FLAT_TOL`) by their limits (:func:`pieces_flat`)."""
    flat = flatness(Z) < FLAT_TOL
    if flat.any():
        P[:, flat], S[:, flat] = pieces_flat(Z[..., flat], W[:, flat], R[:, flat], d, edge_pieces, triangle_pieces)


def pieces_flat(Z, W, R, d, edge_pieces, triangle_pieces):
    """Pieces of flat top simplices (the limit of a degenerate configuration).

    A flat d-simplex is in K only when its lifted points are (nearly) affinely
    dependent too: :math:`\\sum_{i\\in +} \\lambda_i \\pi_i = \\sum_{j \\in -}
    |\\lambda_j| \\pi_j` with the signs of the affine dependency of the centres
    (e.g. four cocircular centres in a plane).  Then one constraint of each
    farthest cell :math:`W_l` is implied by the others, and the piece of l is its
    piece in the facet without that vertex: l's partner when l's side of the
    dependency has two vertices, the lone vertex of the other side when l's side
    has three; the piece is empty when l is alone on its side.
    """
    k1, _, m = Z.shape
    M = np.concatenate([np.moveaxis(Z, 2, 0).transpose(0, 2, 1), np.ones((m, 1, k1))], axis=1)
    lam = np.linalg.svd(M)[2][:, -1, :].T  # (k1, m): sum lam_i z_i = 0, sum lam_i = 0
    pos = lam > 0
    P = np.zeros((k1, m))
    S = np.zeros((k1, m))
    for drop in range(k1):
        face = [v for v in range(k1) if v != drop]
        if d == 2:
            Pf, Sf = edge_pieces(Z[face], W[face], R[face], 2)
        else:
            Pf, Sf = triangle_pieces(Z[face], W[face], R[face])
        for j, l in enumerate(face):
            same = pos == pos[l]
            n_same = same.sum(axis=0)
            use = ((n_same == 2) & same[drop]) | ((n_same == k1 - 1) & ~same[drop])
            P[l, use] = Pf[j, use]
            S[l, use] = Sf[j, use]
    return P, S
