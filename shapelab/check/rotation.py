"""Self-checks for the exercises on quaternions, the optimal rotation and matching
(Notes §23.2; lessons 15–17).

Each check calls *your* function on edge cases first, then on random ones, and
compares with the library (:mod:`shapelab.quaternion`, :mod:`shapelab.registration`).
Quaternions are 4-arrays ``(w, x, y, z)``, scalar part first, as in the notes.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..quaternion import qfrom_axis_angle, qmatrix, qmul
from ..registration import optimal_rotation as _optimal_rotation
from ._runner import CheckResult, allclose, run_check

__all__ = ["quaternion_product", "rotation_matrix", "optimal_rotation", "centroid_alignment"]

_BASIS = np.eye(4)  # 1, i, j, k


def _product_cases():
    cases = []
    # the multiplication table first: ij, ji, jk, kj, ki, ik, then squares
    for a, b in [(1, 2), (2, 1), (2, 3), (3, 2), (3, 1), (1, 3), (1, 1), (2, 2), (3, 3), (0, 3)]:
        cases.append((_BASIS[a].copy(), _BASIS[b].copy()))
    rng = np.random.default_rng(2314)
    for _ in range(6):
        cases.append((rng.normal(size=4), rng.normal(size=4)))
    return cases


def quaternion_product(fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``fn(q, r) -> 4-array``, the Hamilton product :math:`q\\cdot r` (Notes §23.2).

    Starts with the table :math:`\\mathbf{ij} = \\mathbf k`, :math:`\\mathbf{ji} =
    -\\mathbf k`, ... (the notes print the :math:`\\mathbf k` component with the wrong
    sign, so copying it fails here), then random quaternions.

    See Also
    --------
    shapelab.Quaternion
        The reference product.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> quaternion_product(lambda q, r: (sl.Quaternion(*q) * sl.Quaternion(*r)).as_array()).passed
    ✓ quaternion product: correct on all 16 cases.
    True
    >>> # the product in the other order is refused
    >>> quaternion_product(lambda q, r: (sl.Quaternion(*r) * sl.Quaternion(*q)).as_array(), quiet=True).passed
    False
    """
    return run_check(
        "quaternion product", fn, _product_cases(), lambda q, r: qmul(q, r), allclose(1e-10, 1e-9), quiet=quiet
    )


def _unit_cases():
    rng = np.random.default_rng(2315)
    cases = [np.array([1.0, 0.0, 0.0, 0.0])]
    for axis, angle in [([0, 0, 1], np.pi / 2), ([1, 0, 0], np.pi), ([1, 1, 1], 2 * np.pi / 3), ([0, 1, 0], -0.3)]:
        cases.append(qfrom_axis_angle(np.asarray(axis, float), angle))
    for _ in range(5):
        q = rng.normal(size=4)
        cases.append(q / np.linalg.norm(q))
    return [(q,) for q in cases]


