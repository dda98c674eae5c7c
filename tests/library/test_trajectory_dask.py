"""shapelab.trajectory_measures on a Dask cluster (``client=`` / ``scheduler=``).

The oracle is ``jobs=1`` on the same trajectory: a two-worker ``distributed.LocalCluster``
on loopback must give the same per-frame table, cavities and tracks, for a Universe held
in memory (pickled to the workers) and for adenylate kinase's files (opened anew by
each worker).  Each test is bounded by an alarm.  Skips without dask.distributed or
MDAnalysis.
"""

from __future__ import annotations

import signal
import warnings

import pytest

from shapelab.trajectory import trajectory_measures

# the fixtures of the serial tests, the oracle
from tests.library.test_trajectory import adk, adk_measures, bowl  # noqa: F401

dask = pytest.importorskip("dask", reason='dask is not installed (pip install "shapelab[dask]")')
distributed = pytest.importorskip(
    "distributed", reason='dask.distributed is not installed (pip install "shapelab[dask]")'
)
pytest.importorskip("MDAnalysis", reason='MDAnalysis is not installed (pip install "shapelab[md]")')

LIMIT = 120


@pytest.fixture(autouse=True)
def alarm():
    def fire(signum, frame):
        raise TimeoutError(f"the test took more than {LIMIT} s: is the Dask cluster answering?")

    old = signal.signal(signal.SIGALRM, fire)
    signal.alarm(LIMIT)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


@pytest.fixture(scope="module")
def cluster():
    # Dask's nanny starts its workers with MALLOC_TRIM_THRESHOLD_=65536, which makes glibc
    # return the library's mid-sized arrays to the system at once: about 3x the CPU time
    # (page faults).  Unset, as the README says for real clusters ("On a Dask cluster").
    def fire(signum, frame):  # the function-scoped alarm is not armed yet: a cluster that never starts
        raise TimeoutError(f"the LocalCluster did not start within {LIMIT} s")

    old = signal.signal(signal.SIGALRM, fire)
    signal.alarm(LIMIT)
    try:
        with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
            c = distributed.LocalCluster(
                n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
            )
        client = distributed.Client(c, timeout=60, set_as_default=False)  # not the default client
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    with c, client:
        yield c, client


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
