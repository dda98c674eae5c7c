"""shapelab.homology: closed forms (sphere, torus, projective plane, wedges of circles),
Euler–Poincaré on random complexes, the rank mod 2 against a brute force over GF(2),
and agreement with the α-filtration's Betti numbers."""

from __future__ import annotations

from itertools import combinations, product

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shapelab as sl
from shapelab import homology as H

TORUS = sl.closure([t for i in range(7) for t in ((i, (i + 1) % 7, (i + 3) % 7), (i, (i + 2) % 7, (i + 3) % 7))])
RP2 = sl.closure(
    [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5), (0, 1, 5), (1, 2, 4), (2, 3, 5), (1, 3, 4), (2, 4, 5), (1, 3, 5)]
)


def sphere(d):
    """The boundary of the (d+1)-simplex: the d-sphere."""
    return [s for k in range(1, d + 2) for s in combinations(range(d + 2), k)]


def wedge_of_circles(n):
    """n triangles' boundaries sharing vertex 0."""
    return sl.closure([e for i in range(n) for e in ((0, 2 * i + 1), (2 * i + 1, 2 * i + 2), (0, 2 * i + 2))])


@pytest.mark.parametrize("d", [1, 2, 3, 4])
def test_spheres(d):
    assert H.betti_numbers(sphere(d)) == (1, *([0] * (d - 1)), 1)
    assert H.euler_characteristic(sphere(d)) == 1 + (-1) ** d


def test_filled_simplex_is_contractible():
    for d in range(5):
        K = sl.closure([tuple(range(d + 1))])
        assert H.betti_numbers(K) == (1, *([0] * d))
        assert H.euler_characteristic(K) == 1


def test_torus_and_projective_plane():
    assert H.betti_numbers(TORUS) == (1, 2, 1)
    assert H.euler_characteristic(TORUS) == 0
    # Z/2: the projective plane has a 2-cycle (the sum of all triangles) and a loop that bounds twice
    assert H.betti_numbers(RP2) == (1, 1, 1)
    assert H.euler_characteristic(RP2) == 1
    assert H.is_cycle([s for s in RP2 if len(s) == 3])


@pytest.mark.parametrize("n", [1, 2, 5])
def test_wedge_of_circles(n):
    K = wedge_of_circles(n)
    assert H.betti_numbers(K) == (1, n)
    assert H.euler_characteristic(K) == 1 - n


def test_boundary_boundary_is_zero():
    for K in (TORUS, RP2, sphere(3)):
        for k in range(2, 4):
            assert not ((H.boundary_matrix(K, k - 1) @ H.boundary_matrix(K, k)) % 2).any()


def test_boundary_matrix_shapes_and_order():
    K = sl.closure([(0, 1, 2)])
    assert H.boundary_matrix(K, 0).shape == (0, 3)
    assert H.boundary_matrix(K, 3).shape == (1, 0)
    M = H.boundary_matrix(K, 2)
    assert M.ravel().tolist() == [1, 1, 1]
    rows, cols = H.k_simplices(K, 0), H.k_simplices(K, 1)
    D = H.boundary_matrix(K, 1)
    for j, e in enumerate(cols):
        assert {rows[i] for i in np.flatnonzero(D[:, j])} == {(v,) for v in e}


def test_cycles_and_boundaries_annulus_and_torus():
    annulus = sl.closure([(0, 1, 3), (1, 3, 4), (1, 2, 4), (2, 4, 5), (0, 2, 5), (0, 3, 5)])
    inner, outer = [(3, 4), (4, 5), (3, 5)], [(0, 1), (1, 2), (0, 2)]
    assert H.is_cycle(inner, annulus) and not H.is_boundary(inner, annulus)
    assert H.is_boundary(inner + outer, annulus)
    assert not H.is_cycle([(0, 1), (1, 2)])
    assert H.is_boundary([], annulus) and H.is_cycle([])
    assert H.is_boundary([(0, 1), (0, 1)], annulus)  # 1 + 1 = 0: the zero chain
    loop = [(i, (i + 1) % 7) for i in range(7)]
    assert H.is_cycle(loop, TORUS) and not H.is_boundary(loop, TORUS)
    # a chain is a boundary iff it is the boundary of some chain: brute force over all 2-chains of a small complex
    K = sl.closure([(0, 1, 2), (0, 2, 3), (1, 2, 3)])
    tris = H.k_simplices(K, 2)
    bounds = {
        frozenset(H.chain_boundary([t for t, b in zip(tris, bits) if b])) for bits in product((0, 1), repeat=len(tris))
    }
    edges = H.k_simplices(K, 1)
    for bits in product((0, 1), repeat=len(edges)):
        c = [e for e, b in zip(edges, bits) if b]
        assert H.is_boundary(c, K) == (frozenset(c) in bounds)


