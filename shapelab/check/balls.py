"""Self-checks for the lessons on power diagrams and the dual complex (01–05).

* :func:`power_distance` — :math:`\\pi(x) = \\lVert x - z \\rVert^2 - r^2` (Notes §23.1);
* :func:`orthogonal_radius` — the squared radius of the circle orthogonal to three
  circles, which is the time τ at which their triangle enters the α-filtration;
* :func:`union_area` — the area of the union of two disks by inclusion–exclusion.
* :func:`dual_edge` — whether the dual complex of two disks has the edge (they cross
  or touch).
* :func:`attached_edge` — whether an edge of the regular triangulation enters with a
  coface (its smallest orthogonal sphere claimed by another ball).

Each runs the student's function on edge cases first, then on seeded random cases,
and compares with the library (:func:`shapelab.power_distance`,
:func:`shapelab.alpha_filtration`, :func:`shapelab.union_measure`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ._runner import CheckResult, allclose, run_check

__all__ = ["power_distance", "orthogonal_radius", "union_area", "dual_edge", "attached_edge"]


def power_distance(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(x, center, radius) -> float``, the power distance
    :math:`\\lVert x - z\\rVert^2 - r^2` of the point x from the ball (z, r).

    Cases: x at the centre (:math:`-r^2`), x on the sphere (0), a ball of radius 0
    (the squared distance), a point outside (the squared tangent length), 3D points,
    then random points in 2D and 3D.

    See Also
    --------
    shapelab.power_distance
        The reference.

    Examples
    --------
    >>> import numpy as np
    >>> mine = lambda x, z, r: float(np.sum((np.asarray(x) - z) ** 2) - r**2)
    >>> power_distance(mine).passed
    ✓ power distance: correct on all 9 cases.
    True
    >>> power_distance(lambda x, z, r: float(np.sum((np.asarray(x) - z) ** 2)), quiet=True).passed
    False
    """
    from ..balls import Balls
    from ..balls import power_distance as lib

    cases = [
        (np.array([1.0, 2.0]), np.array([1.0, 2.0]), 1.5),
        (np.array([4.0, 6.0]), np.array([1.0, 2.0]), 5.0),
        (np.array([3.0, 4.0]), np.array([0.0, 0.0]), 0.0),
        (np.array([0.0, 0.0]), np.array([3.0, 4.0]), 1.0),
        (np.array([1.0, 1.0, 1.0]), np.array([0.0, 0.0, 0.0]), 2.0),
    ]
    rng = np.random.default_rng(20)
    for d in (2, 3, 2, 3):
        cases.append((rng.normal(size=d) * 3, rng.normal(size=d), float(rng.uniform(0, 2))))

    def reference(x, c, r):
        return float(lib(x, Balls(c[None, :], [r]))[0])

    return run_check("power distance", student_fn, cases, reference, allclose(atol=1e-9, rtol=1e-9), quiet=quiet)


