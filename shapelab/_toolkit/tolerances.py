"""Every numerical tolerance shapelab decides something with, in one place.

Combinatorics (which simplex exists, which ball is hidden, the affine dimension of
the centres) are decided by the exact predicates of :mod:`shapelab._engine.predicates`,
never by a tolerance (CONTRIBUTING, "Exact geometry").  What is left here guards
floating-point *values*: a candidate that an exact certificate checks afterwards, a
margin that keeps a pruning step a superset, a tie rule for values certified to a
known relative accuracy, a stopping rule of an optimiser.  Each constant says what
it guards, what it is relative to, and why its value; ``tests/library/test_tolerances.py``
checks the relations between them.

Not here: error *bounds* that are formulas of the unit roundoff (the filters of
:mod:`shapelab._engine.predicates`, the margins ``8 (d + 4) eps`` of
:mod:`shapelab.distance`, the first-order bound of the filtration's entry times),
and user parameters with a documented default (``matching.optimal_hausdorff``'s
``tol``).
"""

from __future__ import annotations

__all__ = [
    "UNDERFLOW_FLOOR",
    "LINING_AREA_RTOL",
    "DISTANCE_MATRIX_SYMMETRY",
    "ROTATION_EIGEN_GAP",
    "ANDERSON_RCOND",
    "ROTVEC_SERIES_ANGLE",
    "QLOG_SMALL_VECTOR",
    "FILTER_UNDERFLOW",
    "QHULL_VERTICAL",
    "QHULL_STEEP",
    "QHULL_FLAT",
    "QHULL_TIEBREAK",
    "BLOCK_SLACK",
    "BLOCK_POWER",
    "BLOCK_GAP_VOLUME",
    "COVER_PREFILTER",
    "ORTHOCENTRE_CONDITION",
    "ENTRY_TIME_RTOL",
    "ENTRY_TIME_SAFETY",
    "GRAM_PINV_RCOND",
    "PERSISTENCE_ROUNDOFF",
    "MEASURE_TIE",
    "MEASURE_TANGENT",
    "MEASURE_FLAT",
    "PLANE_DETERMINANT",
    "PLANE_FEASIBILITY",
    "PLANE_INCIDENCE_FACTOR",
    "PARALLEL_NORMALS",
    "EDGE_HEIGHT",
    "DISTANCE_BOX_REL",
    "DISTANCE_TIE_REL",
    "DISTANCE_REACH_REL",
    "DISTANCE_AGREE",
    "CURVE_CLOSED",
    "CURVE_FLAT",
    "CURVE_STEP",
    "CURVE_ROOT_XTOL",
    "CURVE_MIN_XATOL",
    "CURVE_WRAP",
    "CURVE_MERGE",
    "CHANNEL_XATOL",
    "CHANNEL_FATOL",
    "MATCHING_GAP_ABS",
    "MATCHING_STEP_REL",
    "MATCHING_XATOL",
    "MATCHING_FATOL",
]

# ------------------------------------------------------------------ generic
#: A length, distance or determinant at or below this is treated as zero before a
#: division (and added to a bound so that it stays positive).  Absolute: the
#: smallest normal float64 is 2.2e-308, so 1e-300 is "zero" at every scale an input
#: of physical size reaches, and never rounds a real quantity of any input away.
UNDERFLOW_FLOOR = 1e-300

# ------------------------------------------------------------------ report
#: An atom lines a cavity when its wall area in the cavity's cells exceeds this
#: fraction of its own sphere's area, 4π r² (relative to the atom's solvent-accessible
#: sphere, so the rule does not depend on the length unit).  The wall areas are exact
#: up to round-off (~1e-15 relative to the sphere); 1e-10 keeps round-off slivers out
#: and every real contact in (a protein atom's 1e-10 of ~110 Å² is ~1e-8 Å²).
LINING_AREA_RTOL = 1e-10