def test_positive_simplices_count_betti():
    order = [(0,), (1,), (2,), (0, 1), (1, 2), (0, 2), (0, 1, 2)]
    assert H.positive_simplices(order) == [True, True, True, False, False, True, False]
    # births minus deaths per dimension give the Betti numbers of the torus, in any valid order
    rng = np.random.default_rng(3)
    S = list(TORUS)
    keys = {s: (len(s), rng.random()) for s in S}
    order = sorted(S, key=keys.get)
    pos = H.positive_simplices(order)
    beta = [0, 0, 0]
    for s, p in zip(order, pos):
        k = len(s) - 1
        if p:
            beta[k] += 1
        else:
            beta[k - 1] -= 1
    assert tuple(beta) == (1, 2, 1)


def _positive_by_prefixes(order):
    """The definition, asked afresh at each step: is ∂σ a boundary of the simplices before it?"""
    return [len(s) == 1 or H.is_boundary(H.chain_boundary([s]), order[:i]) for i, s in enumerate(order)]


@settings(deadline=None)
@given(st.integers(0, 10_000))
def test_positive_simplices_is_the_prefix_definition(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 8))
    tops = [
        tuple(rng.choice(n, size=int(rng.integers(1, min(n, 4) + 1)), replace=False).tolist())
        for _ in range(int(rng.integers(1, 9)))
    ]
    K = H.closure(tops)
    keys = {s: (len(s), rng.random()) for s in K}
    order = sorted(K, key=keys.get)
    shuffled = [tuple(rng.permutation(s).tolist()) for s in order]  # vertex order inside a tuple is irrelevant
    assert H.positive_simplices(shuffled) == _positive_by_prefixes(order)


def test_positive_simplices_on_an_alpha_filtration_is_fast_and_matches_its_betti_numbers():
    rng = np.random.default_rng(5)
    F = sl.alpha_filtration(sl.Balls(rng.uniform(0, 6, size=(400, 2)), rng.uniform(0.3, 1.0, size=400)))
    B = F.boundary_matrix()
    order = [tuple(int(v) for v in F.simplices(k)[r]) for k, r in zip(B.dims, B.rows)]
    assert len(order) > 700
    pos = H.positive_simplices(order)  # once quadratic (a rank per prefix): minutes at this size
    beta = [0, 0, 0]
    for s, p in zip(order, pos):
        beta[len(s) - 1 if p else len(s) - 2] += 1 if p else -1
    assert tuple(beta) == tuple(int(x) for x in F.betti(1e9))


def test_rank_mod2_exact_on_other_integer_forms():
    assert H.rank_mod2(np.array([[2**70, 1], [3, 2**80]], dtype=object)) == 2  # Python ints, reduced exactly
    assert H.rank_mod2(np.array([[2**64 - 2, 1]], dtype=np.uint64)) == 1
    assert H.rank_mod2([[-1, 1], [1, -1]]) == 1
    assert H.rank_mod2(np.eye(3, dtype=bool)) == 3


