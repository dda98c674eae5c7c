"""Voids: the bounded components of the complement of the grown union (Notes §23.1).

"A void of :math:`\\mathbb{P}` is a bounded connected component of
:math:`\\mathbb{R}^3 \\setminus \\bigcup B_i`."  Through the filtration: the
components of the dual graph of the complement of :math:`K_\\tau`
(:mod:`shapelab.cavities.complement`) that avoid the outside; the merge tree of the
complement gives when each was sealed (``born``) and filled (``dies``), and the
free-space integration its volume (:mod:`shapelab.cavities.freespace`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .._engine.persistence import summary
from .._toolkit.validate import as_tau, readonly
from ..filtration import as_filtration
from .complement import complement_labels, full_dimensional, lining_of, sealed_at, vertex_values
from .freespace import void_measure

__all__ = ["Void", "voids"]

if TYPE_CHECKING:
    from ..balls import Balls
    from ..filtration import Filtration


@dataclass(frozen=True, eq=False)
class Void:
    """A bounded component of the complement of the grown union (Notes §23.1).

    Attributes
    ----------
    cells : ndarray, shape (m, d+1), int
        The top simplices of the regular triangulation that form the void, as ball
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
        coefficient field (Alexander duality; :func:`shapelab.persistence.persistence`)."""
        return self.dies - self.born

    def __repr__(self) -> str:
        return (
            f"Void(cells={len(self.cells)}, lining={len(self.lining)}, born={self.born:.6g}, "
            f"dies={self.dies:.6g}, volume={self.volume:.6g}, tau={self.tau:.6g})"
        )


def voids(F: Filtration | Balls, tau: float = 0.0) -> tuple:
    """The voids (holes in 2D) of the union of the balls grown to ``tau``.

    Notes §23.1: "A void of :math:`\\mathbb{P}` is a bounded connected component of
    :math:`\\mathbb{R}^3 \\setminus \\bigcup B_i`"; the notes add that each void of the
    union has a corresponding void of :math:`K` "much more amiable to computation".
    Here they are found as the components of the complement of :math:`K_\\tau` in the
    regular triangulation that do not reach the outside.

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
    shapelab.cavities.freespace.free_space
        The free volume of cells.
    shapelab.persistence.betti
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
    if not full_dimensional(F):
        return ()
    S = summary(F)
    born = sealed_at(F)  # the time each cell's void is sealed
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
                born=float(born[root]),
                dies=float(S.values[k][root]),
                volume=float(max(csum[e] - csum[s], 0.0)),
                tau=tau,
            )
        )
    out.sort(key=lambda x: (-(x.dies - x.born), x.born, int(x.cell_ids[0])))
    return tuple(out)
