"""Input validation shared by every public entry point of shapelab.

One rule per kind of input: arrays of numbers become float64 (:func:`as_float_array`,
ints, bools and floats accepted, complex and strings refused); results handed out are
read-only copies (:func:`readonly`); τ is a real number, never NaN, and ``±inf`` is
allowed unless ``finite=True`` (:func:`as_tau`); balls are checked once, by
:class:`shapelab.Balls`.

Every function here raises :class:`ValueError` or :class:`TypeError` with a message
that names the offending argument, so that a student sees *which* input is wrong and
*why*, instead of a crash deep inside numpy or a silent NaN.
"""

from __future__ import annotations

import numbers

import numpy as np

from .bases import BallsBase

__all__ = [
    "as_float_array",
    "as_precision",
    "check_finite",
    "readonly",
    "freeze",
    "check_balls",
    "as_bbox",
    "default_bbox",
    "as_points",
    "as_point_pair",
    "as_point",
    "as_vector",
    "as_radii",
    "as_finite_scalar",
    "as_tau",
    "as_positive_int",
    "check_same_shape",
]


def as_float_array(x, name: str) -> np.ndarray:
    if isinstance(x, (str, bytes)):
        raise TypeError(f"{name} must be an array of numbers, got {type(x).__name__}")
    try:
        arr = np.asarray(x)
    except Exception as exc:  # ragged lists and the like
        raise ValueError(f"{name} could not be read as an array: {exc}") from None
    if arr.dtype == object:
        raise ValueError(f"{name} must be a rectangular array of numbers (got a ragged or object array)")
    if arr.dtype.kind == "c":
        raise TypeError(f"{name} must be real, got complex values")
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"{name} must hold numbers, got dtype {arr.dtype}")
    return arr.astype(np.float64, copy=False)


def check_finite(arr: np.ndarray, name: str) -> None:
    if not np.all(np.isfinite(arr)):
        bad = np.argwhere(~np.isfinite(arr))[0]
        where = tuple(int(i) for i in bad)
        raise ValueError(f"{name} must be finite; found {float(arr[tuple(bad)])!r} at index {where}")


def as_simplex_balls(centers, weights) -> tuple[np.ndarray, np.ndarray]:
    """``centers`` (..., j + 1, d) with ``j + 1 <= d + 1`` and ``weights`` (..., j + 1),
    finite float64: the balls of one simplex, or of many along the leading axes."""
    z = as_float_array(centers, "centers")
    w = as_float_array(weights, "weights")
    if z.ndim < 2 or z.shape[-1] < 1 or not 1 <= z.shape[-2] <= z.shape[-1] + 1:
        raise ValueError(
            f"centers must have shape (..., j + 1, d) with 1 <= j + 1 <= d + 1 (a simplex's balls), got {z.shape}"
        )
    if w.shape != z.shape[:-1]:
        raise ValueError(f"weights must have shape {z.shape[:-1]} (one per centre), got {w.shape}")
    check_finite(z, "centers")
    check_finite(w, "weights")
    return z, w


class FlatSimplexError(ValueError):
    """Affinely dependent centres (a flat simplex has no orthosphere), or centres so
    nearly so that float64 cannot place its orthosphere."""


#: a float64 solve of ``A u = beta`` keeps about ``16 - log10(cond)`` digits: refused
#: when fewer than about 6 would be left (the exact path computes those spheres)
NEARLY_FLAT = 1e10


def flat_simplex(who: str, *, nearly: bool = False) -> FlatSimplexError:
    """The error for a flat simplex, or one too nearly flat for float64."""
    if nearly:
        return FlatSimplexError(
            f"{who}: the simplex is nearly flat (its edges' condition number exceeds {NEARLY_FLAT:.0e}): "
            "float64 cannot place its orthosphere; precision='exact' computes it exactly"
        )
    return FlatSimplexError(f"{who}: the centres are affinely dependent (a flat simplex has no orthosphere)")


def nearly_flat(A: np.ndarray) -> bool:
    """Whether some edge matrix ``A`` (..., j, d) of a simplex known not to be flat has,
    with its rows scaled to unit size, a condition number above :data:`NEARLY_FLAT`."""
    if A.size == 0:
        return False
    An = A / np.abs(A).max(axis=-1, keepdims=True)
    s = np.linalg.svd(An, compute_uv=False)
    return bool(np.any(s[..., -1] * NEARLY_FLAT < s[..., 0]))


