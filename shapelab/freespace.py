"""Free space of a union of balls: the exact area or volume of cells the balls miss.

Notes §23.1, "Voids and pockets": the free space of a void or pocket is the part of
its Delaunay cells that no grown ball covers.  :mod:`shapelab.cavities` finds the
cells; this module measures them.

``void_measure`` (behind ``Void.volume``) is the fractional inclusion–exclusion over a
void's cells (Edelsbrunner & Fu; Liang et al. 1998): for every cell :math:`t`,
:math:`\\mathrm{vol}(t) - \\sum_{v} \\tfrac{\\Omega_v}{4\\pi}\\mathrm{vol}(B_v)
+ \\sum_{e \\in K} \\tfrac{\\varphi_e}{2\\pi}\\mathrm{vol}(B_a \\cap B_b)
- \\sum_{f \\in K} \\tfrac12 \\mathrm{vol}(B_a \\cap B_b \\cap B_c)`, with solid angles
:math:`\\Omega` and dihedral angles :math:`\\varphi` of the cell (in 2D: angles and
half lenses).  Summed over the cells of a void it is exact; the tests check it
against an independent exact computation (:func:`free_measure`) and Monte Carlo.
The same sum is *not* exact for a pocket, whose mouth is not covered by the balls
(ball caps poke through it), so ``Pocket.volume`` uses :func:`free_measure`, the exact
power-cell decomposition :math:`U \\cap t = \\bigsqcup_i B_i \\cap \\Pi_i \\cap t`, each
piece a ball clipped by a convex polytope, integrated in closed form (lens, cap and
triple-ball volumes).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from itertools import combinations

import numpy as np

from ._toolkit.geometry import cross_rows
from ._toolkit.validate import as_tau, check_balls
from .balls import power_distance
from .filtration import derived

__all__ = ["free_measure", "free_space", "FreeSpace", "void_measure", "vertex_values", "free_points"]


def vertex_values(F, n_balls: int) -> np.ndarray:
    """Entry time of every ball in ``F`` (``inf`` for a ball that never enters)."""
    out = np.full(n_balls, np.inf)
    out[np.asarray(F.simplices(0), dtype=np.int64).ravel()] = F.values(0)
    return out


# ============================================================ fractional measure
def _cross2(a, b):
    """z-component of the cross product of 2D vectors (row-wise)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _lens_area(d, r1, r2):
    d = np.asarray(d, float)
    out = np.zeros_like(d)
    inside = d <= np.abs(r1 - r2)
    out[inside] = np.pi * np.minimum(r1, r2)[inside] ** 2
    m = (~inside) & (d < r1 + r2)
    if np.any(m):
        dd, a, b = d[m], r1[m], r2[m]
        c1 = np.clip((dd * dd + a * a - b * b) / (2 * dd * a), -1, 1)
        c2 = np.clip((dd * dd + b * b - a * a) / (2 * dd * b), -1, 1)
        k = (-dd + a + b) * (dd + a - b) * (dd - a + b) * (dd + a + b)
        out[m] = a * a * np.arccos(c1) + b * b * np.arccos(c2) - 0.5 * np.sqrt(np.maximum(k, 0))
    return out


def _lens_volume(d, r1, r2):
    d = np.asarray(d, float)
    out = np.zeros_like(d)
    inside = d <= np.abs(r1 - r2)
    out[inside] = 4.0 / 3.0 * np.pi * np.minimum(r1, r2)[inside] ** 3
    m = (~inside) & (d < r1 + r2)
    if np.any(m):
        dd, a, b = d[m], r1[m], r2[m]
        out[m] = np.pi * (a + b - dd) ** 2 * (dd * dd + 2 * dd * (a + b) - 3 * (a - b) ** 2) / (12 * dd)
    return out


