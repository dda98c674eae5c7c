"""shapelab.freespace: exact free area against a scan-line oracle (more checks of the
free space through Void.volume and Pocket.volume live in test_cavities.py)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import shapelab as sl
from shapelab._engine import freespace as FSE
from shapelab.cavities import freespace as FS
from tests.library.test_cavities import free_area_scanline, random_balls


def test_free_measure_matches_scanline_oracle_2d():
    balls = random_balls(9, 30, 2, spread=4.0, rmax=1.0)
    F = sl.alpha_filtration(balls)
    rng = np.random.default_rng(0)
    cells = F.simplices(2)[F.values(2) > 0.0]
    cells = cells[rng.choice(len(cells), size=min(6, len(cells)), replace=False)]
    # plus two arbitrary (non-Delaunay) triangles
    cells = np.vstack([cells, [[0, 5, 9], [3, 17, 22]]])
    for tau in (0.3,):
        got = FS.free_measure(balls, tau, cells)
        ref = [free_area_scanline(balls.centers[c], balls.centers, np.sqrt(balls.weights + tau)) for c in cells]
        assert np.allclose(got, ref, rtol=1e-9, atol=1e-11)
        assert np.any(np.asarray(ref) > 1e-3)


def test_free_points_lie_in_the_cells_and_outside_every_grown_ball():
    balls = random_balls(3, 25, 2, spread=4.0, rmax=1.0)
    F = sl.alpha_filtration(balls)
    cells = F.simplices(2)[-10:]  # the last to fill: free space left at tau = 0
    tau = 0.0
    pts = FS.free_points(balls, tau, cells, 2000, np.random.default_rng(0))
    assert pts.shape[1] == 2 and len(pts) > 0
    assert np.all(sl.power_distance(pts, balls).min(axis=1) > tau)
    # inside some cell: barycentric coordinates all >= 0 (up to round-off)
    X = balls.centers[cells]
    inside = np.zeros(len(pts), bool)
    for T in X:
        lam = np.linalg.solve(np.vstack([T.T, np.ones(3)]), np.vstack([pts.T, np.ones(len(pts))]))
        inside |= np.all(lam >= -1e-12, axis=0)
    assert inside.all()


# ------------------------------------------------------------------ closed forms
def _solid_angles(T):
    """Solid angle of a tetrahedron at each vertex (Van Oosterom & Strackee)."""
    out = []
    for j in range(4):
        a, b, c = (T[i] - T[j] for i in range(4) if i != j)
        la, lb, lc = (np.linalg.norm(x) for x in (a, b, c))
        num = abs(np.dot(a, np.cross(b, c)))
        den = la * lb * lc + np.dot(a, b) * lc + np.dot(a, c) * lb + np.dot(b, c) * la
        out.append(2 * np.arctan2(num, den))
    return np.array(out)


@pytest.mark.parametrize("offset", [0.0, 1e6])
def test_ball_inside_a_cell_and_balls_at_its_corners_closed_form(offset):
    # a ball of radius r inside the cell and small balls at its corners: the free
    # volume is the cell minus the ball minus the corner sectors (solid angle / 4π of
    # each corner ball), and the wall their spheres' parts
    T = np.array([[0.0, 0.0, 0.0], [9.0, 0.0, 0.0], [1.0, 8.0, 0.0], [2.0, 2.0, 7.0]])
    inner = T.mean(axis=0)
    r, eps = 1.0, 0.3
    balls = sl.Balls(np.vstack([T, inner]) + offset, np.array([eps] * 4 + [r]))
    fs = FS.free_space(balls, 0.0, np.array([[0, 1, 2, 3]]))
    vol = abs(np.linalg.det(T[1:] - T[0])) / 6
    om = _solid_angles(T)
    want = vol - 4 / 3 * np.pi * r**3 - (om / (4 * np.pi) * 4 / 3 * np.pi * eps**3).sum()
    wall = 4 * np.pi * r**2 + (om / (4 * np.pi) * 4 * np.pi * eps**2).sum()
    tol = 1e-12 if offset == 0 else 1e-7  # 1e6 offsets cost the last digits of the input
    assert fs.measure[0] == pytest.approx(want, rel=tol)
    assert fs.wall[0] == pytest.approx(wall, rel=tol)
    # split by ball: the inner sphere whole, each corner its solid-angle fraction
    per = dict(zip(fs.contact_ball.tolist(), fs.contact_wall.tolist()))
    assert per[4] == pytest.approx(4 * np.pi * r**2, rel=tol)
    for j in range(4):
        assert per[j] == pytest.approx(om[j] * eps**2, rel=max(tol, 1e-9))


def test_free_area_closed_form():
    # three disjoint balls at the corners of a triangle: free area = T - πr²/2, rim = πr
    X = np.array([[0.0, 0.0, 0.0], [6.0, 0.0, 0.0], [1.0, 5.0, 0.0]])
    T = 0.5 * 6.0 * 5.0
    fa = FS.free_area(sl.Balls(X, 1.0), 0.0, np.array([[0, 1, 2]]))
    assert fa.measure[0] == pytest.approx(T - np.pi / 2, rel=1e-12)
    assert fa.wall[0] == pytest.approx(np.pi, rel=1e-12)
    # a fourth ball cutting the plane at height 0.6 with radius 1: a disk of radius 0.8
    b4 = sl.Balls(np.vstack([X, [2.5, 1.5, 0.6]]), 1.0)
    fa = FS.free_area(b4, 0.0, np.array([[0, 1, 2]]))
    assert fa.measure[0] == pytest.approx(T - np.pi / 2 - np.pi * 0.64, rel=1e-12)
    assert fa.wall[0] == pytest.approx(np.pi + 2 * np.pi * 0.8, rel=1e-12)
    assert fa.contact_ball.tolist() == [0, 1, 2, 3]


def test_free_area_is_the_free_space_of_the_section_in_its_plane():
    # triangles in a tilted plane against the 2D free space of the sections, built by hand
    rng = np.random.default_rng(5)
    balls = sl.Balls(rng.uniform(0, 6, (40, 3)), rng.uniform(0.4, 1.3, 40))
    tris = np.array([[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11]])
    fa = FS.free_area(balls, 0.2, tris)
    for m, t in enumerate(tris):
        X = balls.centers[t]
        n = np.cross(X[1] - X[0], X[2] - X[0])
        n /= np.linalg.norm(n)
        e1 = (X[1] - X[0]) / np.linalg.norm(X[1] - X[0])
        E = np.stack([e1, np.cross(n, e1)], axis=1)
        h = (balls.centers - X[0]) @ n
        rho2 = balls.weights + 0.2 - h * h
        cut = np.flatnonzero(rho2 > 0)
        sec = sl.Balls((balls.centers[cut] - X[0]) @ E, np.sqrt(rho2[cut]))
        loc = [int(np.flatnonzero(cut == i)[0]) for i in t]
        ref = FS.free_space(sec, 0.0, np.array([loc]))
        assert fa.measure[m] == pytest.approx(ref.measure[0], rel=1e-10, abs=1e-10)
        assert fa.wall[m] == pytest.approx(ref.wall[0], rel=1e-10, abs=1e-10)


# ------------------------------------------------ the filtration's planes, or all
def _same(a, b, tol=1e-9):
    assert np.allclose(a.measure, b.measure, rtol=tol, atol=tol)
    assert np.allclose(a.wall, b.wall, rtol=tol, atol=tol)
    ka = {(c, i): w for c, i, w in zip(a.contact_cell.tolist(), a.contact_ball.tolist(), a.contact_wall) if w > tol}
    kb = {(c, i): w for c, i, w in zip(b.contact_cell.tolist(), b.contact_ball.tolist(), b.contact_wall) if w > tol}
    assert ka.keys() == kb.keys()
    assert all(abs(ka[k] - kb[k]) <= tol * max(1.0, ka[k]) for k in ka)


@settings(max_examples=40, deadline=None)
@given(
    d=st.sampled_from([2, 3]),
    seed=st.integers(0, 2**31 - 1),
    grid=st.booleans(),
    tau=st.sampled_from([-0.1, 0.0, 0.3, 1.0]),
)
def test_free_space_from_the_filtration_equals_from_the_balls(d, seed, grid, tau):
    """The filtration's edges in K_τ are all the planes the exact measure needs
    (duality); the balls alone give every overlapping pair.  Both must agree, on
    random balls and on grids (co-circular, co-spherical, equal radii)."""
    rng = np.random.default_rng(seed)
    if grid:
        k = 4 if d == 3 else 6
        X = np.stack(np.meshgrid(*[np.arange(k, dtype=float)] * d, indexing="ij"), -1).reshape(-1, d)
        balls = sl.Balls(X, 0.6)
    else:
        balls = sl.Balls(rng.uniform(0, 4, (40, d)), rng.uniform(0.2, 0.9, 40))
    F = sl.alpha_filtration(balls)
    cells = np.asarray(F.simplices(d))
    cells = cells[rng.choice(len(cells), size=min(60, len(cells)), replace=False)]
    a, b = FS.free_space(F, tau, cells), FS.free_space(balls, tau, cells)
    _same(a, b)
    assert np.all(a.measure >= -1e-9)
    if d == 3:
        tris = np.asarray(F.simplices(2))[:50]
        _same(FS.free_area(F, tau, tris), FS.free_area(balls, tau, tris))


@pytest.mark.parametrize("d", [2, 3])
def test_identical_balls_count_once(d):
    # a duplicated ball (same centre, same radius) and one hidden inside another
    # change nothing: the union is the same set
    rng = np.random.default_rng(1)
    base = sl.Balls(rng.uniform(0, 3, (25, d)), rng.uniform(0.4, 0.9, 25))
    cells = np.asarray(sl.alpha_filtration(base).simplices(d))
    X = np.vstack([base.centers, base.centers[[3, 7]]])
    R = np.concatenate([base.radii, [base.radii[3], 0.5 * base.radii[7]]])
    got = FS.free_space(sl.Balls(X, R), 0.0, cells)
    ref = FS.free_space(base, 0.0, cells)
    assert np.allclose(got.measure, ref.measure, rtol=1e-12, atol=1e-12)
    assert np.allclose(got.wall, ref.wall, rtol=1e-12, atol=1e-12)
    assert not np.isin([25, 26], got.contact_ball).any()  # the tie goes to the first, the hidden ball has no wall


def test_void_walls_and_volumes_of_a_real_protein():
    """All 33 voids of 1FMO (2792 atoms, probe 1.4): the exact power-cell measure
    equals the fractional inclusion–exclusion of ``Void.volume`` (an independent
    formula, exact over a void's cells), and every void's wall is positive."""
    s = sl.datasets.structure("1fmo", probe=1.4)
    F = sl.alpha_filtration(s.balls)
    vs = sl.voids(F, 0.0)
    assert len(vs) >= 20
    cells = np.concatenate([v.cells for v in vs])
    fs = FS.free_space(F, 0.0, cells)
    at = np.cumsum([0] + [len(v.cells) for v in vs])
    for k, v in enumerate(vs):
        assert fs.measure[at[k] : at[k + 1]].sum() == pytest.approx(v.volume, rel=1e-9, abs=1e-9)
        assert fs.wall[at[k] : at[k + 1]].sum() > 0


def test_free_area_bad_input():
    b3 = sl.Balls(np.eye(3), 1.0)
    with pytest.raises(ValueError, match="3D"):
        FS.free_area(sl.Balls(np.eye(2), 1.0), 0.0, [[0, 1, 0]])
    with pytest.raises(ValueError, match="triangles"):
        FS.free_area(b3, 0.0, [[0, 1]])
    with pytest.raises(ValueError, match="triangles"):
        FS.free_area(b3, 0.0, [[0, 1, 5]])
    with pytest.raises(TypeError, match="free_space"):
        FS.free_space("balls", 0.0, [[0, 1, 2]])
    # a flat triangle has no area
    assert FS.free_area(sl.Balls(np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]), 0.1), 0.0, [[0, 1, 2]]).measure[0] == 0


def test_pairs_held_a_slice_at_a_time_give_the_same_measure(monkeypatch):
    # the candidate planes are generated for a slice of (cell, ball) pairs at a time
    rng = np.random.default_rng(11)
    balls = sl.Balls(rng.uniform(0, 5, (60, 3)), rng.uniform(0.5, 1.4, 60))
    F = sl.alpha_filtration(balls)
    cells, tris = np.asarray(F.simplices(3))[:80], np.asarray(F.simplices(2))[:80]
    whole = FS.free_space(F, 0.1, cells), FS.free_area(F, 0.1, tris), FS.free_space(balls, 0.1, cells)
    monkeypatch.setattr(FSE, "_PAIRS", 7)
    sliced = FS.free_space(F, 0.1, cells), FS.free_area(F, 0.1, tris), FS.free_space(balls, 0.1, cells)
    for a, b in zip(whole, sliced):
        assert np.array_equal(a.measure, b.measure) and np.array_equal(a.wall, b.wall)
        assert np.array_equal(a.contact_ball, b.contact_ball) and np.array_equal(a.contact_wall, b.contact_wall)


def test_cells_gathered_a_block_at_a_time_give_the_same_measure(monkeypatch):
    # the candidate balls of the cells are gathered for a block of cells at a time
    rng = np.random.default_rng(12)
    balls = sl.Balls(rng.uniform(0, 5, (60, 3)), rng.uniform(0.5, 1.4, 60))
    F = sl.alpha_filtration(balls)
    cells, tris = np.asarray(F.simplices(3))[:80], np.asarray(F.simplices(2))[:80]
    whole = FS.free_space(F, 0.1, cells), FS.free_area(F, 0.1, tris), FS.free_space(balls, 0.1, cells)
    monkeypatch.setattr(FSE, "_CELLS", 3)
    blocks = FS.free_space(F, 0.1, cells), FS.free_area(F, 0.1, tris), FS.free_space(balls, 0.1, cells)
    for a, b in zip(whole, blocks):
        assert np.array_equal(a.measure, b.measure) and np.array_equal(a.wall, b.wall)
        assert np.array_equal(a.contact_cell, b.contact_cell) and np.array_equal(a.contact_ball, b.contact_ball)
        assert np.array_equal(a.contact_wall, b.contact_wall)


def test_slices_in_threads_give_the_same_bits(monkeypatch):
    # the slices of (cell, ball) pairs run in threads (SHAPELAB_THREADS, default: the
    # CPUs): each slice is computed as alone, so any thread count gives the same bits
    rng = np.random.default_rng(13)
    balls = sl.Balls(rng.uniform(0, 5, (60, 3)), rng.uniform(0.5, 1.4, 60))
    F = sl.alpha_filtration(balls)
    cells, tris = np.asarray(F.simplices(3))[:80], np.asarray(F.simplices(2))[:80]
    monkeypatch.setattr(FSE, "_PAIRS", 5)  # many slices
    runs = []
    for threads in ("1", "3"):
        monkeypatch.setenv("SHAPELAB_THREADS", threads)
        runs.append((FS.free_space(F, 0.1, cells), FS.free_area(F, 0.1, tris), FS.free_space(balls, 0.1, cells)))
    assert FSE._threads(100) == 3 and FSE._threads(2) == 2  # threads were used, capped by the slices
    for a, b in zip(*runs):
        assert np.array_equal(a.measure, b.measure) and np.array_equal(a.wall, b.wall)
        assert np.array_equal(a.contact_cell, b.contact_cell) and np.array_equal(a.contact_ball, b.contact_ball)
        assert np.array_equal(a.contact_wall, b.contact_wall)


@pytest.mark.parametrize("value", ["0", "-2", "two"])
def test_bad_thread_count_is_named(monkeypatch, value):
    monkeypatch.setenv("SHAPELAB_THREADS", value)
    with pytest.raises(ValueError, match="SHAPELAB_THREADS"):
        FSE._threads(4)


def test_no_threads_inside_a_worker_thread(monkeypatch):
    import threading

    monkeypatch.setenv("SHAPELAB_THREADS", "4")
    seen = []
    t = threading.Thread(target=lambda: seen.append(FSE._threads(10)))
    t.start()
    t.join()
    assert seen == [1] and FSE._threads(10) == 4


_SPECIAL = [0.0, -0.0, np.nan, np.inf, -np.inf, 5e-324, -5e-324, 2.2e-308, 1e308, -1e308, 1.0, -1.0, 1e-160, 0.1]


@settings(max_examples=150, deadline=None)
@given(
    n=st.integers(0, 40),
    d=st.integers(1, 12),
    layout=st.sampled_from(["C", "F", "strided"]),
    seed=st.integers(0, 2**32 - 1),
    special=st.booleans(),
)
def test_row_dot_is_numpys_row_sum_bit_for_bit(n, d, layout, seed, special):
    # _dot claims the bits of (a * b).sum(1): signed zeros, NaN, inf, subnormals,
    # any layout; from 8 columns on NumPy sums pairwise (it used to differ there, and
    # it failed on one column)
    rng = np.random.default_rng(seed)
    if special:
        a = np.array(_SPECIAL)[rng.integers(0, len(_SPECIAL), (n, 2 * d))]
        b = np.array(_SPECIAL)[rng.integers(0, len(_SPECIAL), (n, 2 * d))]
    else:
        a = rng.normal(size=(n, 2 * d)) * 10.0 ** rng.integers(-8, 8, (n, 2 * d))
        b = rng.normal(size=(n, 2 * d))
    if layout == "strided":
        a, b = a[:, ::2], b[:, ::2]
    else:
        a, b = a[:, :d], b[:, :d]
        if layout == "F":
            a, b = np.asfortranarray(a), np.asfortranarray(b)
    with np.errstate(all="ignore"):
        got, ref = FSE._dot(a, b), (a * b).sum(1)
    assert got.shape == ref.shape
    assert np.array_equal(np.isnan(got), np.isnan(ref))
    ok = ~np.isnan(ref)
    assert np.array_equal(got[ok].view(np.int64), ref[ok].view(np.int64))  # the bits, -0.0 included


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(8, 30),
    kind=st.sampled_from(["random", "grid", "duplicates", "rounded"]),
    tau=st.sampled_from([0.0, 0.3]),
)
def test_thread_counts_give_the_same_bits_on_random_and_degenerate_input(monkeypatch, seed, n, kind, tau):
    rng = np.random.default_rng(seed)
    if kind == "grid":  # lattice points, equal radii: many cospherical sets
        x = rng.choice(np.stack(np.meshgrid(*[np.arange(4.0)] * 3), -1).reshape(-1, 3), n, replace=False)
        r = np.full(n, 0.8)
    else:
        x = rng.uniform(0, 5, (n, 3))
        r = rng.uniform(0.5, 1.4, n)
        if kind == "duplicates":
            x[n // 2 :] = x[: n - n // 2]
        elif kind == "rounded":
            x = np.round(x, 1)
    balls = sl.Balls(x, r)
    F = sl.alpha_filtration(balls)
    cells, tris = np.asarray(F.simplices(3)), np.asarray(F.simplices(2))
    monkeypatch.setattr(FSE, "_PAIRS", 7)  # many slices
    runs = []
    for threads in ("1", "2", "7"):
        monkeypatch.setenv("SHAPELAB_THREADS", threads)
        runs.append((FS.free_space(F, tau, cells), FS.free_area(F, tau, tris), FS.free_space(balls, tau, cells)))
    for a, *others in zip(*runs):
        for b in others:
            for f in ("measure", "wall", "contact_cell", "contact_ball", "contact_wall"):
                assert np.asarray(getattr(a, f)).tobytes() == np.asarray(getattr(b, f)).tobytes()


def test_an_error_in_a_thread_reaches_the_caller(monkeypatch):
    rng = np.random.default_rng(5)
    balls = sl.Balls(rng.uniform(0, 5, (40, 3)), rng.uniform(0.5, 1.4, 40))
    F = sl.alpha_filtration(balls)
    cells = np.asarray(F.simplices(3))
    monkeypatch.setattr(FSE, "_PAIRS", 5)
    monkeypatch.setenv("SHAPELAB_THREADS", "3")
    real, calls = FSE._measure_pairs, []

    def flaky(*args):
        calls.append(1)
        if len(calls) == 4:
            raise FloatingPointError("slice 4")
        return real(*args)

    monkeypatch.setattr(FSE, "_measure_pairs", flaky)
    with pytest.raises(FloatingPointError, match="slice 4"):
        FS.free_space(F, 0.0, cells)
    # the slices not yet started are dropped, not computed before the error is raised
    started, total = len(calls), []
    monkeypatch.setattr(FSE, "_measure_pairs", lambda *a: total.append(1) or real(*a))
    FS.free_space(F, 0.0, cells)
    assert started < len(total) - 10


@pytest.mark.parametrize("value", ["100000000", " 2 "])
def test_huge_or_padded_thread_counts_are_capped_by_the_slices(monkeypatch, value):
    monkeypatch.setenv("SHAPELAB_THREADS", value)
    assert FSE._threads(3) == min(3, int(value))


@pytest.mark.parametrize("module", ["shapelab.tools.batch", "shapelab.tools.trajectory"])
def test_worker_processes_use_one_thread_unless_told(monkeypatch, module):
    # batch and trajectory workers already share out the CPUs: a thread pool in each
    # would oversubscribe them; an explicit SHAPELAB_THREADS is kept
    import importlib
    import os

    init = importlib.import_module(module)._init_worker
    monkeypatch.delenv("SHAPELAB_THREADS", raising=False)
    init()
    assert os.environ["SHAPELAB_THREADS"] == "1" and FSE._threads(10) == 1
    monkeypatch.setenv("SHAPELAB_THREADS", "2")
    init()
    assert os.environ["SHAPELAB_THREADS"] == "2"


def test_default_threads_are_capped_on_many_core_machines(monkeypatch):
    # memory grows with the threads (one slice's temporaries each): without SHAPELAB_THREADS
    # a 64-CPU machine gets the cap, a 2-CPU machine its 2, and the variable may ask for more
    import os

    monkeypatch.delenv("SHAPELAB_THREADS", raising=False)
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(64)), raising=False)
    assert FSE._threads(1000) == FSE._DEFAULT_THREADS_CAP == 4
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    assert FSE._threads(1000) == 2
    monkeypatch.setenv("SHAPELAB_THREADS", "16")
    assert FSE._threads(1000) == 16
