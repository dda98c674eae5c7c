"""shapelab.ranking: features that predict a binding site, the default score and its filters (Notes §23.1).

Oracles: closed forms (the depth of a point in a cube of points, a point inside a
ball blocked in every direction, a ball beyond the rays' reach blocking none, the
solid angle of a ball seen from a point), shapes with a known answer by construction
(a deep flask carved in a block of balls against a shallow dent cut into its top
face), and invariants of the filters (a larger minimum keeps a subset, ``top=k`` is a
prefix of the full ranking), on random features (hypothesis) and on a real report.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import shapelab as sl
from shapelab.datasets import structure_path

R = importlib.import_module("shapelab.ranking")


def _features(balls, lining, volume=10.0, persistence=1.0, **kw):
    m = len(lining)
    return R.pocket_features(
        balls,
        lining,
        volume=[volume] * m,
        area=[20.0] * m,
        mouth_area=[5.0] * m,
        persistence=[persistence] * m,
        **kw,
    )


def block_with_flask_and_dent(n=10, seed=0):
    """A block of n³ balls (spacing 1, radius 0.9: no gaps), slightly jittered, with a
    flask carved in it (a chamber of radius 2.6 whose neck of radius 1.3 opens on the
    top face) and a shallow spherical dent cut into the top face.  Returns the balls,
    the chamber's centre, and the lining of each (balls within 1.6 of the carved
    region's centre line or cap)."""
    g = np.arange(n, dtype=np.float64)
    P = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    top = n - 1.0
    chamber = np.array([3.0, 4.5, top - 4.5])
    dent = np.array([7.0, 4.5, top + 1.6])
    d_ch = np.linalg.norm(P - chamber, axis=1)
    d_axis = np.linalg.norm(P[:, :2] - chamber[:2], axis=1)
    d_dent = np.linalg.norm(P - dent, axis=1)
    carved = (d_ch < 2.6) | ((d_axis < 1.3) & (P[:, 2] > chamber[2])) | (d_dent < 2.8)
    P = P + np.random.default_rng(seed).normal(scale=0.03, size=P.shape)
    keep = ~carved
    balls = sl.Balls(P[keep], 0.9)
    flask = np.flatnonzero(((d_ch < 3.7) | ((d_axis < 2.4) & (P[:, 2] > chamber[2])))[keep])
    dent_lining = np.flatnonzero((d_dent < 3.9)[keep])
    return balls, chamber, flask, dent_lining


@pytest.fixture(scope="module")
def flask_block():
    return block_with_flask_and_dent()


# ------------------------------------------------------------------ closed forms
def test_depth_in_a_cube_of_points():
    g = np.arange(11, dtype=np.float64)
    P = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    balls = sl.Balls(P, 0.5)
    at = lambda *x: int(np.flatnonzero((P == x).all(axis=1))[0])  # noqa: E731
    # centroids of one atom: the cube's centre, a point 1 from a face, a corner
    f = _features(balls, [[at(5, 5, 5)], [at(5, 5, 1)], [at(0, 0, 0)]])
    np.testing.assert_allclose(f.depth, [5.0, 1.0, 0.0], atol=1e-12)
    np.testing.assert_array_equal(f.n_lining, [1, 1, 1])
    np.testing.assert_allclose(f.center[1], [5, 5, 1])


def test_buriedness_closed_forms():
    # the lining centroid inside a ball: every ray starts in it
    c = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [30.0, 0.0, 0.0], [0.5, 20.0, 0.0], [0.5, 20.0, 10.0]]
    balls = sl.Balls(c, [2.0, 0.1, 1.0, 0.1, 0.1])
    f = _features(balls, [[0, 1], [3, 4]])
    assert f.buriedness[0] == 1.0
    # from (0.5, 20, 5), midway between balls 3 and 4 (cones of half-angle 0.02 rad about
    # the z axis, which no Fibonacci direction enters: |z| <= 1 - 1/60), ball 0 (20.6
    # away) and the others lie beyond a 10 Å reach
    assert f.buriedness[1] == 0.0