def orthogonal_radius(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(centers, radii) -> float``: for three disks (centres (3, 2),
    radii (3,)), the squared radius :math:`R^2` of the circle orthogonal to all three.

    Its centre y is the point with equal power distance to the three disks, and
    :math:`R^2 = \\lVert y - z_i \\rVert^2 - r_i^2` (a circle of radius R about y
    meets circle i at a right angle iff :math:`\\lVert y - z_i\\rVert^2 = R^2 + r_i^2`).
    :math:`R^2` is negative when y lies inside the three disks.  It is the time τ
    at which the triangle enters the α-filtration (Notes §23.1), which is what the
    library's answer is: ``alpha_filtration(Balls(centers, radii)).values(2)[0]``.

    Cases: three points (radius 0: the circumradius squared), equal disks, disks that
    overlap around y (:math:`R^2 < 0`), unequal disks, then random triangles.

    See Also
    --------
    shapelab.power_diagram
        Where the orthogonal circle's centre is a vertex.

    Examples
    --------
    >>> import shapelab as sl
    >>> def mine(centers, radii):
    ...     return float(sl.alpha_filtration(sl.Balls(centers, radii)).values(2)[0])
    >>> orthogonal_radius(mine).passed
    ✓ orthogonal circle (squared radius): correct on all 10 cases.
    True
    >>> orthogonal_radius(lambda centers, radii: 0.0, quiet=True).passed
    False
    """
    from ..balls import Balls
    from ..filtration import alpha_filtration

    cases = [
        (np.array([[0.0, 0.0], [4.0, 0.0], [0.0, 3.0]]), np.zeros(3)),
        (np.array([[0.0, 0.0], [2.0, 0.0], [1.0, np.sqrt(3.0)]]), np.full(3, 0.5)),
        (np.array([[0.0, 0.0], [2.0, 0.0], [1.0, np.sqrt(3.0)]]), np.full(3, 1.5)),
        (np.array([[0.0, 0.0], [5.0, 1.0], [2.0, 4.0]]), np.array([1.0, 2.0, 0.5])),
    ]
    rng = np.random.default_rng(21)
    while len(cases) < 10:
        c = rng.uniform(-3, 3, (3, 2))
        e = np.linalg.norm(c[[1, 2, 0]] - c, axis=1)
        u, v = c[1] - c[0], c[2] - c[0]
        area = 0.5 * abs(u[0] * v[1] - u[1] * v[0])
        if area < 0.5:  # keep triangles well shaped
            continue
        cases.append((c, rng.uniform(0, 0.3, 3) * e.min()))  # small disks: none is hidden

    def reference(centers, radii):
        return float(alpha_filtration(Balls(centers, radii)).values(2)[0])

    return run_check(
        "orthogonal circle (squared radius)", student_fn, cases, reference, allclose(atol=1e-9, rtol=1e-8), quiet=quiet
    )


def union_area(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(c1, r1, c2, r2) -> float``, the area of the union of two
    disks: :math:`\\pi r_1^2 + \\pi r_2^2 - \\operatorname{area}(B_1 \\cap B_2)`.

    Cases: disjoint, tangent from outside, overlapping, one inside the other, identical
    disks, a disk of radius 0, tangent from inside, then random pairs.  The library's answer is
    :func:`shapelab.union_measure`.

    See Also
    --------
    shapelab.union_measure
        The reference.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> def mine(c1, r1, c2, r2):
    ...     return sl.union_measure(sl.Balls([c1, c2], [r1, r2])).area
    >>> union_area(mine).passed
    ✓ area of the union of two disks: correct on all 14 cases.
    True
    >>> union_area(lambda c1, r1, c2, r2: np.pi * (r1**2 + r2**2), quiet=True).passed
    False
    """
    from ..balls import Balls
    from ..measure import union_measure

    p = np.array
    cases = [
        (p([0.0, 0.0]), 1.0, p([5.0, 0.0]), 2.0),
        (p([0.0, 0.0]), 1.0, p([3.0, 0.0]), 2.0),
        (p([0.0, 0.0]), 1.0, p([1.0, 0.0]), 1.0),
        (p([0.0, 0.0]), 3.0, p([0.5, 0.5]), 1.0),
        (p([1.0, 1.0]), 2.0, p([1.0, 1.0]), 2.0),
        (p([0.0, 0.0]), 0.0, p([1.0, 0.0]), 1.0),
        (p([0.0, 0.0]), 2.0, p([0.0, 2.5]), 1.0),
        (p([0.0, 0.0]), 2.0, p([1.0, 0.0]), 1.0),  # touching from inside
    ]
    rng = np.random.default_rng(22)
    for _ in range(6):
        cases.append(
            (rng.uniform(-2, 2, 2), float(rng.uniform(0.2, 2)), rng.uniform(-2, 2, 2), float(rng.uniform(0.2, 2)))
        )

    def reference(c1, r1, c2, r2):
        return float(union_measure(Balls(np.array([c1, c2]), [r1, r2])).area)

    return run_check(
        "area of the union of two disks", student_fn, cases, reference, allclose(atol=1e-9, rtol=1e-9), quiet=quiet
    )


def dual_edge(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(c1, r1, c2, r2) -> bool``: whether the dual complex of two
    disks with centres :math:`c_1 \\ne c_2` has the edge (Notes §23.1, the
    definition of K).

    The two power cells meet along the radical axis, and the closed clipped cells
    :math:`B_i \\cap \\Pi(B_i)` share a point exactly when
    :math:`|r_1 - r_2| \\le \\lVert c_1 - c_2 \\rVert \\le r_1 + r_2`: the circles cross
    or touch.  The library's answer is ``dual_complex(Balls([c1, c2], [r1, r2]))``.

    Cases, edge cases first: circles touching from outside and from inside (an edge:
    the cells share the point of contact), one disk inside the other without touching
    (no edge, although neither disk is hidden), disjoint and crossing disks, the same
    with the centres 5 apart on a 3-4-5 triangle (exact in floating point) and the
    larger disk second, then random pairs kept away from tangency.

    See Also
    --------
    shapelab.dual_complex : The library's answer.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995.

    Examples
    --------
    >>> import numpy as np
    >>> def mine(c1, r1, c2, r2):
    ...     d = np.linalg.norm(np.subtract(c1, c2))
    ...     return bool(abs(r1 - r2) <= d <= r1 + r2)
    >>> dual_edge(mine).passed
    ✓ edge of the dual complex of two disks: correct on all 16 cases.
    True
    >>> # forgetting a disk inside the other is refused
    >>> dual_edge(lambda c1, r1, c2, r2: bool(np.linalg.norm(np.subtract(c1, c2)) <= r1 + r2), quiet=True).passed
    False
    """
    from ..balls import Balls
    from ..filtration import dual_complex

    p = np.array
    cases = [
        (p([0.0, 0.0]), 1.0, p([2.0, 0.0]), 1.0),  # touching from outside
        (p([0.0, 0.0]), 1.0, p([0.5, 0.0]), 0.5),  # touching from inside
        (p([0.0, 0.0]), 3.0, p([1.0, 0.0]), 0.5),  # inside, not touching
        (p([0.0, 0.0]), 1.0, p([3.0, 0.0]), 1.0),  # disjoint
        (p([0.0, 0.0]), 1.0, p([1.5, 0.0]), 1.0),  # crossing
        (p([0.0, 0.0]), 2.0, p([3.0, 4.0]), 3.0),  # touching from outside, off the axes
        (p([3.0, 4.0]), 2.0, p([0.0, 0.0]), 7.0),  # touching from inside, larger disk second
        (p([3.0, 4.0]), 1.5, p([0.0, 0.0]), 7.0),  # inside, larger disk second
        (p([1.0, 1.0]), 0.5, p([1.0, 2.2]), 0.9),  # crossing
    ]
    rng = np.random.default_rng(24)
    while len(cases) < 16:
        c1, c2 = rng.uniform(-2, 2, 2), rng.uniform(-2, 2, 2)
        r1, r2 = (float(v) for v in rng.uniform(0.2, 2.0, 2))
        d = float(np.linalg.norm(c2 - c1))
        if min(abs(d - r1 - r2), abs(d - abs(r1 - r2))) > 1e-3:  # no near-tangency
            cases.append((c1, r1, c2, r2))

    def reference(c1, r1, c2, r2):
        return dual_complex(Balls(np.array([c1, c2]), [r1, r2])).dimension >= 1

    def compare(expected, received):
        return isinstance(received, (bool, np.bool_)) and bool(received) == expected

    return run_check("edge of the dual complex of two disks", student_fn, cases, reference, compare, quiet=quiet)


def attached_edge(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(centers, radii, edge) -> bool``: whether the edge ``(i, j)``
    of the regular triangulation of the balls is *attached* (Notes §23.1; lesson 04).

    The edge's smallest orthogonal sphere has its centre c on the line through
    :math:`z_i, z_j`, with :math:`\\pi_i(c) = \\pi_j(c) = \\rho`; the edge is attached
    iff some other ball has :math:`\\pi_v(c) < \\rho`.  The library's answer is
    ``alpha_filtration(Balls(centers, radii)).attached(1)`` at the edge's row.

    Cases: the long edge of an obtuse triangle of equal disks (attached) and a short
    one (not), a tangent pair beside a third ball, a third ball whose centre lies
    outside the orthogonal circle but whose disk claims its centre (attached: the
    test is on the power, not on the centre), unequal radii where the diametral
    circle and the orthogonal circle disagree, a hidden ball, the hypotenuse of a
    right triangle (a tie, :math:`\\pi_v(c) = \\rho`: unattached, so ``<=`` fails),
    unequal radii where the midpoint of the edge and ``c`` disagree, a claiming
    ball that is not the centre nearest ``c``, the obtuse triangle lifted into 3D
    with a fourth ball, then random edges of random balls in 2D and 3D, one
    attached and one unattached edge in each dimension (none of them near a tie).

    See Also
    --------
    shapelab.filtration.Filtration.attached
        The reference.

    Examples
    --------
    >>> import shapelab as sl
    >>> def mine(centers, radii, edge):
    ...     F = sl.alpha_filtration(sl.Balls(centers, radii))
    ...     row = [tuple(s) for s in F.simplices(1).tolist()].index(tuple(sorted(edge)))
    ...     return bool(F.attached(1)[row])
    >>> attached_edge(mine).passed
    ✓ attached edge: correct on all 16 cases.
    True
    >>> attached_edge(lambda centers, radii, edge: False, quiet=True).passed
    False
    """
    from ..balls import Balls
    from ..filtration import alpha_filtration

    p = np.array
    cases = [
        (p([[0.0, 0.0], [4.0, 0.0], [2.0, 1.0]]), p([1.0, 1.0, 1.0]), (0, 1)),
        (p([[0.0, 0.0], [4.0, 0.0], [2.0, 1.0]]), p([1.0, 1.0, 1.0]), (0, 2)),
        (p([[0.0, 0.0], [2.0, 0.0], [1.0, 5.0]]), p([1.0, 1.0, 0.5]), (0, 1)),
        (p([[0.0, 0.0], [4.0, 0.0], [2.0, 2.5]]), p([1.0, 1.0, 2.0]), (0, 1)),
        (p([[0.0, 0.0], [4.0, 0.0], [1.6, 1.7]]), p([2.0, 0.5, 0.0]), (0, 1)),
        (p([[0.0, 0.0], [1.0, 0.0], [5.0, 1.0], [0.2, 0.1], [2.0, 4.0]]), p([3.0, 0.5, 1.0, 0.1, 1.0]), (0, 4)),
        (p([[0.0, 0.0], [4.0, 0.0], [2.0, 2.0]]), p([1.0, 1.0, 1.0]), (0, 1)),  # tie: unattached
        (p([[0.0, 0.0], [4.0, 0.0], [2.75, 1.25]]), p([2.0, 0.5, 0.0]), (0, 1)),  # not at the midpoint
        (p([[0.0, 0.0], [4.0, 0.0], [2.0, -2.25], [2.0, 3.0]]), p([1.0, 1.0, 0.0, 2.5]), (0, 1)),  # far claim
        (p([[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [2.0, 1.0, 0.0], [2.0, 0.0, 3.0]]), p([1.0, 1.0, 1.0, 1.0]), (0, 1)),
    ]
    rng = np.random.default_rng(23)
    for d, want in ((2, True), (2, False), (3, True), (3, False), (2, True), (3, False)):
        while True:
            c, r = rng.uniform(0, 4, (7, d)), rng.uniform(0.2, 1.2, 7)
            F = alpha_filtration(Balls(c, r))
            rows = np.flatnonzero(F.attached(1) == want)
            if rows.size == 0:
                continue
            e = tuple(int(v) for v in F.simplices(1)[rows[rng.integers(rows.size)]])
            ce, re = _edge_orthosphere(c, r, e)
            gap = np.delete(np.sum((c - ce) ** 2, axis=1) - r**2, list(e)) - re
            if np.min(np.abs(gap)) > 1e-3 * (1.0 + abs(re)):  # no near-tie
                cases.append((c, r, e))
                break

    def reference(centers, radii, edge):
        F = alpha_filtration(Balls(centers, radii))
        row = [tuple(s) for s in F.simplices(1).tolist()].index(tuple(sorted(edge)))
        return bool(F.attached(1)[row])

    def compare(expected, received):
        return isinstance(received, (bool, np.bool_)) and bool(received) == expected

    return run_check("attached edge", student_fn, cases, reference, compare, quiet=quiet)


def _edge_orthosphere(c, r, e):
    """Centre and power of the smallest orthogonal sphere of the edge ``e`` (to keep
    the random cases away from ties)."""
    z0, z1 = c[e[0]], c[e[1]]
    a = z1 - z0
    t = (a @ a - r[e[1]] ** 2 + r[e[0]] ** 2) / (2 * (a @ a))
    x = z0 + t * a
    return x, float(np.sum((x - z0) ** 2) - r[e[0]] ** 2)
