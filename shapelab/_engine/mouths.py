"""The cavities' machinery (not required reading): the merge tree of the complement
of the filtration, run backwards in one union-find pass, and the certified search for
a region's mouth.  The public definitions are in :mod:`shapelab.cavities`
(``complement``, ``mouths``); these compute the same sets faster.  Functions take the
filtration's summary ``S`` (its values, the dual graph of the cells ``S.cell_dual``,
the positive facets ``S.pos_facets``) and the filtration ``F`` by duck typing.
"""

from __future__ import annotations

from array import array
from dataclasses import dataclass, fields

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import breadth_first_order, depth_first_order, dijkstra

from .._toolkit.derived import derived
from .._toolkit.unionfind import elder_merges
from .._toolkit.validate import freeze
from .persistence import summary

__all__ = ["MergeTree", "build_merge_tree", "merge_tree_of", "leaf_run", "cells_at_closing", "OutsideGraph"]


# ===================================================================== merge tree
@dataclass(frozen=True)
class MergeTree:
    n_cells: int
    kill_value: np.ndarray  # (n_cells,) value of the facet that seals the void rooted at the cell
    pos: np.ndarray  # (n_cells + 1,) position of every leaf in the final leaf order
    order: np.ndarray  # leaf order: every subtree is a contiguous run
    kill_node: np.ndarray  # (n_cells,) tree node of the component the cell roots when it dies
    left: np.ndarray  # per merge: child node ids, ...
    right: np.ndarray
    value: np.ndarray  # ... the merge value,
    lo: np.ndarray  # ... and its leaf run [lo, hi)
    hi: np.ndarray


def build_merge_tree(S) -> MergeTree:
    """The merge tree of the complement's cells in reverse filtration order (the
    dual :math:`H_0`): when each void is sealed, and its cells at every moment."""
    k = S.k
    n = S.values[k].shape[0]
    N = n + 1
    u, v = S.cell_dual
    # machine integers (array 'q'), not lists of Python ints: a ribosome has a
    # million cells, and a list holds about 36 bytes an entry to the array's 8
    node = array("q", range(N))
    head = array("q", range(N))
    tail = array("q", range(N))
    nxt = array("q", [-1]) * N
    age = array("q", range(n, -1, -1))  # reverse time: outside oldest (0), then last cells
    kill_facet = array("q", [-1]) * n
    kill_node = array("q", [-1]) * n
    m_left, m_right, m_head, m_tail, m_facet = (array("q") for _ in range(5))

    def merge(e, a, b, oldest):  # a keeps (older), b dies
        young = oldest[b]
        kill_facet[young] = e
        kill_node[young] = node[b]
        nxt[tail[a]] = head[b]
        m_left.append(node[a])
        m_right.append(node[b])
        m_head.append(head[a])
        m_tail.append(tail[b])
        m_facet.append(e)
        tail[a] = tail[b]
        node[a] = N + len(m_left) - 1

    parent, _ = elder_merges(N, u, v, S.pos_facets[::-1], age, merge)
    root = n
    while parent[root] != root:
        root = parent[root]
    order = array("q")
    i = head[root]
    while i != -1:
        order.append(i)
        i = nxt[i]
    order = np.asarray(order, dtype=np.int64)
    pos = np.empty(N, dtype=np.int64)
    pos[order] = np.arange(order.shape[0])
    kf = np.asarray(kill_facet, dtype=np.int64)
    kill_value = np.where(kf >= 0, S.values[k - 1][np.maximum(kf, 0)], -np.inf) if k >= 1 else np.full(n, -np.inf)
    mh = np.asarray(m_head, dtype=np.int64)
    mt = np.asarray(m_tail, dtype=np.int64)
    tree = MergeTree(
        n_cells=n,
        kill_value=kill_value,
        pos=pos,
        order=order,
        kill_node=np.asarray(kill_node, dtype=np.int64),
        left=np.asarray(m_left, dtype=np.int64),
        right=np.asarray(m_right, dtype=np.int64),
        value=S.values[k - 1][np.asarray(m_facet, dtype=np.int64)] if m_facet else np.empty(0),
        lo=pos[mh] if mh.size else mh,
        hi=pos[mt] + 1 if mt.size else mt,
    )
    for f in fields(tree):  # kept on F and read by pockets: read-only, as sealed_at
        if isinstance(a := getattr(tree, f.name), np.ndarray):
            freeze(a)
    return tree


def merge_tree_of(F) -> MergeTree:
    """The merge tree of the complement of ``F``, built once and kept on ``F``
    (:func:`shapelab.cavities.complement.merge_tree`)."""
    return derived(F, "cavities.merge_tree", lambda F: build_merge_tree(summary(F)))


def leaf_run(T: MergeTree, node: int):
    """Leaf run [lo, hi) of a tree node (leaves are 0..n_cells, merges above)."""
    N = T.n_cells + 1
    if node < N:
        p = int(T.pos[node])
        return p, p + 1
    m = node - N
    return int(T.lo[m]), int(T.hi[m])


