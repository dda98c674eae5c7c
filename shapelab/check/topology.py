"""Self-checks for the topology lessons (06–10): Euler characteristic and Betti numbers.

Each check runs the student's function on small hand-made complexes first (edge
cases: nothing, one vertex, a hollow and a filled triangle) and then on dual complexes
:math:`K_\\tau` of the course's data sets at several growth times τ (Notes §23.1), and
compares with the library.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from ._runner import CheckResult, run_check

__all__ = ["euler_characteristic", "betti_numbers", "boundary_reduction"]


def _chi(simplices_by_dim) -> int:
    """Σ_k (−1)^k · (number of k-simplices), the Euler characteristic."""
    return int(sum((-1) ** k * len(s) for k, s in enumerate(simplices_by_dim)))


def _complex_lists(K) -> list:
    """A Complex as a list [vertices (n,1), edges (m,2), triangles, ...] relabelled 0..n-1."""
    verts = np.asarray(K.simplices(0)).reshape(-1)
    relabel = np.full(int(verts.max()) + 1 if len(verts) else 0, -1, dtype=np.int64)
    relabel[verts] = np.arange(len(verts))
    out = [np.arange(len(verts), dtype=np.int64).reshape(-1, 1)]
    for k in range(1, int(K.dimension) + 1):
        out.append(relabel[np.asarray(K.simplices(k))])
    return out


def _library_complexes(two_d_only: bool):
    """Dual complexes K_τ of the course data sets (lazily: they need the core)."""
    import shapelab
    from shapelab import datasets as D

    sets = [
        (D.ring(10, radius=2.5, disk_radius=0.9), (-0.5, 0.0, 3.0, 6.0)),
        (D.figure_23_1(), (-0.2, 0.0, 0.8, 1.5, 5.0)),
        (D.figure_23_2()[0], (0.0, 1.0, 3.0)),
    ]
    if not two_d_only:
        sets.append((D.fullerene_c60(), (-2.0, -1.0, 0.0, 9.0, 10.0)))
    for balls, taus in sets:
        F = shapelab.alpha_filtration(balls)
        for t in taus:
            yield F.complex_at(t), F.betti(t)


def _hand_made():
    e = np.zeros((0, 2), np.int64)
    t = np.zeros((0, 3), np.int64)
    v = lambda n: np.arange(n, dtype=np.int64).reshape(-1, 1)  # noqa: E731
    tri_edges = np.array([[0, 1], [0, 2], [1, 2]])
    return [
        [v(0)],
        [v(1)],
        [v(3), tri_edges],  # hollow triangle
        [v(3), tri_edges, np.array([[0, 1, 2]])],  # filled triangle
        [
            v(4),
            np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]),
            np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]),
        ],  # tetrahedron boundary
        [v(5), e, t],
    ]


def euler_characteristic(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(simplices_by_dim) -> int``, the Euler characteristic.

    ``simplices_by_dim[k]`` is an integer array of shape ``(n_k, k + 1)`` listing the
    k-simplices (vertices, edges, triangles, tetrahedra); the answer is
    :math:`\\chi = \\sum_k (-1)^k n_k`.  Cases: hand-made complexes, then dual complexes
    :math:`K_\\tau` of a ring of disks, Figure 23.1, Figure 23.2 and C60 (Notes §23.1),
    whose χ the library computes with :meth:`Complex.euler_characteristic`.

    See Also
    --------
    shapelab.filtration.Complex.euler_characteristic
        The reference.

    Examples
    --------
    >>> euler_characteristic(lambda S: sum((-1) ** k * len(s) for k, s in enumerate(S))).passed
    ✓ Euler characteristic: correct on all 23 cases.
    True
    >>> # forgetting the sign is refused
    >>> euler_characteristic(lambda S: sum(len(s) for s in S), quiet=True).passed
    False
    """
    cases = [(c,) for c in _hand_made()]
    lib = []
    try:
        for K, _ in _library_complexes(two_d_only=False):
            lists = _complex_lists(K)
            # the library and the definition agree, or this check itself is broken
            assert _chi(lists) == int(K.euler_characteristic())
            lib.append((lists,))
    except ImportError:  # the core is missing: check on the hand-made cases only
        pass

    def describe(case):
        return "complex with " + ", ".join(
            f"{len(s)} {name}" for s, name in zip(case[0], ("vertices", "edges", "triangles", "tetrahedra"))
        )

    return run_check(
        "Euler characteristic",
        student_fn,
        cases + lib,
        _chi,
        compare=lambda e, r: _as_int(r) == e,
        describe=describe,
        quiet=quiet,
    )


def _as_int(x):
    try:
        if isinstance(x, (bool, np.bool_)):
            return None
        v = float(x)
        return int(v) if v == int(v) else None
    except (TypeError, ValueError, OverflowError):
        return None


