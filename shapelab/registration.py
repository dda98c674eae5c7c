"""Optimal rotation, rigid registration and ICP (Notes §23.2, "Optimal rotation" and ICP).

Three layers, each built on the one before:

* :func:`optimal_rotation` — Horn's closed form, exactly as the notes derive it: the
  unit quaternion maximising :math:`q^TAq` with :math:`A = \\sum_j \\bar R_j^T G_j`,
  i.e. the *rotation about the origin* minimising
  :math:`\\sum_j \\lVert q r_j q^* - g_j\\rVert^2` for **paired** points.
* :func:`register` — the least-squares rigid motion (rotation *and* translation):
  centre both sets on their centroids, then :func:`optimal_rotation`.
* :func:`icp` — the Iterative Closest Point algorithm of the notes (four steps, cost
  :math:`\\mu(\\pi, i)`), whose step 2 is :func:`register`.

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
* **ICP: which set moves.** The cost :math:`\\mu(\\pi, i) = \\sum d^2(r_j,
  i(\\pi(r_j)))` applies :math:`i` to :math:`G`, but step 3 updates :math:`R \\leftarrow
  i(R)`.  Minimising the cost and then moving :math:`R` by that :math:`i` moves it the
  wrong way (one should apply :math:`i^{-1}` to :math:`R`).  Here the moving set is
  the ``source`` throughout: cost :math:`\\sum_j d^2(i(s_j), t_{\\pi(j)})`, step 3
  moves the source by the :math:`i` found in step 2.
* **ICP: the cost's name.** It is defined as :math:`\\mu` and then minimised as
  :math:`f` in steps 1–2 (and :math:`f` is also the rotation cost).  Step 4 speaks of
  the mean square error, :math:`\\mu/n`, not :math:`\\mu`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from ._toolkit.tolerances import ANDERSON_RCOND, ROTATION_EIGEN_GAP
from ._toolkit.validate import (
    as_finite_scalar,
    as_point,
    as_points,
    as_positive_int,
    as_vector,
    check_same_shape,
)
from ._toolkit.validate import as_float_array as _as_float_array
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
    "ICPResult",
    "icp",
    "closest_points",
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
    """


# --------------------------------------------------------------------------- Horn


def cross_covariance(R, G) -> np.ndarray:
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


def horn_matrix(R, G) -> np.ndarray:
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


def optimal_rotation(R, G, weights=None, *, return_sensitivity: bool = False):
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


def kabsch(R, G, *, proper: bool = True) -> np.ndarray:
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


def _register(R: np.ndarray, G: np.ndarray, *, caller: str, weights=None, sensitivity: bool = False):
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


def register(R, G, weights=None, *, return_sensitivity: bool = False):
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
    return _register(R, G, caller="register", weights=w, sensitivity=bool(return_sensitivity))


# --------------------------------------------------------------------------- ICP


@dataclass(frozen=True, eq=False)
class ICPResult:
    """The outcome of :func:`icp`.

    Attributes
    ----------
    motion : RigidMotion
        The total motion: ``motion.apply(source)`` lies on the target.
    mse : ndarray, shape (n_iter + 1,)
        The mean squared error :math:`\\mu(\\pi_k, i_k)/n` with the closest-point
        correspondence, before the first step (``mse[0]``, at ``init``) and after each
        of the ``n_iter`` steps.  Non-increasing.
    correspondence : ndarray of int, shape (n,)
        For each source point, the index of its closest target point at the final
        motion (``-1`` where farther than ``max_distance``).
    converged : bool
        True when the decrease of the MSE fell below ``tol`` (Notes §23.2, step 4);
        False when ``max_iter`` stopped the loop.
    n_iter : int
        Number of motions applied (steps 1–3 carried out).
    motions : tuple of RigidMotion
        The total motion after each step, ``motions[0]`` the initial one; length
        ``n_iter + 1``.
    correspondences : ndarray of int, shape (n_iter + 1, n), or None
        The correspondence at each motion, when ``icp(..., keep_history=True)``.

    See Also
    --------
    icp
        Produces it.
    """

    motion: RigidMotion
    mse: np.ndarray = field(repr=False)
    correspondence: np.ndarray = field(repr=False)
    converged: bool
    n_iter: int
    motions: tuple = field(repr=False, default=())
    correspondences: np.ndarray | None = field(repr=False, default=None)

    @property
    def rmse(self) -> float:
        """Root of the final mean squared error."""
        return float(np.sqrt(self.mse[-1]))


