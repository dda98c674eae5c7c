"""Tests of shapelab.flow: the discrete flow and its pockets (Notes §23.1).

Oracles: the orthocentre's barycentric coordinates solved in exact rationals (a
different formulation from the module's attachment polynomial), shapes whose pockets
are known by construction, the voids of shapelab.cavities, the entry times of the
filtration (the flow never decreases them), and GUDHI-free invariants.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shapelab as sl
from shapelab import datasets
from shapelab.cavities.flow import flow_side_exact

from .._oracles import exact_solve


# ----------------------------------------------------------------------------- oracle
def _barycentric_orthocentre(z, w):
    """Barycentric coordinates of the orthocentre of the simplex with centres ``z``
    (d+1 rows) and weights ``w``, exactly."""
    Z = [[Fraction(float(c)) for c in row] for row in z]
    W = [Fraction(x) for x in w]
    d = len(Z[0])
    M = [[2 * (Z[i][k] - Z[0][k]) for k in range(d)] for i in range(1, d + 1)]
    b = [sum(c * c for c in Z[i]) - W[i] - sum(c * c for c in Z[0]) + W[0] for i in range(1, d + 1)]
    y = exact_solve(M, b)
    # sum_i lam_i z_i = y, sum_i lam_i = 1
    A = [[Z[i][k] for i in range(d + 1)] for k in range(d)] + [[Fraction(1)] * (d + 1)]
    return exact_solve(A, y + [Fraction(1)])


def _weights(balls):
    # the filtration's weights (r*r rounded once), taken exactly, as the flow does
    return [Fraction(float(w)) for w in balls.weights]


def _check_against_oracle(balls):
    F = sl.alpha_filtration(balls)
    d = balls.dim
    flow = sl.discrete_flow(F, -np.inf)  # every simplex empty, every facet open
    S = F.simplices(d)
    W = _weights(balls)
    assert flow.empty.all()
    for i, row in enumerate(S.tolist()):
        lam = _barycentric_orthocentre(balls.centers[row], [W[v] for v in row])
        assert flow.flows[i].tolist() == [x < 0 for x in lam], (i, row, lam)
    return F, flow


# ------------------------------------------------------------------------- predicate
def test_predicate_obtuse_right_acute():
    e = [[-1.0, 0.0], [1.0, 0.0]]
    assert flow_side_exact(e, [0.0, 0.0], [0.0, 0.5], 0.0) == -1
    assert flow_side_exact(e, [0.0, 0.0], [0.0, 1.0], 0.0) == 0  # right angle: on the edge
    assert flow_side_exact(e, [0.0, 0.0], [0.0, 1.5], 0.0) == 1
    # a heavy apex pushes the orthocentre away from it: acute triangle, yet flow
    assert flow_side_exact(e, [0.0, 0.0], [0.0, 1.5], 4.0) == -1


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("d", [2, 3])
def test_flow_is_the_sign_of_the_orthocentres_barycentric_coordinate(d, seed):
    rng = np.random.default_rng(seed)
    balls = sl.Balls(rng.uniform(-3, 3, (14 if d == 3 else 20, d)), rng.uniform(0.2, 1.2, 14 if d == 3 else 20))
    _check_against_oracle(balls)


@pytest.mark.parametrize("d", [2, 3])
def test_lattice_ties(d):
    """Integer lattices: co-circular/co-spherical everywhere, right angles on facets."""
    g = np.arange(4.0)
    pts = np.array(np.meshgrid(*([g] * d))).reshape(d, -1).T
    F, flow = _check_against_oracle(sl.Balls(pts, 0.4))
    # ties (orthocentre exactly on a facet) are no flow: a square's two right
    # triangles are both sinks
    assert flow.sink.any()


# ------------------------------------------------------------------ known by construction
def _ring(n=12, gap=False, r=0.9):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    if gap:
        t = t[1:]
    return sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], r)


def test_ring_with_a_gap_is_one_pocket_whose_mouth_is_the_gap():
    balls = _ring(gap=True)
    (p,) = sl.flow_pockets(balls)
    assert not p.is_void
    assert sorted(map(sorted, p.mouth.tolist())) == [[0, 10]]  # the two disks beside the gap
    # the whole chamber: every empty triangle of the hull
    F = sl.alpha_filtration(balls)
    assert set(p.cell_ids.tolist()) == set(np.flatnonzero(F.values(2) > 0).tolist())


def test_closed_ring_is_a_void_without_mouth():
    (p,) = sl.flow_pockets(_ring())
    assert p.is_void and p.mouth.shape == (0, 2)


def test_closed_shell_in_3d_is_a_void():
    k = np.arange(100) + 0.5
    phi = np.arccos(1 - 2 * k / 100)
    th = np.pi * (1 + 5**0.5) * k
    pts = 3 * np.c_[np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)]
    balls = sl.Balls(pts, 1.0)
    F = sl.alpha_filtration(balls)
    regions = sl.flow_pockets(F)
    (v,) = sl.voids(F)
    voids = [p for p in regions if p.is_void]
    assert len(voids) == 1
    assert set(voids[0].cell_ids.tolist()) == set(v.cell_ids.tolist())


def test_flask_and_funnel():
    left, right = datasets.figure_23_2()
    F = sl.alpha_filtration(left)
    (p,) = sl.flow_pockets(F)
    (g,) = sl.pockets(F, min_persistence=1e-9)
    # the flow's pocket holds the growth model's, and its one mouth edge is the gap at the top
    assert set(g.cell_ids.tolist()) < set(p.cell_ids.tolist())
    assert len(p.mouth) == 1
    gap = left.centers[p.mouth[0]]
    assert np.allclose(sorted(gap[:, 0]), [-1.0, 1.0]) and np.allclose(gap[:, 1], gap[0, 1])
    assert sl.flow_pockets(right) == ()


# -------------------------------------------------------------------------- invariants
def _invariants(F, tau):
    d = F.balls.dim
    flow = sl.discrete_flow(F, tau)
    vals = F.values(d)
    n = len(vals)
    for i in range(n):
        if not flow.empty[i]:
            assert not flow.flows[i].any() and not flow.sink[i]
            continue
        for s in flow.successors(i).tolist():
            if s >= 0:
                assert flow.empty[s]
                # the flow never lowers the orthosphere's power (a top simplex enters at
                # it); equal powers (co-circular ties) are computed to round-off
                assert vals[s] >= vals[i] or np.isclose(vals[s], vals[i], rtol=1e-12, atol=0)
        down = flow.downstream(i)
        assert down, i  # every path ends: in a sink or at infinity
        assert (-1 in down) == bool(flow.to_infinity[i])
        sinks = [s for s in down if s >= 0]
        assert all(flow.sink[s] for s in sinks)
        if not flow.to_infinity[i]:
            assert {int(flow.region[s]) for s in sinks} == {int(flow.region[i])}
    # no flow is ever blocked by K: the sinks are the centred empty simplices, except
    # where round-off of the entry times (ENTRY_TIME_RTOL) puts a facet in K just
    # before the simplex that flows across it (a near-tie of entry times)
    free = sl.discrete_flow(F, -np.inf).flows
    centred = ~free.any(axis=1)
    assert not (flow.empty & centred & ~flow.sink).any()
    B = np.asarray(F.boundary(d))
    fvals = F.values(d - 1)
    for i in np.flatnonzero(flow.sink & ~centred).tolist():
        for f in B[i][free[i]].tolist():
            assert fvals[f] <= tau < vals[i] and vals[i] - fvals[f] <= 2.5e-9 * abs(vals[i]), (i, f)
    # regions partition the empty simplices that do not reach infinity
    inside = flow.empty & ~flow.to_infinity
    assert np.array_equal(flow.region >= 0, inside)
    cells = np.concatenate([p.cell_ids for p in flow.pockets]) if flow.pockets else np.zeros(0, int)
    assert sorted(cells.tolist()) == np.flatnonzero(inside).tolist()
    # mouthless regions are exactly the voids of the growth model, cell for cell
    ours = sorted(sorted(p.cell_ids.tolist()) for p in flow.pockets if p.is_void)
    theirs = sorted(sorted(v.cell_ids.tolist()) for v in sl.voids(F, tau))
    assert ours == theirs
    return flow


@settings(max_examples=25, deadline=None)
@given(
    seed=st.integers(0, 2**31 - 1),
    d=st.sampled_from([2, 3]),
    tau=st.sampled_from([-0.5, 0.0, 0.3, 1.0]),
)
def test_invariants_random(seed, d, tau):
    rng = np.random.default_rng(seed)
    n = 30 if d == 2 else 25
    balls = sl.Balls(rng.uniform(-3, 3, (n, d)), rng.uniform(0.3, 1.0, n))
    _invariants(sl.alpha_filtration(balls), tau)


@pytest.mark.parametrize("tau", [0.0, 0.2, 0.6])
def test_invariants_shapes(tau):
    for balls in (*datasets.figure_23_2(), datasets.nested_pockets(), datasets.mixed_dent(), _ring(gap=True)):
        _invariants(sl.alpha_filtration(balls), tau)


@pytest.mark.parametrize("d", [2, 3])
def test_invariants_lattice_with_ties(d):
    g = np.arange(4.0)
    pts = np.array(np.meshgrid(*([g] * d))).reshape(d, -1).T
    keep = np.any(pts != 1.0, axis=1)  # a lattice with one site removed
    F = sl.alpha_filtration(sl.Balls(pts[keep], 0.45))
    for tau in (-0.2, 0.0, 0.1, 0.3):
        _invariants(F, tau)


def test_attached_facets_are_the_facets_the_flow_crosses():
    """The filtration's attachment flags (if this version has them) mark the facets
    some coface's orthocentre lies beyond: exactly those the flow crosses at -inf."""
    rng = np.random.default_rng(7)
    balls = sl.Balls(rng.uniform(-3, 3, (40, 2)), rng.uniform(0.2, 1.0, 40))
    F = sl.alpha_filtration(balls)
    if not hasattr(F, "attached"):
        pytest.skip("Filtration.attached not available")
    flow = sl.discrete_flow(F, -np.inf)
    crossed = np.zeros(len(F.values(1)), dtype=bool)
    crossed[np.asarray(F.boundary(2))[flow.flows]] = True
    assert np.array_equal(crossed, F.attached(1))


