"""The course's inputs, by kind (Notes §23.1, §23.2).

Everything here is either *generated* from documented geometry (nothing is
downloaded, and every random choice comes from a seeded
:class:`numpy.random.Generator`, so the same call gives the same balls on every
machine) or *shipped* with its provenance.  Lengths are in Å for the molecules and in
arbitrary units for the 2D figure inputs.

=================================  =====================================================
:mod:`~shapelab.datasets.molecules`   generated molecules: :func:`fullerene_c60`,
                                      :func:`nanotube`, :func:`bowl`, :func:`globule`
:mod:`~shapelab.datasets.figures`     the notes' figures' inputs: :func:`figure_23_1`,
                                      :func:`figure_23_2`, :func:`ring`,
                                      :func:`swiss_cheese`, :func:`nested_pockets`,
                                      :func:`mixed_dent`
:mod:`~shapelab.datasets.shapes`      sampled shapes: :func:`blob_curve`,
                                      :func:`bumpy_sphere`, :func:`ellipse_curve`,
                                      :func:`torus`, :func:`noisy_sphere`,
                                      :func:`sample_shape`, :func:`shape_family`
:mod:`~shapelab.datasets.structures`  shipped structures: :data:`STRUCTURES`,
                                      :func:`structure`, :func:`example_pdb`,
                                      :func:`trajectory_files`
=================================  =====================================================

Every name is imported from ``shapelab.datasets`` (``from shapelab.datasets import
structure``, ``datasets.fullerene_c60()``); the modules say which kind it is.
"""

from __future__ import annotations

from .figures import figure_23_1, figure_23_2, mixed_dent, nested_pockets, ring, swiss_cheese
from .molecules import (
    CARBON_RADIUS,
    GRAPHENE_LATTICE_CONSTANT,
    bowl,
    c60_edges,
    fullerene_c60,
    globule,
    globule_structure,
    nanotube,
    nanotube_radius,
)
from .shapes import (
    blob_curve,
    bumpy_sphere,
    ellipse_curve,
    icosphere,
    noisy_sphere,
    sample_shape,
    shape_family,
    torus,
)
from .structures import STRUCTURES, StructureInfo, example_pdb, structure, structure_path, trajectory_files

__all__ = [
    "fullerene_c60",
    "c60_edges",
    "nanotube",
    "nanotube_radius",
    "bowl",
    "globule",
    "globule_structure",
    "ring",
    "figure_23_1",
    "figure_23_2",
    "swiss_cheese",
    "nested_pockets",
    "mixed_dent",
    "example_pdb",
    "STRUCTURES",
    "StructureInfo",
    "structure",
    "structure_path",
    "trajectory_files",
    "noisy_sphere",
    "blob_curve",
    "ellipse_curve",
    "icosphere",
    "bumpy_sphere",
    "torus",
    "sample_shape",
    "shape_family",
    "GRAPHENE_LATTICE_CONSTANT",
    "CARBON_RADIUS",
]
