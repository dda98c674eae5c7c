"""Tests of shapelab.balls: the Balls container and the power distance (Notes §23.1)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from shapelab import Balls, alpha_filtration, power_distance


def test_construction_and_accessors():
    b = Balls([[0, 0], [3, 4], [1, 1]], [1.0, 2.0, 0.5])
    assert len(b) == 3 and b.dim == 2
    assert b.centers.dtype == np.float64 and b.radii.dtype == np.float64
    np.testing.assert_array_equal(b.weights, [1.0, 4.0, 0.25])
    with pytest.raises(ValueError):
        b.centers[0, 0] = 5.0
    with pytest.raises(ValueError):
        b.radii[0] = 5.0
    with pytest.raises(Exception):
        b.radii = np.zeros(3)  # frozen
    # a scalar radius is broadcast; the input is copied
    c = np.zeros((4, 3))
    b3 = Balls(c, 2)
    c[0, 0] = 9.0
    assert b3.dim == 3 and b3.radii.tolist() == [2.0] * 4 and b3.centers[0, 0] == 0.0


def test_indexing():
    b = Balls([[0, 0], [3, 4], [1, 1]], [1.0, 2.0, 0.5])
    assert len(b[1]) == 1 and b[1].radii.tolist() == [2.0]
    assert b[-1].centers.tolist() == [[1.0, 1.0]]
    assert b[1:].radii.tolist() == [2.0, 0.5]
    assert b[np.array([True, False, True])].radii.tolist() == [1.0, 0.5]
    assert b[[2, 0]].radii.tolist() == [0.5, 1.0]
    assert len(b[[]]) == 0
    with pytest.raises(IndexError):
        b[3]
    with pytest.raises(IndexError):
        b[np.array([True, False])]


def test_grow():
    b = Balls([[0, 0], [1, 0]], [1.0, 2.0])
    np.testing.assert_allclose(b.grow(5.0).radii, [np.sqrt(6), 3.0])
    np.testing.assert_allclose(b.grow(-1.0).radii, [0.0, np.sqrt(3)])
    with pytest.raises(ValueError, match=r"radius of ball 0 imaginary.*tau must be >= -1\.0\)"):
        b.grow(-1.5)
    with pytest.raises(ValueError, match="tau"):
        b.grow(np.inf)
    with pytest.raises(TypeError, match="tau"):
        b.grow("1")


def test_translated_and_scaled():
    b = Balls([[0.0, 0, 0], [1, 2, 3]], [1.0, 2.0])
    t = b.translated([1, 1, 1])
    np.testing.assert_array_equal(t.centers, [[1, 1, 1], [2, 3, 4]])
    s = b.scaled(2.0)
    np.testing.assert_array_equal(s.radii, [2.0, 4.0])
    with pytest.raises(ValueError, match="s must be positive"):
        b.scaled(0.0)


def tangent_length_squared(x, z, r):
    """Squared length of a tangent segment from x to the sphere (z, r), by geometry:
    the tangent point t satisfies |t - z| = r and (t - z) ⟂ (t - x); by Pythagoras in
    the right triangle x, t, z it is |x - z|² - r² (only for x outside the ball)."""
    dist = np.linalg.norm(x - z)
    # construct the tangent point explicitly in 2D and measure it
    u = (x - z) / dist
    v = np.array([-u[1], u[0]])
    cos = r / dist
    t = z + r * (cos * u + np.sqrt(1 - cos**2) * v)
    assert abs(np.dot(t - z, t - x)) < 1e-9 * (1 + dist**2)
    return float(np.sum((t - x) ** 2))


@settings(max_examples=40, deadline=None)
@given(
    c=arrays(np.float64, (5, 2), elements=st.floats(-10, 10)),
    r=arrays(np.float64, (5,), elements=st.floats(0, 3)),
    x=arrays(np.float64, (2,), elements=st.floats(-20, 20)),
)
def test_power_distance_is_the_squared_tangent_length(c, r, x):
    b = Balls(c, r)
    p = power_distance(x, b)
    assert p.shape == (5,)
    for i in range(5):
        d2 = float(np.sum((x - c[i]) ** 2))
        if d2 > (r[i] + 1e-3) ** 2:
            assert p[i] == pytest.approx(tangent_length_squared(x, c[i], r[i]), rel=1e-9, abs=1e-9)
        else:
            assert p[i] <= 1e-9 + 2e-3 * r[i] + 1e-6  # inside (or on) the ball: non-positive


def test_power_distance_shapes_and_precision():
    rng = np.random.default_rng(0)
    b = Balls(rng.uniform(size=(7, 3)), rng.uniform(size=7))
    x = rng.uniform(size=(4, 3))
    P = power_distance(x, b)
    assert P.shape == (4, 7)
    for i in range(4):
        for j in range(7):
            assert P[i, j] == pytest.approx(np.linalg.norm(x[i] - b.centers[j]) ** 2 - b.radii[j] ** 2)
    # far from the origin: no cancellation (difference taken before squaring)
    off = Balls(b.centers + 1e8, b.radii)
    np.testing.assert_allclose(power_distance(x + 1e8, off), P, atol=1e-6)
    assert power_distance(np.zeros((0, 3)), b).shape == (0, 7)
    # the power distance is what the growth model grows: x is in B_i(tau) iff pi_i(x) <= tau
    tau = 0.3
    g = b.grow(tau)
    inside = np.linalg.norm(x[:, None, :] - g.centers[None], axis=2) <= g.radii
    assert np.array_equal(inside, P <= tau)


@pytest.mark.parametrize(
    "centers,radii,exc,match",
    [
        ([[0, 0], [1, np.nan]], 1.0, ValueError, "centers must be finite"),
        ([[0, 0], [1, np.inf]], 1.0, ValueError, "centers must be finite"),
        ([[0, 0], [1, 1]], [1.0, np.nan], ValueError, "radii must be finite"),
        ([[0, 0], [1, 1]], [1.0, -0.5], ValueError, r"radii must be non-negative; radii\[1\]"),
        ([[0, 0], [1, 1]], [1.0, 2.0, 3.0], ValueError, r"radii must have shape \(2,\)"),
        ([[0, 0], [1, 1]], [[1.0, 2.0]], ValueError, "radii must have shape"),
        ([0.0, 1.0], 1.0, ValueError, r"centers must be a 2-D array"),
        ([[0.0, 1.0, 2.0, 3.0]], 1.0, ValueError, "centers must have 2 or 3 columns"),
        ([[0.0]], 1.0, ValueError, "centers must have 2 or 3 columns"),
        ("abc", 1.0, TypeError, "centers"),
        ([[0, 0]], "a", TypeError, "radii"),
        ([["a", "b"]], 1.0, TypeError, "centers must hold numbers"),
        ([[1 + 1j, 0]], 1.0, TypeError, "centers must be real"),
    ],
)
def test_bad_input(centers, radii, exc, match):
    with pytest.raises(exc, match=match):
        Balls(centers, radii)


def test_bad_input_power_distance_and_filtration():
    b = Balls([[0, 0], [1, 1]], 1.0)
    with pytest.raises(ValueError, match="x must have 2 coordinates"):
        power_distance([0, 0, 0], b)
    with pytest.raises(ValueError, match="x must be finite"):
        power_distance([0, np.nan], b)
    with pytest.raises(ValueError, match="x must have 2 columns"):
        power_distance(np.zeros((3, 3)), b)
    with pytest.raises(TypeError, match="balls must be a shapelab.Balls"):
        power_distance([0, 0], np.zeros((2, 2)))
    with pytest.raises(TypeError, match="balls"):
        alpha_filtration([[0, 0], [1, 1]])


@pytest.mark.parametrize("how", ["pickle", "deepcopy", "copy"])
def test_a_copied_or_unpickled_balls_is_read_only_and_derives_afresh(how):
    """Pickle and deepcopy gave back writeable centres and radii: writing into them after
    the filtration was kept (Balls.derived) left it stale (issue 22, second look)."""
    import copy
    import pickle

    from shapelab.filtration import as_filtration

    b = Balls([[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]], [1.0, 1.0, 1.0])
    as_filtration(b, "test")
    c = {"pickle": lambda x: pickle.loads(pickle.dumps(x)), "deepcopy": copy.deepcopy, "copy": copy.copy}[how](b)
    assert not c.centers.flags.writeable and not c.radii.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        c.centers[0, 0] = 5.0
    assert c._derived == {}
    assert np.array_equal(c.centers, b.centers) and np.array_equal(c.radii, b.radii)
    F = as_filtration(c, "test")
    assert F.balls is c and as_filtration(c, "test") is F
