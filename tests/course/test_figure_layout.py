"""Every exported figure is readable: what matplotlib can tell after drawing, checked.

For each registered figure (the notes' figures and the lessons' slides), drawn at the
slide size:
- no two tick labels of one axis overlap (in 3D, where matplotlib does not report the
  drawn boxes reliably, at most six labelled ticks per axis);
- no legend inside an axes covers a data point (a marker, a line vertex, a disk's centre,
  a polygon's vertex) of that axes;
- no text shows raw TeX (an ``_`` or ``^`` or backslash command outside ``$...$``);
- a legend is not repeated, identical, in several panels of one figure.

The checks read the bounding boxes matplotlib computes when it draws; each has a negative
control below that proves it can fail.
"""

from __future__ import annotations

import re

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.collections import PatchCollection, PathCollection  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402

figures = pytest.importorskip("course.figures")

NAMES = [name for name, spec in figures.FIGURES.items() if not figures.missing(spec)]
MAX_3D_TICKS = 6
RAW_TEX = re.compile(r"(?<![\\$])(\b\w+_\{?\w|\\[a-zA-Z]+|\w\^\{?\w)")


def _visible_ticklabels(axis, renderer):
    out = []
    lo, hi = sorted(axis.get_view_interval())
    span = hi - lo
    for loc, t in zip(axis.get_majorticklocs(), axis.get_ticklabels()):
        inside = lo - 1e-9 * span <= loc <= hi + 1e-9 * span
        if inside and t.get_visible() and t.get_text().strip():
            out.append((t.get_text(), t.get_window_extent(renderer)))
    return out


def tick_overlaps(fig) -> list[str]:
    """Pairs of tick labels of one axis whose boxes overlap by more than a pixel."""
    renderer = fig.canvas.get_renderer()
    bad = []
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        for axis in (ax.xaxis, ax.yaxis, getattr(ax, "zaxis", None)):
            if axis is None:
                continue
            labels = _visible_ticklabels(axis, renderer)
            if ax.name == "3d":
                # matplotlib does not report a 3D tick label's drawn box reliably: a policy
                # instead, at most MAX_3D_TICKS labelled ticks per axis of a 3D plot
                if len(labels) > MAX_3D_TICKS:
                    bad.append(f"{ax.get_title()!r}: {len(labels)} tick labels crowd a 3D axis")
                continue
            for i in range(len(labels)):
                for j in range(i + 1, len(labels)):
                    (ta, a), (tb, b) = labels[i], labels[j]
                    w = min(a.x1, b.x1) - max(a.x0, b.x0)
                    h = min(a.y1, b.y1) - max(a.y0, b.y0)
                    if w > 1 and h > 1:
                        bad.append(f"{ax.get_title()!r}: tick labels {ta!r} and {tb!r} overlap")
    return bad


def _data_points(ax) -> np.ndarray:
    """Display coordinates of the data an axes draws (markers, vertices, centres)."""
    pts = []
    for line in ax.get_lines():
        if not line.get_visible() or line.get_label().startswith("_child") and False:
            continue
        xy = np.column_stack(line.get_data(orig=False)).astype(float) if len(line.get_xdata()) else None
        if xy is not None and len(xy):
            pts.append(line.get_transform().transform(xy))
    for coll in ax.collections:
        if not coll.get_visible():
            continue
        if isinstance(coll, PathCollection):
            offs = coll.get_offsets()
            if len(offs):
                pts.append(coll.get_offset_transform().transform(np.asarray(offs, float)))
        elif isinstance(coll, PatchCollection):
            for path in coll.get_paths():
                v = path.vertices
                if len(v):
                    pts.append(coll.get_transform().transform(np.asarray(v, float)))
    for patch in ax.patches:
        if not patch.get_visible():
            continue
        if isinstance(patch, Circle):
            pts.append(
                patch.get_transform().transform(np.asarray([patch.center], float))
                if False
                else ax.transData.transform(np.asarray([patch.center], float))
            )
        elif isinstance(patch, Polygon):
            pts.append(patch.get_transform().transform(patch.get_xy()))
    pts = [p for p in pts if p.size]
    if not pts:
        return np.zeros((0, 2))
    out = np.vstack(pts)
    return out[np.all(np.isfinite(out), axis=1)]


