"""Simplicial homology over :math:`\\mathbb{Z}/2`, small and by hand (lesson 02).

A **simplicial complex** is a finite set of simplices, each a set of vertices, closed
under taking faces: with a simplex, every one of its facets is in the complex. Here a
simplex is a tuple of vertex labels (integers), ``(0, 1, 2)`` a triangle.

A **k-chain** over :math:`\\mathbb{Z}/2` is a set of k-simplices: coefficients are 0 or
1, and the sum of two chains is their symmetric difference (:math:`1 + 1 = 0`). The
**boundary** of a k-simplex is the chain of its k + 1 facets; the boundary matrix
:math:`\\partial_k` has a column per k-simplex and a row per (k−1)-simplex. From the
ranks of these matrices come the Betti numbers (Notes §23.1 uses them for the
components, tunnels and voids of a union of balls):

.. math:: \\beta_k = \\dim Z_k - \\dim B_k = (n_k - \\operatorname{rank}\\partial_k) - \\operatorname{rank}\\partial_{k+1}.

Everything here is exact (integers mod 2) and written to be read; it is meant for
small complexes (a few thousand simplices take a second or two). The filtrations of :mod:`shapelab.filtration`
compute the same numbers much faster (:func:`shapelab.persistence.betti`).
"""

from __future__ import annotations

from collections import Counter
from itertools import combinations
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence

    from numpy.typing import ArrayLike

__all__ = [
    "closure",
    "k_simplices",
    "boundary_matrix",
    "rank_mod2",
    "chain_boundary",
    "betti_numbers",
    "is_cycle",
    "is_boundary",
    "euler_characteristic",
    "positive_simplices",
]


def _simplex(s, name: str) -> tuple:
    """One simplex as a sorted tuple of distinct ints."""
    if isinstance(s, (str, bytes)) or not hasattr(s, "__iter__"):
        hint = " (a list of simplices such as [(0, 1)], not one simplex)" if isinstance(s, (int, np.integer)) else ""
        raise TypeError(f"{name}: each simplex must be a tuple of vertex labels, got {s!r}{hint}")
    out = []
    for v in s:
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, np.integer)):
            raise TypeError(f"{name}: vertex labels must be integers, got {v!r} in {tuple(s)!r}")
        out.append(int(v))
    if not out:
        raise ValueError(f"{name}: a simplex needs at least one vertex")
    if len(set(out)) != len(out):
        raise ValueError(f"{name}: the simplex {tuple(out)} repeats a vertex")
    return tuple(sorted(out))


def _complex(simplices, name: str = "simplices") -> set:
    """The complex as a set of sorted tuples, its closure checked.

    ``simplices`` is an iterable of vertex tuples, or a :class:`shapelab.Complex`
    (anything with ``dimension`` and ``simplices(k)``)."""
    if hasattr(simplices, "simplices") and hasattr(simplices, "dimension"):
        simplices = [tuple(s) for k in range(int(simplices.dimension) + 1) for s in simplices.simplices(k)]
    if isinstance(simplices, (str, bytes)) or not hasattr(simplices, "__iter__"):
        raise TypeError(f"{name}: expected a list of simplices (vertex tuples), got {type(simplices).__name__}")
    K = {_simplex(s, name) for s in simplices}
    for s in K:
        for facet in combinations(s, len(s) - 1):
            if facet and facet not in K:
                raise ValueError(
                    f"{name}: not a simplicial complex: {s} is in it but its face {facet} is not (closure)"
                )
    return K


def _chain(chain, name: str = "chain") -> set:
    """A chain over Z/2 as a set of simplices: a simplex listed twice cancels (1 + 1 = 0)."""
    if isinstance(chain, (str, bytes)) or not hasattr(chain, "__iter__"):
        raise TypeError(f"{name}: expected a list of simplices (vertex tuples), got {type(chain).__name__}")
    counts = Counter(_simplex(s, name) for s in chain)
    c = {s for s, n in counts.items() if n % 2}
    if len({len(s) for s in c}) > 1:
        raise ValueError(
            f"{name}: a chain holds simplices of one dimension, got dimensions {sorted({len(s) - 1 for s in c})}"
        )
    return c