def closest_points(points, target, *, max_distance=None, tree=None):
    """Closest target point of every point (step 1 of ICP, Notes §23.2).

    Parameters
    ----------
    points : array_like, shape (n, 3)
    target : array_like, shape (m, 3)
    max_distance : float, optional
        Pairs farther apart get index ``-1`` and distance ``max_distance``.
    tree : scipy.spatial.cKDTree, optional
        A tree already built on ``target`` (it is then not rebuilt).

    Returns
    -------
    index : ndarray of int, shape (n,)
    distance : ndarray, shape (n,)

    See Also
    --------
    icp
        Step 1 of each iteration.
    scipy.spatial.cKDTree
        The nearest-neighbour search.

    References
    ----------
    .. [1] P. J. Besl and N. D. McKay, "A method for registration of 3-D shapes", *IEEE
           Trans. Pattern Anal. Mach. Intell.* 14(2):239-256, 1992. doi:10.1109/34.121791
    """
    points = as_points(points, "points", dim=3)
    target = as_points(target, "target", dim=3)
    dmax = np.inf if max_distance is None else as_finite_scalar(max_distance, "max_distance", positive=True)
    if tree is None:
        from scipy.spatial import cKDTree  # imported on first use: optimal_rotation needs no SciPy

        tree = cKDTree(target)
    return _closest(points, tree, target.shape[0], dmax)


def _closest(points: np.ndarray, tree, m: int, dmax: float):
    d, idx = tree.query(points, k=1, distance_upper_bound=dmax, workers=-1)
    miss = idx >= m
    if np.any(miss):
        idx = np.where(miss, -1, idx)
        d = np.where(miss, dmax, d)
    return idx.astype(np.intp, copy=False), d


def _morton_order(p: np.ndarray) -> np.ndarray:
    """A permutation putting nearby points next to each other (Z-order, 10 bits per axis).

    Querying a k-d tree in this order is much more cache-friendly than in random
    order; it changes no result.
    """
    lo = p.min(axis=0)
    span = float((p.max(axis=0) - lo).max()) or 1.0
    cell = np.minimum(((p - lo) * (1023.0 / span)).astype(np.uint64), 1023)

    def spread(v):  # insert two zero bits between the 10 bits of v
        v = (v | (v << np.uint64(16))) & np.uint64(0x030000FF)
        v = (v | (v << np.uint64(8))) & np.uint64(0x0300F00F)
        v = (v | (v << np.uint64(4))) & np.uint64(0x030C30C3)
        v = (v | (v << np.uint64(2))) & np.uint64(0x09249249)
        return v

    code = spread(cell[:, 0]) | (spread(cell[:, 1]) << np.uint64(1)) | (spread(cell[:, 2]) << np.uint64(2))
    return np.argsort(code, kind="stable")


class _Anderson:
    """Type-II Anderson acceleration of a fixed-point map x ↦ g(x) in R^6 (depth m)."""

    def __init__(self, m: int = 5):
        self.m = m
        self.g: list[np.ndarray] = []
        self.f: list[np.ndarray] = []

    def reset(self) -> None:
        self.g.clear()
        self.f.clear()

    def __call__(self, x: np.ndarray, g: np.ndarray) -> np.ndarray | None:
        self.g.append(g)
        self.f.append(g - x)
        if len(self.g) > self.m + 1:
            del self.g[0], self.f[0]
        if len(self.g) < 2:
            return None
        F = np.array(self.f)
        Gm = np.array(self.g)
        dF = np.diff(F, axis=0).T  # (6, k)
        dG = np.diff(Gm, axis=0).T
        gamma, *_ = np.linalg.lstsq(dF, F[-1], rcond=ANDERSON_RCOND)
        out = Gm[-1] - dG @ gamma
        return out if np.all(np.isfinite(out)) else None


