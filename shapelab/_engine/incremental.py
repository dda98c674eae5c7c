"""The regular triangulation by exact incremental insertion (Notes §23.1).

The fallback of :func:`shapelab.regular_triangulation` where Qhull's floating-point
lower hull fails its certificate (:mod:`shapelab._engine.certify`): co-spherical centres
(cages, grids), lattices with noise at round-off level, nearly flat configurations.
It is the classic algorithm of Bowyer and Watson, for weighted points as in
Edelsbrunner and Shah (1996), with every decision taken by the exact predicates of
:mod:`shapelab._engine.predicates` and ties broken by Simulation of Simplicity, so its output
is the unique regular triangulation of the perturbed input: the same for every
insertion order and on every machine.

Insertion of a ball ``p``:

1. *locate* ``p`` by a visibility walk (exact orientations);
2. if ``p``'s lifted centre lies above the lifted simplex that contains it, the
   ball is hidden and nothing changes;
3. otherwise collect the *conflict zone*: the simplices whose lifted hyperplane
   passes above lifted ``p`` (power test), grown from the located one; it is
   star-shaped from ``p`` (Edelsbrunner and Shah);
4. replace it by the cone from ``p`` over its boundary.  Vertices inside the zone
   are now hidden.

The outside of the convex hull is handled with a vertex at infinity (as CGAL does):
every hull facet ``f`` carries an infinite simplex ``(f, ∞)``, in conflict with ``p``
when ``p`` lies strictly beyond ``f``, and, when ``p`` lies in the plane of ``f``,
exactly when the finite simplex behind ``f`` is (its orthosphere meets that plane
in the orthocircle of ``f``).

Pure Python over Python lists: about ``10^4`` balls a second in 3D.  It runs only
where the certificate of Qhull's answer fails.
"""

from __future__ import annotations

import numpy as np

from .predicates import WeightedPoints

__all__ = ["incremental_triangulation"]

_INF = -1


class _Triangulation:
    def __init__(self, P: WeightedPoints):
        self.P = P
        self.k = P.k
        self.V: list = []  # vertex lists, _INF for the vertex at infinity
        self.N: list = []  # neighbour lists (opposite each vertex)
        self.alive: list = []
        self.last = 0

    def new_cell(self, verts) -> int:
        self.V.append(list(verts))
        self.N.append([-1] * (self.k + 1))
        self.alive.append(True)
        return len(self.V) - 1

    # ------------------------------------------------------------------ predicates
    def conflict(self, c: int, p: int) -> bool:
        V = self.V[c]
        if _INF in V:
            j = V.index(_INF)
            row = list(V)
            row[j] = p
            o = self.P.orient1(row)
            if o:
                return o > 0
            return self.conflict(self.N[c][j], p)
        return self.P.power1(V + [p]) < 0

    # ------------------------------------------------------------------ location
    def locate(self, p: int) -> int:
        c = self.last
        if not self.alive[c]:
            c = next(i for i in range(len(self.V) - 1, -1, -1) if self.alive[i])
        if _INF in self.V[c]:
            c = self.N[c][self.V[c].index(_INF)]
        w = self.k + 1
        step = 0
        limit = 16 * len(self.V) + 64
        while True:
            V = self.V[c]
            if _INF in V:
                return c
            moved = False
            for jj in range(w):
                i = (jj + step) % w
                row = list(V)
                row[i] = p
                if self.P.orient1(row) < 0:
                    c = self.N[c][i]
                    moved = True
                    break
            if not moved:
                return c
            step += 1
            if step > limit:  # pragma: no cover - impossible in a regular triangulation
                raise RuntimeError("point location did not terminate")

    # ------------------------------------------------------------------ insertion
    def insert(self, p: int) -> bool:
        """Insert point ``p``; False if it is hidden."""
        c0 = self.locate(p)
        if not self.conflict(c0, p):
            return False
        zone = {c0}
        stack = [c0]
        boundary = []
        seen = {}
        while stack:
            c = stack.pop()
            for i, nb in enumerate(self.N[c]):
                if nb in zone:
                    continue
                hit = seen.get(nb)
                if hit is None:
                    hit = seen[nb] = self.conflict(nb, p)
                if hit:
                    zone.add(nb)
                    stack.append(nb)
                else:
                    boundary.append((c, i, nb))
        ridges = {}
        newc = None
        for c, i, nb in boundary:
            verts = list(self.V[c])
            facet = verts[:i] + verts[i + 1 :]
            verts[i] = p
            nc = self.new_cell(verts)
            newc = nc
            self.N[nc][i] = nb
            fs = set(facet)
            Vn = self.V[nb]
            for m in range(self.k + 1):
                if Vn[m] not in fs:
                    self.N[nb][m] = nc
                    break
            for j in range(self.k + 1):
                if j == i:
                    continue
                key = frozenset(verts[:j] + verts[j + 1 :])
                other = ridges.pop(key, None)
                if other is None:
                    ridges[key] = (nc, j)
                else:
                    oc, oj = other
                    self.N[nc][j] = oc
                    self.N[oc][oj] = nc
        if ridges:  # pragma: no cover - the zone's boundary is always closed
            raise RuntimeError("the conflict zone of an insertion is not a ball")
        for c in zone:
            self.alive[c] = False
        self.last = newc if _INF not in self.V[newc] else self.N[newc][self.V[newc].index(_INF)]
        return True


