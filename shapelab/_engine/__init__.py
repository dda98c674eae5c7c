"""The engine: the machinery behind the seam ``precision="exact"`` (issue 33).

The public core (:mod:`shapelab.triangulation`, :mod:`shapelab.filtration`) states each
algorithm top to bottom in the notes' words and runs it in floating point with
``precision="fast"``.  With ``precision="exact"`` (the default) the same questions come
here, where the answers are made the same on every machine.  A student may skip this
package.

=================================  ========================================