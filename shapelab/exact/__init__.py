"""Exact geometry: the decisions that make the triangulation the same on every machine
(Notes §23.1; CONTRIBUTING, "Exact geometry").

==============================  ==================================================
``shapelab.exact.predicates``   orientation and power tests: a floating-point filter,
                                then Python integers on the input's own binary values;
                                ties broken by Simulation of Simplicity
``shapelab.exact.certify``      checks Qhull's candidate triangulation with them
``shapelab.exact.incremental``  the exact incremental algorithm where the check fails
==============================  ==================================================

:func:`shapelab.regular_triangulation` (:mod:`shapelab.power`) is the public entry point;
these modules are its machinery, for readers and tests.
"""

__all__: list = []
