"""The local re-certificate of a repaired triangulation (issue 25): after
:func:`shapelab._engine.certify.repair` stitches a re-triangulated cavity into Qhull's
candidate, ``_certify_stitched`` re-checks only the changed region (and the global
conditions) and relies on the first pass over the candidate for the rest.

Oracle: the whole certificate :func:`shapelab._engine.certify.certify` on the same
stitched triangulation and neighbour relation.  On the right answer (the regular
triangulation, computed by Qhull and certified whole) both accept; on broken stitched
answers (two simplices overlapping, a missing simplex, a facet that is not locally
regular next to the stitched region, a failing simplex of the first pass left in,
wrong neighbour links) both reject, and on every variant they agree.
"""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import Balls, regular_triangulation
from shapelab._engine.certify import _certify_stitched, _first_pass, _grow, certify, facet_adjacency, repair
from shapelab._engine.predicates import WeightedPoints


def _flip23(T, t, u):
    """The three tetrahedra of the other side of the 2-3 flip of the facet between
    ``T[t]`` and ``T[u]`` (sorted rows), or None if one of them is degenerate as a
    vertex set."""
    a = (set(T[t]) - set(T[u])).pop()
    b = (set(T[u]) - set(T[t])).pop()
    face = sorted(set(T[t]) & set(T[u]))
    return [sorted([a, b, face[j], face[(j + 1) % 3]]) for j in range(3)]


def _case(seed, n=80, rounded=False):
    """Random balls, their regular triangulation T, and a candidate broken by one
    convex 2-3 flip; the first pass over the candidate and a cavity around it."""
    rng = np.random.default_rng(seed)
    c = rng.random((n, 3)) * 6
    if rounded:
        c = np.round(c, 0)
        c = np.unique(c, axis=0)
    balls = Balls(c, 0.3 + 0.2 * rng.random(len(c)))
    T = regular_triangulation(balls)
    P = WeightedPoints(balls.centers, balls.radii)
    nbr, _ = facet_adjacency(T)
    for t, i in zip(*np.nonzero(nbr >= 0)):
        u = nbr[t, i]
        three = _flip23(T, t, u)
        if np.all(P.orient(np.array(three)) != 0):
            cand = np.vstack([np.delete(T, [t, u], axis=0), three]).astype(np.int64)
            if certify(P, cand).ok:  # pragma: no cover - a flip keeps DT only if co-spherical
                continue
            first = _first_pass(P, cand)
            if not first.bad.any():  # pragma: no cover - the flip is a global failure
                continue
            cav = _grow(cand, first.nbr, first.bad, P.n, 1)
            return P, T, cand, first, cav
    pytest.fail("no flippable facet")  # pragma: no cover


def _stitch(cand, cav, rows):
    """Stitched form: the kept simplices first, then ``rows``; the neighbour relation by
    sorting the facets (as a repair would have to get right)."""
    rows = np.sort(np.asarray(rows, dtype=np.int64).reshape(-1, cand.shape[1]), axis=1)
    new = np.vstack([cand[~cav], rows])
    return new, facet_adjacency(new)[0]


def _both(P, first, cav, new, nn):
    local = _certify_stitched(P, first, cav, new, nn)
    whole = certify(P, new, nn)
    assert local.ok == whole.ok, (local.reason, whole.reason)
    return local


def _fill(T, cand, cav):
    """The rows of T that replace the cavity (T minus the kept simplices)."""
    kept = {tuple(r) for r in cand[~cav].tolist()}
    return [r for r in T.tolist() if tuple(r) not in kept]


SEEDS = [0, 1, 2, 3]


@pytest.mark.parametrize("seed", SEEDS)
def test_the_right_stitch_passes_both(seed):
    P, T, cand, first, cav = _case(seed)
    new, nn = _stitch(cand, cav, _fill(T, cand, cav))
    assert _both(P, first, cav, new, nn).ok
    fixed = repair(P, cand, max_fraction=1.0)
    assert fixed is not None and fixed[1].ok
    assert {tuple(r) for r in np.sort(fixed[0], axis=1).tolist()} == {tuple(r) for r in T.tolist()}


@pytest.mark.parametrize("seed", SEEDS)
def test_a_missing_simplex_is_rejected_by_both(seed):
    P, T, cand, first, cav = _case(seed)
    fill = _fill(T, cand, cav)
    for j in range(len(fill)):
        new, nn = _stitch(cand, cav, fill[:j] + fill[j + 1 :])
        assert not _both(P, first, cav, new, nn).ok


