"""A complementarity score for docking two molecules (notes §23.2, the motivation).

Shape matching serves docking: two molecules bind where their surfaces fit, burying
surface that was exposed to the solvent.  For two molecules as unions of balls ``A`` and
``B``, with ``B`` moved by a rigid motion, the **buried area** is

.. math::

    \\text{buried} = |\\partial A| + |\\partial B| - |\\partial(A \\cup B)|,

each area exact by the short inclusion–exclusion formula (:func:`shapelab.union_measure`).
Burying surface is good; interpenetrating is not: the **clash** is the summed depth by which
pairs of balls, one from each molecule, overlap beyond a tolerance
(:math:`\\max(0,\\, r_a + r_b - \\|a - b\\| - \\text{tolerance})`).  The score is
``buried - penalty * clash``: higher is better.  Grow every radius by a probe (1.4 Å) to
score solvent-accessible surfaces, as docking programs do.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._toolkit.validate import as_finite_scalar, check_balls

__all__ = ["DockingScore", "docking_score"]


@dataclass(frozen=True)
class DockingScore:
    """The result of :func:`docking_score`.

    Attributes
    ----------
    score : float
        ``buried_area - penalty * clash``; higher is a better fit.
    buried_area : float
        Surface area of ``A`` and ``B`` hidden in their union (Å² for molecules).
    clash : float
        Summed overlap depth of ball pairs across the two molecules, beyond the tolerance.
    """

    score: float
    buried_area: float
    clash: float


def docking_score(A, B, motion=None, *, penalty: float = 10.0, tolerance: float = 0.5) -> DockingScore:
    """Score the pose of ``B`` (moved by ``motion``) against ``A``: buried area minus clashes.

    Parameters
    ----------
    A, B : Balls
        The two molecules, in 3D.
    motion : RigidMotion, optional
        Applied to ``B``'s centres (default: none).
    penalty : float
        Weight of the clash term, in area per unit of overlap depth (≥ 0).
    tolerance : float
        Overlap depth between two balls that is not a clash (≥ 0): van der Waals balls of
        atoms in contact overlap a little.

    Returns
    -------
    DockingScore

    Examples
    --------
    >>> import shapelab as sl
    >>> a = sl.Balls([[0.0, 0.0, 0.0]], 1.0)
    >>> b = sl.Balls([[2.0, 0.0, 0.0]], 1.0)          # touching: nothing buried
    >>> round(docking_score(a, b).buried_area, 12)
    0.0
    """
    from .balls import Balls
    from .measure import union_measure
    from .registration import RigidMotion

    A = check_balls(A, "A")
    B = check_balls(B, "B")
    if A.dim != 3 or B.dim != 3:
        raise ValueError(f"A and B must be 3D balls, got {A.dim}D and {B.dim}D")
    penalty = as_finite_scalar(penalty, "penalty", nonnegative=True)
    tolerance = as_finite_scalar(tolerance, "tolerance", nonnegative=True)
    if motion is not None and not isinstance(motion, RigidMotion):
        raise TypeError(f"motion must be a shapelab.RigidMotion, got {type(motion).__name__}")
    cb = B.centers if motion is None else motion.apply(B.centers)
    both = Balls(np.vstack([A.centers, cb]), np.concatenate([A.radii, B.radii]))
    area_a = union_measure(A).surface_area
    area_b = union_measure(Balls(cb, B.radii)).surface_area
    area_ab = union_measure(both).surface_area
    buried = area_a + area_b - area_ab
    # clashes: pairs (a, b) with r_a + r_b - |a - b| > tolerance, by blocks of A's balls
    clash = 0.0
    for s in range(0, len(A), 2048):
        ca, ra = A.centers[s : s + 2048], A.radii[s : s + 2048]
        d = np.sqrt(((ca[:, None, :] - cb[None, :, :]) ** 2).sum(-1))
        clash += float(np.maximum(0.0, ra[:, None] + B.radii[None, :] - d - tolerance).sum())
    return DockingScore(float(buried - penalty * clash), float(buried), clash)
