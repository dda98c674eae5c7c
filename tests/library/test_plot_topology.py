"""Tests of shapelab.plot.topology and shapelab.widgets.topology: the figures draw
exactly the data they are given (counted from the artists), and bad input is refused."""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib
import numpy as np
import pytest
from matplotlib.collections import LineCollection, PatchCollection, PathCollection, PolyCollection
from matplotlib.figure import Figure

import shapelab
from shapelab import datasets as D
from shapelab.plot import topology as PT
from shapelab.plot._style import COLORS, new_figure

matplotlib.use("Agg")

PAIRS = {
    0: np.array([[0.0, np.inf], [0.0, 1.0], [0.5, 2.0]]),
    1: np.array([[1.0, 3.0], [1.5, 1.6], [2.0, 2.05], [0.2, 4.0]]),
    2: np.zeros((0, 2)),
}


def render(fig):
    """Draw the figure for real (3D collections project their data when drawn)."""
    import io

    fig.savefig(io.BytesIO(), format="png")


def scatter_offsets(ax):
    return [c.get_offsets() for c in ax.collections if isinstance(c, PathCollection)]


# ------------------------------------------------------------ diagrams
def test_persistence_diagram_draws_every_pair():
    fig = PT.persistence_diagram(PAIRS, dim=2)
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    pts = np.concatenate(scatter_offsets(ax))
    assert len(pts) == 3 + 4
    # finite pairs at (birth, death); the essential class on the ∞ line above them
    for b, d in PAIRS[1]:
        assert np.any(np.all(np.isclose(pts, [b, d]), axis=1))
    inf_y = pts[np.isclose(pts[:, 0], 0.0) & (pts[:, 1] > 4.0), 1]
    assert len(inf_y) == 1 and inf_y[0] > 4.0
    assert ax.get_xlabel() == "birth τ" and ax.get_ylabel() == "death τ"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("H₁ holes" in t for t in labels)
    assert not any("H₂" in t for t in labels)  # the empty top dimension is left out


def test_persistence_diagram_min_persistence_greys_short_pairs():
    fig = PT.persistence_diagram(PAIRS, dims=[1], min_persistence=0.5)
    off = scatter_offsets(fig.axes[0])
    sizes = sorted(len(o) for o in off)
    assert sizes == [2, 2]  # two long pairs in colour, two short ones in grey


def test_persistence_diagram_of_a_filtration_matches_its_pairs():
    F = shapelab.alpha_filtration(D.ring(8, radius=2.0, disk_radius=0.9))
    P = F.persistence()
    fig = PT.persistence_diagram(F, tau=0.0)
    n = sum(len(o) for o in scatter_offsets(fig.axes[0]))
    assert n == sum(len(a) for a in P.values())


def test_draws_into_given_axes():
    fig, axes = new_figure(1, 2)
    out = PT.persistence_diagram(PAIRS, ax=axes[0])
    out2 = PT.barcode(PAIRS, ax=axes[1])
    assert out is fig and out2 is fig and len(fig.axes) == 2


# ------------------------------------------------------------ barcodes
def bar_segments(ax):
    return sum(len(c.get_segments()) for c in ax.collections if isinstance(c, LineCollection))


def test_barcode_one_bar_per_pair():
    fig = PT.barcode(PAIRS)
    assert bar_segments(fig.axes[0]) == 7
    # the infinite bar ends in an arrow head beyond every finite death
    heads = np.concatenate(scatter_offsets(fig.axes[0]))
    assert len(heads) == 1 and heads[0, 0] > 4.0


def test_barcode_simplification_and_cap():
    fig = PT.barcode(PAIRS, min_persistence=0.5)
    ax = fig.axes[0]
    assert bar_segments(ax) == 3 + 2
    assert "2 short bars" in ax.get_title()
    fig = PT.barcode(PAIRS, dims=1, max_bars=2)
    segs = [s for c in fig.axes[0].collections if isinstance(c, LineCollection) for s in c.get_segments()]
    lengths = sorted(np.ptp(np.asarray(s)[:, 0]) for s in segs)
    assert lengths == pytest.approx([2.0, 3.8])  # the two most persistent H1 bars


# ------------------------------------------------------------ Betti curves
def test_betti_curve_is_the_library_curve():
    F = shapelab.alpha_filtration(D.ring(8, radius=2.0, disk_radius=0.9))
    taus = np.linspace(-1, 4, 11)
    fig = PT.betti_curve(F, taus=taus, tau=0.0)
    lines = [ln for ln in fig.axes[0].get_lines() if len(ln.get_xdata()) == len(taus)]
    curve = F.betti_curve(taus)
    assert len(lines) == 2  # β0, β1 (β2 is always zero in the plane)
    for k, ln in enumerate(lines):
        assert np.array_equal(ln.get_ydata(), curve[:, k])


