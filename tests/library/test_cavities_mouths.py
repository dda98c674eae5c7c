"""Mouths of pockets open to the outside, for both definitions (Notes §23.1; issue 23).

The mouth of a pocket region R at τ: the faces not in K_τ with one side in R and the
other in the component of ∞ of the complement's dual graph once R is deleted.  Oracles:

* a brute force written from the filtration's raw tables (``F.simplices``,
  ``F.values``, ``F.boundary``) with a plain breadth-first search, independent of
  ``shapelab._pockets`` (no summary, no search tree, no interval certificates);
* shapes whose openings are known by construction: the flask of Figure 23.2 (the neck
  only, not the four notches of the chamber's wall), the two-chamber flask (the inner
  chamber's mouth is the neck), a ring with a gap (a bowl: the gap), a tube closed at
  one end (the triangles of the open end's ring);
* invariants: a mouth face lies on R's boundary and not in K_τ; closing the mouth cuts
  R off from ∞; re-opening any one mouth face joins them again (the cut is minimal);
  every pocket has a mouth.

FlowPocket: its mouth is the same cut (tested against the same brute force), its
measured quantities are Pocket's (volume by the same free-space decomposition, lining
by the same rule), and its (closes_at, fills_at) is a pair of the growth model.
"""

from __future__ import annotations

from collections import deque

import numpy as np
import pytest

import shapelab as sl
from shapelab import datasets
from shapelab.cavities.freespace import free_measure


# ----------------------------------------------------------------------------- oracle
def _dual(F):
    """Per facet row: its cofaces (top-simplex rows; -1 for the outside)."""
    d = F.balls.dim
    B = np.asarray(F.boundary(d), dtype=np.int64)
    co = {}
    for c, row in enumerate(B.tolist()):
        for f in row:
            co.setdefault(f, []).append(c)
    return B, {f: (cs + [-1])[:2] for f, cs in co.items()}


def _reaches_infinity(F, tau, removed, closed=frozenset()):
    """Cells (and -1 for ∞) joined to ∞ through free cells and free facets, avoiding
    ``removed`` cells and the facets in ``closed``: plain BFS."""
    d = F.balls.dim
    B, co = _dual(F)
    fval = np.asarray(F.values(d - 1))
    cval = np.asarray(F.values(d))
    nbrs = {}
    for f, (a, b) in co.items():
        if fval[f] > tau and f not in closed:
            nbrs.setdefault(a, []).append(b)
            nbrs.setdefault(b, []).append(a)
    seen, q = {-1}, deque([-1])
    while q:
        x = q.popleft()
        for y in nbrs.get(x, []):
            if y in seen or y in removed or (y >= 0 and cval[y] <= tau):
                continue
            seen.add(y)
            q.append(y)
    return seen


def _mouth_oracle(F, tau, cell_ids):
    d = F.balls.dim
    B, co = _dual(F)
    fval = np.asarray(F.values(d - 1))
    R = set(int(c) for c in cell_ids)
    outside = _reaches_infinity(F, tau, R)
    out = []
    for f, (a, b) in co.items():
        if fval[f] <= tau or ((a in R) == (b in R)):
            continue
        other = b if a in R else a
        if other in outside:
            out.append(f)
    return sorted(out)


def _random_balls(seed, d, n):
    rng = np.random.default_rng(seed)
    return sl.Balls(rng.uniform(-3, 3, (n, d)), rng.uniform(0.4, 0.9, n))


def _taus(F, k=4):
    v = np.unique(np.asarray(F.values(F.balls.dim)))
    v = v[np.isfinite(v)]
    return [float(x) for x in np.quantile(v, np.linspace(0.05, 0.6, k))] + [0.0]


# ------------------------------------------------------------ brute force, invariants
def _all_pockets(F, tau):
    return [*sl.pockets(F, tau), *sl.pockets(F, tau, method="flow")]


@pytest.mark.parametrize(("seed", "d", "n"), [(s, 2, 40) for s in range(6)] + [(s, 3, 45) for s in range(4)])
def test_mouth_is_the_cut_to_the_outside_brute_force(seed, d, n):
    F = sl.alpha_filtration(_random_balls(seed, d, n))
    checked = 0
    for tau in _taus(F):
        for p in _all_pockets(F, tau):
            assert p.mouth_ids.tolist() == _mouth_oracle(F, tau, p.cell_ids), (tau, p)
            checked += 1
    assert checked > 0  # the inputs have pockets to check


