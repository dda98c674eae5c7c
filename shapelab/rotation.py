"""Horn's optimal rotation and rigid registration (Notes §23.2, "Optimal rotation").

Two layers, the second built on the first (ICP, :mod:`shapelab.icp`, builds on both):

* :func:`optimal_rotation` — Horn's closed form, exactly as the notes derive it: the
  unit quaternion maximising :math:`q^TAq` with :math:`A = \\sum_j \\bar R_j^T G_j`,
  i.e. the *rotation about the origin* minimising
  :math:`\\sum_j \\lVert q r_j q^* - g_j\\rVert^2` for **paired** points.
* :func:`register` — the least-squares rigid motion (rotation *and* translation):
  centre both sets on their centroids, then :func:`optimal_rotation`.

The first two take optional ``weights`` (one per pair; Horn 1987, §2.C) and can
return SciPy's sensitivity matrix of the rotation (``return_sensitivity=True``).

Conventions
-----------
Everything rotates/moves the **first** set onto the **second**: ``optimal_rotation(R,
G)`` returns :math:`q` with :math:`q r_j q^* \\approx g_j`, ``register(R, G).apply(R)
≈ G``, and ``icp(source, target)`` moves ``source`` onto ``target`` (the target is
fixed and holds the k-d tree).  SciPy's ``Rotation.align_vectors(a, b)`` uses the
opposite order: it rotates ``b`` onto ``a``.

Where the notes are wrong or imprecise
--------------------------------------
* **Centring and pairing.** The notes minimise :math:`\\sum_j\\lVert I_q(r_j) -
  g_j\\rVert^2` over rotations only and call the result the optimal rotation.  This is
  the right rotation for a rigid motion only when both sets are **centred** on their
  centroids (then the optimal translation is zero), and only for sets **paired**
  index by index (:math:`r_j \\leftrightarrow g_j`, same :math:`n`).  :func:`register`
  does the centring; :func:`optimal_rotation` deliberately does not (it is the
  notes' formula).
* :math:`f(q) = \\min_{q} \\sum \\dots` puts the minimum inside the definition of a
  function of :math:`q`; it should read :math:`f(q) = \\sum_j\\lVert q r_j q^* -
  g_j\\rVert^2` and we seek :math:`\\arg\\min_{q\\in\\mathbb S^3} f(q)`.  Likewise "we
  have computed :math:`f(q)`" means the minimiser :math:`q = X_1`, not the value.
* :math:`\\sum\\alpha_l^2 = 1` and :math:`q^T(\\sum\\alpha_l\\lambda_lX_l) = \\sum
  \\alpha_l^2\\lambda_l` need the eigenvectors to be chosen **orthonormal** (possible
  as :math:`A` is symmetric); and :math:`q = X_1` is the unique answer (up to sign)
  only if :math:`\\lambda_1 > \\lambda_2`.  When :math:`\\lambda_1 = \\lambda_2` (e.g.
  collinear points) a whole circle of quaternions is optimal; :func:`optimal_rotation`
  and :func:`register` then return the one of smallest rotation angle (the identity
  for ``register(X, X)``), and warn.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from ._toolkit.tolerances import ROTATION_EIGEN_GAP
from ._toolkit.validate import as_float_array as _as_float_array
from ._toolkit.validate import (
    as_point,
    as_points,
    as_vector,
    check_same_shape,
)
from ._toolkit.validate import check_finite as _check_finite
from .quaternion import Quaternion, as_points3, qmul, unit_quaternions

__all__ = [
    "DegenerateRotationWarning",
    "cross_covariance",
    "horn_matrix",
    "optimal_rotation",
    "kabsch",
    "RigidMotion",
    "register",
    "fit_motion",
]


class DegenerateRotationWarning(UserWarning):
    """The optimal rotation is not unique (collinear points, a single point, all zero, or
    a mirror image with two equal singular values).

    The returned rotation is the optimal one of smallest angle; the rotation about the
    common line of the points (or the mirror's axis) is undetermined by the data.

    See Also
    --------
    optimal_rotation
        Warns with it.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629

    Examples
    --------
    A single pair fixes no spin about its line:

    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     _ = optimal_rotation([[1.0, 0, 0]], [[1.0, 0, 0]])
    >>> [w.category.__name__ for w in caught]
    ['DegenerateRotationWarning']
    """


# --------------------------------------------------------------------------- Horn


def cross_covariance(R: npt.ArrayLike, G: npt.ArrayLike) -> np.ndarray:
    """The 3×3 matrix :math:`M = \\sum_j r_j g_j^T` of paired point sets (no centring).

    Computed as one matrix product, O(n).

    See Also
    --------
    horn_matrix
        Horn's matrix, built from these sums.
    kabsch
        Uses its SVD.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629
    .. [2] W. Kabsch, "A solution for the best rotation to relate two sets of vectors",
           *Acta Cryst. A* 32:922-923, 1976. doi:10.1107/S0567739476001873

    Examples
    --------
    >>> cross_covariance([[1.0, 0, 0], [0, 2, 0]], [[0, 1.0, 0], [0, 0, 1]]).tolist()
    [[0.0, 1.0, 0.0], [0.0, 0.0, 2.0], [0.0, 0.0, 0.0]]
    """
    R, G = _paired(R, G)
    return _covariance(R, G)


def _horn_from_m(m: np.ndarray) -> np.ndarray:
    (sxx, sxy, sxz), (syx, syy, syz), (szx, szy, szz) = m
    return np.array(
        [
            [sxx + syy + szz, syz - szy, szx - sxz, sxy - syx],
            [syz - szy, sxx - syy - szz, sxy + syx, szx + sxz],
            [szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy],
            [sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz],
        ]
    )


def horn_matrix(R: npt.ArrayLike, G: npt.ArrayLike) -> np.ndarray:
    """Horn's symmetric 4×4 matrix :math:`A = \\sum_j \\bar R_j^T G_j` (Notes §23.2).

    :math:`\\bar R_j` is the right-multiplication matrix of the pure quaternion
    :math:`r_j` (so :math:`q r_j = \\bar R_j q`) and :math:`G_j` the left-multiplication
    matrix of :math:`g_j` (so :math:`g_j q = G_j q`).  Then
    :math:`\\sum_j\\langle q r_j q^*, g_j\\rangle = q^TAq` for unit :math:`q`.

    :math:`A` is linear in :math:`M = \\sum_j r_j g_j^T` (:func:`cross_covariance`),
    so it is built from the nine entries of :math:`M` in O(n) total, never from n
    4×4 products::

        A = [[Sxx+Syy+Szz, Syz-Szy,      Szx-Sxz,      Sxy-Syx     ],
             [Syz-Szy,     Sxx-Syy-Szz,  Sxy+Syx,      Szx+Sxz     ],
             [Szx-Sxz,     Sxy+Syx,     -Sxx+Syy-Szz,  Syz+Szy     ],
             [Sxy-Syx,     Szx+Sxz,      Syz+Szy,     -Sxx-Syy+Szz ]]

    with :math:`S_{ab} = \\sum_j r_{j,a}\\, g_{j,b}`; the trace of :math:`A` is zero.
    The tests check this against the literal sum of the notes.

    See Also
    --------
    optimal_rotation
        Its top eigenvector.
    cross_covariance
        The 3×3 sums it is made of.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629

    Examples
    --------
    The identity pairing: the top eigenvector is :math:`1`, the identity rotation.

    >>> A = horn_matrix(np.eye(3), np.eye(3))
    >>> A.tolist()[0], float(np.trace(A))
    ([3.0, 0.0, 0.0, 0.0], 0.0)
    """
    return _horn_from_m(cross_covariance(R, G))


_BLOCK = 4096


def _cross(R: np.ndarray, G: np.ndarray) -> np.ndarray:
    """M = Σ r gᵀ as a sum of blocked 3×3 products (cache-friendly, several times faster
    than one (3×n)(n×3) product for large n, and summed blockwise: no less accurate)."""
    n = R.shape[0]
    if n < 2 * _BLOCK:
        return R.T @ G
    k = n // _BLOCK * _BLOCK
    Rb = R[:k].reshape(-1, _BLOCK, 3)
    Gb = G[:k].reshape(-1, _BLOCK, 3)
    return np.matmul(Rb.transpose(0, 2, 1), Gb).sum(axis=0) + R[k:].T @ G[k:]


def _paired(R, G) -> tuple[np.ndarray, np.ndarray]:
    """Validate paired (n, 3) sets, leaving the finiteness test to :func:`_covariance`.

    Any NaN or inf in R or G makes M = Σ r gᵀ non-finite (inf·0 = NaN, inf + (−inf) =
    NaN, NaN propagates), so testing the nine entries of M replaces two passes over
    the input; only then are R and G scanned, to name the culprit.
    """
    out = []
    for x, name in ((R, "R"), (G, "G")):
        a = _as_float_array(x, name)
        if a.ndim != 2:
            raise ValueError(f"{name} must be a 2-D array of shape (n, d), got shape {a.shape}")
        if a.shape[1] != 3:
            raise ValueError(f"{name} must have 3 columns (dimension), got shape {a.shape}")
        if a.shape[0] < 1:
            raise ValueError(f"{name} must hold at least 1 point(s), got {a.shape[0]}")
        out.append(np.ascontiguousarray(a))
    check_same_shape(out[0], out[1], "R", "G")
    return out[0], out[1]


def _covariance(R: np.ndarray, G: np.ndarray) -> np.ndarray:
    """M = Σ r gᵀ; a non-finite input or an overflow raises ValueError naming it."""
    with np.errstate(over="ignore", invalid="ignore"):
        m = _cross(R, G)
    if not np.all(np.isfinite(m)):
        _check_finite(R, "R")
        _check_finite(G, "G")
        raise ValueError("R and G are too large: their cross-covariance overflows float64")
    return m


def _weights(weights, n: int) -> np.ndarray | None:
    """``weights`` as n finite non-negative float64 numbers, not all zero (None stays None)."""
    if weights is None:
        return None
    w = _as_float_array(weights, "weights")
    if w.ndim != 1:
        raise ValueError(f"weights must be a 1-D array (one weight per point pair), got shape {w.shape}")
    if w.shape[0] != n:
        raise ValueError(f"weights must have one value per point pair ({n}), got {w.shape[0]}")
    _check_finite(w, "weights")
    if np.any(w < 0):
        i = int(np.argmax(w < 0))
        raise ValueError(f"weights must be non-negative, got weights[{i}] = {float(w[i])!r}")
    if not np.any(w > 0):
        raise ValueError("weights must not all be zero (no point pair would count)")
    # Only the ratios matter (the rotation, the centroids and the sensitivity are all
    # invariant under w -> c w): dividing by the largest keeps r_j w_j from overflowing
    # (w = 1e300) or underflowing to zero (w = 5e-324), either of which changed the answer.
    return w / w.max()


def _sensitivity(m: np.ndarray, w_mean: float) -> np.ndarray:
    """SciPy's sensitivity matrix of the rotation estimated from M = Σ w r gᵀ.

    With the singular values s₁ ≥ s₂ ≥ s₃ of M (s₃ negated when the best orthogonal
    matrix is a reflection, as in Kabsch), ζ = (s₁+s₂)(s₂+s₃)(s₃+s₁) and
    κ = s₁s₂ + s₂s₃ + s₃s₁: S = mean(w)/ζ · (κI + MᵀM), in the frame of G (SciPy's frame
    A, with B = Σ w a bᵀ = Mᵀ for a = g, b = r).
    """
    u, sv, vt = np.linalg.svd(m)
    if np.linalg.det(u @ vt) < 0:
        sv = sv * np.array([1.0, 1.0, -1.0])
    # S is homogeneous of degree -1 in M: computed from M / s1 and divided by s1 at the
    # end, so that zeta ~ s1^3 neither overflows (coordinates ~1e100) nor underflows.
    s1 = sv[0]
    sv = sv / s1
    mn = m / s1
    zeta = (sv[0] + sv[1]) * (sv[1] + sv[2]) * (sv[2] + sv[0])
    kappa = sv[0] * sv[1] + sv[1] * sv[2] + sv[2] * sv[0]
    return (kappa * np.eye(3) + mn.T @ mn) * (w_mean / zeta / s1)


def _rotation_from_m(m: np.ndarray, *, caller: str, sensitivity: float | None = None):
    """Top eigenvector of Horn's matrix built from M; warn when it is not unique.

    Not unique means λ₁ − λ₂ ≤ 1e-9 · max|λ| (a numerically repeated top eigenvalue).
    Then every unit quaternion of the top eigenspace E (the eigenvalues within that
    tolerance of λ₁) is optimal, and the one of smallest rotation angle is the one of
    largest :math:`|q_0|`: the projection of 1 = (1, 0, 0, 0) on E, normalised.  A = 0
    gives the identity.  If the projection is zero, every optimal rotation is a half turn
    and the top eigenvector is returned.

    ``sensitivity`` (the mean weight) also returns SciPy's sensitivity matrix; a
    degenerate optimum has none (ValueError).
    """
    a = _horn_from_m(m)
    lam, vec = np.linalg.eigh(a)  # ascending
    q = vec[:, 3]
    scale = float(np.abs(lam).max())
    degenerate = scale == 0.0 or lam[3] - lam[2] <= ROTATION_EIGEN_GAP * scale
    if degenerate:
        if sensitivity is not None:
            raise ValueError(
                f"{caller}: the sensitivity matrix is undefined when the optimal rotation is not unique "
                "(collinear points or a single pair: the spin about their line is not determined)"
            )
        warnings.warn(
            f"{caller}: the optimal rotation is not unique (the points are collinear with the "
            "origin/centroid, or fewer than two independent directions, or G mirrors R with two "
            "equal singular values); the rotation about their common line is undetermined and "
            "the optimal rotation of smallest angle is returned",
            DegenerateRotationWarning,
            stacklevel=3,
        )
        top = vec[:, lam >= lam[3] - ROTATION_EIGEN_GAP * scale]
        proj = top @ top[0]  # the projection of (1, 0, 0, 0) on the top eigenspace
        if scale == 0.0:
            q = np.array([1.0, 0.0, 0.0, 0.0])
        elif np.any(proj != 0.0):
            q = proj
    if q[0] < 0 or (q[0] == 0 and q[np.flatnonzero(q)[0]] < 0):
        q = -q
    rot = Quaternion(*(q / np.linalg.norm(q)))
    if sensitivity is None:
        return rot
    return rot, _sensitivity(m, sensitivity)


def optimal_rotation(
    R: npt.ArrayLike, G: npt.ArrayLike, weights: npt.ArrayLike | None = None, *, return_sensitivity: bool = False
) -> Quaternion | tuple[Quaternion, np.ndarray]:
    """Horn's closed-form optimal rotation of paired point sets (Notes §23.2).

    Returns the unit quaternion :math:`q` maximising :math:`q^TAq` with
    :math:`A = \\sum_j w_j\\bar R_j^TG_j` (:func:`horn_matrix`, weighted): the
    eigenvector of the largest eigenvalue :math:`\\lambda_1` of :math:`A`.  It
    minimises :math:`f(q) = \\sum_j w_j\\lVert q r_j q^* - g_j\\rVert^2`, i.e. it
    rotates ``R`` onto ``G`` **about the origin**.

    Parameters
    ----------
    R, G : array_like, shape (n, 3)
        Paired points: :math:`r_j` goes to :math:`g_j`.  Not centred here (this is
        the notes' formula); for a rigid motion use :func:`register`, which centres.
    weights : array_like, shape (n,), optional
        :math:`w_j \\ge 0`, finite, not all zero: the weight of pair :math:`j` in the
        cost (the inverse of its variance, for the sensitivity).  Default: all 1 (the
        notes' cost).  Only their ratios change the rotation.
    return_sensitivity : bool
        Also return SciPy's sensitivity matrix (below).

    Returns
    -------
    Quaternion
        Unit, with :math:`q_0 \\ge 0` (``q`` and ``-q`` are the same rotation).
    sensitivity : ndarray, shape (3, 3)
        Only with ``return_sensitivity=True``: the sensitivity matrix of SciPy's
        ``Rotation.align_vectors(G, R, weights, return_sensitivity=True)`` (note the
        order: SciPy rotates its second argument onto the first).  The error of the
        estimate, as the rotation vector :math:`\\delta` of :math:`q_{\\rm true}q^{-1}`
        (a small rotation after :math:`q`, in the frame of ``G``), has covariance
        :math:`hS` when :math:`g_j` is measured with variance :math:`v_j` per axis,
        small against its length, with weights :math:`w_j \\propto 1/v_j` and
        :math:`h = n/\\sum_j v_j^{-1}` their harmonic mean (SciPy's rule; equal
        variances :math:`\\sigma^2` and weights give :math:`\\sigma^2S`).  With the singular
        values :math:`s_1 \\ge s_2 \\ge s_3` of :math:`M = \\sum_j w_jr_jg_j^T` (the last
        negated when :math:`\\det M < 0`), :math:`S = \\bar w\\,(\\kappa I + M^TM)/\\zeta`,
        :math:`\\kappa = s_1s_2 + s_2s_3 + s_3s_1`, :math:`\\zeta = (s_1+s_2)(s_2+s_3)
        (s_3+s_1)`, :math:`\\bar w` the mean weight (Markley 1988).  Undefined when the
        optimum is not unique: then ValueError, as SciPy raises for a single pair.

    Warns
    -----
    DegenerateRotationWarning
        When :math:`\\lambda_1 = \\lambda_2` (relative gap below 1e-9): all
        :math:`r_j` (or all :math:`g_j`) lie on one line through the origin, a single
        pair, or all points at the origin (or, without collinearity, ``G`` is a mirror
        image of ``R`` and the two smaller singular values of :math:`M` are equal: then
        the spins about the remaining axis are all optimal, e.g. the identity and every
        rotation about x for :math:`M = \\mathrm{diag}(4, 1, -1)`).  Then every
        rotation that aligns the lines and spins arbitrarily about them is optimal, and the one of **smallest angle**
        is returned: the identity for equal directions (and when :math:`A = 0`), the
        turn about :math:`r \\times g` for different ones, as SciPy's ``align_vectors``
        does for one pair; a half turn when the directions are opposite (then all
        optimal rotations are half turns).  The optimal quaternions are the unit
        vectors of the top eigenspace :math:`E` of :math:`A`, the angle is
        :math:`2\\arccos|q_0|`, so the answer is the projection of :math:`1` on
        :math:`E`, normalised.  The threshold is on :math:`\\lambda_1 - \\lambda_2 =
        2(s_2 + s_3)`, quadratic in the spread across the line: points whose spread
        across their line is below about :math:`\\sqrt{10^{-9}} \\approx 3\\cdot10^{-5}`
        of their length count as collinear, and the rotation returned then fits only to
        about that spread (SVD-based ``align_vectors`` still finds the exact spin), a
        jump of up to a half turn about the line across the threshold.

    See Also
    --------
    register : the rigid motion (weighted centroids, then this rotation).
    kabsch : the SVD route.

    Notes
    -----
    * **Reflections.** If ``G`` is a mirror image of ``R``, no rotation matches it;
      the quaternion method returns the best *proper* rotation, whereas the naive SVD
      solution :math:`VU^T` (without the :math:`\\det` fix of Kabsch) returns the
      reflection.  See :func:`kabsch`.
    * Two non-parallel pairs already determine the rotation (:math:`n=2` is fine
      here, unlike for :func:`register`, where centring leaves a single direction).
    * Cost: one pass over the data for :math:`M` (blocked 3×3 products, O(n)) and a
      4×4 symmetric eigenproblem; input finiteness is read off :math:`M`.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
       quaternions", J. Opt. Soc. Am. A 4 (1987) 629–642 (weights: §2.C).
    .. [2] F. L. Markley, "Attitude determination using vector observations and the
       singular value decomposition", J. Astronaut. Sci. 36 (1988) 245–258 (the
       sensitivity); SciPy, ``scipy.spatial.transform.Rotation.align_vectors``.

    Examples
    --------
    >>> q = Quaternion.from_axis_angle([0, 0, 1], np.pi / 2)
    >>> R = np.eye(3)
    >>> optimal_rotation(R, q.rotate(R)).isclose(q)
    True
    >>> q, S = optimal_rotation(R, q.rotate(R), [1.0, 1.0, 2.0], return_sensitivity=True)
    >>> S.shape
    (3, 3)

    One pair has a circle of optimal rotations; the smallest is returned:

    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore", DegenerateRotationWarning)
    ...     print(optimal_rotation([[1, 0, 0]], [[1, 0, 0]]), "|", optimal_rotation([[1, 0, 0]], [[0, 1, 0]]))
    1 +0i +0j +0k | 0.707107 +0i +0j +0.707107k
    """
    R, G = _paired(R, G)
    w = _weights(weights, R.shape[0])
    if w is not None:
        R = R * w[:, None]
    return _rotation_from_m(
        _covariance(R, G),
        caller="optimal_rotation",
        sensitivity=(1.0 if w is None else float(w.mean())) if return_sensitivity else None,
    )


def kabsch(R: npt.ArrayLike, G: npt.ArrayLike, *, proper: bool = True) -> np.ndarray:
    """The SVD solution (Kabsch/Umeyama) for the rotation matrix taking ``R`` onto ``G``.

    Independent of the quaternion route; used by the tests and the lesson on the
    optimal rotation.  With :math:`M = \\sum_j r_j g_j^T = U\\Sigma V^T`, the
    minimiser of :math:`\\sum\\lVert X r_j - g_j\\rVert^2` over orthogonal :math:`X` is
    :math:`VU^T`; over rotations it is :math:`V\\,\\mathrm{diag}(1, 1, \\det VU^T)\\,U^T`.

    Parameters
    ----------
    R, G : array_like, shape (n, 3)
        Paired points (not centred here).
    proper : bool
        True (default): the det fix, always a rotation.  False: the naive
        :math:`VU^T`, which is a reflection when that fits better.

    See Also
    --------
    optimal_rotation
        Horn's quaternion method.
    scipy.spatial.transform.Rotation.align_vectors
        SciPy's.

    References
    ----------
    .. [1] W. Kabsch, "A solution for the best rotation to relate two sets of vectors",
           *Acta Cryst. A* 32:922-923, 1976. doi:10.1107/S0567739476001873
    .. [2] S. Umeyama, "Least-squares estimation of transformation parameters between two
           point patterns", *IEEE Trans. Pattern Anal. Mach. Intell.* 13(4):376-380,
           1991. doi:10.1109/34.88573

    Examples
    --------
    A mirror image: the naive SVD answer is the reflection, the det fix a rotation.

    >>> R = np.array([[1.0, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> G = R * [1, 1, -1]
    >>> round(float(np.linalg.det(kabsch(R, G, proper=False)))), round(float(np.linalg.det(kabsch(R, G))))
    (-1, 1)
    """
    R = as_points(R, "R", dim=3)
    G = as_points(G, "G", dim=3)
    check_same_shape(R, G, "R", "G")
    u, _, vt = np.linalg.svd(R.T @ G)
    if not proper:
        return vt.T @ u.T
    d = np.sign(np.linalg.det(vt.T @ u.T)) or 1.0
    return vt.T @ np.diag([1.0, 1.0, d]) @ u.T


# --------------------------------------------------------------------------- motions


def _readonly(a) -> np.ndarray:
    a = np.array(a, dtype=np.float64, copy=True)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class RigidMotion:
    """A rigid motion :math:`x \\mapsto R(q)\\,x + t` (rotation, then translation).

    Parameters
    ----------
    rotation : Quaternion or array_like (4,), optional
        Any non-zero quaternion; stored normalised.  Default: the identity.
    translation : array_like, shape (3,), optional
        Default: zero.

    See Also
    --------
    register
        The least-squares motion of paired points.
    icp
        The motion of unpaired point sets.

    Notes
    -----
    Composition: ``a @ b`` is the motion "apply ``b``, then ``a``", so that
    ``(a @ b).apply(x) == a.apply(b.apply(x))`` — the order of function composition
    :math:`a\\circ b` and of the 4×4 matrices, ``(a @ b).as_matrix() == a.as_matrix()
    @ b.as_matrix()``.

    Examples
    --------
    >>> m = RigidMotion(Quaternion.from_axis_angle([0, 0, 1], np.pi / 2), [1, 0, 0])
    >>> np.round(m.apply([1.0, 0.0, 0.0]), 12).tolist()
    [1.0, 1.0, 0.0]
    >>> np.allclose((m.inverse() @ m).as_matrix(), np.eye(4))
    True
    """

    rotation: Quaternion
    translation: np.ndarray = field(repr=False)

    def __init__(self, rotation=None, translation=None):
        if rotation is None:
            q = Quaternion.identity()
        elif isinstance(rotation, Quaternion):
            q = rotation
        else:
            q = Quaternion(*as_vector(rotation, "rotation", length=4))
        q = Quaternion(*unit_quaternions(q.as_array(), "rotation"))
        t = np.zeros(3) if translation is None else as_point(translation, "translation", dim=3)
        object.__setattr__(self, "rotation", q)
        object.__setattr__(self, "translation", _readonly(t))

    @classmethod
    def identity(cls) -> "RigidMotion":
        """The motion that moves nothing."""
        return cls()

    @classmethod
    def from_matrix(cls, matrix, *, atol: float = 1e-6) -> "RigidMotion":
        """From a 4×4 homogeneous matrix ``[[R, t], [0, 0, 0, 1]]``."""
        m = _as_float_array(matrix, "matrix")
        if m.shape != (4, 4):
            raise ValueError(f"matrix must have shape (4, 4), got shape {m.shape}")
        _check_finite(m, "matrix")
        if not np.allclose(m[3], [0, 0, 0, 1], atol=atol):
            raise ValueError(f"matrix must have last row (0, 0, 0, 1), got {m[3].tolist()}")
        return cls(Quaternion.from_matrix(m[:3, :3], atol=atol), m[:3, 3])

    @property
    def rotation_matrix(self) -> np.ndarray:
        """The 3×3 rotation matrix :math:`R(q)`."""
        return self.rotation.to_matrix()

    @property
    def angle(self) -> float:
        """The rotation angle in radians, in [0, π]."""
        return self.rotation.to_axis_angle()[1]

    def apply(self, points) -> np.ndarray:
        """Move one point (3,) or many (n, 3): :math:`R(q)\\,x + t`."""
        p = as_points3(points, "points")
        return p @ self.rotation_matrix.T + self.translation

    def inverse(self) -> "RigidMotion":
        """The motion undoing this one: :math:`x \\mapsto R^T(x - t)`."""
        qi = self.rotation.conjugate()
        return RigidMotion(qi, -qi.rotate(self.translation))

    def __matmul__(self, other):
        if not isinstance(other, RigidMotion):
            return NotImplemented
        q = Quaternion(*qmul(self.rotation.as_array(), other.rotation.as_array()))
        return RigidMotion(q, self.rotation.rotate(other.translation) + self.translation)

    def as_matrix(self) -> np.ndarray:
        """The 4×4 homogeneous matrix ``[[R, t], [0, 0, 0, 1]]``."""
        m = np.eye(4)
        m[:3, :3] = self.rotation_matrix
        m[:3, 3] = self.translation
        return m

    def isclose(self, other: "RigidMotion", atol: float = 1e-9) -> bool:
        """Same motion within ``atol`` (rotation up to the sign of the quaternion)."""
        if not isinstance(other, RigidMotion):
            raise TypeError(f"other must be a RigidMotion, got {type(other).__name__}")
        return self.rotation.same_rotation(other.rotation, atol) and bool(
            np.all(np.abs(self.translation - other.translation) <= atol)
        )

    def __repr__(self) -> str:
        axis, ang = self.rotation.to_axis_angle()
        ax = ", ".join(f"{a:.6g}" for a in axis)
        t = ", ".join(f"{a:.6g}" for a in self.translation)
        return f"RigidMotion(angle={np.degrees(ang):.6g}°, axis=({ax}), translation=({t}))"


def fit_motion(R: np.ndarray, G: np.ndarray, *, caller: str = "register", weights=None, sensitivity: bool = False):
    """:func:`register` on arrays already checked: paired float arrays ``(n, 3)``,
    ``weights`` an array or None, ``caller`` named in the warnings.  Step 2 of
    :func:`shapelab.icp.icp` calls it on every iteration.

    Centre both sets on their (weighted) centroids, rotate by :func:`optimal_rotation`'s
    closed form, translate the centroid onto the centroid.

    See Also
    --------
    register
        The same, with its input checked.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
       quaternions", J. Opt. Soc. Am. A 4 (1987) 629–642.

    Examples
    --------
    >>> X = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    >>> fit_motion(X, X + 1.0)
    RigidMotion(angle=0°, axis=(1, 0, 0), translation=(1, 1, 1))
    """
    with np.errstate(over="ignore", invalid="ignore"):
        if weights is None:
            cr = R.mean(axis=0)
            cg = G.mean(axis=0)
        else:
            total = weights.sum()
            cr = (weights @ R) / total
            cg = (weights @ G) / total
    if not (np.all(np.isfinite(cr)) and np.all(np.isfinite(cg))):
        raise ValueError("R and G are too large: their centroids overflow float64")
    Rc = R - cr if weights is None else (R - cr) * weights[:, None]
    out = _rotation_from_m(
        _covariance(Rc, G - cg),
        caller=caller,
        sensitivity=(1.0 if weights is None else float(weights.mean())) if sensitivity else None,
    )
    q = out[0] if sensitivity else out
    motion = RigidMotion(q, cg - q.rotate(cr))
    return (motion, out[1]) if sensitivity else motion


def register(
    R: npt.ArrayLike, G: npt.ArrayLike, weights: npt.ArrayLike | None = None, *, return_sensitivity: bool = False
) -> RigidMotion | tuple[RigidMotion, np.ndarray]:
    """The least-squares rigid motion taking paired points ``R`` onto ``G``.

    Minimises :math:`\\sum_j w_j\\lVert R(q)\\,r_j + t - g_j\\rVert^2`.  The optimal
    translation maps the (weighted) centroid to the (weighted) centroid,
    :math:`t = \\bar g - R(q)\\bar r` with :math:`\\bar r = \\sum w_jr_j/\\sum w_j`, and the
    rotation is :func:`optimal_rotation` of the **centred** sets with the same weights —
    the assumption the notes leave implicit (Notes §23.2, optimal rotation; Horn 1987,
    §2).

    Parameters
    ----------
    R, G : array_like, shape (n, 3)
        Paired points, :math:`r_j \\leftrightarrow g_j`.
    weights : array_like, shape (n,), optional
        :math:`w_j \\ge 0`, finite, not all zero (see :func:`optimal_rotation`).
        Default: all 1.  A pair of weight 0 is ignored.
    return_sensitivity : bool
        Also return the sensitivity matrix of the rotation (that of
        :func:`optimal_rotation` on the centred sets: SciPy's ``align_vectors(G - ḡ,
        R - r̄, weights, return_sensitivity=True)``); the centroids are taken as exact.

    Returns
    -------
    RigidMotion
        ``register(R, G).apply(R)`` is as close to ``G`` as a rigid motion allows.
    sensitivity : ndarray, shape (3, 3)
        Only with ``return_sensitivity=True``.

    Warns
    -----
    DegenerateRotationWarning
        With one or two points, or all points on one line, the rotation about that
        line is undetermined; the one of smallest angle is returned (so
        ``register(X, X)`` is the identity for every ``X``; see
        :func:`optimal_rotation`).  The translation is still optimal.

    See Also
    --------
    optimal_rotation, icp

    Notes
    -----
    Centring also makes the computation robust to huge offsets (e.g. coordinates
    around 1e6): the rotation is computed from centred coordinates only.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
       quaternions", J. Opt. Soc. Am. A 4 (1987) 629–642.

    Examples
    --------
    >>> X = np.array([[0.0, 0, 0], [1, 1, 1], [2, 2, 2]])  # collinear: not unique
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore", DegenerateRotationWarning)
    ...     register(X, X + 1.0)
    RigidMotion(angle=0°, axis=(1, 0, 0), translation=(1, 1, 1))
    """
    R = as_points(R, "R", dim=3)
    G = as_points(G, "G", dim=3)
    check_same_shape(R, G, "R", "G")
    w = _weights(weights, R.shape[0])
    return fit_motion(R, G, caller="register", weights=w, sensitivity=bool(return_sensitivity))
