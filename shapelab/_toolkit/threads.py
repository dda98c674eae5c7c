"""How many threads a computation may start: ``SHAPELAB_THREADS`` or the CPUs this
process may use, capped, and one inside a thread other than the main one (no pools
in pools).  Shared by :mod:`shapelab.freespace` (slices of cell-ball pairs) and
:mod:`shapelab._engine.triangulation` (blocks of the triangulation)."""

from __future__ import annotations

import os
import threading

__all__ = ["thread_count"]


def thread_count(n_tasks: int, cap: int = 4) -> int:
    """Threads for ``n_tasks`` independent tasks: the CPUs this process may use, at
    most ``cap`` by default (``SHAPELAB_THREADS`` in the environment overrides it; 1
    runs them in the calling thread), never more than there are tasks, and 1 when
    called from a thread other than the main one (a Dask worker's or a caller's own
    pool: no pools in pools).

    Raises ValueError naming ``SHAPELAB_THREADS`` if it is not a positive integer.

    >>> thread_count(1)
    1
    """
    if threading.current_thread() is not threading.main_thread():
        return 1
    env = os.environ.get("SHAPELAB_THREADS", "").strip()
    if env:
        try:
            n = int(env)
        except ValueError:
            raise ValueError(f"SHAPELAB_THREADS must be a positive integer, got {env!r}") from None
        if n < 1:
            raise ValueError(f"SHAPELAB_THREADS must be a positive integer, got {env!r}")
    else:
        n = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
        n = min(n, cap)  # each thread holds its task's temporaries
    return max(1, min(n, n_tasks))
