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
    w = alpha_explorer(b, filtration=F, tau=0.0)
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
