"""shapelab.plot.batch_summary and shapelab.plot.trajectory_volumes: the figures draw
exactly the numbers of the summary and of the tracks (read back from the artists), in
the stated order, the failed files named; bad input is refused."""

from __future__ import annotations

import csv
import io

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure

import shapelab
from shapelab.tools.batch import SUMMARY_COLUMNS, BatchSummary
from shapelab.tracking import CavityTrack, TrajectoryMeasures

matplotlib.use("Agg")


def row(stem, status="ok", pocket=None, void=None):
    r = dict.fromkeys(SUMMARY_COLUMNS)
    r.update(path=f"in/{stem}.pdb", stem=stem, status=status, error="boom" if status == "failed" else "")
    r.update(largest_pocket_volume=pocket, largest_void_volume=void)
    return r


ROWS = [
    row("a", pocket=120.0, void=8.0),
    row("bad", "failed"),
    row("b", pocket=300.0),
    row("c", "skipped", pocket=120.0, void=30.0),
    row("d"),  # no cavity at all
]


def bars(ax):
    """(y, width, colour) of every bar, top to bottom."""
    out = [
        (p.get_y() + p.get_height() / 2, p.get_width(), matplotlib.colors.to_hex(p.get_facecolor())) for p in ax.patches
    ]
    return sorted(out, key=lambda t: -t[0])


def test_bars_are_the_summary_sorted_failed_last():
    fig = shapelab.plot.batch_summary(BatchSummary(rows=tuple(ROWS)))
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_yticklabels()]
    # bottom to top: failed, then no cavity, then ties by the largest void, then the largest pocket
    assert labels == ["bad", "d", "a", "c", "b"]
    assert [t.get_color() for t in ax.get_yticklabels()][0] == shapelab.plot.COLORS["void"]
    widths = {}
    for y, w, c in bars(ax):
        widths.setdefault(labels[round(y)], []).append((c, w))
    blue, red = shapelab.plot.PALETTE[0].lower(), shapelab.plot.COLORS["void"].lower()
    assert widths["b"] == [(blue, 300.0), (red, 0.0)]
    assert widths["c"] == [(blue, 120.0), (red, 30.0)]
    assert widths["a"] == [(blue, 120.0), (red, 8.0)]
    assert widths["d"] == [(blue, 0.0), (red, 0.0)]
    assert "bad" not in widths  # a failed file has no bar ...
    texts = [t.get_text() for t in ax.texts]
    assert texts == ["✗ failed"]  # ... but a mark, on its own row
    assert ax.texts[0].xy == (0, 0)
    assert "4 reported, 1 failed" in ax.get_title()
    assert ax.get_xscale() == "linear"  # 8 to 300: less than two decades


def test_the_summary_csv_and_row_dicts_give_the_same_figure(tmp_path):
    summary = BatchSummary(rows=tuple(ROWS))
    path = tmp_path / "s.csv"
    path.write_text(summary.to_csv_text())
    a = shapelab.plot.batch_summary(summary).axes[0]
    for other in (path, str(path), list(ROWS)):
        b = shapelab.plot.batch_summary(other).axes[0]
        assert [t.get_text() for t in b.get_yticklabels()] == [t.get_text() for t in a.get_yticklabels()]
        assert bars(b) == bars(a)


def test_log_axis_when_volumes_span_decades_and_rank_plot_for_many():
    rows = [row(f"s{k:03d}", pocket=10.0 ** (1 + k / 20), void=None if k % 3 else 5.0) for k in range(60)]
    rows.append(row("broken", "failed"))
    fig = shapelab.plot.batch_summary(rows, max_labels=100)
    assert fig.axes[0].get_xscale() == "log"
    fig = shapelab.plot.batch_summary(rows)  # 61 > 25: a rank plot
    ax = fig.axes[0]
    assert ax.get_yscale() == "log" and "60 reported, 1 failed" in ax.get_title()
    pockets, voids = (ln.get_ydata() for ln in ax.lines)
    assert np.array_equal(pockets, sorted((r["largest_pocket_volume"] for r in rows[:60]), reverse=True))
    assert len(voids) == 20 and np.all(voids == 5.0)
    assert np.array_equal(ax.lines[0].get_xdata(), np.arange(1, 61))
    fig.savefig(io.BytesIO(), format="png")


@pytest.mark.parametrize("n", [1, 7, 25])
def test_names_do_not_overlap_at_slide_size(n):
    rows = [row(f"structure_{k:02d}", pocket=10.0 + k) for k in range(n - 1)] + [row("broken", "failed")]
    fig = shapelab.plot.batch_summary(rows)
    w, h = fig.get_size_inches()
    assert w == shapelab.plot.SLIDE[0] and h <= shapelab.plot.SLIDE[1]
    fig.canvas.draw()
    boxes = sorted((t.get_window_extent() for t in fig.axes[0].get_yticklabels()), key=lambda b: b.y0)
    assert len(boxes) == n
    assert all(a.y1 <= b.y0 for a, b in zip(boxes, boxes[1:]))  # no two names overlap
    assert all(t.get_fontsize() >= 10 for t in fig.axes[0].get_yticklabels())


