r"""Area and volume of a union of balls by the short inclusion–exclusion formula
(Notes §23.1; Edelsbrunner, "The union of balls and its dual shape", *Discrete
Comput. Geom.* 13 (1995) 415–440).

The formula
-----------
Let :math:`U = \bigcup_i B_i` and let :math:`K` be its dual complex (Notes §23.1).
Edelsbrunner (1995) proves that inclusion–exclusion over the simplices of :math:`K`
alone is exact:

.. math::
   \operatorname{vol} U \;=\; \sum_{\sigma \in K} (-1)^{\dim \sigma}\,
   \operatorname{vol}\Bigl(\bigcap_{i \in \sigma} B_i\Bigr).

The ordinary formula runs over all :math:`2^n - 1` subsets; this one over at most
:math:`O(n)` (2D) or :math:`O(n^2)` (3D) simplices, and never over more than
:math:`d + 1` balls at a time, because :math:`K` is a subcomplex of the regular
triangulation.  The notes state that :math:`K` has the topology of :math:`U` but do
not give this formula; it is the reason the dual complex makes measures cheap.

Closed forms (derived here, checked in ``tests/library/test_measure.py``)
-----------------------------------------------------------------
Write :math:`\pi_l(x) = \lVert x - z_l \rVert^2 - r_l^2` and, for a simplex
:math:`\sigma \in K` and a vertex :math:`l \in \sigma`, let

.. math:: W_l^\sigma = \{x : \pi_l(x) \ge \pi_m(x)\ \ \forall m \in \sigma\}

be the *farthest* power cell of :math:`l` among the balls of :math:`\sigma`.  A point
is in every ball of :math:`\sigma` iff the largest power distance is :math:`\le 0`,
so :math:`\bigcap_\sigma B = \bigcup_{l\in\sigma} (B_l \cap W_l^\sigma)`: the
intersection splits into one *piece* per vertex.  Because :math:`\sigma \in K`, its
orthocentre :math:`y_\sigma` (the point of :math:`\operatorname{aff}\sigma` with equal
power to all its balls) has power :math:`\le 0` and lies in every ball, and each
piece is a ball cut by at most :math:`d` planes through :math:`y_\sigma`.

By the divergence theorem with respect to the centre :math:`z_l`, for
:math:`P = B_l \cap W_l^\sigma`,

.. math::
   \operatorname{vol} P = \frac{1}{d}\Bigl( r_l\, S_l^\sigma
   \;-\; \sum_{m \in \sigma \setminus l} t_{lm}\, G_{lm}^\sigma \Bigr),

where :math:`S_l^\sigma` is the measure of :math:`\partial B_l \cap W_l^\sigma` (the
part of sphere :math:`l` inside all other balls of :math:`\sigma`),
:math:`t_{lm} = (d_{lm}^2 + r_l^2 - r_m^2)/(2 d_{lm})` the signed distance from
:math:`z_l` to the power plane :math:`H_{lm}`, and :math:`G_{lm}^\sigma` the measure of
the flat face :math:`H_{lm} \cap B_l \cap W_l^\sigma \cap W_m^\sigma`.

* **vertex** (:math:`W = \mathbb{R}^d`): :math:`\pi r^2` and :math:`2\pi r` (2D),
  :math:`\tfrac43 \pi r^3` and :math:`4 \pi r^2` (3D).
* **edge** (:math:`W_l` is the half-space beyond :math:`H_{lm}`), with
  :math:`\rho^2 = r_l^2 - t_{lm}^2` the squared radius of the chord disk:
  2D: :math:`S = 2 r \operatorname{atan2}(\rho, t)`, :math:`G = 2\rho`, so
  :math:`\operatorname{vol}P = r^2 \operatorname{atan2}(\rho,t) - t\rho` (a circular
  segment); 3D: :math:`S = 2\pi r (r - t)` (Archimedes), :math:`G = \pi\rho^2`, so
  :math:`\operatorname{vol}P = \tfrac{\pi}{3}(r-t)^2(2r+t)` (a spherical cap).
* **triangle in 2D** (:math:`W_l` a wedge at :math:`y`): the region
  :math:`\bigcap_\sigma B` is a curvilinear triangle with corners
  :math:`c_k = f_{lm} + \rho_{lm} v` (the intersection point of circles :math:`l, m`
  on the side of :math:`z_k`); :math:`S_l = r_l\theta_l` with :math:`\theta_l` the
  angle of the arc between the two corners on circle :math:`l`, and
  :math:`G_{lm} = \lVert c_k - y \rVert`.
* **triangle in 3D** (:math:`W_l` a dihedral wedge along the line through :math:`y`
  normal to the triangle): :math:`S_l` by Gauss–Bonnet on the sphere,
  :math:`S = r^2 (2\pi - \sum \varepsilon) - r \sum_m t_{lm} \varphi_{lm}`, where the
  :math:`\varepsilon` are the exterior angles at the two corners (the points common to
  the three spheres) and :math:`\varphi_{lm}` the angle of the boundary arc on the
  circle :math:`\partial B_l \cap H_{lm}` (whose geodesic curvature integrates to
  :math:`(t_{lm}/r_l)\varphi_{lm}`); :math:`G_{lm}` is a circular segment of the chord
  disk.
* **tetrahedron in 3D** (:math:`W_l` a trihedral cone at :math:`y`): the same
  Gauss–Bonnet formula with three corners and three arcs, and :math:`G_{lm}` = the
  chord disk cut by a wedge at :math:`y` = a triangle plus a circular segment.

Per-ball contributions
----------------------
Grouping the pieces by ball gives

.. math::
   \operatorname{vol}(B_i \cap \Pi(B_i)) = \sum_{\sigma \ni i} (-1)^{\dim\sigma}
   \operatorname{vol}(B_i \cap W_i^\sigma), \qquad
   \operatorname{area}(\partial B_i \cap \partial U) = \sum_{\sigma \ni i}
   (-1)^{\dim\sigma} S_i^\sigma,

the share of ball :math:`i` in the power-cell decomposition
:math:`U = \bigcup_i B_i \cap \Pi(B_i)` of the notes, and the part of its sphere on
the boundary of the union.  The second is Edelsbrunner's derivative formula
(:math:`\partial \operatorname{vol} U / \partial r_i`); the first follows from the
same argument applied point by point.  Both sum to the totals; the tests check them
against sampling of :math:`B_i \cap \Pi(B_i)`.

Degenerate input
----------------
Tangent balls give simplices whose orthocentre has power exactly 0; their pieces are
the limits of the formulas above (all angles are computed with ``atan2`` so these
limits are taken continuously), and simplices entering at the same time cancel.
Where the regular triangulation is not unique (cocircular centres) any of the
triangulations gives the same measure.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from ._engine import measure as _engine
from ._toolkit import tolerances as tol
from ._toolkit.geometry import cross, dot
from ._toolkit.validate import (
    as_tau,
)
from .balls import Balls
from .filtration import as_filtration, simplices_up_to

__all__ = [
    "UnionMeasure",
    "union_measure",
    "measure_from_simplices",
]

_TWO_PI = 2.0 * np.pi


# =============================================================== result type
@dataclass(frozen=True, eq=False)
class UnionMeasure:
    """Size and boundary of a union of balls, total and per ball.

    Attributes
    ----------
    dim : int
        The dimension d (2: disks, 3: balls).
    tau : float
        The growth time: the balls measured have radii :math:`\\sqrt{r_i^2 + \\tau}`.
    measure : float
        Area (2D) or volume (3D) of the union.
    boundary : float
        Perimeter (2D) or surface area (3D) of the union.
    ball_measure : ndarray, shape (n,)
        Each ball's share :math:`\\operatorname{vol}(B_i \\cap \\Pi(B_i))` of
        ``measure`` (0 for balls whose power cell misses them); sums to ``measure``.
    ball_boundary : ndarray, shape (n,)
        The measure of :math:`\\partial B_i \\cap \\partial U`; sums to ``boundary``.
    terms : tuple of float
        ``terms[k]`` = :math:`\\sum_{\\sigma \\in K, \\dim\\sigma = k}
        \\operatorname{vol}(\\bigcap_{i\\in\\sigma} B_i)`, so that
        ``measure == terms[0] - terms[1] + terms[2] - ...`` (the short formula).
    counts : tuple of int
        Number of k-simplices of K, k = 0..d.

    Properties ``area``, ``perimeter`` (2D), ``volume``, ``surface_area`` (3D) name
    the two numbers in the usual words; in 3D ``area`` is the surface area.

    See Also
    --------
    union_measure
        Produces it.
    """

    dim: int
    tau: float
    measure: float
    boundary: float
    ball_measure: np.ndarray
    ball_boundary: np.ndarray
    terms: tuple
    counts: tuple

    @property
    def area(self) -> float:
        """Area of the union (2D) or of its boundary surface (3D)."""
        return self.measure if self.dim == 2 else self.boundary

    @property
    def perimeter(self) -> float:
        """Perimeter of the union of disks (2D only)."""
        if self.dim != 2:
            raise AttributeError("perimeter is defined for disks (2D); in 3D use surface_area")
        return self.boundary

    @property
    def volume(self) -> float:
        """Volume of the union of balls (3D only)."""
        if self.dim != 3:
            raise AttributeError("volume is defined for balls in 3D; for disks use area")
        return self.measure

    @property
    def surface_area(self) -> float:
        """Surface area of the union of balls (3D only)."""
        if self.dim != 3:
            raise AttributeError("surface_area is defined for balls in 3D; for disks use perimeter")
        return self.boundary

    def __repr__(self) -> str:
        if self.dim == 2:
            what = f"area={self.measure:.6g}, perimeter={self.boundary:.6g}"
        else:
            what = f"volume={self.measure:.6g}, surface_area={self.boundary:.6g}"
        return f"UnionMeasure(dim={self.dim}, tau={self.tau:g}, {what}, counts={self.counts})"


# ====================================================== small vector helpers
# Vectors are stored component-first, shape (d, m): one row per coordinate, one
# column per simplex, so that every operation runs on long contiguous rows.


def _norm(a):
    return np.sqrt(dot(a, a))


def _unit(a, fallback=None):
    """a / |a|; the zero vector stays zero (or becomes ``fallback``)."""
    n = _norm(a)
    ok = n > 0
    u = a / np.where(ok, n, 1.0)
    if fallback is not None:
        u = np.where(ok, u, fallback)
    return u


def _cross_norm(a, b):
    """|a x b| for 2- or 3-vectors."""
    if a.shape[0] == 2:
        return np.abs(a[0] * b[1] - a[1] * b[0])
    return _norm(cross(a, b))


def _angle(a, b):
    """The angle between vectors a and b in [0, pi], accurately (atan2)."""
    return np.arctan2(_cross_norm(a, b), dot(a, b))


def _tangent_angle(um, uk, p):
    """The angle between the projections of ``um`` and ``uk`` on the plane orthogonal
    to the unit vector ``p``: ``_angle(um - (um.p) p, uk - (uk.p) p)`` without forming
    them.  The projections' cross product is parallel to p, of length
    :math:`|\\det(u_m, u_k, p)|`, and their dot product is
    :math:`u_m\\cdot u_k - (u_m\\cdot p)(u_k\\cdot p)`."""
    return np.arctan2(np.abs(dot(cross(um, uk), p)), dot(um, uk) - dot(um, p) * dot(uk, p))


# ============================================================ pair geometry
#: A pair of balls whose chord disk has squared radius below this fraction of
#: max(r_a^2, r_b^2, d_ab^2) is treated as tangent: rounding noise of relative size
#: eps in rho^2 would otherwise become noise of size sqrt(eps) in the angles.
#: Relative to the pair's own size (its radii and distance, in coordinates relative
#: to the simplex's first centre): the input's extent and offset do not enter.
TANGENT_TOL = tol.MEASURE_TANGENT


class _Pair:
    """Geometry of the pair of local vertices (a, b) of every simplex.

    u: unit vector z_a -> z_b; t: signed distance from z_a to the power plane
    H_ab; t_ba = |z_b - z_a| - t; f: centre of the chord disk (on H_ab, on the line
    of centres); rho2: its squared radius (0 for tangent or disjoint pairs).
    """

    __slots__ = ("u", "t", "t_ba", "f", "rho2")

    def __init__(self, Z, W, a, b, tangent=TANGENT_TOL):
        delta = Z[b] - Z[a]
        d = _norm(delta)
        ok = d > 0
        safe = np.where(ok, d, 1.0)
        self.u = delta / safe
        self.t = np.where(ok, (d * d + W[a] - W[b]) / (2.0 * safe), 0.0)
        self.t_ba = d - self.t
        self.f = Z[a] + self.t * self.u
        rho2 = W[a] - self.t * self.t
        # rounding-level overlaps are tangencies (see TANGENT_TOL)
        self.rho2 = np.where(rho2 <= tangent * np.maximum(np.maximum(W[a], W[b]), d * d), 0.0, rho2)


def _pairs(Z, W, tangent=TANGENT_TOL):
    """All pairs of a simplex: ``geo[a, b]`` with u, t seen from a (both orders);
    chords below ``tangent`` (relative) count as tangencies."""
    geo = {}
    for a, b in combinations(range(Z.shape[0]), 2):
        p = _Pair(Z, W, a, b, tangent)
        geo[a, b] = (p.u, p.t, p.f, p.rho2)
        geo[b, a] = (-p.u, p.t_ba, p.f, p.rho2)
    return geo


def _solve_ortho(E, b):
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


def _orthocenter(Z, W, idx=None):
    """Orthocentre y of the simplices with local vertices ``idx`` (default all):
    the point of the affine hull with equal power to all their balls, its power,
    and the solve's determinant."""
    idx = list(range(Z.shape[0])) if idx is None else list(idx)
    z0 = Z[idx[0]]
    E = [Z[i] - z0 for i in idx[1:]]
    b = [0.5 * (dot(e, e) + W[idx[0]] - W[i]) for e, i in zip(E, idx[1:])]
    x, det = _solve_ortho(E, b)
    return z0 + x, dot(x, x) - W[idx[0]], det


