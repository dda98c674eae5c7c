"""Tests of shapelab.cavities: voids, pockets, tunnels and their volumes.

Oracles:
* Betti numbers and persistence (the number of voids at τ is β_{d-1}(τ); every
  pocket is a void later on), themselves tested against GUDHI in test_topology;
* an exact area oracle in 2D written here independently (scan lines: the free length
  of each horizontal line is exact, integrated with adaptive quadrature between all
  event heights);
* closed forms: the hole of a ring of equal disks, the lifetimes of rings and keyholes;
* seeded Monte Carlo with a 5-sigma confidence bound;
* GF(2) ranks for tunnels (the representative cycle is a cycle, not a boundary at τ,
  a boundary at its death).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

import shapelab as sl
from shapelab import cavities as C
from shapelab.cavities import freespace as FS
from tests.library.test_topology import gf2_rank  # noqa: E402


# ----------------------------------------------------------------------------- helpers
def free_area_scanline(tri, centers, radii):
    """Area of triangle ``tri`` not covered by the disks: exact scan-line lengths,
    adaptive quadrature between every height where the integrand has a kink."""
    y0, y1 = tri[:, 1].min(), tri[:, 1].max()
    m = (centers[:, 1] - radii < y1) & (centers[:, 1] + radii > y0)
    c, r = centers[m], radii[m]
    brk = list(tri[:, 1]) + list(c[:, 1] - r) + list(c[:, 1] + r)
    for i in range(len(c)):
        for j in range(i + 1, len(c)):
            d = np.linalg.norm(c[j] - c[i])
            if 0 < d < r[i] + r[j] and d > abs(r[i] - r[j]):
                a = (r[i] ** 2 - r[j] ** 2 + d * d) / (2 * d)
                h = np.sqrt(max(r[i] ** 2 - a * a, 0.0))
                e = (c[j] - c[i]) / d
                pm = c[i] + a * e
                brk += [pm[1] + h * e[0], pm[1] - h * e[0]]
        for k in range(3):
            P, Q = tri[k], tri[(k + 1) % 3]
            D = Q - P
            f = P - c[i]
            A, B, Cc = D @ D, 2 * f @ D, f @ f - r[i] ** 2
            disc = B * B - 4 * A * Cc
            if disc >= 0:
                for s in (-1, 1):
                    t = (-B + s * np.sqrt(disc)) / (2 * A)
                    if 0 <= t <= 1:
                        brk.append(P[1] + t * D[1])
    pts = [y0] + sorted(b for b in set(brk) if y0 < b < y1) + [y1]

    def g(y):
        xs = []
        for k in range(3):
            P, Q = tri[k], tri[(k + 1) % 3]
            if (P[1] - y) * (Q[1] - y) <= 0 and P[1] != Q[1]:
                xs.append(P[0] + (y - P[1]) / (Q[1] - P[1]) * (Q[0] - P[0]))
        if len(xs) < 2:
            return 0.0
        a, b = min(xs), max(xs)
        iv = []
        for i in range(len(c)):
            h = r[i] ** 2 - (y - c[i, 1]) ** 2
            if h > 0:
                s = np.sqrt(h)
                lo, hi = max(a, c[i, 0] - s), min(b, c[i, 0] + s)
                if hi > lo:
                    iv.append((lo, hi))
        iv.sort()
        cov, cur = 0.0, None
        for lo, hi in iv:
            if cur is None or lo > cur[1]:
                if cur:
                    cov += cur[1] - cur[0]
                cur = [lo, hi]
            else:
                cur[1] = max(cur[1], hi)
        if cur:
            cov += cur[1] - cur[0]
        return (b - a) - cov

    return sum(quad(g, a, b, epsabs=1e-13, epsrel=1e-12, limit=200)[0] for a, b in zip(pts[:-1], pts[1:]) if b > a)


def monte_carlo_free(balls, tau, cells, n, seed):
    """Free measure of the cells (union of simplices) by uniform sampling: (estimate, sigma)."""
    rng = np.random.default_rng(seed)
    X = balls.centers[cells]
    d = balls.dim
    vol = np.abs(np.linalg.det(X[:, 1:] - X[:, :1])) / (2 if d == 2 else 6)
    total = vol.sum()
    which = rng.choice(len(cells), size=n, p=vol / total)
    lam = rng.dirichlet(np.ones(d + 1), size=n)
    x = np.einsum("nk,nkd->nd", lam, X[which])
    w = balls.weights + tau
    live = w >= 0
    free = np.ones(n, dtype=bool)
    for z, ww in zip(balls.centers[live], w[live]):
        free &= ((x - z) ** 2).sum(axis=1) > ww
    p = free.mean()
    return p * total, np.sqrt(p * (1 - p) / n) * total


def fibonacci_sphere(m, radius):
    i = np.arange(m) + 0.5
    phi = np.arccos(1 - 2 * i / m)
    th = np.pi * (1 + 5**0.5) * i
    return radius * np.c_[np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)]


def random_balls(seed, n, d, spread=4.0, rmax=0.8):
    rng = np.random.default_rng(seed)
    return sl.Balls(rng.uniform(0, spread, (n, d)), rng.uniform(0.1, rmax, n))


# --------------------------------------------------------------------------- voids
@pytest.mark.parametrize("d, seed", [(2, 0), (2, 1), (3, 2), (3, 3)])
def test_number_of_voids_is_the_betti_number(d, seed):
    balls = random_balls(seed, 90 if d == 2 else 70, d)
    F = sl.alpha_filtration(balls)
    P = F.persistence()[d - 1]
    for tau in (-0.2, 0.0, 0.15, 0.4, 1.0):
        vs = sl.voids(F, tau)
        assert len(vs) == F.betti(tau)[d - 1]
        # each void is one alive H_{d-1} pair
        got = sorted((v.born, v.dies) for v in vs)
        alive = sorted(map(tuple, P[(P[:, 0] <= tau) & (P[:, 1] > tau)]))
        assert np.allclose(got, alive) if got else not alive
        seen = set()
        for v in vs:
            assert v.tau == tau and v.born <= tau < v.dies
            assert np.all(F.values(d)[v.cell_ids] > tau)
            assert np.array_equal(F.simplices(d)[v.cell_ids], v.cells)
            assert not seen & set(v.cell_ids.tolist())
            seen |= set(v.cell_ids.tolist())
            assert set(v.lining.tolist()) <= set(v.cells.ravel().tolist())
        ps = [v.persistence for v in vs]
        assert ps == sorted(ps, reverse=True)


@pytest.mark.parametrize("d, seed", [(2, 5), (3, 5), (3, 9)])
def test_void_volume_equals_exact_power_cell_measure(d, seed):
    """The fast fractional inclusion–exclusion against the exact decomposition."""
    balls = (
        random_balls(seed, 60, d, spread=5.0, rmax=1.0)
        if d == 2
        else random_balls(seed, 70, d, spread=3.5, rmax=0.9)
        if seed == 5
        else random_balls(seed, 60, d, spread=4.0, rmax=1.0)
    )
    F = sl.alpha_filtration(balls)
    n = 0
    for tau in (0.0, 0.2):
        for v in sl.voids(F, tau)[:6]:
            exact = FS.free_measure(balls, tau, v.cells)
            X = balls.centers[v.cells]
            cellvol = np.abs(np.linalg.det(X[:, 1:] - X[:, :1])).sum() / (2 if d == 2 else 6)
            assert abs(v.volume - exact.sum()) <= 1e-9 * cellvol + 1e-7 * exact.sum()
            n += 1
    assert n >= 2


def ring(n, R, r, phase=0.0):
    t = 2 * np.pi * np.arange(n) / n + phase
    return sl.Balls(R * np.c_[np.cos(t), np.sin(t)], r)


@pytest.mark.parametrize("m", [70, 150, 300])
def test_cage_void_volume_against_a_monte_carlo_of_the_sphere(m):
    """Independent of the triangulation: the balls cover the sphere of radius 3 (every
    point of it is within 1 of a centre), so the void is the free space inside it.
    (Before the certified triangulation, m = 150 gave 44.65 here; the truth is 35.8.)"""
    from scipy.spatial import cKDTree

    c = fibonacci_sphere(m, 3.0)
    s = fibonacci_sphere(20_000, 3.0)
    assert cKDTree(c).query(s)[0].max() < 1.0  # the covering
    vs = sl.voids(sl.Balls(c, 1.0), 0.0)
    assert len(vs) == 1
    rng = np.random.default_rng(11)
    N = 1_000_000
    p = rng.normal(size=(N, 3))
    p *= (3.0 * rng.random(N) ** (1 / 3) / np.linalg.norm(p, axis=1))[:, None]
    frac = (cKDTree(c).query(p, k=1)[0] > 1.0).mean()
    vol = 4 / 3 * np.pi * 27
    assert abs(vs[0].volume - vol * frac) < 5 * vol * np.sqrt(frac * (1 - frac) / N)


def test_void_volume_monte_carlo_2d_random():
    balls = random_balls(11, 80, 2, spread=6.0, rmax=0.9)
    vs = sl.voids(balls, 0.1)
    assert len(vs) >= 1
    v = max(vs, key=lambda x: x.volume)
    est, sigma = monte_carlo_free(balls, 0.1, v.cells, 200_000, seed=2)
    assert abs(v.volume - est) < 5 * sigma


# ------------------------------------------------------------------------- pockets
def keyhole(n=24, R=5.0, r=1.0, gap=2):
    """A ring of disks with ``gap`` disks removed: a chamber with a narrow mouth."""
    t = 2 * np.pi * (np.arange(n - gap) + 0.5 * gap) / n + 0.01 * np.sin(np.arange(n - gap))
    return sl.Balls(R * np.c_[np.cos(t), np.sin(t)], r)


def test_keyhole_is_a_pocket_and_closes_when_the_mouth_disks_touch():
    balls = keyhole()
    F = sl.alpha_filtration(balls)
    assert len(sl.voids(F, 0.0)) == 0
    ps = sl.pockets(F, 0.0, min_persistence=1.0)
    assert len(ps) == 1
    p = ps[0]
    c = balls.centers
    mouth_gap = np.linalg.norm(c[0] - c[-1])
    assert p.closes_at == pytest.approx(mouth_gap**2 / 4 - 1.0, rel=1e-9)
    assert p.fills_at > 0.9 * (25 - 1) and p.fills_at <= 25 - 1 + 1e-9
    # the mouth at tau = 0 is the single hull edge across the gap
    assert p.mouth.shape == (1, 2) and sorted(p.mouth[0].tolist()) == [0, len(c) - 1]
    assert p.mouth_size == pytest.approx(mouth_gap)
    # it is the void it becomes
    v = [v for v in sl.voids(F, p.closes_at) if v.dies == p.fills_at]
    assert len(v) == 1 and np.array_equal(v[0].cell_ids, p.cell_ids)
    # volume: exact scan-line oracle, and Monte Carlo
    ref = sum(free_area_scanline(c[t], c, balls.radii) for t in p.cells)
    assert p.volume == pytest.approx(ref, rel=1e-9)
    est, sigma = monte_carlo_free(balls, 0.0, p.cells, 200_000, seed=3)
    assert abs(p.volume - est) < 5 * sigma
    # after the mouth closes it is a void, no longer a pocket
    assert sl.pockets(F, p.closes_at + 0.01, min_persistence=1.0) == ()


def test_shallow_dent_is_not_a_pocket():
    """Figure 23.2, right: a wide shallow dent fills from the bottom before its lips
    meet, so it never becomes a void."""
    n, R, r = 15, 5.0, 0.8
    t = np.linspace(-np.pi / 3, np.pi / 3, n) + 0.004 * np.sin(7 * np.arange(n))
    arc = R * np.c_[np.cos(t), np.sin(t)]
    balls = sl.Balls(arc, r)
    F = sl.alpha_filtration(balls)
    P = F.persistence()[1]
    assert not np.any(P[:, 1] - P[:, 0] > 0.5)  # no lasting hole ever
    assert sl.pockets(F, 0.0, min_persistence=0.5) == ()
    # while the keyhole (Figure 23.2, left) is one
    assert len(sl.pockets(keyhole(), 0.0, min_persistence=0.5)) == 1


def test_figure_23_2_dataset():
    from shapelab import datasets

    left, right = datasets.figure_23_2()
    big = lambda ps: [p for p in ps if p.persistence > 1.0]  # noqa: E731
    assert len(big(sl.pockets(left, 0.0))) == 1
    assert big(sl.pockets(right, 0.0)) == []


@pytest.mark.parametrize("d, seed", [(2, 21), (3, 22)])
def test_pockets_are_future_voids_open_at_tau(d, seed):
    balls = random_balls(seed, 80 if d == 2 else 60, d, rmax=0.7)
    F = sl.alpha_filtration(balls)
    tau = 0.0
    ps = sl.pockets(F, tau)
    assert ps, "the random input should have pockets"
    void_cells = set()
    for v in sl.voids(F, tau):
        void_cells |= set(v.cell_ids.tolist())
    fval = F.values(d - 1)
    for p in ps:
        assert tau < p.closes_at < p.fills_at
        assert not void_cells & set(p.cell_ids.tolist())  # open at tau
        later = {tuple(v.cell_ids): v for v in sl.voids(F, p.closes_at)}
        v = later[tuple(p.cell_ids)]  # closed at closes_at
        assert v.dies == p.fills_at and v.born == p.closes_at
        assert len(p.mouth_ids) >= 1
        assert np.all((fval[p.mouth_ids] > tau) & (fval[p.mouth_ids] <= p.closes_at))
        assert np.array_equal(F.simplices(d - 1)[p.mouth_ids], p.mouth)
    pers = [p.persistence for p in ps]
    assert pers == sorted(pers, reverse=True)
    # every H_{d-1} class born after tau is a pocket or lies inside a void at tau
    P = F.persistence()[d - 1]
    later = P[P[:, 0] > tau]
    assert len(later) >= len(ps)
    mp = np.median(pers)
    assert all(p.persistence >= mp for p in sl.pockets(F, tau, min_persistence=mp))
    assert len(sl.pockets(F, tau, min_persistence=mp)) == sum(x >= mp for x in pers)


def test_pocket_in_a_cage_with_a_hole_3d():
    c = fibonacci_sphere(60, 3.0)
    c = c[c[:, 2] < 3.0 * np.cos(np.radians(35))]  # cut a cap off: a mouth
    c = c + np.random.default_rng(1).normal(scale=0.02, size=c.shape)  # not co-spherical
    balls = sl.Balls(c, 1.0)
    F = sl.alpha_filtration(balls)
    assert len(sl.voids(F, 0.0)) == 0
    ps = sl.pockets(F, 0.0, min_persistence=2.0)
    assert len(ps) == 1
    p = ps[0]
    assert 0.0 < p.closes_at < 4.0 and p.fills_at > 6.0
    # the mouth is mostly at the cut (a tiny gap elsewhere in the shell may still be
    # open at tau = 0; it closes early)
    at_cut = balls.centers[p.mouth][..., 2].min(axis=1) > 1.0
    assert at_cut.mean() > 0.5
    assert np.all(F.values(2)[p.mouth_ids[~at_cut]] < 0.5)
    est, sigma = monte_carlo_free(balls, 0.0, p.cells, 100_000, seed=4)
    assert abs(p.volume - est) < 5 * sigma


# ------------------------------------------------------------------------- tunnels
def tube(rings=8, per_ring=10, R=2.5, r=1.0, dz=1.2):
    k = np.arange(per_ring)
    pts = []
    for j in range(rings):
        t = 2 * np.pi * (k + 0.5 * (j % 2)) / per_ring + 0.02 * j
        pts.append(np.c_[R * np.cos(t), R * np.sin(t), np.full(per_ring, j * dz)] + 0.01 * np.sin(k + j)[:, None])
    return sl.Balls(np.vstack(pts), r)


def winding_parity(cycle, centers):
    """Parity of the crossings of the half-plane {y = 0, x > 0} (odd: winds the z axis)."""
    a, b = centers[cycle[:, 0]], centers[cycle[:, 1]]
    crosses = (a[:, 1] > 0) != (b[:, 1] > 0)
    t = a[:, 1] / np.where(crosses, a[:, 1] - b[:, 1], 1.0)
    x = a[:, 0] + t * (b[:, 0] - a[:, 0])
    return int(np.sum(crosses & (x > 0))) % 2


def in_boundary_span(F, tau, edge_ids):
    """Is the chain of edges a boundary of triangles of K_tau (GF(2))?"""
    tri = np.flatnonzero(F.values(2) <= tau)
    n1 = len(F.values(1))
    M = np.zeros((n1, tri.size + 1), dtype=bool)
    b = F.boundary(2)[tri]
    for j in range(3):
        M[b[:, j], np.arange(tri.size)] = True
    M[edge_ids, -1] = True
    return gf2_rank(M) == gf2_rank(M[:, :-1])


def test_tube_has_one_tunnel_with_a_winding_cycle():
    balls = tube()
    F = sl.alpha_filtration(balls)
    tn = sl.tunnels(F, 0.0)
    assert len(tn) == F.betti(0.0)[1] == 1
    t = tn[0]
    assert t.birth <= 0.0 < t.death
    deg = np.bincount(t.cycle.ravel())
    assert np.all(deg % 2 == 0)  # a cycle
    assert np.all(F.values(1)[t.edge_ids] <= t.birth)  # present from its birth
    assert winding_parity(t.cycle, balls.centers) == 1  # it goes around the tube
    assert not in_boundary_span(F, 0.0, t.edge_ids)  # not a boundary at tau
    assert in_boundary_span(F, t.death, t.edge_ids)  # a boundary at its death


@pytest.mark.parametrize("seed", [31, 32])
def test_tunnels_and_grooves_match_persistence(seed):
    balls = random_balls(seed, 50, 3, spread=4.0, rmax=0.9)
    F = sl.alpha_filtration(balls)
    P = F.persistence()[1]
    for tau in (0.0, 0.3):
        tn = sl.tunnels(F, tau)
        assert len(tn) == F.betti(tau)[1]
        assert sorted((t.birth, t.death) for t in tn) == sorted(map(tuple, P[(P[:, 0] <= tau) & (P[:, 1] > tau)]))
        for t in tn[:4]:
            assert np.all(np.bincount(t.cycle.ravel()) % 2 == 0)
            assert not in_boundary_span(F, tau, t.edge_ids)
        gr = sl.cavities.grooves(F, tau)
        assert len(gr) == int(np.sum(P[:, 0] > tau))
        assert all(g.birth > tau for g in gr)


@pytest.mark.parametrize("offset", [0.0, 1e6])
@pytest.mark.parametrize("dim, n, r", [(2, 5, 0.6), (3, 4, 0.75)])
def test_grids_through_our_filtration(dim, n, r, offset):
    """Integer grids, every square (cube) co-circular (co-spherical), through shapelab's own
    alpha_filtration.  Counts from the geometry: neighbours overlap (r > 1/2); in 2D with
    r < sqrt(2)/2 each unit square keeps its centre free, a hole; in 3D with
    sqrt(2)/2 < r < sqrt(3)/2 every face is covered but each cube's centre is not, a void."""
    g = np.stack(np.meshgrid(*[np.arange(n, dtype=float)] * dim, indexing="ij"), -1).reshape(-1, dim)
    balls = sl.Balls(g + offset, r)
    cells = (n - 1) ** dim
    vs = sl.voids(balls, 0.0)
    assert len(vs) == cells
    assert sl.alpha_filtration(balls).betti(0.0) == ((1, cells, 0) if dim == 2 else (1, 0, cells, 0))
    if dim == 3:
        assert sl.tunnels(balls, 0.0) == ()
    # all cells are congruent: the same free measure, and the centre of each is free
    vols = np.array([v.volume for v in vs])
    np.testing.assert_allclose(vols, vols[0], rtol=1e-9)


