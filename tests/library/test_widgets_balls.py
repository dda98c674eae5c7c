"""Tests of the α-explorer (shapelab.widgets.alpha_explorer)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import ipywidgets as W
import numpy as np
import pytest

from shapelab import Balls, alpha_filtration, union_measure
from shapelab.widgets import alpha_explorer


def rand(n=30, seed=0):
    rng = np.random.default_rng(seed)
    return Balls(rng.uniform(0, 8, (n, 2)), rng.uniform(0.3, 0.9, n))


def test_constructs_a_widget_with_a_frame():
    b = rand()
    w = alpha_explorer(b)
    assert isinstance(w, W.VBox)
    assert isinstance(w.slider, W.FloatSlider) and isinstance(w.image, W.Image)
    assert w.image.value[:8] == b"\x89PNG\r\n\x1a\n"
    F = alpha_filtration(b)
    assert w.slider.min == pytest.approx(F.values(0).min())
    assert repr(w).startswith("AlphaExplorer(n_balls=30, tau=0.000")


def test_moving_the_slider_changes_the_drawn_complex():
    b = rand(seed=1)
    F = alpha_filtration(b)
    w = alpha_explorer(F, tau=0.0)
    edges0 = len(w.view._edges.get_segments())
    frame0 = w.image.value
    w.slider.value = 1.5
    K = F.complex_at(w.slider.value)
    assert w.view.complex.tau == w.slider.value
    assert len(w.view._edges.get_segments()) == len(K.simplices(1)) > edges0
    assert len(w.view._tri.get_paths()) == len(K.simplices(2))
    assert w.image.value != frame0
    # the status line reports the complex, α, Betti numbers and the area
    text = w.status.value
    n = K.counts()
    assert f"{n[1]} edges" in text and "α = √τ = 1.225" in text
    b0, b1 = F.betti(w.slider.value)[:2]
    assert f"(β₀, β₁) = ({b0}, {b1})" in text
    assert f"area {union_measure(b, tau=w.slider.value).area:.4g}" in text


def test_negative_tau_reports_undefined_alpha():
    w = alpha_explorer(rand(seed=2), tau=-0.05)
    assert "undefined" in w.status.value


def test_arguments_are_validated():
    b = rand(5)
    with pytest.raises(TypeError, match="Balls"):
        alpha_explorer(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="2D"):
        alpha_explorer(Balls(np.zeros((2, 3)), 1.0))
    with pytest.raises(ValueError, match="low < high"):
        alpha_explorer(b, tau_range=(1.0, 0.0))
    with pytest.raises(TypeError, match="tau_range"):
        alpha_explorer(b, tau_range="ab")
    with pytest.raises(ValueError, match="at least one"):
        alpha_explorer(Balls(np.zeros((0, 2)), 1.0))
    w = alpha_explorer(b, tau=99.0, tau_range=(-1.0, 2.0))
    assert w.slider.value == 2.0  # clipped into the range


# ------------------------------------------------------------------ power_explorer
from shapelab import power_diagram  # noqa: E402
from shapelab.widgets import complex3d_explorer, power_explorer  # noqa: E402


def strip():
    """A disk at the origin between two of radius 2 at (±1, 0).  Its power cell is the
    strip |x₁| <= (r² - 3)/2 (the radical lines of the pairs), empty when r < √3."""
    return Balls([[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]], [2.0, 2.0, 1.0])


def test_power_explorer_hides_and_shows_a_disk_at_the_analytic_radius():
    w = power_explorer(strip(), index=2, radius_range=(0.0, 3.0))
    assert isinstance(w, W.VBox) and w.image.value[:8] == b"\x89PNG\r\n\x1a\n"
    for r, hidden in ((1.0, True), (np.sqrt(3) - 0.05, True), (np.sqrt(3) + 0.05, False), (2.5, False)):
        w.slider.value = r
        assert bool(w.diagram.hidden[2]) is hidden
        assert ("hidden" in w.status.value.split("·")[1]) is hidden
        assert w.diagram.hidden.tolist() == power_diagram(w.balls, bbox=w._bbox).hidden.tolist()
    assert "hidden disks: 2" not in w.status.value  # at r = 2.5 it is back


def test_power_explorer_picks_another_disk_at_its_own_radius():
    b = rand(12, seed=3)
    w = power_explorer(b, index=0)
    frame = w.image.value
    w.disk.value = 5
    assert w.slider.value == pytest.approx(b.radii[5])
    assert w.balls.radii.tolist() == pytest.approx(b.radii.tolist())  # nothing else changed
    assert w.image.value != frame and w.status.value.startswith("disk 5:")


def test_power_explorer_dual_mode_reports_the_dual_complex():
    b = rand(12, seed=4)
    w = power_explorer(b, index=2, mode="dual")
    w.slider.value = 1.5
    n = alpha_filtration(w.balls).complex_at(0.0).counts()
    nouns = lambda k, one, many: f"{k} {one if k == 1 else many}"  # noqa: E731
    counts = (
        f"{nouns(n[0], 'vertex', 'vertices')}, {nouns(n[1], 'edge', 'edges')}, {nouns(n[2], 'triangle', 'triangles')}"
    )
    assert f"K: {counts}" in w.status.value
    assert repr(w) == "PowerExplorer(n_balls=12, disk=2, radius=1.500, mode='dual')"


def test_power_explorer_arguments_are_validated():
    b = rand(5)
    with pytest.raises(TypeError, match="Balls"):
        power_explorer(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="2D"):
        power_explorer(Balls(np.zeros((2, 3)), 1.0))
    with pytest.raises(ValueError, match="at least two"):
        power_explorer(Balls(np.zeros((1, 2)), 1.0))
    with pytest.raises(ValueError, match="index"):
        power_explorer(b, index=5)
    with pytest.raises(ValueError, match="mode"):
        power_explorer(b, mode="voronoi")
    with pytest.raises(ValueError, match="radius_range"):
        power_explorer(b, radius_range=(-1.0, 2.0))
    with pytest.raises(ValueError, match="low < high"):
        power_explorer(b, radius_range=(2.0, 1.0))
    with pytest.raises(ValueError, match="radius"):
        power_explorer(b, radius=float("nan"))


# ------------------------------------------------------------------ complex3d_explorer
def test_complex3d_explorer_reports_the_filtrations_betti_numbers():
    from shapelab import datasets

    b = datasets.fullerene_c60()
    F = alpha_filtration(b)
    w = complex3d_explorer(F, resolution=4)
    for tau in (w.slider.min, 0.0, 1.0, w.slider.max):
        w.slider.value = tau
        t = w.slider.value
        b0, b1, b2 = F.betti(t)[:3]
        assert f"β₀ = {b0} components, β₁ = {b1} tunnels, β₂ = {b2} voids" in w.status.value
        n = F.complex_at(t).counts()
        assert f"K: {n[0]} vertices, {n[1]} edges" in w.status.value
    w.slider.value = 0.0
    assert "β₂ = 1 voids" in w.status.value  # C60's cage encloses one void (lesson 07)
    frame = w.image.value
    w.azim.value = 120.0
    assert w.image.value != frame


def test_complex3d_explorer_arguments_are_validated():
    b3 = Balls(np.random.default_rng(0).uniform(0, 3, (8, 3)), 0.8)
    with pytest.raises(TypeError, match="Balls"):
        complex3d_explorer(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="3D"):
        complex3d_explorer(rand(5))
    with pytest.raises(ValueError, match="low < high"):
        complex3d_explorer(b3, tau_range=(1.0, 1.0))
    with pytest.raises(ValueError, match="azim"):
        complex3d_explorer(b3, azim=float("inf"))
    with pytest.raises(ValueError, match="resolution"):
        complex3d_explorer(b3, resolution=2)


def test_a_count_of_one_is_singular():
    from shapelab.widgets.balls import _n

    assert [_n(1, "triangle"), _n(0, "triangle"), _n(8, "edge"), _n(1, "vertex", "vertices")] == [
        "1 triangle",
        "0 triangles",
        "8 edges",
        "1 vertex",
    ]
