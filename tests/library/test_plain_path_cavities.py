"""The plain path (``precision="fast"``) equals the exact path on generic input
(issue 33): the same pockets, mouths and flow, and union measures to 1e-12 relative."""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl


def _balls(d, n, seed):
    rng = np.random.default_rng(seed)
    return sl.Balls(rng.uniform(0, 10, (n, d)), rng.uniform(0.8, 1.6, n))


@pytest.mark.parametrize("d, n, seed", [(2, 40, 0), (2, 60, 1), (3, 40, 2), (3, 70, 3)])
@pytest.mark.parametrize("tau", [-0.3, 0.0, 0.7])
def test_union_measure_plain_equals_exact(d, n, seed, tau):
    B = _balls(d, n, seed)
    F = sl.alpha_filtration(B)
    for src in (B, F):
        exact = sl.union_measure(src, tau)
        fast = sl.union_measure(src, tau, precision="fast")
        assert fast.counts == exact.counts
        np.testing.assert_allclose(fast.measure, exact.measure, rtol=1e-12)
        np.testing.assert_allclose(fast.boundary, exact.boundary, rtol=1e-12)
        np.testing.assert_allclose(fast.ball_measure, exact.ball_measure, rtol=1e-12, atol=1e-12 * exact.measure)


def test_union_measure_exact_is_the_default_path():
    B = _balls(3, 30, 5)
    assert sl.union_measure(B, 0.2).measure == sl.union_measure(B, 0.2, precision="exact").measure
    with pytest.raises(ValueError, match="precision"):
        sl.union_measure(B, precision="float")


@pytest.mark.parametrize("d, n, seed", [(2, 60, 10), (2, 90, 11), (3, 60, 12), (3, 90, 13)])
@pytest.mark.parametrize("tau", [-0.2, 0.0, 0.5])
def test_pockets_and_flow_plain_equal_exact(d, n, seed, tau):
    F = sl.alpha_filtration(_balls(d, n, seed))
    for method in ("growth", "flow"):
        exact = sl.pockets(F, tau, method=method)
        fast = sl.pockets(F, tau, method=method, precision="fast")
        assert [p.cell_ids.tolist() for p in fast] == [p.cell_ids.tolist() for p in exact]
        assert [p.mouth_ids.tolist() for p in fast] == [p.mouth_ids.tolist() for p in exact]
        assert [(p.closes_at, p.fills_at) for p in fast] == [(p.closes_at, p.fills_at) for p in exact]
    a, b = sl.discrete_flow(F, tau), sl.discrete_flow(F, tau, precision="fast")
    assert np.array_equal(a.flows, b.flows) and np.array_equal(a.sink, b.sink)
    assert np.array_equal(a.region, b.region)


def test_plain_mouth_is_the_definition_on_the_flask():
    from shapelab.cavities.mouths import mouth

    F = sl.alpha_filtration(sl.datasets.figure_23_2()[0])
    for p in sl.pockets(F):
        assert mouth(F, 0.0, p.cell_ids).tolist() == p.mouth_ids.tolist()


@pytest.mark.parametrize("d, n, seed", [(2, 60, 20), (3, 60, 21)])
def test_voids_and_tunnels_have_one_path(d, n, seed):
    """Voids and tunnels make no floating-point decision of their own (the
    filtration's values decide): the same cells at every τ, asked twice."""
    F = sl.alpha_filtration(_balls(d, n, seed))
    for tau in (-0.2, 0.0, 0.5):
        assert [v.cell_ids.tolist() for v in sl.voids(F, tau)] == [
            v.cell_ids.tolist() for v in sl.voids(sl.alpha_filtration(F.balls), tau)
        ]
        if d == 3:
            assert [t.edge_ids.tolist() for t in sl.tunnels(F, tau)] == [
                t.edge_ids.tolist() for t in sl.tunnels(sl.alpha_filtration(F.balls), tau)
            ]


def test_the_flow_plain_path_can_differ_at_a_tie():
    """A right triangle: the exact path finds no flow (a tie); the test on floats is
    free to decide either way, and the exact path's answer is the sign 0."""
    F = sl.alpha_filtration(sl.Balls([[-1.0, 0.0], [1.0, 0.0], [0.0, 1.0]], 0.0))
    assert not sl.discrete_flow(F, -1.0).flows.any()