def _arc_angle(center, p, q, bisector):
    """Angle (0..2pi) of the arc from p to q on a circle about ``center``, on the side
    of the chord pq that ``bisector`` points to (continuous as the chord shrinks)."""
    chord = q - p
    c = _norm(chord)
    qhat = _unit(chord)
    n = bisector - dot(bisector, qhat) * qhat
    n = _unit(n, fallback=_unit(bisector))
    return 2.0 * np.arctan2(0.5 * c, dot(0.5 * (p + q) - center, n))


def _e_dir(Z, geo, a, b, c):
    """Unit vector perpendicular to z_a z_b in aff(a, b, c), pointing to z_c."""
    u = geo[a, b][0]
    w = Z[c] - Z[a]
    return _unit(w - dot(w, u) * u)


# ======================================================= pieces per simplex
# Each returns (P, S): arrays (k+1, m) with the volume of B_l ∩ W_l^σ and the
# boundary measure of ∂B_l ∩ W_l^σ, for local vertex l of each simplex.


def _pieces_vertex(W, R, d):
    if d == 2:
        return np.pi * W, _TWO_PI * R
    return (4.0 / 3.0) * np.pi * W * R, 4.0 * np.pi * W


def _pieces_edge(Z, W, R, d, geo=None):
    geo = _pairs(Z, W) if geo is None else geo
    P = np.empty(W.shape)
    S = np.empty(W.shape)
    for a, b in ((0, 1), (1, 0)):
        _, t, _, rho2 = geo[a, b]
        if d == 2:
            rho = np.sqrt(rho2)
            S[a] = 2.0 * R[a] * np.arctan2(rho, t)
            G = 2.0 * rho
        else:
            S[a] = _TWO_PI * R[a] * (R[a] - t)
            G = np.pi * rho2
        P[a] = (R[a] * S[a] - t * G) / d
    return P, S