def _closed_surface(edges, triangles) -> bool:
    """True when every edge bounds exactly two triangles (a closed surface, such as the
    tetrahedron's boundary): no such complex lies in the plane, and β₁ = β₀ − χ, which
    holds only where β₂ = 0, would be negative for it (−1 for the sphere)."""
    T = np.sort(np.asarray(triangles, dtype=np.int64).reshape(-1, 3), axis=1)
    if len(T) == 0:
        return False
    sides = np.concatenate([T[:, [0, 1]], T[:, [0, 2]], T[:, [1, 2]]])
    _, per_side = np.unique(sides, axis=0, return_counts=True)
    E = np.unique(np.sort(np.asarray(edges, dtype=np.int64).reshape(-1, 2), axis=1), axis=0)
    return len(per_side) == len(E) and bool(np.all(per_side == 2))


def _betti_planar(n_vertices, edges, triangles):
    """(β0, β1) of a 2-complex embedded in the plane: β0 by connected components,
    β1 = β0 − χ because β2 = 0 in the plane."""
    n = int(n_vertices)
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    if n == 0:
        return (0, 0)
    g = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    b0 = int(connected_components(g, directed=False)[0])
    chi = n - len(edges) + len(np.asarray(triangles).reshape(-1, 3))
    return (b0, b0 - chi)


