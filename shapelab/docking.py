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

:class:`Docking` keeps a receptor and a ligand and scores many poses of the ligand fast
and exactly: a ligand's pose changes the exposed area only of receptor balls it touches,
so each pose measures the union of the ligand and the receptor's balls near it, with the
receptor's own per-ball areas computed once.  :meth:`Docking.search` docks in the notes'
two stages (§23.2): a coarse alignment of the ligand to a site from features
(:func:`shapelab.coarse_align`), then local improvement of the score.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.validate import as_finite_scalar, check_balls

if TYPE_CHECKING:
    from .balls import Balls

__all__ = ["DockingScore", "docking_score", "Docking", "DockedPose"]


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

    See Also
    --------
    docking_score
        Produces it.
    """

    score: float
    buried_area: float
    clash: float


def docking_score(
    A, B, motion=None, *, probe: float = 0.0, penalty: float = 10.0, tolerance: float = 0.5
) -> DockingScore:
    """Score the pose of ``B`` (moved by ``motion``) against ``A``: buried area minus clashes.

    Parameters
    ----------
    A, B : Balls
        The two molecules, in 3D.
    motion : RigidMotion, optional
        Applied to ``B``'s centres (default: none).
    probe : float
        Solvent probe radius (≥ 0): the buried area is measured on the balls grown by
        ``probe`` (solvent-accessible surfaces, 1.4 Å for water), the clashes on the
        balls as given (van der Waals).
    penalty : float
        Weight of the clash term, in area per unit of overlap depth (≥ 0).
    tolerance : float
        Overlap depth between two balls that is not a clash (≥ 0): van der Waals balls of
        atoms in contact overlap a little.

    Returns
    -------
    DockingScore

    See Also
    --------
    Docking
        Scores many poses of one pair fast.
    union_measure
        The exact areas it is built from.

    References
    ----------
    .. [1] I. Halperin, B. Ma, H. Wolfson and R. Nussinov, "Principles of docking: an
           overview of search algorithms and a guide to scoring functions", *Proteins*
           47(4):409-443, 2002. doi:10.1002/prot.10115
    .. [2] J. Liang, H. Edelsbrunner, P. Fu, P. V. Sudhakar and S. Subramaniam,
           "Analytical shape computation of macromolecules: I. Molecular area and volume
           through alpha shape", *Proteins* 33(1):1-17, 1998.

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
    probe = as_finite_scalar(probe, "probe", nonnegative=True)
    if motion is not None and not isinstance(motion, RigidMotion):
        raise TypeError(f"motion must be a shapelab.RigidMotion, got {type(motion).__name__}")
    cb = B.centers if motion is None else motion.apply(B.centers)
    both = Balls(np.vstack([A.centers, cb]), np.concatenate([A.radii, B.radii]) + probe)
    area_a = union_measure(Balls(A.centers, A.radii + probe)).surface_area
    area_b = union_measure(Balls(cb, B.radii + probe)).surface_area
    area_ab = union_measure(both).surface_area
    buried = area_a + area_b - area_ab
    # clashes: pairs (a, b) with r_a + r_b - |a - b| > tolerance, by blocks of A's balls
    clash = 0.0
    for s in range(0, len(A), 2048):
        ca, ra = A.centers[s : s + 2048], A.radii[s : s + 2048]
        d = np.sqrt(((ca[:, None, :] - cb[None, :, :]) ** 2).sum(-1))
        clash += float(np.maximum(0.0, ra[:, None] + B.radii[None, :] - d - tolerance).sum())
    return DockingScore(float(buried - penalty * clash), float(buried), clash)


@dataclass(frozen=True)
class DockedPose:
    """One pose of the ligand found by :meth:`Docking.refine` or :meth:`Docking.search`.

    Attributes
    ----------
    motion : RigidMotion
        The motion of the ligand's balls (as given) into the pose.
    score : DockingScore
        Its score.
    start : RigidMotion
        The pose the local improvement started from.
    feature : str
        Where the start came from: a feature of :func:`shapelab.coarse_align`
        (``"axes"``, ``"critical"``) or ``"given"``.
    evaluations : int
        Number of poses scored by the local improvement.

    See Also
    --------
    Docking.search
        Produces poses.
    """

    motion: object
    score: DockingScore
    start: object
    feature: str
    evaluations: int