def _pieces_top(Z, W, R, d, geo):
    """Pieces of d-simplices (triangles in 2D, tetrahedra in 3D)."""
    k1 = d + 1
    m = Z.shape[2]
    y, _, _ = _orthocenter(Z, W)
    pairs = list(combinations(range(k1), 2))

    # corner[n]: where the spheres of the other vertices meet, on z_n's side
    corner = [None] * k1
    if d == 2:
        for n in range(3):
            a, b = [v for v in range(3) if v != n]
            f, rho2 = geo[a, b][2], geo[a, b][3]
            corner[n] = f + np.sqrt(rho2) * _e_dir(Z, geo, a, b, n)
    else:
        for n in range(4):
            face = [v for v in range(4) if v != n]
            yf, pf, _ = _orthocenter(Z, W, face)
            nrm = _unit(cross(Z[face[1]] - Z[face[0]], Z[face[2]] - Z[face[0]]))
            side = np.sign(dot(Z[n] - Z[face[0]], nrm))
            corner[n] = yf + (side * np.sqrt(np.maximum(-pf, 0.0))) * nrm

    # flat faces G and arc angles phi of the circles ∂B_a ∩ H_ab, per pair
    G, phi = {}, {}
    for a, b in pairs:
        f, rho2 = geo[a, b][2], geo[a, b][3]
        others = [v for v in range(k1) if v not in (a, b)]
        if d == 2:
            (c,) = others
            G[a, b] = np.sqrt(rho2) - dot(y - f, _e_dir(Z, geo, a, b, c))
        else:
            c, n = others
            ck, cn = corner[c], corner[n]
            ang = _arc_angle(f, ck, cn, _e_dir(Z, geo, a, b, c) + _e_dir(Z, geo, a, b, n))
            tri = 0.5 * _norm(cross(ck - y, cn - y))
            G[a, b] = tri + 0.5 * rho2 * (ang - np.sin(ang))
            phi[a, b] = phi[b, a] = ang
        G[b, a] = G[a, b]

    P = np.empty((k1, m))
    S = np.empty((k1, m))
    for l in range(k1):
        others = [v for v in range(k1) if v != l]
        r = R[l]
        if d == 2:
            mm, kk = others
            # the arc of circle l from its corner with circle mm to its corner with kk
            theta = _arc_angle(Z[l], corner[kk], corner[mm], geo[l, mm][0] + geo[l, kk][0])
            S[l] = r * theta
        else:
            rs = np.where(r > 0, r, 1.0)
            ext = np.zeros(m)
            for n in others:  # corner n lies on sphere l: exterior angle there
                mm, kk = [v for v in others if v != n]
                ph = (corner[n] - Z[l]) / rs
                um, uk = geo[l, mm][0], geo[l, kk][0]
                ext += _tangent_angle(um, uk, ph)
            turn = sum(geo[l, mm][1] * phi[l, mm] for mm in others)
            S[l] = np.where(r > 0, r * r * (_TWO_PI - ext) - r * turn, 0.0)
        flat = sum(geo[l, mm][1] * G[l, mm] for mm in others)
        P[l] = (r * S[l] - flat) / d
    return P, S


