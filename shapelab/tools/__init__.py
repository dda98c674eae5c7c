"""The research tools beside the course: many structures, the command line, clusters,
trajectories (Notes §23.1).

The course's core (``shapelab.balls`` ... ``shapelab.report``) is what a lesson
teaches; these modules run it on what a researcher brings -- a folder of thousands of
structures, a shell, a Dask cluster, a molecular-dynamics trajectory -- and add no
geometry of their own.  They import the core; the core never imports them
(``tests/library/test_layers.py``).  Their optional dependencies are extras:
``shapelab[dask]``, ``shapelab[md]``, ``shapelab[parquet]``.

==============  ==================================================================
``batch``       :func:`report_batch`: many structures at once, in parallel, resumable
``cli``         ``python -m shapelab report FILE...``: the command line
``cluster``     the optional Dask client of a batch or a trajectory (imports dask only then)
``trajectory``  :func:`trajectory_measures`: area, volume, cavities of MD frames (MDAnalysis),
                serially, in worker processes or on a Dask cluster
==============  ==================================================================

The old paths ``shapelab.batch``, ``shapelab.cli`` and ``shapelab.trajectory`` give
these modules (``shapelab._MOVED``).
"""

from __future__ import annotations

from .._toolkit.lazy import attach

_EXPORTS = {
    "report_batch": "batch",
    "BatchSummary": "batch",
    "main": "cli",
    "trajectory_measures": "trajectory",
}
_SUBMODULES = {"batch", "cli", "cluster", "trajectory"}

__all__ = sorted(_EXPORTS)

__getattr__, __dir__ = attach(__name__, _EXPORTS, _SUBMODULES, eager=__all__)
