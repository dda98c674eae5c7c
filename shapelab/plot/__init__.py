"""Plotting: one function per kind of figure, one shared style.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into a given
``ax`` and returns its figure) that says what it shows: :func:`alt_text` reads the
description the function wrote, :func:`describe` refines it (the figure's text
alternative on the site, in the decks and in the figure export).  None recomputes geometry: they draw results from
the rest of the library.

================  ==============================================================
``balls``         disks, power diagrams, dual complexes, filtrations, 3D views
``topology``      persistence diagrams, barcodes, Betti curves, voids, pockets
``homology``      small simplicial complexes, chains, boundary matrices
``flow``          the discrete flow in 2D: arrows, sinks, pocket regions
``matching``      critical points, Hausdorff witnesses
``rotation``      point sets, ICP steps and convergence, rotations in 3D
``batch``         a batch's summary, volumes along a trajectory
``viewer3d``      ``view3d``: an interactive 3Dmol.js view of a molecule and its
                  voids, pockets, mouths and tunnels (HTML, not a Figure), offline
================  ==============================================================
"""

from __future__ import annotations

from .._toolkit.lazy import attach
from ._describe import alt_text, describe, register
from ._style import COLORS, PAGE, PALETTE, RC, SLIDE, new_figure, style, thin_3d_ticks

_EXPORTS = {
    # balls.py
    "disks": "balls",
    "power_diagram": "balls",
    "dual_complex": "balls",
    "filtration": "balls",
    "balls3d": "balls",
    "complex3d": "balls",
    # topology.py
    "persistence_diagram": "topology",
    "barcode": "topology",
    "betti_curve": "topology",
    "voids": "topology",
    "pockets": "topology",
    "pocket_gallery": "topology",
    "tunnels": "topology",
    "channel_profile": "topology",
    # homology.py: small complexes, chains, boundary matrices (lesson 02)
    "simplicial_complex": "homology",
    "boundary_matrix": "homology",
    "reduced_matrix": "topology",
    "voxel_slice": "topology",
    # flow.py
    "discrete_flow": "flow",
    # matching.py
    "critical_points": "matching",
    "critical_surface": "matching",
    "hausdorff": "matching",
    "docking_landscape": "matching",
    "docking_pose": "matching",
    "point_clouds": "matching",
    "distance_matrix": "matching",
    "embedding": "matching",
    "stability": "matching",
    # rotation.py
    "icp_step": "rotation",
    "icp_convergence": "rotation",
    "rotation_axis": "rotation",
    "point_sets": "rotation",
    "two_stage": "rotation",
    "displacement": "rotation",
    # batch.py: many structures, trajectories
    "batch_summary": "batch",
    "trajectory_volumes": "batch",
    # viewer3d.py: interactive, in the browser (3Dmol.js), not matplotlib
    "view3d": "viewer3d",
}

__all__ = [
    "COLORS",
    "PALETTE",
    "PAGE",
    "RC",
    "SLIDE",
    "new_figure",
    "style",
    "thin_3d_ticks",
    "describe",
    "alt_text",
    *sorted(_EXPORTS),
]


__getattr__, __dir__ = attach(__name__, _EXPORTS, eager=__all__)

# in a notebook, a figure's PNG output carries its description as alt text (_describe)
register()