def _pieces_triangle3d(Z, W, R, geo=None):
    """Pieces of triangles in 3D (W_l is a dihedral wedge)."""
    geo = _pairs(Z, W) if geo is None else geo
    m = Z.shape[2]
    y, py, _ = _orthocenter(Z, W)
    h = np.sqrt(np.maximum(-py, 0.0))
    nrm = _unit(cross(Z[1] - Z[0], Z[2] - Z[0]))
    G, phi = {}, {}
    for a, b in ((0, 1), (0, 2), (1, 2)):
        (c,) = [v for v in range(3) if v not in (a, b)]
        f, rho2 = geo[a, b][2], geo[a, b][3]
        delta = dot(y - f, _e_dir(Z, geo, a, b, c))
        # the chord disk beyond a chord at signed distance delta from its centre
        # (half-chord h): area rho2 * half - delta * h, arc angle 2 * half
        half = np.arctan2(h, delta)
        G[a, b] = G[b, a] = rho2 * half - delta * h
        phi[a, b] = phi[b, a] = 2.0 * half
    corner = y + h * nrm
    P = np.empty((3, m))
    S = np.empty((3, m))
    for l in range(3):
        mm, kk = [v for v in range(3) if v != l]
        r = R[l]
        ph = (corner - Z[l]) / np.where(r > 0, r, 1.0)
        um, uk = geo[l, mm][0], geo[l, kk][0]
        ext = 2.0 * _tangent_angle(um, uk, ph)
        turn = geo[l, mm][1] * phi[l, mm] + geo[l, kk][1] * phi[l, kk]
        S[l] = np.where(r > 0, r * r * (_TWO_PI - ext) - r * turn, 0.0)
        P[l] = (r * S[l] - geo[l, mm][1] * G[l, mm] - geo[l, kk][1] * G[l, kk]) / 3.0
    return P, S


