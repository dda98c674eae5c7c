"""ICP, the Iterative Closest Point algorithm of the notes (Notes §23.2).

Four steps, with the ``source`` as the moving set and the ``target`` fixed:

1. pair each (moved) source point with its closest target point (:func:`closest_points`);
2. fix the pairs, find the rigid motion minimising the sum of squared distances
   (:func:`shapelab.rotation.register`: centroids, then Horn's optimal rotation);
3. move the source by it;
4. repeat until the mean squared error stops decreasing (by less than ``tol``).

That is what :func:`icp` runs by default.  ``accelerate=True`` adds one option, named
for what it does: after step 2 it also tries an Anderson-extrapolated motion built from
the last few steps and keeps it only if its error is not larger (same fixed points, the
same monotone error, far fewer iterations); the extrapolation itself is in the engine
(:mod:`shapelab._engine.icp`).

Where the notes are wrong or imprecise
--------------------------------------
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

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from ._engine.icp import Anderson
from ._toolkit.geometry import morton_order
from ._toolkit.validate import as_finite_scalar, as_points, as_positive_int
from .quaternion import Quaternion
from .rotation import RigidMotion, fit_motion

__all__ = ["ICPResult", "icp", "closest_points"]


def _readonly(a) -> np.ndarray:
    out = np.array(a, dtype=np.float64)
    out.flags.writeable = False
    return out


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


def _to_params(motion: RigidMotion, c: np.ndarray) -> np.ndarray:
    """6 numbers for a motion: its rotation vector and where it takes the point c."""
    return np.concatenate([motion.rotation.to_rotation_vector(), motion.apply(c)])


def _from_params(x: np.ndarray, c: np.ndarray) -> RigidMotion:
    q = Quaternion.from_rotation_vector(x[:3])
    return RigidMotion(q, x[3:] - q.rotate(c))


def _accelerated(anderson: Anderson, motion: RigidMotion, plain: RigidMotion, cost: float, evaluate, c: np.ndarray):
    """The Anderson-extrapolated motion after the plain step ``plain`` (as ``(motion,
    moved, idx, cost)``), or None when there is none or it is worse than ``cost``."""
    x = anderson(_to_params(motion, c), _to_params(plain, c))
    if x is None or np.linalg.norm(x[:3]) >= 0.95 * np.pi:
        return None
    trial = _from_params(x, c)
    t_moved, t_idx, t_cost = evaluate(trial)
    if t_cost <= cost:
        return trial, t_moved, t_idx, t_cost
    anderson.reset()  # worse: start the extrapolation again from the plain step
    anderson(_to_params(motion, c), _to_params(plain, c))
    return None


def icp(
    source: npt.ArrayLike,
    target: npt.ArrayLike,
    *,
    tol: float = 1e-6,
    max_iter: int = 50,
    init: RigidMotion | None = None,
    max_distance: float | None = None,
    accelerate: bool = False,
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
        basins even on the last bits of the arithmetic, lesson 15); nothing makes it
        the global minimum.
    max_distance : float, optional
        Pairs farther apart than this are left out of step 2 (Open3D's
        ``max_correspondence_distance``).  The cost then counts every source point,
        an unmatched one with :math:`d^2 = \\text{max\\_distance}^2`, which keeps it
        monotone.
    accelerate : bool
        False (default): the notes' algorithm literally, one plain step per
        iteration.  True: after step 2, also try an Anderson-extrapolated motion
        built from the last few steps, and keep it only if its cost (with fresh
        closest points) is not larger than the current one; otherwise take the
        plain step.  Same fixed points and the same monotone cost as the plain
        algorithm, in far fewer iterations (plain point-to-point ICP converges only
        linearly, slowly near the end).
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
    >>> res = icp(src, true.apply(src), max_iter=200, tol=1e-12)
    >>> bool(res.converged), res.motion.rotation.angle_to(true.rotation) < 1e-4
    (True, True)
    >>> fast = icp(src, true.apply(src), max_iter=200, tol=1e-12, accelerate=True)  # the option
    >>> fast.motion.isclose(res.motion, atol=1e-6)
    True
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

    # the source in a space-filling-curve order (cache-friendly tree queries); results
    # are reported in the caller's order
    order = morton_order(src, min_n=0, bits=10)
    unorder = np.empty_like(order)
    unorder[order] = np.arange(order.size)
    src = np.ascontiguousarray(src[order])
    c = src.mean(axis=0)

    from scipy.spatial import cKDTree

    tree = cKDTree(tgt)
    m = tgt.shape[0]

    def evaluate(motion):
        """Step 3 then step 1: move the source, pair it with its closest points."""
        moved = motion.apply(src)
        idx, d = _closest(moved, tree, m, dmax)
        return moved, idx, float(np.mean(d * d))

    motion = init
    moved, idx, cost = evaluate(motion)
    mse = [cost]
    motions = [motion]
    history = [idx[unorder]] if keep_history else None
    anderson = Anderson() if accelerate else None
    converged = False
    for _ in range(max_iter):
        ok = idx >= 0
        if np.count_nonzero(ok) < 3:
            break  # nothing left to register: stop, not converged
        # step 2: the rigid motion minimising the error for the current pairs
        plain = fit_motion(moved[ok], tgt[idx[ok]], caller="icp") @ motion
        candidate = None
        if anderson is not None:  # the option: an extrapolated motion, if not worse
            candidate = _accelerated(anderson, motion, plain, cost, evaluate, c)
        if candidate is None:
            # steps 3 and 1: move the source by it, pair again
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
        # step 4: stop when the error stops decreasing
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