def betti_numbers(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(n_vertices, edges, triangles) -> (beta0, beta1)`` in 2D.

    The complex is a dual complex in the plane (vertices 0..n−1, ``edges`` (m, 2),
    ``triangles`` (t, 3)).  β₀ counts components (union–find on the edges) and β₁ the
    holes; in the plane β₂ = 0, so :math:`\\beta_1 = \\beta_0 - \\chi` — the
    incremental idea of Delfinado & Edelsbrunner.  Cases: hand-made, then
    :math:`K_\\tau` of a ring, Figure 23.1 and Figure 23.2 (left) at several τ,
    compared with :meth:`Filtration.betti`.

    See Also
    --------
    shapelab.persistence.betti
        The reference.

    Examples
    --------
    >>> import shapelab as sl
    >>> def mine(n, edges, triangles):
    ...     b = list(sl.betti_numbers([[v] for v in range(n)] + [list(e) for e in edges] + [list(t) for t in triangles]))
    ...     return tuple((b + [0, 0])[:2])
    >>> betti_numbers(mine).passed
    ✓ Betti numbers (β0, β1) in 2D: correct on all 18 cases.
    True
    >>> # the Euler characteristic in place of beta0, beta1 = 0, is refused
    >>> betti_numbers(lambda n, edges, triangles: (n - len(edges) + len(triangles), 0), quiet=True).passed
    False
    """
    cases = []
    for c in _hand_made():
        V = len(c[0])
        E = c[1] if len(c) > 1 else np.zeros((0, 2), np.int64)
        T = c[2] if len(c) > 2 else np.zeros((0, 3), np.int64)
        if _closed_surface(E, T):  # the tetrahedron boundary: a sphere, not in the plane
            continue
        cases.append((V, E, T))
    cases.append((6, np.array([[0, 1], [1, 2], [0, 2], [3, 4], [4, 5], [3, 5]]), np.zeros((0, 3), np.int64)))
    try:
        for K, lib_b in _library_complexes(two_d_only=True):
            lists = _complex_lists(K)
            E = lists[1] if len(lists) > 1 else np.zeros((0, 2), np.int64)
            T = lists[2] if len(lists) > 2 else np.zeros((0, 3), np.int64)
            case = (len(lists[0]), E, T)
            assert _betti_planar(*case) == tuple(int(b) for b in lib_b[:2])
            cases.append(case)
    except ImportError:
        pass

    def describe(case):
        return f"n_vertices={case[0]}, {len(case[1])} edges, {len(case[2])} triangles"

    def compare(expected, received):
        try:
            r = tuple(_as_int(x) for x in received)
        except TypeError:
            return False
        return r == tuple(expected)

    return run_check(
        "Betti numbers (β0, β1) in 2D",
        student_fn,
        cases,
        _betti_planar,
        compare=compare,
        describe=describe,
        quiet=quiet,
    )


# ------------------------------------------------------------- boundary reduction
def _pairs_from_low(F, B, low) -> dict:
    """Persistence pairs (as values, per dimension) read off the lowest ones of a reduced
    boundary matrix: ``(value[low[j]], value[j])`` in dimension ``dims[low[j]]`` for
    every non-zero column, ``(value[j], inf)`` for every zero column that is nobody's
    lowest one; zero-length pairs dropped, and those that :func:`shapelab.persistence.is_roundoff`
    calls round-off of tied entry times, as :meth:`Filtration.persistence` does."""
    from shapelab.persistence import is_roundoff

    low = np.asarray(low, dtype=np.int64)
    j = np.flatnonzero(low >= 0)
    essential = np.setdiff1d(np.flatnonzero(low < 0), low[j])
    out = {}
    for k in range(int(B.dims.max()) + 1 if B.dims.size else 0):
        fin = j[B.dims[low[j]] == k]
        ess = essential[B.dims[essential] == k]
        P = np.concatenate(
            [
                np.column_stack((B.values[low[fin]], B.values[fin])),
                np.column_stack((B.values[ess], np.full(ess.size, np.inf))),
            ]
        )
        out[k] = P[(P[:, 1] > P[:, 0]) & ~is_roundoff(F, P[:, 0], P[:, 1])]
    return out


def _hand_made_matrices():
    """Boundary matrices of tiny complexes, in a filtration order: nothing, one vertex,
    the hollow and the filled triangle, the tetrahedron's boundary (a sphere: one
    triangle closes a void) and two triangles sharing an edge entered last."""

    def matrix(simplices):
        index = {s: i for i, s in enumerate(simplices)}
        D = np.zeros((len(simplices), len(simplices)), dtype=np.uint8)
        for j, s in enumerate(simplices):
            if len(s) > 1:
                for a in range(len(s)):
                    D[index[s[:a] + s[a + 1 :]], j] = 1
        return D

    tri = [(0,), (1,), (2,), (0, 1), (0, 2), (1, 2)]
    sphere = [(0,), (1,), (2,), (3,), (0, 1), (0, 2), (1, 2), (0, 3), (1, 3), (2, 3)]
    sphere += [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]
    square = [(0,), (1,), (2,), (3,), (0, 1), (1, 2), (2, 3), (0, 3), (0, 2), (0, 1, 2), (0, 2, 3)]
    return [matrix([]), matrix([(0,)]), matrix(tri), matrix(tri + [(0, 1, 2)]), matrix(sphere), matrix(square)]


def _reduction_filtrations():
    """α-filtrations for the reduction check: small random balls in 2D and 3D (seeded),
    then the course's data sets of lessons 03, 04, 06, 10 and 11 (Figure 23.1, a ring,
    C60 and the two-chamber flask)."""
    import shapelab
    from shapelab import datasets as D

    rng = np.random.default_rng(23)
    out = []
    for dim, n in ((2, 6), (2, 10), (3, 7), (3, 12)):
        centers = rng.uniform(0.0, 4.0, size=(n, dim))
        out.append(shapelab.alpha_filtration(shapelab.Balls(centers, rng.uniform(0.3, 0.9, size=n))))
    for balls in (D.figure_23_1(), D.ring(10, radius=2.5, disk_radius=0.9), D.fullerene_c60(), D.nested_pockets()):
        out.append(shapelab.alpha_filtration(balls))
    return out


def _same_pairs(A: dict, B: dict) -> bool:
    for k in set(A) | set(B):
        a = np.asarray(A.get(k, np.empty((0, 2))), dtype=float).reshape(-1, 2)
        b = np.asarray(B.get(k, np.empty((0, 2))), dtype=float).reshape(-1, 2)
        a, b = a[np.lexsort((a[:, 1], a[:, 0]))], b[np.lexsort((b[:, 1], b[:, 0]))]
        if a.shape != b.shape or not np.allclose(a, b, rtol=1e-9, atol=1e-12):
            return False
    return True


class _Lows:
    """The reference of :func:`boundary_reduction`: the lowest one of each column of the
    reduced matrix (-1 for a zero column) and the columns of the reference ``R`` (sets
    of rows), shown in a failure message with what is wrong in the answer."""

    def __init__(self, low, D, R):
        self.low, self.D = np.asarray(low), D
        R = R.tocsc()
        self.cols = [set(R.indices[R.indptr[j] : R.indptr[j + 1]].tolist()) for j in range(R.shape[1])]
        self.owner = {int(i): j for j, i in enumerate(self.low.tolist()) if i >= 0}
        self.why = ""

    def in_span(self, v, j) -> bool:
        """Whether the chain ``v`` (a set of rows) is a sum of the columns ``< j`` of
        ``D``: the reference's columns ``< j`` span the same space and their lowest
        ones are distinct, so reducing by them decides it."""
        v = set(v)
        while v:
            k = self.owner.get(max(v))
            if k is None or k >= j:
                return False
            v ^= self.cols[k]
        return True

    def __repr__(self) -> str:
        n = self.low.size
        with np.printoptions(threshold=20):
            text = (
                f"R = D V of shape ({n}, {n}) (column j of D plus earlier columns), lowest ones "
                f"(-1: zero column) {self.low}"
            )
        return text + (f"\n  what is wrong: {self.why}" if self.why else "")


def boundary_reduction(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(D) -> R``, the column reduction of a boundary matrix over Z/2
    (lesson 11, the persistence algorithm; Notes §23.1).

    ``D`` is an (n, n) uint8 array of 0/1, columns and rows in filtration order
    (:meth:`shapelab.filtration.Filtration.boundary_matrix`, as a dense array).  The
    answer ``R`` (an array, or a scipy.sparse matrix) must be an (n, n) array of 0/1
    with :math:`R = D V` over :math:`\\mathbb{Z}/2`, :math:`V` upper triangular with
    ones on its diagonal (column ``j`` of ``R`` is column ``j`` of ``D`` plus earlier
    columns of ``D``: tested by reducing the difference with the reference's earlier
    columns), and whose lowest ones are those of the standard algorithm
    (:func:`shapelab.persistence.reduce_boundary`): the pairing does not depend on the
    order of the column additions, but adding a *later* column is refused even where
    it keeps the lowest ones.  Cases: tiny hand-made complexes, then small random
    α-filtrations in 2D and 3D and the course's Figure 23.1, a ring, C60 and the
    two-chamber flask, for which the pairs read off the reference's lowest ones are
    first compared with :meth:`Filtration.persistence` (finite and essential classes).

    See Also
    --------
    shapelab.persistence.reduce_boundary
        The reference.
    shapelab.filtration.Filtration.boundary_matrix
        The matrix reduced.

    Examples
    --------
    >>> from shapelab.persistence import reduce_boundary
    >>> boundary_reduction(lambda D: reduce_boundary(D)[0]).passed
    ✓ boundary matrix reduction over Z/2: correct on all 14 cases.
    True
    >>> # the boundary matrix itself, unreduced, is refused
    >>> boundary_reduction(lambda D: D, quiet=True).passed
    False
    """
    from shapelab.persistence import reduce_boundary

    cases = [(D,) for D in _hand_made_matrices()]
    try:
        for F in _reduction_filtrations():
            B = F.boundary_matrix()
            # the reference's pairs are the library's, or this check itself is broken
            assert _same_pairs(_pairs_from_low(F, B, reduce_boundary(B.matrix)[1]), F.persistence())
            cases.append((B.matrix.toarray(),))
    except ImportError:  # the core is missing: the hand-made cases only
        pass

    def reference(D):
        R, low = reduce_boundary(D)
        return _Lows(low, D, R)

    def compare(expected, received):
        expected.why = ""
        n = expected.low.size
        try:
            R = received.toarray() if hasattr(received, "toarray") else np.asarray(received)  # sparse too
            if R.dtype == object or R.dtype.kind not in "biuf":
                expected.why = f"expected an array of 0/1, got {type(received).__name__} of dtype {R.dtype}"
                return False
            if n == 0 and R.shape in ((0, 0), (0,)):  # (0,): a list of no rows, []
                return True
            if R.shape != (n, n):
                expected.why = f"expected shape ({n}, {n}), got shape {R.shape}"
                return False
            if not np.all(np.isin(R, (0, 1))):
                expected.why = "entries other than 0 and 1: add columns mod 2"
                return False
        except (TypeError, ValueError):
            return False
        R = R.astype(np.uint8)
        low = np.where(R.any(axis=0), n - 1 - np.argmax(R[::-1, :], axis=0), -1)
        # the same lowest ones as the standard algorithm ...
        bad = np.flatnonzero(low != expected.low)
        if bad.size:
            j = int(bad[0])
            expected.why = f"the lowest one of column {j} is in row {int(low[j])}, not {int(expected.low[j])}"
            lows = low[low >= 0]
            if lows.size != np.unique(lows).size:
                expected.why += " (and two columns share a lowest one: not reduced)"
            return False
        # ... and R = D V, V upper triangular with ones on its diagonal (so D R = 0):
        # column j minus column j of D is a sum of earlier columns of D
        X = (R != (np.asarray(expected.D) % 2)).T  # rows of X: the columns of R - D
        for j in np.flatnonzero(X.any(axis=1)).tolist():
            if not expected.in_span(np.flatnonzero(X[j]).tolist(), j):
                expected.why = f"column {j} is not column {j} of D plus earlier columns (a later one added?)"
                return False
        return True

    def describe(case):
        D = case[0]
        return f"a {D.shape[0]} x {D.shape[1]} boundary matrix with {int(D.sum())} ones"

    return run_check(
        "boundary matrix reduction over Z/2",
        student_fn,
        cases,
        reference,
        compare=compare,
        describe=describe,
        quiet=quiet,
    )
