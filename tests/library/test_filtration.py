"""Tests of shapelab.filtration: the weighted α-filtration and the dual complex.

Oracles:

* GUDHI's weighted ``AlphaComplex`` (a peer library with exact predicates): same
  simplices, same values (1e-9 relative) on inputs in general position;
* the definition of the dual complex itself: the entry time of a set R of balls is
  the least common power distance over the face of the power diagram dual to R,
  computed here by brute force (enumerating active constraint sets of a tiny
  quadratic program, no triangulation involved);
* invariants (faces before cofaces, monotone values, DT tiles the hull, Euler
  characteristic) and, on degenerate input where DT is not unique, the Euler
  characteristic and the number of components of K(τ) at every critical τ, which do
  not depend on the triangulation chosen (K(τ) has the homotopy type of the union).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import ConvexHull

from shapelab import Balls, alpha_filtration, dual_complex, regular_triangulation
from shapelab.filtration import Complex, Filtration


# ----------------------------------------------------------------------------------
# helpers
# ----------------------------------------------------------------------------------
def random_balls(seed, n, d, rmax, spread=1.0):
    rng = np.random.default_rng(seed)
    return Balls(rng.uniform(0, spread, (n, d)), rng.uniform(0, rmax, n))


def as_dict(F):
    out = {}
    for k in range(F.dimension + 1):
        for s, v in zip(F.simplices(k).tolist(), F.values(k).tolist()):
            out[tuple(s)] = v
    return out


def assert_valid(F):
    """Faces present with value <= coface value, rows ascending, values sorted."""
    assert isinstance(F, (Filtration, Complex))
    for k in range(F.dimension + 1):
        S, v = F.simplices(k), F.values(k)
        assert S.shape == (v.size, k + 1) and S.dtype == np.int32
        assert np.all(np.isfinite(v))
        assert np.all(np.diff(v) >= 0)
        assert np.all(np.diff(S, axis=1) > 0)
        assert np.unique(S, axis=0).shape[0] == S.shape[0]
        if k >= 1:
            B = F.boundary(k)
            fa = F.simplices(k - 1)
            assert B.shape == S.shape
            assert B.min(initial=0) >= 0 and B.max(initial=-1) < fa.shape[0]
            for j in range(k + 1):
                np.testing.assert_array_equal(fa[B[:, j]], np.delete(S, j, axis=1))
            assert np.all(F.values(k - 1)[B].max(axis=1) <= v)


def critical_taus(*value_sets):
    vals = np.unique(np.concatenate([np.asarray(v, float) for v in value_sets]))
    eps = 1e-7 * max(1.0, float(np.abs(vals).max()))
    return np.concatenate([vals - eps, vals + eps])


def euler_and_b0_ours(F, tau):
    K = F.complex_at(tau)
    return K.euler_characteristic(), components(
        K.simplices(0)[:, 0], K.simplices(1) if K.dimension >= 1 else np.zeros((0, 2), int)
    )


def components(verts, edges):
    if verts.size == 0:
        return 0
    idx = {v: i for i, v in enumerate(verts.tolist())}
    e = np.array([[idx[a], idx[b]] for a, b in edges.tolist()], dtype=int).reshape(-1, 2)
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(verts.size, verts.size))
    return connected_components(g, directed=False)[0]


def euler_and_b0_gudhi(simplices, tau):
    present = [s for s, f in simplices if f <= tau]
    chi = sum((-1) ** (len(s) - 1) for s in present)
    verts = np.array(sorted(s[0] for s in present if len(s) == 1), dtype=int)
    edges = np.array([s for s in present if len(s) == 2], dtype=int).reshape(-1, 2)
    return chi, components(verts, edges)


# ----------------------------------------------------------------------------------
# The definition: entry time of R = min common power over the dual power face
# ----------------------------------------------------------------------------------
def entry_time_brute_force(balls, R):
    """min over {x : pi_i(x) equal for i in R, pi_i(x) <= pi_k(x) for all k} of the
    common power, by enumerating active sets of the tiny QP (inf if infeasible)."""
    z, w = balls.centers, balls.weights
    c0 = z.mean(axis=0)
    z = z - c0  # better conditioning; power distances do not change
    i0 = R[0]
    h = np.einsum("ij,ij->i", z, z) - w
    # rows: 2 x.(z_k - z_i0) <= h_k - h_i0
    M = 2.0 * (z - z[i0])
    m = h - h[i0]
    eq = [k for k in R[1:]]
    ineq = [k for k in range(len(balls)) if k not in R]
    d = z.shape[1]
    best = np.inf
    target = z[i0]
    scale = 1.0 + float(np.abs(z).max()) ** 2
    for size in range(0, d + 1):
        for S in itertools.combinations(ineq, size):
            rows = eq + list(S)
            if rows:
                A, b = M[rows], m[rows]
                # project target onto {A x = b}
                lam, *_ = np.linalg.lstsq(A @ A.T, A @ target - b, rcond=1e-12)
                x = target - A.T @ lam
                if np.max(np.abs(A @ x - b)) > 1e-9 * scale:
                    continue
            else:
                x = target
            if ineq and np.max(M[ineq] @ x - m[ineq]) > 1e-9 * scale:
                continue
            best = min(best, float(np.sum((x - z[i0]) ** 2) - w[i0]))
    return best


@pytest.mark.parametrize("d,n", [(2, 8), (3, 7)])
@pytest.mark.parametrize("seed", [3, 4, 5])
def test_entry_times_from_the_definition(d, n, seed):
    rng = np.random.default_rng(seed)
    balls = Balls(rng.uniform(0, 1, (n, d)), rng.uniform(0, 0.4, n))
    ours = as_dict(alpha_filtration(balls))
    for size in range(1, d + 2):
        for R in itertools.combinations(range(n), size):
            t = entry_time_brute_force(balls, list(R))
            if np.isinf(t):
                assert R not in ours, R
            else:
                assert R in ours, R
                assert ours[R] == pytest.approx(t, rel=1e-7, abs=1e-9), R


@pytest.mark.parametrize("seed", [11, 12])
def test_dual_complex_is_the_nerve(seed):
    """K(0) is the nerve of the clipped cells B_i ∩ Π(B_i)."""
    rng = np.random.default_rng(seed)
    balls = Balls(rng.uniform(0, 1, (8, 2)), rng.uniform(0.05, 0.3, 8))
    K = dual_complex(balls)
    present = {tuple(s) for k in range(K.dimension + 1) for s in K.simplices(k).tolist()}
    for size in (1, 2, 3):
        for R in itertools.combinations(range(8), size):
            t = entry_time_brute_force(balls, list(R))
            if abs(t) < 1e-6:
                continue  # too close to call
            assert (R in present) == (t < 0), R


# ----------------------------------------------------------------------------------
# Invariants
# ----------------------------------------------------------------------------------
@pytest.mark.parametrize("d", [2, 3])
def test_invariants(d):
    balls = random_balls(21, 150, d, 0.08)
    F = alpha_filtration(balls)
    assert_valid(F)
    assert len(F) == sum(F.simplices(k).shape[0] for k in range(d + 1))
    assert F.dimension == d
    # complex_at(inf) is the whole DT, its top simplices tile the convex hull
    K = F.complex_at(np.inf)
    assert len(K) == len(F) and K.dimension == d
    top = {tuple(s) for s in K.simplices(d).tolist()}
    assert top == {tuple(s) for s in regular_triangulation(balls).tolist()}
    c = balls.centers
    T = K.simplices(d)
    vol = np.abs(np.linalg.det(c[T[:, 1:]] - c[T[:, :1]])).sum() / (2 if d == 2 else 6)
    assert vol == pytest.approx(ConvexHull(c).volume, rel=1e-10)
    assert K.euler_characteristic() == 1
    # complex_at is monotone and the filtration starts empty
    assert len(F.complex_at(-np.inf)) == 0
    sizes = [len(F.complex_at(t)) for t in np.linspace(-0.01, 0.05, 7)]
    assert sizes == sorted(sizes)
    # dual_complex is complex_at(0)
    K0, K0b = dual_complex(balls), F.complex_at(0.0)
    for k in range(d + 1):
        np.testing.assert_array_equal(K0.simplices(k), K0b.simplices(k))
        assert np.all(K0.values(k) <= 0)
    assert_valid(K0)


def test_ties_broken_deterministically_and_faces_first():
    g = np.array(list(itertools.product(range(4), repeat=2)), float)
    F = alpha_filtration(Balls(g, 0.0))
    for k in range(3):
        S, v = F.simplices(k), F.values(k)
        keys = np.lexsort(list(S.T[::-1]) + [v])
        np.testing.assert_array_equal(keys, np.arange(v.size))
    F2 = alpha_filtration(Balls(g, 0.0))
    for k in range(3):
        np.testing.assert_array_equal(F.simplices(k), F2.simplices(k))


def test_translation_and_scaling():
    balls = random_balls(5, 50, 3, 0.2)
    F = alpha_filtration(balls)
    s = 1e-3
    Fs = alpha_filtration(Balls(balls.centers * s + 1e4 * s, balls.radii * s))
    for k in range(4):
        np.testing.assert_array_equal(F.simplices(k), Fs.simplices(k))
        np.testing.assert_allclose(Fs.values(k), F.values(k) * s**2, rtol=1e-7, atol=1e-12 * s**2)


def test_growth_model_consistency():
    """K(tau) of the balls equals K(0) of the balls grown by tau."""
    balls = random_balls(8, 40, 2, 0.1)
    F = alpha_filtration(balls)
    for tau in (0.001, 0.004, 0.02):
        K = F.complex_at(tau)
        K2 = dual_complex(balls.grow(tau))
        for k in range(3):
            np.testing.assert_array_equal(K.simplices(k), K2.simplices(k))


def test_arrays_are_read_only_and_accessors_validate():
    F = alpha_filtration(random_balls(1, 20, 2, 0.1))
    with pytest.raises(ValueError):
        F.values(0)[0] = 1.0
    with pytest.raises(ValueError, match="k must be between 0 and 2"):
        F.simplices(3)
    with pytest.raises(ValueError, match="k must be >= 1"):
        F.boundary(0)
    with pytest.raises(TypeError, match="k must be an integer"):
        F.values(1.5)
    with pytest.raises(ValueError, match="tau must not be NaN"):
        F.complex_at(np.nan)
    with pytest.raises(TypeError, match="tau"):
        F.complex_at("0")
    with pytest.raises(TypeError, match="balls must be a shapelab.Balls"):
        alpha_filtration(np.zeros((3, 2)))


def test_topology_methods_forward(monkeypatch):
    import shapelab._engine.persistence as topo  # the engine the methods call

    F = alpha_filtration(random_balls(1, 10, 2, 0.1))
    calls = []
    monkeypatch.setattr(topo, "betti", lambda f, t: calls.append(("b", f, t)) or (1, 0, 0))
    monkeypatch.setattr(topo, "betti_curve", lambda f, ts: calls.append(("c", f, ts)) or "curve")
    monkeypatch.setattr(topo, "persistence", lambda f, field=2: calls.append(("p", f)) or {})
    assert F.betti(0.5) == (1, 0, 0)
    assert F.betti_curve([0, 1]) == "curve"
    assert F.persistence() == {}
    assert [c[0] for c in calls] == ["b", "c", "p"] and all(c[1] is F for c in calls)


# ----------------------------------------------------------------------------------
# Degenerate input
# ----------------------------------------------------------------------------------
GRID2 = np.array(list(itertools.product(range(5), repeat=2)), float)
GRID3 = np.array(list(itertools.product(range(4), repeat=3)), float)


def test_empty_balls():
    F = alpha_filtration(Balls(np.zeros((0, 3)), []))
    assert len(F) == 0 and F.dimension == -1
    assert F.simplices(2).shape == (0, 3)
    assert F.complex_at(0.0).euler_characteristic() == 0


# ------------------------------------------------------------------ values near zero
def _exact_orthosphere_power(centers, weights):
    """The power of the smallest orthogonal sphere of one simplex, in exact rational
    arithmetic on the given float64 inputs: solve 2 (z_i - z_0) . c = |z_i|^2 - w_i -
    |z_0|^2 + w_0 for the centre c in the simplex's span, return |c - z_0|^2 - w_0."""
    from fractions import Fraction as Q

    z = [[Q(float(v)) for v in row] for row in centers]
    w = [Q(float(v)) for v in weights]
    a = [[zi[t] - z[0][t] for t in range(len(z[0]))] for zi in z[1:]]
    b = [(sum(v * v for v in zi) - w[i + 1] - sum(v * v for v in z[0]) + w[0]) / 2 for i, zi in enumerate(z[1:])]
    # c - z0 = sum_j lam_j a_j with Gram system G lam = b - a . z0
    rhs = [b[i] - sum(a[i][t] * z[0][t] for t in range(len(z[0]))) for i in range(len(a))]
    G = [[sum(p * q for p, q in zip(ai, aj)) for aj in a] for ai in a]
    n = len(G)
    for col in range(n):  # Gauss-Jordan, exact
        piv = next(r for r in range(col, n) if G[r][col] != 0)
        G[col], G[piv], rhs[col], rhs[piv] = G[piv], G[col], rhs[piv], rhs[col]
        for r in range(n):
            if r != col and G[r][col] != 0:
                f = G[r][col] / G[col][col]
                G[r] = [x - f * y for x, y in zip(G[r], G[col])]
                rhs[r] -= f * rhs[col]
    lam = [rhs[i] / G[i][i] for i in range(n)]
    u = [sum(lam[j] * a[j][t] for j in range(n)) for t in range(len(z[0]))]
    return float(sum(v * v for v in u) - w[0])


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("delta", [1e-6, 1e-7, 1e-8])
def test_values_that_cancel_to_near_zero_are_still_exact(dim, delta):
    """Equal balls on a regular simplex (circumradius R) with r^2 = R^2 (1 - delta): the top
    simplex enters at tau = R^2 - r^2, about delta R^2, a difference of two nearly equal
    numbers.  Plain float64 loses ~eps/delta of it; the value must match the exact
    rational answer for the same float64 inputs to 1e-9 relative, at an offset of 1e3."""
    if dim == 2:
        unit = np.array([[np.cos(t), np.sin(t)] for t in 2 * np.pi * np.arange(3) / 3 + 0.3])
    else:
        unit = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=float) / np.sqrt(3)
    rng = np.random.default_rng(int(-np.log10(delta)) + 10 * dim)
    R = rng.uniform(1.0, 2.0)
    centers = 1e3 + R * unit
    radii = np.full(dim + 1, R * np.sqrt(1.0 - delta))
    F = alpha_filtration(Balls(centers, radii))
    (top,) = F.values(dim)
    exact = _exact_orthosphere_power(centers, radii**2)
    assert 0 < exact < 10 * delta * R**2
    assert top == pytest.approx(exact, rel=1e-9, abs=0)