def test_weights_are_the_filtrations():
    """Second reading (issue 21): the flow took r**2 exactly, the filtration r*r rounded
    to float64; on a near-tie they disagreed.  Here the exact r**2 puts the apex inside
    the facet's orthosphere, the rounded one just outside, and the facet's orthosphere
    has power 0: with r**2 the triangle (entering at ~2e-37) was blocked at tau = 0 by
    its edge (entering at 0) and counted as a sink though not centred."""
    x, h, ra = 0.7983212912404407, 0.3811974851933834, 0.8846628774655148
    balls = sl.Balls(np.array([[-1.0, 0.0], [1.0, 0.0], [x, h]]), np.array([1.0, 1.0, ra]))
    e = [[-1.0, 0.0], [1.0, 0.0]]
    assert flow_side_exact(e, [1.0, 1.0], [x, h], Fraction(ra) ** 2) == -1  # exact r**2
    assert flow_side_exact(e, [1.0, 1.0], [x, h], ra * ra) == 1  # the filtration's weight
    F = sl.alpha_filtration(balls)
    free = sl.discrete_flow(F, -np.inf).flows
    crossed = np.zeros(len(F.values(1)), dtype=bool)
    crossed[np.asarray(F.boundary(2))[free]] = True
    assert np.array_equal(crossed, F.attached(1))
    flow = sl.discrete_flow(F, 0.0)
    assert flow.empty.all() and np.array_equal(flow.sink, ~free.any(axis=1))