def closure(simplices: Iterable[Sequence[int]]) -> list:
    """The smallest complex that holds the given simplices: each with all its faces.

    Parameters
    ----------
    simplices : iterable of tuple of int
        Simplices (usually the maximal ones: triangles, or tetrahedra).

    Returns
    -------
    list of tuple
        Every face of every simplex, once, as sorted tuples, by dimension then
        lexicographically.

    See Also
    --------
    k_simplices : the faces of one dimension.
    betti_numbers : what to compute next.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes).

    Examples
    --------
    A filled triangle: three vertices, three edges and the triangle itself.

    >>> closure([(0, 1, 2)])
    [(0,), (1,), (2,), (0, 1), (0, 2), (1, 2), (0, 1, 2)]
    """
    if isinstance(simplices, (str, bytes)) or not hasattr(simplices, "__iter__"):
        raise TypeError(f"simplices: expected a list of simplices (vertex tuples), got {type(simplices).__name__}")
    faces = set()
    for s in simplices:
        s = _simplex(s, "simplices")
        faces.update(f for k in range(1, len(s) + 1) for f in combinations(s, k))
    return sorted(faces, key=lambda f: (len(f), f))


def k_simplices(simplices: Iterable[Sequence[int]], k: int) -> list:
    """The k-simplices of a complex, as sorted vertex tuples in lexicographic order.

    This is the order of the rows and columns of :func:`boundary_matrix`.

    Parameters
    ----------
    simplices : iterable of tuple of int, or Complex
        The complex; every face of a simplex must be in it.
    k : int
        The dimension (0 vertices, 1 edges, 2 triangles, ...).

    Returns
    -------
    list of tuple

    See Also
    --------
    boundary_matrix : its rows are ``k_simplices(simplices, k - 1)``, its columns ``k_simplices(simplices, k)``.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    >>> k_simplices([(0,), (1,), (2,), (0, 1), (1, 2), (0, 2)], 1)
    [(0, 1), (0, 2), (1, 2)]
    """
    K = _complex(simplices)
    k = _dimension(k)
    return sorted(s for s in K if len(s) == k + 1)


def _dimension(k) -> int:
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, (int, np.integer)):
        raise TypeError(f"k: expected an integer dimension, got {k!r}")
    if k < 0:
        raise ValueError(f"k: a dimension is at least 0, got {k}")
    return int(k)


def boundary_matrix(simplices: Iterable[Sequence[int]], k: int) -> np.ndarray:
    """The boundary matrix :math:`\\partial_k` of a complex over :math:`\\mathbb{Z}/2`.

    Entry ``[i, j]`` is 1 when the i-th (k−1)-simplex is a facet of the j-th k-simplex,
    both in the order of :func:`k_simplices`: column j is the boundary of the j-th
    k-simplex. :math:`\\partial_0` has no rows (a vertex has an empty boundary).

    Parameters
    ----------
    simplices : iterable of tuple of int, or Complex
        The complex; every face of a simplex must be in it (else ValueError).
    k : int
        The dimension of the columns' simplices.

    Returns
    -------
    numpy.ndarray
        ``(n_{k-1}, n_k)`` of 0/1, dtype uint8.

    See Also
    --------
    rank_mod2 : its rank over Z/2.
    betti_numbers : what the ranks give.
    shapelab.filtration.Filtration.boundary_matrix : all dimensions at once, in filtration order (lesson 11).

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    The boundary of a triangle's three edges (rows: vertices 0, 1, 2):

    >>> triangle = [(0,), (1,), (2,), (0, 1), (0, 2), (1, 2)]
    >>> boundary_matrix(triangle, 1)
    array([[1, 1, 0],
           [1, 0, 1],
           [0, 1, 1]], dtype=uint8)
    """
    K = _complex(simplices)
    k = _dimension(k)
    rows = sorted(s for s in K if len(s) == k) if k > 0 else []
    cols = sorted(s for s in K if len(s) == k + 1)
    where = {s: i for i, s in enumerate(rows)}
    M = np.zeros((len(rows), len(cols)), dtype=np.uint8)
    if k > 0:
        for j, s in enumerate(cols):
            for facet in combinations(s, k):
                M[where[facet], j] = 1
    return M