def test_flat_ring_through_our_filtration():
    """Twelve balls on a circle in the plane z = 0 (all centres coplanar and cocircular):
    no void, one tunnel that winds around the axis."""
    t = 2 * np.pi * np.arange(12) / 12
    flat = sl.Balls(np.c_[3 * np.cos(t), 3 * np.sin(t), np.zeros(12)], 1.0)
    assert sl.voids(flat, 0.0) == () and sl.pockets(flat, 0.0) == ()
    tn = sl.tunnels(flat, 0.0)
    assert len(tn) == 1 and winding_parity(tn[0].cycle, flat.centers) == 1


def test_results_are_frozen():
    v = C.voids(ring(8, 3.0, 1.2), 0.0)[0]
    with pytest.raises(AttributeError):
        v.volume = 0.0
    with pytest.raises(ValueError):
        v.cells[0, 0] = 1
    assert "Void(" in repr(v)


# ----------------------------------------------------------------------- bad input
def test_bad_input_errors():
    balls = ring(8, 3.0, 1.2)
    with pytest.raises(TypeError, match="Balls"):
        sl.voids(np.zeros((3, 2)))
    with pytest.raises(TypeError, match="balls"):
        sl.pockets(None)
    with pytest.raises(ValueError, match="tau"):
        sl.voids(balls, float("nan"))
    with pytest.raises(TypeError, match="tau"):
        sl.voids(balls, True)
    with pytest.raises(TypeError, match="tau"):
        sl.pockets(balls, "0")
    with pytest.raises(ValueError, match="min_persistence"):
        sl.pockets(balls, 0.0, min_persistence=-1.0)
    with pytest.raises(ValueError, match="2D"):
        sl.tunnels(balls)
    with pytest.raises(TypeError, match="Filtration"):
        sl.voids(object(), 0.0)


