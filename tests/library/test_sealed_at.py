"""The complement's history in plain code (issue 33): ``sealed_at`` and
``cells_when_sealed`` are the elder rule and the definition, ``merge_tree`` the fast
kernel that ``pockets`` reads; they agree, and the plain functions meet the definition
checked by brute force with ``complement_labels`` at the times themselves."""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl
from shapelab._engine.mouths import cells_at_closing
from shapelab._engine.persistence import summary
from shapelab.cavities.complement import cells_when_sealed, complement_labels, merge_tree, sealed_at


def _random(seed: int, dim: int, n: int) -> sl.Filtration:
    rng = np.random.default_rng(seed)
    return sl.alpha_filtration(sl.Balls(rng.uniform(0, 6, (n, dim)), rng.uniform(0.3, 1.0, n)))


def _grid(dim: int) -> sl.Filtration:
    """Equal balls on a lattice: ties everywhere (many facets sealed at one time)."""
    axes = [np.arange(4.0)] * dim
    pts = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, dim)
    return sl.alpha_filtration(sl.Balls(pts, 0.6))


CASES = {
    **{f"random-2d-{s}": (lambda s=s: _random(s, 2, 120)) for s in range(4)},
    **{f"random-3d-{s}": (lambda s=s: _random(s, 3, 80)) for s in range(3)},
    "grid-2d": lambda: _grid(2),
    "grid-3d": lambda: _grid(3),
    "figure-23-2": lambda: sl.alpha_filtration(sl.datasets.figure_23_2()[0]),
}


@pytest.fixture(params=sorted(CASES), scope="module")
def F(request):
    return CASES[request.param]()


def test_the_plain_pass_equals_the_kernel(F):
    T = merge_tree(F)
    np.testing.assert_array_equal(sealed_at(F), T.kill_value)
    fills = summary(F).values[F.balls.dim]
    roots = np.flatnonzero(fills > sealed_at(F))
    assert roots.size > 0
    for r in roots.tolist():
        np.testing.assert_array_equal(cells_when_sealed(F, r), cells_at_closing(T, r))


def test_the_plain_functions_meet_the_definition(F):
    """At ``b = sealed_at[r]`` the part of ``r`` holds no elder node (not the outside,
    no cell filled later); just before ``b`` it does (it was not yet sealed off)."""
    S = summary(F)
    k = S.k
    fills = S.values[k]
    n = fills.shape[0]
    b = sealed_at(F)
    rank = np.argsort(np.lexsort((np.arange(n), fills)))  # filtration order of the cells
    for r in np.flatnonzero(fills > b).tolist():
        lab, _ = complement_labels(F, S, float(b[r]))
        part = np.flatnonzero(lab[:n] == lab[r])
        assert lab[n] != lab[r], "sealed off, not the outside"
        assert rank[part].max() == rank[r], "r fills last in its part"
        np.testing.assert_array_equal(part, cells_when_sealed(F, r))
        lab, _ = complement_labels(F, S, float(np.nextafter(b[r], -np.inf)))
        elder = np.flatnonzero(lab[:n] == lab[r])
        assert lab[n] == lab[r] or rank[elder].max() > rank[r], "joined to an elder part before"


def test_voids_are_born_when_sealed(F):
    for v in sl.voids(F, 0.0):
        assert v.born == sealed_at(F)[int(v.cell_ids.max())]


def test_every_cell_not_only_the_roots_of_voids(F):
    T = merge_tree(F)
    n = sealed_at(F).shape[0]
    for r in range(0, n, max(1, n // 40)):
        np.testing.assert_array_equal(cells_when_sealed(F, r), cells_at_closing(T, r))


def test_bad_input_is_refused_by_name():
    ring = sl.datasets.ring(12)
    assert sealed_at(ring).shape == (10,)  # Balls are filtered first, as for voids
    assert sealed_at(sl.Balls([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], 0.3)).shape == (0,)  # no cells
    for r, err in ((-1, ValueError), (10, ValueError), (1.5, TypeError), (True, TypeError)):
        with pytest.raises(err, match="^r must"):
            cells_when_sealed(ring, r)