def rank_mod2(M: ArrayLike) -> int:
    """The rank of a 0/1 matrix over :math:`\\mathbb{Z}/2`, by Gaussian elimination.

    Entries are taken mod 2. Column by column, a row with a 1 in that column becomes the
    pivot row and is added (XOR) to every other row with a 1 there; the rank is the
    number of pivots. Exact: integer arithmetic only.

    Parameters
    ----------
    M : array_like of int or bool, 2-D
        The matrix (any shape, also with no rows or no columns).

    Returns
    -------
    int

    See Also
    --------
    boundary_matrix : the matrices whose ranks give the Betti numbers.
    betti_numbers : uses it.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    Over Z/2 the three rows below add up to zero, so the rank is 2 (over the rationals it is 3):

    >>> rank_mod2([[1, 1, 0], [1, 0, 1], [0, 1, 1]])
    2
    """
    if M is None or isinstance(M, (str, bytes)):
        raise TypeError(f"M: expected a 2-D matrix of 0s and 1s, got {type(M).__name__}")
    try:
        A = np.asarray(M)
    except ValueError as exc:  # ragged nested lists
        raise ValueError(f"M: expected a 2-D matrix with rows of equal length ({exc})") from None
    if A.ndim != 2:
        raise ValueError(f"M: expected a 2-D matrix, got shape {A.shape}")
    if A.size and A.dtype == object and all(isinstance(x, int) and not isinstance(x, bool) for x in A.flat):
        A = np.vectorize(lambda x: x % 2, otypes=[np.uint8])(A)  # Python ints of any size, reduced exactly
    if A.size and not (np.issubdtype(A.dtype, np.integer) or A.dtype == np.bool_):
        raise TypeError(f"M: expected integer or boolean entries (0 and 1), got dtype {A.dtype}")
    A = (A % 2).astype(np.uint8)  # parity is exact in every integer dtype
    rank = 0
    for col in range(A.shape[1]):
        if rank == A.shape[0]:
            break
        candidates = np.flatnonzero(A[rank:, col])
        if candidates.size == 0:
            continue  # no pivot in this column
        p = rank + int(candidates[0])
        A[[rank, p]] = A[[p, rank]]  # the pivot row moves up
        others = np.flatnonzero(A[:, col])
        others = others[others != rank]
        A[others] ^= A[rank]  # clear the column: add the pivot row, mod 2
        rank += 1
    return rank


def chain_boundary(chain: Iterable[Sequence[int]]) -> set:
    """The boundary of a chain over :math:`\\mathbb{Z}/2`: the facets met an odd number of times.

    Parameters
    ----------
    chain : iterable of tuple of int
        A k-chain, its k-simplices (a simplex listed twice cancels).

    Returns
    -------
    set of tuple
        The (k−1)-chain :math:`\\partial c` (empty for a chain of vertices).

    See Also
    --------
    is_cycle : whether the boundary is empty.
    boundary_matrix : the same map as a matrix.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    The boundary of a filled triangle is its three edges; theirs is empty (∂∂ = 0):

    >>> sorted(chain_boundary([(0, 1, 2)]))
    [(0, 1), (0, 2), (1, 2)]
    >>> chain_boundary(chain_boundary([(0, 1, 2)]))
    set()
    """
    c = _chain(chain)
    count = Counter(f for s in c for f in combinations(s, len(s) - 1) if f)
    return {f for f, n in count.items() if n % 2}


def is_cycle(chain: Iterable[Sequence[int]], simplices: Iterable[Sequence[int]] | None = None) -> bool:
    """Whether a chain is a cycle: its boundary is zero over :math:`\\mathbb{Z}/2`.

    Parameters
    ----------
    chain : iterable of tuple of int
        A k-chain (its k-simplices).
    simplices : iterable of tuple of int, or Complex, optional
        A complex the chain must lie in (ValueError otherwise).

    Returns
    -------
    bool

    See Also
    --------
    is_boundary : whether a cycle bounds.
    chain_boundary : the boundary itself.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    >>> is_cycle([(0, 1), (1, 2), (0, 2)])
    True
    >>> is_cycle([(0, 1), (1, 2)])
    False
    """
    c = _chain(chain)
    if simplices is not None:
        _inside(c, _complex(simplices))
    return not chain_boundary(c)


