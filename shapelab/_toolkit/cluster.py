"""Dask, optional: the client a batch or a trajectory sends its tasks to.

``dask.distributed`` is imported only here, and only when a caller passes a client or
a scheduler address; ``import shapelab`` and local runs never import it.  Nothing here
schedules: the tasks go to Dask's own scheduler.
"""

from __future__ import annotations

from contextlib import contextmanager

__all__ = ["DASK_HINT", "distributed_module", "cluster_client", "cluster_threads"]

DASK_HINT = 'pip install "shapelab[dask]" (or pip install "dask[distributed]")'


def distributed_module(what: str):
    """``distributed``, or an ImportError saying which extra installs it."""
    try:
        import distributed
    except ImportError as exc:
        raise ImportError(f"{what} on a Dask cluster needs dask.distributed: {DASK_HINT}") from exc
    return distributed


@contextmanager
def cluster_client(client, scheduler, jobs: int, what: str):
    """The ``distributed.Client`` to use, or None for a local run.

    ``client`` is used as given (and left open); ``scheduler``, an address such as
    ``"tcp://10.0.0.5:8786"``, is connected to here and closed on leaving.  Both, or
    either with ``jobs`` other than 1, is a ValueError naming them.
    """
    if client is None and scheduler is None:
        yield None
        return
    if client is not None and scheduler is not None:
        raise ValueError("pass client= or scheduler=, not both")
    if jobs != 1:
        raise ValueError(
            f"jobs={jobs} is for local worker processes; with client= or scheduler= the cluster's workers run the tasks"
        )
    if scheduler is not None and not isinstance(scheduler, str):
        raise TypeError(f"scheduler must be an address such as 'tcp://HOST:8786', got {type(scheduler).__name__}")
    distributed = distributed_module(what)
    if client is not None:
        if not isinstance(client, distributed.Client):
            raise TypeError(f"client must be a dask.distributed.Client, got {type(client).__name__}")
        yield client
        return
    own = distributed.Client(scheduler, set_as_default=False)
    try:
        yield own
    finally:
        own.close()


def cluster_threads(client) -> int:
    """The worker threads the cluster has now (at least 1, so that a cluster still
    starting its workers gets work queued)."""
    return max(1, sum(client.nthreads().values()))
