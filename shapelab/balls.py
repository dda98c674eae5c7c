"""Balls and the power distance (Notes §23.1).

A ball :math:`B_i = (z_i, r_i)` is a centre :math:`z_i \\in \\mathbb{R}^d` (``d`` = 2 or
3) and a radius :math:`r_i \\ge 0`.  Its *weight* is :math:`w_i = r_i^2`.  The power
distance of a point :math:`x` from :math:`B_i` is

.. math:: \\pi_i(x) = \\lVert x - z_i \\rVert^2 - r_i^2,

which is negative inside the ball, zero on its sphere, and equal to the squared length
of a tangent segment from :math:`x` outside it.  The power diagram, the regular
triangulation and the dual complex of the notes are all built from this one function.

The growth model of §23.1 grows every radius to :math:`\\sqrt{r_i^2 + \\tau}`; this is
:meth:`Balls.grow`.  In power-distance terms a point :math:`x` lies in the grown ball
:math:`B_i(\\tau)` iff :math:`\\pi_i(x) \\le \\tau`.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.bases import BallsBase
from ._toolkit.derived import KeepsDerived
from ._toolkit.validate import (
    as_finite_scalar,
    as_point,
    as_points,
    as_radii,
    as_tau,
    check_balls,
    readonly,
)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["Balls", "power_distance"]


@dataclass(frozen=True, eq=False)
class Balls(BallsBase, KeepsDerived):
    """A finite set of balls (disks in 2D) with centres and radii.

    Parameters
    ----------
    centers : array_like, shape (n, d)
        Ball centres :math:`z_i`, ``d`` in {2, 3}, finite.
    radii : array_like, shape (n,) or scalar
        Radii :math:`r_i \\ge 0`, finite.  A scalar is broadcast to all balls.

    Attributes
    ----------
    centers : ndarray, shape (n, d), read-only
    radii : ndarray, shape (n,), read-only

    See Also
    --------
    power_distance
        The distance of a point to the balls.
    alpha_filtration
        The growth model of the balls.

    Notes
    -----
    Notes §23.1 write :math:`\\mathbb{P} = \\{B_1, \\dots, B_n\\}`.  A ball of radius
    zero is a point; a set of balls with radius zero gives the ordinary (unweighted)
    Delaunay / alpha-complex setting.

    Examples
    --------
    >>> b = Balls([[0, 0], [3, 0]], [1.0, 2.0])
    >>> len(b), b.dim, b.weights.tolist()
    (2, 2, [1.0, 4.0])
    """

    centers: np.ndarray
    radii: np.ndarray

    def __init__(self, centers, radii=0.0):
        c = as_points(centers, "centers", dim=(2, 3), min_points=0)
        r = as_radii(radii, c.shape[0], "radii")
        object.__setattr__(self, "centers", readonly(c))
        object.__setattr__(self, "radii", readonly(r))
        object.__setattr__(self, "_derived", {})

    def __getstate__(self):
        return {"centers": self.centers, "radii": self.radii}

    def __setstate__(self, state):
        # pickle and copy.deepcopy give back writeable arrays: validated and frozen again,
        # so that an unpickled or deep-copied Balls is as immutable as any other (and what
        # derived() keeps for it cannot go stale)
        self.__init__(state["centers"], state["radii"])

    # ------------------------------------------------------------------ basics
    @property
    def weights(self) -> np.ndarray:
        """The weights :math:`w_i = r_i^2` (Notes §23.1), shape (n,)."""
        return self.radii * self.radii

    @property
    def dim(self) -> int:
        """The ambient dimension d (2 or 3)."""
        return int(self.centers.shape[1])

    def __len__(self) -> int:
        return int(self.centers.shape[0])

    def __getitem__(self, index) -> "Balls":
        """Select balls by int, slice, boolean mask or integer index array."""
        if isinstance(index, (numbers.Integral, np.integer)) and not isinstance(index, (bool, np.bool_)):
            i = int(index)
            n = len(self)
            if not -n <= i < n:
                raise IndexError(f"ball index {i} out of range for {n} balls")
            index = [i]
        elif isinstance(index, slice):
            pass
        else:
            idx = np.asarray(index)
            if idx.dtype == bool:
                if idx.shape != (len(self),):
                    raise IndexError(f"boolean index must have shape ({len(self)},), got {idx.shape}")
            elif idx.dtype.kind in "iu" or idx.size == 0:
                idx = idx.astype(np.intp).ravel()
            else:
                raise TypeError(f"balls can be indexed by int, slice, mask or int array, got {idx.dtype}")
            index = idx
        return Balls(self.centers[index], self.radii[index])

    def __repr__(self) -> str:
        return f"Balls(n={len(self)}, dim={self.dim})"

    # ------------------------------------------------------------ growth model
    def grow(self, tau) -> "Balls":
        """The balls at growth time ``tau``: radii :math:`\\sqrt{r_i^2 + \\tau}` (Notes §23.1).

        Parameters
        ----------
        tau : float
            Growth time; may be negative as long as every :math:`r_i^2 + \\tau \\ge 0`.

        Raises
        ------
        ValueError
            If some :math:`r_i^2 + \\tau < 0` (that ball's radius would be imaginary;
            the notes: "before time :math:`-r_i^2`, the radius of ball :math:`B_i` is
            imaginary").
        """
        t = as_tau(tau, finite=True)
        w = self.weights + t
        if np.any(w < 0):
            i = int(np.argmin(w))
            raise ValueError(
                f"tau = {t!r} makes the radius of ball {i} imaginary: "
                f"r[{i}]**2 + tau = {float(w[i])!r} < 0 (tau must be >= {float(-self.weights[i])!r})"
            )
        return Balls(self.centers, np.sqrt(w))

    def translated(self, v) -> "Balls":
        """The balls moved by the vector ``v`` (radii unchanged)."""
        v = as_point(v, "v", dim=self.dim)
        return Balls(self.centers + v, self.radii)

    def scaled(self, s) -> "Balls":
        """The balls scaled about the origin by ``s > 0`` (centres and radii)."""
        s = as_finite_scalar(s, "s", positive=True)
        return Balls(self.centers * s, self.radii * s)


def power_distance(x: ArrayLike, balls: Balls) -> np.ndarray:
    """Power distance :math:`\\pi_i(x) = \\lVert x - z_i\\rVert^2 - r_i^2` (Notes §23.1).

    Parameters
    ----------
    x : array_like, shape (d,) or (m, d)
        One point or m points.
    balls : Balls
        The n balls.

    Returns
    -------
    ndarray
        Shape (n,) for a single point, (m, n) for m points.

    See Also
    --------
    power_diagram
        The cells of least power distance.
    Balls.grow
        Grown balls, whose power distances shift by τ.

    Notes
    -----
    Outside :math:`B_i`, :math:`\\pi_i(x)` is the squared length of a tangent from
    :math:`x` to the sphere of :math:`B_i`; it is negative inside.  Computed as
    ``sum((x - z)**2) - r**2`` (not by expanding the square, which would lose
    precision for coordinates far from the origin).

    References
    ----------
    .. [1] F. Aurenhammer, "Power diagrams: properties, algorithms and applications",
           *SIAM J. Comput.* 16(1):78-96, 1987. doi:10.1137/0216006

    Examples
    --------
    >>> power_distance([0.0, 0.0], Balls([[3, 4]], [1.0])).tolist()
    [24.0]
    """
    check_balls(balls)
    arr = np.asarray(x) if not isinstance(x, (str, bytes)) else x
    single = getattr(arr, "ndim", None) == 1
    if single:
        p = as_point(x, "x", dim=balls.dim)[None, :]
    else:
        p = as_points(x, "x", dim=balls.dim, min_points=0)
    diff = p[:, None, :] - balls.centers[None, :, :]
    out = np.einsum("mnd,mnd->mn", diff, diff) - balls.weights[None, :]
    return out[0] if single else out