def _inside(c: set, K: set) -> None:
    outside = sorted(c - K)
    if outside:
        raise ValueError(f"chain: the simplex {outside[0]} is not in simplices")


def is_boundary(chain: Iterable[Sequence[int]], simplices: Iterable[Sequence[int]]) -> bool:
    """Whether a k-chain is a boundary in a complex: :math:`c = \\partial c'` for a (k+1)-chain :math:`c'`.

    Over :math:`\\mathbb{Z}/2` this is a linear system :math:`\\partial_{k+1} x = c`; it has a
    solution exactly when appending :math:`c` as a column does not raise the rank of
    :math:`\\partial_{k+1}`. A boundary is always a cycle; a cycle need not be a
    boundary (it goes round a hole).

    Parameters
    ----------
    chain : iterable of tuple of int
        A k-chain of the complex (the empty chain is the boundary of the empty chain).
    simplices : iterable of tuple of int, or Complex
        The complex.

    Returns
    -------
    bool

    See Also
    --------
    is_cycle : the weaker property.
    rank_mod2 : decides the linear system.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    The three edges of a triangle bound when the triangle is filled, not otherwise:

    >>> hollow = [(0,), (1,), (2,), (0, 1), (0, 2), (1, 2)]
    >>> is_boundary([(0, 1), (1, 2), (0, 2)], hollow)
    False
    >>> is_boundary([(0, 1), (1, 2), (0, 2)], hollow + [(0, 1, 2)])
    True
    """
    c = _chain(chain)
    K = _complex(simplices)
    _inside(c, K)
    if not c:
        return True
    k = len(next(iter(c))) - 1
    D = boundary_matrix(K, k + 1)
    rows = {s: i for i, s in enumerate(sorted(s for s in K if len(s) == k + 1))}
    v = np.zeros((D.shape[0], 1), dtype=np.uint8)
    for s in c:
        v[rows[s], 0] = 1
    return rank_mod2(np.hstack([D, v])) == rank_mod2(D)


def betti_numbers(simplices: Iterable[Sequence[int]]) -> tuple:
    """The Betti numbers :math:`(\\beta_0, \\dots, \\beta_d)` of a complex over :math:`\\mathbb{Z}/2`.

    :math:`\\beta_k = (n_k - \\operatorname{rank}\\partial_k) - \\operatorname{rank}\\partial_{k+1}`:
    the dimension of the k-cycles minus that of the k-boundaries. ``d`` is the largest
    dimension of a simplex; the empty complex gives ``()``.

    Parameters
    ----------
    simplices : iterable of tuple of int, or Complex
        The complex; every face of a simplex must be in it.

    Returns
    -------
    tuple of int

    See Also
    --------
    boundary_matrix, rank_mod2 : the pieces.
    euler_characteristic : their alternating sum (Euler–Poincaré).
    shapelab.persistence.betti : the same for the complexes of a filtration, fast.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    The boundary of a tetrahedron is a sphere: one component, no loop, one void.

    >>> from itertools import combinations
    >>> sphere = [s for k in (1, 2, 3) for s in combinations(range(4), k)]
    >>> betti_numbers(sphere)
    (1, 0, 1)
    """
    K = _complex(simplices)
    d = max((len(s) - 1 for s in K), default=-1)
    n = [sum(1 for s in K if len(s) == k + 1) for k in range(d + 2)]
    ranks = [rank_mod2(boundary_matrix(K, k)) for k in range(d + 2)]
    return tuple(int(n[k] - ranks[k] - ranks[k + 1]) for k in range(d + 1))


