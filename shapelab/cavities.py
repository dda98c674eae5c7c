"""Voids, pockets and tunnels of a union of balls (Notes §23.1, "Voids and pockets").

Notes §23.1 define a *void* as a bounded connected component of
:math:`\\mathbb{R}^3 \\setminus \\bigcup_i B_i` and, through the growth model, a *pocket*
as a dent of the surface that "will produce a void in the life time of the filtration";
a *groove* likewise turns into a *tunnel*.  This module computes all of them from the
α-filtration (:func:`shapelab.alpha_filtration`), in 2D (holes and dents of unions of
disks) and in 3D.

Where the computation lives
---------------------------
* **Complement.**  The dual complex :math:`K_\\tau` lies inside the union
  :math:`U_\\tau` of the grown balls and :math:`U_\\tau` deformation-retracts onto it
  (Edelsbrunner 1995), so by Alexander duality the components of
  :math:`\\mathbb{R}^d \\setminus U_\\tau` correspond one to one to the components of
  :math:`\\mathbb{R}^d \\setminus |K_\\tau|`: the top simplices of the Delaunay
  triangulation not in :math:`K_\\tau`, glued along :math:`(d-1)`-simplices not in
  :math:`K_\\tau`, plus the outside.  A void is such a component that avoids the
  outside; its *cells* are those top simplices and the free space of the void is
  exactly the part of those cells that no grown ball covers.
* **Merge tree.**  Running τ backwards the complement only grows, so one union–find
  pass in reverse filtration order (the dual :math:`H_0`, see
  :mod:`shapelab.topology`) records when every void is sealed (``born``) and filled
  (``dies``), and which cells it holds at every moment.
* **Pockets** (growth-model definition of the notes).  A pocket at τ is a region of
  the complement that is still connected to the outside at τ but is sealed off into a
  void at a later :math:`\\tau' > \\tau` (``closes_at``), filled at ``fills_at``.  Its
  cells are the cells of that void at the moment it closes; its *mouth* at τ is the
  set of :math:`(d-1)`-simplices not in :math:`K_\\tau` through which those cells open
  to the outside: each has one side in the pocket and the other in the component of
  :math:`\\infty` of the complement once the pocket's cells are removed.  A face on
  the pocket's boundary that leads into a crevice of its own wall (free cells reachable
  from the outside only through the pocket) is no opening (:func:`pockets`, Notes).
  A dent whose cells fill before its mouth closes never becomes a void and is no
  pocket (Figure 23.2, right).  Pockets nest: a pocket's cells can contain the cells
  of a pocket that closes later (the "pocket hierarchy").
* **Tunnels** are the :math:`H_1` classes alive at τ in 3D (birth ≤ τ < death), each
  with a representative cycle taken from the reduced boundary matrix: the cycle born
  at ``birth`` that becomes a boundary at ``death``.  Grooves (:func:`grooves`) are the
  :math:`H_1` classes born after τ.

Volumes
-------
``Void.volume`` and ``Pocket.volume`` (the free space of a void or pocket) come from
:mod:`shapelab.freespace`: fractional inclusion–exclusion over the void's cells, and
the exact power-cell decomposition for pockets.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Protocol, runtime_checkable

import numpy as np

from ._pockets import MeasuredRegion, OutsideGraph, complement_labels, leaf_run, lining_of, merge_tree
from ._toolkit import tolerances as tol
from ._toolkit.derived import derived
from ._toolkit.validate import (
    as_finite_scalar,
    as_tau,
    check_balls,
    readonly,
)
from ._topology import is_roundoff, reduce_h1, summary
from .filtration import as_filtration
from .freespace import vertex_values, void_measure

__all__ = [
    "Cavity",
    "Void",
    "Pocket",
    "Tunnel",
    "voids",
    "pockets",
    "tunnels",
    "grooves",
    "ChannelProfile",
    "channel_profile",
]


# ============================================================================ results
@runtime_checkable
class Cavity(Protocol):
    """What a void, a pocket and a tunnel share (Notes §23.1): one protocol, so that code
    that lists, ranks, draws or reports cavities takes any of them.

    Attributes
    ----------
    cells : ndarray, int
        The simplices that carry it, as ball indices: the top simplices of the region
        (:class:`Void`, :class:`Pocket`) or the edges of a representative cycle
        (:class:`Tunnel`).
    cell_ids : ndarray, int
        The same simplices as rows of ``F.simplices(k)``.
    lining : ndarray, int
        The balls around it: the vertices of its cells whose balls exist at ``tau``.
    born, dies : float
        The growth times between which it is a feature of the union: a void is sealed
        and filled, a pocket closes into a void and that void fills
        (``closes_at``, ``fills_at``), a tunnel's :math:`H_1` class is born and dies.
    persistence : float
        ``dies - born``.
    tau : float
        The growth time it was computed at.

    See Also
    --------
    voids, pockets, tunnels
        Produce cavities.

    Notes
    -----
    Voids and pockets also have a ``volume`` (free space, exact); a tunnel bounds no
    region and has none.  The discrete flow's :class:`shapelab.flow.FlowPocket` is a
    region at one τ; its ``born``/``dies`` are those of the most persistent class of
    the growth model rooted in it (``pockets(F, tau, method="flow")``), so it is a
    Cavity too.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.fullerene_c60())
    >>> all(isinstance(c, sl.Cavity) for c in (*sl.voids(F, 0.0), *sl.tunnels(F, -1.5)))
    True
    """

    cells: np.ndarray
    cell_ids: np.ndarray
    lining: np.ndarray
    tau: float

    @property
    def born(self) -> float: ...

    @property
    def dies(self) -> float: ...

    @property
    def persistence(self) -> float: ...


@dataclass(frozen=True, eq=False)
class Void:
    """A bounded component of the complement of the grown union (Notes §23.1).

    Attributes
    ----------
    cells : ndarray, shape (m, d+1), int
        The top simplices of the Delaunay triangulation that form the void, as ball
        indices (rows sorted ascending).
    cell_ids : ndarray, shape (m,), int
        The same cells as row indices into ``F.simplices(d)``.
    lining : ndarray, int
        Indices of the balls lining the void: the vertices of its cells whose balls
        exist at ``tau``.
    born : float
        The τ at which the void was sealed off (its :math:`H_{d-1}` class is born).
    dies : float
        The τ at which its last part is filled.
    volume : float
        Free space inside the void not covered by any ball grown to ``tau`` (area in
        2D); exact.
    tau : float
        The growth time the void was computed at.

    See Also
    --------
    voids
        Produces voids.
    Pocket
        A dent that closes into a void later.

    References
    ----------
    .. [1] J. Liang, H. Edelsbrunner, P. Fu, P. V. Sudhakar and S. Subramaniam,
           "Analytical shape computation of macromolecules: II. Inaccessible cavities in
           proteins", *Proteins* 33(1):18-29, 1998.
    """

    cells: np.ndarray
    cell_ids: np.ndarray
    lining: np.ndarray
    born: float
    dies: float
    volume: float
    tau: float

    @property
    def persistence(self) -> float:
        """``dies - born``: the void's pair in :math:`H_2`, the same over every
        coefficient field (Alexander duality; :func:`shapelab.topology.persistence`)."""
        return self.dies - self.born

    def __repr__(self) -> str:
        return (
            f"Void(cells={len(self.cells)}, lining={len(self.lining)}, born={self.born:.6g}, "
            f"dies={self.dies:.6g}, volume={self.volume:.6g}, tau={self.tau:.6g})"
        )


@dataclass(frozen=True, eq=False)
class Pocket(MeasuredRegion):
    """A dent that closes into a void later in the growth (Notes §23.1, Figure 23.2).

    Attributes
    ----------
    cells, cell_ids : ndarray
        The Delaunay top simplices of the void the pocket becomes, at the moment it
        closes (ball indices, and rows of ``F.simplices(d)``).
    mouth, mouth_ids : ndarray
        The openings to the outside at ``tau``: the :math:`(d-1)`-simplices not in
        :math:`K_\\tau` with one side in the cells and the other in the outside
        beyond them (the component of :math:`\\infty` of the complement without the
        cells); not the faces into crevices of the pocket's wall (see
        :func:`pockets`).  Ball indices, shape (q, d), and rows of ``F.simplices(d-1)``.
    mouth_size : float
        Total size of the mouth simplices: length in 2D, area in 3D.
    lining : ndarray, int
        The pocket's *lining atoms*: the balls at the vertices of its cells that exist
        at ``tau``.  Not the report's ``lining_atoms``
        (:class:`shapelab.cavity_report.CavityRow`), its *wall atoms*: the balls whose
        sphere bounds the free space inside the cells, which a ball can do without
        being a vertex of them (lesson 07b).
    closes_at : float
        The τ′ > τ at which the mouth closes and the pocket becomes a void.
    fills_at : float
        The τ at which that void is filled.
    tau : float
        The growth time the pocket was computed at.
    volume : float
        Free space in the pocket's cells not covered by any ball grown to ``tau``
        (area in 2D); exact, computed on first access.

    See Also
    --------
    pockets
        Produces pockets.
    Void
        What a pocket becomes when it closes.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
           construction of pockets in macromolecules", *Discrete Appl. Math.* 88:83-102,
           1998. doi:10.1016/S0166-218X(98)00067-5
    .. [2] J. Liang, H. Edelsbrunner and C. Woodward, "Anatomy of protein pockets and
           cavities: measurement of binding site geometry and implications for ligand
           design", *Protein Sci.* 7(9):1884-1897, 1998. doi:10.1002/pro.5560070905
    """

    cells: np.ndarray
    cell_ids: np.ndarray
    mouth: np.ndarray
    mouth_ids: np.ndarray
    lining: np.ndarray
    closes_at: float
    fills_at: float
    tau: float
    balls: object

    def __repr__(self) -> str:
        return (
            f"Pocket(cells={len(self.cells)}, mouth={len(self.mouth)}, lining={len(self.lining)}, "
            f"closes_at={self.closes_at:.6g}, fills_at={self.fills_at:.6g}, tau={self.tau:.6g})"
        )


@dataclass(frozen=True, eq=False)
class Tunnel:
    """An :math:`H_1` class of the grown union in 3D (Notes §23.1: tunnels and grooves).

    Attributes
    ----------
    birth, death : float
        When the class appears and when it is filled (τ).
    cycle : ndarray, shape (m, 2), int
        A representative cycle as edges (pairs of ball indices): born at ``birth``,
        it is a boundary from ``death`` on.
    edge_ids : ndarray, shape (m,), int
        The same edges as rows of ``F.simplices(1)``.
    tau : float
        The growth time the tunnel was computed at.

    See Also
    --------
    tunnels
        Produces tunnels.
    channel_profile
        The free radius along a tunnel.
    """

    birth: float
    death: float
    cycle: np.ndarray
    edge_ids: np.ndarray
    tau: float

    @property
    def born(self) -> float:
        """``birth`` (the :class:`Cavity` protocol)."""
        return self.birth

    @property
    def dies(self) -> float:
        """``death`` (the :class:`Cavity` protocol)."""
        return self.death

    @property
    def cells(self) -> np.ndarray:
        """``cycle``: the edges that carry the tunnel (the :class:`Cavity` protocol)."""
        return self.cycle

    @property
    def cell_ids(self) -> np.ndarray:
        """``edge_ids`` (the :class:`Cavity` protocol)."""
        return self.edge_ids

    @cached_property
    def lining(self) -> np.ndarray:
        """The balls on the representative cycle, ascending (the :class:`Cavity` protocol)."""
        out = np.unique(np.asarray(self.cycle, dtype=np.int64))
        out.flags.writeable = False
        return out

    @property
    def persistence(self) -> float:
        """``death - birth``: the tunnel's :math:`H_1` pair over :math:`\\mathbb{Z}/2`
        (its representative cycle is a :math:`\\mathbb{Z}/2` cycle too); over another
        field a tunnel's death can differ (:func:`shapelab.topology.persistence`)."""
        return self.death - self.birth

    def __repr__(self) -> str:
        return (
            f"Tunnel(birth={self.birth:.6g}, death={self.death:.6g}, cycle={len(self.cycle)} edges, tau={self.tau:.6g})"
        )


