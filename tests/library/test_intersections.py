"""shapelab.intersections: closed forms against sympy integration, the library's union
measure and Monte Carlo."""

import math

import numpy as np
import pytest
import sympy as sp

import shapelab as sl
from shapelab.intersections import ball_measure, cap_volume, lens_measure


def test_cap_by_sympy():
    r, h, x = sp.symbols("r h x", positive=True)
    vol = sp.integrate(sp.pi * (r**2 - x**2), (x, r - h, r))  # discs of the cap, by revolution
    assert sp.simplify(vol - sp.pi * h**2 * (3 * r - h) / 3) == 0
    assert cap_volume(1.3, 0.7) == pytest.approx(float(vol.subs({r: 1.3, h: 0.7})), rel=1e-14)


@pytest.mark.parametrize("r1,r2,d", [(1.0, 1.0, 1.0), (1.0, 1.2, 1.5), (2.0, 0.7, 1.8), (1.0, 1.0, 0.01)])
def test_lens_by_sympy(r1, r2, d):
    x = sp.symbols("x", real=True)
    t = sp.Rational(str(d)) ** 2 + sp.Rational(str(r1)) ** 2 - sp.Rational(str(r2)) ** 2
    t1 = t / (2 * sp.Rational(str(d)))
    R1, R2, D = (sp.Rational(str(v)) for v in (r1, r2, d))
    vol = sp.integrate(sp.pi * (R1**2 - x**2), (x, t1, R1)) + sp.integrate(
        sp.pi * (R2**2 - (x - D) ** 2), (x, D - R2, t1)
    )
    assert lens_measure(r1, r2, d) == pytest.approx(float(vol), rel=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize(
    "r1,r2,d", [(1.0, 1.2, 1.5), (1.0, 1.0, 2.0), (2.0, 0.5, 0.3), (1.0, 0.8, 0.5), (1.0, 1.0, 3.0)]
)
def test_union_measure(dim, r1, r2, d):
    b = sl.Balls([[0.0] * dim, [d] + [0.0] * (dim - 1)], [r1, r2])
    m = sl.union_measure(b)
    got = m.volume if dim == 3 else m.area
    assert got == pytest.approx(ball_measure(r1, dim) + ball_measure(r2, dim) - lens_measure(r1, r2, d, dim), rel=1e-12)


def test_monte_carlo():
    rng = np.random.default_rng(0)
    P = rng.uniform(-1, 2.2, (400_000, 3))
    inside = (np.linalg.norm(P, axis=1) <= 1.0) & (np.linalg.norm(P - [1.2, 0, 0], axis=1) <= 1.0)
    est = inside.mean() * 3.2**3
    se = 3.2**3 * math.sqrt(inside.mean() * (1 - inside.mean()) / len(P))
    assert abs(est - lens_measure(1.0, 1.0, 1.2)) < 4 * se


def test_edge_terms_of_the_short_formula():
    c60 = sl.datasets.fullerene_c60()
    F = sl.alpha_filtration(c60)
    E = F.complex_at(0.0).simplices(1)
    Z, R = c60.centers, c60.radii
    lenses = sum(lens_measure(R[i], R[j], np.linalg.norm(Z[i] - Z[j])) for i, j in E)
    m = sl.union_measure(F)
    assert lenses == pytest.approx(m.terms[1], rel=1e-10)
    assert sum(ball_measure(r) for r in R) == pytest.approx(m.terms[0], rel=1e-12)


def test_rejects():
    with pytest.raises(ValueError):
        lens_measure(1.0, 1.0, -1.0)
    with pytest.raises(ValueError):
        cap_volume(1.0, 3.0)
    with pytest.raises(ValueError):
        ball_measure(1.0, dim=4)
