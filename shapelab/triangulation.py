"""Regular triangulations and power diagrams of balls (Notes §23.1).

The power diagram :math:`\\Pi(\\mathbb{P})` assigns to each ball :math:`B_i` the cell

.. math:: \\Pi(B_i) = \\{x : \\pi_i(x) \\le \\pi_j(x) \\ \\forall j\\},

with :math:`\\pi_i` the power distance (:func:`shapelab.power_distance`).  Its dual is
the regular (weighted Delaunay) triangulation :math:`DT(\\mathbb{P})`, the notes'
dual complex of the balls grown without end.  Both come from the *lifting map*

.. math:: z_i \\mapsto \\hat z_i = (z_i, \\lVert z_i\\rVert^2 - r_i^2) \\in \\mathbb{R}^{d+1}:

the lower facets of the convex hull of the lifted points project to the simplices of
DT, and a ball is *hidden* (empty cell) exactly when its lifted point lies strictly
above that lower hull.  The vertices of the power diagram are the centres of the
simplices' orthospheres (:func:`orthosphere`).

Read top to bottom: :func:`regular_triangulation` (lift, lower hull, keep the facets
whose normal points down), :func:`orthosphere` (the smallest ball orthogonal to a
simplex's balls), :func:`power_diagram` (each cell cut from a box by the half-planes
of its DT edges) and :func:`clipped_cells` (the cells inside the union).

The seam ``precision``
----------------------
``precision="fast"`` runs the lines above in floating point, with
``scipy.spatial.ConvexHull`` (Qhull).  On generic input that is the regular
triangulation; on degenerate input (four co-circular centres, a grid, duplicates,
collinear centres) Qhull breaks the ties its own way, may leave flat simplices, or
gives up.  ``precision="exact"`` (the default) asks the same question of the engine
(:mod:`shapelab._engine.triangulation`): Qhull's lower hull certified with exact
predicates (:mod:`shapelab.predicates`), ties broken by Simulation of Simplicity,
failures repaired exactly.  Its answer is *the* regular triangulation of the input
(symbolically perturbed where it is degenerate), the same on every machine, so every
lesson's output is portable.

Notes §23.1 call DT the "Delaunay triangulation ... defined by the set of centers";
for balls of different radii that is imprecise: it is the *regular* triangulation of
the weighted centres, and hidden balls are not vertices.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.spatial import ConvexHull, QhullError

from ._engine import triangulation as engine
from ._engine.predicates import affine_basis, flat_simplices
from ._engine.triangulation import TriangulationReport
from ._toolkit.validate import (
    FlatSimplexError,
    as_bbox,
    as_positive_int,
    as_precision,
    as_simplex_balls,
    as_tau,
    check_balls,
    default_bbox,
    flat_simplex,
    nearly_flat,
)
from .balls import Balls

__all__ = [
    "regular_triangulation",
    "orthosphere",
    "power_diagram",
    "PowerDiagram",
    "triangulation_report",
    "TriangulationReport",
    "clipped_cells",
]


# ----------------------------------------------------------------------------------
# The regular triangulation: lift, lower hull
# ----------------------------------------------------------------------------------
def regular_triangulation(balls: Balls, *, precision: str = "exact") -> np.ndarray:
    """The regular (weighted Delaunay) triangulation DT of the balls (Notes §23.1).

    Parameters
    ----------
    balls : Balls
    precision : {"exact", "fast"}
        ``"exact"`` (default): the unique regular triangulation of the input,
        certified with exact predicates, ties broken by Simulation of Simplicity
        (earlier balls slightly larger): the same on every machine, for any input
        (duplicates, co-spherical, collinear or coplanar centres).  ``"fast"``: the
        lower hull of the lifted balls in floating point, read below; equal to
        ``"exact"`` on generic input (tested).  On degenerate input (co-circular or
        co-spherical centres, duplicates) the result may differ: Qhull breaks ties
        its own way and may leave flat simplices; on centres within round-off of a
        line or plane it may even leave out balls that are not hidden.  It needs
        ``d + 1`` centres that span the space.

    Returns
    -------
    ndarray of int64, shape (m, k+1)
        Top simplices, indices into ``balls``; ``k`` is the affine dimension of the
        centres (``k = d`` normally; with ``"exact"``, less for collinear or coplanar
        input, 0 for a single distinct centre).  Vertices ascend within each row and
        rows are sorted lexicographically.  Hidden balls never appear.

    Raises
    ------
    ValueError
        With ``precision="fast"``, when Qhull cannot build the hull of centres in
        general dimension.  Fewer than ``d + 1`` balls, or centres on a line or plane,
        have no hull to take: ``"fast"`` returns the exact triangulation of them.

    See Also
    --------
    power_diagram
        Its dual: the cells of the balls.
    alpha_filtration
        The growth model's filtration of this triangulation.
    triangulation_report
        Which road (certified Qhull, local repair, exact incremental) ``"exact"`` took.

    Notes
    -----
    Under the lifting map :math:`z \\mapsto (z, h = |z|^2 - r^2)` the power distance
    is :math:`\\pi_i(x) = |x|^2 - 2x\\cdot z_i + h_i`: up to the common :math:`|x|^2`,
    an affine function of x whose graph is the plane through the lifted centre.  So a
    set of balls whose cells share a point is a set of lifted centres on one
    non-vertical hyperplane with every other lifted centre on or above it: a lower
    facet of the convex hull [1]_.  The centres are translated to their mean first
    (the heights change by an affine function of x, which keeps the lower hull) and
    scaled to unit size (a similarity keeps DT) for Qhull's precision [4]_.  For
    co-spherical input (grids, cages) DT is not unique; ``"exact"`` returns that of
    the input with its weights perturbed symbolically [3]_, computed by certifying
    and repairing Qhull's candidate [2]_ (:mod:`shapelab._engine.triangulation`).

    References
    ----------
    .. [1] F. Aurenhammer, "Power diagrams: properties, algorithms and applications",
           *SIAM J. Comput.* 16(1):78-96, 1987. doi:10.1137/0216006
    .. [2] H. Edelsbrunner and N. R. Shah, "Incremental topological flipping works for
           regular triangulations", *Algorithmica* 15:223-241, 1996.
           doi:10.1007/BF01975867
    .. [3] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity: a technique to
           cope with degenerate cases in geometric algorithms", *ACM Trans. Graph.*
           9(1):66-104, 1990. doi:10.1145/77635.77639
    .. [4] C. B. Barber, D. P. Dobkin and H. Huhdanpaa, "The Quickhull algorithm for
           convex hulls", *ACM Trans. Math. Softw.* 22(4):469-483, 1996.
           doi:10.1145/235815.235821

    Examples
    --------
    Three large disks and a small one in their middle, which is hidden (its lifted
    centre lies above the plane through the other three: its cell is empty):

    >>> import shapelab as sl
    >>> balls = sl.Balls([[0, 0], [4, 0], [2, 3], [2, 1]], [2.5, 2.5, 2.5, 0.1])
    >>> regular_triangulation(balls).tolist()
    [[0, 1, 2]]

    With unit disks around it, the small disk is a vertex, and the fast path agrees
    on this generic input:

    >>> big = sl.Balls([[0, 0], [4, 0], [2, 3], [2, 1]], [1.0, 1.0, 1.0, 0.1])
    >>> regular_triangulation(big).tolist()
    [[0, 1, 3], [0, 2, 3], [1, 2, 3]]
    >>> regular_triangulation(big, precision="fast").tolist()
    [[0, 1, 3], [0, 2, 3], [1, 2, 3]]

    The four corners of a square are co-circular: two triangulations are regular, and
    the perturbation picks the one with the diagonal at the first corner.

    >>> regular_triangulation(sl.Balls([[0, 0], [1, 0], [1, 1], [0, 1]], 0.0)).tolist()
    [[0, 1, 2], [0, 2, 3]]
    """
    check_balls(balls)
    if as_precision(precision) == "exact":
        return engine.triangulate(balls)[1]
    n, d = balls.centers.shape
    if n == 0:  # no ball, no simplex (as "exact" says)
        return np.empty((0, 1), dtype=np.int64)
    # 1. lift each ball to (z, |z|^2 - r^2), one dimension up (centred at the mean and
    #    scaled to unit size: z -> z/s, r^2 -> r^2/s^2 keeps the triangulation)
    z = balls.centers - balls.centers.mean(axis=0)
    s = float(np.abs(z).max()) or 1.0
    z = z / s
    h = np.einsum("ij,ij->i", z, z) - balls.weights / s**2
    # 2. one more point high above the middle keeps the hull full-dimensional when
    #    every lifted point lies on one hyperplane (three disks); its facets are no
    #    lower facets
    top = np.append(np.zeros(d), h.max() + 1.0 + (h.max() - h.min()))
    try:
        hull = ConvexHull(np.vstack([np.column_stack([z, h]), top]))
    except QhullError as exc:
        if len(affine_basis(balls.centers)) <= d:  # fewer than d + 1 balls, or all on a
            return engine.triangulate(balls)[1]  # line or plane: no hull; the exact path
        raise ValueError(
            f"precision='fast': Qhull cannot triangulate them ({str(exc).splitlines()[0]}); use precision='exact'"
        ) from None
    # 3. the lower facets: outward normal pointing down (last component negative)
    lower = (hull.equations[:, d] < 0) & ~np.any(hull.simplices == n, axis=1)
    # 4. they are DT; rows ascending, sorted lexicographically
    tri = np.sort(hull.simplices[lower], axis=1).astype(np.int64)
    return tri[np.lexsort(tri.T[::-1])]


def orthosphere(centers, weights) -> tuple[np.ndarray, np.ndarray]:
    """The smallest sphere orthogonal to the balls of a simplex (Notes §23.1).

    The point :math:`c` of the affine hull of the centres :math:`z_0, \\dots, z_j`
    with the same power :math:`\\rho = \\pi_i(c) = |c - z_i|^2 - w_i` to all of them.

    Parameters
    ----------
    centers : array_like, shape (..., j+1, d)
        The centres of the simplex's balls (``j + 1 <= d + 1`` affinely independent
        points); leading axes index many simplices at once.
    weights : array_like, shape (..., j+1)
        Their weights :math:`w_i = r_i^2` (``Balls.weights``).

    Returns
    -------
    c : ndarray, shape (..., d)
        The orthocentre: for a top simplex, a vertex of the power diagram.
    rho : ndarray, shape (...)
        Its squared radius, the common power: the growth time τ at which the grown
        balls first meet there.  A vertex has :math:`c = z_0`, :math:`\\rho = -w_0`.

    See Also
    --------
    power_diagram
        Its ``vertices`` are the orthocentres of DT's top simplices.
    alpha_filtration
        Entry times from these spheres and the attached rule.
    shapelab.power_distance
        :math:`\\pi_i(c)`.

    Notes
    -----
    Write :math:`c = z_0 + u` with :math:`u` in the span of the edges
    :math:`a_i = z_i - z_0`.  Equal power to :math:`z_0` and :math:`z_i`,
    :math:`|u - a_i|^2 - w_i = |u|^2 - w_0`, is the linear equation
    :math:`a_i \\cdot u = \\beta_i = (|a_i|^2 - w_i + w_0)/2`: :math:`j` equations
    :math:`Au = \\beta` for :math:`u`, square for a top simplex (solved directly),
    else solved in the span of the :math:`a_i` (a QR factorisation of the edge matrix,
    :math:`A^T = QR`, :math:`u = Qy`, :math:`R^T y = \\beta`), and
    :math:`\\rho = |u|^2 - w_0` [1]_.  Flatness is decided exactly; a nearly flat simplex (condition > 1e10) is refused.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053

    Examples
    --------
    Two unit disks 4 apart first touch at their midpoint when grown by τ = 3:

    >>> c, rho = orthosphere([[0.0, 0.0], [4.0, 0.0]], [1.0, 1.0])
    >>> c.tolist(), float(rho)
    ([2.0, 0.0], 3.0)
    """
    z, w = as_simplex_balls(centers, weights)
    if z.shape[-2] == 1:  # a vertex: its own centre, power -w
        return z[..., 0, :].copy(), -w[..., 0]
    if flat_simplices(z.reshape(-1, *z.shape[-2:])).any():  # decided exactly
        raise flat_simplex("orthosphere")
    A = z[..., 1:, :] - z[..., :1, :]  # the edges a_i as rows, (..., j, d)
    if nearly_flat(A):  # not flat, but float64 would keep few digits of its sphere
        raise flat_simplex("orthosphere", nearly=True)
    size = np.maximum(np.abs(A).max(axis=(-2, -1), initial=0.0), np.sqrt(np.abs(w).max(axis=-1, initial=0.0)))
    s = np.ldexp(1.0, np.frexp(size)[1])  # in units of s, a power of two: exact, and no overflow
    A, w = A / s[..., None, None], w / s[..., None] / s[..., None]
    beta = 0.5 * (np.einsum("...ik,...ik->...i", A, A) - w[..., 1:] + w[..., :1])
    if A.shape[-2] == A.shape[-1]:  # a top simplex: d equations, d unknowns
        u = np.linalg.solve(A, beta[..., None])[..., 0]
    else:  # a face: u in the span of the edges, A^T = QR, u = Q y, R^T y = beta
        Q, R = np.linalg.qr(np.swapaxes(A, -1, -2))
        u = (Q @ np.linalg.solve(np.swapaxes(R, -1, -2), beta[..., None]))[..., 0]
    with np.errstate(over="ignore"):  # refused just below (rho is infinite if c is)
        c = z[..., 0, :] + s[..., None] * u
        rho = s * s * (np.einsum("...k,...k->...", u, u) - w[..., 0])
    if not np.all(np.isfinite(rho)):
        raise ValueError("orthosphere: the sphere is beyond float64's range (a simplex nearly flat, or too large)")
    return c, rho


# ----------------------------------------------------------------------------------
# Power diagram
# ----------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class PowerDiagram:
    """The power diagram :math:`\\Pi(\\mathbb{P})` of a set of balls (Notes §23.1).

    Attributes
    ----------
    balls : Balls
        The input.
    hidden : ndarray of bool, shape (n,)
        True for balls whose cell is empty (they are not vertices of DT; this
        includes all but one of several balls with the same centre).
    vertices : ndarray, shape (p, d)
        The finite vertices of the diagram: the orthocentres (centres of the
        smallest orthogonal spheres) of the top simplices of DT, in the order of
        :func:`regular_triangulation`'s rows.  Empty if the centres are not in
        general dimension (collinear in 2D, coplanar in 3D).
    cells : tuple of ndarray, one per ball
        2D: the cell :math:`\\Pi(B_i)` clipped to ``bbox`` as a counter-clockwise
        polygon of shape (k_i, 2) (no repeated closing vertex); (0, 2) for hidden
        balls and for cells that miss the box.  3D: int64 indices into ``vertices``
        of the cell's finite vertices, ascending ((0,) for hidden balls).
    adjacency : ndarray of int64, shape (e, 2)
        Pairs ``i < j`` of balls whose cells share a facet: the edges of DT, sorted.
    bbox : ndarray, shape (2, d)
        ``[lower corner, upper corner]`` of the clipping box.
    unbounded : ndarray of bool, shape (n,)
        True for the (non-hidden) balls whose cell is unbounded, i.e. whose centre
        is on the boundary of the convex hull of the centres.

    See Also
    --------
    power_diagram
        Builds it.
    regular_triangulation
        Its dual triangulation.
    """

    balls: Balls
    hidden: np.ndarray
    vertices: np.ndarray
    cells: tuple
    adjacency: np.ndarray
    bbox: np.ndarray
    unbounded: np.ndarray


def _clip_polygon(poly: list, a0: float, a1: float, c: float) -> list:
    """Sutherland–Hodgman: keep the part of a convex polygon with a0*x + a1*y <= c."""
    if not poly:
        return poly
    out = []
    m = len(poly)
    vals = [a0 * x + a1 * y - c for x, y in poly]
    for t in range(m):
        p, q = poly[t], poly[(t + 1) % m]
        fp, fq = vals[t], vals[(t + 1) % m]
        if fp <= 0:
            out.append(p)
        if (fp < 0 < fq) or (fq < 0 < fp):
            s = fp / (fp - fq)
            out.append((p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])))
    return out


def power_diagram(balls: Balls, *, bbox: npt.ArrayLike | None = None, precision: str = "exact") -> PowerDiagram:
    """The power diagram of the balls (Notes §23.1): cells, hidden balls, adjacency.

    Parameters
    ----------
    balls : Balls
    bbox : array_like, shape (2, d), optional
        Clipping box ``[[xmin, ymin], [xmax, ymax]]`` (3D: three columns) for the
        2D polygons.  Default: the bounding box of the balls padded by 10 %.
    precision : {"exact", "fast"}
        The triangulation it is dual to (:func:`regular_triangulation`): ``"exact"``
        (default) certified, the same on every machine, and the vertices of slivers
        in rational arithmetic; ``"fast"`` the lower hull in floating point and the
        vertices by :func:`orthosphere`, equal on generic input.

    Returns
    -------
    PowerDiagram

    See Also
    --------
    power_distance
        The distance whose minimisation defines the cells.
    regular_triangulation
        The dual triangulation.
    clipped_cells
        Cells clipped to the grown disks.

    Notes
    -----
    The cell :math:`\\Pi(B_i) = \\{x : \\pi_i(x) \\le \\pi_j(x)\\ \\forall j\\}` is an
    intersection of half-planes; since :math:`\\pi_i - \\pi_j` is affine in x
    (the :math:`|x|^2` cancels), the constraints are
    :math:`2x\\cdot(z_j - z_i) \\le |z_j|^2 - r_j^2 - |z_i|^2 + r_i^2`.  Only the
    DT neighbours ``j`` of ``i`` matter.  In 2D each cell is clipped from the box by
    these half-planes; in 3D the cell is described by its vertices (orthocentres of
    the incident tetrahedra) and ``unbounded`` flags the cells on the hull.

    References
    ----------
    .. [1] F. Aurenhammer, "Power diagrams: properties, algorithms and applications",
           *SIAM J. Comput.* 16(1):78-96, 1987. doi:10.1137/0216006
    .. [2] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053

    Examples
    --------
    Two unit disks and a larger one: three cells, all unbounded, meeting at one
    vertex of equal power to the three balls.

    >>> import shapelab as sl
    >>> D = power_diagram(sl.Balls([[0, 0], [4, 0], [2, 3]], [1.0, 1.0, 2.0]))
    >>> D.adjacency.tolist(), D.hidden.tolist()
    ([[0, 1], [0, 2], [1, 2]], [False, False, False])
    >>> D.vertices.round(4).tolist()
    [[2.0, 0.3333]]
    """
    check_balls(balls)
    exact = as_precision(precision) == "exact"
    d = balls.dim
    n = len(balls)
    if n == 0 and bbox is None:
        raise ValueError("power_diagram: balls is empty, so there is no default bbox; give one")
    box = default_bbox(balls) if bbox is None else as_bbox(bbox, d)
    tri = engine.triangulate(balls)[1] if exact else regular_triangulation(balls, precision="fast")
    present = np.zeros(n, dtype=bool)
    present[tri.ravel()] = True
    hidden = ~present
    # DT edges
    k = tri.shape[1] - 1
    if k >= 1:
        pairs = np.concatenate([tri[:, [a, b]] for a in range(k + 1) for b in range(a + 1, k + 1)])
        adjacency = np.unique(pairs, axis=0).astype(np.int64)
    else:
        adjacency = np.zeros((0, 2), dtype=np.int64)
    # boundary (unbounded) cells: vertices of hull facets of DT, or everything if flat
    unbounded = np.zeros(n, dtype=bool)
    if k < d:
        unbounded[present] = True
    else:
        fac = np.sort(np.concatenate([np.delete(tri, j, axis=1) for j in range(d + 1)]), axis=1)
        u, cnt = np.unique(fac, axis=0, return_counts=True)
        unbounded[u[cnt == 1].ravel()] = True
    if exact or tri.shape[1] != d + 1:
        vertices = engine.orthocentres(balls, tri)
    else:
        try:
            vertices = orthosphere(balls.centers[tri], balls.weights[tri])[0]
        except FlatSimplexError:  # a flat simplex left by Qhull: no orthosphere
            raise ValueError(
                "precision='fast': Qhull left a (nearly) flat simplex (degenerate centres, "
                "e.g. a grid or co-spherical); use precision='exact'"
            ) from None
    vertices.flags.writeable = False
    if d == 2:
        origin = balls.centers.mean(axis=0) if n else np.zeros(d)
        z = balls.centers - origin
        w = balls.weights
        zz = np.einsum("ij,ij->i", z, z) - w
        lo, hi = box - origin
        square = [(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])]
        nbrs = [[] for _ in range(n)]
        for a, b in adjacency.tolist():
            nbrs[a].append(b)
            nbrs[b].append(a)
        cells = []
        for i in range(n):
            if hidden[i]:
                cells.append(np.zeros((0, 2)))
                continue
            poly = list(square)
            zi = z[i]
            for j in nbrs[i]:
                a = 2.0 * (z[j] - zi)
                poly = _clip_polygon(poly, float(a[0]), float(a[1]), float(zz[j] - zz[i]))
            arr = np.asarray(poly, dtype=float).reshape(-1, 2) + origin
            arr.flags.writeable = False
            cells.append(arr)
    else:
        cells = [np.zeros(0, dtype=np.int64) for _ in range(n)]
        if tri.shape[0] and k == d:
            m = tri.shape[0]
            owner = tri.ravel()
            simp = np.repeat(np.arange(m, dtype=np.int64), d + 1)
            order = np.lexsort((simp, owner))
            owner, simp = owner[order], simp[order]
            starts = np.searchsorted(owner, np.arange(n + 1))
            cells = [simp[starts[i] : starts[i + 1]] for i in range(n)]
        for c in cells:
            c.flags.writeable = False
    for a in (hidden, adjacency, box, unbounded):
        a.flags.writeable = False
    return PowerDiagram(balls, hidden, vertices, tuple(cells), adjacency, box, unbounded)


# ======================================== the cells B_i ∩ Π(B_i), for drawing
def _clip_convex_by_disk(poly, cx, cy, r, step):
    """Polygon approximating (convex polygon) ∩ (disk), counter-clockwise.

    Edges of the polygon inside the disk are kept exactly; between the point where
    the boundary leaves the disk and where it re-enters, the circle is followed with
    points every ``step`` radians."""
    import math

    k = len(poly)
    if k < 3 or r <= 0:
        return np.zeros((0, 2))
    r2 = r * r
    out = []
    leave = None  # angle where the boundary left the disk
    first_entry = None

    def arc_to(a0, a1):
        span = (a1 - a0) % (2 * math.pi)
        m = int(span / step)
        for j in range(1, m + 1):
            a = a0 + span * j / (m + 1)
            out.append((cx + r * math.cos(a), cy + r * math.sin(a)))

    for t in range(k):
        px, py = poly[t]
        qx, qy = poly[(t + 1) % k]
        dx, dy = qx - px, qy - py
        fx, fy = px - cx, py - cy
        a = dx * dx + dy * dy
        b = fx * dx + fy * dy
        c = fx * fx + fy * fy - r2
        if c <= 0:
            out.append((px, py))
        if a == 0:
            continue
        disc = b * b - a * c
        if disc <= 0:
            continue
        sq = math.sqrt(disc)
        s0, s1 = (-b - sq) / a, (-b + sq) / a
        if 0 < s0 < 1 and c > 0:  # enters the disk on this edge
            ang = math.atan2(fy + s0 * dy, fx + s0 * dx)
            if leave is None:
                first_entry = ang if first_entry is None else first_entry
            else:
                arc_to(leave, ang)
                leave = None
            out.append((px + s0 * dx, py + s0 * dy))
        if 0 < s1 < 1 and (px + dx - cx) ** 2 + (py + dy - cy) ** 2 > r2:  # leaves the disk
            out.append((px + s1 * dx, py + s1 * dy))
            leave = math.atan2(fy + s1 * dy, fx + s1 * dx)
    if leave is not None and first_entry is not None:
        arc_to(leave, first_entry)
    if not out:
        # no vertex inside and no crossing: the disk is inside the polygon or misses it
        inside = all(
            (poly[(t + 1) % k][0] - poly[t][0]) * (cy - poly[t][1])
            - (poly[(t + 1) % k][1] - poly[t][1]) * (cx - poly[t][0])
            >= 0
            for t in range(k)
        )
        if not inside:
            return np.zeros((0, 2))
        m = max(int(2 * math.pi / step), 8)
        ang = np.linspace(0, 2 * math.pi, m, endpoint=False)
        return np.column_stack([cx + r * np.cos(ang), cy + r * np.sin(ang)])
    return np.array(out)


def clipped_cells(
    balls: Balls, *, tau: float = 0.0, diagram: PowerDiagram | None = None, arc_resolution: int = 96
) -> tuple[np.ndarray, ...]:
    """The cells :math:`B_i(\\tau) \\cap \\Pi(B_i)` of disks as polygons (Notes §23.1).

    The power diagram partitions the union into these convex pieces, "the cells
    contained in :math:`\\bigcup B_i`"; their areas are ``union_measure(...).
    ball_measure``.  Circular arcs are sampled with ``arc_resolution`` points per full
    turn (the polygons are inscribed, so their areas are slightly smaller).

    Parameters
    ----------
    balls : Balls
        2D balls.
    tau : float
        Growth time (the power diagram does not change with τ).
    diagram : PowerDiagram, optional
        ``power_diagram(balls)`` if already computed; its box must contain the disks.
    arc_resolution : int

    Returns
    -------
    tuple of ndarray
        One (k_i, 2) counter-clockwise polygon per ball, (0, 2) when empty.

    See Also
    --------
    power_diagram
        The unclipped cells.
    dual_complex
        The nerve of these clipped cells.
    shapelab.oracles.sampled_nerve
        The same nerve by sampling, an oracle.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053

    Examples
    --------
    Two overlapping unit disks: their cells meet on the bisector x = 0.5.

    >>> import shapelab as sl
    >>> cells = clipped_cells(sl.Balls([[0, 0], [1, 0]], 1.0))
    >>> len(cells), round(float(cells[0][:, 0].max()), 6), round(float(cells[1][:, 0].min()), 6)
    (2, 0.5, 0.5)
    """
    check_balls(balls)
    if balls.dim != 2:
        raise ValueError(f"clipped_cells works with disks (2D), got balls of dimension {balls.dim}")
    t = as_tau(tau, finite=True)
    res = as_positive_int(arc_resolution, "arc_resolution", minimum=8)
    if diagram is None:
        w = balls.weights + max(t, 0.0)
        lo = (balls.centers - np.sqrt(w)[:, None]).min(axis=0) - 1.0 if len(balls) else np.zeros(2)
        hi = (balls.centers + np.sqrt(w)[:, None]).max(axis=0) + 1.0 if len(balls) else np.ones(2)
        diagram = power_diagram(balls, bbox=np.array([lo, hi]))
    w = balls.weights + t
    step = 2 * np.pi / res
    out = []
    for i, cell in enumerate(diagram.cells):
        if w[i] <= 0 or len(cell) < 3:
            out.append(np.zeros((0, 2)))
            continue
        cx, cy = balls.centers[i]
        out.append(_clip_convex_by_disk(cell.tolist(), float(cx), float(cy), float(np.sqrt(w[i])), step))
    return tuple(out)


def triangulation_report(balls: Balls) -> TriangulationReport:
    """How the engine computed and certified the regular triangulation of ``balls``
    with ``precision="exact"`` (Notes §23.1): Qhull's answer certified exactly,
    repaired locally, or the exact incremental algorithm where the certificate
    failed; see :class:`TriangulationReport`.

    See Also
    --------
    regular_triangulation
        The triangulation itself.
    shapelab._engine.certify.certify
        The exact check of Qhull's candidate.
    shapelab._engine.incremental.incremental_triangulation
        The exact fallback.

    References
    ----------
    .. [1] H. Edelsbrunner and N. R. Shah, "Incremental topological flipping works for
           regular triangulations", *Algorithmica* 15:223-241, 1996.
           doi:10.1007/BF01975867
    .. [2] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity: a technique to
           cope with degenerate cases in geometric algorithms", *ACM Trans. Graph.*
           9(1):66-104, 1990. doi:10.1145/77635.77639

    Examples
    --------
    The corners of a square are co-circular: one tie, broken by Simulation of Simplicity.

    >>> import shapelab as sl
    >>> r = triangulation_report(sl.Balls([[0, 0], [1, 0], [1, 1], [0, 1]], 0.5))
    >>> r.method, r.counts["power_ties"]
    ('qhull', 1)
    """
    check_balls(balls)
    return engine.triangulate_local(balls, report=True)[3]
