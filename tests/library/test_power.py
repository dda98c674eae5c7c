"""Tests of shapelab.triangulation: regular triangulations and power diagrams.

Oracles: scipy's Delaunay (unweighted case), brute-force power distances (empty
orthospheres, argmin of the power distance for sampled points), a linear program for
"the cell of ball i is empty" (hidden balls), the convex hull's volume (DT tiles the
hull), GUDHI's weighted alpha complex (top simplices).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog
from scipy.spatial import ConvexHull, Delaunay

from shapelab import Balls, PowerDiagram, power_diagram, power_distance, regular_triangulation


def random_balls(seed, n, d, rmax):
    rng = np.random.default_rng(seed)
    return Balls(rng.uniform(0, 1, (n, d)), rng.uniform(0, rmax, n))


def as_set(T):
    return {tuple(r) for r in np.asarray(T).tolist()}


def orthocentre(c, w):
    """Point of aff(c) with equal power to all rows (dense solve, full-dim simplex)."""
    A = c[1:] - c[0]
    b = 0.5 * (np.sum(A * A, axis=1) - w[1:] + w[0])
    return c[0] + np.linalg.solve(A, b)


def cell_is_empty_lp(balls, i):
    """Π(B_i) = {x : π_i(x) <= π_j(x) ∀ j} is empty iff this LP is infeasible.

    Each constraint is linear: 2 x·(z_j - z_i) <= |z_j|² - w_j - |z_i|² + w_i.
    A margin ``s`` is maximised so that a cell of positive size is reported non-empty.
    """
    z, w = balls.centers - balls.centers.mean(axis=0), balls.weights
    h = np.sum(z * z, axis=1) - w
    others = [j for j in range(len(balls)) if np.any(z[j] != z[i])]
    same = [j for j in range(len(balls)) if j != i and np.all(z[j] == z[i])]
    if any(w[j] > w[i] or (w[j] == w[i] and j < i) for j in same):
        return True
    if not others:
        return False
    A = np.array([np.r_[2 * (z[j] - z[i]), 1.0] for j in others])
    b = np.array([h[j] - h[i] for j in others])
    d = z.shape[1]
    res = linprog(np.r_[np.zeros(d), -1.0], A_ub=A, b_ub=b, bounds=[(None, None)] * d + [(None, 1.0)])
    return res.status == 0 and res.x[-1] <= 1e-9


# ----------------------------------------------------------------------------------
# regular_triangulation
# ----------------------------------------------------------------------------------
@pytest.mark.parametrize("d", [2, 3])
def test_unweighted_is_scipy_delaunay(d):
    rng = np.random.default_rng(d)
    c = rng.uniform(size=(200, d))
    T = regular_triangulation(Balls(c, 0.0))
    assert T.dtype == np.int64 and T.shape[1] == d + 1
    assert as_set(T) == as_set(np.sort(Delaunay(c).simplices, axis=1))
    # rows ascending, sorted lexicographically
    assert np.all(np.diff(T, axis=1) > 0)
    np.testing.assert_array_equal(np.lexsort(T.T[::-1]), np.arange(T.shape[0]))


@pytest.mark.parametrize("d", [2, 3])
def test_qhull_facets_are_convexhulls(d):
    """Our direct use of scipy's (private) Qhull wrapper gives ConvexHull's arrays."""
    from scipy.spatial import ConvexHull

    from shapelab._engine.triangulation import _QHULL_OPTIONS, _qhull_facets

    rng = np.random.default_rng(7)
    pts = np.c_[rng.uniform(size=(300, d)), rng.normal(size=300)]
    pts = np.vstack([pts, np.floor(pts[:40] * 4) / 4])  # and some grid-like points
    s, nb, eq = _qhull_facets(pts)
    hull = ConvexHull(pts, qhull_options=_QHULL_OPTIONS)
    np.testing.assert_array_equal(s, hull.simplices)
    np.testing.assert_array_equal(nb, hull.neighbors)
    # ConvexHull's equations themselves differ in the last bits from run to run
    np.testing.assert_allclose(eq, hull.equations, rtol=0, atol=1e-12)


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_orthospheres_are_empty_and_hidden_balls_by_lp(d, seed):
    balls = random_balls(seed, 25, d, 0.35)
    T = regular_triangulation(balls)
    c, w = balls.centers, balls.weights
    for s in T:
        x = orthocentre(c[s], w[s])
        p = power_distance(x, balls)
        # regular: no ball has smaller power at the orthocentre than the simplex's own
        assert np.all(p >= p[s[0]] - 1e-9), s
    present = np.zeros(len(balls), bool)
    present[T.ravel()] = True
    for i in range(len(balls)):
        assert present[i] == (not cell_is_empty_lp(balls, i)), i


@pytest.mark.parametrize("d", [2, 3])
def test_tiles_the_convex_hull(d):
    balls = random_balls(5, 300, d, 0.05)
    T = regular_triangulation(balls)
    c = balls.centers
    vol = np.abs(np.linalg.det(c[T[:, 1:]] - c[T[:, :1]])) / (2 if d == 2 else 6)
    assert vol.sum() == pytest.approx(ConvexHull(c[np.unique(T)]).volume, rel=1e-12)
    assert np.all(vol > 0)


def test_agrees_with_gudhi_top_simplices():
    gudhi = pytest.importorskip("gudhi")
    for d in (2, 3):
        balls = random_balls(11, 60, d, 0.3)
        st_ = gudhi.AlphaComplex(points=balls.centers, weights=balls.weights).create_simplex_tree()
        top = {tuple(sorted(s)) for s, _ in st_.get_skeleton(d) if len(s) == d + 1}
        assert as_set(regular_triangulation(balls)) == top


def test_lower_dimensional_and_tiny_inputs():
    rng = np.random.default_rng(3)
    t = rng.permutation(np.arange(7) / 8)  # eighths: 1 - t is exact
    T = regular_triangulation(Balls(np.c_[t, 1 - t], 0.0))  # collinear in 2D, exactly
    assert T.shape == (6, 2)
    order = np.argsort(t)
    assert as_set(T) == as_set(np.sort(np.c_[order[:-1], order[1:]], axis=1))
    T = regular_triangulation(Balls(np.c_[t, t, t] * 1e-6 + 1e6, 0.0))  # collinear in 3D
    assert T.shape == (6, 2)
    P = np.round(rng.uniform(size=(20, 2)) * 2**20) / 2**20
    # coplanar in 3D, exactly: P on two orthogonal integer vectors of length 3 (a
    # similarity, so the Delaunay triangulation is P's), every product exact
    T = regular_triangulation(Balls(P[:, :1] * [1.0, 2.0, 2.0] + P[:, 1:] * [2.0, 1.0, -2.0] + 5.0, 0.0))
    assert T.shape[1] == 3
    assert as_set(T) == as_set(np.sort(Delaunay(P).simplices, axis=1))
    # rotated in floating point the plane is flat only up to round-off: the centres
    # span space (decided exactly), as in GUDHI's exact alpha complex
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    assert regular_triangulation(Balls(np.c_[P, np.zeros(20)] @ Q.T + 5.0, 0.0)).shape[1] == 4
    assert regular_triangulation(Balls([[1.0, 2.0]], 1.0)).tolist() == [[0]]
    assert regular_triangulation(Balls([[1.0, 2.0, 3.0]] * 3, [1, 2, 2])).tolist() == [[1]]
    assert regular_triangulation(Balls([[0.0, 0, 0], [1, 0, 0]], 0.1)).tolist() == [[0, 1]]
    assert regular_triangulation(Balls(np.eye(3), 0.1)).tolist() == [[0, 1, 2]]
    assert regular_triangulation(Balls(np.zeros((0, 2)), [])).shape == (0, 1)


def test_cospherical_grid_has_no_flat_tetrahedra():
    g = np.array(list(itertools.product(range(5), repeat=3)), float)
    for c in (g, g * 1e-6 + 1e6):
        T = regular_triangulation(Balls(c, 0.0))
        vol = np.abs(np.linalg.det(c[T[:, 1:]] - c[T[:, :1]]))
        assert np.all(vol > 1e-6 * np.median(vol))
        assert vol.sum() / 6 == pytest.approx(ConvexHull(c).volume, rel=1e-6)


@pytest.mark.parametrize("offset,scale", [(0.0, 1.0), (1e6, 1.0), (0.0, 1e-6), (1e6, 1e-6)])
def test_offset_and_scale_invariance(offset, scale):
    balls = random_balls(8, 80, 3, 0.2)
    T0 = regular_triangulation(balls)
    T1 = regular_triangulation(Balls(balls.centers * scale + offset, balls.radii * scale))
    assert as_set(T0) == as_set(T1)


@settings(max_examples=15, deadline=None)
@given(
    pts=st.lists(st.tuples(st.integers(0, 3), st.integers(0, 3), st.integers(0, 3)), min_size=5, max_size=40),
    r=st.sampled_from([0.0, 0.5]),
)
def test_integer_grids_give_a_triangulation_of_the_hull(pts, r):
    c = np.unique(np.array(pts, float), axis=0)
    T = regular_triangulation(Balls(c, r))
    k = T.shape[1] - 1
    if k < 3:
        return
    vol = np.abs(np.linalg.det(c[T[:, 1:]] - c[T[:, :1]])) / 6
    assert vol.sum() == pytest.approx(ConvexHull(c).volume, rel=1e-9)
    # no flat tetrahedra (Qhull's "Qt" leaves some on cospherical input; they glue two
    # different splits of a square and are not part of a triangulation)
    assert np.all(vol > 1e-9)
    # every triangle in at most two tetrahedra; each hull facet in exactly one
    faces = np.sort(np.concatenate([np.delete(T, j, axis=1) for j in range(4)]), axis=1)
    _, cnt = np.unique(faces, axis=0, return_counts=True)
    assert cnt.max() <= 2
    # equal radii: no ball is hidden, every point is a vertex
    assert np.unique(T).size == len(c)


# ----------------------------------------------------------------------------------
# power_diagram
# ----------------------------------------------------------------------------------
def point_in_convex_polygon(p, poly, tol):
    e = np.roll(poly, -1, axis=0) - poly
    q = p - poly
    return np.all(e[:, 0] * q[:, 1] - e[:, 1] * q[:, 0] >= -tol)


def polygon_area(P):
    x, y = P[:, 0], P[:, 1]
    return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)


@pytest.mark.parametrize("seed", [0, 1])
def test_power_diagram_2d_cells(seed):
    balls = random_balls(seed, 40, 2, 0.2)
    pd = power_diagram(balls)
    assert isinstance(pd, PowerDiagram)
    assert len(pd.cells) == len(balls)
    T = regular_triangulation(balls)
    assert np.array_equal(pd.hidden, ~np.isin(np.arange(len(balls)), T))
    assert pd.hidden.any()  # this data has hidden balls
    total = 0.0
    for i, cell in enumerate(pd.cells):
        if pd.hidden[i]:
            assert cell.shape == (0, 2)
            continue
        assert polygon_area(cell) > 0  # counter-clockwise
        total += polygon_area(cell)
        p = power_distance(cell, balls)
        assert np.all(p[:, i] <= p.min(axis=1) + 1e-9)
    lo, hi = pd.bbox
    assert total == pytest.approx(np.prod(hi - lo), rel=1e-10)  # the cells tile the box
    # sampled points lie in the cell of the ball of least power
    rng = np.random.default_rng(seed)
    x = rng.uniform(lo, hi, (400, 2))
    owner = np.argmin(power_distance(x, balls), axis=1)
    for p, i in zip(x, owner):
        assert point_in_convex_polygon(p, pd.cells[i], 1e-12)
    # adjacency: the DT edges; the vertices: orthocentres of the triangles
    edges = {tuple(sorted(e)) for t in T.tolist() for e in itertools.combinations(t, 2)}
    assert as_set(pd.adjacency) == edges
    np.testing.assert_allclose(pd.vertices, [orthocentre(balls.centers[t], balls.weights[t]) for t in T], atol=1e-12)


def test_power_diagram_bbox_and_degenerate():
    balls = Balls([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], [0.1, 0.1, 0.1])  # collinear
    pd = power_diagram(balls, bbox=[[-1, -1], [3, 1]])
    assert pd.vertices.shape == (0, 2)
    areas = [polygon_area(c) for c in pd.cells]
    np.testing.assert_allclose(areas, [3.0, 2.0, 3.0])
    assert pd.unbounded.all()
    pd = power_diagram(Balls([[0.0, 0.0]], 1.0))
    assert polygon_area(pd.cells[0]) == pytest.approx(np.prod(np.diff(pd.bbox, axis=0)))
    with pytest.raises(ValueError, match="bbox"):
        power_diagram(balls, bbox=[[0, 0], [0, 1]])
    with pytest.raises(ValueError, match="bbox"):
        power_diagram(balls, bbox=[[0, 0, 0], [1, 1, 1]])
    with pytest.raises(ValueError, match="bbox"):
        power_diagram(balls, bbox=[[0, 0], [np.nan, 1]])
    with pytest.raises(TypeError, match="balls"):
        power_diagram(balls.centers)


def test_power_diagram_3d():
    balls = random_balls(4, 40, 3, 0.25)
    pd = power_diagram(balls)
    T = regular_triangulation(balls)
    assert pd.vertices.shape == (T.shape[0], 3)
    assert np.array_equal(pd.hidden, ~np.isin(np.arange(len(balls)), T))
    # every vertex of the cell of i is at least power for i (among all balls)
    for i, idx in enumerate(pd.cells):
        if pd.hidden[i]:
            assert idx.size == 0
            continue
        p = power_distance(pd.vertices[idx], balls)
        assert np.all(np.abs(p[:, i] - p.min(axis=1)) <= 1e-9)
    hull = set(ConvexHull(balls.centers).vertices.tolist())
    assert set(np.flatnonzero(pd.unbounded).tolist()) >= hull
    edges = {tuple(sorted(e)) for t in T.tolist() for e in itertools.combinations(t, 2)}
    assert as_set(pd.adjacency) == edges


# ------------------------------------------------ clipped cells B_i ∩ Π(B_i)
@pytest.mark.parametrize("tau", [0.0, 0.7])
def test_clipped_cells_have_the_per_ball_areas(tau):
    """The polygons of B_i ∩ Π(B_i), built by clipping the power cells with the disks
    (no inclusion–exclusion), have the areas of the per-ball shares."""
    from shapelab import Balls, union_measure
    from shapelab.triangulation import clipped_cells
    from tests.library.test_measure import _poly_area, random_balls

    b = random_balls(51, 40, 2, 0.2, 1.2, box=6.0)
    cells = clipped_cells(b, tau=tau, arc_resolution=4000)
    m = union_measure(b, tau=tau)
    areas = np.array([_poly_area(P) for P in cells])
    assert np.all(areas >= 0)  # counter-clockwise
    # inscribed polygons: error below r^2 (2π/N)^2 / 6 per full circle
    np.testing.assert_allclose(areas, m.ball_measure, atol=4e-6)
    hidden_inside = union_measure(Balls(np.vstack([b.centers, b.centers[:1]]), np.append(b.radii, 0.1)))
    assert len(clipped_cells(Balls(np.vstack([b.centers, b.centers[:1]]), np.append(b.radii, 0.1)))[-1]) == 0
    assert hidden_inside.ball_measure[-1] == 0.0
    with pytest.raises(ValueError, match="2D"):
        clipped_cells(random_balls(1, 4, 3))


def test_filtration_clipped_cells_reuse_one_diagram_per_box():
    """``F.clipped_cells`` is :func:`shapelab.triangulation.clipped_cells` on a diagram kept on
    the filtration: the same polygons, the diagram built once per box."""
    from shapelab import alpha_filtration, datasets
    from shapelab.triangulation import clipped_cells

    balls = datasets.figure_23_1()
    F = alpha_filtration(balls)
    box = np.array([balls.centers.min(axis=0) - 10, balls.centers.max(axis=0) + 10])
    for tau in (0.0, 0.5):
        ours = F.clipped_cells(tau, bbox=box, arc_resolution=72)
        ref = clipped_cells(balls, tau=tau, diagram=power_diagram(balls, bbox=box), arc_resolution=72)
        assert len(ours) == len(ref) and all(np.array_equal(a, b) for a, b in zip(ours, ref))
    assert sum(k.startswith("power.diagram[") for k in F._derived) == 1
    default = F.clipped_cells(0.0)
    ref = clipped_cells(balls, tau=0.0)
    assert all(np.array_equal(a, b) for a, b in zip(default, ref))
    with pytest.raises(ValueError, match="2"):
        alpha_filtration(Balls(np.eye(3), [1.0, 1.0, 1.0])).clipped_cells(0.0)


def test_empty_and_flat_input_are_refused_or_answered_plainly():
    """Review of issue 33: no numpy reduction error, no LinAlgError, no silent NaN."""
    import pytest

    import shapelab as sl

    empty = Balls(np.zeros((0, 2)), [])
    assert regular_triangulation(empty, precision="fast").shape == (0, 1)  # as "exact"
    with pytest.raises(ValueError, match="balls is empty"):
        sl.power_diagram(empty)  # no default box
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no "mean of empty slice"
        for precision in ("exact", "fast"):
            D = sl.power_diagram(empty, bbox=[[0.0, 0.0], [1.0, 1.0]], precision=precision)
            assert D.cells == () and D.vertices.shape == (0, 2) and D.adjacency.shape == (0, 2)
        from shapelab.triangulation import clipped_cells

        assert clipped_cells(empty) == () and sl.alpha_filtration(empty).clipped_cells(0.0) == ()
    bad = {
        "weights must have shape": ([[0.0, 0.0], [1.0, 0.0]], [1.0, 1.0, 1.0]),
        "centers must have shape": ([0.0, 1.0], [1.0, 1.0]),
        "centers must be finite": ([[0.0, np.nan], [1.0, 0.0]], [1.0, 1.0]),
        "affinely dependent": ([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], [1.0, 1.0, 1.0]),
    }
    for message, (c, w) in bad.items():
        with pytest.raises(ValueError, match=message):
            sl.orthosphere(c, w)
    with pytest.raises(ValueError, match="affinely dependent"):
        sl.orthosphere([[0.0, 0.0], [0.0, 0.0]], [1.0, 1.0])  # duplicate centres
    with pytest.raises(ValueError, match="centers must have shape"):
        sl.orthosphere([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]], [1.0] * 4)  # 4 in 2D
    # exactly collinear / coplanar integer centres in 3D: numpy's solve does not see
    # them singular (it returned c ~ 1e16 before); the rank test does
    with pytest.raises(ValueError, match="affinely dependent"):
        sl.orthosphere([[-5, -4, 3], [-4, -1, 3], [-2, 5, 3]], [0, 0, 0])
    with pytest.raises(ValueError, match="affinely dependent"):
        sl.orthosphere([[0, 0, 0], [1, 2, 3], [2, 4, 6], [5, 1, 0]], [0, 0, 0, 0])
    rng = np.random.default_rng(0)
    z = rng.normal(size=(500, 3, 3))
    z[:, 2] = z[:, 0] + rng.integers(-3, 4, (500, 1)) * (z[:, 1] - z[:, 0])  # collinear
    with pytest.raises(ValueError, match="affinely dependent"):
        sl.orthosphere(z, np.zeros((500, 3)))
    c, rho = sl.orthosphere([[0.0, 0.0], [4.0, 0.0]], [1.0, 1.0])  # a closed form
    assert c.tolist() == [2.0, 0.0] and float(rho) == 3.0
