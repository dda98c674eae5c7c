"""Betti numbers and persistence of an α-filtration (Notes §23.1, "Voids and pockets").

The growth model of Notes §23.1 turns the balls into a filtration
:math:`\\emptyset = K^1 \\subset K^2 \\subset \\dots \\subset K^m = D` of the Delaunay
(regular) triangulation :math:`D`; the dual complex :math:`K_\\tau` has the homotopy type
of the union of the balls grown to :math:`\\sqrt{r_i^2 + \\tau}` (nerve theorem), so its
Betti numbers :math:`\\beta_k(\\tau)` count the components (:math:`k = 0`), tunnels and
holes (:math:`k = 1`) and voids (:math:`k = 2` in 3D) of that union.  Persistence pairs
each feature's birth with its death as :math:`\\tau` grows; this is the hierarchy "big
voids against small ones" that the notes describe at the end of §23.1.

Where the notes are imprecise: "the topology of :math:`K(\\mathbb{P})` is the same as
that of :math:`\\mathbb{P}`" -- :math:`K_\\tau` and the union are homotopy equivalent
(the union deformation-retracts onto :math:`|K_\\tau|`), not homeomorphic; homotopy
equivalence is exactly what makes their Betti numbers and persistence agree.

The algorithm (Edelsbrunner, Letscher & Zomorodian 2002; Edelsbrunner & Harer 2010,
§VII.1) is the standard column reduction of the boundary matrix, read top to bottom in
:func:`persistence` with ``method="reduction"``:

1. order the simplices by entry time, then dimension (a face before its cofaces), then
   row: the filtration order (:func:`filtration_order`);
2. write the boundary matrix :math:`D` in that order, column ``j`` the boundary of
   simplex ``j`` (:func:`boundary_columns`; over :math:`\\mathbb{Z}/p` with the signs
   of the oriented boundary);
3. for each column ``j`` from left to right, while its lowest non-zero row ``low(j)`` is
   the lowest row of an earlier column, add a multiple of that column to it
   (:func:`reduce_columns`);
4. read the pairs: ``low(j) = i`` means simplex ``i`` creates a class that simplex ``j``
   destroys, the pair (value of ``i``, value of ``j``) in dimension ``dim(i)``; a zero
   column that is nobody's ``low`` creates a class that never dies.

**The seam.**  ``method="fast"`` (the default) computes the same pairs without the
matrix (:mod:`shapelab._engine.persistence`: union-find for :math:`H_0`, Alexander
duality for the voids, clearing and compression for :math:`H_1` in 3D), in about linear
time instead of the reduction's cubic worst case; tests hold the two equal on random
α-filtrations.

Every result is computed once per filtration object and kept on it
(:meth:`~shapelab.filtration.Filtration.derived`), so repeated ``betti(tau)`` calls
cost a binary search.

The filtration order is (value, dimension, row): within a dimension the rows of a
:class:`~shapelab.filtration.Filtration` are already in filtration order.  Persistence
pairs (as values) do not depend on how ties are broken, so they equal GUDHI's, which
break ties differently; zero-length pairs, which do depend on it, are omitted as GUDHI
does by default.

**Coefficients.**  Homology and persistence are computed over the field
:math:`\\mathbb{Z}/2` unless ``persistence(F, field=p)`` names another prime.  Only the
:math:`H_1` pairs of a 3-dimensional filtration can depend on the field (where a
2-chain's boundary is a multiple of a cycle, as a Möbius band's is: :func:`persistence`,
Notes); Betti numbers, :math:`H_0` and the voids never do.  Compare with GUDHI in the same field
(``compute_persistence(homology_coeff_field=p)``; GUDHI's default is 11).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal

import numpy as np
import numpy.typing as npt

from ._engine import persistence as _impl
from ._toolkit.derived import derived
from .filtration import as_filtration

if TYPE_CHECKING:
    from scipy.sparse import csc_matrix, sparray, spmatrix

__all__ = [
    "betti",
    "betti_curve",
    "persistence",
    "euler_characteristic_curve",
    "is_roundoff",
    "reduce_boundary",
    "filtration_order",
    "boundary_columns",
    "reduce_columns",
]

#: Relative length below which a pair counts as round-off (see :func:`is_roundoff`).
ROUNDOFF = _impl.ROUNDOFF


def betti(F, tau: float) -> tuple[int, ...]:
    """Betti numbers :math:`(\\beta_0, \\dots, \\beta_d)` of the dual complex :math:`K_\\tau`.

    Notes §23.1: :math:`K_\\tau` has the topology of the union of the balls grown to
    radii :math:`\\sqrt{r_i^2 + \\tau}`, so :math:`\\beta_0` counts its components,
    :math:`\\beta_1` its tunnels (holes in 2D) and :math:`\\beta_2` its voids (3D).

    Parameters
    ----------
    F : Filtration or Balls
        From :func:`shapelab.alpha_filtration` (or any object with the same accessors);
        Balls are turned into their filtration once and it is kept with them
        (the one input rule of the library).
    tau : float
        Growth time (``inf`` gives the whole triangulation, ``-inf`` the empty complex).

    Returns
    -------
    tuple of int
        Length ``d + 1`` for balls in :math:`\\mathbb{R}^d` (zeros above the filtration's
        own dimension when the centres are degenerate, e.g. coplanar in 3D).

    See Also
    --------
    betti_curve
        At many growth times.
    persistence
        The pairs behind the numbers.

    References
    ----------
    .. [1] C. J. A. Delfinado and H. Edelsbrunner, "An incremental algorithm for Betti
           numbers of simplicial complexes on the 3-sphere", *Comput. Aided Geom. Design*
           12(7):771-784, 1995. doi:10.1016/0167-8396(95)00016-Y
    .. [2] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> import numpy as np, shapelab as sl
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> ring = sl.Balls(np.c_[np.cos(t), np.sin(t)] * 3, 0.9)
    >>> sl.alpha_filtration(ring).betti(0.0)
    (1, 1, 0)
    """
    return _impl.betti(as_filtration(F, "betti"), tau)


def betti_curve(F, taus) -> np.ndarray:
    """Betti numbers at many growth times: an int array of shape ``(len(taus), d + 1)``.

    Row ``i`` is :func:`betti` at ``taus[i]`` (Notes §23.1, the hierarchy of features
    as the balls grow).  Costs two spanning forests once per filtration plus a binary
    search per τ: Delfinado–Edelsbrunner with :math:`\\beta_1` from the Euler
    characteristic in 3D.

    See Also
    --------
    betti
        At one growth time.
    shapelab.plot.betti_curve
        Draws it.

    References
    ----------
    .. [1] C. J. A. Delfinado and H. Edelsbrunner, "An incremental algorithm for Betti
           numbers of simplicial complexes on the 3-sphere", *Comput. Aided Geom. Design*
           12(7):771-784, 1995. doi:10.1016/0167-8396(95)00016-Y
    """
    return _impl.betti_curve(as_filtration(F, "betti_curve"), taus)


def euler_characteristic_curve(F, taus) -> np.ndarray:
    """:math:`\\chi(K_\\tau) = \\sum_k (-1)^k \\#\\{k\\text{-simplices with value} \\le \\tau\\}`.

    See Also
    --------
    betti_curve
        The Betti numbers whose alternating sum it is.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069
    """
    return _impl.euler_characteristic_curve(as_filtration(F, "euler_characteristic_curve"), taus)


def is_roundoff(F, births, deaths) -> np.ndarray:
    """Which pairs are round-off of tied entry times rather than features.

    Tied entry times (co-circular or co-spherical balls: grids, symmetric cages) come
    out of floating-point arithmetic a few ulps apart, in GUDHI as here, and give
    pairs of length ~1e-15.  A pair counts as zero-length when
    ``death - birth <= ROUNDOFF * max(|birth|, |death|, scale)`` with
    ``ROUNDOFF = 2.5e-9``, at least twice the relative accuracy to which entry times
    are certified (:mod:`shapelab._toolkit.tolerances`): two tied entry times may come out
    that far apart.  ``scale`` is the size of the input in units of τ, the larger of
    the median :math:`r_i^2` and the median :math:`|z_i - z_j|^2 / 4` over the edges
    that join components (the :math:`H_0` forest), so that ties near τ = 0 (tangent
    balls of decimal input) count as round-off too.  It is geometric: a median of
    entry times would be dominated by the slivers of nearly flat centres (entry times
    up to ~1e30) and drop every finite pair.

    See Also
    --------
    persistence
        Drops these pairs.
    """
    return _impl.is_roundoff(as_filtration(F, "is_roundoff"), births, deaths)


def filtration_order(F) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every simplex of ``F`` in filtration order: by entry time, then dimension, then row.

    Step 1 of the standard algorithm (Notes §23.1): a face enters no later than its
    cofaces, and at a tie the lower dimension comes first, so every face comes before
    its cofaces and the boundary matrix in this order is strictly upper triangular.

    Parameters
    ----------
    F : Filtration or Balls

    Returns
    -------
    dims, rows, values : ndarray, shape (n,)
        Position ``j`` of the order is the simplex ``F.simplices(dims[j])[rows[j]]``,
        entering at ``values[j]``.

    See Also
    --------
    boundary_columns
        The boundary matrix in this order.

    References
    ----------
    .. [1] H. Edelsbrunner, J. Harer, *Computational Topology: An Introduction*, AMS
       (2010), §VII.1.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0, 0], [2, 0], [1, 1.5]], [0.5, 0.5, 0.5]))
    >>> dims, rows, values = filtration_order(F)
    >>> dims.tolist(), rows.tolist()
    ([0, 0, 0, 1, 1, 1, 2], [0, 1, 2, 0, 1, 2, 0])
    """
    F = as_filtration(F, "filtration_order")
    top = int(F.dimension)
    dims = np.concatenate([np.full(len(F.values(k)), k) for k in range(top + 1)] + [np.empty(0, int)])
    rows = np.concatenate([np.arange(len(F.values(k))) for k in range(top + 1)] + [np.empty(0, int)])
    values = np.concatenate([np.asarray(F.values(k), dtype=np.float64) for k in range(top + 1)] + [np.empty(0)])
    order = np.lexsort((rows, dims, values))  # the last key is the first: value, dimension, row
    return dims[order].astype(np.int64), rows[order].astype(np.int64), values[order]