def test_betti_curve_from_arrays_and_default_taus():
    taus = np.array([0.0, 1.0, 2.0])
    curve = np.array([[3, 0, 0], [1, 1, 0], [1, 0, 0]])
    fig = PT.betti_curve((taus, curve))
    assert len(fig.axes[0].get_lines()) == 2
    F = shapelab.alpha_filtration(D.figure_23_2()[0])
    fig = PT.betti_curve(F)
    ax = fig.axes[0]
    x = ax.get_lines()[0].get_xdata()
    # the default range covers every finite death, so the pocket's hole shows
    P = F.persistence()
    assert x.max() >= np.max(P[1][:, 1])
    assert ax.get_yscale() == "symlog"  # ~100 components at first


@pytest.mark.parametrize(
    "call, exc",
    [
        (lambda: PT.persistence_diagram([1, 2]), TypeError),
        (lambda: PT.persistence_diagram({0: [[1.0, 0.0]]}), ValueError),
        (lambda: PT.persistence_diagram({0: [[np.nan, 1.0]]}), ValueError),
        (lambda: PT.persistence_diagram({"a": [[0.0, 1.0]]}), ValueError),
        (lambda: PT.persistence_diagram(PAIRS, dims=[5]), ValueError),
        (lambda: PT.persistence_diagram(PAIRS, tau=np.inf), ValueError),
        (lambda: PT.barcode(PAIRS, max_bars=0), ValueError),
        (lambda: PT.barcode(PAIRS, min_persistence=-1), ValueError),
        (lambda: PT.betti_curve("F"), TypeError),
        (lambda: PT.betti_curve((np.arange(3), np.zeros((2, 2)))), ValueError),
        (lambda: PT.voids(np.zeros((3, 2)), voids=[]), TypeError),
        (lambda: PT.pockets(D.ring(5), pockets=[], tau="x"), TypeError),
    ],
)
def test_bad_input(call, exc):
    with pytest.raises(exc):
        call()


# ------------------------------------------------------------ feature drawings
@dataclass(frozen=True)
class FakeVoid:
    cells: np.ndarray
    lining: np.ndarray
    born: float
    dies: float
    volume: float


@dataclass(frozen=True)
class FakePocket:
    cells: np.ndarray
    mouth: np.ndarray
    lining: np.ndarray
    closes_at: float
    fills_at: float
    volume: float


@dataclass(frozen=True)
class FakeTunnel:
    birth: float
    death: float
    cycle: np.ndarray


def polys(ax, color):
    from matplotlib.colors import to_rgba

    out = []
    for c in ax.collections:
        if (
            isinstance(c, PolyCollection)
            and len(c.get_facecolors())
            and np.allclose(c.get_facecolors()[0][:3], to_rgba(color)[:3])
        ):
            out.extend(c.get_paths())
    return out


def test_voids_2d_draws_cells_under_the_disks():
    b = D.ring(6, radius=2.0, disk_radius=1.2)
    cells = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 5], [3, 4, 5]])
    v = FakeVoid(cells, np.arange(6), -1.0, 2.8, 0.123)
    fig = PT.voids(b, voids=[v], tau=0.0)
    ax = fig.axes[0]
    assert len(polys(ax, COLORS["void"])) == 4
    disks = [c for c in ax.collections if isinstance(c, PatchCollection)][0]
    assert len(disks.get_paths()) == 6
    assert disks.get_zorder() > [c for c in ax.collections if isinstance(c, PolyCollection)][0].get_zorder()
    assert [t.get_text() for t in ax.texts] == ["V1"]
    assert "hole V1: area 0.12" in [t.get_text() for t in fig.legends[0].get_texts()]
    assert "1 hole at τ = 0" in ax.get_title()
    assert ax.get_aspect() == 1.0


def test_voids_grow_the_disks():
    b = D.ring(6, radius=2.0, disk_radius=1.0)
    fig = PT.voids(b, voids=[], tau=3.0)
    disks = [c for c in fig.axes[0].collections if isinstance(c, PatchCollection)][0]
    paths = disks.get_paths()
    assert len(paths) == 6
    for path, c in zip(paths, b.centers):  # radius sqrt(r^2 + tau) = 2
        r = np.linalg.norm(path.vertices - c, axis=1)
        assert np.isclose(r.min(), 2.0, rtol=1e-9)  # on-curve vertices


