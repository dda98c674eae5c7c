"""Tests of shapelab.measure: area/volume of a union of balls (Notes §23.1).

Oracles, all independent of the dual complex:

* closed forms (one ball, two balls, a Reuleaux triangle, disjoint, nested, tangent);
* an exact union-of-disks algorithm written here: the boundary of the union is made
  of the arcs of each circle not covered by another disk, and Green's theorem turns
  them into the area (and their lengths into the perimeter);
* in 3D, the same algorithm on horizontal slices, integrated over height
  (volume = ∫ area(z) dz, surface = ∫ Σ r_i · exposed angle_i(z) dz, by Archimedes);
* Monte Carlo with a 4σ bound, per ball (ownership by least power distance) and total;
* freesasa's Lee–Richards surface area at fine slicing (optional peer).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from shapelab import Balls, alpha_filtration, union_measure
from shapelab.measure import UnionMeasure, measure_from_simplices

PI = np.pi


# ------------------------------------------------------------------ oracles
def _arcs_of_union(c, r):
    """Exposed arcs of each circle: list of (i, phi1, phi2)."""
    out = []
    n = len(r)
    for i in range(n):
        if r[i] <= 0:
            continue
        ivs = [(0.0, 2 * PI)]
        for j in range(n):
            if j == i or not ivs:
                continue
            dv = c[j] - c[i]
            dist = float(np.hypot(*dv))
            if dist >= r[i] + r[j]:
                continue
            if dist + r[i] <= r[j]:
                # circle i inside disk j (ties between identical disks: keep the first)
                if not (dist == 0 and r[i] == r[j] and i < j):
                    ivs = []
                continue
            if dist + r[j] <= r[i]:
                continue
            t = (dist**2 + r[i] ** 2 - r[j] ** 2) / (2 * dist)
            half = float(np.arccos(np.clip(t / r[i], -1, 1)))
            lo = (np.arctan2(dv[1], dv[0]) - half) % (2 * PI)
            hi = lo + 2 * half
            cuts = [(lo, hi)] if hi <= 2 * PI else [(lo, 2 * PI), (0.0, hi - 2 * PI)]
            for b0, b1 in cuts:
                ivs = [s for a0, a1 in ivs for s in ((a0, min(a1, b0)), (max(a0, b1), a1)) if s[1] > s[0]]
        out += [(i, a0, a1) for a0, a1 in ivs]
    return out


def union_disks_exact(c, r):
    """Area and perimeter of a union of disks, by Green's theorem on exposed arcs."""
    c = np.asarray(c, float)
    c = c - c[0]
    r = np.asarray(r, float)
    area = perim = 0.0
    for i, p1, p2 in _arcs_of_union(c, r):
        area += 0.5 * (
            r[i] ** 2 * (p2 - p1) + r[i] * (c[i, 0] * (np.sin(p2) - np.sin(p1)) - c[i, 1] * (np.cos(p2) - np.cos(p1)))
        )
        perim += r[i] * (p2 - p1)
    return area, perim


def union_balls_by_slices(c, r, panels=240, order=10):
    """Volume and surface area of a union of balls by exact 2D slices integrated with
    composite Gauss–Legendre over z (breakpoints at the poles of the spheres)."""
    c = np.asarray(c, float)
    r = np.asarray(r, float)
    x, wq = np.polynomial.legendre.leggauss(order)
    breaks = np.unique(np.concatenate([c[:, 2] - r, c[:, 2] + r]))
    vol = surf = 0.0
    for z0, z1 in zip(breaks[:-1], breaks[1:]):
        edges = np.linspace(z0, z1, max(2, int(panels * (z1 - z0) / (breaks[-1] - breaks[0])) + 2))
        for a, b in zip(edges[:-1], edges[1:]):
            for xi, wi in zip(x, wq):
                z = 0.5 * (a + b) + 0.5 * (b - a) * xi
                rho2 = r**2 - (z - c[:, 2]) ** 2
                live = rho2 > 0
                if not live.any():
                    continue
                cc, rr, R = c[live, :2], np.sqrt(rho2[live]), r[live]
                A, _ = union_disks_exact(cc, rr)
                exposed = sum(R[i] * (p2 - p1) for i, p1, p2 in _arcs_of_union(cc - cc[0], rr))
                vol += 0.5 * (b - a) * wi * A
                surf += 0.5 * (b - a) * wi * exposed
    return vol, surf


