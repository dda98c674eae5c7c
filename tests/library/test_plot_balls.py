"""Tests of shapelab.plot.balls: figures of disks, power diagrams, dual complexes,
filtrations and 3D views (smoke + structure: what is drawn matches the library)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import EllipseCollection, LineCollection, PolyCollection
from matplotlib.figure import Figure

from shapelab import Balls, alpha_filtration, plot, power_diagram
from shapelab.plot.balls import DualComplexView


def rand(n, d, seed=0, lo=0.3, hi=1.0, box=5.0):
    rng = np.random.default_rng(seed)
    return Balls(rng.uniform(0, box, (n, d)), rng.uniform(lo, hi, n))


def colls(ax, kind):
    return [c for c in ax.collections if type(c) is kind]


def render(fig):
    """Draw with Agg for real (a bare Figure's canvas does not draw)."""
    FigureCanvasAgg(fig).draw()
    return fig


def test_disks_structure():
    b = rand(12, 2)
    fig = render(plot.disks(b, labels=True))
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    (ell,) = colls(ax, EllipseCollection)
    assert len(ell.get_offsets()) == 12
    assert ax.get_aspect() == 1.0 and ax.get_legend() is not None
    # grown disks: widths are 2 sqrt(r^2 + tau); imaginary radii drawn as 0
    fig = plot.disks(b, tau=-0.2)
    (ell,) = colls(fig.axes[0], EllipseCollection)
    np.testing.assert_allclose(ell._widths, np.sqrt(np.maximum(b.weights - 0.2, 0)))  # half-widths


def test_power_diagram_cells_and_hidden():
    c = np.array([[0, 0], [4, 0], [2, 3], [2, 1], [2.1, 1]], float)
    b = Balls(c, [2.0, 2.0, 2.0, 2.0, 0.2])  # the small disk is hidden by the one at (2, 1)
    pd = power_diagram(b)
    assert pd.hidden.tolist() == [False, False, False, False, True]
    for arg in (b, pd):
        fig = render(plot.power_diagram(arg))
        ax = fig.axes[0]
        polys = colls(ax, PolyCollection)
        assert len(polys) == 1 and len(polys[0].get_paths()) == 4
        dashed = [e for e in colls(ax, EllipseCollection) if e.get_linestyle()[0][1] is not None]
        assert len(dashed) == 1 and len(dashed[0].get_offsets()) == 1
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert any("hidden" in t for t in labels)
    with pytest.raises(ValueError, match="bbox"):
        plot.power_diagram(pd, bbox=[[0, 0], [1, 1]])
    with pytest.raises(ValueError, match="2D"):
        plot.power_diagram(rand(5, 3))


def test_dual_complex_draws_K():
    b = rand(20, 2, seed=3, lo=0.6, hi=1.2)
    F = alpha_filtration(b)
    K = F.complex_at(0.0)
    fig = render(plot.dual_complex(F))
    ax = fig.axes[0]
    (edges,) = colls(ax, LineCollection)
    assert len(edges.get_segments()) == len(K.simplices(1))
    polys = colls(ax, PolyCollection)  # clipped cells, triangles
    assert len(polys) == 2
    assert len(polys[1].get_paths()) == len(K.simplices(2))
    assert len(polys[0].get_paths()) == int(np.sum(F.values(0) <= 0))
    assert "triangle" in " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert f"{len(K.simplices(1))} edges" in ax.get_title()


def test_view_update_changes_the_drawn_complex():
    b = rand(25, 2, seed=4)
    v = DualComplexView(b, 0.0, title="fixed", view_tau=2.0)
    n0 = len(v._edges.get_segments())
    frame0 = v.render().copy()
    v.update(2.0)
    n1 = len(v._edges.get_segments())
    assert n1 == len(alpha_filtration(b).complex_at(2.0).simplices(1)) and n1 > n0
    frame1 = v.render()
    assert frame1.shape == frame0.shape and not np.array_equal(frame0, frame1)
    assert v.png()[:8] == b"\x89PNG\r\n\x1a\n"
    # blitting gives the same pixels as a full redraw
    full = DualComplexView(b, 2.0, title="fixed", view_tau=2.0)
    full.update(2.0)
    render(full.figure)
    assert np.mean(np.abs(frame1.astype(int) - np.asarray(full.figure.canvas.buffer_rgba()).astype(int))) < 2.0


def test_filtration_colourbar_and_order():
    b = rand(15, 2, seed=5)
    F = alpha_filtration(b)
    fig = render(plot.filtration(F))
    assert len(fig.axes) == 2  # the plot and its colourbar
    assert "entry time" in fig.axes[1].get_ylabel()
    ax = fig.axes[0]
    (edges,) = colls(ax, LineCollection)
    np.testing.assert_array_equal(edges.get_array(), F.values(1))
    widths = edges.get_linewidths()
    assert widths[0] >= widths[-1]  # early simplices thick
    fig = plot.filtration(F, tau=0.0)
    (edges,) = colls(fig.axes[0], LineCollection)
    assert len(edges.get_segments()) == len(F.complex_at(0.0).simplices(1))
    with pytest.raises(TypeError, match="Filtration"):
        plot.filtration(b.centers)  # Balls are accepted (the one input rule), an array is not


def test_3d_views():
    b = rand(10, 3, seed=6, lo=0.8, hi=1.3, box=4.0)
    fig = render(plot.balls3d(b, resolution=5))
    ax = fig.axes[0]
    assert ax.name == "3d"
    assert len(ax.collections[0].get_paths()) == 10 * 5 * 10  # quads per sphere
    F = alpha_filtration(b)
    fig = render(plot.complex3d(F, tau=0.5, show_balls=True))
    assert len(fig.axes) == 2  # with colourbar
    K = F.complex_at(0.5)
    assert f"{len(K.simplices(1))} edges" in fig.axes[0].get_title()
    fig = render(plot.complex3d(K))
    assert len(fig.axes) == 1
    with pytest.raises(ValueError, match="tau"):
        plot.complex3d(K, tau=1.0)
    with pytest.raises(ValueError, match="3D"):
        plot.balls3d(rand(3, 2))


@pytest.mark.parametrize(
    "centers, radii",
    [
        (np.zeros((0, 2)), 1.0),  # nothing
        ([[0.0, 0.0]], 1.0),  # one disk
        ([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], 0.6),  # collinear: no triangles
        ([[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]], 0.5),  # duplicate centres
        ([[0.0, 0.0], [0.1, 0.0], [0.0, 0.1]], [3.0, 0.1, 0.1]),  # all hidden but one
        ([[1e6, 1e6], [1e6 + 1, 1e6], [1e6, 1e6 + 1]], 0.7),  # huge offset
    ],
)
def test_degenerate_inputs_draw(centers, radii):
    b = Balls(centers, radii)
    for fig in (plot.disks(b), plot.dual_complex(b), plot.filtration(alpha_filtration(b))):
        assert isinstance(render(fig), Figure)
    if len(b):
        assert isinstance(render(plot.power_diagram(b)), Figure)


def test_degenerate_3d_and_ax_argument():
    b = Balls([[0, 0, 0], [1, 0, 0], [2, 0, 0]], 0.7)
    render(plot.complex3d(alpha_filtration(b)))
    render(plot.balls3d(b))
    fig, axes = plot.new_figure(1, 2)
    out = plot.dual_complex(rand(6, 2), ax=axes[1])
    assert out is fig and len(axes[1].collections) >= 3
    with pytest.raises(TypeError, match="Balls"):
        plot.disks(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="3D axes"):
        plot.balls3d(rand(3, 3), ax=axes[0])


def test_lifting_and_method_comparison():
    from shapelab.plot.balls import lifting, method_comparison

    b = Balls([[0.0, 0.0], [4.0, 0.0], [2.0, 3.0], [2.4, 1.5]], [2.3, 2.3, 2.3, 0.8])  # the last is hidden
    fig = render(lifting(b))
    ax = fig.axes[0]
    assert ax.name == "3d"
    hollow = [c for c in ax.collections if type(c).__name__ == "Path3DCollection" and len(c.get_offsets()) == 1]
    assert len(hollow) == 1  # the hidden disk, drawn above the hull
    assert "hidden" in " ".join(t.get_text() for t in ax.get_legend().get_texts())
    render(lifting(Balls([[0.0, 0.0], [1.0, 0.0]], 0.3)))  # too few for a triangle
    fig = render(method_comparison([1, 2, 3], {"a": [1e-3, 2e-3, np.nan], "b": [1, 2, 3]}, {"b": [1e-3, 1e-2, 1e-1]}))
    left, right = fig.axes
    assert len(left.get_lines()) == 2 and len(right.get_lines()) == 1
    assert right.get_lines()[0].get_color() == left.get_lines()[1].get_color()  # one colour per method
    assert len(left.get_lines()[0].get_xdata()) == 2  # NaN left out
    with pytest.raises(ValueError, match="values for"):
        method_comparison([1, 2], {"a": [1.0]})


def test_filtration_and_complex3d_take_balls_too():
    """The one input rule (issue 22): plot.filtration and plot.complex3d refused Balls."""
    import matplotlib.pyplot as plt

    from shapelab.datasets import fullerene_c60

    rng = np.random.default_rng(5)
    for fn, balls in (
        (plot.filtration, Balls(rng.random((12, 2)) * 4, 0.5)),
        (plot.complex3d, fullerene_c60()),
    ):
        a, b = fn(balls), fn(alpha_filtration(balls))
        try:
            assert [len(ax.get_children()) for ax in a.axes] == [len(ax.get_children()) for ax in b.axes]
        finally:
            plt.close(a), plt.close(b)