@pytest.mark.parametrize(("seed", "d", "n"), [(s, 2, 40) for s in range(4)] + [(s, 3, 45) for s in range(2)])
def test_mouth_invariants(seed, d, n):
    F = sl.alpha_filtration(_random_balls(seed, d, n))
    B = np.asarray(F.boundary(d), dtype=np.int64)
    fval = np.asarray(F.values(d - 1))
    fsimp = np.asarray(F.simplices(d - 1), dtype=np.int64)
    for tau in _taus(F, 3):
        for p in _all_pockets(F, tau):
            R = set(p.cell_ids.tolist())
            mouth = set(p.mouth_ids.tolist())
            assert mouth, p  # a pocket is open to the outside
            on_boundary = {f for f in mouth if sum(f in set(B[c].tolist()) for c in R) == 1}
            assert on_boundary == mouth
            assert np.all(fval[list(mouth)] > tau)  # not in K_tau
            assert np.array_equal(p.mouth, fsimp[p.mouth_ids])
            # closing the mouth cuts R (and its crevices) off from the outside ...
            reach = _reaches_infinity(F, tau, set(), closed=frozenset(mouth))
            assert not (reach & R)
            # ... and re-opening any one mouth face joins them again
            for f in list(mouth)[:3]:
                reach = _reaches_infinity(F, tau, set(), closed=frozenset(mouth - {f}))
                assert reach & R


# ------------------------------------------------------------------- constructions
def test_flask_mouth_is_the_neck_only():
    left, _ = datasets.figure_23_2()
    F = sl.alpha_filtration(left)
    (p,) = sl.pockets(F, 0.0, min_persistence=1e-9)
    assert len(p.mouth) == 1
    ends = left.centers[p.mouth[0]]
    np.testing.assert_allclose(sorted(ends[:, 0]), [-1.0, 1.0])  # the gap of width 2 at the top
    np.testing.assert_allclose(ends[:, 1], [3 * np.sqrt(3)] * 2)
    assert p.mouth_size == pytest.approx(2.0)
    # the four notches of the chamber's wall: open boundary faces of the region that
    # lead into crevices, not out
    B = np.asarray(F.boundary(2), dtype=np.int64)
    faces, cnt = np.unique(B[p.cell_ids].ravel(), return_counts=True)
    open_boundary = faces[(cnt == 1) & (np.asarray(F.values(1))[faces] > 0.0)]
    assert len(open_boundary) == 5
    crevice = sorted(set(open_boundary.tolist()) - set(p.mouth_ids.tolist()))
    gaps = np.linalg.norm(np.diff(left.centers[np.asarray(F.simplices(1))[crevice]], axis=1)[:, 0], axis=1)
    np.testing.assert_allclose(gaps, np.sqrt(3))
    # the flow's pocket (which takes the notches in) has the same single opening
    (q,) = sl.pockets(F, 0.0, method="flow")
    assert q.mouth_ids.tolist() == p.mouth_ids.tolist()


def test_two_chambers_the_neck_into_the_dead_end_is_no_mouth():
    """Chamber A opens to the outside at the top and into chamber B through a neck.
    The inner pocket is A (it becomes a void of its own when the neck closes); B is
    reachable from the outside only through A, so the neck is no opening of A: both
    pockets open through the same top gap."""
    F = sl.alpha_filtration(datasets.nested_pockets())
    balls = F.balls
    outer, inner = sl.pockets(F, 0.0, min_persistence=1e-9)
    assert set(inner.cell_ids.tolist()) < set(outer.cell_ids.tolist())
    assert outer.mouth_ids.tolist() == inner.mouth_ids.tolist() and len(outer.mouth) == 1
    top = balls.centers[outer.mouth[0]]
    np.testing.assert_allclose(sorted(top[:, 0]), [-1.0, 1.0])  # the gap of width 2 at the top
    assert top[0, 1] > 6.5
    # the neck: an open face on A's boundary, 3 wide, whose closing makes A a void
    B = np.asarray(F.boundary(2), dtype=np.int64)
    fval = np.asarray(F.values(1))
    faces, cnt = np.unique(B[inner.cell_ids].ravel(), return_counts=True)
    neck = faces[(cnt == 1) & (fval[faces] > 0.0) & ~np.isin(faces, inner.mouth_ids)]
    widths = np.linalg.norm(np.diff(balls.centers[np.asarray(F.simplices(1))[neck]], axis=1)[:, 0], axis=1)
    assert widths.max() == pytest.approx(3.0)
    assert fval[neck].max() == pytest.approx(inner.closes_at) == pytest.approx(1.5**2 - 0.65**2)
    # the top gap closes first, sealing A and B together into the outer pocket's void
    assert fval[inner.mouth_ids].max() == pytest.approx(outer.closes_at)
    assert outer.closes_at < inner.closes_at


