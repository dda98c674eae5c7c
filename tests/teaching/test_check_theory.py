"""shapelab.check.theory: each check passes the right answer and refuses wrong answers
of the right type (the plausible mistakes of each exercise), without printing the
right value."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import norm

import shapelab as sl
from shapelab import check
from shapelab.intervals import clopper_pearson_interval, wilson_interval
from shapelab.morse import power_critical_points

THREE = sl.Balls([[0.0, 0.0], [4.0, 0.0], [1.5, 3.0]], [1.0, 1.3, 0.8])
HEXAGON = sl.Balls([[-3.0, 4.0], [5.0, 0.0], [3.0, -4.0], [-5.0, 0.0], [3.0, 4.0], [-3.0, -4.0]], 1.0)
CHAIN = sl.Balls([[0.0, 0.0, 0.0], [1.6, 0.0, 0.0], [3.0, 0.0, 0.0]], [1.0, 1.2, 0.9])
D1, D2 = [[0.0, 4.0], [1.0, 2.0]], [[0.0, 3.0]]


def _maximum():
    cp = power_critical_points(THREE)
    return cp.positions[cp.index == 2][0], float(cp.values[cp.index == 2][0])


def test_morse_maximum(capsys):
    y, v = _maximum()
    assert check.morse_maximum(y, v, THREE)
    z = THREE.centers
    a = 2 * (z[1:] - z[0])
    circumcentre = np.linalg.solve(a, (z[1:] ** 2).sum(1) - (z[0] ** 2).sum())
    wrong = [
        (circumcentre, v),  # radii ignored
        (z.mean(axis=0), v),  # the centroid
        (y, float(((circumcentre - z[0]) ** 2).sum())),  # the circumradius squared
        (y, v + THREE.radii[0] ** 2),  # |y - z|^2 without the weight
        (y, None),
        (None, v),
    ]
    for pos, val in wrong:
        capsys.readouterr()
        assert not check.morse_maximum(pos, val, THREE)
        out = capsys.readouterr().out
        assert "✗" in out and f"{v:.4f}" not in out


def _fan(balls, first):
    around = np.argsort(np.arctan2(balls.centers[:, 1], balls.centers[:, 0]))
    rest = np.roll(around, -int(np.flatnonzero(around == first)[0]))[1:]
    return [[first, int(a), int(b)] for a, b in zip(rest[:-1], rest[1:])]


def test_tie_break(capsys):
    assert check.tie_break(_fan(HEXAGON, 0), HEXAGON)
    assert check.tie_break([t[::-1] for t in _fan(HEXAGON, 0)][::-1], HEXAGON)  # any order
    for k in range(1, 6):  # a fan from another ball
        assert not check.tie_break(_fan(HEXAGON, k), HEXAGON)
    right = _fan(HEXAGON, 0)
    for wrong in (right[:3], right + [right[0]], [[0, 1]] * 4, "0 1 2", None, 0):
        assert not check.tie_break(wrong, HEXAGON)
    assert "✗" in capsys.readouterr().out


def test_chain_volume(capsys):
    v = sl.union_measure(CHAIN).volume
    assert check.chain_volume(v, CHAIN)
    from shapelab.intersections import ball_measure, lens_measure

    balls = sum(ball_measure(r) for r in CHAIN.radii)
    wrong = [
        balls,  # no lenses
        balls - lens_measure(1.0, 1.2, 1.6),  # one lens forgotten
        balls - 2 * lens_measure(1.0, 1.2, 1.6) + 0.0,  # the same lens twice
        balls - lens_measure(1.0, 1.2, 1.6) - lens_measure(1.2, 0.9, 1.4) * 0.5,
        v * 1.1,
    ]
    for w in wrong:
        capsys.readouterr()
        assert not check.chain_volume(w, CHAIN)
        assert f"{v:.4f}" not in capsys.readouterr().out


def test_wasserstein_by_hand(capsys):
    assert check.wasserstein_by_hand(1.5, D1, D2)
    for w in (1.0, 3.0, 4.0, np.sqrt(1.25), 2.0, None):  # bottleneck, other matchings, W2, ...
        capsys.readouterr()
        assert not check.wasserstein_by_hand(w, D1, D2)
        assert "1.5" not in capsys.readouterr().out


def test_wilson(capsys):
    k, n = 46, 61
    lo, hi = wilson_interval(k, n)
    assert check.wilson((lo, hi), k, n)
    assert check.wilson((round(lo, 3), round(hi, 3)), k, n)  # three decimals are enough
    p = k / n
    half = norm.ppf(0.975) * np.sqrt(p * (1 - p) / n)
    wrong = [
        (p - half, p + half),  # Wald
        clopper_pearson_interval(k, n),  # exact, not Wilson
        wilson_interval(k, n, 0.9),  # the 90 % interval
        (hi, lo),  # ends swapped
        (lo, hi + 0.01),
        lo,
        None,
    ]
    for w in wrong:
        capsys.readouterr()
        assert not check.wilson(w, k, n)
        out = capsys.readouterr().out
        assert f"{lo:.3f}" not in out and f"{hi:.3f}" not in out


@pytest.mark.parametrize("name", ["morse_maximum", "tie_break", "chain_volume", "wasserstein_by_hand", "wilson"])
def test_exported(name):
    assert name in check.__all__ and callable(getattr(check, name))
