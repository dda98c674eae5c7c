r"""Closed forms for the terms of the short inclusion–exclusion formula (Notes §23.1;
Edelsbrunner 1995; Edelsbrunner and Fu 1994).

The short formula of :mod:`shapelab.measure` sums, with signs
:math:`(-1)^{\dim\sigma}`, the measure of :math:`\bigcap_{i\in\sigma} B_i` over the
simplices :math:`\sigma` of the dual complex.  Its two lowest terms have elementary
closed forms, given here on their own:

* a vertex: one ball, :math:`\pi r^2` (2D) or :math:`\tfrac43\pi r^3` (3D);
* an edge: a *lens*, two balls at distance :math:`d < r_1 + r_2` cut by their power
  plane (radical plane) at signed distance
  :math:`t_1 = (d^2 + r_1^2 - r_2^2)/(2d)` from the first centre.  In 3D the lens is two
  spherical caps of heights :math:`h_1 = r_1 - t_1`, :math:`h_2 = r_2 - (d - t_1)`, and a
  cap of height :math:`h` on a ball of radius :math:`r` has volume
  :math:`\pi h^2 (3r - h)/3`; in 2D it is two circular segments,
  :math:`r^2 \arccos(t/r) - t\sqrt{r^2 - t^2}` each.

Triangles (three balls) and tetrahedra need the pieces of :mod:`shapelab.measure`
(Gauss–Bonnet on the spheres); :func:`shapelab.measure.measure_from_simplices` evaluates
any single term.
"""

from __future__ import annotations

import math

__all__ = ["ball_measure", "cap_volume", "lens_measure"]


def _positive(x, name: str) -> float:
    x = float(x)
    if not x > 0 or not math.isfinite(x):
        raise ValueError(f"{name} must be a positive finite number, got {x}")
    return x


def _dim(dim) -> int:
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    return int(dim)


def ball_measure(r: float, dim: int = 3) -> float:
    """The area (2D) or volume (3D) of a ball of radius ``r``.

    Parameters
    ----------
    r : float
        The radius, positive.
    dim : {2, 3}
        The dimension.

    Returns
    -------
    float
        :math:`\\pi r^2` or :math:`\\tfrac43 \\pi r^3`.

    See Also
    --------
    lens_measure, shapelab.union_measure

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", Discrete Comput.
       Geom. 13 (1995) 415–440, doi:10.1007/BF02574053.

    Examples
    --------
    >>> round(ball_measure(1.0), 6)
    4.18879
    """
    r, dim = _positive(r, "r"), _dim(dim)
    return math.pi * r * r if dim == 2 else 4.0 / 3.0 * math.pi * r**3


def cap_volume(r, h) -> float:
    """The volume of a spherical cap of height ``h`` on a ball of radius ``r``.

    Parameters
    ----------
    r : float
        The ball's radius, positive.
    h : float
        The cap's height, ``0 <= h <= 2r``.

    Returns
    -------
    float
        :math:`\\pi h^2 (3r - h)/3`.

    See Also
    --------
    lens_measure

    References
    ----------
    .. [1] H. Edelsbrunner and P. Fu, "Measuring space filling diagrams and voids",
       Technical Report UIUC-BI-MB-94-01, Beckman Institute, University of Illinois, 1994.

    Examples
    --------
    >>> round(cap_volume(1.0, 1.0), 6)     # half a unit ball
    2.094395
    """
    r, h = _positive(r, "r"), float(h)
    if not 0 <= h <= 2 * r:
        raise ValueError(f"h must lie in [0, 2r], got h={h}, r={r}")
    return math.pi * h * h * (3 * r - h) / 3


def lens_measure(r1: float, r2: float, d: float, dim: int = 3) -> float:
    """The area (2D) or volume (3D) of the intersection of two balls.

    Parameters
    ----------
    r1, r2 : float
        The radii, positive.
    d : float
        The distance between the centres, ``d >= 0``.
    dim : {2, 3}
        The dimension.

    Returns
    -------
    float
        0 for disjoint or touching balls (:math:`d \\ge r_1 + r_2`), the smaller ball
        when one contains the other (:math:`d \\le |r_1 - r_2|`), else two caps (3D) or
        two circular segments (2D) cut by the power plane.

    See Also
    --------
    ball_measure, cap_volume, shapelab.union_measure

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", Discrete Comput.
       Geom. 13 (1995) 415–440, doi:10.1007/BF02574053.

    Examples
    --------
    >>> round(lens_measure(1.0, 1.0, 1.0), 6)    # two unit balls, centres 1 apart: 5π/12
    1.308997
    >>> lens_measure(1.0, 1.0, 2.0)
    0.0
    """
    r1, r2, dim = _positive(r1, "r1"), _positive(r2, "r2"), _dim(dim)
    d = float(d)
    if not d >= 0 or not math.isfinite(d):
        raise ValueError(f"d must be a finite number >= 0, got {d}")
    if d >= r1 + r2:
        return 0.0
    if d <= abs(r1 - r2):
        return ball_measure(min(r1, r2), dim)
    t1 = (d * d + r1 * r1 - r2 * r2) / (2 * d)
    t2 = d - t1
    if dim == 3:
        return cap_volume(r1, r1 - t1) + cap_volume(r2, r2 - t2)
    seg = lambda r, t: r * r * math.acos(max(-1.0, min(1.0, t / r))) - t * math.sqrt(max(r * r - t * t, 0.0))
    return seg(r1, t1) + seg(r2, t2)