def _initial(P: WeightedPoints, order):
    """The first k+1 affinely independent points in ``order`` (exact)."""
    k = P.k
    chosen = [int(order[0])]
    u0 = P.exact_u(chosen[0])
    for q in order[1:]:
        q = int(q)
        if len(chosen) == 1:
            if P.exact_u(q) != u0:
                chosen.append(q)
        else:
            # affinely independent of the chosen ones: some k-minor of the
            # difference vectors is non-zero
            from itertools import combinations

            from .predicates import det

            vecs = [[a - b for a, b in zip(P.exact_u(i), u0)] for i in chosen[1:] + [q]]
            r = len(vecs)
            if any(det([[v[a] for a in cols] for v in vecs]) != 0 for cols in combinations(range(k), r)):
                chosen.append(q)
        if len(chosen) == k + 1:
            return chosen
    raise ValueError("the centres do not span the dimension they were said to")  # pragma: no cover


def incremental_triangulation(P: WeightedPoints, order=None):
    """The regular triangulation of the weighted points ``P`` (exact, SoS ties).

    Parameters
    ----------
    P : WeightedPoints
        Points of affine dimension ``P.k`` (exactly) in their coordinates ``P.u``.
    order : array of int, optional
        Insertion order (default: the rows' order).  The result does not depend on
        it; a spatially coherent order (Morton) makes the walks short.

    Returns
    -------
    ndarray of int64, shape (m, k+1)
        The top simplices, vertices ascending in each row.

    See Also
    --------
    regular_triangulation
        The public entry point; certified Qhull first.
    shapelab._engine.certify.certify
        The check that decides when this is needed.

    References
    ----------
    .. [1] H. Edelsbrunner and N. R. Shah, "Incremental topological flipping works for
           regular triangulations", *Algorithmica* 15:223-241, 1996.
           doi:10.1007/BF01975867
    .. [2] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity: a technique to
           cope with degenerate cases in geometric algorithms", *ACM Trans. Graph.*
           9(1):66-104, 1990. doi:10.1145/77635.77639
    .. [3] J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast robust
           geometric predicates", *Discrete Comput. Geom.* 18:305-363, 1997.
           doi:10.1007/PL00009321
    """
    n, k = P.n, P.k
    order = np.arange(n) if order is None else np.asarray(order)
    init = _initial(P, order)
    T = _Triangulation(P)
    if P.orient1(init) < 0:
        init[0], init[1] = init[1], init[0]
    c0 = T.new_cell(init)
    infs = []
    for i in range(k + 1):
        verts = list(init)
        verts[i] = _INF
        j = (i + 1) % (k + 1)
        verts[i], verts[j] = verts[j], verts[i]
        ci = T.new_cell(verts)
        infs.append((ci, verts.index(_INF)))
        T.N[c0][i] = ci
        T.N[ci][verts.index(_INF)] = c0
    # infinite cells are glued to each other along ridges that contain infinity
    ridges = {}
    for ci, _ in infs:
        V = T.V[ci]
        for j in range(k + 1):
            if V[j] == _INF:
                continue
            key = frozenset(V[:j] + V[j + 1 :])
            if key in ridges:
                oc, oj = ridges.pop(key)
                T.N[ci][j] = oc
                T.N[oc][oj] = ci
            else:
                ridges[key] = (ci, j)
    T.last = c0
    done = set(init)
    for q in order:
        q = int(q)
        if q in done:
            continue
        T.insert(q)
    rows = [sorted(V) for V, a in zip(T.V, T.alive) if a and _INF not in V]
    return np.array(rows, dtype=np.int64).reshape(-1, k + 1)
