"""Tests of the self-checks in shapelab.check.topology: right answers pass, each
typical mistake fails, and the checks never crash on a broken student function."""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import check


# ---------------------------------------------------------- Euler characteristic
def chi_right(S):
    return sum((-1) ** k * len(s) for k, s in enumerate(S))


def chi_no_triangles(S):  # forgets everything above edges
    return len(S[0]) - (len(S[1]) if len(S) > 1 else 0)


def chi_wrong_sign(S):
    return sum(len(s) for s in S)


def chi_crashes(S):
    return S[1].shape[0]  # IndexError on the one-vertex complex


def test_euler_right_answer_passes(capsys):
    r = check.euler_characteristic(chi_right)
    assert r.passed and r.n_cases > 6  # hand-made plus the library's dual complexes
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize(
    "wrong",
    [chi_no_triangles, chi_wrong_sign, chi_crashes, lambda S: 2, lambda S: float(chi_right(S)) + 0.5, lambda S: "1"],
)
def test_euler_mistakes_fail(wrong, capsys):
    r = check.euler_characteristic(wrong)
    assert not r.passed
    assert "✗" in capsys.readouterr().out


def test_euler_accepts_numpy_integers_and_is_quiet(capsys):
    r = check.euler_characteristic(lambda S: np.int64(chi_right(S)), quiet=True)
    assert r.passed and capsys.readouterr().out == ""


def test_euler_not_a_function():
    assert not check.euler_characteristic(chi_right([np.zeros((1, 1))]), quiet=True).passed


def test_euler_covers_a_closed_surface():
    # the tetrahedron boundary (χ = 2, a sphere) is among the cases: a function right
    # only for complexes with χ <= 1 fails
    assert not check.euler_characteristic(lambda S: min(chi_right(S), 1), quiet=True).passed


# ---------------------------------------------------------- Betti numbers
def betti_union_find(n, edges, triangles):
    """An independent solution: union-find by hand, then β1 = β0 − χ."""
    parent = list(range(n))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    b0 = n
    for u, v in np.asarray(edges).reshape(-1, 2):
        ru, rv = find(int(u)), find(int(v))
        if ru != rv:
            parent[ru] = rv
            b0 -= 1
    return b0, b0 - (n - len(edges) + len(triangles))


def test_betti_right_answer_passes():
    r = check.betti_numbers(betti_union_find, quiet=True)
    assert r.passed and r.n_cases > 8


@pytest.mark.parametrize(
    "wrong",
    [
        lambda n, E, T: (1, 0),
        lambda n, E, T: betti_union_find(n, E, np.zeros((0, 3)))[::-1],
        lambda n, E, T: (betti_union_find(n, E, T)[0], len(E) - n + 1 - len(T)),  # assumes connected
        lambda n, E, T: (betti_union_find(n, E, T)[0], 0),  # no holes ever
        lambda n, E, T: betti_union_find(n, E, T)[0],  # not a pair
        lambda n, E, T: 1 / 0,
    ],
)
def test_betti_mistakes_fail(wrong):
    assert not check.betti_numbers(wrong, quiet=True).passed


def test_betti_sees_holes_in_library_cases():
    # a function right on the hand-made cases but blind to triangles filling holes
    def blind(n, E, T):
        b0, b1 = betti_union_find(n, E, T)
        return (b0, b1 + len(T)) if len(T) > 1 else (b0, b1)

    assert not check.betti_numbers(blind, quiet=True).passed


def betti_by_ranks(n, edges, triangles):
    """An independent right answer that does not assume the plane: β0 = n − rank ∂1 and
    β1 = #E − rank ∂1 − rank ∂2, the ranks of the boundary matrices over the rationals."""
    E = np.sort(np.asarray(edges, dtype=np.int64).reshape(-1, 2), axis=1)
    T = np.sort(np.asarray(triangles, dtype=np.int64).reshape(-1, 3), axis=1)
    d1 = np.zeros((n, len(E)))
    d1[E[:, 0], np.arange(len(E))], d1[E[:, 1], np.arange(len(E))] = -1.0, 1.0
    row = {tuple(e): i for i, e in enumerate(E.tolist())}
    d2 = np.zeros((len(E), len(T)))
    for j, (a, b, c) in enumerate(T.tolist()):
        d2[row[(b, c)], j], d2[row[(a, c)], j], d2[row[(a, b)], j] = 1.0, -1.0, 1.0
    r1 = np.linalg.matrix_rank(d1) if d1.size else 0
    r2 = np.linalg.matrix_rank(d2) if d2.size else 0
    return n - r1, len(E) - r1 - r2


def test_betti_passes_a_right_answer_that_does_not_assume_the_plane():
    # the check once listed the tetrahedron's boundary among its "2D" cases and expected
    # β1 = β0 − χ = −1 there: homology computed by ranks (β1 = 0) was refused
    r = check.betti_numbers(betti_by_ranks, quiet=True)
    assert r.passed, r.message
    assert "-1" not in r.message
