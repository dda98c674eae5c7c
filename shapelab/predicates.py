"""Exact geometric predicates: orientation and power tests on balls (Notes §23.1).

Two questions decide every regular triangulation:

* **orientation**: on which side of the hyperplane through ``d`` centres does another
  centre lie?  The sign of a determinant of coordinate differences;
* **power test**: is a ball closer in power to the orthosphere of ``d + 1`` balls than
  they are, i.e. does its lifted point :math:`(z, |z|^2 - r^2)` lie below the plane
  through theirs?  The sign of a determinant of lifted coordinates.

In floating point a determinant near zero can get the wrong sign.
:class:`WeightedPoints` answers both questions exactly for the input as given: a
floating-point filter with an error bound decides almost every test, and the rest are
computed in integers on the float64 numbers' own binary values; exact ties (four
co-circular centres) are broken by Simulation of Simplicity, so the answer is never
zero for the power test.  ``WeightedPoints(centers, radii).orient(rows)`` gives the
signs (+1, -1 or 0) of the orientations of the simplices ``rows``.

The implementation is in the engine (:mod:`shapelab._engine.predicates`), with the
certificate and repair that use it to make :func:`shapelab.regular_triangulation`
the same on every machine.
"""

from __future__ import annotations

from ._engine.predicates import WeightedPoints

__all__ = ["WeightedPoints"]
