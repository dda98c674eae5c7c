"""What a void, a pocket and a tunnel share: the :class:`Cavity` protocol (Notes §23.1)."""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

__all__ = ["Cavity"]


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
