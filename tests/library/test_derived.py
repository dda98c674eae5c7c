"""Derived results live on the Filtration (Notes §23.1; issue 11): no module-level cache."""

from __future__ import annotations

import dataclasses
import gc
import weakref

import numpy as np

import shapelab as sl
from shapelab import cavities, filtration
from shapelab._engine import persistence as topology  # the engine holds summary()
from shapelab.cavities import complement as _pockets


def _ring(n=12, radius=3.0, r=0.9):
    t = 2 * np.pi * np.arange(n) / n
    return sl.Balls(radius * np.c_[np.cos(t), np.sin(t)], r)


def test_a_used_filtration_leaves_nothing_behind():
    F = sl.alpha_filtration(sl.datasets.fullerene_c60())
    F.persistence(), F.betti(0.0), sl.voids(F, 0.0)
    sl.pockets(F, 0.0), sl.tunnels(F, 0.0)
    F.balls  # the balls come from the filtration
    assert {"topology.summary", "topology.pairs", "cavities.sealed_at"} <= set(F._derived)
    ref = weakref.ref(F)
    del F
    gc.collect()
    assert ref() is None


def test_no_module_level_caches():
    for mod in (topology, cavities, filtration):
        for name, value in vars(mod).items():
            assert not isinstance(value, (weakref.WeakKeyDictionary, weakref.WeakValueDictionary)), (mod, name)
    for name in ("_CACHE", "_PAIR_CACHE", "_cached"):
        assert not hasattr(topology, name)
    for name in ("_TREES", "_CYCLES", "_EDGE_KEYS"):
        assert not hasattr(cavities, name)


def test_derived_results_are_computed_once():
    F = sl.alpha_filtration(_ring())
    calls = []

    def build(G):
        calls.append(G)
        return object()

    a = F.derived("test.thing", build)
    assert F.derived("test.thing", build) is a and calls == [F]
    S = topology.summary(F)
    F.betti(0.5), F.betti_curve([0.0, 1.0]), F.persistence(), sl.voids(F, 0.0)
    assert topology.summary(F) is S
    T = _pockets.merge_tree(F)
    sl.pockets(F, 0.0)
    assert _pockets.merge_tree(F) is T


def test_a_copy_derives_afresh_and_equals():
    F = sl.alpha_filtration(_ring())
    P = F.persistence()
    G = dataclasses.replace(F)
    assert G._derived == {} and G.balls is F.balls
    Q = G.persistence()
    assert topology.summary(G) is not topology.summary(F)
    assert all(np.array_equal(P[k], Q[k]) for k in P)
    assert "_derived" not in repr(F)


def test_duck_typed_filtrations_keep_nothing():
    class Plain:
        def __init__(self, F):
            self.balls, self.dimension, self._F = F.balls, F.dimension, F

        def simplices(self, k):
            return self._F.simplices(k)

        def values(self, k):
            return self._F.values(k)

        def boundary(self, k):
            return self._F.boundary(k)

    F = sl.alpha_filtration(_ring())
    G = Plain(F)
    assert topology.betti(G, 0.0) == F.betti(0.0)
    assert topology.summary(G) is not topology.summary(G)