def boundary_columns(F, field: int = 2) -> list[dict[int, int]]:
    """The boundary matrix of ``F`` over :math:`\\mathbb{Z}/p`, column by column, in
    filtration order (step 2 of the standard algorithm, Notes §23.1).

    Column ``j`` is the boundary of simplex ``j`` of :func:`filtration_order`: for a
    simplex with vertices :math:`v_0 < v_1 < \\dots < v_k`,
    :math:`\\partial [v_0, \\dots, v_k] = \\sum_i (-1)^i [v_0, \\dots, \\hat v_i, \\dots, v_k]`,
    each facet named by its position in the order and its coefficient taken mod ``p``
    (over :math:`\\mathbb{Z}/2` every coefficient is 1).

    Parameters
    ----------
    F : Filtration or Balls
    field : int, default 2
        The prime ``p``.

    Returns
    -------
    list of dict
        ``columns[j] = {i: coefficient}`` for the facets ``i`` of simplex ``j``.

    See Also
    --------
    filtration_order
        The order of the columns (and rows).
    reduce_columns
        Step 3.

    References
    ----------
    .. [1] H. Edelsbrunner, J. Harer, *Computational Topology: An Introduction*, AMS
       (2010), §IV.1 and §VII.1.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0, 0], [2, 0], [1, 1.5]], [0.5, 0.5, 0.5]))
    >>> [sorted(column) for column in boundary_columns(F)[3:]]  # the facets of the 3 edges, the triangle
    [[0, 2], [1, 2], [0, 1], [3, 4, 5]]
    >>> sorted(boundary_columns(F, field=3)[6].items())  # [0, 1, 2]: [1, 2] - [0, 2] + [0, 1]
    [(3, 2), (4, 1), (5, 1)]
    """
    p = _impl.as_field(field)
    F = as_filtration(F, "boundary_columns")
    dims, rows, _ = filtration_order(F)
    # where each simplex (its sorted vertices) stands in the order
    simplices = [
        np.sort(np.asarray(F.simplices(k)).reshape(len(F.values(k)), -1), axis=1) for k in range(int(F.dimension) + 1)
    ]
    position = {tuple(simplices[k][r].tolist()): j for j, (k, r) in enumerate(zip(dims.tolist(), rows.tolist()))}
    columns = []
    for k, r in zip(dims.tolist(), rows.tolist()):
        vertices = simplices[k][r].tolist()
        column = {}
        if k > 0:
            for i in range(k + 1):  # the facet without vertex i, with sign (-1)^i
                column[position[tuple(vertices[:i] + vertices[i + 1 :])]] = (-1) ** i % p
        columns.append(column)
    return columns


