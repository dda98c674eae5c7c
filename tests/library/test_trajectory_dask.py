"""shapelab.trajectory_measures on a Dask cluster (``client=`` / ``scheduler=``).

The oracle is ``jobs=1`` on the same trajectory: a two-worker ``distributed.LocalCluster``
on loopback must give the same per-frame table, cavities and tracks, for a Universe held
in memory (pickled to the workers) and for adenylate kinase's files (opened anew by
each worker).  Each test is bounded by an alarm.  Skips without dask.distributed or
MDAnalysis.
"""

from __future__ import annotations

import warnings

import pytest

from shapelab.tools.trajectory import trajectory_measures

# the fixtures of the serial tests, the oracle
from tests.library.test_trajectory import adk, adk_measures, bowl  # noqa: F401

dask = pytest.importorskip("dask", reason='dask is not installed (pip install "shapelab[dask]")')
distributed = pytest.importorskip(
    "distributed", reason='dask.distributed is not installed (pip install "shapelab[dask]")'
)
pytest.importorskip("MDAnalysis", reason='MDAnalysis is not installed (pip install "shapelab[md]")')

# the same guard against a hung cluster and the same two-worker LocalCluster as the batch's tests
from tests.library.test_batch_dask import alarm, cluster  # noqa: E402, F401


def same(a, b):
    assert a.rows() == b.rows() and a.tracks == b.tracks
    for x, y in zip(a.cavities, b.cavities):
        assert [(c.kind, c.track, c.volume, c.lining.tolist()) for c in x] == [
            (c.kind, c.track, c.volume, c.lining.tolist()) for c in y
        ]


def test_bowl_on_the_cluster_equals_serial(bowl, cluster):  # noqa: F811
    u, r = bowl
    same(trajectory_measures(u, select="all", probe=0.0, progress=False, client=cluster[1]), r)
    addr = cluster[0].scheduler_address  # connects, and closes its own client
    r2 = trajectory_measures(u, select="all", probe=0.0, progress=False, stop=2, scheduler=addr)
    assert r2.rows() == r.rows()[:2]


def test_adk_files_on_the_cluster_equal_serial(adk, adk_measures, cluster):  # noqa: F811
    with warnings.catch_warnings():
        # as in test_trajectory: MDAnalysis' DCD reader announces a change in 3.0
        warnings.simplefilter("ignore", DeprecationWarning)
        r = trajectory_measures(*adk, stop=60, step=30, progress=False, client=cluster[1])
    same(r, adk_measures)


def test_bad_cluster_arguments(bowl, cluster, monkeypatch):  # noqa: F811
    u, _ = bowl
    with pytest.raises(ValueError, match="jobs=2"):
        trajectory_measures(u, select="all", progress=False, jobs=2, client=cluster[1])
    with pytest.raises(ValueError, match="not both"):
        trajectory_measures(u, select="all", progress=False, client=cluster[1], scheduler="tcp://127.0.0.1:1")
    with pytest.raises(TypeError, match="client"):
        trajectory_measures(u, select="all", progress=False, client=object())
    monkeypatch.setitem(__import__("sys").modules, "distributed", None)
    with pytest.raises(ImportError, match=r"shapelab\[dask\]"):
        trajectory_measures(u, select="all", progress=False, scheduler="tcp://127.0.0.1:1")