#: flat top simplices (volume below this fraction of the longest edge^d) are the limits
#: of the general formulas, evaluated by the engine (``shapelab._engine.measure``)
FLAT_TOL = _engine.FLAT_TOL


def _pieces(Z, W, R, d, k, exact=True):
    """Pieces of k-simplices.  A simplex in which two balls only touch has an
    intersection of measure zero (it lies in their lens): its pieces are 0.  With
    ``exact``, rounding-level chords are tangencies and flat top simplices take the
    engine's limits; without, the plain closed forms (generic input)."""
    if k == 0:
        return _pieces_vertex(W, R, d)
    geo = _pairs(Z, W, TANGENT_TOL if exact else 0.0)
    if k == 1:
        return _pieces_edge(Z, W, R, d, geo)
    touch = np.zeros(Z.shape[2], dtype=bool)
    for a, b in combinations(range(k + 1), 2):
        touch |= geo[a, b][3] <= 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        if k == d:
            P, S = _pieces_top(Z, W, R, d, geo)
            flat = _engine.flatness(Z) < FLAT_TOL if exact else np.zeros(Z.shape[2], dtype=bool)
            if flat.any():
                P[:, flat], S[:, flat] = _engine.pieces_flat(
                    Z[..., flat], W[:, flat], R[:, flat], d, _pieces_edge, _pieces_triangle3d
                )
        else:
            P, S = _pieces_triangle3d(Z, W, R, geo)
    P[:, touch] = 0.0
    S[:, touch] = 0.0
    return P, S


