"""The filtration order (:func:`shapelab._engine.alpha.filtration_order`): by value, ties
broken lexicographically by the rows.

Oracle: ``np.lexsort`` on the float values and every column, the definition; on
values with many ties, both signs, signed zeros and infinities, and on vertex indices
wide enough that the rows do not fit in one packed integer.
"""

from __future__ import annotations

import numpy as np
import pytest

from shapelab._engine.alpha import filtration_order as _filtration_order


def _oracle(v, rows):
    return np.lexsort([rows[:, c] for c in range(rows.shape[1] - 1, -1, -1)] + [v])


@pytest.mark.parametrize("nv", [5, 1000, 2**17 + 3, 2**31 - 1])
@pytest.mark.parametrize("w", [1, 2, 3, 4])
def test_order_is_value_then_rows(nv, w):
    rng = np.random.default_rng(nv + w)
    m = 3000
    rows = np.sort(rng.integers(0, nv, size=(m, w)), axis=1)
    rows = np.unique(rows, axis=0)
    rows = rows[rng.permutation(rows.shape[0])].astype(np.int32)
    pool = np.array([-np.inf, -3.5, -1e-300, -0.0, 0.0, 5e-324, 1.0, 1.0 + 2**-52, 7.25, np.inf])
    v = np.where(rng.random(rows.shape[0]) < 0.5, rng.choice(pool, rows.shape[0]), rng.normal(size=rows.shape[0]))
    order = _filtration_order(v, rows)
    assert np.array_equal(order, _oracle(v, rows))


def test_empty():
    assert _filtration_order(np.zeros(0), np.zeros((0, 3), dtype=np.int32)).size == 0