def legends_covering_data(fig) -> list[str]:
    """Legends inside their axes that hide at least one data point of those axes."""
    renderer = fig.canvas.get_renderer()
    bad = []
    for ax in fig.axes:
        leg = ax.get_legend()
        if leg is None or not leg.get_visible() or ax.name == "3d":
            continue
        box = leg.get_window_extent(renderer)
        frame = ax.get_window_extent(renderer)
        if box.x1 <= frame.x0 or box.x0 >= frame.x1 or box.y1 <= frame.y0 or box.y0 >= frame.y1:
            continue  # placed outside the axes
        p = _data_points(ax)
        inside = p[(p[:, 0] > frame.x0) & (p[:, 0] < frame.x1) & (p[:, 1] > frame.y0) & (p[:, 1] < frame.y1)]
        hidden = (
            (inside[:, 0] > box.x0 + 1)
            & (inside[:, 0] < box.x1 - 1)
            & (inside[:, 1] > box.y0 + 1)
            & (inside[:, 1] < box.y1 - 1)
        )
        if hidden.any():
            bad.append(f"{ax.get_title()!r}: the legend covers {int(hidden.sum())} data point(s)")
    return bad


def raw_tex(fig) -> list[str]:
    """Texts that show TeX markup outside math mode."""
    bad = []
    for text in fig.findobj(matplotlib.text.Text):
        s = text.get_text()
        if not s or not text.get_visible():
            continue
        outside = re.sub(r"\$[^$]*\$", "", s)
        if RAW_TEX.search(outside):
            bad.append(f"raw TeX in {s!r}")
    return bad


def repeated_legends(fig) -> list[str]:
    seen = {}
    for ax in fig.axes:
        leg = ax.get_legend()
        if leg is None or not leg.get_visible():
            continue
        key = tuple(t.get_text() for t in leg.get_texts())
        seen.setdefault(key, []).append(ax)
    return [f"the legend {list(k)} is repeated in {len(v)} panels" for k, v in seen.items() if len(v) > 1 and k]


def faults(fig) -> list[str]:
    if not hasattr(fig.canvas, "get_renderer"):  # a Figure made without pyplot
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    fig.canvas.draw()
    return tick_overlaps(fig) + legends_covering_data(fig) + raw_tex(fig) + repeated_legends(fig)


@pytest.mark.parametrize("name", NAMES)
def test_figure_is_readable(name):
    fig = figures.build(name)
    try:
        assert faults(fig) == []
    finally:
        plt.close(fig)


# ---------------------------------------------------------------- negative controls
def test_the_checks_catch_overlapping_ticks_a_covering_legend_raw_tex_and_repeats():
    fig, axes = plt.subplots(1, 2, figsize=(4, 2))
    ax = axes[0]
    ax.plot([0, 1], [0, 1], "o", label="a long label that covers the points")
    ax.set_xticks(np.linspace(0, 1, 30))
    ax.set_xticklabels([f"{v:.4f}" for v in np.linspace(0, 1, 30)])
    ax.scatter([0.05], [0.95])
    ax.legend(loc="upper left", fontsize=14)
    axes[1].plot([0, 1], [0, 1], "o", label="a long label that covers the points")
    axes[1].legend()
    ax.set_title("r_j -> g_j")
    found = faults(fig)
    plt.close(fig)
    assert any("tick labels" in f for f in found)
    assert any("covers" in f for f in found)
    assert any("raw TeX" in f for f in found)
    assert any("repeated" in f for f in found)


def test_a_clean_figure_passes():
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([0, 1, 2], [0, 1, 0], "o-", label="$r_j$ data")
    ax.legend(loc="lower center")
    ax.set_title(r"$r_j \to g_j$")
    assert faults(fig) == []
    plt.close(fig)


def test_the_3d_policy_catches_a_crowded_axis():
    fig = plt.figure(figsize=(4, 4))
    ax = fig.add_subplot(projection="3d")
    ax.plot([0, 1], [0, 1], [0, 1])
    ax.set_xticks(np.linspace(0, 1, 11))
    found = faults(fig)
    plt.close(fig)
    assert any("crowd a 3D axis" in f for f in found)
