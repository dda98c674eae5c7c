"""What the generators of :mod:`shapelab.datasets` share: seeded random generators,
machine-independent cosines, jitter, distances to a segment.  Private to the package
(its names carry no underscore because its modules import them)."""

from __future__ import annotations

import numpy as np

from .._toolkit.validate import as_positive_int

__all__ = ["seeded_rng", "cos_sin", "ball_jitter", "dist_segment"]


def seeded_rng(seed) -> np.random.Generator:
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is None or isinstance(seed, (bool, np.bool_)):
        raise TypeError("seed must be an int or a numpy Generator (datasets are deterministic)")
    return np.random.default_rng(as_positive_int(seed, "seed", minimum=0))


def cos_sin(t: np.ndarray):
    """``cos t`` and ``sin t`` rounded to multiples of :math:`2^{-32}`, the same on every
    machine.

    NumPy's trigonometric functions may differ in the last bit between CPUs (SIMD
    implementations), and the generated molecules are deliberately degenerate
    (co-circular rings, co-cylindrical tubes), where the exact triangulation follows
    those bits.  Rounding to a grid far coarser than one ulp makes the coordinates
    identical everywhere, except for a value within one ulp of a half-grid point
    (probability about :math:`2^{-20}` each); the shapes move by under
    :math:`2^{-33}` of their size.
    """
    q = 2.0**32
    return np.rint(np.cos(t) * q) / q, np.rint(np.sin(t) * q) / q


def ball_jitter(rng: np.random.Generator, n: int, amount: float, dim: int = 3) -> np.ndarray:
    """n vectors uniform in the ball of radius ``amount``."""
    v = rng.normal(size=(n, dim))
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    return v * (amount * rng.random(n) ** (1.0 / dim))[:, None]


def dist_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.clip(((p - a) @ ab) / (ab @ ab), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


# feature positions as fractions of the semi-axes; mouth and slit are directions