@pytest.mark.parametrize("d, r", [(5.0, 2.0), (4.0, 3.0), (8.0, 5.0)])
def test_buriedness_is_the_solid_angle_of_a_ball(d, r):
    """A single ball of radius r at distance d blocks the directions of a cone of
    half-angle asin(r/d): a share (1 - cos)/2 of the sphere, to the resolution of
    N_DIRECTIONS directions (each direction weighs 1/60; the cap's boundary crosses a
    few of them)."""
    # the centre: midway between two tiny lining balls on the z axis, which no
    # direction meets (|z| <= 1 - 1/60 for every Fibonacci direction)
    balls = sl.Balls([[0.0, 0.0, -50.0], [0.0, 0.0, 50.0], [d, 0.0, 0.0]], [0.1, 0.1, r])
    f = _features(balls, [[0, 1]], reach=100.0)
    cap = (1 - np.sqrt(1 - (r / d) ** 2)) / 2
    assert abs(f.buriedness[0] - cap) <= 3.0 / R.N_DIRECTIONS
    # a ray must reach the ball: with reach below d - r nothing is blocked
    assert _features(balls, [[0, 1]], reach=d - r - 0.01).buriedness[0] == 0.0


def test_openness_is_the_open_share_of_the_boundary():
    balls = sl.Balls(np.eye(3) * 3, 1.0)
    f = R.pocket_features(balls, [[0], [1]], volume=[1, 1], area=[30, 10], mouth_area=[10, 0], persistence=[0, 0])
    np.testing.assert_allclose(f.openness, [0.25, 0.0])


# ------------------------------------------------------------ shapes by construction
def test_a_deep_flask_outranks_a_shallow_dent(flask_block):
    balls, chamber, flask, dent = flask_block
    f = _features(balls, [dent, flask])  # same volume, area, mouth and persistence
    assert f.buriedness[1] > f.buriedness[0] + 0.1
    assert f.depth[1] > f.depth[0] + 1.0
    s = R.rank_score(f)
    assert s[1] > s[0]
    assert R.rank_order(f, min_persistence=0, min_volume=0).tolist() == [1, 0]


def test_report_ranks_the_flask_first(flask_block):
    """End to end: the report's first row by score is the flask's chamber (its lining
    centroid within 2 Å of the chamber's centre), and every row's score is at most
    the one before."""
    balls = flask_block[0]
    rep = sl.report(balls, 0.0, rank="score", min_volume=0, min_persistence=0)
    first = rep.rows[0]
    assert first.kind == "pocket"
    assert np.linalg.norm(balls.centers[list(first.lining_atoms)].mean(axis=0) - flask_block[1]) < 2.0
    scores = [r.score for r in rep.rows]
    assert scores == sorted(scores, reverse=True)
    assert [r.id for r in rep.rows] == list(range(1, len(rep.rows) + 1))


# ------------------------------------------------------------------ the filters
@given(
    st.lists(st.tuples(st.floats(0, 100), st.floats(0, 10), st.floats(0, 1)), min_size=1, max_size=30),
    st.floats(0, 100),
    st.floats(0, 100),
    st.floats(0, 10),
    st.floats(0, 10),
    st.integers(1, 40),
)
def test_filters_are_monotone(rows, v1, v2, p1, p2, top):
    balls = sl.Balls(np.random.default_rng(0).normal(size=(8, 3)) * 3, 1.0)
    m = len(rows)
    f = R.pocket_features(
        balls,
        [[k % 8] for k in range(m)],
        volume=[r[0] for r in rows],
        area=[10.0] * m,
        mouth_area=[r[2] * 10 for r in rows],
        persistence=[r[1] for r in rows],
    )
    lo_v, hi_v = sorted((v1, v2))
    lo_p, hi_p = sorted((p1, p2))
    loose = R.rank_order(f, min_volume=lo_v, min_persistence=lo_p)
    tight = R.rank_order(f, min_volume=hi_v, min_persistence=hi_p)
    assert set(tight.tolist()) <= set(loose.tolist())
    # the filters only remove: the kept ones stay in the same relative order
    assert [k for k in loose.tolist() if k in set(tight.tolist())] == tight.tolist()
    assert R.rank_order(f, min_volume=lo_v, min_persistence=lo_p, top=top).tolist() == loose[:top].tolist()
    # exactly the cavities that pass both thresholds
    expect = {k for k in range(m) if f.volume[k] >= lo_v and f.persistence[k] >= lo_p}
    assert set(loose.tolist()) == expect