def reduce_columns(columns: list[dict[int, int]], field: int = 2) -> np.ndarray:
    """The standard column reduction over :math:`\\mathbb{Z}/p`, in place (step 3, Notes §23.1).

    For each column ``j`` from left to right: while it is non-zero and its lowest row
    ``i = low(j)`` (its largest row index) is the lowest row of an earlier column ``k``,
    subtract from it the multiple of column ``k`` that cancels row ``i``.  At the end
    the non-zero columns have distinct lowest rows.

    Parameters
    ----------
    columns : list of dict
        ``{row: coefficient}`` per column, as :func:`boundary_columns` gives; reduced in
        place (the reduced matrix :math:`R = D V`).
    field : int, default 2
        The prime ``p``.

    Returns
    -------
    low : ndarray of int64, shape (n,)
        ``low[j]``: the lowest row of the reduced column ``j``, -1 where it is zero.

    See Also
    --------
    reduce_boundary
        The same on a matrix.
    persistence
        Reads the pairs off ``low``.

    Notes
    -----
    Column additions from left to right do not change the rank of any lower-left
    submatrix of :math:`D`, and these ranks decide the pairs (the pairing lemma,
    Edelsbrunner and Harer 2010, §VII.1): ``low`` is the same for every reduced
    :math:`R = D V`, whatever the order of the additions.  Each of the ``n`` columns may
    be added to up to ``n`` times: :math:`O(n^3)` in the worst case.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher, A. Zomorodian, "Topological persistence and
       simplification", Discrete Comput. Geom. 28 (2002) 511-533.
    .. [2] A. Zomorodian, G. Carlsson, "Computing persistent homology", Discrete Comput.
       Geom. 33 (2005) 249-274 (any field).

    Examples
    --------
    The hollow triangle (vertices 0, 1, 2, then edges 01, 02, 12): the last edge
    closes a loop, its column reduces to zero.

    >>> columns = [{}, {}, {}, {0: 1, 1: 1}, {0: 1, 2: 1}, {1: 1, 2: 1}]
    >>> reduce_columns(columns).tolist()
    [-1, -1, -1, 1, 2, -1]
    >>> columns[5]
    {}
    """
    p = _impl.as_field(field)
    low = np.full(len(columns), -1, dtype=np.int64)
    owner: dict[int, int] = {}  # lowest row -> the column that has it
    for j, column in enumerate(columns):
        while column:
            i = max(column)
            k = owner.get(i)
            if k is None:  # nobody before has this lowest row: column j is reduced
                owner[i] = j
                low[j] = i
                break
            # column j -= f * column k, with f chosen to cancel row i (f = c_j / c_k mod p)
            f = column[i] * pow(columns[k][i], p - 2, p) % p
            for row, c in columns[k].items():
                c = (column.get(row, 0) - f * c) % p
                if c:
                    column[row] = c
                else:
                    column.pop(row, None)
    return low


