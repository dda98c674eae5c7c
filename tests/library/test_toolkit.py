"""The internal toolkit (shapelab._toolkit) against numpy and brute force."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab._toolkit import geometry, lazy, unionfind, validate


def test_dot_and_cross_equal_numpy():
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(2, 3, 50))
    np.testing.assert_allclose(geometry.dot(a, b), np.einsum("km,km->m", a, b), rtol=1e-15)
    np.testing.assert_array_equal(geometry.cross(a, b), np.cross(a.T, b.T).T)
    np.testing.assert_array_equal(geometry.cross_rows(a.T, b.T), np.cross(a.T, b.T))
    # tuples of components work too
    np.testing.assert_array_equal(geometry.cross(tuple(a), tuple(b)), geometry.cross(a, b))


@pytest.mark.parametrize("d", [2, 3])
def test_morton_order_is_a_permutation_that_groups_neighbours(d):
    rng = np.random.default_rng(1)
    x = rng.uniform(size=(5000, d))
    p = geometry.morton_order(x)
    np.testing.assert_array_equal(np.sort(p), np.arange(5000))
    step = np.linalg.norm(np.diff(x[p], axis=0), axis=1).mean()
    assert step < 0.5 * np.linalg.norm(np.diff(x, axis=0), axis=1).mean()
    np.testing.assert_array_equal(geometry.morton_order(x[:10]), np.arange(10))


@settings(max_examples=50)
@given(st.integers(1, 12), st.lists(st.tuples(st.integers(0, 11), st.integers(0, 11)), max_size=30))
def test_elder_merges_matches_brute_force_components(n, edges):
    edges = [(a % n, b % n) for a, b in edges]
    u = np.array([e[0] for e in edges], dtype=np.int64)
    v = np.array([e[1] for e in edges], dtype=np.int64)
    merges = []
    parent, oldest = unionfind.elder_merges(
        n, u, v, np.arange(len(edges)), list(range(n)), lambda e, a, b, old: merges.append((e, old[a], old[b]))
    )
    # brute force: components by repeated relabelling; the elder is the smallest index
    label = list(range(n))
    expected = []
    for e, (a, b) in enumerate(edges):
        la, lb = label[a], label[b]
        if la != lb:
            expected.append((e, min(la, lb), max(la, lb)))
            label = [min(la, lb) if x in (la, lb) else x for x in label]
    assert merges == expected
    roots = {i for i in range(n) if parent[i] == i}
    assert sorted(oldest[r] for r in roots) == sorted(set(label))


def test_readonly_and_freeze():
    a = validate.readonly([1, 2, 3], np.float64)
    assert a.dtype == np.float64 and not a.flags.writeable
    s = validate.readonly(np.array(["C", "N"]))
    assert s.dtype.kind == "U" and not s.flags.writeable
    b = np.zeros(3)
    assert validate.freeze(b) is b and not b.flags.writeable


def test_as_bbox_names_the_argument():
    np.testing.assert_array_equal(validate.as_bbox([0, 0, 1, 1], 2), [[0, 0], [1, 1]])
    with pytest.raises(ValueError, match="bbox"):
        validate.as_bbox([[1, 1], [0, 0]], 2)
    with pytest.raises(ValueError, match="bbox"):
        validate.as_bbox([[0, 0], [np.inf, 1]], 2)


def test_lazy_attach_reexports_on_first_access():
    import shapelab

    assert shapelab.Balls is shapelab.balls.Balls
    assert {"Balls", "plot", "__version__"} <= set(dir(shapelab))
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        shapelab.nope
    getattr_, dir_ = lazy.attach("shapelab.check", {"value": "_runner"})
    assert getattr_("value") is shapelab.check.value
