"""The plain path behind ``precision="fast"`` (issue 33) against the engine's exact path.

``regular_triangulation``, ``power_diagram`` and ``alpha_filtration`` state their
algorithm in public code (lift, lower hull, orthospheres, the attached rule top-down)
and run it in floating point with ``precision="fast"``; the default ``"exact"`` runs
the engine (certified predicates, error bounds, exact fallbacks).  On generic input
the two must give the same simplices and the same entry times to round-off; on
degenerate input they may differ, and the docstrings say so.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shapelab as sl
from shapelab import Balls, alpha_filtration, orthosphere, power_diagram, regular_triangulation

#: relative agreement of the two paths' entry times, relative to the value and to the
#: input's own scale of powers (squared extent plus the largest weight): a value near
#: 0 is the difference of two powers of that size, so its round-off is relative to them
RTOL = 1e-12


def random_balls(seed: int, n: int, d: int) -> Balls:
    rng = np.random.default_rng(seed)
    return Balls(rng.uniform(0, 10, (n, d)), rng.uniform(0.3, 1.5, n))


def as_set(T) -> set:
    return {tuple(int(v) for v in row) for row in T}


def entry_times(F) -> dict:
    return {
        tuple(int(v) for v in s): float(t) for k in range(F.dimension + 1) for s, t in zip(F.simplices(k), F.values(k))
    }


def assert_same_filtration(balls: Balls) -> None:
    exact, fast = alpha_filtration(balls), alpha_filtration(balls, precision="fast")
    assert exact.counts() == fast.counts()
    a, b = entry_times(exact), entry_times(fast)
    assert a.keys() == b.keys()
    keys = list(a)
    va, vb = np.array([a[k] for k in keys]), np.array([b[k] for k in keys])
    scale = float(np.ptp(balls.centers, axis=0).max() ** 2 + balls.weights.max())
    err = np.abs(va - vb)
    assert np.all(err <= RTOL * (np.abs(va) + scale)), float((err / (np.abs(va) + scale)).max())
    # the order within a dimension is the same wherever the values are not within
    # round-off of each other
    for k in range(exact.dimension + 1):
        v = exact.values(k)
        gaps = np.diff(v) > 1e3 * RTOL * (np.abs(v[1:]) + scale)
        if gaps.all():
            np.testing.assert_array_equal(exact.simplices(k), fast.simplices(k))


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("n", [10, 40, 120, 300])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_plain_triangulation_is_the_exact_one(seed, n, d):
    balls = random_balls(seed, n, d)
    exact = regular_triangulation(balls)
    fast = regular_triangulation(balls, precision="fast")
    assert as_set(fast) == as_set(exact)
    np.testing.assert_array_equal(fast, exact)  # same rows, same (lexicographic) order


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("n", [10, 40, 120, 300])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_plain_filtration_is_the_exact_one(seed, n, d):
    assert_same_filtration(random_balls(seed, n, d))


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(10, 300),
    d=st.sampled_from([2, 3]),
    spread=st.sampled_from([0.1, 1.0, 3.0]),
    offset=st.sampled_from([0.0, 1e3]),
)
def test_plain_path_on_generic_input(seed, n, d, spread, offset):
    rng = np.random.default_rng(seed)
    balls = Balls(offset + rng.uniform(0, 10, (n, d)), rng.uniform(0.1, 0.1 + spread, n))
    assert as_set(regular_triangulation(balls, precision="fast")) == as_set(regular_triangulation(balls))
    assert_same_filtration(balls)


@pytest.mark.parametrize("d", [2, 3])
def test_plain_power_diagram_is_the_exact_one(d):
    balls = random_balls(5, 60, d)
    exact, fast = power_diagram(balls), power_diagram(balls, precision="fast")
    np.testing.assert_array_equal(fast.adjacency, exact.adjacency)
    np.testing.assert_array_equal(fast.hidden, exact.hidden)
    np.testing.assert_array_equal(fast.unbounded, exact.unbounded)
    np.testing.assert_allclose(fast.vertices, exact.vertices, rtol=1e-9, atol=1e-9)
    if d == 2:
        for a, b in zip(fast.cells, exact.cells):
            np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9)


def test_hidden_balls_are_left_out_by_both_paths():
    balls = Balls([[0, 0], [4, 0], [2, 3], [2, 1]], [2.5, 2.5, 2.5, 0.1])
    assert regular_triangulation(balls, precision="fast").tolist() == [[0, 1, 2]]
    assert regular_triangulation(balls).tolist() == [[0, 1, 2]]
    assert alpha_filtration(balls, precision="fast").counts() == (3, 3, 1)


@pytest.mark.parametrize("j", [1, 2, 3])
def test_orthosphere_has_equal_power_to_its_balls_and_lies_on_their_hull(j):
    rng = np.random.default_rng(j)
    z = rng.normal(size=(50, j + 1, 3))
    w = rng.uniform(0, 1, (50, j + 1))
    c, rho = orthosphere(z, w)
    power = np.einsum("mik,mik->mi", c[:, None] - z, c[:, None] - z) - w
    np.testing.assert_allclose(power, np.broadcast_to(rho[:, None], power.shape), rtol=1e-9, atol=1e-9)
    # c - z_0 in the span of the edges: no component along the orthogonal complement
    A = z[:, 1:] - z[:, :1]
    for m in range(5):
        coef, *_ = np.linalg.lstsq(A[m].T, c[m] - z[m, 0], rcond=None)
        np.testing.assert_allclose(A[m].T @ coef, c[m] - z[m, 0], atol=1e-9)


def test_orthosphere_closed_forms():
    c, rho = orthosphere([[0.0, 0.0], [4.0, 0.0]], [1.0, 1.0])
    assert c.tolist() == [2.0, 0.0] and rho == 3.0
    c, rho = orthosphere([[1.0, 2.0, 3.0]], [0.25])  # a vertex
    assert c.tolist() == [1.0, 2.0, 3.0] and rho == -0.25
    # circumcircle of a right triangle: the midpoint of the hypotenuse
    c, rho = orthosphere([[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]], [0.0, 0.0, 0.0])
    np.testing.assert_allclose(c, [1.0, 1.0])
    assert rho == pytest.approx(2.0)


def test_degenerate_input_may_differ_and_the_docstrings_say_so():
    # twelve integer points on the circle of radius 5 are exactly co-circular: every
    # triangulation of their polygon is regular; the exact path picks the perturbed
    # one (Simulation of Simplicity), the fast path whichever Qhull's merge gives
    p = [(5, 0), (4, 3), (3, 4), (0, 5), (-3, 4), (-4, 3), (-5, 0), (-4, -3), (-3, -4), (0, -5), (3, -4), (4, -3)]
    balls = Balls(np.array(p, dtype=float), 0.0)
    exact = regular_triangulation(balls)
    fast = regular_triangulation(balls, precision="fast")
    assert exact.tolist() == regular_triangulation(balls).tolist()  # deterministic

    def area(T):
        q = balls.centers
        a, b, c = q[T[:, 0]], q[T[:, 1]], q[T[:, 2]]
        u, v = b - a, c - a
        return np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]).sum() / 2

    # both tile the polygon (whatever diagonals the fast one chose)
    assert area(fast) == pytest.approx(area(exact))
    assert len(fast) == len(exact) == 10
    for f in (regular_triangulation, alpha_filtration):
        doc = " ".join(f.__doc__.split())
        assert "degenerate input" in doc and "differ" in doc


def test_fast_path_on_collinear_centres_is_the_exact_path():
    # no hull to take: "fast" returns the exact triangulation (a path of edges)
    balls = Balls([[0, 0], [1, 1], [2, 2]], 0.5)
    assert regular_triangulation(balls, precision="fast").tolist() == [[0, 1], [1, 2]]
    assert regular_triangulation(balls).tolist() == [[0, 1], [1, 2]]


@pytest.mark.parametrize("bad", ["Exact", "float", None, 1])
def test_precision_is_checked(bad):
    balls = random_balls(0, 10, 2)
    for f in (regular_triangulation, power_diagram, alpha_filtration):
        with pytest.raises(ValueError, match="precision must be 'exact' or 'fast'"):
            f(balls, precision=bad)


def test_the_seam_keeps_the_default_exact():
    balls = random_balls(3, 50, 3)
    assert sl.alpha_filtration(balls, precision="exact").counts() == sl.alpha_filtration(balls).counts()
    for a, b in zip(
        (sl.alpha_filtration(balls).values(k) for k in range(4)),
        (sl.alpha_filtration(balls, precision="exact").values(k) for k in range(4)),
    ):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("scale", [1e-7, 1e-4, 1e5])
def test_plain_path_does_not_depend_on_the_units(d, scale):
    # generic input in other units (nm instead of Å, a tiny model): the plain path
    # lifts in a frame of unit size, so Qhull sees the same hull (review 33: with the
    # point above the hull at an absolute height 1 it lost most simplices at 1e-7)
    balls = random_balls(7, 60, d)
    small = Balls(balls.centers * scale, balls.radii * scale)
    np.testing.assert_array_equal(regular_triangulation(small, precision="fast"), regular_triangulation(small))
    assert as_set(regular_triangulation(small, precision="fast")) == as_set(regular_triangulation(balls))
    assert_same_filtration(small)


def test_fast_path_flat_simplex_is_a_clear_error():
    # a 3x3x3 grid: Qhull's triangulation of the co-spherical cubes leaves flat
    # tetrahedra, which have no orthosphere; the plain path says so and names the way out
    g = np.array([[i, j, k] for i in range(3) for j in range(3) for k in range(3)], dtype=float)
    balls = Balls(g, 0.6)
    T = regular_triangulation(balls, precision="fast")  # flat simplices allowed, documented
    assert T.shape[1] == 4
    for f in (alpha_filtration, power_diagram):
        with pytest.raises(ValueError, match="precision='exact'") as info:
            f(balls, precision="fast")
        assert not isinstance(info.value, np.linalg.LinAlgError)
    assert alpha_filtration(balls).counts()[3] == 48  # the exact path triangulates it
