"""Sampled shapes: point clouds, curves and meshes for matching, critical points, ICP and
classification (Notes §23.2).

======================  =========================================================
:func:`noisy_sphere`    points of the unit sphere plus Gaussian noise (lesson 14)
:func:`ellipse_curve`   an ellipse as a function of its parameter (lessons 13, 14)
:func:`blob_curve`      a smooth closed curve with several critical points (lessons 11, 13)
:func:`icosphere`       a subdivided icosahedron: a triangulated sphere
:func:`bumpy_sphere`    an icosphere with radial bumps (lesson 13)
:func:`torus`           a triangulated torus (lesson 13)
:func:`sample_shape`    random points on a closed test surface (lesson 15)
:func:`shape_family`    classes of sampled shapes (lesson 19)
======================  =========================================================

Every random choice comes from a seeded generator: the same call gives the same points
on every machine.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .._toolkit.validate import as_finite_scalar, as_point, as_positive_int
from ._common import seeded_rng

__all__ = [
    "noisy_sphere",
    "blob_curve",
    "ellipse_curve",
    "icosphere",
    "bumpy_sphere",
    "torus",
    "sample_shape",
    "shape_family",
]


def noisy_sphere(
    n: int, *, noise: float = 0.01, center: ArrayLike = (0.0, 0.0, 0.0), seed: int | np.random.Generator = 0
) -> np.ndarray:
    """``n`` points of the unit sphere (uniform directions) plus isotropic Gaussian
    noise of standard deviation ``noise``, moved to ``center``; deterministic in
    ``seed``.  The data of the benchmarks and of lesson 14.

    See Also
    --------
    shapelab.diagrams.bottleneck_distance
        Compare the diagrams of noisy samples.

    Examples
    --------
    >>> import numpy as np
    >>> x = noisy_sphere(100, seed=0)
    >>> x.shape, round(float(np.linalg.norm(x, axis=1).mean()), 2)
    ((100, 3), 1.0)
    """
    n = as_positive_int(n, "n")
    noise = as_finite_scalar(noise, "noise", nonnegative=True)
    c = np.asarray(center, dtype=float)
    if c.shape != (3,) or not np.all(np.isfinite(c)):
        raise ValueError(f"center must be a finite 3-vector, got {center!r}")
    rng = np.random.default_rng(seed)
    x = rng.standard_normal((n, 3))
    x /= np.linalg.norm(x, axis=1, keepdims=True)
    return x + noise * rng.standard_normal((n, 3)) + c


# --------------------------------------------------------------------------- curves and meshes
# (critical points, lessons 13 and 14)
def ellipse_curve(a: float = 2.0, b: float = 1.0, center: ArrayLike = (0.0, 0.0)) -> Callable[[ArrayLike], np.ndarray]:
    """The ellipse ``t -> center + (a cos t, b sin t)`` as a vectorised function.

    See Also
    --------
    shapelab.critical.polyline
        Samples it.
    critical_points
        Its critical points.

    Examples
    --------
    >>> import numpy as np
    >>> gamma = ellipse_curve(2.0, 1.0)
    >>> np.round(gamma(np.array([0.0, np.pi / 2])), 12).tolist()  # component-first: x row, y row
    [[2.0, 0.0], [0.0, 1.0]]
    """
    a = as_finite_scalar(a, "a", positive=True)
    b = as_finite_scalar(b, "b", positive=True)
    c = as_point(center, "center", dim=2)

    def fn(t):
        t = np.asarray(t, dtype=float)
        return np.array([c[0] + a * np.cos(t), c[1] + b * np.sin(t)])

    return fn


def blob_curve(t: ArrayLike) -> np.ndarray:
    """A smooth star-shaped closed curve like the one of Figure 23.3.

    ``r(t) = 1 + 0.25 cos 3t + 0.12 sin(2t + 0.6)`` in polar coordinates about
    the origin; vectorised: returns ``(x, y)``.  Seen from S = (0.1, 0.05) it has
    three minima and three maxima.

    See Also
    --------
    shapelab.critical.polyline
        Samples it.
    critical_points
        Its critical points.

    Examples
    --------
    >>> import numpy as np
    >>> blob_curve(np.linspace(0, 2 * np.pi, 5)).shape  # component-first
    (2, 5)
    """
    t = np.asarray(t, dtype=float)
    r = 1.0 + 0.25 * np.cos(3 * t) + 0.12 * np.sin(2 * t + 0.6)
    return np.array([r * np.cos(t), r * np.sin(t)])


def icosphere(subdivisions: int = 2, radius: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """A triangulated sphere: the icosahedron, each triangle split in 4
    ``subdivisions`` times, vertices pushed to the sphere.

    Returns ``(vertices, faces)`` with ``10 * 4**s + 2`` vertices and
    ``20 * 4**s`` outward-oriented triangles.

    See Also
    --------
    bumpy_sphere
        A sphere with bumps.
    shapelab.critical.euler_characteristic
        χ = 2.

    Examples
    --------
    >>> V, F = icosphere(2)
    >>> V.shape, F.shape
    ((162, 3), (320, 3))
    """
    subdivisions = as_positive_int(subdivisions, "subdivisions", minimum=0)
    if subdivisions > 7:
        raise ValueError(f"subdivisions must be at most 7 (>{10 * 4**7} vertices), got {subdivisions}")
    radius = as_finite_scalar(radius, "radius", positive=True)
    p = (1.0 + np.sqrt(5.0)) / 2.0
    V = np.array(
        [
            [-1, p, 0],
            [1, p, 0],
            [-1, -p, 0],
            [1, -p, 0],
            [0, -1, p],
            [0, 1, p],
            [0, -1, -p],
            [0, 1, -p],
            [p, 0, -1],
            [p, 0, 1],
            [-p, 0, -1],
            [-p, 0, 1],
        ],
        dtype=float,
    )
    F = np.array(
        [
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ],
        dtype=np.intp,
    )
    V /= np.linalg.norm(V, axis=1, keepdims=True)
    for _ in range(subdivisions):
        e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
        e.sort(axis=1)
        uniq, inv = np.unique(e, axis=0, return_inverse=True)
        inv = inv.ravel()
        mid = V[uniq[:, 0]] + V[uniq[:, 1]]
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        m = V.shape[0] + inv.reshape(3, -1)  # midpoints of edges 01, 12, 20 of each face
        a, b, c = F[:, 0], F[:, 1], F[:, 2]
        F = np.concatenate(
            [
                np.stack([a, m[0], m[2]], 1),
                np.stack([b, m[1], m[0]], 1),
                np.stack([c, m[2], m[1]], 1),
                np.stack([m[0], m[1], m[2]], 1),
            ]
        )
        V = np.vstack([V, mid])
    return radius * V, F


def bumpy_sphere(
    subdivisions: int = 3, *, bumps: int = 6, amplitude: float = 0.3, seed: int | np.random.Generator = 0
) -> tuple[np.ndarray, np.ndarray]:
    """An icosphere pushed radially by ``bumps`` random Gaussian bumps and dents:
    a closed star-shaped surface with several minima, maxima and saddles.

    Returns ``(vertices, faces)``; deterministic in ``seed``.

    See Also
    --------
    icosphere
        The smooth sphere.
    critical_points
        Its critical points.

    Examples
    --------
    >>> V, F = bumpy_sphere()
    >>> V.shape, F.shape
    ((642, 3), (1280, 3))
    """
    bumps = as_positive_int(bumps, "bumps", minimum=0)
    amplitude = as_finite_scalar(amplitude, "amplitude", nonnegative=True)
    if amplitude >= 1:
        raise ValueError(f"amplitude must be below 1 (the surface must stay star-shaped), got {amplitude}")
    V, F = icosphere(subdivisions)
    rng = np.random.default_rng(seed)
    centers = rng.standard_normal((bumps, 3))
    centers /= np.linalg.norm(centers, axis=1, keepdims=True)
    heights = rng.uniform(-1.0, 1.0, bumps)
    widths = rng.uniform(0.25, 0.6, bumps)
    r = np.ones(V.shape[0])
    for c, h, w in zip(centers, heights, widths):
        r += amplitude * h * np.exp(-np.sum((V - c) ** 2, axis=1) / (2 * w * w))
    r = np.clip(r, 0.1, None)
    return V * r[:, None], F


def torus(n_major: int = 24, n_minor: int = 12, *, R: float = 1.0, r: float = 0.4) -> tuple[np.ndarray, np.ndarray]:
    """A triangulated torus (χ = 0) around the z axis: ``n_major * n_minor``
    vertices, ``2 * n_major * n_minor`` triangles.

    See Also
    --------
    icosphere
        A sphere.
    shapelab.critical.euler_characteristic
        χ = 0.

    Examples
    --------
    >>> V, F = torus()
    >>> V.shape, F.shape
    ((288, 3), (576, 3))
    """
    n_major = as_positive_int(n_major, "n_major", minimum=3)
    n_minor = as_positive_int(n_minor, "n_minor", minimum=3)
    R = as_finite_scalar(R, "R", positive=True)
    r = as_finite_scalar(r, "r", positive=True)
    if r >= R:
        raise ValueError(f"r must be smaller than R for an embedded torus, got r={r}, R={R}")
    u = np.arange(n_major) * (2.0 * np.pi / n_major)
    v = np.arange(n_minor) * (2.0 * np.pi / n_minor)
    U, W = np.meshgrid(u, v, indexing="ij")
    V = np.stack([(R + r * np.cos(W)) * np.cos(U), (R + r * np.cos(W)) * np.sin(U), r * np.sin(W)], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n_major), np.arange(n_minor), indexing="ij")
    a = i * n_minor + j
    b = ((i + 1) % n_major) * n_minor + j
    c = ((i + 1) % n_major) * n_minor + (j + 1) % n_minor
    d = i * n_minor + (j + 1) % n_minor
    F = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return V, F


# --------------------------------------------------------------------------- shapes for ICP (lesson 15)
def sample_shape(kind: str, n: int, *, seed: int = 0) -> np.ndarray:
    """Random points on a closed test surface, for ICP demos, tests and benchmarks.

    Parameters
    ----------
    kind : {"lumpy", "ellipsoid", "sphere", "cube", "torus"}
        ``"lumpy"``: an ellipsoid with semi-axes (1, 0.75, 0.55) carrying five bumps
        of different sizes in asymmetric directions — no symmetry at all, so ICP has
        a unique answer.  ``"ellipsoid"``: the same ellipsoid without bumps (three
        mirror planes, 4 rotational symmetries).  ``"sphere"``: the unit sphere (every
        rotation is a symmetry).  ``"cube"``: the surface of the cube [-1, 1]³
        (24 rotational symmetries), uniformly.  ``"torus"``: the torus of radii 1 and
        0.4 about the z axis, with both angles uniform (denser on the inner side).
    n : int
        Number of points.
    seed : int
        Seed of :func:`numpy.random.default_rng`; two different seeds give two
        independent samplings of the same surface.

    Returns
    -------
    ndarray, shape (n, 3)
        For the smooth shapes the direction from the origin is uniform on the sphere
        (not uniform in area); the cube is uniform in area.

    See Also
    --------
    icp
        Registers sampled shapes.
    shape_family
        Shapes in classes.

    Examples
    --------
    >>> sample_shape("torus", 50, seed=0).shape
    (50, 3)
    """
    if not isinstance(kind, str):
        raise TypeError(f"kind must be a string, got {type(kind).__name__}")
    n = as_positive_int(n, "n")
    rng = np.random.default_rng(seed)
    if kind == "torus":
        u, v = rng.uniform(0.0, 2.0 * np.pi, (2, n))
        ring = 1.0 + 0.4 * np.cos(v)
        return np.column_stack([ring * np.cos(u), ring * np.sin(u), 0.4 * np.sin(v)])
    if kind == "cube":
        face = rng.integers(0, 6, n)
        p = rng.uniform(-1.0, 1.0, (n, 3))
        axis = face % 3
        p[np.arange(n), axis] = np.where(face < 3, 1.0, -1.0)
        return p
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    if kind == "sphere":
        return u
    semi = np.array([1.0, 0.75, 0.55])
    if kind == "ellipsoid":
        return u * semi
    if kind == "lumpy":
        centres = np.array([[1, 0.3, 0.2], [-0.4, 1, 0.5], [0.2, -0.6, 1], [-1, -0.5, -0.3], [0.5, 0.4, -1]], float)
        centres /= np.linalg.norm(centres, axis=1, keepdims=True)
        height = np.array([0.35, 0.25, 0.3, 0.15, 0.2])
        width = np.array([0.15, 0.25, 0.1, 0.3, 0.2])
        rho = 1.0 + (height * np.exp((u @ centres.T - 1.0) / width)).sum(axis=1)
        return u * rho[:, None] * semi
    raise ValueError(f"kind must be one of 'lumpy', 'ellipsoid', 'sphere', 'cube', 'torus'; got {kind!r}")


def shape_family(
    kinds: Sequence[str] = ("sphere", "ellipsoid", "cube", "torus"),
    per_class: int = 5,
    n: int = 400,
    *,
    noise: float = 0.02,
    seed: int | np.random.Generator = 0,
) -> tuple[list[np.ndarray], list[str]]:
    """A family of sampled shapes in classes, for shape classification (lesson 19).

    Each member is :func:`sample_shape` of its kind with its own sampling, turned by a
    random rotation, scaled by a factor in [0.95, 1.05] and moved by Gaussian noise of
    standard deviation ``noise``; deterministic in ``seed``.

    Returns
    -------
    shapes : list of ndarray, shape (n, 3)
    labels : list of str
        The kind of each shape; members of one class are contiguous.

    See Also
    --------
    sample_shape
        One shape.
    shapelab.diagrams.distance_matrix
        Compares the family's diagrams.

    Examples
    --------
    >>> shapes, labels = shape_family(("sphere", "torus"), per_class=2, n=50)
    >>> len(shapes), labels
    (4, ['sphere', 'sphere', 'torus', 'torus'])
    """
    from ..quaternion import Quaternion

    if isinstance(kinds, str) or not kinds:
        raise TypeError("kinds must be a non-empty sequence of shape kinds")
    per_class = as_positive_int(per_class, "per_class")
    n = as_positive_int(n, "n", minimum=4)
    noise = as_finite_scalar(noise, "noise", nonnegative=True)
    rng = seeded_rng(seed)
    shapes, labels = [], []
    for kind in kinds:
        for _ in range(per_class):
            X = sample_shape(kind, n, seed=int(rng.integers(2**31)))
            q = Quaternion(*rng.normal(size=4))
            X = q.rotate(X) * rng.uniform(0.95, 1.05) + noise * rng.normal(size=X.shape)
            shapes.append(X)
            labels.append(str(kind))
    return shapes, labels
