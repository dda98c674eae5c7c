"""The figures of shape matching, by their earlier module name (Notes §23.2).

The figures now live by lesson topic -- :mod:`shapelab.plot.critical` (lesson 11),
:mod:`shapelab.plot.hausdorff_distance` (lesson 12), :mod:`shapelab.plot.docking`
(lesson 16), :mod:`shapelab.plot.classification` (lesson 17) -- and this module
re-exports them, so that ``from shapelab.plot import matching as plot_matching`` and
``plot_matching.timings(...)`` keep working.  Every name is also ``shapelab.plot.NAME``.
"""

from __future__ import annotations

from .classification import distance_matrix, embedding, point_clouds, stability
from .critical import critical_points, critical_surface
from .docking import docking_landscape, docking_pose
from .hausdorff_distance import hausdorff, timings, translation

__all__ = [
    "critical_points",
    "critical_surface",
    "hausdorff",
    "translation",
    "timings",
    "docking_landscape",
    "docking_pose",
    "point_clouds",
    "distance_matrix",
    "embedding",
    "stability",
]