# ------------------------------------------------------------------ registration
#: ``optimal_rotation`` calls the optimum *not unique* when the gap between the two
#: largest eigenvalues of Horn's matrix is at most this, relative to the largest
#: |eigenvalue|, and then returns the optimal rotation of smallest angle.  A float
#: decision, not an exact one: the gap of a set of spread s across its line grows as
#: s², so sets with s below ~3e-5 of their length count as collinear, and exactly
#: collinear sets far from the origin (offset/spread ~1e9) can exceed it (documented
#: in ``optimal_rotation``'s Warns section).
ROTATION_EIGEN_GAP = 1e-9
#: Cut-off of the least-squares solve of ICP's Anderson acceleration, relative to the
#: largest singular value of the difference matrix: a nearly dependent history of
#: steps is dropped rather than amplified (an accelerated step is only a candidate:
#: ICP keeps it only if it does not increase the cost).
ANDERSON_RCOND = 1e-10

# ------------------------------------------------------------------ quaternion
#: ``sin(θ/2)/θ`` switches to its Taylor series ``1/2 - θ²/48`` below this angle (in
#: radians, absolute): the series' first omitted term, θ⁴/3840, is below 1e-19 there,
#: under the rounding of the direct formula.
ROTVEC_SERIES_ANGLE = 1e-4
#: The log of a unit quaternion divides by the norm s of its vector part; at or below
#: this (absolute, for unit quaternions) it uses the limit angle/s -> 2, exact to
#: O(s²) = 1e-24.
QLOG_SMALL_VECTOR = 1e-12

# ------------------------------------------------------------------ embedding
#: ``classical_mds`` accepts a distance matrix as symmetric with a zero diagonal when
#: its asymmetry and diagonal are at most this, relative to its largest entry: the
#: round-off of distances computed in float64 (a few ulps), never a real asymmetry.
DISTANCE_MATRIX_SYMMETRY = 1e-12

# ------------------------------------------------------------------ predicates
#: The floating-point filter of :mod:`shapelab._engine.predicates` trusts a sign only when
#: its error bound exceeds this; below it the bound may itself have underflowed,
#: and the determinant is recomputed exactly.  Absolute, on the bound (a product of
#: up to four coordinate differences and heights): 1e-280 leaves 28 decades above
#: the subnormal range.  It routes a test to exact arithmetic, never decides it.
FILTER_UNDERFLOW = 1e-280

# ------------------------------------------------------------------ power (Qhull's candidate)
#: A lower facet of the lifted hull has a downward normal; a facet whose normal's
#: height component is above ``-QHULL_VERTICAL`` is vertical (it projects to a flat
#: simplex).  In the conditioned frame (centres and heights scaled to unit size), a
#: genuine facet this steep would have an orthoradius above ~1e10.  Only shapes
#: Qhull's candidate: the exact certificate (:mod:`shapelab._engine.certify`) decides, and
#: a wrong guess sends the input to the exact incremental algorithm.
QHULL_VERTICAL = 1e-10
#: Facets with a height component in ``(-QHULL_STEEP, -QHULL_VERTICAL)`` are
#: "steep" and are dropped when their projection is flat (:data:`QHULL_FLAT`): Qhull
#: computes the normal of a vertical facet from nearly coplanar points with errors
#: up to ~2e-6, so the vertical test alone misses some.  Slope 1000 in the unit
#: frame.  Candidate only, as above.
QHULL_STEEP = 1e-3
#: A steep facet is flat in projection when ``|det| <= QHULL_FLAT * prod |edges|``
#: (relative to the simplex's own edge lengths: scale-free).  Candidate only.
QHULL_FLAT = 1e-12
#: Where Qhull's candidate fails its certificate everywhere (grids, cages), a second
#: candidate lowers each normalised lifted height (in [-1, 1]) by
#: ``QHULL_TIEBREAK * (1 - rank/n)**2``, ``rank`` the tie-break order of Simulation of
#: Simplicity: far above Qhull's round-off (~1e-15) so that it decides the ties, far
#: below the heights' spread so that it changes few decisions that are not ties.  It
#: agrees with the symbolic perturbation on full lattices in row-major input order
#: (any order of the axes, either direction), not on lattices with holes or in a
#: shuffled order; elsewhere the certificate and the local repair decide.  Its effect
#: on one cell of an m^3 lattice is of order ``QHULL_TIEBREAK / m**5``: 40^3 nodes
#: certify, at 47^3 Qhull no longer resolves it and the whole-input road runs (1e-4
#: certifies 47^3 but triples the repaired cavity of 2nwl).  Candidate only.
QHULL_TIEBREAK = 1e-5
#: The candidate in blocks (threads): a block vouches for a tetrahedron when its
#: orthoball, enlarged by the largest weight and by this relative slack, lies within
#: the block's slab.  Candidate only (the exact certificate decides).
BLOCK_SLACK = 1e-9
#: ... or when no point outside the block in that ball has power below
#: ``-BLOCK_POWER * |rho|`` to the orthosphere (floating point; candidate only).
BLOCK_POWER = 1e-12
#: The fill of the gaps between blocks gives up when its tetrahedra's volume exceeds
#: the gaps' by more than this fraction of the hull's (round-off; candidate only).
BLOCK_GAP_VOLUME = 1e-9

