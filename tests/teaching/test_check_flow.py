"""check.flow_order (lesson 09) passes an order by the orthosphere's power and refuses
the plausible wrong ones: the order given, the reverse, the circumradius that ignores the
weights, the area, an order with a repeat."""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl
from shapelab import check


def _rho(balls, c, weighted=True):
    z = balls.centers[c]
    w = balls.radii[c] ** 2 if weighted else np.zeros(len(c))
    A = 2 * (z[1:] - z[0])
    b = (z[1:] ** 2).sum(1) - w[1:] - (z[0] ** 2).sum() + w[0]
    y = np.linalg.solve(A, b)
    return float(((y - z[0]) ** 2).sum() - w[0])


def by_power(balls, cells):
    return sorted(range(len(cells)), key=lambda n: _rho(balls, cells[n]))


WRONG = {
    "the order given": lambda balls, cells: list(range(len(cells))),
    "the reverse": lambda balls, cells: by_power(balls, cells)[::-1],
    "the circumradius of the centres (weights ignored)": lambda balls, cells: sorted(
        range(len(cells)), key=lambda n: _rho(balls, cells[n], weighted=False)
    ),
    "by area": lambda balls, cells: sorted(
        range(len(cells)), key=lambda n: abs(np.linalg.det(balls.centers[cells[n]][1:] - balls.centers[cells[n]][0]))
    ),
    "one index twice": lambda balls, cells: by_power(balls, cells)[:-1] + by_power(balls, cells)[:1],
    "one index missing": lambda balls, cells: by_power(balls, cells)[:-1],
    "None": lambda balls, cells: None,
}


def test_flow_order_passes_the_order_by_power(capsys):
    assert check.flow_order(by_power)
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize("name", sorted(WRONG))
def test_flow_order_refuses(name, capsys):
    assert not check.flow_order(WRONG[name])
    out = capsys.readouterr().out
    assert "✗" in out and "✓" not in out


def test_flow_order_cases_have_a_triangle_with_two_arrows():
    """The premise of the docstring: among the unequal disks a triangle flows across two
    edges, so 'the one successor' is not the flow."""
    rng = np.random.default_rng(11)
    F = sl.alpha_filtration(sl.Balls(rng.uniform(-5, 5, (40, 2)), rng.uniform(0.3, 1.6, 40)))
    flows = [sl.discrete_flow(F, 0.0).flows.sum(axis=1).max()]
    rng2 = np.random.default_rng(3)
    F2 = sl.alpha_filtration(sl.Balls(rng2.uniform(-5, 5, (60, 2)), rng2.uniform(0.3, 1.5, 60)))
    flows.append(sl.discrete_flow(F2, 0.0).flows.sum(axis=1).max())
    assert max(flows) == 2


def test_flow_order_refuses_what_is_not_a_function(capsys):
    assert not check.flow_order(None)
    assert "expected a function" in capsys.readouterr().out
