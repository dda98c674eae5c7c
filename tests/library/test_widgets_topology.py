"""Tests of the topology explorers (shapelab.widgets.persistence_explorer)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import ipywidgets as W
import numpy as np
import pytest

from shapelab import Balls, alpha_filtration
from shapelab.widgets import persistence_explorer


def filtration(seed=0, n=25):
    rng = np.random.default_rng(seed)
    return alpha_filtration(Balls(rng.uniform(0, 8, (n, 2)), rng.uniform(0.3, 1.0, n)))


def test_kept_features_are_those_at_least_as_persistent_as_the_threshold():
    F = filtration()
    P = F.persistence()
    w = persistence_explorer(F)
    assert isinstance(w, W.VBox) and w.image.value[:8] == b"\x89PNG\r\n\x1a\n"
    assert w._dims == (0, 1)  # 2D: no H2 features, so no H2 panel
    frames = set()
    for t in np.linspace(0.0, w.slider.max, 5):
        w.slider.value = float(t)
        t = w.slider.value
        brute = {k: sum(1 for b, d in np.asarray(P[k]) if d - b >= t) for k in (0, 1)}
        assert w.kept() == brute
        assert f"{brute[0]} of {len(P[0])} in H0" in w.status.value
        frames.add(w.image.value)
    assert len(frames) > 1
    # the essential component survives every threshold
    assert w.kept()[0] >= 1


def test_dims_and_range_arguments():
    F = filtration(1)
    w = persistence_explorer(F, dims=1, threshold=0.2, threshold_range=(0.0, 1.0))
    assert w._dims == (1,) and w.slider.max == 1.0 and w.threshold == pytest.approx(0.2)
    assert repr(w) == "PersistenceExplorer(dims=(1,), threshold=0.200)"


def test_arguments_are_validated():
    F = filtration(2, n=8)
    with pytest.raises(TypeError, match="Filtration"):
        persistence_explorer({0: np.zeros((0, 2))})
    with pytest.raises(ValueError, match="threshold"):
        persistence_explorer(F, threshold=-1.0)
    with pytest.raises(ValueError, match="dims"):
        persistence_explorer(F, dims=(0, 5))
    with pytest.raises(ValueError, match="low < high"):
        persistence_explorer(F, threshold_range=(1.0, 0.5))
    with pytest.raises(ValueError, match="steps"):
        persistence_explorer(F, steps=1)


def test_persistence_explorer_takes_balls_as_F():
    """The one input rule (issue 22): the first parameter is F, Balls or a Filtration."""
    import inspect

    assert next(iter(inspect.signature(persistence_explorer).parameters)) == "F"
    balls = Balls(np.random.default_rng(2).random((20, 2)) * 4, 0.4)
    a, b = persistence_explorer(balls), persistence_explorer(alpha_filtration(balls))
    assert a.kept() == b.kept() and a.status.value == b.status.value and a.image.value == b.image.value
