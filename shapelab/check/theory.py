"""Self-checks for the theory sections (issue 34): Morse theory of the power distance
(lesson 13), general position (lesson 06), the short formula's closed forms (lesson 05),
diagram distances as assignments (lesson 19) and confidence intervals (lesson 20).

Each check computes its reference itself and says how a wrong answer is off, never
what it should be.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._runner import CheckResult, value

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence

    from numpy.typing import ArrayLike

    from ..balls import Balls

__all__ = ["morse_maximum", "tie_break", "chain_volume", "wasserstein_by_hand", "wilson"]


def _done(name: str, passed: bool, msg: str) -> CheckResult:
    print(msg)
    return CheckResult(name, passed, 1, msg)


def morse_maximum(position: ArrayLike, critical_value: float, balls: Balls) -> CheckResult:
    """Lesson 13: the maximum of the power distance :math:`f = \\min_i \\pi_i` of three
    disks whose orthocentre lies inside their triangle: its position (the orthocentre)
    and its value (the triangle's entry time).

    The reference is :func:`shapelab.morse.power_critical_points`, its one critical
    point of index 2.

    See Also
    --------
    shapelab.morse.power_critical_points

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> # an equilateral triangle of equal disks: the orthocentre is the centroid and the
    >>> # value the squared circumradius 4/3 less r^2 = 1/4
    >>> disks = sl.Balls([[0.0, 0.0], [2.0, 0.0], [1.0, np.sqrt(3.0)]], 0.5)
    >>> ok = morse_maximum([1.0, 1.0 / np.sqrt(3.0)], 4.0 / 3.0 - 0.25, disks)
    ✓ the position of the maximum (the orthocentre): correct.
    ✓ its value (the triangle's entry time): correct.
    >>> bad = morse_maximum([1.0, 1.0 / np.sqrt(3.0)], 4.0 / 3.0, disks)
    ✓ the position of the maximum (the orthocentre): correct.
    ✗ its value (the triangle's entry time): not quite: yours is too large.
    """
    from ..morse import power_critical_points

    cp = power_critical_points(balls)
    top = cp.index == balls.dim
    a = value(
        "the position of the maximum (the orthocentre)",
        position,
        cp.positions[top][0],
        rtol=1e-6,
        atol=1e-6,
        quiet=True,
    )
    b = value(
        "its value (the triangle's entry time)",
        critical_value,
        float(cp.values[top][0]),
        rtol=1e-6,
        atol=1e-6,
        quiet=True,
    )
    return _done("the maximum of the power distance", a.passed and b.passed, a.message + "\n" + b.message)


def tie_break(triangles: Iterable[Sequence[int]], balls: Balls) -> CheckResult:
    """Lesson 06: the triangles the library's regular triangulation picks for cocircular
    centres (a tie broken by Simulation of Simplicity), compared as a set of sets with
    :func:`shapelab.regular_triangulation`.

    See Also
    --------
    shapelab.regular_triangulation

    Examples
    --------
    >>> import shapelab as sl
    >>> square = sl.Balls([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], 0.3)
    >>> bad = tie_break([[0, 1, 2]], square)
    ✗ the triangles Simulation of Simplicity picks: not quite: a triangulation of these points has 2 triangles.
    """
    from ..power import regular_triangulation

    name = "the triangles Simulation of Simplicity picks"
    expected = {frozenset(int(v) for v in t) for t in regular_triangulation(balls).tolist()}
    try:
        got = [frozenset(int(v) for v in t) for t in triangles]
    except (TypeError, ValueError):
        return _done(name, False, f"✗ {name}: expected a list of triangles, each three ball indices.")
    if any(len(t) != 3 for t in got):
        return _done(name, False, f"✗ {name}: every triangle needs three different ball indices.")
    if len(set(got)) != len(got):
        return _done(name, False, f"✗ {name}: a triangle is listed twice.")
    if len(got) != len(expected):
        return _done(
            name, False, f"✗ {name}: not quite: a triangulation of these points has {len(expected)} triangles."
        )
    wrong = len(set(got) - expected)
    if wrong:
        return _done(name, False, f"✗ {name}: not quite: {wrong} of your triangles are not the library's.")
    return _done(name, True, f"✓ {name}: correct.")


def chain_volume(volume: float, balls: Balls) -> CheckResult:
    """Lesson 05: the volume of the union of a chain of balls, from the closed forms of
    the short formula's terms; the reference is :func:`shapelab.union_measure`.

    See Also
    --------
    shapelab.union_measure, shapelab.intersections.lens_measure

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> # two unit balls 1 apart share a lens of volume pi (4 + 1)(2 - 1)^2 / 12
    >>> pair = sl.Balls([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], 1.0)
    >>> ok = chain_volume(2 * 4 * np.pi / 3 - 5 * np.pi / 12, pair)
    ✓ the volume of the union of the chain: correct.
    >>> bad = chain_volume(2 * 4 * np.pi / 3, pair)
    ✗ the volume of the union of the chain: not quite: yours is too large.
    """
    from ..measure import union_measure

    return value("the volume of the union of the chain", volume, union_measure(balls).volume, rtol=1e-6, atol=1e-9)


def wasserstein_by_hand(w1: float, D1: ArrayLike, D2: ArrayLike) -> CheckResult:
    """Lesson 19: the 1-Wasserstein distance between two small diagrams, to 1e-6;
    the reference is :func:`shapelab.wasserstein_distance` with ``p=1``.

    See Also
    --------
    shapelab.wasserstein_distance, shapelab.assignment.assignment_distance

    Examples
    --------
    >>> # matching (0, 1) with (0, 2) costs 1; sending both to the diagonal costs 1/2 + 1
    >>> ok = wasserstein_by_hand(1.0, [[0.0, 1.0]], [[0.0, 2.0]])
    ✓ the 1-Wasserstein distance: correct.
    >>> bad = wasserstein_by_hand(1.5, [[0.0, 1.0]], [[0.0, 2.0]])
    ✗ the 1-Wasserstein distance: not quite: yours is too large.
    """
    from ..diagrams import wasserstein_distance

    return value("the 1-Wasserstein distance", w1, wasserstein_distance(D1, D2, p=1), rtol=0.0, atol=1e-6)


def wilson(interval: Sequence[float], k: int, n: int, confidence: float = 0.95) -> CheckResult:
    """Lesson 20: the Wilson score interval for ``k`` successes in ``n`` trials, both
    ends to 0.001; the reference is :func:`shapelab.intervals.wilson_interval`.

    See Also
    --------
    shapelab.intervals.wilson_interval

    Examples
    --------
    >>> import numpy as np
    >>> from shapelab.intervals import wilson_interval
    >>> ok = wilson(wilson_interval(8, 10), 8, 10)
    ✓ the 95 % Wilson interval: correct.
    >>> # the Wald interval p +- 1.96 sqrt(p (1 - p) / n) is refused
    >>> p = 0.8
    >>> bad = wilson([p - 1.96 * np.sqrt(p * (1 - p) / 10), p + 1.96 * np.sqrt(p * (1 - p) / 10)], 8, 10)
    ✗ the 95 % Wilson interval: not quite: 2 of 2 entries differ, the first at index 0.
    """
    from ..intervals import wilson_interval

    return value("the 95 % Wilson interval", interval, np.array(wilson_interval(k, n, confidence)), rtol=0.0, atol=1e-3)