def test_infinite_growth_times_are_the_ends_of_the_filtration():
    """One τ rule (``_toolkit.validate.as_tau``): ±inf are accepted everywhere τ is."""
    F = sl.alpha_filtration(ring(8, 3.0, 1.2))
    assert sl.voids(F, float("inf")) == sl.voids(F, -np.inf) == ()
    assert sl.pockets(F, np.inf) == ()
    # before any ball exists there is no union to dent: a pocket is lined by a ball at tau
    assert sl.pockets(F, -np.inf) == ()
    (p,) = sl.pockets(F, float(np.min(F.values(0))))  # the first balls: the hole, lined
    assert p.lining.size > 0 and p.volume > 0
    C60 = sl.alpha_filtration(sl.datasets.fullerene_c60())
    assert sl.tunnels(C60, np.inf) == sl.tunnels(C60, -np.inf) == ()
    assert FS.free_measure(F.balls, np.inf, F.simplices(2)).sum() == 0.0


@pytest.mark.parametrize("fn", [sl.voids, sl.pockets, sl.tunnels, C.grooves])
def test_one_input_rule(fn):
    """Balls or a Filtration alike (issue 22): the balls' filtration is built once and
    kept with them, so a second call on the same balls reuses it."""
    balls = sl.datasets.fullerene_c60()
    F = sl.alpha_filtration(balls)
    with pytest.raises(TypeError, match="filtration"):
        fn(balls, 0.0, filtration=F)  # the old keyword: Python's own TypeError
    assert [repr(x) for x in fn(balls, 0.0)] == [repr(x) for x in fn(F, 0.0)]
    from shapelab.filtration import as_filtration

    G = as_filtration(balls, "test")
    fn(balls, 0.0)
    assert as_filtration(balls, "test") is G and G is not F

    with pytest.raises(ValueError, match="cells"):
        FS.free_measure(balls, 0.0, [[0, 1]])
    with pytest.raises(ValueError, match="cells"):
        FS.free_measure(balls, 0.0, [[0, 1, 99]])
    # the filtration or the balls
    F = sl.alpha_filtration(balls)
    assert len(sl.voids(F, 0.0)) == len(sl.voids(balls, 0.0)) == 1