def rotation_matrix(fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``fn(q) -> 3×3``, the rotation matrix of a **unit** quaternion.

    The matrix :math:`M` with :math:`M r = q r q^*` (Notes §23.2, :math:`I_q`): the
    lower-right 3×3 block of :math:`\\bar Q^T Q`.

    See Also
    --------
    shapelab.quaternion.qmatrix
        The reference.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> rotation_matrix(lambda q: sl.Quaternion(*q).to_matrix()).passed
    ✓ rotation matrix: correct on all 10 cases.
    True
    >>> # the transpose, the inverse rotation, is refused
    >>> rotation_matrix(lambda q: sl.Quaternion(*q).to_matrix().T, quiet=True).passed
    False
    """
    return run_check("rotation matrix", fn, _unit_cases(), lambda q: qmatrix(q), allclose(1e-10, 1e-9), quiet=quiet)


def _same_rotation(expected, received) -> bool:
    try:
        e = np.asarray(expected, dtype=float)
        r = np.asarray(received, dtype=float)
    except (TypeError, ValueError):
        return False
    if r.shape != (4,) or not np.all(np.isfinite(r)):
        return False
    return bool(min(np.abs(e - r).max(), np.abs(e + r).max()) <= 1e-6)


def _rotation_cases():
    rng = np.random.default_rng(2316)
    cases = []
    # exact rotations: a right angle about z, then a generic one
    R = np.array([[1.0, 0, 0], [0, 2.0, 0], [0, 0, 3.0], [1.0, 1.0, 1.0]])
    R = R - R.mean(axis=0)
    for axis, angle in [([0, 0, 1], np.pi / 2), ([1, 2, 3], 2.0)]:
        q = qfrom_axis_angle(np.asarray(axis, float), angle)
        cases.append((R.copy(), R @ qmatrix(q).T))
    # a planar set (still a unique answer), then noisy random sets
    P = rng.normal(size=(6, 3))
    P[:, 2] = 0.0
    P -= P.mean(axis=0)
    q = qfrom_axis_angle(np.array([0.3, -1.0, 0.5]), 1.1)
    cases.append((P, P @ qmatrix(q).T))
    for _ in range(3):
        A = rng.normal(size=(20, 3))
        A -= A.mean(axis=0)
        q = rng.normal(size=4)
        B = A @ qmatrix(q).T + 0.05 * rng.normal(size=A.shape)
        cases.append((A, B - B.mean(axis=0)))
    # no rotation fits: a mirror image (its most negative eigenvalue is the largest in
    # magnitude) and unrelated sets (np.linalg.eig does not list the top eigenvalue first)
    rng = np.random.default_rng(2318)
    M = rng.normal(size=(12, 3)) * [2.0, 1.2, 0.6]
    M -= M.mean(axis=0)
    cases.append((M, M * [1.0, 1.0, -1.0]))
    for _ in range(3):
        A, B = rng.normal(size=(9, 3)), rng.normal(size=(9, 3))
        cases.append((A - A.mean(axis=0), B - B.mean(axis=0)))
    return cases


def optimal_rotation(fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``fn(R, G) -> unit quaternion (4-array)`` rotating centred ``R`` onto ``G``.

    Horn's solution of the notes: the eigenvector of :math:`A = \\sum_j\\bar R_j^TG_j`
    for the largest eigenvalue.  Compared up to sign (:math:`q` and :math:`-q` are the
    same rotation).  The sets given are centred and paired row by row.

    See Also
    --------
    shapelab.optimal_rotation
        The reference.

    Examples
    --------
    >>> import shapelab as sl
    >>> optimal_rotation(lambda R, G: sl.optimal_rotation(R, G).as_array()).passed
    ✓ optimal rotation: correct on all 10 cases.
    True
    >>> optimal_rotation(lambda R, G: sl.optimal_rotation(G, R).as_array(), quiet=True).passed
    False
    """
    return run_check(
        "optimal rotation",
        fn,
        _rotation_cases(),
        lambda R, G: _optimal_rotation(R, G).as_array(),
        _same_rotation,
        quiet=quiet,
    )


def _centroid_cases():
    rng = np.random.default_rng(2317)
    cases = [
        (np.array([[0.0, 0, 0], [2.0, 0, 0]]), np.array([[1.0, 1, 1], [3.0, 1, 1]])),
        # different sizes: centroids need no pairing
        (np.array([[0.0, 0, 0], [3.0, 0, 0], [0.0, 3, 0]]), np.array([[5.0, 5, 5], [7.0, 5, 5]])),
        (rng.normal(size=(7, 3)) + 1e6, rng.normal(size=(4, 3))),
    ]
    for _ in range(3):
        cases.append((rng.normal(size=(10, 3)), rng.normal(size=(13, 3)) + rng.normal(size=3)))
    return cases


def centroid_alignment(fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``fn(R, G) -> translation (3,)`` moving the centroid of ``R`` onto that of ``G``.

    The reference-point alignment of the notes (§23.2, "For the translation only
    case ... align their centroids"): :math:`t = \\bar g - \\bar r`.  The two sets may
    have different sizes.

    See Also
    --------
    shapelab.register
        The least-squares motion.

    Examples
    --------
    >>> import numpy as np
    >>> centroid_alignment(lambda R, G: np.mean(G, axis=0) - np.mean(R, axis=0)).passed
    ✓ centroid alignment: correct on all 6 cases.
    True
    >>> centroid_alignment(lambda R, G: np.mean(R, axis=0) - np.mean(G, axis=0), quiet=True).passed
    False
    """
    return run_check(
        "centroid alignment",
        fn,
        _centroid_cases(),
        lambda R, G: G.mean(axis=0) - R.mean(axis=0),
        allclose(1e-8, 1e-9),
        quiet=quiet,
    )