def test_validation_names_the_argument():
    with pytest.raises(ValueError, match="simplices.*closure"):
        H.betti_numbers([(0, 1)])
    with pytest.raises(TypeError, match="simplices"):
        H.betti_numbers(3)
    with pytest.raises(TypeError, match="simplices"):
        H.betti_numbers([(0, 1.5)])
    with pytest.raises(ValueError, match="repeats"):
        H.betti_numbers([(0, 0)])
    with pytest.raises(TypeError, match="k"):
        H.boundary_matrix(TORUS, 1.0)
    with pytest.raises(ValueError, match="k"):
        H.boundary_matrix(TORUS, -1)
    with pytest.raises(ValueError, match="chain"):
        H.is_boundary([(0, 9)], TORUS)
    with pytest.raises(ValueError, match="chain"):
        H.is_cycle([(0,), (0, 1)])
    with pytest.raises(TypeError, match="M"):
        H.rank_mod2(np.ones((2, 2)) * 0.5)
    with pytest.raises(ValueError, match="M"):
        H.rank_mod2([1, 0])
    with pytest.raises(ValueError, match="order"):
        H.positive_simplices([(0,), (0, 1)])
    with pytest.raises(ValueError, match="order.*twice"):
        H.positive_simplices([(0,), (1,), (0, 1), (1, 0)])
    with pytest.raises(ValueError, match="M.*equal length"):
        H.rank_mod2([[1, 0], [1]])
    for bad in (None, "10"):
        with pytest.raises(TypeError, match="M"):
            H.rank_mod2(bad)
    with pytest.raises(TypeError, match="chain.*not one simplex"):
        H.is_cycle((0, 1))
    with pytest.raises(TypeError, match="simplices"):
        H.betti_numbers([("a",), ("b",), ("a", "b")])


def test_small_and_degenerate_inputs():
    assert H.betti_numbers([]) == () and H.euler_characteristic([]) == 0 and H.closure([]) == []
    assert H.betti_numbers([(0,)]) == (1,)
    assert H.betti_numbers([(1,), (0,), (1, 0), (0, 1)]) == (1, 0)  # unsorted and repeated
    assert H.betti_numbers(np.array([[0], [1]])) == (2,)
    big = 10**30
    assert H.betti_numbers([(big,), (big + 1,), (big, big + 1)]) == (1, 0)
    assert H.boundary_matrix([(0,)], 5).shape == (0, 0) and H.k_simplices([(0,)], 5) == []
    assert not H.is_boundary([(0, 1, 2)], sl.closure([(0, 1, 2)]))  # no tetrahedra
    assert H.is_boundary([(0,), (1,)], sl.closure([(0, 1)])) and not H.is_boundary([(0,)], sl.closure([(0, 1)]))


def test_plot_names_a_vertex_without_position():
    with pytest.raises(ValueError, match="positions.*vertex 1"):
        sl.plot.simplicial_complex([(0,), (1,), (0, 1)], {0: (0, 0)})


def _brute_rank_gf2(A):
    """The rank over GF(2) as log2 of the number of distinct row combinations."""
    A = np.asarray(A, dtype=np.int64) % 2
    m = A.shape[0]
    seen = {tuple(((np.array(bits) @ A) % 2).tolist()) if m else () for bits in product((0, 1), repeat=m)}
    return int(np.log2(len(seen))) if A.shape[1] else 0


@settings(deadline=None)
@given(st.integers(0, 6), st.integers(0, 7), st.integers(0, 2**42 - 1))
def test_rank_mod2_brute_force(m, n, bits):
    A = np.array([(bits >> i) & 1 for i in range(m * n)], dtype=np.uint8).reshape(m, n)
    assert H.rank_mod2(A) == _brute_rank_gf2(A)
    assert H.rank_mod2(A.T) == H.rank_mod2(A)


@st.composite
def random_complexes(draw):
    n = draw(st.integers(1, 7))
    tops = draw(st.lists(st.lists(st.integers(0, n - 1), min_size=1, max_size=4, unique=True), max_size=10))
    return sl.closure([tuple(t) for t in tops] + [(v,) for v in range(n)])


@settings(deadline=None)
@given(random_complexes())
def test_euler_poincare(K):
    b = H.betti_numbers(K)
    assert sum((-1) ** k * x for k, x in enumerate(b)) == H.euler_characteristic(K)
    assert all(x >= 0 for x in b)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000))
def test_agrees_with_the_alpha_filtration(seed):
    rng = np.random.default_rng(seed)
    dim = 2 + seed % 2
    n = 6 + seed % 9
    balls = sl.Balls(rng.uniform(0, 4, size=(n, dim)), rng.uniform(0.3, 1.0, size=n))
    F = sl.alpha_filtration(balls)
    for tau in (-0.2, 0.0, 0.5, 1.5):
        K = F.complex_at(tau)
        b = H.betti_numbers(K)
        lib = tuple(int(x) for x in F.betti(tau))
        assert b == lib[: len(b)] and not any(lib[len(b) :])
        assert H.euler_characteristic(K) == K.euler_characteristic()
