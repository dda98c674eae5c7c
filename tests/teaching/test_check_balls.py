"""Tests of the self-checks of lessons 01–06 (shapelab.check.balls).

A correct student function written here from first principles (independent of the
library) must pass; typical mistakes must fail; a placeholder must be reported as
not implemented.  That the correct functions pass also checks the references.
"""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import check


# ----------------------------------------------------- correct solutions
def good_power(x, c, r):
    x, c = np.asarray(x, float), np.asarray(c, float)
    return float(np.sum((x - c) ** 2) - r**2)


def good_orthogonal(centers, radii):
    # y solves 2 (z_j - z_0) . y = |z_j|^2 - r_j^2 - |z_0|^2 + r_0^2, j = 1, 2
    z, r = np.asarray(centers, float), np.asarray(radii, float)
    A = 2 * (z[1:] - z[0])
    b = (z[1:] ** 2).sum(1) - r[1:] ** 2 - (z[0] ** 2).sum() + r[0] ** 2
    y = np.linalg.solve(A, b)
    return float(np.sum((y - z[0]) ** 2) - r[0] ** 2)


def good_union(c1, r1, c2, r2):
    d = float(np.linalg.norm(np.asarray(c2) - np.asarray(c1)))
    if d >= r1 + r2:
        lens = 0.0
    elif d <= abs(r1 - r2):
        lens = np.pi * min(r1, r2) ** 2
    else:
        a1 = r1**2 * np.arccos((d**2 + r1**2 - r2**2) / (2 * d * r1))
        a2 = r2**2 * np.arccos((d**2 + r2**2 - r1**2) / (2 * d * r2))
        lens = a1 + a2 - 0.5 * np.sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2))
    return np.pi * (r1**2 + r2**2) - lens


@pytest.mark.parametrize(
    "name, fn", [("power_distance", good_power), ("orthogonal_radius", good_orthogonal), ("union_area", good_union)]
)
def test_correct_solutions_pass(name, fn, capsys):
    res = getattr(check, name)(fn)
    assert res.passed and res.n_cases >= 7
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize(
    "name, fn",
    [
        ("power_distance", lambda x, c, r: float(np.sum((np.asarray(x) - c) ** 2) - r)),  # r, not r²
        ("power_distance", lambda x, c, r: float(np.linalg.norm(np.asarray(x) - c) - r)),  # Euclidean
        ("orthogonal_radius", lambda c, r: good_orthogonal(c, np.zeros(3))),  # ignores radii
        ("orthogonal_radius", lambda c, r: float(np.sqrt(abs(good_orthogonal(c, r))))),  # R, not R²
        ("union_area", lambda c1, r1, c2, r2: np.pi * (r1**2 + r2**2)),  # no lens
        (
            "union_area",
            lambda c1, r1, c2, r2: (
                good_union(c1, r1, c2, r2)
                if np.linalg.norm(np.subtract(c1, c2)) > abs(r1 - r2)
                else np.pi * (r1**2 + r2**2)
            ),
        ),
    ],
)
def test_mistakes_fail(name, fn, capsys):
    res = getattr(check, name)(fn)
    assert not res.passed
    assert "✗" in capsys.readouterr().out


def test_placeholder_and_crash_reported(capsys):
    def todo(*args):
        raise NotImplementedError

    assert not check.union_area(todo)
    assert "not implemented" in capsys.readouterr().out
    res = check.power_distance(lambda x, c, r: 1 / 0, quiet=True)
    assert not res.passed and "ZeroDivisionError" in res.message
    assert not check.orthogonal_radius(42, quiet=True)


def test_orthogonal_circle_is_orthogonal():
    """The reference's R² is the squared radius of a circle meeting all three at right
    angles: |y − z_i|² = R² + r_i² (checked on the check's own cases)."""
    z = np.array([[0.0, 0.0], [5.0, 1.0], [2.0, 4.0]])
    r = np.array([1.0, 2.0, 0.5])
    R2 = good_orthogonal(z, r)
    import shapelab

    assert shapelab.alpha_filtration(shapelab.Balls(z, r)).values(2)[0] == pytest.approx(R2, rel=1e-12)


def good_attached(centers, radii, edge):
    # the edge's orthocentre c on the line z_i z_j (equal power), then every other power at c
    z, r = np.asarray(centers, float), np.asarray(radii, float)
    i, j = edge
    a = z[j] - z[i]
    c = z[i] + (a @ a - r[j] ** 2 + r[i] ** 2) / (2 * (a @ a)) * a
    rho = np.sum((c - z[i]) ** 2) - r[i] ** 2
    pw = np.sum((z - c) ** 2, axis=1) - r**2
    pw[[i, j]] = np.inf
    return bool(np.any(pw < rho))