def test_blocked_only_by_roundoff_of_a_tie():
    """17 disks on a circle (float cos/sin: nearly co-circular), so every triangle's
    entry time is 4 - 0.09 up to round-off; between two of them a facet can enter
    just before the triangle that flows across it, which is then a blocked sink.
    _invariants bounds the gap by the filtration's accuracy."""
    t = np.linspace(0, 2 * np.pi, 17, endpoint=False)
    F = sl.alpha_filtration(sl.Balls(2 * np.c_[np.cos(t), np.sin(t)], 0.3))
    vals = F.values(2)
    assert np.allclose(vals, 3.91, rtol=1e-14, atol=0)
    centred = ~sl.discrete_flow(F, -np.inf).flows.any(axis=1)
    blocked = 0
    for tau in np.unique(vals).tolist():
        flow = _invariants(F, tau)
        blocked += int((flow.sink & ~centred).sum())
    assert blocked > 0  # the case the tolerance is for does occur
    for tau in (3.9, 3.92):  # away from the tie: exactly the centred ones
        flow = sl.discrete_flow(F, tau)
        assert np.array_equal(flow.sink, flow.empty & centred)


def test_flow_side_exact_validates():
    e = [[-1.0, 0.0], [1.0, 0.0]]
    with pytest.raises(ValueError, match="z_facet"):
        flow_side_exact([[0.0, 0.0]], [0.0], [0.0, 1.0], 0.0)
    with pytest.raises(ValueError, match="z_facet"):
        flow_side_exact([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], [0.0, 0.0], [0.0, 1.0, 0.0], 0.0)
    with pytest.raises(ValueError, match="w_facet"):
        flow_side_exact(e, [0.0], [0.0, 1.0], 0.0)
    with pytest.raises(ValueError, match="z_apex"):
        flow_side_exact(e, [0.0, 0.0], [0.0, 1.0, 2.0], 0.0)
    with pytest.raises(ValueError, match="z_apex"):
        flow_side_exact(e, [0.0, 0.0], [np.nan, 1.0], 0.0)
    with pytest.raises(TypeError, match="w_apex"):
        flow_side_exact(e, [0.0, 0.0], [0.0, 1.0], "1")
    with pytest.raises(TypeError, match="z_facet"):
        flow_side_exact("ab", [0.0, 0.0], [0.0, 1.0], 0.0)
    with pytest.raises(ValueError, match="affinely dependent"):
        flow_side_exact([[0.0, 0.0], [0.0, 0.0]], [0.0, 0.0], [0.0, 1.0], 0.0)
    # Fractions and integers are taken as they are
    assert (
        flow_side_exact([[-1, 0], [1, 0]], [Fraction(1, 3)] * 2, [0, Fraction(2, 3)], Fraction(-1, 9)) == -1
    )  # 5/9 < 2/3


