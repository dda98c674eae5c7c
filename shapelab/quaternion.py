"""Quaternions and rotations in 3D (Notes §23.2, "Rotations in 3D and quaternions").

A quaternion :math:`q = q_0 + q_1\\mathbf i + q_2\\mathbf j + q_3\\mathbf k` is stored as
the four real numbers ``(w, x, y, z) = (q0, q1, q2, q3)``, scalar part first, as in
the notes and in Horn (1987).  (SciPy's :class:`scipy.spatial.transform.Rotation`
uses the *other* order, ``(x, y, z, w)``; see :func:`to_scipy_order`.)

Two layers:

* :class:`Quaternion`: one immutable quaternion with the algebra of the notes
  (Hamilton product, conjugate, norm, inner product), inverse and division
  (:math:`q/r = qr^{-1}`), :meth:`~Quaternion.exp`, :meth:`~Quaternion.log` and powers
  ``q ** t`` (numpy-quaternion's conventions), the matrix forms
  :math:`Q` (left multiplication) and :math:`\\bar Q` (right multiplication), and the
  conversions to and from axis-angle and rotation matrices.
* array functions on stacks of quaternions of shape ``(..., 4)``: :func:`qmul`,
  :func:`qconj`, :func:`qnorm`, :func:`qnormalize`, :func:`qrotate`,
  :func:`qmatrix`, :func:`qfrom_matrix`, :func:`left_matrices`,
  :func:`right_matrices`.  They do the work for the class, for
  :mod:`shapelab.registration`, and for lessons that need many quaternions at once.

Rotation convention
-------------------
The unit quaternion :math:`q = \\cos(\\theta/2) + \\sin(\\theta/2)(u_x\\mathbf i + u_y\\mathbf j
+ u_z\\mathbf k)` rotates a vector :math:`r` (as the pure quaternion
:math:`0 + r_x\\mathbf i + r_y\\mathbf j + r_z\\mathbf k`) by :math:`I_q(r) = q r q^*`:
a rotation by :math:`\\theta` about :math:`u`, counter-clockwise when :math:`u` points
at the viewer (right-hand rule).  The notes do not state the handedness.
:math:`q` and :math:`-q` give the same rotation (the notes call :math:`q` a point of
:math:`\\mathbb S^3`; rotations are really *antipodal pairs* of such points).

Non-unit quaternions
--------------------
For any non-zero :math:`q`, :math:`q r q^* = \\lVert q\\rVert^2 R(q/\\lVert q\\rVert)\\,r` is
a rotation *scaled* by :math:`\\lVert q\\rVert^2`.  Everything here that treats a
quaternion *as a rotation* (:meth:`Quaternion.rotate`, :meth:`Quaternion.to_matrix`,
:meth:`Quaternion.to_axis_angle`, :func:`qrotate`, :func:`qmatrix`) first
**normalises** it, so it always returns a proper rotation, and raises
:class:`ValueError` for the zero quaternion, which is no rotation at all.  The raw
sandwich product is still available as ``q * Quaternion(0, *r) * q.conjugate()``.

Where the notes are wrong
-------------------------
* The component formula of :math:`q\\cdot r` has the wrong sign in the
  :math:`\\mathbf k` part: it reads :math:`q_0r_3 - q_1r_2 + q_2r_1 + q_3r_0`, but
  :math:`\\mathbf{ij} = \\mathbf k` forces :math:`q_0r_3 + q_1r_2 - q_2r_1 + q_3r_0`
  (the notes' own matrix has the right sign).
* The matrix form multiplies the matrix of :math:`q`'s entries by the vector of
  :math:`q` itself and calls the result :math:`Rq`; it must be :math:`Q\\,r`
  (:meth:`Quaternion.left_matrix`).
* ":math:`\\bar Q` is the matrix orthogonal to :math:`Q`" is wrong: :math:`\\bar Q` is
  not orthogonal to :math:`Q` in any sense (:math:`Q^T\\bar Q \\ne 0`).  Both are
  orthogonal matrices when :math:`\\lVert q\\rVert = 1`, and they *commute*.  The
  recipe "transpose the lower-right 3×3 block of :math:`Q`" is right.
* :math:`I_q(r) = \\bar Q^T Q r` is right, as a 4×4 identity on pure quaternions; its
  lower-right 3×3 block is the rotation matrix (:meth:`Quaternion.to_matrix`).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.tolerances import QLOG_SMALL_VECTOR, ROTVEC_SERIES_ANGLE
from ._toolkit.validate import as_finite_scalar, as_point, as_vector
from ._toolkit.validate import as_float_array as _as_float_array
from ._toolkit.validate import check_finite as _check_finite

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = [
    "Quaternion",
    "qmul",
    "qconj",
    "qnorm",
    "qnormalize",
    "qrotate",
    "qmatrix",
    "qfrom_matrix",
    "qfrom_axis_angle",
    "left_matrices",
    "right_matrices",
    "rotation_angle",
    "to_scipy_order",
    "from_scipy_order",
]

# --------------------------------------------------------------------------- arrays


def _as_quats(q, name: str) -> np.ndarray:
    """Validate an array of quaternions of shape (..., 4), finite float64."""
    arr = _as_float_array(q, name)
    if arr.ndim == 0 or arr.shape[-1] != 4:
        raise ValueError(f"{name} must have shape (4,) or (n, 4) (w, x, y, z), got shape {arr.shape}")
    _check_finite(arr, name)
    return arr


def qmul(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """Hamilton product of quaternion arrays, broadcast over leading axes.

    Parameters
    ----------
    a, b : array_like, shape (..., 4)
        Quaternions ``(w, x, y, z)``.

    Returns
    -------
    ndarray, shape (..., 4)
        :math:`a\\cdot b` with :math:`(a_0 b_0 - \\vec a\\cdot\\vec b,\\;
        a_0\\vec b + b_0\\vec a + \\vec a\\times\\vec b)`, the product of Notes §23.2 with
        the sign of the :math:`\\mathbf k` part corrected (see the module docstring).

    See Also
    --------
    Quaternion
        The same product on one quaternion (``a * b``).
    left_matrices
        The product as a matrix, ``a * b = Q(a) b``.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629

    Examples
    --------
    >>> qmul([0, 1, 0, 0], [0, 0, 1, 0])  # i j = k
    array([0., 0., 0., 1.])
    >>> qmul([0, 0, 1, 0], [0, 1, 0, 0])  # j i = -k
    array([ 0.,  0.,  0., -1.])
    """
    a = _as_quats(a, "a")
    b = _as_quats(b, "b")
    a0, a1, a2, a3 = np.moveaxis(a, -1, 0)
    b0, b1, b2, b3 = np.moveaxis(b, -1, 0)
    return np.stack(
        [
            a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
            a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
            a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
            a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
        ],
        axis=-1,
    )


def qconj(q) -> np.ndarray:
    """Conjugates :math:`q^* = q_0 - q_1\\mathbf i - q_2\\mathbf j - q_3\\mathbf k` (Notes §23.2).

    See Also
    --------
    qmul
        The product; ``q * qconj(q) = |q|^2``.
    qnorm
        The norm.
    """
    q = _as_quats(q, "q")
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def qnorm(q) -> np.ndarray:
    """Norms :math:`\\lVert q\\rVert = \\sqrt{q_0^2+q_1^2+q_2^2+q_3^2}`, shape (...).

    See Also
    --------
    qnormalize
        Divide by the norm.
    qconj
        ``q q* = |q|^2``.
    """
    q = _as_quats(q, "q")
    return np.linalg.norm(q, axis=-1)


def unit_quaternions(q: np.ndarray, name: str) -> np.ndarray:
    """q / |q| without overflow or underflow; the zero quaternion raises ValueError.

    Shared with :mod:`shapelab.registration` (trusted arrays, validated by the caller);
    not part of the public API."""
    big = np.abs(q).max(axis=-1, keepdims=True)
    if np.any(big == 0):
        bad = np.argwhere(big[..., 0] == 0)
        where = "" if q.ndim == 1 else f" (at index {tuple(int(i) for i in bad[0])})"
        raise ValueError(f"{name} is the zero quaternion{where}, which does not represent a rotation")
    s = q / big
    return s / np.linalg.norm(s, axis=-1, keepdims=True)


def qnormalize(q) -> np.ndarray:
    """Unit quaternions :math:`q/\\lVert q\\rVert`; the zero quaternion raises ValueError.

    See Also
    --------
    qnorm
        The norm.
    qmatrix
        Rotation matrices of unit quaternions.
    """
    return unit_quaternions(_as_quats(q, "q"), "q")


def qmatrix(q) -> np.ndarray:
    """Rotation matrices of (normalised) quaternions, shape (..., 3, 3).

    The matrix :math:`M` with :math:`M r = q r q^*` for a unit :math:`q`, i.e. the
    lower-right 3×3 block of :math:`\\bar Q^T Q` (Notes §23.2, :math:`I_q`).

    See Also
    --------
    qrotate
        Rotate points directly.
    qfrom_matrix
        The inverse map, up to sign.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629
    """
    w, x, y, z = np.moveaxis(unit_quaternions(_as_quats(q, "q"), "q"), -1, 0)
    xx, yy, zz = x * x, y * y, z * z
    xy, xz, yz = x * y, x * z, y * z
    wx, wy, wz = w * x, w * y, w * z
    m = np.stack(
        [
            1 - 2 * (yy + zz),
            2 * (xy - wz),
            2 * (xz + wy),
            2 * (xy + wz),
            1 - 2 * (xx + zz),
            2 * (yz - wx),
            2 * (xz - wy),
            2 * (yz + wx),
            1 - 2 * (xx + yy),
        ],
        axis=-1,
    )
    return m.reshape(m.shape[:-1] + (3, 3))


def qrotate(q, points) -> np.ndarray:
    """Rotate points by (normalised) quaternions, vectorised: :math:`q r q^*`.

    Parameters
    ----------
    q : array_like, shape (4,) or (n, 4)
        One rotation for all points, or one per point.
    points : array_like, shape (3,) or (n, 3)

    Returns
    -------
    ndarray, shape like ``points`` (or (n, 3) when ``q`` has n rows)

    See Also
    --------
    qmatrix
        The rotation matrix of the same quaternion.
    Quaternion.rotate
        One quaternion.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629
    """
    q = _as_quats(q, "q")
    p = np.asarray(as_points3(points, "points"))
    m = qmatrix(q)
    if q.ndim == 1:
        return p @ m.T
    return np.einsum("...ij,...j->...i", m, p)


def as_points3(points, name: str) -> np.ndarray:
    """``points`` as a float array of shape (3,) or (n, 3), finite (shared with
    :mod:`shapelab.registration`; not part of the public API)."""
    arr = _as_float_array(points, name)
    if arr.ndim not in (1, 2) or arr.shape[-1] != 3:
        raise ValueError(f"{name} must have shape (3,) or (n, 3), got shape {arr.shape}")
    _check_finite(arr, name)
    return arr


def qfrom_matrix(m, *, atol: float = 1e-6) -> np.ndarray:
    """Unit quaternions of rotation matrices, Shepperd's method, shape (..., 4).

    For each matrix the largest of :math:`4q_0^2 = 1 + \\operatorname{tr} M` and
    :math:`4q_i^2 = 1 + 2M_{ii} - \\operatorname{tr} M` is taken first, so no division
    by a small number happens (Shepperd 1978).  The result has :math:`q_0 \\ge 0`.

    Parameters
    ----------
    m : array_like, shape (3, 3) or (n, 3, 3)
        Proper rotation matrices: :math:`M^TM = I` and :math:`\\det M = +1` within
        ``atol``.  Anything else (a reflection, a scaling) raises ValueError.

    See Also
    --------
    qmatrix
        The forward map.
    scipy.spatial.transform.Rotation.as_quat
        SciPy's, in (x, y, z, w) order.

    References
    ----------
    .. [1] S. W. Shepperd, "Quaternion from rotation matrix", *J. Guid. Control*
           1(3):223-224, 1978. doi:10.2514/3.55767b
    """
    m = _as_float_array(m, "matrix")
    if m.ndim < 2 or m.shape[-2:] != (3, 3):
        raise ValueError(f"matrix must have shape (3, 3) or (n, 3, 3), got shape {m.shape}")
    _check_finite(m, "matrix")
    eye = np.eye(3)
    err = np.abs(np.swapaxes(m, -1, -2) @ m - eye).max(axis=(-1, -2))
    if np.any(err > atol):
        raise ValueError(f"matrix must be orthogonal (M^T M = I within {atol:g}); deviation {err.max():.3g}")
    det = np.linalg.det(m)
    if np.any(det < 0):
        raise ValueError("matrix has determinant -1: it is a reflection, not a rotation; no quaternion represents it")
    tr = m[..., 0, 0] + m[..., 1, 1] + m[..., 2, 2]
    # 4 q_k^2 for k = 0..3
    d = np.stack([1 + tr, 1 + 2 * m[..., 0, 0] - tr, 1 + 2 * m[..., 1, 1] - tr, 1 + 2 * m[..., 2, 2] - tr], -1)
    k = np.argmax(d, axis=-1)
    s = np.sqrt(np.maximum(np.take_along_axis(d, k[..., None], -1)[..., 0], 0.0))  # = 2|q_k|
    m21_12 = m[..., 2, 1] - m[..., 1, 2]  # 4 q0 q1
    m02_20 = m[..., 0, 2] - m[..., 2, 0]  # 4 q0 q2
    m10_01 = m[..., 1, 0] - m[..., 0, 1]  # 4 q0 q3
    m01_10 = m[..., 0, 1] + m[..., 1, 0]  # 4 q1 q2
    m02p20 = m[..., 0, 2] + m[..., 2, 0]  # 4 q1 q3
    m12_21 = m[..., 1, 2] + m[..., 2, 1]  # 4 q2 q3
    # each row: the four products 4 q_k q_l for l = 0..3 (with 4 q_k^2 = s^2)
    rows = np.stack(
        [
            np.stack([s * s, m21_12, m02_20, m10_01], -1),
            np.stack([m21_12, s * s, m01_10, m02p20], -1),
            np.stack([m02_20, m01_10, s * s, m12_21], -1),
            np.stack([m10_01, m02p20, m12_21, s * s], -1),
        ],
        -2,
    )
    num = np.take_along_axis(rows, k[..., None, None], -2)[..., 0, :]
    q = num / (2.0 * s)[..., None]
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    return np.where(q[..., :1] < 0, -q, q)


def qfrom_axis_angle(axis, angle) -> np.ndarray:
    """Unit quaternions :math:`\\cos(\\theta/2) + \\sin(\\theta/2)\\,u` (Notes §23.2).

    ``axis`` (shape (..., 3), non-zero, normalised here) and ``angle`` (radians,
    shape (...)) broadcast against each other.

    See Also
    --------
    rotation_angle
        The angle between two rotations.
    Quaternion.from_axis_angle
        One quaternion.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629
    """
    u = _as_float_array(axis, "axis")
    if u.ndim == 0 or u.shape[-1] != 3:
        raise ValueError(f"axis must have shape (3,) or (n, 3), got shape {u.shape}")
    _check_finite(u, "axis")
    t = _as_float_array(angle, "angle")
    _check_finite(t, "angle")
    n = np.linalg.norm(u, axis=-1, keepdims=True)
    if np.any(n == 0):
        raise ValueError("axis must be a non-zero vector; the zero vector has no direction to rotate about")
    u = u / n
    lead = np.broadcast_shapes(t.shape, u.shape[:-1])
    half = 0.5 * t[..., None]
    c = np.broadcast_to(np.cos(half), lead + (1,))
    v = np.broadcast_to(np.sin(half) * u, lead + (3,))
    return np.concatenate([c, v], axis=-1)


def _qexp(v: np.ndarray) -> np.ndarray:
    """Unit quaternions of rotation vectors (..., 3), stable at zero angle."""
    theta = np.linalg.norm(v, axis=-1, keepdims=True)
    half = 0.5 * theta
    # sin(θ/2)/θ, with its Taylor series near 0
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.where(theta > ROTVEC_SERIES_ANGLE, np.sin(half) / np.where(theta > 0, theta, 1.0), 0.5 - theta**2 / 48.0)
    return np.concatenate([np.cos(half), k * v], axis=-1)


def _qlog(q: np.ndarray) -> np.ndarray:
    """Rotation vectors (angle in [0, π]) of unit quaternions (..., 4)."""
    q = np.where(q[..., :1] < 0, -q, q)
    s = np.linalg.norm(q[..., 1:], axis=-1, keepdims=True)
    angle = 2.0 * np.arctan2(s, q[..., :1])
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.where(s > QLOG_SMALL_VECTOR, angle / np.where(s > 0, s, 1.0), 2.0)
    return k * q[..., 1:]


def _left(q: np.ndarray) -> np.ndarray:
    w, x, y, z = np.moveaxis(q, -1, 0)
    m = np.stack([w, -x, -y, -z, x, w, -z, y, y, z, w, -x, z, -y, x, w], -1)
    return m.reshape(m.shape[:-1] + (4, 4))


def _right(q: np.ndarray) -> np.ndarray:
    w, x, y, z = np.moveaxis(q, -1, 0)
    m = np.stack([w, -x, -y, -z, x, w, z, -y, y, -z, w, x, z, y, -x, w], -1)
    return m.reshape(m.shape[:-1] + (4, 4))


def left_matrices(q: ArrayLike) -> np.ndarray:
    """The matrices :math:`Q` with :math:`q\\cdot r = Q r`, shape (..., 4, 4) (Notes §23.2).

    A pure 3-vector (shape (..., 3)) is read as the quaternion :math:`0 + r`.

    See Also
    --------
    right_matrices
        The matrices of right multiplication.
    shapelab.registration.horn_matrix
        Built from these matrices.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629

    Examples
    --------
    >>> import numpy as np
    >>> q, r = np.array([1.0, 2.0, 3.0, 4.0]), np.array([0.5, -1.0, 0.0, 2.0])
    >>> bool(np.allclose(left_matrices(q) @ r, qmul(q, r)))
    True
    """
    q = np.asarray(q, dtype=np.float64)
    if q.ndim >= 1 and q.shape[-1] == 3:
        q = np.concatenate([np.zeros(q.shape[:-1] + (1,)), q], -1)
    return _left(_as_quats(q, "q"))


def right_matrices(q: ArrayLike) -> np.ndarray:
    """The matrices :math:`\\bar Q` with :math:`r\\cdot q = \\bar Q r`, shape (..., 4, 4).

    :math:`\\bar Q` is :math:`Q` with its lower-right 3×3 block transposed (Notes §23.2).
    A pure 3-vector (shape (..., 3)) is read as the quaternion :math:`0 + r`.

    See Also
    --------
    left_matrices
        The matrices of left multiplication.
    shapelab.registration.horn_matrix
        Built from these matrices.

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629

    Examples
    --------
    >>> import numpy as np
    >>> q, r = np.array([1.0, 2.0, 3.0, 4.0]), np.array([0.5, -1.0, 0.0, 2.0])
    >>> bool(np.allclose(right_matrices(q) @ r, qmul(r, q)))
    True
    """
    q = np.asarray(q, dtype=np.float64)
    if q.ndim >= 1 and q.shape[-1] == 3:
        q = np.concatenate([np.zeros(q.shape[:-1] + (1,)), q], -1)
    return _right(_as_quats(q, "q"))


def rotation_angle(a, b) -> np.ndarray:
    """Angle (radians, in [0, π]) of the rotation taking rotation ``a`` to rotation ``b``.

    Invariant under the sign of either quaternion; computed as
    :math:`2\\operatorname{atan2}(\\lVert\\vec c\\rVert, |c_0|)` with :math:`c = a^* b`
    (normalised), which stays accurate for tiny angles, unlike :math:`2\\arccos`.

    See Also
    --------
    qfrom_axis_angle
        A rotation from its axis and angle.

    References
    ----------
    .. [1] K. Shoemake, "Animating rotation with quaternion curves", *SIGGRAPH '85*,
           *Comput. Graph.* 19(3):245-254, 1985. doi:10.1145/325165.325242
    """
    a = unit_quaternions(_as_quats(a, "a"), "a")
    b = unit_quaternions(_as_quats(b, "b"), "b")
    c = qmul(qconj(a), b)
    return 2.0 * np.arctan2(np.linalg.norm(c[..., 1:], axis=-1), np.abs(c[..., 0]))


def to_scipy_order(q: ArrayLike) -> np.ndarray:
    """``(w, x, y, z)`` → ``(x, y, z, w)``, the order of SciPy's ``Rotation.from_quat``.

    See Also
    --------
    from_scipy_order
        The inverse.
    scipy.spatial.transform.Rotation
        SciPy's rotations.

    Examples
    --------
    >>> to_scipy_order([1.0, 2.0, 3.0, 4.0])  # (w, x, y, z) -> SciPy's (x, y, z, w)
    array([2., 3., 4., 1.])
    """
    q = _as_quats(q, "q")
    return np.concatenate([q[..., 1:], q[..., :1]], -1)


def from_scipy_order(q) -> np.ndarray:
    """``(x, y, z, w)`` (SciPy's ``Rotation.as_quat``) → ``(w, x, y, z)``.

    See Also
    --------
    to_scipy_order
        The inverse.
    scipy.spatial.transform.Rotation
        SciPy's rotations.
    """
    q = _as_quats(q, "q")
    return np.concatenate([q[..., 3:], q[..., :3]], -1)


# --------------------------------------------------------------------------- class


def _scalar(v, name: str) -> float:
    return as_finite_scalar(v, name)


@dataclass(frozen=True, slots=True)
class Quaternion:
    """An immutable quaternion :math:`w + x\\mathbf i + y\\mathbf j + z\\mathbf k` (Notes §23.2).

    Parameters
    ----------
    w, x, y, z : float
        The notes' :math:`q_0, q_1, q_2, q_3`; finite, stored as float64.

    See Also
    --------
    qmul
        Vectorised products of arrays of quaternions.
    optimal_rotation
        The optimal rotation as a unit quaternion.

    Notes
    -----
    ``*`` is the Hamilton product (and scaling by a real number), ``+``/``-`` are
    componentwise, ``==`` is exact equality of the components (use
    :meth:`isclose`, or :meth:`same_rotation` which also accepts :math:`-q`).

    References
    ----------
    .. [1] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629
    .. [2] K. Shoemake, "Animating rotation with quaternion curves", *SIGGRAPH '85*,
           *Comput. Graph.* 19(3):245-254, 1985. doi:10.1145/325165.325242

    Examples
    --------
    >>> i, j, k = Quaternion(0, 1, 0, 0), Quaternion(0, 0, 1, 0), Quaternion(0, 0, 0, 1)
    >>> i * j == k, i * j * k
    (True, Quaternion(w=-1.0, x=0.0, y=0.0, z=0.0))
    """

    w: float
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0

    __array_ufunc__ = None  # numpy scalars defer to our __rmul__ instead of broadcasting

    def __init__(self, w, x=0.0, y=0.0, z=0.0):
        for name, v in (("w", w), ("x", x), ("y", y), ("z", z)):
            object.__setattr__(self, name, _scalar(v, name))

    # ---------------------------------------------------------------- construction
    @classmethod
    def from_array(cls, q) -> "Quaternion":
        """From a 4-array ``(w, x, y, z)``."""
        a = as_vector(q, "q", length=4)
        return cls(*a)

    @classmethod
    def identity(cls) -> "Quaternion":
        """The identity rotation :math:`1 + 0\\mathbf i + 0\\mathbf j + 0\\mathbf k`."""
        return cls(1.0)

    @classmethod
    def pure(cls, v) -> "Quaternion":
        """The pure quaternion :math:`0 + v_x\\mathbf i + v_y\\mathbf j + v_z\\mathbf k` of a 3-vector."""
        v = as_point(v, "v", dim=3)
        return cls(0.0, *v)

    @classmethod
    def from_axis_angle(cls, axis, angle) -> "Quaternion":
        """The unit quaternion :math:`\\cos(\\theta/2) + \\sin(\\theta/2)\\,u` (Notes §23.2).

        Parameters
        ----------
        axis : array_like, shape (3,)
            Non-zero; normalised here.
        angle : float
            :math:`\\theta` in radians, right-hand rule about ``axis``.
        """
        axis = as_point(axis, "axis", dim=3)
        angle = as_finite_scalar(angle, "angle")
        return cls(*qfrom_axis_angle(axis, angle))

    @classmethod
    def from_matrix(cls, matrix, *, atol: float = 1e-6) -> "Quaternion":
        """The unit quaternion (with :math:`w \\ge 0`) of a 3×3 rotation matrix.

        Shepperd's method (see :func:`qfrom_matrix`); reflections and non-orthogonal
        matrices raise ValueError.
        """
        m = np.asarray(matrix)
        if m.shape != (3, 3):
            raise ValueError(f"matrix must have shape (3, 3), got shape {m.shape}")
        return cls(*qfrom_matrix(m, atol=atol))

    # ---------------------------------------------------------------- arrays
    def as_array(self) -> np.ndarray:
        """The components as a float64 array ``(w, x, y, z)``."""
        return np.array([self.w, self.x, self.y, self.z], dtype=np.float64)

    def __array__(self, dtype=None, copy=None):
        a = self.as_array()
        return a if dtype is None else a.astype(dtype)

    @property
    def scalar(self) -> float:
        """The real part :math:`q_0`."""
        return self.w

    @property
    def vector(self) -> np.ndarray:
        """The imaginary part :math:`(q_1, q_2, q_3)`."""
        return np.array([self.x, self.y, self.z], dtype=np.float64)

    # ---------------------------------------------------------------- algebra
    def __mul__(self, other):
        if isinstance(other, Quaternion):
            return Quaternion(*qmul(self.as_array(), other.as_array()))
        if isinstance(other, numbers.Real) and not isinstance(other, bool):
            s = _scalar(other, "scalar")
            return Quaternion(self.w * s, self.x * s, self.y * s, self.z * s)
        return NotImplemented

    def __rmul__(self, other):
        if isinstance(other, numbers.Real) and not isinstance(other, bool):
            return self.__mul__(other)  # real scalars commute with quaternions
        return NotImplemented

    def __truediv__(self, other):
        """``q / r`` is :math:`q\\,r^{-1}` (right division, numpy-quaternion's convention);
        ``q / s`` divides every component by the real ``s``."""
        if isinstance(other, Quaternion):
            return self * other._inverse("divisor")
        if isinstance(other, numbers.Real) and not isinstance(other, bool):
            s = _scalar(other, "divisor")
            if s == 0:
                raise ZeroDivisionError("division of a quaternion by zero")
            return self * (1.0 / s)
        return NotImplemented

    def __rtruediv__(self, other):
        """``s / q`` is :math:`s\\,q^{-1}` for a real ``s``."""
        if isinstance(other, numbers.Real) and not isinstance(other, bool):
            return self._inverse("divisor") * _scalar(other, "dividend")
        return NotImplemented

    def __pow__(self, t):
        """``q ** t``: an integer ``t`` by repeated products, a real ``t`` as
        :math:`\\exp(t\\log q)`; see :meth:`power`."""
        if isinstance(t, bool) or not isinstance(t, numbers.Real):
            return NotImplemented
        return self.power(t)

    def __add__(self, other):
        if isinstance(other, Quaternion):
            return Quaternion(self.w + other.w, self.x + other.x, self.y + other.y, self.z + other.z)
        return NotImplemented

    def __sub__(self, other):
        if isinstance(other, Quaternion):
            return Quaternion(self.w - other.w, self.x - other.x, self.y - other.y, self.z - other.z)
        return NotImplemented

    def __neg__(self):
        return Quaternion(-self.w, -self.x, -self.y, -self.z)

    def conjugate(self) -> "Quaternion":
        """:math:`q^* = q_0 - q_1\\mathbf i - q_2\\mathbf j - q_3\\mathbf k` (Notes §23.2)."""
        return Quaternion(self.w, -self.x, -self.y, -self.z)

    def norm(self) -> float:
        """:math:`\\lVert q\\rVert = \\sqrt{q_0^2+q_1^2+q_2^2+q_3^2}` (Notes §23.2)."""
        return float(math.hypot(self.w, self.x, self.y, self.z))

    def inner(self, other: "Quaternion") -> float:
        """:math:`\\langle q, r\\rangle = q_0r_0 + q_1r_1 + q_2r_2 + q_3r_3` (Notes §23.2)."""
        if not isinstance(other, Quaternion):
            raise TypeError(f"other must be a Quaternion, got {type(other).__name__}")
        return float(self.w * other.w + self.x * other.x + self.y * other.y + self.z * other.z)

    def normalized(self) -> "Quaternion":
        """:math:`q/\\lVert q\\rVert`; the zero quaternion raises ValueError."""
        return Quaternion(*unit_quaternions(self.as_array(), "quaternion"))

    def _inverse(self, name: str) -> "Quaternion":
        a = self.as_array()
        big = float(np.abs(a).max())
        if big == 0.0:
            raise ValueError(f"{name} is the zero quaternion, which has no inverse")
        s = a / big  # scaled first: |q|^2 neither overflows nor underflows
        with np.errstate(over="ignore"):
            inv = s * np.array([1.0, -1.0, -1.0, -1.0]) / (float(s @ s) * big)
        if not np.all(np.isfinite(inv)):  # |q| below 1/1.8e308 (subnormal components)
            raise OverflowError(f"the inverse of {name} {self!r} overflows float64")
        return Quaternion(*inv)

    def inverse(self) -> "Quaternion":
        """The multiplicative inverse :math:`q^{-1} = q^*/\\lVert q\\rVert^2` (Notes §23.2).

        :math:`q\\,q^{-1} = q^{-1}q = 1`; for a unit quaternion it is the conjugate, the
        inverse rotation.  The zero quaternion has none: ValueError; one whose inverse
        exceeds float64 (components below about 5e-309): OverflowError.

        See Also
        --------
        conjugate, power

        Examples
        --------
        >>> q = Quaternion(1, 2, 3, 4)
        >>> (q * q.inverse()).isclose(Quaternion(1.0), atol=1e-15)
        True
        >>> Quaternion(0, 2, 0, 0).inverse()
        Quaternion(w=0.0, x=-0.5, y=-0.0, z=-0.0)
        """
        return self._inverse("quaternion")

    def exp(self) -> "Quaternion":
        """The exponential :math:`e^q = e^{q_0}(\\cos\\lVert v\\rVert +
        \\tfrac{\\sin\\lVert v\\rVert}{\\lVert v\\rVert}\\,v)`, :math:`v = (q_1, q_2, q_3)`.

        The power series :math:`\\sum q^k/k!`.  For a pure :math:`q = \\tfrac\\theta2 u`
        (unit :math:`u`) it is the unit quaternion of the rotation by :math:`\\theta`
        about :math:`u` (Notes §23.2), so ``Quaternion.pure(v / 2).exp()`` equals
        ``Quaternion.from_rotation_vector(v)``.  :math:`e^{p+q} = e^pe^q` only when
        :math:`p` and :math:`q` commute.  OverflowError when a component of the result
        exceeds float64 (:math:`e^{q_0}` alone may: ``q.log().exp()`` is ``q`` up to
        :math:`\\lVert q\\rVert \\approx 2\\cdot10^{308}`).

        See Also
        --------
        log, power, from_rotation_vector

        References
        ----------
        .. [1] M. Boyle, numpy-quaternion (``np.exp`` on quaternions), same formula.
        .. [2] Wikipedia, "Quaternion", section "Exponential, logarithm, and power functions".

        Examples
        --------
        >>> print(Quaternion(0, np.pi / 2, 0, 0).exp())
        0 +1i +0j +0k
        """
        b = math.hypot(self.x, self.y, self.z)
        c = math.cos(b)
        s = [math.sin(b) * (v / b) if b > 0.0 else v for v in (self.x, self.y, self.z)]
        try:
            e = math.exp(self.w)
            out = [e * c] + [e * v for v in s]
        except OverflowError:
            # e^w overflows for w > 709.78 while e^w cos|v| may not (the exp of the log of
            # a quaternion of norm above 1.8e308): e^(w/2) times e^(w/2) cos|v|.
            try:
                h = math.exp(self.w / 2)
            except OverflowError:
                h = math.inf
            out = [h * (h * c)] + [h * (h * v) for v in s]
        if not all(math.isfinite(v) for v in out):
            raise OverflowError(f"exp of a quaternion with real part {self.w!r} overflows float64")
        return Quaternion(*out)

    def log(self) -> "Quaternion":
        """The principal logarithm :math:`\\ln\\lVert q\\rVert + \\operatorname{atan2}(\\lVert
        v\\rVert, q_0)\\,v/\\lVert v\\rVert`, :math:`v = (q_1, q_2, q_3)`.

        The inverse of :meth:`exp`: ``q.log().exp() == q`` (to rounding) for every
        non-zero ``q``, and ``p.exp().log() == p`` when the vector part of ``p`` has norm
        below π.  The vector part of the result has norm in [0, π]: for a unit
        quaternion the result is pure, half the rotation vector, :math:`\\tfrac\\theta2 u`.
        On the negative real axis (:math:`v = 0`, :math:`q_0 < 0`) the logarithm is
        not unique; :math:`\\ln|q_0| + \\pi\\mathbf i` is returned, as numpy-quaternion
        does.  The zero quaternion has no logarithm: ValueError.

        See Also
        --------
        exp, power, to_rotation_vector

        References
        ----------
        .. [1] M. Boyle, numpy-quaternion (``np.log`` on quaternions), same conventions.

        Examples
        --------
        >>> print(Quaternion.from_axis_angle([0, 0, 1], np.pi / 2).log())
        0 +0i +0j +0.785398k
        >>> print(Quaternion(-1.0).log())
        0 +3.14159i +0j +0k
        """
        big = max(abs(self.w), abs(self.x), abs(self.y), abs(self.z))
        if big == 0.0:
            raise ValueError("quaternion is the zero quaternion, which has no logarithm")
        b = math.hypot(self.x, self.y, self.z)
        # ln|q| from the scaled components: |q| overflows for components near 1e308
        log_n = math.log(big) + math.log(math.hypot(self.w / big, self.x / big, self.y / big, self.z / big))
        if b == 0.0:
            return Quaternion(log_n, math.pi if self.w < 0 else 0.0, 0.0, 0.0)
        # angle times the unit direction v/b: atan2(b, w)/b overflows for a subnormal b
        f = math.atan2(b, self.w)
        return Quaternion(log_n, f * (self.x / b), f * (self.y / b), f * (self.z / b))

    def power(self, t) -> "Quaternion":
        """:math:`q^t` (also ``q ** t``).

        * an integer ``t`` (``int`` or a NumPy integer): repeated Hamilton products,
          by squaring (:math:`O(\\log|t|)` products); a negative ``t`` is the power of
          :meth:`inverse`; ``q ** 0`` is 1, even for the zero quaternion;
        * a real ``t`` (``float``): :math:`\\exp(t\\log q)` with the principal
          :meth:`log`, numpy-quaternion's definition.  For a unit :math:`q` of angle
          :math:`\\theta \\le \\pi` (:math:`q_0 \\ge 0`) this is the rotation by
          :math:`t\\theta` about the same axis, and :math:`q^aq^b = q^{a+b}`; slerp is
          :math:`\\operatorname{slerp}(q_0, q_1; t) = q_0(q_0^{-1}q_1)^t`.  Note that
          :math:`q` and :math:`-q` have different real powers (:math:`(-1)^{1/2} =
          \\mathbf i`).  The zero quaternion: :math:`0^t = 0` for :math:`t > 0`, 1 for
          :math:`t = 0`; a negative power of zero raises ValueError.  A power that leaves
          float64 raises OverflowError, for integer and real ``t`` alike.

        See Also
        --------
        exp, log, inverse

        References
        ----------
        .. [1] K. Shoemake, "Animating rotation with quaternion curves", SIGGRAPH 1985
           (slerp as a power).
        .. [2] M. Boyle, numpy-quaternion (``q ** t``), same definition.

        Examples
        --------
        >>> q = Quaternion.from_axis_angle([0, 0, 1], np.pi / 2)
        >>> (q ** 0.5).same_rotation(Quaternion.from_axis_angle([0, 0, 1], np.pi / 4))
        True
        >>> Quaternion(0, 1, 0, 0) ** 2
        Quaternion(w=-1.0, x=0.0, y=0.0, z=0.0)
        """
        if isinstance(t, bool) or not isinstance(t, numbers.Real):
            raise TypeError(f"exponent must be a real number, got {type(t).__name__}")
        zero = self.w == 0.0 and self.x == 0.0 and self.y == 0.0 and self.z == 0.0
        if isinstance(t, numbers.Integral):
            k = int(t)
            base = self._inverse("quaternion") if k < 0 else self
            out, k = Quaternion(1.0), abs(k)
            try:
                with np.errstate(over="ignore", invalid="ignore"):
                    while k:
                        if k & 1:
                            out = out * base
                        k >>= 1
                        if k:
                            base = base * base
            except ValueError:  # a product left float64 (the constructor refuses inf/NaN)
                raise OverflowError(f"quaternion ** {int(t)} overflows float64") from None
            return out
        t = as_finite_scalar(t, "exponent")
        if zero:
            if t < 0:
                raise ValueError(f"quaternion is the zero quaternion: no negative power (exponent {t!r})")
            return Quaternion(1.0 if t == 0 else 0.0)
        return (self.log() * t).exp()

    def isclose(self, other: "Quaternion", atol: float = 1e-12) -> bool:
        """Componentwise equality within ``atol`` (so :math:`q` and :math:`-q` differ)."""
        if not isinstance(other, Quaternion):
            raise TypeError(f"other must be a Quaternion, got {type(other).__name__}")
        atol = as_finite_scalar(atol, "atol", nonnegative=True)
        return bool(np.all(np.abs(self.as_array() - other.as_array()) <= atol))

    def same_rotation(self, other: "Quaternion", atol: float = 1e-9) -> bool:
        """True when both represent the same rotation: :math:`\\hat q = \\pm\\hat r` within ``atol``."""
        if not isinstance(other, Quaternion):
            raise TypeError(f"other must be a Quaternion, got {type(other).__name__}")
        a = self.normalized().as_array()
        b = other.normalized().as_array()
        return bool(min(np.abs(a - b).max(), np.abs(a + b).max()) <= atol)

    def angle_to(self, other: "Quaternion") -> float:
        """Angle in radians, in [0, π], of the rotation between two rotations (see :func:`rotation_angle`)."""
        if not isinstance(other, Quaternion):
            raise TypeError(f"other must be a Quaternion, got {type(other).__name__}")
        return float(rotation_angle(self.as_array(), other.as_array()))

    # ---------------------------------------------------------------- matrix forms
    def left_matrix(self) -> np.ndarray:
        """The 4×4 matrix :math:`Q` with :math:`q\\cdot r = Q r` (Notes §23.2).

        The notes print this matrix correctly but multiply it by :math:`q` itself.
        """
        return _left(self.as_array())

    def right_matrix(self) -> np.ndarray:
        """The 4×4 matrix :math:`\\bar Q` with :math:`r\\cdot q = \\bar Q r` (Notes §23.2).

        It is :math:`Q` with the lower-right 3×3 block transposed.  It is *not*
        "orthogonal to :math:`Q`" as the notes say; it commutes with :math:`Q`.
        """
        return _right(self.as_array())

    # ---------------------------------------------------------------- rotations
    def to_matrix(self) -> np.ndarray:
        """The 3×3 rotation matrix of :math:`q/\\lVert q\\rVert` (zero raises ValueError).

        Equal to the lower-right block of :math:`\\bar Q^T Q` for a unit :math:`q`
        (Notes §23.2, :math:`I_q(r) = \\bar Q^T Q r`).
        """
        return qmatrix(unit_quaternions(self.as_array(), "quaternion"))

    def to_axis_angle(self) -> tuple[np.ndarray, float]:
        """Unit axis and angle :math:`\\theta \\in [0, \\pi]` of the rotation.

        The sign of :math:`q` is chosen with :math:`q_0 \\ge 0`, so the angle is at most
        π.  For the identity (angle 0) the axis is undetermined and ``(1, 0, 0)`` is
        returned.  The zero quaternion raises ValueError.
        """
        q = unit_quaternions(self.as_array(), "quaternion")
        if q[0] < 0:
            q = -q
        s = float(np.linalg.norm(q[1:]))
        angle = 2.0 * math.atan2(s, float(q[0]))
        if s == 0.0:
            return np.array([1.0, 0.0, 0.0]), 0.0
        return q[1:] / s, angle

    @classmethod
    def from_rotation_vector(cls, v) -> "Quaternion":
        """The unit quaternion of the rotation vector :math:`v = \\theta u` (angle times unit axis).

        The zero vector gives the identity.  Accurate for tiny angles.
        """
        v = as_point(v, "v", dim=3)
        return cls(*_qexp(v))

    def to_rotation_vector(self) -> np.ndarray:
        """The rotation vector :math:`\\theta u` with :math:`\\theta \\in [0, \\pi]` (normalises first)."""
        return _qlog(unit_quaternions(self.as_array(), "quaternion"))

    def rotate(self, points) -> np.ndarray:
        """Rotate one point (3,) or many (n, 3): :math:`I_q(r) = q r q^*` (Notes §23.2).

        The quaternion is normalised first (see the module docstring), so this is
        always a proper rotation; the zero quaternion raises ValueError.
        """
        p = as_points3(points, "points")
        return p @ self.to_matrix().T

    def __repr__(self) -> str:
        return f"Quaternion(w={self.w!r}, x={self.x!r}, y={self.y!r}, z={self.z!r})"

    def __str__(self) -> str:
        # rounded to 6 decimals for reading (no -0, no 1e-18 noise); repr() is exact
        w, x, y, z = (round(v, 6) + 0.0 for v in (self.w, self.x, self.y, self.z))
        return f"{w:.6g} {x:+.6g}i {y:+.6g}j {z:+.6g}k"