def test_bowl_ring_with_a_gap():
    t = np.linspace(0, 2 * np.pi, 12, endpoint=False)[1:]
    ring = sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], 0.9)
    F = sl.alpha_filtration(ring)
    for method in ("growth", "flow"):
        (p,) = sl.pockets(F, 0.0, method=method)
        assert len(p.mouth) == 1
        a, b = ring.centers[p.mouth[0]]
        assert np.linalg.norm(a - b) == pytest.approx(3.0)  # the gap: 2·3·sin(30°)
        assert p.closes_at == pytest.approx(1.5**2 - 0.81)
        assert p.fills_at == pytest.approx(9.0 - 0.81)


def _tube(k=10, rings=6, radius=2.0, neck=1.5, r=0.9):
    """Rings of k balls stacked along z (radius 2), closed at z = 0 by a cap, open at
    the top through a narrower last ring (radius 1.5): its balls touch across the
    axis at τ = 1.5² − r², before the wider rings do (2² − r²), so the whole bore is
    one pocket whose only opening is the top ring."""
    pts = []
    for j in range(rings):
        t = np.linspace(0, 2 * np.pi, k, endpoint=False) + (j % 2) * np.pi / k
        rad = neck if j == rings - 1 else radius
        pts.append(np.c_[rad * np.cos(t), rad * np.sin(t), np.full(k, float(j))])
    a = np.linspace(0, 2 * np.pi, 5, endpoint=False)
    cap = np.vstack([[0.0, 0.0, -0.6], np.c_[0.9 * np.cos(a), 0.9 * np.sin(a), np.full(5, -0.5)]])
    return sl.Balls(np.vstack([*pts, cap]), r), k, rings


def test_tube_open_at_one_end():
    balls, k, rings = _tube()
    F = sl.alpha_filtration(balls)
    top = set(range((rings - 1) * k, rings * k))
    for method in ("growth", "flow"):
        p = sl.pockets(F, 0.0, method=method)[0]  # the most persistent: the tube's bore
        assert p.closes_at == pytest.approx(1.5**2 - 0.81), method
        assert len(p.mouth) > 0
        # every opening triangle spans the open end: its corners are balls of the top ring,
        # and together they tile the ring's decagon
        assert set(np.unique(p.mouth).tolist()) <= top, method
        assert p.mouth_size == pytest.approx(0.5 * k * 1.5**2 * np.sin(2 * np.pi / k)), method
        assert p.mouth_ids.tolist() == _mouth_oracle(F, 0.0, p.cell_ids)


# ------------------------------------------------------------------ flow pockets
@pytest.mark.parametrize(("seed", "d", "n"), [(s, 2, 40) for s in range(4)] + [(s, 3, 45) for s in range(2)])
def test_flow_pockets_measured_like_growth_pockets(seed, d, n):
    balls = _random_balls(seed, d, n)
    F = sl.alpha_filtration(balls)
    vval = np.full(len(balls), np.inf)
    vval[np.asarray(F.simplices(0)).ravel()] = F.values(0)
    cv = np.asarray(F.values(d))
    for tau in _taus(F, 3):
        growth = sl.pockets(F, tau)
        pairs = {(g.closes_at, g.fills_at): g for g in growth}
        flow = sl.flow_pockets(F, tau)
        for q in flow:
            assert isinstance(q, sl.Cavity)
            assert q.volume == pytest.approx(float(free_measure(balls, tau, q.cells).sum()), rel=1e-12, abs=1e-12)
            verts = np.unique(q.cells)
            assert q.lining.tolist() == verts[vval[verts] <= tau].tolist()
            assert q.fills_at <= cv[q.cell_ids].max()
            if q.is_void:
                continue
            if q.persistence > 0:
                # its pair is a growth-model pocket's, rooted inside the region
                g = pairs[(q.closes_at, q.fills_at)]
                assert np.isin(g.cell_ids, q.cell_ids).any()
                # between the two times part of the region is a void
                mid = 0.5 * (q.closes_at + q.fills_at)
                held = np.concatenate([v.cell_ids for v in sl.voids(F, mid)] or [np.zeros(0, int)])
                assert np.isin(q.cell_ids, held).any()
            else:
                assert q.closes_at == q.fills_at == cv[q.cell_ids].max()
        listed = sl.pockets(F, tau, method="flow")
        assert sorted(map(id, listed)) == sorted(id(q) for q in flow if not q.is_void) or len(listed) == sum(
            not q.is_void for q in flow
        )
        assert all(not q.is_void for q in listed)
        assert [q.persistence for q in listed] == sorted((q.persistence for q in listed), reverse=True)