def reduce_boundary(D: npt.ArrayLike | spmatrix | sparray) -> tuple[csc_matrix, np.ndarray]:
    """The standard persistence algorithm on a boundary matrix over :math:`\\mathbb{Z}/2`
    (Notes §23.1, "Voids and pockets"): :func:`reduce_columns` on the columns of ``D``.

    Parameters
    ----------
    D : (n, n) scipy.sparse matrix or array_like of integers
        A boundary matrix with columns and rows in filtration order
        (:meth:`shapelab.filtration.Filtration.boundary_matrix`); entries are taken
        mod 2.

    Returns
    -------
    R : (n, n) scipy.sparse.csc_matrix of uint8
        The reduced matrix, :math:`R = D V` with :math:`V` upper triangular with ones
        on its diagonal.
    low : (n,) ndarray of int64
        ``low[j]``: the row of the lowest 1 of column ``j`` of ``R``, -1 where the
        column is zero.

    See Also
    --------
    shapelab.filtration.Filtration.boundary_matrix : ``D`` of an α-filtration.
    reduce_columns : the reduction itself.
    persistence : the pairs, as values.

    Notes
    -----
    **Reading the pairs.**  Where ``low[j] = i >= 0``, simplex ``i`` creates a class
    and simplex ``j`` destroys it: the pair (value of ``i``, value of ``j``) in
    dimension ``dim(i)``.  A zero column ``j`` that is nobody's lowest one creates a
    class that never dies (an essential class, death ``inf``).

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher, A. Zomorodian, "Topological persistence and
       simplification", Discrete Comput. Geom. 28 (2002) 511-533.
    .. [2] H. Edelsbrunner, J. Harer, *Computational Topology: An Introduction*, AMS
       (2010), §VII.1.

    Examples
    --------
    >>> from shapelab.persistence import reduce_boundary
    >>> D = [[0, 0, 0, 1, 1, 0],
    ...      [0, 0, 0, 1, 0, 1],
    ...      [0, 0, 0, 0, 1, 1],
    ...      [0, 0, 0, 0, 0, 0],
    ...      [0, 0, 0, 0, 0, 0],
    ...      [0, 0, 0, 0, 0, 0]]
    >>> R, low = reduce_boundary(D)
    >>> low.tolist()
    [-1, -1, -1, 1, 2, -1]
    >>> R.toarray()[:, 5].tolist()
    [0, 0, 0, 0, 0, 0]
    """
    from scipy.sparse import csc_matrix

    sets, n = _impl.as_z2_matrix(D)
    columns = [dict.fromkeys(s, 1) for s in sets]
    low = reduce_columns(columns, 2)
    lengths = np.fromiter((len(c) for c in columns), dtype=np.int64, count=n)
    r = np.fromiter((i for c in columns for i in sorted(c)), dtype=np.int64, count=int(lengths.sum()))
    indptr = np.concatenate(([0], np.cumsum(lengths)))
    return csc_matrix((np.ones(r.size, dtype=np.uint8), r, indptr), shape=(n, n)), low


