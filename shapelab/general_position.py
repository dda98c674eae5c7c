r"""General position of balls, decided exactly (Notes §23.1; Edelsbrunner and Mücke 1990).

Balls in :math:`\mathbb{R}^d` are in *general position* for the regular triangulation
when no :math:`k + 2` of their centres lie on a common :math:`k`-flat
(:math:`k < d`) and no :math:`d + 2` of them have a common orthogonal sphere: by the
lifting map :math:`z \mapsto (z, \lVert z\rVert^2 - r^2)`, no :math:`d + 2` lifted
points on one hyperplane.  With equal radii the second condition reads: no four
cocircular centres in the plane, no five cospherical ones in space.  Then the regular
triangulation is unique.  A tie makes it ambiguous: the four corners of a square admit
two triangulations, and the library picks one by Simulation of Simplicity
(:mod:`shapelab._engine.predicates`).

:func:`cospherical_subsets` lists the ties of the second kind by brute force, with the
:math:`(d+2) \times (d+2)` determinant of rows :math:`(1, z_j, \lVert z_j\rVert^2 - r_j^2)`
evaluated in rational arithmetic on the input's binary values.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

import numpy as np

from .balls import Balls

__all__ = ["cospherical_subsets"]


def _det(M) -> Fraction:
    M = [list(r) for r in M]
    n, sign, out = len(M), 1, Fraction(1)
    for c in range(n):
        p = next((r for r in range(c, n) if M[r][c] != 0), None)
        if p is None:
            return Fraction(0)
        if p != c:
            M[c], M[p] = M[p], M[c]
            sign = -sign
        out *= M[c][c]
        for r in range(c + 1, n):
            f = M[r][c] / M[c][c]
            if f:
                M[r] = [a - f * e for a, e in zip(M[r], M[c])]
    return sign * out


def cospherical_subsets(balls: Balls) -> np.ndarray:
    """The sets of :math:`d + 2` balls with a common orthogonal sphere, exactly.

    Parameters
    ----------
    balls : Balls
        The balls (a dozen or two: the search is over all :math:`\\binom{n}{d+2}` sets).

    Returns
    -------
    ndarray of int, shape (m, d + 2)
        The sets, sorted, whose lifted centres lie on one hyperplane (with equal radii:
        cocircular or cospherical centres, or :math:`d + 1` of them on a common
        :math:`(d-1)`-flat with any further one).

    See Also
    --------
    shapelab.regular_triangulation : breaks these ties by Simulation of Simplicity.

    References
    ----------
    .. [1] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity: a technique to
       cope with degenerate cases in geometric algorithms", ACM Trans. Graphics 9
       (1990) 66–104, doi:10.1145/77635.77639.

    Examples
    --------
    >>> import shapelab as sl
    >>> square = sl.Balls([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], [0.6] * 4)
    >>> cospherical_subsets(square)
    array([[0, 1, 2, 3]])
    """
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be Balls, got {type(balls).__name__}")
    d = balls.dim
    rows = []
    for z, r in zip(balls.centers, balls.radii):
        zf = [Fraction(float(v)) for v in z]
        rows.append([Fraction(1), *zf, sum(v * v for v in zf) - Fraction(float(r)) ** 2])
    out = [s for s in combinations(range(len(rows)), d + 2) if _det([rows[i] for i in s]) == 0]
    return np.array(out, dtype=np.int64).reshape(-1, d + 2)