# ============================================================ public entry
#: A simplex with entry time v is in the complex measured at τ iff
#: ``v + TIE_TOL * |v| < tau``: K is taken just before τ, and a simplex entering
#: within TIE_TOL of τ *relative to its own entry time* counts as entering after τ
#: (see union_measure).  The entry times are certified to relative accuracy
#: ``ENTRY_TIME_RTOL`` (1e-9; exact zeros are exact), which TIE_TOL must exceed so
#: that simplices whose exact entry times tie at τ are all left out
#: (``shapelab/_toolkit/tolerances.py``, ``tests/library/test_tolerances.py``).
TIE_TOL = tol.MEASURE_TIE


def _before(values: np.ndarray, tau: float) -> np.ndarray:
    """Which entry times count as before τ: ``v + TIE_TOL * |v| < tau`` (see
    :data:`TIE_TOL`).  The left side increases with v, so the selection is closed
    under faces (a face enters no later than its cofaces)."""
    return values + TIE_TOL * np.abs(values) < tau


_BLOCK = 8192


def measure_from_simplices(
    centers, weights, simplices, *, tau: float = 0.0, precision: str = "exact"
) -> UnionMeasure:
    """The short inclusion–exclusion formula over a given dual complex.

    This is the engine of :func:`union_measure`, exposed so that a complex from
    elsewhere (e.g. GUDHI) can be measured.

    Parameters
    ----------
    centers : ndarray, shape (n, d)
    weights : ndarray, shape (n,)
        Squared radii :math:`r_i^2 + \\tau` of the balls to measure.
    simplices : sequence of ndarray
        ``simplices[k]`` is a (n_k, k+1) integer array of the k-simplices of the
        dual complex K of these balls, k = 0, 1, ...
    tau : float
        Only recorded in the result.
    precision : {"exact", "fast"}, default "exact"
        As for :func:`union_measure`.

    Returns
    -------
    UnionMeasure

    See Also
    --------
    union_measure
        The same on the dual complex it builds.
    shapelab.oracles.naive_union_area
        The full inclusion–exclusion formula, an oracle.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053
    """
    Zall = np.asarray(centers, dtype=np.float64)
    Wall = np.asarray(weights, dtype=np.float64)
    n, d = Zall.shape
    Rall = np.sqrt(np.maximum(Wall, 0.0))
    ZT = np.ascontiguousarray(Zall.T)  # (d, n): gathers per coordinate are contiguous
    Wpos = np.maximum(Wall, 0.0)
    ball_measure = np.zeros(n)
    ball_boundary = np.zeros(n)
    terms, counts = [], []
    for k in range(d + 1):
        simp = (
            np.asarray(simplices[k], dtype=np.int64).reshape(-1, k + 1)
            if k < len(simplices)
            else np.zeros((0, k + 1), np.int64)
        )
        counts.append(int(simp.shape[0]))
        if simp.shape[0] == 0:
            terms.append(0.0)
            continue
        st = np.ascontiguousarray(simp.T)  # (k+1, m)
        P = np.empty(st.shape)
        S = np.empty(st.shape)
        # in blocks: the ~100 temporaries of a block stay in cache and are reused
        # from the heap instead of being mapped (and page-faulted) afresh
        for a in range(0, st.shape[1], _BLOCK):
            sb = st[:, a : a + _BLOCK]
            # relative coordinates, component-first (k+1, d, m): exact for huge offsets
            Z = np.empty((k + 1, d, sb.shape[1]))
            for i in range(d):
                z0 = ZT[i].take(sb[0])
                for v in range(k + 1):
                    np.subtract(ZT[i].take(sb[v]), z0, out=Z[v, i])
            P[:, a : a + _BLOCK], S[:, a : a + _BLOCK] = _pieces(Z, Wpos[sb], Rall[sb], d, k, precision == "exact")
        sign = -1.0 if k % 2 else 1.0
        ball_measure += sign * np.bincount(st.ravel(), weights=P.ravel(), minlength=n)
        ball_boundary += sign * np.bincount(st.ravel(), weights=S.ravel(), minlength=n)
        terms.append(float(P.sum()))
    total = float(sum((-1) ** k * t for k, t in enumerate(terms)))
    bm = ball_measure
    for a in (bm, ball_boundary):
        a.flags.writeable = False
    return UnionMeasure(
        dim=d,
        tau=float(tau),
        measure=total,
        boundary=float(ball_boundary.sum()),
        ball_measure=bm,
        ball_boundary=ball_boundary,
        terms=tuple(terms),
        counts=tuple(counts),
    )