def _to_params(motion: "RigidMotion", c: np.ndarray) -> np.ndarray:
    """6 numbers for a motion: its rotation vector and where it takes the point c."""
    return np.concatenate([motion.rotation.to_rotation_vector(), motion.apply(c)])


def _from_params(x: np.ndarray, c: np.ndarray) -> "RigidMotion":
    q = Quaternion.from_rotation_vector(x[:3])
    return RigidMotion(q, x[3:] - q.rotate(c))


def icp(
    source,
    target,
    *,
    tol: float = 1e-6,
    max_iter: int = 50,
    init: RigidMotion | None = None,
    max_distance: float | None = None,
    accelerate: bool = True,
    keep_history: bool = False,
) -> ICPResult:
    """Iterative Closest Point: move ``source`` onto ``target`` (Notes §23.2).

    The notes' four steps, with the source as the moving set:

    1. :math:`\\pi`: each moved source point :math:`i(s_j)` is paired with its closest
       target point (a k-d tree on the target, built once, queried on all cores);
    2. fix :math:`\\pi`, find the rigid motion minimising
       :math:`\\mu(\\pi, i) = \\sum_j d^2(i(s_j), t_{\\pi(j)})` (:func:`register`);
    3. move the source by it;
    4. stop when the mean squared error decreased by less than ``tol``.

    Parameters
    ----------
    source : array_like, shape (n, 3)
        The moving set, at least 3 points (the notes' :math:`R`).
    target : array_like, shape (m, 3)
        The fixed set, at least 3 points (the notes' :math:`G`); ``m`` may differ
        from ``n``.
    tol : float
        :math:`\\tau \\ge 0`, an absolute threshold on the decrease of the MSE (in
        squared length units), as in step 4 of the notes.
    max_iter : int
        At most this many iterations (0 only evaluates the start).
    init : RigidMotion, optional
        Starting motion of the source (default: identity).  ICP is a local method:
        from ``init`` the cost never increases and it ends (up to ``tol``) at a fixed
        point, a local minimum of the closest-point cost when the closest points
        there are unique.  Which one depends on ``init`` (near the boundary of two
        basins even on the last bits of the arithmetic, lesson 13); nothing makes it
        the global minimum.
    max_distance : float, optional
        Pairs farther apart than this are left out of step 2 (Open3D's
        ``max_correspondence_distance``).  The cost then counts every source point,
        an unmatched one with :math:`d^2 = \\text{max\\_distance}^2`, which keeps it
        monotone.
    accelerate : bool
        True (default): after step 2, also try an Anderson-extrapolated motion
        built from the last few steps, and keep it only if its cost (with fresh
        closest points) is not larger than the current one; otherwise take the
        plain step.  Same fixed points and the same monotone cost as the plain
        algorithm, in far fewer iterations (plain point-to-point ICP converges only
        linearly, slowly near the end).  False: the notes' algorithm literally,
        one plain step per iteration.
    keep_history : bool
        Also store the correspondence of every iteration (memory n × iterations).

    Returns
    -------
    ICPResult

    See Also
    --------
    register
        Step 2 of each iteration.
    closest_points
        Step 1.
    coarse_align
        Starting motions that avoid wrong local minima.

    Notes
    -----
    **Monotone cost.** Step 2 cannot increase :math:`\\mu` for fixed :math:`\\pi` (the
    old motion is a candidate) and step 1 cannot increase it for fixed :math:`i`
    (closest points are a candidate pairing), so the MSE never increases; an
    accelerated step is accepted only if it does not increase it either.  In floating
    point a plain step that would raise it by rounding is rejected and the loop stops
    as converged, so ``result.mse`` is non-increasing exactly.

    **Failure modes.** ICP only finds a *local* minimum (Besl and McKay 1992: the mean
    squared distance decreases monotonically to a local minimum).  On a symmetric shape (a
    sphere, a cube) many motions give the same small cost and ICP can stop at a wrong
    rotation with ``converged=True`` — a small MSE does not certify the right
    motion.  Large initial rotations (more than roughly 30–60° on elongated shapes)
    may also end in a wrong local minimum.

    **Cost.** Each iteration is one k-d tree query of all source points (two when an
    accelerated step is rejected) plus O(n) work.  The source is queried in a
    space-filling-curve order (cache-friendly); results are reported in the
    caller's order.

    References
    ----------
    .. [1] P. J. Besl and N. D. McKay, "A method for registration of 3-D shapes", *IEEE
           Trans. Pattern Anal. Mach. Intell.* 14(2):239-256, 1992. doi:10.1109/34.121791
    .. [2] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629

    Examples
    --------
    >>> from shapelab.datasets import sample_shape
    >>> src = sample_shape("lumpy", 400, seed=1)
    >>> true = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], np.radians(10)), [0.1, 0, 0])
    >>> res = icp(src, true.apply(src))
    >>> bool(res.converged), res.motion.rotation.angle_to(true.rotation) < 1e-4
    (True, True)
    """
    src = as_points(source, "source", dim=3, min_points=3)
    tgt = as_points(target, "target", dim=3, min_points=3)
    tol = as_finite_scalar(tol, "tol", nonnegative=True)
    max_iter = as_positive_int(max_iter, "max_iter", minimum=0)
    if init is None:
        init = RigidMotion()
    elif not isinstance(init, RigidMotion):
        raise TypeError(f"init must be a RigidMotion or None, got {type(init).__name__}")
    dmax = np.inf if max_distance is None else as_finite_scalar(max_distance, "max_distance", positive=True)
    if not isinstance(accelerate, (bool, np.bool_)):
        raise TypeError(f"accelerate must be True or False, got {type(accelerate).__name__}")

    order = _morton_order(src)
    unorder = np.empty_like(order)
    unorder[order] = np.arange(order.size)
    src = np.ascontiguousarray(src[order])
    c = src.mean(axis=0)

    from scipy.spatial import cKDTree

    tree = cKDTree(tgt)
    m = tgt.shape[0]

    def evaluate(motion):
        moved = motion.apply(src)
        idx, d = _closest(moved, tree, m, dmax)
        return moved, idx, float(np.mean(d * d))

    motion = init
    moved, idx, cost = evaluate(motion)
    mse = [cost]
    motions = [motion]
    history = [idx[unorder]] if keep_history else None
    aa = _Anderson() if accelerate else None
    converged = False
    for _ in range(max_iter):
        ok = idx >= 0
        if np.count_nonzero(ok) < 3:
            break  # nothing left to register: stop, not converged
        step = _register(moved[ok], tgt[idx[ok]], caller="icp")
        plain = step @ motion
        candidate = None
        if aa is not None:
            x_aa = aa(_to_params(motion, c), _to_params(plain, c))
            if x_aa is not None and np.linalg.norm(x_aa[:3]) < 0.95 * np.pi:
                trial = _from_params(x_aa, c)
                t_moved, t_idx, t_cost = evaluate(trial)
                if t_cost <= cost:
                    candidate = (trial, t_moved, t_idx, t_cost)
                else:
                    aa.reset()
                    aa(_to_params(motion, c), _to_params(plain, c))
        if candidate is None:
            p_moved, p_idx, p_cost = evaluate(plain)
            if p_cost > cost:  # only rounding can do this; keep the better motion
                converged = True
                break
            candidate = (plain, p_moved, p_idx, p_cost)
        motion, moved, idx, new_cost = candidate
        mse.append(new_cost)
        motions.append(motion)
        if keep_history:
            history.append(idx[unorder])
        decrease = cost - new_cost
        cost = new_cost
        if decrease < tol or (tol == 0 and decrease == 0):
            converged = True
            break
    return ICPResult(
        motion=motion,
        mse=_readonly(mse),
        correspondence=idx[unorder],
        converged=converged,
        n_iter=len(mse) - 1,
        motions=tuple(motions),
        correspondences=None if history is None else np.stack(history),
    )