@pytest.mark.parametrize(("seed", "d", "n"), [(s, 2, 40) for s in range(3)] + [(s, 3, 45) for s in range(2)])
def test_growth_pocket_lies_in_one_flow_pocket_at_exact_entry_times(seed, d, n):
    """Every face on the boundary of a growth pocket's cells R enters K no later than
    ``closes_at`` (else its other side would be in R), and every cell of R later, so
    no cell of R attaches a boundary face: the flow cannot leave R, and R (connected
    through free faces) lies in one flow pocket, whose most persistent class is at
    least R's.  Checked at τ equal to entry times of faces and cells (the quantiles of
    the other tests fall between them), where ``value <= tau`` decides membership."""
    F = sl.alpha_filtration(_random_balls(seed, d, n))
    values = np.unique(np.r_[np.asarray(F.values(d - 1)), np.asarray(F.values(d))])
    values = values[np.isfinite(values) & (values > 0)]
    taus = [0.0, *np.random.default_rng(seed).choice(values, 6, replace=False).tolist()]
    checked = 0
    for tau in taus:
        flow = sl.discrete_flow(F, tau)
        for p in sl.pockets(F, tau):
            (home,) = set(flow.region[p.cell_ids].tolist())
            assert home >= 0
            q = flow.pockets[home]
            assert not q.is_void
            assert q.persistence >= p.persistence
            assert p.mouth_ids.tolist() == _mouth_oracle(F, tau, p.cell_ids)
            checked += 1
        for q in sl.pockets(F, tau, method="flow"):
            assert q.mouth_ids.tolist() == _mouth_oracle(F, tau, q.cell_ids)
    assert checked > 0


def test_flow_void_pair_is_the_voids():
    t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    F = sl.alpha_filtration(sl.Balls(3 * np.c_[np.cos(t), np.sin(t)], 0.9))
    (v,) = sl.voids(F)
    (q,) = sl.flow_pockets(F)
    assert q.is_void and (q.closes_at, q.fills_at) == (v.born, v.dies)
    assert q.volume == pytest.approx(v.volume)
    assert sl.pockets(F, method="flow") == ()


def test_flow_pocket_persistence_is_zero_only_at_a_tie():
    """A sink's facets all enter K strictly before it (its orthocentre lies beyond none
    of them), so it roots a class of positive length: an acute triangle of three disks
    is a flow pocket with the growth model's pair.  A right triangle's circumcentre lies
    on its hypotenuse, which enters with it: a flow pocket of persistence 0, and no
    growth-model pocket.  On generic input every flow pocket has positive persistence."""
    acute = sl.alpha_filtration(sl.Balls(np.array([[0.0, 0.0], [3.0, 0.0], [1.2, 2.5]]), 1.0))
    (q,) = sl.pockets(acute, method="flow")
    (p,) = sl.pockets(acute)
    assert q.persistence > 0 and (q.closes_at, q.fills_at) == (p.closes_at, p.fills_at)
    right = sl.alpha_filtration(sl.Balls(np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]]), 1.0))
    (q,) = sl.pockets(right, method="flow")
    assert q.persistence == 0 and q.closes_at == q.fills_at == pytest.approx(4.5 - 1.0)
    assert len(q.mouth) == 3 and sl.pockets(right) == ()
    assert sl.pockets(right, method="flow", min_persistence=1e-12) == ()
    for seed, d, n in [(0, 2, 40), (1, 2, 40), (0, 3, 45), (1, 3, 45)]:
        F = sl.alpha_filtration(_random_balls(seed, d, n))
        for tau in _taus(F, 3):
            assert all(q.persistence > 0 for q in sl.pockets(F, tau, method="flow"))


def test_method_is_validated():
    F = sl.alpha_filtration(datasets.figure_23_2()[0])
    with pytest.raises(ValueError, match="method"):
        sl.pockets(F, method="castp")