def union_measure(F, tau: float = 0.0, *, precision: str = "exact") -> UnionMeasure:
    """Area and perimeter (2D) or volume and surface area (3D) of a union of balls.

    Computed exactly with the short inclusion–exclusion formula over the dual complex
    K (Notes §23.1; Edelsbrunner 1995):
    :math:`\\operatorname{vol} \\bigcup B_i = \\sum_{\\sigma\\in K}
    (-1)^{\\dim\\sigma} \\operatorname{vol} \\bigcap_{i\\in\\sigma} B_i`.  The
    closed forms are derived in the module docstring.

    Parameters
    ----------
    F : Filtration or Balls
        The balls (disks in 2D), or their filtration ``alpha_filtration(balls)`` to
        measure at many τ.  Given the balls, only the entry times are computed
        (not the whole :class:`~shapelab.filtration.Filtration`), once per call.
    tau : float, optional
        Growth time (Notes §23.1): measure the union of the balls with radii
        :math:`\\sqrt{r_i^2 + \\tau}`; balls with :math:`r_i^2 + \\tau < 0` are
        empty.  Default 0: the balls as given.  ``-inf`` gives the empty union;
        ``inf`` is refused (every ball would be infinite).
    precision : {"exact", "fast"}, default "exact"
        ``"exact"``: chords of rounding-level size are tangencies and flat top
        simplices (nearly cospherical centres) are measured as the limits of the
        closed forms (``shapelab._engine.measure``): portable on degenerate input,
        today's results bit for bit.  ``"fast"``: the plain closed forms of the
        module docstring alone, equal to ``"exact"`` on generic input (tested, to
        1e-12 relative).

    Returns
    -------
    UnionMeasure
        ``measure`` (area/volume), ``boundary`` (perimeter/surface area), the
        per-ball shares ``ball_measure`` = vol(:math:`B_i \\cap \\Pi(B_i)`) and
        ``ball_boundary`` = area(:math:`\\partial B_i \\cap \\partial U`), and the
        per-dimension ``terms`` of the formula.

    See Also
    --------
    dual_complex
        The simplices of the short formula.
    shapelab.oracles.monte_carlo_union_measure
        A sampled estimate, an oracle.

    Notes
    -----
    K is taken just before τ: a simplex entering at v is left out unless
    :math:`v + \\mathrm{TIE\\_TOL}\\,|v| < \\tau` (``counts`` reflects this), a
    tolerance relative to the simplex's own entry time, so that balls of any size
    in a scene of any extent are measured.  At exact ties (tangent balls,
    cospherical centres whose orthosphere has power exactly τ) round-off would
    otherwise decide their membership one by one; the intersections of the
    simplices so left out have measure of order
    :math:`(\\mathrm{TIE\\_TOL}\\,|\\tau|)^{d/2}` or less at τ, and attached pairs,
    which enter together, are left out together.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053
    .. [2] J. Liang, H. Edelsbrunner, P. Fu, P. V. Sudhakar and S. Subramaniam,
           "Analytical shape computation of macromolecules: I. Molecular area and volume
           through alpha shape", *Proteins* 33(1):1-17, 1998.

    Examples
    --------
    >>> from shapelab import Balls
    >>> m = union_measure(Balls([[0.0, 0.0], [3.0, 0.0]], 1.0))   # two disjoint disks
    >>> round(m.area / np.pi, 12), round(m.perimeter / np.pi, 12)
    (2.0, 4.0)
    """
    t = as_tau(tau)
    if precision not in ("exact", "fast"):
        raise ValueError(f'union_measure: precision must be "exact" or "fast", got {precision!r}')
    if isinstance(F, Balls):
        balls, F = F, None
    else:
        F = as_filtration(F, "union_measure")
        balls = F.balls
    if t == np.inf:
        raise ValueError("tau must be finite for union_measure (at tau = inf the union is all of R^d)")
    n, d = len(balls), balls.dim
    if n == 0:
        z = np.zeros(0)
        z.flags.writeable = False
        return UnionMeasure(d, t, 0.0, 0.0, z, z, (0.0,) * (d + 1), (0,) * (d + 1))
    # Simplices entering at or just before tau (relative to their own entry time) are
    # left out, see TIE_TOL.
    if F is None:
        # only K just before tau is needed: the entry times without the Filtration's
        # ordering and boundary matrices (same values, same comparison)
        simplices = simplices_up_to(balls, lambda v: _before(v, t))
    else:
        # the values are sorted, so each dimension's selection is a prefix
        simplices = []
        for k in range(min(F.dimension, d) + 1):
            c = int(np.count_nonzero(_before(F.values(k), t)))
            if c == 0:
                break
            simplices.append(F.simplices(k)[:c])
    return measure_from_simplices(balls.centers, balls.weights + t, simplices, tau=t, precision=precision)