def _full_dim(balls, F) -> bool:
    return int(F.dimension) == balls.dim and len(F.values(balls.dim)) > 0


# ========================================================================== voids
def voids(F, tau=0.0) -> tuple:
    """The voids (holes in 2D) of the union of the balls grown to ``tau``.

    Notes §23.1: "A void of :math:`\\mathbb{P}` is a bounded connected component of
    :math:`\\mathbb{R}^3 \\setminus \\bigcup B_i`"; the notes add that each void of the
    union has a corresponding void of :math:`K` "much more amiable to computation".
    Here they are found as the components of the complement of :math:`K_\\tau` in the
    Delaunay triangulation that do not reach the outside.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 2D or 3D balls; what is derived from it (the
        merge tree of the complement) is kept on it, so asking again at another τ
        is cheap.  A :class:`~shapelab.Balls` is accepted too: its filtration is
        built once and kept with the balls (:meth:`shapelab.Balls.derived`).
    tau : float, default 0.0
        Growth time: radii :math:`\\sqrt{r_i^2 + \\tau}`; balls with
        :math:`r_i^2 + \\tau < 0` do not exist yet.  ``±inf`` give no voids.

    Returns
    -------
    tuple of Void
        Sorted by persistence ``dies - born``, largest first (ties: earlier ``born``).
        Their number equals :math:`\\beta_{d-1}(\\tau)`.

    See Also
    --------
    pockets
        Dents that close into voids later.
    shapelab.freespace.free_space
        The free volume of cells.
    shapelab.topology.betti
        β₂ counts the voids (Alexander duality).

    References
    ----------
    .. [1] J. Liang, H. Edelsbrunner, P. Fu, P. V. Sudhakar and S. Subramaniam,
           "Analytical shape computation of macromolecules: II. Inaccessible cavities in
           proteins", *Proteins* 33(1):18-29, 1998.
    .. [2] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> import numpy as np, shapelab as sl
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> ring = sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], 0.9)
    >>> F = sl.alpha_filtration(ring)
    >>> sl.voids(F)
    (Void(cells=10, lining=12, born=-0.207114, dies=8.19, volume=15.1893, tau=0),)
    """
    F = as_filtration(F, "voids")
    balls = F.balls
    tau = as_tau(tau)
    if not _full_dim(balls, F):
        return ()
    S = summary(F)
    T = merge_tree(F)
    k = S.k
    n = S.values[k].shape[0]
    lab, free = complement_labels(F, S, tau)
    cells = np.flatnonzero(free[:n] & (lab[:n] != lab[n]))
    if cells.size == 0:
        return ()
    L = lab[cells]
    o = np.argsort(L, kind="stable")
    cells, L = cells[o], L[o]
    starts = np.flatnonzero(np.r_[True, L[1:] != L[:-1]])
    ends = np.r_[starts[1:], L.shape[0]]
    meas = void_measure(F, tau, cells)
    csum = np.r_[0.0, np.cumsum(meas)]
    simp = np.asarray(F.simplices(k), dtype=np.int64)
    vval = vertex_values(F, len(balls))
    out = []
    for s, e in zip(starts.tolist(), ends.tolist()):
        cid = cells[s:e]
        root = int(cid.max())
        cv = simp[cid]
        out.append(
            Void(
                cells=readonly(cv, np.int64),
                cell_ids=readonly(cid, np.int64),
                lining=readonly(lining_of(cv, tau, vval), np.int64),
                born=float(T.kill_value[root]),
                dies=float(S.values[k][root]),
                volume=float(max(csum[e] - csum[s], 0.0)),
                tau=tau,
            )
        )
    out.sort(key=lambda x: (-(x.dies - x.born), x.born, int(x.cell_ids[0])))
    return tuple(out)


