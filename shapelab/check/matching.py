"""Self-checks for the exercises on the Hausdorff distance and critical points
(notes §23.2; lessons 13–14).

Each check runs *your* function on edge cases first (single points, identical
sets, duplicates, one dimension, a set inside the other), then on random sets, and
compares with the library (:mod:`shapelab.hausdorff`, :mod:`shapelab.critical`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ._runner import CheckResult, allclose, run_check

__all__ = ["hausdorff", "directed_hausdorff", "critical_points"]


def _pair_cases():
    rng = np.random.default_rng(2320)
    cases = [
        (np.array([[0.0, 0.0]]), np.array([[3.0, 4.0]])),  # one point each: 5
        (np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([[0.0, 0.0], [1.0, 0.0]])),  # identical: 0
        (np.array([[0.0], [1.0]]), np.array([[0.0], [3.0]])),  # 1D
        (np.array([[0.0, 0.0], [1.0, 1.0]]), np.array([[0.0, 0.0], [1.0, 1.0], [5.0, 5.0]])),  # A inside B
        (np.array([[1.0, 1.0]] * 3 + [[2.0, 0.0]]), np.array([[0.0, 0.0], [0.0, 0.0], [2.0, 1.0]])),  # duplicates
    ]
    for n, m, d in [(5, 7, 2), (12, 4, 3), (30, 25, 2)]:
        cases.append((rng.normal(size=(n, d)), rng.normal(size=(m, d)) + rng.normal(size=d)))
    return cases


def _describe(case):
    A, B = case
    return (
        f"A with {len(A)} point(s) in {A.shape[1]}D, B with {len(B)}; A = {A[:3].tolist()}..., B = {B[:3].tolist()}..."
    )


def directed_hausdorff(fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``fn(A, B) -> float``, the directed distance h(A, B) = max_a min_b |a − b|.

    Includes a set A inside B, where h(A, B) = 0 but h(B, A) > 0: computing the
    symmetric distance (or swapping the roles) fails there.

    See Also
    --------
    shapelab.directed_hausdorff
        The reference.

    Examples
    --------
    >>> import numpy as np
    >>> def mine(A, B):
    ...     D = np.linalg.norm(np.asarray(A)[:, None] - np.asarray(B)[None], axis=-1)
    ...     return float(D.min(axis=1).max())
    >>> directed_hausdorff(mine).passed
    ✓ directed Hausdorff distance: correct on all 8 cases.
    True
    >>> # the other direction, min over A of max over B, is refused
    >>> directed_hausdorff(lambda A, B: float(np.linalg.norm(np.asarray(A)[:, None] - np.asarray(B)[None], axis=-1).max(axis=1).min()), quiet=True).passed
    False
    """
    from ..hausdorff import directed_hausdorff as ref

    return run_check(
        "directed Hausdorff distance",
        fn,
        _pair_cases(),
        lambda A, B: ref(A, B).distance,
        allclose(1e-9, 1e-9),
        describe=_describe,
        quiet=quiet,
    )


def hausdorff(fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``fn(A, B) -> float``, the Hausdorff distance H(A, B) of the notes (§23.2).

    See Also
    --------
    shapelab.hausdorff
        The reference.

    Examples
    --------
    >>> import numpy as np
    >>> def h(A, B):
    ...     D = np.linalg.norm(np.asarray(A)[:, None] - np.asarray(B)[None], axis=-1)
    ...     return float(D.min(axis=1).max())
    >>> hausdorff(lambda A, B: max(h(A, B), h(B, A))).passed
    ✓ Hausdorff distance: correct on all 8 cases.
    True
    >>> # one direction only is refused
    >>> hausdorff(h, quiet=True).passed
    False
    """
    from ..hausdorff import hausdorff as ref

    return run_check(
        "Hausdorff distance", fn, _pair_cases(), ref, allclose(1e-9, 1e-9), describe=_describe, quiet=quiet
    )


def _curve_cases():
    square = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.0]])
    # a thin triangle: the far vertex is a maximum although its neighbour is farther
    # from S along the polyline's vertices; compare one-sided slopes, not neighbours
    spike = np.array([[1.0, 0.0], [-1.1, 0.05], [-1.0, -0.6], [1.0, 0.0]])
    t = np.arange(24) * (2 * np.pi / 24)
    ellipse = np.vstack([np.c_[2 * np.cos(t), np.sin(t)], [[2.0, 0.0]]])
    rng = np.random.default_rng(2321)
    a = np.sort(rng.uniform(0, 2 * np.pi, 15))
    r = 1 + 0.4 * rng.uniform(size=15)
    blob = np.c_[r * np.cos(a), r * np.sin(a)]
    blob = np.vstack([blob, blob[:1]])
    return [
        (square, np.array([1.0, 1.0])),  # centre: 4 maxima at corners, 4 minima at midpoints
        (square, np.array([1.0, 0.5])),
        (spike, np.array([0.0, 0.0])),
        (ellipse, np.array([0.3, 0.2])),
        (blob, np.array([0.1, -0.1])),
        (blob, np.array([3.0, 0.0])),  # S outside the curve
        # S on the line of the bottom edge: the feet of the perpendiculars to the right
        # and left edges fall exactly on the vertices (2, 0) and (0, 0), one slope there
        # is exactly 0; (2, 0) is a minimum, counted once, and (0, 0) is no extremum
        # (a foot counted on the closed edge [0, 1], or a slope test with <= / >=, fails)
        (square, np.array([3.0, 0.0])),
    ]


def critical_points(fn: Callable[..., Any], *, kind: str = "max", quiet: bool = False) -> CheckResult:
    """Check ``fn(polyline, S) -> sorted values of F at the maxima`` (or minima).

    Parameters
    ----------
    fn : callable
        ``fn(polyline, S)`` with ``polyline`` an (n, 2) closed polyline (first
        point repeated at the end) and ``S`` a point; returns the values
        ``|x − S|`` at the local maxima (``kind="max"``) or minima
        (``kind="min"``) of F along the polyline, sorted increasingly.
    kind : {"max", "min"}
        Minima include the feet of perpendiculars inside segments.

    See Also
    --------
    shapelab.critical_points
        The reference.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> def maxima(curve, S):
    ...     cp = sl.critical_points(curve, S)
    ...     return np.sort(cp.values[cp.kinds == "max"])
    >>> critical_points(maxima).passed
    ✓ maxima of F on a polyline: correct on all 7 cases.
    True
    >>> critical_points(lambda curve, S: np.array([]), quiet=True).passed
    False
    """
    from ..critical import critical_points as ref

    if kind not in ("max", "min"):
        raise ValueError(f"kind must be 'max' or 'min', got {kind!r}")

    def reference(P, S):
        res = ref(P, S)
        return np.sort(res.values[res.kinds == kind])

    def describe(case):
        P, S = case
        return f"polyline with {len(P) - 1} vertices {P[:4].round(3).tolist()}..., S = {S.tolist()}"

    def compare(expected, received):
        r = np.sort(np.asarray(received, dtype=float).ravel())
        return r.shape == expected.shape and bool(np.allclose(r, expected, atol=1e-9, rtol=1e-9))

    name = "maxima of F on a polyline" if kind == "max" else "minima of F on a polyline"
    return run_check(name, fn, _curve_cases(), reference, compare, describe=describe, quiet=quiet)
