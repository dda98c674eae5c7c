"""shapelab: biogeometric shape analysis for the course "Shape Analysis" (Lecture 23).

The public API is re-exported here and nothing else lives in this file.  Names are
imported lazily so that ``import shapelab`` stays fast and a notebook only pays for
the modules it uses.

Modules, one per concept of the notes:

============================  =====================================================
``shapelab.balls``            :class:`Balls`, :func:`power_distance` (§23.1)
``shapelab.triangulation``    :func:`power_diagram`, :func:`regular_triangulation`, :func:`orthosphere`
``shapelab.filtration``       :func:`alpha_filtration`, :func:`dual_complex`
``shapelab.persistence``      Betti numbers, persistence: the boundary-matrix reduction
``shapelab.homology``         chains, boundary matrices, Betti numbers over Z/2, by hand
``shapelab.cavities``         :func:`voids`, :func:`pockets`, :func:`tunnels`, grooves, mouths;
                              ``cavities.flow``: :func:`discrete_flow`, :func:`flow_pockets`
                              (the literature's pockets); ``cavities.freespace``: exact free
                              area/volume of cells (void and pocket volumes)
``shapelab.measure``          :func:`union_measure` (area/volume of a union)
``shapelab.oracles``          brute-force and sampling oracles (naive formula, Monte Carlo)
``shapelab.quaternion``       :class:`Quaternion` (§23.2, rotations)
``shapelab.rotation``         :func:`optimal_rotation` (Horn), :func:`register`, :class:`RigidMotion`
``shapelab.icp``              :func:`icp`: the notes' four steps (the function; module by import)
``shapelab.registration``     both of the above, re-exported
``shapelab.hausdorff``        :func:`hausdorff`, :func:`directed_hausdorff` (§23.2; module by import)
``shapelab.matching``         :func:`hausdorff_under_translation`, reference points
``shapelab.critical``         :func:`critical_points` on curves and surfaces
``shapelab.simplification``   :func:`simplify`: ε-simplification along a curve (ELZ 2002)
``shapelab.diagrams``         :func:`bottleneck_distance`, :func:`wasserstein_distance`, ``distance_matrix``
``shapelab.embedding``        :func:`classical_mds`: a distance matrix drawn in the plane
``shapelab.docking``          :func:`docking_score`, :class:`Docking`: buried area minus clashes, two-stage docking
``shapelab.features``         :func:`coarse_align`: starts for ICP from pose-free features
``shapelab.io``               :func:`read_structure` (PDB, mmCIF), :func:`read_pdb`
``shapelab.report``           :func:`report`: CASTp-style table of voids and pockets
``shapelab.tracking``         cavities along a trajectory: one frame measured, the tracking rule
``shapelab.datasets``         molecules, the figures' inputs, sampled shapes, shipped structures
``shapelab.tools``            beside the course: :func:`report_batch` (batches, Dask), :func:`trajectory_measures`, the CLI
``shapelab.peers``            GUDHI's diagrams of the lessons' inputs: live if installed, else shipped
``shapelab.plot``             one function per kind of figure, a shared style
``shapelab.widgets``          ipywidgets explorers built on :mod:`shapelab.plot`
``shapelab.check``            self-checks for exercises
============================  =====================================================

The research tools beside the course, which import the core and are never imported by
it (:mod:`shapelab.tools`):

============================  =====================================================
``shapelab.tools.batch``      :func:`report_batch`: many structures at once, in parallel, resumable
``shapelab.tools.trajectory`` :func:`trajectory_measures`: area, volume, cavities of MD frames (MDAnalysis)
``shapelab.tools.cli``        ``python -m shapelab report FILE...``: the command line
``shapelab.tools.cluster``    the optional Dask client of a batch or a trajectory
============================  =====================================================
"""

from __future__ import annotations

from ._toolkit.lazy import attach, moved

__version__ = "0.1.0"