def test_channel_profile_of_stacked_rings_has_the_closed_form_bottleneck():
    """Rings of n unit balls on circles of radius R about the z axis, at heights z_k: by
    symmetry the best centre in a slice is on the axis, where the free radius is the closed
    form min_k sqrt(R_k^2 + (z - z_k)^2) - 1; the narrowest ring is the bottleneck."""
    import shapelab as sl

    n, rows = 12, []
    for z, R in ((0.0, 3.0), (1.5, 2.5), (3.0, 3.0)):
        t = 2 * np.pi * np.arange(n) / n
        rows.append(np.column_stack([R * np.cos(t), R * np.sin(t), np.full(n, z)]))
    balls = sl.Balls(np.vstack(rows), 1.0)
    prof = sl.channel_profile(balls, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.5, 3.0])
    rings = ((0.0, 3.0), (1.5, 2.5), (3.0, 3.0))
    expected = [min(np.hypot(R, z - zk) - 1.0 for zk, R in rings) for z in (0.0, 1.5, 3.0)]
    assert prof.radius == pytest.approx(expected, abs=1e-6)
    assert prof.bottleneck == pytest.approx(1.5, abs=1e-6)
    assert np.allclose(prof.centers[:, :2], 0.0, atol=1e-3)
    with pytest.raises(ValueError, match="direction"):
        sl.channel_profile(balls, [0, 0, 0], [0, 0, 0], [0.0])
    with pytest.raises(TypeError, match="balls"):
        sl.channel_profile(np.zeros((3, 3)), [0, 0, 0], [0, 0, 1], [0.0])