# ------------------------------------------------------------------------ edge cases
def test_flat_and_tiny_input():
    assert sl.flow_pockets(sl.Balls(np.c_[np.arange(5.0), np.zeros(5)], 0.5)) == ()
    assert sl.discrete_flow(sl.Balls(np.zeros((1, 3)), 1.0)).pockets == ()


def test_tau_is_validated():
    with pytest.raises((TypeError, ValueError), match="tau"):
        sl.discrete_flow(_ring(), "0")
    with pytest.raises((TypeError, ValueError), match="tau"):
        sl.discrete_flow(_ring(), float("nan"))


def test_tau_infinite():
    F = sl.alpha_filtration(_ring(gap=True))
    assert sl.flow_pockets(F, np.inf) == ()  # everything in K
    assert sl.discrete_flow(F, -np.inf).empty.all()


# ------------------------------------------------------------------------------ figure
def test_plot_draws_one_arrow_per_flow_step():
    from shapelab import plot

    F = sl.alpha_filtration(_ring(gap=True))
    fig = plot.discrete_flow(F)
    ax = fig.axes[0]
    arrows = [t for t in ax.texts if getattr(t, "arrow_patch", None) is not None]
    assert len(arrows) == int(sl.discrete_flow(F).flows.sum()) > 0
    with pytest.raises(ValueError, match="2D"):
        plot.discrete_flow(sl.Balls(np.eye(3) * 2, 1.0))


@pytest.mark.parametrize(
    ("d", "spacing", "radius", "two_radii"),
    [(2, 0.1, 0.03, True), (2, 1.0, 0.3, False), (3, 0.1, 0.03, False), (3, 0.7, 0.2, False)],
)
def test_exact_road_on_a_grid_is_flow_side_exact(d, spacing, radius, two_radii, monkeypatch):
    """A grid is co-spherical everywhere: many flow decisions are ties, left by the
    float filter to the exact road (integers scaled by one power of two, issue 23
    review: Fractions took 28 s on KVFinder's grid of 1fmo).  Every decision equals
    flow_side_exact's (Fractions) on the same binary values, ties included."""
    from shapelab._engine import flow as flow_module

    calls = []
    scaled = flow_module.scaled_integers
    monkeypatch.setattr(flow_module, "scaled_integers", lambda *a: calls.append(1) or scaled(*a))
    k = 6 if d == 2 else 4
    g = np.stack(np.meshgrid(*[np.arange(k) * spacing] * d), -1).reshape(-1, d) + 0.3
    radii = radius * (1 + 0.5 * two_radii * (np.arange(len(g)) % 3 == 0))  # weights that differ, or not
    F = sl.alpha_filtration(sl.Balls(g, radii))
    out = flow_module.beyond(F)
    S = np.asarray(F.simplices(d), dtype=np.int64)
    z, w = F.balls.centers, F.balls.weights
    for i, row in enumerate(S.tolist()):
        for j in range(d + 1):
            facet = [row[c] for c in range(d + 1) if c != j]
            assert out[i, j] == flow_side_exact(z[facet], w[facet], z[row[j]], float(w[row[j]])), (i, j)
    assert calls  # the float filter left decisions to the exact road