def diametral_attached(centers, radii, edge):  # the unweighted Gabriel test: radii ignored
    z = np.asarray(centers, float)
    i, j = edge
    d = np.sum((z - (z[i] + z[j]) / 2) ** 2, axis=1)
    d[[i, j]] = np.inf
    return bool(np.any(d < np.sum((z[j] - z[i]) ** 2) / 4))


def test_attached_edge_check(capsys):
    assert check.attached_edge(good_attached).passed
    assert "✓" in capsys.readouterr().out
    for wrong in (
        diametral_attached,
        lambda c, r, e: not good_attached(c, r, e),
        lambda c, r, e: False,
        lambda c, r, e: int(good_attached(c, r, e)),  # an int is not an answer
    ):
        assert not check.attached_edge(wrong).passed
        assert "✗" in capsys.readouterr().out


def _powers_at(centers, radii, edge, *, at_midpoint=False, tie=False, nearest=False):
    z, r = np.asarray(centers, float), np.asarray(radii, float)
    i, j = edge
    a = z[j] - z[i]
    c = (z[i] + z[j]) / 2 if at_midpoint else z[i] + (a @ a - r[j] ** 2 + r[i] ** 2) / (2 * (a @ a)) * a
    pw, d2 = np.sum((z - c) ** 2, axis=1) - r**2, np.sum((z - c) ** 2, axis=1)
    rho = pw[i]
    pw[[i, j]] = d2[[i, j]] = np.inf
    if nearest:
        return bool(pw[np.argmin(d2)] < rho)
    return bool(np.any(pw <= rho)) if tie else bool(np.any(pw < rho))


@pytest.mark.parametrize(
    "wrong",
    [
        lambda c, r, e: _powers_at(c, r, e, at_midpoint=True),  # the orthocentre of equal radii
        lambda c, r, e: _powers_at(c, r, e, tie=True),  # a tie (right angle) counted as attached
        lambda c, r, e: _powers_at(c, r, e, nearest=True),  # only the centre nearest c
        lambda c, r, e: good_attached(c, r, e) if np.shape(c)[1] == 2 else False,  # right in 2D only
        lambda c, r, e: good_attached(c, r, e) if np.shape(c)[1] == 3 else False,  # right in 3D only
    ],
)
def test_attached_edge_refuses_plausible_mistakes(wrong):
    """Second reading (issue 21): each of these passed the first version of the check."""
    assert _powers_at([[0.0, 0.0], [4.0, 0.0], [2.0, 1.0]], [1.0] * 3, (0, 1))  # they are answers, not noise
    assert not check.attached_edge(wrong, quiet=True).passed


def good_dual_edge(c1, r1, c2, r2):
    # exact: the closed clipped cells meet iff |r1 - r2| <= d <= r1 + r2 (squared, in rationals)
    from fractions import Fraction as Q

    d2 = sum((Q(float(a)) - Q(float(b))) ** 2 for a, b in zip(c1, c2))
    return (Q(r1) - Q(r2)) ** 2 <= d2 <= (Q(r1) + Q(r2)) ** 2


def test_dual_edge_passes_the_exact_answer_and_refuses_the_open_cases(capsys):
    """check.dual_edge has touching cases (outside and inside) and a disk inside the other:
    strict inequalities, a missing ``abs`` and 'the disks intersect' all fail."""
    res = check.dual_edge(good_dual_edge)
    assert res.passed and res.n_cases >= 9
    mistakes = [
        lambda c1, r1, c2, r2: abs(r1 - r2) < np.linalg.norm(np.subtract(c2, c1)) < r1 + r2,  # touching left out
        lambda c1, r1, c2, r2: bool(np.linalg.norm(np.subtract(c2, c1)) <= r1 + r2),  # nested disks counted
        lambda c1, r1, c2, r2: r1 - r2 <= np.linalg.norm(np.subtract(c2, c1)) <= r1 + r2,  # no abs
        lambda c1, r1, c2, r2: good_dual_edge(c1, r1, c2, r2) and abs(r1 - r2) != np.linalg.norm(np.subtract(c2, c1)),
    ]
    for fn in mistakes:
        assert not check.dual_edge(fn, quiet=True).passed
    assert not check.dual_edge(lambda *a: 1, quiet=True).passed  # an int is not a bool
