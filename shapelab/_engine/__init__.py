"""The engine: the machinery behind the seam ``precision="exact"`` (issue 33).

The public core (:mod:`shapelab.triangulation`, :mod:`shapelab.filtration`) states each
algorithm top to bottom in the notes' words and runs it in floating point with
``precision="fast"``.  With ``precision="exact"`` (the default) the same questions come
here, where the answers are made the same on every machine.  A student may skip this
package.

=================================  ===============================================
``shapelab._engine.predicates``    orientation and power tests: a floating-point
                                   filter, then Python integers on the input's own
                                   binary values; ties broken by Simulation of
                                   Simplicity (public face: :mod:`shapelab.predicates`)
``shapelab._engine.certify``       checks Qhull's candidate triangulation with them,
                                   and repairs it locally
``shapelab._engine.incremental``   the exact incremental algorithm where the check fails
``shapelab._engine.triangulation`` frames, duplicates, Qhull's candidate (in blocks by
                                   threads), tie-break candidates, canonical order
``shapelab._engine.faces``         faces and boundary matrices without sorting
``shapelab._engine.orthospheres``  orthospheres with an error bound, long double and
                                   exact rational fallbacks
``shapelab._engine.alpha``         the certified entry times and the filtration order
``shapelab._engine.persistence``   persistence pairs by union-find and dual graphs (the
                                   fast path of :func:`shapelab.persistence.persistence`)
``shapelab._engine.hausdorff``     the Hausdorff distance's kernels (KD-tree, early break)
``shapelab._engine.icp``           Anderson acceleration of ICP (``accelerate=True``)
``shapelab._engine.mouths``        the merge tree's union-find and the certified mouth search
``shapelab._engine.flow``          the discrete flow's exact signs, neighbours, the
                                   regions' lining and growth-model pair
``shapelab._engine.freespace``     the free space's exact area/volume integration
``shapelab._engine.measure``       the union measure's complex before τ, blocks, vector
                                   helpers, flat simplices' limits
=================================  ===============================================

Modules here import each other and the private toolkit; the names they share are
public inside the package (no underscore name crosses modules).
"""

__all__: list = []
