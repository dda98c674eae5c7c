"""The regular triangulation is exact: predicates, certificate, degenerate families.

Oracles independent of the code under test:

* the predicates against determinants in ``fractions.Fraction``, and Simulation of
  Simplicity against the same determinant with the heights lowered by explicit,
  rapidly decreasing rationals;
* small inputs against a brute-force regular triangulation: every (k+1)-subset
  whose lifted hyperplane passes strictly below every other lifted centre, decided in
  rationals with the same explicit perturbation;
* the tiling of the convex hull: the simplices' volumes (rationals) add up to the
  hull's volume (scipy's Qhull) and the complex has Euler characteristic 1;
* the certificate itself, evaluated on the output with fresh predicates.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import ConvexHull

from shapelab import Balls, alpha_filtration, regular_triangulation
from shapelab._engine.certify import certify
from shapelab._engine.predicates import WeightedPoints
from shapelab.triangulation import triangulation_report


# ------------------------------------------------------------------ rational oracles
def fdet(M):
    M = [[Fraction(v) for v in row] for row in M]
    n = len(M)
    sign = 1
    for c in range(n):
        p = next((r for r in range(c, n) if M[r][c] != 0), None)
        if p is None:
            return Fraction(0)
        if p != c:
            M[c], M[p] = M[p], M[c]
            sign = -sign
        for r in range(c + 1, n):
            f = M[r][c] / M[c][c]
            M[r] = [a - f * b for a, b in zip(M[r], M[c])]
    out = Fraction(sign)
    for c in range(n):
        out *= M[c][c]
    return out


def lifted_det(c, r, rows, eps=None):
    """det of rows (1, z, |z|^2 - r^2 - eps_j) in rationals."""
    M = []
    for j in rows:
        z = [Fraction(float(v)) for v in c[j]]
        h = sum(v * v for v in z) - Fraction(float(r[j])) ** 2
        if eps is not None:
            h -= eps[j]
        M.append([Fraction(1)] + z + [h])
    return fdet(M)


def sos_eps(n):
    """eps_j = delta**(j+1): each far smaller than the one before (small inputs)."""
    delta = Fraction(1, 2**120)
    return [delta ** (j + 1) for j in range(n)]


def brute_force_regular(c, r):
    """All k-simplices (k = d) whose lifted hyperplane lies strictly below every other
    lifted centre, in rationals with explicit SoS heights."""
    n, d = c.shape
    eps = sos_eps(n)
    out = set()
    for S in itertools.combinations(range(n), d + 1):
        o = fdet([[1] + [Fraction(float(v)) for v in c[j]] for j in S])
        if o == 0:
            continue
        ok = True
        for q in range(n):
            if q in S:
                continue
            D = lifted_det(c, r, list(S) + [q], eps)
            if D * o <= 0:  # q below or on the lifted hyperplane
                ok = False
                break
        if ok:
            out.add(S)
    return out


def simplex_volume(c, S):
    d = c.shape[1]
    M = [[Fraction(float(c[j][a])) - Fraction(float(c[S[0]][a])) for a in range(d)] for j in S[1:]]
    return abs(fdet(M)) / (2 if d == 2 else 6)


def assert_tiles_hull(balls, T):
    c = balls.centers
    vol = float(sum(simplex_volume(c, S) for S in T.tolist()))
    hull = ConvexHull(c[np.unique(T)]).volume
    assert vol == pytest.approx(hull, rel=1e-9)
    # Euler characteristic of the closed triangulation: 1
    faces = set()
    for S in T.tolist():
        for k in range(1, len(S) + 1):
            faces.update(itertools.combinations(S, k))
    chi = sum((-1) ** (len(f) - 1) for f in faces)
    assert chi == 1


def assert_certified(balls, T):
    # the output re-checked with fresh predicates (hidden balls included)
    from shapelab._engine.triangulation import _frame  # noqa: PLC2701 - the test reads the engine's frame

    fr = _frame(balls)
    local = {int(g): i for i, g in enumerate(fr.keep)}
    S = np.array([[local[int(v)] for v in row] for row in T.tolist()], dtype=np.int64)
    S.sort(axis=1)
    axes = None if fr.k == balls.dim else fr.axes
    P = WeightedPoints(balls.centers[fr.keep], balls.radii[fr.keep], axes=axes, priority=fr.keep)
    cert = certify(P, S)
    assert cert.ok, cert.reason


# ------------------------------------------------------------------ predicates
small = st.integers(-4, 4)


@settings(max_examples=150, deadline=None)
@given(
    st.lists(st.tuples(small, small, small), min_size=4, max_size=4),
    st.sampled_from([1.0, 1e-6, 3.0]),
    st.sampled_from([0.0, 1e6]),
)
def test_orient_is_the_rational_determinant(pts, scale, offset):
    c = np.array(pts, dtype=float) * scale + offset
    P = WeightedPoints(c, np.zeros(4))
    exact = fdet([[Fraction(float(v)) - Fraction(float(c[0][a])) for a, v in enumerate(p)] for p in c[1:]])
    assert P.orient([[0, 1, 2, 3]])[0] == (exact > 0) - (exact < 0)
    assert P.orient1([0, 1, 2, 3]) == (exact > 0) - (exact < 0)


@settings(max_examples=200, deadline=None)
@given(
    st.lists(st.tuples(small, small, small), min_size=5, max_size=5),
    st.lists(st.integers(0, 2), min_size=5, max_size=5),
    st.permutations(range(5)),
)
def test_power_with_simulation_of_simplicity(pts, radii, prio):
    c = np.array(pts, dtype=float)
    r = np.array(radii, dtype=float)
    P = WeightedPoints(c, r, priority=np.array(prio))
    rank = np.array(prio)
    eps_by_rank = sos_eps(5)
    eps = {j: eps_by_rank[rank[j]] for j in range(5)}
    rows = list(range(5))
    exact = lifted_det(c, r, rows)
    pert = lifted_det(c, r, rows, eps)
    want = (pert > 0) - (pert < 0)
    if exact != 0:
        assert want == (exact > 0) - (exact < 0)
    assert P.power([rows])[0] == want
    assert P.power1(rows) == want


def test_filter_decides_random_input_and_exact_decides_ties():
    rng = np.random.default_rng(5)
    c = rng.random((2000, 3))
    P = WeightedPoints(c, rng.random(2000) * 0.1)
    rows = np.argsort(rng.random((5000, 2000)), axis=1)[:, :5]  # five distinct points a row
    P.power(rows)
    assert P.stats["power_exact"] == 0 and P.stats["power_filtered"] == 5000
    grid = np.stack(np.meshgrid(*[np.arange(3.0)] * 3), -1).reshape(-1, 3)
    G = WeightedPoints(grid, np.zeros(27))
    cube = [0, 1, 3, 4, 9]  # five corners of one unit cube: co-spherical
    assert lifted_det(grid, np.zeros(27), cube) == 0
    assert G.power([cube])[0] != 0 and G.stats["power_ties"] == 1


# ------------------------------------------------------------------ brute force
@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.integers(0, 3), st.integers(0, 3)), min_size=3, max_size=9, unique=True),
    st.lists(st.integers(0, 1), min_size=9, max_size=9),
)
def test_small_integer_inputs_2d_equal_brute_force(pts, radii):
    c = np.array(pts, dtype=float)
    if np.linalg.matrix_rank(c - c[0]) < 2:
        return
    r = np.array(radii[: len(pts)], dtype=float)
    balls = Balls(c, r)
    T = regular_triangulation(balls)
    assert {tuple(s) for s in T.tolist()} == brute_force_regular(c, r)


@settings(max_examples=25, deadline=None)
@given(
    st.lists(st.tuples(st.integers(0, 2), st.integers(0, 2), st.integers(0, 2)), min_size=4, max_size=8, unique=True),
    st.lists(st.integers(0, 1), min_size=8, max_size=8),
)
def test_small_integer_inputs_3d_equal_brute_force(pts, radii):
    c = np.array(pts, dtype=float)
    if np.linalg.matrix_rank(c - c[0]) < 3:
        return
    r = np.array(radii[: len(pts)], dtype=float)
    T = regular_triangulation(Balls(c, r))
    assert {tuple(s) for s in T.tolist()} == brute_force_regular(c, r)


# ------------------------------------------------------------------ families
def fibonacci(n, R=3.0):
    i = np.arange(n) + 0.5
    phi = np.arccos(1 - 2 * i / n)
    th = np.pi * (1 + 5**0.5) * i
    return R * np.c_[np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)]


def polyhedra():
    g = (1 + 5**0.5) / 2
    cube = np.array(list(itertools.product([-1.0, 1.0], repeat=3)))
    octa = np.vstack([np.eye(3), -np.eye(3)])
    ico = np.array([p for s1 in (-1, 1) for s2 in (-1, 1) for p in ([0, s1, s2 * g], [s1, s2 * g, 0], [s2 * g, 0, s1])])
    dode = np.vstack(
        [
            cube,
            [[0, s1 / g, s2 * g] for s1 in (-1, 1) for s2 in (-1, 1)],
            [[s1 / g, s2 * g, 0] for s1 in (-1, 1) for s2 in (-1, 1)],
            [[s2 * g, 0, s1 / g] for s1 in (-1, 1) for s2 in (-1, 1)],
        ]
    )
    tetra = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1.0]])
    return {"tetra": tetra, "cube": cube, "octa": octa, "ico": ico, "dode": dode}


def grid(m, d):
    return np.stack(np.meshgrid(*[np.arange(float(m))] * d, indexing="ij"), -1).reshape(-1, d)


def families():
    rng = np.random.default_rng(2026)
    out = {}
    for n in (24, 70, 150, 300):
        out[f"cage{n}"] = Balls(fibonacci(n), 1.0)
        out[f"cage{n}-mixed"] = Balls(fibonacci(n), 0.8 + 0.4 * rng.random(n))
    for name, p in polyhedra().items():
        out[name] = Balls(p, 0.5)
        out[name + "+centre"] = Balls(np.vstack([p, [[0, 0, 0]]]), np.r_[np.full(len(p), 0.5), 0.2])
    for m, d in ((12, 2), (5, 3)):
        g = grid(m, d)
        out[f"grid{d}d"] = Balls(g, 0.3)
        out[f"grid{d}d-offset"] = Balls(g + 1e6, 0.3)
        out[f"grid{d}d-scaled"] = Balls(g * 1e-6, 0.3e-6)
        out[f"grid{d}d-weights"] = Balls(g, 0.2 + 0.2 * (np.arange(len(g)) % 3))
    t = 2 * np.pi * np.arange(16) / 16
    out["ring2d"] = Balls(np.c_[np.cos(t), np.sin(t)], 0.1)
    out["ring2d+centre"] = Balls(np.vstack([np.c_[np.cos(t), np.sin(t)], [[0, 0]]]), 0.1)
    out["rings3d"] = Balls(np.vstack([np.c_[np.cos(t), np.sin(t), np.full(16, z)] for z in (-1.0, 0.0, 1.0)]), 0.2)
    z = np.repeat(np.arange(6.0), 12)
    a = np.tile(2 * np.pi * np.arange(12) / 12, 6)
    out["cylinder"] = Balls(np.c_[2 * np.cos(a), 2 * np.sin(a), z], 0.5)
    dup = rng.random((40, 3))
    out["duplicates"] = Balls(
        np.vstack([dup, dup[:10], dup[:5]]), np.r_[np.full(40, 0.1), np.full(10, 0.1), np.full(5, 0.2)]
    )
    g = grid(5, 3)
    out["lattice-noise"] = Balls(g + 1e-12 * rng.standard_normal(g.shape), 0.3)
    g2 = grid(10, 2)
    out["lattice2d-noise"] = Balls(g2 + 1e-12 * rng.standard_normal(g2.shape), 0.3)
    big = rng.random((300, 3)) * 100
    out["tiny-in-large"] = Balls(big, np.r_[np.full(290, 1e-9), np.full(10, 5.0)])
    return out


FAMILIES = families()


@pytest.mark.parametrize("name", sorted(FAMILIES))
def test_degenerate_families_are_certified_and_tile_the_hull(name):
    balls = FAMILIES[name]
    T = regular_triangulation(balls)
    assert T.shape[1] == balls.dim + 1
    assert_certified(balls, T)
    assert_tiles_hull(balls, T)


@pytest.mark.parametrize("name", ["cage70", "grid3d", "grid2d", "ico", "lattice-noise"])
def test_same_triangulation_after_a_change_of_the_last_bits_is_still_certified(name):
    """The certificate holds on every ±1-ulp variant (what another CPU's trigonometry
    gives); co-spherical input is no longer decided by luck."""
    balls = FAMILIES[name]
    rng = np.random.default_rng(7)
    for _ in range(5):
        c = balls.centers.copy()
        c = np.nextafter(c, c + rng.choice([-1.0, 1.0], size=c.shape))
        b = Balls(c, balls.radii)
        T = regular_triangulation(b)
        assert_certified(b, T)
        assert_tiles_hull(b, T)


def test_grid_triangulation_is_the_same_under_offset_and_scale():
    """SoS breaks ties by the input order, so a grid, shifted by 1e6 or scaled by
    1e-6 (exact binary operations on small integers), keeps its triangulation."""
    g = grid(5, 3)
    T0 = regular_triangulation(Balls(g, 0.25))
    assert np.array_equal(T0, regular_triangulation(Balls(g + 2.0**20, 0.25)))
    assert np.array_equal(T0, regular_triangulation(Balls(g * 2.0**-20, 0.25 * 2.0**-20)))


def test_random_input_is_certified_without_the_fallback():
    rng = np.random.default_rng(1)
    b = Balls(rng.random((3000, 3)) * 20, rng.random(3000))
    rep = triangulation_report(b)
    assert rep.method == "qhull", rep.reason
    assert rep.counts["power_exact"] == 0
    b2 = Balls(rng.random((20000, 2)), rng.random(20000) * 0.004)
    assert triangulation_report(b2).method == "qhull"


def test_cage_falls_back_and_matches_gudhi_betti():
    gudhi = pytest.importorskip("gudhi")
    balls = FAMILIES["cage70"]
    F = alpha_filtration(balls)
    ac = gudhi.AlphaComplex(points=balls.centers, weights=balls.radii**2, precision="exact")
    st_ = ac.create_simplex_tree()
    st_.compute_persistence()
    from shapelab.topology import betti

    # strictly between critical values: both filtrations give the union's Betti numbers
    vals = np.unique(np.concatenate([F.values(k) for k in range(4)]))
    for tau in (-0.5, 0.0, 3.0, 7.9, 8.1):
        assert not np.any(np.isclose(vals, tau, atol=1e-6))
        theirs = list(st_.persistent_betti_numbers(tau, tau)) + [0, 0, 0]
        assert tuple(betti(F, tau))[:3] == tuple(theirs[:3])
        chi_g = sum((-1) ** (len(s) - 1) for s, v in st_.get_filtration() if v <= tau)
        chi_o = sum((-1) ** k * int(np.sum(F.values(k) <= tau)) for k in range(4))
        assert chi_o == chi_g


@pytest.mark.parametrize(
    "name", ["cage24", "cage150-mixed", "grid3d", "grid2d", "lattice-noise", "ico+centre", "cylinder", "duplicates"]
)
def test_euler_characteristic_matches_gudhi_between_critical_values(name):
    """χ(K(τ)) from our filtration equals GUDHI's exact alpha complex strictly between
    critical values (where both are the union's, whatever triangulation of ties)."""
    gudhi = pytest.importorskip("gudhi")
    balls = FAMILIES[name]
    F = alpha_filtration(balls)
    d = balls.dim
    ac = gudhi.AlphaComplex(points=balls.centers, weights=balls.radii**2, precision="exact")
    st_ = ac.create_simplex_tree()
    gv = np.array([v for _, v in st_.get_filtration()])
    gdim = np.array([len(s) - 1 for s, _ in st_.get_filtration()])
    ov = [F.values(k) for k in range(d + 1)]
    crit = np.unique(np.concatenate(ov + [gv]))
    mids = (crit[:-1] + crit[1:]) / 2
    gaps = crit[1:] - crit[:-1]
    mids = mids[gaps > 1e-6 * (1 + np.abs(mids))]
    for tau in mids[:: max(1, mids.size // 40)]:
        chi_o = sum((-1) ** k * int(np.sum(ov[k] <= tau)) for k in range(d + 1))
        chi_g = int(np.sum((-1) ** gdim[gv <= tau]))
        assert chi_o == chi_g, tau


@pytest.mark.parametrize("scale", [2.0**-500, 2.0**400])
def test_extreme_scales_give_the_same_triangulation_without_warnings(scale):
    """Squares of 1e-150 underflow and of 1e120 overflow in the float filter: those
    tests go exact, silently (RuntimeWarnings from shapelab are errors here)."""
    rng = np.random.default_rng(0)
    c, r = rng.random((200, 3)), rng.random(200) * 0.05
    T0 = regular_triangulation(Balls(c, r))
    b = Balls(c * scale, r * scale)
    assert np.array_equal(regular_triangulation(b), T0)
    F0, F = alpha_filtration(Balls(c, r)), alpha_filtration(b)
    np.testing.assert_allclose(F.values(3) / scale**2, F0.values(3), rtol=1e-9)


@pytest.mark.parametrize("name", ["grid2d", "grid2d-offset", "grid3d", "lattice2d-noise", "ring2d", "cage70"])
def test_power_diagram_vertices_of_slivers(name):
    """Rounded lattices have hull slivers (points collinear only up to round-off) that
    the exact triangulation keeps; their orthocentres are far away but finite, and
    every vertex has equal power to the balls of its simplex."""
    from shapelab import datasets, power_diagram, power_distance

    balls = FAMILIES[name]
    pd = power_diagram(balls)
    T = regular_triangulation(balls)
    assert np.all(np.isfinite(pd.vertices))
    for t, v in zip(T, pd.vertices):
        p = power_distance(v, Balls(balls.centers[t], balls.radii[t]))
        assert np.ptp(p) <= 1e-9 * (np.abs(p).max() + np.abs(v).max() ** 2 + 1.0)
    left = datasets.figure_23_2()[0]
    assert np.all(np.isfinite(power_diagram(left).vertices))
