r"""Morse theory of the power distance: the critical points behind the α-filtration
(Notes §23.1, the growth model; Edelsbrunner 1995; Bauer and Edelsbrunner 2017).

The union of the balls grown to time :math:`\tau` (radius :math:`\sqrt{r_i^2 + \tau}`)
is the sublevel set :math:`f^{-1}(-\infty, \tau]` of

.. math:: f(x) = \min_i \pi_i(x), \qquad \pi_i(x) = \lVert x - z_i\rVert^2 - r_i^2,

the power distance to the nearest ball.  :math:`f` is not smooth (it is a minimum of
quadratics), but it has critical points in the sense of distance functions: :math:`x`
is critical when it lies in the convex hull of the centres of the balls that attain the
minimum at :math:`x`.  Let :math:`\sigma` be that set of balls.  In general position
:math:`x` then lies on the power face :math:`V_\sigma` dual to :math:`\sigma` (equal
power to the balls of :math:`\sigma`, more to every other) and in the affine hull of
:math:`\sigma`; the two meet in one point, the *orthocentre* :math:`y_\sigma` (the centre
of the smallest sphere orthogonal to the balls of :math:`\sigma`).  So

* the critical points are the orthocentres :math:`y_\sigma` of the simplices
  :math:`\sigma` of the regular triangulation with :math:`y_\sigma` in the interior of
  :math:`\sigma` and in the interior of :math:`V_\sigma` (no other ball closer in power:
  :math:`\sigma` is *unattached*, :meth:`shapelab.Filtration.attached`);
* the critical value is :math:`f(y_\sigma) = \pi_{z}(y_\sigma)` for any vertex of
  :math:`\sigma`, which is :math:`\sigma`'s entry time in the α-filtration;
* the index is :math:`\dim\sigma`: along :math:`\operatorname{aff}\sigma`, :math:`f`
  has a maximum at :math:`y_\sigma`, across it (along :math:`V_\sigma`) a minimum.

A vertex is a minimum (index 0, value :math:`-r_i^2` at :math:`z_i`) unless another ball
covers its centre in power; a triangle in 2D (a tetrahedron in 3D) is a maximum when
its orthocentre lies inside it.  Passing a critical value of index :math:`k` attaches a
:math:`k`-cell to the union, which either creates a class of :math:`H_k` or kills one
of :math:`H_{k-1}`: every birth and every finite death of the α-filtration's
persistence diagram is a critical value.

:func:`power_critical_points` reads them off the filtration;
:func:`critical_points_by_subsets` finds them from the definition, over all subsets of
at most :math:`d + 1` balls, with no triangulation (the oracle).  Both decide "inside"
and "no other ball closer" exactly, in rational arithmetic on the input's binary
values; they are meant for teaching-size input (tens of balls).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from itertools import combinations
from typing import TYPE_CHECKING

import numpy as np

from .balls import Balls
from .filtration import as_filtration

if TYPE_CHECKING:
    from .filtration import Filtration

__all__ = ["PowerCriticalPoints", "power_critical_points", "critical_points_by_subsets"]


@dataclass(frozen=True, eq=False)
class PowerCriticalPoints:
    """The critical points of the power distance :math:`f(x) = \\min_i \\pi_i(x)`.

    Attributes
    ----------
    simplices : tuple of tuple of int
        The critical simplices :math:`\\sigma` (sorted ball indices), in order of value.
    index : ndarray of int, shape (m,)
        The Morse index of each, :math:`\\dim\\sigma`.
    values : ndarray, shape (m,)
        The critical values :math:`f(y_\\sigma)`.
    positions : ndarray, shape (m, d)
        The critical points, the orthocentres :math:`y_\\sigma`.

    See Also
    --------
    power_critical_points, critical_points_by_subsets
    """

    simplices: tuple
    index: np.ndarray
    values: np.ndarray
    positions: np.ndarray

    @property
    def counts(self) -> tuple:
        """The number of critical points of each index :math:`0, \\dots, d`."""
        d = self.positions.shape[1] if self.positions.ndim == 2 else 0
        return tuple(int(np.sum(self.index == k)) for k in range(d + 1))

    @property
    def euler_characteristic(self) -> int:
        """:math:`\\sum_k (-1)^k c_k`: 1, the Euler characteristic of the whole space
        (the sublevel set for large :math:`\\tau`)."""
        return int(sum((-1) ** k * c for k, c in enumerate(self.counts)))

    def __len__(self) -> int:
        return len(self.simplices)

    def __repr__(self) -> str:
        return f"PowerCriticalPoints({len(self)} critical points, counts by index {self.counts})"


def _exact(balls: Balls):
    Z = [[Fraction(float(v)) for v in row] for row in balls.centers]
    W = [Fraction(float(r)) ** 2 for r in balls.radii]
    return Z, W


def _solve(A, b):
    """Solve the square rational system A x = b by Gaussian elimination; None if singular."""
    n = len(A)
    M = [list(A[i]) + [b[i]] for i in range(n)]
    for c in range(n):
        p = next((r for r in range(c, n) if M[r][c] != 0), None)
        if p is None:
            return None
        M[c], M[p] = M[p], M[c]
        for r in range(n):
            if r != c and M[r][c] != 0:
                f = M[r][c] / M[c][c]
                M[r] = [a - f * e for a, e in zip(M[r], M[c])]
    return [M[i][n] / M[i][i] for i in range(n)]


def _orthocentre(Z, W, sigma):
    """Barycentric coordinates, point and power of the orthocentre of ``sigma``, exactly;
    None when the centres of ``sigma`` are affinely dependent."""
    z0, w0 = Z[sigma[0]], W[sigma[0]]
    E = [[a - b for a, b in zip(Z[j], z0)] for j in sigma[1:]]
    # y = z0 + E^T mu with equal power to all balls of sigma:
    # 2 (y - z0) . e_j = |e_j|^2 - w_j + w0
    rhs = [sum(e * e for e in E[i]) - W[j] + w0 for i, j in enumerate(sigma[1:])]
    if E:
        G = [[2 * sum(a * b for a, b in zip(E[i], E[j])) for j in range(len(E))] for i in range(len(E))]
        mu = _solve(G, rhs)
        if mu is None:
            return None
    else:
        mu = []
    y = [z0[c] + sum(m * E[i][c] for i, m in enumerate(mu)) for c in range(len(z0))]
    power = sum((a - b) ** 2 for a, b in zip(y, z0)) - w0
    return [1 - sum(mu), *mu], y, power


def _power(Z, W, i, y):
    return sum((a - b) ** 2 for a, b in zip(y, Z[i])) - W[i]


def _result(found, dim: int) -> PowerCriticalPoints:
    found = sorted(found, key=lambda t: (t[2], len(t[0]), t[0]))
    return PowerCriticalPoints(
        simplices=tuple(tuple(int(v) for v in s) for s, _, _ in found),
        index=np.array([len(s) - 1 for s, _, _ in found], dtype=np.int64),
        values=np.array([float(v) for _, _, v in found], dtype=float),
        positions=np.array([[float(c) for c in y] for _, y, _ in found], dtype=float).reshape(-1, dim),
    )


def power_critical_points(F: Filtration | Balls) -> PowerCriticalPoints:
    """The critical points of the power distance, read off the α-filtration.

    A simplex :math:`\\sigma` of the regular triangulation is critical when it is
    unattached (its orthocentre :math:`y_\\sigma` lies on its dual power face) and
    :math:`y_\\sigma` lies in the interior of :math:`\\sigma`; its critical value is
    its entry time and its index its dimension (module docstring).

    Parameters
    ----------
    F : Balls or Filtration
        The balls, or their α-filtration.

    Returns
    -------
    PowerCriticalPoints
        Sorted by value.  The values are the filtration's entry times of the
        critical simplices.

    See Also
    --------
    critical_points_by_subsets : the same from the definition, without a triangulation.
    shapelab.Filtration.attached : the unattached simplices.

    Notes
    -----
    Notes §23.1 (the growth model).  The interior test is exact (rational barycentric
    coordinates of the orthocentre); a coordinate exactly zero (the orthocentre on the
    boundary, a degenerate input) does not count as inside.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", Discrete Comput.
       Geom. 13 (1995) 415–440, doi:10.1007/BF02574053.
    .. [2] U. Bauer and H. Edelsbrunner, "The Morse theory of Čech and Delaunay
       complexes", Trans. Amer. Math. Soc. 369 (2017) 3741–3762,
       doi:10.1090/tran/6991.

    Examples
    --------
    >>> import shapelab as sl
    >>> b = sl.Balls([[0.0, 0.0], [4.0, 0.0], [2.0, 3.0]], [1.0, 1.0, 1.0])
    >>> cp = power_critical_points(b)
    >>> cp.counts                      # three minima, three saddles, one maximum
    (3, 3, 1)
    >>> cp.euler_characteristic
    1
    """
    F = as_filtration(F, "power_critical_points")
    balls = F.balls
    Z, W = _exact(balls)
    found = []
    for k in range(balls.dim + 1):
        S = np.asarray(F.simplices(k))
        if S.size == 0:
            continue
        att = np.asarray(F.attached(k)) if k < balls.dim else np.zeros(len(S), dtype=bool)
        vals = np.asarray(F.values(k), dtype=float)
        for s, a, v in zip(S.tolist(), att, vals):
            if a:
                continue
            o = _orthocentre(Z, W, s)
            if o is None or not all(c > 0 for c in o[0]):
                continue
            found.append((sorted(s), o[1], float(v)))
    return _result(found, balls.dim)


def critical_points_by_subsets(balls: Balls) -> PowerCriticalPoints:
    """The critical points of the power distance from the definition, by brute force.

    For every set :math:`\\sigma` of at most :math:`d + 1` balls with affinely
    independent centres, the orthocentre :math:`y_\\sigma` is critical when it lies in
    the interior of :math:`\\sigma` and every other ball has strictly larger power at
    it; no triangulation is used.  :math:`O(n^{d+2})` exact tests: for a dozen balls.

    Parameters
    ----------
    balls : Balls
        The balls.

    Returns
    -------
    PowerCriticalPoints
        Sorted by value; the values are :math:`f(y_\\sigma)`.

    See Also
    --------
    power_critical_points : the same from the α-filtration.

    References
    ----------
    .. [1] U. Bauer and H. Edelsbrunner, "The Morse theory of Čech and Delaunay
       complexes", Trans. Amer. Math. Soc. 369 (2017) 3741–3762,
       doi:10.1090/tran/6991.

    Examples
    --------
    >>> import shapelab as sl
    >>> b = sl.Balls([[0.0, 0.0], [4.0, 0.0], [2.0, 3.0]], [1.0, 1.0, 1.0])
    >>> critical_points_by_subsets(b).counts
    (3, 3, 1)
    """
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be Balls, got {type(balls).__name__}")
    Z, W = _exact(balls)
    n, d = len(Z), balls.dim
    found = []
    for k in range(min(d, n - 1) + 1):
        for s in combinations(range(n), k + 1):
            o = _orthocentre(Z, W, list(s))
            if o is None or not all(c > 0 for c in o[0]):
                continue
            bary, y, value = o
            if all(_power(Z, W, i, y) > value for i in range(n) if i not in s):
                found.append((list(s), y, float(value)))
    return _result(found, d)