# ======================================================================== pockets
def pockets(F, tau=0.0, *, min_persistence=0.0, method="growth") -> tuple:
    """Pockets by the growth model of Notes §23.1 (Figure 23.2), or by the discrete flow.

    "If we grow the balls ... uniformly, the left pocket will produce a void in the life
    time of the filtration while the right pocket will not."  A pocket at ``tau`` is
    therefore an :math:`H_{d-1}` class born (sealed) at ``closes_at`` > ``tau`` whose
    region, at ``tau``, is still part of the outside component of the complement.
    Regions that at ``tau`` sit inside an existing void (they will split off as a
    smaller void) are not pockets; dents that fill without ever closing are not pockets.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` (or the :class:`~shapelab.Balls`, as for :func:`voids`).
    tau : float, default 0.0
        Growth time at which the pockets are reported (mouths and volumes refer to it).
    min_persistence : float, default 0.0
        Keep pockets with ``fills_at - closes_at >= min_persistence`` (zero-length
        classes never count in the growth model; a flow pocket of persistence 0, whose
        classes all have zero length up to round-off, is kept at 0.0: see
        :class:`shapelab.FlowPocket`).
    method : {"growth", "flow"}, default "growth"
        ``"growth"``: the notes' growth-model pockets (:class:`Pocket`).  ``"flow"``:
        CASTp's pockets, the regions of the discrete flow on the same regular
        triangulation that have a mouth (:func:`shapelab.flow_pockets` without its
        voids), as :class:`shapelab.FlowPocket`.  Both kinds have the same
        measured attributes (``cells``, ``cell_ids``, ``lining``, ``mouth``,
        ``mouth_ids``, ``mouth_size``, ``volume``, ``closes_at``, ``fills_at``,
        ``persistence``) and satisfy the :class:`Cavity` protocol.

    Returns
    -------
    tuple of Pocket or FlowPocket
        Sorted by persistence ``fills_at - closes_at``, largest first (ties: earlier
        ``closes_at``, then lower first cell row).

    Raises
    ------
    ValueError
        If ``method`` is not ``"growth"`` or ``"flow"``.

    See Also
    --------
    voids
        The voids at a time.
    shapelab.freespace.free_area
        The area of a mouth.
    shapelab.report
        Pockets measured as CASTp does.

    Notes
    -----
    The notes only say "a pocket can be roughly viewed as a dent on the surface"; which
    part of the dent is the pocket is left open.  Here it is the part that gets sealed:
    the cells of the void at the moment it closes.  Nested pockets are all reported.

    **Mouths** (Notes §23.1; CASTp's "mouth openings" [2]_, [3]_).  At ``tau`` the
    pocket's cells :math:`R` are part of the outside component of the complement of
    :math:`K_\\tau`.  Glue the free cells and :math:`\\infty` along the faces not in
    :math:`K_\\tau` and delete :math:`R`: the component of :math:`\\infty` is the rest of
    the outside, the other components are *crevices*, free cells that reach the outside
    only through :math:`R`.  The mouth is the set of faces not in :math:`K_\\tau`
    between :math:`R` and the rest of the outside: the cut that separates the pocket
    from :math:`\\infty` (every path out leaves :math:`R` for the last time through a
    mouth face), which is what CASTp calls the mouth: the openings through which a
    probe in the pocket reaches the bulk solvent.  Two consequences, tested:

    * a face into a crevice of the pocket's wall is no opening: Figure 23.2's flask
      has one mouth edge, the neck, not the four notches of the chamber's wall whose
      triangles are not yet in :math:`K_0`;
    * the mouth need not be what seals the pocket.  In a two-chamber flask the inner
      pocket (the upper chamber, sealed when the neck to the lower chamber closes) opens
      to the outside through the flask's neck, as the outer pocket does; the neck to
      the lower chamber leads into a dead end and is no mouth.  ``closes_at`` is when
      the pocket becomes a void of its own, which is after its mouth has closed.

    The discrete flow's pockets (``method="flow"``) have mouths by the same
    definition: a simplex that flows to :math:`\\infty` reaches it without crossing
    the region, so the flow's mouth (open faces to simplices that flow out) is this cut.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
           construction of pockets in macromolecules", *Discrete Appl. Math.* 88:83-102,
           1998. doi:10.1016/S0166-218X(98)00067-5
    .. [2] J. Liang, H. Edelsbrunner and C. Woodward, "Anatomy of protein pockets and
           cavities: measurement of binding site geometry and implications for ligand
           design", *Protein Sci.* 7(9):1884-1897, 1998. doi:10.1002/pro.5560070905
    .. [3] T. A. Binkowski, S. Naghibzadeh and J. Liang, "CASTp: Computed Atlas of
           Surface Topography of proteins", *Nucleic Acids Res.* 31(13):3352-3355, 2003.
           doi:10.1093/nar/gkg512

    Examples
    --------
    Figure 23.2's flask: one pocket, its mouth the neck (the gap of width 2 at the top);
    the discrete flow's pocket also takes in the notches of the chamber's wall, and has
    the same mouth and the same free area:

    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.figure_23_2()[0])
    >>> (p,) = sl.pockets(F)
    >>> p
    Pocket(cells=9, mouth=1, lining=11, closes_at=0.5775, fills_at=4.3275, tau=0)
    >>> (q,) = sl.pockets(F, method="flow")
    >>> len(q.cells), q.mouth_ids.tolist() == p.mouth_ids.tolist(), round(q.volume - p.volume, 12)
    (13, True, 0.0)
    """
    if method not in ("growth", "flow"):
        raise ValueError(f'pockets: method must be "growth" or "flow", got {method!r}')
    F = as_filtration(F, "pockets")
    balls = F.balls
    tau = as_tau(tau)
    mp = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    if not _full_dim(balls, F):
        return ()
    if method == "flow":
        from .flow import flow_pockets

        kept = [p for p in flow_pockets(F, tau) if not p.is_void and p.persistence >= mp]
        kept.sort(key=lambda p: (-p.persistence, p.closes_at, int(p.cell_ids[0])))
        return tuple(kept)
    S = summary(F)
    T = merge_tree(F)
    k = S.k
    n = S.values[k].shape[0]
    N = n + 1
    cv = S.values[k]
    b = T.kill_value
    cand = np.flatnonzero((b > tau) & (cv > b) & (cv - b >= mp))
    cand = cand[~is_roundoff(F, b[cand], cv[cand])]
    if cand.size == 0:
        return ()
    lab, _ = complement_labels(F, S, tau)
    cand = cand[lab[cand] == lab[n]]
    if cand.size == 0:
        return ()
    simp = np.asarray(F.simplices(k), dtype=np.int64)
    fsimp = np.asarray(F.simplices(k - 1), dtype=np.int64)
    outside = OutsideGraph(F, tau)
    vval = vertex_values(F, len(balls))
    out = []
    for r in cand.tolist():
        bb = float(b[r])
        node = int(T.kill_node[r])
        # merges at exactly the closing value happen at the same time: undo them
        while node >= N and T.value[node - N] <= bb:
            lo, hi = leaf_run(T, int(T.left[node - N]))
            node = int(T.left[node - N]) if lo <= T.pos[r] < hi else int(T.right[node - N])
        lo, hi = leaf_run(T, node)
        cid = np.sort(T.order[lo:hi])
        mouth = outside.mouth(cid)
        cverts = simp[cid]
        out.append(
            Pocket(
                cells=readonly(cverts, np.int64),
                cell_ids=readonly(cid, np.int64),
                mouth=readonly(fsimp[mouth].reshape(-1, k), np.int64),
                mouth_ids=readonly(mouth, np.int64),
                lining=readonly(lining_of(cverts, tau, vval), np.int64),
                closes_at=bb,
                fills_at=float(cv[r]),
                tau=tau,
                balls=balls,
            )
        )
    out.sort(key=lambda p: (-(p.fills_at - p.closes_at), p.closes_at, int(p.cell_ids[0])))
    return tuple(out)