def test_voids_pockets_and_tunnels_share_the_cavity_protocol():
    """One protocol (issue 22): born/dies/persistence agree with each kind's own fields
    and with the persistence pairs; lining is the alive vertices of the cells."""
    F = sl.alpha_filtration(sl.datasets.globule())
    h1 = F.persistence()[1]
    b, d = h1[np.argmax(h1[:, 1] - h1[:, 0])]  # inside the longest H1 pair: a tunnel is alive
    found = [*sl.voids(F, 0.0), *sl.pockets(F, 0.0), *sl.tunnels(F, 0.5 * (b + d))]
    kinds = {type(c).__name__ for c in found}
    assert kinds == {"Void", "Pocket", "Tunnel"}, kinds
    pairs = F.persistence()
    for c in found:
        assert isinstance(c, sl.Cavity)
        assert c.persistence == pytest.approx(c.dies - c.born)
        assert c.born <= c.dies
        assert set(np.unique(c.cells).tolist()) >= set(np.asarray(c.lining).tolist())
        k = 1 if isinstance(c, C.Tunnel) else F.balls.dim - 1
        assert any(np.isclose(b, c.born) and np.isclose(d, c.dies) for b, d in pairs[k]), (c, k)
    t = next(c for c in found if isinstance(c, C.Tunnel))
    assert t.born == t.birth and t.dies == t.death and t.cells is t.cycle and t.cell_ids is t.edge_ids
    p = next(c for c in found if isinstance(c, C.Pocket))
    assert p.born == p.closes_at and p.dies == p.fills_at
    # the discrete flow's pockets are cavities too (issue 23): a pair of the growth model, or
    # persistence 0 for a region no part of which is ever sealed off
    flow = sl.flow_pockets(F, 0.0)
    assert flow
    for q in flow:
        assert isinstance(q, sl.Cavity) and q.born <= q.dies
        assert q.persistence == 0 or any(np.isclose(b, q.born) and np.isclose(d, q.dies) for b, d in pairs[2]), q