def euler_characteristic(simplices: Iterable[Sequence[int]]) -> int:
    """The Euler characteristic :math:`\\chi = \\sum_k (-1)^k n_k` of a complex.

    By the Euler–Poincaré formula it is also :math:`\\sum_k (-1)^k \\beta_k`, over any field.

    Parameters
    ----------
    simplices : iterable of tuple of int, or Complex
        The complex.

    Returns
    -------
    int

    See Also
    --------
    betti_numbers : the other side of Euler–Poincaré.
    shapelab.filtration.Complex.euler_characteristic : the same for a dual complex.

    References
    ----------
    .. [1] H. Edelsbrunner and J. Harer, *Computational Topology: An Introduction*,
       American Mathematical Society, 2010, §III.1 (simplicial complexes) and §IV.1–IV.2 (homology groups, matrix reduction).

    Examples
    --------
    >>> euler_characteristic([(0,), (1,), (2,), (0, 1), (0, 2), (1, 2)])
    0
    """
    K = _complex(simplices)
    return int(sum((-1) ** (len(s) - 1) for s in K))


def positive_simplices(order: Sequence[Sequence[int]]) -> list:
    """For simplices added one at a time, whether each creates a class or kills one.

    Adding a k-simplex :math:`\\sigma` to a complex either raises :math:`\\beta_k` by one
    (its boundary already bounded, so :math:`\\sigma` closes a new k-cycle: a **birth**;
    :math:`\\sigma` is *positive*) or lowers :math:`\\beta_{k-1}` by one (its boundary
    was a cycle that did not bound, and now does: a **death**; :math:`\\sigma` is
    *negative*). A vertex is always positive. Which class dies at a death is
    decided by the elder rule, through the reduction of the boundary matrix (lesson 11).

    Each step asks :func:`is_boundary`'s question of :math:`\\partial\\sigma` and the
    simplices before it; the answer is kept up to date exactly, one elimination step per
    simplex (the boundaries entered so far stay reduced mod 2), rather than by a fresh
    rank of every prefix.

    Parameters
    ----------
    order : sequence of tuple of int
        The simplices in the order they enter; every prefix must be a complex
        (a simplex after all its faces).

    Returns
    -------
    list of bool
        True where the simplex is positive (a birth), False where it is negative.

    See Also
    --------
    is_boundary : the question asked at each step (answered here incrementally).
    shapelab.persistence.reduce_boundary : pairs each death with its birth.
    shapelab.filtration.Filtration.persistence : the pairs of an α-filtration.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher and A. Zomorodian, "Topological persistence and
       simplification", Discrete Comput. Geom. 28 (2002) 511-533 (positive and negative
       simplices).

    Examples
    --------
    Three vertices, three edges: the third edge closes a loop, the triangle fills it.

    >>> order = [(0,), (1,), (2,), (0, 1), (1, 2), (0, 2), (0, 1, 2)]
    >>> positive_simplices(order)
    [True, True, True, False, False, True, False]
    """
    if isinstance(order, (str, bytes)) or not hasattr(order, "__iter__"):
        raise TypeError(f"order: expected a sequence of simplices (vertex tuples), got {type(order).__name__}")
    order = [_simplex(s, "order") for s in order]
    if len(set(order)) != len(order):
        raise ValueError("order: a simplex enters twice")
    # The question at each step is is_boundary(∂σ, simplices so far). Asked afresh it costs a
    # rank of the whole prefix; here it is answered incrementally and exactly: the boundaries
    # of the k-simplices entered so far are kept reduced mod 2 (a chain is a Python int, bit
    # i for the i-th (k-1)-simplex to enter), so ∂σ is a boundary iff it reduces to zero.
    index: dict = {}  # simplex -> its bit among those of its dimension
    count: Counter = Counter()  # how many simplices of each dimension entered
    reduced: dict = {}  # k -> {highest bit: reduced boundary}
    out = []
    for s in order:
        k = len(s) - 1
        if k > 0:
            missing = [f for f in combinations(s, k) if f not in index]
            if missing:
                raise ValueError(f"order: {s} enters before its face {missing[0]}: a prefix is not a complex")
            v = 0
            for f in combinations(s, k):
                v ^= 1 << index[f]
            basis = reduced.setdefault(k, {})
            while v and v.bit_length() - 1 in basis:
                v ^= basis[v.bit_length() - 1]  # add an earlier boundary, mod 2
            if v:
                basis[v.bit_length() - 1] = v  # ∂σ did not bound: σ is negative
            out.append(not v)
        else:
            out.append(True)
        index[s] = count[k]
        count[k] += 1
    return out
