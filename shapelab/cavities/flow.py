"""Edelsbrunner's discrete flow and the pockets it defines (Notes §23.1, "Voids and pockets").

The notes define a pocket by the growth model (:func:`shapelab.pockets`): a dent that
becomes a void later in the growth.  The literature's pocket, the one CAST and CASTp
compute, is defined instead on one complex, by a *discrete flow* on the regular
(weighted Delaunay) triangulation [EFL98]_, [LEW98]_.  This module computes it, in 2D
and 3D, from the α-filtration (:func:`shapelab.alpha_filtration`) at one growth time
τ, and states the definitions it uses:

* **Empty simplices.**  A top simplex :math:`\\sigma` (a triangle in 2D, a
  tetrahedron in 3D) of the regular triangulation DT is *empty* at τ if it is not in
  the dual complex :math:`K_\\tau`; a facet is *open* if it is not in :math:`K_\\tau`.
  An open facet belongs to two empty top simplices or, on the boundary of the convex
  hull, to one empty top simplex and the outside, written :math:`\\infty`.
* **Flow.**  Let :math:`y_\\sigma` be the orthocentre of :math:`\\sigma` (the centre of
  its orthogonal sphere, the weighted circumcentre: the vertex of the power diagram
  dual to :math:`\\sigma`).  An empty :math:`\\sigma` *flows* across its facet
  :math:`\\nu` into the simplex on the other side of :math:`\\nu` (or into
  :math:`\\infty` if :math:`\\nu` is on the hull) when :math:`\\nu` is open and
  :math:`y_\\sigma` lies strictly beyond the affine hull of :math:`\\nu`, on the side
  opposite :math:`\\sigma`'s own vertex :math:`a`.  Equivalently (see below), when
  :math:`a` lies inside the smallest orthogonal sphere of :math:`\\nu`:
  :math:`\\pi_a(y_\\nu) < \\rho_\\nu`, i.e. :math:`a` *attaches* :math:`\\nu`.  In 2D
  with equal radii: an obtuse triangle flows across its longest edge.  A simplex can
  flow across up to :math:`d` facets (a weighted orthocentre can lie beyond two
  edges of a triangle), so the flow is a directed graph, not a forest.
* **Sinks.**  An empty simplex that flows across no facet is a *sink*.  In a
  general complex the flow could be *blocked* (the orthocentre beyond a facet of
  :math:`K_\\tau`), but not in the α-complex: if :math:`y_\\sigma` lies beyond
  :math:`\\nu`, then :math:`\\nu` is attached (see below), so it enters
  :math:`K` with its earliest coface, at :math:`\\min(\\rho_\\sigma, \\rho_{\\tau'})
  = \\rho_\\sigma`, together with :math:`\\sigma`: a facet beyond which an empty
  simplex's orthocentre lies is open.  So the sinks are exactly the *centred* empty
  simplices (orthocentre in the closed simplex: local maxima of the power distance to
  the balls), tested.  :math:`\\infty` is a sink too.  Following the flow from an
  empty simplex one reaches a set of sinks (one in 2D with equal radii).
  That is exact arithmetic.  The filtration's entry times are computed to a relative
  accuracy (``ENTRY_TIME_RTOL``, 1e-9), so where two of them are equal or nearly so
  (nearly co-spherical balls) a facet can be put into :math:`K_\\tau` by round-off
  just before the simplex that flows across it; at a τ between the two times that
  simplex is *blocked* and counts as a sink although not centred (tested on a
  float ring of 17 disks, where this happens within 2e-15 of the common time).  At
  a τ farther than that tolerance from the entry time of every top simplex the
  sinks are the centred empty simplices.
* **Pockets and voids.**  The empty simplices that do not flow to :math:`\\infty`,
  glued along their open facets, form the *pocket regions* (:func:`flow_pockets`):
  the collections flowing into the same sink, merged when they share an open facet,
  as in [LEW98]_.  A region's *mouth* is the set of its open facets shared with
  simplices that flow to :math:`\\infty` or with the outside; a region without a
  mouth is a *void* (a cavity).  This is the growth model's definition of a mouth
  (:func:`shapelab.pockets`, Notes): the faces through which the region opens to the
  component of :math:`\\infty` once the region is removed, since a simplex that flows
  to :math:`\\infty` gets there through open facets and simplices that flow there too,
  never through the region.  Each region is measured as a growth-model pocket is
  (:class:`FlowPocket`: volume, lining, mouth size, and the pair of the most
  persistent growth-model class rooted in it), and ``shapelab.pockets(F, tau,
  method="flow")`` lists the regions with a mouth beside the growth model's pockets.  These voids are exactly the voids of
  :func:`shapelab.voids` (tested): a component of the complement of
  :math:`K_\\tau` that does not reach the outside cannot flow out of itself.

The pair of a region
--------------------
A :class:`FlowPocket`'s ``(closes_at, fills_at)`` is the pair ``(born, dies)`` of the
most persistent growth-model class rooted in the region: the :math:`H_{d-1}` class of
the merge tree whose youngest cell (the last to fill) is one of the region's cells.
For a pocket region that is the most persistent growth-model pocket
(:func:`shapelab.pockets`) whose void fills last inside it; for a void, the void's own
pair (:class:`shapelab.Void`).  A pocket region holds a sink, and a sink's facets all
enter :math:`K` strictly before it (none is attached by its own apex), so it roots a
class of positive length: a region's persistence is positive, except at a tie, where a
sink's orthocentre lies on one of its facets (three disks at the corners of a right
triangle) or within the filtration's round-off of one (a flat tetrahedron of PDB 3THY,
7e-9 apart in 5.4).  Such a region, whose classes all have zero length up to round-off
(the growth model lists none of them), has ``closes_at = fills_at`` = the time its last
cell fills, and persistence 0 (ties: the earlier birth, then the lower row;
``shapelab._engine.flow.region_measures``).

CASTp goes on to measure pockets, keep only those with a cross section wider than
their mouth, and rank them; that is not done here.

Why the flow stops
------------------
Let :math:`\\sigma` and :math:`\\tau'` share the facet :math:`\\nu` and put the line
:math:`L` through :math:`y_\\nu` orthogonal to :math:`\\nu` as a coordinate :math:`t`,
positive towards :math:`\\tau'`.  Both orthocentres lie on :math:`L`, and the power of
the orthogonal sphere of a simplex with centre at :math:`t` is
:math:`\\rho(t) = t^2 + \\rho_\\nu`.  For the vertex :math:`a` of :math:`\\sigma` opposite
:math:`\\nu`, :math:`g(t) = \\pi_a - \\pi_\\nu` is affine along :math:`L`, increasing
away from :math:`a`, and zero at :math:`t_\\sigma`; so :math:`t_\\sigma > 0` (the
orthocentre is beyond :math:`\\nu`) exactly when :math:`g(0) < 0`, which is the
attachment test above.  Local regularity of DT at :math:`\\nu` (the far vertex
:math:`b` of :math:`\\tau'` is not closer in power than :math:`\\rho_\\sigma` to
:math:`y_\\sigma`) gives :math:`t_\\sigma \\le t_{\\tau'}` in the same way.  Hence along a
flow step :math:`0 < t_\\sigma \\le t_{\\tau'}` and :math:`\\rho_\\sigma \\le \\rho_{\\tau'}`:
the flow never decreases the orthosphere's power, and where it keeps it (a tie,
:math:`y_\\sigma = y_{\\tau'}`) it moves towards that common point, which is acyclic by
Edelsbrunner's acyclicity theorem for regular complexes [E90]_.  So the flow has no
cycle and every path ends in a sink; :func:`discrete_flow` checks this on every call
and raises ``RuntimeError`` if it ever failed.

Exact decisions
---------------
Whether :math:`\\sigma` flows across :math:`\\nu` is the sign of
:math:`D\\,(\\pi_a(y_\\nu) - \\rho_\\nu)`, with :math:`D > 0` the Gram determinant of the
facet's edge vectors: a polynomial in the input's coordinates and weights
(degree 4 in 2D, 6 in 3D, counting a weight as degree 2).  The weights are
``balls.weights`` (:math:`r^2` rounded once to float64), taken as exact, the numbers
the filtration's attachment test uses: so :math:`\\sigma` flows across :math:`\\nu`
exactly when the filtration finds :math:`\\nu` attached by :math:`\\sigma`'s apex, even
where the exact :math:`r^2` and its rounding would decide a near-tie differently.  It
is evaluated in floating point with a bound on its rounding error (the same
expression on absolute values, times a generous :math:`64u`, as in
:mod:`shapelab._engine.predicates`); where the bound cannot decide, it is recomputed exactly
from those binary values, as integers (every float times one power of two; the
expression is homogeneous, so its sign is that of the rational value, as
:func:`flow_side_exact` computes it with :class:`fractions.Fraction`).  A tie (the orthocentre
exactly on the facet's hull, as in a right triangle) is no flow.  The decisions do
not depend on τ and are kept on the filtration.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import breadth_first_order, connected_components

from .._engine import flow as _engine
from .._toolkit.validate import as_tau, readonly
from ..filtration import as_filtration
from .mouths import MeasuredRegion

if TYPE_CHECKING:
    from ..balls import Balls
    from ..filtration import Filtration

__all__ = ["DiscreteFlow", "FlowPocket", "discrete_flow", "flow_pockets", "flow_side_exact", "orthocentre_beyond"]


# ============================================================================ results
@dataclass(frozen=True, eq=False)
class FlowPocket(MeasuredRegion):
    """A pocket region of the discrete flow at ``tau`` (or a void: no mouth).

    Attributes
    ----------
    cells : ndarray, shape (m, d+1), int
        Its empty top simplices, as ball indices.
    cell_ids : ndarray, shape (m,), int
        The same, as rows of ``F.simplices(d)`` (ascending).
    sinks : ndarray, int
        Rows of ``F.simplices(d)`` of the sinks in the region (its centred simplices,
        see :attr:`DiscreteFlow.sink`).
    mouth, mouth_ids : ndarray
        The open facets through which the region meets simplices that flow to
        infinity, or the outside: ball indices, shape (q, d), and rows of
        ``F.simplices(d-1)``.  Empty for a void.  The same cut as a
        :class:`shapelab.cavities.Pocket`'s mouth (module docstring), tested.
    lining : ndarray, int
        The balls at the vertices of its cells that exist at ``tau`` (as
        :attr:`shapelab.Pocket.lining`).
    closes_at, fills_at : float
        The pair ``(born, dies)`` of the most persistent growth-model class rooted in
        the region (module docstring, *The pair of a region*); equal, persistence 0,
        only at a tie.
    tau : float
        The growth time of the complex :math:`K_\\tau` the flow was computed on.
    volume : float
        Free space of its cells not covered by any ball grown to ``tau`` (area in 2D):
        the same exact power-cell decomposition as ``Pocket.volume``.
    mouth_size : float
        Total size of the mouth facets (length in 2D, area in 3D), as ``Pocket.mouth_size``.

    See Also
    --------
    flow_pockets
        Produces them.
    shapelab.pockets
        ``pockets(F, tau, method="flow")`` lists the regions with a mouth beside the
        growth model's pockets.
    shapelab.cavities.Pocket
        The growth model's pocket.

    Notes
    -----
    A FlowPocket satisfies the :class:`shapelab.Cavity` protocol (``born``,
    ``dies``, ``persistence``), so the report, the plots and the ranking take it as
    they take a growth-model :class:`~shapelab.cavities.Pocket`.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
           construction of pockets in macromolecules", *Discrete Appl. Math.* 88:83-102,
           1998. doi:10.1016/S0166-218X(98)00067-5
    """

    cells: np.ndarray
    cell_ids: np.ndarray
    sinks: np.ndarray
    mouth: np.ndarray
    mouth_ids: np.ndarray
    tau: float
    lining: np.ndarray = field(default_factory=lambda: readonly(np.zeros(0, dtype=np.int64)))
    closes_at: float = float("nan")
    fills_at: float = float("nan")
    balls: object = field(default=None, repr=False)

    @property
    def is_void(self) -> bool:
        """``True`` when the region has no mouth: a void (cavity), not a pocket."""
        return len(self.mouth_ids) == 0

    def __repr__(self) -> str:
        kind = "void" if self.is_void else "pocket"
        return (
            f"FlowPocket({kind}, cells={len(self.cell_ids)}, sinks={len(self.sinks)}, "
            f"mouth={len(self.mouth_ids)}, tau={self.tau:.6g})"
        )


@dataclass(frozen=True, eq=False)
class DiscreteFlow:
    """The discrete flow on the empty top simplices of :math:`K_\\tau` (Notes §23.1).

    Attributes
    ----------
    tau : float
        The growth time.
    empty : ndarray of bool, shape (n,)
        Top simplex ``i`` (row of ``F.simplices(d)``) is not in :math:`K_\\tau`.
    neighbour : ndarray of int, shape (n, d+1)
        The top simplex across the facet ``F.boundary(d)[i, j]`` (opposite vertex
        ``j``), ``-1`` for the outside.
    flows : ndarray of bool, shape (n, d+1)
        ``flows[i, j]``: simplex ``i`` flows across that facet (into ``neighbour[i, j]``,
        or to infinity if it is ``-1``).
    sink : ndarray of bool, shape (n,)
        Empty simplices that flow across no facet: the centred ones (their
        orthocentre in the closed simplex), except within the filtration's round-off
        of a tie of entry times (module docstring, *Sinks*).
    to_infinity : ndarray of bool, shape (n,)
        Empty simplices from which the flow reaches the outside.
    region : ndarray of int, shape (n,)
        The index in :attr:`pockets` of the region of each simplex, ``-1`` for
        simplices in :math:`K_\\tau` or flowing to infinity.
    pockets : tuple of FlowPocket
        The regions, ordered by their smallest cell row.

    See Also
    --------
    discrete_flow
        Produces it.
    FlowPocket
        Its pocket regions.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
           construction of pockets in macromolecules", *Discrete Appl. Math.* 88:83-102,
           1998. doi:10.1016/S0166-218X(98)00067-5
    """

    tau: float
    empty: np.ndarray
    neighbour: np.ndarray
    flows: np.ndarray
    sink: np.ndarray
    to_infinity: np.ndarray
    region: np.ndarray
    pockets: tuple

    def successors(self, i: int) -> np.ndarray:
        """Where simplex ``i`` flows in one step: rows of ``F.simplices(d)``, ``-1`` for
        infinity (empty for a sink or a simplex of :math:`K_\\tau`)."""
        return self.neighbour[i][self.flows[i]]

    def downstream(self, i: int) -> frozenset:
        """The sinks the flow from simplex ``i`` reaches (``-1`` for infinity)."""
        seen, stack, out = {int(i)}, [int(i)], set()
        while stack:
            c = stack.pop()
            nxt = self.successors(c).tolist()
            if not nxt and self.empty[c]:
                out.add(c)
            for s in nxt:
                if s < 0:
                    out.add(-1)
                elif s not in seen:
                    seen.add(s)
                    stack.append(s)
        return frozenset(out)

    def __repr__(self) -> str:
        n_void = sum(p.is_void for p in self.pockets)
        return (
            f"DiscreteFlow(tau={self.tau:.6g}, empty={int(self.empty.sum())}, sinks={int(self.sink.sum())}, "
            f"to_infinity={int(self.to_infinity.sum())}, pockets={len(self.pockets) - n_void}, voids={n_void})"
        )


# ===================================================================== the predicate
def flow_side_exact(z_facet, w_facet, z_apex, w_apex) -> int:
    """Sign of :math:`D(\\pi_a(y_\\nu) - \\rho_\\nu)` in exact rational arithmetic (Notes §23.1).

    ``-1``: the apex :math:`a` is closer in power to the facet's orthocentre
    :math:`y_\\nu` than its balls, so the simplex :math:`\\nu \\cup \\{a\\}` flows across
    :math:`\\nu`; ``0``: a tie (no flow); ``+1``: no flow.

    Parameters
    ----------
    z_facet : array_like, shape (d, d)
        The centres of the facet's ``d`` balls (``d`` = 2 or 3).
    w_facet : array_like, shape (d,)
        Their weights (squared radii), as :class:`fractions.Fraction` or floats (taken
        exactly).
    z_apex : array_like, shape (d,)
        The centre of the apex ball, opposite the facet.
    w_apex : float or Fraction
        Its weight.

    Returns
    -------
    int

    Raises
    ------
    TypeError
        If an argument holds something other than real numbers.
    ValueError
        If the shapes do not match (``d`` facet centres of dimension ``d``), a value is
        not finite, or the facet's centres are affinely dependent.

    See Also
    --------
    discrete_flow : makes the same exact decision where its floating-point filter cannot.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
       construction of pockets in macromolecules", Discrete Appl. Math. 88 (1998) 83-102.

    Examples
    --------
    An obtuse triangle flows across its long edge, an acute one does not:

    >>> flow_side_exact([[-1.0, 0.0], [1.0, 0.0]], [0.0, 0.0], [0.0, 0.1], 0.0)
    -1
    >>> flow_side_exact([[-1.0, 0.0], [1.0, 0.0]], [0.0, 0.0], [0.0, 3.0], 0.0)
    1
    >>> flow_side_exact([[-1.0, 0.0], [1.0, 0.0]], [0.0, 0.0], [0.0, 1.0], 0.0)  # right angle
    0
    """
    Z = _engine.exact_values(z_facet, "z_facet", 2)
    d = len(Z)
    if d not in (2, 3) or any(len(row) != d for row in Z):
        raise ValueError(
            f"flow_side_exact: z_facet must hold the centres of a facet's d balls, shape (d, d) with "
            f"d = 2 or 3, got shape ({d}, {', '.join(sorted({str(len(row)) for row in Z}))})"
        )
    W = _engine.exact_values(w_facet, "w_facet", 1)
    if len(W) != d:
        raise ValueError(f"flow_side_exact: w_facet must hold {d} weights, one per facet ball, got {len(W)}")
    A = _engine.exact_values(z_apex, "z_apex", 1)
    if len(A) != d:
        raise ValueError(f"flow_side_exact: z_apex must be a point of dimension {d}, got {len(A)} coordinates")
    (wa,) = _engine.exact_values([w_apex], "w_apex", 1)
    if _engine.gram(Z) == 0:
        raise ValueError("flow_side_exact: the centres z_facet are affinely dependent (a degenerate facet)")
    return _engine.sign(_engine.flow_value(Z, W, A, wa))


def orthocentre_beyond(F) -> np.ndarray:
    """``(n, d+1)`` int8, in plain floating point: ``-1`` where top simplex ``i`` flows
    across its facet opposite vertex ``j`` (module docstring, *Flow*), else ``+1``.

    The facet's orthocentre :math:`y_\\nu` is the point of its affine hull with equal
    power :math:`\\rho_\\nu` to its balls; the simplex flows across it when its apex
    :math:`a` attaches it, :math:`\\pi_a(y_\\nu) < \\rho_\\nu`.  The exact path
    (``precision="exact"``) decides the same sign with a certified error bound and
    integer arithmetic where the floats cannot (``shapelab._engine.flow``).

    See Also
    --------
    discrete_flow
        Uses it with ``precision="fast"``.

    Examples
    --------
    An obtuse triangle of three points flows across its long edge (opposite vertex 2):

    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[-1.0, 0.0], [1.0, 0.0], [0.0, 0.1]], 0.0))
    >>> orthocentre_beyond(F).tolist()
    [[1, 1, -1]]
    """
    balls = F.balls
    d = balls.dim
    S = np.asarray(F.simplices(d), dtype=np.int64)
    z, w = balls.centers, balls.weights
    out = np.ones((S.shape[0], d + 1), dtype=np.int8)
    for j in range(d + 1):
        facet = S[:, [c for c in range(d + 1) if c != j]]
        p0, w0 = z[facet[:, 0]], w[facet[:, 0]]
        E = z[facet[:, 1:]] - p0[:, None, :]  # (n, d-1, d): the facet's edge vectors
        b = 0.5 * (np.einsum("nkd,nkd->nk", E, E) + w0[:, None] - w[facet[:, 1:]])
        # y = p0 + E^T lam with E E^T lam = b: the orthocentre in the facet's hull
        lam = np.linalg.solve(np.einsum("nkd,nld->nkl", E, E), b[..., None])[..., 0]
        x = np.einsum("nkd,nk->nd", E, lam)
        rho = np.einsum("nd,nd->n", x, x) - w0
        apex = z[S[:, j]] - p0
        power = np.einsum("nd,nd->n", x - apex, x - apex) - w[S[:, j]]
        out[:, j] = np.where(power < rho, -1, 1)
    return out


# ======================================================================= the flow
def discrete_flow(F: Filtration | Balls, tau: float = 0.0, *, precision: str = "exact") -> DiscreteFlow:
    """Edelsbrunner's discrete flow on the empty simplices of :math:`K_\\tau`
    (Notes §23.1; [1]_).

    Each top simplex of the regular triangulation not in :math:`K_\\tau` flows across
    each facet not in :math:`K_\\tau` beyond which its orthocentre lies strictly; the
    simplices that flow nowhere are the sinks (the centred ones), the outside is the sink
    :math:`\\infty`.  The empty simplices that do not reach :math:`\\infty`, glued along
    facets not in :math:`K_\\tau`, are the pocket regions; those without a mouth
    are the voids.  The definitions, the proof that the flow is acyclic and how its
    decisions are made exact are in the module docstring (:mod:`shapelab.cavities.flow`).

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 2D or 3D balls (a :class:`~shapelab.Balls` is
        accepted too: its filtration is built once and kept with the balls).  The flow's decisions
        do not depend on τ and are kept on ``F``.
    tau : float, default 0.0
        The growth time of the complex (radii :math:`\\sqrt{r_i^2 + \\tau}`).  CASTp's
        complex is that of the balls grown by the probe, at ``tau = 0``.
    precision : {"exact", "fast"}, default "exact"
        ``"exact"``: every flow decision is the exact sign of its polynomial (a
        floating-point filter with a certified error bound, integer arithmetic where
        it cannot decide; ``shapelab._engine.flow``), so the flow never disagrees with
        the filtration's own attachment test, and is kept on ``F``.  ``"fast"``: the
        plain test :func:`orthocentre_beyond` in floating point, the lines to read;
        the same flow on generic input (tested), possibly not at ties (a right
        triangle).

    Returns
    -------
    DiscreteFlow

    Raises
    ------
    RuntimeError
        If the flow had a cycle (impossible for a regular triangulation; checked).

    See Also
    --------
    flow_pockets : the pocket regions alone.
    shapelab.pockets : pockets by the growth model of the notes.
    shapelab.voids : the voids, which the flow's mouthless regions equal.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
       construction of pockets in macromolecules", Discrete Appl. Math. 88 (1998) 83-102.
    .. [2] J. Liang, H. Edelsbrunner and C. Woodward, "Anatomy of protein pockets and
       cavities: measurement of binding site geometry and implications for ligand
       design", Protein Sci. 7 (1998) 1884-1897.
    .. [3] H. Edelsbrunner, "An acyclicity theorem for cell complexes in d dimensions",
       Combinatorica 10 (1990) 251-260.

    Examples
    --------
    A ring of twelve disks with one gap: the chamber is a pocket, its mouth the gap.

    >>> import numpy as np, shapelab as sl
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)[1:]
    >>> ring = sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], 0.9)
    >>> flow = sl.discrete_flow(sl.alpha_filtration(ring))
    >>> flow.pockets
    (FlowPocket(pocket, cells=9, sinks=1, mouth=1, tau=0),)
    """
    F = as_filtration(F, "discrete_flow")
    tau = as_tau(tau)
    if precision not in ("exact", "fast"):
        raise ValueError(f'discrete_flow: precision must be "exact" or "fast", got {precision!r}')
    d = F.balls.dim
    n = len(F.values(d)) if int(F.dimension) == d else 0
    if n == 0:
        return DiscreteFlow(tau, *_engine.empty_flow(d), ())
    # where each top simplex's orthocentre lies beyond a facet, and the simplex
    # across each facet (-1: the outside); the exact decisions are kept on F
    beyond, nb = _engine.static(F) if precision == "exact" else (orthocentre_beyond(F), _engine.neighbours(F))
    B = np.asarray(F.boundary(d), dtype=np.int64)
    empty = np.asarray(F.values(d)) > tau  # top simplices not in K_tau
    open_f = np.asarray(F.values(d - 1)) > tau  # facets not in K_tau
    flows = (beyond < 0) & open_f[B]  # an open facet has only empty cofaces
    sink = empty & ~flows.any(axis=1)
    # the flow graph, with node n for infinity: which simplices drain to infinity
    src, col = np.nonzero(flows)
    dst = np.where(nb[src, col] < 0, n, nb[src, col])
    G = coo_matrix((np.ones(src.size, dtype=np.int8), (src, dst)), shape=(n + 1, n + 1)).tocsr()
    if connected_components(G, directed=True, connection="strong")[0] != n + 1:
        raise RuntimeError("discrete_flow: the flow has a cycle; please report this input")
    to_inf = np.zeros(n + 1, dtype=bool)
    to_inf[breadth_first_order(G.T.tocsr(), n, directed=True, return_predecessors=False)] = True
    to_inf = to_inf[:n] & empty
    # the pocket regions: empty cells that do not drain to infinity, glued along open facets
    inpk = empty & ~to_inf
    i, j = np.nonzero(open_f[B] & (nb >= 0))
    m = inpk[i] & inpk[np.maximum(nb[i, j], 0)]
    g = coo_matrix((np.ones(int(m.sum()), dtype=np.int8), (i[m], nb[i, j][m])), shape=(n, n))
    _, lab = connected_components(g, directed=False)
    region = np.full(n, -1, dtype=np.int64)
    ids = np.flatnonzero(inpk)
    pockets = []
    if ids.size:
        _, first, inv = np.unique(lab[ids], return_index=True, return_inverse=True)
        # regions numbered by their smallest cell row
        region[ids] = np.argsort(np.argsort(ids[first], kind="stable"), kind="stable")[inv]
        simp = np.asarray(F.simplices(d), dtype=np.int64)
        fsimp = np.asarray(F.simplices(d - 1), dtype=np.int64)
        measures = _engine.region_measures(F)
        for k in range(first.size):
            cid = np.flatnonzero(region == k)
            # the mouth: open facets to the outside or to simplices that drain to infinity
            other = nb[cid]
            mouth = np.unique(B[cid][open_f[B[cid]] & ((other < 0) | (region[np.maximum(other, 0)] != k))])
            lining, closes, fills = measures(cid, simp[cid], tau)
            pockets.append(
                FlowPocket(
                    cells=readonly(simp[cid], np.int64),
                    cell_ids=readonly(cid, np.int64),
                    sinks=readonly(cid[sink[cid]], np.int64),
                    mouth=readonly(fsimp[mouth].reshape(-1, d), np.int64),
                    mouth_ids=readonly(mouth, np.int64),
                    tau=tau,
                    lining=lining,
                    closes_at=closes,
                    fills_at=fills,
                    balls=F.balls,
                )
            )
    nb, flows, sink, to_inf, region = (
        readonly(nb, np.int64),
        readonly(flows),
        readonly(sink),
        readonly(to_inf),
        readonly(region),
    )
    return DiscreteFlow(tau, readonly(empty), nb, flows, sink, to_inf, region, tuple(pockets))


def flow_pockets(F: Filtration | Balls, tau: float = 0.0, *, precision: str = "exact") -> tuple:
    """The pockets and voids of the discrete flow at ``tau`` (Notes §23.1; [1]_, [2]_).

    Shorthand for ``discrete_flow(F, tau).pockets``: the empty top simplices that do
    not flow to infinity, glued along facets not in :math:`K_\\tau`; a region with no
    mouth (:attr:`FlowPocket.is_void`) is a void.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 2D or 3D balls (or the :class:`~shapelab.Balls`).
    tau : float, default 0.0
    precision : {"exact", "fast"}, default "exact"
        As for :func:`discrete_flow`.

    Returns
    -------
    tuple of FlowPocket
        Ordered by their smallest cell row.

    See Also
    --------
    discrete_flow : the flow itself (sinks, arrows, which simplices reach infinity).
    shapelab.pockets : the notes' growth-model pockets, for comparison.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
       construction of pockets in macromolecules", Discrete Appl. Math. 88 (1998) 83-102.
    .. [2] J. Liang, H. Edelsbrunner and C. Woodward, "Anatomy of protein pockets and
       cavities", Protein Sci. 7 (1998) 1884-1897.

    Examples
    --------
    A closed ring of disks encloses a void, which has no mouth:

    >>> import numpy as np, shapelab as sl
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> sl.flow_pockets(sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], 0.9))
    (FlowPocket(void, cells=10, sinks=1, mouth=0, tau=0),)
    """
    return discrete_flow(as_filtration(F, "flow_pockets"), tau, precision=precision).pockets
