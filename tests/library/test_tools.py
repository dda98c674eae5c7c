"""shapelab.tools: the research tools beside the course, and their old paths (issue 33)."""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
from pathlib import Path

import pytest

import shapelab

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize(
    "old, new", [("batch", "tools.batch"), ("cli", "tools.cli"), ("trajectory", "tools.trajectory")]
)
def test_old_paths_give_the_moved_module(old, new):
    assert importlib.import_module(f"shapelab.{old}") is importlib.import_module(f"shapelab.{new}")
    assert getattr(shapelab, old) is importlib.import_module(f"shapelab.{new}")


def test_public_names_are_where_they_were():
    from shapelab.batch import BatchSummary, report_batch
    from shapelab.trajectory import CavityTrack, TrajectoryMeasures, selection_radii, track_cavities

    from shapelab import tools, tracking

    assert shapelab.report_batch is report_batch is tools.report_batch and tools.BatchSummary is BatchSummary
    assert shapelab.trajectory_measures is tools.trajectory_measures
    assert shapelab.TrajectoryMeasures is TrajectoryMeasures is tracking.TrajectoryMeasures
    assert (CavityTrack, selection_radii, track_cavities) == (
        tracking.CavityTrack,
        tracking.selection_radii,
        tracking.track_cavities,
    )


@pytest.mark.parametrize("module", ["shapelab", "shapelab.cli", "shapelab.tools.cli"])
def test_every_way_of_running_the_command_line(module):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    r = subprocess.run([sys.executable, "-m", module, "--help"], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "usage: python -m shapelab" in r.stdout, (r.stdout, r.stderr)