@pytest.mark.parametrize("seed", SEEDS)
def test_flips_in_and_next_to_the_stitched_region_are_rejected_by_both(seed):
    """Every 2-3 flip of a facet with a new simplex on one side: convex ones leave a
    facet that is not locally regular, the others overlap; when the other side is a
    kept simplex it moves into the cavity (the flip is next to the stitched region)."""
    P, T, cand, first, cav = _case(seed)
    new, nn = _stitch(cand, cav, _fill(T, cand, cav))
    nk = int(np.count_nonzero(~cav))
    kept_ids = np.flatnonzero(~cav)
    tried = {"inside": 0, "next to": 0, "overlap": 0}
    for t in range(nk, new.shape[0]):
        for i in range(4):
            u = int(nn[t, i])
            if u < 0 or (u >= nk and u < t):
                continue
            three = _flip23(new, t, u)
            o = P.orient(np.array(three))
            if np.any(o == 0):
                continue
            cav2 = cav.copy()
            if u < nk:
                cav2[kept_ids[u]] = True
            rows = [r for k, r in enumerate(new.tolist()) if k >= nk and k not in (t, u)] + three
            new2, nn2 = _stitch(cand, cav2, rows)
            assert not _both(P, first, cav2, new2, nn2).ok
            tried["inside" if u >= nk else "next to"] += 1
            s = P.orient(np.array([new[t], new[u]]))
            tried["overlap"] += int(len(set(o.tolist())) > 1 or o[0] != s[0])
    assert tried["inside"] and tried["next to"], tried


@pytest.mark.parametrize("seed", SEEDS)
def test_a_failing_simplex_left_in_is_rejected(seed):
    """The cavity must hold every failing simplex of the first pass: with one of the
    flipped tetrahedra left in (and the rest of the regular triangulation around it) the
    stitch is rejected, by the whole check."""
    P, T, cand, first, cav = _case(seed)
    truth = {tuple(r) for r in T.tolist()}
    wrong = [t for t in np.flatnonzero(first.bad) if tuple(cand[t].tolist()) not in truth]
    cav2 = cav.copy()
    cav2[wrong[0]] = False
    fill = _fill(T, cand, cav2)
    new, nn = _stitch(cand, cav2, fill)
    assert not _both(P, first, cav2, new, nn).ok


@pytest.mark.parametrize("seed", SEEDS)
def test_wrong_links_across_the_region_fall_back_to_the_whole_check(seed):
    """Neighbour links that do not match the facets (swapped slots of a new simplex, a
    link into a kept simplex that does not share the facet): the local check refuses
    them and the whole check decides (it sorts the facets itself)."""
    P, T, cand, first, cav = _case(seed)
    new, nn = _stitch(cand, cav, _fill(T, cand, cav))
    nk = int(np.count_nonzero(~cav))
    bad_nn = nn.copy()
    bad_nn[nk, [0, 1]] = bad_nn[nk, [1, 0]]
    local = _both(P, first, cav, new, bad_nn)
    assert local.ok == certify(P, new).ok
    bad_nn = nn.copy()
    bad_nn[nk, 0] = 0 if nn[nk, 0] != 0 else 1
    _both(P, first, cav, new, bad_nn)