_EXPORTS = {
    "Balls": "balls",
    "power_distance": "balls",
    "power_diagram": "triangulation",
    "PowerDiagram": "triangulation",
    "regular_triangulation": "triangulation",
    "orthosphere": "triangulation",
    "alpha_filtration": "filtration",
    "dual_complex": "filtration",
    "Filtration": "filtration",
    "Complex": "filtration",
    "union_measure": "measure",
    "UnionMeasure": "measure",
    "voids": "cavities.void",
    "pockets": "cavities.pocket",
    "tunnels": "cavities.tunnel",
    "grooves": "cavities.tunnel",
    "channel_profile": "cavities.tunnel",
    "Void": "cavities.void",
    "Pocket": "cavities.pocket",
    "Tunnel": "cavities.tunnel",
    "Cavity": "cavities.cavity",
    "discrete_flow": "cavities.flow",
    "flow_pockets": "cavities.flow",
    "DiscreteFlow": "cavities.flow",
    "FlowPocket": "cavities.flow",
    "Quaternion": "quaternion",
    "optimal_rotation": "rotation",
    "register": "rotation",
    "RigidMotion": "rotation",
    "icp": "icp",
    "ICPResult": "icp",
    "directed_hausdorff": "hausdorff",
    "hausdorff": "hausdorff",
    "hausdorff_under_translation": "matching",
    "TranslationMatch": "matching",
    "reference_point": "matching",
    "critical_points": "critical",
    "CriticalPoints": "critical",
    "read_pdb": "io",
    "read_structure": "io",
    "bottleneck_distance": "diagrams",
    "wasserstein_distance": "diagrams",
    "DiagramMatching": "diagrams",
    "classical_mds": "embedding",
    "Embedding": "embedding",
    "docking_score": "docking",
    "coarse_align": "features",
    "DockingScore": "docking",
    "Docking": "docking",
    "DockedPose": "docking",
    "curve_persistence": "simplification",
    "simplify": "simplification",
    "report": "report",
    "CavityReport": "report",
    "report_batch": "tools.batch",
    "trajectory_measures": "tools.trajectory",
    "TrajectoryMeasures": "tracking",
    # homology.py: chains, boundary matrices and Betti numbers over Z/2, by hand (lesson 02)
    "closure": "homology",
    "boundary_matrix": "homology",
    "rank_mod2": "homology",
    "k_simplices": "homology",
    "chain_boundary": "homology",
    "betti_numbers": "homology",
    "is_cycle": "homology",
    "is_boundary": "homology",
    "euler_characteristic": "homology",
    "positive_simplices": "homology",
}
_SUBMODULES = {
    "balls",
    "triangulation",
    "predicates",
    "power",
    "filtration",
    "topology",
    "homology",
    "persistence",
    "cavities",
    "flow",  # moved: shapelab.cavities.flow (_MOVED)
    "freespace",  # moved: shapelab.cavities.freespace (_MOVED)
    "measure",
    "oracles",
    "quaternion",
    "registration",
    "rotation",
    "distance",
    "matching",
    "critical",
    "io",
    "datasets",
    "peers",
    "plot",
    "widgets",
    "check",
    "simplification",
    "cavity_report",  # moved: shapelab.report (_MOVED)
    "tracking",
    "tools",
    "batch",  # moved: shapelab.tools.batch (_MOVED)
    "trajectory",  # moved: shapelab.tools.trajectory
    "cli",  # moved: shapelab.tools.cli
    "morse",
    "intersections",
    "general_position",
    "assignment",
    "intervals",
}

__all__ = sorted(_EXPORTS) + ["__version__"]


__getattr__, __dir__ = attach(__name__, _EXPORTS, _SUBMODULES, eager=__all__)

#: modules that moved (issue 33), by their old name: ``import shapelab.power`` still
#: gives the module now called ``shapelab.triangulation``
_MOVED: dict[str, str] = {
    "power": "triangulation",
    "exact": "_engine",
    "topology": "persistence",
    "distance": "hausdorff",
    "flow": "cavities.flow",
    "freespace": "cavities.freespace",
    "cavity_report": "report",
    "batch": "tools.batch",
    "cli": "tools.cli",
    "trajectory": "tools.trajectory",
}
moved(__name__, _MOVED)
#: ``shapelab.report`` is the function, also once its module ``shapelab.report`` is imported