def as_points(x, name: str = "points", *, dim=None, min_points: int = 1) -> np.ndarray:
    """Return ``x`` as a finite float64 array of shape (n, d).

    Parameters
    ----------
    x : array_like
        The points, one per row.
    name : str
        The argument's name, used in error messages.
    dim : int or tuple of int, optional
        The allowed dimension(s) d.
    min_points : int
        The least number of rows accepted.
    """
    arr = as_float_array(x, name)
    if arr.ndim != 2:
        raise ValueError(f"{name} must be a 2-D array of shape (n, d), got shape {arr.shape}")
    if dim is not None:
        allowed = (dim,) if isinstance(dim, numbers.Integral) else tuple(dim)
        if arr.shape[1] not in allowed:
            want = " or ".join(str(a) for a in allowed)
            raise ValueError(f"{name} must have {want} columns (dimension), got shape {arr.shape}")
    if arr.shape[0] < min_points:
        raise ValueError(f"{name} must hold at least {min_points} point(s), got {arr.shape[0]}")
    check_finite(arr, name)
    return np.ascontiguousarray(arr)


def as_point_pair(A, B, names=("A", "B")) -> tuple[np.ndarray, np.ndarray]:
    """Two point sets of the same dimension, as :func:`as_points` returns each.

    >>> a, b = as_point_pair([[0.0, 0.0]], [[1.0, 2.0], [3.0, 4.0]])
    >>> a.shape, b.shape
    ((1, 2), (2, 2))
    """
    A = as_points(A, names[0])
    B = as_points(B, names[1])
    if A.shape[1] != B.shape[1]:
        raise ValueError(
            f"{names[0]} and {names[1]} must have the same dimension, got {names[0]} with {A.shape[1]} "
            f"and {names[1]} with {B.shape[1]} columns"
        )
    return A, B


def as_point(x, name: str = "point", *, dim=None) -> np.ndarray:
    """Return ``x`` as a finite float64 vector of shape (d,)."""
    arr = as_float_array(x, name)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a single point of shape (d,), got shape {arr.shape}")
    if dim is not None:
        allowed = (dim,) if isinstance(dim, numbers.Integral) else tuple(dim)
        if arr.shape[0] not in allowed:
            want = " or ".join(str(a) for a in allowed)
            raise ValueError(f"{name} must have {want} coordinates, got {arr.shape[0]}")
    check_finite(arr, name)
    return arr


def as_vector(x, name: str, *, length: int | None = None) -> np.ndarray:
    """Return ``x`` as a finite float64 1-D array, optionally of a given length."""
    arr = as_float_array(x, name)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array, got shape {arr.shape}")
    if length is not None and arr.shape[0] != length:
        raise ValueError(f"{name} must have length {length}, got {arr.shape[0]}")
    check_finite(arr, name)
    return arr


def as_radii(r, n: int, name: str = "radii") -> np.ndarray:
    """Return radii as a float64 array of shape (n,), finite and non-negative.

    A scalar is broadcast to all n balls.
    """
    arr = as_float_array(r, name)
    if arr.ndim == 0:
        arr = np.full(n, float(arr))
    if arr.ndim != 1 or arr.shape[0] != n:
        raise ValueError(f"{name} must have shape ({n},) to match the centers, got shape {arr.shape}")
    check_finite(arr, name)
    if np.any(arr < 0):
        i = int(np.argmax(arr < 0))
        raise ValueError(f"{name} must be non-negative; {name}[{i}] = {float(arr[i])!r}")
    return np.ascontiguousarray(arr)


def as_finite_scalar(x, name: str, *, positive: bool = False, nonnegative: bool = False) -> float:
    """Return ``x`` as a finite float, optionally > 0 or >= 0."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (numbers.Real, np.floating, np.integer)):
        if not (isinstance(x, np.ndarray) and x.ndim == 0 and x.dtype.kind in "iuf"):
            raise TypeError(f"{name} must be a real number, got {type(x).__name__}")
    v = float(x)
    if not np.isfinite(v):
        raise ValueError(f"{name} must be finite, got {v!r}")
    if positive and not v > 0:
        raise ValueError(f"{name} must be positive, got {v!r}")
    if nonnegative and v < 0:
        raise ValueError(f"{name} must be non-negative, got {v!r}")
    return v


def as_positive_int(x, name: str, *, minimum: int = 1) -> int:
    """Return ``x`` as an int >= ``minimum``."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (numbers.Integral, np.integer)):
        raise TypeError(f"{name} must be an integer, got {type(x).__name__}")
    v = int(x)
    if v < minimum:
        raise ValueError(f"{name} must be at least {minimum}, got {v}")
    return v


