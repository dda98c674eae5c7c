"""shapelab's internal toolkit: the helpers that several modules share, once.

Private as a package (nothing here is part of the public API), public inside: the
names carry no underscore because they are meant to be imported across modules.

==============  ================================================================
``validate``    read-only arrays, τ, scalars, points, radii, bounding boxes
``geometry``    dot and cross products of component-first vectors, Morton order
``unionfind``   union–find with the elder rule (persistence, merge trees)
``lazy``        lazy re-export of a package's public names
``tolerances``  every numerical tolerance the library decides with, documented
``threads``     how many threads a computation may start (``SHAPELAB_THREADS``)
==============  ================================================================
"""
