"""Shared input validation: every message names the argument and the problem."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from shapelab._toolkit import validate as v


def test_points_accepts_lists_and_returns_float64():
    out = v.as_points([[1, 2], [3, 4]], "A", dim=2)
    assert out.dtype == np.float64 and out.shape == (2, 2) and out.flags.c_contiguous


@pytest.mark.parametrize(
    "bad, exc, words",
    [
        ([1.0, 2.0], ValueError, "A must be a 2-D array"),
        ([[1.0, np.nan]], ValueError, "A must be finite"),
        ([[1.0, np.inf]], ValueError, "A must be finite"),
        ("abc", TypeError, "A must be an array"),
        ([[1 + 2j, 0]], TypeError, "A must be real"),
        ([[1.0, 2.0], [3.0]], ValueError, "A"),
        (np.zeros((0, 2)), ValueError, "at least 1"),
        (np.zeros((3, 4)), ValueError, "2 or 3 columns"),
    ],
)
def test_points_rejections_name_the_argument(bad, exc, words):
    with pytest.raises(exc, match=words):
        v.as_points(bad, "A", dim=(2, 3))


def test_radii_broadcast_and_reject():
    assert np.array_equal(v.as_radii(2.0, 3), [2.0, 2.0, 2.0])
    with pytest.raises(ValueError, match=r"radii\[1\] = -1"):
        v.as_radii([1.0, -1.0], 2)
    with pytest.raises(ValueError, match=r"shape \(3,\)"):
        v.as_radii([1.0, 1.0], 3)
    with pytest.raises(ValueError, match="finite"):
        v.as_radii([1.0, np.nan], 2)


def test_scalars_and_ints():
    assert v.as_finite_scalar(np.float32(2.5), "tol", positive=True) == 2.5
    with pytest.raises(TypeError, match="tol must be a real number"):
        v.as_finite_scalar("1", "tol")
    with pytest.raises(TypeError, match="tol"):
        v.as_finite_scalar(True, "tol")
    with pytest.raises(ValueError, match="tol must be positive"):
        v.as_finite_scalar(0.0, "tol", positive=True)
    with pytest.raises(ValueError, match="finite"):
        v.as_finite_scalar(float("nan"), "tol")
    assert v.as_positive_int(np.int64(3), "max_iter") == 3
    with pytest.raises(TypeError, match="max_iter must be an integer"):
        v.as_positive_int(2.0, "max_iter")
    with pytest.raises(ValueError, match="at least 1"):
        v.as_positive_int(0, "max_iter")


def test_same_shape():
    with pytest.raises(ValueError, match="R and G must have the same shape"):
        v.check_same_shape(np.zeros((3, 3)), np.zeros((4, 3)), "R", "G")


@settings(max_examples=60, deadline=None)
@given(
    hnp.arrays(
        np.float64,
        hnp.array_shapes(min_dims=2, max_dims=2, min_side=1, max_side=5),
        elements=st.floats(allow_nan=True, allow_infinity=True, width=64),
    )
)
def test_points_never_lets_a_nonfinite_value_through(arr):
    try:
        out = v.as_points(arr, "P")
    except ValueError as exc:
        assert "P" in str(exc)
        assert not np.all(np.isfinite(arr))
    else:
        assert np.all(np.isfinite(out)) and np.array_equal(out, arr)