def mc_union(c, r, n, seed):
    """Monte Carlo: total and per-ball shares (owner = least power distance), with
    standard errors."""
    rng = np.random.default_rng(seed)
    lo, hi = (c - r[:, None]).min(0), (c + r[:, None]).max(0)
    box = np.prod(hi - lo)
    x = rng.uniform(lo, hi, (n, c.shape[1]))
    pd = ((x[:, None, :] - c[None]) ** 2).sum(-1) - r[None] ** 2
    inside = (pd <= 0).any(1)
    counts = np.bincount(pd.argmin(1)[inside], minlength=len(r))
    p_all, p_ball = inside.mean(), counts / n
    return box * p_all, box * np.sqrt(p_all * (1 - p_all) / n), box * p_ball, box * np.sqrt(p_ball * (1 - p_ball) / n)


def lens_area(d, r, R):
    """Area of the intersection of two disks (standard closed form)."""
    if d >= r + R:
        return 0.0
    if d <= abs(R - r):
        return PI * min(r, R) ** 2
    a = r**2 * np.arccos((d**2 + r**2 - R**2) / (2 * d * r)) + R**2 * np.arccos((d**2 + R**2 - r**2) / (2 * d * R))
    return a - 0.5 * np.sqrt((-d + r + R) * (d + r - R) * (d - r + R) * (d + r + R))


def lens_volume(d, r, R):
    """Volume of the intersection of two balls (standard closed form)."""
    if d >= r + R:
        return 0.0
    if d <= abs(R - r):
        return 4 / 3 * PI * min(r, R) ** 3
    return PI * (R + r - d) ** 2 * (d**2 + 2 * d * r - 3 * r**2 + 2 * d * R + 6 * r * R - 3 * R**2) / (12 * d)


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def random_balls(seed, n, d, lo=0.3, hi=1.2, box=4.0):
    rng = np.random.default_rng(seed)
    return Balls(rng.uniform(0, box, (n, d)), rng.uniform(lo, hi, n))


# ------------------------------------------------------------ closed forms
@pytest.mark.parametrize("r", [0.0, 1e-6, 1.0, 3.7])
def test_single_ball(r):
    m2 = union_measure(Balls([[1.0, 2.0]], r))
    assert m2.area == pytest.approx(PI * r**2, rel=1e-14, abs=0)
    assert m2.perimeter == pytest.approx(2 * PI * r, rel=1e-14, abs=0)
    m3 = union_measure(Balls([[1.0, 2.0, 3.0]], r))
    assert m3.volume == pytest.approx(4 / 3 * PI * r**3, rel=1e-14, abs=0)
    assert m3.surface_area == pytest.approx(4 * PI * r**2, rel=1e-14, abs=0)