@pytest.fixture(scope="module")
def hvr():
    """HIV-1 protease without its inhibitor (and without any HETATM record)."""
    return sl.read_structure(structure_path("1hvr"), hetatm=False)


def test_report_filters_are_monotone_on_a_protein(hvr):
    def keys(**kw):
        return [r.lining_atoms for r in sl.report(hvr, 1.4, rank="score", **kw).rows]

    all_rows = keys(min_volume=0, min_persistence=0)
    prev = all_rows
    for v in (1.0, 5.0, 20.0, 100.0):
        cur = keys(min_volume=v, min_persistence=0)
        assert [k for k in prev if k in set(cur)] == cur  # a subset, in the same order
        prev = cur
    prev = all_rows
    for p in (0.1, 0.5, 2.0):
        cur = keys(min_volume=0, min_persistence=p)
        assert [k for k in prev if k in set(cur)] == cur
        prev = cur
    assert keys(min_volume=0, min_persistence=0, top=4) == all_rows[:4]


def test_rank_none_is_the_old_table(hvr):
    """rank="none" with its default filters is the report as it was: every row, voids
    first, each kind by volume, and the CSV and Markdown without the ranking's columns
    or the line on ranking and filters."""
    old = sl.report(hvr, 1.4, rank="none")
    same = sl.report(hvr, 1.4, rank="none", method="growth", min_persistence=0.0, min_volume=0.0)
    assert old._csv_text() == same._csv_text() and old.to_markdown() == same.to_markdown()
    assert old._csv_text().splitlines()[0].endswith("lining_residues,lining_atoms")
    kinds = [r.kind for r in old.rows]
    assert kinds == sorted(kinds, key=lambda k: k != "void")
    assert all(r.score is None for r in old.rows)
    assert old.found == len(old.rows) and "filtered out" not in old.to_markdown()
    assert old.to_markdown().splitlines()[4].startswith("| kind |")  # title, blank, counts, blank, table


def test_the_default_is_the_ranking_and_says_what_it_dropped(hvr):
    """The default report is rank="score" with the ranking's default filters; its
    Markdown names the order and the filter, and counts what was left out against
    the unfiltered table (rank="none": every cavity)."""
    from shapelab.ranking import DEFAULT_MIN_PERSISTENCE, DEFAULT_MIN_VOLUME

    default = sl.report(hvr, 1.4)
    explicit = sl.report(hvr, 1.4, rank="score", min_volume=DEFAULT_MIN_VOLUME, min_persistence=DEFAULT_MIN_PERSISTENCE)
    assert default.rank == "score" and default.to_markdown() == explicit.to_markdown()
    every = sl.report(hvr, 1.4, rank="none")
    assert default.found == len(every.rows)
    small = [r for r in every.rows if r.volume_sa < DEFAULT_MIN_VOLUME]
    assert small and len(default.rows) == len(every.rows) - len(small)
    assert all(r.volume_sa >= DEFAULT_MIN_VOLUME for r in default.rows)
    line = default.to_markdown().splitlines()[4]
    assert line.startswith("Ranked best first by shapelab.ranking.rank_score")
    assert f"kept SA volume ≥ {DEFAULT_MIN_VOLUME:g} Å³" in line
    assert f": {len(default.rows)} of {len(every.rows)} cavities listed, {len(small)} filtered out" in line
    # rank="none" with a filter says so too
    some = sl.report(hvr, 1.4, rank="none", min_volume=DEFAULT_MIN_VOLUME)
    assert [r.volume_sa for r in some.rows] == [r.volume_sa for r in every.rows if r.volume_sa >= DEFAULT_MIN_VOLUME]
    assert f"{len(small)} filtered out" in some.to_markdown().splitlines()[4]


def test_ranked_outputs_have_the_ranking_columns(hvr):
    rep = sl.report(hvr, 1.4, rank="score", top=5)
    lines = rep._csv_text().splitlines()
    assert lines[0].endswith("lining_atoms,score,buriedness,depth,openness")
    assert len(lines) == 1 + len(rep.rows) <= 6
    md = rep.to_markdown().splitlines()
    header = next(k for k, line in enumerate(md) if line.startswith("| kind"))
    ncol = md[header].count("|")
    assert all(line.count("|") == ncol for line in md[header:])  # no residue label holds a "|"
    assert "Ranked best first by shapelab.ranking.rank_score" in rep.to_markdown()
    assert "kept SA volume ≥ 10 Å³, the first 5:" in rep.to_markdown()