# ================================================================ tunnels/grooves
def _build_h1_cycles(F):
    return reduce_h1(summary(F), F, compress=False)


def _h1_with_cycles(F):
    return derived(F, "cavities.h1_cycles", _build_h1_cycles)


def _h1_classes(F, tau, select, fname):
    balls = F.balls
    if balls.dim != 3:
        raise ValueError(
            f"{fname}: tunnels and grooves are H1 classes of unions of balls in 3D; in 2D the H1 "
            "classes are holes, which voids() returns"
        )
    S = summary(F)
    if S.k < 2:
        return ()
    piv_e, piv_t, cols = _h1_with_cycles(F)
    if piv_e.size == 0:
        return ()
    birth = S.values[1][piv_e]
    death = S.values[2][piv_t]
    keep = np.flatnonzero(select(birth, death) & (death > birth) & ~is_roundoff(F, birth, death))
    edges = np.asarray(F.simplices(1), dtype=np.int64)
    out = []
    for i in keep.tolist():
        ids = np.asarray(sorted(cols[int(piv_e[i])]), dtype=np.int64)
        out.append(
            Tunnel(
                birth=float(birth[i]),
                death=float(death[i]),
                cycle=readonly(edges[ids], np.int64),
                edge_ids=readonly(ids, np.int64),
                tau=tau,
            )
        )
    out.sort(key=lambda t: (-(t.death - t.birth), t.birth, int(t.edge_ids[-1])))
    return tuple(out)