@pytest.mark.parametrize(
    "d, r, R", [(1.0, 1.0, 1.0), (1.5, 1.0, 0.7), (0.3, 1.0, 0.9), (2.5, 2.0, 1.0), (0.1, 3.0, 2.95)]
)
def test_two_disks_and_two_balls_closed_form(d, r, R):
    m = union_measure(Balls([[0.0, 0.0], [d, 0.0]], [r, R]))
    assert m.area == pytest.approx(PI * (r**2 + R**2) - lens_area(d, r, R), rel=1e-12)
    # perimeter: each circle minus its arc inside the other disk (law of cosines)
    a1 = 2 * np.arccos(np.clip((d**2 + r**2 - R**2) / (2 * d * r), -1, 1))
    a2 = 2 * np.arccos(np.clip((d**2 + R**2 - r**2) / (2 * d * R), -1, 1))
    assert m.perimeter == pytest.approx(r * (2 * PI - a1) + R * (2 * PI - a2), rel=1e-12)
    m3 = union_measure(Balls([[0.0, 0.0, 0.0], [d, 0.0, 0.0]], [r, R]))
    assert m3.volume == pytest.approx(4 / 3 * PI * (r**3 + R**3) - lens_volume(d, r, R), rel=1e-12)
    # surface: each sphere minus its cap inside the other ball (Archimedes: 2πrh)
    t1 = (d**2 + r**2 - R**2) / (2 * d)
    t2 = d - t1
    assert m3.surface_area == pytest.approx(4 * PI * (r**2 + R**2) - 2 * PI * (r * (r - t1) + R * (R - t2)), rel=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_disjoint_nested_tangent(dim):
    e = np.eye(dim)[0]
    z = np.zeros(dim)
    vol = (lambda r: PI * r**2) if dim == 2 else (lambda r: 4 / 3 * PI * r**3)
    bnd = (lambda r: 2 * PI * r) if dim == 2 else (lambda r: 4 * PI * r**2)
    disjoint = union_measure(Balls([z, 5 * e], [1.0, 2.0]))
    assert disjoint.measure == pytest.approx(vol(1) + vol(2), rel=1e-14)
    assert disjoint.boundary == pytest.approx(bnd(1) + bnd(2), rel=1e-14)
    tangent = union_measure(Balls([z, 3 * e], [1.0, 2.0]))
    assert tangent.measure == pytest.approx(vol(1) + vol(2), rel=1e-14)
    assert tangent.boundary == pytest.approx(bnd(1) + bnd(2), rel=1e-14)
    nested = union_measure(Balls([z, 0.5 * e, -0.2 * e], [2.0, 1.0, 1.8]))
    assert nested.measure == pytest.approx(vol(2), rel=1e-14)
    assert nested.boundary == pytest.approx(bnd(2), rel=1e-14)
    assert nested.ball_measure[1:] == pytest.approx([0, 0], abs=1e-14)
    internally_tangent = union_measure(Balls([z, e], [2.0, 1.0]))
    assert internally_tangent.measure == pytest.approx(vol(2), rel=1e-13)
    assert internally_tangent.boundary == pytest.approx(bnd(2), rel=1e-13)


def test_three_disks_reuleaux():
    """Three disks of radius s centred at the corners of an equilateral triangle of
    side s: the triple intersection is the Reuleaux triangle, (π − √3) s²/2."""
    s = 1.3
    c = s * np.array([[0, 0], [1, 0], [0.5, np.sqrt(3) / 2]])
    m = union_measure(Balls(c, s))
    assert m.counts == (3, 3, 1)
    lens = 2 * s**2 * PI / 3 - np.sqrt(3) / 2 * s**2
    reuleaux = (PI - np.sqrt(3)) * s**2 / 2
    assert m.area == pytest.approx(3 * PI * s**2 - 3 * lens + reuleaux, rel=1e-13)
    assert m.terms[2] == pytest.approx(reuleaux, rel=1e-13)
    assert m.terms[1] == pytest.approx(3 * lens, rel=1e-13)


def test_three_collinear_balls_3d():
    c = np.array([[0, 0, 0], [1.5, 0, 0], [3.0, 0, 0]], float)
    r = np.array([1.0, 1.0, 1.0])
    m = union_measure(Balls(c, r))
    assert m.volume == pytest.approx(3 * 4 / 3 * PI - 2 * lens_volume(1.5, 1, 1), rel=1e-13)


# -------------------------------------------------------- exact 2D oracle
@pytest.mark.parametrize("seed", range(12))
def test_random_disks_against_exact_arcs(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 40))
    b = random_balls(seed, n, 2, 0.0, 1.4)
    m = union_measure(b)
    A, L = union_disks_exact(b.centers, b.radii)
    assert rel(m.area, A) < 1e-11
    assert rel(m.perimeter, L) < 1e-11
    assert m.ball_measure.sum() == pytest.approx(m.area, rel=1e-12)
    assert m.ball_boundary.sum() == pytest.approx(m.perimeter, rel=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.integers(0, 5), st.integers(0, 5), st.sampled_from([0.5, 1.0, 1.5, 2**0.5 / 2, 2**0.5, 5**0.5 / 2])
        ),
        min_size=1,
        max_size=14,
    )
)
def test_integer_disks_hypothesis(rows):
    """Grid centres and radii chosen so that tangencies, cocircular and duplicate
    centres are frequent."""
    a = np.array(rows, float)
    b = Balls(a[:, :2], a[:, 2])
    m = union_measure(b)
    A, L = union_disks_exact(b.centers, b.radii)
    # tangencies make the perimeter sensitive at sqrt(eps) to rounding in the oracle
    assert abs(m.area - A) <= 1e-9 * A
    assert abs(m.perimeter - L) <= 1e-7 * L
    assert m.ball_measure.sum() == pytest.approx(m.area, rel=1e-12)
    assert np.all(m.ball_boundary >= -1e-12)


