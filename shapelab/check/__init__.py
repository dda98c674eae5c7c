"""Self-checks for the exercises.

Call a check with *your* function, e.g. ``check.quaternion_product(my_product)``.
It runs your function on random and edge cases against the library and prints
"correct" or the first failing input with the expected and received values.
An exercise whose answer is a value uses ``check.value(name, yours, library's)``,
which says how a wrong answer is off but never what it should be.

One module per topic holds the checks; all are re-exported here.
"""

from __future__ import annotations

from .._toolkit.lazy import attach
from ._runner import CheckResult, allclose, run_check, value

_EXPORTS = {
    # balls.py: power distance, dual complex, union measure
    "power_distance": "balls",
    "orthogonal_radius": "balls",
    "union_area": "balls",
    "dual_edge": "balls",
    "attached_edge": "balls",
    # topology.py
    "euler_characteristic": "topology",
    "betti_numbers": "topology",
    "boundary_reduction": "topology",
    # homology.py: lesson 02, chains and Betti numbers by hand
    "rank_mod2": "homology",
    "complex_betti": "homology",
    "cycles_and_boundaries": "homology",
    # flow.py: the discrete flow (lesson 09)
    "flow_order": "flow",
    # matching.py
    "hausdorff": "matching",
    "directed_hausdorff": "matching",
    "critical_points": "matching",
    # rotation.py
    "quaternion_product": "rotation",
    "rotation_matrix": "rotation",
    "optimal_rotation": "rotation",
    "centroid_alignment": "rotation",
    # answers.py: value exercises whose reference stays out of the lesson
    "connected_time": "answers",
    "distinct_complexes": "answers",
    "standard_error_factor": "answers",
    "neck_closing": "answers",
    "mouth_closing": "answers",
    "flow_sinks": "answers",
    "torus_viewpoints": "answers",
    "radical_center": "answers",
    "void_count": "answers",
    "ring_tunnel": "answers",
    "buried_area": "answers",
    "most_spread_class": "answers",
    "rips_not_nerve": "answers",
    "curve_pairs": "answers",
    "euler_poincare": "answers",
    "most_exposed_residue": "answers",
    "pocket_residues": "answers",
    "void_radii": "answers",
    "void_components": "answers",
    "first_site_rank": "answers",
    # theory.py: the theory sections of issue 34
    "morse_maximum": "theory",
    "tie_break": "theory",
    "chain_volume": "theory",
    "wasserstein_by_hand": "theory",
    "wilson": "theory",
    # quizzes.py: the end-of-part quizzes
    "quiz": "quizzes",
    "show_quiz": "quizzes",
}
__all__ = ["CheckResult", "allclose", "run_check", "value", *sorted(_EXPORTS)]


__getattr__, __dir__ = attach(__name__, _EXPORTS, eager=__all__)
