"""Dask, optional: the client a batch or a trajectory sends its tasks to.

``dask.distributed`` is imported only here, and only when a caller passes a client or
a scheduler address; ``import shapelab`` and local runs never import it.  Nothing here
schedules: the tasks go to Dask's own scheduler.
"""

from __future__ import annotations

from contextlib import contextmanager

__all__ = [
    "DASK_HINT",
    "distributed_module",
    "cluster_client",
    "cluster_threads",
    "submit_with_bytes",
    "cancelled_error",
]

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
        _check_workers(client, what)
        yield client
        return
    _check_scheduler(distributed, scheduler)
    own = distributed.Client(scheduler, set_as_default=False)
    try:
        _check_workers(own, what)
        yield own
    finally:
        own.close()


def _check_scheduler(distributed, address: str) -> None:
    """An OSError, within Dask's connect timeout, unless a Dask *scheduler* answers at ``address``.

    ``distributed.Client`` given an address where something else answers (a web server,
    the dashboard's port, a worker) fails with a MemoryError or a TypeError, and then
    its half-started client waits twice the timeout (60 s) before the process can end.
    One ``identity`` call on a fresh event loop, in a thread of its own (so that a
    notebook's running loop is left alone), tells first.
    """
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    import dask

    limit = dask.utils.parse_timedelta(dask.config.get("distributed.comm.timeouts.connect"), "s")

    async def identity():
        async with distributed.rpc(address) as scheduler:
            return await scheduler.identity()

    def ask():
        return asyncio.run(asyncio.wait_for(identity(), limit + 5))

    try:
        with ThreadPoolExecutor(1) as thread:
            kind = thread.submit(ask).result().get("type")
    except Exception as e:  # refused (after the timeout), unreachable, or not Dask's protocol
        msg = str(e).splitlines()[0] if str(e).strip() else type(e).__name__
        if isinstance(e, MemoryError):
            msg = "it does not speak Dask's protocol"
        raise OSError(f"no Dask scheduler answers at {address!r} ({msg})") from None
    if kind != "Scheduler":
        raise OSError(f"no Dask scheduler answers at {address!r} (a Dask {kind} does: give its scheduler's address)")


def _check_workers(client, what: str) -> None:
    """An ImportError unless every worker the cluster has now imports shapelab, the
    same version as here.

    A worker that cannot unpickle a task (``shapelab.batch`` missing) closes its
    connection and ends, and the tasks then wait for workers forever: asked first,
    the workers say so.  The question itself, ``eval`` of one expression, needs
    nothing but Python on the worker.  Workers that join later are not asked.
    """
    import sys

    # the package is imported already (this module is part of it): read its version without
    # an import of the top layer from this bottom one (tests/library/test_layers.py)
    shapelab = sys.modules[__name__.partition(".")[0]]

    try:
        found = client.run(eval, "__import__('shapelab').__version__")
    except Exception as e:  # a worker's ImportError, as the worker raised it
        msg = str(e).splitlines()[0] if str(e).strip() else type(e).__name__
        raise ImportError(
            f"{what}: a worker of the Dask cluster cannot import shapelab ({msg}); install shapelab "
            f"{shapelab.__version__} where the workers run"
        ) from None
    other = sorted(f"{worker} has {version}" for worker, version in found.items() if version != shapelab.__version__)
    if other:
        raise ImportError(
            f"{what}: the Dask workers need shapelab {shapelab.__version__}, as here, but {', '.join(other)}"
        )


def cluster_threads(client) -> int:
    """The worker threads the cluster has now (at least 1, so that a cluster still
    starting its workers gets work queued)."""
    return max(1, sum(client.nthreads().values()))


def submit_with_bytes(client, fn, *args, **kwargs):
    """``client.submit(fn, *args, **kwargs)`` whose arguments hold an input's bytes on
    purpose (in the task, the scheduler can give it to another worker if the first one
    dies): without Dask's "Sending large graph" warning for each input over 10 MB."""
    import dask
    from dask.utils import parse_bytes

    key = "distributed.admin.large-graph-warning-threshold"
    limit = dask.config.get(key, 0)
    limit = parse_bytes(limit) if isinstance(limit, str) else int(limit or 0)
    size = sum(len(a) for a in args if isinstance(a, (bytes, bytearray, memoryview)))
    with dask.config.set({key: max(limit, size + 2**20)}):
        return client.submit(fn, *args, **kwargs)


def cancelled_error(distributed):
    """The exception a future's ``result()`` raises when its task was cancelled (the
    scheduler lost, or someone cancelled it): not an ``Exception`` subclass."""
    return getattr(distributed, "FutureCancelledError", None) or distributed.client.FutureCancelledError
