"""Tests of the self-checks in shapelab.check.homology (lesson 02): right answers pass,
wrong answers of the right type fail (an entry off, the rationals' answer, a cycle
claimed a boundary), and no message gives the right answer away."""

from __future__ import annotations

import numpy as np
import pytest

import shapelab as sl
from shapelab import check

TORUS = sl.closure([t for i in range(7) for t in ((i, (i + 1) % 7, (i + 3) % 7), (i, (i + 2) % 7, (i + 3) % 7))])
RP2 = sl.closure(
    [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5), (0, 1, 5), (1, 2, 4), (2, 3, 5), (1, 3, 4), (2, 4, 5), (1, 3, 5)]
)
LOOP = [(i, (i + 1) % 7) for i in range(7)]
CHAINS = [LOOP, [(0, 1), (1, 3), (0, 3)], [(0, 1), (1, 2)], [(i, (i + s) % 7) for s in (1, 2, 3) for i in range(7)]]
CYCLE = [True, True, False, True]
BOUNDS = [False, True, False, True]


# ------------------------------------------------------------------ rank mod 2
def rank_reals(M):
    A = np.asarray(M, dtype=float)
    return int(np.linalg.matrix_rank(A)) if A.size else 0


def rank_no_swap(M):  # uses a pivot only if it is already on the diagonal
    A = np.array(M, dtype=np.uint8) % 2
    r = 0
    for c in range(A.shape[1]):
        if r < A.shape[0] and A[r, c]:
            for i in range(A.shape[0]):
                if i != r and A[i, c]:
                    A[i] ^= A[r]
            r += 1
    return r


def rank_nonzero_rows(M):  # counts rows that are not zero
    return int(np.asarray(M).any(axis=1).sum()) if np.asarray(M).size else 0


def rank_crashes_on_empty(M):
    return sl.rank_mod2(M) if np.asarray(M).size else np.asarray(M)[0, 0]


def test_rank_right_answer_passes(capsys):
    r = check.rank_mod2(sl.rank_mod2)
    assert r.passed and r.n_cases > 50
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize(
    "wrong",
    [
        rank_reals,
        rank_no_swap,
        rank_nonzero_rows,
        rank_crashes_on_empty,
        lambda M: min(np.shape(M)),
        lambda M: True,
        lambda M: None,
    ],
)
def test_rank_mistakes_fail(wrong, capsys):
    assert not check.rank_mod2(wrong).passed
    assert "✗" in capsys.readouterr().out


# ------------------------------------------------------------- Betti numbers
def test_betti_right_answer_passes(capsys):
    assert check.complex_betti((1, 1, 1), RP2).passed
    assert check.complex_betti([1, 2, 1], TORUS).passed
    for form in (
        np.array([1, 1, 1]),
        np.array([1, 1, 1], dtype=np.uint8),
        tuple(np.int64(1) for _ in range(3)),
        (1.0, 1.0, 1.0),
    ):
        assert check.complex_betti(form, RP2).passed
    assert "β0, β1)" in check.complex_betti((1, 1), sl.closure([(0, 1), (1, 2), (0, 2)])).message


def _betti_over_the_reals_unsigned(K):  # the 0/1 matrices' ranks over the reals: no signs
    n = [len(sl.k_simplices(K, k)) for k in range(3)]
    r = [0] + [int(np.linalg.matrix_rank(sl.boundary_matrix(K, k).astype(float))) for k in (1, 2)] + [0]
    return tuple(n[k] - r[k] - r[k + 1] for k in range(3))


def _cycles_only(K):  # dim Z_k, forgetting the boundaries
    return tuple(len(sl.k_simplices(K, k)) - sl.rank_mod2(sl.boundary_matrix(K, k)) for k in range(3))


@pytest.mark.parametrize(
    "wrong",
    [
        (1, 0, 0),
        (2, 1, 1),
        (1, 1, 2),
        (1, 1, 0),
        (1, 1),
        None,
        0,
        "111",
        (1.5, 1, 1),
        (True, True, True),
        np.array([True, True, True]),
        (1, 1, 1, 0),
        (1, 2, 1),
        _betti_over_the_reals_unsigned(RP2),
        _cycles_only(RP2),
    ],
)
def test_betti_mistakes_fail(wrong, capsys):
    assert not check.complex_betti(wrong, RP2).passed
    out = capsys.readouterr().out
    assert "✗" in out and "(1, 1, 1)" not in out and "[1, 1, 1]" not in out


# --------------------------------------------------- cycles and boundaries
def test_cycles_right_answer_passes(capsys):
    assert [sl.is_cycle(c, TORUS) for c in CHAINS] == CYCLE
    assert [sl.is_boundary(c, TORUS) for c in CHAINS] == BOUNDS
    assert check.cycles_and_boundaries(CYCLE, BOUNDS, CHAINS, TORUS).passed


@pytest.mark.parametrize(
    "cycle, bounds",
    [
        (CYCLE, [True, True, False, True]),  # the loop around the torus claimed a boundary
        (CYCLE, CYCLE),  # every cycle a boundary
        (CYCLE, [False, True, False, False]),  # the three loops' sum claimed not to bound
        ([True, True, True, True], BOUNDS),  # the path claimed a cycle
        ([False, True, False, True], BOUNDS),
        (CYCLE, BOUNDS[:3]),
        (CYCLE, None),
        ([1, 1, 0, 1], [0, 1, 0, 1]),  # numbers, not truth values
    ],
)
def test_cycles_mistakes_fail(cycle, bounds, capsys):
    assert not check.cycles_and_boundaries(cycle, bounds, CHAINS, TORUS).passed
    assert "✗" in capsys.readouterr().out


def test_right_answers_in_other_forms_pass(capsys):
    for c, b in (
        (tuple(CYCLE), tuple(BOUNDS)),
        (np.array(CYCLE), np.array(BOUNDS)),
        ([np.bool_(x) for x in CYCLE], BOUNDS),
    ):
        assert check.cycles_and_boundaries(c, b, CHAINS, TORUS).passed


@pytest.mark.parametrize(
    "cycle, bounds",
    [
        (CYCLE, [True, True, False, True]),
        ([True, True, True, True], BOUNDS),
        (np.array(True), np.array(False)),
        ([CYCLE], [BOUNDS]),
    ],
)
def test_cycles_messages_do_not_name_the_chain(cycle, bounds, capsys):
    """With two possible answers per chain, naming the wrong chain would give its answer away."""
    r = check.cycles_and_boundaries(cycle, bounds, CHAINS, TORUS)
    assert not r.passed and "chain 0" not in r.message and "chain 2" not in r.message and "first" not in r.message
    assert "`bounds`" in r.message or "`cycle`" in r.message


def test_a_boundary_that_is_not_a_cycle_gets_the_hint(capsys):
    check.cycles_and_boundaries([True, True, False, True], [False, True, True, True], CHAINS, TORUS)
    assert "every boundary is a cycle" in capsys.readouterr().out