@pytest.mark.parametrize("method", ["growth", "flow"])
def test_both_pocket_definitions_rank_alike(hvr, method):
    """The flow's pockets are measured and ranked by the same code: rank="none" lists
    every pocket of pockets(F, method=...), rank="score" orders them by the score."""
    F = sl.alpha_filtration(sl.Balls(hvr.balls.centers, hvr.balls.radii - hvr.probe + 1.4))  # the SA model
    n_pockets = len(sl.pockets(F, 0.0, method=method))
    assert len(sl.report(hvr, 1.4, method=method, rank="none").pockets) == n_pockets
    rep = sl.report(hvr, 1.4, method=method, rank="score", min_volume=0, min_persistence=0)
    assert len(rep.pockets) == n_pockets
    scores = [r.score for r in rep.rows]
    assert scores == sorted(scores, reverse=True)


@pytest.mark.parametrize(
    "kw, exc, words",
    [
        (dict(rank="best"), ValueError, "rank must be"),
        (dict(method="castp"), ValueError, "method must be"),
        (dict(min_volume=-1.0), ValueError, "min_volume"),
        (dict(min_persistence=float("nan")), ValueError, "min_persistence"),
        (dict(top=0), ValueError, "top"),
        (dict(top=2.5), TypeError, "top"),
    ],
)
def test_report_validates_the_ranking_arguments(kw, exc, words):
    with pytest.raises(exc, match=words):
        sl.report(sl.Balls(np.zeros((1, 3)), 1.0), 1.4, **kw)


def test_pocket_features_validates():
    b = sl.Balls(np.eye(3), 1.0)
    with pytest.raises(ValueError, match="volume"):
        R.pocket_features(b, [[0]], volume=[1, 2], area=[1], mouth_area=[0], persistence=[0])
    with pytest.raises(ValueError, match="lining"):
        R.pocket_features(b, [[5]], volume=[1], area=[1], mouth_area=[0], persistence=[0])
    with pytest.raises(TypeError, match="balls"):
        R.pocket_features(np.eye(3), [[0]], volume=[1], area=[1], mouth_area=[0], persistence=[0])
    with pytest.raises(ValueError, match="reach"):
        R.pocket_features(b, [[0]], volume=[1], area=[1], mouth_area=[0], persistence=[0], reach=0)
    with pytest.raises(TypeError, match="features"):
        R.rank_score([1, 2])


# --------------------------------------------------------- the same bits everywhere
def _buriedness_in_python_floats(centers, radii, pt, reach, dirs):
    """The ray test of pocket_features in plain Python floats, one operation at a time
    in the documented order (each correctly rounded: the same bits on every machine)."""
    blocked = 0
    for d in dirs.tolist():
        hit = False
        for c, r in zip(centers.tolist(), radii.tolist()):
            v = [c[0] - pt[0], c[1] - pt[1], c[2] - pt[2]]
            if v[0] * v[0] + v[1] * v[1] + v[2] * v[2] > (reach + max(radii.tolist())) ** 2:
                continue
            t = v[0] * d[0] + v[1] * d[1] + v[2] * d[2]
            vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
            gap = r * r - (vv - t * t)
            half = gap**0.5 if gap > 0 else 0.0
            if gap > 0 and t + half > 0 and t - half < reach:
                hit = True
                break
        blocked += hit
    return blocked / len(dirs)


def test_the_directions_are_unit_vectors_built_without_numpy_trigonometry():
    import math

    d = R._directions(R.N_DIRECTIONS)
    assert d.shape == (60, 3) and not d.flags.writeable
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, atol=1e-15)
    golden = math.pi * (3.0 - math.sqrt(5.0))
    for i in (0, 17, 59):
        k = i + 0.5
        z = 1.0 - 2.0 * k / 60
        s = math.sqrt(1.0 - z * z)
        assert d[i].tolist() == [s * math.cos(k * golden), s * math.sin(k * golden), z]


