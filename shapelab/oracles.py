"""Independent oracles for the union of balls and its dual complex (Notes §23.1).

Brute force and sampling, deliberately *not* built on the dual complex, so that the
tests and the lessons can check the library's exact answers against them:

* :func:`intersection_area` and :func:`naive_union_area`: the ordinary
  inclusion–exclusion formula over all :math:`2^n - 1` subsets of disks (the formula
  the dual complex shortens, :mod:`shapelab.measure`);
* :func:`monte_carlo_union_measure`: area or volume of the union by uniform sampling,
  with its standard error;
* :func:`sampled_nerve`: the dual complex from its definition (the nerve of the
  clipped cells :math:`B_i \\cap \\Pi(B_i)`) by dense sampling;
* :func:`raster_topology`: Betti numbers of the union of disks from a raster image;
* :func:`voxel_complement`: the components of the complement of a union of balls in
  3D on a voxel grid, the bounded ones (the voids) apart.

They are slow (exponential, or sampling) and meant for small inputs.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from ._toolkit.validate import as_finite_scalar, as_positive_int, as_tau, check_balls
from .balls import Balls

__all__ = [
    "intersection_area",
    "naive_union_area",
    "monte_carlo_union_measure",
    "sampled_nerve",
    "raster_topology",
    "voxel_complement",
]

_TWO_PI = 2.0 * np.pi


# ================================================== naive formula and sampling
def intersection_area(centers, radii) -> float:
    """Exact area of the intersection of any number of disks (2D).

    Green's theorem over the boundary arcs: the boundary of a convex intersection of
    disks is made of arcs of their circles; each arc of circle (c, r) from angle
    :math:`\\phi_1` to :math:`\\phi_2` contributes
    :math:`\\tfrac12[r^2 (\\phi_2-\\phi_1) + r\\,(c_x(\\sin\\phi_2-\\sin\\phi_1)
    - c_y(\\cos\\phi_2-\\cos\\phi_1))]`.  Used by :func:`naive_union_area`; cost
    :math:`O(k^2)` for k disks.

    See Also
    --------
    naive_union_area
        Sums it over all subsets.
    """
    from ._toolkit.validate import as_points, as_radii

    C = as_points(centers, "centers", dim=2)
    r = as_radii(radii, C.shape[0], "radii")
    # exact duplicates contribute one boundary
    _, keep = np.unique(np.column_stack([C, r]), axis=0, return_index=True)
    keep = np.sort(keep)
    C, r = C[keep] - C[keep[0]], r[keep]
    k = C.shape[0]
    if k == 1:
        return float(np.pi * r[0] ** 2)
    area = 0.0
    for l in range(k):
        intervals = [(0.0, _TWO_PI)]
        for j in range(k):
            if j == l:
                continue
            dv = C[j] - C[l]
            dist = float(np.hypot(*dv))
            if dist >= r[l] + r[j]:
                return 0.0  # two disjoint (or tangent) disks: empty intersection
            if dist + r[l] <= r[j]:
                continue  # circle l inside disk j: no constraint
            if dist + r[j] <= r[l]:
                intervals = []  # disk j strictly inside disk l: circle l is outside j
                break
            t = (dist * dist + r[l] ** 2 - r[j] ** 2) / (2 * dist)
            half = float(np.arccos(np.clip(t / r[l], -1.0, 1.0)))
            mid = float(np.arctan2(dv[1], dv[0]))
            lo = (mid - half) % _TWO_PI
            arc = [(lo, lo + 2 * half)] if lo + 2 * half <= _TWO_PI else [(lo, _TWO_PI), (0.0, lo + 2 * half - _TWO_PI)]
            intervals = [
                (max(a0, b0), min(a1, b1)) for a0, a1 in intervals for b0, b1 in arc if min(a1, b1) > max(a0, b0)
            ]
            if not intervals:
                break
        cx, cy = C[l]
        for p1, p2 in intervals:
            area += 0.5 * (
                r[l] ** 2 * (p2 - p1) + r[l] * (cx * (np.sin(p2) - np.sin(p1)) - cy * (np.cos(p2) - np.cos(p1)))
            )
    return float(max(area, 0.0))


def naive_union_area(balls: Balls, *, max_balls: int = 16, max_order: int | None = None) -> tuple[float, int, int]:
    """Area of a union of disks by the *ordinary* inclusion–exclusion formula.

    :math:`\\operatorname{area} \\bigcup B_i = \\sum_{\\emptyset \\ne S \\subseteq
    \\{1..n\\}} (-1)^{|S|+1} \\operatorname{area} \\bigcap_{i \\in S} B_i`, over all
    :math:`2^n - 1` subsets (a subset whose intersection is empty makes all its
    supersets empty, which is used to skip them).  For teaching: exponential in n.

    Parameters
    ----------
    balls : Balls
        2D balls.
    max_balls : int
        Refuse more disks than this (the cost is exponential).
    max_order : int, optional
        Keep only the subsets of at most this many disks (a *truncated* formula,
        which is not the area in general; for teaching).

    Returns
    -------
    area : float
    n_subsets : int
        :math:`2^n - 1`, the number of terms of the formula.
    n_nonzero : int
        How many terms were nonzero.

    See Also
    --------
    union_measure
        The short formula this checks.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> balls = sl.Balls([[0.0, 0.0], [1.0, 0.0], [0.5, 0.8]], [1.0, 1.0, 0.7])
    >>> area, n_terms, n_nonzero = naive_union_area(balls)
    >>> n_terms, n_nonzero, bool(np.isclose(area, sl.union_measure(balls).area))
    (7, 7, True)
    """
    check_balls(balls)
    if balls.dim != 2:
        raise ValueError(f"naive_union_area works with disks (2D), got balls of dimension {balls.dim}")
    max_balls = as_positive_int(max_balls, "max_balls")
    max_order = None if max_order is None else as_positive_int(max_order, "max_order")
    n = len(balls)
    if n > max_balls:
        raise ValueError(
            f"balls has {n} disks; the naive formula has 2**n - 1 terms, allowed up to max_balls={max_balls}"
        )
    C, r = balls.centers, balls.radii
    total, nonzero = 0.0, 0
    level = [((i,), float(np.pi * r[i] ** 2)) for i in range(n)]
    size = 1
    while level and (max_order is None or size <= max_order):
        sign = 1.0 if size % 2 else -1.0
        nxt = []
        for subset, a in level:
            if a <= 0.0:
                continue
            total += sign * a
            nonzero += 1
            for j in range(subset[-1] + 1, n):
                s2 = subset + (j,)
                nxt.append((s2, intersection_area(C[list(s2)], r[list(s2)])))
        level = nxt
        size += 1
    return total, 2**n - 1, nonzero


def monte_carlo_union_measure(
    balls: Balls, n_samples: int = 100_000, *, seed: int | None = 0, chunk: int = 20_000
) -> tuple[float, float]:
    """Monte Carlo estimate of the area/volume of a union of balls.

    Samples uniformly in the bounding box; returns the estimate and its standard
    error :math:`V_{box}\\sqrt{p(1-p)/N}`.

    See Also
    --------
    union_measure
        The exact measure this estimates.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> two = sl.Balls([[0.0, 0.0], [3.0, 0.0]], [1.0, 1.0])  # disjoint: the area is 2 pi
    >>> estimate, error = monte_carlo_union_measure(two, 10_000, seed=0)
    >>> bool(abs(estimate - 2 * np.pi) < 4 * error), round(float(error), 2)
    (True, 0.05)
    """
    check_balls(balls)
    n_samples = as_positive_int(n_samples, "n_samples")
    rng = np.random.default_rng(seed)
    lo = (balls.centers - balls.radii[:, None]).min(axis=0)
    hi = (balls.centers + balls.radii[:, None]).max(axis=0)
    box = float(np.prod(hi - lo))
    hits, done = 0, 0
    while done < n_samples:
        m = min(chunk, n_samples - done)
        x = rng.uniform(lo, hi, size=(m, balls.dim))
        inside = np.zeros(m, dtype=bool)
        for i0 in range(0, len(balls), 256):
            c = balls.centers[i0 : i0 + 256]
            d2 = ((x[:, None, :] - c[None]) ** 2).sum(-1)
            inside |= (d2 <= balls.weights[i0 : i0 + 256][None]).any(axis=1)
        hits += int(inside.sum())
        done += m
    p = hits / n_samples
    return box * p, box * np.sqrt(p * (1 - p) / n_samples)


# ============================================ sampling oracles for the lessons
def _grid(balls: Balls, tau: float, spacing: float):
    w = np.maximum(balls.weights + tau, 0.0)
    r = np.sqrt(w)
    lo = (balls.centers - r[:, None]).min(axis=0) - 2 * spacing
    hi = (balls.centers + r[:, None]).max(axis=0) + 2 * spacing
    axes = [np.arange(a, b + spacing, spacing) for a, b in zip(lo, hi)]
    if np.prod([len(a) for a in axes]) > 5e6:
        raise ValueError(f"spacing={spacing!r} gives more than 5 million grid points; use a coarser spacing")
    mesh = np.meshgrid(*axes, indexing="ij")
    return np.stack([m.ravel() for m in mesh], axis=1), [len(a) for a in axes]


def sampled_nerve(
    balls: Balls, *, tau: float = 0.0, spacing: float = 0.02, margin: float | None = None, max_dim: int | None = None
) -> set:
    """The nerve of the sets :math:`B_i(\\tau) \\cap \\Pi(B_i)` found by dense sampling
    (Notes §23.1, the definition of the dual complex K).

    A grid point x *witnesses* the set of balls whose power distance at x is within
    ``margin`` of the smallest and at most ``margin`` above τ; every subset of a
    witnessed set is a simplex of the sampled nerve.  With a fine grid and a small
    margin this is the definition of K read literally, independent of any
    triangulation; simplices whose witnesses are thinner than the grid (tangent
    balls, entry times within about ``margin`` of τ) can be missed or added.

    Parameters
    ----------
    balls : Balls
    tau : float
    spacing : float
        Grid step.
    margin : float, optional
        Tolerance on power distances; default ``3 * spacing * (largest radius at τ)``,
        about the change of a power distance across one grid cell near the spheres.
        Simplices entering within about ``margin`` of τ may be reported or missed.
    max_dim : int, optional
        Largest simplex dimension reported (default d).

    Returns
    -------
    set of tuple of int
        The simplices, each a sorted tuple of ball indices.

    See Also
    --------
    dual_complex
        The exact nerve this checks.
    shapelab.triangulation.clipped_cells
        The sets whose nerve it is.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053

    Examples
    --------
    >>> import shapelab as sl
    >>> balls = sl.Balls([[0.0, 0.0], [1.5, 0.0], [5.0, 0.0]], [1.0, 1.0, 1.0])
    >>> sorted(sampled_nerve(balls, spacing=0.05))
    [(0,), (0, 1), (1,), (2,)]
    """
    check_balls(balls)
    t = as_tau(tau, finite=True)
    h = as_finite_scalar(spacing, "spacing", positive=True)
    max_dim = balls.dim if max_dim is None else as_positive_int(max_dim, "max_dim", minimum=0)
    if len(balls) == 0:
        return set()
    X, _ = _grid(balls, t, h)
    rmax = float(np.sqrt(np.maximum(balls.weights + t, 0.0)).max())
    eps = 3.0 * h * max(rmax, h) if margin is None else as_finite_scalar(margin, "margin", nonnegative=True)
    out = set()
    for i0 in range(0, len(X), 20_000):
        x = X[i0 : i0 + 20_000]
        d = x[:, None, :] - balls.centers[None]
        P = np.einsum("mnd,mnd->mn", d, d) - balls.weights[None]
        low = P.min(axis=1, keepdims=True)
        wit = (P <= low + eps) & (P <= t + eps)
        for row in np.unique(wit[wit.any(axis=1)], axis=0):
            S = tuple(int(i) for i in np.flatnonzero(row))
            for k in range(1, min(len(S), max_dim + 1) + 1):
                out.update(combinations(S, k))
    return out


def raster_topology(
    balls: Balls, *, tau: float = 0.0, spacing: float = 0.02, min_hole_pixels: int = 6
) -> tuple[int, int]:
    """Components and holes of a union of disks, counted on a raster image.

    The union of the disks grown to τ is rasterised on a grid; its connected pieces
    (8-connectivity) are the components, and the bounded pieces of the complement
    (4-connectivity, the dual choice) are the holes: :math:`(\\beta_0, \\beta_1)` of
    the union, to compare with the Betti numbers of the dual complex (Notes §23.1:
    "the topology of K(P) is the same as that of P").  Pieces of the complement
    smaller than ``min_hole_pixels`` pixels are not counted: a raster traps single
    pixels in the cusps where two circles cross.

    Returns
    -------
    tuple of int
        ``(components, holes)``.

    See Also
    --------
    shapelab.persistence.betti
        The exact Betti numbers this checks.

    Examples
    --------
    >>> import shapelab as sl
    >>> # a ring of 12 disks: one component around one hole
    >>> raster_topology(sl.datasets.ring(12), spacing=0.05)
    (1, 1)
    """
    from scipy import ndimage

    check_balls(balls)
    if balls.dim != 2:
        raise ValueError(f"raster_topology works with disks (2D), got balls of dimension {balls.dim}")
    t = as_tau(tau, finite=True)
    h = as_finite_scalar(spacing, "spacing", positive=True)
    min_hole_pixels = as_positive_int(min_hole_pixels, "min_hole_pixels")
    if len(balls) == 0:
        return 0, 0
    X, shape = _grid(balls, t, h)
    inside = np.zeros(len(X), dtype=bool)
    w = balls.weights + t
    for i0 in range(0, len(balls), 64):
        d = X[:, None, :] - balls.centers[None, i0 : i0 + 64]
        inside |= (np.einsum("mnd,mnd->mn", d, d) <= w[None, i0 : i0 + 64]).any(axis=1)
    img = inside.reshape(shape)
    _, n_comp = ndimage.label(img, structure=np.ones((3, 3), dtype=int))
    lab, n_out = ndimage.label(~img)  # the grid has a margin: exactly one unbounded piece
    sizes = np.bincount(lab.ravel())[1:]
    # pixels trapped in the cusps where two circles cross are not holes
    holes = int(np.sum(sizes >= min_hole_pixels)) - 1
    return int(n_comp), max(holes, 0)


def voxel_complement(
    balls: Balls, *, tau: float = 0.0, spacing: float = 0.1
) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The components of the complement of a union of balls, labelled on a voxel grid.

    The balls grown to τ (radius :math:`\\sqrt{r_i^2 + \\tau}`, Notes §23.1) are
    stamped into a grid of step ``spacing``: a voxel is in the union iff its centre
    lies in a closed ball.  The other voxels are grouped into components by a flood fill
    with 26-connectivity (voxels meeting at a corner are neighbours; the union's voxels
    are then connected through faces, the dual digital topology).  The grid has a margin
    of two voxels, so the unbounded component is the one touching the grid's border;
    every other component is bounded: a void (Notes §23.1, "Voids and pockets").  By
    Alexander duality their number is :math:`\\beta_2` of the union, hence of the dual
    complex :math:`K_\\tau` (lesson 07).  Nothing here uses the triangulation, so it is
    an independent check of :func:`shapelab.voids`; near an event (τ close to a birth or
    death) a voxel grid can open a thin wall or close a thin gap, so compare at τ away
    from events and at two spacings.  A margin in τ is not one in space: C60 at
    τ = -1.2, 0.27 after its pentagons close, still has hexagonal windows of radius
    0.1 Å.  On a protein the check is not available: its events are dense (T4 lysozyme
    L99A, 1290 atoms: each of τ = 0, 0.5, 1, 1.5, 2 and 3 lies within 0.001 of one), and
    even 26-connected, single voxels trapped where four or five spheres pass within a
    voxel of their centre count as components (three at τ = 0 and spacing 0.15, where
    the α-complex has one void of 2e-5 Å³, far below a voxel).

    Parameters
    ----------
    balls : Balls
        Balls in 3D.
    tau : float
        Growth time.
    spacing : float
        Voxel edge length (same unit as the centres).

    Returns
    -------
    labels : ndarray of int32, shape (nx, ny, nz)
        0 for a voxel in the union, 1 for the unbounded component of the complement,
        2, 3, ... for the bounded components (so there are ``labels.max() - 1`` voids).
    axes : tuple of 3 ndarrays
        The voxel centres' coordinates along x, y and z.

    Raises
    ------
    ValueError
        If the balls are not 3D, or the grid would have more than 5e7 voxels.

    See Also
    --------
    shapelab.voids : the voids from the dual complex.
    raster_topology : the same idea for disks in the plane.

    References
    ----------
    .. [1] Lecture notes, §23.1 ("Voids and pockets").
    .. [2] A. Hatcher, *Algebraic Topology*, Cambridge University Press, 2002,
       Theorem 3.44 (Alexander duality).
    .. [3] T. Y. Kong and A. Rosenfeld, "Digital topology: introduction and survey",
       Computer Vision, Graphics, and Image Processing 48 (1989) 357-393.

    Examples
    --------
    >>> from shapelab.datasets import fullerene_c60
    >>> labels, axes = voxel_complement(fullerene_c60(), tau=0.0, spacing=0.2)
    >>> int(labels.max()) - 1  # bounded components: C60's one void
    1
    """
    from scipy import ndimage

    check_balls(balls)
    if balls.dim != 3:
        raise ValueError(f"voxel_complement works with balls in 3D, got balls of dimension {balls.dim}")
    t = as_tau(tau, finite=True)
    h = as_finite_scalar(spacing, "spacing", positive=True)
    w = balls.weights + t
    keep = w >= 0
    C, w = balls.centers[keep], w[keep]
    if len(C) == 0:
        return np.ones((1, 1, 1), dtype=np.int32), tuple(np.zeros(1) for _ in range(3))
    r = np.sqrt(w)
    lo = (C - r[:, None]).min(axis=0) - 2 * h
    hi = (C + r[:, None]).max(axis=0) + 2 * h
    axes = tuple(np.arange(a, b + h, h) for a, b in zip(lo, hi))
    shape = tuple(len(a) for a in axes)
    if np.prod(shape, dtype=float) > 5e7:
        raise ValueError(f"spacing={spacing!r} gives more than 5e7 voxels; use a coarser spacing")
    inside = np.zeros(shape, dtype=bool)
    for c, ri, wi in zip(C, r, w):
        box, offsets = [], []
        for k in range(3):
            i0 = max(int(np.ceil((c[k] - ri - lo[k]) / h)), 0)
            i1 = min(int(np.floor((c[k] + ri - lo[k]) / h)) + 1, shape[k])
            box.append(slice(i0, i1))
            offsets.append(axes[k][i0:i1] - c[k])
        dx, dy, dz = offsets
        inside[tuple(box)] |= dx[:, None, None] ** 2 + dy[None, :, None] ** 2 + dz[None, None, :] ** 2 <= wi
    lab, n = ndimage.label(~inside, structure=np.ones((3, 3, 3), dtype=int))
    faces = [lab[0], lab[-1], lab[:, 0], lab[:, -1], lab[:, :, 0], lab[:, :, -1]]
    outer = np.unique(np.concatenate([f.ravel() for f in faces]))
    new = np.zeros(n + 1, dtype=np.int32)
    new[1:] = 1
    bounded = np.setdiff1d(np.arange(1, n + 1), outer)
    new[bounded] = np.arange(2, 2 + len(bounded), dtype=np.int32)
    return new[lab], axes