# ------------------------------------------------------------------ certify
#: The cover count of :func:`shapelab._engine.certify.certify` picks, by float bounding
#: boxes, the simplices that may contain a centroid, then decides each one exactly.
#: The boxes are widened by this fraction of (the simplex's extent + the centroid's
#: magnitude): relative to the coordinates, so an offset input keeps it far above
#: the rounding of the centroid (a few ulps).  A prefilter: too large only costs time.
COVER_PREFILTER = 1e-6

# ------------------------------------------------------------------ power diagram
#: The orthocentre of a top simplex is solved in floating point when
#: ``|det A| > ORTHOCENTRE_CONDITION * prod |rows of A|`` (the simplex is not a
#: sliver, relative to its own edges), else in rationals.  Decides the road to a
#: value, not a combinatorial fact: its relative error stays ~1e-8 of the vertex's
#: distance at worst.
ORTHOCENTRE_CONDITION = 1e-8

# ------------------------------------------------------------------ filtration
#: Entry times (smallest orthogonal spheres) computed in floating point are
#: accepted when ``ENTRY_TIME_SAFETY`` times their first-order error bound is at most
#: ``ENTRY_TIME_RTOL`` times the value; others go to long double, then to exact
#: rationals (rounded once).  Relative to the value itself (exact zeros are exact),
#: so every entry time is within ENTRY_TIME_RTOL of the exact one.
ENTRY_TIME_RTOL = 1e-9
#: Factor on the first-order bound for the neglected second-order terms.
ENTRY_TIME_SAFETY = 2.0
#: Cut-off of the pseudo-inverse for exactly affinely dependent rows only (their
#: dependency is decided exactly first), relative to the largest singular value.
GRAM_PINV_RCOND = 1e-10

# ------------------------------------------------------------------ topology
#: A persistence pair counts as zero-length when ``death - birth <=
#: PERSISTENCE_ROUNDOFF * max(|birth|, |death|, scale)``: relative to the values,
#: or to the input's size in units of τ near τ = 0 (``scale``: the larger of the
#: median r² and the median squared half-length of the edges that join components,
#: :func:`shapelab.topology.is_roundoff`; geometric, since the entry times of the
#: slivers of nearly flat input reach 1e30).  Two entry times whose exact values tie may differ by up to
#: ``2 ENTRY_TIME_RTOL / (1 - ENTRY_TIME_RTOL)`` relative, so a guaranteed filter
#: needs ``PERSISTENCE_ROUNDOFF >= 2 ENTRY_TIME_RTOL / (1 - ENTRY_TIME_RTOL)``
#: (``tests/library/test_tolerances.py``); 2.5e-9 meets it with a margin.  A pair shorter
#: than that cannot be told from a tie at the accuracy the entry times are certified
#: to (on a protein, τ ~ 10 Å²: 2.5e-8 Å²).
PERSISTENCE_ROUNDOFF = 2.5e-9

# ------------------------------------------------------------------ measure
#: A simplex with entry time v is in the complex measured at τ iff
#: ``v + MEASURE_TIE * |v| < tau`` (K just before τ).  Relative to the entry time;
#: must exceed ENTRY_TIME_RTOL so that simplices whose exact entry times tie at τ are
#: all left out, whatever their rounding.
MEASURE_TIE = 1e-8
#: A pair of balls whose chord disk has squared radius at most this fraction of
#: ``max(r_a^2, r_b^2, d_ab^2)`` is tangent: rounding noise of relative size eps in
#: rho^2 would otherwise become noise of size sqrt(eps) in the angles.  Relative to
#: the pair's own size; ~450 ulps.
MEASURE_TANGENT = 1e-13
#: A top simplex with ``|det(edges)| / (longest edge)^d`` below this is measured by
#: the flat limit formulas (its orthocentre would be rounding noise).  Relative to
#: the simplex's size.  Chooses between two formulas of the same continuous value.
MEASURE_FLAT = 1e-9