def tunnels(F, tau=0.0) -> tuple:
    """The tunnels of the union of balls grown to ``tau``, in 3D (Notes §23.1).

    The :math:`H_1` classes alive at ``tau`` (``birth <= tau < death``); their number is
    :math:`\\beta_1(\\tau)`.  Each has a representative cycle from the column reduction
    of the boundary matrix (see :mod:`shapelab.topology`), computed once per
    filtration and kept on it.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 3D balls (or the :class:`~shapelab.Balls`, as
        for :func:`voids`).
    tau : float, default 0.0

    Returns
    -------
    tuple of Tunnel
        Sorted by persistence, largest first.

    Raises
    ------
    ValueError
        For 2D balls (there the :math:`H_1` classes are the holes: use :func:`voids`).

    See Also
    --------
    grooves
        H₁ classes born later.
    channel_profile
        The free radius along a tunnel.
    shapelab.topology.persistence
        The H₁ pairs.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069
    """
    F = as_filtration(F, "tunnels")
    tau = as_tau(tau)
    return _h1_classes(F, tau, lambda b, d: (b <= tau) & (d > tau), "tunnels")


def grooves(F, tau=0.0, *, min_persistence=0.0) -> tuple:
    """Grooves at ``tau``: :math:`H_1` classes born later, ``birth > tau`` (3D).

    Notes §23.1: "a groove on the surface of a molecule can be transformed into a
    tunnel, and be captured by our model" -- a groove is a tunnel that is born later in
    the growth.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 3D balls (or the :class:`~shapelab.Balls`, as
        for :func:`voids`).
    tau : float, default 0.0
    min_persistence : float, default 0.0
        Keep the grooves with ``death - birth >= min_persistence``.

    Returns
    -------
    tuple of Tunnel
        Sorted by persistence, largest first.

    See Also
    --------
    tunnels
        H₁ classes alive at τ.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069
    """
    F = as_filtration(F, "grooves")
    tau = as_tau(tau)
    mp = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    return _h1_classes(F, tau, lambda b, d: (b > tau) & (d - b >= mp), "grooves")


