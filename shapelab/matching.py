"""Matching under translation (notes §23.2): ``min_t H(A, B + t)``.

"For the translation only case, a quick way to match R and G is to align their
centroids."  :func:`reference_point` gives the notes' centroid and the centre of the
bounding box (a *reference point*: its alignment is within a factor ``1 + sqrt(d)`` of the
optimum, Aichholzer, Alt and Rote 1997); :func:`hausdorff_under_translation` compares
those alignments with a certified numerical optimum (:class:`TranslationMatch`).
The Hausdorff distance itself is in :mod:`shapelab.hausdorff`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.geometry import kdtree
from ._toolkit.tolerances import MATCHING_FATOL, MATCHING_GAP_ABS, MATCHING_STEP_REL, MATCHING_XATOL
from ._toolkit.validate import as_finite_scalar, as_point_pair, as_points, as_positive_int
from .hausdorff import hausdorff

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["reference_point", "TranslationMatch", "hausdorff_under_translation"]


def reference_point(points: ArrayLike, kind: str = "centroid") -> np.ndarray:
    """A reference point of a point set (notes §23.2, "reference points").

    Parameters
    ----------
    points : array_like, shape (n, d)
    kind : {"centroid", "bbox"}
        ``"centroid"``: the mean of the points, the notes' choice.
        ``"bbox"``: the centre of the axis-parallel bounding box.

    Returns
    -------
    ndarray, shape (d,)

    See Also
    --------
    hausdorff_under_translation
        Uses reference points to match under translation.

    Notes
    -----
    A *reference point* r for the Hausdorff distance must be equivariant,
    ``r(X + t) = r(X) + t``, and Lipschitz, ``|r(X) - r(Y)| <= c H(X, Y)``.
    Then aligning reference points is a ``(1 + c)``-approximation of the best
    translation: with ``t*`` optimal,
    ``H(A, B + t_r) <= H(A, B + t*) + |t_r - t*| <= (1 + c) H(A, B + t*)``.

    * The bounding-box centre qualifies with ``c = sqrt(d)``: each coordinate of
      the box's minimum and maximum moves by at most H, so each coordinate of the
      centre does too.
    * The centroid of a *finite point set* does **not** qualify: adding k points
      within eps of one point x of an n-point set moves the set by at most eps in
      H but moves its centroid a fraction k/(n + k) of the way to x (up to eps).
      (Repeating x would not do: a repeated point leaves a set unchanged.)  The ratio of
      centroid alignment to the optimum is unbounded; see
      :func:`hausdorff_under_translation`.  The notes call centroids reference
      points without this caveat.  (For convex bodies the Steiner point is a
      reference point with c = 4/π in the plane — Aichholzer, Alt and Rote; not
      implemented here.)

    References
    ----------
    .. [1] H. Alt, B. Behrends and J. Blömer, "Approximate matching of polygonal shapes",
           *Ann. Math. Artif. Intell.* 13:251-265, 1995. doi:10.1007/BF01530830

    Examples
    --------
    >>> import numpy as np
    >>> square = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    >>> reference_point(square)
    array([1., 1.])
    >>> reference_point(np.vstack([square, [[10.0, 0.0]]]), "bbox")
    array([5., 1.])
    """
    P = as_points(points, "points")
    if kind == "centroid":
        return P.mean(axis=0)
    if kind == "bbox":
        return 0.5 * (P.min(axis=0) + P.max(axis=0))
    raise ValueError(f"kind must be 'centroid' or 'bbox', got {kind!r}")


@dataclass(frozen=True, eq=False)
class TranslationMatch:
    """Hausdorff matching of B to A under translation: ``min_t H(A, B + t)``.

    Attributes
    ----------
    centroid_translation : ndarray, shape (d,)
        ``mean(A) - mean(B)``, the notes' quick match.
    centroid_distance : float
        ``H(A, B + centroid_translation)``.
    bbox_translation : ndarray, shape (d,)
        Difference of the bounding-box centres, a reference point with a
        guarantee.
    bbox_distance : float
        ``H(A, B + bbox_translation)``; at most ``bound * optimal``.
    optimal_translation : ndarray, shape (d,)
        The best translation found by the certified search.
    optimal_distance : float
        ``H(A, B + optimal_translation)``: an upper bound of the optimum.
    lower_bound : float
        A certified lower bound of ``min_t H(A, B + t)``.  ``optimal_distance -
        lower_bound`` is the remaining gap (at most ``tol`` when ``converged``).
    ratio : float
        ``centroid_distance / optimal_distance`` (1.0 when both are 0).  No
        constant bounds it for point sets.  Meaningless when both distances are
        at round-off level (a translated copy).
    bbox_ratio : float
        ``bbox_distance / optimal_distance``; at most :attr:`bound`.
    bound : float
        ``1 + sqrt(d)``, the proven approximation factor of bounding-box alignment.
    n_evaluations : int
        How many translations were evaluated.
    converged : bool
        Whether the gap closed to the tolerance within the evaluation budget.

    See Also
    --------
    hausdorff_under_translation
        Produces it.
    """

    centroid_translation: np.ndarray
    centroid_distance: float
    bbox_translation: np.ndarray
    bbox_distance: float
    optimal_translation: np.ndarray
    optimal_distance: float
    lower_bound: float
    ratio: float
    bbox_ratio: float
    bound: float
    n_evaluations: int
    converged: bool

    def __repr__(self) -> str:
        t = np.array2string(self.optimal_translation, precision=6, suppress_small=True)
        return (
            f"TranslationMatch(optimal_distance={self.optimal_distance:.6g}, optimal_translation={t}, "
            f"centroid_distance={self.centroid_distance:.6g}, ratio={self.ratio:.4g}, "
            f"bbox_ratio={self.bbox_ratio:.4g} <= {self.bound:.4g}, converged={self.converged})"
        )


def _translated_values(A: np.ndarray, B: np.ndarray, T: np.ndarray) -> np.ndarray:
    """``H(A, B + t)`` for every row t of T (vectorised brute force for small sets,
    the pruned algorithm otherwise)."""
    n, d = A.shape
    m = B.shape[0]
    out = np.empty(T.shape[0])
    if n * m > 1 << 18:  # two k-d trees built once serve every translation
        ta, tb = kdtree(A), kdtree(B)
        for k, t in enumerate(T):
            hab = tb.query(A - t, k=1, workers=-1)[0].max()
            hba = ta.query(B + t, k=1, workers=-1)[0].max()
            out[k] = max(hab, hba)
        return out
    step = max(1, (1 << 21) // (n * m))
    for s in range(0, T.shape[0], step):
        Tc = T[s : s + step]
        D = np.zeros((Tc.shape[0], n, m))
        for k in range(d):
            diff = A[None, :, None, k] - (B[None, None, :, k] + Tc[:, None, None, k])
            D += diff * diff
        hab = D.min(axis=2).max(axis=1)
        hba = D.min(axis=1).max(axis=1)
        out[s : s + step] = np.sqrt(np.maximum(hab, hba))
    return out


def hausdorff_under_translation(
    A: ArrayLike, B: ArrayLike, *, tol: float = 1e-3, max_evaluations: int = 20000, polish: bool = True
) -> TranslationMatch:
    """Match B to A by a translation: reference points against the optimum (§23.2).

    The notes propose aligning centroids ("reference points") as a quick match
    under translation.  This returns that match, the bounding-box match (a true
    reference point, with a proven factor), and the optimum
    ``min_t H(A, B + t)`` found by a *certified* global search.

    Parameters
    ----------
    A, B : array_like, shape (n, d) and (m, d)
        The fixed set A and the moving set B.
    tol : float
        Relative tolerance of the optimum: the search stops when
        ``optimal_distance - lower_bound <= tol * optimal_distance`` (plus 1e-12
        absolute).
    max_evaluations : int
        Budget of translations evaluated by the branch-and-bound search.
    polish : bool
        Finish with a Nelder-Mead search (scipy) from the best translation; it can
        only lower ``optimal_distance``.

    Returns
    -------
    TranslationMatch

    Raises
    ------
    ValueError
        Bad A or B (see :func:`directed_hausdorff`), tol <= 0, or
        max_evaluations < 1.

    See Also
    --------
    reference_point
        The reference points used for the first guess.
    hausdorff
        The distance it minimises.
    icp
        Local improvement under rigid motions.

    Notes
    -----
    The search is a Lipschitz branch and bound.  ``f(t) = H(A, B + t)`` is
    1-Lipschitz in t, so a cube of half-width w centred at c cannot hold a value
    below ``f(c) - w sqrt(d)``.  The optimum lies in the cube of half-width
    ``f(t_bbox)`` around the bounding-box translation (each coordinate of the box
    centre moves by at most H).  Cubes whose bound cannot beat the best value by
    more than the tolerance are discarded, the others are split in 2^d, until
    the gap closes or the budget runs out.  Unlike a local method
    (Nelder-Mead alone gets stuck: f has many local minima), this returns a
    certified interval ``[lower_bound, optimal_distance]`` for the optimum.

    References
    ----------
    .. [1] H. Alt, B. Behrends and J. Blömer, "Approximate matching of polygonal shapes",
           *Ann. Math. Artif. Intell.* 13:251-265, 1995. doi:10.1007/BF01530830
    .. [2] D. P. Huttenlocher, G. A. Klanderman and W. J. Rucklidge, "Comparing images
           using the Hausdorff distance", *IEEE Trans. Pattern Anal. Mach. Intell.*
           15(9):850-863, 1993. doi:10.1109/34.232073

    Examples
    --------
    >>> import numpy as np
    >>> A = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    >>> m = hausdorff_under_translation(A, A + [3.0, -2.0])
    >>> np.round(m.centroid_translation, 6).tolist(), round(m.centroid_distance, 9)
    ([-3.0, 2.0], 0.0)
    >>> round(m.optimal_distance, 6), m.ratio <= 1.0
    (0.0, True)
    """
    A, B = as_point_pair(A, B)
    tol = as_finite_scalar(tol, "tol", positive=True)
    max_evaluations = as_positive_int(max_evaluations, "max_evaluations")
    d = A.shape[1]
    t_c = A.mean(axis=0) - B.mean(axis=0)
    t_b = 0.5 * (A.min(axis=0) + A.max(axis=0)) - 0.5 * (B.min(axis=0) + B.max(axis=0))
    f_c = hausdorff(A, B + t_c)
    f_b = hausdorff(A, B + t_b)
    best_t, best_f = (t_b, f_b) if f_b <= f_c else (t_c, f_c)
    n_eval = 2
    sqrt_d = float(np.sqrt(d))
    # Branch and bound over cubes (centres C with values F, common half-width w).
    # ``floor`` is the least lower bound of every cube discarded so far.
    w = f_b
    C = t_b[None, :].copy()
    F = np.array([f_b])
    floor = np.inf
    converged = False
    offsets = np.array(np.meshgrid(*[[-0.5, 0.5]] * d, indexing="ij")).reshape(d, -1).T
    while True:
        lb = F - w * sqrt_d
        keep = lb < best_f - (tol * best_f + MATCHING_GAP_ABS)
        if (~keep).any():
            floor = min(floor, float(lb[~keep].min()))
        C, lb = C[keep], lb[keep]
        if C.shape[0] == 0:
            converged = True
            break
        children = (C[:, None, :] + w * offsets[None, :, :]).reshape(-1, d)
        if n_eval + children.shape[0] > max_evaluations:
            floor = min(floor, float(lb.min()))
            break
        w *= 0.5
        F = _translated_values(A, B, children)
        n_eval += children.shape[0]
        C = children
        k = int(np.argmin(F))
        if F[k] < best_f:
            best_f, best_t = float(F[k]), children[k].copy()
    lower = float(max(0.0, min(floor, best_f)))
    if polish and best_f > 0:
        from scipy.optimize import minimize

        def fun(t):
            return float(_translated_values(A, B, np.asarray(t, dtype=float)[None, :])[0])

        step = max(w, MATCHING_STEP_REL * (1.0 + float(np.abs(best_t).max())))
        simplex = np.vstack([best_t, best_t + step * np.eye(d)])
        res = minimize(
            fun,
            best_t,
            method="Nelder-Mead",
            options={"initial_simplex": simplex, "xatol": MATCHING_XATOL, "fatol": MATCHING_FATOL, "maxfev": 400 * d},
        )
        n_eval += int(res.nfev)
        if res.fun < best_f:
            best_t = np.asarray(res.x, dtype=float)
            best_f = hausdorff(A, B + best_t)
    best_f = float(hausdorff(A, B + best_t))
    lower = min(lower, best_f)

    def _ratio(x: float) -> float:
        if best_f > 0:
            return x / best_f
        return 1.0 if x == 0 else float("inf")

    return TranslationMatch(
        centroid_translation=t_c,
        centroid_distance=float(f_c),
        bbox_translation=t_b,
        bbox_distance=float(f_b),
        optimal_translation=np.asarray(best_t, dtype=float),
        optimal_distance=best_f,
        lower_bound=float(lower),
        ratio=_ratio(f_c),
        bbox_ratio=_ratio(f_b),
        bound=1.0 + sqrt_d,
        n_evaluations=n_eval,
        converged=converged,
    )


# --------------------------------------------------------------------------- #
# The classical algorithms, for comparisons in lessons and benchmarks          #
# --------------------------------------------------------------------------- #
