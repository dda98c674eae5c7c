"""The value checks that compare content: the pocket's residues as a set of labels, and
the void's radius interval against a closed form (not against the count of labels, or a
grid of radii)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from shapelab import check

NAMES = np.array(["THR", "THR", "MET", "TYR", "TYR", "GLY", "ALA"])
NUMBERS = np.array([11, 11, 14, 25, 25, 30, 31])
MOL = SimpleNamespace(residue_names=NAMES, residue_numbers=NUMBERS)
POCKET = SimpleNamespace(lining=np.array([0, 1, 2, 4]))  # THR 11, MET 14, TYR 25
RIGHT = ["THR 11", "MET 14", "TYR 25"]


@pytest.mark.parametrize(
    "answer",
    [RIGHT, RIGHT[::-1], ["thr 11", " MET  14", "Tyr 25"], tuple(RIGHT), set(RIGHT), np.array(RIGHT)],
)
def test_pocket_residues_right_in_any_order_case_or_spacing(answer, capsys):
    assert check.pocket_residues(answer, MOL, POCKET)
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("answer", "hint"),
    [
        (["THR 11", "MET 14", "GLY 30"], "1 of your 3 labels does not line the pocket; 1 lining residue is missing"),
        (["THR 11", "MET 14", "TYR 26"], "(1 is no residue of the structure)"),
        (["THR 11", "MET 14"], "1 lining residue is missing"),
        (RIGHT + ["ALA 31"], "1 of your 4 labels does not line the pocket"),
        (RIGHT + ["THR 11"], "1 label is repeated"),
        (["ALA 31", "GLY 30", "THR 11"], "2 of your 3 labels do not line"),
        ("THR 11, MET 14, TYR 25", "expected a list of labels"),
        ([11, 14, 25], "got a int among them"),
        (None, "expected a list of labels"),
    ],
)
def test_pocket_residues_wrong_content_fails_without_naming_the_answer(answer, hint, capsys):
    assert not check.pocket_residues(answer, MOL, POCKET)
    out = capsys.readouterr().out
    assert "✗" in out and hint in out, out
    missing = set(RIGHT) - ({str(a) for a in answer} if isinstance(answer, list) else set())
    assert not any(label in out for label in missing), out


def test_pocket_residues_same_count_is_not_enough(capsys):
    """The old check compared the number of labels: three random ones passed."""
    assert not check.pocket_residues(["GLY 30", "ALA 31", "THR 12"], MOL, POCKET)


R_HIGH = 1.4 / 2 * np.sqrt(9 * ((1 + 5**0.5) / 2) ** 2 + 1)  # the cage's circumradius (lesson 07)


def test_void_radii_closed_form_passes(capsys):
    assert check.void_radii(1.4, R_HIGH)


@pytest.mark.parametrize(
    "ends",
    [(1.45, R_HIGH), (1.4, 3.45), (1.4 * (1 + 1e-6), R_HIGH), (R_HIGH, 1.4), (0.7, R_HIGH), (1.4, float("nan"))],
)
def test_void_radii_read_off_a_grid_or_swapped_fails(ends, capsys):
    assert not check.void_radii(*ends)
    out = capsys.readouterr().out
    assert "✗" in out and "3.469" not in out and "1.4" not in out.split(":", 1)[1].replace("(r_low, r_high)", "")


def _mouth_time(equal_radii: bool):
    def closes_at(pocket, balls):
        i, j = np.asarray(pocket.mouth).T
        z, r = balls.centers, balls.radii
        d = np.linalg.norm(z[j] - z[i], axis=1)
        t = d / 2 if equal_radii else (d**2 + r[i] ** 2 - r[j] ** 2) / (2 * d)
        return float(np.max(t**2 - r[i] ** 2))

    return closes_at


def test_mouth_closing_refuses_the_equal_radii_formula(capsys):
    # every disk of the data sets has one radius, on which (d/2)² − r² is right; the
    # check once passed it on all its cases
    assert check.mouth_closing(_mouth_time(equal_radii=False))
    assert not check.mouth_closing(_mouth_time(equal_radii=True))
    assert "✗" in capsys.readouterr().out


def test_mouth_closing_refuses_the_first_mouth_edge_to_close(capsys):
    # every case once had a single mouth edge, so the smallest (or the mean, or the
    # first) of the edges' times passed: the gapped ring's two edges tell them apart
    def first_to_close(pocket, balls):
        i, j = np.asarray(pocket.mouth).T
        z, r = balls.centers, balls.radii
        d = np.linalg.norm(z[j] - z[i], axis=1)
        t = (d**2 + r[i] ** 2 - r[j] ** 2) / (2 * d)
        return float(np.min(t**2 - r[i] ** 2))

    assert not check.mouth_closing(first_to_close)
    assert "✗" in capsys.readouterr().out


# ---- lesson 19: the most spread-out class, with its per-class values -------------------
#: four classes of two shapes each; within-class distances 0.3, 0.1, 0.5, 0.2 (the cube
#: is the most spread out); between classes 1.0
SPREAD_LABELS = ["sphere", "sphere", "ellipsoid", "ellipsoid", "cube", "cube", "torus", "torus"]
SPREAD_RIGHT = {"sphere": 0.3, "ellipsoid": 0.1, "cube": 0.5, "torus": 0.2}


def _spread_matrix():
    D = np.ones((8, 8)) - np.eye(8)
    for k, v in enumerate(SPREAD_RIGHT.values()):
        D[2 * k, 2 * k + 1] = D[2 * k + 1, 2 * k] = v
    return D


def test_most_spread_class_passes_the_closed_form(capsys):
    assert check.most_spread_class(" Cube", _spread_matrix(), SPREAD_LABELS, spread=dict(SPREAD_RIGHT))
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize(
    "answer, spread",
    [
        ("sphere", SPREAD_RIGHT),  # the runner-up class
        ("cube", {**SPREAD_RIGHT, "cube": 0.25}),  # right class, one value wrong (a mean, say)
        ("cube", {k: v for k, v in SPREAD_RIGHT.items() if k != "torus"}),  # a class missing
        ("cube", list(SPREAD_RIGHT.values())),  # not a dict
    ],
)
def test_most_spread_class_refuses_a_wrong_label_or_value_without_giving_it(answer, spread, capsys):
    assert not check.most_spread_class(answer, _spread_matrix(), SPREAD_LABELS, spread=spread)
    out = capsys.readouterr().out
    assert "✗" in out and "✓" not in out and "0.5" not in out  # a wrong value is named by its class only


# ---- lesson 19: Rips triangles outside the nerve -----------------------------------------
def _exact_rips_only(X, rho):
    """Brute force in exact rationals, by the angles: a triangle with sides <= 2 rho is
    outside the nerve iff it is acute with circumradius > rho (R^2 = a^2 b^2 c^2 / (16 A^2))."""
    from fractions import Fraction
    from itertools import combinations

    P = [[Fraction(float(x)) for x in p] for p in X]
    r2 = Fraction(float(rho)) ** 2

    def d2(p, q):
        return sum((a - b) ** 2 for a, b in zip(p, q))

    n = 0
    for i, j, k in combinations(range(len(P)), 3):
        a2, b2, c2 = d2(P[j], P[k]), d2(P[i], P[k]), d2(P[i], P[j])
        if max(a2, b2, c2) > 4 * r2:
            continue
        s = sorted((a2, b2, c2))
        if s[0] + s[1] <= s[2]:
            continue  # right or obtuse: the smallest ball has the longest side as diameter
        u = [x - y for x, y in zip(P[j], P[i])]
        v = [x - y for x, y in zip(P[k], P[i])]
        uu, vv, uv = sum(x * x for x in u), sum(x * x for x in v), sum(x * y for x, y in zip(u, v))
        area2 = (uu * vv - uv * uv) / 4
        n += a2 * b2 * c2 / (16 * area2) > r2
    return n


def test_rips_not_nerve_closed_forms(capsys):
    # the regular octahedron: 8 equilateral faces of side sqrt(2), circumradius sqrt(2/3)
    octahedron = np.vstack([np.eye(3), -np.eye(3)])
    assert check.rips_not_nerve(8, octahedron, 0.75)  # sqrt(2) <= 1.5 < 2, sqrt(2/3) > 0.75
    assert check.rips_not_nerve(0, octahedron, 0.9)  # the faces are in the nerve from sqrt(2/3)
    assert check.rips_not_nerve(0, octahedron, 1.1)  # 20 Rips triangles, all in the nerve
    assert not check.rips_not_nerve(20, octahedron, 1.1)  # every Rips triangle: no
    # an equilateral triangle of side 1: Rips from rho = 1/2, nerve from 1/sqrt(3)
    tri = [[0.0, 0.0], [1.0, 0.0], [0.5, np.sqrt(3) / 2]]
    assert check.rips_not_nerve(1, tri, 0.55)
    assert check.rips_not_nerve(0, tri, 0.45) and check.rips_not_nerve(0, tri, 0.6)
    assert not check.rips_not_nerve(1.0, tri, 0.55)  # a float is not a count
    out = capsys.readouterr().out
    assert out.count("✗") == 2 and out.count("✓") == 6


@pytest.mark.parametrize("seed", range(6))
def test_rips_not_nerve_against_exact_brute_force(seed):
    rng = np.random.default_rng(seed)
    X = rng.uniform(0, 1, (18, 2 + seed % 2))
    rho = 0.3
    want = _exact_rips_only(X, rho)
    assert check.rips_not_nerve(want, X, rho)
    assert not check.rips_not_nerve(want + 1, X, rho)


@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_rips_not_nerve_collinear_and_repeated_points(dim, capsys):
    # lattice points with repeats: collinear triples and triangles with a repeated
    # vertex have no circumcentre (a singular system); their smallest ball is half the
    # longest side, as in the exact brute force (review of issue 32)
    rng = np.random.default_rng(dim)
    X = rng.integers(0, 3, (14, dim)).astype(float)
    X = np.vstack([X, X[:3]])  # three repeated points
    for rho in (0.55, 1.05, 1.3):
        want = _exact_rips_only(X, rho)
        assert check.rips_not_nerve(want, X, rho)
        assert not check.rips_not_nerve(want + 1, X, rho)
    assert check.rips_not_nerve(0, [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], 1.2)  # a segment: in the nerve
    assert check.rips_not_nerve(0, [[1.0, 1.0]] * 3, 0.5)  # one point thrice
    assert check.rips_not_nerve(0, [[1.0, 1.0, 1.0]], 0.5)  # a single point
    assert capsys.readouterr().out.count("✗") == 3  # the three off-by-one answers


@pytest.mark.parametrize("wrong", [np.int64(1), 1, -1, True, False, 2.0, "2", None])
def test_rips_not_nerve_wrong_answers_of_any_type_fail(wrong):
    # an equilateral triangle of side 1 beside a far point: at rho = 0.55, 1 Rips triangle, 0 in the nerve
    tri = [[0.0, 0.0], [1.0, 0.0], [0.5, np.sqrt(3) / 2], [9.0, 9.0]]
    assert check.rips_not_nerve(np.int64(1), tri, 0.55)
    expected_pass = bool(isinstance(wrong, (int, np.integer)) and not isinstance(wrong, bool) and wrong == 1)
    assert bool(check.rips_not_nerve(wrong, tri, 0.55)) is expected_pass
    assert not check.rips_not_nerve(0, tri, 0.55)  # the Čech count of outside triangles
    assert not check.rips_not_nerve(np.int32(0), tri, 0.55)


def test_rips_not_nerve_refuses_a_tie_and_bad_rho():
    with pytest.raises(ValueError, match="within 1e-9"):
        check.rips_not_nerve(0, [[0.0, 0.0], [1.0, 0.0]], 0.5)  # a side exactly 2 rho
    with pytest.raises(ValueError, match="rho"):
        check.rips_not_nerve(0, [[0.0, 0.0], [1.0, 0.0]], -1.0)


def _exposed_toy():
    """Three balls in a row: ALA 1 is one end ball; GLY 2, the middle and the other end, is the most exposed."""
    from shapelab import Balls

    balls = Balls([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [4.0, 0.0, 0.0]], [1.0, 1.0, 1.0])
    return SimpleNamespace(
        balls=balls, residue_names=np.array(["ALA", "GLY", "GLY"]), residue_numbers=np.array([1, 2, 2])
    )


@pytest.mark.parametrize("answer", ["GLY 2", "gly 2", " GLY  2 "])
def test_most_exposed_residue_right_in_any_case_or_spacing(answer, capsys):
    assert check.most_exposed_residue(answer, _exposed_toy())
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("answer", "hint"),
    [
        ("GLY2", "is no residue of this structure"),  # refused with the label's spelling, not "not the answer"
        ("2", "is no residue of this structure"),
        ("ALA 1", "% below the largest"),
        (None, "expected a str"),
    ],
)
def test_most_exposed_residue_wrong_answer_says_how(answer, hint, capsys):
    assert not check.most_exposed_residue(answer, _exposed_toy())
    out = capsys.readouterr().out
    assert "✗" in out and hint in out and "GLY 2" not in out, out


def test_most_exposed_residue_oracle_toy_by_hand(capsys):
    """Independent oracle: the end ball of three in a row, grown by the probe, keeps more of its sphere."""
    from shapelab import Balls, union_measure

    toy = _exposed_toy()
    shares = union_measure(Balls(toy.balls.centers, toy.balls.radii + 1.4)).ball_boundary
    # radius 2.4, neighbours 2 apart: each cap cut off at height 1 is 2*pi*2.4*(2.4-1); the middle ball loses two
    cap = 2 * np.pi * 2.4 * (2.4 - 1.0)
    np.testing.assert_allclose(
        shares, [4 * np.pi * 2.4**2 - cap, 4 * np.pi * 2.4**2 - 2 * cap, 4 * np.pi * 2.4**2 - cap]
    )
    assert shares[1] + shares[2] > shares[0]


# lesson 07, exercise 4: C60 and a cage of 0.8 Å balls 16 Å away; a cage's void lives on
# (b² - r², R² - r²) (closed forms, lesson 07), so the counts are known without the library
TWO_TAUS = [-1.8, 0.0, 2.5, 7.0, 9.6, 12.0]
TWO_COUNTS = [sum(1.4**2 - r * r < t < R_HIGH**2 - r * r for r in (1.70, 0.8)) for t in TWO_TAUS]


@pytest.fixture(scope="module")
def two_cages():
    from shapelab import Balls, datasets

    big, small = datasets.fullerene_c60(), datasets.fullerene_c60(atom_radius=0.8)
    return Balls(np.vstack([big.centers, small.centers + [16.0, 0.0, 0.0]]), np.r_[big.radii, small.radii])


def test_void_components_closed_forms_pass(two_cages, capsys):
    assert TWO_COUNTS == [0, 1, 2, 2, 1, 0]
    assert check.void_components(TWO_COUNTS, two_cages, TWO_TAUS)
    assert check.void_components(np.array(TWO_COUNTS, dtype=float), two_cages, TWO_TAUS)
    assert "✓" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("answer", "hints", "absent"),
    [
        # 6-connectivity: cusp voxels counted as components (measured at 0.15 Å: 9 at τ = 0)
        ([0, 9, 2, 2, 1, 0], ["1 of 6 counts differ", "τ = 0 (too many)", "26-connectivity"], []),
        ([n + 1 for n in TWO_COUNTS], ["6 of 6 counts differ", "unbounded component"], []),
        # radius r + τ instead of √(r² + τ): the voids fill too early
        ([0, 1, 1, 0, 0, 0], ["τ = 2.5 (too few)", "√(r² + τ)"], ["26-connectivity"]),
        (np.array(TWO_COUNTS, dtype=bool), ["truth values"], []),
        ("012210", ["got a str"], []),
        ([0, 1, 2, 2, 1], ["expected shape (6,)"], []),
        ([0, 1, 2, 2, 1, np.nan], ["NaN"], []),
    ],
)
def test_void_components_wrong_counts_say_where_and_how(two_cages, answer, hints, absent, capsys):
    assert not check.void_components(answer, two_cages, TWO_TAUS)
    out = capsys.readouterr().out
    assert "✗" in out and all(h in out for h in hints) and not any(a in out for a in absent), out


# ---- check.first_site_rank (lesson 20): the reference is the report's own order -----------
@pytest.fixture(scope="module")
def t4l_and_xylene():
    from shapelab.datasets import structure

    return structure("t4l-l99a"), structure("t4l-l99a-ligand").balls.centers


def test_first_site_rank_is_the_void_in_the_growth_model_second_in_the_flow(t4l_and_xylene, capsys):
    # independent of the check's loop: the L99A void (lesson 12) holds p-xylene; every atom
    # of the ligand lies within 4 Å of the void's lining centroid or not, by brute force
    import shapelab as sl

    t4l, xylene = t4l_and_xylene
    void = sl.report(t4l, 1.4, rank="none").voids[0]
    centre = t4l.balls.centers[list(void.lining_atoms)].mean(axis=0)
    assert np.min(np.linalg.norm(xylene - centre, axis=1)) <= 4.0
    assert check.first_site_rank(1, t4l, xylene)
    assert check.first_site_rank(2, t4l, xylene, method="flow")
    for wrong in (0, 1, 3):
        assert not check.first_site_rank(wrong, t4l, xylene, method="flow")
    out = capsys.readouterr().out
    assert "too small" in out and "too large" in out


@pytest.mark.parametrize("answer", [None, 2.0, np.float64(2.0), True, np.bool_(True), "2", [2]])
def test_first_site_rank_refuses_what_is_not_a_whole_number(t4l_and_xylene, answer, capsys):
    t4l, xylene = t4l_and_xylene
    assert not check.first_site_rank(answer, t4l, xylene, method="flow")
    assert "whole number" in capsys.readouterr().out


def test_first_site_rank_takes_a_numpy_integer(t4l_and_xylene, capsys):
    # a rank computed with NumPy (np.flatnonzero(d <= 4)[0] + 1) is an np.int64: accepted
    t4l, xylene = t4l_and_xylene
    assert check.first_site_rank(np.int64(2), t4l, xylene, method="flow")
    assert "✓" in capsys.readouterr().out


def test_first_site_rank_is_zero_when_no_cavity_is_near(t4l_and_xylene):
    t4l, xylene = t4l_and_xylene
    far = xylene + 1000.0
    assert check.first_site_rank(0, t4l, far)
    assert not check.first_site_rank(1, t4l, far)
