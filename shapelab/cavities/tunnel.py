"""Tunnels and grooves: the :math:`H_1` classes of the grown union in 3D (Notes §23.1).

A tunnel at τ is an :math:`H_1` class alive at τ (birth ≤ τ < death), with a
representative cycle taken from the reduced boundary matrix: the cycle born at
``birth`` that becomes a boundary at ``death``.  "A groove on the surface of a
molecule can be transformed into a tunnel": grooves are the :math:`H_1` classes born
after τ.  :func:`channel_profile` measures the free radius along a channel.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from .._engine.persistence import is_roundoff, reduce_h1, summary
from .._toolkit import tolerances as tol
from .._toolkit.derived import derived
from .._toolkit.validate import as_finite_scalar, as_tau, check_balls, readonly
from ..filtration import as_filtration

if TYPE_CHECKING:
    from ..balls import Balls
    from ..filtration import Filtration

__all__ = ["Tunnel", "tunnels", "grooves", "ChannelProfile", "channel_profile"]


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
        field a tunnel's death can differ (:func:`shapelab.persistence.persistence`)."""
        return self.death - self.birth

    def __repr__(self) -> str:
        return (
            f"Tunnel(birth={self.birth:.6g}, death={self.death:.6g}, cycle={len(self.cycle)} edges, tau={self.tau:.6g})"
        )


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


def tunnels(F: Filtration | Balls, tau: float = 0.0) -> tuple:
    """The tunnels of the union of balls grown to ``tau``, in 3D (Notes §23.1).

    The :math:`H_1` classes alive at ``tau`` (``birth <= tau < death``); their number is
    :math:`\\beta_1(\\tau)`.  Each has a representative cycle from the column reduction
    of the boundary matrix (see :mod:`shapelab.persistence`), computed once per
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
    shapelab.persistence.persistence
        The H₁ pairs.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    A ring of 12 balls in 3D has one tunnel, a cycle through all of them:

    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.ring(12, dim=3))
    >>> sl.tunnels(F)
    (Tunnel(birth=-0.397114, death=8, cycle=12 edges, tau=0),)
    """
    F = as_filtration(F, "tunnels")
    tau = as_tau(tau)
    return _h1_classes(F, tau, lambda b, d: (b <= tau) & (d > tau), "tunnels")


def grooves(F: Filtration | Balls, tau: float = 0.0, *, min_persistence: float = 0.0) -> tuple:
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

    Examples
    --------
    Before the ring's tunnel is born (at τ = -0.397114) it is a groove:

    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.ring(12, dim=3))
    >>> sl.grooves(F, -0.5)  # balls of radius about 0.71: the ring not yet closed
    (Tunnel(birth=-0.397114, death=8, cycle=12 edges, tau=-0.5),)
    """
    F = as_filtration(F, "grooves")
    tau = as_tau(tau)
    mp = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    return _h1_classes(F, tau, lambda b, d: (b > tau) & (d - b >= mp), "grooves")


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


def channel_profile(
    balls: Balls, point: npt.ArrayLike, direction: npt.ArrayLike, offsets: npt.ArrayLike, *, search: float = 3.0
) -> ChannelProfile:
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

    Examples
    --------
    Through a ring of balls of radius 1 on a circle of radius 3 the channel is
    narrowest in the ring's plane, where the free radius is 3 - 1:

    >>> import shapelab as sl
    >>> balls = sl.datasets.ring(8, radius=3.0, disk_radius=1.0, dim=3)
    >>> prof = sl.channel_profile(balls, [0, 0, 0], [0, 0, 1], [-1.0, 0.0, 1.0])
    >>> prof.radius.round(3).tolist(), round(prof.bottleneck, 3)
    ([2.162, 2.0, 2.162], 2.0)
    """
    from scipy.optimize import minimize
    from scipy.spatial import cKDTree

    from .._toolkit.validate import as_points

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