# ---------------------------------------------------- 3D: slices, freesasa
@pytest.mark.parametrize("seed", range(3))
def test_random_balls_against_slices(seed):
    b = random_balls(100 + seed, 6, 3, 0.8, 1.5, box=2.5)
    m = union_measure(b)
    assert m.counts[3] >= 1  # the quadruple-intersection terms are exercised
    V, S = union_balls_by_slices(b.centers, b.radii)
    # the oracle's quadrature: ~1e-9 for the volume, ~1e-5 for the surface (its
    # integrand has kinks where circles become tangent inside a panel)
    assert rel(m.volume, V) < 1e-7
    assert rel(m.surface_area, S) < 3e-5


def test_regular_tetrahedron_of_balls_against_slices():
    c = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    b = Balls(c, 1.75)  # > sqrt(3), the circumradius: the tetrahedron is in K
    m = union_measure(b)
    assert m.counts == (4, 6, 4, 1)
    V, S = union_balls_by_slices(c, b.radii)
    # the oracle's quadrature: ~1e-9 for the volume, ~1e-5 for the surface (its
    # integrand has kinks where circles become tangent inside a panel)
    assert rel(m.volume, V) < 1e-7
    assert rel(m.surface_area, S) < 3e-5


@pytest.mark.parametrize("seed", range(3))
def test_surface_against_freesasa_lee_richards(seed):
    freesasa = pytest.importorskip("freesasa")
    freesasa.setVerbosity(freesasa.silent)
    b = random_balls(200 + seed, 40, 3, 0.9, 1.7, box=5.0)
    m = union_measure(b)
    params = freesasa.Parameters({"algorithm": freesasa.LeeRichards, "n-slices": 2000, "probe-radius": 0.0})
    res = freesasa.calcCoord(b.centers.ravel(), b.radii, params)
    per_atom = np.array([res.atomArea(i) for i in range(len(b))])
    assert rel(m.surface_area, res.totalArea()) < 1e-4
    np.testing.assert_allclose(m.ball_boundary, per_atom, atol=2e-3 * (b.radii**2).max())


# ------------------------------------------------------------ Monte Carlo
@pytest.mark.parametrize("dim, seed", [(2, 0), (2, 1), (3, 0), (3, 1)])
def test_monte_carlo_total_and_per_ball(dim, seed):
    b = random_balls(300 + seed, 12, dim, 0.5, 1.3, box=3.0)
    m = union_measure(b)
    tot, se, per, per_se = mc_union(b.centers, b.radii, 200_000, seed)
    assert abs(m.measure - tot) < 4 * se + 1e-12
    # each ball's share is vol(B_i ∩ Π(B_i)); 4σ per ball with a Bonferroni margin
    assert np.all(np.abs(m.ball_measure - per) < 5 * per_se + 1e-9)