@pytest.mark.parametrize(
    "rows", [[], [row("x", "failed"), row("y", "failed")], [row(f"f{i}", "failed") for i in range(30)]]
)
def test_nothing_reported_is_said_without_an_empty_legend(rows):
    ax = shapelab.plot.batch_summary(rows).axes[0]
    assert ax.get_legend() is None  # its swatches were both blue, for bars never drawn
    assert [t.get_text() for t in ax.texts if t.get_text() == "no structure reported"] == ["no structure reported"]
    assert list(ax.get_xticks()) == []
    assert [t.get_text() for t in ax.get_yticklabels()] == ([] if len(rows) > 25 else [r["stem"] for r in rows[::-1]])


def test_nan_volumes_are_no_bar():
    nan = float("nan")
    rows = [row("a", pocket=nan, void=nan), row("b", pocket=5000.0, void=nan), row("c", pocket=3.0)]
    ax = shapelab.plot.batch_summary(rows).axes[0]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["a", "c", "b"]
    assert all(np.isfinite(w) for _, w, _ in bars(ax))
    assert sorted(w for _, w, _ in bars(ax) if w > 0) == [3.0, 5000.0]
    assert ax.get_xscale() == "log" and ax.get_legend() is not None


def test_batch_summary_refuses_bad_input():
    with pytest.raises(TypeError, match="summary"):
        shapelab.plot.batch_summary(42)
    with pytest.raises(ValueError, match="largest_pocket_volume"):
        shapelab.plot.batch_summary([{"path": "x", "status": "ok"}])
    with pytest.raises(ValueError, match="max_labels"):
        shapelab.plot.batch_summary(ROWS, max_labels=0)


def test_an_existing_axes_is_drawn_into():
    fig, ax = shapelab.plot.new_figure()
    assert shapelab.plot.batch_summary(ROWS, ax=ax) is fig and len(ax.patches) == 8


# ------------------------------------------------------------------ trajectories
def measures():
    tracks = (
        CavityTrack(0, (0, 10, 20), ("pocket", "void", "pocket"), (50.0, 40.0, 55.0), (0.9, 0.8)),
        CavityTrack(1, (10,), ("pocket",), (7.0,), ()),
        CavityTrack(2, (20, 30), ("void", "void"), (12.0, 14.0), (1.0,)),
    )
    frame = np.array([0, 10, 20, 30])
    z = np.zeros(4)
    return TrajectoryMeasures(
        frame=frame,
        time=frame * 2.0,
        area=z,
        volume=np.array([1000.0, 990.0, 1010.0, 1005.0]),
        n_voids=z.astype(int),
        largest_void=z,
        n_pockets=z.astype(int),
        cavities=(),
        tracks=tracks,
        probe=1.4,
        min_overlap=0.5,
        n_atoms=100,
    )


def test_trajectory_volumes_draws_the_longest_tracks():
    m = measures()
    fig = shapelab.plot.trajectory_volumes(m, tracks=2)
    top, ax = fig.axes
    assert np.array_equal(top.lines[0].get_xdata(), [0, 20, 40, 60])
    assert np.array_equal(top.lines[0].get_ydata(), m.volume)
    # one line style per track (issue 35: colour is not the only cue), markers drawn without a line
    lines = [ln for ln in ax.lines if ln.get_linestyle() not in ("None", "")]
    assert [ln.get_linestyle() for ln in lines] == ["-", "--"]
    assert [ln.get_label() for ln in lines] == ["track 0", "track 2"]  # 3 frames, then 2
    assert np.array_equal(lines[0].get_xdata(), [0, 20, 40]) and np.array_equal(lines[0].get_ydata(), [50, 40, 55])
    markers = {(ln.get_marker(), tuple(ln.get_xdata())) for ln in ax.lines if ln.get_linestyle() in ("None", "")}
    assert ("o", (0.0, 40.0)) in markers and ("s", (20.0,)) in markers and ("s", (40.0, 60.0)) in markers
    fig.savefig(io.BytesIO(), format="png")


def test_trajectory_volumes_by_id_frames_and_ax():
    m = measures()
    fig, ax = shapelab.plot.new_figure()
    assert shapelab.plot.trajectory_volumes(m, tracks=[1], time=False, ax=ax) is fig
    (line,) = [ln for ln in ax.lines if ln.get_linestyle() == "-"]
    assert line.get_label() == "track 1" and np.array_equal(line.get_xdata(), [10])
    assert ax.get_xlabel() == "frame"
    with pytest.raises(ValueError, match="no track has id 7"):
        shapelab.plot.trajectory_volumes(m, tracks=[7])
    with pytest.raises(ValueError, match="tracks"):
        shapelab.plot.trajectory_volumes(m, tracks=-1)
    with pytest.raises(TypeError, match="TrajectoryMeasures"):
        shapelab.plot.trajectory_volumes(ROWS)


def test_rows_read_back_from_csv_are_numbers(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text(BatchSummary(rows=tuple(ROWS)).to_csv_text())
    with open(path, newline="") as fh:
        assert next(csv.DictReader(fh))["largest_void_volume"] == "8.000000"
    ax = shapelab.plot.batch_summary(path).axes[0]
    assert max(w for _, w, _ in bars(ax)) == 300.0