def _cap_segment(d, l0, l1, q0, q1, r):
    """∫ F(S) dφ with F(S) = (2/3)(r³ - (r² - S²)^{3/2}) along a line at distance ``d``
    from the centre, from arclength ``l0`` to ``l1`` (points inside the disk), vectorised.

    ``q0``, ``q1`` are :math:`\\sqrt{r^2 - d^2 - l^2}` at the two ends, passed in so
    that ends known to lie on the circle get exactly 0: evaluating them from
    coordinates would lose half the digits (square-root conditioning).  The
    antiderivative of :math:`(r^2 - d^2\\sec^2\\varphi)^{3/2}` is, with :math:`a^2 =
    r^2 - d^2`, :math:`r^3\\operatorname{atan2}(r l, d q) - d(r^2 + a^2/2)
    \\operatorname{atan2}(l, q) - d l q / 2`.
    """
    out = np.zeros_like(d)
    m = d > 1e-300
    if np.any(m):
        dd, rr = d[m], r[m]
        a2 = np.maximum(rr * rr - dd * dd, 0.0)

        def J(lv, qv):
            return (
                rr**3 * np.arctan2(rr * lv, dd * qv) - dd * (rr * rr + a2 / 2) * np.arctan2(lv, qv) - 0.5 * dd * lv * qv
            )

        la, lb = l0[m], l1[m]
        phi = np.arctan2(lb, dd) - np.arctan2(la, dd)
        out[m] = (2.0 / 3.0) * (rr**3 * phi - (J(lb, q1[m]) - J(la, q0[m])))
    return out


