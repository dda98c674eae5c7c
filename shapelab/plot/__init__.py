"""Plotting: one function per kind of figure, one shared style.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into a given
``ax`` and returns its figure) that says what it shows: :func:`alt_text` reads the
description the function wrote, :func:`describe` refines it (the figure's text
alternative on the site, in the decks and in the figure export).  None recomputes geometry: they draw results from
the rest of the library.

======================  ==============================================================
``balls``               disks, power diagrams, dual complexes, filtrations, 3D views
``topology``            persistence diagrams, barcodes, Betti curves, voids, pockets
``homology``            small simplicial complexes, chains, boundary matrices (lesson 02)
``flow``                the discrete flow in 2D: arrows, sinks, pocket regions
``critical``            critical points of curves and surfaces (lesson 13)
``hausdorff_distance``  Hausdorff witnesses, matching under translation, timings (lesson 14)
``docking``             docking landscapes and poses (lesson 18)
``classification``      families of shapes, distance matrices, embeddings (lesson 19)
``matching``            the four above under their earlier module name
``rotation``            point sets, ICP steps and convergence, rotations in 3D
``batch``               a batch's summary, volumes along a trajectory
``viewer3d``            ``view3d``: an interactive 3Dmol.js view of a molecule and its
                        voids, pockets, mouths and tunnels (HTML, not a Figure), offline
======================  ==============================================================
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
    # critical.py (lesson 11), hausdorff_distance.py (12), docking.py (16), classification.py (17);
    # matching.py re-exports the four under their earlier module name
    "critical_points": "critical",
    "critical_surface": "critical",
    "hausdorff": "hausdorff_distance",
    "docking_landscape": "docking",
    "docking_pose": "docking",
    "point_clouds": "classification",
    "distance_matrix": "classification",
    "embedding": "classification",
    "stability": "classification",
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


#: modules by lesson topic reachable as attributes (``shapelab.plot.matching.timings``)
_SUBMODULES = {"matching", "critical", "hausdorff_distance", "docking", "classification"}

__getattr__, __dir__ = attach(__name__, _EXPORTS, _SUBMODULES, eager=__all__)

# in a notebook, a figure's PNG output carries its description as alt text (_describe)
register()