def _pairs_by_reduction(F, p: int) -> dict[int, np.ndarray]:
    """Steps 1-4 of the module docstring: the pairs of ``F`` by the standard reduction."""
    dims, _, values = filtration_order(F)
    columns = boundary_columns(F, p)
    low = reduce_columns(columns, p)
    ambient = int(getattr(getattr(F, "balls", None), "dim", max(int(F.dimension), 0)))
    pairs: dict[int, list] = {k: [] for k in range(ambient + 1)}
    killed = set(low[low >= 0].tolist())
    for j, i in enumerate(low.tolist()):
        if i >= 0:  # simplex i creates a class, simplex j destroys it
            pairs[int(dims[i])].append((values[i], values[j]))
        elif j not in killed:  # a zero column nobody kills: a class that never dies
            pairs[int(dims[j])].append((values[j], np.inf))
    out = {}
    for k, rows in pairs.items():
        a = np.array(rows, dtype=np.float64).reshape(-1, 2)
        a = a[a[:, 1] > a[:, 0]]  # zero-length pairs are omitted
        a = a[~is_roundoff(F, a[:, 0], a[:, 1])]
        a = a[np.lexsort((a[:, 1], a[:, 0]))]
        a.flags.writeable = False
        out[k] = a
    return out


def persistence(F, *, field: int = 2, method: Literal["fast", "reduction"] = "fast") -> dict[int, np.ndarray]:
    """Persistence pairs of the α-filtration, per homology dimension, over the field
    :math:`\\mathbb{Z}/p` (``field=p``; :math:`\\mathbb{Z}/2` by default).

    Notes §23.1: growing the balls "distinguishes big voids or tunnels from smaller
    ones"; a feature's persistence is its death minus its birth, in units of τ.

    Parameters
    ----------
    F : Filtration or Balls
    field : int, default 2
        The prime ``p`` of the coefficient field :math:`\\mathbb{Z}/p` (GUDHI's
        ``homology_coeff_field``).  The default, :math:`\\mathbb{Z}/2`, is the field of
        the α-shape and persistence literature (Edelsbrunner, Letscher and Zomorodian
        2002; Edelsbrunner and Harer 2010); GUDHI's own default is :math:`\\mathbb{Z}/11`.
    method : {"fast", "reduction"}, default "fast"
        The seam.  ``"reduction"`` runs the standard algorithm of the module docstring
        in this module (:func:`filtration_order`, :func:`boundary_columns`,
        :func:`reduce_columns`, then the pairs are read off ``low``): the code to read,
        :math:`O(n^3)` in the worst case, for small filtrations.  ``"fast"`` computes
        the same pairs in about linear time in the engine
        (:mod:`shapelab._engine.persistence`: union-find, Alexander duality, clearing and
        compression).  Both return the same arrays (tested on random α-filtrations).

    Returns
    -------
    dict
        ``{k: (p, 2) float array}`` for ``k = 0..d``, rows ``(birth, death)`` in τ.
        Essential classes (only the components of the whole triangulation) have death
        ``inf``; zero-length pairs are omitted, and so are pairs shorter than the
        round-off of tied entry times (:func:`is_roundoff`: relative length below
        2.5e-9, twice the accuracy to which entry times are certified).  As multisets the pairs equal GUDHI's
        ``persistence_intervals_in_dimension(k)`` on the weighted alpha complex of the
        same balls computed *in the same field*
        (``compute_persistence(homology_coeff_field=p)``), up to those round-off pairs,
        which GUDHI reports too.  Rows are sorted by birth, then death; arrays are
        read-only.

    See Also
    --------
    betti, betti_curve : Betti numbers (field-independent).
    shapelab.diagrams.bottleneck_distance : compare two diagrams.

    Notes
    -----
    **Which diagrams depend on the field.**  Only :math:`H_1` of a 3-dimensional
    filtration.  :math:`H_0` (components) and :math:`H_{d-1}` (voids in 3D, holes in
    2D, read off the complement by Alexander duality) are the same over every field,
    and so are all Betti numbers of a complex in :math:`\\mathbb{R}^3` (its homology has
    no torsion).  But the *pairing* of :math:`H_1` classes can change: a 2-chain whose
    boundary is twice a cycle -- a Möbius band, whose rim runs twice around its core
    circle -- kills the rim in :math:`\\mathbb{Z}/2` (where :math:`2 = 0`) and only
    ties the rim to twice the core otherwise, so two loops may exchange their deaths.
    The pairs of two fields differ only where some 2-chain's boundary is a multiple of a
    cycle (relative to an earlier complex), as the band's is; real structures have such
    chains (lesson 11: 3MHT).

    Tunnels and their representative cycles (:func:`shapelab.tunnels`) are computed in
    :math:`\\mathbb{Z}/2`.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher, A. Zomorodian, "Topological persistence and
       simplification", Discrete Comput. Geom. 28 (2002) 511-533.
    .. [2] A. Zomorodian, G. Carlsson, "Computing persistent homology", Discrete Comput.
       Geom. 33 (2005) 249-274 (persistence over any field).
    .. [3] U. Bauer, M. Kerber, J. Reininghaus, "Clear and compress: computing persistent
       homology in chunks", Topological Methods in Data Analysis and Visualization III
       (2014) 103-117.

    Examples
    --------
    >>> import shapelab as sl
    >>> from shapelab.persistence import persistence
    >>> F = sl.alpha_filtration(sl.Balls([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0.4, 0.4, 0.4]))
    >>> {k: len(v) for k, v in persistence(F).items()}
    {0: 3, 1: 0, 2: 0, 3: 0}
    >>> F.persistence(field=3)[0].shape  # H0: the same in every field
    (3, 2)
    >>> persistence(F, method="reduction")[0].tolist() == persistence(F)[0].tolist()
    True
    """
    p = _impl.as_field(field)
    if method == "fast":  # the seam: the same pairs without the matrix (the engine)
        return _impl.persistence(as_filtration(F, "persistence"), field=p)
    if method != "reduction":
        raise ValueError(f"method must be 'fast' or 'reduction', got {method!r}")
    F = as_filtration(F, "persistence")
    return dict(derived(F, f"persistence.reduction.Z{p}", lambda G: _pairs_by_reduction(G, p)))