def _triple_volume(c, r):
    """Exact volume of the intersection of three balls, vectorised.

    ``c`` (m, 3, 3) centres, ``r`` (m, 3) radii, for triples whose radical axis meets
    the intersection (true for every triangle of K).  The intersection is cut by the
    three radical planes into the parts where ball i is the binding one, a ball
    clipped by a dihedral wedge whose edge is the radical axis; each part is the
    integral of the ball's height over a planar region bounded by two radical rays and
    a circular arc, evaluated in closed form.
    """
    m = c.shape[0]
    if m == 0:
        return np.zeros(0)
    o = c.mean(axis=1, keepdims=True)
    c = c - o
    e1 = c[:, 1] - c[:, 0]
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    nrm = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
    e2 = np.cross(nrm, e1)
    p = np.stack([np.einsum("mij,mj->mi", c, e1), np.einsum("mij,mj->mi", c, e2)], axis=-1)  # (m,3,2)
    r2 = r * r
    # power centre w: 2(p_j - p_0).w = |p_j|^2 - |p_0|^2 - r_j^2 + r_0^2
    A = 2 * (p[:, 1:] - p[:, :1])
    rhs = (p[:, 1:] ** 2).sum(-1) - (p[:, :1] ** 2).sum(-1) - r2[:, 1:] + r2[:, :1]
    w = np.linalg.solve(A, rhs[..., None])[..., 0]
    total = np.zeros(m)
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        pi, pj, pk = p[:, i], p[:, j], p[:, k]
        ri = r[:, i]
        wi = w - pi  # w relative to centre i
        h2 = np.maximum(r2[:, i] - (wi**2).sum(-1), 0.0)

        def perp_toward(a, b):
            # unit vector perpendicular to a, with positive component along b
            q = np.stack([-a[:, 1], a[:, 0]], axis=-1)
            q /= np.linalg.norm(q, axis=1, keepdims=True)
            s = np.sign((q * b).sum(-1))
            s[s == 0] = 1
            return q * s[:, None]

        uu = perp_toward(pj - pi, pk - pi)
        vv = perp_toward(pk - pi, pj - pi)

        def exit_pt(dirn, wi=wi, h2=h2):
            bdot = (wi * dirn).sum(-1)
            s = -bdot + np.sqrt(bdot * bdot + h2)
            return wi + s[:, None] * dirn

        eu, ev = exit_pt(uu), exit_pt(vv)
        mid = uu + vv
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        em = exit_pt(mid)
        th = lambda x: np.arctan2(x[:, 1], x[:, 0])  # noqa: E731
        tu, tv, tm = th(eu), th(ev), th(em)
        two = 2 * np.pi
        ccw = np.mod(tm - tu, two) <= np.mod(tv - tu, two)
        dth = np.where(ccw, np.mod(tv - tu, two), -np.mod(tu - tv, two))

        def seg(a, b, qa, qb, ri=ri):
            # signed ∫ F dθ along the straight segment a -> b (centre at origin)
            ab = b - a
            L = np.linalg.norm(ab, axis=1)
            ok = L > 1e-300
            uhat = ab / np.where(ok, L, 1.0)[:, None]
            la = (a * uhat).sum(-1)
            q = a - la[:, None] * uhat  # foot of the centre on the line
            d = np.linalg.norm(q, axis=1)
            lb = (b * uhat).sum(-1)
            side = np.sign(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
            val = _cap_segment(d, la, lb, qa, qb, ri)
            return np.where(ok, side * val, 0.0)

        qw = np.sqrt(h2)
        zero = np.zeros_like(qw)
        part = seg(wi, eu, qw, zero) + (2.0 / 3.0) * ri**3 * dth + seg(ev, wi, zero, qw)
        total += np.sign(dth) * part
    return total


def _build_edge_lookup(F):
    e = np.asarray(F.simplices(1), dtype=np.int64)
    key = e[:, 0] * len(F.balls) + e[:, 1]
    o = np.argsort(key)
    return key[o], o


def _edge_lookup(F):
    """Edges of ``F`` as sorted integer keys ``i * n + j`` and the sorting permutation."""
    return derived(F, "cavities.edge_keys", _build_edge_lookup)


def void_measure(F, balls, tau: float, cell_ids: np.ndarray) -> np.ndarray:
    """Fractional inclusion–exclusion free measure of each cell (exact summed over a
    void; see the module docstring)."""
    k = int(F.dimension)
    simp = np.asarray(F.simplices(k), dtype=np.int64)[cell_ids]
    W = balls.weights
    vval = vertex_values(F, len(balls))
    X = balls.centers[simp]
    X = X - X.mean(axis=1, keepdims=True)
    r2 = W[simp] + tau
    vin = (vval[simp] <= tau) & (r2 >= 0)
    r2 = np.where(vin, np.maximum(r2, 0.0), 0.0)
    rr = np.sqrt(r2)
    fval = np.asarray(F.values(k - 1))
    fin = fval[np.asarray(F.boundary(k), dtype=np.int64)[cell_ids]] <= tau  # facet j opposite vertex j
    if k == 2:
        area = 0.5 * np.abs(_cross2(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]))
        out = area.copy()
        for j in range(3):
            a, b = X[:, (j + 1) % 3] - X[:, j], X[:, (j + 2) % 3] - X[:, j]
            th = np.arctan2(np.abs(_cross2(a, b)), (a * b).sum(-1))
            out -= 0.5 * th * r2[:, j]
            # edge opposite vertex j
            p, q = (j + 1) % 3, (j + 2) % 3
            dist = np.linalg.norm(X[:, q] - X[:, p], axis=1)
            lens = _lens_area(dist, rr[:, p], rr[:, q])
            out += 0.5 * np.where(fin[:, j], lens, 0.0)
        return out
    # k == 3
    vol = np.abs(np.einsum("mi,mi->m", X[:, 1] - X[:, 0], np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 0]))) / 6
    out = vol.copy()
    for j in range(4):
        o = [i for i in range(4) if i != j]
        a, b, c = (X[:, i] - X[:, j] for i in o)
        la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
        num = np.abs(np.einsum("mi,mi->m", a, np.cross(b, c)))
        den = la * lb * lc + (a * b).sum(-1) * lc + (a * c).sum(-1) * lb + (b * c).sum(-1) * la
        omega = 2 * np.arctan2(num, den)
        out -= omega * rr[:, j] ** 3 / 3.0
    keys, order = _edge_lookup(F)
    eval_ = np.asarray(F.values(1))
    for p, q in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)):
        s, t = [i for i in range(4) if i not in (p, q)]
        key = simp[:, p] * len(balls) + simp[:, q]
        idx = order[np.searchsorted(keys, key)]
        ein = eval_[idx] <= tau
        if not np.any(ein):
            continue
        e = X[:, q] - X[:, p]
        L = np.linalg.norm(e, axis=1)
        eh = e / L[:, None]
        ps = X[:, s] - X[:, p]
        pt = X[:, t] - X[:, p]
        ps -= (ps * eh).sum(-1)[:, None] * eh
        pt -= (pt * eh).sum(-1)[:, None] * eh
        phi = np.arctan2(np.linalg.norm(np.cross(ps, pt), axis=1), (ps * pt).sum(-1))
        lv = _lens_volume(L, rr[:, p], rr[:, q])
        out += np.where(ein, phi / (2 * np.pi) * lv, 0.0)
    for j in range(4):
        m = fin[:, j]
        if not np.any(m):
            continue
        o = [i for i in range(4) if i != j]
        tv = _triple_volume(X[m][:, o], rr[m][:, o])
        out[m] -= 0.5 * tv
    return out


