"""The Hausdorff distance between point sets, exact and fast (notes §23.2).

The notes define, for two finite point sets R and G,

.. math::

    H(R, G) = \\max\\Big\\{\\max_{g\\in G}\\min_{r\\in R} d(g, r),\\;
                          \\max_{r\\in R}\\min_{g\\in G} d(r, g)\\Big\\},

the larger of the two *directed* distances
:math:`h(A, B) = \\max_{a\\in A}\\min_{b\\in B} |a - b|`.  (The notes write
``d(g, r)`` in one term and ``d(r, g)`` in the other; since ``d`` is symmetric
this is only cosmetic.)

Public functions
----------------
:func:`directed_hausdorff`
    h(A, B) with a witness pair ``(i, j)``: ``A[i]`` is a point of A farthest
    from B and ``B[j]`` is its nearest neighbour in B.
:func:`hausdorff`
    H(A, B) as a float.
:func:`hausdorff_kdtree`, :func:`hausdorff_early_break`, :func:`timings`
    the classical algorithms, for comparison (lesson 14).

Matching under translation, :func:`shapelab.hausdorff_under_translation`, is in
:mod:`shapelab.matching`.  (``shapelab.hausdorff`` is the function; the package keeps it
so after this module is imported.  The module's old name ``shapelab.distance`` still
imports it.)

The algorithm and the seam
--------------------------
``method="plain"`` runs the notes' definition as written, in this module: for each
``a``, the squared distances to every ``b`` (coordinates summed in order), the nearest
``b``; keep the farthest ``a``; for :math:`H`, the larger of both directions.
:math:`O(nm)` distances.  The other values of ``method`` (``"auto"``, the default) call
the engine's fast kernels (:mod:`shapelab._engine.hausdorff`: a coarse-to-fine grid, a
batched early break, k-d trees) through one seam; they return the same distance bit for
bit (every distance they report is recomputed by the same direct formula), usually
with the same witness (among exact ties another may be chosen).

"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, NamedTuple

import numpy as np
import numpy.typing as npt

from ._engine import hausdorff as _engine
from ._toolkit import tolerances as tol
from ._toolkit.geometry import kdtree
from ._toolkit.validate import as_point_pair, as_positive_int

__all__ = [
    "DirectedHausdorff",
    "directed_hausdorff",
    "directed_plain",
    "METHODS",
    "hausdorff",
    "hausdorff_pair",
    "hausdorff_kdtree",
    "hausdorff_early_break",
    "Timings",
    "timings",
]

#: the values of ``method``: "plain" is this module's loop, the others the engine's
METHODS = ("plain",) + _engine.METHODS
Method = Literal["auto", "brute", "pruned", "grid", "plain"]


class DirectedHausdorff(NamedTuple):
    """The directed Hausdorff distance h(A, B) with its witness pair.

    Attributes
    ----------
    distance : float
        ``max_a min_b |a - b|``.
    i : int
        Index of a point of A realising the maximum.
    j : int
        Index of the nearest point of B to ``A[i]``; ``|A[i] - B[j]| == distance``.

    See Also
    --------
    directed_hausdorff
        Computes it.
    """

    distance: float
    i: int
    j: int


def _check_method(method: str) -> str:
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    return method


def directed_plain(A: np.ndarray, B: np.ndarray) -> tuple[float, int, int]:
    """h(A, B) squared, with its witness ``(i, j)``, by the notes' definition read directly.

    For each point ``a`` of A its nearest point of B (the smallest squared distance,
    coordinates summed in order; the first among ties), and the farthest such ``a``
    (the first among ties): :math:`\\max_{a} \\min_{b} |a - b|^2`.  ``n m`` distances.

    See Also
    --------
    directed_hausdorff
        Calls it with ``method="plain"``; the default runs the engine's fast kernels.

    References
    ----------
    .. [1] D. P. Huttenlocher, G. A. Klanderman and W. J. Rucklidge, "Comparing images
           using the Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           15(9):850-863, 1993. doi:10.1109/34.232073

    Examples
    --------
    >>> import numpy as np
    >>> directed_plain(np.array([[0.0, 0.0], [3.0, 0.0]]), np.array([[0.0, 1.0]]))
    (10.0, 1, 0)
    """
    best_d2, best_i, best_j = -1.0, -1, -1
    for i, a in enumerate(A):
        diff = B - a
        d2 = diff[:, 0] * diff[:, 0]  # |a - b|^2 for every b of B
        for k in range(1, A.shape[1]):
            d2 = d2 + diff[:, k] * diff[:, k]
        j = int(np.argmin(d2))  # the nearest point of B to a
        if d2[j] > best_d2:  # a is farther from B than every point of A before it
            best_d2, best_i, best_j = float(d2[j]), i, j
    return best_d2, best_i, best_j


# --------------------------------------------------------------------------- #
# Public API                                                                   #
# --------------------------------------------------------------------------- #
def directed_hausdorff(A: npt.ArrayLike, B: npt.ArrayLike, *, method: Method = "auto") -> DirectedHausdorff:
    """The directed Hausdorff distance h(A, B) and a witness pair (notes §23.2).

    .. math:: h(A, B) = \\max_{a \\in A} \\min_{b \\in B} |a - b|

    One of the two terms of the notes' H(R, G).  It is not symmetric:
    ``h(A, B) = 0`` whenever A is a subset of B.

    Parameters
    ----------
    A, B : array_like, shape (n, d) and (m, d)
        Two finite point sets of the same dimension d >= 1.  Duplicates are
        allowed.
    method : {"auto", "brute", "pruned", "grid", "plain"}
        The seam.  ``"plain"``: the notes' definition as written
        (:func:`directed_plain`, ``n m`` distances).  The others run the engine
        (:mod:`shapelab._engine.hausdorff`): ``"auto"`` (default) uses brute force
        for small problems (n * m <= 2**21) and otherwise a coarse-to-fine grid,
        which hands over to a batched early break and k-d trees when the sets
        overlap; ``"grid"`` is ``"auto"`` without the brute-force shortcut,
        ``"pruned"`` skips the grid.  All give the same distance, bit for bit.

    Returns
    -------
    DirectedHausdorff
        ``(distance, i, j)``: ``distance == |A[i] - B[j]|`` and ``B[j]`` is a
        nearest point of B to ``A[i]``.  Unpacks like scipy's result.

    Raises
    ------
    ValueError
        If A or B is empty, not 2-D, not finite, or their dimensions differ.

    See Also
    --------
    hausdorff
        The symmetric distance, the larger of both directions.
    scipy.spatial.distance.directed_hausdorff
        SciPy's early-break algorithm.

    Notes
    -----
    Exact: equal to ``max_i min_j sqrt(sum((A[i] - B[j])**2))`` computed by brute
    force (coordinates summed in order).  On 10⁶ × 10⁶ points in 3D,
    :func:`hausdorff` is faster than the faster of
    :func:`scipy.spatial.distance.directed_hausdorff` and a two-way
    :class:`scipy.spatial.cKDTree` query, whether the sets overlap or are far
    apart (``benchmarks/cases/matching.py``); on small sets the classical
    algorithm suited to the regime can be a little faster.

    References
    ----------
    .. [1] D. P. Huttenlocher, G. A. Klanderman and W. J. Rucklidge, "Comparing images
           using the Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           15(9):850-863, 1993. doi:10.1109/34.232073
    .. [2] A. A. Taha and A. Hanbury, "An efficient algorithm for calculating the exact
           Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           37(11):2153-2163, 2015. doi:10.1109/TPAMI.2015.2408351

    Examples
    --------
    >>> directed_hausdorff([[0.0, 0.0], [3.0, 0.0]], [[0.0, 1.0]])
    DirectedHausdorff(distance=3.1622776601683795, i=1, j=0)
    """
    method = _check_method(method)
    A, B = as_point_pair(A, B)
    if method == "plain":
        d2, i, j = directed_plain(A, B)
    else:  # the seam: the engine's fast kernels, the same distance
        d2, i, j, _ = _engine.directed(A, B, method)
    return DirectedHausdorff(float(np.sqrt(d2)), i, j)


def hausdorff(A: npt.ArrayLike, B: npt.ArrayLike, *, method: Method = "auto") -> float:
    """The Hausdorff distance H(A, B) of the notes (§23.2).

    .. math:: H(A, B) = \\max\\{h(A, B),\\, h(B, A)\\}

    Symmetric, zero exactly when the two sets (as sets) are equal, and a metric
    on finite sets.  The second directed distance is computed knowing the first
    as a lower bound, which prunes most of it.

    Parameters
    ----------
    A, B : array_like, shape (n, d) and (m, d)
        Two finite point sets of the same dimension.
    method : {"auto", "brute", "pruned", "grid"}
        See :func:`directed_hausdorff`.

    Returns
    -------
    float
        Equal bit for bit to brute force.

    See Also
    --------
    directed_hausdorff
        One direction, with its witness.
    hausdorff_under_translation
        Minimised over translations.

    References
    ----------
    .. [1] D. P. Huttenlocher, G. A. Klanderman and W. J. Rucklidge, "Comparing images
           using the Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           15(9):850-863, 1993. doi:10.1109/34.232073

    Examples
    --------
    >>> hausdorff([[0.0], [1.0]], [[0.0], [3.0]])
    2.0
    >>> hausdorff([[0.0], [1.0]], [[0.0], [3.0]], method="plain")  # the definition, read directly
    2.0
    """
    method = _check_method(method)
    A, B = as_point_pair(A, B)
    if method == "plain":
        return float(np.sqrt(max(directed_plain(A, B)[0], directed_plain(B, A)[0])))
    # the seam: h(B, A) is computed knowing h(A, B) as a lower bound, which prunes it
    d2, _, _, problem = _engine.directed(A, B, method)
    d2, _, _, _ = _engine.directed(A, B, method, swap=True, floor2=d2, problem=problem)
    return float(np.sqrt(d2))


def hausdorff_pair(A, B, *, method: Method = "auto") -> tuple[DirectedHausdorff, DirectedHausdorff]:
    """Both directed distances ``(h(A, B), h(B, A))`` with their witnesses.

    Used by :func:`shapelab.plot.matching.hausdorff` to draw the two witness
    segments; slower than :func:`hausdorff`, which prunes the second direction
    with the first.

    See Also
    --------
    hausdorff
        The larger of the two.
    directed_hausdorff
        One direction.

    References
    ----------
    .. [1] D. P. Huttenlocher, G. A. Klanderman and W. J. Rucklidge, "Comparing images
           using the Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           15(9):850-863, 1993. doi:10.1109/34.232073
    """
    method = _check_method(method)
    A, B = as_point_pair(A, B)
    if method == "plain":
        ab, ba = directed_plain(A, B), directed_plain(B, A)
    else:
        *ab, problem = _engine.directed(A, B, method)
        *ba, _ = _engine.directed(A, B, method, swap=True, problem=problem)
    return (
        DirectedHausdorff(float(np.sqrt(ab[0])), ab[1], ab[2]),
        DirectedHausdorff(float(np.sqrt(ba[0])), ba[1], ba[2]),
    )


# --------------------------------------------------------------------------- #
# Matching under translation                                                   #
# --------------------------------------------------------------------------- #


def hausdorff_kdtree(A, B) -> float:
    """H(A, B) by two k-d tree queries (scipy ``cKDTree``, every nearest neighbour).

    The reference "k-d tree" algorithm of the benchmarks: fast when the sets
    overlap, slow when they are far apart.

    See Also
    --------
    hausdorff
        The library's default.
    hausdorff_early_break
        SciPy's early break.

    References
    ----------
    .. [1] D. P. Huttenlocher, G. A. Klanderman and W. J. Rucklidge, "Comparing images
           using the Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           15(9):850-863, 1993. doi:10.1109/34.232073
    """
    A, B = as_point_pair(A, B)
    hab = kdtree(B).query(A, k=1, workers=-1)[0].max()
    hba = kdtree(A).query(B, k=1, workers=-1)[0].max()
    return float(max(hab, hba))


def hausdorff_early_break(A, B, seed: int = 0) -> float:
    """H(A, B) by scipy's early-break algorithm (Taha & Hanbury), both directions.

    Fast when the sets are far apart, slow when they overlap.

    See Also
    --------
    hausdorff
        The library's default.
    hausdorff_kdtree
        Two k-d tree queries.

    References
    ----------
    .. [1] A. A. Taha and A. Hanbury, "An efficient algorithm for calculating the exact
           Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           37(11):2153-2163, 2015. doi:10.1109/TPAMI.2015.2408351
    """
    from scipy.spatial.distance import directed_hausdorff as _scipy_dh

    A, B = as_point_pair(A, B)
    return float(max(_scipy_dh(A, B, seed=seed)[0], _scipy_dh(B, A, seed=seed)[0]))


@dataclass(frozen=True, eq=False)
class Timings:
    """Wall times (best of ``repeat``) and results of several Hausdorff algorithms.

    Attributes
    ----------
    seconds : dict
        ``{name: seconds}``.
    values : dict
        ``{name: H(A, B)}``; all equal when the algorithms are exact.

    See Also
    --------
    timings
        Produces it.
    """

    seconds: dict
    values: dict

    @property
    def agree(self) -> bool:
        """Whether every algorithm returned the same distance (to 1e-12 relative)."""
        v = np.array(list(self.values.values()))
        return bool(np.allclose(v, v[0], rtol=tol.DISTANCE_AGREE, atol=0.0))


def timings(A, B, *, repeat: int = 3, brute: bool = True) -> Timings:
    """Time brute force, a k-d tree, scipy's early break and :func:`hausdorff`.

    Each algorithm first runs once untimed (a warm-up: the first k-d tree call
    imports ``scipy.spatial``, 0.3-0.8 s, which is not the algorithm's cost), then
    the best of ``repeat`` timed runs is kept.

    Parameters
    ----------
    A, B : array_like
    repeat : int
        Best of this many timed runs per algorithm, after the untimed warm-up.
    brute : bool
        Include brute force (``n * m`` distances; keep the sets small).

    Returns
    -------
    Timings

    See Also
    --------
    hausdorff
        The library's default algorithm.

    References
    ----------
    .. [1] A. A. Taha and A. Hanbury, "An efficient algorithm for calculating the exact
           Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           37(11):2153-2163, 2015. doi:10.1109/TPAMI.2015.2408351
    """
    import time

    A, B = as_point_pair(A, B)
    repeat = as_positive_int(repeat, "repeat")
    algos = {}
    if brute:
        algos["brute force"] = lambda: hausdorff(A, B, method="brute")
    algos["k-d tree (scipy)"] = lambda: hausdorff_kdtree(A, B)
    algos["early break (scipy)"] = lambda: hausdorff_early_break(A, B)
    algos["shapelab"] = lambda: hausdorff(A, B)
    seconds, values = {}, {}
    for name, fn in algos.items():
        fn()  # warm-up, untimed: first-call imports and allocations are not the algorithm
        best = np.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            values[name] = float(fn())
            best = min(best, time.perf_counter() - t0)
        seconds[name] = best
    return Timings(seconds, values)
