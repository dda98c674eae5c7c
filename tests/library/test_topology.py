"""Tests of shapelab.topology: Betti numbers and persistence of the α-filtration.

Oracles:
* GUDHI's weighted alpha complex and its persistence (peer library), both through a
  small adapter that exposes a GUDHI simplex tree with the Filtration accessors (so
  the algorithms are tested independently of shapelab's own filtration) and against
  ``shapelab.alpha_filtration``;
* Betti numbers by brute-force ranks of boundary matrices over GF(2);
* the Euler–Poincaré formula χ = Σ(-1)^k β_k at every τ;
* closed forms for synthetic shapes (a ring of disks, a cage of balls).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shapelab as sl
from shapelab import topology as T


def same_diagram(a, b, tol=1e-9):
    """Equal as multisets of (birth, death) pairs, up to ``tol`` (relative to scale)."""
    a = np.asarray(a, float).reshape(-1, 2)
    b = np.asarray(b, float).reshape(-1, 2)
    if a.shape != b.shape:
        return False
    if a.size == 0:
        return True
    a = a[np.lexsort((a[:, 1], a[:, 0]))]
    b = b[np.lexsort((b[:, 1], b[:, 0]))]
    if not np.array_equal(np.isinf(a), np.isinf(b)):
        return False
    fin = np.isfinite(a)
    scale = max(1.0, float(np.max(np.abs(a[fin]))) if fin.any() else 1.0)
    return bool(np.all(np.abs(a[fin] - b[fin]) <= tol * scale))


def drop_short(P, tol):
    P = np.asarray(P, float).reshape(-1, 2)
    return P[~(P[:, 1] - P[:, 0] <= tol)]


def gf2_rank(M: np.ndarray) -> int:
    M = M.copy().astype(bool)
    r = 0
    rows, cols = M.shape
    for c in range(cols):
        piv = np.flatnonzero(M[r:, c])
        if piv.size == 0:
            continue
        p = r + piv[0]
        M[[r, p]] = M[[p, r]]
        below = np.flatnonzero(M[:, c])
        below = below[below != r]
        M[below] ^= M[r]
        r += 1
        if r == rows:
            break
    return r


def brute_betti(F, tau):
    """Betti numbers of K_tau from GF(2) ranks of its boundary matrices."""
    k = F.dimension
    keep = [np.flatnonzero(np.asarray(F.values(j)) <= tau) for j in range(k + 1)]
    ranks = [0] * (k + 2)
    for j in range(1, k + 1):
        rows = keep[j - 1]
        cols = keep[j]
        pos = -np.ones(len(F.values(j - 1)), dtype=np.int64)
        pos[rows] = np.arange(rows.size)
        M = np.zeros((rows.size, cols.size), dtype=bool)
        if cols.size:
            b = np.asarray(F.boundary(j))[cols]
            assert np.all(pos[b] >= 0), "a face enters after its coface"
            for c in range(b.shape[1]):
                M[pos[b[:, c]], np.arange(cols.size)] = True
        ranks[j] = gf2_rank(M) if M.size else 0
    return tuple(keep[j].size - ranks[j] - ranks[j + 1] for j in range(k + 1))


def random_balls(rng, n, d, spread=4.0, rmax=0.8):
    return rng.uniform(0, spread, (n, d)), rng.uniform(0.0, rmax, n)


def all_taus(F):
    v = np.unique(np.concatenate([np.asarray(F.values(k)) for k in range(F.dimension + 1)]))
    mids = (v[1:] + v[:-1]) / 2
    return np.sort(np.concatenate([[v[0] - 1.0], v, mids, [v[-1] + 1.0]]))


points_2d = st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6)), min_size=3, max_size=16, unique=True)


# --------------------------------------------------------------------- Betti numbers
@pytest.mark.parametrize("d, seed", [(2, 3), (3, 4)])
def test_betti_matches_gf2_ranks_and_euler(d, seed):
    rng = np.random.default_rng(seed)
    p, r = random_balls(rng, 30 if d == 3 else 40, d, spread=3.0)
    F = sl.alpha_filtration(sl.Balls(p, r))
    taus = all_taus(F)
    B = F.betti_curve(taus)
    assert B.shape == (taus.size, d + 1) and B.dtype.kind == "i"
    chi = T.euler_characteristic_curve(F, taus)
    assert np.array_equal(chi, (B * (-1) ** np.arange(d + 1)).sum(axis=1))
    for t in taus[:: max(1, taus.size // 25)]:
        assert F.betti(t) == brute_betti(F, t)
        assert tuple(B[np.searchsorted(taus, t)]) == F.betti(t)


def test_betti_counts_the_alive_persistence_intervals():
    rng = np.random.default_rng(7)
    p, r = random_balls(rng, 120, 3, spread=5.0)
    F = sl.alpha_filtration(sl.Balls(p, r))
    P = F.persistence()
    taus = all_taus(F)
    B = F.betti_curve(taus)
    for k in range(4):
        I = P[k]
        alive = ((I[:, 0][None] <= taus[:, None]) & (I[:, 1][None] > taus[:, None])).sum(axis=1)
        assert np.array_equal(alive, B[:, k]), f"beta_{k}"


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 10**6), n=st.integers(4, 30), d=st.sampled_from([2, 3]))
def test_betti_euler_characteristic_random(seed, n, d):
    rng = np.random.default_rng(seed)
    p, r = random_balls(rng, n, d, spread=2.5)
    F = sl.alpha_filtration(sl.Balls(p, r))
    taus = all_taus(F)
    B = F.betti_curve(taus)
    chi = T.euler_characteristic_curve(F, taus)
    assert np.array_equal(chi, (B * (-1) ** np.arange(d + 1)).sum(axis=1))
    assert np.all(B >= 0)
    # before everything: empty; after everything: a point (DT is contractible)
    assert tuple(B[0]) == (0,) * (d + 1)
    assert tuple(B[-1]) == (1,) + (0,) * d


def test_ring_of_disks_has_one_hole_with_closed_form_lifetime():
    n, R, rad = 16, 4.0, 1.0
    t = 2 * np.pi * (np.arange(n) + 0.1 * np.sin(np.arange(n))) / n  # co-circular, uneven gaps
    c = R * np.c_[np.cos(t), np.sin(t)]
    F = sl.alpha_filtration(sl.Balls(c, rad))
    assert F.betti(0.0) == (1, 1, 0)
    P = F.persistence()
    # all centres are co-circular: every triangle enters at R^2 - r^2 up to round-off
    # (GUDHI too), and the round-off pairs are dropped
    tri = F.values(2)
    assert np.ptp(tri[tri < 100]) > 0 and np.ptp(tri[tri < 100]) < 1e-12 * 15
    big = P[1][np.argmax(P[1][:, 1] - P[1][:, 0])]
    # born when the most distant neighbours touch: (max gap / 2)^2 - r^2 (Gabriel edges);
    # dies when the centre region is covered: the largest circumradius^2 - r^2 <= R^2 - r^2
    gaps = np.linalg.norm(c - np.roll(c, -1, axis=0), axis=1)
    assert big[0] == pytest.approx((gaps.max() / 2) ** 2 - rad**2, rel=1e-9)
    assert big[1] <= R**2 - rad**2 + 1e-9 and big[1] > 0.9 * (R**2 - rad**2)
    assert len(P[1]) == 1


def test_cage_of_balls_has_one_void():
    # Fibonacci points on a sphere of radius 3, balls of radius 1: one void (beta_2 = 1)
    m = 80
    i = np.arange(m) + 0.5
    phi = np.arccos(1 - 2 * i / m)
    th = np.pi * (1 + 5**0.5) * i
    c = 3 * np.c_[np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)]
    F = sl.alpha_filtration(sl.Balls(c, 1.0))
    assert F.betti(0.0) == (1, 0, 1, 0)
    P = F.persistence()
    alive = P[2][(P[2][:, 0] <= 0) & (P[2][:, 1] > 0)]
    assert len(alive) == 1
    # the centres are co-spherical: every tetrahedron has the sphere's centre as its
    # orthocentre, so the void is filled at 3^2 - 1 = 8 exactly (up to round-off);
    # late in the growth it may pinch into pieces, which all die then too
    assert np.allclose(P[2][:, 1], 8.0, rtol=1e-9)


def test_tiny_inputs_and_huge_offsets():
    one = sl.alpha_filtration(sl.Balls([[0.0, 0.0, 0.0]], 1.0))
    assert one.betti(0.0) == (1, 0, 0, 0)
    assert one.betti(-5.0) == (0, 0, 0, 0)
    P = one.persistence()
    assert np.array_equal(P[0], [[-1.0, np.inf]])
    two = sl.alpha_filtration(sl.Balls([[0.0, 0.0], [3.0, 0.0]], 1.0))
    assert two.betti(0.0) == (2, 0, 0) and two.betti(1.25) == (1, 0, 0)
    rng = np.random.default_rng(5)
    p, r = random_balls(rng, 40, 3)
    P0 = sl.alpha_filtration(sl.Balls(p, r)).persistence()
    P1 = sl.alpha_filtration(sl.Balls(p + 1e6, r)).persistence()
    for k in range(4):
        a, b = drop_short(P0[k], 1e-6), drop_short(P1[k], 1e-6)
        assert a.shape == b.shape
        assert np.allclose(np.sort(a, axis=0), np.sort(b, axis=0), atol=1e-5)


def test_results_are_cached_and_read_only():
    rng = np.random.default_rng(8)
    F = sl.alpha_filtration(sl.Balls(*random_balls(rng, 30, 3)))
    P1, P2 = F.persistence(), F.persistence()
    assert P1[1] is P2[1]
    with pytest.raises(ValueError):
        P1[1][0, 0] = 0.0
    assert F.betti(0.3) == T.betti(F, 0.3)


# ----------------------------------------------------------------------- bad input
def test_bad_input_errors():
    F = sl.alpha_filtration(sl.Balls([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], 0.2))
    with pytest.raises(TypeError, match="tau"):
        T.betti(F, "zero")
    with pytest.raises(ValueError, match="tau"):
        T.betti(F, float("nan"))
    with pytest.raises(TypeError, match="Filtration"):
        T.betti(np.zeros(3), 0.0)
    with pytest.raises(TypeError, match="Filtration"):
        T.persistence("not a filtration")
    with pytest.raises(ValueError, match="taus"):
        T.betti_curve(F, [[0.0, 1.0]])
    with pytest.raises(ValueError, match="taus"):
        T.betti_curve(F, 0.5)
    with pytest.raises(ValueError, match="taus"):
        T.betti_curve(F, [0.0, np.nan])
    # infinite times are fine: everything or nothing
    assert T.betti(F, np.inf) == (1, 0, 0)
    assert T.betti(F, -np.inf) == (0, 0, 0)


def test_field_changes_nothing_but_h1_and_betti_numbers_never():
    """H0 and H2 are the same in every field (components; voids by Alexander duality)."""
    from .._oracles import random_balls

    F = sl.alpha_filtration(random_balls(150, 3, seed=7))
    P2, P3 = F.persistence(), F.persistence(field=3)
    for k in (0, 2, 3):
        np.testing.assert_array_equal(P2[k], P3[k])
    # the default is Z/2, and one field's pairs are kept apart from another's
    assert F.persistence(field=2) is not P3 and np.array_equal(F.persistence(field=2)[1], P2[1])


@pytest.mark.parametrize("bad", [4, 1, 0, -3, 2**31 + 11])
def test_field_must_be_a_prime(bad):
    F = sl.alpha_filtration(sl.Balls([[0.0, 0, 0], [1, 0, 0]], 0.5))
    with pytest.raises(ValueError, match="field must be a prime"):
        F.persistence(field=bad)


@pytest.mark.parametrize("bad", [2.0, True, "2", None])
def test_field_must_be_an_integer(bad):
    F = sl.alpha_filtration(sl.Balls([[0.0, 0, 0], [1, 0, 0]], 0.5))
    with pytest.raises(TypeError, match="field must be a prime"):
        T.persistence(F, field=bad)