# ------------------------------------------------------------- invariants
@pytest.mark.parametrize("dim", [2, 3])
def test_shares_sum_and_hidden_balls_get_nothing(dim):
    b = random_balls(7, 25, dim)
    m = union_measure(b)
    assert m.ball_measure.sum() == pytest.approx(m.measure, rel=1e-12)
    assert m.ball_boundary.sum() == pytest.approx(m.boundary, rel=1e-12)
    assert np.all(m.ball_measure >= -1e-12) and np.all(m.ball_boundary >= -1e-12)
    # a ball hidden inside another adds nothing and gets nothing
    c2 = np.vstack([b.centers, b.centers[:1] + 0.01])
    r2 = np.append(b.radii, b.radii[0] * 0.3)
    m2 = union_measure(Balls(c2, r2))
    assert m2.measure == pytest.approx(m.measure, rel=1e-12)
    assert m2.boundary == pytest.approx(m.boundary, rel=1e-12)
    assert m2.ball_measure[-1] == pytest.approx(0.0, abs=1e-12)
    # short formula: alternating sum of the terms
    assert sum((-1) ** k * t for k, t in enumerate(m.terms)) == pytest.approx(m.measure, rel=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_rigid_motion_scaling_permutation(dim):
    b = random_balls(11, 30, dim)
    m = union_measure(b)
    rot = Rotation.random(random_state=3).as_matrix()[:dim, :dim] if dim == 3 else np.array([[0.6, -0.8], [0.8, 0.6]])
    moved = union_measure(Balls(b.centers @ rot.T + 1e6, b.radii))
    assert moved.measure == pytest.approx(m.measure, rel=1e-8)
    assert moved.boundary == pytest.approx(m.boundary, rel=1e-8)
    s = 1e-6
    tiny = union_measure(b.scaled(s))
    assert tiny.measure == pytest.approx(m.measure * s**dim, rel=1e-11)
    assert tiny.boundary == pytest.approx(m.boundary * s ** (dim - 1), rel=1e-11)
    perm = np.random.default_rng(0).permutation(len(b))
    mp = union_measure(b[perm])
    assert mp.measure == pytest.approx(m.measure, rel=1e-12)
    np.testing.assert_allclose(mp.ball_measure, m.ball_measure[perm], rtol=1e-9, atol=1e-12)


def test_duplicates_give_the_same_union():
    b = random_balls(12, 15, 3)
    m = union_measure(b)
    dup = union_measure(Balls(np.vstack([b.centers, b.centers[:5]]), np.append(b.radii, b.radii[:5])))
    assert dup.measure == pytest.approx(m.measure, rel=1e-12)
    assert dup.boundary == pytest.approx(m.boundary, rel=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("tau", [-0.5, 0.0, 0.7])
def test_without_a_filtration_is_the_same_as_with_one(dim, tau):
    """union_measure builds only K(tau) when not given the Filtration: same complex,
    same numbers (duplicates and a 1e6 offset included)."""
    b = random_balls(40, 30, dim)
    b = Balls(np.vstack([b.centers, b.centers[:4]]) + 1e6, np.append(b.radii, b.radii[:4] * 0.5))
    fast = union_measure(b, tau=tau)
    full = union_measure(alpha_filtration(b), tau=tau)
    assert fast.counts == full.counts
    assert fast.measure == pytest.approx(full.measure, rel=1e-12)
    assert fast.boundary == pytest.approx(full.boundary, rel=1e-12)
    np.testing.assert_allclose(fast.ball_measure, full.ball_measure, rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("radius", [0.5, 0.6, 2**0.5 / 2, 0.8, 3**0.5 / 2, 0.9, 1.2])
def test_cubic_grid_rotated_equals_axis_aligned(radius):
    """A 3x3x3 grid is maximally degenerate (cospherical, coplanar, tangent balls);
    rotated by a random rotation the triangulation changes (flat tetrahedra appear),
    the union does not."""
    g = np.array([[i, j, k] for i in range(3) for j in range(3) for k in range(3)], float)
    m0 = union_measure(Balls(g, radius))
    for seed in range(2):
        m = union_measure(Balls(Rotation.random(random_state=seed).apply(g) + 1e3, radius))
        assert m.volume == pytest.approx(m0.volume, rel=1e-12)
        assert m.surface_area == pytest.approx(m0.surface_area, rel=1e-12)
        np.testing.assert_allclose(np.sort(m.ball_measure), np.sort(m0.ball_measure), atol=1e-12)
    if radius == 0.5:  # tangent, no overlaps
        assert m0.volume == pytest.approx(27 * 4 / 3 * PI * 0.125, rel=1e-14)


def test_square_grid_of_disks():
    g = np.array([[i, j] for i in range(5) for j in range(5)], float)
    for r in (0.5, 0.6, 2**0.5 / 2, 1.0):
        m = union_measure(Balls(g, r))
        A, L = union_disks_exact(g, np.full(25, r))
        assert rel(m.area, A) < 1e-12 and rel(m.perimeter, L) < 1e-12
        th = 0.3
        rot = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        mr = union_measure(Balls(g @ rot.T, r))
        assert rel(mr.area, A) < 1e-12 and rel(mr.perimeter, L) < 1e-7


# -------------------------------------------------------------- growth time
@pytest.mark.parametrize("dim", [2, 3])
def test_tau_is_the_union_of_grown_balls(dim):
    b = random_balls(21, 20, dim)
    F = alpha_filtration(b)
    for tau in (0.3, 1.0):
        assert union_measure(F, tau=tau).measure == pytest.approx(union_measure(b.grow(tau)).measure, rel=1e-11)
    # negative tau: balls with r^2 + tau < 0 are empty
    tau = -0.2
    alive = b.weights + tau >= 0
    grown = Balls(b.centers[alive], np.sqrt(b.weights[alive] + tau))
    assert union_measure(F, tau=tau).measure == pytest.approx(union_measure(grown).measure, rel=1e-11)
    assert union_measure(b, tau=-10.0).measure == 0.0


@pytest.mark.parametrize("dim", [2, 3])
def test_boundary_is_the_derivative_of_measure(dim):
    """d vol/dτ = Σ_i area(∂B_i ∩ ∂U) · dr_i/dτ with dr_i/dτ = 1/(2 r_i)."""
    b = random_balls(31, 15, dim, 0.6, 1.2)
    F = alpha_filtration(b)
    h = 1e-5
    num = (union_measure(F, tau=h).measure - union_measure(F, tau=-h).measure) / (2 * h)
    m = union_measure(F)
    assert num == pytest.approx(np.sum(m.ball_boundary / (2 * b.radii)), rel=1e-6)


# ------------------------------------------------------- API and validation
def test_result_type_and_words():
    m2 = union_measure(random_balls(1, 5, 2))
    assert isinstance(m2, UnionMeasure)
    assert m2.area == m2.measure and m2.perimeter == m2.boundary
    with pytest.raises(AttributeError):
        m2.volume
    m3 = union_measure(random_balls(1, 5, 3))
    assert m3.area == m3.surface_area == m3.boundary and m3.volume == m3.measure
    with pytest.raises(AttributeError):
        m3.perimeter
    assert repr(m3).startswith("UnionMeasure(dim=3, tau=0, volume=")
    with pytest.raises(ValueError):
        m3.ball_measure[0] = 1.0
    empty = union_measure(Balls(np.zeros((0, 2)), 1.0))
    assert empty.area == 0.0 and empty.ball_measure.shape == (0,)


def test_bad_input():
    b = random_balls(1, 5, 2)
    with pytest.raises(TypeError, match="balls"):
        union_measure(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="tau"):
        union_measure(b, tau=float("nan"))
    with pytest.raises(TypeError, match="tau"):
        union_measure(b, tau="1")
    with pytest.raises(TypeError, match="Filtration"):
        union_measure(object())
    with pytest.raises(TypeError, match="filtration"):  # the old keyword: Python's own TypeError
        union_measure(b, filtration=alpha_filtration(b))
    with pytest.raises(ValueError, match="finite"):
        union_measure(b, float("inf"))
    empty = union_measure(alpha_filtration(b), -np.inf)
    assert empty.measure == 0.0 and empty.boundary == 0.0
    # the filtration or the balls, τ by position or by keyword: the same numbers
    assert union_measure(alpha_filtration(b), 0.3).measure == union_measure(b, tau=0.3).measure


def test_measure_from_simplices_matches_gudhi_complex():
    gudhi = pytest.importorskip("gudhi")
    b = random_balls(41, 30, 3)
    stree = gudhi.AlphaComplex(points=b.centers, weights=b.weights).create_simplex_tree()
    K = [[] for _ in range(4)]
    for s, v in stree.get_filtration():
        if v <= 0:
            K[len(s) - 1].append(sorted(s))
    K = [np.array(k, dtype=np.int64).reshape(-1, i + 1) for i, k in enumerate(K)]
    ours = union_measure(b)
    theirs = measure_from_simplices(b.centers, b.weights, K)
    assert theirs.volume == pytest.approx(ours.volume, rel=1e-12)
    assert theirs.counts == ours.counts


# ------------------------------------------------- the cells B_i ∩ Π(B_i)
def _poly_area(P):
    if len(P) < 3:
        return 0.0
    x, y = P.T
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


@pytest.mark.parametrize(
    "centers, radii",
    [
        ([[0, 0], [1, 0], [2, 0]], 0.6),  # collinear: K has no triangle
        ([[0, 0], [1, 1]], 0.8),  # n <= d
        ([[0, 0], [0.1, 0], [0, 0.1]], [3.0, 0.1, 0.1]),  # all hidden but one
        ([[0, 0], [0, 0], [0.5, 0]], [1.0, 1.0, 0.7]),  # duplicate centres
    ],
)
def test_low_dimensional_disks(centers, radii):
    b = Balls(centers, radii)
    m = union_measure(b)
    A, L = union_disks_exact(b.centers, b.radii)
    assert m.area == pytest.approx(A, rel=1e-12) and m.perimeter == pytest.approx(L, rel=1e-12)


@pytest.mark.parametrize(
    "centers",
    [
        [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]],  # coplanar and cocircular
        [[0, 0, 0], [1, 0, 0], [2, 0, 0]],  # collinear
        [[0, 0, 0], [1, 0.2, 0.1]],  # n <= d
    ],
)
def test_low_dimensional_balls(centers):
    b = Balls(centers, 0.8)
    m = union_measure(b)
    V, S = union_balls_by_slices(b.centers, b.radii)
    assert rel(m.volume, V) < 1e-7 and rel(m.surface_area, S) < 3e-5


def test_tangent_angle_is_the_angle_of_the_projections():
    from shapelab._engine.measure import angle as _angle
    from shapelab._engine.measure import tangent_angle as _tangent_angle
    from shapelab._toolkit.geometry import dot as _dot

    rng = np.random.default_rng(3)
    um, uk, p = (rng.normal(size=(3, 500)) for _ in range(3))
    um, uk, p = (v / np.sqrt(_dot(v, v)) for v in (um, uk, p))
    projected = _angle(um - _dot(um, p) * p, uk - _dot(uk, p) * p)
    np.testing.assert_allclose(_tangent_angle(um, uk, p), projected, rtol=0, atol=1e-12)
    # right angle about the z axis, whatever the components along it
    ez = np.array([[0.0], [0.0], [1.0]])
    a = np.array([[1.0], [0.0], [5.0]]) / np.sqrt(26.0)
    b = np.array([[0.0], [1.0], [-2.0]]) / np.sqrt(5.0)
    assert _tangent_angle(a, b, ez)[0] == pytest.approx(np.pi / 2, abs=1e-15)


# ------------------------------------------- tiny balls in a large scene (issue 10)
# Every tolerance of union_measure is relative to the quantity it guards (a ball's own
# radius, a simplex's own entry time), never to the input's extent: small balls far
# apart are measured, not dropped.
def _cap_area(d, r, R):
    """Area of sphere r outside ball R at distance d (Archimedes: 2 pi r h)."""
    t = (d**2 + r**2 - R**2) / (2 * d)
    return 4 * PI * r**2 - 2 * PI * r * (r - t)


def _arc_length(d, r, R):
    """Length of circle r outside disk R at distance d."""
    return r * (2 * PI - 2 * np.arccos((d**2 + r**2 - R**2) / (2 * d * r)))


@pytest.mark.parametrize("dim", [2, 3])
def test_two_tiny_balls_far_apart(dim):
    """The issue's case: r = 3e-6 at distance 1 gave 0; the union is two balls."""
    r = 3e-6
    c = np.zeros((2, dim))
    c[1, 0] = 1.0
    m = union_measure(Balls(c, r))
    if dim == 3:
        assert m.volume == pytest.approx(2 * 4 / 3 * PI * r**3, rel=1e-14, abs=0)  # 2.26e-16
        assert m.surface_area == pytest.approx(2 * 4 * PI * r**2, rel=1e-14, abs=0)
    else:
        assert m.area == pytest.approx(2 * PI * r**2, rel=1e-14, abs=0)
        assert m.perimeter == pytest.approx(2 * 2 * PI * r, rel=1e-14, abs=0)
    assert m.counts[0] == 2 and m.counts[1] == 0


@pytest.mark.parametrize("dim, n", [(2, 20_000), (3, 20_000)])
def test_many_tiny_disjoint_balls_in_the_unit_cube(dim, n):
    """n balls of radius 1e-9 in the unit cube (the issue: 200,000 of them gave volume
    and area 0): disjoint, so the sums of the closed forms, ball by ball."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(2026)
    c = rng.uniform(0.0, 1.0, (n, dim))
    r = 1e-9
    assert cKDTree(c).query(c, k=2)[0][:, 1].min() > 2 * r
    m = union_measure(Balls(c, r))
    vol1, bnd1 = (PI * r**2, 2 * PI * r) if dim == 2 else (4 / 3 * PI * r**3, 4 * PI * r**2)
    assert m.measure == pytest.approx(n * vol1, rel=1e-12, abs=0)
    assert m.boundary == pytest.approx(n * bnd1, rel=1e-12, abs=0)
    np.testing.assert_allclose(m.ball_measure, vol1, rtol=1e-14, atol=0)
    np.testing.assert_allclose(m.ball_boundary, bnd1, rtol=1e-14, atol=0)
    assert m.counts[1:] == (0,) * dim


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("scale, offset", [(1e-6, 0.0), (1e-6, 1e6), (1.0, 1e6)])
def test_overlapping_tiny_pairs_next_to_big_balls(dim, scale, offset):
    """A cluster of unit-size balls at the origin and, at ``offset + 100 k`` (k = 1..5),
    pairs of overlapping balls of radii ``scale * (1, 0.7)``: the union is the cluster
    plus five lenses' complements, each by its two-ball closed form (with the distance
    the float64 centres actually have)."""
    rng = np.random.default_rng(7 + dim)
    big = random_balls(11 + dim, 30, dim, 0.8, 1.5, box=4.0)
    cs, rs, expect_m, expect_b = [big.centers], [big.radii], 0.0, 0.0
    for k in range(1, 6):
        a = np.full(dim, offset + 100.0 * k)
        u = rng.normal(size=dim)
        b = a + scale * rng.uniform(0.5, 1.5) * u / np.linalg.norm(u)
        r, R = scale * 1.0, scale * 0.7
        cs.append(np.array([a, b]))
        rs.append(np.array([r, R]))
        d = float(np.linalg.norm(b - a))
        assert abs(r - R) < d < r + R
        if dim == 3:
            expect_m += 4 / 3 * PI * (r**3 + R**3) - lens_volume(d, r, R)
            expect_b += _cap_area(d, r, R) + _cap_area(d, R, r)
        else:
            expect_m += PI * (r**2 + R**2) - lens_area(d, r, R)
            expect_b += _arc_length(d, r, R) + _arc_length(d, R, r)
    m = union_measure(Balls(np.concatenate(cs), np.concatenate(rs)))
    mb = union_measure(big)
    n_big = len(big)
    assert m.ball_measure[:n_big] == pytest.approx(mb.ball_measure, rel=1e-9, abs=1e-12)
    assert m.ball_boundary[:n_big] == pytest.approx(mb.ball_boundary, rel=1e-9, abs=1e-12)
    assert m.ball_measure[n_big:].sum() == pytest.approx(expect_m, rel=1e-9, abs=0)
    assert m.ball_boundary[n_big:].sum() == pytest.approx(expect_b, rel=1e-9, abs=0)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("scale, offset", [(1e-6, 0.0), (1e-6, 1e6), (1.0, 1e6), (1e6, 0.0)])
def test_scaled_and_offset_copies(dim, scale, offset):
    """``offset + scale * x`` measures scale^d times x's measure, where x is the
    configuration the float64 centres really describe, ``(c - offset) / scale``
    (the offset quantises them)."""
    b = random_balls(40 + dim, 40, dim, 0.5, 1.3, box=5.0)
    c = offset + scale * b.centers
    r = scale * b.radii
    m = union_measure(Balls(c, r))
    unit = union_measure(Balls((c - offset) / scale, r / scale))
    assert m.measure == pytest.approx(unit.measure * scale**dim, rel=1e-10)
    assert m.boundary == pytest.approx(unit.boundary * scale ** (dim - 1), rel=1e-10)


@pytest.mark.parametrize("scale", [1e-6, 1e-3])
def test_tiny_balls_surface_against_freesasa(scale):
    """freesasa's Lee–Richards area (a peer that knows nothing of dual complexes) for a
    cluster at scale 1e-6, next to which a unit ball sits 10^3 away."""
    freesasa = pytest.importorskip("freesasa")
    freesasa.setVerbosity(freesasa.silent)
    b = random_balls(201, 40, 3, 0.9, 1.7, box=5.0)
    c, r = scale * b.centers, scale * b.radii
    params = freesasa.Parameters({"algorithm": freesasa.LeeRichards, "n-slices": 2000, "probe-radius": 0.0})
    res = freesasa.calcCoord(c.ravel(), r, params)
    per_atom = np.array([res.atomArea(i) for i in range(len(b))])
    m = union_measure(Balls(np.r_[c, [[1e3, 0.0, 0.0]]], np.r_[r, 1.0]))
    assert rel(m.ball_boundary[:-1].sum(), res.totalArea()) < 1e-4
    np.testing.assert_allclose(m.ball_boundary[:-1], per_atom, atol=2e-3 * (r**2).max())
    assert m.ball_boundary[-1] == pytest.approx(4 * PI, rel=1e-14)