def test_grazing_rays_are_decided_as_in_plain_ieee_arithmetic():
    """Balls placed so that a ray only grazes them (their centre at distance r from the
    ray's line, to rounding): whether each is blocked depends on the last bits, and
    pocket_features decides exactly as the same formula in Python floats, operation by
    operation -- not as a BLAS matrix product, whose fused or reordered sums vary
    between libraries and CPUs (with ``v @ dirs.T`` this machine's OpenBLAS decided
    several of these 60 rays the other way)."""
    rng = np.random.default_rng(0)
    dirs = R._directions(R.N_DIRECTIONS)
    pt = np.array([0.25, -0.5, 0.75])
    centers, radii = [], []
    for j in range(R.N_DIRECTIONS):  # one small ball grazing each ray (too small to block another)
        d = dirs[j]
        u = np.cross(d, rng.normal(size=3))
        u /= np.linalg.norm(u)
        r = float(rng.uniform(0.05, 0.2))
        centers.append(pt + rng.uniform(2.0, 9.0) * d + r * u)
        radii.append(r)
    centers, radii = np.array(centers), np.array(radii)
    # lining: two tiny far-away balls whose centroid is pt
    lin = np.array([pt + [0, 0, 80.0], pt - [0, 0, 80.0]])
    balls = sl.Balls(np.vstack([centers, lin]), np.concatenate([radii, [1e-3, 1e-3]]))
    f = _features(balls, [[len(centers), len(centers) + 1]], reach=10.0)
    np.testing.assert_array_equal(f.center[0], pt)
    expect = _buriedness_in_python_floats(balls.centers, balls.radii, pt.tolist(), 10.0, dirs)
    assert f.buriedness[0] == expect
    assert 0.2 < expect < 0.8  # about half of the grazing balls block their ray: the test decides something


def test_ties_are_broken_by_volume_then_by_index():
    z = np.zeros(4)
    f = R.PocketFeatures(
        np.zeros((4, 3)), np.array([20.0, 20.0, 20.0, 30.0]), z, z, z, z, np.array([0.5, 0.5, 0.5, 0.0]), z, z
    )
    # scores: three equal, one 0; equal score and volume: the earlier index first
    assert R.rank_order(f, min_volume=0).tolist() == [0, 1, 2, 3]
    g = R.PocketFeatures(
        np.zeros((3, 3)), np.array([5.0, 7.0, 7.0]), *[np.zeros(3)] * 4, np.zeros(3), *[np.zeros(3)] * 2
    )
    assert R.rank_order(g, min_volume=0).tolist() == [1, 2, 0]  # all score 0: larger volume first


# ------------------------------------------------- a void, a flat dent, end to end
def test_a_void_is_blocked_in_every_direction():
    """A spherical chamber sealed inside a block of balls is a void: the report lists it
    as a void (not a pocket) and first, every ray from its centre meets the wall
    (buriedness 1), it has no mouth (openness 0), and its depth is the distance from
    its centre to the nearest face of the block (the hull of the atom centres)."""
    n = 10
    g = np.arange(n, dtype=np.float64)
    P = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    chamber = np.array([4.5, 4.5, 3.5])
    carved = np.linalg.norm(P - chamber, axis=1) < 2.2
    P = P + np.random.default_rng(3).normal(scale=0.02, size=P.shape)
    balls = sl.Balls(P[~carved], 0.9)
    rep = sl.report(balls, 0.0, rank="score", min_volume=0)
    assert len(rep.voids) == 1 and rep.rows[0].kind == "void" and rep.rows[0].id == 1
    v = rep.rows[0]
    centre = balls.centers[list(v.lining_atoms)].mean(axis=0)
    assert np.linalg.norm(centre - chamber) < 0.3
    assert v.buriedness == 1.0 and v.openness == 0.0 and v.mouths == 0
    assert abs(v.depth - (centre[2] - balls.centers[:, 2].min())) < 0.15  # the bottom face is the nearest


def test_a_flat_dent_is_shallow(flask_block):
    """The dent cut into the top face of the block: its lining centroid lies just below
    that face, and its depth is the distance to it (the nearest face of the hull)."""
    balls, _, _, dent = flask_block
    f = _features(balls, [dent])
    c = balls.centers[dent].mean(axis=0)
    top = balls.centers[:, 2].max()
    assert f.depth[0] == pytest.approx(top - c[2], abs=0.15)
    assert f.depth[0] < 1.5 and f.buriedness[0] < 1.0
