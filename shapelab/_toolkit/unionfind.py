"""Union–find with the elder rule, once (persistence pairs and merge trees).

Notes §23.1: when two components merge as τ grows, the younger dies and the elder
lives on.  :func:`elder_merges` runs the edges of a spanning forest in order and
reports every merge to a callback; :mod:`shapelab.topology` uses it for the
H0 pairs and the dual merges, :mod:`shapelab.cavities` for the merge tree of the
free space, :mod:`shapelab.simplification` for the persistence of a function along
a curve.
"""

from __future__ import annotations

from array import array

import numpy as np

__all__ = ["elder_merges"]


def elder_merges(n_nodes, u, v, edge_ids, node_age, on_merge):
    """Union–find over the edges ``edge_ids`` (already in processing order).

    Parameters
    ----------
    n_nodes : int
    u, v : int arrays
        Endpoints of every edge.
    edge_ids : int array
        The edges to process, in order.
    node_age : sequence
        Smaller = older; ages are distinct.
    on_merge : callable
        ``on_merge(edge, elder_root, younger_root, oldest)`` for every edge that joins
        two components, called *before* the younger root is attached under the elder
        one; ``oldest`` holds each root's oldest node.

    Returns
    -------
    parent, oldest : arrays of int (``array.array``)
        The union–find forest (a node is a root iff ``parent[i] == i``) and the oldest
        node of each root.
    """
    # machine integers (array 'q'), not lists of Python ints: 8 bytes an entry
    # instead of about 36, for the million cells and facets of a ribosome
    parent = array("q", range(n_nodes))
    oldest = array("q", range(n_nodes))
    uu = array("q", np.asarray(u, dtype=np.int64).tobytes())
    vv = array("q", np.asarray(v, dtype=np.int64).tobytes())
    age = node_age
    for e in array("q", np.asarray(edge_ids, dtype=np.int64).tobytes()):
        a = uu[e]
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        b = vv[e]
        while parent[b] != b:
            parent[b] = parent[parent[b]]
            b = parent[b]
        if a == b:
            continue
        if age[oldest[a]] > age[oldest[b]]:
            a, b = b, a
        on_merge(e, a, b, oldest)
        parent[b] = a
    return parent, oldest