@pytest.mark.parametrize("seed", [5, 6])
def test_rounded_coordinates_agree_on_every_single_deletion(seed):
    """Co-planar and co-spherical centres (coordinates rounded to integers): the local
    and the whole check agree on the right stitch and on each simplex removed."""
    P, T, cand, first, cav = _case(seed, n=120, rounded=True)
    fill = _fill(T, cand, cav)
    new, nn = _stitch(cand, cav, fill)
    assert _both(P, first, cav, new, nn).ok
    for j in range(0, len(fill), max(1, len(fill) // 8)):
        new, nn = _stitch(cand, cav, fill[:j] + fill[j + 1 :])
        assert not _both(P, first, cav, new, nn).ok


def _ball_cut_out_case():
    """A 3x3 grid without its centre (2D) whose candidate leaves out ball 5 = (2, 0):
    the regular triangulation's [3, 5, 6] is missing, so the ball lies outside the
    candidate's union (found by the fuzzing of the second reader, issue 25)."""
    c = np.array([[0, 0], [0, 1], [0, 2], [1, 0], [1, 2], [2, 0], [2, 1], [2, 2]], dtype=float)
    r = np.array(
        [
            0.7377766191326491,
            0.7776346925578066,
            0.4089836078472413,
            0.3524881744533123,
            0.6052490561587722,
            0.4855814952455459,
            0.7472735728717307,
            0.523931343205731,
        ]
    )
    P = WeightedPoints(c, r)
    cand = np.array([[0, 1, 3], [4, 6, 7], [1, 3, 6], [1, 2, 6], [2, 4, 6]], dtype=np.int64)
    return P, cand


def test_a_ball_the_first_pass_cannot_locate_is_not_called_hidden():
    """The first pass walks in its sane simplices; a ball it cannot locate there must
    stay unlocated (-1), not be taken as lying in the last sane simplex (``sane[-1]``)
    and then be "hidden" by a simplex that does not contain it.  Oracle: the exact
    orientation tests of each claimed location."""
    P, cand = _ball_cut_out_case()
    first = _first_pass(P, cand)
    assert first.q.tolist() == [5]
    for q, t, h in zip(first.q, first.loc, first.hidden):
        if t >= 0:
            s = int(P.orient(cand[t : t + 1])[0])
            for i in range(cand.shape[1]):
                row = cand[t].copy()
                row[i] = q
                assert int(P.orient(row[None, :])[0]) * s >= 0, (q, t)
        else:
            assert not h
    assert first.loc.tolist() == [-1] and first.bad[2]  # the simplex it starts from


def test_a_stitch_that_leaves_a_ball_outside_is_rejected_by_both():
    """Before the fix the local check accepted this stitch (it trusted a wrong
    "hidden" from the first pass) while the whole certificate rejects it: ball 5 lies
    outside the stitched union, whose boundary is still closed and convex."""
    P, cand = _ball_cut_out_case()
    first = _first_pass(P, cand)
    cav = np.zeros(len(cand), dtype=bool)
    cav[[3, 4]] = True
    new = np.array([[0, 1, 3], [4, 6, 7], [1, 3, 6], [1, 2, 4], [1, 4, 6]], dtype=np.int64)
    nn = facet_adjacency(new)[0]
    assert not certify(P, new, nn).ok
    assert not _both(P, first, cav, new, nn).ok


def test_repair_of_a_candidate_that_leaves_a_ball_outside_is_the_regular_triangulation():
    """End to end: before the fix :func:`repair` returned a triangulation without
    ball 5 (the whole certificate rejects it).  Oracle: the exact incremental road."""
    from shapelab._engine.incremental import incremental_triangulation

    P, cand = _ball_cut_out_case()
    fixed = repair(P, cand, max_fraction=1.0)
    assert fixed is not None and certify(P, fixed[0]).ok
    truth = {tuple(r) for r in incremental_triangulation(P).tolist()}
    assert {tuple(r) for r in np.sort(fixed[0], axis=1).tolist()} == truth


def _left_out_case(seed):
    """Balls on a small integer grid (2D or 3D: co-circular and co-planar centres) and
    a candidate that lost the star of one vertex or one simplex on the hull, so balls
    are left out of it and its hull is wrong; ``None`` if the candidate has no failing
    simplex (the failure is global) or the cavity would be everything."""
    from shapelab._engine.incremental import incremental_triangulation

    rng = np.random.default_rng(seed)
    d = 2 + seed % 2
    c = np.unique(rng.integers(0, 3, size=(12 + 2 * d, d)).astype(float), axis=0)
    P = WeightedPoints(c, 0.3 + 0.5 * rng.random(len(c)))
    T = incremental_triangulation(P)
    if T.shape[1] != d + 1:  # pragma: no cover - flat draw
        return None
    nbr, _ = facet_adjacency(T)
    if seed % 4 < 2:
        cand = T[~np.any(T == rng.integers(len(c)), axis=1)]
    else:
        hull = np.flatnonzero(np.any(nbr == -1, axis=1))
        cand = np.delete(T, hull[rng.integers(hull.size)], axis=0)
    if cand.shape[0] == 0:  # pragma: no cover
        return None
    first = _first_pass(P, cand)
    cav = first.bad | _grow(cand, first.nbr, first.bad, P.n, int(rng.integers(0, 2)))
    if not first.bad.any() or cav.all():
        return None
    return P, T, cand, first, cav


# seeds 749, 1068, 1164 and 1229 broke the local check before the first pass kept
# unlocated balls unlocated (found by a search over 1,500 seeds)
@pytest.mark.parametrize("seed", [*range(24), 749, 1068, 1164, 1229])
def test_stitches_of_candidates_with_balls_left_out_agree_with_the_whole_certificate(seed):
    """The first pass's claims about balls left out (located in a kept simplex and
    hidden there) are what the local check skips condition 6 on: on every stitch (the
    regular triangulation's rows in the cavity, then each with one row missing, which
    can leave a ball outside a still convex union) the local and the whole check agree,
    and what they accept is the regular triangulation (oracle: the exact incremental
    road)."""
    case = _left_out_case(seed)
    if case is None:
        pytest.skip("the candidate has no local failure")
    P, T, cand, first, cav = case
    truth = {tuple(r) for r in T.tolist()}
    fill = _fill(T, cand, cav)
    for j in range(-1, len(fill)):
        new, nn = _stitch(cand, cav, fill if j < 0 else fill[:j] + fill[j + 1 :])
        if _both(P, first, cav, new, nn).ok:
            assert {tuple(r) for r in new.tolist()} == truth and len(new) == len(truth)