def check_same_shape(a: np.ndarray, b: np.ndarray, name_a: str, name_b: str) -> None:
    """Raise if two arrays of points do not pair up row by row."""
    if a.shape != b.shape:
        raise ValueError(f"{name_a} and {name_b} must have the same shape to be paired, got {a.shape} and {b.shape}")


def as_tau(tau, name: str = "tau", *, finite: bool = False) -> float:
    """Return a growth time τ (Notes §23.1: radii :math:`\\sqrt{r_i^2 + \\tau}`) as a float.

    The one rule for τ everywhere in shapelab: a real number (Python, NumPy scalar or
    0-d array of numbers), never a bool or a string, never NaN.  ``±inf`` is accepted:
    ``-inf`` is the start of the filtration (no ball yet, the empty complex) and
    ``inf`` its end (the whole triangulation).

    Parameters
    ----------
    tau : real
    name : str
        The argument's name, used in error messages.
    finite : bool
        Also reject ``±inf``: for what needs balls of finite radius (a measure of
        the union, a picture of the grown balls).
    """
    if isinstance(tau, (bool, np.bool_)) or not isinstance(tau, (numbers.Real, np.floating, np.integer)):
        if not (isinstance(tau, np.ndarray) and tau.ndim == 0 and tau.dtype.kind in "iuf"):
            raise TypeError(f"{name} must be a real number, got {type(tau).__name__}")
    t = float(tau)
    if np.isnan(t):
        raise ValueError(f"{name} must not be NaN")
    if finite and not np.isfinite(t):
        raise ValueError(f"{name} must be finite here (balls grown by {name} = {t!r} have no finite size)")
    return t


def readonly(a, dtype=None) -> np.ndarray:
    """A read-only copy of ``a`` (as ``dtype`` if given, else with its own dtype), for
    the arrays that results hand out.  Validate and convert numbers first
    (:func:`as_points`, :func:`as_radii`, ... give float64): this only freezes."""
    a = np.array(a, dtype=dtype, copy=True)
    a.flags.writeable = False
    return a


def freeze(a: np.ndarray) -> np.ndarray:
    """Make ``a`` read-only in place (no copy) and return it."""
    a.flags.writeable = False
    return a


def check_balls(balls, name: str = "balls", *, dim: int | None = None):
    """Return ``balls`` if it is a :class:`shapelab.Balls` (of dimension ``dim`` if
    given), else raise a TypeError/ValueError naming ``name``.  The one ball check:
    the centres and radii themselves were validated when the Balls was built."""
    if not isinstance(balls, BallsBase):
        raise TypeError(f"{name} must be a shapelab.Balls, got {type(balls).__name__}")
    if dim is not None and balls.dim != dim:
        raise ValueError(f"{name} must be {dim}-dimensional here, got dim={balls.dim}")
    return balls


def default_bbox(balls) -> np.ndarray:
    """The balls' bounding box padded by 10 % of its largest extent (1 if it is a point),
    as ``[lower corner, upper corner]``."""
    lo = np.min(balls.centers - balls.radii[:, None], axis=0)
    hi = np.max(balls.centers + balls.radii[:, None], axis=0)
    ext = float(np.max(hi - lo))
    pad = 0.1 * ext if ext > 0 else 1.0
    return np.array([lo - pad, hi + pad])


def as_bbox(bbox, d: int) -> np.ndarray:
    """Return ``bbox`` as a finite (2, d) array ``[lower corner, upper corner]``;
    a flat ``(2d,)`` array is read as the lower corner then the upper one."""
    b = as_float_array(bbox, "bbox")
    if b.shape == (2 * d,):
        b = b.reshape(2, d) if d == 2 else np.array([b[:d], b[d:]])
    if b.shape != (2, d):
        raise ValueError(f"bbox must have shape (2, {d}) as [lower corner, upper corner], got shape {b.shape}")
    check_finite(b, "bbox")
    if np.any(b[1] <= b[0]):
        raise ValueError(f"bbox must have lower corner < upper corner in every coordinate, got {b.tolist()}")
    return b


#: the values of the seam ``precision`` (issue 33): ``"exact"`` runs the engine
#: (certified, the same on every machine), ``"fast"`` the readable floating-point path
PRECISIONS = ("exact", "fast")


def as_precision(precision, name: str = "precision") -> str:
    """Return ``precision`` if it is one of :data:`PRECISIONS`, else raise."""
    if not isinstance(precision, str) or precision not in PRECISIONS:
        raise ValueError(f"{name} must be 'exact' or 'fast', got {precision!r}")
    return precision