# ------------------------------------------------- nearly flat simplices (issue 10)
# A simplex with a tiny relative determinant gets its own orthosphere, computed in
# exact arithmetic where the floating-point error bound cannot certify it.  Oracles:
# GUDHI's exact AlphaComplex (same float64 inputs, weights = balls.weights) and the
# closed form below, in Fractions.
def _cramer_orthosphere(centers, weights):
    """Power and barycentric coordinates of the orthocentre of a full-dimensional
    simplex (d + 1 points in R^d), exactly: Cramer's rule on the d x d system
    2 (z_i - z_0) . c = |z_i - z_0|^2 - w_i + w_0 for the offset c of the orthocentre
    from z_0, then rho = |c|^2 - w_0, and the barycentric coordinates of z_0 + c by
    Cramer's rule on the edge matrix (sum_i lam_i (z_i - z_0) = c)."""
    from fractions import Fraction as Q

    z = [[Q(float(v)) for v in row] for row in centers]
    w = [Q(float(v)) for v in weights]
    d = len(z[0])
    E = [[z[i][t] - z[0][t] for t in range(d)] for i in range(1, d + 1)]

    def det(M):
        if len(M) == 2:
            return M[0][0] * M[1][1] - M[0][1] * M[1][0]
        return (
            M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
            - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
            + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
        )

    rhs = [(sum(e * e for e in E[i]) - w[i + 1] + w[0]) / 2 for i in range(d)]
    D = det(E)
    assert D != 0
    c = []
    for t in range(d):  # replace column t of E by rhs
        c.append(det([[rhs[i] if s == t else E[i][s] for s in range(d)] for i in range(d)]) / D)
    rho = sum(v * v for v in c) - w[0]
    ET = [[E[i][t] for i in range(d)] for t in range(d)]  # columns are the edges
    lam = [det([[c[r] if s == i else ET[r][s] for s in range(d)] for r in range(d)]) / D for i in range(d)]
    return rho, [1 - sum(lam)] + lam