def test_pockets_2d_draws_mouths():
    b = D.ring(6, radius=2.0, disk_radius=1.2)
    p = FakePocket(np.array([[0, 1, 2], [0, 2, 3]]), np.array([[0, 3], [1, 2]]), np.array([0, 1, 2, 3]), 0.5, 2.0, 0.4)
    fig = PT.pockets(b, pockets=[p], tau=0.0, show_voids=False)
    ax = fig.axes[0]
    assert len(polys(ax, COLORS["accent"])) == 2
    mouths = [c for c in ax.collections if isinstance(c, LineCollection)]
    assert sum(len(m.get_segments()) for m in mouths) == 2
    seg = np.asarray(mouths[0].get_segments()[0])
    assert np.allclose(seg, b.centers[[0, 3]])
    assert "1 pocket at τ = 0" in ax.get_title()
    assert [t.get_text() for t in fig.legends[0].get_texts()] == ["pocket P1: area 0.40", "mouth", "lining balls"]


def test_tunnels_3d_draws_the_cycle():
    b = D.ring(8, radius=3.0, disk_radius=1.0, dim=3)
    cyc = np.array([[i, (i + 1) % 8] for i in range(8)])
    fig = PT.tunnels(b, tunnels=[FakeTunnel(-0.4, 8.0, cyc)], tau=0.0)
    render(fig)
    ax = fig.axes[0]
    assert ax.name == "3d"
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    lines = [c for c in ax.collections if isinstance(c, Line3DCollection)]
    assert len(lines) == 1 and len(lines[0].get_segments()) == 8


def test_voids_3d_draws_the_free_space_of_the_cells():
    b = D.fullerene_c60(jitter=1e-3)
    # a fake void: one interior "cell" made of 4 atoms around the centre
    far = np.argsort(b.centers @ np.array([1.0, 0.3, 0.1]))[[0, 20, 40, 59]]
    cells = np.array([np.sort(far)])
    fig = PT.voids(b, voids=[FakeVoid(cells, far, -0.9, 9.1, 1.0)])
    render(fig)
    ax = fig.axes[0]
    cloud = [c for c in ax.collections if isinstance(c, PathCollection)][-1]
    pts = np.asarray(cloud._offsets3d).T
    assert len(pts) > 100
    # every drawn point is free (outside every ball) and inside the cell
    assert np.all(shapelab.power_distance(pts, b).min(axis=1) > 0)
    X = b.centers[cells[0]]
    lam = np.linalg.solve((X[1:] - X[0]).T, (pts - X[0]).T)
    assert np.all(lam >= -1e-9) and np.all(lam.sum(0) <= 1 + 1e-9)
    assert "void V1" in [t.get_text() for t in fig.legends[0].get_texts()]


# ------------------------------------------------------------ with the library
def test_plots_of_real_features():
    left, _ = D.figure_23_2()
    P = shapelab.pockets(left, 0.0, min_persistence=1e-9)
    fig = PT.pockets(left, tau=0.0)
    assert len(polys(fig.axes[0], COLORS["accent"])) == sum(len(p.cells) for p in P)
    V = shapelab.voids(D.fullerene_c60(), 0.0)
    assert isinstance(PT.voids(D.fullerene_c60(), voids=V), Figure)
    assert isinstance(PT.tunnels(D.nanotube()), Figure)


def test_pocket_explorer_widget():
    from shapelab.widgets import pocket_explorer

    left, _ = D.figure_23_2()
    w = pocket_explorer(left, tau=0.0, steps=20)
    assert repr(w).startswith("PocketExplorer(n_balls=112, tau=0.00")
    assert "1 pocket, 0 holes" in w.status.value
    png = w.image.value
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    w.slider.value = 2.0  # the mouth has closed: a hole, no pocket
    assert "0 pockets, 1 hole" in w.status.value
    assert w.image.value != png
    with pytest.raises(ValueError):
        pocket_explorer(left, tau_range=(1.0, 0.0))
    with pytest.raises(TypeError):
        pocket_explorer(left.centers)


def test_pockets_3d_close_up_zooms_on_one_pocket_in_its_overview_colour():
    F = shapelab.alpha_filtration(D.globule())
    P = shapelab.pockets(F, 0.0, min_persistence=0.5)
    assert len(P) >= 3
    p = P[2]
    fig = PT.pockets(F, pockets=[p], numbers=[3], focus=True, show_voids=False, legend=False)
    render(fig)
    ax = fig.axes[0]
    # the axes hold the pocket's lining balls, and are smaller than the molecule's
    lining = F.balls.centers[p.lining]
    for (lo, hi), x in zip((ax.get_xlim(), ax.get_ylim(), ax.get_zlim()), lining.T):
        assert lo <= x.min() and x.max() <= hi
    assert np.ptp(ax.get_xlim()) < 0.8 * np.ptp(F.balls.centers[:, 0])
    # the free-space points are drawn in the colour of P3 of the overview, not of P1
    cloud = [c for c in ax.collections if isinstance(c, PathCollection)][-1]
    assert matplotlib.colors.to_hex(cloud.get_facecolor()[0]) == PT._pocket_color(3).lower()
    assert PT._pocket_color(3) != PT._pocket_color(1)
    # the overview names every pocket (and the void) beside it
    fig = PT.pockets(F, pockets=P, legend=False)
    render(fig)
    names = sorted(t.get_text() for t in fig.axes[0].texts)
    assert names == sorted(
        [f"P{k}" for k in range(1, len(P) + 1)] + [f"V{k}" for k in range(1, len(shapelab.voids(F, 0.0)) + 1)]
    )
    with pytest.raises(ValueError, match="numbers"):
        PT.pockets(F, pockets=P, numbers=[1])


