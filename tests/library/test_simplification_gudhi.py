"""GUDHI comparisons of test_simplification.py: the tests that need the peer library as an oracle,
kept apart so that the oracle-free tests run without GUDHI (issue 22)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shapelab.simplification import curve_persistence
from tests.library.test_simplification import (  # noqa: E402
    _ours,
    float_values_st,
    values_st,
)

gudhi = pytest.importorskip("gudhi")


def _gudhi_diagram(f, closed):
    st_ = gudhi.SimplexTree()
    n = len(f)
    for i, v in enumerate(f):
        st_.insert([i], filtration=float(v))
    for i in range(n - 1 + int(closed)):
        j = (i + 1) % n
        if i != j:
            st_.insert([i, j], filtration=float(max(f[i], f[j])))
    pers = st_.persistence(homology_coeff_field=2, min_persistence=-1, persistence_dim_max=True)
    finite = sorted((b, d) for dim, (b, d) in pers if dim == 0 and np.isfinite(d) and d > b)
    essential = sorted((dim, b) for dim, (b, d) in pers if not np.isfinite(d))
    return finite, essential


@settings(max_examples=300, deadline=None)
@given(values_st, st.booleans())
def test_persistence_matches_gudhi_with_ties(f, closed):
    P = curve_persistence(f, closed=closed)
    finite, essential = _gudhi_diagram(f, closed)
    assert _ours(P) == finite
    assert f[P.essential_min] == f.min()
    if closed and len(f) > 2:
        assert essential == [(0, f.min()), (1, f.max())]
        assert f[P.essential_max] == f.max()
    assert np.all(P.persistence >= 0)


@settings(max_examples=150, deadline=None)
@given(float_values_st, st.booleans())
def test_persistence_matches_gudhi_on_floats(f, closed):
    P = curve_persistence(f, closed=closed)
    assert _ours(P) == _gudhi_diagram(f, closed)[0]
