"""Critical points of F(x) = |x − S| (notes §23.2, Figure 23.3): closed forms on
circles, ellipses and a square; dense sampling on random polygons; Euler
characteristic and an independent link-walking classifier on surfaces; signatures;
bad input."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import shapelab
from shapelab.critical import (
    CriticalPoints,
    compare,
    critical_points,
    distance_along,
    euler_characteristic,
    polyline,
    signature,
)
from shapelab.datasets import blob_curve, bumpy_sphere, ellipse_curve, icosphere, torus

finite = dict(allow_nan=False, allow_infinity=False)


# ------------------------------------------------------------------ circles, ellipses
@settings(max_examples=40, deadline=None)
@given(
    st.floats(-3, 3, **finite),
    st.floats(-3, 3, **finite),
    st.floats(0.2, 4, **finite),
    st.floats(0, 2 * np.pi, **finite),
    st.floats(0.05, 3, **finite),
)
def test_circle_with_off_centre_viewpoint(cx, cy, rho, angle, dist):
    """One minimum at c + ρ u and one maximum at c − ρ u, u the unit vector to S."""
    c = np.array([cx, cy])
    u = np.array([np.cos(angle), np.sin(angle)])
    S = c + dist * u
    assume(abs(dist - rho) > 1e-3)  # S on the circle makes F non-smooth at S
    r = critical_points(lambda t: (cx + rho * np.cos(t), cy + rho * np.sin(t)), S)
    assert r.source == "parametric" and not r.degenerate
    assert r.n_min == 1 and r.n_max == 1
    scale = 1 + np.abs(c).max() + rho
    np.testing.assert_allclose(r.minima[0], c + rho * u, atol=1e-9 * scale)
    np.testing.assert_allclose(r.maxima[0], c - rho * u, atol=1e-9 * scale)
    assert r.values[r.kinds == "min"][0] == pytest.approx(abs(rho - dist), abs=1e-12 * scale)
    assert r.values[r.kinds == "max"][0] == pytest.approx(rho + dist, abs=1e-12 * scale)
    # parameter of the minimum: the angle of u (mod 2π)
    tmin = r.parameters[r.kinds == "min"][0]
    assert abs(np.angle(np.exp(1j * (tmin - angle)))) < 1e-9


def test_ellipse_seen_from_its_centre():
    a, b = 2.0, 1.0
    r = critical_points(ellipse_curve(a, b), (0.0, 0.0))
    assert r.n_min == 2 and r.n_max == 2
    np.testing.assert_allclose(sorted(r.minima[:, 1]), [-b, b], atol=1e-12)
    np.testing.assert_allclose(r.minima[:, 0], 0.0, atol=1e-12)
    np.testing.assert_allclose(sorted(r.maxima[:, 0]), [-a, a], atol=1e-12)
    np.testing.assert_allclose(r.values[r.kinds == "min"], b, atol=1e-14)
    np.testing.assert_allclose(r.values[r.kinds == "max"], a, atol=1e-14)
    np.testing.assert_allclose(np.sort(r.parameters), [0, np.pi / 2, np.pi, 3 * np.pi / 2], atol=1e-12)
    assert list(r.kinds) == ["max", "min", "max", "min"]
    assert r.euler_characteristic == 0


def test_circle_centred_at_the_viewpoint_is_degenerate():
    r = critical_points(lambda t: (2 + np.cos(t), -1 + np.sin(t)), (2.0, -1.0))
    assert r.degenerate and len(r) == 0
    assert "degenerate" in repr(r)


def test_scalar_parametric_functions_are_accepted():
    r = critical_points(lambda t: [2 * np.cos(t), np.sin(t)], [0.0, 0.0])
    assert (r.n_min, r.n_max) == (2, 2)
    # a scalar function is never handed an array (NumPy < 2.4 warned on float(array([t])))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = critical_points(lambda t: (float(np.cos(t)), float(np.sin(t))), [0.5, 0.0])
    assert not caught, [str(w.message) for w in caught]
    assert (r.n_min, r.n_max) == (1, 1)


# ------------------------------------------------------------------ polygons
def test_square_seen_from_its_centre_and_off_centre():
    sq = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.0]])
    r = critical_points(sq, (1.0, 1.0))
    assert list(r.kinds) == ["max", "min"] * 4
    np.testing.assert_allclose(r.maxima, sq[:4])
    np.testing.assert_allclose(r.minima, [[1, 0], [2, 1], [1, 2], [0, 1]])
    assert np.all(r.interior[r.kinds == "min"]) and not np.any(r.interior[r.kinds == "max"])
    np.testing.assert_allclose(r.values, [np.sqrt(2), 1] * 4)
    np.testing.assert_allclose(r.parameters, np.arange(8) / 8)
    # S = (1, 0.5): maxima at the corners, minima at the four feet of perpendiculars
    r = critical_points(sq, (1.0, 0.5))
    np.testing.assert_allclose(np.sort(r.values[r.kinds == "max"]), np.sort([np.sqrt(1.25)] * 2 + [np.sqrt(3.25)] * 2))
    np.testing.assert_allclose(r.minima, [[1, 0], [2, 0.5], [1, 2], [0, 0.5]])
    np.testing.assert_allclose(r.values[r.kinds == "min"], [0.5, 1.0, 1.5, 1.0])


def test_vertex_minimum_and_far_vertex_maximum():
    """A vertex pointing at S is a minimum; a vertex can be a maximum although both
    neighbouring vertices are farther from S (F dips inside the segments)."""
    tri = np.array([[1.0, 0.0], [-1.1, 0.05], [-1.0, -0.6], [1.0, 0.0]])
    r = critical_points(tri, (0.0, 0.0))
    top = r.positions[(r.kinds == "max") & (r.indices == 0)]
    np.testing.assert_allclose(top, [[1.0, 0.0]])
    kite = np.array([[0.0, 1.0], [-2.0, 0.0], [0.0, -1.0], [2.0, 0.0], [0.0, 1.0]])
    r = critical_points(kite, (0.0, 3.0))  # S outside, above the top vertex
    # the top vertex is a minimum; the lower edges dip below their end points:
    # feet of the perpendiculars at (∓1.6, −0.2), |(1.6, 3.2)| = 3.2 sqrt(1.25)
    np.testing.assert_allclose(r.minima, [[0.0, 1.0], [-1.6, -0.2], [1.6, -0.2]], atol=1e-15)
    assert r.interior[r.kinds == "min"].tolist() == [False, True, True]
    np.testing.assert_allclose(r.values[r.kinds == "min"], [2.0, 3.2 * np.sqrt(1.25), 3.2 * np.sqrt(1.25)])
    np.testing.assert_allclose(r.maxima, [[-2.0, 0.0], [0.0, -1.0], [2.0, 0.0]])


def random_star_polygon(rng, n):
    a = np.sort(rng.uniform(0, 2 * np.pi, n))
    rad = rng.uniform(0.5, 1.5, n)
    P = np.c_[rad * np.cos(a), rad * np.sin(a)]
    return np.vstack([P, P[:1]])


def dense_samples(P, per_segment=400):
    t = np.arange(per_segment) / per_segment
    return np.concatenate([P[i] + t[:, None] * (P[i + 1] - P[i]) for i in range(len(P) - 1)])


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10**6), st.integers(3, 12), st.floats(-2, 2, **finite), st.floats(-2, 2, **finite))
def test_polylines_against_dense_sampling(seed, n, sx, sy):
    rng = np.random.default_rng(seed)
    P = random_star_polygon(rng, n)
    S = np.array([sx, sy])
    r = critical_points(P, S)
    X = dense_samples(P)
    F = np.linalg.norm(X - S, axis=1)
    # global extrema: the maximum is at a vertex, which is sampled exactly; the sampled
    # minimum is within half a sample spacing of the true one (triangle inequality)
    spacing = np.linalg.norm(np.diff(P, axis=0), axis=1).max() / 400
    assert r.values.max() == pytest.approx(F.max(), abs=1e-12)
    assert r.values.min() <= F.min() + 1e-12
    assert r.values.min() >= F.min() - spacing / 2 - 1e-12
    # minima and maxima alternate along the curve; as many of each
    assert r.n_min == r.n_max and r.euler_characteristic == 0
    assert all(k1 != k2 for k1, k2 in zip(r.kinds, np.roll(r.kinds, 1)))
    # every reported point is a local extremum: compare with points nearby along C
    L = np.linalg.norm(np.diff(P, axis=0), axis=1)
    s_samples = np.concatenate([(np.sum(L[:i]) + L[i] * np.arange(400) / 400) for i in range(len(L))]) / L.sum()
    for p, v, kind in zip(r.parameters, r.values, r.kinds):
        others = np.abs((r.parameters - p + 0.5) % 1.0 - 0.5)
        window = min(0.01, 0.5 * np.sort(others)[1])  # up to halfway to the next extremum
        gap = np.abs((s_samples - p + 0.5) % 1.0 - 0.5)
        Fn = F[gap < window]
        if kind == "min":
            assert np.all(Fn >= v - 1e-12)
        else:
            assert np.all(Fn <= v + 1e-12)
    # and none is missed: count the strict local extrema of the dense samples
    d = np.sign(np.diff(np.r_[F, F[:1]]))
    changes = np.count_nonzero(d != np.roll(d, 1))
    assert len(r) <= changes  # the samples can only add (flat) sign changes, never lose one
    assert len(r) >= changes - 2 * np.count_nonzero(d == 0)


def test_polyline_closing_and_duplicate_vertices():
    open_sq = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    with pytest.raises(ValueError, match="curve must be closed"):
        critical_points(open_sq, (1.0, 1.0))
    a = critical_points(open_sq, (1.0, 1.0), close=True)
    b = critical_points(np.array([[0, 0], [2, 0], [2, 0], [2, 2], [0, 2], [0, 0]], float), (1.0, 1.0))
    np.testing.assert_allclose(a.values, b.values)
    np.testing.assert_allclose(a.positions, b.positions)


def test_parametric_and_fine_polyline_agree():
    S = (0.1, 0.05)
    smooth = critical_points(blob_curve, S)
    fine = critical_points(polyline(blob_curve, 4000), S)
    assert (smooth.n_min, smooth.n_max) == (3, 3)
    assert compare(smooth, signature(fine, tolerance=1e-4)) < 1e-5
    s, F = distance_along(blob_curve, S)
    assert F.max() == pytest.approx(smooth.values.max(), abs=1e-5)


# ------------------------------------------------------------------ signatures
def rotate(P, angle):
    c, s = np.cos(angle), np.sin(angle)
    return P @ np.array([[c, s], [-s, c]])


def test_signature_invariances_and_differences():
    P = polyline(blob_curve, 300)
    S = np.array([0.1, 0.05])
    base = critical_points(P, S)
    # rotate + scale + translate the pair (shape, S); start elsewhere; travel backwards
    Q = 2.5 * rotate(P, 0.7) + [3.0, -1.0]
    Q = np.vstack([Q[:-1][::-1][37:], Q[:-1][::-1][:37]])
    Q = np.vstack([Q, Q[:1]])
    moved = critical_points(Q, 2.5 * rotate(S[None], 0.7)[0] + [3.0, -1.0])
    assert compare(base, moved) < 1e-12
    other = critical_points(polyline(ellipse_curve(2, 1), 300), (0.1, 0.05))
    assert compare(base, other) == np.inf
    squashed = critical_points(polyline(lambda t: blob_curve(t) * [[1.0], [0.95]], 300), S)
    # the chords of a polyline add tiny min-max pairs near flat extrema: cancel them
    assert (squashed.n_min, squashed.n_max) != (base.n_min, base.n_max)
    d = compare(signature(base, tolerance=1e-3), signature(squashed, tolerance=1e-3))
    assert 0.01 < d < np.inf
    sig = signature(base)
    assert sig.kinds[0] == "max" and sig.values[0] == 1.0 and sig.cyclic


def test_signature_tolerance_cancels_small_pairs():
    fine = critical_points(polyline(blob_curve, 400), (0.1, 0.05))
    assert (fine.n_min, fine.n_max) == (4, 4)  # a spurious pair from the chords
    sig = signature(fine, tolerance=1e-3)
    assert len(sig.kinds) == 6
    assert len(signature(fine, tolerance=10.0).kinds) == 2  # only the global pair remains


# ------------------------------------------------------------------ surfaces
def link_walk_classify(V, F, S):
    """Independent classifier: walk each vertex's link cycle explicitly and count
    the arcs of lower neighbours (ties broken by index)."""
    h = np.sqrt(((V - S) ** 2).sum(axis=1))  # the same rounding as the library: ties must agree
    lower = lambda u, v: (h[u], u) < (h[v], v)  # noqa: E731
    out = {}
    for v in range(len(V)):
        opp = {}
        for f in F:
            if v in f:
                k = list(f).index(v)
                opp[f[(k + 1) % 3]] = f[(k + 2) % 3]  # oriented link edge
        start = next(iter(opp))
        cycle, x = [start], opp[start]
        while x != start:
            cycle.append(x)
            x = opp[x]
        assert len(cycle) == len(opp)
        low = [lower(u, v) for u in cycle]
        if not any(low):
            out[v] = ("min", 1)
        elif all(low):
            out[v] = ("max", 1)
        else:
            arcs = sum(1 for i in range(len(low)) if low[i] and not low[i - 1])
            if arcs >= 2:
                out[v] = ("saddle", arcs - 1)
    return out


def surface_counts(V, F):
    e = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    return len(V) - len(np.unique(e, axis=0)) + len(F)


@settings(max_examples=25, deadline=None)
@given(
    st.integers(0, 10**6),
    st.floats(-0.6, 0.6, **finite),
    st.floats(-0.6, 0.6, **finite),
    st.floats(-0.6, 0.6, **finite),
    st.integers(1, 2),
)
def test_deformed_spheres_have_euler_characteristic_two(seed, sx, sy, sz, sub):
    V, F = bumpy_sphere(sub, bumps=8, amplitude=0.45, seed=seed)
    S = np.array([sx, sy, sz])
    r = critical_points(V, S, faces=F)
    assert r.euler_characteristic == 2 == surface_counts(V, F) == euler_characteristic(V, F)
    ref = link_walk_classify(V, F, S)
    got = {int(i): (k, int(m)) for i, k, m in zip(r.indices, r.kinds, r.multiplicities)}
    assert got == ref


@settings(max_examples=15, deadline=None)
@given(st.floats(-3, 3, **finite), st.floats(-3, 3, **finite), st.floats(-1, 1, **finite))
def test_torus_has_euler_characteristic_zero(sx, sy, sz):
    V, F = torus(12, 8)
    S = np.array([sx, sy, sz])
    r = critical_points(V, S, faces=F)
    assert r.euler_characteristic == 0 == surface_counts(V, F)
    # the global extremes of F (ties broken by index: the higher index is higher) must be
    # found as a minimum and a maximum; with chi = 0 that forces at least two saddles
    d = np.linalg.norm(V - S, axis=1)
    lowest, highest = int(np.argmin(d)), len(d) - 1 - int(np.argmax(d[::-1]))
    assert lowest in r.indices[r.kinds == "min"] and highest in r.indices[r.kinds == "max"]
    got = {int(i): (k, int(m)) for i, k, m in zip(r.indices, r.kinds, r.multiplicities)}
    assert got == link_walk_classify(V, F, S)


def test_exact_ties_are_broken_by_index_and_monkey_saddles_count_twice():
    # octahedron seen from its centre: every vertex at distance 1, so the order is
    # the index: 0 and 1 (opposite, all neighbours higher) are minima, 4 and 5
    # maxima, and 2, 3 (links 0-4-1-5: two lower arcs) saddles
    V = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    F = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    r = critical_points(V, (0.0, 0.0, 0.0), faces=F)
    assert r.euler_characteristic == 2
    assert r.indices[r.kinds == "min"].tolist() == [0, 1] and r.indices[r.kinds == "max"].tolist() == [4, 5]
    assert r.indices[r.kinds == "saddle"].tolist() == [2, 3]
    # a monkey saddle: a hexagonal bipyramid seen from the origin.  The apex (index 6) is at
    # distance 1 and its ring neighbours alternate between distance 0.8 (lower) and 1.2
    # (higher), so its lower link has three arcs: a saddle of multiplicity 3 - 1 = 2
    ang = np.arange(6) * np.pi / 3
    rho = np.where(np.arange(6) % 2 == 0, 0.8, 1.2)
    V = np.vstack([np.c_[rho * np.cos(ang), rho * np.sin(ang), np.zeros(6)], [[0, 0, 1.0]], [[0, 0, -1.5]]])
    F = np.array([[6, k, (k + 1) % 6] for k in range(6)] + [[7, (k + 1) % 6, k] for k in range(6)])
    S = np.zeros(3)
    r = critical_points(V, S, faces=F)
    assert r.euler_characteristic == 2
    apex = r.kinds[r.indices == 6].tolist(), r.multiplicities[r.indices == 6].tolist()
    assert apex == (["saddle"], [2]), apex
    assert set(map(tuple, link_walk_classify(V, F, S).items())) == {
        (int(i), (k, int(m))) for i, k, m in zip(r.indices, r.kinds, r.multiplicities)
    }


def test_mesh_generators():
    for s in range(4):
        V, F = icosphere(s, radius=2.0)
        assert V.shape == (10 * 4**s + 2, 3) and F.shape == (20 * 4**s, 3)
        np.testing.assert_allclose(np.linalg.norm(V, axis=1), 2.0)
        assert euler_characteristic(V, F) == 2
        # outward orientation: signed volume positive
        vol = np.einsum("ij,ij->i", V[F[:, 0]], np.cross(V[F[:, 1]], V[F[:, 2]])).sum() / 6
        assert vol > 0
    V, F = torus(10, 6)
    assert V.shape == (60, 3) and F.shape == (120, 3) and euler_characteristic(V, F) == 0
    V1, _ = bumpy_sphere(2, seed=4)
    V2, _ = bumpy_sphere(2, seed=4)
    assert np.array_equal(V1, V2)


# ------------------------------------------------------------------ bad input
def test_bad_curves_name_the_argument():
    sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]])
    with pytest.raises(ValueError, match="curve must be finite"):
        critical_points(np.vstack([sq[:2], [[np.nan, 0.0]], sq[2:]]), (0.5, 0.5))
    with pytest.raises(ValueError, match="viewpoint must have"):
        critical_points(sq, (0.5, 0.5, 0.5))
    with pytest.raises(ValueError, match="viewpoint must be finite"):
        critical_points(sq, (np.inf, 0.5))
    with pytest.raises(ValueError, match="curve must have 2 or 3 columns"):
        critical_points(np.zeros((5, 4)), (0.0, 0.0))
    with pytest.raises(ValueError, match="at least 3 distinct"):
        critical_points(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]), (0.0, 1.0))
    with pytest.raises(ValueError, match="curve must be closed"):
        critical_points(lambda t: (t, np.sin(t)), (0.0, 0.0))
    with pytest.raises(ValueError, match="curve\\(t\\)"):
        critical_points(lambda t: (np.cos(t), np.sin(t), np.cos(t), t), (0.0, 0.0))
    with pytest.raises(ValueError, match="n_samples"):
        critical_points(blob_curve, (0.0, 0.0), n_samples=4)


def test_bad_surfaces_name_the_argument():
    V, F = icosphere(1)
    with pytest.raises(ValueError, match="closed surface"):
        critical_points(V, (0, 0, 0), faces=F[1:])
    with pytest.raises(ValueError, match="faces must index"):
        critical_points(V, (0, 0, 0), faces=np.vstack([F, [[0, 1, 99]]]))
    with pytest.raises(ValueError, match=r"faces must have shape \(f, 3\)"):
        critical_points(V, (0, 0, 0), faces=F[:, :2])
    with pytest.raises(TypeError, match="faces must hold integer"):
        critical_points(V, (0, 0, 0), faces=F + 0.5)
    with pytest.raises(ValueError, match="vertices must have 3"):
        critical_points(V[:, :2], (0, 0), faces=F)
    with pytest.raises(ValueError, match="not used by any face"):
        critical_points(np.vstack([V, [[5.0, 5.0, 5.0]]]), (0, 0, 0), faces=F)
    # two tetrahedra glued at one vertex: closed, but not a manifold there
    T = np.array([[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]])
    P = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]], float)
    T2 = np.where(T == 0, 0, T + 3)
    with pytest.raises(ValueError, match="pinched"):
        critical_points(P, (0.1, 0.2, 0.3), faces=np.vstack([T, T2]))


def test_result_and_public_name():
    assert shapelab.critical_points is critical_points
    assert shapelab.CriticalPoints is CriticalPoints
    r = critical_points(ellipse_curve(2, 1), (0.0, 0.0))
    assert repr(r) == "CriticalPoints(parametric: 2 min, 2 max, χ = 0)"
    with pytest.raises(Exception):
        r.values = None  # frozen


# ------------------------------------------------------------------ figures and widget
def test_figures_and_explorer():
    import matplotlib.figure

    from shapelab.plot import matching as pm
    from shapelab.widgets.matching import critical_points_explorer

    r = critical_points(blob_curve, (0.1, 0.05))
    fig = pm.critical_points(blob_curve, r)
    assert isinstance(fig, matplotlib.figure.Figure) and len(fig.axes) == 2
    V, F = bumpy_sphere(2, seed=1)
    rs = critical_points(V, (0.1, 0.0, 0.0), faces=F)
    fig = pm.critical_surface(V, F, rs)
    assert str(rs.euler_characteristic) in fig.axes[0].get_title()
    with pytest.raises(ValueError, match="surface"):
        pm.critical_points(blob_curve, rs)
    w = critical_points_explorer(blob_curve, viewpoint=(0.1, 0.05))
    assert repr(w) == "CriticalPointsExplorer(S=(0.10, 0.05), 3 minima, 3 maxima)"
    w.sx.value = 1.6  # S outside: still as many minima as maxima
    assert w.result.n_min == w.result.n_max
    with pytest.raises(ValueError, match="x_range"):
        critical_points_explorer(blob_curve, x_range=(1, 0))