def _relative_det(P):
    A = P[1:] - P[0]
    return abs(np.linalg.det(A)) / np.prod(np.linalg.norm(A, axis=1))


def _sliver(h, seed=0):
    """A unit square (cocircular) moved by ~h out of its plane and ~0.1 h in it, and an
    apex on either side: the square's four points form a nearly flat tetrahedron with
    a finite orthosphere (its centre is at height O(1)), in the triangulation."""
    rng = np.random.default_rng(seed)
    P = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    P[:, 2] += rng.uniform(-h, h, 4)
    P[:, :2] += rng.uniform(-0.1 * h, 0.1 * h, (4, 2))
    return np.r_[P, [[0.5, 0.5, 1.0], [0.5, 0.5, -1.0]]]


def test_certificate_of_the_floating_point_orthospheres():
    """The error bound of the vectorised path: every row it accepts is within _RTOL of
    the exact value and has the exact attachment; rows it rejects are recomputed.
    Random tetrahedra and triangles whose flatness (relative determinant 1 .. 1e-16)
    and power (near 0 against the weights) vary over many orders of magnitude."""
    from fractions import Fraction as Q

    from shapelab._engine.orthospheres import _RTOL, _orthospheres

    rng = np.random.default_rng(123)
    rows, ws = [], []
    for _ in range(400):
        d = int(rng.integers(2, 4))
        P = rng.uniform(-1, 1, (d + 1, d))
        flat = 10.0 ** -rng.uniform(0, 16)
        P[-1] = P[:-1].mean(axis=0) + flat * (P[-1] - P[:-1].mean(axis=0))
        w = rng.uniform(0, 1, d + 1)
        if rng.uniform() < 0.5:  # shift the weights so that rho ~ 10^-k (cancellation)
            rho, _ = _cramer_orthosphere(P, w)
            w = w + (float(rho) - 10.0 ** -rng.uniform(0, 16))
        rows.append(P)
        ws.append(w)
    accepted = 0
    for d in (2, 3):
        sel = [i for i, P in enumerate(rows) if P.shape[1] == d]
        x = np.concatenate([rows[i] for i in sel])
        w = np.concatenate([ws[i] for i in sel])
        S = np.arange(x.shape[0]).reshape(-1, d + 1)
        rho, att, bad = _orthospheres(x, w, S)
        for t in range(S.shape[0]):
            if bad[t]:
                continue
            accepted += 1
            exact, lam = _cramer_orthosphere(x[S[t]], w[S[t]])
            assert abs(Q(float(rho[t])) - exact) <= Q(_RTOL) * abs(exact), t
            assert att[t].tolist() == [v < 0 for v in lam], t
    assert 50 < accepted < 350  # both branches are exercised