# ================================================================ exact measure
def _poly_vertices(A, b, eps):
    """Vertices of the bounded polytope {x : A x <= b} by brute force over d-subsets of
    its planes (few planes here: a simplex plus the power planes of nearby balls)."""
    p, d = A.shape
    idx = _COMBOS[d](p)
    if idx.shape[0] == 0:
        return np.empty((0, d))
    M = A[idx]
    det = np.linalg.det(M)
    ok = np.abs(det) > 1e-12 * np.prod(np.linalg.norm(M, axis=2), axis=1)
    if not np.any(ok):
        return np.empty((0, d))
    X = np.linalg.solve(M[ok], b[idx[ok]][..., None])[..., 0]
    X = X[np.all(X @ A.T <= b + eps, axis=1)]
    if X.shape[0] <= 1:
        return X
    # merge near-duplicates (several plane triples through one vertex)
    key = np.round(X / (100 * eps)).astype(np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    return X[np.sort(first)]


def _combos(d):
    from functools import lru_cache
    from itertools import combinations

    @lru_cache(maxsize=64)
    def f(p):
        return np.array(list(combinations(range(p), d)), dtype=np.int64).reshape(-1, d)

    return f


_COMBOS = {2: _combos(2), 3: _combos(3)}


def _segment_integral(kind, h, d, la, lb, r):
    """Vectorised ∫ F(d sec φ) dφ between arclengths la < lb on a line at distance d
    from the foot of the centre; the radial integrals behind disk ∩ polygon (kind 2)
    and ball ∩ polytope (kind 3, face plane at signed distance h from the centre).

    kind 2: F(S) = min(S, r)²/2 (area of a disk sector fan).
    kind 3: F(S) = ∫_0^S min(1, r³/(h²+s²)^{3/2}) s ds (ball ∩ cone over a face).
    Inside the inner radius ρ0 (r in 2D, √(r²-h²) in 3D) F = S²/2, whose integral is
    d·Δl/2; outside it is elementary (atan2 / arcsin).
    """
    out = np.zeros_like(d)
    ok = d > 1e-300
    if not np.any(ok):
        return out
    h, d, la, lb, r = (x[ok] for x in (h, d, la, lb, r))
    if kind == 2:
        rho2 = r * r
    else:
        rho2 = r * r - h * h
    has_in = (rho2 > 0) & (d * d < rho2)
    ls = np.sqrt(np.where(has_in, rho2 - d * d, 0.0))
    # inner piece [max(la,-ls), min(lb,ls)]
    lo = np.maximum(la, -ls)
    hi = np.minimum(lb, ls)
    inner = np.where(has_in & (hi > lo), 0.5 * d * (hi - lo), 0.0)

    def outer(a, b):
        if kind == 2:
            return 0.5 * r * r * (np.arctan2(b, d) - np.arctan2(a, d))
        ah = np.abs(h)
        C0 = np.where(rho2 > 0, 0.5 * rho2 + r * r, r**3 / np.maximum(ah, 1e-300))
        k = np.sqrt(h * h + d * d)
        sa, sb = a / np.hypot(a, d), b / np.hypot(b, d)
        return C0 * (np.arctan2(b, d) - np.arctan2(a, d)) - (r**3 / np.maximum(ah, 1e-300)) * (
            np.arcsin(np.clip(ah * sb / k, -1, 1)) - np.arcsin(np.clip(ah * sa / k, -1, 1))
        )

    # outer pieces: without an inner disk, the whole [la, lb]; else the parts beyond ±ls
    a1, b1 = la, np.where(has_in, np.minimum(lb, -ls), lb)
    a2, b2 = np.where(has_in, np.maximum(la, ls), lb), lb
    res = inner + np.where(b1 > a1, outer(a1, b1), 0.0) + np.where(b2 > a2, outer(a2, b2), 0.0)
    out[ok] = res
    return out


def _ball_clip_measure(A, b, r, eps, keep=0, boundary=False):
    """Measure of the ball (disk) of radius r at the origin ∩ the bounded polytope
    {x : A x <= b}: a sum of closed-form radial integrals over the polytope's edges
    (2D) or its faces' edges (3D), each signed by the side the centre lies on.

    With ``boundary=True`` returns ``(measure, sphere)``, where ``sphere`` is the
    measure of the sphere (circle) of radius r inside the polytope, from the
    divergence theorem about the centre: ``d * measure = r * sphere + Σ_f h_f |f ∩ B|``
    (``h_f`` the signed distance of facet f's plane, ``|f ∩ B|`` the facet's part in the
    ball), so no further integral is needed."""
    if A.shape[1] == 3:
        return _ball_clip_measure3(A, b, r, eps, keep, boundary)
    nA = np.linalg.norm(A, axis=1)
    dist = b / nA  # signed distance of the centre to each line
    if np.any(dist <= -r):
        return (0.0, 0.0) if boundary else 0.0  # the disk misses a halfplane
    if np.all(dist >= r):
        return (np.pi * r * r, 2 * np.pi * r) if boundary else np.pi * r * r
    V = _poly_vertices(A, b, eps)
    if V.shape[0] < 3:
        return (0.0, 0.0) if boundary else 0.0
    D, LA, LB, S, H = [], [], [], [], []
    for q in range(A.shape[0]):
        n = A[q] / nA[q]
        on = np.abs(V @ n - dist[q]) <= 10 * eps
        if on.sum() < 2:
            continue
        # the edge on this line, oriented counter-clockwise (interior on the left)
        P = V[on]
        t = np.array([-n[1], n[0]])
        P = P[np.argsort(P @ t)]
        a_, b_ = P[0], P[-1]
        ab = b_ - a_
        L = np.linalg.norm(ab)
        if L <= 0:
            continue
        u = ab / L
        la = a_ @ u
        D.append(np.linalg.norm(a_ - la * u)), LA.append(la), LB.append(la + L)
        S.append(np.sign(_cross2(ab, -a_)))
        H.append(dist[q])
    if not D:
        return (0.0, 0.0) if boundary else 0.0
    D, LA, LB, S, H = (np.asarray(x, dtype=np.float64) for x in (D, LA, LB, S, H))
    I = _segment_integral(2, np.zeros_like(D), D, LA, LB, np.full(D.shape, r))
    area = float(np.sum(S * I))
    if not boundary:
        return area
    # chord of each edge inside the disk, weighted by the edge line's signed distance
    half = np.sqrt(np.maximum(r * r - D * D, 0.0))
    chord = np.maximum(np.minimum(LB, half) - np.maximum(LA, -half), 0.0)
    return area, max((2.0 * area - float(np.sum(H * chord))) / r, 0.0)


@lru_cache(maxsize=64)
def _triples(p):
    return np.array(list(combinations(range(p), 3)), dtype=np.int64).reshape(-1, 3)


def _vertices3(A, b, eps):
    """Vertices of the bounded polytope {x : A x <= b} (rows of A unit normals):
    every triple of planes solved by Cramer's rule, kept if feasible."""
    idx = _triples(A.shape[0])
    na, nb, nc = A[idx[:, 0]], A[idx[:, 1]], A[idx[:, 2]]
    bc, ca, ab = cross_rows(nb, nc), cross_rows(nc, na), cross_rows(na, nb)
    det = (na * bc).sum(1)
    ok = np.abs(det) > 1e-12
    X = (b[idx[ok, 0], None] * bc[ok] + b[idx[ok, 1], None] * ca[ok] + b[idx[ok, 2], None] * ab[ok]) / det[ok, None]
    X = X[np.all(X @ A.T <= b + eps, axis=1)]
    if X.shape[0] <= 1:
        return X
    key = np.round(X / (100 * eps)).astype(np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    return X[np.sort(first)]


_BOX = np.vstack([np.eye(3), -np.eye(3)])
_REF = (np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))


def _ball_clip_measure3(A, b, r, eps, keep=0, boundary=False):
    """Volume of the ball of radius r at the origin ∩ the bounded polytope {x : A x <= b}.

    Planes the ball lies inside are dropped, except the first ``keep`` rows (which
    must bound the polytope on their own; with ``keep=0`` a box around the ball does
    that instead); the faces of what is left, with their edges in counter-clockwise order,
    are found at once from the vertex–plane incidences, and the volume is the sum of
    closed-form radial integrals over those edges (see :func:`_segment_integral`).
    """
    nA = np.sqrt((A * A).sum(1))
    dist = b / nA
    if np.any(dist <= -r):
        return (0.0, 0.0) if boundary else 0.0
    cut = dist < r
    if not np.any(cut):
        return (4.0 / 3.0 * np.pi * r**3, 4.0 * np.pi * r * r) if boundary else 4.0 / 3.0 * np.pi * r**3
    if keep:
        cut[:keep] = True
        A2, b2 = A[cut] / nA[cut, None], dist[cut]
    else:
        A2 = np.concatenate([A[cut] / nA[cut, None], _BOX])
        b2 = np.concatenate([dist[cut], np.full(6, 2.0 * r)])
    V = _vertices3(A2, b2, eps)
    if V.shape[0] < 4:
        return (0.0, 0.0) if boundary else 0.0
    inc = np.abs(V @ A2.T - b2) <= 10 * eps
    cnt = inc.sum(axis=0)
    planes = np.flatnonzero(cnt >= 3)
    sub = inc[:, planes]
    vi, qi = np.nonzero(sub)
    q = planes[qi]
    n = A2[q]
    c = ((sub.T @ V) / cnt[planes][:, None])[qi]
    ref = np.where(np.abs(n[:, :1]) < 0.6, _REF[0], _REF[1])
    e1 = cross_rows(n, ref)
    e1 /= np.sqrt((e1 * e1).sum(1))[:, None]
    e2 = cross_rows(n, e1)
    rel = V[vi] - c
    ang = np.arctan2((rel * e2).sum(1), (rel * e1).sum(1))
    o = np.lexsort((ang, q))
    vi, q = vi[o], q[o]
    m = q.size
    first = np.concatenate(([True], q[1:] != q[:-1]))
    last = np.concatenate((q[1:] != q[:-1], [True]))
    gs = np.maximum.accumulate(np.where(first, np.arange(m), 0))
    nxt = np.arange(1, m + 1)
    nxt[last] = gs[last]
    a_ = V[vi]
    ab = V[vi[nxt]] - a_
    n = A2[q]
    h = b2[q]
    foot = h[:, None] * n
    L = np.sqrt((ab * ab).sum(1))
    ok = (L > 0) & (np.abs(h) > 1e-14 * r)
    a_, ab, L, n, h, foot = a_[ok], ab[ok], L[ok], n[ok], h[ok], foot[ok]
    u = ab / L[:, None]
    rel = a_ - foot
    la = (rel * u).sum(1)
    perp = rel - la[:, None] * u
    dd = np.sqrt((perp * perp).sum(1))
    side = np.sign((cross_rows(ab, foot - a_) * n).sum(1))
    I = _segment_integral(3, h, dd, la, la + L, np.full(h.shape, r))
    vol = float(np.sum(h / 3.0 * side * I))
    if not boundary:
        return vol
    # the facets' parts in the ball: disks of radius sqrt(r² - h²) clipped by the facet,
    # from the same edges (kind 2); then the divergence theorem gives the sphere's part
    rho = np.sqrt(np.maximum(r * r - h * h, 0.0))
    I2 = _segment_integral(2, h, dd, la, la + L, rho)
    return vol, max((3.0 * vol - float(np.sum(h * side * I2))) / r, 0.0)


def _simplex_halfspaces(X):
    """Halfspaces A x <= b of a simplex with vertices X (d+1, d)."""
    d = X.shape[1]
    A, b = [], []
    for j in range(d + 1):
        o = [i for i in range(d + 1) if i != j]
        P = X[o]
        if d == 2:
            t = P[1] - P[0]
            n = np.array([-t[1], t[0]])
        else:
            n = np.cross(P[1] - P[0], P[2] - P[0])
        n = n / np.linalg.norm(n)
        if n @ (X[j] - P[0]) > 0:
            n = -n
        A.append(n)
        b.append(n @ P[0])
    return np.array(A), np.array(b)


def free_measure(balls, tau, cells) -> np.ndarray:
    """Exact free measure (area in 2D, volume in 3D) of simplices not covered by the balls.

    For each simplex :math:`t` (a row of ``cells``, ball indices) returns
    :math:`\\mathrm{vol}(t) - \\mathrm{vol}(t \\cap U_\\tau)`, where :math:`U_\\tau` is
    the union of all balls grown to ``tau`` (Notes §23.1).  Uses the power-diagram
    decomposition :math:`U \\cap t = \\bigsqcup_i B_i \\cap \\Pi_i \\cap t` (Notes §23.1,
    :math:`U \\cap \\Pi(B_i) = B_i \\cap \\Pi(B_i)`): each piece is a ball clipped by a
    convex polytope, whose volume is a sum over its faces and their edges of
    closed-form integrals (no sampling).  Costs about a millisecond per simplex and
    ball meeting it: meant for pockets and checks, not for millions of cells.

    Parameters
    ----------
    balls : Balls
    tau : float
    cells : array_like, shape (m, d+1), int
        Simplices as ball indices (any simplices, not only Delaunay ones).

    Returns
    -------
    ndarray, shape (m,)
    """
    return _free_space(balls, tau, cells, False).measure


@dataclass(frozen=True, eq=False)
class FreeSpace:
    """Free measure and wall of simplices (see :func:`free_space`).

    Attributes
    ----------
    measure : ndarray, shape (m,)
        Free volume (area in 2D) of each simplex: as :func:`free_measure`.
    wall : ndarray, shape (m,)
        Measure of :math:`\\partial U_\\tau \\cap t`: the area (length in 2D) of the
        union's boundary inside each simplex.
    contact_cell, contact_ball, contact_wall : ndarray, shape (q,)
        The wall split by ball: simplex row, ball index and the measure of
        :math:`\\partial B_i \\cap \\Pi_i \\cap t` (positive entries only); summed per
        simplex they give ``wall``.
    """

    measure: np.ndarray
    wall: np.ndarray
    contact_cell: np.ndarray
    contact_ball: np.ndarray
    contact_wall: np.ndarray


def free_space(balls, tau, cells) -> FreeSpace:
    """Exact free measure and wall of simplices: :func:`free_measure` plus the boundary.

    The wall of a simplex :math:`t` is :math:`\\partial U_\\tau \\cap t
    = \\bigsqcup_i \\partial B_i \\cap \\Pi_i \\cap t` (a point of sphere i inside its
    power cell is on the boundary of the union).  Each piece comes from the same
    clipped ball as the volume, by the divergence theorem about the ball's centre
    (:math:`d\\,\\mathrm{vol}(B \\cap Q) = r\\,|\\partial B \\cap Q| + \\sum_f h_f |f \\cap B|`,
    the facet parts being disks (chords in 2D) clipped by a polygon, in closed form):
    exact, no sampling.  Summed over the cells of a void it is the void's surface
    area (Notes §23.1, "Voids and pockets").

    Parameters
    ----------
    balls : Balls
    tau : float
    cells : array_like, shape (m, d+1), int
        Simplices as ball indices (any simplices, not only Delaunay ones).

    Returns
    -------
    FreeSpace
    """
    return _free_space(balls, tau, cells, True)


def _free_space(balls, tau, cells, boundary):

    from scipy.spatial import cKDTree

    check_balls(balls)
    tau = as_tau(tau)
    d = balls.dim
    cells = np.asarray(cells)
    if cells.ndim != 2 or cells.shape[1] != d + 1 or (cells.size and cells.dtype.kind not in "iu"):
        raise ValueError(f"cells must be an integer array of shape (m, {d + 1}), got shape {cells.shape}")
    if cells.size and (cells.min() < 0 or cells.max() >= len(balls)):
        raise ValueError(f"cells holds ball indices outside 0..{len(balls) - 1}")
    w = balls.weights + tau
    alive = np.flatnonzero(w >= 0)
    out = np.zeros(cells.shape[0])
    wall = np.zeros(cells.shape[0])
    cc, cb, cw = [], [], []

    def result():
        ints = lambda x: np.asarray(x, dtype=np.int64)  # noqa: E731
        return FreeSpace(out, wall, ints(cc), ints(cb), np.asarray(cw, dtype=np.float64))

    if cells.shape[0] == 0 or tau == np.inf:  # at τ = inf the balls cover everything
        return result()
    C = balls.centers
    tree = cKDTree(C[alive]) if alive.size else None
    rmax = float(np.sqrt(w[alive].max())) if alive.size else 0.0
    for m, cell in enumerate(cells.astype(np.int64)):
        X0 = C[cell]
        o = X0.mean(axis=0)
        X = X0 - o
        scale = float(np.max(np.linalg.norm(X, axis=1)))
        if d == 2:
            meas = 0.5 * abs(float(_cross2(X[1] - X[0], X[2] - X[0])))
        else:
            meas = abs(np.dot(X[1] - X[0], np.cross(X[2] - X[0], X[3] - X[0]))) / 6
        if meas <= 0 or tree is None:
            out[m] = meas
            continue
        As, bs = _simplex_halfspaces(X)
        cand = alive[tree.query_ball_point(o, scale + rmax)]
        Z = C[cand] - o
        R = np.sqrt(w[cand])
        # a ball misses the simplex if it lies beyond one of its facet planes
        gap = np.max(Z @ As.T - bs, axis=1)
        keep = (gap < R) & (R > 0)
        cand, Z, R = cand[keep], Z[keep], R[keep]
        eps = 1e-12 * max(scale, 1e-300)
        covered = 0.0
        for i in range(cand.shape[0]):
            # only balls meeting B_i can cut B_i ∩ Π_i (a point of B_i closer in power to
            # z_j lies in B_j); power halfspaces 2 (z_j - z_i).x <= |z_j|² - |z_i|² - w_j + w_i
            dz = np.linalg.norm(Z - Z[i], axis=1)
            js = np.flatnonzero((dz < R + R[i]) & (np.arange(cand.shape[0]) != i))
            Ap = 2 * (Z[js] - Z[i])
            bp = (Z[js] ** 2).sum(1) - (Z[i] ** 2).sum() - R[js] ** 2 + R[i] ** 2
            A = np.vstack([As, Ap])
            b = np.concatenate([bs, bp])
            got = _ball_clip_measure(A, b - A @ Z[i], float(R[i]), eps, keep=d + 1, boundary=boundary)
            if boundary:
                got, sph = got
                if sph > 0:
                    wall[m] += sph
                    cc.append(m), cb.append(int(cand[i])), cw.append(sph)
            covered += got
        out[m] = meas - covered
    return result()


def free_points(balls, tau, cells, n_points, rng) -> np.ndarray:
    """Points of the free space inside ``cells`` (uniform in the cells, then kept where
    no ball grown to τ covers them, by :func:`shapelab.power_distance`): a picture of a
    void's shape for :func:`shapelab.plot.voids`, not a measurement.

    Parameters
    ----------
    balls : Balls
    tau : float
    cells : int array (m, d+1)
        Simplices as ball indices.
    n_points : int
        Points drawn in the cells before the covered ones are dropped.
    rng : numpy.random.Generator

    Returns
    -------
    ndarray (k, d)
    """
    X = balls.centers[cells]  # (m, d+1, d)
    E = X[:, 1:] - X[:, :1]
    vol = np.abs(np.linalg.det(E))
    if not len(cells) or vol.sum() <= 0:
        return np.zeros((0, balls.dim))
    k = rng.multinomial(n_points, vol / vol.sum())
    idx = np.repeat(np.arange(len(cells)), k)
    w = rng.dirichlet(np.ones(balls.dim + 1), size=len(idx))
    pts = np.einsum("mk,mkd->md", w, X[idx])
    keep = power_distance(pts, balls).min(axis=1) > tau if len(pts) else np.zeros(0, bool)
    return pts[keep]
