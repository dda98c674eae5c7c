"""Tests of :meth:`shapelab.Filtration.attached`: which simplices enter with a coface.

Oracles, independent of the library's certified floating-point kernel:

* exact rationals (``fractions.Fraction``): the smallest orthogonal sphere of every
  simplex by solving its Gram system exactly, and the power of every other ball at its
  centre; a simplex is attached iff some ball is closer in power than its own balls.
  The same test restricted to the vertices of its cofaces (the rule's statement) must
  agree with the test over all balls (the definition: the orthocentre lies in the dual
  power face);
* the entry times: an unattached simplex enters at its exact :math:`\\rho_\\sigma`, an
  attached one with its earliest coface, and every value is GUDHI's weighted
  ``AlphaComplex`` value.

Inputs: random balls in 2D and 3D, points (radius 0: the unweighted Gabriel test),
a hidden ball, the obtuse triangle of equal disks, a tangent pair, and integer grids
(co-circular ties, where the exact tie counts as unattached).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from shapelab import Balls, alpha_filtration

from .._oracles import exact_orthosphere as orthosphere

gudhi = pytest.importorskip("gudhi")


def power(Z, W, v, c):
    return sum((p - q) ** 2 for p, q in zip(c, Z[v])) - W[v]


def check_against_oracles(balls, *, unique_dt=True):
    F = alpha_filtration(balls)
    Z = [[Fraction(float(x)) for x in row] for row in balls.centers]
    W = [Fraction(float(w)) for w in balls.weights]
    ours = {}
    for k in range(F.dimension + 1):
        for s, v in zip(F.simplices(k).tolist(), F.values(k).tolist()):
            ours[tuple(s)] = v
    # keep the simplex tree alive while its filtration is read (a temporary segfaults)
    tree = gudhi.AlphaComplex(points=balls.centers, weights=balls.weights).create_simplex_tree()
    theirs = {tuple(sorted(s)): f for s, f in tree.get_filtration()}
    if unique_dt:
        assert set(ours) == set(theirs)
    else:  # co-spherical centres: GUDHI may choose other diagonals; compare the common ones
        assert {s for s in ours if len(s) == 1} == {s for s in theirs if len(s) == 1}
    scale = max(1.0, max(abs(v) for v in theirs.values()))
    n_att = 0
    for k in range(F.dimension + 1):
        att = F.attached(k)
        assert att.dtype == bool and att.shape == (F.simplices(k).shape[0],)
        cof = {}
        if k < F.dimension:
            for t in F.simplices(k + 1).tolist():
                for i in range(k + 2):
                    cof.setdefault(tuple(t[:i] + t[i + 1 :]), []).append(tuple(t))
        for s, a in zip(F.simplices(k).tolist(), att.tolist()):
            s = tuple(s)
            c, rho = orthosphere(Z, W, s)
            link = {v for t in cof.get(s, ()) for v in t} - set(s)
            by_link = any(power(Z, W, v, c) < rho for v in link)
            by_all = any(power(Z, W, v, c) < rho for v in range(len(balls)) if v not in s)
            assert by_link == by_all, (s, by_link, by_all)
            assert a == by_link, (k, s, a)
            if s in theirs:
                assert ours[s] == pytest.approx(theirs[s], rel=1e-9, abs=1e-9 * scale)
            if a:
                n_att += 1
                assert ours[s] == min(ours[t] for t in cof[s])
                assert ours[s] >= float(rho) - 1e-9 * scale
            else:
                assert ours[s] == pytest.approx(float(rho), rel=1e-9, abs=1e-12 * scale)
    return F, n_att


@pytest.mark.parametrize("d,n", [(2, 14), (3, 11)])
@pytest.mark.parametrize("seed", range(4))
def test_random_balls(d, n, seed):
    rng = np.random.default_rng(seed)
    check_against_oracles(Balls(rng.uniform(0, 1, (n, d)), rng.uniform(0, 0.4, n)))


@pytest.mark.parametrize("d,n", [(2, 12), (3, 10)])
def test_points_are_the_unweighted_gabriel_test(d, n):
    rng = np.random.default_rng(7)
    _, n_att = check_against_oracles(Balls(rng.uniform(0, 1, (n, d)), 0.0))
    assert n_att > 0  # random points always have some non-Gabriel simplex


def test_obtuse_triangle_of_equal_disks():
    F, n_att = check_against_oracles(Balls([[0.0, 0.0], [4.0, 0.0], [2.0, 1.0]], 1.0))
    assert n_att == 1
    (i,) = np.flatnonzero(F.attached(1))
    assert F.simplices(1)[i].tolist() == [0, 1]
    assert F.values(1)[i] == 5.25 > (4.0 / 2) ** 2 - 1.0  # later than its closed form, 3


def test_acute_triangle_has_no_attached_edge():
    F, n_att = check_against_oracles(Balls([[0.0, 0.0], [4.0, 0.0], [2.0, 3.0]], 1.0))
    assert n_att == 0 and not F.attached(2).any()


def test_tangent_pair_and_a_third_ball():
    F, _ = check_against_oracles(Balls([[0.0, 0.0], [2.0, 0.0], [1.0, 5.0]], [1.0, 1.0, 0.5]))
    (i,) = [i for i, s in enumerate(F.simplices(1).tolist()) if s == [0, 1]]
    assert not F.attached(1)[i] and F.values(1)[i] == 0.0


def test_hidden_ball_and_a_covered_vertex():
    # ball 3 is hidden (not a vertex); ball 1's centre is covered by ball 0's power
    balls = Balls([[0.0, 0.0], [1.0, 0.0], [5.0, 1.0], [0.2, 0.1], [2.0, 4.0]], [3.0, 0.5, 1.0, 0.1, 1.0])
    F, _ = check_against_oracles(balls)
    assert 3 not in F.simplices(0).ravel().tolist()
    v = F.simplices(0).ravel().tolist()
    assert F.attached(0)[v.index(1)] and not F.attached(0)[v.index(0)]


@pytest.mark.parametrize("d,k", [(2, 3), (2, 4), (3, 3)])
def test_integer_grids_with_ties(d, k):
    g = np.stack(np.meshgrid(*([np.arange(k)] * d), indexing="ij"), -1).reshape(-1, d)
    check_against_oracles(Balls(g.astype(np.float64), 0.3), unique_dt=False)


def test_accessor_validates_and_is_read_only():
    F = alpha_filtration(Balls([[0.0, 0.0], [4.0, 0.0], [2.0, 1.0]], 1.0))
    with pytest.raises(ValueError, match="k must be between 0 and 2"):
        F.attached(3)
    with pytest.raises(TypeError, match="k must be an integer"):
        F.attached(1.0)
    with pytest.raises(ValueError):
        F.attached(1)[0] = False
    assert F.attached(1) is F.attached(1)  # computed once
    empty = alpha_filtration(Balls(np.zeros((0, 3)), 1.0))
    assert empty.attached(0).shape == (0,)