class OutsideGraph:
    """The dual graph of the complement of :math:`K_\\tau` (free cells and
    :math:`\\infty`, glued along free faces), built once per ``(F, tau)`` to find the
    mouths of many regions (module docstring, *Mouths*).

    A breadth-first tree from :math:`\\infty` over the outside component, numbered in
    depth-first preorder, certifies most faces at once: a cell whose tree path to
    :math:`\\infty` avoids :math:`R` is in :math:`O_R`.  The others are settled by a
    search that avoids :math:`R` and stops at the first certified cell (then the cells
    it saw are in :math:`O_R`) or exhausts a crevice.
    """

    def __init__(self, S, F, tau: float):
        k = S.k
        n = S.values[k].shape[0]
        self.n = n
        u, v = S.cell_dual
        self.u, self.v = np.asarray(u, dtype=np.int64), np.asarray(v, dtype=np.int64)
        self.fval = S.values[k - 1]
        self.bnd = np.asarray(F.boundary(k), dtype=np.int64)
        self.tau = tau
        m = self.fval > tau
        a, b = self.u[m], self.v[m]
        g = coo_matrix((np.ones(2 * a.size, dtype=np.int8), (np.r_[a, b], np.r_[b, a])), shape=(n + 1, n + 1))
        self.adj = g.tocsr()
        order, pred = breadth_first_order(self.adj, n, directed=False, return_predecessors=True)
        child = order[1:]
        tree = coo_matrix((np.ones(child.size, dtype=np.int8), (pred[child], child)), shape=(n + 1, n + 1)).tocsr()
        pre = depth_first_order(tree, n, directed=True, return_predecessors=False)
        tin = np.full(n + 1, -1, dtype=np.int64)
        tin[pre] = np.arange(pre.size)
        # subtree sizes, deepest level first (BFS order lists parents before children)
        dist = dijkstra(self.adj, indices=n, unweighted=True)
        depth = np.where(np.isfinite(dist), dist, 0).astype(np.int64)
        size = np.zeros(n + 1, dtype=np.int64)
        size[order] = 1
        if child.size:
            by = child[np.argsort(-depth[child], kind="stable")]
            dd = depth[by]
            cut = np.flatnonzero(np.r_[True, dd[1:] != dd[:-1], True])
            for s, e in zip(cut[:-1].tolist(), cut[1:].tolist()):
                xs = by[s:e]
                np.add.at(size, pred[xs], size[xs])
        self.tin, self.size = tin, size
        # membership of the region asked about, set and cleared by each call: one
        # allocation for all the pockets, not n + 1 bytes per pocket
        self._in_region = np.zeros(n + 1, dtype=bool)

    def mouth(self, cell_ids) -> np.ndarray:
        """Rows of ``F.simplices(d-1)`` of the mouth of the region ``cell_ids``, ascending."""
        cid = np.asarray(cell_ids, dtype=np.int64)
        if cid.size == 0:
            return np.zeros(0, dtype=np.int64)
        self._in_region[cid] = True
        try:
            return self._mouth(cid, self._in_region)
        finally:
            self._in_region[cid] = False

    def _mouth(self, cid, inR) -> np.ndarray:
        faces = self.bnd[cid].ravel()
        uf, cnt = np.unique(faces, return_counts=True)
        uf = uf[(cnt == 1) & (self.fval[uf] > self.tau)]
        if uf.size == 0:
            return uf
        other = np.where(inR[self.u[uf]], self.v[uf], self.u[uf])
        # the union of R's subtrees as disjoint preorder intervals
        st = self.tin[cid]
        if np.any(st < 0):
            raise ValueError("the region is not in the outside component at tau")
        o = np.argsort(st, kind="stable")
        st, en = st[o], st[o] + self.size[cid][o]
        prev = np.r_[-1, np.maximum.accumulate(en)[:-1]]
        keep = st >= prev
        ks, ke = st[keep], en[keep]

        def below_r(x):
            t = self.tin[x]
            i = np.searchsorted(ks, t, side="right") - 1
            return (i >= 0) & (t < ke[np.maximum(i, 0)])

        ok = ~below_r(other)
        if not ok.all():
            status = {}  # cell -> True (in O_R) / False (crevice)
            indptr, ind = self.adj.indptr, self.adj.indices
            for j in np.flatnonzero(~ok).tolist():
                y = int(other[j])
                if y not in status:
                    seen, stack, found = {y}, [y], False
                    while stack and not found:
                        x = stack.pop()
                        for z in ind[indptr[x] : indptr[x + 1]].tolist():
                            if inR[z] or z in seen:
                                continue
                            if status.get(z, False) or not below_r(np.int64(z)):
                                found = True
                                break
                            seen.add(z)
                            stack.append(z)
                    for x in seen:
                        status[x] = found
                ok[j] = status[y]
        return uf[ok]


def cells_at_closing(T: MergeTree, r: int) -> np.ndarray:
    """The cells (ascending) of the void rooted at cell ``r`` at the moment it is sealed,
    ``T.kill_value[r]``: the leaf run of its tree node, merges at exactly that value
    undone (they happen at the same time)."""
    N = T.n_cells + 1
    bb = float(T.kill_value[r])
    node = int(T.kill_node[r])
    while node >= N and T.value[node - N] <= bb:
        lo, hi = leaf_run(T, int(T.left[node - N]))
        node = int(T.left[node - N]) if lo <= T.pos[r] < hi else int(T.right[node - N])
    lo, hi = leaf_run(T, node)
    return np.sort(T.order[lo:hi])
