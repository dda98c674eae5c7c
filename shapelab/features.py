"""Feature-based coarse alignment: the first stage of two-stage matching (notes §23.2).

The notes describe matching as two stages: an initial matching on geometric features
(reference points, critical points), then local improvement.  ICP
(:func:`shapelab.icp`) is the local improvement, and it only finds the motion when it
starts close enough; from a 120° or 150° turn it stops in a wrong local minimum
(lesson 15).  :func:`coarse_align` proposes starts from features that do not depend on
the pose:

* ``"axes"``: the centroid and the principal axes (the eigenvectors of the covariance).
  Matching the two frames leaves only the signs of the axes open: 4 proper rotations
  in 3D, 2 in 2D.  Every one is proposed.
* ``"critical"``: a stand-in for the critical points of the distance from the
  centroid (§23.2's Figure 23.3): the three sample points of each set farthest from
  its centroid.  They lie near the global maximum of that distance but need not be
  three distinct critical points (often they are neighbours of one maximum).  Each
  of the 6 ways of matching the two triples (with the centroids) gives a rigid
  motion by Horn's method.

Candidates are ranked by the mean distance from each moved point to its nearest target
point (a cheap stand-in for the Hausdorff distance), best first.  Each is a
:class:`shapelab.RigidMotion`, ready for ``icp(R, G, init=...)``.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.validate import as_points

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike

__all__ = ["Candidate", "coarse_align"]

_FEATURES = ("axes", "critical")


@dataclass(frozen=True)
class Candidate:
    """A proposed motion and its score (mean nearest-neighbour distance, lower is better).

    See Also
    --------
    coarse_align
        Produces candidates.
    """

    motion: object
    score: float
    feature: str


def _frame(X):
    c = X.mean(axis=0)
    cov = np.cov((X - c).T)
    w, V = np.linalg.eigh(cov)
    return c, V[:, ::-1], w[::-1]  # axes by decreasing variance


def coarse_align(R: ArrayLike, G: ArrayLike, *, features: str | Sequence[str] = ("axes", "critical")) -> list:
    """Candidate rigid motions taking ``R`` near ``G``, from pose-independent features.

    Parameters
    ----------
    R, G : array_like, shape (n, 3) and (m, 3)
        Source and target point sets (not paired; they may differ in size).
    features : str or sequence of str
        ``"axes"`` (centroid and principal axes: 4 candidates) and/or ``"critical"``
        (the three points farthest from the centroid, in each of the 6 orders).

    Returns
    -------
    list of Candidate
        Best first (lowest mean nearest-neighbour distance after the motion).

    See Also
    --------
    icp
        Local improvement from each candidate.
    critical_points
        The critical points proper (of a curve or a surface mesh); here only
        approximated by the farthest samples.
    optimal_rotation
        Horn's rotation of matched features.

    Notes
    -----
    When two principal variances are equal (for example a shape with a symmetry axis),
    the frame is not unique and the axes candidates are only as good as an arbitrary
    choice; the ``"critical"`` candidates and ICP then decide.  Cost: two 3 × 3
    covariance eigendecompositions, six 4 × 4 ones (Horn), and one nearest-neighbour
    query of all of ``R`` per candidate (10 with both features).

    References
    ----------
    .. [1] P. J. Besl and N. D. McKay, "A method for registration of 3-D shapes", *IEEE
           Trans. Pattern Anal. Mach. Intell.* 14(2):239-256, 1992. doi:10.1109/34.121791
    .. [2] B. K. P. Horn, "Closed-form solution of absolute orientation using unit
           quaternions", *J. Opt. Soc. Am. A* 4(4):629-642, 1987.
           doi:10.1364/JOSAA.4.000629

    Examples
    --------
    >>> from shapelab import Quaternion, RigidMotion, icp
    >>> from shapelab.datasets import sample_shape
    >>> R = sample_shape("lumpy", 400, seed=1)
    >>> truth = RigidMotion(Quaternion.from_axis_angle([1, 2, 3], np.radians(150)), [0.3, 0, 0])
    >>> G = truth.apply(R)
    >>> best = coarse_align(R, G)[0]
    >>> icp(R, G, init=best.motion).motion.isclose(truth, atol=1e-6)
    True
    """
    from scipy.spatial import cKDTree

    from .quaternion import Quaternion
    from .registration import RigidMotion, register

    R = as_points(R, "R", dim=3, min_points=4)
    G = as_points(G, "G", dim=3, min_points=4)
    if isinstance(features, str):
        features = (features,)
    features = tuple(features)
    bad = [f for f in features if f not in _FEATURES]
    if bad or not features:
        raise ValueError(f"features must be among {_FEATURES}, got {features!r}")
    tree = cKDTree(G)

    def score(m):
        d, _ = tree.query(m.apply(R))
        return float(np.mean(d))

    out = []
    cR, VR, _ = _frame(R)
    cG, VG, _ = _frame(G)
    if "axes" in features:
        for signs in itertools.product((1.0, -1.0), repeat=3):
            S = np.diag(signs)
            M = VG @ S @ VR.T  # maps R's axes onto G's, up to the signs
            if np.linalg.det(M) < 0:
                continue
            m = RigidMotion(Quaternion.from_matrix(M, atol=1e-6), cG - M @ cR)
            out.append(Candidate(m, score(m), "axes"))
    if "critical" in features:
        k = min(3, len(R), len(G))
        fr = np.argsort(-np.linalg.norm(R - cR, axis=1))[:k]
        fg = np.argsort(-np.linalg.norm(G - cG, axis=1))[:k]
        for perm in itertools.permutations(range(k)):
            P = np.vstack([R[fr], cR])
            Q = np.vstack([G[fg[list(perm)]], cG])
            m = register(P, Q)
            out.append(Candidate(m, score(m), "critical"))
    out.sort(key=lambda c: c.score)
    return out