# ===================================================================== channel radius
@dataclass(frozen=True, eq=False)
class ChannelProfile:
    """The free radius along a channel: the result of :func:`channel_profile`.

    Attributes
    ----------
    offsets : ndarray, shape (k,)
        Positions along the axis (length units from ``point``).
    radius : ndarray, shape (k,)
        In each cross-section, the radius of the largest sphere centred in it that
        overlaps no ball (negative where the balls cover the whole neighbourhood).
    centers : ndarray, shape (k, 3)
        The centres of those spheres.

    See Also
    --------
    channel_profile
        Produces it.
    """

    offsets: np.ndarray
    radius: np.ndarray
    centers: np.ndarray

    @property
    def bottleneck(self) -> float:
        """The smallest free radius along the channel."""
        return float(self.radius.min())


def channel_profile(balls, point, direction, offsets, *, search: float = 3.0) -> ChannelProfile:
    """The free radius along a channel, slice by slice (in the manner of the HOLE program).

    In the plane through ``point + s * direction`` perpendicular to ``direction``, for
    each offset ``s``, find the point ``x`` farthest from the balls, maximising
    :math:`\\min_i(\\lVert x - c_i\\rVert - r_i)` (Nelder–Mead, started from the previous
    slice's answer and from the axis, kept within ``search`` of the axis).  That value is
    the radius of the largest probe sphere centred in the slice; its minimum along the
    channel is the bottleneck that a tunnel's death time τ measures in the growth model
    (Notes §23.1, tunnels).

    Parameters
    ----------
    balls : Balls
        3D balls (van der Waals radii for a molecule).
    point, direction : array_like, shape (3,)
        A point on the channel's axis and the axis' direction.
    offsets : array_like, shape (k,)
        Where to slice, along ``direction`` from ``point``.
    search : float
        How far from the axis a slice's centre may move.

    Returns
    -------
    ChannelProfile

    See Also
    --------
    tunnels
        The channels.
    shapelab.plot.channel_profile
        Draws the profile.

    References
    ----------
    .. [1] O. S. Smart, J. M. Goodfellow and B. A. Wallace, "The pore dimensions of
           gramicidin A", *Biophys. J.* 65(6):2455-2460, 1993.
           doi:10.1016/S0006-3495(93)81293-1
    """
    from scipy.optimize import minimize
    from scipy.spatial import cKDTree

    from ._toolkit.validate import as_finite_scalar, as_points

    balls = check_balls(balls, "balls", dim=3)
    point = as_points(np.reshape(point, (1, -1)), "point", dim=3)[0]
    direction = as_points(np.reshape(direction, (1, -1)), "direction", dim=3)[0]
    norm = float(np.linalg.norm(direction))
    if not norm > 0:
        raise ValueError("direction must be a nonzero vector")
    u = direction / norm
    offsets = as_points(np.reshape(offsets, (-1, 1)), "offsets").ravel()
    search = as_finite_scalar(search, "search", positive=True)
    if len(balls) == 0:
        raise ValueError("balls must not be empty")
    # an orthonormal basis (e1, e2) of the slices
    e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)
    C, r = balls.centers, balls.radii
    tree = cKDTree(C)
    k_near = min(len(C), 32)
    rmax = float(r.max())

    def clearance(x3):
        # min_i |x - c_i| - r_i, exactly: the k nearest centres decide unless radii differ a lot
        d, idx = tree.query(x3, k=k_near)
        d, idx = np.atleast_1d(d), np.atleast_1d(idx)
        best = float(np.min(d - r[idx]))
        if k_near < len(C) and d[-1] - rmax < best:  # a far big ball could be closer: check all
            best = float(np.min(np.linalg.norm(C - x3, axis=1) - r))
        return best

    radius, centers, prev = np.empty(len(offsets)), np.empty((len(offsets), 3)), np.zeros(2)
    for k, s in enumerate(offsets):
        origin = point + s * u

        def cost(y, origin=origin):
            y = np.asarray(y)
            excess = max(0.0, float(np.hypot(*y)) - search)
            return -clearance(origin + y[0] * e1 + y[1] * e2) + 10.0 * excess

        starts = [prev, np.zeros(2)]
        runs = [
            minimize(cost, y0, method="Nelder-Mead", options={"xatol": tol.CHANNEL_XATOL, "fatol": tol.CHANNEL_FATOL})
            for y0 in starts
        ]
        best = min(runs, key=lambda res: res.fun)
        y = best.x
        prev = y
        centers[k] = origin + y[0] * e1 + y[1] * e2
        radius[k] = clearance(centers[k])
    for a in (offsets, radius, centers):
        a.flags.writeable = False
    return ChannelProfile(offsets, radius, centers)