# ------------------------------------------------------------------ freespace
#: d unit normals are independent (a polytope vertex exists) when their determinant
#: exceeds this.  Absolute on unit normals, i.e. relative: an angle of ~1e-12 rad.
PLANE_DETERMINANT = 1e-12
#: A candidate vertex is feasible when it lies within ``PLANE_FEASIBILITY * scale``
#: of every plane (``scale`` the extent of the clipped cell), so a vertex on a plane
#: up to rounding is kept.  Relative to the cell.
PLANE_FEASIBILITY = 1e-12
#: A vertex is incident to a plane within ``PLANE_INCIDENCE_FACTOR`` times the
#: feasibility tolerance, and two planes with offsets that close are the same: the
#: incidence test must accept every vertex the feasibility test let through.
PLANE_INCIDENCE_FACTOR = 10.0
#: Two unit normals are the same direction when their dot product exceeds
#: ``1 - PARALLEL_NORMALS`` (an angle of ~1.4e-6 rad).
PARALLEL_NORMALS = 1e-12
#: A face edge contributes to a ball's wall only when its plane's distance from the
#: centre exceeds ``EDGE_HEIGHT * r`` (a plane through the centre contributes 0, and
#: the formula divides by that distance).  Relative to the radius.
EDGE_HEIGHT = 1e-14

# ------------------------------------------------------------------ distance
#: Relative widening of the cell boxes' distance bounds (a few ulps are needed; far
#: above, so pruning keeps a superset).  Relative to the squared distances.
DISTANCE_BOX_REL = 1e-12
#: Nearest neighbours within ``(1 + DISTANCE_TIE_REL)`` of the best distance are
#: re-evaluated by the direct formula, so that ties are broken bit-exactly the same
#: way whatever found them.  Relative to the distance.
DISTANCE_TIE_REL = 1e-12
#: Relative widening of k-d tree query radii (the tree's own rounding differs from
#: ours in the last bits).  Relative to the radius.
DISTANCE_REACH_REL = 1e-9
#: ``timings(...).agree``: the algorithms' distances agree within this, relative to
#: the distance (each is exact up to the last bits of one square root).
DISTANCE_AGREE = 1e-12

# ------------------------------------------------------------------ critical points of a curve
#: ``curve(2π)`` must equal ``curve(0)`` within this fraction of the curve's size + 1.
CURVE_CLOSED = 1e-9
#: The distance function is constant (every point critical) when its samples'
#: spread is at most this fraction of their maximum.
CURVE_FLAT = 1e-12
#: Step (in the parameter t, radians) of the central difference of the derivative.
CURVE_STEP = 1e-3
#: Absolute parameter tolerance of the root finder (``brentq``).
CURVE_ROOT_XTOL = 1e-15
#: Absolute parameter tolerance of the bounded minimiser.
CURVE_MIN_XATOL = 1e-12
#: A parameter within this of 2π is t = 0 (absolute, radians).
CURVE_WRAP = 1e-12
#: Two refined extrema of one kind closer than this (radians) are one: must exceed
#: the refiners' accuracy (CURVE_MIN_XATOL).
CURVE_MERGE = 1e-9

# ------------------------------------------------------------------ cavities (channel profile)
#: Nelder-Mead stopping rule of the widest passage through a slice of a channel (absolute, Å: the
#: clearance is reported to 1e-4 Å, far below atomic scale).
CHANNEL_XATOL = 1e-4
CHANNEL_FATOL = 1e-6

# ------------------------------------------------------------------ matching
#: Branch-and-bound keeps a cell while its lower bound is below
#: ``best - (tol * best + MATCHING_GAP_ABS)``: the absolute term stops the search at
#: distance 0.
MATCHING_GAP_ABS = 1e-12
#: The polishing simplex's smallest step, relative to ``1 + |t|``.
MATCHING_STEP_REL = 1e-9
#: Nelder-Mead stopping rule of the polish (absolute, in the input's units).
MATCHING_XATOL = 1e-12
MATCHING_FATOL = 1e-14
