"""Pockets by the growth model (Notes §23.1, Figure 23.2).

"If we grow the balls ... uniformly, the left pocket will produce a void in the life
time of the filtration while the right pocket will not."  A pocket at τ is a region
of the complement that is still part of the outside at τ but is sealed off into a
void at a later :math:`\\tau' > \\tau` (``closes_at``), filled at ``fills_at``: an
:math:`H_{d-1}` class of the merge tree of the complement
(:mod:`shapelab.cavities.complement`) born after τ whose cells are, at τ, in the
component of :math:`\\infty`.  Its *mouth* (:mod:`shapelab.cavities.mouths`) is the
set of open faces through which it opens to the rest of the outside.  A dent whose
cells fill before its mouth closes never becomes a void and is no pocket.  Pockets
nest (the "pocket hierarchy").

Mouths
------
The notes only say "a pocket can be roughly viewed as a dent on the surface"; which
part of the dent is the pocket is left open.  Here it is the part that gets sealed:
the cells of the void at the moment it closes.  Nested pockets are all reported.

The mouth (Notes §23.1; CASTp's "mouth openings", Liang et al. 1998, Binkowski et
al. 2003).  At ``tau`` the
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
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .._engine.mouths import cells_at_closing
from .._engine.persistence import is_roundoff, summary
from .._toolkit.validate import as_finite_scalar, as_precision, as_tau, readonly
from ..filtration import as_filtration
from .complement import complement_labels, full_dimensional, lining_of, merge_tree, sealed_at, vertex_values
from .mouths import MeasuredRegion, mouth_finder

__all__ = ["Pocket", "pockets", "growth_pockets"]

if TYPE_CHECKING:
    from ..balls import Balls
    from ..filtration import Filtration


@dataclass(frozen=True, eq=False)
class Pocket(MeasuredRegion):
    """A dent that closes into a void later in the growth (Notes §23.1, Figure 23.2).

    Attributes
    ----------
    cells, cell_ids : ndarray
        The cells (top simplices of the regular triangulation) of the void the pocket
        becomes, when it closes (ball indices, and rows of ``F.simplices(d)``).
    mouth, mouth_ids : ndarray
        The openings at ``tau`` to the rest of the outside (module docstring): ball
        indices, shape (q, d), and rows of ``F.simplices(d-1)``.
    mouth_size : float
        Total size of the mouth simplices: length in 2D, area in 3D.
    lining : ndarray, int
        The pocket's *lining atoms*: the balls at the vertices of its cells that exist
        at ``tau`` (the report's ``lining_atoms`` are its wall atoms, lesson 09).
    closes_at : float
        The τ′ > τ at which the mouth closes and the pocket becomes a void.
    fills_at : float
        The τ at which that void is filled.
    tau : float
        The growth time the pocket was computed at.
    volume : float
        Free space in the cells at ``tau`` (area in 2D), exact, on first access.

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


def pockets(
    F: Filtration | Balls,
    tau: float = 0.0,
    *,
    min_persistence: float = 0.0,
    method: str = "growth",
    precision: str = "exact",
) -> tuple:
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
        Before the first ball enters (``tau`` below every entry time, ``-inf``) the
        union is empty: no growth-model pockets.
    min_persistence : float, default 0.0
        Keep pockets with ``fills_at - closes_at >= min_persistence`` (a flow pocket of
        persistence 0, a tie, is kept at 0.0: :class:`shapelab.FlowPocket`).
    method : {"growth", "flow"}, default "growth"
        ``"growth"``: the notes' growth-model pockets (:class:`Pocket`).  ``"flow"``:
        CAST's pockets, the regions of the discrete flow that have a mouth
        (:func:`shapelab.flow_pockets` without its voids), :class:`shapelab.FlowPocket`;
        the same measured attributes, and both satisfy the :class:`Cavity` protocol.
    precision : {"exact", "fast"}, default "exact"
        ``"exact"``: the mouths by the engine's certified search and the flow's exact
        decisions.  ``"fast"``: the plain definitions (:func:`shapelab.cavities.mouths.mouth`,
        the flow's floating-point test); the same pockets on generic input (tested).

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
    shapelab.cavities.freespace.free_area
        The area of a mouth.
    shapelab.report
        Pockets measured as CASTp does.

    Notes
    -----
    Which part of a dent is the pocket, and what its mouth is (a cut, not what seals
    it; CASTp's "mouth openings" [2]_, [3]_): module docstring, *Mouths*.

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
    if precision not in ("exact", "fast"):
        raise ValueError(f'pockets: precision must be "exact" or "fast", got {precision!r}')
    if method == "flow":
        from .flow import flow_pockets

        F = as_filtration(F, "pockets")
        tau = as_tau(tau)
        mp = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
        if not full_dimensional(F):
            return ()
        kept = [p for p in flow_pockets(F, tau, precision=precision) if not p.is_void and p.persistence >= mp]
        kept.sort(key=lambda p: (-p.persistence, p.closes_at, int(p.cell_ids[0])))
        return tuple(kept)
    return growth_pockets(F, tau, min_persistence=min_persistence, precision=precision)


def growth_pockets(
    F: Filtration | Balls, tau: float = 0.0, *, min_persistence: float = 0.0, precision: str = "exact"
) -> tuple[Pocket, ...]:
    """The growth model's pockets (Notes §23.1): :func:`pockets` with its default method.

    Parameters
    ----------
    F, tau, min_persistence, precision
        As for :func:`pockets`.

    Returns
    -------
    tuple of Pocket
        Sorted by persistence, largest first.

    See Also
    --------
    pockets
        The same, or the discrete flow's pockets (``method="flow"``).

    Examples
    --------
    >>> import shapelab as sl
    >>> growth_pockets(sl.datasets.figure_23_2()[0])  # Figure 23.2's flask
    (Pocket(cells=9, mouth=1, lining=11, closes_at=0.5775, fills_at=4.3275, tau=0),)
    """
    precision = as_precision(precision, "pockets: precision")
    F = as_filtration(F, "pockets")
    balls = F.balls
    tau = as_tau(tau)
    mp = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    if not full_dimensional(F) or tau < F.values(0)[0]:  # no balls yet: no union to dent
        return ()
    S = summary(F)
    k = S.k
    n = S.values[k].shape[0]
    # every cell r roots a part of the complement: sealed off at b[r], filled at cv[r]
    cv = S.values[k]
    b = sealed_at(F)
    # a pocket at tau: a class sealed later than tau, of positive length ...
    cand = np.flatnonzero((b > tau) & (cv > b) & (cv - b >= mp))
    cand = cand[~is_roundoff(F, b[cand], cv[cand])]
    # ... whose cells are, at tau, still part of the outside
    lab, _ = complement_labels(F, S, tau)
    cand = cand[lab[cand] == lab[n]]
    if cand.size == 0:
        return ()
    simp = np.asarray(F.simplices(k), dtype=np.int64)
    fsimp = np.asarray(F.simplices(k - 1), dtype=np.int64)
    mouth_of = mouth_finder(F, tau, precision)
    vval = vertex_values(F, len(balls))
    out = []
    for r in cand.tolist():
        # the void's cells when it closes, cells_when_sealed(F, r), by the merge tree (tested equal)
        cid = cells_at_closing(merge_tree(F), r)
        cverts = simp[cid]
        lining = lining_of(cverts, tau, vval)
        mouth = mouth_of(cid)
        out.append(
            Pocket(
                cells=readonly(cverts, np.int64),
                cell_ids=readonly(cid, np.int64),
                mouth=readonly(fsimp[mouth].reshape(-1, k), np.int64),
                mouth_ids=readonly(mouth, np.int64),
                lining=readonly(lining, np.int64),
                closes_at=float(b[r]),
                fills_at=float(cv[r]),
                tau=tau,
                balls=balls,
            )
        )
    out.sort(key=lambda p: (-(p.fills_at - p.closes_at), p.closes_at, int(p.cell_ids[0])))
    return tuple(out)
