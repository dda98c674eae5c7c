"""Rigid registration (Notes §23.2): Horn's optimal rotation and ICP, in one place.

The algorithms are in two modules, one concept each: :mod:`shapelab.rotation` (Horn's
closed form :func:`optimal_rotation`, :func:`register`, :class:`RigidMotion`) and
:mod:`shapelab.icp` (:func:`icp`, the notes' four steps).  This module re-exports both,
so that ``from shapelab.registration import ...`` keeps working.
"""

from __future__ import annotations

from .icp import ICPResult, closest_points, icp
from .rotation import (
    DegenerateRotationWarning,
    RigidMotion,
    cross_covariance,
    horn_matrix,
    kabsch,
    optimal_rotation,
    register,
)

__all__ = [
    "DegenerateRotationWarning",
    "cross_covariance",
    "horn_matrix",
    "optimal_rotation",
    "kabsch",
    "RigidMotion",
    "register",
    "ICPResult",
    "icp",
    "closest_points",
]