def test_pocket_colours_are_none_of_the_other_roles():
    for i in range(1, 6):
        assert PT._pocket_color(i) not in (COLORS["mouth"], COLORS["ball"], COLORS["ball_edge"], COLORS["void"])


def test_pocket_gallery_has_an_overview_and_one_close_up_per_pocket():
    F = shapelab.alpha_filtration(D.globule())
    P = shapelab.pockets(F, 0.0, min_persistence=0.5)
    fig = shapelab.plot.pocket_gallery(F, pockets=P, elev=12, azim=-90)
    render(fig)
    assert len(fig.axes) == 1 + len(P)
    overview, *close = fig.axes
    assert sorted(t.get_text() for t in overview.texts)[: len(P)] == [f"P{k}" for k in range(1, len(P) + 1)]
    for k, (ax, p) in enumerate(zip(close, P), 1):  # in reading order, named and coloured as in the overview
        assert ax.get_title().startswith(f"P{k}: {len(p.cells)} cells")
        cloud = [c for c in ax.collections if isinstance(c, PathCollection)][-1]
        assert matplotlib.colors.to_hex(cloud.get_facecolor()[0]) == PT._pocket_color(k).lower()
    with pytest.raises(ValueError, match="3D"):
        shapelab.plot.pocket_gallery(D.ring(6, radius=2.0, disk_radius=1.2))
    with pytest.raises(ValueError, match="no pocket"):
        shapelab.plot.pocket_gallery(shapelab.alpha_filtration(D.fullerene_c60()), pockets=[])


@pytest.mark.parametrize("fn", [PT.persistence_diagram, PT.barcode, PT.betti_curve])
def test_balls_stand_for_their_filtration(fn):
    """The one input rule (issue 22): Balls or a Filtration alike; these refused Balls."""
    import matplotlib.pyplot as plt

    balls = D.fullerene_c60()
    a, b = fn(balls), fn(shapelab.alpha_filtration(balls))
    try:
        assert [ax.get_title() for ax in a.axes] == [ax.get_title() for ax in b.axes]
        assert [len(ax.get_children()) for ax in a.axes] == [len(ax.get_children()) for ax in b.axes]
    finally:
        plt.close(a), plt.close(b)


# ------------------------------------------------------------ boundary matrix, voxels
def test_reduced_matrix_marks_every_lowest_one():
    from shapelab.topology import reduce_boundary

    F = shapelab.alpha_filtration(shapelab.Balls([[0, 0], [2, 0], [2.2, 1.9], [0.1, 2.1]], 0.5))
    B = F.boundary_matrix()
    R, low = reduce_boundary(B.matrix)
    names = ["".join(map(str, F.simplices(k)[r])) for k, r in zip(B.dims, B.rows)]
    fig = PT.reduced_matrix(B.matrix, R, names, low)
    crosses = np.concatenate(scatter_offsets(fig.axes[1]))
    j = np.flatnonzero(np.asarray(low) >= 0)
    assert sorted(map(tuple, crosses.tolist())) == sorted(zip(j.tolist(), np.asarray(low)[j].tolist()))
    assert np.array_equal(fig.axes[0].images[0].get_array(), B.matrix.toarray() % 2)
    assert f"{len(j)} lowest ones" in shapelab.plot.alt_text(fig)
    fig2 = PT.reduced_matrix(B.matrix, R, names)  # low computed from R
    assert len(np.concatenate(scatter_offsets(fig2.axes[1]))) == len(j)
    with pytest.raises(ValueError, match="must be"):
        PT.reduced_matrix(B.matrix, R, names[:-1])


def test_voxel_slice_colours_each_bounded_component():
    labels = np.ones((6, 5, 4), dtype=np.int64)
    labels[0] = 0
    labels[2, 2, 1] = 2
    labels[4, 1, 1] = 3
    grid = (np.arange(6.0), np.arange(5.0), np.arange(4.0))
    fig = PT.voxel_slice(labels, grid)
    shown = fig.axes[0].images[0].get_array()
    assert np.array_equal(shown, labels[:, :, 1].T)  # the slice with most void voxels
    assert "2 bounded components" in shapelab.plot.alt_text(fig)
    with pytest.raises(ValueError, match="shape of the grid"):
        PT.voxel_slice(labels[:, :, 0], grid)
