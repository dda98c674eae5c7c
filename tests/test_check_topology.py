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