class Docking:
    """A receptor and a ligand as balls: score poses of the ligand, and dock it (Notes §23.2).

    Parameters
    ----------
    receptor, ligand : Balls
        The two molecules in 3D, van der Waals balls.  The ligand moves; the receptor
        stays.
    probe, penalty, tolerance : float
        As in :func:`docking_score`: the buried area is that of the balls grown by
        ``probe``, the clashes are those of the balls as given.

    See Also
    --------
    docking_score
        One pose, from scratch.
    coarse_align
        The first of the two stages.
    icp
        Local improvement of a shape match.

    Notes
    -----
    :meth:`score` equals ``docking_score(receptor, ligand, motion)`` (the tests check it)
    but costs a union of the ligand and the receptor balls within
    :math:`3 r_{\\max}^A + r_{\\max}^B` of it, not of the whole receptor: a receptor ball
    :math:`a` changes its exposed area only if it meets a ligand ball (it lies within
    :math:`r_{\\max}^A + r_{\\max}^B` of one), and all the balls that meet such an
    :math:`a` are in that neighbourhood, so its per-ball area there is exact.

    References
    ----------
    .. [1] I. Halperin, B. Ma, H. Wolfson and R. Nussinov, "Principles of docking: an
           overview of search algorithms and a guide to scoring functions", *Proteins*
           47(4):409-443, 2002. doi:10.1002/prot.10115

    Examples
    --------
    >>> import shapelab as sl
    >>> lock = sl.Balls([[x, y, 0.0] for x in range(-3, 4) for y in range(-3, 4) if x * x + y * y > 2], 1.0)
    >>> key = sl.Balls([[0.0, 0.0, 0.0], [0.0, 0.0, 1.5]], 1.2)
    >>> dock = Docking(lock, key)
    >>> a = dock.score(sl.RigidMotion(None, [0.0, 0.0, 0.5])).score
    >>> b = docking_score(lock, key, sl.RigidMotion(None, [0.0, 0.0, 0.5])).score
    >>> bool(abs(a - b) < 1e-9 * abs(b))
    True
    """

    def __init__(
        self, receptor: Balls, ligand: Balls, *, probe: float = 0.0, penalty: float = 10.0, tolerance: float = 0.5
    ):
        from scipy.spatial import cKDTree

        from .balls import Balls
        from .measure import union_measure

        self.receptor = check_balls(receptor, "receptor", dim=3)
        self.ligand = check_balls(ligand, "ligand", dim=3)
        if len(self.receptor) == 0 or len(self.ligand) == 0:
            raise ValueError("receptor and ligand must each have at least one ball")
        self.penalty = as_finite_scalar(penalty, "penalty", nonnegative=True)
        self.tolerance = as_finite_scalar(tolerance, "tolerance", nonnegative=True)
        self.probe = as_finite_scalar(probe, "probe", nonnegative=True)
        self._tree = cKDTree(self.receptor.centers)
        self._ra = self.receptor.radii + self.probe  # radii for the areas
        self._rb = self.ligand.radii + self.probe
        self._area_receptor = union_measure(Balls(self.receptor.centers, self._ra)).ball_boundary
        self._area_ligand = union_measure(Balls(self.ligand.centers, self._rb)).ball_boundary
        self._rmax_a = float(self._ra.max())
        self._rmax_b = float(self._rb.max())
        self._center = self.ligand.centers.mean(axis=0)
        self.evaluations = 0

    def __repr__(self) -> str:
        return f"Docking(receptor={len(self.receptor)} balls, ligand={len(self.ligand)} balls, probe={self.probe:g})"

    def _near(self, cb, reach):
        hits = self._tree.query_ball_point(cb, reach)
        idx = np.unique(np.concatenate([np.asarray(h, dtype=np.int64) for h in hits] + [np.zeros(0, np.int64)]))
        return idx

    def score(self, motion=None) -> DockingScore:
        """Score the ligand moved by ``motion`` (default: as given); see :func:`docking_score`."""
        from .balls import Balls
        from .measure import union_measure
        from .registration import RigidMotion

        if motion is not None and not isinstance(motion, RigidMotion):
            raise TypeError(f"motion must be a shapelab.RigidMotion, got {type(motion).__name__}")
        self.evaluations += 1
        A, B = self.receptor, self.ligand
        cb = B.centers if motion is None else motion.apply(B.centers)
        contact = self._near(cb, self._rmax_a + self._rmax_b)
        local = self._near(cb, 3.0 * self._rmax_a + self._rmax_b)
        both = Balls(np.vstack([A.centers[local], cb]), np.concatenate([self._ra[local], self._rb]))
        m = union_measure(both).ball_boundary
        pos = np.searchsorted(local, contact)  # contact is a subset of local
        buried = float((self._area_receptor[contact] - m[pos]).sum())
        buried += float((self._area_ligand - m[len(local) :]).sum())
        clash = 0.0
        if len(contact):  # the van der Waals balls that clash are among the contacts
            ca, ra = A.centers[contact], A.radii[contact]
            d = np.sqrt(((ca[:, None, :] - cb[None, :, :]) ** 2).sum(-1))
            clash = float(np.maximum(0.0, ra[:, None] + B.radii[None, :] - d - self.tolerance).sum())
        return DockingScore(buried - self.penalty * clash, buried, clash)

    def refine(self, start=None, *, max_evals: int = 200, step: float = 1.0, feature: str = "given") -> DockedPose:
        """Local improvement: maximise the score from ``start`` (Nelder–Mead, deterministic).

        The pose is parametrised by a rotation vector about the ligand's centroid (radians)
        and a translation (length units) applied after ``start``.

        Parameters
        ----------
        start : RigidMotion, optional
            The starting pose (default: the ligand as given).
        max_evals : int
            Budget of scored poses.
        step : float
            Initial step: ``step`` length units of translation and ``step / 4`` radians.
        feature : str
            Recorded on the result (where ``start`` came from).

        Returns
        -------
        DockedPose
            The best pose scored (never worse than ``start``).
        """
        from scipy.optimize import minimize

        from ._toolkit.validate import as_positive_int
        from .quaternion import Quaternion
        from .registration import RigidMotion

        start = RigidMotion() if start is None else start
        if not isinstance(start, RigidMotion):
            raise TypeError(f"start must be a shapelab.RigidMotion, got {type(start).__name__}")
        max_evals = as_positive_int(max_evals, "max_evals")
        step = as_finite_scalar(step, "step", positive=True)
        pivot = start.apply(self._center)

        def pose(x):
            rot = RigidMotion(Quaternion.from_rotation_vector(x[:3]))
            about = RigidMotion(None, pivot + x[3:]) @ rot @ RigidMotion(None, -pivot)
            return about @ start

        best = {"x": np.zeros(6), "s": self.score(start)}
        n = [1]

        def cost(x):
            n[0] += 1
            s = self.score(pose(x))
            if s.score > best["s"].score:
                best["x"], best["s"] = np.array(x), s
            return -s.score

        simplex = np.vstack([np.zeros(6), np.diag([step / 4] * 3 + [step] * 3)])
        minimize(
            cost,
            np.zeros(6),
            method="Nelder-Mead",
            options={"initial_simplex": simplex, "maxfev": max_evals - 1, "xatol": 1e-3, "fatol": 1e-3},
        )
        return DockedPose(pose(best["x"]), best["s"], start, str(feature), n[0])

    def landscape(self, angles, shifts, *, axis, direction, pose=None) -> np.ndarray:
        """Scores on a grid of poses: turns about ``axis`` through the ligand's centroid, by
        shifts along ``direction``, around ``pose``.

        Parameters
        ----------
        angles : array_like, shape (a,)
            Rotation angles in radians.
        shifts : array_like, shape (s,)
            Translations along ``direction`` (length units).
        axis, direction : array_like, shape (3,)
            Rotation axis and shift direction (normalised here).
        pose : RigidMotion, optional
            The pose at angle 0 and shift 0 (default: the ligand as given).

        Returns
        -------
        ndarray, shape (a, s)
            ``out[i, j]`` is the score after turning by ``angles[i]`` and shifting by
            ``shifts[j]``.
        """
        from ._toolkit.validate import as_points
        from .quaternion import Quaternion
        from .registration import RigidMotion

        angles = as_points(np.reshape(angles, (-1, 1)), "angles").ravel()
        shifts = as_points(np.reshape(shifts, (-1, 1)), "shifts").ravel()
        axis = as_points(np.reshape(axis, (1, -1)), "axis", dim=3)[0]
        direction = as_points(np.reshape(direction, (1, -1)), "direction", dim=3)[0]
        for v, name in ((axis, "axis"), (direction, "direction")):
            if not np.linalg.norm(v) > 0:
                raise ValueError(f"{name} must be a nonzero vector")
        direction = direction / np.linalg.norm(direction)
        pose = RigidMotion() if pose is None else pose
        if not isinstance(pose, RigidMotion):
            raise TypeError(f"pose must be a shapelab.RigidMotion, got {type(pose).__name__}")
        pivot = pose.apply(self._center)
        out = np.empty((len(angles), len(shifts)))
        for i, a in enumerate(angles):
            turn = (
                RigidMotion(None, pivot) @ RigidMotion(Quaternion.from_axis_angle(axis, a)) @ RigidMotion(None, -pivot)
            )
            for j, t in enumerate(shifts):
                out[i, j] = self.score(RigidMotion(None, t * direction) @ turn @ pose).score
        return out

    def search(self, site, *, n_starts: int = 3, max_evals: int = 200, step: float = 1.0) -> tuple:
        """Dock in two stages (Notes §23.2): coarse alignment to a site, then local improvement.

        Parameters
        ----------
        site : array_like, shape (m, 3)
            Points filling the binding site, for example the free space of the
            receptor's largest pocket (:func:`shapelab.cavities.freespace.free_points` on a
            :class:`shapelab.Pocket`'s cells).
        n_starts : int
            How many of :func:`shapelab.coarse_align`'s candidates (ligand centres onto
            ``site``, best first) to refine.
        max_evals, step : int, float
            Passed to :meth:`refine` for each start.

        Returns
        -------
        tuple of DockedPose
            Best score first.
        """
        from ._toolkit.validate import as_points, as_positive_int
        from .features import coarse_align

        site = as_points(site, "site", dim=3, min_points=4)
        n_starts = as_positive_int(n_starts, "n_starts")
        if len(self.ligand) < 4:
            raise ValueError(f"search needs a ligand of at least 4 balls for coarse alignment, got {len(self.ligand)}")
        starts = coarse_align(self.ligand.centers, site)[:n_starts]
        poses = [self.refine(c.motion, max_evals=max_evals, step=step, feature=c.feature) for c in starts]
        return tuple(sorted(poses, key=lambda p: -p.score.score))
